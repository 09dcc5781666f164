"""The viewer's technique list gives each valid technique's fidelity: the reload worker
measures them after a build's validations, one technique a step (LoadedEffect.measure_next),
and the panel shows the figures (effects.viewer.panel.fidelity_note)."""
from __future__ import annotations

import shutil
import time

import effects
from effects.host.fidelity import meter_for
from effects.viewer.panel import fidelity_heading, fidelity_note
from effects.viewer.reload import BuildSettings, Reloader, build_effect, effect_builder
from tests.paths import ROOT

PHONG = ROOT / "fxfiles" / "phong.fx"


def test_the_list_shows_the_figures_the_meter_gives():
    card = effects.load_profile("geforce2")
    loaded = build_effect(str(PHONG), card, lower=False, defer=True)
    assert fidelity_heading(loaded) == "fidelity: measuring..."
    assert fidelity_note(loaded, loaded.selected) == ""
    steps = 0
    while loaded.unfinished():
        if loaded.pending:
            loaded.complete_validations()
        else:
            loaded.measure_next()
        steps += 1
    valid = [v for v in loaded.validations if v.ok]
    assert [v.technique.name for v in valid] == ["Dot3_dx7", "SingleTexture"]
    assert steps == 1 + len(valid) + 1      # the validations, a technique a step, the end
    assert fidelity_heading(loaded) == "fidelity: against PerPixelPhong_ps20 on refrast"
    meter = meter_for(loaded.effect)        # the viewer's scene: the default one here
    for v in valid:
        assert fidelity_note(loaded, v) == f", {meter.measure(v.technique, card)}"
        assert "SSIM 0." in fidelity_note(loaded, v)
    rejected = next(v for v in loaded.validations if not v.ok)
    assert fidelity_note(loaded, rejected) == ""


def test_the_reloader_measures_after_the_frame(tmp_path):
    path = tmp_path / "phong.fx"
    shutil.copy(PHONG, path)
    shutil.copytree(PHONG.parent / "textures", tmp_path / "textures")
    settings = BuildSettings(effects.load_profile("geforce2"))
    build = effect_builder(str(path), lambda: settings)
    first = build(None)
    reloader = Reloader(str(path), build, use_watchdog=False, poll_interval=0.05)
    reloader.start(first)
    try:
        reloader.drawn()
        deadline = time.perf_counter() + 30
        while first.unfinished() and time.perf_counter() < deadline:
            time.sleep(0.02)
        assert first.fidelity_done and first.fidelity_best == "PerPixelPhong_ps20"
        assert sorted(first.validations[i].technique.name for i in first.fidelity) == \
            ["Dot3_dx7", "SingleTexture"]
    finally:
        reloader.stop()
