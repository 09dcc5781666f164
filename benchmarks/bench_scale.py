"""Cost as the work grows (issue 15): each row of the issue's table, measured side by side in
one run, with the fitted exponent where the work grows, and the goal.

    .venv/bin/python benchmarks/bench_scale.py [--quick] [--only ROW,...] [--json]

Rows (names for --only):
  validate   every technique of a generated 1k / 10k / 100k-line effect on every bundled card,
             card by card (`Effect.validate`)
  validate-cards  the same, every card at once per technique, as `effects matrix` does
  lower      every pass of a generated 1k / 10k / 100k-line effect
             (--quick: 1k / 10k / 30k for both; goals 10k <= 11x 1k, 100k <= 110x, 30k <= 33x)
  render     effects.render() called again vs a reused Runtime, 64x64 NumPy; memory over 1,000 calls
  frame      NumPy Phong frame (phong.fx on the radeon9700) 64/128/512, 1 and 2 threads
  startup    `effects --help`, `import effects`, `effects profiles`, `effects matrix fxfiles/*.fx`
  memory     peak memory of a process that draws one 2048x2048 NumPy frame
  mesh       a 1M-triangle .obj with tangent frames; sphere() of 1M triangles
  textures   Runtime construction over an effect with 100 textures
  sheet      `effects matrix --render` contact sheet, all fxfiles x every card: --jobs 1 vs 2, Dask
The growth rows (validate, validate-cards, lower) give the median CPU time of rounds over all
sizes in turn and the median ratio of samples taken side by side (see `_growth_times`); the
render row the median of rounds of both ways in turn; the other rows the minimum of several
runs of the wall clock (the least disturbed by other work on the machine). The exponent is
the least-squares slope of log(time) over log(lines).
"""
from __future__ import annotations

import argparse
import gc
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

import effects  # noqa: E402
from bench_load import make_effect  # noqa: E402
from effects.d3d9.caps import list_profiles, load_profile  # noqa: E402

ROWS: list[tuple[str, str, str, str]] = []   # (work, figures, exponent, goal)


def row(work: str, figures: str, exponent: str, goal: str) -> None:
    ROWS.append((work, figures, exponent, goal))
    print(f"{work:<44} {figures:<46} {exponent:<10} {goal}", flush=True)


def best(fn, runs: int = 3, clock=time.perf_counter) -> float:
    times = []
    for _ in range(runs):
        start = clock()
        fn()
        times.append(clock() - start)
    return min(times)


def exponent(sizes, times) -> float:
    xs, ys = [math.log(s) for s in sizes], [math.log(t) for t in times]
    mx, my = statistics.fmean(xs), statistics.fmean(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def ms(seconds: float) -> str:
    return f"{seconds * 1000:.1f} ms" if seconds < 1 else f"{seconds:.2f} s"


def _verdict(ok: bool) -> str:
    return "ok" if ok else "MISSED"


# each size's sample is its work repeated until this much CPU time has passed (at least once)
GROWTH_SAMPLE_S = 0.3
GROWTH_ROUNDS = 5


def _growth_sample(fn, last: float | None) -> float:
    """Seconds of CPU time per call of `fn`, repeated until GROWTH_SAMPLE_S have passed.
    One untimed call first where this is the first sample (`last` None: that call makes
    what an effect keeps, its shaders assembled) or a call is shorter than the window (a
    small effect's work fits in the CPU's caches once it has run, after the other sizes'
    work pushed it out; a big one's never does). The clock is the process's CPU time (the
    work is one thread's; the wall clock also counts the time other processes held the
    core)."""
    if last is None or last < GROWTH_SAMPLE_S:
        fn()
    calls, start = 0, time.process_time()
    while True:
        fn()
        calls += 1
        spent = time.process_time() - start
        if spent >= GROWTH_SAMPLE_S:
            return spent / calls


def _growth_times(fns: list) -> tuple[list[list[float]], list[float]]:
    """Each of `fns` (the same work on effects of growing size) sampled in GROWTH_ROUNDS
    rounds, every size once a round in turn, and the smallest once more at the end: the
    samples per size, and each larger size's median ratio to the smallest, a round's ratio
    taken against the mean of the smallest size's samples on either side of it. On this VM
    the same work's CPU time drifts by 1.5x over tens of seconds; a ratio made of samples
    taken side by side cancels the drift, where the minimum of unequal numbers of runs
    (7 of the 1k effect against 2 of the 100k one, before) picked a luckier moment for the
    small size. The garbage the loads left is collected first, and the effects' own objects
    are set aside from the cyclic collector (`gc.freeze`): with every size loaded at once, a
    full collection during the 1k effect's work would otherwise walk the 100k one's too."""
    gc.collect()
    gc.freeze()
    samples: list[list[float]] = [[] for _ in fns]
    for _ in range(GROWTH_ROUNDS):
        for fn, times in zip(fns, samples):
            times.append(_growth_sample(fn, times[-1] if times else None))
    first = samples[0] + [_growth_sample(fns[0], samples[0][-1])]
    ratios = [statistics.median(t / ((first[r] + first[r + 1]) / 2) for r, t in enumerate(times))
              for times in samples[1:]]
    gc.unfreeze()
    return samples, ratios


# -- rows --------------------------------------------------------------------------------------

# the goals for the growth rows: 10k lines <= 11x the 1k-line cost, 100k <= 110x
GROWTH_GOALS = {10000: 11.0, 100000: 110.0}


def _growth_sizes(quick: bool) -> list[int]:
    """1k, 10k, 100k lines (the goals' sizes); --quick stops at 30k (its goal scaled: 33x)."""
    return [1000, 10000, 30000] if quick else [1000, 10000, 100000]


def _growth_goals(sizes: list[int], ratios: list[float]) -> str:
    """Each larger size's ratio to the first against its goal (1.1x the line ratio)."""
    out = []
    for n, ratio in zip(sizes[1:], ratios):
        limit = GROWTH_GOALS.get(n, 1.1 * n / sizes[0])
        out.append(f"{n // 1000}k {ratio:.1f}× (≤ {limit:.0f}×) {_verdict(ratio <= limit)}")
    return "; ".join(out)


def _growth_row(what: str, sizes: list[int], make_fn) -> None:
    """Load an effect of each size, time `make_fn(effect)()` over all of them together (see
    `_growth_times`) and print the row: each size's median time, the exponent fitted to
    them, the paired ratios against the goals, and each size's spread; the seconds each
    load took are said at the end (the 100k-line load is slow)."""
    fns, loads = [], []
    for n in sizes:
        start = time.perf_counter()
        fns.append(make_fn(effects.load_effect(make_effect(n))))
        loads.append(time.perf_counter() - start)
    samples, ratios = _growth_times(fns)
    times = [statistics.median(t) for t in samples]
    row(f"{what}, {' → '.join(f'{n // 1000}k' for n in sizes)} lines",
        " → ".join(ms(t) for t in times), f"{exponent(sizes, times):.2f}",
        _growth_goals(sizes, ratios))
    print(f"  (CPU time, median of {GROWTH_ROUNDS} rounds, ratios of side-by-side samples; "
          "spread " + ", ".join(f"{ms(min(t))}-{ms(max(t))}" for t in samples)
          + f"; loads took {', '.join(ms(t) for t in loads)} wall, not counted)", flush=True)


def bench_validate(quick: bool) -> None:
    cards = [load_profile(p) for p in list_profiles()]

    def make(effect):
        def validate_all():
            for card in cards:       # each result dropped once made, as a report would print it
                for t in effect.techniques:
                    effect.validate(t, card)
        return validate_all
    _growth_row(f"validate on {len(cards)} cards", _growth_sizes(quick), make)


def bench_validate_cards(quick: bool) -> None:
    """As `bench_validate`, the way `effects matrix` and `effects validate -p ...` validate:
    each technique on every card at once (`report.validate_cards`: what no card changes
    about a pass is made once for all of them, and a technique's objects are read while
    they are in the CPU's caches, where the card-by-card row sweeps the whole effect 20
    times)."""
    from effects.cli.report import validate_cards
    cards = [load_profile(p) for p in list_profiles()]

    def make(effect):
        return lambda: validate_cards(effect, cards)
    _growth_row(f"validate on {len(cards)} cards at once", _growth_sizes(quick), make)


def bench_lower(quick: bool) -> None:
    from effects.lower.passes import clear_cache, lower_pass
    card = load_profile("radeon9700")

    def make(effect):
        def lower_all():
            clear_cache()
            for t in effect.techniques:
                for i in range(len(t.passes)):
                    try:
                        lower_pass(effect, t, i, card)
                    except effects.EffectError:
                        pass
        return lower_all
    _growth_row("lower every pass", _growth_sizes(quick), make)


def bench_render() -> None:
    from effects.host.runtime import Runtime
    effect = effects.load_effect(str(ROOT / "fxfiles" / "phong.fx"))
    card = load_profile("radeon9700")
    runtime = Runtime(effect, card, size=(64, 64))
    runtime.render()
    effects.render(effect, card, size=(64, 64))
    # blocks of 20 frames each way in turn, 9 rounds: the ratio is the median of each round's
    # (side by side, as the growth rows: this VM's speed drifts between one block and the next)
    rounds = []
    for _ in range(9):
        rounds.append((best(lambda: [runtime.render() for _ in range(20)], 1) / 20,
                       best(lambda: [effects.render(effect, card, size=(64, 64))
                                     for _ in range(20)], 1) / 20))
    reused = statistics.median(r for r, _ in rounds)
    again = statistics.median(a for _, a in rounds)
    ratio = statistics.median(a / r for r, a in rounds)
    tracemalloc.start()
    for _ in range(100):
        effects.render(effect, card, size=(64, 64))
    gc.collect()   # what is still referenced, not garbage awaiting the cycle collector
    before = tracemalloc.get_traced_memory()[0]
    for _ in range(900):
        effects.render(effect, card, size=(64, 64))
    gc.collect()
    growth = tracemalloc.get_traced_memory()[0] - before
    tracemalloc.stop()
    row("effects.render() again, 64² NumPy", f"{ms(again)} vs Runtime {ms(reused)} ({ratio:.2f}×)",
        "", f"≤ 1.2×: {_verdict(ratio <= 1.2)}; +{growth / 1024:.0f} KiB over calls 100-1000")


def bench_frame() -> None:
    from effects.program.backend import create_backend
    from effects.host.runtime import Runtime
    effect = effects.load_effect(str(ROOT / "fxfiles" / "phong.fx"))
    card = load_profile("radeon9700")
    for size in (64, 128, 512):
        out = {}
        for threads in (1, 2):
            runtime = Runtime(effect, card, size=(size, size),
                              backend=create_backend("numpy", threads=threads))
            runtime.render()
            frames = 30 if size < 512 else 5
            out[threads] = best(lambda: [runtime.render() for _ in range(frames)], 3) / frames
        figures = f"1 thread {ms(out[1])}, 2 threads {ms(out[2])}"
        goal = {64: ("1 thread ≤ 2.5 ms", out[1] <= 0.0025), 128: ("2 threads ≤ 1 thread", out[2] <= out[1] * 1.05),
                512: ("≤ 23 ms (today)", min(out.values()) <= 0.023)}[size]
        if size == 512:
            # the 23 ms was 8-9x the GL path on its machine: the same frame on GL says
            # what the machine in hand makes of it
            gl = _gl_frame(effect, card, size)
            if gl is not None:
                ratio = min(out.values()) / gl
                figures += f"; GL {ms(gl)} ({ratio:.1f}×)"
                goal = ("≤ 23 ms (today) or ≤ 8× GL", goal[1] or ratio <= 8.0)
        row(f"NumPy Phong frame {size}²", figures, "", f"{goal[0]}: {_verdict(goal[1])}")


def _gl_frame(effect, card, size: int) -> float | None:
    """Seconds per frame of the same Runtime on the GL back end, or None without a GL context."""
    from effects.program.backend import create_backend
    from effects.host.runtime import Runtime
    try:
        runtime = Runtime(effect, card, size=(size, size), backend=create_backend("gl"))
        runtime.render()
    except Exception as exc:   # no EGL here: say so, the row keeps its absolute goal
        print(f"  (no GL frame: {type(exc).__name__}: {exc})")
        return None
    return best(lambda: [runtime.render() for _ in range(5)], 3) / 5


def _command(*argv: str, runs: int = 5, env: dict | None = None) -> float:
    def once():
        subprocess.run([sys.executable, *argv], cwd=ROOT, check=True, capture_output=True,
                       env=None if env is None else {**os.environ, **env})
    return best(once, runs)


def bench_startup() -> None:
    files = sorted(str(p.relative_to(ROOT)) for p in (ROOT / "fxfiles").glob("*.fx"))
    bare = _command("-c", "pass")
    helps = _command("-m", "effects", "--help")
    imports = _command("-c", "import effects")
    profiles = _command("-m", "effects", "profiles")
    with tempfile.TemporaryDirectory(prefix="bench-scale-store-") as store:
        # the command line's store (effects/base/disk_store.py): filled by the first run, so the
        # others read every row back; and off, every effect loaded and validated
        kept = _command("-m", "effects", "matrix", *files, runs=4, env={"EFFECTS_CACHE_DIR": store})
    made = _command("-m", "effects", "matrix", *files, runs=3, env={"EFFECTS_CACHE": "off"})
    row("effects --help / import effects", f"{ms(helps)} / {ms(imports)} (python alone {ms(bare)})", "",
        f"--help ≤ 60 ms: {_verdict(helps <= 0.060)}")
    row(f"effects profiles / matrix ({len(files)} files × {len(list_profiles())} cards)",
        f"{ms(profiles)} / rows kept {ms(kept)}, store off {ms(made)}", "",
        f"matrix ≤ 300 ms: rows kept {_verdict(kept <= 0.300)}, store off {_verdict(made <= 0.300)}")


# The child's own peak is its memory's high-water mark (VmHWM, KiB): Linux carries
# ru_maxrss across exec, so a child of this process (hundreds of MiB after the growth rows)
# would report the parent's size.
_PEAK = """
import re, resource, sys
sys.path.insert(0, {root!r})
import effects
from effects.host.runtime import Runtime
runtime = Runtime(effects.load_effect({fx!r}), "radeon9700", size=(2048, 2048))
runtime.render()
try:
    with open("/proc/self/status") as status:
        print(re.search(r"VmHWM:\\s*(\\d+)", status.read()).group(1))
except OSError:
    print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)
"""


def bench_memory() -> None:
    script = _PEAK.format(root=str(ROOT), fx=str(ROOT / "fxfiles" / "phong.fx"))
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True)
    peak = int(out.stdout.split()[-1]) / 1024
    row("NumPy frame at 2048²: peak memory of the process", f"{peak:.0f} MiB", "",
        f"≤ 200 MiB: {_verdict(peak <= 200)}")


def _grid_obj(path: str, cells: int) -> int:
    import numpy as np
    u = np.linspace(0, 1, cells + 1)
    uu, vv = np.meshgrid(u, u)
    p = np.stack([uu * 4 - 2, np.sin(uu * 6) * np.cos(vv * 5) * 0.3, vv * 4 - 2], -1).reshape(-1, 3)
    t = np.stack([uu, vv], -1).reshape(-1, 2)
    idx = np.arange((cells + 1) ** 2).reshape(cells + 1, cells + 1) + 1
    a, b, c, d = idx[:-1, :-1], idx[:-1, 1:], idx[1:, :-1], idx[1:, 1:]
    tris = np.concatenate([np.stack([a, c, b], -1).reshape(-1, 3), np.stack([b, c, d], -1).reshape(-1, 3)])
    with open(path, "w") as fh:
        fh.write("".join(f"v {x:.6f} {y:.6f} {z:.6f}\n" for x, y, z in p))
        fh.write("".join(f"vt {x:.6f} {y:.6f}\n" for x, y in t))
        fh.write("vn 0 1 0\n")
        fh.write("".join(f"f {i}/{i}/1 {j}/{j}/1 {k}/{k}/1\n" for i, j, k in tris))
    return len(tris)


def bench_mesh() -> None:
    from effects.assets.meshes import load_obj, sphere
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "grid.obj")
        count = _grid_obj(path, 707)
        obj = best(lambda: load_obj(path), 3)
    ball = best(lambda: sphere(500, 1000), 3)
    row(f"{count / 1e6:.1f}M-triangle .obj / sphere() mesh, with tangent frames", f"{ms(obj)} / {ms(ball)}", "",
        f".obj ≤ 1.5 s: {_verdict(obj <= 1.5)}")


def bench_textures() -> None:
    from effects.host.runtime import Runtime
    decls = "\n".join(f'texture T{i} < string Procedural = "power_table:{8 + i}"; >;' for i in range(100))
    passes = "\n".join(f"pass P{i} {{ Texture[0] = <T{i}>; }}" for i in range(100))
    effect = effects.load_effect(f"{decls}\ntechnique t {{ {passes} }}")
    card = load_profile("radeon9700")

    def make():
        runtime = Runtime(effect, card, size=(8, 8))
        for i in range(100):
            runtime.texture(f"T{i}")
    make()
    row("Runtime over an effect with 100 textures", f"{ms(best(make, 3))} per construction", "",
        "no reload once cached")


SHEET_ROUNDS = 3


def bench_sheet() -> None:
    files = sorted(str(p) for p in (ROOT / "fxfiles").glob("*.fx"))
    try:
        from effects.cli.sheet import render_sheet
    except ImportError:
        row("contact sheet --jobs 1 vs 2", "n/a (no effects.cli.sheet)", "", "")
        return
    cards = list_profiles()
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "sheet.png")
        # once untimed: the first sheet of a process also pays its imports and first compiles
        # (with --only sheet, --jobs 1 came out 2.7x slower than --jobs 2 on 2 cores); then
        # rounds of both in turn, the ratio the median of each round's (side by side, as the
        # render row: one run of each gave 1.55x-1.9x here)
        render_sheet(files, cards, out, size=(64, 64), jobs=1, progress=False)
        ones, twos = [], []
        for _ in range(SHEET_ROUNDS):
            ones.append(best(lambda: render_sheet(files, cards, out, size=(64, 64), jobs=1,
                                                  progress=False), 1))
            twos.append(best(lambda: render_sheet(files, cards, out, size=(64, 64), jobs=2,
                                                  progress=False), 1))
        dask = "n/a (no dask)"
        try:
            import logging

            from distributed import Client, LocalCluster
            # silence_logs: a worker's heartbeat that meets the scheduler closing at the end
            # logs a traceback; a job that fails raises in render_sheet all the same
            with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None,
                              silence_logs=logging.CRITICAL) as cluster, \
                    Client(cluster) as client:
                render_sheet(files, cards, out, size=(64, 64), scheduler=client, progress=False)
                dask = ms(best(lambda: render_sheet(files, cards, out, size=(64, 64), scheduler=client,
                                                    progress=False), 1))
        except ImportError:
            pass
        # as a user runs it: `effects matrix --render` as commands, each process cold (the
        # command line's store filled by the first run: compiled shaders and matrix rows)
        command = ["-m", "effects", "matrix", *files, "--render", out, "--size", "64x64"]
        store = {"EFFECTS_CACHE_DIR": os.path.join(tmp, "store")}
        _command(*command, "--jobs", "1", runs=1, env=store)
        by_command = [(_command(*command, "--jobs", "1", runs=1, env=store),
                       _command(*command, "--jobs", "2", runs=1, env=store))
                      for _ in range(SHEET_ROUNDS)]
    speedup = statistics.median(a / b for a, b in zip(ones, twos))
    command_speedup = statistics.median(a / b for a, b in by_command)
    row(f"contact sheet, {len(files)} effects × {len(cards)} cards, 64²",
        f"in process --jobs 1 {ms(statistics.median(ones))}, --jobs 2 {ms(statistics.median(twos))} "
        f"({speedup:.2f}×); as commands {ms(statistics.median(a for a, _ in by_command))}, "
        f"{ms(statistics.median(b for _, b in by_command))} ({command_speedup:.2f}×), medians of "
        f"{SHEET_ROUNDS} rounds; Dask 2 workers {dask}", "",
        f"--jobs 2 ≥ 1.7×: {_verdict(speedup >= 1.7)} in process, "
        f"{_verdict(command_speedup >= 1.7)} as commands")


BENCHES = {"validate": bench_validate, "validate-cards": bench_validate_cards,
           "lower": bench_lower, "render": bench_render,
           "frame": bench_frame, "startup": bench_startup, "memory": bench_memory,
           "mesh": bench_mesh, "textures": bench_textures, "sheet": bench_sheet}


def _raise_limits() -> None:
    """The generated 30k/100k-line effects are bigger than the hostile-input limits allow."""
    try:
        from effects.base import limits
    except ImportError:   # older code without limits
        return
    limits.set_limit("source_bytes", 1 << 30)
    # the 1M-triangle .obj row is over the default mesh limits on purpose
    limits.set_limit("mesh_file_bytes", 1 << 30)
    limits.set_limit("mesh_vertices", 1 << 24)
    limits.set_limit("mesh_indices", 1 << 26)


def main(argv: list[str] | None = None) -> int:
    _raise_limits()
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="smaller effects for the growth rows")
    ap.add_argument("--only", default="", help="comma-separated row names (see the docstring)")
    ap.add_argument("--json", action="store_true",
                    help="end with one line of JSON: the rows as [work, figures, exponent, goal] "
                         "(docs/make_performance.py reads it)")
    args = ap.parse_args(argv)
    names = [n for n in args.only.split(",") if n] or list(BENCHES)
    print(f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}, Python {sys.version.split()[0]}")
    print(f"{'work':<44} {'figures':<46} {'exponent':<10} goal")
    for name in names:
        bench = BENCHES[name]
        bench(args.quick) if name in ("validate", "validate-cards", "lower") else bench()
    if args.json:
        import json
        print(json.dumps(ROWS, ensure_ascii=False))
    return 0


if __name__ == "__main__":
    sys.exit(main())
