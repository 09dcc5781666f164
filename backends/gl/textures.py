"""`effects.program.texture.Texture`s as GL textures: float32 RGBA texels, every mip level.

A Texture holds decoded texel values (signed bump formats already in [-1, 1], DXT already
decompressed), so every format uploads as RGBA32F and the GL sampler returns exactly the
values the reference sampler reads. Row 0 of a level is v = 0, which is also GL's t = 0, so
no flip is needed; cube faces are in D3D's order, which is GL's (+X, -X, +Y, -Y, +Z, -Z) with
the same face (s, t) table.
"""
from __future__ import annotations

from collections import OrderedDict
from dataclasses import dataclass

import numpy as np

from backends.gl import rawgl as G
from backends.gl.rawgl import RawGL

TARGETS = {"1d": G.TEXTURE_1D, "2d": G.TEXTURE_2D, "3d": G.TEXTURE_3D, "cube": G.TEXTURE_CUBE_MAP}
_UNBOUND_TEXEL = np.array([0.0, 0.0, 0.0, 1.0], np.float32)  # an unbound sampler reads this


class TextureKindError(ValueError):
    """A texture whose kind cannot serve the sampler kind a program declares."""


@dataclass(frozen=True)
class GLTexture:
    name: int
    target: int
    level_count: int


def srgb_to_linear(x: np.ndarray) -> np.ndarray:
    """The inverse sRGB transfer function (IEC 61966-2-1) on [0, 1] values."""
    x = np.clip(np.asarray(x, np.float32), 0, 1)
    return np.where(x <= 0.04045, x / 12.92, np.power((x + 0.055) / 1.055, 2.4)).astype(np.float32)


def levels_for(texture_kind: str, levels, kind: str) -> list[np.ndarray]:
    """The levels of a texture of `texture_kind` shaped for a GL texture of `kind`:
    1d (W, 4), 2d (H, W, 4), 3d (D, H, W, 4), cube (6, H, W, 4); all float32 RGBA."""
    out = []
    for level in levels:
        a = np.asarray(level, np.float32)
        if a.shape[-1] < 4:  # channels a level lacks read (0, 0, 0, 1)
            full = np.broadcast_to(_UNBOUND_TEXEL, (*a.shape[:-1], 4)).copy()
            full[..., :a.shape[-1]] = a
            a = full
        if kind == "1d" and texture_kind in ("1d", "2d"):
            a = a[0]            # a 1D texture is stored as one row
        elif kind == "2d" and texture_kind in ("1d", "2d"):
            pass
        elif kind != texture_kind:
            raise TextureKindError(f"a {texture_kind} texture cannot be sampled as {kind}")
        out.append(np.ascontiguousarray(a))
    return out


def upload(gl: RawGL, kind: str, levels: list[np.ndarray]) -> GLTexture:
    """A new GL texture of `kind` holding `levels` (shaped as `levels_for` returns them)."""
    target = TARGETS[kind]
    name = gl.gen("Textures")
    gl.glBindTexture(target, name)
    gl.glPixelStorei(G.UNPACK_ALIGNMENT, 4)
    for k, a in enumerate(levels):
        if kind == "1d":
            gl.glTexImage1D(target, k, G.RGBA32F, a.shape[0], 0, G.RGBA, G.FLOAT, a.ctypes.data)
        elif kind == "2d":
            gl.glTexImage2D(target, k, G.RGBA32F, a.shape[1], a.shape[0], 0, G.RGBA, G.FLOAT,
                            a.ctypes.data)
        elif kind == "3d":
            gl.glTexImage3D(target, k, G.RGBA32F, a.shape[2], a.shape[1], a.shape[0], 0, G.RGBA,
                            G.FLOAT, a.ctypes.data)
        else:
            for face in range(6):
                f = np.ascontiguousarray(a[face])
                gl.glTexImage2D(G.TEXTURE_CUBE_MAP_POSITIVE_X + face, k, G.RGBA32F, f.shape[1],
                                f.shape[0], 0, G.RGBA, G.FLOAT, f.ctypes.data)
    # Levels beyond the supplied chain do not exist: the texture is complete with what it has.
    gl.glTexParameteri(target, G.TEXTURE_BASE_LEVEL, 0)
    gl.glTexParameteri(target, G.TEXTURE_MAX_LEVEL, len(levels) - 1)
    gl.check(f"uploading a {kind} texture")
    return GLTexture(name, target, len(levels))


def _unbound_levels(kind: str) -> list[np.ndarray]:
    shape = {"1d": (1,), "2d": (1, 1), "3d": (1, 1, 1), "cube": (6, 1, 1)}[kind]
    return [np.broadcast_to(_UNBOUND_TEXEL, (*shape, 4)).copy()]


class TextureCache:
    """GL textures for Texture objects, uploaded once per (texture, GL kind, sRGB) and kept
    while the texture object and its level arrays stay the same (least recently used first
    out beyond `capacity`)."""

    def __init__(self, gl: RawGL, capacity: int = 64) -> None:
        self.gl = gl
        self.capacity = capacity
        self._entries: OrderedDict[tuple, tuple[object, tuple, GLTexture]] = OrderedDict()
        self._unbound: dict[str, GLTexture] = {}
        self.uploads = 0

    def get(self, texture, kind: str, srgb: bool = False) -> GLTexture:
        key = (id(texture), kind, bool(srgb))
        identity = tuple(id(level) for level in texture.levels)
        entry = self._entries.get(key)
        if entry is not None and entry[0] is texture and entry[1] == identity:
            self._entries.move_to_end(key)
            return entry[2]
        if entry is not None:
            self.gl.delete("Textures", entry[2].name)
        levels = levels_for(texture.kind, texture.levels, kind)
        if srgb:
            levels = [np.concatenate([srgb_to_linear(a[..., :3]), a[..., 3:]], axis=-1)
                      for a in levels]
        gl_texture = upload(self.gl, kind, levels)
        self.uploads += 1
        self._entries[key] = (texture, identity, gl_texture)
        while len(self._entries) > self.capacity:
            _, (_, _, old) = self._entries.popitem(last=False)
            self.gl.delete("Textures", old.name)
        return gl_texture

    def unbound(self, kind: str) -> GLTexture:
        """A 1-texel texture of (0, 0, 0, 1): what D3D samples from an empty slot."""
        if kind not in self._unbound:
            self._unbound[kind] = upload(self.gl, kind, _unbound_levels(kind))
        return self._unbound[kind]

    def release(self) -> None:
        for _, _, gl_texture in self._entries.values():
            self.gl.delete("Textures", gl_texture.name)
        for gl_texture in self._unbound.values():
            self.gl.delete("Textures", gl_texture.name)
        self._entries.clear()
        self._unbound.clear()
