"""Real effect files written by others (tests/data/realfx/<origin>/, unmodified copies from
Debian packages, tests/data/realfx/MANIFEST.md) load, validate and render what their engines
drew; the Direct3D 10/11 ones fail with an error that says so, where it starts."""
from __future__ import annotations

from tests.paths import TESTS

import hashlib
import re

import numpy as np
import pytest

import effects
from effects.cli.main import main
from effects.host.runtime import render_frame
from effects.host.scene import Scene

DATA = TESTS / "data" / "realfx"
WM = DATA / "wildmagic"
IRR = DATA / "irrlicht"
SIZE = (64, 64)


def lit(image: np.ndarray) -> np.ndarray:
    """Pixels with any colour (every technique here clears to black)."""
    return image[..., :3].max(axis=-1) > 0


def drawn(image: np.ndarray) -> np.ndarray:
    """Pixels the mesh covers: the clear is (0, 0, 0, 0), the shaders write colour or alpha."""
    return image.max(axis=-1) > 0


# -- the manifest ---------------------------------------------------------------------------

def test_every_third_party_file_is_unmodified_and_in_the_manifest():
    manifest = (DATA / "MANIFEST.md").read_text()
    rows = dict(re.findall(r"^\| `([\w/.]+)` \| [^|]+ \| `[^`]+` \| [^|]+ \| `([0-9a-f]{64})` \|$",
                           manifest, re.M))
    theirs = [p for p in DATA.glob("*/*") if not p.name.startswith(("wm_", "irr_", "al_"))
              and p.name not in ("COPYRIGHT.debian", "GPL-2")]
    assert len(theirs) >= 30
    for path in theirs:
        key = str(path.relative_to(DATA))
        assert key in rows, key
        assert hashlib.sha256(path.read_bytes()).hexdigest() == rows[key], key
    for ours in DATA.glob("*/*"):
        if ours.name.startswith(("wm_", "irr_", "al_")):
            assert ours.read_text().startswith("// Ours (the effects project)"), ours.name
    for folder in ("wildmagic", "irrlicht", "microprofile"):
        assert (DATA / folder / "COPYRIGHT.debian").is_file()
    assert "GNU GENERAL PUBLIC LICENSE" in (DATA / "kodi" / "GPL-2").read_text()


# -- Wild Magic 5 (Geometric Tools): HLSL/Cg entry functions with uniform parameters --------

WRAPPERS = sorted(p.name for p in WM.glob("wm_*.fx"))


@pytest.mark.parametrize("name", WRAPPERS)
def test_every_wild_magic_shader_renders_on_a_dx9_card(name):
    effect = effects.load_effect(WM / name)
    card = "radeon9700"
    scene = {"mesh": "quad"} if name == "wm_ScreenShader.fx" else None
    frame = render_frame(effect, card, size=SIZE, scene=scene)
    covered = drawn(frame.image)
    # the unit sphere 3 units from the camera covers 57% of the frame; the quad all of it
    assert covered.mean() == pytest.approx(1.0 if scene else 0.573, abs=0.03), name
    assert lit(frame.image).mean() > 0.25, name                  # and not in black


def test_wild_magic_spot_per_pixel_fits_ps_2_0():
    # 65 arithmetic slots before mul(PVWMatrix, p) / mul((float3x3)WMatrix, d) were compiled
    # over the matrix columns (a mul and mads, as fxc does); 64 are allowed
    effect = effects.load_effect(WM / "wm_LightSpotPerPixel.fx")
    assert effect.validate("LightSpotPerPixel", effects.load_profile("radeon9700")).ok


def test_wild_magic_cgfx_sampler_spellings_load_with_warnings():
    effect = effects.load_effect(WM / "wm_Texture2D.fx")
    texts = [str(w) for w in effect.warnings]
    assert f"{WM / 'Texture2D.fx'}:4:16: warning: MinFilter = Nearest: 'Nearest' is CgFX's " \
           "(OpenGL's) spelling; D3DX's effect compiler rejects it; read as Point" in texts
    assert any(t.startswith(f"{WM / 'Texture2D.fx'}:6:4: warning: 'WrapS' is CgFX's (OpenGL's) "
                            "name for AddressU") for t in texts)
    # read as Point: the checker stand-in keeps its two values, no filtered in-betweens
    image = render_frame(effect, "radeon9700", size=SIZE).image
    inside = image[lit(image)][:, 0]
    assert set(np.unique(inside).tolist()) <= {0, 255} and (inside == 255).any()


def test_wild_magic_directional_per_pixel_matches_its_formula_at_the_centre():
    # (a large frame: at the centre of a small one the highlight's slope is 8 levels a pixel)
    frame = render_frame(effects.load_effect(WM / "wm_LightDirectionalPerPixel.fx"),
                         "radeon9700", size=(256, 256))
    scene = Scene()
    # the sphere point facing the camera: p = n = (0, 0, 1) (camera at +z); Wild Magic's
    # p_LightDirectionalPerPixel with wm_host.fxh's material and the scene's light
    n = np.array([0.0, 0.0, 1.0])
    light = scene.light_direction()[:3]
    view = np.array(scene.camera.eye) - n
    view /= np.linalg.norm(view)
    half = (view - light) / np.linalg.norm(view - light)
    n_dot_l, n_dot_h = -n @ light, n @ half
    diffuse, specular = max(n_dot_l, 0.0), (max(n_dot_h, 0.0) ** 24 if n_dot_l > 0 else 0.0)
    color = (np.array([0.2, 0.2, 0.25]) * 0.25 + diffuse * np.array([0.9, 0.6, 0.3])
             + specular * 0.5)
    centre = frame.image[127:129, 127:129, :3].reshape(-1, 3).mean(0)
    np.testing.assert_allclose(centre, np.clip(color, 0, 1) * 255, atol=4)


@pytest.mark.parametrize("name, expected", [("wm_Default.fx", (255, 0, 255)),
                                            ("wm_Material.fx", (230, 153, 77)),
                                            ("wm_LightAmbient.fx", (13, 13, 16))])
def test_wild_magic_constant_colours(name, expected):
    # Default: magenta; Material: MaterialDiffuse passed as a compile argument (a global);
    # LightAmbient: MaterialAmbient * LightAmbient * attenuation.w = (0.05, 0.05, 0.0625)
    image = render_frame(effects.load_effect(WM / name), "radeon9700", size=SIZE).image
    np.testing.assert_allclose(image[32, 32, :3], expected, atol=1)


def test_wild_magic_texture3d_samples_the_volume_stand_in():
    frame = render_frame(effects.load_effect(WM / "wm_Texture3D.fx"), "radeon9700", size=SIZE)
    assert [w.message.split("; drawn")[1] for w in frame.warnings] == \
        [" with a stand-in (noise_volume, 3d)"]
    colours = {tuple(c) for c in frame.image[lit(frame.image)][:, :3].tolist()}
    assert len(colours) > 20            # noise, not the two values of a 2D checker


def test_wild_magic_vertex_colour_adds_to_the_texture():
    frame = render_frame(effects.load_effect(WM / "wm_VertexColor4Texture.fx"), "radeon9700",
                         size=SIZE, scene={"vertex": {"diffuse": [0.25, 0, 0, 1]}})
    colours = {tuple(c) for c in frame.image[lit(frame.image)][:, :3].tolist()}
    # saturate(checker + (0.25, 0, 0)): the black squares turn dark red, the white stay white
    assert {(64, 0, 0), (255, 255, 255)} <= colours


@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_wild_magic_point_light_on_both_back_ends(backend):
    image = render_frame(effects.load_effect(WM / "wm_LightPointPerVertex.fx"), "radeon9700",
                         size=SIZE, backend=backend).image.astype(int)
    # the scene light at (2, 2, 2): the upper left of the image (+x is on the left) is lit
    upper_left, lower_right = image[18:26, 18:26, 0].mean(), image[40:46, 40:46, 0].mean()
    assert upper_left > lower_right + 60


def test_wild_magic_on_dx8_and_dx7_cards_says_why_not(capsys, tmp_path):
    for card, why in (("geforce3", "runs pixel shaders up to ps_1_1"),
                      ("geforce2", "has no pixel shader hardware")):
        assert main(["render", str(WM / "wm_Texture2D.fx"), "--profile", card, "-o",
                     str(tmp_path / "out.png")]) == 1
        assert why in capsys.readouterr().err


# -- Irrlicht 1.8: its example 10.Shaders, asm and HLSL ----------------------------------------

@pytest.mark.parametrize("backend", ["numpy", "gl"])
@pytest.mark.parametrize("wrapper, technique", [("irr_d3d9_asm.fx", "Irrlicht_vs11_ps11_dx9"),
                                                ("irr_d3d8_asm.fx", "Irrlicht_vs11_ps11_dx8")])
def test_irrlicht_asm_shaders_light_the_wall_cyan(wrapper, technique, backend):
    effect = effects.load_effect(IRR / wrapper)
    frame = render_frame(effect, "geforce3", size=SIZE, backend=backend)
    assert frame.technique.name == technique and not frame.warnings
    solid = render_frame(effect, "geforce3", size=SIZE, technique="Irrlicht_Solid").image
    image, plain = frame.image[..., :3].astype(int), solid[..., :3].astype(int)
    inside = lit(frame.image)
    assert inside.mean() > 0.4 and (image[inside][:, 0] == 0).all()   # light colour (0, 1, 1)
    # at the centre the normal faces the light at the camera: N.L = 1, so the pixel shader's
    # 4 * texture * (0, 1, 1), saturated, of the unlit texture the fallback draws there
    centre, texel = image[30:34, 30:34].reshape(-1, 3), plain[30:34, 30:34].reshape(-1, 3)
    np.testing.assert_allclose(centre[:, 1:], np.minimum(4 * texel[:, 1:], 255), atol=12)


def test_irrlicht_on_a_dx7_card_draws_the_plain_material():
    frame = render_frame(effects.load_effect(IRR / "irr_d3d8_asm.fx"), "geforce2", size=SIZE)
    assert frame.technique.name == "Irrlicht_Solid"
    image = frame.image[..., :3].astype(int)
    assert lit(frame.image).mean() > 0.4 and image[lit(frame.image)][:, 0].mean() > 60  # the wall


def test_irrlicht_hlsl_binds_its_globals_by_name(capsys):
    path = IRR / "irr_d3d9_hlsl.fx"
    assert main(["doctor", str(path), "--profile", "radeon9700", "--technique",
                 "Irrlicht_HLSL"]) in (0, 1)
    out = capsys.readouterr().out
    assert "mInvWorld <- bound by name (XNA convention) as WORLDINVERSE" in out
    assert "mTransWorld <- bound by name (XNA convention) as WORLDTRANSPOSE" in out
    assert "mWorldViewProj <- bound by name (DirectX 8 SDK convention) as WORLDVIEWPROJECTION" in out
    # compiled for vs_1_1 / ps_1_1 as the example does, with the example's light (at the
    # camera) and colour set by name: the same picture as its assembly twin
    effect = effects.load_effect(path)
    frame = render_frame(effect, "geforce3", size=SIZE,
                         params={"mLightPos": "0,0,3", "mLightColor": "0,1,1,0"})
    assert frame.technique.name == "Irrlicht_HLSL"
    asm = render_frame(effects.load_effect(IRR / "irr_d3d9_asm.fx"), "geforce3", size=SIZE).image
    inside = lit(frame.image)
    assert inside.mean() > 0.4 and (frame.image[inside][:, 0] == 0).all()
    assert np.abs(frame.image[..., :3].astype(int) - asm[..., :3]).mean() < 3


# -- Direct3D 10/11 files: a located error or warning that says what they are ---------------

@pytest.mark.parametrize("path, defines, where, word", [
    ("kodi/convolution_d3d.fx", [], "kodi/convolution_d3d.fx:27:1", "SamplerState"),
    ("kodi/yuv2rgb_d3d.fx", [], "kodi/yuv2rgb_d3d.fx:31:1", "SamplerState"),
    ("kodi/output_d3d.fx", ["-D", "KODI_OUTPUT_T"], "kodi/convolution_d3d.fx:27:1", "SamplerState"),
])
def test_kodi_direct3d11_effects_are_named_as_such(capsys, path, defines, where, word):
    assert main(["validate", str(DATA / path), *defines]) == 2
    err = capsys.readouterr().err
    assert f"{DATA}/{where}: error: '{word}' is Direct3D 10/11 effect syntax: this is a " \
           "Direct3D 10/11 effect (fx_4_0/fx_5_0), not a Direct3D 9 (D3DX9, fx_2_0) one" in err


def test_a_direct3d11_shader_without_techniques_gets_a_warning():
    effect = effects.load_effect(DATA / "microprofile" / "Tutorial02.fx")
    assert not effect.techniques
    assert [str(w).split(" is a ")[0] for w in effect.warnings] == [
        f"{DATA}/microprofile/Tutorial02.fx:10:38: warning: 'SV_POSITION'"]


# -- Allegro 5: its ex_shader example's HLSL, in the effect Allegro's D3D path builds -----------

ALLEGRO = DATA / "allegro"


@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_allegro_ex_shader_tints_the_bitmap(backend):
    effect = effects.load_effect(ALLEGRO / "al_ex_shader.fx")
    bitmap = str(ALLEGRO / "mysha.pcx")                   # the example's bitmap, a PCX file

    def draw(tint: str) -> np.ndarray:
        frame = render_frame(effect, "radeon9700", size=(80, 50), scene={"mesh": "quad"},
                             backend=backend, params={"al_tex": bitmap, "tint": tint})
        assert frame.technique.name == "TECH" and not frame.warnings
        return frame.image[..., :3].astype(int)

    plain, tinted = draw("1, 1, 1"), draw("4, 0, 1")      # the example's first tint
    assert plain.std() > 30                               # the mouse, not a flat colour
    # ps_main: pixel.rgb *= tint, saturated to the render target
    np.testing.assert_allclose(tinted[..., 0], np.minimum(4 * plain[..., 0], 255), atol=3)
    assert (tinted[..., 1] == 0).all()
    np.testing.assert_allclose(tinted[..., 2], plain[..., 2], atol=1)


def test_allegro_projview_matrix_is_bound_by_its_name(capsys):
    assert main(["doctor", str(ALLEGRO / "al_ex_shader.fx"), "--profile", "radeon9700"]) in (0, 1)
    out = capsys.readouterr().out
    assert "al_projview_matrix <- bound by name (Allegro 5 convention) as WORLDVIEWPROJECTION" in out
    assert "tint (declared at" in out                     # the example sets it: nothing here does
    frame = render_frame(effects.load_effect(ALLEGRO / "al_ex_shader.fx"), "radeon9700",
                         size=SIZE, params={"tint": "0, 4, 1"})
    assert drawn(frame.image).mean() == pytest.approx(0.573, abs=0.03)    # the camera's sphere


def test_render_of_a_direct3d11_shader_file_says_what_it_is(capsys, tmp_path):
    path = DATA / "microprofile" / "Tutorial02.fx"
    assert main(["render", str(path), "--profile", "radeon9700", "-o", str(tmp_path / "o.png")]) == 1
    err = capsys.readouterr().err
    assert f"{path}:10:38: warning: 'SV_POSITION' is a Direct3D 10/11 system-value semantic" in err
    assert "the effect has no techniques, so Radeon 9700 has nothing to render" in err
