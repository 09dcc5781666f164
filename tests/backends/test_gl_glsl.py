"""The IR -> GLSL 330 printer of the GL back end: golden shader text, `#line` mapping to the
printed IR, and every printed shader compiling on the machine's GL.

Golden files live in tests/golden/glsl/. After an intended change of the printer, regenerate
them with `EFFECTS_UPDATE_GOLDEN=1 .venv/bin/python -m pytest tests/backends/test_gl_glsl.py` and read
the diff before committing it.
"""
from __future__ import annotations

from tests.paths import TESTS

import os
import re

import pytest

from backends.gl import glsl
from backends.gl.context import headless_context
from effects.program.ir import Builder, IRError, Program, format_program

GOLDEN_DIR = TESTS / "golden" / "glsl"
UPDATE_GOLDEN = os.environ.get("EFFECTS_UPDATE_GOLDEN") == "1"


# --------------------------------------------------------------------------------------------
# Hand-built programs


def per_pixel_n_dot_l() -> Program:
    """ps.2.0 style: normalised interpolated normal . light direction, times the diffuse."""
    b = Builder("fragment")
    n = b.nrm(b.varying("texcoord1", "TEXCOORD1", 3))
    light = b.nrm(b.uniform("LightDirection"))
    diffuse = b.uniform("MaterialDiffuse")
    lit = b.mul(b.saturate(b.dp3(n, light)), diffuse)
    b.output("color0", b.merge(lit, diffuse, "w"))
    return b.build()


def ps11_style() -> Program:
    """ps.1.1 style: fixed-point values clamped to [-1, 1] and held on the 9-bit signed grid
    after every arithmetic instruction; texkill on xyz; cnd on r0.a."""
    b = Builder("fragment")

    def fixed(value: int) -> int:
        return b.quantize(b.clamp(value, -1.0, 1.0), bits=9, signed=True)

    t0 = b.sample(0, b.varying("texcoord0", "TEXCOORD0", 2))
    t1 = b.sample(1, b.varying("texcoord1", "TEXCOORD1", 2))
    b.kill(b.varying("texcoord2", "TEXCOORD2", 3), "xyz")
    v0 = b.varying("color0", "COLOR0")
    n = fixed(b.mad(t0, b.const(2.0), b.const(-1.0)))             # t0_bx2
    l = fixed(b.mad(v0, b.const(2.0), b.const(-1.0)))             # v0_bx2
    r0 = fixed(b.dp3(n, l))
    r1 = fixed(b.mul(r0, t1))
    r0a = b.swizzle(r0, "wwww")
    out = fixed(b.cnd(r0a, r1, b.lrp(v0, t1, b.uniform("c0"))))
    b.output("color0", out)
    return b.build()


def every_sample_variant() -> Program:
    """One sample of each kind and addressing variant, summed."""
    b = Builder("fragment")
    c = b.varying("texcoord0")
    variants = [
        dict(kind="1d"), dict(kind="1d", proj=True),
        dict(kind="2d"), dict(kind="2d", proj=True), dict(kind="2d", bias=True),
        dict(kind="2d", lod=True),
        dict(kind="3d"), dict(kind="3d", proj=True), dict(kind="3d", lod=True),
        dict(kind="cube"), dict(kind="cube", proj=True), dict(kind="cube", bias=True),
    ]
    total = None
    for index, attrs in enumerate(variants):
        texel = b.sample(index, c, **attrs)
        total = texel if total is None else b.add(total, texel)
    b.output("color0", total)
    return b.build()


def vertex_transform() -> Program:
    """vs.1.1 style: position by four matrix rows, colour and texture coordinate passed on."""
    b = Builder("vertex")
    p = b.varying("position", "POSITION", 3)
    rows = [b.dp4(p, b.uniform(f"WorldViewProjection_c{i}")) for i in range(4)]
    x = b.merge(b.merge(b.merge(rows[0], rows[1], "y"), rows[2], "z"), rows[3], "w")
    b.output("position", x)
    b.output("color0", b.varying("color0", "COLOR0"))
    b.output("texcoord0", b.varying("texcoord0", "TEXCOORD0", 2))
    b.output("fog", b.swizzle(rows[2], "zzzz"))
    return b.build()


FULL_EPILOGUE = glsl.FragmentOptions(flat_colors=True, alpha_test=True, depth_bias=True,
                                     srgb_write=True)


def _shaders() -> dict[str, str]:
    ndotl = per_pixel_n_dot_l()
    ps11 = ps11_style()
    vertex = vertex_transform()
    varyings = glsl.fragment_varyings(ps11, glsl.FragmentOptions())
    return {
        "n_dot_l.frag.glsl": glsl.fragment_shader(ndotl),
        "ps11_quantize.frag.glsl": glsl.fragment_shader(ps11),
        "every_sample.frag.glsl": glsl.fragment_shader(every_sample_variant()),
        "epilogue.frag.glsl": glsl.fragment_shader(ndotl, FULL_EPILOGUE),
        "vertex_transform.vert.glsl": glsl.vertex_shader(
            vertex, ("color0", "texcoord0", "texcoord1"), {"position", "texcoord0"}),
        "pass_through.vert.glsl": glsl.vertex_shader(None, varyings, {"position", "texcoord0",
                                                                      "color0"}, True),
    }


SHADERS = _shaders()


@pytest.mark.parametrize("name", sorted(SHADERS))
def test_golden_glsl(name):
    path = GOLDEN_DIR / name
    text = SHADERS[name]
    if UPDATE_GOLDEN:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    assert path.exists(), f"missing golden file {path} (EFFECTS_UPDATE_GOLDEN=1 writes it)"
    assert text == path.read_text()


# --------------------------------------------------------------------------------------------
# What the text must say


def test_quantize_and_clamp_appear_exactly_where_the_ir_has_them():
    program = ps11_style()
    text = glsl.fragment_shader(program)
    ir_quantizes = sum(1 for i in program.instrs if i.op == "quantize")
    ir_clamps = sum(1 for i in program.instrs if i.op == "clamp")
    # ps11_style wraps each of its 5 arithmetic results once: counted by hand.
    assert ir_quantizes == ir_clamps == 5
    assert len(re.findall(r"= \(sign\(clamp", text)) == 5            # the quantize template
    assert len(re.findall(r"= clamp\(v\d+, -1\.0, 1\.0\);", text)) == 5
    # the 9-bit signed grid: 255 steps per unit
    assert "* 255.0 + 0.5) / 255.0)" in text


def test_line_directive_maps_each_statement_to_its_printed_ir_line():
    for program in (per_pixel_n_dot_l(), ps11_style(), every_sample_variant(),
                    vertex_transform()):
        ir_lines = format_program(program).splitlines()
        shader = (glsl.fragment_shader(program) if program.stage == "fragment" else
                  glsl.vertex_shader(program, ("color0",), {"position"}))
        lines = shader.splitlines()
        start = next(i for i, line in enumerate(lines) if line.startswith("#line "))
        first = int(lines[start].split()[1])
        body = lines[start + 1:start + 1 + len(program.instrs) + len(program.outputs)]
        for offset, line in enumerate(body):
            ir_line = ir_lines[first + offset - 1]        # GLSL numbers lines from 1
            comment = line.split("//", 1)[1].strip()
            assert comment == ir_line, (offset, line, ir_line)


def test_inputs_named_like_glsl_keywords_and_builtins_are_renamed():
    b = Builder("fragment")
    t = b.uniform("texture")
    f = b.varying("filter")
    s = b.uniform("sample")
    b.output("color0", b.add(b.add(t, f), b.sample(0, b.input("input", "varying"))))
    b.output("color1", s)
    text = glsl.fragment_shader(b.build())
    assert "uniform vec4 u_texture;" in text and "in vec4 vary_filter;" in text
    assert "uniform vec4 u_sample;" in text and "in vec4 vary_input;" in text
    _link(glsl.vertex_shader(None, ("filter", "input"), {"position"}), text)


def test_unsupplied_streams_read_d3d_defaults():
    text = glsl.vertex_shader(None, ("color0", "color1", "texcoord3"), {"position"})
    assert "const vec4 attr_color0 = vec4(1.0, 1.0, 1.0, 1.0);" in text
    assert "const vec4 attr_color1 = vec4(0.0, 0.0, 0.0, 0.0);" in text
    assert "const vec4 attr_texcoord3 = vec4(0.0, 0.0, 0.0, 1.0);" in text
    assert "vary_color0 = clamp(attr_color0, 0.0, 1.0);" in text  # colours are saturated
    assert "vary_texcoord3 = attr_texcoord3;" in text


def test_unknown_builtin_is_an_ir_error():
    b = Builder("fragment")
    b.output("color0", b.builtin("vfoo"))
    with pytest.raises(IRError, match="unknown fragment builtin 'vfoo'"):
        glsl.fragment_shader(b.build())


def test_vertex_program_without_position_is_an_ir_error():
    b = Builder("vertex")
    b.output("color0", b.const(1.0))
    with pytest.raises(IRError, match="writes no position"):
        glsl.vertex_shader(b.build(), ("color0",), set())


# --------------------------------------------------------------------------------------------
# Everything printed compiles (GL is required: no context is a failure, not a skip)


def _link(vertex_text: str, fragment_text: str) -> None:
    ctx = headless_context()
    program = ctx.program(vertex_shader=vertex_text, fragment_shader=fragment_text)
    program.release()


@pytest.mark.parametrize("name", sorted(n for n in SHADERS if n.endswith(".frag.glsl")))
def test_golden_fragment_shaders_compile(name):
    options = FULL_EPILOGUE if name.startswith("epilogue") else glsl.FragmentOptions()
    program = {"n_dot_l": per_pixel_n_dot_l, "epilogue": per_pixel_n_dot_l,
               "ps11_quantize": ps11_style, "every_sample": every_sample_variant}[
        name.split(".")[0]]()
    varyings = glsl.fragment_varyings(program, options)
    vertex = glsl.vertex_shader(None, varyings, {"position", *varyings}, options.flat_colors)
    _link(vertex, SHADERS[name])


def test_golden_vertex_shaders_compile():
    fragment = Builder("fragment")
    fragment.output("color0", fragment.add(fragment.varying("color0"),
                                           fragment.varying("texcoord0")))
    fragment_text = glsl.fragment_shader(fragment.build())
    _link(glsl.vertex_shader(vertex_transform(), ("color0", "texcoord0"), {"position"}),
          fragment_text)


def test_error_of_a_broken_template_points_at_the_ir_line():
    """A GLSL compiler message's line number is the IR listing's line of the instruction."""
    program = per_pixel_n_dot_l()
    text = glsl.fragment_shader(program)
    target = next(i for i in program.instrs if i.op == "dp3")
    broken = text.replace("vec4(dot(", "vec4(dotx(", 1)
    ctx = headless_context()
    with pytest.raises(Exception) as info:
        ctx.program(vertex_shader=glsl.vertex_shader(None, ("texcoord1",), {"position"}),
                    fragment_shader=broken)
    ir_line = format_program(program).splitlines().index(f"%{target.dest} = dp3 "
                                                         + ", ".join(f"%{a}" for a in target.args))
    assert re.search(rf"\b0:{ir_line + 1}\(", str(info.value)), str(info.value)
