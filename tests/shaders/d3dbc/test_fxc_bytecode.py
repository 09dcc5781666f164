"""Bytecode that fxc wrote (tests/data/d3dbc/MANIFEST.md: SDL's Direct3D 9 pixel shaders, fxc
10.1 and 6.3, and mpv's YUV shaders, fxc 9.29): it reads, writes back byte for byte (fxc 9.x's
constant infos aside, below), passes the assembly checks, validates per card and renders on
both back ends; our compile of the HLSL source beside it draws the same picture as fxc's
bytecode on both back ends."""
from __future__ import annotations

import hashlib
import re
import struct

import numpy as np
import pytest
from PIL import Image

import effects
from effects.host.runtime import render_frame
from effects.shaders.asm import check
from effects.shaders.asm.text import program_text
from effects.shaders.d3dbc import load_shader, read_header, read_shader, write_program
from tests.paths import ROOT, TESTS
from tests.shaders.d3dbc import mojoshader

DATA = TESTS / "data" / "d3dbc"
SDL = DATA / "sdl"
MPV = DATA / "mpv"
WINE = DATA / "wine"
WINE_FILE = WINE / "d3d10core_test_create_shader.c"
FILES = sorted(SDL.glob("*.h")) + [SDL / "SDL2_shaders_d3d_excerpt.c"] + sorted(MPV.glob("*.h")) \
    + [WINE_FILE]
# (file, array name): every array of bytecode those files hold
ARRAYS = [(path, name) for path in FILES for name, _ in read_header(path.read_text())]
SOURCES = [SDL / "D3D9_PixelShader_Palette.hlsl", MPV / "d3d_shader_yuv.hlsl"]
SIZE = (48, 48)


def _array(path, name: str) -> bytes:
    return dict(read_header(path.read_text()))[name]


def _manifest_shas(path) -> list[str]:
    name = path.relative_to(DATA).as_posix()
    row = next(line for line in (DATA / "MANIFEST.md").read_text().splitlines()
               if line.startswith(f"| `{name}`"))
    return re.findall(r"`([0-9a-f]{64})`", row)


def test_every_file_is_in_the_manifest_with_its_hash():
    for folder in (SDL, MPV, WINE):
        for path in sorted(folder.iterdir()):
            assert f"`{path.relative_to(DATA).as_posix()}`" in (DATA / "MANIFEST.md").read_text()
    for path in FILES:     # one hash per array, in file order
        assert [hashlib.sha256(data).hexdigest() for _, data in read_header(path.read_text())] \
            == _manifest_shas(path)
    for path in SOURCES:
        assert [hashlib.sha256(path.read_bytes()).hexdigest()] == _manifest_shas(path)


def _without_reserved(data: bytes, binary) -> bytes:
    """`data` with the Reserved halfword of each D3DXSHADER_CONSTANTINFO zeroed. mpv's headers
    (fxc 9.29) carry 2, 6, 10 there (4 * RegisterIndex + 2); Wine's compiles with that same
    fxc, SDL's (6.3, 10.1) carry 0. The format gives it no meaning, so the reader keeps none
    and writes 0."""
    out = bytearray(data)
    # the CTAB comment's body starts after the comment token and the 'CTAB' fourcc (byte 12)
    start = 12
    count, infos = struct.unpack_from("<II", data, start + 12)
    for k in range(count):
        struct.pack_into("<H", out, start + infos + 20 * k + 10, 0)
    return bytes(out)


@pytest.mark.parametrize("path,name", ARRAYS, ids=[f"{p.name}:{n}" for p, n in ARRAYS])
def test_fxc_bytecode_reads_checks_and_writes_back_byte_for_byte(path, name):
    data = _array(path, name)
    binary = read_shader(data, str(path))
    assert binary.table.creator.startswith("Microsoft (R) HLSL Shader Compiler ")
    assert binary.table.target == binary.program.name
    assert check(binary.program) == []
    written = write_program(binary.program, binary.table)
    assert written == _without_reserved(data, binary)
    assert (written == data) == (path.parent != MPV)      # only mpv's carry Reserved values
    # fxc's listing in the header's `#if 0` is our disassembly, line for line
    if path.suffix == ".h":
        listed = [line.strip() for line in path.read_text().split("#endif")[0].splitlines()
                  if line.startswith("    ") and line.strip()]
        assert listed == program_text(binary.program).strip().splitlines()
    lib = mojoshader.load()
    if lib is not None:
        assert mojoshader.parse(lib, data, "glsl")[0] == []


VS = """asm {
    vs_1_1
    dcl_position v0
    dcl_texcoord v1
    m4x4 oPos, v0, c0
    mov oT0, v1
    mov oD0, c4
}"""
# mpv's shaders read t0-t2: the same coordinates in each
VS3 = VS.replace("mov oT0, v1", "mov oT0, v1 mov oT1, v1 mov oT2, v1")


def _pass(pixel_shader: str, extra: str = "", vs: str = VS) -> str:
    return f"""pass P0 {{
        VertexShaderConstantF[0] = <WorldViewProjection>;
        VertexShaderConstantF[4] = {{1, 0.75, 0.5, 1}};
        VertexShader = {vs};
        Texture[0] = <ImageTexture>; Texture[1] = <SecondTexture>; Texture[2] = <ImageTexture>;
        {extra}
        PixelShader = {pixel_shader};
    }}"""


def _effect(tmp_path, body: str, include: str = "", folder=SDL):
    ramp = np.zeros((1, 256, 4), np.uint8)       # a 1D palette, one texel high, as SDL binds
    ramp[0, :, 0] = np.arange(256)
    ramp[0, :, 1] = 255 - np.arange(256)
    ramp[0, :, 3] = 255
    Image.fromarray(ramp).save(tmp_path / "palette.png")
    text = f"""{include}
float4x4 WorldViewProjection : WORLDVIEWPROJECTION;
texture ImageTexture < string ResourceName = "{ROOT / 'fxfiles' / 'textures' / 'stones_base.png'}"; >;
texture SecondTexture < string ResourceName = "{tmp_path / 'palette.png'}"; >;
{body}
"""
    return effects.load_effect(text, include_dirs=[str(folder)])


def _fxc(name: str, folder=SDL, array: int = 0) -> str:
    data = read_header((folder / name).read_text())[array][1]
    return "asm { " + program_text(read_shader(data, name).program) + " }"


@pytest.fixture(scope="module")
def palette_effect(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("palette")
    return _effect(tmp, f"""
technique Fxc {{ {_pass(_fxc("D3D9_PixelShader_Palette.h"))} }}
technique Ours {{ {_pass("compile ps_2_0 main()")} }}
technique Index {{ {_pass("asm { ps_2_0 dcl t0.xy dcl_2d s0 texld r0, t0, s0 mov oC0, r0 }")} }}
""", include='#include "D3D9_PixelShader_Palette.hlsl"')


def test_fxc_bytecode_validates_per_card(palette_effect):
    assert palette_effect.validate("Fxc", effects.load_profile("radeon9700")).ok
    refused = palette_effect.validate("Fxc", effects.load_profile("geforce3"))
    assert not refused.ok
    assert any("ps_2_0" in str(r) for p in refused.pass_reports for r in p.reasons)


@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_our_compile_and_fxcs_draw_the_same_palette_picture(palette_effect, backend):
    frames = {t: render_frame(palette_effect, "radeon9700", technique=t, size=SIZE,
                              backend=backend) for t in ("Fxc", "Ours", "Index")}
    fxc, ours, index = (frames[t].image.astype(int) for t in ("Fxc", "Ours", "Index"))
    drawn = fxc[..., 3] > 0
    assert drawn.mean() > 0.4 and not frames["Fxc"].warnings
    assert np.abs(fxc - ours).max() <= 1
    # by hand: the palette's red is the index (255/256 scaled, half a texel on), its green
    # 255 minus that, times the vertex colour (1, 0.75, 0.5)
    i = index[..., 0][drawn] / 255.0
    u = i * 255 / 256 + 0.5 / 256
    texel = np.clip(u * 256 - 0.5, 0, 255)                    # linear filtering between texels
    assert np.abs(fxc[..., 0][drawn] - texel).max() <= 2
    assert np.abs(fxc[..., 1][drawn] - (255 - texel) * 0.75).max() <= 2


@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_fxcs_yuv_shader_draws_bt601_by_hand(tmp_path, backend):
    # SDL's BT.601 constants: Yoffset, Rcoeff, Gcoeff, Bcoeff (c0-c3)
    constants = """PixelShaderConstantF[0] = {-0.0627451017, -0.501960814, -0.501960814, 0};
        PixelShaderConstantF[1] = {1.1644, 0.0, 1.5960, 0};
        PixelShaderConstantF[2] = {1.1644, -0.3918, -0.8130, 0};
        PixelShaderConstantF[3] = {1.1644, 2.0172, 0.0, 0};"""
    effect = _effect(tmp_path, f"""
technique Fxc {{ {_pass(_fxc("D3D9_PixelShader_YUV.h"), constants)} }}
technique Planes {{ {_pass("asm { ps_2_0 dcl t0.xy dcl_2d s0 dcl_2d s1 texld r0, t0, s0 "
                           "texld r1, t0, s1 mov r0.y, r1.x mov oC0, r0 }")} }}
""")
    yuv = render_frame(effect, "radeon9700", technique="Fxc", size=SIZE, backend=backend)
    planes = render_frame(effect, "radeon9700", technique="Planes", size=SIZE, backend=backend)
    drawn = planes.image[..., 3] > 0
    y = planes.image[..., 0][drawn] / 255.0               # Y and V: the stone image's red
    u = planes.image[..., 1][drawn] / 255.0               # U: the palette's red
    y0, u0, v0 = y - 0.0627451017, u - 0.501960814, y - 0.501960814
    want = np.stack([1.1644 * y0 + 1.5960 * v0,
                     (1.1644 * y0 - 0.3918 * u0 - 0.8130 * v0) * 0.75,
                     (1.1644 * y0 + 2.0172 * u0) * 0.5], -1)
    got = yuv.image[..., :3][drawn] / 255.0
    assert np.abs(got - np.clip(want, 0, 1)).max() <= 3 / 255


@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_fxc63s_jpeg_shader_draws_the_formula_by_hand(tmp_path, backend):
    effect = _effect(tmp_path, f"""
technique Fxc {{ {_pass(_fxc("SDL2_shaders_d3d_excerpt.c"))} }}
technique Planes {{ {_pass("asm { ps_2_0 dcl t0.xy dcl_2d s0 dcl_2d s1 texld r0, t0, s0 "
                           "texld r1, t0, s1 mov r0.y, r1.x mov oC0, r0 }")} }}
""")
    out = render_frame(effect, "radeon9700", technique="Fxc", size=SIZE, backend=backend)
    planes = render_frame(effect, "radeon9700", technique="Planes", size=SIZE, backend=backend)
    drawn = planes.image[..., 3] > 0
    y = planes.image[..., 0][drawn] / 255.0
    u = planes.image[..., 1][drawn] / 255.0
    u0, v0 = u - 0.501960814, y - 0.501960814          # the HLSL's JPEG constants
    want = np.stack([y + 1.402 * v0, (y - 0.3441 * u0 - 0.7141 * v0) * 0.75,
                     (y + 1.772 * u0) * 0.5], -1)
    got = out.image[..., :3][drawn] / 255.0
    assert np.abs(got - np.clip(want, 0, 1)).max() <= 3 / 255


# mpv's colour matrix (c0-c3), row vectors times it as the HLSL's mul(c, colormatrix): BT.601
# limited range, the last row the offsets (c.w = 1).
COLORMATRIX = [[1.164, 1.164, 1.164, 0], [0, -0.392, 2.017, 0], [1.596, -0.813, 0, 0],
               [-0.871, 0.529, -1.082, 1]]


@pytest.fixture(scope="module", params=["420P", "NV12"])
def mpv_effect(request, tmp_path_factory):
    variant = request.param
    header = f"d3d_shader_{variant.lower()}.h"
    tmp = tmp_path_factory.mktemp(variant)
    effect = _effect(tmp, f"""
technique Fxc {{ {_pass(_fxc(header, MPV), "PixelShaderConstantF[0] = <colormatrix>;", VS3)} }}
technique Ours {{ {_pass("compile ps_2_0 main()", vs=VS3)} }}
technique Planes {{ {_pass("asm { ps_2_0 dcl t0.xy dcl_2d s0 dcl_2d s1 texld r0, t0, s0 "
                           "texld r1, t0, s1 mov r0.y, r1.x mov r0.z, r1.z mov oC0, r0 }")} }}
""", include=f'#define USE_{variant} 1\n#include "d3d_shader_yuv.hlsl"', folder=MPV)
    return variant, effect


def test_mpvs_fxc_bytecode_validates_per_card(mpv_effect):
    _, effect = mpv_effect
    assert effect.validate("Fxc", effects.load_profile("radeon9700")).ok
    assert not effect.validate("Fxc", effects.load_profile("geforce3")).ok


@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_our_compile_and_fxcs_draw_the_same_mpv_yuv_picture(mpv_effect, backend):
    variant, effect = mpv_effect
    frames = {t: render_frame(effect, "radeon9700", technique=t, size=SIZE, backend=backend,
                              params={"colormatrix": COLORMATRIX})
              for t in ("Fxc", "Ours", "Planes")}
    fxc, ours, planes = (frames[t].image.astype(int) for t in ("Fxc", "Ours", "Planes"))
    drawn = planes[..., 3] > 0
    assert drawn.mean() > 0.4 and not frames["Fxc"].warnings
    assert np.abs(fxc - ours).max() <= 1
    # by hand: (Y, U, V, 1) times the matrix; 420P reads V from tex2 (the stone image's red,
    # as Y), NV12 from tex1's blue (the palette's, 0)
    y = planes[..., 0][drawn] / 255.0
    u = planes[..., 1][drawn] / 255.0
    v = y if variant == "420P" else planes[..., 2][drawn] / 255.0
    m = np.array(COLORMATRIX)
    want = np.stack([y, u, v, np.ones_like(y)], -1) @ m
    got = fxc[..., :3][drawn] / 255.0
    assert np.abs(got - np.clip(want[:, :3], 0, 1)).max() <= 3 / 255


# Wine's HLSL vertex shader and fxc's vs_2_0 and vs_3_0 of it; a pixel shader of the same
# model passes the colour through.
PASS_COLOR = {"vs_2_0": "asm { ps_2_0 dcl v0 mov oC0, v0 }",
              "vs_3_0": "asm { ps_3_0 dcl_color v0 mov oC0, v0 }"}
LIGHT = [-0.36, 0.48, 0.8, 0]


def _wine_effect():
    text = WINE_FILE.read_text()
    hlsl = text[text.index("#if 0") + len("#if 0"):text.index("#endif")]
    body = [hlsl]
    for k, target in enumerate(("vs_2_0", "vs_3_0")):
        fxc = "asm { " + program_text(read_shader(_array(WINE_FILE, target), target).program) + " }"
        body.append(f"""technique Fxc_{target} {{ pass P {{
            VertexShaderConstantF[0] = <mat>; VertexShaderConstantF[4] = <light>;
            VertexShader = {fxc}; PixelShader = {PASS_COLOR[target]}; }} }}
technique Ours_{target} {{ pass P {{
            VertexShader = compile {target} main(); PixelShader = {PASS_COLOR[target]}; }} }}""")
    return effects.load_effect("\n".join(body))


def _wine_params() -> dict:
    from effects.host.scene import load_scene
    m = load_scene(None).matrices(SIZE)
    return {"mat": (m["world"] @ m["view"] @ m["projection"]).tolist(), "light": LIGHT}


@pytest.mark.parametrize("target,card", [("vs_2_0", "radeon9700"), ("vs_3_0", "geforce6800")])
def test_wines_fxc_vertex_shaders_validate_per_card(target, card):
    effect = _wine_effect()
    assert effect.validate(f"Fxc_{target}", effects.load_profile(card)).ok
    assert not effect.validate(f"Fxc_{target}", effects.load_profile("geforce3")).ok


@pytest.mark.parametrize("backend", ["numpy", "gl"])
@pytest.mark.parametrize("target,card", [("vs_2_0", "radeon9700"), ("vs_3_0", "geforce6800")])
def test_our_compile_and_fxcs_draw_the_same_wine_vertex_shader_picture(target, card, backend):
    effect = _wine_effect()
    frames = [render_frame(effect, card, technique=f"{who}_{target}", size=SIZE,
                           backend=backend, params=_wine_params()) for who in ("Fxc", "Ours")]
    fxc, ours = (f.image.astype(int) for f in frames)
    assert not frames[0].warnings
    assert np.abs(fxc - ours).max() <= 1
    # the diffuse term dot(light.xyz, normal), replicated to all four channels (alpha too),
    # shades the sphere from black at the terminator to white facing the light
    lit = fxc[..., 0] > 8
    assert lit.mean() > 0.4 and fxc[..., 0].max() == 255
    assert (fxc[..., 0] == fxc[..., 1]).all() and (fxc[..., 1] == fxc[..., 2]).all()
    assert (fxc[..., 3][lit] == fxc[..., 0][lit]).all()
