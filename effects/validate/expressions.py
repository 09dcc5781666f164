"""Expression-valued states (D3DX's preshaders) judged as literal values are.

`PointSize = Size * 2`, `ColorWriteEnable = Mask | Blue`, `TextureTransformFlags[0] = Count |
Projected`: the pass checker reads a copy of the device state in which each such value is what
the one evaluation lowering also runs (`effects.shaders.hlsl.preshader.state_value`) gives at
the parameters' current values, as D3DX's ValidateTechnique ran the preshaders with the values
the effect held. So every check written for literal values (caps bits, write masks, texture
transform flags, anisotropy, point sizes ...) judges them too, and each reason at such a state
says that its value came from the expression and at which parameter values.

What cannot be known before render time is said, not guessed: an expression that reads a
parameter without a value is left unknown (a note: not checked until the application sets it),
and a parameter with a semantic, which the application may set each frame, is named in the
reason as judged at its current value only. An expression that does not evaluate (X3017 ...)
rejects the technique at the expression, as lowering would fail to draw it. The device state
kept in the pass report stays as written: lowering evaluates again at render time.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from effects.d3d9.device import DeviceState
from effects.base.errors import EffectError, Location
from effects.model import Effect, EnumValue, Expression, ParamRef, RecordedReads
from effects.d3d9.states import lookup_state
from effects.validate.values import spelled

_SHADERS = ("VertexShader", "PixelShader")     # judged by the shader checks (shader_element)


@dataclass(frozen=True)
class Evaluated:
    """One expression-valued state as validation judged it."""

    shown: str                 # 'ColorWriteEnable', 'TextureTransformFlags[0]'
    text: str                  # 'Mask | Blue'
    value: str                 # 'Red | Green | Blue', '400'
    reads: tuple[str, ...]     # 'Mask = 3', 'Time = 0 (semantic TIME: ...)'

    def clause(self) -> str:
        at = ", ".join(self.reads) if self.reads else "it reads no parameter"
        return f"{self.shown} = {self.text} is {self.value} at the parameters' current values ({at})"


class ExpressionValues:
    """The pass's expression-valued states evaluated: `state` (a copy with their values, or the
    state itself when it has none), what each was (`by_location`, keyed by the assignment's
    location, where the checks locate their reasons), the ones left for render time
    (`pending`: location -> note; empty for one that does not evaluate) and the ones that do
    not evaluate (`errors`)."""

    def __init__(self, effect: Effect, state: DeviceState) -> None:
        self.by_location: dict[Location, Evaluated] = {}
        self.pending: dict[Location, str] = {}
        self.errors: list[tuple[str, EffectError]] = []
        found = {}
        for key, assignment in state.items():
            expression = _expression_of(effect, assignment.value)
            if expression is None or assignment.name in _SHADERS:
                continue
            value = self._evaluate(effect, assignment.name, assignment.index, expression,
                                   assignment.location)
            if value is not None:
                found[key] = replace(assignment, value=value)
        self.state = state
        if found:
            self.state = state.copy()
            self.state.values.update(found)

    def _evaluate(self, effect: Effect, name: str, index: int | None, expression: Expression,
                  where: Location) -> Any:
        from effects.shaders.hlsl.preshader import expression_value   # lark: when needed
        info = lookup_state(name)
        shown = name if index is None or info is None or info.index == "none" else f"{name}[{index}]"
        text = _flag_names(name, info, expression.text.strip())
        view = RecordedReads(effect)
        known: dict[str, Any] = {}          # the initialisers it evaluated, for the reads below
        try:
            number = expression_value(name, index, expression, view, known)
        except EffectError as err:
            self.errors.append((shown, err))
            self.pending[where] = ""        # the error is the reason: no note besides
            return None
        reads = []
        for what, param_name, _ in view.snapshot():
            param = effect.parameter(param_name) if what == "parameter" else None
            if param is None:
                continue
            if param.value is None:
                self.pending[where] = (f"{shown} = {text} reads {param_name}, which has no value: "
                                       "not checked until the application sets it")
                return None
            read = f"{param_name} = {_number_text(_current(effect, param, known))}"
            if param.semantic:
                read += (f" (semantic {param.semantic}: the application may set another value "
                         "at render time)")
            reads.append(read)
        value = _typed(name, info, number)
        self.by_location[where] = Evaluated(shown, text, _value_text(name, value), tuple(reads))
        return value

    def annotate(self, reasons: list[Any]) -> list[Any]:
        """Each reason located at an evaluated state, with where its value came from."""
        if not self.by_location:
            return reasons
        out = []
        for r in reasons:
            ev = self.by_location.get(r.location)
            out.append(r if ev is None else replace(r, message=f"{r.message}; {ev.clause()}"))
        return out


def _current(effect: Effect, param: Any, known: dict[str, Any]) -> Any:
    """A parameter's value as the expression read it: one whose initialiser is itself an
    expression (`float P1 = P0 * 2;`) is that expression's numbers, as the state's evaluation
    found them (`known`), else evaluated the same way."""
    if not isinstance(param.value, (Expression, ParamRef)):
        return param.value
    if param.name not in known:
        from effects.shaders.hlsl.expressions import initializer_text   # lark: when needed
        from effects.shaders.hlsl.preshader import initializer_numbers
        init = initializer_text(param)
        known[param.name] = np.asarray(initializer_numbers(
            init.text, init.location, effect, host_values=True, known=known))
    return known[param.name]


def _expression_of(effect: Effect, value: Any) -> Expression | None:
    """The expression a state is assigned, directly or through a parameter whose initialiser is
    one (`FogDensity = <Density>`, `float Density = 1.0 / Distance;`), as lowering finds it."""
    if isinstance(value, Expression):
        return value
    if isinstance(value, ParamRef) and value.index is None:
        param = effect.parameter(value.name)
        if param is not None and isinstance(param.value, Expression):
            return param.value
    return None


def _typed(name: str, info: Any, number: Any) -> Any:
    """An enum state's number as the enum value it is (a flags state's names, smallest first),
    so the checks read and spell it as they do a literal; others (and a number no names make
    up) as they are."""
    table = info.enum if info is not None and info.type == "enum" else None
    if table is None or isinstance(number, np.ndarray):
        return number
    n = int(number)
    if table.flags:
        # largest first, so a field such as TTFF's counts (Count3 = 3) is one name, not two
        rest, names = n, []
        for k, v in sorted(table.values.items(), key=lambda kv: -kv[1]):
            if v and rest & v == v:
                names.append(k)
                rest -= v
        return EnumValue(tuple(reversed(names)), n) if names and not rest else number
    found = next((k for k, v in table.values.items() if v == n), None)
    return EnumValue((found,), n) if found is not None else number


def _flag_names(name: str, info: Any, text: str) -> str:
    """`Mask | 4` as the effect wrote it, `Mask | Blue`: the loader keeps flags OR-ed with a
    parameter as an expression with the flag names as their numbers (states._flags_expression)."""
    table = info.enum if info is not None and info.type == "enum" else None
    if table is None or not table.flags or " | " not in text:
        return text
    by_number = {v: k for k, v in reversed(list(table.values.items()))}
    return " | ".join(spelled(name, by_number[int(t)]) if t.isdigit() and int(t) in by_number
                      else t for t in text.split(" | "))


def _value_text(name: str, value: Any) -> str:
    if isinstance(value, EnumValue):
        return " | ".join(spelled(name, n) for n in value.names)
    return _number_text(value)


def _number_text(value: Any) -> str:
    array = np.ravel(np.asarray(value, dtype=np.float64)) if not isinstance(value, str) else None
    if array is None or array.size == 0:
        return str(value)
    if array.size == 1:
        return f"{array[0]:g}"
    return "(" + ", ".join(f"{x:g}" for x in array) + ")"
