"""Technique selection: D3DX's FindNextValidTechnique, and policies a user can name.

The default policy is D3DX's: the first valid technique in file order. Other policies read
two technique annotations (the convention of fxfiles/README.md):

    int   Quality   how good the technique looks; higher is better (default 0);
    float Cost      estimated per-pixel work; lower is cheaper (default: unknown, ranked last).

A policy is written as comma-separated parts, each at most once:

    first            file order (D3DX); the default
    quality          the highest Quality first, file order breaking ties
    cost             the lowest Cost first, file order breaking ties
    max-passes=N     techniques with more than N passes are not chosen
    max-cost=X       techniques whose Cost is above X (or unknown) are not chosen

so "quality,max-passes=1" is the best-looking single-pass technique and "quality,max-cost=4"
the best-looking one under a budget. No valid technique is a normal answer (None, with every
reason in `rank`), never an exception.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Union

import numpy as np

from effects.d3d9.caps import CapsProfile
from effects.base.errors import EffectError, Location
from effects.model import Effect, Technique
from effects.validate.technique import Validation, validate_technique

_POLICY_LOCATION = Location("<policy>", 1, 1)
ORDERS = ("first", "quality", "cost")


@dataclass(frozen=True)
class Policy:
    """How to choose among valid techniques: an order and optional limits."""

    order: str = "first"
    max_passes: int | None = None
    max_cost: float | None = None

    @classmethod
    def parse(cls, text: str) -> "Policy":
        """Parse 'first', 'quality', 'cost', 'max-passes=N', 'max-cost=X', comma-joined."""
        order: str | None = None
        limits: dict[str, float | int] = {}
        parts = [p.strip().lower() for p in text.split(",")]
        if not any(parts):
            raise EffectError("empty selection policy (use first, quality, cost, max-passes=N, "
                              "max-cost=X, comma-separated)", _POLICY_LOCATION)
        for part in parts:
            if part in ORDERS:
                if order is not None and order != part:
                    raise EffectError(f"bad policy '{text}': '{order}' and '{part}' are both orders; "
                                      "name one", _POLICY_LOCATION)
                order = part
                continue
            key, eq, value = part.partition("=")
            if key in ("max-passes", "max-cost") and eq:
                limits[key] = _limit(text, key, value.strip())
                continue
            raise EffectError(f"unknown selection policy '{part}' (use first, quality, cost, "
                              "max-passes=N, max-cost=X, comma-separated)", _POLICY_LOCATION)
        max_passes = limits.get("max-passes")
        return cls(order or "first", None if max_passes is None else int(max_passes),
                   limits.get("max-cost"))

    def __str__(self) -> str:
        parts = [self.order]
        if self.max_passes is not None:
            parts.append(f"max-passes={self.max_passes}")
        if self.max_cost is not None:
            parts.append(f"max-cost={self.max_cost:g}")
        return ",".join(parts)

    def refusal(self, validation: Validation) -> str | None:
        """Why the policy will not choose this (valid) technique, or None when it may."""
        if self.max_passes is not None and validation.passes > self.max_passes:
            return (f"the technique takes {validation.passes} passes; the policy allows at most "
                    f"{self.max_passes}")
        if self.max_cost is not None:
            cost = technique_cost(validation.technique)
            if cost is None:
                return f"the technique has no Cost annotation; the policy allows at most {self.max_cost:g}"
            if cost > self.max_cost:
                return f"the technique's Cost is {cost:g}; the policy allows at most {self.max_cost:g}"
        return None

    def accepts(self, validation: Validation) -> bool:
        return validation.ok and self.refusal(validation) is None


def _limit(text: str, key: str, value: str) -> float | int:
    try:
        number = int(value) if key == "max-passes" else float(value)
    except ValueError:
        kind = "an integer" if key == "max-passes" else "a number"
        raise EffectError(f"bad policy '{text}': {key} needs {kind}, not '{value}'",
                          _POLICY_LOCATION) from None
    if number < 0 or (isinstance(number, float) and not math.isfinite(number)):
        raise EffectError(f"bad policy '{text}': {key} must be a finite number >= 0", _POLICY_LOCATION)
    return number


PolicyLike = Union[str, Policy, None]


def as_policy(policy: PolicyLike) -> Policy:
    """A Policy from a Policy, a policy string, or None (the default)."""
    if policy is None:
        return Policy()
    return policy if isinstance(policy, Policy) else Policy.parse(policy)


_as_policy = as_policy   # the name earlier callers used


def _annotation_number(tech: Technique, name: str) -> float | None:
    a = tech.annotation(name)
    if a is None or isinstance(a.value, str):
        return None
    flat = np.asarray(a.value).reshape(-1)
    if not flat.size or flat.dtype.kind not in "biuf":
        return None
    return float(flat[0])


def technique_quality(tech: Technique) -> float:
    """The `int Quality` annotation (0 when absent)."""
    q = _annotation_number(tech, "Quality")
    return 0.0 if q is None else q


def technique_cost(tech: Technique) -> float | None:
    """The `float Cost` annotation, or None when absent."""
    return _annotation_number(tech, "Cost")


def rank(effect: Effect, profile: CapsProfile, policy: PolicyLike = "first") -> list[Validation]:
    """Every technique's validation: those the policy accepts first, in its preferred order,
    then the others in file order. The first entry is the choice when `policy.accepts` it."""
    pol = as_policy(policy)
    results = [validate_technique(effect, t, profile) for t in effect.techniques]
    return order_validations(results, pol)


def order_validations(results: list[Validation], policy: PolicyLike = "first") -> list[Validation]:
    """`rank` for validations already made (in file order)."""
    pol = as_policy(policy)
    position = {id(v): i for i, v in enumerate(results)}

    def key(v: Validation):
        if not pol.accepts(v):
            return (1, 0.0, position[id(v)])
        if pol.order == "quality":
            score = -technique_quality(v.technique)
        elif pol.order == "cost":
            cost = technique_cost(v.technique)
            score = math.inf if cost is None else cost
        else:
            score = 0.0
        return (0, score, position[id(v)])

    return sorted(results, key=key)


def choose(results: list[Validation], policy: PolicyLike = "first") -> Validation | None:
    """The validation of the technique the policy picks, or None."""
    pol = as_policy(policy)
    ordered = order_validations(results, pol)
    return ordered[0] if ordered and pol.accepts(ordered[0]) else None


def select_validation(effect: Effect, profile: CapsProfile,
                      policy: PolicyLike = "first") -> Validation | None:
    """The validation of the technique the policy picks on this card (None when none is
    valid). The default policy validates in file order and stops at the first valid one, as
    FindNextValidTechnique does; the others rank every technique."""
    pol = as_policy(policy)
    if pol == Policy():
        for tech in effect.techniques:
            validation = validate_technique(effect, tech, profile)
            if validation.ok:
                return validation
        return None
    return choose([validate_technique(effect, t, profile) for t in effect.techniques], pol)


def find_valid_technique(effect: Effect, profile: CapsProfile,
                         policy: PolicyLike = "first") -> Technique | None:
    """The technique the policy picks on this card, or None when none is valid."""
    chosen = select_validation(effect, profile, policy)
    return chosen.technique if chosen else None


def find_next_valid_technique(effect: Effect, profile: CapsProfile,
                              after: Technique | str | None = None) -> Technique | None:
    """D3DX's FindNextValidTechnique: the first valid technique after `after` in file order
    (from the start when `after` is None)."""
    techniques = effect.techniques
    start = 0
    if after is not None:
        target = effect.technique(after) if isinstance(after, str) else after
        index = next((i for i, t in enumerate(techniques) if t is target), None)
        if index is None:
            raise EffectError(f"technique '{getattr(target, 'name', target)}' is not one of this "
                              "effect's techniques", Location(effect.path, 1, 1))
        start = index + 1
    for tech in techniques[start:]:
        if validate_technique(effect, tech, profile).ok:
            return tech
    return None
