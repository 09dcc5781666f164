"""effects.render: the contract (shape, dtype, orientation), technique choice, device state
per render and across passes, parameter values, textures and vertex streams."""
from __future__ import annotations

from tests.paths import ROOT

import os

import numpy as np
import pytest
from PIL import Image

import effects

ROOT = str(ROOT)
from effects import NoValidTechnique, SceneError, load_effect, load_profile
from effects.host.resources import TextureCache, geometry, scene_mesh
from effects.host.runtime import Runtime, render_frame
from effects.host.scene import load_scene

# One suite, every back end: the contract tests run on both.
BACKENDS = pytest.mark.parametrize("backend", ["numpy", "gl"])
RED, GREEN, BLUE, WHITE = (255, 0, 0, 255), (0, 255, 0, 255), (0, 0, 255, 255), (255, 255, 255, 255)

# Draws the vertex diffuse colour: no lighting, stage 0 selects DIFFUSE for colour and alpha.
DIFFUSE_PASS = """
        Lighting = False;
        ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse;
        AlphaOp[0] = SelectArg1; AlphaArg1[0] = Diffuse;
"""
DIFFUSE_EFFECT = f"technique Diffuse {{ pass P {{ {DIFFUSE_PASS} }} }}"


def strip(x0, y0, x1, y1, diffuse="0xffffffff", z=0.5, **extra):
    """Inline clip-space vertices of the rectangle (x0, y0)-(x1, y1) as a strip, clockwise on
    screen (front-facing under the default CullMode = CCW)."""
    corners = [(x0, y1), (x1, y1), (x0, y0), (x1, y0)]
    return {"primitive": "strip",
            "vertices": [{"position": [x, y, z], "diffuse": diffuse, **extra} for x, y in corners]}


def full_screen(diffuse="0xffffffff"):
    return strip(-1, -1, 1, 1, diffuse)


# ---------------------------------------------------------------------------------------------
# The contract


@BACKENDS
def test_render_returns_h_w_4_uint8_rgba_with_row_0_at_the_top(backend):
    # A red rectangle over the top half (clip y from 0 to 1 is the upper half of the screen)
    # on a blue clear.
    scene = {"mesh": strip(-1, 0, 1, 1, "0xffff0000"), "clear": {"color": "0xff0000ff"}}
    image = effects.render(load_effect(DIFFUSE_EFFECT), load_profile("geforce2"), scene=scene,
                           size=(8, 6), backend=backend)
    assert image.shape == (6, 8, 4) and image.dtype == np.uint8
    assert (image[:3] == RED).all(), image[:, :, 0]
    assert (image[3:] == BLUE).all(), image[:, :, 2]


def test_a_profile_may_be_named_and_an_effect_given_as_a_path(tmp_path):
    path = tmp_path / "diffuse.fx"
    path.write_text(DIFFUSE_EFFECT)
    image = effects.render(str(path), "tnt2", scene={"mesh": full_screen("0xff00ff00")}, size=(2, 2))
    assert (image == GREEN).all()


def test_an_explicit_size_wins_over_the_scenes():
    effect = load_effect(DIFFUSE_EFFECT)
    scene = {"mesh": full_screen(), "size": [16, 8]}
    assert effects.render(effect, "tnt2", scene=scene).shape == (8, 16, 4)
    assert effects.render(effect, "tnt2", scene=scene, size=(10, 4)).shape == (4, 10, 4)


@pytest.mark.parametrize("size", [(0, 4), (4,), "4x4", (2.5, 3)])
def test_a_bad_size_is_a_scene_error(size):
    with pytest.raises(SceneError, match="size"):
        effects.render(load_effect(DIFFUSE_EFFECT), "tnt2", scene={"mesh": "quad"}, size=size)


# ---------------------------------------------------------------------------------------------
# Which technique


PS20_THEN_DOT3 = f"""
technique Shader {{ pass P {{ PixelShader = asm {{ ps.2.0
    mov oC0, c0
}}; }} }}
technique Dot3 {{ pass P {{ {DIFFUSE_PASS} ColorOp[0] = DotProduct3; ColorArg2[0] = Diffuse; }} }}
"""


def test_no_valid_technique_carries_every_reason():
    effect = load_effect(PS20_THEN_DOT3)
    with pytest.raises(NoValidTechnique) as info:
        effects.render(effect, "tnt2", scene={"mesh": "quad"}, size=(4, 4))
    error = info.value
    assert isinstance(error, effects.EffectError)
    assert set(error.reasons) == {"Shader", "Dot3"}
    assert all(error.reasons[name] for name in ("Shader", "Dot3"))
    text = str(error)
    assert "ps_2_0" in text and "D3DTEXOPCAPS_DOTPRODUCT3" in text and "RIVA TNT2" in text


def test_an_effect_without_techniques_has_nothing_to_render():
    with pytest.raises(NoValidTechnique, match="no techniques"):
        effects.render(load_effect("float4 C;\n"), "tnt2")


@BACKENDS
def test_a_named_technique_renders_as_asked_even_when_invalid(backend):
    # DOTPRODUCT3 of red with itself: 4 * ((1-.5)^2 + (0-.5)^2 + (0-.5)^2) = 3, saturated to 1
    # and replicated to every channel: white, which no TNT2 could draw.
    effect = load_effect(PS20_THEN_DOT3)
    assert not effect.validate("Dot3", load_profile("tnt2")).ok
    image = effects.render(effect, "tnt2", technique="Dot3",
                           scene={"mesh": full_screen("0xffff0000")}, size=(2, 2), backend=backend)
    assert (image == WHITE).all()


def test_the_card_selects_the_first_valid_technique():
    frame = render_frame(load_effect(PS20_THEN_DOT3), "geforce2",
                         scene={"mesh": full_screen("0xffff0000")}, size=(2, 2))
    assert frame.technique.name == "Dot3" and frame.passes == 1
    assert (frame.image == WHITE).all()


def test_an_unknown_technique_name_is_an_effect_error():
    with pytest.raises(effects.EffectError, match="no technique named 'Nope'"):
        effects.render(load_effect(DIFFUSE_EFFECT), "tnt2", technique="Nope")


# ---------------------------------------------------------------------------------------------
# Device state: fresh per render, persisting across passes


STATEFUL = f"""
technique Invisible {{ pass P {{ {DIFFUSE_PASS}
    AlphaBlendEnable = True; SrcBlend = Zero; DestBlend = One;   // keeps the target as it is
    CullMode = CW; ZFunc = Never;
}} }}
technique Plain {{ pass P {{ {DIFFUSE_PASS} }} }}
"""


@BACKENDS
def test_each_render_starts_from_the_default_device_state(backend):
    effect = load_effect(STATEFUL)
    scene = {"mesh": full_screen("0xffff0000"), "clear": {"color": "0xff0000ff"}}
    runtime = Runtime(effect, "geforce2", scene=scene, size=(4, 4), backend=backend)
    first = runtime.render("Invisible").image
    assert (first == BLUE).all()            # blending (0, 1) left the clear colour
    second = runtime.render("Plain").image
    assert (second == RED).all()            # none of the first render's states leaked
    again = effects.render(effect, "geforce2", technique="Plain", scene=scene, size=(4, 4),
                           backend=backend)
    assert (again == RED).all()


@BACKENDS
def test_states_set_by_a_pass_persist_into_the_following_passes(backend):
    # Pass 0 draws red and turns on additive blending; pass 1 only switches the colour source
    # to TFACTOR (green). Blending persists, so the result is red + green = yellow; ColorOp
    # SelectArg1 persists too.
    effect = load_effect(f"""
        technique Two {{
            pass P0 {{ {DIFFUSE_PASS} AlphaBlendEnable = True; SrcBlend = One; DestBlend = One; }}
            pass P1 {{ TextureFactor = 0xff00ff00; ColorArg1[0] = TFactor; }}
        }}""")
    frame = render_frame(effect, "geforce2", scene={"mesh": full_screen("0xffff0000")}, size=(3, 3),
                         backend=backend)
    assert frame.passes == 2
    assert (frame.image == (255, 255, 0, 255)).all()


# ---------------------------------------------------------------------------------------------
# Parameter values


TFACTOR_EFFECT = f"""
DWORD Col = 0xff0000ff;
technique T {{ pass P {{ {DIFFUSE_PASS} TextureFactor = <Col>; ColorArg1[0] = TFactor; }} }}
"""


def test_params_set_values_on_a_copy_and_never_change_the_callers_effect():
    effect = load_effect(TFACTOR_EFFECT)
    scene = {"mesh": full_screen()}
    assert (effects.render(effect, "tnt2", scene=scene, size=(2, 2)) == BLUE).all()
    image = effects.render(effect, "tnt2", scene=scene, size=(2, 2), params={"Col": "0xff00ff00"})
    assert (image == GREEN).all()
    assert int(effect.parameter("Col").value) == 0xFF0000FF
    assert (effects.render(effect, "tnt2", scene=scene, size=(2, 2)) == BLUE).all()


def test_params_win_over_scene_params():
    effect = load_effect(TFACTOR_EFFECT)
    scene = {"mesh": full_screen(), "params": {"Col": "0xffff0000"}}
    assert (effects.render(effect, "tnt2", scene=scene, size=(2, 2)) == RED).all()
    image = effects.render(effect, "tnt2", scene=scene, size=(2, 2), params={"Col": 0xFF00FF00})
    assert (image == GREEN).all()


def test_an_unknown_parameter_is_a_scene_error_naming_it():
    with pytest.raises(SceneError, match="'Colour'.*no parameter of that name"):
        effects.render(load_effect(TFACTOR_EFFECT), "tnt2", params={"Colour": 1})
    with pytest.raises(SceneError, match="scene params: 'Colour'"):
        effects.render(load_effect(TFACTOR_EFFECT), "tnt2", scene={"params": {"Colour": 1}})


def test_set_value_and_commit_changes_like_id3dxeffect():
    runtime = Runtime(load_effect(TFACTOR_EFFECT), "tnt2", scene={"mesh": full_screen()}, size=(2, 2))
    assert runtime.begin() == 1
    runtime.begin_pass(0)
    runtime.draw()
    runtime.set_value("Col", "0xffff0000")
    runtime.commit_changes()
    runtime.draw()
    runtime.end_pass()
    assert (runtime.end() == RED).all()


def test_semantic_matrices_place_the_mesh():
    # A unit sphere 3 units from the eye, vertical fov 90 (tan 45 = 1), 64 x 64 pixels: its
    # outline has angular radius asin(1/3), so its radius is 32 * tan(asin(1/3)) = 11.3 px.
    effect = load_effect(f"""
        float4x4 W : WORLD; float4x4 V : VIEW; float4x4 P : PROJECTION;
        technique T {{ pass P0 {{ {DIFFUSE_PASS}
            WorldTransform[0] = <W>; ViewTransform = <V>; ProjectionTransform = <P>; }} }}""")
    scene = {"mesh": "sphere", "camera": {"eye": [0, 0, 3], "fov": 90}, "clear": {"color": "0xff000000"}}
    image = effects.render(effect, "tnt2", scene=scene, size=(64, 64))
    covered = (image[..., :3] == 255).all(-1)
    assert covered[32, 32] and covered[32, 32 + 9] and covered[32 - 9, 32]
    assert not covered[32, 32 + 14] and not covered[32 + 14, 32] and not covered[0, 0]


# ---------------------------------------------------------------------------------------------
# Textures


def write_png(path, rows):
    Image.fromarray(np.asarray(rows, np.uint8), "RGBA").save(path)


TEXTURED = """
texture Tex < string ResourceName = "four.png"; string Type = "2D"; >;
technique T { pass P {
    Lighting = False; Texture[0] = <Tex>; MinFilter[0] = Point; MagFilter[0] = Point;
    ColorOp[0] = SelectArg1; ColorArg1[0] = Texture; AlphaOp[0] = SelectArg1; AlphaArg1[0] = Texture;
} }
"""


@pytest.fixture()
def textured(tmp_path):
    """An effect file whose texture names a 2x2 image beside it: red, green / blue, white."""
    write_png(tmp_path / "four.png", [[RED, GREEN], [BLUE, WHITE]])
    path = tmp_path / "textured.fx"
    path.write_text(TEXTURED)
    return path


def quads(image, a, b, c, d):
    """Each 2x2 corner block of a 4x4 image has one colour (row 0 at the top)."""
    return ((image[:2, :2] == a).all() and (image[:2, 2:] == b).all()
            and (image[2:, :2] == c).all() and (image[2:, 2:] == d).all())


@BACKENDS
def test_resource_name_loads_relative_to_the_effect_file(textured, backend):
    image = effects.render(load_effect(str(textured)), "tnt2", scene={"mesh": "quad"}, size=(4, 4),
                           backend=backend)
    assert quads(image, RED, GREEN, BLUE, WHITE), image


def test_a_set_path_is_relative_to_the_cwd_and_wins(textured, tmp_path, monkeypatch):
    other = tmp_path / "sub"
    other.mkdir()
    write_png(other / "swap.png", [[WHITE, BLUE], [GREEN, RED]])
    monkeypatch.chdir(other)
    image = effects.render(load_effect(str(textured)), "tnt2", scene={"mesh": "quad"}, size=(4, 4),
                           params={"Tex": "swap.png"})
    assert quads(image, WHITE, BLUE, GREEN, RED)


def test_a_scene_path_is_relative_to_the_scene_file(textured, tmp_path):
    folder = tmp_path / "scenes"
    folder.mkdir()
    write_png(folder / "green.png", [[GREEN]])
    (folder / "s.yaml").write_text("mesh: quad\nsize: [4, 4]\nparams: {Tex: green.png}\n")
    image = effects.render(load_effect(str(textured)), "tnt2", scene=str(folder / "s.yaml"))
    assert (image == GREEN).all()


def test_a_missing_image_is_located_where_it_was_named(textured, tmp_path):
    (tmp_path / "s.yaml").write_text("mesh: quad\nparams:\n  Tex: nothere.png\n")
    with pytest.raises(SceneError) as info:
        effects.render(load_effect(str(textured)), "tnt2", scene=str(tmp_path / "s.yaml"))
    assert (info.value.path, info.value.line, info.value.column) == (str(tmp_path / "s.yaml"), 3, 8)
    assert "not found" in info.value.message


def test_procedural_textures_are_generated():
    # checker:2 is 2 x 2 squares, top-left white: point-sampled over a 4x4 quad.
    effect = load_effect(TEXTURED.replace('string ResourceName = "four.png"', 'string Procedural = "checker:2"'))
    image = effects.render(effect, "tnt2", scene={"mesh": "quad"}, size=(4, 4))
    black = (0, 0, 0, 255)
    assert quads(image, WHITE, black, black, WHITE)


def test_a_procedural_argument_follows_the_parameter_it_names():
    # checker:<Squares>: 2 squares a side, then 4 (the texture is made again after set_value)
    text = 'float Squares = 2;\n' + TEXTURED.replace('string ResourceName = "four.png"',
                                                     'string Procedural = "checker:<Squares>"')
    runtime = Runtime(load_effect(text), "tnt2", scene={"mesh": "quad"}, size=(4, 4))
    black = (0, 0, 0, 255)
    assert quads(runtime.render().image, WHITE, black, black, WHITE)
    assert runtime.texture("Tex").name == "checker:2"
    runtime.set_value("Squares", 4)
    image = runtime.render().image
    assert (image[0, 0] == WHITE).all() and (image[0, 1] == black).all()
    assert runtime.texture("Tex").name == "checker:4"


@pytest.mark.parametrize("argument, message", [
    ("<Nope>", "names <Nope>, which is no parameter"),
    ("<Name>", "Name is not a finite number"),
    ("2*<Big>", "texture size|procedural texture 'checker'")])
def test_a_procedural_argument_naming_a_bad_parameter_is_located(argument, message):
    text = ('string Name = "x";\nfloat Big = 1e30;\n'
            + TEXTURED.replace('string ResourceName = "four.png"', f'string Procedural = "checker:{argument}"'))
    effect = load_effect(text)
    with pytest.raises(SceneError, match=message) as info:
        effects.render(effect, "tnt2", scene={"mesh": "quad"}, size=(4, 4))
    assert info.value.line == 4                    # the texture's annotation


def test_an_unbound_texture_samples_nothing_and_the_pass_still_draws():
    effect = load_effect(TEXTURED.replace('string ResourceName = "four.png";', ""))
    image = effects.render(effect, "tnt2", scene={"mesh": "quad"}, size=(2, 2))
    assert image.shape == (2, 2, 4)


def test_a_texture_of_the_wrong_kind_is_a_scene_error(textured):
    cube = load_effect(TEXTURED.replace('"2D"', '"CUBE"').replace("four.png", str(textured.parent / "four.png")))
    with pytest.raises(SceneError, match="a 2d texture, but a cube texture is needed"):
        effects.render(cube, "geforce2", scene={"mesh": "quad"}, size=(2, 2))


def test_an_untyped_texture_takes_the_kind_of_what_is_bound(tmp_path):
    cube = np.zeros((6, 4, 4, 4), np.uint8)
    np.save(tmp_path / "cube.npy", cube)
    effect = load_effect("texture T; technique X { pass P { Texture[0] = <T>; } }")
    runtime = Runtime(effect, "tnt2", params={"T": str(tmp_path / "cube.npy")})
    assert runtime.effect.parameter("T").type.dim == "CUBE"
    assert effect.parameter("T").type.dim == ""          # the caller's effect is untouched
    assert runtime.texture("T").kind == "cube"


def test_loaded_images_are_cached_until_the_file_changes(textured):
    cache = TextureCache()
    effect = load_effect(str(textured))
    for _ in range(2):
        Runtime(effect, "tnt2", scene={"mesh": "quad"}, textures=cache).texture("Tex")
    assert cache.loads == 1
    stamp = os.stat(textured.parent / "four.png").st_mtime_ns
    os.utime(textured.parent / "four.png", ns=(stamp + 10**9, stamp + 10**9))
    Runtime(effect, "tnt2", scene={"mesh": "quad"}, textures=cache).texture("Tex")
    assert cache.loads == 2


# ---------------------------------------------------------------------------------------------
# Vertex streams


def test_mesh_streams_and_their_defaults():
    scene = load_scene({"mesh": "cube", "vertex": {"diffuse": [0.5, 0.25, 1, 1], "specular": "0xff00ff00"}})
    mesh = scene_mesh(scene)
    geo = geometry(scene, load_effect(DIFFUSE_EFFECT))
    s = geo.streams
    assert np.array_equal(s["position"], mesh.positions) and np.array_equal(s["normal"], mesh.normals)
    assert np.array_equal(s["tangent"], mesh.tangents) and np.array_equal(s["binormal"], mesh.binormals)
    assert s["color0"].shape == (mesh.vertex_count, 4) and (s["color0"] == [0.5, 0.25, 1, 1]).all()
    assert (s["color1"] == [0, 1, 0, 1]).all()
    for i in range(8):
        assert np.array_equal(s[f"texcoord{i}"], mesh.uv)
    assert geo.primitive == "list" and np.array_equal(geo.indices, mesh.indices)


def test_the_default_vertex_colours_are_white_and_black():
    geo = geometry(load_scene({"mesh": "quad"}), load_effect(DIFFUSE_EFFECT))
    assert (geo.streams["color0"] == 1).all() and (geo.streams["color1"] == 0).all()


STREAMS_EFFECT = 'string VertexStreams = "texcoord1=binormal, texcoord3=normal";\n' + DIFFUSE_EFFECT


def test_the_effect_and_the_scene_choose_what_feeds_a_texcoord_set():
    effect = load_effect(STREAMS_EFFECT)
    scene = load_scene({"mesh": "sphere", "streams": {"texcoord1": "tangent", "texcoord2": "binormal"}})
    mesh = scene_mesh(scene)
    s = geometry(scene, effect).streams
    assert np.array_equal(s["texcoord1"], mesh.tangents)      # the scene wins over the effect
    assert np.array_equal(s["texcoord2"], mesh.binormals)
    assert np.array_equal(s["texcoord3"], mesh.normals)       # the effect's own default
    assert np.array_equal(s["texcoord0"], mesh.uv)


def test_brdf_reads_its_tangent_from_texcoord1():
    effect = load_effect(os.path.join(str(ROOT), "fxfiles", "brdf.fx"))
    scene = load_scene({"mesh": "sphere"})
    assert np.array_equal(geometry(scene, effect).streams["texcoord1"], scene_mesh(scene).tangents)


def test_a_bad_stream_override_is_located(tmp_path):
    path = tmp_path / "s.yaml"
    path.write_text("mesh: sphere\nstreams:\n  texcoord1: tangnet\n")
    with pytest.raises(SceneError) as info:
        geometry(load_scene(str(path)), load_effect(DIFFUSE_EFFECT))
    assert (info.value.line, info.value.column) == (3, 14)
    assert "unknown vertex attribute 'tangnet'" in info.value.message
    bad = load_effect('string VertexStreams = "texcoord9=uv";\n' + DIFFUSE_EFFECT)
    with pytest.raises(SceneError, match="unknown vertex stream 'texcoord9'") as info:
        geometry(load_scene({"mesh": "quad"}), bad)
    assert info.value.line == 1


def test_inline_vertices_feed_their_own_attributes():
    scene = load_scene({"mesh": strip(-1, -1, 1, 1, "0x80ff0000", tex0=[0.25, 0.75],
                                      normal=[0, 0, -1])})
    geo = geometry(scene, load_effect(DIFFUSE_EFFECT))
    assert geo.primitive == "strip" and geo.indices.tolist() == [0, 1, 2, 3]
    assert geo.streams["color0"][0] == pytest.approx([1, 0, 0, 128 / 255])
    assert (geo.streams["texcoord0"] == [0.25, 0.75]).all()
    assert (geo.streams["texcoord5"] == [0.25, 0.75]).all()
    assert (geo.streams["normal"] == [0, 0, -1]).all()
    assert "tangent" not in geo.streams
    with pytest.raises(SceneError, match="the mesh has no tangent"):
        geometry(load_scene({"mesh": full_screen(), "streams": {"texcoord1": "tangent"}}),
                 load_effect(DIFFUSE_EFFECT))


# ---------------------------------------------------------------------------------------------
# The bundled effects (these need the shader lowering for the shader techniques)

FXFILES = os.path.join(str(ROOT), "fxfiles")


@pytest.mark.parametrize("name, card", [
    ("phong.fx", "tnt2"), ("phong.fx", "geforce3"), ("phong.fx", "radeon9700"),
    ("specular_bump.fx", "tnt2"), ("specular_bump.fx", "geforce3"), ("specular_bump.fx", "radeon9700"),
])
def test_bundled_effects_render_a_lit_textured_sphere(name, card):
    frame = render_frame(os.path.join(FXFILES, name), card, size=(64, 64))
    image = frame.image.astype(int)
    centre, corner = image[32, 32], image[0, 0]
    assert tuple(corner) == (0, 0, 0, 0)                  # the clear colour around the sphere
    assert centre[:3].sum() > 30                          # the sphere is lit where it faces us
    inside = image[20:44, 20:44, :3].reshape(-1, 3)
    assert inside.std(axis=0).max() > 4                   # and textured, not flat


def test_a_scene_param_may_name_a_texture_generator():
    # DX8 files cannot annotate their textures; the bundled scene for sdk8_style.fx gives them,
    # two of them by generator ('sobel_normals:<image>', 'sky_cube:64') rather than by file.
    from effects.host.resources import resolve_texture, TextureSource
    from effects.base.errors import Location
    effect = load_effect(os.path.join(ROOT, "fxfiles", "sdk8_style.fx"))
    at = Location("scene.yaml", 1, 1)
    fx_dir = os.path.join(ROOT, "fxfiles")
    env = resolve_texture(effect.parameter("tEnv"), effect, TextureSource("sky_cube:16", fx_dir, at))
    assert env.kind == "cube" and env.width == 16
    normals = resolve_texture(effect.parameter("tNrm"), effect,
                              TextureSource("sobel_normals:textures/stones_height.png", fx_dir, at))
    assert normals.kind == "2d" and normals.levels[0][..., 2].min() > 0.5   # z of 0.5 + 0.5 n
    image = effects.render(effect, load_profile("geforce3"), size=(32, 32),
                           scene=os.path.join(ROOT, "fxfiles", "sdk8_style.yaml"))
    assert image[..., :3].std() > 10   # textured, not black
