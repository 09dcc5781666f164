"""Golden GLSL for every technique of the seed effects (brdf, specular_bump, phong,
hemisphere): each technique is lowered on a card that selects it (or, for a technique no
card selects, on the first card that validates it), and the vertex and fragment shaders the
GL back end would compile for each pass are compared with
tests/golden/glsl/seeds/<effect>_<technique>.{vert,frag}. A change in lowering or in the
printer shows as a diff of these files.

After an intended change, regenerate them with
`EFFECTS_UPDATE_GOLDEN=1 .venv/bin/python -m pytest tests/backends/test_golden_seed_glsl.py` and read
the diff before committing.
"""
from __future__ import annotations

from tests.paths import ROOT, TESTS

import os
from functools import lru_cache

import pytest

from backends.gl import glsl
from backends.gl.renderer import fragment_options
from effects.d3d9.caps import list_profiles, load_profile
from effects.api import load_effect
from effects.lower.passes import lower_pass
from effects.host.runtime import Runtime

GOLDEN_DIR = TESTS / "golden" / "glsl" / "seeds"
UPDATE_GOLDEN = os.environ.get("EFFECTS_UPDATE_GOLDEN") == "1"
SEEDS = ("brdf", "specular_bump", "phong", "hemisphere")


@lru_cache(maxsize=None)
def _effect(name: str):
    return load_effect(str(ROOT / "fxfiles" / f"{name}.fx"))


def card_for(effect_name: str, technique_name: str) -> str:
    """The first card (list_profiles order) that selects the technique, else the first that
    validates it."""
    effect = _effect(effect_name)
    cards = list_profiles()
    for card in cards:
        chosen = effect.find_valid_technique(load_profile(card))
        if chosen is not None and chosen.name == technique_name:
            return card
    for card in cards:
        if effect.validate(effect.technique(technique_name), load_profile(card)).ok:
            return card
    raise AssertionError(f"no card runs {effect_name}:{technique_name}")


def shader_texts(effect_name: str, technique_name: str) -> tuple[str, str, str]:
    """(card, vertex text, fragment text); a multipass technique's passes follow each other,
    each after a `// pass i of n: NAME` line."""
    card = card_for(effect_name, technique_name)
    profile = load_profile(card)
    runtime = Runtime(_effect(effect_name), profile, size=(64, 64))
    technique = runtime.effect.technique(technique_name)
    streams = runtime.geometry().streams
    vertex_parts, fragment_parts = [], []
    for index, pass_ in enumerate(technique.passes):
        program = lower_pass(runtime.effect, technique, index, profile)
        options = fragment_options(program, float_target=False)
        varyings = glsl.fragment_varyings(program.fragment, options)
        present = {n for n in streams if program.vertex is None
                   or any(i.name == n and i.kind == "varying" for i in program.vertex.inputs)}
        header = f"// pass {index + 1} of {len(technique.passes)}: {pass_.name}\n"
        vertex_parts.append(header + glsl.vertex_shader(program.vertex, varyings, present,
                                                        options.flat_colors))
        fragment_parts.append(header + glsl.fragment_shader(program.fragment, options))
    return card, "".join(vertex_parts), "".join(fragment_parts)


CASES = [(e, t.name) for e in SEEDS for t in _effect(e).techniques]


def test_every_seed_technique_has_a_case():
    assert len(CASES) == 16
    assert ("phong", "PerPixelPhong_ps11") in CASES and ("brdf", "tec0") in CASES


@pytest.mark.parametrize("effect_name, technique_name", CASES)
def test_golden_seed_glsl(effect_name, technique_name):
    card, vertex, fragment = shader_texts(effect_name, technique_name)
    for suffix, text in (("vert", vertex), ("frag", fragment)):
        path = GOLDEN_DIR / f"{effect_name}_{technique_name}.{suffix}"
        text = f"// {effect_name}.fx technique {technique_name}, lowered for {card}\n" + text
        if UPDATE_GOLDEN:
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text)
        assert path.exists(), f"missing golden file {path} (EFFECTS_UPDATE_GOLDEN=1 writes it)"
        assert text == path.read_text(), f"{path.name} differs from the lowering"


def test_the_golden_shaders_are_what_the_gl_back_end_draws_with():
    """The printed pair for phong's ps.2.0 pass is exactly what GLBackend compiles for that
    draw (the golden files are not a separate printing path)."""
    from backends.gl import GLBackend
    card, vertex, fragment = shader_texts("phong", "PerPixelPhong_ps20")
    profile = load_profile(card)
    runtime = Runtime(_effect("phong"), profile, size=(16, 16), backend=GLBackend())
    compiled = []
    original = runtime.backend.ctx.program

    def spy(**sources):
        compiled.append(sources)
        return original(**sources)

    runtime.backend.ctx.program = spy
    try:
        runtime.render("PerPixelPhong_ps20")
    finally:
        del runtime.backend.ctx.program
        runtime.backend.close()
    header = "// pass 1 of 1: P0\n"
    assert compiled, "no program was compiled"
    assert header + compiled[-1]["vertex_shader"] == vertex
    assert header + compiled[-1]["fragment_shader"] == fragment
