"""Constructs fxc compiled in Wine's d3dx9 test shaders and effects (issues 30/35) that our
front end refused: each rendered on both back ends with values worked out by hand, and the
neighbouring form fxc refused refused here too, at its place."""
from __future__ import annotations

import numpy as np
import pytest

import effects
from tests.shaders.hlsl.test_hlsl_render import backend, effect_for, render  # noqa: F401

TOL = 1.5 / 255


# -- an unnamed struct type: `struct { ... } s = ...;` ---------------------------------------------

def test_an_unnamed_struct_declares_its_variables_at_the_effects_scope(backend):
    fx = effect_for("""
float4 PS() : COLOR
{
    return float4(s.f, s.i / 8.0, s_2[1].f, s_2[0].i / 8.0);
}""", params="struct {float f; int i;} s = {0.25f, 4}, s_2[2] = {{0.1, 1}, {0.75, 2}};")
    assert [p.name for p in fx.parameters] == ["s", "s_2"]
    img = render(fx, backend)
    assert np.allclose(img[3, 3], (0.25, 0.5, 0.75, 0.125), atol=TOL), img[3, 3]


def test_an_unnamed_struct_as_a_struct_member(backend):
    fx = effect_for("""
float4 PS() : COLOR
{
    return float4(ss.f, ss.s.f, ss.s.v.y, ss.f1);
}""", params="struct {float f; struct {float f; float3 v;} s; float f1;} "
              "ss = {0.125, 0.25, 0.3, 0.5, 0.7, 1.0};")
    img = render(fx, backend)
    assert np.allclose(img[3, 3], (0.125, 0.25, 0.5, 1.0), atol=TOL), img[3, 3]


def test_an_unnamed_struct_member_named_twice_is_fxcs_x3003_at_the_second():
    fx = effect_for("""
float4 PS() : COLOR { return s.f; }""", params="struct {\n  float f;\n  float f;\n} s;")
    with pytest.raises(effects.EffectError) as err:
        effects.render(fx, "radeon9700", technique="T", size=(4, 4))
    assert "X3003: redefinition of 'f'" in str(err.value)
    assert (err.value.line, err.value.column) == (3, 9), str(err.value)


# -- a loop counted by one component of a uniform int; an `if` on one of a uniform bool ----------
# fxc gives such a parameter a register per component (effects/shaders/hlsl/components.py):
# `int3 vn` is i0-i2 and `i < vn.z` is `rep i2`

PS = "float4 PS(float4 c : COLOR0) : COLOR { return c; }"
COUNTED = """
float4 VS(float4 p : POSITION, out float4 c : COLOR0) : POSITION
{
    float4 acc = float4(0, 0, 0, 1);
    int i;
    for (i = 0; i < BOUND; i++)
        acc.x += 0.125;
    if (FLAG) acc.y = 0.5; else acc.z = 0.75;
    c = acc;
    return p;
}
""" + PS
SHAPES = ("int3 vn = {1, 2, 3};\nrow_major int3x2 rn = {1, 2, 3, 4, 5, 6};\n"
          "int3x2 cn = {1, 2, 3, 4, 5, 6};\nint an[2] = {1, 6};\n"
          "struct {int n; int3 vn;} sn[2] = {1, 2, 3, 4, 5, 6, 7, 1};\n"
          "bool3 vb = {true, false, true};\nstruct {bool b; bool2 v;} sb = {false, true, false};")


@pytest.mark.parametrize("bound, flag, registers, count, flagged", [
    # the bound, the flag, fxc's layout (first i#, the loop's i#, the if's b#), the count
    # and the flag at the defaults above
    ("vn.z", "vb.z", ("vn", 0, "rep i2", "if b2"), 3, True),
    ("rn._31", "!vb.y", ("rn", 0, "rep i4", "if b1"), 5, True),     # row by row: 3 * 2 - 1
    ("cn._31", "vb.x", ("cn", 0, "rep i4", "if b0"), 5, True),      # packing does not matter
    ("an[1]", "sb.v.x", ("an", 0, "rep i1", "if b1"), 6, True),
    ("sn[1].vn.y", "sb.b", ("sn", 0, "rep i6", "if b0"), 7, False),  # 4 a struct, + 1 + 1
])
def test_a_loop_counted_by_a_component_and_an_if_on_one(backend, bound, flag, registers, count,
                                                         flagged):
    from effects.shaders.hlsl import compile_shader
    fx = effect_for(COUNTED.replace("BOUND", bound).replace("FLAG", flag),
                    vs="compile vs_2_0 VS()", params=SHAPES)
    shader = compile_shader(fx, "VS", "vs_2_0")
    name, first, rep, if_b = registers
    assert shader.int_registers == {name: first}, shader.int_registers
    assert rep in shader.text and if_b in shader.text, shader.text
    img = render(fx, backend)
    want = (0.125 * count, 0.5 if flagged else 0, 0 if flagged else 0.75, 1)
    assert np.allclose(img[4, 4], want, atol=TOL), (img[4, 4], want)


def test_the_effect_sets_each_components_register_from_the_parameters_value(backend):
    fx = effect_for(COUNTED.replace("BOUND", "vn.y").replace("FLAG", "vb.z"),
                    vs="compile vs_2_0 VS()", params=SHAPES)
    img = render(fx, backend, params={"vn": [7, 4, 1], "vb": [True, True, False]})
    assert np.allclose(img[4, 4], (0.5, 0, 0.75, 1), atol=TOL), img[4, 4]


def test_the_register_table_counts_up_to_the_last_component_read():
    # fxc's table for `int3x2 ran[2]` read at ran[1]._21 (i8): 9 registers of 12 (Wine's
    # registerset_blob_special_int); ours for this counts the same way
    from effects.shaders.d3dbc.writer import constant_table
    from effects.shaders.hlsl import compile_shader
    fx = effect_for(COUNTED.replace("BOUND", "ran[1]._21").replace("FLAG", "vb.z"),
                    vs="compile vs_3_0 VS()",
                    params="row_major int3x2 ran[2] = {4, 5, 6, 1, 8, 1, 2, 3, 4, 7, 9, 1};\n"
                           "bool3 vb = {true, false, true};",)
    shader = compile_shader(fx, "VS", "vs_3_0")
    table = {c.name: (c.register_set, c.register_index, c.register_count)
             for c in constant_table(shader.program, shader).constants}
    assert table == {"ran": ("int4", 0, 9), "vb": ("bool", 0, 3)}, table


def test_a_component_bound_on_a_target_without_loops_is_x3511_at_the_loop():
    from effects.shaders.hlsl import compile_shader
    fx = effect_for(COUNTED.replace("BOUND", "vn.z").replace("FLAG", "vb.z"),
                    vs="compile vs_1_1 VS()", params=SHAPES)
    with pytest.raises(effects.EffectError) as err:
        compile_shader(fx, "VS", "vs_1_1")
    assert err.value.message.startswith("X3511: unable to unroll loop: its count is the "
                                        "uniform 'vn', known only when the shader runs"), \
        err.value.message
    line = SHAPES.count("\n") + 1 + next(k for k, t in enumerate(COUNTED.split("\n"))
                                         if "for (" in t) + 1
    assert (err.value.location.line, err.value.location.column) == (line, 5)


# -- a shader-constant state given fewer numbers than its registers hold -------------------------

def test_a_scalar_and_a_partial_constant_state_set_registers_as_d3dx_did(backend):
    # D3DX (Wine's test_effect_states on native): a scalar sets its register's x; a value
    # short of whole registers sets its first register and zeros the rest
    fx = effects.load_effect("""
technique T { pass P {
    VertexShaderConstant1[1] = 0.5f;
    VertexShaderConstant4[4] = {0.25, 0.75, 1, 1, 1, 1, 1, 1, 1};
    VertexShader = asm { vs_1_1 dcl_position v0
        mov oPos, v0
        add oD0, c1, c5
        mov oD0.z, c4.y
        mov oD0.w, c4.z };
    PixelShader = asm { ps_1_1 mov r0, v0 };
} }""")
    img = render(fx, backend)
    assert np.allclose(img[4, 4], (0.5, 0, 0.75, 1), atol=TOL), img[4, 4]


# -- an element of a constructed value in a state's expression: `float3(1, 2, 3)[i]` ------------

INDEXED = """int Index = 1;
technique T { pass P {
    PixelShaderConstantF[0] = float4(float3(0.25, 0.5, 0.75)[SUBSCRIPT], 0, 0, 1);
    VertexShader = asm { vs_1_1 dcl_position v0
        mov oPos, v0 };
    PixelShader = asm { ps_2_0 mov oC0, c0 };
} }"""


@pytest.mark.parametrize("index", [0, 1, 2])
def test_a_constructors_element_picked_by_a_parameter_in_a_state(backend, index):
    fx = effects.load_effect(INDEXED.replace("SUBSCRIPT", "Index"))
    img = effects.render(fx, "radeon9700", technique="T", backend=backend,
                         scene={"mesh": "quad", "size": [8, 8]},
                         params={"Index": index}).astype(np.float64) / 255
    assert np.allclose(img[4, 4], ((0.25, 0.5, 0.75)[index], 0, 0, 1), atol=TOL), img[4, 4]


def test_a_constructors_element_past_its_end_is_x3504_at_the_subscript():
    fx = effects.load_effect(INDEXED.replace("SUBSCRIPT", "3"))
    with pytest.raises(effects.EffectError) as err:
        effects.render(fx, "radeon9700", technique="T", size=(4, 4))
    assert "X3504: array index 3 out of bounds (the size is 3)" in str(err.value)
    assert (err.value.line, err.value.column) == (3, 62)


# -- a string array with an initialiser list: `string s_2[2] = {"a", "b"};` ------------------------

def test_a_string_array_holds_its_strings_and_writes_to_a_binary_and_back(tmp_path):
    from effects.shaders.fxo import write_effect_binary
    fx = effects.load_effect('string s_2[2] = {"test1", "test2"};\nstring s = "one";\n'
                             "technique T { pass P { } }")
    assert [(p.name, p.value) for p in fx.parameters] == [("s_2", ["test1", "test2"]),
                                                          ("s", "one")]
    out = tmp_path / "s.fxo"
    out.write_bytes(write_effect_binary(fx))
    back = effects.load_effect(out)
    assert [(p.name, p.value) for p in back.parameters] == [("s_2", ["test1", "test2"]),
                                                            ("s", "one")]


@pytest.mark.parametrize("text, message, column", [
    ('string s_2[2] = {"test1", 2};', "'s_2' is a string array: expected a string literal, "
                                      "found '2'", 27),
    ('string s_2[2] = {"test1"};', "'s_2' has 2 elements, the initializer gives 1", 17),
    ('string s_2[2] = "test1";', "'s_2' is an array: expected '{' with 2 values", 17),
])
def test_a_string_array_given_something_else_is_refused_where_it_is(text, message, column):
    with pytest.raises(effects.EffectError) as err:
        effects.load_effect(text + "\ntechnique T { pass P { } }")
    assert err.value.message == message
    assert (err.value.line, err.value.column) == (1, column)
