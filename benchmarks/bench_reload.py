"""Reload latency of the viewer: an edit written to disk -> the first frame drawn with it.

    xvfb-run -a -s "-screen 0 1280x800x24" python benchmarks/bench_reload.py [--edits 15]
        [--card radeon9700] [--effect fxfiles/phong.fx]...

For each bundled effect (a copy in a temporary folder, textures included) a viewer runs in a
child process. A thread in it edits the effect `--edits` times -- alternately an in-place
write and an editor's atomic save (write a temp file, rename it onto the effect) -- each
edit changing a comment at the end, so the whole rebuild runs (read, preprocess, parse,
validate, select, lower, textures, draw). The time from just before the write to the return
of the swap of the first frame drawn with the rebuilt effect is one sample; the next edit
waits until the viewer is idle again. Printed: per effect the median and the worst sample
and the median build time in the worker, then the median over all samples. Goal: 50 ms.
The watcher's wait is part of every sample: both kinds of edit end a save (the in-place write
closes the file, the atomic save renames onto it), so it is the settle time
(effects.viewer.watch.SETTLE_S), not the debounce (DEBOUNCE_S) a write still open would wait.

`--hlsl-edit`: a one-line change to HLSL code instead (issue 11's reload goal), for the effects
whose pixel shader is a `compile` of an HLSL function: each edit rewrites, in place, the first
assignment line of that function (`x = e;` -> `x = (e) * 1.000N;`, N the edit's number), so the
function compiles again for its target(s) on every reload while the other shaders are kept.

`--breakdown`: also where each sample's time went (medians over the edits, ms): the watcher's
event (the watcher's wait included), the build and inside it load / validate (HLSL compiles included) /
HLSL compiles / prepare (lowering, textures, streams) / listing, then the first draw of the new
effect (the GL program build inside it) and the buffer swaps until the frame is shown. The
parts are timed by wrapping those functions in the child; they overlap (validate holds the
compiles) and the render thread's frames of the old effect drawn while the build runs are in
"draw" and "swap" too.
"""
from __future__ import annotations

import argparse
import glob
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GOAL_MS = 50.0


def hlsl_edit_line(text: str) -> int | None:
    """The index of the line that `--hlsl-edit` rewrites: the first `x = e;` line of the
    function the first `PixelShader = compile` names (None: the effect has none)."""
    m = re.search(r"PixelShader\s*=\s*compile\s+\w+\s+(\w+)\s*\(", text)
    if m is None:
        return None
    lines = text.split("\n")
    start = next((k for k, line in enumerate(lines)
                  if re.match(rf"\s*\w+\s+{m.group(1)}\s*\(", line)), None)
    if start is None:
        return None
    for k in range(start + 1, len(lines)):
        if re.fullmatch(r"\s*[\w.]+(\s+\w+)?\s*=[^=].*;\s*", lines[k]):
            return k
    return None


def edited(text: str, i: int, hlsl_line: int | None) -> str:
    """Edit number `i`: a comment at the end, or the HLSL line scaled by 1.000N."""
    if hlsl_line is None:
        return text + f"\n// edit {i}\n"
    lines = text.split("\n")
    lhs, rhs = lines[hlsl_line].split("=", 1)
    lines[hlsl_line] = f"{lhs}= ({rhs.strip().rstrip(';')}) * 1.{i + 1:04d};"
    return "\n".join(lines)


_PARTS: list[tuple[str, float, float]] = []      # (part, start, ms) while --breakdown times


def _timed(owner, attr: str, part: str) -> None:
    real = getattr(owner, attr)

    def wrapper(*args, **kwargs):
        start = time.perf_counter()
        try:
            return real(*args, **kwargs)
        finally:
            _PARTS.append((part, start, (time.perf_counter() - start) * 1000.0))
    setattr(owner, attr, wrapper)


def _instrument() -> None:
    import moderngl

    import effects.frontend.loader as loader
    import effects.shaders.hlsl.compiler as compiler
    import effects.validate.technique as technique
    import effects.viewer.app as app
    import effects.viewer.reload as reload
    _timed(loader, "load_effect", "load")
    _timed(technique, "validate_technique", "validate")
    _timed(compiler, "compile_shader", "HLSL compile")
    _timed(reload, "prepare", "prepare")
    _timed(reload, "technique_listing", "listing")
    _timed(app.Viewer, "_render_effect", "draw (effect)")
    _timed(moderngl.Context, "program", "GL program build")
    opened = app.Viewer._open_window

    def open_window(self):
        opened(self)
        _timed(self.window, "swap_buffers", "swap")
    app.Viewer._open_window = open_window


def measure_one(path: str, card: str, edits: int, hlsl: bool = False,
                breakdown: bool = False) -> dict:
    """Run a viewer on `path` in this process and time `edits` edits."""
    from effects.viewer.watch import SETTLE_S
    from effects.viewer.app import FrameEvent, Viewer, ViewerOptions
    if breakdown:
        _instrument()
    parts: list[dict[str, float]] = []

    text = open(path, encoding="utf-8").read()
    hlsl_line = hlsl_edit_line(text) if hlsl else None
    if hlsl and hlsl_line is None:
        raise SystemExit(f"{path}: no HLSL pixel shader function to edit")
    frames: list[FrameEvent] = []
    new_frame = threading.Condition()
    samples: list[float] = []
    builds: list[float] = []
    after_event: list[float] = []
    done = threading.Event()

    def on_frame(event: FrameEvent) -> None:
        with new_frame:
            frames.append(event)
            new_frame.notify_all()
        if done.is_set():
            viewer.window.close()

    def wait_for(predicate, timeout: float = 10.0) -> FrameEvent:
        deadline = time.perf_counter() + timeout
        with new_frame:
            while True:
                hit = next((f for f in reversed(frames) if predicate(f)), None)
                if hit is not None:
                    return hit
                left = deadline - time.perf_counter()
                if left <= 0:
                    raise TimeoutError("the viewer drew no frame with the edit")
                new_frame.wait(left)

    def editor() -> None:
        try:
            wait_for(lambda f: f.number >= 3, 30.0)
            for i in range(edits):
                time.sleep(0.15)                       # idle: the last frame is long drawn
                generation = frames[-1].effect_generation
                body = edited(text, i, hlsl_line)
                _PARTS.clear()
                start = time.perf_counter()
                if i % 2:
                    tmp = path + ".tmp"
                    with open(tmp, "w", encoding="utf-8") as f:
                        f.write(body)
                    os.replace(tmp, path)
                else:
                    with open(path, "w", encoding="utf-8") as f:
                        f.write(body)
                frame = wait_for(lambda f: f.effect_generation > generation)
                samples.append((frame.time - start) * 1000.0)
                if frame.result is not None:
                    builds.append(frame.result.build_ms)
                    after_event.append((frame.time - frame.result.requested_at) * 1000.0)
                    row = {"event": (frame.result.requested_at - start) * 1000.0,
                           "build": frame.result.build_ms}
                    for part, at, ms in list(_PARTS):
                        if start <= at <= frame.time:
                            row[part] = row.get(part, 0.0) + ms
                    parts.append(row)
        finally:
            done.set()

    viewer = Viewer(ViewerOptions(path, profile=card, exit_after=120.0), on_frame=on_frame,
                    output=lambda line: None)
    threading.Thread(target=editor, daemon=True).start()
    viewer.run()
    return {"effect": os.path.basename(path), "card": card, "samples_ms": samples,
            "build_ms": builds, "after_event_ms": after_event,
            "settle_ms": SETTLE_S * 1000.0, "parts": parts}


def drawable_card(path: str, preferred: str) -> str | None:
    """`preferred` if its technique for the effect can be prepared, else the most capable card
    whose can (a reload that cannot be drawn is a failed reload: nothing to time)."""
    import effects
    from effects.viewer.reload import build_effect
    cards = [preferred] + [c for c in reversed(effects.list_profiles()) if c != preferred]
    for card in cards:
        loaded = build_effect(path, effects.load_profile(card), keep_prepare_error=True)
        if loaded.technique is not None and loaded.prepare_error is None:
            return card
    return None


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--edits", type=int, default=15)
    parser.add_argument("--card", default="radeon9700")
    parser.add_argument("--effect", action="append", default=[], help="default: every fxfiles/*.fx")
    parser.add_argument("--hlsl-edit", action="store_true",
                        help="edit one line of the HLSL pixel shader function, not a comment")
    parser.add_argument("--breakdown", action="store_true",
                        help="also print where each sample's time went (see above)")
    parser.add_argument("--one", help=argparse.SUPPRESS)     # child mode: one effect, JSON out
    args = parser.parse_args(argv)
    if args.one:
        if os.path.abspath(args.one).startswith(ROOT + os.sep):
            parser.error("--one edits the file it is given: pass a copy outside the project")
        print(json.dumps(measure_one(args.one, args.card, args.edits, args.hlsl_edit,
                                     args.breakdown)), flush=True)
        return 0

    effects_ = args.effect or sorted(glob.glob(os.path.join(ROOT, "fxfiles", "*.fx")))
    all_samples: list[float] = []
    with tempfile.TemporaryDirectory() as tmp:
        shutil.copytree(os.path.join(ROOT, "fxfiles"), os.path.join(tmp, "fxfiles"))
        print(f"{'effect':<20} {'card':<14} {'median':>9} {'worst':>9} {'build':>9} "
              f"{'event->frame':>16}")
        for source in effects_:
            copy = os.path.join(tmp, "fxfiles", os.path.basename(source))
            if not os.path.exists(copy):
                shutil.copy(source, copy)
            if args.hlsl_edit and hlsl_edit_line(open(copy, encoding="utf-8").read()) is None:
                continue                       # no HLSL pixel shader function to edit
            card = drawable_card(copy, args.card)
            if card is None:
                print(f"{os.path.basename(source):<20} no card can draw it: skipped")
                continue
            out = subprocess.run([sys.executable, __file__, "--one", copy, "--card", card,
                                  "--edits", str(args.edits)]
                                 + (["--hlsl-edit"] if args.hlsl_edit else [])
                                 + (["--breakdown"] if args.breakdown else []),
                                 capture_output=True, text=True, cwd=ROOT)
            line = out.stdout.strip().splitlines()[-1] if out.stdout.strip() else ""
            if out.returncode != 0 or not line.startswith("{"):
                print(f"{os.path.basename(source)}: failed\n{out.stdout}{out.stderr}")
                return 1
            result = json.loads(line)
            samples = result["samples_ms"]
            if not samples:
                print(f"{os.path.basename(source)}: no edit was drawn\n{out.stdout}{out.stderr}")
                return 1
            all_samples += samples
            build = statistics.median(result["build_ms"])
            rest = statistics.median(result["after_event_ms"])
            print(f"{result['effect']:<20} {card:<14} {statistics.median(samples):7.1f}ms "
                  f"{max(samples):7.1f}ms {build:7.1f}ms {rest:14.1f}ms")
            if args.breakdown and result["parts"]:
                names = list(dict.fromkeys(k for row in result["parts"] for k in row))
                print("    " + ", ".join(
                    f"{k} {statistics.median(row.get(k, 0.0) for row in result['parts']):.1f}"
                    for k in names))
    median = statistics.median(all_samples)
    print(f"median write -> first frame with the edit: {median:.1f} ms over {len(all_samples)} "
          f"edits (goal {GOAL_MS:.0f} ms; the watcher's {result['settle_ms']:.0f} ms settle "
          "after each completed save included)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
