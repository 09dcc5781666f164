"""Hot reload without a window: real file events on a temp folder, real builds.

The effect under test draws a flat TextureFactor colour whose value comes from an #include,
so each edit's result can be checked on the lowered program's `tfactor` uniform: 0xAARRGGBB
0xff00ff00 is (r, g, b, a) = (0, 1, 0, 1) by the D3DCOLOR layout.
"""
from __future__ import annotations

from tests.paths import ROOT

import os
import re
import threading
import time

import pytest
from PIL import Image

import effects
from effects.viewer.reload import (BuildSettings, Reloader, Watcher, build_effect, content_hash, effect_builder,
                            referenced_files, watched_files)

TIMEOUT = 5.0
QUIET = 0.4        # long enough for any debounce (25 ms) + polling safety net to have fired


def tint(hex_colour: str) -> str:
    return f"#define TINT {hex_colour}\n"


@pytest.fixture
def folder(tinted_effect):
    """The folder of conftest's tinted effect: flat.fx, tint.fxh (red) and base.png."""
    return tinted_effect.parent


def save(path, text: str) -> None:
    """Write an edit atomically. A plain write truncates first, and on a loaded 2-core machine
    the watcher can read the empty file in between: an empty effect loads "ok" with no
    technique, an empty include fails, and the next result a test expects is the one after.
    Tests about the write itself (the burst, the truncated image) write plainly."""
    tmp = f"{path}.part"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def write_png(path, rgb):
    # Atomically: Pillow writes a PNG in several chunks, and on a loaded machine the watcher can
    # hash the half-written file, build after the write completes, then see the rest as a
    # second change (one extra "ok" reload that a test expecting the next edit would take).
    tmp = f"{path}.part.png"
    Image.new("RGB", (4, 4), rgb).save(tmp)
    os.replace(tmp, path)


def tfactor(loaded) -> tuple[float, ...]:
    return dict(loaded.programs[0].uniforms)["tfactor"]


def start_reloader(folder, *, use_watchdog=True, technique=None, card="tnt2", **options):
    settings = BuildSettings(effects.load_profile(card), technique)
    path = str(folder / "flat.fx")
    build = effect_builder(path, lambda: settings)
    reloader = Reloader(path, build, use_watchdog=use_watchdog, **options)
    reloader.start(build(None))
    time.sleep(0.05)   # let the observer settle before the first edit
    return reloader, settings


def expect_result(reloader):
    result = reloader.wait(TIMEOUT)
    assert result is not None, "no reload within the timeout"
    return result


def expect_quiet(reloader):
    extra = reloader.wait(QUIET)
    assert extra is None, f"unexpected extra reload: {extra.log_line()}"


OK_LINE = re.compile(r"^reload: (?P<path>\S+) ok in (?P<ms>\d+\.\d) ms \(technique (?P<tech>\w+)\)$")


def test_initial_build_selects_lowers_and_lists_its_files(folder):
    loaded = build_effect(str(folder / "flat.fx"), effects.load_profile("tnt2"))
    assert loaded.technique.name == "Flat"
    assert [v.ok for v in loaded.validations] == [True, False]
    assert tfactor(loaded) == (1.0, 0.0, 0.0, 1.0)
    assert watched_files(loaded.effect) == [str(folder / "flat.fx"), str(folder / "tint.fxh"),
                                            str(folder / "base.png")]


def test_good_edit_of_an_include_reloads_with_the_new_value(folder):
    reloader, _ = start_reloader(folder)
    try:
        save((folder / "tint.fxh"), tint("0xff00ff00"))
        result = expect_result(reloader)
        assert result.ok and result.kind == "reload"
        assert result.changed == (str(folder / "tint.fxh"),)
        m = OK_LINE.match(result.log_line())
        assert m and m["path"] == str(folder / "flat.fx") and m["tech"] == "Flat"
        assert tfactor(result.loaded) == (0.0, 1.0, 0.0, 1.0)
        expect_quiet(reloader)
    finally:
        reloader.stop()


def test_truncated_write_fails_located_keeps_last_good_then_recovers(folder):
    reloader, _ = start_reloader(folder)
    good = reloader.last_good
    path = folder / "flat.fx"
    effect = path.read_text()
    try:
        cut = effect.index("AlphaOp[0]")      # line 11: the pass and technique are left open
        save(path, effect[:cut])
        bad = expect_result(reloader)
        assert not bad.ok and bad.loaded is None
        line = bad.log_line()
        assert line.startswith(f"reload: {path} failed: {path}:")
        assert re.search(r":\d+:\d+: error: ", line), line
        assert reloader.last_good is good
        save(path, effect.replace("TINT;", "0xff0000ff;"))
        fixed = expect_result(reloader)
        assert fixed.ok and tfactor(fixed.loaded) == (0.0, 0.0, 1.0, 1.0)
        assert reloader.last_good is fixed.loaded
    finally:
        reloader.stop()


def test_delete_then_recreate(folder):
    reloader, _ = start_reloader(folder)
    path = folder / "flat.fx"
    effect = path.read_text()
    try:
        path.unlink()
        gone = expect_result(reloader)
        assert gone.log_line() == (f"reload: {path} failed: {path}:1:1: error: cannot read "
                                   "effect file: No such file or directory")
        save(path, effect.replace("TINT;", "0xff00ffff;"))
        back = expect_result(reloader)
        assert back.ok and tfactor(back.loaded) == (0.0, 1.0, 1.0, 1.0)
        expect_quiet(reloader)
    finally:
        reloader.stop()


@pytest.mark.parametrize("use_watchdog", [True, False], ids=["watchdog", "polling"])
def test_rename_into_place_counts_as_a_save(folder, use_watchdog):
    reloader, _ = start_reloader(folder, use_watchdog=use_watchdog)
    try:
        assert reloader.watcher.mode == ("watchdog" if use_watchdog else "polling")
        tmp = folder / "flat.fx.tmp"
        tmp.write_text((folder / "flat.fx").read_text().replace("TINT;", "0xffffff00;"))
        os.replace(tmp, folder / "flat.fx")
        result = expect_result(reloader)
        assert result.ok and tfactor(result.loaded) == (1.0, 1.0, 0.0, 1.0)
        expect_quiet(reloader)
    finally:
        reloader.stop()


def test_a_burst_of_writes_is_one_reload_of_the_last_content(folder):
    # A 0.3 s debounce (and a 2 s cap) so that a loaded machine's late sleeps cannot split the
    # burst: at 50 ms a 5 ms sleep stretched past it about one run in eight while the rest of
    # the suite ran beside it. What is tested is the coalescing, not the default's latency:
    # each write_text closes the file, a completed save that the default reports after
    # SETTLE_S, so the settle time is as long as the debounce here.
    reloader, _ = start_reloader(folder, debounce=0.3, settle=0.3, max_delay=2.0)
    try:
        for i in range(8):   # an autosaving editor: a write every 5 ms
            (folder / "tint.fxh").write_text(tint(f"0xff0000{0x10 * (i + 1):02x}"))
            time.sleep(0.005)
        result = expect_result(reloader)
        assert result.ok and tfactor(result.loaded) == pytest.approx((0.0, 0.0, 0x80 / 255, 1.0), abs=1e-6)
        expect_quiet(reloader)
    finally:
        reloader.stop()


def test_unchanged_content_does_not_reload(folder):
    reloader, _ = start_reloader(folder)
    try:
        path = folder / "flat.fx"
        save(path, path.read_text())                  # saved without edits
        os.utime(folder / "tint.fxh")                      # touched
        tmp = folder / "x.tmp"                             # atomic save of the same bytes
        tmp.write_text(tint("0xffff0000"))
        os.replace(tmp, folder / "tint.fxh")
        expect_quiet(reloader)
    finally:
        reloader.stop()


def test_texture_image_change_reloads(folder):
    reloader, _ = start_reloader(folder)
    try:
        write_png(folder / "base.png", (0, 0, 255))
        result = expect_result(reloader)
        assert result.ok and result.changed == (str(folder / "base.png"),)
        (folder / "base.png").write_bytes(b"a truncated image")
        bad = expect_result(reloader)
        assert bad.log_line().startswith(f"reload: {folder / 'flat.fx'} failed: {folder / 'flat.fx'}:2:")
        assert "cannot read image" in bad.log_line()
        assert reloader.last_good is result.loaded
    finally:
        reloader.stop()


def test_new_include_is_watched_after_the_reload_that_added_it(folder):
    reloader, _ = start_reloader(folder)
    try:
        save((folder / "more.fxh"), "#define OTHER 1\n")
        path = folder / "flat.fx"
        save(path, '#include "more.fxh"\n' + path.read_text())
        assert expect_result(reloader).ok
        assert str(folder / "more.fxh") in reloader.watcher.paths
        save((folder / "more.fxh"), "#define OTHER 2\n")
        assert expect_result(reloader).changed == (str(folder / "more.fxh"),)
    finally:
        reloader.stop()


def test_forced_technique_not_valid_keeps_the_selection_and_carries_reasons(folder):
    reloader, settings = start_reloader(folder, technique="Dot3")
    try:
        first = reloader.last_good
        assert first.technique.name == "Flat"
        assert first.forced_rejected is not None
        assert "D3DTEXOPCAPS_DOTPRODUCT3" in str(first.forced_rejected.reasons[0])
        # the same technique on a card that has DotProduct3: drawn, without reading the file again
        settings.profile = effects.load_profile("geforce2")
        (folder / "flat.fx").write_text("broken on disk, but a reselect does not read it")
        time.sleep(0.2)
        while reloader.poll() is not None:     # drop the failed file reload
            pass
        reloader.reselect()
        result = expect_result(reloader)
        assert result.kind == "select" and result.ok
        assert result.loaded.technique.name == "Dot3" and result.loaded.forced_rejected is None
    finally:
        reloader.stop()


def test_an_unexpected_exception_in_a_build_is_reported_and_the_worker_survives(tmp_path):
    path = tmp_path / "a.fx"
    path.write_text("x")
    calls = []

    def build(previous):
        calls.append(previous)
        if len(calls) == 1:
            raise ZeroDivisionError("a bug")
        return "built"

    reloader = Reloader(str(path), build).start()
    try:
        first = expect_result(reloader)
        assert first.log_line() == f"reload: {path} failed: internal error: ZeroDivisionError: a bug"
        reloader.request()
        assert expect_result(reloader).loaded == "built"
    finally:
        reloader.stop()


def test_building_says_a_result_is_on_its_way_until_it_is_queued(tmp_path):
    # The viewer's idle frames wait for a build instead of redrawing while it runs
    # (app.BUILD_WAIT_S): `building` must hold from the request until the result is queued,
    # and count coalesced requests as answered by the one build.
    path = tmp_path / "a.fx"
    path.write_text("x")
    release = threading.Event()

    def build(previous):
        release.wait(TIMEOUT)
        return "built"

    reloader = Reloader(str(path), build).start(build_now=False)
    try:
        assert not reloader.building
        reloader.request()
        reloader.request()                 # queued behind the first: coalesced or next
        assert reloader.building
        release.set()
        assert expect_result(reloader).loaded == "built"
        deadline = time.monotonic() + TIMEOUT
        while reloader.building and time.monotonic() < deadline:
            reloader.wait(0.01)            # a second build, if the two were not coalesced
        assert not reloader.building
    finally:
        reloader.stop()


def test_watcher_reports_only_files_whose_hash_changed(tmp_path):
    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    a.write_text("a")
    b.write_text("b")
    seen: list[list[str]] = []
    got = threading.Event()

    def on_change(paths):
        seen.append(paths)
        got.set()

    watcher = Watcher([str(a), str(b)], on_change).start()
    try:
        time.sleep(0.05)
        b.write_text("b")          # same content
        a.write_text("A")
        assert got.wait(TIMEOUT)
        time.sleep(QUIET)
        assert seen == [[str(a)]]
    finally:
        watcher.stop()


def _reports(path, **options):
    """A watchdog Watcher on `path` and the monotonic times of its reports."""
    times: list[float] = []
    got = threading.Event()

    def on_change(paths):
        times.append(time.monotonic())
        got.set()
    watcher = Watcher([str(path)], on_change, **options).start()
    assert watcher.mode == "watchdog"
    time.sleep(0.05)
    return watcher, times, got


@pytest.mark.parametrize("how", ["in place", "renamed onto it"])
def test_a_completed_save_is_reported_without_waiting_for_the_debounce(tmp_path, how):
    # The writer closed the file (inotify's IN_CLOSE_WRITE) or renamed its temporary file onto
    # it: the save is complete, so the watcher waits only the settle time, not the debounce
    # (2 s here, so a late report cannot pass for an early one).
    path = tmp_path / "a.fx"
    path.write_text("a")
    watcher, times, got = _reports(path, debounce=2.0, max_delay=4.0)
    try:
        start = time.monotonic()
        if how == "in place":
            path.write_text("b")
        else:
            (tmp_path / "a.fx.tmp").write_text("b")
            os.replace(tmp_path / "a.fx.tmp", path)
        assert got.wait(TIMEOUT)
        assert times[0] - start < 1.0
    finally:
        watcher.stop()


def test_a_write_still_open_waits_for_the_debounce_then_its_close_ends_it(tmp_path):
    path = tmp_path / "a.fx"
    path.write_text("a")
    watcher, times, got = _reports(path, debounce=1.5, max_delay=4.0)
    try:
        with open(path, "w") as f:         # a writer still writing: modified, not closed
            f.write("half")
            f.flush()
            assert not got.wait(0.5)       # well inside the 1.5 s debounce: not reported
            f.write(" and the rest")
            closing = time.monotonic()
        assert got.wait(TIMEOUT)           # the close: reported after the settle time
        assert times[0] - closing < 1.0
    finally:
        watcher.stop()


def test_reading_a_watched_file_is_not_an_event(tmp_path, monkeypatch):
    # The watcher's own hashing (and the reload's reading) opens the file: were an open or a
    # read-only close an event, each hash would start the next debounce, for ever.
    import effects.viewer.watch as watch
    hashes = []
    real = watch.content_hash
    monkeypatch.setattr(watch, "content_hash", lambda p: hashes.append(p) or real(p))
    path = tmp_path / "a.fx"
    path.write_text("a")
    watcher, times, got = _reports(path)
    try:
        path.write_text("b")
        assert got.wait(TIMEOUT)
        for _ in range(5):
            path.read_text()
        time.sleep(QUIET)
        assert len(times) == 1 and len(hashes) <= 2, (times, hashes)
    finally:
        watcher.stop()


def test_content_hash_and_referenced_files(folder):
    assert content_hash(str(folder / "missing")) is None
    assert content_hash(str(folder / "tint.fxh")) != content_hash(str(folder / "flat.fx"))
    effect = effects.load_effect(str(folder / "flat.fx"))
    assert referenced_files(effect) == [str(folder / "base.png")]


def test_bundled_effects_watch_their_texture_images():
    root = os.path.join(str(ROOT), "fxfiles")
    effect = effects.load_effect(os.path.join(root, "specular_bump.fx"))
    names = sorted(os.path.basename(p) for p in referenced_files(effect))
    # earth_height.png is named twice (ResourceName and two Sobel generators): listed once
    assert names == ["earth_base.png", "earth_height.png", "earth_light.png"]


def test_unchanged_textures_are_not_read_again_and_a_changed_one_is(folder):
    """The rebuilt effect gets the very Texture object it had (so the GL back end's upload,
    keyed on it, stays); only an image whose file changed is read again."""
    reloader, _ = start_reloader(folder)
    try:
        before = reloader.last_good.runtime.texture("Base")
        save((folder / "tint.fxh"), tint("0xff00ff00"))
        after_edit = expect_result(reloader).loaded.runtime.texture("Base")
        assert after_edit is before
        write_png(folder / "base.png", (0, 0, 255))
        after_image = expect_result(reloader).loaded.runtime.texture("Base")
        assert after_image is not before
        assert after_image.levels[0][0, 0, :3] == pytest.approx((0.0, 0.0, 1.0))
    finally:
        reloader.stop()


def test_a_build_validates_each_technique_once_and_lowers_from_those_answers(tinted_effect,
                                                                             monkeypatch):
    """build_effect validates every technique once (the panel lists them), selects among those
    same answers, and lowering draws the chosen one's per-pass device states: nothing replays
    the passes or validates again."""
    import effects.lower.passes as passes
    import effects.validate.select as select
    import effects.validate.technique as technique
    calls = []
    real = technique.validate_technique

    def counting(effect, tech, profile):
        calls.append(tech.name)
        return real(effect, tech, profile)

    def no_replay(*args, **kwargs):
        raise AssertionError("lowering replayed the passes instead of using the validation")

    monkeypatch.setattr(technique, "validate_technique", counting)
    monkeypatch.setattr(select, "validate_technique", counting)
    monkeypatch.setattr(passes, "pass_states", no_replay)
    passes.clear_cache()
    loaded = build_effect(str(tinted_effect), effects.load_profile("geforce3"))
    assert sorted(calls) == ["Dot3", "Flat"]
    assert loaded.technique.name == "Flat" and len(loaded.programs) == 1
    chosen = next(v for v in loaded.validations if v.technique is loaded.technique)
    assert loaded.runtime.validation is chosen
    assert chosen.pass_reports[0].state.get_color("TextureFactor") == (1.0, 0.0, 0.0, 1.0)
