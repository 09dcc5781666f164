"""Write-mask liveness (effects/shaders/hlsl/liveness.py, issue 31): only the lanes a reader
reads are written. The pass alone on a hand-built graph, then a shader per rule with the
instructions expected, and the pictures of those shaders on both back ends."""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.program.backend import create_backend
from effects.shaders.hlsl import compile_shader
from effects.shaders.hlsl.dag import Graph, Operand
from effects.shaders.hlsl.liveness import analyse


def _swz(op: Operand, *lanes: int) -> Operand:
    return Operand(op.node, tuple(op.swizzle[k] for k in lanes), op.negate)


# -- the pass alone --------------------------------------------------------------------------

def test_each_shape_reads_what_its_instruction_reads():
    g = Graph()
    a = g.leaf("uniform", ("A", 0), 4)
    b = g.leaf("uniform", ("B", 0), 4)
    u = g.leaf("input", ("texcoord", "t0"), 4)
    add = g.op("add", [a, _swz(b, 1, 0, 2, 3)])          # lanes: add.c reads a.c, b.swizzle[c]
    dp3 = g.op("dp3", [u, add])                          # reduce: lanes 0-2 of both, whatever
    rcp = g.op("rcp", [_swz(u, 3)])                      # scalar: the one component named
    pack = g.leaf("pack", None, 4, args=(_swz(dp3, 0), _swz(rcp, 0), _swz(a, 2), _swz(b, 3)))
    roots = [_swz(pack, 0), _swz(pack, 2)]               # pack lanes 1 and 3 are never read
    live = analyse(g.nodes, roots)
    assert live is not None
    assert live.of(pack.node) == {0, 2}
    assert live.of(dp3.node) == {0}
    assert live.of(add.node) == {0, 1, 2}                # dp3 reads three lanes of it
    assert live.of(a.node) == {0, 1, 2}                  # add lanes 0-2 and pack lane 2
    assert live.of(b.node) == {0, 1, 2}                  # through the swizzle .yxz
    assert live.of(u.node) == {0, 1, 2}                  # not .w: only the dead rcp read it
    assert live.of(rcp.node) == frozenset()              # read only by a dead pack lane


def test_code_with_real_flow_control_is_left_whole():
    g = Graph()
    a = g.leaf("uniform", ("A", 0), 4)
    loop = g.leaf("loop", ("rep", 0), 4, args=(a,))
    assert analyse(g.nodes, [_swz(loop, 0)]) is None


# -- a shader per rule ----------------------------------------------------------------------

RULES = """
float4 A; float4 B; float4 C;
float4 Narrow() : COLOR { float4 t = A + B; return float4(t.x * t.y, 0, 0, 1); }
float4 Swizzle() : COLOR { float4 t = A.yxzw + B; return t.xxxx; }
float4 Pack(float2 uv : TEXCOORD0) : COLOR { float4 v = float4(uv, 0, 1) * A; return v.xxxx; }
float4 Dead(float2 uv : TEXCOORD0) : COLOR
{
    float4 v = float4(uv.x, rcp(uv.y), 0.5, 1) * A;
    return v.xxxx;
}
float4 Normalize(float4 n : TEXCOORD0) : COLOR { float4 k = normalize(n); return k.xyzz; }
float4 VS(float4 p : POSITION, float3 n : NORMAL, out float fog : FOG) : POSITION
{
    fog = (n * A.xyz + B.xyz).x;
    return p;
}
technique T { pass P { PixelShader = compile ps_2_0 Narrow(); } }
"""


def code(entry: str, target: str = "ps_2_0") -> tuple[list[str], int]:
    compiled = compile_shader(effects.load_effect(RULES), entry, target)
    lines = [line.strip() for line in compiled.text.splitlines()
             if line.strip() and not line.strip().startswith("//")]
    return lines, compiled.program.stats.total_slots


def test_a_vector_op_read_in_two_lanes_writes_two():
    lines, _ = code("Narrow")
    assert "add r0.xy, c0, c1" in lines, lines


def test_a_swizzle_ps_2_0_refuses_over_four_lanes_is_read_in_place_over_one():
    # all four lanes: .yxzw is no ps_2_0 swizzle, so four movs put A in order first (6 slots)
    lines, slots = code("Swizzle")
    assert lines[1:] == ["add r0.x, c0.y, c1", "mov oC0, r0.x"] and slots == 2, lines


def test_a_vector_built_from_pieces_moves_only_the_lanes_read():
    # float4(uv, 0, 1) * A read in .x: no mov for .y, .z, .w of the vector (4 slots before)
    lines, slots = code("Pack")
    assert "mul r0.x, t0, c0" in lines and slots == 2, lines
    assert not any(line.startswith("def ") for line in lines), lines


def test_what_only_an_unread_lane_needs_is_not_computed():
    lines, slots = code("Dead")
    assert not any(line.startswith("rcp") for line in lines) and slots == 2, lines


def test_normalize_whose_w_is_unread_multiplies_three_lanes():
    lines, _ = code("Normalize")
    assert "mul r0.xyz, t0, r0.x" in lines, lines


def test_a_read_port_copy_copies_the_lanes_read():
    # vs_1_1 reads one constant per instruction: B moves to a temporary, its .x only
    lines, _ = code("VS", "vs_1_1")
    assert "mov r0.x, c1" in lines and "mad oFog.x, v1, c0, r0" in lines, lines


# -- the same shaders drawn ---------------------------------------------------------------------

@pytest.fixture(scope="module", params=("numpy", "gl"))
def backend(request):
    made = create_backend(request.param)
    yield made
    made.close()


@pytest.mark.parametrize("entry, want", [
    ("Narrow", lambda u, v: [0.5 * 0.25 + 0.0, 0, 0, 1]),   # t = (0.5, 0.25, ...)
    ("Swizzle", lambda u, v: [0.5] * 4),                      # A.y + B.x = 0.25 + 0.25
    ("Pack", lambda u, v: [u * 0.25] * 4),
    ("Dead", lambda u, v: [u * 0.25] * 4),
])
def test_the_narrowed_code_draws_the_same_values(backend, entry, want):
    fx = effects.load_effect(RULES.replace("compile ps_2_0 Narrow()", f"compile ps_2_0 {entry}()"))
    img = effects.render(fx, "radeon9700", technique="T", backend=backend,
                         scene={"mesh": "quad", "size": [8, 8]},
                         params={"A": [0.25, 0.25, 0.5, 1.0], "B": [0.25, 0.0, 0.0, 0.0]}
                         ).astype(np.float64) / 255.0
    for y, x in ((1, 1), (2, 5), (6, 3)):
        expected = np.clip(want(x / 8, y / 8), 0, 1)
        assert np.allclose(img[y, x], expected, atol=1.5 / 255), (entry, x, y, img[y, x], expected)
