"""C macros: `#define` parsing, and expansion with hide sets (Prosser's algorithm).

A macro is not expanded again inside its own expansion; function-like macros take
arguments with nested parentheses (an argument list may continue on the following lines),
`#` stringizes and `##` pastes. The driver applies it everywhere outside comments and
string literals, `asm { }` blocks included.

Not done here: the predefined `__FILE__` and `__LINE__` (the driver, preprocess.predefined,
replaces them per line). Not done, on purpose: a function-like macro name
at the end of a line whose `(` is on the next line (that name is left unexpanded).
Every limit below is a located `PreprocessError`, never a hang or a stack overflow.
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Callable, Mapping

from effects.base.errors import Location, PreprocessError
from effects.frontend.preprocess_tokens import (IDENT, MAX_TOKENIZED_CHARS, NO_HIDE, Span, Token, next_solid,
                                strip_blanks, tokenize, word_after)

MAX_EXPANSION_TOKENS = 300_000  # tokens made by all macro expansions of one load together
MAX_MACRO_NESTING = 100         # macro calls inside macro arguments inside ...
MAX_ARGUMENT_PARENS = 256       # parentheses open inside one macro call's arguments


@dataclass(frozen=True)
class Macro:
    name: str
    params: tuple[str, ...] | None       # None: object-like
    body: tuple[tuple[str, str], ...]    # (text, kind); whitespace runs are one " "
    variadic: bool = False
    index: dict[str, int] = field(default_factory=dict)  # parameter name -> position


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


class MacroTable:
    """The macros defined so far, and C macro expansion with them.

    `budget` is what is left of MAX_EXPANSION_TOKENS for the whole load; `error(message,
    location)` makes the located `PreprocessError` the driver raises.
    """

    def __init__(self, error: Callable[[str, Location], PreprocessError]) -> None:
        self.error = error
        self.defined: dict[str, Macro] = {}
        self.budget = MAX_EXPANSION_TOKENS
        self._pattern = None
        self._pattern_builds = 0
        self._hides: dict[tuple[frozenset[str], str], frozenset[str]] = {}
        self._flat: dict[str, tuple[str, int] | None] = {}  # object-like macro -> (text, tokens)

    # ----------------------------------------------------------------- #define and #undef

    def define(self, text: str, rest: int, span: Span) -> None:
        name, at = word_after(text, rest)
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
                elif not IDENT.fullmatch(item):
                    raise bad()
                if item in names:
                    raise self.error(f"duplicate macro parameter '{item}'", span.location(pos))
                names[item] = None
            params = tuple(names)
            pos = close + 1
        tokens = strip_blanks(tokenize(text, pos))
        if tokens and ("##" in (tokens[0].text, tokens[-1].text)):
            edge = tokens[0] if tokens[0].text == "##" else tokens[-1]
            raise self.error("'##' cannot appear at either end of a macro expansion",
                             span.location(edge.pos))
        if params is not None:
            for k, tok in enumerate(tokens):
                if tok.text == "#":
                    nxt = next_solid(tokens, k + 1)
                    if nxt >= len(tokens) or tokens[nxt].text not in params:
                        raise self.error("'#' is not followed by a macro parameter",
                                         span.location(tok.pos))
        body = tuple((" ", "ws") if t.kind == "ws" else (t.text, t.kind) for t in tokens)
        index = {p: k for k, p in enumerate(params or ())}
        self.defined[name] = Macro(name, params, body, variadic, index)
        self.changed()

    def undef(self, name: str) -> None:
        if self.defined.pop(name, None) is not None:
            self.changed()

    def changed(self) -> None:
        self._pattern = None
        self._flat = {}

    def pattern(self):
        """A regex finding any defined macro name in a line (the filter before tokenizing)."""
        if self._pattern is None:
            if len(self.defined) <= 200 and self._pattern_builds < 50:
                self._pattern_builds += 1
                names = "|".join(map(re.escape, self.defined))
                self._pattern = re.compile(rf"\b(?:{names})\b", re.ASCII)
            else:  # many macros, or defines interleaved with text: don't recompile every time
                self._pattern = _NameSetFinder(self.defined)
        return self._pattern

    # ----------------------------------------------------------------- macro expansion

    def expand_lines(self, lines: list[str], i: int, first_name: int,
                     path: str) -> tuple[str, int, tuple]:
        """Expand macros in lines[i] (and following lines an argument list runs into), whose
        first macro name starts at column index `first_name`. Returns the expanded text, one
        output line, how many lines it used (the caller leaves the others empty), and where
        its pieces came from (`effects.base.errors.through_expansion`), so that an error in
        the expanded text is placed at the macro call or the argument it is in."""
        line = lines[i]
        simple = self._expand_simple(line, path, i + 1)
        if simple is not None:
            pieces: list[tuple[int, int, int, bool]] = []
            out = prev = 0     # the made text's length so far; the end of the last name
            for match in self.pattern().finditer(line):
                a, b = match.span()
                if a > prev:
                    pieces.append((out + 1, i + 1, prev + 1, True))
                    out += a - prev
                pieces.append((out + 1, i + 1, a + 1, False))
                out += len(self._flat[match.group()][0])
                prev = b
            if prev < len(line):
                pieces.append((out + 1, i + 1, prev + 1, True))
            return simple, 1, tuple(pieces)
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
            span = Span(path, chunk, starts, list(range(i + 1, i + count + 1)))
            if len(chunk) - start > MAX_TOKENIZED_CHARS:
                what = "line" if calling is None else f"argument list of macro '{calling.name}'"
                raise self.error(f"{what} too long for macro expansion ({len(chunk) - start} characters; "
                                 f"the limit is {MAX_TOKENIZED_CHARS})",
                                 span.location(first_name if calling is None else calling.pos))
            budget = self.budget
            try:
                tokens = self.expand(tokenize(chunk, start), span, 0, top=True)
                break
            except _NeedMoreInput as need:
                self.budget, calling = budget, need
                added = self._lines_to_close(lines, i + count, need.open_parens)
                if added == 0:
                    raise self.error(f"unterminated argument list invoking macro '{need.name}'",
                                     span.location(need.pos)) from None
                count += added
        text = line[:start] + "".join(t.text for t in tokens)
        if count > 1:  # the call's lines become one output line; the others stay empty
            text = text.replace("\n", " ")
        return text, count, _pieces(tokens, span, chunk, start, i + 1)

    def _expand_simple(self, line: str, path: str, number: int) -> str | None:
        """The line with each object-like macro replaced by its full expansion (computed once),
        or None when the line needs the general algorithm: it has a string literal or a
        function-like macro, a name may be part of a number (`1.X`, `1e+X`), or an expansion
        ends in a function-like macro's name that could take arguments from the line."""
        if '"' in line:
            return None
        pattern, flat, macros = self.pattern(), self._flat, self.defined
        tokens = 0
        for match in pattern.finditer(line):
            name, start = match.group(), match.start()
            before = line[start - 1] if start else " "
            if before == "." or (before in "+-" and start > 1 and line[start - 2] in "eEpP"):
                return None
            if name not in flat:
                flat[name] = None
                if macros[name].params is None:
                    span = Span(path, line, [0], [number])
                    expansion = self.expand([Token(name, "id", NO_HIDE, start)], span, 0, top=False)
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
    def _lines_to_close(lines: list[str], k: int, open_parens: int) -> int:
        """How many lines from index k it takes (roughly) to close `open_parens` parentheses;
        0 when the file ends or a directive comes first."""
        added = 0
        while k < len(lines) and open_parens > 0:
            line = lines[k]
            if line.lstrip(" \t\f\v").startswith("#"):
                break
            open_parens += line.count("(") - line.count(")")
            k += 1
            added += 1
        return added

    def expand(self, tokens: list[Token], span: Span, depth: int, top: bool) -> list[Token]:
        """C macro expansion of `tokens` (rescanning each expansion with what follows it)."""
        if depth > MAX_MACRO_NESTING:
            raise self.error("macro arguments nest too deeply", span.location(tokens[0].pos))
        macros = self.defined
        out: list[Token] = []
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

    def _collect_args(self, stack: list[Token], j: int, tok: Token, span: Span,
                      top: bool) -> tuple[list[list[Token]], Token]:
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
        return [strip_blanks(arg) for arg in args], close

    def _check_arity(self, macro: Macro, args: list[list[Token]], tok: Token,
                     span: Span) -> list[list[Token]]:
        wanted = len(macro.params)
        if wanted == 0 and len(args) == 1 and not args[0]:
            return []
        if macro.variadic:
            if len(args) > wanted:  # the extra arguments, commas and all, are __VA_ARGS__
                merged = args[wanted - 1]
                for extra in args[wanted:]:
                    merged = merged + [Token(",", "punct", NO_HIDE, tok.pos), Token(" ", "ws", NO_HIDE, tok.pos)] + extra
                args = args[:wanted - 1] + [merged]
            elif len(args) == wanted - 1:
                args = args + [[]]
        if len(args) != wanted:
            plural = "" if wanted == 1 else "s"
            raise self.error(f"macro '{macro.name}' expects {wanted} argument{plural}, got {len(args)}",
                             span.location(tok.pos))
        return args

    def substitute(self, macro: Macro, args: list[list[Token]] | None, hide: frozenset[str],
                   pos: int, span: Span, depth: int) -> list[Token]:
        """The macro's body with arguments put in, `#` and `##` applied, `hide` added."""
        body = macro.body
        index = macro.index if args is not None else {}
        expanded: dict[int, list[Token]] = {}
        res: list[Token] = []
        n = len(body)
        i = 0

        def pasted_operand(k: int) -> list[Token]:
            text, kind = body[k]
            if kind == "id" and text in index:
                return list(args[index[text]]) or [Token("", "mark", hide, pos)]
            return [Token(text, kind, hide, pos)]

        while i < n:
            text, kind = body[i]
            if text == "#" and args is not None:
                k = self._next_body(body, i + 1)
                res.append(Token(_stringize(args[index[body[k][0]]]), "str", hide, pos))
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
                res.append(Token(text, kind, hide, pos))
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
    def _paste(left: Token, right: list[Token], hide: frozenset[str], pos: int) -> list[Token]:
        if left.kind == "mark":
            return right
        if right[0].kind == "mark":
            return [left] + right[1:]
        return tokenize(left.text + right[0].text, 0, hide, pos) + right[1:]


def _pieces(tokens: list[Token], span: Span, chunk: str, start: int,
            line: int) -> tuple[tuple[int, int, int, bool], ...]:
    """Where each piece of `chunk[:start] + tokens` came from: a token that stands in the
    text at its position (`pos`) is verbatim there, any other is a body token placed at its
    macro's call (`pos` is the call's). Neighbours that continue each other are one piece."""
    pieces: list[tuple[int, int, int, bool]] = [(1, line, 1, True)] if start else []
    out = start + 1
    for tok in tokens:
        n = len(tok.text)
        if n == 0 or tok.kind == "ws":
            out += n
            continue
        where = span.location(tok.pos)
        verbatim = chunk.startswith(tok.text, tok.pos)
        if pieces:
            o, ln, col, v = pieces[-1]
            if v == verbatim and ln == where.line and (
                    (verbatim and col + (out - o) == where.column) or
                    (not verbatim and col == where.column)):
                out += n
                continue
        pieces.append((out, where.line, where.column, verbatim))
        out += n
    return tuple(pieces)


def _stringize(arg: list[Token]) -> str:
    parts = []
    for t in arg:
        if t.kind == "ws":
            parts.append(" ")
        elif t.kind == "str":
            parts.append(t.text.replace("\\", "\\\\").replace('"', '\\"'))
        else:
            parts.append(t.text)
    return '"' + "".join(parts).strip() + '"'

