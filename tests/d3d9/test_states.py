"""The effect-state table: names, enum numbers, device defaults, value coercion and its errors.

Expected numbers are the documented Direct3D 9 values (d3d9types.h as documented on
learn.microsoft.com) and the defaults of docs/reference/semantics.md 1.1, written out here by hand.
"""
import numpy as np
import pytest

from effects.base.errors import Location, StateError
from effects.model import (CompileShader, EnumValue, Expression, NullValue, ParamRef,
                           SamplerState, ShaderBlock)
from effects.d3d9.states import (ENUMS, STATES, check_index, coerce_state_value,
                                 constant_register_count, default_value, lookup_state,
                                 pack_color, suggest_state)

LOC = Location("fx/test.fx", 12, 9)


def coerce(state, raw, parameters=()):
    return coerce_state_value(lookup_state(state), raw, LOC, parameters)


def error_of(state, raw, parameters=()):
    with pytest.raises(StateError) as caught:
        coerce(state, raw, parameters)
    assert (caught.value.line, caught.value.column) == (12, 9)
    return caught.value.message


# --------------------------------------------------------------------------------------------
# Names

# Wine's d3dx9 state_table, in effect-file spelling (docs/reference/effect_format.md section 2).
WINE_NAMES = """
ZEnable FillMode ShadeMode ZWriteEnable AlphaTestEnable LastPixel SrcBlend DestBlend CullMode
ZFunc AlphaRef AlphaFunc DitherEnable AlphaBlendEnable FogEnable SpecularEnable FogColor
FogTableMode FogStart FogEnd FogDensity RangeFogEnable StencilEnable StencilFail StencilZFail
StencilPass StencilFunc StencilRef StencilMask StencilWriteMask TextureFactor
Wrap0 Wrap1 Wrap2 Wrap3 Wrap4 Wrap5 Wrap6 Wrap7 Wrap8 Wrap9 Wrap10 Wrap11 Wrap12 Wrap13 Wrap14
Wrap15 Clipping Lighting Ambient FogVertexMode ColorVertex LocalViewer NormalizeNormals
DiffuseMaterialSource SpecularMaterialSource AmbientMaterialSource EmissiveMaterialSource
VertexBlend ClipPlaneEnable PointSize PointSize_Min PointSize_Max PointSpriteEnable
PointScaleEnable PointScale_A PointScale_B PointScale_C MultiSampleAntialias MultiSampleMask
PatchEdgeStyle DebugMonitorToken IndexedVertexBlendEnable ColorWriteEnable TweenFactor BlendOp
PositionDegree NormalDegree ScissorTestEnable SlopeScaleDepthBias AntialiasedLineEnable
MinTessellationLevel MaxTessellationLevel AdaptiveTess_X AdaptiveTess_Y AdaptiveTess_Z
AdaptiveTess_W EnableAdaptiveTessellation TwoSidedStencilMode CCW_StencilFail CCW_StencilZFail
CCW_StencilPass CCW_StencilFunc ColorWriteEnable1 ColorWriteEnable2 ColorWriteEnable3
BlendFactor SRGBWriteEnable DepthBias SeparateAlphaBlendEnable SrcBlendAlpha DestBlendAlpha
BlendOpAlpha
ColorOp ColorArg0 ColorArg1 ColorArg2 AlphaOp AlphaArg0 AlphaArg1 AlphaArg2 ResultArg
BumpEnvMat00 BumpEnvMat01 BumpEnvMat10 BumpEnvMat11 TexCoordIndex BumpEnvLScale BumpEnvLOffset
TextureTransformFlags Constant
NPatchMode FVF
ProjectionTransform ViewTransform WorldTransform TextureTransform
MaterialDiffuse MaterialAmbient MaterialSpecular MaterialEmissive MaterialPower
LightType LightDiffuse LightSpecular LightAmbient LightPosition LightDirection LightRange
LightFallOff LightAttenuation0 LightAttenuation1 LightAttenuation2 LightTheta LightPhi
LightEnable VertexShader PixelShader
VertexShaderConstantF VertexShaderConstantB VertexShaderConstantI VertexShaderConstant
VertexShaderConstant1 VertexShaderConstant2 VertexShaderConstant3 VertexShaderConstant4
PixelShaderConstantF PixelShaderConstantB PixelShaderConstantI PixelShaderConstant
PixelShaderConstant1 PixelShaderConstant2 PixelShaderConstant3 PixelShaderConstant4
Texture AddressU AddressV AddressW BorderColor MagFilter MinFilter MipFilter MipMapLodBias
MaxMipLevel MaxAnisotropy SRGBTexture ElementIndex DMAPOffset Sampler
""".split()


def test_every_wine_state_is_a_row_and_nothing_else_is_except_dx8_leftovers():
    assert len(WINE_NAMES) == 179
    rows = {lookup_state(name).name for name in WINE_NAMES}
    assert len(rows) == 179  # distinct rows, no name resolved to another's row
    extra = {s.name for s in STATES} - rows
    assert extra == {"LinePattern", "ZVisible", "EdgeAntialias", "ZBias",
                     "SoftwareVertexProcessing"}
    assert all(lookup_state(name).legacy for name in extra)


def test_lookup_ignores_case_and_underscores():
    assert lookup_state("COLOROP").name == "ColorOp"
    assert lookup_state("alphablendenable").name == "AlphaBlendEnable"
    assert lookup_state("PointSizeMin").name == "PointSize_Min"
    assert lookup_state("ccwstencilfunc").name == "CCW_StencilFunc"
    assert lookup_state("NoSuchState") is None


def test_dx8_spellings_are_aliases():
    assert lookup_state("PositionOrder").name == "PositionDegree"
    assert lookup_state("NormalOrder").name == "NormalDegree"
    assert lookup_state("PatchSegments").name == "NPatchMode"
    assert lookup_state("LightFalloff").name == lookup_state("LightFallOff").name


def test_state_kinds_codes_and_indices():
    colorop = lookup_state("ColorOp")
    assert (colorop.kind, colorop.type, colorop.code, colorop.index, colorop.max_index) == \
        ("stage", "enum", 1, "optional", 7)
    assert colorop.enum is ENUMS["D3DTEXTUREOP"]
    minfilter = lookup_state("MinFilter")
    assert (minfilter.kind, minfilter.code, minfilter.max_index) == ("sampler", 6, 15)
    assert lookup_state("ZEnable").code == 7
    assert lookup_state("BlendOpAlpha").code == 209
    assert lookup_state("Wrap8").code == 198
    assert lookup_state("ColorWriteEnable3").code == 192
    assert lookup_state("Constant").code == 32
    assert lookup_state("ResultArg").code == 28
    assert lookup_state("WorldTransform").kind == "transform"
    assert lookup_state("ViewTransform").index == "none"
    assert lookup_state("LightEnable").kind == "light"
    assert lookup_state("VertexShaderConstant4").registers == 4
    assert lookup_state("PixelShaderConstant1").registers == 1
    assert lookup_state("Sampler").kind == "sampler_object"


def test_suggestions():
    assert suggest_state("ColorArg") == "ColorArg1"
    assert suggest_state("AlphaBlendEnabled") == "AlphaBlendEnable"
    assert suggest_state("MinFiltr") == "MinFilter"
    assert suggest_state("Zzzzzzzzzzzzzz") is None


# --------------------------------------------------------------------------------------------
# Enum tables

D3DTOP_DOCUMENTED = [
    "DISABLE", "SELECTARG1", "SELECTARG2", "MODULATE", "MODULATE2X", "MODULATE4X", "ADD",
    "ADDSIGNED", "ADDSIGNED2X", "SUBTRACT", "ADDSMOOTH", "BLENDDIFFUSEALPHA", "BLENDTEXTUREALPHA",
    "BLENDFACTORALPHA", "BLENDTEXTUREALPHAPM", "BLENDCURRENTALPHA", "PREMODULATE",
    "MODULATEALPHA_ADDCOLOR", "MODULATECOLOR_ADDALPHA", "MODULATEINVALPHA_ADDCOLOR",
    "MODULATEINVCOLOR_ADDALPHA", "BUMPENVMAP", "BUMPENVMAPLUMINANCE", "DOTPRODUCT3",
    "MULTIPLYADD", "LERP"]


def test_every_d3dtop_value_matches_the_header():
    table = ENUMS["D3DTEXTUREOP"]
    assert dict(table.values) == {name: i + 1 for i, name in enumerate(D3DTOP_DOCUMENTED)}


def test_every_d3dta_value_matches_the_header():
    assert dict(ENUMS["D3DTA"].values) == {
        "DIFFUSE": 0, "CURRENT": 1, "TEXTURE": 2, "TFACTOR": 3, "SPECULAR": 4, "TEMP": 5,
        "CONSTANT": 6, "COMPLEMENT": 0x10, "ALPHAREPLICATE": 0x20}
    assert ENUMS["D3DTA"].flags


@pytest.mark.parametrize("spelling", ["D3DTOP_MODULATE", "Modulate", "MODULATE", "modulate",
                                      "d3dtop_Modulate"])
def test_enum_lookup_case_and_prefix(spelling):
    assert ENUMS["D3DTEXTUREOP"].lookup(spelling) == ("MODULATE", 4)


def test_other_enum_numbers():
    assert ENUMS["D3DBLEND"].lookup("InvSrcAlpha") == ("INVSRCALPHA", 6)
    assert ENUMS["D3DBLEND"].lookup("BlendFactor") == ("BLENDFACTOR", 14)
    assert ENUMS["D3DCMPFUNC"].lookup("D3DCMP_LESSEQUAL") == ("LESSEQUAL", 4)
    assert ENUMS["D3DTEXTUREFILTERTYPE"].lookup("Anisotropic") == ("ANISOTROPIC", 3)
    assert ENUMS["D3DTEXTUREFILTERTYPE"].lookup("GaussianQuad") == ("GAUSSIANQUAD", 7)
    assert ENUMS["D3DTSS_TCI"].lookup("D3DTSS_TCI_SPHEREMAP") == ("SPHEREMAP", 0x40000)
    assert ENUMS["D3DVERTEXBLENDFLAGS"].lookup("D3DVBF_TWEENING") == ("TWEENING", 255)
    assert ENUMS["D3DWRAP"].lookup("D3DWRAPCOORD_3") == ("COORD3", 8)
    assert ENUMS["D3DWRAP"].lookup("D3DWRAP_V") == ("V", 2)
    assert ENUMS["D3DDEGREETYPE"].lookup("D3DORDER_QUINTIC") == ("QUINTIC", 5)
    assert ENUMS["D3DFVF"].lookup("Tex8") == ("TEX8", 0x800)
    assert ENUMS["D3DTEXTUREOP"].lookup("Modulate8x") is None


# --------------------------------------------------------------------------------------------
# Defaults (docs/reference/semantics.md 1.1 and the D3DRENDERSTATETYPE page)


def value_of(state, index=None):
    result = default_value(lookup_state(state), index)
    return result.value if isinstance(result, EnumValue) else result


def test_stage_cascade_defaults():
    assert value_of("ColorOp", 0) == 4            # MODULATE
    assert value_of("ColorOp", None) == 4         # no index means stage 0
    assert [value_of("ColorOp", s) for s in range(1, 8)] == [1] * 7   # DISABLE
    assert value_of("AlphaOp", 0) == 2            # SELECTARG1
    assert value_of("AlphaOp", 5) == 1
    for stage in (0, 3):
        assert value_of("ColorArg1", stage) == 2 and value_of("AlphaArg1", stage) == 2
        assert value_of("ColorArg2", stage) == 1 and value_of("AlphaArg2", stage) == 1
        assert value_of("ColorArg0", stage) == 1 and value_of("ResultArg", stage) == 1
        assert value_of("BumpEnvMat10", stage) == 0.0
        assert value_of("TextureTransformFlags", stage) == 0
        assert value_of("Constant", stage) == 0
    assert [value_of("TexCoordIndex", s) for s in range(8)] == list(range(8))
    assert default_value(lookup_state("ColorOp"), 0).names == ("MODULATE",)


def test_render_and_sampler_defaults():
    assert value_of("TextureFactor") == 0xFFFFFFFF
    assert value_of("Lighting") is True
    assert value_of("CullMode") == 3              # CCW
    assert value_of("ZFunc") == 4                 # LESSEQUAL
    assert value_of("ZEnable") == 1
    assert value_of("SrcBlend") == 2 and value_of("DestBlend") == 1
    assert value_of("ColorWriteEnable") == 0xF
    assert value_of("FogEnd") == 1.0 and value_of("PointSize_Max") == 64.0
    assert value_of("StencilMask") == 0xFFFFFFFF
    assert value_of("DiffuseMaterialSource") == 1 and value_of("SpecularMaterialSource") == 2
    assert value_of("AddressU", 9) == 1 and value_of("MagFilter") == 1
    assert value_of("MipFilter") == 0 and value_of("MaxAnisotropy") == 1
    assert isinstance(value_of("Texture", 2), NullValue)
    assert value_of("VertexShaderConstantF", 0) is None


def test_transform_light_and_material_defaults():
    world = value_of("WorldTransform", 3)
    assert world.dtype == np.float32
    assert np.array_equal(world, [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1])
    world[0] = 7  # a copy: the next default is untouched
    assert value_of("WorldTransform", 3)[0] == 1
    assert value_of("LightType", 2) == 3          # DIRECTIONAL
    assert np.array_equal(value_of("LightDiffuse", 0), [1, 1, 1, 0])
    assert np.array_equal(value_of("LightDirection", 0), [0, 0, 1])
    assert value_of("LightEnable", 4) is False
    assert np.array_equal(value_of("MaterialDiffuse"), [0, 0, 0, 0])


# --------------------------------------------------------------------------------------------
# Coercion


def test_enum_single_names_and_numbers():
    assert coerce("ColorOp", ["Modulate"]) == EnumValue(("MODULATE",), 4)
    assert coerce("ColorOp", ["D3DTOP_DOTPRODUCT3"]) == EnumValue(("DOTPRODUCT3",), 24)
    assert coerce("ColorOp", 24) == EnumValue(("24",), 24)
    assert coerce("ColorOp", 24.0) == EnumValue(("24",), 24)
    result = coerce("SrcBlend", ["srcalpha"])
    assert result.value == 5 and result.location == LOC


def test_d3dta_modifiers_combine():
    assert coerce("ColorArg1", ["Texture", "Complement"]) == EnumValue(("TEXTURE", "COMPLEMENT"), 0x12)
    assert coerce("AlphaArg2", ["Current", "AlphaReplicate"]).value == 0x21
    assert coerce("ResultArg", ["Temp"]).value == 5
    assert coerce("ColorArg0", ["Complement", "Diffuse", "AlphaReplicate"]).value == 0x30


def test_texcoordindex_takes_an_index_and_a_generation_mode():
    assert coerce("TexCoordIndex", ["CameraSpaceReflectionVector", 1]) == \
        EnumValue(("CAMERASPACEREFLECTIONVECTOR", "1"), 0x30001)
    assert coerce("TexCoordIndex", 2) == EnumValue(("2",), 2)
    assert coerce("TexCoordIndex", ["D3DTSS_TCI_CAMERASPACENORMAL"]).value == 0x10000


def test_flag_enums():
    assert coerce("TextureTransformFlags", ["Count2", "Projected"]) == \
        EnumValue(("COUNT2", "PROJECTED"), 0x102)
    assert coerce("TextureTransformFlags", ["Disable"]).value == 0
    assert coerce("FVF", ["XYZ", "NORMAL", "TEX1"]).value == 0x112
    assert coerce("ColorWriteEnable", ["RED", "GREEN", "BLUE", "ALPHA"]).value == 0xF
    assert coerce("ColorWriteEnable", ["Red", "Alpha"]).value == 9
    assert coerce("Wrap0", ["U", "V"]).value == 3
    assert coerce("ClipPlaneEnable", ["D3DCLIPPLANE0", "D3DCLIPPLANE2"]).value == 5


def test_zenable_takes_true_false_and_usew():
    assert coerce("ZEnable", True) == EnumValue(("TRUE",), 1)
    assert coerce("ZEnable", ["FALSE"]).value == 0
    assert coerce("ZEnable", ["UseW"]).value == 2
    assert coerce("ZEnable", ["D3DZB_USEW"]).value == 2


def test_bools():
    assert coerce("AlphaBlendEnable", True) is True
    assert coerce("AlphaBlendEnable", ["false"]) is False
    assert coerce("ZWriteEnable", 1) is True
    assert coerce("ZWriteEnable", 0) is False
    assert coerce("LightEnable", ["TRUE"]) is True


def test_integers_and_dwords():
    assert coerce("AlphaRef", 0x80) == 128
    assert coerce("AlphaRef", 128.0) == 128
    assert coerce("StencilMask", -1) == 0xFFFFFFFF
    assert coerce("StencilWriteMask", 0xFF) == 255
    assert coerce("MaxAnisotropy", (8,)) == 8


def test_colors_pack_like_d3dxcolor():
    # (1, .5, .25, 1): r 0xff, g (0.5*255+0.5)=128=0x80, b (0.25*255+0.5)=64.25→0x40, a 0xff
    assert coerce("TextureFactor", (1.0, 0.5, 0.25, 1.0)) == 0xFFFF8040
    # saturates: r 2.0→0xff, g -1→0, b 0→0, a .5→0x80
    assert coerce("FogColor", (2.0, -1.0, 0.0, 0.5)) == 0x80FF0000
    assert coerce("BorderColor", 0xFF00FF00) == 0xFF00FF00
    assert coerce("Constant", 0x80808080) == 0x80808080
    assert pack_color((0.0, 0.0, 1.0, 0.0)) == 0x000000FF


def test_floats_vectors_and_matrices():
    assert coerce("FogStart", 2) == 2.0 and isinstance(coerce("FogStart", 2), float)
    assert coerce("BumpEnvMat00", -0.5) == -0.5
    diffuse = coerce("MaterialDiffuse", (0.7, 0.0, 0.0, 1.0))
    assert diffuse.dtype == np.float32 and np.allclose(diffuse, [0.7, 0, 0, 1])
    assert np.array_equal(coerce("LightPosition", (10.0, 1.0, 23.0)), [10, 1, 23])
    assert np.array_equal(coerce("LightDirection", (0.0, -1.0, 0.0, 0.0)), [0, -1, 0])
    matrix = coerce("ViewTransform", tuple(float(i) for i in range(16)))
    assert matrix.shape == (16,) and matrix[5] == 5.0
    nested = coerce("WorldTransform", ((1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1)))
    assert np.array_equal(nested, np.eye(4).reshape(16))


def test_shader_constants():
    two_registers = coerce("VertexShaderConstant", (1, 2, 3, 4, 5, 6, 7, 8))
    assert two_registers.dtype == np.float32 and two_registers.size == 8
    assert coerce("PixelShaderConstant1", (0.5, 0.5, 0.5, 1.0)).size == 4
    assert coerce("VertexShaderConstant4", tuple(range(16))).size == 16
    ints = coerce("VertexShaderConstantI", (3, 0, 1, 0))
    assert ints.dtype == np.int32 and list(ints) == [3, 0, 1, 0]
    assert list(coerce("PixelShaderConstantB", (True, False, True))) == [True, False, True]


def test_a_shader_constant_value_short_of_whole_registers_sets_them_as_d3dx_did():
    # Wine's d3dx9 test_effect_states (fxc's binary, native D3DX): VertexShaderConstant1[1] =
    # 3.0f gives c1.x = 3; VertexShaderConstant4[2] = 1 one register, c2.x = 1; and
    # VertexShaderConstant4[4] = {4,4,4,4, 5,5,5,5, 6} c4 = 4s, c5 = c6 = 0, c7 untouched
    assert list(coerce("VertexShaderConstant1", 3.0)) == [3, 0, 0, 0]
    one = coerce("VertexShaderConstant4", 1)
    assert list(one) == [1, 0, 0, 0]
    assert constant_register_count(lookup_state("VertexShaderConstant4"), one.size) == 1
    nine = coerce("VertexShaderConstant4", (4, 4, 4, 4, 5, 5, 5, 5, 6))
    assert list(nine) == [4, 4, 4, 4] + [0] * 8
    assert list(coerce("PixelShaderConstantF", (1, 2, 3))) == [1, 2, 3, 0]
    assert list(coerce("VertexShaderConstantI", (5,))) == [5, 0, 0, 0]


def test_parameters_drive_any_state():
    params = {"BlendMode", "FogAmount", "tex", "Texture", "WorldViewProj"}
    assert coerce("SrcBlend", ["BlendMode"], params) == ParamRef("BlendMode")
    assert coerce("FogDensity", ["FogAmount"], params) == ParamRef("FogAmount")
    assert coerce("Texture", ["tex"], params) == ParamRef("tex")
    assert coerce("VertexShaderConstant4", ["WorldViewProj"], params) == ParamRef("WorldViewProj")
    # an enum name wins over a parameter of the same name
    assert coerce("ColorArg1", ["Texture"], params) == EnumValue(("TEXTURE",), 2)
    ref = ParamRef("x", angle=True)
    assert coerce("ZFunc", ref) is ref
    expr = Expression("Bias * 2")
    assert coerce("MipMapLodBias", expr) is expr


def test_objects_pass_through():
    null = NullValue()
    assert coerce("PixelShader", null) is null
    assert isinstance(coerce("Texture", ["NULL"]), NullValue)
    sampler = SamplerState()
    assert coerce("Sampler", sampler) is sampler
    vs = ShaderBlock("vertex", "vs_1_1", "vs.1.1\nmov oPos, v0\n")
    assert coerce("VertexShader", vs) is vs
    compiled = CompileShader("ps_2_0", "main")
    assert coerce("PixelShader", compiled) is compiled


# --------------------------------------------------------------------------------------------
# Errors, as the user reads them


def test_unknown_enum_name_suggests_the_closest():
    assert error_of("ColorOp", ["Modulat"]) == (
        "ColorOp expects a D3DTEXTUREOP value such as Modulate; 'Modulat' is not one "
        "(did you mean Modulate?)")
    assert error_of("ColorArg1", ["Texture", "Complment"]) == (
        "ColorArg1 expects a D3DTA value such as Texture; 'Complment' is not one "
        "(did you mean Complement?)")
    assert error_of("CullMode", ["Sideways"]) == (
        "CullMode expects a D3DCULL value such as CCW; 'Sideways' is not one")


def test_error_str_has_the_location():
    with pytest.raises(StateError) as caught:
        coerce("ColorOp", ["Modulat"])
    assert str(caught.value).startswith("fx/test.fx:12:9: error: ColorOp expects")


def test_combination_errors():
    assert error_of("SrcBlend", ["One", "Zero"]) == (
        "SrcBlend takes a single D3DBLEND value; 'One | Zero' combines 2")
    assert error_of("ColorArg1", ["Texture", "Diffuse"]) == (
        "ColorArg1: 'Texture | Diffuse' combines 2 D3DTA argument selectors (Texture, Diffuse); "
        "only one may be used")
    assert "coordinate counts (Count2, Count3)" in error_of(
        "TextureTransformFlags", ["Count2", "Count3"])


def test_type_errors():
    assert error_of("ZWriteEnable", 2) == "ZWriteEnable expects a bool (TRUE or FALSE); got 2"
    assert error_of("ZWriteEnable", ["Maybe"]) == (
        "ZWriteEnable expects a bool (TRUE or FALSE); 'Maybe' is neither TRUE/FALSE nor a parameter")
    assert error_of("CullMode", True) == "CullMode expects a D3DCULL value such as CCW; 'TRUE' is not one"
    assert error_of("FogStart", "far") == 'FogStart expects a float; got the string "far"'
    assert error_of("FogStart", ["far"]) == "FogStart expects a float; 'far' is neither a number nor a parameter"
    assert error_of("AlphaRef", 1.5) == "AlphaRef expects an integer; got 1.5"
    assert error_of("AlphaRef", -3) == "AlphaRef expects an integer; -3 is negative"
    assert error_of("TextureFactor", (1.0, 0.0, 0.0)) == (
        "TextureFactor expects a colour (a D3DCOLOR such as 0xFF808080, or a float4); "
        "got {1.0, 0.0, 0.0} (3 values)")
    assert error_of("MaterialDiffuse", (1.0, 0.0)) == \
        "MaterialDiffuse expects a float4 (4 numbers); got 2 value(s)"
    assert error_of("ViewTransform", tuple(range(12))) == \
        "ViewTransform expects a 4x4 matrix (16 numbers); got 12 value(s)"
    assert error_of("PixelShaderConstant2", tuple(range(9))) == (
        "PixelShaderConstant2 expects 2 float4 register(s) (8 numbers); got 9 value(s), more "
        "than those registers hold")
    assert error_of("Lighting", NullValue()) == "Lighting expects a bool (TRUE or FALSE); got NULL"


def test_object_errors():
    assert error_of("Texture", ["missing"], {"other"}) == \
        "Texture expects a texture parameter or NULL; 'missing' is not a parameter"
    assert error_of("Texture", SamplerState()) == \
        "Texture expects a texture parameter or NULL; got SamplerState"
    assert error_of("PixelShader", ShaderBlock("vertex", "vs_1_1", "vs.1.1")) == (
        "PixelShader expects a pixel shader (an asm block, a compile target, a parameter or "
        "NULL); the asm block is a vertex shader")
    assert error_of("VertexShader", CompileShader("ps_2_0", "main")).endswith(
        "'compile ps_2_0' targets a pixel shader")


def test_index_checks():
    check_index(lookup_state("ColorOp"), 7, LOC)
    check_index(lookup_state("MinFilter"), None, LOC)
    check_index(lookup_state("Texture"), 257, LOC)  # a vertex texture sampler
    with pytest.raises(StateError, match=r"ColorOp\[8\]: the index must be 0 to 7"):
        check_index(lookup_state("ColorOp"), 8, LOC)
    with pytest.raises(StateError, match=r"ZEnable takes no index; remove \[0\]"):
        check_index(lookup_state("ZEnable"), 0, LOC)
    with pytest.raises(StateError, match=r"VertexShaderConstant needs an index"):
        check_index(lookup_state("VertexShaderConstant"), None, LOC)
    with pytest.raises(StateError, match=r"MinFilter\[100\]"):
        check_index(lookup_state("MinFilter"), 100, LOC)


def test_a_suggested_name_that_starts_with_a_digit_keeps_its_prefix():
    # `VertexBlend = VBF_2WEIGHT` must suggest something a file can contain.
    table = next(t for t in ENUMS.values() if t.name == "D3DVERTEXBLENDFLAGS")
    assert table.suggest("VBF_2WEIGHT") == "D3DVBF_2WEIGHTS"


# --------------------------------------------------------------------------------------------
# The contracts' defaults agree with the table (effects.program.passprogram cannot import it: back ends
# read passprogram and must not see the state table)


def _fresh_device():
    import effects
    from effects.d3d9.device import DeviceState
    effect = effects.load_effect("technique t { pass p { } }")
    return effect, DeviceState(effect)


def test_render_state_defaults_are_the_state_tables_defaults():
    from dataclasses import fields

    from effects.lower.passes import _RENDER_FIELDS, read_render_state
    from effects.program.passprogram import RenderState
    assert set(_RENDER_FIELDS) == {f.name for f in fields(RenderState)}  # every field has a row
    _, state = _fresh_device()
    assert read_render_state(state) == RenderState()


def test_texture_binding_defaults_are_the_sampler_state_defaults():
    from effects.lower.passes import texture_binding
    from effects.program.passprogram import TextureBinding
    effect, state = _fresh_device()
    for sampler in (0, 15):
        assert texture_binding(effect, state, sampler, "2d") == TextureBinding(sampler)


def test_typed_readers_read_each_state_as_its_row_types_it():
    import effects
    from effects.d3d9.device import DeviceState
    effect = effects.load_effect("""float Ref = 127.9; float4 Tint = {0.5, 0.25, 1, 0.75};
        technique t { pass p { AlphaRef = <Ref>; BlendFactor = <Tint>; FogEnd = 3;
        ColorWriteEnable = Red | Alpha; CullMode = 2; ZEnable = UseW; } }""")
    state = DeviceState(effect)
    state.apply_pass(effect.techniques[0].passes[0])
    assert state.read("AlphaRef") == 127                      # a float cast to a DWORD
    assert state.read("BlendFactor") == (0.5, 0.25, 1.0, 0.75)  # a float4 colour parameter
    assert state.read("TextureFactor") == (1.0, 1.0, 1.0, 1.0)  # the default 0xFFFFFFFF
    assert state.read("FogEnd") == 3.0 and isinstance(state.read("FogEnd"), float)
    assert state.read("ColorWriteEnable") == 0x9               # flags read as a number
    assert state.read("CullMode") == "CW" and state.read("ZEnable") == "USEW"
    assert state.read("Lighting") is True and state.read("FogEnable") is False


def test_every_caps_limit_names_a_bit_field_and_its_bits():
    """Each limited state's row names a D3DCAPS9 bit field, and every value it can take needs a
    bit of that field, except the blend factors that only Direct3D 9Ex reports."""
    from effects.d3d9.caps import FIELDS, bit_prefix
    no_caps_bit = {("SrcBlend", "SRCCOLOR2"), ("SrcBlend", "INVSRCCOLOR2"),
                   ("DestBlend", "SRCCOLOR2"), ("DestBlend", "INVSRCCOLOR2"),
                   ("SrcBlendAlpha", "SRCCOLOR2"), ("SrcBlendAlpha", "INVSRCCOLOR2"),
                   ("DestBlendAlpha", "SRCCOLOR2"), ("DestBlendAlpha", "INVSRCCOLOR2")}
    limited = [row for row in STATES if row.limit is not None]
    # D3DTEXF_NONE turns a filter off; the cubic, convolution (and, for mipmaps, the
    # anisotropic and quad) filters have no D3DPTFILTERCAPS bit: no card reports them.
    no_caps_bit |= {(row.name, value) for row in limited if row.limit.field == "TextureFilterCaps"
                    for value in row.enum.values if value not in row.limit.renamed}
    assert ("MipFilter", "ANISOTROPIC") in no_caps_bit and ("MinFilter", "LINEAR") not in no_caps_bit
    assert {row.name for row in limited} >= {"SrcBlend", "ZFunc", "AlphaFunc", "StencilPass",
                                             "CCW_StencilFail", "CullMode", "BlendOp"}
    for row in limited:
        table = FIELDS[row.limit.field].table
        assert table is not None and bit_prefix(row.limit.field).startswith("D3D")
        if row.limit.bit is not None:
            assert row.limit.bit in table, row.name
            continue
        for value in row.enum.values:
            bit = row.limit.bit_for(value)
            assert bit in table or (row.name, value) in no_caps_bit, (row.name, value)


def test_a_number_past_float32_is_saturated_in_a_colour_and_refused_in_a_vector():
    """D3DX keeps state numbers as float32. A colour saturates each channel before its DWORD
    cast, so 1e39 is 0xFF (and NaN 0), without a float32 overflow; a float3 or float4 state
    has no float32 for 1e39 and says so, located at the value."""
    import warnings
    import effects
    from effects.d3d9.states import pack_color
    with warnings.catch_warnings():
        warnings.simplefilter("error")     # no "overflow encountered in cast"
        assert pack_color([1e39, 0.5, float("nan"), -3.0]) == 0x00FF8000
        assert pack_color([1.0, 0.5, 0.25, 1.0]) == 0xFFFF8040
        with pytest.raises(effects.EffectError) as err:
            effects.load_effect("technique T { pass P { LightDirection[0] = {1e39, 0, 0}; } }")
    assert str(err.value) == ("<string>:1:44: error: LightDirection expects a float3 (3 numbers); "
                              "got {1e+39, 0, 0}: a value past the largest float32 (3.4e38)")
    # the largest float32 itself is a value
    effects.load_effect("technique T { pass P { LightDirection[0] = {3.4e38, 0, 0}; } }")
