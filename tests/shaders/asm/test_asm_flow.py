"""Shader Model 2.x/3.0 flow control, lowered to the IR's structured blocks and drawn by both
back ends (the `backend` fixture), each pixel checked against a value worked out by hand.

Every case draws a full-screen quad into an A32B32G32R32F target, so pixel (px, py) reads
vPos = (px, py, 0, 1) (D3D9's integer pixel centres) and colours are not clamped. Expected
values follow the DirectX 9 assembly reference pages of each instruction (loop: aL from i.y
stepping i.z, i.x times; break_comp; setp_comp; callnz; if_comp on vFace ...).
"""
from __future__ import annotations

from tests.paths import TESTS

import numpy as np
import pytest

from effects.program.backend import create_backend
from effects.base.errors import Location
from effects.program.ir import IRError
from effects.model import ShaderBlock
from effects.program.passprogram import PassProgram, RenderState
from effects.d3d9.precision import LoweringOptions
from effects.shaders.asm import assemble, check
from effects.shaders.asm.lower import ShaderContext, lower_pixel_shader, lowering_problems

NO_CULL = RenderState(cull_mode="NONE")
FLOAT = "A32B32G32R32F"


@pytest.fixture(scope="module", params=("numpy", "gl"))
def backend(request):
    made = create_backend(request.param)
    yield made
    made.close()


def program(src: str):
    prog = assemble(ShaderBlock("pixel", None, src, location=Location("t.fx", 1, 1)))
    assert [str(e) for e in check(prog)] == []
    assert [str(e) for e in lowering_problems(prog)] == []
    return lower_pixel_shader(prog, ShaderContext(LoweringOptions()))


def quad(x0=-1.0, x1=1.0):
    """A full-height rectangle from x0 to x1 in clip space; clockwise on screen (front facing)
    when x0 < x1, counter-clockwise (back facing) when x0 > x1."""
    position = np.array([[x0, 1, 0.5], [x1, 1, 0.5], [x0, -1, 0.5], [x1, -1, 0.5]], np.float32)
    return {"position": position}, np.arange(4), "strip"


def draw(backend, src: str, size=(16, 1), uniforms=None, quads=None) -> np.ndarray:
    fragment = program(src)
    passp = PassProgram(fragment, render_state=NO_CULL,
                        uniforms=PassProgram.pack_uniforms(uniforms or {}))
    backend.begin_frame(size, (0.25, 0.25, 0.25, 0.25), 1.0, 0, format=FLOAT)
    for streams, indices, primitive in quads or [quad()]:
        backend.draw(passp, streams, indices, primitive, {})
    return backend.end_frame()


PX = np.arange(16, dtype=np.float32)


def test_nested_loops_read_al_indexed_constants(backend):
    # outer aL = 0, 1, 2 adds c[aL]; inner aL = 4, 5 adds c[aL + 1] (c5, c6) each time:
    # x = (1 + 2 + 4) + 3 (16 + 32) = 151; y counts the inner iterations: 3 * 2 = 6.
    # After the inner loop aL is the outer one again (c[aL] in the second add).
    src = """ps_3_0
    defi i0, 3, 0, 1, 0
    defi i1, 2, 4, 1, 0
    def c0, 1, 0, 0, 0
    def c1, 2, 0, 0, 0
    def c2, 4, 0, 0, 0
    def c9, 0, 1, 0, 0
    def c10, 0, 0, 0, 1
    mov r0, c10
    loop aL, i0
        add r0, r0, c[aL]
        loop aL, i1
            add r0, r0, c[aL + 1]
            add r0, r0, c9
        endloop
        add r0.z, r0.z, c[aL].x
    endloop
    mov oC0, r0
    """
    image = draw(backend, src, uniforms={"c5": [16, 0, 0, 0], "c6": [32, 0, 0, 0]})
    np.testing.assert_array_equal(image[0], np.tile([151, 6, 7, 1], (16, 1)))


def test_early_break_leaves_each_pixel_at_its_own_count(backend):
    # r0.x counts up by one until it reaches vPos.x (break_ge), at most 10 iterations:
    # pixel px ends at min(px, 10); r0.y counts the adds after the break test as well.
    src = """ps_3_0
    dcl vPos.xy
    defi i0, 10, 0, 1, 0
    def c0, 1, 1, 0, 0
    def c1, 0, 0, 0, 1
    mov r0, c1
    rep i0
        break_ge r0.x, vPos.x
        add r0, r0, c0
    endrep
    mov oC0, r0
    """
    image = draw(backend, src)
    expected = np.minimum(PX, 10)
    np.testing.assert_array_equal(image[0, :, 0], expected)
    np.testing.assert_array_equal(image[0, :, 1], expected)


def test_predicated_writes_per_component(backend):
    # setp_gt p0, vPos.xxxx, c0 with c0 = (3, 7, 11, -1): p0 = (px > 3, px > 7, px > 11, 1);
    # (p0) mov r0, c1 writes c1's components where p0 holds (w always: px > -1); then
    # (!p0.x) add r0.w, r0.w, c1.x adds 10 to w where px <= 3: w = 50 there, 40 elsewhere.
    src = """ps_3_0
    dcl vPos.xy
    def c0, 3, 7, 11, -1
    def c1, 10, 20, 30, 40
    def c2, 0, 0, 0, 1
    mov r0, c2
    setp_gt p0, vPos.x, c0
    (p0) mov r0, c1
    (!p0.x) add r0.w, r0.w, c1.x
    mov oC0, r0
    """
    image = draw(backend, src)
    expected = np.stack([np.where(PX > 3, 10, 0), np.where(PX > 7, 20, 0),
                         np.where(PX > 11, 30, 0), np.where(PX > 3, 40, 50)], axis=1)
    np.testing.assert_array_equal(image[0], expected)


def test_callnz_on_a_boolean_and_on_a_predicate(backend):
    # l0 adds (1, 0, 0, 0), l1 adds (0, 1, 0, 0). callnz l0, b0 (true) runs; callnz l0, b1
    # (false) does not; callnz l1, p0.x runs where px < 5 (setp_lt); call l1 always runs.
    src = """ps_3_0
    dcl vPos.xy
    defb b0, true
    defb b1, false
    def c0, 5, 5, 5, 5
    def c1, 1, 0, 0, 0
    def c2, 0, 1, 0, 0
    def c3, 0, 0, 0, 1
    mov r0, c3
    setp_lt p0, vPos.x, c0
    callnz l0, b0
    callnz l0, b1
    callnz l1, p0.x
    call l1
    mov oC0, r0
    ret
    label l0
    add r0, r0, c1
    ret
    label l1
    add r0, r0, c2
    ret
    """
    image = draw(backend, src)
    np.testing.assert_array_equal(image[0, :, 0], np.ones(16))
    np.testing.assert_array_equal(image[0, :, 1], np.where(PX < 5, 2, 1))


def test_if_on_vface_and_else(backend):
    # The left half is drawn front facing (clockwise), the right half back facing: vFace is
    # positive, negative. if_lt vFace, c0.x (0) picks (0, 1, 0, 1) on the back, else (1, 0, 0, 1).
    src = """ps_3_0
    dcl vFace
    def c0, 0, 0, 0, 0
    def c1, 0, 1, 0, 1
    def c2, 1, 0, 0, 1
    if_lt vFace, c0.x
        mov r0, c1
    else
        mov r0, c2
    endif
    mov oC0, r0
    """
    image = draw(backend, src, size=(8, 2), quads=[quad(-1.0, 0.0), quad(1.0, 0.0)])
    assert (image[:, :4] == [1, 0, 0, 1]).all() and (image[:, 4:] == [0, 1, 0, 1]).all()


def test_texkill_inside_a_branch_only_kills_there(backend):
    # if_lt vPos.x, c0.x (4): texkill of a negative value; those pixels keep the clear colour.
    src = """ps_3_0
    dcl vPos.xy
    def c0, 4, 0, 0, 0
    def c1, -1, -1, -1, -1
    def c2, 1, 1, 1, 1
    if_lt vPos.x, c0.x
        texkill c1
    endif
    mov oC0, c2
    """
    image = draw(backend, src)
    np.testing.assert_array_equal(image[0, :, 0], np.where(PX < 4, 0.25, 1.0))


def test_loop_counts_clamp_to_255_and_zero_runs_nothing(backend):
    # rep i0 with i0.x = 255 adds 255 times; rep i1 with i1.x = 0 never runs its body.
    src = """ps_3_0
    defi i0, 255, 0, 0, 0
    defi i1, 0, 0, 0, 0
    def c0, 1, 0, 0, 0
    def c1, 0, 1, 0, 0
    def c2, 0, 0, 0, 1
    mov r0, c2
    rep i0
        add r0, r0, c0
    endrep
    rep i1
        add r0, r0, c1
    endrep
    mov oC0, r0
    """
    image = draw(backend, src, size=(2, 1))
    np.testing.assert_array_equal(image[0], [[255, 0, 0, 1]] * 2)


def test_static_if_on_a_boolean_constant(backend):
    src = """ps_3_0
    defb b0, false
    def c0, 1, 0, 0, 1
    def c1, 0, 0, 1, 1
    mov r0, c0
    if b0
        mov r0, c1
    endif
    mov oC0, r0
    """
    image = draw(backend, src, size=(2, 1))
    np.testing.assert_array_equal(image[0], [[1, 0, 0, 1]] * 2)


# -- errors and the IR's structure checks ----------------------------------------------------

def test_counts_the_application_sets_lower_and_count_against_the_limit():
    # i3 without defi: the pass's value (ShaderContext.int_constants), else (0, 0, 0, 0);
    # the effect-level forms are in test_shader_int_bool_constants.py
    src = "ps_3_0\nrep i3\nrep i3\nmov r0, c0\nendrep\nendrep\nmov oC0, c0"
    prog = assemble(ShaderBlock("pixel", None, src, location=Location("t.fx", 1, 1)))
    assert lowering_problems(prog) == [] == lowering_problems(prog, {3: (255, 0, 0, 0)})
    assert lowering_problems(prog, {3: (255, 0, 0, 0)}) == []       # 65,025 <= 65,536
    src = src.replace("mov r0", "rep i3\nmov r0").replace("endrep\nendrep", "endrep\nendrep\nendrep")
    prog = assemble(ShaderBlock("pixel", None, src, location=Location("t.fx", 1, 1)))
    assert [e.location.line for e in lowering_problems(prog, {3: (255, 0, 0, 0)})] == [4]
    with pytest.raises(Exception, match="65,536|65536"):
        lower_pixel_shader(prog, ShaderContext(LoweringOptions(), int_constants={3: (255, 0, 0, 0)}))


EARLY_RET_IF = """ps_3_0
dcl vPos.xy
def c0, 4, 0, 0, 0
def c1, 1, 0, 0, 0
def c2, 0, 10, 0, 0
def c3, 0, 0, 0, 1
mov r0, c3
call l0
add r0.z, r0.z, c1.x
mov oC0, r0
ret
label l0
add r0, r0, c1
if_lt vPos.x, c0.x
ret
endif
add r0, r0, c2
ret
"""


def test_an_early_ret_in_an_if_leaves_the_subroutine(backend):
    # l0 adds (1, 0, 0, 0), returns where vPos.x < 4, else adds (0, 10, 0, 0); after the call
    # z += 1 for every pixel: (1, 0, 1) left of x = 4, (1, 10, 1) from there
    image = draw(backend, EARLY_RET_IF, size=(8, 1))
    np.testing.assert_array_equal(image[0, :, :3], [[1, 0, 1]] * 4 + [[1, 10, 1]] * 4)


def test_an_early_ret_in_a_loop_leaves_the_loop_and_the_subroutine(backend):
    # rep 5 adds 1 to x and returns once x >= vPos.x: x = max(px, 1) up to 5; pixels whose
    # loop runs out (px 6, 7) go on to add 100 to y
    src = """ps_3_0
    dcl vPos.xy
    defi i0, 5, 0, 0, 0
    def c1, 1, 0, 0, 0
    def c2, 0, 100, 0, 0
    def c3, 0, 0, 0, 1
    mov r0, c3
    call l0
    mov oC0, r0
    ret
    label l0
    rep i0
        add r0, r0, c1
        if_ge r0.x, vPos.x
            ret
        endif
    endrep
    add r0, r0, c2
    ret
    """
    image = draw(backend, src, size=(8, 1))
    np.testing.assert_array_equal(image[0, :, :2], [[1, 0], [1, 0], [2, 0], [3, 0], [4, 0],
                                                    [5, 0], [5, 100], [5, 100]])


def test_an_early_ret_in_the_main_program_ends_it(backend):
    src = """ps_3_0
    dcl vPos.xy
    def c0, 2, 0, 0, 0
    def c1, 1, 0, 0, 1
    def c2, 0, 1, 0, 1
    mov oC0, c1
    if_lt vPos.x, c0.x
        ret
    endif
    mov oC0, c2
    """
    image = draw(backend, src, size=(4, 1))
    np.testing.assert_array_equal(image[0], [[1, 0, 0, 1]] * 2 + [[0, 1, 0, 1]] * 2)


def test_inputs_and_outputs_addressed_by_al(backend):
    # vs_3_0: aL = 1, 2, 3 sums v[aL] (texcoord0..2 = x, y, z unit vectors) into r0 and
    # writes each partial sum to o[aL]: o1 = (1,0,0,0), o2 = (1,1,0,0), o3 = (1,1,1,0).
    # ps_3_0: aL = 0, 1, 2 reads v[aL] (those three) as dp3 with (1, 10, 100) = 1, 11, 111,
    # adding each to r0 and then multiplying y by 10: x = 1 + 11 + 111 = 123,
    # y = ((1 * 10 + 11) * 10 + 111) * 10 = 3210.
    vs_src = """vs_3_0
    dcl_position v0
    dcl_texcoord0 v1
    dcl_texcoord1 v2
    dcl_texcoord2 v3
    dcl_position o0
    dcl_texcoord0 o1
    dcl_texcoord1 o2
    dcl_texcoord2 o3
    defi i0, 3, 1, 1, 0
    def c0, 0, 0, 0, 0
    mov o0, v0
    mov r0, c0
    loop aL, i0
        add r0, r0, v[aL]
        mov o[aL], r0
    endloop
    """
    ps_src = """ps_3_0
    dcl_texcoord0 v0
    dcl_texcoord1 v1
    dcl_texcoord2 v2
    defi i0, 3, 0, 1, 0
    def c0, 0, 0, 0, 0
    def c1, 1, 10, 100, 0
    mov r0, c0
    loop aL, i0
        dp3 r1.x, v[aL], c1
        add r0, r0, r1.x
        mul r0.y, r0.y, c1.y
    endloop
    mov oC0, r0
    """
    vs = assemble(ShaderBlock("vertex", None, vs_src, location=Location("t.fx", 1, 1)))
    assert [str(e) for e in check(vs) + lowering_problems(vs)] == []
    from effects.shaders.asm.lower import lower_vertex_shader
    passp = PassProgram(program(ps_src), vertex=lower_vertex_shader(
        vs, ShaderContext(LoweringOptions(), constant_prefix="vc")), render_state=NO_CULL)
    streams, indices, primitive = quad()
    units = np.eye(4, dtype=np.float32)
    streams = {"position": np.hstack([streams["position"], np.ones((4, 1), np.float32)]),
               **{f"texcoord{k}": np.tile(units[k], (4, 1)) for k in range(3)}}
    backend.begin_frame((2, 2), (0, 0, 0, 0), 1.0, 0, format=FLOAT)
    backend.draw(passp, streams, indices, primitive, {})
    image = backend.end_frame()
    np.testing.assert_array_equal(image.reshape(-1, 4), [[123, 3210, 123, 123]] * 4)


def test_relative_inputs_need_al():
    # D3D indexes v# / o# by aL only (vs_3_0 / ps_3_0); the checker or the lowering says so
    src = "vs_3_0\ndcl_position v0\ndcl_position o0\nmova a0.x, v0.x\nmov o0, v[a0.x]"
    prog = assemble(ShaderBlock("vertex", None, src, location=Location("t.fx", 1, 1)))
    assert [e.location.line for e in check(prog) or lowering_problems(prog)] == [5]


def test_gradients_after_an_early_ret_in_a_dynamic_if_are_rejected():
    src = EARLY_RET_IF.replace("add r0, r0, c2\nret", "dsx r1, vPos\nadd r0, r0, c2\nret")
    prog = assemble(ShaderBlock("pixel", None, src, location=Location("t.fx", 1, 1)))
    assert [str(e) for e in lowering_problems(prog)] == [
        "t.fx:17:1: error: dsx: gradients inside dynamic flow control are undefined (X4014: "
        "move it out of the if or loop, or use texldl / texldd)"]


def test_ir_rejects_badly_nested_blocks_and_out_of_scope_values():
    from effects.program.ir import Builder
    b = Builder("fragment")
    with pytest.raises(IRError, match="without its opening"):
        b.endif()
    b = Builder("fragment")
    one = b.const(1.0)
    b.if_(one)
    inside = b.add(one, one)
    b.endif()
    assert b.add(one, one) != inside            # not shared across the block's end
    b.output("color0", inside)
    with pytest.raises(IRError, match="undefined %1"):     # out of scope after endif
        b.build()
    b = Builder("fragment")
    with pytest.raises(IRError, match="outside a loop"):
        b.break_(b.const(1.0))
        b.output("color0", b.const(0.0))
        b.build()


# -- gradients ---------------------------------------------------------------------------------

def test_dsx_dsy_of_a_ramp(backend):
    # vPos.x * 3 + vPos.y * 5 (c0 = (3, 5)): d/dx = 3, d/dy = 5 at every pixel; the squared
    # ramp (vPos.x)^2 has d/dx = (x + 1)^2 - x^2 = 2x + 1 over the quad's pixel pair, x even.
    src = """ps_3_0
    dcl vPos.xy
    def c0, 3, 5, 0, 0
    def c1, 0, 0, 0, 1
    mul r0, vPos.xxxx, c0.x
    mad r0, vPos.yyyy, c0.y, r0
    mul r1, vPos.x, vPos.x
    dsx r2, r0
    dsy r3, r0
    dsx r4, r1
    mov r5, c1
    mov r5.x, r2.x
    mov r5.y, r3.x
    mov r5.z, r4.x
    mov oC0, r5
    """
    image = draw(backend, src, size=(8, 4))
    x0 = (np.arange(8) // 2) * 2                        # the left pixel of each quad
    assert (image[..., 0] == 3).all() and (image[..., 1] == 5).all()
    np.testing.assert_array_equal(image[0, :, 2], 2 * x0 + 1)


def test_gradients_in_dynamic_flow_control_are_rejected_located():
    src = ("ps_3_0\ndcl vPos.xy\ndcl_2d s0\ndef c0, 4, 0, 0, 0\nif_lt vPos.x, c0.x\n"
           "dsx r0, vPos\ntexld r1, vPos, s0\ntexldl r2, vPos, s0\nendif\nmov oC0, c0")
    prog = assemble(ShaderBlock("pixel", None, src, location=Location("t.fx", 1, 1)))
    assert [str(e) for e in lowering_problems(prog)] == [
        f"t.fx:{line}:1: error: {op}: gradients inside dynamic flow control are undefined "
        "(X4014: move it out of the if or loop, or use texldl / texldd)"
        for line, op in ((6, "dsx"), (7, "texld"))]
    static = src.replace("if_lt vPos.x, c0.x", "defb b0, true\nif b0")
    assert lowering_problems(assemble(ShaderBlock("pixel", None, static,
                                                  location=Location("t.fx", 1, 1)))) == []


# -- the rest of SM3 ---------------------------------------------------------------------------

@pytest.mark.parametrize("version, expected", [("3_0", 1.0), ("2_0", 0.5)])
def test_sm3_colour_interpolators_are_not_clamped(backend, version, expected):
    # The vertex shader writes colour 2; the pixel shader halves it. vs_3_0 / ps_3_0 keep 2
    # (1.0 out); vs_2_0 / ps_2_0 saturate the colour interpolator first (0.5 out).
    from effects.shaders.asm.lower import lower_vertex_shader
    out = "o1" if version == "3_0" else "oD0"
    decl = "dcl_position o0\ndcl_color o1\n" if version == "3_0" else ""
    position = "o0" if version == "3_0" else "oPos"
    vsrc = f"vs_{version}\ndcl_position v0\n{decl}def c0, 2, 2, 2, 2\nmov {position}, v0\nmov {out}, c0"
    psrc = (f"ps_{version}\n" + ("dcl_color v0\n" if version == "3_0" else "dcl v0\n") +
            "def c0, 0.5, 0.5, 0.5, 0.5\nmul r0, v0, c0\nmov oC0, r0")
    block = ShaderBlock("vertex", None, vsrc, location=Location("t.fx", 1, 1))
    vertex = lower_vertex_shader(assemble(block), ShaderContext(LoweringOptions(),
                                                               constant_prefix="vc"))
    fragment = lower_pixel_shader(assemble(ShaderBlock("pixel", None, psrc,
                                                       location=Location("t.fx", 1, 1))),
                                  ShaderContext(LoweringOptions()))
    assert vertex.clamp_colors == (version != "3_0")
    passp = PassProgram(fragment, vertex=vertex, render_state=NO_CULL)
    backend.begin_frame((2, 2), (0, 0, 0, 0), 1.0, 0, format=FLOAT)
    streams, indices, primitive = quad()
    streams["position"] = np.hstack([streams["position"], np.ones((4, 1), np.float32)])
    backend.draw(passp, streams, indices, primitive, {})
    image = backend.end_frame()
    np.testing.assert_allclose(image[..., :3], expected)


# -- the cards' flow-control caps ---------------------------------------------------------------

def _vs_effect(body: str):
    from effects import load_effect
    return load_effect("technique T { pass P { VertexShader = asm {\nvs_2_0\ndcl_position v0\n"
                       "defi i0, 2, 0, 1, 0\nmov r0, v0\n" + body + "\nmov oPos, r0\n}; } }")


def test_static_flow_depth_is_the_cards_vs20caps():
    from effects import load_profile
    one = _vs_effect("loop aL, i0\nadd r0, r0, c0\nendloop")
    two = _vs_effect("loop aL, i0\nrep i0\nadd r0, r0, c0\nendrep\nendloop")
    r9700, fx = load_profile("radeon9700"), load_profile("geforcefx5900")
    assert one.validate("T", r9700).ok                 # the loop: valid, and renders
    hardware = one.validate("T", r9700).pass_reports[0]
    assert not hardware.software_vertex_processing
    assert two.validate("T", fx).ok and not two.validate("T", fx).pass_reports[0] \
        .software_vertex_processing                    # StaticFlowControlDepth 4
    # StaticFlowControlDepth 1: over the hardware's limit, so software vertex processing
    nested = two.validate("T", r9700)
    assert nested.ok and nested.pass_reports[0].software_vertex_processing


def test_dynamic_flow_depth_is_the_cards_ps20caps():
    from effects import load_effect, load_profile
    effect = load_effect("technique T { pass P { PixelShader = asm {\nps_2_x\ndcl t0\n"
                         "def c0, 0, 0, 0, 1\nmov r0, c0\nif_lt t0.x, c0.x\nmov r0, t0\n"
                         "endif\nmov oC0, r0\n}; } }")
    assert effect.validate("T", load_profile("geforce6800")).ok
    result = effect.validate("T", load_profile("geforcefx5900"))   # ps_2_a: depth 0
    assert not result.ok
    assert "the pixel shader nests dynamic flow control 1 deep; the GeForce FX 5900 has " \
        "DynamicFlowControlDepth 0" in [str(r).split("): ", 1)[1] for r in result.reasons]


def test_texldd_takes_the_lod_from_its_gradients(backend):
    # A 4x4 texture with three mip levels of one colour each (red, green, blue), point mip
    # filtering: d coord/dx = (g, 0) is 4g texels per pixel, LOD log2(4g): g = 0 -> level 0,
    # g = 0.5 -> level 1 (LOD 1), g = 1 -> level 2 (LOD 2).
    from effects.program.texture import Texture
    from effects.program.passprogram import TextureBinding
    levels = [np.broadcast_to(np.array(c, np.float32), (n, n, 4)).copy()
              for c, n in (((1, 0, 0, 1), 4), ((0, 1, 0, 1), 2), ((0, 0, 1, 1), 1))]
    texture = Texture("2d", "A32B32G32R32F", levels)
    src = """ps_3_0
    dcl vPos.xy
    dcl_2d s0
    def c1, 0, 0, 0, 0
    def c2, 0.25, 0.25, 0, 0
    texldd r0, c2, s0, c0, c1
    mov oC0, r0
    """
    fragment = program(src)
    binding = TextureBinding(0, "t", min_filter="POINT", mag_filter="POINT", mip_filter="POINT")
    for g, expected in ((0.0, (1, 0, 0, 1)), (0.5, (0, 1, 0, 1)), (1.0, (0, 0, 1, 1))):
        passp = PassProgram(fragment, render_state=NO_CULL, textures=(binding,),
                            uniforms=PassProgram.pack_uniforms({"c0": [g, 0, 0, 0]}))
        backend.begin_frame((2, 2), (0, 0, 0, 0), 1.0, 0, format=FLOAT)
        backend.draw(passp, *quad(), {"t": texture})
        np.testing.assert_array_equal(backend.end_frame()[0, 0], expected, err_msg=str(g))


@pytest.mark.parametrize("direction, gradient, expected", [
    # +Z face (s = (x / |z| + 1) / 2): a gradient (g, 0, 0) moves s by g / 2, 8 * g / 2 texels
    ((0, 0, 1), (0.25, 0, 0), 0), ((0, 0, 1), (0.5, 0, 0), 1), ((0, 0, 1), (1, 0, 0), 2),
    # along the major axis at x = 0.5: ds = -(x / z^2) dz / 2 = -g / 4, 8 * g / 4 texels
    ((0.5, 0, 1), (0, 0, 0.5), 0), ((0.5, 0, 1), (0, 0, 1), 1), ((0.5, 0, 1), (0, 0, 2), 2),
    # -X face (s = (-z / |x| + 1) / 2, t = (-y / |x| + 1) / 2): a gradient in y moves t
    ((-1, 0, 0), (0, 0.5, 0), 1),
])
def test_texldd_on_a_cube_map_carries_the_gradients_onto_the_face(backend, direction,
                                                                  gradient, expected):
    # An 8x8 cube map whose four mip levels are red, green, blue, white on every face, point
    # mip filtering: the LOD is log2(8 |(ds, dt)|) with (ds, dt) the face-coordinate change
    # the direction gradient makes (the OpenGL rule; D3D9 leaves the cube case unspecified)
    from effects.program.texture import Texture
    from effects.program.passprogram import TextureBinding
    colours = ((1, 0, 0, 1), (0, 1, 0, 1), (0, 0, 1, 1), (1, 1, 1, 1))
    levels = [np.broadcast_to(np.array(c, np.float32), (6, n, n, 4)).copy()
              for c, n in zip(colours, (8, 4, 2, 1))]
    texture = Texture("cube", "A32B32G32R32F", levels)
    src = """ps_3_0
    dcl vPos.xy
    dcl_cube s0
    texldd r0, c2, s0, c0, c1
    mov oC0, r0
    """
    binding = TextureBinding(0, "t", kind="cube", min_filter="POINT", mag_filter="POINT",
                             mip_filter="POINT")
    passp = PassProgram(program(src), render_state=NO_CULL, textures=(binding,),
                        uniforms=PassProgram.pack_uniforms(
                            {"c0": list(gradient) + [0], "c1": [0, 0, 0, 0],
                             "c2": list(direction) + [0]}))
    backend.begin_frame((2, 2), (0, 0, 0, 0), 1.0, 0, format=FLOAT)
    backend.draw(passp, *quad(), {"t": texture})
    np.testing.assert_array_equal(backend.end_frame()[0, 0], colours[expected])


def test_an_unclosed_block_is_a_validation_reason_not_a_crash():
    from effects import load_effect, load_profile
    effect = load_effect("technique T { pass P { PixelShader = asm {\nps_3_0\ndcl vPos.xy\n"
                         "def c0, 1, 1, 1, 1\nif_lt vPos.x, c0.x\nmov oC0, c0\n};\n"
                         "VertexShader = asm { vs_3_0\ndcl_position v0\ndcl_position o0\n"
                         "mov o0, v0 }; } }")
    result = effect.validate("T", load_profile("geforce6800"))
    assert [str(r) for r in result.reasons] == ["pass P (line 5): if is never closed by endif"]


# -- golden printed IR and GLSL of a flow-control program (a change in lowering shows as a diff)

GOLDEN = TESTS / "golden"
GOLDEN_SRC = """ps_3_0
dcl vPos.xy
defi i0, 2, 0, 1, 0
def c0, 1, 0, 0, 0
def c1, 0.5, 0.5, 0.5, 1
def c4, 4, 4, 4, 4
mov r0, c1
setp_lt p0, vPos.x, c4
loop aL, i0
    add r0.x, r0.x, c[aL].x
    break_ge r0.x, vPos.y
endloop
if_lt vPos.x, c4.x
    (p0) mul r0.y, r0.y, c0.x
else
    texkill -c1
endif
mov oC0, r0
"""


@pytest.mark.parametrize("kind", ["ir", "glsl"])
def test_flow_program_golden(kind):
    import os
    from backends.gl.glsl import fragment_shader
    prog = program(GOLDEN_SRC)
    text = str(prog) if kind == "ir" else fragment_shader(prog)
    path = GOLDEN / kind / ("flow_loop_if_predicate." + ("txt" if kind == "ir" else "frag"))
    if os.environ.get("UPDATE_GOLDEN"):
        path.write_text(text)
    assert path.exists(), f"{path} missing: run with UPDATE_GOLDEN=1"
    assert text == path.read_text()


def test_flow_golden_program_draws_its_hand_values(backend):
    # r0.x = 0.5 + c0.x (1) = 1.5, then breaks where 1.5 >= vPos.y (rows 0, 1); rows 2, 3 add
    # c1.x (0.5) too: 2.0. Columns px >= 4 take the else: texkill -c1 kills them (clear 0.25).
    fragment = program(GOLDEN_SRC)
    passp = PassProgram(fragment, render_state=NO_CULL)
    backend.begin_frame((8, 4), (0.25, 0.25, 0.25, 0.25), 1.0, 0, format=FLOAT)
    backend.draw(passp, *quad(), {})
    image = backend.end_frame()
    expected = np.where(np.arange(4)[:, None] < 2, 1.5, 2.0) * np.ones((4, 4))
    np.testing.assert_array_equal(image[:, :4, 0], expected)
    np.testing.assert_array_equal(image[:, :4, 1:], np.broadcast_to([0.5, 0.5, 1], (4, 4, 3)))
    assert (image[:, 4:] == 0.25).all()


def test_nested_loop_iterations_are_bounded_by_a_named_limit():
    # rep 255 inside rep 255 (65,025 runs) is within the default; a third level is not
    import effects.base.limits
    nest = "ps_3_0\ndefi i0, 255, 0, 0, 0\ndef c0, 1, 1, 1, 1\nmov r0, c0\n{open}add r0, r0, c0\n{close}mov oC0, r0"
    two = nest.format(open="rep i0\n" * 2, close="endrep\n" * 2)
    three = nest.format(open="rep i0\n" * 3, close="endrep\n" * 3)
    prog = lambda s: assemble(ShaderBlock("pixel", None, s, location=Location("t.fx", 1, 1)))
    assert lowering_problems(prog(two)) == []
    (problem,) = lowering_problems(prog(three))
    assert str(problem).startswith("t.fx:7:1: error: rep (nested 3 deep) has 16,581,375 "
                                   "iterations; the limit is 65,536 (limit shader_loop_iterations")
    with effects.base.limits.raised(shader_loop_iterations=17_000_000):
        assert lowering_problems(prog(three)) == []


def test_recursive_and_too_deep_calls_are_located_problems():
    prog = lambda s: assemble(ShaderBlock("pixel", None, s, location=Location("t.fx", 1, 1)))
    recursive = "ps_3_0\ndef c0, 1, 1, 1, 1\nmov r0, c0\ncall l0\nmov oC0, r0\nret\n" \
                "label l0\ncall l0\nret"
    (problem,) = lowering_problems(prog(recursive))
    assert str(problem) == ("t.fx:4:1: error: call l0: calls nest deeper than 4 (or recurse), "
                            "which Direct3D does not allow")
    chain = "".join(f"label l{k}\ncall l{k + 1}\nret\n" for k in range(4)) + "label l4\nret"
    deep = "ps_3_0\ndef c0, 1, 1, 1, 1\nmov r0, c0\ncall l0\nmov oC0, r0\nret\n" + chain
    assert [p.location.line for p in lowering_problems(prog(deep))] == [4]
