"""Tangent frames (and smooth normals) of a triangle mesh, as `effects.assets.meshes` defines
them (its module docstring: Boyd and Taylor's per-triangle dP/du, dP/dv, area-weighted sums
per vertex pooled across texture seams, then orthonormalised).

Vectors are held as three (N,) float64 component columns, not (N, 3) rows: NumPy reduces a
3-wide axis and broadcasts (N, 1) factors several times slower than it runs whole columns,
and a 1M-triangle mesh makes a dozen such vectors. Every value is computed by the formula,
in the order, that the row form used (dot products (x*x + y*y) + z*z, as `np.add.reduce`
sums three; cross products as `np.cross` forms them; sums per vertex in triangle-corner order,
as `np.add.at` would), so the frames are the same bit for bit.
"""
from __future__ import annotations

import numpy as np

Columns = list      # three (N,) float64 arrays: x, y, z

_FALLBACK_NORMAL = (0.0, 1.0, 0.0)     # a vertex whose normal sums to zero points up
_TINY = 1e-12


def columns(rows: np.ndarray) -> Columns:
    """An (N, k) array's columns as contiguous float64 arrays."""
    return [np.ascontiguousarray(rows[:, k], np.float64) for k in range(rows.shape[1])]


def rows32(cols: Columns) -> np.ndarray:
    """Columns back as an (N, k) float32 array (each value rounded as astype rounds it)."""
    out = np.empty((len(cols[0]), len(cols)), np.float32)
    for k, c in enumerate(cols):
        out[:, k] = c
    return out


def dot(a: Columns, b: Columns) -> np.ndarray:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a: Columns, b: Columns) -> Columns:
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def length(v: Columns) -> np.ndarray:
    return np.sqrt(dot(v, v))


def normalize(v: Columns, fallback=None) -> Columns:
    """v / |v|; rows shorter than 1e-12 stay as they are, or take `fallback` (three scalars
    or columns) where given."""
    size = length(v)
    ok = size > _TINY
    divisor = np.where(ok, size, 1.0)
    out = [c / divisor for c in v]
    if fallback is not None:
        out = [np.where(ok, o, f) for o, f in zip(out, fallback)]
    return out


def corner_sum(corners: np.ndarray, values: Columns, size: int,
               spread: np.ndarray | None = None) -> Columns:
    """Per vertex the sum of a per-triangle vector over the triangle corners at it: `corners`
    is every triangle's corner 0, then every corner 1, then 2 (tri.T.reshape(-1)), each
    triangle's value standing for all three, summed in that order. `spread`: a (3M,) float64
    buffer to lay each column out in (one for every column, instead of one each)."""
    out = []
    for c in values:
        if spread is None:
            weights = np.concatenate([c, c, c])
        else:
            weights = spread
            weights.reshape(3, -1)[:] = c
        out.append(np.bincount(corners, weights=weights, minlength=size))
    return out


def group_sum(values: Columns, groups: np.ndarray) -> Columns:
    """Each row replaced by the sum over the rows of its group (row order)."""
    count = int(groups.max()) + 1
    return [np.bincount(groups, weights=c, minlength=count)[groups] for c in values]


def row_groups(keys: list[np.ndarray]) -> np.ndarray:
    """A group number per row of integer key columns, equal exactly where all the keys are
    equal (numbered in the sorted order of the keys). The columns are folded into one int64
    code by their value ranges (re-numbered densely before the code could overflow), so one
    1-D sort replaces sorting K-wide rows."""
    count = len(keys[0])
    code = np.zeros(count, np.int64)
    span = 1
    for col in keys:
        lo = int(col.min()) if count else 0
        width = (int(col.max()) - lo + 1) if count else 1
        if span * width >= 1 << 62:
            code = _dense_rank(code)
            span = int(code.max()) + 1 if count else 1
        if width >= 1 << 62:
            values = _dense_rank(col)
            width = int(values.max()) + 1
        else:
            values = col.astype(np.int64) - lo
        code *= width
        code += values
        span *= width
    return _dense_rank(code)


def _dense_rank(code: np.ndarray) -> np.ndarray:
    """np.unique(code, return_inverse=True)[1]: each value's rank among the distinct values.
    Codes spanning at most a few times their count are ranked through a table instead of a
    sort."""
    if not len(code):
        return np.zeros(0, np.int64)
    lo, hi = int(code.min()), int(code.max())
    if hi - lo < 4 * len(code) + 1024:
        offset = code - lo
        present = np.zeros(hi - lo + 1, bool)
        present[offset] = True
        rank = np.cumsum(present) - 1
        return rank[offset]
    return np.unique(code, return_inverse=True)[1].ravel().astype(np.int64)


def position_key(p: Columns) -> list[np.ndarray]:
    """Positions snapped to 1e-4 of the largest coordinate, as integers (equal positions up
    to rounding share a key)."""
    largest = max((float(np.abs(c).max()) for c in p if len(c)), default=0.0)
    scale = 1e4 / max(1e-6, largest)
    return [np.rint(c * scale).astype(np.int64) for c in p]


def any_perpendicular(n: Columns) -> Columns:
    """A unit vector perpendicular to each n: n x X, or n x Y where n is near the x axis."""
    near_x = np.abs(n[0]) < 0.9
    axis = [np.where(near_x, 1.0, 0.0), np.where(near_x, 0.0, 1.0), np.zeros(len(n[0]))]
    return normalize(cross(n, axis))


# Triangles are worked a chunk at a time: a chunk's temporaries (a dozen (C,) columns) stay in
# the cache and reuse the same memory, where whole-mesh temporaries would take ~40 fresh
# 8 MB arrays for 1M triangles (page faults cost more than the arithmetic on them).
_CHUNK = 1 << 15


def _triangle_terms(p: Columns, tex: Columns, at: list[np.ndarray], want_normals: bool,
                    out: dict[str, Columns]) -> None:
    """The per-triangle vectors of the triangles `at` (their corner 0, 1, 2 vertex indices),
    written into `out`'s columns at the same rows: area-weighted unit dP/du ('dpdu') and
    dP/dv ('dpdv') and, with `want_normals`, the face normals ('face_n', length twice the
    area)."""
    count = len(at[0])
    for lo in range(0, count, _CHUNK):
        hi = min(lo + _CHUNK, count)
        i0, i1, i2 = (a[lo:hi] for a in at)
        p0 = [c[i0] for c in p]
        e1 = [c[i1] - a for c, a in zip(p, p0)]
        e2 = [c[i2] - a for c, a in zip(p, p0)]
        face_n = cross(e1, e2)                # length = 2 * area
        if want_normals:
            for dst, src in zip(out["face_n"], face_n):
                dst[lo:hi] = src
        # dP/du and dP/dv per triangle: solve [e1 e2] = [dP/du dP/dv] [[du1 du2], [dv1 dv2]].
        u, v = tex
        u0, v0 = u[i0], v[i0]
        du1, dv1, du2, dv2 = u[i1] - u0, v[i1] - v0, u[i2] - u0, v[i2] - v0
        det = du1 * dv2 - du2 * dv1
        ok = np.abs(det) > _TINY
        safe = np.where(ok, det, 1.0)
        dpdu = [(a * dv2 - b * dv1) / safe for a, b in zip(e1, e2)]
        dpdv = [(b * du1 - a * du2) / safe for a, b in zip(e1, e2)]
        area = 0.5 * length(face_n) * ok
        for name, vec in (("dpdu", dpdu), ("dpdv", dpdv)):
            for dst, c in zip(out[name], normalize(vec)):
                np.multiply(c, area, out=dst[lo:hi])


def tangent_frames(positions: np.ndarray, uv: np.ndarray, indices: np.ndarray,
                   normals: np.ndarray | None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(normals, tangents, binormals) as (N, 3) float32 for a triangle list (`indices`
    (M, 3)); `normals` None computes smooth ones (area-weighted face normals summed over
    every vertex at the same position)."""
    p = columns(positions)
    tex = columns(uv)
    indices = np.asarray(indices)
    n_vert, n_tri = len(positions), len(indices)
    # corner 0 of every triangle, then 1, then 2; each third is one corner's column
    corners = np.empty(3 * n_tri, np.int64)
    corners.reshape(3, n_tri)[:] = indices.reshape(-1, 3).T
    at = [corners[k * n_tri:(k + 1) * n_tri] for k in range(3)]
    names = ("dpdu", "dpdv") + (("face_n",) if normals is None else ())
    terms = {name: [np.empty(n_tri) for _ in range(3)] for name in names}
    _triangle_terms(p, tex, at, normals is None, terms)
    spread = np.empty(3 * n_tri)          # a triangle's value at each of its three corners

    if normals is None:
        acc = corner_sum(corners, terms.pop("face_n"), n_vert, spread)
        acc = group_sum(acc, row_groups(position_key(p)))
        nrm = normalize(acc, _FALLBACK_NORMAL)
    else:
        nrm = normalize(columns(normals), _FALLBACK_NORMAL)

    t_acc = corner_sum(corners, terms.pop("dpdu"), n_vert, spread)
    b_acc = corner_sum(corners, terms.pop("dpdv"), n_vert, spread)
    del spread, corners, at
    # Pool across texture seams: same position, same normal, UVs equal up to whole numbers.
    frac_uv = [np.rint(((c + 0.5) % 1.0 - 0.5) * 1e4).astype(np.int64) % 10000 for c in tex]
    keys = position_key(p) + [np.rint(c * 1e3).astype(np.int64) for c in nrm] + frac_uv
    groups = row_groups(keys)
    t_acc, b_acc = group_sum(t_acc, groups), group_sum(b_acc, groups)

    along = dot(t_acc, nrm)
    t = [a - n * along for a, n in zip(t_acc, nrm)]
    t = _normalize_or_perpendicular(t, nrm)
    b = cross(nrm, t)
    sign = np.where(dot(b, b_acc) < 0, -1.0, 1.0)
    return rows32(nrm), rows32(t), rows32([c * sign for c in b])


def _normalize_or_perpendicular(t: Columns, n: Columns) -> Columns:
    """normalize(t, any_perpendicular(n)), the perpendicular made only for the rows that take
    it (a vertex whose tangents cancel or that has none)."""
    size = length(t)
    ok = size > _TINY
    divisor = np.where(ok, size, 1.0)
    out = [c / divisor for c in t]
    short = np.flatnonzero(~ok)
    if len(short):
        fallback = any_perpendicular([c[short] for c in n])
        for o, f in zip(out, fallback):
            o[short] = f
    return out
