"""The sixteen shaders fxc 9.29 compiled for Wine's D3DX9 constant-table tests, with their HLSL
beside them (tests/data/d3dbc/wine/d3dx9_36_shader_excerpt.c, from Debian's wine 8.0 source:
tests/data/d3dbc/MANIFEST.md): each reads, passes the assembly checks and names its target and
compiler; it writes back byte for byte (default values, shared names and types as fxc laid
them out); our compile of its HLSL either gives a constant table with the same constants at
fxc's register set, index and count, but those KNOWN_LAYOUT_DIFFERENCES names, or fails with
the gap named in COMPILE_GAPS (so both are kept current); and fxc's vertex shaders and ours,
evaluated side by side, compute the same position."""
from __future__ import annotations

import hashlib
import re

import numpy as np
import pytest

import effects
from effects.shaders.asm import check
from effects.shaders.d3dbc import read_header, read_shader, write_program
from effects.shaders.d3dbc.ctab import (MATRIX_COLUMNS, MATRIX_ROWS, OBJECT, SCALAR, STRUCT,
                                        VECTOR, TypeInfo, default_size)
from effects.shaders.d3dbc.writer import constant_table
from effects.shaders.hlsl import compile_state
from tests.paths import TESTS

DATA = TESTS / "data" / "d3dbc"
EXCERPT = DATA / "wine" / "d3dx9_36_shader_excerpt.c"
# "/*\n * fxc.exe /Tvs_3_0\n */", the HLSL in #if 0, then its array
_PAIR = re.compile(r"/\*\n \* fxc\.exe /T(\w+)\n \*/\n#if 0\n((?:(?!#if|#endif).)*)#endif\n"
                   r"\s*static const DWORD (\w+)\[\] =\n\{[^}]*\};", re.S)


def _fourcc() -> dict[str, str]:
    """The file's `#define X MAKEFOURCC('C','T','A','B')` macros as numbers, for the arrays."""
    out = {}
    for name, chars in re.findall(r"#define (\w+) MAKEFOURCC\(([^)]*)\)", EXCERPT.read_text()):
        codes = [ord(c) for c in re.findall(r"'(.)'", chars)]
        out[name] = hex(sum(c << (8 * k) for k, c in enumerate(codes)))
    return out


def _pairs() -> list[tuple[str, str, str, bytes]]:
    """(array name, target, HLSL, bytecode) of every shader in the excerpt, in file order."""
    text = EXCERPT.read_text()
    macros = _fourcc()
    out = []
    for m in _PAIR.finditer(text):
        target, hlsl, name = m.groups()
        array = re.sub(r"\b\w+\b", lambda w: macros.get(w.group(), w.group()), m.group())
        (found, data), = read_header(array[array.index("static const DWORD"):])
        out.append((name, target, hlsl, data))
    return out


PAIRS = _pairs()
IDS = [p[0] for p in PAIRS]
# Our HLSL compiler's gaps these shaders show (fxc compiled every one): the array, and the
# start of the error we give today. None left: the anonymous structs and the loops counted by
# a uniform int's component (`rep i2` for `i < vn.z`) compile.
COMPILE_GAPS: dict[str, str] = {}


def test_the_excerpt_holds_sixteen_shaders_with_the_manifests_hashes():
    assert len(PAIRS) == 16 and len(set(IDS)) == 16
    row = next(line for line in (DATA / "MANIFEST.md").read_text().splitlines()
               if line.startswith("| `wine/d3dx9_36_shader_excerpt.c`"))
    cells = row.split("|")
    assert re.findall(r"`([0-9a-f]{64})`", cells[-3]) == [
        hashlib.sha256(EXCERPT.read_bytes()).hexdigest()]
    assert re.findall(r"`([0-9a-f]{64})`", cells[-2]) == [
        hashlib.sha256(data).hexdigest() for *_, data in PAIRS]


@pytest.mark.parametrize("name,target,hlsl,data", PAIRS, ids=IDS)
def test_fxcs_bytecode_reads_and_checks(name, target, hlsl, data):
    binary = read_shader(data, name)
    assert binary.table.creator == "Microsoft (R) HLSL Shader Compiler 9.29.952.3111"
    assert binary.program.name == binary.table.target == target
    assert check(binary.program) == []


@pytest.mark.parametrize("register_set,type_,size", [
    ("bool", TypeInfo(SCALAR, 1), 4),                                   # bool b: one DWORD
    ("bool", TypeInfo(MATRIX_ROWS, 1, 3, 2), 24),                       # bool3x2: six
    ("float4", TypeInfo(MATRIX_COLUMNS, 3, 4, 4), 64),                  # float4x4 held in c0-c1
    ("int4", TypeInfo(MATRIX_ROWS, 2, 3, 2, 2), 96),                    # row_major int3x2[2]
    ("float4", TypeInfo(STRUCT, 0, 1, 4, 1, (("f", TypeInfo(SCALAR, 3)),
                                           ("v", TypeInfo(VECTOR, 3, 1, 3)))), 32),
    ("sampler", TypeInfo(OBJECT, 12), 0)])
def test_a_default_value_spans_the_whole_types_registers(register_set, type_, size):
    assert default_size(register_set, type_) == size


@pytest.mark.parametrize("name,target,hlsl,data", PAIRS, ids=IDS)
def test_fxcs_bytecode_writes_back_byte_for_byte(name, target, hlsl, data):
    binary = read_shader(data, name)
    assert write_program(binary.program, binary.table) == data


def _ours(hlsl: str, target: str):
    state = "PixelShader" if target.startswith("ps") else "VertexShader"
    effect = effects.load_effect(f"{hlsl}\ntechnique T {{ pass P {{ {state} = compile {target} "
                                 "main(); } }")
    return compile_state(effect, effect.techniques[0].passes[0].state(state).value)


# Where our constant table still differs from fxc's: (array, constant) -> (fxc's (register
# set, index, count), ours, why). Every other constant of the sixteen has fxc's register set,
# index and count (float ones by constant_layout.py's rules, int and bool by components.py).
KNOWN_LAYOUT_DIFFERENCES: dict[tuple[str, str], tuple[tuple, tuple, str]] = {
    # five samplers of one register each: fxc gave s1D s0, s2D s1, scube s2, s3D s3, s s4,
    # neither their declaration order (s, s1D, s2D, s3D, scube: ours, the order fxc 9.29 gave
    # the samplers of its effect in tests/data/fxo/wine/test_effect_preshader_effect_blob.fxo
    # and d3dcompiler gave in Wine's test_constant_table and vkd3d's combined-samplers test),
    # nor their first use (s1D, s3D, s, s2D, scube), nor their names' order; typed before
    # untyped and then 2D, cube, volume would fit this shader but not d3dcompiler's (its
    # untyped m, n, o before the sampler2D s), so no rule found fits every piece of evidence
    ("get_shader_samplers_blob", "s"): (("sampler", 4, 1), ("sampler", 0, 1), "sampler order"),
    ("get_shader_samplers_blob", "s1D"): (("sampler", 0, 1), ("sampler", 1, 1), "sampler order"),
    ("get_shader_samplers_blob", "s2D"): (("sampler", 1, 1), ("sampler", 2, 1), "sampler order"),
    ("get_shader_samplers_blob", "scube"): (("sampler", 2, 1), ("sampler", 4, 1),
                                            "sampler order"),
}


def _layout(table) -> dict[str, tuple[str, int, int]]:
    return {c.name: (c.register_set, c.register_index, c.register_count) for c in table.constants}


@pytest.mark.parametrize("name,target,hlsl,data", PAIRS, ids=IDS)
def test_our_compile_gives_fxcs_constants_or_the_named_gap(name, target, hlsl, data):
    if name in COMPILE_GAPS:
        with pytest.raises(effects.EffectError, match=COMPILE_GAPS[name]):
            _ours(hlsl, target)
        return
    ours = _ours(hlsl, target)
    theirs = _layout(read_shader(data, name).table)
    mine = _layout(constant_table(ours.program, ours))
    assert set(mine) == set(theirs)
    # every constant at fxc's register set, index and count, but those named (each of which
    # still differs as it says)
    differ = {(name, c): (theirs[c], mine[c]) for c in theirs if theirs[c] != mine[c]}
    known = {k: v[:2] for k, v in KNOWN_LAYOUT_DIFFERENCES.items() if k[0] == name}
    assert differ == known


# The ps_3_0 shader (get_shader_samplers_blob) drawn: fxc's code and our compile, each with its
# own constant table's sampler registers bound to a texture per sampler (a different image for
# each 2D one, so that two swapped samplers show), on a sphere whose third texture coordinate
# runs with x (for the volume and cube lookups).
IMAGES = ["stones_base.png", "marble_vein.png", "earth_base.png"]


def _textures_of(kinds: dict[str, str]) -> dict[str, str]:
    """Sampler name -> texture parameter: T0, T1, ... (2D images) in declaration order, TV
    for a volume, TC for a cube."""
    flat = [n for n, k in kinds.items() if k not in ("sampler3D", "samplerCUBE")]
    return {n: "TV" if k == "sampler3D" else "TC" if k == "samplerCUBE" else f"T{flat.index(n)}"
            for n, k in kinds.items()}
VS3 = """asm { vs_3_0 dcl_position v0 dcl_texcoord v1 dcl_position o0 dcl_texcoord o1
    m4x4 o0, v0, c0 mov o1.xy, v1 mad o1.z, v0.x, c4.x, c4.x }"""
INIT = [-3.2, -3.2, -3.2, 1]       # the six texels' sum, brought into range


def _sampler_kinds(hlsl: str) -> dict[str, str]:
    return dict((n, k) for k, n in re.findall(r"^(sampler\w*)\s+(\w+);", hlsl, re.M))


@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_fxcs_ps_3_0_and_ours_draw_the_same_sampler_picture(backend):
    from effects.host.runtime import render_frame
    from effects.shaders.asm.text import program_text
    from tests.paths import ROOT

    (name, target, hlsl, data), = [p for p in PAIRS if p[1].startswith("ps")]
    kinds = _sampler_kinds(hlsl)
    assert len(kinds) == 5
    texture_of = _textures_of(kinds)
    images = "\n".join(f'texture T{k} < string ResourceName = "{ROOT / "fxfiles" / "textures" / i}"; >;'
                       for k, i in enumerate(IMAGES))
    head = f"""float4x4 WorldViewProjection : WORLDVIEWPROJECTION;
{images}
texture3D TV < string Procedural = "noise3d:32"; >;
textureCUBE TC < string Procedural = "sky_cube:64"; >;
{hlsl}
"""
    probe = effects.load_effect(head + f"technique T {{ pass P {{ PixelShader = compile {target} "
                                "main(); } }")
    ours = compile_state(probe, probe.techniques[0].passes[0].state("PixelShader").value)
    theirs = read_shader(data, name)
    fxc_samplers = {c.name: c.register_index for c in theirs.table.constants
                    if c.register_set == "sampler"}
    assert set(fxc_samplers) == set(ours.samplers) == set(kinds)

    def pass_(ps: str, samplers: dict[str, int], extra: str = "") -> str:
        bound = " ".join(f"Texture[{r}] = <{texture_of[n]}>;" for n, r in samplers.items())
        return f"""pass P {{ VertexShaderConstantF[0] = <WorldViewProjection>;
            VertexShaderConstantF[4] = {{0.5, 0.5, 0.5, 0.5}}; VertexShader = {VS3};
            {bound} {extra} PixelShader = {ps}; }}"""
    init_at = next(c.register_index for c in theirs.table.constants if c.name == "init")
    fxc = "asm { " + program_text(theirs.program) + " }"
    effect = effects.load_effect(head + f"""
technique Fxc {{ {pass_(fxc, fxc_samplers, f"PixelShaderConstantF[{init_at}] = <init>;")} }}
technique Ours {{ {pass_(f"compile {target} main()", ours.samplers)} }}""")
    frames = [render_frame(effect, "geforce6800", technique=t, size=(64, 64), backend=backend,
                           params={"init": INIT}) for t in ("Fxc", "Ours")]
    fxc_image, our_image = (f.image.astype(int) for f in frames)
    assert not frames[0].warnings and not frames[1].warnings
    drawn = fxc_image[..., 3] > 0
    # a lit sphere, most of it between black and white (the sum of six texels minus 3.2)
    assert drawn.mean() > 0.4
    assert ((fxc_image[..., 0] > 0) & (fxc_image[..., 0] < 255))[drawn].mean() > 0.5
    assert np.abs(fxc_image - our_image).max() <= 1


# The vertex shaders run side by side: fxc's bytecode (its constant table binding the
# parameters: float4, int4 and bool registers, set by the pass as D3DX sets them) and our
# compile of its HLSL, each lowered for a card and evaluated on one vertex by the NumPy
# evaluator. Their POSITION has w = 0 (the programs write x and y only), so nothing of them
# can be drawn; the output is compared instead. Hand values for two: registerset_blob_scalar
# runs `rep i0` n = 8 times of pos.z * f * nf = 0.75 * 5.1 * 11; registerset_blob_vector
# takes `if b2` (vb.z) and `rep i2` vn.z = 9 times of pos.z * vf.z * vnf.z = 0.75 * 5.3 * 62.
HAND = {"registerset_blob_scalar": (8 * 0.75 * 5.1 * 11, 0, 0, 0),
        "registerset_blob_vector": (9 * 0.75 * 5.3 * 62, 0, 0, 0)}
VERTEX = (0.5, 0.25, 0.75, 1.0)


def _position(effect, technique: int):
    from backends.reference.evaluate import evaluate
    from effects.d3d9.caps import load_profile
    from effects.lower.passes import lower_pass
    pp = lower_pass(effect, effect.techniques[technique], 0, load_profile("geforce6800"))
    inputs = pp.uniform_values()
    for item in pp.vertex.inputs:
        if item.kind == "varying":
            inputs[item.name] = np.array([VERTEX], np.float32)
    return evaluate(pp.vertex, inputs, count=1).outputs["position"][0]


@pytest.mark.parametrize("name,target,hlsl,data", [p for p in PAIRS if p[1].startswith("vs")],
                         ids=[p[0] for p in PAIRS if p[1].startswith("vs")])
def test_fxcs_vertex_shader_and_ours_compute_the_same_position(name, target, hlsl, data):
    import dataclasses
    from effects.model import BytecodeShader
    effect = effects.load_effect(
        f"{hlsl}\ntechnique Ours {{ pass P {{ VertexShader = compile {target} main(); }} }}\n"
        "technique Fxc { pass P { VertexShader = NULL; } }")
    states = effect.techniques[1].passes[0].states
    states[0] = dataclasses.replace(states[0], value=BytecodeShader(
        "vertex", target, "", data=data, location=states[0].location))
    ours, fxc = _position(effect, 0), _position(effect, 1)
    assert np.allclose(ours, fxc, rtol=1e-5, atol=1e-4), (ours, fxc)
    if name in HAND:
        assert np.allclose(fxc, HAND[name], rtol=1e-5), (fxc, HAND[name])
