"""The scene file's hot reload (effects.viewer.scene_reload): editing NAME.yaml beside NAME.fx
redraws; a broken scene file keeps the last good scene on screen with its located error.

Windowless: a SceneReloader on a temp folder (real file events), and ViewerState taking each
reading. In a window: `effects view` under Xvfb as tests/viewer/test_viewer.py runs it, the
scene edited while it runs, the screenshot read back. The effect is conftest's flat one: its
TextureFactor colour (red) on every pixel the mesh covers, so the sphere is a red disc and
the corners show the scene's clear colour.
"""
from __future__ import annotations

import os

import numpy as np

from effects.host.scene import load_scene
from effects.viewer.scene_reload import SceneReloader
from effects.viewer.state import Orbit, ViewerState

from tests.viewer.test_viewer import SIZE, ViewerProcess, effect_pixels

TIMEOUT = 10.0


def save(path, text: str) -> None:
    """Atomically, as an editor saves (a plain write can be read half done on a loaded machine)."""
    tmp = f"{path}.part"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def test_each_edit_is_read_again_and_a_broken_one_is_a_located_error(tmp_path):
    path = tmp_path / "flat.yaml"
    path.write_text("mesh: quad\n")
    scenes = SceneReloader(str(path)).start()
    try:
        save(path, "mesh: sphere\nclear: {color: [0, 0, 1, 1]}\n")
        result = scenes.wait(TIMEOUT)
        assert result is not None and result.ok, result
        assert result.scene.mesh == "sphere" and result.scene.clear_color == (0, 0, 1, 1)
        assert result.log_line().startswith(f"scene: {path} ok in ")
        save(path, "mesh: sphere\nclear: {color: [0, 0, 1\n")
        result = scenes.wait(TIMEOUT)
        assert result is not None and not result.ok
        assert result.log_line().startswith(f"scene: {path} failed: {path}:3:1: error: scene file is "
                                            "not valid YAML"), result.log_line()
        save(path, "mesh: sphere\nclear: {color: [0, 0, 1\n")      # the same bytes: nothing to read
        assert scenes.wait(0.5) is None
    finally:
        scenes.stop()


def test_the_viewer_state_takes_what_the_edited_scene_changed(tmp_path):
    path = tmp_path / "s.yaml"
    path.write_text("mesh: quad\ncamera: {eye: [0, 0, 5]}\n")
    state = ViewerState(["tnt2"])
    state.start_from_scene(load_scene(str(path)))
    assert state.mesh == "quad" and state.orbit.distance == 5
    state.orbit.drag(40, 0)                    # the user turns the camera
    yaw, selections = state.orbit.yaw, state.selection_generation
    path.write_text("mesh: sphere\ncamera: {eye: [0, 0, 5]}\nclear: {color: [1, 0, 0, 1]}\n")
    state.reload_scene(load_scene(str(path)))
    # the file's new mesh and clear colour; its camera is as it was: the user's orbit stays
    assert state.mesh == "sphere" and state.orbit.yaw == yaw
    assert state.scene((64, 64)).clear_color == (1, 0, 0, 1)
    assert state.selection_generation == selections + 1      # built again with the new scene
    path.write_text("mesh: sphere\ncamera: {eye: [0, 0, 7]}\n")
    state.reload_scene(load_scene(str(path)))
    assert state.orbit == Orbit.looking(load_scene(str(path)).camera) and state.orbit.distance == 7
    state.set_mesh("cube")                     # the user's mesh is not the file's to change
    path.write_text("mesh: torus\ncamera: {eye: [0, 0, 9]}\n")
    before = state.reload_scene(load_scene(str(path)))
    assert state.mesh == "cube" and state.orbit.distance == 9
    key = state.scene_key((64, 64))
    state.restore_scene(before)                # a scene the effect cannot be drawn in: undone
    assert state.orbit.distance == 7 and state.base_scene.camera.eye == (0, 0, 7)
    assert state.scene_key((64, 64)) != key


def test_editing_the_scene_file_redraws_and_a_broken_one_keeps_the_last_good_scene(tinted_effect):
    flat = tinted_effect.parent
    path, scene = flat / "flat.fx", flat / "flat.yaml"     # NAME.yaml beside NAME.fx
    scene.write_text("mesh: quad\n")
    shot = flat / "last.png"
    viewer = ViewerProcess(str(path), "--profile", "tnt2", "--size", SIZE, "--exit-after", "15",
                           "--screenshot", str(shot))
    viewer.expect(lambda l: l == f"view: {path} on tnt2: technique Flat (1 pass)", "view: ...")
    # 1. a good edit: the sphere on blue
    save(scene, "mesh: sphere\nclear: {color: [0, 0, 1, 1]}\n")
    line = viewer.expect(lambda l: l.startswith("scene:"), "after a good edit of the scene")
    assert line.startswith(f"scene: {scene} ok in "), line
    line = viewer.expect(lambda l: l.startswith("select:"), "the effect prepared in the new scene")
    assert line == "select: tnt2: technique Flat (1 pass)", line
    # 2. a scene that reads but names a mesh file that is not there: the effect cannot be
    # prepared in it; said, located in the scene file, and the last good scene stays
    save(scene, "mesh: nope.obj\nclear: {color: [0, 1, 0, 1]}\n")
    line = viewer.expect(lambda l: l.startswith("scene:"), "the scene read")
    assert line.startswith(f"scene: {scene} ok in "), line
    line = viewer.expect(lambda l: l.startswith("scene:"), "the scene that cannot be drawn")
    assert line == f"scene: {scene} failed: {scene}:1:7: error: mesh file not found: {flat / 'nope.obj'}"
    # 3. a broken edit: said, located; the last good scene stays
    save(scene, "mesh: sphere\nclear: {color: [0, 0, 1\n")
    line = viewer.expect(lambda l: l.startswith("scene:"), "after a broken edit of the scene")
    assert line.startswith(f"scene: {scene} failed: {scene}:3:1: error: scene file is not valid "
                           "YAML"), line
    # a broken scene at exit is a file that does not load: 2, as a broken effect's
    assert viewer.finish() == 2, "\n".join(viewer.lines)
    assert not any(l.startswith(("reload:", "render:")) for l in viewer.lines), viewer.lines
    pixels = effect_pixels(str(shot))
    # the last good scene on screen: blue corners (the clear colour), the red sphere between
    assert (pixels[:20, :20] == (0, 0, 255)).all(), np.unique(pixels[:20, :20].reshape(-1, 3), axis=0)
    assert (pixels[170:190, 170:190] == (255, 0, 0)).all(), pixels[180, 180]
