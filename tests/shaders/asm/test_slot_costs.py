"""Slot costs as the limit decision counts them (issue 31): fxc's own count where its listings
show it differs from the instruction reference (lrp: 1 slot on ps_2_0 and up, the reference's
2), the reference's elsewhere; each row keeps the reference's number beside it."""
from __future__ import annotations

from effects.base.errors import Location
from effects.model import ShaderBlock
from effects.shaders.asm import assemble, lookup


def test_lrp_counts_one_slot_on_ps_2_0_and_up_as_fxc_counted():
    for version in ("ps_2_0", "ps_2_a", "ps_2_b", "ps_2_x", "ps_3_0"):
        row = lookup("lrp", version)
        assert (row.slot_cost(version), row.documented_cost(version)) == (1, 2), version


def test_lrp_keeps_the_reference_cost_where_no_fxc_count_was_read():
    assert lookup("lrp", "vs_2_0").slot_cost("vs_2_0") == 2
    assert lookup("lrp", "ps_1_4").slot_cost("ps_1_4") == 1        # the reference's own 1


def test_pow_and_nrm_count_three_as_fxc_and_the_reference_agree():
    for op in ("pow", "nrm"):
        row = lookup(op, "ps_2_0")
        assert row.slot_cost("ps_2_0") == row.documented_cost("ps_2_0") == 3


def test_a_program_counts_lrp_once_toward_the_arithmetic_limit():
    # 2 lrp + 1 pow + 1 nrm + 2 mov = 2*1 + 3 + 3 + 2 = 10 arithmetic slots (12 by the
    # reference's lrp), 1 texture slot
    src = ("ps_2_0\ndcl t0\ndcl_2d s0\ntexld r0, t0, s0\nlrp r1, r0.x, r0, t0\n"
           "lrp r1, r0.y, r1, t0\npow r2.x, r1.x, r0.z\nnrm r3.xyz, r1\nmov r3.w, r2.x\n"
           "mov oC0, r3\n")
    prog = assemble(ShaderBlock("pixel", None, src, location=Location("t.fx", 1, 1)))
    stats = prog.stats
    assert (stats.texture_slots, stats.arithmetic_slots, stats.total_slots) == (1, 10, 11)
