"""The HLSL compile cache (effects.shaders.hlsl.cache): a `compile` state compiles once per
distinct input, across passes, cards and reloads; what it returns is what a fresh compile
gives; any change the output depends on (the entry, a function it calls, a struct or global
it reads, a macro, the target, the compile arguments) compiles again; and it is bounded."""
from __future__ import annotations

import pytest

import effects
from effects.base.errors import EffectError
from effects.base.lru import ByteLRU
from effects.model import CompileShader
from effects.shaders.hlsl import cache, compile_shader, compile_state

BASE = """float Scale = 0.5;
float Other = 1;
static const float Gain = 2;
sampler2D Tex;
struct V { float4 c : COLOR0; };
float3 tint(float3 c) { return c * Scale * Gain; }
float unused(float x) { return x * Other; }
float4 PS(V v) : COLOR
{
    return float4(tint(v.c.rgb), 1) * tex2D(Tex, v.c.xy);
}
technique A { pass P { PixelShader = compile ps_2_0 PS(); } }
technique B { pass P { PixelShader = compile ps_2_0 PS(); } }
"""


@pytest.fixture(autouse=True)
def fresh_cache():
    cache.clear()
    yield
    cache.clear()


def pixel_shader(effect: effects.Effect, technique: str = "A") -> CompileShader:
    value = effect.technique(technique).passes[0].state("PixelShader").value
    assert isinstance(value, CompileShader)
    return value


def compiled(text: str, technique: str = "A", **load):
    fx = effects.load_effect(text, **load)
    return compile_state(fx, pixel_shader(fx, technique))


def test_a_hit_is_what_a_fresh_compile_gives():
    fx = effects.load_effect(BASE)
    first = compile_state(fx, pixel_shader(fx))
    fresh = compile_shader(fx, "PS", "ps_2_0", (), pixel_shader(fx).location)
    assert compile_state(fx, pixel_shader(fx)) is first
    assert (first.text, first.constants, first.samplers, first.lines, first.types) == \
        (fresh.text, fresh.constants, fresh.samplers, fresh.lines, fresh.types)
    assert [str(w) for w in first.warnings] == [str(w) for w in fresh.warnings]


def test_one_compile_for_every_pass_card_and_reload():
    fx = effects.load_effect(BASE)
    shader = compile_state(fx, pixel_shader(fx, "A"))
    assert compile_state(fx, pixel_shader(fx, "B")) is shader        # another technique
    for card in ("radeon9700", "geforce6800"):
        assert fx.validate("A", effects.load_profile(card)).ok
    assert compiled(BASE) is shader                                   # the same file again
    assert len(cache.CACHE) == 1


@pytest.mark.parametrize("edit", [
    ("float unused(float x) { return x * Other; }", "float unused(float x) { return x + 1; }"),
    ("float Other = 1;", "float2 Other = 1;"),
    ("technique B { pass P { PixelShader = compile ps_2_0 PS(); } }", ""),
])
def test_an_edit_the_entry_cannot_reach_keeps_the_compile(edit):
    before = compiled(BASE)
    assert compiled(BASE.replace(*edit)) is before


@pytest.mark.parametrize("edit", [
    ("return c * Scale * Gain;", "return c * Scale * Gain + 0.25;"),           # a called function
    ("float Scale = 0.5;", "float3 Scale = 0.5;"),                               # a global's type
    ("float Scale = 0.5;", "float Scale : register(c7) = 0.5;"),                 # its register
    ("static const float Gain = 2;", "static const float Gain = 3;"),            # a static's value
    ("struct V { float4 c : COLOR0; };", "struct V { float4 c : COLOR1; };"),    # a struct
    ("sampler2D Tex;", "sampler2D Tex : register(s3);"),                         # a sampler
    ("compile ps_2_0 PS(); } }\ntechnique B", "compile ps_2_a PS(); } }\ntechnique B"),  # target
])
def test_a_change_the_output_depends_on_compiles_again(edit):
    text = BASE.replace(*edit)
    assert text != BASE
    before = compiled(BASE)
    after = compiled(text)
    assert after is not before
    fx = effects.load_effect(text)
    value = pixel_shader(fx)
    fresh = compile_shader(fx, value.function, value.profile, value.args, value.location)
    assert after.text == fresh.text and after.constants == fresh.constants
    assert after.samplers == fresh.samplers


def test_a_macro_that_changes_the_function_compiles_again():
    text = BASE.replace("return c * Scale * Gain;", "return c * Scale * GAIN;")
    low = compiled(text, defines={"GAIN": "2"})
    high = compiled(text, defines={"GAIN": "4"})
    assert high is not low and high.text != low.text
    assert compiled(text, defines={"GAIN": "2"}) is low


def test_moving_the_function_relocates_its_instructions():
    before = compiled(BASE)
    after = compiled("\n\n" + BASE)
    assert after is not before
    assert [loc.line + 2 if loc.line else 0 for loc in before.lines] == \
        [loc.line for loc in after.lines]


def test_compile_arguments_are_in_the_key():
    text = BASE.replace("float4 PS(V v) : COLOR", "float4 PS(V v, uniform float k) : COLOR") \
               .replace("return float4(", "return k * float4(")
    one = compiled(text.replace("PS();", "PS(1);"))
    two = compiled(text.replace("PS();", "PS(2);"))
    assert one.text != two.text


def test_errors_are_cached_and_located_at_each_compile_state():
    text = BASE.replace("compile ps_2_0 PS()", "compile ps_2_0 Missing()")
    fx = effects.load_effect(text)
    found = []
    for technique in ("A", "B"):
        with pytest.raises(EffectError, match="X3501: 'Missing': entrypoint not found") as info:
            compile_state(fx, pixel_shader(fx, technique))
        found.append(info.value)
    assert [err.line for err in found] == [12, 13]
    with pytest.raises(EffectError) as again:
        compile_state(fx, pixel_shader(fx, "A"))
    assert again.value is found[0]


def test_the_cache_is_bounded(monkeypatch):
    monkeypatch.setattr(cache, "CACHE", ByteLRU(3, size_of=lambda value: 1))
    shaders = [compiled(BASE.replace("Gain = 2;", f"Gain = {k};")) for k in range(5)]
    assert len(cache.CACHE) == 3
    assert compiled(BASE.replace("Gain = 2;", "Gain = 4;")) is shaders[4]      # recent: kept
    assert compiled(BASE.replace("Gain = 2;", "Gain = 0;")) is not shaders[0]  # oldest: evicted


def test_a_function_that_does_not_parse_fails_every_compile_of_the_effect():
    # fxc compiles the whole file: a broken function fails the shaders that never call it
    broken = BASE.replace("return x * Other;", "return x * ;")
    good = compiled(BASE)
    with pytest.raises(EffectError, match="X3000: syntax error") as info:
        compiled(broken)
    assert info.value.line == 7
    assert compiled(BASE) is good                  # fixed again: the first compile still holds
    with pytest.raises(EffectError, match="X3000: syntax error"):
        compiled(broken.replace("float Other = 1;", "float Other = 2;"))


def test_the_bound_counts_what_an_entry_holds():
    small = compiled(BASE)
    big = compiled(BASE.replace("return float4(tint(v.c.rgb), 1)",
                                "return float4(tint(tint(tint(v.c.rgb) * v.c.a).bgr), 1)"))
    assert cache.entry_bytes(big) > cache.entry_bytes(small) > 4096
    assert cache.CACHE.bytes == cache.entry_bytes(small) + cache.entry_bytes(big)


def test_the_key_is_kept_per_effect_and_follows_parameter_changes():
    """compile_key is kept per effect and compile state (validation asks once per card); a
    kept key is what a fresh walk gives, even after a parameter it reached changed in place
    (a runtime sets values and texture types), and a recording view sees the same reads."""
    import numpy as np
    from effects.model import RecordedReads
    fx = effects.load_effect(BASE)
    value = pixel_shader(fx)
    first = cache.compile_key(fx, value)
    assert cache.compile_key(fx, value) is first                 # kept
    assert cache._compile_key(fx, value, []) == first             # what a fresh walk gives
    fx.parameter("Gain").value = np.array(3.0, dtype=np.float32)  # a static global: in the key
    changed = cache.compile_key(fx, value)
    assert changed != first and changed == cache._compile_key(fx, value, [])
    fx.parameter("Scale").value = np.array(9.0, dtype=np.float32)  # a uniform: not in the key
    assert cache.compile_key(fx, value) is changed
    fresh_reads, kept_reads = RecordedReads(fx), RecordedReads(fx)
    cache._compile_key(fresh_reads, value, [])
    assert cache.compile_key(kept_reads, value) == changed
    assert kept_reads.snapshot() == fresh_reads.snapshot()
    other = effects.load_effect(BASE.replace("* Gain", "* Gain * 2"))   # another effect
    assert cache.compile_key(other, pixel_shader(other)) != changed
