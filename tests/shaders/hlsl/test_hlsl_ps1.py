"""HLSL compiled for ps_1_1-ps_1_4 (codegen_ps1), rendered on DX8 cards on both back ends.

Each case is a pixel function on the full-screen quad of test_hlsl_render (texture coordinate
u = x/8 left to right, v = y/8 top to bottom; vertex diffuse from the scene), run on the
GeForce3 (ps_1_1, about 8-bit fixed point in [-1, 1]), GeForce4 Ti (ps_1_3) or Radeon 8500
(ps_1_4); the expected colours are worked out here from the HLSL. Then the assembly of a few
functions as golden text, and every construct ps_1_x cannot express as a located error.
"""
from __future__ import annotations

from tests.paths import ROOT

import math

import numpy as np
import pytest

import effects
from effects.program.backend import create_backend
from effects.base.errors import EffectError
from effects.assets.textures import make_texture
from effects.shaders.asm import check
from effects.shaders.hlsl.compiler import compile_shader

BACKENDS = ("numpy", "gl")
SIZE = (8, 8)
DIFFUSE = (0.5, 0.75, 1.0, 1.0)
QUAD = {"mesh": "quad", "size": list(SIZE), "vertex": {"diffuse": list(DIFFUSE)}}
CARD = {"ps_1_1": "geforce3", "ps_1_3": "geforce4ti", "ps_1_4": "radeon8500"}
TOL = 2.5 / 255      # DX8 fixed point: a step or two of the 8-bit grid
PARAMS = """
texture T;
sampler2D Checker = sampler_state { Texture = <T>; MinFilter = Point; MagFilter = Point;
                                    MipFilter = None; AddressU = Clamp; AddressV = Clamp; };
float4 K0 = { 0.5, 0.25, 0.0, 1.0 };
float4 K1 = { 0.0, 1.0, 0.5, 0.5 };
float3 L = { 0.5, 0.25, 0.0 };
float Scale = 0.5;
"""
# 4 x 4 texels, each a distinct colour: odd pixels of the quad read a texel centre (no tie)
TEXELS = np.stack(list(np.meshgrid(np.linspace(0, 1, 4), np.linspace(1, 0, 4))) +
                  [np.full((4, 4), 0.5), np.ones((4, 4))], axis=-1)


@pytest.fixture(scope="module", params=BACKENDS)
def backend(request):
    made = create_backend(request.param)
    yield made
    made.close()


def effect_for(function: str, target: str) -> effects.Effect:
    return effects.load_effect(f"{PARAMS}\n{function}\n"
                               f"technique T {{ pass P {{ Lighting = False; PixelShader = compile {target} PS(); }} }}\n")


def render(function: str, target: str, backend) -> np.ndarray:
    fx = effect_for(function, target)
    img = effects.render(fx, CARD[target], technique="T", backend=backend, scene=QUAD,
                         params={"T": make_texture(TEXELS, mips=False)})
    return img.astype(np.float64) / 255.0


def asm(function: str, target: str) -> str:
    shader = compile_shader(effect_for(function, target), "PS", target)
    assert check(shader.program) == [], shader.text     # the version's own rules hold
    return shader.text


def uv(x: int, y: int) -> tuple[float, float]:
    return x / SIZE[0], y / SIZE[1]


def each_pixel(img: np.ndarray, want, target: str, text: str) -> None:
    for y in range(SIZE[1]):
        for x in range(SIZE[0]):
            expected = np.clip(np.asarray(want(*uv(x, y)), np.float64), 0, 1)
            assert np.allclose(img[y, x], expected, atol=TOL), (target, x, y, img[y, x], expected, text)


@pytest.mark.parametrize("target", ["ps_1_1", "ps_1_4"])
def test_texture_times_colour_input(backend, target):
    fn = "float4 PS(float2 uv : TEXCOORD0, float4 c : COLOR0) : COLOR { return tex2D(Checker, uv) * c; }"
    img = render(fn, target, backend)
    text = asm(fn, target)
    assert ("tex t0" if target == "ps_1_1" else "texld r0, t0") in text
    for y in range(1, SIZE[1], 2):
        for x in range(1, SIZE[0], 2):
            want = TEXELS[y // 2, x // 2] * DIFFUSE
            assert np.allclose(img[y, x], want, atol=TOL), (x, y, img[y, x], want, text)


@pytest.mark.parametrize("target", ["ps_1_1", "ps_1_4"])
def test_expand_dot3_saturate(backend, target):
    # 2*n - 1 is _bx2; saturate(dot()) is dp3_sat; the scalar is replicated in every lane
    fn = """float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float3 n = float3(uv, 0.5);
    return saturate(dot(2 * n - 1, L));
}"""
    text = asm(fn, target)
    assert "dp3_sat" in text and "_bx2" in text, text
    img = render(fn, target, backend)
    each_pixel(img, lambda u, v: [0.5 * (2 * u - 1) + 0.25 * (2 * v - 1)] * 4, target, text)


@pytest.mark.parametrize("target", ["ps_1_1", "ps_1_4"])
def test_lerp_by_one_component(backend, target):
    # lrp; ps_1_1 cannot select .x of t0 alone, so a dp3 with (1, 0, 0) extracts it
    fn = "float4 PS(float2 uv : TEXCOORD0) : COLOR { return lerp(K0, K1, uv.x); }"
    text = asm(fn, target)
    assert "lrp" in text and (("dp3" in text) == (target == "ps_1_1")), text
    k0, k1 = np.array([0.5, 0.25, 0, 1]), np.array([0, 1, 0.5, 0.5])
    img = render(fn, target, backend)
    each_pixel(img, lambda u, v: k0 + (k1 - k0) * u, target, text)


@pytest.mark.parametrize("target", ["ps_1_1", "ps_1_4"])
def test_parts_of_a_vector_through_masks(backend, target):
    # float4(uv, 0, 1): .rgb through a 0/1 mask and a mad (ps_1_1) or the .ba mask (ps_1_4)
    fn = "float4 PS(float2 uv : TEXCOORD0) : COLOR { return float4(uv, 0, 1); }"
    text = asm(fn, target)
    img = render(fn, target, backend)
    each_pixel(img, lambda u, v: [u, v, 0, 1], target, text)


# four channels, four modifiers: fits ps_1_4's temporaries, not ps_1_1's two
FOUR_CHANNELS = """float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float4 o;
    o.r = uv.x * Scale;
    o.g = saturate(uv.x * uv.y * 4);
    o.b = (uv.x + uv.y) * 0.5;
    o.a = 1 - uv.y;
    return o;
}"""


def test_shifts_invert_and_scalar_uniform(backend):
    # uv.x*Scale (a scalar uniform), *4 with saturate (mul_x4_sat), *0.5 (_d2), 1-x (invert)
    fn = FOUR_CHANNELS
    text = asm(fn, "ps_1_4")
    assert "mul_x4_sat" in text and "add_d2" in text and "1-r" in text, text
    img = render(fn, "ps_1_4", backend)
    each_pixel(img, lambda u, v: [u * 0.5, min(u * v * 4, 1), (u + v) / 2, 1 - v], "ps_1_4", text)


@pytest.mark.parametrize("target, fn", [
    ("ps_1_4", "float4 PS(float2 uv : TEXCOORD0) : COLOR { return uv.x > 0.5 ? K0 : K1; }"),
    # a per-component comparison is cmp on ps_1_3 (cnd there compares r0.a for all lanes)
    ("ps_1_3", "float4 PS(float2 uv : TEXCOORD0) : COLOR { return uv.xxxx > 0.5 ? K0 : K1; }")])
def test_select_is_cmp(backend, target, fn):
    text = asm(fn, target)
    assert "cmp" in text and "cnd" not in text, text
    img = render(fn, target, backend)
    img[:, 4] = [0.5, 0.25, 0, 1]     # u = 0.5 exactly: d = 0 is a tie the interpolation decides
    each_pixel(img, lambda u, v: [0.5, 0.25, 0, 1] if u >= 0.5 else [0, 1, 0.5, 0.5], target, text)


def texel(x: int, y: int) -> np.ndarray:
    """The texel an odd pixel reads (at its centre, no tie): r = column/3, g = 1 - row/3."""
    return TEXELS[y // 2, x // 2]


def odd_pixels(img: np.ndarray, want, target: str, text: str) -> None:
    for y in range(1, SIZE[1], 2):
        for x in range(1, SIZE[0], 2):
            expected = np.clip(np.asarray(want(texel(x, y)), np.float64), 0, 1)
            assert np.allclose(img[y, x], expected, atol=TOL), (target, x, y, img[y, x], expected, text)


K0_, K1_ = np.array([0.5, 0.25, 0.0, 1.0]), np.array([0.0, 1.0, 0.5, 0.5])

# ps_1_1-1_3 order a one-channel comparison by cnd, whose condition is r0.a: a > b is
# cnd on a - (b - 0.5), b - 0.5 the _bias modifier; against 0.5 itself the channel is moved
# (or extracted by dp3) into r0.a
CND_CASES = [
    ("float4 c = tex2D(Checker, uv); return c.r > 0.5 ? K0 : c;",
     lambda t: K0_ if t[0] > 0.5 else t),
    ("float4 c = tex2D(Checker, uv); return c.g <= Scale ? c : K1;",      # Scale = 0.5
     lambda t: t if t[1] <= 0.5 else K1_),
    ("float4 c = tex2D(Checker, uv); return c.r >= col.r ? col : K1;",    # col.r = 0.5
     lambda t: np.array(DIFFUSE) if t[0] >= 0.5 else K1_),
    ("float4 c = tex2D(Checker, uv); return c.g < 0.25 ? K0 : K1;",
     lambda t: K0_ if t[1] < 0.25 else K1_),
    ("float4 c = tex2D(Checker, uv); return (c.r > c.b) * K0;",           # c.b = 0.5
     lambda t: K0_ * (t[0] > t[2])),
]


@pytest.mark.parametrize("target", ["ps_1_1", "ps_1_3"])
@pytest.mark.parametrize("case", range(len(CND_CASES)))
def test_select_on_one_channel_is_cnd(backend, target, case):
    body, want = CND_CASES[case]
    fn = f"float4 PS(float2 uv : TEXCOORD0, float4 col : COLOR0) : COLOR {{ {body} }}"
    text = asm(fn, target)
    assert "cnd r0, r0.a," in text and "cmp" not in text, text
    odd_pixels(render(fn, target, backend), want, target, text)


def test_two_cnds_one_into_alpha_one_into_colour(backend):
    # each condition goes through r0.a in turn; the .rgb cnd is not co-issued (a co-issued
    # colour cnd returns its first choice on ps_1_1-1_3)
    fn = """float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float4 c = tex2D(Checker, uv);
    float4 o;
    o.a = c.r > 0.5 ? 1 : 0;
    o.rgb = c.g > 0.25 ? K0.rgb : K1.rgb;
    return o;
}"""
    text = asm(fn, "ps_1_3")
    assert text.count("cnd") == 2 and "+cnd" not in text, text
    odd_pixels(render(fn, "ps_1_3", backend),
               lambda t: list((K0_ if t[1] > 0.25 else K1_)[:3]) + [1.0 if t[0] > 0.5 else 0.0],
               "ps_1_3", text)


def test_ps14_dependent_read_in_phase_two(backend):
    fn = "float4 PS(float2 uv : TEXCOORD0) : COLOR { return tex2D(Checker, uv * 0.5 + 0.0625); }"
    text = asm(fn, "ps_1_4")
    assert text.splitlines()[-2:] == ["phase", "texld r0, r0"], text
    img = render(fn, "ps_1_4", backend)
    for y in range(SIZE[1]):
        for x in range(SIZE[0]):
            u, v = uv(x, y)      # the read is at u/2 + 1/16: texel floor(2u + 1/4) of 4
            want = TEXELS[int(4 * (v * 0.5 + 0.0625)), int(4 * (u * 0.5 + 0.0625))]
            assert np.allclose(img[y, x], want, atol=TOL), (x, y, img[y, x], want)


# -- golden assembly -----------------------------------------------------------------------------

GOLDEN = {
    ("ps_1_1", """float4 PS(float2 uv : TEXCOORD0, float3 n : TEXCOORD1, float4 c : COLOR0) : COLOR
{
    float4 col = tex2D(Checker, uv) * c * saturate(dot(2 * n - 1, L));
    col.a = 1;
    return col;
}"""): """ps_1_1
def c1, 0, 0, 0, 1
tex t0
texcoord t1
mul r0, t0, v0
dp3_sat r1, t1_bx2, c0
mul r0.rgb, r0, r1
+mov r0.a, c1
""",
    ("ps_1_4", """float4 PS(float2 uv : TEXCOORD0, float4 c : COLOR0) : COLOR
{
    return tex2D(Checker, uv) * c * 2;
}"""): """ps_1_4
texld r0, t0
mul_x2 r0, r0, v0
""",
    # a > b as cnd on a - b_bias (the DX9 docs' own ps_1_1 cnd example)
    ("ps_1_1", """float4 PS(float4 a : COLOR0, float4 b : COLOR1) : COLOR
{
    return a.a > b.a ? K0 : K1;
}"""): """ps_1_1
add r0.a, v0, -v1_bias
cnd r0, r0.a, c0, c1
""",
    # .b alone is read only into an .a write, as the condition is
    ("ps_1_1", """float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    return tex2D(Checker, uv).b < 0.25 ? K0 : K1;
}"""): """ps_1_1
def c2, 0, 0, 0, 0.25
tex t0
add r0.a, c2, -t0_bias.b
cnd r0, r0.a, c0, c1
""",
    ("ps_1_1", """float4 PS(float2 uv : TEXCOORD0) : COLOR { return float4(uv, 0, 1); }"""): """ps_1_1
def c0, 1, 1, 0, 1
def c1, 0, 0, 0, 0
texcoord t0
mov r0.a, c0
+mad r0.rgb, t0, c0, c1
""",
}


@pytest.mark.parametrize("target, fn", list(GOLDEN))
def test_golden_assembly(target, fn):
    assert asm(fn, target) == GOLDEN[(target, fn)]


def test_texcoord_read_as_a_value_warns_of_the_clamp():
    fx = effect_for("float4 PS(float2 uv : TEXCOORD0) : COLOR { return float4(uv, 0, 1); }", "ps_1_1")
    shader = compile_shader(fx, "PS", "ps_1_1")
    assert [str(w) for w in shader.warnings] == [
        f"<string>:{PARAMS.count(chr(10)) + 2}:21: warning: ps_1_1 reads TEXCOORD0 as a value "
        "through texcoord, which clamps it to [0, 1]"]


# -- what ps_1_x cannot express ------------------------------------------------------------------

REFUSED = [
    ("ps_1_1", "return float4(normalize(float3(uv, 1)), 1);", 18,
     "ps_1_1 has no normalize, length or rsqrt (rsq)"),
    ("ps_1_4", "return uv.x / uv.y;", 8, "ps_1_4 has no per-pixel division or sqrt (rcp)"),
    ("ps_1_1", "return pow(uv.x, uv.y);", 8, "ps_1_1 cannot compute pow of a non-constant exponent"),
    ("ps_1_1", "return uv.x + 2;", 8, "the literal 2 is outside [-1, 1], the range of ps_1_1 constants"),
    ("ps_1_1", "return uv.x == 0.5 ? K0 : K1;", 8,
     "ps_1_1 has no equality test (cnd orders values only; == and != need cmp, ps_1_2)"),
    ("ps_1_1", "return uv.xyxy > 0.5 ? K0 : K1;", 8,
     "ps_1_1's cnd compares r0.a, one value for every component; this comparison is per component"),
    ("ps_1_1", "return tex2D(Checker, uv * 0.5);", 8,
     "ps_1_1 has no texture read at computed coordinates (a dependent read needs ps_1_4"),
    ("ps_1_4", "return tex2D(Checker, tex2D(Checker, uv * 0.5).xy);", 8,
     "ps_1_4 allows one level of dependent texture read"),
    ("ps_1_1", "return uv.yxyx * K0;", 12, "ps_1_1 has no swizzle .yxyx"),
    ("ps_1_1", "return tex2D(Checker, uv) + uv.x;", 8, "TEXCOORD0 is both sampled and read as a value"),
    ("ps_1_1", "return max(K0, uv.x);", 8, "ps_1_1 has no max"),
    # a vector built of parts is located at the expression that reads it (it was line 0)
    ("ps_1_1", "float4 c = tex2D(Checker, uv); return c * float4(c.b, c.r, c.g, 1);", 42,
     "ps_1_1 has no swizzle .zxy"),
]


@pytest.mark.parametrize("target, body, column, message", REFUSED)
def test_refused_with_the_hlsl_location(target, body, column, message):
    fn = f"float4 PS(float2 uv : TEXCOORD0) : COLOR\n{{\n    {body}\n}}"
    fx = effect_for(fn, target)
    with pytest.raises(EffectError) as info:
        compile_shader(fx, "PS", target)
    err = info.value
    assert message in err.message, err.message
    assert err.message.startswith("X4532: ") or "pow" in message
    line = PARAMS.count("\n") + 4     # the body line of `fn` in the effect text
    assert (err.location.line, err.location.column >= column) == (line, True), str(err)


def test_temporaries_beyond_r1_are_refused_at_the_value():
    fn = FOUR_CHANNELS
    with pytest.raises(EffectError, match=r"ps_1_1 has 2 temporary registers \(r0-r1\)") as info:
        compile_shader(effect_for(fn, "ps_1_1"), "PS", "ps_1_1")
    assert info.value.location.line > PARAMS.count("\n") + 3


def test_nine_arithmetic_instructions_reject_the_technique_at_the_line():
    body = "\n".join(f"    c = c * K{i % 2};" for i in range(9))
    fn = f"float4 PS(float4 c : COLOR0) : COLOR\n{{\n{body}\n    return c;\n}}"
    fx = effect_for(fn, "ps_1_1")
    validation = fx.validate("T", effects.load_profile("geforce3"))
    assert not validation.ok
    [reason] = validation.reasons
    assert reason.message == "ps_1_1 allows 8 arithmetic instructions; this is the 9th"
    # the ninth mul, at its HLSL line and operator (the `*` of `c * K0`)
    assert (reason.location.line, reason.location.column) == (PARAMS.count("\n") + 2 + 10, 11)


@pytest.mark.parametrize("target", ["ps_1_1", "ps_1_4"])
def test_pow_of_a_small_whole_exponent_is_multiplications(backend, target):
    fn = "float4 PS(float2 uv : TEXCOORD0) : COLOR { return pow(saturate(uv.x), 8); }"
    text = asm(fn, target)
    assert text.count("mul") == 3, text       # x^2, x^4, x^8
    img = render(fn, target, backend)
    # the card's fixed point rounds each square: allow a few steps
    for y in range(SIZE[1]):
        for x in range(SIZE[0]):
            u = uv(x, y)[0]
            assert np.allclose(img[y, x], u ** 8, atol=4 / 255), (x, y, img[y, x], u ** 8)


def test_sdk9_hlsl_dx8_builds_match_the_dx9_one_but_for_the_highlight():
    """Scene_ps11 on a GeForce3 and Scene_ps14 on a Radeon 8500 draw the ps_2_0 picture of a
    Radeon 9700 without its specular term (the DX8 builds leave pow out) and with the
    interpolated, not renormalised, normal: the same within a step or two everywhere else."""
    fx = effects.load_effect(str(ROOT / "fxfiles" / "sdk9_hlsl.fx"))
    pictures = {card: effects.render(fx, card, backend="numpy", size=(64, 64)).astype(int)
                for card in ("geforce3", "radeon8500", "radeon9700")}
    assert {card: fx.find_valid_technique(effects.load_profile(card)).name for card in pictures} == {
        "geforce3": "Scene_ps11", "radeon8500": "Scene_ps14", "radeon9700": "Scene_ps20"}
    ps11, ps14, ps20 = (pictures[c][..., :3] for c in ("geforce3", "radeon8500", "radeon9700"))
    sphere = ps20.sum(-1) > 0
    assert np.abs(ps11 - ps14).max() <= 3
    extra = (ps20 - ps11).max(-1)
    assert extra.min() >= -3                               # specular only adds
    assert np.median(np.abs(extra[sphere])) <= 2
    highlight = extra > 24
    assert 20 < highlight.sum() < 0.2 * sphere.sum()       # a highlight, not everywhere
    assert extra.max() > 60


# -- one sampler read at two texture coordinates -------------------------------------------------

# TEXCOORD0 = uv of the quad, TEXCOORD1 = uv mirrored left to right (u' = 1 - u): inline
# clip-space vertices, top-left first, as the quad's
MIRRORED = {"size": list(SIZE), "mesh": {"primitive": "strip", "vertices": [
    {"position": [x, y, 0.5], "diffuse": list(DIFFUSE), "tex0": [u, v], "tex1": [1 - u, v]}
    for (x, y), (u, v) in (((-1, 1), (0, 0)), ((1, 1), (1, 0)), ((-1, -1), (0, 1)), ((1, -1), (1, 1)))]}}
# the texture of TEXELS with an alpha that grows by column: (column + 1) / 4
ALPHA_TEXELS = TEXELS.copy()
ALPHA_TEXELS[..., 3] = (np.arange(4)[None, :] + 1) / 4
TWO_READS = "float4 PS(float2 uv : TEXCOORD0, float2 uv2 : TEXCOORD1) : COLOR\n{{\n{}\n}}"


def two_reads(body: str) -> str:
    return TWO_READS.format("    float4 a = tex2D(Checker, uv);\n    float4 b = tex2D(Checker, uv2);\n"
                            f"    {body}")


@pytest.mark.parametrize("body, want", [
    ("return (a + b) * 0.5;", lambda a, b: (a + b) / 2),
    ("return a.a * b;", lambda a, b: a[3] * b),
    ("return float4(b.rgb, a.a);", lambda a, b: np.append(b[:3], a[3])),
])
def test_ps14_reads_one_sampler_at_two_coordinates_one_per_phase(backend, body, want):
    # texld r# samples stage # at any coordinates: the first read in phase 1, carried out of
    # r0 (.rgb, and .a replicated in another register's .rgb), the second in phase 2
    fn = two_reads(body)
    text = asm(fn, "ps_1_4")
    assert text.count("texld r0, t") == 2 and "phase" in text, text
    fx = effect_for(fn, "ps_1_4")
    img = effects.render(fx, CARD["ps_1_4"], technique="T", backend=backend, scene=MIRRORED,
                         params={"T": make_texture(ALPHA_TEXELS, mips=False)}).astype(np.float64) / 255
    for y in range(1, SIZE[1], 2):
        for x in range(1, SIZE[0], 2):
            a, b = ALPHA_TEXELS[y // 2, x // 2], ALPHA_TEXELS[y // 2, 3 - x // 2]
            assert np.allclose(img[y, x], want(a, b), atol=TOL), (x, y, img[y, x], want(a, b), text)


def test_ps14_two_reads_golden():
    assert asm(two_reads("return a + b;"), "ps_1_4") == """ps_1_4
texld r0, t0
mov r1.rgb, r0
mov r2.rgb, r0.a
phase
texld r0, t1
mov r1.a, r2.b
add r0, r1, r0
"""


FIRST_READ_LINE = PARAMS.count("\n") + 4    # `float4 a = tex2D(Checker, uv);` in the effect


@pytest.mark.parametrize("target", ["ps_1_1", "ps_1_3"])
def test_one_sampler_at_two_coordinates_is_refused_naming_both_reads(target):
    with pytest.raises(EffectError) as info:
        compile_shader(effect_for(two_reads("return a + b;"), target), "PS", target)
    err = info.value
    assert err.message == (
        "X4532: cannot map expression to pixel shader instruction set: sampler 'Checker' is read "
        f"at TEXCOORD0 (line {FIRST_READ_LINE}) and at TEXCOORD1 (line {FIRST_READ_LINE + 1}); "
        f"{target} samples stage # at TEXCOORD# (tex t#), and a sampler is one stage")
    assert (err.location.line, err.location.column) == (FIRST_READ_LINE + 1, 16)   # the second tex2D


def test_two_samplers_at_one_texcoord_are_refused_on_ps11():
    fn = TWO_READS.format("    return tex2D(Checker, uv) + tex2D(Other, uv);")
    fx = effects.load_effect(f"{PARAMS}\nsampler2D Other = sampler_state {{ Texture = <T>; }};\n{fn}\n"
                             "technique T { pass P { PixelShader = compile ps_1_1 PS(); } }\n")
    with pytest.raises(EffectError, match="samplers 'Checker' and 'Other' are both read at TEXCOORD0; "
                       "ps_1_1 samples stage 0, one sampler, at TEXCOORD0") as info:
        compile_shader(fx, "PS", "ps_1_1")
    assert info.value.location.line == PARAMS.count("\n") + 5


def test_ps14_a_third_read_of_one_sampler_is_refused_at_it():
    fn = two_reads("return a + b + tex2D(Checker, uv * 0.5);")
    with pytest.raises(EffectError, match="sampler 'Checker' is read at 3 coordinates; ps_1_4 samples "
                       "a stage once in each of its two phases") as info:
        compile_shader(effect_for(fn, "ps_1_4"), "PS", "ps_1_4")
    assert info.value.location.line == FIRST_READ_LINE + 2


# --- fxc's preshader: what reads only uniforms runs on the host -------------------------------

PRESHADED = "float4 PS(float4 c : COLOR0) : COLOR { return c * -K0 + K1 * Scale; }"


def _preshaded(u, v, scale=0.5):
    # COLOR0 * -K0 + K1 * Scale, each channel by hand:
    # (0.5, 0.75, 1, 1) * -(0.5, 0.25, 0, 1) + (0, 1, 0.5, 0.5) * Scale
    d, k0, k1 = np.array(DIFFUSE), np.array([0.5, 0.25, 0.0, 1.0]), np.array([0.0, 1.0, 0.5, 0.5])
    return d * -k0 + k1 * scale


@pytest.mark.parametrize("target", ["ps_1_1", "ps_1_4"])
def test_uniform_only_expressions_are_computed_on_the_host(backend, target):
    """`K1 * Scale` reads only uniforms: fxc's preshader computed it on the CPU into a
    constant of its own, and so does this compiler, on every ps_1_x. `-K0` is a negated
    constant, which ps_1_4 does not allow: there the negation goes to the host too (without
    the preshader this shader does not assemble for ps_1_4)."""
    from effects.shaders.hlsl.registers import constant_values
    fx = effect_for(PRESHADED, target)
    shader = compile_shader(fx, "PS", target)
    assert check(shader.program) == [], shader.text
    registers = constant_values(fx, shader)
    host = {name: registers[shader.constants[name][0]] for name in shader.preshaders}
    values = sorted(host.values())
    # K1 * Scale = (0, 0.5, 0.25, 0.25); on ps_1_4 also -K0 = (-0.5, -0.25, 0, -1)
    assert values == ([(-0.5, -0.25, 0.0, -1.0)] if target == "ps_1_4" else []) + \
        [(0.0, 0.5, 0.25, 0.25)], shader.text
    assert "K1" not in shader.constants and "Scale" not in shader.constants
    assert ("K0" in shader.constants) == (target == "ps_1_1")   # ps_1_1 reads -c#
    img = render(PRESHADED, target, backend)
    each_pixel(img, _preshaded, target, shader.text)
    # computed when the pass is drawn, from the values then: not folded at compile time
    img = effects.render(fx, CARD[target], technique="T", backend=backend, scene=QUAD,
                         params={"Scale": 1.0, "T": make_texture(TEXELS, mips=False)})
    each_pixel(img.astype(np.float64) / 255.0, lambda u, v: _preshaded(u, v, 1.0), target,
               shader.text)


def test_a_stored_shader_keeps_its_preshader(tmp_path):
    from effects.base import disk_store
    from effects.shaders.hlsl import cache, store
    fx = effect_for(PRESHADED, "ps_1_4")
    value = next(a.value for a in fx.techniques[0].passes[0].states
                 if type(a.value).__name__ == "CompileShader")
    fresh = compile_shader(fx, "PS", "ps_1_4")
    assert disk_store.enable(str(tmp_path))
    try:
        name = store.key(cache.key_parts(fx, value, []), cache.declarations(fx), value.location)
        store.save(name, fresh)
        back = store.load(name)
    finally:
        disk_store.disable()
    assert back is not fresh and back.preshaders == fresh.preshaders and len(back.preshaders) == 2
    assert back.text == fresh.text and back.constants == fresh.constants


def test_what_a_preshader_reads_is_read_by_the_pass():
    """`normalize(L)` of a uniform is per-pixel work ps_1_4 has no instruction for (X4532);
    on the host it is one constant. The pass reads L and Scale through its preshaders: the
    doctor names Scale as unset, and a `set` between frames is drawn on the next one."""
    from effects.cli.doctor import parameters_read
    from effects.host.runtime import Runtime
    fx = effects.load_effect(PARAMS.replace("float Scale = 0.5;", "float Scale;") + """
        float4 PS(float4 c : COLOR0) : COLOR { return dot(c.rgb, normalize(L)) * Scale; }
        technique T { pass P { Lighting = False; PixelShader = compile ps_1_4 PS(); } }""")
    assert {"L", "Scale"} <= parameters_read(fx, fx.techniques[0])
    runtime = Runtime(fx, "radeon8500", scene=QUAD, size=SIZE, backend="numpy")
    assert runtime.render().image.max() == 0          # Scale reads 0 until it is set
    # dot((0.5, 0.75, 1), (0.5, 0.25, 0) / |..|) = (0.25 + 0.1875) / 0.559 = 0.7826
    runtime.set_value("Scale", 0.5)
    lit = runtime.render().image[4, 4, :3] / 255.0
    assert np.allclose(lit, 0.7826 * 0.5, atol=TOL), lit


@pytest.mark.parametrize("target", ["ps_1_1", "ps_1_4"])
def test_sin_of_a_uniform_is_the_preshaders(backend, target):
    """ps_1_x has no sincos; sin of a uniform is one constant the host computes, as fxc's
    preshader did; sin of a per-pixel value is still refused, located."""
    from effects.shaders.listing import listing
    fn = "float4 PS(float4 c : COLOR0) : COLOR { return c * sin(Scale * 1.0471976); }"
    fx = effect_for(fn, target)
    shader = compile_shader(fx, "PS", target)
    assert list(shader.preshaders) == ["<preshader 0>"] and "Scale" not in shader.constants
    assert any("= sincos(mad(frc(mad(mul(Scale" in line for line in listing(fx, shader))
    img = render(fn, target, backend)
    each_pixel(img, lambda u, v: np.array(DIFFUSE) * math.sin(0.5 * 1.0471976), target,
               shader.text)                 # sin(pi / 6) = 0.5
    with pytest.raises(EffectError, match=f"{target} cannot compute sin/cos") as info:
        compile_shader(effect_for("float4 PS(float2 uv : TEXCOORD0) : COLOR "
                                  "{ return sin(uv.x); }", target), "PS", target)
    assert info.value.location.line == PARAMS.count("\n") + 2


def test_ps14_rearranges_components_through_write_masks(backend):
    """ps_1_4 reads any one component replicated (.r/.g/.b/.a) and writes any mask, so a
    swizzle it has no source form for is a mov per selector into a temporary, as fxc compiled
    `c.r = c.g`; ps_1_1 still refuses it (only .a and .b replicate there)."""
    fn = ("float4 PS(float4 c : COLOR0) : COLOR "
          "{ float4 d = c; d.rb = c.gr; return d * float4(c.b, c.r, c.g, 1); }")
    text = asm(fn, "ps_1_4")
    import re
    # d = (c.g, c.g, c.r, c.a): the lanes keeping their own component in one mov, then one
    # mov per replicated selector
    assert re.search(r"mov r\d\.ga, v0\n", text) and re.search(r"mov r\d\.b, v0\.r\n", text) \
        and re.search(r"mov r\d\.r, v0\.g\n", text), text
    img = render(fn, "ps_1_4", backend)
    r, g, b, a = DIFFUSE
    each_pixel(img, lambda u, v: [g * b, g * r, r * g, a], "ps_1_4", text)
    with pytest.raises(EffectError, match="ps_1_1 has no swizzle"):
        compile_shader(effect_for(fn, "ps_1_1"), "PS", "ps_1_1")
