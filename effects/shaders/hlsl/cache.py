"""The compile cache: one compile per distinct input, across techniques, passes, cards,
effects and reloads.

A `compile ps_2_0 f(args)` state compiles to the same shader wherever it stands, for whichever
card validates it, as long as what the compiler reads is the same. The key is exactly that:
the target, the entry and its compile arguments, and every declaration the entry can reach —
the functions (all overloads), structs, typedefs and globals named anywhere in the text of what
is reached, transitively, each with its full text, declaration and location (the shader's
instructions and warnings are located in them). A name is taken as reached when it appears in
the text at all (a local that shadows a global reaches the global too): a superset, so the key
never misses a dependency, and an edit elsewhere in the file (another function, an unrelated
global, a technique) keeps the entry. Uniform values are not in the key (the shader reads them
from constant registers at draw time); static globals' values are (they fold into the code).

One thing reaches further: as fxc type-checked the whole file, a function or struct that does
not parse or resolve, or a language error anywhere in a function body or a global's
initialiser (check.py), fails every compile of the effect, reached or not. So the key also
says whether all of them load and check, and when they do not, holds all of them (and every
global's declaration).

Errors are cached too, keyed with the `compile` state's location besides (an unknown entry
point or a bad argument is reported there). Bounded by bytes: the least recently used entry
goes first.
"""
from __future__ import annotations

import re
from typing import Any, Callable

from effects.base import caches, limits
from effects.base.errors import EffectError
from effects.model import CompileShader, Effect, RecordedReads
from effects.shaders.hlsl.declared import declaration as _declaration, declarations, \
    unit_declarations

CACHE_BYTES = 64 << 20
_COMPILER_LIMITS = ("hlsl_nesting", "hlsl_components", "hlsl_work", "literal_digits")
_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def entry_bytes(value: Any) -> int:
    """About what a cached compile holds: a CompiledShader keeps ~65 bytes per character of its
    assembly (tracemalloc: 827 KiB for the 618-slot, 12.6k-character shader of a 150-line
    function; 88 KiB for wood.fx's ps_2_0 one), an error a few KiB."""
    return 4096 + 72 * len(getattr(value, "text", ""))


# key -> CompiledShader | EffectError, bounded by what they hold (64 MiB: ~700 shaders the size
# of wood.fx's, ~75 of 150-line functions)
CACHE = caches.declare(
    "shaders.hlsl.compiles", keys="compile_key: target, entry, arguments, every declaration "
    "reached (and whether all load); an error with its compile state's location besides",
    max_bytes=CACHE_BYTES, size_of=entry_bytes)
# every struct, typedef, function and global of an effect -> whether they all parse, resolve
# and pass the whole-file check (the key's tuples share the model's texts: an entry is the
# tuple and a bool)
_LOADS = caches.declare("shaders.hlsl.declaration_loads", keys="every struct, typedef, global and "
                        "function of an effect as the key holds them", entry_bytes=1024,
                        max_bytes=1024 * 1024)


# a set of a function's identifiers: ~2 KB for a 300-character function
@caches.memo("shaders.hlsl.identifiers", keys="a declaration's text", entry_bytes=2048,
             max_bytes=4096 * 2048)
def _names(text: str) -> frozenset[str]:
    """Every identifier in `text` (kept per text: the same function is keyed once per card)."""
    return frozenset(_IDENTIFIER.findall(text))


def compile_key(effect: Any, value: CompileShader) -> tuple:
    """What the compile of `value` in `effect` depends on (see the module docstring).
    Parameters are looked up through `effect.parameter`, so a recording view (lowering's)
    learns which globals the shader depends on.

    Kept per effect and compile state (validation asks once per card, the same question): a
    kept key is used again while the effect's path, function and struct lists are the ones it
    was made from and every name its walk looked up finds the same parameter with the same
    declaration; the lookups are made again, so a recording view records the same reads."""
    base = effect.effect if isinstance(effect, RecordedReads) else effect
    memo = base._compile_keys
    held = memo.get(value)
    if held is not None and held.holds(effect):
        return held.key
    seen: list[tuple[str, Any, tuple | None]] = []
    key = _compile_key(effect, value, seen)
    if len(memo) >= _MEMO_SIZE:     # a viewer editing: keep a few
        memo.clear()
    memo[value] = _KeptKey(effect, seen, key)
    return key


_MEMO_SIZE = 1024    # kept keys per effect (Effect._compile_keys)


class _KeptKey:
    """A compile key with what it was made from: the effect's path, function and struct lists,
    and every parameter lookup of the walk (name, what it found, its part of the key)."""

    __slots__ = ("path", "functions", "structs", "counts", "seen", "key")

    def __init__(self, effect: Any, seen: list, key: tuple) -> None:
        self.path, self.functions, self.structs = effect.path, effect.functions, effect.structs
        self.counts = (len(effect.functions), len(effect.structs))
        self.seen, self.key = seen, key

    def holds(self, effect: Any) -> bool:
        # Functions and structs are made by the loader and not edited in place (an edit is a
        # reload, a new effect): the same lists of the same length hold the same declarations.
        # Parameters are (a runtime sets values and texture types): each is checked again.
        if effect.path != self.path or effect.functions is not self.functions \
                or effect.structs is not self.structs \
                or (len(self.functions), len(self.structs)) != self.counts:
            return False
        if not isinstance(effect, Effect):   # a recording view: every lookup made again
            for name, param, part in self.seen:
                now = effect.parameter(name)
                if now is not param or (now is not None and _parameter_part(now) != part):
                    return False
            return True
        # A plain effect: a name its index does not hold is what `parameter` answers None for
        # (most of the names are a function's locals and intrinsics), so only the found ones
        # are asked; the index is read again after each, as `parameter` may rebuild it.
        by_name = effect._index().by_name
        for name, param, part in self.seen:
            if param is None:
                if by_name.get(name) is not None:
                    return False
                continue
            now = effect.parameter(name)
            if now is not param or _parameter_part(now) != part:
                return False
            by_name = effect._index().by_name
        return True


def _parameter_part(param: Any) -> tuple:
    """A parameter as the key holds it (a static global with its value)."""
    return _declaration(param, value="static" in param.storage)


def _compile_key(effect: Any, value: CompileShader, seen: list) -> tuple:
    """The key, walking from the entry; every parameter lookup is appended to `seen`."""
    return key_parts(effect, value, seen) + (_all_load(effect),)


def key_parts(effect: Any, value: CompileShader, seen: list) -> tuple:
    """The key without its last part (whether every declaration loads, which parses them)."""
    functions: dict[str, list[Any]] = {}
    for f in effect.functions:
        functions.setdefault(f.name, []).append(f)
    structs: dict[str, list[Any]] = {}
    for s in effect.structs:
        structs.setdefault(s.name, []).append(s)
    parts: list[tuple] = []
    done: set[str] = set()
    todo = [value.function]
    for arg in value.args:
        todo.extend(_names(arg))
    while todo:
        name = todo.pop()
        if name in done:
            continue
        done.add(name)
        for obj in functions.get(name, []) + structs.get(name, []):
            parts.append(_declaration(obj, value=False))
            todo.extend(_names(obj.source))
        param = effect.parameter(name)
        part = None if param is None else _parameter_part(param)
        seen.append((name, param, part))
        if param is not None:
            static = "static" in param.storage
            parts.append(part)
            if param.type.struct:
                todo.append(param.type.base)
            text = getattr(param.value, "text", None)
            if static and isinstance(text, str):     # an initialiser kept as an expression
                todo.extend(_names(text))
    where = value.location if value.args else None   # arguments are located at the state
    return (effect.path, value.profile.lower(), value.function, value.args, where, tuple(parts))


def _all_load(effect: Any) -> tuple:
    """() when every struct, typedef and function of `effect` parses and resolves and the
    whole file passes the check fxc made of it (check.check_unit: every function body and
    global initialiser, called or not; kept by their texts); else all of them, since the
    error comes from one."""
    every = unit_declarations(effect)
    ok = _LOADS.get(every)
    if ok is None:
        from effects.shaders.hlsl.check import check_unit   # the HLSL front end: here only
        ok = check_unit(effect, every) is None
        _LOADS.put(every, ok)
    return () if ok else every


def cached_compile(effect: Any, value: CompileShader, compile: Callable[[], Any],
                   error_type: type[Exception]) -> Any:
    """`compile()`'s shader for `value`, from the cache when the key was compiled before;
    a cached error is raised again. Where the on-disk store is enabled (store.py: the command
    line), a shader stored by an earlier process for the same inputs is used first, found by
    a key that needs no parse of the effect's declarations."""
    from effects.base import disk_store
    from effects.shaders.hlsl import store
    stored = store.key(key_parts(effect, value, []), unit_declarations(effect), value.location) \
        if disk_store.enabled() else None
    if stored is not None:
        hit = _STORED.get(stored)
        if hit is None:
            hit = store.load(stored)
            if hit is not None:
                _STORED.put(stored, hit)
        if hit is not None:
            if isinstance(hit, error_type):
                raise hit
            return hit
    # the limits the compiler reads: a compile refused at one limit is tried again when the
    # host raises it (the on-disk key above holds every limit already)
    key = compile_key(effect, value) + tuple(limits.get(name) for name in _COMPILER_LIMITS)
    hit = CACHE.get(key)
    if hit is None:
        hit = CACHE.get(key + (value.location,))
    if hit is None:
        try:
            hit = compile()
            CACHE.put(key, hit)
        except error_type as err:
            hit = err
            CACHE.put(key + (value.location,), err)
    if stored is not None:
        _STORED.put(stored, hit)
        store.save(stored, hit)
    if isinstance(hit, error_type):
        raise hit
    return hit


# on-disk store key -> what it names, for the length of the process (a stored shader is read
# once, not once per card)
_STORED = caches.declare("shaders.hlsl.stored", keys="the on-disk store's entry name "
                         "(store.key)", max_bytes=CACHE_BYTES, size_of=entry_bytes)


def compile_state(effect: Effect, value: CompileShader) -> Any:
    """The shader (a shader.CompiledShader) of a `compile` state, compiled once per distinct
    input."""
    def compile() -> Any:
        from effects.shaders.hlsl import compiler
        return compiler.compile_shader(effect, value.function, value.profile, value.args,
                                       value.location)
    return cached_compile(effect, value, compile, EffectError)


def clear() -> None:
    """Forget every compile (tests; a host that wants the memory back)."""
    CACHE.clear()
    _LOADS.clear()
    _STORED.clear()
