"""The IR: builder, checks, printer (golden text), GLSL templates (by string, by compiling them
with a real GLSL 330 compiler and by running them against the NumPy kernels), pass state."""
import dataclasses

import numpy as np
import pytest

from backends.reference.evaluate import evaluate
from effects.program.ir import (OPS, Builder, Input, Instr, IRError, Program, SamplerBinding,
                        format_program, glsl_float, normalize_attrs)
from effects.program.passprogram import PassProgram, RenderState, TextureBinding


def small_program() -> Program:
    b = Builder("fragment")
    uv = b.varying("texcoord0", "TEXCOORD0", 2)
    diffuse = b.varying("diffuse", "COLOR0")
    texel = b.sample(0, uv)
    bx2 = b.mad(texel, b.const(2.0), b.const(-1.0))
    lit = b.saturate(b.dp3(bx2, b.uniform("LightDir")))
    b.kill(uv, "xyz")
    rgb = b.quantize(b.mul(lit, diffuse), bits=9, signed=True)
    b.output("color0", b.merge(rgb, diffuse, "a"))
    return b.build()


GOLDEN = """\
fragment program
input texcoord0: varying semantic=TEXCOORD0 components=2
input diffuse: varying semantic=COLOR0
input LightDir: uniform
sampler 0: 2d
%0 = input texcoord0
%1 = input diffuse
%2 = sample %0 sampler=0
%3 = const (2.0, 2.0, 2.0, 2.0)
%4 = const (-1.0, -1.0, -1.0, -1.0)
%5 = mad %2, %3, %4
%6 = input LightDir
%7 = dp3 %5, %6
%8 = saturate %7
kill %0 components=xyz
%9 = mul %8, %1
%10 = quantize %9 bits=9 signed=true
%11 = merge %10, %1 mask=w
output color0 = %11
"""


def test_printer_golden():
    assert format_program(small_program()) == GOLDEN


def test_printer_shows_non_default_sample_and_clamp_attributes():
    b = Builder("fragment")
    c = b.varying("texcoord1")
    b.output("color0", b.clamp(b.sample(2, c, kind="cube", proj=True), -8, 8))
    text = format_program(b.build())
    assert "sampler 2: cube" in text
    assert "%1 = sample %0 sampler=2 kind=cube proj=true" in text
    assert "%2 = clamp %1 lo=-8.0 hi=8.0" in text


def test_programs_built_alike_are_equal_hashable_and_share_a_key():
    a, b = small_program(), small_program()
    assert a == b and hash(a) == hash(b) and a.key() == b.key()
    assert len({a, b}) == 1
    other = Builder("fragment")
    other.output("color0", other.const(1))
    assert other.build() != a and other.build().key() != a.key()


def test_builder_deduplicates_constants_and_repeated_ops():
    b = Builder("fragment")
    half = b.const(0.5)
    assert b.const((0.5, 0.5, 0.5, 0.5)) == half
    assert b.const(np.float32(0.5)) == half
    # 0.1 and its float32 rounding are the same constant on the device
    assert b.const(0.1) == b.const(float(np.float32(0.1)))
    assert b.const((1, 0, 0, 1)) != b.const((0, 1, 0, 1))
    x = b.varying("texcoord0")
    assert b.varying("texcoord0") == x
    assert b.add(x, half) == b.add(x, half)
    assert b.add(x, half) != b.add(half, x)  # no algebra: just identical instructions
    b.output("color0", b.add(x, half))
    program = b.build()
    assert [i.op for i in program.instrs] == ["const", "input", "add"]


def test_identity_swizzle_and_full_merge_emit_nothing():
    b = Builder("fragment")
    x, y = b.varying("a"), b.varying("b")
    assert b.swizzle(x, "xyzw") == x and b.swizzle(x, "rgba") == x
    assert b.merge(x, y, "xyzw") == y
    assert b.swizzle(x, "w") == b.swizzle(x, "wwww")


def test_build_prunes_dead_code_and_renumbers():
    b = Builder("fragment")
    unused = b.varying("unused")
    b.sample(5, b.mul(unused, unused), kind="3d")
    x = b.varying("a")
    b.output("color0", b.add(x, x))
    program = b.build()
    assert [i.name for i in program.inputs] == ["a"]
    assert program.samplers == ()
    assert program.instrs == (Instr(0, "input", (), (("name", "a"),)), Instr(1, "add", (0, 0)))
    assert len(b.build(prune=False).instrs) == 5  # input, mul, sample, input, add


def test_outputs_are_kept_in_stage_order():
    b = Builder("vertex")
    v = b.varying("position")
    b.output("fog", v)
    b.output("texcoord3", v)
    b.output("position", v)
    assert [name for name, _ in b.build().outputs] == ["position", "texcoord3", "fog"]


@pytest.mark.parametrize("make, message", [
    (lambda b: b.output("color5", b.const(1)), "not a fragment output"),
    (lambda b: b.swizzle(b.const(1), "xyzq"), "bad swizzle"),
    (lambda b: b.merge(b.const(1), b.const(2), "zx"), "bad write mask"),
    (lambda b: b.add(b.const(1), 7), "not a value"),
    (lambda b: b.emit("dp5", b.const(1)), "unknown op"),
    (lambda b: b.emit("add", b.const(1)), "takes 2 argument"),
    (lambda b: b.clamp(b.const(1), 1, 0), "lo <= hi"),
    (lambda b: b.quantize(b.const(1), bits=0), "bits"),
    (lambda b: b.sample(0, b.const(1), kind="2D"), "kind"),
    (lambda b: b.sample(0, b.const(1), proj=True, bias=True), "at most one"),
    (lambda b: (b.sample(0, b.const(1)), b.sample(0, b.const(1), kind="cube")), "used as"),
    (lambda b: (b.uniform("x"), b.varying("x")), "redeclared"),
    (lambda b: b.emit("swizzle", b.const(1), pattern="xyzw", mask="x"), "no attribute"),
])
def test_builder_rejects_malformed_ir(make, message):
    with pytest.raises(IRError, match=message):
        make(Builder("fragment"))


def test_kill_is_fragment_only():
    b = Builder("vertex")
    with pytest.raises(IRError, match="fragment"):
        b.kill(b.const(1))


def test_program_construction_checks_ssa_and_declarations():
    value = (("value", (1.0, 1.0, 1.0, 1.0)),)
    with pytest.raises(IRError, match="before it is defined"):
        Program("fragment", instrs=(Instr(0, "add", (0, 0)),))
    with pytest.raises(IRError, match="defined twice"):
        Program("fragment", instrs=(Instr(0, "const", (), value), Instr(0, "const", (), value)))
    with pytest.raises(IRError, match="not declared"):
        Program("fragment", instrs=(Instr(0, "input", (), (("name", "a"),)),))
    with pytest.raises(IRError, match="not declared as 2d"):
        Program("fragment", instrs=(
            Instr(0, "const", (), value),
            Instr(1, "sample", (0,), (("sampler", 0), ("kind", "2d"), ("proj", False),
                                      ("bias", False), ("lod", False)))),
            samplers=(SamplerBinding(0, "cube"),))
    with pytest.raises(IRError, match="canonical"):
        Program("fragment", instrs=(Instr(0, "const", (), value),
                                    Instr(1, "quantize", (0,), (("bits", 8),))))
    with pytest.raises(IRError, match="identifier"):
        Program("fragment", inputs=(Input("gl_Color"),))
    with pytest.raises(IRError, match="undefined"):
        Program("fragment", outputs=(("color0", 3),))


# --------------------------------------------------------------------------------------------
# GLSL templates


def test_op_table_rows_are_complete():
    for name, info in OPS.items():
        assert info.name == name and info.doc and info.glsl and callable(info.kernel)
        assert len(info.arg_demand(frozenset(range(4)), {"pattern": "xyzw", "mask": "x"})) \
            == info.arity
        assert not (info.per_component and info.columns is None and info.kernel is None)
    assert {"add", "sub", "mul", "mad", "dp3", "dp4", "min", "max", "rcp", "rsq", "exp2",
            "log2", "pow", "frc", "abs", "cmp", "cnd", "lrp", "nrm", "crs", "slt", "sge",
            "swizzle", "merge", "saturate", "clamp", "quantize", "sample", "kill"} <= set(OPS)


_ROW_ATTRS = {"swizzle": {"pattern": "wxzy"}, "merge": {"mask": "yw"}, "clamp": {"lo": -.5, "hi": .5},
              "quantize": {"bits": 8}}


@pytest.mark.parametrize("name", [n for n, info in OPS.items()
                                  if info.arity and info.has_result and not info.needs_quads
                                  and not info.names_sampler])
def test_demand_column_is_what_the_kernel_reads(name):
    # The row's demand rule (and its per-component flag) is checked against its own kernel:
    # changing an argument component the rule says is unread leaves every wanted component
    # of the result as it was.
    info = OPS[name]
    attrs = dict(normalize_attrs(name, _ROW_ATTRS.get(name, {})))
    rng = np.random.default_rng(7)
    args = [rng.uniform(0.1, 2.0, (1, 4)).astype(np.float32) for _ in range(info.arity)]
    for want in range(4):
        wanted = frozenset({want})
        base = info.kernel(None, args, attrs)[0, want]
        for k, reads in enumerate(info.arg_demand(wanted, attrs)):
            for j in set(range(4)) - reads:
                changed = [a.copy() for a in args]
                changed[k][0, j] += 0.75
                assert info.kernel(None, changed, attrs)[0, want] == base, (name, k, j)


def test_glsl_templates_by_string():
    assert OPS["mad"].format_glsl(["v1", "v2", "v3"]) == "(v1 * v2 + v3)"
    assert OPS["dp3"].format_glsl(["a", "b"]) == "vec4(dot(a.xyz, b.xyz))"
    assert OPS["cmp"].format_glsl(["a", "b", "c"]) == "mix(c, b, greaterThanEqual(a, vec4(0.0)))"
    assert OPS["lrp"].format_glsl(["f", "a", "b"]) == "mix(b, a, f)"
    assert OPS["swizzle"].format_glsl(["v"], {"pattern": "wzyx"}) == "v.wzyx"
    assert OPS["merge"].format_glsl(["o", "n"], {"mask": "yw"}) == "vec4(o.x, n.y, o.z, n.w)"
    assert OPS["const"].format_glsl([], {"value": (1.0, 0.5, -2.0, 1e20)}) == \
        "vec4(1.0, 0.5, -2.0, 1e+20)"
    sample = dict(sampler=1, kind="2d", proj=False, bias=False, lod=False)
    assert OPS["sample"].format_glsl(["t"], sample) == "texture(sampler1, t.xy)"
    assert OPS["sample"].format_glsl(["t"], {**sample, "proj": True}) == \
        "textureProj(sampler1, t.xyw)"
    assert OPS["sample"].format_glsl(["t"], {**sample, "kind": "cube", "bias": True}) == \
        "texture(sampler1, t.xyz, t.w)"
    assert OPS["kill"].format_glsl(["t"], {"components": "xyz"}) == \
        "if (any(lessThan(t.xyz, vec3(0.0)))) discard;"
    assert glsl_float(3) == "3.0" and glsl_float(-0.25) == "-0.25"
    with pytest.raises(IRError):
        glsl_float(float("inf"))


def glsl_body(program: Program) -> tuple[list[str], dict[str, str]]:
    """A minimal IR -> GLSL statement list (what the GL back end's printer does), and the GLSL
    expression of each output."""
    lines = []
    for instr in program.instrs:
        info = OPS[instr.op]
        text = info.format_glsl([f"v{a}" for a in instr.args], instr.attr_map)
        lines.append(f"    vec4 v{instr.dest} = {text};" if info.has_result else f"    {text}")
    return lines, {name: f"v{value}" for name, value in program.outputs}


SAMPLER_TYPES = {"1d": "sampler1D", "2d": "sampler2D", "3d": "sampler3D", "cube": "samplerCube"}


@pytest.fixture(scope="module")
def gl():
    moderngl = pytest.importorskip("moderngl")
    try:
        ctx = moderngl.create_standalone_context(backend="egl")
    except Exception as exc:  # no EGL device on this machine: say so in the skip reason
        pytest.skip(f"no headless OpenGL context: {exc}")
    # A standalone EGL context has no default framebuffer; drawing needs one bound.
    fbo = ctx.simple_framebuffer((1, 1))
    fbo.use()
    yield ctx
    fbo.release()
    ctx.release()


def every_op_fragment_program() -> Program:
    """One fragment program that uses every op and every sample variant."""
    b = Builder("fragment")
    a, c, d = b.varying("a"), b.varying("b"), b.uniform("u")
    acc = b.const((0.25, 0.5, 0.75, 1.0))
    for name, info in OPS.items():
        if info.arity == 0 or not info.has_result or info.names_sampler or name in (
                "swizzle", "merge", "clamp", "quantize"):
            continue
        acc = b.add(acc, b.emit(name, *[a, c, d][:info.arity]))
    acc = b.merge(acc, b.swizzle(a, "wzyx"), "yw")
    acc = b.add(b.clamp(acc, -8, 8), b.quantize(acc, bits=9, signed=True))
    acc = b.add(acc, b.quantize(acc, bits=8))
    for index, kind in enumerate(("1d", "2d", "3d", "cube")):
        for flags in ({}, {"proj": True}, {"bias": True}, {"lod": True}):
            acc = b.add(acc, b.sample(index, a, kind=kind, **flags))
    b.kill(a, "xyz")
    b.kill(c, "xyzw")
    b.kill(d, "w")
    b.output("color0", acc)
    b.output("depth", b.swizzle(acc, "zzzz"))
    return b.build()


def test_every_template_compiles_as_glsl_330(gl):
    program = every_op_fragment_program()
    body, outputs = glsl_body(program)
    decls = [f"in vec4 {i.name};" if i.kind == "varying" else f"uniform vec4 {i.name};"
             for i in program.inputs]
    decls += [f"uniform {SAMPLER_TYPES[s.kind]} sampler{s.index};" for s in program.samplers]
    source = "\n".join(["#version 330", *decls, "out vec4 color0;", "void main() {", *body,
                        f"    color0 = {outputs['color0']};",
                        f"    gl_FragDepth = {outputs['depth']}.x;", "}"])
    vertex = ("#version 330\nin vec4 position;\nout vec4 a;\nout vec4 b;\n"
              "void main() { a = position; b = position; gl_Position = position; }")
    prog = gl.program(vertex_shader=vertex, fragment_shader=source)  # raises on a GLSL error
    assert "sampler3" in prog and "u" in prog


# Rows chosen to hit the D3D edge cases whose GLSL is written out explicitly (rcp/rsq/log2 of
# zero, cmp at 0, cnd at 0.5), while avoiding inputs GLSL leaves undefined (pow(0, y <= 0)).
ROWS_A = [[1, -2, 0.5, 4], [0, 3, -1, 0.25], [0.5, -0.0, 2.5, 0.5001], [-3, 0.75, 1.5, -0.5]]
ROWS_B = [[2, 0.5, -4, 1], [1, 1, 2, 8], [-1, 0.5, 0, 3], [0.25, -2, 1, 0]]
ROWS_C = [[0.25, 0.25, 0.25, 0.25], [-3, 0, 1, 2], [7, -7, 0.5, 1], [1, 2, 3, 4]]
ATTRS = {"swizzle": {"pattern": "wxzy"}, "merge": {"mask": "xz"},
         "clamp": {"lo": -1.0, "hi": 0.5}, "quantize": {"bits": 8}}
# (ops that need 2x2 quads are checked by rendering: tests/shaders/asm/test_asm_flow.py)
ARITH = [n for n, info in OPS.items() if info.arity > 0 and info.has_result
         and not info.needs_quads and not info.names_sampler]


@pytest.mark.parametrize("op", ARITH)
def test_template_computes_what_the_kernel_computes(gl, op):
    """Run the op's GLSL in a vertex shader (transform feedback) and compare with NumPy."""
    b = Builder("vertex")
    args = [b.varying(n) for n in "abc"[:OPS[op].arity]]
    b.output("position", b.emit(op, *args, **ATTRS.get(op, {})))
    program = b.build()
    body, outputs = glsl_body(program)
    source = "\n".join(["#version 330", "in vec4 a;", "in vec4 b;", "in vec4 c;",
                        "out vec4 result;", "void main() {", *body,
                        f"    result = {outputs['position']};", "    gl_Position = vec4(0.0);",
                        "}"])
    prog = gl.program(vertex_shader=source, varyings=["result"])
    rows = {"a": ROWS_A, "b": ROWS_B, "c": ROWS_C}
    content = [(gl.buffer(np.array(rows[n], dtype="f4").tobytes()), "4f", n)
               for n in "abc" if n in prog]
    vao = gl.vertex_array(prog, content)
    out_buffer = gl.buffer(reserve=len(ROWS_A) * 16)
    vao.transform(out_buffer, vertices=len(ROWS_A))
    gpu = np.frombuffer(out_buffer.read(), dtype="f4").reshape(-1, 4)
    ref = evaluate(program, {n: np.array(rows[n], dtype=np.float32) for n in "abc"[:len(args)]}
                   ).outputs["position"]
    np.testing.assert_allclose(gpu, ref, rtol=2e-6, atol=1e-6)
    for release in (vao, out_buffer, prog, *(c[0] for c in content)):
        release.release()


# --------------------------------------------------------------------------------------------
# PassProgram and state defaults


def test_render_state_defaults_are_the_d3d9_device_defaults():
    rs = RenderState()
    assert (rs.z_enable, rs.z_write_enable, rs.z_func) == (True, True, "LESSEQUAL")
    assert rs.cull_mode == "CCW" and rs.fill_mode == "SOLID" and rs.shade_mode == "GOURAUD"
    assert (rs.alpha_test_enable, rs.alpha_func, rs.alpha_ref) == (False, "ALWAYS", 0)
    assert (rs.alpha_blend_enable, rs.src_blend, rs.dest_blend, rs.blend_op) == \
        (False, "ONE", "ZERO", "ADD")
    assert rs.color_write_enable == 0xF
    assert (rs.stencil_enable, rs.stencil_func, rs.stencil_mask, rs.stencil_pass) == \
        (False, "ALWAYS", 0xFFFFFFFF, "KEEP")
    t = TextureBinding(0, "BaseTexture")
    assert (t.address_u, t.address_v, t.address_w) == ("WRAP", "WRAP", "WRAP")
    assert (t.min_filter, t.mag_filter, t.mip_filter) == ("POINT", "POINT", "NONE")
    assert (t.max_anisotropy, t.max_mip_level, t.mip_lod_bias) == (1, 0, 0.0)
    assert dataclasses.replace(rs, cull_mode="NONE") != rs


def test_pass_program_checks_stages_and_sampler_kinds():
    fragment = small_program()
    passp = PassProgram(fragment, textures=(TextureBinding(0, "NormalMap"),),
                        uniforms=PassProgram.pack_uniforms({"LightDir": [0, 0, 1]}))
    assert passp.uniform_values()["LightDir"].tolist() == [0, 0, 1, 1]
    assert passp.texture(0).texture == "NormalMap" and passp.texture(1) is None
    assert hash(passp) == hash(PassProgram(fragment, textures=(TextureBinding(0, "NormalMap"),),
                                           uniforms=(("LightDir", (0.0, 0.0, 1.0, 1.0)),)))
    with pytest.raises(IRError, match="texture binding is cube"):
        PassProgram(fragment, textures=(TextureBinding(0, "Env", kind="cube"),))
    with pytest.raises(IRError, match="vertex program"):
        PassProgram(fragment, vertex=fragment)
