"""Which scene an effect is drawn in (`scene_for`), in a module of its own: the scene reader
(effects.host.scene) loads NumPy and PyYAML, and the command line asks this while it keys
stored matrix rows, before anything else needs them (effects.cli.matrix_store)."""
from __future__ import annotations

import os


def scene_for(effect_path: str, scene: str | None, *, beside: bool = True) -> str | None:
    """The scene an effect is drawn in: the one named; else, unless `beside` is false
    (`--no-scene`), `NAME.yaml` next to `NAME.fx` (the way fxfiles/wood.yaml supplies the
    colours and light a file's techniques read, and sdk8_style.yaml what a DX8 file cannot
    declare); else None, the default scene. Every command that draws or diagnoses asks this."""
    if scene is not None:
        return scene
    if not beside:
        return None
    path = os.path.splitext(os.fspath(effect_path))[0] + ".yaml"
    return path if os.path.isfile(path) else None

