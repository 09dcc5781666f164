"""compile_shader as a named list of passes (effects/shaders/hlsl/compiler.py PASSES): each
run up to itself and looked at alone -- what it sets, what it changes of what came before."""
from __future__ import annotations

import pytest

import effects
from effects.base.errors import EffectError, Location
from effects.model import ShaderBlock
from effects.shaders.asm import assemble, check
from effects.shaders.hlsl import compiler
from effects.shaders.hlsl.compiler import PASSES, Compilation, run_passes
from effects.shaders.hlsl.legalize import _choose
from effects.shaders.hlsl.records import needed


def compilation(functions: str, entry: str, target: str, until) -> Compilation:
    fx = effects.load_effect(functions + "\ntechnique T { pass P { } }\n")
    return run_passes(Compilation(fx, entry, target, (), Location(fx.path, 1, 1)), until)


def test_the_passes_in_order():
    assert [p.__name__ for p in PASSES] == [
        "bind", "evaluate", "bind_outputs", "preshade", "reach", "layout_constants", "fuse",
        "select", "optimise", "legalize_code", "allocate_registers", "write_program",
        "list_program"]


def test_bind_declares_the_inputs_by_semantic_and_refuses_a_missing_entry():
    c = compilation("float4 VS(float4 p : POSITION, float3 n : NORMAL) : POSITION { return p; }",
                    "VS", "vs_2_0", compiler.bind)
    assert [(r, d.usage, d.register.name) for r, d in c.binder.dcls.items()] == [
        ("v0", "position", "v0"), ("v1", "normal", "v1")]
    assert c.outputs == [] and c.program is None          # nothing after it ran
    with pytest.raises(EffectError, match="X3501"):
        compilation("float4 VS() : POSITION { return 0; }", "Nope", "vs_2_0", compiler.bind)


def test_reach_keeps_only_what_the_outputs_read():
    fn = "float4 PS(float2 uv : TEXCOORD0) : COLOR { float u = uv.x * 3; return float4(uv, 0, 1); }"
    c = compilation(fn, "PS", "ps_2_0", compiler.reach)
    assert "mul" not in {n.op for n in c.nodes}
    used = fn.replace("float4(uv, 0, 1)", "float4(uv, u, 1)")
    assert "mul" in {n.op for n in compilation(used, "PS", "ps_2_0", compiler.reach).nodes}


def test_layout_constants_by_explicit_register_then_declaration_order():
    # one register each: A before C as declared, though the code reads C first (fxc's rules:
    # tests/shaders/hlsl/test_constant_layout.py)
    fn = ("float4 A; float4 B : register(c5); float4 C;\n"
          "float4 PS() : COLOR { return C * A + B; }")
    c = compilation(fn, "PS", "ps_2_0", compiler.layout_constants)
    assert c.constants == {"B": 5, "A": 0, "C": 1}


MAD = "float4 A; float4 B; float4 PS(float4 c : COLOR0) : COLOR { return c * A + B; }"


def test_fuse_makes_mad_of_mul_and_add():
    c = compilation(MAD, "PS", "ps_2_0", compiler.layout_constants)
    assert {"mul", "add"} <= {n.op for n in c.gen.reachable()}
    compiler.fuse(c)
    ops = {n.op for n in c.gen.reachable()}
    assert "mad" in ops and not {"mul", "add"} & ops


def test_select_emits_on_virtual_temporaries_then_optimise_removes_the_copy():
    c = compilation(MAD, "PS", "ps_2_0", compiler.select)
    assert [i.opcode for i in c.gen.instrs] == ["mad", "mov"]
    assert c.gen.instrs[0].dst.kind == "vr"               # no physical r# before allocation
    compiler.optimise(c)
    # the mad writes oC0 itself: oC0 takes mov only on ps_2_0, so it stays a mad + mov
    assert [i.opcode for i in c.gen.instrs] == ["mad", "mov"]
    c = compilation("float4 K; float4 PS() : COLOR { return K; }", "PS", "ps_2_0", compiler.select)
    assert len(c.gen.instrs) == 2                          # mov vr, c0; mov oC0, vr
    compiler.optimise(c)
    assert len(c.gen.instrs) == 1                          # mov oC0, c0


def test_legalize_builds_a_swizzle_ps_2_0_lacks():
    fn = "float4 K; float4 PS(float4 c : COLOR0) : COLOR { return c * K.xwzy; }"
    c = compilation(fn, "PS", "ps_2_0", compiler.optimise)
    rule = "ps20"
    assert any(_choose(needed(s), rule) is None for i in c.gen.instrs for s in i.srcs)
    before = len(c.gen.instrs)
    compiler.legalize_code(c)
    assert len(c.gen.instrs) > before
    assert all(_choose(needed(s), rule) is not None for i in c.gen.instrs for s in i.srcs)


def test_allocate_gives_every_temporary_a_register_of_the_version():
    c = compilation(MAD, "PS", "ps_2_0", compiler.allocate_registers)
    temps = {s.index for i in c.code.instrs for s in i.srcs if s.kind == "vr"}
    assert temps and set(c.code.alloc) >= temps and max(c.code.alloc.values()) < 12
    assert c.code.constants == {"A": (0, 1), "B": (1, 1)}


@pytest.mark.parametrize("target", ["ps_2_0", "ps_1_1", "ps_1_4", "ps_3_0"])
def test_write_makes_the_records_the_assembler_makes_of_the_listing(target):
    c = compilation(MAD, "PS", target, None)
    assert check(c.program) == []
    parsed = assemble(ShaderBlock("pixel", target, c.shader.text))
    assert parsed.instructions == c.program.instructions
    assert parsed.dcls == c.program.dcls and parsed.defs == c.program.defs
    assert all(i.location.path == c.fdef.origin.at(c.fdef.tree).path for i in c.program.instructions)


def test_no_text_is_parsed_back_when_compiling(monkeypatch):
    from effects.shaders.asm import parser

    def refuse(self):
        raise AssertionError("the compiler parsed assembly text")
    monkeypatch.setattr(parser._Parser, "parse", refuse)
    fx = effects.load_effect(MAD + "\ntechnique T { pass P { } }\n")
    for target in ("ps_2_0", "ps_1_4", "ps_3_0"):
        assert compiler.compile_shader(fx, "PS", target).program.instructions
