"""The texel codec: decoded float RGBA <-> the stored words of a D3DFORMAT, one place for
quantisation. `effects.program.formats` says how each format lays its texels out; the .dds reader
and writer (`effects.assets.dds`) and the texture container (`effects.assets.textures`) both use
this, and it reads neither.

Decoded values (what a card's sampler returns), per docs/reference/semantics.md §1.7:
- unsigned normalised fields: q / (2^n - 1);
- signed 8/16-bit fields (V8U8, Q8W8V8U8, X8L8V8U8, V16U16): max(q / (2^(n-1) - 1), -1), so
  0x7f -> 1.0, 0x81 -> -1.0 and 0x80 -> -1.0;
- the 5-bit U and V of L6V5U5 are asymmetric: q/15 for q >= 0 and q/16 for q < 0;
- missing channels: rgb 0 and alpha 1 for the colour formats (X8R8G8B8 alpha = 1, L8 =
  (L, L, L, 1), A8 = (0, 0, 0, A)); V8U8 and V16U16 read (U, V, 1, 1); the float formats read
  1 for every missing channel (Microsoft, "Recommended DirectX 9.0 driver support": drivers set
  the unused channels of R16F, G16R16F, R32F, G32R32F to 1.0, and B = A = 1 for V16U16).
- DXT1-5 (BC1-BC3) blocks decode to exact float interpolants (2/3 c0 + 1/3 c1 ...); cards
  rounded those to 8 bits or fewer, which is within one 8-bit step. DXT2 and DXT4 hold
  premultiplied colour and are returned as stored.
"""
from __future__ import annotations

import numpy as np

from effects.program.formats import Field, PixelFormat


def _words(raw: np.ndarray, nbytes: int, count: int) -> np.ndarray:
    """`count` little-endian words of `nbytes` bytes each (as uint32) from a byte buffer."""
    data = raw[:count * nbytes].reshape(count, nbytes).astype(np.uint32)
    word = np.zeros(count, np.uint32)
    for i in range(nbytes):
        word |= data[:, i] << np.uint32(8 * i)
    return word


def _decode_field(q: np.ndarray, f: Field) -> np.ndarray:
    if f.encoding == "unorm":
        return q.astype(np.float32) / np.float32(2 ** f.bits - 1)
    s = q.astype(np.int64)
    s = np.where(s >= 2 ** (f.bits - 1), s - 2 ** f.bits, s)   # sign-extend
    if f.encoding == "snorm5":
        return np.where(s >= 0, s / 15.0, s / 16.0).astype(np.float32)
    return np.maximum(s / float(2 ** (f.bits - 1) - 1), -1.0).astype(np.float32)


def _encode_field(v: np.ndarray, f: Field) -> np.ndarray:
    """Nearest stored integer for decoded value(s) `v` (the inverse of `_decode_field`)."""
    v = np.nan_to_num(np.asarray(v, np.float64))
    if f.encoding == "unorm":
        top = 2 ** f.bits - 1
        return np.rint(np.clip(v, 0.0, 1.0) * top).astype(np.int64)
    if f.encoding == "snorm5":
        v = np.clip(v, -1.0, 1.0)
        return np.where(v >= 0, np.rint(v * 15), np.rint(v * 16)).astype(np.int64)
    top = 2 ** (f.bits - 1) - 1
    return np.rint(np.clip(v, -1.0, 1.0) * top).astype(np.int64)


def unpack(raw: np.ndarray, fmt: PixelFormat, shape: tuple[int, int]) -> np.ndarray:
    """Decode one 2D surface of stored bytes into (H, W, 4) float32 texel values."""
    h, w = shape
    if fmt.compressed:
        return _decode_blocks(raw, fmt, h, w)
    count = h * w
    out = np.empty((count, 4), np.float32)
    out[:] = fmt.defaults
    if fmt.float_dtype:
        vals = raw[:count * fmt.bits // 8].view(fmt.float_dtype).reshape(count, fmt.float_channels)
        out[:, :fmt.float_channels] = vals.astype(np.float32)
        return out.reshape(h, w, 4)
    word = _words(raw, fmt.bits // 8, count)
    for f in fmt.fields:
        value = _decode_field((word >> np.uint32(f.shift)) & np.uint32(2 ** f.bits - 1), f)
        for c in f.channels:
            out[:, c] = value
    return out.reshape(h, w, 4)


def pack(values: np.ndarray, fmt: PixelFormat) -> np.ndarray:
    """Store (..., 4) float texel values as the bytes of `fmt` (uint8, tightly packed).

    A luminance field takes its value from the red channel. Block formats are not encoded.
    """
    if fmt.compressed:
        raise ValueError(f"encoding {fmt.name} blocks is not supported")
    flat = np.asarray(values, np.float32).reshape(-1, 4)
    if fmt.float_dtype:
        return np.ascontiguousarray(flat[:, :fmt.float_channels].astype(fmt.float_dtype)).view(np.uint8).ravel()
    word = np.zeros(len(flat), np.uint64)
    for f in fmt.fields:
        q = _encode_field(flat[:, f.channels[0]], f) & (2 ** f.bits - 1)
        word |= q.astype(np.uint64) << np.uint64(f.shift)
    nbytes = fmt.bits // 8
    out = np.empty((len(flat), nbytes), np.uint8)
    for i in range(nbytes):
        out[:, i] = (word >> np.uint64(8 * i)) & np.uint64(0xFF)
    return out.ravel()


def quantize(values: np.ndarray, fmt: PixelFormat) -> np.ndarray:
    """The values a card samples after storing `values` in `fmt` (same shape, float32)."""
    values = np.asarray(values, np.float32)
    if fmt.compressed:
        raise ValueError(f"encoding {fmt.name} blocks is not supported")
    flat = values.reshape(-1, 4)
    return unpack(pack(flat, fmt), fmt, (1, len(flat))).reshape(values.shape)


# ---------------------------------------------------------------------------------------------
# DXT1-5 (BC1-BC3) block decoding, vectorised over all blocks


def _rgb565(c: np.ndarray) -> np.ndarray:
    r = (c >> 11) & 31
    g = (c >> 5) & 63
    b = c & 31
    return np.stack([r / 31.0, g / 63.0, b / 31.0], axis=-1)


def _colour_palette(blocks: np.ndarray, dxt1: bool) -> tuple[np.ndarray, np.ndarray]:
    """Per block: the 4-entry RGBA palette and the 16 two-bit indices (texel k at row k//4)."""
    c0 = blocks[:, 0].astype(np.uint32) | (blocks[:, 1].astype(np.uint32) << 8)
    c1 = blocks[:, 2].astype(np.uint32) | (blocks[:, 3].astype(np.uint32) << 8)
    bits = _words(blocks[:, 4:8].reshape(-1), 4, len(blocks))
    p0, p1 = _rgb565(c0), _rgb565(c1)
    # Four-colour mode always for DXT2-5; for DXT1 only when c0 > c1 (else 3 colours + transparent).
    four = (c0 > c1) | (not dxt1)
    pal = np.zeros((len(blocks), 4, 4))
    pal[:, 0, :3], pal[:, 1, :3] = p0, p1
    pal[:, 2, :3] = np.where(four[:, None], (2 * p0 + p1) / 3, (p0 + p1) / 2)
    pal[:, 3, :3] = np.where(four[:, None], (p0 + 2 * p1) / 3, 0.0)
    pal[:, :3, 3] = 1.0
    pal[:, 3, 3] = np.where(four, 1.0, 0.0)
    idx = (bits[:, None] >> (2 * np.arange(16, dtype=np.uint32))) & 3
    return pal, idx


def _explicit_alpha(blocks: np.ndarray) -> np.ndarray:
    """DXT2/3: 16 four-bit alphas, texel k in bits 4k..4k+3 of a little-endian 64-bit word."""
    nib = np.stack([blocks[:, :8] & 15, blocks[:, :8] >> 4], axis=-1).reshape(-1, 16)
    return nib / 15.0


def _interpolated_alpha(blocks: np.ndarray) -> np.ndarray:
    """DXT4/5: two 8-bit endpoints and 16 three-bit indices into an 8-entry ramp."""
    a0 = blocks[:, 0].astype(np.float64)
    a1 = blocks[:, 1].astype(np.float64)
    eight = (a0 > a1)[:, None]
    i = np.arange(2, 8)
    ramp8 = ((8 - i) * a0[:, None] + (i - 1) * a1[:, None]) / 7
    ramp6 = ((6 - i[:4]) * a0[:, None] + (i[:4] - 1) * a1[:, None]) / 5
    ramp6 = np.concatenate([ramp6, np.zeros((len(blocks), 1)), np.full((len(blocks), 1), 255.0)], 1)
    pal = np.concatenate([a0[:, None], a1[:, None], np.where(eight, ramp8, ramp6)], axis=1) / 255.0
    word = np.zeros(len(blocks), np.uint64)
    for k in range(6):
        word |= blocks[:, 2 + k].astype(np.uint64) << np.uint64(8 * k)
    idx = ((word[:, None] >> (3 * np.arange(16, dtype=np.uint64))) & np.uint64(7)).astype(np.int64)
    return np.take_along_axis(pal, idx, axis=1)


def _decode_blocks(raw: np.ndarray, fmt: PixelFormat, h: int, w: int) -> np.ndarray:
    bw, bh = max(1, (w + 3) // 4), max(1, (h + 3) // 4)
    blocks = raw[:bw * bh * fmt.block_bytes].reshape(bw * bh, fmt.block_bytes)
    colour = blocks if fmt.name == "DXT1" else blocks[:, 8:]
    pal, idx = _colour_palette(colour, fmt.name == "DXT1")
    texels = np.take_along_axis(pal, idx.astype(np.int64)[:, :, None], axis=1)   # (n, 16, 4)
    if fmt.name in ("DXT2", "DXT3"):
        texels[:, :, 3] = _explicit_alpha(blocks)
    elif fmt.name in ("DXT4", "DXT5"):
        texels[:, :, 3] = _interpolated_alpha(blocks)
    img = texels.reshape(bh, bw, 4, 4, 4).transpose(0, 2, 1, 3, 4).reshape(bh * 4, bw * 4, 4)
    return img[:h, :w].astype(np.float32)
