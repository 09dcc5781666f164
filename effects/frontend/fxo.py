"""fx_2_0 effect binaries (`fxc /T fx_2_0 /Fo x.fxo`) read into the `Effect` model a source
file gives: parameters with their types, default values and annotations, techniques and
passes with their state assignments, shaders as their bytecode (`BytecodeShader`).

The layout, from the public record (Wine `dlls/d3dx9_36/effect.c`: d3dx9_effect_init_from_binary,
d3dx_parse_effect, d3dx_parse_effect_typedef, d3dx_parse_value, d3dx_parse_state,
d3dx_parse_resource), restated:

    u32 tag 0xFEFF0901, u32 offset; then, from byte 8 (the base every offset counts from):
    [base .. base+offset): names, type definitions and values, found by offset
    at base+offset: u32 parameters, techniques, shader count (unused), objects;
      parameter * n: typedef offset, value offset, flags, annotation count, annotations
      technique * n: name offset, annotation count, pass count, annotations,
                     pass * n: name offset, annotation count, state count, annotations, states
      u32 strings, u32 resources;
      string * n: object id, u32 size, bytes padded to 4 (strings; top-level shaders' bytecode)
      resource * n: technique (0xFFFFFFFF: a parameter's sampler), pass or parameter index,
                    element (0xFFFFFFFF: none), state index, usage, u32 size, bytes padded
    annotation: typedef offset, value offset; state: state number, index, typedef offset,
    value offset. A name is u32 size (with its NUL) and the bytes. A typedef is u32 type,
    class, name offset, semantic offset, element count, then columns and rows (vector) or
    rows and columns (scalar, matrix), or a member count and the members' typedefs (struct).
    Object values are u32 object ids; a sampler's value is u32 state count and its states.
    Resource usage 0: the bytecode of a shader state (or FXLC of an expression state);
    1: the name of the parameter a state refers to; 2: an array selector (name + FXLC).

The state number is the `fx2` column of effects.d3d9.states. Untrusted input: every read is
bounds-checked; errors are `FxoError` located at the byte offset (line 1, the offset + 1 as
the column), within the `effect_binary_bytes` limit.
"""
from __future__ import annotations

import struct
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from effects.base import limits
from effects.base.errors import EffectError, Location
from effects.model import (Annotation, BytecodeShader, Effect, EnumValue, NullValue, Parameter,
                           ParamRef, Pass, Preshader, SamplerState, StateAssignment, Struct,
                           Technique, TypeSpec)

MAGIC = 0xFEFF0901
MAGIC_BYTES = struct.pack("<I", MAGIC)
NONE = 0xFFFFFFFF

# D3DXPARAMETER_TYPE and D3DXPARAMETER_CLASS (d3dx9shader.h, as Wine's headers declare them)
PT_VOID, PT_BOOL, PT_INT, PT_FLOAT, PT_STRING = 0, 1, 2, 3, 4
PT_TEXTURE, PT_TEXTURE1D, PT_TEXTURE2D, PT_TEXTURE3D, PT_TEXTURECUBE = 5, 6, 7, 8, 9
PT_SAMPLER, PT_SAMPLER1D, PT_SAMPLER2D, PT_SAMPLER3D, PT_SAMPLERCUBE = 10, 11, 12, 13, 14
PT_PIXELSHADER, PT_VERTEXSHADER = 15, 16
PC_SCALAR, PC_VECTOR, PC_MATRIX_ROWS, PC_MATRIX_COLUMNS, PC_OBJECT, PC_STRUCT = range(6)
# D3DX_PARAMETER_SHARED (effect.c PARAMETER_FLAG_SHARED)
FLAG_SHARED = 1
# resource usages (d3dx_parse_resource)
USAGE_DATA, USAGE_PARAMETER, USAGE_SELECTOR = 0, 1, 2

# object types: the model's (base, dim) <-> D3DXPARAMETER_TYPE, one row each
OBJECT_TYPES: dict[tuple[str, str], int] = {
    ("string", ""): PT_STRING, ("texture", ""): PT_TEXTURE, ("texture", "1D"): PT_TEXTURE1D,
    ("texture", "2D"): PT_TEXTURE2D, ("texture", "3D"): PT_TEXTURE3D,
    ("texture", "CUBE"): PT_TEXTURECUBE, ("sampler", ""): PT_SAMPLER,
    ("sampler", "1D"): PT_SAMPLER1D, ("sampler", "2D"): PT_SAMPLER2D,
    ("sampler", "3D"): PT_SAMPLER3D, ("sampler", "CUBE"): PT_SAMPLERCUBE,
    ("pixelshader", ""): PT_PIXELSHADER, ("vertexshader", ""): PT_VERTEXSHADER,
}
OBJECT_BY_TYPE = {v: k for k, v in OBJECT_TYPES.items()}
# numeric bases; half and dword are stored as float and int (D3DX has no other)
NUMERIC_TYPES = {"bool": PT_BOOL, "int": PT_INT, "dword": PT_INT, "half": PT_FLOAT,
                 "float": PT_FLOAT}
NUMERIC_BY_TYPE = {PT_BOOL: "bool", PT_INT: "int", PT_FLOAT: "float"}
_SPELLING = {"bool": "bool", "int": "int", "float": "float"}

# vs_3_sw's version token: a software vertex shader (vs_3_0 with software processing's limits)
VS_3_SW = 0xFFFE03FF
# how deep struct members may nest before the binary counts as hostile
MAX_TYPE_DEPTH = 32


class FxoError(EffectError):
    """An fx_2_0 effect binary that cannot be read."""


def is_effect_binary(data: bytes) -> bool:
    """Whether `data` starts with the fx_2_0 tag (an .fxo, whatever its name)."""
    return data[:4] == MAGIC_BYTES


@dataclass
class TypeDef:
    """A typedef as the binary gives it (also what the writer writes)."""

    type: int
    cls: int
    name: str
    semantic: str
    elements: int = 0
    rows: int = 1
    columns: int = 1
    members: list["TypeDef"] = field(default_factory=list)

    def element_bytes(self) -> int:
        """Bytes of one element's numeric value (0 for objects)."""
        if self.cls == PC_STRUCT:
            return sum(m.value_bytes() for m in self.members)
        if self.cls == PC_OBJECT:
            return 0
        return 4 * self.rows * self.columns

    def value_bytes(self) -> int:
        return self.element_bytes() * max(1, self.elements)


def read_effect_binary(data: bytes, path: str = "<fxo>",
                       effect_type: type[Effect] = Effect, origin: int = 0) -> Effect:
    """Read an fx_2_0 effect binary into an Effect. Raises FxoError (located by byte).
    `origin`: where the effect starts in the file `path` (inside a container), so that
    locations are the file's bytes."""
    limits.check("effect_binary_bytes", len(data), Location(path, 1, 1),
                 "the effect binary", FxoError)
    return _Reader(bytes(data), path, origin).read(effect_type)


class _Reader:
    def __init__(self, data: bytes, path: str, origin: int = 0) -> None:
        self.data, self.path, self.origin = data, path, origin
        self.base = 8
        self.objects: dict[int, tuple[int, bytes]] = {}   # id -> (file offset, bytes)
        self.object_count = 0
        self.parameters: list[Parameter] = []
        self.typedefs: list[TypeDef] = []
        self.structs: dict[str, Struct] = {}
        self.pending_strings: list[tuple[Annotation, Any]] = []

    # -- bytes ------------------------------------------------------------------------------
    def loc(self, at: int) -> Location:
        """Byte `at` of the effect as a location in its file (an effect inside a container,
        XNA's .xnb, starts `origin` bytes in)."""
        return Location(self.path, 1, self.origin + at + 1)

    def fail(self, message: str, at: int) -> FxoError:
        return FxoError(f"{message} (at byte {self.origin + at})", self.loc(at))

    def u32(self, at: int, what: str) -> int:
        if at < 0 or at + 4 > len(self.data):
            raise self.fail(f"the effect binary ends where {what} belongs", min(max(at, 0),
                                                                                 len(self.data)))
        return struct.unpack_from("<I", self.data, at)[0]

    def at(self, offset: int, what: str, where: int) -> int:
        """A file position from an offset the binary gives (counted from byte 8)."""
        pos = self.base + offset
        if offset >= NONE or pos + 4 > len(self.data):
            raise self.fail(f"{what} offset {offset} lies outside the {len(self.data)}-byte "
                            "effect binary", where)
        return pos

    def count(self, value: int, each: int, at: int, what: str) -> int:
        """A count the binary gives, held to what the bytes left could hold (`each` bytes at
        least per item): a count beyond them is a lie, refused before any work is done."""
        if value * each > len(self.data) - at:
            raise self.fail(f"{value} {what} cannot fit in the {len(self.data) - at} bytes "
                            "left", at)
        return value

    def blob(self, at: int, what: str) -> tuple[bytes, int]:
        """u32 size + bytes padded to 4: (the bytes, the position after them)."""
        size = self.u32(at, f"the size of {what}")
        if size > len(self.data) - at - 4:
            raise self.fail(f"{what} of {size} bytes runs past the end of the effect binary", at)
        return self.data[at + 4:at + 4 + size], at + 4 + (size + 3 & ~3)

    def name(self, offset: int, where: int, what: str) -> str:
        pos = self.at(offset, what, where)
        raw, _ = self.blob(pos, what)
        text = raw.split(b"\0", 1)[0]
        return text.decode("latin-1")

    # -- the effect -------------------------------------------------------------------------
    def read(self, effect_type: type[Effect]) -> Effect:
        if not is_effect_binary(self.data):
            raise self.fail("not an fx_2_0 effect binary (its first 4 bytes are not the tag "
                            "01 09 FF FE)", 0)
        start = self.at(self.u32(4, "the offset of the effect description"),
                        "the effect description", 4)
        pos = start
        nparams = self.count(self.u32(pos, "the parameter count"), 16, pos, "parameters")
        ntech = self.count(self.u32(pos + 4, "the technique count"), 12, pos, "techniques")
        self.u32(pos + 8, "the shader count")
        self.object_count = self.count(self.u32(pos + 12, "the object count"), 0, pos, "objects")
        if self.object_count > len(self.data):
            raise self.fail(f"{self.object_count} objects cannot be in "
                            f"{len(self.data)} bytes", pos + 12)
        pos += 16
        raw_params = []
        for _ in range(nparams):
            param, pos = self.parameter(pos)
            raw_params.append(param)
        techniques = []
        for _ in range(ntech):
            technique, pos = self.technique(pos)
            techniques.append(technique)
        nstrings = self.count(self.u32(pos, "the string count"), 8, pos + 8, "strings")
        nresources = self.count(self.u32(pos + 4, "the resource count"), 24, pos + 8,
                                "resources")
        pos += 8
        for _ in range(nstrings):
            ident = self.object_id(self.u32(pos, "an object id"), pos)
            data, after = self.blob(pos + 4, "an object")
            self.objects[ident] = (pos + 8, data)
            pos = after
        resources = []
        for _ in range(nresources):
            fields = [self.u32(pos + 4 * k, "a resource entry") for k in range(5)]
            data, after = self.blob(pos + 20, "a resource")
            resources.append((pos, fields, pos + 24, data))
            pos = after
        for annotation, value in self.pending_strings:
            annotation.value = self.string(value, value[2])
        effect = effect_type(self.path)
        effect.parameters = [self.finish_parameter(p) for p in raw_params]
        effect.techniques = techniques
        for where, fields, data_at, data in resources:
            self.resource(effect, where, fields, data_at, data)
        self.check_states(effect)
        effect.structs = list(self.structs.values())
        effect.files = (self.path,) if self.path != "<fxo>" else ()
        return effect

    def object_id(self, ident: int, where: int) -> int:
        if ident >= self.object_count:
            raise self.fail(f"object id {ident} is beyond the {self.object_count} objects the "
                            "binary declares", where)
        return ident

    # -- types and values -------------------------------------------------------------------
    def typedef(self, pos: int, depth: int = 0, state: bool = False) -> tuple[TypeDef, int]:
        """A typedef at `pos`. A `state`'s value may be a matrix of any size (fxc writes
        `VertexShaderConstant4[4] = {4, 4, 4, 4, 5, 5, 5, 5, 6}` as a 9x1 one); a parameter's
        is D3DX's 1-4 by 1-4."""
        if depth > MAX_TYPE_DEPTH:
            raise self.fail(f"struct members nest more than {MAX_TYPE_DEPTH} deep", pos)
        where = pos
        kind, cls = self.u32(pos, "a type"), self.u32(pos + 4, "a type class")
        name = self.name(self.u32(pos + 8, "a type name"), pos + 8, "a name")
        semantic = self.name(self.u32(pos + 12, "a semantic"), pos + 12, "a semantic")
        elements = self.u32(pos + 16, "an element count")
        if elements > len(self.data):
            raise self.fail(f"{elements} array elements cannot be in {len(self.data)} bytes",
                            pos + 16)
        pos += 20
        t = TypeDef(kind, cls, name, semantic, elements)
        if cls in (PC_SCALAR, PC_VECTOR, PC_MATRIX_ROWS, PC_MATRIX_COLUMNS):
            a, b = self.u32(pos, "a size"), self.u32(pos + 4, "a size")
            t.columns, t.rows = (a, b) if cls == PC_VECTOR else (b, a)
            pos += 8
            most = len(self.data) if state and cls in (PC_MATRIX_ROWS, PC_MATRIX_COLUMNS) else 4
            if kind not in NUMERIC_BY_TYPE or not (1 <= t.rows <= most and 1 <= t.columns <= most) \
                    or (cls == PC_SCALAR and t.rows * t.columns != 1) \
                    or (cls == PC_VECTOR and t.rows != 1):
                raise self.fail(f"type {kind} class {cls} of {t.rows}x{t.columns} is no "
                                "numeric type D3DX has", where)
        elif cls == PC_STRUCT:
            members = self.count(self.u32(pos, "a member count"), 20, pos, "struct members")
            pos += 4
            for _ in range(members):
                member, pos = self.typedef(pos, depth + 1)
                if member.cls == PC_OBJECT:
                    raise self.fail("a struct member that is an object (not read)", pos)
                t.members.append(member)
        elif cls == PC_OBJECT:
            if kind not in OBJECT_BY_TYPE:
                raise self.fail(f"object type {kind} is none this framework reads (string, "
                                "texture, sampler, shader)", where)
        else:
            raise self.fail(f"type class {cls} is none of D3DX's (0-5)", where + 4)
        return t, pos

    def value(self, t: TypeDef, pos: int, where: int) -> tuple[Any, int]:
        """The value of type `t` at file position `pos`: numbers (as numpy), a struct's
        numbers flat, object ids, or a sampler's states; and the position after it."""
        if t.cls != PC_OBJECT:
            size = t.value_bytes()
            if pos + size > len(self.data):
                raise self.fail(f"a value of {size} bytes runs past the end of the effect "
                                "binary", where)
            return self.data[pos:pos + size], pos + size
        count = max(1, t.elements)
        out = []
        for _ in range(count):
            if t.type in (PT_SAMPLER, PT_SAMPLER1D, PT_SAMPLER2D, PT_SAMPLER3D, PT_SAMPLERCUBE):
                n = self.count(self.u32(pos, "a sampler's state count"), 16, pos, "states")
                pos += 4
                states = []
                for _ in range(n):
                    state, pos = self.state(pos, "sampler")
                    states.append(state)
                out.append(SamplerState(states, self.loc(where)))
            else:
                out.append(("object", self.object_id(self.u32(pos, "an object id"), pos), pos))
                pos += 4
        return (out if t.elements else out[0]), pos

    def numbers(self, t: TypeDef, raw: bytes, dims: tuple[int, ...]) -> np.ndarray:
        shape = dims + ((t.columns,) if t.cls == PC_VECTOR else
                        () if t.cls == PC_SCALAR else (t.rows, t.columns))
        if t.type == PT_FLOAT:
            return np.frombuffer(raw, "<f4").astype(np.float32).reshape(shape)
        ints = np.frombuffer(raw, "<i4").astype(np.int32)
        return (ints != 0).reshape(shape) if t.type == PT_BOOL else ints.reshape(shape)

    def spec(self, t: TypeDef) -> TypeSpec:
        if t.cls == PC_STRUCT:
            # the binary names variables, not types: the struct's type is named for the
            # variable (`Marble` of a type the binary does not name: `Marble_struct`)
            return TypeSpec(struct_name(t), struct=True, spelling=struct_name(t))
        if t.cls == PC_OBJECT:
            base, dim = OBJECT_BY_TYPE[t.type]
            return TypeSpec(base, dim=dim, spelling=f"{base}{dim}")
        base = NUMERIC_BY_TYPE[t.type]
        if t.cls == PC_SCALAR:
            return TypeSpec(base, spelling=base)
        if t.cls == PC_VECTOR:
            return TypeSpec(base, 1, t.columns, spelling=f"{base}{t.columns}")
        return TypeSpec(base, t.rows, t.columns, spelling=f"{base}{t.rows}x{t.columns}")

    # -- parameters and annotations ---------------------------------------------------------
    def parameter(self, pos: int) -> tuple[tuple, int]:
        type_at = self.at(self.u32(pos, "a parameter's type offset"), "a type", pos)
        value_at = self.at(self.u32(pos + 4, "a parameter's value offset"), "a value", pos + 4)
        flags = self.u32(pos + 8, "a parameter's flags")
        nann = self.count(self.u32(pos + 12, "an annotation count"), 8, pos, "annotations")
        where = pos
        pos += 16
        t, _ = self.typedef(type_at)
        value, _ = self.value(t, value_at, value_at)
        annotations = []
        for _ in range(nann):
            annotation, pos = self.annotation(pos)
            annotations.append(annotation)
        self.typedefs.append(t)
        return (t, value, flags, annotations, where), pos

    def annotation(self, pos: int) -> tuple[Annotation, int]:
        type_at = self.at(self.u32(pos, "an annotation's type offset"), "a type", pos)
        value_at = self.at(self.u32(pos + 4, "an annotation's value offset"), "a value", pos + 4)
        t, _ = self.typedef(type_at)
        value, _ = self.value(t, value_at, value_at)
        loc = self.loc(pos)
        if t.cls == PC_OBJECT:
            if t.type != PT_STRING or t.elements:
                raise self.fail("an annotation that is an object other than a string", pos)
            # its text is in the strings section, read after the tables: resolved then
            annotation = Annotation(self.spec(t), t.name, None, loc)
            self.pending_strings.append((annotation, value))
            return annotation, pos + 8
        if t.cls == PC_STRUCT:
            # as a struct parameter: the struct declared, the value its initializer text
            return Annotation(self.spec(t), t.name, self.struct_value(t, value, pos), loc), pos + 8
        dims = (t.elements,) if t.elements else ()
        return Annotation(self.spec(t), t.name, self.numbers(t, value, dims), loc), pos + 8

    def string(self, value: Any, where: int) -> str:
        _, ident, at = value
        if ident not in self.objects:
            raise self.fail(f"string object {ident} has no data in the binary", at)
        return self.objects[ident][1].split(b"\0", 1)[0].decode("latin-1")

    def finish_parameter(self, raw: tuple) -> Parameter:
        t, value, flags, annotations, where = raw
        spec = self.spec(t)
        dims = (t.elements,) if t.elements else ()
        # (the class says nothing of row_major / column_major: fxc writes MATRIX_ROWS for
        # every matrix parameter, as Wine's test blobs show; the shaders' constant tables
        # carry the packing)
        storage = ("shared",) if flags & FLAG_SHARED else ()
        loc = self.loc(where)
        if t.cls == PC_STRUCT:
            model_value: Any = self.struct_value(t, value, where)
        elif t.cls != PC_OBJECT:
            model_value = self.numbers(t, value, dims)
        else:
            items = value if isinstance(value, list) else [value]
            made = [self.object_value(t, v, where) for v in items]
            model_value = made if t.elements else made[0]
        return Parameter(t.name, spec, storage, dims, t.semantic or None, annotations,
                         model_value, loc)

    def object_value(self, t: TypeDef, value: Any, where: int) -> Any:
        if isinstance(value, SamplerState):
            return value
        _, ident, at = value
        if t.type == PT_STRING:
            return self.string(value, where) if ident in self.objects else None
        if t.type in (PT_VERTEXSHADER, PT_PIXELSHADER):
            if ident not in self.objects:
                return None
            offset, data = self.objects[ident]
            return self.shader(t.type, data, offset)
        return None                        # a texture: the host binds one

    def shader(self, kind: int, data: bytes, offset: int) -> Any:
        if not data:
            return NullValue(self.loc(offset))
        stage = "vertex" if kind == PT_VERTEXSHADER else "pixel"
        version = self.shader_version(data, offset)
        if version[:2] != stage[0] + "s":
            raise self.fail(f"a {stage} shader object holds {version} bytecode", offset)
        return BytecodeShader(stage, version, "", location=self.loc(offset),
                              data=data)

    def shader_version(self, data: bytes, offset: int) -> str:
        """The profile a shader's version token names (vs_1_1 ... ps_3_0)."""
        token = struct.unpack_from("<I", data)[0] if len(data) >= 4 else 0
        kind = {0xFFFE: "vs", 0xFFFF: "ps"}.get(token >> 16)
        major, minor = token >> 8 & 0xFF, token & 0xFF
        if token == VS_3_SW:
            # D3DX loaded it (CreateVertexShader fails on a hardware device and the effect
            # loads all the same, as Wine's unsupported_shader test shows); validation refuses
            # it (effects.shaders.shader_value)
            return "vs_3_sw"
        if kind is None or (major, minor) not in ((1, 0), (1, 1), (1, 2), (1, 3), (1, 4),
                                                  (2, 0), (2, 1), (3, 0)):
            raise self.fail(f"a shader object whose version token 0x{token:08X} is none of "
                            "vs_1_1-vs_3_0, ps_1_0-ps_3_0", offset)
        return f"{kind}_{major}_{'x' if minor == 1 and major == 2 else minor}"

    def struct_value(self, t: TypeDef, raw: bytes, where: int) -> Any:
        """A struct parameter as the model keeps it: its declaration among the effect's structs
        and its initializer as the text `{ {..}, .. }` (the model's form for a struct)."""
        from effects.model import Expression
        name = struct_name(t)
        if name not in self.structs:
            self.structs[name] = Struct(name, _struct_text(t), self.loc(where))
        words = np.frombuffer(raw, "<u4")
        return Expression(_initializer(t, words, [0]), self.loc(where))

    # -- techniques, passes, states ---------------------------------------------------------
    def technique(self, pos: int) -> tuple[Technique, int]:
        where = pos
        name = self.name(self.u32(pos, "a technique name"), pos, "a technique name")
        nann = self.count(self.u32(pos + 4, "an annotation count"), 8, pos, "annotations")
        npass = self.count(self.u32(pos + 8, "a pass count"), 12, pos, "passes")
        pos += 12
        annotations = []
        for _ in range(nann):
            annotation, pos = self.annotation(pos)
            annotations.append(annotation)
        passes = []
        for _ in range(npass):
            pass_at = pos
            pname = self.name(self.u32(pos, "a pass name"), pos, "a pass name")
            pann = self.count(self.u32(pos + 4, "an annotation count"), 8, pos, "annotations")
            nstates = self.count(self.u32(pos + 8, "a state count"), 16, pos, "states")
            pos += 12
            pass_annotations = []
            for _ in range(pann):
                annotation, pos = self.annotation(pos)
                pass_annotations.append(annotation)
            states = []
            for _ in range(nstates):
                state, pos = self.state(pos, "pass")
                states.append(state)
            passes.append(Pass(pname or None, states, pass_annotations,
                               self.loc(pass_at)))
        return Technique(name or None, passes, annotations, self.loc(where)), pos

    def state(self, pos: int, context: str) -> tuple[StateAssignment, int]:
        from effects.d3d9.states import BY_FX2
        number = self.u32(pos, "a state number")
        info = BY_FX2.get(number)
        if info is None:
            raise self.fail(f"state number {number} is not in D3DX's state table (0-178)", pos)
        index = self.u32(pos + 4, "a state index")
        type_at = self.at(self.u32(pos + 8, "a state's type offset"), "a type", pos + 8)
        value_at = self.at(self.u32(pos + 12, "a state's value offset"), "a value", pos + 12)
        t, _ = self.typedef(type_at, state=True)
        sampler = t.cls == PC_OBJECT and t.type in (PT_SAMPLER, PT_SAMPLER1D, PT_SAMPLER2D,
                                                    PT_SAMPLER3D, PT_SAMPLERCUBE)
        if sampler and (context == "sampler" or t.elements):
            raise self.fail("a sampler inside a sampler, or an array of them, as a state's "
                            "value", pos)
        value, _ = self.value(t, value_at, value_at)
        loc = self.loc(pos)
        if info.index == "none" or context == "sampler":
            if index and info.index == "none":
                raise self.fail(f"{info.name} takes no index; the binary gives {index}", pos + 4)
            model_index = None
        else:
            if info.max_index is not None and index > info.max_index and not (
                    info.kind in ("sampler", "texture", "sampler_object") and index in range(256, 261)):
                raise self.fail(f"{info.name}[{index}]: the index is beyond {info.max_index}",
                                pos + 4)
            model_index = index
        # the typed value; a state an object resource fills later is kept as its raw value
        model = self.state_value(info, t, value, loc, pos)
        return StateAssignment(info.name, model, model_index, True, loc), pos + 16

    def state_value(self, info: Any, t: TypeDef, value: Any, loc: Location, where: int) -> Any:
        if isinstance(value, SamplerState):
            return value        # `Sampler[n] = sampler_state {...}`; a resource may name one
        if t.cls == PC_OBJECT:
            # filled by a resource (a shader's bytecode, a parameter's name); until then the
            # placeholder records which object it is
            return _Pending(t, value[1], where)
        if t.cls == PC_STRUCT or (t.elements and info.type != "constants"):
            raise self.fail(f"{info.name}: a struct or array value", where)
        if info.type in ("texture", "sampler", "vertexshader", "pixelshader"):
            # NULL: one number, 0, where an object belongs (Wine d3dx_parse_state); fxc writes
            # `VertexShader = null` as an int of class MATRIX_ROWS 1x1 (Wine's null_shader blob)
            if t.type in NUMERIC_BY_TYPE and t.rows * t.columns == 1 and not t.elements \
                    and not any(value):
                return NullValue(loc)
            raise self.fail(f"{info.name}: a number where an object belongs", where)
        numbers = self.numbers(t, value, (t.elements,) if t.elements else ())
        return typed_state_value(info, numbers, loc, lambda m: self.fail(m, where))

    def resource(self, effect: Effect, where: int, fields: list[int], data_at: int,
                 data: bytes) -> None:
        technique, index, element, state_index, usage = fields
        if technique == NONE:
            if index >= len(effect.parameters):
                raise self.fail(f"resource for parameter {index} of "
                                f"{len(effect.parameters)}", where + 4)
            value = effect.parameters[index].value
            if isinstance(value, list):
                if element >= len(value):
                    raise self.fail(f"resource for element {element} of {len(value)}", where + 8)
                value = value[element]
            if not isinstance(value, SamplerState):
                raise self.fail(f"resource for a state of parameter {index}, which is no "
                                "sampler", where + 4)
            states = value.states
        else:
            if technique >= len(effect.techniques):
                raise self.fail(f"resource for technique {technique} of "
                                f"{len(effect.techniques)}", where)
            passes = effect.techniques[technique].passes
            if index >= len(passes):
                raise self.fail(f"resource for pass {index} of {len(passes)}", where + 4)
            states = passes[index].states
        if state_index >= len(states):
            raise self.fail(f"resource for state {state_index} of {len(states)}", where + 12)
        state = states[state_index]
        pending = state.value
        if usage == USAGE_PARAMETER:
            # a state naming a parameter (`Texture = <t>`, `WorldTransform[0] = <m>`): its
            # value the parameter's
            text = data.split(b"\0", 1)[0].decode("latin-1")
            state.value = self.reference(text, effect, data_at)
            return
        if not isinstance(pending, _Pending):
            if usage == USAGE_DATA and isinstance(pending, (int, float, bool, np.ndarray,
                                                            EnumValue)):
                # an expression state: its preshader, run where a source expression is
                # evaluated (effects.shaders.fxlc reads it)
                state.value = Preshader(f"preshader at byte {data_at}", state.location, data,
                                        data_at, np.asarray(pending).size)
                return
            raise self.fail(f"resource for {state.name}, which holds no object", where + 12)
        if usage == USAGE_DATA:
            if pending.t.type not in (PT_VERTEXSHADER, PT_PIXELSHADER):
                raise self.fail(f"{state.name}: data for a {OBJECT_BY_TYPE[pending.t.type][0]} "
                                "state (FXLC expressions are not read yet)", data_at)
            state.value = self.shader(pending.t.type, data, data_at)
        elif usage == USAGE_SELECTOR:
            state.value = self.selector(state, pending, effect, data, data_at)
        else:
            raise self.fail(f"resource usage {usage} is none of D3DX's (0-2)", where + 16)

    def selector(self, state: StateAssignment, pending: _Pending, effect: Effect, data: bytes,
                 at: int) -> Preshader:
        """`VertexShader = vs_arr[expression]`: u32 size, the array's name (size bytes), then
        the preshader computing the index (effect.c d3dx9_parse_array_selector)."""
        size = struct.unpack_from("<I", data)[0] if len(data) >= 4 else NONE
        if size > len(data) - 4 or size % 4:
            raise self.fail(f"{state.name}: an array selector's name of {size} bytes (a "
                            f"multiple of 4 within the resource's {len(data)})", at)
        name = data[4:4 + size].split(b"\0", 1)[0].decode("latin-1")
        param = effect.parameter(name)
        kind = OBJECT_BY_TYPE.get(pending.t.type, ("",))[0]
        if param is None or not param.array or param.type.base != kind:
            raise self.fail(f"{state.name}: the array selector names '{name[:40]}', which is no "
                            f"array of {kind or 'objects'} the effect declares", at + 4)
        return Preshader(f"{name}[preshader at byte {at + 4 + size}]", state.location,
                         data[4 + size:], at + 4 + size, 1, name)

    def reference(self, text: str, effect: Effect, at: int) -> ParamRef:
        """`name` or `name[3]`: the parameter a state names."""
        name, index = text, None
        if text.endswith("]") and "[" in text:
            name, _, rest = text[:-1].partition("[")
            if not rest.isdigit():
                raise self.fail(f"cannot read the parameter reference '{text[:40]}'", at)
            index = int(rest)
        if effect.parameter(name) is None:
            raise self.fail(f"a state names parameter '{name[:40]}', which the effect does "
                            "not declare", at)
        return ParamRef(name, True, index, self.loc(at))

    def check_states(self, effect: Effect) -> None:
        """Every object state got its resource (else the binary is short of one)."""
        for s in effect.every_state():
            if isinstance(s.value, _Pending):
                p = s.value
                if p.t.type in (PT_VERTEXSHADER, PT_PIXELSHADER) and p.ident in self.objects:
                    s.value = self.shader(p.t.type, self.objects[p.ident][1],
                                          self.objects[p.ident][0])
                else:
                    raise self.fail(f"{s.name}: the binary gives no resource for its value",
                                    p.where)


@dataclass
class _Pending:
    """An object state whose value a resource gives."""

    t: TypeDef
    ident: int
    where: int


def typed_state_value(info: Any, numbers: np.ndarray, loc: Location, fail: Any) -> Any:
    """A state's numbers as the model keeps that state's value (what
    effects.d3d9.states.coerce_state_value makes of the same value written in source)."""
    flat = numbers.reshape(-1)
    kind = info.type
    if kind in ("float3", "float4", "matrix"):
        want = {"float3": 3, "float4": 4, "matrix": 16}[kind]
        if flat.size != want:
            raise fail(f"{info.name}: {flat.size} numbers where {want} belong")
        return flat.astype(np.float32)
    if kind == "constants":
        if info.name.endswith("B"):
            return flat.astype(bool)
        if info.name.endswith("I"):
            return flat.astype(np.int32)
        return flat.astype(np.float32)
    if kind == "color" and flat.size in (3, 4) and flat.dtype.kind == "f":
        # a colour as three or four floats (a vector-typed colour state: fxc's Ambient in
        # vkd3d's fx_2 state table, our writer's float4 preshader), kept as the floats the
        # source path keeps for a colour expression (the device reads either)
        return flat.astype(np.float32)
    if flat.size != 1:
        raise fail(f"{info.name}: {flat.size} numbers where one belongs")
    x = flat[0].item()
    if kind == "bool":
        return bool(x)
    if kind == "float":
        return float(np.float32(x))
    n = int(x) & 0xFFFFFFFF if not isinstance(x, float) else int(x)
    if kind in ("int", "dword", "color"):
        return n if kind != "int" else (n - (1 << 32) if n >= 1 << 31 else n)
    if kind == "enum":
        return enum_names(info.enum, n)
    raise fail(f"{info.name}: a number for a {kind} state")


def enum_names(table: Any, value: int) -> EnumValue:
    """The EnumValue of number `value` in `table`: its name where one has it, else (flags)
    the names of its bits, else the number."""
    for name, v in table.values.items():
        if v == value:
            return EnumValue((name,), value)
    if table.flags and value:
        names, left = [], value
        for name, v in sorted(table.values.items(), key=lambda kv: -kv[1]):
            if v and v & left == v:
                names.append(name)
                left &= ~v
        if left:
            names.append(str(left))
        return EnumValue(tuple(reversed(names)), value)
    return EnumValue((str(value),), value)


def struct_name(t: TypeDef) -> str:
    return f"{t.name}_struct"


def _struct_text(t: TypeDef) -> str:
    """`struct X_struct { float4 Diffuse; ... };` for a struct typedef (members by name; a
    member struct declared inline)."""
    members = []
    for m in t.members:
        if m.cls == PC_STRUCT:
            base = _struct_text(m)[len("struct "):-1]
        else:
            b = NUMERIC_BY_TYPE[m.type]
            base = b if m.cls == PC_SCALAR else f"{b}{m.columns}" if m.cls == PC_VECTOR else \
                f"{b}{m.rows}x{m.columns}"
        members.append(f" {base} {m.name}" + (f"[{m.elements}]" if m.elements else "") + ";")
    return f"struct {struct_name(t)} {{{''.join(members)} }};"


def _initializer(t: TypeDef, words: np.ndarray, at: list[int]) -> str:
    """The initializer text of `t`'s value from words[at[0]:] (consumed)."""
    def one(t: TypeDef) -> str:
        if t.cls == PC_STRUCT:
            return "{ " + ", ".join(_initializer(m, words, at) for m in t.members) + " }"
        n = t.rows * t.columns
        chunk = words[at[0]:at[0] + n]
        at[0] += n
        if t.type == PT_FLOAT:
            items = [repr(float(np.uint32(w).view(np.float32))) for w in chunk]
        elif t.type == PT_BOOL:
            items = ["true" if w else "false" for w in chunk]
        else:
            items = [str(int(np.uint32(w).view(np.int32))) for w in chunk]
        return items[0] if n == 1 else "{ " + ", ".join(items) + " }"
    if t.elements:
        return "{ " + ", ".join(one(t) for _ in range(t.elements)) + " }"
    return one(t)
