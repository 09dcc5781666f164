"""bench_hlsl.py judges the 150-line ps_2_0 goal on benchmarks/data/lighting_ps20.fx's
`LightingPS`: this holds it to what the README says of it -- 150 lines of which at most a
quarter are comments or blank, a program ps_2_0 can hold (<= 64 arithmetic slots, <= 12
temporaries), compiled without a warning, and run by a ps_2_0 card."""
from __future__ import annotations

from tests.paths import ROOT

import re

import effects
from effects.model import CompileShader
from effects.shaders.hlsl import compile_state

FILE = ROOT / "benchmarks" / "data" / "lighting_ps20.fx"


def _function_lines() -> list[str]:
    lines = FILE.read_text().split("\n")
    first = next(k for k, line in enumerate(lines) if line.startswith("float4 LightingPS("))
    last = next(k for k in range(first, len(lines)) if lines[k] == "}")
    return lines[first:last + 1]


def test_the_function_is_150_lines_and_at_most_a_quarter_comments_or_blank():
    lines = _function_lines()
    assert len(lines) == 150
    quiet = [line for line in lines if re.fullmatch(r"\s*(//.*)?", line)]
    assert len(quiet) <= len(lines) // 4, len(quiet)


def test_it_compiles_for_ps_2_0_within_the_limits_without_warnings():
    fx = effects.load_effect(str(FILE))
    value = next(s.value for s in fx.techniques[0].passes[0].states
                 if isinstance(s.value, CompileShader))
    shader = compile_state(fx, value)
    stats = shader.program.stats
    assert shader.warnings == []
    assert stats.arithmetic_slots <= 64 and stats.texture_slots <= 32
    assert stats.temps_used <= 12
    assert fx.validate(fx.techniques[0], effects.load_profile("radeon9700")).ok
    assert not fx.validate(fx.techniques[0], effects.load_profile("geforce4ti")).ok
