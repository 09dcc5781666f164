"""Technique selection: D3DX's FindNextValidTechnique, and policies a user can name.

The default policy is D3DX's: the first valid technique in file order. Other policies read
two technique annotations (the convention of fxfiles/README.md):

    int   Quality   how good the technique looks; higher is better (default 0);
    float Cost      estimated per-pixel work; lower is cheaper (default: unknown, ranked last).

A policy is written as comma-separated parts, each at most once:

    first            file order (D3DX); the default
    quality          the highest Quality first, file order breaking ties
    cost             the lowest Cost first, file order breaking ties
    fidelity         the technique whose picture on this card is most like the effect's best
                     technique's (SSIM, measured by the host: effects.host.fidelity); those
                     within FIDELITY_TIE of the highest SSIM are alike, and among them the
                     least per-pixel work (`technique_work`) is drawn, then file order;
                     those not measured (not drawn, or the best picture shows nothing)
                     follow in file order
    max-passes=N     techniques with more than N passes are not chosen
    max-cost=X       techniques whose Cost is above X (or unknown) are not chosen

so "quality,max-passes=1" is the best-looking single-pass technique and "quality,max-cost=4"
the best-looking one under a budget. No valid technique is a normal answer (a `Selection`
with nothing chosen and every reason), never an exception.

`select` is the one route by which a technique is chosen: the runtime, the viewer's reloads,
`effects render/matrix/validate/doctor` and `Effect.find_valid_technique` all ask it.

The fidelity order needs pictures, and pictures are made above this floor (a render is the
host's work): its Policy carries `likeness`, a function the host supplies that scores the
valid techniques from their Validations (effects.host.fidelity.policy_for). The ranking stays
here, so every route ranks the same scores the same way; a route handed that one Policy
object gives the one answer.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Mapping, Sequence, Union

import numpy as np

from effects.d3d9.caps import CapsProfile
from effects.base.errors import EffectError, Location
from effects.model import Effect, Technique
from effects.validate.technique import PassReport, Validation, validate_technique

_POLICY_LOCATION = Location("<policy>", 1, 1)

# What the host supplies for the fidelity order: given the validations in file order (None for
# those the policy may not choose), each valid one's likeness to the effect's best technique
# on its card (SSIM, 1 alike) by position; None or absent where it could not be measured.
Likeness = Callable[[Sequence["Validation | None"]], Mapping[int, "float | None"]]
ORDERS = ("first", "quality", "cost", "fidelity")
# How far below the highest SSIM on a card a technique's SSIM may lie and still count as alike:
# among the alike, the least work (`technique_work`) is drawn, then file order. Rounding to the
# shown three places was no tie rule: specular_bump.fx's ps.1.1 table and multiply techniques on
# a Radeon 8500 draw pictures within one level of each other, score 0.9773 and 0.9775, round
# apart, and the 10-slot technique won. The band cannot reach the third place: fast_phong.fx's
# Gouraud scores 0.995 against Phong's 1 on refrast with its highlight visibly faceted (57
# pixels more than 8 levels off: a small area moves the mean little), while multilight.fx's
# fixed-function technique scores 0.997 on a GeForce FX with no pixel more than 8 levels off.
# So only differences in the fourth place are taken for noise (tests/host/test_fidelity.py).
FIDELITY_TIE = 0.001
_POLICY_NAMES = "first, quality, cost, fidelity, max-passes=N, max-cost=X, comma-separated"


@dataclass(frozen=True)
class Policy:
    """How to choose among valid techniques: an order and optional limits."""

    order: str = "first"
    max_passes: int | None = None
    max_cost: float | None = None
    # the fidelity order's scores, supplied by the host (effects.host.fidelity.policy_for);
    # not part of equality: two policies differ by what they say, and caches that key on a
    # policy add its likeness by identity (effects.host.runtime._selected)
    likeness: "Likeness | None" = field(default=None, compare=False, repr=False)

    @classmethod
    def parse(cls, text: str) -> "Policy":
        """Parse 'first', 'quality', 'cost', 'fidelity', 'max-passes=N', 'max-cost=X',
        comma-joined."""
        order: str | None = None
        limits: dict[str, float | int] = {}
        parts = [p.strip().lower() for p in text.split(",")]
        if not any(parts):
            raise EffectError(f"empty selection policy (use {_POLICY_NAMES})", _POLICY_LOCATION)
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
            raise EffectError(f"unknown selection policy '{part}' (use {_POLICY_NAMES})",
                              _POLICY_LOCATION)
        max_passes = limits.get("max-passes")
        return cls(order or "first", None if max_passes is None else int(max_passes),
                   limits.get("max-cost"))

    def with_likeness(self, likeness: "Likeness | None") -> "Policy":
        """This policy with the fidelity order's scores (effects.host.fidelity.policy_for)."""
        import dataclasses
        return dataclasses.replace(self, likeness=likeness)

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


def pass_work(report: "PassReport") -> int:
    """One pass's per-pixel work in instruction slots, plus one for its fill: a pixel
    shader's slots as the card's checks count them (`AsmStats.total_slots`: texture,
    arithmetic and flow slots, co-issued pairs as one), or for the fixed-function stages one
    slot per texture read and one per stage's combine, as ps_1_1 would spend them (`tex` and
    an arithmetic instruction). The fill (+1): every pass writes each pixel it covers again,
    through the blender. A card's fill rate and clock are a factor common to every technique
    on that card (and no profile records them), so they do not change the order on a card."""
    shader = report.shaders.get("PixelShader")
    slots = shader.program.stats.total_slots if shader is not None \
        else report.textures + report.stages
    return 1 + slots


def technique_work(validation: Validation) -> int:
    """The per-pixel work of a technique on the card that validated it: the sum of its
    passes' `pass_work`. The fidelity policy's tie-breaker."""
    return sum(pass_work(p) for p in validation.pass_reports)


@dataclass
class Selection:
    """What selecting a technique for one effect on one card found (`select`): the technique
    drawn, every technique's Validation made on the way, and the policy's reasons.

    `validations` are in file order. A lazy selection under the default policy stops at the
    first valid technique (D3DX's FindNextValidTechnique) and leaves the techniques after it
    in `pending`; otherwise, or when none is valid, every technique is validated."""

    policy: Policy
    validations: list[Validation]
    chosen: Validation | None                  # the technique to draw; None: nothing valid
    forced_rejected: Validation | None = None  # a forced technique the card cannot run
    pending: list[Technique] = field(default_factory=list)
    # the fidelity order's scores, by position in `validations` (SSIM against the best)
    likeness: Mapping[int, "float | None"] = field(default_factory=dict)

    @property
    def technique(self) -> Technique | None:
        return self.chosen.technique if self.chosen is not None else None

    def _top_likeness(self) -> float | None:
        """The highest fidelity score among the techniques the policy accepts (None: none
        measured): the top of the band of alike techniques (FIDELITY_TIE)."""
        scores = [s for i, s in self.likeness.items() if s is not None
                  and i < len(self.validations) and self.policy.accepts(self.validations[i])]
        return max(scores) if scores else None

    def _preference(self, v: Validation, position: int) -> tuple[float, float, int]:
        """Where the policy places a technique among those it accepts: its score (quality,
        cost, fidelity then work, or none for file order), then its `position` in file order.
        Under the fidelity order every technique within FIDELITY_TIE of the highest score
        takes that score, so work and then file order decide among them."""
        if self.policy.order == "quality":
            return (-technique_quality(v.technique), 0.0, position)
        if self.policy.order == "cost":
            cost = technique_cost(v.technique)
            return (math.inf if cost is None else cost, 0.0, position)
        if self.policy.order == "fidelity":
            if not v.ok:   # never drawn, so never measured: had it compiled, it might have won
                return (-math.inf, 0.0, position)
            score = self.likeness.get(position)
            if score is None:
                # unmeasured: no figure says one looks more like the best, so file order (D3DX's)
                # decides, not the least work -- with every technique unmeasured the policy would
                # otherwise draw the cheapest fallback on a card that runs the author's first
                return (math.inf, 0.0, position)
            top = self._top_likeness()
            if top is not None and score >= top - FIDELITY_TIE:
                score = top
            return (-score, float(technique_work(v)), position)
        return (0.0, 0.0, position)

    @property
    def ranked(self) -> list[Validation]:
        """The validations the policy accepts first, in its preferred order, then the others
        in file order; the first is the policy's choice when it accepts it."""
        def key(item: tuple[int, Validation]) -> tuple[int, float, float, int]:
            position, v = item
            if not self.policy.accepts(v):
                return (1, 0.0, 0.0, position)
            return (0, *self._preference(v, position))

        return [v for _, v in sorted(enumerate(self.validations), key=key)]

    @property
    def passed_over(self) -> EffectError | None:
        """The language error of a technique the selection fell past (effects.validate.
        verdicts): one the policy would have chosen before the chosen technique (before any,
        when none was) had it compiled, and that the policy's limits do not refuse. A card
        limit is the card's reason; a language error is an error, said as one."""
        bar = None
        ahead = []
        for position, v in enumerate(self.validations):
            if v is self.chosen:
                bar = self._preference(v, position)
            error = language_error(v)
            if error is not None and self.policy.refusal(v) is None:
                ahead.append((self._preference(v, position), error))
        ahead = [item for item in ahead if bar is None or item[0] < bar]
        return min(ahead, key=lambda item: item[0])[1] if ahead else None

    def rejected(self) -> dict[str, list[str]]:
        """By technique name, in file order: every reason of each technique the card cannot
        run, and the policy's reason for each valid one it refuses (max-passes, max-cost)."""
        out: dict[str, list[str]] = {}
        for v in self.validations:
            name = v.technique.name or "<anonymous>"
            if not v.ok:
                out[name] = [str(r) for r in v.reasons]
            else:
                refusal = self.policy.refusal(v)
                if refusal is not None:
                    out[name] = [f"policy {self.policy}: {refusal}"]
        return out


def select(effect: Effect, profile: CapsProfile, policy: PolicyLike = "first", *,
           forced: Technique | None = None, lazy: bool = True,
           validations: Sequence[Validation] | None = None) -> Selection:
    """The one route by which a technique is selected: the runtime, the viewer's reloads, the
    command line and `Effect.find_valid_technique` all ask here.

    `forced`: a technique the caller would draw; it is chosen when the card can run it
    (whatever the policy), else the policy chooses and `forced_rejected` says why not.
    `lazy`: under the default policy, validate in file order only until the answer is known
    (the first valid technique, and the forced one's answer), as FindNextValidTechnique does;
    other policies rank every technique. `validations`: every technique's answer on this card
    already made, in file order (the command line validates all cards at once).
    The fidelity order ranks its Policy's `likeness` (the host's measures); a fidelity policy
    without them is an error, said where the policy is named."""
    pol = as_policy(policy)
    if pol.order == "fidelity" and pol.likeness is None:
        raise EffectError("policy 'fidelity' ranks techniques by how like the best technique's "
                          "their pictures are, and nothing here draws them: the commands "
                          "(effects render/matrix/validate/view) measure them; in Python pass "
                          "effects.host.fidelity.policy_for(effect, scene=...)", _POLICY_LOCATION)
    if validations is not None:
        made, pending = list(validations), []
    else:
        made, pending = [], list(effect.techniques)
        stop = lazy and pol == Policy()
        while pending and not (stop and _decided(made, forced)):
            made.append(validate_technique(effect, pending.pop(0), profile))
    forced_rejected = None
    if forced is not None:
        answer = next((v for v in made if v.technique is forced), None)
        if answer is None:
            raise EffectError(f"technique '{forced.name}' is not one of this effect's techniques",
                              Location(effect.path, 1, 1))
        if answer.ok:
            return Selection(pol, made, answer, None, pending)
        forced_rejected = answer
    selection = Selection(pol, made, None, forced_rejected, pending)
    if pol.order == "fidelity" and pol.likeness is not None:
        # only the techniques the policy may choose are measured (each costs renders)
        selection.likeness = dict(pol.likeness([v if pol.accepts(v) else None for v in made]))
    ranked = selection.ranked
    if ranked and pol.accepts(ranked[0]):
        selection.chosen = ranked[0]
    return selection


def language_error(validation: Validation) -> EffectError | None:
    """The first language error among a technique's reasons on a card (HLSL that compiles for
    no target: `EffectError.language`), or None."""
    return next((r.error for r in validation.reasons if r.error is not None), None)


def _decided(made: list[Validation], forced: Technique | None) -> bool:
    """Under the default policy, whether these answers (the first techniques in file order)
    decide the selection: the forced technique when it is valid, else the first valid one,
    which nothing later can precede."""
    first_valid = any(v.ok for v in made)
    if forced is None:
        return first_valid
    answer = next((v for v in made if v.technique is forced), None)
    return answer is not None and (answer.ok or first_valid)


def find_valid_technique(effect: Effect, profile: CapsProfile,
                         policy: PolicyLike = "first") -> Technique | None:
    """The technique the policy picks on this card, or None when none is valid (`select`)."""
    return select(effect, profile, policy).technique


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
