"""Validation: for every card, a technique using exactly what the card has is valid and one
needing one more thing is rejected with that reason; then the rules that are the same on every
card (argument rules, persistence, quirks, unknown values, render targets, HLSL).

The per-card effects are built here from the card's own caps (its stage count, an op it has
and one it lacks ...), so the tests stay right when a profile changes.
"""
from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

import effects
from effects.d3d9.caps import BLENDCAPS, FORMATS, TEXOPCAPS, list_profiles, load_profile
from effects.validate.technique import spelled, validate_technique

CARDS = list_profiles()
PROFILES = {name: load_profile(name) for name in CARDS}
PS_VERSIONS = [(1, 1), (1, 2), (1, 3), (1, 4), (2, 0), (3, 0)]
VS_VERSIONS = [(1, 1), (2, 0), (3, 0)]

PS_SOURCE = {
    (1, 1): "ps_1_1\n tex t0\n mov r0, t0", (1, 2): "ps_1_2\n tex t0\n mov r0, t0",
    (1, 3): "ps_1_3\n tex t0\n mov r0, t0", (1, 4): "ps_1_4\n texld r0, t0",
    (2, 0): "ps_2_0\n dcl t0\n dcl_2d s0\n texld r0, t0, s0\n mov oC0, r0",
    (3, 0): "ps_3_0\n dcl_texcoord0 v0\n dcl_2d s0\n texld r0, v0, s0\n mov oC0, r0",
}
VS_SOURCE = {
    (1, 1): "vs_1_1\n dcl_position v0\n m4x4 oPos, v0, c0",
    (2, 0): "vs_2_0\n dcl_position v0\n m4x4 oPos, v0, c0",
    (3, 0): "vs_3_0\n dcl_position v0\n dcl_position o0\n m4x4 o0, v0, c0",
}


def card(name: str):
    return PROFILES[name]


def display(profile) -> str:
    return profile.display_name or profile.name


def line_of(source: str, snippet: str) -> int:
    """1-based line of the first line containing `snippet`."""
    for number, line in enumerate(source.splitlines(), 1):
        if snippet in line:
            return number
    raise AssertionError(f"{snippet!r} not in the source")


def effect_with_pass(body: str, params: str = "") -> tuple[effects.Effect, str]:
    """An effect whose one technique `T` has one pass `p0` with `body` (one state a line)."""
    source = textwrap.dedent(params) + "\ntechnique T\n{\n    pass p0\n    {\n"
    source += "".join(f"        {line.strip()}\n" for line in body.strip().splitlines())
    source += "    }\n}\n"
    return effects.load_effect(source), source


def validate(body: str, profile, params: str = ""):
    effect, source = effect_with_pass(body, params)
    return effect.validate("T", profile), source


def texture_params(n: int, extra: str = "") -> str:
    return "".join(f"texture T{i}{extra};\n" for i in range(n))


def cards_where(predicate) -> list[str]:
    chosen = [n for n in CARDS if predicate(card(n))]
    assert chosen, "the caps table has no card for this case"
    return chosen


def stage_op(profile) -> str:
    """An op every stage of these tests uses: one the card has."""
    for op in ("MODULATE", "SELECTARG1"):
        if profile.has("TextureOpCaps", op):
            return spelled("ColorOp", op)
    raise AssertionError(f"{profile.name} has neither MODULATE nor SELECTARG1")


def stages_body(profile, stages: int, textures: int = 0) -> str:
    """`stages` enabled stages; the first `textures` of them read a bound texture."""
    op = stage_op(profile)
    lines = []
    for s in range(stages):
        arg = "Texture" if s < textures else "Diffuse"
        lines += [f"ColorOp[{s}] = {op};", f"ColorArg1[{s}] = {arg};", f"ColorArg2[{s}] = Current;"]
        if s < textures:
            lines.append(f"Texture[{s}] = <T{s}>;")
    # the third texture of a card whose driver demands a bump op for it (G400): use that op
    for quirk in profile.quirks:
        if quirk.rule == "textures_need_op" and quirk.severity == "error" and textures > quirk.get("max_textures"):
            bump = next(o for o in quirk.get("ops") if profile.has("TextureOpCaps", o))
            lines.append(f"ColorOp[1] = {spelled('ColorOp', bump)};")
    if stages < 8:
        lines.append(f"ColorOp[{stages}] = Disable;")
    return "\n".join(lines)


# --- stages and textures, per card ---------------------------------------------------------------

@pytest.mark.parametrize("name", CARDS)
def test_exactly_the_cards_stage_count_is_valid(name):
    p = card(name)
    n = p.get("MaxTextureBlendStages")
    v, _ = validate(stages_body(p, n), p)
    assert v.ok, v.reasons
    assert v.passes == 1 and v.pass_reports[0].stages == n


@pytest.mark.parametrize("name", cards_where(lambda p: p.get("MaxTextureBlendStages") < 8))
def test_one_stage_more_than_the_card_has_is_rejected(name):
    p = card(name)
    n = p.get("MaxTextureBlendStages")
    v, source = validate(stages_body(p, n + 1), p)
    assert not v.ok
    r = v.reasons[0]
    assert (r.subject, r.requirement, r.card_value) == (
        f"ColorOp[{n}]", f"MaxTextureBlendStages >= {n + 1}", f"MaxTextureBlendStages {n}")
    assert r.location.line == line_of(source, f"ColorOp[{n}] =")
    assert str(r) == (f"pass p0 (line {r.location.line}): ColorOp[{n}] enables texture stage {n}, "
                      f"so {n + 1} stages are needed; the {display(p)} has {n}")


@pytest.mark.parametrize("name", CARDS)
def test_exactly_the_cards_texture_count_is_valid(name):
    p = card(name)
    n = p.get("MaxSimultaneousTextures")
    v, _ = validate(stages_body(p, n, textures=n), p, texture_params(n))
    assert v.ok, v.reasons
    assert v.pass_reports[0].textures == n


@pytest.mark.parametrize("name", cards_where(lambda p: p.get("MaxSimultaneousTextures") < 8))
def test_one_texture_more_than_the_card_binds_is_rejected(name):
    p = card(name)
    n = p.get("MaxSimultaneousTextures")
    v, source = validate(stages_body(p, n + 1, textures=n + 1), p, texture_params(n + 1))
    wanted = [r for r in v.reasons if r.requirement == f"MaxSimultaneousTextures >= {n + 1}"]
    assert len(wanted) == 1, v.reasons
    units = ", ".join(str(i) for i in range(n + 1))
    assert wanted[0].message == (f"this pass reads {n + 1} textures at once (stages {units}); "
                                 f"the {display(p)} can bind {n}")
    assert wanted[0].location.line == line_of(source, f"Texture[{n}] =")


# --- texture ops --------------------------------------------------------------------------------

@pytest.mark.parametrize("name", CARDS)
def test_every_texture_op_the_card_has_is_valid_at_stage_0(name):
    p = card(name)
    ops = sorted(b for b in TEXOPCAPS if b != "DISABLE" and p.has("TextureOpCaps", b))
    assert ops
    for op in ops:
        v, _ = validate(f"ColorOp[0] = {spelled('ColorOp', op)};\nColorArg1[0] = Diffuse;", p)
        assert v.ok, (op, v.reasons)


def lacking_op(p) -> str:
    return next(b for b in TEXOPCAPS if not p.has("TextureOpCaps", b))


@pytest.mark.parametrize("name", cards_where(lambda p: any(not p.has("TextureOpCaps", b) for b in TEXOPCAPS)))
def test_a_texture_op_the_card_lacks_is_rejected_with_that_reason(name):
    p = card(name)
    op = lacking_op(p)
    shown = spelled("ColorOp", op)
    v, source = validate(f"ColorOp[0] = {shown};\nColorArg1[0] = Diffuse;", p)
    line = line_of(source, "ColorOp[0] =")
    assert [str(r) for r in v.reasons] == [
        f"pass p0 (line {line}): ColorOp[0] = {shown} needs D3DTEXOPCAPS_{op}; "
        f"the {display(p)} does not have it"]
    assert v.reasons[0].card_value == "not in TextureOpCaps"


def test_the_issue_example_sentence_for_bumpenvmap_on_the_tnt2():
    v, source = validate("ColorOp[0] = Modulate;\nColorOp[1] = BumpEnvMap;\nColorOp[2] = Disable;",
                         card("tnt2"))
    line = line_of(source, "ColorOp[1] = BumpEnvMap")
    assert str(v.reasons[0]) == (f"pass p0 (line {line}): ColorOp[1] = BumpEnvMap needs "
                                 "D3DTEXOPCAPS_BUMPENVMAP; the RIVA TNT2 does not have it")


@pytest.mark.parametrize("name", CARDS)
def test_alpha_op_is_checked_like_colour_op(name):
    p = card(name)
    lacking = [b for b in TEXOPCAPS if not p.has("TextureOpCaps", b)]
    op = lacking[0] if lacking else "MODULATE"
    v, _ = validate(f"AlphaOp[0] = {spelled('AlphaOp', op)};\nAlphaArg1[0] = Diffuse;", p)
    assert [r.requirement for r in v.reasons] == ([f"D3DTEXOPCAPS_{op}"] if lacking else [])


# --- shader versions ----------------------------------------------------------------------------

# Shader Model 3 runs only with itself in hardware: the partner a ps_3_0 / vs_3_0 needs
PS3_PARTNER = ("\nVertexShader = asm\n{\nvs_3_0\n dcl_position v0\n dcl_position o0\n"
               " dcl_texcoord0 o1\n mov o0, v0\n mov o1, v0\n};")
VS3_PARTNER = "\nPixelShader = asm\n{\nps_3_0\n def c0, 1, 1, 1, 1\n mov oC0, c0\n};"


def ps_body(version) -> str:
    return ("PixelShader = asm\n{\n" + PS_SOURCE[version] + "\n};"
            + (PS3_PARTNER if version == (3, 0) else ""))


def vs_body(version, extra: str = "", partner: bool = False) -> str:
    source = VS_SOURCE[version] + extra
    return ("VertexShader = asm\n{\n" + source + "\n};"
            + (VS3_PARTNER if partner and version == (3, 0) else ""))


@pytest.mark.parametrize("name", cards_where(lambda p: p.pixel_shader_version > (0, 0)))
def test_a_pixel_shader_of_the_cards_own_version_is_valid(name):
    p = card(name)
    v, _ = validate(ps_body(p.pixel_shader_version), p)
    assert v.ok, v.reasons
    major, minor = p.pixel_shader_version
    assert v.pass_reports[0].pixel_shader == f"ps_{major}_{minor}"


@pytest.mark.parametrize("name", cards_where(lambda p: p.pixel_shader_version < (3, 0)))
def test_the_next_pixel_shader_version_is_rejected(name):
    p = card(name)
    have = p.pixel_shader_version
    nxt = next(v for v in PS_VERSIONS if v > have)
    v, source = validate(ps_body(nxt), p)
    label = f"ps_{nxt[0]}_{nxt[1]}"
    limit = (f"runs pixel shaders up to ps_{have[0]}_{have[1]}" if have > (0, 0)
             else "has no pixel shader hardware")
    assert [r.message for r in v.reasons] == [f"PixelShader is {label}; the {display(p)} {limit}"]
    assert v.reasons[0].requirement == f"PixelShaderVersion >= {nxt[0]}.{nxt[1]}"
    # located at the shader text (the line after `asm {`)
    assert v.reasons[0].location.line == line_of(source, label)


@pytest.mark.parametrize("name", cards_where(lambda p: p.vertex_shader_version > (0, 0)))
def test_a_vertex_shader_of_the_cards_version_runs_in_hardware(name):
    p = card(name)
    v, _ = validate(vs_body(p.vertex_shader_version, partner=True), p)
    assert v.ok, v.reasons
    assert v.pass_reports[0].software_vertex_processing is False


@pytest.mark.parametrize("name", cards_where(lambda p: p.vertex_shader_version < (3, 0)))
def test_a_newer_vertex_shader_runs_in_software_where_the_card_offers_it(name):
    p = card(name)
    assert p.vertex_processing & {"software", "mixed"}   # every bundled card offers it
    for version in (v for v in VS_VERSIONS if v > p.vertex_shader_version):
        v, _ = validate(vs_body(version), p)
        assert v.ok, (version, v.reasons)
        assert v.pass_reports[0].software_vertex_processing is True


def hardware_only_profile(tmp_path: Path, parent: str, extra: str = ""):
    path = tmp_path / f"{parent}_hw.yaml"
    path.write_text(f"inherit: {parent}\nname: {parent}_hw\nVertexProcessing: [hardware]\n{extra}")
    return load_profile(str(path))


def test_a_newer_vertex_shader_is_rejected_without_software_processing(tmp_path):
    p = hardware_only_profile(tmp_path, "geforce3")
    v, _ = validate(vs_body((2, 0)), p)
    assert [r.message for r in v.reasons] == [
        "VertexShader is vs_2_0; the GeForce3 runs vertex shaders up to vs_1_1 and it offers no "
        "software vertex processing"]


@pytest.mark.parametrize("name", cards_where(lambda p: p.vertex_shader_version > (0, 0)))
def test_vertex_shader_constants_up_to_the_cards_count(name, tmp_path):
    hw = hardware_only_profile(tmp_path, name)
    limit = hw.get("MaxVertexShaderConst")
    version = hw.vertex_shader_version
    ok, _ = validate(vs_body(version, f"\n mov r0, c{limit - 1}", partner=True), hw)
    assert ok.ok, ok.reasons
    over, source = validate(vs_body(version, f"\n mov r0, c{limit}", partner=True), hw)
    assert [(r.requirement, r.card_value) for r in over.reasons] == [
        (f"MaxVertexShaderConst >= {limit + 1}", f"MaxVertexShaderConst {limit}")]
    assert over.reasons[0].message == (f"the vertex shader reads constants up to c{limit}; "
                                       f"the {display(hw)} has MaxVertexShaderConst {limit}")
    # the real card (with software processing) runs the same shader on the CPU instead
    real = validate(vs_body(version, f"\n mov r0, c{limit}", partner=True), card(name))[0]
    assert real.ok and real.pass_reports[0].software_vertex_processing


# --- textures: kind, size, format, filters, addressing -------------------------------------------

@pytest.mark.parametrize("kind,bit,what", [("CUBE", "CUBEMAP", "a cube map"),
                                           ("3D", "VOLUMEMAP", "a volume texture")])
@pytest.mark.parametrize("name", CARDS)
def test_texture_kind_against_texture_caps(name, kind, bit, what):
    p = card(name)
    params = f'texture E < string Type = "{kind}"; >;'
    v, source = validate("Texture[0] = <E>;", p, params)
    if p.has("TextureCaps", bit):
        assert v.ok, v.reasons
    else:
        assert [r.message for r in v.reasons] == [
            f"Texture[0] = <E> ({what}) needs D3DPTEXTURECAPS_{bit}; the {display(p)} does not have it"]


def test_texture_kind_comes_from_the_sampler_type_when_the_texture_has_none():
    params = ("texture E;\nsamplerCUBE S = sampler_state { Texture = <E>; };")
    v, _ = validate("Sampler[0] = (S);", card("tnt2"), params)
    assert [r.requirement for r in v.reasons] == ["D3DPTEXTURECAPS_CUBEMAP"]


@pytest.mark.parametrize("name", CARDS)
def test_texture_size_up_to_the_cards_limit(name):
    p = card(name)
    w, h = p.get("MaxTextureWidth"), p.get("MaxTextureHeight")
    ok, _ = validate("Texture[0] = <T>;", p, f"texture T < int Width = {w}; int Height = {h}; >;")
    assert ok.ok, ok.reasons
    big, _ = validate("Texture[0] = <T>;", p, f"texture T < int Width = {2 * w}; int Height = {2 * h}; >;")
    assert [(r.requirement, r.card_value) for r in big.reasons] == [
        (f"MaxTextureWidth >= {2 * w}", f"MaxTextureWidth {w}"),
        (f"MaxTextureHeight >= {2 * h}", f"MaxTextureHeight {h}")]
    assert big.reasons[0].message == (f"Texture[0] = <T> is {2 * w} texels along one side; "
                                      f"the {display(p)} allows {w} (MaxTextureWidth)")


@pytest.mark.parametrize("name", CARDS)
def test_square_only_cards_reject_oblong_textures(name):
    p = card(name)
    v, _ = validate("Texture[0] = <T>;", p, "texture T < int Width = 128; int Height = 64; >;")
    ratio = p.get("MaxTextureAspectRatio")
    expected = (["square textures"] if p.has("TextureCaps", "SQUAREONLY") else []) + (
        ["MaxTextureAspectRatio >= 2"] if ratio is not None and ratio < 2 else [])
    assert [r.requirement for r in v.reasons] == expected


@pytest.mark.parametrize("name", CARDS)
def test_a_format_the_card_lists_is_valid_and_one_it_lacks_is_rejected(name):
    p = card(name)
    formats = p.get("TextureFormats") or {}
    has = sorted(f for f, usages in formats.items() if "texture" in usages)
    lacks = sorted(f for f in FORMATS if "texture" not in formats.get(f, ()))
    ok, _ = validate("Texture[0] = <T>;", p, f'texture T < string Format = "{has[0]}"; >;')
    assert ok.ok, ok.reasons
    bad, source = validate("Texture[0] = <T>;", p, f'texture T < string Format = "{lacks[0]}"; >;')
    assert [r.message for r in bad.reasons] == [
        f"Texture[0] = <T> uses the format {lacks[0]} for a texture; the {display(p)} does not support that"]
    assert bad.reasons[0].location.line == line_of(source, "string Format")


@pytest.mark.parametrize("name", CARDS)
def test_linear_filtering_needs_the_formats_filter_usage(name):
    p = card(name)
    formats = p.get("TextureFormats") or {}
    unfiltered = sorted(f for f, u in formats.items() if "texture" in u and "filter" not in u)
    filtered = sorted(f for f, u in formats.items() if "texture" in u and "filter" in u)
    for fmt in filtered[:1]:
        v, _ = validate("Texture[0] = <T>;\nMinFilter[0] = Linear;", p, f'texture T < string Format = "{fmt}"; >;')
        assert v.ok, v.reasons
    for fmt in unfiltered[:1]:
        v, _ = validate("Texture[0] = <T>;\nMinFilter[0] = Linear;", p, f'texture T < string Format = "{fmt}"; >;')
        assert [r.requirement for r in v.reasons] == [f"format {fmt} (filter)"]


def test_an_unknown_format_name_is_a_reason_not_a_crash():
    v, _ = validate("Texture[0] = <T>;", card("radeon9700"), 'texture T < string Format = "RGBA8"; >;')
    assert [r.message for r in v.reasons] == [
        "Texture[0] = <T> names the format 'RGBA8', which is not a Direct3D 9 format; "
        "the Radeon 9700 cannot create it"]


@pytest.mark.parametrize("name", CARDS)
def test_render_target_annotation_needs_the_rendertarget_usage(name):
    p = card(name)
    formats = p.get("TextureFormats") or {}
    rt = sorted(f for f, u in formats.items() if {"texture", "rendertarget"} <= u)
    tex_only = sorted(f for f, u in formats.items() if "texture" in u and "rendertarget" not in u)
    for fmt in rt[:1]:
        v, _ = validate("Texture[0] = <T>;", p, f'texture T < string Format = "{fmt}"; bool RenderTarget = true; >;')
        assert v.ok, v.reasons
    for fmt in tex_only[:1]:
        v, _ = validate("Texture[0] = <T>;", p, f'texture T < string Format = "{fmt}"; bool RenderTarget = true; >;')
        assert [r.message for r in v.reasons] == [
            f"Texture[0] = <T> uses the format {fmt} as a render target; the {display(p)} does not support that"]
    assert rt or tex_only


@pytest.mark.parametrize("name", CARDS)
def test_filters_against_filter_caps(name):
    p = card(name)
    for state, bit in (("MinFilter", "MINFANISOTROPIC"), ("MagFilter", "MAGFANISOTROPIC"),
                       ("MipFilter", "MIPFLINEAR")):
        value = "Anisotropic" if "ANISO" in bit else "Linear"
        v, _ = validate(f"Texture[0] = <T>;\n{state}[0] = {value};", p, "texture T;")
        expected = [] if p.has("TextureFilterCaps", bit) else [f"D3DPTFILTERCAPS_{bit}"]
        if state == "MipFilter" and not p.has("TextureCaps", "MIPMAP"):
            expected.append("D3DPTEXTURECAPS_MIPMAP")
        assert [r.requirement for r in v.reasons] == expected, (state, v.reasons)


@pytest.mark.parametrize("name", CARDS)
def test_max_anisotropy_up_to_the_cards_value(name):
    p = card(name)
    have = p.get("MaxAnisotropy", 1) or 1
    ok, _ = validate(f"Texture[0] = <T>;\nMaxAnisotropy[0] = {have};", p, "texture T;")
    assert ok.ok, ok.reasons
    over, _ = validate(f"Texture[0] = <T>;\nMaxAnisotropy[0] = {have + 1};", p, "texture T;")
    assert [r.message for r in over.reasons] == [
        f"MaxAnisotropy[0] = {have + 1}; the {display(p)} filters with at most {have}"]


@pytest.mark.parametrize("mode", ["Border", "MirrorOnce", "Mirror", "Clamp"])
@pytest.mark.parametrize("name", CARDS)
def test_address_modes_against_address_caps(name, mode):
    p = card(name)
    v, _ = validate(f"Texture[0] = <T>;\nAddressU[0] = {mode};", p, "texture T;")
    bit = mode.upper()
    assert [r.requirement for r in v.reasons] == (
        [] if p.has("TextureAddressCaps", bit) else [f"D3DPTADDRESSCAPS_{bit}"])


def test_non_power_of_two_textures_on_a_conditional_card_need_clamp_and_no_mipmaps():
    g400 = card("g400")   # POW2 | NONPOW2CONDITIONAL
    params = "texture T < int Width = 100; int Height = 64; >;"
    ok, _ = validate("Texture[0] = <T>;\nAddressU[0] = Clamp;\nAddressV[0] = Clamp;", g400, params)
    assert ok.ok, ok.reasons
    bad, _ = validate("Texture[0] = <T>;\nMipFilter[0] = Point;", g400, params)
    assert [r.subject for r in bad.reasons] == [
        "Texture[0] = <T> with AddressU[0] = Wrap", "Texture[0] = <T> with AddressV[0] = Wrap",
        "Texture[0] = <T> with MipFilter[0] = Point"]
    tnt2, _ = validate("Texture[0] = <T>;", card("tnt2"), params)   # POW2 only
    assert [r.message for r in tnt2.reasons] == [
        "Texture[0] = <T> is 100x64, not a power of two; the RIVA TNT2 needs power-of-two sizes"]


# --- frame-buffer states ---------------------------------------------------------------------------

@pytest.mark.parametrize("name", CARDS)
def test_blend_factors_against_blend_caps(name):
    p = card(name)
    for factor in BLENDCAPS:
        if factor == "BOTHSRCALPHA" or factor == "BOTHINVSRCALPHA":
            continue   # source-only factors: checked below against SrcBlendCaps
        shown = spelled("DestBlend", factor)
        v, _ = validate(f"AlphaBlendEnable = True;\nSrcBlend = One;\nDestBlend = {shown};", p)
        expected = [] if p.has("DestBlendCaps", factor) else [f"D3DPBLENDCAPS_{factor}"]
        expected = ([] if p.has("SrcBlendCaps", "ONE") else ["D3DPBLENDCAPS_ONE"]) + expected
        assert [r.requirement for r in v.reasons] == expected, factor
    v, _ = validate("AlphaBlendEnable = True;\nSrcBlend = BothSrcAlpha;", p)
    assert [r.requirement for r in v.reasons] == (
        [] if p.has("SrcBlendCaps", "BOTHSRCALPHA") else ["D3DPBLENDCAPS_BOTHSRCALPHA"])


def test_blend_states_are_not_checked_while_blending_is_off():
    v, _ = validate("AlphaBlendEnable = False;\nSrcBlend = BlendFactor;\nBlendOp = Max;", card("tnt2"))
    assert v.ok


@pytest.mark.parametrize("name", CARDS)
def test_blend_op_and_separate_alpha(name):
    p = card(name)
    v, _ = validate("AlphaBlendEnable = True;\nBlendOp = RevSubtract;", p)
    assert [r.requirement for r in v.reasons] == ([] if p.has("PrimitiveMiscCaps", "BLENDOP")
                                                  else ["D3DPMISCCAPS_BLENDOP"])
    v, _ = validate("AlphaBlendEnable = True;\nSeparateAlphaBlendEnable = True;", p)
    assert [r.requirement for r in v.reasons] == (
        [] if p.has("PrimitiveMiscCaps", "SEPARATEALPHABLEND") else ["D3DPMISCCAPS_SEPARATEALPHABLEND"])


@pytest.mark.parametrize("name", CARDS)
def test_alpha_test_and_depth_compare(name):
    p = card(name)
    v, _ = validate("AlphaTestEnable = True;\nAlphaFunc = Greater;\nZFunc = Always;", p)
    expected = ([] if p.has("AlphaCmpCaps", "GREATER") else ["D3DPCMPCAPS_GREATER"]) + (
        [] if p.has("ZCmpCaps", "ALWAYS") else ["D3DPCMPCAPS_ALWAYS"])
    assert [r.requirement for r in v.reasons] == expected


@pytest.mark.parametrize("name", CARDS)
def test_stencil(name):
    p = card(name)
    v, _ = validate("StencilEnable = True;\nStencilPass = Replace;", p)
    if not p.get("StencilCaps"):
        assert [r.message for r in v.reasons] == [
            f"StencilEnable needs a stencil buffer; the {display(p)} has none"]
        return
    assert [r.requirement for r in v.reasons] == ([] if p.has("StencilCaps", "REPLACE")
                                                  else ["D3DSTENCILCAPS_REPLACE"])
    v, _ = validate("StencilEnable = True;\nTwoSidedStencilMode = True;", p)
    assert [r.requirement for r in v.reasons] == ([] if p.has("StencilCaps", "TWOSIDED")
                                                  else ["D3DSTENCILCAPS_TWOSIDED"])


@pytest.mark.parametrize("name", CARDS)
def test_colour_write_mask(name):
    p = card(name)
    v, _ = validate("ColorWriteEnable = Red | Green;", p)
    assert [r.requirement for r in v.reasons] == (
        [] if p.has("PrimitiveMiscCaps", "COLORWRITEENABLE") else ["D3DPMISCCAPS_COLORWRITEENABLE"])
    full, _ = validate("ColorWriteEnable = Red | Green | Blue | Alpha;", p)
    assert full.ok


# --- render targets ------------------------------------------------------------------------------

def mrt_body(outputs: int) -> str:
    writes = "\n".join(f" mov oC{i}, r0" for i in range(outputs))
    return ("PixelShader = asm\n{\nps_2_0\n dcl t0\n dcl_2d s0\n texld r0, t0, s0\n"
            + writes + "\n};")


@pytest.mark.parametrize("name", cards_where(lambda p: p.pixel_shader_version >= (2, 0)))
def test_render_target_outputs_up_to_num_simultaneous_rts(name):
    p = card(name)
    n = p.get("NumSimultaneousRTs", 1)
    ok, _ = validate(mrt_body(n), p)
    assert ok.ok, ok.reasons
    assert ok.pass_reports[0].render_targets == n
    if n < 4:
        over, _ = validate(mrt_body(n + 1), p)
        assert [r.message for r in over.reasons] == [
            f"the pixel shader writes oC{n}, so {n + 1} render targets at once; "
            f"the {display(p)} has NumSimultaneousRTs {n}"]


@pytest.mark.parametrize("name", cards_where(lambda p: (p.get("NumSimultaneousRTs") or 1) > 1))
def test_blending_into_several_render_targets_needs_post_pixel_shader_blending(name):
    p = card(name)
    v, _ = validate(mrt_body(2) + "\nAlphaBlendEnable = True;", p)
    assert [r.requirement for r in v.reasons] == (
        [] if p.has("PrimitiveMiscCaps", "MRTPOSTPIXELSHADERBLENDING")
        else ["D3DPMISCCAPS_MRTPOSTPIXELSHADERBLENDING"])


# --- argument rules (the same on every card) ---------------------------------------------------------

def test_argument_modifiers_are_accepted_on_every_card():
    for name in CARDS:
        p = card(name)
        body = (f"ColorOp[0] = {stage_op(p)};\nColorArg1[0] = Diffuse | Complement;\n"
                "ColorArg2[0] = Current | AlphaReplicate;")
        v, _ = validate(body, p)
        assert v.ok, (name, v.reasons)


def test_result_arg_must_be_current_or_temp_without_modifiers():
    v, source = validate("ColorOp[0] = Modulate;\nResultArg[0] = Texture | Complement;", card("radeon9700"))
    line = line_of(source, "ResultArg[0]")
    assert [str(r) for r in v.reasons] == [
        f"pass p0 (line {line}): ResultArg[0] = Texture | Complement: a stage writes its result "
        "to Current or Temp only, without modifiers; no card accepts this"]


def test_temp_needs_tssargtemp_and_the_last_stage_must_write_current():
    body = ("ColorOp[0] = Modulate;\nResultArg[0] = Temp;\nColorOp[1] = Add;\n"
            "ColorArg1[1] = Temp;\nColorArg2[1] = Current;\nColorOp[2] = Disable;")
    for name in CARDS:
        p = card(name)
        v, _ = validate(body, p)
        need = [] if p.has("PrimitiveMiscCaps", "TSSARGTEMP") else ["D3DPMISCCAPS_TSSARGTEMP"] * 2
        need += [] if p.has("TextureOpCaps", "ADD") else ["D3DTEXOPCAPS_ADD"]
        assert sorted(r.requirement for r in v.reasons) == sorted(need), name
    last, _ = validate("ColorOp[0] = Modulate;\nResultArg[0] = Temp;", card("radeon9700"))
    assert [r.requirement for r in last.reasons] == ["D3DTA_CURRENT on the last active stage"]


# --- collecting, locating, persisting ----------------------------------------------------------------

def test_every_failure_is_collected_in_pass_order_with_its_location():
    params = 'texture T < string Type = "CUBE"; >;'
    body = ("ColorOp[0] = DotProduct3;\nColorOp[1] = BumpEnvMap;\nColorOp[2] = Modulate;\n"
            "ColorOp[3] = Disable;\nTexture[0] = <T>;\nAlphaBlendEnable = True;\nBlendOp = Max;")
    v, source = validate(body, card("tnt2"), params)
    got = [(r.subject, r.location.line) for r in v.reasons]
    assert got == [
        ("ColorOp[2]", line_of(source, "ColorOp[2]")),
        ("ColorOp[0] = DotProduct3", line_of(source, "ColorOp[0]")),
        ("ColorOp[1] = BumpEnvMap", line_of(source, "ColorOp[1]")),
        ("Texture[0] = <T> (a cube map)", line_of(source, "Texture[0]")),
        ("BlendOp = Max", line_of(source, "BlendOp")),
    ]
    assert all(r.technique == "T" and r.pass_name == "p0" for r in v.reasons)


def test_state_set_by_an_earlier_pass_persists_and_is_reported_in_each_pass():
    source = textwrap.dedent("""\
        technique T
        {
            pass first
            {
                ColorOp[0] = BumpEnvMap;
            }
            pass second
            {
                AlphaBlendEnable = True;
            }
        }
        """)
    effect = effects.load_effect(source)
    v = effect.validate("T", card("tnt2"))
    assert v.passes == 2
    line = line_of(source, "BumpEnvMap")
    assert [(r.pass_name, r.location.line) for r in v.reasons] == [("first", line), ("second", line)]


def test_a_technique_without_passes_is_valid_with_zero_passes():
    effect = effects.load_effect("technique Empty { }")
    v = effect.validate("Empty", card("tnt2"))
    assert v.ok and v.passes == 0 and v.reasons == []


# --- values unknown until the application sets them -------------------------------------------------

UNKNOWN_STATES = [
    "ColorOp[1]", "ColorArg1[0]", "AlphaOp[0]", "ResultArg[0]", "Texture[0]", "MinFilter[0]",
    "MipFilter[0]", "AddressU[0]", "MaxAnisotropy[0]", "AlphaBlendEnable", "SrcBlend", "BlendOp",
    "AlphaTestEnable", "AlphaFunc", "ZFunc", "StencilEnable", "StencilPass", "CullMode",
    "ColorWriteEnable", "PixelShader", "VertexShader", "TextureTransformFlags[0]",
]


@pytest.mark.parametrize("state", UNKNOWN_STATES)
@pytest.mark.parametrize("decl", ["int u;", "texture u;", "pixelshader u;"])
def test_a_state_bound_to_a_parameter_without_value_never_crashes(state, decl):
    body = f"ColorOp[0] = Modulate;\nTexture[0] = <T>;\n{state} = <u>;"
    effect, _ = effect_with_pass(body, decl + "\ntexture T;")
    wanted = {"Texture[0]": "texture u;", "PixelShader": "pixelshader u;",
              "VertexShader": "vertexshader u;"}.get(state, "int u;")
    for name in CARDS:
        v = validate_technique(effect, effect.techniques[0], card(name))
        # whatever else the card says, an unknown value of the right type is never a reason;
        # a parameter of the wrong type is the one reason about the state (issue 14)
        about = [r for r in v.reasons if r.subject.startswith(state)]
        if decl == wanted:
            assert about == [], v.reasons
        else:
            assert [r.message.split(";")[0] for r in about] == [f"{state} = <u> needs a "
                                                                f"{'number' if wanted == 'int u;' else wanted.split()[0]}"
                                                                + ("" if wanted == "int u;" else " parameter")], v.reasons
        assert all(str(r).startswith("pass p0 (line ") for r in v.reasons)


def test_an_unknown_op_is_noted_not_checked():
    v, _ = validate("ColorOp[0] = <u>;", card("tnt2"), "DWORD u;")
    assert v.ok
    assert v.notes == ["pass p0: ColorOp[0] is set from parameter u, which has no value: "
                       "not checked until the application sets it"]


def test_a_parameter_with_a_value_is_checked_with_that_value():
    v, _ = validate("ColorOp[0] = <u>;", card("tnt2"), "DWORD u = 24;")   # 24 = D3DTOP_DOTPRODUCT3
    assert [r.requirement for r in v.reasons] == ["D3DTEXOPCAPS_DOTPRODUCT3"]


# --- HLSL ---------------------------------------------------------------------------------------

HLSL = """
float4 PS(float2 uv : TEXCOORD0) : COLOR { return float4(uv, 0, 1); }
float4 VS(float4 p : POSITION) : POSITION { return p; }
"""


def test_hlsl_is_checked_by_profile_then_compiled_and_judged_by_its_assembly():
    body = "VertexShader = compile vs_1_1 VS();\nPixelShader = compile ps_2_0 PS();"
    on_gf3, _ = validate(body, card("geforce3"), HLSL)
    assert [r.message for r in on_gf3.reasons] == [
        "PixelShader is ps_2_0; the GeForce3 runs pixel shaders up to ps_1_1"]
    on_r300, _ = validate(body, card("radeon9700"), HLSL)
    assert on_r300.ok, on_r300.reasons
    on_gma, _ = validate(body, card("gma900"), HLSL)
    assert on_gma.ok and on_gma.pass_reports[0].software_vertex_processing


def test_hlsl_that_does_not_compile_rejects_the_technique_at_its_line():
    body = "PixelShader = compile ps_2_0 Bad();"
    source = "float4 Bad() : COLOR\n{\n    return foo;\n}\n"
    v, _ = validate(body, card("radeon9700"), source)
    assert not v.ok
    assert [r.message for r in v.reasons] == ["X3004: undeclared identifier 'foo'"]
    assert (v.reasons[0].location.line, v.reasons[0].location.column) == (3, 12)


# --- quirks ---------------------------------------------------------------------------------------

def test_g400_third_texture_only_as_a_bump_map():
    g400 = card("g400")
    quirk = next(q for q in g400.quirks if q.id == "third-texture-bump-only")
    three = stages_body(g400, 3)   # no textures yet
    body = three + "\n" + "\n".join(f"ColorArg1[{s}] = Texture;\nTexture[{s}] = <T{s}>;" for s in range(3))
    v, source = validate(body, g400, texture_params(3))
    assert [r.message for r in v.reasons] == [f"3 textures in one pass: {quirk.text} (Matrox G400)"]
    assert v.reasons[0].location.line == line_of(source, "Texture[2] =")
    with_bump, _ = validate(body + "\nColorOp[1] = BumpEnvMap;", g400, texture_params(3))
    assert with_bump.ok, with_bump.reasons


@pytest.mark.parametrize("name", ["g400", "rage128"])
def test_modulatealpha_addcolor_with_a_texture_as_second_argument(name):
    p = card(name)
    base = "ColorOp[0] = ModulateAlpha_AddColor;\nColorArg1[0] = Diffuse;\nTexture[0] = <T>;\n"
    bad, _ = validate(base + "ColorArg2[0] = Texture;", p, "texture T;")
    assert [r.requirement for r in bad.reasons] == ["driver rule modalpha-addcolor-texture-arg2"]
    assert bad.reasons[0].subject == "ColorOp[0] = ModulateAlpha_AddColor with ColorArg2[0] = Texture"
    good, _ = validate(base + "ColorArg2[0] = Current;", p, "texture T;")
    assert good.ok


def test_warning_quirks_are_reported_but_reject_nothing():
    voodoo3 = card("voodoo3")
    v, _ = validate(stages_body(voodoo3, 2, textures=2), voodoo3, texture_params(2))
    assert v.ok
    quirk = next(q for q in voodoo3.quirks if q.id == "dx8-multitexture")
    assert [w.message for w in v.warnings] == [f"2 textures in one pass: {quirk.text} (Voodoo3)"]


def test_a_format_marked_unreliable_warns():
    gf3 = card("geforce3")
    quirk = next(q for q in gf3.quirks if q.rule == "format_unreliable")
    v, _ = validate("Texture[0] = <T>;", gf3, f'texture T < string Format = "{quirk.get("format")}"; >;')
    assert v.ok
    assert [w.requirement for w in v.warnings] == [f"driver rule {quirk.id}"]


def test_an_unreliable_cap_with_severity_error_rejects(tmp_path):
    path = tmp_path / "flaky.yaml"
    path.write_text(textwrap.dedent("""\
        inherit: tnt2
        name: flaky
        Quirks:
          - {id: broken-addsigned, rule: cap_unreliable, field: TextureOpCaps, bit: ADDSIGNED, text: "AddSigned is reported but renders black", source: "test"}
        """))
    flaky = load_profile(str(path))
    v, _ = validate("ColorOp[0] = AddSigned;", flaky)
    assert [r.message for r in v.reasons] == [
        "ColorOp[0] = AddSigned: AddSigned is reported but renders black (RIVA TNT2)"]
    assert validate("ColorOp[0] = Add;", flaky)[0].ok


def test_an_op_stages_quirk_rejects_the_op_at_other_stages(tmp_path):
    path = tmp_path / "stage0.yaml"
    path.write_text(textwrap.dedent("""\
        inherit: radeon7500
        name: stage0
        Quirks:
          - {id: bump-stage, rule: op_stages, op: BUMPENVMAP, stages: [1], text: "BumpEnvMap only at stage 1", source: "test"}
        """))
    p = load_profile(str(path))
    assert validate("ColorOp[0] = Modulate;\nColorOp[1] = BumpEnvMap;", p)[0].ok
    v, _ = validate("ColorOp[0] = BumpEnvMap;", p)
    assert [r.message for r in v.reasons] == ["ColorOp[0] = BumpEnvMap: BumpEnvMap only at stage 1 (Radeon 7500)"]


# --- a texture kind implied by the lookup (DX8 files cannot declare it) -------------------------------

REFLECTION = ("ColorOp[0] = SelectArg1;\nColorArg1[0] = Texture;\nTexture[0] = <E>;\n"
              "TexCoordIndex[0] = CameraSpaceReflectionVector;\nTextureTransformFlags[0] = Count3;")


@pytest.mark.parametrize("name", CARDS)
def test_camera_space_3d_coordinates_imply_a_cube_map(name):
    p = card(name)
    v, _ = validate(REFLECTION, p, "texture E;")
    if p.has("TextureCaps", "CUBEMAP"):
        assert v.ok, v.reasons
    else:
        assert [r.subject for r in v.reasons] == [
            "Texture[0] = <E> (a cube map, looked up with 3-component camera-space texture coordinates)"]
    # two coordinates (or a declared 2D texture) are an ordinary 2D lookup
    flat, _ = validate(REFLECTION.replace("Count3", "Count2"), p, "texture E;")
    declared, _ = validate(REFLECTION, p, 'texture E < string Type = "2D"; >;')
    assert flat.ok and declared.ok


def no_cube_profile(tmp_path: Path, parent: str):
    base = card(parent)
    bits = sorted(b for b in ("PERSPECTIVE", "POW2", "ALPHA", "MIPMAP", "PROJECTED", "VOLUMEMAP")
                  if base.has("TextureCaps", b))
    path = tmp_path / f"{parent}_nocube.yaml"
    path.write_text(f"inherit: {parent}\nname: {parent}_nocube\nTextureCaps: [{', '.join(bits)}]\n")
    return load_profile(str(path))


def test_texm3x3_lookups_and_dcl_cube_imply_a_cube_map(tmp_path):
    ps11 = ("PixelShader = asm\n{\nps_1_1\n tex t0\n texm3x3pad t1, t0\n texm3x3pad t2, t0\n"
            " texm3x3tex t3, t0\n mov r0, t3\n};\nTexture[3] = <E>;")
    assert validate(ps11, card("geforce3"), "texture E;")[0].ok
    v, _ = validate(ps11, no_cube_profile(tmp_path, "geforce3"), "texture E;")
    assert [r.subject for r in v.reasons] == ["Texture[3] = <E> (a cube map, read by texm3x3tex t3)"]
    ps20 = ("PixelShader = asm\n{\nps_2_0\n dcl t0\n dcl_cube s1\n texld r0, t0, s1\n mov oC0, r0\n};\n"
            "Texture[1] = <E>;")
    assert validate(ps20, card("radeon9700"), "texture E;")[0].ok
    v, _ = validate(ps20, no_cube_profile(tmp_path, "radeon9700"), "texture E;")
    assert [r.subject for r in v.reasons] == ["Texture[1] = <E> (a cube map, declared by dcl_cube s1)"]


@pytest.mark.parametrize("card_name, body, reason", [
    ("geforce6800", ps_body((3, 0)).replace(PS3_PARTNER, ""),
     "PixelShader (ps_3_0) runs with the fixed-function vertex pipeline"),
    ("geforce6800", ps_body((3, 0)).replace(PS3_PARTNER, "") + vs_body((2, 0)),
     "PixelShader (ps_3_0) runs with a vs_2_0 vertex shader"),
    ("geforce6800", vs_body((3, 0)) + ps_body((2, 0)),
     "VertexShader (vs_3_0) runs with a ps_2_0 pixel shader"),
    ("geforce6800", vs_body((3, 0)),
     "VertexShader (vs_3_0) runs with the fixed-function pixel pipeline"),
    ("radeon9700", vs_body((3, 0)) + ps_body((2, 0)), None),    # vs_3_0 in software: any ps
    ("geforce6800", vs_body((3, 0), partner=True), None),
])
def test_shader_model_3_runs_only_with_itself_in_hardware(card_name, body, reason):
    v, _ = validate(body, card(card_name))
    want = [] if reason is None else [
        f"{reason}; Shader Model 3 shaders run only with each other in hardware (a vs_3_0 in "
        "software vertex processing excepted)"]
    assert [r.message for r in v.reasons] == want


def test_many_cards_at_once_answer_as_each_card_alone():
    """`validate_on_cards` makes what the stage, sampler and frame-buffer checks ask of a pass
    once for all the cards; each card's reasons, warnings and notes (those of states set from
    parameters without a value too, in order) are what validating on that card alone gives."""
    from effects.validate.technique import validate_on_cards
    effect = effects.load_effect(textwrap.dedent("""
        int Op; int Filter; int Blend; texture Tex;
        sampler S = sampler_state { Texture = <Tex>; MinFilter = <Filter>; MagFilter = Anisotropic;
                                    MipFilter = Linear; MaxAnisotropy = 16; AddressU = Border; };
        technique T {
            pass P0 { ColorOp[0] = BumpEnvMap; ColorArg1[0] = Texture; ColorArg2[0] = Temp;
                      AlphaOp[0] = <Op>; ColorOp[1] = DotProduct3; ColorArg1[1] = Constant;
                      Texture[0] = <Tex>; MinFilter[0] = <Filter>; MagFilter[0] = Anisotropic;
                      MipFilter[0] = Linear; MaxAnisotropy[0] = 16; AddressU[0] = MirrorOnce;
                      AlphaBlendEnable = TRUE; SrcBlend = <Blend>; DestBlend = BlendFactor;
                      BlendOp = Max; StencilEnable = TRUE; StencilFunc = Equal;
                      StencilPass = IncrSat; CullMode = CW; ZFunc = <Op>; }
            pass P1 { ColorOp[0] = Modulate; AlphaBlendEnable = FALSE; }
        }"""))
    cards = [PROFILES[name] for name in CARDS]
    together = validate_on_cards(effect, effect.techniques[0], cards)
    rejected = 0
    for card, v in zip(cards, together):
        alone = validate_technique(effect, effect.techniques[0], card)
        assert [str(r) for r in v.reasons] == [str(r) for r in alone.reasons], card.name
        assert [str(r) for r in v.warnings] == [str(r) for r in alone.warnings], card.name
        assert v.notes == alone.notes and v.notes, card.name
        rejected += not v.ok
    # the checks ran and cards differ: the DX6-DX8 parts lack some of it, the DX9 ones not
    assert 0 < rejected < len(cards)
    assert any("BUMPENVMAP" in r.requirement for v in together for r in v.reasons)
    # the notes of the card-free part, P1 inheriting P0's unset states: seven on every card
    assert len(together[0].notes) == 7 and "MinFilter[0] is set from parameter Filter" in together[0].notes[1]
