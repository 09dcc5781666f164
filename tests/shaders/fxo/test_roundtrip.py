"""Every bundled effect written as an fx_2_0 binary and read back: the same verdicts on every
card (the `matrix`), the same technique chosen, and the same pixels on both back ends.

The binaries are written beside copies of the bundled files, so their textures and meshes
resolve as the sources' do."""
from __future__ import annotations

import shutil

import numpy as np
import pytest

import effects
from effects.d3d9.caps import list_profiles, load_profile
from effects.frontend.fxo import is_effect_binary
from effects.model import BytecodeShader, CompileShader, ShaderBlock
from effects.shaders.fxo import write_effect_binary
from tests.paths import ROOT

FXFILES = sorted(p.name for p in (ROOT / "fxfiles").glob("*.fx"))
CARDS = ("geforce2", "radeon8500", "modern")   # fixed function, ps_1_4, ps_3_0


@pytest.fixture(scope="module")
def pairs(tmp_path_factory):
    """{file name: (source effect, binary effect, binary path)} for every bundled effect."""
    folder = tmp_path_factory.mktemp("fxo") / "fxfiles"
    shutil.copytree(ROOT / "fxfiles", folder)
    out = {}
    for name in FXFILES:
        source = effects.load_effect(str(folder / name))
        path = folder / (name + "o")
        path.write_bytes(write_effect_binary(source))
        out[name] = (source, effects.load_effect(str(path)), path)
    return out


def _bits(value):
    """A value as D3DX holds it: 32-bit words (D3DX has no DWORD type: a DWORD parameter is an
    INT, so 0xff0000ff reads back as the int -16776961, the same bits)."""
    if value.dtype.kind == "f":
        return value.astype(np.float32).view(np.uint32)
    return value.astype(np.int64) & 0xFFFFFFFF


def _shaders(effect):
    for t in effect.techniques:
        for p in t.passes:
            for s in p.states:
                if isinstance(s.value, (ShaderBlock, CompileShader)):
                    yield s.value


@pytest.mark.parametrize("name", FXFILES)
def test_the_binary_holds_what_the_source_says(pairs, name):
    source, binary, path = pairs[name]
    assert is_effect_binary(path.read_bytes()[:4])
    assert [p.name for p in binary.parameters] == [p.name for p in source.parameters]
    assert [(t.name, [p.name for p in t.passes]) for t in binary.techniques] == \
        [(t.name, [p.name for p in t.passes]) for t in source.techniques]
    for a, b in zip(source.parameters, binary.parameters):
        assert (a.semantic, a.array) == (b.semantic, b.array), a.name
        assert [x.name for x in a.annotations] == [y.name for y in b.annotations], a.name
        for x, y in zip(a.annotations, b.annotations):
            assert (_bits(x.value) == _bits(y.value)).all() if isinstance(x.value, np.ndarray) \
                else x.value == y.value, (a.name, x.name)
        if isinstance(a.value, np.ndarray):
            assert np.array_equal(_bits(a.value), _bits(b.value)), a.name
    # every shader is bytecode now, as many as the source has
    assert all(isinstance(v, BytecodeShader) for v in _shaders(binary))
    assert len(list(_shaders(binary))) == len(list(_shaders(source)))


@pytest.mark.parametrize("name", FXFILES)
def test_the_binary_gives_the_same_matrix(pairs, name):
    source, binary, _ = pairs[name]
    for card in list_profiles():
        profile = load_profile(card)
        for ts, tb in zip(source.techniques, binary.techniques):
            vs, vb = source.validate(ts, profile), binary.validate(tb, profile)
            assert vs.ok == vb.ok, (card, ts.name)
            assert [(r.subject, r.requirement, r.card_value) for p in vs.pass_reports
                    for r in p.reasons] == \
                [(r.subject, r.requirement, r.card_value) for p in vb.pass_reports
                 for r in p.reasons], (card, ts.name)
        chosen = source.find_valid_technique(profile), binary.find_valid_technique(profile)
        assert [t.name if t else None for t in chosen] == [chosen[0].name if chosen[0] else None] * 2


@pytest.mark.parametrize("backend", ["numpy", "gl"])
@pytest.mark.parametrize("name", FXFILES)
def test_the_binary_draws_the_same_pixels(pairs, name, backend):
    source, binary, _ = pairs[name]
    drawn = 0
    for card in CARDS:
        for t in source.techniques:
            try:
                a = effects.render(source, card, backend=backend, technique=t.name, size=(48, 48))
            except effects.EffectError as err:   # not valid on this card: the same refusal
                with pytest.raises(effects.EffectError) as got:
                    effects.render(binary, card, backend=backend, technique=t.name, size=(48, 48))
                assert got.value.message == err.message
                continue
            b = effects.render(binary, card, backend=backend, technique=t.name, size=(48, 48))
            assert np.array_equal(a, b), (card, t.name)
            drawn += 1
    assert drawn > 0
