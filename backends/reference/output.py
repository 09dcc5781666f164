"""The output merger: alpha test, stencil, depth, blending, colour mask and the
render-target write, in Direct3D 9's order (D3DRENDERSTATETYPE docs;
docs/reference/semantics.md section 0).

- Alpha test compares the fragment alpha quantised to 8 bits, round(sat(a) * 255), with
  AlphaRef: `alpha FUNC ref`.
- Stencil (8 bits): `(ref & mask) FUNC (stencil & mask)`; the op chosen by stencil fail /
  depth fail / pass is written through StencilWriteMask. With TwoSidedStencilMode the
  counter-clockwise (back-facing) triangles use the CCW_* func and ops.
- Depth: `z FUNC stored`; written only where stencil and depth pass and ZWriteEnable is set;
  with ZEnable off the depth test passes and nothing is written.
- Blending: `src * SrcBlend OP dst * DestBlend` per channel (MIN/MAX ignore the factors), the
  alpha channel with the *Alpha states when SeparateAlphaBlendEnable is set. On 8-bit targets
  the source is saturated first and the result is written as round(sat(x) * 255) / 255.
- Fragments of one draw that hit the same pixel are merged in draw order exactly: the k-th
  fragment of every pixel forms layer k, and each layer is merged vectorised.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from effects.program.passprogram import RenderState

from effects.program.backend import DrawError
from effects.program.formats import TARGET_FORMATS

COMPARE_FUNCS = ("NEVER", "LESS", "EQUAL", "LESSEQUAL", "GREATER", "NOTEQUAL", "GREATEREQUAL",
                 "ALWAYS")
STENCIL_OPS = ("KEEP", "ZERO", "REPLACE", "INCRSAT", "DECRSAT", "INVERT", "INCR", "DECR")
BLEND_OPS = ("ADD", "SUBTRACT", "REVSUBTRACT", "MIN", "MAX")
BLEND_FACTORS = ("ZERO", "ONE", "SRCCOLOR", "INVSRCCOLOR", "SRCALPHA", "INVSRCALPHA",
                 "DESTALPHA", "INVDESTALPHA", "DESTCOLOR", "INVDESTCOLOR", "SRCALPHASAT",
                 "BOTHSRCALPHA", "BOTHINVSRCALPHA", "BLENDFACTOR", "INVBLENDFACTOR",
                 "SRCCOLOR2", "INVSRCCOLOR2")


# ------------------------------------------------------------------------------------------------
# The render target

@dataclass
class Framebuffer:
    """The render target of a frame: colour (H, W, 4) as the format stores it (uint8 for the
    8-bit formats, float32 for the float ones; channels the format lacks read 1), depth (H, W)
    float32, stencil (H, W) uint8."""

    format: str
    color: np.ndarray
    depth: np.ndarray
    stencil: np.ndarray

    @staticmethod
    def create(size: tuple[int, int], format: str = "A8R8G8B8", clear_color=(0, 0, 0, 0),
               clear_depth: float = 1.0, clear_stencil: int = 0) -> "Framebuffer":
        if format not in TARGET_FORMATS:
            raise DrawError(f"render-target format must be one of {tuple(TARGET_FORMATS)}, "
                            f"got {format!r}")
        width, height = size
        if width <= 0 or height <= 0:
            raise DrawError(f"render-target size must be positive, got {size}")
        dtype = np.float32 if TARGET_FORMATS[format][0] else np.uint8
        fb = Framebuffer(format, np.empty((height, width, 4), dtype),
                         np.empty((height, width), np.float32), np.empty((height, width), np.uint8))
        fb.clear(clear_color, clear_depth, clear_stencil)
        return fb

    def clear(self, clear_color=(0, 0, 0, 0), clear_depth: float = 1.0,
              clear_stencil: int = 0) -> None:
        """Fill colour, depth and stencil with the clear values (as `create` makes them)."""
        clear = encode(np.asarray(clear_color, np.float32).reshape(1, 4), self.format)[0]
        if clear.dtype == np.uint8:   # one 32-bit word per pixel: a faster fill
            self.color.view(np.uint32)[...] = np.ascontiguousarray(clear).view(np.uint32)
        else:
            self.color[...] = clear
        self.depth.fill(np.float32(clear_depth))
        self.stencil.fill(int(clear_stencil) & 0xFF)

    @property
    def size(self) -> tuple[int, int]:
        return self.color.shape[1], self.color.shape[0]

    @property
    def is_float(self) -> bool:
        return TARGET_FORMATS[self.format][0]

    def values(self) -> np.ndarray:
        """The stored colours as float32 (H, W, 4): k/255 for the 8-bit formats."""
        return decode(self.color)

    def image(self) -> np.ndarray:
        """uint8 RGBA for 8-bit formats, float32 RGBA for float formats; row 0 at the top."""
        return self.color.copy()


def encode(values: np.ndarray, format: str) -> np.ndarray:
    """(N, 4) float colours as a target of `format` stores them: the UNORM8 write
    round(sat(x) * 255) as uint8, or float32 (float16-rounded for the half formats)."""
    is_float, channels = TARGET_FORMATS[format]
    if is_float:
        out = np.array(values, np.float32)
        if "16F" in format:      # R16F, G16R16F, A16B16G16R16F: s10e5 halves
            out = out.astype(np.float16).astype(np.float32)
        out[:, channels:] = 1
        return out
    out = np.minimum(values, np.float32(1))
    np.maximum(out, 0, out=out)
    out[np.isnan(out)] = 0  # NaN writes 0 to UNORM targets, as GL does
    out *= np.float32(255)
    np.rint(out, out=out)
    out = out.astype(np.uint8)
    out[:, channels:] = 255
    return out


def decode(stored: np.ndarray) -> np.ndarray:
    """Stored colours back as float32 (k/255 for uint8 storage)."""
    if stored.dtype == np.uint8:
        return stored.astype(np.float32) / np.float32(255)
    return np.array(stored, np.float32)


# ------------------------------------------------------------------------------------------------
# Tests and ops

def compare(a: np.ndarray, func: str, b: np.ndarray) -> np.ndarray:
    """`a FUNC b` as D3DCMPFUNC defines it (a: the incoming value, b: the reference/stored)."""
    if func == "NEVER":
        return np.zeros(np.broadcast(a, b).shape, bool)
    if func == "ALWAYS":
        return np.ones(np.broadcast(a, b).shape, bool)
    if func == "LESS":
        return a < b
    if func == "EQUAL":
        return a == b
    if func == "LESSEQUAL":
        return a <= b
    if func == "GREATER":
        return a > b
    if func == "NOTEQUAL":
        return a != b
    if func == "GREATEREQUAL":
        return a >= b
    raise DrawError(f"compare function must be one of {COMPARE_FUNCS}, got {func!r}")


def stencil_op(op: str, value: np.ndarray, ref: int) -> np.ndarray:
    """The new 8-bit stencil value for D3DSTENCILOP `op` (before the write mask)."""
    v = value.astype(np.int32)
    if op == "KEEP":
        return v
    if op == "ZERO":
        return np.zeros_like(v)
    if op == "REPLACE":
        return np.full_like(v, ref)
    if op == "INCRSAT":
        return np.minimum(v + 1, 255)
    if op == "DECRSAT":
        return np.maximum(v - 1, 0)
    if op == "INVERT":
        return ~v & 0xFF
    if op == "INCR":
        return (v + 1) & 0xFF
    if op == "DECR":
        return (v - 1) & 0xFF
    raise DrawError(f"stencil op must be one of {STENCIL_OPS}, got {op!r}")


def alpha_test(alpha: np.ndarray, func: str, ref: int) -> np.ndarray:
    """Which fragments pass: round(sat(alpha) * 255) FUNC AlphaRef (0..255)."""
    a8 = np.rint(np.clip(alpha, 0, 1) * 255).astype(np.int32)
    return compare(a8, func, np.int32(int(ref) & 0xFF))


def blend_factor(name: str, src: np.ndarray, dst: np.ndarray, constant: np.ndarray,
                 src2: np.ndarray | None = None) -> np.ndarray:
    """The (N, 4) per-channel factor of D3DBLEND `name` (alpha channel included: SRCCOLOR's
    alpha factor is the source alpha, SRCALPHASAT's is 1)."""
    sa, da = src[:, 3:4], dst[:, 3:4]
    if name == "ZERO":
        return np.zeros_like(src)
    if name == "ONE":
        return np.ones_like(src)
    if name == "SRCCOLOR":
        return src
    if name == "INVSRCCOLOR":
        return 1 - src
    if name in ("SRCALPHA", "BOTHSRCALPHA"):
        return np.broadcast_to(sa, src.shape)
    if name in ("INVSRCALPHA", "BOTHINVSRCALPHA"):
        return np.broadcast_to(1 - sa, src.shape)
    if name == "DESTALPHA":
        return np.broadcast_to(da, src.shape)
    if name == "INVDESTALPHA":
        return np.broadcast_to(1 - da, src.shape)
    if name == "DESTCOLOR":
        return dst
    if name == "INVDESTCOLOR":
        return 1 - dst
    if name == "SRCALPHASAT":
        f = np.minimum(sa, 1 - da)
        out = np.repeat(f, 4, axis=1)
        out[:, 3] = 1
        return out
    if name == "BLENDFACTOR":
        return np.broadcast_to(constant, src.shape)
    if name == "INVBLENDFACTOR":
        return np.broadcast_to(1 - constant, src.shape)
    if name in ("SRCCOLOR2", "INVSRCCOLOR2"):
        c2 = np.zeros_like(src) if src2 is None else src2
        return c2 if name == "SRCCOLOR2" else 1 - c2
    raise DrawError(f"blend factor must be one of {BLEND_FACTORS}, got {name!r}")


def _dest_factor_name(src_name: str, dest_name: str) -> str:
    # BOTHSRCALPHA / BOTHINVSRCALPHA as the source blend set the destination factor too.
    return {"BOTHSRCALPHA": "INVSRCALPHA", "BOTHINVSRCALPHA": "SRCALPHA"}.get(src_name, dest_name)


def _combine(op: str, s: np.ndarray, fs: np.ndarray, d: np.ndarray, fd: np.ndarray) -> np.ndarray:
    if op == "ADD":
        return s * fs + d * fd
    if op == "SUBTRACT":
        return s * fs - d * fd
    if op == "REVSUBTRACT":
        return d * fd - s * fs
    if op == "MIN":
        return np.minimum(s, d)
    if op == "MAX":
        return np.maximum(s, d)
    raise DrawError(f"blend op must be one of {BLEND_OPS}, got {op!r}")


def blend(state: RenderState, src: np.ndarray, dst: np.ndarray,
          src2: np.ndarray | None = None) -> np.ndarray:
    """Blend (N, 4) source colours over (N, 4) destination colours by `state`."""
    constant = np.asarray(state.blend_factor, np.float32)
    fs = blend_factor(state.src_blend, src, dst, constant, src2)
    fd = blend_factor(_dest_factor_name(state.src_blend, state.dest_blend), src, dst,
                      constant, src2)
    out = _combine(state.blend_op, src, fs, dst, fd)
    if state.separate_alpha_blend_enable:
        fsa = blend_factor(state.src_blend_alpha, src, dst, constant, src2)[:, 3:]
        fda = blend_factor(_dest_factor_name(state.src_blend_alpha, state.dest_blend_alpha),
                           src, dst, constant, src2)[:, 3:]
        out[:, 3:] = _combine(state.blend_op_alpha, src[:, 3:], fsa, dst[:, 3:], fda)
    return out.astype(np.float32)


# ------------------------------------------------------------------------------------------------
# Merging

def layers(pixels: np.ndarray, pixel_count: int) -> list[np.ndarray]:
    """Split fragment rows (in draw order) into layers: layer k holds the k-th fragment of each
    pixel, so no layer touches a pixel twice. Returns row-index arrays in layer order."""
    n = len(pixels)
    if n == 0:
        return []
    if np.bincount(pixels, minlength=pixel_count).max() <= 1:
        return [np.arange(n)]
    order = np.argsort(pixels, kind="stable")
    sorted_pixels = pixels[order]
    starts = np.r_[0, np.nonzero(np.diff(sorted_pixels))[0] + 1]
    lengths = np.diff(np.r_[starts, n])
    rank_sorted = np.arange(n) - np.repeat(starts, lengths)
    rank = np.empty(n, np.int64)
    rank[order] = rank_sorted
    by_rank = np.argsort(rank, kind="stable")  # rows of layer 0, then 1, ... each in draw order
    bounds = np.cumsum(np.bincount(rank))
    return np.split(by_rank, bounds[:-1])


def merge(fb: Framebuffer, state: RenderState, pixels: np.ndarray, color: np.ndarray,
          depth: np.ndarray, front: np.ndarray, color2: np.ndarray | None = None) -> None:
    """Merge fragments (in draw order) into `fb`. `pixels`: (N,) flat indices y*W + x;
    `color` (N, 4) the fragment program's colour; `depth` (N,) z;
    `front` (N,) whether each fragment's triangle is clockwise; `color2` the second colour
    output (for the SRCCOLOR2 blend factors)."""
    if state.alpha_test_enable:
        keep = alpha_test(color[:, 3], state.alpha_func, state.alpha_ref)
        if not keep.all():
            pixels, color, depth, front = pixels[keep], color[keep], depth[keep], front[keep]
            color2 = None if color2 is None else color2[keep]
    if len(pixels) == 0:
        return
    # Layers over the span of pixels this merge touches (a band of rows), not the whole frame.
    lo = int(pixels.min())
    split = layers(pixels - lo, int(pixels.max()) - lo + 1)
    if len(split) == 1:   # no pixel hit twice: one layer holding every row, in order
        _merge_layer(fb, state, pixels, color, depth, front, color2)
        return
    for rows in split:
        _merge_layer(fb, state, pixels[rows], color[rows], depth[rows], front[rows],
                     None if color2 is None else color2[rows])


def _stencil_state(state: RenderState, front: np.ndarray):
    """(func, fail, zfail, pass) per fragment: arrays of names where two-sided stencil differs."""
    cw = (state.stencil_func, state.stencil_fail, state.stencil_zfail, state.stencil_pass)
    if not state.two_sided_stencil_mode:
        return [(cw, None)]
    ccw = (state.ccw_stencil_func, state.ccw_stencil_fail, state.ccw_stencil_zfail,
           state.ccw_stencil_pass)
    return [(cw, front), (ccw, ~front)]


def _merge_layer(fb: Framebuffer, state: RenderState, pix: np.ndarray, color: np.ndarray,
                 depth: np.ndarray, front: np.ndarray, color2: np.ndarray | None) -> None:
    n = len(pix)
    passed = np.ones(n, bool)
    depth_pass = np.ones(n, bool)
    if state.z_enable:
        depth_pass = compare(depth, state.z_func, fb.depth.reshape(-1)[pix])
    if state.stencil_enable:
        stencil = fb.stencil.reshape(-1)
        old = stencil[pix]
        mask = int(state.stencil_mask) & 0xFF
        ref = int(state.stencil_ref) & 0xFF
        write_mask = int(state.stencil_write_mask) & 0xFF
        new = old.astype(np.int32)
        stencil_pass = np.ones(n, bool)
        for (func, fail, zfail, pass_), rows in _stencil_state(state, front):
            sel = np.ones(n, bool) if rows is None else rows
            s_ok = compare(np.int32(ref & mask), func, old.astype(np.int32) & mask)
            stencil_pass = np.where(sel, s_ok, stencil_pass)
            for op, where in ((fail, ~s_ok), (zfail, s_ok & ~depth_pass),
                              (pass_, s_ok & depth_pass)):
                hit = sel & where
                if op != "KEEP" and hit.any():
                    new = np.where(hit, stencil_op(op, old, ref), new)
        stencil[pix] = ((old.astype(np.int32) & ~write_mask) | (new & write_mask)).astype(np.uint8)
        passed &= stencil_pass
    passed &= depth_pass
    if not passed.all():
        pix, depth, color = pix[passed], depth[passed], color[passed]
        color2 = None if color2 is None else color2[passed]
    if len(pix) == 0:
        return
    if state.z_enable and state.z_write_enable:
        fb.depth.reshape(-1)[pix] = depth
    _write_color(fb, state, pix, color, color2)


def _write_color(fb: Framebuffer, state: RenderState, pix: np.ndarray, color: np.ndarray,
                 color2: np.ndarray | None) -> None:
    mask = int(state.color_write_enable) & 0xF
    if mask == 0:
        return
    target = fb.color.reshape(-1, 4)
    # encode saturates for 8-bit targets anyway; sRGB and blending need saturated values first
    saturate = not fb.is_float and (state.srgb_write_enable or state.alpha_blend_enable)
    src = np.clip(color, 0, 1) if saturate else color
    if state.srgb_write_enable and not fb.is_float:
        src = src.copy()
        src[:, :3] = linear_to_srgb(src[:, :3])
    if state.alpha_blend_enable:
        src2 = None if color2 is None else (color2 if fb.is_float else np.clip(color2, 0, 1))
        src = blend(state, src, decode(target[pix]), src2)
    stored = encode(src, fb.format)
    if mask == 0xF and stored.dtype == np.uint8 and stored.flags.c_contiguous:
        # one 4-byte word per pixel: a flat scatter, faster than one of (N, 4) rows
        fb.color.view(np.uint32).reshape(-1)[pix] = stored.view(np.uint32).reshape(-1)
    elif mask == 0xF:
        target[pix] = stored
    else:
        channels = [c for c in range(4) if mask >> c & 1]
        current = target[pix]
        current[:, channels] = stored[:, channels]
        target[pix] = current


def linear_to_srgb(x: np.ndarray) -> np.ndarray:
    """The sRGB transfer function (IEC 61966-2-1) on [0, 1] values."""
    x = np.clip(x, 0, 1)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055).astype(np.float32)


def srgb_to_linear(x: np.ndarray) -> np.ndarray:
    """The inverse sRGB transfer function on [0, 1] values."""
    x = np.asarray(x, np.float32)
    return np.where(x <= 0.04045, x / 12.92, np.power((x + 0.055) / 1.055, 2.4)).astype(np.float32)
