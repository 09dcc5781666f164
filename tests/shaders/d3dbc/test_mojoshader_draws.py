"""MojoShader's GLSL translation of the bytecode we write draws what we draw: every technique of
every bundled effect that has shaders and that the Radeon 9700 validates, drawn through
`mojo_gl.MojoShaderBackend` (MojoShader's GLSL on the GL back end's context, textures, sampler
objects, streams, constants and render state; scripts included) and compared with our GL and
NumPy back ends' pictures.

Tolerance. Against our GL back end: 2/255 per channel. The two draws share the driver, the
textures, the sampler objects, the rasteriser and the blending; only the shader text differs
(MojoShader's GLSL 1.10 against ours), so what may differ is float evaluation order, which
moves an 8-bit result by a rounding step at most (measured: 0 on every technique). Against the
NumPy reference: no pixel further from it than our GL back end's picture is, plus the same 2:
MojoShader must add no difference of its own to the ones tests/backends/test_conformance.py
bounds and explains (llvmpipe's level of detail, ties on texel boundaries).

What does not draw the same, and why (each case asserted, so a change on either side shows):
- `NOT_TRANSLATED`: MojoShader (hg 1314) refuses to translate ps_1_4's texld (its GLSL profile
  says "TEXLD == Shader Model 1.4 unimplemented"), ps_1_1's texcoord (same opcode as texcrd)
  and texreg2gb ("unimplemented in glsl profile").
- `MODIFIER_DROPPED`: texm3x2pad/texm3x2tex with a `_bx2` source. Its emit_GLSL_TEXM3X2TEX
  (mojoshader_profile_glsl.c) builds the dot products from the registers' names ("this code
  counts on the register not having swizzles, etc."), so the source modifier is lost; the same
  effect with `_bx2` taken off those sources draws, on our GL back end, MojoShader's picture.
- On the GeForce3 (not the card above) ps_1_x differs by design: MojoShader computes it in
  float, we model the card's 8-bit fixed point (`test_on_the_geforce3_...`).
"""
from __future__ import annotations

import os
import re

import numpy as np
import pytest

import effects
from effects.host.runtime import render_frame, validate_technique
from effects.shaders.d3dbc import write_shader
from tests.backends.test_conformance import params_for
from tests.paths import ROOT
from tests.shaders.d3dbc import mojoshader
from tests.shaders.d3dbc.programs import effect_shaders

LIB = mojoshader.load()
pytestmark = pytest.mark.skipif(LIB is None, reason="libmojoshader0 is not installed (apt-get "
                                "install libmojoshader0; .ci/setup does)")

CARD = "radeon9700"
SIZE = (63, 63)        # odd, as tests/backends/test_conformance.py: no pixel centre on a texel edge
NOT_TRANSLATED = {
    ("sdk8_style.fx", "TPS4"): "TEXLD == Shader Model 1.4 unimplemented",
    ("sdk9_hlsl.fx", "Scene_ps14"): "TEXLD == Shader Model 1.4 unimplemented",
    ("sdk9_hlsl.fx", "Scene_ps11"): "TEXCRD unimplemented in glsl profile",
    ("sdk9_style.fx", "Marble_ps11"): "TEXREG2GB unimplemented in glsl profile",
}
MODIFIER_DROPPED = {("phong.fx", "PerPixelPhong_ps11"), ("specular_bump.fx", "SpecularTable_ps11")}


def _techniques() -> list[tuple[str, str]]:
    out = []
    profile = effects.load_profile(CARD)
    for path in sorted((ROOT / "fxfiles").glob("*.fx")):
        effect = effects.load_effect(path)
        for technique in effect.techniques:
            validation = validate_technique(effect, technique, profile)
            if validation.ok and any(r.shaders for r in validation.pass_reports):
                out.append((path.name, technique.name))
    return out


TECHNIQUES = _techniques() if LIB is not None else []


def test_the_uniform_packing_read_from_parse_data_is_the_translations_own():
    """`uniform_slots` (from MOJOSHADER_parseData.uniforms) puts each register where the
    translation's `#define vs_c# vs_uniforms_vec4[k]` lines say it is."""
    from tests.shaders.d3dbc.mojo_gl import uniform_slots
    checked = 0
    for name, shader in effect_shaders():
        t = mojoshader.translate(LIB, write_shader(shader.program, shader.compiled))
        if t.errors:
            continue
        stage = shader.program.name[:2]        # vs_2_0 -> vs
        defined = {int(r): int(k) for r, k in re.findall(
            rf"^#define {stage}_c(\d+) {stage}_uniforms_vec4\[(\d+)\]$", t.text, re.M)}
        assert uniform_slots(t) == defined, name
        assert {s[2] for s in t.samplers} <= set(re.findall(r"uniform sampler\w+ (\w+);",
                                                              t.text)), name
        checked += bool(defined)
    assert checked >= 20


@pytest.fixture(scope="module")
def backend():
    from tests.shaders.d3dbc.mojo_gl import MojoShaderBackend
    mojo = MojoShaderBackend(LIB)
    yield mojo
    mojo.close()


def _mojo_frame(backend, effect, technique: str, params: dict):
    from tests.shaders.d3dbc.mojo_gl import MojoRuntime
    backend.sources.clear()
    backend.own_draws = 0
    runtime = MojoRuntime(effect, CARD, size=SIZE, params=params, backend=backend)
    return runtime.render(technique).image


def _ours(effect, technique: str, params: dict, backend: str) -> np.ndarray:
    return render_frame(effect, CARD, technique=technique, size=SIZE, params=params,
                        backend=backend).image.astype(int)


def _without_texm3x2_modifiers(tmp_path, name: str):
    """The bundled effect with `_bx2` taken off its texm3x2pad/texm3x2tex sources (its
    textures found through a link to fxfiles/textures)."""
    text = (ROOT / "fxfiles" / name).read_text()
    changed, count = re.subn(r"(texm3x2(?:pad|tex)\s+t\d+\s*,\s*t\d+)_bx2", r"\1", text)
    assert count >= 2
    (tmp_path / name).write_text(changed)
    os.symlink(ROOT / "fxfiles" / "textures", tmp_path / "textures")
    return effects.load_effect(tmp_path / name)


@pytest.mark.parametrize("name,technique", TECHNIQUES, ids=[f"{f}:{t}" for f, t in TECHNIQUES])
def test_mojoshaders_translation_draws_what_we_draw(backend, tmp_path, name, technique):
    from tests.shaders.d3dbc.mojo_gl import NotDrawable
    effect = effects.load_effect(ROOT / "fxfiles" / name)
    params = params_for(name)
    if (name, technique) in NOT_TRANSLATED:
        with pytest.raises(NotDrawable, match=re.escape(NOT_TRANSLATED[(name, technique)])):
            _mojo_frame(backend, effect, technique, params)
        return
    mojo = _mojo_frame(backend, effect, technique, params).astype(int)
    assert backend.sources and not backend.own_draws      # every draw was MojoShader's
    drawn = mojo[..., :3].max(-1) > 8
    assert drawn.mean() > 0.2                              # a picture, not a blank frame
    if (name, technique) in MODIFIER_DROPPED:
        assert np.abs(mojo - _ours(effect, technique, params, "gl")).max() > 32
        effect = _without_texm3x2_modifiers(tmp_path, name)
    gl = _ours(effect, technique, params, "gl")
    reference = _ours(effect, technique, params, "numpy")
    assert np.abs(mojo - gl).max() <= 2
    assert (np.abs(mojo - reference) <= np.abs(gl - reference) + 2).all()


def test_every_bundled_technique_with_shaders_is_drawn_or_explained():
    assert len(TECHNIQUES) >= 20
    assert set(NOT_TRANSLATED) | MODIFIER_DROPPED <= set(TECHNIQUES)


PS1X = [("hemisphere.fx", "HemisphereOcclusion_ps11"), ("hemisphere.fx", "HemispherePerPixel_ps11"),
        ("sdk8_style.fx", "TPS1"), ("specular_bump.fx", "SpecularMultiply_ps11")]


@pytest.mark.parametrize("name,technique", PS1X, ids=[f"{f}:{t}" for f, t in PS1X])
def test_on_the_geforce3_mojoshader_draws_ps1x_in_float(backend, name, technique):
    """MojoShader's GLSL computes ps_1_x in float; on the GeForce3 we model its 8-bit signed
    fixed point (effects/d3d9/precision.py). So its GeForce3 picture is our picture where
    ps_1_x is not quantised (the Radeon 9700's lowering), and SpecularMultiply's ^16 by
    repeated 8-bit products bands in ours and not in MojoShader's."""
    from tests.shaders.d3dbc.mojo_gl import MojoRuntime
    effect = effects.load_effect(ROOT / "fxfiles" / name)
    params = params_for(name)
    backend.own_draws = 0
    mojo = MojoRuntime(effect, "geforce3", size=SIZE, params=params,
                       backend=backend).render(technique).image.astype(int)
    assert not backend.own_draws
    unquantised = _ours(effect, technique, params, "gl")                    # radeon9700
    quantised = render_frame(effect, "geforce3", technique=technique, size=SIZE, params=params,
                             backend="gl").image.astype(int)
    assert np.abs(mojo - unquantised).max() <= 2
    if technique == "SpecularMultiply_ps11":
        assert np.abs(mojo - quantised).max() >= 5
