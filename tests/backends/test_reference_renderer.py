"""What only the NumPy reference back end has: threaded chunks that give the single-threaded
image, and fast paths in its sampler and evaluator (trilinear rows at many levels at once,
row-major kernel results, dense uniforms, replicated scalar ops on one column) that must
give the plain formulas' values. The pixel rules themselves are tested on both back ends in
test_backends_suite.py."""
import math

import numpy as np
import pytest

from effects.program.backend import create_backend
from backends.reference.evaluate import _dense, evaluate
from backends.reference.sampler import SamplerSettings, sample_2d
from effects.program.ir import OPS, Builder
from effects.program.passprogram import PassProgram, RenderState, TextureBinding
from effects.program.texture import Texture


@pytest.mark.parametrize("band_pixels", [1 << 30, 1 << 10, 200])
def test_bands_and_threads_give_the_same_image(monkeypatch, band_pixels):
    # Bands of rows (one, 16, many of two rows each) on one thread and on two, against the
    # whole frame as one band: overlapping triangles so the in-order merge matters (blending is
    # order dependent), a texture with helper pixels, and an odd height for a short last band.
    from backends.reference import renderer
    rng = np.random.default_rng(11)
    count = 3000
    centre = rng.uniform(-1, 1, (count, 2))
    offsets = rng.uniform(-0.15, 0.15, (count, 3, 2))
    xy = (centre[:, None, :] + offsets).reshape(-1, 2)
    pos = np.column_stack([xy, rng.uniform(0.1, 0.9, len(xy)), np.ones(len(xy))]).astype(
        np.float32)
    uv = rng.uniform(0, 1, (len(xy), 2)).astype(np.float32)
    b = Builder("fragment")
    texel = b.sample(0, b.varying("texcoord0"))
    b.output("color0", b.mul(texel, b.const((0.6, 0.6, 0.6, 0.5))))
    state = RenderState(cull_mode="NONE", alpha_blend_enable=True, src_blend="SRCALPHA",
                        dest_blend="INVSRCALPHA", z_enable=False)
    program = PassProgram(b.build(), render_state=state, textures=(
        TextureBinding(0, "tex", min_filter="LINEAR", mag_filter="LINEAR", mip_filter="LINEAR"),))
    levels = [np.random.default_rng(n).uniform(0, 1, (16 >> n, 16 >> n, 4)).astype(np.float32)
              for n in range(5)]
    textures = {"tex": Texture("2d", "A32B32G32R32F", levels)}
    images = []
    for threads, band in ((1, 1 << 30), (1, band_pixels), (2, band_pixels)):
        monkeypatch.setattr(renderer, "BAND_PIXELS", band)
        backend = create_backend("numpy", threads=threads)
        backend.begin_frame((64, 61))
        backend.draw(program, {"position": pos, "texcoord0": uv}, np.arange(len(xy)), "list",
                     textures)
        images.append(backend.end_frame())
    assert len(renderer.band_rows((64, 61), 1)) == {1 << 30: 1, 1 << 10: 4, 200: 16}[band_pixels]
    np.testing.assert_array_equal(images[0], images[1])
    np.testing.assert_array_equal(images[0], images[2])
    assert len(np.unique(images[0][..., 0])) > 50


def test_band_rows_cover_the_frame_in_even_steps():
    from backends.reference.renderer import band_rows
    for size, threads in (((64, 64), 1), ((64, 64), 2), ((2048, 2048), 2), ((7, 3), 2), ((1, 1), 4)):
        bands = band_rows(size, threads)
        assert bands[0][0] == 0 and bands[-1][1] == size[1]
        assert all(a[1] == b[0] for a, b in zip(bands, bands[1:]))
        assert all(y0 % 2 == 0 for y0, _ in bands)
    # two threads share a frame from two bands of 32k pixels (256x256); a smaller frame is one
    assert len(band_rows((128, 128), 2)) == 1 and len(band_rows((180, 180), 2)) == 1
    assert len(band_rows((256, 256), 2)) == 2 and len(band_rows((256, 256), 1)) == 1
    assert max(y1 - y0 for y0, y1 in band_rows((2048, 2048), 2)) * 2048 <= 1 << 16


# --------------------------------------------------------------------------------------------
# Fast paths, same values


def _bilinear_by_hand(level: np.ndarray, u: float, v: float, mode: str) -> np.ndarray:
    """One bilinear lookup written out from the sampler's conventions (texel i covers
    [i/N, (i+1)/N); the four texels around (u N - 1/2, v N - 1/2))."""
    h, w = level.shape[:2]

    def fold(i, n):
        if mode == "WRAP":
            return i % n, True
        if mode == "MIRROR":
            p = i % (2 * n)
            return (p if p < n else 2 * n - 1 - p), True
        if mode == "BORDER":
            return min(max(i, 0), n - 1), 0 <= i < n
        return min(max(i, 0), n - 1), True          # CLAMP

    x, y = u * w - 0.5, v * h - 0.5
    x0, y0 = math.floor(x), math.floor(y)
    fx, fy = x - x0, y - y0
    total = np.zeros(4)
    for dy, wy in ((0, 1 - fy), (1, fy)):
        for dx, wx in ((0, 1 - fx), (1, fx)):
            (i, in_x), (j, in_y) = fold(x0 + dx, w), fold(y0 + dy, h)
            texel = level[j, i] if in_x and in_y else np.full(4, 0.25)
            total += wx * wy * texel
    return total


@pytest.mark.parametrize("mode", ["WRAP", "CLAMP", "MIRROR", "BORDER"])
def test_trilinear_rows_at_many_levels_match_the_formula(mode):
    """Quads at different LODs (levels 0..3 and between) in one call: each row is the blend
    of two bilinear lookups at floor(LOD) and the next level, as written out by hand."""
    rng = np.random.default_rng(5)
    levels = [rng.uniform(0, 1, (16 >> k, 16 >> k, 4)).astype(np.float32) for k in range(5)]
    quads = 200
    centre = rng.uniform(-0.5, 1.5, (quads, 2))
    step = 2.0 ** rng.uniform(-5, -1, quads) # texels per pixel from 1/2 to 8 on level 0
    offsets = np.array([[0, 0], [1, 0], [0, 1], [1, 1]], np.float64)
    uv = (centre[:, None, :] + offsets[None] * step[:, None, None]).reshape(-1, 2)
    uv = uv.astype(np.float32)
    settings = SamplerSettings(address_u=mode, address_v=mode, border=(0.25,) * 4,
                               min_filter="LINEAR", mag_filter="LINEAR", mip_filter="LINEAR")
    got = sample_2d(levels, uv, settings)
    for q in range(quads):
        lod = max(math.log2(float(step[q]) * 16), 0.0)
        lod = min(lod, 4.0)
        k = min(int(math.floor(lod)), 4)
        frac = lod - k
        for p in range(4):
            row = 4 * q + p
            u, v = float(uv[row, 0]), float(uv[row, 1])
            a = _bilinear_by_hand(levels[k], u, v, mode)
            if frac > 0:
                a = a + (_bilinear_by_hand(levels[k + 1], u, v, mode) - a) * frac
            np.testing.assert_allclose(got[row], a, atol=2e-5, err_msg=f"quad {q}, lod {lod}")


def test_swizzles_and_replicated_results_are_row_major():
    """Kernel results are C-ordered (N, 4): NumPy arithmetic mixing orders is several times
    slower, which is why swizzle must not return a fancy-indexed (column-major) array."""
    a = np.arange(40, dtype=np.float32).reshape(10, 4)
    for pattern in ("xxxx", "yzxw", "wwzz"):
        out = OPS["swizzle"].kernel(None, [a], {"pattern": pattern})
        assert out.flags.c_contiguous
        np.testing.assert_array_equal(out, a[:, ["xyzw".index(c) for c in pattern]])
    dp3 = OPS["dp3"].kernel(None, [a, a], {})
    assert dp3.flags.c_contiguous
    np.testing.assert_array_equal(dp3[:, 2], (a[:, :3] ** 2).sum(axis=1))


def test_uniform_operands_are_expanded_to_dense_rows():
    u = np.array([1, 2, 3, 4], np.float32)
    view = np.broadcast_to(u, (6, 4))
    dense = _dense(view)
    assert dense.flags.c_contiguous and dense.strides[0] != 0
    np.testing.assert_array_equal(dense, view)
    column = np.broadcast_to(np.arange(6, dtype=np.float32)[:, None], (6, 4))
    np.testing.assert_array_equal(_dense(column), column)
    assert _dense(column).flags.c_contiguous


def test_replicated_scalar_ops_run_on_one_column_with_the_same_values():
    """pow(dp3, c.xxxx) is replicated: the evaluator computes it once per row; the values are
    those of the per-component formula, and a non-replicated pow is left alone."""
    b = Builder("fragment")
    t = b.varying("texcoord0")
    ndl = b.dp3(t, t)
    replicated = b.pow(b.saturate(ndl), b.swizzle(b.uniform("k"), "xxxx"))
    mixed = b.pow(b.abs(t), b.const(3.0))
    b.output("color0", b.add(replicated, mixed))
    program = b.build()
    rng = np.random.default_rng(3)
    coords = rng.uniform(-1, 1, (64, 4)).astype(np.float32)
    k = np.array([5.0, 1.0, 2.0, 3.0], np.float32)
    out = evaluate(program, {"texcoord0": coords, "k": k}).outputs["color0"]
    d = np.clip((coords[:, :3] ** 2).sum(axis=1), 0, 1)
    expected = d[:, None] ** 5.0 + np.abs(coords) ** 3.0
    np.testing.assert_allclose(out, expected, rtol=2e-6)
