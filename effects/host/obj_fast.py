"""The fast path of `effects.host.meshes.load_obj`: a whole .obj read at once, vectorised.

Most .obj files are regular: `v x y z`, `vt u v`, `vn x y z` lines, then triangles `f a b c`
whose corners all share one form (`v`, `v/vt`, `v//vn` or `v/vt/vn`) with positive indices.
Such a file is classified line by line with NumPy over its bytes, each kind's tokens are split
at once, numbers are converted by Python's own float() (as the per-line reader does) and
indices by NumPy, and corners are numbered by one sort in order of first appearance, as the
per-line reader numbers them: the mesh is the same, value for value.

Anything else returns None and the per-line reader, which locates every error, reads the file:
a byte outside printable ASCII, tab and line ends; a '#' after the start of a line; an
indented line; a statement with another number of fields; a quad; mixed corner forms; a
negative or out-of-range index; a vertex after the first face; a bad number.
"""
from __future__ import annotations

import numpy as np

_NL, _CR, _SP, _TAB, _HASH = 10, 13, 32, 9, 35
_ALLOWED = np.zeros(256, bool)
_ALLOWED[32:127] = True
_ALLOWED[[_TAB, _NL, _CR]] = True


def parse(raw: bytes) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray | None] | None:
    """(positions, uv flipped to D3D, triangles, normals or None) as the per-line reader makes
    them, or None when the file is not of the regular shape (see the module docstring)."""
    body = raw if raw.endswith(b"\n") else raw + b"\n"
    data = np.frombuffer(body + b"\n\n", np.uint8)   # two more: every line has bytes 0-2
    size = len(body)
    if not _ALLOWED[np.bincount(data, minlength=256).nonzero()[0]].all():
        return None
    nl = np.flatnonzero(data[:size] == _NL)
    starts = np.concatenate([[0], nl[:-1] + 1])
    ends = nl                                          # each line's '\n'
    cr = np.flatnonzero(data == _CR)
    if len(cr) and not (data[cr + 1] == _NL).all():    # a lone carriage return
        return None
    hashes = np.flatnonzero(data[:size] == _HASH)
    if len(hashes) and not ((hashes == 0) | (data[hashes - 1] == _NL)).all():
        return None                                    # a comment after a statement
    b0, b1, b2 = data[starts], data[starts + 1], data[starts + 2]
    blank = ends == starts
    if ((b0 == _SP) | (b0 == _TAB)).any():
        return None                                    # an indented line
    ws1 = (b1 == _SP) | (b1 == _TAB) | (b1 == _CR) | (b1 == _NL)
    ws2 = (b2 == _SP) | (b2 == _TAB) | (b2 == _CR) | (b2 == _NL)
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
    lengths = ends - starts + 1
    chunks = {kind: data[:size][np.repeat(lines, lengths)] for kind, lines in kinds.items()}
    tokens = {}
    for kind, fields in (("v", 4), ("vt", 3), ("vn", 4)):
        words = chunks[kind].tobytes().split()
        count = int(kinds[kind].sum())
        if len(words) != fields * count or words[0::fields].count(kind.encode()) != count:
            return None                                # a line with another number of fields
        tokens[kind] = words
    try:
        v = _floats(tokens["v"], 4)
        vt = _floats(tokens["vt"], 3)
        vn = _floats(tokens["vn"], 4)
    except ValueError:
        return None
    form = _corner_form(chunks["f"], len(faces_at))
    if form is None:
        return None
    has_t, has_n = form
    per = 1 + has_t + has_n
    words = chunks["f"].tobytes().replace(b"/", b" ").split()
    if len(words) != (1 + 3 * per) * len(faces_at) or \
            words[0::1 + 3 * per].count(b"f") != len(faces_at):
        return None
    del words[0::1 + 3 * per]
    try:
        ids = np.array(words).astype(np.int64).reshape(-1, per) - 1
    except ValueError:
        return None
    vi = ids[:, 0]
    ti = ids[:, 1] if has_t else np.full(len(vi), -1, np.int64)
    ni = ids[:, per - 1] if has_n else np.full(len(vi), -1, np.int64)
    used = [(vi, len(v))] + ([(ti, len(vt))] if has_t else []) + ([(ni, len(vn))] if has_n else [])
    if any(index.min() < 0 or index.max() >= size for index, size in used):
        return None                                    # out of range: the reader says where
    if len(v) * (len(vt) + 1) * (len(vn) + 1) >= 1 << 62:
        return None
    # Corners numbered in order of first appearance, as the per-line reader's dict does.
    key = (vi * (len(vt) + 1) + (ti + 1)) * (len(vn) + 1) + (ni + 1)
    _, first_at, inverse = np.unique(key, return_index=True, return_inverse=True)
    order = np.argsort(first_at, kind="stable")
    rank = np.empty(len(order), np.int64)
    rank[order] = np.arange(len(order))
    tris = rank[inverse.ravel()].reshape(-1, 3)
    first = first_at[order]
    positions = v[vi[first]]
    uv = vt[ti[first]] if has_t else np.zeros((len(first), 2))
    uv[:, 1] = 1.0 - uv[:, 1]
    normals = None
    if has_n:
        normals = vn[ni[first]]
        if not np.any(normals != 0, axis=1).all():
            normals = None
    return positions, uv, tris, normals


def _corner_form(f: np.ndarray, faces: int) -> tuple[bool, bool] | None:
    """(has vt, has vn) when every face line is `f` and three corners of one form, else None.
    Counts the slashes of each whitespace-separated token (a total per line could hide a
    corner of four fields next to one of two)."""
    ws = (f == _SP) | (f == _TAB) | (f == _CR) | (f == _NL)
    start = ~ws
    start[1:] &= ws[:-1]
    starts = np.flatnonzero(start)
    count = len(starts)
    if count != 4 * faces:
        return None
    slash = f == ord("/")
    at = np.flatnonzero(slash)
    # the token of each slash: the last token start at or before it (a search, not a
    # running sum over every byte)
    per_token = np.bincount(np.searchsorted(starts, at, "right") - 1,
                            minlength=count).reshape(faces, 4)
    double = at[:-1][np.diff(at) == 1]
    doubled = np.bincount(np.searchsorted(starts, double, "right") - 1,
                          minlength=count).reshape(faces, 4)
    first, twice = int(per_token[0, 1]), int(doubled[0, 1])
    if (per_token[:, 0] != 0).any() or (per_token[:, 1:] != first).any() or \
            (doubled[:, 1:] != twice).any():
        return None
    return {(0, 0): (False, False), (1, 0): (True, False), (2, 0): (True, True),
            (2, 1): (False, True)}.get((first, twice))


def _floats(words: list[bytes], fields: int) -> np.ndarray:
    """Python's float() of each line's numbers (the per-line reader's own conversion)."""
    columns = [np.array(list(map(float, words[k::fields])), np.float64) for k in range(1, fields)]
    return np.stack(columns, axis=1) if columns[0].size else np.zeros((0, fields - 1))
