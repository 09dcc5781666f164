"""The viewer's reloads validate only up to the technique they draw, and the rest after the
first frame (effects.viewer.reload: build_effect(defer=True), LoadedEffect.pending,
Reloader.drawn): the drawn technique, its validation and the full list once completed are
what a build that validates everything gives."""
from __future__ import annotations

from tests.paths import ROOT

import os
import shutil
import time
from pathlib import Path

import pytest

import effects
from effects.viewer.reload import BuildSettings, Reloader, build_effect, effect_builder

SDK9 = ROOT / "fxfiles" / "sdk9_hlsl.fx"


def _answers(loaded):
    return [(v.technique.name, v.ok, [str(r) for r in v.reasons]) for v in loaded.validations]


@pytest.mark.parametrize("card, forced, validated, drawn", [
    ("radeon9700", None, ["Scene_ps20"], "Scene_ps20"),
    ("radeon8500", None, ["Scene_ps20", "Scene_ps14"], "Scene_ps14"),
    ("geforce2", None, ["Scene_ps20", "Scene_ps14", "Scene_ps11", "Scene_ff"], "Scene_ff"),
    ("radeon9700", "Scene_ps11", ["Scene_ps20", "Scene_ps14", "Scene_ps11"], "Scene_ps11"),
    # a forced technique the card rejects: the first valid one is drawn, known at once here
    ("radeon8500", "Scene_ps20", ["Scene_ps20", "Scene_ps14"], "Scene_ps14"),
])
def test_a_deferred_build_stops_at_what_it_draws_and_completes_to_the_full_answer(
        card, forced, validated, drawn):
    profile = effects.load_profile(card)
    full = build_effect(str(SDK9), profile, technique=forced, keep_prepare_error=True)
    lazy = build_effect(str(SDK9), profile, technique=forced, keep_prepare_error=True, defer=True)
    assert [v.technique.name for v in lazy.validations] == validated
    assert [t.name for t in lazy.pending] == [t.name for t in lazy.effect.techniques][len(validated):]
    assert lazy.technique.name == drawn == full.technique.name
    assert lazy.selected.ok and _answers(lazy) == _answers(full)[:len(validated)]
    assert (lazy.forced_rejected is None) == (full.forced_rejected is None)
    assert lazy.listing == full.listing
    lazy.complete_validations()
    assert lazy.pending == [] and _answers(lazy) == _answers(full)


def test_a_policy_other_than_first_validates_everything():
    lazy = build_effect(str(SDK9), effects.load_profile("radeon9700"), policy="quality",
                        defer=True)
    assert lazy.pending == [] and len(lazy.validations) == 4


def test_the_reloader_completes_a_reload_s_validations_after_the_frame_and_by_itself(tmp_path):
    path = tmp_path / "sdk9_hlsl.fx"
    shutil.copy(SDK9, path)
    shutil.copytree(SDK9.parent / "textures", tmp_path / "textures")
    settings = BuildSettings(effects.load_profile("radeon9700"))
    build = effect_builder(str(path), lambda: settings)
    reloader = Reloader(str(path), build, use_watchdog=False, poll_interval=0.05)
    reloader.start(build(None))
    try:
        for k, signal in enumerate((True, False)):     # told it was drawn / no render thread
            text = SDK9.read_text().replace("color.a = 1.0;", f"color.a = 0.{k + 5};")
            tmp = f"{path}.part"
            Path(tmp).write_text(text)
            os.replace(tmp, path)
            result = reloader.wait(10)
            assert result is not None and result.ok, result and result.error
            loaded = result.loaded
            assert [v.technique.name for v in loaded.validations] == ["Scene_ps20"]
            if signal:
                reloader.drawn()
            deadline = time.perf_counter() + 10
            while loaded.pending and time.perf_counter() < deadline:
                time.sleep(0.01)
            assert [v.technique.name for v in loaded.validations] == [
                "Scene_ps20", "Scene_ps14", "Scene_ps11", "Scene_ff"]
            assert [v.ok for v in loaded.validations] == [True, True, True, True]
    finally:
        reloader.stop()
