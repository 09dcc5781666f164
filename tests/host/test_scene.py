"""Scene YAML parsing (every key, located errors), semantic binding and user values."""
from __future__ import annotations

import math
import textwrap

import numpy as np
import pytest

from effects import load_effect
from effects.base.errors import SceneError
from effects.host.scene import InlineMesh, load_scene, look_at_lh, perspective_fov_lh
from effects.host.semantics import bind_scene, coerce_value, parse_assignments


def write(tmp_path, text: str, name: str = "scene.yaml") -> str:
    path = tmp_path / name
    path.write_text(textwrap.dedent(text).lstrip("\n"))
    return str(path)


def error_of(tmp_path, text: str) -> SceneError:
    path = write(tmp_path, text)
    with pytest.raises(SceneError) as info:
        load_scene(path)
    return info.value


# ---------------------------------------------------------------------------------------------
# Every key


def test_every_key_is_read(tmp_path):
    path = write(tmp_path, """
        mesh: teapot
        clear: {color: '0x80102030', depth: 0.5, stencil: 7}
        size: [320, 200]
        camera: {eye: [1, 2, 3], target: [0, 1, 0], up: [0, 1, 0], fov: 60, near: 0.5, far: 50}
        light: {position: [4, 5, 6], color: [1, 0.5, 0.25, 1], direction: [0, -1, 0]}
        vertex: {diffuse: [0.5, 0.5, 0.5, 1], specular: '0xff00ff00'}
        params: {BaseTexture: textures/stone.png, SpecularPower: 24}
        streams: {texcoord1: tangent, texcoord2: binormal}
        world: [2, 0, 0, 0,  0, 2, 0, 0,  0, 0, 2, 0,  1, 0, 0, 1]
        time: 1.5
    """)
    s = load_scene(path)
    assert s.mesh == "teapot"
    assert s.clear_color == pytest.approx((0x10 / 255, 0x20 / 255, 0x30 / 255, 0x80 / 255))
    assert (s.clear_depth, s.clear_stencil) == (0.5, 7)
    assert s.size == (320, 200)
    assert s.camera.eye == (1, 2, 3) and s.camera.target == (0, 1, 0)
    assert (s.camera.fov, s.camera.near, s.camera.far) == (60, 0.5, 50)
    assert s.light.position == (4, 5, 6) and s.light.color == (1, 0.5, 0.25, 1)
    assert s.light_given and list(s.light_direction()) == [0, -1, 0]
    assert s.vertex_diffuse == (0.5, 0.5, 0.5, 1) and s.vertex_specular == (0, 1, 0, 1)
    assert s.params == {"BaseTexture": "textures/stone.png", "SpecularPower": 24}
    assert s.streams == {"texcoord1": "tangent", "texcoord2": "binormal"}
    assert s.world[3, 0] == 1 and s.world[0, 0] == 2
    assert s.time == 1.5
    assert s.base_dir == str(tmp_path)
    # where each value was written, for errors found later (line 7 holds params)
    assert (s.location("params.SpecularPower").line, s.location("streams.texcoord2").line) == (7, 8)


def test_defaults_without_a_file():
    s = load_scene(None)
    assert s.mesh == "sphere" and s.size == (256, 256)
    assert s.clear_color == (0, 0, 0, 0) and s.clear_depth == 1.0 and s.clear_stencil == 0
    assert s.vertex_diffuse == (1, 1, 1, 1) and s.vertex_specular == (0, 0, 0, 0)
    assert not s.light_given


def test_colours_in_both_forms_agree():
    a = load_scene({"clear": {"color": "0xff336699"}}).clear_color
    b = load_scene({"clear": {"color": [0x33 / 255, 0x66 / 255, 0x99 / 255, 1.0]}}).clear_color
    assert a == pytest.approx(b)
    assert load_scene({"clear": {"color": [1, 0, 0]}}).clear_color == (1, 0, 0, 1)  # a defaults to 1


def test_inline_vertices_with_the_d3d_colour_defaults():
    s = load_scene({"mesh": {"primitive": "strip", "vertices": [
        {"position": [-1, 1, 0.1], "diffuse": "0x55ff0000", "tex0": [0, 0]},
        {"position": [1, 1, 0.1], "tex0": [1, 0]},
        {"position": [-1, -1, 0.1], "tex0": [0, 1]},
        {"position": [1, -1, 0.1], "specular": [0, 0, 1, 1], "tex0": [1, 1]}]}})
    assert isinstance(s.mesh, InlineMesh) and s.mesh.primitive == "strip" and s.untransformed
    diffuse, specular = s.mesh.attributes["diffuse"], s.mesh.attributes["specular"]
    assert diffuse[0] == pytest.approx([1, 0, 0, 0x55 / 255])
    assert diffuse[1].tolist() == [1, 1, 1, 1]          # 0xffffffff
    assert specular[0].tolist() == [0, 0, 0, 0]         # 0x00000000
    assert specular[3].tolist() == [0, 0, 1, 1]
    assert s.mesh.attributes["tex0"].shape == (4, 2)
    assert s.matrices()["view"].tolist() == np.identity(4).tolist()


def test_the_quad_is_untransformed_and_models_are_not():
    assert load_scene({"mesh": "quad"}).untransformed
    assert not load_scene({"mesh": "sphere"}).untransformed


# ---------------------------------------------------------------------------------------------
# Errors, located at the offending value


@pytest.mark.parametrize("text, line, column, words", [
    ("mesh: sphere\ncolour: red\n", 2, 9, "unknown scene key 'colour'"),
    ("clear:\n  color: 'ff0000'\n", 2, 10, "neither [r, g, b, a] nor '0xAARRGGBB'"),
    ("clear: {color: [1, 0]}\n", 1, 16, "colour [1, 0]"),
    ("size: [0, 10]\n", 1, 7, "whole numbers from 1 to 8192"),
    ("size: 256\n", 1, 7, "size needs 2 numbers"),
    ("camera:\n  eye: [0, 0]\n", 2, 8, "camera eye needs 3 numbers"),
    ("camera: {fov: 200}\n", 1, 15, "fov 200.0 must be between 0 and 180"),
    ("camera: {zoom: 2}\n", 1, 16, "unknown camera key 'zoom'"),
    ("light: {position: [1, 2, 3], colour: [1, 1, 1]}\n", 1, 38, "unknown light key 'colour'"),
    ("vertex: {diffuse: blue}\n", 1, 19, "colour 'blue'"),
    ("mesh: donut\n", 1, 7, "unknown mesh 'donut'"),
    ("mesh: {primitive: loop, vertices: []}\n", 1, 19, "primitive must be one of strip, list, fan"),
    ("mesh:\n  primitive: list\n  vertices:\n    - {position: [0, 0, 0]}\n    - {position: [1, 0, 0]}\n"
     "    - {position: [0, 1]}\n", 6, 18, "vertex 2 position needs 3 or 4 numbers"),
    ("mesh:\n  primitive: strip\n  vertices:\n    - {position: [0, 0, 0], tex0: [0, 0]}\n"
     "    - {position: [1, 0, 0]}\n    - {position: [0, 1, 0], tex0: [0, 1]}\n", 5, 7,
     "vertex 1 lacks tex0, unlike vertex 0"),
    ("mesh: {primitive: list, vertices: [{position: [0, 0, 0]}, {position: [1, 0, 0]}, "
     "{position: [0, 1, 0]}, {position: [1, 1, 0]}]}\n", 1, 35, "multiple of 3 vertices, got 4"),
    ("params: [1, 2]\n", 1, 9, "params is a mapping"),
    ("streams: {texcoord1: [1]}\n", 1, 10, "streams is a mapping"),
    ("time: soon\n", 1, 7, "time needs a number"),
    ("clear:\n  color: [1, 1, 1, 1]\n  depth: 2\n", 3, 10, "clear depth 2.0 is outside 0..1"),
    ("mesh: [sphere\n", 2, 1, "not valid YAML"),
])
def test_scene_errors_are_located(tmp_path, text, line, column, words):
    error = error_of(tmp_path, text)
    assert (error.line, error.column) == (line, column), str(error)
    assert error.path.endswith("scene.yaml")
    assert words in error.message


def test_a_missing_scene_file_is_a_scene_error(tmp_path):
    with pytest.raises(SceneError, match="cannot read scene file"):
        load_scene(str(tmp_path / "nope.yaml"))


# ---------------------------------------------------------------------------------------------
# Semantic binding

EFFECT = """
float4x4 W : WORLD; float4x4 V : VIEW; float4x4 P : PROJECTION;
float4x4 WVP : WORLDVIEWPROJECTION; float4x4 VI : VIEWINVERSE;
float4 Eye : CAMERAPOSITION;
float4 LightPos : LIGHTPOSITION = {9, 9, 9, 1};
float3 LightDir : LIGHTDIRECTION;
float4 Plain = {1, 2, 3, 4};
matrix mTot; vector lhtR; MATRIX mViw;
technique T { pass P { } }
"""


def test_matrices_and_positions_bound_by_semantic():
    effect = load_effect(EFFECT)
    scene = load_scene({"camera": {"eye": [0, 0, -4], "target": [0, 0, 0], "fov": 90},
                        "size": [200, 100]})
    bound = bind_scene(effect, scene)
    # By hand: eye on -z looking at +z: the view is a translation by +4 in z;
    # fov 90: yScale = 1, xScale = 1 / aspect = 0.5; zf/(zf-zn) and -zn*zf/(zf-zn).
    view = np.identity(4)
    view[3, 2] = 4.0
    q = 100.0 / (100.0 - 0.1)
    proj = np.array([[0.5, 0, 0, 0], [0, 1, 0, 0], [0, 0, q, 1], [0, 0, -0.1 * q, 0]])
    assert bound["W"] == pytest.approx(np.identity(4))
    assert bound["V"] == pytest.approx(view)
    assert bound["P"] == pytest.approx(proj)
    assert bound["WVP"] == pytest.approx(view @ proj)
    assert bound["VI"][3, 2] == pytest.approx(-4.0)
    assert bound["Eye"].tolist() == [0, 0, -4, 1]
    # DX8 names stand in for semantics
    assert bound["mTot"] == pytest.approx(view @ proj) and bound["mViw"] == pytest.approx(view)
    assert "Plain" not in bound


def test_an_explicit_size_changes_the_aspect_of_the_projection():
    effect = load_effect(EFFECT)
    scene = load_scene({"camera": {"fov": 90}, "size": [200, 100]})
    assert bind_scene(effect, scene, (100, 100))["P"][0, 0] == pytest.approx(1.0)


def test_the_light_binds_only_when_the_scene_places_one_or_the_effect_has_none():
    effect = load_effect(EFFECT)
    unlit = bind_scene(effect, load_scene({}))
    assert "LightPos" not in unlit                       # the effect's {9, 9, 9, 1} stands
    # LightDir has no initial value: from the default light (2, 2, 2) to the target (origin)
    assert unlit["LightDir"] == pytest.approx(-np.ones(3) / math.sqrt(3))
    lit = bind_scene(effect, load_scene({"light": {"position": [0, 3, 0]}}))
    assert lit["LightPos"].tolist() == [0, 3, 0, 1]
    assert lit["LightDir"] == pytest.approx([0, -1, 0])
    assert lit["lhtR"] == pytest.approx([0, -1, 0, 0])   # DX8 name, w = 0 for a direction


def test_look_at_and_perspective_follow_d3dx():
    m = look_at_lh((0, 0, -5), (0, 0, 0), (0, 1, 0))
    assert (np.array([1, 2, 0, 1]) @ m).tolist() == [1, 2, 5, 1]
    p = perspective_fov_lh(math.pi / 2, 1.0, 1.0, 10.0)
    near = np.array([0, 0, 1, 1]) @ p
    far = np.array([0, 0, 10, 1]) @ p
    assert near[2] / near[3] == pytest.approx(0.0) and far[2] / far[3] == pytest.approx(1.0)


def test_a_cameras_matrices_are_made_once_and_shared_read_only():
    # every Runtime takes its camera's matrices: one array per placement, which no caller may
    # write into (a caller that did would move every other Runtime's camera)
    a = load_scene({"camera": {"eye": [0, 1, 4], "fov": 60}}).matrices((64, 48))
    b = load_scene({"camera": {"eye": [0.0, 1.0, 4.0], "fov": 60.0}}).matrices((64, 48))
    assert a["view"] is b["view"] and a["projection"] is b["projection"]
    np.testing.assert_array_equal(a["view"], look_at_lh((0, 1, 4), (0, 0, 0), (0, 1, 0)))
    np.testing.assert_array_equal(a["projection"],
                                  perspective_fov_lh(math.radians(60), 64 / 48, 0.1, 100.0))
    with pytest.raises(ValueError):
        a["view"][3, 2] = 0.0
    assert load_scene(None).matrices((64, 64))["projection"] is not a["projection"]


# ---------------------------------------------------------------------------------------------
# Values a user writes (--set, params)

VALUES = """
float F = 1; float3 V3; float4 C; float4x4 M; int I; DWORD D; bool B; half H;
float2 A[2]; string S = "x"; texture T; sampler Smp; pixelshader Psh;
technique T0 { pass P { } }
"""


@pytest.mark.parametrize("name, text, expected", [
    ("F", "24", 24.0), ("F", "0.5", 0.5), ("F", "1.5f", 1.5), ("H", "2", 2.0),
    ("V3", "1,0.5,0.25", [1, 0.5, 0.25]), ("V3", "[1, 0.5, 0.25]", [1, 0.5, 0.25]),
    ("C", "1,0.5,0.25,1", [1, 0.5, 0.25, 1]), ("C", "(1 0 0)", [1, 0, 0, 1]),
    ("C", "0x80ff0000", [1, 0, 0, 128 / 255]), ("V3", "0xff00ff00", [0, 1, 0]),
    ("I", "-3", -3), ("D", "0xff0000ff", 0xFF0000FF), ("B", "true", True), ("B", "0", False),
    ("A", "1,2,3,4", [[1, 2], [3, 4]]), ("S", "hello", "hello"),
    ("M", ",".join(str(i) for i in range(16)), np.arange(16).reshape(4, 4).tolist()),
])
def test_set_values_are_parsed_to_the_parameter_type(name, text, expected):
    effect = load_effect(VALUES)
    value = coerce_value(effect.parameter(name), text)
    if isinstance(expected, str):
        assert value == expected
    else:
        assert np.asarray(value, np.float64) == pytest.approx(np.asarray(expected, np.float64))
        assert np.asarray(value).shape == np.asarray(expected).shape


def test_set_value_types_follow_the_parameter():
    effect = load_effect(VALUES)
    assert coerce_value(effect.parameter("F"), 3).dtype == np.float32
    assert coerce_value(effect.parameter("I"), "3").dtype == np.int32
    assert coerce_value(effect.parameter("D"), "0xffffffff").dtype == np.int64
    assert coerce_value(effect.parameter("T"), " stone.png ") == "stone.png"


@pytest.mark.parametrize("name, value, words", [
    ("F", "abc", "'abc' is not a number"),
    ("F", "1,2", "takes a number, got 2"),
    ("V3", "1,2", "takes 3 numbers, got 2"),
    ("I", "1.5", "whole numbers"),
    ("D", "-1", "0..0xFFFFFFFF"),
    ("F", "nan", "not a finite number"),
    ("S", 3, "takes text"),
    ("T", 3, "takes an image path"),
    ("Smp", 3, "takes an image path"),        # the host sets a texture on its stage
    ("Psh", "x", "cannot be set"),
])
def test_values_that_do_not_fit_name_the_parameter_and_its_declaration(name, value, words):
    effect = load_effect(VALUES)
    param = effect.parameter(name)
    with pytest.raises(SceneError) as info:
        coerce_value(param, value, None, "--set")
    error = info.value
    assert (error.line, error.column) == (param.location.line, param.location.column)
    assert error.message.startswith(f"--set {name}=")
    assert name in error.message and words in error.message


def test_a_scene_value_error_points_at_the_scene_and_names_the_declaration(tmp_path):
    from effects.base.errors import Location
    effect = load_effect(VALUES)
    param = effect.parameter("F")
    with pytest.raises(SceneError) as info:
        coerce_value(param, "x", Location("scene.yaml", 3, 7), "scene params")
    assert str(info.value).startswith("scene.yaml:3:7: error: scene params F='x': float F "
                                      f"(declared at {param.location})")


def test_parse_assignments():
    assert parse_assignments(["A=1", "B = 1,2", "C=x=y"]) == {"A": "1", "B": "1,2", "C": "x=y"}
    with pytest.raises(SceneError, match="expected NAME=VALUE"):
        parse_assignments(["A"])
