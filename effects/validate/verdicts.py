"""Language errors are errors, card limits are reasons (issue 30).

A `compile ps_2_0 f()` that fxc refuses whatever the target (an undeclared identifier, a type
or syntax error: `EffectError.language`, set where the HLSL compiler raises it) rejects its
technique on every card. The validator still lists it among the technique's reasons
(`Reason.error` holds it), but the selection must not pass over it in silence, as if a card
could not run the technique: a selection that fell past one is answered with that located
error, which the commands print as an error (exit 1) and the viewer shows as a failed reload.
A refusal for the target only (slots, registers, X3511, X4532 on ps_1_x) stays the card's
reason, and the selection goes on to the next technique as D3DX's FindNextValidTechnique does.

    chosen, error = selection(effect, profile, policy)   # error: the one the selection fell past
    error = passed_over(validations, chosen, policy)     # the same, for validations made already
    errors = language_errors(effect)                     # every shader of the effect compiled:
                                                         # what `strict` loads refuse
"""
from __future__ import annotations

import math
from typing import Any, Sequence

from effects.base.errors import EffectError
from effects.d3d9.caps import CapsProfile
from effects.model import CompileShader, Effect
from effects.validate.select import (Policy, PolicyLike, as_policy, choose, technique_cost,
                                     technique_quality)
from effects.validate.technique import Validation, validate_technique


def language_error(validation: Validation) -> EffectError | None:
    """The first language error among a technique's reasons on a card, or None."""
    return next((r.error for r in validation.reasons if r.error is not None), None)


def _rank_key(policy: Policy, validation: Validation, position: int) -> tuple[float, int]:
    """Where the policy would place the technique were it valid (select.order_validations'
    order among the techniques it accepts)."""
    if policy.order == "quality":
        return (-technique_quality(validation.technique), position)
    if policy.order == "cost":
        cost = technique_cost(validation.technique)
        return (math.inf if cost is None else cost, position)
    return (0.0, position)


def passed_over(results: Sequence[Validation], chosen: Validation | None,
                policy: PolicyLike = "first") -> EffectError | None:
    """The language error of a technique the selection fell past: one that the policy would
    have chosen before `chosen` (before any, when nothing was chosen) had it compiled, and
    that the policy's limits (max-passes, max-cost) do not refuse. `results` are the
    validations in file order (for the default policy, those up to the chosen one suffice)."""
    pol = as_policy(policy)
    position = {id(v.technique): i for i, v in enumerate(results)}   # file order
    bar = None if chosen is None else \
        _rank_key(pol, chosen, position.get(id(chosen.technique), len(results)))
    ahead = []
    for i, v in enumerate(results):
        error = language_error(v)
        if error is None or pol.refusal(v) is not None:
            continue
        key = _rank_key(pol, v, i)
        if bar is None or key < bar:
            ahead.append((key, error))
    return min(ahead, key=lambda item: item[0])[1] if ahead else None


def selection(effect: Effect, profile: CapsProfile,
              policy: PolicyLike = "first") -> tuple[Validation | None, EffectError | None]:
    """The validation of the technique the policy picks on this card (None when none is
    valid), as `select.select_validation` gives it, and the language error it fell past
    (None when it fell past none). The default policy validates in file order up to the
    first valid technique, as FindNextValidTechnique does."""
    pol = as_policy(policy)
    results: list[Validation] = []
    for tech in effect.techniques:
        results.append(validate_technique(effect, tech, profile))
        if pol == Policy() and results[-1].ok:
            break
    chosen = choose(results, pol)
    return chosen, passed_over(results, chosen, pol)


def _shaders(value: Any) -> list[CompileShader]:
    """The `compile` shaders a state or parameter value holds (an array's elements too)."""
    if isinstance(value, CompileShader):
        return [value]
    if isinstance(value, (list, tuple)):
        return [s for item in value for s in _shaders(item)]
    return []


def language_errors(effect: Effect) -> list[EffectError]:
    """Every language error of the effect's `compile` shaders (in its techniques' passes and
    in shader parameters), each compiled for its own target, in file order: what D3DX's
    D3DXCreateEffect, which compiled them all, failed on. Refusals for a target are not
    errors here: the cards judge those."""
    from effects.shaders.hlsl import compile_state   # the HLSL compiler: when asked
    values = [s for param in effect.parameters for s in _shaders(param.value)]
    values += [s for tech in effect.techniques for p in tech.passes for a in p.states
               for s in _shaders(a.value)]
    errors: dict[tuple, EffectError] = {}
    for value in sorted(set(values), key=lambda v: v.location):
        try:
            compile_state(effect, value)
        except EffectError as err:
            if err.language:
                errors.setdefault((err.location, err.message), err)
    return sorted(errors.values(), key=lambda e: e.location)


def check_language(effect: Effect) -> None:
    """Raise the first language error of the effect's shaders (a `strict` load)."""
    errors = language_errors(effect)
    if errors:
        raise errors[0]
