"""DirectDraw Surface (.dds) files: the header around surfaces of `effects.program.formats`.

File layout (Microsoft, "DDS programming guide"): the magic "DDS ", a 124-byte DDS_HEADER
holding a 32-byte DDS_PIXELFORMAT, then the surfaces: for a cube map each face (+X, -X, +Y,
-Y, +Z, -Z) with its whole mip chain in turn; for a volume each mip level holds all its depth
slices. Uncompressed rows are tightly packed. Float formats carry their D3DFORMAT number as
FourCC (D3DFMT_R32F = 114 ...), as D3DX writes them.
"""
from __future__ import annotations

import os
import struct

import numpy as np

from effects.base import limits, untrusted
from effects.base.errors import Location, SceneError
from effects.program.formats import (BY_CODE, DDPF_ALPHA, DDPF_ALPHAPIXELS, DDPF_BUMPDUDV,
                                     DDPF_BUMPLUMINANCE, DDPF_FOURCC, TABLE, PixelFormat,
                                     fourcc_code, pixel_format, surface_bytes)
from effects.program.texels import pack, unpack
from effects.program.texture import Texture

# ---------------------------------------------------------------------------------------------
# The file

_MAGIC = b"DDS "
DDSD_CAPS, DDSD_HEIGHT, DDSD_WIDTH, DDSD_PITCH = 0x1, 0x2, 0x4, 0x8
DDSD_PIXELFORMAT, DDSD_MIPMAPCOUNT, DDSD_LINEARSIZE, DDSD_DEPTH = 0x1000, 0x20000, 0x80000, 0x800000
DDSCAPS_COMPLEX, DDSCAPS_TEXTURE, DDSCAPS_MIPMAP = 0x8, 0x1000, 0x400000
DDSCAPS2_CUBEMAP, DDSCAPS2_ALLFACES, DDSCAPS2_VOLUME = 0x200, 0xFC00, 0x200000


def _match_pixel_format(flags: int, fourcc: int, bitcount: int, masks: tuple[int, ...]) -> PixelFormat | None:
    if flags & DDPF_FOURCC:
        return BY_CODE.get(fourcc)
    bump = flags & (DDPF_BUMPDUDV | DDPF_BUMPLUMINANCE)
    has_alpha = flags & (DDPF_ALPHAPIXELS | DDPF_ALPHA)
    r, g, b, a = masks
    for fmt in TABLE:
        if fmt.dds is None:
            continue
        fflags, fbits, *fmasks = fmt.dds
        if fbits != bitcount or bool(bump) != bool(fflags & (DDPF_BUMPDUDV | DDPF_BUMPLUMINANCE)):
            continue
        want_a = fmasks[3] if (fflags & (DDPF_ALPHAPIXELS | DDPF_ALPHA)) or bump else 0
        got_a = a if has_alpha or bump else 0
        if (r, g, b, got_a) == (fmasks[0], fmasks[1], fmasks[2], want_a):
            return fmt
    return None


def read_dds(path: str | os.PathLike[str]) -> Texture:
    """Read a .dds file (2D, cube or volume, with its mips) into a `Texture` of decoded texels.

    Raises `SceneError` located at the file (line 1, column 1) for anything it cannot read.
    """
    path = os.fspath(path)
    where = Location(path, 1, 1)
    data = untrusted.read_file(path, "texture file", SceneError, "texture_file_bytes", where)
    if len(data) < 128 or data[:4] != _MAGIC:
        raise SceneError("not a DDS file (no 'DDS ' header)", where)
    (size, flags, height, width, _pitch, depth, mip_count) = struct.unpack_from("<7I", data, 4)
    pf_size, pf_flags, fourcc, bitcount, *masks = struct.unpack_from("<8I", data, 76)
    caps, caps2 = struct.unpack_from("<2I", data, 108)
    if size != 124 or pf_size != 32:
        raise SceneError(f"malformed DDS header (size {size}, pixel format size {pf_size})", where)
    if pf_flags & DDPF_FOURCC and fourcc == fourcc_code("DX10"):
        raise SceneError("DDS files with the DX10 extended header are not supported", where)
    fmt = _match_pixel_format(pf_flags, fourcc, bitcount, tuple(masks))
    if fmt is None:
        desc = (f"FourCC {struct.pack('<I', fourcc)!r} ({fourcc})" if pf_flags & DDPF_FOURCC else
                f"{bitcount}-bit masks {', '.join(hex(m) for m in masks)} (flags {pf_flags:#x})")
        raise SceneError(f"unsupported DDS pixel format: {desc}", where)
    if width == 0 or height == 0:
        raise SceneError("DDS file has an empty surface", where)
    levels = mip_count if (flags & DDSD_MIPMAPCOUNT) and mip_count > 0 else 1
    if caps2 & DDSCAPS2_CUBEMAP:
        if caps2 & DDSCAPS2_ALLFACES != DDSCAPS2_ALLFACES:
            raise SceneError("DDS cube maps with missing faces are not supported", where)
        kind, faces, depth = "cube", 6, 1
    elif caps2 & DDSCAPS2_VOLUME and flags & DDSD_DEPTH and depth > 1:
        kind, faces = "3d", 1
    else:
        kind, faces, depth = "2d", 1, 1
    # The header is untrusted: check what it claims before allocating for it (2^32 mips...).
    limits.check_texture(width, height, faces * depth, where, "DDS texture", SceneError)
    most = max(width, height, depth).bit_length()      # floor(log2(largest edge)) + 1
    if levels > most:
        raise SceneError(f"DDS header claims {levels:,} mip levels; a {width} x {height}"
                         f"{f' x {depth}' if kind == '3d' else ''} texture has at most {most}", where)

    buf = np.frombuffer(data, np.uint8)
    offset = 128
    surfaces: list[list[np.ndarray]] = [[] for _ in range(levels)]   # per level: faces or slices
    for _face in range(faces):
        for level in range(levels):
            w, h, d = max(1, width >> level), max(1, height >> level), max(1, depth >> level)
            n = surface_bytes(fmt, w, h)
            for _slice in range(d):
                if offset + n > len(data):
                    raise SceneError(f"DDS file is truncated (mip level {level} of {fmt.name} data)", where)
                surfaces[level].append(unpack(buf[offset:offset + n], fmt, (h, w)))
                offset += n
    if kind == "2d":
        decoded = [s[0] for s in surfaces]
    else:
        decoded = [np.stack(s) for s in surfaces]
    return Texture(kind, fmt.name, decoded, name=os.path.basename(path))


def write_dds(path: str | os.PathLike[str], texture: Texture) -> None:
    """Write a `Texture` of an uncompressed format (2D, cube or volume, all its mips) as .dds.

    The values are quantised to the format on the way out, so reading the file back gives
    `encode(texture.levels, texture.format)` exactly.
    """
    fmt = pixel_format(texture.format)
    if fmt.compressed:
        raise ValueError(f"write_dds cannot encode {fmt.name} blocks")
    if texture.kind not in ("2d", "cube", "3d"):
        raise ValueError(f"DDS has no {texture.kind} textures")
    width, height, depth = texture.width, texture.height, texture.depth
    levels = len(texture.levels)
    flags = DDSD_CAPS | DDSD_HEIGHT | DDSD_WIDTH | DDSD_PIXELFORMAT | DDSD_PITCH
    caps, caps2 = DDSCAPS_TEXTURE, 0
    if levels > 1:
        flags |= DDSD_MIPMAPCOUNT
        caps |= DDSCAPS_COMPLEX | DDSCAPS_MIPMAP
    if texture.kind == "cube":
        caps |= DDSCAPS_COMPLEX
        caps2 |= DDSCAPS2_CUBEMAP | DDSCAPS2_ALLFACES
    elif texture.kind == "3d":
        flags |= DDSD_DEPTH
        caps |= DDSCAPS_COMPLEX
        caps2 |= DDSCAPS2_VOLUME
    if fmt.dds is not None:
        pf = struct.pack("<8I", 32, *fmt.dds[:1], 0, *fmt.dds[1:])
    else:
        pf = struct.pack("<8I", 32, DDPF_FOURCC, fmt.code, 0, 0, 0, 0, 0)
    pitch = (width * fmt.bits + 7) // 8
    header = struct.pack("<7I", 124, flags, height, width, pitch,
                         depth if texture.kind == "3d" else 0, levels)
    header += b"\0" * 44 + pf + struct.pack("<5I", caps, caps2, 0, 0, 0)
    chunks = [_MAGIC, header]
    if texture.kind == "cube":
        for face in range(6):
            chunks += [pack(level[face], fmt).tobytes() for level in texture.levels]
    else:   # a 2D level is one surface; a volume level's slices follow each other
        chunks += [pack(level, fmt).tobytes() for level in texture.levels]
    with open(os.fspath(path), "wb") as fh:
        fh.write(b"".join(chunks))
