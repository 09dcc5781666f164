"""The bundled effects on the 20 cards: which technique each card selects (D3DX order), the
DX6 → DX9 pattern of the chapter, and the matrix's JSON shape."""
from __future__ import annotations

from tests.paths import ROOT

import json

import pytest

import effects
from effects.d3d9.caps import list_profiles, load_profile
from effects.cli.report import matrix, validate_all
from effects.validate.select import find_valid_technique

FX = {p.stem: str(p.relative_to(ROOT)) for p in sorted((ROOT / "fxfiles").glob("*.fx"))}
CARDS = list_profiles()

DX6 = ["g400", "rage128", "tnt2", "voodoo3", "voodoo5"]
DX7 = ["geforce2", "geforce256", "geforce4mx", "i865g", "radeon7500"]
DX8 = ["geforce3", "geforce4ti", "radeon8500"]
DX9 = ["geforcefx5900", "gma900", "radeon9700", "geforce6800", "modern", "radeonx1800",
       "refrast"]


def row(**by_card) -> dict[str, tuple[str | None, int]]:
    """Expand {'dx6': (T, n), 'tnt2': (T2, m)} style keys into one entry per card."""
    groups = {"dx6": DX6, "dx7": DX7, "dx8": DX8, "dx9": DX9}
    out: dict[str, tuple[str | None, int]] = {}
    for key, value in by_card.items():
        for name in groups.get(key, [key]):
            out[name] = value
    assert sorted(out) == sorted(CARDS)
    return out


NONE = (None, 0)
# (technique, passes) per card, as read from each file's fallback chain and the cards' caps.
EXPECTED = {
    "brdf": row(dx6=NONE, dx7=NONE, dx8=("tec0", 1), dx9=("tec0", 1)),
    # ShadeMode = Phong needs D3DPSHADECAPS_COLORPHONGRGB, which only refrast reports
    "fast_phong": row(dx6=("Gouraud", 1), dx7=("Gouraud", 1), dx8=("Gouraud", 1),
                      dx9=("Gouraud", 1), refrast=("Phong", 1)),
    "hemisphere": row(dx6=("HemisphereVertex_vs11", 1), dx7=("HemisphereVertex_vs11", 1),
                      dx8=("HemisphereOcclusion_ps11", 1), dx9=("HemisphereOcclusion_ps11", 1)),
    # SM3 on the GeForce 6800 and the reference device (and the modern profile); ps_2_0 on
    # the other DX9 cards; fixed-function lighting below
    "multilight": row(dx6=("MultiLight_ff", 1), dx7=("MultiLight_ff", 1),
                      dx8=("MultiLight_ff", 1), geforcefx5900=("MultiLight_ps20", 1),
                      gma900=("MultiLight_ps20", 1), radeon9700=("MultiLight_ps20", 1),
                      geforce6800=("MultiLight_ps30", 1), modern=("MultiLight_ps30", 1),
                      radeonx1800=("MultiLight_ps30", 1), refrast=("MultiLight_ps30", 1)),
    "phong": row(dx6=("SingleTexture", 1), dx7=("Dot3_dx7", 1), dx8=("PerPixelPhong_ps11", 2),
                 dx9=("PerPixelPhong_ps20", 1)),
    # an R32F cube render target on refrast, modern and the ATI cards (R300's float cube maps,
    # caps_profiles/radeon9700.yaml); the GeForce FX and GMA 900 take the 8-bit linear-distance
    # cube, the GeForce 6800 its R16F cube (Shadow1_R32F runs wherever Shadow4_R32F does: never
    # selected)
    "shadows": row(dx6=("Lit_ff", 1), dx7=("Lit_ff", 1), dx8=("Lit_ff", 1),
                   geforcefx5900=("Shadow4_Linear8", 2), gma900=("Shadow4_Linear8", 2),
                   radeon9700=("Shadow4_R32F", 2), geforce6800=("Shadow4_R16F", 2),
                   radeonx1800=("Shadow4_R32F", 2), modern=("Shadow4_R32F", 2),
                   refrast=("Shadow4_R32F", 2)),
    "sdk8_style": row(dx6=("TDX6", 1), dx7=("TFF7", 1), geforce3=("TPS1", 1),
                      geforce4ti=("TPS1", 1), radeon8500=("TPS4", 1), dx9=("TPS4", 1)),
    # Marble_ps20 and Wood_ps20 compile HLSL (vs_1_1 + ps_2_0): every DX9 card runs them.
    # one HLSL function per stage, compiled for vs_2_0/ps_2_0, vs_1_1/ps_1_4 and ps_1_1: each
    # DX8 card runs the ps_1_x build its pixel shader version has
    "sdk9_hlsl": row(dx6=("Scene_ff", 1), dx7=("Scene_ff", 1), geforce3=("Scene_ps11", 1),
                     geforce4ti=("Scene_ps11", 1), radeon8500=("Scene_ps14", 1),
                     dx9=("Scene_ps20", 1)),
    "sdk9_style": row(dx6=("Marble_dx6", 1), dx7=("Marble_dx7", 1), dx8=("Marble_ps11", 1),
                      dx9=("Marble_ps20", 2)),
    "specular_bump": row(g400=("BumpEnvMap_dx6", 1), rage128=("Emboss_dx6", 2),
                         tnt2=("Emboss_dx6", 2), voodoo3=("Emboss_dx6", 2),
                         voodoo5=("Emboss_dx6", 2), dx7=("Dot3_dx7", 1),
                         dx8=("SpecularTable_ps11", 1), dx9=("Specular_ps20", 1)),
    "wood": row(dx6=NONE, dx7=NONE, dx8=NONE, dx9=("Wood_ps20", 1)),
}


@pytest.fixture(scope="module")
def loaded() -> dict[str, effects.Effect]:
    return {stem: effects.load_effect(str(ROOT / path)) for stem, path in FX.items()}


@pytest.fixture(scope="module")
def profiles():
    return [load_profile(n) for n in CARDS]


@pytest.fixture(scope="module")
def result(loaded, profiles):
    return matrix(loaded, profiles)


def test_every_bundled_effect_is_covered():
    assert sorted(FX) == sorted(EXPECTED)


@pytest.mark.parametrize("stem", sorted(EXPECTED))
def test_the_technique_each_card_selects(stem, result):
    got = {card: (cell["technique"], cell["passes"]) for card, cell in result[stem].items()}
    assert got == EXPECTED[stem]


def chosen_validation(effect, profile):
    tech = find_valid_technique(effect, profile)
    return next(v for v in validate_all(effect, profile) if v.technique is tech)


def valid_names(effect, name):
    return [v.technique.name for v in validate_all(effect, load_profile(name)) if v.ok]


# --- the pattern the seeds describe, stated per feature --------------------------------------------

def test_embm_runs_on_the_g400_and_the_radeons(loaded):
    bump = loaded["specular_bump"]
    for name in ("g400", "radeon7500", "radeon8500"):
        assert "BumpEnvMap_dx6" in valid_names(bump, name), name
    for name in ("tnt2", "voodoo3", "rage128", "geforce256", "geforce2", "geforce4mx", "i865g"):
        assert "BumpEnvMap_dx6" not in valid_names(bump, name), name


def test_dot3_runs_on_geforce256_geforce2_and_radeon_but_not_on_dx6_cards(loaded):
    for stem in ("specular_bump", "phong"):
        for name in ("geforce256", "geforce2", "radeon7500"):
            assert "Dot3_dx7" in valid_names(loaded[stem], name), (stem, name)
        for name in DX6:
            assert "Dot3_dx7" not in valid_names(loaded[stem], name), (stem, name)


def test_ps_1_1_on_geforce3_ps_1_4_on_radeon8500_ps_2_0_on_radeon9700_and_fx(loaded, profiles):
    sdk8, bump, phong = loaded["sdk8_style"], loaded["specular_bump"], loaded["phong"]
    gf3, r8500 = load_profile("geforce3"), load_profile("radeon8500")
    assert chosen_validation(sdk8, gf3).pass_reports[0].pixel_shader == "ps_1_1"
    assert chosen_validation(sdk8, r8500).pass_reports[0].pixel_shader == "ps_1_4"
    assert "TPS4" not in valid_names(sdk8, "geforce3") and "TPS4" not in valid_names(sdk8, "geforce4ti")
    for name in ("radeon9700", "geforcefx5900"):
        p = load_profile(name)
        assert chosen_validation(bump, p).pass_reports[0].pixel_shader == "ps_2_0"
        assert chosen_validation(phong, p).pass_reports[0].pixel_shader == "ps_2_0"
    for name in DX8:
        assert "Specular_ps20" not in valid_names(bump, name)


def test_the_gma900_runs_its_vertex_shaders_in_software(loaded):
    gma = load_profile("gma900")
    with_vs = []
    for stem, effect in loaded.items():
        if find_valid_technique(effect, gma) is None:
            continue
        for report in chosen_validation(effect, gma).pass_reports:
            if report.vertex_shader is not None:
                with_vs.append(stem)
                assert report.software_vertex_processing, stem
    assert {"hemisphere", "sdk8_style", "specular_bump"} <= set(with_vs)
    # a card with hardware vertex shaders of that version runs them in hardware
    r9700 = load_profile("radeon9700")
    hemi = chosen_validation(loaded["hemisphere"], r9700)
    assert [r.software_vertex_processing for r in hemi.pass_reports] == [False]


def test_dx6_and_dx7_cards_run_vs_1_1_fallbacks_in_software(loaded):
    hemi = loaded["hemisphere"]
    for name in DX6 + DX7:
        v = chosen_validation(hemi, load_profile(name))
        assert v.pass_reports[0].vertex_shader == "vs_1_1"
        assert v.pass_reports[0].software_vertex_processing


def test_every_chain_ending_in_fixed_function_renders_everywhere(result):
    for stem in ("hemisphere", "multilight", "phong", "sdk8_style", "sdk9_style",
                 "specular_bump"):
        assert all(cell["technique"] for cell in result[stem].values()), stem


# --- the JSON shape ------------------------------------------------------------------------------

def test_matrix_shape_and_rejected_reasons(result, loaded):
    assert list(result) == sorted(EXPECTED)
    for stem, cards in result.items():
        assert list(cards) == CARDS
        names = [t.name or "<anonymous>" for t in loaded[stem].techniques]
        for card, cell in cards.items():
            assert set(cell) == {"technique", "passes", "rejected"}
            assert set(cell["rejected"]) <= set(names)
            assert cell["technique"] not in cell["rejected"]
            for reasons in cell["rejected"].values():
                assert reasons and all(isinstance(r, str) and r.startswith("pass ") for r in reasons)
            # every technique before the chosen one was rejected (first-valid order)
            if cell["technique"] is not None:
                before = names[:names.index(cell["technique"])]
                assert before == [n for n in names if n in cell["rejected"]][:len(before)]
            else:
                assert sorted(cell["rejected"]) == sorted(names)
    json.dumps(result)   # plain JSON values only


def test_rejected_lists_every_reason_of_a_technique(result):
    tnt2 = result["specular_bump"]["tnt2"]["rejected"]["BumpEnvMap_dx6"]
    assert any("D3DTEXOPCAPS_BUMPENVMAP" in r for r in tnt2)
    assert any("3 stages are needed; the RIVA TNT2 has 2" in r for r in tnt2)
    assert any("reads 3 textures at once" in r for r in tnt2)
    assert any("format V8U8 for a texture" in r for r in tnt2)


def test_a_policy_refusal_is_listed_with_the_policys_reason(loaded, profiles):
    gf3 = [p for p in profiles if p.name == "geforce3"]
    res = matrix({"phong": loaded["phong"]}, gf3, "max-passes=1")
    cell = res["phong"]["geforce3"]
    assert (cell["technique"], cell["passes"]) == ("Dot3_dx7", 1)
    assert cell["rejected"]["PerPixelPhong_ps11"] == [
        "policy first,max-passes=1: the technique takes 2 passes; the policy allows at most 1"]
