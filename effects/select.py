"""Technique selection: D3DX's FindNextValidTechnique, and policies a user can name.

The default policy is D3DX's: the first valid technique in file order. Others read the
technique annotations `int Quality` (higher is better) and `float Cost` (lower is cheaper),
and can cap the number of passes. Policies combine: `"quality,max-passes=2"`.
No valid technique is a normal answer (None), never an exception.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Union

import numpy as np

from .caps import CapsProfile
from .errors import EffectError, Location
from .model import Effect, Technique
from .validate import Validation, validate_technique


@dataclass(frozen=True)
class Policy:
    """How to choose among valid techniques.

    order: 'first' (file order, as D3DX), 'quality' (highest `int Quality` annotation first,
    file order breaking ties) or 'cost' (lowest `float Cost` first).
    max_passes: techniques with more passes are not considered.
    """

    order: str = "first"
    max_passes: int | None = None

    @classmethod
    def parse(cls, text: str) -> "Policy":
        """Parse 'first', 'quality', 'cost', 'max-passes=N' and comma-joined combinations."""
        order, max_passes = "first", None
        for part in filter(None, (p.strip().lower() for p in text.split(","))):
            if part in ("first", "quality", "cost"):
                order = part
            elif part.startswith("max-passes="):
                try:
                    max_passes = int(part.split("=", 1)[1])
                except ValueError:
                    raise EffectError(f"bad policy '{text}': max-passes needs an integer",
                                      Location("<policy>", 1, 1)) from None
            else:
                raise EffectError(f"unknown selection policy '{part}' (use first, quality, cost, "
                                  "max-passes=N, comma-separated)", Location("<policy>", 1, 1))
        return cls(order, max_passes)


PolicyLike = Union[str, Policy, None]


def _as_policy(policy: PolicyLike) -> Policy:
    if policy is None:
        return Policy()
    return policy if isinstance(policy, Policy) else Policy.parse(policy)


def _annotation_number(tech: Technique, name: str, default: float) -> float:
    a = tech.annotation(name)
    if a is None or isinstance(a.value, str):
        return default
    return float(np.asarray(a.value).reshape(-1)[0])


def rank(effect: Effect, profile: CapsProfile, policy: PolicyLike = "first") -> list[Validation]:
    """Every technique's validation, valid ones first in the order the policy prefers."""
    pol = _as_policy(policy)
    results = [validate_technique(effect, t, profile) for t in effect.techniques]
    position = {id(v): i for i, v in enumerate(results)}

    def key(v: Validation):
        usable = v.ok and (pol.max_passes is None or v.passes <= pol.max_passes)
        if pol.order == "quality":
            score = -_annotation_number(v.technique, "Quality", 0.0)
        elif pol.order == "cost":
            score = _annotation_number(v.technique, "Cost", float("inf"))
        else:
            score = 0.0
        return (not usable, score, position[id(v)])

    return sorted(results, key=key)


def find_valid_technique(effect: Effect, profile: CapsProfile,
                         policy: PolicyLike = "first") -> Technique | None:
    """The technique the policy picks on this card, or None when none is valid."""
    pol = _as_policy(policy)
    if pol == Policy():
        return find_next_valid_technique(effect, profile, None)
    best = rank(effect, profile, pol)
    if best and best[0].ok and (pol.max_passes is None or best[0].passes <= pol.max_passes):
        return best[0].technique
    return None


def find_next_valid_technique(effect: Effect, profile: CapsProfile,
                              after: Technique | str | None = None) -> Technique | None:
    """D3DX's FindNextValidTechnique: the first valid technique after `after` in file order."""
    techniques = effect.techniques
    start = 0
    if after is not None:
        target = effect.technique(after) if isinstance(after, str) else after
        start = next(i for i, t in enumerate(techniques) if t is target) + 1
    for tech in techniques[start:]:
        if validate_technique(effect, tech, profile).ok:
            return tech
    return None
