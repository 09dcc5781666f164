"""The whole translation unit type-checked, as fxc did before it optimised anything.

fxc type-checked every function body, every statement and every global initialiser as it
parsed the file, so a name, type or syntax error was reported wherever it was written: in a
function no entry point calls, in a second entry point no technique compiles, in `if (false)
{ ... }`, in the body of a loop that runs no times, after a `return`. The evaluator
(evaluate.py) folds and drops such code, so a compile alone never sees it. Target-dependent
refusals (X3511, X3512, X4014, X4532, semantics, registers, intrinsics a target lacks) fxc gave
only for the code it compiled for a target; they stay the compile's.

DXC's verify tests record fxc's errors in functions their entry never calls (`fxc-error`
notes, e.g. tools/clang/test/HLSL/string.hlsl's get_message, X3038); vkd3d's tests/hlsl/
function.shader_test (native d3dcompiler's verdicts) allows in unused code only what is legal
there: a call to a function that is declared and never defined. That one is refused here
(X3004): the loader keeps no prototypes (docs/guide/hlsl.md, "Where it differs from fxc").

    check_unit(effect)     # None, or the first language error of the file (HlslError)

How: a `Checker` is the evaluator with the values taken out of the decisions. Every function
with a body is walked once, its parameters opaque run-time values of their declared types;
both sides of every `if` are walked whatever the condition, a loop's condition, body and step
once each, every case of a `switch`; nothing after a `return` is dropped; a call to a user
function resolves the overload and checks the arguments (the `out` ones as l-values) but does
not inline the body, whose own walk checks it. The typing rules are the evaluator's own (one
set of rules: expressions.py, arith.py, intrinsics.py, lvalues.py), so the walk refuses
exactly what a compile of that code would refuse for its language. It runs for ps_3_0, the
target with every statement and intrinsic; a target-dependent refusal met on the way ends the
walk of that function without an error (what follows in it is not checked). Every global
initialiser kept as an expression is converted to its global's type.

The answer is kept per effect's declarations (functions, structs, typedefs and globals), so a
file is checked once however many compiles, cards and reloads ask.
"""
from __future__ import annotations

from typing import Any

import lark

from effects.base import caches, limits
from effects.base.errors import EffectError
from effects.model import Effect
from effects.shaders.hlsl.calls import constant_parameters, parameters, return_type
from effects.shaders.hlsl.declared import unit_declarations
from effects.shaders.hlsl.context import Context, FunctionDef, load_context, parameter_type
from effects.shaders.hlsl.evaluate import Evaluator
from effects.shaders.hlsl.expressions import initializer_text, uniform_value
from effects.shaders.hlsl.lvalues import store
from effects.shaders.hlsl.parse import Origin, parse
from effects.shaders.hlsl.switch import _cases, _selector
from effects.shaders.hlsl.types import HType
from effects.shaders.hlsl.values import Frame, Loop, Value

CHECK_TARGET = "ps_3_0"     # every statement (discard) and intrinsic (ddx, tex2Dlod) of HLSL 9
_OPAQUE = "<{}>"            # an opaque value's register name: never a parameter's


class Checker(Evaluator):
    """The evaluator walking every statement once, its values never deciding what is walked."""

    # an index out of bounds is an error only where written as a number (lvalues.const_index):
    # one the walk folds (a counter's first value, a constant in a dropped branch) is fxc's
    # optimiser's to judge, in the code it compiled
    literal_bounds_only = True

    def dead(self) -> bool:
        return False         # the statements after a return or a break are checked too

    def active(self, local: bool = False) -> Any:
        return None          # every write unconditional: no value decides anything here

    def _if(self, tree: Any, cond_tree: Any, then: Any, other: Any) -> None:
        self.condition(cond_tree)
        self.scoped(then)
        if other is not None:
            self.scoped(other)

    def s_for_stmt(self, tree: lark.Tree) -> None:
        _attrs, _tok, init, cond, step, body = tree.children
        self.scopes.append({})
        try:
            if init is not None:
                for child in init.children:
                    if child is None:
                        continue
                    if child.data == "var_decl":
                        self.s_var_decl(child)
                    else:
                        for e in child.children:
                            self.expr(e)
            self._loop(tree, cond, body, step, test_first=True)
        finally:
            # the init's declarations outlive the loop, as fxc scoped them (evaluate.py's
            # s_for_stmt): a later `for (i = 0; ...)` or a read of `i` after it is no error
            self.scopes[-2].update(self.scopes.pop())

    def _loop(self, tree: Any, cond: Any, body: Any, step: Any, test_first: bool,
              why: str | None = None, own: frozenset[int] = frozenset()) -> None:
        self.loops.append(Loop())
        try:
            if cond is not None:
                self.condition(cond, "loop")
            self.scoped(body)
            self.run_step(step, own)
        finally:
            self.loops.pop()

    def s_switch_stmt(self, tree: lark.Tree) -> None:
        _attrs, _keyword, selector_tree, *items = tree.children
        cases = _cases(self, items, tree)        # switch.py's checks, before anything runs
        _selector(self, selector_tree)
        self.loops.append(Loop(switch=True))
        self.scopes.append({})                   # the body is one scope, as C's
        try:
            for case in cases:
                for stmt in case.statements:
                    self.stmt(stmt)
        finally:
            self.scopes.pop()
            self.loops.pop()

    def call_user(self, fdef: FunctionDef, args: list[Value], arg_trees: list[Any],
                  where: Any) -> Value:
        """What inlining checks of a call (calls.inline_call), without the body: each `in`
        argument converts to its parameter, each `out`/`inout` one is an l-value the
        parameter's type converts back to; the value is an opaque one of the return type."""
        for k, (name, t, direction, default, _sem) in enumerate(parameters(self, fdef)):
            loc = self.at(arg_trees[k]) if k < len(arg_trees) else fdef.origin.at(default)
            if k < len(args) and direction != "out":
                self.a.convert(args[k], t, loc)
            if direction in ("out", "inout") and k < len(arg_trees):
                result = opaque(self, name, t)
                store(self, arg_trees[k], lambda current, result=result, loc=loc:
                      self.a.convert(result, current.type, loc))
        rtype = return_type(self.ctx, fdef)
        return opaque(self, fdef.name, rtype) if rtype.kind != "void" else Value(rtype)


def opaque(ev: Evaluator, name: str, t: HType) -> Value:
    """A value of type `t` known only at run time (a parameter's, a call's): constant
    registers of a name no parameter has; a sampler named so too."""
    label = _OPAQUE.format(name)
    if t.kind == "sampler":
        return Value(t, sampler=label)
    if t.kind == "array" and t.element is not None and t.element.kind == "sampler":
        return Value(t, elements=[Value(t.element, sampler=f"{label}[{k}]")
                                  for k in range(t.length)])
    return uniform_value(ev, label, t, 0)


def _has_body(fdef: FunctionDef) -> bool:
    last = fdef.tree.children[-1]
    return isinstance(last, lark.Tree) and last.data == "block"


def _check_function(ctx: Context, fdef: FunctionDef) -> None:
    ev = Checker(ctx, fdef.origin)
    ev.frames.append(Frame(return_type(ctx, fdef)))
    fixed = constant_parameters(fdef)
    for name, t, _direction, default, _sem in parameters(ev, fdef):
        if default is not None:              # a default value converts to its parameter
            ev.a.convert(ev.expr(default), t, ev.at(default))
        ev.declare(name, t, opaque(ev, name, t), const=name in fixed)
    ev.block(fdef.tree.children[-1])


def _check_initializers(ctx: Context) -> None:
    """Every global's initialiser kept as an expression (the loader reads literal ones),
    converted to the global's type as a local's would be: fxc's X3017 for a string into a
    bool, a list of the wrong count (DXC's tests, tools/clang/test/HLSL/string.hlsl)."""
    for param in ctx.effect.parameters:
        init = initializer_text(param)
        if init is None:
            continue
        origin = Origin(init.location, init.text)
        tree = parse(init.text, "initializer", origin, ctx.type_names)
        Checker(ctx, origin).initial(tree, parameter_type(ctx, param))


def _first_error(ctx: Context) -> EffectError | None:
    """The first language error, by place in the file, of the functions' bodies and the
    globals' initialisers (each walk stops at its first error, as the rest of it would be
    checked against a wrong state)."""
    found: list[EffectError] = []
    walks = [(lambda f=f: _check_function(ctx, f)) for fdefs in ctx.functions.values()
             for f in fdefs if _has_body(f)]
    walks.append(lambda: _check_initializers(ctx))
    for walk in walks:
        try:
            walk()
        except EffectError as err:
            if err.language:
                found.append(err)
            elif ctx.graph.work > ctx.work_cap:
                break            # the budget is spent: the rest stays unchecked (hlsl_work)
        except RecursionError:
            continue             # a compile of it reports its nesting (budget.out_of_stack)
    return min(found, key=lambda e: e.location) if found else None


# the effect's declarations (and the compiler's limits) -> the first language error, or None
_CHECKED = caches.declare("shaders.hlsl.unit_checks", keys="every struct, typedef, function "
                          "and global declaration of an effect, the compiler's limits",
                          entry_bytes=2048, max_bytes=1024 * 2048)


def check_unit(effect: Effect, unit: tuple | None = None) -> EffectError | None:
    """The first language error of `effect`'s HLSL (its declarations' own, load_context's,
    or one the walk finds), or None. `unit`: the effect's declarations as the compile cache
    keys them (declared.unit_declarations), when the caller has them."""
    key = (unit if unit is not None else unit_declarations(effect)) + \
        tuple(limits.get(name) for name in ("hlsl_nesting", "hlsl_work", "literal_digits"))
    hit = _CHECKED.get(key)
    if hit is not None:
        return hit[0]
    try:
        ctx = load_context(effect, CHECK_TARGET)
        error = _first_error(ctx)
    except EffectError as err:
        error = err if err.language else None
    _CHECKED.put(key, (error,))
    return error
