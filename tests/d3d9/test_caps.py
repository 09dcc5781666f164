"""Caps profiles: the bundled cards, the historical record they must match, and located errors."""
from __future__ import annotations

import re
import textwrap
from pathlib import Path

import pytest

from effects import ProfileError
from effects.d3d9.caps import (GENERATIONS, PROFILE_DIR, TEXOPCAPS, bits_mask, list_profiles,
                          load_profile)

ALL_CARDS = ["tnt2", "voodoo3", "voodoo5", "rage128", "g400", "geforce256", "geforce2",
             "geforce4mx", "radeon7500", "i865g", "geforce3", "geforce4ti", "radeon8500",
             "radeon9700", "geforcefx5900", "gma900", "geforce6800", "refrast", "modern",
             "radeonx1800"]

# A complete minimal profile; tests append or replace lines to break it at known places.
MINIMAL = """\
generation: dx6
VendorId: 0x1234
DeviceId: 0x0001
MaxTextureBlendStages: 2
MaxSimultaneousTextures: 2
TextureOpCaps: [DISABLE, MODULATE]
VertexShaderVersion: "0.0"
PixelShaderVersion: "0.0"
VertexProcessing: [software]
"""


def write(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / f"{name}.yaml"
    path.write_text(textwrap.dedent(text))
    return path


def error_of(path: Path) -> ProfileError:
    with pytest.raises(ProfileError) as info:
        load_profile(str(path))
    return info.value


# --- the bundled set --------------------------------------------------------------------------

def test_list_profiles_names_the_twenty_cards_by_generation_then_name():
    names = list_profiles()
    assert sorted(names) == sorted(ALL_CARDS)
    assert names == [
        "g400", "rage128", "tnt2", "voodoo3", "voodoo5",
        "geforce2", "geforce256", "geforce4mx", "i865g", "radeon7500",
        "geforce3",
        "geforce4ti", "radeon8500",
        "geforcefx5900", "gma900", "radeon9700",
        "geforce6800", "modern", "radeonx1800", "refrast",
    ]


@pytest.mark.parametrize("card", ALL_CARDS)
def test_every_bundled_profile_loads_and_passes_the_schema(card):
    profile = load_profile(card)
    assert profile.name == card
    assert profile.generation in GENERATIONS
    assert profile.display_name and profile.description
    assert profile.get("MaxSimultaneousTextures") <= profile.get("MaxTextureBlendStages")
    assert Path(profile.path) == PROFILE_DIR / f"{card}.yaml"


# Lines that carry a value must say where it came from (source/derived) or why (inferred).
_PROVENANCE = re.compile(r"#\s*(source|inferred|derived):")
_METADATA = ("name:", "display_name:", "description:", "inherit:")


@pytest.mark.parametrize("card", ALL_CARDS)
def test_every_value_in_a_bundled_profile_carries_its_provenance(card):
    missing = []
    for number, line in enumerate((PROFILE_DIR / f"{card}.yaml").read_text().splitlines(), 1):
        code = line.split("#", 1)[0].strip()
        if not code or code.startswith(_METADATA) or re.fullmatch(r"[\w.]+:", code):
            continue  # comments, identity, block starts (`TextureFormats:`)
        if not _PROVENANCE.search(line):
            missing.append(f"{card}.yaml:{number}: {line.strip()}")
    assert missing == []


# --- the historical record ----------------------------------------------------------------------

# card: (BUMPENVMAP, DOTPRODUCT3, pixel shader, hardware vertex shader)
RECORD = {
    "tnt2": (False, False, (0, 0), (0, 0)),
    "voodoo3": (False, False, (0, 0), (0, 0)),
    "voodoo5": (False, False, (0, 0), (0, 0)),
    "rage128": (False, False, (0, 0), (0, 0)),
    "g400": (True, False, (0, 0), (0, 0)),
    "geforce256": (False, True, (0, 0), (0, 0)),
    "geforce2": (False, True, (0, 0), (0, 0)),
    "geforce4mx": (False, True, (0, 0), (0, 0)),
    "radeon7500": (True, True, (0, 0), (0, 0)),
    "i865g": (False, True, (0, 0), (0, 0)),
    "geforce3": (True, True, (1, 1), (1, 1)),
    "geforce4ti": (True, True, (1, 3), (1, 1)),
    "radeon8500": (True, True, (1, 4), (1, 1)),
    "radeon9700": (True, True, (2, 0), (2, 0)),
    "geforcefx5900": (True, True, (2, 0), (2, 0)),
    "gma900": (True, True, (2, 0), (0, 0)),
    "geforce6800": (True, True, (3, 0), (3, 0)),
    "refrast": (True, True, (3, 0), (3, 0)),
    "modern": (True, True, (3, 0), (3, 0)),
    "radeonx1800": (True, True, (3, 0), (3, 0)),
}


@pytest.mark.parametrize("card", ALL_CARDS)
def test_bump_ops_and_shader_versions_follow_the_record(card):
    embm, dot3, ps, vs = RECORD[card]
    profile = load_profile(card)
    assert profile.has("TextureOpCaps", "BUMPENVMAP") is embm
    assert profile.has("TextureOpCaps", "DOTPRODUCT3") is dot3
    assert profile.pixel_shader_version == ps
    assert profile.vertex_shader_version == vs


def test_tnt2_is_a_two_stage_two_texture_card():
    tnt2 = load_profile("tnt2")
    assert tnt2.get("MaxTextureBlendStages") == 2
    assert tnt2.get("MaxSimultaneousTextures") == 2
    assert not tnt2.hardware_tnl
    assert tnt2.format_usages("V8U8") == frozenset()


def test_g400_can_run_the_three_stage_dx6_bumpenvmap_earth():
    # Boyd ch.5: MODULATE(earth, diffuse); BUMPENVMAP(bump map); ADD(env map, current).
    g400 = load_profile("g400")
    assert g400.get("MaxTextureBlendStages") >= 3
    assert g400.get("MaxSimultaneousTextures") >= 3
    assert all(g400.has("TextureOpCaps", op) for op in ("MODULATE", "BUMPENVMAP", "ADD"))
    assert {"texture", "filter"} <= g400.format_usages("D3DFMT_V8U8")
    # Its third texture is only for the bump map: the quirk allows three with a bump stage.
    rule = next(q for q in g400.quirks if q.rule == "textures_need_op")
    assert rule.get("max_textures") == 2 and "BUMPENVMAP" in rule.get("ops")


@pytest.mark.parametrize("card", ["g400", "rage128"])
def test_modulatealpha_addcolor_is_reported_but_cannot_take_a_texture_second(card):
    profile = load_profile(card)
    assert profile.has("TextureOpCaps", "MODULATEALPHA_ADDCOLOR")
    quirk = next(q for q in profile.quirks if q.rule == "arg_not_texture")
    assert (quirk.get("op"), quirk.get("arg"), quirk.severity) == ("MODULATEALPHA_ADDCOLOR", 2,
                                                                    "error")
    assert "caps.md" in quirk.source


def test_gma900_runs_vertex_shaders_only_in_software():
    gma = load_profile("gma900")
    assert gma.vertex_shader_version == (0, 0)
    assert gma.vertex_processing == frozenset({"software"})
    assert gma.software_vertex_shader_version == (3, 0)
    assert not gma.hardware_tnl
    assert gma.pixel_shader_version == (2, 0)


def test_refrast_and_modern_have_every_texture_op_and_shader_model_3():
    for card in ("refrast", "modern"):
        profile = load_profile(card)
        assert profile.get("TextureOpCaps") == frozenset(TEXOPCAPS)
        # Every D3DTEXOPCAPS bit from DISABLE (0x1) to LERP (0x2000000): 26 bits, all set.
        assert bits_mask("TextureOpCaps", profile.get("TextureOpCaps")) == 0x3FFFFFF
        assert profile.get("PS20Caps")["NumTemps"] == 32
        assert profile.precision("ps_2_0").format == "fp32"
    modern = load_profile("modern")
    assert {"texture", "rendertarget", "filter", "blend"} <= modern.format_usages("R32F")
    assert modern.get("MaxPixelShaderValue") > 1e38  # FLT_MAX: no ps_1_x clamp


def test_precision_separates_nvidia_dx8_from_ati_dx8_and_dx9():
    gf3, r8500, r9700 = (load_profile(n) for n in ("geforce3", "radeon8500", "radeon9700"))
    assert (gf3.precision("ps_1_x").range, gf3.precision("ps_1_x").bits) == (1.0, 8)
    assert gf3.get("MaxPixelShaderValue") == 1.0
    assert (r8500.precision("ps_1_4").range, r8500.precision("ps_1_4").bits) == (8.0, 12)
    assert r8500.get("PixelShader1xMaxValue") == 8.0  # the D3DCAPS9 spelling finds it too
    assert r9700.precision("ps_2_0").format == "fp24" and r9700.precision("ps_2_0").is_float
    assert load_profile("tnt2").precision("ps_1_x") is None


def test_ps20caps_tell_plain_ps_2_0_from_ps_2_a():
    r9700, fx = load_profile("radeon9700"), load_profile("geforcefx5900")
    assert r9700.get("PS20Caps")["NumInstructionSlots"] == 96
    assert r9700.get("PS20Caps")["Caps"] == frozenset()
    assert fx.get("PS20Caps")["NumInstructionSlots"] == 512
    assert "ARBITRARYSWIZZLE" in fx.get("PS20Caps")["Caps"]


# --- helpers, inheritance, caching ------------------------------------------------------------

def test_has_accepts_the_header_prefix_and_rejects_unknown_bits():
    g400 = load_profile("g400")
    assert g400.has("TextureOpCaps", "D3DTEXOPCAPS_BUMPENVMAP")
    assert not g400.has("TextureCaps", "CUBEMAP")
    with pytest.raises(ValueError):
        g400.has("TextureOpCaps", "BUMPMAP")
    with pytest.raises(ValueError):
        g400.has("MaxTextureWidth", "X")


def test_profiles_are_cached_and_read_only():
    assert load_profile("geforce3") is load_profile("geforce3")
    with pytest.raises(TypeError):
        load_profile("geforce3").caps["MaxTextureWidth"] = 1  # type: ignore[index]


def test_bundled_inherit_overrides_and_locates_each_field_in_its_own_file():
    gf2 = load_profile("geforce2")
    assert gf2.inherits == ("geforce256",)
    assert gf2.get("DeviceId") == 0x0150 and load_profile("geforce256").get("DeviceId") == 0x0100
    assert gf2.has("TextureOpCaps", "DOTPRODUCT3")  # inherited
    assert Path(gf2.location("DeviceId").path).name == "geforce2.yaml"
    assert Path(gf2.location("TextureOpCaps").path).name == "geforce256.yaml"
    mx = load_profile("geforce4mx")
    assert mx.inherits == ("geforce2", "geforce256")
    assert "nsr-no-reflective-bump" not in {q.id for q in mx.quirks}  # removed by id
    assert "dxt1-quality" in {q.id for q in mx.quirks}                # kept from geforce256


def test_a_user_profile_inherits_a_bundled_one_and_merges_mappings(tmp_path):
    path = write(tmp_path, "g400plus", """\
        inherit: g400
        MaxTextureWidth: 4096
        TextureFormats:
          DXT1: [texture, filter]
        """)
    card = load_profile(str(path))
    assert card.name == "g400plus"
    assert card.get("MaxTextureWidth") == 4096
    assert card.format_usages("DXT1") == frozenset({"texture", "filter"})
    assert card.format_usages("V8U8") == frozenset({"texture", "filter"})  # from g400
    assert card.has("TextureOpCaps", "BUMPENVMAP")
    loc = card.location("MaxTextureWidth")
    assert (Path(loc.path).name, loc.line, loc.column) == ("g400plus.yaml", 2, 1)


# --- located errors -----------------------------------------------------------------------------

def test_unknown_key_is_located_with_a_suggestion(tmp_path):
    path = write(tmp_path, "bad", MINIMAL + "MaxTextureWidht: 256\n")
    err = error_of(path)
    assert (err.line, err.column) == (10, 1)
    assert str(err) == (f"{path}:10:1: error: unknown key 'MaxTextureWidht'; "
                        f"did you mean 'MaxTextureWidth'?")


def test_wrong_type_is_located_at_the_value(tmp_path):
    path = write(tmp_path, "bad", MINIMAL + "MaxTextureWidth: big\n")
    err = error_of(path)
    assert (err.line, err.column) == (10, 18)
    assert "MaxTextureWidth must be an integer" in err.message


def test_unquoted_version_is_a_type_error_that_says_to_quote_it(tmp_path):
    path = write(tmp_path, "bad", MINIMAL.replace('PixelShaderVersion: "0.0"',
                                                  "PixelShaderVersion: 1.1"))
    err = error_of(path)
    assert (err.line, err.column) == (8, 21)
    assert 'quoted version string such as "1.1"' in err.message


def test_unknown_cap_bit_is_located_at_the_list_item(tmp_path):
    path = write(tmp_path, "bad", MINIMAL.replace("[DISABLE, MODULATE]",
                                                  "[DISABLE, MODULATE, BUMPENVMAPP]"))
    err = error_of(path)
    # "TextureOpCaps: [DISABLE, MODULATE, BUMPENVMAPP]": the bad item starts at column 36.
    assert (err.line, err.column) == (6, 36)
    assert "unknown TextureOpCaps bit 'BUMPENVMAPP'" in err.message
    assert "did you mean 'BUMPENVMAP'?" in err.message


def test_yaml_syntax_error_is_located(tmp_path):
    path = write(tmp_path, "bad", "generation: dx6\nname: a: b\n")
    err = error_of(path)
    # "name: a: b": the second ':' (column 8) is where a mapping value is not allowed.
    assert (err.line, err.column) == (2, 8)
    assert err.message.startswith("YAML syntax error: mapping values are not allowed")


def test_missing_inherit_target_is_located_at_the_inherit_value(tmp_path):
    path = write(tmp_path, "bad", "inherit: geforce9999\n" + MINIMAL)
    err = error_of(path)
    assert (err.line, err.column) == (1, 10)
    assert "unknown profile 'geforce9999'" in err.message


def test_inherit_cycle_is_located_in_the_file_that_closes_it(tmp_path):
    write(tmp_path, "a", "inherit: b.yaml\n" + MINIMAL)
    b = write(tmp_path, "b", MINIMAL + "inherit: a.yaml\n")
    err = error_of(tmp_path / "a.yaml")
    assert (Path(err.path), err.line, err.column) == (b.resolve(), 10, 10)
    assert "inherit cycle: a -> b -> a.yaml" in err.message


def test_parents_are_loaded_once_and_the_inherit_depth_still_holds(tmp_path):
    """A parent is built once (kept for the next profile that inherits it), and a kept parent
    does not hide a chain deeper than `inherit_depth`: the error is the one a fresh load
    reports, at the same place."""
    from effects.d3d9 import caps
    from effects.base import limits
    write(tmp_path, "p0", MINIMAL)
    for k in range(1, 5):
        write(tmp_path, f"p{k}", f"inherit: p{k - 1}.yaml\n" + MINIMAL)
    caps.clear_cache()
    with limits.raised(inherit_depth=4):
        fresh = error_of(tmp_path / "p4.yaml")
        caps.clear_cache()
        middle = load_profile(str(tmp_path / "p3.yaml"))       # a chain of 4: allowed
        assert load_profile(str(tmp_path / "p2.yaml")) is caps._LOADED[str((tmp_path / "p2.yaml").resolve())]
        kept = error_of(tmp_path / "p4.yaml")                  # 5 with p3 kept: refused
    assert middle.inherits == ("p2", "p1", "p0")
    assert (kept.message, kept.location) == (fresh.message, fresh.location)
    caps.clear_cache()


def test_missing_required_field_is_reported_at_the_top_of_the_file(tmp_path):
    path = write(tmp_path, "bad", MINIMAL.replace("VertexProcessing: [software]\n", ""))
    err = error_of(path)
    assert (err.line, err.column) == (1, 1)
    assert "VertexProcessing" in err.message


def test_bad_quirk_op_is_located_with_a_suggestion(tmp_path):
    path = write(tmp_path, "bad", MINIMAL + "Quirks:\n"
                 "  - {id: q, rule: arg_not_texture, op: MODULATEALPHA_ADDCOLR, arg: 2, text: t}\n")
    err = error_of(path)
    assert (err.line, err.column) == (11, 40)  # the op value starts at column 40
    assert "did you mean 'MODULATEALPHA_ADDCOLOR'?" in err.message


def test_more_textures_than_stages_is_rejected_at_the_texture_count(tmp_path):
    path = write(tmp_path, "bad", MINIMAL.replace("MaxSimultaneousTextures: 2",
                                                  "MaxSimultaneousTextures: 4"))
    err = error_of(path)
    assert (err.line, err.column) == (5, 1)
    assert "exceeds MaxTextureBlendStages (2)" in err.message


def test_unknown_bundled_name_suggests_the_closest(tmp_path):
    with pytest.raises(ProfileError) as info:
        load_profile("geforce33")
    assert "did you mean 'geforce3'?" in info.value.message
