"""The few OpenGL entry points moderngl does not wrap, called through ctypes.

moderngl has no stencil state, blend colour, mirrored or mirror-once wrap modes, 1D textures,
per-level uploads of cube and volume textures, or packed depth-stencil attachments. Those calls
go straight to the GL library. On Linux the GL library is GLVND's `libOpenGL.so.0` (or
`libGL.so.1`), whose entry points dispatch to whatever context is current on the thread, EGL
or GLX alike, so the same table serves the headless context and the viewer's window.
"""
from __future__ import annotations

import ctypes
import ctypes.util
from ctypes import POINTER, c_float, c_int, c_uint, c_void_p
from typing import Any

from effects.base.errors import EffectError, Location

# Enum values from the OpenGL 4.5 core registry (gl.xml).
ZERO, ONE = 0, 1
NEVER, LESS, EQUAL, LEQUAL, GREATER, NOTEQUAL, GEQUAL, ALWAYS = range(0x0200, 0x0208)
SRC_COLOR, ONE_MINUS_SRC_COLOR, SRC_ALPHA, ONE_MINUS_SRC_ALPHA = 0x0300, 0x0301, 0x0302, 0x0303
DST_ALPHA, ONE_MINUS_DST_ALPHA, DST_COLOR, ONE_MINUS_DST_COLOR = 0x0304, 0x0305, 0x0306, 0x0307
SRC_ALPHA_SATURATE = 0x0308
CONSTANT_COLOR, ONE_MINUS_CONSTANT_COLOR = 0x8001, 0x8002
SRC1_COLOR, ONE_MINUS_SRC1_COLOR = 0x88F9, 0x88FA
FUNC_ADD, MIN, MAX, FUNC_SUBTRACT, FUNC_REVERSE_SUBTRACT = 0x8006, 0x8007, 0x8008, 0x800A, 0x800B
KEEP, REPLACE, INCR, DECR, INVERT = 0x1E00, 0x1E01, 0x1E02, 0x1E03, 0x150A
INCR_WRAP, DECR_WRAP = 0x8507, 0x8508
FRONT, BACK, FRONT_AND_BACK = 0x0404, 0x0405, 0x0408
CW, CCW = 0x0900, 0x0901
CULL_FACE, DEPTH_TEST, STENCIL_TEST, BLEND = 0x0B44, 0x0B71, 0x0B90, 0x0BE2
SCISSOR_TEST = 0x0C11
TEXTURE_CUBE_MAP_SEAMLESS = 0x884F
POINT, LINE, FILL = 0x1B00, 0x1B01, 0x1B02
FIRST_VERTEX_CONVENTION = 0x8E4D
TEXTURE_1D, TEXTURE_2D, TEXTURE_3D, TEXTURE_CUBE_MAP = 0x0DE0, 0x0DE1, 0x806F, 0x8513
TEXTURE_CUBE_MAP_POSITIVE_X = 0x8515
TEXTURE0 = 0x84C0
TEXTURE_BASE_LEVEL, TEXTURE_MAX_LEVEL = 0x813C, 0x813D
TEXTURE_MAG_FILTER, TEXTURE_MIN_FILTER = 0x2800, 0x2801
TEXTURE_WRAP_S, TEXTURE_WRAP_T, TEXTURE_WRAP_R = 0x2802, 0x2803, 0x8072
TEXTURE_BORDER_COLOR, TEXTURE_LOD_BIAS = 0x1004, 0x8501
TEXTURE_MIN_LOD, TEXTURE_MAX_LOD = 0x813A, 0x813B
TEXTURE_MAX_ANISOTROPY = 0x84FE
NEAREST, LINEAR = 0x2600, 0x2601
NEAREST_MIPMAP_NEAREST, LINEAR_MIPMAP_NEAREST = 0x2700, 0x2701
NEAREST_MIPMAP_LINEAR, LINEAR_MIPMAP_LINEAR = 0x2702, 0x2703
REPEAT, CLAMP_TO_BORDER, CLAMP_TO_EDGE = 0x2901, 0x812D, 0x812F
MIRRORED_REPEAT, MIRROR_CLAMP_TO_EDGE = 0x8370, 0x8743
RGBA, FLOAT, UNSIGNED_BYTE = 0x1908, 0x1406, 0x1401
RGBA8, RGB8, R32F, RG32F, RGBA16F, RGBA32F = 0x8058, 0x8051, 0x822E, 0x8230, 0x881A, 0x8814
R16F, RG16F = 0x822D, 0x822F
UNPACK_ALIGNMENT, PACK_ALIGNMENT = 0x0CF5, 0x0D05
FRAMEBUFFER, RENDERBUFFER = 0x8D40, 0x8D41
COLOR_ATTACHMENT0, DEPTH_STENCIL_ATTACHMENT = 0x8CE0, 0x821A
DEPTH32F_STENCIL8 = 0x8CAD
FRAMEBUFFER_COMPLETE = 0x8CD5
DEPTH_BUFFER_BIT, STENCIL_BUFFER_BIT, COLOR_BUFFER_BIT = 0x0100, 0x0400, 0x4000
NO_ERROR = 0

_f, _i, _u, _p = c_float, c_int, c_uint, c_void_p
# name -> argument types (all these functions return void unless listed in _RETURNS)
_SIGNATURES: dict[str, tuple] = {
    "glEnable": (_u,), "glDisable": (_u,),
    "glDepthFunc": (_u,), "glDepthMask": (ctypes.c_ubyte,),
    "glCullFace": (_u,), "glFrontFace": (_u,), "glPolygonMode": (_u, _u),
    "glProvokingVertex": (_u,),
    "glColorMask": (ctypes.c_ubyte,) * 4,
    "glBlendFuncSeparate": (_u, _u, _u, _u), "glBlendEquationSeparate": (_u, _u),
    "glBlendColor": (_f, _f, _f, _f),
    "glStencilFuncSeparate": (_u, _u, _i, _u), "glStencilOpSeparate": (_u, _u, _u, _u),
    "glStencilMaskSeparate": (_u, _u),
    "glClearColor": (_f, _f, _f, _f), "glClearDepth": (ctypes.c_double,),
    "glClearStencil": (_i,), "glClear": (_u,),
    "glGenTextures": (_i, POINTER(_u)), "glDeleteTextures": (_i, POINTER(_u)),
    "glActiveTexture": (_u,), "glBindTexture": (_u, _u),
    "glTexParameteri": (_u, _u, _i), "glPixelStorei": (_u, _i),
    "glTexImage1D": (_u, _i, _i, _i, _i, _u, _u, _p),
    "glTexImage2D": (_u, _i, _i, _i, _i, _i, _u, _u, _p),
    "glTexImage3D": (_u, _i, _i, _i, _i, _i, _i, _u, _u, _p),
    "glGenSamplers": (_i, POINTER(_u)), "glDeleteSamplers": (_i, POINTER(_u)),
    "glBindSampler": (_u, _u), "glSamplerParameteri": (_u, _u, _i),
    "glSamplerParameterf": (_u, _u, _f), "glSamplerParameterfv": (_u, _u, POINTER(_f)),
    "glGenFramebuffers": (_i, POINTER(_u)), "glDeleteFramebuffers": (_i, POINTER(_u)),
    "glBindFramebuffer": (_u, _u), "glFramebufferTexture2D": (_u, _u, _u, _u, _i),
    "glFramebufferRenderbuffer": (_u, _u, _u, _u), "glCheckFramebufferStatus": (_u,),
    "glGenRenderbuffers": (_i, POINTER(_u)), "glDeleteRenderbuffers": (_i, POINTER(_u)),
    "glBindRenderbuffer": (_u, _u), "glRenderbufferStorage": (_u, _u, _i, _i),
    "glViewport": (_i, _i, _i, _i), "glReadPixels": (_i, _i, _i, _i, _u, _u, _p),
    "glGetError": (), "glFinish": (),
}
_RETURNS = {"glCheckFramebufferStatus": _u, "glGetError": _u}
_LIBRARIES = ("libOpenGL.so.0", "libGL.so.1", "OpenGL", "GL")


class RawGLUnavailable(EffectError):
    """No GL library with the needed entry points could be loaded (a user-facing error: it
    names the package that provides the library)."""

    def __init__(self, message: str) -> None:
        super().__init__(f"{message}; the GL back end needs GLVND's libOpenGL (Debian/Ubuntu: "
                         "apt-get install libopengl0), or use the numpy back end",
                         Location("<gl>", 0, 0))


def _load_library() -> ctypes.CDLL:
    errors = []
    for name in _LIBRARIES:
        path = ctypes.util.find_library(name) if "." not in name else name
        if not path:
            continue
        try:
            return ctypes.CDLL(path)
        except OSError as exc:
            errors.append(f"{name}: {exc}")
    raise RawGLUnavailable("no OpenGL library found (" + "; ".join(errors or ["none of "
                           + ", ".join(_LIBRARIES)]) + ")")


class RawGL:
    """Attribute access to the GL functions in `_SIGNATURES` (`gl.glEnable(gl.BLEND)`), plus
    the module's enum constants."""

    def __init__(self) -> None:
        self._lib = _load_library()
        for name, args in _SIGNATURES.items():
            try:
                fn = getattr(self._lib, name)
            except AttributeError:
                raise RawGLUnavailable(f"the GL library lacks {name}") from None
            fn.argtypes = list(args)
            fn.restype = _RETURNS.get(name)
            setattr(self, name, fn)

    def __getattr__(self, name: str) -> Any:
        # Enum constants: gl.DEPTH_TEST and so on.
        if name.isupper() or name[:1].isdigit():
            try:
                return globals()[name]
            except KeyError:
                pass
        raise AttributeError(name)

    # -- object helpers
    def gen(self, kind: str) -> int:
        """A new object name: kind is 'Textures', 'Samplers', 'Framebuffers' or 'Renderbuffers'."""
        out = c_uint(0)
        getattr(self, f"glGen{kind}")(1, ctypes.byref(out))
        return int(out.value)

    def delete(self, kind: str, name: int) -> None:
        getattr(self, f"glDelete{kind}")(1, ctypes.byref(c_uint(name)))

    def sampler_color(self, sampler: int, pname: int, rgba) -> None:
        values = (c_float * 4)(*(float(v) for v in rgba))
        self.glSamplerParameterfv(sampler, pname, values)

    def set_enabled(self, cap: int, on: bool) -> None:
        (self.glEnable if on else self.glDisable)(cap)

    def check(self, what: str) -> None:
        """Raise RuntimeError if GL recorded an error (a bug in this back end)."""
        code = self.glGetError()
        if code != NO_ERROR:
            raise RuntimeError(f"GL error 0x{code:04X} after {what}")


_INSTANCE: RawGL | None = None


def raw_gl() -> RawGL:
    """The process-wide table (the functions dispatch to the current context)."""
    global _INSTANCE
    if _INSTANCE is None:
        _INSTANCE = RawGL()
    return _INSTANCE
