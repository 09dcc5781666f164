"""How files named by untrusted input are read: regular files only, bounded, decoded, confined.

Every door that opens a file an effect, scene or profile names goes through here (README
"Untrusted effects"):
- `read_file` reads only a regular file (a FIFO would block forever, /dev/zero never ends, a
  directory is no file), at most the named size limit, checked before reading and while
  reading (a file may grow);
- `decode_text` decodes UTF-8 and, with a byte-order mark, UTF-8/UTF-16/UTF-32; bytes that do
  not decode are a located error naming the encoding (effect files may instead fall back to
  Latin-1, as Windows-1252-era .fx files need);
- `confine` keeps a path an effect names inside its include root: no absolute paths, no
  backslashes, nothing (after `..` and symlinks) outside the root.

Since every named file passes here, here is where a caller learns which files some work
depended on (`recording`): every path confined or read is noted, also those whose contents
a cache then supplies (the confined name is asked before the cache is). The command line
keeps the fidelity rows of `effects matrix` on disk by the files their renders named
(effects.cli.matrix_store).
"""
from __future__ import annotations

import codecs
import contextlib
import os
import stat
import threading
from typing import Iterator

from effects.base import limits
from effects.base.errors import EffectError, Location

_BOMS = [(codecs.BOM_UTF32_LE, "utf-32-le"), (codecs.BOM_UTF32_BE, "utf-32-be"),
         (codecs.BOM_UTF8, "utf-8"), (codecs.BOM_UTF16_LE, "utf-16-le"),
         (codecs.BOM_UTF16_BE, "utf-16-be")]   # UTF-32 LE starts like UTF-16 LE: test it first


_NOTES = threading.local()


@contextlib.contextmanager
def recording() -> Iterator[set[str]]:
    """The absolute paths of every file named or read on this thread inside the block."""
    outer = getattr(_NOTES, "paths", None)
    paths: set[str] = set()
    _NOTES.paths = paths
    try:
        yield paths
    finally:
        _NOTES.paths = outer
        if outer is not None:
            outer |= paths


def note(path: str | os.PathLike[str]) -> None:
    """Note `path` as named, for `recording` (a no-op outside one)."""
    paths = getattr(_NOTES, "paths", None)
    if paths is not None:
        paths.add(os.path.abspath(os.fspath(path)))


def _kind(mode: int) -> str:
    if stat.S_ISDIR(mode):
        return "a directory"
    if stat.S_ISFIFO(mode):
        return "a FIFO (named pipe)"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "not a regular file"


def check_regular(path: str, what: str, error: type[EffectError], location: Location | None = None,
                  limit: str | None = None) -> int:
    """The size of `path` if it is a regular file within `limit`; else a located `error`."""
    where = location or Location(path, 1, 1)
    note(path)
    try:
        info = os.stat(path)
    except OSError as exc:
        raise error(f"cannot read {what}: {exc.strerror or exc}", where) from None
    if not stat.S_ISREG(info.st_mode):
        raise error(f"cannot read {what}: {path} is {_kind(info.st_mode)}; only regular files are read",
                    where)
    if limit is not None:
        limits.check(limit, info.st_size, where, f"{what} {os.path.basename(path)}", error)
    return info.st_size


def read_file(path: str | os.PathLike[str], what: str, error: type[EffectError], limit: str,
              location: Location | None = None) -> bytes:
    """The bytes of regular file `path`, at most limit `limit` of them."""
    path = os.fspath(path)
    where = location or Location(path, 1, 1)
    check_regular(path, what, error, where, limit)
    cap = limits.get(limit)
    try:
        # O_NONBLOCK: should the file be swapped for a FIFO after the check, open does not block
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
        with os.fdopen(fd, "rb") as f:
            if not stat.S_ISREG(os.fstat(f.fileno()).st_mode):
                raise error(f"cannot read {what}: {path} is not a regular file", where)
            data = f.read(cap + 1)
    except OSError as exc:
        raise error(f"cannot read {what}: {exc.strerror or exc}", where) from None
    limits.check(limit, len(data), where, f"{what} {os.path.basename(path)}", error)
    return data


def _position(text: bytes, offset: int) -> tuple[int, int]:
    """1-based (line, column) of byte `offset`, counting bytes on the line."""
    line = text.count(b"\n", 0, offset) + 1
    return line, offset - (text.rfind(b"\n", 0, offset) + 1) + 1


def decode_text(data: bytes, path: str, error: type[EffectError], *, latin1_fallback: bool = False) -> str:
    """`data` as text: a BOM names the encoding, else UTF-8 (else Latin-1 when allowed)."""
    for bom, encoding in _BOMS:
        if data.startswith(bom):
            body = data[len(bom):]
            try:
                return body.decode(encoding)
            except UnicodeDecodeError as exc:
                line, column = _position(body, exc.start) if encoding == "utf-8" else (1, 1)
                raise error(f"the file starts with a {encoding.upper()} byte-order mark but byte "
                            f"{exc.start + len(bom)} is not valid {encoding.upper()}: {exc.reason}",
                            Location(path, line, column)) from None
    nul = data.find(b"\0", 0, 4096)
    if nul >= 0:   # no text format we read holds NUL; UTF-16 without a BOM is half NULs
        raise error("the file holds NUL bytes: it is binary, or UTF-16/UTF-32 without a "
                    "byte-order mark (save it as UTF-8)", Location(path, *_position(data, nul))) from None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        where = Location(path, *_position(data, exc.start))
        if not latin1_fallback:
            raise error(f"the file is not valid UTF-8 (byte 0x{data[exc.start]:02x}: {exc.reason}); "
                        "save it as UTF-8, or as UTF-16 with a byte-order mark", where) from None
    # Old effect files are Windows-1252 or worse; latin-1 maps every byte to one character.
    return data.decode("latin-1")


def read_text(path: str | os.PathLike[str], what: str, error: type[EffectError], limit: str,
              location: Location | None = None, *, latin1_fallback: bool = False) -> str:
    """`read_file` then `decode_text`."""
    path = os.fspath(path)
    return decode_text(read_file(path, what, error, limit, location), path, error,
                       latin1_fallback=latin1_fallback)


def confine(name: str, base_dir: str, root: str | None, what: str, error: type[EffectError],
            location: Location) -> str:
    """The path `name` means relative to `base_dir`, refused unless it stays inside `root`.

    Without a root, absolute names and backslashes are taken as they are (trusted input).
    """
    if root is None:
        path = name if os.path.isabs(name) else os.path.join(base_dir, name)
        note(path)
        return path
    shown = name if len(name) <= 80 else name[:77] + "..."
    if "\\" in name:
        raise error(f"{what} '{shown}' contains a backslash; under an include root paths use '/'",
                    location)
    if os.path.isabs(name) or (len(name) > 1 and name[1] == ":"):
        raise error(f"{what} '{shown}' is an absolute path; under the include root '{root}' only "
                    "relative paths are read", location)
    path = os.path.normpath(os.path.join(base_dir, name))
    root_real = os.path.realpath(root)
    real = os.path.realpath(path)
    try:
        inside = os.path.commonpath([root_real, real]) == root_real
    except ValueError:  # another drive on Windows
        inside = False
    if not inside:
        raise error(f"{what} '{shown}' escapes the include root '{root}'", location)
    note(path)
    return path
