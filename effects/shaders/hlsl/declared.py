"""An effect's declarations as the compiler reads them: the keys of the compile cache
(cache.py) and of the whole-file check (check.py), in a module both import (the check runs
inside a compile, and the cache compiles: neither may import the other)."""
from __future__ import annotations

import dataclasses
from typing import Any

from effects.base import caches
from effects.model import Expression, ParamRef, RecordedReads


@caches.memo("shaders.hlsl.field_names", keys="a model class", entry_bytes=256,
             max_bytes=64 * 256)    # unbounded before; the model has a dozen classes
def _field_names(cls: type) -> tuple[str, ...]:
    return tuple(f.name for f in dataclasses.fields(cls))


def declaration(obj: Any, value: bool) -> tuple:
    """A model object (Function, Struct, Parameter) as the compiler reads it: every field,
    so a field added to the model later is in the key too; a parameter's annotations never
    matter and its value only when `value` (a static global's initialiser)."""
    out: list[Any] = [type(obj).__name__]
    for name in _field_names(type(obj)):
        if name == "annotations" or (name == "value" and not value):
            continue
        v = getattr(obj, name)
        if hasattr(v, "tobytes") and hasattr(v, "dtype"):
            v = ("array", v.dtype.str, v.shape, v.tobytes())
        else:
            try:
                hash(v)
            except TypeError:       # a list, a sampler_state: by what they print
                v = ("repr", repr(v))
        out.append(v)
    return tuple(out)


def declarations(effect: Any) -> tuple:
    """Every struct, typedef and function of `effect` as the compile key holds them."""
    return tuple(declaration(obj, value=False) for obj in [*effect.structs, *effect.functions])


def unit_declarations(effect: Any) -> tuple:
    """Every declaration the whole-file check (check.py) reads: the structs, typedefs and
    functions, and every global's declaration (with its initialiser where it is kept as an
    expression: the check evaluates those; a value set at run time is not in it)."""
    base = effect.effect if isinstance(effect, RecordedReads) else effect   # records nothing
    return declarations(effect) + tuple(
        declaration(p, value=isinstance(p.value, (Expression, ParamRef)))
        for p in base.parameters)
