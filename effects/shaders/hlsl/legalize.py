"""The version's rules on the emitted code, then temporaries (allocate.py), for the writer.

- read ports: an instruction reading more distinct registers of a kind than the version
  allows (one c# in vs_1_1, one t#/v# in ps_2_0) reads the extra ones through a mov;
- texture coordinates and texkill operands are registers read without swizzle; a 1D read's
  coordinate (tex1D: x alone, on a sampler declared 2d) has its y written too (`one_d_reads`);
- swizzles: ps_2_0 and ps_2_b take identity, replicate and three fixed swizzles only; any
  other lane selection is built into a temporary one component at a time;
"""
from __future__ import annotations

from dataclasses import replace
from typing import Any

from effects.base import caches
from effects.base.errors import Location
from effects.shaders.asm.versions import IDENTITY, PS20_SWIZZLES
from effects.shaders.asm.program import Instruction, Operand
from effects.shaders.hlsl.allocate import ALIASES, allocate
from effects.shaders.hlsl.components import laid_out, used_counts
from effects.shaders.hlsl.constant_layout import declaration_order
from effects.shaders.hlsl.context import explicit_register
from effects.shaders.hlsl.ops import OPS
from effects.shaders.hlsl.records import fixed, instruction, is_flow, needed, read, reg, same
from effects.shaders.hlsl.writer import Code, declaration

_SAMPLER_DCL = {"2d": "2d", "1d": "2d", "3d": "volume", "cube": "cube"}

_TEXLD = {"texld", "texldp", "texldb", "texldl", "texldd"}
# by the op table's shapes (ops.py): instructions whose one result is replicated into every lane
# of the write mask (dp3, rcp ...: "the scalar result is replicated"), and those whose lane L
# reads lane L of each source (add, mul ...), which can write their lanes elsewhere, or more of
# them, once their sources' swizzles follow. Only the single instructions that may write any
# register (allocate.ALIASES): the macros' pages ask for a temporary destination (pow: "The
# dest register should be a temporary register"; nrm, crs, lrp, sincos; vs_1_1's frc)
REPLICATED = frozenset(r.mnemonic for r in OPS.values()
                       if r.shape in ("scalar", "reduce")) & ALIASES
COMPONENTWISE = frozenset(r.mnemonic for r in OPS.values() if r.shape == "lanes") & ALIASES


def _choose(needed: dict[int, int], rule: str) -> tuple[int, ...] | None:
    """The source swizzle that puts component `needed[lane]` in each lane the instruction
    reads (None: ps_2_0 has no such swizzle)."""
    if not needed:
        return IDENTITY
    return _choose_lanes(tuple(sorted(needed.items())), rule)


# ps_2_0's swizzles in the order tried: identity, the replicates, then the rest
_PS20_ORDER = (IDENTITY, *((k,) * 4 for k in range(4)), *sorted(PS20_SWIZZLES - {IDENTITY}))


# a few hundred distinct lane maps; asked per source per instruction
@caches.memo("shaders.hlsl.lanes", keys="lanes needed, the swizzle rule", entry_bytes=128,
             max_bytes=4096 * 128)
def _choose_lanes(items: tuple[tuple[int, int], ...], rule: str) -> tuple[int, ...] | None:
    needed = dict(items)
    if rule == "any":
        full: list[int] = []
        for i in range(4):
            full.append(needed.get(i, full[-1] if full else needed[min(needed)]))
        if all(needed.get(i, i) == i for i in range(4)) and all(needed[i] == i for i in needed):
            return IDENTITY
        return tuple(full)
    for cand in _PS20_ORDER:
        if all(cand[i] == v for i, v in items):
            return cand
    return None


def legalize(cg: Any) -> None:
    """The version's rules on the emitted instructions, in place: extra read ports, texture
    coordinates and swizzles the version lacks go through a mov into a temporary."""
    rules = cg.rules
    rule = "ps20" if rules.swizzles == "ps20" else "any"
    out: list[Instruction] = []
    over = [_over_ports(ins, rules) for ins in cg.instrs]
    copies: dict[tuple[str, int], tuple[Operand, set[int]]] = {}
    for k, ins in enumerate(cg.instrs):
        if is_flow(ins):
            copies.clear()                 # a copy serves the straight-line code after it
        for kind, regs in over[k].items():
            _read_ports(cg, out, k, kind, regs, over, copies)
        if ins.opcode in _TEXLD and cg.target.kind == "ps" and _one_d(ins):
            _second_lane(cg, out, ins)
        # texture coordinates: a register read whole
        if ins.opcode in _TEXLD and cg.target.kind == "ps" and cg.rules.major == 2:
            for k, s in enumerate(ins.srcs):
                lanes = needed(s)
                if s.kind == "s" or s.kind in ("vr", "t") and \
                        all(v == i for i, v in lanes.items()) and not s.negate \
                        and not s.modifier:
                    continue
                tmp = cg.temp()
                _copy(cg, out, tmp, s, ins.location, rule)
                ins.srcs[k] = read(tmp, {i: i for i in range(4)})
        # swizzles
        for k, s in enumerate(ins.srcs):
            lanes = needed(s)
            if _choose(lanes, rule) is None:
                tmp = cg.temp()
                _copy(cg, out, tmp, s, ins.location, rule)
                ins.srcs[k] = read(tmp, {i: i for i in lanes})
        out.append(ins)
    cg.instrs = out


def _over_ports(ins: Instruction, rules: Any) -> dict[str, list[int]]:
    """The kinds `ins` reads more registers of than the version's read ports, with those
    registers in source order. A relative constant, c[a0.x + n] or c[aL + n], is not counted
    here: the copy propagation that puts one in an instruction counts it (peephole._ports_ok)."""
    if ins.opcode == "texkill":
        return {}
    regs: dict[str, list[int]] = {}
    for s in ins.srcs:
        if s.kind in rules.read_ports and s.relative is None:
            seen = regs.setdefault(s.kind, [])
            if s.index not in seen:
                seen.append(s.index)  # type: ignore[arg-type]
    return {kind: r for kind, r in regs.items() if len(r) > rules.read_ports[kind]}


def _read_ports(cg: Any, out: list[Instruction], k: int, kind: str, regs: list[int],
                over: list[dict[str, list[int]]],
                copies: dict[tuple[str, int], tuple[Operand, set[int]]]) -> None:
    """Instruction `k` reading registers `regs` of `kind`, more than the version's ports, reads
    the extra ones from temporaries: a copy made for an earlier instruction of the same
    straight-line code where one holds the lanes read (the registers copied are never
    written), else a new one. The registers kept are those the fewest later instructions read
    past their ports, so one copy serves them all (fxc's `mov r1.xyz, c7` read by three dp3
    past vs_1_1's one constant port: the DirectX docs' preshader sample); a copy holds the
    lanes all those read (write-mask liveness: `mov r0.x, c5` for `mad r.x, v1, c4, c5.x`)."""
    instrs = cg.instrs
    ins = instrs[k]
    limit = cg.rules.read_ports[kind]
    kept = list(regs)
    for r in regs:
        held = copies.get((kind, r))
        if len(kept) > limit and held is not None and _lanes_of(ins, kind, r) <= held[1]:
            _retarget(ins, kind, r, held[0])
            kept.remove(r)
    if len(kept) <= limit:
        return
    later: dict[int, list[int]] = {r: [] for r in kept}
    for j in range(k, len(instrs)):
        if j > k and is_flow(instrs[j]):
            break
        for r in over[j].get(kind, ()):
            if r in later:
                later[r].append(j)
    keep = sorted(kept, key=lambda r: (len(later[r]), kept.index(r)))[:limit]
    for r in kept:
        if r in keep:
            continue
        lanes = set().union(*(_lanes_of(instrs[j], kind, r) for j in later[r]))
        tmp = cg.temp()
        out.append(instruction("mov", tmp, tuple(sorted(lanes)),
                               [read(reg(kind, r), {i: i for i in sorted(lanes)})],
                               cg.rules.name, ins.location))
        copies[(kind, r)] = (tmp, lanes)
        _retarget(ins, kind, r, tmp)


def _lanes_of(ins: Instruction, kind: str, index: int) -> set[int]:
    """The components of register `kind``index` that `ins` reads."""
    return {lane for s in ins.srcs if s.kind == kind and s.index == index and s.relative is None
            for lane in needed(s).values()}


def _retarget(ins: Instruction, kind: str, index: int, tmp: Operand) -> None:
    """Every source of `ins` reading register `kind``index` reads `tmp` instead."""
    for s in ins.srcs:
        if s.kind == kind and s.index == index and s.relative is None:
            s.kind, s.index = tmp.kind, tmp.index


def _one_d(ins: Instruction) -> bool:
    """A 1D read: the coordinate gives x alone (tex1D's float; the others give two or more)."""
    s = ins.srcs[0]
    return s.lanes is not None and set(s.lanes) == {0}


def _second_lane(cg: Any, out: list[Instruction], ins: Instruction) -> None:
    """A 1D read's coordinate with a written y. The sampler is declared 2d (shader models 2-3
    have no 1D textures: a height-1 2D one), and texld reads x and y ("Validation enforces that
    coordinates provided to texld are sufficient for the texture dimension declared for the
    sampler"), so y must hold a value: fxc read `v0.y` as `texld r1, v0.y, s0` (a replicate)
    and `v0.x` as `texld r0, v0, s0` (its y declared: Wine's ps_3_0 sampler test,
    tests/data/d3dbc/wine). ps_3_0 replicates x into y by the swizzle where y holds nothing
    declared or written; ps_2_0's texld takes no swizzle, so t# is declared .xy and a temporary's
    producer writes x into y as well (`mad r0.xy`), else a copy `mov r1.xy, r0.x` does (legalize
    copies coordinates it cannot read in place, replicated alike)."""
    s = ins.srcs[0]
    x = s.lanes[0]  # type: ignore[index]
    if s.kind in ("v", "t") and x == 0 and _declared_width(cg, s) >= 2:
        return                                   # x and y declared: read as they are
    if cg.rules.major >= 3 or s.kind != "vr" or x != 0:
        if cg.rules.major == 2 and s.kind == "t" and x == 0:
            _declare_xy(cg, s)                    # ps_2_0 reads t# whole, unswizzled
            return
        ins.srcs[0] = _relaned(s, {0: x, 1: x})   # replicate (or copied so)
        return
    writers = [w for w in out if w.dst is not None and same(w.dst, s)]
    if any(1 in w.dst.mask for w in writers):  # type: ignore[union-attr, operator]
        return                                   # y holds a value already
    if len(writers) == 1 and _widen(writers[0]):
        return
    ins.srcs[0] = _relaned(s, {0: 0, 1: 0})       # copied below: mov r1.xy, r0.x


def _widen(w: Instruction) -> bool:
    """`w` (writing .x alone) writing its x into y too, where one instruction can."""
    d = w.dst
    if d is None or tuple(d.mask) != (0,):  # type: ignore[arg-type]
        return False
    if w.opcode in REPLICATED:
        d.mask = (0, 1)
        return True
    if w.opcode not in COMPONENTWISE:
        return False
    w.srcs = [s if s.lanes is None else _relaned(s, {0: s.lanes[0], 1: s.lanes[0]})
              for s in w.srcs]
    d.mask = (0, 1)
    return True


def _declared_width(cg: Any, reg: Operand) -> int:
    d = cg.inputs.get(f"{reg.kind}{reg.index}")
    return 4 if d is None or d.register.mask is None else len(d.register.mask)


def _declare_xy(cg: Any, reg: Operand) -> None:
    name = f"{reg.kind}{reg.index}"
    d = cg.inputs.get(name)
    if d is not None and d.register.mask is not None and len(d.register.mask) < 2:
        cg.inputs[name] = declaration(reg.kind, reg.index, d.usage, d.usage_index, mask=(0, 1),
                                      centroid=d.centroid)


def _copy(cg: Any, out: list[Instruction], tmp: Operand, s: Operand, loc: Location,
          rule: str) -> None:
    """tmp.lane = s.<lane it needs>: one mov where the version has the swizzle, else one mov
    per component replicated, or, where that makes fewer, one plain mov of the lanes that keep
    their own component and one per other component (ps_2_0's .xyzy: fxc's `mov r1.xyz, r0`
    / `mov r1.w, r0.y` in Pale Moon's LayerManagerD3D9 shaders)."""
    lanes = needed(s)
    version = cg.rules.name
    if _choose(lanes, rule) is not None:
        out.append(instruction("mov", tmp, tuple(sorted(lanes)), [_relaned(s, lanes)],
                               version, loc))
        return
    own = {lane: c for lane, c in lanes.items() if lane == c}
    moved = _by_component({lane: c for lane, c in lanes.items() if lane != c})
    by_source = _by_component(lanes)
    if own and 1 + len(moved) < len(by_source):
        out.append(instruction("mov", tmp, tuple(sorted(own)), [_relaned(s, own)], version,
                               loc))
        by_source = moved
    for src_lane, dst_lanes in by_source.items():
        copy = fixed(s, (src_lane,) * 4, s.negate)
        copy.modifier = s.modifier
        out.append(instruction("mov", tmp, tuple(sorted(dst_lanes)), [copy], version, loc))


def _by_component(lanes: dict[int, int]) -> dict[int, list[int]]:
    """Component -> the lanes that read it."""
    out: dict[int, list[int]] = {}
    for lane, c in lanes.items():
        out.setdefault(c, []).append(lane)
    return out


def _relaned(s: Operand, lanes: dict[int, int]) -> Operand:
    """`s` (its sign and modifier) reading `lanes`."""
    out = read(s, lanes, s.negate)
    out.modifier = s.modifier
    return out


# the instructions that read an int or bool parameter's register
_READERS = {"i": ("rep", "loop"), "b": ("if",)}


def _int_bool_tables(cg: Any, int_defs: dict[int, Any]
                     ) -> dict[str, tuple[dict[str, int], dict[str, int]]]:
    """The int and bool parameters laid out again now that the code's reads are known
    (components.laid_out), their registers in the instructions renumbered: per kind, each
    parameter's first register and the registers it holds."""
    ctx = cg.ctx
    counts = getattr(ctx, "component_counts", {})
    declared = declaration_order(ctx.effect)
    out = {}
    for kind, regs in (("i", getattr(ctx, "int_registers", {})),
                       ("b", getattr(ctx, "bool_registers", {}))):
        readers = [ins for ins in cg.instrs if ins.opcode in _READERS[kind]]
        used = {s.index for ins in readers for s in ins.srcs if s.kind == kind}
        fixed = {n for n in regs if explicit_register(ctx, n, kind) is not None}
        defs = set(int_defs) & used if kind == "i" else set()
        firsts, sizes, remap = laid_out(regs, counts, used, fixed, declared, defs)
        for ins in readers:
            ins.srcs = [replace(s, index=remap[s.index])
                        if s.kind == kind and s.index in remap else s for s in ins.srcs]
        out[kind] = (firsts, {**counts, **sizes})
    return out


def source_swizzle(instrs: list[Instruction], rule: str) -> None:
    """Each source's swizzle, one the version has (`_choose`), where it read lanes."""
    for ins in instrs:
        for s in ins.srcs:
            s.swizzle = _choose(needed(s), rule) or IDENTITY  # type: ignore[assignment]
            s.lanes = None


def code_of(cg: Any) -> Code:
    """The legalized instructions allocated (allocate.py), their swizzles chosen and samplers
    numbered, with the defs, the declarations of the inputs, outputs and samplers read and
    the tables of registers the pass loads, for the writer (writer.py)."""
    rule = "ps20" if cg.rules.swizzles == "ps20" else "any"
    alloc = allocate(cg.instrs)
    source_swizzle(cg.instrs, rule)
    int_defs = getattr(cg.ctx, "int_defs", {})      # a [loop] over literal bounds (loops.py)
    tables = _int_bool_tables(cg, int_defs)
    used_i = {s.index for ins in cg.instrs if ins.opcode in ("rep", "loop") for s in ins.srcs
              if s.kind == "i"}
    used_inputs: dict[str, None] = {}
    samplers: dict[str, int] = dict(cg.sampler_regs)
    read: dict[str, None] = {}
    for ins in cg.instrs:
        for s in ins.srcs:
            if s.kind in ("v", "t"):
                used_inputs.setdefault(f"{s.kind}{s.index}")
            elif s.kind in ("vPos", "vFace"):    # ps_3_0's misc inputs, unindexed
                used_inputs.setdefault(s.kind)
            elif s.kind == "s" and s.index is None:
                name = s.text
                read.setdefault(name)
                if name not in samplers:
                    taken = set(samplers.values())
                    k = 0
                    while k in taken:
                        k += 1
                    samplers[name] = k
                s.index = samplers[name]
    dcls = []
    for name in sorted(used_inputs, key=lambda n: (n[0], int(n[1:]) if n[1:].isdigit() else -1)):
        dcls.append(cg.inputs[name] if name in cg.inputs else
                    declaration(name[0], int(name[1:])))
    dcls += getattr(cg, "output_dcls", [])
    kinds = cg.ctx.samplers_used
    for name, k in sorted(samplers.items(), key=lambda kv: kv[1]):
        if name in read:
            dcls.append(declaration("s", k, sampler_type=_SAMPLER_DCL.get(kinds.get(name, "2d"), "2d")))
    used_c = {name: (start, cg.register_sizes.get(name, 1)) for name, start in cg.const_regs.items()}
    used_b = {s.index for ins in cg.instrs if ins.opcode == "if" for s in ins.srcs
              if s.kind == "b"}
    ints, int_counts = used_counts(*tables["i"], used_i)
    bools, bool_counts = used_counts(*tables["b"], used_b)
    return Code(cg.instrs, alloc,
                {r: tuple(0.0 if v is None else v for v in vals) for r, vals in cg.defs.items()},
                {r: v for r, v in int_defs.items() if r in used_i}, dcls, constants=used_c,
                samplers={n: k for n, k in samplers.items() if n in read}, int_registers=ints,
                bool_registers=bools, register_counts={**int_counts, **bool_counts})
