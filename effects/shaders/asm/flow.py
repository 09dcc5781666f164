"""Shader Model 2.x/3.0 flow control, lowered to the IR's structured blocks.

Each function is the `Handler` of its instruction's row (instructions.py). The lowering
(lower.py) keeps a register file of IR values; a block (if, rep, loop, an inlined callnz
subroutine) that writes registers first turns each of them into an IR variable (`var`), so the
writes inside become `assign`s and the values after the block are what ran. Sources: the
DirectX 9 assembly reference pages for if_bool / if_comp / if_pred, loop, rep, break_comp,
breakp, call, callnz, label, ret, setp_comp, and the predicate register.

Decisions:
- Loop and rep counts are the integer constant's x (`defi`, else the value the pass sets,
  ShaderContext.int_constants, else 0), clamped to D3D's 0..255; loop starts aL at i.y and
  steps it by i.z at the end of each iteration.
- Conditions are IR values whose x is 1 (true) or 0: if_comp / break_comp compare the x of
  the (replicated) sources; b# is its defb value, else the pass's (ShaderContext.
  bool_constants), else FALSE; p0.c (or !p0.c) a predicate component.
- call / callnz are inlined (D3D forbids recursion); a subroutine body runs from its label to
  its ret (the first outside every block). A body with an early ret (inside an if, rep or
  loop) is lowered inside a one-iteration IR loop, the ret being a break out of it (see `ret`).
- Predicated instructions `(p0) op` write, per component, only where p0 (or !p0) is true.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any, Mapping

from effects.base import limits

from effects.base.errors import AsmError
from effects.program.ir import MAX_LOOP_COUNT
from effects.shaders.asm.rewrites import COMPARE

if TYPE_CHECKING:  # pragma: no cover
    from effects.shaders.asm.lower import _Lowering as Lowering
    from effects.shaders.asm.program import Instruction, Operand

OPENS = {"if": "endif", "rep": "endrep", "loop": "endloop"}


def block_end(instrs: list, pos: int) -> int:
    """The index of the endif / endrep / endloop that closes the block opened at `pos`."""
    depth = 0
    for k in range(pos, len(instrs)):
        op = instrs[k].opcode
        if op in OPENS:
            depth += 1
        elif op in OPENS.values():
            depth -= 1
            if depth == 0:
                return k
    raise AsmError(f"{instrs[pos].opcode} is not closed", instrs[pos].location)


def body_end(instrs: list, start: int) -> int:
    """The index of the `ret` or `label` that ends the body (main program or subroutine)
    starting at `start`, or len(instrs): the first one outside every block. A `ret` inside
    an if / rep / loop is an early return, not the body's end."""
    depth = 0
    for k in range(start, len(instrs)):
        op = instrs[k].opcode
        if op in OPENS:
            depth += 1
        elif op in OPENS.values():
            depth -= 1
        elif instrs[k].info.ends_body and (depth <= 0 or op == "label"):
            return k
    return len(instrs)


def early_returns(instrs: list, start: int) -> list[int]:
    """The positions of the early rets (inside a block) of the body starting at `start`."""
    end, depth, found = body_end(instrs, start), 0, []
    for k in range(start, end):
        op = instrs[k].opcode
        depth += op in OPENS
        depth -= op in OPENS.values()
        if op == "ret" and depth > 0:
            found.append(k)
    return found


def dynamic_blocks(instrs: list) -> list[tuple[int, int]]:
    """(start, end) of the blocks whose fragments may diverge: an if on a comparison or a
    predicate, and a loop or rep with a break on one (a break inside a dynamic if counts);
    a subroutine body is dynamic when some callnz on a predicate calls it. Ifs on a
    boolean constant and loop counts are static (the same for every fragment)."""
    found = []
    for pos, instr in enumerate(instrs):
        if instr.opcode == "if" and _divergent(instr):
            found.append((pos, block_end(instrs, pos)))
        elif instr.opcode == "callnz" and _divergent(instr) and instr.srcs:
            start = next((k for k, ins in enumerate(instrs) if ins.opcode == "label" and
                          ins.srcs and ins.srcs[0].index == instr.srcs[0].index), None)
            if start is not None:
                found.append((start, body_end(instrs, start + 1)))
    # after an early ret inside a divergent block, the rest of its body runs for some
    # fragments only
    for start in [0] + [k + 1 for k, ins in enumerate(instrs) if ins.opcode == "label"]:
        end = body_end(instrs, start)
        for k in early_returns(instrs, start):
            if any(s < k < e for s, e in list(found)):
                found.append((k, end))
    branches = list(found)
    for pos, instr in enumerate(instrs):
        if instr.opcode in ("loop", "rep"):
            end = block_end(instrs, pos)
            if any(instrs[k].opcode in ("break", "breakp") and (
                    _divergent(instrs[k]) or any(s < k < e for s, e in branches))
                   for k in range(pos + 1, end)):
                found.append((pos, end))
    return found


def nesting(instrs: list) -> tuple[int, int]:
    """(static, dynamic) flow-control nesting depths, as the caps count them
    (D3DVSHADERCAPS2_0 / D3DPSHADERCAPS2_0): static = loop, rep, if b#, call / callnz b#;
    dynamic = if_comp, if p0, break_comp, breakp, callnz p0."""
    static = dynamic = most_static = most_dynamic = 0
    stack = []
    for instr in instrs:
        op = instr.opcode
        divergent = _divergent(instr)
        if op in OPENS:
            kind = "dynamic" if op == "if" and divergent else "static"
            stack.append(kind)
        elif op in OPENS.values() and stack:
            stack.pop()
        static = stack.count("static")
        dynamic = stack.count("dynamic")
        if op in ("break", "breakp", "callnz") and divergent:
            dynamic += 1
        elif op in ("call", "callnz"):
            static += 1
        most_static, most_dynamic = max(most_static, static), max(most_dynamic, dynamic)
    return most_static, most_dynamic


def _divergent(instr: Instruction) -> bool:
    """A condition that may differ between fragments: a comparison or a predicate."""
    return instr.comparison is not None or any(op.kind == "p" for op in instr.srcs)


def iteration_problems(program: Any, int_constants: Mapping[int, Any] | None = None
                       ) -> list[AsmError]:
    """Nested rep / loop blocks whose counts (defi, else `int_constants`, the pass's i#)
    multiply past the `shader_loop_iterations` limit (effects.base.limits): the reference
    evaluator and GL would run them all."""
    found, counts = [], []
    for instr in program.instructions:
        if instr.opcode in ("rep", "loop"):
            reg = instr.srcs[-1]
            values = integer(program, int_constants or {}, reg.index)
            counts.append(min(max(int(values[0]), 0), MAX_LOOP_COUNT))
            total = 1
            for n in counts:
                total *= n
            if total > limits.get("shader_loop_iterations"):
                found.append(AsmError(limits.message("shader_loop_iterations", total,
                                                     f"{instr.opcode} (nested {len(counts)} deep)"),
                                      instr.location))
        elif instr.opcode in ("endrep", "endloop") and counts:
            counts.pop()
    return found


MAX_CALL_DEPTH = 4    # D3D9: call / callnz nest at most 4 deep (vs_3_0, ps_3_0; 2_x caps <= 4)


def call_problems(instrs: list) -> list[AsmError]:
    """Calls to a missing label, recursion, and call chains deeper than D3D's nesting limit:
    the lowering inlines every call, so each would not lower (or would blow up)."""
    labels = {ins.srcs[0].index: k for k, ins in enumerate(instrs)
              if ins.opcode == "label" and ins.srcs}

    def body_calls(start: int) -> list:
        calls = []
        for k in range(start, body_end(instrs, start)):
            if instrs[k].opcode in ("call", "callnz") and instrs[k].srcs:
                calls.append(instrs[k])
        return calls

    def depth(label: int, path: tuple) -> int:
        if label in path:
            return MAX_CALL_DEPTH + 1                 # recursion: D3D forbids it
        start = labels.get(label)
        if start is None:
            return 1
        inner = [depth(c.srcs[0].index, path + (label,)) for c in body_calls(start + 1)]
        return 1 + max(inner, default=0)

    found = []
    for call in body_calls(0):
        target = call.srcs[0].index
        if target not in labels:
            found.append(AsmError(f"{call.opcode}: l{target} has no label", call.location))
        elif depth(target, ()) > MAX_CALL_DEPTH:
            found.append(AsmError(f"{call.opcode} l{target}: calls nest deeper than "
                                  f"{MAX_CALL_DEPTH} (or recurse), which Direct3D does not "
                                  "allow", call.location))
    return found


def integer(program: Any, int_constants: Mapping[int, Any], index: int) -> tuple:
    """i#: the shader's defi, else the pass's value, else (0, 0, 0, 0)."""
    values = program.int_defs.get(index)
    if values is None:
        values = int_constants.get(index, (0, 0, 0, 0))
    return tuple(values)


def loop_count(lo: Lowering, reg: Operand) -> tuple[int, int, int]:
    """(count, start, step) of the integer constant a rep / loop names."""
    values = integer(lo.p, lo.ctx.int_constants, reg.index)
    return min(max(int(values[0]), 0), MAX_LOOP_COUNT), int(values[1]), int(values[2])


def condition(lo: Lowering, instr: Instruction, reads: dict, operand: int = 0) -> int:
    """The IR condition (x = 1 or 0) of an if / break / callnz: a comparison of two sources,
    a boolean constant or a predicate component."""
    if instr.comparison is not None:
        a = lo.source(instr.srcs[0], reads, scalar=True)
        b = lo.source(instr.srcs[1], reads, scalar=True)
        return lo.e.emit(COMPARE[instr.comparison], {"a": a, "b": b})
    if not instr.srcs[operand:]:
        return lo.e.const(1.0)                        # plain break
    return truth(lo, instr.srcs[operand], reads)


def truth(lo: Lowering, op: Operand, reads: dict) -> int:
    """b# (its defb value) or [!]p0.c as an IR value of 1s and 0s."""
    if op.kind == "b":
        value = lo.p.bool_defs.get(op.index)
        if value is None:
            value = lo.ctx.bool_constants.get(op.index, False)
        return lo.e.const(1.0 if value else 0.0)
    return predicate(lo, op, reads)


def predicate(lo: Lowering, op: Operand, reads: dict) -> int:
    """The predicate register under the operand's swizzle, inverted by `!`."""
    p0 = reads.get(("p", 0))
    value = lo.e.const(0.0) if p0 is None else p0
    value = lo.e.swizzle(value, "".join("xyzw"[c] for c in op.swizzle))
    return lo.b.sub(lo.e.const(1.0), value) if op.negate else value


# -- handlers -----------------------------------------------------------------------------------

def if_(lo: Lowering, instr: Instruction, reads: dict) -> None:
    cond = condition(lo, instr, reads)
    lo.enter_block(lo.pos)
    lo.b.if_(cond)


def else_(lo: Lowering, instr: Instruction, reads: dict) -> None:
    lo.b.else_()


def endif(lo: Lowering, instr: Instruction, reads: dict) -> None:
    lo.b.endif()


def rep(lo: Lowering, instr: Instruction, reads: dict) -> None:
    count, _, _ = loop_count(lo, instr.srcs[0])
    lo.enter_block(lo.pos)
    lo.loops.append(None)
    lo.b.loop(count)


def loop(lo: Lowering, instr: Instruction, reads: dict) -> None:
    count, start, step = loop_count(lo, instr.srcs[1])
    lo.enter_block(lo.pos)
    outer = lo.regs.get(("aL", 0))
    counter = lo.b.var(lo.e.const(float(start)))
    lo.regs[("aL", 0)] = counter
    lo.loops.append((counter, outer, start, step, count))
    lo.b.loop(count)


def endloop(lo: Lowering, instr: Instruction, reads: dict) -> None:
    counter, outer, _, step, _ = lo.loops.pop()
    lo.b.assign(counter, lo.b.add(counter, lo.e.const(float(step))))
    lo.b.endloop()
    if outer is None:
        lo.regs.pop(("aL", 0), None)
    else:
        lo.regs[("aL", 0)] = outer
    after_loop(lo)


def endrep(lo: Lowering, instr: Instruction, reads: dict) -> None:
    lo.loops.pop()
    lo.b.endloop()
    after_loop(lo)


def break_(lo: Lowering, instr: Instruction, reads: dict) -> None:
    lo.b.break_(condition(lo, instr, reads))


def ret(lo: Lowering, instr: Instruction, reads: dict) -> None:
    """An early ret (inside a block; a ret outside every block ends the body before it is
    lowered): the body runs inside a one-iteration loop (`Lowering.body`), so a ret leaves
    it with a break; from inside the body's own loops it sets the body's flag first, and
    each of those loops breaks on the flag when it ends (`after_loop`)."""
    flag, loops_at_entry = lo.returns[-1]
    if len(lo.loops) > loops_at_entry:
        lo.b.assign(flag, lo.e.const(1.0))
    lo.b.break_(lo.e.const(1.0))


def after_loop(lo: Lowering) -> None:
    """After a loop inside a body with early rets: leave the next loop out too where a ret
    inside it set the flag."""
    if lo.returns and len(lo.loops) >= lo.returns[-1][1]:
        lo.b.break_(lo.returns[-1][0])


def call(lo: Lowering, instr: Instruction, reads: dict) -> None:
    lo.inline(instr.srcs[0])


def callnz(lo: Lowering, instr: Instruction, reads: dict) -> None:
    cond = truth(lo, instr.srcs[1], reads)
    lo.enter_block(lo.pos, subroutine=instr.srcs[0])
    lo.b.if_(cond)
    lo.inline(instr.srcs[0])
    lo.b.endif()


def setp(lo: Lowering, instr: Instruction, reads: dict) -> None:
    a = lo.source(instr.srcs[0], reads)
    b = lo.source(instr.srcs[1], reads)
    lo.write(instr, lo.e.emit(COMPARE[instr.comparison], {"a": a, "b": b}))


def aL_candidates(lo: Lowering, offset: int, limit: int) -> list[int]:
    """The constant registers c[aL + offset] can reach in the innermost loop: its aL runs
    start, start + step, ... for count iterations."""
    loops = [entry for entry in lo.loops if entry is not None]
    if not loops:
        return []
    _, _, start, step, count = loops[-1]
    return sorted({start + k * step + offset for k in range(count)} & set(range(limit)))

