"""The typed front end: evaluates the entry function symbolically over the DAG.

Evaluating, rather than translating, gives fxc's passes for free: every call is inlined
(arguments bound by value, `out`/`inout` copied back), a loop is unrolled by running it until
its condition is a compile-time false (X3511 after 1024 iterations), and an `if` on a value
not known at compile time runs both branches under a predicate so that every assignment
becomes a select (flattening: `cmp`/`lrp`); a `switch` is one such `if` per case (switch.py).
`return`, `break`, `continue` and `discard` under such a predicate set their own predicates.
Real flow control is generated where the target has it: a `for` loop counted by an int
uniform becomes `rep i#` (loops.py, with break_comp for a break), an `if` on a uniform bool
`if b#` and a `[branch] if` `if_comp` (branches.py); every other `if` on a run-time value is
flattened.
"""
from __future__ import annotations

from typing import Any

import lark

from effects.base.errors import Location
from effects.shaders.hlsl.arith import Arith
from effects.shaders.hlsl.budget import OverBudget, check, enter_level, leave_level, spend
from effects.shaders.hlsl.calls import inline_call
from effects.shaders.hlsl.expressions import _leaves as leaves, evaluate_expr
from effects.shaders.hlsl.context import (Context, FunctionDef, array_of, resolve_type,
                                          struct_type)
from effects.shaders.hlsl.dag import Operand, complement_of
from effects.shaders.hlsl.branches import (bool_register, bool_uniform, comparison,
                                            condition_error, real_if)
from effects.shaders.hlsl.flowrules import DYNAMIC_TARGETS, NotReal, TargetFlow
from effects.shaders.hlsl.loops import bound_of, has_attribute, real_loop
from effects.shaders.hlsl.parse import Origin
from effects.shaders.hlsl.switch import NO_CODE, switch_statement
from effects.shaders.hlsl.types import HType, scalar
from effects.shaders.hlsl.livefold import fold_assuming_zero
from effects.shaders.hlsl.unroll import never_ends
from effects.shaders.hlsl.values import Frame, Loop, Value, Var, build_value, count_components

MAX_ITERATIONS = 1024
PROBE_AFTER = 8          # most loops end sooner: they never pay for unroll.never_ends
# the statements that hold others (one level of hlsl_nesting each: budget.py)
_COMPOUND = frozenset(("block", "if_stmt", "if_else", "for_stmt", "while_stmt", "do_stmt"))
_COMPARE_NOW = {"lt": lambda a, b: a < b, "le": lambda a, b: a <= b, "gt": lambda a, b: a > b,
                "ge": lambda a, b: a >= b, "eq": lambda a, b: a == b, "ne": lambda a, b: a != b}
_SWIZZLE = {c: i for i, c in enumerate("xyzw")} | {c: i for i, c in enumerate("rgba")}
# storage a local cannot have: a global's (uniform, extern), and fxc's code for each
_NOT_LOCAL = (("uniform", "X3047"), ("extern", "X3006"))


class Evaluator:
    def __init__(self, ctx: Context, origin: Origin) -> None:
        self.ctx = ctx
        self.g = ctx.graph
        self.origin = origin
        self.a = Arith(ctx, self.error, self.warn)
        self.scopes: list[dict[str, Var]] = [{}]
        self.frames: list[Frame] = []
        self.loops: list[Loop] = []
        self.mask: Operand | None = None       # path predicate (None: always)
        self.outer: Operand | None = None      # an inlined call's: the caller's, at the call
        self.depth = 0
        self.in_expression = 0                 # expression evaluations under way (budget.py)
        # the for-init variables of an unrolled loop while its step runs (lvalues.store):
        # stepped whatever the predicate, so the count stays a constant
        self.stepping: frozenset[int] = frozenset()

    def spawn(self, origin: Origin) -> "Evaluator":
        """An evaluator for another text (a called function, a compile argument)."""
        return Evaluator(self.ctx, origin)

    def const_number(self, tree: Any) -> float:
        v = self.expr(tree)
        values = v.const_values() if v.type.numeric else None
        if values is None:
            raise self.error("X3013: expression is not a compile-time constant", tree)
        return values[0]

    def array_of(self, t: HType, dims: Any, subject: str = "this variable") -> HType:
        """`t` with the array sizes `dims` (constant expressions), checked (context.array_of)."""
        if any(d is None for d in dims.children):
            raise self.error(f"an array of implicit size ('[]') needs an initializer list "
                             f"{NO_CODE}", dims, language=True)
        return array_of(t, [self._dimension(d) for d in dims.children],
                        lambda m: self.error(m, dims), subject)

    def _dimension(self, tree: Any) -> float:
        """An array size: an expression that folds to a number (d3dx's X3058 text else)."""
        v = self.expr(tree)
        values = v.const_values() if v.type.numeric and v.type.size == 1 else None
        if values is None:
            raise self.error("X3058: array dimensions must be literal scalar expressions", tree)
        return values[0]

    def run_step(self, step: Any, own: frozenset[int]) -> None:
        """A `for` loop's step expressions (None: none), its counters `own` written as an
        unrolled loop's counter (lvalues: unpredicated), not as a conditional write."""
        if step is None:
            return
        outer, self.stepping = self.stepping, own
        try:
            for e in step.children:
                self.expr(e)
        finally:
            self.stepping = outer

    # -- diagnostics ------------------------------------------------------------------------
    def at(self, item: Any) -> Location:
        return item if isinstance(item, Location) else self.origin.at(item)

    def error(self, message: str, item: Any, language: bool | None = None) -> Exception:
        return self.origin.error(message, self.at(item), language)

    def warn(self, message: str, loc: Location) -> None:
        w = self.origin.warning(message, loc)
        if w not in self.ctx.warnings:
            self.ctx.warnings.append(w)

    # -- predicates -------------------------------------------------------------------------
    def _and(self, p: Operand | None, q: Operand | None) -> Operand | None:
        if p is None:
            return q
        if q is None:
            return p
        if _complements(p, q) or _complements(q, p):
            # a predicate is 0 or 1: p and not p is never (after `if (true) break;` under a
            # case's or an if's predicate, the rest of its statements are not reached)
            return self.g.const((0.0,))
        return self.g.op("mul", [p, q], 1)

    def _or(self, p: Operand | None, q: Operand | None) -> Operand:
        if p is None:
            return q  # type: ignore[return-value]
        if q is None:
            return p
        if q.node.op == "mul" and not q.negate and q.swizzle == (0,):
            # p or (a and not p) is p or a: a return or break after an earlier one runs under
            # 'not returned', and the flag it adds need not say so again (a later select on
            # 'not returned' then unfolds into one cmp per return, arith._unfold_predicate)
            a, b = q.node.args
            if _complements(p, b):
                return self.g.op("max", [p, a], 1)
            if _complements(p, a):
                return self.g.op("max", [p, b], 1)
        return self.g.op("max", [p, q], 1)

    def _not(self, p: Operand | None) -> Operand | None:
        if p is None:
            return None
        return self.g.op("add", [self.g.const((1.0,)), p.neg()], 1)

    def active(self, local: bool = False) -> Operand | None:
        """The predicate under which a statement runs now (None: always). For a write to a
        local of this function (`local`, lvalues.store) without the caller's predicate and
        the function's 'returned': no one reads the local where those are false (the value
        returned and the out parameters are taken under them), and a while loop's counter
        stays a constant in a call under a run-time condition or after a return in it."""
        p = self.mask if local else self._and(self.outer, self.mask)
        if not local and self.frames and self.frames[-1].returned is not None:
            p = self._and(p, self._not(self.frames[-1].returned))
        if self.loops:
            loop = self.loops[-1]
            p = self._and(p, self._not(loop.broken))
            p = self._and(p, self._not(loop.continued))
        if p is not None and p.const_values() == (1.0,):
            return None
        return p

    def dead(self) -> bool:
        p = self.active()
        return p is not None and p.const_values() == (0.0,)

    def merge(self, old: Value, new: Value, p: Operand | None, loc: Location) -> Value:
        if p is None:
            return new
        if new.type.kind in ("struct", "array"):      # a select per component
            spend(self, new.type.components, loc)
        return self._merge(old, new, p, loc)

    def _merge(self, old: Value, new: Value, p: Operand, loc: Location) -> Value:
        if new.type.numeric:
            return Value(new.type, self.a.select([p], new.comps, old.comps, loc,
                                                 unfold=not self.loops))
        if new.type.kind == "struct":
            return Value(new.type, fields={k: self._merge(old.fields[k], new.fields[k], p, loc)
                                           for k in new.fields})
        if new.type.kind == "array":
            return Value(new.type, elements=[self._merge(o, n, p, loc)
                                             for o, n in zip(old.elements, new.elements)])
        return new

    # -- variables --------------------------------------------------------------------------
    def lookup(self, name: str) -> Var | None:
        for scope in reversed(self.scopes):
            if name in scope:
                return scope[name]
        return None

    def declare(self, name: str, t: HType, value: Value, const: bool = False,
                where: Any = None) -> None:
        """`name` in the innermost scope; `where` (its declarator) when a second declaration
        of the name in that scope is fxc's X3003 (d3dx's "redefinition of '%s'")."""
        scope = self.scopes[-1]
        if where is not None and name in scope:
            raise self.error(f"X3003: redefinition of '{name}'", where)
        if where is not None and len(self.scopes) == 2 and self.frames and name in self.scopes[0]:
            # a local of a function's body named as one of its parameters (scope 0): fxc's
            # X3036, "redefinition of the specified formal parameter" (its error list)
            raise self.error(f"X3036: '{name}': formal parameter redefinition", where)
        scope[name] = Var(t, value, const)

    def zero(self, t: HType) -> Value:
        if t.numeric:
            return Value(t, [self.g.const((0.0,))] * t.size)
        if t.kind == "struct":
            return Value(t, fields={n: self.zero(ft) for n, ft, _ in t.fields})
        if t.kind == "array":
            return Value(t, elements=[self.zero(t.element) for _ in range(t.length)])  # type: ignore[arg-type]
        return Value(t)

    # -- statements -------------------------------------------------------------------------
    def block(self, tree: lark.Tree) -> None:
        self.scopes.append({})
        try:
            for stmt in tree.children:
                if self.dead():
                    break
                self.stmt(stmt)
        finally:
            self.scopes.pop()

    def stmt(self, tree: Any) -> None:
        kind = tree.data
        handler = getattr(self, f"s_{kind}", None)
        if handler is None:
            raise self.error(f"X3000: unsupported statement '{kind}'", tree)
        check(self, tree)
        if kind not in _COMPOUND:
            handler(tree)
            return
        enter_level(self, tree)              # a statement holding others: one more level
        try:
            handler(tree)
        finally:
            leave_level(self)

    def s_block(self, tree: lark.Tree) -> None:
        self.block(tree)

    def s_empty(self, tree: lark.Tree) -> None:
        pass

    def s_expr_stmt(self, tree: lark.Tree) -> None:
        for e in tree.children:              # `a = 1, b = 2;`: C's comma, left to right
            self.expr(e)

    def s_struct_stmt(self, tree: lark.Tree) -> None:
        """`struct L { ... } a, b = { ... };` in a function: its type for the rest of the
        text (as a local typedef is), then its variables declared as `L a, b = ...;` are."""
        name_tok, *members, decls = tree.children
        if name_tok is None:                 # `struct { ... } s;`: a type only s has
            line, column = self.at(tree).line, self.at(tree).column
            name_tok = lark.Token("NAME", f"(anonymous struct at {line}:{column})")
        t = struct_type(self.ctx, lark.Tree("struct_def", [name_tok, *members]), self.origin)
        self.ctx.typedefs[str(name_tok)] = t
        if decls.children:
            self.s_var_decl(lark.Tree("var_decl", [None, lark.Tree("user_type", [name_tok]),
                                                   *decls.children]))

    def s_var_decl(self, tree: lark.Tree) -> None:
        mods, spec, *decls = tree.children
        base = resolve_type(self.ctx, spec, self.origin, mods)
        is_const = mods is not None and any(str(m) == "const" for m in mods.children)
        for d in decls:
            name, dims, _sem, init = d.children
            if base.kind == "void":      # ReShade's text for fxc's X3038
                raise self.error(f"X3038: '{name}': variables cannot be void", name)
            if is_const and init is None:     # fxc's text, as DXC's tests record it
                raise self.error(f"X3012: '{name}': missing initial value", name)
            for word, code in _NOT_LOCAL:       # ReShade's texts for fxc's codes
                if mods is not None and any(str(m) == word for m in mods.children):
                    raise self.error(f"{code}: '{name}': local variables cannot be declared "
                                     f"'{word}'", name)
            if dims.children and dims.children[0] is None and isinstance(init, lark.Tree) \
                    and init.data == "init_list":
                t, value = self.implicit_array(base, dims, init)
                spend(self, t.components, d)         # the storage it is given
            else:
                t = self.array_of(base, dims, f"'{name}'")
                spend(self, t.components, d)
                value = self.zero(t) if init is None else self.initial(init, t)
            self.declare(str(name), t, value, is_const, where=name)

    def implicit_array(self, base: HType, dims: Any, init: lark.Tree) -> tuple[HType, Value]:
        """`T a[] = { ... }`: as many elements as the flattened list fills (fxc's rule: the
        list's numbers, braces ignored, over the numbers of one element)."""
        element = self.array_of(base, lark.Tree("dims", dims.children[1:]))
        comps = self.flatten_list(init)
        per = count_components(element)
        if not comps or len(comps) % per:
            raise self.error(f"X3017: initializer has {len(comps)} values, an array of "
                             f"'{element}' needs a multiple of {per}", init)
        t = array_of(element, [len(comps) // per], lambda m: self.error(m, init))
        return t, self.from_list(comps, t, init)

    def initial(self, init: Any, t: HType) -> Value:
        if isinstance(init, lark.Tree) and init.data == "init_list":
            return self.from_list(self.flatten_list(init), t, init)
        return self.a.convert(self.expr(init), t, self.at(init))

    def flatten_list(self, init: Any) -> list[Operand]:
        """The numbers of an initialiser, `{ {1, 2}, x, {{3}} }` flattened in order (braces
        walked with an explicit stack: their nesting takes no Python stack)."""
        out: list[Operand] = []
        stack = [init]
        while stack:
            item = stack.pop()
            if item is None:
                continue
            if isinstance(item, lark.Tree) and item.data == "init_list":
                stack.extend(reversed(item.children))
                continue
            v = self.expr(item)
            if v.type.numeric:
                out.extend(v.comps)
            elif v.type.kind in ("struct", "array"):      # its numbers in declaration order
                out.extend(c for c, _ in leaves(v))
        return out

    def from_list(self, comps: list[Operand], t: HType, where: Any) -> Value:
        need = count_components(t)
        if len(comps) == 1 and need > 1 and t.numeric:
            comps = comps * need
        if len(comps) != need:
            raise self.error(f"X3017: initializer has {len(comps)} values, '{t}' needs {need}", where)
        return build_value(t, comps)

    def s_typedef_decl(self, tree: lark.Tree) -> None:
        _, mods, spec, *declared = tree.children
        base = resolve_type(self.ctx, spec, self.origin, mods)
        for name, dims in zip(declared[::2], declared[1::2]):     # `typedef T a, b[2];`
            self.ctx.typedefs[str(name)] = self.array_of(base, dims, f"'{name}'")

    def s_if_stmt(self, tree: lark.Tree) -> None:
        self._if(tree, tree.children[2], tree.children[3], None)

    def s_if_else(self, tree: lark.Tree) -> None:
        self._if(tree, tree.children[2], tree.children[3], tree.children[5])

    def _if(self, tree: Any, cond_tree: Any, then: Any, other: Any) -> None:
        attrs = tree.children[0]
        flow = TargetFlow.of(self.ctx.target)
        branch = has_attribute(attrs, "branch")
        if not has_attribute(attrs, "flatten"):
            # a bool uniform: a static branch where the target has them (branches.py)
            b = bool_uniform(self, cond_tree)
            if b is not None and flow.static:
                name, component, negated = b
                sides = (other, then) if negated else (then, other)
                try:
                    real_if(self, tree, ("bool", [bool_register(self, name, component)]), *sides,
                            "static")
                    return
                except NotReal as err:
                    if branch:
                        raise self.error(f"cannot [branch] on '{name}' here: {err}",
                                         tree) from None
            elif branch:
                if not flow.dynamic:
                    raise self.error(f"[branch] needs dynamic flow control (if_comp), "
                                     f"which {self.ctx.target.name} does not have ("
                                     f"{DYNAMIC_TARGETS} do); use [flatten] or no attribute "
                                     "(no X code: fxc's wording for this was not found)",
                                     tree)
                test, args = comparison(self, cond_tree)
                known = [a.const_values() for a in args]
                if all(k is not None for k in known):
                    taken = _COMPARE_NOW[test](known[0][0], known[1][0])   # type: ignore[index]
                    branch_tree = then if taken else other
                    if branch_tree is not None:
                        self.scoped(branch_tree)
                    return
                try:
                    real_if(self, tree, (test, args), then, other, "dynamic")
                    return
                except NotReal as err:
                    raise self.error(f"cannot [branch] here: {err}", tree) from None
        cond = self.condition(cond_tree)
        value = cond.const_values()
        if value is not None:
            branch = then if value[0] else other
            if branch is not None:
                self.scoped(branch)
            return
        saved = self.mask
        self.mask = self._and(saved, cond)
        self.scoped(then)
        if other is not None:
            self.mask = self._and(saved, self._not(cond))
            self.scoped(other)
        self.mask = saved

    def scoped(self, stmt: Any) -> None:
        self.scopes.append({})
        try:
            self.stmt(stmt)
        finally:
            self.scopes.pop()

    def condition(self, tree: Any, statement: str = "if") -> Operand:
        """The 0/1 truth of an `if`'s or a loop's (`statement` "loop") condition, a scalar."""
        v = self.expr(tree)
        if not v.type.numeric or v.type.size > 1:
            raise self.error(condition_error(statement, v.type), tree)
        return self.a.to_bool(v, self.at(tree)).comps[0]

    def s_for_stmt(self, tree: lark.Tree) -> None:
        """A `for` loop. Its init's declarations outlive it, in the enclosing scope: fxc's
        scoping (d3dx9), which compiled `for (int i = 0; ...) {} for (i = 0; ...)` and gave
        a second `for (int i ...)` in one scope warning X3078 (its text, as real effects'
        `#pragma warning(disable: 3078)` comments quote it) instead of a redefinition."""
        attrs, _tok, init, cond, step, body = tree.children
        self.scopes.append({})
        try:
            if init is not None:
                for child in init.children:
                    if child is None:
                        continue
                    if child.data == "var_decl":
                        for d in child.children[2:]:
                            if str(d.children[0]) in self.scopes[-2]:
                                self.warn(f"X3078: '{d.children[0]}': loop control variable "
                                          "conflicts with a previous declaration in the outer "
                                          "scope; most recent declaration will be used",
                                          self.at(d.children[0]))
                        self.s_var_decl(child)
                    else:
                        for e in child.children:
                            self.expr(e)
            match = None if has_attribute(attrs, "unroll") else \
                bound_of(self, tree, cond, step, attrs)
            why = None
            if match is not None:
                target = self.ctx.target
                if not TargetFlow.of(target).static:
                    why = (f"{match.why()}, and {target.name} has no loops (rep needs vs_2_0, "
                           "ps_2_x or ps_3_0)")
                else:
                    try:
                        real_loop(self, tree, body, step, match)
                        return
                    except NotReal as err:
                        why = f"{match.why()}, and it cannot be a rep: {err}"
                if match.param is None:
                    # literal bounds unroll (fxc's default for them); [loop] is only a request
                    if has_attribute(attrs, "loop"):
                        self.warn(f"[loop] not kept: {why}; the loop is unrolled", self.at(tree))
                    why = None
            self._loop(tree, cond, body, step, test_first=True, why=why,
                       own=frozenset(id(v) for v in self.scopes[-1].values()))
        finally:
            self.scopes[-2].update(self.scopes.pop())

    def s_while_stmt(self, tree: lark.Tree) -> None:
        self._loop(tree, tree.children[2], tree.children[3], None, test_first=True)

    def s_do_stmt(self, tree: lark.Tree) -> None:
        self._loop(tree, tree.children[4], tree.children[2], None, test_first=False)

    def _loop(self, tree: Any, cond: Any, body: Any, step: Any, test_first: bool,
              why: str | None = None, own: frozenset[int] = frozenset()) -> None:
        """Unroll: run the body until the condition is a compile-time false. The variables
        the for's init declares (`own`) are the loop's, so its step sets them whatever the
        predicate (a pixel that broke, returned or is masked off reads them only under that
        predicate): a counter stays a constant under a run-time break, an enclosing
        flattened if or a real loop's body, and the loop ends. After it, they hold what each
        lane left the loop with (`seen`).

        A loop still running after PROBE_AFTER iterations whose end the body cannot change
        (unroll.py) is run again from its start without its body: one that never ends is
        X3511 then, not after 1,024 runs of the body. A loop of exactly 1,024 iterations
        unrolls (the condition is tested before the count)."""
        start = [(var, var.value) for scope in self.scopes for var in scope.values()]
        # the counters' values per lane, as read after the loop (the for's declarations
        # outlive it): a lane that left the loop keeps the value it left with, though the
        # step went on writing the counter unpredicated
        counters = [var for var, _ in start if id(var) in own]
        # per iteration where lanes had left: (lanes in the loop at its start, the counters
        # before the step, lanes still in it, after the step); made into selects only when
        # the loop ends (not for one that runs into X3511 or the work limit)
        steps: list[tuple[Any, list[Value], Any, list[Value]]] = []
        loop = Loop()
        saved = self.mask
        self.loops.append(loop)
        try:
            for i in range(MAX_ITERATIONS + 1):
                in_loop = self.active()
                if i == PROBE_AFTER:          # a long loop: does it end at all? (unroll.py)
                    never = never_ends(self, tree, cond, body, step, test_first, own,
                                       MAX_ITERATIONS, start)
                    if never is not None:
                        raise self.error(
                            f"X3511: unable to unroll loop: {why}" if why is not None else
                            f"X3511: unable to unroll loop, loop does not appear to terminate "
                            f"in a timely manner ({never})", tree)
                if cond is not None and (test_first or i > 0):
                    c = self.condition(cond, "loop")
                    v = c.const_values()
                    if v is not None and not v[0]:
                        break
                    if v is None and self._ends_where_running(c, loop):
                        break       # every lane still in the loop fails the condition
                    if v is None:
                        # a condition known only at run time: the rest runs under it
                        loop.broken = self._or(loop.broken, self._and(self.active(), self._not(c)))
                        loop.left.append(loop.broken)
                if self.dead():
                    break
                if i == MAX_ITERATIONS:       # the body would run a 1,025th time
                    raise self.error(f"X3511: unable to unroll loop: {why}" if why is not None
                                     else f"X3511: unable to unroll loop, loop does not appear "
                                     f"to terminate in a timely manner ({MAX_ITERATIONS} "
                                     "iterations)", tree)
                loop.continued = None
                try:
                    self.scoped(body)
                except OverBudget:
                    if why is None:
                        raise
                    # a loop that could not be a rep, unrolled until the budget ran out
                    raise self.error(f"X3511: unable to unroll loop: {why}", tree) from None
                loop.continued = None
                if self.dead():
                    break
                p = self.active()
                before = [var.value for var in counters]
                self.run_step(step, own)
                if counters and (in_loop is not None or p is not None):
                    steps.append((in_loop, before, p, [var.value for var in counters]))
        except OverBudget:
            if why is None:
                raise
            # unrolled until the budget ran out in its condition or step (the body's above)
            raise self.error(f"X3511: unable to unroll loop: {why}", tree) from None
        finally:
            self.loops.pop()
            self.mask = saved
        if steps:
            self._counters_as_left(counters, start, steps, tree)

    def _counters_as_left(self, counters: list[Var], start: list[tuple[Var, Value]],
                          steps: list, tree: Any) -> None:
        """Each counter of a finished loop as each lane left it: a lane that broke out keeps
        the value it had then, though the step went on writing the counter unpredicated."""
        initial = {id(var): value for var, value in start}
        loc = self.at(tree)
        seen = [initial[id(var)] for var in counters]
        for in_loop, before, p, after in steps:
            seen = [self.merge(old, value, in_loop, loc) for old, value in zip(seen, before)]
            seen = [self.merge(old, value, p, loc) for old, value in zip(seen, after)]
        for var, value in zip(counters, seen):
            var.value = value

    def _ends_where_running(self, c: Operand, loop: Loop) -> bool:
        """Whether condition `c` is a constant false in the lanes that neither broke out of
        the loop nor returned (livefold.py): the loop ends for every lane still in it."""
        if not loop.left:
            return False
        for p in loop.left[loop.zeroed:]:
            for lane in p.swizzle:
                loop.zero.setdefault(p.node.id, set()).add(lane)
        loop.zeroed = len(loop.left)
        v = fold_assuming_zero(c, loop.zero, loop.known)
        return v is not None and not v[0]

    def s_break_stmt(self, tree: lark.Tree) -> None:
        if not self.loops:
            raise self.error("X3518: break must be inside a loop", tree)
        loop = self.loops[-1]
        loop.broken = self._or(loop.broken, self.active() or self.g.const((1.0,)))
        loop.left.append(loop.broken)

    def s_switch_stmt(self, tree: lark.Tree) -> None:
        switch_statement(self, tree)

    def s_continue_stmt(self, tree: lark.Tree) -> None:
        if not self.loops:
            raise self.error("X3519: continue must be inside a loop", tree)
        loop = self.loops[-1]
        if loop.switch:
            raise self.error(f"continue cannot be used in a switch {NO_CODE}", tree, language=True)
        loop.continued = self._or(loop.continued, self.active() or self.g.const((1.0,)))

    def s_return_stmt(self, tree: lark.Tree) -> None:
        frame = self.frames[-1]
        expr = tree.children[1]
        p = self.active()
        if expr is not None:
            if frame.return_type.kind == "void":
                raise self.error("X3079: void functions cannot return a value", expr)
            v = self.a.convert(self.expr(expr), frame.return_type, self.at(expr))
            frame.retval = v if frame.retval is None else self.merge(frame.retval, v, p, self.at(tree))
        elif frame.return_type.kind != "void":
            raise self.error("X3080: function must return a value", tree)
        frame.returned = self._or(frame.returned, p or self.g.const((1.0,)))
        for loop in self.loops:
            loop.left.append(frame.returned)

    def s_discard_stmt(self, tree: lark.Tree) -> None:
        self.kill([self.g.const((-1.0,))], self.at(tree))

    def kill(self, comps: list[Operand], loc: Location) -> None:
        if self.ctx.target.kind != "ps":
            raise self.error("X3536: discard and clip are pixel-shader only", loc)
        p = self.active()
        if p is not None:
            comps = self.a.select([p], comps, [self.g.const((0.0,))] * len(comps), loc)
        for k in range(0, len(comps), 4):          # a texkill tests one register
            op = self.g.pack(comps[k:k + 4])
            self.ctx.kills.append(self.g.leaf("kill", None, op.width, loc, (op,)))

    # -- expressions live in expressions.py --------------------------------------------------
    def expr(self, tree: Any) -> Value:
        return evaluate_expr(self, tree)

    # -- calls ------------------------------------------------------------------------------
    def call_user(self, fdef: FunctionDef, args: list[Value], arg_trees: list[Any], where: Any) -> Value:
        return inline_call(self, fdef, args, arg_trees, where)


def _numbers(v: Value) -> list[Operand]:
    """A value's numbers in declaration order: an initializer list takes a struct or an array
    as its members' numbers, braces ignored (fxc's flattened initializers)."""
    if v.type.kind == "struct":
        return [c for f in v.fields.values() for c in _numbers(f)]
    if v.type.kind == "array":
        return [c for e in v.elements for c in _numbers(e)]
    return list(v.comps)


def _complements(p: Operand, q: Operand) -> bool:
    """Whether `q` is `Evaluator._not(p)`: 1 - p."""
    c = complement_of(q) if q.swizzle == (0,) else None
    return c is not None and c.sig() == p.sig()


def _block_in_frame(self: Evaluator, body: lark.Tree) -> None:
    """Run a function body: its statements see the parameters (scope 0) and its own locals."""
    self.block(body)


Evaluator.block_in_frame = _block_in_frame  # type: ignore[attr-defined]
