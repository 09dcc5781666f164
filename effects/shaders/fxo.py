"""An `Effect` written as an fx_2_0 effect binary (`fxc /T fx_2_0 /Fo x.fxo`), and the
listing of one (`effects compile --disassemble X.fxo`).

The layout is effects/frontend/fxo.py's (which reads it back); every shader is written as
Direct3D 9 bytecode with its constant table (effects.shaders.d3dbc), an HLSL shader's naming
the parameters in its registers as fxc's does. An expression state (and a shader array
selected by an expression) is written as the FXLC preshader fxc writes
(effects.shaders.fxlc_compile), one a binary gave as it came. A ps_1_x shader's constant
preshaders and a parameter initialised by an expression of others are refused with a located
error: this writer does not write those as FXLC yet.
"""
from __future__ import annotations

import re
import struct
from typing import Any

import numpy as np

from effects.base.errors import EffectError, Location
from effects.frontend import fxo as fmt
from effects.frontend.fxo import TypeDef
from effects.model import (Annotation, BytecodeShader, CompileShader, Effect, EnumValue,
                           Expression, NullValue, Parameter, ParamRef, Preshader, SamplerState,
                           ShaderBlock, StateAssignment)


class FxoEncodeError(EffectError):
    """An effect this writer cannot write as an fx_2_0 binary."""


def write_effect_binary(effect: Effect) -> bytes:
    """`effect` as fx_2_0 effect-binary bytes. Raises FxoEncodeError (located at what cannot
    be written) and the located error of a shader that does not assemble or compile."""
    return _Writer(effect).write()


# the typedef a state's value is written with, by the state's value type
_STATE_TYPES = {
    "bool": (fmt.PT_BOOL, fmt.PC_SCALAR, 1, 1), "int": (fmt.PT_INT, fmt.PC_SCALAR, 1, 1),
    "dword": (fmt.PT_INT, fmt.PC_SCALAR, 1, 1), "color": (fmt.PT_INT, fmt.PC_SCALAR, 1, 1),
    "enum": (fmt.PT_INT, fmt.PC_SCALAR, 1, 1), "float": (fmt.PT_FLOAT, fmt.PC_SCALAR, 1, 1),
    "float3": (fmt.PT_FLOAT, fmt.PC_VECTOR, 1, 3), "float4": (fmt.PT_FLOAT, fmt.PC_VECTOR, 1, 4),
    "matrix": (fmt.PT_FLOAT, fmt.PC_MATRIX_ROWS, 4, 4),
}
_OBJECT_STATE_TYPES = {"texture": fmt.PT_TEXTURE, "sampler": fmt.PT_SAMPLER,
                       "vertexshader": fmt.PT_VERTEXSHADER, "pixelshader": fmt.PT_PIXELSHADER}
_NUMBER_RE = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?[fFhH]?|true|false")


class _Writer:
    def __init__(self, effect: Effect) -> None:
        self.effect = effect
        self.data = bytearray(struct.pack("<I", 0))      # offset 0: the empty name
        self.names: dict[str, int] = {"": 0}
        self.next_id = 1                                 # object 0: D3DX's scratch object
        self.strings: list[tuple[int, bytes]] = []
        self.resources: list[tuple[int, int, int, int, int, bytes]] = []
        self.shaders = 0

    def fail(self, message: str, location: Location | None) -> FxoEncodeError:
        return FxoEncodeError(message, location or Location(self.effect.path, 1, 1))

    # -- the data area ------------------------------------------------------------------------
    def put(self, raw: bytes) -> int:
        at = len(self.data)
        self.data += raw + b"\0" * (-len(raw) % 4)
        return at

    def name(self, text: str | None) -> int:
        text = text or ""
        if text not in self.names:
            raw = text.encode("latin-1", "replace") + b"\0"
            self.names[text] = self.put(struct.pack("<I", len(raw)) + raw)
        return self.names[text]

    def typedef_bytes(self, t: TypeDef, names: list[tuple[int, str]], at: int = 0) -> bytes:
        """A typedef with its name and semantic offsets left 0; `names` gets (position in the
        bytes, text) for each to patch once the names are written."""
        names += [(at + 8, t.name), (at + 12, t.semantic)]
        out = struct.pack("<5I", t.type, t.cls, 0, 0, t.elements)
        if t.cls == fmt.PC_VECTOR:
            out += struct.pack("<2I", t.columns, t.rows)
        elif t.cls in (fmt.PC_SCALAR, fmt.PC_MATRIX_ROWS, fmt.PC_MATRIX_COLUMNS):
            out += struct.pack("<2I", t.rows, t.columns)
        elif t.cls == fmt.PC_STRUCT:
            out += struct.pack("<I", len(t.members))
            for m in t.members:
                out += self.typedef_bytes(m, names, at + len(out))
        return out

    def typed(self, t: TypeDef, value: bytes) -> tuple[int, int]:
        """Put a typedef, then its value, then its names (fxc's order, as its binaries in
        Wine's tests show): the typedef's and the value's offsets."""
        names: list[tuple[int, str]] = []
        type_at = self.put(self.typedef_bytes(t, names))
        value_at = self.put(value)
        for pos, text in names:
            struct.pack_into("<I", self.data, type_at + pos, self.name(text))
        return type_at, value_at

    def new_object(self) -> int:
        ident = self.next_id
        self.next_id += 1
        return ident

    # -- the effect ---------------------------------------------------------------------------
    def write(self) -> bytes:
        body = bytearray()
        params = b"".join(self.parameter(k, p) for k, p in enumerate(self.effect.parameters))
        techniques = b"".join(self.technique(k, t) for k, t in enumerate(self.effect.techniques))
        passes = sum(len(t.passes) for t in self.effect.techniques)
        body += struct.pack("<4I", len(self.effect.parameters), len(self.effect.techniques),
                            self.shaders + passes, self.next_id)
        body += params + techniques
        body += struct.pack("<2I", len(self.strings), len(self.resources))
        for ident, raw in self.strings:
            body += struct.pack("<2I", ident, len(raw)) + raw + b"\0" * (-len(raw) % 4)
        for technique, index, element, state, usage, raw in self.resources:
            body += struct.pack("<6I", technique, index, element, state, usage, len(raw))
            body += raw + b"\0" * (-len(raw) % 4)
        return struct.pack("<2I", fmt.MAGIC, len(self.data)) + bytes(self.data) + bytes(body)

    # -- parameters ---------------------------------------------------------------------------
    def parameter(self, index: int, p: Parameter) -> bytes:
        t = self.param_type(p.name, p.type, p.array, p.semantic, p.storage, p.location,
                            p.value)
        value = self.value(t, p.value, p.location, (index, p))
        flags = fmt.FLAG_SHARED if "shared" in p.storage else 0
        out = struct.pack("<4I", *self.typed(t, value), flags, len(p.annotations))
        return out + b"".join(self.annotation(a) for a in p.annotations)

    def param_type(self, name: str, spec: Any, dims: tuple[int, ...], semantic: str | None,
                   storage: tuple[str, ...], location: Location, value: Any) -> TypeDef:
        if len(dims) > 1:
            raise self.fail(f"'{name}': an array of more than one dimension (the format "
                            "holds one)", location)
        elements = dims[0] if dims else 0
        if spec.struct:
            members = self.struct_members(spec.base, location)
            return TypeDef(fmt.PT_VOID, fmt.PC_STRUCT, name, semantic or "", elements,
                           members=members)
        if spec.is_numeric:
            kind = fmt.NUMERIC_TYPES[spec.base]
            # float1 is a vector and float1x1 a matrix, as written (the spelling tells them
            # from a scalar); fxc writes every matrix parameter as MATRIX_ROWS (Wine's
            # test_effect_parameter_value blobs)
            spelled = (spec.spelling or "").lower()
            if spec.rows > 1 or re.search(r"[1-4]x[1-4]$", spelled) or spelled == "matrix":
                cls, rows, cols = fmt.PC_MATRIX_ROWS, spec.rows, spec.cols
            elif spec.cols > 1 or re.search(r"[1-4]$", spelled) or spelled == "vector":
                cls, rows, cols = fmt.PC_VECTOR, 1, spec.cols
            else:
                cls, rows, cols = fmt.PC_SCALAR, 1, 1
            return TypeDef(kind, cls, name, semantic or "", elements, rows, cols)
        key = (spec.base, spec.dim.upper() if spec.dim else "")
        if key not in fmt.OBJECT_TYPES:
            raise self.fail(f"'{name}': a {spec.spelling or spec.base} parameter has no "
                            "fx_2_0 type", location)
        return TypeDef(fmt.OBJECT_TYPES[key], fmt.PC_OBJECT, name, semantic or "", elements)

    def struct_members(self, type_name: str, location: Location) -> list[TypeDef]:
        """The members of struct `type_name` as the effect declares it (simple members:
        numeric types, one-dimensional arrays)."""
        from effects.frontend.types import resolve_type
        decl = next((s for s in self.effect.structs if s.name == type_name), None)
        body = None if decl is None else re.search(r"\{(.*)\}", decl.source, re.S)
        if body is None:
            raise self.fail(f"struct '{type_name}' is not declared in the effect", location)
        members = []
        for stmt in body.group(1).split(";"):
            words = re.sub(r"//[^\n]*|/\*.*?\*/", " ", stmt, flags=re.S).split()
            if not words:
                continue
            m = re.fullmatch(r"([A-Za-z_]\w*)(?:\[(\d+)\])?", "".join(words[1:]).split(":")[0])
            spec = resolve_type(words[0])
            if m is None or spec is None or not spec.is_numeric:
                raise self.fail(f"struct '{type_name}': member '{' '.join(words)[:40]}' is not "
                                "a numeric member this writer can write", decl.location)
            members.append(self.param_type(m.group(1), spec,
                                           (int(m.group(2)),) if m.group(2) else (), None, (),
                                           decl.location, None))
        return members

    def value(self, t: TypeDef, value: Any, location: Location, owner: Any) -> bytes:
        if t.cls == fmt.PC_STRUCT:
            return self.struct_value(t, value, location)
        if t.cls != fmt.PC_OBJECT:
            return self.numbers(t, value, location)
        items = value if isinstance(value, list) else [value] * max(1, t.elements)
        return b"".join(self.object_value(t, v, location, owner, k if t.elements else None)
                        for k, v in enumerate(items))

    def numbers(self, t: TypeDef, value: Any, location: Location) -> bytes:
        count = t.rows * t.columns * max(1, t.elements)
        if value is None:
            return b"\0" * 4 * count
        if isinstance(value, Expression):
            raise self.fail(f"'{t.name}' = {value.text[:40]}: an initializer D3DX evaluates as "
                            "a preshader (FXLC), which this writer does not write yet", location)
        flat = np.asarray(value).reshape(-1)
        if flat.size != count:
            raise self.fail(f"'{t.name}': {flat.size} numbers for {count}", location)
        if t.type == fmt.PT_FLOAT:
            return flat.astype("<f4").tobytes()
        ints = [int(x) & 0xFFFFFFFF for x in flat.astype(np.int64)]
        return struct.pack(f"<{len(ints)}I", *ints)

    def struct_value(self, t: TypeDef, value: Any, location: Location) -> bytes:
        total = t.value_bytes() // 4
        if value is None:
            return b"\0" * 4 * total
        text = value.text if isinstance(value, Expression) else None
        if text is None or re.search(r"[A-Za-z_]\w*", _NUMBER_RE.sub(" ", text)):
            raise self.fail(f"'{t.name}': a struct initializer that is not a list of "
                            "numbers", location)
        numbers = [1.0 if w == "true" else 0.0 if w == "false" else float(w.rstrip("fFhH"))
                   for w in _NUMBER_RE.findall(text)]
        if len(numbers) != total:
            raise self.fail(f"'{t.name}': {len(numbers)} numbers for a struct of {total}",
                            location)
        out = bytearray()
        at = 0
        for m in t.members * max(1, t.elements):
            n = m.value_bytes() // 4
            chunk = numbers[at:at + n]
            at += n
            out += (struct.pack(f"<{n}f", *chunk) if m.type == fmt.PT_FLOAT else
                    struct.pack(f"<{n}i", *(int(x) for x in chunk)))
        return bytes(out)

    def object_value(self, t: TypeDef, value: Any, location: Location, owner: Any,
                     element: int | None) -> bytes:
        if t.type in (fmt.PT_SAMPLER, fmt.PT_SAMPLER1D, fmt.PT_SAMPLER2D, fmt.PT_SAMPLER3D,
                      fmt.PT_SAMPLERCUBE):
            states = value.states if isinstance(value, SamplerState) else []
            index, _ = owner
            return struct.pack("<I", len(states)) + b"".join(
                self.state(s, (fmt.NONE, index, fmt.NONE if element is None else element, k))
                for k, s in enumerate(states))
        ident = self.new_object()
        if t.type == fmt.PT_STRING:
            if isinstance(value, str):
                self.strings.append((ident, value.encode("latin-1", "replace") + b"\0"))
        elif t.type in (fmt.PT_VERTEXSHADER, fmt.PT_PIXELSHADER):
            self.shaders += 1
            if isinstance(value, (ShaderBlock, CompileShader, BytecodeShader)):
                self.strings.append((ident, self.shader_bytes(value, location)))
            elif value is None or isinstance(value, NullValue):
                # a NULL shader (`VertexShader vs[2];` declares two): an empty string entry,
                # as fxc wrote each element of Wine's null_shader blob (read back as NULL)
                self.strings.append((ident, b""))
            else:
                raise self.fail(f"'{t.name}': a shader parameter given as "
                                f"{type(value).__name__} (not written)", location)
        return struct.pack("<I", ident)

    def shader_bytes(self, value: Any, location: Location) -> bytes:
        """A shader value as bytecode: as read (a bytecode shader), or assembled / compiled
        and written with its constant table."""
        if isinstance(value, BytecodeShader):
            return value.data
        from effects.shaders.d3dbc import write_shader
        from effects.shaders.shader_value import shader_of
        shader = shader_of(self.effect, value)
        compiled = shader.compiled
        if compiled is not None and compiled.preshaders:
            names = ", ".join(sorted(compiled.preshaders))[:60]
            raise self.fail(f"the shader's constants {names} are computed by a preshader "
                            "(FXLC), which this writer does not write yet",
                            getattr(value, "location", location))
        return write_shader(shader.program, compiled)

    def annotation(self, a: Annotation) -> bytes:
        t = self.param_type(a.name, a.type, np.shape(a.value)[:1] if a.type.is_numeric and
                            np.ndim(a.value) > (0 if a.type.components == 1 else
                                                1 if a.type.rows == 1 else 2) else (),
                            None, (), a.location, a.value)
        if t.cls == fmt.PC_OBJECT:
            if t.type != fmt.PT_STRING:
                raise self.fail(f"annotation '{a.name}': only numbers and strings are written",
                                a.location)
            ident = self.new_object()
            self.strings.append((ident, str(a.value).encode("latin-1", "replace") + b"\0"))
            value = struct.pack("<I", ident)
        else:
            value = self.value(t, a.value, a.location, None)
        return struct.pack("<2I", *self.typed(t, value))

    # -- techniques, passes, states -----------------------------------------------------------
    def technique(self, index: int, t: Any) -> bytes:
        # a pass's name follows its annotations and states, the technique's its passes
        annotations = b"".join(self.annotation(a) for a in t.annotations)
        passes = b""
        for k, p in enumerate(t.passes):
            body = b"".join(self.annotation(a) for a in p.annotations)
            body += b"".join(self.state(s, (index, k, fmt.NONE, n))
                             for n, s in enumerate(p.states))
            passes += struct.pack("<3I", self.name(p.name), len(p.annotations),
                                  len(p.states)) + body
        return struct.pack("<3I", self.name(t.name), len(t.annotations),
                           len(t.passes)) + annotations + passes

    def state(self, s: StateAssignment, where: tuple[int, int, int, int]) -> bytes:
        from effects.d3d9.states import lookup_state
        info = lookup_state(s.name) if s.known else None
        if info is None or info.fx2 is None:
            raise self.fail(f"state '{s.name}' has no number in D3DX's fx_2_0 state table",
                            s.location)
        value = s.value
        index = s.index or 0
        technique, pass_or_param, element, state_index = where

        def resource(usage: int, raw: bytes) -> None:
            self.resources.append((technique, pass_or_param, element, state_index, usage, raw))

        if isinstance(value, Expression) and not isinstance(value, Preshader):
            # a source expression: compiled to the preshader fxc would have written
            from effects.shaders.fxlc_compile import preshader_of
            value = preshader_of(self.effect, info.name, value)
        if isinstance(value, Preshader):           # (read from a binary: written as it came)
            return self.preshader_state(info, index, value, s.location, resource)
        if info.type in _OBJECT_STATE_TYPES:
            if isinstance(value, NullValue) or value is None:
                t = TypeDef(fmt.PT_INT, fmt.PC_SCALAR, "", "")
                raw = struct.pack("<I", 0)
            else:
                kind = _OBJECT_STATE_TYPES[info.type]
                t = TypeDef(kind, fmt.PC_OBJECT, "", "")
                # a sampler's value is its states (none: the resource names the parameter);
                # any other object's an object id
                raw = struct.pack("<I", 0 if kind == fmt.PT_SAMPLER else self.new_object())
                if isinstance(value, ParamRef):
                    resource(fmt.USAGE_PARAMETER, _reference(value))
                elif isinstance(value, (ShaderBlock, CompileShader)):
                    self.shaders += 1
                    resource(fmt.USAGE_DATA, self.shader_bytes(value, s.location))
                else:
                    raise self.fail(f"{s.name}: a {type(value).__name__} value is not written",
                                    s.location)
            return struct.pack("<4I", info.fx2, index, *self.typed(t, raw))
        t, raw = self.state_number(info, value, s.location)
        if isinstance(value, ParamRef):
            resource(fmt.USAGE_PARAMETER, _reference(value))
        return struct.pack("<4I", info.fx2, index, *self.typed(t, raw))

    def preshader_state(self, info: Any, index: int, value: Preshader, location: Location,
                        resource: Any) -> bytes:
        """A state a binary gave as a preshader: its type with a placeholder value, and the
        preshader as its resource (usage 0), or, for a shader array's selector, an object
        whose resource (usage 2) is the array's name, padded to 4, then the preshader."""
        if value.selects is not None:
            t = TypeDef(_OBJECT_STATE_TYPES[info.type], fmt.PC_OBJECT, "", "")
            name = value.selects.encode("latin-1", "replace") + b"\0"
            name += b"\0" * (-len(name) % 4)
            resource(fmt.USAGE_SELECTOR, struct.pack("<I", len(name)) + name + value.data)
            raw = struct.pack("<I", self.new_object())
            return struct.pack("<4I", info.fx2, index, *self.typed(t, raw))
        n = value.components or 1
        if info.type == "constants":
            # any count of numbers, as fxc types such a value (a 9x1 matrix)
            kind = fmt.PT_INT if info.name.endswith("I") else \
                fmt.PT_BOOL if info.name.endswith("B") else fmt.PT_FLOAT
            t, raw = TypeDef(kind, fmt.PC_MATRIX_COLUMNS, "", "", 0, n, 1), b"\0" * (4 * n)
        elif info.type == "color" and n in (3, 4):
            # fxc types a colour render state as one DWORD (vkd3d's fx_2 state table:
            # FogColor, TextureFactor, BlendFactor, BorderColor, Constant are one UINT), so its
            # preshader gave one number; a float3/float4 expression is typed as that vector
            # here, so the reader gets every component back (D3DX reads a vector as floats)
            t, raw = TypeDef(fmt.PT_FLOAT, fmt.PC_VECTOR, "", "", 0, 1, n), b"\0" * (4 * n)
        else:
            t, raw = self.state_number(info, np.zeros(n, np.float32), location)
        resource(fmt.USAGE_DATA, value.data)
        return struct.pack("<4I", info.fx2, index, *self.typed(t, raw))

    def state_number(self, info: Any, value: Any, location: Location) -> tuple[TypeDef, bytes]:
        """The typedef and value bytes of a numeric state (a ParamRef's placeholder zeros)."""
        if info.type == "constants":
            flat = None if isinstance(value, ParamRef) else np.asarray(value).reshape(-1)
            n = 4 if flat is None else flat.size
            if info.name.endswith("B"):
                t = TypeDef(fmt.PT_BOOL, fmt.PC_SCALAR, "", "", n if n > 1 else 0)
            else:
                kind = fmt.PT_INT if info.name.endswith("I") else fmt.PT_FLOAT
                # whole registers as float4s; another count as fxc types it, an n x 1 matrix
                # (`VertexShaderConstant1[1] = 3.0f` in Wine's states blob)
                t = TypeDef(kind, fmt.PC_MATRIX_COLUMNS, "", "", 0, n, 1) if n % 4 else \
                    TypeDef(kind, fmt.PC_VECTOR, "", "", n // 4 if n > 4 else 0, 1, 4)
        else:
            kind, cls, rows, cols = _STATE_TYPES[info.type]
            t = TypeDef(kind, cls, "", "", 0, rows, cols)
        if isinstance(value, ParamRef):
            return t, b"\0" * t.value_bytes()
        if isinstance(value, EnumValue):
            if value.value is None:
                raise self.fail(f"{info.name}: the value {'|'.join(value.names)} has no "
                                "number", location)
            numbers: Any = [value.value]
        elif isinstance(value, (bool, int, float, np.ndarray, np.generic)):
            numbers = np.asarray(value).reshape(-1)
        else:
            raise self.fail(f"{info.name}: a {type(value).__name__} value is not written",
                            location)
        if t.type == fmt.PT_FLOAT:
            return t, np.asarray(numbers, dtype="<f4").reshape(-1).tobytes()
        ints = [int(x) & 0xFFFFFFFF for x in np.asarray(numbers, dtype=np.float64 if
                                                        isinstance(value, float) else
                                                        np.int64).reshape(-1)]
        return t, struct.pack(f"<{len(ints)}I", *ints)


def _reference(ref: ParamRef) -> bytes:
    text = ref.name if ref.index is None else f"{ref.name}[{ref.index}]"
    return text.encode("latin-1", "replace") + b"\0"


def listing(effect: Effect) -> str:
    """An effect (read from a binary) as text: parameters with types, semantics, annotations
    and defaults; techniques, passes and states; every shader disassembled."""
    from effects.shaders.d3dbc import binary_listing, read_shader
    lines: list[str] = [f"// fx_2_0 effect {effect.path}", "", "// parameters"]
    for p in effect.parameters:
        dims = "".join(f"[{d}]" for d in p.array)
        semantic = f" : {p.semantic}" if p.semantic else ""
        lines.append(f"{' '.join(p.storage) + ' ' if p.storage else ''}"
                     f"{p.type.spelling or p.type.base} {p.name}{dims}{semantic}"
                     f"{_value_text(p.value)};")
        for a in p.annotations:
            lines.append(f"    <{a.type.spelling or a.type.base} {a.name} = {_value_text(a.value, '')}>")
    shaders: list[tuple[str, BytecodeShader]] = []
    for t in effect.techniques:
        lines += ["", f"technique {t.name or ''}"]
        for a in t.annotations:
            lines.append(f"    <{a.type.spelling or a.type.base} {a.name} = {_value_text(a.value, '')}>")
        for k, p in enumerate(t.passes):
            lines.append(f"  pass {p.name or k}")
            for s in p.states:
                index = "" if s.index is None else f"[{s.index}]"
                v = s.value
                if isinstance(v, BytecodeShader):
                    label = f"shader {len(shaders)}"
                    shaders.append((label, v))
                    text = f"<{label}: {v.version}, {len(v.data)} bytes>"
                else:
                    text = _value_text(v, "")
                lines.append(f"    {s.name}{index} = {text};")
    for p in effect.parameters:
        for v in p.value if isinstance(p.value, list) else [p.value]:
            if isinstance(v, BytecodeShader):
                shaders.append((f"parameter {p.name}", v))
    for label, v in shaders:
        lines += ["", f"// {label} ({v.version}) at byte {v.location.column - 1}",
                  "// (a software vertex shader: not disassembled)" if v.version == "vs_3_sw"
                  else binary_listing(read_shader(v.data, v.location.path))]
    return "\n".join(lines)


def _value_text(value: Any, prefix: str = " = ") -> str:
    if value is None:
        return ""
    if isinstance(value, np.ndarray):
        flat = value.reshape(-1).tolist()
        shown = ", ".join(f"{x:g}" if isinstance(x, float) else str(x) for x in flat[:16])
        return f"{prefix}{{{shown}{', ...' if len(flat) > 16 else ''}}}" if value.ndim else \
            f"{prefix}{shown}"
    if isinstance(value, str):
        return f'{prefix}"{value}"'
    if isinstance(value, EnumValue):
        return prefix + " | ".join(value.names)
    if isinstance(value, ParamRef):
        return f"{prefix}<{value.name}{'' if value.index is None else f'[{value.index}]'}>"
    if isinstance(value, NullValue):
        return prefix + "NULL"
    if isinstance(value, SamplerState):
        inner = " ".join(f"{s.name} = {_value_text(s.value, '')};" for s in value.states)
        return f"{prefix}sampler_state {{ {inner} }}"
    if isinstance(value, BytecodeShader):
        return f"{prefix}<{value.version} bytecode, {len(value.data)} bytes>"
    if isinstance(value, Preshader):
        from effects.shaders.fxlc import decode, listing
        program = f"preshader {{ {listing(decode(value, value.location.path))} }}"
        return prefix + (f"{value.selects}[{program}]" if value.selects else program)
    if isinstance(value, Expression):
        return prefix + value.text
    if isinstance(value, list):
        return prefix + "{ " + ", ".join(_value_text(v, "") for v in value) + " }"
    return f"{prefix}{value}"
