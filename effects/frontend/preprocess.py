"""The effect-file preprocessor: comments, `#include`, `#define`, `#if` and macro expansion.

It runs before the lark parse and keeps one output line per input line: comments become
spaces (newlines kept), directive lines and skipped lines become empty lines, and an
`#include` line is replaced by the lines of the included file. So `SourceMap.lines` maps every
output line back to a file and line, and columns of untouched text stay where they were.

This module reads the files and drives the directives; macros (C's rules, with hide sets)
are in effects/macros.py, `#if` expressions in effects/preprocess_expr.py, tokens in
effects/preprocess_tokens.py. `#pragma` and `#line` are ignored, except `#pragma once`.

Bad input never hangs or overflows the stack: every limit is a located `PreprocessError`.
"""
from __future__ import annotations

import gc
import os
import re
from dataclasses import dataclass, field
from itertools import repeat
from typing import Callable, Mapping, Sequence

from effects.base import limits, untrusted
from effects.base.errors import Location, PreprocessError
from effects.frontend.macros import MAX_ARGUMENT_PARENS, MAX_EXPANSION_TOKENS, MAX_MACRO_NESTING, MacroTable
from effects.frontend.preprocess_expr import MAX_EXPRESSION_NESTING, evaluate_condition
from effects.frontend.preprocess_tokens import BLANKS, MAX_TOKENIZED_CHARS, Span, tokenize, word_after
from effects.frontend.source import Preprocessed, SourceMap

MAX_INCLUDE_DEPTH = 64          # files open at once through #include
# The other limits live with the code they bound; named here too, as they always were.
__all__ = ["preprocess", "MAX_INCLUDE_DEPTH", "MAX_EXPANSION_TOKENS", "MAX_MACRO_NESTING",
           "MAX_EXPRESSION_NESTING", "MAX_ARGUMENT_PARENS", "MAX_TOKENIZED_CHARS"]


_NEWLINE = re.compile(r"\r\n?")
_COMMENT_OR_STRING = re.compile(r'"[^"\\\n]*(?:\\.[^"\\\n]*)*"?|//[^\n]*|/\*.*?(?:\*/|\Z)', re.S)
_DIRECTIVE = re.compile(r"[ \t\f\v]*#[ \t\f\v]*([A-Za-z_][A-Za-z0-9_]*)?")
_PACK_MATRIX = re.compile(r"[ \t\f\v]*pack_matrix[ \t\f\v]*\([ \t\f\v]*(row_major|column_major)"
                          r"[ \t\f\v]*\)[ \t\f\v]*(?://.*|/\*.*)?$")
_CONDITIONALS = frozenset({"if", "ifdef", "ifndef", "elif", "else", "endif"})


@dataclass
class _Branch:
    """One open #if group."""

    directive: str
    location: Location
    outer_active: bool
    taken: bool          # a branch of this group has been chosen already
    seen_else: bool = False


_ASM_OPEN = re.compile(r"\basm\s*\{", re.I)


def _splice_continuations(lines: list[str]) -> None:
    """A backslash ending a line outside a directive joins the next line to it, as C's
    translation phase 2 does (NVIDIA files break long annotation strings so): the joined text
    stays on the first line and the lines it took are left empty, so line numbers hold.
    Directives read their own continuations (`directive`)."""
    i, n = 0, len(lines)
    while i < n:
        line = lines[i]
        directive = line.lstrip(" \t\f\v").startswith("#")
        j = i
        while lines[j].endswith("\\") and j + 1 < n:
            j += 1
        if j > i and not directive:
            lines[i] = "".join(part[:-1] for part in lines[i:j]) + lines[j]
            for k in range(i + 1, j + 1):
                lines[k] = ""
        i = j + 1


@dataclass
class _File:
    path: str
    real: str | None     # realpath, for cycle checks and #pragma once; None for text
    lines: list[str]
    depth: int
    branches: list[_Branch] = field(default_factory=list)
    active: bool = True


def _is_pseudo_path(path: str) -> bool:
    return path.startswith("<") and path.endswith(">")


def _other_case(folder: str, local: str) -> str | None:
    """`folder/local` found component by component ignoring letter case, as Windows opens
    it; None when a component has no match or more than one (skin.fx and SKIN.fx)."""
    path = folder or "."
    for part in [p for p in local.replace("\\", "/").split("/") if p not in ("", ".")]:
        if part == "..":
            path = os.path.join(path, part)
            continue
        exact = os.path.join(path, part)
        if os.path.exists(exact):
            path = exact
            continue
        try:
            names = os.listdir(path)
        except OSError:
            return None
        found = [n for n in names if n.lower() == part.lower()]
        if len(found) != 1:
            return None
        path = os.path.join(path, found[0])
    return os.path.normpath(path) if path != (folder or ".") else None


class _Preprocessor:
    def __init__(self, include_dirs: Sequence[str], include_handler, include_root: str | None) -> None:
        self.include_dirs = [os.fspath(d) for d in include_dirs]
        self.include_handler = include_handler
        self.include_root = None if include_root is None else os.fspath(include_root)
        self.root_real = None if include_root is None else os.path.realpath(self.include_root)
        self.macros = MacroTable(self.error)
        self.smap = SourceMap()
        self.out: list[str] = []
        self.files: list[str] = []
        self.chain: list[tuple[str, str]] = []  # (realpath, path) of the files being included
        self.once: set[str] = set()
        self.include_count = 0
        self.included_bytes = 0
        self.pack_matrix: list[tuple[int, bool]] = []
        self.warnings: list[tuple[str, Location]] = []

    def error(self, message: str, location: Location) -> PreprocessError:
        return self.smap.error_at(PreprocessError, message, location)

    def pack_matrix_pragma(self, text: str, rest: int, span: Span) -> None:
        """`#pragma pack_matrix(row_major)`: the default majorness of the matrices declared
        after it (fxc's); recorded at the output line the directive's blank line takes."""
        m = _PACK_MATRIX.match(text, rest)
        if m is None:
            at = text.index("pack_matrix", rest)
            raise self.error("#pragma pack_matrix expects (row_major) or (column_major)",
                             span.location(at))
        self.pack_matrix.append((len(self.out) + 1, m.group(1) == "row_major"))

    # ----------------------------------------------------------------- files and lines

    def predefine(self, defines: Mapping[str, str]) -> None:
        """`defines` act like #define lines before line 1; errors point into "<defines>"."""
        texts = []
        for name, value in defines.items():
            value = "1" if value is None else str(value)
            texts.append(f"{name} {value}".replace("\r", " ").replace("\n", " "))
        self.smap.texts["<defines>"] = texts
        for number, text in enumerate(texts, 1):
            self.macros.define(text, 0, Span("<defines>", text, [0], [number]))

    def run_file(self, text: str, path: str, depth: int, real: str | None, spliced: bool) -> None:
        if "\r" in text:
            text = _NEWLINE.sub("\n", text)
        if text.startswith("\ufeff"):
            text = text[1:]
        self.smap.texts[path] = text.split("\n")
        if path not in self.files:
            self.files.append(path)
        lines = self._strip_comments(text, path).split("\n")
        if spliced and len(lines) > 1 and lines[-1] == "":
            lines.pop()  # the newline ending an included file does not add a line
        if "\\\n" in text:
            _splice_continuations(lines)
        unit = _File(path, real, lines, depth)
        out, line_map = self.out, self.smap.lines
        macros, defined = self.macros, self.macros.defined  # `defined` is never replaced, only changed
        if not defined and "#" not in text and "__" not in text:  # fast path: only map lines
            out.extend(lines)
            line_map.extend(zip(repeat(path), range(1, len(lines) + 1)))
            return
        i, n = 0, len(lines)
        while i < n:
            line = lines[i]
            if "#" in line and line.lstrip(" \t\f\v").startswith("#"):
                i = self.directive(unit, i)
                continue
            if not unit.active:
                line = ""
            elif defined:
                match = macros.pattern().search(line)
                if match is not None:
                    expanded, used, pieces = macros.expand_lines(lines, i, match.start(), path)
                    out.append(predefined(expanded, path, i + 1) if "__" in expanded else expanded)
                    line_map.append((path, i + 1))
                    self.smap.expanded[len(out)] = pieces
                    if used > 1:  # an argument list ran on: its other lines stay empty
                        self.emit_blank(path, i + 2, used - 1)
                    i += used
                    continue
            out.append(predefined(line, path, i + 1) if "__" in line else line)
            line_map.append((path, i + 1))
            i += 1
        if unit.branches:
            branch = unit.branches[-1]
            raise self.error(f"unterminated #{branch.directive}", branch.location)

    def _strip_comments(self, text: str, path: str) -> str:
        if "/" not in text:
            return text

        def blank(match: re.Match) -> str:
            s = match.group()
            if s[0] == '"':
                return s
            if s[1] == "*" and (len(s) < 4 or not s.endswith("*/")):
                start = match.start()
                line = text.count("\n", 0, start) + 1
                raise self.error("unterminated comment",
                                 Location(path, line, start - text.rfind("\n", 0, start)))
            if "\n" not in s:
                return " " * len(s)
            return "\n".join(" " * len(part) for part in s.split("\n"))

        return _COMMENT_OR_STRING.sub(blank, text)

    def emit_blank(self, path: str, first_line: int, count: int) -> None:
        self.out.extend(repeat("", count))
        self.smap.lines.extend(zip(repeat(path), range(first_line, first_line + count)))

    # ----------------------------------------------------------------- directives

    def directive(self, unit: _File, i: int) -> int:
        """Handle the directive starting at line index i; returns the index after it."""
        lines, path = unit.lines, unit.path
        parts, starts, numbers, offset = [], [], [], 0
        j = i
        while True:
            part = lines[j]
            continued = part.endswith("\\") and j + 1 < len(lines)
            if continued:
                part = part[:-1]
            parts.append(part)
            starts.append(offset)
            numbers.append(j + 1)
            offset += len(part)
            if not continued:
                break
            j += 1
        text = "".join(parts)
        span = Span(path, text, starts, numbers)
        if len(text) > MAX_TOKENIZED_CHARS:
            raise self.error(f"directive too long ({len(text)} characters; the limit is "
                             f"{MAX_TOKENIZED_CHARS})", span.location(text.index("#")))
        used = j - i + 1
        match = _DIRECTIVE.match(text)
        name = match.group(1) or ""
        rest = match.end()
        hash_at = span.location(text.index("#"))

        if name in _CONDITIONALS:
            self.conditional(unit, name, text, rest, span, hash_at)
        elif not unit.active:
            pass  # anything else in a skipped group is not even looked at
        elif name == "include":
            self.include(unit, text, rest, span, hash_at)
            self.emit_blank(path, i + 2, used - 1)
            return i + used
        elif name == "define":
            self.macros.define(text, rest, span)
        elif name == "undef":
            word, at = word_after(text, rest)
            if word is None:
                raise self.error("#undef expects a macro name", span.location(at))
            self.macros.undef(word)
        elif name == "error":
            message = text[rest:].strip()
            raise self.error(f"#error {message}" if message else "#error", hash_at)
        elif name == "pragma":
            if text[rest:].split() == ["once"] and unit.real is not None:
                self.once.add(unit.real)
            elif text[rest:].split("(")[0].strip() == "pack_matrix":
                self.pack_matrix_pragma(text, rest, span)
        elif name == "line":
            pass  # kept as an empty line: our own map already knows where every line came from
        elif name or text[rest:].strip():
            if self._inside_asm_block():
                # Not a directive but a line some engines' asm blocks carry: passed on as it
                # is, for the effect builder to warn about (D3DX rejects it).
                self.out.append(text)
                self.smap.lines.append((path, i + 1))
                self.emit_blank(path, i + 2, used - 1)
                return i + used
            word = name or text[rest:].split()[0][:40]
            raise self.error(f"unknown preprocessor directive '#{word}'", hash_at)
        self.emit_blank(path, i + 1, used)
        return i + used

    def _inside_asm_block(self) -> bool:
        """Whether the text emitted so far ends inside an `asm { ...` block (asm bodies hold no
        braces, so: the last `asm {` has no `}` after it). Only asked for unknown directives."""
        tail = "\n".join(self.out[-400:])
        found = None
        for found in _ASM_OPEN.finditer(tail):
            pass
        return found is not None and "}" not in tail[found.end():]

    def conditional(self, unit: _File, name: str, text: str, rest: int, span: Span,
                    hash_at: Location) -> None:
        branches = unit.branches
        if name in ("if", "ifdef", "ifndef"):
            if not unit.active:
                branches.append(_Branch(name, hash_at, False, True))
                return
            if name == "if":
                value = evaluate_condition(text, rest, span, name, self.macros)
            else:
                word, at = word_after(text, rest)
                if word is None:
                    raise self.error(f"#{name} expects a macro name", span.location(at))
                value = (word in self.macros.defined) == (name == "ifdef")
            branches.append(_Branch(name, hash_at, True, value))
            unit.active = value
            return
        if not branches:
            raise self.error(f"#{name} without #if", hash_at)
        branch = branches[-1]
        if name == "endif":
            branches.pop()
            unit.active = branch.outer_active
            return
        if branch.seen_else:
            raise self.error(f"#{name} after #else", hash_at)
        if name == "else":
            branch.seen_else = True
            unit.active = branch.outer_active and not branch.taken
            branch.taken = True
            return
        # elif: evaluated only when no earlier branch of the group was taken
        if branch.outer_active and not branch.taken:
            unit.active = evaluate_condition(text, rest, span, name, self.macros)
            branch.taken = unit.active
        else:
            unit.active = False

    # ----------------------------------------------------------------- #include

    def include(self, unit: _File, text: str, rest: int, span: Span, hash_at: Location) -> None:
        at = BLANKS.match(text, rest).end()
        spec, name_at = text[at:].rstrip(), at
        if spec[:1] not in ('"', "<") and spec:  # #include MACRO
            spec = "".join(t.text for t in self.macros.expand(tokenize(text, at), span, 0, top=False)).strip()
        closing = {'"': '"', "<": ">"}.get(spec[:1])
        end = spec.find(closing, 1) if closing else -1
        if end < 0:
            raise self.error('#include expects "FILENAME" or <FILENAME>',
                             span.location(name_at) if spec else hash_at)
        name = spec[1:end]
        location = span.location(name_at)
        if not name:
            raise self.error("empty file name in #include", location)
        if unit.depth + 1 > MAX_INCLUDE_DEPTH:
            raise self.error(f"#include nested too deeply (more than {MAX_INCLUDE_DEPTH} levels)", location)
        path = self.resolve(name, closing == ">", unit.path, location)
        real = os.path.realpath(path)
        if real in self.once:
            self.emit_blank(unit.path, location.line, 1)
            return
        chain = [p for _, p in self.chain]
        if real in (r for r, _ in self.chain):
            start = [r for r, _ in self.chain].index(real)
            cycle = " -> ".join(chain[start:] + [path])
            raise self.error(f"#include cycle: {cycle}", location)
        # the budget of the whole load: each file including the next twice doubles per level
        self.include_count += 1
        if self.include_count > limits.get("include_count"):
            raise self.error(limits.message("include_count", self.include_count,
                                            "this load's #include list"), location)
        try:
            included = untrusted.read_text(path, f"include file '{name}'", PreprocessError,
                                           "source_bytes", location, latin1_fallback=True)
        except PreprocessError as exc:
            raise self.error(exc.message, location) from None
        self.included_bytes += len(included)
        if self.included_bytes > limits.get("included_bytes"):
            raise self.error(limits.message("included_bytes", self.included_bytes,
                                            "the text this load read through #include"), location)
        self.chain.append((real, path))
        self.run_file(included, path, unit.depth + 1, real, spliced=True)
        self.chain.pop()

    def resolve(self, name: str, angled: bool, including: str, location: Location) -> str:
        """The path of the file `#include name` means, checked against the include root."""
        if self.include_handler is not None:
            given = self.include_handler(name, including)
            if given is not None:
                given = os.fspath(given)
                if not os.path.isfile(given):
                    raise self.error(f"cannot open include file '{name}' (the include handler "
                                     f"gave '{given}')", location)
                return self._inside_root(given, name, location)
        local = name.replace("\\", "/") if os.sep == "/" else name  # "..\inc\x.fx" on POSIX
        if os.path.isabs(local):
            folders = [""]
        else:
            here = "." if _is_pseudo_path(including) else (os.path.dirname(including) or ".")
            folders = [*self.include_dirs, here] if angled else [here, *self.include_dirs]
        for folder in folders:
            candidate = os.path.normpath(os.path.join(folder, local))
            if not os.path.exists(candidate):
                # fxc ran on Windows, where `#include "Skin.fx"` opens skin.fx: the same file
                # under another letter case, when exactly one name in the folder matches
                other = _other_case(folder, local)
                if other is not None:
                    shown = os.path.relpath(other, folder) if folder else other
                    self.warnings.append((f"#include \"{name}\" opens '{shown}': the names "
                                          "differ in letter case (Windows file names do not)",
                                          location))
                    candidate = other
            if os.path.isfile(candidate):
                return self._inside_root(candidate, name, location)
            if os.path.exists(candidate) and not os.path.isdir(candidate):   # a FIFO, a device: say so
                try:
                    untrusted.check_regular(candidate, f"include file '{name}'", PreprocessError, location)
                except PreprocessError as exc:
                    raise self.error(exc.message, location) from None
        if os.path.isabs(local):
            raise self.error(f"cannot open include file '{name}'", location)
        searched = ", ".join(dict.fromkeys(folders))
        raise self.error(f"cannot open include file '{name}' (searched: {searched})", location)

    def _inside_root(self, path: str, name: str, location: Location) -> str:
        if self.root_real is None:
            return path
        real = os.path.realpath(path)
        try:
            inside = os.path.commonpath([self.root_real, real]) == self.root_real
        except ValueError:  # another drive on Windows
            inside = False
        if not inside:
            raise self.error(f"include '{name}' escapes the include root '{self.include_root}'", location)
        return path


# --------------------------------------------------------------------- entry point

def preprocess(text: str, path: str = "<string>", *, defines: Mapping[str, str] | None = None,
               include_dirs: Sequence[str] = (), include_handler: Callable[[str, str], str | None] | None = None,
               include_root: str | None = None) -> Preprocessed:
    """Preprocess effect source `text` read from `path` ("<string>" for text given directly).

    `defines` act as #define lines before line 1. `#include "x"` looks in the including
    file's folder, then `include_dirs`; `<x>` the other way round; `include_handler(name,
    including_path)` is asked first and may return the path to use. With `include_root`,
    every included file must lie inside that folder. Raises a located `PreprocessError`.
    """
    pre = _Preprocessor(include_dirs, include_handler, include_root)
    real = None if _is_pseudo_path(path) else os.path.realpath(path)
    if real is not None:
        pre.chain.append((real, path))
    # Expansion makes many small objects and no cycles: the cycle collector would only
    # rescan them (it tripled the time of large expansions), so it pauses meanwhile.
    collecting = gc.isenabled()
    gc.disable()
    try:
        if defines:
            pre.predefine(defines)
        pre.run_file(text, path, 0, real, spliced=False)
    finally:
        if collecting:
            gc.enable()
    return Preprocessed("\n".join(pre.out), pre.smap, tuple(pre.files), tuple(pre.pack_matrix),
                        tuple(pre.smap.warning_at(m, at) for m, at in pre.warnings))


# C's predefined macros, which fxc's preprocessor has (the reference's #line page: "the
# predefined macros __FILE__ and __LINE__"): the line in its file (#line is not followed
# here) and the file's name as a string. A string literal is left as it is.
_PREDEFINED = re.compile(r'"(?:[^"\\\n]|\\.)*"|\b__(LINE|FILE)__\b')


def predefined(line: str, path: str, number: int) -> str:
    """`line` with __LINE__ as `number` and __FILE__ as `path` in quotes."""
    def value(m: re.Match) -> str:
        if m.group(1) is None:
            return m.group(0)
        if m.group(1) == "LINE":
            return str(number)
        return '"' + path.replace("\\", "\\\\").replace('"', '\\"') + '"'
    return _PREDEFINED.sub(value, line)
