"""Constructs that public shaders compiled by fxc use and this compiler refused or mistook
(issue 31's held-out comparison): the D3D10 interpolation modifiers on struct members and
parameters (`centroid` declares `dcl_texcoord_centroid`), and unsigned integer literals
(`1U << 31` is 2147483648). Our own small shaders; values worked out by hand, drawn on both
back ends where they render.
"""
from __future__ import annotations

import numpy as np
import pytest

import effects
from tests.shaders.hlsl.test_hlsl_render import backend, effect_for, fx_asm, render  # noqa: F401

TOL = 1.5 / 255


# -- interpolation modifiers ---------------------------------------------------------------------

SHARED = """
struct V2P
{
    float4 pos : POSITION;
    centroid float4 colour : TEXCOORD0;
    linear float2 uv : TEXCOORD1;
    noperspective float2 scale : TEXCOORD2;
};
"""


def test_centroid_declares_a_centroid_input_and_a_plain_vertex_output():
    fx = effect_for(SHARED + """
V2P VS(float4 p : POSITION)
{
    V2P o;
    o.pos = p;
    o.colour = float4(0.25, 0.5, 0.75, 1);
    o.uv = p.xy;
    o.scale = float2(2, 4);
    return o;
}
float4 PS(V2P i, centroid float2 extra : TEXCOORD3) : COLOR
{
    return i.colour * float4(i.uv * i.scale + extra, 1, 1);
}""", ps="compile ps_3_0 PS()", vs="compile vs_3_0 VS()")
    ps = fx_asm(fx, "PS", "ps_3_0")
    # the member's and the parameter's modifier: _centroid inputs; linear and noperspective
    # are the default interpolation, declared plainly
    decls = [line.split()[0] for line in ps.splitlines() if line.startswith("dcl_texcoord")]
    assert decls == ["dcl_texcoord_centroid", "dcl_texcoord1", "dcl_texcoord2",
                     "dcl_texcoord3_centroid"], ps
    vs = fx_asm(fx, "VS", "vs_3_0")
    # the same struct as a vertex output: no centroid there (o0 is the position)
    assert "dcl_texcoord o1" in vs and "_centroid" not in vs, vs
    ps2 = fx_asm(fx, "PS", "ps_2_0")
    assert "dcl_centroid t0" in ps2 and "dcl_centroid t3.xy" in ps2, ps2


def test_a_centroid_member_renders_its_interpolated_value(backend):
    fx = effect_for("""
struct In { centroid float2 uv : TEXCOORD0; };
float4 PS(In i) : COLOR
{
    return float4(i.uv, 0.5, 1);
}""", ps="compile ps_3_0 PS()")
    img = render(fx, backend)
    # the quad's texture coordinate at pixel (x, y) is (x / 8, y / 8)
    for x, y in ((0, 0), (4, 2), (7, 6)):
        assert np.allclose(img[y, x], (x / 8, y / 8, 0.5, 1), atol=TOL), (x, y, img[y, x])


def test_the_modifiers_are_words_only_at_a_member_and_a_variable_may_take_their_names(backend):
    fx = effect_for("""
struct In { sample float2 uv : TEXCOORD0; };
float4 PS(In i) : COLOR
{
    float linear = 0.5;                 // names, where a statement starts
    float sample = 0.25;
    return float4(i.uv * linear, sample, 1);
}""", ps="compile ps_3_0 PS()")
    img = render(fx, backend)
    assert np.allclose(img[4, 6], (6 / 16, 4 / 16, 0.25, 1), atol=TOL), img[4, 6]

# -- unsigned literals ---------------------------------------------------------------------------

def test_a_u_suffix_makes_an_unsigned_literal(backend):
    fx = effect_for("""
float4 PS() : COLOR
{
    const float big = 1U << 31;          // 2147483648 (an int shift wraps to -2147483648)
    const float wrapped = 1 << 31;
    return float4(big / 4294967296.0,    // 0.5
                  wrapped / -4294967296.0,   // 0.5
                  (7u >> 1) / 4.0,       // 3 / 4
                  1);
}""")
    text = fx_asm(fx, "PS", "ps_2_0")
    assert "0.5, 0.5, 0.75, 1" in text, text
    img = render(fx, backend)
    assert np.allclose(img[4, 4], (0.5, 0.5, 0.75, 1), atol=TOL), img[4, 4]


@pytest.mark.parametrize("literal", ["0x80000000u", "2147483648U"])
def test_unsigned_literals_past_int32_keep_their_value(literal):
    fx = effect_for(f"""
float4 PS() : COLOR
{{
    return float4(({literal} >> 31) * 0.25, 0, 0, 1);   // 1 * 0.25
}}""")
    text = fx_asm(fx, "PS", "ps_2_0")
    assert "0.25, 0, 0, 1" in text, text


# -- a register-bound array past the target's last constant --------------------------------------

BONES = """
float4 Bones[100] : register(c200);     // c200..c299: past vs_2_0's c255
float4 VS(float4 p : POSITION, float4 i : BLENDINDICES) : POSITION
{
    return p * Bones[%s];
}"""


def test_an_array_read_only_by_a_run_time_index_may_run_past_the_last_register():
    fx = effect_for(BONES % "(int)i.x", ps="compile ps_2_0 PS()", vs="compile vs_2_0 VS()",
                    params="float4 PS() : COLOR { return 1; }")
    text = fx_asm(fx, "VS", "vs_2_0")
    assert "mova a0.x" in text and "c[a0.x + 200]" in text, text


@pytest.mark.parametrize("index, last", [("55", "c255"), ("56", "c256")])
def test_a_constant_index_is_checked_against_the_last_register(index, last):
    fx = effect_for(BONES % index, ps="compile ps_2_0 PS()", vs="compile vs_2_0 VS()",
                    params="float4 PS() : COLOR { return 1; }")
    if last == "c255":          # Bones[55] is c255, the last vs_2_0 has
        assert "c255" in fx_asm(fx, "VS", "vs_2_0")
        return
    with pytest.raises(effects.EffectError) as err:
        fx_asm(fx, "VS", "vs_2_0")
    assert "X4507: maximum constant register index exceeded: 'Bones' is bound to c200..c256, " \
        "vs_2_0 has c0..c255" in str(err.value), str(err.value)
    assert err.value.location.line == 3, err.value.location    # the declaration of Bones


# -- an else-if chain selects on each comparison -------------------------------------------------

CHAIN = """
float Mode;
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float4 c = float4(uv, 0.25, 1);
    if (Mode == 0) c.rgb = float3(1, 0, 0);
    else if (Mode == 1) c.rgb = c.rgb * 0.5;
    else if (Mode == 2) c.rgb = 1 - c.rgb;
    return c;
}"""


@pytest.mark.parametrize("mode", [0, 1, 2, 3])
def test_an_else_if_chain_renders_each_side(backend, mode):
    fx = effect_for(CHAIN)
    img = render(fx, backend, params={"Mode": float(mode)})
    for x, y in ((1, 2), (6, 5)):
        u, v = x / 8, y / 8
        want = {0: (1, 0, 0), 1: (u / 2, v / 2, 0.125), 2: (1 - u, 1 - v, 0.75),
                3: (u, v, 0.25)}[mode]
        assert np.allclose(img[y, x], (*want, 1), atol=TOL), (mode, x, y, img[y, x], want)


def test_an_else_if_chain_computes_no_flags_or_products():
    # each `Mode == k` is a cmp on -|Mode - k| choosing between a side's value and the value
    # before it (fxc's form): no 0/1 flag, no `1 - flag`, no product of flags. Here: |Mode|,
    # and Mode - 1, Mode - 2 in one add and one abs (fusion.pack_scalars: fxc's `add r7.xyz,
    # -r4_abs.yxww, c5.x`); two movs building c.rgb; the sides' mul and add, each on c as it
    # was before the chain (an else side is computed where the tests before it were false,
    # dag._prune); one cmp per level on .rgb alone (.a is the same on both sides); .a's mov
    # and the final mov. 12 instructions, where the flags and their products took 23, the
    # levels reselecting the ones before them 18, and a difference each 14.
    text = fx_asm(effect_for(CHAIN), "PS", "ps_2_0")
    body = [line.split()[0] for line in text.splitlines()
            if line and not line.startswith(("ps_", "def", "dcl", "//"))]
    assert body.count("cmp") == 3 and body.count("abs") == 2, text
    assert body.count("mul") == 1 and body.count("add") == 2, text
    assert len(body) == 12, (len(body), text)
    assert all(line.startswith("cmp r") and line.split()[1].endswith(".xyz,")
               for line in text.splitlines() if line.startswith("cmp")), text



NESTED = """
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float s = uv.x - 0.5;
    if (s > 0) { if (uv.y > 0.5) { if (s > 0) { s += 1; } } }
    return float4(s, uv.y, 0, 1);
}"""


def test_nested_ifs_on_one_condition_select_on_it_once():
    # the store stands under (s > 0) * (uv.y > 0.5) * (s > 0): selecting on each distinct
    # compare once is one cmp on s (the repeated factor) and one on 0.5 - uv.y, so two cmps;
    # a select per factor was three
    text = fx_asm(effect_for(NESTED), "PS", "ps_2_0")
    body = [line.split()[0] for line in text.splitlines()
            if line and not line.startswith(("ps_", "def", "dcl", "//"))]
    assert body.count("cmp") == 2, text


def test_nested_ifs_on_one_condition_render(backend):
    img = render(effect_for(NESTED), backend)
    for x, y in ((1, 2), (6, 2), (6, 6), (1, 6)):
        u, v = x / 8, y / 8
        s = u - 0.5
        want = (min(max(s + 1 if s > 0 and v > 0.5 else s, 0), 1), v, 0, 1)
        assert np.allclose(img[y, x], want, atol=TOL), (x, y, img[y, x], want)

# -- `a && b` selects on b's comparison ----------------------------------------------------------

BETWEEN = """
float4 Low = { 0.25, 0.25, 0.25, 0 };
float4 High = { 0.75, 0.75, 0.75, 0 };
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float3 c = float3(uv, 0.5);
    bool3 inside = c >= Low.rgb && c <= High.rgb;
    return float4(inside, all(inside));
}"""


def test_and_of_two_comparisons_renders(backend):
    img = render(effect_for(BETWEEN), backend)
    for x, y in ((1, 4), (4, 4), (7, 4), (4, 1), (4, 7), (5, 3)):
        inx, iny = 0.25 < x / 8 < 0.75, 0.25 < y / 8 < 0.75
        want = (inx, iny, 1, inx and iny)
        assert np.allclose(img[y, x], want, atol=TOL), (x, y, img[y, x], want)


def test_and_of_two_comparisons_is_two_cmps():
    # c - Low and High - c (two adds), a cmp making the first flag, a cmp choosing it or 0 on
    # the second difference (no second flag, no mul), all(): two muls, and the output's movs
    text = fx_asm(effect_for(BETWEEN), "PS", "ps_2_0")
    body = [line.split()[0] for line in text.splitlines()
            if line and not line.startswith(("ps_", "def", "dcl", "//"))]
    assert body.count("cmp") == 2 and body.count("mul") == 2, text


# -- early returns select on each comparison -----------------------------------------------------

# joeyballentine/librw's toon ps_3_0 (ToonGainLimit and friends) returns early from a function
# in several places; fxc writes each `if (p) return a;` as one cmp on p's difference
LIMIT = """
float Limit(float l, float d)
{
    if (d > 0.5) return (1 - l) / d;
    if (d < -0.5) return -l / d;
    return 0.25;
}
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    return float4(Limit(uv.y, uv.x * 2 - 1), 0, 0, 1);
}"""


def test_early_returns_render_each_return(backend):
    img = render(effect_for(LIMIT), backend)
    # d = 2u - 1 at pixel x (u = x / 8), l = v = y / 8; x = 2 and 6 sit on the boundaries
    for x, y, want in ((0, 4, 0.5 / 1.0),            # d = -1: -l/d
                       (1, 2, 0.25 / 0.75),           # d = -0.75
                       (3, 5, 0.25), (4, 1, 0.25),    # -0.5 < d < 0.5: the last return
                       (7, 4, 0.5 / 0.75),            # d = 0.75: (1 - l)/d
                       (7, 6, 0.25 / 0.75)):
        assert np.allclose(img[y, x], (want, 0, 0, 1), atol=TOL), (x, y, img[y, x], want)


def test_early_returns_are_one_cmp_each():
    # d (mad); 0.5 - d and d + 0.5 (two adds); 1 - l, rcp d and the two quotients' muls; a cmp
    # per return that is not the last (fxc's form): no 0/1 flag for 'returned', no max of
    # flags, no `1 - returned`; then the output's two movs. 11, where the flags took 18.
    text = fx_asm(effect_for(LIMIT), "PS", "ps_2_0")
    body = [line.split()[0] for line in text.splitlines()
            if line and not line.startswith(("ps_", "def", "dcl", "//"))]
    assert body.count("cmp") == 2 and "max" not in body, text
    assert len(body) == 11, (len(body), text)


def test_a_cmp_inside_a_cmp_on_the_same_difference_takes_the_same_side():
    from effects.shaders.hlsl.dag import Graph
    g = Graph()
    d, a, b, c = (g.leaf("uniform", (name, 0), 1) for name in "DABC")
    e = g.leaf("uniform", ("E", 0), 1)
    # d >= 0 ? (d >= 0 ? a : b) : c is d >= 0 ? a : c; and on the other side, through a cmp on
    # another difference: d >= 0 ? c : (e >= 0 ? (d >= 0 ? a : b) : c) is d >= 0 ? c : (e >= 0 ? b : c)
    inner = g.op("cmp", [d, a, b])
    pruned = g.op("cmp", [d, inner, c]).node
    assert [x.sig() for x in pruned.args] == [d.sig(), a.sig(), c.sig()]
    outer = g.op("cmp", [d, c, g.op("cmp", [e, inner, c])]).node
    assert outer.args[0].sig() == d.sig() and outer.args[1].sig() == c.sig()
    assert [x.sig() for x in outer.args[2].node.args] == [e.sig(), b.sig(), c.sig()]
    # a different difference (or its negation) is left alone: -d >= 0 is not d < 0 at d = 0
    kept = g.op("cmp", [d.neg(), inner, c]).node
    assert kept.args[1].node is inner.node


# -- compares of one value against several constants: one vector op ------------------------------

# dxwrapper's FixUpMultiStageVertexShader tests `texCount > k` for seven k (fxc: two slt on a
# vector of the k); Effekseer's blend-type chains test `blendType == k` for three
STEPS = """
float Mode;
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    return float4(Mode > 1, Mode > 2, Mode > 3, Mode > 0.5) * uv.x;
}"""


@pytest.mark.parametrize("mode, flags", [(2.5, (1, 1, 0, 1)), (0.75, (0, 0, 0, 1)),
                                         (3.5, (1, 1, 1, 1)), (0.25, (0, 0, 0, 0))])
def test_compares_against_several_constants_render(backend, mode, flags):
    img = render(effect_for(STEPS), backend, params={"Mode": mode})
    for x, y in ((2, 1), (6, 5)):
        want = tuple(f * x / 8 for f in flags)
        assert np.allclose(img[y, x], want, atol=TOL), (mode, x, y, img[y, x], want)


def test_compares_against_several_constants_are_one_add_and_one_cmp():
    # (1, 2, 3, 0.5) - Mode in one add, the four flags in one cmp, the mul, the output's mov:
    # 4 instructions where a difference and a cmp per compare took 10
    text = fx_asm(effect_for(STEPS), "PS", "ps_2_0")
    body = [line.split()[0] for line in text.splitlines()
            if line and not line.startswith(("ps_", "def", "dcl", "//"))]
    assert body == ["add", "cmp", "mul", "mov"], text


def test_one_lane_ops_differing_in_a_constant_pack_into_one_with_a_vector_constant():
    from effects.shaders.hlsl.dag import Graph, reachable
    from effects.shaders.hlsl.fusion import pack_scalars
    g = Graph()
    x = g.leaf("uniform", ("X", 0), 1)
    diffs = [g.op("add", [x, g.const((-k,))]) for k in (1.0, 2.0, 3.0)]
    absd = [g.op("abs", [d]) for d in diffs]
    roots = [list(absd)]
    nodes = reachable([a.node for a in absd])
    assert pack_scalars(nodes, roots, lambda lanes: True) == 4     # 2 adds, then 2 abs
    add, = {a.node.args[0].node for a in roots[0]}
    assert add.op == "add" and add.width == 3
    assert add.args[0].sig() == (x.node.id, (0, 0, 0), False)       # x read replicated
    assert add.args[1].node.value == (-1.0, -2.0, -3.0)           # the constants, one vector
    assert [a.swizzle for a in roots[0]] == [(0,), (1,), (2,)]    # each abs a lane of one
    assert len({a.node.id for a in roots[0]}) == 1
