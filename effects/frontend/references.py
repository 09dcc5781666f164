"""State values that name a parameter (`Texture[0] = <BaseTex>`, `VertexShader = (vs)`) must
name a declared parameter of a type the state takes.

The parser keeps `<Name>` as written (a DX8 effect may name a parameter declared later in an
include), so the check is here, once the whole effect is known: an undeclared name or one of
the wrong type (`Texture[0] = <Tint>` with `float4 Tint`) is a validation reason for every
technique that uses it, and a load warning (`effects.frontend.loader`). It lives in the front end, below both.
"""
from __future__ import annotations

from typing import Iterator

from effects.base.errors import Location
from effects.model import Effect, Parameter, ParamRef, Pass, SamplerState, StateAssignment
from effects.d3d9.states import lookup_state

# a state's value type -> the parameter types it can name
_OBJECT_TYPES = {"texture": ("texture",), "sampler": ("sampler",),
                 "vertexshader": ("vertexshader",), "pixelshader": ("pixelshader",)}


def _assignments(states: list[StateAssignment]) -> Iterator[StateAssignment]:
    for a in states:
        yield a
        if isinstance(a.value, SamplerState):
            yield from _assignments(a.value.states)


def _problem(effect: Effect, a: StateAssignment) -> str | None:
    ref = a.value
    if not isinstance(ref, ParamRef) or not a.known:
        return None
    shown = f"{a.name}[{a.index}]" if a.index is not None else a.name
    param: Parameter | None = effect.parameter(ref.name)
    if param is None:
        return f"{shown} = <{ref.name}> names no parameter of the effect"
    info = lookup_state(a.name)
    if info is None:
        return None
    wanted = _OBJECT_TYPES.get(info.type)
    base = param.type.base
    if wanted is not None and base not in wanted:
        return (f"{shown} = <{ref.name}> needs a {wanted[0]} parameter; {ref.name} "
                f"(line {param.location.line}) is a {param.type.spelling or base}")
    if wanted is None and not param.type.is_numeric:
        return (f"{shown} = <{ref.name}> needs a number; {ref.name} "
                f"(line {param.location.line}) is a {param.type.spelling or base}")
    return None


def pass_reference_problems(effect: Effect, p: Pass) -> list[tuple[Location, str]]:
    """(location, message) for every bad parameter reference in one pass's states."""
    out: list[tuple[Location, str]] = []
    _pass_problems(effect, p.states, out)
    return out


def _pass_problems(effect: Effect, states: list[StateAssignment],
                   out: list[tuple[Location, str]]) -> None:
    # `_assignments` and `_problem` spelled out for the states that are neither references nor
    # sampler_state blocks (most of them): validation asks this per pass on every card
    for a in states:
        value = a.value
        if isinstance(value, ParamRef):
            message = _problem(effect, a)
            if message is not None:
                out.append((value.location if value.location.line else a.location, message))
        elif isinstance(value, SamplerState):
            _pass_problems(effect, value.states, out)


def reference_problems(effect: Effect) -> list[tuple[Location, str]]:
    """Every bad parameter reference of the effect: its techniques' passes and the
    sampler_state blocks of its sampler parameters, each once."""
    out: list[tuple[Location, str]] = []
    for param in effect.parameters:
        if isinstance(param.value, SamplerState):
            for a in _assignments(param.value.states):
                message = _problem(effect, a)
                if message is not None:
                    out.append((a.location, message))
    for technique in effect.techniques:
        for p in technique.passes:
            out.extend(pass_reference_problems(effect, p))
    return list(dict.fromkeys(out))
