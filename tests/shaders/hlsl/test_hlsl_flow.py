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
from effects.base.errors import EffectError
from effects.shaders.hlsl import compile_shader
from effects.shaders.listing import listing
from tests.shaders.hlsl.test_hlsl_render import QUAD, backend  # noqa: F401

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
                                 "or no attribute (no X code: fxc's wording for this was not "
                                 "found)")
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


# -- loop aL: a counter that indexes constants ------------------------------------------------

LIGHTS = """int NumLights = 2;
struct Light { float4 Color; };
Light Lights[4] = {0.125,0,0,0, 0,0.25,0,0, 0,0,0.5,0, 0.25,0.25,0.25,0};
float4 VS(float4 p : POSITION, out float4 c : COLOR0) : POSITION
{
    c = float4(0, 0, 0, 1);
    for (int i = 0; i < NumLights; i++)
        c.rgb += Lights[i].Color.rgb;
    return p;
}
"""
COLORS = [(0.125, 0, 0), (0, 0.25, 0), (0, 0, 0.5), (0.25, 0.25, 0.25)]


def lights_by_hand(n: int, scale: float = 1.0) -> tuple[float, ...]:
    """The first n colours summed (times `scale`), alpha 1. aL must run 0, 1, ... n - 1: an
    i# of (n, 0, 0, 0) (step 0) would add the first colour n times instead."""
    return tuple(scale * sum(c[k] for c in COLORS[:n]) for k in range(3)) + (1.0,)


GOLDEN_LIGHTS_VS20 = """vs_2_0
def c4, 0, 0, 0, 1
dcl_position v0
mov r0, c4
loop aL, i0
add r0.xyz, r0, c0[aL]
endloop
mov oPos, v0
mov oD0, r0
"""


def test_a_counter_indexing_a_uniform_array_is_loop_al_as_fxc_compiles_it():
    # the counter is not carried as a float (nothing reads it as a number); the effect sets
    # i0 from NumLights, the shader defines no defi
    fx = load(LIGHTS + PASS_PS, "compile vs_2_0 VS()")
    shader = compile_shader(fx, "VS", "vs_2_0")
    assert shader.text == GOLDEN_LIGHTS_VS20, shader.text
    assert shader.int_registers == {"NumLights": 0}
    assert shader.constants == {"Lights": (0, 4)}


def test_the_pass_sets_the_int_register_as_d3dx_does():
    # D3DX's constant table writes an int into an int4 register as (value, 0, 1, 0): the
    # loop's count, first aL and aL step
    from effects.d3d9.device import pass_states
    from effects.lower.passes import _assemble, _int_constants, _shader
    fx = load(LIGHTS + PASS_PS, "compile vs_2_0 VS()")
    fx.parameter("NumLights").value = 3
    [(_, state)] = pass_states(fx, fx.techniques[0].passes)
    _, compiled = _assemble(fx, state, _shader(state, "VertexShader"), "vertex")
    assert compiled.int_registers == {"NumLights": 0}
    assert state.int_constants("Vertex")[0] == (3, 0, 0, 0)        # the state as assigned
    assert _int_constants(state, "Vertex", compiled)[0] == (3, 0, 1, 0)


@pytest.mark.parametrize("target, card", [("vs_2_0", "radeon9700"), ("vs_2_a", "geforcefx5900"),
                                          ("vs_3_0", "geforce6800")])
@pytest.mark.parametrize("count", [0, 1, 2, 4])
def test_loop_al_renders_the_first_n_elements(backend, target, card, count):
    ps = "compile ps_3_0 PS3()" if target == "vs_3_0" else "compile ps_2_0 PS()"
    fx = load(LIGHTS + PASS_PS + PASS_PS3, f"compile {target} VS()", ps)
    text = compile_shader(fx, "VS", target).text
    assert text.index("loop aL, i0") < text.index("c0[aL]") < text.index("endloop"), text
    img = draw(fx, card, backend, {"NumLights": count})
    assert np.allclose(img[4, 4], lights_by_hand(count), atol=TOL), (img[4, 4], count)


LIGHTS_PS = """int NumLights = 2;
struct Light { float4 Color; };
Light Lights[4] = {0.125,0,0,0, 0,0.25,0,0, 0,0,0.5,0, 0.25,0.25,0.25,0};
float4 VS(float4 p : POSITION, float2 uv : TEXCOORD0, out float2 t : TEXCOORD0) : POSITION
{ t = uv; return p; }
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float4 c = float4(0, 0, 0, 1);
    for (int i = 0; i < NumLights; i++)
        c.rgb += Lights[i].Color.rgb * uv.x;
    return c;
}
"""


@pytest.mark.parametrize("count", [0, 1, 3])
def test_ps_3_0_indexes_constants_by_al_in_a_loop(backend, count):
    # the relative-addressing page: c# is indexed by aL in ps_3_0 (no a0 there)
    fx = load(LIGHTS_PS, "compile vs_3_0 VS()", "compile ps_3_0 PS()")
    text = compile_shader(fx, "PS", "ps_3_0").text
    assert "loop aL, i0" in text and "mad r0.xyz, c0[aL], v0.x, r0" in text, text
    img = draw(fx, "geforce6800", backend, {"NumLights": count})
    for x, y in ((2, 1), (4, 4), (7, 6)):
        want = lights_by_hand(count, x / 8)
        assert np.allclose(img[y, x], want, atol=TOL), (x, img[y, x], want)


@pytest.mark.parametrize("count, want", [(0, (0, 0, 0, 1)), (1, (0.0625, 0, 0, 1)),
                                         (3, (0.0625, 0, 0.25, 1))])
def test_ps_3_0_picks_an_element_of_two_registers_in_a_uniform_loop_by_selects(backend, count,
                                                                               want):
    # aL steps by 1 and an element takes two registers, and ps_3_0 has no a0: fxc's select
    # chain over the counter instead (issue 30: a run-time index where no aL applies). The
    # list fills Color, Spare of each element in turn: Colors (1/8, 0, 0), (0, 0, 1/2), 0, 0
    # (the list padded to the 32 numbers the array holds: fxc refused a short one, X3017)
    text = LIGHTS_PS.replace("struct Light { float4 Color; };",
                             "struct Light { float4 Color; float4 Spare; };").replace(
        "0.25,0.25,0.25,0};", "0.25,0.25,0.25,0" + ", 0" * 16 + "};")
    fx = load(text, "compile vs_3_0 VS()", "compile ps_3_0 PS()")
    asm = compile_shader(fx, "PS", "ps_3_0").text
    assert "rep i0" in asm and "cmp" in asm and "aL" not in asm, asm
    img = draw(fx, "geforce6800", backend, {"NumLights": count})
    assert np.allclose(img[4, 4], want, atol=TOL), img[4, 4]     # u = 1/2 scales the sum


PAIRS_LOOP = """struct Pair { float4 a; float4 b; };
Pair Pairs[3] = {0.125,0,0,0, 0,0,0.0625,0, 0,0.25,0,0, 0,0,0.125,0, 0.25,0.25,0,0, 0,0,0.25,0};
float4 VS(float4 p : POSITION, out float4 c : COLOR0) : POSITION
{
    float4 acc = float4(0, 0, 0, 0.25);
    [loop] for (int i = 1; i < 3; i++) {
        acc.rgb += Pairs[i].a.rgb * 2 + Pairs[i].b.rgb;
        acc.a += 0.125 * i;
    }
    c = acc;
    return p;
}
"""


def test_a_loop_over_literal_bounds_defines_its_count_start_and_step():
    # [loop] keeps a real loop: i runs 1, 2, so aL = 2i runs 2, 4 (a Pair takes two
    # registers): defi (count 2, first aL 2, step 2, 0); the counter is carried too, as the
    # body reads it as a number
    fx = load(PAIRS_LOOP + PASS_PS, "compile vs_2_0 VS()")
    shader = compile_shader(fx, "VS", "vs_2_0")
    text = shader.text
    assert "defi i0, 2, 2, 2, 0" in text.split("\n"), text
    assert text.index("loop aL, i0") < text.index("c0[aL]") < text.index("endloop"), text
    assert "c1[aL]" in text and shader.int_registers == {}, text


def test_the_literal_loop_renders(backend):
    # i = 1: a = (0, 0.25, 0), b = (0, 0, 0.125); i = 2: a = (0.25, 0.25, 0), b = (0, 0, 0.25);
    # rgb = 2 (a1 + a2) + b1 + b2 = (0.5, 1, 0.375); alpha 1/4 + 1/8 (1 + 2) = 5/8
    fx = load(PAIRS_LOOP + PASS_PS, "compile vs_2_0 VS()")
    img = draw(fx, "radeon9700", backend)
    assert np.allclose(img[4, 4], (0.5, 1.0, 0.375, 0.625), atol=TOL), img[4, 4]


def test_loop_on_a_target_without_loops_is_unrolled_with_a_warning(backend):
    fx = load(PAIRS_LOOP + PASS_PS, "compile vs_1_1 VS()", "compile ps_1_1 PS()")
    shader = compile_shader(fx, "VS", "vs_1_1")
    assert "loop" not in shader.text and "rep" not in shader.text, shader.text
    [warning] = [w for w in shader.warnings if "[loop]" in w.message]
    assert warning.message == ("[loop] not kept: it is marked [loop], and vs_1_1 has no loops "
                               "(rep needs vs_2_0, ps_2_x or ps_3_0); the loop is unrolled")
    assert (warning.location.line, warning.location.column) == located(PAIRS_LOOP, "[loop]")
    img = draw(fx, "geforce3", backend)
    assert np.allclose(img[4, 4], (0.5, 1.0, 0.375, 0.625), atol=TOL), img[4, 4]


def test_a_body_that_changes_the_counter_is_not_a_loop_and_says_so():
    # a rep / loop runs the count the effect set, whatever the body does to i
    text = LIGHTS.replace("        c.rgb += Lights[i].Color.rgb;\n",
                          "    {\n        c.rgb += Lights[i].Color.rgb;\n"
                          "        if (c.r > 0.1) i++;\n    }\n")
    fx = load(text + PASS_PS, "compile vs_2_0 VS()")
    with pytest.raises(EffectError) as err:
        compile_shader(fx, "VS", "vs_2_0")
    assert err.value.message == (
        "X3511: unable to unroll loop: its count is the uniform 'NumLights', known only when "
        "the shader runs, and it cannot be a rep: the body changes the counter 'i' (the loop "
        "runs the count it was given, and aL steps by itself)")
    loc = err.value.location
    assert (loc.line, loc.column) == located(text, "for (int i")


# -- discard, clip and return inside real branches and loops ---------------------------------

ESCAPES = """int N = 3;
float Threshold = 0.55;
bool Cut = true;
float4 VS(float4 p : POSITION, float2 uv : TEXCOORD0, out float2 t : TEXCOORD0) : POSITION
{ t = uv; return p; }
float4 PSK(float2 uv : TEXCOORD0) : COLOR
{
    float4 c = float4(uv.x, 0.5, 0, 1);
    [branch] if (uv.x < Threshold) { c.b = 1; discard; }
    return c;
}
float4 PSR(float2 uv : TEXCOORD0) : COLOR
{
    float4 c = float4(uv.x, 0.5, 0, 1);
    [branch] if (uv.x < Threshold) return float4(0, 0, 1, 1);
    c.g = 0.25;
    return c;
}
float4 PSB(float2 uv : TEXCOORD0) : COLOR
{
    if (Cut) { clip(uv.x - Threshold); return float4(1, 1, 0, 1); }
    return float4(uv.x, 0.5, 0, 1);
}
float4 PSL(float2 uv : TEXCOORD0) : COLOR
{
    float4 c = float4(0, 0, 0, 1);
    for (int i = 0; i < N; i++) {
        c.r += 0.25;
        if (c.r > uv.x) return float4(c.r, 1, 0, 1);
        clip(uv.y - 0.25 * i);
    }
    return c;
}
"""
BACKGROUND = (0.0, 0.0, 0.0, 0.0)        # what a discarded pixel leaves (the cleared target)
ODD = [(x, y) for x in (1, 3, 5, 7) for y in (1, 3, 5, 7)]   # u, v = 1/8, 3/8 ...: no ties


def escapes(entry: str) -> effects.Effect:
    return load(ESCAPES, "compile vs_3_0 VS()", f"compile ps_3_0 {entry}()")


def test_discard_in_a_dynamic_branch_is_texkill_inside_it(backend):
    fx = escapes("PSK")
    text = compile_shader(fx, "PSK", "ps_3_0").text
    assert text.index("if_lt") < text.index("texkill") < text.index("else"), text
    img = draw(fx, "geforce6800", backend)
    for x, y in ODD:
        u = x / 8
        want = BACKGROUND if u < 0.55 else (u, 0.5, 0, 1)
        assert np.allclose(img[y, x], want, atol=TOL), (x, y, img[y, x], want)


def test_return_in_a_dynamic_branch_is_a_returned_predicate(backend):
    # the side sets 'returned' and the value; what follows the if runs under 'not returned'
    fx = escapes("PSR")
    text = compile_shader(fx, "PSR", "ps_3_0").text
    assert "if_lt v0.x, c0.x" in text and "endif" in text, text
    img = draw(fx, "geforce6800", backend)
    for x, y in ODD:
        u = x / 8
        want = (0, 0, 1, 1) if u < 0.55 else (u, 0.25, 0, 1)
        assert np.allclose(img[y, x], want, atol=TOL), (x, y, img[y, x], want)


@pytest.mark.parametrize("cut", [True, False])
def test_clip_and_return_in_a_static_branch(backend, cut):
    fx = escapes("PSB")
    text = compile_shader(fx, "PSB", "ps_3_0").text
    assert text.index("if b0") < text.index("texkill") < text.index("endif"), text
    img = draw(fx, "geforce6800", backend, {"Cut": cut})
    for x, y in ODD:
        u = x / 8
        want = (u, 0.5, 0, 1) if not cut else BACKGROUND if u < 0.55 else (1, 1, 0, 1)
        assert np.allclose(img[y, x], want, atol=TOL), (x, y, img[y, x], want)


def loop_escapes_by_hand(u: float, v: float, n: int) -> tuple[float, ...]:
    """PSL: red steps by 1/4; the iteration where it passes u returns (red, 1, 0, 1); until
    then each iteration clips where v < i / 4 (the pixel is discarded, whatever follows)."""
    red, killed = 0.0, False
    for i in range(n):
        red += 0.25
        if red > u:
            return BACKGROUND if killed else (red, 1.0, 0.0, 1.0)
        killed = killed or v - 0.25 * i < 0
    return BACKGROUND if killed else (red, 0.0, 0.0, 1.0)


def test_loop_escape_hand_values():
    assert loop_escapes_by_hand(0.875, 0.125, 3) == BACKGROUND           # clipped at i = 1
    assert loop_escapes_by_hand(0.375, 0.125, 3) == (0.5, 1.0, 0.0, 1.0)
    assert loop_escapes_by_hand(0.875, 0.625, 3) == (0.75, 0.0, 0.0, 1.0)


@pytest.mark.parametrize("count", [0, 1, 3])
def test_return_and_clip_in_a_rep_body(backend, count):
    # ps_3_0 has break_comp: the rep also leaves once it returned (break_ne on 'returned')
    fx = escapes("PSL")
    text = compile_shader(fx, "PSL", "ps_3_0").text
    assert text.index("rep i0") < text.index("texkill") < text.index("break_ne") \
        < text.index("endrep"), text
    img = draw(fx, "geforce6800", backend, {"N": count})
    for x, y in ODD:
        want = loop_escapes_by_hand(x / 8, y / 8, count)
        assert np.allclose(img[y, x], want, atol=TOL), (x, y, count, img[y, x], want)


VS_RETURN = """int N = 4;
float Limit = 0.6;
float4 VS(float4 p : POSITION, out float4 c : COLOR0) : POSITION
{
    c = float4(0, 0, 0, 1);
    for (int i = 0; i < N; i++) {
        c.r += 0.25;
        if (c.r > Limit) return p;
    }
    c.g = 1;
    return p;
}
"""


def vs_return_by_hand(n: int, limit: float) -> tuple[float, ...]:
    red = 0.0
    for _ in range(n):
        red += 0.25
        if red > limit:
            return (red, 0.0, 0.0, 1.0)
    return (red, 1.0, 0.0, 1.0)


@pytest.mark.parametrize("target, card", [("vs_2_0", "radeon9700"), ("vs_2_a", "geforcefx5900")])
@pytest.mark.parametrize("count, limit", [(0, 0.6), (2, 0.6), (4, 0.6), (4, 0.9)])
def test_return_in_a_vertex_rep(backend, target, card, count, limit):
    # vs_2_0 has no break_comp: the iterations after the return run under 'not returned';
    # vs_2_a leaves the rep with break_ne
    fx = load(VS_RETURN + PASS_PS, f"compile {target} VS()")
    text = compile_shader(fx, "VS", target).text
    assert "rep i0" in text and ("break_ne" in text) == (target == "vs_2_a"), text
    img = draw(fx, card, backend, {"N": count, "Limit": limit})
    want = vs_return_by_hand(count, limit)
    assert np.allclose(img[4, 4], want, atol=TOL), (img[4, 4], want)


STRUCT_RETURN = """float Threshold = 0.5;
int N = 2;
struct PS_OUT { float4 color : COLOR0; };
float4 VS(float4 p : POSITION, float2 uv : TEXCOORD0, out float2 t : TEXCOORD0) : POSITION
{ t = uv; return p; }
PS_OUT PS(float2 uv : TEXCOORD0)
{
    PS_OUT o;
    o.color = float4(uv.x, 0, 0, 1);
    [branch] if (uv.x < Threshold) return o;
    o.color.g = 1;
    return o;
}
PS_OUT PSL(float2 uv : TEXCOORD0)
{
    PS_OUT o;
    o.color = float4(0, 0, 0, 1);
    float red = 0;
    for (int i = 0; i < N; i++) {
        red += 0.25;
        if (red > uv.x) return o;
    }
    o.color.r = red;
    return o;
}
"""


def test_a_struct_returned_in_a_dynamic_branch_is_carried_out_of_it(backend):
    # a side's struct (here the return value) is carried out of a real `if` as a loop carries
    # it (branches.real_if); before, "return of a struct inside it is not generated in a
    # branch yet"
    fx = load(STRUCT_RETURN, "compile vs_3_0 VS()", "compile ps_3_0 PS()")
    assert "if_lt" in compile_shader(fx, "PS", "ps_3_0").text
    img = draw(fx, "geforce6800", backend)
    # o.color = (u, 0, 0, 1), returned where u < 0.5; elsewhere its green is set to 1
    for x in (1, 3, 5, 7):
        u = x / QUAD["size"][0]
        want = (u, 0, 0, 1) if u < 0.5 else (u, 1, 0, 1)
        assert np.allclose(img[4, x], want, atol=TOL), (x, img[4, x])


def test_a_struct_returned_in_a_rep_body_is_carried_round_the_loop(backend):
    # issue 31: a struct (the return value) is carried in registers like a number; before,
    # "return of a struct in the body is not generated in a rep yet" (X3511)
    fx = load(STRUCT_RETURN, "compile vs_3_0 VS()", "compile ps_3_0 PSL()")
    assert "loop" in compile_shader(fx, "PSL", "ps_3_0").text or \
        "rep" in compile_shader(fx, "PSL", "ps_3_0").text
    img = draw(fx, "geforce6800", backend)
    # N = 2: red reaches 0.25, then 0.5; a pixel with u < red at either step returns black
    for x in (1, 3, 5, 7):                      # u = 0.5 exactly would be a tie
        u = x / QUAD["size"][0]                # test_hlsl_render.pixel_uv
        want = (0, 0, 0, 1) if u < 0.5 else (0.5, 0, 0, 1)
        assert np.allclose(img[4, x], want, atol=1.5 / 255), (x, img[4, x])


# -- gradients and dynamic flow control ------------------------------------------------------

GRADIENTS = """int N = 3;
float Threshold = 0.5;
float4 VS(float4 p : POSITION, float2 uv : TEXCOORD0, out float2 t : TEXCOORD0) : POSITION
{ t = uv; return p; }
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float4 c = float4(0.25, 0.25, 0.25, 1);
    [branch] if (uv.x < Threshold) { c.r = ddx(uv.x * 2) * 2; c.g = ddy(uv.y) * 4; }
    return c;
}
float4 PSL(float2 uv : TEXCOORD0) : COLOR
{
    float4 c = float4(0, 0, 0, 1);
    for (int i = 0; i < N; i++) {
        c.r += 0.25;
        if (c.r > uv.x) break;
        c.g += ddx(uv.x * c.r);
    }
    return c;
}
"""


@pytest.mark.parametrize("threshold", [0.55, 0.3])
def test_gradients_in_a_dynamic_branch_are_computed_before_it(backend, threshold):
    # as fxc does: a gradient is undefined where neighbouring pixels take different sides,
    # so dsx / dsy (and texld) move before the if_comp, their operands with them.
    # ddx(2u) * 2 = 2 / 8 * 2 = 1/2 and ddy(v) * 4 = 1/2 on the 8 x 8 quad
    fx = load(GRADIENTS, "compile vs_3_0 VS()", "compile ps_3_0 PS()")
    text = compile_shader(fx, "PS", "ps_3_0").text
    assert text.index("dsx") < text.index("if_lt") and text.index("dsy") < text.index("if_lt"), text
    img = draw(fx, "geforce6800", backend, {"Threshold": threshold})
    for x, y in ODD:
        want = (0.5, 0.5, 0.25, 1) if x / 8 < threshold else (0.25, 0.25, 0.25, 1)
        assert np.allclose(img[y, x], want, atol=TOL), (x, y, img[y, x], want)


def test_a_gradient_that_needs_a_loop_with_a_break_is_x4014_at_it():
    fx = load(GRADIENTS, "compile vs_3_0 VS()", "compile ps_3_0 PSL()")
    with pytest.raises(EffectError) as err:
        compile_shader(fx, "PSL", "ps_3_0")
    assert err.value.message.startswith("X4014: cannot have gradient operations inside loops "
                                        "with divergent flow control"), err.value.message
    loc = err.value.location
    assert (loc.line, loc.column) == located(GRADIENTS, "ddx(uv.x * c.r)")


UNROLLED_INSIDE = LIGHTS_PS.replace(
    "        c.rgb += Lights[i].Color.rgb * uv.x;\n",
    "        for (int k = 0; k < 2; k++)\n            c.rgb += Lights[i].Color.rgb * uv.x * 0.5;\n")


@pytest.mark.parametrize("count", [0, 2, 3])
def test_al_indexes_from_a_loop_unrolled_inside_the_real_one(backend, count):
    # the inner loop unrolls (twice half the colour), making no block: aL is still i
    fx = load(UNROLLED_INSIDE, "compile vs_3_0 VS()", "compile ps_3_0 PS()")
    text = compile_shader(fx, "PS", "ps_3_0").text
    assert text.count("loop aL, i0") == 1 and "c0[aL]" in text, text
    img = draw(fx, "geforce6800", backend, {"NumLights": count})
    for x, y in ((3, 2), (6, 5)):
        want = lights_by_hand(count, x / 8)
        assert np.allclose(img[y, x], want, atol=TOL), (x, img[y, x], want)


# -- unrolled loops under a run-time predicate -------------------------------------------------

@pytest.mark.parametrize("body, by_hand", [
    # a literal loop inside a flattened if: twice 1/4 where u > 1/2
    ("if (uv.x > 0.5) { for (int k = 0; k < 2; k++) c.r += 0.25; }",
     lambda u: 0.5 if u > 0.5 else 0.0),
    # a run-time break: the pixels right of the middle leave at once, the others add 4 x 1/4
    ("for (int k = 0; k < 4; k++) { if (uv.x > 0.5) break; c.r += 0.25; }",
     lambda u: 0.0 if u > 0.5 else 1.0),
])
def test_an_unrolled_loop_under_a_run_time_predicate_still_ends(backend, body, by_hand):
    # its counter (declared by the for) steps whatever the predicate, so `k < n` stays a
    # compile-time value and the loop unrolls n times (it was X3511 'does not terminate')
    from tests.shaders.hlsl.test_hlsl_render import effect_for, render
    fx = effect_for("float4 PS(float2 uv : TEXCOORD0) : COLOR\n{\n    float4 c = 0;\n    "
                    + body + "\n    return c;\n}\n")
    img = render(fx, backend)
    for x in (1, 3, 5, 7):
        want = (by_hand(x / 8), 0, 0, 0)
        assert np.allclose(img[2, x], want, atol=TOL), (x, img[2, x], want)
