"""The version's rules on the emitted code, then temporaries, then the text.

- read ports: an instruction reading more distinct registers of a kind than the version
  allows (one c# in vs_1_1, one t#/v# in ps_2_0) reads the extra ones through a mov;
- texture coordinates and texkill operands are registers read without swizzle;
- swizzles: ps_2_0 and ps_2_b take identity, replicate and three fixed swizzles only; any
  other lane selection is built into a temporary one component at a time;
- temporaries: linear scan, lowest free register first, a register reused from the
  instruction where its last value dies.
"""
from __future__ import annotations

from typing import Any

from effects.base import caches
from effects.base.errors import Location, UNKNOWN_LOCATION
from effects.shaders.asm.versions import IDENTITY, PS20_SWIZZLES
from effects.shaders.hlsl.asmcode import Generated, Instr, Reg, Src, _SAMPLER_DCL

COMPONENTS = "xyzw"
_TEXLD = {"texld", "texldp", "texldb", "texldl", "texldd"}


def _lanes_needed(ins: Instr, src: Src) -> dict[int, int]:
    if src.fixed is not None:
        return {i: src.fixed[i] for i in range(4)}
    return dict(src.lanes)


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


def finish(cg: Any) -> Generated:
    rules = cg.rules
    rule = "ps20" if rules.swizzles == "ps20" else "any"
    out: list[Instr] = []
    for ins in cg.instrs:
        # read ports
        if ins.opcode not in ("texkill",):
            seen: dict[str, list[str]] = {}
            for s in ins.srcs:
                kind = s.reg.kind
                if kind not in rules.read_ports:
                    continue
                names = seen.setdefault(kind, [])
                key = f"{kind}{s.reg.index}"
                if key in names:
                    continue
                if len(names) >= rules.read_ports[kind]:
                    tmp = cg.temp()
                    # the copy's lanes: the register's components this instruction reads
                    # (write-mask liveness: `mov r0.x, c5` for a `mad r.x, v1, c4, c5.x`)
                    read = sorted({lane for other in ins.srcs if other.reg.kind == kind
                                   and other.reg.index == s.reg.index
                                   for lane in _lanes_needed(ins, other).values()})
                    out.append(Instr("mov", tmp, tuple(read), [Src(s.reg, {i: i for i in read})],
                                     ins.location))
                    for other in ins.srcs:
                        if other.reg is s.reg or (other.reg.kind == kind and other.reg.index == s.reg.index):
                            other.reg = tmp
                    continue
                names.append(key)
        # texture coordinates: a register read whole
        if ins.opcode in _TEXLD and cg.target.kind == "ps" and cg.rules.major == 2:
            for k, s in enumerate(ins.srcs):
                needed = _lanes_needed(ins, s)
                if s.reg.kind in ("vr", "t") and all(v == i for i, v in needed.items()) \
                        and not s.negate:
                    continue
                tmp = cg.temp()
                _copy(cg, out, tmp, s, ins.location, rule)
                ins.srcs[k] = Src(tmp, {i: i for i in range(4)})
        # swizzles
        for k, s in enumerate(ins.srcs):
            needed = _lanes_needed(ins, s)
            if _choose(needed, rule) is None:
                tmp = cg.temp()
                _copy(cg, out, tmp, s, ins.location, rule)
                ins.srcs[k] = Src(tmp, {i: i for i in needed}, False)
        out.append(ins)
    cg.instrs = out
    return _text(cg)


def _copy(cg: Any, out: list[Instr], tmp: Reg, s: Src, loc: Location, rule: str) -> None:
    """tmp.lane = s.reg.<lane it needs>, one mov per source lane (replicate swizzles)."""
    needed = _lanes_needed(Instr("mov", None, (), []), s)
    if _choose(needed, rule) is not None:
        out.append(Instr("mov", tmp, tuple(sorted(needed)), [Src(s.reg, needed, s.negate)], loc))
        return
    by_source: dict[int, list[int]] = {}
    for lane, src_lane in needed.items():
        by_source.setdefault(src_lane, []).append(lane)
    for src_lane, lanes in by_source.items():
        out.append(Instr("mov", tmp, tuple(sorted(lanes)), [Src(s.reg, {}, s.negate, fixed=(src_lane,) * 4)], loc))


def _allocate(instrs: list[Instr]) -> dict[int, int]:
    first: dict[int, int] = {}
    last: dict[int, int] = {}
    for i, ins in enumerate(instrs):
        for reg in [ins.dst] + [s.reg for s in ins.srcs]:
            if reg is not None and reg.kind == "vr":
                first.setdefault(reg.index, i)  # type: ignore[arg-type]
                last[reg.index] = i  # type: ignore[index]
    # a register set before a rep and read inside is read again by the next iteration: it
    # lives to the endrep (innermost loops first, so an outer one extends it further)
    for start, end in sorted(_loops(instrs), key=lambda r: r[1] - r[0]):
        for vr in first:
            if first[vr] < start and start <= last[vr] <= end:
                last[vr] = end
    alloc: dict[int, int] = {}
    active: list[tuple[int, int]] = []     # (end, physical)
    free: list[int] = []
    count = 0
    for vr in sorted(first, key=lambda v: (first[v], v)):
        start = first[vr]
        for end, phys in list(active):
            if end <= start and end != start or (end == start and _dies_before_write(instrs[start], vr)):
                active.remove((end, phys))
                free.append(phys)
        free.sort()
        if free:
            phys = free.pop(0)
        else:
            phys, count = count, count + 1
        alloc[vr] = phys
        active.append((last[vr], phys))
    return alloc


def _loops(instrs: list[Instr]) -> list[tuple[int, int]]:
    """(rep index, its endrep index) of every loop in the code."""
    out, stack = [], []
    for i, ins in enumerate(instrs):
        if ins.opcode in ("rep", "loop"):
            stack.append(i)
        elif ins.opcode in ("endrep", "endloop"):
            out.append((stack.pop(), i))
    return out


# single-slot instructions that read every source before writing: a register whose last
# read is one of these may be its destination (`add r0, r0, c0`, as fxc reuses temporaries).
# Not the macros (pow, nrm, crs, lrp, sincos, m#x#), whose pages forbid or do not promise it,
# nor vs_1_1's frc, a macro there.
_ALIASES = frozenset({"mov", "add", "mul", "mad", "min", "max", "slt", "sge", "cmp", "dp3",
                      "dp4", "dp2add", "rcp", "rsq", "exp", "log", "abs", "texld", "texldp",
                      "texldb", "texldl", "texldd", "dsx", "dsy"})


def _dies_before_write(ins: Instr, vr: int) -> bool:
    # a register whose last read is this instruction may be this instruction's destination
    return ins.opcode in _ALIASES and ins.dst is not None and ins.dst.kind == "vr" \
        and ins.dst.index == vr


def _swizzle_text(sw: tuple[int, ...]) -> str:
    if sw == IDENTITY:
        return ""
    letters = [COMPONENTS[i] for i in sw]
    while len(letters) > 1 and letters[-1] == letters[-2]:
        letters.pop()
    return "." + "".join(letters)


def _src_text(s: Src, alloc: dict[int, int], rule: str, ins: Instr) -> str:
    sw = _choose(_lanes_needed(ins, s), rule) or IDENTITY
    return f"{'-' if s.negate else ''}{s.reg.text(alloc)}{_swizzle_text(sw)}"


def _text(cg: Any) -> Generated:
    rule = "ps20" if cg.rules.swizzles == "ps20" else "any"
    alloc = _allocate(cg.instrs)
    lines: list[str] = [cg.target.name]
    locs: list[Location] = [UNKNOWN_LOCATION]
    for reg in sorted(cg.defs):
        vals = [0.0 if v is None else v for v in cg.defs[reg]]
        lines.append(f"def c{reg}, " + ", ".join(_num(v) for v in vals))
        locs.append(UNKNOWN_LOCATION)
    used_i = {s.reg.index for ins in cg.instrs if ins.opcode in ("rep", "loop") for s in ins.srcs
              if s.reg.kind == "i"}
    int_defs = getattr(cg.ctx, "int_defs", {})      # a [loop] over literal bounds (loops.py)
    for reg in sorted(k for k in int_defs if k in used_i):
        lines.append(f"defi i{reg}, " + ", ".join(str(int(v)) for v in int_defs[reg]))
        locs.append(UNKNOWN_LOCATION)
    used_inputs: dict[str, None] = {}
    samplers: dict[str, int] = dict(cg.sampler_regs)
    for ins in cg.instrs:
        for s in ins.srcs:
            if s.reg.kind in ("v", "t"):
                used_inputs.setdefault(f"{s.reg.kind}{s.reg.index}")
            elif s.reg.kind in ("vPos", "vFace"):    # ps_3_0's misc inputs, unindexed
                used_inputs.setdefault(s.reg.kind)
        if ins.sampler is not None and ins.sampler not in samplers:
            taken = set(samplers.values())
            k = 0
            while k in taken:
                k += 1
            samplers[ins.sampler] = k
    for name in sorted(used_inputs, key=lambda n: (n[0], int(n[1:]) if n[1:].isdigit() else -1)):
        lines.append(cg.inputs.get(name, f"dcl {name}"))
        locs.append(UNKNOWN_LOCATION)
    for dcl in getattr(cg, "output_dcls", []):
        lines.append(dcl)
        locs.append(UNKNOWN_LOCATION)
    kinds = cg.ctx.samplers_used
    for name, k in sorted(samplers.items(), key=lambda kv: kv[1]):
        if any(i.sampler == name for i in cg.instrs):
            lines.append(f"dcl_{_SAMPLER_DCL.get(kinds.get(name, '2d'), '2d')} s{k}")
            locs.append(UNKNOWN_LOCATION)
    for ins in cg.instrs:
        if _no_op(ins, alloc):
            continue
        op = ins.opcode + ("_sat" if ins.saturate else "")
        if ins.dst is None:                     # rep i#, if_lt a, b, endrep ...
            srcs = [_src_text(s, alloc, rule, ins) for s in ins.srcs]
            lines.append(ins.opcode + (" " + ", ".join(srcs) if srcs else ""))
            locs.append(ins.location)
            continue
        if ins.opcode == "texkill":
            lines.append(f"texkill {ins.dst.text(alloc)}")  # type: ignore[union-attr]
            locs.append(ins.location)
            continue
        dst = ins.dst.text(alloc) if ins.dst is not None else ""
        mask = "" if tuple(ins.mask) == (0, 1, 2, 3) else "." + "".join(COMPONENTS[i] for i in ins.mask)
        if ins.dst is not None and ins.dst.kind == "oPos" and False:
            mask = ""
        srcs = [_src_text(s, alloc, rule, ins) for s in ins.srcs]
        if ins.sampler is not None:
            srcs.insert(1, f"s{samplers[ins.sampler]}")
        lines.append(f"{op} {dst}{mask}, " + ", ".join(srcs))
        locs.append(ins.location)
    used_c = {name: (start, cg.register_sizes.get(name, 1)) for name, start in cg.const_regs.items()}
    ints = {name: k for name, k in getattr(cg.ctx, "int_registers", {}).items() if k in used_i}
    used_b = {s.reg.index for ins in cg.instrs if ins.opcode == "if" for s in ins.srcs
              if s.reg.kind == "b"}
    bools = {name: k for name, k in getattr(cg.ctx, "bool_registers", {}).items() if k in used_b}
    return Generated(lines, locs, used_c, {n: k for n, k in samplers.items()
                                           if any(i.sampler == n for i in cg.instrs)},
                     {r: tuple(0.0 if v is None else v for v in vals) for r, vals in cg.defs.items()},
                     ints, bools)


def _no_op(ins: Instr, alloc: dict[int, int]) -> bool:
    """`mov r0.xyz, r0`: a copy the register allocation made into the register it reads."""
    if ins.opcode != "mov" or ins.saturate or ins.dst is None or ins.dst.kind != "vr":
        return False
    s = ins.srcs[0]
    if s.reg.kind != "vr" or s.negate or alloc[s.reg.index] != alloc[ins.dst.index]:  # type: ignore[index]
        return False
    need = _lanes_needed(ins, s)
    return all(need.get(l) == l for l in ins.mask)


def _num(v: float) -> str:
    if abs(v) < 1e7 and v == int(v):      # never inf or NaN here (compiler._finite_constants)
        return f"{int(v)}"
    return f"{v:.9g}"
