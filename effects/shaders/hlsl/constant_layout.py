"""fxc's layout of the float constants a shader reads (c#), as its output shows it.

Three rules, each seen in fxc 9.29's bytecode for Wine's D3DX9 tests
(tests/data/d3dbc/wine/d3dx9_36_shader_excerpt.c) and in the register tables vkd3d-shader's
tests record from native d3dcompiler (its sm1-const-allocation test):

- a uniform holds the registers up to the last one the code reads, not its whole type
  (`float4x4 cf` read only at `cf._22` is c0-c1: registerset_blob_matrix_column_clamp;
  `float3 vaf[10]` read at `vaf[8]` is c0-c8: registerset_blob_bigvec); an array read by a
  run-time index holds all of it;
- the uniforms are placed the largest first, those of one size in declaration order (in
  test_get_shader_constant_variables_blob: `p` 18 registers at c0, then 6, 5, 4, 4, 2, 2, 2,
  2, 1, 1, 1, the fours and twos and ones in the order the file declares them);
- each goes to the first run of free registers it fits (a `register(c#)` binding holds its
  whole type's registers, read or not, and a smaller uniform may fill a gap before it).

Literal constants (`def`) take the registers after them (codegen.CodeGen.const_src).
"""
from __future__ import annotations

from typing import Any, Callable, Iterable

from effects.shaders.hlsl.dag import Node

UNIFORM_READS = ("uniform", "uniform_rel", "uniform_al")


def used_sizes(nodes: Iterable[Node], full_size: Callable[[str], int]) -> dict[str, int]:
    """Uniform -> the registers it holds: up to the last one read, or its whole type's
    (`full_size`) where a run-time index (a0 or aL) reads it. In the order of first read."""
    used: dict[str, int] = {}
    for n in nodes:
        if n.op not in UNIFORM_READS:
            continue
        name, offset = n.key
        # a relative read's offset is the indexed array's first register: which element it
        # reads is known only when it runs
        last = full_size(name) if n.op != "uniform" else offset + 1
        used[name] = max(used.get(name, 0), last)
    return used


def free_run(taken: set[int], size: int, start: int = 0) -> int:
    """The first register from `start` at which `size` registers in a row are not `taken`."""
    first = start
    while any(first + i in taken for i in range(size)):
        first += 1
    return first


def overlap(spans: Iterable[tuple[str, int, int]]) -> tuple[str, str, int] | None:
    """The first register two of `spans` (name, first register, count; in fxc's order: the
    file's) both hold, as (the earlier's name, the later's, the register), or None. fxc
    refused two variables the code reads whose `register()` bindings overlap in the registers
    they use (X4500, every target)."""
    owner: dict[int, str] = {}
    for name, first, size in spans:
        for r in range(first, first + size):
            if r in owner:
                return owner[r], name, r
            owner[r] = name
    return None


def declaration_order(effect: Any) -> dict[str, int]:
    """Each global's position in the file: the tie-break of `first_fit`."""
    return {p.name: k for k, p in enumerate(effect.parameters)}


def first_fit(names: list[str], sizes: dict[str, int], taken: set[int],
              declared: dict[str, int]) -> dict[str, int]:
    """The first register of each of `names`: the largest first (ties in declaration order,
    `declared`: a global's position in the file; others after them, in the order given),
    each at the lowest run of `sizes[name]` registers not in `taken` (which grows)."""
    order = sorted(range(len(names)),
                   key=lambda k: (-sizes[names[k]], declared.get(names[k], len(declared) + k)))
    out: dict[str, int] = {}
    for k in order:
        name, size = names[k], sizes[names[k]]
        first = free_run(taken, size)
        out[name] = first
        taken.update(range(first, first + size))
    return out
