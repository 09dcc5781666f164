"""No silent blank (issue 32): a render says what its picture shows nothing of, located.

The newcomer cases (tests/data/blank, ours): a toon shader whose light direction nothing
sets, ColorWriteEnable read from a parameter nothing sets, a 3ds Max-style CullMode = CW on
the built-in sphere; and every blank render of the real-effect corpus names a cause."""
from __future__ import annotations

from tests.paths import ROOT, TESTS

import numpy as np
import pytest

import effects
from effects.cli.main import main
from effects.host.diagnostics import _culled_front, uniform_colour, zero_meaning
from effects.host.runtime import Runtime, render_frame
from effects.host.scene import scene_for

DATA = TESTS / "data" / "blank"
SIZE = (48, 48)


def diagnostics(name: str, **options):
    frame = render_frame(effects.load_effect(DATA / name), "refrast", size=SIZE, diagnose=True,
                         **options)
    return frame, frame.diagnostics


def test_toon_shader_names_the_light_direction_nothing_sets():
    frame, found = diagnostics("toon_unset_light.fx")
    assert uniform_colour(frame.image) == (0, 0, 0)
    light = [w for w in found if w.message.startswith("parameter vLightDirection is set by nothing")]
    assert len(light) == 1
    # at the parameter's declaration, naming the shader constant and what 0 does there
    assert (light[0].location.line, light[0].location.column) == (3, 8)
    assert "ps_2_0 pixel shader of pass p0 reads it (c0) as 0" in light[0].message
    assert "every lit term (N·L) is 0" in light[0].message
    one_colour = [w for w in found if w.message.startswith("the frame is one colour (0, 0, 0)")]
    assert len(one_colour) == 1 and "vLightDirection" in one_colour[0].message
    # drawn black with alpha 0, as the clear: the unset light explains it, so the frame is not
    # said to be unwritten
    assert "no pixel was written" not in one_colour[0].message
    # set, the picture is the toon's bands and nothing is said
    lit, found = diagnostics("toon_unset_light.fx", params={"vLightDirection": "0,0,-1"})
    assert found == [] and uniform_colour(lit.image) is None
    bands = {tuple(p) for p in lit.image[..., :3].reshape(-1, 3)}
    # cBase x 1.0 and x 0.6: 0.5 x 0.6 is 0.29999998 in float32, 76.49 of 255
    assert bands == {(255, 128, 51), (153, 76, 31), (0, 0, 0)}


def test_colorwriteenable_from_an_unset_parameter_says_no_colour_is_written():
    frame, found = diagnostics("colorwrite_unset.fx")
    assert uniform_colour(frame.image) == (0, 0, 0)
    state = [w for w in found if w.message.startswith("pass p0: ColorWriteEnable reads colorWriteEnable = 0")]
    assert len(state) == 1 and "no colour is written" in state[0].message
    assert (state[0].location.line, state[0].location.column) == (12, 9)   # the state
    # no second warning for the same ColorWriteEnable = 0
    assert not any(w.message.endswith("ColorWriteEnable = 0: no colour is written") for w in found)
    drawn, found = diagnostics("colorwrite_unset.fx", params={"colorWriteEnable": "15"})
    # Colour (0.2, 0.8, 0.3) in 8 bits; 0.3 is 76.49999 of 255 in float32
    assert found == [] and tuple(drawn.image[24, 24, :3]) == (51, 204, 76)


def test_cw_cull_mode_on_the_sphere_warns_that_it_culls_the_front_faces():
    frame, found = diagnostics("max_cullmode_cw.fx")
    cull = [w for w in found if "CullMode = CW culls the front faces of the scene's sphere" in w.message]
    assert len(cull) == 1 and (cull[0].location.line, cull[0].location.column) == (22, 9)
    assert uniform_colour(frame.image) is None        # the sphere's inside is drawn: no blank
    # the winding facts: seen from the default camera every face toward it is clockwise on
    # screen (Direct3D's front faces), so CCW culls none of them and CW all
    runtime = Runtime(effects.load_effect(DATA / "max_cullmode_cw.fx"), "refrast", size=SIZE)
    culled, toward = _culled_front(runtime, "CW")
    assert toward > 0 and culled == toward
    assert _culled_front(runtime, "CCW") == (0, toward)


def test_the_default_cull_mode_on_the_bundled_effects_says_nothing():
    frame = render_frame(effects.load_effect(ROOT / "fxfiles" / "phong.fx"), "refrast", size=SIZE,
                         scene=scene_for(str(ROOT / "fxfiles" / "phong.fx"), None), diagnose=True)
    assert not any("CullMode" in w.message for w in frame.diagnostics)


ALPHA = """
float4x4 WorldViewProj : WORLDVIEWPROJECTION;
float4 vs_main(float4 p : POSITION) : POSITION { return mul(p, WorldViewProj); }
float4 ps_main() : COLOR0 { return float4(1, 1, 1, 0.5); }
technique T { pass p0 {
    AlphaTestEnable = TRUE; AlphaFunc = %s; AlphaRef = %d;
    VertexShader = compile vs_2_0 vs_main(); PixelShader = compile ps_2_0 ps_main();
} }
"""


@pytest.mark.parametrize("func, ref, discards", [("NEVER", 0, True), ("GREATER", 255, True),
                                                 ("LESS", 0, True), ("GREATER", 0, False)])
def test_an_alpha_test_no_pixel_can_pass_is_said(tmp_path, func, ref, discards):
    path = tmp_path / "alpha.fx"
    path.write_text(ALPHA % (func, ref))
    frame = render_frame(effects.load_effect(path), "refrast", size=SIZE, diagnose=True)
    said = [w for w in frame.diagnostics if "the alpha test discards every pixel" in w.message]
    assert bool(said) == discards
    if discards:
        assert said[0].location.line == 6 and uniform_colour(frame.image) is not None
    else:
        assert frame.diagnostics == [] and uniform_colour(frame.image) is None


def test_uniform_colour_and_what_zero_means():
    image = np.zeros((4, 4, 4), np.uint8)
    image[..., :3] = (10, 20, 30)
    image[0, 0, 3] = 255                       # alpha is not part of the picture
    assert uniform_colour(image) == (10, 20, 30)
    image[1, 2, 1] = 21
    assert uniform_colour(image) is None
    effect = effects.load_effect(DATA / "toon_unset_light.fx")
    assert "zero matrix" in zero_meaning(effect.parameter("matWorld"), "vertex")
    assert "N·L" in zero_meaning(effect.parameter("vLightDirection"))
    assert zero_meaning(effect.parameter("cBase")) == ""        # nothing known of "cBase"
    assert "black" in zero_meaning(effects.load_effect(DATA / "colorwrite_unset.fx").parameter("Colour"))


def test_render_prints_them_and_strict_makes_them_errors(tmp_path, capsys):
    out = tmp_path / "toon.png"
    args = ["render", str(DATA / "toon_unset_light.fx"), "-p", "refrast", "--size", "32x32",
            "-o", str(out)]
    assert main(args) == 0 and out.exists()
    err = capsys.readouterr().err
    assert "toon_unset_light.fx:3:8: warning: parameter vLightDirection is set by nothing" in err
    out.unlink()
    assert main([*args, "--strict"]) == 1 and not out.exists()
    err = capsys.readouterr().err
    assert "toon_unset_light.fx:3:8: error: parameter vLightDirection" in err
    assert "error: the frame is one colour (0, 0, 0)" in err


def test_matrix_render_prints_each_cells_diagnostics(tmp_path, capsys):
    sheet = tmp_path / "sheet.png"
    args = ["matrix", str(DATA / "colorwrite_unset.fx"), "-p", "refrast", "-p", "radeon9700",
            "--render", str(sheet), "--size", "24x24", "--jobs", "1"]
    assert main(args) == 0 and sheet.exists()
    err = capsys.readouterr().err
    # said once for the two cards that draw the same technique the same way
    assert err.count("warning: pass p0: ColorWriteEnable reads colorWriteEnable = 0") == 1
    assert err.startswith("[refrast] ") or "\n[refrast] " in err
    assert main([*args, "--strict"]) == 1
    assert "error: pass p0: ColorWriteEnable" in capsys.readouterr().err


def _valid_on_refrast(path):
    effect = effects.load_effect(path)
    card = effects.load_profile("refrast")
    return effect, [t for t in effect.techniques if t.name and effect.validate(t.name, card).ok]


REALFX = sorted(p for p in (TESTS / "data" / "realfx").rglob("*.fx"))


def test_every_blank_render_of_the_real_effect_corpus_names_a_cause():
    """Each technique valid on the reference card that draws one colour says why (the files
    that do not load are tests/realfx/test_corpus_renders.py's), and there are such renders,
    so this checks something."""
    blank = []
    for path in REALFX:
        try:
            effect, techniques = _valid_on_refrast(path)
        except effects.EffectError:
            continue
        for technique in techniques:
            frame = render_frame(effect, "refrast", technique=technique, size=SIZE,
                                 scene=scene_for(str(path), None), diagnose=True)
            if uniform_colour(frame.image) is None:
                continue
            blank.append(f"{path.name}:{technique.name}")
            one = [w for w in frame.diagnostics if w.message.startswith("the frame is one colour")]
            assert len(one) == 1, blank[-1]
            assert "likely causes: " in one[0].message, blank[-1]
            assert "no cause found" not in one[0].message, blank[-1]
            assert one[0].location.path == str(path)
    assert len(blank) >= 2, blank


def test_a_technique_without_passes_and_a_mesh_past_the_far_plane_are_said(tmp_path):
    path = tmp_path / "mme.fx"
    path.write_text(ALPHA.replace("AlphaTestEnable = TRUE;", "").replace(
        "AlphaFunc = %s; AlphaRef = %d;", "") + 'technique ShadowTec < string MMDPass = "shadow"; > { }\n')
    effect = effects.load_effect(path)
    empty = render_frame(effect, "refrast", technique="ShadowTec", size=SIZE, diagnose=True)
    said = [w.message for w in empty.diagnostics]
    assert said[0] == ("technique ShadowTec has no passes: it draws nothing (a host's "
                       "placeholder, such as MikuMikuEffect's empty shadow and edge techniques)")
    assert "likely causes: technique ShadowTec has no passes" in said[1]
    # the sphere 2 to 4 units away, the far plane at 1: nothing is written, not even alpha
    far = render_frame(effect, "refrast", technique="T", size=SIZE, diagnose=True,
                       scene={"camera": {"far": 1.0}})
    one = [w.message for w in far.diagnostics if w.message.startswith("the frame is one colour")]
    assert len(one) == 1 and "no pixel was written" in one[0] and "0.1 and 1 here" in one[0]
    near = render_frame(effect, "refrast", technique="T", size=SIZE, diagnose=True)
    assert near.diagnostics == []
