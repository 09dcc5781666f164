"""fx_2_0 binaries fxc wrote for others (tests/data/fxo/MANIFEST.md): each reads with
the parameters, types and defaults its source declares; source and binary give the same matrix
and pixels on both back ends; and our writer, given the source, writes fxc's bytes."""
from __future__ import annotations

import hashlib
import re

import numpy as np
import pytest

import effects
from effects.d3d9.caps import list_profiles, load_profile
from effects.frontend.fxo import PC_MATRIX_ROWS
from effects.shaders.fxo import write_effect_binary
from tests.paths import ROOT

DATA = ROOT / "tests" / "data" / "fxo" / "wine"   # from Debian's wine 8.0 (tests/data/fxo/MANIFEST.md)
# the blob whose source our writer reproduces byte for byte (parameters and an empty pass);
# every blob's load and verdicts: tests/shaders/fxo/test_fxo_wine.py; sha256s:
# tests/formats/test_fxo_wine_files.py
PAIRS = ["test_effect_parameter_value_blob_float"]


@pytest.mark.parametrize("stem", PAIRS)
def test_fxc_binary_reads_as_its_source_declares(stem):
    binary = effects.load_effect(str(DATA / f"{stem}.fxo"))
    source = effects.load_effect(str(DATA / f"{stem}.fx"))
    assert [p.name for p in binary.parameters] == [p.name for p in source.parameters]
    for b, s in zip(binary.parameters, source.parameters):
        assert (b.type.base, b.type.rows, b.type.cols, b.array) == \
            (s.type.base, s.type.rows, s.type.cols, s.array), s.name
        assert np.asarray(b.value).shape == np.asarray(s.value).shape, s.name
        assert np.array_equal(np.asarray(b.value, np.float32), np.asarray(s.value, np.float32)), s.name
    assert [(t.name, [p.name for p in t.passes]) for t in binary.techniques] == \
        [(t.name, [p.name for p in t.passes]) for t in source.techniques]


def test_hand_checked_values_of_wine_blob():
    e = effects.load_effect(str(DATA / "test_effect_parameter_value_blob_float.fxo"))
    by = {p.name: p for p in e.parameters}
    assert by["f"].value == np.float32(0.1)
    assert by["f21"].value.tolist() == [[np.float32(21.11)], [np.float32(21.21)]]
    assert by["f4_2"].value[1].tolist() == np.float32([4.102, 4.202, 4.302, 4.402]).tolist()
    assert by["f44_2"].value.shape == (2, 4, 4)
    assert by["f44_2"].value[1, 3, 2] == np.float32(44.3402)


@pytest.mark.parametrize("stem", PAIRS)
def test_our_writer_writes_fxc_bytes(stem):
    data = (DATA / f"{stem}.fxo").read_bytes()
    assert write_effect_binary(effects.load_effect(str(DATA / f"{stem}.fx"))) == data
    # fxc writes every matrix as MATRIX_ROWS: f11's typedef (the 6th parameter) says so
    start = 8 + int.from_bytes(data[4:8], "little")
    typedef = 8 + int.from_bytes(data[start + 16 + 5 * 16:start + 16 + 5 * 16 + 4], "little")
    assert int.from_bytes(data[typedef + 4:typedef + 8], "little") == PC_MATRIX_ROWS


@pytest.mark.parametrize("backend", ["numpy", "gl"])
@pytest.mark.parametrize("stem", PAIRS)
def test_source_and_binary_give_the_same_matrix_and_pixels(stem, backend):
    binary = effects.load_effect(str(DATA / f"{stem}.fxo"))
    source = effects.load_effect(str(DATA / f"{stem}.fx"))
    for card in list_profiles():
        profile = load_profile(card)
        assert [source.validate(t, profile).ok for t in source.techniques] == \
            [binary.validate(t, profile).ok for t in binary.techniques], card
    a = effects.render(source, "geforce2", backend=backend, size=(32, 32))
    b = effects.render(binary, "geforce2", backend=backend, size=(32, 32))
    assert np.array_equal(a, b)
