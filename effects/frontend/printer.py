"""Print an `Effect` model back as effect source (DX9 syntax).

The output parses back to an equal model: `parse(print(parse(x))) == parse(x)`. So numbers
are printed in a form that reads back to the same value (float32 values with numpy's
shortest round-trip repr), parameter references keep their `<name>` / `(name)` form, enum
values print as their canonical names joined by ` | `, and asm bodies, HLSL functions,
structs and kept expressions are printed verbatim.

Order: structs, parameters, functions, techniques (the model keeps them in separate lists;
the parser does not care about declaration order).
"""
from __future__ import annotations

import re
from typing import Any

import numpy as np

from effects.model import (Annotation, CompileShader, Effect, EnumValue, Expression, NullValue,
                    Parameter, ParamRef, Pass, SamplerState, ShaderBlock, StateAssignment,
                    Technique, TypeSpec, VertexDeclElement)

__all__ = ["print_effect", "format_value", "type_name"]

_INDENT = "    "
_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def print_effect(effect: Effect) -> str:
    """Effect source text for `effect`."""
    out: list[str] = []
    packing = [False]      # `#pragma pack_matrix` in force in the printed text

    def pack(row_major: bool) -> None:
        if row_major != packing[0]:
            out.append(f"#pragma pack_matrix({'row_major' if row_major else 'column_major'})")
            packing[0] = row_major
    printed = None
    for struct in effect.structs:
        if (struct.source, struct.location) == printed:
            continue       # `typedef float4 A, B;`: one statement, an entry per name
        printed = (struct.source, struct.location)
        pack(struct.row_major)
        out.append(struct.source.rstrip() + "\n")
    if effect.structs:
        out.append("")
    pack(False)   # parameters carry their majorness as a qualifier
    for param in effect.parameters:
        out.append(_parameter(param))
    if effect.parameters:
        out.append("")
    for function in effect.functions:
        pack(function.row_major)
        out.append(function.source.rstrip() + "\n")
    for technique in effect.techniques:
        out.append(_technique(technique))
    return "\n".join(out).rstrip("\n") + "\n"


# ---------------------------------------------------------------------------------------------
# Declarations


def type_name(spec: TypeSpec) -> str:
    """The spelling of a type: as the file wrote it, else built from the TypeSpec."""
    if spec.spelling:
        return spec.spelling
    if spec.struct:
        return spec.base
    if spec.is_numeric:
        if spec.rows > 1:
            return f"{spec.base}{spec.rows}x{spec.cols}"
        return f"{spec.base}{spec.cols}" if spec.cols > 1 else spec.base
    if spec.base in ("texture", "sampler") and spec.dim:
        return spec.base + spec.dim
    return {"vertexshader": "VertexShader", "pixelshader": "PixelShader"}.get(spec.base, spec.base)


def _parameter(p: Parameter) -> str:
    parts = [*p.storage, type_name(p.type), p.name]
    text = " ".join(parts) + "".join(f"[{d}]" for d in p.array)
    if p.semantic:
        text += f" : {p.semantic}"
    # the register bindings the semantic does not already spell (`: WORLD : register(c4)`)
    shown = p.registers[1:] if p.semantic and p.semantic.lower().startswith("register(") \
        else p.registers
    for profile, register in shown:
        text += f" : register({profile}, {register})" if profile else f" : register({register})"
    if p.annotations:
        text += " " + _annotations(p.annotations, 0)
    if isinstance(p.value, SamplerState) and p.type.base == "stateblock":
        text += " = " + format_value(p.value, 0).replace("sampler_state", "stateblock_state", 1)
    elif p.value is not None:
        text += " = " + _initializer(p.value, 0)
    # a tbuffer's member in a block of its own (the file's members of one tbuffer read back
    # as the same parameters)
    return f"tbuffer {p.tbuffer} {{ {text}; }};" if p.tbuffer else text + ";"


def _annotations(annotations: list[Annotation], level: int) -> str:
    pad = _INDENT * (level + 1)
    lines = [f"{pad}{type_name(a.type)} {a.name} = {_initializer(a.value, level + 1)};"
             for a in annotations]
    return "<\n" + "\n".join(lines) + "\n" + _INDENT * level + ">"


def _initializer(value: Any, level: int) -> str:
    """A parameter or annotation value."""
    if isinstance(value, list):  # an array of objects
        inner = _INDENT * (level + 1)
        items = ",\n".join(inner + format_value(v, level + 1) for v in value)
        return "{\n" + items + "\n" + _INDENT * level + "}"
    return format_value(value, level)


# ---------------------------------------------------------------------------------------------
# Techniques


def _technique(t: Technique) -> str:
    head = "technique" + (f" {t.name}" if t.name else "")
    if t.annotations:
        head += "\n" + _annotations(t.annotations, 0)
    body = "\n".join(_pass(p) for p in t.passes)
    return f"{head}\n{{\n{body}\n}}\n" if body else f"{head}\n{{\n}}\n"


def _pass(p: Pass) -> str:
    pad = _INDENT
    head = pad + "pass" + (f" {p.name}" if p.name else "")
    if p.annotations:
        head += "\n" + pad + _annotations(p.annotations, 1)
    states = "".join(_state(s, 2) + "\n" for s in p.states)
    return f"{head}\n{pad}{{\n{states}{pad}}}"


def _state(s: StateAssignment, level: int) -> str:
    index = f"[{s.index}]" if s.index is not None else ""
    value = s.value
    if isinstance(value, EnumValue) and not all(_IDENT.fullmatch(n) or n.isdigit()
                                                for n in value.names):
        text = _prefixed_enum(s.name, value)
    else:
        text = format_value(value, level)
    return f"{_INDENT * level}{s.name}{index} = {text};"


def _prefixed_enum(state: str, value: EnumValue) -> str:
    """Enum names that are not identifiers (`2WEIGHTS`) are written with their D3D prefix
    (`D3DVBF_2WEIGHTS`), which the states table also reads."""
    from effects.d3d9.states import lookup_state
    info = lookup_state(state)
    prefix = info.enum.prefixes[0] if info is not None and info.enum is not None \
        and info.enum.prefixes else ""
    return " | ".join(n if n.isdigit() or (_IDENT.fullmatch(n) and not prefix) else prefix + n
                      for n in value.names)


# ---------------------------------------------------------------------------------------------
# Values


def _number(x: Any) -> str:
    if isinstance(x, (bool, np.bool_)):
        return "true" if x else "false"
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    if isinstance(x, np.float32):
        return str(x)  # numpy prints the shortest text that reads back as this float32
    return repr(float(x))


def _escape(s: str) -> str:
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") \
        .replace("\t", "\\t").replace("\r", "\\r") + '"'


def format_value(value: Any, level: int = 0) -> str:
    """Source text of one value (a state value, a parameter initializer, an annotation)."""
    if isinstance(value, (bool, np.bool_)):
        return "TRUE" if value else "FALSE"
    if isinstance(value, (int, float, np.integer, np.floating)):
        return _number(value)
    if isinstance(value, np.ndarray):
        if value.ndim == 0:
            return _number(value[()])
        return "{" + ", ".join(_number(x) for x in value.reshape(-1)) + "}"
    if isinstance(value, str):
        return _escape(value)
    if isinstance(value, tuple):
        return "{" + ", ".join(format_value(x, level) for x in value) + "}"
    if isinstance(value, EnumValue):
        return " | ".join(value.names)
    if isinstance(value, ParamRef):
        target = value.name + (f"[{value.index}]" if value.index is not None else "")
        return f"<{target}>" if value.angle and value.index is None else f"({target})"
    if isinstance(value, NullValue):
        return "NULL"
    if isinstance(value, Expression):
        return value.text
    if isinstance(value, CompileShader):
        return f"compile {value.profile} {value.function}({', '.join(value.args)})"
    if isinstance(value, ShaderBlock):
        decl = _decl(value.decl, level) if value.decl is not None else ""
        return f"{decl}asm {{{value.source}}}"
    if isinstance(value, SamplerState):
        keyword = "sampler_state"
        states = "".join(_state(s, level + 1) + "\n" for s in value.states)
        return f"{keyword}\n{_INDENT * level}{{\n{states}{_INDENT * level}}}"
    if isinstance(value, list):
        return "{" + ", ".join(format_value(x, level) for x in value) + "}"
    raise TypeError(f"cannot print a {type(value).__name__} as an effect value")


def _decl(elements: tuple[VertexDeclElement, ...], level: int) -> str:
    pad = _INDENT * (level + 1)
    lines, stream = [], None
    for e in elements:
        if e.stream != stream:
            lines.append(f"{pad}stream {e.stream};")
            stream = e.stream
        if e.type == "skip":
            lines.append(f"{pad}skip {e.count};")
        else:
            lines.append(f"{pad}{e.type} v{e.register}[{e.count}];")
    if not lines:
        lines.append(f"{pad}stream 0;")
    return "decl\n" + _INDENT * level + "{\n" + "\n".join(lines) + "\n" + _INDENT * level + "} "
