"""fxc's float constant layout (effects/shaders/hlsl/constant_layout.py), one small program per
rule, with the registers fxc gave: each rule is read off fxc 9.29's bytecode for Wine's D3DX9
tests (tests/data/d3dbc/wine/d3dx9_36_shader_excerpt.c; the array named) or off the register
tables vkd3d-shader's sm1-const-allocation test records from native d3dcompiler."""
from __future__ import annotations

import re

import effects
from effects.shaders.hlsl.compiler import compile_shader


def table(functions: str, entry: str = "VS", target: str = "vs_3_0"
          ) -> dict[str, tuple[int, int]]:
    """parameter -> (first c#, registers) of the compiled shader's constant table."""
    fx = effects.load_effect(functions + "\ntechnique T { pass P { } }\n")
    return dict(compile_shader(fx, entry, target).constants)


def literal_registers(functions: str, entry: str = "VS", target: str = "vs_3_0") -> list[int]:
    fx = effects.load_effect(functions + "\ntechnique T { pass P { } }\n")
    return sorted(compile_shader(fx, entry, target).program.defs)


def test_a_matrix_holds_the_columns_up_to_the_last_read():
    # registerset_blob_matrix_column_clamp: `cf._22` is column 1, so cf is c0-c1 and f c2
    fn = """float4x4 cf; float f;
float4 VS(float4 p : POSITION) : POSITION { return float4(0, cf._22, f, 0); }"""
    assert table(fn) == {"cf": (0, 2), "f": (2, 1)}


def test_an_array_holds_the_elements_up_to_the_last_read():
    # registerset_blob_bigvec: `float3 vaf[10]` read at vaf[8] is c0-c8 (9 registers)
    fn = "float3 vaf[10];\nfloat4 VS(float4 p : POSITION) : POSITION { return p.y + vaf[8].x; }"
    assert table(fn) == {"vaf": (0, 9)}


def test_a_struct_holds_the_members_up_to_the_last_read():
    # test_get_shader_constant_variables_blob: s_3[3] of {float f; int i;} read at s_3[2].f
    # is 5 registers of its 6
    fn = """struct P { float f; int i; }; P s_3[3];
float4 VS(float4 p : POSITION) : POSITION { return p * s_3[2].f; }"""
    assert table(fn) == {"s_3": (0, 5)}


def test_the_largest_is_placed_first():
    # test_get_shader_constant_variables_blob: 18, 6, 5, 4, 4, 2, 2, 2, 2, 1, 1, 1 registers
    # from c0 up, whatever the order of declaration or use
    fn = """float A; float4 B[2]; float4 C; float4 D[3];
float4 VS(float4 p : POSITION) : POSITION { return A * p + B[1] + C + D[2]; }"""
    assert table(fn) == {"D": (0, 3), "B": (3, 2), "A": (5, 1), "C": (6, 1)}


def test_those_of_one_size_in_declaration_order_not_first_use():
    # test_get_shader_constant_variables_blob: f_2, s_2, v, r13 (two registers each) at c37,
    # c39, c41, c43 in the file's order, though the code reads v and r13 first; vkd3d's
    # "declaration order is more important than instruction order"
    fn = """float4 Z; float4 A;
float4 VS(float4 p : POSITION) : POSITION { return A * p + Z; }"""
    assert table(fn) == {"Z": (0, 1), "A": (1, 1)}


def test_a_register_binding_holds_its_whole_type_and_a_smaller_one_fills_a_gap():
    # vkd3d's sm1-const-allocation: `float4x4 a : register(c1)` read at a._11 is c1, one
    # register in the table, but c1-c4 are held, so b[4] read at b[1] goes to c5; and an
    # unread `float U[2] : register(c2)` leaves c0-c1, where a two-register uniform fits
    # and a three-register one does not
    fn = """float4x4 a : register(c1); float b[4];
float4 VS(float4 p : POSITION) : POSITION { return float4(a._11, b[1], 0, 0); }"""
    assert table(fn) == {"a": (1, 1), "b": (5, 2)}
    fn = """float U[2] : register(c2); float S3[3]; float S2[2];
float4 VS(float4 p : POSITION) : POSITION { return float4(S3[2], S2[1], 0, 0); }"""
    assert table(fn) == {"S3": (4, 3), "S2": (0, 2)}


def test_a_literal_takes_no_register_a_binding_holds():
    # the def goes after what `float4x4 M : register(c0)` holds (c0-c3), though the code
    # reads only c0
    fn = """float4x4 M : register(c0);
float4 VS(float4 p : POSITION) : POSITION { return p * M._11 + 2.5; }"""
    assert table(fn) == {"M": (0, 1)}
    assert literal_registers(fn) == [4]


def test_an_array_read_by_a_run_time_index_holds_all_of_it():
    # which element `K[i]` reads is known only when it runs (c[a0.x + n])
    fn = """float4 K[6]; float4 L;
float4 VS(float4 p : POSITION, float i : TEXCOORD0) : POSITION { return p * K[i] + L; }"""
    assert table(fn, target="vs_2_0") == {"K": (0, 6), "L": (6, 1)}


def test_fxcs_effect_binary_lays_six_matrices_out_by_size_then_declaration():
    # fxc's ps_3_0 RenderScenePS(mb2x3row) in tests/data/fxo/wine/
    # test_effect_preshader_effect_blob.fxo: its constant table gives the three-register
    # m2x3column (three columns) and m3x2row (three rows) first, then the two-register ones
    # as the .fx declares them (m2x2row, m2x2column, m2x3row, m3x2column)
    from tests.paths import TESTS
    fx = effects.load_effect(TESTS / "data" / "fxo" / "wine" /
                             "test_effect_preshader_effect_blob.fx")
    shader = compile_shader(fx, "RenderScenePS", "ps_3_0", ("mb2x3row",))
    floats = {n: r for n, r in shader.constants.items()
              if n.startswith("m") and not n.startswith("mb")}
    assert floats == {"m2x3column": (0, 3), "m3x2row": (3, 3), "m2x2row": (6, 2),
                      "m2x2column": (8, 2), "m2x3row": (10, 2), "m3x2column": (12, 2)}


def _fxc_and_ours(entry: str, target: str, args: tuple[str, ...], fxc_array: str, k: int):
    """(fxc's, ours) name -> (register set, first, count) for a shader of Wine's preshader
    effect: fxc's from the .fxo (parameter `fxc_array`, element k), ours compiled from the .fx."""
    from effects.shaders.d3dbc import read_shader
    from effects.shaders.d3dbc.writer import constant_table
    from tests.paths import TESTS
    wine = TESTS / "data" / "fxo" / "wine"
    fxo = effects.load_effect(wine / "test_effect_preshader_effect_blob.fxo")
    theirs = read_shader(fxo.parameter(fxc_array).value[k].data, "fxc").table
    fx = effects.load_effect(wine / "test_effect_preshader_effect_blob.fx")
    shader = compile_shader(fx, entry, target, args)
    ours = constant_table(shader.program, shader)
    return ({c.name: (c.register_set, c.register_index, c.register_count, c.type.elements)
             for c in t.constants} for t in (theirs, ours))


def test_fxcs_effect_binary_ps_3_0_table_is_ours_entry_for_entry():
    # RenderScenePS(mb2x3row): six float matrices (above), g_iVect's `rep i0`, the bool
    # matrices of `if (mb[1][1])` and `if (mb2x3column[0][0])` (b0 count 5: row by row,
    # [1][1] is the fifth component; b5 count 1, up to the last read), and sampler1 s0,
    # samplers_array s1 count 1 (its [0] read; its type two elements)
    fxc, ours = _fxc_and_ours("RenderScenePS", "ps_3_0", ("mb2x3row",), "ps_arr", 0)
    assert fxc["mb2x3row"] == ("bool", 0, 5, 1) and fxc["mb2x3column"] == ("bool", 5, 1, 1)
    assert fxc["sampler1"] == ("sampler", 0, 1, 1)
    assert fxc["samplers_array"] == ("sampler", 1, 1, 2)
    assert ours == fxc


def test_a_sampler_array_holds_its_elements_up_to_the_last_read_the_largest_first():
    # RenderSceneVS reads sampler1, then samplers_array[1]: fxc gave the two-register array
    # s0-s1 and sampler1 s2 (the floats of this shader differ: fxc made g_Selector's test a
    # preshader)
    fxc, ours = _fxc_and_ours("RenderSceneVS", "vs_3_0", ("1", "true"), "vs_arr2", 0)
    samplers = {n: r for n, r in fxc.items() if r[0] == "sampler"}
    assert samplers == {"samplers_array": ("sampler", 0, 2, 2), "sampler1": ("sampler", 2, 1, 1)}
    assert {n: r for n, r in ours.items() if r[0] == "sampler"} == samplers


def _samplers(functions: str, entry: str = "PS", target: str = "ps_3_0") -> dict[str, int]:
    fx = effects.load_effect(functions + "\ntechnique T { pass P { } }\n")
    return compile_shader(fx, entry, target).samplers


def test_samplers_of_one_size_in_declaration_order_not_first_use():
    # vkd3d's combined-samplers test, as native d3dcompiler ran it: sam1 read first, but
    # 100 * tex2D(sam1) + 10 * tex2D(sam0) + tex2D(sam2) reads s1, s0, s2 (probe 102 with
    # texture k holding k); Wine's test_constant_table: m, n, o, s at s2, s3, s4, s6
    fn = """sampler sam0; sampler sam1; sampler sam2;
float4 PS(float2 uv : TEXCOORD0) : COLOR {
    return 100 * tex2D(sam1, uv) + 10 * tex2D(sam0, uv) + tex2D(sam2, uv); }"""
    assert _samplers(fn) == {"sam0": 0, "sam1": 1, "sam2": 2}


def test_a_sampler_register_binding_is_kept_and_the_rest_fit_around_it():
    # Wine's test_constant_table: `sampler l : register(s5)` stays at s5 and the unbound
    # ones take the free registers around it in declaration order
    fn = """sampler a; sampler l : register(s1); sampler b; sampler c;
float4 PS(float2 uv : TEXCOORD0) : COLOR {
    return tex2D(c, uv) + tex2D(l, uv) + tex2D(b, uv) + tex2D(a, uv); }"""
    assert _samplers(fn) == {"a": 0, "l": 1, "b": 2, "c": 3}


def test_bool_registers_hold_up_to_the_last_component_read():
    # as fxc's b0 count 5 / b5 for Wine's bool2x3 matrices: a later bool goes right after the
    # last register an earlier one's reads reach, not after all its components
    fn = """bool4 A; bool B;
float4 VS(float4 p : POSITION) : POSITION {
    float4 r = p;
    if (A.y) r = r * 2;
    if (B) r = r + 1;
    return r; }"""
    fx = effects.load_effect(fn + "\ntechnique T { pass P { } }\n")
    shader = compile_shader(fx, "VS", "vs_3_0")
    assert shader.bool_registers == {"A": 0, "B": 2}
    assert "if b1" in shader.text and "if b2" in shader.text


def test_the_listing_names_a_sampler_array_as_the_constant_table_does():
    # fxc's /Fc register table lists the array, from its first register up to the last
    # element read, as the constant table does (samplers_array s0 2 for RenderSceneVS)
    from effects.shaders.listing import listing
    from tests.paths import TESTS
    fx = effects.load_effect(TESTS / "data" / "fxo" / "wine" /
                             "test_effect_preshader_effect_blob.fx")
    shader = compile_shader(fx, "RenderSceneVS", "vs_3_0", ("1", "true"))
    rows = [line.split()[1:] for line in listing(fx, shader)
            if re.fullmatch(r"//\s+\S+\s+s\d+\s+\d+", line)]
    assert rows == [["samplers_array", "s0", "2"], ["sampler1", "s2", "1"]]
