"""The one register allocator (effects/shaders/hlsl/allocate.py), alone: instructions on
virtual temporaries built by hand, the registers worked out by hand from their live ranges."""
from __future__ import annotations

import pytest

from effects.shaders.hlsl.allocate import (OutOfRegisters, RegisterConflict, allocate,
                                           live_ranges)
from effects.shaders.asm.program import Instruction as Instr, Operand as Reg
from effects.shaders.hlsl.records import instruction, read, reg


def vr(n: int) -> Reg:
    return reg("vr", n)


def src(r: Reg) -> Reg:
    return read(r, {i: i for i in range(4)})


def ins(op: str, dst: Reg | None, *srcs: Reg) -> Instr:
    return instruction(op, dst, (0, 1, 2, 3) if dst is not None else (), [src(s) for s in srcs],
                       "ps_3_0")


def test_a_register_is_reused_once_its_value_is_read_for_the_last_time():
    # 0: vr0 = c0        vr0 lives 0..2
    # 1: vr1 = c1        vr1 lives 1..2
    # 2: vr2 = vr0+vr1   vr2 lives 2..3: its instruction reads vr0 last and may write it
    # 3: oC0 = vr2
    code = [ins("mov", vr(0), reg("c", 0)), ins("mov", vr(1), reg("c", 1)),
            ins("add", vr(2), vr(0), vr(1)), ins("mov", reg("oC", 0), vr(2))]
    assert live_ranges(code) == ({0: 0, 1: 1, 2: 2}, {0: 2, 1: 2, 2: 3})
    assert allocate(code) == {0: 0, 1: 1, 2: 0}


def test_a_macro_does_not_write_the_register_it_reads_last():
    # lrp is a macro (two slots on ps_2_0): its page does not promise it reads before it
    # writes, so its result takes a third register
    code = [ins("mov", vr(0), reg("c", 0)), ins("mov", vr(1), reg("c", 1)),
            ins("lrp", vr(2), vr(0), vr(1), vr(1)), ins("mov", reg("oC", 0), vr(2))]
    assert allocate(code) == {0: 0, 1: 1, 2: 2}
    # ps_1_x reads every source first (touch always): the same code takes two
    assert allocate(code, lambda i, v: True) == {0: 0, 1: 1, 2: 0}


def test_a_register_set_before_a_loop_and_read_in_it_lives_to_the_endrep():
    # vr0 is read at 2 inside rep..endrep (1..4): the next iteration reads it again, so vr2
    # (written at 3) may not take r0
    code = [ins("mov", vr(0), reg("c", 0)), ins("rep", None, reg("i", 0)),
            ins("add", vr(1), vr(0), reg("c", 1)), ins("mov", vr(2), vr(1)),
            ins("endrep", None), ins("mov", reg("oC", 0), vr(2))]
    first, last = live_ranges(code)
    assert last[0] == 4
    alloc = allocate(code)
    assert alloc[0] == 0 and alloc[2] != 0


def test_pinned_registers_first_and_their_clash():
    # vr2 pinned to r0 from 2 to 3; vr0 (0..1) fits before it in r0, vr1 (1..3) does not
    code = [ins("mov", vr(0), reg("c", 0)), ins("mov", vr(1), vr(0)),
            ins("mov", vr(2), reg("c", 1)), ins("add", reg("oC", 0), vr(1), vr(2))]
    assert allocate(code, lambda i, v: True, {2: 0}) == {2: 0, 0: 0, 1: 1}
    with pytest.raises(RegisterConflict) as err:
        allocate(code, lambda i, v: True, {1: 0, 2: 0})
    assert err.value.vr == 2


def test_out_of_registers_names_the_temporary_that_found_none():
    code = [ins("mov", vr(0), reg("c", 0)), ins("mov", vr(1), reg("c", 1)),
            ins("mov", vr(2), reg("c", 2)), ins("mad", reg("oC", 0), vr(0), vr(1), vr(2))]
    assert allocate(code, count=3) == {0: 0, 1: 1, 2: 2}
    with pytest.raises(OutOfRegisters) as err:
        allocate(code, count=2)
    assert err.value.vr == 2
