"""What every back end implements, and the registry that names them.

A back end draws lowered passes (`effects.program.passprogram.PassProgram`) into a frame:

    backend = create_backend("numpy")
    backend.begin_frame((256, 256), clear_color=(0, 0, 0, 1))
    backend.draw(program, streams, indices, "list", textures)   # as many draws as passes
    image = backend.end_frame()                                  # H x W x 4 uint8 RGBA

- `streams`: vertex attributes by usage name ('position' (N, 3|4), 'normal', 'tangent',
  'binormal', 'color0', 'color1', 'texcoord0'..'texcoord7'): the vertex program's inputs. With
  `program.vertex` None the positions are already in clip space and every other stream passes
  through as the varying of the same name.
- `indices`: (M,) or (M, 3) vertex indices; `primitive`: 'list', 'strip' or 'fan' (triangle
  strips alternate winding as Direct3D's do; see `triangle_list`).
- `textures`: TextureBinding.texture name -> `effects.program.texture.Texture`.
- The frame's render target persists across draws (multipass accumulation). Its format is
  A8R8G8B8 unless `begin_frame(format=...)` names one of `TARGET_FORMATS`; `end_frame` returns
  uint8 RGBA for the 8-bit formats and float32 RGBA for the float ones (channels a format lacks
  read as 1, as a texture of that format samples).
"""
from __future__ import annotations

import importlib
from typing import Callable, Mapping, Protocol, runtime_checkable

import numpy as np

from effects.base.errors import EffectError
from effects.program.passprogram import PassProgram

PRIMITIVES = ("list", "strip", "fan")
# Cube faces in D3DCUBEMAP_FACES order: (look direction, up) of the left-handed view that
# renders each face so that it matches the face's texel layout (D3D9 "Cubic Environment
# Mapping": +X, -X, +Y, -Y, +Z, -Z).
CUBE_FACE_VIEWS = (
    ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
    ((-1.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
    ((0.0, 1.0, 0.0), (0.0, 0.0, -1.0)),
    ((0.0, -1.0, 0.0), (0.0, 0.0, 1.0)),
    ((0.0, 0.0, 1.0), (0.0, 1.0, 0.0)),
    ((0.0, 0.0, -1.0), (0.0, 1.0, 0.0)),
)


class DrawError(ValueError):
    """A malformed draw call (a bug in the caller, not in user input)."""


class UnknownBackend(EffectError):
    """A back end name nobody registered (a user's --backend choice)."""


@runtime_checkable
class Backend(Protocol):
    """A renderer of lowered passes. See the module docstring for the argument conventions."""

    name: str

    def begin_frame(self, size: tuple[int, int], clear_color=(0.0, 0.0, 0.0, 0.0),
                    clear_depth: float = 1.0, clear_stencil: int = 0, *,
                    format: str = "A8R8G8B8") -> None: ...

    def draw(self, program: PassProgram, streams: Mapping[str, np.ndarray],
             indices: np.ndarray, primitive: str, textures: Mapping[str, object]) -> None: ...

    def end_frame(self) -> np.ndarray: ...

    def reset_shared_state(self) -> None:
        """Undo device state a draw leaves behind that a caller sharing the back end's context
        (the viewer's panel) does not expect; a back end with no shared context does nothing."""


def triangle_list(indices: np.ndarray, primitive: str) -> np.ndarray:
    """(M, 3) vertex indices of the triangles of a list, strip or fan, in draw order, as the
    D3D9 docs ("Triangle Strips", "Triangle Fans") list them: strip triangle k (from 0) is
    (k, k+1, k+2) for even k and (k, k+2, k+1) for odd k, so all keep the first one's winding
    and start at their provoking (flat-shading) vertex; fan triangle k is (k+1, k+2, 0).
    Degenerate triangles stay (the rasteriser drops them)."""
    idx = np.asarray(indices)
    if idx.size and not np.issubdtype(idx.dtype, np.integer):
        raise DrawError(f"indices must be integers, got {idx.dtype}")
    idx = idx.astype(np.int64).reshape(-1)
    if primitive == "list":
        if idx.size % 3:
            raise DrawError(f"a triangle list needs a multiple of 3 indices, got {idx.size}")
        return idx.reshape(-1, 3)
    if primitive == "strip":
        if idx.size < 3:
            return np.zeros((0, 3), np.int64)
        k = np.arange(idx.size - 2)
        odd = (k & 1).astype(bool)
        second = np.where(odd, idx[k + 2], idx[k + 1])
        third = np.where(odd, idx[k + 1], idx[k + 2])
        return np.stack([idx[k], second, third], axis=1)
    if primitive == "fan":
        if idx.size < 3:
            return np.zeros((0, 3), np.int64)
        k = np.arange(idx.size - 2)
        return np.stack([idx[k + 1], idx[k + 2], np.full_like(k, idx[0])], axis=1)
    raise DrawError(f"primitive must be one of {PRIMITIVES}, got {primitive!r}")


def render_cube_faces(backend: Backend, size: int, draw_face: Callable[[int], None], *,
                      format: str = "R32F", clear_color=(0.0, 0.0, 0.0, 0.0),
                      clear_depth: float = 1.0) -> np.ndarray:
    """Render the six faces of a cube map target: for each face f (D3D order, see
    CUBE_FACE_VIEWS) a frame of size x size in `format` into which `draw_face(f)` draws.
    Returns (6, size, size, 4) texels, ready for a cube `Texture` level."""
    faces = []
    for face in range(6):
        backend.begin_frame((size, size), clear_color, clear_depth, 0, format=format)
        draw_face(face)
        faces.append(backend.end_frame())
    return np.stack(faces)


# ---------------------------------------------------------------------------------------------
# Registry

BackendFactory = Callable[..., Backend]
_REGISTRY: dict[str, BackendFactory] = {}
# Modules that register the built-in back ends when imported (imported on first use, so
# `effects` never imports a back end and the GL one is only loaded when asked for).
_BUILTIN_MODULES = {"numpy": "backends.reference.renderer", "reference": "backends.reference.renderer",
                    "gl": "backends.gl.renderer"}


def register_backend(name: str, factory: BackendFactory) -> None:
    """Make `create_backend(name)` call `factory(**options)`."""
    _REGISTRY[name] = factory


def available_backends() -> list[str]:
    """Names that `create_backend` accepts (built-in ones whether or not loaded yet)."""
    return sorted(set(_REGISTRY) | set(_BUILTIN_MODULES))


def create_backend(name: str, **options) -> Backend:
    """A new back end by name ('numpy' is the NumPy reference; 'gl' the moderngl one)."""
    if name not in _REGISTRY and name in _BUILTIN_MODULES:
        importlib.import_module(_BUILTIN_MODULES[name])
    try:
        factory = _REGISTRY[name]
    except KeyError:
        raise UnknownBackend(f"unknown back end {name!r} (known: "
                             f"{', '.join(available_backends())})") from None
    return factory(**options)
