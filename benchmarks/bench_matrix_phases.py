"""Time two phases of `effects matrix fxfiles/*.fx`, each alone in a fresh interpreter.

    python benchmarks/bench_matrix_phases.py [--runs 9]

CPU milliseconds (time.process_time: the machine's other work inflates wall time more) of
each phase, imports not counted, median and min of --runs fresh processes:
- profiles: the first list_profiles() and load_profile() of every bundled card (YAML parse,
  checks, merging), then what the matrix asks again once they are loaded (list_profiles()
  and load_profile(card) for each of the 11 effect files);
- assembly: the shader blocks one matrix run assembles (recorded from a `matrix --jobs 1`
  run with the shader store off) assembled again, then check_cached + lowering_cached and
  the stats of each program, as validation asks for them.
"""
from __future__ import annotations

import argparse
import os
import pickle
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

_PROFILES = """
import time
from effects.d3d9 import caps
t0 = time.process_time()
for name in caps.list_profiles():
    caps.load_profile(name)
t1 = time.process_time()
for _ in range(11):
    for name in caps.list_profiles():
        caps.load_profile(name)
t2 = time.process_time()
print((t1 - t0) * 1e3, (t2 - t1) * 1e3)
"""

_RECORD = """
import contextlib, glob, io, os, pickle, sys
os.environ["EFFECTS_CACHE"] = "off"
from effects.cli import main as cli
from effects.shaders.asm import parser
blocks = []
parse = parser._Parser.parse
def recording(self):
    blocks.append(self.block)
    return parse(self)
parser._Parser.parse = recording
with contextlib.redirect_stdout(io.StringIO()):
    cli.main(["matrix", "--jobs", "1", *sorted(glob.glob("fxfiles/*.fx"))])
with open(sys.argv[1], "wb") as f:
    pickle.dump(blocks, f)
"""

_ASSEMBLY = """
import pickle, sys, time
from effects.base.errors import AsmError
from effects.shaders.asm import assemble, check_cached
from effects.shaders.asm import lower  # noqa: F401  (imported by validation before; not timed)
from effects.shaders.asm.limits import lowering_cached
with open(sys.argv[1], "rb") as f:
    blocks = pickle.load(f)
t0 = time.process_time()
programs = []
for block in blocks:
    try:
        programs.append(assemble(block))
    except AsmError:
        pass
t1 = time.process_time()
for program in programs:
    if not check_cached(program):
        lowering_cached(program, {})
t2 = time.process_time()
for program in programs:
    program.stats
t3 = time.process_time()
print((t1 - t0) * 1e3, (t2 - t1) * 1e3, (t3 - t2) * 1e3, len(blocks))
"""


def _run(code: str, *args: str) -> list[float]:
    out = subprocess.run([sys.executable, "-c", code, *args], cwd=ROOT, check=True,
                         capture_output=True, text=True).stdout.split()
    return [float(x) for x in out]


def _line(label: str, values: list[float]) -> str:
    return f"{label:<34}{statistics.median(values):7.2f} ms  (min {min(values):.2f}, {len(values)} runs)"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=9)
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="bench-phases-") as tmp:
        blocks = os.path.join(tmp, "blocks.pickle")
        _run(_RECORD, blocks)
        with open(blocks, "rb") as f:
            count = len(pickle.load(f))
        profiles, assembly = [], []
        for _ in range(args.runs):          # interleaved: the same load for both
            profiles.append(_run(_PROFILES))
            assembly.append(_run(_ASSEMBLY, blocks))
    print(_line("profiles: first load of 20", [p[0] for p in profiles]))
    print(_line("profiles: 11 x the matrix's asks", [p[1] for p in profiles]))
    print(_line(f"assembly: assemble {count} blocks", [a[0] for a in assembly]))
    print(_line("assembly: check + lowering check", [a[1] for a in assembly]))
    print(_line("assembly: stats", [a[2] for a in assembly]))
    print(_line("assembly: all", [a[0] + a[1] + a[2] for a in assembly]))
    if hasattr(os, "getloadavg"):
        print(f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())} ({os.cpu_count()} cores)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
