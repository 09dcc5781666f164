"""`switch` (issue 30's most frequent construct that valid programs failed on): flattened into
one select per case for ps_2_0, as fxc compiled it for Direct3D 9 targets, rendered on both
back ends with values worked out by hand; fxc's rules for it (vkd3d's switch.shader_test,
checked against native d3dcompiler below shader model 4) refused with located errors.

The quad's texture coordinate runs 0..1 across the 8 x 8 target: at pixel x, u = x / 8, so
`(int)(uv.x * 4 + 0.25)` is x // 2 (0 0 1 1 2 2 3 3), a quarter away from the next integer
(a back end's u may be a rounding below x / 8).
"""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.base.errors import EffectError
from effects.program.backend import create_backend
from effects.shaders.hlsl import compile_shader

SIZE = (8, 8)
QUAD = {"mesh": "quad", "size": list(SIZE)}
TOL = 1.5 / 255


@pytest.fixture(scope="module", params=("numpy", "gl"))
def backend(request):
    made = create_backend(request.param)
    yield made
    made.close()


def effect_for(functions: str, params: str = "", target: str = "ps_2_0") -> effects.Effect:
    return effects.load_effect(f"{params}\n{functions}\n"
                               f"technique T {{ pass P {{ PixelShader = compile {target} PS(); }} }}\n")


def render(fx: effects.Effect, backend, params: dict | None = None) -> np.ndarray:
    return effects.render(fx, "radeon9700", technique="T", backend=backend, scene=QUAD,
                          params=params).astype(np.float64) / 255.0


BY_COLUMN = """
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float4 c = float4(0.1, 0.2, 0.3, 1);
    int k = (int)(uv.x * 4 + 0.25);
    switch (k)
    {
    case 0:
        c.r = 0.5;
        break;
    case 1:
    case 1 + 1:             // an empty case falls through; a case value folds
        c.g = 0.75;
        if (true) break;    // ends the case, as fxc folded it: the next line is not reached
        c = 9;
    default:
        c.b = 1;
        break;
    }
    return c;
}"""


def test_a_run_time_selector_picks_one_case_per_pixel(backend):
    fx = effect_for(BY_COLUMN)
    assert "cmp" in compile_shader(fx, "PS", "ps_2_0").text       # flattened into selects
    img = render(fx, backend)
    want = {0: (0.5, 0.2, 0.3, 1), 1: (0.1, 0.75, 0.3, 1), 2: (0.1, 0.75, 0.3, 1),
            3: (0.1, 0.2, 1.0, 1)}
    for x in range(8):
        assert np.allclose(img[4, x], want[x // 2], atol=TOL), (x, img[4, x])


def test_return_in_a_case_and_a_default_in_the_middle(backend):
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    switch ((int)(uv.x * 4 + 0.25))
    {
    case 3:
        return float4(0, 0, 1, 1);
    default:
    case 0:
        break;
    case 1:
        return float4(uv.x, 0, 0, 1);
    }
    return float4(0, 1, 0, 1);
}""")
    img = render(fx, backend)
    for x in range(8):
        k = x // 2
        want = (0, 0, 1, 1) if k == 3 else (x / 8, 0, 0, 1) if k == 1 else (0, 1, 0, 1)
        assert np.allclose(img[4, x], want, atol=TOL), (x, img[4, x])


@pytest.mark.parametrize("mode, want", [(0, (1, 0, 0, 1)), (1, (0, 1, 0, 1)),
                                         (2, (0, 1, 0, 1)), (7, (0, 0, 1, 1))])
def test_an_int_uniform_selector(backend, mode, want):
    fx = effect_for("""
float4 PS() : COLOR
{
    switch (Mode)
    {
    case 0: return float4(1, 0, 0, 1);
    case 1:
    case 2: return float4(0, 1, 0, 1);
    default: return float4(0, 0, 1, 1);
    }
}""", params="int Mode = 0;")
    img = render(fx, backend, {"Mode": mode})
    assert np.allclose(img[3, 3], want, atol=TOL)


def test_break_leaves_the_switch_not_the_loop_around_it(backend):
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float4 c = 0;
    for (int i = 0; i < 4; i++)
    {
        switch (i)
        {
        case 1:
            c.r += 0.25;
            break;
        case 2:
            c.g += uv.x;
            break;
        default:
            c.b += 0.125;
            break;
        }
    }
    return c;
}""")
    img = render(fx, backend)
    u = 5 / 8
    assert np.allclose(img[2, 5], (0.25, u, 0.25, 0), atol=TOL)    # i = 0 and 3 took default


def test_a_constant_selector_compiles_only_its_case():
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    switch (2)
    {
    case 1: return float4(uv, 0, 1);
    case 2: return float4(0.5, 0.25, 0, 1);
    default: return 0;
    }
}""")
    text = compile_shader(fx, "PS", "ps_2_0").text
    assert "cmp" not in text and "dcl t0" not in text and "0.5, 0.25, 0, 1" in text


# --- what fxc refused ----------------------------------------------------------------------------

NO_CODE = "(no X code: fxc's wording for this was not found)"


def refused(body: str, params: str = "") -> EffectError:
    fx = effect_for("float4 PS(float2 uv : TEXCOORD0) : COLOR\n{\n" + body + "\n}", params)
    with pytest.raises(EffectError) as info:
        compile_shader(fx, "PS", "ps_2_0")
    assert info.value.language, info.value
    return info.value


def where(err: EffectError) -> tuple[int, int, str]:
    """(line, column) of the error in `body`, with the message (the effect's first lines: the
    parameters' line, the function's signature and its brace)."""
    return err.line - 3, err.column, err.message


@pytest.mark.parametrize("body, line, column, message", [
    ("  float4 c = 0;\n  switch ((int)uv.x)\n  {\n  case 0:\n    c = 1;\n  case 1:\n    c = 2;\n"
     "    break;\n  }\n  return c;",
     4, 3, "X3533: non-empty case statements must have break or return"),
    ("  switch ((int)uv.x)\n  {\n  case 0:\n    discard;\n  case 1:\n    break;\n  }\n  return 0;",
     3, 3, "X3533: non-empty case statements must have break or return"),
    ("  switch ((int)uv.x)\n  {\n  case 2: return 1;\n  case 1 + 1: return 0;\n  }\n  return 0;",
     4, 3, f"duplicate case value 2 (first at line 6) {NO_CODE}"),
    ("  switch ((int)uv.x)\n  {\n  default: return 1;\n  case 1: return 0;\n  default: break;\n  }\n"
     "  return 0;",
     5, 3, f"a switch has one default label (the first is at line 6) {NO_CODE}"),
    ("  switch ((int)uv.x)\n  {\n  case 0: return 1;\n  case 1:\n  }\n  return 0;",
     4, 3, f"the last case of a switch has no statements; end it with break {NO_CODE}"),
    ("  switch ((int)uv.x)\n  {\n  }\n  return 0;",
     1, 3, f"a switch needs at least one case label {NO_CODE}"),
    ("  int a = 1;\n  switch ((int)uv.x)\n  {\n  case 1 + a: return 1;\n  }\n  return 0;",
     4, 8, f"a case value must be a literal expression {NO_CODE}"),
    ("  switch (uv.x)\n  {\n  case 0: return 1;\n  }\n  return 0;",
     1, 11, "X3020: a switch needs a scalar int or uint selector, not 'float'"),
    ("  float4 c = 0;\n  for (int i = 0; i < 2; i++)\n  {\n    switch (i)\n    {\n    case 0:\n"
     "      c += 0.1;\n      continue;\n      break;\n    default:\n      break;\n    }\n  }\n"
     "  return c;",
     8, 7, f"continue cannot be used in a switch {NO_CODE}"),
])
def test_what_fxc_refused_is_a_located_language_error(body, line, column, message):
    assert where(refused(body)) == (line, column, message)
