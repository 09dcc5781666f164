"""What the fidelity figures cost, and that `effects matrix` without them costs what it did.

    python benchmarks/bench_fidelity.py [--runs 5] [--tree /path/to/another/checkout]

- per effect, in process: the meter's renders and measures (effects.host.fidelity) of every
  technique valid on every bundled card, cold (a new effect object: nothing measured), in
  seconds, with the count of (technique, card) pictures drawn;
- `python -m effects matrix fxfiles/*.fx`, wall clock, median of --runs, four ways: without
  and with `--fidelity`, each with the on-disk store off (EFFECTS_CACHE=off: everything made)
  and with the rows kept by a run before (read back). `--tree` runs the plain command in
  another checkout too (e.g. the main branch, to compare the command without the figures),
  with this interpreter, alternating runs so that both see the same load on the machine.
"""
from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _files(root: Path) -> list[str]:
    return sorted(str(p.relative_to(root)) for p in (root / "fxfiles").glob("*.fx"))


def _run(root: Path, args: list[str], env: dict) -> float:
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "effects", "matrix", *_files(root), *args],
                          cwd=root, capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": str(root), **env})
    elapsed = time.perf_counter() - start
    if proc.returncode != 0:
        raise SystemExit(f"matrix {' '.join(args)} in {root} exited {proc.returncode}: {proc.stderr}")
    return elapsed


def per_effect() -> None:
    sys.path.insert(0, str(ROOT))
    import effects
    from effects.d3d9.caps import list_profiles, load_profile
    from effects.host.fidelity import meter_for
    from effects.host.scene import scene_for
    from effects.validate.technique import validate_technique
    cards = [load_profile(n) for n in list_profiles()]
    print("per effect, every valid (technique, card) drawn and measured, cold:")
    for path in _files(ROOT):
        effect = effects.load_effect(str(ROOT / path))
        pairs = [(t, c) for t in effect.techniques for c in cards
                 if validate_technique(effect, t, c).ok]
        start = time.perf_counter()
        meter = meter_for(effect, scene=scene_for(str(ROOT / path), None))
        for t, c in pairs:
            meter.measure(t, c)
        elapsed = time.perf_counter() - start
        print(f"  {path:28s} {len(pairs):4d} pictures  {elapsed:6.2f} s  "
              f"({1000 * elapsed / max(1, len(pairs)):.0f} ms each)")


def commands(runs: int, other: Path | None) -> None:
    ways = [("plain, store off", [], {"EFFECTS_CACHE": "off"}),
            ("plain, rows kept", [], {}),
            ("--fidelity, store off", ["--fidelity"], {"EFFECTS_CACHE": "off"}),
            ("--fidelity, rows kept", ["--fidelity"], {})]
    trees = [("this tree", ROOT)] + ([("--tree", other)] if other is not None else [])
    with tempfile.TemporaryDirectory() as tmp:
        times: dict[tuple[str, str], list[float]] = {}
        for n in range(runs + 1):                      # the first round fills the stores
            for label, args, env in ways:
                for tree_label, root in trees:
                    if args and root is not ROOT:
                        continue                      # the other tree has no --fidelity
                    store = os.path.join(tmp, tree_label.replace(" ", "_"))
                    took = _run(root, args, {"EFFECTS_CACHE_DIR": store, **env})
                    if n:
                        times.setdefault((label, tree_label), []).append(took)
    print(f"effects matrix fxfiles/*.fx, every card, median of {runs} (wall):")
    for (label, tree_label), values in times.items():
        print(f"  {label:24s} {tree_label:10s} {statistics.median(values):6.2f} s  "
              f"(min {min(values):.2f}, max {max(values):.2f})")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--tree", type=Path, default=None)
    parser.add_argument("--skip-effects", action="store_true")
    args = parser.parse_args()
    if not args.skip_effects:
        per_effect()
    commands(args.runs, args.tree)


if __name__ == "__main__":
    main()
