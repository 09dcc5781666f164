"""A back end that draws a pass with MojoShader's GLSL translation of its shaders' bytecode
(what FNA and MonoGame's OpenGL path draw with) instead of the GL back end's own GLSL, on the
same headless context, with the same textures, sampler objects, render state, streams and
constant values: the picture shows whether a real consumer of our bytecode draws what we draw.

What MojoShader's GLSL leaves to its host is done here, as MojoShader's own GL layer and its
hosts do (facts from its output and mojoshader.h, hg 1314):
- uniforms: one `vs_uniforms_vec4` / `ps_uniforms_vec4` array each, packed in the order of
  MOJOSHADER_parseData.uniforms (register `index`, `array_count` registers or one), filled
  from the pass's constant registers (the host's `vs_c#` / `ps_c#` values);
- samplers `ps_s#` / `vs_s#`: the texture unit the GL back end binds sampler # to;
- attributes `vs_v#`: the stream their dcl usage names (`input_name`), D3D's default where
  the scene supplies none;
- `vposFlip` (ps_3_0 vPos): (1, 0), since GL's row r is D3D's row r here;
- clip space: the hg-1314 vertex shader leaves oPos in Direct3D's clip space (its GL layer's
  later `vpFlip`/`posFixup` are not in this revision), so its `main` is renamed and wrapped
  by one doing what backends/gl/glsl.py's vertex epilogue does: the half-pixel shift, y flip
  and z to GL's range, and D3D's saturation of oD0/oD1 below vs_3_0.
A pass with a vertex shader and fixed-function pixel stages draws MojoShader's vertex shader
with the GL back end's fragment shader: the translation's output #defines (`vs_oT0
gl_TexCoord[0]`) are pointed at the back end's varyings instead (`vary_texcoord0`).
"""
from __future__ import annotations

import re
from typing import Mapping

import moderngl
import numpy as np

from backends.gl import glsl
from backends.gl import rawgl as G
from backends.gl.state import apply_render_state
from backends.gl.renderer import GLBackend, GLShaderError, _numbered, _sampler_units, \
    _stream_array, fragment_options
from effects.program.backend import DrawError, triangle_list
from effects.host.runtime import Runtime, validate_technique
from effects.program.passprogram import PassProgram
from effects.shaders.asm.lower import input_name
from effects.shaders.d3dbc import write_shader
from tests.shaders.d3dbc import mojoshader

# D3D's value of a vertex input no stream feeds (backends/gl/glsl.py VARYING_DEFAULTS).
INPUT_DEFAULTS = {"color0": (1.0, 1.0, 1.0, 1.0), "color1": (0.0, 0.0, 0.0, 0.0)}
# The texture kinds MojoShader's sampler map has (MOJOSHADER_samplerType).
_MOJO_KINDS = ("2d", "cube", "3d")
# vs_3_0 texldl s0-s3 are the pass's vertex samplers 257-260 (D3DVERTEXTEXTURESAMPLER0).
VERTEX_SAMPLER0 = 257
# The GLSL 1.10 built-in each vs_1_1-vs_2_x output register is #defined to, and the GL back
# end's varying of the same D3D output (for the fixed-function pixel stages).
_BUILTIN_VARYINGS = {"gl_FrontColor": "color0", "gl_FrontSecondaryColor": "color1",
                     **{f"gl_TexCoord[{n}]": f"texcoord{n}" for n in range(8)}}


class NotDrawable(Exception):
    """A pass MojoShader cannot draw as the pass says (its translation failed, or the pass
    needs what its GLSL does not do): the reason, for the test's report."""


def _wrapped_vertex(text: str, clamp_colors: bool) -> str:
    if text.count("void main()") != 1:
        raise NotDrawable("the vertex translation has no single main()")
    body = text.replace("void main()", "void mojoshader_main()")
    # by the registers' names: the #defines may point them at other varyings
    clamps = "".join(f"\t{name} = clamp({name}, 0.0, 1.0);\n" for name in ("vs_oD0", "vs_oD1")
                     if clamp_colors and f"#define {name} " in text)
    return body + (
        "uniform vec2 d3d_pixel_size;\n"
        "void main()\n{\n\tmojoshader_main();\n" + clamps +
        "\tvec4 p = gl_Position;\n"
        "\tgl_Position = vec4(p.x + 0.5 * d3d_pixel_size.x * p.w,\n"
        "\t                   -(p.y - 0.5 * d3d_pixel_size.y * p.w), 2.0 * p.z - p.w, p.w);\n"
        "}\n")


def _to_backend_varyings(text: str) -> str:
    """MojoShader's vertex translation with its output #defines pointed at the GL back end's
    varyings (for its fixed-function fragment shader)."""
    declared = []

    def redirect(match: re.Match) -> str:
        register, builtin = match.group(1), match.group(2)
        name = _BUILTIN_VARYINGS.get(builtin)
        if name is None:
            return match.group(0)
        declared.append(glsl.varying_name(name))
        return f"#define {register} {glsl.varying_name(name)}"

    text = re.sub(r"^#define (vs_o\w+) (gl_\w+(?:\[\d\])?)$", redirect, text, flags=re.M)
    lines = text.split("\n")
    lines[1:1] = [f"varying vec4 {name};" for name in declared]
    return "\n".join(lines)


def uniform_slots(translation: mojoshader.Translation, kind: str = "float") -> dict[int, int]:
    """Register -> element of the packed uniform array, in parseData.uniforms' order."""
    slots, k = {}, 0
    for utype, register, count, constant, _ in translation.uniforms:
        if utype != kind or constant:
            continue
        for r in range(max(count, 1)):
            slots[register + r] = k + r
        k += max(count, 1)
    return slots


class MojoShaderBackend(GLBackend):
    """Draws each pass that `MojoRuntime.lower` made with MojoShader's translation of that
    pass's shaders; any other draw (a script's picture copy, a fixed-function pass) with the
    GL back end's own GLSL, counted in `own_draws`."""

    name = "mojoshader"

    def __init__(self, lib) -> None:
        super().__init__()
        self.lib = lib
        self._shaders: dict[int, tuple] = {}
        self._translations: dict[tuple, mojoshader.Translation] = {}
        self._mojo_programs: dict[tuple, moderngl.Program] = {}
        self.sources: list[tuple[str, str]] = []       # (vertex, fragment) GLSL of each draw
        self.own_draws = 0

    def bind(self, program: PassProgram, shaders: Mapping[str, object]) -> None:
        """The shaders (by state name) the pass `program` was lowered from."""
        self._shaders[id(program)] = (program, shaders.get("VertexShader"),
                                      shaders.get("PixelShader"))

    def translation(self, shader, sampler_types: Mapping[int, str] | None = None
                    ) -> mojoshader.Translation:
        """MojoShader's translation; `sampler_types` (ps_1_x, whose bytecode declares none):
        the kind of texture the pass binds to each sampler, as a host passes them."""
        data = write_shader(shader.program, shader.compiled)
        types = tuple(sorted((sampler_types or {}).items()))
        found = self._translations.get((data, types))
        if found is None:
            found = self._translations[(data, types)] = mojoshader.translate(
                self.lib, data, "glsl", dict(types))
        if found.errors:
            raise NotDrawable(f"{shader.program.name}: MojoShader: {found.errors[0]}")
        return found

    def draw(self, program: PassProgram, streams: Mapping[str, np.ndarray], indices: np.ndarray,
             primitive: str, textures: Mapping[str, object]) -> None:
        found = self._shaders.get(id(program))
        if found is None or found[0] is not program or found[1] is None:
            # not a pass of the technique, or a fixed-function vertex pipeline (no bytecode)
            self.own_draws += 1
            return super().draw(program, streams, indices, primitive, textures)
        _, vertex, pixel = found
        target = self._require_frame()
        options = fragment_options(program, False)
        if options != glsl.FragmentOptions() and pixel is not None:
            raise NotDrawable(f"the pass needs the fixed-function epilogue {options}")
        tris = triangle_list(indices, primitive)
        if len(tris) == 0:
            return
        kinds = {s.index: s.kind for p in (program.vertex, program.fragment) for s in p.samplers}
        vs = self.translation(vertex)
        ps = None
        if pixel is not None:
            declared = pixel.program.version >= (2, 0)
            ps = self.translation(pixel, None if declared else {
                i: k for i, k in kinds.items() if i < VERTEX_SAMPLER0 and k in _MOJO_KINDS})
        vertex_text = _wrapped_vertex(vs.text, vertex.program.version < (3, 0))
        if ps is None:
            vertex_text = _to_backend_varyings(vertex_text)
            fragment_text = glsl.fragment_shader(program.fragment, options)
        else:
            fragment_text = ps.text
        shader = self._mojo_program(vertex_text, fragment_text)
        self.sources.append((vertex_text, fragment_text))
        values = dict(program.uniforms)
        self._fill_uniforms(shader, "vs", vs, values)
        if ps is not None:
            self._fill_uniforms(shader, "ps", ps, values)
            if shader.get("vposFlip", None) is not None:
                shader["vposFlip"].value = (1.0, 0.0)
        else:
            self._set_uniforms(shader, program, target, options)
        shader["d3d_pixel_size"].value = (2.0 / target.size[0], 2.0 / target.size[1])
        self._bind_textures(shader, program, textures)
        units = _sampler_units(program)
        for stage, translation, base in (("ps", ps, 0), ("vs", vs, VERTEX_SAMPLER0)):
            for stype, register, name in (translation.samplers if translation else ()):
                index = base + register
                if index not in units or shader.get(name, None) is None:
                    continue
                if kinds[index] != stype:
                    raise NotDrawable(f"{name}: MojoShader declares a {stype} sampler, the pass "
                                      f"samples a {kinds[index]} texture")
                shader[name].value = units[index]
        count = len(next(iter(streams.values())))
        content = []
        for usage, index, name in vs.attributes:
            if shader.get(name, None) is None:
                continue
            stream = input_name(usage, index)
            array = _stream_array(streams[stream]) if stream in streams else np.tile(
                np.array(INPUT_DEFAULTS.get(stream, (0.0, 0.0, 0.0, 1.0)), np.float32),
                (count, 1))
            content.append((self._fill(stream, array), f"{array.shape[1]}f", name))
        index_buffer = self._fill(" indices", tris.astype(np.uint32))
        vao = self.ctx.vertex_array(shader, content, index_buffer=index_buffer,
                                    index_element_size=4, skip_errors=True)
        try:
            gl = self.gl
            gl.glBindFramebuffer(G.FRAMEBUFFER, target.framebuffer)
            gl.glViewport(0, 0, *target.size)
            gl.glProvokingVertex(G.FIRST_VERTEX_CONVENTION)
            gl.glDisable(G.TEXTURE_CUBE_MAP_SEAMLESS)
            apply_render_state(gl, program.render_state)
            vao.render(moderngl.TRIANGLES, vertices=tris.size)
            gl.check("drawing MojoShader's translation")
        finally:
            vao.release()
            self._leave_state(sorted(units.values()))

    def _mojo_program(self, vertex_text: str, fragment_text: str) -> moderngl.Program:
        key = (vertex_text, fragment_text)
        shader = self._mojo_programs.get(key)
        if shader is None:
            try:
                shader = self.ctx.program(vertex_shader=vertex_text,
                                          fragment_shader=fragment_text)
            except moderngl.Error as exc:
                raise GLShaderError(f"{exc}\n--- vertex ---\n{_numbered(vertex_text)}"
                                    f"--- fragment ---\n{_numbered(fragment_text)}") from exc
            self._mojo_programs[key] = shader
        return shader

    @staticmethod
    def _fill_uniforms(shader: moderngl.Program, stage: str,
                       translation: mojoshader.Translation, values: Mapping) -> None:
        if any(u[0] != "float" for u in translation.uniforms):
            raise NotDrawable(f"{stage}: int/bool uniforms are not bound by this test")
        uniform = shader.get(f"{stage}_uniforms_vec4", None)
        if uniform is None:
            return
        data = np.zeros((uniform.array_length, 4), np.float32)
        for register, slot in uniform_slots(translation).items():
            if slot < len(data):
                data[slot] = values.get(f"{stage}_c{register}", (0.0, 0.0, 0.0, 0.0))
        uniform.write(data.tobytes())

    def close(self) -> None:
        for shader in self._mojo_programs.values():
            shader.release()
        self._mojo_programs.clear()
        super().close()


class MojoRuntime(Runtime):
    """A runtime whose lowered passes tell its MojoShaderBackend the shaders the card's
    validation judged for them (scripts included: they lower through here too)."""

    def __init__(self, effect, profile, *, backend: MojoShaderBackend, **kw) -> None:
        super().__init__(effect, profile, backend=backend, **kw)
        self._reports: dict[int, tuple] = {}

    def lower(self, technique, index, host=None):
        program = super().lower(technique, index, host)
        found = self._reports.get(id(technique))
        if found is None or found[0] is not technique:
            reports = validate_technique(self.effect, technique, self.profile).pass_reports
            found = self._reports[id(technique)] = (technique, reports)
        self.backend.bind(program, found[1][index].shaders)
        return program
