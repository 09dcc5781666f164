"""Compiled effects inside XNA's containers: the fx_2_0 binary an `.xnb` file (XNA Game Studio
3.x/4.0's content pipeline) or XNA 4.0's effect bytecode holds, found and handed to the fx_2_0
reader (`effects.frontend.fxo`), located at its offset in the file.

The layout, from the public record (the XNA Game Studio 4.0 "Compiled XNB Content Format"
document; MojoShader's effect reader, which FNA loads XNA 4.0 effects with), restated:

    .xnb: "XNB", platform letter ('w' Windows, 'x' Xbox 360, 'm' Windows Phone), format
    version (5: XNA 4.0, 4: XNA 3.1), flags (0x01 HiDef, 0x80 LZX-compressed), u32 file size;
    a 7-bit-encoded count of type readers, each a 7-bit-length UTF-8 name and an i32 version;
    a 7-bit count of shared resources; the primary asset: a 7-bit reader index (1-based),
    and for `Microsoft.Xna.Framework.Content.EffectReader` a u32 length and the effect's bytes.
    XNA 4.0's effect bytes: u32 0xBCF00BCF, u32 offset; the fx_2_0 binary starts `offset`
    bytes from that tag. XNA 3.x's are the fx_2_0 binary itself.

Compressed content (LZX) is refused by name, as are MonoGame's MGFX effects (another format).
Every read is bounds-checked; errors are `FxoError` at the file's byte.
"""
from __future__ import annotations

import struct

from effects.base.errors import Location
from effects.frontend.fxo import MAGIC_BYTES, FxoError

XNB_TAG = b"XNB"
XNA4_EFFECT_TAG = struct.pack("<I", 0xBCF00BCF)
EFFECT_READER = "Microsoft.Xna.Framework.Content.EffectReader"
_FLAG_LZX, _FLAG_LZ4 = 0x80, 0x40
_HEADER = 10                      # tag, platform, version, flags, u32 size
MAX_READERS = 256                 # a content file names a handful; more is hostile


def is_wrapped_effect(data: bytes) -> bool:
    """Whether `data` starts as an .xnb container or XNA 4.0's effect bytecode."""
    return data[:3] == XNB_TAG or data[:4] == XNA4_EFFECT_TAG


def unwrap(data: bytes, path: str) -> tuple[bytes, int]:
    """The fx_2_0 binary inside `data` and its offset in the file."""
    if data[:4] == XNA4_EFFECT_TAG:
        return _xna4_effect(data, 0, path)
    return _Xnb(data, path).effect()


def _xna4_effect(data: bytes, start: int, path: str) -> tuple[bytes, int]:
    """XNA 4.0's effect bytes at `start`: its tag, the offset of the fx_2_0 binary from it."""
    if start + 8 > len(data):
        raise _fail(path, "XNA 4.0 effect bytes end before their header's offset", start)
    offset = struct.unpack_from("<I", data, start + 4)[0]
    at = start + offset
    if offset < 8 or at + 4 > len(data):
        raise _fail(path, f"XNA 4.0 effect header gives the effect at byte {at}, outside the "
                    f"{len(data)} bytes", start + 4)
    if data[at:at + 4] != MAGIC_BYTES:
        raise _fail(path, "XNA 4.0 effect header points at bytes that are no fx_2_0 effect "
                    "(tag 0xFEFF0901)", at)
    return data[at:], at


def _fail(path: str, message: str, at: int) -> FxoError:
    return FxoError(f"{message} (at byte {at})", Location(path, 1, at + 1))


class _Xnb:
    def __init__(self, data: bytes, path: str) -> None:
        self.data, self.path, self.pos = data, path, 0

    def byte(self, what: str) -> int:
        if self.pos >= len(self.data):
            raise _fail(self.path, f"the .xnb file ends where {what} belongs", self.pos)
        self.pos += 1
        return self.data[self.pos - 1]

    def u32(self, what: str) -> int:
        if self.pos + 4 > len(self.data):
            raise _fail(self.path, f"the .xnb file ends where {what} belongs", self.pos)
        self.pos += 4
        return struct.unpack_from("<I", self.data, self.pos - 4)[0]

    def count(self, what: str) -> int:
        """A 7-bit-encoded int (.NET's BinaryReader.Read7BitEncodedInt): at most five bytes."""
        at, value = self.pos, 0
        for shift in range(0, 35, 7):
            b = self.byte(what)
            value |= (b & 0x7F) << shift
            if not b & 0x80:
                return value
        raise _fail(self.path, f"{what}: a 7-bit-encoded number longer than five bytes", at)

    def string(self, what: str) -> str:
        size = self.count(f"{what}'s length")
        at = self.pos
        if at + size > len(self.data):
            raise _fail(self.path, f"{what} runs past the end of the .xnb file", at)
        self.pos += size
        return self.data[at:self.pos].decode("utf-8", errors="replace")

    def effect(self) -> tuple[bytes, int]:
        if len(self.data) < _HEADER:
            raise _fail(self.path, "the .xnb header is cut short", len(self.data))
        self.pos = 3
        self.byte("the platform")
        version = self.byte("the format version")
        flags = self.byte("the flags")
        if version not in (4, 5):
            raise _fail(self.path, f".xnb format version {version}: XNA 3.1's (4) and 4.0's (5) "
                        "are read", 4)
        if flags & (_FLAG_LZX | _FLAG_LZ4):
            kind = "LZX" if flags & _FLAG_LZX else "LZ4"
            raise _fail(self.path, f"the .xnb content is {kind}-compressed, which is not read: "
                        "build the content uncompressed to open its effect", 5)
        size = self.u32("the file size")
        if size != len(self.data):
            raise _fail(self.path, f"the .xnb header gives {size} bytes, the file has "
                        f"{len(self.data)}", 6)
        readers = []
        n = self.count("the type reader count")
        if n > MAX_READERS:
            raise _fail(self.path, f"{n} type readers (at most {MAX_READERS} are read)", 10)
        for k in range(n):
            readers.append(self.string(f"type reader {k + 1}"))
            self.u32(f"type reader {k + 1}'s version")
        self.count("the shared resource count")
        at = self.pos
        index = self.count("the asset's type reader")
        if not 1 <= index <= len(readers):
            raise _fail(self.path, f"the asset names type reader {index}; the file lists "
                        f"{len(readers)}", at)
        reader = readers[index - 1]
        if not reader.startswith(EFFECT_READER):
            raise _fail(self.path, f"the .xnb holds a {reader.split(',')[0]} asset, not an "
                        "effect", at)
        length = self.u32("the effect's length")
        start = self.pos
        if start + length > len(self.data):
            raise _fail(self.path, f"the effect's {length} bytes run past the end of the "
                        ".xnb file", start - 4)
        body = self.data[start:start + length]
        if body[:4] == b"MGFX":
            raise _fail(self.path, "MonoGame's MGFX effect, not fxc's fx_2_0: not read", start)
        if body[:4] == XNA4_EFFECT_TAG:
            return _xna4_effect(self.data[:start + length], start, self.path)
        if body[:4] != MAGIC_BYTES:
            raise _fail(self.path, "the effect's bytes start with neither XNA 4.0's effect "
                        "tag (0xBCF00BCF) nor fx_2_0's (0xFEFF0901)", start)
        return body, start
