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


def light_directions(count: int = 24, within: float = 75.0) -> np.ndarray:
    """`count` unit vectors spread evenly (a Fibonacci spiral) over the cap within `within`
    degrees of +z, the triangles' mean normal: every way a light (or half vector) can face a
    lit triangle."""
    k = np.arange(count) + 0.5
    z = 1 - (1 - np.cos(np.radians(within))) * k / count
    phi = np.pi * (1 + 5 ** 0.5) * k
    r = np.sqrt(1 - z * z)
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)


def curve(spans, spread: str, exponent: float | None = None, table: int = 1024) -> dict:
    """Per span (degrees) the median and the largest, over the light directions, of the
    triangle's largest |Taylor - Phong| in 1/255: the diffuse term alone (kd 1, no ambient;
    `exponent` None) or the specular alone (ks 1, H swept over the same directions, the
    power from a `table`-entry table)."""
    out = {}
    for span in spans:
        normals = F.spread_normals(span, spread)
        errors = []
        for d in light_directions():
            if exponent is None:
                light = F.Light(d, eye=EYE, ambient=0.0, diffuse=1.0, specular=0.0)
            else:       # eye = L makes H = L
                light = F.Light(d, eye=d, ambient=0.0, diffuse=0.0, specular=1.0,
                                exponent=exponent, table_size=table)
            errors.append(F.series_error(normals, light) * 255)
        out[span] = (float(np.median(errors)), float(np.max(errors)))
    return out


def growth(errors: dict, a: float, b: float, which: int) -> float:
    """The power of the span the error grows as between spans a and b."""
    return float(np.log(errors[b][which] / errors[a][which]) / np.log(b / a))


def test_diffuse_series_error_against_the_span_of_the_normals():
    # "For polygons with more than about 60 degrees of curvature, this new expansion will
    # produce shadings that are noticeably different from Phong shading." The expansion is of
    # the whole N.L/|N| (the paper's (ax + by + c) / sqrt(dx^2 + ... + i), T0..T5 checked
    # below), about the centroid; it does not depend on the length of N or L (the quotient
    # is scale-free), nor on the triangle's size. Measured (median / worst light, 1/255),
    # normals pairwise `span` apart ('cone', a sphere's triangle):
    #   10: 0.09/0.11  20: 0.73/0.94  25: 1.44/1.88  30: 2.55/3.29  40: 6.3/8.4
    #   50: 12.8/16.4  60: 23.0/32.2  75: 43.6/72.3  90: 75/136
    # and bent one way only ('strip', a cylinder's): 0.08/0.16, 0.64/1.33, 1.27/2.62,
    # 2.22/4.57, 5.4/10.1, 10.7/20.6, 17.5/37.6 at 10..60. So the series is Phong within
    # 2/255 up to a span of 25 degrees (sphere; about 22 for the worst light on a cylinder),
    # and grows as the cube of the span (the remainder of a second-order series: a power of
    # 3.0-3.2 from 20 to 60 degrees); at the paper's 60 degrees it is 7-13 % of full scale,
    # plainly visible, so "noticeably different past 60" holds, while "indistinguishable"
    # below it holds only to about 25 degrees at 8 bits.
    cone = curve((10, 20, 25, 30, 60), "cone")
    assert cone[10][1] < 0.2 and cone[20][1] < 1.0 and cone[25][1] <= 2.0 < cone[30][1]
    assert 18.0 < cone[60][0] < 28.0 and 25.0 < cone[60][1] < 40.0
    assert 3.0 <= growth(cone, 20, 60, 0) <= 3.3 and 3.0 <= growth(cone, 20, 60, 1) <= 3.3
    strip = curve((20, 60), "strip")
    assert 1.0 < strip[20][1] < 2.0 and 30.0 < strip[60][1] < 45.0
    assert 2.8 <= growth(strip, 20, 60, 0) <= 3.2


def test_specular_series_error_at_the_papers_exponents():
    # The specular series (N.H/|N|, then the power table) where the highlight lies on the
    # triangle (the worst half vector; for most, median 0, it misses): an error d in N.H is
    # about n d in (N.H)^n near the peak, so it grows with the exponent. Measured, worst H,
    # 'cone' spread, in 1/255: exponent 20, the 1 KB table: 2.45, 3.2, 8.6, 34, 182 at
    # spans 10, 20, 30, 40, 60 (at 10 the table's own 1 %); exponent 164, the 8 KB table:
    # 2.3, 7.1, 15.7, 40, 255. So within about 2.5/255 only to a span of about 10-15 degrees,
    # and a span of 60 degrees loses the highlight altogether.
    twenty = curve((10, 20, 30, 60), "cone", exponent=20, table=1024)
    assert twenty[10][1] <= 2.6 and 2.5 < twenty[20][1] < 4.5
    assert 6.0 < twenty[30][1] < 12.0 and twenty[60][1] > 150.0
    high = curve((10, 20, 30), "cone", exponent=164, table=8192)
    assert high[10][1] <= 2.6 and 5.0 < high[20][1] < 10.0 and high[30][1] > 12.0
    assert high[20][1] > twenty[20][1]          # the higher power amplifies the same series


def test_full_model_at_the_shading_a_sphere_gets():
    # ambient 0.1, diffuse 0.6, specular 0.3 at exponent 20 (1 KB table): Phong within 2/255
    # at a 20-degree span (the 24 x 48 sphere's triangles span about 7.5)
    assert taylor_error(20, FULL) <= 2.0
    assert taylor_error(60, DIFFUSE) > 10.0


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


def test_duffs_form_is_phong_but_for_the_exponent_table():
    # Duff's form is exact: N.L / |N| by forward differences of a linear and a quadratic
    # polynomial, a division and a square root. Even at a 60-degree span, where the series is
    # 10/255 off, the diffuse term is Phong's to rounding; the specular differs only by the
    # 1K table's nearest entry (at most 20 x 0.5 / 1023 of the power: 0.3 x 0.0098 x 255 = 0.75)
    xy, n = triangle(60.0)
    prep = F.prepare(xy, n, (160, 160))
    diffuse = np.abs(F.pixel_values(prep, DIFFUSE, "duff") - F.pixel_values(prep, DIFFUSE, "phong"))
    assert diffuse.max() < 1e-9
    full = np.abs(F.pixel_values(prep, FULL, "duff") - F.pixel_values(prep, FULL, "phong"))
    assert 0.05 < full.max() * 255 <= 0.8
    finite = F.prepare(xy, n, (160, 160), np.broadcast_to(EYE, n.shape))
    with pytest.raises(ValueError, match="eye at infinity"):
        F.pixel_values(finite, F.Light(L, eye=None), "duff")
