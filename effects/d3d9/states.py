"""The table of every Direct3D 9 effect state: one row per state, one table per value enum.

Everything that reads or writes a state assignment (parser, validator, lowering, runtime,
printer) asks this module: which states exist, what `[n]` means for each, which type its
value has, which enum names it takes, what the device default is, and which D3DCAPS9 field
limits the values a card accepts (`StateInfo.limit`, read by the validator; the bit names
and their header prefixes are `effects.d3d9.caps`' tables).

Sources (facts only, restated here):
- state names and their order: Wine `dlls/d3dx9_36/effect.c` `state_table`;
- value types: "Effect States (Direct3D 9)" (MicrosoftDocs/win32 effect-states.md);
- state codes and defaults: D3DRENDERSTATETYPE, D3DTEXTURESTAGESTATETYPE, D3DSAMPLERSTATETYPE
  docs, cross-checked with Wine `wined3d/stateblock.c` (`init_default_render_states`,
  `init_default_texture_state`, `init_default_sampler_states`, `WINED3D_default_light`);
- enum values: the d3d9types.h enums as documented (D3DTEXTUREOP, D3DTA, D3DBLEND, ...);
- limiting caps: the d3d9caps.h fields as documented (D3DPBLENDCAPS, D3DPCMPCAPS,
  D3DSTENCILCAPS, D3DPMISCCAPS_CULL*, MASKZ, BLENDOP, SEPARATEALPHABLEND, D3DPRASTERCAPS_*).

`[n]` means, by `kind`: 'stage' → texture stage 0-7, 'sampler' / 'texture' / 'sampler_object'
→ sampler 0-15 (256-260 are the displacement-map and vertex samplers), 'light' → light index,
'transform' → world-matrix index (WorldTransform) or stage (TextureTransform), 'shader_const'
→ first constant register. An 'optional' index that is left out means 0 (inside
`sampler_state` it means "this sampler").
"""
from __future__ import annotations

import difflib
import sys
from dataclasses import dataclass, field
from collections.abc import Callable, Container, Iterable, Mapping
from types import MappingProxyType
from typing import Any

import math

import numpy as np

from effects.base.errors import Location, StateError
from effects.model import (CompileShader, EnumValue, Expression, NullValue, ParamRef, SamplerState,
                    ShaderBlock)

DWORD_MASK = 0xFFFFFFFF
# How many units the indexed kinds have on a D3D9 device: texture stages and pixel samplers.
MAX_STAGES = 8
MAX_SAMPLERS = 16
# TexCoordIndex: the D3DTSS_TCI_* texgen mode sits above this bit, the coordinate set below.
TCI_SHIFT = 16
# D3DDMAPSAMPLER and D3DVERTEXTEXTURESAMPLER0-3: sampler numbers above the 16 pixel samplers.
VERTEX_SAMPLER_INDICES = range(256, 261)
# D3DVERTEXTEXTURESAMPLER0 (= D3DDMAPSAMPLER + 1): vs_3_0's s0..s3 are samplers 257..260, so a
# pass binds them as `Sampler[257] = <s>` / `Texture[257]`, and lowered vertex programs sample
# IR sampler 257 + n.
VERTEX_TEXTURE_SAMPLER0 = 257
VERTEX_TEXTURE_SAMPLERS = 4


# ---------------------------------------------------------------------------------------------
# Enum tables


@dataclass(frozen=True, eq=False)
class EnumTable:
    """The names a state value may use. `values` maps canonical UPPER-CASE names (without the
    prefix) to numbers; `flags` tables allow `A | B`. `exclusive` lists groups of names of which
    at most one may appear in a combination (two D3DTA selectors, two TTFF counts ...)."""

    name: str
    prefixes: tuple[str, ...]
    values: Mapping[str, int]
    flags: bool = False
    aliases: Mapping[str, str] = field(default_factory=dict)      # other name -> canonical
    spellings: Mapping[str, str] = field(default_factory=dict)    # canonical -> 'Modulate'
    exclusive: tuple[tuple[str, frozenset[str]], ...] = ()        # (what they are, names)
    example: str = ""

    def lookup(self, name: str) -> tuple[str, int] | None:
        """(canonical name, value) for `name`, case-insensitive, prefix optional."""
        key = name.strip().upper()
        candidates = [key] + [key[len(p):] for p in self.prefixes if key.startswith(p)]
        for candidate in candidates:
            canonical = self.aliases.get(candidate, candidate)
            if canonical in self.values:
                # the one shared string (the table's key is an interned literal), not a copy
                # per state value that names it: effects keep thousands of these
                return sys.intern(canonical), self.values[canonical]
        return None

    def spelling(self, canonical: str) -> str:
        """How the docs write a name ('Modulate'); numbers and unknown names as given."""
        return self.spellings.get(canonical, canonical)

    def suggest(self, name: str) -> str | None:
        """The closest known name, spelled for a message, or None."""
        key = name.strip().upper()
        for p in self.prefixes:
            if key.startswith(p):
                key = key[len(p):]
                break
        pool = list(self.values) + list(self.aliases)
        match = difflib.get_close_matches(key, pool, n=1, cutoff=0.6)
        if not match:
            return None
        spelled = self.spelling(self.aliases.get(match[0], match[0]))
        # A name such as 2WEIGHTS can only be written with its prefix (D3DVBF_2WEIGHTS).
        return spelled if spelled[:1].isalpha() or spelled[:1] == "_" else self.prefixes[0] + match[0]


def _table(name: str, prefixes: Iterable[str], entries: Iterable[tuple[str, int]], *,
           flags: bool = False, aliases: Mapping[str, str] | None = None,
           exclusive: Iterable[tuple[str, Iterable[str]]] = (), example: str = "") -> EnumTable:
    entries = list(entries)
    values = {spelled.upper(): value for spelled, value in entries}
    spellings = {spelled.upper(): spelled for spelled, _ in entries}
    groups = tuple((what, frozenset(n.upper() for n in names)) for what, names in exclusive)
    return EnumTable(name, tuple(p.upper() for p in prefixes), MappingProxyType(values), flags,
                     MappingProxyType(dict(aliases or {})), MappingProxyType(spellings), groups,
                     example or entries[0][0])


D3DTEXTUREOP = _table("D3DTEXTUREOP", ["D3DTOP_"], [
    ("Disable", 1), ("SelectArg1", 2), ("SelectArg2", 3), ("Modulate", 4), ("Modulate2x", 5),
    ("Modulate4x", 6), ("Add", 7), ("AddSigned", 8), ("AddSigned2x", 9), ("Subtract", 10),
    ("AddSmooth", 11), ("BlendDiffuseAlpha", 12), ("BlendTextureAlpha", 13),
    ("BlendFactorAlpha", 14), ("BlendTextureAlphaPM", 15), ("BlendCurrentAlpha", 16),
    ("PreModulate", 17), ("ModulateAlpha_AddColor", 18), ("ModulateColor_AddAlpha", 19),
    ("ModulateInvAlpha_AddColor", 20), ("ModulateInvColor_AddAlpha", 21), ("BumpEnvMap", 22),
    ("BumpEnvMapLuminance", 23), ("DotProduct3", 24), ("MultiplyAdd", 25), ("Lerp", 26),
], example="Modulate")

_TA_SELECTORS = ("Diffuse", "Current", "Texture", "TFactor", "Specular", "Temp", "Constant")
D3DTA = _table("D3DTA", ["D3DTA_"], [
    *((name, value) for value, name in enumerate(_TA_SELECTORS)),
    ("Complement", 0x10), ("AlphaReplicate", 0x20),
], flags=True, exclusive=[("argument selectors", _TA_SELECTORS)], example="Texture")

D3DBLEND = _table("D3DBLEND", ["D3DBLEND_"], [
    ("Zero", 1), ("One", 2), ("SrcColor", 3), ("InvSrcColor", 4), ("SrcAlpha", 5),
    ("InvSrcAlpha", 6), ("DestAlpha", 7), ("InvDestAlpha", 8), ("DestColor", 9),
    ("InvDestColor", 10), ("SrcAlphaSat", 11), ("BothSrcAlpha", 12), ("BothInvSrcAlpha", 13),
    ("BlendFactor", 14), ("InvBlendFactor", 15), ("SrcColor2", 16), ("InvSrcColor2", 17),
], example="SrcAlpha")

D3DBLENDOP = _table("D3DBLENDOP", ["D3DBLENDOP_"], [
    ("Add", 1), ("Subtract", 2), ("RevSubtract", 3), ("Min", 4), ("Max", 5)])

D3DCMPFUNC = _table("D3DCMPFUNC", ["D3DCMP_"], [
    ("Never", 1), ("Less", 2), ("Equal", 3), ("LessEqual", 4), ("Greater", 5), ("NotEqual", 6),
    ("GreaterEqual", 7), ("Always", 8)], example="LessEqual")

D3DCULL = _table("D3DCULL", ["D3DCULL_"], [("None", 1), ("CW", 2), ("CCW", 3)], example="CCW")
D3DFILLMODE = _table("D3DFILLMODE", ["D3DFILL_"],
                     [("Point", 1), ("Wireframe", 2), ("Solid", 3)], example="Solid")
D3DSHADEMODE = _table("D3DSHADEMODE", ["D3DSHADE_"],
                      [("Flat", 1), ("Gouraud", 2), ("Phong", 3)], example="Gouraud")
D3DFOGMODE = _table("D3DFOGMODE", ["D3DFOG_"],
                    [("None", 0), ("Exp", 1), ("Exp2", 2), ("Linear", 3)], example="Linear")
D3DSTENCILOP = _table("D3DSTENCILOP", ["D3DSTENCILOP_"], [
    ("Keep", 1), ("Zero", 2), ("Replace", 3), ("IncrSat", 4), ("DecrSat", 5), ("Invert", 6),
    ("Incr", 7), ("Decr", 8)])
D3DTEXTUREADDRESS = _table("D3DTEXTUREADDRESS", ["D3DTADDRESS_"], [
    ("Wrap", 1), ("Mirror", 2), ("Clamp", 3), ("Border", 4), ("MirrorOnce", 5)])
# FlatCubic and GaussianCubic are DX8 filter names (values 4 and 5), gone from D3D9 headers.
D3DTEXTUREFILTERTYPE = _table("D3DTEXTUREFILTERTYPE", ["D3DTEXF_"], [
    ("None", 0), ("Point", 1), ("Linear", 2), ("Anisotropic", 3), ("FlatCubic", 4),
    ("GaussianCubic", 5), ("PyramidalQuad", 6), ("GaussianQuad", 7), ("ConvolutionMono", 8),
], example="Linear")
D3DZBUFFERTYPE = _table("D3DZBUFFERTYPE", ["D3DZB_"],
                        [("False", 0), ("True", 1), ("UseW", 2)], example="True")
D3DMATERIALCOLORSOURCE = _table("D3DMATERIALCOLORSOURCE", ["D3DMCS_"],
                                [("Material", 0), ("Color1", 1), ("Color2", 2)])
_TTFF_COUNTS = ("Disable", "Count1", "Count2", "Count3", "Count4")
D3DTEXTURETRANSFORMFLAGS = _table("D3DTEXTURETRANSFORMFLAGS", ["D3DTTFF_"], [
    *((name, value) for value, name in enumerate(_TTFF_COUNTS)), ("Projected", 0x100),
], flags=True, exclusive=[("coordinate counts", _TTFF_COUNTS)], example="Count2")
_TCI_MODES = ("PassThru", "CameraSpaceNormal", "CameraSpacePosition",
              "CameraSpaceReflectionVector", "SphereMap")
D3DTSS_TCI = _table("D3DTSS_TCI", ["D3DTSS_TCI_"], [
    (name, value << TCI_SHIFT) for value, name in enumerate(_TCI_MODES)
], flags=True, exclusive=[("texture coordinate generation modes", _TCI_MODES)],
    example="CameraSpaceReflectionVector")
D3DLIGHTTYPE = _table("D3DLIGHTTYPE", ["D3DLIGHT_"],
                      [("Point", 1), ("Spot", 2), ("Directional", 3)], example="Directional")
D3DVERTEXBLENDFLAGS = _table("D3DVERTEXBLENDFLAGS", ["D3DVBF_"], [
    ("Disable", 0), ("1Weights", 1), ("2Weights", 2), ("3Weights", 3), ("Tweening", 255),
    ("0Weights", 256)])
D3DCOLORWRITEENABLE = _table("D3DCOLORWRITEENABLE", ["D3DCOLORWRITEENABLE_"], [
    ("Red", 1), ("Green", 2), ("Blue", 4), ("Alpha", 8)], flags=True)
_FVF_POSITIONS = ("XYZ", "XYZRHW", "XYZB1", "XYZB2", "XYZB3", "XYZB4", "XYZB5", "XYZW")
_FVF_TEXCOUNTS = tuple(f"Tex{n}" for n in range(9))
D3DFVF = _table("D3DFVF", ["D3DFVF_"], [
    ("XYZ", 0x002), ("XYZRHW", 0x004), ("XYZB1", 0x006), ("XYZB2", 0x008), ("XYZB3", 0x00A),
    ("XYZB4", 0x00C), ("XYZB5", 0x00E), ("XYZW", 0x4002), ("Normal", 0x010), ("PSize", 0x020),
    ("Diffuse", 0x040), ("Specular", 0x080),
    *((f"Tex{n}", n << 8) for n in range(9)),
    ("LastBeta_UByte4", 0x1000), ("LastBeta_D3DColor", 0x8000),
], flags=True, exclusive=[("position formats", _FVF_POSITIONS),
                          ("texture-coordinate counts", _FVF_TEXCOUNTS)], example="XYZ")
D3DPATCHEDGESTYLE = _table("D3DPATCHEDGESTYLE", ["D3DPATCHEDGE_"],
                           [("Discrete", 0), ("Continuous", 1)])
# DX8 called these D3DORDERTYPE (D3DORDER_*) with the same values.
D3DDEGREETYPE = _table("D3DDEGREETYPE", ["D3DDEGREE_", "D3DORDER_"], [
    ("Linear", 1), ("Quadratic", 2), ("Cubic", 3), ("Quintic", 5)], example="Cubic")
# The effect docs spell the wrap flags U, V, W and COORD0-3 (D3DWRAP_*, D3DWRAPCOORD_*).
D3DWRAP = _table("D3DWRAP", ["D3DWRAP_", "D3D"], [
    ("U", 1), ("V", 2), ("W", 4), ("Coord0", 1), ("Coord1", 2), ("Coord2", 4), ("Coord3", 8),
], flags=True, aliases={f"WRAPCOORD_{n}": f"COORD{n}" for n in range(4)}, example="U")
D3DCLIPPLANE = _table("D3DCLIPPLANE", ["D3D"], [(f"ClipPlane{n}", 1 << n) for n in range(6)],
                      flags=True)
D3DDEBUGMONITORTOKENS = _table("D3DDEBUGMONITORTOKENS", ["D3DDMT_"],
                               [("Enable", 0), ("Disable", 1)])

ENUMS: Mapping[str, EnumTable] = MappingProxyType({t.name: t for t in (
    D3DTEXTUREOP, D3DTA, D3DBLEND, D3DBLENDOP, D3DCMPFUNC, D3DCULL, D3DFILLMODE, D3DSHADEMODE,
    D3DFOGMODE, D3DSTENCILOP, D3DTEXTUREADDRESS, D3DTEXTUREFILTERTYPE, D3DZBUFFERTYPE,
    D3DMATERIALCOLORSOURCE, D3DTEXTURETRANSFORMFLAGS, D3DTSS_TCI, D3DLIGHTTYPE,
    D3DVERTEXBLENDFLAGS, D3DCOLORWRITEENABLE, D3DFVF, D3DPATCHEDGESTYLE, D3DDEGREETYPE, D3DWRAP,
    D3DCLIPPLANE, D3DDEBUGMONITORTOKENS)})


def enum_value(table: EnumTable, *names: str | int) -> EnumValue:
    """An EnumValue built from names (any spelling) and numbers, e.g. (D3DTA, 'Texture', 'Complement')."""
    canonical: list[str] = []
    value = 0
    for item in names:
        if isinstance(item, int):
            canonical.append(str(item))
            value |= item
            continue
        found = table.lookup(item)
        if found is None:
            raise KeyError(f"{item!r} is not a {table.name} name")
        canonical.append(found[0])
        value |= found[1]
    return EnumValue(tuple(canonical), value)


# ---------------------------------------------------------------------------------------------
# State rows


@dataclass(frozen=True)
class CapsLimit:
    """The D3DCAPS9 bit field that limits a state's values (validation checks it).

    `bit` names the one bit the state needs when `needs(value)` says so (BlendOp needs BLENDOP
    for anything but ADD); without `bit`, an enum value needs the bit of its own name
    (ZFunc = LessEqual needs D3DPCMPCAPS_LESSEQUAL), or its entry in `renamed`. `gate` lists
    the bool states that must be on for the state to matter: a gated state is checked at the
    value in force, its default included (what the card must draw with); an ungated one only
    where a pass assigns it, so a card is never rejected for a default. `what` says what a
    value does, for the message (per value, or one text for all)."""

    field: str
    bit: str | None = None
    needs: Callable[[Any], bool] = bool
    renamed: Mapping[str, str] = field(default_factory=dict)
    gate: tuple[str, ...] = ()
    what: Mapping[str, str] | str = ""

    def bit_for(self, value: Any) -> str | None:
        """The bit `value` needs, or None when it needs none."""
        if self.bit is not None:
            return self.bit if self.needs(value) else None
        return self.renamed.get(value, value) if isinstance(value, str) else None

    def describe(self, value: Any) -> str:
        return self.what if isinstance(self.what, str) else self.what.get(value, "")


_BLEND = ("AlphaBlendEnable",)
_SEPARATE_BLEND = ("AlphaBlendEnable", "SeparateAlphaBlendEnable")
_STENCIL = ("StencilEnable",)
_TWO_SIDED = ("StencilEnable", "TwoSidedStencilMode")
# D3DBLEND_INVBLENDFACTOR shares D3DPBLENDCAPS_BLENDFACTOR.
_SRC_BLEND = CapsLimit("SrcBlendCaps", renamed={"INVBLENDFACTOR": "BLENDFACTOR"}, gate=_BLEND)
_DEST_BLEND = CapsLimit("DestBlendCaps", renamed={"INVBLENDFACTOR": "BLENDFACTOR"}, gate=_BLEND)
_BLEND_OP = CapsLimit("PrimitiveMiscCaps", "BLENDOP", lambda v: v != "ADD", gate=_BLEND)


def _alpha_blend(limit: CapsLimit) -> CapsLimit:
    # The *Alpha blend states matter only with SeparateAlphaBlendEnable.
    return CapsLimit(limit.field, limit.bit, limit.needs, limit.renamed, _SEPARATE_BLEND)


_STENCIL_OP = CapsLimit("StencilCaps", gate=_STENCIL)
_CCW_STENCIL_OP = CapsLimit("StencilCaps", gate=_TWO_SIDED)


@dataclass(frozen=True)
class StateInfo:
    """One effect state. `default` is the Direct3D 9 device default: a value, or a callable of
    the index (stage, sampler, light ...) where it differs per index; read it with
    `default_value`. Extra fields: `aliases` (other accepted names), `registers` (register
    count of VertexShaderConstant1-4 / PixelShaderConstant1-4), `legacy` (a DX8 state that
    Direct3D 9 no longer has; kept so old files load), `limit` (the caps field that limits its
    values, see CapsLimit)."""

    name: str
    kind: str
    type: str
    enum: EnumTable | None = None
    index: str = "none"
    max_index: int | None = None
    code: int | None = None
    default: object = None
    aliases: tuple[str, ...] = ()
    registers: int | None = None
    legacy: bool = False
    limit: CapsLimit | None = None
    # the state's number in an fx_2_0 effect binary (D3DX's state table, as Wine's
    # dlls/d3dx9_36/effect.c `state_table` lists it); None for a state the format cannot hold
    # (the DX8 render states Direct3D 9 dropped)
    fx2: int | None = None


def _identity() -> np.ndarray:
    return np.eye(4, dtype=np.float32).reshape(16)


def _vec(*xs: float) -> Callable[[int], np.ndarray]:
    return lambda _index: np.array(xs, dtype=np.float32)


def _ev(table: EnumTable, *names: str | int) -> EnumValue:
    return enum_value(table, *names)


def _rs(name: str, code: int, type_: str, default: object, enum: EnumTable | None = None,
        **extra: Any) -> StateInfo:
    return StateInfo(name, "render", type_, enum, "none", None, code, default, **extra)


_RENDER_STATES = (
    # ZEnable: TRUE when the device has an automatic depth buffer, which every render here has.
    _rs("ZEnable", 7, "enum", _ev(D3DZBUFFERTYPE, "True"), D3DZBUFFERTYPE, fx2=0),
    _rs("FillMode", 8, "enum", _ev(D3DFILLMODE, "Solid"), D3DFILLMODE, fx2=1),
    _rs("ShadeMode", 9, "enum", _ev(D3DSHADEMODE, "Gouraud"), D3DSHADEMODE, limit=CapsLimit(
        "ShadeCaps", "COLORPHONGRGB", lambda v: v == "PHONG", what="lights per pixel"), fx2=2),
    _rs("ZWriteEnable", 14, "bool", True, limit=CapsLimit(
        "PrimitiveMiscCaps", "MASKZ", lambda v: not v, what="turns depth writes off"), fx2=3),
    _rs("AlphaTestEnable", 15, "bool", False, fx2=4),
    _rs("LastPixel", 16, "bool", True, fx2=5),
    _rs("SrcBlend", 19, "enum", _ev(D3DBLEND, "One"), D3DBLEND, limit=_SRC_BLEND, fx2=6),
    _rs("DestBlend", 20, "enum", _ev(D3DBLEND, "Zero"), D3DBLEND, limit=_DEST_BLEND, fx2=7),
    _rs("CullMode", 22, "enum", _ev(D3DCULL, "CCW"), D3DCULL, limit=CapsLimit(
        "PrimitiveMiscCaps", renamed={"NONE": "CULLNONE", "CW": "CULLCW", "CCW": "CULLCCW"},
        what={"NONE": "draws both faces", "CW": "culls clockwise faces",
              "CCW": "culls counter-clockwise faces"}), fx2=8),
    _rs("ZFunc", 23, "enum", _ev(D3DCMPFUNC, "LessEqual"), D3DCMPFUNC,
        limit=CapsLimit("ZCmpCaps"), fx2=9),
    _rs("AlphaRef", 24, "int", 0, fx2=10),
    _rs("AlphaFunc", 25, "enum", _ev(D3DCMPFUNC, "Always"), D3DCMPFUNC,
        limit=CapsLimit("AlphaCmpCaps", gate=("AlphaTestEnable",)), fx2=11),
    _rs("DitherEnable", 26, "bool", False, fx2=12),
    _rs("AlphaBlendEnable", 27, "bool", False, fx2=13),
    _rs("FogEnable", 28, "bool", False, fx2=14),
    _rs("SpecularEnable", 29, "bool", False, fx2=15),
    _rs("FogColor", 34, "color", 0, fx2=16),
    _rs("FogTableMode", 35, "enum", _ev(D3DFOGMODE, "None"), D3DFOGMODE, limit=CapsLimit(
        "RasterCaps", "FOGTABLE", lambda v: v not in (None, "NONE"), gate=("FogEnable",),
        what="computes fog per pixel"), fx2=17),
    _rs("FogStart", 36, "float", 0.0, fx2=18),
    _rs("FogEnd", 37, "float", 1.0, fx2=19),
    _rs("FogDensity", 38, "float", 1.0, fx2=20),
    _rs("RangeFogEnable", 48, "bool", False, fx2=21),
    _rs("StencilEnable", 52, "bool", False, fx2=22),
    _rs("StencilFail", 53, "enum", _ev(D3DSTENCILOP, "Keep"), D3DSTENCILOP, limit=_STENCIL_OP, fx2=23),
    _rs("StencilZFail", 54, "enum", _ev(D3DSTENCILOP, "Keep"), D3DSTENCILOP, limit=_STENCIL_OP, fx2=24),
    _rs("StencilPass", 55, "enum", _ev(D3DSTENCILOP, "Keep"), D3DSTENCILOP, limit=_STENCIL_OP, fx2=25),
    _rs("StencilFunc", 56, "enum", _ev(D3DCMPFUNC, "Always"), D3DCMPFUNC, fx2=26),
    _rs("StencilRef", 57, "int", 0, fx2=27),
    _rs("StencilMask", 58, "dword", DWORD_MASK, fx2=28),
    _rs("StencilWriteMask", 59, "dword", DWORD_MASK, fx2=29),
    _rs("TextureFactor", 60, "color", DWORD_MASK, fx2=30),
    *(_rs(f"Wrap{n}", 128 + n, "enum", _ev(D3DWRAP, 0), D3DWRAP, fx2=31 + n) for n in range(8)),
    _rs("Clipping", 136, "bool", True, fx2=47),
    _rs("Lighting", 137, "bool", True, fx2=48),
    _rs("Ambient", 139, "color", 0, fx2=49),
    _rs("FogVertexMode", 140, "enum", _ev(D3DFOGMODE, "None"), D3DFOGMODE, fx2=50),
    _rs("ColorVertex", 141, "bool", True, fx2=51),
    _rs("LocalViewer", 142, "bool", True, fx2=52),
    _rs("NormalizeNormals", 143, "bool", False, fx2=53),
    _rs("DiffuseMaterialSource", 145, "enum", _ev(D3DMATERIALCOLORSOURCE, "Color1"),
        D3DMATERIALCOLORSOURCE, fx2=54),
    _rs("SpecularMaterialSource", 146, "enum", _ev(D3DMATERIALCOLORSOURCE, "Color2"),
        D3DMATERIALCOLORSOURCE, fx2=55),
    _rs("AmbientMaterialSource", 147, "enum", _ev(D3DMATERIALCOLORSOURCE, "Material"),
        D3DMATERIALCOLORSOURCE, fx2=56),
    _rs("EmissiveMaterialSource", 148, "enum", _ev(D3DMATERIALCOLORSOURCE, "Material"),
        D3DMATERIALCOLORSOURCE, fx2=57),
    _rs("VertexBlend", 151, "enum", _ev(D3DVERTEXBLENDFLAGS, "Disable"), D3DVERTEXBLENDFLAGS, fx2=58),
    _rs("ClipPlaneEnable", 152, "enum", _ev(D3DCLIPPLANE, 0), D3DCLIPPLANE, fx2=59),
    # PointSize: the docs say "the driver's value"; Wine and the DX7-style default use 1.0.
    _rs("PointSize", 154, "float", 1.0, fx2=60),
    _rs("PointSize_Min", 155, "float", 1.0, fx2=61),
    _rs("PointSpriteEnable", 156, "bool", False, fx2=63),
    _rs("PointScaleEnable", 157, "bool", False, fx2=64),
    _rs("PointScale_A", 158, "float", 1.0, fx2=65),
    _rs("PointScale_B", 159, "float", 0.0, fx2=66),
    _rs("PointScale_C", 160, "float", 0.0, fx2=67),
    _rs("MultiSampleAntialias", 161, "bool", True, fx2=68),
    _rs("MultiSampleMask", 162, "dword", DWORD_MASK, fx2=69),
    _rs("PatchEdgeStyle", 163, "enum", _ev(D3DPATCHEDGESTYLE, "Discrete"), D3DPATCHEDGESTYLE, fx2=70),
    _rs("DebugMonitorToken", 165, "enum", _ev(D3DDEBUGMONITORTOKENS, "Enable"),
        D3DDEBUGMONITORTOKENS, fx2=71),
    _rs("PointSize_Max", 166, "float", 64.0, fx2=62),
    _rs("IndexedVertexBlendEnable", 167, "bool", False, fx2=72),
    _rs("ColorWriteEnable", 168, "enum", _ev(D3DCOLORWRITEENABLE, "Red", "Green", "Blue", "Alpha"),
        D3DCOLORWRITEENABLE, fx2=73),
    _rs("TweenFactor", 170, "float", 0.0, fx2=74),
    _rs("BlendOp", 171, "enum", _ev(D3DBLENDOP, "Add"), D3DBLENDOP, limit=_BLEND_OP, fx2=75),
    # DX8 named these two D3DRS_POSITIONORDER / D3DRS_NORMALORDER.
    _rs("PositionDegree", 172, "enum", _ev(D3DDEGREETYPE, "Cubic"), D3DDEGREETYPE,
        aliases=("PositionOrder",), fx2=76),
    _rs("NormalDegree", 173, "enum", _ev(D3DDEGREETYPE, "Linear"), D3DDEGREETYPE,
        aliases=("NormalOrder",), fx2=77),
    _rs("ScissorTestEnable", 174, "bool", False, limit=CapsLimit(
        "RasterCaps", "SCISSORTEST", what="clips to a scissor rectangle"), fx2=78),
    _rs("SlopeScaleDepthBias", 175, "float", 0.0, limit=CapsLimit(
        "RasterCaps", "SLOPESCALEDEPTHBIAS", what="offsets depth by slope"), fx2=79),
    _rs("AntialiasedLineEnable", 176, "bool", False, fx2=80),
    _rs("MinTessellationLevel", 178, "float", 1.0, fx2=81),
    _rs("MaxTessellationLevel", 179, "float", 1.0, fx2=82),
    _rs("AdaptiveTess_X", 180, "float", 0.0, fx2=83),
    _rs("AdaptiveTess_Y", 181, "float", 0.0, fx2=84),
    _rs("AdaptiveTess_Z", 182, "float", 1.0, fx2=85),
    _rs("AdaptiveTess_W", 183, "float", 0.0, fx2=86),
    _rs("EnableAdaptiveTessellation", 184, "bool", False, fx2=87),
    _rs("TwoSidedStencilMode", 185, "bool", False,
        limit=CapsLimit("StencilCaps", "TWOSIDED", gate=_STENCIL), fx2=88),
    _rs("CCW_StencilFail", 186, "enum", _ev(D3DSTENCILOP, "Keep"), D3DSTENCILOP,
        limit=_CCW_STENCIL_OP, fx2=89),
    _rs("CCW_StencilZFail", 187, "enum", _ev(D3DSTENCILOP, "Keep"), D3DSTENCILOP,
        limit=_CCW_STENCIL_OP, fx2=90),
    _rs("CCW_StencilPass", 188, "enum", _ev(D3DSTENCILOP, "Keep"), D3DSTENCILOP,
        limit=_CCW_STENCIL_OP, fx2=91),
    _rs("CCW_StencilFunc", 189, "enum", _ev(D3DCMPFUNC, "Always"), D3DCMPFUNC, fx2=92),
    *(_rs(f"ColorWriteEnable{n}", 189 + n, "enum",
          _ev(D3DCOLORWRITEENABLE, "Red", "Green", "Blue", "Alpha"), D3DCOLORWRITEENABLE, fx2=92 + n)
      for n in (1, 2, 3)),
    _rs("BlendFactor", 193, "color", DWORD_MASK, fx2=96),
    _rs("SRGBWriteEnable", 194, "bool", False, fx2=97),
    _rs("DepthBias", 195, "float", 0.0,
        limit=CapsLimit("RasterCaps", "DEPTHBIAS", what="offsets depth"), fx2=98),
    *(_rs(f"Wrap{n}", 190 + n, "enum", _ev(D3DWRAP, 0), D3DWRAP, fx2=31 + n)
      for n in range(8, 16)),
    _rs("SeparateAlphaBlendEnable", 206, "bool", False,
        limit=CapsLimit("PrimitiveMiscCaps", "SEPARATEALPHABLEND", gate=_BLEND), fx2=99),
    _rs("SrcBlendAlpha", 207, "enum", _ev(D3DBLEND, "One"), D3DBLEND,
        limit=_alpha_blend(_SRC_BLEND), fx2=100),
    _rs("DestBlendAlpha", 208, "enum", _ev(D3DBLEND, "Zero"), D3DBLEND,
        limit=_alpha_blend(_DEST_BLEND), fx2=101),
    _rs("BlendOpAlpha", 209, "enum", _ev(D3DBLENDOP, "Add"), D3DBLENDOP,
        limit=_alpha_blend(_BLEND_OP), fx2=102),
    # DX8 render states with no D3D9 equivalent (codes from d3d8types.h): accepted, flagged.
    _rs("LinePattern", 10, "dword", 0, legacy=True),
    _rs("ZVisible", 30, "bool", False, legacy=True),
    _rs("EdgeAntialias", 40, "bool", False, legacy=True),
    _rs("ZBias", 47, "int", 0, legacy=True),
    _rs("SoftwareVertexProcessing", 153, "bool", False, legacy=True),
)


def _ts(name: str, code: int, type_: str, default: object, enum: EnumTable | None = None,
        fx2: int | None = None) -> StateInfo:
    return StateInfo(name, "stage", type_, enum, "optional", MAX_STAGES - 1, code, default,
                     fx2=fx2)


def _stage0_else(stage0: EnumValue, others: EnumValue) -> Callable[[int], EnumValue]:
    return lambda stage: stage0 if stage == 0 else others


_STAGE_STATES = (
    _ts("ColorOp", 1, "enum",
        _stage0_else(_ev(D3DTEXTUREOP, "Modulate"), _ev(D3DTEXTUREOP, "Disable")), D3DTEXTUREOP, fx2=103),
    _ts("ColorArg1", 2, "enum", _ev(D3DTA, "Texture"), D3DTA, fx2=105),
    _ts("ColorArg2", 3, "enum", _ev(D3DTA, "Current"), D3DTA, fx2=106),
    _ts("AlphaOp", 4, "enum",
        _stage0_else(_ev(D3DTEXTUREOP, "SelectArg1"), _ev(D3DTEXTUREOP, "Disable")), D3DTEXTUREOP, fx2=107),
    _ts("AlphaArg1", 5, "enum", _ev(D3DTA, "Texture"), D3DTA, fx2=109),
    _ts("AlphaArg2", 6, "enum", _ev(D3DTA, "Current"), D3DTA, fx2=110),
    _ts("BumpEnvMat00", 7, "float", 0.0, fx2=112),
    _ts("BumpEnvMat01", 8, "float", 0.0, fx2=113),
    _ts("BumpEnvMat10", 9, "float", 0.0, fx2=114),
    _ts("BumpEnvMat11", 10, "float", 0.0, fx2=115),
    # TexCoordIndex: coordinate set = stage number by default; D3DTSS_TCI_* may be OR-ed in.
    _ts("TexCoordIndex", 11, "enum", lambda stage: EnumValue((str(stage),), stage), D3DTSS_TCI, fx2=116),
    _ts("BumpEnvLScale", 22, "float", 0.0, fx2=117),
    _ts("BumpEnvLOffset", 23, "float", 0.0, fx2=118),
    _ts("TextureTransformFlags", 24, "enum", _ev(D3DTEXTURETRANSFORMFLAGS, "Disable"),
        D3DTEXTURETRANSFORMFLAGS, fx2=119),
    _ts("ColorArg0", 26, "enum", _ev(D3DTA, "Current"), D3DTA, fx2=104),
    _ts("AlphaArg0", 27, "enum", _ev(D3DTA, "Current"), D3DTA, fx2=108),
    _ts("ResultArg", 28, "enum", _ev(D3DTA, "Current"), D3DTA, fx2=111),
    # Constant: Wine leaves it 0 (docs/reference/semantics.md 1.1); the D3DTA page claims
    # 0xffffffff.
    _ts("Constant", 32, "color", 0, fx2=120),
)


def _ss(name: str, code: int, type_: str, default: object, enum: EnumTable | None = None,
        limit: CapsLimit | None = None, fx2: int | None = None) -> StateInfo:
    # In a pass `MinFilter[n]` (the DX8 texture-stage spelling); inside sampler_state no index.
    return StateInfo(name, "sampler", type_, enum, "optional", MAX_SAMPLERS - 1, code, default,
                     limit=limit, fx2=fx2)


def _filter_limit(prefix: str, filters: Iterable[str]) -> CapsLimit:
    # D3DPTFILTERCAPS_MINF* / MAGF* / MIPF*: a filter without such a bit no card reports. The
    # field is the 2D one; cube and volume textures read CubeTextureFilterCaps /
    # VolumeTextureFilterCaps where the card lists them (effects.validate.textures).
    return CapsLimit("TextureFilterCaps", renamed={f: f"{prefix}{f}" for f in filters})


_MINMAG_FILTERS = ("POINT", "LINEAR", "ANISOTROPIC", "PYRAMIDALQUAD", "GAUSSIANQUAD")
_ADDRESS = CapsLimit("TextureAddressCaps")


_SAMPLER_STATES = (
    _ss("AddressU", 1, "enum", _ev(D3DTEXTUREADDRESS, "Wrap"), D3DTEXTUREADDRESS, _ADDRESS, fx2=165),
    _ss("AddressV", 2, "enum", _ev(D3DTEXTUREADDRESS, "Wrap"), D3DTEXTUREADDRESS, _ADDRESS, fx2=166),
    _ss("AddressW", 3, "enum", _ev(D3DTEXTUREADDRESS, "Wrap"), D3DTEXTUREADDRESS, _ADDRESS, fx2=167),
    _ss("BorderColor", 4, "color", 0, fx2=168),
    _ss("MagFilter", 5, "enum", _ev(D3DTEXTUREFILTERTYPE, "Point"), D3DTEXTUREFILTERTYPE,
        _filter_limit("MAGF", _MINMAG_FILTERS), fx2=169),
    _ss("MinFilter", 6, "enum", _ev(D3DTEXTUREFILTERTYPE, "Point"), D3DTEXTUREFILTERTYPE,
        _filter_limit("MINF", _MINMAG_FILTERS), fx2=170),
    _ss("MipFilter", 7, "enum", _ev(D3DTEXTUREFILTERTYPE, "None"), D3DTEXTUREFILTERTYPE,
        _filter_limit("MIPF", ("POINT", "LINEAR")), fx2=171),
    _ss("MipMapLodBias", 8, "float", 0.0, fx2=172),
    _ss("MaxMipLevel", 9, "int", 0, fx2=173),
    _ss("MaxAnisotropy", 10, "int", 1, fx2=174),
    _ss("SRGBTexture", 11, "bool", False, fx2=175),
    _ss("ElementIndex", 12, "int", 0, fx2=176),
    # DMAPOffset: the docs say 0; the debug runtime reports 256 (docs/reference/effect_format.md 2).
    _ss("DMAPOffset", 13, "int", 0, fx2=177),
)

_OBJECT_STATES = (
    StateInfo("Texture", "texture", "texture", None, "optional", MAX_SAMPLERS - 1, None,
              NullValue(), fx2=164),
    StateInfo("Sampler", "sampler_object", "sampler", None, "optional", MAX_SAMPLERS - 1, None,
              NullValue(), fx2=178),
    StateInfo("VertexShader", "shader", "vertexshader", None, "none", None, None, NullValue(), fx2=146),
    StateInfo("PixelShader", "shader", "pixelshader", None, "none", None, None, NullValue(), fx2=147),
)

# D3DTRANSFORMSTATETYPE: VIEW 2, PROJECTION 3, TEXTURE0 16, WORLDMATRIX(n) 256 + n.
_TRANSFORM_STATES = (
    StateInfo("WorldTransform", "transform", "matrix", None, "optional", 255, 256,
              lambda _i: _identity(), fx2=125),
    StateInfo("ViewTransform", "transform", "matrix", None, "none", None, 2,
              lambda _i: _identity(), fx2=124),
    StateInfo("ProjectionTransform", "transform", "matrix", None, "none", None, 3,
              lambda _i: _identity(), fx2=123),
    StateInfo("TextureTransform", "transform", "matrix", None, "optional", MAX_STAGES - 1, 16,
              lambda _i: _identity(), fx2=126),
)

# The device starts with an all-zero material (Wine: zero-initialised state).
_MATERIAL_STATES = (
    StateInfo("MaterialDiffuse", "material", "float4", default=_vec(0, 0, 0, 0), fx2=127),
    StateInfo("MaterialAmbient", "material", "float4", default=_vec(0, 0, 0, 0), fx2=128),
    StateInfo("MaterialSpecular", "material", "float4", default=_vec(0, 0, 0, 0), fx2=129),
    StateInfo("MaterialEmissive", "material", "float4", default=_vec(0, 0, 0, 0), fx2=130),
    StateInfo("MaterialPower", "material", "float", default=0.0, fx2=131),
)


def _ls(name: str, type_: str, default: object, enum: EnumTable | None = None,
        fx2: int | None = None) -> StateInfo:
    return StateInfo(name, "light", type_, enum, "optional", None, None, default, fx2=fx2)


# Members an effect leaves out take the values of the light LightEnable creates
# (a white directional light shining down +z: D3D docs, Wine WINED3D_default_light).
_LIGHT_STATES = (
    _ls("LightType", "enum", _ev(D3DLIGHTTYPE, "Directional"), D3DLIGHTTYPE, fx2=132),
    _ls("LightDiffuse", "float4", _vec(1, 1, 1, 0), fx2=133),
    _ls("LightSpecular", "float4", _vec(0, 0, 0, 0), fx2=134),
    _ls("LightAmbient", "float4", _vec(0, 0, 0, 0), fx2=135),
    _ls("LightPosition", "float3", _vec(0, 0, 0), fx2=136),
    _ls("LightDirection", "float3", _vec(0, 0, 1), fx2=137),
    _ls("LightRange", "float", 0.0, fx2=138),
    _ls("LightFalloff", "float", 0.0, fx2=139),
    _ls("LightAttenuation0", "float", 0.0, fx2=140),
    _ls("LightAttenuation1", "float", 0.0, fx2=141),
    _ls("LightAttenuation2", "float", 0.0, fx2=142),
    _ls("LightTheta", "float", 0.0, fx2=143),
    _ls("LightPhi", "float", 0.0, fx2=144),
    _ls("LightEnable", "bool", False, fx2=145),
)


# The shader constant register files of Direct3D 9 (the index of a constant state is the first
# register it sets). Integer and boolean: 16 each, vertex and pixel (i0-i15, b0-b15 of vs_2_0+
# and ps_2_x+; Wine WINED3D_MAX_CONSTS_I/B). Float: the card's (MaxVertexShaderConst, or
# 8192 under software vertex processing; 8 for ps_1_x, 32 for ps_2_x, 224 for ps_3_0: "the
# runtime validates that the specified register range lies within the legal range",
# D3DHAL_DP2SETPIXELSHADERCONST / ...VERTEXSHADERCONST); the table bounds the index by the
# largest of them and validation by the card's (effects.validate.constants).
INT_BOOL_CONSTANT_REGISTERS = 16
FLOAT_CONSTANT_REGISTERS_MAX = {"Vertex": 8192, "Pixel": 224}


def _constant_states(stage: str, fx2: int) -> tuple[StateInfo, ...]:
    # The bare, F and 1-4 forms all set float registers (Wine); B and I set bool/int registers.
    # Shader constants have no defined initial value: default None.
    floats = FLOAT_CONSTANT_REGISTERS_MAX[stage]
    # `fx2`: the first one's number in the fx_2_0 state table, the others following in order
    rows = [StateInfo(f"{stage}ShaderConstant{suffix}", "shader_const", "constants",
                      index="required", max_index=file - 1, registers=registers, fx2=fx2 + k)
            for k, (suffix, registers, file) in enumerate((
                ("F", None, floats), ("B", None, INT_BOOL_CONSTANT_REGISTERS),
                ("I", None, INT_BOOL_CONSTANT_REGISTERS), ("", None, floats), ("1", 1, floats),
                ("2", 2, floats), ("3", 3, floats), ("4", 4, floats)))]
    return tuple(rows)


def constant_register_count(info: StateInfo, numbers: int) -> int:
    """How many registers a constant state's value of `numbers` numbers sets: one BOOL a
    b# register, four a c# or i# register (the last one padded); the 1-4 forms too, whose
    digit only bounds the numbers (D3DX sets what the value holds: d3dx_constant_registers)."""
    if info.name.endswith("B"):
        return numbers
    return -(-numbers // 4)


_MISC_STATES = (
    # NPatchMode = SetNPatchMode(nSegments); below 1.0 N-patches are off. The D3D9 effect docs
    # list the same state as PatchSegments (the DX8 render-state name).
    StateInfo("NPatchMode", "misc", "float", default=0.0, aliases=("PatchSegments",), fx2=121),
    StateInfo("FVF", "misc", "enum", D3DFVF, default=EnumValue(("0",), 0), fx2=122),
)

STATES: tuple[StateInfo, ...] = (
    _RENDER_STATES + _STAGE_STATES + _SAMPLER_STATES + _OBJECT_STATES + _TRANSFORM_STATES
    + _MATERIAL_STATES + _LIGHT_STATES + _constant_states("Vertex", 148) + _constant_states("Pixel", 156)
    + _MISC_STATES)


def _key(name: str) -> str:
    # State names match case-insensitively and ignore underscores (PointSize_Min = PointSizeMin).
    return name.strip().lower().replace("_", "")


_BY_KEY: dict[str, StateInfo] = {}
# the fx_2_0 column read back: state number -> row
BY_FX2: dict[int, StateInfo] = {_row.fx2: _row for _row in STATES if _row.fx2 is not None}
assert sorted(BY_FX2) == list(range(0xB3)), "the fx2 column: 0..0xb2, each once"
for _row in STATES:
    for _spelling in (_row.name, *_row.aliases):
        assert _key(_spelling) not in _BY_KEY, f"duplicate state name {_spelling}"
        _BY_KEY[_key(_spelling)] = _row


# CgFX's (OpenGL's) sampler-state spellings, which engines that compiled one shader source
# with cgc for both APIs left in their .fx files (Wild Magic 5's `sampler_state { MinFilter =
# Nearest; WrapS = Clamp; }`). D3DX's effect compiler rejects them; the builder reads them as
# the Direct3D state or value named here, with a located warning (an error when strict).
# Names from the CgFX state list and glTexParameter's GL_TEXTURE_WRAP_S/T/R and filter enums.
CGFX_SAMPLER_STATES = {"wraps": "AddressU", "wrapt": "AddressV", "wrapr": "AddressW"}
CGFX_SAMPLER_VALUES = {
    "D3DTEXTUREFILTERTYPE": {"nearest": "Point", "nearestmipmapnearest": "Point",
                             "nearestmipmaplinear": "Point", "linearmipmapnearest": "Linear",
                             "linearmipmaplinear": "Linear"},
    "D3DTEXTUREADDRESS": {"repeat": "Wrap", "clamptoedge": "Clamp", "clamptoborder": "Border",
                          "mirroredrepeat": "Mirror"},
}


def lookup_state(name: str) -> StateInfo | None:
    """The row for a state name (any case, with or without underscores, DX8 aliases), or None."""
    return _BY_KEY.get(_key(name))


def suggest_state(name: str) -> str | None:
    """The canonical name of the known state closest to `name`, for "did you mean ...?"."""
    known = lookup_state(name)
    if known is not None:
        return known.name
    key = _key(name)
    best: tuple[float, StateInfo] | None = None
    for spelling, row in _BY_KEY.items():
        score = difflib.SequenceMatcher(None, key, spelling).ratio()
        if score >= 0.6 and (best is None or score > best[0]):  # ties: first in table order
            best = (score, row)
    return best[1].name if best else None


def default_value(info: StateInfo, index: int | None = None) -> object:
    """The Direct3D 9 device default of a state at a stage / sampler / light (None → 0).
    Arrays are fresh copies; shader constants have no default (None)."""
    default = info.default
    if callable(default):
        return default(0 if index is None else index)
    if isinstance(default, np.ndarray):
        return default.copy()
    return default


def check_index(info: StateInfo, index: int | None, location: Location) -> None:
    """Raise StateError when `[index]` does not fit the state (none allowed, missing, range)."""
    if index is None:
        if info.index == "required":
            raise StateError(f"{info.name} needs an index such as {info.name}[0]", location)
        return
    if info.index == "none":
        raise StateError(f"{info.name} takes no index; remove [{index}]", location)
    if index < 0:
        raise StateError(f"{info.name}[{index}]: the index cannot be negative", location)
    if info.max_index is not None and index > info.max_index:
        if info.kind in ("sampler", "texture", "sampler_object") and index in VERTEX_SAMPLER_INDICES:
            return
        raise StateError(f"{info.name}[{index}]: the index must be 0 to {info.max_index}",
                         location)


# ---------------------------------------------------------------------------------------------
# Coercion of parsed values


_DESCRIPTIONS = {
    "bool": "a bool (TRUE or FALSE)",
    "int": "an integer",
    "dword": "a DWORD (an integer such as 0xFFFFFFFF)",
    "color": "a colour (a D3DCOLOR such as 0xFF808080, or a float4)",
    "float": "a float",
    "float3": "a float3 (3 numbers)",
    "float4": "a float4 (4 numbers)",
    "matrix": "a 4x4 matrix (16 numbers)",
    "texture": "a texture parameter or NULL",
    "sampler": "a sampler_state block, a sampler parameter or NULL",
    "vertexshader": "a vertex shader (an asm block, a compile target, a parameter or NULL)",
    "pixelshader": "a pixel shader (an asm block, a compile target, a parameter or NULL)",
}


def describe_type(info: StateInfo) -> str:
    """What a state's value must be, in words, for messages."""
    if info.type == "enum" and info.enum is not None:
        return f"a {info.enum.name} value such as {info.enum.example}"
    if info.type == "constants":
        if info.name.endswith("B"):
            return "bool shader constants (TRUE/FALSE values)"
        if info.name.endswith("I"):
            return "int shader constants (4 integers per register)"
        if info.registers:
            return f"{info.registers} float4 register(s) ({4 * info.registers} numbers)"
        return "float shader constants (4 numbers per register)"
    return _DESCRIPTIONS[info.type]


def _fail(info: StateInfo, detail: str, location: Location) -> StateError:
    return StateError(f"{info.name} expects {describe_type(info)}; {detail}", location)


def _shown(raw: Any) -> str:
    """How a parsed value looked in the source, roughly, for messages."""
    if isinstance(raw, bool):
        return "TRUE" if raw else "FALSE"
    if isinstance(raw, list):
        return " | ".join(str(item) for item in raw)
    if isinstance(raw, tuple):
        return "{" + ", ".join(_shown(x) for x in raw) + "}"
    if isinstance(raw, str):
        return f'"{raw}"'
    if isinstance(raw, (int, float)):
        return repr(raw)
    return type(raw).__name__


def _is_number(x: Any) -> bool:
    return isinstance(x, (int, float, np.integer, np.floating)) and not isinstance(x, (bool, np.bool_))


def _integral(x: Any) -> int | None:
    """`x` as an int when it is an integer or an integral float, else None."""
    if isinstance(x, (bool, np.bool_)):
        return None
    if isinstance(x, (int, np.integer)):
        return int(x)
    if isinstance(x, (float, np.floating)) and float(x).is_integer():
        return int(x)
    return None


def _single_name(raw: Any) -> str | None:
    if isinstance(raw, list) and len(raw) == 1 and isinstance(raw[0], str):
        return raw[0]
    return None


def _unwrap_scalar(raw: Any) -> Any:
    """A one-element `{x}` / `(x)` or a one-number `|` list is just x."""
    if isinstance(raw, tuple) and len(raw) == 1:
        return raw[0]
    if isinstance(raw, list) and len(raw) == 1 and not isinstance(raw[0], str):
        return raw[0]
    return raw


def _flatten(raw: Any) -> list[Any] | None:
    if isinstance(raw, np.ndarray):
        return list(raw.reshape(-1))
    if not isinstance(raw, tuple):
        return None
    out: list[Any] = []
    for x in raw:
        if isinstance(x, (tuple, np.ndarray)):
            inner = _flatten(x)
            if inner is None:
                return None
            out.extend(inner)
        else:
            out.append(x)
    return out


def _param_ref(name: str | None, parameters: Container[str], location: Location) -> ParamRef | None:
    if name is not None and name in parameters:
        return ParamRef(name, location=location)
    return None


def _flags_expression(info: StateInfo, raw: list, parameters: Container[str],
                      location: Location) -> Expression | None:
    """`ColorWriteEnable = Mask | BLUE`: flags OR-ed with a parameter are an effect-level
    expression (evaluated on the host when the pass is lowered, see effects/lower/preshaders),
    the flag names written as their numbers. None when no parameter is named."""
    table = info.enum
    assert table is not None
    if not any(isinstance(item, str) and table.lookup(item) is None and item in parameters
               for item in raw):
        return None
    terms = []
    for item in raw:
        if isinstance(item, str):
            found = table.lookup(item)
            if found is not None:
                terms.append(str(found[1]))
            elif item in parameters:
                terms.append(item)
            else:
                hint = table.suggest(item)
                raise _fail(info, f"'{item}' is not one" + (f" (did you mean {hint}?)" if hint
                                                            else ""), location)
        else:
            number = _integral(item)
            if number is None or not 0 <= number <= DWORD_MASK:
                raise _fail(info, f"{_shown(item)} is not one", location)
            terms.append(str(number))
    return Expression(" | ".join(terms), location)


def _coerce_enum(info: StateInfo, raw: Any, location: Location, parameters: Container[str]) -> Any:
    table = info.enum
    assert table is not None
    raw = _unwrap_scalar(raw)
    if isinstance(raw, (bool, np.bool_)):  # TRUE/FALSE literals: only tables that name them
        raw = ["TRUE" if raw else "FALSE"]
    if _is_number(raw):
        raw = [raw]
    if not isinstance(raw, list) or not raw:
        raise _fail(info, f"got {_shown(raw)}", location)
    name = _single_name(raw)
    if name is not None and table.lookup(name) is None:
        ref = _param_ref(name, parameters, location)
        if ref is not None:
            return ref
    if table.flags and len(raw) > 1:
        expression = _flags_expression(info, raw, parameters, location)
        if expression is not None:
            return expression
    if len(raw) > 1 and not table.flags:
        raise StateError(f"{info.name} takes a single {table.name} value; "
                         f"'{_shown(raw)}' combines {len(raw)}", location)
    names: list[str] = []
    value = 0
    for item in raw:
        if isinstance(item, str):
            found = table.lookup(item)
            if found is None:
                hint = table.suggest(item)
                detail = f"'{item}' is not one" + (f" (did you mean {hint}?)" if hint else "")
                raise _fail(info, detail, location)
            names.append(found[0])
            value |= found[1]
            continue
        number = _integral(item)
        if number is None or not 0 <= number <= DWORD_MASK:
            raise _fail(info, f"{_shown(item)} is not one", location)
        names.append(str(number))
        value |= number
    for what, group in table.exclusive:
        used = [n for n in names if n in group]
        if len(used) > 1:
            spelled = ", ".join(table.spelling(n) for n in used)
            raise StateError(f"{info.name}: '{_shown(raw)}' combines {len(used)} {table.name} "
                             f"{what} ({spelled}); only one may be used", location)
    return EnumValue(tuple(names), value, location)


_TRUE_FALSE = {"TRUE": True, "FALSE": False}


def _coerce_bool(info: StateInfo, raw: Any, location: Location, parameters: Container[str]) -> Any:
    raw = _unwrap_scalar(raw)
    if isinstance(raw, (bool, np.bool_)):
        return bool(raw)
    name = _single_name(raw)
    if name is not None:
        if name.upper() in _TRUE_FALSE:
            return _TRUE_FALSE[name.upper()]
        ref = _param_ref(name, parameters, location)
        if ref is not None:
            return ref
        raise _fail(info, f"'{name}' is neither TRUE/FALSE nor a parameter", location)
    number = _integral(raw) if _is_number(raw) else None
    if number in (0, 1):
        return bool(number)
    raise _fail(info, f"got {_shown(raw)}", location)


def _named_parameter(info: StateInfo, raw: Any, location: Location,
                     parameters: Container[str]) -> Any:
    """The parameter a single name refers to (None: `raw` is not one name); a name that is no
    parameter is the state's error, as it is not a number either."""
    name = _single_name(raw)
    if name is None:
        return None
    ref = _param_ref(name, parameters, location)
    if ref is None:
        raise _fail(info, f"'{name}' is neither a number nor a parameter", location)
    return ref


def _coerce_integer(info: StateInfo, raw: Any, location: Location, parameters: Container[str]) -> Any:
    raw = _unwrap_scalar(raw)
    ref = _named_parameter(info, raw, location, parameters)
    if ref is not None:
        return ref
    if isinstance(raw, list) and all(_integral(x) is not None for x in raw):  # `a | b`
        combined = 0
        for x in raw:
            combined |= _integral(x) & DWORD_MASK
        raw = combined
    if isinstance(raw, (bool, np.bool_)):
        raw = int(raw)  # the effect compiler casts TRUE/FALSE to 1/0
    number = _integral(raw) if _is_number(raw) else None
    if number is None:
        raise _fail(info, f"got {_shown(raw)}", location)
    if not -(1 << 31) <= number <= DWORD_MASK:
        raise _fail(info, f"{number} does not fit in 32 bits", location)
    if info.type == "int":
        if number < 0:
            raise _fail(info, f"{number} is negative", location)
        return number
    return number & DWORD_MASK


def pack_color(rgba: Iterable[float]) -> int:
    """Pack r, g, b, a floats into D3DCOLOR 0xAARRGGBB as D3DXCOLOR's DWORD cast does:
    each channel saturated to [0, 1], then (DWORD)(x * 255 + 0.5) in float32."""
    channels = []
    for x in rgba:
        x = float(x)
        if not x > 0:          # saturated before the float32 cast: 1e39 has no float32; NaN is 0
            channels.append(0)
        elif x >= 1:
            channels.append(0xFF)
        else:
            channels.append(int(np.float32(x) * np.float32(255.0) + np.float32(0.5)))
    r, g, b, a = channels
    return (a << 24) | (r << 16) | (g << 8) | b


def unpack_color(value: int) -> tuple[float, float, float, float]:
    """D3DCOLOR 0xAARRGGBB as (r, g, b, a) floats in [0, 1] (the inverse of `pack_color`'s
    rounding for every 8-bit value)."""
    v = int(value) & DWORD_MASK
    return ((v >> 16 & 0xFF) / 255, (v >> 8 & 0xFF) / 255, (v & 0xFF) / 255, (v >> 24) / 255)


def _coerce_color(info: StateInfo, raw: Any, location: Location, parameters: Container[str]) -> Any:
    values = _flatten(raw)
    if values is not None and len(values) > 1:
        if len(values) != 4 or not all(_is_number(v) for v in values):
            raise _fail(info, f"got {_shown(raw)} ({len(values)} values)", location)
        return pack_color(float(v) for v in values)
    return _coerce_integer(info, raw, location, parameters)


def _coerce_float(info: StateInfo, raw: Any, location: Location, parameters: Container[str]) -> Any:
    raw = _unwrap_scalar(raw)
    ref = _named_parameter(info, raw, location, parameters)
    if ref is not None:
        return ref
    if not _is_number(raw):
        raise _fail(info, f"got {_shown(raw)}", location)
    return float(raw)


def _numbers(info: StateInfo, raw: Any, location: Location, dtype: Any = np.float32) -> np.ndarray:
    values = _flatten(raw)
    if values is None and _is_number(raw):
        values = [raw]
    if values is None or not values or not all(_is_number(v) for v in values):
        raise _fail(info, f"got {_shown(raw)}", location)
    numbers = [float(v) for v in values]
    if dtype == np.float32 and any(math.isfinite(v) and abs(v) > _FLT_MAX for v in numbers):
        # D3DX keeps a state's numbers as float32: 1e39 has no float32 (it would be inf)
        raise _fail(info, f"got {_shown(raw)}: a value past the largest float32 (3.4e38)",
                    location)
    return np.array(numbers, dtype=dtype)


_FLT_MAX = 3.4028234663852886e38 * (1 + 2.0 ** -25)   # what still rounds to a finite float32


def _coerce_vector(info: StateInfo, raw: Any, location: Location, parameters: Container[str]) -> Any:
    ref = _param_ref(_single_name(raw), parameters, location)
    if ref is not None:
        return ref
    array = _numbers(info, raw, location)
    wanted = {"float3": (3, 4), "float4": (4,), "matrix": (16,)}[info.type]
    if array.size not in wanted:
        raise _fail(info, f"got {array.size} value(s)", location)
    # A float4 given for a float3 (LightPosition = float4(...)) drops w, as HLSL truncation does.
    return array[:wanted[0]]


def _coerce_constants(info: StateInfo, raw: Any, location: Location, parameters: Container[str]) -> Any:
    ref = _param_ref(_single_name(raw), parameters, location)
    if ref is not None:
        return ref
    if info.name.endswith("B"):  # one BOOL per register
        items = _flatten(raw) if isinstance(raw, tuple) else [_unwrap_scalar(raw)]
        bools = []
        for item in items or []:
            if isinstance(item, (bool, np.bool_)) or _integral(item) in (0, 1):
                bools.append(bool(item))
            elif isinstance(item, list) and _single_name(item) and item[0].upper() in _TRUE_FALSE:
                bools.append(_TRUE_FALSE[item[0].upper()])
            else:
                raise _fail(info, f"got {_shown(raw)}", location)
        if not bools:
            raise _fail(info, f"got {_shown(raw)}", location)
        return np.array(bools, dtype=bool)
    if info.name.endswith("I"):
        array = _numbers(info, raw, location, np.float64)
        if not np.all(np.mod(array, 1) == 0):
            raise _fail(info, f"got non-integer values {_shown(raw)}", location)
        array = array.astype(np.int32)
    else:
        array = _numbers(info, raw, location)
    if info.registers is not None and array.size > 4 * info.registers:
        raise _fail(info, f"got {array.size} value(s), more than those registers hold", location)
    return d3dx_constant_registers(array)


def d3dx_constant_registers(array: np.ndarray) -> np.ndarray:
    """A float or int shader-constant state's value as the registers D3DX sets from it (fxc
    stores the value as written; Wine's d3dx9 test_effect_states records what native D3DX
    did): one register per four numbers, a last partial one counting; a value that is a whole
    number of registers sets them all; one that is not sets its first register from its first
    four numbers and the others to zero (`{4,4,4,4, 5,5,5,5, 6}` at c4: c4 = 4s, c5 = c6 = 0).
    The lanes a scalar leaves (`VertexShaderConstant1[1] = 3.0f`: c1.x = 3) held whatever
    was on the stack; here zero."""
    if array.size % 4 == 0:
        return array
    out = np.zeros(-(-array.size // 4) * 4, dtype=array.dtype)
    first = min(4, array.size)
    out[:first] = array[:first]
    return out


def _coerce_object(info: StateInfo, raw: Any, location: Location, parameters: Container[str]) -> Any:
    if isinstance(raw, NullValue):
        return raw
    name = _single_name(raw)
    if name is not None:
        if name.upper() == "NULL":
            return NullValue(location)
        ref = _param_ref(name, parameters, location)
        if ref is not None:
            return ref
        raise _fail(info, f"'{name}' is not a parameter", location)
    if info.type == "sampler" and isinstance(raw, SamplerState):
        return raw
    if info.type in ("vertexshader", "pixelshader"):
        wanted = "vertex" if info.type == "vertexshader" else "pixel"
        if isinstance(raw, ShaderBlock):
            if raw.stage != wanted:
                raise _fail(info, f"the asm block is a {raw.stage} shader", location)
            return raw
        if isinstance(raw, CompileShader):
            prefix = raw.profile.lower()[:2]
            if prefix in ("vs", "ps") and prefix != wanted[0] + "s":
                raise _fail(info, f"'compile {raw.profile}' targets a "
                                  f"{'vertex' if prefix == 'vs' else 'pixel'} shader", location)
            return raw
    raise _fail(info, f"got {_shown(raw)}", location)


_COERCERS: dict[str, Callable[[StateInfo, Any, Location, Container[str]], Any]] = {
    "enum": _coerce_enum, "bool": _coerce_bool, "int": _coerce_integer,
    "dword": _coerce_integer, "color": _coerce_color, "float": _coerce_float,
    "float3": _coerce_vector, "float4": _coerce_vector, "matrix": _coerce_vector,
    "constants": _coerce_constants, "texture": _coerce_object, "sampler": _coerce_object,
    "vertexshader": _coerce_object, "pixelshader": _coerce_object,
}


def coerce_state_value(info: StateInfo, raw: Any, location: Location,
                       parameters: Container[str] = ()) -> object:
    """Turn what the parser read into the typed value the model stores, or raise StateError.

    Results: enum → EnumValue (canonical names in source order, numbers as decimal strings,
    OR-ed value); bool → bool; int/dword/color → int (color also packs a 4-vector);
    float → float; float3/float4/matrix/constants → numpy array (float32; B constants bool,
    I constants int32); texture/sampler/shader states → the model object. ParamRef and
    Expression pass through for every state; a single identifier that is not a name of the
    state's enum but is in `parameters` becomes ParamRef(name).
    """
    if isinstance(raw, (ParamRef, Expression)):
        return raw
    if isinstance(raw, str):
        raise _fail(info, f"got the string {_shown(raw)}", location)
    if isinstance(raw, (NullValue, SamplerState, ShaderBlock, CompileShader)) and \
            info.type not in ("texture", "sampler", "vertexshader", "pixelshader"):
        what = "NULL" if isinstance(raw, NullValue) else type(raw).__name__
        raise _fail(info, f"got {what}", location)
    return _COERCERS[info.type](info, raw, location, parameters)
