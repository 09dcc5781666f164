"""Mutated fx_2_0 effect binaries (the round trip's .fxo files of the bundled effects):
whatever the damage, reading one, validating its techniques and listing it gives an effect or
a located `EffectError` (line 1, the byte offset as the column), never another exception.

Mutations are deterministic (fixed seeds): flip bytes, overwrite a 32-bit field with a value
that breaks offsets and counts, truncate, delete, duplicate or insert bytes."""
from __future__ import annotations

import random
import struct

import pytest

from effects import EffectError, load_effect
from effects.d3d9.caps import load_profile
from effects.frontend.fxo import read_effect_binary
from effects.shaders.fxo import listing, write_effect_binary
from tests.paths import ROOT

NAMES = sorted(p.name for p in (ROOT / "fxfiles").glob("*.fx"))
MUTATIONS = ("flip", "field", "truncate", "delete", "duplicate", "insert")
FIELDS = (0, 1, 2, 3, 0xFF, 0x7FFFFFFF, 0x80000000, 0xFFFFFFFE, 0xFFFFFFFF, 0x10000)
CASES = [(name, kind, seed) for name in NAMES for kind in MUTATIONS for seed in range(8)]
CARDS = ("geforce3", "modern")


@pytest.fixture(scope="module")
def binaries():
    return {name: write_effect_binary(load_effect(str(ROOT / "fxfiles" / name)))
            for name in NAMES}


def mutate(data: bytes, kind: str, rng: random.Random) -> bytes:
    b = bytearray(data)
    if kind == "flip":
        for _ in range(rng.randint(1, 4)):
            b[rng.randrange(len(b))] ^= 1 << rng.randrange(8)
    elif kind == "field":        # a u32 on a 4-byte boundary: offsets, counts, ids, sizes
        for _ in range(rng.randint(1, 2)):
            at = 4 * rng.randrange(len(b) // 4)
            struct.pack_into("<I", b, at, rng.choice(FIELDS))
    elif kind == "truncate":
        del b[rng.randrange(4, len(b)):]
    elif kind == "delete":
        at = rng.randrange(len(b))
        del b[at:at + 4 * rng.randint(1, 8)]
    elif kind == "duplicate":
        at = rng.randrange(len(b))
        b[at:at] = b[at:at + 4 * rng.randint(1, 8)]
    else:
        at = rng.randrange(len(b))
        b[at:at] = bytes(rng.randrange(256) for _ in range(rng.randint(1, 12)))
    return bytes(b)


def test_enough_cases():
    assert len(NAMES) >= 10 and len(CASES) >= 500


@pytest.mark.parametrize("name,kind,seed", CASES)
def test_a_mutated_binary_is_read_or_refused_with_a_location(binaries, name, kind, seed):
    data = mutate(binaries[name], kind, random.Random(f"{name}-{kind}-{seed}"))
    path = f"/fuzz/{name}o"
    try:
        effect = read_effect_binary(data, path)
        for card in CARDS:
            profile = load_profile(card)
            for technique in effect.techniques:
                effect_validate(effect, technique, profile)
        listing(effect)
    except EffectError as err:
        assert err.location.path == path and err.location.line == 1, err
        assert 1 <= err.location.column <= len(data) + 1, err


def effect_validate(effect, technique, profile):
    from effects.validate.technique import validate_technique
    return validate_technique(effect, technique, profile)


# Wine's fxc-written blobs with preshaders (FXLC): mutations confined to the bytes from the
# first preshader on, so they land in constant tables, literals and instructions
FXLC_BLOBS = ("test_effect_preshader_effect_blob", "test_effect_preshader_ops_blob",
              "test_effect_shared_parameters_blob", "test_effect_skip_constants_blob")
FXLC_CASES = [(name, kind, seed) for name in FXLC_BLOBS for kind in ("flip", "field")
              for seed in range(12)]


@pytest.mark.parametrize("name,kind,seed", FXLC_CASES)
def test_a_mutated_preshader_is_run_or_refused_with_a_location(name, kind, seed):
    from effects.model import Preshader
    from effects.shaders.fxlc import check_preshaders
    from effects.shaders.hlsl.preshader import expression_element, expression_value
    data = (ROOT / "tests" / "data" / "fxo" / "wine" / f"{name}.fxo").read_bytes()
    start = data.find(b"FXLC") & ~3
    tail = mutate(data[start:], kind, random.Random(f"{name}-{kind}-{seed}"))
    data = data[:start] + tail
    path = f"/fuzz/{name}.fxo"
    try:
        effect = read_effect_binary(data, path)
        check_preshaders(effect)
        for technique in effect.techniques:
            for p in technique.passes:
                for s in p.states:
                    if isinstance(s.value, Preshader):
                        try:
                            if s.value.selects:
                                expression_element(effect, s.value)
                            else:
                                expression_value(s.name, s.index, s.value, effect)
                        except EffectError as err:     # located at the state
                            assert err.location.path == path, err
            effect_validate(effect, technique, load_profile("modern"))
        listing(effect)
    except EffectError as err:
        assert err.location.path == path and err.location.line == 1, err
        assert 1 <= err.location.column <= len(data) + 1, err
