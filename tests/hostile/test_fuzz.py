"""Mutated effect files: whatever the damage, `load_effect` returns an effect or raises a
located `EffectError`, never another exception, and never takes long.

Mutations are deterministic (fixed seeds): delete, duplicate or swap tokens, delete or insert
bytes, truncate, insert junk. Each case loads the mutated text from a string.
"""
from __future__ import annotations

from tests.paths import ROOT

import random
import re
import time

import pytest

from effects import EffectError, load_effect

FXFILES = ROOT / "fxfiles"
SOURCES = {p.name: p.read_text(encoding="latin-1") for p in sorted(FXFILES.glob("*.fx"))}
TOKEN_RE = re.compile(r'\s+|[A-Za-z_]\w*|\d+(?:\.\d*)?[fF]?|"[^"\n]*"|//[^\n]*|.', re.S)
JUNK = ["{", "}", "(", ")", "<", ">", ";", "=", "asm {", "decl {", "technique", "pass",
        "sampler_state", "compile", "#", "@", "\x00", "\"", "/*", "*/", "//", "0x", "1e999",
        "9" * 50, "[", "]", "|", "-", "struct", "NULL", "\\", "\n", "\u00e9", "[99999]"]

MUTATIONS = ("delete_token", "duplicate_token", "swap_tokens", "delete_bytes", "insert_bytes",
             "truncate", "insert_junk")


def mutate(text: str, kind: str, rng: random.Random) -> str:
    if kind in ("delete_token", "duplicate_token", "swap_tokens"):
        tokens = TOKEN_RE.findall(text)
        for _ in range(rng.randint(1, 3)):
            i, j = rng.randrange(len(tokens)), rng.randrange(len(tokens))
            if kind == "delete_token":
                tokens[i] = ""
            elif kind == "duplicate_token":
                tokens[i] = tokens[i] + " " + tokens[i]
            else:
                tokens[i], tokens[j] = tokens[j], tokens[i]
        return "".join(tokens)
    if kind == "delete_bytes":
        i = rng.randrange(len(text))
        return text[:i] + text[i + rng.randint(1, 40):]
    if kind == "insert_bytes":
        i = rng.randrange(len(text))
        junk = "".join(chr(rng.randrange(0, 256)) for _ in range(rng.randint(1, 8)))
        return text[:i] + junk + text[i:]
    if kind == "truncate":
        return text[:rng.randrange(len(text))]
    i = rng.randrange(len(text))
    return text[:i] + rng.choice(JUNK) + text[i:]


CASES = [(name, kind, seed) for name in SOURCES for kind in MUTATIONS for seed in range(8)]


def test_enough_cases():
    assert len(SOURCES) >= 4 and len(CASES) >= 200


@pytest.mark.parametrize("name, kind, seed", CASES, ids=[f"{n}-{k}-{s}" for n, k, s in CASES])
def test_mutated_effect_loads_or_reports_a_located_error(name, kind, seed):
    rng = random.Random(f"{name}/{kind}/{seed}")
    text = mutate(SOURCES[name], kind, rng)
    start = time.process_time()
    try:
        effect = load_effect(text + "\n")
    except EffectError as err:
        assert err.line >= 1 and err.column >= 1, str(err)
        assert str(err).startswith(f"{err.path}:{err.line}:{err.column}: error: ")
        err.report()  # formats without raising
    else:
        effect.to_source()  # whatever parsed can be printed
    assert time.process_time() - start < 5.0   # the untrusted-input bound (issue 14)
