"""Bishop and Weimer, "Fast Phong Shading" (SIGGRAPH 1986), in the reference back end's
screen-space shader (backends/reference/fast_phong.py): the Taylor form against exact Phong,
as the triangle's normals spread; the forward differences; the exponent-table sizes; and the
printed coefficient formulas."""
from __future__ import annotations

import numpy as np
import pytest

from backends.reference import fast_phong as F

L = np.array([0.3, 0.5, 0.81]) / np.linalg.norm([0.3, 0.5, 0.81])
EYE = np.array([0.0, 0.0, 1.0])


def triangle(span_deg: float, axis=(0.0, 0.3, 1.0)) -> tuple[np.ndarray, np.ndarray]:
    """An equilateral triangle 104 pixels a side whose three vertex normals are tilted about
    `axis` so that any two of them are `span_deg` apart."""
    angles = np.radians([90.0, 210.0, 330.0])
    xy = 80.0 + 60.0 * np.stack([np.cos(angles), -np.sin(angles)], axis=-1)
    a = np.asarray(axis) / np.linalg.norm(axis)
    u = np.cross(a, [1.0, 0.0, 0.0])
    u /= np.linalg.norm(u)
    w = np.cross(a, u)
    # two normals tilted by t, 120 degrees apart in azimuth: cos(span) = cos^2 t - sin^2 t / 2
    t = np.arccos(np.sqrt((np.cos(np.radians(span_deg)) + 0.5) / 1.5))
    n = np.stack([np.cos(t) * a + np.sin(t) * (np.cos(g) * u + np.sin(g) * w) for g in angles])
    return xy[None], n[None]


def taylor_error(span_deg: float, light: F.Light) -> float:
    xy, n = triangle(span_deg)
    prep = F.prepare(xy, n, (160, 160))
    return float(np.abs(F.pixel_values(prep, light, "taylor")
                        - F.pixel_values(prep, light, "phong")).max() * 255)


DIFFUSE = F.Light(L, eye=EYE, ambient=0.05, diffuse=0.9, specular=0.0)
FULL = F.Light(L, eye=EYE)          # ambient 0.1, diffuse 0.6, specular 0.3, exponent 20


def test_taylor_form_is_exact_phong_on_gently_curved_triangles_and_grows_as_they_bend():
    # Measured (max over the triangle, in 1/255): diffuse 0.04, 0.39, 1.6, 4.4, 10, 21 at
    # spans 10..60 degrees; with specular (1 KB table) 0.7, 0.9, 2.4, 5.4, 9.1, 14.3. So the
    # Taylor form is Phong within 2/255 up to a span of about 30 degrees (20 with the
    # specular); past that the error grows as about the third power of the span (the
    # remainder of a second-order series) and at the paper's 60 degrees it is plainly visible.
    errors = {s: taylor_error(s, DIFFUSE) for s in (10, 20, 30, 60)}
    assert errors[10] < 0.2 and errors[20] < 1.0 and errors[30] <= 2.0
    assert errors[60] > 10.0
    assert errors[60] / errors[30] > 8.0            # at least the cube of the span ratio 2
    assert taylor_error(20, FULL) <= 2.0


def test_finite_eye_taylor_matches_finite_eye_phong():
    xy, n = triangle(20.0)
    eye = np.array([80.0, 80.0, 300.0])
    points = np.concatenate([xy[0], np.zeros((3, 1))], axis=1)
    v = eye - points
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    prep = F.prepare(xy, n, (160, 160), v[None])
    light = F.Light(L, eye=None)
    error = np.abs(F.pixel_values(prep, light, "taylor") - F.pixel_values(prep, light, "phong"))
    assert error.max() * 255 <= 2.0


def test_forward_differences_evaluate_the_polynomial():
    xy, n = triangle(40.0)
    prep = F.prepare(xy, n, (160, 160))
    rng = np.random.default_rng(3)
    coeffs = rng.normal(size=(1, 6)) * np.array([1, 1e-2, 1e-2, 1e-4, 1e-4, 1e-4])
    x, y = prep.spans.dx, prep.spans.dy
    direct = (coeffs[0, 0] + coeffs[0, 1] * x + coeffs[0, 2] * y + coeffs[0, 3] * x * x
              + coeffs[0, 4] * x * y + coeffs[0, 5] * y * y)
    assert np.abs(F.forward_differences(coeffs, prep.spans) - direct).max() < 1e-9
    assert len(x) > 4000 and (prep.spans.span_len > 1).all()


def test_the_printed_infinite_eye_coefficients():
    # The paper's T0..T5 for (a x + b y + c) / sqrt(d x^2 + e xy + f y^2 + g x + h y + i).
    a, b, c, d, e, f, g, h, i = np.random.default_rng(7).uniform(0.2, 1.0, 9)
    r = np.sqrt(i)
    printed = {"T0": c / r, "T1": (2 * b * i - c * h) / (2 * i * r),
               "T2": (2 * a * i - c * g) / (2 * i * r),
               "T3": (3 * c * h * h - 4 * c * f * i - 4 * b * h * i) / (8 * i * i * r),
               "T4": (3 * c * g * h - 2 * c * e * i - 2 * b * g * i - 2 * a * h * i) / (4 * i * i * r),
               "T5": (3 * c * g * g - 4 * c * d * i - 4 * a * g * i) / (8 * i * i * r)}
    got = F.taylor_quotient(np.array([[c, a, b, 0, 0, 0]]), np.array([[i, g, h, d, e, f]]))[0]
    ours = {"T0": got[0], "T2": got[1], "T1": got[2], "T5": got[3], "T4": got[4], "T3": got[5]}
    for name, value in printed.items():
        assert ours[name] == pytest.approx(value, rel=1e-12), name


def largest_exponent(entries: int, tolerance: float = 0.01) -> float:
    """The largest exponent n for which a table of `entries` values x^n, read at the nearest
    entry, is within `tolerance` of x^n everywhere in [0, 1]."""
    x = np.linspace(0.0, 1.0, 200001)

    def error(n: float) -> float:
        return float(np.abs(F.table_lookup(F.power_table(n, entries), x) - x ** n).max())

    lo, hi = 1.0, 1000.0
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if error(mid) < tolerance else (lo, mid)
    return lo


def test_the_exponent_table_sizes():
    # "A table of 1K bytes will allow exponentiation to powers up to 20 with less than 1
    # percent error and a table of 8K bytes allows powers up to 164": a byte an entry, read
    # at the nearest entry, the error is about n / (2 entries) near x = 1 (20.5 and 164);
    # measured exactly: 20.7 and 167.5.
    assert largest_exponent(1024) == pytest.approx(20.5, abs=0.5)
    assert largest_exponent(8192) == pytest.approx(164, abs=4)


def test_taylor_is_closer_to_phong_than_flat_or_gouraud():
    xy, n = triangle(30.0)
    prep = F.prepare(xy, n, (160, 160))
    exact = F.pixel_values(prep, FULL, "phong")
    err = {m: np.abs(F.pixel_values(prep, FULL, m) - exact).max() * 255
           for m in ("flat", "gouraud", "taylor")}
    assert err["taylor"] * 4 < min(err["flat"], err["gouraud"])
