"""What each Direct3D shader version allows: registers, read ports, slots, modifiers, swizzles.

One row per version; the parser, the checker and the caps validator all read these rows.
Sources: the DirectX 9 assembly reference (register tables "ps_1_1__ps_1_2__ps_1_3__ps_1_4
Registers", "ps_2_0 Registers", "ps_2_x Registers", "Registers - vs_1_1/vs_2_0/vs_3_0",
"Modifiers for ps_1_X", "Pixel Shader Source Register Modifiers", "Source Register Swizzling",
the per-version instruction tables) as restated in docs/reference/caps.md §1 and
docs/reference/semantics.md §2–4.

Where a limit depends on the card (ps_2_x slots and temps, constants in vertex shaders), the row
holds the largest value the version can address (`check()` enforces that) and the guaranteed
minimum beside it; the caps validator compares `AsmProgram.stats` with the card's own caps.
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from functools import cached_property

# Register kinds as the parser names them, with the words used in messages.
KIND_NAMES = {
    "r": "temporary", "c": "constant", "t": "texture", "v": "input", "s": "sampler",
    "a": "address", "b": "boolean constant", "i": "integer constant", "p": "predicate",
    "aL": "loop counter", "o": "output", "oPos": "position output", "oD": "colour output",
    "oT": "texture coordinate output", "oFog": "fog output", "oPts": "point size output",
    "oC": "colour output", "oDepth": "depth output", "vPos": "position input",
    "vFace": "face input", "l": "label",
}

# Replicate swizzles and the ps_2_0 fixed set (Source Register Swizzling page).
IDENTITY = (0, 1, 2, 3)
PS20_SWIZZLES = {IDENTITY, (1, 2, 0, 3), (2, 0, 1, 3), (3, 2, 1, 0)}


@dataclass(frozen=True)
class VersionRules:
    """The rules of one shader version. `registers` maps a register kind to how many a
    program may address (index range 0..n-1); kinds missing from it do not exist here."""

    name: str                      # canonical: 'ps_1_1', 'vs_2_0', 'ps_2_a'
    kind: str                      # 'ps' | 'vs'
    major: int
    minor: int                     # 0..4; ps_2_x/2_a/2_b and vs_2_x/2_a count as 2.1
    registers: dict[str, int]
    writable: frozenset[str]       # kinds arithmetic may write
    readable: frozenset[str]       # kinds an ordinary source may read
    read_ports: dict[str, int]     # distinct registers of a kind one instruction may read
    tex_slots: int | None          # texture-instruction slots (None: no separate limit)
    arith_slots: int | None
    total_slots: int               # the most this version can hold
    total_slots_min: int           # what every card of this version guarantees
    per_phase: bool = False        # ps_1_4: tex/arith limits apply to each phase
    shifts: tuple[int, ...] = ()   # allowed instruction shifts (_x2 = 1, _d2 = -1 ...)
    saturate: bool = True
    partial_precision: bool = False
    src_modifiers: frozenset[str] = frozenset()   # beyond negate
    swizzles: str = "any"          # 'ps11' | 'ps14' | 'ps20' | 'any'
    masks: str = "any"             # 'ps11' (rgba, rgb, a) | 'any' (ordered subsets)
    dependent_read_limit: int | None = None   # levels of texture reads
    coissue: bool = False
    flow_control: bool = False
    predication: bool = False
    gradients: bool = False
    temps_min: int = 0             # guaranteed r# count (ps_2_x: 12 of up to 32)
    constants_min: int = 0         # guaranteed c# count (vs: MaxVertexShaderConst floor)
    notes: str = ""

    # asked for every instruction the checker sees: worked out once per version
    @cached_property
    def is_ps1(self) -> bool:
        return self.kind == "ps" and self.major == 1

    @cached_property
    def is_ps11_13(self) -> bool:
        return self.kind == "ps" and self.major == 1 and self.minor < 4

    @cached_property
    def is_ps14(self) -> bool:
        return self.kind == "ps" and self.major == 1 and self.minor == 4

    @property
    def dotted(self) -> str:
        """The version as DX8 files write it, e.g. ps.1.1."""
        return self.name.replace("_", ".")


def _ps1(name: str, minor: int, *, t_ports: int, r: int = 2, t: int = 4) -> VersionRules:
    ps14 = minor == 4
    return VersionRules(
        name=name, kind="ps", major=1, minor=minor,
        registers={"c": 8, "r": r, "t": t, "v": 2},
        writable=frozenset({"r"} if ps14 else {"r", "t"}),
        readable=frozenset({"c", "r", "t", "v"}),
        read_ports={"c": 2, "r": 3 if ps14 else 2, "t": t_ports, "v": 2},
        # ps.1.0 (DX8.0 docs): 4 texture-address instructions and 8 in all
        tex_slots=6 if ps14 else 4, arith_slots=8 if minor else None,
        total_slots=28 if ps14 else (8 if minor == 0 else 12),
        total_slots_min=28 if ps14 else (8 if minor == 0 else 12),
        per_phase=ps14,
        shifts=(-3, -2, -1, 0, 1, 2, 3) if ps14 else (-1, 0, 1, 2),
        src_modifiers=frozenset({"bias", "bx2", "invert"} | ({"x2", "dz", "dw"} if ps14 else set())),
        swizzles="ps14" if ps14 else "ps11",
        masks="any" if ps14 else "ps11",
        coissue=True,
        notes="c# reads clamp to [-1, 1]",
    )


def _ps2(name: str, minor: int, *, temps: int, temps_min: int, slots: int, tex_arith: bool,
         dep_limit: int | None, flow: bool, pred: bool, grad: bool, arb: bool) -> VersionRules:
    regs = {"c": 32, "r": temps, "t": 8, "v": 2, "s": 16, "oC": 4, "oDepth": 1}
    if minor:
        regs.update({"b": 16, "i": 16})
        if pred:
            regs["p"] = 1
    return VersionRules(
        name=name, kind="ps", major=2, minor=minor, registers=regs,
        writable=frozenset({"r", "oC", "oDepth"} | ({"p"} if pred else set())),
        readable=frozenset({"c", "r", "t", "v"}),
        read_ports={"c": 2, "r": 3, "t": 1, "v": 1, "s": 1},
        tex_slots=32 if tex_arith else None, arith_slots=64 if tex_arith else None,
        total_slots=slots, total_slots_min=96,
        partial_precision=True,
        swizzles="any" if arb else "ps20",
        dependent_read_limit=dep_limit,
        flow_control=flow, predication=pred, gradients=grad,
        temps_min=temps_min, constants_min=32,
    )


def _vs(name: str, major: int, minor: int, *, temps: int, slots: int, slots_min: int,
        consts_min: int, c_ports: int | None) -> VersionRules:
    regs = {"v": 16, "r": temps, "c": 8192, "a": 1}
    outputs = {"oPos": 1, "oD": 2, "oT": 8, "oFog": 1, "oPts": 1}
    if major >= 2:
        regs.update({"b": 16, "i": 16, "aL": 1})
    if minor or major == 3:
        regs["p"] = 1
    if major == 3:
        regs.update({"s": 4, "o": 12})
    else:
        regs.update(outputs)
    out_kinds = {"o"} if major == 3 else set(outputs)
    return VersionRules(
        name=name, kind="vs", major=major, minor=minor, registers=regs,
        writable=frozenset({"r", "a"} | out_kinds | ({"p"} if "p" in regs else set())),
        readable=frozenset({"c", "r", "v"} | ({"a"} if major >= 2 else set())),
        read_ports={k: n for k, n in {"c": c_ports, "v": 1, "r": 3}.items() if n},
        tex_slots=None, arith_slots=None, total_slots=slots, total_slots_min=slots_min,
        saturate=major == 3,
        src_modifiers=frozenset({"abs"} if major == 3 else set()),
        flow_control=major >= 2, predication="p" in regs,
        temps_min=12, constants_min=consts_min,
        notes="c# count is the card's MaxVertexShaderConst",
    )


VERSIONS: dict[str, VersionRules] = {v.name: v for v in [
    _ps1("ps_1_0", 0, t_ports=2),
    _ps1("ps_1_1", 1, t_ports=2),
    _ps1("ps_1_2", 2, t_ports=3),
    _ps1("ps_1_3", 3, t_ports=3),
    _ps1("ps_1_4", 4, t_ports=1, r=6, t=6),
    _ps2("ps_2_0", 0, temps=12, temps_min=12, slots=96, tex_arith=True, dep_limit=4,
         flow=False, pred=False, grad=False, arb=False),
    # ps_2_x: every optional PS20Caps feature is allowed here; the card's caps decide.
    _ps2("ps_2_x", 1, temps=32, temps_min=12, slots=512, tex_arith=False, dep_limit=None,
         flow=True, pred=True, grad=True, arb=True),
    # HLSL profiles (docs/reference/caps.md §1a): 2_a = arbitrary swizzle, gradients,
    # predication, no dependent-read or texture limit, >= 22 temps; 2_b = no texture limit,
    # 32 temps.
    _ps2("ps_2_a", 1, temps=22, temps_min=22, slots=512, tex_arith=False, dep_limit=None,
         flow=True, pred=True, grad=True, arb=True),
    _ps2("ps_2_b", 1, temps=32, temps_min=32, slots=512, tex_arith=False, dep_limit=4,
         flow=False, pred=False, grad=False, arb=False),
    VersionRules(
        name="ps_3_0", kind="ps", major=3, minor=0,
        registers={"c": 224, "r": 32, "v": 10, "s": 16, "b": 16, "i": 16, "p": 1, "aL": 1,
                   "oC": 4, "oDepth": 1, "vPos": 1, "vFace": 1},
        writable=frozenset({"r", "oC", "oDepth", "p"}),
        readable=frozenset({"c", "r", "v", "vPos", "vFace"}),
        read_ports={}, tex_slots=None, arith_slots=None, total_slots=32768, total_slots_min=512,
        partial_precision=True, src_modifiers=frozenset({"abs"}),
        flow_control=True, predication=True, gradients=True, temps_min=32, constants_min=224,
    ),
    _vs("vs_1_1", 1, 1, temps=12, slots=128, slots_min=128, consts_min=96, c_ports=1),
    # vs_2_0 table: c# "reads/inst 2"; we allow two distinct constants from vs_2_0 on.
    _vs("vs_2_0", 2, 0, temps=12, slots=256, slots_min=256, consts_min=256, c_ports=2),
    _vs("vs_2_x", 2, 1, temps=32, slots=256, slots_min=256, consts_min=256, c_ports=2),
    _vs("vs_2_a", 2, 1, temps=32, slots=256, slots_min=256, consts_min=256, c_ports=2),
    _vs("vs_3_0", 3, 0, temps=32, slots=32768, slots_min=512, consts_min=256, c_ports=None),
]}

# The order versions appear in messages ("available in ps_1_2, ps_1_3").
VERSION_ORDER = list(VERSIONS)

_VERSION_TOKEN = re.compile(r"(?i)^([pv]s)[._]([0-9])[._]([0-9]|x|a|b|sw)$")


def canonical_version(token: str) -> str | None:
    """'ps.1.1' / 'PS_1_1' / 'vs.2.0' → 'ps_1_1' ...; None when it is not a version token."""
    m = _VERSION_TOKEN.match(token.strip())
    if not m:
        return None
    return f"{m.group(1).lower()}_{m.group(2)}_{m.group(3).lower()}"


def version_rules(name: str) -> VersionRules | None:
    return VERSIONS.get(name)


@dataclass(frozen=True)
class Group:
    """A named set of versions, for the instruction table."""

    names: frozenset[str] = field(default_factory=frozenset)

    def __or__(self, other: "Group") -> "Group":
        return Group(self.names | other.names)

    def __contains__(self, name: object) -> bool:
        return name in self.names


def group(*names: str) -> Group:
    return Group(frozenset(names))


PS10_13 = group("ps_1_0", "ps_1_1", "ps_1_2", "ps_1_3")
PS12_13 = group("ps_1_2", "ps_1_3")
PS13 = group("ps_1_3")
PS14 = group("ps_1_4")
PS1 = PS10_13 | PS14
PS20 = group("ps_2_0")
PS2X = group("ps_2_x", "ps_2_a", "ps_2_b")
PS2 = PS20 | PS2X
PS3 = group("ps_3_0")
VS1 = group("vs_1_1")
VS2 = group("vs_2_0", "vs_2_x", "vs_2_a")
VS3 = group("vs_3_0")
VS = VS1 | VS2 | VS3
