"""Compiled HLSL shaders kept on disk between processes: the command line's compile cache.

The in-memory compile cache (cache.py) lasts one process; every `effects matrix` run compiled
each effect's `compile` states again (~60 ms of its ~0.5 s, plus the HLSL front end's import
and grammar). Entries live in the command line's store (`effects.base.disk_store`: the folder, its
bounds and safety, `EFFECTS_CACHE=off`), enabled for the length of a command.

Correctness: an entry is found by the SHA-256 of everything a compile reads (`key`): the
compile key of cache.py without its "do all declarations load" flag, with every struct,
typedef and function declaration of the effect instead (that flag is made from them); the
`compile` state's location (errors are located there); every resource limit in force
(`effects.base.limits`); and the code doing the compiling (`disk_store.fingerprint`). A value the
key cannot spell exactly (an object it knows no canonical form for) keeps that compile off the
disk.

What an entry holds is data, not code: JSON with the generated assembly, its per-line HLSL
locations, constant/sampler/int/bool register tables, warnings and types, or the error. The
program is made again from the assembly listing by `shader.assemble_generated`, which gives
the records the compiler's writer made (tests/shaders/hlsl/test_hlsl_store.py compares them
field by field), so it is checked by the assembler as any text is. An entry that does not decode is a
miss (and removed). An untrusted effect can only add entries for its own text.
"""
from __future__ import annotations

import dataclasses
from typing import Any

from effects.base import disk_store
from effects.base.disk_store import Unkeyable
from effects.base.errors import EffectError, EffectWarning, Location

FORMAT = 2     # 2: an error keeps its `language` flag


def key(parts: tuple, declarations: tuple, location: Location) -> str | None:
    """The entry name for a compile: `parts` and `declarations` as cache.key_parts and
    cache.declarations give them for the `compile` state at `location`. None when some input
    has no exact spelling (that compile is not stored)."""
    from effects.base import limits
    try:
        path, target, function, args, where, reached = parts
        # the walk finds the reached declarations in an order that follows string hashing,
        # which differs between processes: they are spelled one by one and sorted
        reached_spelled = []
        for part in reached:
            out: list[str] = []
            disk_store.spell(part, out)
            reached_spelled.append("".join(out))
        material = ("effects-compiled-shader", FORMAT, disk_store.fingerprint(),
                    tuple((name, limits.get(name)) for name in sorted(limits.LIMITS)),
                    (path, target, function, args, where), tuple(sorted(reached_spelled)),
                    declarations, location)
        return disk_store.digest(material)
    except Unkeyable:
        return None


# -- entries ------------------------------------------------------------------------------------

def load(name: str) -> Any:
    """The CompiledShader or EffectError stored under `name`, or None."""
    entry = disk_store.read(name)
    if entry is None:
        return None
    try:
        return _decode(entry)
    except Exception:   # not a shader entry this code can use: a miss
        disk_store.discard(name)
        return None


def save(name: str, result: Any) -> None:
    """Store a compile's result (a CompiledShader or EffectError) under `name`, if it can be
    written out exactly; never raises."""
    if not disk_store.enabled():
        return
    try:
        entry = _encode(result)
    except Unkeyable:
        return
    disk_store.write(name, entry)


# -- encoding -----------------------------------------------------------------------------------

_ERRORS = ("HlslError", "EffectError", "AsmError")


def _loc(v: Location | None) -> Any:
    if v is None:
        return None
    if type(v) is not Location:
        raise Unkeyable("not a Location")
    return [v.path, v.line, v.column]


def _unloc(v: Any) -> Location | None:
    if v is None:
        return None
    path, line, column = v
    if type(path) is not str or type(line) is not int or type(column) is not int:
        raise ValueError("bad location")
    return Location(path, line, column)


def _names(d: Any, width: int | None = None) -> dict:
    """{str: int} or {str: (int, ...)} checked."""
    if type(d) is not dict:
        raise ValueError("not a table")
    for k, v in d.items():
        if type(k) is not str:
            raise ValueError("bad name")
        values = v if width is not None else [v]
        if width is not None and (type(v) is not list or len(v) != width):
            raise ValueError("bad entry")
        if any(type(x) is not int for x in values):
            raise ValueError("bad number")
    return {k: tuple(v) for k, v in d.items()} if width is not None else dict(d)


def _htype(t: Any) -> Any:
    from effects.shaders.hlsl.types import HType
    if type(t) is not HType:
        raise Unkeyable("not an HType")
    return {"kind": t.kind, "base": t.base, "rows": t.rows, "cols": t.cols, "name": t.name,
            "fields": [[n, _htype(ft), s] for n, ft, s in t.fields],
            "element": None if t.element is None else _htype(t.element), "length": t.length,
            "row_major": t.row_major}


def _unhtype(d: Any) -> Any:
    from effects.shaders.hlsl.types import HType
    if type(d) is not dict or set(d) != {"kind", "base", "rows", "cols", "name", "fields",
                                         "element", "length", "row_major"}:
        raise ValueError("bad type")
    for k in ("kind", "base", "name"):
        if type(d[k]) is not str:
            raise ValueError("bad type")
    for k in ("rows", "cols", "length"):
        if type(d[k]) is not int:
            raise ValueError("bad type")
    if type(d["row_major"]) is not bool or type(d["fields"]) is not list:
        raise ValueError("bad type")
    fields = []
    for item in d["fields"]:
        n, ft, s = item
        if type(n) is not str or (s is not None and type(s) is not str):
            raise ValueError("bad field")
        fields.append((n, _unhtype(ft), s))
    return HType(d["kind"], d["base"], d["rows"], d["cols"], d["name"], tuple(fields),
                 None if d["element"] is None else _unhtype(d["element"]), d["length"],
                 d["row_major"])


def _encode(result: Any) -> dict:
    from effects.shaders.hlsl.shader import CompiledShader
    if isinstance(result, EffectError):
        cls = type(result).__name__
        if cls not in _ERRORS or type(result).__module__ not in (
                "effects.base.errors", "effects.shaders.hlsl.parse"):
            raise Unkeyable(cls)
        return {"error": cls, "message": result.message,
                "location": _loc(result.location), "source_line": result.source_line,
                "language": bool(result.language)}
    if type(result) is not CompiledShader:
        raise Unkeyable(type(result).__qualname__)
    known = {"function", "target", "text", "program", "constants", "samplers", "lines",
             "warnings", "types", "int_registers", "bool_registers", "preshaders",
             "register_counts"}
    if {f.name for f in dataclasses.fields(CompiledShader)} != known:
        raise Unkeyable("CompiledShader has fields this store does not know")
    for w in result.warnings:
        if type(w) is not EffectWarning:
            raise Unkeyable("a warning of another kind")
    return {
        "function": result.function, "target": result.target, "text": result.text,
        "entry_location": _loc(result.program.location),
        "constants": {k: list(v) for k, v in result.constants.items()},
        "samplers": dict(result.samplers), "lines": [_loc(x) for x in result.lines],
        "warnings": [[w.message, _loc(w.location), w.source_line] for w in result.warnings],
        "types": {k: _htype(t) for k, t in result.types.items()},
        "int_registers": dict(result.int_registers), "bool_registers": dict(result.bool_registers),
        "preshaders": {k: {"width": p.width, "steps": [list(step) for step in p.steps]}
                       for k, p in result.preshaders.items()},
        "register_counts": dict(result.register_counts),
    }


def _decode(d: dict) -> Any:
    """The shader or error of entry `d` (disk_store.read has checked it is this entry's)."""
    if "error" in d:
        cls_name = d["error"]
        if cls_name not in _ERRORS or type(d["message"]) is not str or \
                (d["source_line"] is not None and type(d["source_line"]) is not str) or \
                type(d["language"]) is not bool:
            raise ValueError("bad error")
        if cls_name == "HlslError":
            from effects.shaders.hlsl.parse import HlslError
            return HlslError(d["message"], _unloc(d["location"]), source_line=d["source_line"],
                             language=d["language"])
        import effects.base.errors
        cls = getattr(effects.base.errors, cls_name)
        return cls(d["message"], _unloc(d["location"]), source_line=d["source_line"])
    from effects.shaders.hlsl.shader import CompiledShader, assemble_generated
    function, target, text = d["function"], d["target"], d["text"]
    if type(function) is not str or type(target) is not str or type(text) is not str:
        raise ValueError("bad shader")
    lines = [_unloc(x) for x in d["lines"]]
    warnings = []
    for message, where, source_line in d["warnings"]:
        if type(message) is not str or (source_line is not None and type(source_line) is not str):
            raise ValueError("bad warning")
        warnings.append(EffectWarning(message, _unloc(where), source_line))
    entry_loc = _unloc(d["entry_location"])
    if entry_loc is None:
        raise ValueError("no entry location")
    generated = text.split("\n")[:-1] if text.endswith("\n") else text.split("\n")
    program = assemble_generated(text, target, function, generated, lines, entry_loc)
    return CompiledShader(function, target, text, program, _names(d["constants"], 2),
                          _names(d["samplers"]), lines, warnings,
                          {k: _unhtype(t) for k, t in _checked_dict(d["types"]).items()},
                          _names(d["int_registers"]), _names(d["bool_registers"]),
                          {k: _unpreshader(p) for k, p in _checked_dict(d["preshaders"]).items()},
                          _names(d["register_counts"]))


def _unpreshader(d: Any) -> Any:
    """A ShaderPreshader from its entry, every step checked (an argument names an earlier
    step, an op is one the host folds)."""
    from effects.shaders.hlsl.dag import can_fold
    from effects.shaders.hlsl.shader import ShaderPreshader
    if type(d) is not dict or set(d) != {"width", "steps"} or type(d["width"]) is not int \
            or type(d["steps"]) is not list or not d["steps"]:
        raise ValueError("bad preshader")
    steps = []
    for k, step in enumerate(d["steps"]):
        if type(step) is not list or not step or type(step[0]) is not str:
            raise ValueError("bad preshader step")
        if step[0] == "const" and len(step) == 2 and type(step[1]) is list \
                and all(type(v) in (int, float) for v in step[1]):
            steps.append(("const", tuple(float(v) for v in step[1])))
        elif step[0] == "uniform" and len(step) == 4 and type(step[1]) is str \
                and type(step[2]) is int and type(step[3]) is int:
            steps.append(tuple(step))
        elif can_fold(step[0]) and len(step) == 3 and type(step[1]) is int \
                and type(step[2]) is list:
            args = []
            for arg in step[2]:
                if (type(arg) is not list or len(arg) != 3 or type(arg[0]) is not int
                        or not 0 <= arg[0] < k or type(arg[1]) is not list
                        or any(type(i) is not int or not 0 <= i < 4 for i in arg[1])
                        or type(arg[2]) is not bool):
                    raise ValueError("bad preshader argument")
                args.append((arg[0], tuple(arg[1]), arg[2]))
            steps.append((step[0], step[1], tuple(args)))
        else:
            raise ValueError("bad preshader step")
    return ShaderPreshader(tuple(steps), d["width"])


def _checked_dict(d: Any) -> dict:
    if type(d) is not dict or any(type(k) is not str for k in d):
        raise ValueError("not a table")
    return d
