"""Code generation: the DAG the outputs reach, as Direct3D assembly for the target.

1. combine: `add(mul(a, b), c)` with a single-use mul becomes `mad`; a single-use
   instruction followed by `sat` takes `_sat` where the version has it;
2. homes: each node gets a place — an input register, a constant (uniform or `def`),
   or a temporary; a node used only by a `pack` (a vector built from pieces) writes its
   lanes of the pack's register directly (so `dp4 r0.x` ... `dp4 r0.w`), and in vertex
   shaders straight into the output register;
3. emit in node order (already topological), with the version's rules on sources: ps_2_0
   swizzles, read ports (one constant in vs_1_1, one t#/v# in ps_2_0), texld coordinates
   in a register without swizzle, oC# written by mov;
4. temporaries are allocated by linear scan over the emitted code;
5. flow control (flowcode.py): each node is placed in the main program, a loop body or a
   side of an if; a `loop` node (loops.py) is emitted as `rep i#` ... `endrep`, an `if` node
   (branches.py) as `if b#` / `if_comp` ... `else` ... `endif`; a register read inside a
   loop lives to its end (legalize.py).
Each instruction keeps the HLSL location of the node it comes from.
"""
from __future__ import annotations


from effects.base.errors import Location
from effects.shaders.asm.versions import IDENTITY
from effects.shaders.hlsl.context import Context
from effects.shaders.hlsl.constant_layout import free_run
from effects.shaders.asm.program import Instruction, Operand as Register, RelativeAddress
from effects.shaders.hlsl.dag import SHAPED, Node, Operand, Output
from effects.shaders.hlsl.flowcode import emit_block, emit_if, emit_kill, emit_loop, needed, place
from effects.shaders.hlsl.fusion import fuse_lrp, fuse_mad, pack_scalars, share_lit_diffuse
from effects.shaders.hlsl.legalize import _choose, code_of, legalize
from effects.shaders.hlsl.liveness import LiveLanes, analyse
from effects.shaders.hlsl.ops import LANEWISE, OPS, REDUCE, SCALAR, TEXTURE, shaped
from effects.shaders.hlsl.peephole import optimise
from effects.shaders.hlsl.records import fix, fixed, instruction, read, reg as register, temp
from effects.shaders.hlsl.writer import Code

# how each op is emitted: the op table's rows (ops.py)
_LANEWISE, _SCALAR, _REDUCE, _TEX = LANEWISE, SCALAR, REDUCE, TEXTURE


class CodeGen:
    def __init__(self, ctx: Context, inputs: dict[str, str], outputs: list[Output],
                 constant_registers: dict[str, int], sampler_registers: dict[str, int],
                 register_sizes: dict[str, int]) -> None:
        self.ctx = ctx
        self.target = ctx.target
        self.rules = ctx.target.rules
        self.inputs = inputs                     # input key -> dcl line
        self.outputs = outputs
        self.instrs: list[Instruction] = []
        self.home: dict[int, tuple[Register, dict[int, int]]] = {}
        self.next_vr = 0
        self.const_regs = dict(constant_registers)
        self.register_sizes = register_sizes
        self.sampler_regs = dict(sampler_registers)
        self.defs: dict[int, list[float | None]] = {}
        # indexes of defs (const_src finds a constant in O(1), not by scanning every def:
        # a shader of thousands of literals took quadratic time): the first lane holding each
        # value, the registers with a free lane (in the order made), each full row's register
        self._lane_of: dict[float, tuple[int, int]] = {}
        self._open: list[int] = []
        self._row_of: dict[tuple[float, ...], int] = {}
        self._low = 0                  # every register below it is taken (taken only grows)
        self.loop_regs: dict[int, list[Register]] = {}  # loop id -> carried registers
        self.if_regs: dict[int, list[Register]] = {}    # if id -> result registers
        self.a0: dict[int, tuple] | None = None         # a0 lane -> the address it holds
        self.addresses: list[tuple] = []                # relative reads' addresses (generate)
        self._address_of: dict[tuple, Operand] = {}
        self.live: LiveLanes | None = None              # write-mask liveness (liveness.py)

    # -- registers --------------------------------------------------------------------------
    def temp(self) -> Register:
        self.next_vr += 1
        return temp(self.next_vr - 1)

    def uniform_reg(self, name: str, offset: int) -> Register:
        if name not in self.const_regs:
            start = self._free_constant(self.register_sizes.get(name, 1))
            self.const_regs[name] = start
        return register("c", self.const_regs[name] + offset)

    def _taken(self) -> set[int]:
        taken = set(self.defs) | self.ctx.reserved_constants
        for name, start in self.const_regs.items():
            taken.update(range(start, start + self.register_sizes.get(name, 1)))
        return taken

    def _free_constant(self, count: int) -> int:
        k = free_run(self._taken(), count, self._low if count == 1 else 0)
        if count == 1:
            self._low = k
        return k

    def const_src(self, values: list[float]) -> Register:
        """A `def` constant holding `values` (one per instruction lane used): a lane already
        holding a single value, else a free lane of a scalar pool register, else a new one."""
        if len(set(values)) == 1:
            v = values[0]
            hit = self._lane_of.get(v)
            if hit is not None:                          # a lane already holding it
                return fixed(register("c", hit[0]), (hit[1],) * 4)
            while self._open:                            # a free lane of a pool register
                reg = self._open[0]
                slots = self.defs[reg]
                if None not in slots:
                    self._open.pop(0)
                    continue
                lane = slots.index(None)
                slots[lane] = v
                self._lane_of.setdefault(v, (reg, lane))
                return fixed(register("c", reg), (lane,) * 4)
            reg = self._free_constant(1)
            self.defs[reg] = [v, None, None, None]
            self._lane_of.setdefault(v, (reg, 0))
            self._open.append(reg)
            return fixed(register("c", reg), (0,) * 4)
        want = tuple(values) + (values[-1],) * (4 - len(values))
        reg = self._row_of.get(want)
        if reg is not None:
            return fixed(register("c", reg), IDENTITY)
        reg = self._free_constant(1)
        self.defs[reg] = list(want)
        self._row_of[want] = reg
        for lane, x in enumerate(want):
            self._lane_of.setdefault(x, (reg, lane))
        return fixed(register("c", reg), IDENTITY)

    # -- analysis ---------------------------------------------------------------------------
    def reachable(self) -> list[Node]:
        return needed([c.node for o in self.outputs for c in o.comps]
                      + [k.node for k in self.ctx.kills])

    def count_uses(self, nodes: list[Node]) -> None:
        for n in nodes:
            n.uses = 0
        for n in nodes:
            for a in n.args:
                a.node.uses += 1
        for o in self.outputs:
            for c in o.comps:
                c.node.uses += 1

    def combine(self, nodes: list[Node]) -> None:
        """The DAG's fusions (fusion.py): lerp written out -> lrp where the target has it,
        then mul + add -> mad where the mul has no other use."""
        if share_lit_diffuse(nodes, [o.comps for o in self.outputs] + [self.ctx.kills]):
            nodes = self.reachable()
        self.count_uses(nodes)
        uses = {n.id: n.uses for n in nodes}
        if self.target.has("lrp"):
            fuse_lrp(nodes, uses)
        fuse_mad(nodes, uses)
        if not any(n.op in ("loop", "if") for n in nodes):
            rule = "ps20" if self.rules.swizzles == "ps20" else "any"
            pack_scalars([n for n in nodes if uses.get(n.id, 1)],
                         [o.comps for o in self.outputs] + [self.ctx.kills],
                         lambda lanes: _choose(lanes, rule) is not None)

    # -- emission ---------------------------------------------------------------------------
    def place(self, op: Operand, lanes: list[int], reduce: bool = False) -> Register:
        """A source reading operand lanes: instruction lane i reads op lane i (or, for
        reductions, source lanes 0..k-1)."""
        node = op.node
        if node.op == "const":
            vals = [node.value[op.swizzle[i]] * (-1 if op.negate else 1) for i in lanes]  # type: ignore[index]
            src = self.const_src([float(v) for v in vals])
            if src.lanes is None and len(set(vals)) > 1:
                src.lanes = {i: k for k, i in enumerate(lanes)}
            return src
        reg, where = self.home[node.id]
        return read(reg, {i: where[op.swizzle[i]] for i in lanes}, op.negate)

    def home_of(self, node: Node) -> tuple[Register, dict[int, int]]:
        if node.id not in self.home:
            self.home[node.id] = (self.temp(), {c: c for c in range(node.width)})
        return self.home[node.id]

    def emit(self, opcode: str, dst: Register | None, mask: tuple[int, ...],
             srcs: list[Register], loc: Location, sampler: str | None = None,
             saturate: bool = False) -> None:
        self.instrs.append(instruction(opcode, dst, mask, srcs, self.target.name, loc, saturate,
                                       sampler))

    def generate(self) -> Code:
        """The generator's passes in order (compiler.py runs them one by one)."""
        self.fuse()
        self.select()
        self.optimise()
        legalize(self)
        return code_of(self)

    def fuse(self) -> None:
        """Optimise the DAG the outputs reach: fusion.py's rewrites (combine)."""
        self.combine(self.reachable())

    def select(self) -> None:
        """Instruction selection: each node the outputs reach as instructions on virtual
        temporaries, in place where coalesced, in the order of its block (flowcode.py)."""
        nodes = self.reachable()
        self.count_uses(nodes)
        self.live = analyse(nodes, [c for o in self.outputs for c in o.comps] + list(self.ctx.kills))
        self.coalesce(nodes)
        # the addresses relative reads use, in code without flow control: lanes of one node
        # are loaded into a0 together (relative_read)
        self.addresses = [] if any(n.op in ("loop", "if") for n in nodes) else \
            list(dict.fromkeys(n.args[0].sig() for n in nodes if n.op == "uniform_rel"))
        self._address_of = {n.args[0].sig(): n.args[0] for n in nodes if n.op == "uniform_rel"}
        self.blocks = place(self, nodes)
        emit_block(self, None)
        for k in self.ctx.kills:       # the program's own discards, at its end (a branch's
            if k.node.op == "kill":    # or loop's are emitted in it: flowcode.py)
                emit_kill(self, k.node)
        for o in self.outputs:
            self.output(o)

    def optimise(self) -> dict:
        """peephole.py's rewrites of the emitted instructions: what each removed."""
        return optimise(self)

    def _move(self, reg: Register, value: Operand, loc: Location) -> None:
        lanes = [(c, c) for c in range(value.width)]
        self.emit("mov", reg, tuple(range(value.width)), [self._lanewise(value, lanes)], loc)

    def coalesce(self, nodes: list[Node]) -> None:
        self._gathers: list[tuple[tuple[Operand, ...], object]] = []
        for p in nodes:
            if p.op != "pack":
                continue
            reg = self.home_of(p)[0]
            self._coalesce_into(p.args, reg, p.location, lambda lane: lane, shared=True)
        self.out_regs: dict[str, Register] = {}
        for o in self.outputs:
            # vertex shaders compute straight into the output; oC# and oDepth take a mov
            reg = register(*_split_reg(o.register)) if self.target.kind == "vs" else self.temp()
            self.out_regs[o.register] = reg
            self._coalesce_into(tuple(o.comps), reg, o.location, lambda lane: lane,
                                shared=reg.kind == "vr")
        self._gather_loose()

    def _coalesce_into(self, comps: tuple[Operand, ...], reg: Register, loc: Location, lane_of,
                       shared: bool = False) -> None:
        """Give the nodes that make `comps` their lanes of `reg` as home, so they compute in
        place. `shared`: `reg` is a temporary, which other instructions can read too, so a
        one-lane result (dp4, rcp ...) read elsewhere as well goes there all the same: the
        three dp4 of a position land in r0.xyz and every reader reads r0 (fxc's packing);
        an output register is written only."""
        by_node: dict[int, list[tuple[int, int]]] = {}
        for lane, c in enumerate(comps):
            if c.negate:
                continue
            by_node.setdefault(c.node.id, []).append((c.swizzle[0], lane))
        for c in comps:
            node = c.node
            pairs = by_node.get(node.id)
            if not pairs or node.id in self.home:
                continue
            uses_here = sum(1 for x in comps if x.node is node)
            movable = (node.op in _LANEWISE and not (node.op == "frc" and self.target.name == "vs_1_1")) or (node.width == 1 and (node.op in _SCALAR or node.op in _REDUCE))
            comps_used = [p[0] for p in pairs]
            alone = node.uses == uses_here or (
                shared and node.width == 1 and uses_here == 1 and node.op not in _LANEWISE)
            if movable and alone and len(set(comps_used)) == len(comps_used) \
                    and len(pairs) == uses_here:
                self.home[node.id] = (reg, {comp: lane_of(lane) for comp, lane in pairs})
                node.coalesced = True
        self._gathers.append((comps, lane_of))

    def _gather_loose(self) -> None:
        """What is left of the one-lane results a vector is made of (read negated, or read
        elsewhere too where the vector is an output) is gathered in a temporary of its own,
        lane for lane, so one mov (`mov oT2.xyz, -r0`), or none once the copy is read in
        place, makes the vector. After every vector had its turn at homing them itself."""
        for comps, lane_of in self._gathers:
            self._gather_into_temp(comps, lane_of)

    def _gather_into_temp(self, comps: tuple[Operand, ...], lane_of) -> None:
        loose = [(lane, c.node) for lane, c in enumerate(comps)
                 if c.node.id not in self.home and c.node.width == 1
                 and (c.node.op in _SCALAR or c.node.op in _REDUCE)
                 and sum(1 for x in comps if x.node is c.node) == 1]
        if len(loose) > 1:
            gather = self.temp()
            for lane, node in loose:
                self.home[node.id] = (gather, {0: lane_of(lane)})

    def node(self, n: Node) -> None:
        op = n.op
        if op == "const":
            return
        if op == "input":
            self.home[n.id] = (register(*_split_reg(n.key[1])), {c: c for c in range(4)})
            return
        if op == "uniform":
            self.home[n.id] = (self.uniform_reg(*n.key), {c: c for c in range(4)})
            return
        if op == "uniform_rel":
            self.relative_read(n)
            return
        if op == "uniform_al":               # c[aL + n], read where it is used (flowcode.py)
            base = self.uniform_reg(*n.key).index
            self.home[n.id] = (register("c", base, RelativeAddress("aL", 0, 0)),
                               {c: c for c in range(4)})
            return
        if op == "kill" and n.block is not None:
            emit_kill(self, n)         # inside a branch side or a loop body
            return
        if op == "kill" or op == "phi":
            return
        if op == "loop":
            emit_loop(self, n)
            return
        if op == "if":
            emit_if(self, n)
            return
        if op in ("loop_out", "if_out"):
            block_id, k = n.key
            reg = (self.loop_regs if op == "loop_out" else self.if_regs)[block_id][k]
            self.home[n.id] = (reg, {c: c for c in range(n.width)})
            return
        if self.live is not None and not self.live.of(n):
            return                     # nothing reads any of its lanes (liveness.py)
        if op == "pack":
            reg, _ = self.home_of(n)
            groups: dict[tuple, list[tuple[int, Operand]]] = {}
            for lane, c in enumerate(n.args):
                if self.home.get(c.node.id, (None,))[0] is reg and c.node.coalesced:
                    continue
                if self.live is not None and not self.live.keeps(n, lane):
                    continue           # a lane of the vector nobody reads
                groups.setdefault(self._source_key(c), []).append((lane, c))
            for items in groups.values():
                lanes = [lane for lane, _ in items]
                src = self._gather(items)
                self.emit("mov", reg, tuple(lanes), [src], n.location)
            return
        reg, where = self.home_of(n)
        lanes_out = sorted(where.items(), key=lambda kv: kv[1])    # (comp, register lane)
        if op in _TEX:
            srcs = [self.place(a, list(range(a.width))) for a in n.args]
            self.emit(_TEX[op], reg, (0, 1, 2, 3), srcs, n.location, sampler=n.key[0])
            return
        if shaped(op):
            widths = SHAPED[op][0]
            srcs = [self.place(a, list(range(w))) for a, w in zip(n.args, widths)]
            for s in srcs:
                if s.lanes is not None:
                    s.lanes = dict(s.lanes)
            mask = tuple(sorted(where[c] for c in range(n.width)))
            if op == "sincos":
                if self.rules.major < 3:
                    srcs += [self.const_src([-1.5500992e-06, -2.1701389e-05, 0.0026041667, 0.00026041668]),
                             self.const_src([-0.020833334, -0.125, 1.0, 0.5])]
                    fix(srcs[1], IDENTITY)
                    fix(srcs[2], IDENTITY)
                fix(srcs[0], (srcs[0].lanes[0],) * 4)  # type: ignore[index]
            self.emit(op, reg, mask, srcs, n.location)
            return
        if op in _REDUCE:
            k = _REDUCE[op]
            srcs = [self.place(a, list(range(k))) for a in n.args[:2]]
            if op == "dp2add":
                srcs.append(self.place(n.args[2], [0]))
                if srcs[2].lanes is not None:
                    fix(srcs[2], (srcs[2].lanes.get(0, 0),) * 4)
            mask = tuple(sorted(lane for _, lane in lanes_out))
            self.emit(op, reg, mask, srcs, n.location)
            return
        if op in _SCALAR:
            srcs = [self.place(a, [0]) for a in n.args]
            for s in srcs:
                if s.lanes is not None:
                    fix(s, (s.lanes[0],) * 4)
            mask = tuple(sorted(lane for _, lane in lanes_out))
            self.emit(op, reg, mask, srcs, n.location)
            return
        # component-wise: instruction lane L computes node comp c where where[c] = L, for the
        # comps some reader reads (liveness.py: the write mask holds only those)
        if self.live is not None:
            lanes_out = [(c, lane) for c, lane in lanes_out if self.live.keeps(n, c)]
        mask = tuple(lane for _, lane in lanes_out)
        srcs = []
        for a in n.args:
            s = self._lanewise(a, lanes_out)
            srcs.append(s)
        self.emit(OPS[op].mnemonic, reg, mask, srcs, n.location, saturate=op == "sat")  # type: ignore[arg-type]

    def relative_read(self, n: Node) -> None:
        """c[a0.? + n] copied to a temporary (read in place where nothing reloads that lane
        of a0 in between: peephole.py), a0 loaded first unless a lane holds this address
        already. vs_1_1 has a0.x alone, loaded with mov (which floors); vs_2_0 and up load
        any lane with mova (which rounds: the address is a whole number either way), so two
        bones' addresses sit in a0.x and a0.y and the first bone's rows stay readable (fxc's
        `mova a0.xy`); a fifth address takes the lane loaded longest ago."""
        address = n.args[0]
        lanes: dict[int, tuple] = self.a0 or {}
        lane = next((k for k, sig in lanes.items() if sig == address.sig()), None)
        if lane is None:
            count = 1 if self.rules.major == 1 else 4
            free = [k for k in range(count) if k not in lanes]
            lane = free[0] if free else next(iter(lanes))
            lanes.pop(lane, None)
            # the other addresses still to load that are lanes of the same node come along
            # in the free lanes: one `mova a0.xy, r0` for two bones (fxc's code)
            group = [address] + [
                self._address_of[sig] for sig in self.addresses
                if sig != address.sig() and sig not in lanes.values()
                and sig[0] == address.node.id and sig[2] == address.negate
                and address.node.op != "const"][:len(free) - 1]
            targets = [lane] + [k for k in free if k != lane][:len(group) - 1]
            if len(group) > 1:
                src = self._lanewise(Operand(address.node, tuple(a.swizzle[0] for a in group),
                                             address.negate),
                                     [(i, t) for i, t in enumerate(targets)])
            else:
                src = self.place(address, [0])
                if src.lanes is not None:
                    fix(src, (src.lanes[0],) * 4)
            self.emit("mov" if self.rules.major == 1 else "mova", register("a", 0),
                      tuple(sorted(targets)), [src], n.location)
            for a, t in zip(group, targets):
                lanes[t] = a.sig()              # insertion order: the oldest first
            self.a0 = lanes
        base = self.uniform_reg(n.key[0], n.key[1]).index
        reg, _ = self.home_of(n)
        lanes_read = tuple(sorted(self.live.of(n))) if self.live is not None else (0, 1, 2, 3)
        self.emit("mov", reg, lanes_read,
                  [read(register("c", base, RelativeAddress("a", 0, lane)),
                        {i: i for i in lanes_read})], n.location)

    def _lanewise(self, a: Operand, lanes_out: list[tuple[int, int]]) -> Register:
        node = a.node
        if node.op == "const":
            return self._const_lanes({lane: node.value[a.swizzle[min(c, a.width - 1)]]  # type: ignore[index]
                                      * (-1 if a.negate else 1) for c, lane in lanes_out})
        reg, where = self.home[node.id]
        return read(reg, {lane: where[a.swizzle[min(c, a.width - 1)]] for c, lane in lanes_out},
                    a.negate)

    def _const_lanes(self, vals: dict[int, float]) -> Register:
        """A constant source giving each destination lane its value: one replicated register
        when they agree, else a register holding them lane by lane (the rest repeat one)."""
        if len(set(vals.values())) == 1:
            return self.const_src([next(iter(vals.values()))])
        full = [vals.get(l, next(iter(vals.values()))) for l in range(4)]
        src = self.const_src([float(x) for x in full])
        src.lanes = {l: l for l in vals}
        return src

    def _source_key(self, c: Operand) -> tuple:
        """Lanes of a vector built from pieces that one mov can gather: the constants, and
        the pieces whose homes are one register (several one-lane results coalesced into it),
        with the same sign."""
        if c.node.op == "const":
            return ("const",)
        home = self.home.get(c.node.id)
        if home is None:
            return (c.node.id, c.negate)
        return (home[0].kind, home[0].index, c.negate)

    def _gather(self, items: list[tuple[int, Operand]]) -> Register:
        first = items[0][1]
        if first.node.op == "const":
            return self._const_lanes({lane: c.const_values()[0] for lane, c in items})  # type: ignore[index]
        reg = self.home[first.node.id][0]
        return read(reg, {lane: self.home[c.node.id][1][c.swizzle[0]] for lane, c in items},
                    first.negate)

    def output(self, o: Output) -> None:
        final = register(*_split_reg(o.register))
        reg = self.out_regs[o.register]
        comps = list(o.comps)
        if o.register.startswith("oC"):
            comps += [comps[-1]] * (4 - len(comps))
        pending = [(lane, c) for lane, c in enumerate(comps)
                   if not (lane < len(o.comps) and self.home.get(c.node.id, (None,))[0] is reg)]
        if self.target.kind == "ps" and len(pending) == len(comps):
            first = comps[0].node
            home = self.home.get(first.id)
            if home is not None and all(c.node is first and not c.negate for c in comps) \
                    and home[0].kind in ("vr", "t", "v"):
                src = read(home[0], {l: home[1][c.swizzle[0]] for l, c in enumerate(comps)})
                self.emit("mov", final, (0, 1, 2, 3) if o.register.startswith("oC") else (0,),
                          [src], o.location)
                return
        groups: dict[tuple, list[tuple[int, Operand]]] = {}
        for lane, c in pending:
            groups.setdefault(self._source_key(c), []).append((lane, c))
        for items in groups.values():
            self.emit("mov", reg, tuple(l for l, _ in items), [self._gather(items)], o.location)
        if self.target.kind == "ps":
            mask = (0, 1, 2, 3) if o.register.startswith("oC") else (0,)
            self.emit("mov", final, mask, [read(reg, {l: l for l in mask})], o.location)


def _split_reg(name: str) -> tuple[str, int | None]:
    head = name.rstrip("0123456789")
    tail = name[len(head):]
    return head, int(tail) if tail else None
