"""effects: a D3DX-style effect framework with technique fallback over simulated cards.

    effect = effects.load_effect("fxfiles/phong.fx")
    card = effects.load_profile("geforce3")
    tech = effect.find_valid_technique(card)
    picture = effects.render(effect, card, size=(256, 256))
"""
# the package's version, its one source: pyproject.toml reads it, `effects --version` prints it
__version__ = "0.1.0"

from effects.base.errors import (AsmError, EffectError, EffectWarning, Location, NoValidTechnique,
                                 ParseError, PreprocessError, ProfileError, SceneError, StateError)

# Where each public name lives. The loader, the model and the runtime import numpy and lark;
# they load on first use (PEP 562), so that `effects --help` and `effects profiles` do not pay.
_LAZY = {"load_effect": "effects.api", "Effect": "effects.api", "load_shader": "effects.api",
         "load_profile": "effects.d3d9.caps", "list_profiles": "effects.d3d9.caps",
         "render": "effects.host.runtime",
         "cache_report": "effects.base.caches", "clear_caches": "effects.base.caches",
         "Parameter": "effects.model", "Pass": "effects.model",
         "StateAssignment": "effects.model", "Technique": "effects.model"}


def __getattr__(name: str):
    if name in _LAZY:
        import importlib
        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'effects' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))


__all__ = [
    "AsmError", "Effect", "EffectError", "EffectWarning", "Location", "NoValidTechnique",
    "ParseError", "Parameter", "Pass", "PreprocessError", "ProfileError", "SceneError",
    "StateAssignment", "StateError", "Technique", "cache_report", "clear_caches", "load_effect",
    "load_shader", "load_profile", "list_profiles", "render",
]
