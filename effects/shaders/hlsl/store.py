"""Compiled HLSL shaders kept on disk between processes: the command line's compile cache.

The in-memory compile cache (cache.py) lasts one process; every `effects matrix` run compiled
each effect's `compile` states again (~60 ms of its ~0.5 s, plus the HLSL front end's import
and grammar). The command line (`effects.cli.main`) enables this store for the length of a
command; library use does not touch the disk unless a host calls `enable()`.

Correctness: an entry is found by the SHA-256 of everything a compile reads (`key`): the
compile key of cache.py without its "do all declarations load" flag, with every struct,
typedef and function declaration of the effect instead (that flag is made from them); the
`compile` state's location (errors are located there); every resource limit in force
(`effects.limits`); and the code doing the compiling -- the size and modification time of each
source and grammar file of the `effects` package, the Python, NumPy and lark versions. A
value the key cannot spell exactly (an object it knows no canonical form for) keeps that
compile off the disk.

What an entry holds is data, not code: JSON with the generated assembly, its per-line HLSL
locations, constant/sampler/int/bool register tables, warnings and types, or the error. The
program is made again from the assembly by `shader.assemble_generated`, the code a compile
runs, so it is checked by the assembler as any text is. A file that does not read back as such
an entry is a miss (and removed).

Safety and bounds: the folder is `$EFFECTS_CACHE_DIR`, else `$XDG_CACHE_HOME/effects/shaders`,
else `~/.cache/effects/shaders`, made private (0700); it is used only when it is a real folder
(not a link) owned by this user and writable by no one else. Entries are written to a temporary
file and renamed into place, at most `MAX_ENTRY_BYTES` each; when the folder holds more than
`MAX_ENTRIES` files or `MAX_BYTES` bytes, the least recently written go until three quarters
remain. An untrusted effect can only add entries for its own text. `EFFECTS_SHADER_CACHE=off`
turns the store off.
"""
from __future__ import annotations

import dataclasses
import hashlib
import os
import sys
from typing import Any

from effects.errors import EffectError, EffectWarning, Location

FORMAT = 1
MAX_ENTRY_BYTES = 2 << 20
MAX_ENTRIES = 4096
MAX_BYTES = 64 << 20

_state: dict[str, Any] = {"dir": None, "fingerprint": None}


class _Unkeyable(Exception):
    """A value the key has no exact, stable spelling for."""


# -- the folder ---------------------------------------------------------------------------------

def default_dir() -> str:
    explicit = os.environ.get("EFFECTS_CACHE_DIR")
    if explicit:
        return explicit
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "effects", "shaders")


def enable(path: str | None = None) -> bool:
    """Use the on-disk store (in `path`, or `default_dir()`); False, and off, where the folder
    cannot be made private to this user or `EFFECTS_SHADER_CACHE` is off."""
    _state["dir"] = None
    if os.environ.get("EFFECTS_SHADER_CACHE", "").lower() in ("0", "off", "no", "false"):
        return False
    folder = path or default_dir()
    try:
        os.makedirs(folder, mode=0o700, exist_ok=True)
        st = os.lstat(folder)
    except OSError:
        return False
    import stat
    if not stat.S_ISDIR(st.st_mode) or (hasattr(os, "getuid") and st.st_uid != os.getuid()) \
            or st.st_mode & 0o022:
        return False
    _state["dir"] = folder
    return True


def disable() -> None:
    _state["dir"] = None


def enabled() -> bool:
    return _state["dir"] is not None


# -- the key ------------------------------------------------------------------------------------

def fingerprint() -> str:
    """The compiling code: each source and grammar file of the package by path, size and
    modification time, and the Python, NumPy and lark versions (once per process)."""
    held = _state["fingerprint"]
    if held is not None:
        return held
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    h = hashlib.sha256()
    h.update(f"{FORMAT}|{sys.version}|{sys.implementation.cache_tag}".encode())
    stack = [root]
    while stack:
        folder = stack.pop()
        with os.scandir(folder) as it:
            entries = sorted(it, key=lambda e: e.name)
        for e in entries:
            if e.is_dir(follow_symlinks=False):
                if e.name != "__pycache__":
                    stack.append(e.path)
            elif e.name.endswith((".py", ".lark")):
                st = e.stat()
                h.update(f"{os.path.relpath(e.path, root)}|{st.st_size}|{st.st_mtime_ns}\n".encode())
    import numpy
    h.update(f"numpy {numpy.__version__}\n".encode())
    import importlib.util
    spec = importlib.util.find_spec("lark")
    origin = spec.origin if spec is not None else None
    if origin:
        with open(origin, "rb") as f:          # lark's __init__ holds its __version__
            h.update(f.read())
    held = _state["fingerprint"] = h.hexdigest()
    return held


def key(parts: tuple, declarations: tuple, location: Location) -> str | None:
    """The entry name for a compile: `parts` and `declarations` as cache.key_parts and
    cache.declarations give them for the `compile` state at `location`. None when some input
    has no exact spelling (that compile is not stored)."""
    from effects import limits
    try:
        path, target, function, args, where, reached = parts
        # the walk finds the reached declarations in an order that follows string hashing,
        # which differs between processes: they are spelled one by one and sorted
        reached_spelled = []
        for part in reached:
            out: list[str] = []
            _spell(part, out)
            reached_spelled.append("".join(out))
        material = ("effects-compiled-shader", FORMAT, fingerprint(),
                    tuple((name, limits.get(name)) for name in sorted(limits.LIMITS)),
                    (path, target, function, args, where), tuple(sorted(reached_spelled)),
                    declarations, location)
        out = []
        _spell(material, out)
    except _Unkeyable:
        return None
    return hashlib.sha256("".join(out).encode("utf-8", "surrogatepass")).hexdigest()


def _spell(v: Any, out: list[str]) -> None:
    """An exact, stable text for a key value: types and lengths spelled out, so no two values
    read alike; an object without a known form raises _Unkeyable."""
    t = type(v)
    if v is None or t is bool or t is int or t is float:
        out.append(f"{t.__name__}:{v!r};")
    elif t is str:
        out.append(f"s{len(v)}:{v}")
    elif t is bytes:
        out.append(f"b{len(v)}:{v.hex()}")
    elif t is tuple or t is list:
        if t is tuple and len(v) == 2 and v[0] == "repr":
            raise _Unkeyable("a value cache.py keys by its repr")
        out.append(f"{t.__name__}{len(v)}(")
        for x in v:
            _spell(x, out)
        out.append(")")
    elif t is Location:
        out.append(f"L{len(v.path)}:{v.path}:{v.line}:{v.column};")
    elif dataclasses.is_dataclass(v) and not isinstance(v, type) \
            and type(v).__dataclass_params__.frozen:       # TypeSpec, Expression ...
        fields = dataclasses.fields(v)
        out.append(f"D{t.__module__}.{t.__qualname__}{len(fields)}(")
        for f in fields:
            out.append(f"{f.name}=")
            _spell(getattr(v, f.name), out)
        out.append(")")
    else:
        raise _Unkeyable(t.__qualname__)


# -- entries ------------------------------------------------------------------------------------

def _path(name: str) -> str:
    return os.path.join(_state["dir"], f"{name}.json")


def load(name: str) -> Any:
    """The CompiledShader or EffectError stored under `name`, or None."""
    if _state["dir"] is None:
        return None
    path = _path(name)
    try:
        with open(path, "rb") as f:
            data = f.read(MAX_ENTRY_BYTES + 1)
    except OSError:
        return None
    try:
        import json
        if len(data) > MAX_ENTRY_BYTES:
            raise ValueError("too big")
        return _decode(json.loads(data), name)
    except Exception:   # not an entry of ours (truncated, foreign, older): a miss
        try:
            os.unlink(path)
        except OSError:
            pass
        return None


def save(name: str, result: Any) -> None:
    """Store a compile's result (a CompiledShader or EffectError) under `name`, if it can be
    written out exactly; never raises."""
    folder = _state["dir"]
    if folder is None:
        return
    import json
    import tempfile
    try:
        data = json.dumps(_encode(result, name), separators=(",", ":")).encode()
    except _Unkeyable:
        return
    if len(data) > MAX_ENTRY_BYTES:
        return
    try:
        fd, tmp = tempfile.mkstemp(dir=folder, prefix=".tmp-", suffix=".json")
        try:
            with os.fdopen(fd, "wb") as f:
                f.write(data)
            os.replace(tmp, _path(name))
        except BaseException:
            try:
                os.unlink(tmp)
            except OSError:
                pass
            raise
        _prune(folder)
    except OSError:
        pass


def _prune(folder: str) -> None:
    entries = []
    total = 0
    with os.scandir(folder) as it:
        for e in it:
            if e.name.endswith(".json") and not e.name.startswith("."):
                st = e.stat(follow_symlinks=False)
                entries.append((st.st_mtime_ns, st.st_size, e.path))
                total += st.st_size
    if len(entries) <= MAX_ENTRIES and total <= MAX_BYTES:
        return
    entries.sort()
    while entries and (len(entries) > MAX_ENTRIES * 3 // 4 or total > MAX_BYTES * 3 // 4):
        _, size, path = entries.pop(0)
        try:
            os.unlink(path)
        except OSError:
            pass
        total -= size


# -- encoding -----------------------------------------------------------------------------------

_ERRORS = ("HlslError", "EffectError", "AsmError")


def _loc(v: Location | None) -> Any:
    if v is None:
        return None
    if type(v) is not Location:
        raise _Unkeyable("not a Location")
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
        raise _Unkeyable("not an HType")
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


def _encode(result: Any, name: str) -> dict:
    from effects.shaders.hlsl.shader import CompiledShader
    if isinstance(result, EffectError):
        cls = type(result).__name__
        if cls not in _ERRORS or type(result).__module__ not in (
                "effects.errors", "effects.shaders.hlsl.parse"):
            raise _Unkeyable(cls)
        return {"entry": name, "error": cls, "message": result.message,
                "location": _loc(result.location), "source_line": result.source_line}
    if type(result) is not CompiledShader:
        raise _Unkeyable(type(result).__qualname__)
    known = {"function", "target", "text", "program", "constants", "samplers", "lines",
             "warnings", "types", "int_registers", "bool_registers"}
    if {f.name for f in dataclasses.fields(CompiledShader)} != known:
        raise _Unkeyable("CompiledShader has fields this store does not know")
    for w in result.warnings:
        if type(w) is not EffectWarning:
            raise _Unkeyable("a warning of another kind")
    return {
        "entry": name, "function": result.function, "target": result.target, "text": result.text,
        "entry_location": _loc(result.program.location),
        "constants": {k: list(v) for k, v in result.constants.items()},
        "samplers": dict(result.samplers), "lines": [_loc(x) for x in result.lines],
        "warnings": [[w.message, _loc(w.location), w.source_line] for w in result.warnings],
        "types": {k: _htype(t) for k, t in result.types.items()},
        "int_registers": dict(result.int_registers), "bool_registers": dict(result.bool_registers),
    }


def _decode(d: Any, name: str) -> Any:
    if type(d) is not dict or d.get("entry") != name:
        raise ValueError("not this entry")
    if "error" in d:
        cls_name = d["error"]
        if cls_name not in _ERRORS or type(d["message"]) is not str or \
                (d["source_line"] is not None and type(d["source_line"]) is not str):
            raise ValueError("bad error")
        if cls_name == "HlslError":
            from effects.shaders.hlsl.parse import HlslError as cls
        else:
            import effects.errors
            cls = getattr(effects.errors, cls_name)
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
                          _names(d["int_registers"]), _names(d["bool_registers"]))


def _checked_dict(d: Any) -> dict:
    if type(d) is not dict or any(type(k) is not str for k in d):
        raise ValueError("not a table")
    return d
