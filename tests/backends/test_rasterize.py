"""The rasteriser: coverage (fill rule, shared edges, viewport), clipping, culling, depth and
perspective-correct interpolation, against values worked out by hand from D3D9's rules
(pixel (px, py) is sampled at exactly (px, py); NDC x = 2 px / W - 1, y = 1 - 2 py / H)."""
import numpy as np
import pytest

from effects.program.backend import DrawError, triangle_list
from backends.reference.rasterize import rasterize


def hits(frags, size):
    """How many covered fragments landed on each pixel."""
    w, h = size
    count = np.zeros((h, w), int)
    np.add.at(count, (frags.y[frags.covered], frags.x[frags.covered]), 1)
    return count


def clip_xy(points, z=0.5, w=1.0):
    """Clip-space rows (x*w, y*w, z*w, w) for NDC points (x, y)."""
    p = np.asarray(points, float)
    return np.column_stack([p[:, 0] * w, p[:, 1] * w, np.full(len(p), z * w), np.full(len(p), w)])


def pixel_to_ndc(px, py, size):
    w, h = size
    return 2 * px / w - 1, 1 - 2 * py / h


def ndc_to_pixel(x, y, size):
    w, h = size
    return (x + 1) * w / 2, (1 - y) * h / 2


QUAD = clip_xy([(-1, -1), (-1, 1), (1, 1), (1, -1)])     # bottom-left, top-left, top-right, ...
QUAD_TRIS = np.array([[0, 1, 2], [0, 2, 3]])            # both clockwise on screen


@pytest.mark.parametrize("size", [(8, 8), (7, 5), (1, 1), (33, 17)])
def test_full_screen_quad_covers_every_pixel_once(size):
    frags = rasterize(QUAD, {}, QUAD_TRIS, size)
    assert (hits(frags, size) == 1).all()


def test_quads_come_whole_with_helpers_and_pixel_mode_only_covered():
    # Triangle covering only pixel (1, 1)'s neighbourhood: quads include helper pixels.
    size = (8, 8)
    tri = clip_xy([pixel_to_ndc(*p, size) for p in [(0.5, 0.5), (2.5, 0.5), (0.5, 2.5)]])
    frags = rasterize(tri, {}, [[0, 1, 2]], size)
    assert frags.count % 4 == 0
    quads = np.stack([frags.x, frags.y], 1).reshape(-1, 4, 2)
    # each quad is (x0, y0), (x0+1, y0), (x0, y0+1), (x0+1, y0+1) with even x0, y0
    assert (quads[:, 0] % 2 == 0).all()
    np.testing.assert_array_equal(quads - quads[:, :1], np.broadcast_to(
        [[0, 0], [1, 0], [0, 1], [1, 1]], quads.shape))
    covered = {(int(x), int(y)) for x, y in zip(frags.x[frags.covered], frags.y[frags.covered])}
    # pixel centres strictly inside x + y < 3 from (0.5, 0.5): (1,1) (2,1)? 2+1=3 on the edge
    assert covered == {(1, 1)}
    pixels = rasterize(tri, {}, [[0, 1, 2]], size, quads=False)
    assert pixels.count == 1 and pixels.covered.all() and (pixels.x[0], pixels.y[0]) == (1, 1)


def test_top_left_rule_on_edges_through_pixel_centres():
    # Rectangle spanning pixels [0, 4] x [0, 4] exactly (edges through pixel centres): the
    # left and top edges own their pixels, the right and bottom ones do not -> 4 x 4 pixels.
    size = (8, 8)
    corners = [pixel_to_ndc(x, y, size) for x, y in [(0, 4), (0, 0), (4, 0), (4, 4)]]
    frags = rasterize(clip_xy(corners), {}, QUAD_TRIS, size)
    expected = np.zeros((8, 8), int)
    expected[0:4, 0:4] = 1
    np.testing.assert_array_equal(hits(frags, size), expected)
    # The neighbour to the right, [4, 8] x [0, 4], takes column 4 (its left edge).
    corners = [pixel_to_ndc(x, y, size) for x, y in [(4, 4), (4, 0), (8, 0), (8, 4)]]
    right = hits(rasterize(clip_xy(corners), {}, QUAD_TRIS, size), size)
    assert right[0:4, 4:8].sum() == 16 and right.sum() == 16


def test_triangle_fan_with_shared_edges_hits_every_pixel_once():
    size = (37, 29)
    centre = (0.137, -0.271)
    rim = []
    for t in np.linspace(0, 1, 9)[:-1]:          # points around the square [-1, 1]^2
        rim += [(-1 + 2 * t, 1)]
    for t in np.linspace(0, 1, 9)[:-1]:
        rim += [(1, 1 - 2 * t)]
    for t in np.linspace(0, 1, 9)[:-1]:
        rim += [(1 - 2 * t, -1)]
    for t in np.linspace(0, 1, 9)[:-1]:
        rim += [(-1, -1 + 2 * t)]
    pts = clip_xy([centre] + rim)
    n = len(rim)
    tris = np.array([[0, 1 + i, 1 + (i + 1) % n] for i in range(n)])
    frags = rasterize(pts, {}, tris, size, cull="NONE")
    assert (hits(frags, size) == 1).all()


def jittered_grid(cells, seed=1, span=1.0):
    rng = np.random.default_rng(seed)
    g = np.linspace(-span, span, cells + 1)
    x, y = np.meshgrid(g, g)
    jitter = rng.uniform(-0.35, 0.35, (2,) + x.shape) * (2 * span / cells)
    interior = np.zeros_like(x, bool)
    interior[1:-1, 1:-1] = True
    x = np.where(interior, x + jitter[0], x)
    y = np.where(interior, y + jitter[1], y)
    pts = np.column_stack([x.ravel(), y.ravel()])
    i = (np.arange(cells)[:, None] * (cells + 1) + np.arange(cells)).ravel()
    # rows of the grid go up in y; (i, i+cells+1, i+1) is clockwise on screen
    tris = np.concatenate([np.stack([i, i + cells + 1, i + 1], 1),
                           np.stack([i + 1, i + cells + 1, i + cells + 2], 1)])
    return pts, tris


@pytest.mark.parametrize("size", [(64, 48), (50, 50)])
def test_jittered_mesh_grid_hits_every_pixel_once(size):
    pts, tris = jittered_grid(13)
    frags = rasterize(clip_xy(pts), {}, tris, size)
    assert len(np.unique(frags.prim)) > 300  # nearly every triangle drew something
    assert (hits(frags, size) == 1).all()


def test_grid_extending_past_the_viewport_still_hits_once():
    size = (40, 30)
    pts, tris = jittered_grid(9, seed=5, span=1.7)
    frags = rasterize(clip_xy(pts), {}, tris, size)
    assert (hits(frags, size) == 1).all()


def test_fragments_come_in_draw_order():
    pts, tris = jittered_grid(6)
    frags = rasterize(clip_xy(pts), {}, tris, (32, 32))
    assert (np.diff(frags.prim) >= 0).all()


def test_cull_modes():
    size = (8, 8)
    cw = [[0, 1, 2]]            # bottom-left, top-left, top-right: clockwise on screen
    ccw = [[0, 2, 1]]
    assert rasterize(QUAD, {}, cw, size, cull="CCW").covered.any()
    assert not rasterize(QUAD, {}, ccw, size, cull="CCW").covered.any()
    assert rasterize(QUAD, {}, ccw, size, cull="CW").covered.any()
    assert not rasterize(QUAD, {}, cw, size, cull="CW").covered.any()
    a = rasterize(QUAD, {}, cw, size, cull="NONE")
    b = rasterize(QUAD, {}, ccw, size, cull="NONE")
    assert a.front.all() and not b.front.any()
    np.testing.assert_array_equal(hits(a, size), hits(b, size))
    with pytest.raises(ValueError):
        rasterize(QUAD, {}, cw, size, cull="BACK")


def test_strip_triangles_keep_the_first_winding():
    # Strip v0..v3 = bottom-left, top-left, bottom-right, top-right: (0,1,2) is clockwise and
    # the second, (1,3,2) in D3D order, is clockwise too.
    pts = clip_xy([(-1, -1), (-1, 1), (1, -1), (1, 1)])
    tris = triangle_list(np.arange(4), "strip")
    np.testing.assert_array_equal(tris, [[0, 1, 2], [1, 3, 2]])
    frags = rasterize(pts, {}, tris, (6, 6), cull="CCW")
    assert (hits(frags, (6, 6)) == 1).all()


def test_triangle_list_errors_and_fan():
    with pytest.raises(DrawError):
        triangle_list(np.arange(4), "list")
    with pytest.raises(DrawError):
        triangle_list(np.arange(3), "points")
    np.testing.assert_array_equal(triangle_list(np.arange(5), "fan"), [[1, 2, 0], [2, 3, 0],
                                                                        [3, 4, 0]])
    np.testing.assert_array_equal(triangle_list(np.array([[0, 1, 2]]), "list"), [[0, 1, 2]])


def test_pixel_centres_and_linear_interpolation_on_a_flat_quad():
    size = (8, 4)
    uv = np.array([[0, 1], [0, 0], [1, 0], [1, 1]], np.float32)  # u right, v down
    frags = rasterize(QUAD, {"uv": uv}, QUAD_TRIS, size, quads=False)
    # D3D9 samples pixel (px, py) at (px, py): u = px / W, v = py / H
    np.testing.assert_allclose(frags.varyings["uv"][:, 0], frags.x / 8, atol=1e-6)
    np.testing.assert_allclose(frags.varyings["uv"][:, 1], frags.y / 4, atol=1e-6)
    np.testing.assert_allclose(frags.depth, 0.5, atol=1e-7)


def test_perspective_correct_interpolation_on_a_tilted_quad():
    # Left edge at w = 1, right edge at w = 4 (the quad recedes to the right). u = 0 on the
    # left, 1 on the right. A pixel at NDC x lies at parameter t where
    # x = ((1-t) x0 w0 + t x1 w1) / ((1-t) w0 + t w1), with x0 = -1, x1 = 1, w0 = 1, w1 = 4:
    # x (1 + 3t) = -1 + 5t  ->  t = (x + 1) / (5 - 3x); u = t exactly.
    w0, w1 = 1.0, 4.0
    pos = np.array([[-w0, -w0, 0.0, w0], [-w0, w0, 0.0, w0], [w1, w1, 3.0, w1], [w1, -w1, 3.0, w1]])
    u = np.array([[0], [0], [1], [1]], np.float32)
    size = (40, 40)
    frags = rasterize(pos, {"u": u}, QUAD_TRIS, size, quads=False)
    x, _ = pixel_to_ndc(frags.x, frags.y, size)
    t = (x + 1) / (5 - 3 * x)
    np.testing.assert_allclose(frags.varyings["u"][:, 0], t, atol=2e-6)
    # depth z/w is linear in screen space: z/w = 0 on the left, 3/4 on the right
    np.testing.assert_allclose(frags.depth, 0.75 * (x + 1) / 2, atol=1e-6)
    # and a screen-linear interpolation would be visibly different
    assert np.abs(frags.varyings["u"][:, 0] - (x + 1) / 2).max() > 0.2


def test_near_plane_clipping_cuts_at_z_zero():
    # A big triangle over the whole screen with z = x (w = 1): the part with x < 0 lies in
    # front of the near plane. Clipped, it covers exactly the pixels with NDC x >= 0, i.e.
    # px >= W/2 (the clipped edge passes through pixel centres of column W/2, a left edge).
    size = (16, 10)
    pts = np.array([[-1, -1], [-1, 3], [3, -1]], float)
    pos = np.column_stack([pts, pts[:, 0], np.ones(3)])
    frags = rasterize(pos, {"z": pos[:, 2:3].astype(np.float32)}, [[0, 1, 2]], size)
    expected = np.zeros((10, 16), int)
    expected[:, 8:] = 1
    np.testing.assert_array_equal(hits(frags, size), expected)
    covered_z = frags.varyings["z"][frags.covered, 0]
    assert covered_z.min() >= 0
    np.testing.assert_allclose(frags.depth[frags.covered], covered_z, atol=1e-6)


def test_far_plane_clipping_and_vertex_behind_the_eye():
    size = (16, 16)
    # z > w on the right half: dropped beyond the far plane (NDC x > 0 -> z/w > 1)
    pts = np.array([[-1, -1], [-1, 3], [3, -1]], float)
    pos = np.column_stack([pts, 1 + pts[:, 0], np.ones(3)])
    expected = np.zeros((16, 16), int)
    expected[:, :9] = 1            # x <= 0 kept: columns 0..8 (column 8 is x = 0, z/w = 1)
    got = hits(rasterize(pos, {}, [[0, 1, 2]], size), size)
    # column 8 is on the clipped (right) edge, which the top-left rule excludes
    expected[:, 8] = 0
    np.testing.assert_array_equal(got, expected)
    # A vertex behind the eye (w < 0, z < 0) is clipped away instead of wrapping around.
    behind = np.array([[0.0, 0.5, 0.5, 1.0], [-0.5, -0.5, 0.5, 1.0], [0.5, -0.5, -2.0, -1.0]])
    frags = rasterize(behind, {}, [[0, 1, 2]], size, cull="NONE")
    assert frags.covered.sum() > 0
    assert (frags.depth[frags.covered] >= 0).all()


def test_huge_coordinates_stay_exact_through_the_guard_band():
    # A triangle far larger than the screen (1e6 NDC units) still covers each pixel once
    # together with its partner.
    size = (12, 12)
    big = clip_xy([(-1e6, -1e6), (-1e6, 1e6), (1e6, 1e6), (1e6, -1e6)])
    frags = rasterize(big, {}, QUAD_TRIS, size)
    assert (hits(frags, size) == 1).all()


def test_flat_shading_takes_the_first_vertex():
    colours = np.array([[1, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 1], [1, 1, 1, 1]], np.float32)
    frags = rasterize(QUAD, {"color0": colours}, QUAD_TRIS, (8, 8), flat=("color0",),
                      quads=False)
    # both triangles start at vertex 0 (red)
    np.testing.assert_array_equal(frags.varyings["color0"], np.tile([1, 0, 0, 1], (64, 1)))


def test_depth_bias_and_slope_scale():
    size = (8, 8)
    pos = QUAD.copy()
    pos[:, 2] = [0.2, 0.2, 0.6, 0.6]   # z/w = 0.2 on the left, 0.6 on the right
    plain = rasterize(pos, {}, QUAD_TRIS, size, quads=False)
    biased = rasterize(pos, {}, QUAD_TRIS, size, quads=False, depth_bias=0.01,
                       slope_scale_depth_bias=2.0)
    # slope dz/dx = 0.4 / 8 pixels = 0.05 per pixel, dz/dy = 0
    np.testing.assert_allclose(biased.depth - plain.depth, 0.01 + 2.0 * 0.05, atol=1e-6)
    np.testing.assert_allclose(plain.depth, 0.2 + 0.4 * plain.x / 8, atol=1e-6)


def test_degenerate_and_offscreen_triangles_draw_nothing():
    size = (8, 8)
    line = clip_xy([(-1, -1), (0, 0), (1, 1)])
    assert rasterize(line, {}, [[0, 1, 2]], size, cull="NONE").count == 0
    away = clip_xy([(2, 2), (2, 3), (3, 3)])
    assert rasterize(away, {}, [[0, 1, 2]], size, cull="NONE").count == 0
    assert rasterize(QUAD, {"c": np.ones((4, 2), np.float32)}, np.zeros((0, 3), int),
                     size).varyings["c"].shape == (0, 2)


@pytest.mark.parametrize("cells", [4, 8])
def test_regular_grid_with_edges_through_pixel_centres_hits_once(cells):
    # 16 x 16 pixels, grid lines every 16/cells pixels: every vertex is a pixel centre and
    # horizontal, vertical and diagonal edges run through rows of pixel centres.
    g = np.linspace(-1, 1, cells + 1)
    x, y = np.meshgrid(g, g)
    pts = np.column_stack([x.ravel(), y.ravel()])
    i = (np.arange(cells)[:, None] * (cells + 1) + np.arange(cells)).ravel()
    tris = np.concatenate([np.stack([i, i + cells + 1, i + 1], 1),
                           np.stack([i + 1, i + cells + 1, i + cells + 2], 1)])
    assert (hits(rasterize(clip_xy(pts), {}, tris, (16, 16)), (16, 16)) == 1).all()
    # the other diagonal
    tris = np.concatenate([np.stack([i, i + cells + 1, i + cells + 2], 1),
                           np.stack([i, i + cells + 2, i + 1], 1)])
    assert (hits(rasterize(clip_xy(pts), {}, tris, (16, 16)), (16, 16)) == 1).all()


def test_non_finite_vertices_drop_their_triangles():
    pos = QUAD.copy()
    pos[3, 0] = np.nan
    frags = rasterize(pos, {}, QUAD_TRIS, (8, 8))
    expected = hits(rasterize(QUAD, {}, QUAD_TRIS[:1], (8, 8)), (8, 8))
    np.testing.assert_array_equal(hits(frags, (8, 8)), expected)
