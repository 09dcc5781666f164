"""The viewer's reload of the HLSL typo case (issue 30), without a window: an edit that leaves
the technique the card would draw with an undeclared identifier fails the reload with the
located X3004 error (shown in red like a parse error) and keeps the last good effect, where
it used to log "reload ok" with the fallback technique."""
from __future__ import annotations

import os

import pytest

import effects
from effects.base.errors import EffectError
from effects.viewer.reload import BuildSettings, Reloader, build_effect, effect_builder

GOOD_LINE = "    return Tint;"
TYPO_LINE = "    return Tint * fooo;"
EFFECT = """float4 Tint = {1, 0.5, 0.25, 1};

float4 PS(float2 uv : TEXCOORD0) : COLOR
{
%s
}

technique Shader
{
    pass P0 { PixelShader = compile ps_2_0 PS(); }
}

technique Fallback
{
    pass P0 { Lighting = false; ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse; }
}
"""
COLUMN = TYPO_LINE.index("fooo") + 1


def save(path, text: str) -> None:
    tmp = f"{path}.part"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def located(path) -> str:
    return f"{path}:5:{COLUMN}: error: X3004: undeclared identifier 'fooo'"


@pytest.fixture
def typo(tmp_path):
    path = tmp_path / "typo.fx"
    path.write_text(EFFECT % TYPO_LINE)
    return path


def test_a_build_that_would_fall_past_it_raises_the_located_error(typo):
    with pytest.raises(EffectError) as info:
        build_effect(str(typo), effects.load_profile("radeon9700"))
    assert info.value.report() == f"{located(typo)}\n{TYPO_LINE}\n{' ' * (COLUMN - 1)}^"
    with pytest.raises(EffectError, match="X3004"):     # the technique asked for, the same
        build_effect(str(typo), effects.load_profile("radeon9700"), technique="Shader")
    # a card without pixel shaders never compiles it: the fallback is drawn
    assert build_effect(str(typo), effects.load_profile("geforce2")).technique.name == "Fallback"
    with pytest.raises(EffectError, match="X3004"):     # unless strict, as D3DXCreateEffect
        build_effect(str(typo), effects.load_profile("geforce2"), strict=True)


def test_the_typo_fails_the_reload_and_the_last_good_effect_stays(tmp_path):
    path = tmp_path / "edit.fx"
    path.write_text(EFFECT % GOOD_LINE)
    settings = BuildSettings(effects.load_profile("radeon9700"))
    build = effect_builder(str(path), lambda: settings)
    reloader = Reloader(str(path), build)
    reloader.start(build(None))
    try:
        good = reloader.last_good
        assert good.technique.name == "Shader"
        save(path, EFFECT % TYPO_LINE)
        bad = reloader.wait(5.0)
        assert bad is not None and not bad.ok and bad.loaded is None
        assert bad.error.language
        assert bad.log_line() == f"reload: {path} failed: {located(path)}"
        assert reloader.last_good is good
        save(path, EFFECT % GOOD_LINE)
        fixed = reloader.wait(5.0)
        assert fixed is not None and fixed.ok and fixed.loaded.technique.name == "Shader"
    finally:
        reloader.stop()
