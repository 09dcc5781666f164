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

from backends.reference.fast_phong import (linear_dot, poly_mul, interpolation_planes,
                                           power_table, table_lookup, taylor_quotient)
from effects.passprogram import PixelLighting

TABLE_ENTRIES = 8192


@dataclass
class TaylorLighting:
    """Per kept triangle its centroid (T, 2) in pixels and, per light, the (T, 6) series of
    N.L / |N| and of N.H / (|N| |H|) (terms 1, x, y, x^2, xy, y^2)."""

    lighting: PixelLighting
    centre: np.ndarray
    diffuse: list[np.ndarray]
    specular: list[np.ndarray]
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
    table = power_table(lighting.power, TABLE_ENTRIES)
    return TaylorLighting(lighting, centre, diffuse, specular, table)


def _evaluate(series: np.ndarray, tri: np.ndarray, dx: np.ndarray, dy: np.ndarray) -> np.ndarray:
    c = series[tri]
    return c[:, 0] + dx * (c[:, 1] + c[:, 3] * dx + c[:, 4] * dy) + dy * (c[:, 2] + c[:, 5] * dy)


def shade(taylor: TaylorLighting, tri: np.ndarray, x: np.ndarray, y: np.ndarray
          ) -> tuple[np.ndarray, np.ndarray]:
    """(diffuse, specular), (N, 4) float32 each and saturated, of fragments of triangles `tri`
    at pixels (x, y): the D3D lighting sums of `PixelLighting` with the series for N.L / |N|
    and N.H / (|N| |H|) and the table for the power."""
    lighting = taylor.lighting
    dx = x - taylor.centre[tri, 0]
    dy = y - taylor.centre[tri, 1]
    n = len(tri)
    lit_diffuse = np.zeros((n, 4))
    lit_specular = np.zeros((n, 4))
    for light, d_series, s_series in zip(lighting.lights, taylor.diffuse, taylor.specular):
        n_dot_l = _evaluate(d_series, tri, dx, dy)
        lit_diffuse[:, :3] += np.clip(n_dot_l, 0.0, 1.0)[:, None] * light.diffuse[:3]
        if lighting.specular_value is not None:
            n_dot_h = _evaluate(s_series, tri, dx, dy)
            term = table_lookup(taylor.table, n_dot_h) * ((n_dot_l > 0) & (n_dot_h > 0))
            lit_specular += term[:, None] * np.asarray(light.specular)
    diffuse = np.asarray(lighting.base, np.float64) + np.asarray(lighting.material_diffuse) * lit_diffuse
    diffuse[:, 3] = lighting.material_diffuse[3]
    specular = np.asarray(lighting.material_specular, np.float64) * lit_specular
    return (np.clip(diffuse, 0.0, 1.0).astype(np.float32),
            np.clip(specular, 0.0, 1.0).astype(np.float32))
