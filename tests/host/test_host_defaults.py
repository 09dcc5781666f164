"""What a host (FX Composer, EffectEdit) supplies around an effect: device transforms from the
scene camera, parameters bound by DXSAS semantics and annotations, UI defaults, and stand-in
textures with located warnings."""
from __future__ import annotations

from tests.paths import ROOT

import math

import numpy as np
import pytest

import effects
from effects.cli.main import main
from effects.base.errors import SceneError
from effects.host.runtime import Runtime, render_frame
from effects.host.scene import load_scene
from effects.host.semantics import bind_scene, binding_table, ui_defaults

BACKENDS = ["numpy", "gl"]

# A fixed-function technique that sets no transforms: drawn with D3D9's identity transforms the
# unit sphere would fill the frame; with the host's camera it is a disc.
FF_NO_TRANSFORMS = """
technique Unlit {
    pass P0 {
        Lighting = false;
        TextureFactor = 0xff00ff00;
        ColorOp[0] = SelectArg1; ColorArg1[0] = TFactor;
        AlphaOp[0] = SelectArg1; AlphaArg1[0] = TFactor;
    }
}
"""


@pytest.mark.parametrize("backend", BACKENDS)
def test_camera_sets_the_device_transforms_of_a_fixed_function_pass(backend):
    effect = effects.load_effect(FF_NO_TRANSFORMS)
    image = effects.render(effect, "geforce2", backend=backend, scene={"mesh": "sphere"},
                           size=(64, 64))
    covered = (image[..., 1] == 255)
    # The unit sphere seen from 3 units away with a 45 degree vertical field of view: its
    # silhouette's angular radius is asin(1/3), so its NDC radius is tan(asin(1/3)) / tan(22.5°)
    # and it covers pi r^2 / 4 of the square frame (the tessellated sphere a little less).
    r = math.tan(math.asin(1 / 3)) / math.tan(math.radians(22.5))
    assert covered.mean() == pytest.approx(math.pi * r * r / 4, abs=0.03)
    assert covered[32, 32] and not covered[0, 0] and not covered[63, 63]


def test_a_pass_that_sets_a_transform_wins_over_the_host():
    # the pass's view moves the sphere 2 units away and its orthographic projection halves x
    # and y: a disc of NDC radius 0.5, not the host camera's 0.85
    text = """float4x4 V = {1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,2,1};
    float4x4 P = {0.5,0,0,0, 0,0.5,0,0, 0,0,0.1,0, 0,0,0,1};
    technique T { pass P { ProjectionTransform = <P>; ViewTransform = <V>; Lighting = false;
        TextureFactor = 0xffffffff; ColorOp[0] = SelectArg1; ColorArg1[0] = TFactor; } }"""
    image = effects.render(effects.load_effect(text), "geforce2", scene={"mesh": "sphere"},
                           size=(64, 64))
    assert (image[..., 0] == 255).mean() == pytest.approx(math.pi * 0.25 / 4, abs=0.02)


SAS = """
float4x4 Wvp : WorldViewProjection;
float4x4 wit : worldinversetranspose;
float4x4 VI : ViewInverse;
float4x4 VIXf : VIEWI;
float4x4 VPt : ViewProjectionTranspose;
float4x4 W43 : World;
float Clock : Time;
float2 Vp : ViewportPixelSize;
float3 LampPos : Position < string Object = "PointLight0"; string Space = "World"; > = {9, 9, 9};
float3 LampDir : DIRECTION < string Object = "DirectionalLight0"; > = {0, 0, 1};
float4 LampCol : Diffuse < string Object = "PointLight0"; > = {1, 0, 0, 1};
float4 NotALight : Diffuse = {0.5, 0.5, 0.5, 1};
float Shine < string UIName = "Shininess"; float UIMin = 8; float UIMax = 64; >;
float Given < float UIMin = 1; float UIMax = 3; > = 7;
technique T { pass P { } }
"""


def test_sas_semantics_and_light_objects_bind_case_insensitively():
    effect = effects.load_effect(SAS)
    scene = load_scene({"mesh": "sphere", "camera": {"eye": [1, 2, 3]}, "time": 2.5,
                        "light": {"position": [4, 5, 6], "color": [0.25, 0.5, 0.75, 1]}})
    bound = bind_scene(effect, scene, (320, 200))
    m = scene.matrices((320, 200))
    world, view, proj = m["world"], m["view"], m["projection"]
    np.testing.assert_allclose(bound["Wvp"], world @ view @ proj, rtol=1e-6)
    np.testing.assert_allclose(bound["wit"], np.linalg.inv(world).T, atol=1e-6)
    # the inverse view's last row is the eye (row-vector convention)
    np.testing.assert_allclose(bound["VI"][3], [1, 2, 3, 1], atol=1e-5)
    np.testing.assert_allclose(bound["VIXf"], bound["VI"], atol=1e-6)
    np.testing.assert_allclose(bound["VPt"], (view @ proj).T, rtol=1e-5, atol=1e-6)
    assert float(bound["Clock"]) == 2.5
    assert bound["Vp"].tolist() == [320, 200]
    assert bound["LampPos"].tolist() == [4, 5, 6]
    d = np.array([-4, -5, -6]) / math.sqrt(77)           # from the light towards the target
    np.testing.assert_allclose(bound["LampDir"], d, rtol=1e-5)
    assert bound["LampCol"].tolist() == [0.25, 0.5, 0.75, 1]
    assert "NotALight" not in bound                       # a Diffuse without a light Object


def test_light_objects_keep_the_effect_defaults_when_the_scene_places_no_light():
    bound = bind_scene(effects.load_effect(SAS), load_scene({"mesh": "sphere"}))
    assert "LampPos" not in bound and "LampCol" not in bound


def test_ui_range_gives_an_uninitialised_parameter_its_middle():
    defaults = ui_defaults(effects.load_effect(SAS))
    assert float(defaults["Shine"]) == 36.0
    assert "Given" not in defaults                         # the file's own value stands


def test_binding_table_lists_every_semantic_once():
    names = [row[0] for row in binding_table()]
    assert len(names) == len(set(names))
    assert "WORLDVIEWPROJECTION" in names and "VIEWPORTPIXELSIZE" in names


# -- stand-in textures ---------------------------------------------------------------------

UNSUPPLIED = """
texture {kind}Tex{annotation};
sampler S = sampler_state {{ Texture = <{kind}Tex>; MinFilter = Point; MagFilter = Point; }};
technique T {{ pass P {{
    Lighting = false; Sampler[0] = <S>;
    ColorOp[0] = SelectArg1; ColorArg1[0] = Texture; AlphaOp[0] = SelectArg1; AlphaArg1[0] = Texture;
}} }}
"""


@pytest.mark.parametrize("backend", BACKENDS)
def test_an_unsupplied_2d_texture_is_a_checker_with_a_located_warning(backend):
    effect = effects.load_effect(UNSUPPLIED.format(kind="", annotation=""), strict=True)
    frame = render_frame(effect, "geforce2", backend=backend, scene={"mesh": "quad"}, size=(64, 64))
    assert len(frame.warnings) == 1
    warning = frame.warnings[0]
    assert (warning.location.line, warning.location.column) == (2, 9)
    assert "texture parameter Tex: nothing supplies it" in str(warning)
    assert "stand-in (checker:8, 2d)" in str(warning)
    # the default checker has 8 squares a side: 8-pixel squares of two colours on 64 pixels
    red = frame.image[..., 0].astype(int)
    assert red[4, 4] != red[4, 12] and red[4, 4] == red[12, 12] and red[4, 12] == red[12, 4]
    assert len(np.unique(red)) == 2


def test_a_missing_resource_file_is_a_stand_in_warned_at_its_annotation(tmp_path):
    path = tmp_path / "e.fx"
    path.write_text(UNSUPPLIED.format(kind="", annotation=' < string ResourceName = "gone.dds"; >'))
    frame = render_frame(effects.load_effect(path), "geforce2", scene={"mesh": "quad"}, size=(8, 8))
    (warning,) = frame.warnings
    assert str(warning).startswith(f"{path}:2:22: warning: texture parameter Tex: texture file "
                                   f"not found: {tmp_path / 'gone.dds'}; drawn with a stand-in")


@pytest.mark.parametrize("decl, kind, stand_in", [
    ("textureCUBE", "cube", "sky_cube"), ("texture3D", "3d", "noise_volume")])
def test_stand_ins_follow_the_kind(decl, kind, stand_in):
    text = f"""{decl} T; sampler S = sampler_state {{ Texture = <T>; }};
    technique X {{ pass P {{ Sampler[0] = <S>; }} }}"""
    runtime = Runtime(effects.load_effect(text), "radeon9700", scene={"mesh": "quad"}, size=(4, 4))
    texture = runtime.used_texture("T")
    assert texture.kind == kind and texture.name == stand_in


def test_strict_makes_a_stand_in_an_error():
    effect = effects.load_effect(UNSUPPLIED.format(kind="", annotation=""))
    with pytest.raises(SceneError, match=r":2:9: error: texture parameter Tex: nothing supplies it"):
        effects.render(effect, "geforce2", scene={"mesh": "quad"}, size=(8, 8), strict=True)


def test_a_missing_file_the_user_names_stays_an_error(tmp_path):
    effect = effects.load_effect(UNSUPPLIED.format(kind="", annotation=""))
    with pytest.raises(SceneError, match="texture file not found"):
        effects.render(effect, "geforce2", scene={"mesh": "quad"}, size=(8, 8),
                       params={"Tex": str(tmp_path / "nope.png")})


def test_render_prints_the_warning_and_strict_fails(tmp_path, capsys):
    path = tmp_path / "e.fx"
    path.write_text(UNSUPPLIED.format(kind="", annotation=""))
    out = tmp_path / "o.png"
    assert main(["render", str(path), "-p", "geforce2", "--size", "8x8", "-o", str(out)]) == 0
    err = capsys.readouterr().err
    assert f"{path}:2:9: warning: texture parameter Tex: nothing supplies it" in err
    assert main(["render", str(path), "-p", "geforce2", "--size", "8x8", "--strict",
                 "-o", str(out)]) == 2
    assert f"{path}:2:9: error: texture parameter Tex" in capsys.readouterr().err


def test_the_guide_lists_the_binding_table():
    guide = (ROOT / "docs" / "guide" / "host.md").read_text()
    for semantic, what in binding_table():
        assert semantic in guide and what in guide, semantic
