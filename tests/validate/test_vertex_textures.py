"""Vertex texture fetch in vs_3_0 (texldl on the vertex samplers 257-260): a heightfield
displaces vertices on both back ends, by heights worked out by hand; the cards that cannot
(Radeon X1800: vs_3_0 without any vertex texture format) and the formats and filters the
GeForce 6800 does not take are located validation errors."""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.d3d9.caps import load_profile
from effects.assets.textures import make_texture
from effects.program.ir import Builder, IRError

# A 4x2 R32F heightfield; bar k (k = 0..7, 8 pixels wide) reads texel (k % 4, k // 4).
HEIGHTS = np.array([[0.25, 0.5, 0.75, 1.0], [0.125, 0.375, 0.625, 0.875]], np.float32)
SIZE = (64, 32)

SAMPLER = """
texture HeightMap < string Format = "{fmt}"; >;
texture Tint;
sampler HeightSampler = sampler_state {{
    Texture = <HeightMap>; MinFilter = {filter}; MagFilter = Point; MipFilter = None;
    AddressU = Clamp; AddressV = Clamp;
}};
sampler TintSampler = sampler_state {{ Texture = <Tint>; }};
"""
# y = -1 + 2 h w (w = 0 at a bar's foot, 1 at its top); colour (h, h, h, 1) times the pixel
# shader's tint texel (a pixel sampler 0 next to the vertex sampler 257)
ASM_PASS = """
technique Displace {
    pass P0 {
        Sampler[257] = <HeightSampler>;
        Sampler[0] = <TintSampler>;
        CullMode = None;
        VertexShader = asm {
            vs_3_0
            dcl_position v0
            dcl_texcoord0 v1
            dcl_texcoord1 v2
            dcl_2d s0
            dcl_position o0
            dcl_color o1
            def c0, 0, 2, 1, 0
            mov r0.xy, v1.xy
            mov r0.zw, c0.x
            texldl r1, r0, s0
            mul r2.x, r1.x, c0.y
            mov r4, v2
            mov r3, v0
            mad r3.y, r2.x, r4.x, r3.y
            mov o0, r3
            mov o1, r1.xxxz
        };
        PixelShader = asm {
            ps_3_0
            dcl_color0 v0
            dcl_2d s0
            def c0, 0.5, 0.5, 0, 0
            texldl r0, c0, s0
            mul oC0, v0, r0
        };
    }
}
"""
HLSL_PASS = """
struct VOut { float4 pos : POSITION; float4 color : COLOR0; };
VOut VS(float4 pos : POSITION, float2 uv : TEXCOORD0, float w : TEXCOORD1) {
    VOut o;
    float h = tex2Dlod(HeightSampler, float4(uv, 0, 0)).x;
    o.pos = pos + float4(0, 2 * h * w, 0, 0);
    o.color = float4(h, h, h, 1);
    return o;
}
float4 PS(float4 c : COLOR0) : COLOR0 { return c * tex2D(TintSampler, float2(0.5, 0.5)); }
technique Displace { pass P0 { CullMode = None;
    VertexShader = compile vs_3_0 VS(); PixelShader = compile ps_3_0 PS(); } }
"""
TINT = (1.0, 0.5, 1.0, 1.0)


def _effect(body: str, fmt: str = "R32F", filter: str = "Point") -> effects.Effect:
    return effects.load_effect(SAMPLER.format(fmt=fmt, filter=filter) + body)


def _scene() -> dict:
    verts = []
    for k in range(8):
        uv = [(k % 4 + 0.5) / 4, (k // 4 + 0.5) / 2]          # texel centres
        x0, x1 = -1 + k * 0.25, -1 + (k + 1) * 0.25

        def corner(x, top):
            return {"position": [x, -1, 0.5, 1], "tex0": uv, "tex1": [1.0 if top else 0.0]}
        a, b, c, d = corner(x0, 0), corner(x1, 0), corner(x0, 1), corner(x1, 1)
        verts += [a, b, c, c, b, d]
    return {"mesh": {"primitive": "list", "vertices": verts}, "size": list(SIZE),
            "clear": {"color": "0xff0000ff"}}


def _params() -> dict:
    values = np.zeros((2, 4, 4), np.float32)
    values[..., 0] = HEIGHTS
    tint = np.broadcast_to(np.array(TINT, np.float32), (1, 1, 4))
    return {"HeightMap": make_texture(values, "R32F"),
            "Tint": make_texture(np.array(tint), "A8R8G8B8")}


@pytest.mark.parametrize("body", [ASM_PASS, HLSL_PASS], ids=["asm", "hlsl"])
@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_the_heightfield_raises_each_bar_by_its_texel(body, backend):
    image = effects.render(_effect(body), load_profile("geforce6800"), backend=backend,
                           scene=_scene(), params=_params())
    for k in range(8):
        h = float(HEIGHTS[k // 4, k % 4])
        column = image[:, k * 8 + 4]
        # top vertex at clip y = -1 + 2h: h * 32 rows from the bottom, the rest is the clear
        # colour (blue); each bar's colour is its height times the tint (1, 0.5, 1)
        rows = int(h * SIZE[1])
        bar, above = column[SIZE[1] - rows:], column[:SIZE[1] - rows]
        expected = np.rint(np.array([h, 0.5 * h, h]) * 255)
        assert np.abs(bar[:, :3].astype(int) - expected).max() <= 1, (k, bar[0])
        assert (above[:, :3] == (0, 0, 255)).all(), (k, above[-1:])


def test_both_binding_forms_and_back_ends_agree():
    # `Texture[257]` and sampler states on index 257 in the pass, as well as Sampler[257]
    body = ASM_PASS.replace("Sampler[257] = <HeightSampler>;",
                            "Texture[257] = <HeightMap>; MinFilter[257] = Point; "
                            "AddressU[257] = Clamp; AddressV[257] = Clamp;")
    images = [effects.render(_effect(b), load_profile("geforce6800"), backend=be,
                             scene=_scene(), params=_params())
              for b in (ASM_PASS, body) for be in ("numpy", "gl")]
    for other in images[1:]:
        assert np.array_equal(other, images[0])


def _reasons(effect, card):
    validation = effect.validate("Displace", load_profile(card))
    return validation.ok, [str(r) for r in validation.reasons]


def _line(text: str, needle: str) -> int:
    return 1 + next(k for k, t in enumerate(text.split("\n")) if needle in t)


@pytest.mark.parametrize("body, needle", [(ASM_PASS, "texldl r1"), (HLSL_PASS, "tex2Dlod")],
                         ids=["asm", "hlsl"])
def test_the_radeon_x1800_has_vs_3_0_but_no_vertex_texture_format(body, needle):
    effect = _effect(body)
    ok, reasons = _reasons(effect, "radeonx1800")
    line = _line(SAMPLER + body, needle)
    assert not ok
    assert reasons == [f"pass P0 (line {line}): VertexShader texldl on s0 (vertex texture "
                       "sampler 257): the Radeon X1800 reports vs_3_0 but accepts vertex "
                       "textures in no format, so no texture can be read here"]
    assert _reasons(effect, "geforce6800") == (True, [])
    assert _reasons(effect, "refrast") == (True, [])


def test_an_a8r8g8b8_vertex_texture_is_refused_on_the_geforce_6800():
    effect = _effect(ASM_PASS, fmt="A8R8G8B8")
    ok, reasons = _reasons(effect, "geforce6800")
    assert not ok
    assert reasons == ["pass P0 (line 2): Texture[257] = <HeightMap> Format = A8R8G8B8 is read "
                       "as a vertex texture; the GeForce 6800 takes vertex textures only in "
                       "A32B32G32R32F, R32F"]
    assert _reasons(effect, "refrast")[0] is False      # refrast: float formats only, too
    assert _reasons(_effect(ASM_PASS, fmt="A32B32G32R32F"), "geforce6800") == (True, [])


def test_vertex_textures_are_point_sampled_on_the_geforce_6800():
    effect = _effect(ASM_PASS, filter="Linear")
    ok, reasons = _reasons(effect, "geforce6800")
    assert not ok
    # the vertex sampler's filter caps, and R32F is not filterable on the card at all
    assert reasons == ["pass P0 (line 2): Texture[257] = <HeightMap> uses the format R32F with "
                       "linear filtering; the GeForce 6800 does not support that",
                       "pass P0 (line 5): MinFilter[257] = Linear needs "
                       "D3DPTFILTERCAPS_MINFLINEAR; the GeForce 6800 does not have it"]
    assert _reasons(effect, "refrast") == (True, [])     # refrast filters vertex textures


def test_software_vertex_processing_samples_vertex_textures():
    # the GMA 900 has no vertex shader hardware: vs_3_0 runs in software, textures and all
    # (its pixel shaders are ps_2_0: the tint read becomes a texld of a constant coordinate)
    ps = ASM_PASS[ASM_PASS.index("PixelShader"):]
    body = ASM_PASS.replace(ps, """PixelShader = asm {
            ps_2_0
            dcl v0
            dcl_2d s0
            def c0, 0.5, 0.5, 0, 0
            mov r1, c0
            texld r0, r1, s0
            mul r0, v0, r0
            mov oC0, r0
        };
    }
}
""")
    validation = _effect(body).validate("Displace", load_profile("gma900"))
    assert validation.ok, [str(r) for r in validation.reasons]
    assert any("software vertex processing" in n for n in validation.notes)


def test_a_vertex_program_names_its_lod():
    b = Builder("vertex")
    b.output("position", b.sample(257, b.varying("position"), "2d"))
    with pytest.raises(IRError, match="vertex program needs an explicit lod"):
        b.build()
    b = Builder("vertex")
    b.output("position", b.sample(257, b.varying("position"), "2d", lod=True))
    assert b.build().samplers[0].index == 257


@pytest.mark.parametrize("body, needle, parameter", [(ASM_PASS, "texldl r1", None),
                                                     (HLSL_PASS, "tex2Dlod", "HeightSampler")],
                         ids=["asm", "hlsl"])
def test_validation_records_each_shader_with_its_sampler_bindings(body, needle, parameter):
    # settled once, on the pass report: the vertex shader's s0 is the vertex texture sampler
    # 257, first sampled where the effect reads it; the compiler names the parameter in it
    effect = _effect(body)
    report = effect.validate("Displace", load_profile("geforce6800")).pass_reports[0]
    vs, ps = report.shaders["VertexShader"], report.shaders["PixelShader"]
    assert (vs.kind, ps.kind) == ("vs", "ps")
    [binding] = vs.samplers
    assert (binding.register, binding.unit, binding.parameter) == (0, 257, parameter)
    assert binding.read_at.line == _line(SAMPLER + body, needle)
    [tint] = ps.samplers
    assert (tint.register, tint.unit, tint.parameter) == (0, 0, parameter and "TintSampler")


def test_lowering_binds_from_the_shaders_validation_judged(monkeypatch):
    # with the Validation, lowering makes no program of its own; the pass it lowers is the
    # one lowered without it (which makes them itself)
    import effects.lower.passes as passes
    effect = _effect(HLSL_PASS)
    card = load_profile("geforce6800")
    technique = effect.techniques[0]
    validation = effect.validate(technique, card)
    alone = passes.lower_pass(effect, technique, 0, card)
    passes.clear_cache()

    def no_second_route(*args):
        raise AssertionError("lowering worked out a shader validation had settled")
    monkeypatch.setattr(passes, "shader_of", no_second_route)
    judged = passes.lower_pass(effect, technique, 0, card, validation=validation)
    assert [(b.sampler, b.texture) for b in judged.textures] == [(0, "Tint"), (257, "HeightMap")]
    assert judged.textures == alone.textures
    assert (str(judged.vertex), str(judged.fragment)) == (str(alone.vertex), str(alone.fragment))
