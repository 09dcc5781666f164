"""Drives `effects view` in a real window (under xvfb-run) as a user would: clicks a slider,
types a texture path into its field and presses Enter, edits the file, lets the clock run; a
screenshot after each step. Run by tests/viewer/test_previewer.py and benchmarks/bench_viewer.py:

    xvfb-run -a python tests/viewer/previewer_driver.py edit EFFECT.fx OUT_DIR IMAGE.png
    xvfb-run -a python tests/viewer/previewer_driver.py run EFFECT.fx OUT_DIR

It writes OUT_DIR/NAME.png per screenshot and OUT_DIR/result.json (what each step saw).
Input goes through the window's own callbacks (the functions pyglet calls on a click or a
key), so the panel's imgui widgets do the changing, not a shortcut into the state.
"""
from __future__ import annotations

import json
import os
import sys
import time
from types import SimpleNamespace

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, ROOT)

from effects.viewer.app import Viewer, ViewerOptions  # noqa: E402

SIZE = (800, 700)     # the effect is the top-left 360 x 360 square; the panel is tall enough
                      # to show every parameter of the test effect


class Script:
    """Steps run one per frame after the first few: each returns True when done (else it is
    run again next frame, e.g. while waiting for a reload)."""

    def __init__(self, viewer: Viewer, out: str, steps) -> None:
        self.viewer, self.out, self.steps = viewer, out, list(steps)
        self.result: dict = {"shots": {}, "log": []}
        self.frame = 0
        self.window = None

    def __call__(self, event) -> None:
        self.frame += 1
        if self.frame < 4:          # a few frames for the first picture and the panel's layout
            return
        if not self.steps:
            self.viewer.window.close()
            return
        if self.steps[0](self):
            self.steps.pop(0)

    # -- what a user does
    def shot(self, name: str):
        def step(s: "Script") -> bool:
            v = s.viewer
            v._draw_frame()
            path = os.path.join(s.out, f"{name}.png")
            v._save_screenshot(path)
            s.result["shots"][name] = {"seconds": v.state.clock.seconds, "path": path,
                                       "tweaks": {str(k): val for k, val in v.state.tweaks.values.items()}}
            return True
        return step

    def press(self, widget: str, fraction: float):
        """Left button down on a widget, `fraction` of its width from its left, then up."""
        state = {"phase": 0}

        def step(s: "Script") -> bool:
            v = s.viewer
            x0, y0, x1, y1 = v.status.widget_rects[widget]
            x, y = x0 + fraction * (x1 - x0), (y0 + y1) / 2
            left = v.window.mouse.left
            if state["phase"] == 0:
                v.window.mouse_position_event_func(x, y, 0, 0)
            elif state["phase"] == 1:
                v.window.mouse_press_event_func(x, y, left)
            elif state["phase"] == 3:
                v.window.mouse_release_event_func(x, y, left)
            state["phase"] += 1
            return state["phase"] > 5       # a few frames for the change to be drawn
        return step

    def type_text(self, text: str):
        """Characters into the focused field, then Enter."""
        state = {"phase": 0}

        def step(s: "Script") -> bool:
            v = s.viewer
            keys = v.window.keys
            mods = SimpleNamespace(shift=False, ctrl=False, alt=False)
            if state["phase"] == 0:
                for char in text:
                    v.window.unicode_char_entered_func(char)
            elif state["phase"] == 1:
                v.window.key_event_func(keys.ENTER, keys.ACTION_PRESS, mods)
            elif state["phase"] == 2:
                v.window.key_event_func(keys.ENTER, keys.ACTION_RELEASE, mods)
            state["phase"] += 1
            return state["phase"] > 5
        return step

    def key(self, name: str):
        def step(s: "Script") -> bool:
            keys = s.viewer.window.keys
            mods = SimpleNamespace(shift=False, ctrl=False, alt=False)
            s.viewer.window.key_event_func(getattr(keys, name), keys.ACTION_PRESS, mods)
            s.viewer.window.key_event_func(getattr(keys, name), keys.ACTION_RELEASE, mods)
            return True
        return step

    def edit_file(self, path: str, old: str, new: str):
        state: dict = {}

        def step(s: "Script") -> bool:
            if not state:
                state["generation"] = s.viewer.effect_generation
                state["start"] = time.monotonic()
                text = open(path).read()
                tmp = path + ".part"
                with open(tmp, "w") as f:
                    f.write(text.replace(old, new))
                os.replace(tmp, path)
                return False
            if s.viewer.effect_generation != state["generation"]:
                if "frames" not in state:
                    s.result["log"].append(f"reloaded after {time.monotonic() - state['start']:.2f} s")
                state.setdefault("frames", 0)
                state["frames"] += 1
                return state["frames"] > 3
            if time.monotonic() - state["start"] > 30:
                s.result["log"].append("no reload within 30 s")
                return True
            return False
        return step

    def wait(self, frames: int):
        state = {"left": frames}

        def step(s: "Script") -> bool:
            state["left"] -= 1
            return state["left"] <= 0
        return step

    def record(self, name: str, fn):
        def step(s: "Script") -> bool:
            s.result[name] = fn(s.viewer)
            return True
        return step


def runtime_value(name: str):
    def read(viewer: Viewer):
        param = viewer.status.runtime.effect.parameter(name)
        value = param.value
        return value.tolist() if hasattr(value, "tolist") else value
    return read


def main(argv: list[str]) -> int:
    mode, path, out = argv[0], argv[1], argv[2]
    os.makedirs(out, exist_ok=True)
    lines: list[str] = []
    if mode == "edit":
        image = argv[3]
        options = ViewerOptions(path, profile="radeon9700", mesh="quad", size=SIZE, time=0.125)
        viewer = Viewer(options, output=lines.append)
        script = Script(viewer, out, [])
        script.steps = [
            script.shot("start"),
            script.press("Speed", 0.0),                 # the slider's left end: UIMin
            script.record("speed_after_click", runtime_value("Speed")),
            script.shot("slider"),
            script.press("Pattern", 0.5),               # focus the texture's path field
            script.type_text(image),
            script.shot("texture"),
            script.edit_file(path, "// the end", "// the end, edited"),
            script.record("speed_after_reload", runtime_value("Speed")),
            script.shot("reloaded"),
            script.key("PERIOD"),                       # one frame forward (1/30 s)
            script.wait(3),
            script.shot("stepped"),
        ]
    else:
        options = ViewerOptions(path, profile="radeon9700", mesh="quad", size=SIZE)
        viewer = Viewer(options, output=lines.append)
        script = Script(viewer, out, [])
        script.steps = [script.shot("first"), script.wait(20), script.shot("later"),
                        script.key("SPACE"), script.wait(3), script.shot("paused"),
                        script.wait(10), script.shot("still_paused")]
    viewer.on_frame = script
    rc = viewer.run()
    script.result["rc"] = rc
    script.result["lines"] = lines
    script.result["errors"] = dict(viewer.state.tweaks.errors)
    with open(os.path.join(out, "result.json"), "w") as f:
        json.dump(script.result, f, indent=1, default=str)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
