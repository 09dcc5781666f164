"""The fixed-function texture cascade, lowered and run on the NumPy evaluator, against values
worked out by hand from the D3D formulas (docs/reference/semantics.md section 1)."""
from __future__ import annotations

from tests.paths import TESTS

import os

import numpy as np
import pytest

import effects
from backends.reference.evaluate import evaluate
from effects.d3d9.caps import load_profile
from effects.base.errors import EffectError
from effects.lower.passes import clear_cache, lower_pass

GOLDEN_DIR = TESTS / "golden" / "ir"
UPDATE_GOLDEN = os.environ.get("EFFECTS_UPDATE_GOLDEN") == "1"


def argb(value: int) -> tuple[float, float, float, float]:
    """0xAARRGGBB as (r, g, b, a)."""
    return ((value >> 16 & 255) / 255, (value >> 8 & 255) / 255, (value & 255) / 255,
            (value >> 24 & 255) / 255)


# docs/reference/semantics.md 1.4 worked check: tex 0x9900ff00, TFACTOR 0xdd333333,
# diffuse 0x55ff0000
TEX = argb(0x9900FF00)       # (0, 1, 0, 0.6)
DIFFUSE = argb(0x55FF0000)   # (1, 0, 0, 1/3)


def lower(states: str, profile: str = "modern", params: str = "", technique: str = "t"):
    source = f"""
        texture Tex0; texture Tex1; texture Tex2;
        {params}
        technique {technique} {{ pass p {{
            {states}
        }} }}"""
    effect = effects.load_effect(source)
    return lower_pass(effect, effect.techniques[0], 0, load_profile(profile))


def constant_sampler(color):
    color = np.array(color, dtype=np.float32)
    return lambda coord, **kw: np.tile(color, (len(coord), 1))


def coord_sampler(coord, **kw):
    """A texture whose texel is its own coordinate, to see where a stage samples."""
    return np.array(coord, dtype=np.float32)


def shade(pp, diffuse=DIFFUSE, specular=(0, 0, 0, 0), textures=None, texcoords=None, fog=None):
    """Evaluate a pass's fragment program for one pixel."""
    inputs = pp.uniform_values()
    for item in pp.fragment.inputs:
        if item.name == "color0":
            inputs["color0"] = np.array([diffuse], np.float32)
        elif item.name == "color1":
            inputs["color1"] = np.array([specular], np.float32)
        elif item.name.startswith("texcoord"):
            n = int(item.name[8:])
            inputs[item.name] = np.array([(texcoords or {}).get(n, (0, 0, 0, 1))], np.float32)
        elif item.name == "fog":
            inputs["fog"] = np.array([[fog]], np.float32)
    samplers = {}
    for n, tex in (textures or {}).items():
        samplers[n] = tex if callable(tex) else constant_sampler(tex)
    return evaluate(pp.fragment, inputs, samplers, count=1).outputs["color0"][0]


def close(actual, expected, atol=1e-5):
    np.testing.assert_allclose(np.asarray(actual, np.float64), np.asarray(expected, np.float64),
                               atol=atol)


STAGE0 = """Texture[0] = <Tex0>; TextureFactor = 0xdd333333;
            ColorArg0[0] = Diffuse; ColorArg1[0] = Texture; ColorArg2[0] = TFactor;"""

# Colour results of every op at stage 0 with Arg0 = diffuse (1, 0, 0, 1/3), Arg1 = texture
# (0, 1, 0, 0.6), Arg2 = TFACTOR (0.2, 0.2, 0.2, 0xdd/255), worked out from the table.
AF = 0xDD / 255
OP_RESULTS = {
    "SelectArg1": (0, 1, 0),
    "SelectArg2": (0.2, 0.2, 0.2),
    "Modulate": (0, 0.2, 0),
    "Modulate2x": (0, 0.4, 0),
    "Modulate4x": (0, 0.8, 0),
    "Add": (0.2, 1, 0.2),                              # 1.2 saturates
    "AddSigned": (0, 0.7, 0),                          # 0.2 - 0.5 < 0 -> 0; 1.2 - 0.5
    "AddSigned2x": (0, 1, 0),                          # 2 * 0.7 = 1.4 -> 1
    "Subtract": (0, 0.8, 0),
    "AddSmooth": (0.2, 1, 0.2),                        # 1 + 0.2 - 0.2
    "BlendDiffuseAlpha": (0.2 * 2 / 3, 1 / 3 + 0.2 * 2 / 3, 0.2 * 2 / 3),
    "BlendTextureAlpha": (0.08, 0.68, 0.08),           # tex * 0.6 + tf * 0.4
    "BlendFactorAlpha": (0.2 * (1 - AF), AF + 0.2 * (1 - AF), 0.2 * (1 - AF)),
    "BlendTextureAlphaPM": (0.08, 1, 0.08),            # tex + tf * 0.4, saturated
    "BlendCurrentAlpha": (0.2 * 2 / 3, 1 / 3 + 0.2 * 2 / 3, 0.2 * 2 / 3),  # current = diffuse
    "ModulateAlpha_AddColor": (0.12, 1, 0.12),         # tex + 0.6 * tf
    "ModulateColor_AddAlpha": (0.6, 0.8, 0.6),         # tex * tf + 0.6
    "ModulateInvAlpha_AddColor": (0.08, 1, 0.08),      # 0.4 * tf + tex
    "ModulateInvColor_AddAlpha": (0.8, 0.6, 0.8),      # (1 - tex) * tf + 0.6
    "DotProduct3": (0.6, 0.6, 0.6),                    # 4 (0.15 - 0.15 + 0.15)
    "MultiplyAdd": (1, 0.2, 0),                        # diffuse + tex * tf
    "Lerp": (0, 0.2, 0.2),                             # diffuse * tex + (1 - diffuse) * tf
}


@pytest.mark.parametrize("op", sorted(OP_RESULTS))
def test_every_texture_op_matches_the_formula(op):
    pp = lower(f"{STAGE0} ColorOp[0] = {op};")
    close(shade(pp, textures={0: TEX})[:3], OP_RESULTS[op])


@pytest.mark.parametrize("op", sorted(OP_RESULTS))
def test_every_texture_op_within_one_step_on_an_8_bit_card(op):
    pp = lower(f"{STAGE0} ColorOp[0] = {op};", profile="geforce2")
    out = shade(pp, textures={0: TEX})[:3]
    close(out * 255, np.round(np.array(OP_RESULTS[op]) * 255), atol=1.0)
    close(out * 255, np.round(out * 255), atol=1e-3)  # on the 8-bit grid


def test_worked_check_bytes():
    # docs/reference/semantics.md: DOTPRODUCT3 = 0x99, MULTIPLYADD = 0xff3300
    dot = shade(lower(f"{STAGE0} ColorOp[0] = DotProduct3;", "geforce2"), textures={0: TEX})
    assert [round(x * 255) for x in dot[:3]] == [0x99] * 3
    mad = shade(lower(f"{STAGE0} ColorOp[0] = MultiplyAdd;", "geforce2"), textures={0: TEX})
    assert [round(x * 255) for x in mad[:3]] == [0xFF, 0x33, 0x00]


def test_current_at_stage_zero_is_diffuse_and_default_alpha_is_texture_alpha():
    pp = lower("Texture[0] = <Tex0>; ColorOp[0] = SelectArg1; ColorArg1[0] = Current;")
    close(shade(pp, textures={0: TEX}), (1, 0, 0, 0.6))


def test_dotproduct3_result_is_written_to_alpha():
    # semantics 1.4: dot3 of diffuse 0x408080c0 with TFACTOR 0xffffffff, ALPHAOP
    # SelectArg1(Diffuse) ignored; the next stage reads CURRENT | ALPHAREPLICATE.
    diffuse = argb(0x408080C0)
    dot = 4 * 0.5 * ((128 / 255 - 0.5) * 2 + (192 / 255 - 0.5))
    pp = lower("""TextureFactor = 0xffffffff;
        ColorOp[0] = DotProduct3; ColorArg1[0] = Diffuse; ColorArg2[0] = TFactor;
        AlphaOp[0] = SelectArg1; AlphaArg1[0] = Diffuse;
        ColorOp[1] = SelectArg1; ColorArg1[1] = Current | AlphaReplicate;""")
    out = shade(pp, diffuse=diffuse)
    close(out, (dot, dot, dot, dot))
    assert abs(dot - 0x40 / 255) > 0.2  # not the diffuse alpha


def test_complement_and_alpha_replicate():
    base = "Texture[0] = <Tex0>; ColorOp[0] = SelectArg1; AlphaOp[0] = SelectArg1;"
    both = shade(lower(base + "ColorArg1[0] = Texture | Complement | AlphaReplicate;"
                       "AlphaArg1[0] = Texture | Complement;"), textures={0: TEX})
    close(both, (0.4, 0.4, 0.4, 0.4))                  # (1 - 0.6) replicated
    comp = shade(lower(base + "ColorArg1[0] = Texture | Complement;"), textures={0: TEX})
    close(comp[:3], (1, 0, 1))
    rep = shade(lower(base + "ColorArg1[0] = Texture | AlphaReplicate;"), textures={0: TEX})
    close(rep[:3], (0.6, 0.6, 0.6))


def test_resultarg_temp_and_the_last_stage_writes_current():
    pp = lower("""Texture[0] = <Tex0>; TextureFactor = 0xdd333333;
        ColorOp[0] = SelectArg1; ColorArg1[0] = Texture; ResultArg[0] = Temp;
        ColorOp[1] = SelectArg1; ColorArg1[1] = TFactor;
        ColorOp[2] = Add; ColorArg1[2] = Current; ColorArg2[2] = Temp; ResultArg[2] = Temp;""")
    close(shade(pp, textures={0: TEX})[:3], (0.2, 1, 0.2))
    # temp starts at 0: reading it before any stage wrote it
    pp = lower("ColorOp[0] = Add; ColorArg1[0] = Diffuse; ColorArg2[0] = Temp;")
    close(shade(pp)[:3], DIFFUSE[:3])


def test_first_disabled_stage_ends_the_cascade():
    pp = lower("""Texture[0] = <Tex0>; ColorOp[0] = SelectArg1; ColorArg1[0] = Texture;
        ColorOp[1] = Disable; ColorOp[2] = SelectArg1; ColorArg1[2] = TFactor;""")
    close(shade(pp, textures={0: TEX})[:3], (0, 1, 0))
    pp = lower("ColorOp[0] = Disable; ColorOp[1] = SelectArg1; ColorArg1[1] = TFactor;")
    close(shade(pp), DIFFUSE)  # stage 0 disabled: diffuse, rgb and alpha


def test_alphaop_disable_passes_current_alpha_through():
    pp = lower("""Texture[0] = <Tex0>; TextureFactor = 0xdd333333;
        ColorOp[0] = SelectArg1; AlphaOp[0] = SelectArg1; AlphaArg1[0] = TFactor;
        ColorOp[1] = SelectArg1; ColorArg1[1] = Diffuse; AlphaOp[1] = Disable;""")
    close(shade(pp, textures={0: TEX}), (1, 0, 0, AF))


def test_missing_texture_rule_selects_current():
    # Default stage 0 (Modulate texture x current, alpha SelectArg1 texture), nothing bound:
    # colour and alpha both become SelectArg1(Current) = diffuse (Wine is_invalid_op).
    pp = lower("ColorOp[0] = Modulate;")
    close(shade(pp), DIFFUSE)
    assert pp.textures == () and pp.fragment.samplers == ()
    # SelectArg2 ignores a TEXTURE Arg1, so it is not replaced
    pp = lower("TextureFactor = 0xdd333333; ColorOp[0] = SelectArg2; ColorArg1[0] = Texture;"
               "ColorArg2[0] = TFactor;")
    close(shade(pp)[:3], (0.2, 0.2, 0.2))
    # Arg0 counts only for MultiplyAdd / Lerp
    pp = lower("TextureFactor = 0xdd333333; ColorOp[0] = MultiplyAdd; ColorArg0[0] = Texture;"
               "ColorArg1[0] = TFactor; ColorArg2[0] = TFactor;")
    close(shade(pp)[:3], DIFFUSE[:3])


def test_premodulate_multiplies_the_next_stage_current_by_its_texture():
    pp = lower("""Texture[1] = <Tex1>; TextureFactor = 0xdd333333;
        ColorOp[0] = PreModulate; ColorArg1[0] = TFactor;
        ColorOp[1] = SelectArg1; ColorArg1[1] = Current;""")
    close(shade(pp, textures={1: (0.5, 0.25, 1, 1)})[:3], (0.1, 0.05, 0.2))


def test_specular_add_after_the_cascade_leaves_alpha():
    pp = lower("SpecularEnable = TRUE; ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse;"
               "AlphaOp[0] = SelectArg1; AlphaArg1[0] = Diffuse;")
    close(shade(pp, diffuse=(0.5, 0.25, 0, 0.5), specular=(0.75, 0.25, 0.5, 1)),
          (1, 0.5, 0.5, 0.5))
    assert any(i.name == "color1" for i in pp.fragment.inputs)  # folded into the program
    # Specular as a stage argument
    pp = lower("ColorOp[0] = SelectArg1; ColorArg1[0] = Specular;")
    close(shade(pp, specular=(0.1, 0.2, 0.3, 0.4))[:3], (0.1, 0.2, 0.3))


def test_stage_constant():
    pp = lower("Constant[0] = 0x80402010; ColorOp[0] = SelectArg1; ColorArg1[0] = Constant;")
    close(shade(pp)[:3], (0x40 / 255, 0x20 / 255, 0x10 / 255))


# -- bump environment mapping -----------------------------------------------------------------

BUMP = """Texture[0] = <Tex0>; Texture[1] = <Tex1>;
    ColorOp[0] = {op}; ColorArg1[0] = Texture;
    BumpEnvMat00[0] = 0.5; BumpEnvMat01[0] = 0.25; BumpEnvMat10[0] = -0.125; BumpEnvMat11[0] = 1.0;
    ColorOp[1] = SelectArg1; ColorArg1[1] = Texture; AlphaOp[1] = SelectArg1;"""
BUMP_TEXEL = (0.4, -0.2, 16 / 63, 1)  # du, dv, L


def test_bumpenvmap_perturbs_the_next_stage_with_the_documented_matrix_order():
    pp = lower(BUMP.format(op="BumpEnvMap"))
    out = shade(pp, textures={0: BUMP_TEXEL, 1: coord_sampler}, texcoords={1: (0.3, 0.6, 0, 1)})
    # u' = u + M00 du + M10 dv = 0.3 + 0.2 + 0.025; v' = v + M01 du + M11 dv = 0.6 + 0.1 - 0.2
    close(out[:2], (0.525, 0.5))
    # the transposed matrix would give (0.45, 0.35)


def test_bumpenvmap_projected_divides_before_the_offset():
    pp = lower(BUMP.format(op="BumpEnvMap") + "TextureTransformFlags[1] = Count4 | Projected;")
    out = shade(pp, textures={0: BUMP_TEXEL, 1: coord_sampler}, texcoords={1: (0.6, 1.2, 0, 2)})
    close(out[:2], (0.525, 0.5))  # offset after: (0.3, 0.6) + offset; before: (0.4125, 0.55)


def test_bump_stage_outputs_nothing():
    pp = lower(BUMP.format(op="BumpEnvMap") + "ColorOp[1] = SelectArg2; ColorArg2[1] = Current;"
               "AlphaOp[0] = SelectArg1; AlphaArg1[0] = TFactor; ResultArg[0] = Temp;"
               "AlphaOp[1] = SelectArg1; AlphaArg1[1] = Current;")
    close(shade(pp, textures={0: BUMP_TEXEL, 1: (0, 0, 1, 1)}), DIFFUSE)


@pytest.mark.parametrize("scale, offset, factor", [
    (2.0, 0.1, 2 * 16 / 63 + 0.1),   # 0.608
    (10.0, 10.0, 1.0),               # 12.5 clamps to 1
    (1000.0, -1.0, 1.0),             # 253 clamps to 1
    (1.0, -0.5, 0.0),                # negative clamps to 0
])
def test_bumpenvmap_luminance_scales_the_texel_with_a_clamp(scale, offset, factor):
    pp = lower(BUMP.format(op="BumpEnvMapLuminance")
               + f"BumpEnvLScale[0] = {scale}; BumpEnvLOffset[0] = {offset};")
    out = shade(pp, textures={0: BUMP_TEXEL, 1: (0.5, 0.5, 0.5, 0.5)})
    close(out, [0.5 * factor] * 4)


def test_bump_uniforms_come_from_the_bump_stage():
    pp = lower(BUMP.format(op="BumpEnvMapLuminance")
               + "BumpEnvLScale[0] = 2.0; BumpEnvLOffset[0] = 0.1; BumpEnvMat00[1] = 9.0;")
    uniforms = dict(pp.uniforms)
    assert uniforms["bumpenv0_mat"] == (0.5, 0.25, -0.125, 1.0)
    close(uniforms["bumpenv0_lum"][:2], (2.0, 0.1))


# -- precision ----------------------------------------------------------------------------------

TWO_STAGES = """Texture[0] = <Tex0>; TextureFactor = 0xff808080;
    ColorOp[0] = Modulate; ColorArg1[0] = Texture; ColorArg2[0] = Diffuse;
    ColorOp[1] = Modulate4x; ColorArg1[1] = Current; ColorArg2[1] = TFactor;"""


def test_stage_results_are_held_at_8_bits_on_a_dx7_card():
    pp = lower(TWO_STAGES, profile="geforce2")
    assert sum(i.op == "quantize" for i in pp.fragment.instrs) == 2
    out = shade(pp, diffuse=(0.1, 0.1, 0.1, 1), textures={0: (0.3, 0.3, 0.3, 1)})
    # stage 0: 0.03 -> round(7.65) = 8/255; stage 1: 4 * 8/255 * 128/255 = 0.06299
    #  -> round(16.06) = 16/255
    close(out[:3], [16 / 255] * 3)


def test_stage_results_are_float_on_modern_and_refrast():
    for profile in ("modern", "refrast"):
        pp = lower(TWO_STAGES, profile=profile)
        assert not any(i.op == "quantize" for i in pp.fragment.instrs)
        out = shade(pp, diffuse=(0.1, 0.1, 0.1, 1), textures={0: (0.3, 0.3, 0.3, 1)})
        close(out[:3], [4 * 0.03 * 128 / 255] * 3)


# -- fog ------------------------------------------------------------------------------------------

def test_vertex_fog_blends_towards_the_fog_colour_and_keeps_alpha():
    pp = lower("FogEnable = TRUE; FogVertexMode = Linear; FogColor = 0x000000ff;"
               "ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse;"
               "AlphaOp[0] = SelectArg1; AlphaArg1[0] = Diffuse;")
    out = shade(pp, diffuse=(1, 0.5, 0, 0.5), fog=0.25)
    close(out, (0.25, 0.125, 0.75, 0.5))  # f c + (1 - f) fog colour
    assert dict(pp.uniforms)["fog_color"] == (0.0, 0.0, 1.0, 0.0)  # folded into the program


def test_table_fog_computes_the_factor_per_pixel():
    pp = lower("FogEnable = TRUE; FogTableMode = Linear; FogStart = 0.0; FogEnd = 4.0;"
               "FogColor = 0x00ffffff; ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse;")
    close(shade(pp, diffuse=(0, 0, 0, 1), fog=1.0)[:3], [0.25] * 3)  # f = (4 - 1) / 4
    pp = lower("FogEnable = TRUE; FogTableMode = Exp; FogDensity = 0.5;"
               "FogColor = 0x00ffffff; ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse;")
    close(shade(pp, diffuse=(0, 0, 0, 1), fog=2.0)[:3], [1 - np.exp(-1.0)] * 3, atol=1e-5)
    pp = lower("FogEnable = TRUE; FogTableMode = Exp2; FogDensity = 0.5;"
               "FogColor = 0x00ffffff; ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse;")
    # f = e^-((2 * 0.5)^2) = e^-1
    close(shade(pp, diffuse=(0, 0, 0, 1), fog=2.0)[:3], [1 - np.exp(-1.0)] * 3, atol=1e-5)
    # LINEAR saturates: a distance beyond FogEnd is all fog, one before FogStart none
    pp = lower("FogEnable = TRUE; FogTableMode = Linear; FogStart = 1.0; FogEnd = 3.0;"
               "FogColor = 0x00ffffff; ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse;")
    close(shade(pp, diffuse=(0, 0, 0, 1), fog=5.0)[:3], [1.0] * 3)
    close(shade(pp, diffuse=(0, 0, 0, 1), fog=0.5)[:3], [0.0] * 3)


def test_fog_with_no_mode_takes_the_factor_from_the_specular_alpha():
    """FogEnable with both modes NONE: the factor is the specular (color1) alpha (Wine's
    FOGCOORD case), so f = 0.25 blends three quarters of the fog colour in."""
    pp = lower("FogEnable = TRUE; FogColor = 0x0000ff00;"
               "ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse;")
    out = shade(pp, diffuse=(1, 0, 0, 1), specular=(0, 0, 0, 0.25))
    close(out[:3], (0.25, 0.75, 0.0))


def test_specular_is_added_before_fog():
    """Diffuse 0.5 grey + specular 0.25 red = (0.75, 0.5, 0.5); table fog f = 0.5 keeps half
    and adds half of the blue fog colour: (0.375, 0.25, 0.75); alpha stays the diffuse's."""
    pp = lower("SpecularEnable = TRUE; FogEnable = TRUE; FogTableMode = Linear; FogStart = 0.0;"
               "FogEnd = 1.0; FogColor = 0x000000ff; ColorOp[0] = SelectArg1;"
               "ColorArg1[0] = Diffuse; AlphaOp[0] = SelectArg1; AlphaArg1[0] = Diffuse;")
    out = shade(pp, diffuse=(0.5, 0.5, 0.5, 0.8), specular=(0.25, 0, 0, 0), fog=0.5)
    close(out, (0.375, 0.25, 0.75, 0.8))


def test_specular_add_saturates_and_fog_is_held_at_8_bits_on_a_dx7_card():
    """On a GeForce2 the specular add saturates (0.75 + 0.5 -> 1) and the fogged colour is
    quantised to 8 bits: f = (4 - 1) / 4 of 1.0 red plus a quarter of 0x40 blue
    = (0.75, 0, 16/255) -> round(191.25) / 255 and round(16) / 255."""
    pp = lower("SpecularEnable = TRUE; FogEnable = TRUE; FogTableMode = Linear; FogStart = 0.0;"
               "FogEnd = 4.0; FogColor = 0x00000040; ColorOp[0] = SelectArg1;"
               "ColorArg1[0] = Diffuse;", profile="geforce2")
    assert sum(i.op == "quantize" for i in pp.fragment.instrs) >= 2
    out = shade(pp, diffuse=(0.75, 0, 0, 1), specular=(0.5, 0, 0, 0), fog=1.0)
    close(out[:3], (191 / 255, 0, 16 / 255))


# -- texture bindings and coordinates -------------------------------------------------------------

def test_texture_bindings_carry_parameter_kind_and_sampler_states():
    pp = lower("""Texture[0] = <Env>; MinFilter[0] = Linear; MagFilter[0] = Linear;
        AddressU[0] = Clamp; ColorOp[0] = SelectArg1;""",
               params='texture Env < string Type = "CUBE"; >;')
    (binding,) = pp.textures
    assert (binding.sampler, binding.texture, binding.kind) == (0, "Env", "cube")
    assert (binding.min_filter, binding.mag_filter, binding.address_u, binding.address_v) == \
        ("LINEAR", "LINEAR", "CLAMP", "WRAP")
    assert pp.fragment.sampler(0).kind == "cube"


def test_projected_count3_divides_by_z():
    pp = lower("Texture[0] = <Tex0>; ColorOp[0] = SelectArg1;"
               "TextureTransformFlags[0] = Count3 | Projected;")
    out = shade(pp, textures={0: coord_sampler}, texcoords={0: (1.0, 0.5, 2.0, 7.0)})
    close(out[:2], (0.5, 0.25))


def test_state_persists_from_earlier_passes():
    effect = effects.load_effect("""texture Tex0;
        technique t {
            pass a { TextureFactor = 0xff336699; ColorOp[0] = SelectArg1; ColorArg1[0] = TFactor; }
            pass b { AlphaOp[0] = SelectArg1; AlphaArg1[0] = TFactor; }
        }""")
    pp = lower_pass(effect, effect.techniques[0], 1, load_profile("modern"))
    close(shade(pp), (0x33 / 255, 0x66 / 255, 0x99 / 255, 1))


# -- shaders, errors, cache -----------------------------------------------------------------------

def test_shader_pass_gets_its_constants_from_the_pass_state():
    # c0 from a float4 parameter, c1..c4 from a matrix parameter put in by columns; c5 unset.
    effect = effects.load_effect("""float4 Tint = {0.5, 0.25, 1.0, 1.0};
        float4x4 M = {1, 2, 3, 4,  5, 6, 7, 8,  9, 10, 11, 12,  13, 14, 15, 16};
        technique t { pass p {
            PixelShaderConstant[0] = <Tint>;
            VertexShaderConstant[1] = <M>;
            PixelShader = asm { ps_2_0 mov oC0, c0 };
            VertexShader = asm { vs_1_1 dcl_position v0 m4x4 oPos, v0, c1 mov oD0, c5 };
        } }""")
    pp = lower_pass(effect, effect.techniques[0], 0, load_profile("modern"))
    uniforms = dict(pp.uniforms)
    assert uniforms["ps_c0"] == (0.5, 0.25, 1.0, 1.0)
    assert uniforms["vs_c1"] == (1.0, 5.0, 9.0, 13.0)       # first column of M
    assert uniforms["vs_c4"] == (4.0, 8.0, 12.0, 16.0)
    assert uniforms["vs_c5"] == (0.0, 0.0, 0.0, 0.0)
    assert "vs_c0" not in uniforms and "ps_c1" not in uniforms
    close(shade(pp), (0.5, 0.25, 1.0, 1.0))


def test_hlsl_compile_of_a_missing_function_is_a_located_error():
    with pytest.raises(EffectError, match=r"X3501: 'f': entrypoint not found"):
        lower("PixelShader = compile ps_2_0 f();", technique="ps")


def test_bad_stage_op_value_is_located():
    with pytest.raises(EffectError) as info:
        lower("ColorOp[0] = 99;")
    assert info.value.line == 5


def test_cache_returns_the_same_program_until_a_parameter_changes():
    clear_cache()
    effect = effects.load_effect("""DWORD Factor = 0xff000000;
        technique t { pass p { TextureFactor = <Factor>; ColorOp[0] = SelectArg1;
                               ColorArg1[0] = TFactor; } }""")
    profile = load_profile("modern")
    first = lower_pass(effect, effect.techniques[0], 0, profile)
    assert lower_pass(effect, effect.techniques[0], 0, profile) is first
    effect.parameter("Factor").value = np.array(0xFF00FF00, dtype=np.int64)
    second = lower_pass(effect, effect.techniques[0], 0, profile)
    assert dict(second.uniforms)["tfactor"] == (0.0, 1.0, 0.0, 1.0)


# -- golden printed IR of the seeds' fixed-function setups ----------------------------------------
# Regenerate with EFFECTS_UPDATE_GOLDEN=1 after checking the diff by eye.

SEED_SETUPS = {
    # Boyd & Taylor, DX6 multitexture: MODULATE(Earth, Diffuse); BUMPENVMAP(BumpMap);
    # ADD(EnvMap, Current)
    "earth_bumpenvmap": ("g400", """
        Texture[0] = <EarthTexture>; TexCoordIndex[0] = 1;
        ColorOp[0] = Modulate; ColorArg1[0] = Texture; ColorArg2[0] = Diffuse;
        Texture[1] = <BumpMap>; TexCoordIndex[1] = 1;
        ColorOp[1] = BumpEnvMap; ColorArg1[1] = Texture; ColorArg2[1] = Current;
        BumpEnvMat00[1] = 0.5; BumpEnvMat01[1] = 0.0; BumpEnvMat10[1] = 0.0;
        BumpEnvMat11[1] = 0.5; BumpEnvLScale[1] = 4.0; BumpEnvLOffset[1] = 0.0;
        Texture[2] = <EnvMapTexture>; TexCoordIndex[2] = 0;
        ColorOp[2] = Add; ColorArg1[2] = Texture; ColorArg2[2] = Current;"""),
    # DOTPRODUCT3 of the normal map with the diffuse-encoded light vector, then MODULATE base
    "dot3": ("geforce2", """
        Texture[0] = <NormalMap>; Texture[1] = <ColorMap>;
        ColorOp[0] = DotProduct3; ColorArg1[0] = Texture; ColorArg2[0] = Diffuse;
        ColorOp[1] = Modulate; ColorArg1[1] = Texture; ColorArg2[1] = Current;"""),
    # Emboss: SELECTARG1 height map; ADDSIGNED with the complemented shifted height map
    "emboss": ("tnt2", """
        Texture[0] = <HeightMap>; Texture[1] = <HeightMap>;
        ColorOp[0] = SelectArg1; ColorArg1[0] = Texture;
        ColorOp[1] = AddSigned; ColorArg1[1] = Texture | Complement; ColorArg2[1] = Current;"""),
}


@pytest.mark.parametrize("name", sorted(SEED_SETUPS))
def test_golden_ir_of_seed_setups(name):
    profile, states = SEED_SETUPS[name]
    params = ("texture EarthTexture; texture BumpMap; texture EnvMapTexture; "
              "texture NormalMap; texture ColorMap; texture HeightMap;")
    pp = lower(states, profile=profile, params=params)
    text = (f"# {name} on {profile}\n" + str(pp.fragment) + "\n" + str(pp.vertex)
            + "\n" + "\n".join(f"binding {t.sampler}: {t.texture} {t.kind}" for t in pp.textures)
            + "\n")
    path = GOLDEN_DIR / f"{name}.txt"
    if UPDATE_GOLDEN:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    assert path.exists(), f"{path} is missing: run with EFFECTS_UPDATE_GOLDEN=1"
    assert text == path.read_text()


def test_lowering_draws_the_device_state_the_validation_checked():
    """With a Validation, pass 1 lowers from the state the validator kept for it (pass 0's
    TextureFactor persisting), and gives what playing the passes through gives."""
    from effects.validate.technique import validate_technique
    effect = effects.load_effect("""technique t {
        pass a { TextureFactor = 0xff336699; ColorOp[0] = SelectArg1; ColorArg1[0] = TFactor; }
        pass b { AlphaOp[0] = SelectArg1; AlphaArg1[0] = TFactor; } }""")
    technique, profile = effect.techniques[0], load_profile("modern")
    validation = validate_technique(effect, technique, profile)
    assert validation.pass_reports[1].state.get_color("TextureFactor") == argb(0xff336699)
    clear_cache()
    drawn = lower_pass(effect, technique, 1, profile, validation=validation)
    close(shade(drawn), argb(0xff336699))
    clear_cache()
    assert lower_pass(effect, technique, 1, profile) == drawn
    other = effects.load_effect("technique u { pass p { } }")
    clear_cache()
    with pytest.raises(ValueError, match="validation is of technique 'u'"):
        lower_pass(effect, technique, 0, profile,
                   validation=validate_technique(other, other.techniques[0], profile))


def test_cache_is_shared_by_runtime_copies_and_checks_only_what_the_pass_reads():
    from effects.host.runtime import Runtime
    clear_cache()
    effect = effects.load_effect("""DWORD Factor = 0xff000000; float Unused = 1;
        technique t { pass p { Lighting = False; TextureFactor = <Factor>; ColorOp[0] = SelectArg1;
                               ColorArg1[0] = TFactor; } }""")
    profile = load_profile("modern")
    first = Runtime(effect, profile, size=(4, 4))
    first.begin(); first.begin_pass(0)
    program = first._program
    first.end_pass(); first.end()
    again = Runtime(effect, profile, size=(4, 4))   # a fresh copy of the effect's parameters
    again.begin(); again.begin_pass(0)
    assert again._program is program
    again.effect.parameter("Unused").value = np.array(2.0, dtype=np.float32)
    again.commit_changes()
    assert again._program is program                # the pass never reads Unused
    again.set_value("Factor", 0xFF0000FF)
    again.commit_changes()
    assert again._program is not program
    assert dict(again._program.uniforms)["tfactor"] == (0.0, 0.0, 1.0, 1.0)
    again.end_pass(); again.end()
