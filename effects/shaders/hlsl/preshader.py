"""HLSL values computed on the host (what D3DX compiled to a "preshader" and ran on the CPU).

Effect level: a parameter initialiser kept as text (a struct's `{ {..}, {..}, 32.0 }`) as the
flat list of its numbers, and a state's expression (`FogDensity = 1.0 / Distance`,
`TextureTransform[0] = mul(A, B)`, `VertexShaderConstant[4] = <Light> * 0.5`) with the
parameters' current values. Both go through the one HLSL evaluator: in a preshader context
(`Context.host_values`) a uniform global reads as a constant, its current value, so the whole
expression folds to numbers; what cannot fold (a sampler, a texture read) is fxc's X3013,
located.

Inside a ps_1_x shader (`preshade_ps1`): what reads only uniforms and literals (`-LightDir`,
`Intensity * 2`, `normalize(LightDir)`) is taken out of the shader, as fxc took it, and
computed on the host into a constant register of its own before each draw. DX8 pixel
shaders have eight constants in [-1, 1] and few slots, and ps_1_4 allows no source modifier
on a constant, so per-pixel code for such values is often impossible there."""
from __future__ import annotations

import re
from typing import Any

import numpy as np

from effects.base.errors import EffectError, Location
from effects.model import Effect, Expression, ParamRef, Preshader
from effects.shaders.hlsl.budget import out_of_stack
from effects.shaders.hlsl.dag import Operand, host_computable, reachable
from effects.shaders.hlsl.parse import Origin, parse
from effects.shaders.hlsl.shader import PRESHADER_NAME, ShaderPreshader
from effects.shaders.hlsl.types import scalar, vector
from effects.d3d9.states import lookup_state

# `<Light>` / `<Lights[2]>`: the effect syntax for a parameter reference inside an expression.
# The brackets are blanked to spaces, so every column of the text stays where it was.
_REFERENCE = re.compile(r"<(\s*[A-Za-z_]\w*\s*(?:\[\s*\d+\s*\]\s*)?)>")


def initializer_numbers(text: str, location: Location, effect: Effect | None = None,
                        host_values: bool = False,
                        known: dict[str, np.ndarray] | None = None) -> list[float]:
    """The numbers of a constant initialiser, in order (X3013 if it is not constant).
    `host_values`: uniform globals read as their current values (a preshader), not as
    registers unknown until the shader runs. `known`: the parameters' initialisers already
    evaluated (name -> numbers), read and filled in: callers evaluating several expressions
    of one effect at the same parameter values share them."""
    from effects.shaders.hlsl.context import Context, Target, type_names
    from effects.shaders.asm.versions import VERSIONS
    from effects.shaders.hlsl.evaluate import Evaluator
    text = _REFERENCE.sub(lambda m: " " + m.group(1) + " ", text)
    origin = Origin(location, text)
    tree = parse(text, "initializer", origin, type_names(effect) if effect else frozenset())
    ctx = Context(effect or Effect(location.path), Target("vs_3_0", VERSIONS["vs_3_0"]),
                  host_values=host_values)
    if known is not None:
        ctx.initialized = known          # expressions.global_value reads and fills it
    ev = Evaluator(ctx, origin)
    try:
        comps = ev.flatten_list(tree)
    except RecursionError:
        raise out_of_stack(location, origin.line_text(1)) from None
    out = []
    for c in comps:
        v = c.const_values()
        if v is None:
            raise origin.error("X3013: the initializer is not a compile-time constant", tree)
        out.append(float(v[0]))
    return out


def parameter_numbers(effect: Effect, name: str) -> list[float] | None:
    """A parameter's numbers in declaration order at its current value (its initialiser
    evaluated where that is an expression), read through `effect`; None without a value."""
    p = effect.parameter(name)
    if p is None or p.value is None:
        return None
    v = p.value
    if isinstance(v, Expression):
        return initializer_numbers(v.text, v.location, effect, host_values=True)
    if isinstance(v, (list, tuple)):
        return [float(x) for x in np.asarray(v, dtype=np.float64).reshape(-1)]
    try:
        return [float(x) for x in np.asarray(v, dtype=np.float64).reshape(-1)]
    except (TypeError, ValueError):
        return None


def state_numbers(text: str, location: Location, effect: Effect,
                  known: dict[str, np.ndarray] | None = None) -> np.ndarray:
    """A state assignment's expression evaluated with the parameters' current values: its
    components, flat (a matrix row by row, as the effect writes one)."""
    numbers = initializer_numbers(text, location, effect, host_values=True, known=known)
    if not all(np.isfinite(numbers)):
        raise Origin(location, text).error(
            f"X3013: '{text.strip()}' does not evaluate to finite numbers ({numbers})", location)
    return np.asarray(numbers, dtype=np.float64)


def state_value(name: str, index: int | None, text: str, location: Location, effect: Effect,
                known: dict[str, np.ndarray] | None = None) -> Any:
    """A state's expression as the value its typed readers take (lowering draws it, validation
    judges it): one component a plain number (every typed reader takes one), more an array (a
    vector, a matrix row by row, constant registers four floats each); X3017 when the state's
    type takes another count."""
    return _state_typed(name, index, state_numbers(text, location, effect, known), text, location)


def expression_value(name: str, index: int | None, value: Expression, effect: Effect,
                     known: dict[str, np.ndarray] | None = None) -> Any:
    """`state_value` of any expression a state holds: source text, or the preshader an fx_2_0
    binary compiled it to (effects.shaders.fxlc), run at the parameters' current values."""
    if isinstance(value, Preshader):
        return _state_typed(name, index, _preshader_numbers(value, effect), value.text,
                            value.location)
    return state_value(name, index, value.text, value.location, effect, known)


def _preshader_numbers(value: Preshader, effect: Effect) -> np.ndarray:
    """A binary's preshader run at the parameters' current values. An infinity or NaN is
    passed on, as D3DX set it (Wine's test_effect_preshader: `1 / opvect1` with opvect1 =
    (0, -0, -2.2, FLT_MAX) sets a light's diffuse to (inf, -inf, -0.4545, 2.9e-39)); a source
    expression's is refused (state_numbers, X3013)."""
    from effects.shaders.fxlc import numbers
    return numbers(value, effect, lambda name: parameter_numbers(effect, name),
                   value.components or None)


def _state_typed(name: str, index: int | None, numbers: np.ndarray, text: str,
                 location: Location) -> Any:
    need = _SIZES.get(getattr(lookup_state(name), "type", ""))
    if need is not None and numbers.size not in need:
        shown = name if index is None else f"{name}[{index}]"
        wanted = " or ".join(str(n) for n in sorted(need))
        raise EffectError(f"X3017: {shown} takes {wanted} value(s); '{text.strip()}' "
                          f"has {numbers.size}", location)
    return float(numbers[0]) if numbers.size == 1 else numbers


# How many components an expression may have, by the states table's type of the state (a
# colour is three or four floats, or one packed DWORD); a type not here takes any number
# (shader constants: four floats a register).
_SIZES: dict[str, set[int]] = {
    "bool": {1}, "int": {1}, "dword": {1}, "float": {1}, "enum": {1},
    "color": {1, 3, 4}, "float3": {1, 3}, "float4": {1, 4}, "matrix": {16},
}


# `PixelShader = (PSArray[ShaderIndex]);`: one element of an array of shaders, picked by an
# expression of the parameters (D3DX's preshader selects the shader when the pass begins).
_SHADER_ELEMENT = re.compile(r"^\s*\(?\s*([A-Za-z_]\w*)\s*\[(.+)\]\s*\)?\s*$", re.DOTALL)
_SHADER_TYPES = ("vertexshader", "pixelshader")


def shader_element(effect: Effect, text: str, location: Location) -> ParamRef | None:
    """The element of a shader-array parameter that `text` (`(PSArray[ShaderIndex])`) picks at
    the parameters' current values, as a reference to it; None when `text` is not an index
    into an array of shaders. The index truncates to an int, as HLSL converts; one past the
    array is a located error naming the value."""
    m = _SHADER_ELEMENT.match(text)
    if m is None:
        return None
    param = effect.parameter(m.group(1))
    if param is None or not param.array or param.type.base not in _SHADER_TYPES:
        return None
    return _element(param, state_numbers(m.group(2), location, effect), text, location)


def expression_element(effect: Effect, value: Expression) -> ParamRef | None:
    """`shader_element` of any expression a shader state holds: source text, or an fx_2_0
    binary's array selector (a preshader computing the index)."""
    if not isinstance(value, Preshader):
        return shader_element(effect, value.text, value.location)
    if value.selects is None:
        return None
    param = effect.parameter(value.selects)
    if param is None:
        return None
    return _element(param, _preshader_numbers(value, effect), value.text, value.location)


def _element(param: Any, numbers: np.ndarray, text: str, location: Location) -> ParamRef:
    # the declared length: an array without initialiser holds NULL shaders (an fx_2_0 binary
    # writes them as empty objects), as many as it declares
    count = param.array[0] if param.array else 0
    if numbers.size != 1:
        raise EffectError(f"X3017: the index of {param.name} in '{text.strip()}' has "
                          f"{numbers.size} components, it takes one", location)
    index = int(numbers[0])
    if not 0 <= index < count:
        raise EffectError(f"'{text.strip()}' picks {param.name}[{index}] at the parameters' "
                          f"current values; {param.name} holds {count} shaders", location)
    return ParamRef(param.name, index=index, location=location)


# ------------------------------------------------------------------------------------------------
# A ps_1_x shader's preshader

def preshade_ps1(graph: Any, roots: list[Any], negated_constants: bool,
                 uniform_types: dict) -> dict[str, ShaderPreshader]:
    """Take what reads only uniforms and literals out of a ps_1_x shader's DAG: each operand of
    per-pixel work (or root: an output or kill component) whose node computes from uniforms
    alone now reads a new uniform leaf, and its computation becomes that leaf's preshader.
    With `negated_constants` False (ps_1_4), a negated uniform operand does too, its negation
    folded in. The DAG is rewritten in place; `uniform_types` gets each new register's type.
    Returns the preshaders by register name."""
    nodes = reachable(r.node for r in roots)
    host = host_computable(nodes)
    made: dict[tuple, Any] = {}    # (node id, negation folded) -> the new leaf
    preshaders: dict[str, ShaderPreshader] = {}

    def moved(a: Any) -> Any:
        node = a.node
        if not host[node.id] or node.op == "const":
            return a
        fold_negation = a.negate and not negated_constants
        if node.op == "uniform" and not fold_negation:
            return a
        key = (node.id, fold_negation)
        leaf = made.get(key)
        if leaf is None:
            name = PRESHADER_NAME.format(len(preshaders))
            preshaders[name] = _preshader_steps(node, fold_negation)
            uniform_types[name] = scalar() if node.width == 1 else vector("float", node.width)
            leaf = made[key] = graph.leaf("uniform", (name, 0), node.width, node.location).node
        return Operand(leaf, a.swizzle, a.negate and not fold_negation)

    for node in nodes:
        if not host[node.id]:
            node.args = tuple(moved(a) for a in node.args)
    roots[:] = [moved(r) for r in roots]
    return preshaders


def _preshader_steps(node: Any, negate: bool) -> ShaderPreshader:
    index: dict[int, int] = {}
    steps: list[tuple] = []
    for n in reachable([node]):
        if n.op == "const":
            steps.append(("const", tuple(n.value)))
        elif n.op == "uniform":
            steps.append(("uniform", n.key[0], n.key[1], n.width))
        else:
            steps.append((n.op, n.width, tuple((index[a.node.id], tuple(a.swizzle), a.negate)
                                               for a in n.args)))
        index[n.id] = len(steps) - 1
    if negate:
        steps.append(("mov", node.width, ((len(steps) - 1, tuple(range(node.width)), True),)))
    return ShaderPreshader(tuple(steps), node.width)

