"""The NumPy evaluator: every op's kernel against values worked out by hand from the D3D
formulas, the D3D edge cases, sampling through callbacks, kill, and a per-pixel N.L program."""
import numpy as np
import pytest

from backends.reference.evaluate import evaluate
from effects.program.ir import FLT_MAX, Builder, IRError


def run_op(method, *rows, **attrs):
    """Apply Builder.<method> to varyings a, b, c holding `rows` (each a list of vec4 rows)."""
    b = Builder("fragment")
    names = "abc"[:len(rows)]
    args = [b.varying(n) for n in names]
    b.output("color0", getattr(b, method)(*args, **attrs))
    inputs = {n: np.array(r, dtype=np.float32) for n, r in zip(names, rows)}
    return evaluate(b.build(), inputs).outputs["color0"]


def close(actual, expected):
    np.testing.assert_allclose(actual, np.array(expected, dtype=np.float32), rtol=1e-6, atol=1e-7)


A = [[1, -2, 0.5, 4], [0, 3, -1, 0.25]]
B = [[2, 0.5, -4, 1], [-1, 1, 2, 8]]
C = [[0.25, 0.25, 0.25, 0.25], [-3, 0, 1, 2]]


def test_elementwise_arithmetic():
    close(run_op("add", A, B), [[3, -1.5, -3.5, 5], [-1, 4, 1, 8.25]])
    close(run_op("sub", A, B), [[-1, -2.5, 4.5, 3], [1, 2, -3, -7.75]])
    close(run_op("mul", A, B), [[2, -1, -2, 4], [0, 3, -2, 2]])
    close(run_op("mad", A, B, C), [[2.25, -0.75, -1.75, 4.25], [-3, 3, -1, 4]])
    close(run_op("min", A, B), [[1, -2, -4, 1], [-1, 1, -1, 0.25]])
    close(run_op("max", A, B), [[2, 0.5, 0.5, 4], [0, 3, 2, 8]])
    close(run_op("neg", A), [[-1, 2, -0.5, -4], [0, -3, 1, -0.25]])
    close(run_op("abs", A), [[1, 2, 0.5, 4], [0, 3, 1, 0.25]])
    close(run_op("frc", [[1.25, -0.25, 3.0, -2.5]]), [[0.25, 0.75, 0.0, 0.5]])


def test_dot_products_replicate_to_all_components():
    # dp3: 1*2 + (-2)(0.5) + 0.5(-4) = -1; 0*-1 + 3*1 + (-1)*2 = 1
    close(run_op("dp3", A, B), [[-1] * 4, [1] * 4])
    # dp4 adds w*w: -1 + 4*1 = 3; 1 + 0.25*8 = 3
    close(run_op("dp4", A, B), [[3] * 4, [3] * 4])


def test_reciprocals_and_logs_with_d3d_edge_cases():
    close(run_op("rcp", [[2, -4, 1, 0.5]]), [[0.5, -0.25, 1, 2]])
    # rcp of zero is +inf for either sign of zero (IEEE would give -inf for -0)
    assert np.all(run_op("rcp", [[0.0, -0.0, 0.0, 0.0]]) == np.inf)
    # rsq uses |x|: rsq(-4) = 1/2; rsq(0) = +inf
    out = run_op("rsq", [[4, -4, 0.25, 0]])
    close(out[:, :3], [[0.5, 0.5, 2]])
    assert out[0, 3] == np.inf
    close(run_op("exp2", [[0, 3, -1, 0.5]]), [[1, 8, 0.5, 2 ** 0.5]])
    # log2 of |x|; log2(0) = -inf
    out = run_op("log2", [[8, -0.25, 1, 0]])
    close(out[:, :3], [[3, -2, 0]])
    assert out[0, 3] == -np.inf


def test_pow_uses_absolute_base():
    # |-2|^3 = 8, 4^0.5 = 2, |-0.5|^-1 = 2, 0^2 = 0
    close(run_op("pow", [[-2, 4, -0.5, 0]], [[3, 0.5, -1, 2]]), [[8, 2, 2, 0]])


def test_cmp_cnd_lrp_and_set_ops_at_their_boundaries():
    sel = [[0.0, -0.0001, 0.5, 0.50001]]
    one, two = [[1, 1, 1, 1]], [[2, 2, 2, 2]]
    # cmp: a >= 0 picks b, so exactly 0 picks b
    close(run_op("cmp", sel, one, two), [[1, 2, 1, 1]])
    # cnd: a > 0.5 picks b, so exactly 0.5 picks c
    close(run_op("cnd", sel, one, two), [[2, 2, 2, 1]])
    # lrp f*a + (1-f)*b with f = 0.25: 0.25*4 + 0.75*8 = 7
    close(run_op("lrp", [[0.25, 0, 1, 0.5]], [[4, 4, 4, 4]], [[8, 8, 8, 8]]), [[7, 8, 4, 6]])
    close(run_op("slt", [[1, 2, 3, -1]], [[2, 2, 2, 2]]), [[1, 0, 0, 1]])
    close(run_op("sge", [[1, 2, 3, -1]], [[2, 2, 2, 2]]), [[0, 1, 1, 0]])


def test_nrm_scales_w_and_handles_zero_length():
    # |(3, 0, 4)| = 5, so each component (w too) is divided by 5
    close(run_op("nrm", [[3, 0, 4, 10]]), [[0.6, 0, 0.8, 2]])
    # zero xyz: the D3D reference multiplies by FLT_MAX, giving 0 for xyz and w * FLT_MAX
    out = run_op("nrm", [[0, 0, 0, 1e-38]])
    close(out[:, :3], [[0, 0, 0]])
    assert out[0, 3] == pytest.approx(1e-38 * FLT_MAX, rel=1e-5)


def test_crs_is_the_cross_product_of_xyz():
    close(run_op("crs", [[1, 0, 0, 7]], [[0, 1, 0, 9]]), [[0, 0, 1, 0]])
    # (1,2,3) x (4,5,6) = (2*6-3*5, 3*4-1*6, 1*5-2*4) = (-3, 6, -3)
    close(run_op("crs", [[1, 2, 3, 0]], [[4, 5, 6, 0]]), [[-3, 6, -3, 0]])


def test_swizzles_and_masked_merges():
    v = [[1, 2, 3, 4]]
    close(run_op("swizzle", v, pattern="wzyx"), [[4, 3, 2, 1]])
    close(run_op("swizzle", v, pattern="a"), [[4, 4, 4, 4]])      # replicate alpha
    close(run_op("swizzle", v, pattern="xy"), [[1, 2, 2, 2]])     # last component repeats
    close(run_op("swizzle", v, pattern="bgra"), [[3, 2, 1, 4]])   # rgba letters
    old, new = [[1, 2, 3, 4]], [[10, 20, 30, 40]]
    close(run_op("merge", old, new, mask="xz"), [[10, 2, 30, 4]])
    close(run_op("merge", old, new, mask="rgb"), [[10, 20, 30, 4]])
    close(run_op("merge", old, new, mask="w"), [[1, 2, 3, 40]])


def test_saturate_and_clamp():
    close(run_op("saturate", [[-0.5, 0.25, 1.5, 1.0]]), [[0, 0.25, 1, 1]])
    close(run_op("clamp", [[-9, -0.5, 3, 8.5]], lo=-8, hi=8), [[-8, -0.5, 3, 8]])


def test_quantize_unsigned_8_bit_rounds_half_up():
    # round(0.5 * 255) = round(127.5) = 128, so 0.5 reads back as 128/255 = 0.50196
    # 0.2 * 255 = 51 exactly; 1.5 and -0.25 clamp to the [0, 1] range first
    out = run_op("quantize", [[0.5, 0.2, 1.5, -0.25]], bits=8)
    close(out, [[128 / 255, 51 / 255, 1, 0]])
    assert out[0, 0] == pytest.approx(0.50196, abs=1e-5)
    # 1/600 * 255 = 0.425 rounds down to 0; 1/400 * 255 = 0.6375 rounds up to 1/255
    close(run_op("quantize", [[1 / 600, 1 / 400, 0, 0]], bits=8), [[0, 1 / 255, 0, 0]])


def test_quantize_signed_9_bit_geforce3_grid():
    # 9-bit signed: 255 steps per unit over [-1, 1]; halves round away from zero
    # -0.5 * 255 = -127.5 -> -128; -0.75 * 255 = -191.25 -> -191; 2 -> 1; -3 -> -1
    close(run_op("quantize", [[-0.5, -0.75, 2, -3]], bits=9, signed=True),
          [[-128 / 255, -191 / 255, 1, -1]])


def test_quantize_scaled_range():
    # signed 4 bits = 7 steps over [-8, 8]: steps of 8/7; 3 -> 3 * 7/8 = 2.625 -> 3 steps
    close(run_op("quantize", [[3, -9, 0.5, 8]], bits=4, signed=True, scale=8),
          [[24 / 7, -8, 0, 8]])


# --------------------------------------------------------------------------------------------
# Inputs, samplers, kill


def test_short_inputs_pad_with_0001_and_uniforms_broadcast():
    b = Builder("fragment")
    t = b.varying("texcoord0", components=2)
    u = b.uniform("tint")
    b.output("color0", b.add(t, u))
    out = evaluate(b.build(), {"texcoord0": np.array([[0.25, 0.5], [1, 2]]),
                               "tint": np.array([1, 1, 1, 1])}).outputs["color0"]
    close(out, [[1.25, 1.5, 1, 2], [2, 3, 1, 2]])


def test_missing_input_and_mismatched_rows_are_reported():
    b = Builder("fragment")
    b.output("color0", b.add(b.varying("a"), b.varying("b")))
    program = b.build()
    with pytest.raises(IRError, match="missing inputs: b"):
        evaluate(program, {"a": np.zeros((2, 4))})
    with pytest.raises(IRError, match="disagree"):
        evaluate(program, {"a": np.zeros((2, 4)), "b": np.zeros((3, 4))})


def test_sampler_receives_projected_coords_and_bias():
    seen = {}

    def fake(coord, kind, bias, lod):
        seen.update(coord=coord.copy(), kind=kind, bias=bias, lod=lod)
        return np.tile([0.5, 0.25, 1, 1], (len(coord), 1)).astype(np.float32)

    b = Builder("fragment")
    c = b.varying("texcoord0")
    b.output("color0", b.sample(3, c, kind="3d", proj=True))
    out = evaluate(b.build(), {"texcoord0": np.array([[2, 4, 6, 2]])}, {3: fake})
    close(seen["coord"], [[1, 2, 3, 1]])
    assert seen["kind"] == "3d" and seen["bias"] is None and seen["lod"] is None
    close(out.outputs["color0"], [[0.5, 0.25, 1, 1]])

    b = Builder("fragment")
    b.output("color0", b.sample(0, b.varying("texcoord0"), bias=True))
    evaluate(b.build(), {"texcoord0": np.array([[0.5, 0.5, 0, -1.5]])}, {0: fake})
    close(seen["coord"], [[0.5, 0.5, 0, -1.5]])
    close(seen["bias"], [-1.5])


def test_unbound_sampler_reads_0001():
    b = Builder("fragment")
    b.output("color0", b.sample(1, b.varying("texcoord0"), kind="cube"))
    out = evaluate(b.build(), {"texcoord0": np.ones((2, 4))}).outputs["color0"]
    close(out, [[0, 0, 0, 1], [0, 0, 0, 1]])


def test_kill_masks_fragments_with_any_tested_component_negative():
    coords = np.array([[0.1, 0.2, 0.3, -1],    # only w negative
                       [0.1, -0.2, 0.3, 1],     # y negative
                       [0, 0, 0, 0],            # zero is not negative
                       [-0.0, 0.5, 0.5, 0.5]])  # -0 is not negative
    for components, expected in (("xyz", [False, True, False, False]),
                                 ("xyzw", [True, True, False, False])):
        b = Builder("fragment")
        t = b.varying("texcoord0")
        b.kill(t, components)
        b.output("color0", b.const(1))
        result = evaluate(b.build(), {"texcoord0": coords})
        assert result.killed.tolist() == expected


def test_two_kills_combine_and_programs_without_kill_report_none():
    b = Builder("fragment")
    t = b.varying("texcoord0")
    b.kill(b.swizzle(t, "xxxx"))
    b.kill(b.swizzle(t, "yyyy"))
    b.output("color0", t)
    coords = np.array([[-1, 1, 0, 0], [1, -1, 0, 0], [1, 1, 0, 0]])
    assert evaluate(b.build(), {"texcoord0": coords}).killed.tolist() == [True, True, False]
    b = Builder("fragment")
    b.output("color0", b.varying("texcoord0"))
    assert evaluate(b.build(), {"texcoord0": coords}).killed is None


def test_per_pixel_n_dot_l_end_to_end():
    """color = saturate(dot(2*normalmap - 1, L)) * diffuse, alpha from diffuse: the classic
    ps.1.1 `tex t0; dp3_sat r0, t0_bx2, v0_bx2`-style look, in IR."""
    texels = np.array([[0.5, 0.5, 1.0, 1.0],     # normal (0, 0, 1)
                       [1.0, 0.5, 0.5, 1.0],     # normal (1, 0, 0)
                       [0.5, 0.0, 0.5, 1.0]],    # normal (0, -1, 0)
                      dtype=np.float32)

    def normal_map(coord, kind, bias, lod):
        # a 3x1 texture addressed by u in thirds
        return texels[np.clip((coord[:, 0] * 3).astype(int), 0, 2)]

    b = Builder("fragment")
    uv = b.varying("texcoord0", "TEXCOORD0", 2)
    diffuse = b.varying("color0", "COLOR0")
    light = b.uniform("LightDir")
    n = b.mad(b.sample(0, uv), b.const(2), b.const(-1))
    lit = b.mul(b.saturate(b.dp3(n, light)), diffuse)
    b.output("color0", b.merge(lit, diffuse, "w"))
    program = b.build()

    l = np.array([0.6, 0.0, 0.8, 0.0])
    diffuse_rows = np.array([[1, 1, 1, 0.5], [1, 0.5, 0.25, 1], [1, 1, 1, 1]])
    out = evaluate(program, {"texcoord0": np.array([[0.1, 0], [0.5, 0], [0.9, 0]]),
                             "color0": diffuse_rows, "LightDir": l},
                   {0: normal_map}).outputs["color0"]
    # N.L: (0,0,1).L = 0.8; (1,0,0).L = 0.6; (0,-1,0).L = 0 -> 0
    close(out, [[0.8, 0.8, 0.8, 0.5], [0.6, 0.3, 0.15, 1], [0, 0, 0, 1]])


def test_vertex_program_transforms_positions_with_dp4_rows():
    # position = (dp4(p, r0), dp4(p, r1), dp4(p, r2), dp4(p, r3)) with a scale-and-translate
    b = Builder("vertex")
    p = b.varying("position", "POSITION", 3)
    rows = [b.dp4(p, b.uniform(f"c{i}")) for i in range(4)]
    pos = b.merge(b.merge(b.merge(rows[0], rows[1], "y"), rows[2], "z"), rows[3], "w")
    b.output("position", pos)
    program = b.build()
    matrix = {"c0": [2, 0, 0, 1], "c1": [0, 2, 0, 0], "c2": [0, 0, 1, 0], "c3": [0, 0, 0, 1]}
    out = evaluate(program, {"position": np.array([[1, 2, 3], [0, 0, 0]]),
                             **{k: np.array(v) for k, v in matrix.items()}})
    close(out.outputs["position"], [[3, 4, 3, 1], [1, 0, 0, 1]])
    assert out.killed is None


def test_evaluation_stays_float32_and_vectorised_over_many_rows():
    b = Builder("fragment")
    x = b.varying("a")
    b.output("color0", b.mad(x, x, b.const(0.5)))
    rows = np.random.default_rng(1).random((10000, 4), dtype=np.float32)
    out = evaluate(b.build(), {"a": rows}).outputs["color0"]
    assert out.dtype == np.float32 and out.shape == (10000, 4)
    close(out, rows * rows + np.float32(0.5))


def _matrix_rows_program():
    """m4x4 / m3x3 as lowered: dp4 / dp3 of one vector with uniform rows, merged."""
    b = Builder("vertex")
    p = b.varying("position")
    rows = [b.uniform(f"c{i}") for i in range(4)]
    d4 = [b.dp4(p, r) for r in rows]
    out = d4[0]
    for i, mask in ((1, "y"), (2, "z"), (3, "w")):
        out = b.merge(out, d4[i], mask)
    b.output("position", out)
    d3 = [b.dp3(p, r) for r in rows[:3]]
    t = b.merge(d3[0], d3[1], "y")
    b.output("texcoord0", b.merge(t, d3[2], "z"))
    return b.build()


def test_dot_rows_of_uniforms_are_one_batch_and_equal_each_dot_on_its_own():
    """dp3/dp4 of one vector with several uniforms run as one batch (effects.program.ir OpInfo.batch):
    bit for bit the per-instruction dots (x*a + y*b) + z*c (+ w*d) in float32, and the same
    when a 'uniform' comes per row (the batch declines and each dot runs alone)."""
    from backends.reference.evaluate import _BATCH, _steps
    program = _matrix_rows_program()
    assert [len(s[1]) for s in _steps(program, frozenset()).steps if s[0] == _BATCH] == [4, 3]
    rng = np.random.default_rng(5)
    pos = rng.normal(size=(37, 4)).astype(np.float32)
    mat = rng.normal(size=(4, 4)).astype(np.float32)
    f = np.float32
    want4 = ((pos[:, :1] * mat[:, 0] + pos[:, 1:2] * mat[:, 1]) + pos[:, 2:3] * mat[:, 2]) \
        + pos[:, 3:4] * mat[:, 3]
    want3 = (pos[:, :1] * mat[:3, 0] + pos[:, 1:2] * mat[:3, 1]) + pos[:, 2:3] * mat[:3, 2]
    assert want4.dtype == f
    uniform = {f"c{i}": mat[i] for i in range(4)}
    per_row = {f"c{i}": np.repeat(mat[i][None], len(pos), axis=0) for i in range(4)}
    for given in (uniform, per_row):
        out = evaluate(program, {"position": pos, **given}).outputs
        assert out["position"].tobytes() == want4.tobytes()
        assert out["texcoord0"][:, :3].tobytes() == np.ascontiguousarray(want3).tobytes()
