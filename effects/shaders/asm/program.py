"""An assembled shader program: instructions and operands as dataclasses that know their place.

`assemble()` (parser.py) builds these from a ShaderBlock; `check()` (check.py) reads them;
the lowering reads `Instruction.info` (the table row) to know what each instruction computes.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING

from effects.base.errors import Location, UNKNOWN_LOCATION
from effects.shaders.asm.instructions import InstrInfo
from effects.shaders.asm.versions import IDENTITY, VersionRules

if TYPE_CHECKING:  # pragma: no cover
    from effects.shaders.asm.stats import AsmStats

COMPONENTS = "xyzw"


@dataclass(frozen=True)
class RelativeAddress:
    """`c[a0.x + 5]`: the register indexing (a0 or aL), its component, and the offset is the
    operand's own index."""

    kind: str            # 'a' | 'aL'
    index: int
    component: int       # 0..3


@dataclass
class Operand:
    """A register operand as written. Sources carry `swizzle` (always four components, identity
    when none is written) and modifiers; a destination carries `mask` (None = all four)."""

    kind: str                              # 'r' 'c' 't' 'v' 's' 'a' 'b' 'i' 'p' 'aL' 'o' 'oPos'
                                           # 'oD' 'oT' 'oFog' 'oPts' 'oC' 'oDepth' 'vPos'
                                           # 'vFace' 'l'; 'imm' for a literal
    index: int | None
    location: Location = field(default=UNKNOWN_LOCATION, compare=False)
    text: str = field(default="", compare=False)
    swizzle: tuple[int, int, int, int] = IDENTITY
    swizzle_text: str = ""                 # as written, e.g. 'a', 'xyw', 'rgb' ('' = none)
    mask: tuple[int, ...] | None = None
    negate: bool = False
    modifier: str | None = None            # 'bias' 'bx2' 'x2' 'invert' 'dz' 'dw' 'abs'
    relative: RelativeAddress | None = None
    value: float | bool | None = None      # literal operands (def, defi, defb)
    # a source the HLSL compiler's generators made, before legalize.source_swizzle chose its
    # swizzle: instruction lane -> register lane read (None: `swizzle` says, as written)
    lanes: dict[int, int] | None = field(default=None, compare=False, repr=False)

    @property
    def name(self) -> str:
        """The register as D3D spells it: r0, c12, oPos, oT3, aL."""
        if self.kind == "imm":
            return self.text
        return f"{self.kind}{'' if self.index is None else self.index}"

    @property
    def components(self) -> tuple[int, ...]:
        """Components a destination writes (its mask, or all four)."""
        return self.mask if self.mask is not None else (0, 1, 2, 3)

    @property
    def is_replicate(self) -> bool:
        return len(set(self.swizzle)) == 1

    @property
    def mask_text(self) -> str:
        return "" if self.mask is None else "".join(COMPONENTS[i] for i in self.mask)


@dataclass
class Instruction:
    """One instruction. `shift` is the result scale exponent (_x2 = 1, _d2 = -1 ...);
    `phase` is 1 or 2 in ps_1_4 (None elsewhere); `coissue` marks a `+` paired instruction."""

    opcode: str
    dst: Operand | None
    srcs: list[Operand]
    info: InstrInfo
    location: Location = field(default=UNKNOWN_LOCATION, compare=False)
    shift: int = 0
    saturate: bool = False
    partial_precision: bool = False
    centroid: bool = False
    coissue: bool = False
    phase: int | None = None
    comparison: str | None = None          # if_gt, break_ne, setp_le: 'gt', 'ne', 'le'
    predicate: Operand | None = None       # (p0) / (!p0.x) prefix; negate = '!'
    opcode_text: str = field(default="", compare=False)
    source_line: str | None = field(default=None, compare=False, repr=False)

    @property
    def operands(self) -> list[Operand]:
        return ([self.dst] if self.dst is not None else []) + list(self.srcs)

    @property
    def is_texture(self) -> bool:
        return self.info.category == "tex"

    @property
    def is_arithmetic(self) -> bool:
        return self.info.category == "arith"


@dataclass
class Declaration:
    """`dcl_texcoord0 v1`, `dcl_2d s0`, `dcl t0.xy`, `dcl_position o0` ..."""

    register: Operand
    usage: str | None = None               # 'position', 'texcoord', 'normal' ... (vs, ps_3_0)
    usage_index: int = 0
    sampler_type: str | None = None        # '2d' | 'cube' | 'volume'
    partial_precision: bool = False
    centroid: bool = False
    location: Location = field(default=UNKNOWN_LOCATION, compare=False)
    after_code: bool = False               # written after the first instruction
    from_decl: bool = False                # a DX8 decl{} element, not written in the program


@dataclass
class ConstantDef:
    register: Operand
    values: tuple
    location: Location = field(default=UNKNOWN_LOCATION, compare=False)
    after_code: bool = False


@dataclass
class AsmProgram:
    """A parsed shader. `defs` maps c# to its four floats (defi/defb in `int_defs`/`bool_defs`);
    `dcls` lists declarations in source order (DX8 `decl{}` inputs included, marked
    `from_decl`). `phase_location` is where the ps_1_4 `phase` marker stands, if any."""

    kind: str                              # 'vs' | 'ps'
    version: tuple[int, int]               # (1, 1); 2_x/2_a/2_b count as (2, 1)
    name: str                              # canonical 'ps_1_1'
    rules: VersionRules
    instructions: list[Instruction] = field(default_factory=list)
    defs: dict[int, tuple[float, float, float, float]] = field(default_factory=dict)
    int_defs: dict[int, tuple[int, int, int, int]] = field(default_factory=dict)
    bool_defs: dict[int, bool] = field(default_factory=dict)
    dcls: list[Declaration] = field(default_factory=list)
    def_statements: list[ConstantDef] = field(default_factory=list)
    location: Location = UNKNOWN_LOCATION   # the version token
    origin: Location = UNKNOWN_LOCATION     # the block's first character (ShaderBlock.location)
    phase_locations: list[Location] = field(default_factory=list)
    # the block's lines as the file has them (line 0 padded to its file column), for carets
    source_lines: tuple[str, ...] = ()
    has_decl_block: bool = False
    # Worked out by modules this one cannot import (they import it), kept with the program:
    # check.check_cached's errors, and limits.lowering_cached's problems by integer constants
    _check_errors: list | None = field(default=None, init=False, repr=False, compare=False)
    _lowering_problems: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    @property
    def phase_location(self) -> Location | None:
        return self.phase_locations[0] if self.phase_locations else None

    @cached_property
    def stats(self) -> "AsmStats":
        from effects.shaders.asm.stats import compute_stats
        return compute_stats(self)

    # Asked of one program once per card: worked out once, kept with it. Read them; don't
    # change them. (check.check_cached keeps the checker's errors in a field instead: the
    # checker imports this module, so a property here would make an import cycle.)
    @cached_property
    def flow_nesting(self) -> tuple[int, int]:
        """`flow.nesting` of the instructions: (static, dynamic) flow-control depth."""
        from effects.shaders.asm.flow import nesting
        return nesting(self.instructions)

    @cached_property
    def read_levels(self) -> dict[int, int]:
        """`stats.texture_read_levels`: the level of every texture read, by position."""
        from effects.shaders.asm.stats import texture_read_levels
        return texture_read_levels(self)

    def declaration(self, kind: str, index: int) -> Declaration | None:
        for d in self.dcls:
            if d.register.kind == kind and d.register.index == index:
                return d
        return None

    def source_line(self, location: Location) -> str | None:
        """The text of the file line `location` points at, when it lies in this program."""
        k = location.line - self.origin.line
        if 0 <= k < len(self.source_lines):
            return self.source_lines[k]
        return None
