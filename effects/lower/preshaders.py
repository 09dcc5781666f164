"""A pass's effect-level expressions evaluated on the host, as D3DX ran its preshaders.

A state assigned an HLSL expression (`FogDensity = 1.0 / Distance`, `TextureTransform[0] =
mul(A, B)`, `VertexShaderConstant[4] = <Light> * 0.5`), or assigned a parameter whose own
initialiser is one, is evaluated when the pass is lowered, from the parameters' current values,
by the HLSL evaluator (`effects.shaders.hlsl.preshader`). Lowering reads the parameters through
its `RecordedReads` view, so the lowering cache holds the program only while the parameters the
expression read keep their values: a `set` of one lowers (and so evaluates) again on the next
frame. Validation judges the value the same evaluation gives at the parameters' current values
(`effects.validate.expressions`), and a shader picked from an array of shaders (`PixelShader =
(PSArray[ShaderIndex])`) as the element the current values pick (`shader_element`).
"""
from __future__ import annotations

from dataclasses import replace
from typing import Any

from effects.d3d9.device import DeviceState
from effects.model import Effect, Expression, ParamRef, StateAssignment
from effects.shaders.hlsl.preshader import expression_element, expression_value


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
        element = expression_element(effect, expression)
        if element is not None:            # `(PSArray[ShaderIndex])`: the element it picks
            return replace(assignment, value=element)
    return replace(assignment, value=expression_value(assignment.name, assignment.index,
                                                      expression, effect))
