"""docs/design.md habit 14: a cache is declared once, through effects.base.caches, and used by name;
values are not stashed on objects' __dict__."""
from __future__ import annotations

import re

from tests.paths import ROOT

# A cache made by hand (functools.lru_cache, cache decorators) or a value kept in an object's
# __dict__ outside the cache policy's own module
HAND_MADE = re.compile(r"lru_cache|functools\.cache\b|@cache\b|__dict__\s*\[|__dict__\.(get|setdefault|pop|update)")


def test_no_cache_is_made_by_hand_and_nothing_is_stashed_in_dict():
    found = []
    for folder in ("effects", "backends"):
        for path in sorted((ROOT / folder).rglob("*.py")):
            if path == ROOT / "effects" / "base" / "caches.py":
                continue
            for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                if HAND_MADE.search(line):
                    found.append(f"{path.relative_to(ROOT)}:{number}: {line.strip()}")
    assert found == []
