"""One cache policy: every in-memory cache is declared through this module, by name, and used
by that name (`LAYER.WHAT`: "lower.passes", "shaders.hlsl.compiles", "reference.steps").

A declaration says what the cache keys on (the inputs its value depends on) and how it is
bounded, in bytes: each value's size is measured (`nbytes`: the NumPy arrays it holds; or the
declaration's own `size_of`) or a declared per-entry estimate (`entry_bytes`). The least
recently used entries go first once the total passes the bound. Two kinds of storage sit
behind the one policy:

- `declare(name, keys=..., max_bytes=..., size_of=... | entry_bytes=...)`: a `Cache` (a
  `ByteLRU`, which counts its hits and misses), for values of varying size or keys a caller
  makes (a lowered pass by technique, pass and card; a texture by file and stamp);
- `@memo(name, keys=..., entry_bytes=..., max_bytes=...)`: a pure function of hashable
  arguments memoised by `functools.lru_cache` (C speed, for the lookups asked thousands of
  times per validation), its count bound `max_bytes // entry_bytes`.

The registry (`report()` and `clear()`, exported as `effects.cache_report()` and
`effects.clear_caches()`) lists every cache declared by the modules imported so far (a module
not imported has nothing cached), and the on-disk store (`effects.base.disk_store`), so a host
can see what its memory holds and give it back. A value derived from one object, meant to go
with it, is no cache here: it is the object's own declared field or
`functools.cached_property` (never an attribute stashed in its `__dict__`).
"""
from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any, Callable, Hashable, Iterable, Protocol, TypeVar

from effects.base.lru import ByteLRU

F = TypeVar("F", bound=Callable[..., Any])

OBJECT_BYTES = 64      # what an entry costs besides its arrays (the key, the tuple, the object)


@dataclass(frozen=True)
class CacheStats:
    """One row of `report()`."""

    name: str
    kind: str          # 'memory' (Cache), 'memo' (a memoised function), 'disk' (the store)
    keys: str          # what the cache keys on
    entries: int
    bytes: int         # measured, or entries x the declared per-entry estimate
    max_bytes: int
    hits: int
    misses: int


class Registered(Protocol):
    name: str
    kind: str

    def stats(self) -> CacheStats: ...

    def clear(self) -> None: ...


_REGISTRY: dict[str, Registered] = {}


def register(cache: Registered) -> None:
    """Name `cache` in the registry. A module imported again (importlib.reload) declares its
    caches again: the new object replaces the old."""
    _REGISTRY[cache.name] = cache


def nbytes(value: Any, _depth: int = 0) -> int:
    """About what `value` holds: the bytes of the NumPy arrays in it (through tuples, lists,
    dicts and object attributes, three levels down) plus `OBJECT_BYTES` for the entry."""
    total = OBJECT_BYTES if _depth == 0 else 0
    size = getattr(value, "nbytes", None)
    if isinstance(size, int) and hasattr(value, "dtype"):
        return total + size
    if _depth >= 3:
        return total
    if isinstance(value, (tuple, list)):
        parts: Iterable[Any] = value
    elif isinstance(value, dict):
        parts = value.values()
    elif hasattr(value, "__dict__") and not isinstance(value, type):
        parts = vars(value).values()
    elif hasattr(type(value), "__slots__"):
        parts = (getattr(value, s, None) for s in type(value).__slots__)
    else:
        return total
    return total + sum(nbytes(p, _depth + 1) for p in parts)


class Cache(ByteLRU):
    """A declared cache: key -> value, least recently used out first past `max_bytes`.
    Values are never None (`get` answers None for a miss)."""

    kind = "memory"

    def __init__(self, name: str, keys: str, max_bytes: int,
                 size_of: Callable[[Any], int]) -> None:
        super().__init__(max_bytes, size_of)
        self.name, self.keys = name, keys

    def get_or_make(self, key: Hashable, make: Callable[[], Any]) -> Any:
        """The value kept for `key`, else `make()`'s, kept (two threads may both make it)."""
        found = self.get(key)
        if found is None:
            found = make()
            self.put(key, found)
        return found

    def __getitem__(self, key: Hashable) -> Any:
        found = self.get(key)
        if found is None:
            raise KeyError(key)
        return found

    def stats(self) -> CacheStats:
        return CacheStats(self.name, self.kind, self.keys, len(self), self.bytes,
                          self.max_bytes, self.hits, self.misses)


def declare(name: str, *, keys: str, max_bytes: int,
            size_of: Callable[[Any], int] | None = None,
            entry_bytes: int | None = None) -> Cache:
    """A new cache named `name`: `keys` says what it keys on; each value is sized by
    `size_of`, or counted as `entry_bytes` (a declared estimate), or measured by `nbytes`."""
    if size_of is None:
        size_of = nbytes if entry_bytes is None else (lambda value, n=int(entry_bytes): n)
    cache = Cache(name, keys, max_bytes, size_of)
    register(cache)
    return cache


class _Memo:
    """A function memoised by functools.lru_cache, as the registry sees it."""

    kind = "memo"

    def __init__(self, name: str, keys: str, entry_bytes: int, max_bytes: int,
                 cached: Any) -> None:
        self.name, self.keys, self.cached = name, keys, cached
        self.entry_bytes, self.max_bytes = entry_bytes, max_bytes

    def stats(self) -> CacheStats:
        info = self.cached.cache_info()
        return CacheStats(self.name, self.kind, self.keys, info.currsize,
                          info.currsize * self.entry_bytes, self.max_bytes, info.hits,
                          info.misses)

    def clear(self) -> None:
        self.cached.cache_clear()


def memo(name: str, *, keys: str, entry_bytes: int, max_bytes: int) -> Callable[[F], F]:
    """Decorate a pure function of hashable arguments (`keys` names them): its results are
    kept, at most `max_bytes // entry_bytes` of them, least recently used out first."""
    def wrap(fn: F) -> F:
        cached = functools.lru_cache(maxsize=max(1, max_bytes // entry_bytes))(fn)
        register(_Memo(name, keys, entry_bytes, max_bytes, cached))
        return cached  # type: ignore[return-value]
    return wrap


def report() -> list[CacheStats]:
    """Every registered cache, by name."""
    return [_REGISTRY[name].stats() for name in sorted(_REGISTRY)]


def named(name: str) -> Registered:
    """The registered cache `name` (KeyError when no imported module declares it)."""
    return _REGISTRY[name]


def clear(*names: str) -> None:
    """Empty the caches named (KeyError for an unknown name), or with no name every in-memory
    one: the on-disk store only when named ('disk_store'), as other processes share it."""
    for name in names or [n for n, c in _REGISTRY.items() if c.kind != "disk"]:
        _REGISTRY[name].clear()


# the names `effects` exports them by
cache_report, clear_caches = report, clear
