"""`effects compile ... -o out.pso` writes bytecode, `--header` fxc's /Fh C array,
`effects compile --disassemble` prints a bytecode file's listing; `effects.load_shader` reads
raw bytecode and headers (BYTE and DWORD arrays); bad files are located errors, exit 2."""
from __future__ import annotations

import struct

import pytest

import effects
from effects.cli import main as cli
from effects.shaders.d3dbc import read_header, read_shader, write_header, write_shader
from effects.shaders.hlsl import compile_shader
from tests.paths import ROOT

WOOD = str(ROOT / "fxfiles" / "wood.fx")


def _compiled():
    return compile_shader(effects.load_effect(WOOD), "Wood", "ps_2_0")


def test_compile_writes_the_bytecode_fxc_fo_would(tmp_path, capsys):
    out = tmp_path / "wood.pso"
    assert cli.main(["compile", WOOD, "--entry", "Wood", "--target", "ps_2_0", "-o", str(out)]) == 0
    compiled = _compiled()
    assert out.read_bytes() == write_shader(compiled.program, compiled)
    assert out.read_bytes()[:4] == bytes([0x00, 0x02, 0xFF, 0xFF])    # ps_2_0's version token
    binary = effects.load_shader(out)
    assert binary.program.name == "ps_2_0"
    assert {c.name for c in binary.table.constants} >= {"lightwood", "darkwood", "NoiseSampler"}
    assert cli.main(["compile", "--disassemble", str(out)]) == 0
    listing = capsys.readouterr().out
    assert "ps_2_0\n" in listing and "dcl_volume s0" in listing and "//   lightwood" in listing
    assert "instruction slots" in listing


def test_header_round_trip(tmp_path, capsys):
    out = tmp_path / "wood.h"
    assert cli.main(["compile", WOOD, "--entry", "Wood", "--target", "ps_2_0", "--header",
                     "-o", str(out)]) == 0
    text = out.read_text()
    assert "const BYTE g_ps20_Wood[] =" in text and text.startswith("#if 0\n")
    compiled = _compiled()
    assert read_header(text) == [("g_ps20_Wood", write_shader(compiled.program, compiled))]
    assert effects.load_shader(out).program.instructions == read_shader(
        write_shader(compiled.program, compiled)).program.instructions
    assert cli.main(["compile", WOOD, "--entry", "Wood", "--target", "ps_2_0", "--header"]) == 0
    assert capsys.readouterr().out == text + "\n"


def test_old_sdk_dword_headers_read(tmp_path):
    data = write_shader(_compiled().program)
    dwords = struct.unpack(f"<{len(data) // 4}I", data)
    text = ("// a DX9 SDK-era header\nconst DWORD g_ps20_main[] =\n{\n    "
            + ", ".join(f"0x{w:08x}" for w in dwords) + "\n};\n")
    path = tmp_path / "old.h"
    path.write_text(write_header(b"\x01\x01\xff\xff\xff\xff\x00\x00", "g_first") + text)
    assert [name for name, _ in read_header(path.read_text())] == ["g_first", "g_ps20_main"]
    assert effects.load_shader(path, "g_ps20_main").program.name == "ps_2_0"
    with pytest.raises(effects.EffectError, match="no shader array nothere"):
        effects.load_shader(path, "nothere")


def test_bad_files_are_located_errors_exit_2(tmp_path, capsys):
    bad = tmp_path / "bad.pso"
    bad.write_bytes(b"\x00\x02\xff\xff\x05\x00\x00\x03")
    assert cli.main(["compile", "--disassemble", str(bad)]) == 2
    err = capsys.readouterr().err
    assert f"{bad}:1:5: error: " in err and "Traceback" not in err
    assert cli.main(["compile", "--disassemble", str(tmp_path / "missing.pso")]) == 2
    assert "cannot read shader bytecode" in capsys.readouterr().err
    # one shader's header needs its entry and target (`-o` alone writes the whole effect as
    # an fx_2_0 binary: tests/shaders/fxo/test_cli.py)
    assert cli.main(["compile", WOOD, "--header"]) == 2
    assert "--entry and --target" in capsys.readouterr().err
