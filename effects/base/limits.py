"""The resource policy for untrusted input: one named limit per thing an input can make us spend.

Effect files, includes, caps profiles, scenes, textures and meshes are data from strangers
(README "Untrusted effects"). Every door that reads them checks the amount it is about to
spend against a limit here *before* spending it, and a breach is a located `EffectError`
that names the limit and how to raise it. The defaults keep any one load or render of the
bundled kind well under 1 GiB of memory and a few seconds, and are far above what the bundled
effects, profiles and scenes use.

A host raises a limit with the environment (`EFFECTS_LIMIT_TEXTURE_TEXELS=67108864`, read
when a limit is looked up) or in code, `effects.base.limits.set_limit("texture_texels", N)`, or for
a block, `with effects.base.limits.raised(texture_texels=N): ...`.

Every limit bounds an amount of work or storage, never a time: the machine's load changes
how long a bounded input takes, not whether it is refused. The meter (`meter()`) keeps,
per limit, the largest amount measured against it in this process and the largest refused,
so a host or a test can see how much of each budget an input used.
"""
from __future__ import annotations

import os
import sys
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Iterator

from effects.base.errors import EffectError, Location


@dataclass(frozen=True)
class Limit:
    """One bound: its name, default value, unit and what it counts."""

    name: str
    default: int
    unit: str
    what: str


_MIB = 1 << 20

LIMITS: dict[str, Limit] = {limit.name: limit for limit in [
    # text the front end reads (the lexer holds ~100 bytes per character of a long string)
    Limit("source_bytes", 1 * _MIB, "bytes", "size of one effect file or effect text"),
    Limit("include_count", 256, "includes", "#include directives expanded in one load"),
    Limit("included_bytes", 1 * _MIB, "bytes", "text read through #include in one load"),
    Limit("literal_digits", 200, "digits",
          "digits of one integer literal (#if, asm, YAML, HLSL, register(c#))"),
    # YAML (caps profiles, scenes)
    Limit("yaml_bytes", 2 * _MIB, "bytes", "size of one caps profile or scene file"),
    Limit("yaml_depth", 64, "levels", "nesting of YAML lists and mappings"),
    Limit("inherit_depth", 16, "levels", "profiles in one `inherit` chain"),
    # textures: level 0 texels counting every cube face and volume slice
    Limit("texture_file_bytes", 256 * _MIB, "bytes", "size of one texture file"),
    Limit("texture_edge", 8192, "texels along an edge", "width, height or depth of one texture"),
    Limit("texture_texels", 4096 * 1024, "texels", "texels of one texture's top level"),
    Limit("effect_texels", 16 * 1024 * 1024, "texels", "texels of all textures one render binds"),
    # a generator evaluates noise or lighting per texel: about ten times a decoded file's cost
    Limit("procedural_texels", 128 * 1024, "texels", "texels of one procedural texture's top level"),
    # meshes
    Limit("mesh_file_bytes", 32 * _MIB, "bytes", "size of one .obj or .x file"),
    Limit("mesh_nesting", 64, "levels", "frames and data objects inside one another in a .x file"),
    Limit("mesh_vertices", 500_000, "vertices", "vertices of one mesh"),
    Limit("mesh_indices", 3_000_000, "indices", "indices of one mesh (3 per triangle)"),
    # compiled shaders (effects/shaders/d3dbc): a ps_3_0 of 32,768 slots is ~1 MiB of tokens
    Limit("bytecode_bytes", 4 * _MIB, "bytes", "size of one shader's bytecode"),
    Limit("effect_binary_bytes", 16 * _MIB, "bytes", "size of one fx_2_0 effect binary (.fxo)"),
    # shaders: nested rep / loop counts multiply (four nested 255s are 4e9 iterations)
    Limit("shader_loop_iterations", 65_536, "iterations",
          "body runs of the innermost of nested rep / loop blocks (the counts' product)"),
    # the HLSL compiler evaluates a function symbolically (inlining, unrolling): its work and
    # storage grow with what the text asks for, not with the text's size
    Limit("hlsl_nesting", 64, "levels",
          "HLSL blocks, ifs and loops inside one another, calls inside calls, and structs or "
          "arrays inside one another"),
    Limit("hlsl_components", 65_536, "components",
          "numbers one HLSL variable, parameter or type holds (a float4[16] holds 64)"),
    # ~20,000 steps a second on a busy 2-core machine: a runaway stops within a few seconds;
    # a 1,024-iteration loop takes ~16,000, the bundled and sample effects under 200
    Limit("hlsl_work", 50_000, "steps",
          "operations one HLSL compile or effect expression builds, copies or emits, one per "
          "node or component: unrolled iterations x inlined calls x components"),
    # render targets, per back end (the reference works in bands: 2048² peaks near 160 MiB)
    Limit("target_pixels_numpy", 2048 * 2048, "pixels", "render-target pixels on the numpy back end"),
    Limit("target_pixels_gl", 4096 * 4096, "pixels", "render-target pixels on the gl back end"),
    # DXSAS scripts: LoopByCount blocks nest and Pass= runs another pass's script, so the
    # commands one frame runs multiply (three nested 256-count loops are 16.7 M commands)
    Limit("script_commands", 65_536, "commands",
          "script commands one frame runs (each loop round and Pass= script counted)"),
    # each draw costs: 4,096 full-screen draws of an 8 x 8 frame took 15 s on the numpy back
    # end (the 2-core test VM, loaded)
    Limit("script_draws", 1024, "draws", "draws one frame's script makes"),
]}

_overrides: dict[str, int] = {}


@dataclass(frozen=True)
class Meter:
    """What the limits measured since `reset_meter()`: per limit, the largest amount one
    check measured (a texture's texels, a compile's hlsl_work steps so far, a frame's script
    commands), allowed or not, and the largest amount refused (over the limit in force)."""

    largest: dict[str, int]
    refused: dict[str, int]


_largest: dict[str, int] = {}
_refused: dict[str, int] = {}


def measure(name: str, amount: int) -> None:
    """Note `amount` of limit `name`, spent or asked for (the meter keeps the largest)."""
    if amount > _largest.get(name, -1):
        _largest[name] = amount


def meter() -> Meter:
    """A copy of the meter now."""
    return Meter(dict(_largest), dict(_refused))


def reset_meter() -> None:
    _largest.clear()
    _refused.clear()


def env_name(name: str) -> str:
    """The environment variable that raises limit `name`."""
    return f"EFFECTS_LIMIT_{name.upper()}"


def get(name: str) -> int:
    """The value of limit `name` now: set_limit's, else the environment's, else the default."""
    value = _value(name)
    if name == "literal_digits":   # Python itself converts no more (sys.set_int_max_str_digits)
        python = getattr(sys, "get_int_max_str_digits", lambda: 0)()
        value = min(value, python) if python else value
    return value


def _value(name: str) -> int:
    limit = LIMITS[name]
    if name in _overrides:
        return _overrides[name]
    text = os.environ.get(env_name(name))
    if text:
        try:
            return max(0, int(text.strip()[:30]))
        except ValueError:
            pass  # a malformed override leaves the default in force
    return limit.default


def set_limit(name: str, value: int | None) -> None:
    """Set limit `name` for this process (None: back to the environment or the default)."""
    if name not in LIMITS:
        raise KeyError(f"unknown limit {name!r} (known: {', '.join(LIMITS)})")
    if value is None:
        _overrides.pop(name, None)
    else:
        _overrides[name] = int(value)


@contextmanager
def raised(**values: int) -> Iterator[None]:
    """Limits changed for the duration of a `with` block."""
    old = {name: _overrides.get(name) for name in values}
    try:
        for name, value in values.items():
            set_limit(name, value)
        yield
    finally:
        for name, value in old.items():
            set_limit(name, value)


def message(name: str, amount: int, subject: str) -> str:
    """'SUBJECT has AMOUNT UNIT; the limit is N (limit NAME: raise it with ...)'."""
    limit = LIMITS[name]
    measure(name, amount)
    if amount > _refused.get(name, -1):   # every refusal is worded here
        _refused[name] = amount
    return (f"{subject} has {amount:,} {limit.unit}; the limit is {get(name):,} "
            f"(limit {name}: raise it with {env_name(name)}=N or "
            f"effects.base.limits.set_limit({name!r}, N))")


def check(name: str, amount: int, location: Location, subject: str,
          error: type[EffectError] = EffectError) -> None:
    """Raise `error` at `location` when `amount` is over limit `name`."""
    measure(name, amount)
    if amount > get(name):
        raise error(message(name, amount, subject), location)


def check_digits(digits: str, location: Location, error: type[EffectError] = EffectError) -> None:
    """An integer literal's digits against `literal_digits` (Python refuses over 4,300 itself)."""
    if len(digits) > get("literal_digits"):
        check("literal_digits", len(digits), location, "an integer literal", error)


def check_texture(width: int, height: int, layers: int, location: Location, subject: str,
                  error: type[EffectError] = EffectError) -> None:
    """A texture's top level (`layers` = 6 cube faces or the volume depth) against
    `texture_edge` and `texture_texels`, before anything is allocated for it."""
    edge = max(width, height, layers)
    measure("texture_edge", edge)
    if edge > get("texture_edge"):
        raise error(message("texture_edge", edge, f"{subject} ({width} x {height} x {layers})"), location)
    check("texture_texels", width * height * layers, location, f"{subject} ({width} x {height} x {layers})",
          error)
