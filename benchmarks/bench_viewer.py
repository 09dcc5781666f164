"""The viewer as a previewer, timed: a slider dragged on a ps_2_0 effect, and an effect animated
by TIME, each on the GL path with the effect drawn at 512 x 512 in a real window.

    xvfb-run -a -s "-screen 0 1280x800x24" .venv/bin/python benchmarks/bench_viewer.py
        [--seconds 4] [--effect fxfiles/phong.fx --param SpecularPower]

Slider: the left button goes down on the parameter's slider in the panel (its rectangle as
the panel drew it) and the mouse moves along it one step every frame, through the window's
own mouse callbacks, so imgui's slider changes the value and the viewer draws the effect
again (the pass lowered again with the new constant, then drawn). Counted: frames that drew
a new picture per second of wall time, and the median and 95th-percentile time of one such
frame (from the frame before it swapped to its own swap), with the median GL render inside.
Every frame whose value is new must draw anew (one that did not is counted and printed;
at the slider's end the value holds at UIMax for a frame, with nothing new to draw). Also
the process's CPU time per frame (all its threads: llvmpipe's rasteriser threads included):
on a machine shared with other work the wall-clock rate is what is left over, and
1000 / (CPU ms) is the rate the same work gives one otherwise idle core.

TIME: benchmarks/data/wave_ps20.fx (a ps_2_0 wave whose phase is TIME), the clock running, no
input: the same figures. Goal (issue 32): 30 frames per second or more, both.
"""
from __future__ import annotations

import argparse
import os
import statistics
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, ROOT)

from effects.viewer.app import Viewer, ViewerOptions  # noqa: E402

GOAL_FPS = 30.0
SIZE = (952, 560)          # the effect's square: min(560, 952 - 440) = 512
WAVE = os.path.join(ROOT, "benchmarks", "data", "wave_ps20.fx")


class Run:
    def __init__(self, viewer: Viewer, seconds: float, param: str | None) -> None:
        self.viewer, self.seconds, self.param = viewer, seconds, param
        self.frame = 0
        self.start: float | None = None
        self.last: float | None = None
        self.frames: list[float] = []       # wall time of each frame that drew anew
        self.render_ms: list[float] = []
        self.cpu_ms: list[float] = []       # process CPU time of each such frame
        self.cpu_last = time.process_time()
        self.stale = 0                      # frames that drew nothing though their value was new
        self.x = 0.0
        # the panel's values after the last two frames: a frame draws with what the panel set
        # in the frame before it, so it has something new to draw only where those differ
        # (at the slider's end the value holds at UIMax for a frame: nothing new to draw)
        self.values: list[dict] = [{}, {}]

    def __call__(self, event) -> None:
        v = self.viewer
        self.frame += 1
        if self.frame < 10:                 # the first picture, the panel laid out, caches warm
            self.last = event.time
            return
        if self.start is None:
            self.start = event.time
            if self.param is not None:
                x0, y0, x1, y1 = v.status.widget_rects[self.param]
                self.y, self.x0, self.x1 = (y0 + y1) / 2, x0 + 2, x1 - 2
                self.x = self.x0
                v.window.mouse_position_event_func(self.x, self.y, 0, 0)
                v.window.mouse_press_event_func(self.x, self.y, v.window.mouse.left)
            self.last = event.time
            self.cpu_last = time.process_time()
            return
        cpu = time.process_time()
        values = dict(v.state.tweaks.values)
        new_value = self.param is None or self.values[-1] != self.values[-2]
        self.values = [self.values[-1], values]
        if event.render_ms is not None:
            self.frames.append(event.time - self.last)
            self.render_ms.append(event.render_ms)
            self.cpu_ms.append(1000 * (cpu - self.cpu_last))
        elif self.frame > 12 and new_value:
            self.stale += 1
        self.cpu_last = cpu
        self.last = event.time
        if self.param is not None:
            # one step along the slider a frame, back and forth: a new value every frame
            span = self.x1 - self.x0
            k = (self.frame % 200) / 100.0
            self.x = self.x0 + span * (k if k <= 1 else 2 - k)
            v.window.mouse_drag_event_func(self.x, self.y, 1, 0)
        if event.time - self.start >= self.seconds:
            if self.param is not None:
                v.window.mouse_release_event_func(self.x, self.y, v.window.mouse.left)
            v.window.close()


def measure(path: str, param: str | None, seconds: float, technique: str | None) -> dict:
    lines: list[str] = []
    viewer = Viewer(ViewerOptions(path, profile="radeon9700", technique=technique, size=SIZE),
                    output=lines.append)
    run = Run(viewer, seconds, param)
    viewer.on_frame = run
    viewer.run()
    if not run.frames:
        raise SystemExit(f"{path}: no frame drew anew; viewer said:\n" + "\n".join(lines))
    side = viewer.effect_size()
    wall = sum(run.frames)
    frames = sorted(run.frames)
    return {"effect": os.path.relpath(path, ROOT), "param": param or "TIME", "side": side[0],
            "fps": len(run.frames) / wall if wall else 0.0,
            "frame_ms": 1000 * statistics.median(frames),
            "p95_ms": 1000 * frames[int(0.95 * (len(frames) - 1))],
            "render_ms": statistics.median(run.render_ms), "frames": len(run.frames),
            "cpu_ms": statistics.median(run.cpu_ms),
            "stale": run.stale,
            "technique": viewer.loaded.technique.name if viewer.loaded else None}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seconds", type=float, default=4.0, help="length of each run")
    ap.add_argument("--effect", default=os.path.join(ROOT, "fxfiles", "phong.fx"))
    ap.add_argument("--param", default="SpecularPower", help="the slider dragged")
    ap.add_argument("--technique", default="PerPixelPhong_ps20")
    args = ap.parse_args(argv)
    load = os.getloadavg()[0]
    rows = [measure(args.effect, args.param, args.seconds, args.technique),
            measure(WAVE, None, args.seconds, None)]
    print(f"machine: {os.cpu_count()} cores, load average {load:.1f} at the start")
    print(f"{'what':58} {'side':>5} {'fps':>6} {'frame ms':>9} {'p95 ms':>7} {'GL ms':>6} "
          f"{'CPU ms':>7} {'frames':>6} {'stale':>5}")
    ok = True
    for r in rows:
        what = f"{r['effect']} ({r['technique']}): {'drag ' + r['param'] if r['param'] != 'TIME' else 'TIME runs'}"
        print(f"{what:58} {r['side']:>5} {r['fps']:6.1f} {r['frame_ms']:9.1f} {r['p95_ms']:7.1f} "
              f"{r['render_ms']:6.1f} {r['cpu_ms']:7.1f} {r['frames']:>6} {r['stale']:>5}")
        ok &= r["fps"] >= GOAL_FPS and r["stale"] == 0
    print(f"goal: {GOAL_FPS:.0f} frames per second, every frame new: {'met' if ok else 'NOT met'} "
          "(wall clock, on this machine as loaded now)")
    idle = ", ".join(f"{1000 / r['cpu_ms']:.0f}" for r in rows)
    print(f"the same work on one otherwise idle core (1000 / CPU ms): {idle} frames per second")
    return 0


if __name__ == "__main__":
    sys.exit(main())
