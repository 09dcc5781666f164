"""HLSL types: scalars, vectors, matrices, structs, arrays, samplers, as one frozen dataclass.

A numeric value holds `rows * cols` components in row-major order (a vector is one row), so
swizzles, matrix swizzles (`._m00_m11`) and component-wise arithmetic read the same list.
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field

from effects.base import caches

# Conversion rank: an operation between two bases takes the higher one (fxc's rule).
RANKS = {"bool": 0, "int": 1, "uint": 2, "dword": 2, "half": 3, "float": 4, "double": 5}
SAMPLER_KINDS = {"sampler": "2d", "sampler1d": "1d", "sampler2d": "2d", "sampler3d": "3d",
                 "samplercube": "cube", "sampler_state": "2d", "samplerstate": "2d"}
# a texture's kind is its `base` ('' for an untyped `texture`): `Texture2D T; T.Sample(S, uv)`
# reads it as the texture says (intrinsics.texture_method)
TEXTURE_KINDS = {"texture": "", "texture1d": "1d", "texture2d": "2d", "texture3d": "3d",
                 "texturecube": "cube"}
_NUMERIC = re.compile(r"^(bool|int|uint|half|float|double|dword)([1-4])?(?:x([1-4]))?$")


@dataclass(frozen=True)
class HType:
    kind: str                        # 'scalar' 'vector' 'matrix' 'struct' 'array' 'sampler'
                                     # 'texture' 'string' 'void'
    base: str = "float"              # numeric base; sampler kind for samplers
    rows: int = 1
    cols: int = 1
    name: str = ""                   # struct name
    fields: tuple[tuple[str, "HType", str | None], ...] = ()   # struct members (semantic)
    element: "HType | None" = None   # arrays
    length: int = 0
    row_major: bool = field(default=False, compare=False)

    def __post_init__(self) -> None:
        # the numbers the type holds and its nesting, from its parts' (already known): a struct
        # of structs that doubles per level is counted without walking it (limits.py:
        # hlsl_components, hlsl_nesting are checked against these before anything is built)
        if self.kind in ("scalar", "vector", "matrix"):
            n, depth = self.rows * self.cols, 0
        elif self.kind == "struct":
            n = sum(f[1].components for f in self.fields)
            depth = 1 + max((f[1].depth for f in self.fields), default=0)
        elif self.kind == "array" and self.element is not None:
            n, depth = self.length * self.element.components, 1 + self.element.depth
        else:
            n, depth = 0, 0
        object.__setattr__(self, "components", n)
        object.__setattr__(self, "depth", depth)

    # set by __post_init__: not fields, so equality, hashing and the repr stay as they were
    components: int = field(init=False, repr=False, compare=False, default=0)
    depth: int = field(init=False, repr=False, compare=False, default=0)

    @property
    def numeric(self) -> bool:
        return self.kind in ("scalar", "vector", "matrix")

    @property
    def size(self) -> int:
        return self.rows * self.cols

    def with_base(self, base: str) -> "HType":
        if self.kind in ("scalar", "vector", "matrix"):
            return _numeric(self.kind, base, self.rows, self.cols)
        return HType(self.kind, base, self.rows, self.cols)

    def __str__(self) -> str:
        if self.kind == "scalar":
            return self.base
        if self.kind == "vector":
            return f"{self.base}{self.cols}"
        if self.kind == "matrix":
            return f"{self.base}{self.rows}x{self.cols}"
        if self.kind == "struct":
            return self.name
        if self.kind == "array":
            return f"{self.element}[{self.length}]"
        return self.kind if self.kind != "sampler" else "sampler"


# The evaluator asks for a numeric type per operator and per value (thousands per function);
# a type is frozen and equal by its fields, so one object per shape serves them all
@caches.memo("shaders.hlsl.types", keys="a numeric type's kind, base, rows and columns",
             entry_bytes=256, max_bytes=512 * 256)
def _numeric(kind: str, base: str, rows: int, cols: int) -> HType:
    return HType(kind, base, rows, cols)


def scalar(base: str = "float") -> HType:
    return _numeric("scalar", base, 1, 1)


def vector(base: str, n: int) -> HType:
    return _numeric("scalar", base, 1, 1) if n == 1 else _numeric("vector", base, 1, n)


def matrix(base: str, rows: int, cols: int) -> HType:
    return _numeric("matrix", base, rows, cols)


FLOAT, INT, BOOL, VOID = scalar("float"), scalar("int"), scalar("bool"), HType("void")


@caches.memo("shaders.hlsl.builtin_types", keys="a type's name", entry_bytes=256,
             max_bytes=512 * 256)
def builtin(name: str) -> HType | None:
    """The type a built-in name spells (`float4x3`, `half2`, `sampler2D`, `matrix`; kept per
    name, as `_numeric` keeps shapes)."""
    low = name.lower()
    if "<" in low:              # `Texture2D<float4>` (its element type: frontend.types)
        low = low.split("<", 1)[0].rstrip()
        return HType("texture", TEXTURE_KINDS[low]) if low in TEXTURE_KINDS else None
    if low in SAMPLER_KINDS:
        return HType("sampler", SAMPLER_KINDS[low])
    if low in TEXTURE_KINDS:
        return HType("texture", TEXTURE_KINDS[low])
    if low == "string":
        return HType("string")
    if low == "void":
        return VOID
    if low == "matrix":
        return matrix("float", 4, 4)
    if low == "vector":
        return vector("float", 4)
    m = _NUMERIC.match(name)
    if not m:
        return None
    base = "uint" if m.group(1) == "dword" else m.group(1)
    if m.group(3):
        return matrix(base, int(m.group(2)), int(m.group(3)))
    if m.group(2):
        return vector(base, int(m.group(2)))
    return scalar(base)


def shape_of(rows: int, cols: int, base: str) -> HType:
    if rows == 1:
        return vector(base, cols)
    return matrix(base, rows, cols)


def common_base(a: str, b: str) -> str:
    return a if RANKS.get(a, 4) >= RANKS.get(b, 4) else b


def register_count(t: HType, row_major: bool = False) -> int:
    """Constant registers a uniform of this type takes (fxc packing: each array element,
    struct member and matrix column (row, for row_major) starts a register)."""
    if t.kind in ("scalar", "vector"):
        return 1
    if t.kind == "matrix":
        return t.rows if (row_major or t.row_major) else t.cols
    if t.kind == "array" and t.element is not None:
        return t.length * register_count(t.element, row_major)
    if t.kind == "struct":
        return sum(register_count(f[1], row_major) for f in t.fields)
    return 0
