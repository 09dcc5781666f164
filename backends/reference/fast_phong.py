"""Shading a triangle mesh in screen space five ways, after Bishop and Weimer, "Fast Phong
Shading" (SIGGRAPH 1986): flat, Gouraud, Phong (the normal interpolated and normalised at
every pixel), Duff's form (the dot product and the squared length by forward differences,
then a division and a square root a pixel; eye at infinity) and their Taylor form, a second-order expansion of the reflection equation about
each triangle's centre evaluated along scanlines by forward differences (2 additions a pixel
for the diffuse term, as many for the specular dot product, then a power-table lookup), with
the eye at infinity or at a finite distance.

Everything is in screen space, as in the paper: a pixel's (x, y) is measured from the
triangle's centroid; the vertex normals N (and for a finite eye the vertex eye vectors V) are
interpolated linearly in x and y, N(x, y) = A x + B y + C, with no perspective correction.

    intensity = ambient + kd N.L / |N| + ks table[(N.H / (|N| |H|))]

The Taylor coefficients: the paper's closed forms for the infinite eye are those of
`taylor_quotient` below with numerator a x + b y + c and denominator
d x^2 + e x y + f y^2 + g x + h y + i; for the finite eye the denominator is the product of
the two quadratics |N|^2 |H|^2 and the numerator N.H is quadratic, and the paper's T0..T5 are
again the second-order expansion of numerator / sqrt(denominator). `taylor_quotient` computes
that expansion for any quadratic numerator and quartic-truncated denominator, so both forms
come from one function (tests check it against the paper's printed infinite-eye formulas).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

MODES = ("flat", "gouraud", "phong", "taylor", "duff")

# Polynomial coefficients in x, y up to second order, in this order:
# (1, x, y, x^2, xy, y^2)
_TERMS = 6


@dataclass
class Light:
    """A directional light L (unit, toward the light), the eye, and the reflection constants.
    `eye` is a unit direction toward the eye (infinite eye) or None for a finite eye, whose
    per-vertex eye vectors are given to `shade`."""

    direction: np.ndarray
    eye: np.ndarray | None = None
    ambient: float = 0.1
    diffuse: float = 0.6
    specular: float = 0.3
    exponent: float = 20.0
    table_size: int = 1024


def poly_mul(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Product of two (T, 6) second-order polynomials, truncated at second order."""
    c0, cx, cy, cxx, cxy, cyy = (p[:, k] for k in range(6))
    d0, dx, dy, dxx, dxy, dyy = (q[:, k] for k in range(6))
    return np.stack([c0 * d0, c0 * dx + cx * d0, c0 * dy + cy * d0,
                     c0 * dxx + cx * dx + cxx * d0,
                     c0 * dxy + cx * dy + cy * dx + cxy * d0,
                     c0 * dyy + cy * dy + cyy * d0], axis=1)


def linear_dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(T, 6) polynomial of the dot product of two linearly interpolated vectors, each given
    as (A, B, C): (T, 3, 3) rows = the x, y and constant coefficients."""
    ax, ay, a0 = a[:, 0], a[:, 1], a[:, 2]
    bx, by, b0 = b[:, 0], b[:, 1], b[:, 2]
    dot = lambda u, v: np.sum(u * v, axis=-1)   # noqa: E731
    return np.stack([dot(a0, b0), dot(ax, b0) + dot(a0, bx), dot(ay, b0) + dot(a0, by),
                     dot(ax, bx), dot(ax, by) + dot(ay, bx), dot(ay, by)], axis=1)


def taylor_quotient(numerator: np.ndarray, denominator: np.ndarray) -> np.ndarray:
    """Second-order Taylor expansion about (0, 0) of numerator / sqrt(denominator), both (T, 6)
    polynomials (the denominator's terms beyond second order do not reach second order of the
    result). Returns (T, 6): T0, T2 (x), T1 (y), T5 (x^2), T4 (xy), T3 (y^2) in the paper's
    names. q^(-1/2) = q0^(-1/2) (1 - delta / 2 + 3 delta^2 / 8), delta = (q - q0) / q0."""
    q0 = denominator[:, 0]
    delta = denominator / q0[:, None]
    delta[:, 0] = 0.0
    inv_sqrt = -0.5 * delta + 0.375 * poly_mul(delta, delta)
    inv_sqrt[:, 0] += 1.0
    return poly_mul(numerator, inv_sqrt) / np.sqrt(q0)[:, None]


def interpolation_planes(xy: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per triangle the centroid (T, 2) and (A, B, C) of the plane through the three vertex
    values, in coordinates measured from the centroid: (T, 3, K) for (T, 3, K) values."""
    centre = xy.mean(axis=1)
    rel = xy - centre[:, None]
    m = np.concatenate([rel, np.ones(rel.shape[:2] + (1,))], axis=2)      # (T, 3, 3)
    return centre, np.linalg.solve(m, values)


@dataclass
class Spans:
    """The pixels the triangles cover, grouped into scanline spans. Per span: its triangle,
    first pixel's offset from the triangle's centroid (x0, y) and length; per pixel: triangle,
    pixel x and y, offset from the centroid."""

    span_tri: np.ndarray
    span_dx: np.ndarray
    span_dy: np.ndarray
    span_len: np.ndarray
    tri: np.ndarray
    x: np.ndarray
    y: np.ndarray
    dx: np.ndarray
    dy: np.ndarray

    @property
    def first(self) -> np.ndarray:
        """Index of each span's first pixel."""
        return np.cumsum(self.span_len) - self.span_len


def scan(xy: np.ndarray, width: int, height: int) -> tuple[Spans, np.ndarray]:
    """Scan-convert (T, 3, 2) screen triangles: pixel (px, py) is covered when its centre
    (px + 0.5, py + 0.5) is inside (top-left rule not needed here: shared edges may repeat a
    pixel, which only re-shades it). Returns the spans and the centroids."""
    t_count = len(xy)
    centre = xy.mean(axis=1)
    ymin = np.clip(np.ceil(xy[:, :, 1].min(axis=1) - 0.5), 0, height).astype(np.int64)
    ymax = np.clip(np.floor(xy[:, :, 1].max(axis=1) - 0.5), -1, height - 1).astype(np.int64)
    rows = np.maximum(ymax - ymin + 1, 0)
    tri = np.repeat(np.arange(t_count), rows)
    first = np.repeat(np.cumsum(rows) - rows, rows)
    y = ymin[tri] + np.arange(len(tri)) - first
    yc = y + 0.5
    # the span: intersect the scanline with the three edges
    lo = np.full(len(tri), np.inf)
    hi = np.full(len(tri), -np.inf)
    for a, b in ((0, 1), (1, 2), (2, 0)):
        pa, pb = xy[tri, a], xy[tri, b]
        dy_edge = pb[:, 1] - pa[:, 1]
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (yc - pa[:, 1]) / dy_edge
        ok = (dy_edge != 0) & (t >= 0) & (t <= 1)
        xe = pa[:, 0] + t * (pb[:, 0] - pa[:, 0])
        lo = np.where(ok, np.minimum(lo, xe), lo)
        hi = np.where(ok, np.maximum(hi, xe), hi)
    x0 = np.clip(np.ceil(lo - 0.5), 0, width).astype(np.int64)
    x1 = np.clip(np.floor(hi - 0.5), -1, width - 1).astype(np.int64)
    length = np.where(np.isfinite(lo), np.maximum(x1 - x0 + 1, 0), 0)
    keep = length > 0
    tri, y, x0, length = tri[keep], y[keep], x0[keep], length[keep]
    p_tri = np.repeat(tri, length)
    offsets = np.arange(length.sum()) - np.repeat(np.cumsum(length) - length, length)
    px = np.repeat(x0, length) + offsets
    py = np.repeat(y, length)
    span_dx, span_dy = x0 + 0.5 - centre[tri, 0], y + 0.5 - centre[tri, 1]
    return Spans(tri, span_dx, span_dy, length, p_tri, px, py,
                 px + 0.5 - centre[p_tri, 0], py + 0.5 - centre[p_tri, 1]), centre


def forward_differences(coeffs: np.ndarray, spans: Spans) -> np.ndarray:
    """Evaluate P = T0 + T2 x + T1 y + T5 x^2 + T4 xy + T3 y^2 at every pixel the way the paper
    does: per span the value P and the first difference D = P(x + 1) - P(x) at its first
    pixel, then along the span two additions a pixel (P += D; D += 2 T5). The additions are
    two running sums over all pixels; where a span starts, the increment also cancels what the
    previous span left in the sum (its last D and P, known per span in closed form)."""
    c = coeffs[spans.span_tri]
    x, y, n = spans.span_dx, spans.span_dy, spans.span_len
    p0 = c[:, 0] + c[:, 1] * x + c[:, 2] * y + c[:, 3] * x * x + c[:, 4] * x * y + c[:, 5] * y * y
    d0 = c[:, 1] + c[:, 3] * (2 * x + 1) + c[:, 4] * y
    second = 2.0 * c[:, 3]
    d_last = d0 + (n - 1) * second                   # D after the span's last pixel's step
    p_last = p0 + (n - 1) * d0 + 0.5 * (n - 1) * (n - 2) * second
    first = spans.first
    d_inc = np.repeat(second, n)
    d_inc[first] = d0 - np.concatenate([[0.0], d_last[:-1]])
    d = np.cumsum(d_inc)                             # D at each pixel (before its step)
    p_inc = np.empty_like(d)
    p_inc[1:] = d[:-1]
    p_inc[first] = p0 - np.concatenate([[0.0], p_last[:-1]])
    return np.cumsum(p_inc)


def power_table(exponent: float, size: int) -> np.ndarray:
    """The exponentiation table: entry k holds (k / (size - 1)) ** exponent."""
    return np.linspace(0.0, 1.0, size) ** exponent


def table_lookup(table: np.ndarray, value: np.ndarray) -> np.ndarray:
    """The nearest entry for values in [0, 1] (the series is scaled to address it directly)."""
    k = np.rint(np.clip(value, 0.0, 1.0) * (len(table) - 1)).astype(np.int64)
    return table[k]


@dataclass
class Prepared:
    """What every mode shares: the covered pixels and the per-triangle interpolation planes of
    the vertex normals (and eye vectors), (T, 3, 3) rows A, B, C."""

    xy: np.ndarray
    normals: np.ndarray
    eye_vectors: np.ndarray | None
    spans: Spans
    n_plane: np.ndarray
    v_plane: np.ndarray | None
    size: tuple[int, int]


def prepare(xy: np.ndarray, normals: np.ndarray, size: tuple[int, int],
            eye_vectors: np.ndarray | None = None) -> Prepared:
    """Scan-convert triangles (T, 3, 2) in pixels with vertex normals (T, 3, 3) and, for a
    finite eye, vertex vectors toward the eye (T, 3, 3)."""
    xy, normals = np.asarray(xy, np.float64), np.asarray(normals, np.float64)
    spans, _ = scan(xy, *size)
    _, n_plane = interpolation_planes(xy, normals)
    v_plane = None
    if eye_vectors is not None:
        eye_vectors = np.asarray(eye_vectors, np.float64)
        _, v_plane = interpolation_planes(xy, eye_vectors)
    return Prepared(xy, normals, eye_vectors, spans, n_plane, v_plane, size)


def shade(xy: np.ndarray, normals: np.ndarray, light: Light, mode: str, size: tuple[int, int],
          eye_vectors: np.ndarray | None = None) -> np.ndarray:
    """(H, W) intensities of the triangles; 0 where nothing is drawn (`prepare`, then
    `shade_prepared`)."""
    return shade_prepared(prepare(xy, normals, size, eye_vectors), light, mode)


def pixel_values(prep: Prepared, light: Light, mode: str) -> np.ndarray:
    """The intensity of every covered pixel (in `prep.spans` order) by `mode`."""
    if mode not in MODES:
        raise ValueError(f"mode {mode!r} is not one of {MODES}")
    spans, n_plane, v_plane = prep.spans, prep.n_plane, prep.v_plane
    L = np.asarray(light.direction, np.float64)
    finite = light.eye is None
    if finite and v_plane is None:
        raise ValueError("a finite eye needs the vertices' eye vectors")
    if mode == "taylor":
        table = power_table(light.exponent, light.table_size)
        constant = np.array([0.0, 0.0, 1.0])[None, :, None]
        l_plane = np.broadcast_to(L, n_plane.shape) * constant
        n_sq = linear_dot(n_plane, n_plane)
        diffuse = forward_differences(taylor_quotient(linear_dot(n_plane, l_plane), n_sq), spans)
        if finite:
            # the paper's H(x, y) = V(x, y) + L, V interpolating the (unit) vertex eye vectors
            h_plane = v_plane + l_plane
            denominator = poly_mul(n_sq, linear_dot(h_plane, h_plane))
        else:
            h = L + np.asarray(light.eye, np.float64)
            h_plane = np.broadcast_to(h / np.linalg.norm(h), n_plane.shape) * constant
            denominator = n_sq
        n_dot_h = forward_differences(taylor_quotient(linear_dot(n_plane, h_plane), denominator),
                                      spans)
        return (light.ambient + light.diffuse * np.maximum(diffuse, 0.0)
                + light.specular * table_lookup(table, n_dot_h))
    if mode == "duff":
        # Duff's form (the paper's "Duff" row): N.L and |N|^2 of the interpolated normal,
        # linear and quadratic in x and y, by forward differences, then per pixel one
        # division and one square root -- exact where the series approximates
        if finite:
            raise ValueError("Duff's form is timed, as in the paper, with the eye at infinity")
        table = power_table(light.exponent, light.table_size)
        constant = np.array([0.0, 0.0, 1.0])[None, :, None]
        l_plane = np.broadcast_to(L, n_plane.shape) * constant
        h = L + np.asarray(light.eye, np.float64)
        h_plane = np.broadcast_to(h / np.linalg.norm(h), n_plane.shape) * constant
        inv_length = 1.0 / np.sqrt(forward_differences(linear_dot(n_plane, n_plane), spans))
        diffuse = forward_differences(linear_dot(n_plane, l_plane), spans) * inv_length
        n_dot_h = forward_differences(linear_dot(n_plane, h_plane), spans) * inv_length
        return (light.ambient + light.diffuse * np.maximum(diffuse, 0.0)
                + light.specular * table_lookup(table, n_dot_h))
    if mode == "flat":          # the normal (and eye vector) at the triangle's centre
        n = n_plane[:, 2][spans.tri]
        v = v_plane[:, 2][spans.tri] if finite else None
        return _reflect(n, v, L, light)
    if mode == "gouraud":       # intensities at the vertices, interpolated
        v = prep.eye_vectors.reshape(-1, 3) if finite else None
        lit = _reflect(prep.normals.reshape(-1, 3), v, L, light).reshape(-1, 3, 1)
        c = interpolation_planes(prep.xy, lit)[1][..., 0][spans.tri]
        return c[:, 0] * spans.dx + c[:, 1] * spans.dy + c[:, 2]
    c = n_plane[spans.tri]      # phong: the normal interpolated, normalised at each pixel
    n = c[:, 0] * spans.dx[:, None] + c[:, 1] * spans.dy[:, None] + c[:, 2]
    v = None
    if finite:
        cv = v_plane[spans.tri]
        v = cv[:, 0] * spans.dx[:, None] + cv[:, 1] * spans.dy[:, None] + cv[:, 2]
    return _reflect(n, v, L, light)


def shade_prepared(prep: Prepared, light: Light, mode: str) -> np.ndarray:
    """(H, W) intensities; 0 where nothing is drawn."""
    width, height = prep.size
    out = np.zeros((height, width))
    out[prep.spans.y, prep.spans.x] = pixel_values(prep, light, mode)
    return out


def _reflect(n: np.ndarray, v: np.ndarray | None, L: np.ndarray, light: Light) -> np.ndarray:
    """Phong's reflection equation with normalised vectors (exact pow)."""
    n = n / np.linalg.norm(n, axis=-1, keepdims=True)
    if v is None:
        h = L + np.asarray(light.eye, np.float64)
        h = np.broadcast_to(h / np.linalg.norm(h), n.shape)
    else:
        h = v + L
        h = h / np.linalg.norm(h, axis=-1, keepdims=True)
    diffuse = np.maximum(np.sum(n * L, axis=-1), 0.0)
    n_dot_h = np.clip(np.sum(n * h, axis=-1), 0.0, 1.0)
    return light.ambient + light.diffuse * diffuse + light.specular * n_dot_h ** light.exponent


# -- Measuring the series against exact Phong (tests/looks/test_fast_phong.py, and
# benchmarks/bench_fast_phong.py --errors print the whole curve)

SPREADS = ("cone", "strip")


def spread_normals(span_deg: float, spread: str = "cone",
                   axis: tuple[float, float, float] = (0.0, 0.0, 1.0)) -> np.ndarray:
    """(3, 3) unit vertex normals about `axis` that are at most `span_deg` apart: 'cone' tilts
    all three equally, 120 degrees apart in azimuth, so every pair is `span_deg` apart (a
    triangle of a sphere); 'strip' bends in one direction only, vertex 0 at +span/2 and
    vertices 1 and 2 at -span/2 (a triangle of a cylinder)."""
    a = np.asarray(axis, np.float64) / np.linalg.norm(axis)
    u = np.cross(a, [1.0, 0.0, 0.0]) if abs(a[0]) < 0.9 else np.cross(a, [0.0, 1.0, 0.0])
    u /= np.linalg.norm(u)
    w = np.cross(a, u)
    if spread == "cone":
        # cos(span) = cos^2 t - sin^2 t / 2 for two normals tilted by t, 120 degrees apart
        t = np.arccos(np.sqrt((np.cos(np.radians(span_deg)) + 0.5) / 1.5))
        return np.stack([np.cos(t) * a + np.sin(t) * (np.cos(g) * u + np.sin(g) * w)
                         for g in np.radians([90.0, 210.0, 330.0])])
    if spread == "strip":
        h = np.radians(span_deg) / 2
        return np.stack([np.cos(h) * a + s * np.sin(h) * u for s in (1.0, -1.0, -1.0)])
    raise ValueError(f"spread must be one of {SPREADS}, got {spread!r}")


def series_error(normals: np.ndarray, light: Light, radius: float = 40.0) -> float:
    """The largest |Taylor - Phong| (intensity units) over an equilateral screen triangle of
    circumradius `radius` pixels with vertex normals (3, 3), eye at infinity. The error does
    not depend on the triangle's size (both are functions of the barycentric position); the
    size only sets how densely it is sampled."""
    angles = np.radians([90.0, 210.0, 330.0])
    xy = radius + 5.0 + radius * np.stack([np.cos(angles), -np.sin(angles)], axis=-1)
    side = int(2 * radius + 10)
    prep = prepare(xy[None], np.asarray(normals, np.float64)[None], (side, side))
    return float(np.abs(pixel_values(prep, light, "taylor")
                        - pixel_values(prep, light, "phong")).max())
