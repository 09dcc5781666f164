"""ShadeMode = Phong in the reference back end: the pass's fixed-function lighting
(`PassProgram.lighting`) shaded by Bishop and Weimer's Taylor form ("Fast Phong Shading",
SIGGRAPH 1986; `fast_phong`), in place of the fragment program's exact per-pixel lighting.

Per triangle the rasteriser kept (clipped, culled), each light's N.L / |N| and
N.H / (|N| |H|) are expanded to second order about the triangle's centroid in pixels, from the
vertex normals and, for a local viewer (D3DRS_LOCALVIEWER), the vertex vectors toward the eye
(the paper's finite eye: V interpolated, H = V + L); without it H is constant (the paper's eye
at infinity, D3D's (0, 0, -1)). The expansion is made of the vertex values divided by w: a
perspective-correct N is (that plane) / (the plane of 1/w), and the 1/w plane cancels from
N.L / |N| (and, with L times it added to V's, from the finite eye's quotient), so the series
is that of the perspective-correct Phong the GL back end draws, not of a screen-space one.
The exponent is the paper's table: 8192 entries (their 8 KB table, within 1 % up to a power
of about 164), read at the nearest entry.

Each fragment evaluates its triangle's polynomials at its offset from the centroid. The paper
steps them along scanlines by forward differences (`fast_phong.forward_differences`, two
additions a pixel, tested equal to this polynomial); the rasteriser here emits 2x2 quads, not
spans, so the same polynomial is evaluated directly.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from backends.reference.fast_phong import (interpolation_planes, linear_dot, poly_mul,
                                           power_table, taylor_quotient)
from effects.program.passprogram import PixelLighting

TABLE_ENTRIES = 8192


@dataclass
class TaylorLighting:
    """Per kept triangle its centroid in pixels (2, T) and, per light, the series of N.L / |N|
    and of N.H / (|N| |H|), (12, T): terms 1, x, y, x^2, xy, y^2 of each, float32 (the
    component-major layout makes every term one contiguous row)."""

    lighting: PixelLighting
    centre_t: np.ndarray
    series: list[np.ndarray]
    table: np.ndarray


def _constant_plane(v: np.ndarray, count: int) -> np.ndarray:
    """(T, 3, 3) planes of a constant vector: A = B = 0, C = v."""
    plane = np.zeros((count, 3, 3))
    plane[:, 2] = v
    return plane


def prepare(lighting: PixelLighting, xy: np.ndarray, inv_w: np.ndarray, normal: np.ndarray,
            position: np.ndarray | None) -> TaylorLighting:
    """The series of the triangles with screen vertices `xy` (T, 3, 2) in pixels, 1/w (T, 3),
    camera-space vertex normals and (local viewer only) positions (T, 3, 3)."""
    count = len(xy)
    w = inv_w[..., None]
    centre, n_plane = interpolation_planes(xy, normal * w)
    n_sq = linear_dot(n_plane, n_plane)
    one_plane = None
    if lighting.local_viewer:
        to_eye = -position / np.linalg.norm(position, axis=-1, keepdims=True)
        _, v_plane = interpolation_planes(xy, to_eye * w)
        _, one_plane = interpolation_planes(xy, np.broadcast_to(w, xy.shape[:2] + (1,)))
    diffuse, specular = [], []
    for light in lighting.lights:
        to_light = np.asarray(light.direction, np.float64)
        l_plane = _constant_plane(to_light, count)
        diffuse.append(taylor_quotient(linear_dot(n_plane, l_plane), n_sq))
        if one_plane is None:
            h = to_light + np.array([0.0, 0.0, -1.0])
            h_plane = _constant_plane(h / np.linalg.norm(h), count)
            denominator = n_sq
        else:       # (V + L) / w: V's plane plus L times the plane of 1/w
            h_plane = v_plane + one_plane * to_light
            denominator = poly_mul(n_sq, linear_dot(h_plane, h_plane))
        specular.append(taylor_quotient(linear_dot(n_plane, h_plane), denominator))
    table = power_table(lighting.power, TABLE_ENTRIES).astype(np.float32)
    series = [np.ascontiguousarray(np.concatenate([d, sp], axis=1).T, np.float32)
              for d, sp in zip(diffuse, specular)]
    return TaylorLighting(lighting, np.ascontiguousarray(centre.T, np.float32), series, table)


def _runs(tri: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The distinct triangles of `tri` and how many rows each has: the rasteriser emits a
    triangle's rows together, so a per-triangle value reaches its rows by a repeat (a copy
    per run, faster than a gather per row)."""
    if len(tri) == 0:
        return tri, np.zeros(0, np.int64)
    starts = np.flatnonzero(np.diff(tri)) + 1
    bounds = np.concatenate([[0], starts, [len(tri)]])
    return tri[bounds[:-1]], np.diff(bounds)


def shade(taylor: TaylorLighting, tri: np.ndarray, x: np.ndarray, y: np.ndarray
          ) -> tuple[np.ndarray, np.ndarray]:
    """(diffuse, specular), (N, 4) float32 each and saturated, of fragments of triangles `tri`
    at pixels (x, y): the D3D lighting sums of `PixelLighting` with the series for N.L / |N|
    and N.H / (|N| |H|) and the table for the power."""
    lighting = taylor.lighting
    which, counts = _runs(tri)
    per_row = lambda a: np.repeat(a[:, which], counts, axis=1)  # noqa: E731  (K, T) -> (K, N)
    centre = per_row(taylor.centre_t)
    dx = x.astype(np.float32) - centre[0]
    dy = y.astype(np.float32) - centre[1]
    n = len(tri)
    lit_diffuse = np.zeros((3, n), np.float32)
    lit_specular = np.zeros((4, n), np.float32)
    for k, light in enumerate(lighting.lights):
        c = per_row(taylor.series[k])                  # (12, N): diffuse then specular terms
        n_dot_l = _poly(c[:6], dx, dy)
        lit = np.clip(n_dot_l, 0.0, 1.0)
        for j in range(3):
            lit_diffuse[j] += lit * np.float32(light.diffuse[j])
        if lighting.specular_value is not None:
            n_dot_h = _poly(c[6:], dx, dy)
            term = taylor.table[_table_index(n_dot_h, len(taylor.table))]
            term[(n_dot_l <= 0) | (n_dot_h <= 0)] = 0.0
            for j in range(4):
                lit_specular[j] += term * np.float32(light.specular[j])
    diffuse = np.empty((n, 4), np.float32)
    specular = np.empty((n, 4), np.float32)
    for j in range(3):
        diffuse[:, j] = lighting.base[j] + lighting.material_diffuse[j] * lit_diffuse[j]
    diffuse[:, 3] = lighting.material_diffuse[3]
    for j in range(4):
        specular[:, j] = lighting.material_specular[j] * lit_specular[j]
    np.clip(diffuse, 0.0, 1.0, out=diffuse)
    np.clip(specular, 0.0, 1.0, out=specular)
    return diffuse, specular


def _poly(c: np.ndarray, dx: np.ndarray, dy: np.ndarray) -> np.ndarray:
    """c0 + c1 x + c2 y + c3 x^2 + c4 xy + c5 y^2, row by row, as (c1 + c3 x + c4 y) x +
    (c2 + c5 y) y + c0."""
    out = c[3] * dx
    out += c[4] * dy
    out += c[1]
    out *= dx
    inner = c[5] * dy
    inner += c[2]
    inner *= dy
    out += inner
    out += c[0]
    return out


def _table_index(value: np.ndarray, entries: int) -> np.ndarray:
    """The nearest entry of an `entries` table over [0, 1] (as `fast_phong.table_lookup`)."""
    k = np.clip(value, 0.0, 1.0) * np.float32(entries - 1)
    return np.rint(k, out=k).astype(np.int32)
