"""The viewer as a user runs it: `effects view` in a real window under Xvfb, scripted with
--exit-after and --screenshot, edited from the test while it runs.

These tests need `xvfb-run` (the `xvfb` and `xauth` packages, installed by .ci/setup); without
it they fail with that message rather than skip.
"""
from __future__ import annotations

from tests.paths import ROOT

import glob
import math
import os
import queue
import shutil
import subprocess
import sys
import threading
import time

import numpy as np
import pytest
from PIL import Image

import effects
from effects.host.scene import Camera, Light
from effects.viewer.state import LightPath, Orbit, ViewerState

ROOT = str(ROOT)
FXFILES = sorted(glob.glob(os.path.join(ROOT, "fxfiles", "*.fx")))
CARDS = effects.list_profiles()
# The window is 640x360 in these tests: the effect is the left 360x360 square (PANEL_WIDTH 440
# would leave too little, so tests use --size 800x360: square side min(360, 800 - 440) = 360).
SIZE = "800x360"
SIDE = 360


def xvfb_run() -> str:
    path = shutil.which("xvfb-run")
    if path is None:
        pytest.fail("xvfb-run is not installed: the viewer tests need a virtual X server. "
                    "Run .ci/setup (it installs the xvfb and xauth packages), or "
                    "apt-get install xvfb xauth")
    return path


class ViewerProcess:
    """`effects view ...` under xvfb-run, its stdout lines collected as they come."""

    def __init__(self, *args: str, cwd: str | None = None) -> None:
        cmd = [xvfb_run(), "-a", "-s", "-screen 0 1280x800x24", sys.executable, "-m", "effects",
               "view", *args]
        env = dict(os.environ, PYTHONUNBUFFERED="1")
        self.proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                     text=True, cwd=cwd or ROOT, env=env)
        self.lines: list[str] = []
        self._queue: "queue.Queue[str | None]" = queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            self._queue.put(line.rstrip("\n"))
        self._queue.put(None)

    def expect(self, predicate, what: str, timeout: float = 20.0) -> str:
        """The next line (after those already seen) that satisfies `predicate`."""
        deadline = time.monotonic() + timeout
        while True:
            left = deadline - time.monotonic()
            try:
                line = self._queue.get(timeout=max(0.01, left))
            except queue.Empty:
                line = ""
                if left <= 0:
                    pytest.fail(f"no line {what} within {timeout} s; output so far:\n"
                                + "\n".join(self.lines))
                continue
            if line is None:
                self._queue.put(None)
                pytest.fail(f"the viewer ended before printing {what}; output:\n" + "\n".join(self.lines))
            self.lines.append(line)
            if predicate(line):
                return line

    def finish(self, timeout: float = 60.0) -> int:
        try:
            rc = self.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            pytest.fail("the viewer did not exit; output:\n" + "\n".join(self.lines))
        while True:
            try:
                line = self._queue.get(timeout=5)
            except queue.Empty:
                break
            if line is None:
                break
            self.lines.append(line)
        return rc


def effect_pixels(png: str) -> np.ndarray:
    image = np.asarray(Image.open(png).convert("RGB"))
    assert image.shape[:2] == (360, 800), image.shape
    return image[:, :SIDE]


# ---------------------------------------------------------------------------------------------
# Start-up on every effect and every card


@pytest.mark.parametrize("path", FXFILES, ids=[os.path.basename(p) for p in FXFILES])
def test_viewer_starts_on_every_effect_and_shows_every_card(path, tmp_path):
    """One process per effect: it opens on a card, then --tour draws every other card once."""
    start = CARDS[FXFILES.index(path) * 3 % len(CARDS)]
    shot = tmp_path / "shot.png"
    rel = os.path.relpath(path, ROOT)
    viewer = ViewerProcess(rel, "--profile", start, "--tour", "--size", SIZE,
                           "--screenshot", str(shot), "--exit-after", "60")
    viewer.expect(lambda l: l.startswith(f"view: {rel} on {start}: "), "view: ...")
    rc = viewer.finish()
    # exit 1 (as `effects render`) when the card shown last runs none of the techniques
    last = (CARDS[CARDS.index(start):] + CARDS[:CARDS.index(start)])[-1]
    runs = effects.load_effect(path).find_valid_technique(effects.load_profile(last)) is not None
    assert rc == (0 if runs else 1), "\n".join(viewer.lines)
    selected = [l.split(":")[1].strip() for l in viewer.lines if l.startswith("select: ")]
    tour = CARDS[CARDS.index(start):] + CARDS[:CARDS.index(start)]
    assert selected == tour[1:], "\n".join(viewer.lines)
    assert not [l for l in viewer.lines if "internal error" in l or "Traceback" in l], \
        "\n".join(viewer.lines)
    image = np.asarray(Image.open(shot).convert("RGB"))
    assert image.shape == (360, 800, 3)
    panel = image[:, SIDE:]
    assert panel.std() > 10, "the panel is blank"


# ---------------------------------------------------------------------------------------------
# Editing while it runs


@pytest.fixture
def flat(tinted_effect):
    """The folder of conftest's tinted effect: flat.fx, tint.fxh (red) and base.png."""
    return tinted_effect.parent


def test_edits_while_running_reload_fail_recover_and_end_on_the_last_effect(flat):
    path = flat / "flat.fx"
    effect = path.read_text()
    shot = flat / "final.png"
    viewer = ViewerProcess(str(path), "--profile", "tnt2", "--mesh", "quad", "--size", SIZE,
                           "--exit-after", "5", "--screenshot", str(shot))
    viewer.expect(lambda l: l == f"view: {path} on tnt2: technique Flat (1 pass)", "view: ...")
    ok = f"reload: {path} ok in "
    failed = f"reload: {path} failed: "

    # 1. a good edit of the #include: green
    (flat / "tint.fxh").write_text("#define TINT 0xff00ff00\n")
    line = viewer.expect(lambda l: l.startswith("reload:"), "after a good edit")
    assert line.startswith(ok) and line.endswith(" ms (technique Flat)"), line

    # 2. a truncated write: the located error, and the viewer goes on
    path.write_text(effect[:effect.index("AlphaOp[0]")])
    line = viewer.expect(lambda l: l.startswith("reload:"), "after a truncated write")
    assert line.startswith(failed + f"{path}:"), line
    assert ": error: " in line

    # 3. delete, then create again with other content (blue)
    path.unlink()
    line = viewer.expect(lambda l: l.startswith("reload:"), "after a delete")
    assert line == failed + f"{path}:1:1: error: cannot read effect file: No such file or directory"
    path.write_text(effect.replace("TINT;", "0xff0000ff;"))
    line = viewer.expect(lambda l: l.startswith("reload:"), "after re-creating the file")
    assert line.startswith(ok), line

    # 4. an editor's atomic save: write a temp file, rename it onto the effect (yellow)
    tmp = flat / ".flat.fx.swp"
    tmp.write_text(effect.replace("TINT;", "0xffffff00;"))
    os.replace(tmp, path)
    line = viewer.expect(lambda l: l.startswith("reload:"), "after a rename into place")
    assert line.startswith(ok), line

    assert viewer.finish() == 0, "\n".join(viewer.lines)
    reloads = [l for l in viewer.lines if l.startswith("reload:")]
    assert len(reloads) == 5, reloads          # one line per change, none extra
    pixels = effect_pixels(str(shot))
    # TextureFactor 0xffffff00 selected as the colour: (255, 255, 0) on every pixel of the quad
    assert (pixels == (255, 255, 0)).all(), np.unique(pixels.reshape(-1, 3), axis=0)[:5]


def test_a_broken_file_at_start_opens_with_its_error_and_loads_once_fixed(flat):
    path = flat / "flat.fx"
    effect = path.read_text()
    path.write_text(effect.replace("technique Flat", "technique Flat oops"))
    shot = flat / "fixed.png"
    viewer = ViewerProcess(str(path), "--profile", "tnt2", "--mesh", "quad", "--size", SIZE,
                           "--exit-after", "2.5", "--screenshot", str(shot))
    line = viewer.expect(lambda l: l.startswith("view:"), "view: ... failed")
    assert line.startswith(f"view: {path} failed: {path}:3:"), line
    time.sleep(0.3)
    path.write_text(effect.replace("TINT;", "0xff00ffff;"))
    line = viewer.expect(lambda l: l.startswith("reload:"), "after the fix")
    assert line.startswith(f"reload: {path} ok in "), line
    assert viewer.finish() == 0
    assert (effect_pixels(str(shot)) == (0, 255, 255)).all()


def test_forced_technique_the_card_cannot_run_shows_its_reason(flat):
    viewer = ViewerProcess(str(flat / "flat.fx"), "--profile", "tnt2", "--technique", "Dot3",
                           "--mesh", "quad", "--size", SIZE, "--exit-after", "0.5")
    line = viewer.expect(lambda l: l.startswith("view:"), "view: ...")
    assert line == (f"view: {flat / 'flat.fx'} on tnt2: technique Flat (1 pass); forced Dot3 is "
                    "not valid here: pass P0 (line 15): ColorOp[0] = DotProduct3 needs "
                    "D3DTEXOPCAPS_DOTPRODUCT3; the RIVA TNT2 does not have it")
    assert viewer.finish() == 0


def test_a_stand_in_texture_is_warned_about_once(tmp_path):
    path = tmp_path / "bare.fx"
    path.write_text("texture Base;\nsampler S = sampler_state { Texture = <Base>; };\n"
                    "technique T { pass P { Sampler[0] = <S>; Lighting = false; } }\n")
    viewer = ViewerProcess(str(path), "--profile", "geforce2", "--size", SIZE,
                           "--exit-after", "1.0")
    line = viewer.expect(lambda l: ": warning: " in l, "PATH:LINE:COL: warning: ...")
    assert line.startswith(f"{path}:1:9: warning: texture parameter Base: nothing supplies it")
    assert viewer.finish() == 0
    assert sum(": warning: " in l for l in viewer.lines) == 1
    from effects.viewer.reload import build_effect
    loaded = build_effect(str(path), effects.load_profile("geforce2"), keep_prepare_error=True,
                          strict=True)
    assert "texture parameter Base: nothing supplies it" in str(loaded.prepare_error)


def test_exit_codes_say_what_happened(flat, tmp_path):
    """As the other commands: 2 for a file that does not load (or a screenshot that cannot be
    written), 1 for nothing drawable, 0 otherwise."""
    # a missing file is said before a window opens, as the other commands say it
    missing = flat / "missing.fx"
    viewer = ViewerProcess(str(missing), "--size", SIZE, "--exit-after", "0.3")
    viewer.expect(lambda l: l == f"{missing}:1:1: error: cannot read effect file: No such file "
                                 "or directory", "PATH:1:1: error: cannot read effect file")
    assert viewer.finish() == 2
    viewer = ViewerProcess(str(flat / "flat.fx"), "--profile", "tnt2", "--technique", "Nope",
                           "--size", SIZE, "--exit-after", "0.3")
    assert "no technique named 'Nope'" in viewer.expect(lambda l: l.startswith("view:"), "view:")
    assert viewer.finish() == 2
    viewer = ViewerProcess(str(flat / "flat.fx"), "--profile", "tnt2", "--mesh", "quad",
                           "--size", SIZE, "--exit-after", "0.3",
                           "--screenshot", str(tmp_path / "no" / "such" / "dir.png"))
    viewer.expect(lambda l: l.startswith("screenshot:"), "screenshot: ... failed")
    assert viewer.finish() == 2
    root = tmp_path / "root"
    root.mkdir()
    viewer = ViewerProcess(str(flat / "flat.fx"), "--include-root", str(root), "--size", SIZE,
                           "--exit-after", "0.3")
    assert "escapes the include root" in viewer.expect(lambda l: l.startswith("view:"), "view:")
    assert viewer.finish() == 2


def test_bad_arguments_are_usage_errors():
    out = subprocess.run([sys.executable, "-m", "effects", "view", "x.fx", "--size", "big"],
                         capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 2 and "--size 'big' is not WxH" in out.stderr
    out = subprocess.run([sys.executable, "-m", "effects", "view", "x.fx", "--mesh", "blob"],
                         capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 2 and "unknown mesh 'blob'" in out.stderr


# ---------------------------------------------------------------------------------------------
# The state behind the keys (no window)


def test_keys_step_cards_and_techniques_with_wrap_around():
    state = ViewerState(["tnt2", "geforce3", "radeon9700"], 0)
    state.next_card(-1)
    assert state.card == "radeon9700" and state.selection_generation == 1
    state.next_card(1)
    assert state.card == "tnt2"
    names = ["A", "B"]
    seen = []
    for _ in range(3):
        state.cycle_technique(names)
        seen.append(state.technique)
    assert seen == ["A", "B", None]
    state.cycle_technique(names, -1)
    assert state.technique == "B"
    views = []
    for _ in range(3):
        state.cycle_view()
        views.append(state.view)
    assert views == ["reference", "difference", "gl"]


def test_orbit_camera_positions():
    orbit = Orbit(yaw=0.0, pitch=0.0, distance=3.0)
    assert orbit.eye() == pytest.approx(Camera().eye)           # the scene's default eye, +z
    orbit = Orbit(yaw=math.pi / 2, pitch=math.pi / 6, distance=2.0)
    # x = -d cos(p) sin(y) = -2 * (sqrt(3)/2) * 1; y = d sin(p) = 1
    assert orbit.eye() == pytest.approx((-math.sqrt(3), 1.0, 0.0), abs=1e-12)
    orbit.zoom(100)
    assert orbit.distance == 1.2
    # the viewer opens where `effects render` looks from, its light where the scene's is
    assert Orbit().eye()[2] > 0 and LightPath().position() == pytest.approx(Light().position, abs=0.03)
    orbit.drag(0, 10_000)
    assert orbit.pitch == 1.5


@pytest.mark.parametrize("fx, shader, fixed", [("multilight.fx", "MultiLight_ps20", "MultiLight_ff"),
                                                ("sdk9_hlsl.fx", "Scene_ps14", "Scene_ff")])
def test_a_files_own_lights_stay_its_own_in_the_viewers_scene(fx, shader, fixed):
    # The viewer's scene gives its own light, which a host binds by name (XNA's LightDir0,
    # LightColor0) and by semantic. These files light every technique alike with lights of
    # their own: named so that no scene takes them over. When multilight.fx called its first
    # light LightDir0, the viewer swapped it for its own light in the shader techniques, as the
    # way the light travels (the opposite of what they read), and not in the fixed-function
    # one, which reads LightTravel0: the two differed by 35 levels on average.
    state = ViewerState(cards=["radeon9700"])
    scene = state.scene((96, 96))
    path = os.path.join(ROOT, "fxfiles", fx)
    a, b = (effects.render(path, "radeon9700", scene=scene, size=(96, 96), technique=t)
            .astype(int) for t in (shader, fixed))
    assert np.abs(a - b)[..., :3].mean() < 2.0           # per pixel against per vertex
    assert a[..., :3].mean() > 20                         # and lit: not two black pictures


def test_the_viewer_says_what_its_picture_shows_nothing_of(tmp_path):
    """No silent blank (issue 32): the toon shader whose light direction nothing sets draws
    black; the viewer lists why in its panel and says it once on the console."""
    toon = os.path.join(ROOT, "tests", "data", "blank", "toon_unset_light.fx")
    shot = tmp_path / "toon.png"
    viewer = ViewerProcess(str(toon), "--profile", "radeon9700", "--size", SIZE,
                           "--exit-after", "1.5", "--screenshot", str(shot))
    line = viewer.expect(lambda l: "vLightDirection is set by nothing" in l, "the diagnosis")
    assert line.startswith(f"{toon}:3:8: warning: parameter vLightDirection")
    assert viewer.finish() == 0
    assert sum("vLightDirection is set by nothing" in l and "warning: parameter" in l
               for l in viewer.lines) == 1
    # the sphere is black on the viewer's backdrop: the cause is said though the frame has
    # two colours
    # the panel's list is what the console said: the runtime's frame, diagnosed
    from effects.viewer.app import frame_diagnostics
    from effects.host.runtime import Runtime
    runtime = Runtime(effects.load_effect(toon), "radeon9700", size=(64, 64))
    frame = runtime.render()
    said = frame_diagnostics(runtime, frame.technique, frame.image)
    assert said[0].startswith(f"{toon}:3:8: warning: parameter vLightDirection is set by nothing")
