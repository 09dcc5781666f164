"""Time `effects matrix fxfiles/*.fx` over every bundled card (goal: 0.5 s or less).

    python benchmarks/bench_matrix.py [--runs 7] [--json] [--profile]

Three numbers:
- in-process, first run: the command as `effects.cli.main.main` runs it in a fresh interpreter that
  has imported the package (loads the 19 profiles, parses the 7 effects, validates 7 effects ×
  19 cards, prints the table);
- in-process, median of --runs: the same after the first, with the profile cache cleared before
  each run so every run reads the YAML files again (the parser tables and imports stay warm);
- subprocess, median of --runs: `python -m effects matrix fxfiles/*.fx`, what a user waits for,
  interpreter start and imports included.
"""
from __future__ import annotations

import argparse
import contextlib
import io
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
GOAL_S = 0.5


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


def _subprocess(argv: list[str]) -> float:
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "effects", *argv], cwd=ROOT,
                          capture_output=True, text=True)
    elapsed = time.perf_counter() - start
    if proc.returncode != 0:
        raise SystemExit(f"effects {' '.join(argv)} exited with {proc.returncode}: {proc.stderr}")
    return elapsed


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
    from effects import caps

    first = _in_process(command)
    warm = []
    for _ in range(args.runs):
        caps.clear_cache()
        warm.append(_in_process(command))
    sub = [_subprocess(command) for _ in range(args.runs)]

    n_cards = len(caps.list_profiles())
    print(f"effects {' '.join(command[:1])} {len(command) - 1 - args.json} files × {n_cards} cards")
    print(f"in-process, first run:  {first * 1000:7.1f} ms  {_verdict(first)}")
    print(f"in-process, median:     {statistics.median(warm) * 1000:7.1f} ms  "
          f"(min {min(warm) * 1000:.1f}, max {max(warm) * 1000:.1f}, {args.runs} runs)  "
          f"{_verdict(statistics.median(warm))}")
    print(f"subprocess, median:     {statistics.median(sub) * 1000:7.1f} ms  "
          f"(min {min(sub) * 1000:.1f}, max {max(sub) * 1000:.1f}, {args.runs} runs)  "
          f"{_verdict(statistics.median(sub))}")
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
