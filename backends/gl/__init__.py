"""The GPU back end: IR printed as GLSL 330, Direct3D 9 state set through moderngl.

    from effects.program.backend import create_backend
    backend = create_backend("gl")             # headless EGL context
    backend = GLBackend(window_context())      # the viewer's window context

Modules: `glsl` (the printer), `state` (render and sampler states), `textures` (uploads),
`context` (contexts and the GLUnavailable error), `rawgl` (GL calls moderngl lacks),
`renderer` (the back end, registered as "gl").
"""
from backends.gl.context import GLUnavailable, headless_context, window_context
from backends.gl.renderer import GLBackend, GLShaderError

__all__ = ["GLBackend", "GLShaderError", "GLUnavailable", "headless_context", "window_context"]
