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
