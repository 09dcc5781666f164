"""Every program of the invalid corpus (invalid_corpus.py) is refused with fxc's code, and a
language error is one for every target (issue 30's measure: programs fxc refused)."""
from __future__ import annotations

import pytest

from effects.shaders.hlsl.parse import LANGUAGE_CODES
from tests.shaders.hlsl.invalid_corpus import CORPUS, refusal


@pytest.mark.parametrize("row", CORPUS, ids=[r.name for r in CORPUS])
def test_an_invalid_program_is_refused_with_fxc_code(row):
    assert refusal(row) == row.code


def test_the_corpus_is_of_size_and_spread():
    assert len(CORPUS) >= 60
    codes = {r.code for r in CORPUS}
    assert len(codes) >= 25
    # only the semantics and register rows are refusals for the target (X3507, a language
    # error here, shares its code with a target's refusal: the raise marks it)
    assert {r.code for r in CORPUS if r.code not in LANGUAGE_CODES} == {
        "X3507", "X4502", "X4503", "X4507", "X4509"}
