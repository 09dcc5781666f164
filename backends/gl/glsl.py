"""IR programs printed as GLSL 330 core shaders, plus the fixed-function epilogues of Direct3D 9.

Every instruction becomes one line `vec4 vN = <template>;` (a statement for ops without a
result: `if (...) {`, `for (...) {`, `}`, an assignment) where the template is the op's row in
`effects.program.ir.OPS` (`OpInfo.format_glsl`), indented by the blocks the rows open and close;
nothing here knows an op by name. Values live in
variables because templates may use an argument twice. A `#line` directive before the body
numbers each instruction line as the same instruction's line in the printed IR
(`effects.program.ir.format_program`), so a GLSL compiler message points into the IR listing, and a
trailing comment repeats the IR instruction.

Names: the IR's inputs are declared under prefixed names so that no effect name can collide
with a GLSL keyword or built-in function (`filter`, `input`, `texture`, `sample` are all taken):
vertex streams `attr_<name>`, varyings `vary_<name>`, uniforms `u_<name>`; samplers are
`sampler<index>` as the op table prints them; this module's own uniforms start with `d3d_`.

Direct3D conventions handled here, once:
- Clip space: D3D has 0 <= z <= w and window y growing downward; the vertex epilogue maps to
  GL's -w <= z <= w (z' = 2z - w) and renders upside down (y' = -y), so GL's window row r is
  D3D's row r, the read-back needs no flip and GL's counter-clockwise is D3D's clockwise (front).
- Pixel centres: D3D9 samples pixel (px, py) at window (px, py), GL at (px + .5, py + .5); the
  vertex epilogue shifts every position by half a pixel (as Wine and DXVK do).
- Colour varyings (color0, color1) are saturated before interpolation unless the vertex
  program says its colours are unclamped (vs_3_0: `Program.clamp_colors`); varyings nothing supplies
  read D3D's defaults: color0 (1, 1, 1, 1), color1 (0, 0, 0, 0), others (0, 0, 0, 1).
- Fragment epilogue, in D3D9's order: oDepth (saturated) or the depth bias, alpha test against
  the 8-bit alpha, sRGB write. Fog and the specular add are in the IR (lowering folds them in).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable, Sequence

from effects.program.ir import OPS, IRError, Program, format_instr, glsl_float

GLSL_VERSION = "#version 330 core"
SAMPLER_TYPES = {"1d": "sampler1D", "2d": "sampler2D", "3d": "sampler3D", "cube": "samplerCube"}
COLOR_VARYINGS = ("color0", "color1")
VARYING_DEFAULTS = {"color0": (1.0, 1.0, 1.0, 1.0), "color1": (0.0, 0.0, 0.0, 0.0)}
DEFAULT_VALUE = (0.0, 0.0, 0.0, 1.0)
# Fragment builtins: name -> GLSL expression (D3D9 vPos has integer pixel centres; vFace is
# +1 on front faces).
FRAGMENT_BUILTINS = {
    "vpos": "vec4(floor(gl_FragCoord.xy), 0.0, 1.0)",
    "vface": "vec4(gl_FrontFacing ? 1.0 : -1.0)",
}
# Order of D3DCMPFUNC as the `d3d_alpha_func` uniform numbers them.
COMPARE_FUNCS = ("NEVER", "LESS", "EQUAL", "LESSEQUAL", "GREATER", "NOTEQUAL", "GREATEREQUAL",
                 "ALWAYS")
# GLSL line numbers of the code after the IR body (a message there is this module's bug).
EPILOGUE_LINE = 10000
# Outputs that are not varyings.
_NOT_VARYINGS = ("position", "psize")


@dataclass(frozen=True)
class FragmentOptions:
    """Fixed-function work appended to the fragment program (part of the program cache key;
    the values it needs are uniforms, so changing them does not recompile)."""

    flat_colors: bool = False
    alpha_test: bool = False
    depth_bias: bool = False
    srgb_write: bool = False


def attribute_name(name: str) -> str:
    return f"attr_{name}"


def varying_name(name: str) -> str:
    return f"vary_{name}"


def uniform_name(name: str) -> str:
    return f"u_{name}"


def value_name(value: int) -> str:
    return f"v{value}"


def fragment_varyings(fragment: Program, options: FragmentOptions) -> tuple[str, ...]:
    """The varyings the fragment shader declares, in a stable order."""
    names = [i.name for i in fragment.inputs if i.kind == "varying"]
    return tuple(sorted(set(names)))


def uniforms_of(*programs: Program | None) -> tuple[str, ...]:
    """IR uniform names the programs read (each is `u_<name>` in GLSL)."""
    return tuple(sorted({i.name for p in programs if p is not None
                         for i in p.inputs if i.kind == "uniform"}))


# --------------------------------------------------------------------------------------------
# The body: one statement per instruction, from the op table


def _input_expression(program: Program, name: str, attribute_inputs: bool) -> str:
    item = program.input(name)
    if item.kind == "uniform":
        return uniform_name(name)
    if item.kind == "builtin":
        if program.stage != "fragment" or name not in FRAGMENT_BUILTINS:
            raise IRError(f"unknown {program.stage} builtin {name!r} "
                          f"(known: {', '.join(FRAGMENT_BUILTINS)})")
        return f"builtin_{name}"
    return attribute_name(name) if attribute_inputs else varying_name(name)


def _body(program: Program, attribute_inputs: bool) -> list[str]:
    """`#line` then one line per instruction, then one per output (`out_<name>` locals)."""
    first_instr_line = 2 + len(program.inputs) + len(program.samplers)
    lines = [f"#line {first_instr_line}"]
    depth = 1
    for instr in program.instrs:
        info = OPS[instr.op]
        if info.flow in ("middle", "close"):
            depth -= 1
        attrs = instr.attr_map
        if info.names_input:
            # The op's `name` attribute names a declared input, which GLSL knows under a
            # prefixed identifier: hand the op's template that identifier.
            attrs = {**attrs, "name": _input_expression(program, attrs["name"], attribute_inputs)}
        text = info.format_glsl([value_name(a) for a in instr.args], attrs)
        if instr.dest is not None:
            text = f"vec4 {value_name(instr.dest)} = {text};"
        lines.append(f"{'    ' * depth}{text}  // {format_instr(instr)}")
        if info.flow in ("open", "middle"):   # the op's row says it opens a block
            depth += 1
    for name, value in program.outputs:
        lines.append(f"    vec4 out_{name} = {value_name(value)};  // output {name} = %{value}")
    return lines


def _vec4(values: Iterable[float]) -> str:
    return "vec4(" + ", ".join(glsl_float(v) for v in values) + ")"


def _sampler_declarations(program: Program | None) -> list[str]:
    if program is None:
        return []
    return [f"uniform {SAMPLER_TYPES[s.kind]} sampler{s.index};" for s in program.samplers]


def _uniform_declarations(program: Program | None) -> list[str]:
    if program is None:
        return []
    return [f"uniform vec4 {uniform_name(i.name)};" for i in program.inputs
            if i.kind == "uniform"]


def _header(stage: str, program: Program | None) -> list[str]:
    key = program.key()[:16] if program is not None else "pass-through"
    return [GLSL_VERSION, f"// {stage} shader for IR program {key}"]


# --------------------------------------------------------------------------------------------
# Vertex shader


def vertex_shader(vertex: Program | None, varyings: Sequence[str], streams: Iterable[str],
                  flat_colors: bool = False) -> str:
    """The vertex shader: the vertex program (or, with None, positions already in D3D clip
    space and every varying passed through from the stream of its name), writing `varyings`.

    `streams` names the vertex streams the draw supplies; a vertex input without one reads
    D3D's default for it, a constant."""
    streams = set(streams)
    lines = _header("vertex", vertex)
    if vertex is None:
        attributes = ["position", *(n for n in varyings if n != "position")]
        outputs: dict[str, str] = {n: attribute_name(n) for n in varyings}
        position = attribute_name("position")
    else:
        attributes = [i.name for i in vertex.inputs if i.kind == "varying"]
        outputs = {n: f"out_{n}" for n, _ in vertex.outputs if n not in _NOT_VARYINGS}
        if "position" not in vertex.output_map:
            raise IRError("the vertex program writes no position")
        position = "out_position"
    for name in attributes:
        if name in streams:
            lines.append(f"in vec4 {attribute_name(name)};")
        else:
            default = _vec4(VARYING_DEFAULTS.get(name, DEFAULT_VALUE))
            lines.append(f"const vec4 {attribute_name(name)} = {default};  // no {name} stream")
    lines += _uniform_declarations(vertex)
    lines += _sampler_declarations(vertex)
    lines.append("uniform vec2 d3d_pixel_size;  // (2/W, 2/H): one pixel in NDC")
    for name in varyings:
        lines.append(f"{_interpolation(name, flat_colors)}out vec4 {varying_name(name)};")
    lines.append("")
    lines.append("void main() {")
    if vertex is not None:
        lines += _body(vertex, attribute_inputs=True)
    lines.append(f"#line {EPILOGUE_LINE}")
    for name in varyings:
        value = outputs.get(name, _vec4(VARYING_DEFAULTS.get(name, DEFAULT_VALUE)))
        if name in COLOR_VARYINGS and (vertex is None or vertex.clamp_colors):
            value = f"clamp({value}, 0.0, 1.0)"  # D3D saturates colour interpolators (< SM3)
        lines.append(f"    {varying_name(name)} = {value};")
    lines += [
        f"    vec4 p = {position};",
        "    // D3D clip space to GL's: half-pixel shift to D3D9 pixel centres, y flipped",
        "    // (GL row r is D3D row r), z in [0, w] to [-w, w].",
        "    gl_Position = vec4(p.x + 0.5 * d3d_pixel_size.x * p.w,",
        "                       -(p.y - 0.5 * d3d_pixel_size.y * p.w),",
        "                       2.0 * p.z - p.w, p.w);",
        "}",
    ]
    return "\n".join(lines) + "\n"


def _interpolation(name: str, flat_colors: bool) -> str:
    return "flat " if flat_colors and name in COLOR_VARYINGS else ""


# --------------------------------------------------------------------------------------------
# Fragment shader

_COMPARE_FUNCTION = """\
bool d3d_compare(int func, int a, int b) {  // D3DCMPFUNC, numbered as COMPARE_FUNCS
    if (func == 0) return false;
    if (func == 1) return a < b;
    if (func == 2) return a == b;
    if (func == 3) return a <= b;
    if (func == 4) return a > b;
    if (func == 5) return a != b;
    if (func == 6) return a >= b;
    return true;
}"""

_SRGB_FUNCTION = """\
vec3 d3d_linear_to_srgb(vec3 x) {  // IEC 61966-2-1
    x = clamp(x, 0.0, 1.0);
    return mix(1.055 * pow(x, vec3(1.0 / 2.4)) - 0.055, 12.92 * x,
               lessThanEqual(x, vec3(0.0031308)));
}"""

def fragment_shader(fragment: Program, options: FragmentOptions = FragmentOptions()) -> str:
    """The fragment shader: the fragment program, then the fixed-function epilogue `options`
    asks for, writing colour output 0 (and output 0 index 1 for the second colour, which the
    SRCCOLOR2 blend factors read)."""
    outputs = fragment.output_map
    lines = _header("fragment", fragment)
    for name in fragment_varyings(fragment, options):
        lines.append(f"{_interpolation(name, options.flat_colors)}in vec4 {varying_name(name)};")
    lines += _uniform_declarations(fragment)
    lines += _sampler_declarations(fragment)
    if options.depth_bias:
        lines.append("uniform vec2 d3d_depth_bias;  // (DepthBias, SlopeScaleDepthBias)")
    if options.alpha_test:
        lines.append("uniform int d3d_alpha_func;  // index in COMPARE_FUNCS")
        lines.append("uniform int d3d_alpha_ref;")
    lines.append("layout(location = 0, index = 0) out vec4 frag_color;")
    if "color1" in outputs:
        lines.append("layout(location = 0, index = 1) out vec4 frag_color1;")
    if options.alpha_test:
        lines.append(_COMPARE_FUNCTION)
    if options.srgb_write:
        lines.append(_SRGB_FUNCTION)
    lines.append("")
    lines.append("void main() {")
    for item in fragment.inputs:
        if item.kind == "builtin":
            expression = FRAGMENT_BUILTINS.get(item.name)
            if expression is None:
                raise IRError(f"unknown fragment builtin {item.name!r} "
                              f"(known: {', '.join(FRAGMENT_BUILTINS)})")
            lines.append(f"    vec4 builtin_{item.name} = {expression};")
    lines += _body(fragment, attribute_inputs=False)
    lines.append(f"#line {EPILOGUE_LINE}")
    lines += _fragment_epilogue(outputs, options)
    lines.append("}")
    return "\n".join(lines) + "\n"


def _fragment_epilogue(outputs: dict[str, int], options: FragmentOptions) -> list[str]:
    lines = [f"    vec4 color = {'out_color0' if 'color0' in outputs else 'vec4(0.0)'};"]
    if "depth" in outputs:
        lines.append("    gl_FragDepth = clamp(out_depth.x, 0.0, 1.0);  // oDepth, saturated")
    elif options.depth_bias:
        lines += [
            "    float z_slope = max(abs(dFdx(gl_FragCoord.z)), abs(dFdy(gl_FragCoord.z)));",
            "    gl_FragDepth = gl_FragCoord.z + d3d_depth_bias.x + d3d_depth_bias.y * z_slope;"]
    if options.alpha_test:
        lines.append("    int alpha8 = int(floor(clamp(color.a, 0.0, 1.0) * 255.0 + 0.5));")
        lines.append("    if (!d3d_compare(d3d_alpha_func, alpha8, d3d_alpha_ref)) discard;")
    if options.srgb_write:
        lines.append("    color.rgb = d3d_linear_to_srgb(color.rgb);")
    lines.append("    frag_color = color;")
    if "color1" in outputs:
        lines.append("    frag_color1 = out_color1;")
    return lines
