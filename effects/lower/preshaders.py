"""A pass's effect-level expressions evaluated on the host, as D3DX ran its preshaders.

A state assigned an HLSL expression (`FogDensity = 1.0 / Distance`, `TextureTransform[0] =
mul(A, B)`, `VertexShaderConstant[4] = <Light> * 0.5`), or assigned a parameter whose own
initialiser is one, is evaluated when the pass is lowered, from the parameters' current values,
by the HLSL evaluator (`effects.shaders.hlsl.preshader`). Lowering reads the parameters through
its `RecordedReads` view, so the lowering cache holds the program only while the parameters the
expression read keep their values: a `set` of one lowers (and so evaluates) again on the next
frame. Validation leaves these states unknown, as it does an unset parameter, except a shader
picked from an array of shaders (`PixelShader = (PSArray[ShaderIndex])`): lowering draws, and
validation judges, the element the current values pick (`shader_element`).
"""
from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from effects.device import DeviceState
from effects.errors import EffectError
from effects.model import Effect, Expression, ParamRef, StateAssignment
from effects.shaders.hlsl.preshader import shader_element, state_numbers
from effects.states import lookup_state


def evaluate_expressions(effect: Effect, state: DeviceState) -> DeviceState:
    """`state` with every expression-valued assignment replaced by its numbers (the same
    object when it has none; `state` itself, perhaps a validation's, is left as it is).
    `effect`: the view the parameters are read through."""
    found = _evaluated_all(effect, state)
    if not found:
        return state
    out = state.copy()
    out.values.update(found)
    return out


def evaluate_into(effect: Effect, state: DeviceState) -> None:
    """The same, in `state` itself: for assignments lowering added to its own copy (the
    sampler states a compiled shader's samplers bring)."""
    state.values.update(_evaluated_all(effect, state))


def _evaluated_all(effect: Effect, state: DeviceState) -> dict:
    found = {}
    for key, assignment in state.items():
        expression = _expression_of(effect, assignment.value)
        if expression is not None:
            found[key] = _evaluated(effect, assignment, expression)
    return found


def _expression_of(effect: Effect, value: Any) -> Expression | None:
    if isinstance(value, Expression):
        return value
    if isinstance(value, ParamRef) and value.index is None:
        param = effect.parameter(value.name)   # `FogDensity = <Density>`, Density = 1.0 / D
        if param is not None and isinstance(param.value, Expression):
            return param.value
    return None


def _evaluated(effect: Effect, assignment: StateAssignment, expression: Expression
               ) -> StateAssignment:
    if assignment.name in ("VertexShader", "PixelShader"):
        element = shader_element(effect, expression.text, expression.location)
        if element is not None:            # `(PSArray[ShaderIndex])`: the element it picks
            return replace(assignment, value=element)
    numbers = state_numbers(expression.text, expression.location, effect)
    need = _SIZES.get(getattr(lookup_state(assignment.name), "type", ""))
    if need is not None and numbers.size not in need:
        shown = assignment.name if assignment.index is None else \
            f"{assignment.name}[{assignment.index}]"
        wanted = " or ".join(str(n) for n in sorted(need))
        raise EffectError(f"X3017: {shown} takes {wanted} value(s); '{expression.text.strip()}' "
                          f"has {numbers.size}", expression.location)
    # One component reads as a plain number (every typed reader takes one); more as an array
    # (a vector, a matrix row by row, constant registers four floats each).
    value: Any = float(numbers[0]) if numbers.size == 1 else numbers
    return replace(assignment, value=value)


# How many components an expression may have, by the states table's type of the state (a
# colour is three or four floats, or one packed DWORD); a type not here takes any number
# (shader constants: four floats a register).
_SIZES: dict[str, set[int]] = {
    "bool": {1}, "int": {1}, "dword": {1}, "float": {1}, "enum": {1},
    "color": {1, 3, 4}, "float3": {1, 3}, "float4": {1, 4}, "matrix": {16},
}
