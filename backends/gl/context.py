"""OpenGL contexts for the GL back end: a headless EGL one, or the viewer window's own.

A headless context has no default framebuffer; the renderer always draws into its own
framebuffer object, so both kinds serve alike. Failing to get GL is a user-facing problem (a
machine without Mesa), reported as `GLUnavailable`, an `EffectError` that names the packages.
"""
from __future__ import annotations

import moderngl

from effects.base.errors import EffectError, Location

GL_LOCATION = Location("<gl>", 0, 0)
REQUIRED_VERSION = 330
SYSTEM_PACKAGES = "libegl1, libegl-mesa0 and libgl1-mesa-dri"

_headless: moderngl.Context | None = None


class GLUnavailable(EffectError):
    """No usable OpenGL 3.3 context (no EGL/Mesa, or too old a driver)."""


def headless_context() -> moderngl.Context:
    """The process's headless OpenGL context (EGL, no display needed), made on first use."""
    global _headless
    if _headless is None:
        try:
            _headless = moderngl.create_standalone_context(backend="egl",
                                                           require=REQUIRED_VERSION)
        except Exception as exc:  # moderngl raises plain Exceptions for every EGL failure
            raise GLUnavailable(
                f"no headless OpenGL {REQUIRED_VERSION // 100}.{REQUIRED_VERSION // 10 % 10} "
                f"context could be created through EGL ({type(exc).__name__}: {exc}); the GL "
                f"back end needs the system packages {SYSTEM_PACKAGES} (Debian/Ubuntu: "
                f"apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri), or use the numpy "
                f"back end", GL_LOCATION) from exc
    return _headless


def window_context() -> moderngl.Context:
    """The context current on this thread (the viewer's window, e.g. moderngl-window's), so
    the back end renders with the window's context and can share its textures."""
    try:
        return moderngl.create_context(require=REQUIRED_VERSION)
    except Exception as exc:
        raise GLUnavailable(
            f"no current OpenGL {REQUIRED_VERSION // 100}.{REQUIRED_VERSION // 10 % 10} context "
            f"to share ({type(exc).__name__}: {exc}); create the window first, or use a "
            f"headless context", GL_LOCATION) from exc
