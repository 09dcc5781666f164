"""Real flow control from HLSL where the target has it (branches.py, loops.py, flowcode.py):

- `if (B)` on a `uniform bool` is `if b#` from vs_2_0 on (the bool gets a b# the pass sets as
  VertexShaderConstantB / PixelShaderConstantB), flattened where the target has no flow
  control (ps_2_0);
- `[branch] if (a < b)` is `if_lt a, b` on vs_2_a / vs_3_0 / ps_3_0, a located error on
  targets without dynamic flow control; `[flatten]` and plain `if`s are flattened;
- `break` in a uniform loop is `break_ne` (vs_2_a and up), `continue` runs the rest under a
  predicate, uniform loops nest (rep inside rep) up to 4 deep.
Each is rendered on both back ends and checked against values worked out by hand."""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.errors import EffectError
from effects.shaders.hlsl import compile_shader
from effects.shaders.listing import listing
from tests.test_hlsl_render import QUAD, backend  # noqa: F401

TOL = 1.5 / 255
PASS_PS = "float4 PS(float4 c : COLOR0) : COLOR { return c; }\n"
PASS_PS3 = "float4 PS3(float4 c : COLOR0) : COLOR { return c; }\n"


def load(text: str, vs: str, ps: str = "compile ps_2_0 PS()") -> effects.Effect:
    return effects.load_effect(text + f"technique T {{ pass P {{ VertexShader = {vs}; "
                                      f"PixelShader = {ps}; }} }}\n")


def draw(fx: effects.Effect, card: str, backend: str, params: dict | None = None) -> np.ndarray:
    img = effects.render(fx, card, technique="T", backend=backend, scene=QUAD, params=params)
    return img.astype(np.float64) / 255.0


def located(text: str, needle: str) -> tuple[int, int]:
    """(line, column) of the first `needle` in the effect text, 1-based."""
    for k, line in enumerate(text.split("\n")):
        if needle in line:
            return k + 1, line.index(needle) + 1
    raise AssertionError(needle)


# -- if (BoolUniform): a static branch -----------------------------------------------------------

BOOL_VS = """bool UseRed = true;
float4 VS(float4 p : POSITION, out float4 c : COLOR0) : POSITION
{
    c = float4(0, 0.5, 1, 1);
    if (UseRed) { c.r = 1; c.b = 0.25; }
    return p;
}
""" + PASS_PS


def bool_by_hand(use_red: bool) -> tuple[float, ...]:
    # red 1 and blue 1/4 when the bool is set, else the colour as first written
    return (1.0, 0.5, 0.25, 1.0) if use_red else (0.0, 0.5, 1.0, 1.0)


def test_a_bool_uniform_is_if_b_with_a_b_register():
    fx = load(BOOL_VS, "compile vs_2_0 VS()")
    shader = compile_shader(fx, "VS", "vs_2_0")
    lines = shader.text.split("\n")
    assert "if b0" in lines and "endif" in lines, shader.text
    assert shader.bool_registers == {"UseRed": 0}
    assert "UseRed" not in shader.constants           # read only as the branch
    assert any("UseRed" in line and "b0" in line for line in listing(fx, shader))


@pytest.mark.parametrize("use_red", [True, False])
def test_a_static_branch_renders_each_side(backend, use_red):
    fx = load(BOOL_VS, "compile vs_2_0 VS()")
    img = draw(fx, "radeon9700", backend, {"UseRed": use_red})
    assert np.allclose(img[4, 4], bool_by_hand(use_red), atol=TOL), img[4, 4]


@pytest.mark.parametrize("use_red", [True, False])
def test_not_bool_swaps_the_sides(backend, use_red):
    fx = load(BOOL_VS.replace("if (UseRed)", "if (!UseRed)"), "compile vs_2_0 VS()")
    assert "if b0" in compile_shader(fx, "VS", "vs_2_0").text
    img = draw(fx, "radeon9700", backend, {"UseRed": use_red})
    assert np.allclose(img[4, 4], bool_by_hand(not use_red), atol=TOL), img[4, 4]


BOOL_PS = """bool Bright = false;
float4 VS(float4 p : POSITION, float2 uv : TEXCOORD0, out float2 t : TEXCOORD0) : POSITION
{ t = uv; return p; }
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float4 c = float4(uv.x, 0.25, 0, 1);
    if (Bright) c.rg = c.rg * 2;
    else c.b = 0.5;
    return c;
}
"""


def bright_by_hand(u: float, bright: bool) -> tuple[float, ...]:
    # red and green doubled when set (the framebuffer clamps red to 1 past u = 1/2), else
    # blue 1/2
    return (min(2 * u, 1.0), 0.5, 0.0, 1.0) if bright else (u, 0.25, 0.5, 1.0)


@pytest.mark.parametrize("bright", [True, False])
def test_ps_2_0_has_no_branches_so_the_bool_is_a_constant_and_flattened(backend, bright):
    fx = load(BOOL_PS, "compile vs_2_0 VS()")
    shader = compile_shader(fx, "PS", "ps_2_0")
    assert "if" not in shader.text and shader.bool_registers == {}, shader.text
    assert "Bright" in shader.constants
    img = draw(fx, "radeon9700", backend, {"Bright": bright})
    for x, y in ((1, 1), (5, 6)):
        want = bright_by_hand(x / 8, bright)
        assert np.allclose(img[y, x], want, atol=TOL), (x, img[y, x], want)


@pytest.mark.parametrize("bright", [True, False])
def test_ps_3_0_branches_on_the_bool_with_an_else(backend, bright):
    fx = load(BOOL_PS, "compile vs_3_0 VS()", "compile ps_3_0 PS()")
    text = compile_shader(fx, "PS", "ps_3_0").text
    assert text.index("if b0") < text.index("else") < text.index("endif"), text
    img = draw(fx, "geforce6800", backend, {"Bright": bright})
    for x, y in ((2, 1), (7, 4)):
        want = bright_by_hand(x / 8, bright)
        assert np.allclose(img[y, x], want, atol=TOL), (x, img[y, x], want)


def test_an_explicit_b_register_is_kept():
    fx = load(BOOL_VS.replace("bool UseRed = true;", "bool UseRed : register(b3) = true;"),
              "compile vs_2_0 VS()")
    shader = compile_shader(fx, "VS", "vs_2_0")
    assert "if b3" in shader.text and shader.bool_registers == {"UseRed": 3}


# -- [branch]: a dynamic branch ----------------------------------------------------------------

BRANCH = """float Threshold = 0.5;
float4 VS(float4 p : POSITION, float2 uv : TEXCOORD0, out float2 t : TEXCOORD0) : POSITION
{ t = uv; return p; }
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float4 c = float4(0.25, 0.25, 0.25, 1);
    [branch] if (uv.x < Threshold) { c.r = uv.x * 2; c.g = 0.75; }
    else c.b = 1;
    return c;
}
"""


def branch_by_hand(u: float, threshold: float) -> tuple[float, ...]:
    return (2 * u, 0.75, 0.25, 1.0) if u < threshold else (0.25, 0.25, 1.0, 1.0)


@pytest.mark.parametrize("threshold", [0.55, 0.3])   # never a sampled u (k / 8)
def test_branch_is_if_comp_in_ps_3_0(backend, threshold):
    fx = load(BRANCH, "compile vs_3_0 VS()", "compile ps_3_0 PS()")
    text = compile_shader(fx, "PS", "ps_3_0").text
    assert "if_lt v0.x, c0.x" in text, text
    body = text[text.index("if_lt"):text.index("else")]
    assert "mul" in body, text                        # uv.x * 2 only where it is taken
    assert "cmp" not in text and "lrp" not in text, text
    img = draw(fx, "geforce6800", backend, {"Threshold": threshold})
    for x, y in ((1, 2), (3, 3), (4, 5), (7, 1)):
        want = branch_by_hand(x / 8, threshold)
        assert np.allclose(img[y, x], want, atol=TOL), (x, img[y, x], want)


def test_flatten_and_no_attribute_flatten_in_ps_3_0(backend):
    # the rule: without [branch] an if on a run-time value is flattened on every target (fxc
    # flattens small ifs itself; flattening never needs a cap)
    for attr in ("[flatten] ", ""):
        fx = load(BRANCH.replace("[branch] ", attr), "compile vs_3_0 VS()",
                  "compile ps_3_0 PS()")
        text = compile_shader(fx, "PS", "ps_3_0").text
        assert "if" not in text and "cmp" in text, text
        img = draw(fx, "geforce6800", backend)
        for x in (2, 6):
            assert np.allclose(img[3, x], branch_by_hand(x / 8, 0.5), atol=TOL), img[3, x]


@pytest.mark.parametrize("target", ["ps_2_0", "ps_2_a", "ps_2_b"])
def test_branch_on_a_target_without_dynamic_flow_control_is_a_located_error(target):
    fx = load(BRANCH, "compile vs_2_0 VS()", f"compile {target} PS()")
    with pytest.raises(EffectError) as err:
        compile_shader(fx, "PS", target)
    assert err.value.message == (f"[branch] needs dynamic flow control (if_comp), which {target} "
                                 "does not have (vs_2_a, vs_3_0 and ps_3_0 do); use [flatten] "
                                 "or no attribute")
    loc = err.value.location
    assert (loc.line, loc.column) == located(BRANCH, "[branch]")


VS_BRANCH = """float4 VS(float4 p : POSITION, out float4 c : COLOR0) : POSITION
{
    c = float4(0, 0, 0, 1);
    [branch] if (p.x > 0) c.r = 1;
    else c.g = 1;
    return p;
}
""" + PASS_PS


def test_branch_in_a_vertex_shader_is_if_gt_in_vs_2_a_and_refused_in_vs_2_0(backend):
    fx = load(VS_BRANCH, "compile vs_2_a VS()")
    assert "if_gt" in compile_shader(fx, "VS", "vs_2_a").text
    img = draw(fx, "geforcefx5900", backend)
    # the quad's two right corners are red, the left ones green: colours interpolate across
    # x, so at pixel x the colour is x / 8 red and the rest green (D3D 9 samples at the
    # pixel's integer position: tests/test_hlsl_render.pixel_uv)
    for x in (0, 3, 7):
        r = x / 8
        assert np.allclose(img[4, x], (r, 1 - r, 0, 1), atol=2.5 / 255), (x, img[4, x])
    with pytest.raises(EffectError, match=r"\[branch\] needs dynamic flow control \(if_comp\), "
                                          "which vs_2_0 does not have"):
        compile_shader(fx, "VS", "vs_2_0")


# -- loops: break, continue, nesting -----------------------------------------------------------

BREAK = """int N = 5;
float4 VS(float4 p : POSITION, out float4 c : COLOR0) : POSITION
{
    float4 acc = float4(0, 0, 0, 1);
    for (int i = 0; i < N; i++) {
        acc.z += 0.125;
        if (acc.x > 0.3) break;
        acc.x += 0.25;
        acc.y += 0.0625;
    }
    c = acc;
    return p;
}
""" + PASS_PS


def break_by_hand(n: int) -> tuple[float, ...]:
    """acc.x grows by 1/4 until it passes 0.3 (after two steps); the iteration that breaks
    still adds its 1/8 to z before the test."""
    x = y = z = 0.0
    for _ in range(n):
        z += 0.125
        if x > 0.3:
            break
        x += 0.25
        y += 0.0625
    return (x, y, z, 1.0)


def test_break_hand_values():
    assert break_by_hand(5) == (0.5, 0.125, 0.375, 1.0)
    assert break_by_hand(1) == (0.25, 0.0625, 0.125, 1.0)


@pytest.mark.parametrize("target, card", [("vs_2_a", "geforcefx5900"), ("vs_3_0", "geforce6800")])
@pytest.mark.parametrize("count", [0, 1, 2, 5])
def test_break_leaves_the_rep_with_break_ne(backend, target, card, count):
    ps = "compile ps_3_0 PS3()" if target == "vs_3_0" else "compile ps_2_0 PS()"
    fx = load(BREAK + PASS_PS3, f"compile {target} VS()", ps)
    text = compile_shader(fx, "VS", target).text
    assert text.index("rep i0") < text.index("break_ne") < text.index("endrep"), text
    img = draw(fx, card, backend, {"N": count})
    assert np.allclose(img[4, 4], break_by_hand(count), atol=TOL), (img[4, 4], count)


CONTINUE = """int N = 4;
float4 VS(float4 p : POSITION, out float4 c : COLOR0) : POSITION
{
    float4 acc = float4(0, 0, 0, 1);
    for (int i = 0; i < N; i++) {
        acc.y += 0.0625;
        if (i == 1) continue;
        acc.x += 0.25;
    }
    c = acc;
    return p;
}
""" + PASS_PS


@pytest.mark.parametrize("count, want", [(0, (0, 0, 0, 1)), (1, (0.25, 0.0625, 0, 1)),
                                         (2, (0.25, 0.125, 0, 1)), (4, (0.75, 0.25, 0, 1))])
def test_continue_skips_the_rest_of_one_iteration_in_vs_2_0(backend, count, want):
    # iteration 1 skips the red step: red 1/4 for each other iteration, green 1/16 for all
    fx = load(CONTINUE, "compile vs_2_0 VS()")
    text = compile_shader(fx, "VS", "vs_2_0").text
    assert text.count("rep i0") == 1, text
    img = draw(fx, "radeon9700", backend, {"N": count})
    assert np.allclose(img[4, 4], want, atol=TOL), (img[4, 4], want)


NESTED = """int N = 3;
int M = 2;
float4 VS(float4 p : POSITION, out float4 c : COLOR0) : POSITION
{
    float4 acc = float4(0, 0, 0, 1);
    for (int j = 0; j < N; j++) {
        acc.x += 0.125;
        for (int k = 0; k < M; k++)
            acc.y += 0.0625;
    }
    c = acc;
    return p;
}
""" + PASS_PS


@pytest.mark.parametrize("n, m", [(0, 2), (1, 3), (3, 2), (2, 0)])
def test_nested_uniform_loops_are_nested_reps(backend, n, m):
    # red 1/8 per outer iteration, green 1/16 per inner one: n * m of them
    fx = load(NESTED, "compile vs_2_0 VS()")
    text = compile_shader(fx, "VS", "vs_2_0").text
    assert text.index("rep i0") < text.index("rep i1") < text.index("endrep"), text
    assert text.count("endrep") == 2
    img = draw(fx, "geforcefx5900", backend, {"N": n, "M": m})
    want = (0.125 * n, 0.0625 * n * m, 0.0, 1.0)
    assert np.allclose(img[4, 4], want, atol=TOL), (img[4, 4], want)


def nested(depth: int) -> str:
    head = "".join(f"{'    ' * (k + 1)}for (int i{k} = 0; i{k} < N; i{k}++)\n" for k in range(depth))
    return ("int N = 2;\nfloat4 VS(float4 p : POSITION, out float4 c : COLOR0) : POSITION\n{\n"
            "    float4 acc = float4(0, 0, 0, 1);\n" + head + "    " * (depth + 1) +
            "acc.x += 0.03125;\n    c = acc;\n    return p;\n}\n" + PASS_PS)


def test_four_nested_loops_compile_and_a_fifth_is_a_located_error(backend):
    fx = load(nested(4), "compile vs_2_0 VS()")
    assert compile_shader(fx, "VS", "vs_2_0").text.count("rep i0") == 4
    img = draw(fx, "geforcefx5900", backend, {"N": 2})
    assert np.allclose(img[4, 4], (16 / 32, 0, 0, 1), atol=TOL), img[4, 4]   # 2**4 times 1/32
    text = nested(5)
    with pytest.raises(EffectError) as err:
        compile_shader(load(text, "compile vs_2_0 VS()"), "VS", "vs_2_0")
    assert err.value.message.endswith("it cannot be a rep: it would nest loops (rep, loop) 5 "
                                      "deep, and vs_2_0 allows 4"), err.value.message
    loc = err.value.location
    assert (loc.line, loc.column) == located(text, "for (int i4")
