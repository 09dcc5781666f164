"""Code size of the HLSL compiler (issue 31): the slots and temporaries of every `compile` state
of the bundled effects (fxfiles/*.fx) and of tests/data/realfx/**/*.fx, per shader and as
median / 90th percentile, optionally beside a saved earlier run.

    .venv/bin/python benchmarks/bench_slots.py [--save FILE] [--before FILE]

`--save` writes {shader: [total, arithmetic, texture, temps]} as JSON; `--before` reads such a
file (e.g. saved on the commit before a change) and prints the ratio ours-after / ours-before
per shader and at the median and 90th percentile. A state that does not compile counts as
"refused" in both columns (its error's first words are shown).
"""
from __future__ import annotations

import argparse
import json
import statistics
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import effects  # noqa: E402
from effects.base.errors import EffectError  # noqa: E402
from effects.model import CompileShader  # noqa: E402
from effects.shaders.hlsl import compile_state  # noqa: E402


def effect_files() -> list[Path]:
    return sorted((ROOT / "fxfiles").glob("*.fx")) + \
        sorted((ROOT / "tests" / "data" / "realfx").rglob("*.fx"))


def measure() -> dict[str, list[int] | str]:
    out: dict[str, list[int] | str] = {}
    for path in effect_files():
        try:
            fx = effects.load_effect(str(path))
        except EffectError as err:
            out[str(path.relative_to(ROOT))] = f"refused: {err.message[:50]}"
            continue
        seen: set[tuple] = set()
        for t in fx.techniques:
            for i, p in enumerate(t.passes):
                for s in p.states:
                    v = s.value
                    if not isinstance(v, CompileShader):
                        continue
                    key = (v.profile, v.function, tuple(v.args))
                    if key in seen:
                        continue
                    seen.add(key)
                    name = f"{path.relative_to(ROOT)}:{v.function}({','.join(v.args)}) {v.profile}"
                    try:
                        st = compile_state(fx, v).program.stats
                    except EffectError as err:
                        out[name] = f"refused: {err.message[:50]}"
                        continue
                    out[name] = [st.total_slots, st.arithmetic_slots, st.texture_slots,
                                 st.temps_used]
    return out


def _pct(values: list[float], q: float) -> float:
    values = sorted(values)
    k = (len(values) - 1) * q
    lo = int(k)
    hi = min(lo + 1, len(values) - 1)
    return values[lo] + (values[hi] - values[lo]) * (k - lo)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--save")
    ap.add_argument("--before")
    a = ap.parse_args()
    now = measure()
    before = json.loads(Path(a.before).read_text()) if a.before else {}
    ratios: list[float] = []
    temps: list[float] = []
    print(f"{'shader':78} {'slots':>6} {'temps':>5}" + (f" {'before':>6} {'ratio':>6}" if before else ""))
    for name, v in now.items():
        b = before.get(name)
        if isinstance(v, str):
            print(f"{name[:78]:78} {v}" + (f"   before: {b if isinstance(b, str) else b[0]}" if b else ""))
            continue
        line = f"{name[:78]:78} {v[0]:6d} {v[3]:5d}"
        if isinstance(b, list):
            ratios.append(v[0] / b[0] if b[0] else 1.0)
            temps.append(v[3] / b[3] if b[3] else 1.0)
            line += f" {b[0]:6d} {v[0] / b[0] if b[0] else 1.0:6.2f}"
        elif b:
            line += f"   before: {b}"
        print(line)
    done = [v for v in now.values() if not isinstance(v, str)]
    print(f"\n{len(done)} compiled, {len(now) - len(done)} refused; slots median "
          f"{statistics.median(x[0] for x in done):.1f}, 90th percentile "
          f"{_pct([x[0] for x in done], 0.9):.1f}")
    if ratios:
        print(f"ours-after / ours-before slots: median {statistics.median(ratios):.3f}, 90th "
              f"percentile {_pct(ratios, 0.9):.3f}, 10th percentile {_pct(ratios, 0.1):.3f}; "
              f"{sum(r < 1 for r in ratios)} shorter, {sum(r > 1 for r in ratios)} longer "
              f"of {len(ratios)}; temps median {statistics.median(temps):.3f}")
    if a.save:
        Path(a.save).write_text(json.dumps(now, indent=1))


if __name__ == "__main__":
    main()
