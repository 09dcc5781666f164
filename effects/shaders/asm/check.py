"""Validate an assembled program against the rules of its version.

`check(program)` returns every violation as a located AsmError (sorted by position): which
instructions the version has, register kinds and ranges, read ports, modifiers, swizzles and
write masks, slot limits, the ps_1_1–1_3 texture-address rules, the ps_1_4 phase rules, the
ps_2_0 dependent-read limit, uninitialised reads, declarations and the final output write.
Limits come from versions.py and costs from instructions.py (sources named there).
"""
from __future__ import annotations

from effects.base.errors import AsmError, Location
from effects.shaders.asm.instructions import versions_having
from effects.shaders.asm.program import AsmProgram, Instruction, Operand
from effects.shaders.asm.ps1_rules import PS1Rules, coissue_split
from effects.shaders.asm.stats import instruction_slots
from effects.shaders.asm.versions import IDENTITY, KIND_NAMES, PS20_SWIZZLES

_MODIFIER_SYNTAX = {"bias": "_bias", "bx2": "_bx2", "x2": "_x2", "invert": "1-", "dz": "_dz",
                    "dw": "_dw", "abs": "_abs"}
_SHIFT_SYNTAX = {1: "_x2", 2: "_x4", 3: "_x8", -1: "_d2", -2: "_d4", -3: "_d8"}
_OUTPUT_ONLY = {"o", "oPos", "oD", "oT", "oFog", "oPts", "oC", "oDepth"}
# What a source of each non-vector role may name (the vector roles s and x read the version's
# readable kinds, or the row's narrower list).
_ROLE_KINDS = {"S": ("s",), "l": ("l",), "b": ("b", "p"), "I": ("i",), "L": ("aL",), "p": ("p",)}


def _ordinal(n: int) -> str:
    suffix = "th" if 10 <= n % 100 <= 20 else {1: "st", 2: "nd", 3: "rd"}.get(n % 10, "th")
    return f"{n}{suffix}"


def _register_range(kind: str, count: int) -> str:
    if count == 1:
        return f"{kind}0" if kind not in ("oPos", "oFog", "oPts", "oDepth", "aL", "vPos", "vFace") else kind
    return f"{kind}0–{kind}{count - 1}"


class _Checker(PS1Rules):
    def __init__(self, program: AsmProgram) -> None:
        self.p = program
        self.rules = program.rules
        self.v = program.name
        self.errors: list[AsmError] = []
        self.out_of_range: set[str] = set()   # registers already reported: once each
        self.written: set[tuple[str, int | None]] = set()
        # a pixel shader's temporaries by component: the reference's rule for them ("If a
        # temporary register uses components that are not defined in previous code, shader
        # validation will fail": the ps temporary register page), from ps_2_0, where a
        # sampler's dcl says which coordinate components a read takes. A vertex shader's page
        # asks only that the register be written first; ps_1_x keeps that too (a ps_1_4
        # texld r(n), r(n) after bem takes what its stage's texture needs, which no dcl names)
        self.written_lanes: dict[tuple[str, int | None], set[int]] = {}
        self.by_component = program.kind == "ps" and self.rules.major >= 2
        self.written_phase: dict[tuple[str, int | None], int] = {}
        # asked for every source: the declared registers (AsmProgram.declaration's answer, the
        # first declaration of each), and whether this vertex shader declares its inputs
        self.declared: set[tuple[str, int | None]] = {(d.register.kind, d.register.index)
                                                      for d in program.dcls}
        self.vs_declares_inputs = program.kind == "vs" and (
            program.has_decl_block or any(not d.from_decl for d in program.dcls))

    def err(self, message: str, location: Location) -> None:
        self.errors.append(AsmError(message, location,
                                    source_line=self.p.source_line(location)))

    # ------------------------------------------------------------------------------------------
    def run(self) -> list[AsmError]:
        self._setup_statements()
        self._instructions()
        self._slots()
        if self.rules.is_ps11_13:
            self._ps11_texture_rules()
        if self.rules.is_ps14:
            self._ps14_phase_rules()
        self._dependent_reads()
        self._flow_nesting()
        self._final_output()
        return sorted(self.errors, key=lambda e: (e.location.line, e.location.column))

    # -- def / dcl -----------------------------------------------------------------------------
    def _setup_statements(self) -> None:
        for at in self.p.phase_locations:   # `phase` splits a ps_1_4 shader; no other version has it
            if self.v not in _versions_of("phase"):
                self.err(_not_available("phase", self.v), at)
        seen: set[tuple[str, int | None]] = set()
        for cd in self.p.def_statements:
            reg = cd.register
            opcode = {"c": "def", "i": "defi", "b": "defb"}.get(reg.kind, "def")
            if self.v not in _versions_of(opcode):
                self.err(_not_available(opcode, self.v), cd.location)
                continue
            want = 1 if opcode == "defb" else 4
            if reg.kind not in ("c", "i", "b"):
                self.err(f"def needs a constant register (c#), not {reg.name}", reg.location)
                continue
            if len(cd.values) != want:
                self.err(f"{opcode} {reg.name} needs {want} value{'s' if want > 1 else ''}; "
                         f"found {len(cd.values)}", cd.location)
            self._check_index(reg)
            if cd.after_code:
                self.err(f"{opcode} must come before the first instruction", cd.location)
        for d in self.p.dcls:
            if d.from_decl:
                continue
            reg = d.register
            if self.v not in _versions_of("dcl"):
                self.err(_not_available("dcl", self.v), d.location)
                continue
            if d.after_code:
                self.err("declarations must come before the first instruction", d.location)
            key = (reg.kind, reg.index)
            if key in seen:
                self.err(f"{reg.name} is declared twice", d.location)
            seen.add(key)
            if not self._check_index(reg):
                continue
            self._check_declaration(d)

    def _check_declaration(self, d) -> None:
        reg, kind = d.register, d.register.kind
        if kind == "s":
            if self.p.kind == "vs" and self.rules.major < 3:
                self.err(f"{self.v} has no samplers to declare", d.location)
            elif d.sampler_type is None:
                self.err(f"dcl {reg.name} needs a texture type: dcl_2d, dcl_cube or dcl_volume",
                         d.location)
            return
        if d.sampler_type is not None:
            self.err(f"dcl_{d.sampler_type} declares a sampler (s#), not {reg.name}", d.location)
            return
        if self.p.kind == "vs":
            if kind not in ("v", "o"):
                self.err(f"a vertex shader declares inputs (v#) or vs_3_0 outputs (o#), not "
                         f"{reg.name}", d.location)
            elif d.usage is None:
                self.err(f"dcl {reg.name} needs a usage, e.g. dcl_position {reg.name}",
                         d.location)
        elif self.rules.major == 2:
            if kind not in ("t", "v"):
                self.err(f"{self.v} declares t#, v# and s# registers, not {reg.name}", d.location)
            elif d.usage is not None:
                self.err(f"{self.v} declares {reg.name} with plain dcl (usages are for vertex "
                         "shaders and ps_3_0)", d.location)
        elif kind not in ("v", "vPos", "vFace"):
            self.err(f"{self.v} declares v# and s# registers, not {reg.name}", d.location)

    # -- per instruction -----------------------------------------------------------------------
    def _instructions(self) -> None:
        prev: Instruction | None = None
        for ins in self.p.instructions:
            if self.v not in ins.info.versions:
                self.err(_not_available(ins.opcode, self.v), ins.location)
                self._record_write(ins)
                prev = ins
                continue
            self._instruction_modifiers(ins)
            self._coissue(ins, prev)
            ok = self._operand_kinds(ins)
            if ok:
                self._source_modifiers(ins)
                self._swizzles(ins)
                self._write_mask(ins)
                self._read_ports(ins)
                self._special(ins)
                self._reads_initialised(ins)
            self._record_write(ins)
            prev = ins

    def _instruction_modifiers(self, ins: Instruction) -> None:
        r = self.rules
        if not ins.info.modifiers and (ins.shift or ins.saturate):
            mod = _SHIFT_SYNTAX.get(ins.shift) or "_sat"
            self.err(f"{ins.opcode} takes no instruction modifiers ({mod})", ins.location)
            return
        if ins.shift not in r.shifts and ins.shift:
            syntax = _SHIFT_SYNTAX[ins.shift]
            if r.shifts:
                allowed = ", ".join(_SHIFT_SYNTAX[s] for s in r.shifts if s)
                self.err(f"the {syntax} instruction modifier is not available in {self.v} "
                         f"(it has {allowed})", ins.location)
            else:
                self.err(f"{self.v} has no result shift modifiers ({syntax})", ins.location)
        if ins.saturate and not r.saturate:
            self.err(f"the _sat modifier is not available in {self.v}", ins.location)
        if ins.partial_precision and not r.partial_precision:
            self.err(f"the _pp modifier needs ps_2_0 or later (this program is {self.v})",
                     ins.location)
        if ins.predicate is not None and not r.predication:
            self.err(f"predicated instructions need ps_2_x, ps_2_a, ps_3_0 or vs_2_x "
                     f"(this program is {self.v})", ins.predicate.location)

    def _coissue(self, ins: Instruction, prev: Instruction | None) -> None:
        if not ins.coissue:
            return
        if not self.rules.coissue:
            self.err(f"co-issue (+) exists only in ps_1_x, not in {self.v}", ins.location)
            return
        if not ins.is_arithmetic or prev is None or not prev.is_arithmetic or prev.coissue:
            self.err("a co-issued (+) instruction must pair with the arithmetic instruction "
                     "just before it", ins.location)
            return
        if not coissue_split(prev.dst.components if prev.dst else (),
                             ins.dst.components if ins.dst else ()):
            self.err("co-issued instructions must split the work: one writes .rgb (colour), "
                     "the other .a (alpha)", ins.location)

    def _operand_kinds(self, ins: Instruction) -> bool:
        ok = True
        info = ins.info
        if ins.dst is not None:
            allowed = info.dst_kinds or self.rules.writable
            if ins.dst.kind not in allowed:
                self.err(self._kind_message(ins, ins.dst, allowed, write=True),
                         ins.dst.location)
                ok = False
            elif not self._check_index(ins.dst):
                ok = False
        roles = info.source_roles if not (ins.opcode in ("if", "break") and ins.comparison) \
            else "ss"
        for i, (src, role) in enumerate(zip(ins.srcs, roles)):
            if role in "sx":
                allowed = info.src_kind(i) or self.rules.readable
            else:
                allowed = _ROLE_KINDS.get(role, ())
            if src.kind == "imm":
                self.err(f"{ins.opcode} needs a register here, not the number {src.text}",
                         src.location)
                ok = False
            elif src.kind not in allowed:
                self.err(self._kind_message(ins, src, allowed, write=False), src.location)
                ok = False
            elif not self._check_index(src):
                ok = False
        return ok

    def _kind_message(self, ins: Instruction, op: Operand, allowed, *, write: bool) -> str:
        if op.kind not in self.rules.registers and op.kind != "imm":
            return f"{self.v} has no {KIND_NAMES.get(op.kind, op.kind)} registers ({op.name})"
        if not write and op.kind in _OUTPUT_ONLY:
            return f"{op.name} is an output register; it cannot be read"
        if write and op.kind not in self.rules.writable and op.kind in self.rules.registers \
                and not ins.info.dst_kinds:
            return f"{op.name} is read-only in {self.v}; it cannot be written"
        names = " or ".join(f"{k}#" if k not in ("aL", "oPos", "oFog", "oPts", "oDepth") else k
                            for k in sorted(allowed))
        what = "write" if write else "read"
        return f"{ins.opcode} cannot {what} {op.name} in {self.v} (it takes {names})"

    def _check_index(self, op: Operand) -> bool:
        count = self.rules.registers.get(op.kind)
        if count is None:
            if op.kind not in ("imm", "l"):
                self.err(f"{self.v} has no {KIND_NAMES.get(op.kind, op.kind)} registers "
                         f"({op.name})", op.location)
                return False
            return True
        if op.relative is not None:
            if op.kind != "c" and not (self.rules.major == 3 and op.kind in ("v", "o")):
                self.err(f"{op.kind}# registers cannot be indexed relatively", op.location)
                return False
            if self.p.kind == "ps" and self.rules.major < 3:
                self.err(f"relative addressing is not available in {self.v}", op.location)
                return False
            if self.rules.major == 1 and (op.relative.kind != "a" or op.relative.component != 0):
                self.err(f"{self.v} indexes constants only with a0.x", op.location)
                return False
        if op.index is not None and op.index >= count:
            # at its first use only: a shader compiled to r12..r14 used them in dozens of
            # instructions, each said the same sentence
            if op.name not in self.out_of_range:
                self.out_of_range.add(op.name)
                name = KIND_NAMES.get(op.kind, op.kind)
                plural = "register" if count == 1 else "registers"
                self.err(f"{op.name} is out of range: {self.v} has {count} {name} {plural} "
                         f"({_register_range(op.kind, count)})", op.location)
            return False
        return True

    def _source_modifiers(self, ins: Instruction) -> None:
        r = self.rules
        for i, src in enumerate(ins.srcs):
            if src.modifier is None and not src.negate:
                continue
            if src.negate and src.kind in ("s", "l", "i", "aL") and ins.opcode not in ("if", "callnz", "breakp"):
                self.err(f"{src.name} cannot be negated", src.location)
                continue
            mod = src.modifier
            if mod is None:
                if r.is_ps11_13 and ins.is_texture:
                    self.err(f"texture address instructions take no source modifiers except "
                             f"_bx2 in {self.v}", src.location)
                if not r.is_ps1 and ins.opcode.startswith("m") and ins.opcode[1:2] in "34" \
                        and i == 1 and self.p.kind == "ps":
                    self.err(f"{ins.opcode} cannot negate its matrix source", src.location)
                if r.is_ps14 and src.kind == "c":
                    self.err(f"ps_1_4 allows no source modifiers on constants ({src.text})",
                             src.location)
                continue
            syntax = _MODIFIER_SYNTAX[mod]
            if mod not in r.src_modifiers:
                if mod == "x2":
                    self.err(f"the _x2 source modifier needs ps_1_4 (this program is {self.v})",
                             src.location)
                elif mod in ("dz", "dw"):
                    self.err(f"the {syntax} modifier exists only on ps_1_4 texld and texcrd "
                             f"sources", src.location)
                elif mod == "abs":
                    self.err(f"the _abs source modifier needs a 3_0 shader (this program is "
                             f"{self.v}); use the abs instruction", src.location)
                else:
                    self.err(f"the {syntax} source modifier exists only in ps_1_x, not in "
                             f"{self.v}", src.location)
                continue
            if r.is_ps11_13 and ins.is_texture:
                if mod != "bx2":
                    self.err(f"texture address instructions take no source modifiers except "
                             f"_bx2 in {self.v}", src.location)
                elif self.v in ("ps_1_0", "ps_1_1") and not ins.opcode.startswith("texm"):
                    self.err(f"in {self.v} _bx2 is allowed only on texm* sources, not on "
                             f"{ins.opcode}", src.location)
                continue
            if mod in ("dz", "dw"):
                if ins.opcode not in ("texld", "texcrd"):
                    self.err(f"the {syntax} modifier exists only on texld and texcrd sources",
                             src.location)
                elif mod == "dz" and (ins.opcode != "texld" or src.kind != "r"):
                    self.err("_dz is allowed only on texld with an r# source (phase 2)",
                             src.location)
                continue
            if r.is_ps14 and src.kind == "c":
                self.err(f"ps_1_4 allows no source modifiers on constants ({src.text})",
                         src.location)
            if r.is_ps14 and ins.opcode in ("texld", "texcrd"):
                self.err(f"{ins.opcode} takes only the _dz/_dw modifiers on its source",
                         src.location)

    def _swizzles(self, ins: Instruction) -> None:
        r = self.rules
        for i, src in enumerate(ins.srcs):
            if src.kind in ("imm", "l"):
                continue
            role = ins.info.source_roles[i] if i < len(ins.info.source_roles) else "s"
            text = src.swizzle_text
            if src.kind == "s" and text and (r.major < 3):
                self.err(f"a sampler takes no swizzle in {self.v} ({src.name}.{text})",
                         src.location)
                continue
            if r.is_ps11_13:
                if ins.is_texture:
                    if text and src.swizzle != IDENTITY:
                        self.err(f"texture address instructions take no swizzle in {self.v}",
                                 src.location)
                    continue
                if src.swizzle == IDENTITY or src.swizzle == (3, 3, 3, 3):
                    continue
                if src.swizzle == (2, 2, 2, 2):
                    if ins.dst is None or ins.dst.mask != (3,):
                        self.err(f"the .{text} (blue replicate) selector is allowed in {self.v} "
                                 "only when the instruction writes .a alone", src.location)
                    continue
                self.err(f"{self.v} does not support the swizzle .{text}; sources take only "
                         f"the .a selector (and .b in alpha-only instructions)", src.location)
            elif r.is_ps14:
                if ins.opcode in ("texld", "texcrd"):
                    if src.swizzle not in (IDENTITY, (0, 1, 2, 2), (0, 1, 3, 3)):
                        self.err(f"{ins.opcode} takes .xyz or .xyw on its source, not .{text}",
                                 src.location)
                    continue
                if src.swizzle != IDENTITY and not src.is_replicate:
                    self.err(f"ps_1_4 does not support the swizzle .{text}; sources take only "
                             "the .r, .g, .b or .a selectors", src.location)
            elif self.p.kind == "ps":
                if ins.opcode in ("texld", "texldp", "texldb") and r.major == 2 and text:
                    self.err(f"{ins.opcode} takes no swizzle on its sources in {self.v}",
                             src.location)
                    continue
                if role == "x" and not src.is_replicate:
                    shown = f"{src.name}.{text}" if text else src.name
                    self.err(f"{ins.opcode} reads one component: give {shown} a replicate "
                             "swizzle (.x, .y, .z or .w)", src.location)
                    continue
                if r.swizzles == "ps20" and src.swizzle != IDENTITY and not src.is_replicate \
                        and src.swizzle not in PS20_SWIZZLES:
                    self.err(f"{self.v} does not support the swizzle .{text}; arbitrary swizzles "
                             "need ps_2_x with D3DPS20CAPS_ARBITRARYSWIZZLE, ps_2_a or ps_3_0",
                             src.location)

    def _write_mask(self, ins: Instruction) -> None:
        d = ins.dst
        if d is None:
            return
        r = self.rules
        if r.is_ps11_13:
            if ins.is_texture:
                if d.mask is not None:
                    self.err(f"texture address instructions write all of {d.name}; remove "
                             f"the write mask .{d.mask_text}", d.location)
                return
            if d.mask not in (None, (0, 1, 2), (3,), (0, 1, 2, 3)):
                self.err(f"{self.v} allows only the write masks .rgba, .rgb and .a; "
                         f".{d.swizzle_text} is not one of them", d.location)
            elif ins.opcode == "dp3" and d.mask == (3,):
                self.err(f"dp3 in {self.v} must write .rgb or .rgba", d.location)
            return
        if ins.opcode in ("texld", "texldp", "texldb", "texldd") and r.major == 2 \
                and d.mask is not None and d.mask != (0, 1, 2, 3):
            self.err(f"{ins.opcode} writes all four components in {self.v}; remove the write "
                     f"mask .{d.swizzle_text}", d.location)
        elif ins.opcode == "sincos" and (d.mask is None or not set(d.mask) <= {0, 1}):
            self.err("sincos writes .x, .y or .xy only; give it one of those write masks",
                     d.location)
        elif ins.opcode == "crs" and 3 in d.components:
            self.err("crs writes .x, .y and .z only; give it a write mask without .w",
                     d.location)
        elif ins.opcode == "frc" and self.v == "vs_1_1" and d.mask not in ((1,), (0, 1)):
            self.err("frc in vs_1_1 must write .y or .xy", d.location)
        elif ins.opcode == "bem" and d.mask != (0, 1):
            self.err("bem must write .rg (.xy)", d.location)
        if d.kind == "a":
            if d.mask not in ((0,), None) and r.major == 1:
                self.err(f"a0 can be written only as a0.x in {self.v}", d.location)
            elif r.major == 1 and d.mask is None:
                self.err(f"a0 can be written only as a0.x in {self.v}", d.location)
            if r.major == 1 and ins.opcode != "mov":
                self.err(f"a0 can be written only by mov in {self.v}", ins.location)
            if r.major >= 2 and ins.opcode != "mova":
                self.err(f"a0 can be written only by mova in {self.v}", ins.location)
        if d.kind in ("oC", "oDepth") and ins.opcode != "mov" and r.major == 2:
            self.err(f"{d.name} can be written only by mov", ins.location)

    def _read_ports(self, ins: Instruction) -> None:
        seen: dict[str, dict[str, Operand]] = {}   # kind -> register name -> its first operand
        for src in ins.srcs:
            if src.kind in self.rules.read_ports:
                seen.setdefault(src.kind, {}).setdefault(src.name, src)
        for kind, named in seen.items():
            ops = list(named.values())
            limit = self.rules.read_ports[kind]
            if kind == "c" and ins.opcode == "sincos" and not self.rules.is_ps1:
                # sincos's two D3DSINCOSCONST operands do not count against the constant
                # read ports (the one exception, docs/reference/semantics.md §3).
                limit += 2
            if len(ops) > limit:
                name = KIND_NAMES.get(kind, kind)
                listed = ", ".join(o.name for o in ops)
                what = f"1 {name} register" if limit == 1 else \
                    f"{limit} different {name} registers"
                self.err(f"{self.v} lets one instruction read {what}; this one reads {listed}",
                         ops[limit].location)

    def _special(self, ins: Instruction) -> None:
        r = self.rules
        if ins.opcode == "cnd" and r.is_ps11_13:
            s0 = ins.srcs[0]
            if s0.kind != "r" or s0.index != 0 or s0.swizzle != (3, 3, 3, 3) or s0.modifier \
                    or s0.negate:
                self.err(f"cnd in {self.v} must use r0.a as its first source", s0.location)
        rows = ins.info.matrix_rows
        if rows and len(ins.srcs) > 1 and ins.srcs[1].relative is None:
            m = ins.srcs[1]
            count = self.rules.registers.get(m.kind, 0)
            if m.index is not None and m.index + rows > count:
                last = f"{m.kind}{m.index + rows - 1}"
                self.err(f"{ins.opcode} reads {m.name}–{last}; {self.v} has "
                         f"{count} {KIND_NAMES.get(m.kind, m.kind)} registers "
                         f"({_register_range(m.kind, count)})", m.location)
        if ins.opcode == "texdepth" and ins.dst is not None and ins.dst.index != 5:
            self.err("texdepth must write r5", ins.dst.location)

    def _reads_initialised(self, ins: Instruction) -> None:
        # sgn's second and third sources are scratch registers it writes, not inputs
        srcs = ins.srcs[:1] if ins.opcode == "sgn" else ins.srcs
        reads = [s for s in srcs if s.kind in ("r", "a")]
        for s in ins.srcs:
            if s.relative is not None and s.relative.kind == "a":
                reads.append(Operand("a", 0, s.location, text="a0"))
        if ins.opcode in ("texkill", "texdepth") and ins.dst is not None and ins.dst.kind == "r":
            reads.append(ins.dst)   # they read the register named in the dst slot
        reported: set[str] = set()
        for s in reads:
            key = (s.kind, s.index)
            if s.name in reported:
                continue
            if key not in self.written:
                reported.add(s.name)
                self.err(f"{s.name} is read before it is written", s.location)
            elif self.by_component and s.kind == "r":
                missing = sorted(self._lanes_read(ins, s) - self.written_lanes.get(key, set()))
                if missing:
                    reported.add(s.name)
                    have = "".join("xyzw"[c] for c in sorted(self.written_lanes[key]))
                    self.err(f"{s.name}.{''.join('xyzw'[c] for c in missing)} is read before "
                             f"it is written (only {s.name}.{have} is written before here)",
                             s.location)
        if self.p.kind == "ps" and self.rules.major >= 2:
            for s in ins.srcs:
                if s.kind in ("t", "v", "s") and (s.kind, s.index) not in self.declared \
                        and s.name not in reported:
                    reported.add(s.name)
                    how = (f"dcl_2d {s.name}, dcl_cube {s.name} or dcl_volume {s.name}"
                           if s.kind == "s" else f"dcl {s.name}")
                    self.err(f"{s.name} is used but not declared (add {how})", s.location)
        if self.vs_declares_inputs:
            for s in ins.srcs:
                if s.kind == "v" and ("v", s.index) not in self.declared \
                        and s.name not in reported:
                    reported.add(s.name)
                    self.err(f"{s.name} is read but not declared (by a dcl_usage or the "
                             f"decl{{}} block)", s.location)

    def _lanes_read(self, ins: Instruction, s: Operand) -> set[int]:
        """The components of register `s`, a source of `ins` (or the register texkill and
        texdepth name in the dst slot), that the instruction reads (its row's `reads`)."""
        k = next((i for i, x in enumerate(ins.srcs) if x is s), -1)
        if k < 0:
            # the register texkill and texdepth name in the dst slot: texkill's a.xyz,
            # texdepth's r5.xy
            return {0, 1} if ins.opcode == "texdepth" else {0, 1, 2}
        info = ins.info
        roles = info.source_roles
        if k < len(roles) and roles[k] == "x":
            return {s.swizzle[3]}
        rule = info.reads[k] if k < len(info.reads) else ""
        if rule.startswith("coord"):
            sampler = ins.srcs[1] if len(ins.srcs) > 1 else None
            d = self.p.declaration("s", sampler.index) if sampler is not None else None
            n = 2 if d is not None and d.sampler_type == "2d" else 3
            lanes = list(range(n)) + ([3] if rule == "coord+w" else [])
        elif rule:
            lanes = ["xyzw".index(c) for c in rule]
        elif ins.dst is not None:
            lanes = list(ins.dst.components)
        else:                       # if_gt r0.x, c0.x; break_ne: the lanes the swizzle names
            lanes = [0, 1, 2, 3]
        return {s.swizzle[c] for c in lanes}

    def _record_write(self, ins: Instruction) -> None:
        if ins.dst is None or ins.opcode in ("texkill", "texdepth"):
            return
        key = (ins.dst.kind, ins.dst.index)
        self.written.add(key)
        # a texld writes all four components (a write mask on one is refused on its own)
        lanes = (0, 1, 2, 3) if ins.opcode.startswith("texld") else ins.dst.components
        self.written_lanes.setdefault(key, set()).update(lanes)
        if ins.phase is not None:
            self.written_phase.setdefault(key, ins.phase)

    # -- slots ---------------------------------------------------------------------------------
    def _slots(self) -> None:
        r = self.rules
        totals: dict[tuple[int | None, str], int] = {}
        reported: set[tuple[int | None, str]] = set()
        limits = {"texture": r.tex_slots, "arithmetic": r.arith_slots, "total": r.total_slots}
        for ins in self.p.instructions:
            if self.v not in ins.info.versions:
                continue
            t, a, f = instruction_slots(self.p, ins)
            phase = ins.phase if r.per_phase else None
            for what, n in (("texture", t), ("arithmetic", a), ("total", t + a + f)):
                if not n:
                    continue
                key = (phase, what)
                before = totals.get(key, 0)
                totals[key] = before + n
                limit = limits[what]
                if limit is None or totals[key] <= limit or key in reported:
                    continue
                if what == "total" and (r.tex_slots is not None and r.arith_slots is not None):
                    continue   # tex + arith limits already bound the total
                reported.add(key)
                self.err(self._slot_message(ins, what, limit, n, totals[key], phase),
                         ins.location)

    def _slot_message(self, ins: Instruction, what: str, limit: int, cost: int, total: int,
                      phase: int | None) -> str:
        kind = "" if what == "total" else what + " "
        per = " per phase" if phase is not None else ""
        where = f" in phase {phase}" if phase is not None else ""
        if self.rules.is_ps1 and cost == 1:
            return (f"{self.v} allows {limit} {kind}instructions{per}; this is the "
                    f"{_ordinal(total)}{where}")
        if cost == 1:
            return (f"{self.v} allows {limit} {kind}instruction slots{per}; this instruction "
                    f"is the {_ordinal(total)}{where}")
        return (f"{self.v} allows {limit} {kind}instruction slots{per}; this {ins.opcode} takes "
                f"{cost} and brings the count to {total}{where}")

    # -- dependent reads -----------------------------------------------------------------------
    def _dependent_reads(self) -> None:
        limit = self.rules.dependent_read_limit
        if limit is None:
            return
        levels = self.p.read_levels
        for pos, level in sorted(levels.items()):
            if level > limit:
                ins = self.p.instructions[pos]
                self.err(f"this {ins.opcode} is a {_ordinal(level - 1)}-order dependent read "
                         f"({level} levels of texture reads); {self.v} allows at most {limit} "
                         f"levels", ins.location)
                return

    # -- flow control --------------------------------------------------------------------------
    def _flow_nesting(self) -> None:
        closers = {"endif": "if", "endloop": "loop", "endrep": "rep"}
        stack: list[Instruction] = []
        for ins in self.p.instructions:
            if self.v not in ins.info.versions:
                continue
            op = ins.opcode
            if op in ("if", "loop", "rep"):
                stack.append(ins)
            elif op == "else":
                if not stack or stack[-1].opcode != "if":
                    self.err("else without a matching if", ins.location)
            elif op in closers:
                if not stack or stack[-1].opcode != closers[op]:
                    self.err(f"{op} without a matching {closers[op]}", ins.location)
                else:
                    stack.pop()
            elif op in ("break", "breakp") and not any(s.opcode in ("loop", "rep") for s in stack):
                self.err(f"{op} outside a loop or rep block", ins.location)
        for open_ins in stack:
            end = {"if": "endif", "loop": "endloop", "rep": "endrep"}[open_ins.opcode]
            self.err(f"{open_ins.opcode} is never closed by {end}", open_ins.location)

    # -- output --------------------------------------------------------------------------------
    def _final_output(self) -> None:
        written = {(i.dst.kind, i.dst.index) for i in self.p.instructions
                   if i.dst is not None and i.opcode not in ("texkill", "texdepth")}
        if self.p.kind == "ps":
            if self.rules.is_ps1:
                if ("r", 0) not in written:
                    self.err("the shader never writes r0, its output colour", self.p.location)
            elif ("oC", 0) not in written:
                self.err("the shader never writes oC0, its output colour", self.p.location)
            return
        if self.rules.major < 3:
            if ("oPos", None) not in written:
                self.err("the shader never writes oPos, the position output", self.p.location)
            return
        pos_regs = [d.register.index for d in self.p.dcls
                    if d.register.kind == "o" and d.usage == "position"]
        if not pos_regs:
            self.err("vs_3_0 needs a position output: declare one with dcl_position o#",
                     self.p.location)
        elif not any(("o", i) in written for i in pos_regs):
            self.err(f"the shader never writes o{pos_regs[0]}, its position output",
                     self.p.location)


def _versions_of(opcode: str):
    return set(versions_having(opcode))


def _not_available(opcode: str, version: str) -> str:
    having = versions_having(opcode)
    kind = version[:2]
    same_kind = [v for v in having if v.startswith(kind)]
    if not same_kind:
        other = "vertex" if kind == "ps" else "pixel"
        return f"{opcode} is not available in {version} (it is a {other} shader instruction)"
    return f"{opcode} is not available in {version} (it exists in {', '.join(same_kind)})"


def check(program: AsmProgram) -> list[AsmError]:
    """Every rule of the program's version that it breaks, each located at the instruction or
    operand concerned, in source order. An empty list means the program is valid."""
    return _Checker(program).run()


def check_cached(program: AsmProgram) -> list[AsmError]:
    """`check`, once per assembled program object (kept on it, `AsmProgram._check_errors`, so
    it goes with it): validation asks per card, and the lowering check asks again. Read the
    list; don't change it."""
    hit = program._check_errors
    if hit is None:
        hit = program._check_errors = check(program)
    return hit
