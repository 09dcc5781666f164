"""MojoShader (Debian's libmojoshader0: the effect reader FNA and MonoGame's OpenGL path load
fxc's .fxo with) reads the fx_2_0 binaries we write: MOJOSHADER_compileEffect gives the same
parameters (names, semantics, D3DX classes and types), techniques and passes.

Each binary is read in a child process (a crash of the C library fails one case, not the
run). The one thing MojoShader reads differently from D3DX is named in SHADER_REFERENCE:
its readlargeobjects (mojoshader_effects.c) parses every resource of a shader state as
bytecode, so a pass whose `VertexShader = <param>` names a shader parameter (resource usage 1,
the parameter's name, as Wine's d3dx_parse_resource reads it) is refused with its parser's
message; those effects must hold such a reference. fxc wrote the same reference the same way
(resource usage 1, element NONE, the name and a NUL: Wine's effect_code and
shared_parameters blobs), and MojoShader refuses those binaries alike
(test_mojoshader_refuses_fxcs_own_shader_reference_alike)."""
from __future__ import annotations

import json
import shutil
import subprocess
import sys

import pytest

import effects
from effects.frontend.fxo import OBJECT_TYPES, NUMERIC_TYPES
from effects.model import ParamRef
from effects.shaders.fxo import write_effect_binary
from tests.paths import ROOT
from tests.shaders.d3dbc import mojoshader

LIB = mojoshader.load()
pytestmark = pytest.mark.skipif(LIB is None, reason="libmojoshader0 is not installed (apt-get "
                                "install libmojoshader0; .ci/setup does)")

FXFILES = sorted(p.name for p in (ROOT / "fxfiles").glob("*.fx"))
SHADER_REFERENCE = "Unsupported shader type or not a shader at all"


def _names_a_shader_parameter(effect) -> bool:
    return any(s.name in ("VertexShader", "PixelShader") and isinstance(s.value, ParamRef)
               for t in effect.techniques for p in t.passes for s in p.states)


@pytest.mark.parametrize("name", FXFILES)
def test_mojoshader_reads_what_we_write(tmp_path, name):
    folder = tmp_path / "fx"
    shutil.copytree(ROOT / "fxfiles", folder)
    effect = effects.load_effect(str(folder / name))
    path = folder / (name + "o")
    path.write_bytes(write_effect_binary(effect))
    run = subprocess.run([sys.executable, str(ROOT / "tests/shaders/d3dbc/mojoshader.py"),
                          str(path)], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr[-2000:]
    got = json.loads(run.stdout)
    if got["errors"]:
        assert _names_a_shader_parameter(effect), got["errors"]
        assert set(got["errors"]) == {SHADER_REFERENCE}
        return
    assert got["shader_errors"] == []
    expected = []
    for p in effect.parameters:
        if p.type.struct:
            kind = 0                    # D3DXPT_VOID: a struct's type is its members'
        elif p.type.is_numeric:
            kind = NUMERIC_TYPES[p.type.base]
        else:
            kind = OBJECT_TYPES[(p.type.base, p.type.dim.upper())]
        expected.append([p.name, p.semantic or "", kind, p.array[0] if p.array else 0])
    assert [[n, s, t, e] for n, s, _, t, _, _, e in got["parameters"]] == expected
    assert got["techniques"] == [[t.name or "", [p.name or "" for p in t.passes]]
                                 for t in effect.techniques]


def test_mojoshader_reads_fxc_own_binary_as_we_do():
    # the binding itself checked on fxc's output (tests/data/fxo): 42 parameters, class and
    # type as fxc wrote them (MATRIX_ROWS = 2 for every matrix)
    path = ROOT / "tests/data/fxo/wine/test_effect_parameter_value_blob_float.fxo"
    run = subprocess.run([sys.executable, str(ROOT / "tests/shaders/d3dbc/mojoshader.py"),
                          str(path)], capture_output=True, text=True, timeout=120)
    got = json.loads(run.stdout)
    assert got["errors"] == [] and len(got["parameters"]) == 42
    ours = effects.load_effect(str(path))
    assert [p[0] for p in got["parameters"]] == [p.name for p in ours.parameters]
    by = {p[0]: p for p in got["parameters"]}
    assert by["f"][2:] == [0, 3, 1, 1, 0] and by["f4"][2:] == [1, 3, 1, 4, 0]
    # float2x3: fxc wrote rows 2 then columns 3 (Wine reads Rows 2, Columns 3, its test's
    # D3DXPARAMETER_DESC); MojoShader reads a matrix's two words the other way round
    assert by["f23"][2:] == [2, 3, 3, 2, 0] and by["f44_2"][2:] == [2, 3, 4, 4, 2]
    assert got["techniques"] == [["t", ["p"]]]


def _mojoshader(path):
    run = subprocess.run([sys.executable, str(ROOT / "tests/shaders/d3dbc/mojoshader.py"),
                          str(path)], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr[-2000:]
    return json.loads(run.stdout)


@pytest.mark.parametrize("stem, reference, message", [
    # `VertexShader = vs;`: 3 bytes, short of a version token
    ("effect_code", b"vs", "Expected version token, got none at all."),
    # `VertexShader = vs_arr2[0];`: "vs_a" read as a version token
    ("test_effect_shared_parameters_blob", b"vs_arr2[0]", SHADER_REFERENCE),
])
def test_mojoshader_refuses_fxcs_own_shader_reference_alike(tmp_path, stem, reference, message):
    # fxc's binary of a pass that names a shader parameter holds the resource we write for
    # `VertexShader = <vs>`: technique 0, pass 0, element NONE, state 0 (effect_code; the
    # shared_parameters pass's VertexShader is its state 3), usage 1 (a parameter), the name
    # and its NUL; MojoShader parses it as bytecode and refuses the effect
    import struct
    from tests.paths import TESTS
    fxc = (TESTS / "data/fxo/wine" / f"{stem}.fxo").read_bytes()
    state = 3 if stem.startswith("test_effect_shared") else 0
    record = struct.pack("<6I", 0, 0, 0xFFFFFFFF, state, 1, len(reference) + 1) + reference
    assert record + b"\0" in fxc
    assert _mojoshader(TESTS / "data/fxo/wine" / f"{stem}.fxo")["errors"] == [message]
    # ours, of the same pass, is the same record (padded to 4 bytes as fxc's is)
    shader = "asm { vs_1_1 dcl_position v0 mov oPos, v0 }"
    declared = f"vs_arr2[2] = {{ {shader}, {shader} }}" if b"[" in reference else \
        f"vs = {shader}"
    ours = write_effect_binary(effects.load_effect(
        f"vertexshader {declared};\n"
        f"technique T {{ pass P {{ VertexShader = <{reference.decode()}>; }} }}"))
    ours_record = struct.pack("<6I", 0, 0, 0xFFFFFFFF, 0, 1, len(reference) + 1) + reference
    assert ours_record + b"\0" in ours
    path = tmp_path / "ours.fxo"
    path.write_bytes(ours)
    assert _mojoshader(path)["errors"] == [message]


def test_mojoshader_refuses_fxcs_null_shader_objects_as_ours(tmp_path):
    # `vertexshader vs_arr[2];`: fxc gives each element an empty string entry (Wine's
    # null_shader blob), which MojoShader compiles as bytecode and refuses; we write the same
    from tests.paths import TESTS
    fxc = TESTS / "data/fxo/wine/test_effect_null_shader_blob"
    assert _mojoshader(fxc.with_suffix(".fxo"))["errors"] == [SHADER_REFERENCE]
    path = tmp_path / "ours.fxo"
    path.write_bytes(write_effect_binary(effects.load_effect(fxc.with_suffix(".fx"))))
    assert _mojoshader(path)["errors"] == [SHADER_REFERENCE]
