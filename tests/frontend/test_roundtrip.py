"""Printing and parsing agree: parse(print(effect)) == effect.

Checked on every bundled effect, and as a property over random effect models: parameters of
every kind with values and annotations, techniques, passes, state assignments of known states
with valid values (typed by the states table, as the parser types them) and unknown states.
"""
from __future__ import annotations

from tests.paths import ROOT


import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from effects import load_effect
from effects.base.errors import Location, StateError
from effects.model import (Annotation, CompileShader, Effect, EnumValue, Expression, Function,
                           NullValue, Parameter, ParamRef, Pass, SamplerState, ShaderBlock,
                           StateAssignment, Struct, Technique, TypeSpec, VertexDeclElement)
from effects.frontend.parser import resolve_type
from effects.frontend.printer import print_effect
from effects.d3d9.states import STATES, coerce_state_value, lookup_state

FXFILES = ROOT / "fxfiles"
HERE = Location("<generated>", 1, 1)


def same_effect(a: Effect, b: Effect) -> bool:
    """Model equality without the path (a printed effect is parsed from a string)."""
    return (a.parameters == b.parameters and a.techniques == b.techniques
            and a.functions == b.functions and a.structs == b.structs)


# ---------------------------------------------------------------------------------------------
# The bundled effects


@pytest.mark.parametrize("path", sorted(FXFILES.glob("*.fx")), ids=lambda p: p.name)
def test_bundled_effect_round_trips(path):
    original = load_effect(str(path))
    printed = original.to_source()
    again = load_effect(printed)
    assert same_effect(original, again)
    assert len(again.warnings) == len(original.warnings)
    assert again.to_source() == printed  # printing is stable


def test_printed_source_looks_like_an_effect():
    e = load_effect('float4 c : COLOR < string UIName = "Tint"; > = {1, 0.5, 0, 1};\n'
                    "texture t;\n"
                    "technique T { pass P { ColorArg1[0] = Texture | Complement;\n"
                    "  Texture[0] = <t>; PixelShader = asm { ps.1.1\n mov r0, v0 }; } }\n")
    assert e.to_source() == (
        "float4 c : COLOR <\n"
        '    string UIName = "Tint";\n'
        "> = {1.0, 0.5, 0.0, 1.0};\n"
        "texture t;\n"
        "\n"
        "technique T\n"
        "{\n"
        "    pass P\n"
        "    {\n"
        "        ColorArg1[0] = TEXTURE | COMPLEMENT;\n"
        "        Texture[0] = <t>;\n"
        "        PixelShader = asm { ps.1.1\n mov r0, v0 };\n"
        "    }\n"
        "}\n")


# ---------------------------------------------------------------------------------------------
# Random effect models

float32s = st.floats(width=32, allow_nan=False, allow_infinity=False)
int32s = st.integers(-(2 ** 31), 2 ** 31 - 1)
dwords = st.integers(0, 2 ** 32 - 1)
words = st.text("abcdefghijklmnopqrstuvwxyz ABCXYZ0123456789.,:;!?'\"\\/<>{}()#%-_\t", max_size=20)

NUMERIC_TYPES = ["float", "half", "float2", "float3", "float4", "float4x4", "float3x2", "int",
                 "int3", "bool", "bool2", "DWORD", "dword", "vector", "matrix", "VECTOR",
                 "float1"]
OBJECT_TYPES = ["string", "texture", "Texture2D", "textureCUBE", "sampler", "sampler2D",
                "VertexShader", "PixelShader"]
ANNOTATION_TYPES = ["string", "float", "int", "bool", "float4"]

STATE_ROWS = [s for s in STATES if s.type not in ("sampler",)]
SAMPLER_ROWS = [s for s in STATES if s.kind == "sampler"]


def type_spec(spelling: str) -> TypeSpec:
    spec = resolve_type(spelling)
    assert spec is not None
    return spec


def shape_of(spelling: str) -> tuple[int, ...]:
    from effects.frontend.parser import type_shape
    return type_shape(type_spec(spelling))


@st.composite
def numeric_value(draw, spelling: str, dims: tuple[int, ...] = ()) -> np.ndarray:
    spec = type_spec(spelling)
    shape = dims + shape_of(spelling)
    count = int(np.prod(shape)) if shape else 1
    if spec.base == "bool":
        return np.array(draw(st.lists(st.booleans(), min_size=count, max_size=count)),
                        dtype=bool).reshape(shape)
    if spec.base in ("float", "half"):
        return np.array(draw(st.lists(float32s, min_size=count, max_size=count)),
                        dtype=np.float32).reshape(shape)
    values = draw(st.lists(dwords if spec.base == "dword" else int32s,
                           min_size=count, max_size=count))
    # the parser's rule: int32 when every value fits, else int64
    dtype = np.int32 if all(-(2 ** 31) <= v < 2 ** 31 for v in values) else np.int64
    return np.array(values, dtype=dtype).reshape(shape)


@st.composite
def annotations(draw) -> list[Annotation]:
    out = []
    for i in range(draw(st.integers(0, 3))):
        spelling = draw(st.sampled_from(ANNOTATION_TYPES))
        value = draw(words) if spelling == "string" else draw(numeric_value(spelling))
        out.append(Annotation(type_spec(spelling), f"a{i}", value))
    return out


@st.composite
def shader_block(draw, stage: str) -> ShaderBlock:
    prefix = "vs" if stage == "vertex" else "ps"
    major, minor = draw(st.sampled_from([(1, 1), (1, 4), (2, 0)]))
    sep = draw(st.sampled_from([".", "_"]))
    body = f"\n    {prefix}{sep}{major}{sep}{minor}\n    mov r0, v0 ; a comment\n"
    decl = None
    if stage == "vertex" and draw(st.booleans()):
        decl = tuple(draw(st.lists(st.builds(
            VertexDeclElement, st.integers(0, 1), st.sampled_from(["float", "d3dcolor", "ubyte"]),
            st.integers(0, 15), st.integers(1, 4)), min_size=1, max_size=4)))
        decl = tuple(sorted(decl, key=lambda e: e.stream))
    return ShaderBlock(stage, f"{prefix}_{major}_{minor}", body, decl)


def compile_shader(stage: str):
    prefix = "vs" if stage == "vertex" else "ps"
    return st.builds(CompileShader, st.sampled_from([f"{prefix}_1_1", f"{prefix}_2_0"]),
                     st.sampled_from(["Main", "VS", "Shade"]),
                     st.lists(st.sampled_from(["1", "true", "2.5", "p0"]), max_size=2).map(tuple))


def raw_for(draw, info, names: dict[str, str]):
    """A raw value (what the parser reads) that the states table accepts for `info`."""
    t = info.type

    def refs(kind: str):
        pool = [n for n, k in names.items() if k == kind]
        return pool

    if t == "enum":
        options = sorted(info.enum.values)
        first = draw(st.sampled_from(options))
        if info.enum.flags and draw(st.booleans()):
            return [first, draw(st.sampled_from(options))]
        return [first]
    if t == "bool":
        return draw(st.booleans())
    if t in ("int",):
        return draw(st.integers(0, 2 ** 31 - 1))
    if t in ("dword", "color"):
        return draw(dwords)
    if t == "float":
        if draw(st.integers(0, 9)) == 0:
            return Expression("p0 * 2")
        return draw(st.floats(allow_nan=False, allow_infinity=False, width=32))
    if t in ("float3", "float4", "matrix"):
        n = {"float3": 3, "float4": 4, "matrix": 16}[t]
        return tuple(draw(st.lists(float32s, min_size=n, max_size=n)))
    if t == "constants":
        n = 4 * (info.registers or draw(st.integers(1, 2)))
        if info.name.endswith("B"):
            return tuple(draw(st.lists(st.booleans(), min_size=1, max_size=4)))
        if info.name.endswith("I"):
            return tuple(draw(st.lists(st.integers(-1000, 1000), min_size=n, max_size=n)))
        return tuple(draw(st.lists(float32s, min_size=n, max_size=n)))
    if t == "texture":
        pool = refs("texture")
        if pool and draw(st.booleans()):
            return ParamRef(draw(st.sampled_from(pool)), angle=draw(st.booleans()))
        return NullValue()
    if t in ("vertexshader", "pixelshader"):
        stage = "vertex" if t == "vertexshader" else "pixel"
        choice = draw(st.integers(0, 3))
        pool = refs(t)
        if choice == 0:
            return draw(shader_block(stage))
        if choice == 1:
            return draw(compile_shader(stage))
        if choice == 2 and pool:
            return ParamRef(draw(st.sampled_from(pool)), angle=True)
        return NullValue()
    raise AssertionError(t)


@st.composite
def state_assignment(draw, rows, names: dict[str, str], in_sampler: bool = False):
    if draw(st.integers(0, 12)) == 0 and not in_sampler:  # an unknown state, kept as written
        name = draw(st.sampled_from(["ColorArg", "Frobnicate", "ZEnabled"]))
        assert lookup_state(name) is None
        value = draw(st.one_of(st.integers(0, 100).map(int),
                               st.sampled_from([EnumValue(("TEXTURE",)),
                                                EnumValue(("A", "B"))])))
        return StateAssignment(name, value, draw(st.none() | st.integers(0, 7)), known=False)
    info = draw(st.sampled_from(rows))
    index = None
    if not in_sampler:
        if info.index == "required" or (info.index == "optional" and draw(st.booleans())):
            index = draw(st.integers(0, info.max_index if info.max_index is not None else 200))
    raw = raw_for(draw, info, names)
    try:
        value = coerce_state_value(info, raw, HERE, set(names))
    except StateError:  # an exclusive enum combination: use its first name alone
        value = coerce_state_value(info, raw[:1], HERE, set(names))
    return StateAssignment(info.name, value, index)


@st.composite
def parameter(draw, name: str, names: dict[str, str]) -> Parameter:
    spelling = draw(st.sampled_from(NUMERIC_TYPES + OBJECT_TYPES))
    spec = type_spec(spelling)
    dims: tuple[int, ...] = ()
    value = None
    if spec.is_numeric:
        dims = draw(st.sampled_from([(), (), (2,), (2, 3)]))
        if draw(st.integers(0, 3)):
            value = draw(numeric_value(spelling, dims))
    elif spec.base == "string":
        value = draw(words)
    elif spec.base == "texture":
        value = draw(st.sampled_from([None, None, NullValue()]))
    elif spec.base == "sampler":
        if draw(st.booleans()):
            sampler_names = {k: v for k, v in names.items() if v == "texture"}
            states = draw(st.lists(state_assignment(SAMPLER_ROWS + [lookup_state("Texture")],
                                                    sampler_names, in_sampler=True), max_size=4))
            value = SamplerState(states)
    else:
        stage = "vertex" if spec.base == "vertexshader" else "pixel"
        if draw(st.booleans()):
            dims = (2,)
            value = draw(st.lists(compile_shader(stage), min_size=2, max_size=2))
        else:
            value = draw(st.one_of(shader_block(stage), compile_shader(stage),
                                   st.just(NullValue()), st.none()))
    storage = tuple(s for s in ("shared", "static", "uniform", "const", "extern", "volatile")
                    if draw(st.integers(0, 5)) == 0)
    semantic = draw(st.sampled_from([None, None, "WORLD", "COLOR0", "register(c4)"]))
    return Parameter(name, spec, storage, dims, semantic, draw(annotations()), value)


@st.composite
def effects_models(draw) -> Effect:
    count = draw(st.integers(1, 6))
    params: list[Parameter] = []
    names: dict[str, str] = {}
    for i in range(count):
        p = draw(parameter(f"p{i}", names))
        params.append(p)
        names[p.name] = p.type.base
    techniques = []
    for t in range(draw(st.integers(0, 3))):
        passes = []
        for k in range(draw(st.integers(0, 3))):
            states = draw(st.lists(state_assignment(STATE_ROWS, names), max_size=6))
            passes.append(Pass(draw(st.sampled_from([None, f"P{k}"])), states,
                               draw(annotations())))
        techniques.append(Technique(draw(st.sampled_from([None, f"T{t}"])), passes,
                                    draw(annotations())))
    functions, structs = [], []
    if draw(st.booleans()):
        structs.append(Struct("S", "struct S\n{\n    float4 a : COLOR0;\n};"))
        functions.append(Function("Main", "float4",
                                  "float4 Main(float4 p : POSITION, uniform int n) : COLOR\n"
                                  "{\n    if (n > 0) { p *= 2; }\n    return p;\n}"))
    return Effect("<generated>", params, techniques, functions, structs)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(effects_models())
def test_random_effects_round_trip(effect):
    printed = print_effect(effect)
    parsed = load_effect(printed)
    assert parsed.parameters == effect.parameters, printed
    assert parsed.techniques == effect.techniques, printed
    assert parsed.functions == effect.functions
    assert parsed.structs == effect.structs
    unknown = sum(not s.known for t in effect.techniques for p in t.passes for s in p.states)
    assert len(parsed.warnings) == unknown
