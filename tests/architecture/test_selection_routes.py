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
