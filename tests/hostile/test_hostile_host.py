"""Hostile input against the host (issue 33: scripts, scene values, meshes, constant states):
every bad input a located `EffectError` as the user reads it, every input the limits allow
rendered or loaded, each within bounded work (its count on limits.py's meter: WORK) and 1 GiB
(tests/hostile/host_cases.py, run in limited children by test_hostile's machinery, the clock a
hang detector only); and the command line's exit code and message."""
from __future__ import annotations



import pytest

from effects.cli.main import main

from tests.hostile import hostile_cases, host_cases
from tests.hostile.test_hostile import _run_children, assert_bounded

# case -> (outcome, words the text must contain: the message as the user reads it)
EXPECTED: dict[str, tuple[str, str]] = {
    "script_pass_runs_itself": (
        "error", "e.fx:3:49: error: script: Pass=P runs pass P, which is already running (P -> P): "
                 "a pass's Script cannot lead back to itself"),
    "script_passes_run_each_other": (
        "error", "e.fx:4:17: error: script: Pass=A runs pass A, which is already running (A -> B -> A)"),
    "script_nested_loops_of_16_million_commands": (
        "error", "e.fx:3:9: error: script of technique T has 65,537 commands; the limit is 65,536 "
                 "(limit script_commands: raise it with EFFECTS_LIMIT_SCRIPT_COMMANDS=N"),
    "script_loops_nested_20000_deep": ("value", "[255, 255, 255, 255]"),
    "script_commands_at_the_limit": ("value", "(8, 8, 4)"),
    "script_commands_one_over_the_limit": (
        "error", "error: script of technique T has 11 commands; the limit is 10 (limit script_commands"),
    "script_draws_over_the_limit": (
        "error", "e.fx:3:76: error: script of technique T has 101 draws; the limit is 100 (limit script_draws"),
    "script_draws_at_the_limit": ("value", "(8, 8, 4)"),
    "script_clear_set_depth_empty": (
        "error", "e.fx:3:9: error: script: ClearSetDepth=: no parameter of that name with a value, nor numbers"),
    "script_clear_set_depth_outside_0_to_1": (
        "error", "e.fx:3:9: error: script: ClearSetDepth=2 is 2; a depth is from 0 to 1"),
    "script_clear_set_color_nan": (
        "error", "e.fx:3:9: error: script: ClearSetColor=nan 0 0 1 needs 1 to 4 finite numbers"),
    "script_clear_set_stencil_of_nothing": (
        "error", "e.fx:3:9: error: script: ClearSetStencil=Nope: no parameter of that name with a value"),
    "script_loop_count_past_a_double": (
        "error", "e.fx:3:9: error: script: LoopByCount=1e999: not a number or a numeric parameter"),
    "script_loop_count_of_5000_digits": (
        "error", "error: script: LoopByCount=999999999999999999999999999999999999999999999999999999999...: "
                 "not a number"),
    "target_dimensions_of_100000": (
        "error", "e.fx:1:39: error: render target RT has 100,000 texels along an edge; the limit is 8,192 "
                 "(limit texture_edge"),
    "target_width_height_of_4096_on_numpy": (
        "error", "e.fx:1:38: error: render target RT (4096 x 4096) has 16,777,216 pixels; the limit is "
                 "4,194,304 (limit target_pixels_numpy"),
    "target_viewport_ratio_of_1e30": ("error", "e.fx:1:41: error: render target RT has 8,000,000,"),
    "target_viewport_ratio_negative": (
        "error", "e.fx:1:41: error: render target RT: ViewportRatio = {-1, 1} must be finite numbers, "
                 "not negative"),
    "target_cube_of_5000": (
        "error", "e.fx:2:68: error: render target RT (5000 x 5000 x 6 cube) has 150,000,000 pixels; "
                 "the limit is 4,194,304 (limit target_pixels_numpy"),
    "target_sampled_never_drawn_8192_square": (
        "error", "e.fx:1:39: error: render target RT (8192 x 8192) has 67,108,864 pixels"),
    "legal_target_sampled_never_drawn_2048_square": ("value", "((8, 8, 4), 0, 'peak under 16 MiB: True')"),
    "legal_target_of_2048_by_1024": ("value", "(8, 8, 4)"),
    "legal_cube_target_at_the_numpy_pixel_limit": ("value", "(8, 8, 4)"),
    "scene_params_nested_100000_deep": (
        "error", "<scene>:1:1: error: scene params C=[[[[...]]]]: float4 C (declared at "),
    "set_value_nested_100000_deep": (
        "error", "e.fx:1:8: error: --set C=[[[[...]]]]: float4 C: takes 4 numbers, got 1 ([[[[...]]]])"),
    "scene_params_sharing_sublists_into_10_to_the_30_numbers": ("error", "takes 4 numbers, got more than 4"),
    "legal_scene_params_nested_60_deep": ("value", "[0.25, 0.5, 0.75, 1.0]"),
    "obj_one_face_of_2_million_corners": (
        "error", "m.obj:4:1: error: the .obj file's face list (3 indices a triangle; a face of k corners "
                 "makes k - 2 triangles) has 5,999,997 indices; the limit is 3,000,000 (limit mesh_indices"),
    "legal_obj_one_face_of_a_million_corners": ("value", "(3, 999998)"),
    "obj_corners_split_past_mesh_vertices": (
        "error", "m.obj:1:1: error: the .obj file's mesh (a vertex for each distinct v/vt/vn corner) has "
                 "900,000 vertices; the limit is 500,000 (limit mesh_vertices"),
    "obj_600000_texture_coordinates": (
        "error", "m.obj:1:1: error: the .obj file's texture-coordinate list has 600,000 vertices"),
    "legal_obj_indices_at_the_limit": (
        "value", "[3, \"six.obj:8:1: error: the .obj file's face list (3 indices a triangle; a face of "
                 "k corners makes k - 2 triangles) has 12 indices; the limit is 9 (limit mesh_indices: "
                 "raise it with EFFECTS_LIMIT_MESH_INDICES=N or effects.base.limits.set_limit("
                 "'mesh_indices', N))\", \"indented.obj:8:1: error: the .obj file's face list (3 indices a "
                 "triangle; a face of k corners makes k - 2 triangles) has 12 indices; the limit is 9"),
    "vertex_shader_constant_i_16": (
        "error", "<string>:2:23: error: VertexShaderConstantI[16]: the index must be 0 to 15"),
    "pixel_shader_constant_b_2048": (
        "error", "<string>:2:22: error: PixelShaderConstantB[2048]: the index must be 0 to 15"),
    "vertex_shader_constant_f_8192": (
        "error", "<string>:2:23: error: VertexShaderConstantF[8192]: the index must be 0 to 8191"),
    "pixel_shader_constant_f_224": (
        "error", "<string>:2:21: error: PixelShaderConstant[224]: the index must be 0 to 223"),
    "constant_i_value_running_past_i15": (
        "value", "{'radeon9700': ['pass p (line 3): VertexShaderConstantI[15] sets i15..i16; Direct3D 9 "
                 "has 16 integer registers (i0..i15)']}"),
    "constant_f_past_each_cards_file": (
        "value", "{'geforce3': ['pass p (line 3): VertexShaderConstantF[94] sets c94..c97; the GeForce3 "
                 "has MaxVertexShaderConst 96 (c0..c95)', \"pass p (line 4): PixelShaderConstantF[31] "
                 "sets c31; the GeForce3's pixel shaders (ps_1_1) have c0..c7\"], 'radeon9700': [], "
                 "'tnt2': ['pass p (line 4): PixelShaderConstantF[31] sets c31; the RIVA TNT2 has no "
                 "pixel shaders, so no pixel shader constant registers']}"),
    "legal_constants_at_the_ends_of_the_register_files": ("value", "{'geforce3': [], 'radeon9700': []}"),
}


# case -> what it spent on limits.py's meter (test_hostile.WORK's form)
WORK: dict[str, dict[str, int | tuple[int, int]]] = {
    "script_nested_loops_of_16_million_commands": {"script_commands": 65_537, "script_draws": 0},
    "script_loops_nested_20000_deep": {"script_commands": 2 * 20_000 + 2},   # + Pass=P, Draw
    "script_commands_at_the_limit": {"script_commands": 11},
    "script_commands_one_over_the_limit": {"script_commands": 11},
    "script_draws_over_the_limit": {"script_draws": 101},
    "script_draws_at_the_limit": {"script_draws": 100},
    "target_width_height_of_4096_on_numpy": {"target_pixels_numpy": 4096 ** 2},
    "target_cube_of_5000": {"target_pixels_numpy": 6 * 5000 ** 2},
    "target_sampled_never_drawn_8192_square": {"target_pixels_numpy": 8192 ** 2},
    "legal_target_sampled_never_drawn_2048_square": {"target_pixels_numpy": 2048 ** 2},
    "legal_target_of_2048_by_1024": {"target_pixels_numpy": 2048 * 1024},
    "legal_cube_target_at_the_numpy_pixel_limit": {"target_pixels_numpy": 6 * 836 ** 2},
    "obj_one_face_of_2_million_corners": {"mesh_indices": 3 * (3 * 666_667 - 2)},
    "legal_obj_one_face_of_a_million_corners": {"mesh_indices": 3 * 999_998},
    "obj_corners_split_past_mesh_vertices": {"mesh_vertices": 900_000},
    "obj_600000_texture_coordinates": {"mesh_vertices": 600_000},
}


def test_every_case_has_an_expectation():
    assert set(EXPECTED) == set(host_cases.CASES)
    assert not set(host_cases.CASES) & set(hostile_cases.CASES)
    assert set(WORK) <= set(host_cases.CASES)


@pytest.fixture(scope="module")
def outcomes() -> dict[str, dict]:
    return _run_children(list(host_cases.CASES), host_cases)


@pytest.mark.slow
@pytest.mark.parametrize("name", list(EXPECTED))
def test_hostile_host_input_gives_a_located_answer_in_bounded_work_and_memory(name, outcomes):
    result = outcomes[name]
    outcome, words = EXPECTED[name]
    assert result["outcome"] == outcome, result["text"]
    assert words in result["text"], result["text"]
    assert_bounded(result, words, WORK.get(name, {}))


SELF_PASS = ('technique T < string Script = "Pass=P;"; > {\n'
             '  pass P < string Script = "Pass=P;"; > { } }\n')
HUGE_TARGET = ("texture RT : RenderColorTarget < int2 Dimensions = {8192, 8192}; >;\n"
               'technique T < string Script = "Pass=P;"; > {\n'
               '  pass P < string Script = "Draw=Buffer;"; > { Texture[0] = <RT>; } }\n')


@pytest.mark.parametrize("command, source, words", [
    ("render", SELF_PASS, "e.fx:2:19: error: script: Pass=P runs pass P, which is already running"),
    ("render", HUGE_TARGET, "e.fx:1:39: error: render target RT (8192 x 8192) has 67,108,864 pixels"),
    ("doctor", HUGE_TARGET, "e.fx:1:39: error: render target RT (8192 x 8192) has 67,108,864 pixels"),
    ("validate", "technique t { pass p { PixelShaderConstantB[16] = true; } }",
     "e.fx:1:44: error: PixelShaderConstantB[16]: the index must be 0 to 15"),
])
def test_the_command_line_exits_2_with_the_located_message(command, source, words, tmp_path, capsys):
    (tmp_path / "e.fx").write_text(source)
    argv = [command, str(tmp_path / "e.fx"), "-p", "radeon9700"]
    if command == "render":
        argv += ["--size", "8x8", "-o", str(tmp_path / "o.png")]
    code = main(argv)
    out, err = capsys.readouterr()
    assert code == 2, (out, err)
    assert words in err, err
    assert "Traceback" not in err and "internal error" not in err
