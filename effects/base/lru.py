"""A least-recently-used cache bounded by the bytes its values hold, not by their count.

Textures differ in size by orders of magnitude (a 1x1 stand-in, a 2048^2 cube with mips), so a
count bound either thrashes on an effect with many small textures or pins gigabytes with a few
big ones. `ByteLRU` evicts the least recently used entries until the total fits `max_bytes`;
a value bigger than the bound on its own is returned but not kept. With `size_of=lambda v: 1`
the bound is a count. The storage of every declared cache (effects.base.caches).
"""
from __future__ import annotations

import threading
from collections import OrderedDict
from typing import Any, Callable, Hashable

DEFAULT_TEXTURE_BYTES = 512 << 20


def texture_bytes(texture: Any) -> int:
    """The bytes of a texture's mip levels (anything with `.levels` of arrays), else 0."""
    return int(sum(getattr(level, "nbytes", 0) for level in getattr(texture, "levels", ())))


class ByteLRU:
    """key -> value, least recently used evicted first once the values pass `max_bytes`
    (sized by `size_of`). Safe to share between threads (the viewer loads on two): a read
    takes no lock (each step is one atomic dict operation under the GIL, and an entry evicted
    between them is a miss), a write does. `hits` and `misses` count the reads."""

    def __init__(self, max_bytes: int = DEFAULT_TEXTURE_BYTES,
                 size_of: Callable[[Any], int] = texture_bytes) -> None:
        self.max_bytes = int(max_bytes)
        self.size_of = size_of
        self._entries: OrderedDict[Hashable, tuple[Any, int]] = OrderedDict()
        self._lock = threading.Lock()
        self.bytes = 0
        self.hits = self.misses = 0

    def get(self, key: Hashable) -> Any:
        try:
            hit = self._entries[key]
            self._entries.move_to_end(key)
        except KeyError:
            self.misses += 1
            return None
        self.hits += 1
        return hit[0]

    def put(self, key: Hashable, value: Any) -> None:
        size = self.size_of(value)
        with self._lock:
            old = self._entries.pop(key, None)
            if old is not None:
                self.bytes -= old[1]
            if size > self.max_bytes:
                return
            self._entries[key] = (value, size)
            self.bytes += size
            while self.bytes > self.max_bytes:
                _, (_, freed) = self._entries.popitem(last=False)
                self.bytes -= freed

    def clear(self) -> None:
        """Forget every entry, and the counts of reads (as a memo's clear does)."""
        with self._lock:
            self._entries.clear()
            self.bytes = 0
            self.hits = self.misses = 0

    def __len__(self) -> int:
        return len(self._entries)

    def __contains__(self, key: Hashable) -> bool:
        return key in self._entries
