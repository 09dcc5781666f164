"""Direct3D 9 render and sampler states as OpenGL state: tables from D3D enum names to GL.

The tables follow the D3D9 documentation of D3DBLEND, D3DBLENDOP, D3DCMPFUNC, D3DSTENCILOP,
D3DTEXTUREADDRESS and D3DTEXTUREFILTERTYPE; the merge rules (what each one means for a pixel)
are those of the reference back end's output merger. The vertex shader renders D3D's clockwise
triangles counter-clockwise in GL's window (see `glsl`), so GL's front faces are D3D's.

Alpha test, depth bias and sRGB writes are not GL state here: they are fragment-shader
epilogues (`glsl.FragmentOptions`), as in Wine's and DXVK's shaders. Fog and the specular add
are already in the lowered fragment program.
"""
from __future__ import annotations

from dataclasses import dataclass

from effects.program.passprogram import RenderState, TextureBinding

from backends.gl import rawgl as G
from backends.gl.rawgl import RawGL

BLEND_FACTORS = {
    "ZERO": G.ZERO, "ONE": G.ONE,
    "SRCCOLOR": G.SRC_COLOR, "INVSRCCOLOR": G.ONE_MINUS_SRC_COLOR,
    "SRCALPHA": G.SRC_ALPHA, "INVSRCALPHA": G.ONE_MINUS_SRC_ALPHA,
    "DESTALPHA": G.DST_ALPHA, "INVDESTALPHA": G.ONE_MINUS_DST_ALPHA,
    "DESTCOLOR": G.DST_COLOR, "INVDESTCOLOR": G.ONE_MINUS_DST_COLOR,
    "SRCALPHASAT": G.SRC_ALPHA_SATURATE,
    # The obsolete BOTH* factors as a source blend also set the destination factor.
    "BOTHSRCALPHA": G.SRC_ALPHA, "BOTHINVSRCALPHA": G.ONE_MINUS_SRC_ALPHA,
    "BLENDFACTOR": G.CONSTANT_COLOR, "INVBLENDFACTOR": G.ONE_MINUS_CONSTANT_COLOR,
    "SRCCOLOR2": G.SRC1_COLOR, "INVSRCCOLOR2": G.ONE_MINUS_SRC1_COLOR,
}
BOTH_DEST = {"BOTHSRCALPHA": G.ONE_MINUS_SRC_ALPHA, "BOTHINVSRCALPHA": G.SRC_ALPHA}
BLEND_OPS = {"ADD": G.FUNC_ADD, "SUBTRACT": G.FUNC_SUBTRACT,
             "REVSUBTRACT": G.FUNC_REVERSE_SUBTRACT, "MIN": G.MIN, "MAX": G.MAX}
COMPARE = {"NEVER": G.NEVER, "LESS": G.LESS, "EQUAL": G.EQUAL, "LESSEQUAL": G.LEQUAL,
           "GREATER": G.GREATER, "NOTEQUAL": G.NOTEQUAL, "GREATEREQUAL": G.GEQUAL,
           "ALWAYS": G.ALWAYS}
STENCIL_OPS = {"KEEP": G.KEEP, "ZERO": G.ZERO, "REPLACE": G.REPLACE, "INCRSAT": G.INCR,
               "DECRSAT": G.DECR, "INVERT": G.INVERT, "INCR": G.INCR_WRAP, "DECR": G.DECR_WRAP}
FILL_MODES = {"POINT": G.POINT, "WIREFRAME": G.LINE, "SOLID": G.FILL}
# D3DCULL names the winding that is culled; D3D's clockwise is GL's front here.
CULL_FACES = {"CW": G.FRONT, "CCW": G.BACK}
ADDRESS_MODES = {"WRAP": G.REPEAT, "MIRROR": G.MIRRORED_REPEAT, "CLAMP": G.CLAMP_TO_EDGE,
                 "BORDER": G.CLAMP_TO_BORDER, "MIRRORONCE": G.MIRROR_CLAMP_TO_EDGE}
# Filters other than POINT / NONE (LINEAR, ANISOTROPIC, the quad filters) filter linearly, as
# the reference sampler does.
_POINT_FILTERS = ("POINT", "NONE")


def _lookup(table: dict, name: str, what: str) -> int:
    try:
        return table[name]
    except KeyError:
        raise ValueError(f"{what} must be one of {sorted(table)}, got {name!r}") from None


def apply_render_state(gl: RawGL, state: RenderState) -> None:
    """Set depth, stencil, cull, fill, blend and colour-mask state for a draw."""
    gl.set_enabled(G.DEPTH_TEST, state.z_enable)
    gl.glDepthFunc(_lookup(COMPARE, state.z_func, "ZFunc"))
    gl.glDepthMask(bool(state.z_enable and state.z_write_enable))

    gl.set_enabled(G.CULL_FACE, state.cull_mode != "NONE")
    if state.cull_mode != "NONE":
        gl.glCullFace(_lookup(CULL_FACES, state.cull_mode, "CullMode"))
    gl.glFrontFace(G.CCW)
    gl.glPolygonMode(G.FRONT_AND_BACK, _lookup(FILL_MODES, state.fill_mode, "FillMode"))

    _apply_stencil(gl, state)
    _apply_blend(gl, state)
    mask = int(state.color_write_enable)
    gl.glColorMask(bool(mask & 1), bool(mask & 2), bool(mask & 4), bool(mask & 8))


def _apply_stencil(gl: RawGL, state: RenderState) -> None:
    gl.set_enabled(G.STENCIL_TEST, state.stencil_enable)
    if not state.stencil_enable:
        return
    ref = int(state.stencil_ref) & 0xFF
    read_mask = int(state.stencil_mask) & 0xFF
    write_mask = int(state.stencil_write_mask) & 0xFF
    clockwise = (state.stencil_func, state.stencil_fail, state.stencil_zfail, state.stencil_pass)
    counter = ((state.ccw_stencil_func, state.ccw_stencil_fail, state.ccw_stencil_zfail,
                state.ccw_stencil_pass) if state.two_sided_stencil_mode else clockwise)
    for face, (func, fail, zfail, pass_) in ((G.FRONT, clockwise), (G.BACK, counter)):
        gl.glStencilFuncSeparate(face, _lookup(COMPARE, func, "StencilFunc"), ref, read_mask)
        gl.glStencilOpSeparate(face, _lookup(STENCIL_OPS, fail, "StencilFail"),
                               _lookup(STENCIL_OPS, zfail, "StencilZFail"),
                               _lookup(STENCIL_OPS, pass_, "StencilPass"))
        gl.glStencilMaskSeparate(face, write_mask)


def _blend_factors(src: str, dest: str) -> tuple[int, int]:
    return (_lookup(BLEND_FACTORS, src, "SrcBlend"),
            BOTH_DEST.get(src) or _lookup(BLEND_FACTORS, dest, "DestBlend"))


def _apply_blend(gl: RawGL, state: RenderState) -> None:
    gl.set_enabled(G.BLEND, state.alpha_blend_enable)
    if not state.alpha_blend_enable:
        return
    src, dest = _blend_factors(state.src_blend, state.dest_blend)
    op = _lookup(BLEND_OPS, state.blend_op, "BlendOp")
    if state.separate_alpha_blend_enable:
        src_a, dest_a = _blend_factors(state.src_blend_alpha, state.dest_blend_alpha)
        op_a = _lookup(BLEND_OPS, state.blend_op_alpha, "BlendOpAlpha")
    else:
        src_a, dest_a, op_a = src, dest, op
    gl.glBlendFuncSeparate(src, dest, src_a, dest_a)
    gl.glBlendEquationSeparate(op, op_a)
    gl.glBlendColor(*(float(c) for c in state.blend_factor))


def reset_for_clear(gl: RawGL) -> None:
    """Let a clear reach every channel, depth and stencil bit (D3D's Clear ignores the masks)."""
    gl.glColorMask(True, True, True, True)
    gl.glDepthMask(True)
    gl.glStencilMaskSeparate(G.FRONT_AND_BACK, 0xFF)


# --------------------------------------------------------------------------------------------
# Samplers


@dataclass(frozen=True)
class SamplerKey:
    """The GL sampler-object parameters of one TextureBinding (a cache key), and the base
    level to set on the texture it samples."""

    kind: str
    wrap: tuple[int, int, int]
    min_filter: int
    mag_filter: int
    lod_bias: float
    min_lod: float
    border: tuple[float, float, float, float]
    base_level: int


def sampler_key(binding: TextureBinding | None, kind: str, level_count: int) -> SamplerKey:
    """GL sampler parameters for a binding (None: D3D's default sampler states).

    MaxMipLevel k (as the reference sampler reads it): the LOD is measured on level 0 and the
    level index is clamped to >= k. With a mip filter that is GL's TEXTURE_MIN_LOD = k. Without
    one, level k is sampled: it becomes the texture's base level, and since GL measures the LOD
    on the base level, the bias grows by k so the magnify/minify choice stays on level 0."""
    b = binding or TextureBinding(sampler=0, kind=kind)
    if kind == "cube":
        wrap = (G.CLAMP_TO_EDGE,) * 3      # D3D9 cube maps clamp within a face
    else:
        wrap = tuple(_lookup(ADDRESS_MODES, m, "AddressU/V/W")
                     for m in (b.address_u, b.address_v, b.address_w))
    k = min(max(int(b.max_mip_level), 0), max(level_count - 1, 0))
    min_linear = b.min_filter not in _POINT_FILTERS
    mag_filter = G.NEAREST if b.mag_filter in _POINT_FILTERS else G.LINEAR
    bias = float(b.mip_lod_bias)
    border = tuple(float(c) for c in b.border_color)
    if b.mip_filter == "NONE" or level_count - k <= 1:
        min_filter = G.LINEAR if min_linear else G.NEAREST
        return SamplerKey(kind, wrap, min_filter, mag_filter, bias + k, -1000.0, border, k)
    if b.mip_filter == "POINT":
        min_filter = G.LINEAR_MIPMAP_NEAREST if min_linear else G.NEAREST_MIPMAP_NEAREST
    else:
        min_filter = G.LINEAR_MIPMAP_LINEAR if min_linear else G.NEAREST_MIPMAP_LINEAR
    return SamplerKey(kind, wrap, min_filter, mag_filter, bias, float(k), border, 0)


def create_sampler(gl: RawGL, key: SamplerKey) -> int:
    """A GL sampler object with `key`'s parameters."""
    sampler = gl.gen("Samplers")
    for pname, value in zip((G.TEXTURE_WRAP_S, G.TEXTURE_WRAP_T, G.TEXTURE_WRAP_R), key.wrap):
        gl.glSamplerParameteri(sampler, pname, value)
    gl.glSamplerParameteri(sampler, G.TEXTURE_MIN_FILTER, key.min_filter)
    gl.glSamplerParameteri(sampler, G.TEXTURE_MAG_FILTER, key.mag_filter)
    gl.glSamplerParameterf(sampler, G.TEXTURE_LOD_BIAS, key.lod_bias)
    gl.glSamplerParameterf(sampler, G.TEXTURE_MIN_LOD, key.min_lod)
    # The maximum anisotropy stays at GL's default of 1: ANISOTROPIC filters as LINEAR, as in
    # the reference back end.
    gl.sampler_color(sampler, G.TEXTURE_BORDER_COLOR, key.border)
    return sampler
