"""The viewer's listing window (key C): the text it holds for the technique it draws is what
`effects compile` prints for that technique's passes, it follows reloads and card switches,
and a broken reload keeps the last good listing with the error.

The window parts run `effects view` (or the key handler) under xvfb-run, as tests/viewer/test_viewer.py
does; without xvfb-run they fail saying so rather than skip.
"""
from __future__ import annotations

from tests.paths import ROOT

import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import effects
from effects.cli.main import main
from effects.viewer.app import Viewer, ViewerOptions
from effects.viewer.reload import Reloader, build_effect, effect_builder


def save(path: Path, text: str) -> None:
    """Write an edit atomically, as test_reload's save() does: a plain write truncates first,
    and on a loaded machine the polling watcher can read the empty file in between (an empty
    effect loads "ok" with no technique, and the result a test expects is the one after)."""
    tmp = f"{path}.part"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)

SDK9 = ROOT / "fxfiles" / "sdk9_hlsl.fx"


def compile_output(capsys, *argv: str) -> str:
    assert main(["compile", *argv]) == 0
    return capsys.readouterr().out


def viewer_for(path: Path, card: str) -> Viewer:
    """A Viewer without its window: the builds, swaps and listing text are the window's own."""
    viewer = Viewer(ViewerOptions(str(path), profile=card, size=(800, 360)), output=lambda _: None)
    assert viewer._initial_build() is not None, viewer.status.error
    return viewer


@pytest.mark.parametrize("path, card, technique", [
    (SDK9, "radeon9700", "Scene_ps20"),            # vs_2_0 + ps_2_0 compiled from HLSL
    (SDK9, "geforce3", "Scene_ps11"),              # vs_1_1 + ps_1_1
    (ROOT / "fxfiles" / "sdk8_style.fx", "radeon8500", "TPS4"),   # hand-written asm blocks
    (ROOT / "fxfiles" / "sdk9_style.fx", "radeon9700", "Marble_ps20"),   # two passes
])
def test_the_listing_held_per_pass_is_effects_compile_for_that_pass(capsys, path, card, technique):
    loaded = build_effect(str(path), effects.load_profile(card))
    assert loaded.technique is not None and loaded.technique.name == technique
    assert loaded.listing is not None and len(loaded.listing) == len(loaded.technique.passes)
    for i, lines in enumerate(loaded.listing):
        expected = compile_output(capsys, str(path), "--technique", technique, "--pass", str(i))
        assert "\n".join(lines) + "\n" == expected
        assert "// approximately " in expected      # a real listing, with its counts
    viewer = viewer_for(path, card)
    assert viewer.listing_text() + "\n" == compile_output(capsys, str(path), "--technique", technique)


def test_a_fixed_function_pass_says_so(capsys, tinted_effect):
    out = compile_output(capsys, str(tinted_effect), "--technique", "Flat")
    assert out == "// technique Flat, pass P0: fixed function (no shaders)\n\n"
    viewer = viewer_for(tinted_effect, "tnt2")
    assert viewer.listing_text() + "\n" == out
    out = compile_output(capsys, str(SDK9), "--technique", "Scene_ff")   # VertexShader = NULL
    assert "pass P0: VertexShader\n//   NULL: the fixed-function pipeline\n" in out
    assert viewer_for(SDK9, "tnt2").listing_text() + "\n" == out


def test_the_listing_follows_a_reload_a_broken_reload_and_a_card_switch(tmp_path, capsys):
    folder = tmp_path / "fx"
    shutil.copytree(ROOT / "fxfiles", folder)
    path = folder / "sdk9_hlsl.fx"
    source = path.read_text()
    viewer = viewer_for(path, "radeon9700")
    before = viewer.listing_text()
    assert "ScenePS compiled for ps_2_0" in before
    builder = effect_builder(str(path), lambda: viewer.state.build_settings(viewer.effect_size()))
    reloader = Reloader(str(path), builder, use_watchdog=False, poll_interval=0.05)
    reloader.start(viewer.loaded)
    try:
        # 1. an edit of the pixel function: its new instruction is in the listing
        edited = source.replace("return o;", "o.Position.x = frac(o.Position.x);\n    return o;", 1)
        assert edited != source
        save(path, edited)
        result = reloader.wait(10)
        assert result is not None and result.ok, result and result.error
        viewer._take(result)
        after = viewer.listing_text()
        assert after != before and "frc" in after and "frc" not in before
        assert after + "\n" == compile_output(capsys, str(path), "--technique", "Scene_ps20")

        # 2. a broken edit: the last good listing stays, and the error is what the window shows
        save(path, edited.replace("technique Scene_ps20", "technique Scene_ps20 oops"))
        result = reloader.wait(10)
        assert result is not None and not result.ok
        viewer._take(result)
        assert viewer.listing_text() == after
        assert viewer.status.error is not None and "error" in viewer.status.error

        # 3. fixed again, then another card: the technique it selects is listed
        save(path, edited)
        result = reloader.wait(10)
        assert result is not None and result.ok
        viewer._take(result)
        viewer.state.set_card(viewer.state.cards.index("radeon8500"))
        reloader.reselect()
        result = reloader.wait(10)
        assert result is not None and result.ok and result.kind == "select"
        viewer._take(result)
        assert viewer.loaded.technique.name == "Scene_ps14"
        card_listing = viewer.listing_text()
        assert "ScenePS compiled for ps_1_4" in card_listing and card_listing != after
        assert card_listing + "\n" == compile_output(capsys, str(path), "--technique", "Scene_ps14")
    finally:
        reloader.stop()


def test_a_card_switch_after_a_broken_edit_lists_the_last_good_source(tmp_path, capsys):
    """The switch re-selects in the last good effect while the broken file is on disk: the
    listing quotes the source that was compiled, not the lines now at those numbers."""
    folder = tmp_path / "fx"
    shutil.copytree(ROOT / "fxfiles", folder)
    path = folder / "sdk9_hlsl.fx"
    source = path.read_text()
    good_ps14 = compile_output(capsys, str(path), "--technique", "Scene_ps14")
    viewer = viewer_for(path, "radeon9700")
    builder = effect_builder(str(path), lambda: viewer.state.build_settings(viewer.effect_size()))
    reloader = Reloader(str(path), builder, use_watchdog=False, poll_interval=0.05)
    reloader.start(viewer.loaded)
    try:
        save(path, "// three lines\n// pushed in\n// above\n" + source + "\n}")   # broken
        result = reloader.wait(10)
        assert result is not None and not result.ok
        viewer._take(result)
        viewer.state.set_card(viewer.state.cards.index("radeon8500"))
        reloader.reselect()
        result = reloader.wait(10)
        assert result is not None and result.ok and result.kind == "select"
        viewer._take(result)
        assert viewer.listing_text() + "\n" == good_ps14
    finally:
        reloader.stop()


def xvfb_run() -> str:
    found = shutil.which("xvfb-run")
    if found is None:
        pytest.fail("xvfb-run is not installed: the viewer tests need a virtual X server. "
                    "Run .ci/setup (it installs the xvfb and xauth packages), or "
                    "apt-get install xvfb xauth")
    return found


KEY_SCRIPT = """
import sys
from types import SimpleNamespace
from imgui_bundle import imgui
from moderngl_window.context.pyglet.keys import Keys
from effects.viewer.app import Viewer, ViewerOptions
viewer = Viewer(ViewerOptions(sys.argv[1]), output=lambda _: None)
imgui.create_context()
viewer.imgui = SimpleNamespace(key_event=lambda *a: None)
viewer.window = SimpleNamespace(keys=Keys)
seen = [viewer.state.show_listing]
for _ in range(2):
    viewer._key(Keys.C, Keys.ACTION_PRESS, SimpleNamespace(shift=False))
    seen.append(viewer.state.show_listing)
viewer._key(Keys.C, Keys.ACTION_RELEASE, SimpleNamespace(shift=False))
seen.append(viewer.state.show_listing)
print(seen)
"""


def test_the_c_key_toggles_the_listing():
    out = subprocess.run([xvfb_run(), "-a", sys.executable, "-c", KEY_SCRIPT, str(SDK9)],
                         capture_output=True, text=True, cwd=ROOT, timeout=60)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip().splitlines()[-1] == "[False, True, False, False]"


def test_the_listing_window_covers_the_picture(tmp_path):
    """--listing starts with it shown: the left square is the listing's text on its dark
    window, not the lit sphere; without it, the sphere."""
    shots = {}
    for shown in (False, True):
        shot = tmp_path / f"{shown}.png"
        cmd = [xvfb_run(), "-a", "-s", "-screen 0 1280x800x24", sys.executable, "-m", "effects",
               "view", str(SDK9), "--profile", "radeon9700", "--size", "800x360",
               "--exit-after", "1.5", "--screenshot", str(shot), *(["--listing"] if shown else [])]
        out = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT, timeout=120)
        assert out.returncode == 0, out.stdout + out.stderr
        shots[shown] = np.asarray(Image.open(shot).convert("RGB"))[:, :360].astype(int)
    plain, listed = shots[False], shots[True]
    # without the listing the square's centre is the sphere, lit from above, left and in front
    # (bright, and varied by its texture); with it, the listing's dark window, its text light
    # grey in rows of glyphs down most of the square (the lit sphere's light pixels reach
    # about a third of the rows)
    centre = (slice(140, 220), slice(140, 220))
    assert plain[centre].mean() > 60 and plain[centre].std() > 20
    assert listed[centre].mean() < 40
    light = listed.min(axis=-1) > 150
    assert light[40:300].mean() > 0.01
    assert light[40:300].any(axis=1).mean() > 0.6
    assert np.abs(plain - listed).mean() > 5
