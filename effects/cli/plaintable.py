"""The selection matrix as plain text, character for character what rich prints for it when
the output is not a terminal, without importing rich (rich.console alone is ~25 ms of an
`effects matrix` run that is otherwise ~0.3 s).

Only the one table shape `report.print_matrix` builds is drawn here: `rich.table.Table` with its
defaults (box HEAVY_HEAD, edge, header, padding (0, 1), no lines, no expand), every column
`overflow="fold"`, cells of plain text. Column widths follow rich's Table._calculate_column_widths
(measure each column's min/max, collapse the widest wrappable columns, then reduce evenly,
measure again), cell text wraps as rich.text.Text.wrap does (rich._wrap.divide_line, words
folded by characters), and the whole is cropped to the console width as Console.print crops.

It is used only where rich would print plain text with the same measures (`plain_width`):
stdout not a terminal and no FORCE_COLOR / TTY_COMPATIBLE asking for one, a UTF-8 stream (else
rich draws ASCII boxes), not Windows (legacy console widths), not Jupyter or IDLE; and only for
cells of printable ASCII without markup or emoji syntax ('[', ':', '\\') nor empty, and column
widths of at least 3 (`render` answers None otherwise): everything else goes to rich.
tests/test_plaintable.py compares the two on random tables and widths.
"""
from __future__ import annotations

import os
import re
import sys
from typing import Sequence

_WORD = re.compile(r"\s*\S+\s*")
_PLAIN_CELL = re.compile(r"[ -~]+")      # printable ASCII, one cell per character
_PADDING = 2                             # (0, 1) padding: one space either side


def plain_width() -> int | None:
    """The width rich's default Console (writing to sys.stdout) would render at, when it would
    render without styles; None where rich decides otherwise or this cannot tell."""
    if sys.platform == "win32":
        return None
    import builtins
    if getattr(builtins, "get_ipython", None) is not None:   # Jupyter, IPython: rich's rules
        return None
    if getattr(sys.stdin, "__module__", "").startswith("idlelib"):
        return None
    environ = os.environ
    if "FORCE_COLOR" in environ or "TTY_COMPATIBLE" in environ:
        return None
    out = sys.stdout
    isatty = getattr(out, "isatty", None)
    if isatty is None:
        return None
    try:
        if isatty():
            return None
    except ValueError:
        return None
    encoding = (getattr(out, "encoding", "utf-8") or "utf-8").lower()
    if not encoding.startswith("utf"):
        return None
    columns = environ.get("COLUMNS")
    if columns is not None and columns.isdigit():
        return int(columns)
    width = None
    for fd in (0, 1, 2):     # rich asks stdin, stdout, stderr for a terminal size, in that order
        try:
            width = os.get_terminal_size(fd)[0]
        except (AttributeError, ValueError, OSError):
            continue
        break
    return width or 80


def plain_cell(text: str) -> bool:
    """Whether rich would show `text` (a table cell or header given as a string) as it is."""
    return bool(_PLAIN_CELL.fullmatch(text)) and not ("[" in text or ":" in text or "\\" in text)


def render(header: Sequence[str], rows: Sequence[Sequence[str]], width: int) -> str | None:
    """The table as rich prints it at console `width`, or None where this does not follow
    rich (a cell `plain_cell` refuses, a width too narrow for every column to hold text)."""
    n = len(header)
    if n == 0 or width < 1 or any(len(r) != n for r in rows):
        return None
    columns = [[header[j], *(r[j] for r in rows)] for j in range(n)]
    if not all(plain_cell(c) for col in columns for c in col):
        return None
    extra = 2 + (n - 1)                    # the edges and the dividers
    widths = _column_widths(columns, max(0, width - extra))
    if min(widths) < 3:
        return None
    lines = [_rule("┏", "━", "┳", "┓", widths)]
    lines += _row([c[0] for c in columns], widths, "┃", bottom=True)
    lines.append(_rule("┡", "━", "╇", "┩", widths))
    for i in range(len(rows)):
        lines += _row([c[i + 1] for c in columns], widths, "│", bottom=False)
    lines.append(_rule("└", "─", "┴", "┘", widths))
    return "".join(line[:width] + "\n" for line in lines)


# -- widths: rich.table.Table._calculate_column_widths for flexible, wrappable columns ------------

def _measure(cell: str, max_width: int) -> tuple[int, int]:
    """Measurement.get of Padding(Text(cell), (0, 1)) at `max_width`."""
    if max_width < 1:
        return 0, 0
    if max_width - _PADDING < 1:
        padded = (max_width, max_width)
    else:
        words = cell.split()
        longest = len(cell)                       # one line: no newline in a plain cell
        lo, hi = _got((max(len(w) for w in words) if words else longest, longest), max_width)
        padded = _most((lo + _PADDING, hi + _PADDING), max_width)
    return _got(padded, max_width)


def _got(m: tuple[int, int], max_width: int) -> tuple[int, int]:
    """What Measurement.get makes of a renderable's own measure: normalised, at most
    `max_width`, (0, 0) when nothing fits."""
    m = _most(_normal(m), max_width)
    return (0, 0) if m[1] < 1 else _normal(m)


def _normal(m: tuple[int, int]) -> tuple[int, int]:
    lo, hi = m
    lo = min(max(0, lo), hi)
    return max(0, lo), max(0, max(lo, hi))


def _most(m: tuple[int, int], width: int) -> tuple[int, int]:
    return min(m[0], width), min(m[1], width)


def _measure_column(cells: Sequence[str], max_width: int) -> tuple[int, int]:
    if max_width < 1:
        return 0, 0
    measured = [_measure(c, max_width) for c in cells]
    lo = max(m[0] for m in measured) if measured else 1
    hi = max(m[1] for m in measured) if measured else max_width
    return min(lo, max_width), min(hi, max_width)


def _column_widths(columns: Sequence[Sequence[str]], max_width: int) -> list[int]:
    widths = [_measure_column(col, max_width)[1] or 1 for col in columns]
    if sum(widths) > max_width:
        widths = _collapse(widths, max_width)
        if sum(widths) > max_width:
            widths = _ratio_reduce(sum(widths) - max_width, [1] * len(widths), widths, widths)
        widths = [_measure_column(col, w)[1] or 0 for col, w in zip(columns, widths)]
    return widths


def _collapse(widths: list[int], max_width: int) -> list[int]:
    """Table._collapse_widths with every column wrappable."""
    total = sum(widths)
    excess = total - max_width
    while total and excess > 0:
        widest = max(widths)
        second = max(w if w != widest else 0 for w in widths)
        ratios = [1 if w == widest else 0 for w in widths]
        if not any(ratios) or not widest - second:
            break
        widths = _ratio_reduce(excess, ratios, [min(excess, widest - second)] * len(widths), widths)
        total = sum(widths)
        excess = total - max_width
    return widths


def _ratio_reduce(total: int, ratios: list[int], maximums: list[int], values: list[int]) -> list[int]:
    """rich._ratio.ratio_reduce."""
    ratios = [r if m else 0 for r, m in zip(ratios, maximums)]
    total_ratio = sum(ratios)
    if not total_ratio:
        return values[:]
    remaining = total
    out = []
    for ratio, maximum, value in zip(ratios, maximums, values):
        if ratio and total_ratio > 0:
            distributed = min(maximum, round(ratio * remaining / total_ratio))
            out.append(value - distributed)
            remaining -= distributed
            total_ratio -= ratio
        else:
            out.append(value)
    return out


# -- cells and rules -------------------------------------------------------------------------------

def _wrap(text: str, width: int) -> list[str]:
    """Text.wrap(width, overflow='fold') of one line of ASCII, each line padded to `width`."""
    offsets = _divide_line(text, width)
    bounds = [0, *offsets, len(text)]
    return [text[a:b][:width].ljust(width) for a, b in zip(bounds, bounds[1:])]


def _divide_line(text: str, width: int) -> list[int]:
    """rich._wrap.divide_line with fold=True, for text one cell per character."""
    breaks: list[int] = []
    offset = 0
    for match in _WORD.finditer(text) if text else ():
        start, word = match.start(), match.group(0)
        length = len(word.rstrip())
        if width - offset >= length:
            offset += len(word)
        elif length > width:
            pieces = [word[k:k + width] for k in range(0, len(word), width)] or [""]
            for k, piece in enumerate(pieces):
                if start:
                    breaks.append(start)
                if k == len(pieces) - 1:
                    offset = len(piece)
                else:
                    start += len(piece)
        elif offset and start:
            breaks.append(start)
            offset = len(word)
    return breaks


def _row(cells: Sequence[str], widths: Sequence[int], edge: str, bottom: bool) -> list[str]:
    wrapped = [[f" {line} " for line in _wrap(c, w - _PADDING)] for c, w in zip(cells, widths)]
    height = max(len(w) for w in wrapped)
    out = []
    for k in range(height):
        parts = []
        for lines, w in zip(wrapped, widths):
            blank = height - len(lines)
            # the header row aligns to the bottom, the others to the top (rich's defaults)
            i = k - blank if bottom else k
            parts.append(lines[i] if 0 <= i < len(lines) else " " * w)
        out.append(edge + edge.join(parts) + edge)
    return out


def _rule(left: str, line: str, cross: str, right: str, widths: Sequence[int]) -> str:
    return left + cross.join(line * w for w in widths) + right
