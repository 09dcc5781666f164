"""HLSL (the DX9 language) compiled to Direct3D shader assembly for a named target, as fxc did.

    shader = compile_state(effect, compile_shader_value)   # a `compile ps_2_0 f()` state
    shader.text, shader.program, shader.constants, shader.samplers

Pipeline: parse.py (lark grammar grammar/hlsl.lark) → evaluate.py / expressions.py / calls.py /
intrinsics.py (typed symbolic evaluation: inlining, folding, unrolling, flattening over the
DAG of dag.py) → codegen.py / legalize.py (assembly for the target) → the assembler.
"""
from __future__ import annotations

from typing import Any

__all__ = ["CompiledShader", "HlslError", "compile_shader", "compile_state"]

# Loaded when first asked for (PEP 562): a shader the compile cache already holds is handed
# out by cache.compile_state without the compiler, its grammar or lark.
_WHERE = {"CompiledShader": "shader", "compile_state": "cache", "compile_shader": "compiler",
          "HlslError": "parse"}


def __getattr__(name: str) -> Any:
    module = _WHERE.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    import importlib
    value = getattr(importlib.import_module(f"{__name__}.{module}"), name)
    globals()[name] = value
    return value
