"""What only the GL back end has: its program cache and buffer reuse across draws (counted),
the error that names the Mesa packages when no context can be made, and whole scenes
compared with the NumPy reference by PSNR. The pixel rules themselves (pixel centres,
blending, stencil, sampling, fog ...) are tested on both back ends in test_backends_suite.py.

GL is required: without a context these tests fail with GLUnavailable (which names the Mesa
packages to install); they are never skipped.
"""
from __future__ import annotations

import moderngl
import numpy as np
import pytest

from backends.gl import GLBackend, GLUnavailable, context
from effects.program import ir
from effects.program.ir import Builder
from effects.program.passprogram import PassProgram, RenderState, TextureBinding
from effects.program.texture import Texture
from tests.backends.test_backends_suite import NO_CULL, quad, render, show, u8
from tests.backends.test_conformance import psnr

# The `gl` and `ref` fixtures (one back end of each per module) are in conftest.py.


# --------------------------------------------------------------------------------------------
# What a draw costs: compiles, IR digests, buffers


def test_changed_uniforms_do_not_recompile(gl):
    """New uniform values reach the pixels without compiling the shader again."""
    b = Builder("fragment")
    b.output("color0", b.uniform("Tint"))
    fragment = b.build()
    before = gl.compiles
    for value in ((1.0, 0.0, 0.0, 1.0), (0.0, 0.0, 1.0, 1.0)):
        program = PassProgram(fragment, render_state=NO_CULL,
                              uniforms=PassProgram.pack_uniforms({"Tint": value}))
        image = render(gl, [(program, quad())], size=(2, 2))
        np.testing.assert_array_equal(image[0, 0], u8(value))
    assert gl.compiles - before <= 1


def test_gl_redraws_of_a_pass_do_not_print_its_ir_again(monkeypatch):
    """The program cache is keyed by the IR's digest; a pass drawn again (lowering hands back
    the same Program objects) must not print and hash its IR again each draw."""
    gl = GLBackend()
    try:
        v = Builder("vertex")
        v.output("position", v.varying("position", "POSITION", 3))
        v.output("texcoord0", v.varying("texcoord0", "TEXCOORD0", 2))
        program = PassProgram(show("texcoord0").fragment, vertex=v.build(), render_state=NO_CULL)
        first = render(gl, [(program, quad())])
        calls = []
        original = ir.Program.key
        monkeypatch.setattr(ir.Program, "key", lambda self: calls.append(self) or original(self))
        again = render(gl, [(program, quad())])
        assert calls == []
        np.testing.assert_array_equal(first, again)
    finally:
        gl.close()


def test_gl_redraws_reuse_buffers_and_keep_each_passes_uniforms(monkeypatch):
    """A frame drawn again makes no new GL buffers or vertex arrays; passes that share a
    shader but not their uniform values (A, B, A in one frame) each draw with their own."""
    gl = GLBackend()
    try:
        b = Builder("fragment")
        b.output("color0", b.uniform("Tint"))
        fragment = b.build()

        def tinted(colour):
            return PassProgram(fragment, render_state=NO_CULL,
                               uniforms=PassProgram.pack_uniforms({"Tint": colour}))

        red, blue = tinted((1.0, 0.0, 0.0, 1.0)), tinted((0.0, 0.0, 1.0, 1.0))
        draws = [(red, quad(-1, -1, -0.5, 1)), (blue, quad(-0.5, -1, 0.5, 1)),
                 (red, quad(0.5, -1, 1, 1))]
        first = render(gl, draws)
        made = []
        for name in ("buffer", "vertex_array"):
            def counted(*args, _original=getattr(gl.ctx, name), **kwargs):
                made.append(args)
                return _original(*args, **kwargs)
            monkeypatch.setattr(gl.ctx, name, counted)
        again = render(gl, draws)
        assert made == []
        np.testing.assert_array_equal(first, again)
        assert first[0, 0].tolist() == [255, 0, 0, 255]       # x < 2: the first red quad
        assert first[0, 4].tolist() == [0, 0, 255, 255]       # the blue one
        assert first[0, 7].tolist() == [255, 0, 0, 255]       # red again, after blue
    finally:
        gl.close()


# --------------------------------------------------------------------------------------------
# No GL: a clear error


def test_no_gl_is_a_clear_error(monkeypatch):
    def fail(**kwargs):
        raise Exception("eglGetDisplay failed")
    monkeypatch.setattr(context, "_headless", None)
    monkeypatch.setattr(moderngl, "create_standalone_context", fail)
    with pytest.raises(GLUnavailable) as info:
        GLBackend()
    message = str(info.value)
    assert message.startswith("<gl>:0:0: error: no headless OpenGL 3.3 context")
    assert "eglGetDisplay failed" in message
    assert "libegl1" in message and "libgl1-mesa-dri" in message and "libegl-mesa0" in message


# --------------------------------------------------------------------------------------------


# The same passes through the reference back end


def _checker(size: int) -> Texture:
    y, x = np.mgrid[0:size, 0:size]
    level = np.zeros((size, size, 4), np.float32)
    level[..., 0] = ((x // 4 + y // 4) % 2) * 0.8 + 0.1
    level[..., 1] = x / size
    level[..., 2] = y / size
    level[..., 3] = 1
    levels = [level]
    while levels[-1].shape[0] > 1:
        prev = levels[-1]
        levels.append(0.25 * (prev[0::2, 0::2] + prev[1::2, 0::2] + prev[0::2, 1::2]
                              + prev[1::2, 1::2]))
    return Texture("2d", "A32B32G32R32F", levels)


def _perspective_floor():
    """A textured quad receding in depth (w from 1 to 4), trilinear filtered and tiled. Its
    edges avoid passing exactly through pixel centres: there the owner of a pixel depends on
    the rasterisers' sub-pixel snapping (GL and the reference differ by 1/4096 pixel), and a
    pixel on the diagonal would take its LOD from the other triangle's plane."""
    w = np.array([1, 1, 4, 4], np.float32)[:, None]
    ndc = np.array([[-0.97, -0.98, 0.2], [0.99, -0.97, 0.2], [-0.53, 0.77, 0.9],
                    [0.51, 0.79, 0.9]], np.float32)
    streams = {"position": np.concatenate([ndc * w, w], axis=1),
               "texcoord0": np.array([[0, 4], [4, 4], [0, 0], [4, 0]], np.float32)}
    b = Builder("fragment")
    texel = b.sample(0, b.varying("texcoord0"))
    b.output("color0", b.mul(texel, b.varying("color0")))
    binding = TextureBinding(0, "checker", min_filter="LINEAR", mag_filter="LINEAR",
                             mip_filter="LINEAR")
    program = PassProgram(b.build(), render_state=RenderState(), textures=(binding,))
    return program, (streams, np.array([0, 2, 1, 3]), "strip"), {"checker": _checker(32)}


def _n_dot_l_sphere():
    """A lit sphere: vertex program scales the unit sphere into clip space; the fragment
    program normalises the interpolated normal, dots it with the light and adds a specular
    power, all in float."""
    from effects.assets.meshes import sphere
    mesh = sphere(12, 24)
    v = Builder("vertex")
    p = v.varying("position", "POSITION", 3)
    scale = v.uniform("scale")
    clip = v.merge(v.add(v.mul(p, scale), v.const((0, 0, 0.5, 0))), v.const(1.0), "w")
    v.output("position", clip)
    v.output("texcoord0", v.varying("normal", "NORMAL", 3))
    f = Builder("fragment")
    n = f.nrm(f.varying("texcoord0"))
    ndl = f.saturate(f.dp3(n, f.uniform("light")))
    spec = f.pow(ndl, f.const(16.0))
    f.output("color0", f.merge(f.mad(ndl, f.uniform("diffuse"), spec), f.const(1.0), "w"))
    uniforms = PassProgram.pack_uniforms({"scale": (0.8, 0.8, 0.4, 1),
                                          "light": (0.48, 0.64, -0.6, 0),
                                          "diffuse": (0.9, 0.6, 0.3, 1)})
    program = PassProgram(f.build(), vertex=v.build(), render_state=RenderState(cull_mode="NONE"),
                          uniforms=uniforms)
    streams = {"position": mesh.positions, "normal": mesh.normals}
    return program, (streams, mesh.indices, "list"), {}


def _ps11_multipass():
    """Fixed-point pass (9-bit signed grid, clamp to [-1, 1]) then an additive second pass
    with an alpha test, over a vertex-coloured quad."""
    b = Builder("fragment")
    c = b.varying("color0")
    bx2 = b.mad(c, b.const(2.0), b.const(-1.0))
    r0 = b.quantize(b.clamp(b.dp3(bx2, b.uniform("c0")), -1, 1), bits=9, signed=True)
    b.output("color0", b.merge(b.saturate(r0), c, "w"))
    first = PassProgram(b.build(), render_state=NO_CULL,
                        uniforms=PassProgram.pack_uniforms({"c0": (0.6, 0.8, 0.0, 0)}))
    second = PassProgram(show("color0").fragment, render_state=RenderState(
        cull_mode="NONE", alpha_blend_enable=True, src_blend="SRCALPHA", dest_blend="ONE",
        alpha_test_enable=True, alpha_func="GREATER", alpha_ref=60, z_func="LESSEQUAL"))
    colours = np.array([[1, 0.2, 0.5, 0.1], [0.1, 1, 0.3, 0.9], [0.4, 0.4, 1, 0.5],
                        [0.9, 0.7, 0.1, 0.2]], np.float32)
    geometry = quad(color0=colours)
    return [(first, geometry), (second, geometry)], {}


CROSS_CASES = {
    "perspective_trilinear": lambda: ([_perspective_floor()[:2]], _perspective_floor()[2], False),
    "n_dot_l_sphere": lambda: ([_n_dot_l_sphere()[:2]], {}, True),
    "ps11_multipass": lambda: (*_ps11_multipass(), True),
}


@pytest.mark.parametrize("name", sorted(CROSS_CASES))
def test_gl_agrees_with_the_reference(gl, ref, name):
    draws, textures, exact = CROSS_CASES[name]()
    images = [render(backend, draws, size=(64, 48), clear=(0.1, 0.1, 0.1, 1),
                     textures=textures) for backend in (gl, ref)]
    assert psnr(*images) >= 40.0, name
    if exact:  # no LOD estimate involved: every pixel within 2/255
        diff = np.abs(images[0].astype(int) - images[1].astype(int))
        assert diff.max() <= 2, (name, np.argwhere(diff > 2)[:5])
    assert images[0].std() > 10  # the scene is not blank
