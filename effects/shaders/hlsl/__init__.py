"""HLSL (the DX9 language) compiled to Direct3D shader assembly for a named target, as fxc did.

    shader = compile_state(effect, compile_shader_value)   # a `compile ps_2_0 f()` state
    shader.text, shader.program, shader.constants, shader.samplers

Pipeline: parse.py (lark grammar grammar/hlsl.lark) → evaluate.py / expressions.py / calls.py /
intrinsics.py (typed symbolic evaluation: inlining, folding, unrolling, flattening over the
DAG of dag.py) → codegen.py / legalize.py (assembly for the target) → the assembler.
"""
from effects.shaders.hlsl.compiler import CompiledShader, compile_shader, compile_state
from effects.shaders.hlsl.parse import HlslError

__all__ = ["CompiledShader", "HlslError", "compile_shader", "compile_state"]
