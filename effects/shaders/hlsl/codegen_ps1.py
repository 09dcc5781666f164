"""ps_1_1–ps_1_4 code generation: what fxc made of a simple HLSL pixel function for DX8 cards.

The DAG (dag.py) is mapped onto the DX8 pixel pipeline (docs/reference/semantics.md §2):
- texture reads come first: `tex t#` samples stage # at TEXCOORD# (ps_1_1–1_3); `texld r#, t#`
  samples stage # into r# (ps_1_4), and a read at computed coordinates is a phase-2
  `texld r#, r#` after `phase` (one level of dependent read, the only one ps_1_4 has); one
  sampler read at two coordinates is refused on ps_1_1-1_3 (a sampler is one stage, and stage #
  reads TEXCOORD#) and on ps_1_4 is one read per phase (the first carried across `phase`);
- a TEXCOORD read as a value is `texcoord t#` (clamped to [0, 1]: a located warning) or
  `texcrd r#.rgb, t#`; COLOR inputs are v0/v1; uniforms are c0–c7 and literals `def`
  constants, which must lie in [-1, 1] (the ps_1_x constant range);
- add, mul, mad, lrp, dp3, dp4 (1_2+), cmp (1_2+), cnd and mov (cnd's condition is r0.a
  on ps_1_1-1_3: the condition is computed into r0.a, or moved there), with the idioms of ps1_idioms.py
  as source modifiers, result shifts and `_sat`; a scalar is held replicated in every lane (dp3
  writes it so), since ps_1_1–1_3 read no component but .a and .b alone (dp3 with a unit vector
  extracts one);
- vectors built from parts (`float4(c.rgb, 1)`) are written through the .rgb/.a masks, with
  mul/mad by 0/1 masks where lanes of one .rgb group come from different values;
- the result goes to r0; temporaries are r0–r1 (r0–r5 in ps_1_4), allocated by live range.
Anything else is X4532 ("cannot map expression to pixel shader instruction set", fxc's words)
at the HLSL expression; slot counts are left to the assembler's checks like hand-written code.
"""
from __future__ import annotations

from effects.base.errors import Location, UNKNOWN_LOCATION
from effects.shaders.hlsl.allocate import RegisterConflict
from effects.shaders.asm.program import Instruction, Operand as Register
from effects.shaders.hlsl.context import Context
from effects.shaders.hlsl.dag import Node, Operand, Output, reachable
from effects.shaders.hlsl.ops import PS1_LACKS, PS1_LANEWISE
from effects.shaders.hlsl.parse import HlslError
from effects.shaders.hlsl.ps1_analysis import Ps1Analysis, State, combine, readers_of
from effects.shaders.hlsl.ps1_asm import Home, Ps1Emit
from effects.shaders.hlsl.ps1_idioms import power_of_two
from effects.shaders.hlsl.ps1_textures import Ps1Textures
from effects.shaders.hlsl.records import FULL, instruction, reg, replicated, temp
from effects.shaders.hlsl.writer import Code



class Ps1CodeGen(Ps1Analysis, Ps1Textures, Ps1Emit):
    def __init__(self, ctx: Context, outputs: list[Output], constant_registers: dict[str, int],
                 register_sizes: dict[str, int], sampler_registers: dict[str, int]) -> None:
        self.ctx = ctx
        self.v = ctx.target.name
        self.rules = ctx.target.rules
        self.ps14 = self.rules.is_ps14
        self.outputs = outputs
        self.const_regs = dict(constant_registers)
        self.sizes = register_sizes
        self.explicit_samplers = sampler_registers

    # -- driver ---------------------------------------------------------------------------------
    def generate(self) -> Code:
        try:
            return self._generate(out_direct=True)
        except RegisterConflict:
            pass
        try:
            return self._generate(out_direct=False)
        except RegisterConflict as clash:
            # only cnd conditions are pinned then: two of them live at once
            self.refuse(f"{self.v}'s cnd reads its condition from r0.a only, and two conditions "
                        "are needed there at once", self.vr_loc.get(clash.vr, UNKNOWN_LOCATION))
            raise AssertionError from clash  # pragma: no cover

    def _generate(self, out_direct: bool) -> Code:
        self.instrs: list[Instruction] = []
        self.optional: set[int] = set()
        self.home: dict[int, Home] = {}
        self.defs: dict[int, list[float | None]] = {}
        self.precolor: dict[int, int] = {}
        self.vr_loc: dict[int, Location] = {}
        self.next_vr = 0
        self.samplers: dict[str, int] = {}
        self.sampled: set[tuple[str, int]] = set()     # (sampler, phase) read
        self.carried_alpha: dict[int, Register] = {}         # phase-1 read -> its .a across phase
        self.used_uniforms: set[str] = set()
        self.extracted: dict[tuple, Home] = {}   # _extract's and _rearranged's temporaries
        self.phase = 2
        self.s = State()
        self._input_homes: dict[str, Home] = {}
        out = self._the_output()
        if self.ctx.kills:
            self.fail("clip/discard (texkill reads texture coordinates only)", self.ctx.kills[0].node.location)
        comps = list(out.comps) + [out.comps[-1]] * (4 - len(out.comps))
        nodes = reachable([c.node for c in comps])
        self.readers = readers_of(nodes, comps)
        if combine(nodes, self.readers):
            nodes = reachable([c.node for c in comps])
            self.readers = readers_of(nodes, comps)
        self._analyse(nodes)
        self.cnd_pins = self._conditions_into_r0(nodes)
        p1 = self._p1 = self._phase_one(nodes)
        carried = self._reads_of_one_sampler(nodes, p1)
        self.out_home = Home(temp(self.temp(out.location, pin=0 if out_direct else None)))
        pending = self._coalesce_output(comps, out.location)
        live = self._live(comps)
        arith = [n for n in nodes if self._emitted(n) and n.id in live]
        tex = [n for n in nodes if n.op == "tex" and n.id in live]
        values = self._inputs_read_as_values(arith, comps)
        if p1:
            self.phase = 1
            self._textures([n for n in tex if n.id in p1], {k: w for k, w in values.items() if w == 1})
            for n in tex:
                if n.id in carried:
                    self._carry_out_of_stage(n)
            for n in arith:
                if n.id in p1:
                    self.compute(n)
            self.instrs.append(self.record("phase", None, (), [], UNKNOWN_LOCATION))
            self.phase = 2
        self._textures([n for n in tex if n.id not in p1],
                       {k: w for k, w in values.items() if k not in self._input_homes})
        for n in arith:
            if n.id not in p1:
                self.compute(n)
        self.assemble_lanes(self.out_home, pending, out.location)
        if not out_direct:
            self.instrs.append(self.record("mov", temp(self.temp(out.location, pin=0)), FULL,
                                       [replicated(self.out_home.reg)], out.location))
        return self._code()

    def record(self, opcode: str, dst: Register | None, mask: tuple[int, ...],
               srcs: list[Register], loc: Location, saturate: bool = False,
               shift: int = 0) -> Instruction:
        """An instruction of this version (records.instruction)."""
        return instruction(opcode, dst, mask, srcs, self.v, loc, saturate, shift=shift)

    def temp(self, loc: Location, pin: int | None = None) -> int:
        self.next_vr += 1
        vr = self.next_vr - 1
        self.vr_loc[vr] = loc
        if pin is not None:
            self.precolor[vr] = pin
        return vr

    def _the_output(self) -> Output:
        for o in self.outputs:
            if o.register != "oC0":
                what = "a depth output" if o.register == "oDepth" else f"a second colour output ({o.register})"
                self.fail(f"{what}: ps_1_x writes only r0", o.location)
        return self.outputs[0]

    # -- arithmetic -----------------------------------------------------------------------------
    def compute(self, n: Node) -> None:
        op = n.op
        if op in PS1_LACKS:
            self.fail(PS1_LACKS[op], n.location)
        home = self.home.get(n.id)
        if home is None:
            if n.id in self.cnd_pins:     # a cnd condition: r0.a only (so .b may be read)
                home = Home(temp(self.temp(n.location, pin=0)), n.width == 1, self.phase, mask=(3,))
            else:
                home = Home(temp(self.temp(n.location)), n.width == 1, self.phase)
            self.home[n.id] = home
        if op == "pack":   # a vector built of parts has no expression of its own: say where
            loc = n.location if n.location.line else next(          # it is read
                (r.location for r, _ in self.readers.get(n.id, ()) if r is not None
                 and r.location.line), n.location)
            self.assemble_lanes(home, list(enumerate(n.args)), loc)
            return
        mask = home.mask or self.mask_for(n.width)
        home.phase = self.phase
        shift, sat = self.s.shift.get(n.id, 0), n.id in self.s.sat
        if op == "sat":
            op, sat, args = "mov", True, [n.args[0]]
        elif op == "mul" and self._scaled(n) is not None:
            y, k, s = self._scaled(n)  # type: ignore[misc]
            shift += s
            args = [y] if k is None else [y, k]
            op = "mov" if k is None else "mul"
        else:
            args = list(n.args)
        if op == "cnd":
            self._cnd(n, home, mask, shift, sat)
            return
        if op in ("dp3", "dp4"):
            if op == "dp4" and not self.ctx.target.has("dp4"):
                self.fail("dp4 (a 4-component dot product needs ps_1_2)", n.location)
            width = int(op[2])
            srcs = [self.read(a, {i: i for i in range(width)}, n.location) for a in args]
        elif op in PS1_LANEWISE:         # add mul mad lrp cmp mov (cnd and sat: above)
            if op == "cmp" and not self.ctx.target.has("cmp"):
                self.fail("cmp (a select or comparison needs ps_1_2)", n.location)
            need = {lane: (0 if n.width == 1 else lane) for lane in mask if n.width == 1 or lane < n.width}
            srcs = [self.read(a, need, n.location) for a in args]
        else:
            self.fail(op, n.location)
        if op == "add" and self.ps14:
            op, srcs = _sub_for_negated_constant(op, srcs)
        self.emit(self.record(op, home.reg, mask, srcs, n.location, saturate=sat, shift=shift))

    def _cnd(self, n: Node, home: Home, mask: tuple[int, ...], shift: int, sat: bool) -> None:
        """ps_1_1-1_3: cnd d, r0.a, a, b -- the condition is r0.a, one value for all lanes
        (docs/reference/semantics.md 2.4; the DX9 docs' cnd page); it is computed there or
        moved there."""
        cond, mod = self.resolve(n.args[0])
        if len(set(cond.swizzle)) != 1:
            self.refuse(f"{self.v}'s cnd compares r0.a, one value for every component; this "
                        "comparison is per component (compare one channel, or target ps_1_4)",
                        n.location)
        held = self.home.get(cond.node.id)
        if held is not None and held.reg.kind == "vr" and self.precolor.get(held.reg.index) == 0 \
                and cond.node.id in self.cnd_pins and not mod and not cond.negate:
            test = replicated(held.reg, 3)
        else:
            r0 = temp(self.temp(n.location, pin=0))
            self.emit(self.record("mov", r0, (3,), [self.read(n.args[0], {3: 0}, n.location)],
                              n.location))
            test = replicated(r0, 3)
        need = {lane: (0 if n.width == 1 else lane) for lane in mask if n.width == 1 or lane < n.width}
        srcs = [test] + [self.read(a, need, n.location) for a in n.args[1:]]
        self.emit(self.record("cnd", home.reg, mask, srcs, n.location, saturate=sat, shift=shift))

    def _scaled(self, n: Node) -> tuple[Operand, Operand | None, int] | None:
        """mul by a literal outside [-1, 1]: (y, the literal scaled into range or None, shift)."""
        for y, k in ((n.args[0], n.args[1]), (n.args[1], n.args[0])):
            vals = k.const_values()
            if vals is None or y.node.op == "const":
                continue
            s = power_of_two(vals, self.rules.shifts)
            if s is not None:
                return y, None, s
            big = max(abs(v) for v in vals)
            if big <= 1:
                return None
            for s in sorted(x for x in self.rules.shifts if x > 0):
                if big / 2 ** s <= 1:
                    g = self.ctx.graph
                    return y, g.const(tuple(v / 2 ** s for v in vals)), s
        return None

    def emit(self, ins: Instruction) -> None:
        """Append, reading extra constants/inputs through a mov when an instruction reads more
        distinct registers of a kind than the version's read ports allow."""
        for kind in ("c", "v", "t"):
            limit = self.rules.read_ports.get(kind)
            seen: list[int | None] = []
            for k, s in enumerate(ins.srcs):
                if s.kind != kind or s.index in seen:
                    continue
                if limit is not None and len(seen) >= limit:
                    # this source reads the copy (a later one of the same register, its own)
                    vr = self.temp(ins.location)
                    self.instrs.append(self.record("mov", temp(vr), FULL, [replicated(s)], ins.location))
                    s.kind, s.index = "vr", vr
                    continue
                seen.append(s.index)
        self.instrs.append(ins)

    # -- sources --------------------------------------------------------------------------------
    def read(self, op: Operand, need: dict[int, int], loc: Location) -> Register:
        """A source giving, at instruction lane L, component need[L] of `op`."""
        base, mod = self.resolve(op)
        comps = {lane: base.swizzle[min(c, base.width - 1)] for lane, c in need.items()}
        return self.read_resolved(base, mod, comps, loc)

    def read_resolved(self, base: Operand, mod: str, comps: dict[int, int],
                      loc: Location) -> Register:
        node = base.node
        if node.op == "const":
            sign = -1.0 if base.negate else 1.0
            return replicated(self.def_reg({lane: sign * node.value[c] for lane, c in comps.items()}, loc))  # type: ignore[index]
        home = self._home_of(node, loc)
        neg = base.negate
        if self.ps14 and home.reg.kind == "v" and self.phase == 1:
            self.refuse(f"{self.v} reads colour inputs (v#) only in phase 2", loc)
        if any(c >= home.lanes for c in comps.values()) and not home.scalar:
            self.refuse(f"{self.v}'s texcrd gives a texture coordinate's .xyz only; .w is not read", loc)
        across = self.ps14 and home.phase == 1 and self.phase == 2
        if across and node.id in self.carried_alpha and 3 in comps.values():
            if set(comps.values()) == {3}:
                return replicated(self.carried_alpha[node.id], 2, mod, neg)
            home, across = self._rejoin(node, loc), False
        if home.scalar:
            return replicated(home.reg, 2 if across and 3 in comps else None, mod, neg)
        if all(lane == c for lane, c in comps.items()):
            if across and 3 in comps:
                self.refuse(f"{self.v} keeps only .rgb of a register across phase; this reads the .a "
                            "of a value computed before the dependent read", loc)
            return replicated(home.reg, None, mod, neg)
        picked = set(comps.values())
        if len(picked) == 1:
            k = picked.pop()
            # ps_1_1-1_3 read .b alone only into an .a-only write
            if k == 3 or (k == 2 and set(comps) == {3}) or self.ps14:
                if across and k == 3:
                    self.refuse(f"{self.v} keeps only .rgb of a register across phase", loc)
                return replicated(home.reg, k, mod, neg)
            return replicated(self._extract(node, k, home, loc).reg, None, mod, neg)
        if self.ps14 and not across:
            return replicated(self._rearranged(node, comps, home, mod, neg, loc).reg)
        order = "".join("xyzw"[comps[lane]] for lane in sorted(comps))
        self.fail(f"swizzle .{order} (ps_1_x sources take .rgba, .a or .b only)", loc)
        raise AssertionError  # pragma: no cover

    def _rearranged(self, node: Node, comps: dict[int, int], home: Home, mod: str, neg: bool,
                    loc: Location) -> Home:
        """ps_1_4: the lanes `comps` asks for (lane -> component of the value), moved into a
        temporary through write masks, one `mov` per source selector (.r/.g/.b/.a replicate
        one component; lanes that keep their own component go in one plain `mov`), as fxc
        compiled `c.r = c.g`."""
        key = (node.id, tuple(sorted(comps.items())), mod, neg)
        if key not in self.extracted:
            vr = self.temp(loc)
            own = tuple(lane for lane, c in sorted(comps.items()) if lane == c)
            if own:
                self.emit(self.record("mov", temp(vr), own, [replicated(home.reg, None, mod, neg)], loc))
            for k in sorted({c for lane, c in comps.items() if lane != c}):
                lanes = tuple(lane for lane, c in sorted(comps.items()) if lane != c and c == k)
                self.emit(self.record("mov", temp(vr), lanes, [replicated(home.reg, k, mod, neg)], loc))
            self.extracted[key] = Home(temp(vr), False, self.phase)  # type: ignore[index]
        return self.extracted[key]  # type: ignore[index]

    def _extract(self, node: Node, k: int, home: Home, loc: Location) -> Home:
        """Component k replicated: dp3 with a unit vector (ps_1_1-1_3 cannot select .r/.g)."""
        key = (node.id, k)
        if key not in self.extracted:
            vr = self.temp(loc)
            unit = self.def_reg({i: 1.0 if i == k else 0.0 for i in range(3)}, loc)
            self.emit(self.record("dp3", temp(vr), FULL, [replicated(home.reg), replicated(unit)], loc))
            self.extracted[key] = Home(temp(vr), True, self.phase)
        return self.extracted[key]

    def _home_of(self, node: Node, loc: Location) -> Home:
        if node.id in self.home:
            return self.home[node.id]
        if node.op == "input":
            name = node.key[1]
            if name.startswith("v"):
                return Home(reg("v", int(name[1:])))
            return self._input_homes[name]
        if node.op == "uniform":
            name, row = node.key
            index = self.const_regs[name] + row
            if index > 7:
                self.refuse(f"'{name.lstrip('$')}' is in c{index}; {self.v} has c0-c7", loc)
            self.used_uniforms.add(name)
            t = self.ctx.uniforms_used.get(name)
            return Home(reg("c", index), t is not None and t.kind == "scalar")
        raise HlslError(f"internal: no register holds the value of this {node.op}", loc)

    def def_reg(self, lanes: dict[int, float], loc: Location) -> Register:
        for v in lanes.values():
            if not -1.0 <= v <= 1.0:
                self.refuse(f"the literal {v:g} is outside [-1, 1], the range of {self.v} constants",
                            loc)
        taken = {self.const_regs[n] + k for n in self.const_regs
                 for k in range(self.sizes.get(n, 1))} | self.ctx.reserved_constants
        for k, slots in self.defs.items():
            if all(slots[lane] in (None, v) for lane, v in lanes.items()):
                for lane, v in lanes.items():
                    slots[lane] = v
                return reg("c", k)
        free = next((k for k in range(8) if k not in taken and k not in self.defs), None)
        if free is None:
            self.refuse(f"{self.v} has 8 constant registers; this literal needs a ninth", loc)
        slots: list[float | None] = [None] * 4
        for lane, v in lanes.items():
            slots[lane] = v
        self.defs[free] = slots  # type: ignore[index]
        return reg("c", free)

    # -- vectors from parts -----------------------------------------------------------------------
    def assemble_lanes(self, home: Home, items: list[tuple[int, Operand]], loc: Location) -> None:
        if not items:
            return
        groups: dict[tuple, dict[int, int]] = {}
        bases: dict[tuple, tuple[Operand, str]] = {}
        consts: dict[int, float] = {}
        for lane, op in items:
            base, mod = self.resolve(op)
            if base.node.op == "const":
                consts[lane] = base.const_values()[0]  # type: ignore[index]
                continue
            key = (base.node.id, base.negate, mod)
            groups.setdefault(key, {})[lane] = base.swizzle[0]
            bases[key] = (base, mod)
        dst = home.reg
        if self.ps14:
            for key, comps in groups.items():
                base, mod = bases[key]
                self.emit(self.record("mov", dst, tuple(sorted(comps)), [self.read_resolved(
                    _whole(base), mod, comps, loc)], loc))
            if consts:
                self.emit(self.record("mov", dst, tuple(sorted(consts)), [replicated(self.def_reg(consts, loc))], loc))
            return
        if len(groups) == 1 and not consts and set(next(iter(groups.values()))) == set(FULL):
            key, comps = next(iter(groups.items()))
            base, mod = bases[key]
            self.emit(self.record("mov", dst, FULL, [self.read_resolved(_whole(base), mod, comps, loc)], loc))
            return
        alpha = [(k, c) for k, c in groups.items() if 3 in c]
        if 3 in consts:
            self.emit(self.record("mov", dst, (3,), [replicated(self.def_reg({3: consts.pop(3)}, loc))], loc))
        for key, comps in alpha:
            base, mod = bases[key]
            self.emit(self.record("mov", dst, (3,), [self.read_resolved(_whole(base), mod, {3: comps.pop(3)}, loc)], loc))
        rgb = [(k, c) for k, c in groups.items() if c]
        if not rgb:
            if consts:
                self.emit(self.record("mov", dst, (0, 1, 2), [replicated(self.def_reg(consts, loc))], loc))
            return
        if len(rgb) == 1 and not consts:
            key, comps = rgb[0]
            base, mod = bases[key]
            self.emit(self.record("mov", dst, (0, 1, 2), [self.read_resolved(_whole(base), mod, comps, loc)], loc))
            return
        for i, (key, comps) in enumerate(rgb):
            base, mod = bases[key]
            src = self.read_resolved(_whole(base), mod, comps, loc)
            select = replicated(self.def_reg({lane: 1.0 if lane in comps else 0.0 for lane in range(3)}, loc))
            if i == 0:
                if consts:
                    fill = replicated(self.def_reg({lane: consts.get(lane, 0.0) for lane in range(3)}, loc))
                    self.emit(self.record("mad", dst, (0, 1, 2), [src, select, fill], loc))
                else:
                    self.emit(self.record("mul", dst, (0, 1, 2), [src, select], loc))
            else:
                self.emit(self.record("mad", dst, (0, 1, 2), [src, select, replicated(dst)], loc))


def _whole(base: Operand) -> Operand:
    """The node read through an identity swizzle (component maps are given separately)."""
    return Operand(base.node, tuple(range(max(base.node.width, 1))), base.negate)


def _sub_for_negated_constant(op: str, srcs: list[Register]) -> tuple[str, list[Register]]:
    # ps_1_4 takes no modifier on c#: a - c is `sub`
    a, b = srcs
    if a.kind == "c" and a.negate and not b.negate:
        a, b = b, a
    if b.kind == "c" and b.negate:
        b.negate = False
        return "sub", [a, b]
    return op, srcs


def generate_ps1(ctx: Context, outputs: list[Output], constant_registers: dict[str, int],
                 register_sizes: dict[str, int], sampler_registers: dict[str, int]) -> Code:
    """The ps_1_x assembly of a compiled pixel function (see the module docstring)."""
    return Ps1CodeGen(ctx, outputs, constant_registers, register_sizes, sampler_registers).generate()
