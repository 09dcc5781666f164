"""The one register allocator of the HLSL compiler's code generators (codegen.py for vs_1_1 -
ps_3_0, codegen_ps1.py for ps_1_x): virtual temporaries (kind 'vr', records.py) onto r0, r1 ...

A temporary lives from the first instruction that names it to the last. Pinned temporaries
(ps_1_x's result in r0, a ps_1_4 texld in its stage's register, a cnd condition in r0.a) take
their register first; the others go in order of first use to the lowest register no value
living at the same time holds (linear scan, as fxc reuses temporaries). Two live ranges that
meet at one instruction share a register when `touch` says that instruction reads its sources
before it writes (`add r0, r0, c0`). A temporary set before a `rep`/`loop` and read inside is
read again by the next iteration, so it lives to the `endrep`/`endloop`.
"""
from __future__ import annotations

from typing import Any, Callable

# single-slot instructions that read every source before writing: a register whose last
# read is one of these may be its destination (`add r0, r0, c0`, as fxc reuses temporaries).
# Not the macros (pow, nrm, crs, lrp, sincos, m#x#), whose pages forbid or do not promise it,
# nor vs_1_1's frc, a macro there.
ALIASES = frozenset({"mov", "add", "mul", "mad", "min", "max", "slt", "sge", "cmp", "dp3",
                     "dp4", "dp2add", "rcp", "rsq", "exp", "log", "abs", "texld", "texldp",
                     "texldb", "texldl", "texldd", "dsx", "dsy"})


class RegisterConflict(Exception):
    """Two temporaries pinned to one register are live at once."""

    def __init__(self, vr: int) -> None:
        super().__init__(vr)
        self.vr = vr


class OutOfRegisters(Exception):
    """The version's temporaries are all taken where temporary `vr` starts."""

    def __init__(self, vr: int) -> None:
        super().__init__(vr)
        self.vr = vr


def dies_into_destination(ins: Any, vr: int) -> bool:
    """A register whose last read is `ins` may be the destination `vr` that `ins` writes."""
    return ins.opcode in ALIASES and ins.dst is not None and ins.dst.kind == "vr" \
        and ins.dst.index == vr


def live_ranges(instrs: list[Any]) -> tuple[dict[int, int], dict[int, int]]:
    """Each temporary's first and last instruction (by position), a loop's carried
    temporaries extended to its end (innermost loops first, so an outer one extends further)."""
    first: dict[int, int] = {}
    last: dict[int, int] = {}
    for i, ins in enumerate(instrs):
        d = ins.dst
        if d is not None and d.kind == "vr":
            first.setdefault(d.index, i)
            last[d.index] = i
        for r in ins.srcs:
            if r.kind == "vr":
                first.setdefault(r.index, i)
                last[r.index] = i
    loops, stack = [], []
    for i, ins in enumerate(instrs):
        if ins.opcode in ("rep", "loop"):
            stack.append(i)
        elif ins.opcode in ("endrep", "endloop"):
            loops.append((stack.pop(), i))
    for start, end in sorted(loops, key=lambda r: r[1] - r[0]):
        for vr in first:
            if first[vr] < start <= last[vr] <= end:
                last[vr] = end
    return first, last


def allocate(instrs: list[Any], touch: Callable[[Any, int], bool] | None = None,
             pinned: dict[int, int] | None = None, count: int | None = None) -> dict[int, int]:
    """Temporary -> register. `touch(ins, vr)`: ranges meeting at `ins`, where `vr` starts,
    may share a register. `pinned`: temporaries whose register is fixed (RegisterConflict
    when two of them overlap). `count`: the version's temporaries (OutOfRegisters past it).
    Without `touch`, `dies_into_destination`."""
    touch = touch or dies_into_destination
    pinned = pinned or {}
    first, last = live_ranges(instrs)

    def apart(a: int, b: int) -> bool:
        """Ranges a and b can share a register."""
        return last[a] < first[b] or last[b] < first[a] \
            or (last[a] == first[b] and touch(instrs[first[b]], b)) \
            or (last[b] == first[a] and touch(instrs[first[a]], a))

    alloc: dict[int, int] = {}
    held: dict[int, list[int]] = {}      # register -> the pinned temporaries in it
    tail: dict[int, int] = {}            # register -> the last unpinned temporary given it
    for vr in sorted(pinned, key=lambda v: (first.get(v, -1), v)):
        if vr not in first:
            continue
        phys = pinned[vr]
        if any(not apart(vr, o) for o in held.get(phys, ())):
            raise RegisterConflict(vr)
        held.setdefault(phys, []).append(vr)
        alloc[vr] = phys
    # in order of first use, an unpinned range can meet only the last unpinned one in each
    # register (every earlier one ended before that one started)
    for vr in sorted((v for v in first if v not in pinned), key=lambda v: (first[v], v)):
        phys = 0
        while (phys in tail and not apart(tail[phys], vr)) or \
                any(not apart(o, vr) for o in held.get(phys, ())):
            phys += 1
        if count is not None and phys >= count:
            raise OutOfRegisters(vr)
        alloc[vr] = phys
        tail[phys] = vr
    return alloc
