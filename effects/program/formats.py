"""The texel formats of the Direct3D 7-9 era: every D3DFORMAT, and how each stores a texel.

`D3DFORMAT` names every format of d3d9types.h (without the D3DFMT_ prefix) with its number: the
one list of names that caps profiles, render targets and textures are checked against.
`FORMATS` says how each format the codec stores lays a texel out: its bit fields (shift, width,
encoding, which RGBA channels they feed) and what a sampler reads for the channels the format
lacks. `TARGET_FORMATS` are the render targets the back ends draw into. The codec that reads
this table is `effects.program.texels` (NumPy); this module imports no NumPy, so that what only
checks names (a caps profile) does not load it.
"""
from __future__ import annotations

import struct
from dataclasses import dataclass


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

# Every D3DFORMAT of d3d9types.h: those the codec stores (FORMATS) and those a card may list but
# nothing here decodes (depth/stencil, palettised, YUV, the 10- and 16-bit-per-channel ones).
D3DFORMAT: dict[str, int] = {f.name: f.code for f in TABLE} | {
    "R3G3B2": 27, "A8R3G3B2": 29, "X4R4G4B4": 30, "A2B10G10R10": 31, "G16R16": 34,
    "A2R10G10B10": 35, "A16B16G16R16": 36, "A8P8": 40, "P8": 41, "A4L4": 52,
    "A2W10V10U10": 67, "D16_LOCKABLE": 70, "D32": 71, "D15S1": 73, "D24S8": 75, "D24X8": 77,
    "D24X4S4": 79, "D16": 80, "L16": 81, "D32F_LOCKABLE": 82, "D24FS8": 83,
    "Q16W16V16U16": 110, "CxV8U8": 117, "UYVY": fourcc_code("UYVY"), "YUY2": fourcc_code("YUY2"),
    "R8G8_B8G8": fourcc_code("RGBG"), "G8R8_G8B8": fourcc_code("GRGB"),
}


def _stored_channels(f: PixelFormat) -> int:
    return f.float_channels or len({c for field in f.fields for c in field.channels})


# The render-target formats the back ends draw into: name -> (float?, channels stored).
TARGET_FORMATS: dict[str, tuple[bool, int]] = {
    name: (FORMATS[name].float_dtype is not None, _stored_channels(FORMATS[name]))
    for name in ("A8R8G8B8", "X8R8G8B8", "R16F", "G16R16F", "R32F", "G32R32F",
                 "A16B16G16R16F", "A32B32G32R32F")}


def pixel_format(name: str) -> PixelFormat:
    """The table row for a D3DFORMAT name ('A8R8G8B8', 'D3DFMT_V8U8' ...); KeyError if unknown."""
    key = name.upper()
    if key.startswith("D3DFMT_"):
        key = key[len("D3DFMT_"):]
    return FORMATS[key]


def surface_bytes(fmt: PixelFormat, w: int, h: int) -> int:
    """Size in bytes of one w x h surface of `fmt`."""
    if fmt.compressed:
        return max(1, (w + 3) // 4) * max(1, (h + 3) // 4) * fmt.block_bytes
    return (w * fmt.bits + 7) // 8 * h
