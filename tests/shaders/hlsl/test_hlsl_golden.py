"""Golden assembly of the bundled HLSL shaders: every `compile` state of fxfiles/*.fx, as the
compiler emits it, in tests/golden/asm/<effect>_<technique>_<pass>_<stage>.asm. A change in the
compiler shows as a diff here; after checking it, regenerate with
`EFFECTS_UPDATE_GOLDEN=1 .venv/bin/python -m pytest tests/shaders/hlsl/test_hlsl_golden.py` and read the
diff before committing. Also `effects compile`, the listing that shows the same code."""
from __future__ import annotations

from tests.paths import ROOT, TESTS

import os

import pytest

import effects
from effects.base.errors import EffectError
from effects.cli.main import main
from effects.model import CompileShader
from effects.shaders.asm import check
from effects.shaders.hlsl import compile_state

GOLDEN_DIR = TESTS / "golden" / "asm"
UPDATE_GOLDEN = os.environ.get("EFFECTS_UPDATE_GOLDEN") == "1"


def compiled_states():
    for path in sorted((ROOT / "fxfiles").glob("*.fx")):
        effect = effects.load_effect(str(path))
        for technique in effect.techniques:
            for i, p in enumerate(technique.passes):
                for state in p.states:
                    if isinstance(state.value, CompileShader):
                        name = f"{path.stem}_{technique.name}_{p.name or i}_{state.name}.asm"
                        yield pytest.param(effect, state.value, name, id=name)


@pytest.mark.parametrize("effect, value, name", list(compiled_states()))
def test_golden_assembly(effect, value, name):
    shader = compile_state(effect, value)
    assert check(shader.program) == []      # the version's own rules hold
    golden = GOLDEN_DIR / name
    if UPDATE_GOLDEN:
        GOLDEN_DIR.mkdir(parents=True, exist_ok=True)
        golden.write_text(shader.text)
    assert golden.exists(), f"{golden} missing: run with EFFECTS_UPDATE_GOLDEN=1"
    assert shader.text == golden.read_text()


def test_the_bundled_hlsl_has_golden_files():
    assert {p.id for p in compiled_states()} >= {
        "wood_Wood_ps20_p0_VertexShader.asm", "wood_Wood_ps20_p0_PixelShader.asm",
        "sdk9_style_Marble_ps20_Marble_VertexShader.asm",
        "sdk9_style_Marble_ps20_Outline_VertexShader.asm"}


def test_compile_lists_the_assembly_with_source_lines_registers_and_counts(capsys):
    code = main(["compile", str(ROOT / "fxfiles" / "wood.fx"), "--pass", "0"])
    out = capsys.readouterr().out
    assert code == 0
    assert "// Wood compiled for ps_2_0" in out
    assert "//   WorldViewProjection      c0       4" in out
    assert "wood.fx:136: r  = frac(r);" in out
    assert "frc r" in out.split("wood.fx:136:")[1].split("//")[0]
    assert "2 texture (of 32)" in out and "arithmetic (of 64)" in out


def test_compile_entry_and_target(capsys):
    code = main(["compile", str(ROOT / "fxfiles" / "wood.fx"), "--entry", "WoodVS", "--target", "vs_2_0"])
    out = capsys.readouterr().out
    assert code == 0 and "vs_2_0" in out and "dp4 oPos.x, v0, c0" in out
    code = main(["compile", str(ROOT / "fxfiles" / "wood.fx"), "--entry", "Nope", "--target", "ps_2_0"])
    assert code == 2
    assert "error: X3501: 'Nope': entrypoint not found" in capsys.readouterr().err
