"""Triangle rasterisation as Direct3D 9 defines it, vectorised over 2x2 pixel quads.

- Clip space is D3D's: 0 <= z <= w. Triangles are clipped against the near and far planes and
  against a guard band in x and y (wide enough that no visible triangle is ever cut by it; it
  only keeps the fixed-point edge arithmetic inside int64).
- The viewport maps NDC x in [-1, 1] to [0, W] and y in [1, -1] to [0, H]; pixel (px, py) is
  sampled at exactly (px, py) (D3D9's pixel centres, no +0.5).
- Coverage uses edge functions on vertex positions snapped to 1/256 pixel, evaluated in
  integers, with the top-left rule: a shared edge belongs to exactly one triangle. Each pair of
  pixel rows of a triangle is solved for its exact covered spans, so the work is proportional to
  the quads a triangle touches, not to its bounding box.
- Every covered pixel comes with its whole 2x2 quad (helper pixels included), as GPUs shade,
  so texture LOD can be taken from quad differences of any value, dependent reads included.
- Varyings are interpolated perspective-correctly; depth (z/w) linearly in screen space.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from effects.base import caches

SUBPIXEL_BITS = 8
_ONE = 1 << SUBPIXEL_BITS
# Quad pixel order inside a 2x2 quad: (0,0), (1,0), (0,1), (1,1).
QUAD_DX = np.array([0, 1, 0, 1], dtype=np.int32)
QUAD_DY = np.array([0, 0, 1, 1], dtype=np.int32)
# Screen coordinates stay within +-2^16 pixels (so edge products stay below 2^50).
_GUARD_PIXELS = float(1 << 16)
CULL_MODES = ("NONE", "CW", "CCW")
_CLIPPING_PLANES = 7        # near, far, four guard-band sides, w > 0
_NEXT = [1, 2, 0]           # edge i runs from vertex i to vertex _NEXT[i]
_LAM_J, _LAM_K = [1, 2, 0], [2, 0, 1]    # corner i's barycentric from the edge j -> k


@dataclass
class QuadFragments:
    """The fragments of a draw, one row per pixel, in primitive order (then y, then x).

    With `quads` (the default) rows come as whole 2x2 quads, row = quad*4 + pixel in
    QUAD_DX/QUAD_DY order, helper pixels included (covered False), so an IR program can take
    texture LOD from quad differences. Without, rows are the covered pixels only (for programs
    that need no derivatives). Varyings are (N, k) rows an IR program runs over directly.
    """

    x: np.ndarray          # (N,) int32 pixel x (helper pixels may lie outside the viewport)
    y: np.ndarray          # (N,) int32 pixel y
    covered: np.ndarray    # (N,) bool: inside the triangle and inside the viewport
    depth: np.ndarray      # (N,) float32 z/w (with the depth bias)
    prim: np.ndarray       # (N,) int64: index of the source triangle in draw order
    front: np.ndarray      # (N,) bool: the triangle is front-facing (clockwise on screen)
    varyings: dict[str, np.ndarray]
    quads: bool = True
    tri: np.ndarray | None = None   # (N,) int64: the row's triangle in its TriangleSetup

    @property
    def count(self) -> int:
        """Number of rows (4 per quad with `quads`)."""
        return int(self.x.shape[0])

    @staticmethod
    def empty(names_dims: dict[str, int], quads: bool = True) -> "QuadFragments":
        z = np.zeros(0, np.int32)
        return QuadFragments(z, z.copy(), np.zeros(0, bool), np.zeros(0, np.float32),
                             np.zeros(0, np.int64), np.zeros(0, bool),
                             {n: np.zeros((0, d), np.float32) for n, d in names_dims.items()},
                             quads)


# ------------------------------------------------------------------------------------------------
# Clipping: dot(plane[:4], position) + plane[4] >= 0 is inside

@caches.memo("reference.clip_planes", keys="target size", entry_bytes=256, max_bytes=64 * 256)
def _clip_planes(size: tuple[int, int]) -> np.ndarray:
    """The clip planes for a target size (kept per size: read-only, made once)."""
    planes = _make_clip_planes(size)
    planes.setflags(write=False)
    return planes


def _make_clip_planes(size: tuple[int, int]) -> np.ndarray:
    gx = _GUARD_PIXELS / (0.5 * size[0])   # NDC extent of the guard band
    gy = _GUARD_PIXELS / (0.5 * size[1])
    return np.array([
        [0, 0, 1, 0, 0],            # near: z >= 0
        [0, 0, -1, 1, 0],           # far: z <= w
        [-1, 0, 0, gx, 0], [1, 0, 0, gx, 0],
        [0, -1, 0, gy, 0], [0, 1, 0, gy, 0],
        [0, 0, 0, 1, -1e-30],       # w > 0 (a vertex at w = 0 has no screen position)
        [0, 0, 0, 0, 1],            # never crossed: pads the outside flags to 8 bytes a vertex
    ], dtype=np.float64)


def _clip_polygon(poly: list[np.ndarray], plane: np.ndarray) -> list[np.ndarray]:
    """Sutherland-Hodgman against one plane. Each vertex is a flat float64 array: 4 position
    components then every attribute component (interpolated linearly in clip space)."""
    out: list[np.ndarray] = []
    if not poly:
        return out
    dist = [float(plane[:4] @ v[:4] + plane[4]) for v in poly]
    for i, v in enumerate(poly):
        j = (i + 1) % len(poly)
        di, dj = dist[i], dist[j]
        if di >= 0:
            out.append(v)
        if (di >= 0) != (dj >= 0):
            t = di / (di - dj)
            out.append(v + (poly[j] - v) * t)
    return out


def clip_triangles(pos: np.ndarray, attrs: np.ndarray, tris: np.ndarray, size: tuple[int, int]
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Clip triangles to the view volume (near, far, guard band). Returns (pos, attrs, tris,
    source triangle index), triangles still in draw order; a clipped triangle becomes a fan that
    keeps its winding."""
    planes = _clip_planes(tuple(int(v) for v in size))
    # One 8-byte word per vertex, byte p true when it lies outside plane p (the eighth plane
    # is never crossed): a triangle's AND of its vertices' words is non-zero when all three
    # lie beyond one plane, its OR when some vertex lies beyond some plane -- the per-plane
    # tests of (T, 3, P) booleans in a few passes over (T,) words.
    outside = (pos @ planes[:, :4].T + planes[:, 4]) < 0        # (V, 8)
    code = outside.view(np.uint64)[:, 0]
    corners = code[tris]                                        # (T, 3)
    c0, c1, c2 = corners[:, 0], corners[:, 1], corners[:, 2]
    rejected = (c0 & c1 & c2) != 0
    any_out = (c0 | c1 | c2) != 0
    finite = np.isfinite(pos)
    if not finite.all():        # NaN/inf: nowhere to draw
        bad = (~finite.all(axis=1))[tris].any(axis=1)
        rejected |= bad
        any_out |= bad
    partial = any_out & ~rejected
    keep = ~any_out
    if not partial.any():
        if keep.all():
            return pos, attrs, tris, np.arange(len(tris))
        return pos, attrs, tris[keep], np.nonzero(keep)[0]
    source = np.nonzero(keep)[0]
    new_pos, new_tris, new_src = [], [], []
    base = len(pos)
    flat = np.concatenate([pos, attrs.astype(np.float64)], axis=1)
    for t in np.nonzero(partial)[0]:
        poly = [flat[i] for i in tris[t]]
        for plane in planes[:_CLIPPING_PLANES]:
            poly = _clip_polygon(poly, plane)
        if len(poly) < 3:
            continue
        first = base + len(new_pos)
        new_pos.extend(poly)
        for k in range(1, len(poly) - 1):
            new_tris.append((first, first + k, first + k + 1))
            new_src.append(t)
    if not new_pos:
        return pos, attrs, tris[keep], source
    extra = np.array(new_pos)
    pos = np.concatenate([pos, extra[:, :4]])
    attrs = np.concatenate([attrs, extra[:, 4:].astype(attrs.dtype)])
    all_tris = np.concatenate([tris[keep], np.array(new_tris, dtype=tris.dtype)])
    all_src = np.concatenate([source, np.array(new_src, dtype=np.int64)])
    order = np.argsort(all_src, kind="stable")
    return pos, attrs, all_tris[order], all_src[order]


# ------------------------------------------------------------------------------------------------
# Rasterisation

def rasterize(clip_pos: np.ndarray, varyings: dict[str, np.ndarray], triangles: np.ndarray,
              size: tuple[int, int], cull: str = "CCW", *, flat: tuple[str, ...] = (),
              depth_bias: float = 0.0, slope_scale_depth_bias: float = 0.0,
              quads: bool = True) -> QuadFragments:
    """Rasterise a triangle list (see `setup_triangles`): the whole frame as one band."""
    setup = setup_triangles(clip_pos, varyings, triangles, size, cull, flat=flat,
                            depth_bias=depth_bias, slope_scale_depth_bias=slope_scale_depth_bias,
                            quads=quads)
    return setup if isinstance(setup, QuadFragments) else setup.rows()


def setup_triangles(clip_pos: np.ndarray, varyings: dict[str, np.ndarray], triangles: np.ndarray,
                    size: tuple[int, int], cull: str = "CCW", *, flat: tuple[str, ...] = (),
                    depth_bias: float = 0.0, slope_scale_depth_bias: float = 0.0,
                    quads: bool = True,
                    vertex_only: tuple[str, ...] = ()) -> "TriangleSetup | QuadFragments":
    """Clip, project, cull and orient a triangle list; empty fragments when nothing is left.

    `clip_pos` (N, 4) in D3D clip space, `varyings` name -> (N, k), `triangles` (M, 3) vertex
    indices in draw order, `size` (W, H). `cull` is D3DCULL's NONE, CW or CCW (the default culls
    counter-clockwise, i.e. back, faces). `flat` names varyings taken from each triangle's first
    vertex (D3DSHADE_FLAT colours). Depth gets DepthBias + SlopeScaleDepthBias * max slope.
    `quads` False returns covered pixels only (no helpers), for programs without derivatives.
    `vertex_only` names varyings kept at the clipped vertices (`TriangleSetup.attrs`) but not
    interpolated to the fragments (a back end's own per-triangle setup reads them).
    """
    width, height = size
    cull = cull.upper()
    if cull not in CULL_MODES:
        raise ValueError(f"cull mode must be one of {CULL_MODES}, got {cull!r}")
    names = list(varyings)
    dims = {n: int(np.shape(varyings[n])[1]) for n in names}
    triangles = np.asarray(triangles, np.int64).reshape(-1, 3)
    if len(triangles) == 0 or width <= 0 or height <= 0:
        return QuadFragments.empty(dims, quads)
    attrs = (np.concatenate([np.asarray(varyings[n], np.float32) for n in names], axis=1)
             if names else np.zeros((len(clip_pos), 0), np.float32))
    flat_cols = np.zeros(attrs.shape[1], bool)
    col = 0
    for n in names:
        flat_cols[col:col + dims[n]] = n in flat
        col += dims[n]
    provoking = attrs[triangles[:, 0]] if flat_cols.any() else None
    pos, attrs, tris, source = clip_triangles(np.asarray(clip_pos, np.float64), attrs,
                                              triangles, size)
    if len(tris) == 0:
        return QuadFragments.empty(dims, quads)

    # Vertices no remaining triangle uses may lie anywhere (w = 0, NaN): their garbage is unused.
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        inv_w = 1.0 / pos[:, 3]
        fx = np.rint((pos[:, 0] * inv_w + 1.0) * (0.5 * width * _ONE)).astype(np.int64)
        fy = np.rint((1.0 - pos[:, 1] * inv_w) * (0.5 * height * _ONE)).astype(np.int64)
        sz = pos[:, 2] * inv_w

    X, Y = fx[tris], fy[tris]                                       # (T, 3)
    area = ((X[:, 1] - X[:, 0]) * (Y[:, 2] - Y[:, 0])
            - (Y[:, 1] - Y[:, 0]) * (X[:, 2] - X[:, 0]))
    front = area > 0  # clockwise on a y-down screen: D3D's front face
    visible = area != 0
    if cull == "CCW":
        visible &= front
    elif cull == "CW":
        visible &= ~front
    if not visible.all():   # one index for the six arrays (a boolean mask is scanned each time)
        kept = np.flatnonzero(visible)
        tris, source, area, front, X, Y = (a.take(kept, axis=0)
                                           for a in (tris, source, area, front, X, Y))
    if len(tris) == 0:
        return QuadFragments.empty(dims, quads)
    # Orient every triangle clockwise so one inside test serves both windings (vertex 0 stays
    # first, so it is still the provoking vertex).
    flip = area < 0
    if flip.any():
        tris = tris.copy()
        tris[flip, 1:] = tris[flip, 2:0:-1]
        X, Y = fx[tris], fy[tris]
        area = np.abs(area)

    y_lo = np.maximum(-((-_min3(Y)) // _ONE), 0)                # first pixel row, ceil
    y_hi = np.minimum(_max3(Y) // _ONE, height - 1)              # last pixel row
    return TriangleSetup(size, tris, X, Y, area, sz, inv_w, attrs, source, front, names, dims,
                         flat_cols, provoking, depth_bias, slope_scale_depth_bias, quads,
                         y_lo, y_hi, tuple(vertex_only))


@dataclass
class TriangleSetup:
    """A draw's triangles clipped, projected, culled and oriented: what rasterising any band of
    pixel rows needs. Built once per draw; `rows` rasterises one band."""

    size: tuple[int, int]
    tris: np.ndarray
    X: np.ndarray
    Y: np.ndarray
    area: np.ndarray
    sz: np.ndarray
    inv_w: np.ndarray
    attrs: np.ndarray
    source: np.ndarray
    front: np.ndarray
    names: list[str]
    dims: dict[str, int]
    flat_cols: np.ndarray
    provoking: np.ndarray | None
    depth_bias: float
    slope_bias: float
    quads: bool
    y_lo: np.ndarray      # (T,) first and last pixel row each triangle can cover
    y_hi: np.ndarray
    vertex_only: tuple[str, ...] = ()
    # `attrs` component-major, made on first use (`_attrs_t`): derived, so no init or compare
    _attrs_t_cache: np.ndarray | None = field(default=None, init=False, repr=False, compare=False)

    def rows(self, y0: int = 0, y1: int | None = None) -> QuadFragments:
        """The fragments in pixel rows [y0, y1) (y0 even, so quads stay whole): the same
        rows, in the same order, as the whole frame's fragments restricted to those rows."""
        height = self.size[1]
        y1 = height if y1 is None else min(int(y1), height)
        if y0 % 2:
            raise ValueError(f"a band starts on an even row, not {y0}")
        sel = (self.y_hi >= y0) & (self.y_lo < y1)
        if not sel.any():
            return QuadFragments.empty(self.dims, self.quads)
        part = None if sel.all() else np.nonzero(sel)[0]

        def pick(a):
            return a if part is None else a[part]

        tris, X, Y = pick(self.tris), pick(self.X), pick(self.Y)
        quad_tri, qx, qy, covered = _cover(X, Y, self.size[0], y1, y0,
                                           rows=(pick(self.y_lo), pick(self.y_hi)))
        if len(quad_tri) == 0:
            return QuadFragments.empty(self.dims, self.quads)
        names, attrs_t, flat_cols, provoking = (self.names, self._attrs_t(), self.flat_cols,
                                                self.provoking)
        if self.vertex_only:
            names = [n for n in self.names if n not in self.vertex_only]
            cols = np.concatenate([np.full(self.dims[n], n not in self.vertex_only)
                                   for n in self.names]).astype(bool)
            attrs_t, flat_cols = attrs_t[cols], flat_cols[cols]
            provoking = None if provoking is None else provoking[:, cols]
        frags = _shade_setup(quad_tri, qx, qy, covered, tris, X, Y, pick(self.area), self.sz,
                             self.inv_w, attrs_t, pick(self.source), pick(self.front),
                             names, self.dims, flat_cols, provoking,
                             self.depth_bias, self.slope_bias, self.quads)
        if part is not None and frags.tri is not None:
            frags.tri = part[frags.tri]
        return frags

    def _attrs_t(self) -> np.ndarray:
        """The attributes component-major, (K, V): made once per draw, read by every band
        (two bands' threads may both make it; either copy is the same)."""
        found = self._attrs_t_cache
        if found is None:
            found = self._attrs_t_cache = np.ascontiguousarray(self.attrs.T)
        return found


def _min3(a: np.ndarray) -> np.ndarray:
    """The smallest of each row of a (T, 3) array: `a.min(axis=1)`, as two elementwise
    passes (NumPy reduces a 3-wide axis about ten times slower)."""
    return np.minimum(np.minimum(a[:, 0], a[:, 1]), a[:, 2])


def _max3(a: np.ndarray) -> np.ndarray:
    """The largest of each row of a (T, 3) array (see `_min3`)."""
    return np.maximum(np.maximum(a[:, 0], a[:, 1]), a[:, 2])


def _cover(X: np.ndarray, Y: np.ndarray, width: int, height: int, y0: int = 0,
           rows: tuple[np.ndarray, np.ndarray] | None = None):
    """Exact coverage of clockwise triangles (T, 3) fixed-point vertices, by quad rows, in the
    pixel rows [y0, height) (y0 even).

    For each pair of pixel rows a triangle spans, every edge function E(x) = c - dy*256*x is
    solved for the range of integer x where E >= bias (bias 0 on top and left edges, 1 on the
    others: the top-left rule), giving the covered span of each row. Returns the quads (triangle
    index, quad origin x, y, (Q, 4) coverage) in triangle order, then y, then x.
    `rows`: each triangle's first and last pixel row in the frame (`TriangleSetup.y_lo`,
    `y_hi`), when known; clamped here to the band.
    """
    if rows is None:
        y_lo = np.maximum(-((-_min3(Y)) // _ONE), y0)           # ceil, clamped to the band
        y_hi = np.minimum(_max3(Y) // _ONE, height - 1)
    else:
        y_lo = np.maximum(rows[0], y0)
        y_hi = np.minimum(rows[1], height - 1)
    qy0 = y_lo & ~1
    nrows = np.where(y_hi >= y_lo, (y_hi - qy0) // 2 + 1, 0)
    total_rows = int(nrows.sum())
    if total_rows == 0:
        return np.zeros(0, np.int64), None, None, None

    # Rows come grouped by triangle in triangle order, and quads by row: a triangle's (a
    # row's) value reaches its rows (quads) by a repeat, the values of a gather, faster.
    def per_row(values: np.ndarray) -> np.ndarray:
        return np.repeat(values, nrows)

    starts = np.cumsum(nrows) - nrows
    row_qy = per_row(qy0 - 2 * starts) + 2 * np.arange(total_rows)

    # Edge i runs from vertex i to i+1; its edge function on pixel row y, less the top-left
    # bias, is c(y) - slope * x with c(y) = dx*(y*256 - ay) + dy*ax - bias, slope = dy*256,
    # and pixel x is inside it where slope * x <= c(y). A clockwise triangle has one or two
    # edges of slope < 0 (each bounds x below, by ceil(c / slope)), one or two of slope > 0
    # (each bounds it above, by floor(c / slope)), and at most one of slope 0 (which keeps
    # or drops the whole row). Four edge slots, two of each bound (a lone edge of its kind
    # in both), make the bounds two maxima and two minima with no selection per row; every
    # value is an exact integer, so the spans are those of testing each edge on its own.
    count = len(X)
    ax, ay = np.ascontiguousarray(X.T), np.ascontiguousarray(Y.T)    # (3, T): edge i's start
    dx, dy = ax[_NEXT] - ax, ay[_NEXT] - ay
    # top-left edges own the pixels on them (bias 0), the others not (bias 1)
    c0 = dy * ax
    c0 -= dx * ay
    c0 -= ~((dy < 0) | ((dy == 0) & (dx > 0)))
    slope = dy * _ONE
    fall, rise = slope < 0, slope > 0
    # ceil(c / s) = floor((c + s + 1) / s) for s < 0: one floor division serves both bounds
    c0 += (slope + 1) * fall
    # each triangle's first and last edge of each kind, as indices into the (3, T) arrays
    f0, f1, f2 = fall
    r0, r1, r2 = rise
    slots = np.empty((4, count), np.int64)
    slots[0] = np.where(f0, 0, np.where(f1, 1, 2))
    slots[1] = np.where(f2, 2, np.where(f1, 1, 0))
    slots[2] = np.where(r0, 0, np.where(r1, 1, 2))
    slots[3] = np.where(r2, 2, np.where(r1, 1, 0))
    slots *= count
    slots += np.arange(count)
    picked = np.empty((3, 4, count), np.int64)
    for out, values in zip(picked, (dx, c0, slope)):
        values.reshape(-1).take(slots, out=out)
    e_dx, e_c0, e_slope = np.repeat(picked, nrows, axis=2)          # (4, rows) each
    flat = slope == 0
    has_flat = bool(flat.any())
    if has_flat:   # the horizontal edge's c(y) (0 where a triangle has none: keeps every row)
        h_dx = per_row((dx * flat).sum(axis=0))
        h_c0 = per_row((c0 * flat).sum(axis=0))
    span_lo, span_hi = [], []
    for r in (0, 1):
        py = (row_qy + r) * _ONE
        q = e_dx * py
        q += e_c0
        q //= e_slope                       # rows 0, 1: lower bounds; rows 2, 3: upper
        x_lo = np.maximum(np.maximum(q[0], q[1]), 0)
        x_hi = np.minimum(np.minimum(q[2], q[3]), width - 1)
        empty = (x_hi < x_lo) | (row_qy + r >= height)
        if has_flat:
            empty |= h_dx * py + h_c0 < 0
        # an empty row as the span (width + 1, -2): past both ends, so it never joins a
        # quad's span, as a clipped one never reaches past them
        span_lo.append(np.where(empty, width + 1, x_lo).astype(np.int32))
        span_hi.append(np.where(empty, -2, x_hi).astype(np.int32))
    qx_lo = np.minimum(span_lo[0], span_lo[1]) & ~1
    qx_hi = np.maximum(span_hi[0], span_hi[1])
    nquads = np.where(qx_hi >= qx_lo, (qx_hi - qx_lo) // 2 + 1, 0)
    total = int(nquads.sum())
    if total == 0:
        return np.zeros(0, np.int64), None, None, None

    def per_quad(values: np.ndarray) -> np.ndarray:
        return np.repeat(values, nquads)

    qstart = np.cumsum(nquads) - nquads
    qx = (per_quad(qx_lo - 2 * qstart) + 2 * np.arange(total)).astype(np.int32)
    qx1 = qx + 1
    covered = np.empty((total, 4), bool)
    for r in (0, 1):
        lo, hi = per_quad(span_lo[r]), per_quad(span_hi[r])
        np.logical_and(qx >= lo, qx <= hi, out=covered[:, 2 * r])
        np.logical_and(qx1 >= lo, qx1 <= hi, out=covered[:, 2 * r + 1])
    qy = per_quad(row_qy.astype(np.int32))
    tri = per_quad(per_row(np.arange(len(X))))
    touched = covered.view(np.uint32)[:, 0] != 0     # any of the quad's four pixels
    if not touched.all():  # quads between the spans of a thin sliver's two rows
        tri, qx, qy, covered = tri[touched], qx[touched], qy[touched], covered[touched]
    return tri, qx, qy, covered


def _shade_setup(quad_tri, qx, qy, covered, tris, X, Y, area, sz, inv_w, attrs_t, source, front,
                 names, dims, flat_cols, provoking, depth_bias, slope_bias,
                 quads) -> QuadFragments:
    """Depth and perspective-correct varyings at every row (pixel), from per-triangle plane
    equations (float64) of the screen-space barycentrics weighted by 1/w, and of z/w.
    `attrs_t` is the vertex attributes component-major, (K, V).
    Work is laid out as long runs over stacked arrays: the three corners (and the depth
    plane) side by side, a row's per-triangle values gathered in one take (NumPy is slow on
    tiny trailing axes and pays per call)."""
    count_t = len(tris)
    fxs, fys = X.T / _ONE, Y.T / _ONE                               # (3, T), in pixels
    a2 = area.astype(np.float64) / (_ONE * _ONE)
    # the barycentric plane of corner i from the edge opposite it, j -> k
    ex, ey = fxs[_LAM_K] - fxs[_LAM_J], fys[_LAM_K] - fys[_LAM_J]
    lam = np.empty((3, 3, count_t))                                 # (coefficient, corner, T)
    np.divide(-ey, a2, out=lam[0])
    np.divide(ex, a2, out=lam[1])
    np.divide(ey * fxs[_LAM_J] - ex * fys[_LAM_J], a2, out=lam[2])
    corners = np.ascontiguousarray(tris.T)                          # (3, T): vertex i of each
    # planes: corners 0, 1, 2 (lam / w), then z/w: (plane, coefficient, T)
    planes = np.empty((4, 3, count_t))
    np.multiply(lam, inv_w[corners], out=planes[:3].transpose(1, 0, 2))
    z_terms = lam * sz[corners]                                     # (coefficient, corner, T)
    z_plane = planes[3]
    np.add(0, z_terms[:, 0], out=z_plane)                           # as sum() adds, from 0
    z_plane += z_terms[:, 1]
    z_plane += z_terms[:, 2]
    if depth_bias or slope_bias:
        slope = np.maximum(np.abs(z_plane[0]), np.abs(z_plane[1]))
        z_plane[2] = z_plane[2] + depth_bias + slope_bias * slope

    if quads:
        count = len(quad_tri) * 4
        x = np.repeat(qx, 4)
        x[1::2] += 1                                                # QUAD_DX: 0 1 0 1
        y = np.repeat(qy, 4)
        y[2::4] += 1                                                # QUAD_DY: 0 0 1 1
        y[3::4] += 1
        row_tri = np.repeat(quad_tri, 4)
        covered = covered.reshape(-1)
    else:
        q, pixel = np.nonzero(covered)
        count = len(q)
        x = qx[q] + QUAD_DX[pixel]
        y = qy[q] + QUAD_DY[pixel]
        row_tri = quad_tri[q]
        covered = np.ones(count, bool)

    # Rows come grouped by triangle in triangle order (see `_cover`), so a per-triangle value
    # reaches its rows by a repeat: the same values as a gather by `row_tri`, faster.
    counts = (np.bincount(quad_tri, minlength=count_t) * 4 if quads
              else np.bincount(row_tri, minlength=count_t))
    xf, yf = x.astype(np.float64), y.astype(np.float64)
    at_row = np.repeat(planes, counts, axis=2)                      # (plane, coefficient, N)
    values = at_row[:, 0]
    values *= xf
    at_row[:, 1] *= yf
    values += at_row[:, 1]
    values += at_row[:, 2]                                          # (plane, N)
    # D3D clamps depth to the viewport's [MinZ, MaxZ] = [0, 1] (bias and helpers can leave it)
    depth = np.clip(values[3], 0.0, 1.0).astype(np.float32)

    rows: dict[str, np.ndarray] = {}
    if attrs_t.shape[0]:
        inv_sum = values[0] + values[1]
        inv_sum += values[2]
        np.divide(1.0, inv_sum, out=inv_sum)
        weights = values[:3]
        weights *= inv_sum
        # Covered pixels lie inside the triangle, so their weights are >= 0 up to rounding:
        # clamp the noise so a value equal at two vertices is exact along their edge and never
        # changes sign. Helper pixels keep their extrapolated weights (derivatives need them).
        floor = np.where(covered, 0.0, -np.inf) if quads else 0.0
        np.maximum(weights, floor, out=weights)
        # Component-major (K, corner, N): each corner's attributes gathered at the rows'
        # vertices, scaled by the corner's weight, the three summed in corner order.
        at_corners = attrs_t.take(corners.reshape(-1), axis=1).reshape(-1, 3, count_t)
        if provoking is not None:   # flat: every corner holds the provoking value
            at_corners[flat_cols] = provoking[source][:, flat_cols].T[:, None, :]
        terms = np.repeat(at_corners, counts, axis=2)                 # (K, corner, N)
        terms *= weights.astype(np.float32)
        everything = terms[:, 0] + terms[:, 1]
        everything += terms[:, 2]
        col = 0
        for n in names:
            rows[n] = everything[col:col + dims[n]].T                 # (N, k) views
            col += dims[n]
    else:
        rows = {n: np.zeros((count, 0), np.float32) for n in names}
    return QuadFragments(x, y, covered, depth, np.repeat(source, counts),
                         np.repeat(front, counts), rows, quads, row_tri)
