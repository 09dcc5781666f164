"""Parse the text of an `asm { }` block into an AsmProgram.

The assembler syntax is free-form: an instruction is an opcode (with `_sat`, `_x2`, `_pp` ...
suffixes) followed by comma-separated operands, so line breaks carry no meaning and an
instruction ends where the next token is not a comma. `;` and `//` start comments, `/* */`
encloses them. Every position is mapped back into the .fx file: line k of the block is file
line `block.location.line + k`, and on line 0 columns are offset by `block.location.column - 1`.

`assemble()` raises AsmError at the first syntax error; version rules are `check()`'s job.
"""
from __future__ import annotations

import re
from dataclasses import dataclass

from effects.base import caches, limits
from effects.base.errors import AsmError, Location
from effects.model import ShaderBlock
from effects.shaders.asm.instructions import COMPARISONS, is_known, lookup, rows_named
from effects.shaders.asm.program import (AsmProgram, ConstantDef, Declaration, Instruction, Operand,
                      RelativeAddress)
from effects.shaders.asm.versions import IDENTITY, VERSIONS, canonical_version

NOT_ASSEMBLY = ("not Direct3D shader assembly: expected a version token such as ps.1.1 or "
                "vs_2_0")

_TOKEN = re.compile(r"""
  (?P<ws>[ \t\r\f\v]+)
| (?P<nl>\n)
| (?P<version>[pPvV][sS][._][0-9][._](?:[0-9]|[xXaAbB]|[sS][wW])(?![A-Za-z0-9_.]))
| (?P<number>(?:\d+\.\d*|\.\d+|\d+)(?:[eE][+-]?\d+)?[fF]?(?![A-Za-z0-9_]))
| (?P<word>[A-Za-z_][A-Za-z0-9_]*)
| (?P<punct>[,.\-+\[\]()!])
""", re.VERBOSE)

_REGISTER = re.compile(
    r"^(?P<kind>opos|ofog|opts|odepth|od|ot|oc|vpos|vface|al|[rctvsabipol])"
    r"(?P<index>\d+)?(?P<mods>(?:_[a-z0-9]+)*)$")
_KIND_CASE = {"opos": "oPos", "ofog": "oFog", "opts": "oPts", "odepth": "oDepth", "od": "oD",
              "ot": "oT", "oc": "oC", "vpos": "vPos", "vface": "vFace", "al": "aL"}
_UNINDEXED = {"oPos", "oFog", "oPts", "oDepth", "vPos", "vFace", "aL"}
_SRC_MODIFIERS = {"bias": "bias", "bx2": "bx2", "x2": "x2", "dz": "dz", "db": "dz",
                  "dw": "dw", "da": "dw", "abs": "abs"}
_SWIZZLE_LETTERS = {"x": 0, "y": 1, "z": 2, "w": 3, "r": 0, "g": 1, "b": 2, "a": 3}
_SHIFTS = {"x2": 1, "x4": 2, "x8": 3, "d2": -1, "d4": -2, "d8": -3}
_SAMPLER_TYPES = {"2d", "cube", "volume"}
_USAGES = ("positiont", "position", "blendweight", "blendindices", "normal", "psize",
           "texcoord", "tangent", "binormal", "tessfactor", "color", "fog", "depth", "sample")
USAGES = frozenset(_USAGES)    # the dcl_ usages (D3DDECLUSAGE): the HLSL compiler's inputs too
_ROLE_NAMES = {"d": "dst", "s": "src", "x": "src", "S": "sampler", "f": "value", "n": "value",
               "B": "value", "l": "label", "b": "condition", "I": "i#", "L": "aL", "p": "p0"}


@dataclass(slots=True)      # one per token of every shader: slots make them cheaper to build
class Token:
    type: str      # 'version' 'number' 'word' 'punct' 'end'
    text: str
    line: int      # 0-based line in the block
    col: int       # 1-based column in that line


_PHASE_WORD = re.compile(r"(?i)(?<![A-Za-z0-9_])phase(?![A-Za-z0-9_])")
_DIGITS = re.compile(r"\d+")
_USAGE = re.compile(r"([a-z]+?)(\d*)")    # dcl_texcoord1: usage and index

# `;` and `//` to the end of the line, `/* */` (or to the end of an unclosed one); the first
# opener from the left wins, as when scanning character by character
_COMMENT = re.compile(r";[^\n]*|//[^\n]*|/\*(?:.*?\*/|.*)", re.S)
_NOT_NEWLINE = re.compile(r"[^\n]")


def _strip_comments(text: str) -> str:
    """Blank out comments, keeping every other character (and newline) where it is."""
    if ";" not in text and "/" not in text:   # compiled HLSL: no comments
        return text
    return _COMMENT.sub(lambda m: _NOT_NEWLINE.sub(" ", m.group()), text)


class _Parser:
    def __init__(self, block: ShaderBlock) -> None:
        self.block = block
        self.origin = block.location
        raw_lines = block.source.split("\n")
        pad = " " * max(0, self.origin.column - 1)
        self.file_lines = tuple([pad + raw_lines[0]] + raw_lines[1:]) if raw_lines else ()
        self.text = _strip_comments(block.source)
        self.tokens = self._lex(self.text)
        self.max_word = limits.get("literal_digits")   # read once: a lookup per token cost 30%
        self.pos = 0
        self.current: Token | None = None

    # -- positions and errors ------------------------------------------------------------------
    def loc(self, tok: Token) -> Location:
        col = tok.col + self.origin.column - 1 if tok.line == 0 else tok.col
        return Location(self.origin.path, self.origin.line + tok.line, col)

    def line_of(self, tok: Token) -> str | None:
        return self.file_lines[tok.line] if tok.line < len(self.file_lines) else None

    def error(self, message: str, tok: Token) -> AsmError:
        return AsmError(message, self.loc(tok), source_line=self.line_of(tok))

    # -- lexing --------------------------------------------------------------------------------
    def _lex(self, text: str) -> list[Token]:
        """Every token up to the end (or up to a character no token starts with, as a 'bad'
        token, which is an error only when the parser reaches it). One pass of finditer: a
        gap between two matches is such a character."""
        out: list[Token] = []
        line, line_start, end = 0, 0, 0
        for m in _TOKEN.finditer(text):
            i = m.start()
            if i != end:
                out.append(Token("bad", text[end], line, end - line_start + 1))
                return out
            kind = m.lastgroup
            end = m.end()
            if kind == "nl":
                line, line_start = line + 1, end
            elif kind != "ws":
                out.append(Token(kind, m.group(), line, i - line_start + 1))  # type: ignore[arg-type]
        if end != len(text):
            out.append(Token("bad", text[end], line, end - line_start + 1))
            return out
        out.append(Token("end", "", line, end - line_start + 1))
        return out

    def peek(self) -> Token:
        if self.current is not None:     # the common case first: this runs several times a token
            return self.current
        self.current = self.tokens[self.pos]
        self.pos += 1
        if self.current.type == "bad":
            raise self.error(f"unexpected character '{self.current.text}'", self.current)
        if len(self.current.text) > self.max_word:  # c99999...: Python's int() stops at 4,300 digits
            raise self.error(limits.message("literal_digits", len(self.current.text), "a word"), self.current)
        return self.current

    def advance(self) -> Token:
        tok = self.peek()
        if tok.type != "end":
            self.current = None
        return tok

    def at(self, text: str) -> bool:
        tok = self.current if self.current is not None else self.peek()
        return tok.text == text and tok.type == "punct"

    def expect_punct(self, text: str, what: str) -> Token:
        tok = self.peek()
        if not self.at(text):
            raise self.error(f"expected '{text}' {what}, found {_describe(tok)}", tok)
        return self.advance()

    # -- program -------------------------------------------------------------------------------
    def parse(self) -> AsmProgram:
        first = self.current = self.tokens[0]
        self.pos = 1
        if first.type != "version":
            raise AsmError(NOT_ASSEMBLY, self.loc(first), source_line=self.line_of(first))
        self.advance()
        name = canonical_version(first.text)
        rules = VERSIONS.get(name or "")
        if rules is None:
            known = ", ".join(VERSIONS)
            raise self.error(f"unknown shader version '{first.text}' (known: {known})", first)
        stage_kind = {"vertex": "vs", "pixel": "ps"}.get(self.block.stage)
        if stage_kind and stage_kind != rules.kind:
            stage = "vertex" if stage_kind == "vs" else "pixel"
            raise self.error(f"a {stage} shader must start with a {stage_kind} version token; "
                             f"this one starts with {first.text}", first)
        self.rules = rules
        prog = AsmProgram(kind=rules.kind, version=(rules.major, rules.minor), name=rules.name,
                          rules=rules, location=self.loc(first), origin=self.origin,
                          source_lines=self.file_lines,
                          has_decl_block=self.block.decl is not None)
        for el in self.block.decl or ():
            reg = Operand("v", el.register, el.location, text=f"v{el.register}")
            prog.dcls.append(Declaration(reg, location=el.location, from_decl=True))
        phase = 1 if rules.is_ps14 and self._has_phase_marker() else (2 if rules.is_ps14 else None)
        while self.peek().type != "end":
            self._statement(prog, phase)
            if prog.phase_locations and rules.is_ps14:
                phase = 2
        return prog

    def _has_phase_marker(self) -> bool:
        return _PHASE_WORD.search(self.text) is not None

    def _statement(self, prog: AsmProgram, phase: int | None) -> None:
        coissue = self.at("+")
        if coissue:
            self.advance()
        predicate = self._predicate() if self.at("(") else None
        tok = self.advance()
        if tok.type == "version":
            raise self.error(f"a second version token '{tok.text}'; the version must come "
                             "first and only once", tok)
        if tok.type != "word":
            raise self.error(f"expected an instruction, found {_describe(tok)}", tok)
        base, suffixes = self._split_opcode(tok)
        if base == "dcl":
            self._declaration(prog, tok, suffixes)
            return
        mods = self._instruction_modifiers(tok, base, suffixes)
        info = lookup(base, prog.name)
        in_version = info is not None
        if info is None:
            info = rows_named(base)[0]
        roles = info.operands
        if base in ("if", "break") and mods["comparison"]:
            roles = "ss"
        operands = self._operands(roles, tok)
        if in_version and len(operands) != len(roles):
            raise self._arity_error(base, roles, len(operands), tok)
        if not in_version:
            # the instruction belongs to another version: pick the row whose shape fits, so
            # check() can say "not available in ps_1_1" rather than "wrong operand count"
            for alt in rows_named(base):
                if len(alt.operands) == len(operands):
                    info = alt
                    break
        if base == "def" or base == "defi" or base == "defb":
            self._constant(prog, base, operands, tok, in_version)
            return
        if base == "phase":
            prog.phase_locations.append(self.loc(tok))
            return
        has_dst = info.has_dst and bool(operands)
        dst = operands[0] if has_dst else None
        if dst is not None:
            self._as_destination(dst)
        srcs = operands[1:] if has_dst else operands
        prog.instructions.append(Instruction(
            opcode=base, dst=dst, srcs=srcs, info=info, location=self.loc(tok),
            shift=mods["shift"], saturate=mods["sat"], partial_precision=mods["pp"],
            centroid=mods["centroid"], coissue=coissue, phase=phase,
            comparison=mods["comparison"], predicate=predicate, opcode_text=tok.text,
            source_line=self.line_of(tok)))

    def _arity_error(self, base: str, roles: str, found: int, tok: Token) -> AsmError:
        names = []
        n_src = 0
        for r in roles:
            if r in "sx":
                names.append(f"src{n_src}")
                n_src += 1
            else:
                names.append(_ROLE_NAMES[r])
        listed = f" ({', '.join(names)})" if names else ""
        plural = "operand" if len(roles) == 1 else "operands"
        return self.error(f"{base} takes {len(roles)} {plural}{listed}; found {found}", tok)

    # -- opcodes -------------------------------------------------------------------------------
    def _split_opcode(self, tok: Token) -> tuple[str, list[str]]:
        parts = tok.text.lower().split("_")
        base, rest = parts[0], parts[1:]
        if not is_known(base):
            raise self.error(f"unknown instruction '{tok.text}'", tok)
        return base, rest

    def _instruction_modifiers(self, tok: Token, base: str, suffixes: list[str]) -> dict:
        mods = {"shift": 0, "sat": False, "pp": False, "centroid": False, "comparison": None}
        for s in suffixes:
            if s in _SHIFTS and mods["shift"] == 0:
                mods["shift"] = _SHIFTS[s]
            elif s == "sat" and not mods["sat"]:
                mods["sat"] = True
            elif s == "pp" and not mods["pp"]:
                mods["pp"] = True
            elif s == "centroid":
                mods["centroid"] = True
            elif s in COMPARISONS and base in ("if", "break", "setp") and not mods["comparison"]:
                mods["comparison"] = s
            else:
                raise self.error(f"unknown or repeated instruction modifier '_{s}' in "
                                 f"'{tok.text}'", tok)
        if base == "setp" and not mods["comparison"]:
            raise self.error("setp needs a comparison, e.g. setp_gt", tok)
        return mods

    def _predicate(self) -> Operand:
        self.expect_punct("(", "before the predicate")
        negate = self.at("!")
        if negate:
            self.advance()
        op = self._operand("s")
        op.negate = negate
        self.expect_punct(")", "after the predicate register")
        return op

    # -- operands ------------------------------------------------------------------------------
    def _operands(self, roles: str, opcode_tok: Token) -> list[Operand]:
        if not roles:
            return []
        ops = [self._operand(roles[0])]
        while self.at(","):
            self.advance()
            ops.append(self._operand(roles[len(ops)] if len(ops) < len(roles) else "s"))
        return ops

    def _operand(self, role: str) -> Operand:
        start = self.peek()
        negate = invert = False
        if start.type == "punct" and start.text in ("-", "!"):
            self.advance()
            negate = True
        elif start.type == "number" and start.text == "1" and role not in "fnB":
            self.advance()
            if not self.at("-"):
                raise self.error("expected '-' after '1' (the invert modifier is 1-reg)", start)
            self.advance()
            invert = True
        tok = self.peek()
        if tok.type == "number":
            self.advance()
            value = float(tok.text.rstrip("fF"))
            return Operand("imm", None, self.loc(start), text=("-" if negate else "") + tok.text,
                           value=-value if negate else value)
        if tok.type != "word":
            raise self.error(f"expected a register, found {_describe(tok)}", tok)
        self.advance()
        word = tok.text.lower()
        if word in ("true", "false"):
            return Operand("imm", None, self.loc(tok), text=tok.text, value=word == "true")
        register = _register(word)
        if register is None:
            raise self.error(f"'{tok.text}' is not a register", tok)
        kind, index, mods = register
        if kind in _UNINDEXED:
            if index is not None:
                raise self.error(f"'{tok.text}' is not a register ({kind} takes no number)", tok)
        op = Operand(kind, index, self.loc(start), tok.text)   # positional: a third the cost
        if negate:
            op.negate = True
        if invert:
            op.modifier = "invert"
        if mods:
            self._source_modifiers(op, mods, tok)
        if self.at("["):
            self._relative(op)
        if op.index is None and op.relative is None and kind not in _UNINDEXED:
            raise self.error(f"register '{tok.text}' needs a number, e.g. {kind}0", tok)
        if self.at("."):
            dot = self.advance()
            sw = self.peek()
            if sw.type != "word":
                raise self.error(f"expected a swizzle or write mask after '.', found "
                                 f"{_describe(sw)}", sw)
            self.advance()
            letters, _, mods = sw.text.lower().partition("_")
            swizzle = _swizzle(letters)
            if swizzle is None:
                raise self.error(f"'.{sw.text}' is not a swizzle or write mask (use up to four "
                                 "of x, y, z, w or r, g, b, a)", dot)
            op.swizzle_text = letters
            op.swizzle = swizzle
            if mods:
                self._source_modifiers(op, "_" + mods, sw)
        return op

    def _source_modifiers(self, op: Operand, text: str, tok: Token) -> None:
        for part in filter(None, text.split("_")):
            mod = _SRC_MODIFIERS.get(part)
            if mod is None:
                raise self.error(f"unknown source modifier '_{part}' on '{tok.text}'", tok)
            if op.modifier == "invert":
                raise self.error("the invert modifier 1-reg cannot be combined with "
                                 f"_{part}", tok)
            if op.modifier is not None:
                raise self.error(f"only one source modifier per operand ('{tok.text}' has "
                                 f"_{op.modifier} and _{part})", tok)
            op.modifier = mod

    def _relative(self, op: Operand) -> None:
        open_tok = self.expect_punct("[", "")
        offset = op.index or 0
        rel = None
        while True:
            tok = self.advance()
            if tok.type == "number" and _DIGITS.fullmatch(tok.text):
                offset += int(tok.text)
            elif tok.type == "word" and tok.text.lower() in ("a0", "al"):
                kind = "aL" if tok.text.lower() == "al" else "a"
                comp = 0
                if self.at("."):
                    self.advance()
                    c = self.advance()
                    if c.type != "word" or len(c.text) != 1 or c.text.lower() not in _SWIZZLE_LETTERS:
                        raise self.error("expected one component (x, y, z or w) after the "
                                         "address register", c)
                    comp = _SWIZZLE_LETTERS[c.text.lower()]
                if rel is not None:
                    raise self.error("only one address register may index a register", tok)
                rel = RelativeAddress(kind, 0, comp)
            else:
                raise self.error(f"expected a0.x, aL or a number inside [ ], found "
                                 f"{_describe(tok)}", tok)
            if self.at("+"):
                self.advance()
                continue
            break
        self.expect_punct("]", "to close the relative address")
        if rel is None:
            # c[5] is just c5
            op.index = offset
            return
        op.index = offset
        op.relative = rel
        del open_tok

    def _as_destination(self, op: Operand) -> None:
        """A destination's '.xyz' is a write mask: distinct components in order."""
        if op.swizzle_text:
            comps = [_SWIZZLE_LETTERS[c] for c in op.swizzle_text]
            if comps != sorted(set(comps)):
                raise AsmError(f"write mask '.{op.swizzle_text}' must name each component at "
                               "most once, in the order x, y, z, w", op.location,
                               source_line=self._line_at(op.location))
            op.mask = tuple(comps)
            op.swizzle = IDENTITY

    def _line_at(self, location: Location) -> str | None:
        k = location.line - self.origin.line
        return self.file_lines[k] if 0 <= k < len(self.file_lines) else None

    # -- setup statements ----------------------------------------------------------------------
    def _declaration(self, prog: AsmProgram, tok: Token, suffixes: list[str]) -> None:
        usage, usage_index, sampler_type, pp, centroid = None, 0, None, False, False
        for i, s in enumerate(suffixes):
            if s == "pp":
                pp = True
            elif s == "centroid":
                centroid = True
            elif i == 0 and s in _SAMPLER_TYPES:
                sampler_type = s
            elif i == 0:
                m = _USAGE.fullmatch(s)
                if m is None or m.group(1) not in _USAGES:
                    raise self.error(f"unknown declaration '{tok.text}'", tok)
                usage = m.group(1)
                usage_index = int(m.group(2) or 0)
            else:
                raise self.error(f"unknown declaration modifier '_{s}' in '{tok.text}'", tok)
        reg = self._operand("d")
        self._as_destination(reg)
        prog.dcls.append(Declaration(reg, usage, usage_index, sampler_type, pp, centroid,
                                     self.loc(tok), after_code=bool(prog.instructions)))

    def _constant(self, prog: AsmProgram, base: str, operands: list[Operand], tok: Token,
                  in_version: bool) -> None:
        reg = operands[0]
        if reg.kind == "imm":
            raise self.error(f"{base} needs a register first, e.g. {base} c0, ...", tok)
        values = []
        for op in operands[1:]:
            if op.kind != "imm":
                raise AsmError(f"{base} takes numbers after the register; '{op.text}' is a "
                               "register", op.location, source_line=self._line_at(op.location))
            if base == "def" and not abs(op.value) <= _FLT_MAX:
                # a def register is a float32: 1e39 would be inf, which no constant holds
                raise AsmError(f"def takes finite float32 values (at most 3.4e38); {op.text} is "
                               "not one", op.location, source_line=self._line_at(op.location))
            values.append(op.value)
        if base == "defi":
            values = [int(v) for v in values]
        if base == "defb":
            values = [bool(v) for v in values]
        prog.def_statements.append(ConstantDef(reg, tuple(values), self.loc(tok),
                                               after_code=bool(prog.instructions)))
        if reg.index is None:
            return
        if base == "def":
            prog.defs[reg.index] = tuple(float(v) for v in values)  # type: ignore[assignment]
        elif base == "defi":
            prog.int_defs[reg.index] = tuple(values)  # type: ignore[assignment]
        elif values:
            prog.bool_defs[reg.index] = bool(values[0])


_FLT_MAX = 3.4028234663852886e38 * (1 + 2.0 ** -25)   # what still rounds to a finite float32


# a shader names a few registers many times
@caches.memo("shaders.asm.registers", keys="a register word", entry_bytes=128,
             max_bytes=1024 * 128)
def _register(word: str) -> tuple[str, int | None, str] | None:
    """'r0_bx2' -> ('r', 0, '_bx2'); 'opos' -> ('oPos', None, ''); None if not a register."""
    m = _REGISTER.match(word)
    if m is None:
        return None
    kind, index, mods = m.groups()
    return _KIND_CASE.get(kind, kind), None if index is None else int(index), mods


@caches.memo("shaders.asm.swizzles", keys="swizzle letters", entry_bytes=128, max_bytes=1024 * 128)
def _swizzle(letters: str) -> tuple[int, int, int, int] | None:
    """'xy' -> (0, 1, 1, 1): the components read, the last one repeated; None if the letters
    are no swizzle (none, more than four, or one that is not x, y, z, w, r, g, b, a)."""
    if not letters or len(letters) > 4 or any(c not in _SWIZZLE_LETTERS for c in letters):
        return None
    comps = [_SWIZZLE_LETTERS[c] for c in letters]
    return tuple(comps + [comps[-1]] * (4 - len(comps)))  # type: ignore[return-value]


def _describe(tok: Token) -> str:
    return "the end of the program" if tok.type == "end" else f"'{tok.text}'"


def assemble(block: ShaderBlock) -> AsmProgram:
    """Parse a shader block. Raises AsmError (located in the .fx file) on the first syntax
    error, and for text that is not Direct3D assembly at all."""
    return _Parser(block).parse()
