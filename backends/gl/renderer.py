"""The GL back end: lowered passes drawn with moderngl into an offscreen framebuffer.

Each draw prints the pass's IR as GLSL (`glsl`), compiles it once per (vertex key, fragment
key, fixed-function epilogue, stream set) so that changed uniforms never recompile, binds
textures and sampler objects (`textures`, `state`), sets the render state and draws the
triangles in `effects.program.backend.triangle_list` order (so flat shading takes the same provoking
vertex as the reference). The frame is a framebuffer object with a packed 32-bit float depth
and 8-bit stencil buffer; `end_frame` reads it back, row 0 at the top, without a flip (the
vertex shader renders upside down; see `glsl`).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping

import moderngl
import numpy as np

from effects.program.passprogram import PassProgram, RenderState

from effects.program.backend import DrawError, register_backend, triangle_list
from effects.program.formats import TARGET_FORMATS
from backends.gl import glsl
from backends.gl import rawgl as G
from backends.gl.context import headless_context
from backends.gl.rawgl import raw_gl
from backends.gl.state import apply_render_state, create_sampler, reset_for_clear, sampler_key
from backends.gl.textures import TextureCache, TextureKindError

# Render-target format -> (GL internal format, read-back type, numpy dtype)
TARGET_GL_FORMATS = {
    "A8R8G8B8": (G.RGBA8, G.UNSIGNED_BYTE, np.uint8),
    "X8R8G8B8": (G.RGB8, G.UNSIGNED_BYTE, np.uint8),
    "R16F": (G.R16F, G.FLOAT, np.float32),
    "G16R16F": (G.RG16F, G.FLOAT, np.float32),
    "R32F": (G.R32F, G.FLOAT, np.float32),
    "G32R32F": (G.RG32F, G.FLOAT, np.float32),
    "A16B16G16R16F": (G.RGBA16F, G.FLOAT, np.float32),
    "A32B32G32R32F": (G.RGBA32F, G.FLOAT, np.float32),
}


class GLShaderError(RuntimeError):
    """Printed GLSL that the driver rejected: a bug in this back end, shown with its source."""


@dataclass
class _Target:
    """An offscreen render target: colour texture, depth-stencil renderbuffer, framebuffer."""

    size: tuple[int, int]
    format: str
    color: int
    depth_stencil: int
    framebuffer: int


class GLBackend:
    """The moderngl renderer. `context`: a moderngl context to draw with (the viewer passes
    its window's, see `context.window_context`); by default the process's headless EGL one.
    Calls must come from the thread on which that context is current (the headless one is
    made current on its thread when created)."""

    name = "gl"

    def __init__(self, context: moderngl.Context | None = None) -> None:
        self.ctx = context if context is not None else headless_context()
        # A context of our own is made current at each frame: another headless context made
        # (and released) in the same process since would otherwise receive our GL calls.
        self._owns_context = context is None
        self.gl = raw_gl()
        self.textures = TextureCache(self.gl)
        self._programs: dict[tuple, moderngl.Program] = {}
        # Program.key() prints and hashes the whole IR: remember it per Program object (kept
        # alive here, so its id is not reused; lowering hands back the same objects).
        self._ir_keys: dict[int, tuple[object, str]] = {}
        # Per-draw work that repeats frame after frame, kept between draws:
        # uniform values per (pass, shader, target size), and which ones a shader last got;
        self._uniform_plans: dict[tuple, tuple[PassProgram, list]] = {}
        self._uniforms_in: dict[int, list] = {}
        # vertex and index buffers per stream name (refilled each draw), and vertex arrays.
        self._buffers: dict[str, moderngl.Buffer] = {}
        self._vaos: dict[tuple, moderngl.VertexArray] = {}
        self._samplers: dict = {}
        self._targets: dict[tuple[tuple[int, int], str], _Target] = {}
        self._frame: _Target | None = None
        self.compiles = 0

    # -- frame
    def begin_frame(self, size: tuple[int, int], clear_color=(0.0, 0.0, 0.0, 0.0),
                    clear_depth: float = 1.0, clear_stencil: int = 0, *,
                    format: str = "A8R8G8B8") -> None:
        size = (int(size[0]), int(size[1]))
        if format not in TARGET_GL_FORMATS:
            raise DrawError(f"render-target format must be one of {tuple(TARGET_GL_FORMATS)}, "
                            f"got {format!r}")
        if size[0] <= 0 or size[1] <= 0:
            raise DrawError(f"render-target size must be positive, got {size}")
        if self._owns_context:
            self.ctx.__enter__()
        gl = self.gl
        target = self._target(size, format)
        gl.glBindFramebuffer(G.FRAMEBUFFER, target.framebuffer)
        gl.glViewport(0, 0, *size)
        reset_for_clear(gl)
        gl.glClearColor(*(float(c) for c in clear_color))
        gl.glClearDepth(float(clear_depth))
        gl.glClearStencil(int(clear_stencil) & 0xFF)
        gl.glClear(G.COLOR_BUFFER_BIT | G.DEPTH_BUFFER_BIT | G.STENCIL_BUFFER_BIT)
        gl.check("clearing the frame")
        self._frame = target

    def reset_shared_state(self) -> None:
        """Undo what a draw leaves bound that moderngl does not track, for a caller that draws
        with the same context (the viewer's panel and blit): sampler objects on the texture
        units (they would override the caller's sampling), stencil, scissor, polygon mode and
        write masks. Depth, blend and cull are moderngl's own (`ctx.enable_only`)."""
        gl = self.gl
        for unit in range(16):
            gl.glBindSampler(unit, 0)
        gl.glDisable(G.STENCIL_TEST)
        gl.glDisable(G.SCISSOR_TEST)
        gl.glPolygonMode(G.FRONT_AND_BACK, G.FILL)
        gl.glColorMask(True, True, True, True)
        gl.glDepthMask(True)
        gl.glActiveTexture(G.TEXTURE0)

    def end_frame(self) -> np.ndarray:
        """The frame: uint8 RGBA for the 8-bit formats, float32 RGBA for the float ones
        (channels the format lacks read 1), row 0 at the top."""
        target = self._require_frame()
        width, height = target.size
        _, read_type, dtype = TARGET_GL_FORMATS[target.format]
        image = np.empty((height, width, 4), dtype)
        self.gl.glBindFramebuffer(G.FRAMEBUFFER, target.framebuffer)
        self.gl.glPixelStorei(G.PACK_ALIGNMENT, 4)
        self.gl.glReadPixels(0, 0, width, height, G.RGBA, read_type, image.ctypes.data)
        self.gl.check("reading the frame back")
        is_float, channels = TARGET_FORMATS[target.format]
        if is_float:
            image[..., channels:] = 1  # GL reads absent channels as 0 (alpha 1); D3D as 1
        self._frame = None
        return image

    def _require_frame(self) -> _Target:
        if self._frame is None:
            raise DrawError("no frame: call begin_frame first")
        return self._frame

    def _target(self, size: tuple[int, int], format: str) -> _Target:
        key = (size, format)
        if key not in self._targets:
            self._targets[key] = self._create_target(size, format)
        return self._targets[key]

    def _create_target(self, size: tuple[int, int], format: str) -> _Target:
        gl = self.gl
        width, height = size
        color = gl.gen("Textures")
        gl.glBindTexture(G.TEXTURE_2D, color)
        gl.glTexImage2D(G.TEXTURE_2D, 0, TARGET_GL_FORMATS[format][0], width, height, 0, G.RGBA,
                        G.FLOAT, None)
        gl.glTexParameteri(G.TEXTURE_2D, G.TEXTURE_MAX_LEVEL, 0)
        depth = gl.gen("Renderbuffers")
        gl.glBindRenderbuffer(G.RENDERBUFFER, depth)
        gl.glRenderbufferStorage(G.RENDERBUFFER, G.DEPTH32F_STENCIL8, width, height)
        framebuffer = gl.gen("Framebuffers")
        gl.glBindFramebuffer(G.FRAMEBUFFER, framebuffer)
        gl.glFramebufferTexture2D(G.FRAMEBUFFER, G.COLOR_ATTACHMENT0, G.TEXTURE_2D, color, 0)
        gl.glFramebufferRenderbuffer(G.FRAMEBUFFER, G.DEPTH_STENCIL_ATTACHMENT, G.RENDERBUFFER,
                                     depth)
        status = gl.glCheckFramebufferStatus(G.FRAMEBUFFER)
        if status != G.FRAMEBUFFER_COMPLETE:
            raise RuntimeError(f"a {format} {width}x{height} framebuffer is incomplete on this "
                               f"GL (status 0x{status:04X})")
        gl.check("creating a render target")
        return _Target(size, format, color, depth, framebuffer)

    # -- drawing
    def draw(self, program: PassProgram, streams: Mapping[str, np.ndarray], indices: np.ndarray,
             primitive: str, textures: Mapping[str, object]) -> None:
        target = self._require_frame()
        tris = triangle_list(indices, primitive)
        count = _vertex_count(streams)
        if len(tris) and (tris.min() < 0 or tris.max() >= count):
            raise DrawError(f"indices out of range for {count} vertices")
        if len(tris) == 0:
            return
        state = program.render_state
        options = fragment_options(program, TARGET_FORMATS[target.format][0])
        varyings = glsl.fragment_varyings(program.fragment, options)
        attributes = _attributes(program, varyings)
        present = frozenset(a for a in attributes if a in streams)
        shader = self._program(program, options, varyings, present)
        self._set_uniforms(shader, program, target, options)
        self._bind_textures(shader, program, textures)
        arrays = {a: _stream_array(streams[a]) for a in sorted(present)}
        content = [(self._fill(a, array), f"{array.shape[1]}f", glsl.attribute_name(a))
                   for a, array in arrays.items()]
        index_buffer = self._fill(" indices", tris.astype(np.uint32))
        vao_key = (shader.glo, index_buffer.glo, tuple((b.glo, f, n) for b, f, n in content))
        vao = self._vaos.get(vao_key)
        if vao is None:
            vao = self._vaos[vao_key] = self.ctx.vertex_array(
                shader, content, index_buffer=index_buffer, index_element_size=4,
                skip_errors=True)
        try:
            gl = self.gl
            gl.glBindFramebuffer(G.FRAMEBUFFER, target.framebuffer)
            gl.glViewport(0, 0, *target.size)
            gl.glProvokingVertex(G.FIRST_VERTEX_CONVENTION)
            gl.glDisable(G.TEXTURE_CUBE_MAP_SEAMLESS)  # D3D9 cube maps are not seamless
            apply_render_state(gl, state)
            vao.render(moderngl.TRIANGLES, vertices=tris.size)
            gl.check("drawing")
        finally:
            self._leave_state(sorted(_sampler_units(program).values()))

    def _fill(self, name: str, array: np.ndarray) -> moderngl.Buffer:
        """The buffer kept for `name`, given fresh storage (orphaned, so a draw still using
        the old contents never waits) holding `array`; a new one when the size changes."""
        data = np.ascontiguousarray(array)
        buffer = self._buffers.get(name)
        if buffer is None or buffer.size != data.nbytes:
            if buffer is not None:
                self._release_vaos(buffer.glo)
                buffer.release()
            buffer = self._buffers[name] = self.ctx.buffer(data)
        else:
            buffer.orphan()
            buffer.write(data)
        return buffer

    def _release_vaos(self, glo: int | None = None) -> None:
        """Release the vertex arrays that use buffer or program `glo` (all when None)."""
        for key in [k for k in self._vaos if glo is None or glo == k[0] or glo == k[1]
                    or any(glo == b for b, _, _ in k[2])]:
            self._vaos.pop(key).release()

    def _leave_state(self, units: list[int]) -> None:
        """Put back what moderngl does not track, so a shared (window) context draws on as
        before: no sampler objects on the units used, stencil off, solid fill, full masks,
        and moderngl's current framebuffer bound again. Depth, blend and cull stay as the
        pass set them (moderngl's `enable`/`enable_only` set those)."""
        gl = self.gl
        for unit in units:
            gl.glBindSampler(unit, 0)
        gl.glActiveTexture(G.TEXTURE0)
        gl.glDisable(G.STENCIL_TEST)
        gl.glPolygonMode(G.FRONT_AND_BACK, G.FILL)
        gl.glColorMask(True, True, True, True)
        gl.glDepthMask(True)
        if self.ctx.fbo is not None:
            self.ctx.fbo.use()

    def _program(self, program: PassProgram, options: glsl.FragmentOptions,
                 varyings: tuple[str, ...], present: frozenset) -> moderngl.Program:
        vertex = program.vertex
        key = (None if vertex is None else self._ir_key(vertex), self._ir_key(program.fragment),
               options, varyings, present)
        shader = self._programs.get(key)
        if shader is None:
            vertex_text = glsl.vertex_shader(vertex, varyings, present, options.flat_colors)
            fragment_text = glsl.fragment_shader(program.fragment, options)
            try:
                shader = self.ctx.program(vertex_shader=vertex_text,
                                          fragment_shader=fragment_text)
            except moderngl.Error as exc:
                raise GLShaderError(f"{exc}\n--- vertex shader ---\n{_numbered(vertex_text)}"
                                    f"--- fragment shader ---\n{_numbered(fragment_text)}") from exc
            self._programs[key] = shader
            self.compiles += 1
        return shader

    def _ir_key(self, ir: object) -> str:
        found = self._ir_keys.get(id(ir))
        if found is None:
            if len(self._ir_keys) > 4096:   # bounded: a viewer edits for hours
                self._ir_keys.clear()
            found = self._ir_keys[id(ir)] = (ir, ir.key())
        return found[1]

    def _set_uniforms(self, shader: moderngl.Program, program: PassProgram, target: _Target,
                      options: glsl.FragmentOptions) -> None:
        key = (id(program), shader.glo, target.size, options)
        found = self._uniform_plans.get(key)
        if found is None or found[0] is not program:
            if len(self._uniform_plans) > 4096:
                self._uniform_plans.clear()
            found = self._uniform_plans[key] = (program, self._uniform_plan(shader, program,
                                                                            target, options))
        plan = found[1]
        if self._uniforms_in.get(shader.glo) is plan:
            return  # this shader already holds exactly these values
        for uniform, value in plan:
            uniform.value = value
        self._uniforms_in[shader.glo] = plan

    @staticmethod
    def _uniform_plan(shader: moderngl.Program, program: PassProgram, target: _Target,
                      options: glsl.FragmentOptions) -> list:
        """(moderngl uniform, value) for every uniform the shader declares."""
        values = dict(program.uniforms)
        state = program.render_state
        settings: dict[str, object] = {
            "d3d_pixel_size": (2.0 / target.size[0], 2.0 / target.size[1]),
            "d3d_depth_bias": (float(state.depth_bias), float(state.slope_scale_depth_bias)),
            "d3d_alpha_ref": int(state.alpha_ref) & 0xFF,
        }
        if options.alpha_test:
            settings["d3d_alpha_func"] = _compare_index(state)
        for name in glsl.uniforms_of(program.vertex, program.fragment):
            # A uniform the pass does not supply reads 0, as in the reference back end.
            settings[glsl.uniform_name(name)] = tuple(float(v) for v in
                                                      values.get(name, (0.0, 0.0, 0.0, 0.0)))
        return [(shader.get(name, None), value) for name, value in settings.items()
                if shader.get(name, None) is not None]

    def _bind_textures(self, shader: moderngl.Program, program: PassProgram,
                       textures: Mapping[str, object]) -> None:
        gl = self.gl
        used = {s.index: s.kind for p in (program.vertex, program.fragment) if p is not None
                for s in p.samplers}
        units = _sampler_units(program)
        # Upload first: an upload binds its texture, which must not displace the ones bound
        # to the units below.
        resolved = [(index, *self._texture_for(program, index, kind, textures))
                    for index, kind in sorted(used.items())]
        for index, gl_texture, key in resolved:
            sampler = self._samplers.get(key)
            if sampler is None:
                sampler = self._samplers[key] = create_sampler(gl, key)
            unit = units[index]
            gl.glActiveTexture(G.TEXTURE0 + unit)
            gl.glBindTexture(gl_texture.target, gl_texture.name)
            gl.glTexParameteri(gl_texture.target, G.TEXTURE_BASE_LEVEL, key.base_level)
            gl.glBindSampler(unit, sampler)
            uniform = shader.get(f"sampler{index}", None)
            if uniform is not None:
                uniform.value = unit
        gl.glActiveTexture(G.TEXTURE0)

    def _texture_for(self, program: PassProgram, index: int, kind: str,
                     textures: Mapping[str, object]):
        """(GL texture, sampler key) for a sampler slot: the bound texture, or the (0, 0, 0, 1)
        texture of an empty slot with the default sampler states."""
        binding = program.texture(index)
        texture = None
        if binding is not None and binding.texture is not None:
            texture = textures.get(binding.texture)
        try:
            if texture is None:
                gl_texture = self.textures.unbound(kind)
                binding = None
            else:
                gl_texture = self.textures.get(texture, kind, binding.srgb_texture)
        except TextureKindError as exc:
            raise DrawError(f"sampler {index}: {exc}") from None
        return gl_texture, sampler_key(binding, kind, gl_texture.level_count)

    # -- lifetime
    def close(self) -> None:
        """Release every GL object this back end made (the context stays)."""
        gl = self.gl
        self._release_vaos()
        for buffer in self._buffers.values():
            buffer.release()
        self._buffers.clear()
        for shader in self._programs.values():
            shader.release()
        for sampler in self._samplers.values():
            gl.delete("Samplers", sampler)
        for target in self._targets.values():
            gl.delete("Framebuffers", target.framebuffer)
            gl.delete("Renderbuffers", target.depth_stencil)
            gl.delete("Textures", target.color)
        self.textures.release()
        self._programs.clear()
        self._ir_keys.clear()
        self._uniform_plans.clear()
        self._uniforms_in.clear()
        self._samplers.clear()
        self._targets.clear()
        self._frame = None


def fragment_options(program: PassProgram, float_target: bool) -> glsl.FragmentOptions:
    """The fixed-function epilogue a pass needs, from its render state (sRGB writes apply to
    8-bit targets, as in the reference back end)."""
    state: RenderState = program.render_state
    return glsl.FragmentOptions(
        flat_colors=state.shade_mode == "FLAT",
        alpha_test=bool(state.alpha_test_enable),
        depth_bias=bool(state.depth_bias or state.slope_scale_depth_bias),
        srgb_write=bool(state.srgb_write_enable and not float_target))


def _sampler_units(program: PassProgram) -> dict[int, int]:
    """Sampler index -> GL texture unit. A pixel sampler n keeps unit n; other slots (the
    vertex program's, 257 and up) take the units after the highest pixel one, in order, so
    both stages' samplers fit GL's combined units."""
    fragment = sorted({s.index for s in program.fragment.samplers})
    others = sorted({s.index for s in program.vertex.samplers} - set(fragment)
                    if program.vertex is not None else ())
    units = {index: index for index in fragment}
    first = max(fragment, default=-1) + 1
    units.update({index: first + k for k, index in enumerate(others)})
    return units


def _compare_index(state: RenderState) -> int:
    try:
        return glsl.COMPARE_FUNCS.index(state.alpha_func)
    except ValueError:
        raise DrawError(f"AlphaFunc must be one of {glsl.COMPARE_FUNCS}, "
                        f"got {state.alpha_func!r}") from None


def _attributes(program: PassProgram, varyings: tuple[str, ...]) -> list[str]:
    """The vertex streams the vertex shader reads."""
    if program.vertex is None:
        return ["position", *(n for n in varyings if n != "position")]
    return [i.name for i in program.vertex.inputs if i.kind == "varying"]


def _vertex_count(streams: Mapping[str, np.ndarray]) -> int:
    if "position" not in streams:
        raise DrawError("streams need a 'position'")
    counts = {name: len(np.asarray(v)) for name, v in streams.items()}
    if len(set(counts.values())) > 1:
        raise DrawError(f"streams disagree on the vertex count: {counts}")
    return counts["position"]


def _stream_array(value: np.ndarray) -> np.ndarray:
    a = np.asarray(value, np.float32)
    if a.ndim == 1:
        a = a[:, None]
    if a.ndim != 2 or not 1 <= a.shape[1] <= 4:
        raise DrawError(f"a vertex stream must be (N, 1..4), got {np.shape(value)}")
    return np.ascontiguousarray(a)


def _numbered(text: str) -> str:
    return "".join(f"{n:4d}  {line}\n" for n, line in enumerate(text.splitlines(), 1))


register_backend("gl", GLBackend)
