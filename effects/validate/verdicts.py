"""Language errors are errors, card limits are reasons (issue 30).

A `compile ps_2_0 f()` that fxc refuses whatever the target (an undeclared identifier, a type
or syntax error: `EffectError.language`, set where the HLSL compiler raises it) rejects its
technique on every card. The validator still lists it among the technique's reasons
(`Reason.error` holds it), but the selection must not pass over it in silence, as if a card
could not run the technique: a selection that fell past one is answered with that located
error, which the commands print as an error (exit 1) and the viewer shows as a failed reload.
A refusal for the target only (slots, registers, X3511, X4532 on ps_1_x) stays the card's
reason, and the selection goes on to the next technique as D3DX's FindNextValidTechnique does.

    select(effect, profile).passed_over   # the language error the selection fell past, or None
    language_error(validation)            # a technique's language error on a card, or None
                                          # (both in effects.validate.select)
    language_errors(effect)               # every shader of the effect compiled: what `strict`
                                          # loads refuse
"""
from __future__ import annotations

from typing import Any

from effects.base.errors import EffectError
from effects.model import CompileShader, Effect


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
    from effects.shaders.hlsl.lvalues import is_compatibility_warning, strict_message
    from effects.shaders.hlsl.parse import HlslError
    errors: dict[tuple, EffectError] = {}
    if effect.functions:
        # fxc type-checked every function of the file, compiled or not (check.py): an effect
        # whose techniques compile none of them fails on one all the same
        from effects.shaders.hlsl.check import check_unit
        unit_error = check_unit(effect)
        if unit_error is not None:
            errors[(unit_error.location, unit_error.message)] = unit_error
    for value in sorted(set(values), key=lambda v: v.location):
        try:
            shader = compile_state(effect, value)
        except EffectError as err:
            if err.language:
                errors.setdefault((err.location, err.message), err)
            continue
        for w in shader.warnings:
            # what fxc accepted only in compatibility mode (/Gec: a write to a uniform
            # global) is the error it gave without the flag
            if is_compatibility_warning(w.message):
                errors.setdefault((w.location, w.message), HlslError(
                    strict_message(w.message), w.location, source_line=w.source_line,
                    language=True))
    return sorted(errors.values(), key=lambda e: e.location)


def check_language(effect: Effect) -> None:
    """Raise the first language error of the effect's shaders (a `strict` load)."""
    errors = language_errors(effect)
    if errors:
        raise errors[0]


def load_effect(path_or_text: Any, *, strict: bool = False, **options: Any) -> Effect:
    """`effects.frontend.loader.load_effect`, as D3DXCreateEffect loaded: with `strict`, a
    language error in any of the effect's shaders also fails the load (`check_language`).
    Every loader of a user's effect that honours `strict` loads through here."""
    from effects.frontend.loader import load_effect as read
    from effects.shaders.fxlc import check_preshaders
    effect = read(path_or_text, strict=strict, **options)
    check_preshaders(effect)        # an fx_2_0 binary's expression states, read (bad: located)
    if strict:
        check_language(effect)
    return effect
