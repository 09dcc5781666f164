"""Type names of the effect language → `TypeSpec`, and the numeric shape of a type."""
from __future__ import annotations

import re

from effects.base import caches
from effects.model import TypeSpec

__all__ = ["type_shape", "resolve_type"]

_NUMERIC_RE = re.compile(r"(bool|int|uint|half|float|double|dword)([1-4])?(?:x([1-4]))?")
_BASE_OF = {"bool": "bool", "int": "int", "uint": "dword", "half": "half", "float": "float",
            "double": "float", "dword": "dword"}
_TEMPLATE_RE = re.compile(r"(?:matrix|vector)<([a-z]+)(?:,([1-4]))?(?:,([1-4]))?>")
_OBJECT_TYPES = {
    "string": ("string", ""), "texture": ("texture", ""), "texture1d": ("texture", "1D"),
    "texture2d": ("texture", "2D"), "texture3d": ("texture", "3D"),
    "texturecube": ("texture", "CUBE"), "sampler": ("sampler", ""),
    "sampler1d": ("sampler", "1D"), "sampler2d": ("sampler", "2D"),
    "sampler3d": ("sampler", "3D"), "samplercube": ("sampler", "CUBE"),
    # the later fxc's separate sampler (`SamplerState S;`, with `Texture2D T; T.Sample(S, uv)`)
    "samplerstate": ("sampler", ""),
    "vertexshader": ("vertexshader", ""), "pixelshader": ("pixelshader", ""),
    "stateblock": ("stateblock", ""),
}


def type_shape(spec: TypeSpec) -> tuple[int, ...]:
    """The numeric shape of one element of a type: () scalar, (n,) vector, (r, c) matrix.
    Read from the spelling, because float and float1 share rows/cols but not shape."""
    spelling = spec.spelling.lower()
    if spelling == "vector":
        return (4,)
    if spelling == "matrix":
        return (4, 4)
    m = _NUMERIC_RE.fullmatch(spelling)
    if m is None:  # no spelling (a model built in code): infer from rows/cols
        if spec.rows > 1:
            return (spec.rows, spec.cols)
        return (spec.cols,) if spec.cols > 1 else ()
    if m.group(3):
        return (int(m.group(2)), int(m.group(3)))
    return (int(m.group(2)),) if m.group(2) else ()


def resolve_type(name: str, structs: set[str] = frozenset()) -> TypeSpec | None:
    """The TypeSpec a type name denotes, or None when no such type exists."""
    spec = _built_in(name)
    if spec is None and name in structs:
        return TypeSpec(name, struct=True, spelling=name)
    return spec


# TypeSpec is immutable: one object per spelling of a built-in type serves every declaration
# (an effect declares thousands of float4 and texture parameters, annotations typed string);
# bounded, as spellings come from the file
@caches.memo("frontend.type_names", keys="a type's spelling", entry_bytes=256,
             max_bytes=4096 * 256)
def _built_in(name: str) -> TypeSpec | None:
    """`resolve_type` for the language's own types (a struct name is no built-in type)."""
    low = name.lower()
    template = _TEMPLATE_RE.fullmatch(low)
    if template:  # `matrix<float,4,3>` is float4x3, `vector<float,3>` float3
        base, a, b = template.groups()
        if low.startswith("vector") and b is None:
            spelled = f"{base}{a or 4}"
        elif low.startswith("matrix") and (a is None) == (b is None):
            spelled = f"{base}{a or 4}x{b or 4}"
        else:
            return None
        spec = resolve_type(spelled)
        if spec is None or not spec.is_numeric:
            return None
        return TypeSpec(spec.base, spec.rows, spec.cols, spelling=spelled)
    if low == "vector":
        return TypeSpec("float", 1, 4, spelling=name)
    if low == "matrix":
        return TypeSpec("float", 4, 4, spelling=name)
    m = _NUMERIC_RE.fullmatch(low)
    if m:
        base = _BASE_OF[m.group(1)]
        if m.group(3):
            return TypeSpec(base, int(m.group(2)), int(m.group(3)), spelling=name)
        return TypeSpec(base, 1, int(m.group(2) or 1), spelling=name)
    if low in _OBJECT_TYPES:
        base, dim = _OBJECT_TYPES[low]
        return TypeSpec(base, dim=dim, spelling=name)
    return None

