"""One route for selection: the runtime (`effects render`, `doctor`), the viewer's reloads and
`effects matrix` (and `validate`) all choose through `effects.validate.select.select`, so they
give the same answer for every bundled effect on every card; the answer is checked against
D3DX's rule computed here from the validator alone (the first valid technique in file order)."""
from __future__ import annotations

from tests.paths import ROOT

import pytest

import effects
from effects.base.errors import NoValidTechnique
from effects.cli.report import matrix
from effects.d3d9.caps import list_profiles, load_profile
from effects.host.runtime import Runtime
from effects.validate.technique import validate_technique
from effects.viewer.reload import build_effect

FX_FILES = sorted((ROOT / "fxfiles").glob("*.fx"))
CARDS = [load_profile(name) for name in list_profiles()]


def _runtime_choice(effect, profile, policy):
    try:
        return Runtime(effect, profile, backend=None).select(policy=policy).name
    except NoValidTechnique:
        return None


def _viewer_choice(path, effect, profile, policy):
    loaded = build_effect(str(path), profile, policy=policy, previous=effect, lower=False,
                          defer=True)
    return loaded.technique.name if loaded.technique is not None else None


@pytest.mark.parametrize("path", FX_FILES, ids=lambda p: p.stem)
def test_runtime_viewer_and_matrix_pick_the_same_technique_on_every_card(path):
    effect = effects.load_effect(str(path))
    by_matrix = matrix({str(path): effect}, CARDS)[str(path)]
    for profile in CARDS:
        # D3DX's FindNextValidTechnique from the start, from the validator's answers
        first_valid = next((t.name for t in effect.techniques
                            if validate_technique(effect, t, profile).ok), None)
        answers = {"matrix": by_matrix[profile.name]["technique"],
                   "runtime": _runtime_choice(effect, profile, "first"),
                   "viewer": _viewer_choice(path, effect, profile, "first")}
        assert answers == dict.fromkeys(answers, first_valid), (path.name, profile.name)


@pytest.mark.parametrize("policy", ["quality", "cost", "quality,max-passes=1"])
def test_the_routes_agree_under_named_policies(policy):
    for path in FX_FILES:
        effect = effects.load_effect(str(path))
        by_matrix = matrix({str(path): effect}, CARDS, policy)[str(path)]
        for profile in CARDS:
            answers = {"matrix": by_matrix[profile.name]["technique"],
                       "runtime": _runtime_choice(effect, profile, policy),
                       "viewer": _viewer_choice(path, effect, profile, policy),
                       "api": getattr(effect.find_valid_technique(profile, policy), "name", None)}
            assert len(set(answers.values())) == 1, (path.name, profile.name, answers)


@pytest.mark.parametrize("path", FX_FILES, ids=lambda p: p.stem)
def test_the_routes_agree_under_the_fidelity_policy(path):
    """One fidelity Policy (its measures in the default scene) handed to every route gives one
    answer, and it is the rule worked out here from the meter's figures: the highest SSIM,
    those within FIDELITY_TIE of it taken as alike, then the least work, then file order;
    those not measured after, in file order (wood.fx in the default scene, without its
    wood.yaml, draws nothing: no technique is measured)."""
    from effects.host.fidelity import meter_for, policy_for
    from effects.validate.select import FIDELITY_TIE, technique_work
    effect = effects.load_effect(str(path))
    policy = policy_for(effect, "fidelity")
    meter = meter_for(effect)
    by_matrix = matrix({str(path): effect}, CARDS, policy)[str(path)]
    for profile in CARDS:
        valid = [(i, v) for i, v in enumerate(validate_technique(effect, t, profile)
                                               for t in effect.techniques) if v.ok]

        scores = {i: meter.measure(v.technique, profile) for i, v in valid}
        top = max((f.ssim for f in scores.values() if f is not None), default=None)

        def rank(item):
            i, v = item
            found = scores[i]
            if found is None:
                return (1.0, 0, i)
            alike = found.ssim >= top - FIDELITY_TIE
            return (-(top if alike else found.ssim), technique_work(v), i)
        expected = min(valid, key=rank)[1].technique if valid else None
        answers = {"runtime": _runtime_choice(effect, profile, policy),
                   "viewer": _viewer_choice(path, effect, profile, policy),
                   "api": getattr(effect.find_valid_technique(profile, policy), "name", None)}
        name = getattr(expected, "name", None)
        assert answers == dict.fromkeys(answers, name), (path.name, profile.name)
        # the matrix names an anonymous technique as the tables do
        assert by_matrix[profile.name]["technique"] == (
            None if expected is None else name or "<anonymous>"), (path.name, profile.name)
