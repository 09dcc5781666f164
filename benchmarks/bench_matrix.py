"""Time `effects matrix fxfiles/*.fx` over every bundled card (goal: 0.3 s wall or less).

    python benchmarks/bench_matrix.py [--runs 7] [--json] [--profile]

The numbers (in process, the on-disk shader store is off: every compile is made):
- in-process, first run: the command with `--jobs 1` as `effects.cli.main.main` runs it in a
  fresh interpreter that has imported the package (loads every bundled profile, parses the
  effects, validates every effect on every card, prints the table);
- in-process, median of --runs: the same after the first, with the profile cache cleared before
  each run so every run reads the YAML files again (the parser tables and imports stay warm);
- subprocess, median of --runs: `python -m effects matrix FILES`, what a user waits for
  (the effect files validated on worker processes, one a core: `--jobs` left at its default),
  interpreter start and imports included, its output a pipe (as a script or `| less` reads
  it). The command line keeps compiled shaders (effects/shaders/hlsl/store.py) and each
  effect's row of the matrix (effects/cli/matrix_store.py) on disk between runs, so five ways:
  cold (an empty store folder for every run: it compiles, validates and writes); rows kept
  (the store filled by a run before: every row read back); one effect edited (copies of the
  effects, one of them changed before each run: its row is made again, the others read
  back); every effect edited (each copy changed before each run: every effect loaded and
  validated again, its shaders read back); and with the store off (EFFECTS_CACHE=off:
  compiles and validates, writes nothing);
- `python -c pass` in the same rounds: the interpreter's start on this machine, the yardstick
  for comparing figures taken on different machines (20-54 ms on the VMs so far).
Wall clock, with each run's CPU time (user + system of the child) beside it.
"""
from __future__ import annotations

import argparse
import contextlib
import io
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
GOAL_S = 0.3


def _files() -> list[str]:
    return sorted(str(p.relative_to(ROOT)) for p in (ROOT / "fxfiles").glob("*.fx"))


def _in_process(argv: list[str]) -> float:
    from effects.cli import main as cli
    start = time.perf_counter()
    with contextlib.redirect_stdout(io.StringIO()):
        code = cli.main(argv)
    elapsed = time.perf_counter() - start
    if code != 0:
        raise SystemExit(f"effects {' '.join(argv)} exited with {code}")
    return elapsed


def _subprocess(argv: list[str], env: dict | None = None, *,
                command: tuple[str, ...] = ("-m", "effects")) -> tuple[float, float]:
    """(wall, child CPU) seconds of one run of `python -m effects ARGV` (or of `python
    COMMAND...`: `command=("-c", "pass")` is the interpreter's start on this machine, the
    yardstick for comparing figures across machines)."""
    before = os.times()
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, *command, *argv], cwd=ROOT,
                          capture_output=True, text=True, env=env)
    elapsed = time.perf_counter() - start
    after = os.times()
    if proc.returncode != 0:
        raise SystemExit(f"{' '.join(command)} {' '.join(argv)} exited with {proc.returncode}: {proc.stderr}")
    return elapsed, (after.children_user - before.children_user) + (after.children_system - before.children_system)


def _copies(tmp: str) -> list[str]:
    """The effect files copied into `tmp` (their rows are the ones the edited runs change)."""
    folder = os.path.join(tmp, "fxfiles")
    os.mkdir(folder)
    out = []
    for name in _files():
        out.append(os.path.join(folder, os.path.basename(name)))
        with open(ROOT / name, "rb") as src, open(out[-1], "wb") as dst:
            dst.write(src.read())
    _edit(out, "copied")
    return out


def _edit(paths: list[str], mark: str) -> None:
    """Add a comment line at the end of each file, as saving an edit does, dated 10 s back: a
    file written in the last 2 s is not kept (matrix_store), and an editor's save is seldom
    followed by a command that soon. The shaders' keys do not change (the line is below them)."""
    then = time.time() - 10
    for p in paths:
        with open(p, "a") as f:
            f.write(f"// {mark}\n")
        os.utime(p, (then, then))


def _line(label: str, runs: list[tuple[float, float]]) -> str:
    wall = [w for w, _ in runs]
    cpu = [c for _, c in runs]
    med = statistics.median(wall)
    return (f"{label:<24}{med * 1000:7.1f} ms  (min {min(wall) * 1000:.1f}, max {max(wall) * 1000:.1f}; "
            f"CPU median {statistics.median(cpu) * 1000:.0f} ms, {len(runs)} runs)  {_verdict(med)}")


def _verdict(seconds: float) -> str:
    return "ok" if seconds <= GOAL_S else f"over the {GOAL_S:g} s goal"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--json", action="store_true", help="time `matrix --json` instead of the table")
    ap.add_argument("--profile", action="store_true", help="print a cProfile of one cold run")
    args = ap.parse_args(argv)

    command = ["matrix", *_files()] + (["--json"] if args.json else [])
    import effects.cli.main  # noqa: F401  (imports are part of the subprocess figure, not these)
    from effects.d3d9 import caps

    os.environ["EFFECTS_CACHE"] = "off"      # in process: compiles and validation are made
    first = _in_process(command + ["--jobs", "1"])
    warm = []
    for _ in range(args.runs):
        caps.clear_cache()
        warm.append(_in_process(command + ["--jobs", "1"]))
    del os.environ["EFFECTS_CACHE"]
    with tempfile.TemporaryDirectory(prefix="bench-matrix-") as tmp:
        copies = _copies(tmp)
        edited = [c if a.endswith(".fx") else a for a, c in zip(command, ["matrix", *copies])]
        edited += command[len(edited):]
        cold, stored, one, every, off, bare = [], [], [], [], [], []
        filled = dict(os.environ, EFFECTS_CACHE_DIR=os.path.join(tmp, "warm"))
        _subprocess(command, filled)                           # fill the warm store
        _subprocess(edited, filled)
        for k in range(args.runs):                              # interleaved: the same load for all
            cold.append(_subprocess(command, dict(os.environ, EFFECTS_CACHE_DIR=os.path.join(tmp, f"cold{k}"))))
            stored.append(_subprocess(command, filled))
            _edit(copies[k % len(copies):k % len(copies) + 1], f"one {k}")
            one.append(_subprocess(edited, filled))
            _edit(copies, f"every {k}")
            every.append(_subprocess(edited, filled))
            off.append(_subprocess(command, dict(os.environ, EFFECTS_CACHE="off")))
            bare.append(_subprocess([], command=("-c", "pass")))

    n_cards = len(caps.list_profiles())
    print(f"effects {' '.join(command[:1])} {len(command) - 1 - args.json} files × {n_cards} cards")
    print(f"in-process, first run:  {first * 1000:7.1f} ms  {_verdict(first)}")
    print(f"in-process, median:     {statistics.median(warm) * 1000:7.1f} ms  "
          f"(min {min(warm) * 1000:.1f}, max {max(warm) * 1000:.1f}, {args.runs} runs)  "
          f"{_verdict(statistics.median(warm))}")
    print(_line("subprocess, cold store:", cold))
    print(_line("rows kept:", stored))
    print(_line("one effect edited:", one))
    print(_line("every effect edited:", every))
    print(_line("subprocess, store off:", off))
    print(f"python -c pass:         {statistics.median(w for w, _ in bare) * 1000:7.1f} ms  "
          "(this machine's interpreter start, in the same rounds)")
    if hasattr(os, "getloadavg"):
        print(f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())} "
              f"({os.cpu_count()} cores)")
    if args.profile:
        import cProfile
        import pstats
        caps.clear_cache()
        prof = cProfile.Profile()
        prof.enable()
        _in_process(command)
        prof.disable()
        pstats.Stats(prof, stream=sys.stdout).sort_stats("cumulative").print_stats(20)
    return 0


if __name__ == "__main__":
    sys.exit(main())
