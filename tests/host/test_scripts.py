"""DXSAS Script annotations: render-target chains of post-processing effects, on both back
ends, against values computed by hand."""
from __future__ import annotations

from tests.paths import TESTS


import numpy as np
import pytest

import effects
from effects.base.errors import EffectError
from effects.host.runtime import Runtime, render_frame
from effects.host.scripts import parse_script, target_format, target_size, unsupported_commands
from effects.assets.textures import make_texture
from effects.base.errors import Location

BACKENDS = ["numpy", "gl"]
DATA = TESTS / "data" / "realfx"
HERE = Location("<test>", 1, 1)


def quadrant_scene(size: int = 32) -> dict:
    """White over the pixels px <= 16, py <= 16 of a 32x32 frame (D3D pixel centres are at
    integer positions: px/32*2-1 < 0.03 for px <= 16), on the effect's opaque black clear."""
    v = [{"position": p, "diffuse": "0xffffffff", "tex0": [0, 0]}
         for p in ([-1, 1, 0.5], [0.03, 1, 0.5], [-1, -0.03, 0.5], [0.03, -0.03, 0.5])]
    return {"mesh": {"primitive": "strip", "vertices": v}, "size": [size, size]}


def box4(line: np.ndarray) -> np.ndarray:
    """The effect's 4-tap box at texel offsets -1, 0, +1, +2, clamped at the borders."""
    n = len(line)
    idx = np.clip(np.arange(n)[:, None] + np.array([-1, 0, 1, 2])[None, :], 0, n - 1)
    return line[idx].mean(axis=1)


@pytest.mark.parametrize("backend", BACKENDS)
def test_post_blur_renders_through_its_target_chain(backend):
    effect = effects.load_effect(DATA / "own_postblur.fx")
    white = make_texture(np.ones((1, 1, 4), np.float32), mips=False)
    frame = render_frame(effect, "geforce3", backend=backend, scene=quadrant_scene(),
                         params={"SceneTexture": white})
    assert frame.technique.name == "Blur" and frame.passes == 3 and not frame.warnings
    covered = (np.arange(32) <= 16).astype(float)
    h = box4(covered)                                  # the horizontal pass, per column
    v = box4(covered)                                  # the vertical pass, per row
    h8 = np.round(h * 255) / 255                       # BlurMap holds 8 bits
    expected = np.round(np.outer(v, h8) * 255)
    got = frame.image[..., 0].astype(float)
    assert np.abs(got - expected).max() <= 2, np.argwhere(np.abs(got - expected) > 2)[:5]
    # by hand at a few places: inside, the blurred corner, outside
    assert got[5, 5] == 255 and got[30, 30] == 0
    assert abs(got[16, 16] - 255 * 0.5 * 0.5) <= 2     # taps 15,16 inside, 17,18 outside
    assert abs(got[5, 15] - 255 * 0.75) <= 2           # taps 14,15,16 inside
    assert (frame.image[..., 3] == 255).all()          # ClearColor's alpha is 1


LOOP = """
float4 Half = {0.25, 0.25, 0.25, 1};
int Count = 3;
float4 Black = {0, 0, 0, 1};
technique Add < string Script = "RenderColorTarget0=; ClearSetColor=Black; Clear=Color;"
                                "LoopByCount=Count; Pass=P; LoopEnd=;"; > {
    pass P < string Script = "Draw=Buffer;"; > {
        Lighting = false; TextureFactor = 0xff404040;
        ColorOp[0] = SelectArg1; ColorArg1[0] = TFactor; AlphaOp[0] = SelectArg1; AlphaArg1[0] = TFactor;
        AlphaBlendEnable = true; SrcBlend = One; DestBlend = One; ZEnable = false;
    }
}
"""


@pytest.mark.parametrize("backend", BACKENDS)
def test_loop_by_count_repeats_its_passes(backend):
    # three additive draws of 0x40 = 64 on black: 192
    frame = render_frame(effects.load_effect(LOOP), "geforce2", backend=backend,
                         scene={"mesh": "sphere"}, size=(8, 8))
    assert frame.passes == 3
    assert (frame.image[..., 0] == 192).all()


def test_draw_buffer_ignores_the_camera_of_a_fixed_function_pass():
    # the quad covers the frame although the scene camera looks at a sphere
    frame = render_frame(effects.load_effect(LOOP.replace("int Count = 3", "int Count = 1")),
                         "geforce2", scene={"mesh": "sphere"}, size=(8, 8))
    assert (frame.image[..., 0] == 64).all()


def test_script_external_draws_the_scene_with_the_hosts_material():
    text = """technique T < string Script = "RenderColorTarget0=; Clear=Color; Clear=Depth;"
                                            "ScriptExternal=color;"; > { pass P { } }"""
    frame = render_frame(effects.load_effect(text), "geforce2", scene={"mesh": "sphere"},
                         size=(32, 32))
    image = frame.image
    assert image[16, 16, :3].max() > 40 and image[0, 0, :3].max() == 0   # a lit sphere
    assert len(np.unique(image[8:24, 8:24, 0])) > 4                      # checkered, shaded


def test_script_parsing_and_targets():
    commands = parse_script("RenderColorTarget0=Map; ;Clear=Color;Draw=Buffer;Frob=1", HERE)
    assert [(c.name, c.value, c.known) for c in commands] == [
        ("RenderColorTarget0", "Map", True), ("Clear", "Color", True), ("Draw", "Buffer", True),
        ("Frob", "1", False)]
    effect = effects.load_effect("""
        texture A : RenderColorTarget < float2 ViewportRatio = {0.5, 0.25}; string Format = "A16B16G16R16F"; >;
        texture B : RENDERCOLORTARGET < int2 Dimensions = {64, 32}; string Format = "D3DFMT_X8R8G8B8"; >;
        texture C : RenderColorTarget < string Format = "DXT1"; >;
        technique T < string Script = "ScriptExternal=depth; RenderPort=x;"; > { pass P { } }""")
    a, b, c = effect.parameters
    assert target_size(a, (256, 128)) == (128, 32) and target_format(a) == "A16B16G16R16F"
    assert target_size(b, (256, 128)) == (64, 32) and target_format(b) == "X8R8G8B8"
    assert target_size(c, (256, 128)) == (256, 128) and target_format(c) == "A8R8G8B8"
    assert [c.name for c in unsupported_commands(effect, effect.techniques[0])] == [
        "ScriptExternal", "RenderPort"]


@pytest.mark.parametrize("script, message", [
    ("LoopByCount=2; Pass=P;", "LoopByCount without LoopEnd"),
    ("LoopEnd=;", "LoopEnd without LoopByCount"),
    ("Pass=Q;", "Pass=Q: technique T has no such pass (passes: P)"),
    ("Draw=Geometry;", "Draw=Geometry outside a pass"),
    ("RenderColorTarget0=Nope;", "'Nope' is not a texture parameter"),
    ("Clear=Everything;", "Clear=Everything: expected Color, Depth or Stencil"),
    ("LoopByCount=100000; LoopEnd=;", "at most 256"),
    ("Clear", "script command 'Clear' is not NAME=VALUE"),
])
def test_script_errors_are_located_at_the_annotation(script, message):
    text = f'technique T <\n  string Script = "{script}"; > {{ pass P {{ }} }}'
    with pytest.raises(EffectError) as err:
        effects.render(effects.load_effect(text), "geforce2", scene={"mesh": "quad"}, size=(4, 4))
    assert ":2:10: error: script" in str(err.value) or ":2:10: error: " in str(err.value)
    assert message in str(err.value)


def test_an_unknown_command_warns_and_strict_fails():
    text = 'technique T < string Script = "RenderPort=x; Pass=P;"; > { pass P { } }'
    frame = render_frame(effects.load_effect(text), "geforce2", scene={"mesh": "quad"}, size=(4, 4))
    assert [str(w) for w in frame.warnings] == [
        "<string>:1:22: warning: script command RenderPort=x is not supported; ignored"]
    with pytest.raises(EffectError, match="RenderPort=x is not supported"):
        Runtime(effects.load_effect(text), "geforce2", scene={"mesh": "quad"}, size=(4, 4),
                strict=True).render()


def test_an_empty_script_external_draws_nothing():
    text = """float4 Black = {0, 0, 0, 1};
    technique T < string Script = "RenderColorTarget0=; ClearSetColor=Black; Clear=Color;"
                                  "ScriptExternal=;"; > { pass P { } }"""
    frame = render_frame(effects.load_effect(text), "geforce2", scene={"mesh": "sphere"},
                         size=(8, 8))
    assert (frame.image[..., :3] == 0).all() and (frame.image[..., 3] == 255).all()
    assert not frame.warnings


RESUME = """
texture A : RenderColorTarget;
texture B : RenderColorTarget;
float4 Black = {0, 0, 0, 1};
technique T < string Script =
        "RenderColorTarget0=A; ClearSetColor=Black; Clear=Color; Pass=Add;"
        "RenderColorTarget0=B; Clear=Color; Pass=Add;"
        "RenderColorTarget0=A; Pass=Add;"
        "RenderColorTarget0=; Clear=Color; Pass=Show;"; > {
    pass Add < string Script = "Draw=Buffer;"; > {
        Lighting = false; TextureFactor = 0xff404040; ZEnable = false;
        ColorOp[0] = SelectArg1; ColorArg1[0] = TFactor; AlphaOp[0] = SelectArg1; AlphaArg1[0] = TFactor;
        AlphaBlendEnable = true; SrcBlend = One; DestBlend = One;
    }
    pass Show < string Script = "Draw=Buffer;"; > {
        AlphaBlendEnable = false; Texture[0] = <A>; MinFilter[0] = Point; MagFilter[0] = Point;
        ColorOp[0] = SelectArg1; ColorArg1[0] = Texture; AlphaOp[0] = SelectArg1; AlphaArg1[0] = Texture;
    }
}
"""


@pytest.mark.parametrize("backend", BACKENDS)
def test_a_target_drawn_into_again_without_a_clear_keeps_its_picture(backend):
    # A gets 0x40 twice, with B drawn in between: 0x80 on the screen
    frame = render_frame(effects.load_effect(RESUME), "geforce2", backend=backend,
                         scene={"mesh": "quad"}, size=(16, 8))
    assert (frame.image[..., 0] == 128).all(), np.unique(frame.image[..., 0])
    assert not frame.warnings


CUBE = """
float4 Origin = {0, 0, 0, 1};
float4 Black = {0, 0, 0, 1};
float4x4 WVP : WORLDVIEWPROJECTION;
texture Cube : RENDERCOLORTARGET < string ResourceType = "Cube"; string Format = "R32F";
                                   int Width = 8; string CubeOrigin = "Origin"; >;
technique T < string Script = "RenderColorTarget0=Cube; ClearSetColor=Black; Clear=Color;"
                              "Pass=P; RenderColorTarget0=;"; > {
    pass P < string Script = "Draw=Buffer;"; > {
        Lighting = false; TextureFactor = 0xff808080; ZEnable = false;
        ColorOp[0] = SelectArg1; ColorArg1[0] = TFactor; AlphaOp[0] = SelectArg1; AlphaArg1[0] = TFactor;
    }
}
"""


@pytest.mark.parametrize("backend", BACKENDS)
def test_a_cube_render_target_is_drawn_face_by_face(backend):
    rt = Runtime(effects.load_effect(CUBE), "refrast", scene={"mesh": "sphere"}, size=(4, 4),
                 backend=backend)
    frame = rt.render()
    assert frame.passes == 1 and not frame.warnings
    cube = rt.texture("Cube")
    assert cube.kind == "cube" and cube.format == "R32F"
    level = cube.levels[0]
    assert level.shape[:3] == (6, 8, 8)
    np.testing.assert_allclose(level[..., 0], 128 / 255, atol=1e-6)   # every face drawn


def test_a_cube_target_without_an_origin_is_an_error():
    text = CUBE.replace('string CubeOrigin = "Origin";', "")
    with pytest.raises(EffectError, match="CubeOrigin"):
        render_frame(effects.load_effect(text), "refrast", scene={"mesh": "sphere"}, size=(4, 4))
