"""The command line's store on disk: results kept between processes, found by what made them.

Two kinds of entry live here: compiled HLSL shaders (`effects.shaders.hlsl.store`) and the
rows of `effects matrix` (`effects.cli.matrix_store`). This module is what they share: the
folder, the fingerprint of the code, the exact spelling of a key, and JSON entries written and
read back within bounds. Each kind spells its own key and checks its own entries; an entry's
name is the SHA-256 of its key, which begins with the kind, so kinds never meet.

The command line (`effects.cli.main`) enables the store for the length of a command; library
use does not touch the disk unless a host calls `enable()`.

Safety and bounds: the folder is `$EFFECTS_CACHE_DIR`, else `$XDG_CACHE_HOME/effects/store`,
else `~/.cache/effects/store`, made private (0700); it is used only when it is a real folder
(not a link) owned by this user and writable by no one else. Entries are written to a temporary
file and renamed into place, at most `MAX_ENTRY_BYTES` each; when the folder holds more than
`MAX_ENTRIES` files or `MAX_BYTES` bytes, the least recently written go until three quarters
remain. The folder is counted at a process's first write and again only when what this process
wrote since would pass a bound, or after `RESCAN_WRITES` writes or `RESCAN_BYTES` bytes (what
other processes add meanwhile): a write does not scan thousands of entries. A file that does
not read back as the entry asked for is a miss (and removed); what an entry holds is data,
never code. `EFFECTS_CACHE=off` turns the store off.
"""
from __future__ import annotations

import dataclasses
import hashlib
import os
import sys
from typing import Any

from effects.base import caches
from effects.base.errors import Location

FORMAT = 1
MAX_ENTRY_BYTES = 2 << 20
MAX_ENTRIES = 4096
MAX_BYTES = 64 << 20
RESCAN_WRITES = 64
RESCAN_BYTES = 4 << 20

# "counted": (entries, bytes) at the last count of the folder, then what this process has
# written since (entries, bytes); None until this process first writes
_state: dict[str, Any] = {"dir": None, "fingerprint": None, "counted": None, "hits": 0,
                          "misses": 0}


class Unkeyable(Exception):
    """A value a key has no exact, stable spelling for (what it keys is not stored)."""


# -- the folder ---------------------------------------------------------------------------------

def default_dir() -> str:
    explicit = os.environ.get("EFFECTS_CACHE_DIR")
    if explicit:
        return explicit
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "effects", "store")


def enable(path: str | None = None) -> bool:
    """Use the store (in `path`, or `default_dir()`); False, and off, where the folder cannot
    be made private to this user or `EFFECTS_CACHE` is off."""
    _state["dir"] = None
    if os.environ.get("EFFECTS_CACHE", "").lower() in ("0", "off", "no", "false"):
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
    _state["counted"] = None
    return True


def disable() -> None:
    _state["dir"] = None
    _state["counted"] = None


def enabled() -> bool:
    return _state["dir"] is not None


# -- the key ------------------------------------------------------------------------------------

def fingerprint() -> str:
    """The code that makes every entry: each source and grammar file of the package by path,
    size and modification time; the Python; and the NumPy, lark and PyYAML releases, read from
    their version files rather than imported (a warm `effects matrix` imports none of them).
    Made once per process."""
    held = _state["fingerprint"]
    if held is not None:
        return held
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))   # the whole package
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
    import importlib.util
    for package, version_file in (("numpy", "version.py"), ("lark", "__init__.py"),
                                  ("yaml", "__init__.py")):
        spec = importlib.util.find_spec(package)   # finds, does not import
        folder = os.path.dirname(spec.origin) if spec is not None and spec.origin else None
        h.update(f"{package}\n".encode())
        if folder:
            try:
                with open(os.path.join(folder, version_file), "rb") as f:
                    h.update(f.read(1 << 20))
            except OSError:
                pass
    held = _state["fingerprint"] = h.hexdigest()
    return held


def digest(material: Any) -> str:
    """An entry's name: the SHA-256 of `material` spelled exactly (`spell`). Raises
    Unkeyable."""
    out: list[str] = []
    spell(material, out)
    return hashlib.sha256("".join(out).encode("utf-8", "surrogatepass")).hexdigest()


def spell(v: Any, out: list[str]) -> None:
    """An exact, stable text for a key value: types and lengths spelled out, so no two values
    read alike; an object without a known form raises Unkeyable."""
    t = type(v)
    if v is None or t is bool or t is int or t is float:
        out.append(f"{t.__name__}:{v!r};")
    elif t is str:
        out.append(f"s{len(v)}:{v}")
    elif t is bytes:
        out.append(f"b{len(v)}:{v.hex()}")
    elif t is tuple or t is list:
        if t is tuple and len(v) == 2 and v[0] == "repr":
            raise Unkeyable("a value the compile cache keys by its repr")
        out.append(f"{t.__name__}{len(v)}(")
        for x in v:
            spell(x, out)
        out.append(")")
    elif t is Location:
        out.append(f"L{len(v.path)}:{v.path}:{v.line}:{v.column};")
    elif dataclasses.is_dataclass(v) and not isinstance(v, type) \
            and type(v).__dataclass_params__.frozen:       # TypeSpec, Expression ...
        fields = dataclasses.fields(v)
        out.append(f"D{t.__module__}.{t.__qualname__}{len(fields)}(")
        for f in fields:
            out.append(f"{f.name}=")
            spell(getattr(v, f.name), out)
        out.append(")")
    else:
        raise Unkeyable(t.__qualname__)


# -- entries ------------------------------------------------------------------------------------

def _path(name: str) -> str:
    return os.path.join(_state["dir"], f"{name}.json")


def read(name: str) -> dict | None:
    """The JSON object stored under `name` (its "entry" field is `name`), or None: the store
    off, no such entry, or a file that is not one (removed)."""
    if _state["dir"] is None:
        return None
    path = _path(name)
    try:
        with open(path, "rb") as f:
            data = f.read(MAX_ENTRY_BYTES + 1)
    except OSError:
        _state["misses"] += 1
        return None
    try:
        import json
        if len(data) > MAX_ENTRY_BYTES:
            raise ValueError("too big")
        entry = json.loads(data)
        if type(entry) is not dict or entry.get("entry") != name:
            raise ValueError("not this entry")
        _state["hits"] += 1
        return entry
    except Exception:   # not an entry of ours (truncated, foreign, older): a miss
        _state["misses"] += 1
        discard(name)
        return None


def discard(name: str) -> None:
    """Remove the entry `name` (one its kind found it cannot use); never raises."""
    if _state["dir"] is None:
        return
    try:
        os.unlink(_path(name))
    except OSError:
        pass


def write(name: str, entry: dict) -> None:
    """Store the JSON object `entry` under `name` (its "entry" field set to `name`), when it
    is within bounds; never raises."""
    folder = _state["dir"]
    if folder is None:
        return
    import json
    import tempfile
    try:
        data = json.dumps({**entry, "entry": name}, separators=(",", ":")).encode()
    except (TypeError, ValueError):
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
        _prune_when_due(folder, len(data))
    except OSError:
        pass


def _prune_when_due(folder: str, written: int) -> None:
    counted = _state["counted"]
    if counted is not None:
        entries, size, writes, wrote = counted
        writes, wrote = writes + 1, wrote + written
        # an overwrite is counted as a new entry: at worst a count comes early
        if (entries + writes <= MAX_ENTRIES and size + wrote <= MAX_BYTES
                and writes < RESCAN_WRITES and wrote < RESCAN_BYTES):
            _state["counted"] = (entries, size, writes, wrote)
            return
    _state["counted"] = (*_prune(folder), 0, 0)


def _prune(folder: str) -> tuple[int, int]:
    """Count the folder's entries and bytes, drop the least recently written where they pass
    a bound, and say what remains."""
    entries = []
    total = 0
    with os.scandir(folder) as it:
        for e in it:
            if e.name.endswith(".json") and not e.name.startswith("."):
                st = e.stat(follow_symlinks=False)
                entries.append((st.st_mtime_ns, st.st_size, e.path))
                total += st.st_size
    if len(entries) <= MAX_ENTRIES and total <= MAX_BYTES:
        return len(entries), total
    entries.sort()
    while entries and (len(entries) > MAX_ENTRIES * 3 // 4 or total > MAX_BYTES * 3 // 4):
        _, size, path = entries.pop(0)
        try:
            os.unlink(path)
        except OSError:
            pass
        total -= size
    return len(entries), total


# -- in the cache registry ----------------------------------------------------------------------

def _entries(folder: str) -> list[os.DirEntry]:
    with os.scandir(folder) as it:
        return [e for e in it if e.name.endswith(".json") and not e.name.startswith(".")]


class _Registered:
    """The store as `effects.base.caches.report()` lists it: its entries and bytes counted in
    the folder when enabled (nothing otherwise); `clear` removes every entry of the folder."""

    name, kind = "disk_store", "disk"
    keys = ("SHA-256 of what made the entry: its kind, the code's fingerprint and the kind's own "
            "inputs (effects.shaders.hlsl.store, effects.cli.matrix_store)")

    def stats(self) -> caches.CacheStats:
        count = size = 0
        folder = _state["dir"]
        if folder is not None:
            try:
                found = _entries(folder)
                count = len(found)
                size = sum(e.stat(follow_symlinks=False).st_size for e in found)
            except OSError:
                pass
        return caches.CacheStats(self.name, self.kind, self.keys, count, size, MAX_BYTES,
                                 _state["hits"], _state["misses"])

    def clear(self) -> None:
        folder = _state["dir"]
        if folder is None:
            return
        try:
            for e in _entries(folder):
                try:
                    os.unlink(e.path)
                except OSError:
                    pass
        except OSError:
            pass
        _state["counted"] = None


caches.register(_Registered())
