"""fxc's fx_2_0 effect binaries from Wine's d3dx9_36 tests (tests/data/fxo/MANIFEST.md), read by
`effects.load_effect`: each loads with its parameters, annotations, default values, techniques
and passes, and where Wine kept the HLSL it was compiled from, binary and source agree on all of
those and on the verdict (valid or not) of every technique on every card, as `effects matrix`
would print it.

Where a check here fails, the difference is a finding to judge, not a typo: the binary holds
fxc's decisions (its compiled shaders, its folded defaults), the source ours.
"""
from __future__ import annotations

import re

import numpy as np
import pytest

import effects
from effects.model import (Annotation, CompileShader, Expression, NullValue, Parameter, SamplerState,
                           ShaderBlock)
from tests.paths import TESTS

DATA = TESTS / "data" / "fxo" / "wine"
BINARIES = sorted(DATA.glob("*.fxo"))
# Sources Wine kept that our HLSL front end refuses today (first error, as of this writing):
# fxc compiled them, so each is a front-end gap to close; once closed, drop it from here.
SOURCE_REFUSED: dict[str, str] = {}

# Binaries the reader refuses today, each with a located error naming what it cannot read yet
# (none of Wine's 15 since FXLC preshaders, array selectors, struct annotations, a null shader
# written as a number, vs_3_sw and a 9x1 state value are read). A gap found: add it here.
BINARY_REFUSED: dict[str, str] = {
}

# Pairs where the binary's verdict is D3DX's (its preshaders run as D3DX ran them) and our
# evaluation of the source's expressions differs (first reason, as of this writing): each is a
# gap of the source path to close; once closed, drop it from here.
SOURCE_VERDICT_GAPS = {
    # D3DX's preshader log is log2|x| with log 0 = 0, and atan2(0, 0) is 0; the HLSL
    # evaluator gives -inf and NaN, which a state refuses (X3013)
    "test_effect_preshader_ops_blob": "does not evaluate to finite numbers",
    # `FogDensity = arr2[0]` and `ts2[0].fv_2` of a shared struct array: the host evaluation
    # does not find the struct type
    "test_effect_shared_parameters_blob": "unknown struct 'test_struct'",
}

# the binaries whose source we load: compared part by part
COMPARED = [b for b in BINARIES if b.with_suffix(".fx").exists() and b.stem not in SOURCE_REFUSED
            and b.stem not in BINARY_REFUSED]


def _source(binary):
    fx = binary.with_suffix(".fx")
    return fx if fx.exists() else None


@pytest.fixture(scope="module", params=COMPARED, ids=[b.stem for b in COMPARED])
def pair(request):
    """(name, the binary's Effect, the source's Effect)."""
    binary = request.param
    return binary.stem, effects.load_effect(binary), effects.load_effect(binary.with_suffix(".fx"))


def test_the_list_of_refused_sources_is_current():
    for stem, reason in SOURCE_REFUSED.items():
        with pytest.raises(effects.EffectError, match=re.escape(reason)):
            effects.load_effect(DATA / f"{stem}.fx")


@pytest.mark.parametrize("binary", BINARIES, ids=[b.stem for b in BINARIES])
def test_each_binary_loads_with_the_techniques_and_passes_its_source_names(binary):
    if binary.stem in BINARY_REFUSED:
        with pytest.raises(effects.EffectError, match=re.escape(BINARY_REFUSED[binary.stem])) as err:
            effects.load_effect(binary)
        assert err.value.line == 1 and err.value.column > 1    # at the byte offset
        return
    fxo = effects.load_effect(binary)
    assert fxo.techniques, binary.stem
    fx = _source(binary)
    if fx is not None:       # even a source we refuse names its techniques and passes
        text = re.sub(r"//[^\n]*|/\*.*?\*/", "", fx.read_text(), flags=re.S)
        assert [t.name for t in fxo.techniques] == re.findall(r"\btechnique\s+(\w+)", text)
        assert [p.name for t in fxo.techniques for p in t.passes] == \
            re.findall(r"\bpass\s+(\w+)", text)


def _value(value):
    """A default value as the two front ends can agree on it: numbers as a flat float array
    (an uninitialised number is zeros in a binary), objects by kind."""
    if isinstance(value, (CompileShader, ShaderBlock)):
        return "shader"
    if isinstance(value, SamplerState):
        return ("sampler", tuple((s.name, s.index) for s in value.states))
    if isinstance(value, NullValue):
        return "null"
    if isinstance(value, Expression):
        # a struct's initialiser, kept as text by both ({4} in the source, { { 4.0 } } in the
        # binary): its numbers in order
        return [float(x) for x in re.findall(r"[-+]?\d+\.?\d*(?:[eE][-+]?\d+)?", value.text)]
    if isinstance(value, (list, tuple)) and value and not isinstance(value[0], (int, float)):
        return [_value(v) for v in value]
    if isinstance(value, str) or value is None:
        return value
    return np.asarray(value, dtype=float).ravel().round(6).tolist()


def _annotations(annotations: list[Annotation]) -> list:
    return [(a.name, "struct" if a.type.struct else a.type.base, _value(a.value))
            for a in annotations]


def _parameter(p: Parameter, with_value: bool = True) -> tuple:
    """What a binary and its source must agree on; `with_value` False where the source's
    default is an expression (a struct initialiser) that only the binary holds folded."""
    # a `register(c4)` binding lives in the shaders' constant tables, not in the parameter
    # table of an fx_2_0 binary
    semantic = None if p.semantic and p.semantic.startswith("register(") else p.semantic
    # a binary names a struct's type for its variable (the typedef names variables only)
    base = "struct" if p.type.struct else p.type.base
    if not with_value:
        return (p.name, base, p.type.rows, p.type.cols, p.array, semantic,
                _annotations(p.annotations))
    value = _value(p.value)
    if value is None and p.type.base == "string":
        value = ""           # an uninitialised string is the empty string in a binary
    if value is None and p.type.base in ("vertexshader", "pixelshader"):
        value = ["null"] * int(np.prod(p.array)) if p.array else "null"   # NULL, as D3DX has it
    if p.type.struct and isinstance(value, list) and not any(value):
        value = None         # an uninitialised struct is its zeros in a binary
    if value is None and p.type.base in ("float", "int", "bool", "half", "double"):
        value = [0.0] * (p.type.rows * p.type.cols * int(np.prod(p.array or (1,))))
    return (p.name, base, p.type.rows, p.type.cols, p.array, semantic,
            _annotations(p.annotations), value)


def test_binary_and_source_hold_the_same_parameters(pair):
    stem, fxo, fx = pair
    assert [p.name for p in fxo.parameters] == [p.name for p in fx.parameters]
    for ours, theirs in zip(fx.parameters, fxo.parameters):
        folded = not isinstance(ours.value, Expression)
        assert _parameter(theirs, folded) == _parameter(ours, folded), (stem, ours.name)


def test_binary_and_source_hold_the_same_techniques_passes_and_states(pair):
    stem, fxo, fx = pair

    def shape(effect):
        return [(t.name, _annotations(t.annotations),
                 [(p.name, _annotations(p.annotations),
                   [(a.name.lower(), a.index) for a in p.states]) for p in t.passes])
                for t in effect.techniques]
    assert shape(fxo) == shape(fx)


def test_binary_and_source_get_the_same_verdict_on_every_card(pair):
    stem, fxo, fx = pair
    for card in effects.list_profiles():
        profile = effects.load_profile(card)
        for t in fx.techniques:
            binary, source = fxo.validate(t.name, profile), fx.validate(t.name, profile)
            ok = source.ok
            if stem in SOURCE_VERDICT_GAPS:     # the source refused for the gap, and else alike
                gap = [r for r in source.reasons if SOURCE_VERDICT_GAPS[stem] in str(r)]
                assert gap, (stem, t.name, card)
                ok = len(gap) == len(source.reasons)
            assert binary.ok == ok, (stem, t.name, card)
