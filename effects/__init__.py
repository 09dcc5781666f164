"""effects: a D3DX-style effect framework with technique fallback over simulated cards.

    effect = effects.load_effect("fxfiles/phong.fx")
    card = effects.load_profile("geforce3")
    tech = effect.find_valid_technique(card)
"""
from effects.errors import (AsmError, EffectError, EffectWarning, Location, NoValidTechnique, ParseError,
                     PreprocessError, ProfileError, SceneError, StateError)

# The model and the loader import numpy and lark; they load on first use (PEP 562), so that
# `effects --help` and `effects profiles` do not pay for them.
_LAZY = {"load_effect": "effects.frontend.loader", "Effect": "effects.model",
         "Parameter": "effects.model", "Pass": "effects.model",
         "StateAssignment": "effects.model", "Technique": "effects.model"}


def __getattr__(name: str):
    if name in _LAZY:
        import importlib
        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'effects' has no attribute {name!r}")

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
