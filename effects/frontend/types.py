"""Type names of the effect language → `TypeSpec`, and the numeric shape of a type."""
from __future__ import annotations

import re

from effects.base import caches
from effects.model import TypeSpec

__all__ = ["type_shape", "resolve_type", "texture_element", "texture_element_error"]

_NUMERIC_RE = re.compile(r"(bool|int|uint|half|float|double|dword)([1-4])?(?:x([1-4]))?")
_BASE_OF = {"bool": "bool", "int": "int", "uint": "dword", "half": "half", "float": "float",
            "double": "float", "dword": "dword"}
_TEMPLATE_RE = re.compile(r"(?:matrix|vector)<([a-z]+)(?:,([1-4]))?(?:,([1-4]))?>")
# `Texture2D<float4>`: the later fxc's texture with the type its reads return
_TEXTURE_TEMPLATE_RE = re.compile(r"(texture1d|texture2d|texture3d|texturecube)<([a-z0-9_]+)>")
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
    texture = _TEXTURE_TEMPLATE_RE.fullmatch(low)
    if texture:
        if texture_element_error(name) is not None:
            return None
        base, dim = _OBJECT_TYPES[texture.group(1)]
        return TypeSpec(base, dim=dim, spelling=name)
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



def texture_element(spec: TypeSpec) -> TypeSpec | None:
    """The type a `Texture2D<float2>`'s reads return (float2), or None for a texture declared
    without one (its reads return float4) and for every other type."""
    m = _TEXTURE_TEMPLATE_RE.fullmatch(spec.spelling.lower()) if spec.base == "texture" else None
    return _built_in(spec.spelling[spec.spelling.index("<") + 1:-1]) if m else None


def texture_element_error(name: str) -> str | None:
    """Why `name`, a texture with a template argument (`Texture2D<float4x4>`), is no type, as
    the later fxc refused it (its error list: X3124 an object element type, X3521 a return type
    over four components), or None when it is one or is not such a texture."""
    m = _TEXTURE_TEMPLATE_RE.fullmatch(name.lower())
    if m is None:
        return None
    argument = name[name.index("<") + 1:-1]
    element = _built_in(argument)
    if element is not None and element.is_object:
        return f"X3124: '{name}': object element type cannot be an object type"
    if element is None or not element.is_numeric:
        return (f"unknown type '{argument}' in '{name}' (a texture's element type is a scalar, "
                f"vector or matrix type: float4, float, int2 ...)")
    if element.rows * element.cols > 4:
        return (f"X3521: '{name}': the return type of a texture cannot exceed four components "
                f"('{argument}' has {element.rows * element.cols})")
    return None
