"""Bishop and Weimer's timing table (Fast Phong Shading, SIGGRAPH 1986) as ratios to Gouraud,
measured on the NumPy reference's screen-space shader (backends/reference/fast_phong.py):
a 64 x 128 sphere seen from the front at 1024 x 1024, one directional light, exponent 20.

    .venv/bin/python benchmarks/bench_fast_phong.py [--size 1024] [--repeat 5] [--json] [--errors]
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
once (`prepare`) and timed apart. The modes are timed in interleaved rounds (each round times
every mode once, in the same order) of CPU time (the process's, so other work on a shared
machine counts less), so that a machine whose speed drifts slows all of them alike: each ratio is the median over the rounds of that round's time over its Gouraud time,
printed with the lowest and highest round. `--json` prints the rows as one JSON line
(docs/make_performance.py puts them on docs/performance.md).

The paper's table (microVAX-II, figure 4's 14620 polygons at 2048^2, CPU seconds): Gouraud
406, Taylor (infinite eye) 767 (incl. 119 for the Taylor coefficients), Taylor (finite eye)
850 (incl. 202), Duff 2597 (incl. 1420 in sqrt), Phong 3900 (incl. 1405 in sqrt) -- ratios
1, 1.89, 2.09, 6.40, 9.61. Duff's form evaluates N.L and |N|^2 by forward differences, then
divides by a square root at each pixel (its specular here reads the same exponent table as
the Taylor rows); Phong interpolates the normal and normalises it.
"""
from __future__ import annotations

import argparse
import json
import statistics
import time

import numpy as np

from backends.reference.fast_phong import (SPREADS, Light, pixel_values, prepare,
                                           series_error, spread_normals)
from effects.assets.meshes import sphere
from bench_scale import best as best_of  # one timing helper for the benchmarks

PAPER = {"gouraud": 406.0, "taylor, infinite eye": 767.0, "taylor, finite eye": 850.0,
         "duff, infinite eye": 2597.0, "phong (normalised normal), infinite eye": 3900.0}


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


def renderer_frames(size: int, repeat: int, as_json: bool = False) -> None:
    from pathlib import Path

    import effects
    from effects.program.backend import create_backend
    from effects.host.runtime import Runtime
    fx = effects.load_effect(str(Path(__file__).resolve().parent.parent / "fxfiles" / "fast_phong.fx"))
    cases = {"gouraud (vertex lighting)": ("normalised", "Gouraud"),
             "taylor, finite eye": ("taylor", "Phong"),
             "phong (normalised normal), finite eye": ("normalised", "Phong")}
    draws = {}
    for name, (mode, technique) in cases.items():
        runtime = Runtime(fx, "refrast", size=(size, size),
                          backend=create_backend("numpy", threads=1, phong=mode))
        tech = fx.technique(technique)
        runtime.render(tech)                          # once before timing
        draws[name] = (runtime, tech)
    times: dict[str, list[float]] = {name: [] for name in cases}
    for _ in range(repeat):                           # interleaved rounds, CPU time
        for name, (runtime, tech) in draws.items():
            start = time.process_time()
            runtime.render(tech)
            times[name].append(time.process_time() - start)
    base = times["gouraud (vertex lighting)"]
    rows = []
    for name in cases:
        ratios = [t / g for t, g in zip(times[name], base)]
        rows.append({"name": name, "ms": min(times[name]) * 1e3, "ratio": statistics.median(ratios),
                     "ratio_low": min(ratios), "ratio_high": max(ratios)})
    over = [p / t for p, t in zip(times["phong (normalised normal), finite eye"],
                                  times["taylor, finite eye"])]
    summary = {"over_taylor": statistics.median(over), "over_taylor_low": min(over),
               "over_taylor_high": max(over), "faster_rounds": sum(o > 1 for o in over)}
    if as_json:
        print(json.dumps({"size": size, "rounds": repeat, "rows": rows, **summary}))
        return
    print(f"fast_phong.fx frames at {size}^2 through the reference back end (one thread, "
          f"{repeat} interleaved rounds)")
    for row in rows:
        print(f"{row['name']:42s} {row['ms']:8.1f} ms {row['ratio']:6.2f} "
              f"({row['ratio_low']:.2f}-{row['ratio_high']:.2f})")
    print(f"normalised-normal Phong / Taylor frame: {summary['over_taylor']:.2f}x "
          f"({summary['over_taylor_low']:.2f}-{summary['over_taylor_high']:.2f}; the Taylor "
          f"frame faster in {summary['faster_rounds']} of {repeat} rounds)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=1024)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--errors", action="store_true",
                        help="print the series' error against the normals' span instead")
    parser.add_argument("--renderer", action="store_true",
                        help="time fast_phong.fx frames through the reference back end instead")
    parser.add_argument("--json", action="store_true", help="the table as one JSON line")
    args = parser.parse_args()
    if args.errors:
        error_curves()
        return
    if args.renderer:
        renderer_frames(args.size, args.repeat, args.json)
        return
    rows, pixels, setup = paper_table(args.size, args.repeat)
    if args.json:
        print(json.dumps({"size": args.size, "rounds": args.repeat, "pixels": pixels,
                          "setup_ms": setup * 1e3, "rows": rows}))
        return
    print(f"{pixels} pixels at {args.size}^2; scan conversion and planes (shared) "
          f"{setup * 1e3:.1f} ms; {args.repeat} interleaved rounds")
    print(f"{'shading':42s} {'ms':>8s} {'ns/pixel':>9s} {'ratio':>6s} {'rounds':>11s} {'paper':>6s}")
    for row in rows:
        paper = f"{row['paper_ratio']:.2f}" if row["paper_ratio"] else "-"
        print(f"{row['name']:42s} {row['ms']:8.1f} {row['ms'] * 1e6 / pixels:9.1f} "
              f"{row['ratio']:6.2f} {row['ratio_low']:5.2f}-{row['ratio_high']:<5.2f} {paper:>6s}")
    by_name = {row["name"]: row for row in rows}
    phong = by_name["phong (normalised normal), infinite eye"]
    print(f"normalised-normal Phong / Taylor (infinite eye): {phong['over_taylor']:.2f}x, rounds "
          f"{phong['over_taylor_low']:.2f}-{phong['over_taylor_high']:.2f} (paper "
          f"{PAPER[phong['name']] / PAPER['taylor, infinite eye']:.2f}x)")


CASES = ("gouraud", "taylor, infinite eye", "taylor, finite eye", "duff, infinite eye",
         "phong (normalised normal), infinite eye", "phong (normalised normal), finite eye")


def paper_table(size: int, rounds: int) -> tuple[list[dict], int, float]:
    """The paper's rows timed in `rounds` interleaved rounds: (rows, pixels, setup seconds);
    each row: name, best ms, ratio to Gouraud (median of the rounds, with the lowest and the
    highest), and the paper's seconds and ratio where it has the row."""
    xy, n, v = front_sphere(size)
    to_light = np.array([0.4, 0.5, 0.77]) / np.linalg.norm([0.4, 0.5, 0.77])
    infinite = Light(to_light, eye=np.array([0.0, 0.0, 1.0]))
    finite = Light(to_light, eye=None)
    setup = best_of(lambda: prepare(xy, n, (size, size), v), rounds)
    prep = prepare(xy, n, (size, size), v)
    modes = {"gouraud": (infinite, "gouraud"), "taylor, infinite eye": (infinite, "taylor"),
             "taylor, finite eye": (finite, "taylor"), "duff, infinite eye": (infinite, "duff"),
             "phong (normalised normal), infinite eye": (infinite, "phong"),
             "phong (normalised normal), finite eye": (finite, "phong")}
    for light, mode in modes.values():                 # once each before timing (warm caches)
        pixel_values(prep, light, mode)
    times: dict[str, list[float]] = {name: [] for name in CASES}
    for _ in range(rounds):
        for name in CASES:
            light, mode = modes[name]
            start = time.process_time()
            pixel_values(prep, light, mode)
            times[name].append(time.process_time() - start)
    rows = []
    for name in CASES:
        ratios = [t / g for t, g in zip(times[name], times["gouraud"])]
        over = [t / g for t, g in zip(times[name], times["taylor, infinite eye"])]
        paper = PAPER.get(name)
        rows.append({"name": name, "ms": min(times[name]) * 1e3,
                     "ratio": statistics.median(ratios), "ratio_low": min(ratios),
                     "ratio_high": max(ratios), "over_taylor": statistics.median(over),
                     "over_taylor_low": min(over), "over_taylor_high": max(over),
                     "paper_s": paper, "paper_ratio": paper / PAPER["gouraud"] if paper else None})
    return rows, len(prep.spans.x), setup


if __name__ == "__main__":
    main()
