"""Caps profiles: simulated cards described by D3DCAPS9 fields in YAML.

A profile (`caps_profiles/<name>.yaml`) names one card. Its keys are `name`, `description`,
`display_name`, `generation` (dx6, dx7, dx8, dx8.1, dx9, dx9c), an optional `inherit` (a
bundled name, or a path relative to the file), `VendorId`, `DeviceId`, then D3DCAPS9 fields by
their exact names. Cap-bit fields are lists of bit names without their prefix
(`TextureOpCaps: [MODULATE, BUMPENVMAP]` means D3DTEXOPCAPS_MODULATE | D3DTEXOPCAPS_BUMPENVMAP).
Comments carry each value's provenance (`# source: ...` or `# inferred: ...`); the loader
ignores them.

Fields that are not in D3DCAPS9 (documented where `FIELDS` lists them):
  VertexProcessing             which of hardware / mixed / software CreateDevice accepts.
  SoftwareVertexShaderVersion  the vertex shader version the runtime runs on the CPU
                               (default "3.0" when software processing is available).
  PS20Caps.DependentReadDepth  levels of dependent texture reads ps_2_x allows (ps_2_0: 4;
                               NODEPENDENTREADLIMIT lifts it).
  TextureFormats               D3DFORMAT name -> usages CheckDeviceFormat accepts:
                               texture, cube, volume, rendertarget, depthstencil, filter,
                               blend (post-pixel-shader blending), vertextexture.
  Precision                    what lowering needs per shader model: `fixed_function`,
                               `ps_1_x` (1.0-1.3), `ps_1_4`, `ps_2_0`, `ps_3_0`; each is
                               fp16 | fp24 | fp32 or {format: fixed, bits: N, range: R,
                               signed: bool} (N fraction bits, values held in [-R, R], or
                               [0, R] when unsigned).
  Quirks                       rules the driver enforced beyond its caps bits (below).
  MaxPixelShaderValue          D3DCAPS8's name for D3DCAPS9.PixelShader1xMaxValue; both
                               spellings are accepted and stored under this one.

Quirk vocabulary. Each quirk is `{id, rule, text, source, severity?, ...params}`; severity
`error` (default) means ValidateDevice failed on the card, `warning` means the driver accepted
it but it misbehaved (the validator reports it, nothing is rejected).
  arg_not_texture   op, arg (0-2), channel (color|alpha|both, default both): a stage whose
                    `op` takes D3DTA_TEXTURE as argument `arg` fails.
  textures_need_op  max_textures, ops: a pass that binds more than `max_textures` textures
                    fails unless one of its stages uses one of `ops`.
  op_stages         op, stages: `op` is accepted only at the listed stage indices.
  max_textures      count: at most `count` textures bound in one pass.
  cap_unreliable    field, bit: the bit is reported but does not work.
  format_unreliable format, usage (optional): the format (for that usage) is reported but
                    unusable or broken.
  note              no params: behaviour worth knowing (rendering, precision); not a rule.
  remove            only in an inheriting profile: drops the parent's quirk with this id.

Errors in a profile are `ProfileError`s located at the offending key or value.
"""
from __future__ import annotations

import difflib
import os
import stat
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from types import MappingProxyType
from typing import Any, Callable, Mapping

import yaml

from effects.base import limits, untrusted, yaml_input
from effects.base.bundled import PROFILE_FOLDER, names_a_profile_file
from effects.base.errors import Location, ProfileError
from effects.program.formats import D3DFORMAT

PROFILE_DIR = Path(PROFILE_FOLDER).resolve()

GENERATIONS = ("dx6", "dx7", "dx8", "dx8.1", "dx9", "dx9c")


def _bit_table(text: str) -> Mapping[str, int]:
    """'NAME=0x1 OTHER=0x2' -> {NAME: 1, OTHER: 2}."""
    pairs = (item.split("=") for item in text.split())
    return MappingProxyType({name: int(value, 16) for name, value in pairs})


# Bit names and values of d3d9caps.h (DirectX 9 SDK; the same values are in Wine's copy,
# include/d3d9caps.h). Names are stored without the prefix in the second column.
DEVCAPS = _bit_table("""
    EXECUTESYSTEMMEMORY=0x10 EXECUTEVIDEOMEMORY=0x20 TLVERTEXSYSTEMMEMORY=0x40
    TLVERTEXVIDEOMEMORY=0x80 TEXTURESYSTEMMEMORY=0x100 TEXTUREVIDEOMEMORY=0x200
    DRAWPRIMTLVERTEX=0x400 CANRENDERAFTERFLIP=0x800 TEXTURENONLOCALVIDMEM=0x1000
    DRAWPRIMITIVES2=0x2000 SEPARATETEXTUREMEMORIES=0x4000 DRAWPRIMITIVES2EX=0x8000
    HWTRANSFORMANDLIGHT=0x10000 CANBLTSYSTONONLOCAL=0x20000 HWRASTERIZATION=0x80000
    PUREDEVICE=0x100000 QUINTICRTPATCHES=0x200000 RTPATCHES=0x400000
    RTPATCHHANDLEZERO=0x800000 NPATCHES=0x1000000""")
PMISCCAPS = _bit_table("""
    MASKZ=0x2 LINEPATTERNREP=0x4 CULLNONE=0x10 CULLCW=0x20 CULLCCW=0x40
    COLORWRITEENABLE=0x80 CLIPPLANESCALEDPOINTS=0x100 CLIPTLVERTS=0x200 TSSARGTEMP=0x400
    BLENDOP=0x800 NULLREFERENCE=0x1000 INDEPENDENTWRITEMASKS=0x4000
    PERSTAGECONSTANT=0x8000 FOGANDSPECULARALPHA=0x10000 SEPARATEALPHABLEND=0x20000
    MRTINDEPENDENTBITDEPTHS=0x40000 MRTPOSTPIXELSHADERBLENDING=0x80000
    FOGVERTEXCLAMPED=0x100000""")
RASTERCAPS = _bit_table("""
    DITHER=0x1 PAT=0x8 ZTEST=0x10 FOGVERTEX=0x80 FOGTABLE=0x100 ANTIALIASEDGES=0x1000
    MIPMAPLODBIAS=0x2000 ZBIAS=0x4000 ZBUFFERLESSHSR=0x8000 FOGRANGE=0x10000
    ANISOTROPY=0x20000 WBUFFER=0x40000 WFOG=0x100000 ZFOG=0x200000
    COLORPERSPECTIVE=0x400000 SCISSORTEST=0x1000000 SLOPESCALEDEPTHBIAS=0x2000000
    DEPTHBIAS=0x4000000 MULTISAMPLE_TOGGLE=0x8000000""")
CMPCAPS = _bit_table("""
    NEVER=0x1 LESS=0x2 EQUAL=0x4 LESSEQUAL=0x8 GREATER=0x10 NOTEQUAL=0x20
    GREATEREQUAL=0x40 ALWAYS=0x80""")
BLENDCAPS = _bit_table("""
    ZERO=0x1 ONE=0x2 SRCCOLOR=0x4 INVSRCCOLOR=0x8 SRCALPHA=0x10 INVSRCALPHA=0x20
    DESTALPHA=0x40 INVDESTALPHA=0x80 DESTCOLOR=0x100 INVDESTCOLOR=0x200 SRCALPHASAT=0x400
    BOTHSRCALPHA=0x800 BOTHINVSRCALPHA=0x1000 BLENDFACTOR=0x2000""")
# COLORPHONGRGB / SPECULARPHONGRGB: DirectX 7's d3dcaps.h (D3DPSHADECAPS_*, dropped from
# d3d9caps.h with D3DSHADE_PHONG still in d3d9types.h); no shipped driver set them.
SHADECAPS = _bit_table("""
    COLORGOURAUDRGB=0x8 COLORPHONGRGB=0x20 SPECULARGOURAUDRGB=0x200 SPECULARPHONGRGB=0x800
    ALPHAGOURAUDBLEND=0x4000 FOGGOURAUD=0x80000""")
TEXTURECAPS = _bit_table("""
    PERSPECTIVE=0x1 POW2=0x2 ALPHA=0x4 SQUAREONLY=0x20 TEXREPEATNOTSCALEDBYSIZE=0x40
    ALPHAPALETTE=0x80 NONPOW2CONDITIONAL=0x100 PROJECTED=0x400 CUBEMAP=0x800
    VOLUMEMAP=0x2000 MIPMAP=0x4000 MIPVOLUMEMAP=0x8000 MIPCUBEMAP=0x10000
    CUBEMAP_POW2=0x20000 VOLUMEMAP_POW2=0x40000 NOPROJECTEDBUMPENV=0x200000""")
FILTERCAPS = _bit_table("""
    MINFPOINT=0x100 MINFLINEAR=0x200 MINFANISOTROPIC=0x400 MINFPYRAMIDALQUAD=0x800
    MINFGAUSSIANQUAD=0x1000 MIPFPOINT=0x10000 MIPFLINEAR=0x20000 MAGFPOINT=0x1000000
    MAGFLINEAR=0x2000000 MAGFANISOTROPIC=0x4000000 MAGFPYRAMIDALQUAD=0x8000000
    MAGFGAUSSIANQUAD=0x10000000""")
ADDRESSCAPS = _bit_table("""
    WRAP=0x1 MIRROR=0x2 CLAMP=0x4 BORDER=0x8 INDEPENDENTUV=0x10 MIRRORONCE=0x20""")
STENCILCAPS = _bit_table("""
    KEEP=0x1 ZERO=0x2 REPLACE=0x4 INCRSAT=0x8 DECRSAT=0x10 INVERT=0x20 INCR=0x40
    DECR=0x80 TWOSIDED=0x100""")
TEXOPCAPS = _bit_table("""
    DISABLE=0x1 SELECTARG1=0x2 SELECTARG2=0x4 MODULATE=0x8 MODULATE2X=0x10
    MODULATE4X=0x20 ADD=0x40 ADDSIGNED=0x80 ADDSIGNED2X=0x100 SUBTRACT=0x200
    ADDSMOOTH=0x400 BLENDDIFFUSEALPHA=0x800 BLENDTEXTUREALPHA=0x1000
    BLENDFACTORALPHA=0x2000 BLENDTEXTUREALPHAPM=0x4000 BLENDCURRENTALPHA=0x8000
    PREMODULATE=0x10000 MODULATEALPHA_ADDCOLOR=0x20000 MODULATECOLOR_ADDALPHA=0x40000
    MODULATEINVALPHA_ADDCOLOR=0x80000 MODULATEINVCOLOR_ADDALPHA=0x100000
    BUMPENVMAP=0x200000 BUMPENVMAPLUMINANCE=0x400000 DOTPRODUCT3=0x800000
    MULTIPLYADD=0x1000000 LERP=0x2000000""")
VTXPCAPS = _bit_table("""
    TEXGEN=0x1 MATERIALSOURCE7=0x2 DIRECTIONALLIGHTS=0x8 POSITIONALLIGHTS=0x10
    LOCALVIEWER=0x20 TWEENING=0x40 TEXGEN_SPHEREMAP=0x100 NO_TEXGEN_NONLOCALVIEWER=0x200""")
DTCAPS = _bit_table("""
    UBYTE4=0x1 UBYTE4N=0x2 SHORT2N=0x4 SHORT4N=0x8 USHORT2N=0x10 USHORT4N=0x20
    UDEC3=0x40 DEC3N=0x80 FLOAT16_2=0x100 FLOAT16_4=0x200""")
PS20CAPS = _bit_table("""
    ARBITRARYSWIZZLE=0x1 GRADIENTINSTRUCTIONS=0x2 PREDICATION=0x4
    NODEPENDENTREADLIMIT=0x8 NOTEXINSTRUCTIONLIMIT=0x10""")
VS20CAPS = _bit_table("PREDICATION=0x1")

# Header prefix of each bit table, for messages and for `has()` given a full name.
_PREFIXES = {
    id(DEVCAPS): "D3DDEVCAPS_", id(PMISCCAPS): "D3DPMISCCAPS_", id(RASTERCAPS): "D3DPRASTERCAPS_",
    id(CMPCAPS): "D3DPCMPCAPS_", id(BLENDCAPS): "D3DPBLENDCAPS_", id(SHADECAPS): "D3DPSHADECAPS_",
    id(TEXTURECAPS): "D3DPTEXTURECAPS_", id(FILTERCAPS): "D3DPTFILTERCAPS_",
    id(ADDRESSCAPS): "D3DPTADDRESSCAPS_", id(STENCILCAPS): "D3DSTENCILCAPS_",
    id(TEXOPCAPS): "D3DTEXOPCAPS_", id(VTXPCAPS): "D3DVTXPCAPS_", id(DTCAPS): "D3DDTCAPS_",
    id(PS20CAPS): "D3DPS20CAPS_", id(VS20CAPS): "D3DVS20CAPS_",
}



def bit_prefix(field: str) -> str:
    """The d3d9caps.h header prefix of a cap-bit field's bits: 'SrcBlendCaps' ->
    'D3DPBLENDCAPS_' (messages name a bit in full, as the header does)."""
    spec = FIELDS.get(ALIASES.get(field, field))
    if spec is None or spec.table is None:
        raise ValueError(f"{field} is not a cap-bit field")
    return _PREFIXES[id(spec.table)]


# D3DFORMAT names a profile may list: every one of d3d9types.h (effects.program.formats).
FORMATS = frozenset(D3DFORMAT)
USAGES = ("texture", "cube", "volume", "rendertarget", "depthstencil", "filter", "blend",
          "vertextexture")
VERTEX_PROCESSING = ("hardware", "mixed", "software")
PIXEL_SHADER_VERSIONS = ("0.0", "1.0", "1.1", "1.2", "1.3", "1.4", "2.0", "3.0")
VERTEX_SHADER_VERSIONS = ("0.0", "1.0", "1.1", "2.0", "3.0")
PRECISION_MODELS = ("fixed_function", "ps_1_x", "ps_1_4", "ps_2_0", "ps_3_0")
FLOAT_FORMATS = ("fp16", "fp24", "fp32")
SEVERITIES = ("error", "warning")

# Software vertex processing runs every vertex shader model of the Direct3D 9 runtime
# ("full support for programmable vertex shaders", DX9 docs "Processing Vertex Data").
DEFAULT_SOFTWARE_VS_VERSION = "3.0"

ALIASES = {"PixelShader1xMaxValue": "MaxPixelShaderValue"}


# ---------------------------------------------------------------------------------------------
# Schema: one row per field.

@dataclass(frozen=True)
class FieldSpec:
    """How a profile field is checked: its kind, the bit table or choices, and its range."""

    kind: str                       # int, float, str, version, bits, choice, list, mapping...
    table: Mapping[str, int] | None = None
    choices: tuple[str, ...] = ()
    low: float | None = None
    high: float | None = None
    doc: str = ""


def _int(low: int = 0, high: int | None = None, doc: str = "") -> FieldSpec:
    return FieldSpec("int", low=low, high=high, doc=doc)


def _bits(table: Mapping[str, int], doc: str = "") -> FieldSpec:
    return FieldSpec("bits", table=table, doc=doc)


FIELDS: dict[str, FieldSpec] = {
    # identity (not D3DCAPS9)
    "name": FieldSpec("str"), "description": FieldSpec("str"), "display_name": FieldSpec("str"),
    "generation": FieldSpec("choice", choices=GENERATIONS), "inherit": FieldSpec("str"),
    "VendorId": _int(0, 0xFFFF), "DeviceId": _int(0, 0xFFFF),
    # D3DCAPS9 bit fields
    "DevCaps": _bits(DEVCAPS), "PrimitiveMiscCaps": _bits(PMISCCAPS),
    "RasterCaps": _bits(RASTERCAPS), "ZCmpCaps": _bits(CMPCAPS), "AlphaCmpCaps": _bits(CMPCAPS),
    "SrcBlendCaps": _bits(BLENDCAPS), "DestBlendCaps": _bits(BLENDCAPS),
    "ShadeCaps": _bits(SHADECAPS), "TextureCaps": _bits(TEXTURECAPS),
    "TextureFilterCaps": _bits(FILTERCAPS), "CubeTextureFilterCaps": _bits(FILTERCAPS),
    "VolumeTextureFilterCaps": _bits(FILTERCAPS), "VertexTextureFilterCaps": _bits(FILTERCAPS),
    "StretchRectFilterCaps": _bits(FILTERCAPS),
    "TextureAddressCaps": _bits(ADDRESSCAPS), "VolumeTextureAddressCaps": _bits(ADDRESSCAPS),
    "StencilCaps": _bits(STENCILCAPS), "TextureOpCaps": _bits(TEXOPCAPS),
    "VertexProcessingCaps": _bits(VTXPCAPS), "DeclTypes": _bits(DTCAPS),
    # D3DCAPS9 numbers
    "MaxTextureWidth": _int(1), "MaxTextureHeight": _int(1), "MaxVolumeExtent": _int(0),
    "MaxTextureRepeat": _int(0), "MaxTextureAspectRatio": _int(0), "MaxAnisotropy": _int(0),
    "MaxVertexW": FieldSpec("float", low=0.0),
    "MaxTextureBlendStages": _int(1, 8), "MaxSimultaneousTextures": _int(1, 8),
    "MaxActiveLights": _int(0), "MaxUserClipPlanes": _int(0), "MaxVertexBlendMatrices": _int(0),
    "MaxVertexBlendMatrixIndex": _int(0), "MaxPointSize": FieldSpec("float", low=0.0),
    "MaxPrimitiveCount": _int(0), "MaxVertexIndex": _int(0), "MaxStreams": _int(0),
    "MaxStreamStride": _int(0), "MaxVertexShaderConst": _int(0),
    "MaxPixelShaderValue": FieldSpec("float", low=0.0),
    "MaxNpatchTessellationLevel": FieldSpec("float", low=0.0),
    "NumSimultaneousRTs": _int(1, 4),
    "MaxVShaderInstructionsExecuted": _int(0), "MaxPShaderInstructionsExecuted": _int(0),
    "MaxVertexShader30InstructionSlots": _int(0, 32768),
    "MaxPixelShader30InstructionSlots": _int(0, 32768),
    "VertexShaderVersion": FieldSpec("version", choices=VERTEX_SHADER_VERSIONS),
    "PixelShaderVersion": FieldSpec("version", choices=PIXEL_SHADER_VERSIONS),
    "SoftwareVertexShaderVersion": FieldSpec("version", choices=VERTEX_SHADER_VERSIONS),
    # structured fields
    "PS20Caps": FieldSpec("ps20caps"), "VS20Caps": FieldSpec("vs20caps"),
    "VertexProcessing": FieldSpec("choicelist", choices=VERTEX_PROCESSING),
    "TextureFormats": FieldSpec("formats"), "Precision": FieldSpec("precision"),
    "Quirks": FieldSpec("quirks"),
}

# Ranges of D3DPSHADERCAPS2_0 / D3DVSHADERCAPS2_0 (d3d9caps.h D3DPS20_MIN_* .. D3DPS20_MAX_*).
PS20_FIELDS: dict[str, FieldSpec] = {
    "Caps": _bits(PS20CAPS), "DynamicFlowControlDepth": _int(0, 24), "NumTemps": _int(12, 32),
    "StaticFlowControlDepth": _int(0, 4), "NumInstructionSlots": _int(96, 512),
    "DependentReadDepth": _int(0, 16),
}
VS20_FIELDS: dict[str, FieldSpec] = {
    "Caps": _bits(VS20CAPS), "DynamicFlowControlDepth": _int(0, 24), "NumTemps": _int(12, 32),
    "StaticFlowControlDepth": _int(1, 4),
}
PRECISION_FIELDS: dict[str, FieldSpec] = {
    "format": FieldSpec("choice", choices=("fixed",) + FLOAT_FORMATS),
    "bits": _int(1, 23), "range": FieldSpec("float", low=0.0), "signed": FieldSpec("bool"),
}
QUIRK_COMMON = {"id": FieldSpec("str"), "rule": FieldSpec("str"), "text": FieldSpec("str"),
                "source": FieldSpec("str"), "severity": FieldSpec("choice", choices=SEVERITIES)}
QUIRK_RULES: dict[str, dict[str, FieldSpec]] = {
    "arg_not_texture": {"op": FieldSpec("texop"), "arg": _int(0, 2),
                        "channel": FieldSpec("choice", choices=("color", "alpha", "both"))},
    "textures_need_op": {"max_textures": _int(0, 8), "ops": FieldSpec("texoplist")},
    "op_stages": {"op": FieldSpec("texop"), "stages": FieldSpec("intlist", low=0, high=7)},
    "max_textures": {"count": _int(0, 8)},
    "cap_unreliable": {"field": FieldSpec("str"), "bit": FieldSpec("str")},
    "format_unreliable": {"format": FieldSpec("choice", choices=tuple(sorted(FORMATS))),
                          "usage": FieldSpec("choice", choices=USAGES)},
    "note": {},
    "remove": {},
}
QUIRK_REQUIRED = {"arg_not_texture": ("op", "arg"), "textures_need_op": ("max_textures", "ops"),
                  "op_stages": ("op", "stages"), "max_textures": ("count",),
                  "cap_unreliable": ("field", "bit"), "format_unreliable": ("format",),
                  "note": (), "remove": ()}

# Present in every profile after `inherit` is applied.
REQUIRED = ("generation", "VendorId", "DeviceId", "MaxTextureBlendStages",
            "MaxSimultaneousTextures", "TextureOpCaps", "VertexShaderVersion",
            "PixelShaderVersion", "VertexProcessing")

# Mapping fields merge key by key with their parent's; every other field replaces it.
_MERGED_MAPPINGS = ("PS20Caps", "VS20Caps", "TextureFormats", "Precision")


# ---------------------------------------------------------------------------------------------
# Public types

@dataclass(frozen=True)
class Precision:
    """How a shader model's values are held: fixed point (bits, range) or a float format."""

    format: str                 # fixed | fp16 | fp24 | fp32
    bits: int | None = None     # fraction bits, fixed only
    range: float | None = None  # magnitude bound, fixed only
    signed: bool = True

    @property
    def is_float(self) -> bool:
        return self.format != "fixed"


@dataclass(frozen=True)
class Quirk:
    """One driver rule beyond the caps bits; `params` holds the rule's own keys."""

    id: str
    rule: str
    params: Mapping[str, Any]
    text: str
    source: str
    severity: str
    location: Location

    def get(self, key: str, default: Any = None) -> Any:
        return self.params.get(key, default)


@dataclass(frozen=True)
class CapsProfile:
    """A simulated card: its merged caps (read-only) and where each field was written."""

    name: str
    description: str
    generation: str
    caps: Mapping[str, Any]
    path: str
    display_name: str = ""
    inherits: tuple[str, ...] = ()
    locations: Mapping[str, Location] = field(default_factory=dict, repr=False, compare=False)
    quirk_list: tuple[Quirk, ...] = field(default=(), repr=False)

    def get(self, name: str, default: Any = None) -> Any:
        return self.caps.get(ALIASES.get(name, name), default)

    def has(self, name: str, bit: str) -> bool:
        """Whether cap-bit field `name` has `bit` (with or without its header prefix)."""
        field_name, short = _cap_bit(name, bit)
        return short in self.caps.get(field_name, frozenset())

    def generation_index(self) -> int:
        return GENERATIONS.index(self.generation)

    @property
    def pixel_shader_version(self) -> tuple[int, int]:
        return _version_tuple(self.caps["PixelShaderVersion"])

    @property
    def vertex_shader_version(self) -> tuple[int, int]:
        """The vertex shader version run in hardware ((0, 0): none)."""
        return _version_tuple(self.caps["VertexShaderVersion"])

    @property
    def software_vertex_shader_version(self) -> tuple[int, int]:
        """The vertex shader version run on the CPU, or (0, 0) without software processing."""
        if "software" not in self.vertex_processing:
            return (0, 0)
        return _version_tuple(self.caps.get("SoftwareVertexShaderVersion",
                                            DEFAULT_SOFTWARE_VS_VERSION))

    @property
    def vertex_processing(self) -> frozenset[str]:
        return self.caps["VertexProcessing"]

    @property
    def hardware_tnl(self) -> bool:
        return "HWTRANSFORMANDLIGHT" in self.caps.get("DevCaps", frozenset())

    def format_usages(self, fmt: str) -> frozenset[str]:
        """The usages CheckDeviceFormat accepts for `fmt` (D3DFMT_ prefix optional)."""
        short = fmt[len("D3DFMT_"):] if fmt.startswith("D3DFMT_") else fmt
        return self.caps.get("TextureFormats", {}).get(short, frozenset())

    def precision(self, model: str) -> Precision | None:
        """Precision for `fixed_function`, `ps_1_x`, `ps_1_4`, `ps_2_0` or `ps_3_0`."""
        return self.caps.get("Precision", {}).get(model)

    @property
    def quirks(self) -> list[Quirk]:
        return list(self.quirk_list)

    def location(self, name: str) -> Location:
        """Where `name` was defined (this file or the profile it inherits from)."""
        return self.locations.get(ALIASES.get(name, name), Location(self.path, 1, 1))

    @property
    def title(self) -> str:
        return self.display_name or self.name

    def __str__(self) -> str:
        return f"{self.title} ({self.generation})"


@lru_cache(maxsize=1024)   # validation asks a few hundred (field, bit) pairs thousands of times
def _cap_bit(name: str, bit: str) -> tuple[str, str]:
    """(the field's canonical name, the bit without its prefix); ValueError for a field that
    has no bits or a bit it does not have."""
    spec = FIELDS.get(ALIASES.get(name, name))
    table = spec.table if spec is not None else None
    if table is None:
        raise ValueError(f"{name} is not a cap-bit field")
    prefix = _PREFIXES[id(table)]
    short = bit[len(prefix):] if bit.startswith(prefix) else bit
    if short not in table:
        raise ValueError(f"{bit} is not a {prefix}* bit")
    return ALIASES.get(name, name), short


def _version_tuple(text: str) -> tuple[int, int]:
    major, minor = text.split(".")
    return int(major), int(minor)


def bits_mask(field_name: str, bits) -> int:
    """The DWORD value of a set of bit names of `field_name` (for display and tests)."""
    table = FIELDS[field_name].table
    return sum(table[b] for b in bits)


# ---------------------------------------------------------------------------------------------
# Loading

def list_profiles() -> list[str]:
    """Bundled profile names, by generation then name."""
    names = []
    for path in PROFILE_DIR.glob("*.yaml"):
        names.append((GENERATIONS.index(load_profile(path.stem).generation), path.stem))
    return [name for _, name in sorted(names)]


def load_profile(name_or_path: str | Path) -> CapsProfile:
    """A bundled profile by name (`geforce3`) or a profile file by path."""
    return _load_resolved(str(_resolve(name_or_path)))


def clear_cache() -> None:
    """Forget loaded profiles (after editing a profile file)."""
    _LOADED.clear()
    _resolved_folder.cache_clear()


def _resolve(name_or_path: str | Path, relative_to: Path | None = None,
             where: Location | None = None) -> Path:
    text = str(name_or_path)

    def here() -> Location:   # where an error about `text` is reported
        return where or Location(yaml_input.brief(text)[1:-1] or "<profile>", 1, 1)

    if not text.strip():
        raise ProfileError("the profile name is empty; name a card (`effects profiles` lists "
                           "them) or a .yaml file", here())
    if names_a_profile_file(text):
        path = Path(text)
        if not path.is_absolute() and relative_to is not None:
            path = relative_to / path
        found = _resolved_file(path)
        if found is not None:
            return found
        if path.exists():   # a directory, a FIFO, a device: say which
            untrusted.check_regular(str(path), "profile", ProfileError, here())
        raise _located(f"no profile file '{text}'", here())
    found = _resolved_file(PROFILE_DIR / f"{text}.yaml")
    if found is not None:
        return found
    known = sorted(p.stem for p in PROFILE_DIR.glob("*.yaml"))
    raise _located(f"unknown profile '{text}'{_did_you_mean(text, known)}; "
                   f"known profiles: {', '.join(known)}", here())


def _resolved_file(path: Path) -> Path | None:
    """What `path.resolve() if path.is_file() else None` answers. A regular file that is no
    symlink, named by an absolute path, resolves to its folder's resolution plus its name, and
    that is kept per folder (clear_cache forgets it): resolve() walks every component (~30 us),
    and `effects matrix` names each card again for every effect file."""
    try:
        mode: int | None = os.lstat(path).st_mode if path.is_absolute() else None
    except (OSError, ValueError):
        mode = None    # is_file() below says what this means
    if mode is not None and stat.S_ISREG(mode):
        return _resolved_folder(path.parent) / path.name
    return path.resolve() if path.is_file() else None


@lru_cache(maxsize=16)
def _resolved_folder(folder: Path) -> Path:
    return folder.resolve()


# resolved path -> its profile: every profile loaded in this process, parents included
_LOADED: dict[str, CapsProfile] = {}


def _load_resolved(path: str) -> CapsProfile:
    held = _LOADED.get(path)
    if held is None:
        held = _LOADED[path] = _build(Path(path), ())
    return held


def _build(path: Path, chain: tuple[str, ...]) -> CapsProfile:
    raw, inherit_location, key_locations = _read(path)
    parent: CapsProfile | None = None
    inherit = raw.get("inherit")
    if inherit is not None:
        where = inherit_location
        parent_path = _resolve(inherit, path.parent, where)
        if str(parent_path) in chain + (str(path),):
            raise _located(f"inherit cycle: {' -> '.join(Path(p).stem for p in chain)}"
                           f"{' -> ' if chain else ''}{path.stem} -> {inherit}", where)
        if len(chain) + 2 > limits.get("inherit_depth"):
            raise _located(limits.message("inherit_depth", len(chain) + 2, "the inherit chain"), where)
        # A parent not loaded yet is built along the chain (so a cycle is seen) and kept: it is
        # the profile a load of its own file gives (the chain only finds cycles). One loaded
        # before was built from its own file, its own chain checked then.
        # (A kept parent deeper than the chain allows is built along it again, so the depth
        # error is the one a fresh build reports, where it reports it.)
        parent = _LOADED.get(str(parent_path))
        if parent is None or len(chain) + 2 + len(parent.inherits) > limits.get("inherit_depth"):
            parent = _build(parent_path, chain + (str(path),))
            _LOADED[str(parent_path)] = parent
    caps, where_defined, quirks = _merge(parent, raw, key_locations, path)
    missing = [name for name in REQUIRED if name not in caps]
    if missing:
        raise ProfileError(f"profile lacks required field(s): {', '.join(missing)}",
                           Location(str(path), 1, 1))
    _check_consistency(caps, where_defined)
    return CapsProfile(
        name=raw.get("name", path.stem),
        description=raw.get("description", parent.description if parent else ""),
        generation=caps["generation"],
        caps=MappingProxyType(caps),
        path=str(path),
        display_name=raw.get("display_name", parent.display_name if parent else ""),
        inherits=((parent.name,) + parent.inherits) if parent else (),
        locations=MappingProxyType(where_defined),
        quirk_list=tuple(quirks),
    )


def _merge(parent: CapsProfile | None, raw: dict, key_locations: dict, path: Path):
    caps: dict[str, Any] = dict(parent.caps) if parent else {}
    where: dict[str, Location] = dict(parent.locations) if parent else {}
    for name, value in raw.items():
        if name in ("name", "description", "display_name", "inherit", "Quirks"):
            continue
        if name in _MERGED_MAPPINGS and name in caps:
            value = MappingProxyType({**caps[name], **value})
        caps[name] = value
        where[name] = key_locations[name]
    quirks = {q.id: q for q in (parent.quirk_list if parent else ())}
    for quirk in raw.get("Quirks", ()):
        if quirk.rule == "remove":
            if quirk.id not in quirks:
                raise _located(f"no inherited quirk '{quirk.id}' to remove", quirk.location)
            del quirks[quirk.id]
        else:
            quirks[quirk.id] = quirk
    if "Quirks" in raw:
        where["Quirks"] = key_locations["Quirks"]
    caps["Quirks"] = tuple(quirks.values())
    return caps, where, list(quirks.values())


def _check_consistency(caps: dict, where: dict) -> None:
    """Rules between fields that the D3D9 runtime relies on."""
    if caps["MaxSimultaneousTextures"] > caps["MaxTextureBlendStages"]:
        raise _located(
            f"MaxSimultaneousTextures ({caps['MaxSimultaneousTextures']}) exceeds "
            f"MaxTextureBlendStages ({caps['MaxTextureBlendStages']})",
            where["MaxSimultaneousTextures"])
    if _version_tuple(caps["PixelShaderVersion"]) >= (2, 0) and "PS20Caps" not in caps:
        raise _located("PixelShaderVersion 2.0 or later needs PS20Caps",
                       where["PixelShaderVersion"])
    if _version_tuple(caps["VertexShaderVersion"]) >= (2, 0) and "VS20Caps" not in caps:
        raise _located("VertexShaderVersion 2.0 or later needs VS20Caps",
                       where["VertexShaderVersion"])


# ---------------------------------------------------------------------------------------------
# Reading one file: YAML nodes -> checked Python values, with every key's location.

_STR_TAG = "tag:yaml.org,2002:str"


class _Reader:
    """Converts a composed YAML document into checked values, raising located errors."""

    def __init__(self, path: Path, text: str) -> None:
        self.path = str(path)
        self.lines = text.splitlines()
        self.constructor = yaml_input.Constructor()

    def loc(self, node: yaml.Node) -> Location:
        return Location(self.path, node.start_mark.line + 1, node.start_mark.column + 1)

    def error(self, message: str, node: yaml.Node) -> ProfileError:
        where = self.loc(node)
        line = self.lines[where.line - 1] if 0 < where.line <= len(self.lines) else None
        return ProfileError(message, where, source_line=line)

    def scalar(self, node: yaml.Node) -> Any:
        if not isinstance(node, yaml.ScalarNode):
            return node  # the caller reports the wrong type
        if node.tag == _STR_TAG:
            return node.value   # what the constructor makes of it (most scalars: names, bits)
        try:
            return self.constructor.construct_object(node)
        except yaml.YAMLError as exc:   # a tag that cannot build its value (`!!int abc`)
            raise yaml_input.located(exc, self.path, ProfileError, "YAML value error", self.lines) from None

    def pairs(self, node: yaml.Node, what: str) -> list[tuple[str, yaml.Node, yaml.Node]]:
        if not isinstance(node, yaml.MappingNode):
            raise self.error(f"{what} must be a mapping", node)
        seen: dict[str, yaml.Node] = {}
        result = []
        for key_node, value_node in node.value:
            key = self.scalar(key_node)
            if not isinstance(key, str):
                raise self.error(f"{what}: keys must be names, not {yaml_input.brief(key)}", key_node)
            if key in seen:
                first = self.loc(seen[key])
                raise self.error(f"duplicate key '{key}' (first at line {first.line})", key_node)
            seen[key] = key_node
            result.append((key, key_node, value_node))
        return result

    def mapping(self, node: yaml.Node, fields: Mapping[str, FieldSpec], what: str) -> dict:
        result = {}
        for key, key_node, value_node in self.pairs(node, what):
            spec = fields.get(key)
            if spec is None:
                raise self.error(f"unknown key '{key}' in {what}"
                                 f"{_did_you_mean(key, list(fields))}", key_node)
            result[key] = self.value(spec, value_node, key)
        return result

    def value(self, spec: FieldSpec, node: yaml.Node, name: str) -> Any:
        check: Callable[[FieldSpec, yaml.Node, str], Any] = getattr(self, f"check_{spec.kind}")
        return check(spec, node, name)

    # -- one method per kind of field ---------------------------------------------------------
    def check_str(self, spec, node, name):
        value = self.scalar(node)
        if not isinstance(value, str):
            raise self.error(f"{name} must be a string, not {_describe(value)}", node)
        return value

    def check_bool(self, spec, node, name):
        value = self.scalar(node)
        if not isinstance(value, bool):
            raise self.error(f"{name} must be true or false, not {_describe(value)}", node)
        return value

    def check_int(self, spec, node, name):
        value = self.scalar(node)
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.error(f"{name} must be an integer, not {_describe(value)}", node)
        self._range(spec, value, node, name)
        return value

    def check_float(self, spec, node, name):
        value = self.scalar(node)
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.error(f"{name} must be a number, not {_describe(value)}", node)
        self._range(spec, value, node, name)
        return float(value)

    def _range(self, spec, value, node, name):
        if value != value:   # NaN compares false with every bound
            raise self.error(f"{name} must be a number, not NaN", node)
        if spec.low is not None and value < spec.low:
            raise self.error(f"{name} must be at least {spec.low}, not {value}", node)
        if spec.high is not None and value > spec.high:
            raise self.error(f"{name} must be at most {spec.high}, not {value}", node)

    def check_choice(self, spec, node, name):
        value = self.scalar(node)
        if not isinstance(value, str):
            raise self.error(f"{name} must be one of {', '.join(spec.choices)}, "
                             f"not {_describe(value)}", node)
        if value not in spec.choices:
            raise self.error(f"{name} '{value}' is not one of {', '.join(spec.choices)}"
                             f"{_did_you_mean(value, spec.choices)}", node)
        return value

    def check_version(self, spec, node, name):
        value = self.scalar(node)
        if not isinstance(value, str):
            raise self.error(f"{name} must be a quoted version string such as \"1.1\", "
                             f"not {_describe(value)}", node)
        if value not in spec.choices:
            raise self.error(f"{name} '{value}' is not one of {', '.join(spec.choices)}", node)
        return value

    def items(self, node, name):
        if not isinstance(node, yaml.SequenceNode):
            raise self.error(f"{name} must be a list, not {_describe(self.scalar(node))}", node)
        return node.value

    def check_bits(self, spec, node, name):
        prefix = _PREFIXES[id(spec.table)]
        bits = set()
        for item in self.items(node, name):
            bit = self.scalar(item)
            if not isinstance(bit, str):
                raise self.error(f"{name} entries must be {prefix}* names without the prefix, "
                                 f"not {_describe(bit)}", item)
            if bit.startswith(prefix):
                raise self.error(f"write '{bit[len(prefix):]}' without the {prefix} prefix", item)
            if bit not in spec.table:
                raise self.error(f"unknown {name} bit '{bit}' (no {prefix}{bit})"
                                 f"{_did_you_mean(bit, list(spec.table))}", item)
            bits.add(bit)
        return frozenset(bits)

    def check_choicelist(self, spec, node, name):
        return frozenset(self.check_choice(spec, item, name) for item in self.items(node, name))

    def check_intlist(self, spec, node, name):
        return tuple(self.check_int(spec, item, name) for item in self.items(node, name))

    def check_texop(self, spec, node, name):
        op = self.check_str(spec, node, name)
        if op not in TEXOPCAPS:
            raise self.error(f"{name} '{op}' is not a texture op (D3DTEXOPCAPS_*)"
                             f"{_did_you_mean(op, list(TEXOPCAPS))}", node)
        return op

    def check_texoplist(self, spec, node, name):
        return tuple(self.check_texop(spec, item, name) for item in self.items(node, name))

    def check_ps20caps(self, spec, node, name):
        return MappingProxyType(self.mapping(node, PS20_FIELDS, name))

    def check_vs20caps(self, spec, node, name):
        return MappingProxyType(self.mapping(node, VS20_FIELDS, name))

    def check_formats(self, spec, node, name):
        formats = {}
        usage_spec = FieldSpec("choice", choices=USAGES)
        for fmt, key_node, value_node in self.pairs(node, name):
            if fmt not in FORMATS:
                raise self.error(f"unknown format '{fmt}' in {name} (no D3DFMT_{fmt})"
                                 f"{_did_you_mean(fmt, list(FORMATS))}", key_node)
            usages = self.items(value_node, f"{name}.{fmt}")
            formats[fmt] = frozenset(self.check_choice(usage_spec, u, f"usage of {fmt}")
                                     for u in usages)
        return MappingProxyType(formats)

    def check_precision(self, spec, node, name):
        result = {}
        for model, key_node, value_node in self.pairs(node, name):
            if model not in PRECISION_MODELS:
                raise self.error(f"unknown shader model '{model}' in {name}; use one of "
                                 f"{', '.join(PRECISION_MODELS)}"
                                 f"{_did_you_mean(model, PRECISION_MODELS)}", key_node)
            result[model] = self.one_precision(value_node, f"{name}.{model}")
        return MappingProxyType(result)

    def one_precision(self, node, name) -> Precision:
        if isinstance(node, yaml.ScalarNode):
            fmt = self.check_choice(FieldSpec("choice", choices=FLOAT_FORMATS), node, name)
            return Precision(fmt)
        values = self.mapping(node, PRECISION_FIELDS, name)
        if "format" not in values:
            raise self.error(f"{name} needs a format", node)
        if values["format"] == "fixed" and not {"bits", "range"} <= values.keys():
            raise self.error(f"{name}: fixed point needs bits and range", node)
        return Precision(values["format"], values.get("bits"), values.get("range"),
                         values.get("signed", True))

    def check_quirks(self, spec, node, name):
        quirks = []
        ids: set[str] = set()
        for item in self.items(node, name):
            pairs = self.pairs(item, "a quirk")
            keys = {key: (key_node, value_node) for key, key_node, value_node in pairs}
            for required in ("id", "rule"):
                if required not in keys:
                    raise self.error(f"quirk lacks '{required}'", item)
            rule_node = keys["rule"][1]
            rule = self.check_str(spec, rule_node, "rule")
            if rule not in QUIRK_RULES:
                raise self.error(f"unknown quirk rule '{rule}'; rules: "
                                 f"{', '.join(QUIRK_RULES)}{_did_you_mean(rule, QUIRK_RULES)}",
                                 rule_node)
            allowed = {**QUIRK_COMMON, **QUIRK_RULES[rule]}
            values = self.mapping(item, allowed, f"a {rule} quirk")
            for required in QUIRK_REQUIRED[rule] + (("text",) if rule != "remove" else ()):
                if required not in values:
                    raise self.error(f"{rule} quirk '{values['id']}' lacks '{required}'", item)
            if rule == "cap_unreliable":
                self.check_cap_reference(values, keys)
            if values["id"] in ids:
                raise self.error(f"duplicate quirk id '{values['id']}'", keys["id"][1])
            ids.add(values["id"])
            params = {k: v for k, v in values.items() if k not in QUIRK_COMMON}
            quirks.append(Quirk(values["id"], rule, MappingProxyType(params),
                                values.get("text", ""), values.get("source", ""),
                                values.get("severity", "error"), self.loc(item)))
        return tuple(quirks)

    def check_cap_reference(self, values, keys):
        spec = FIELDS.get(values["field"])
        if spec is None or spec.kind != "bits":
            raise self.error(f"'{values['field']}' is not a cap-bit field", keys["field"][1])
        if values["bit"] not in spec.table:
            raise self.error(f"unknown {values['field']} bit '{values['bit']}'"
                             f"{_did_you_mean(values['bit'], list(spec.table))}", keys["bit"][1])


def _read(path: Path) -> tuple[dict, Location | None, dict[str, Location]]:
    """Parse and check one profile file: (values, where the `inherit` value is, key locations)."""
    text = untrusted.read_text(path, "profile", ProfileError, "yaml_bytes")
    reader = _Reader(path, text)
    # libyaml's parser where PyYAML has it (yaml_input): the pure-Python one is most of the
    # time `effects matrix` takes; both give the same nodes and marks.
    loader, root = yaml_input.compose(text, str(path), ProfileError)
    loader.dispose()
    if root is None:
        raise ProfileError("empty profile", Location(str(path), 1, 1))
    values: dict[str, Any] = {}
    inherit_location: Location | None = None
    key_locations: dict[str, Location] = {}
    spelled: dict[str, str] = {}
    for key, key_node, value_node in reader.pairs(root, "a profile"):
        canonical = ALIASES.get(key, key)
        spec = FIELDS.get(canonical)
        if spec is None:
            raise reader.error(f"unknown key '{key}'{_did_you_mean(key, list(FIELDS))}",
                               key_node)
        if canonical in values:  # both spellings of an aliased field
            raise reader.error(f"'{key}' and '{spelled[canonical]}' name the same field",
                               key_node)
        spelled[canonical] = key
        values[canonical] = reader.value(spec, value_node, key)
        key_locations[canonical] = reader.loc(key_node)
        if canonical == "inherit":
            inherit_location = reader.loc(value_node)
    return values, inherit_location, key_locations


def _located(message: str, where: Location) -> ProfileError:
    """A ProfileError at `where`, showing that line of the file when it can be read."""
    try:
        lines = untrusted.read_text(where.path, "profile", ProfileError, "yaml_bytes").splitlines()
        line = lines[where.line - 1] if 0 < where.line <= len(lines) else None
    except ProfileError:
        line = None
    return ProfileError(message, where, source_line=line)


def _did_you_mean(word: str, candidates) -> str:
    close = difflib.get_close_matches(word, list(candidates), n=1, cutoff=0.6)
    if not close:  # case slips: 'modulate' for MODULATE
        close = [c for c in candidates if c.lower() == word.lower()]
    return f"; did you mean '{close[0]}'?" if close else ""


def _describe(value: Any) -> str:
    if isinstance(value, yaml.Node):
        return "a mapping" if isinstance(value, yaml.MappingNode) else "a list"
    if value is None:
        return "nothing"
    return f"{type(value).__name__} {yaml_input.brief(value)}"
