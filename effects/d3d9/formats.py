"""The texel formats of the Direct3D 7-9 era: how each D3DFORMAT stores a texel, and the codec.

One table, `FORMATS`, says how each D3DFORMAT stores a texel: its bit fields (shift, width,
encoding, which RGBA channels they feed) and what a sampler reads for the channels the format
lacks. `pack`/`unpack` turn decoded float texels into stored words and back, so quantisation
lives in one place. The .dds reader and writer (`effects.assets.dds`) and the texture container
(`effects.assets.textures`) both read it; it reads neither, so neither imports the other.

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

import struct
from dataclasses import dataclass

import numpy as np

# ---------------------------------------------------------------------------------------------
# The format table


@dataclass(frozen=True)
class Field:
    """One bit field of a texel word: bits [shift, shift+bits) feeding `channels` (0=R .. 3=A)."""

    shift: int
    bits: int
    encoding: str              # 'unorm' | 'snorm' | 'snorm5' (asymmetric L6V5U5 rule)
    channels: tuple[int, ...]  # luminance feeds (0, 1, 2)


@dataclass(frozen=True)
class PixelFormat:
    """How one D3DFORMAT stores a texel and what a sampler reads from it."""

    name: str
    code: int                                   # the D3DFORMAT number (FourCC as an int for DXTn)
    bits: int                                   # bits per texel (0 for block formats)
    defaults: tuple[float, float, float, float]  # what the missing channels read
    fields: tuple[Field, ...] = ()              # integer formats
    float_dtype: str | None = None              # '<f2' / '<f4' for the float formats
    float_channels: int = 0                     # R, G, B, A in memory order
    block_bytes: int = 0                        # 8 or 16 for DXT1-5
    # DDS_PIXELFORMAT as written: (flags, bit count, R, G, B, A masks); None -> FourCC
    dds: tuple[int, int, int, int, int, int] | None = None

    @property
    def signed(self) -> bool:
        return any(f.encoding != "unorm" for f in self.fields)

    @property
    def compressed(self) -> bool:
        return self.block_bytes > 0


DDPF_ALPHAPIXELS = 0x1
DDPF_ALPHA = 0x2
DDPF_FOURCC = 0x4
DDPF_RGB = 0x40
DDPF_LUMINANCE = 0x20000
DDPF_BUMPLUMINANCE = 0x40000
DDPF_BUMPDUDV = 0x80000

_RGB, _RGBA = DDPF_RGB, DDPF_RGB | DDPF_ALPHAPIXELS
_COLOUR = (0.0, 0.0, 0.0, 1.0)   # missing rgb read 0, missing alpha 1
_ONES = (1.0, 1.0, 1.0, 1.0)


def _u(shift: int, bits: int, *channels: int) -> Field:
    return Field(shift, bits, "unorm", channels)


def _s(shift: int, bits: int, *channels: int) -> Field:
    return Field(shift, bits, "snorm", channels)


def fourcc_code(text: str) -> int:
    return struct.unpack("<I", text.encode("ascii"))[0]


TABLE = [
    PixelFormat("A8R8G8B8", 21, 32, _COLOUR, (_u(16, 8, 0), _u(8, 8, 1), _u(0, 8, 2), _u(24, 8, 3)),
                dds=(_RGBA, 32, 0xFF0000, 0xFF00, 0xFF, 0xFF000000)),
    PixelFormat("X8R8G8B8", 22, 32, _COLOUR, (_u(16, 8, 0), _u(8, 8, 1), _u(0, 8, 2)),
                dds=(_RGB, 32, 0xFF0000, 0xFF00, 0xFF, 0)),
    PixelFormat("A8B8G8R8", 32, 32, _COLOUR, (_u(0, 8, 0), _u(8, 8, 1), _u(16, 8, 2), _u(24, 8, 3)),
                dds=(_RGBA, 32, 0xFF, 0xFF00, 0xFF0000, 0xFF000000)),
    PixelFormat("X8B8G8R8", 33, 32, _COLOUR, (_u(0, 8, 0), _u(8, 8, 1), _u(16, 8, 2)),
                dds=(_RGB, 32, 0xFF, 0xFF00, 0xFF0000, 0)),
    PixelFormat("R8G8B8", 20, 24, _COLOUR, (_u(16, 8, 0), _u(8, 8, 1), _u(0, 8, 2)),
                dds=(_RGB, 24, 0xFF0000, 0xFF00, 0xFF, 0)),
    PixelFormat("R5G6B5", 23, 16, _COLOUR, (_u(11, 5, 0), _u(5, 6, 1), _u(0, 5, 2)),
                dds=(_RGB, 16, 0xF800, 0x07E0, 0x001F, 0)),
    PixelFormat("X1R5G5B5", 24, 16, _COLOUR, (_u(10, 5, 0), _u(5, 5, 1), _u(0, 5, 2)),
                dds=(_RGB, 16, 0x7C00, 0x03E0, 0x001F, 0)),
    PixelFormat("A1R5G5B5", 25, 16, _COLOUR,
                (_u(10, 5, 0), _u(5, 5, 1), _u(0, 5, 2), _u(15, 1, 3)),
                dds=(_RGBA, 16, 0x7C00, 0x03E0, 0x001F, 0x8000)),
    PixelFormat("A4R4G4B4", 26, 16, _COLOUR,
                (_u(8, 4, 0), _u(4, 4, 1), _u(0, 4, 2), _u(12, 4, 3)),
                dds=(_RGBA, 16, 0x0F00, 0x00F0, 0x000F, 0xF000)),
    PixelFormat("A8", 28, 8, _COLOUR, (_u(0, 8, 3),), dds=(DDPF_ALPHA, 8, 0, 0, 0, 0xFF)),
    PixelFormat("L8", 50, 8, _COLOUR, (_u(0, 8, 0, 1, 2),), dds=(DDPF_LUMINANCE, 8, 0xFF, 0, 0, 0)),
    PixelFormat("A8L8", 51, 16, _COLOUR, (_u(0, 8, 0, 1, 2), _u(8, 8, 3)),
                dds=(DDPF_LUMINANCE | DDPF_ALPHAPIXELS, 16, 0xFF, 0, 0, 0xFF00)),
    PixelFormat("V8U8", 60, 16, _ONES, (_s(0, 8, 0), _s(8, 8, 1)),
                dds=(DDPF_BUMPDUDV, 16, 0xFF, 0xFF00, 0, 0)),
    PixelFormat("L6V5U5", 61, 16, _ONES,
                (Field(0, 5, "snorm5", (0,)), Field(5, 5, "snorm5", (1,)), _u(10, 6, 2)),
                dds=(DDPF_BUMPLUMINANCE, 16, 0x001F, 0x03E0, 0xFC00, 0)),
    PixelFormat("X8L8V8U8", 62, 32, _ONES, (_s(0, 8, 0), _s(8, 8, 1), _u(16, 8, 2)),
                dds=(DDPF_BUMPLUMINANCE, 32, 0xFF, 0xFF00, 0xFF0000, 0)),
    PixelFormat("Q8W8V8U8", 63, 32, _ONES, (_s(0, 8, 0), _s(8, 8, 1), _s(16, 8, 2), _s(24, 8, 3)),
                dds=(DDPF_BUMPDUDV, 32, 0xFF, 0xFF00, 0xFF0000, 0xFF000000)),
    PixelFormat("V16U16", 64, 32, _ONES, (_s(0, 16, 0), _s(16, 16, 1)),
                dds=(DDPF_BUMPDUDV, 32, 0xFFFF, 0xFFFF0000, 0, 0)),
    PixelFormat("R16F", 111, 16, _ONES, float_dtype="<f2", float_channels=1),
    PixelFormat("G16R16F", 112, 32, _ONES, float_dtype="<f2", float_channels=2),
    PixelFormat("A16B16G16R16F", 113, 64, _ONES, float_dtype="<f2", float_channels=4),
    PixelFormat("R32F", 114, 32, _ONES, float_dtype="<f4", float_channels=1),
    PixelFormat("G32R32F", 115, 64, _ONES, float_dtype="<f4", float_channels=2),
    PixelFormat("A32B32G32R32F", 116, 128, _ONES, float_dtype="<f4", float_channels=4),
] + [PixelFormat(f"DXT{n}", fourcc_code(f"DXT{n}"), 0, _COLOUR, block_bytes=8 if n == 1 else 16)
     for n in range(1, 6)]

FORMATS: dict[str, PixelFormat] = {f.name: f for f in TABLE}
BY_CODE: dict[int, PixelFormat] = {f.code: f for f in TABLE}


def pixel_format(name: str) -> PixelFormat:
    """The table row for a D3DFORMAT name ('A8R8G8B8', 'D3DFMT_V8U8' ...); KeyError if unknown."""
    key = name.upper()
    if key.startswith("D3DFMT_"):
        key = key[len("D3DFMT_"):]
    return FORMATS[key]


# ---------------------------------------------------------------------------------------------
# Texel codec: decoded float RGBA <-> stored words


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


def surface_bytes(fmt: PixelFormat, w: int, h: int) -> int:
    """Size in bytes of one w x h surface of `fmt`."""
    if fmt.compressed:
        return max(1, (w + 3) // 4) * max(1, (h + 3) // 4) * fmt.block_bytes
    return (w * fmt.bits + 7) // 8 * h
