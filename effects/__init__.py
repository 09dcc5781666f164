"""effects: a D3DX-style effect framework with technique fallback over simulated cards.

    effect = effects.load_effect("fxfiles/phong.fx")
    card = effects.load_profile("geforce3")
    tech = effect.find_valid_technique(card)
"""
from effects.errors import (AsmError, EffectError, EffectWarning, Location, NoValidTechnique, ParseError,
                     PreprocessError, ProfileError, SceneError, StateError)
from effects.frontend.loader import load_effect
from effects.model import Effect, Parameter, Pass, StateAssignment, Technique

__all__ = [
    "AsmError", "Effect", "EffectError", "EffectWarning", "Location", "NoValidTechnique",
    "ParseError", "Parameter", "Pass", "PreprocessError", "ProfileError", "SceneError",
    "StateAssignment", "StateError", "Technique", "load_effect", "load_profile", "list_profiles",
    "render",
]


def load_profile(name_or_path: str):
    """Load a caps profile by name (`geforce3`) or path; see `effects.caps`."""
    from effects.caps import load_profile as _load
    return _load(name_or_path)


def list_profiles() -> list[str]:
    """The names of the bundled caps profiles."""
    from effects.caps import list_profiles as _list
    return _list()


def render(effect, profile, **kwargs):
    """Render an effect on a simulated card; see `effects.host.runtime.render`."""
    from effects.host.runtime import render as _render
    return _render(effect, profile, **kwargs)
