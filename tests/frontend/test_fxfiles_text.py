"""Text-level checks of the bundled effect files (fxfiles/).

The parser is written elsewhere; these tests only read the text: the files exist, their
braces balance once comments and strings are removed, their techniques appear in the
documented fallback order, the BRDF transcription holds the chapter's printed programs, the
textures they name exist, and the ps.1.1 / ps_2_0 blocks stay inside their version's limits.
"""
from __future__ import annotations

from tests.paths import ROOT

import re
from pathlib import Path

import pytest

FX_DIR = ROOT / "fxfiles"

# File -> techniques in fallback order (None = an anonymous technique).
EXPECTED_TECHNIQUES: dict[str, list[str | None]] = {
    "brdf.fx": ["tec0"],
    "wood.fx": ["Wood_ps20", "WoodRings_ps20"],
    "fast_phong.fx": ["Phong", "Gouraud"],
    "phong.fx": ["PerPixelPhong_ps20", "PerPixelPhong_ps11", "Dot3_dx7", "SingleTexture"],
    "specular_bump.fx": ["Specular_ps20", "SpecularTable_ps11", "SpecularMultiply_ps11",
                         "Dot3_dx7", "BumpEnvMap_dx6", "Emboss_dx6", "SingleTexture"],
    "hemisphere.fx": ["HemisphereOcclusion_ps11", "HemispherePerPixel_ps11", "HemisphereVertex_vs11",
                      "SingleTexture"],
    "sdk8_style.fx": ["TPS4", "TPS1", "TFF7", "TDX6", None],
    "sdk9_style.fx": ["Marble_ps20", "Marble_ps11", "Marble_dx7", "Marble_dx6"],
    "sdk9_hlsl.fx": ["Scene_ps20", "Scene_ps14", "Scene_ps11", "Scene_ff"],
}

# The chapter's printed BRDF programs, instruction by instruction (comments dropped), typed
# from "Hardware Shading with Direct3D", section "DirectX 8 Pixel Shaders".
PRINTED_BRDF_VS = [
    "vs.1.1",
    "m4x4 oPos, v0, c4", "m4x4 r4,v0,c0", "m3x3 r0,v3,c0", "m3x3 r1,v8,c0",
    "mul r2,-r1.zxyw,r0.yzxw", "mad r2,-r1.yzxw,r0.zxyw,-r2",
    "add r4.xyz,-r4.xyz,c10", "dp3 r5.x,r4.xyz,r4.xyz", "rsq r5.x,r5.x",
    "mul r4.xyz,r5.xxx,r4.xyz",
    "add r5.xyz,r4.xyz,-c16", "dp3 r6.x,r5.xyz,r5.xyz", "rsq r6.x,r6.x",
    "mul r5.xyz,r6.xxx,r5.xyz",
    "dp3 oT0.x,r4,r1", "dp3 oT0.y,r4,r2", "dp3 oT0.z,r4,r0",
    "dp3 oT1.x,-c16,r1", "dp3 oT1.y,-c16,r2", "dp3 oT2.z,-c16,r0",
    "dp3 oT2.x,r5,r1", "dp3 oT2.y,r5,r2", "dp3 oT2.z,r5,r0",
    "mov oT3.xy,v7.xy", "mov oD0,c9",
]
PRINTED_BRDF_PS = [
    "ps.1.1", "tex t0", "tex t1", "tex t2", "tex t3",
    "mul r0,t0,t1", "mul r0,r0,t2", "mul r0,r0,t3", "mul r0,r0,v0",
]
# The one OCR repair brdf.fx makes (documented in its header): printed -> repaired.
BRDF_REPAIRS = {("dp3 oT2.z,-c16,r0", 20): "dp3 oT1.z,-c16,r0"}


def strip_comments(text: str, keep_strings: bool = False) -> str:
    """Remove // and /* */ comments and, unless `keep_strings`, the contents of string
    literals (kept as "")."""
    out: list[str] = []
    i, n = 0, len(text)
    while i < n:
        ch = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            assert j >= 0, "unterminated /* comment"
            out.append("\n" * text.count("\n", i, j))
            i = j + 2
        elif ch == '"':
            j = text.find('"', i + 1)
            assert j >= 0, "unterminated string"
            out.append(text[i:j + 1] if keep_strings else '""')
            i = j + 1
        else:
            out.append(ch)
            i += 1
    return "".join(out)


def read(name: str) -> str:
    return (FX_DIR / name).read_text(encoding="utf-8")


def techniques(text: str) -> list[str | None]:
    names: list[str | None] = []
    for m in re.finditer(r"\btechnique\b\s*(\w+)?\s*[<{]", strip_comments(text), re.IGNORECASE):
        names.append(m.group(1))
    return names


def asm_blocks(text: str) -> list[list[str]]:
    """Each `asm { ... }` body as a list of instruction lines (comments and blanks removed,
    `;` asm comments cut, whitespace normalised)."""
    clean = strip_comments(text)
    blocks = []
    for m in re.finditer(r"\basm\s*\{", clean, re.IGNORECASE):
        end = clean.index("}", m.end())
        lines = []
        for raw in clean[m.end():end].splitlines():
            line = raw.split(";", 1)[0].strip()
            if line:
                lines.append(re.sub(r"\s+", " ", line))
        blocks.append(lines)
    return blocks


def canonical(instruction: str) -> str:
    return re.sub(r"\s*,\s*", ",", instruction.strip())


@pytest.mark.parametrize("name", sorted(EXPECTED_TECHNIQUES))
def test_file_exists_and_is_ascii(name: str) -> None:
    data = (FX_DIR / name).read_bytes()
    assert data.strip(), f"{name} is empty"
    data.decode("ascii")  # old toolchains read these files as ANSI text


@pytest.mark.parametrize("name", sorted(EXPECTED_TECHNIQUES))
def test_braces_balance_outside_comments(name: str) -> None:
    clean = strip_comments(read(name))
    for open_, close in ("{}", "()", "[]"):
        depth = 0
        for line_no, line in enumerate(clean.splitlines(), 1):
            for ch in line:
                depth += (ch == open_) - (ch == close)
                assert depth >= 0, f"{name}:{line_no}: unmatched {close!r}"
        assert depth == 0, f"{name}: {depth} unclosed {open_!r}"


@pytest.mark.parametrize("name", sorted(EXPECTED_TECHNIQUES))
def test_techniques_in_fallback_order(name: str) -> None:
    assert techniques(read(name)) == EXPECTED_TECHNIQUES[name]


def test_strip_comments_ignores_techniques_in_comments() -> None:
    text = '// technique Fake { }\n/* technique Old { } */\nstring s = "technique T {";\ntechnique Real { }'
    assert techniques(text) == ["Real"]


def test_brdf_holds_the_printed_programs() -> None:
    blocks = asm_blocks(read("brdf.fx"))
    assert len(blocks) == 2
    vs, ps = ([canonical(i) for i in b] for b in blocks)
    expected_vs = [canonical(i) for i in PRINTED_BRDF_VS]
    for (printed, index), repaired in BRDF_REPAIRS.items():
        assert expected_vs[index] == canonical(printed)
        expected_vs[index] = canonical(repaired)
    assert vs == expected_vs
    assert ps == [canonical(i) for i in PRINTED_BRDF_PS]


def test_brdf_keeps_the_printed_declarations() -> None:
    clean = strip_comments(read("brdf.fx"))
    for decl in ("vector lhtR;", "vector MaterialColor;", "matrix mWld;", "matrix mTot;",
                 "texture BRDFTexture1;", "texture ObjectTexture;", "DWORD  BCLR = 0xff0000ff;",
                 "VertexShaderConstant[16] = <lhtR>;", "pixelshader ="):
        assert decl in clean
    decl_block = re.search(r"decl\s*\{([^}]*)\}", clean).group(1)
    assert re.findall(r"float\s+v(\d+)\[3\]", decl_block) == ["0", "3", "7", "8"]
    assert "stream 0;" in decl_block


ANNOTATED_TEXTURE = re.compile(r'string\s+(ResourceName|Procedural)\s*=\s*"([^"]*)"')


@pytest.mark.parametrize("name", sorted(EXPECTED_TECHNIQUES))
def test_named_texture_files_exist(name: str) -> None:
    for kind, value in ANNOTATED_TEXTURE.findall(strip_comments(read(name), keep_strings=True)):
        if kind == "Procedural":
            generator, _, argument = value.partition(":")
            assert generator in {"sobel_normals", "sobel_normals_ao", "sobel_dudv", "normalization_cube",
                                 "power_table", "noise3d", "sky_cube"}, value
            referenced = re.findall(r"<\s*(\w+)\s*>", argument)
            if referenced:                   # a parameter's value (effects/host/resources.py)
                for param in referenced:
                    assert re.search(rf"\bfloat\s+{param}\b", read(name)), f"{name}: {value}"
            elif not argument.replace(".", "").isdigit():
                assert (FX_DIR / argument).is_file(), f"{name}: {value}"
        else:
            assert (FX_DIR / value).is_file(), f"{name}: {value}"


@pytest.mark.parametrize("name", ["phong.fx", "specular_bump.fx", "hemisphere.fx", "sdk9_style.fx"])
def test_quality_annotations_fall_in_file_order(name: str) -> None:
    qualities = [int(q) for q in re.findall(r"int\s+Quality\s*=\s*(\d+)\s*;", strip_comments(read(name)))]
    assert len(qualities) == len(EXPECTED_TECHNIQUES[name])
    assert qualities == sorted(qualities, reverse=True) and len(set(qualities)) == len(qualities)


PS1_TEXTURE_OPS = {"tex", "texcoord", "texkill", "texbem", "texbeml", "texreg2ar", "texreg2gb",
                   "texm3x2pad", "texm3x2tex", "texm3x3pad", "texm3x3tex", "texm3x3spec",
                   "texm3x3vspec"}
PS2_TEXTURE_OPS = {"texld", "texldp", "texldb", "texkill"}
PS2_SLOTS = {"pow": 3, "nrm": 3, "lrp": 2, "crs": 2, "m3x2": 2, "m3x3": 3, "m3x4": 4,
             "m4x3": 3, "m4x4": 4, "sincos": 8, "dcl": 0, "def": 0}


def shader_blocks(version_prefixes: tuple[str, ...]):
    for name in sorted(EXPECTED_TECHNIQUES):
        for block in asm_blocks(read(name)):
            if block and block[0].lower().startswith(version_prefixes):
                yield name, block


def test_ps11_blocks_fit_the_version() -> None:
    blocks = list(shader_blocks(("ps.1.1", "ps_1_1")))
    assert len(blocks) >= 8  # brdf, phong x2, specular_bump x2, hemisphere, sdk8, sdk9
    for name, block in blocks:
        texture = arithmetic = 0
        for line in block[1:]:
            op = line.split()[0].lower().split("_")[0]
            if op in PS1_TEXTURE_OPS:
                assert arithmetic == 0, f"{name}: texture instruction after arithmetic: {line}"
                texture += 1
            elif op != "def" and not line.startswith("+"):
                arithmetic += 1
            for kind, number in re.findall(r"\b([rtcv])(\d+)", line.split(None, 1)[1]):
                limit = {"r": 2, "t": 4, "c": 8, "v": 2}[kind]
                assert int(number) < limit, f"{name}: {kind}{number} in ps.1.1: {line}"
        assert texture <= 4 and arithmetic <= 8, f"{name}: {texture} tex + {arithmetic} arith"


def test_ps20_blocks_fit_the_version() -> None:
    blocks = list(shader_blocks(("ps_2_0", "ps.2.0")))
    assert len(blocks) >= 4  # phong, specular_bump, sdk9 x2
    for name, block in blocks:
        texture = arithmetic = 0
        for line in block[1:]:
            op = line.split()[0].lower().split("_")[0]
            if op in PS2_TEXTURE_OPS:
                texture += 1
            else:
                arithmetic += PS2_SLOTS.get(op, 1)
        assert texture <= 32 and arithmetic <= 64, f"{name}: {texture} tex + {arithmetic} arith"


def test_every_bundled_effect_is_pictured_on_three_cards_in_the_gallery():
    """The gallery's pictures (docs/gallery.md): every fxfiles/*.fx on at least three cards (a
    card is the profile named in the thumbnail's file name), and every picture it shows exists."""
    import re
    import effects
    docs = FX_DIR.parent / "docs"
    gallery = (docs / "gallery.md").read_text()
    pictures = [f"docs/{p}" for p in re.findall(r"!\[[^\]]*\]\(([^)]+\.png)\)", gallery)]
    assert pictures and all((FX_DIR.parent / p).is_file() for p in pictures)
    profiles = set(effects.list_profiles())
    for fx in sorted(FX_DIR.glob("*.fx")):
        cards = {token for p in pictures if p.startswith(f"docs/thumbs/{fx.stem}_")
                 for token in Path(p).stem.split("_") if token in profiles}
        assert len(cards) >= 3, (fx.name, sorted(cards))
