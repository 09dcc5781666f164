"""DirectX .x meshes (the retained-mode format of the DirectX SDK samples and EffectEdit), text
and binary, read as untrusted input.

Why not a library: assimp reads .x (its XFileImporter), through pyassimp and Debian's
libassimp5, but it is C++ parsing untrusted bytes, and its .x code has a record of memory
errors found by fuzzing (assimp/assimp#1729, a heap overflow in XFileParser::GetNextToken;
#6879, still open, a heap overflow from a Frame name over 1,024 characters): a hostile file
would crash the process instead of being refused with a located error, and its messages carry
no line and column. The part of the format the samples' meshes use is small, so it is read
here, every count checked against the limits before anything it sizes is allocated.

The format (the DirectX 9 SDK's "X File Format Reference"): a 16-byte header
`xof 0303txt 0032` (version, `txt ` or `bin `, float size 0032 or 0064; the MSZIP-compressed
`tzip`/`bzip` are refused, named), then templates (skipped: the standard ones are known) and
data objects `Identifier [name] { [<guid>] members... nested objects... }`. In text the
members are numbers and strings separated by `;` and `,`, which carry no meaning for reading
the standard templates and are skipped; `{ name }` inside an object is a reference (skipped).
In binary the same comes as tokens (a 16-bit token number, then its data): names, strings,
integer and float lists, braces. Both are read into one tree of `XObject`s, whose numbers are
then taken in the order the templates declare them:

- `Mesh`: nVertices, vertices (x y z), nFaces, then per face n and n vertex indices (faces of
  more than three corners are fanned).
- `MeshNormals`: nNormals, normals, nFaceNormals, faces as in Mesh, corner for corner.
- `MeshTextureCoords`: nTextureCoords, (u v) per vertex (Direct3D's top-left origin, as
  `effects.assets.meshes` keeps them).
- `MeshVertexColors`: nVertexColors, (index; r g b a) each.
- `Frame` (nested): `FrameTransformMatrix` (16 numbers, row-major, row vectors as D3DX
  multiplies them); a frame's meshes are drawn with its matrix times its parents', as
  D3DXLoadMeshHierarchyFromX's frames are. Positions are transformed by it, normals by its
  inverse transpose, and the triangles keep the file's order (Direct3D draws them so).

Other objects (materials, skin weights, animation, DeclData ...) are read past. All meshes of
a file are merged into one. Errors are `SceneError`s at the line and column of text (the byte
offset of binary, as `offset N`).
"""
from __future__ import annotations

import bisect
import os
import re
import struct
from dataclasses import dataclass, field

import numpy as np

from effects.base import limits, untrusted
from effects.base.errors import Location, SceneError

HEADER = re.compile(rb"xof (\d{4})(txt |bin |tzip|bzip)(0032|0064)")


@dataclass
class XObject:
    """One data object: its template name, its own name, its numbers (in file order,
    excluding its children's), and the objects inside it."""

    kind: str
    name: str
    offset: int
    numbers: list = field(default_factory=list)       # floats and ints, or numpy arrays (binary)
    children: list["XObject"] = field(default_factory=list)

    def values(self) -> np.ndarray:
        parts = [np.atleast_1d(np.asarray(p, np.float64)) for p in self.numbers]
        return np.concatenate(parts) if parts else np.zeros(0)


class _Reader:
    """Errors at a byte offset, said as line and column for text."""

    def __init__(self, path: str, raw: bytes, text: bool) -> None:
        self.path, self.raw, self.text = path, raw, text
        self._lines: list[int] | None = None

    def where(self, offset: int) -> Location:
        if not self.text:
            return Location(self.path, 1, offset + 1)
        if self._lines is None:
            self._lines = [0] + [m.end() for m in re.finditer(rb"\n", self.raw)]
        line = bisect.bisect_right(self._lines, offset)
        return Location(self.path, line, offset - self._lines[line - 1] + 1)

    def error(self, message: str, offset: int) -> SceneError:
        where = self.where(offset)
        if not self.text:
            message = f"{message} (offset {offset})"
        return SceneError(message, where)


# ---------------------------------------------------------------------------------------------
# Tokens: ('{', None) ('}', None) ('name', str) ('string', str) ('numbers', list or array)
# ('guid', None) ('other', None), each with its byte offset

_TEXT_TOKEN = re.compile(rb"""
    (?P<skip>[\s;,]+|(?://|\#)[^\n]*)
  | (?P<num>[-+]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?)
  | (?P<name>[A-Za-z_][A-Za-z0-9_\-.]*)
  | (?P<string>"[^"\n]*")
  | (?P<guid><[^<>\n]*>)
  | (?P<open>\{) | (?P<close>\})
  | (?P<other>[\[\]().])
""", re.X)


def _text_tokens(reader: _Reader, start: int):
    raw = reader.raw
    pos, end = start, len(raw)
    match = _TEXT_TOKEN.match
    while pos < end:
        m = match(raw, pos)
        if m is None:
            raise reader.error(f"unexpected character {raw[pos:pos + 1]!r} in the .x file", pos)
        kind = m.lastgroup
        if kind == "num":
            token = m.group()
            yield "numbers", (float(token) if b"." in token or b"e" in token or b"E" in token
                              else int(token)), pos
        elif kind == "name":
            yield "name", m.group().decode("ascii"), pos
        elif kind == "string":
            yield "string", m.group()[1:-1].decode("latin-1"), pos
        elif kind == "open":
            yield "{", None, pos
        elif kind == "close":
            yield "}", None, pos
        elif kind in ("guid", "other"):
            yield kind, None, pos
        pos = m.end()


# binary token numbers (X File Format Reference, "Binary Format": tokens)
_NAME, _STRING, _INTEGER, _GUID, _INTEGER_LIST, _FLOAT_LIST = 1, 2, 3, 5, 6, 7
_OBRACE, _CBRACE = 10, 11
_PUNCTUATION = {12, 13, 14, 15, 16, 17, 18, 19, 20}           # ( ) [ ] < > . , ;
_TYPE_WORDS = {31, 40, 41, 42, 43, 44, 45, 46, 47, 48, 49, 50, 51, 52, 53}  # template, WORD...


def _binary_tokens(reader: _Reader, start: int, double: bool):
    raw = reader.raw
    pos, end = start, len(raw)
    most = limits.get("mesh_indices")
    width, code = (8, "<d") if double else (4, "<f")

    def need(count: int, at: int) -> None:
        if pos + count > end:
            raise reader.error("the .x file ends inside a token", at)

    while pos < end:
        at = pos
        need(2, at)
        token = struct.unpack_from("<H", raw, pos)[0]
        pos += 2
        if token in (_NAME, _STRING):
            need(4, at)
            count = struct.unpack_from("<I", raw, pos)[0]
            pos += 4
            need(count, at)
            text = raw[pos:pos + count].decode("latin-1")
            pos += count
            if token == _STRING:
                need(2, at)
                pos += 2                                    # its terminator (; or ,)
                yield "string", text, at
            else:
                yield "name", text, at
        elif token == _INTEGER:
            need(4, at)
            yield "numbers", struct.unpack_from("<I", raw, pos)[0], at
            pos += 4
        elif token == _GUID:
            need(16, at)
            pos += 16
            yield "guid", None, at
        elif token in (_INTEGER_LIST, _FLOAT_LIST):
            need(4, at)
            count = struct.unpack_from("<I", raw, pos)[0]
            pos += 4
            size = 4 if token == _INTEGER_LIST else width
            if count > most * 4:     # more numbers than any mesh within the limits holds
                raise reader.error(limits.message("mesh_indices", count,
                                                  "a number list of the .x file"), at)
            need(count * size, at)
            dtype = np.dtype("<u4" if token == _INTEGER_LIST else code)
            values = np.frombuffer(raw, dtype=dtype, count=count, offset=pos)
            pos += count * size
            yield "numbers", values, at
        elif token == _OBRACE:
            yield "{", None, at
        elif token == _CBRACE:
            yield "}", None, at
        elif token in _PUNCTUATION or token in _TYPE_WORDS:
            yield "other", None, at
        else:
            raise reader.error(f"unknown binary .x token {token}", at)


# ---------------------------------------------------------------------------------------------
# The object tree


def parse(path: str, raw: bytes) -> list[XObject]:
    """The top-level data objects of an .x file (templates read past)."""
    m = HEADER.match(raw)
    if m is None:
        raise SceneError("not a DirectX .x file: it does not start with a header such as "
                         "'xof 0303txt 0032'", Location(path, 1, 1))
    fmt, floats = m.group(2), m.group(3)
    if fmt in (b"tzip", b"bzip"):
        raise SceneError(f"compressed .x files ('{fmt.decode()}') are not read; save it as "
                         "text or binary", Location(path, 1, 1))
    text = fmt == b"txt "
    reader = _Reader(path, raw, text)
    tokens = _text_tokens(reader, m.end()) if text else \
        _binary_tokens(reader, m.end(), floats == b"0064")
    return _objects(reader, tokens)


def _objects(reader: _Reader, tokens) -> list[XObject]:
    """Data objects from tokens, as a stack (no recursion: the nesting is `mesh_nesting`)."""
    top: list[XObject] = []
    stack: list[XObject] = []
    pending: list[tuple[str, object, int]] = []      # a name (and its object's name) before {
    most = limits.get("mesh_nesting")
    skip = 0                                          # inside a template or a reference
    count = 0
    for kind, value, at in tokens:
        if skip:
            if kind == "{":
                skip += 1
            elif kind == "}":
                skip -= 1
            continue
        if kind == "name":
            pending.append((kind, value, at))
            if len(pending) > 2:
                raise reader.error(f"unexpected name '{pending[0][1]}' (a value of the .x "
                                   "file's objects is a number or a string)", pending[0][2])
            continue
        if kind == "{":
            if not pending:
                skip = 1                              # a reference: { name } or { <guid> }
                continue
            if pending[0][1] == "template":
                pending.clear()
                skip = 1
                continue
            if len(stack) >= most:
                raise reader.error(limits.message("mesh_nesting", len(stack) + 1,
                                                  "the .x file's objects"), at)
            obj = XObject(str(pending[0][1]), str(pending[1][1]) if len(pending) > 1 else "",
                          pending[0][2])
            pending.clear()
            count += 1
            (stack[-1].children if stack else top).append(obj)
            stack.append(obj)
            continue
        if pending:
            raise reader.error(f"'{pending[0][1]}' is not followed by '{{'", pending[0][2])
        if kind == "}":
            if not stack:
                raise reader.error("'}' closes no object", at)
            stack.pop()
        elif kind == "numbers":
            if not stack:
                raise reader.error("a number outside any object", at)
            stack[-1].numbers.append(value)
        # strings, GUIDs and punctuation carry nothing the standard templates read here
    if skip or stack:
        name = stack[-1].kind if stack else "template"
        raise reader.error(f"the .x file ends inside {name} (a '}}' is missing)",
                           stack[-1].offset if stack else len(reader.raw))
    if pending:
        raise reader.error(f"'{pending[0][1]}' is not followed by '{{'", pending[0][2])
    return top


# ---------------------------------------------------------------------------------------------
# Meshes


class _Numbers:
    """An object's numbers, taken in template order; running short is a located error."""

    def __init__(self, reader: _Reader, obj: XObject) -> None:
        self.reader, self.obj = reader, obj
        self.values = obj.values()
        self.pos = 0

    def error(self, message: str) -> SceneError:
        return self.reader.error(f"{self.obj.kind}: {message}", self.obj.offset)

    def count(self, what: str, limit: str) -> int:
        n = self.take(1, what)[0]
        if n < 0 or n != int(n):
            raise self.error(f"{what} is {n}, not a count")
        limits.check(limit, int(n), self.reader.where(self.obj.offset),
                     f"the .x file's {self.obj.kind} ({what})", SceneError)
        return int(n)

    def take(self, n: int, what: str) -> np.ndarray:
        if self.pos + n > len(self.values):
            raise self.error(f"{what}: {n} numbers needed, {len(self.values) - self.pos} left")
        out = self.values[self.pos:self.pos + n]
        self.pos += n
        return out

    def faces(self, what: str) -> list[np.ndarray]:
        """nFaces, then per face n and n indices."""
        count = self.count(f"n{what}", "mesh_indices")
        faces = []
        total = 0
        for _ in range(count):
            n = self.count(f"a {what[:-1] if what.endswith('s') else what} size", "mesh_indices")
            if n < 3:
                raise self.error(f"a face of {n} vertices (a face needs 3)")
            total += 3 * (n - 2)
            limits.check("mesh_indices", total, self.reader.where(self.obj.offset),
                         f"the .x file's {self.obj.kind} (3 indices a triangle)", SceneError)
            faces.append(self.take(n, f"a face's {n} indices").astype(np.int64))
        return faces


@dataclass
class XMesh:
    """A file's meshes as arrays: what `effects.assets.meshes.make_mesh` takes."""

    positions: np.ndarray          # (N, 3), placed by the frames
    uv: np.ndarray                 # (N, 2)
    triangles: np.ndarray          # (M, 3)
    normals: np.ndarray            # (N, 3) unit
    colors: np.ndarray | None      # (N, 4) or None
    name: str


@dataclass
class _Part:
    positions: np.ndarray
    normals: np.ndarray | None
    uv: np.ndarray | None
    colors: np.ndarray | None
    triangles: np.ndarray          # (M, 3) into positions


def _mesh_part(reader: _Reader, obj: XObject, matrix: np.ndarray) -> _Part:
    nums = _Numbers(reader, obj)
    n = nums.count("nVertices", "mesh_vertices")
    positions = nums.take(3 * n, f"{n} vertices").reshape(n, 3)
    faces = nums.faces("Faces")
    normals = uv = colors = None
    face_normals: list[np.ndarray] | None = None
    normal_list = None
    for child in obj.children:
        sub = _Numbers(reader, child)
        if child.kind == "MeshNormals":
            k = sub.count("nNormals", "mesh_vertices")
            normal_list = sub.take(3 * k, f"{k} normals").reshape(k, 3)
            face_normals = sub.faces("FaceNormals")
            if len(face_normals) != len(faces):
                raise sub.error(f"{len(face_normals)} face normals for {len(faces)} faces")
        elif child.kind == "MeshTextureCoords":
            k = sub.count("nTextureCoords", "mesh_vertices")
            if k != n:
                raise sub.error(f"{k} texture coordinates for {n} vertices")
            uv = sub.take(2 * k, f"{k} texture coordinates").reshape(k, 2)
        elif child.kind == "MeshVertexColors":
            k = sub.count("nVertexColors", "mesh_vertices")
            table = sub.take(5 * k, f"{k} vertex colours").reshape(k, 5)
            index = table[:, 0].astype(np.int64)
            if k and (index.min() < 0 or index.max() >= n):
                raise sub.error(f"a vertex colour's index is outside 0..{n - 1}")
            colors = np.ones((n, 4))
            colors[index] = table[:, 1:]
    for face in faces:
        if face.size and (face.min() < 0 or face.max() >= n):
            raise nums.error(f"a face's vertex index is outside 0..{n - 1}")
    # corners: (vertex, normal) pairs; a vertex with two normals becomes two vertices
    corners = np.concatenate(faces) if faces else np.zeros(0, np.int64)
    if face_normals is not None and normal_list is not None:
        normal_corners = np.concatenate(face_normals) if face_normals else np.zeros(0, np.int64)
        sizes = [len(f) for f in faces]
        if [len(f) for f in face_normals] != sizes:
            raise reader.error("MeshNormals: its faces' sizes differ from the mesh's",
                               obj.offset)
        if normal_corners.size and (normal_corners.min() < 0
                                    or normal_corners.max() >= len(normal_list)):
            raise reader.error(f"MeshNormals: a face's normal index is outside "
                               f"0..{len(normal_list) - 1}", obj.offset)
        pairs = np.stack([corners, normal_corners], axis=1)
        unique, inverse = np.unique(pairs, axis=0, return_inverse=True)
        limits.check("mesh_vertices", len(unique), reader.where(obj.offset),
                     "the .x file's mesh (a vertex for each distinct vertex and normal)",
                     SceneError)
        vertex_of = unique[:, 0]
        normals = normal_list[unique[:, 1]]
        corner_vertex = inverse.reshape(-1)
    else:
        vertex_of = np.arange(n)
        corner_vertex = corners
    # fan each face into triangles, over the corners' new vertex numbers
    tris = []
    start = 0
    for face in faces:
        k = len(face)
        idx = corner_vertex[start:start + k]
        tris.append(np.stack([np.full(k - 2, idx[0]), idx[1:-1], idx[2:]], axis=1))
        start += k
    triangles = np.concatenate(tris) if tris else np.zeros((0, 3), np.int64)
    p = positions[vertex_of]
    p = np.concatenate([p, np.ones((len(p), 1))], axis=1) @ matrix
    part_normals = None
    if normals is not None:
        part_normals = normals @ np.linalg.inv(matrix[:3, :3]).T
        length = np.linalg.norm(part_normals, axis=1, keepdims=True)
        part_normals = np.divide(part_normals, length, out=np.zeros_like(part_normals),
                                 where=length > 0)
    return _Part(p[:, :3], part_normals, None if uv is None else uv[vertex_of],
                 None if colors is None else colors[vertex_of], triangles)


def _walk(reader: _Reader, objects: list[XObject], matrix: np.ndarray, parts: list[_Part]) -> None:
    """Meshes under `objects`, each frame's matrix over its parents' (iteratively)."""
    work = [(objects, matrix)]
    while work:
        level, m = work.pop(0)
        local = m
        for obj in level:
            if obj.kind == "FrameTransformMatrix":
                values = _Numbers(reader, obj).take(16, "the matrix's 16 numbers")
                local = values.reshape(4, 4) @ m
                if not np.all(np.isfinite(local)) or abs(np.linalg.det(local[:3, :3])) < 1e-30:
                    raise reader.error("FrameTransformMatrix: not an invertible transform",
                                       obj.offset)
        for obj in level:
            if obj.kind == "Frame":
                work.append((obj.children, local))
            elif obj.kind == "Mesh":
                parts.append(_mesh_part(reader, obj, local))


def _index_normals(positions: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """Normals for a mesh whose file gives none, as D3DXComputeNormals makes them: each
    vertex the area-weighted sum of its triangles' normals, by vertex index (a cube's 24
    vertices keep flat faces; `make_mesh` would merge them by position into a rounded one)."""
    p = positions[triangles]
    face = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    normals = np.zeros_like(positions)
    for corner in range(3):
        np.add.at(normals, triangles[:, corner], face)
    length = np.linalg.norm(normals, axis=1, keepdims=True)
    fallback = np.zeros_like(normals)
    fallback[:, 1] = 1.0            # a vertex of no triangle's area: any unit vector
    return np.where(length > 0, normals / np.where(length > 0, length, 1.0), fallback)


def read_x(path: str | os.PathLike[str]) -> XMesh:
    """Read a DirectX .x file (text or binary): every mesh of it, merged, placed by its frames
    (see the module docstring). `effects.assets.meshes.load_x` makes the Mesh of it."""
    path = os.fspath(path)
    raw = untrusted.read_file(path, ".x file", SceneError, "mesh_file_bytes")
    reader = _Reader(path, raw, raw[8:12] == b"txt ")
    parts: list[_Part] = []
    _walk(reader, parse(path, raw), np.identity(4), parts)
    parts = [p for p in parts if len(p.triangles)]
    if not parts:
        raise SceneError(".x file has no mesh with faces", Location(path, 1, 1))
    offsets = np.cumsum([0] + [len(p.positions) for p in parts])
    limits.check("mesh_vertices", int(offsets[-1]), Location(path, 1, 1),
                 "the .x file's meshes together", SceneError)
    positions = np.concatenate([p.positions for p in parts])
    triangles = np.concatenate([p.triangles + o for p, o in zip(parts, offsets)])
    uv = np.concatenate([p.uv if p.uv is not None else np.zeros((len(p.positions), 2))
                         for p in parts])
    normals = None
    if all(p.normals is not None for p in parts):
        normals = np.concatenate([p.normals for p in parts])
    if normals is None or not np.all(np.any(normals, axis=1)):
        normals = _index_normals(positions, triangles)
    colors = None
    if any(p.colors is not None for p in parts):
        colors = np.concatenate([p.colors if p.colors is not None
                                 else np.ones((len(p.positions), 4)) for p in parts])
    for what, values in (("vertex", positions), ("texture coordinate", uv)):
        if not np.all(np.isfinite(values)):
            raise SceneError(f".x file has a {what} that is not a finite number",
                             Location(path, 1, 1))
    return XMesh(positions, uv, triangles, normals, colors, os.path.basename(path))
