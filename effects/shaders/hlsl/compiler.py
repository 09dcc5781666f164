"""compile_shader: an effect's HLSL function compiled for a target, as fxc did.

    shader = compile_shader(effect, "Wood", "ps_2_0")          # or cache.compile_state(effect, cs)
    shader.text        # the assembly listing (vs_1_1 ... ps_3_0), printed from `program`
    shader.program     # the assembler's records (effects.shaders.asm), located in the HLSL
    shader.constants   # parameter -> (first c#, count): what the pass must load
    shader.samplers    # sampler parameter -> s#
    shader.int_registers   # int parameter -> i# (a `rep` count the pass sets)
    shader.bool_registers  # bool parameter -> b# (an `if b#` the pass sets)

The passes (PASSES, below) run in order over one Compilation; the writer (writer.py) makes
the assembler's own records, which go through the assembler's checks and the card's limits like
any hand-written shader; each instruction of `program` is located at the HLSL line it comes
from. No text is parsed back.
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any, Callable

from effects.base.errors import EffectError, Location, UNKNOWN_LOCATION
from effects.model import Effect
from effects.shaders.asm.program import AsmProgram, Declaration
from effects.shaders.asm.parser import USAGES
# CompiledShader lives in shader.py and compile_state in cache.py: a cached shader needs no
# compiler (CompiledShader is importable from here as before)
from effects.shaders.hlsl.shader import CompiledShader
from effects.shaders.hlsl.calls import constant_parameters, parameters, return_type
from effects.shaders.hlsl.budget import out_of_stack, spend
from effects.shaders.hlsl.check import check_unit
from effects.shaders.hlsl.codegen import CodeGen
from effects.shaders.hlsl.legalize import code_of, legalize
from effects.shaders.hlsl.codegen_ps1 import generate_ps1
from effects.shaders.hlsl.constant_layout import (declaration_order, first_fit, overlap,
                                                  used_sizes)
from effects.shaders.hlsl.context import (Context, explicit_register as _explicit, load_context,
                                          parameter_type, sampler_element)
from effects.shaders.hlsl.dag import Node, Operand, Output
from effects.shaders.hlsl.flowcode import needed
from effects.shaders.hlsl.folding import finite32
from effects.shaders.hlsl.ops import TEXTURE
from effects.shaders.hlsl.evaluate import Evaluator, Frame
from effects.shaders.hlsl.parse import HlslError, Origin, parse
from effects.shaders.hlsl.types import HType, register_count
from effects.shaders.hlsl.values import Value
from effects.shaders.hlsl.writer import Code, declaration, listing, write

EMIT_COST = 4
_SEMANTIC = re.compile(r"^([A-Za-z_]+?)(\d*)$")
_VS_OUT = {"POSITION": "oPos", "COLOR": "oD", "TEXCOORD": "oT", "FOG": "oFog", "PSIZE": "oPts"}


def split_semantic(text: str) -> tuple[str, int]:
    m = _SEMANTIC.match(text.strip())
    if not m:
        return text.upper(), 0
    return m.group(1).upper(), int(m.group(2) or 0)


# The Direct3D 10 system-value semantics fxc accepts for Direct3D 9 targets, by what they mean
# there: a vertex output SV_Position is POSITION, a pixel output SV_Target[n] COLOR[n] and
# SV_Depth DEPTH; a ps_3_0 input SV_Position is VPOS (fxc declares both as vPos: dxbc-spirv
# pull request 71). Files written for both APIs use them (foo_wave_seekbar's Direct3D 9 effect).
_SV_AS_D3D9 = {"SV_POSITION": "POSITION", "SV_TARGET": "COLOR", "SV_DEPTH": "DEPTH"}
# ps_3_0's two misc inputs: (register, its declaration)
_PS3_MISC = {"VPOS": ("vPos", (0, 1)), "VFACE": ("vFace", None)}


def compile_shader(effect: Effect, entry: str, target: str, args: tuple[str, ...] = (),
                   where: Location | None = None) -> CompiledShader:
    where = where or Location(effect.path, 1, 1)
    fdefs = [f for f in effect.functions if f.name == entry]
    at = fdefs[0].location if fdefs else where
    try:
        shader, literal_loops = _compile_shader(effect, entry, target, args, where)
        if literal_loops and not _fits(shader):
            # fxc unrolled a for over literal bounds when it could and the code fitted the
            # target; when it did not, the loop stayed a loop (rep / loop aL): the XNA toon
            # shader's `for (i = 0; i < 30; ++i)` over lightPositions[i], 858 ps_3_0 slots
            # unrolled, which fxc compiled. [unroll] and [loop] decide where written.
            looped, _ = _compile_shader(effect, entry, target, args, where, loops_for_size=True)
            if looped.program.stats.total_slots < shader.program.stats.total_slots:
                return looped
        return shader
    except RecursionError:
        raise out_of_stack(at) from None
    except EffectError as err:
        if err.location != UNKNOWN_LOCATION:
            raise
        # a check deep in code generation that had no place to give: the function's
        raise type(err)(err.message, at) from None


def _fits(shader: CompiledShader) -> bool:
    """Whether the code fits what fxc allowed the target: the version's slots (vs_2_0 256,
    ps_2_a 512), and for shader model 3 the 512 every card has (its X5608 limit)."""
    rules = shader.program.rules
    stats = shader.program.stats
    limit = rules.total_slots_min if rules.major >= 3 else rules.total_slots
    return stats.total_slots <= limit and \
        (rules.arith_slots is None or stats.arithmetic_slots <= rules.arith_slots) and \
        (rules.tex_slots is None or stats.texture_slots <= rules.tex_slots)


@dataclass
class Compilation:
    """What the passes hand on (PASSES): each reads what earlier ones set and sets its own."""

    effect: Effect
    entry: str
    target: str
    args: tuple[str, ...]
    where: Location
    loops_for_size: bool = False
    ctx: Context = field(init=False)
    fdef: Any = field(init=False)
    ev: Evaluator = field(init=False)
    binder: "_Binder" = field(init=False)
    outs: list[tuple[str, HType, Any, Any]] = field(default_factory=list)  # out/inout params
    outputs: list[Output] = field(default_factory=list)
    preshaders: dict[str, Any] = field(default_factory=dict)
    nodes: list[Node] = field(default_factory=list)
    constants: dict[str, int] = field(default_factory=dict)    # uniform -> first c#
    sizes: dict[str, int] = field(default_factory=dict)        # uniform -> registers
    samplers: dict[str, int] = field(default_factory=dict)     # fixed before generation
    gen: Any = None                        # the code generator (codegen.CodeGen)
    code: Code | None = None
    program: AsmProgram | None = None
    generated_at: dict[int, Location] = field(default_factory=dict)
    shader: CompiledShader | None = None

    @property
    def ps1(self) -> bool:
        return self.ctx.target.rules.is_ps1


def bind(c: Compilation) -> None:
    """The entry point and its parameters: inputs by semantic (_Binder), uniforms, compile
    arguments; out parameters declared for `outputs`."""
    ctx = c.ctx = load_context(c.effect, c.target.lower())
    # fxc type-checked the whole file before it compiled the entry: a language error in any
    # function or initialiser, called or not, fails every compile (check.py)
    unit_error = check_unit(c.effect)
    if unit_error is not None:
        raise unit_error
    ctx.loops_for_size = c.loops_for_size
    fdefs = ctx.functions.get(c.entry)
    if not fdefs:
        raise HlslError(f"X3501: '{c.entry}': entrypoint not found", c.where)
    fdef = c.fdef = fdefs[0]
    if ctx.target.name == "ps_1_0":
        raise HlslError("X3507: fxc compiles HLSL for ps_1_1 and later, not ps_1_0", c.where)
    ev = c.ev = Evaluator(ctx, fdef.origin)
    ev.frames.append(Frame(return_type(ctx, fdef)))
    compile_args = list(c.args)
    binder = c.binder = _Binder(ctx, ev)
    fixed = constant_parameters(fdef)
    for name, t, direction, default, sem in parameters(ev, fdef):
        sem_text = sem.children[0] if sem is not None and sem.data != "register" else None
        if direction == "uniform":
            if compile_args:
                value = _compile_argument(ctx, ev, compile_args.pop(0), t, c.where)
            elif default is not None:
                value = ev.a.convert(ev.expr(default), t, ev.at(default))
            else:
                value = binder.uniform_param(name, t)
            ev.declare(name, t, value, const=True)
        elif direction == "out":
            ev.declare(name, t, ev.zero(t))
            c.outs.append((name, t, sem_text, sem))
        else:
            value = binder.input(t, str(sem_text) if sem_text is not None else None,
                                 fdef.origin.at(sem if sem is not None else fdef.tree), name)
            ev.declare(name, t, value, const=name in fixed)
            if direction == "inout":
                c.outs.append((name, t, sem_text, sem))
    if compile_args:
        raise HlslError(f"X3013: '{c.entry}': too many compile arguments ({len(c.args)})",
                        c.where)


def evaluate(c: Compilation) -> None:
    """The body, evaluated into the DAG (evaluate.py)."""
    c.ev.block(c.fdef.tree.children[-1])


def bind_outputs(c: Compilation) -> None:
    """The return value and out parameters onto output registers by semantic, and the
    outputs fxc requires (X4541, X4530)."""
    ev, fdef, frame = c.ev, c.fdef, c.ev.frames[-1]
    fsem = fdef.tree.children[4]
    if frame.return_type.kind != "void":
        if frame.retval is None:
            raise fdef.origin.error(f"X3080: '{c.entry}': function must return a value",
                                    fdef.tree)
        c.binder.outputs(frame.retval, str(fsem.children[0]) if fsem is not None else None,
                         fdef.origin.at(fdef.tree), c.outputs)
    for name, t, sem_text, sem in c.outs:
        c.binder.outputs(ev.scopes[0][name].value if name in ev.scopes[0] else
                         ev.lookup(name).value,
                         str(sem_text) if sem_text is not None else None,
                         fdef.origin.at(sem if sem is not None else fdef.tree), c.outputs)
    _check_required_outputs(c.ctx, c.entry, c.binder.bound, fdef)


def preshade(c: Compilation) -> None:
    """ps_1_x: fxc's preshader, what reads only uniforms computed on the host (preshader.py)."""
    if not c.ps1:
        return
    from effects.shaders.hlsl.preshader import preshade_ps1
    ctx = c.ctx
    roots = [x for o in c.outputs for x in o.comps] + list(ctx.kills)
    c.preshaders = preshade_ps1(c.ev.g, roots, not ctx.target.rules.is_ps14, ctx.uniforms_used)
    for o in c.outputs:
        o.comps, roots = roots[:len(o.comps)], roots[len(o.comps):]
    ctx.kills[:] = roots


def reach(c: Compilation) -> None:
    """The nodes the outputs and discards reach, with what no code can hold refused: a
    constant that is not a finite float32, an input the target cannot map."""
    ctx = c.ctx
    c.nodes = needed([x.node for o in c.outputs for x in o.comps] + [k.node for k in ctx.kills])
    # generating the code costs about four evaluation steps a node
    spend(c.ev, EMIT_COST * len(c.nodes), c.fdef.tree)
    _finite_constants(ctx, c.nodes, c.outputs, c.fdef)
    for n in c.nodes:
        if n.op == "input" and n.key[0] == "unmapped":
            raise HlslError(f"X4502: invalid {ctx.target.name} input semantic '{n.key[1]}'",
                            n.location)


def layout_constants(c: Compilation) -> None:
    """Constant registers in fxc's order and the samplers fixed before generation."""
    c.constants, c.sizes = _constant_registers(c.ctx, c.nodes)
    c.samplers = _sampler_registers(c.ctx, {n.key[0] for n in c.nodes if n.op in TEXTURE},
                                   not c.ps1)
    if not c.ps1:
        c.gen = CodeGen(c.ctx, c.binder.dcls, c.outputs, c.constants, c.samplers, c.sizes)
        c.gen.output_dcls = c.binder.output_dcls


def fuse(c: Compilation) -> None:
    """The DAG's fusions (fusion.py: lrp, mad, lit sharing, scalar packing)."""
    if not c.ps1:
        c.gen.fuse()


def select(c: Compilation) -> None:
    """Instruction selection onto virtual temporaries (codegen.py). ps_1_x has a generator of
    its own (no dcl, no oC#, one texture read per stage, modifiers: codegen_ps1.py), which
    fuses, selects and allocates in one: its allocation decides where the result is made."""
    if c.ps1:
        c.code = generate_ps1(c.ctx, c.outputs, c.constants, c.samplers, c.sizes)
    else:
        c.gen.select()


def optimise(c: Compilation) -> None:
    """The rewrites of the selected instructions (peephole.py)."""
    if not c.ps1:
        c.gen.optimise()


def legalize_code(c: Compilation) -> None:
    """The version's read ports, texture coordinates and swizzles (legalize.py)."""
    if not c.ps1:
        legalize(c.gen)


def allocate_registers(c: Compilation) -> None:
    """Temporaries onto r# (allocate.py), with the tables of registers the pass loads."""
    if not c.ps1:
        c.code = code_of(c.gen)


def write_program(c: Compilation) -> None:
    """The assembler's records (writer.py), located in the HLSL."""
    c.program, c.generated_at = write(c.code, c.ctx.target.rules,  # type: ignore[arg-type]
                                      c.fdef.origin.at(c.fdef.tree))


def list_program(c: Compilation) -> None:
    """The listing (text only for reading and the on-disk store) and the compiled shader."""
    code, ctx = c.code, c.ctx
    text, lines = listing(c.program, c.generated_at)  # type: ignore[arg-type]
    c.shader = CompiledShader(c.entry, ctx.target.name, text, c.program, code.constants,  # type: ignore[union-attr, arg-type]
                              code.samplers, lines, list(ctx.warnings),  # type: ignore[union-attr]
                              {**ctx.uniforms_used, **_sampler_arrays(ctx, code.samplers)},  # type: ignore[union-attr]
                              code.int_registers,  # type: ignore[union-attr]
                              code.bool_registers,  # type: ignore[union-attr]
                              {n: p for n, p in c.preshaders.items() if n in code.constants},  # type: ignore[union-attr]
                              dict(code.register_counts))  # type: ignore[union-attr]


# bind -> evaluate -> outputs -> (ps_1_x preshader) -> reach -> layout constants -> fuse ->
# select -> optimise -> legalize -> allocate -> write -> listing, as vkd3d-shader's
# hlsl_emit_bytecode runs its passes in order; each is a function of the Compilation, so a
# test can run the list up to one and look at what that one does
PASSES: tuple[Callable[[Compilation], None], ...] = (
    bind, evaluate, bind_outputs, preshade, reach, layout_constants, fuse, select, optimise,
    legalize_code, allocate_registers, write_program, list_program)


def run_passes(c: Compilation, until: Callable[[Compilation], None] | None = None) -> Compilation:
    """Run PASSES in order on `c`, up to and including `until` (all of them without)."""
    for p in PASSES:
        p(c)
        if p is until:
            break
    return c


def _compile_shader(effect: Effect, entry: str, target: str, args: tuple[str, ...],
                    where: Location, loops_for_size: bool = False) -> tuple[CompiledShader, int]:
    """The shader, and how many loops over literal bounds it unrolled that could have been
    real loops."""
    c = run_passes(Compilation(effect, entry, target, args, where, loops_for_size))
    return c.shader, c.ctx.literal_loops  # type: ignore[return-value]


def _check_required_outputs(ctx: Context, entry: str, bound: set[tuple[str, int]],
                            fdef: Any) -> None:
    """The outputs fxc requires of an entry point, by semantic (usage, index) as bound:
    a vertex shader writes POSITION0 (X4541) and a pixel shader COLOR0 (X4530), whatever else
    it writes. Codes and wording: fxc's HLSL error list (XShaderCompiler's HLSLErr.h mirrors
    it: ERR_WRITE_ALL_POS = 4541, ERR_WRITE_TO_COLOR0 = 4530) and d3dcompiler's own check,
    which counts the components of the output with usage POSITION, index 0 (its disassembly
    prints "vertex shader must minimally write all four components of POSITION" with
    0x11bd = 4541). dcl_usage's reference page: a vs_3_0 output "must be declared as
    position", so the rule holds for every vertex shader version."""
    if ctx.target.kind == "vs" and ("POSITION", 0) not in bound:
        raise fdef.origin.error(f"X4541: '{entry}': vertex shader must minimally write all "
                                "four components of POSITION", fdef.tree)
    if ctx.target.kind == "ps" and ("COLOR", 0) not in bound:
        raise fdef.origin.error(f"X4530: '{entry}': pixel shader must minimally write all "
                                "four components of COLOR0", fdef.tree)


def _array_semantics(semantic: str, t: HType) -> list[str]:
    """An array's elements take the semantic's next indices: `float4 v[3] : TEXCOORD2` is
    TEXCOORD2, TEXCOORD3, TEXCOORD4 (as fxc bound it: DungeonQuest's, an XNA game's, light
    vectors)."""
    usage, index = split_semantic(semantic)
    return [f"{usage}{index + k}" for k in range(t.length)]


def _sampler_registers(ctx: Context, read: set[str], every: bool = True) -> dict[str, int]:
    """The s# of the samplers the code reads, fixed before code generation. Explicit
    register(s#) bindings first. A sampler paired with a texture (`Tex.Sample(S, uv)`:
    `S+Tex`) takes the sampler's register(s#) where it has one, else the first free register
    before the samplers read alone, as native d3dcompiler placed the combined samplers it made
    for shader models 1-3 (vkd3d's combined-samplers shader test). The rest as fxc laid out
    the float constants (constant_layout.py): a sampler array holds the registers up to the
    last element read (`S[1]` read alone: two), the largest first, those of one size in
    declaration order, each at the first free run (fxc 9.29's effect in
    tests/data/fxo/wine/test_effect_preshader_effect_blob.fxo: its vs_3_0 reads sampler1 and
    samplers_array[1] and gives samplers_array s0-s1, sampler1 s2; its ps_3_0 reads
    samplers_array[0] and gives sampler1 s0, samplers_array s1; d3dcompiler's, in Wine's
    test_constant_table and vkd3d's combined-samplers test, are in declaration order, not the
    order of use). `every` False (ps_1_x, whose code generator gives a sampler read alone
    its stage) places the arrays alone. `read`: the samplers the code reads (a sampler passed
    to `Tex.Sample` is named without being read alone)."""
    regs = {name: b for name in ctx.samplers_used if (b := _explicit(ctx, name, "s")) is not None}
    for name, b in regs.items():
        _within(ctx, name, b, 1, "s")
    # what each bound sampler the code reads holds: an array up to its last element read,
    # a sampler paired with a texture its own register (S alone and S+Tex are two samplers)
    spans: dict[str, tuple[int, int]] = {}
    for name, b in regs.items():
        if name not in read:
            continue
        holder, index = sampler_element(name) if "+" not in name else (name, None)
        k = index or 0
        first, size = spans.get(holder, (b - k, 0))
        spans[holder] = (first, max(size, k + 1))
    declared = declaration_order(ctx.effect)
    ordered = sorted(spans, key=lambda h: (declared.get(h.split("+")[0], len(declared)), h))
    _no_overlap(ctx, [(h, *spans[h]) for h in ordered], "s")
    taken = set(regs.values())
    for name in ctx.samplers_used:
        if "+" in name and name not in regs:
            regs[name] = min(set(range(len(taken) + 1)) - taken)
            taken.add(regs[name])
    # the rest, by the name that holds the registers: an array's up to its last element read
    sizes: dict[str, int] = {}
    for name in ctx.samplers_used:
        if name in regs or name not in read or "+" in name:
            continue
        base, index = sampler_element(name)
        if index is None and not every:
            continue
        sizes[base] = max(sizes.get(base, 0), 1 if index is None else index + 1)
    first = first_fit(list(sizes), sizes, taken, declared)
    for name in ctx.samplers_used:
        if name in regs or name not in read or "+" in name:
            continue
        base, index = sampler_element(name)
        if index is not None:
            regs[name] = first[base] + index
        elif name in first:
            regs[name] = first[name]
    return regs


def _sampler_arrays(ctx: Context, samplers: dict[str, int]) -> dict[str, HType]:
    """The types of the sampler arrays whose elements the code reads, for the constant
    table (its entry is the array, of the array's type: fxc's in
    tests/data/fxo/wine/test_effect_preshader_effect_blob.fxo)."""
    out: dict[str, HType] = {}
    for name in samplers:
        p = ctx.effect.parameter(name.split("[", 1)[0]) if name.endswith("]") else None
        if p is not None:
            out[p.name] = parameter_type(ctx, p)
    return out


def _finite_constants(ctx: Context, nodes: list[Node], outputs: list[Output], fdef: Any) -> None:
    """Every constant the code reads is a finite float32, as a `def` register holds: a value
    folded to inf or NaN (`1.0 / 0`, `1e39`, `frac(1e39 * 1e39)`) is refused where it is read.
    fxc refused infinities and NaNs for shader models 1-3 (vkd3d-shader, which follows it:
    "Infinities and NaNs are not allowed by the shader model"; its X code was not found)."""
    def refuse(values: tuple[float, ...], loc: Location) -> None:
        bad = next(v for v in values if not finite32(v))
        where = loc if loc != UNKNOWN_LOCATION else fdef.origin.at(fdef.tree)
        raise fdef.origin.error(
            f"a constant here folds to {bad!r}, which a {ctx.target.name} constant register "
            "cannot hold (Direct3D 9 shader constants are finite float32: at most "
            "3.4e38, no infinity or NaN)", where)

    def check(operand: Operand, loc: Location) -> None:
        values = operand.const_values()
        if values is not None and not all(finite32(v) for v in values):
            own = operand.node.location          # a literal's, or the op it was folded from
            refuse(values, own if own != UNKNOWN_LOCATION else loc)

    for n in nodes:
        if n.op != "const":
            for a in n.args:
                check(a, n.location)
    for o in outputs:
        for c in o.comps:
            check(c, o.location)


def _no_overlap(ctx: Context, spans: list[tuple[str, int, int]], kind: str) -> None:
    """fxc's X4500 (its words: "overlapping register semantics not yet implemented 'c0'"):
    two variables the code reads, bound by `register()` to registers that overlap in what
    each reads. The binding is the file's, so every target refuses it: a language error.
    `spans`: (name, first register, registers read) in declaration order."""
    clash = overlap(spans)
    if clash is None:
        return
    first, second, r = clash
    param = ctx.effect.parameter(second.split("+")[0].split("[")[0])
    why = (" (a sampler read with two textures, or alone and with a texture, is two samplers "
           "on shader models 1-3)" if "+" in first + second else "")
    raise HlslError(f"X4500: overlapping register semantics not yet implemented '{kind}{r}': "
                    f"'{first}' and '{second}' are both bound to {kind}{r}{why}",
                    param.location if param is not None else UNKNOWN_LOCATION)


def _constant_registers(ctx: Context, nodes: list[Node]) -> tuple[dict[str, int], dict[str, int]]:
    """fxc's float constant layout (constant_layout.py): each uniform the code reads takes
    the registers up to the last it reads; explicit register(c#) bindings first, then the
    rest, the largest first, first fit. `ctx.reserved_constants` gets every register an
    explicit binding holds (its whole type's, read or not), which no literal may take."""
    used = used_sizes(nodes, lambda name: register_count(ctx.uniforms_used.get(name)
                                                         or HType("scalar")))
    # the registers a constant offset reads, per uniform: where only a run-time index (a0, aL)
    # reaches further, fxc let the binding run past the target's last register (librw's
    # skin_VS: `float4x4 boneMatrices[64] : register(c41)` for vs_2_0, c41..c296 in its CTAB)
    reach: dict[str, int] = {}
    for n in nodes:
        if n.op == "uniform":
            reach[n.key[0]] = max(reach.get(n.key[0], 1), n.key[1] + 1)
    regs: dict[str, int] = {}
    reserved: set[int] = set()
    for p in ctx.effect.parameters:
        b = _explicit(ctx, p.name, "c")
        if b is None or "static" in p.storage or (p.name not in used and not p.type.is_numeric):
            continue
        full = register_count(ctx.uniforms_used.get(p.name) or parameter_type(ctx, p))
        if p.name in used:
            _within(ctx, p.name, b, reach.get(p.name, 1), "c")
            regs[p.name] = b
        reserved.update(range(b, b + full))
    _no_overlap(ctx, [(name, b, used[name]) for name, b in regs.items()], "c")
    ctx.reserved_constants = reserved
    declared = declaration_order(ctx.effect)
    regs.update(first_fit([n for n in used if n not in regs], used, reserved, declared))
    return regs, used


# fxc's refusals of a `register()` past what the target addresses (d3dx's message table:
# X4507 "maximum constant register index exceeded"; DXC's packreg test: X4509 "maximum sampler
# register index exceeded"): a refusal for the target, the same binding compiles for a larger one
_REGISTER_CODES = {"c": ("X4507", "constant"), "s": ("X4509", "sampler")}


def _within(ctx: Context, name: str, first: int, count: int, kind: str) -> None:
    """Refuse parameter `name` bound by `register()` to `first` .. `first + count - 1` of
    register kind `kind` where the target has fewer (the float constants fxc allows a target:
    a vertex shader's guaranteed count, 96 or 256; a pixel shader's file)."""
    rules = ctx.target.rules
    if kind == "c":
        have = rules.constants_min or rules.registers.get("c", 0)
    else:       # ps_1_x samples by stage (t#); a vs_1_1/2_0 sampler is refused where it samples
        have = rules.registers.get("s") or rules.registers.get("t") or 16
    if first + count <= have:
        return
    code, what = _REGISTER_CODES[kind]
    base = name.split("[", 1)[0]
    param = ctx.effect.parameter(base)
    at = param.location if param is not None else UNKNOWN_LOCATION
    raise HlslError(f"{code}: maximum {what} register index exceeded: '{base}' is bound to "
                    f"{kind}{first}{f'..{kind}{first + count - 1}' if count > 1 else ''}, "
                    f"{ctx.target.name} has {kind}0..{kind}{have - 1}", at)


def _compile_argument(ctx: Context, ev: Evaluator, text: str, t: HType, where: Location) -> Value:
    origin = Origin(where, text)
    tree = parse(text, "initializer", origin, ctx.type_names)
    sub = ev.spawn(origin)
    # A literal folds to a constant; a global parameter (NVIDIA's shader library passes
    # `std_VS(gWorldITXf, gWorldXf, gViewIXf, gWvpXf)`) stays a uniform read, so the entry's
    # uniform parameter reads that global's constant registers, as fxc compiles it. Only
    # globals are in scope here, so nothing else can be non-constant.
    return sub.a.convert(sub.expr(tree), t, where)


class _Binder:
    """Entry-point inputs and outputs by semantic, per target."""

    def __init__(self, ctx: Context, ev: Evaluator) -> None:
        self.ctx = ctx
        self.ev = ev
        self.dcls: dict[str, Declaration] = {}     # input register -> its dcl
        self.output_dcls: list[Declaration] = []
        self.next_v = 0
        self.next_o = 0
        self.input_keys: dict[str, tuple] = {}   # v# -> (usage, index) of a vertex input
        self.bound: set[tuple[str, int]] = set()  # the (usage, index) of every output bound

    def _error(self, message: str, loc: Location) -> HlslError:
        """A located error of the entry's semantics, shown with its line of the file."""
        return HlslError(message, loc, source_line=self.ev.origin.source_line(loc))

    def uniform_param(self, name: str, t: HType) -> Value:
        from effects.shaders.hlsl.expressions import uniform_value
        key = f"${name}"
        self.ctx.uniforms_used.setdefault(key, t)
        return uniform_value(self.ev, key, t, 0)

    def input(self, t: HType, semantic: str | None, loc: Location, name: str) -> Value:
        if t.kind == "struct":
            out = Value(t)
            for fname, ft, fsem in t.fields:
                out.fields[fname] = self.input(ft, fsem, loc, f"{name}.{fname}")
            return out
        if semantic is None:
            raise self._error(f"X4502: input '{name}' of the entry point has no semantic", loc)
        if t.kind == "array":
            return Value(t, elements=[self.input(t.element, element, loc, f"{name}[{k}]")  # type: ignore[arg-type]
                                      for k, element in enumerate(_array_semantics(semantic, t))])
        target = self.ctx.target
        # `TEXCOORD0_centroid`: the reference's centroid modifier on a pixel input (ps_2_0
        # and up, "Modifiers for ps_2_0 and above"), declared `dcl_centroid t0` /
        # `dcl_texcoord0_centroid v0`
        centroid = target.kind == "ps" and not target.rules.is_ps1 \
            and semantic.lower().endswith("_centroid")
        if centroid:
            semantic = semantic[:-len("_centroid")]
        usage, index = split_semantic(semantic)
        if target.kind == "ps" and usage == "SV_POSITION":
            usage = "VPOS"
        # a pixel input is declared with the components of its type, as fxc did (SDL 2's
        # ps_2_0 YUV shaders, tests/data/d3dbc: `dcl t0.xy` for a float2 TEXCOORD0, `dcl v0`
        # for a float4 COLOR); a vertex input with all four (`dcl_normal v1` for Wine's float3)
        width = t.size if t.kind in ("scalar", "vector") else 4
        if target.kind == "ps" and target.rules.major >= 3 and usage in _PS3_MISC:
            reg, mask = _PS3_MISC[usage]
            self.dcls[reg] = declaration(reg, None, mask=mask)
        elif target.kind == "ps" and target.rules.major < 3:
            if usage in ("COLOR", "TEXCOORD"):
                kind = "v" if usage == "COLOR" else "t"
                if index >= target.rules.registers.get(kind, 0):     # COLOR2, TEXCOORD8
                    raise self._error(f"X4502: invalid {target.name} input semantic "
                                    f"'{semantic}' ({target.name} has {kind}0.."
                                    f"{kind}{target.rules.registers.get(kind, 0) - 1})", loc)
                reg = f"{kind}{index}"
            else:
                # fxc accepts a pixel input it cannot map (the POSITION0 of a vertex-output struct
                # reused as the pixel input, as most XNA effects do) as long as nothing reads it
                node = self.ctx.graph.leaf("input", ("unmapped", semantic), 4, loc)
                return Value(t, [Operand(node.node, (min(i, 3),)) for i in range(t.size)])
            self._declare(reg, width, lambda mask: declaration(reg[0], int(reg[1:]), mask=mask,
                                                             centroid=centroid))
        else:
            key = (usage, index)
            reg = None
            for r in self.dcls:
                if self.input_keys.get(r) == key:
                    reg = r
            if reg is None:
                if usage.lower().removeprefix("sv_") not in USAGES:   # no dcl_ usage
                    raise self._error(f"X4502: invalid {target.name} input semantic "
                                    f"'{semantic}'", loc)
                reg = f"v{self.next_v}"
                self.next_v += 1
                self.input_keys[reg] = key
            v = int(reg[1:])
            self._declare(reg, width if target.kind == "ps" else 4, lambda mask: declaration(
                "v", v, usage.lower().removeprefix("sv_"), index, mask=mask, centroid=centroid))
        if not t.numeric:
            raise self._error(f"X4502: input '{name}' must be numeric, not '{t}'", loc)
        node = self.ctx.graph.leaf("input", ("input", reg), 4, loc)
        comps = [Operand(node.node, (min(i, 3),)) for i in range(t.size)]
        return Value(t, comps)

    def _declare(self, reg: str, width: int, make: Callable[[tuple[int, ...] | None], Declaration]
                 ) -> None:
        """Declare input `reg` with its first `width` components (all four: no mask), or more
        where another input already bound to it declared more."""
        old = self.dcls.get(reg)
        if old is not None:
            had = old.register.mask
            width = max(width, 4 if had is None else len(had))
        self.dcls[reg] = make(None if width >= 4 else tuple(range(width)))

    def outputs(self, value: Value, semantic: str | None, loc: Location, out: list[Output]) -> None:
        if value.type.kind == "struct":
            for fname, ft, fsem in value.type.fields:
                self.outputs(value.fields[fname], fsem, loc, out)
            return
        if semantic is None:
            raise self._error("X4503: output of the entry point has no semantic", loc)
        if value.type.kind == "array":
            for element, sem in zip(value.elements, _array_semantics(semantic, value.type)):
                self.outputs(element, sem, loc, out)
            return
        if self.ctx.target.kind == "vs" and semantic.lower().endswith("_centroid"):
            # a struct both stages share: the pixel side's centroid modifier means nothing to
            # the vertex shader's output (Effekseer's ad_sprite_lit_vs: fxc 9.29 declares
            # `centroid float4 ... : TEXCOORD0` as `dcl_texcoord o0`)
            semantic = semantic[:-len("_centroid")]
        usage, index = split_semantic(semantic)
        usage = _SV_AS_D3D9.get(usage, usage)
        target = self.ctx.target
        if (usage, index) in self.bound:     # d3dx's message table: X4504 (0x1198)
            raise self._error(f"X4504: overlapping output semantics ('{semantic}' is written "
                              "twice)", loc)
        self.bound.add((usage, index))
        if target.kind == "ps":
            if usage == "COLOR":
                if index >= target.rules.registers.get("oC", 1):    # ps_1_x: r0 only
                    raise self._error(f"X4503: invalid pixel shader output semantic "
                                    f"'{semantic}'", loc)
                reg = f"oC{index}"
            elif usage == "DEPTH":
                reg = "oDepth"
            else:
                raise self._error(f"X4503: invalid pixel shader output semantic '{semantic}'", loc)
        elif target.rules.major < 3:
            limit = {"COLOR": "oD", "TEXCOORD": "oT"}.get(usage)
            if usage not in _VS_OUT or \
                    (limit is not None and index >= target.rules.registers.get(limit, 0)):
                raise self._error(f"X4503: invalid vertex shader output semantic '{semantic}'", loc)
            reg = _VS_OUT[usage] + (str(index) if usage in ("COLOR", "TEXCOORD") else "")
        else:
            if usage.lower() not in USAGES:         # vs_3_0: any dcl_ usage
                raise self._error(f"X4503: invalid vertex shader output semantic '{semantic}'", loc)
            reg = f"o{self.next_o}"
            self.next_o += 1
            self.output_dcls.append(declaration("o", self.next_o - 1, usage.lower(), index))
        comps = list(value.comps)
        if usage == "POSITION" and len(comps) < 4:
            comps = comps + [self.ctx.graph.const((1.0,))] * (4 - len(comps))
        out.append(Output(reg, comps, loc))
