"""`load_effect`: read an effect from a path or text, preprocess it, parse it into the model."""
from __future__ import annotations

import os
from typing import Callable, Mapping

from effects.errors import EffectError, Location, PreprocessError
from effects.model import Effect

IncludeHandler = Callable[[str, str], "str | None"]


def _looks_like_path(source: str) -> bool:
    """One line with no braces or semicolons names a file; anything else is effect text."""
    return not any(c in source for c in "\n{;") and len(source) < 4096


def read_source_file(path: str) -> str:
    """Read an effect file as text; a stray non-ASCII byte must not stop the load."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as exc:
        raise PreprocessError(f"cannot read effect file: {exc.strerror}", Location(path, 1, 1)) from None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        # Old effect files are Windows-1252 or worse; latin-1 maps every byte to one char.
        return data.decode("latin-1")


def load_effect(path_or_text: "str | os.PathLike[str]", *, defines: Mapping[str, str] | None = None,
                include_dirs=(), include_handler: IncludeHandler | None = None,
                include_root: str | None = None, strict: bool = False) -> Effect:
    """Load an effect file (or effect source text) into an `Effect`.

    Raises `EffectError` (located) for every problem in the input.
    """
    from effects.frontend.parser import parse_effect
    from effects.frontend.preprocess import preprocess

    source = os.fspath(path_or_text)
    if _looks_like_path(source):
        path = source
        text = read_source_file(path)
    else:
        path, text = "<string>", source
    pre = preprocess(text, path, defines=defines, include_dirs=tuple(include_dirs),
                     include_handler=include_handler, include_root=include_root)
    try:
        return parse_effect(pre, strict=strict)
    except EffectError:
        raise
    except RecursionError:
        loc = pre.source_map.locate(1, 1)
        raise pre.source_map.error_at(EffectError, "input nests too deeply to parse", loc) from None
