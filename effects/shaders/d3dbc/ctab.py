"""The constant table comment fxc writes into a shader ('CTAB'): which parameter lives in which
registers, with its type and default value, and the compile target.

Layout (D3DXSHADER_CONSTANTTABLE, D3DXSHADER_CONSTANTINFO, D3DXSHADER_TYPEINFO,
D3DXSHADER_STRUCTMEMBERINFO in the DirectX SDK's D3DX9 reference): a 28-byte header (Size,
Creator, Version, Constants, ConstantInfo, Flags, Target), an array of 20-byte constant records
(Name, RegisterSet, RegisterIndex, RegisterCount, Reserved, TypeInfo, DefaultValue), 16-byte
type records (Class, Type, Rows, Columns, Elements, StructMembers, StructMemberInfo) and
8-byte struct member records (Name, TypeInfo). Every offset counts bytes from the header's
first byte (the DWORD after the 'CTAB' code); strings end with a NUL. fxc writes the strings
and records after the constant array, the target and then the creator last, and pads the
comment to whole DWORDs; a string, a numeric type several constants share and a struct's member
list are written once (_write_type says which), the padding before a record or a default value
is 0xAB bytes, and a default value spans the whole type's registers (default_size).
"""
from __future__ import annotations

import struct
from dataclasses import dataclass

from effects.base.errors import EffectError, Location

CREATOR = "effects (Python D3DX-style effect framework)"
HEADER_SIZE = 28
# D3DXREGISTER_SET
REGISTER_SETS = ("bool", "int4", "float4", "sampler")
# D3DXPARAMETER_CLASS
SCALAR, VECTOR, MATRIX_ROWS, MATRIX_COLUMNS, OBJECT, STRUCT = range(6)
# D3DXPARAMETER_TYPE
PARAMETER_TYPES = ("void", "bool", "int", "float", "string", "texture", "texture1D",
                   "texture2D", "texture3D", "textureCUBE", "sampler", "sampler1D", "sampler2D",
                   "sampler3D", "samplerCUBE", "pixelshader", "vertexshader", "pixelfragment",
                   "vertexfragment", "unsupported")
TYPE_DEPTH = 16         # struct members within struct members: deeper is a hostile table


@dataclass(frozen=True)
class TypeInfo:
    cls: int                                   # SCALAR .. STRUCT
    type: int                                  # index into PARAMETER_TYPES
    rows: int = 1
    columns: int = 1
    elements: int = 1
    members: tuple[tuple[str, "TypeInfo"], ...] = ()

    def registers(self, register_set: str) -> int:
        """The registers the whole type takes in `register_set` (before any clamp to those the
        shader reads): a bool register per component; a float4/int4 register per element of a
        scalar or vector, per row of a row-major matrix, per column of a column-major one,
        a struct its members'."""
        if self.members:
            one = sum(t.registers(register_set) for _, t in self.members)
        elif register_set == "bool":
            one = self.rows * self.columns
        else:
            one = {MATRIX_ROWS: self.rows, MATRIX_COLUMNS: self.columns}.get(self.cls, 1)
        return one * max(1, self.elements)

    @property
    def type_name(self) -> str:
        return PARAMETER_TYPES[self.type] if self.type < len(PARAMETER_TYPES) else str(self.type)


@dataclass(frozen=True)
class ConstantInfo:
    name: str
    register_set: str                          # 'bool' 'int4' 'float4' 'sampler'
    register_index: int
    register_count: int
    type: TypeInfo
    default: bytes | None = None               # when given, default_bytes() of them: fxc
                                               # writes the whole type's value even where
                                               # the registers are clamped to fewer

    @property
    def register_letter(self) -> str:
        return {"bool": "b", "int4": "i", "float4": "c", "sampler": "s"}[self.register_set]


@dataclass(frozen=True)
class ConstantTable:
    constants: tuple[ConstantInfo, ...]
    target: str
    version: int                               # the shader's version token
    creator: str = CREATOR
    flags: int = 0


def default_size(register_set: str, typ: TypeInfo) -> int:
    """The bytes of a default value as fxc 9.29 lays it out (Wine's d3dx9 constant-table test
    shaders show it): a DWORD per bool register, 16 bytes per float4 or int4 register, for
    every register of the whole type, so a float4x4 clamped to c0-c1 still has 64 bytes and a
    bool 4. A sampler has none."""
    if register_set == "sampler":
        return 0
    return typ.registers(register_set) * (4 if register_set == "bool" else 16)


# -- writing ---------------------------------------------------------------------------------
class _Blob:
    """Bytes with offsets handed out as things are appended."""

    def __init__(self, size: int) -> None:
        self.data = bytearray(size)
        self.types: dict[tuple[TypeInfo, bool], int] = {}  # (type, a member's?) written once
                                                           # and shared, as fxc does
        self.strings: dict[str, int] = {}       # and a name
        self.members: dict[tuple, int] = {}     # and a struct's member list

    def align(self) -> None:
        self.data += b"\xab" * (-len(self.data) % 4)     # fxc pads with 0xAB bytes

    def add(self, chunk: bytes) -> int:
        at = len(self.data)
        self.data += chunk
        return at

    def string(self, text: str) -> int:
        if text not in self.strings:
            self.strings[text] = self.add(text.encode("ascii", "replace") + b"\0")
        return self.strings[text]


def write_ctab(table: ConstantTable) -> bytes:
    """The table's bytes (without the 'CTAB' code), padded to whole DWORDs."""
    n = len(table.constants)
    blob = _Blob(HEADER_SIZE + 20 * n)
    records = []
    for c in table.constants:
        name = blob.string(c.name)
        type_at = _write_type(blob, c.type)
        if c.default:
            blob.align()                     # fxc starts a default value on a DWORD
        default = blob.add(c.default) if c.default else 0
        records.append(struct.pack("<IHHHHII", name, REGISTER_SETS.index(c.register_set),
                                   c.register_index, c.register_count, 0, type_at, default))
    target = blob.string(table.target)
    creator = blob.string(table.creator)
    blob.data[:HEADER_SIZE] = struct.pack("<7I", HEADER_SIZE, creator, table.version, n,
                                          HEADER_SIZE, table.flags, target)
    blob.data[HEADER_SIZE:HEADER_SIZE + 20 * n] = b"".join(records)
    blob.data += b"\xab" * (-len(blob.data) % 4)     # fxc's padding byte
    return bytes(blob.data)


def _write_type(blob: _Blob, t: TypeInfo, member: bool = False) -> int:
    """The offset of `t`'s record: a new one (aligned to 4 bytes) or, for a numeric type that
    is no array, the same type's written before in the same scope, constants' or struct
    members' (fxc 9.29 shares one bool among constants, one float among the members of
    any struct, but not a constant's float with a member's, nor an array's, a struct's or
    a sampler's record; s and s_2[2] of one struct type share its member list). A struct's
    members go first, each name followed by its type."""
    key = (t, member)
    shared = t.cls not in (OBJECT, STRUCT) and t.elements <= 1
    if shared and key in blob.types:
        return blob.types[key]
    members_at = blob.members.get(t.members, 0)
    if t.members and not members_at:
        pairs = [(blob.string(name), _write_type(blob, mt, True)) for name, mt in t.members]
        blob.align()
        members_at = blob.add(b"".join(struct.pack("<II", a, b) for a, b in pairs))
        blob.members[t.members] = members_at
    blob.align()
    at = blob.add(struct.pack("<6HI", t.cls, t.type, t.rows, t.columns, t.elements,
                              len(t.members), members_at))
    if shared:
        blob.types[key] = at
    return at


# -- reading ---------------------------------------------------------------------------------
class CtabError(EffectError):
    """A constant table that is not one (offsets out of the comment, unending strings ...)."""


class _Reader:
    def __init__(self, data: bytes, base: int, path: str) -> None:
        self.data, self.base, self.path = data, base, path
        self.types: dict[int, TypeInfo] = {}   # by offset: a table that shares one type many
                                               # times is read once (no exponential walk)

    def fail(self, message: str, at: int) -> CtabError:
        return CtabError(f"constant table: {message} (at byte {self.base + at})",
                         Location(self.path, 1, self.base + at + 1))

    def unpack(self, fmt: str, at: int, what: str) -> tuple:
        size = struct.calcsize(fmt)
        if at < 0 or at + size > len(self.data):
            raise self.fail(f"{what} at byte {at} lies outside the table ({len(self.data)} "
                            "bytes)", max(0, min(at, len(self.data))))
        return struct.unpack_from(fmt, self.data, at)

    def string(self, at: int, what: str) -> str:
        if not 0 <= at < len(self.data):
            raise self.fail(f"{what} string at byte {at} lies outside the table", 0)
        end = self.data.find(b"\0", at)
        if end < 0:
            raise self.fail(f"{what} string at byte {at} has no end", at)
        return self.data[at:end].decode("ascii", "replace")

    def type(self, at: int, depth: int) -> TypeInfo:
        if at in self.types:
            return self.types[at]
        if depth > TYPE_DEPTH:
            raise self.fail(f"types nested more than {TYPE_DEPTH} deep (a cyclic table?)", at)
        cls, typ, rows, cols, elements, count, members_at = self.unpack("<6HI", at, "type")
        members = []
        if count:
            if members_at + 8 * count > len(self.data):
                raise self.fail(f"{count} struct members at byte {members_at} run past the "
                                "table", at)
            for k in range(count):
                name_at, type_at = self.unpack("<II", members_at + 8 * k, "struct member")
                members.append((self.string(name_at, "member name"), self.type(type_at, depth + 1)))
        self.types[at] = TypeInfo(cls, typ, rows, cols, elements, tuple(members))
        return self.types[at]


def read_ctab(data: bytes, base: int, path: str) -> ConstantTable:
    """A constant table from its bytes (those after 'CTAB'); `base` is their byte offset in
    the shader, for error columns. Raises CtabError."""
    r = _Reader(data, base, path)
    size, creator, version, n, info_at, flags, target = r.unpack("<7I", 0, "header")
    if size != HEADER_SIZE:
        raise r.fail(f"header size {size}, expected {HEADER_SIZE}", 0)
    if info_at + 20 * n > len(data):
        raise r.fail(f"{n:,} constant records at byte {info_at} run past the table's "
                     f"{len(data)} bytes", 12)
    constants = []
    for k in range(n):
        at = info_at + 20 * k
        name_at, rset, index, count, _, type_at, default_at = r.unpack("<IHHHHII", at, "constant")
        if rset >= len(REGISTER_SETS):
            raise r.fail(f"constant {k}: register set {rset} is none of bool, int4, float4, "
                         "sampler", at + 4)
        typ = r.type(type_at, 0)
        default = None
        if default_at:
            size = default_size(REGISTER_SETS[rset], typ)
            default = bytes(r.unpack(f"<{size}s", default_at, "default value")[0])
        constants.append(ConstantInfo(r.string(name_at, "constant name"), REGISTER_SETS[rset],
                                      index, count, typ, default))
    return ConstantTable(tuple(constants), r.string(target, "target") if target else "",
                         version, r.string(creator, "creator") if creator else "", flags)
