"""Bytecode that fxc wrote, copied from Debian source packages (tests/data/d3dbc/MANIFEST.md:
SDL 2's three Direct3D 9 YUV pixel shaders, fxc 6.3, and a Wine vertex shader, fxc 9.29): it
reads, writes back byte for byte, passes the assembly checks, validates per card and renders
on both back ends; SDL's draw the YUV formula of the HLSL beside them by hand, and our compile
of Wine's HLSL draws the same picture as fxc's bytecode on both back ends."""
from __future__ import annotations

import hashlib
import re

import numpy as np
import pytest
from PIL import Image

import effects
from effects.host.runtime import render_frame
from effects.shaders.asm import check
from effects.shaders.asm.text import program_text
from effects.shaders.d3dbc import read_header, read_shader, write_program
from tests.paths import ROOT, TESTS
from tests.shaders.d3dbc import mojoshader

DATA = TESTS / "data" / "d3dbc"
SDL_FILE = DATA / "sdl" / "SDL_shaders_d3d.c"
WINE_FILE = DATA / "wine" / "d3d10core_test_create_shader.c"
FILES = [SDL_FILE, WINE_FILE]
# (file, array name): every array of bytecode those files hold
ARRAYS = [(path, name) for path in FILES for name, _ in read_header(path.read_text())]
SDL_ARRAYS = [name for path, name in ARRAYS if path == SDL_FILE]
SIZE = (48, 48)


def _array(path, name: str) -> bytes:
    return dict(read_header(path.read_text()))[name]


def _manifest_row(path) -> str:
    name = path.relative_to(DATA).as_posix()
    return next(line for line in (DATA / "MANIFEST.md").read_text().splitlines()
                if line.startswith(f"| `{name}`"))


def test_every_file_is_in_the_manifest_with_its_hashes():
    manifest = (DATA / "MANIFEST.md").read_text()
    for path in sorted(p for p in DATA.rglob("*") if p.is_file() and p.name != "MANIFEST.md"):
        assert f"`{path.relative_to(DATA).as_posix()}`" in manifest
    for path in FILES:     # the file's own hash, then one per array, in file order
        shas = re.findall(r"`([0-9a-f]{64})`", _manifest_row(path).split("|")[-3])
        arrays = re.findall(r"`([0-9a-f]{64})`", _manifest_row(path).split("|")[-2])
        assert shas == [hashlib.sha256(path.read_bytes()).hexdigest()]
        assert arrays == [hashlib.sha256(data).hexdigest()
                          for _, data in read_header(path.read_text())]


@pytest.mark.parametrize("path,name", ARRAYS, ids=[f"{p.name}:{n}" for p, n in ARRAYS])
def test_fxc_bytecode_reads_checks_and_writes_back_byte_for_byte(path, name):
    data = _array(path, name)
    binary = read_shader(data, str(path))
    assert binary.table.creator.startswith("Microsoft (R) HLSL Shader Compiler ")
    assert binary.table.target == binary.program.name
    assert check(binary.program) == []
    assert write_program(binary.program, binary.table) == data
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


def _pass(pixel_shader: str, extra: str = "", vs: str = VS) -> str:
    return f"""pass P0 {{
        VertexShaderConstantF[0] = <WorldViewProjection>;
        VertexShaderConstantF[4] = {{1, 0.75, 0.5, 1}};
        VertexShader = {vs};
        Texture[0] = <ImageTexture>; Texture[1] = <SecondTexture>; Texture[2] = <ImageTexture>;
        {extra}
        PixelShader = {pixel_shader};
    }}"""


def _effect(tmp_path, body: str):
    ramp = np.zeros((1, 256, 4), np.uint8)       # red rises, green falls across the quad
    ramp[0, :, 0] = np.arange(256)
    ramp[0, :, 1] = 255 - np.arange(256)
    ramp[0, :, 3] = 255
    Image.fromarray(ramp).save(tmp_path / "palette.png")
    text = f"""
float4x4 WorldViewProjection : WORLDVIEWPROJECTION;
texture ImageTexture < string ResourceName = "{ROOT / 'fxfiles' / 'textures' / 'stones_base.png'}"; >;
texture SecondTexture < string ResourceName = "{tmp_path / 'palette.png'}"; >;
{body}
"""
    return effects.load_effect(text)


def _fxc(path, name: str) -> str:
    return "asm { " + program_text(read_shader(_array(path, name), name).program) + " }"


def _sdl_constants(name: str) -> dict[str, list[float]]:
    """The `const float3` offset and coefficients of the HLSL that SDL keeps in a comment
    before array `name` (`/* --- name.hlsl --- ... */`)."""
    text = SDL_FILE.read_text()
    hlsl = text[text.index(f"/* --- {name}.hlsl ---"):text.index(f"{name}[]")]
    return {m.group(1): [float(v) for v in m.group(2).split(",")]
            for m in re.finditer(r"const float3 (\w+) = \{([^}]*)\};", hlsl)}


PLANES = ("asm { ps_2_0 dcl t0.xy dcl_2d s0 dcl_2d s1 texld r0, t0, s0 texld r1, t0, s1 "
          "mov r0.y, r1.x mov oC0, r0 }")


@pytest.mark.parametrize("name", SDL_ARRAYS)
def test_sdls_fxc_bytecode_validates_per_card(tmp_path, name):
    effect = _effect(tmp_path, f"technique Fxc {{ {_pass(_fxc(SDL_FILE, name))} }}")
    assert effect.validate("Fxc", effects.load_profile("radeon9700")).ok
    refused = effect.validate("Fxc", effects.load_profile("geforce3"))
    assert not refused.ok
    assert any("ps_2_0" in str(r) for p in refused.pass_reports for r in p.reasons)


@pytest.mark.parametrize("backend", ["numpy", "gl"])
@pytest.mark.parametrize("name", SDL_ARRAYS)
def test_sdls_fxc_yuv_shaders_draw_their_hlsls_formula_by_hand(tmp_path, name, backend):
    # The HLSL is Direct3D 10 syntax (Texture2D, SamplerState), so fxc's code is drawn
    # against the HLSL's own formula, read from its comment: (Y, U, V) + offset, dotted with
    # each coefficient row, times the vertex colour (1, 0.75, 0.5, 1).
    k = _sdl_constants(name)
    assert set(k) == {"offset", "Rcoeff", "Gcoeff", "Bcoeff"}
    effect = _effect(tmp_path, f"""
technique Fxc {{ {_pass(_fxc(SDL_FILE, name))} }}
technique Planes {{ {_pass(PLANES)} }}
""")
    out = render_frame(effect, "radeon9700", technique="Fxc", size=SIZE, backend=backend)
    planes = render_frame(effect, "radeon9700", technique="Planes", size=SIZE, backend=backend)
    assert not out.warnings
    drawn = planes.image[..., 3] > 0
    assert drawn.mean() > 0.4
    y = planes.image[..., 0][drawn] / 255.0        # Y and V (s0, s2): the stone image's red
    u = planes.image[..., 1][drawn] / 255.0        # U (s1): the ramp's red
    yuv = np.stack([y, u, y], -1) + np.array(k["offset"])
    want = np.stack([yuv @ np.array(k["Rcoeff"]), yuv @ np.array(k["Gcoeff"]) * 0.75,
                     yuv @ np.array(k["Bcoeff"]) * 0.5], -1)
    got = out.image[..., :3][drawn] / 255.0
    assert np.abs(got - np.clip(want, 0, 1)).max() <= 3 / 255


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
