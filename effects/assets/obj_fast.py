"""The fast path of `effects.assets.meshes.load_obj`: a whole .obj read at once, vectorised.

Most .obj files are regular: `v x y z`, `vt u v`, `vn x y z` lines, then triangles `f a b c`
whose corners all share one form (`v`, `v/vt`, `v//vn` or `v/vt/vn`) with positive indices.
Such a file is classified line by line with NumPy over its bytes, and every token is read by
Horner's rule over its bytes, one byte position of all the tokens at a time, a batch of lines
at a time: an index is its digits' value; a number written plainly (sign, up to 15 digits, a
point) is its digits as an integer divided by a power of ten, both exact in a double, so the
one rounded division gives the double nearest the text, which is what Python's float() (the
per-line reader's conversion, correctly rounded) gives. Numbers of any other spelling (an
exponent, more digits) go through float() one by one.
Corners are numbered by one sort in order of first appearance, as the per-line reader numbers
them: the mesh is the same, value for value.

Anything else returns None and the per-line reader, which locates every error, reads the file:
a byte outside printable ASCII, tab and line ends; a '#' after the start of a line; an
indented line; a statement with another number of fields; a quad; mixed corner forms; a
negative or out-of-range index; a vertex after the first face; a bad number.
"""
from __future__ import annotations

from typing import Callable, Iterator, NamedTuple

import numpy as np

_NL, _CR, _SP, _TAB, _HASH, _SLASH = 10, 13, 32, 9, 35, 47
_ALLOWED_BYTES = bytes([*range(32, 127), _TAB, _NL, _CR])
_WS = np.zeros(256, bool)
_WS[[_SP, _TAB, _CR, _NL]] = True
# Lines are read a batch at a time so that every temporary array stays small (in the cache,
# and under the size at which the allocator maps fresh pages for each)
_BATCH = 1 << 20
_SCAN = 8 << 20
_PLAIN_DIGITS = 15                      # 10**15 < 2**53: the digits are an exact double
_INDEX_DIGITS = 9                       # an index of up to 9 digits fits an int32
_POW10 = np.array([float(10 ** k) for k in range(_PLAIN_DIGITS + 1)])   # exact doubles


def parse(raw: bytes, check_counts: Callable[[int, int], None] | None = None
          ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray | None] | None:
    """(positions, uv flipped to D3D, triangles, normals or None) as the per-line reader makes
    them, or None when the file is not of the regular shape (see the module docstring).
    `check_counts(vertices, faces)` is called, when the lines have been told apart and before
    any is read, with the number of lines starting `v ` / `v<tab>` and `f ` / `f<tab>` (it
    raises to refuse the file); it is not called when None is returned before that."""
    body = raw if raw.endswith(b"\n") else raw + b"\n"
    if body.translate(None, _ALLOWED_BYTES):          # what is left is not allowed
        return None
    data = np.frombuffer(body, np.uint8)
    size = len(body)
    nl = np.concatenate([np.flatnonzero(data[at:at + _SCAN] == _NL) + at
                         for at in range(0, size, _SCAN)])
    starts = np.empty_like(nl)
    starts[:1] = 0
    np.add(nl[:-1], 1, out=starts[1:])
    ends = nl                                          # each line's '\n'
    if b"\r" in body:
        cr = np.flatnonzero(data == _CR)
        if not (data[cr + 1] == _NL).all():            # a lone carriage return
            return None
    if b"#" in body:
        hashes = np.flatnonzero(data == _HASH)
        if not ((hashes == 0) | (data[hashes - 1] == _NL)).all():
            return None                                # a comment after a statement
    # bytes 1 and 2 of each line (the file's last '\n' past its end, as if it had more)
    # (data[k:] at a line start, clipped to its last byte: data[min(start + k, size - 1)])
    b0, b1, b2 = (data[k:].take(starts, mode="clip") if size > k
                  else data[np.minimum(starts + k, size - 1)] for k in range(3))
    if check_counts is not None:
        spaced = (b1 == _SP) | (b1 == _TAB)
        check_counts(int(np.count_nonzero((b0 == ord("v")) & spaced)),
                     int(np.count_nonzero((b0 == ord("f")) & spaced)))
    blank = ends == starts
    if ((b0 == _SP) | (b0 == _TAB)).any():
        return None                                    # an indented line
    ws1, ws2 = _WS[b1], _WS[b2]
    kinds = {"v": (b0 == ord("v")) & ws1 & ~blank,
             "vt": (b0 == ord("v")) & (b1 == ord("t")) & ws2,
             "vn": (b0 == ord("v")) & (b1 == ord("n")) & ws2,
             "f": (b0 == ord("f")) & ws1 & ~blank}
    faces_at = np.flatnonzero(kinds["f"])
    if not len(faces_at):
        return None
    vertex_lines = kinds["v"] | kinds["vt"] | kinds["vn"]
    if vertex_lines[faces_at[0]:].any():               # "defined so far" would matter
        return None
    lengths = np.subtract(ends, starts)
    lengths += 1
    columns = {}
    for kind, fields in (("v", 3), ("vt", 2), ("vn", 3)):
        parts = [_floats(*batch, fields) for batch in _batches(data, starts, lengths, kinds[kind], len(kind))]
        if any(part is None for part in parts):
            return None
        columns[kind] = np.concatenate(parts) if parts else np.zeros((0, fields))
    face_columns = _face_columns(data, starts, lengths, kinds["f"], len(faces_at))
    if face_columns is None:
        return None
    (has_t, has_n), (vi, ti, ni) = face_columns
    v, vt, vn = columns["v"], columns["vt"], columns["vn"]
    used = [(vi, len(v))] + ([(ti, len(vt))] if has_t else []) + ([(ni, len(vn))] if has_n else [])
    if any(index.min() < 0 or index.max() >= count for index, count in used):
        return None                                    # out of range: the reader says where
    # Corners numbered in order of first appearance, as the per-line reader's dict does.
    numbered = _number_by_vertex(vi, ti, ni, len(v))
    if numbered is None:
        numbered = _number_by_key(vi, ti, ni, len(v), len(vt), len(vn))
        if numbered is None:
            return None
    tris, corner_v, corner_t, corner_n = numbered
    positions = v[corner_v]
    uv = vt[corner_t] if has_t else np.zeros((len(corner_v), 2))
    uv[:, 1] = 1.0 - uv[:, 1]
    normals = None
    if has_n:
        normals = vn[corner_n]
        if not ((normals[:, 0] != 0) | (normals[:, 1] != 0) | (normals[:, 2] != 0)).all():
            normals = None                             # a zero normal: computed instead
    return positions, uv, tris, normals


class Counts(NamedTuple):
    """What an .obj asks for, counted over its bytes before a line is parsed."""

    vertices: int              # `v` lines
    coords: int                # `vt` lines
    normals: int               # `vn` lines
    face_lines: np.ndarray     # the 1-based line number of each `f` line
    indices: np.ndarray        # the indices the faces make, running total at each `f` line


def count(raw: bytes) -> Counts:
    """The lines of each kind of any .obj, and the indices its faces make: a face of k
    corners (whitespace-separated tokens up to a '#') fans into k - 2 triangles of 3 indices.
    Lines are told apart as `parse` does (a line starting `v `, `vt `, `vn ` or `f `, a space
    or a tab after the keyword), so an indented line is not counted here; the per-line reader
    counts again, exactly, as it reads."""
    data = np.frombuffer(b"\n" + raw + b"\n", np.uint8)
    nl = np.flatnonzero(data == _NL)
    starts, ends = nl[:-1] + 1, nl[1:]                # each line, and its '\n'
    b0, b1, b2 = (data[np.minimum(starts + k, len(data) - 1)] for k in range(3))
    spaced1, spaced2 = _WS[b1] & (b1 != _NL), _WS[b2] & (b2 != _NL)
    v = b0 == ord("v")
    lines = [int(np.count_nonzero(mask)) for mask in
             (v & spaced1, v & (b1 == ord("t")) & spaced2, v & (b1 == ord("n")) & spaced2)]
    faces = np.flatnonzero((b0 == ord("f")) & spaced1)
    first, last = starts[faces], ends[faces]
    if len(first) and b"#" in raw:                    # a face line ends at its comment
        hashes = np.flatnonzero(data == _HASH)
        after = np.searchsorted(hashes, first)
        cut = hashes[np.minimum(after, len(hashes) - 1)]
        last = np.where((after < len(hashes)) & (cut < last), cut, last)
    blank = _WS[data]
    token_starts = np.flatnonzero(blank[:-1] & ~blank[1:]) + 1
    corners = np.searchsorted(token_starts, last) - np.searchsorted(token_starts, first) - 1
    indices = np.cumsum(3 * np.maximum(corners - 2, 0), dtype=np.int64)
    return Counts(*lines, faces + 1, indices)


def _face_columns(data: np.ndarray, starts: np.ndarray, lengths: np.ndarray, which: np.ndarray,
                  faces: int):
    """The faces' corners as zero-based index columns (v, vt or None, vn or None), int32,
    each filled batch by batch (no whole-file temporaries), and the one form (has vt, has
    vn) of every corner; None unless every face is a triangle of that form."""
    form, out, at = None, None, 0
    for batch in _batches(data, starts, lengths, which, 1):
        found = _corners(*batch, 3)
        if found is None or (form is not None and found[1] != form):
            return None                                # one form in every face of the file
        ids, form = found
        per = 1 + form[0] + form[1]
        if out is None:
            out = [np.empty(3 * faces, np.int32) for _ in range(per)]
        rows = ids.reshape(-1, per)
        for column, values in zip(out, rows.T):
            np.subtract(values, 1, out=column[at:at + len(rows)])
        at += len(rows)
    if out is None or at != 3 * faces:
        return None
    vi = out[0]
    ti = out[1] if form[0] else None
    ni = out[-1] if form[1] else None
    return form, (vi, ti, ni)


def _number_by_vertex(vi: np.ndarray, ti: np.ndarray | None, ni: np.ndarray | None,
                      vertices: int):
    """The corners numbered in order of first appearance when every vertex index comes with
    one texture-coordinate and one normal index throughout the file (as exporters write
    them): a corner is then its vertex, numbered through a table, with no sort. Returns
    (triangles, and per corner its v, vt and vn index), or None where a vertex comes with
    two different vt or vn."""
    partners = []
    for other in (ti, ni):
        if other is None:
            partners.append(None)
            continue
        table = np.zeros(vertices, other.dtype)
        table[vi] = other                              # some occurrence's partner ...
        if not (table[vi] == other).all():             # ... is every occurrence's
            return None
        partners.append(table)
    count = len(vi)
    # corner and vertex numbers in int32 where they fit (half the memory a 1M-triangle file
    # touches here: fresh pages cost more than the arithmetic)
    number = np.int32 if max(count, vertices) < 1 << 31 else np.int64
    first = np.full(vertices, count, number)
    np.minimum.at(first, vi, np.arange(count, dtype=number))   # where each vertex first appears
    seen = np.flatnonzero(first < count)
    slot = np.zeros(count, bool)
    slot[first[seen]] = True
    owner = np.empty(count, number)
    owner[first[seen]] = seen
    corner_v = owner[slot]                             # vertices in order of first appearance
    rank = np.empty(vertices, number)
    rank[corner_v] = np.arange(len(corner_v), dtype=number)
    tris = rank[vi].reshape(-1, 3)
    return (tris, corner_v, None if partners[0] is None else partners[0][corner_v],
            None if partners[1] is None else partners[1][corner_v])


def _number_by_key(vi: np.ndarray, ti: np.ndarray | None, ni: np.ndarray | None,
                   vertices: int, coords: int, normals: int):
    """The corners numbered in order of first appearance of their (v, vt, vn) triple, by
    one sort of the triples' codes; None where the code could overflow."""
    if vertices * (coords + 1) * (normals + 1) >= 1 << 62:
        return None
    key = vi.astype(np.int64) * (coords + 1)
    if ti is not None:
        key += ti
        key += 1
    key *= normals + 1
    if ni is not None:
        key += ni
        key += 1
    _, first_at, inverse = np.unique(key, return_index=True, return_inverse=True)
    order = np.argsort(first_at, kind="stable")
    rank = np.empty(len(order), np.int64)
    rank[order] = np.arange(len(order))
    tris = rank[inverse.ravel()].reshape(-1, 3)
    first = first_at[order]
    return (tris, vi[first], None if ti is None else ti[first],
            None if ni is None else ni[first])


def _batches(data: np.ndarray, starts: np.ndarray, lengths: np.ndarray, which: np.ndarray,
             keyword: int) -> Iterator[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """The lines `which` marks, about _BATCH bytes of them at a time: a copy of their bytes
    with each line's keyword blanked (so every token left is a value), and where each line
    starts and ends in it. Lines of a kind mostly stand together, in a few spans of the
    file; lines scattered among others are gathered first."""
    span_first, span_last = _runs(which)
    if len(span_first) > 64:
        mask = np.repeat(which, lengths)
        taken = lengths[which]
        groups = [(data[:len(mask)][mask], np.cumsum(taken) - taken, taken)]
    else:
        groups = [(data, starts[a:b], lengths[a:b]) for a, b in zip(span_first, span_last)]
    for base, line_starts, line_lengths in groups:
        offsets = line_starts - line_starts[0]
        total = int(offsets[-1] + line_lengths[-1])
        cuts = np.searchsorted(offsets, np.arange(_BATCH, total, _BATCH))
        bounds = np.unique(np.concatenate([[0], cuts, [len(line_starts)]]))
        for i, j in zip(bounds[:-1], bounds[1:]):
            lo = line_starts[i]
            chunk = base[lo:line_starts[j - 1] + line_lengths[j - 1]].copy()
            at = line_starts[i:j] - lo
            for k in range(keyword):
                chunk[at + k] = _SP
            yield chunk, at, at + line_lengths[i:j]


def _runs(mask: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Start and end (exclusive) of each run of True in `mask`."""
    padded = np.zeros(len(mask) + 2, bool)
    padded[1:-1] = mask
    edges = np.flatnonzero(np.not_equal(padded[1:], padded[:-1]))   # starts and ends alternate
    return edges[0::2].copy(), edges[1::2].copy()


def _per_line(first: np.ndarray, last: np.ndarray, line_starts: np.ndarray,
              line_ends: np.ndarray, per_line: int) -> bool:
    """Whether each line holds exactly `per_line` of the runs: as many runs as that in all,
    and each line's share (runs k*n .. k*n+n-1, in order) within the line."""
    return (len(first) == per_line * len(line_starts)
            and bool((first[0::per_line] >= line_starts).all())
            and bool((last[per_line - 1::per_line] <= line_ends).all()))


def _floats(chunk: np.ndarray, line_starts: np.ndarray, line_ends: np.ndarray,
            fields: int) -> np.ndarray | None:
    """(lines, fields) doubles, each as float() reads its token; None if one is not a number
    or a line has another number of them. A plain token (sign, point, up to 15 digits) is
    read by Horner's rule over its bytes, one byte position of every token at a time."""
    first, last = _runs(chunk > _SP)   # not whitespace: every other allowed byte is above ' '
    if not _per_line(first, last, line_starts, line_ends, fields):
        return None
    count = len(first)
    if not count:
        return np.zeros((0, fields))
    lengths = last - first
    longest = min(int(lengths.max()), _PLAIN_DIGITS + 2)
    mantissa = np.zeros(count, np.int64)
    digits = np.zeros(count, np.int8)
    scale = np.zeros(count, np.int8)             # digits after the point
    points = np.zeros(count, np.int8)
    odd = lengths > longest                      # too long to be plain, or a stray byte
    short = np.minimum(lengths, 127).astype(np.int8)
    padded = np.concatenate([chunk, np.zeros(longest, np.uint8)])
    byte, scale_by = np.empty(count, np.uint8), np.empty(count, np.uint8)
    for k in range(longest):                     # byte k of every token (buffers reused)
        padded[k:].take(first, out=byte)         # the byte k after each token's start
        inside = short > k
        point = (byte == ord(".")) & inside
        sign = ((byte == ord("-")) | (byte == ord("+"))) & inside
        byte -= 48                               # a digit's value; other bytes wrap past 9
        digit = (byte < 10) & inside
        # mantissa = mantissa * 10 + digit where a digit stands (no masked loops: SIMD)
        np.multiply(digit, np.uint8(9), out=scale_by)
        scale_by += 1
        mantissa *= scale_by
        byte *= digit
        mantissa += byte
        digits += digit
        scale += digit & (points > 0)
        points += point
        odd |= inside & ~(digit | point | sign)
        if k:
            odd |= sign                          # a sign only leads
    odd |= (points > 1) | (digits == 0) | (digits > _PLAIN_DIGITS)
    # both exact doubles: the one rounded division is the double nearest the text
    value = mantissa.astype(np.float64) / _POW10[np.minimum(scale, _PLAIN_DIGITS)]
    value = np.where(chunk[first] == ord("-"), -value, value)
    for i in np.flatnonzero(odd):                # exponents, long digit strings ...
        try:
            value[i] = float(chunk[first[i]:last[i]].tobytes())
        except ValueError:
            return None
    return value.reshape(-1, fields)


_FACE_BYTES = b"0123456789/ \t\r\n"
_FORMS = {(1, 0): (False, False), (2, 1): (True, False), (3, 1): (True, True),
          (2, 2): (False, True)}   # (indices per corner, slashes between two) -> (vt, vn)


def _corners(chunk: np.ndarray, line_starts: np.ndarray, line_ends: np.ndarray,
             fields: int) -> tuple[np.ndarray, tuple[bool, bool]] | None:
    """Every face's corner indices in order, and the corners' one form (has vt, has vn); None
    unless every face has `fields` corners of one form, of digits and slashes.

    The indices are the runs of digits. Each line must hold the same number of them, 3, 6 or
    9 (1, 2 or 3 a corner); between two of one corner stands exactly '/' (or '//' for
    v//vn, 2 a corner) and the file has no other slash, so every other gap between runs,
    having neither digits nor slashes, is whitespace: the corners are separate tokens."""
    if chunk.tobytes().translate(None, _FACE_BYTES):
        return None                                # a sign, a letter: the reader says
    first, last = _runs(np.subtract(chunk, 48, dtype=np.uint8) < 10)   # '0'..'9' (others wrap)
    lines = len(line_starts)
    if not lines or len(first) % (fields * lines):
        return None
    per = len(first) // (fields * lines)
    if not _per_line(first, last, line_starts, line_ends, fields * per):
        return None
    # the gaps after each run but a corner's last
    gap_at = last.reshape(-1, per)[:, :-1]
    gap_len = first.reshape(-1, per)[:, 1:] - gap_at
    slashes = int(gap_len.flat[0]) if gap_len.size else 0
    form = _FORMS.get((per, slashes))
    if form is None or (gap_len != slashes).any() or (chunk[gap_at] != _SLASH).any() \
            or (slashes == 2 and (chunk[gap_at + 1] != _SLASH).any()) \
            or int(np.count_nonzero(chunk == _SLASH)) != slashes * gap_at.size:
        return None
    lengths = last - first
    if lengths.max() > _INDEX_DIGITS:
        return None                                # out of any range: the reader says
    longest = int(lengths.max())
    padded = np.concatenate([chunk, np.zeros(longest, np.uint8)])
    value = np.zeros(len(first), np.int32)
    short = lengths.astype(np.int8)
    count = len(first)
    byte, inside, scale_by = (np.empty(count, np.uint8), np.empty(count, np.uint8),
                              np.empty(count, np.uint8))
    for k in range(longest):                       # digit k of every index (buffers reused)
        padded[k:].take(first, out=byte)           # the byte k after each run's start
        np.greater(short, k, out=inside, casting="unsafe")
        # value = value * 10 + digit inside the run (no masked loops: SIMD)
        np.multiply(inside, 9, out=scale_by)
        scale_by += 1
        value *= scale_by
        byte -= 48
        byte *= inside
        value += byte
    return value, form
