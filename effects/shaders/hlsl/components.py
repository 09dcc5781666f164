"""Integer and boolean registers of a uniform, one per component, as fxc gave them.

fxc puts an int parameter that counts a `rep` / `loop`, and a bool parameter an `if b#` tests,
in the int4 or bool register set with one register per scalar component, in declaration order
(Wine's d3dx9 constant-table test shaders, compiled by fxc 9.29, show it): `int3 vn` takes
i0-i2 and `for (i = 0; i < vn.z; i++)` is `rep i2`; a row_major or column_major `int3x2 cn`
takes six, `cn._31` is the fifth (i4, row by row whatever the packing); `int3x2 ran[2]`'s
`ran[1]._21` is i8; a struct's members follow one another (`struct {int n; int3 vn;} sn`:
`sn.vn.z` is i3); `bool3 vb`'s `vb.z` is `if b2`. The register table counts registers up to the
last the shader reads (so `ran` shows 9 of its 12), and the effect sets each from its
component: (value, 0, 1, 0) for an i#, as D3DX's constant table does.

So a loop bound or an `if` condition that is one component of such a parameter, read by
constant indices, members and swizzles (`an[1]`, `rn._31`, `sab[1].vb.z`), names a register
here: `uniform_component` finds (parameter, component), `component_register` gives the
parameter its registers (all of its components, so a later one cannot overlap them).
"""
from __future__ import annotations

from typing import Any

import lark

from effects.shaders.hlsl.constant_layout import first_fit, free_run
from effects.shaders.hlsl.context import explicit_register
from effects.shaders.hlsl.types import HType, register_count

Slot = tuple[int, int, str]          # (float4 register offset, lane, scalar base type)


def component_slots(t: HType) -> list[Slot]:
    """Where each scalar component of a uniform of type `t` sits in its float4 registers
    (the layout `uniform_value` reads), in declaration order: a matrix row by row."""
    if t.kind in ("scalar", "vector"):
        return [(0, k, t.base) for k in range(t.size)]
    if t.kind == "matrix":
        return [((r, c) if t.row_major else (c, r)) + (t.base,)
                for r in range(t.rows) for c in range(t.cols)]
    out: list[Slot] = []
    if t.kind == "array" and t.element is not None:
        step = register_count(t.element)
        for k in range(t.length):
            out += [(reg + k * step, lane, base) for reg, lane, base in component_slots(t.element)]
    elif t.kind == "struct":
        at = 0
        for _, ft, _ in t.fields:
            out += [(reg + at, lane, base) for reg, lane, base in component_slots(ft)]
            at += register_count(ft)
    return out


def _literal_path(tree: Any) -> str | None:
    """The variable a chain of members, swizzles and literal indices starts from (`an[1]`,
    `sab[1].vb.z`), else None: only such a chain is read again without side effects."""
    while isinstance(tree, lark.Tree) and tree.data in ("member", "index", "paren"):
        if tree.data == "index" and not (isinstance(tree.children[1], lark.Tree)
                                         and tree.children[1].data == "int_lit"):
            return None
        tree = tree.children[0]
    if isinstance(tree, lark.Tree) and tree.data == "var":
        return str(tree.children[0])
    return None


def uniform_component(ev: Any, tree: Any, bases: tuple[str, ...]) -> tuple[str, int] | None:
    """(parameter, component index) when `tree`, a chain of members, swizzles and literal
    indices, reads one scalar component of a uniform (not static, not const) global whose
    scalar type is one of `bases`; else None."""
    # a local or an entry parameter read so holds what was put in it: `uniform bool2x3 mb`
    # given `mb2x3row` by the compile (Wine's preshader effect: fxc's `if b4` for mb[1][1])
    if _literal_path(tree) is None or ev.ctx.host_values:
        return None
    value = ev.expr(tree)
    if value.type.size != 1 or len(value.comps) != 1 or value.type.base not in bases:
        return None
    op = value.comps[0]
    if op.node.op != "uniform" or op.negate:
        return None
    name = op.node.key[0]
    p = ev.ctx.effect.parameter(name)
    if p is None or "static" in p.storage or "const" in p.storage:
        return None
    t = ev.ctx.uniforms_used.get(name)
    if t is None:
        return None
    at = (op.node.key[1], op.swizzle[0])
    for k, (reg, lane, base) in enumerate(component_slots(t)):
        if (reg, lane) == at:
            return (name, k) if base in bases else None
    return None


def taken_registers(ctx: Any, kind: str) -> set[int]:
    """The i# or b# given out so far (each parameter's whole run; i# also the `defi`s)."""
    regs = ctx.int_registers if kind == "i" else ctx.bool_registers
    taken: set[int] = set(ctx.int_defs) if kind == "i" else set()
    for name, first in regs.items():
        taken.update(range(first, first + ctx.component_counts.get(name, 1)))
    return taken


def component_register(ctx: Any, name: str, kind: str) -> int:
    """The first i# (kind 'i') or b# ('b') of parameter `name`: its register() binding, else
    the first run of free registers that holds all of its components."""
    regs = ctx.int_registers if kind == "i" else ctx.bool_registers
    if name not in regs:
        t = ctx.uniforms_used.get(name)
        size = len(component_slots(t)) if t is not None else 1
        bound = explicit_register(ctx, name, kind)
        if bound is None:
            bound = free_run(taken_registers(ctx, kind), size)
        regs[name] = bound
        ctx.component_counts[name] = size
    return regs[name]


def used_counts(registers: dict[str, int], counts: dict[str, int], used: set[int]
                ) -> tuple[dict[str, int], dict[str, int]]:
    """The parameters whose registers the code reads, first register and count: up to the
    last one read (fxc's table shows `ran` 9 registers of 12 where i8 is the last)."""
    firsts: dict[str, int] = {}
    sizes: dict[str, int] = {}
    for name, first in registers.items():
        read = [r for r in used if first <= r < first + counts.get(name, 1)]
        if read:
            firsts[name], sizes[name] = first, max(read) - first + 1
    return firsts, sizes


def laid_out(registers: dict[str, int], counts: dict[str, int], used: set[int],
             fixed: set[str], declared: dict[str, int], taken: set[int]
             ) -> tuple[dict[str, int], dict[str, int], dict[int, int]]:
    """The int or bool parameters the code reads laid out again as fxc laid out the float
    constants (constant_layout.py), now that the reads are known: each holds its registers up
    to the last one read, the largest first, ties in declaration order (`declared`), each at
    the first free run; a register(i#/b#) binding (`fixed`) stays, holding all of its
    components, and `taken` (the `defi`s) are left alone. Wine's preshader effect shows it
    (tests/data/fxo/wine/test_effect_preshader_effect_blob.fxo: fxc's ps_3_0 reads `if b4`,
    mb2x3row[1][1], then `if b5`, mb2x3column[0][0]: b0 count 5 and b5 count 1, where holding
    all six of mb2x3row's would put mb2x3column at b6). Returns each parameter's first
    register and count, and old register -> new for those that move."""
    taken = set(taken)
    firsts: dict[str, int] = {}
    sizes: dict[str, int] = {}
    for name, first in registers.items():
        read = [r - first for r in used if first <= r < first + counts.get(name, 1)]
        if name in fixed:
            firsts[name], sizes[name] = first, counts.get(name, 1)
            taken.update(range(first, first + sizes[name]))
        elif read:
            sizes[name] = max(read) + 1
    moving = [n for n in sizes if n not in firsts]
    firsts.update(first_fit(moving, sizes, taken, declared))
    remap = {registers[n] + k: firsts[n] + k for n in moving for k in range(sizes[n])}
    return firsts, sizes, remap


__all__ = ["component_register", "component_slots", "taken_registers", "uniform_component",
           "laid_out", "used_counts"]
