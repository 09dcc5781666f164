"""The effect parser: every construct of the effect language, DX8 and DX9, as the model sees it."""
from __future__ import annotations

from tests.paths import ROOT

from pathlib import Path
import dataclasses

import numpy as np
import pytest

from effects import StateError, load_effect
from effects.model import (CompileShader, EnumValue, Expression, NullValue, ParamRef,
                           SamplerState, ShaderBlock, TypeSpec, VertexDeclElement)

FXFILES = ROOT / "fxfiles"


def parse(src: str, **kw):
    return load_effect(src + "\n", **kw)


def one_pass(states: str, prelude: str = ""):
    effect = parse(f"{prelude}\ntechnique T {{ pass P {{\n{states}\n}} }}")
    return effect.techniques[0].passes[0]


# ---------------------------------------------------------------------------------------------
# Parameters: types, storage, shapes, values


@pytest.mark.parametrize("decl, base, rows, cols, shape, dtype", [
    ("float x = 0.25;", "float", 1, 1, (), np.float32),
    ("half h = 2;", "half", 1, 1, (), np.float32),
    ("double d = 1.5;", "float", 1, 1, (), np.float32),
    ("int i = -3;", "int", 1, 1, (), np.int32),
    ("bool b = true;", "bool", 1, 1, (), np.bool_),
    ("float4 v = {1, 2, 3, 4};", "float", 1, 4, (4,), np.float32),
    ("int3 v = {1, 2, 3};", "int", 1, 3, (3,), np.int32),
    ("bool2 v = {true, false};", "bool", 1, 2, (2,), np.bool_),
    ("float1 v = 7;", "float", 1, 1, (1,), np.float32),
    ("float3x2 m = {1, 2, 3, 4, 5, 6};", "float", 3, 2, (3, 2), np.float32),
    ("vector v = (1.0f, 1.0f, 1.0f, 1.0f);", "float", 1, 4, (4,), np.float32),
    ("VECTOR v = {0, 0, 0, 1};", "float", 1, 4, (4,), np.float32),
    ("matrix m = {1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1};", "float", 4, 4, (4, 4), np.float32),
    ("DWORD d = 0x10;", "dword", 1, 1, (), np.int32),
])
def test_numeric_parameter_types_and_shapes(decl, base, rows, cols, shape, dtype):
    p = parse(decl).parameters[0]
    assert (p.type.base, p.type.rows, p.type.cols) == (base, rows, cols)
    assert p.value.shape == shape
    assert p.value.dtype == dtype


def test_numeric_values_are_read_exactly():
    e = parse("""
        float a = 0.25;
        float b = -1.5e2f;
        float c = .5;
        float d = 1.;
        int e = 0xff;
        float4 f = float4(1, -2, 3.5f, 0x10);
        float4x4 g = { {1,2,3,4}, {5,6,7,8}, {9,10,11,12}, {13,14,15,16} };
        float3 h = 2;
    """)
    v = {p.name: p.value for p in e.parameters}
    assert v["a"] == np.float32(0.25) and v["b"] == np.float32(-150.0)
    assert v["c"] == np.float32(0.5) and v["d"] == np.float32(1.0)
    assert v["e"] == 255
    assert v["f"].tolist() == [1.0, -2.0, 3.5, 16.0]
    assert v["g"][2].tolist() == [9, 10, 11, 12] and v["g"][3, 0] == 13
    assert v["h"].tolist() == [2.0, 2.0, 2.0]  # a scalar fills every component


def test_hex_dword_above_int32_range_is_int64():
    p = parse("DWORD BCLR = 0xff202060;").parameters[0]
    assert p.value.dtype == np.int64
    assert int(p.value) == 0xFF202060 == 4280295520


def test_arrays_prefix_their_dims():
    e = parse("float4 a[2] = { {1,2,3,4}, {5,6,7,8} };\nfloat b[2][3] = {1,2,3,4,5,6};")
    a, b = e.parameters
    assert a.array == (2,) and a.value.shape == (2, 4) and a.value[1, 0] == 5
    assert b.array == (2, 3) and b.value.shape == (2, 3) and b.value[1, 2] == 6


def test_storage_classes_semantic_and_annotations():
    p = parse("""shared static uniform const extern volatile float4x4 WVP : WORLDVIEWPROJECTION
        < string UIName = "World \\"view\\" projection"; float4 Tint = {1, 0.5, 0, 1};
          int Count = -2; bool Visible = TRUE; float2 Range = float2(0, 10); >;""").parameters[0]
    assert p.storage == ("shared", "static", "uniform", "const", "extern", "volatile")
    assert p.semantic == "WORLDVIEWPROJECTION"
    assert p.value is None
    ann = {a.name: a for a in p.annotations}
    assert ann["UIName"].value == 'World "view" projection'
    assert ann["Tint"].value.tolist() == [1.0, 0.5, 0.0, 1.0]
    assert ann["Count"].value == -2 and ann["Count"].value.dtype == np.int32
    assert ann["Visible"].value.dtype == np.bool_ and bool(ann["Visible"].value)
    assert ann["Range"].value.tolist() == [0.0, 10.0]
    assert p.annotation("uiname") is ann["UIName"]


def test_string_parameter():
    assert parse('string XFile = "sphere.x";').parameters[0].value == "sphere.x"


@pytest.mark.parametrize("spelling, base, dim", [
    ("texture", "texture", ""), ("Texture", "texture", ""), ("TEXTURE", "texture", ""),
    ("texture1D", "texture", "1D"), ("Texture2D", "texture", "2D"),
    ("texture3D", "texture", "3D"), ("textureCUBE", "texture", "CUBE"),
    ("sampler", "sampler", ""), ("sampler2D", "sampler", "2D"), ("samplerCUBE", "sampler", "CUBE"),
    ("VertexShader", "vertexshader", ""), ("pixelshader", "pixelshader", ""),
])
def test_object_types_case_insensitive(spelling, base, dim):
    p = parse(f"{spelling} x;").parameters[0]
    assert (p.type.base, p.type.dim, p.type.spelling) == (base, dim, spelling)


def test_sampler_state_is_coerced_by_the_states_table():
    e = parse("""texture2D Tex;
        sampler2D S = sampler_state { Texture = <Tex>; MinFilter = Linear;
                                      AddressU = CLAMP; MaxAnisotropy = 4; };""")
    s = e.parameters[1].value
    assert isinstance(s, SamplerState)
    assert [a.name for a in s.states] == ["Texture", "MinFilter", "AddressU", "MaxAnisotropy"]
    assert s.get("texture").value == ParamRef("Tex", angle=True)
    assert s.get("MinFilter").value.names == ("LINEAR",)
    assert s.get("AddressU").value.names == ("CLAMP",)
    assert s.get("MaxAnisotropy").value == 4


def test_struct_is_kept_verbatim_and_usable_as_a_type():
    src = "struct S\n{\n    float4 a : COLOR0; // { brace in a comment\n};\nS s;"
    e = parse(src)
    assert e.structs[0].name == "S"
    assert e.structs[0].source == "struct S\n{\n    float4 a : COLOR0;                        \n};"
    assert e.structs[0].location.line == 1
    assert e.parameters[0].type == TypeSpec("S", struct=True)


def test_shader_parameters_asm_compile_and_arrays():
    e = parse("""
        PixelShader ps14 = asm { ps.1.4
            texld r0, t0 };
        VertexShader vs[2] = { compile vs_1_1 VS(1, 2 + 3), compile vs_2_0 VS(2) };
        PixelShader none = NULL;
        PixelShader alias = ps14;
    """)
    ps, vs, none, alias = e.parameters
    assert alias.value == ParamRef("ps14")
    assert load_effect(e.to_source()).parameters == e.parameters
    assert isinstance(ps.value, ShaderBlock)
    assert (ps.value.stage, ps.value.version) == ("pixel", "ps_1_4")
    assert vs.array == (2,)
    assert vs.value == [CompileShader("vs_1_1", "VS", ("1", "2 + 3")),
                        CompileShader("vs_2_0", "VS", ("2",))]
    assert isinstance(none.value, NullValue)


def test_stateblock():
    e = parse("stateblock b = stateblock_state { AlphaBlendEnable = FALSE; ColorOp[0] = Modulate; };")
    block = e.parameters[0].value
    assert [(s.name, s.index) for s in block.states] == [("AlphaBlendEnable", None), ("ColorOp", 0)]
    assert block.states[0].value is False


def test_non_constant_initializer_is_kept_as_an_expression():
    e = parse("float a = 2;\nfloat b = a * 2;")
    assert e.parameters[1].value == Expression("a * 2")


# ---------------------------------------------------------------------------------------------
# Functions


def test_hlsl_functions_are_captured_with_exact_text():
    fn1 = ("float4 VS(float4 p : POSITION, uniform int n) : POSITION\n"
           "{\n    if (n > 0) { for (int i = 0; i < n; i++) { p.x += 1; } }\n    return p;\n}")
    fn2 = "void Nothing() { }"
    fn3 = "static VS_OUT Make(float4 p) { VS_OUT o; o.p = p; return o; }"
    e = parse("struct VS_OUT { float4 p : POSITION; };\n\n" + fn1 + "\n" + fn2 + "\n" + fn3)
    assert [(f.name, f.return_type) for f in e.functions] == [
        ("VS", "float4"), ("Nothing", "void"), ("Make", "VS_OUT")]
    assert e.functions[0].source == fn1
    assert e.functions[0].location.line == 3 and e.functions[0].location.column == 1
    assert e.functions[1].source == fn2 and e.functions[1].location.line == 8
    assert e.functions[2].source == fn3


def test_register_semantic_is_not_a_function():
    p = parse("float4 c : register(c0);").parameters[0]
    assert p.semantic == "register(c0)"


# ---------------------------------------------------------------------------------------------
# Techniques, passes, keywords


@pytest.mark.parametrize("technique, pass_", [("technique", "pass"), ("Technique", "Pass"),
                                              ("TECHNIQUE", "PASS"), ("tEcHnIqUe", "pAsS")])
def test_keywords_are_case_insensitive(technique, pass_):
    e = parse(f"{technique} T {{ {pass_} P {{ ZEnable = TRUE; }} }}")
    assert e.techniques[0].name == "T" and e.techniques[0].passes[0].name == "P"


def test_anonymous_techniques_passes_annotations_and_stray_semicolons():
    e = parse("""
        ;
        technique < string Desc = "first"; > { ; pass { ZEnable = true; ; } pass P1 < int n = 1; > {} };
        technique Named { }
    """)
    t0, t1 = e.techniques
    assert t0.name is None and t0.annotation("Desc").value == "first"
    assert [p.name for p in t0.passes] == [None, "P1"]
    assert len(t0.passes[0].states) == 1
    assert t0.passes[1].annotations[0].value == 1
    assert t1.name == "Named" and t1.passes == []


def test_an_annotation_of_a_struct_type_declared_before_it():
    # Wine's variable-names effect, which fxc compiled: `float i <s k[1] = {4};>;`
    e = parse("struct s { float j; };\nfloat i < s k[1] = {4}; >;\n"
              "technique T < s l = {5}; > { pass P < s m[1] = {6}; > { } }")
    k = e.parameters[0].annotations[0]
    assert (k.name, k.type.struct, k.type.base) == ("k", True, "s")
    assert isinstance(k.value, Expression) and k.value.text == "{4}"
    assert e.techniques[0].annotations[0].value.text == "{5}"
    assert e.techniques[0].passes[0].annotations[0].value.text == "{6}"


def test_an_annotation_of_an_undeclared_type_is_located():
    with pytest.raises(Exception, match=r"<string>:2:11: error: unknown type 'u'"):
        parse("float x;\nfloat i < u k = {4}; >;\ntechnique T { pass P { } }")


def test_locations_point_at_names_in_the_file():
    e = parse("float x;\n\ntechnique T\n{\n  pass P\n  {\n    ZEnable = TRUE;\n  }\n}")
    t = e.techniques[0]
    assert (t.location.line, t.location.column) == (3, 1)
    assert (t.passes[0].location.line, t.passes[0].location.column) == (5, 3)
    s = t.passes[0].states[0]
    assert (s.location.line, s.location.column) == (7, 5)
    assert (e.parameters[0].location.line, e.parameters[0].location.column) == (1, 7)


# ---------------------------------------------------------------------------------------------
# State values


def test_state_values_literals_enums_and_combinations():
    p = one_pass("""
        AlphaBlendEnable = TRUE;
        AlphaRef = 0x80;
        FogStart = 0.5f;
        FogColor = 0xff202060;
        ColorOp[0] = Modulate;
        ColorArg1[0] = Texture | Complement;
        COLOROP[1] = SELECTARG1;
        TexCoordIndex[1] = 1 | CameraSpaceNormal;
        DepthBias = -1.0;
        Ambient = {0.5, 0.25, 0, 1};
    """)
    s = {(a.name, a.index): a.value for a in p.states}
    assert s[("AlphaBlendEnable", None)] is True
    assert s[("AlphaRef", None)] == 128
    assert s[("FogStart", None)] == 0.5
    assert s[("FogColor", None)] == 0xFF202060
    assert s[("ColorOp", 0)] == EnumValue(("MODULATE",), 4)             # D3DTOP_MODULATE = 4
    assert s[("ColorArg1", 0)] == EnumValue(("TEXTURE", "COMPLEMENT"), 0x12)  # 2 | 0x10
    assert s[("ColorOp", 1)] == EnumValue(("SELECTARG1",), 2)
    assert s[("TexCoordIndex", 1)] == EnumValue(("1", "CAMERASPACENORMAL"), 0x10001)
    assert s[("DepthBias", None)] == -1.0
    # Ambient is a D3DCOLOR: the float4 is packed as 0xAARRGGBB with x*255+0.5 rounding
    assert s[("Ambient", None)] == (0xFF << 24) | (128 << 16) | (64 << 8) | 0


def test_state_values_references():
    p = one_pass("""
        Texture[0] = <t>;
        Texture[1] = (t);
        Texture[2] = t;
        VertexShader = (vsArray[2]);
        PixelShader = <ps14>;
        Sampler[0] = (s);
        Texture[3] = NULL;
    """, prelude="texture t; sampler s; VertexShader vsArray[4]; PixelShader ps14;")
    v = [a.value for a in p.states]
    assert v[0] == ParamRef("t", angle=True)
    assert v[1] == ParamRef("t", angle=False)
    assert v[2] == ParamRef("t")
    assert v[3] == ParamRef("vsArray", index=2)
    assert v[4] == ParamRef("ps14", angle=True)
    assert v[5] == ParamRef("s")
    assert isinstance(v[6], NullValue)


def test_state_value_expressions_are_kept_as_text():
    p = one_pass("FogStart = Bias * 2;\nFogEnd = (Bias + 1);\nVertexShader = (vs[CurNumBones]);",
                 prelude="float Bias; int CurNumBones; VertexShader vs[4];")
    assert [a.value for a in p.states] == [Expression("Bias * 2"), Expression("(Bias + 1)"),
                                           Expression("(vs[CurNumBones])")]


def test_asm_block_body_is_exact_with_location_of_its_first_character():
    src = ("technique T {\n  pass P {\n    PixelShader = asm {\n      ps.1.1\n      tex t0 ; c\n"
           "      mov r0, t0\n    };\n  }\n}")
    e = parse(src)
    block = e.techniques[0].passes[0].states[0].value
    assert block.source == "\n      ps.1.1\n      tex t0 ; c\n      mov r0, t0\n    "
    assert (block.location.line, block.location.column) == (3, 24)
    assert (block.stage, block.version) == ("pixel", "ps_1_1")


@pytest.mark.parametrize("first, stage, version", [
    ("vs.1.1", "vertex", "vs_1_1"), ("vs_1_1", "vertex", "vs_1_1"), ("ps.1.4", "pixel", "ps_1_4"),
    ("ps_2_0", "pixel", "ps_2_0"), ("PS.1.3", "pixel", "ps_1_3"),
    ("// comment\n ; another\n vs.2.0", "vertex", "vs_2_0"),
])
def test_asm_profile_from_first_token(first, stage, version):
    state = "VertexShader" if stage == "vertex" else "PixelShader"
    p = one_pass(f"{state} = asm {{ {first}\n mov r0, r1 }};")
    assert (p.states[0].value.stage, p.states[0].value.version) == (stage, version)


def test_non_d3d_asm_text_has_no_version():
    p = one_pass("PixelShader = asm { !!ARBfp1.0\n PARAM c = {1, 2, 3, 4};\n MOV result.color, c;\n END };")
    block = p.states[0].value
    assert block.version is None and block.stage == "pixel"
    assert "PARAM c = {1, 2, 3, 4};" in block.source


def test_dx8_decl_block():
    p = one_pass("""VertexShader = decl { stream 0; float v0[3]; D3DCOLOR v5; float v7[2];
                                          stream 1; skip 2; UBYTE v2; }
                                   asm { vs.1.1
                                         mov oPos, v0 };""")
    block = p.states[0].value
    assert block.version == "vs_1_1"
    assert block.decl == (VertexDeclElement(0, "float", 0, 3), VertexDeclElement(0, "d3dcolor", 5, 4),
                          VertexDeclElement(0, "float", 7, 2), VertexDeclElement(1, "skip", -1, 2),
                          VertexDeclElement(1, "ubyte", 2, 4))


def test_compile_shader_state():
    p = one_pass("VertexShader = compile vs_1_1 VS(1, true);\nPixelShader = compile PS_2_0 PS();")
    assert p.states[0].value == CompileShader("vs_1_1", "VS", ("1", "true"))
    assert p.states[1].value == CompileShader("ps_2_0", "PS", ())


def test_dx8_file_style_end_to_end():
    e = parse("""
        VECTOR vLight = (0.0f, 0.0f, -1.0f, 0.0f);
        MATRIX mTot;
        TEXTURE tBase;
        DWORD BCLR = 0xff202060;
        PIXELSHADER ps = asm { ps.1.1
            tex t0
            mov r0, t0 };
        TECHNIQUE T0
        {
            PASS P0
            {
                VertexShaderConstant[4] = <mTot>;
                Texture[0] = <tBase>;
                PixelShader = <ps>;
            }
        }
    """)
    assert [p.type.base for p in e.parameters] == ["float", "float", "texture", "dword",
                                                    "pixelshader"]
    assert e.parameters[0].value.tolist() == [0.0, 0.0, -1.0, 0.0]
    s = e.techniques[0].passes[0].states
    assert [(a.name, a.index) for a in s] == [("VertexShaderConstant", 4), ("Texture", 0),
                                              ("PixelShader", None)]
    assert s[2].value == ParamRef("ps", angle=True)


# ---------------------------------------------------------------------------------------------
# Unknown states, strict mode, typed errors


def test_unknown_state_is_a_warning_with_did_you_mean():
    e = parse("technique T\n{\n  pass P\n  {\n    ColorArg[0] = Texture;\n  }\n}")
    (w,) = e.warnings
    assert w.message == "unknown state 'ColorArg' (did you mean 'ColorArg1'?)"
    assert (w.location.line, w.location.column) == (5, 5)
    s = e.techniques[0].passes[0].states[0]
    assert (s.name, s.index, s.known) == ("ColorArg", 0, False)
    assert s.value == EnumValue(("TEXTURE",))


def test_unknown_state_in_strict_mode_is_an_error():
    with pytest.raises(StateError) as info:
        parse("technique T\n{\n  pass P\n  {\n    ColorArg[0] = Texture;\n  }\n}", strict=True)
    assert str(info.value) == ("<string>:5:5: error: unknown state 'ColorArg' "
                               "(did you mean 'ColorArg1'?)")


def test_state_names_are_canonical():
    p = one_pass("zenable = true;\nCOLOROP[0] = modulate;\npointsize_min = 1.0;")
    assert [s.name for s in p.states] == ["ZEnable", "ColorOp", "PointSize_Min"]


def test_effect_files_come_from_the_preprocessor(tmp_path):
    (tmp_path / "inc.fx").write_text("float a = 1;\n")
    main = tmp_path / "main.fx"
    main.write_text('#include "inc.fx"\nfloat b = 2;\n')
    e = load_effect(str(main))
    assert [p.name for p in e.parameters] == ["a", "b"]
    assert sorted(Path(f).name for f in e.files) == ["inc.fx", "main.fx"]
    assert Path(e.path).name == "main.fx"
    assert Path(e.parameters[0].location.path).name == "inc.fx"


# ---------------------------------------------------------------------------------------------
# The bundled effects

# Counts read from the files by hand: {file: [(technique, [states per pass...]), ...]}.
FX_COUNTS = {
    "brdf.fx": [("tec0", [24])],
    "fast_phong.fx": [("Phong", [27]), ("Gouraud", [27])],
    "wood.fx": [("Wood_ps20", [2]), ("WoodRings_ps20", [2])],
    "shadows.fx": [("Shadow4_R32F", [8, 15]), ("Shadow1_R32F", [8, 14]),
                   ("Shadow4_R16F", [8, 15]), ("Shadow4_Linear8", [9, 16]), ("Lit_ff", [18])],
    "sdk9_hlsl.fx": [("Scene_ps20", [2]), ("Scene_ps14", [2]), ("Scene_ps11", [2]), ("Scene_ff", [18])],
    "sdk9_style.fx": [("Marble_ps20", [17, 10]), ("Marble_ps11", [18]), ("Marble_dx7", [25]),
                      ("Marble_dx6", [19])],
    "sdk8_style.fx": [("TPS4", [21]), ("TPS1", [21]), ("TFF7", [38]), ("TDX6", [28]),
                      (None, [17])],
    "hemisphere.fx": [("HemisphereOcclusion_ps11", [17]), ("HemispherePerPixel_ps11", [17]),
                      ("HemisphereVertex_vs11", [20]), ("SingleTexture", [21])],
    "multilight.fx": [("MultiLight_ps30", [13]), ("MultiLight_ps20", [13]),
                      ("MultiLight_ff", [34])],
    "phong.fx": [("PerPixelPhong_ps20", [14]), ("PerPixelPhong_ps11", [18, 14]),
                 ("Dot3_dx7", [30]), ("SingleTexture", [34])],
    "specular_bump.fx": [("Specular_ps20", [10]), ("SpecularTable_ps11", [19]),
                         ("SpecularMultiply_ps11", [13]), ("Dot3_dx7", [19]),
                         ("BumpEnvMap_dx6", [34]), ("Emboss_dx6", [18, 11]),
                         ("SingleTexture", [20])],
}


def test_fx_directory_has_effects():
    assert sorted(FXFILES.glob("*.fx")), "fxfiles/ holds no effects"


@pytest.mark.parametrize("path", sorted(FXFILES.glob("*.fx")), ids=lambda p: p.name)
def test_every_bundled_effect_loads_with_the_expected_counts(path):
    effect = load_effect(str(path))
    assert path.name in FX_COUNTS, f"add the technique/pass/state counts of {path.name}"
    got = [(t.name, [len(p.states) for p in t.passes]) for t in effect.techniques]
    assert got == FX_COUNTS[path.name]
    assert all(s.known for t in effect.techniques for p in t.passes for s in p.states)


def test_brdf_dx8_details():
    e = load_effect(str(FXFILES / "brdf.fx"))
    p = e.techniques[0].passes[0]
    vs = p.state("VertexShader").value
    assert vs.version == "vs_1_1" and vs.decl[0] == VertexDeclElement(0, "float", 0, 3)
    assert [d.register for d in vs.decl] == [0, 3, 7, 8]
    assert p.state("PixelShader").value.version == "ps_1_1"
    assert p.state("Texture", 3).value == ParamRef("ObjectTexture", angle=True)
    assert e.parameter("BCLR").value == 0xFF0000FF
    assert e.parameter("tec0").value == "BRDF Shader"


def test_parameter_lookups_follow_the_list_first_match_wins():
    e = parse("""float A : COLOR0 = 1; float B : color0 = 3;
        texture T; sampler3D S = sampler_state { Texture = <T>; };""")
    e.parameters.insert(1, dataclasses.replace(e.parameters[0]))   # a second A
    assert e.parameter("A") is e.parameters[0] and e.parameter("Missing") is None
    assert e.parameter_by_semantic("COLOR0") is e.parameters[0]
    assert e.sampler_dim_of("T") == "3D" and e.sampler_dim_of("A") is None
    extra = dataclasses.replace(e.parameters[2], name="C")
    e.parameters.append(extra)                      # appended after the index was built
    assert e.parameter("C") is extra
    e.parameters[0].name = "Renamed"                 # renamed in place
    assert e.parameter("A") is e.parameters[1] and e.parameter("Renamed") is e.parameters[0]


def test_every_state_walks_sampler_blocks_then_passes_in_file_order():
    e = parse("texture T;\n"
              "sampler S = sampler_state { Texture = <T>; MinFilter = Linear; };\n"
              "sampler A[2] = { sampler_state { MagFilter = Point; },"
              " sampler_state { MipFilter = None; } };\n"
              "technique X { pass P { ZEnable = false; } pass Q { CullMode = None; } }\n")
    assert [s.name for s in e.every_state()] == [
        "Texture", "MinFilter", "MagFilter", "MipFilter", "ZEnable", "CullMode"]
