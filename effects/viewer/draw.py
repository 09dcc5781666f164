"""The viewer's pictures: the effect through the GL back end, the NumPy reference, and their
difference, each shown as a texture in the window.

The GL back end draws with the window's own context (`GLBackend(context=window.ctx)`) into its
offscreen target and reads the frame back; the viewer uploads it and draws it 1:1 beside the
panel. One GL path, the same one `effects render --backend gl` uses, so what the viewer shows is
what the tests check. The reference is slow (seconds), so it renders in a thread of its own and
the view says so until it is ready.
"""
from __future__ import annotations

import threading
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import moderngl
import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    from effects.viewer.reload import LoadedEffect
    from effects.host.scene import Scene

_BLIT_VERTEX = """
#version 330
in vec2 in_pos;
out vec2 uv;
void main() {
    // the image's row 0 is its top: flip v so it shows upright
    uv = vec2(in_pos.x * 0.5 + 0.5, 0.5 - in_pos.y * 0.5);
    gl_Position = vec4(in_pos, 0.0, 1.0);
}
"""
_BLIT_FRAGMENT = """
#version 330
uniform sampler2D image;
in vec2 uv;
out vec4 color;
void main() { color = vec4(texture(image, uv).rgb, 1.0); }
"""


def render_effect(loaded: "LoadedEffect", scene: "Scene", backend: Any,
                  runtime: Any = None, params: dict[str, Any] | None = None) -> np.ndarray:
    """One frame of the loaded effect's technique in `scene`: H x W x 4 uint8 RGBA, top row
    first. `runtime`: a Runtime already bound to this effect and scene (its lowered passes,
    textures and streams are reused), else a new one is made with `params` (the viewer's
    --set values and edits)."""
    from effects.host.runtime import Runtime
    if runtime is None:
        runtime = Runtime(loaded.effect, loaded.profile, scene=scene, backend=backend,
                          params=params)
    runtime.backend = backend
    return runtime.render(loaded.technique).image


def difference_image(a: np.ndarray, b: np.ndarray, scale: int) -> np.ndarray:
    """|a - b| per RGB channel times `scale`, clamped to 255, opaque."""
    d = np.abs(a[..., :3].astype(np.int16) - b[..., :3].astype(np.int16)) * scale
    out = np.empty(a.shape[:2] + (4,), np.uint8)
    out[..., :3] = np.minimum(d, 255)
    out[..., 3] = 255
    return out


@dataclass
class DifferenceStats:
    max: int
    mean: float
    over_2: float         # fraction of pixels with some channel off by more than 2

    @classmethod
    def of(cls, a: np.ndarray, b: np.ndarray) -> "DifferenceStats":
        d = np.abs(a[..., :3].astype(np.int16) - b[..., :3].astype(np.int16))
        return cls(int(d.max(initial=0)), float(d.mean()) if d.size else 0.0,
                   float((d.max(axis=-1) > 2).mean()) if d.size else 0.0)


class Blitter:
    """Draws an RGBA image (top row first) into a rectangle of the window, 1:1."""

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.program = ctx.program(vertex_shader=_BLIT_VERTEX, fragment_shader=_BLIT_FRAGMENT)
        quad = np.array([-1, -1, 1, -1, -1, 1, 1, 1], np.float32)
        self.vbo = ctx.buffer(quad.tobytes())
        self.vao = ctx.vertex_array(self.program, [(self.vbo, "2f", "in_pos")])
        self.texture: moderngl.Texture | None = None

    def upload(self, image: np.ndarray) -> None:
        h, w = image.shape[:2]
        if self.texture is None or self.texture.size != (w, h):
            if self.texture is not None:
                self.texture.release()
            self.texture = self.ctx.texture((w, h), 4)
            self.texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
        self.texture.write(np.ascontiguousarray(image[..., :4]).tobytes())

    def draw(self, rect: tuple[int, int, int, int]) -> None:
        """rect: (x, y, w, h) in framebuffer pixels, y from the bottom (GL's viewport)."""
        if self.texture is None:
            return
        self.ctx.viewport = rect
        self.ctx.disable(moderngl.BLEND | moderngl.DEPTH_TEST | moderngl.CULL_FACE)
        self.texture.use(0)
        self.program["image"].value = 0
        self.vao.render(moderngl.TRIANGLE_STRIP)


class ReferenceRenderer:
    """Renders with the NumPy back end in a background thread; the newest request wins."""

    def __init__(self) -> None:
        self._lock = threading.Condition()
        self._request: tuple[Any, "LoadedEffect", "Scene", dict[str, Any]] | None = None
        self._running_key: Any = None
        self._result: tuple[Any, np.ndarray | None, float, BaseException | None] | None = None
        self._stopping = False
        self._thread = threading.Thread(target=self._work, name="effects-reference", daemon=True)
        self._thread.start()
        self._backend = None

    def request(self, key: Any, loaded: "LoadedEffect", scene: "Scene",
                params: dict[str, Any] | None = None) -> None:
        with self._lock:
            if key == self._running_key or (self._request is not None and self._request[0] == key):
                return
            self._request = (key, loaded, scene, dict(params or {}))
            self._lock.notify_all()

    @property
    def busy(self) -> bool:
        with self._lock:
            return self._running_key is not None or self._request is not None

    def take(self) -> tuple[Any, np.ndarray | None, float, BaseException | None] | None:
        with self._lock:
            result, self._result = self._result, None
            return result

    def stop(self) -> None:
        with self._lock:
            self._stopping = True
            self._lock.notify_all()

    def _work(self) -> None:
        while True:
            with self._lock:
                while self._request is None and not self._stopping:
                    self._lock.wait()
                if self._stopping:
                    return
                key, loaded, scene, params = self._request  # type: ignore[misc]
                self._request = None
                self._running_key = key
            start = time.perf_counter()
            try:
                if self._backend is None:
                    from effects.program.backend import create_backend
                    self._backend = create_backend("numpy")
                image, error = render_effect(loaded, scene, self._backend, params=params), None
            except BaseException as exc:  # noqa: BLE001 - shown in the panel
                image, error = None, exc
            ms = (time.perf_counter() - start) * 1000.0
            with self._lock:
                self._running_key = None
                self._result = (key, image, ms, error)
