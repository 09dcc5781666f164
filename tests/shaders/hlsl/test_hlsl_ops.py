"""The DAG's op table (effects/shaders/hlsl/ops.py): one row per op, read by dag.py and
codegen.py; every row's instruction exists in the assembler's table, every op the compiler
builds has a row."""
from __future__ import annotations

import re

from tests.paths import ROOT

from effects.shaders.asm import INSTRUCTIONS
from effects.shaders.hlsl import dag
from effects.shaders.hlsl.folding import FOLDS
from effects.shaders.hlsl.ops import LANEWISE, OPAQUE, OPS, REDUCE, SCALAR, TEXTURE, shaped


def test_every_emitted_op_names_an_instruction_of_the_assembler():
    names = {row.name for row in INSTRUCTIONS}
    for row in OPS.values():
        if row.mnemonic is not None:
            assert row.mnemonic in names, row


def test_the_shapes_are_the_ones_the_code_generator_dispatched_on():
    assert LANEWISE == {"add", "mul", "mad", "min", "max", "frc", "abs", "cmp", "cnd", "lrp",
                        "slt", "sge", "mov", "sat", "dsx", "dsy"}
    assert SCALAR == {"rcp", "rsq", "exp", "log", "pow"}
    assert REDUCE == {"dp3": 3, "dp4": 4, "dp2add": 2}
    assert TEXTURE == {"tex": "texld", "texldp": "texldp", "texldb": "texldb",
                       "texldl": "texldl", "texldd": "texldd"}
    assert OPS["sat"].mnemonic == "mov"


def test_what_folds_is_what_the_fold_kernels_compute():
    assert dag.OPAQUE is OPAQUE
    for name, row in OPS.items():
        assert row.folds == (name in FOLDS and not row.opaque)
        assert dag.can_fold(name) == row.folds
        if shaped(name):
            assert FOLDS[name][1] is not None          # argument and result widths


def test_every_op_the_compiler_builds_has_a_row():
    # the op names passed to Graph.op / Graph.leaf / the arithmetic helpers, by their text
    built: set[str] = set()
    for path in (ROOT / "effects" / "shaders" / "hlsl").glob("*.py"):
        text = path.read_text()
        built |= set(re.findall(r'\.(?:op|leaf|lanes|scalar_lanes)\(\s*"([a-z_0-9]+)"', text))
    assert built and built <= set(OPS), built - set(OPS)


def test_what_ps_1_x_lacks_is_a_column_of_the_table():
    from effects.shaders.hlsl.ops import PS1_LACKS, PS1_LANEWISE
    # ps_1_x's component-wise instructions: the lanes rows it has (cnd and sat as mov_sat too)
    assert PS1_LANEWISE == {"add", "mul", "mad", "cmp", "cnd", "lrp", "mov", "sat"}
    assert set(PS1_LACKS) <= set(OPS) and PS1_LACKS["frc"] == "frac/floor/fmod (frc)"
    assert not {"add", "mul", "mad", "dp3", "dp4", "tex"} & set(PS1_LACKS)


def test_the_ps_1_x_refusal_names_the_row():
    import pytest

    import effects
    from effects.base.errors import EffectError
    from effects.shaders.hlsl import compile_shader
    fx = effects.load_effect("float4 PS(float4 c : COLOR0) : COLOR { return frac(c); }\n"
                             "technique T { pass P { } }\n")
    with pytest.raises(EffectError, match=re.escape(OPS["frc"].ps1_lacks)):
        compile_shader(fx, "PS", "ps_1_1")
