"""Raw records → the `Effect` model.

`Builder` resolves types, types parameter values as numpy arrays, coerces state values through
`effects.d3d9.states` and reports unknown states (warnings, or errors when strict).

Parameter values: numeric parameters are numpy arrays shaped (array dims) + () for a scalar,
(n,) for a vector, (r, c) for a matrix; float/half/double are float32, bool is bool, and
int/uint/dword are int32, or int64 when a value does not fit in int32 (hex colours such as
0xff202060 in a DWORD); a value beyond 64 bits is an error. A non-constant initializer is kept
as an `Expression`.
"""
from __future__ import annotations

import math
import re
from typing import Any

import numpy as np
from lark import Token

from effects.base.errors import Location, ParseError, StateError
from effects.model import (Annotation, CompileShader, register_binding, Effect, Expression, Function, NullValue,
                           Parameter, ParamRef, Pass, SamplerState, ShaderBlock, StateAssignment,
                           Struct, Technique, TypeSpec, VertexDeclElement)
from effects.frontend.lexer import EffectLexer
from effects.frontend.shapes import RawBlock, RawParam, RawState, V, int_value
from effects.frontend.source import Preprocessed
from effects.frontend.types import resolve_type, texture_element_error, type_shape

__all__ = ["Builder"]

_INT32 = (-(2 ** 31), 2 ** 31 - 1)
_INT64 = (-(2 ** 63), 2 ** 63 - 1)
_ASM_GAP_RE = re.compile(r"(?:\s+|//[^\n]*|;[^\n]*|/\*.*?\*/)*", re.S)
_VERSION_RE = re.compile(r"(vs|ps)[._]([0-9])[._]([0-9a-z]+)\b", re.I)
_DECL_TYPES = {"float": 1, "d3dcolor": 4, "ubyte": 4, "short": 2}


_SIZE_OPERATORS = frozenset("+-*/%")


class _NotConstant(Exception):
    """A value is an expression, not a constant the parser can evaluate."""


class Builder:
    def __init__(self, pre: Preprocessed, lexer: EffectLexer, strict: bool) -> None:
        self.pre, self.text, self.strict = pre, pre.text, strict
        self.smap = pre.source_map
        self.lexer = lexer
        self.map_lines = self.smap.lines
        self.nlines = len(self.map_lines)
        self.warnings: list = list(pre.warnings)
        self.param_names: set[str] = set()
        self.typedefs: dict[str, TypeSpec] = {}
        self.array_typedefs: set[str] = set()
        self.structs: set[str] = set()          # struct types declared so far (annotations use them)
        self.built: dict[str, Parameter] = {}   # parameters so far, for `[N]` and `= m[3][2]`
        from effects.d3d9 import states  # the states table; imported late so the parser loads without it
        self.states = states

    # -- locations and errors -------------------------------------------------------------
    def loc(self, item: Any) -> Location:
        line = item.line
        if 0 < line <= self.nlines:  # SourceMap.locate, inlined: this runs for every node
            path, original = self.map_lines[line - 1]
            return Location(path, original, item.column)
        return self.smap.locate(line, item.column)

    def error(self, cls: type, message: str, item: Any) -> Exception:
        return self.smap.error_at(cls, message, self.loc(item))

    def text_of(self, v: V) -> str:
        return self.text[v.start:v.end]

    # -- the effect -----------------------------------------------------------------------
    def build(self, items: list, effect_type: type[Effect] = Effect) -> Effect:
        path = self.pre.files[0] if self.pre.files else (
            self.smap.lines[0][0] if self.smap.lines else "<string>")
        effect = effect_type(path)
        structs = self.structs
        first_param: dict[str, Any] = {}
        for item in items:
            if isinstance(item, RawParam):
                prior = first_param.get(item.name.value)
                if prior is not None:
                    # fxc's code and text (d3dx's message table), the first place besides
                    raise self.error(ParseError, f"X3003: redefinition of '{item.name.value}' "
                                     f"(first declared at line {self.loc(prior).line})", item.name)
                first_param[item.name.value] = item.name
        self.param_names = set(first_param)
        seen_tech: dict[str, Token] = {}
        for item in items:
            if isinstance(item, RawParam):
                param = self.parameter(item, structs)
                effect.parameters.append(param)
                self.built[param.name] = param
            elif isinstance(item, RawBlock):
                if item.name is not None:
                    prior = seen_tech.get(item.name.value)
                    if prior is not None:
                        raise self.error(ParseError, f"duplicate technique '{item.name.value}' "
                                         f"(first declared at line {self.loc(prior).line})",
                                         item.name)
                    seen_tech[item.name.value] = item.name
                effect.techniques.append(self.technique(item))
            elif item[0] == "typedef":
                self.typedef(item[1], structs)
                # kept with the structs, in order, for the HLSL functions that name it: each
                # name with the whole statement (context.load_context picks its own name)
                c = item[1]
                for name_tok, _dims in _typedef_names(c):
                    effect.structs.append(Struct(name_tok.value,
                                                 self.text[c[0].start_pos:c[-1].end_pos],
                                                 self.loc(c[0]), self.row_major_at(c[0].line)))
            elif item[0] == "struct":
                c = item[1]
                structs.add(c[1].value)
                # a struct declared with variables ends at its body (shapes.struct_vars): its
                # text is a declaration of its own with the `;`
                text = self.text[c[0].start_pos:c[3].end_pos] + (";" if c[3] is c[2] else "")
                effect.structs.append(Struct(c[1].value, text, self.loc(c[0]),
                                             self.row_major_at(c[0].line)))
            elif item[0] == "typedef_struct":
                # `typedef struct [S] { ... } T;`: the struct under each name it has, its text
                # `struct T { ... }` placed so the body keeps its place in the file
                c = item[1]
                body = c[3]
                for name_tok in [t for t in (c[2], c[4]) if t is not None]:
                    structs.add(name_tok.value)
                    head = f"struct {name_tok.value} "
                    at = self.loc(body)
                    at = Location(at.path, at.line, max(1, at.column - len(head)))
                    effect.structs.append(Struct(name_tok.value, head + body.value + ";", at,
                                                 self.row_major_at(body.line)))
            else:
                c = item[1]
                first = c[0][0] if c[0] else c[1]
                effect.functions.append(Function(c[2].value, c[1].value,
                                                 self.text[first.start_pos:c[5].end_pos],
                                                 self.loc(first), self.row_major_at(first.line),
                                                 self.expanded_lines(first.line, c[5].end_line)))
        effect.warnings = self.warnings
        effect.files = tuple(self.pre.files)
        return effect

    def expanded_lines(self, first: int, last: int) -> tuple:
        """`Function.expanded` for text lines first..last: those macro expansion made."""
        made = self.smap.expanded
        if not made:
            return ()
        out = []
        for line in range(first, last + 1):
            pieces = made.get(line)
            if pieces:
                path = self.map_lines[line - 1][0]
                texts = self.smap.texts.get(path, [])
                written = tuple((n, texts[n - 1]) for n in sorted({p[1] for p in pieces})
                                if 0 < n <= len(texts))
                out.append((line - first + 1, pieces, written))
        return tuple(out)

    def row_major_at(self, line: int) -> bool:
        """Whether `#pragma pack_matrix(row_major)` is in force at `line` of the text."""
        row = False
        for at, is_row in self.pre.pack_matrix:
            if at > line:
                break
            row = is_row
        return row

    # -- parameters -----------------------------------------------------------------------
    def type_of(self, tok: Token, structs: set[str]) -> TypeSpec:
        if tok.value in self.array_typedefs:
            raise self.error(ParseError, f"typedef '{tok.value}' is an array type: a parameter "
                             "of an array typedef is not supported (declare the array)", tok)
        spec = self.typedefs.get(tok.value) or resolve_type(tok.value, structs)
        if spec is None:
            raise self.error(ParseError, texture_element_error(tok.value)
                             or f"unknown type '{tok.value}'", tok)
        return spec

    def typedef(self, c: list, structs: set[str]) -> None:
        """`typedef float4 COLOR;`. An array typedef (`typedef float2 Pair[2];`) is for the
        HLSL functions, which read it from the struct list; a parameter may not use one."""
        type_tok = c[2]
        for name_tok, dims in _typedef_names(c):
            if dims:
                self.array_typedefs.add(name_tok.value)
                continue
            self.typedefs[name_tok.value] = self.type_of(type_tok, structs)

    def parameter(self, raw: RawParam, structs: set[str]) -> Parameter:
        if raw.type.value == "void":   # fxc's code; the text as ReShade gives it for a local
            raise self.error(ParseError, f"X3038: '{raw.name.value}': variables cannot be void",
                             raw.name)
        spec = self.type_of(raw.type, structs)
        name = raw.name.value
        dims = self.dims(raw.dims, spec, raw.value, name)
        value = None if raw.value is None else self.param_value(spec, dims, raw.value, name)
        storage = tuple(t.value.lower() for t in raw.storage)
        if spec.rows > 1 and "column_major" not in storage and "row_major" not in storage \
                and self.row_major_at(raw.name.line):
            storage += ("row_major",)     # the pragma's default, made explicit
        semantics = self.packoffset(raw)
        return Parameter(name, spec, storage, dims,
                         _semantic(semantics), self.annotations(raw.annotations), value,
                         self.loc(raw.name), _registers(semantics), raw.tbuffer)

    def packoffset(self, raw: RawParam) -> list[str]:
        """The semantics of a declaration, a cbuffer member's `packoffset(c#)` (or
        `packoffset(c#.x)`) read as the `register(c#)` it binds. Shader models 1-3 give every
        uniform whole registers, so a member packed into a later lane (`packoffset(c1.y)`,
        which only a constant buffer can hold) has no register here: refused at the
        parameter, as is a binding of another kind than c#."""
        out = []
        for s in raw.semantic or ():
            if not s.lower().startswith("packoffset("):
                out.append(s)
                continue
            inner = s[len("packoffset("):-1].strip()
            reg, _, lane = inner.partition(".")
            if not (reg[:1].lower() == "c" and reg[1:].isdigit()) or lane.lower() not in ("", "x"):
                raise self.error(ParseError, f"'{raw.name.value}': packoffset({inner}) has no "
                                 f"register in shader models 1-3, which give each uniform whole "
                                 f"constant registers: write packoffset(c#) (or c#.x)", raw.name)
            out.append(f"register({reg})")
        return out

    def dims(self, raws: list, spec: TypeSpec, value: V | None, name: str) -> tuple[int, ...]:
        """Array sizes: `[4]`; `[N]` with N a constant parameter declared before (a macro is
        already a number); `[]` sized by the initializer."""
        dims = []
        for d in raws:
            if isinstance(d, Token):
                dims.append(self.small_int(d, "array size"))
            elif d[0] == "expr":
                size = self.constant_int(d[1])
                if not 0 <= size <= 65535:
                    raise self.error(ParseError, f"array size {size} is too large"
                                     if size > 0 else f"array size {size} is negative", d[1])
                dims.append(size)
            else:
                dims.append(self.unsized(spec, value, name, d[1]))
        if any(n == 0 for n in dims):
            first = raws[0] if isinstance(raws[0], Token) else raws[0][1]
            raise self.error(ParseError, "array size must be at least 1", first)
        return tuple(dims)

    def constant_int(self, v: V) -> int:
        """An array size's constant integer expression: literals, constants declared before,
        parentheses and + - * / % (C precedence, integer division toward zero, as fxc)."""
        if v.kind == "int":
            return v.data
        if v.kind == "float" and float(v.data).is_integer():
            return int(v.data)
        if v.kind == "paren" and len(v.data) == 1:
            return self.constant_int(v.data[0])
        if v.kind == "name":
            param = self.built.get(v.data)
            value = None if param is None else param.value
            if not isinstance(value, np.ndarray) or value.size != 1 \
                    or value.dtype.kind not in "iuf" \
                    or float(value.reshape(-1)[0]) != int(value.reshape(-1)[0]):
                raise self.error(ParseError, f"array size '{v.data}' is not a constant integer "
                                 "declared before (a static const int or a macro)", v)
            return int(value.reshape(-1)[0])
        if v.kind == "expr" and v.data is not None \
                and all(op in _SIZE_OPERATORS for op in v.data[1]):
            operands, ops = v.data
            values = [self.constant_int(x) for x in operands]
            # one pass for * / %, then + and - left to right
            terms, signs = [values[0]], []
            for op, value in zip(ops, values[1:]):
                if op in "+-":
                    terms.append(value)
                    signs.append(op)
                    continue
                if op != "*" and value == 0:
                    raise self.error(ParseError, "array size divides by zero", v)
                a = terms[-1]
                terms[-1] = a * value if op == "*" else \
                    int(a / value) if op == "/" else a - value * int(a / value)
            total = terms[0]
            for op, value in zip(signs, terms[1:]):
                total = total + value if op == "+" else total - value
            return total
        raise self.error(ParseError, f"array size '{self.text_of(v)[:40]}' is not a constant "
                         "integer expression", v)

    def unsized(self, spec: TypeSpec, value: V | None, name: str, tok: Token) -> int:
        if value is None or value.kind != "list":
            raise self.error(ParseError, f"'{name}[]' needs an initializer list to give its "
                             "size", tok)
        per = max(1, math.prod(type_shape(spec))) if spec.is_numeric else 1
        if len(value.data) > 0 and all(item.kind == "list" for item in value.data):
            return len(value.data)  # {{...}, {...}}: one list per element
        if spec.is_numeric:
            try:
                count = len(self.flatten(value, []))
            except _NotConstant:
                count = len(value.data) * per
            if count % per:
                raise self.error(ParseError, f"'{name}[]': {count} values do not fill whole "
                                 f"{spec.spelling} elements", value)
            return count // per
        return len(value.data)

    def small_int(self, tok: Token, what: str) -> int:
        value = int_value(tok.value)
        if value > 65535:
            raise self.error(ParseError, f"{what} {value} is too large", tok)
        return value

    def annotations(self, raws: list) -> list[Annotation]:
        out = []
        for type_tok, name_tok, v, raw_dims in raws:
            spec = self.type_of(type_tok, self.structs)   # fxc took `<s k[1] = {4};>`
            dims = self.dims(raw_dims, spec, v, name_tok.value) if raw_dims else ()
            out.append(Annotation(spec, name_tok.value,
                                  self.param_value(spec, dims, v, name_tok.value),
                                  self.loc(name_tok)))
        return out

    def param_value(self, spec: TypeSpec, dims: tuple[int, ...], v: V, name: str) -> Any:
        if spec.struct:
            return Expression(self.text_of(v), self.loc(v))
        if spec.is_numeric:
            return self.numeric(spec, dims, v, name)
        if spec.base == "string" and not dims:
            if v.kind != "str":
                raise self.error(ParseError, f"'{name}' is a string: expected a string literal, "
                                 f"found '{self.text_of(v)[:40]}'", v)
            return v.data
        if dims:
            if v.kind != "list":
                raise self.error(ParseError, f"'{name}' is an array: expected '{{' with "
                                 f"{math.prod(dims)} values", v)
            if len(v.data) != math.prod(dims):
                raise self.error(ParseError, f"'{name}' has {math.prod(dims)} elements, "
                                 f"the initializer gives {len(v.data)}", v)
            return [self.object_value(spec, item, name) for item in v.data]
        return self.object_value(spec, v, name)

    def object_value(self, spec: TypeSpec, v: V, name: str) -> Any:
        if v.kind == "null":
            return NullValue(self.loc(v))
        if spec.base == "string":
            # an element of `string s_2[2] = {"a", "b"}` (fxc takes string arrays)
            if v.kind != "str":
                raise self.error(ParseError, f"'{name}' is a string array: expected a string "
                                 f"literal, found '{self.text_of(v)[:40]}'", v)
            return v.data
        if spec.base == "sampler":
            if v.kind == "sampler":
                return SamplerState([self.state(s, "sampler") for s in v.data], self.loc(v))
        elif spec.base == "stateblock":
            if v.kind in ("stateblock", "sampler"):
                return SamplerState([self.state(s, "pass") for s in v.data], self.loc(v))
        elif spec.base in ("vertexshader", "pixelshader"):
            if v.kind == "asm":
                return self.shader_block(v, "vertex" if spec.base == "vertexshader" else "pixel")
            if v.kind == "compile":
                return self.compile_shader(v)
            if v.kind == "name":
                return ParamRef(v.data, False, None, self.loc(v))
            if v.kind in ("ref", "paren", "index"):
                return self.state_raw(v, None)
        elif spec.base == "texture":
            return Expression(self.text_of(v), self.loc(v))
        raise self.error(ParseError, f"'{name}' ({spec.spelling}) cannot be initialised with "
                         f"'{self.text_of(v)[:40]}'", v)

    def numeric(self, spec: TypeSpec, dims: tuple[int, ...], v: V, name: str) -> Any:
        ref = self.constant_reference(v)
        if ref is not None:
            v = ref
        try:
            flat = self.flatten(v, [])
        except _NotConstant:
            return Expression(self.text_of(v), self.loc(v))
        shape = dims + type_shape(spec)
        need = math.prod(shape)
        if len(flat) == 1 and need > 1 and not dims:
            flat = flat * need  # a scalar initialises every component (HLSL promotion)
        if len(flat) != need:
            raise self.error(ParseError, f"'{name}' ({spec.spelling}"
                             f"{''.join(f'[{d}]' for d in dims)}) needs {need} "
                             f"value{'s' if need != 1 else ''}, the initializer gives {len(flat)}",
                             v)
        base = spec.base
        if base == "bool":
            return np.array([bool(x) for x in flat], dtype=bool).reshape(shape)
        if base in ("float", "half"):
            try:
                values = [float(x) for x in flat]
            except OverflowError:
                values = [math.inf]
            with np.errstate(over="ignore"):
                arr = np.array(values, dtype=np.float32)
            if not np.all(np.isfinite(arr)):
                raise self.error(ParseError, f"a value for '{name}' is out of range for "
                                 f"{spec.spelling}", v)
            return arr.reshape(shape)
        try:
            ints = [int(x) for x in flat]
        except (OverflowError, ValueError):
            raise self.error(ParseError, f"a value for '{name}' is out of range for "
                             f"{spec.spelling}", v) from None
        lo, hi = min(ints), max(ints)
        if _INT32[0] <= lo and hi <= _INT32[1]:
            dtype = np.int32
        elif _INT64[0] <= lo and hi <= _INT64[1]:
            dtype = np.int64  # hex colours such as 0xff202060 do not fit in int32
        else:
            raise self.error(ParseError, f"a value for '{name}' does not fit in 64 bits", v)
        return np.array(ints, dtype=dtype).reshape(shape)

    def constant_reference(self, v: V) -> V | None:
        """`= world[3][2]`, `= Other`, `= (float4)0` over a constant earlier parameter: that
        value, as a list of numbers (D3DX evaluates such initializers when it loads)."""
        if v.kind == "cast":
            inner = self.constant_reference(v.data[1])
            return inner if inner is not None else v.data[1]
        if v.kind == "name":
            name, index = v.data, []
        elif v.kind == "index" and v.data[1].kind == "int":
            name, index = v.data[0], [v.data[1].data]
        elif v.kind == "mindex":
            name, index = v.data
        else:
            return None
        param = self.built.get(name)
        if param is None or not isinstance(param.value, np.ndarray):
            return None
        value = param.value
        try:
            for i in index:
                value = value[i]
        except IndexError:
            raise self.error(ParseError, f"index out of range: '{self.text_of(v)[:40]}' "
                             f"({param.name} is {param.type.spelling}"
                             f"{''.join(f'[{d}]' for d in param.array)})", v) from None
        numbers = [x.item() for x in np.asarray(value).reshape(-1)]
        return V("list", [V("float" if isinstance(x, float) else "int", x, v.start, v.end,
                            v.line, v.column) for x in numbers], v.start, v.end, v.line, v.column)

    def flatten(self, v: V, out: list) -> list:
        """Numbers of a constant initializer in order; raises _NotConstant otherwise."""
        kind = v.kind
        if kind in ("int", "float", "bool"):
            out.append(v.data)
        elif kind == "cast":
            self.flatten(v.data[1], out)
        elif kind in ("list", "paren"):
            for item in v.data:
                self.flatten(item, out)
        elif kind == "call" and resolve_type(v.data[0]) is not None \
                and resolve_type(v.data[0]).is_numeric:
            for item in v.data[1]:
                self.flatten(item, out)
        else:
            raise _NotConstant
        return out

    # -- shaders --------------------------------------------------------------------------
    def shader_block(self, v: V, stage_hint: str | None) -> ShaderBlock:
        tok, decl_tok = v.data
        brace = tok.value.index("{")
        body = tok.value[brace + 1:-1]
        line, col = self.lexer.position(tok.start_pos + brace + 1)
        if "#" in body:
            body = self.hash_lines(body, tok.start_pos + brace + 1)
        version = None
        stage = stage_hint or "pixel"
        m = _VERSION_RE.match(body, _ASM_GAP_RE.match(body).end())
        if m:
            kind = m.group(1).lower()
            version = f"{kind}_{m.group(2)}_{m.group(3).lower()}"
            stage = "vertex" if kind == "vs" else "pixel"
        decl = self.vertex_decl(decl_tok) if decl_tok is not None else None
        return ShaderBlock(stage, version, body, decl, self.smap.locate(line, col))

    def hash_lines(self, body: str, base: int) -> str:
        """A line of an asm block starting with '#' that the preprocessor did not take as a
        directive (some engines' files carry `# ...` remarks there): D3DX's assembler rejects
        it; here it is a warning and the line is dropped, an error when strict."""
        out = []
        offset = 0
        for text in body.split("\n"):
            stripped = text.lstrip()
            if stripped.startswith("#"):
                line, col = self.lexer.position(base + offset + len(text) - len(stripped))
                where = self.smap.locate(line, col)
                message = (f"'{stripped[:40]}' in an asm block is not a preprocessor directive; "
                           "D3DX's assembler rejects it (ignored here)")
                if self.strict:
                    raise self.smap.error_at(ParseError, message, where)
                self.warnings.append(self.smap.warning_at(message, where))
                text = " " * len(text)
            out.append(text)
            offset += len(text) + 1
        return "\n".join(out)

    def vertex_decl(self, tok: Token) -> tuple[VertexDeclElement, ...]:
        """DX8 `decl { stream 0; float v0[3]; D3DCOLOR v5; skip 2; }` (a skip is an element
        of type 'skip', register -1, `count` DWORDs)."""
        brace = tok.value.index("{")
        body = tok.value[brace + 1:-1]
        base = tok.start_pos + brace + 1
        clean = re.sub(r"//[^\n]*|/\*.*?\*/", lambda m: " " * len(m.group()), body, flags=re.S)
        elements: list[VertexDeclElement] = []
        stream = 0
        offset = 0
        for stmt in clean.split(";"):
            words = stmt.split()
            start = offset + len(stmt) - len(stmt.lstrip())
            offset += len(stmt) + 1
            if not words:
                continue
            line, col = self.lexer.position(base + start)
            where = self.smap.locate(line, col)
            head = words[0].lower()
            m = None
            if head in ("stream", "skip") and len(words) == 2 and words[1].isdigit():
                if head == "stream":
                    stream = int(words[1])
                else:
                    elements.append(VertexDeclElement(stream, "skip", -1, int(words[1]), where))
                continue
            if head in _DECL_TYPES and len(words) >= 2:
                m = re.fullmatch(r"[vV]([0-9]{1,2})(?:\[([1-4])\])?", "".join(words[1:]))
            if m is None:
                raise self.smap.error_at(ParseError, f"cannot read vertex declaration "
                                         f"'{' '.join(words)[:40]}' (expected 'stream N', "
                                         f"'skip N' or 'TYPE vN[count]')", where)
            count = int(m.group(2)) if m.group(2) else _DECL_TYPES[head]
            elements.append(VertexDeclElement(stream, head, int(m.group(1)), count, where))
        return tuple(elements)

    def compile_shader(self, v: V) -> CompileShader:
        profile, function, args = v.data
        return CompileShader(profile.lower(), function, tuple(self.text_of(a) for a in args),
                             self.loc(v))

    # -- techniques, passes, states -------------------------------------------------------
    def technique(self, raw: RawBlock) -> Technique:
        passes = []
        for p in raw.items:
            passes.append(Pass(p.name.value if p.name is not None else None,
                               [self.state(s, "pass") for s in p.items],
                               self.annotations(p.annotations), self.loc(p.keyword)))
        return Technique(raw.name.value if raw.name is not None else None, passes,
                         self.annotations(raw.annotations), self.loc(raw.keyword))

    def state(self, raw: RawState, context: str) -> StateAssignment:
        name_tok = raw.name
        name = name_tok.value
        index = None if raw.index is None else self.small_int(raw.index, "state index")
        where = self.loc(name_tok)
        info = self.states.lookup_state(name)
        if info is None and context == "sampler" and name.lower() in self.states.CGFX_SAMPLER_STATES:
            info = self.states.lookup_state(self.states.CGFX_SAMPLER_STATES[name.lower()])
            self.complain(f"'{name}' is CgFX's (OpenGL's) name for {info.name}; D3DX's effect "
                          f"compiler rejects it; read as {info.name}", where)
        if info is not None and context == "sampler" and info.kind not in ("sampler", "texture"):
            self.complain(f"state '{info.name}' cannot be set inside sampler_state "
                          f"(only sampler states and Texture)", where)
            return StateAssignment(name, self.unknown_value(raw.value), index, False, where)
        if info is None:
            hint = self.states.suggest_state(name)
            message = f"unknown state '{name}'" + (f" (did you mean '{hint}'?)" if hint else "")
            self.complain(message, where)
            return StateAssignment(name, self.unknown_value(raw.value), index, False, where)
        self.check_index(info, index, context, raw, where)
        stage = {"vertexshader": "vertex", "pixelshader": "pixel"}.get(info.type)
        value_raw = self.state_raw(raw.value, stage)
        if type(value_raw) is int and value_raw == 0 and (stage is not None
                                                          or info.type == "matrix"):
            # `PixelShader = 0;`, `WorldTransform[0] = 0;`: D3DX reads a literal 0 for a
            # shader or matrix state as NULL (no shader: the fixed-function pipeline; a NULL
            # matrix sets nothing, so the device keeps the transform it has)
            null = NullValue(self.loc(raw.value))
            if info.type == "matrix":
                return StateAssignment(info.name, null, index, True, where)
            value_raw = null
        value_raw = self.cgfx_value(info, value_raw, raw, context)
        value = self.states.coerce_state_value(info, value_raw, self.loc(raw.value),
                                               self.param_names)
        return StateAssignment(info.name, value, index, True, where)

    def cgfx_value(self, info: Any, value_raw: Any, raw: RawState, context: str) -> Any:
        """A CgFX filter or address spelling (`Nearest`, `Repeat`) in a sampler state, read as
        the Direct3D value with a warning (`states.CGFX_SAMPLER_VALUES`)."""
        spellings = self.states.CGFX_SAMPLER_VALUES.get(info.enum.name if info.enum else "")
        if context != "sampler" or not spellings or not isinstance(value_raw, list) \
                or len(value_raw) != 1 or not isinstance(value_raw[0], str):
            return value_raw
        word = value_raw[0]
        if info.enum.lookup(word) is not None or word.lower() not in spellings:
            return value_raw
        d3d = spellings[word.lower()]
        self.complain(f"{info.name} = {word}: '{word}' is CgFX's (OpenGL's) spelling; D3DX's "
                      f"effect compiler rejects it; read as {d3d}", self.loc(raw.value))
        return [d3d]

    def complain(self, message: str, where: Location) -> None:
        if self.strict:
            raise self.smap.error_at(StateError, message, where)
        self.warnings.append(self.smap.warning_at(message, where))

    def check_index(self, info: Any, index: int | None, context: str, raw: RawState,
                    where: Location) -> None:
        if context == "sampler":
            if index is not None:
                raise self.error(StateError, f"{info.name} takes no index inside "
                                 f"sampler_state; remove [{index}]", raw.index)
            return
        if index is None or (info.index != "none" and (info.max_index is None
                                                       or index <= info.max_index)):
            self.states.check_index(info, index, where)  # fine, or a missing index
        else:
            self.states.check_index(info, index, self.loc(raw.index))

    def state_raw(self, v: V, stage: str | None) -> Any:
        """A state value in the form `states.coerce_state_value` reads."""
        kind = v.kind
        if kind in ("int", "float", "bool", "str"):
            return v.data
        if kind == "null":
            return NullValue(self.loc(v))
        if kind == "name":
            return [v.data]
        if kind == "bar":
            if all(o.kind in ("name", "int") for o in v.data):
                return [o.data for o in v.data]
        elif kind == "ref":
            if isinstance(v.data, tuple):   # `<g_vLightPos[0]>`
                return ParamRef(v.data[0], True, v.data[1], self.loc(v))
            return ParamRef(v.data, True, None, self.loc(v))
        elif kind == "cast":
            inner = self.state_raw(v.data[1], stage)
            spec = resolve_type(v.data[0])
            if isinstance(inner, (int, float)) and not isinstance(inner, bool) and spec:
                value = float(inner) if spec.base in ("float", "half") else inner
                n = spec.rows * spec.cols
                return value if n == 1 else tuple([value] * n)  # (float4)0.9: every component
            return inner
        elif kind == "index":
            name, idx = v.data
            if idx.kind == "int":
                return ParamRef(name, False, idx.data, self.loc(v))
        elif kind == "paren":
            if len(v.data) == 1:
                inner = v.data[0]
                if inner.kind in ("name", "index"):
                    ref = self.state_raw(inner, stage)
                    if isinstance(ref, list):
                        return ParamRef(inner.data, False, None, self.loc(v))
                    if isinstance(ref, ParamRef):
                        return ref
                if inner.kind in ("int", "float", "bool", "str", "paren", "ref", "null"):
                    return self.state_raw(inner, stage)
            else:
                try:
                    return tuple(self.flatten(v, []))
                except _NotConstant:
                    pass
        elif kind in ("list", "call"):
            try:
                return tuple(self.flatten(v, []))
            except _NotConstant:
                pass
        elif kind == "asm":
            return self.shader_block(v, stage)
        elif kind == "compile":
            return self.compile_shader(v)
        elif kind == "sampler":
            return SamplerState([self.state(s, "sampler") for s in v.data], self.loc(v))
        elif kind == "stateblock":
            return SamplerState([self.state(s, "pass") for s in v.data], self.loc(v))
        return Expression(self.text_of(v), self.loc(v))

    def unknown_value(self, v: V) -> Any:
        """The value of an assignment to an unknown state, kept in model form."""
        from effects.model import EnumValue
        raw = self.state_raw(v, None)
        if isinstance(raw, list):
            return EnumValue(tuple(str(x).upper() for x in raw), None, self.loc(v))
        return raw



def _registers(semantics: list[str]) -> tuple[tuple[str, str], ...]:
    """Every `register(...)` binding, as (profile, register): `register(c4)` is ('', 'c4'),
    `register(ps, c1)` ('ps', 'c1'); lower-case, in the order written (HLSL allows several:
    `: register(vs, c0) : register(ps, c1)`)."""
    return tuple(register_binding(s) for s in semantics or () if s.lower().startswith("register("))


def _semantic(semantics: list[str]) -> str | None:
    """The semantic of `: WORLD : register(c0)` (the register only when there is nothing else)."""
    if not semantics:
        return None
    named = [s for s in semantics if not s.lower().startswith("register(")]
    return named[0] if named else semantics[0]


def _typedef_names(c: list) -> list[tuple[Token, list]]:
    """The (name, array sizes) pairs of a `typedef` item: TYPEDEF storage type name dims
    (COMMA name dims)* SEMI."""
    return [(c[k], c[k + 1]) for k in range(3, len(c) - 1, 3)]
