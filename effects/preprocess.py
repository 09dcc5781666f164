"""Placeholder preprocessor: passes text through unchanged (the real one replaces this file)."""
from __future__ import annotations

from .source import Preprocessed, SourceMap


def preprocess(text: str, path: str = "<string>", *, defines=None, include_dirs=(),
               include_handler=None, include_root=None) -> Preprocessed:
    text = text.replace("\r\n", "\n")
    smap = SourceMap()
    smap.add_file(path, text)
    smap.lines = [(path, i + 1) for i in range(text.count("\n") + 1)]
    return Preprocessed(text, smap, (path,))
