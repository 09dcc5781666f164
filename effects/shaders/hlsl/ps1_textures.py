"""ps_1_x texture reads for codegen_ps1: `tex t#` / `texcoord t#` (ps_1_1-1_3), `texld r#` /
`texcrd r#` (ps_1_4), the stage each sampler takes, and a sampler read in both ps_1_4 phases
carried across `phase` (docs/reference/semantics.md 2.5-2.6).

A mixin of Ps1CodeGen, like ps1_analysis: it reads the code generator's state (homes, phase,
the instructions emitted so far).
"""
from __future__ import annotations

from typing import Any

from effects.base.errors import EffectWarning, Location, UNKNOWN_LOCATION
from effects.shaders.asm.program import Instruction, Operand as Register
from effects.shaders.hlsl.dag import Node
from effects.shaders.hlsl.parse import HlslError
from effects.shaders.hlsl.ps1_asm import Home
from effects.shaders.hlsl.records import FULL, reg as register, replicated, temp


class Ps1Textures:
    """Mixin of Ps1CodeGen, which holds these."""

    ctx: Any
    v: str
    ps14: bool
    phase: int
    home: dict[int, Home]
    instrs: list[Instruction]
    optional: set[int]
    samplers: dict[str, int]
    sampled: set[tuple[str, int]]
    explicit_samplers: dict[str, int]
    carried_alpha: dict[int, Register]
    readers: dict[int, list[tuple[Node | None, Any]]]
    _input_homes: dict[str, Home]

    def _textures(self, tex: list[Node], values: dict[str, int]) -> None:
        for n in tex:
            self._sample(n)
        for reg in sorted(values):
            m = int(reg[1:])
            if self.ps14:
                vr = self.temp(UNKNOWN_LOCATION)
                self.instrs.append(self.record("texcrd", temp(vr), (0, 1, 2), [replicated(register("t", m))],
                                           UNKNOWN_LOCATION))
                self._input_homes[reg] = Home(temp(vr), phase=self.phase, lanes=3)
                continue
            if any(self.home.get(t.id) and self.home[t.id].reg.kind == "t" and self.home[t.id].reg.index == m
                   for t in tex):
                self.refuse(f"TEXCOORD{m} is both sampled and read as a value; {self.v} loads each "
                            f"t register once (tex or texcoord)", self._input_loc(reg, reader=True))
            self.instrs.append(self.record("texcoord", register("t", m), FULL, [], UNKNOWN_LOCATION))
            self._input_homes[reg] = Home(register("t", m))
            # a located warning: the value read is clamped, unlike in HLSL
            warning = EffectWarning(f"{self.v} reads TEXCOORD{m} as a value through texcoord, which "
                                    "clamps it to [0, 1]", self._input_loc(reg))
            if warning not in self.ctx.warnings:
                self.ctx.warnings.append(warning)

    def _input_loc(self, reg: str, reader: bool = False) -> Location:
        """Where the input is declared, or (reader) the first expression reading it as a value."""
        for n in self.ctx.graph.nodes:
            if n.op == "input" and n.key[1] == reg:
                users = [r for r, _ in self.readers.get(n.id, []) if r is not None and r.op != "tex"]
                return users[0].location if reader and users else n.location
        return UNKNOWN_LOCATION

    def _sample(self, n: Node) -> None:
        name = n.key[0]
        coord, mod = self.resolve(n.args[0])
        explicit = self.explicit_samplers.get(name)
        if not self.ps14:
            m = int(coord.node.key[1][1:]) if coord.node.op == "input" and \
                coord.node.key[1].startswith("t") else -1
            if m < 0 or mod or coord.negate or coord.swizzle != tuple(range(coord.width)):
                self.fail("texture read at this coordinate: ps_1_1-1_3 sample stage # at TEXCOORD# "
                          "as interpolated (no swizzle, modifier or colour input)", n.location)
            stage, dst = m, register("t", m)
            ins = self.record("tex", dst, FULL, [], n.location)
        else:
            taken = set(self.samplers.values()) | {s for s in self.explicit_samplers.values()}
            stage = self.samplers.get(name, explicit if explicit is not None else next(
                (k for k in range(6) if k not in taken), 6))
            if stage > 5:
                self.refuse(f"{self.v} has 6 texture stages; this is the 7th texture read", n.location)
            dst = temp(self.temp(n.location, pin=stage))
            if coord.node.op == "input":
                if not coord.node.key[1].startswith("t"):
                    self.fail("texture read at colour-input coordinates", n.location)
                src = replicated(register("t", int(coord.node.key[1][1:])))
            else:
                home = self.home.get(coord.node.id)
                if home is None or mod or coord.negate or coord.swizzle != tuple(range(coord.width)):
                    self.fail("dependent read at coordinates with a swizzle or modifier", n.location)
                src = replicated(home.reg)
            ins = self.record("texld", dst, FULL, [src], n.location)
        if explicit is not None and explicit != stage:
            self.refuse(f"sampler '{name}' is bound to s{explicit}, but {self.v} samples it at "
                        f"stage {stage}", n.location)
        other = next((k for k, s in self.samplers.items() if s == stage and k != name), None)
        if other is not None:
            self.refuse(f"samplers '{other}' and '{name}' are both read at TEXCOORD{stage}; "
                        f"{self.v} samples stage {stage}, one sampler, at TEXCOORD{stage}",
                        n.location)
        if (name, self.phase) in self.sampled:     # planned out by _reads_of_one_sampler
            raise HlslError(f"internal: '{name}' sampled twice in phase {self.phase}", n.location)
        self.sampled.add((name, self.phase))
        self.samplers[name] = stage
        self.instrs.append(ins)
        self.home[n.id] = Home(dst, phase=self.phase)

    def _carry_out_of_stage(self, n: Node) -> None:
        """ps_1_4: a phase-1 read of a sampler read again in phase 2 leaves r<stage> (which the
        second texld writes) for other registers: its .rgb in one, its .a replicated in the .rgb
        of another (only .rgb crosses the phase, docs/reference/semantics.md 2.6); each move is
        left out if phase 2 does not read it."""
        stage = self.home[n.id].reg
        rgb, alpha = self.temp(n.location), self.temp(n.location)
        for vr, lane in ((rgb, None), (alpha, 3)):
            ins = self.record("mov", temp(vr), (0, 1, 2), [replicated(stage, lane)], n.location)
            self.optional.add(id(ins))
            self.emit(ins)
        self.home[n.id] = Home(temp(rgb), phase=1)
        self.carried_alpha[n.id] = temp(alpha)

    def _rejoin(self, node: Node, loc: Location) -> Home:
        """Phase 2: a carried read whole again (.rgb and its .a from where they crossed)."""
        whole = temp(self.temp(loc))
        self.emit(self.record("mov", whole, (0, 1, 2), [replicated(self.home[node.id].reg)], loc))
        self.emit(self.record("mov", whole, (3,), [replicated(self.carried_alpha.pop(node.id), 2)], loc))
        self.home[node.id] = Home(whole, phase=2)
        return self.home[node.id]
