"""Write docs/performance.md: the quick rows of benchmarks/bench_scale.py, each run as its own
command (a fresh process, as a user would run it), with that command beside its figures, the
date and the machine; then Bishop and Weimer's timing table measured by
benchmarks/bench_fast_phong.py, beside the paper's.

    .venv/bin/python docs/make_performance.py                 # the default rows, ~2.5 min on 2 cores
    .venv/bin/python docs/make_performance.py --rows frame,memory
    .venv/bin/python docs/make_performance.py --all           # also the slow rows (minutes)

The figures are this machine's on the day: the page says which machine and how loaded it was.
"""
from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
PAGE = DOCS / "performance.md"

# bench_scale.py's rows (its --only names) in the order the page shows them, and why the slow
# ones are left out unless asked for (times measured on the 2-core VM, loaded by other work)
ROWS = ["validate-cards", "lower", "render", "frame", "startup", "memory", "mesh", "textures"]
SLOW = {
    "validate": "about 80 s: every technique validated card by card, at three sizes "
                "(`validate-cards` is the same work the way `effects matrix` does it)",
    "sheet": "several minutes: the whole contact sheet drawn six times, in process and as "
             "commands, with --jobs 1, --jobs 2 and on Dask",
}
COMMAND = ".venv/bin/python benchmarks/bench_scale.py --quick --only {row}"
# Bishop and Weimer's timing table, measured in one run of each command (interleaved rounds)
FAST_PHONG = ".venv/bin/python benchmarks/bench_fast_phong.py --repeat 15"
FAST_PHONG_FRAMES = ".venv/bin/python benchmarks/bench_fast_phong.py --renderer --size 512 --repeat 9"


def run_row(row: str) -> tuple[list[list[str]], list[str], float]:
    """(rows, notes, seconds) of one bench_scale row run as a command."""
    argv = [sys.executable, str(ROOT / "benchmarks" / "bench_scale.py"), "--quick", "--only", row,
            "--json"]
    start = time.perf_counter()
    done = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True)
    seconds = time.perf_counter() - start
    if done.returncode != 0:
        raise SystemExit(f"{COMMAND.format(row=row)} failed:\n{done.stdout[-2000:]}{done.stderr[-2000:]}")
    lines = done.stdout.splitlines()
    rows = json.loads(lines[-1])
    # bench_scale prints its remarks on a row as indented lines in parentheses
    notes = [line.strip() for line in lines[:-1] if line.startswith("  (")]
    return rows, notes, seconds


def run_json(command: str) -> tuple[dict, float]:
    """The JSON line a benchmark command prints with --json, and the seconds it ran."""
    argv = [sys.executable, *command.split()[1:], "--json"]
    start = time.perf_counter()
    done = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True)
    seconds = time.perf_counter() - start
    if done.returncode != 0:
        raise SystemExit(f"{command} failed:\n{done.stdout[-2000:]}{done.stderr[-2000:]}")
    return json.loads(done.stdout.splitlines()[-1]), seconds


def fast_phong_section(table: dict, frames: dict) -> list[str]:
    """Bishop and Weimer's timing table beside the paper's, as ratios to Gouraud."""
    out = [
        "## Fast Phong shading: the paper's timing table",
        "",
        "Bishop and Weimer timed figure 4 (14,620 polygons at 2048²) on a microVAX-II; "
        "`benchmarks/bench_fast_phong.py` shades a 64 × 128 sphere at "
        f"{table['size']}² ({table['pixels']:,} pixels) in the NumPy reference's screen-space "
        f"shader, every mode once a round for {table['rounds']} interleaved rounds of CPU time. "
        "A ratio is the median over the rounds of the mode's time over that round's Gouraud "
        "time, with the lowest and highest round. NumPy runs each step over every pixel at "
        "once, so a pixel's additions cost about what its square root does: the ratios are "
        "this implementation's, not the microVAX's.",
        "",
        "| shading | paper: CPU s | paper: ratio | measured: best round | measured: ratio (rounds) | command |",
        "|---|---|---|---|---|---|",
    ]
    for row in table["rows"]:
        paper_s = f"{row['paper_s']:.0f}" if row["paper_s"] else "—"
        paper_r = f"{row['paper_ratio']:.2f}" if row["paper_ratio"] else "—"
        out.append(f"| {row['name']} | {paper_s} | {paper_r} | {row['ms']:.1f} ms | "
                   f"{row['ratio']:.2f} ({row['ratio_low']:.2f}–{row['ratio_high']:.2f}) | "
                   f"`{FAST_PHONG}` |")
    phong = next(r for r in table["rows"] if r["name"] == "phong (normalised normal), infinite eye")
    out += ["",
            f"Normalised-normal Phong over the Taylor form (eye at infinity): {phong['over_taylor']:.2f}× "
            f"(rounds {phong['over_taylor_low']:.2f}–{phong['over_taylor_high']:.2f}); the paper's "
            f"3900 s / 767 s is 5.08×.",
            "",
            f"Through the renderer (`fxfiles/fast_phong.fx`, whole {frames['size']}² frames on the "
            f"reference back end, one thread, {frames['rounds']} interleaved rounds), where "
            "transforming, rasterising and writing the frame are shared by every mode:",
            "",
            "| frame | best round | ratio to Gouraud (rounds) | command |",
            "|---|---|---|---|"]
    for row in frames["rows"]:
        out.append(f"| {row['name']} | {row['ms']:.1f} ms | {row['ratio']:.2f} "
                   f"({row['ratio_low']:.2f}–{row['ratio_high']:.2f}) | `{FAST_PHONG_FRAMES}` |")
    out += ["",
            f"Normalised-normal Phong frame over the Taylor frame: {frames['over_taylor']:.2f}× "
            f"(rounds {frames['over_taylor_low']:.2f}–{frames['over_taylor_high']:.2f}; the Taylor "
            f"frame faster in {frames['faster_rounds']} of {frames['rounds']} rounds).",
            ""]
    return out


def machine() -> str:
    """One line: the processor, cores, memory, OS, Python and NumPy."""
    cpu = platform.processor() or platform.machine()
    memory = ""
    try:
        with open("/proc/cpuinfo") as info:
            cpu = next((line.split(":", 1)[1].strip() for line in info if line.startswith("model name")), cpu)
        with open("/proc/meminfo") as info:
            kib = int(next(line.split()[1] for line in info if line.startswith("MemTotal")))
        memory = f", {kib / (1 << 20):.0f} GiB memory"
    except (OSError, StopIteration, ValueError):
        pass
    import numpy
    return (f"{cpu}, {os.cpu_count()} cores{memory}; {platform.system()} {platform.release()}; "
            f"Python {platform.python_version()}, NumPy {numpy.__version__}")


def _cell(text: str) -> str:
    return " ".join(str(text).split()).replace("|", "\\|")


def page(results: list[tuple[str, list[list[str]], list[str], float]], started: datetime.datetime,
         loads: tuple[float, float], left_out: list[str],
         fast_phong: tuple[dict, dict] | None = None) -> str:
    total = sum(seconds for *_, seconds in results)
    out = [
        "# Performance",
        "",
        "Written by `docs/make_performance.py`, which runs each row of",
        "`benchmarks/bench_scale.py --quick` as its own command (the one beside each figure) and",
        "writes this page; run it again to measure your machine. What each row measures, and how",
        "(medians of CPU time for the growth rows, minima of wall-clock runs for the others), is",
        "in that benchmark's docstring. The goals are those of the issues that asked for the work;",
        "`MISSED` marks one this run did not reach.",
        "",
        f"Measured {started:%Y-%m-%d %H:%M} UTC on {machine()}; load average {loads[0]:.1f} "
        f"before and {loads[1]:.1f} after (the machine is shared: absolute times move by 10-30 % "
        "from run to run; ratios and exponents move less).",
        "",
        "| work | figures | exponent | goal | command |",
        "|---|---|---|---|---|",
    ]
    for row, rows, _, _ in results:
        for work, figures, exponent, goal in rows:
            out.append(f"| {_cell(work)} | {_cell(figures)} | {_cell(exponent)} | {_cell(goal)} "
                       f"| `{COMMAND.format(row=row)}` |")
    notes = [(row, note) for row, _, row_notes, _ in results for note in row_notes]
    if notes:
        out += ["", "Remarks the benchmark printed with its rows:", ""]
        out += [f"- `{row}`: {_cell(note)}" for row, note in notes]
    out += ["", f"How long each command ran (the page took {total:.0f} s):", "",
            "| row | seconds |", "|---|---|"]
    out += [f"| `{row}` | {seconds:.0f} |" for row, _, _, seconds in results]
    if left_out:
        out += ["", "Rows left out of this run (`docs/make_performance.py --all` runs them):", ""]
        out += [f"- `{row}`: {SLOW.get(row, 'not asked for')} "
                f"(`{COMMAND.format(row=row)}`)" for row in left_out]
    if fast_phong is not None:
        out += ["", *fast_phong_section(*fast_phong)]
    out += [
        "",
        "## Other benchmarks",
        "",
        "Not in the table above; each prints its own figures:",
        "",
        "| command | what it measures |",
        "|---|---|",
        "| `.venv/bin/python benchmarks/bench_render.py` | one 512² Phong frame three ways: the NumPy reference, the GL path, and the same shading written by hand in GLSL |",
        "| `.venv/bin/python benchmarks/bench_hlsl.py` | HLSL compile times, cold and cached, by function size |",
        "| `.venv/bin/python benchmarks/bench_load.py` | `load_effect` of a generated 1,000-line effect |",
        "| `.venv/bin/python benchmarks/bench_matrix.py --runs 9` | `effects matrix fxfiles/*.fx` as a command: rows kept, one or every effect edited, store cold or off |",
        "| `.venv/bin/python benchmarks/bench_matrix_phases.py` | two phases of `effects matrix fxfiles/*.fx`, each alone in a fresh interpreter |",
        "| `.venv/bin/python benchmarks/bench_raster.py` | the NumPy reference on a 512² lit sphere drawn by a hand-written vertex and fragment program |",
        "| `.venv/bin/python benchmarks/bench_flow.py` | Shader Model 3 flow control: `multilight.fx`'s ps_3_0 loop against its unrolled ps_2_0 technique, on both back ends |",
        "| `.venv/bin/python benchmarks/bench_fast_phong.py --errors` | the Taylor form's error against exact Phong as a triangle's normals spread |",
        "| `xvfb-run -a -s \"-screen 0 1280x800x24\" .venv/bin/python benchmarks/bench_reload.py` | viewer hot reload, from the write to the first frame drawn with the new effect (`--hlsl-edit --breakdown` for an HLSL edit, by part) |",
        "| `xvfb-run -a -s \"-screen 0 1280x800x24\" .venv/bin/python benchmarks/bench_viewer.py` | the viewer as a previewer at 512²: frames per second while a slider is dragged on phong.fx's ps_2_0 technique (each frame a new value), and while `TIME` runs a ps_2_0 wave (goal: 30) |",
        "",
    ]
    return "\n".join(out)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", default="", help="comma-separated bench_scale rows (default: "
                    + ",".join(ROWS) + ")")
    ap.add_argument("--all", action="store_true", help="also the slow rows: " + ", ".join(SLOW))
    ap.add_argument("-o", "--output", default=str(PAGE), help="the page to write")
    ap.add_argument("--no-fast-phong", action="store_true",
                    help="leave out Bishop and Weimer's timing table (benchmarks/bench_fast_phong.py)")
    args = ap.parse_args(argv)
    rows = [r for r in args.rows.split(",") if r] or (["validate", *ROWS, "sheet"] if args.all else ROWS)
    left_out = [r for r in ["validate", *ROWS, "sheet"] if r not in rows]
    started = datetime.datetime.now(datetime.timezone.utc)
    before = os.getloadavg()[0]
    results = []
    for row in rows:
        print(f"{COMMAND.format(row=row)} ...", flush=True)
        found, notes, seconds = run_row(row)
        results.append((row, found, notes, seconds))
        print(f"  {seconds:.0f} s", flush=True)
    fast_phong = None
    if not args.no_fast_phong:
        print(f"{FAST_PHONG} ...", flush=True)
        table, seconds = run_json(FAST_PHONG)
        print(f"  {seconds:.0f} s\n{FAST_PHONG_FRAMES} ...", flush=True)
        frames, seconds = run_json(FAST_PHONG_FRAMES)
        print(f"  {seconds:.0f} s", flush=True)
        fast_phong = (table, frames)
    Path(args.output).write_text(page(results, started, (before, os.getloadavg()[0]), left_out,
                                      fast_phong), encoding="utf-8")
    print(f"wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
