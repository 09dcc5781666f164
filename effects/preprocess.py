"""The effect-file preprocessor: comments, `#include`, `#define`, `#if` and macro expansion.

It runs before the lark parse and keeps one output line per input line: comments become
spaces (newlines kept), directive lines and skipped lines become empty lines, and an
`#include` line is replaced by the lines of the included file. So `SourceMap.lines` maps every
output line back to a file and line, and columns of untouched text stay where they were.

Macro expansion follows C's rules with hide sets (Prosser's algorithm): a macro is not
expanded again inside its own expansion; function-like macros take arguments with nested
parentheses (an argument list may continue on the following lines), `#` stringizes and `##`
pastes. It applies everywhere outside comments and string literals, `asm { }` blocks included.
`#if` expressions are C integer expressions evaluated here by a small parser, in signed
64-bit arithmetic (the `u` suffix is accepted but does not make a value unsigned).

Not done, on purpose: `'c'` character constants in `#if`, predefined macros (`__FILE__`,
`__LINE__`), a function-like macro name at the end of a line whose `(` is on the next line
(that name is left unexpanded). `#pragma` and `#line` are ignored, except `#pragma once`.

Bad input never hangs or overflows the stack: every limit below is a located `PreprocessError`.
"""
from __future__ import annotations

import bisect
import gc
import operator
import os
import re
from dataclasses import dataclass, field
from itertools import repeat
from typing import Callable, Mapping, NamedTuple, Sequence

from .errors import Location, PreprocessError
from .source import Preprocessed, SourceMap

MAX_INCLUDE_DEPTH = 64          # files open at once through #include
MAX_EXPANSION_TOKENS = 300_000  # tokens made by all macro expansions of one load together
MAX_MACRO_NESTING = 100         # macro calls inside macro arguments inside ...
MAX_EXPRESSION_NESTING = 64     # parentheses and ?: in an #if expression (C guarantees 63)
MAX_ARGUMENT_PARENS = 256       # parentheses open inside one macro call's arguments
MAX_TOKENIZED_CHARS = 200_000   # a directive, or a line needing the full macro algorithm

_NEWLINE = re.compile(r"\r\n?")
_COMMENT_OR_STRING = re.compile(r'"[^"\\\n]*(?:\\.[^"\\\n]*)*"?|//[^\n]*|/\*.*?(?:\*/|\Z)', re.S)
_TOKEN = re.compile(
    r'(?P<id>[A-Za-z_][A-Za-z0-9_]*)'
    r'|(?P<num>\.?[0-9](?:[eEpP][+-]|[A-Za-z0-9_.])*)'   # a C "pp-number": 1.5e-3f, 0x1F, 10u
    r'|(?P<str>"[^"\\\n]*(?:\\.[^"\\\n]*)*"?)'
    r'|(?P<ws>[ \t\f\v\n]+)'
    r'|(?P<punct>##|\.\.\.|<<|>>|<=|>=|==|!=|&&|\|\||.)', re.S)
_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_BLANKS = re.compile(r"[ \t\f\v]*")
_DIRECTIVE = re.compile(r"[ \t\f\v]*#[ \t\f\v]*([A-Za-z_][A-Za-z0-9_]*)?")
_INTEGER = re.compile(r"(0[xX][0-9a-fA-F]+|0[0-7]*|[1-9][0-9]*)(?:[uU](?:ll|LL|[lL])?|(?:ll|LL|[lL])[uU]?)?")
_CONDITIONALS = frozenset({"if", "ifdef", "ifndef", "elif", "else", "endif"})
_NO_HIDE: frozenset[str] = frozenset()


class _Tok(NamedTuple):
    text: str
    kind: str             # "id", "num", "str", "ws", "punct", or "mark" (an empty ## operand)
    hide: frozenset[str]  # macros that must not expand this token (C's hide set)
    pos: int              # offset in the span where it (or the macro call it came from) stands


def _tokenize(text: str, start: int = 0, hide: frozenset[str] = _NO_HIDE, pos: int | None = None) -> list[_Tok]:
    """Tokens of text[start:]; positions are offsets into `text`, or all `pos` when given."""
    return [_Tok(m.group(), m.lastgroup, hide, m.start() if pos is None else pos)
            for m in _TOKEN.finditer(text, start)]


def _strip(tokens: list[_Tok]) -> list[_Tok]:
    lo, hi = 0, len(tokens)
    while lo < hi and tokens[lo].kind == "ws":
        lo += 1
    while hi > lo and tokens[hi - 1].kind == "ws":
        hi -= 1
    return tokens[lo:hi]


@dataclass
class _Span:
    """Physical lines joined into one logical text, with the way back to line:column."""

    path: str
    text: str
    starts: list[int]  # offset in `text` where each physical line's part begins
    lines: list[int]   # 1-based line number of each part

    def location(self, offset: int) -> Location:
        k = max(bisect.bisect_right(self.starts, offset) - 1, 0)
        return Location(self.path, self.lines[k], offset - self.starts[k] + 1)


@dataclass(frozen=True)
class _Macro:
    name: str
    params: tuple[str, ...] | None       # None: object-like
    body: tuple[tuple[str, str], ...]    # (text, kind); whitespace runs are one " "
    variadic: bool = False
    index: dict[str, int] = field(default_factory=dict)  # parameter name -> position


@dataclass
class _Branch:
    """One open #if group."""

    directive: str
    location: Location
    outer_active: bool
    taken: bool          # a branch of this group has been chosen already
    seen_else: bool = False


@dataclass
class _File:
    path: str
    real: str | None     # realpath, for cycle checks and #pragma once; None for text
    lines: list[str]
    depth: int
    branches: list[_Branch] = field(default_factory=list)
    active: bool = True


class _NeedMoreInput(Exception):
    """A macro's argument list is still open at the end of the text given."""

    def __init__(self, pos: int, name: str, open_parens: int) -> None:
        self.pos, self.name, self.open_parens = pos, name, open_parens


class _NameSetFinder:
    """Stands in for the compiled macro-name regex when there are very many macros."""

    _word = re.compile(r"(?<![A-Za-z0-9_])[A-Za-z_][A-Za-z0-9_]*")

    def __init__(self, names: Mapping[str, object]) -> None:
        self.names = names

    def search(self, line: str):
        return next(self.finditer(line), None)

    def finditer(self, line: str):
        return (m for m in self._word.finditer(line) if m.group() in self.names)

    def sub(self, replace, line: str) -> str:
        return self._word.sub(lambda m: replace(m) if m.group() in self.names else m.group(), line)


def _is_pseudo_path(path: str) -> bool:
    return path.startswith("<") and path.endswith(">")


def _read_text(path: str) -> str:
    with open(path, "rb") as f:
        data = f.read()
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return data.decode("latin-1")  # every byte is one character: a stray byte survives


class _Preprocessor:
    def __init__(self, include_dirs: Sequence[str], include_handler, include_root: str | None) -> None:
        self.include_dirs = [os.fspath(d) for d in include_dirs]
        self.include_handler = include_handler
        self.include_root = None if include_root is None else os.fspath(include_root)
        self.root_real = None if include_root is None else os.path.realpath(self.include_root)
        self.macros: dict[str, _Macro] = {}
        self.smap = SourceMap()
        self.out: list[str] = []
        self.files: list[str] = []
        self.chain: list[tuple[str, str]] = []  # (realpath, path) of the files being included
        self.once: set[str] = set()
        self.budget = MAX_EXPANSION_TOKENS
        self._pattern = None
        self._pattern_builds = 0
        self._hides: dict[tuple[frozenset[str], str], frozenset[str]] = {}
        self._flat: dict[str, tuple[str, int] | None] = {}  # object-like macro -> (text, tokens)

    def error(self, message: str, location: Location) -> PreprocessError:
        return self.smap.error_at(PreprocessError, message, location)

    # ----------------------------------------------------------------- files and lines

    def predefine(self, defines: Mapping[str, str]) -> None:
        """`defines` act like #define lines before line 1; errors point into "<defines>"."""
        texts = []
        for name, value in defines.items():
            value = "1" if value is None else str(value)
            texts.append(f"{name} {value}".replace("\r", " ").replace("\n", " "))
        self.smap.texts["<defines>"] = texts
        for number, text in enumerate(texts, 1):
            self.define(text, 0, _Span("<defines>", text, [0], [number]))

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
        unit = _File(path, real, lines, depth)
        out, line_map = self.out, self.smap.lines
        if not self.macros and "#" not in text:  # fast path: nothing to do but map lines
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
            elif self.macros:
                match = self.macro_pattern().search(line)
                if match is not None:
                    used = self.expand_lines(unit, i, match.start())
                    i += used
                    continue
            out.append(line)
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
        span = _Span(path, text, starts, numbers)
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
            self.define(text, rest, span)
        elif name == "undef":
            word, at = self._word_after(text, rest)
            if word is None:
                raise self.error("#undef expects a macro name", span.location(at))
            if self.macros.pop(word, None) is not None:
                self.macros_changed()
        elif name == "error":
            message = text[rest:].strip()
            raise self.error(f"#error {message}" if message else "#error", hash_at)
        elif name == "pragma":
            if text[rest:].split() == ["once"] and unit.real is not None:
                self.once.add(unit.real)
        elif name == "line":
            pass  # kept as an empty line: our own map already knows where every line came from
        elif name or text[rest:].strip():
            word = name or text[rest:].split()[0][:40]
            raise self.error(f"unknown preprocessor directive '#{word}'", hash_at)
        self.emit_blank(path, i + 1, used)
        return i + used

    @staticmethod
    def _word_after(text: str, pos: int) -> tuple[str | None, int]:
        pos = _BLANKS.match(text, pos).end()
        match = _IDENT.match(text, pos)
        return (match.group() if match else None), pos

    def conditional(self, unit: _File, name: str, text: str, rest: int, span: _Span,
                    hash_at: Location) -> None:
        branches = unit.branches
        if name in ("if", "ifdef", "ifndef"):
            if not unit.active:
                branches.append(_Branch(name, hash_at, False, True))
                return
            if name == "if":
                value = self.condition(text, rest, span, name)
            else:
                word, at = self._word_after(text, rest)
                if word is None:
                    raise self.error(f"#{name} expects a macro name", span.location(at))
                value = (word in self.macros) == (name == "ifdef")
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
            unit.active = self.condition(text, rest, span, name)
            branch.taken = unit.active
        else:
            unit.active = False

    def condition(self, text: str, rest: int, span: _Span, directive: str) -> bool:
        tokens = _tokenize(text, rest)
        # The operand of `defined` is a name, not something to expand: hide it from itself.
        for k, tok in enumerate(tokens):
            if tok.kind == "id" and tok.text == "defined":
                k = self._next_solid(tokens, k + 1)
                if k < len(tokens) and tokens[k].text == "(":
                    k = self._next_solid(tokens, k + 1)
                if k < len(tokens) and tokens[k].kind == "id":
                    tokens[k] = tokens[k]._replace(hide=frozenset((tokens[k].text,)))
        tokens = [t for t in self.expand(tokens, span, 0, top=False) if t.kind != "ws"]
        if not tokens:
            raise self.error(f"#{directive} with no expression", span.location(rest))
        try:
            return _Expression(tokens, self, span, directive).value() != 0
        except RecursionError:
            raise self.error(f"#{directive} expression nests too deeply",
                             span.location(tokens[0].pos)) from None

    @staticmethod
    def _next_solid(tokens: list[_Tok], k: int) -> int:
        while k < len(tokens) and tokens[k].kind == "ws":
            k += 1
        return k

    # ----------------------------------------------------------------- #define

    def define(self, text: str, rest: int, span: _Span) -> None:
        name, at = self._word_after(text, rest)
        if name is None:
            message = "macro name missing" if not text[at:].strip() else "macro names must be identifiers"
            raise self.error(message, span.location(at))
        if name == "defined":
            raise self.error("'defined' cannot be used as a macro name", span.location(at))
        pos = at + len(name)
        params: tuple[str, ...] | None = None
        variadic = False
        if text.startswith("(", pos):
            close = text.find(")", pos)
            bad = lambda: self.error(f"malformed parameter list for macro '{name}'", span.location(pos))
            if close < 0:
                raise bad()
            inner = text[pos + 1:close]
            items = [item.strip() for item in inner.split(",")] if inner.strip() else []
            names: dict[str, None] = {}  # ordered, and a fast membership test
            for k, item in enumerate(items):
                if item == "..." and k == len(items) - 1:
                    variadic = True
                    item = "__VA_ARGS__"
                elif not _IDENT.fullmatch(item):
                    raise bad()
                if item in names:
                    raise self.error(f"duplicate macro parameter '{item}'", span.location(pos))
                names[item] = None
            params = tuple(names)
            pos = close + 1
        tokens = _strip(_tokenize(text, pos))
        if tokens and ("##" in (tokens[0].text, tokens[-1].text)):
            edge = tokens[0] if tokens[0].text == "##" else tokens[-1]
            raise self.error("'##' cannot appear at either end of a macro expansion",
                             span.location(edge.pos))
        if params is not None:
            for k, tok in enumerate(tokens):
                if tok.text == "#":
                    nxt = self._next_solid(tokens, k + 1)
                    if nxt >= len(tokens) or tokens[nxt].text not in params:
                        raise self.error("'#' is not followed by a macro parameter",
                                         span.location(tok.pos))
        body = tuple((" ", "ws") if t.kind == "ws" else (t.text, t.kind) for t in tokens)
        index = {p: k for k, p in enumerate(params or ())}
        self.macros[name] = _Macro(name, params, body, variadic, index)
        self.macros_changed()

    def macros_changed(self) -> None:
        self._pattern = None
        self._flat = {}

    def macro_pattern(self):
        """A regex finding any defined macro name in a line (the filter before tokenizing)."""
        if self._pattern is None:
            if len(self.macros) <= 200 and self._pattern_builds < 50:
                self._pattern_builds += 1
                names = "|".join(map(re.escape, self.macros))
                self._pattern = re.compile(rf"\b(?:{names})\b", re.ASCII)
            else:  # many macros, or defines interleaved with text: don't recompile every time
                self._pattern = _NameSetFinder(self.macros)
        return self._pattern

    # ----------------------------------------------------------------- macro expansion

    def expand_lines(self, unit: _File, i: int, first_name: int) -> int:
        """Expand macros in line i (and following lines an argument list runs into);
        emits one output line per line used and returns how many were used."""
        lines = unit.lines
        line = lines[i]
        simple = self._expand_simple(line, unit.path, i + 1)
        if simple is not None:
            self.out.append(simple)
            self.smap.lines.append((unit.path, i + 1))
            return 1
        # Tokenize from the whitespace before the first macro name: a token never spans a
        # blank, so the text before it can be kept as it is (unless a string starts there).
        start = max(line.rfind(" ", 0, first_name), line.rfind("\t", 0, first_name)) + 1
        if '"' in line[:start]:
            start = 0
        count, calling = 1, None
        while True:
            chunk = "\n".join(lines[i:i + count]) if count > 1 else line
            starts, offset = [], 0
            for k in range(count):
                starts.append(offset)
                offset += len(lines[i + k]) + 1
            span = _Span(unit.path, chunk, starts, list(range(i + 1, i + count + 1)))
            if len(chunk) - start > MAX_TOKENIZED_CHARS:
                what = "line" if calling is None else f"argument list of macro '{calling.name}'"
                raise self.error(f"{what} too long for macro expansion ({len(chunk) - start} characters; "
                                 f"the limit is {MAX_TOKENIZED_CHARS})",
                                 span.location(first_name if calling is None else calling.pos))
            budget = self.budget
            try:
                tokens = self.expand(_tokenize(chunk, start), span, 0, top=True)
                break
            except _NeedMoreInput as need:
                self.budget, calling = budget, need
                added = self._lines_to_close(unit, i + count, need.open_parens)
                if added == 0:
                    raise self.error(f"unterminated argument list invoking macro '{need.name}'",
                                     span.location(need.pos)) from None
                count += added
        text = line[:start] + "".join(t.text for t in tokens)
        if count > 1:  # the call's lines become one output line; the others stay empty
            text = text.replace("\n", " ")
        self.out.append(text)
        self.smap.lines.append((unit.path, i + 1))
        self.emit_blank(unit.path, i + 2, count - 1)
        return count

    def _expand_simple(self, line: str, path: str, number: int) -> str | None:
        """The line with each object-like macro replaced by its full expansion (computed once),
        or None when the line needs the general algorithm: it has a string literal or a
        function-like macro, a name may be part of a number (`1.X`, `1e+X`), or an expansion
        ends in a function-like macro's name that could take arguments from the line."""
        if '"' in line:
            return None
        pattern, flat, macros = self.macro_pattern(), self._flat, self.macros
        tokens = 0
        for match in pattern.finditer(line):
            name, start = match.group(), match.start()
            before = line[start - 1] if start else " "
            if before == "." or (before in "+-" and start > 1 and line[start - 2] in "eEpP"):
                return None
            if name not in flat:
                flat[name] = None
                if macros[name].params is None:
                    span = _Span(path, line, [0], [number])
                    expansion = self.expand([_Tok(name, "id", _NO_HIDE, start)], span, 0, top=False)
                    if not any(t.kind == "id" and t.text in macros and t.text not in t.hide
                               and macros[t.text].params is not None for t in expansion):
                        flat[name] = ("".join(t.text for t in expansion), len(expansion))
            if flat[name] is None:
                return None
            tokens += flat[name][1]
            if tokens > self.budget:
                raise self.error(f"expansion of macro '{name}' is too large "
                                 f"(more than {MAX_EXPANSION_TOKENS} tokens)", Location(path, number, start + 1))
        self.budget -= tokens
        return pattern.sub(lambda m: flat[m.group()][0], line)

    @staticmethod
    def _lines_to_close(unit: _File, k: int, open_parens: int) -> int:
        """How many lines from index k it takes (roughly) to close `open_parens` parentheses;
        0 when the file ends or a directive comes first."""
        lines, added = unit.lines, 0
        while k < len(lines) and open_parens > 0:
            line = lines[k]
            if line.lstrip(" \t\f\v").startswith("#"):
                break
            open_parens += line.count("(") - line.count(")")
            k += 1
            added += 1
        return added

    def expand(self, tokens: list[_Tok], span: _Span, depth: int, top: bool) -> list[_Tok]:
        """C macro expansion of `tokens` (rescanning each expansion with what follows it)."""
        if depth > MAX_MACRO_NESTING:
            raise self.error("macro arguments nest too deeply", span.location(tokens[0].pos))
        macros = self.macros
        out: list[_Tok] = []
        stack = tokens[::-1]  # the next token is at the end
        while stack:
            tok = stack.pop()
            name = tok.text
            if tok.kind != "id" or name in tok.hide or name not in macros:
                out.append(tok)
                continue
            macro = macros[name]
            if macro.params is None:
                body = self.substitute(macro, None, self._hide(tok.hide, name), tok.pos, span, depth)
                stack.extend(reversed(body))
                continue
            j = len(stack) - 1
            while j >= 0 and stack[j].kind == "ws":
                j -= 1
            if j < 0 or stack[j].text != "(":
                out.append(tok)  # a function-like macro's name without arguments stays a name
                continue
            args, close = self._collect_args(stack, j, tok, span, top)
            args = self._check_arity(macro, args, tok, span)
            hide = self._hide(tok.hide & close.hide, name)
            stack.extend(reversed(self.substitute(macro, args, hide, tok.pos, span, depth)))
        return out

    def _hide(self, hide: frozenset[str], name: str) -> frozenset[str]:
        """hide ∪ {name}, shared between tokens (building sets was most of deep expansions' time)."""
        key = (hide, name)
        result = self._hides.get(key)
        if result is None:
            result = self._hides[key] = hide | {name}
        return result

    def _collect_args(self, stack: list[_Tok], j: int, tok: _Tok, span: _Span,
                      top: bool) -> tuple[list[list[_Tok]], _Tok]:
        level, args, k = 0, [[]], j - 1
        while k >= 0:
            t = stack[k]
            if t.kind == "punct":
                if t.text == "(":
                    level += 1
                    if level > MAX_ARGUMENT_PARENS:
                        raise self.error("macro arguments nest too deeply", span.location(tok.pos))
                elif t.text == ")":
                    if level == 0:
                        break
                    level -= 1
                elif t.text == "," and level == 0:
                    args.append([])
                    k -= 1
                    continue
            args[-1].append(t)
            k -= 1
        if k < 0:
            if top:
                raise _NeedMoreInput(tok.pos, tok.text, level + 1)
            raise self.error(f"unterminated argument list invoking macro '{tok.text}'",
                             span.location(tok.pos))
        close = stack[k]
        del stack[k:]
        return [_strip(arg) for arg in args], close

    def _check_arity(self, macro: _Macro, args: list[list[_Tok]], tok: _Tok,
                     span: _Span) -> list[list[_Tok]]:
        wanted = len(macro.params)
        if wanted == 0 and len(args) == 1 and not args[0]:
            return []
        if macro.variadic:
            if len(args) > wanted:  # the extra arguments, commas and all, are __VA_ARGS__
                merged = args[wanted - 1]
                for extra in args[wanted:]:
                    merged = merged + [_Tok(",", "punct", _NO_HIDE, tok.pos), _Tok(" ", "ws", _NO_HIDE, tok.pos)] + extra
                args = args[:wanted - 1] + [merged]
            elif len(args) == wanted - 1:
                args = args + [[]]
        if len(args) != wanted:
            plural = "" if wanted == 1 else "s"
            raise self.error(f"macro '{macro.name}' expects {wanted} argument{plural}, got {len(args)}",
                             span.location(tok.pos))
        return args

    def substitute(self, macro: _Macro, args: list[list[_Tok]] | None, hide: frozenset[str],
                   pos: int, span: _Span, depth: int) -> list[_Tok]:
        """The macro's body with arguments put in, `#` and `##` applied, `hide` added."""
        body = macro.body
        index = macro.index if args is not None else {}
        expanded: dict[int, list[_Tok]] = {}
        res: list[_Tok] = []
        n = len(body)
        i = 0

        def pasted_operand(k: int) -> list[_Tok]:
            text, kind = body[k]
            if kind == "id" and text in index:
                return list(args[index[text]]) or [_Tok("", "mark", hide, pos)]
            return [_Tok(text, kind, hide, pos)]

        while i < n:
            text, kind = body[i]
            if text == "#" and args is not None:
                k = self._next_body(body, i + 1)
                res.append(_Tok(_stringize(args[index[body[k][0]]]), "str", hide, pos))
                i = k + 1
            elif text == "##":
                k = self._next_body(body, i + 1)
                while res and res[-1].kind == "ws":
                    res.pop()
                left = res.pop()
                res.extend(self._paste(left, pasted_operand(k), hide, pos))
                i = k + 1
            elif kind == "id" and text in index:
                k = self._next_body(body, i + 1)
                if k < n and body[k][0] == "##":
                    res.extend(pasted_operand(i))
                else:
                    p = index[text]
                    if p not in expanded:
                        expanded[p] = self.expand(args[p], span, depth + 1, top=False) if args[p] else []
                    res.extend(expanded[p])
                i += 1
            else:
                res.append(_Tok(text, kind, hide, pos))
                i += 1
            if len(res) > self.budget:
                raise self.error(f"expansion of macro '{macro.name}' is too large "
                                 f"(more than {MAX_EXPANSION_TOKENS} tokens)", span.location(pos))
        self.budget -= len(res)
        return [t if t.hide is hide else t._replace(hide=t.hide | hide)
                for t in res if t.kind != "mark"]

    @staticmethod
    def _next_body(body: tuple[tuple[str, str], ...], k: int) -> int:
        while k < len(body) and body[k][1] == "ws":
            k += 1
        return k

    @staticmethod
    def _paste(left: _Tok, right: list[_Tok], hide: frozenset[str], pos: int) -> list[_Tok]:
        if left.kind == "mark":
            return right
        if right[0].kind == "mark":
            return [left] + right[1:]
        return _tokenize(left.text + right[0].text, 0, hide, pos) + right[1:]

    # ----------------------------------------------------------------- #include

    def include(self, unit: _File, text: str, rest: int, span: _Span, hash_at: Location) -> None:
        at = _BLANKS.match(text, rest).end()
        spec, name_at = text[at:].rstrip(), at
        if spec[:1] not in ('"', "<") and spec:  # #include MACRO
            spec = "".join(t.text for t in self.expand(_tokenize(text, at), span, 0, top=False)).strip()
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
        try:
            included = _read_text(path)
        except OSError as exc:
            raise self.error(f"cannot read include file '{name}': {exc.strerror}", location) from None
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
            if os.path.isfile(candidate):
                return self._inside_root(candidate, name, location)
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


def _stringize(arg: list[_Tok]) -> str:
    parts = []
    for t in arg:
        if t.kind == "ws":
            parts.append(" ")
        elif t.kind == "str":
            parts.append(t.text.replace("\\", "\\\\").replace('"', '\\"'))
        else:
            parts.append(t.text)
    return '"' + "".join(parts).strip() + '"'


# --------------------------------------------------------------------- #if expressions

_BINARY_PRECEDENCE = {"||": 1, "&&": 2, "|": 3, "^": 4, "&": 5, "==": 6, "!=": 6,
                      "<": 7, ">": 7, "<=": 7, ">=": 7, "<<": 8, ">>": 8,
                      "+": 9, "-": 9, "*": 10, "/": 10, "%": 10}
_UNARY = frozenset({"!", "~", "-", "+"})
_ARITHMETIC = {"+": operator.add, "-": operator.sub, "*": operator.mul, "|": operator.or_,
               "^": operator.xor, "&": operator.and_, "==": operator.eq, "!=": operator.ne,
               "<": operator.lt, ">": operator.gt, "<=": operator.le, ">=": operator.ge}


def _int64(value: int) -> int:
    value &= (1 << 64) - 1
    return value - (1 << 64) if value >= 1 << 63 else value


class _Expression:
    """Precedence climbing over the tokens of an #if line; never Python's eval.

    `live` is False inside the operand C does not evaluate (`0 && x`, `1 || x`, the unused
    arm of `?:`), where division by zero is no error.
    """

    def __init__(self, tokens: list[_Tok], pre: _Preprocessor, span: _Span, directive: str) -> None:
        self.tokens, self.pre, self.span = tokens, pre, span
        self.where = f"#{directive} expression"
        self.i = 0

    def fail(self, message: str, tok: _Tok | None = None) -> PreprocessError:
        """An error at `tok`, or just after the end of the line without one."""
        pos = tok.pos if tok is not None else len(self.span.text.rstrip())
        return self.pre.error(message, self.span.location(pos))

    def peek(self) -> str | None:
        if self.i < len(self.tokens):
            tok = self.tokens[self.i]
            return tok.text if tok.kind == "punct" else None
        return None

    def value(self) -> int:
        result = self.conditional(True, 0)
        if self.i < len(self.tokens):
            tok = self.tokens[self.i]
            raise self.fail(f"unexpected '{tok.text[:40]}' in {self.where}", tok)
        return result

    def conditional(self, live: bool, nesting: int) -> int:
        if nesting > MAX_EXPRESSION_NESTING:
            raise self.fail(f"{self.where} nests too deeply", self.tokens[self.i - 1])  # at ( ? or :
        cond = self.binary(1, live, nesting)
        if self.peek() != "?":
            return cond
        self.i += 1
        then = self.conditional(live and cond != 0, nesting + 1)
        self.expect(":")
        other = self.conditional(live and cond == 0, nesting + 1)
        return then if cond != 0 else other

    def expect(self, text: str) -> None:
        if self.peek() != text:
            tok = self.tokens[self.i] if self.i < len(self.tokens) else None
            raise self.fail(f"expected '{text}' in {self.where}", tok)
        self.i += 1

    def binary(self, min_precedence: int, live: bool, nesting: int) -> int:
        left = self.unary(live, nesting)
        while True:
            op = self.peek()
            precedence = _BINARY_PRECEDENCE.get(op)
            if precedence is None or precedence < min_precedence:
                return left
            op_tok = self.tokens[self.i]
            self.i += 1
            if op == "&&":
                right = self.binary(precedence + 1, live and left != 0, nesting)
                left = int(left != 0 and right != 0)
            elif op == "||":
                right = self.binary(precedence + 1, live and left == 0, nesting)
                left = int(left != 0 or right != 0)
            else:
                right = self.binary(precedence + 1, live, nesting)
                left = self.apply(op, left, right, live, op_tok)

    def apply(self, op: str, a: int, b: int, live: bool, tok: _Tok) -> int:
        if op in ("/", "%"):
            if b == 0:
                if live:
                    raise self.fail(f"division by zero in {self.where}", tok)
                return 0
            quotient = abs(a) // abs(b) * (1 if (a < 0) == (b < 0) else -1)  # C truncates
            return _int64(quotient if op == "/" else a - b * quotient)
        if op in ("<<", ">>"):
            if b < 0:
                if live:
                    raise self.fail(f"negative shift count in {self.where}", tok)
                return 0
            b = min(b, 64)
            return _int64(a << b if op == "<<" else a >> b)
        return _int64(int(_ARITHMETIC[op](a, b)))

    def unary(self, live: bool, nesting: int) -> int:
        ops = []
        while self.peek() in _UNARY:
            ops.append(self.tokens[self.i].text)
            self.i += 1
        value = self.primary(live, nesting)
        for op in reversed(ops):
            value = int(value == 0) if op == "!" else ~value if op == "~" else _int64(-value) if op == "-" else value
        return value

    def primary(self, live: bool, nesting: int) -> int:
        if self.i >= len(self.tokens):
            raise self.fail(f"unexpected end of {self.where}")
        tok = self.tokens[self.i]
        if tok.kind == "punct" and tok.text == "(":
            self.i += 1
            value = self.conditional(live, nesting + 1)
            self.expect(")")
            return value
        if tok.kind == "num":
            match = _INTEGER.fullmatch(tok.text)
            if match is None:
                raise self.fail(f"invalid integer constant '{tok.text[:40]}' in {self.where}", tok)
            digits = match.group(1)
            base = 16 if digits[:2] in ("0x", "0X") else 8 if len(digits) > 1 and digits[0] == "0" else 10
            self.i += 1
            return _int64(int(digits, base))
        if tok.kind == "id":
            self.i += 1
            if tok.text != "defined":
                return 0  # an identifier left after expansion counts as 0, as in C
            parens = self.peek() == "("
            if parens:
                self.i += 1
            if self.i >= len(self.tokens) or self.tokens[self.i].kind != "id":
                raise self.fail("'defined' expects a macro name",
                                self.tokens[self.i] if self.i < len(self.tokens) else None)
            name = self.tokens[self.i].text
            self.i += 1
            if parens:
                self.expect(")")
            return int(name in self.pre.macros)
        raise self.fail(f"unexpected '{tok.text[:40]}' in {self.where}", tok)


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
    return Preprocessed("\n".join(pre.out), pre.smap, tuple(pre.files))
