"""The Direct3D 9 shader token format (d3dbc): the numbers of version, instruction, parameter,
declaration and comment tokens, one table per field, read by the writer, the reader and the
disassembler alike. Opcode numbers are a column of the instruction table
(effects/shaders/asm/instructions.py, `InstrInfo.code`).

Sources (facts only): the Windows driver documentation of the shader token format ("Version
Token", "Instruction Token", "Destination Parameter Token", "Source Parameter Token", "Shader
Relative Addressing", "Comment Token", "D3DSHADER_PARAM_REGISTER_TYPE",
"D3DSHADER_PARAM_SRCMOD_TYPE", "D3DSHADER_COMPARISON", "D3DDECLUSAGE", "D3DSAMPLER_TEXTURE_TYPE")
and the DirectX SDK's "Shader Binary Format" notes; vkd3d-shader's d3dbc notes for the order of
an instruction's tokens (destination, then the predicate, then the sources).
"""
from __future__ import annotations

VS_VERSION = 0xFFFE0000          # version token: high word 0xFFFE (vertex) or 0xFFFF (pixel),
PS_VERSION = 0xFFFF0000          # then major << 8 | minor
END = 0x0000FFFF
COMMENT = 0xFFFE                 # opcode of a comment; bits 16-30 count its DWORDs
PHASE = 0xFFFD

OPCODE_MASK = 0x0000FFFF
CONTROL_SHIFT, CONTROL_MASK = 16, 0xFF          # opcode-specific controls (comparison, texldp)
LENGTH_SHIFT, LENGTH_MASK = 24, 0xF             # tokens after this one: versions 2_0 and up
PREDICATED = 1 << 28                            # 2_0 and up: a predicate source token follows
COISSUE = 1 << 30                               # ps_1_x only
COMMENT_SHIFT, COMMENT_MASK = 16, 0x7FFF

PARAM = 1 << 31                                 # bit 31 of every parameter token
REG_NUMBER_MASK = 0x7FF
RELATIVE = 1 << 13                              # relative addressing (D3DSHADER_ADDRMODE_RELATIVE)
WRITEMASK_SHIFT = 16
RESULT_SHIFT = 20                               # destination: D3DSPDM_*
SATURATE, PARTIAL_PRECISION, CENTROID = 1, 2, 4
DSTSHIFT_SHIFT = 24                             # destination: a signed 4-bit result shift
SWIZZLE_SHIFT = 16                              # source: two bits per component, x first
SRCMOD_SHIFT = 24


def register_type(token: int) -> int:
    """D3DSHADER_PARAM_REGISTER_TYPE: bits 28-30 low, bits 11-12 high."""
    return ((token >> 28) & 0x7) | ((token >> 8) & 0x18)


def register_bits(rtype: int) -> int:
    return ((rtype & 0x7) << 28) | ((rtype & 0x18) << 8)


# D3DSHADER_PARAM_REGISTER_TYPE. The same number means a different register in vertex and
# pixel shaders (3: a0 / t#) and in vs_3_0 (6: o# rather than oT#); `register_kinds` settles it.
TEMP, INPUT, CONST, ADDR_TEXTURE, RASTOUT, ATTROUT, TEXCRDOUT_OUTPUT, CONSTINT, COLOROUT, \
    DEPTHOUT, SAMPLER, CONST2, CONST3, CONST4, CONSTBOOL, LOOP, TEMPFLOAT16, MISCTYPE, LABEL, \
    PREDICATE = range(20)
CONST_BANKS = (CONST, CONST2, CONST3, CONST4)   # c0-2047, c2048-4095, ...
CONST_BANK_SIZE = 2048
RASTOUT_KINDS = ("oPos", "oFog", "oPts")        # D3DSRO_POSITION, _FOG, _POINT_SIZE
MISC_KINDS = ("vPos", "vFace")                  # D3DSMO_POSITION, D3DSMO_FACE


def register_kinds(stage: str, major: int) -> dict[int, str]:
    """Register type -> the assembler's register kind (effects/shaders/asm/program.py) for a
    stage and major version; RASTOUT and MISCTYPE name their register by number instead."""
    return {TEMP: "r", INPUT: "v", CONST: "c", ADDR_TEXTURE: "a" if stage == "vs" else "t",
            ATTROUT: "oD", TEXCRDOUT_OUTPUT: "o" if (stage, major) == ("vs", 3) else "oT",
            CONSTINT: "i", COLOROUT: "oC", DEPTHOUT: "oDepth", SAMPLER: "s",
            CONSTBOOL: "b", LOOP: "aL", LABEL: "l", PREDICATE: "p"}


def kind_types(stage: str, major: int) -> dict[str, int]:
    """The inverse of `register_kinds`, with the named registers of RASTOUT and MISCTYPE."""
    out = {kind: rtype for rtype, kind in register_kinds(stage, major).items()}
    out.update({k: RASTOUT for k in RASTOUT_KINDS})
    out.update({k: MISCTYPE for k in MISC_KINDS})
    return out


# D3DSHADER_PARAM_SRCMOD_TYPE: (modifier, negate) -> number
SRCMODS: dict[tuple[str | None, bool], int] = {
    (None, False): 0, (None, True): 1, ("bias", False): 2, ("bias", True): 3,
    ("bx2", False): 4, ("bx2", True): 5, ("invert", False): 6, ("x2", False): 7,
    ("x2", True): 8, ("dz", False): 9, ("dw", False): 10, ("abs", False): 11,
    ("abs", True): 12,
}
SRCMOD_NOT = 13                 # !b# / !p0: a boolean's logical not
SRCMOD_NAMES = {n: key for key, n in SRCMODS.items()}

# D3DSHADER_COMPARISON, bits 16-18 of ifc / breakc / setp
COMPARISONS = {"gt": 1, "eq": 2, "ge": 3, "lt": 4, "ne": 5, "le": 6}
COMPARISON_NAMES = {n: name for name, n in COMPARISONS.items()}

# D3DDECLUSAGE, bits 0-4 of a dcl token; the usage index in bits 16-19
USAGES = ("position", "blendweight", "blendindices", "normal", "psize", "texcoord", "tangent",
          "binormal", "tessfactor", "positiont", "color", "fog", "depth", "sample")
USAGE_INDEX_SHIFT = 16
# D3DSAMPLER_TEXTURE_TYPE, bits 27-30 of a sampler's dcl token
SAMPLER_TYPE_SHIFT = 27
SAMPLER_TYPES = {"2d": 2, "cube": 3, "volume": 4}
SAMPLER_TYPE_NAMES = {n: name for name, n in SAMPLER_TYPES.items()}

# the result shift, a signed 4-bit number: _x2 = 1 ... _d8 = -3 (0xD); D3D9 defines these
SHIFTS = (-3, -2, -1, 0, 1, 2, 3)


def shift_bits(shift: int) -> int:
    return shift & 0xF


def shift_value(bits: int) -> int:
    return bits - 16 if bits >= 8 else bits


def fourcc(text: str) -> int:
    """'CTAB' as the DWORD that starts a constant-table comment."""
    return int.from_bytes(text.encode("ascii"), "little")
