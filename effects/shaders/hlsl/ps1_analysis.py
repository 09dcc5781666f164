"""What codegen_ps1 decides before it emits: folded idioms, absorbed shifts and saturates,
the live nodes, ps_1_4's phase-1 nodes, which values go straight into r0.

A mixin of Ps1CodeGen (like the assembler's PS1Rules): it reads `self.readers` (node -> who
reads it), `self.s` (the decisions) and the version rules.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from effects.base.errors import Location
from effects.shaders.hlsl.dag import Node, Operand
from effects.shaders.hlsl.parse import HlslError
from effects.shaders.hlsl.ops import PS1_LACKS
from effects.shaders.hlsl.ps1_asm import Home
from effects.shaders.hlsl.records import FULL
from effects.shaders.hlsl.ps1_idioms import power_of_two, source_idiom

@dataclass
class State:
    alias: dict[int, Operand] = field(default_factory=dict)    # shift/sat absorbed: the producer
    folded: dict[int, tuple[Operand, str]] = field(default_factory=dict)   # source modifiers
    shift: dict[int, int] = field(default_factory=dict)
    sat: set[int] = field(default_factory=set)


class Ps1Analysis:
    """Mixin of Ps1CodeGen, which holds these."""

    v: str
    rules: Any
    ps14: bool
    s: State
    readers: dict[int, list[tuple[Node | None, Operand]]]
    home: dict[int, Home]

    def fail(self, what: str, loc: Location) -> HlslError:
        raise HlslError(f"X4532: cannot map expression to pixel shader instruction set: {self.v} "
                        f"has no {what}", loc)

    def refuse(self, message: str, loc: Location) -> HlslError:
        raise HlslError(f"X4532: cannot map expression to pixel shader instruction set: "
                        f"{message}", loc)

    # -- analysis -------------------------------------------------------------------------------
    def _analyse(self, nodes: list[Node]) -> None:
        """Which nodes fold into their readers' source modifiers and which into their
        producer's shift or _sat (fxc's modifier idioms)."""
        for n in nodes:
            if n.op in ("const", "input", "uniform", "tex", "pack"):
                continue
            if n.op == "mul" and self._shift_absorbed(n):
                continue             # a shift of its producer before an x2 source modifier
            idiom = source_idiom(n, self.v)
            if idiom is not None and self._can_fold(n, *idiom):
                self.s.folded[n.id] = idiom
            elif n.op == "sat" and self._absorbs(n.args[0], n, lambda p: p.id not in self.s.sat):
                self.s.alias[n.id] = n.args[0]
                self.s.sat.add(self.resolve(n.args[0])[0].node.id)

    def _shift_absorbed(self, n: Node) -> bool:
        """y * 2^k as y's own instruction shift (mul_x2, add_d2 ...) where nothing else reads y."""
        for y, k in ((n.args[0], n.args[1]), (n.args[1], n.args[0])):
            shift = power_of_two(k.const_values(), self.rules.shifts)
            if shift is not None and self._absorbs(y, n, lambda p: p.id not in self.s.shift
                                                   and p.id not in self.s.sat):
                self.s.alias[n.id] = y
                self.s.shift[self.resolve(y)[0].node.id] = shift
                return True
        return False

    def _conditions_into_r0(self, nodes: list[Node]) -> set[int]:
        """ps_1_1-1_3: the cnd conditions computed straight into r0 (read there as r0.a): an
        arithmetic value only that cnd reads, whose alpha lane holds it (a scalar, replicated,
        or the .a of a 4-vector)."""
        pins: set[int] = set()
        if not self.rules.is_ps11_13:
            return pins
        for n in nodes:
            if n.op != "cnd":
                continue
            cond, mod = self.resolve(n.args[0])
            c = cond.node
            if mod or cond.negate or not self._emitted(c) or c.op == "pack" or c.id in pins:
                continue
            if not (c.width == 1 or (c.width == 4 and set(cond.swizzle) == {3})):
                continue
            if c.op in ("dp3", "dp4") or self._readers_through_aliases(c) != [n]:
                continue
            pins.add(c.id)
        return pins

    def _live(self, comps: list[Operand]) -> set[int]:
        """The nodes the result reads once modifiers are folded (an idiom's own mul or add
        is not computed)."""
        live: set[int] = set()
        stack = [self.resolve(c)[0].node for c in comps]
        while stack:
            n = stack.pop()
            if n.id not in live:
                live.add(n.id)
                stack.extend(self.resolve(a)[0].node for a in n.args)
        return live

    def _can_fold(self, n: Node, x: Operand, mod: str) -> bool:
        base, inner_mod = self.resolve(x)
        if inner_mod or base.node.op == "const":
            return False
        if self.ps14 and base.node.op == "uniform":
            return False             # ps_1_4 takes no source modifier on a constant
        for reader, op in self.readers.get(n.id, []):
            if reader is not None and reader.op in ("tex",) + tuple(PS1_LACKS):
                return False
            if mod == "invert" and op.negate:
                return False
        return True

    def _absorbs(self, y: Operand, n: Node, free) -> bool:
        """Whether `n` (a shift or saturate of y) can be y's own instruction modifier."""
        base, mod = self.resolve(y)
        p = base.node
        if mod or base.negate or p.op in ("const", "input", "uniform", "tex", "pack") \
                or p.op in PS1_LACKS or base.swizzle != tuple(range(p.width)) or y.width != p.width:
            return False
        users = self._readers_through_aliases(p)
        return len(users) == 1 and users[0] is n and free(p)

    def _readers_through_aliases(self, node: Node) -> list[Node | None]:
        out: list[Node | None] = []
        for reader, _ in self.readers.get(node.id, []):
            if reader is not None and reader.id in self.s.alias:
                out.extend(self._readers_through_aliases(reader))
            else:
                out.append(reader)
        return out

    def resolve(self, op: Operand) -> tuple[Operand, str]:
        """The operand a reader really reads (through absorbed shifts/saturates) and the
        source modifier it reads it with."""
        op = self._unalias(op)
        hit = self.s.folded.get(op.node.id)
        if hit is None:
            return op, ""
        inner, mod = hit
        picked = inner.pick(op.swizzle)
        return self._unalias(Operand(picked.node, picked.swizzle, op.negate)), mod

    def _unalias(self, op: Operand) -> Operand:
        while op.node.id in self.s.alias:
            target = self.s.alias[op.node.id].pick(op.swizzle)
            op = Operand(target.node, target.swizzle, op.negate != target.negate)
        return op

    def _emitted(self, n: Node) -> bool:
        return n.op not in ("const", "input", "uniform", "tex") and n.id not in self.s.folded \
            and n.id not in self.s.alias and not (n.op in PS1_LACKS and n.op.startswith("tex"))

    def _phase_one(self, nodes: list[Node]) -> set[int]:
        """ps_1_4: the nodes a dependent read's coordinates need (phase 1)."""
        p1: set[int] = set()
        for n in nodes:
            if n.op in PS1_LACKS and n.op.startswith("tex"):
                self.fail(PS1_LACKS[n.op], n.location)
            if n.op != "tex":
                continue
            coord, _ = self.resolve(n.args[0])
            if coord.node.op == "input":
                continue
            if not self.ps14:
                self.fail("texture read at computed coordinates (a dependent read needs ps_1_4, "
                          "or the texbem/texm3x* instructions fxc did not generate)", n.location)
            stack = [coord.node]
            while stack:
                m = stack.pop()
                if m.id in p1:
                    continue
                if m.op == "tex" and self.resolve(m.args[0])[0].node.op != "input":
                    self.refuse(f"{self.v} allows one level of dependent texture read; this read's "
                                "coordinates come from another dependent read", n.location)
                if m.op == "input" and m.key[1].startswith("v"):
                    self.refuse(f"{self.v} reads colour inputs (v#) only in phase 2, after the "
                                "dependent reads", m.location)
                p1.add(m.id)
                if m.op != "tex":
                    stack.extend(a.node for a in m.args)
        return p1

    def _reads_of_one_sampler(self, nodes: list[Node], p1: set[int]) -> set[int]:
        """A sampler read at two coordinates. ps_1_1-1_3 cannot: `tex t#` samples stage # at
        TEXCOORD#, and a sampler is one stage. ps_1_4 can, once per phase: `texld r#` samples
        stage # whatever its coordinates, so one read (at a TEXCOORD) goes to phase 1 -- added
        to p1 -- and the other to phase 2. Returns the phase-1 reads to carry out of r<stage>."""
        by: dict[str, list[Node]] = {}
        for n in nodes:
            if n.op == "tex":
                by.setdefault(n.key[0], []).append(n)
        carried: set[int] = set()
        for name, reads in by.items():
            if len(reads) < 2:
                continue
            first, second = reads[0], reads[1]
            where = (f"sampler '{name}' is read at {self._coord_text(first)} (line "
                     f"{first.location.line}) and at {self._coord_text(second)} (line "
                     f"{second.location.line})")
            if not self.ps14:
                self.refuse(f"{where}; {self.v} samples stage # at TEXCOORD# (tex t#), and a "
                            "sampler is one stage", second.location)
            if len(reads) > 2:
                self.refuse(f"sampler '{name}' is read at {len(reads)} coordinates; {self.v} "
                            "samples a stage once in each of its two phases", reads[2].location)
            plain = [r for r in reads if self.resolve(r.args[0])[0].node.op == "input"]
            early = [r for r in reads if r.id in p1]
            if len(early) == 2 or not plain:
                self.refuse(f"{where}; {self.v} samples a stage once per phase, and "
                            + ("both reads are needed before the dependent read" if early else
                               "both are dependent reads (phase 2)"), second.location)
            one = early[0] if early else plain[0]
            p1.add(one.id)
            carried.add(one.id)
        return carried

    def _coord_text(self, n: Node) -> str:
        coord = self.resolve(n.args[0])[0].node
        if coord.op == "input" and coord.key[1].startswith("t"):
            return f"TEXCOORD{coord.key[1][1:]}"
        return "computed coordinates"

    def _inputs_read_as_values(self, arith: list[Node], comps: list[Operand]) -> dict[str, int]:
        """t# inputs read by arithmetic: register -> first phase that reads them."""
        found: dict[str, int] = {}
        p1 = self._p1

        def visit(op: Operand, phase: int) -> None:
            base, _ = self.resolve(op)
            if base.node.op == "input" and base.node.key[1].startswith("t"):
                found[base.node.key[1]] = min(found.get(base.node.key[1], 2), phase)
        for n in arith:
            for a in n.args:
                visit(a, 1 if n.id in p1 else 2)
        for c in comps:
            visit(c, 2)
        return found

    def _coalesce_output(self, comps: list[Operand], loc: Location) -> list[tuple[int, Operand]]:
        """Compute a value straight into r0 where it fills whole .rgb/.a/.rgba of the result."""
        by: dict[int, list[int]] = {}
        for lane, c in enumerate(comps):
            base, mod = self.resolve(c)
            if not mod and not base.negate and (base.swizzle[0] == lane or base.node.width == 1):
                by.setdefault(base.node.id, []).append(lane)
        done: set[int] = set()
        for lanes_of in by.values():
            lanes = tuple(lanes_of)
            base = self.resolve(comps[lanes[0]])[0].node
            if not self._emitted(base) or base.op == "pack" or base.id in self.home:
                continue
            mask = self._mask_for_lanes(lanes)
            if mask is None or not self._only_output_reads(base):
                continue
            if base.op in ("dp3", "dp4") and mask == (3,) and not self.ps14:
                continue
            self.home[base.id] = Home(self.out_home.reg, base.width == 1, mask=mask)
            done.update(lanes)
        return [(lane, c) for lane, c in enumerate(comps) if lane not in done]

    def _only_output_reads(self, node: Node) -> bool:
        return all(r is None for r in self._readers_through_aliases(node))

    def _mask_for_lanes(self, lanes: tuple[int, ...]) -> tuple[int, ...] | None:
        if self.ps14:
            return tuple(sorted(lanes))
        s = set(lanes)
        return (0, 1, 2) if s == {0, 1, 2} else (3,) if s == {3} else FULL if s == set(FULL) else None

    def mask_for(self, width: int) -> tuple[int, ...]:
        if width in (1, 4):
            return FULL
        return tuple(range(width)) if self.ps14 else (0, 1, 2)


def combine(nodes: list[Node], readers: dict[int, list[tuple[Node | None, Operand]]]) -> bool:
    """add(mul(a, b), c) -> mad(a, b, c) where the mul has no other reader and no literal out
    of the constant range (a mul by 2 or 4 is a result shift, kept for _analyse)."""
    changed = False
    for n in nodes:
        if n.op != "add":
            continue
        for k in (0, 1):
            m = n.args[k]
            users = readers.get(m.node.id, [])
            if m.node.op != "mul" or len(users) != 1 or m.node.width < m.width or any(
                    v is not None and any(abs(x) > 1 for x in v)
                    for v in (a.const_values() for a in m.node.args)):
                continue
            a, b = (x.pick(m.swizzle) for x in m.node.args)
            n.op, n.args = "mad", (a.neg() if m.negate else a, b, n.args[1 - k])
            changed = True
            break
    return changed


def readers_of(nodes: list[Node], comps: list[Operand]) -> dict[int, list[tuple[Node | None, Operand]]]:
    out: dict[int, list[tuple[Node | None, Operand]]] = {}
    for n in nodes:
        for a in n.args:
            out.setdefault(a.node.id, []).append((n, a))
    for c in comps:
        out.setdefault(c.node.id, []).append((None, c))
    return out
