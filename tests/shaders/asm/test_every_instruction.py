"""Every instruction of every shader version in the instruction table either lowers and
renders on both back ends, or validation rejects it with a located reason (valid means
renders: issue 12).

For each (row, version) pair of effects.shaders.asm.instructions.TABLE a small program that
uses the instruction is built from the row's operand roles (or, for instructions that only
make sense in a sequence, from a short snippet), and must pass the version's assembly checks.
Then `lowering_problems` (what validation reports) is empty and the program lowers and draws
a 2x2 quad on the NumPy reference and on GL with finite results that agree, or it is not
empty and every problem is located on the instruction's line.
"""
from __future__ import annotations

import numpy as np
import pytest

from effects.program.backend import create_backend
from effects.base.errors import Location
from effects.model import ShaderBlock
from effects.program.passprogram import PassProgram, RenderState
from effects.d3d9.precision import LoweringOptions
from effects.shaders.asm import INSTRUCTIONS, assemble, check
from effects.shaders.asm.lower import (ShaderContext, lower_pixel_shader, lower_vertex_shader,
                                       lowering_problems)
from effects.shaders.asm.versions import VERSION_ORDER

MARK = "// the instruction"
# Instructions that need company: the snippet around them (versions in the key's family).
PS1_SNIPPETS = {
    "tex": "tex t0 " + MARK,
    "texcoord": "texcoord t0 " + MARK,
    "texbem": "tex t0\ntexbem t1, t0 " + MARK,
    "texbeml": "tex t0\ntexbeml t1, t0 " + MARK,
    "texreg2ar": "tex t0\ntexreg2ar t1, t0 " + MARK,
    "texreg2gb": "tex t0\ntexreg2gb t1, t0 " + MARK,
    "texreg2rgb": "tex t0\ntexreg2rgb t1, t0 " + MARK,
    "texm3x2pad": "tex t0\ntexm3x2pad t1, t0 " + MARK + "\ntexm3x2tex t2, t0",
    "texm3x2tex": "tex t0\ntexm3x2pad t1, t0\ntexm3x2tex t2, t0 " + MARK,
    "texm3x2depth": "tex t0\ntexm3x2pad t1, t0\ntexm3x2depth t2, t0 " + MARK,
    "texm3x3pad": "tex t0\ntexm3x3pad t1, t0 " + MARK + "\ntexm3x3pad t2, t0\ntexm3x3tex t3, t0",
    "texm3x3tex": "tex t0\ntexm3x3pad t1, t0\ntexm3x3pad t2, t0\ntexm3x3tex t3, t0 " + MARK,
    "texm3x3": "tex t0\ntexm3x3pad t1, t0\ntexm3x3pad t2, t0\ntexm3x3 t3, t0 " + MARK,
    "texm3x3spec": "tex t0\ntexm3x3pad t1, t0\ntexm3x3pad t2, t0\n"
                   "texm3x3spec t3, t0, c0 " + MARK,
    "texm3x3vspec": "tex t0\ntexm3x3pad t1, t0\ntexm3x3pad t2, t0\ntexm3x3vspec t3, t0 " + MARK,
    "texdp3": "tex t0\ntexdp3 t1, t0 " + MARK,
    "texdp3tex": "tex t0\ntexdp3tex t1, t0 " + MARK,
    "texkill": "texkill t0 " + MARK,
    "cnd": "mov r0, c0\ncnd r0, r0.a, c0, c1 " + MARK,
}
PS14_SNIPPETS = {
    "texld": "texld r0, t0 " + MARK,
    "texcrd": "texcrd r0.xyz, t0 " + MARK,
    "texkill": "texkill t0 " + MARK + "\nmov r0, c0",
    "texdepth": "texcrd r5.xyz, t0\nphase\ntexdepth r5 " + MARK + "\nmov r0, c0",
    "phase": "texld r1, t0\nphase " + MARK + "\nmov r0, r1",
    "bem": "texld r0, t0\nbem r1.xy, r0, c0 " + MARK + "\nphase\ntexld r1, r1\nmov r0, r1",
}
FLOW_SNIPPETS = {
    "if": "if b0 " + MARK + "\nmov r0, c1\nelse\nmov r0, c2\nendif",
    "else": "if b0\nmov r0, c1\nelse " + MARK + "\nmov r0, c2\nendif",
    "endif": "if_lt c0.x, c1.x\nmov r0, c1\nendif " + MARK,
    "rep": "rep i0 " + MARK + "\nadd r0, r0, c1\nendrep",
    "endrep": "rep i0\nadd r0, r0, c1\nendrep " + MARK,
    "loop": "loop aL, i0 " + MARK + "\nadd r0, r0, c1\nendloop",
    "endloop": "loop aL, i0\nadd r0, r0, c1\nendloop " + MARK,
    "break": "rep i0\nbreak_ge r0.x, c1.x " + MARK + "\nadd r0, r0, c1\nendrep",
    "breakp": "setp_ge p0, r0, c1\nrep i0\nbreakp p0.x " + MARK + "\nadd r0, r0, c1\nendrep",
    "call": "call l0 " + MARK,
    "callnz": "callnz l0, b0 " + MARK,
    "label": "call l0",
    "ret": "call l0",
    "setp": "setp_gt p0, c0, c1 " + MARK + "\n(p0) mov r0, c2",
    "defi": "defi i1, 1, 2, 3, 4 " + MARK,
    "defb": "defb b1, false " + MARK,
}
SUBROUTINE = "ret\nlabel l0 {label}\nadd r0, r0, c2\nret {ret}"


def _operand(role: str, k: int, row, version: str) -> str:
    if role == "d":
        kinds = row.dst_kinds or ("r",)
        reg = {"r": "r0", "t": "t1", "a": "a0", "p": "p0", "c": "c9", "i": "i1", "b": "b1"}[
            kinds[-1] if "r" not in kinds else "r"]
        mask = {"xy": ".xy", "xyz": ".xyz"}.get(row.writes, "")
        if row.name == "sincos" or (row.name == "frc" and version == "vs_1_1"):
            mask = ".xy"
        elif row.name == "crs":
            mask = ".xyz"
        elif reg == "a0" or (row.name in ("crs", "nrm") and version.startswith("ps")):
            mask = ".x" if reg == "a0" else ".xyz"
        return reg + mask
    if role in "sx":
        kinds = row.src_kind(k)
        if kinds is not None and "c" not in kinds:
            return {"t": "t0", "r": "r1"}[kinds[0]] + (".x" if role == "x" else "")
        if row.name == "sgn" and k > 0:
            return f"r{k + 1}"
        if row.name == "texldd":
            return "c0" if k == 0 else "c1"
        third = "v0" if version.startswith("ps_1") else "r2"
        return ("r1", "c0", third)[k % 3] + (".x" if role == "x" else "")
    return {"S": "s0", "f": "1.0", "n": "1", "B": "true", "l": "l0", "b": "b0", "I": "i0",
            "L": "aL", "p": "p0"}[role]


def _body(row, version: str) -> str | None:
    name = row.name
    if version in ("ps_1_0", "ps_1_1", "ps_1_2", "ps_1_3") and name in PS1_SNIPPETS:
        return PS1_SNIPPETS[name]
    if version == "ps_1_4" and name in PS14_SNIPPETS:
        return PS14_SNIPPETS[name]
    if name in FLOW_SNIPPETS:
        return FLOW_SNIPPETS[name]
    if name == "def":
        return "def c5, 1, 2, 3, 4 " + MARK
    if name == "dcl":
        return None                      # every generated program declares its inputs
    if name in ("texld", "texldp", "texldb", "texldl") and version != "ps_1_4":
        coord = "t0" if version.startswith("ps_2") else ("v0" if version == "ps_3_0" else "c0")
        return f"{name} r0, {coord}, s0 {MARK}"
    if name == "texldd":
        coord = "t0" if version.startswith("ps_2") else "v0"
        return f"texldd r0, {coord}, s0, c0, c1 {MARK}"
    if name == "texkill":
        return ("texkill t0 " if version.startswith("ps_2") else "texkill v0 ") + MARK
    roles = row.operands
    ops = [_operand(roles[0], -1, row, version)] if row.has_dst else []
    ops += [_operand(r, k, row, version) for k, r in enumerate(row.source_roles)]
    text = f"{name} {', '.join(ops)}".strip()
    if name == "setp":
        text = text.replace("setp", "setp_gt", 1)
    return f"{text} {MARK}"


def program_text(row, version: str) -> str | None:
    body = _body(row, version)
    if body is None:
        return None
    ps, v1 = version.startswith("ps"), version in ("ps_1_0", "ps_1_1", "ps_1_2", "ps_1_3")
    lines = [version]
    if version == "ps_3_0":
        lines += ["dcl_texcoord0 v0", "dcl_2d s0"]
    elif ps and not version.startswith("ps_1"):
        lines += ["dcl t0", "dcl_2d s0"]
    elif not ps:
        lines += ["dcl_position v0"] + (["dcl_position o0", "dcl_color o1", "dcl_2d s0"]
                                        if version == "vs_3_0" else [])
    lines += ["def c0, 0.5, 0.25, 0.75, 1", "def c1, 0.25, 1, 0.5, 0.125",
              "def c2, 0.125, 0.5, 1, 0.25"]
    if "i0" in body or "b0" in body:
        lines += ["defi i0, 3, 0, 1, 0", "defb b0, true"]
    if not v1 and version != "ps_1_4":
        lines += ["mov r0, c0", "mov r1, c1", "mov r2, c2", "mov r3, c0"]
    elif v1 or body.split()[0] not in PS14_SNIPPETS:
        lines += ["mov r0, c0", "mov r1, c1"] + ([] if v1 else ["mov r2, c2"])
    texture_first = v1 and row.is_texture      # ps_1_1-1_3: texture instructions first
    if body.split()[0] in ("def", "defi", "defb") or texture_first:  # before the others
        first = next(k for k, t in enumerate(lines) if t.startswith("mov"))
        lines.insert(first, body)
    else:
        lines += body.split("\n")
    if ps and not version.startswith("ps_1"):
        lines.append("mov oC0, r0")
    elif not ps:
        lines += (["mov o0, v0", "mov o1, r0"] if version == "vs_3_0"
                  else ["mov oPos, v0", "mov oD0, r0"])
    if "l0" in body:
        lines += SUBROUTINE.format(label="", ret="").split("\n")
    elif v1 and "tex" in body and "texcoord" not in body and "texkill" not in body:
        last = body.split("\n")[-1].split()[1].rstrip(",")
        lines.append(f"mov r0, {last}")
    return "\n".join(lines)


PAIRS = sorted({(row.name, v) for row in INSTRUCTIONS for v in row.versions.names},
               key=lambda p: (p[0], VERSION_ORDER.index(p[1])))


def _row(name: str, version: str):
    return next(r for r in INSTRUCTIONS if r.name == name and version in r.versions)


@pytest.fixture(scope="module")
def backends():
    made = {name: create_backend(name) for name in ("numpy", "gl")}
    yield made
    for backend in made.values():
        backend.close()


def _draw(backend, passp: PassProgram) -> np.ndarray:
    position = np.array([[-1, 1, 0.5, 1], [1, 1, 0.5, 1], [-1, -1, 0.5, 1], [1, -1, 0.5, 1]],
                        np.float32)
    streams = {"position": position, "texcoord0": np.full((4, 4), 0.5, np.float32)}
    backend.begin_frame((2, 2), (0, 0, 0, 0), 1.0, 0, format="A32B32G32R32F")
    backend.draw(passp, streams, np.arange(4), "strip", {})
    return backend.end_frame()


@pytest.mark.parametrize("name, version", PAIRS, ids=[f"{n}-{v}" for n, v in PAIRS])
def test_instruction_lowers_and_renders_or_is_rejected(backends, name, version):
    row = _row(name, version)
    text = program_text(row, version)
    if text is None:                     # dcl: in every generated program
        assert name == "dcl"
        return
    stage = "pixel" if version.startswith("ps") else "vertex"
    prog = assemble(ShaderBlock(stage, None, text, location=Location("t.fx", 1, 1)))
    line = 1 + next(k for k, t in enumerate(text.split("\n")) if MARK in t or (
        name in ("label", "ret") and t.startswith(name)))
    errors = check(prog)
    if errors:   # the table lists the instruction, but the version lacks a register it needs
        assert all(" has no " in e.message or "predicated instructions need" in e.message
                   for e in errors), (text, [str(e) for e in errors])
        return
    problems = lowering_problems(prog)
    if problems:                         # validation rejects it, located
        assert all(p.location.line == line for p in problems), [str(p) for p in problems]
        return
    options = ShaderContext(LoweringOptions(), constant_prefix="vc" if stage == "vertex" else "c")
    if stage == "pixel":
        passp = PassProgram(lower_pixel_shader(prog, options), render_state=RenderState(
            cull_mode="NONE"))
    else:
        fragment = lower_pixel_shader(assemble(ShaderBlock(
            "pixel", None, "ps_2_0\ndcl v0\nmov oC0, v0", location=Location("t.fx", 1, 1))),
            ShaderContext(LoweringOptions()))
        passp = PassProgram(fragment, vertex=lower_vertex_shader(prog, options),
                            render_state=RenderState(cull_mode="NONE"))
    reference, gl = (_draw(backends[b], passp) for b in ("numpy", "gl"))
    assert np.isfinite(reference).all()
    np.testing.assert_allclose(gl, reference, atol=2e-3, err_msg=text)


def test_what_does_not_render_is_exactly_this():
    # The walk's other outcomes, named: none. The table lists each instruction only in the
    # versions whose registers it needs (p0, aL), and every row lowers, so every pair renders.
    refused, rejected, rendered = set(), set(), 0
    for name, version in PAIRS:
        text = program_text(_row(name, version), version)
        if text is None:
            continue
        stage = "pixel" if version.startswith("ps") else "vertex"
        prog = assemble(ShaderBlock(stage, None, text, location=Location("t.fx", 1, 1)))
        if check(prog):
            refused.add((name, version))
        elif lowering_problems(prog):
            rejected.add((name, version))
        else:
            rendered += 1
    assert refused == set()
    assert rejected == set()
    assert rendered == 587
