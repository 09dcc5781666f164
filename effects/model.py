"""The effect model: what an effect file says, as dataclasses that know where they came from.

The parser builds these; validation, selection, lowering and the printer read them: they are
functions over this data in the layers above, and this module imports none of them. (The
`Effect` users get from `effects.load_effect` is `effects.api.Effect`, this class with those
functions as methods.) Locations never take part in equality, so an effect printed with
`to_source()` and parsed again compares equal to the original.
"""
from __future__ import annotations

import sys
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Iterator, Union

from effects.base.errors import EffectWarning, Location, UNKNOWN_LOCATION

if TYPE_CHECKING:  # pragma: no cover
    import numpy as np


def _loc() -> Any:
    return field(default=UNKNOWN_LOCATION, compare=False, repr=False)


def values_equal(a: Any, b: Any) -> bool:
    """Equality that treats numpy arrays by value (dataclass __eq__ cannot)."""
    # The model does not import numpy (`effects profiles` and `--help` start without it): the
    # parser that makes arrays does, and until then no value can be one.
    np = sys.modules.get("numpy")
    if np is not None and (isinstance(a, np.ndarray) or isinstance(b, np.ndarray)):
        return (isinstance(a, np.ndarray) and isinstance(b, np.ndarray)
                and a.dtype.kind == b.dtype.kind and a.shape == b.shape
                and bool(np.array_equal(a, b)))
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return type(a) is type(b) and len(a) == len(b) and all(map(values_equal, a, b))
    return a == b


# --------------------------------------------------------------------------------------------
# Types


@dataclass(frozen=True, slots=True)
class TypeSpec:
    """A parameter type. `base` is canonical lower case: bool, int, half, float, dword, string,
    texture, sampler, vertexshader, pixelshader, or a struct name (then `struct=True`).
    `rows`/`cols` give the numeric shape (float4 → 1×4, float4x4 → 4×4, scalar 1×1).
    `dim` is '', '1D', '2D', '3D' or 'CUBE' for textures and samplers. `spelling` is the text
    the file used (`VECTOR`, `float4`, `matrix`...), kept for printing; it is not compared.
    """

    base: str
    rows: int = 1
    cols: int = 1
    dim: str = ""
    struct: bool = False
    spelling: str = field(default="", compare=False)

    @property
    def is_numeric(self) -> bool:
        return self.base in ("bool", "int", "half", "float", "dword")

    @property
    def is_object(self) -> bool:
        return self.base in ("string", "texture", "sampler", "vertexshader", "pixelshader")

    @property
    def takes_image(self) -> bool:
        """A host can bind a picture to it: a texture, or a sampler (the texture on the stage
        its shader samples, where its sampler_state names none: the host's SetTexture)."""
        return self.base in ("texture", "sampler")

    @property
    def components(self) -> int:
        return self.rows * self.cols


# --------------------------------------------------------------------------------------------
# Values


@dataclass(slots=True)
class Annotation:
    type: TypeSpec
    name: str
    value: Any  # numpy array for numeric annotations, str for strings
    location: Location = _loc()

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, Annotation) and self.type == other.type
                and self.name == other.name and values_equal(self.value, other.value))


@dataclass(frozen=True, slots=True)
class ParamRef:
    """A reference to a parameter as a state value: `<name>` (DX8, `angle=True`), `(name)` or
    `name`; `index` for an array element such as `(vsArray[2])`."""

    name: str
    angle: bool = False
    index: int | None = None
    location: Location = _loc()


@dataclass(frozen=True, slots=True)
class EnumValue:
    """An enum state value, possibly `|`-combined. `names` are canonical (no D3DTOP_ prefix,
    upper case) in source order; `value` is the combined integer from the states table (None
    when the state is unknown and the names could not be resolved)."""

    names: tuple[str, ...]
    value: int | None = None
    location: Location = _loc()


@dataclass(frozen=True, slots=True)
class NullValue:
    location: Location = _loc()


@dataclass(frozen=True, slots=True)
class VertexDeclElement:
    """One line of a DX8 `decl {}` block: `float v0[3];` → ('float', 0, 3) of `stream`."""

    stream: int
    type: str
    register: int
    count: int
    location: Location = _loc()


@dataclass
class ShaderBlock:
    """An `asm { ... }` shader. `stage` is 'vertex' or 'pixel'; `version` the canonical
    profile (`ps_1_1`, `vs_2_0` ...) read from the first token, or None when the text is not
    Direct3D assembly. `source` is the exact body text between the braces and `location` the
    position of the first character of that body, so line k of `source` is line
    `location.line + k` of the file."""

    stage: str
    version: str | None
    source: str
    decl: tuple[VertexDeclElement, ...] | None = None
    location: Location = _loc()
    # the assembler's result for this text and position, with the key it was made from, as
    # effects.shaders.asm.assemble_cached keeps it (derived: no init, repr or compare)
    _assembled: tuple | None = field(default=None, init=False, repr=False, compare=False)

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, ShaderBlock) and self.stage == other.stage
                and self.version == other.version and self.source.strip() == other.source.strip()
                and self.decl == other.decl)

    __hash__ = None  # type: ignore[assignment]


@dataclass(eq=False)
class BytecodeShader(ShaderBlock):
    """A shader given as Direct3D 9 bytecode (a shader object of an fx_2_0 effect binary):
    `data` is the token stream, `version` read from its version token, `source` empty. It is
    a ShaderBlock to everything that asks which version a shader is; its program is read from
    the bytecode (effects.shaders.shader_value.shader_of), never assembled from text.
    `location` is where the bytecode starts in the binary (line 1, the byte offset + 1 as the
    column), so an error in it is located in the file."""

    data: bytes = b""
    # the program and bindings read from `data`, as effects.shaders.shader_value keeps them
    # (derived: no init, repr or compare)
    _read: Any = field(default=None, init=False, repr=False, compare=False)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, BytecodeShader) and self.data == other.data

    __hash__ = None  # type: ignore[assignment]


@dataclass(frozen=True, slots=True)
class CompileShader:
    """`compile vs_1_1 func(args)`: an HLSL function compiled for a profile (args as source text)."""

    profile: str
    function: str
    args: tuple[str, ...] = ()
    location: Location = _loc()


@dataclass(frozen=True, slots=True)
class Expression:
    """A state value we keep as text: a preshader expression such as `Bias * 2`."""

    text: str
    location: Location = _loc()


@dataclass(frozen=True, slots=True)
class Preshader(Expression):
    """An expression state as an fx_2_0 binary keeps it: fxc's compiled preshader (the FXLC
    program with its constant table and literals, `data`, at byte `offset` of the binary),
    run on the host as a source expression is evaluated (effects.shaders.fxlc). `components`:
    how many of its output components the state takes (the binary's type for the state's
    value; 0: all). `selects`: the shader array whose element the program's value picks
    (`VertexShader = vs_arr[i]`), if any."""

    data: bytes = field(default=b"", repr=False)
    offset: int = 0
    components: int = 0
    selects: str | None = None


StateValue = Union["np.ndarray", str, bool, EnumValue, ParamRef, NullValue, ShaderBlock,
                   CompileShader, Expression, "SamplerState"]


@dataclass(slots=True)
class StateAssignment:
    """`Name = value;` or `Name[index] = value;`. `name` is the states table's canonical
    spelling when the state is known (`known=True`), otherwise the text as written."""

    name: str
    value: Any
    index: int | None = None
    known: bool = True
    location: Location = _loc()

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, StateAssignment) and self.name == other.name
                and self.index == other.index and self.known == other.known
                and values_equal(self.value, other.value))


@dataclass(slots=True)
class SamplerState:
    """`sampler_state { ... }` (also `stateblock_state`)."""

    states: list[StateAssignment] = field(default_factory=list)
    location: Location = _loc()

    def __eq__(self, other: object) -> bool:
        return isinstance(other, SamplerState) and self.states == other.states

    def get(self, name: str) -> StateAssignment | None:
        """The last assignment to `name` (last wins, as in D3DX)."""
        for s in reversed(self.states):
            if s.name.lower() == name.lower():
                return s
        return None


# --------------------------------------------------------------------------------------------
# Declarations


def register_binding(text: str) -> tuple[str, str]:
    """`register(c4)` as ('', 'c4'), `register(ps, c1)` as ('ps', 'c1'): lower-case."""
    parts = [p.strip().lower() for p in text.strip()[len("register("):-1].split(",")]
    return ("", parts[0]) if len(parts) == 1 else (parts[0], parts[1])


@dataclass(slots=True)
class Parameter:
    name: str
    type: TypeSpec
    storage: tuple[str, ...] = ()
    array: tuple[int, ...] = ()
    semantic: str | None = None
    annotations: list[Annotation] = field(default_factory=list)
    # numpy array (numeric), str (string), SamplerState, ShaderBlock, CompileShader, list of
    # those for arrays of objects, or None when uninitialised
    value: Any = None
    location: Location = _loc()
    # `: register(c4)` / `: register(ps, c1)` bindings as (profile, register), lower-case:
    # profile '' for every shader, else 'vs' / 'ps' or a target such as 'ps_2_0'
    registers: tuple[tuple[str, str], ...] = ()
    # the tbuffer it is a member of (`tbuffer Bones { float4 M[60]; };`), '' for none: fxc
    # read a texture buffer on shader model 4 only (X3546 for the models 1-3)
    tbuffer: str = ""

    def __post_init__(self) -> None:
        # `Parameter(semantic="register(c4)")`, as code builds one: the binding it names
        if not self.registers and self.semantic and self.semantic.lower().startswith("register("):
            self.registers = (register_binding(self.semantic),)

    def register_for(self, target: str, kind: str) -> str | None:
        """The register of kind `kind` ('c', 's', 'i', 'b') this parameter is bound to in a
        shader compiled for `target` ('ps_2_0'): a binding naming that target wins over one
        naming its stage ('ps'), which wins over an unqualified one; None when unbound."""
        rank = {target.lower(): 0, target[:2].lower(): 1, "": 2}
        best = None
        for profile, register in self.registers:
            if profile in rank and register[:1] == kind and register[1:].isdigit() and \
                    (best is None or rank[profile] < best[0]):
                best = (rank[profile], register)
        return None if best is None else best[1]

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, Parameter) and self.name == other.name
                and self.type == other.type and self.storage == other.storage
                and self.array == other.array and self.semantic == other.semantic
                and self.annotations == other.annotations
                and self.registers == other.registers
                and values_equal(self.value, other.value))

    def annotation(self, name: str) -> Annotation | None:
        return _find_annotation(self.annotations, name)

    @property
    def declared_texture_kind(self) -> str | None:
        """'2d', '1d', 'cube' or '3d' as a texture parameter's `string Type` (or `TextureType`,
        or FX Composer's `ResourceType`) annotation or its type (textureCUBE) says; None for an
        untyped `texture`."""
        for key in ("Type", "TextureType", "ResourceType"):
            ann = self.annotation(key)
            if ann is not None and isinstance(ann.value, str) and ann.value.upper() in TEXTURE_KINDS:
                return TEXTURE_KINDS[ann.value.upper()]
        return TEXTURE_KINDS.get(self.type.dim.upper()) if self.type.dim else None


# Texture kinds as annotations and type suffixes spell them -> the IR's sampler kinds.
TEXTURE_KINDS = {"2D": "2d", "1D": "1d", "CUBE": "cube", "3D": "3d", "VOLUME": "3d"}


@dataclass(slots=True)
class Struct:
    """A user type for HLSL: a `struct` or a global `typedef` (its name and exact text)."""

    name: str
    source: str  # exact text of the declaration
    location: Location = _loc()
    row_major: bool = False  # declared under `#pragma pack_matrix(row_major)`


@dataclass(slots=True)
class Function:
    """An HLSL function captured with its exact source text (compiled by a later stage)."""

    name: str
    return_type: str
    source: str
    location: Location = _loc()
    row_major: bool = False  # declared under `#pragma pack_matrix(row_major)`
    # the lines of `source` macro expansion made: (line of `source`, where its pieces came
    # from (effects.base.errors.through_expansion), ((file line, its text as written), ...)),
    # so an HLSL error in them points into the file as written
    expanded: tuple = field(default=(), compare=False)


@dataclass(slots=True)
class Pass:
    name: str | None
    states: list[StateAssignment] = field(default_factory=list)
    annotations: list[Annotation] = field(default_factory=list)
    location: Location = _loc()

    def state(self, name: str, index: int | None = None) -> StateAssignment | None:
        """The effective assignment of a state in this pass (the last one wins)."""
        key = name.lower()
        for s in reversed(self.states):
            if s.name.lower() == key and s.index == index:
                return s
        return None


@dataclass(slots=True)
class Technique:
    name: str | None
    passes: list[Pass] = field(default_factory=list)
    annotations: list[Annotation] = field(default_factory=list)
    location: Location = _loc()

    def annotation(self, name: str) -> Annotation | None:
        return _find_annotation(self.annotations, name)


@dataclass
class Effect:
    path: str
    parameters: list[Parameter] = field(default_factory=list)
    techniques: list[Technique] = field(default_factory=list)
    functions: list[Function] = field(default_factory=list)
    structs: list[Struct] = field(default_factory=list)
    warnings: list[EffectWarning] = field(default_factory=list, compare=False)
    # paths of every file read (the effect and its #includes), for hot reload
    files: tuple[str, ...] = field(default=(), compare=False)
    # the folder every file the effect names must lie in (load_effect's include_root), or None
    include_root: str | None = field(default=None, compare=False)
    # Derived, kept with the effect (so they go with it; a copy made by dataclasses.replace
    # starts without them): not what the effect says, so no init, repr or compare.
    # the name, semantic and sampler maps of `_index`
    _parameter_index: "_ParameterIndex | None" = field(default=None, init=False, repr=False,
                                                       compare=False)
    # the HLSL compile cache's keys of this effect's `compile` states, as
    # effects.shaders.hlsl.cache.compile_key keeps them ({CompileShader: its kept key})
    _compile_keys: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    # -- lookup ------------------------------------------------------------------------------
    def every_state(self) -> Iterator[StateAssignment]:
        """Every state assignment the effect holds: the `sampler_state` blocks of its
        parameters (each element of an array), then each pass's states, in file order."""
        for p in self.parameters:
            for v in p.value if isinstance(p.value, list) else [p.value]:
                if isinstance(v, SamplerState):
                    yield from v.states
        for t in self.techniques:
            for ps in t.passes:
                yield from ps.states

    def technique(self, name: str) -> Technique:
        for t in self.techniques:
            if t.name == name:
                return t
        from effects.base.errors import EffectError
        known = ", ".join(t.name or "<anonymous>" for t in self.techniques)
        raise EffectError(f"no technique named '{name}' (the effect has: {known})",
                          Location(self.path, 1, 1))

    def parameter(self, name: str) -> Parameter | None:
        """The first parameter named `name` (a dict lookup; see `_ParameterIndex`)."""
        index = self._index()
        found = index.by_name.get(name)
        if found is not None and found.name != name:   # renamed since the index was built
            index = self._index(rebuild=True)
            found = index.by_name.get(name)
        return found

    def parameter_by_semantic(self, semantic: str) -> Parameter | None:
        return self._index().by_semantic.get(semantic.lower())

    def sampler_dim_of(self, texture: str) -> str | None:
        """The dim ('2D', 'CUBE', ...) of the first typed sampler whose sampler_state binds the
        texture parameter `texture` (`Texture = <name>`), or None."""
        return self._index().sampler_dims.get(texture)

    def _index(self, rebuild: bool = False) -> "_ParameterIndex":
        # Lookups by name happen per state per pass per card: a linear scan made validation
        # and lowering quadratic in the file. The index is rebuilt when the parameter list is
        # replaced or changes length (the parser appends; the runtime copies the list).
        index = self._parameter_index
        params = self.parameters
        if rebuild or index is None or index.list_id != id(params) or index.size != len(params):
            index = self._parameter_index = _ParameterIndex(params)
        return index


class _ParameterIndex:
    """Name, semantic and sampler-binding maps over one parameter list (first match wins,
    as the linear scans they replace did)."""

    def __init__(self, parameters: list[Parameter]) -> None:
        self.list_id, self.size = id(parameters), len(parameters)
        self.by_name: dict[str, Parameter] = {}
        self.by_semantic: dict[str, Parameter] = {}
        self.sampler_dims: dict[str, str] = {}
        for p in parameters:
            self.by_name.setdefault(p.name, p)
            if p.semantic:
                self.by_semantic.setdefault(p.semantic.lower(), p)
            if p.type.base == "sampler" and p.type.dim:
                for s in p.value if isinstance(p.value, list) else [p.value]:
                    bound = s.get("Texture") if isinstance(s, SamplerState) else None
                    if bound is not None and isinstance(bound.value, ParamRef):
                        self.sampler_dims.setdefault(bound.value.name, p.type.dim)


class RecordedReads:
    """A view of an effect that notes every parameter looked up through it (by name, and the
    sampler binding of a texture). Validation and lowering read parameters only this way, so
    a result computed through the view depends on the effect's structure (its techniques, which
    copies of the effect share) and on these reads alone; `still_holds` checks them again, at
    the cost of what was read rather than of every parameter the file declares."""

    def __init__(self, effect: Effect) -> None:
        self.effect, self.path = effect, effect.path
        self._reads: dict[tuple[str, str], Any] = {}

    def parameter(self, name: str) -> Parameter | None:
        param = self.effect.parameter(name)
        self._reads[("parameter", name)] = param
        return param

    def sampler_dim_of(self, texture: str) -> str | None:
        dim = self.effect.sampler_dim_of(texture)
        self._reads[("sampler_dim_of", texture)] = dim
        return dim

    def __getattr__(self, name: str) -> Any:   # techniques, technique(), warnings ...
        return getattr(self.effect, name)

    def snapshot(self) -> tuple:
        return tuple((what, name, _fingerprint(value)) for (what, name), value in self._reads.items())


def still_holds(effect: Effect, snapshot: tuple) -> bool:
    """Whether every read of a `RecordedReads.snapshot` gives the same answer on `effect`."""
    for what, name, fp in snapshot:
        if not _same_fingerprint(_fingerprint(getattr(effect, what)(name)), fp):
            return False
    return True


def _fingerprint(value: Any) -> tuple:
    """A parameter as validation and lowering see it: its type (an untyped texture takes the
    kind of what is bound), annotations (`string Type`) and value: arrays by bytes, other
    objects (shader blocks, sampler states, lists of them) by identity; a plain value as is."""
    if not isinstance(value, Parameter):
        return ("plain", value)
    v = value.value
    if hasattr(v, "tobytes") and hasattr(v, "dtype"):
        held: tuple = ("array", v.dtype.str, v.shape, v.tobytes())
    elif v is None or isinstance(v, (str, int, float, bool)):
        held = ("plain", type(v), v)
    else:
        held = ("object", v)
    return ("parameter", value.type, value.annotations, held)


def _same_fingerprint(a: tuple, b: tuple) -> bool:
    if a[0] != b[0] or a[0] == "plain":
        return a == b
    if a[1] != b[1] or (a[2] is not b[2] and a[2] != b[2]):
        return False
    va, vb = a[3], b[3]
    return va[0] == vb[0] and (va[1] is vb[1] if va[0] == "object" else va == vb)


def _find_annotation(annotations: list[Annotation], name: str) -> Annotation | None:
    key = name.lower()
    for a in annotations:
        if a.name.lower() == key:
            return a
    return None
