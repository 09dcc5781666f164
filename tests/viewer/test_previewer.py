"""The viewer as a previewer: the parameter panel built from SAS/UI annotations, edits that
apply live and survive hot reloads, TIME that runs, the effect's scene and --set.

The window tests run tests/viewer/previewer_driver.py under xvfb-run: it clicks the panel's
slider, types a texture path into its field, edits the file, lets the clock run, and takes a
screenshot after each step; the pictures are compared with the wave the test effect draws,
computed here by hand. Without xvfb-run they fail saying so (tests/viewer/test_viewer.py).
"""
from __future__ import annotations

from tests.paths import ROOT

import json
import math
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

import effects
from effects.frontend.loader import load_effect
from effects.host.runtime import Runtime
from effects.host.scene import load_scene
from effects.viewer.params import Clock, Tweaks, tweakable, tweakables
from effects.viewer.state import Orbit, ViewerState

DRIVER = os.path.join(str(ROOT), "tests", "viewer", "previewer_driver.py")

# colour = Tint * (0.5 + 0.5 sin(2 pi (u + TIME * Speed))) * Pattern, on the full-screen quad
WAVE = """\
float Time : TIME;
float Speed < string UIName = "Speed"; float UIMin = 0.0; float UIMax = 2.0; > = 1.0;
float3 Tint < string UIWidget = "Color"; > = { 1.0, 0.5, 0.25 };
texture Pattern < string ResourceName = "white.png"; >;
sampler S = sampler_state { Texture = <Pattern>; MinFilter = Point; MagFilter = Point; };
float4 ps(float2 uv : TEXCOORD0) : COLOR
{
    float wave = 0.5 + 0.5 * sin(6.2831853 * (uv.x + Time * Speed));
    return float4(Tint * wave, 1.0) * tex2D(S, uv);
}
technique Wave { pass P { PixelShader = compile ps_2_0 ps(); } }
// the end
"""


def wave_row(phase: float, tint=(1.0, 0.5, 0.25), texel=(1.0, 1.0, 1.0), side: int = 360):
    """The row the quad draws at TIME * Speed = `phase`: pixel j samples u = (j + 0.5) / side."""
    u = (np.arange(side) + 0.5) / side
    wave = 0.5 + 0.5 * np.sin(2 * math.pi * (u + phase))
    return np.stack([255.0 * tint[c] * texel[c] * wave for c in range(3)], axis=-1)


@pytest.fixture
def wave_effect(tmp_path):
    (tmp_path / "wave.fx").write_text(WAVE)
    Image.new("RGB", (4, 4), (255, 255, 255)).save(tmp_path / "white.png")
    Image.new("RGB", (4, 4), (0, 255, 0)).save(tmp_path / "green.png")
    return tmp_path / "wave.fx"


# ---------------------------------------------------------------------------------------------
# The panel's model, without a window


def params_of(text: str):
    return load_effect(text).parameters


@pytest.mark.parametrize("declaration, widget, lo, hi, step", [
    ('float A < float UIMin = 0; float UIMax = 4; > = 1;', "slider", 0.0, 4.0, None),
    ('float A < float UIMin = 0; float UIMax = 4; float UIStep = 0.5; string UIWidget = "Spinner"; > = 1;',
     "spinner", 0.0, 4.0, 0.5),
    ('float A = 1;', "spinner", None, None, None),                    # no range: a spinner
    ('float A < string UIWidget = "slider"; > = 1;', "spinner", None, None, None),  # no ends
    ('float4 DiffuseColor = {1, 0, 0, 1};', "color", None, None, None),   # a colour by its name
    ('float3 Albedo < string UIWidget = "Color"; > = {1, 0, 0};', "color", None, None, None),
    ('float2 Offset < string UIWidget = "Color"; > = {1, 0};', "spinner", None, None, None),
    ('bool Enabled = true;', "checkbox", None, None, None),
    ('int Count < int UIMin = 1; int UIMax = 8; > = 2;', "slider", 1.0, 8.0, None),
    ('float3 Axis < string UIWidget = "Direction"; > = {0, -1, 0};', "spinner", None, None, None),
    ('texture Base;', "texture", None, None, None),
])
def test_the_widget_follows_the_annotations(declaration, widget, lo, hi, step):
    item = tweakable(params_of(declaration)[0])
    assert item is not None
    assert (item.widget, item.lo, item.hi, item.step) == (widget, lo, hi, step)


@pytest.mark.parametrize("declaration", [
    'float A < string UIWidget = "None"; > = 1;',     # hidden by the file
    'float4x4 WVP : WORLDVIEWPROJECTION;',            # a matrix, bound by the scene
    'float Time : TIME;',                             # the clock's
    'float4 LightPos : LIGHTPOSITION = {1, 1, 1, 1};',  # the scene's light
    'float Weights[4];',                              # arrays: not here
    'string Name = "x";',
])
def test_parameters_the_host_binds_or_that_are_hidden_get_no_widget(declaration):
    assert tweakable(params_of(declaration)[0]) is None


def test_the_label_is_the_ui_name():
    item = tweakable(params_of('float A < string UIName = "Roughness"; > = 1;')[0])
    assert item.label == "Roughness"


def test_an_edit_waits_while_its_parameter_has_another_type_and_applies_again_after():
    float1 = tweakables(load_effect("float A = 1;\nfloat B = 2;"))
    float2 = tweakables(load_effect("float2 A = {1, 1};\nfloat B = 2;"))
    edits = Tweaks()
    edits.set(float1[0], [0.25])
    edits.set(float1[1], [7.0])
    assert edits.for_effect(float1) == {"A": [0.25], "B": [7.0]}
    assert edits.for_effect(float2) == {"B": [7.0]}           # A is a float2 now: waits
    assert edits.for_effect(float1) == {"A": [0.25], "B": [7.0]}   # and is back


def test_the_clock_runs_pauses_steps_and_holds():
    clock = Clock()
    assert clock.advance(0.5) and clock.seconds == 0.5
    clock.toggle()
    assert not clock.advance(0.5) and clock.seconds == 0.5
    clock.step(3)
    assert clock.seconds == pytest.approx(0.5 + 3 / 30)
    clock.step(-100)
    assert clock.seconds == 0.0
    held = Clock(seconds=2.0, fixed=True)
    assert not held.advance(1.0) and held.seconds == 2.0
    held.toggle()                                  # space on a held clock: it runs from there
    assert held.advance(1.0) and held.seconds == 3.0


def test_time_bound_parameters_follow_set_time_and_a_set_value_stays(wave_effect):
    runtime = Runtime(str(wave_effect), "radeon9700", scene={"mesh": "quad", "time": 0.5})
    assert runtime.time_parameters() == ["Time"]
    assert float(runtime.effect.parameter("Time").value) == 0.5
    assert runtime.set_time(2.25)
    assert float(runtime.effect.parameter("Time").value) == 2.25
    fixed = Runtime(str(wave_effect), "radeon9700", scene={"mesh": "quad"}, params={"Time": "3"})
    assert fixed.time_parameters() == [] and not fixed.set_time(9.0)
    assert float(fixed.effect.parameter("Time").value) == 3.0


def test_the_state_draws_in_the_effects_scene(tmp_path):
    (tmp_path / "s.yaml").write_text(
        "camera: {eye: [3, 1, -2], target: [0, 0.5, 0], fov: 30}\n"
        "light: {position: [0, 4, 3], color: [1, 0.5, 0.5]}\n"
        "params: {Speed: 0.5}\ntime: 4.5\nmesh: torus\n")
    state = ViewerState(["radeon9700"])
    state.start_from_scene(load_scene(str(tmp_path / "s.yaml")))
    scene = state.scene((64, 64))
    assert scene.mesh == "torus" and scene.time == 4.5 and scene.params == {"Speed": 0.5}
    assert np.allclose(scene.camera.eye, (3, 1, -2)) and scene.camera.fov == 30
    assert np.allclose(scene.light.position, (0, 4, 3)) and scene.light.color[:3] == (1, 0.5, 0.5)
    state.set_mesh("cube")
    assert state.scene((64, 64)).mesh == "cube"


def test_an_orbit_from_a_camera_puts_the_eye_back_where_it_was():
    from effects.host.scene import Camera
    for eye in [(0, 0, 3), (3, 1, -2), (-1, 2, 0.5)]:
        orbit = Orbit.looking(Camera(eye=eye, target=(0.5, 0, 0)))
        assert np.allclose(orbit.eye(), eye)


# ---------------------------------------------------------------------------------------------
# In a window: click, type, edit, run


def xvfb_run() -> str:
    path = shutil.which("xvfb-run")
    if path is None:
        pytest.fail("xvfb-run is not installed: the viewer tests need a virtual X server. "
                    "Run .ci/setup (it installs the xvfb and xauth packages), or "
                    "apt-get install xvfb xauth")
    return path


def drive(*args: str) -> dict:
    out = subprocess.run([xvfb_run(), "-a", "-s", "-screen 0 1280x800x24", sys.executable,
                          DRIVER, *args], capture_output=True, text=True, cwd=str(ROOT),
                         timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr
    with open(os.path.join(args[2], "result.json")) as f:
        result = json.load(f)
    assert not [l for l in result["lines"] if "failed" in l or "internal error" in l], result["lines"]
    return result


def effect_square(path: str) -> np.ndarray:
    return np.asarray(Image.open(path).convert("RGB")).astype(float)[:360, :360]


@pytest.mark.slow
def test_a_slider_a_texture_path_and_a_reload_in_the_window(wave_effect, tmp_path):
    out = tmp_path / "shots"
    result = drive("edit", str(wave_effect), str(out), str(wave_effect.parent / "green.png"))
    shots = {name: effect_square(shot["path"]) for name, shot in result["shots"].items()}
    for picture in shots.values():                 # the quad: every row alike
        assert picture.std(axis=0).max() == 0
    # TIME is held at 0.125 (--time); Speed starts at 1
    assert np.abs(shots["start"][180] - wave_row(0.125)).max() <= 3
    # a click at the slider's left end: Speed = UIMin = 0, the wave stands at phase 0
    assert result["speed_after_click"] == 0.0
    assert np.abs(shots["slider"][180] - wave_row(0.0)).max() <= 3
    assert np.abs(shots["slider"] - shots["start"]).max() > 90
    # green.png typed into Pattern's field: only green is left, at half the wave (Tint.g 0.5)
    assert np.abs(shots["texture"][180] - wave_row(0.0, texel=(0, 1, 0))).max() <= 3
    # the file edited: reloaded, and both edits still apply
    assert result["log"] and result["log"][0].startswith("reloaded after")
    assert result["speed_after_reload"] == 0.0
    assert np.array_equal(shots["reloaded"], shots["texture"])
    assert result["rc"] == 0


@pytest.mark.slow
def test_time_runs_between_two_screenshots_and_stands_while_paused(wave_effect, tmp_path):
    out = tmp_path / "shots"
    result = drive("run", str(wave_effect), str(out))
    seconds = {name: shot["seconds"] for name, shot in result["shots"].items()}
    shots = {name: effect_square(shot["path"]) for name, shot in result["shots"].items()}
    assert seconds["later"] > seconds["first"] + 0.2       # 20 frames later
    for name in ("first", "later"):                          # each the wave at its own time
        assert np.abs(shots[name][180] - wave_row(seconds[name])).max() <= 3, name
    # ... so they differ, unless the frames between took a whole period of the wave (1 s at
    # Speed 1): on a loaded machine 20 frames can, and both pictures are then rightly the same
    apart = (seconds["later"] - seconds["first"]) % 1.0
    if 0.05 < apart < 0.95:
        assert np.abs(shots["later"] - shots["first"]).max() > 20, seconds
    # space pauses: the clock and the picture stand
    assert seconds["still_paused"] == seconds["paused"]
    assert np.array_equal(shots["still_paused"], shots["paused"])


def view_square(*args: str, cwd: str) -> np.ndarray:
    """`effects view ARGS --exit-after 1.5 --screenshot`: the effect's 360 x 360 square."""
    shot = os.path.join(cwd, "view.png")
    out = subprocess.run([xvfb_run(), "-a", "-s", "-screen 0 1280x800x24", sys.executable, "-m",
                          "effects", "view", *args, "--size", "800x360", "--exit-after", "1.5",
                          "--screenshot", shot], capture_output=True, text=True, cwd=cwd,
                         timeout=180)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "warning" not in out.stdout and "failed" not in out.stdout, out.stdout
    return effect_square(shot)


@pytest.mark.slow
def test_view_reads_the_scene_beside_the_effect_and_takes_set_and_x_meshes(wave_effect):
    folder = str(wave_effect.parent)
    common = ["--profile", "radeon9700", "--time", "0.125"]
    # wave.yaml beside wave.fx: the quad, and Speed 0 -> the wave at phase 0
    (wave_effect.parent / "wave.yaml").write_text("mesh: quad\nparams: {Speed: 0.0}\n")
    beside = view_square("wave.fx", *common, cwd=folder)
    assert np.abs(beside[180] - wave_row(0.0)).max() <= 3
    # --no-scene: the file's Speed 1 on the --mesh quad; --set wins over the file
    plain = view_square("wave.fx", *common, "--no-scene", "--mesh", "quad", cwd=folder)
    assert np.abs(plain[180] - wave_row(0.125)).max() <= 3
    (wave_effect.parent / "other.yaml").write_text("mesh: quad\n")
    half = view_square("wave.fx", *common, "--scene", "other.yaml", "--set", "Speed=2", cwd=folder)
    assert np.abs(half[180] - wave_row(0.25)).max() <= 3
    # an SDK .x mesh by --mesh: the cube's silhouette, not the quad's full square
    cube = view_square("wave.fx", *common, "--no-scene", "--mesh",
                       str(ROOT / "tests" / "data" / "xmeshes" / "Cube.x"), cwd=folder)
    background = (cube.max(axis=-1) < 30)
    assert 0.3 < background.mean() < 0.95


def test_a_set_name_the_effect_lacks_is_said_once_and_the_rest_apply(wave_effect):
    from effects.viewer.app import Viewer, ViewerOptions
    said: list[str] = []
    viewer = Viewer(ViewerOptions(str(wave_effect), profile="radeon9700", mesh="quad",
                                  assignments={"Sped": "0", "Speed": "0.5"}), output=said.append)
    loaded = viewer._initial_build()
    assert loaded is not None and float(loaded.runtime.effect.parameter("Speed").value) == 0.5
    assert said == [f"{wave_effect}:1:1: warning: --set 'Sped': {wave_effect} has no parameter "
                    "of that name (settable: Time, Speed, Tint, Pattern)"]
    viewer._swap(loaded)
    assert len(said) == 1
