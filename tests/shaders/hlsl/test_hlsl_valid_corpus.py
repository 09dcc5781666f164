"""Every program of the valid corpus (valid_corpus.py: programs fxc compiled, each with the
colours it draws worked out by hand) compiles, validates and draws its values on both back
ends (issue 30's measure for valid programs)."""
from __future__ import annotations

import pytest

from tests.shaders.hlsl.test_hlsl_render import backend  # noqa: F401
from tests.shaders.hlsl.valid_corpus import Row, all_rows, expected, outcome

ROWS = all_rows()


@pytest.mark.parametrize("row", [pytest.param(r, marks=pytest.mark.xfail(reason=r.known, strict=True))
                                 if r.known else r for r in ROWS], ids=[r.name for r in ROWS])
def test_a_valid_program_draws_its_values(backend, row):
    assert outcome(row, backend) == "ok"


def test_the_corpus_is_of_size_and_spread():
    assert len(ROWS) >= 280
    assert len({r.name for r in ROWS}) == len(ROWS)
    targets = {r.target for r in ROWS} | {r.vs for r in ROWS if r.vs}
    assert targets >= {"ps_2_0", "ps_3_0", "vs_1_1", "vs_2_0", "vs_3_0"}
    # every intrinsic of the DirectX 9 table but noise (texture fill only) has a row
    from effects.shaders.hlsl.intrinsics import INTRINSICS
    text = "\n".join(r.text for r in ROWS)
    missing = [name for name in INTRINSICS if f"{name}(" not in text]
    assert missing == []


def test_outcome_fails_a_row_whose_values_are_wrong(backend):
    # the check can fail: the same program with a colour off by a quarter is not "ok"
    row = next(r for r in ROWS if r.name == "lit")
    wrong = row._replace(want=lambda u, v: tuple(c + 0.25 for c in row.want(u, v)))
    assert outcome(wrong, backend).startswith("wrong:")
    assert expected(wrong, 1, 2)[0] == pytest.approx(0.75)


def test_outcome_reports_a_refusal_and_a_missing_warning(backend):
    refused = Row("x", "float4 PS() : COLOR { return undeclared; }\n", lambda u, v: (0, 0, 0, 0))
    assert outcome(refused, backend).startswith("refused: X3004")
    quiet = Row("y", "float4 PS() : COLOR { return 0.5; }\n", lambda u, v: (0.5,) * 4,
                warns=("X3206",))
    assert outcome(quiet, backend).startswith("warning ['X3206'] not given")


def test_global_struct_forms_print_and_read_back():
    # `struct S { ... } a, b;` and C's `typedef struct [S] { ... } T;`: each struct is a
    # declaration of its own in the printed effect, which reads back the same
    import effects
    fx = effects.load_effect("struct GS { float a; float b; } G = { 0.25, 0.5 }, H;\n"
                             "typedef struct { float a; } Pair;\n"
                             "typedef struct Named { float2 q; } Alias;\n")
    assert [s.name for s in fx.structs] == ["GS", "Pair", "Named", "Alias"]
    assert [(p.name, p.type.base) for p in fx.parameters] == [("G", "GS"), ("H", "GS")]
    again = effects.load_effect(fx.to_source())
    assert [s.name for s in again.structs] == ["GS", "Pair", "Named", "Alias"]
    assert [p.name for p in again.parameters] == ["G", "H"]
