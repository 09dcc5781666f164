"""Bishop and Weimer's timing table (Fast Phong Shading, SIGGRAPH 1986) as ratios to Gouraud,
measured on the NumPy reference's screen-space shader (backends/reference/fast_phong.py):
a 64 x 128 sphere seen from the front at 1024 x 1024, one directional light, exponent 20.

    .venv/bin/python benchmarks/bench_fast_phong.py [--size 1024] [--repeat 5] [--errors]
    .venv/bin/python benchmarks/bench_fast_phong.py --renderer [--size 1024] [--repeat 5]

`--renderer` times whole frames of fxfiles/fast_phong.fx (Phong, refrast, the default
sphere) through the reference back end instead: ShadeMode = Phong by the Taylor form (finite
eye, as the file's LocalViewer says) against the same pass lit by the normalised normal
(`ReferenceBackend(phong="normalised")`), and the Gouraud technique, on one thread.

`--errors` prints instead the series' error against exact Phong as the vertex normals spread
(tests/looks/test_fast_phong.py asserts it): per span the median and worst over 150 light (or half)
directions within 75 degrees of the triangle's mean normal, for the diffuse term and for the
specular at the paper's exponents and table sizes.

Shading only: the scan conversion and interpolation planes, which every mode shares, are made
once (`prepare`) and timed apart. The paper's table (microVAX-II, 14620 polygons at 2048^2):
Gouraud 406 s, Taylor (infinite eye) 767 s, Taylor (finite eye) 850 s, Phong 3900 s --
ratios 1, 1.89, 2.09, 9.6.
"""
from __future__ import annotations

import argparse

import numpy as np

from backends.reference.fast_phong import (SPREADS, Light, pixel_values, prepare,
                                           series_error, spread_normals)
from effects.assets.meshes import sphere
from bench_scale import best as best_of  # one timing helper for the benchmarks

PAPER = {"gouraud": 406.0, "taylor, infinite eye": 767.0, "taylor, finite eye": 850.0,
         "phong (normalised normal), infinite eye": 3900.0}


def front_sphere(size: int, rings: int = 64, segments: int = 128):
    """Front-facing triangles of a unit sphere, orthographic view from +z, in pixels, with
    vertex normals and unit vectors toward an eye at (0, 0, 4)."""
    m = sphere(rings, segments)
    tri = m.indices.astype(np.int64)
    p, n = m.positions[tri].astype(np.float64), m.normals[tri].astype(np.float64)
    front = n[:, :, 2].mean(axis=1) > 0
    p, n = p[front], n[front]
    xy = np.stack([(p[..., 0] + 1.2) / 2.4 * size, (1.2 - p[..., 1]) / 2.4 * size], axis=-1)
    v = np.array([0.0, 0.0, 4.0]) - p
    return xy, n, v / np.linalg.norm(v, axis=-1, keepdims=True)


def error_curves(spans=(10, 20, 25, 30, 40, 50, 60, 75, 90), count: int = 150) -> None:
    rng = np.random.default_rng(1)
    d = rng.normal(size=(4 * count, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    d[:, 2] = np.abs(d[:, 2])
    d = d[d[:, 2] > np.cos(np.radians(75))][:count]
    kinds = {"diffuse": None, "specular n=20, 1K table": (20, 1024),
             "specular n=164, 8K table": (164, 8192)}
    print("max |Taylor - Phong| over the triangle, 1/255: median / worst direction")
    print(f"{'term':26s} {'spread':6s} " + " ".join(f"{s:>12d}" for s in spans))
    for name, kind in kinds.items():
        for spread in SPREADS:
            cells = []
            for span in spans:
                normals = spread_normals(span, spread)
                if kind is None:
                    lights = [Light(v, eye=np.array([0.0, 0.0, 1.0]), ambient=0.0, diffuse=1.0,
                                    specular=0.0) for v in d]
                else:
                    lights = [Light(v, eye=v, ambient=0.0, diffuse=0.0, specular=1.0,
                                    exponent=kind[0], table_size=kind[1]) for v in d]
                e = np.array([series_error(normals, light) * 255 for light in lights])
                cells.append(f"{np.median(e):5.2f}/{e.max():6.2f}")
            print(f"{name:26s} {spread:6s} " + " ".join(f"{c:>12s}" for c in cells), flush=True)


def renderer_frames(size: int, repeat: int) -> None:
    from pathlib import Path

    import effects
    from effects.program.backend import create_backend
    from effects.host.runtime import Runtime
    fx = effects.load_effect(str(Path(__file__).resolve().parent.parent / "fxfiles" / "fast_phong.fx"))
    rows = {"gouraud (vertex lighting)": ("normalised", "Gouraud"),
            "taylor, finite eye": ("taylor", "Phong"),
            "phong (normalised normal), finite eye": ("normalised", "Phong")}
    times = {}
    for name, (mode, technique) in rows.items():
        runtime = Runtime(fx, "refrast", size=(size, size),
                          backend=create_backend("numpy", threads=1, phong=mode))
        tech = fx.technique(technique)
        runtime.render(tech)
        times[name] = best_of(lambda: runtime.render(tech), repeat)
    print(f"fast_phong.fx frames at {size}^2 through the reference back end (one thread)")
    for name, t in times.items():
        print(f"{name:42s} {t * 1e3:8.1f} ms {t / times['gouraud (vertex lighting)']:6.2f}")
    ratio = times["phong (normalised normal), finite eye"] / times["taylor, finite eye"]
    print(f"normalised-normal Phong / Taylor frame: {ratio:.2f}x")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=1024)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--errors", action="store_true",
                        help="print the series' error against the normals' span instead")
    parser.add_argument("--renderer", action="store_true",
                        help="time fast_phong.fx frames through the reference back end instead")
    args = parser.parse_args()
    if args.errors:
        error_curves()
        return
    if args.renderer:
        renderer_frames(args.size, args.repeat)
        return
    xy, n, v = front_sphere(args.size)
    to_light = np.array([0.4, 0.5, 0.77]) / np.linalg.norm([0.4, 0.5, 0.77])
    infinite = Light(to_light, eye=np.array([0.0, 0.0, 1.0]))
    finite = Light(to_light, eye=None)
    setup = best_of(lambda: prepare(xy, n, (args.size, args.size), v), args.repeat)
    prep = prepare(xy, n, (args.size, args.size), v)
    cases = {"gouraud": (infinite, "gouraud"), "taylor, infinite eye": (infinite, "taylor"),
             "taylor, finite eye": (finite, "taylor"),
             "phong (normalised normal), infinite eye": (infinite, "phong"),
             "phong (normalised normal), finite eye": (finite, "phong")}
    times = {name: best_of(lambda: pixel_values(prep, light, mode), args.repeat)
             for name, (light, mode) in cases.items()}
    pixels = len(prep.spans.x)
    print(f"{len(xy)} triangles, {pixels} pixels at {args.size}^2; scan conversion and planes "
          f"(shared) {setup * 1e3:.1f} ms")
    print(f"{'shading':42s} {'ms':>8s} {'ns/pixel':>9s} {'ratio':>6s} {'paper':>6s}")
    for name, t in times.items():
        paper = f"{PAPER[name] / PAPER['gouraud']:.2f}" if name in PAPER else "-"
        print(f"{name:42s} {t * 1e3:8.1f} {t / pixels * 1e9:9.1f} "
              f"{t / times['gouraud']:6.2f} {paper:>6s}")
    ratio = times["phong (normalised normal), infinite eye"] / times["taylor, infinite eye"]
    print(f"normalised-normal Phong / Taylor (infinite eye): {ratio:.2f}x (goal >= 2)")


if __name__ == "__main__":
    main()
