"""`load_effect`: read an effect from a path or text, preprocess it, parse it into the model."""
from __future__ import annotations

import os
import stat
from typing import Callable, Mapping

from effects.base import limits, untrusted
from effects.base.errors import EffectError, Location, PreprocessError
from effects.model import Effect

IncludeHandler = Callable[[str, str], "str | None"]


def _names_a_file(source: str) -> bool:
    """Whether `source` names a file rather than being effect text: an existing path always
    does (`my{1}.fx` too); otherwise one short line with no braces or semicolons."""
    if "\n" in source or len(source) > 4096:
        return False
    try:
        if os.path.lexists(source):
            return True
    except (ValueError, OSError):  # a NUL byte, a name too long for the file system
        return False
    return not any(c in source for c in "{;")


def _starts_binary(path: str) -> bool:
    """Whether regular file `path` starts with the fx_2_0 effect-binary tag (the magic, not
    the name, tells a binary from source). Anything unreadable is left to the text path,
    which reports it."""
    from effects.frontend.fxo import is_effect_binary
    from effects.frontend.xnb import is_wrapped_effect
    try:
        # O_NONBLOCK: a FIFO must not block the peek (untrusted.read_file's care)
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
        with os.fdopen(fd, "rb") as f:
            head = f.read(4)
            return stat.S_ISREG(os.fstat(f.fileno()).st_mode) and (
                is_effect_binary(head) or is_wrapped_effect(head))
    except (OSError, ValueError):
        return False


def _read_binary(raw: bytes, path: str, effect_type: type[Effect]) -> Effect:
    """An fx_2_0 binary, bare or inside XNA's containers (effects.frontend.xnb)."""
    from effects.frontend import fxo, xnb
    if xnb.is_wrapped_effect(raw):
        blob, origin = xnb.unwrap(raw, path)
        return fxo.read_effect_binary(blob, path, effect_type, origin)
    return fxo.read_effect_binary(raw, path, effect_type)


def read_source_file(path: str) -> str:
    """Read an effect file as text: a regular file within the `source_bytes` limit, UTF-8 or
    BOM-marked UTF-16/32, else Latin-1 (a stray Windows-1252 byte must not stop the load)."""
    return untrusted.read_text(path, "effect file", PreprocessError, "source_bytes",
                               latin1_fallback=True)


def load_effect(path_or_text: "str | bytes | os.PathLike[str]", *, defines: Mapping[str, str] | None = None,
                include_dirs=(), include_handler: IncludeHandler | None = None,
                include_root: str | None = None, strict: bool = False,
                effect_type: type[Effect] = Effect) -> Effect:
    """Load an effect file (or effect source text) into an `Effect` (or the subclass
    `effect_type`: `effects.load_effect` gives `effects.api.Effect`).

    Raises `EffectError` (located) for every problem in the input.
    """
    from effects.frontend.parser import parse_effect
    from effects.frontend.preprocess import preprocess

    if isinstance(path_or_text, (bytes, bytearray, memoryview)):
        # an fx_2_0 binary in memory (the documented contract: a compiled .fxo path or bytes)
        from effects.frontend import fxo, xnb
        raw = bytes(path_or_text)
        if not fxo.is_effect_binary(raw) and not xnb.is_wrapped_effect(raw):
            raise fxo.FxoError("bytes that do not start with the fx_2_0 tag (0xFEFF0901) or "
                               "an XNA container's: pass effect source as text, a binary as "
                               "bytes", Location("<bytes>", 1, 1))
        return _read_binary(raw, "<bytes>", effect_type)
    source = os.fspath(path_or_text)
    if _names_a_file(source):
        path = source
        if _starts_binary(path):    # an fx_2_0 binary (.fxo, .xnb), whatever its name says
            from effects.frontend import fxo
            raw = untrusted.read_file(path, "effect binary", fxo.FxoError, "effect_binary_bytes")
            return _read_binary(raw, path, effect_type)
        text = read_source_file(path)
    else:
        path, text = "<string>", source
        if len(text) * 4 > limits.get("source_bytes"):   # count bytes only when it may matter
            limits.check("source_bytes", len(text.encode("utf-8", "surrogatepass")),
                         Location(path, 1, 1), "the effect text", PreprocessError)
    pre = preprocess(text, path, defines=defines, include_dirs=tuple(include_dirs),
                     include_handler=include_handler, include_root=include_root)
    try:
        effect = parse_effect(pre, strict=strict, effect_type=effect_type)
    except EffectError:
        raise
    except RecursionError:
        loc = pre.source_map.locate(1, 1)
        raise pre.source_map.error_at(EffectError, "input nests too deeply to parse", loc) from None
    effect.include_root = None if include_root is None else os.fspath(include_root)
    from effects.frontend.references import reference_problems
    for location, message in reference_problems(effect):
        effect.warnings.append(pre.source_map.warning_at(message, location))
    return effect
