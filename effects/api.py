"""The effect users load: the model with the spine's verbs, on top of the layers that do them.

`Effect` here is the model's `Effect` (what the file says) with the spine's functions as its
methods, D3DX-style: `validate` (effects.validate.technique), `find_valid_technique` and
`find_next_valid_technique` (effects.validate.select; the first is its `select`, the one route
by which every host selects), `to_source` (effects.frontend.printer).
They live here, above those layers, so that the model stays data that everything below can
import. `load_effect` gives this `Effect`.
"""
from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any, Mapping

from effects import model
from effects.frontend import loader
from effects.frontend.printer import print_effect
from effects.validate.select import find_next_valid_technique, select
from effects.validate.technique import validate_technique
from effects.validate import verdicts

if TYPE_CHECKING:  # pragma: no cover
    from effects.d3d9.caps import CapsProfile
    from effects.shaders.d3dbc import ShaderBinary
    from effects.validate.technique import Validation


class Effect(model.Effect):
    """An effect as loaded: its parameters, techniques and passes, with the spine's verbs."""

    def validate(self, technique: model.Technique | str, profile: "CapsProfile") -> "Validation":
        """Whether `profile` can run `technique` (a Technique or its name), with every reason."""
        if isinstance(technique, str):
            technique = self.technique(technique)
        return validate_technique(self, technique, profile)

    def find_valid_technique(self, profile: "CapsProfile", policy: Any = "first", *,
                             scene: Any = None) -> model.Technique | None:
        """The technique `profile` selects (D3DX's FindNextValidTechnique from the start, or a
        named policy), or None. The fidelity policy measures the techniques' pictures in
        `scene` (a YAML path, mapping or None for the default scene: effects.host.fidelity)."""
        from effects.host.fidelity import policy_for
        return select(self, profile, policy_for(self, policy, scene=scene)).technique

    def find_next_valid_technique(self, profile: "CapsProfile",
                                  after: model.Technique | str | None = None) -> model.Technique | None:
        """The first valid technique after `after`, in file order (D3DX's iteration)."""
        return find_next_valid_technique(self, profile, after)

    def to_source(self) -> str:
        """The effect printed as .fx text that parses back to an equal effect."""
        return print_effect(self)


def load_effect(path_or_text: "str | bytes | os.PathLike[str]", *, defines: Mapping[str, str] | None = None,
                include_dirs=(), include_handler: loader.IncludeHandler | None = None,
                include_root: str | None = None, strict: bool = False) -> Effect:
    """Load an effect file (or effect source text) into an `Effect`; see
    `effects.frontend.loader.load_effect`. Raises a located `EffectError` for bad input;
    `strict` also compiles every HLSL shader of the effect and raises the first language
    error (fxc's for every target: `effects.validate.verdicts`), as D3DXCreateEffect failed."""
    return verdicts.load_effect(path_or_text, defines=defines, include_dirs=include_dirs,
                                include_handler=include_handler, include_root=include_root,
                                strict=strict, effect_type=Effect)  # type: ignore[return-value]




def load_shader(path: "str | os.PathLike[str]", name: str | None = None) -> "ShaderBinary":
    """Read one compiled shader: raw Direct3D 9 bytecode (.pso, .vso, .cso, fxc /Fo) or, for
    a C header (.h: fxc /Fh), its array `name` (default: the first); see
    `effects.shaders.d3dbc.load_shader`."""
    from effects.shaders.d3dbc import load_shader as load
    return load(path, name)
