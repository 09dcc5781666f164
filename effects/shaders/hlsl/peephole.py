"""Rewrites of the emitted instructions (virtual registers, before legalize.finish): what fxc
made of the same code. Each pass takes the code generator (its `instrs`, `rules`, `defs`) and
returns how many instructions it removed, so a test can show the count drop pass by pass.

- `propagate_copies`: `mov vrX, src` whose every reader can read `src` in its place (the
  version's read ports and swizzles allow it, nothing rewrites `src` or a0 in between) is
  left out: `mov r0, c0; mov oC0, r0` is `mov oC0, c0`, a bone row is read as `c[a0.x + n]`
  where it is used (issue 31, from fxc's listings);
- `abs_into_sources`: `abs vrX, src` read as `src_abs` where the version has the `_abs`
  source modifier (vs_3_0, ps_3_0), by the same rule (fxc's `cmp r1, -r0_abs.w, ...`);
- `clamp_to_saturate`: `max x, 0` then `min 1` (clamp(x, 0, 1) where `saturate` was not
  written) is `mov_sat`, where the version has the modifier;
- `fold_into_producer`: `op vrA ...; mov[_sat] D, vrA`, vrA read nowhere else, is `op[_sat] D`
  (the `_sat` on the producing instruction; a result written straight to its destination,
  where the version lets `op` write it: ps_2_x writes oC#/oDepth with mov only). The mov may
  spread or reorder the lanes: `dp3 r0.x ...; mov oD0, r0.x` is `dp3 oD0 ...` (a replicated
  result fills every lane of the mask, fxc's code for `o.diffuse = dot(...)`), `add r0.xy ...;
  mov oT0.yx, r0.xy` is the add writing oT0.yx with its sources' lanes swapped;
- `build_in_place`: a register built from another's own lanes and new ones, then copied back
  over it (a loop's carried vector with one lane updated), is that register updated in place;
- `drop_dead_writes`: what writes a temporary no kept instruction reads is left out (a loop
  counter nothing reads after the loop).

Straight-line code only: a flow instruction (rep, loop, if, else, break ...) ends what a pass
looks at, so a value carried round a loop or chosen by an if is never moved across one
(`drop_dead_writes` marks registers over the whole program: a value read anywhere is kept).
"""
from __future__ import annotations

from typing import Any

from effects.shaders.asm.program import Instruction, Operand
from effects.shaders.hlsl.allocate import ALIASES as _ALIASES
from effects.shaders.hlsl.legalize import COMPONENTWISE as _COMPONENTWISE, \
    REPLICATED as _REPLICATED, _choose
from effects.shaders.hlsl.records import fixed, is_flow, needed, read, row, same as _same, written

_TEXLD = frozenset({"texld", "texldp", "texldb", "texldl", "texldd"})
# instructions whose sources a copy may be folded into: one slot, ordinary sources (texld's
# coordinate register, texkill's operand, sincos's constants have rules of their own)
_READERS = frozenset({"mov", "add", "mul", "mad", "min", "max", "slt", "sge", "cmp", "lrp",
                      "dp3", "dp4", "dp2add", "rcp", "rsq", "exp", "log", "pow", "frc", "abs",
                      "mova", "nrm", "crs", "dsx", "dsy"})
# instructions that may take `_sat` and write another destination than the temporary their
# result went to (every arithmetic instruction the code generator emits but sincos, whose
# destination rules differ)
_PRODUCERS = _READERS - {"mova"} | _TEXLD
# registers read in place of a copy (ps_3_0's vPos and vFace are left where they are: vFace
# is read by comparisons only); c also as c[a0.x + n] and c[aL + n]
_SOURCES = frozenset({"vr", "c", "v", "t"})


def _read_regs(ins: Instruction) -> list[Operand]:
    return ins.srcs


def _writes(ins: Instruction) -> Operand | None:
    return ins.dst


def _census(instrs: list[Instruction]) -> tuple[dict[int, list[int]], dict[int, int]]:
    """Each temporary's writing instructions (by position) and how many sources read it, in
    one pass over the code (asked once per pass: it is most of what the passes cost)."""
    defs: dict[int, list[int]] = {}
    uses: dict[int, int] = {}
    for i, ins in enumerate(instrs):
        for r in ins.srcs:
            if r.kind == "vr":
                uses[r.index] = uses.get(r.index, 0) + 1  # type: ignore[index]
        d = ins.dst
        if d is not None and d.kind == "vr":
            defs.setdefault(d.index, []).append(i)        # type: ignore[arg-type]
    return defs, uses


def _ports_ok(srcs: list[Operand], rules: Any) -> bool:
    # c[a0.x + n] and c[aL + n] read the constant file through its port, as registers of
    # their own
    seen: dict[str, set[tuple]] = {}
    for s in srcs:
        kind = s.kind
        if kind in rules.read_ports:
            seen.setdefault(kind, set()).add((s.index, s.relative and s.relative.kind))
    return all(len(v) <= rules.read_ports[k] for k, v in seen.items())


def _rule(rules: Any) -> str:
    return "ps20" if rules.swizzles == "ps20" else "any"


def _compose(use: Operand, mov: Instruction) -> Operand | None:
    """`use` (reading mov's destination) as a read of mov's source, or None where it reads a
    lane the mov did not write."""
    src = mov.srcs[0]
    through = needed(src)                        # mov lane -> source lane
    mask = written(mov)
    if use.lanes is None:
        if any(l not in mask for l in use.swizzle):
            return None
        return _absolute(fixed(src, tuple(through[l] for l in use.swizzle),
                               use.negate != src.negate), use, mov)
    if any(l not in mask for l in use.lanes.values()):
        return None
    out = read(src, {i: through[l] for i, l in use.lanes.items()}, use.negate != src.negate)
    return _absolute(out, use, mov)


def _absolute(out: Operand, use: Operand, mov: Instruction) -> Operand:
    """`out` (reading mov's source, its sign the two signs combined) with the `_abs` of the
    read, of the source or of an `abs` in the mov's place: |-x| is |x|, so under an abs only
    the reader's sign stays, applied after it (`-r0_abs` is -|r0|, the modifier's order)."""
    src = mov.srcs[0]
    if mov.opcode == "abs" or use.modifier == "abs":
        out.modifier, out.negate = "abs", use.negate
    else:
        out.modifier = src.modifier
    return out


def propagate_copies(cg: Any) -> int:
    return _read_in_place(cg, "mov")


def abs_into_sources(cg: Any) -> int:
    """`abs vrX, src` whose every reader can read `src_abs` in its place (the `_abs` source
    modifier of vs_3_0 and ps_3_0) is left out, as propagate_copies leaves out a copy: fxc
    wrote `cmp r1, -r0_abs.w, c0.x, c0.y` (Effekseer's sprite_unlit_ps, vs `abs r1.x, r0.w`
    and the cmp reading r1.x)."""
    if "abs" not in cg.rules.src_modifiers:
        return 0
    return _read_in_place(cg, "abs")


def _read_in_place(cg: Any, opcode: str) -> int:
    """`opcode vrX, src` (a mov, or an abs read as a modifier) whose readers read `src`
    instead, left out where every reader could."""
    instrs: list[Instruction] = cg.instrs
    rules = cg.rules
    defs, uses = _census(instrs)
    drop: set[int] = set()
    for i, mov in enumerate(instrs):
        if mov.opcode != opcode or mov.saturate or mov.dst is None or mov.dst.kind != "vr" \
                or len(defs.get(mov.dst.index, ())) != 1 or len(mov.srcs) != 1:  # type: ignore[arg-type]
            continue
        x = mov.dst
        source = mov.srcs[0]
        if source.kind not in _SOURCES or (opcode == "abs" and (
                source.modifier is not None or source.relative is not None)):
            continue
        left = uses.get(x.index, 0)  # type: ignore[arg-type]
        for j in range(i + 1, len(instrs)):
            if left == 0:
                break
            ins = instrs[j]
            if is_flow(ins):
                break
            reads = [k for k, s in enumerate(ins.srcs) if _same(s, x)]
            if reads:
                if ins.opcode in _READERS and reads and not (ins.dst is not None and ins.dst.kind == "a"
                                                             and _indexed_by_a0(source)):
                    new = list(ins.srcs)
                    for k in reads:
                        c = _compose(ins.srcs[k], mov)
                        if c is None:
                            break
                        new[k] = c
                    else:
                        if _ports_ok(new, rules) and all(
                                _choose(needed(s), _rule(rules)) is not None
                                for s in new):
                            ins.srcs = new
                            left -= len(reads)
                if _same_written(ins, source):
                    break
                continue
            if _same_written(ins, source):
                break
        if left == 0:
            drop.add(i)
    cg.instrs = [ins for k, ins in enumerate(instrs) if k not in drop]
    return len(drop)


def _indexed_by_a0(reg: Operand) -> bool:
    return reg.relative is not None and reg.relative.kind == "a"


def _same_written(ins: Instruction, source: Operand) -> bool:
    d = _writes(ins)
    if d is None:
        return False
    if _indexed_by_a0(source):          # c[a0.y + n] reads another register once a0.y changes
        return d.kind == "a" and source.relative.component in written(ins)  # type: ignore[union-attr]
    return _same(d, source)


def _const_lane_values(cg: Any, s: Operand, lanes: tuple[int, ...]) -> list[float] | None:
    if s.kind != "c" or s.relative is not None or s.index not in cg.defs:
        return None
    values = cg.defs[s.index]
    need = needed(s)
    vals = [values[need[l]] for l in lanes]
    if any(v is None for v in vals):
        return None
    return [-v if s.negate else v for v in vals]  # type: ignore[operator]


def _bound(cg: Any, ins: Instruction, value: float) -> Operand | None:
    """The other source of `ins` (max/min of two) when one is the constant `value` in every
    lane the instruction writes."""
    if len(ins.srcs) != 2:
        return None
    for k in (0, 1):
        vals = _const_lane_values(cg, ins.srcs[k], written(ins))
        if vals is not None and all(v == value for v in vals):
            return ins.srcs[1 - k]
    return None


def clamp_to_saturate(cg: Any) -> int:
    """`max vrA, x, 0; min D, vrA, 1` (or min then max), vrA read once: `mov_sat D, x`.
    Saturate is the same clamp for every number but NaN (the assembly reference's _sat
    page: "clamps to the range [0, 1]"), which shader constants never hold."""
    rules = cg.rules
    if not (rules.saturate and (rules.kind == "ps" or rules.major >= 3)):
        return 0
    instrs: list[Instruction] = cg.instrs
    defs, uses = _census(instrs)
    where = {i: ins for i, ins in enumerate(instrs)}
    drop: set[int] = set()
    for j, outer in enumerate(instrs):
        for first, second, lo_hi in (("max", "min", (0.0, 1.0)), ("min", "max", (1.0, 0.0))):
            if outer.opcode != second or outer.saturate:
                continue
            inner_src = _bound(cg, outer, lo_hi[1])
            if inner_src is None or inner_src.kind != "vr" or inner_src.negate \
                    or inner_src.modifier:
                continue
            vr = inner_src.index
            d = defs.get(vr, [])  # type: ignore[arg-type]
            if len(d) != 1 or uses.get(vr) != 1 or d[0] >= j:  # type: ignore[arg-type]
                continue
            inner = where[d[0]]
            if inner.opcode != first or inner.saturate or any(is_flow(x) for x in instrs[d[0]:j]):
                continue
            x = _bound(cg, inner, lo_hi[0])
            if x is None:
                continue
            composed = _compose(inner_src, Instruction("mov", inner.dst, [x], outer.info))
            if composed is None:
                continue
            outer.opcode, outer.srcs, outer.saturate = "mov", [composed], True
            outer.info = row("mov", rules.name)
            drop.add(d[0])
            break
    cg.instrs = [ins for k, ins in enumerate(instrs) if k not in drop]
    return len(drop)


def _writable(rules: Any, op: str, dst: Operand) -> bool:
    if dst.kind == "vr":
        return True
    if op in _TEXLD or dst.kind == "a" or dst.relative is not None:
        return False
    if rules.kind == "ps" and rules.major == 2 and dst.kind in ("oC", "oDepth"):
        return op == "mov"          # ps_2_0 / ps_2_x: "oC# and oDepth are written by mov"
    return True


def _moved(prod: Instruction, mov: Instruction, rules: Any
           ) -> tuple[tuple[int, ...], list] | None:
    """`prod`'s write mask and sources once it writes what `mov` (its one reader) copies of its
    result, lane for lane where `mov` writes: the same instruction where the lanes agree, the
    mask widened for a replicated result, the sources' swizzles following a lane-wise one's
    lanes; None where the instruction cannot (a macro, or a swizzle ps_2_0 lacks)."""
    mov_mask, prod_mask = written(mov), written(prod)
    need = needed(mov.srcs[0])
    need = {l: need[l] for l in mov_mask}         # mov lane -> the lane of prod's result
    if any(n not in prod_mask for n in need.values()):
        return None
    if all(need[l] == l for l in mov_mask) and tuple(prod_mask) == tuple(mov_mask):
        return tuple(prod_mask), prod.srcs
    if prod.opcode in _REPLICATED and len(prod_mask) == 1:
        return tuple(mov_mask), prod.srcs
    if prod.opcode not in _COMPONENTWISE:
        return None
    srcs: list = []
    for s in prod.srcs:
        reads = needed(s)
        lanes = {l: reads[need[l]] for l in mov_mask}
        if _choose(lanes, _rule(rules)) is None:
            return None
        moved = read(s, lanes, s.negate)
        moved.modifier = s.modifier
        srcs.append(moved)
    return tuple(mov_mask), srcs


def fold_into_producer(cg: Any) -> int:
    rules = cg.rules
    instrs: list[Instruction] = cg.instrs
    defs, uses = _census(instrs)
    drop: set[int] = set()
    for j, mov in enumerate(instrs):
        if mov.opcode != "mov" or mov.dst is None or len(mov.srcs) != 1:
            continue
        s = mov.srcs[0]
        if s.kind != "vr" or s.negate or s.modifier or uses.get(s.index) != 1:  # type: ignore[arg-type]
            continue
        d = defs.get(s.index, [])  # type: ignore[arg-type]
        if len(d) != 1 or d[0] >= j or d[0] in drop:
            continue
        i = d[0]
        prod = instrs[i]
        if prod.opcode not in _PRODUCERS:
            continue
        if mov.saturate and (prod.opcode in _TEXLD or not rules.saturate):
            continue
        target = mov.dst
        if not _writable(rules, prod.opcode, target):
            continue
        moved = _moved(prod, mov, rules)
        if moved is None:
            continue
        if prod.opcode not in _ALIASES and any(_same(r, target) for r in _read_regs(prod)):
            continue            # a macro may write its destination before its last read
        between = instrs[i + 1:j]
        if any(is_flow(x) or any(_same(r, target) for r in _read_regs(x))
               or (_writes(x) is not None and _same(_writes(x), target)) for x in between):  # type: ignore[arg-type]
            continue
        mask, prod.srcs = moved
        prod.dst = Operand(target.kind, target.index, relative=target.relative, mask=mask)
        prod.saturate = prod.saturate or mov.saturate
        drop.add(j)
    cg.instrs = [ins for k, ins in enumerate(instrs) if k not in drop]
    return len(drop)


def _lanes_read(ins: Instruction, reg: Operand) -> set[int]:
    return {lane for s in ins.srcs if _same(s, reg) for lane in needed(s).values()}


def build_in_place(cg: Any) -> int:
    """`mov C, X` whose X, read nowhere else, was built lane by lane from C's own lanes and new
    ones (`mad X.x, ..., C.x; mov X.yzw, C; mov C, X`: a loop's carried vector with one lane
    updated) is C updated in place (`mad C.x, ..., C.x`): X's writers write C, the copies of
    C's own lanes and the mov are left out. Each lane of the mov written once, in straight-line
    code, where nothing between a writer and the mov reads or writes the lanes it now writes
    of C (the writer itself reads its sources before it writes)."""
    instrs: list[Instruction] = cg.instrs
    defs, uses = _census(instrs)
    drop: set[int] = set()
    for j, mov in enumerate(instrs):
        if mov.opcode != "mov" or mov.saturate or mov.dst is None or mov.dst.kind != "vr" \
                or len(mov.srcs) != 1:
            continue
        s, c = mov.srcs[0], mov.dst
        if s.kind != "vr" or s.negate or s.modifier or _same(s, c) or uses.get(s.index) != 1:  # type: ignore[arg-type]
            continue
        need = needed(s)
        if any(need[l] != l for l in written(mov)):
            continue
        ws = defs.get(s.index, [])  # type: ignore[arg-type]
        if not ws or ws[-1] >= j or any(k in drop for k in ws):
            continue
        first = ws[0]
        lanes = [l for w in ws for l in written(instrs[w])]
        if sorted(lanes) != sorted(written(mov)) or \
                any(is_flow(x) for x in instrs[first:j]):
            continue
        same = [w for w in ws if _is_self_copy(instrs[w], c)]
        moved = [w for w in ws if w not in same]
        ok = all(instrs[w].opcode in _ALIASES or not _lanes_read(instrs[w], c) for w in moved)
        for k in range(first, j):
            x = instrs[k]
            if k in ws:
                continue
            d = _writes(x)
            if d is not None and _same(d, c):
                ok = False                      # C changes between: the order would matter
        for w in moved:
            mask = set(written(instrs[w]))
            if any(_lanes_read(instrs[k], c) & mask for k in range(w + 1, j) if k not in same):
                ok = False
        if not ok:
            continue
        for w in moved:
            instrs[w].dst = Operand(c.kind, c.index, mask=written(instrs[w]))
        drop.update(same)
        drop.add(j)
    cg.instrs = [ins for k, ins in enumerate(instrs) if k not in drop]
    return len(drop)


def _is_self_copy(ins: Instruction, c: Operand) -> bool:
    """`mov X.m, C.m`: C's own lanes, each where it was."""
    if ins.opcode != "mov" or ins.saturate or len(ins.srcs) != 1:
        return False
    s = ins.srcs[0]
    need = needed(s)
    return _same(s, c) and not s.negate and not s.modifier and \
        all(need[l] == l for l in written(ins))


def drop_dead_writes(cg: Any) -> int:
    """Instructions whose temporary no kept instruction reads: what is kept is what writes an
    output, a0 or a flow test (rep, if, break, texkill), and, back from there, what writes a
    temporary a kept instruction reads (a mark over registers, flow-insensitive, so a value
    read round a loop or after an if is kept). A loop counter no one reads after its loop
    (`for (i = 0; i < n; i++)` run by `rep i0`) was carried round the loop and copied out of
    it (`add r2.x, r2, c3.y` in the body, `mov r1.x, r2` after: Wine's registerset_blob_scalar
    test shader, whose fxc code has neither)."""
    instrs: list[Instruction] = cg.instrs
    writers: dict[int, list[int]] = {}
    roots: list[int] = []
    for i, ins in enumerate(instrs):
        d = _writes(ins)
        if d is not None and d.kind == "vr":
            writers.setdefault(d.index, []).append(i)     # type: ignore[arg-type]
        else:
            roots.append(i)
    kept: set[int] = set()
    seen: set[int] = set()
    todo = roots
    while todo:
        i = todo.pop()
        if i in kept:
            continue
        kept.add(i)
        for r in _read_regs(instrs[i]):
            if r.kind == "vr" and r.index not in seen:
                seen.add(r.index)                          # type: ignore[arg-type]
                todo.extend(writers.get(r.index, ()))      # type: ignore[arg-type]
    cg.instrs = [ins for i, ins in enumerate(instrs) if i in kept]
    return len(instrs) - len(kept)


# The passes in the order run, each to a fixed point with the others (a copy left out can
# let a clamp become _sat, whose mov then folds into its producer).
PASSES = (("propagate copies", propagate_copies), ("abs into sources", abs_into_sources),
          ("clamp to saturate", clamp_to_saturate),
          ("fold into producer", fold_into_producer), ("build in place", build_in_place),
          ("drop dead writes", drop_dead_writes))


ROUNDS = 2


def optimise(cg: Any) -> dict[str, int]:
    """Run the passes in order, a second round where the first removed something (what one
    pass leaves can open a rewrite for an earlier one: a mov left out makes a clamp's input
    a temporary read once); how many each removed. Two rounds: a third removed nothing on
    the bundled effects and tests/data/realfx, and each round costs a few census scans."""
    removed = {name: 0 for name, _ in PASSES}
    for _ in range(ROUNDS):
        total = 0
        for name, fn in PASSES:
            n = fn(cg)
            removed[name] += n
            total += n
        if not total:
            break
    # a `def` only the removed instructions read (clamp's 0 and 1) is left out
    kept = {s.index for ins in cg.instrs for s in ins.srcs
            if s.kind == "c" and s.relative is None}
    for reg in [r for r in cg.defs if r not in kept]:
        del cg.defs[reg]
    return removed
