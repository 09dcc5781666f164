"""Hot reload of the scene file (--scene, or NAME.yaml beside NAME.fx): the effect's hot reload
(`effects.viewer.reload`) for the YAML that says what it is drawn in.

A `SceneReloader` watches the one file with `effects.viewer.watch.Watcher` (watchdog events,
debounced, filtered by content hash) and reads it again on the watcher's thread when it
changes: a scene file is small and its reading bounded (`yaml_bytes`, `yaml_depth`,
`literal_digits` in effects/base/limits.py), so no worker of its own is needed. Each read is a
`SceneResult` on a queue: the new Scene, or the located error. The render thread polls it
each frame; a good scene replaces the one drawn (the viewer builds again with it, off the
render thread), a broken one leaves the last good scene on screen and its error in the panel.
It prints:
    scene: PATH ok in 1.2 ms
    scene: PATH failed: PATH:LINE:COL: error: MESSAGE
Nothing here opens a window.
"""
from __future__ import annotations

import os
import queue
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING

from effects.viewer.watch import Watcher

if TYPE_CHECKING:  # pragma: no cover
    from effects.host.scene import Scene


@dataclass
class SceneResult:
    """One reading of the scene file: `scene`, or the `error` that stopped it."""

    path: str
    scene: "Scene | None"
    error: BaseException | None
    read_ms: float

    @property
    def ok(self) -> bool:
        return self.error is None

    def log_line(self) -> str:
        from effects.viewer.reload import error_text
        if self.ok:
            return f"scene: {self.path} ok in {self.read_ms:.1f} ms"
        return f"scene: {self.path} failed: {error_text(self.error)}"


class SceneReloader:
    """Read scene file `path` again whenever its content changes; `poll()` gives each reading."""

    def __init__(self, path: str, *, use_watchdog: bool = True, **watch_options: float) -> None:
        self.path = path
        self.results: "queue.Queue[SceneResult]" = queue.Queue()
        self.watcher = Watcher([os.path.abspath(path)], self._changed, use_watchdog=use_watchdog,
                               **watch_options)

    def start(self) -> "SceneReloader":
        self.watcher.start()
        return self

    def stop(self) -> None:
        self.watcher.stop()

    def poll(self) -> SceneResult | None:
        """The next reading, or None. For the render thread; never blocks."""
        try:
            return self.results.get_nowait()
        except queue.Empty:
            return None

    def wait(self, timeout: float) -> SceneResult | None:
        """Block up to `timeout` seconds for the next reading (tests)."""
        try:
            return self.results.get(timeout=timeout)
        except queue.Empty:
            return None

    def _changed(self, paths: list[str]) -> None:
        from effects.host.scene import load_scene
        start = time.perf_counter()
        try:
            scene, error = load_scene(self.path), None
        except Exception as exc:  # noqa: BLE001 - said in the panel; the last good scene stays
            scene, error = None, exc
        self.results.put(SceneResult(self.path, scene, error, (time.perf_counter() - start) * 1000.0))
