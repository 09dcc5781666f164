"""Hostile inputs against what the host runs (issue 33): DXSAS scripts and their render
targets, scene and --set values, .obj meshes, shader constant states. One function per case,
run by tests/hostile/test_hostile_host.py in a child process as tests/hostile/hostile_cases.py
runs its own (at most 1 GiB of data, metered work and a hang detector: the same child machinery, imported from
there); each returns what the framework gave back, an `EffectError` being the answer to most.
Cases named `..._at_the_limit` or `legal_...` are inputs the limits allow: they must work.
"""
from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Callable

if __package__:
    from tests.hostile import hostile_cases as base
else:   # run as a script: this folder is on the path
    import hostile_cases as base  # type: ignore[no-redef]

CASES: dict[str, Callable[[Path], object]] = {}


def case(fn: Callable[[Path], object]) -> Callable[[Path], object]:
    CASES[fn.__name__] = fn
    return fn


def _effects():
    import effects
    return effects


def _render(source: str, d: Path, card: str = "radeon9700", **kw):
    (d / "e.fx").write_text(source)
    kw.setdefault("size", (8, 8))
    kw.setdefault("scene", {"mesh": "quad"})
    return _effects().render(base.load(d / "e.fx"), card, **kw)


def _reasons(source: str, cards: tuple[str, ...]) -> dict[str, list[str]]:
    effects = _effects()
    effect = base.load(source)
    return {card: [str(r) for r in effect.validate(effect.techniques[0], effects.load_profile(card)).reasons]
            for card in cards}


# a pass that draws a full-screen quad, and a technique running `script`
DRAW = 'pass P < string Script = "Draw=Buffer;"; > { Lighting = false; ZEnable = false; }'


def _scripted(script: str, declarations: str = "", passes: str = DRAW) -> str:
    return f'{declarations}\ntechnique T <\n string Script = "{script}"; > {{ {passes} }}\n'


# ---------------------------------------------------------------------------------------------
# DXSAS scripts: the pass graph, the command and draw budgets, every command's arguments

@case
def script_pass_runs_itself(d):
    return _render(_scripted("Pass=P;", passes='pass P < string Script = "Pass=P;"; > { }'), d)


@case
def script_passes_run_each_other(d):
    return _render(_scripted("Pass=A;", passes='pass A < string Script = "Draw=Buffer; Pass=B;"; > { }\n'
                                               'pass B < string Script = "Pass=A;"; > { }'), d)


@case
def script_nested_loops_of_16_million_commands(d):
    return _render(_scripted("LoopByCount=256; LoopByCount=256; LoopByCount=256; "
                             "ClearSetColor=0 0 0 1; LoopEnd=; LoopEnd=; LoopEnd=; Pass=P;"), d)


@case
def script_loops_nested_20000_deep(d):
    return _render(_scripted("LoopByCount=1;" * 20000 + "LoopEnd=;" * 20000 + "Pass=P;"), d)


def _commands_case(d: Path, spare: int):
    """4 rounds of 2 commands in a loop (1 + 2 * 4), then Pass=P and its Draw=Buffer: 11
    commands, run under a script_commands limit of 11 + spare."""
    from effects.base import limits
    source = _scripted("LoopByCount=4; ClearSetColor=0 0 0 1; LoopEnd=; Pass=P;")
    with limits.raised(script_commands=11 + spare):
        return _render(source, d).shape


@case
def script_commands_at_the_limit(d):
    return _commands_case(d, 0)


@case
def script_commands_one_over_the_limit(d):
    return _commands_case(d, -1)


@case
def script_draws_over_the_limit(d):
    from effects.base import limits
    with limits.raised(script_draws=100):   # the default (1,024) takes seconds of drawing
        return _render(_scripted("LoopByCount=101; Pass=P; LoopEnd=;"), d)


@case
def script_draws_at_the_limit(d):
    from effects.base import limits
    with limits.raised(script_draws=100):
        return _render(_scripted("LoopByCount=100; Pass=P; LoopEnd=;"), d).shape


@case
def script_clear_set_depth_empty(d):
    return _render(_scripted("ClearSetDepth=; Pass=P;"), d)


@case
def script_clear_set_depth_outside_0_to_1(d):
    return _render(_scripted("ClearSetDepth=2; Pass=P;"), d)


@case
def script_clear_set_color_nan(d):
    return _render(_scripted("ClearSetColor=nan 0 0 1; Pass=P;"), d)


@case
def script_clear_set_stencil_of_nothing(d):
    return _render(_scripted("ClearSetStencil=Nope; Pass=P;"), d)


@case
def script_loop_count_past_a_double(d):
    return _render(_scripted("LoopByCount=1e999; LoopEnd=; Pass=P;"), d)


@case
def script_loop_count_of_5000_digits(d):
    return _render(_scripted("LoopByCount=" + "9" * 5000 + "; LoopEnd=; Pass=P;"), d)


# render targets: checked against texture_edge and target_pixels_<back end> before allocation

TARGET = "texture RT : RenderColorTarget < {size} >;"
INTO_TARGET = "RenderColorTarget0=RT; Pass=P; RenderColorTarget0=; Pass=P;"


@case
def target_dimensions_of_100000(d):
    return _render(_scripted(INTO_TARGET, TARGET.format(size="int2 Dimensions = {100000, 100000};")), d)


@case
def target_width_height_of_4096_on_numpy(d):
    return _render(_scripted(INTO_TARGET, TARGET.format(size="int Width = 4096; int Height = 4096;")), d)


@case
def target_viewport_ratio_of_1e30(d):
    return _render(_scripted(INTO_TARGET, TARGET.format(size="float2 ViewportRatio = {1e30, 1e30};")), d)


@case
def target_viewport_ratio_negative(d):
    return _render(_scripted(INTO_TARGET, TARGET.format(size="float2 ViewportRatio = {-1, 1};")), d)


@case
def target_cube_of_5000(d):
    return _render(_scripted(INTO_TARGET, 'float4 O = {0, 0, 0, 1};\n'
                             'texture RT : RenderColorTarget < string ResourceType = "Cube"; '
                             'int Width = 5000; string CubeOrigin = "O"; >;'), d)


SAMPLED = ('pass P < string Script = "Draw=Buffer;"; > { Lighting = false; ZEnable = false;\n'
           ' Texture[0] = <RT>; ColorOp[0] = SelectArg1; ColorArg1[0] = Texture; }')


@case
def target_sampled_never_drawn_8192_square(d):
    return _render(_scripted("Pass=P;", TARGET.format(size="int2 Dimensions = {8192, 8192};"), SAMPLED), d)


@case
def legal_target_sampled_never_drawn_2048_square(d):
    def run():
        import tracemalloc
        source = _scripted("Pass=P;", TARGET.format(size="int2 Dimensions = {2048, 2048};"), SAMPLED)
        _render(source.replace("2048", "8"), d)   # the same code run once: imports, caches
        tracemalloc.start()
        try:
            image = _render(source, d)
            peak = tracemalloc.get_traced_memory()[1]
        finally:
            tracemalloc.stop()
        # black, without the 64 MiB of a 2048 x 2048 float stand-in (one black texel samples
        # as black as four million do)
        return image.shape, int(image[..., :3].max()), f"peak under 16 MiB: {peak < 16 << 20}"
    return run


@case
def legal_target_of_2048_by_1024(d):
    # half the numpy pixel limit, as render_at_the_numpy_target_limit draws its frame
    return lambda: _render(_scripted(INTO_TARGET, TARGET.format(size="int2 Dimensions = {2048, 1024};")),
                           d).shape


@case
def legal_cube_target_at_the_numpy_pixel_limit(d):
    # 6 faces of 836 x 836: 4,193,376 pixels, the largest cube within 4,194,304, drawn into
    # (a cube only cleared is never allocated: the meter showed this case spent 64 pixels)
    return lambda: _render(_scripted("RenderColorTarget0=RT; ClearSetColor=0 0 0 1; Clear=Color; "
                                     "Pass=P; RenderColorTarget0=; Pass=P;",
                                     'float4 O = {0, 0, 0, 1};\n'
                                     'texture RT : RenderColorTarget < string ResourceType = "Cube"; '
                                     'int Width = 836; string CubeOrigin = "O"; >;'), d).shape


# ---------------------------------------------------------------------------------------------
# scene and --set values

def _nested(value: object, depth: int) -> object:
    for _ in range(depth):
        value = [value]
    return value


COLOUR = "float4 C; technique t { pass p { Lighting = false; } }"


@case
def scene_params_nested_100000_deep(d):
    return _render(COLOUR, d, scene={"mesh": "quad", "params": {"C": _nested(1.0, 100_000)}})


@case
def set_value_nested_100000_deep(d):
    return _render(COLOUR, d, params={"C": _nested(1.0, 100_000)})


@case
def scene_params_sharing_sublists_into_10_to_the_30_numbers(d):
    value: object = [1.0] * 10
    for _ in range(29):
        value = [value] * 10
    return _render(COLOUR, d, scene={"mesh": "quad", "params": {"C": value}})


@case
def legal_scene_params_nested_60_deep(d):
    from effects.host.runtime import Runtime
    (d / "e.fx").write_text(COLOUR)
    runtime = Runtime(base.load(d / "e.fx"), "radeon9700",
                      scene={"mesh": "quad", "params": {"C": _nested([0.25, 0.5, 0.75, 1], 60)}})
    return runtime.effect.parameter("C").value.tolist()


# ---------------------------------------------------------------------------------------------
# .obj meshes: indices as the faces fan out, vertices as the corners split

def _obj_render(d: Path, text: str):
    (d / "m.obj").write_text(text)
    (d / "s.yaml").write_text("mesh: m.obj\n")
    return _render("technique t { pass p { Lighting = false; } }", d, scene=str(d / "s.yaml"))


TRIANGLE = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"


@case
def obj_one_face_of_2_million_corners(d):
    return _obj_render(d, TRIANGLE + "f " + " ".join(["1 2 3"] * 666_667) + "\n")


@case
def legal_obj_one_face_of_a_million_corners(d):
    # 1,000,000 corners fan into 999,998 triangles: 2,999,994 indices, within 3,000,000
    path = d / "m.obj"
    path.write_text(TRIANGLE + "f " + " ".join(["1 2 3"] * 333_333) + " 1\n")

    def run():
        from effects.assets.meshes import load_obj
        mesh = load_obj(path)
        return mesh.vertex_count, mesh.triangle_count
    return run


@case
def obj_corners_split_past_mesh_vertices(d):
    # 300,000 v and vt; each triangle's corners pair them differently: 900,000 mesh vertices
    n = 300_000
    lines = [f"v {i} 0 0" for i in range(n)] + [f"vt 0.{i} 0" for i in range(n)]
    lines += [f"f {i % n + 1}/{(i + 1) % n + 1} {(i + 1) % n + 1}/{(i + 5) % n + 1} "
              f"{(i + 2) % n + 1}/{(i + 9) % n + 1}" for i in range(n)]
    (d / "m.obj").write_text("\n".join(lines) + "\n")

    def run():
        from effects.assets.meshes import load_obj
        return load_obj(d / "m.obj")
    return run


@case
def obj_600000_texture_coordinates(d):
    (d / "m.obj").write_text(TRIANGLE + "vt 0 0\n" * 600_000 + "f 1 2 3 1\n")

    def run():
        from effects.assets.meshes import load_obj
        return load_obj(d / "m.obj")
    return run


@case
def legal_obj_indices_at_the_limit(d):
    """A pentagon makes 3 triangles, 9 indices: it loads under mesh_indices = 9; a hexagon
    (12) is refused at its line, by the count made before reading and, where that count
    does not see the face (an indented line), by the per-line reader as it reads."""
    from effects.assets.meshes import load_obj
    from effects.base import limits
    from effects.base.errors import SceneError
    shape = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0.5 2 0\nv 0 1 0\nv -1 1 0\n"
    (d / "five.obj").write_text(shape + "f 1 2 3 4 5\n")
    (d / "six.obj").write_text(shape + "# a hexagon\nf 1 2 3 4 5 6\n")
    (d / "indented.obj").write_text(shape + "f 1 2 3\n  f 1 2 3 4 5\n")
    with limits.raised(mesh_indices=9):
        out: list[object] = [load_obj(d / "five.obj").triangle_count]
        for name in ("six.obj", "indented.obj"):
            try:
                load_obj(d / name)
            except SceneError as exc:
                out.append(str(exc).replace(f"{d}{os.sep}", ""))
    return out


# ---------------------------------------------------------------------------------------------
# shader constant states: indices past the register files

@case
def vertex_shader_constant_i_16(d):
    return base.load("technique t { pass p {\n VertexShaderConstantI[16] = int4(1, 2, 3, 4); } }")


@case
def pixel_shader_constant_b_2048(d):
    return base.load("technique t { pass p {\n PixelShaderConstantB[2048] = true; } }")


@case
def vertex_shader_constant_f_8192(d):
    return base.load("technique t { pass p {\n VertexShaderConstantF[8192] = float4(1, 2, 3, 4); } }")


@case
def pixel_shader_constant_f_224(d):
    return base.load("technique t { pass p {\n PixelShaderConstant[224] = float4(1, 2, 3, 4); } }")


@case
def constant_i_value_running_past_i15(d):
    return _reasons("int4x2 P = {1, 2, 3, 4, 5, 6, 7, 8};\ntechnique t { pass p {\n"
                    " VertexShaderConstantI[15] = <P>; } }", ("radeon9700",))


@case
def constant_f_past_each_cards_file(d):
    return _reasons("float4x4 M;\ntechnique t { pass p {\n VertexShaderConstantF[94] = <M>;\n"
                    " PixelShaderConstantF[31] = float4(1, 2, 3, 4); } }",
                    ("geforce3", "radeon9700", "tnt2"))


@case
def legal_constants_at_the_ends_of_the_register_files(d):
    return _reasons("technique t { pass p {\n VertexShaderConstantI[15] = int4(1, 2, 3, 4);\n"
                    " PixelShaderConstantB[15] = true;\n VertexShaderConstantF[92] = float4x4("
                    + ", ".join("1" * 16) + ");\n PixelShaderConstantF[7] = float4(1, 2, 3, 4); } }",
                    ("geforce3", "radeon9700"))


if __name__ == "__main__":   # as hostile_cases runs its own, with its limits and clock
    import json
    base.CASES.update(CASES)   # run_case finds cases by name in its own table
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    base._limit_memory()
    base.install_alarms()
    import effects  # noqa: F401 - imported before the clock starts
    for name in sys.argv[1:]:
        print(json.dumps({"case": name, "started": True}), flush=True)
        print(json.dumps(base.run_case(name)), flush=True)
