"""Language constructs real effect files use (DirectX SDK samples, NVIDIA's shader library,
engines): each loads as fxc/D3DX reads it, and each misuse is a located error."""
from __future__ import annotations

import numpy as np
import pytest

from effects.d3d9.caps import load_profile
from effects.d3d9.device import pass_states
from effects.base.errors import EffectError, ParseError
from effects.api import load_effect
from effects.model import NullValue, ParamRef


def params(text: str):
    return {p.name: p for p in load_effect(text).parameters}


def test_several_declarators_in_one_declaration():
    p = params("""shared matrix W : WORLD, V : VIEW, P;
                  float a = 1, b < string UIName = "B"; > = 2, c;
                  texture t0, t1 < string ResourceName = "x.png"; >;""")
    assert [n for n in p] == ["W", "V", "P", "a", "b", "c", "t0", "t1"]
    assert p["W"].storage == ("shared",) and p["P"].storage == ("shared",)
    assert (p["W"].semantic, p["V"].semantic, p["P"].semantic) == ("WORLD", "VIEW", None)
    assert float(p["a"].value) == 1 and float(p["b"].value) == 2 and p["c"].value is None
    assert p["b"].annotation("UIName").value == "B"
    assert p["t1"].annotation("ResourceName").value == "x.png" and p["t0"].annotations == []


def test_a_semantic_and_a_register_together():
    p = params("float4x4 W : WORLD : register(c0); float4 K : register(c4);")
    assert p["W"].semantic == "WORLD" and p["K"].semantic == "register(c4)"


def test_typedef_and_template_types():
    p = params("""typedef float4 COLOR; typedef vector<float, 3> POS;
                  COLOR tint = {1, 0, 0, 1}; POS at = {1, 2, 3};
                  matrix<float, 4, 3> M43; vector<half,2> h = {1, 2}; matrix<float,2,2> I = {1,0,0,1};""")
    assert p["tint"].value.tolist() == [1, 0, 0, 1] and p["at"].value.shape == (3,)
    assert (p["M43"].type.rows, p["M43"].type.cols) == (4, 3)
    assert p["h"].type.base == "half" and p["I"].value.shape == (2, 2)


def test_arrays_sized_by_a_constant_a_macro_or_the_initializer():
    p = params("""#define NUM 3
                  static const int N = 2;
                  float4 lights[N]; float w[NUM] = {1, 2, 3};
                  float k[] = {1, 2, 3, 4,}; float3 v[] = {{1, 2, 3}, {4, 5, 6},};
                  float2 u[] = {1, 2, 3, 4};""")
    assert p["lights"].array == (2,) and p["w"].array == (3,)
    assert p["k"].array == (4,) and p["k"].value.tolist() == [1, 2, 3, 4]
    assert p["v"].array == (2,) and p["v"].value.shape == (2, 3)
    assert p["u"].array == (2,)


def test_annotation_arrays_parentheses_and_adjacent_strings():
    p = params("""#define FMT "A8R8G8B8"
        texture T < string Format = (FMT); float2 Range[2] = {0, 1, 2, 3};
                    string Script = "Draw=Buffer;" "ScriptExternal=;"; float S = (0.5); >;""")
    t = p["T"]
    assert t.annotation("Format").value == "A8R8G8B8"
    assert t.annotation("Range").value.tolist() == [[0, 1], [2, 3]]
    assert t.annotation("Script").value == "Draw=Buffer;ScriptExternal=;"
    assert float(t.annotation("S").value) == 0.5


def test_indexed_references_in_states_and_indexing_in_initializers():
    effect = load_effect("""
        float4 g_vLightPos[2] = {{1, 2, 3, 1}, {4, 5, 6, 1}};
        float4x4 world = {1,0,0,0, 0,1,0,0, 0,0,1,0, 7,8,9,1};
        float z = world[3][2];
        float4 row = world[3];
        technique T { pass P { LightPosition[0] = <g_vLightPos[1]>; LightEnable[0] = true; } }""")
    p = {q.name: q for q in effect.parameters}
    assert float(p["z"].value) == 9 and p["row"].value.tolist() == [7, 8, 9, 1]
    a = effect.techniques[0].passes[0].states[0]
    assert isinstance(a.value, ParamRef) and a.value.index == 1
    (_, state), = list(pass_states(effect, effect.techniques[0].passes))
    assert np.asarray(state.get("LightPosition", 0)).tolist() == [4, 5, 6, 1]


def test_casts():
    p = params("float4 c = (float4)0; float h = (float)1; float4 d = (float4)(0.5);")
    assert p["c"].value.tolist() == [0, 0, 0, 0] and float(p["h"].value) == 1
    assert p["d"].value.tolist() == [0.5] * 4
    effect = load_effect("technique T { pass P { FogStart = (float)2; } }")
    assert effect.techniques[0].passes[0].states[0].value == 2.0


def test_zero_is_null_for_shader_and_matrix_states():
    effect = load_effect("""float4x4 M = {2,0,0,0, 0,2,0,0, 0,0,2,0, 0,0,0,1};
        technique T { pass A { ViewTransform = <M>; } pass B { PixelShader = 0; VertexShader = 0;
                                                             ViewTransform = 0; } }""")
    b = effect.techniques[0].passes[1]
    assert all(isinstance(s.value, NullValue) for s in b.states)
    states = [s for _, s in pass_states(effect, effect.techniques[0].passes)]
    # NULL sets no matrix: pass B keeps pass A's view transform
    assert np.asarray(states[1].get("ViewTransform")).reshape(-1)[0] == 2


def test_backslash_continuations_outside_define():
    p = params('string s = "one" \\\n"two";\nfloat f = \\\n  3;\nfloat g = 4;')
    assert p["s"].value == "onetwo" and float(p["f"].value) == 3
    assert p["g"].location.line == 5


@pytest.mark.parametrize("source, where, message", [
    ("float a[N];", "1:9", "array size 'N' is not a constant integer declared before"),
    ("float b = 1.5; float a[b];", "1:24", "array size 'b' is not a constant integer"),
    ("float a[];", "1:8", "'a[]' needs an initializer list to give its size"),
    ("float3 a[] = {1, 2, 3, 4};", "1:14", "'a[]': 4 values do not fill whole float3 elements"),
    ("typedef frob COLOR;", "1:9", "unknown type 'frob'"),
    ("matrix<float, 9, 9> M;", "1:1", "unknown type 'matrix<float,9,9>'"),
    ("float4x4 m; float4 w = {1,2,3,4}; float z = w[7];", "1:45", "index out of range: 'w[7]'"),
    ("float a, ;", "1:10", "expected a name, found ';'"),
])
def test_construct_misuse_is_a_located_error(source, where, message):
    with pytest.raises(ParseError) as err:
        load_effect(source)
    assert f"<string>:{where}: error: {message}" in str(err.value)


# -- assembly that is not Direct3D assembly -------------------------------------------------

NOT_D3D = """technique ARB { pass P { PixelShader = asm { !!ARBfp1.0
MOV result.color, fragment.color;
END }; } }
technique NoVersion { pass P { VertexShader = asm { mov oPos, v0 }; } }
"""


@pytest.mark.parametrize("profile", ["refrast", "radeon9700", "geforce3"])
def test_assembly_that_is_not_direct3d_is_rejected_at_validation(profile):
    effect = load_effect(NOT_D3D)
    profile = load_profile(profile)
    arb = effect.validate("ARB", profile)
    assert not arb.ok
    assert len(arb.reasons) == 1 and str(arb.reasons[0]).endswith(
        "PixelShader: the asm block is an OpenGL ARB program ('!!ARBfp1.0'), not Direct3D "
        "shader assembly")
    assert arb.reasons[0].location.line == 1
    none = effect.validate("NoVersion", profile)
    assert not none.ok and "does not start with a version token" in str(none.reasons[0])
    assert none.reasons[0].location.line == 4


HASH_LINE = """technique Hash { pass P { PixelShader = asm {
    ps.1.1
  # the engine's remark
    mov r0, v0
}; } }"""


def test_a_hash_line_in_asm_is_a_located_warning_and_strict_an_error():
    effect = load_effect(HASH_LINE)
    assert [str(w) for w in effect.warnings] == [
        "<string>:3:3: warning: '# the engine's remark' in an asm block is not a preprocessor "
        "directive; D3DX's assembler rejects it (ignored here)"]
    assert effect.validate("Hash", load_profile("geforce3")).ok
    with pytest.raises(ParseError, match=r"<string>:3:3: error: '# the engine's remark' in an "
                                         r"asm block .* D3DX's assembler rejects it"):
        load_effect(HASH_LINE, strict=True)


def test_an_unknown_directive_outside_asm_stays_an_error():
    with pytest.raises(EffectError, match="unknown preprocessor directive '#frob'"):
        load_effect("#frob\nfloat x;")
