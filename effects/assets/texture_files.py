"""Texture files by extension: a registry of loaders, so a new file type is one registration.

    @register(".ktx")
    def _ktx(path, where, kind): ...  -> Texture

Bundled: images through Pillow (`effects.assets.images`; A8R8G8B8, full mip chain), `.dds`
through our reader (`effects.assets.dds`: its own format, kind and mips), `.npy` raw texels
(H, W, C), (6, H, W, C) cube or (D, H, W, C) volume, uint8 (A8R8G8B8) or float
(A32B32G32R32F), C = L, LA, RGB or RGBA. Every loader checks the texture limits
(`effects.base.limits`) from the file's header, before the texels are allocated.
"""
from __future__ import annotations

import os
from typing import Callable

import numpy as np

from effects.base import limits, untrusted
from effects.base.errors import Location, SceneError
from effects.assets import dds
from effects.assets.images import read_image
from effects.assets.textures import make_texture
from effects.program.texture import KINDS, Texture

Loader = Callable[[str, Location, "str | None"], Texture]
LOADERS: dict[str, Loader] = {}


def register(*extensions: str) -> Callable[[Loader], Loader]:
    """Register a loader for file extensions ('.png'; lower case, with the dot)."""
    def add(loader: Loader) -> Loader:
        for ext in extensions:
            LOADERS[ext.lower()] = loader
        return loader
    return add


# .pcx: the PC Paintbrush images DOS-era and Allegro games ship (Pillow reads them)
@register(".png", ".jpg", ".jpeg", ".bmp", ".tga", ".gif", ".tif", ".tiff", ".ppm", ".pcx")
def _load_image(path: str, where: Location, kind: str | None) -> Texture:
    rgba = read_image(path, "RGBA", where).astype(np.float32) / 255.0
    return make_texture(rgba, "A8R8G8B8", name=os.path.basename(path))


@register(".dds")
def _load_dds(path: str, where: Location, kind: str | None) -> Texture:
    return dds.read_dds(path)


def _expand_channels(a: np.ndarray) -> np.ndarray:
    """(..., C) texels, C = 1 (L), 2 (L, A), 3 (RGB) or 4 (RGBA) -> (..., 4)."""
    c = a.shape[-1]
    if c == 1:
        return np.concatenate([a, a, a, np.ones_like(a)], -1)
    if c == 2:
        return np.concatenate([a[..., :1]] * 3 + [a[..., 1:]], -1)
    if c == 3:
        return np.concatenate([a, np.ones_like(a[..., :1])], -1)
    return a


def _npy_header(path: str, where: Location) -> tuple[tuple[int, ...], np.dtype, bool, int]:
    """(shape, dtype, fortran order, header length) read without touching the data."""
    fmt = np.lib.format
    try:
        with open(path, "rb") as f:
            version = fmt.read_magic(f)
            if version == (1, 0):
                shape, fortran, dtype = fmt.read_array_header_1_0(f)
            else:
                shape, fortran, dtype = fmt.read_array_header_2_0(f)
            return shape, dtype, fortran, f.tell()
    except (OSError, ValueError, SyntaxError, TypeError, OverflowError, MemoryError) as exc:
        raise SceneError(f"cannot read .npy texture header: {str(exc)[:200]}", where) from None


def _load_raw_npy(path: str, where: Location) -> np.ndarray:
    size = untrusted.check_regular(path, ".npy texture", SceneError, where, "texture_file_bytes")
    shape, dtype, fortran, offset = _npy_header(path, where)
    if dtype.hasobject:
        raise SceneError(".npy texture holds Python objects; only numbers are read", where)
    if dtype != np.uint8 and dtype.kind != "f":
        raise SceneError(f".npy texture must be uint8 or float, not {dtype}", where)
    if len(shape) not in (3, 4) or not 1 <= shape[-1] <= 4 or 0 in shape:
        raise SceneError(f".npy texture shape {str(shape)[:80]} is not (H, W, C), (6, H, W, C) or "
                         "(D, H, W, C) with C in 1..4", where)
    height, width = shape[-3], shape[-2]
    layers = shape[0] if len(shape) == 4 else 1
    limits.check_texture(width, height, layers, where, ".npy texture", SceneError)
    count = height * width * layers * shape[-1]
    if offset + count * dtype.itemsize > size:
        raise SceneError(f".npy texture is truncated: its header says {shape}, the file holds "
                         f"{max(0, size - offset):,} bytes of data", where)
    try:
        return np.load(path, allow_pickle=False)
    except (OSError, ValueError) as exc:
        raise SceneError(f"cannot read .npy texture: {exc}", where) from None


@register(".npy")
def _load_npy(path: str, where: Location, kind: str | None) -> Texture:
    raw = _load_raw_npy(path, where)
    if raw.dtype == np.uint8:
        values, fmt = raw.astype(np.float32) / 255.0, "A8R8G8B8"
    else:
        values, fmt = raw.astype(np.float32), "A32B32G32R32F"
    if raw.ndim == 3:
        file_kind = "1d" if kind == "1d" and raw.shape[0] == 1 else "2d"
    elif kind in ("cube", "3d"):
        file_kind = kind
    else:
        file_kind = "cube" if raw.shape[0] == 6 and raw.shape[1] == raw.shape[2] else "3d"
    if file_kind == "cube" and (raw.shape[0] != 6 or raw.shape[1] != raw.shape[2]):
        raise SceneError(f".npy cube map must be (6, N, N, C), not {raw.shape}", where)
    if not np.all(np.isfinite(values)):
        raise SceneError(".npy texture holds NaN or infinite values", where)
    return make_texture(_expand_channels(values), fmt, kind=file_kind, name=os.path.basename(path))


def load_texture(path: str | os.PathLike[str], *, kind: str | None = None) -> Texture:
    """Load a texture file by its extension (module docstring).

    `kind`, when given, is what the caller needs ('2d', 'cube', '3d', '1d'); a file of another
    kind is an error. Every problem is a `SceneError` at the file (line 1, column 1).
    """
    path = os.fspath(path)
    where = Location(path, 1, 1)
    if kind is not None and kind not in KINDS:
        raise ValueError(f"unknown texture kind {kind!r}")
    if not os.path.exists(path):
        raise SceneError("texture file not found", where)
    untrusted.check_regular(path, "texture file", SceneError, where, "texture_file_bytes")
    ext = os.path.splitext(path)[1].lower()
    loader = LOADERS.get(ext)
    if loader is None:
        raise SceneError(f"unknown texture file type {ext or '(none)'!r} (known: "
                         f"{', '.join(sorted(LOADERS))})", where)
    texture = loader(path, where, kind)
    if kind == "1d" and texture.kind == "2d" and texture.height == 1:
        texture.kind = "1d"
    if kind is not None and texture.kind != kind:
        raise SceneError(f"texture is a {texture.kind} texture, but a {kind} texture is needed", where)
    return texture
