"""Uniform arrays indexed at run time in vertex shaders: c[a0.x + n] through the address
register (vs_1_1 `mov a0.x`, vs_2_0 and up `mova`), rendered on both back ends, values worked
out by hand; HLSL truncates the index to int first, an address outside the constant file
reads (0, 0, 0, 0)."""
from __future__ import annotations

import numpy as np
import pytest

from tests.shaders.hlsl.test_hlsl_render import backend, effect_for, fx_asm, pixel_uv, render  # noqa: F401

TOL = 1.5 / 255
PS = "float4 PS(float4 c : COLOR0) : COLOR { return c; }"
COLOURS = [(0.1, 0.2, 0.3, 1.0), (0.9, 0.1, 0.5, 1.0), (0.2, 0.8, 0.4, 1.0),
           (0.6, 0.6, 0.1, 1.0), (0.3, 0.0, 0.9, 1.0), (1.0, 0.5, 0.25, 1.0)]
PALETTE = "float4 Palette[6] = {" + ", ".join(f"{x:g}" for c in COLOURS for x in c) + "};\nfloat4 Sel;"


def palette_effect(index: str, target: str) -> object:
    return effect_for(f"""
float4 VS(float4 p : POSITION, float2 uv : TEXCOORD0, out float4 c : COLOR0) : POSITION
{{
    c = Palette[{index}];
    return p;
}}
{PS}""", vs=f"compile {target} VS()", params=PALETTE)


@pytest.mark.parametrize("target, load", [("vs_1_1", "mov a0.x"), ("vs_2_0", "mova a0.x")])
@pytest.mark.parametrize("sel, element", [(2.0, 2), (4.7, 4), (-0.6, 0), (1.0, 1)])
def test_a_uniform_index_reads_its_element(backend, target, load, sel, element):
    fx = palette_effect("Sel.x", target)      # a float index: truncated toward zero
    text = fx_asm(fx, "VS", target)
    assert load in text and "c[a0.x" in text, text
    img = render(fx, backend, params={"Sel": f"{sel},0,0,0"})
    assert np.allclose(img[4, 4], COLOURS[element], atol=TOL), (img[4, 4], COLOURS[element])


def test_a_per_vertex_index_then_interpolation(backend):
    # vertex uv (0,0) -> 0, (1,0) -> trunc(2.5) = 2, (0,1) -> trunc(3.2) = 3, (1,1) -> 5; the
    # quad's triangles (TL, TR, BL) and (BL, TR, BR) interpolate those per vertex
    fx = palette_effect("(int)(uv.x * 2.5 + uv.y * 3.2)", "vs_1_1")
    img = render(fx, backend)
    c = [np.array(COLOURS[k]) for k in (0, 2, 3, 5)]     # TL, TR, BL, BR
    for x, y in ((1, 1), (2, 5), (6, 2), (6, 6), (4, 7)):
        u, v = pixel_uv(x, y)
        if u + v <= 1:
            want = c[0] * (1 - u - v) + c[1] * u + c[2] * v
        else:
            want = c[3] * (u + v - 1) + c[1] * (1 - v) + c[2] * (1 - u)
        assert np.allclose(img[y, x], want, atol=TOL), (x, y, img[y, x], want)


def test_an_address_outside_the_constant_file_reads_zero(backend):
    # vs_1_1 has c0..c95: element 200 of a 6-element palette is c[a0.x + first] past c95
    fx = palette_effect("Sel.x", "vs_1_1")
    img = render(fx, backend, params={"Sel": "200,0,0,0"})
    assert np.allclose(img[4, 4], (0, 0, 0, 0), atol=TOL), img[4, 4]


@pytest.mark.parametrize("target", ["vs_1_1", "vs_2_0"])
def test_arrays_of_matrices_and_structs(backend, target):
    # Bones[i]: a float4x3 (three registers each, a0.x = 3i); Lights[i].colour: a struct
    # member at register 1 of each two-register element
    bones = [np.array([[0.5, 0, 0], [0, 0.25, 0], [0, 0, 0], [0.1, 0.2, 0.3]]),
             np.array([[0, 0.5, 0], [0.5, 0, 0], [0, 0, 0], [0.2, 0.1, 0.5]])]
    text = "float4x3 Bones[2] = {" + ", ".join(f"{x:g}" for b in bones for x in b.reshape(-1)) + "};\n"
    text += ("struct LIGHT { float4 dir; float4 colour; };\nLIGHT Lights[2] = { {0,0,0,0, 1,0.5,0,1}, "
             "{0,0,0,0, 0,0.25,1,1} };\nfloat4 Sel;")
    fx = effect_for(f"""
float4 VS(float4 p : POSITION, float2 uv : TEXCOORD0, out float4 c : COLOR0, out float4 d : COLOR1) : POSITION
{{
    int i = (int)Sel.x;
    c = float4(mul(float4(uv, 0, 1), Bones[i]), 1);
    d = Lights[1 - i].colour;
    return p;
}}
float4 PS(float4 c : COLOR0, float4 d : COLOR1) : COLOR {{ return c * 0.5 + d * 0.5; }}""",
                    vs=f"compile {target} VS()", params=text)
    for i in (0, 1):
        img = render(fx, backend, params={"Sel": f"{i},0,0,0"})
        colour = np.array([[1, 0.5, 0, 1], [0, 0.25, 1, 1]][1 - i])
        for x, y in ((2, 3), (5, 6)):
            u, v = pixel_uv(x, y)
            want = np.append(np.array([u, v, 0, 1]) @ bones[i], 1) * 0.5 + colour * 0.5
            assert np.allclose(img[y, x], want, atol=TOL), (i, x, y, img[y, x], want)


def test_a_run_time_index_in_a_pixel_shader_is_a_select_chain(backend):
    # no address register in pixel shaders: fxc compared the index with each element's
    # (issue 30; test_hlsl_valid_constructs.py has the rest of it)
    fx = effect_for("float4 PS(float2 uv : TEXCOORD0) : COLOR\n{\n"
                    "    return Palette[uv.x * 4 + 0.25];\n}", params=PALETTE)
    text = fx_asm(fx, "PS", "ps_2_0")
    assert "cmp" in text and "a0" not in text, text
    img = render(fx, backend)
    for x in range(8):
        assert np.allclose(img[2, x], COLOURS[x // 2], atol=TOL), (x, img[2, x])


@pytest.mark.parametrize("k", [0, 1, 2])
def test_a_run_time_index_of_a_local_array_in_a_vertex_shader_is_a_select_chain(backend, k):
    # a0 reaches constants only: a local array's element is chosen by compares
    fx = effect_for("""
float4 VS(float4 p : POSITION, out float4 c : COLOR0) : POSITION
{
    float4 a[3] = { float4(1, 0, 0, 1), float4(0, 1, 0, 1), float4(0.5, 0.5, p.z * 0 + 0.25, 1) };
    c = a[Sel.x];
    return p;
}
""" + PS, vs="compile vs_2_0 VS()", params=PALETTE)
    assert "a0" not in fx_asm(fx, "VS", "vs_2_0")
    img = render(fx, backend, params={"Sel": np.array([k, 0, 0, 0], np.float32)})
    want = [(1, 0, 0, 1), (0, 1, 0, 1), (0.5, 0.5, 0.25, 1)][k]
    assert np.allclose(img[4, 4], want, atol=TOL), img[4, 4]


SKIN = """float4x3 Bones[8];
float4 Sel;
float4 VS(float4 p : POSITION, float2 uv : TEXCOORD0, out float4 c : COLOR0) : POSITION
{
    float3 acc = 0;
    int4 idx = D3DCOLORtoUBYTE4(Sel);          // the blend indices of a D3DCOLOR stream
    float w[4] = { 0.5, 0.25, 0.125, 0.125 };
    for (int k = 0; k < 4; k++)                // unrolled: four a0 loads, three reads each
        acc += mul(float4(uv, 0, 1), Bones[idx[k]]) * w[k];
    c = float4(acc, 1);
    return p;
}
float4 PS(float4 c : COLOR0) : COLOR { return c; }
technique T { pass P { VertexShader = compile %s VS(); PixelShader = compile %s PS(); } }"""


@pytest.mark.parametrize("vs, ps, card", [("vs_1_1", "ps_2_0", "radeon9700"),
                                          ("vs_3_0", "ps_3_0", "geforce6800")])
def test_a_skinning_palette_indexed_by_d3dcolor_blend_indices(backend, vs, ps, card):
    import effects
    fx = effects.load_effect(SKIN % (vs, ps))
    text = fx_asm(fx, "VS", vs)
    # vs_1_1: one load of a0.x a bone; vs_2_0 and up: the four addresses, lanes of one
    # register, in a0.x ... a0.w by one `mova a0, r0` (fxc's code, issue 31)
    loads = [line for line in text.splitlines() if line.split(" ")[0] in ("mov", "mova")
             and line.split(" ")[1].startswith("a0")]
    if vs == "vs_1_1":
        assert len(loads) == 4 and all(x.startswith("mov a0.x, ") for x in loads), loads
    else:
        assert loads == ["mova a0, r0"], loads
    assert ("c[a0.w" in text) == (vs != "vs_1_1")
    rng = np.random.default_rng(1)
    bones = rng.uniform(0, 0.25, (8, 4, 3))
    sel = (3, 6, 1, 5)                                  # D3DCOLOR bytes r, g, b, a
    idx = (sel[2], sel[1], sel[0], sel[3])              # UBYTE4 order: b, g, r, a
    params = {"Bones": ",".join(f"{x:.6f}" for x in bones.reshape(-1)),
              "Sel": ",".join(f"{x / 255:.8f}" for x in sel)}
    img = effects.render(fx, card, technique="T", backend=backend, scene={"mesh": "quad", "size": [8, 8]},
                         params=params).astype(np.float64) / 255
    for x, y in ((3, 5), (6, 1)):
        u, v = pixel_uv(x, y)
        want = sum(np.array([u, v, 0, 1]) @ bones[i] * w for i, w in zip(idx, (0.5, .25, .125, .125)))
        assert np.allclose(img[y, x, :3], want, atol=TOL), (x, y, img[y, x], want)


@pytest.mark.parametrize("vs", ["vs_1_1", "vs_2_0", "vs_3_0"])
def test_d3dcolor_to_ubyte4_is_one_mul_as_fxc_wrote_it(vs):
    import effects
    fx = effects.load_effect(SKIN % (vs, "ps_3_0" if vs == "vs_3_0" else "ps_2_0"))
    text = fx_asm(fx, "VS", vs)
    # the four indices: `mul r0, c8.zyxw, c32.x` (255.001953 in a def), no truncation after
    # it (fxc's code; it was a mul and seven instructions of trunc)
    assert "255.001953" in text
    muls = [line for line in text.splitlines() if line.startswith("mul ") and ".zyxw" in line]
    assert len(muls) == 1, text
    assert not any(line.startswith(("frc", "slt", "sge")) for line in text.splitlines()), text


def test_every_d3dcolor_byte_scales_to_its_index_under_floor_and_round():
    # what the mul leaves in float32 for the byte k of a D3DCOLOR stream (k / 255): k plus
    # under 0.002, so vs_1_1's `mov a0.x` (floor) and `mova` (round) both address k
    k = np.arange(256, dtype=np.float32)
    scaled = (k / np.float32(255)) * np.float32(255.001953)
    assert np.all(scaled - k >= 0) and np.all(scaled - k < 0.002)
    assert np.array_equal(np.floor(scaled), k) and np.array_equal(np.rint(scaled), k)
