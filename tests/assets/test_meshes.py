"""Meshes: geometry, winding, tangent frames (averaged, continuous across the texture seam) and
the .obj reader with located errors."""
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from effects.assets import meshes as M
from effects.base.errors import SceneError


def face_normals(mesh):
    p = mesh.positions[mesh.indices].astype(np.float64)
    return np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), p.mean(axis=1)


def signed_volume(mesh):
    p = mesh.positions[mesh.indices].astype(np.float64)
    return float(np.einsum("ij,ij->i", p[:, 0], np.cross(p[:, 1], p[:, 2])).sum() / 6)


def unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def assert_orthonormal_frames(mesh):
    for v in (mesh.normals, mesh.tangents, mesh.binormals):
        assert np.allclose(np.linalg.norm(v, axis=1), 1, atol=1e-5)
    assert np.abs(np.sum(mesh.normals * mesh.tangents, 1)).max() < 1e-5
    assert np.abs(np.sum(mesh.normals * mesh.binormals, 1)).max() < 1e-5
    assert np.abs(np.sum(mesh.tangents * mesh.binormals, 1)).max() < 1e-5


def edge_counts(mesh):
    """How many triangles use each undirected edge, vertices identified by position."""
    _, pid = np.unique(np.round(mesh.positions, 5), axis=0, return_inverse=True)
    tri = pid.ravel()[mesh.indices]
    edges = np.sort(np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    return counts


# ---- sphere ------------------------------------------------------------------------------------

def test_sphere_normals_are_unit_positions():
    s = M.sphere(12, 24)
    assert s.positions.dtype == np.float32 and s.indices.dtype == np.uint32
    assert np.allclose(np.linalg.norm(s.positions, axis=1), 1, atol=1e-6)
    assert np.allclose(s.normals, s.positions, atol=1e-6)
    assert_orthonormal_frames(s)


def test_sphere_winding_is_outward_and_closed():
    s = M.sphere(12, 24)
    n, centre = face_normals(s)
    assert np.all(np.sum(n * centre, axis=1) > 0)
    assert np.all(edge_counts(s) == 2)
    # 4/3 pi r^3 is approached from below by the inscribed polyhedron
    assert 0.95 * 4 / 3 * np.pi < signed_volume(s) < 4 / 3 * np.pi


def test_sphere_tangents_follow_u_and_binormals_follow_v():
    s = M.sphere(24, 48)
    phi = 2 * np.pi * s.uv[:, 0].astype(np.float64)
    theta = np.pi * s.uv[:, 1].astype(np.float64)
    away = (theta > 0.2) & (theta < np.pi - 0.2)              # off the poles
    dpdu = np.stack([-np.sin(phi), 0 * phi, np.cos(phi)], 1)  # d/du of (sin t cos p, cos t, sin t sin p)
    dpdv = np.stack([np.cos(theta) * np.cos(phi), -np.sin(theta), np.cos(theta) * np.sin(phi)], 1)
    assert np.min(np.sum(s.tangents[away] * dpdu[away], 1)) > 0.995
    assert np.min(np.sum(s.binormals[away] * dpdv[away], 1)) > 0.995


def test_sphere_frames_are_continuous_across_the_seam():
    rings, segments = 12, 24
    s = M.sphere(rings, segments)
    grid = np.arange((rings + 1) * (segments + 1)).reshape(rings + 1, segments + 1)
    left, right = grid[1:-1, 0], grid[1:-1, -1]                # u = 0 and u = 1 columns
    assert np.all(s.uv[left, 0] == 0) and np.all(s.uv[right, 0] == 1)
    np.testing.assert_array_equal(s.positions[left], s.positions[right])
    for attr in ("normals", "tangents", "binormals"):
        a, b = getattr(s, attr)[left], getattr(s, attr)[right]
        assert np.allclose(a, b, atol=1e-6), attr
    # the pooled frame averages both sides: close to the smooth dP/du = +z at u = 0, where
    # either side alone would lean 7.5 degrees (half a segment) towards its own facets
    assert np.min(s.tangents[left] @ np.array([0, 0, 1.0])) > 0.998


# ---- other shapes ------------------------------------------------------------------------------

def test_cube_faces():
    c = M.cube()
    assert (c.vertex_count, c.triangle_count) == (24, 12)
    assert signed_volume(c) == pytest.approx(1.0)
    n, _ = face_normals(c)
    per_triangle_normal = c.normals[c.indices[:, 0]]
    assert np.allclose(unit(n), per_triangle_normal)
    assert_orthonormal_frames(c)
    front = np.all(c.normals == [0, 0, 1], axis=1)               # +Z face: u towards -x, v towards -y
    assert np.allclose(c.tangents[front], [-1, 0, 0]) and np.allclose(c.binormals[front], [0, -1, 0])
    assert np.all(edge_counts(c) == 2)


def test_torus_closed_outward_and_seamless():
    t = M.torus(24, 12, radius=0.7, tube=0.3)
    assert np.all(edge_counts(t) == 2)
    smooth = 2 * np.pi ** 2 * 0.7 * 0.3 ** 2     # Pappus; the inscribed mesh holds a little less
    assert 0.9 * smooth < signed_volume(t) < smooth
    ring = unit(t.positions * np.array([1, 0, 1]))
    centre_of_tube = 0.7 * ring
    assert np.allclose(t.normals, unit(t.positions - centre_of_tube), atol=1e-5)
    assert_orthonormal_frames(t)
    grid = np.arange(25 * 13).reshape(25, 13)
    for a, b in ((grid[0], grid[-1]), (grid[:, 0], grid[:, -1])):   # both seams
        assert np.allclose(t.tangents[a], t.tangents[b], atol=1e-6)
        assert np.allclose(t.binormals[a], t.binormals[b], atol=1e-6)


def test_teapot_faces_out():
    t = M.teapot(6)
    assert t.triangle_count > 32 * 6 * 6   # 2 per cell, less the degenerate ones
    # its volume (lid gap and all) is that of the classic model scaled by 0.3^3
    assert signed_volume(t) > 0.5
    n, _ = face_normals(t)
    agree = np.sum(unit(n) * t.normals[t.indices].mean(axis=1), axis=1)
    assert np.mean(agree > 0) > 0.99          # winding agrees with the smooth normals
    assert_orthonormal_frames(t)
    lowest = np.argmin(t.positions[:, 1])
    assert t.normals[lowest][1] < -0.9        # the bottom faces down
    highest = np.argmax(t.positions[:, 1])
    assert t.normals[highest][1] > 0.9        # the lid knob faces up


def test_quad_is_clip_space_full_screen():
    q = M.quad()
    assert q.space == "clip"
    assert q.positions[:, :2].min() == -1 and q.positions[:, :2].max() == 1
    assert np.all(q.positions[:, 2] == 0.5)
    top_left = np.argmin(q.positions[:, 0] - q.positions[:, 1])
    assert q.uv[top_left].tolist() == [0, 0]
    n, _ = face_normals(q)
    assert np.all(n[:, 2] < 0)                # towards the viewer of a left-handed view
    assert np.allclose(q.tangents, [1, 0, 0]) and np.allclose(q.binormals, [0, -1, 0])


def test_mirrored_uvs_flip_the_binormal():
    positions = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
    plain = M.make_mesh(positions, [[0, 0], [1, 0], [0, 1]], [[0, 1, 2]], name="t")
    mirrored = M.make_mesh(positions, [[0, 0], [1, 0], [0, -1]], [[0, 1, 2]], name="t")
    assert np.allclose(plain.normals, [0, 0, 1])
    assert np.allclose(plain.binormals, [0, 1, 0]) and np.allclose(mirrored.binormals, [0, -1, 0])
    assert np.allclose(mirrored.tangents, [1, 0, 0])


# ---- .obj -------------------------------------------------------------------------------------

OBJ = """# a unit square (quad) and a triangle on top, mixed index forms
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0.5 2 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
f 1/1/1 2/2/1 3/3/1 4/4/1
f -2//1 -3//1 -1//1
"""


def test_obj_quads_negative_indices_and_flipped_v(tmp_path):
    path = tmp_path / "m.obj"
    path.write_text(OBJ)
    m = M.load_obj(path)
    assert m.triangle_count == 3
    assert np.allclose(m.normals, [0, 0, 1])
    first = m.indices[0]
    assert m.positions[first].tolist() == [[0, 0, 0], [1, 0, 0], [1, 1, 0]]
    assert m.uv[first].tolist() == [[0, 1], [1, 1], [1, 0]]    # v flipped to the top-left origin
    last = m.indices[2]
    assert m.positions[last].tolist() == [[0, 1, 0], [1, 1, 0], [0.5, 2, 0]]
    assert np.allclose(m.tangents[first], [1, 0, 0]) and np.allclose(m.binormals[first], [0, -1, 0])


def test_obj_without_normals_gets_smooth_ones(tmp_path):
    path = tmp_path / "tet.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    m = M.load_obj(path)
    assert signed_volume(m) == pytest.approx(1 / 6)
    # at (1, 0, 0): area-weighted face normals 0.5 (0, 0, -1) + 0.5 (0, -1, 0) + (sqrt 3 / 2) (1, 1, 1) / sqrt 3
    # sum to (0.5, 0, 0)
    corner = m.positions.tolist().index([1, 0, 0])
    assert np.allclose(m.normals[corner], [1, 0, 0], atol=1e-6)


@pytest.mark.parametrize("text, line, column, message", [
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", 4, 7, "vertex index 9 is out of range"),
    ("v 0 0 0\nv 1 x 0\n", 2, 5, "bad vertex number 'x'"),
    ("v 0 0 0\nv 1 0 0\nf 1 2\n", 3, 1, "a face needs at least 3 vertices"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/4 2 3\n", 4, 3, "texture coordinate index 4 is out of range"),
    ("v 0 0 0\n", 1, 1, "no faces"),
])
def test_obj_errors_are_located(tmp_path, text, line, column, message):
    path = tmp_path / "bad.obj"
    path.write_text(text)
    with pytest.raises(SceneError) as info:
        M.load_obj(path)
    assert message in str(info.value)
    assert (info.value.line, info.value.column) == (line, column)
    assert str(info.value).startswith(f"{path}:{line}:{column}: error:")


def test_by_name(tmp_path):
    assert M.by_name("teapot").name == "teapot"
    (tmp_path / "m.obj").write_text(OBJ)
    assert M.by_name("m.obj", base_dir=str(tmp_path)).triangle_count == 3
    with pytest.raises(SceneError, match="unknown mesh 'donut'"):
        M.by_name("donut")
    with pytest.raises(SceneError, match="mesh file not found"):
        M.by_name("gone.obj", base_dir=str(tmp_path))


# -- the vectorised .obj reader ---------------------------------------------------------------

_OBJ_GRID = "".join(f"v {x * 0.5} {y * 0.25} {(x * y) % 3 * 0.1}\n" for y in range(4) for x in range(4))
_OBJ_UV = "".join(f"vt {x / 3} {y / 3}\n" for y in range(4) for x in range(4))
_OBJ_N = "".join(f"vn 0 {1 + x % 2} {y % 2}\n" for y in range(4) for x in range(4))


def _faces(form: str) -> str:
    out = []
    for y in range(3):
        for x in range(3):
            a, b, c, d = (y * 4 + x + 1, y * 4 + x + 2, y * 4 + x + 5, y * 4 + x + 6)
            for tri in ((a, c, b), (b, c, d)):
                out.append("f " + " ".join(form.format(i=i, t=(i % 16) + 1, n=17 - i) for i in tri))
    return "\n".join(out) + "\n"


@pytest.mark.parametrize("header, form", [
    (_OBJ_GRID, "{i}"), (_OBJ_GRID + _OBJ_UV, "{i}/{t}"), (_OBJ_GRID + _OBJ_N, "{i}//{n}"),
    ("# a comment\no grid\n" + _OBJ_GRID + _OBJ_UV + _OBJ_N + "s 1\r\n", "{i}/{t}/{n}"),
])
def test_fast_obj_reader_makes_the_per_line_readers_mesh(tmp_path, monkeypatch, header, form):
    from effects.assets import obj_fast
    path = tmp_path / "m.obj"
    path.write_text(header + _faces(form))
    assert obj_fast.parse(path.read_bytes()) is not None
    fast = M.load_obj(path)
    monkeypatch.setattr(obj_fast, "parse", lambda raw, check_counts=None: None)
    slow = M.load_obj(path)
    for name in ("positions", "normals", "uv", "tangents", "binormals", "indices"):
        np.testing.assert_array_equal(getattr(fast, name), getattr(slow, name))


@pytest.mark.parametrize("text", [
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3 4\n",               # a quad
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n",                       # negative indices
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 # a comment\n",              # a comment after it
    "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n",                          # a face before its vertex
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1/1 3/1\n",         # mixed corner forms
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1 2/1/1/1 3/1/1\n",  # 2 + 4 fields
    "v 0 0 0\nv 1 0 0\nv 0 x 0\nf 1 2 3\n",                          # a bad number
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",                          # out of range
    "  v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",                        # indented
    "v 0 0 0\nv 1 0\u00a0 0\nv 0 1 0\nf 1 2 3\n",                    # odd whitespace
])
def test_fast_obj_reader_leaves_irregular_files_to_the_per_line_reader(text):
    from effects.assets import obj_fast
    assert obj_fast.parse(text.encode()) is None


def _fast_and_slow(path, monkeypatch):
    from effects.assets import obj_fast
    fast = M.load_obj(path)
    with monkeypatch.context() as patch:
        patch.setattr(obj_fast, "parse", lambda raw, check_counts=None: None)
        slow = M.load_obj(path)
    return fast, slow


def _assert_same_mesh(fast, slow):
    for name in ("positions", "normals", "uv", "tangents", "binormals", "indices"):
        a, b = getattr(fast, name), getattr(slow, name)
        assert a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes(), name


# Spellings float() reads: the plain ones go through the digit arithmetic (up to 15 digits),
# the rest (exponents, 16+ digits, underscores, inf) through float() one by one.
_SPELLINGS = ["0.5", "-0.000000", "+1.25", ".5", "-.75", "7.", "00012.5000", "123456789012345",
              "1234567890123456", "0.30000000000000004", "0.1234567890123456789", "1e-3", "-2.5E+2",
              "1_0", "9007199254740993", "-1.994342", "3", "0.1", "0.7", "1.15", "2.675"]


@pytest.mark.parametrize("spelling", _SPELLINGS)
def test_fast_obj_reader_reads_each_number_as_float_does(tmp_path, monkeypatch, spelling):
    from effects.assets import obj_fast
    text = (f"v {spelling} 0 0\nv 1 {spelling} 0\nv 0 1 {spelling}\nvt {spelling} 0.5\n"
            f"vn 0 0 1\nf 1/1/1 2/1/1 3/1/1\n")
    assert obj_fast.parse(text.encode()) is not None
    positions = obj_fast.parse(text.encode())[0]
    assert positions[0, 0] == float(spelling) and positions[1, 1] == float(spelling)
    path = tmp_path / "m.obj"
    path.write_text(text)
    _assert_same_mesh(*_fast_and_slow(path, monkeypatch))


def test_fast_obj_reader_plain_numbers_are_float_exactly():
    """Many random plain spellings (sign, point, 1-15 digits): every double equals float()'s,
    bit for bit (the digits and the power of ten are exact; one division rounds)."""
    from effects.assets import obj_fast
    rng = np.random.default_rng(7)
    words = []
    for _ in range(20000):
        digits = "".join(map(str, rng.integers(0, 10, rng.integers(1, 16))))
        cut = int(rng.integers(0, len(digits) + 1))
        words.append(str(rng.choice(["", "-", "+"])) + digits[:cut] + "." + digits[cut:])
    words = words[:len(words) // 9 * 9]
    text = "".join(f"v {words[i]} {words[i + 1]} {words[i + 2]}\n" for i in range(0, len(words), 3))
    faces = "".join(f"f {i + 1} {i + 2} {i + 3}\n" for i in range(0, len(words) // 3, 3))
    positions = obj_fast.parse((text + faces).encode())[0]   # every vertex, in file order
    assert positions.tobytes() == np.array([float(w) for w in words]).reshape(-1, 3).tobytes()


def test_fast_obj_reader_in_small_batches_and_scattered_lines(tmp_path, monkeypatch):
    """Batches of a few lines and vertex lines interleaved by kind (gathered, not copied as a
    span) make the same mesh as the per-line reader."""
    from effects.assets import obj_fast
    rng = np.random.default_rng(3)
    n = 150
    lines = []
    for i in range(n):   # v, vt, vn interleaved: hundreds of one-line spans
        lines += [f"v {rng.normal():.6f} {rng.normal():.6f} {rng.normal():.6f}",
                  f"vt {rng.random():.5f} {rng.random():.5f}", f"vn {rng.normal():.4f} 1 0.5"]
    for _ in range(300):
        a, b, c = rng.integers(1, n + 1, 3)
        lines.append(f"f {a}/{b}/{c} {b}/{c}/{a}  {c}/{a}/{b}")
    path = tmp_path / "m.obj"
    path.write_text("\n".join(lines) + "\n")
    monkeypatch.setattr(obj_fast, "_BATCH", 100)
    _assert_same_mesh(*_fast_and_slow(path, monkeypatch))


def test_fast_obj_reader_wants_one_corner_form_in_every_batch(monkeypatch):
    from effects.assets import obj_fast
    monkeypatch.setattr(obj_fast, "_BATCH", 16)
    head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
    assert obj_fast.parse((head + "f 1/1 2/1 3/1\n" * 4).encode()) is not None
    assert obj_fast.parse((head + "f 1/1 2/1 3/1\n" * 4 + "f 1//1 2//1 3//1\n").encode()) is None


_CORNERS = {"v": "{i}", "v/vt": "{i}/{t}", "v//vn": "{i}//{n}", "v/vt/vn": "{i}/{t}/{n}"}


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data())
def test_fast_obj_reader_matches_the_per_line_reader_on_random_files(tmp_path, monkeypatch, data):
    """Random regular files (numbers of any spelling float() takes, any corner form, \\r\\n
    or \\n, spaces or tabs): the fast reader's mesh is the per-line reader's, bit for bit."""
    from effects.assets import obj_fast
    number = st.one_of(
        st.floats(-1e6, 1e6, allow_nan=False).map(repr),
        st.floats(-1e3, 1e3, allow_nan=False).map(lambda x: f"{x:.6f}"),
        st.floats(-1e3, 1e3, allow_nan=False).map(lambda x: f"{x:e}"),
        st.integers(-10 ** 17, 10 ** 17).map(str),
        st.sampled_from(_SPELLINGS))
    nv, nt, nn = (data.draw(st.integers(3, 12)), data.draw(st.integers(1, 6)),
                  data.draw(st.integers(1, 6)))
    space = data.draw(st.sampled_from([" ", "\t", "  "]))
    lines = [f"v{space}" + space.join(data.draw(st.lists(number, min_size=3, max_size=3)))
             for _ in range(nv)]
    lines += [f"vt{space}" + space.join(data.draw(st.lists(number, min_size=2, max_size=2)))
              for _ in range(nt)]
    lines += [f"vn{space}" + space.join(data.draw(st.lists(number, min_size=3, max_size=3)))
              for _ in range(nn)]
    lines = data.draw(st.permutations(lines))
    form = _CORNERS[data.draw(st.sampled_from(sorted(_CORNERS)))]
    for _ in range(data.draw(st.integers(1, 10))):
        corners = [form.format(i=data.draw(st.integers(1, nv)), t=data.draw(st.integers(1, nt)),
                               n=data.draw(st.integers(1, nn))) for _ in range(3)]
        lines.append("f " + space.join(corners))
    end = data.draw(st.sampled_from(["\n", "\r\n"]))
    raw = (end.join(lines) + end).encode()
    monkeypatch.setattr(obj_fast, "_BATCH", data.draw(st.sampled_from([8, 64, 1 << 20])))
    assert obj_fast.parse(raw) is not None
    path = tmp_path / "m.obj"
    path.write_bytes(raw)
    _assert_same_mesh(*_fast_and_slow(path, monkeypatch))


def test_fast_obj_reader_numbers_corners_by_vertex_or_by_triple(tmp_path, monkeypatch):
    """Corners are numbered in order of first appearance of their (v, vt, vn) triple. Where
    every vertex comes with one vt and one vn (as exporters write) the fast reader numbers
    them by vertex through a table; where a vertex comes with two (a UV seam, a crease) by
    a sort of the triples. Both make the per-line reader's mesh."""
    from effects.assets import obj_fast
    taken = []
    for name in ("_number_by_vertex", "_number_by_key"):
        real = getattr(obj_fast, name)
        monkeypatch.setattr(obj_fast, name,
                            lambda *a, _real=real, _name=name: taken.append(_name) or _real(*a))
    # vertex 2 with vt 1 and vt 3, vertex 3 with vn 1 and vn 2: a seam and a crease; the
    # faces list the vertices out of order, so first appearance is not vertex order
    seam = ("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nvn 0 1 1\n"
            "f 3/3/1 1/1/1 2/1/1\nf 2/3/1 4/2/2 3/3/2\n")
    cases = {"seam": seam, "by vertex": _OBJ_GRID + _OBJ_UV + _OBJ_N + _faces("{i}/{t}/{n}")}
    for label, text in cases.items():
        taken.clear()
        path = tmp_path / "m.obj"
        path.write_text(text)
        fast, slow = _fast_and_slow(path, monkeypatch)
        _assert_same_mesh(fast, slow)
        assert taken[-1] == ("_number_by_key" if label == "seam" else "_number_by_vertex")
    assert fast.vertex_count == 16 and M.load_obj(tmp_path / "m.obj").triangle_count == 18


@pytest.mark.parametrize("text", [
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv\t1 1 0\nf 1 2 3\nf 2 4 3\n",       # read by the fast reader
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv\t1 1 0\nf 1 2 4 3\n",               # a quad: the per-line one
])
def test_obj_vertex_limit_is_checked_before_either_reader_reads(tmp_path, text):
    from effects.base import limits
    path = tmp_path / "m.obj"
    path.write_text(text)
    with limits.raised(mesh_vertices=4):
        assert M.load_obj(path).vertex_count == 4
    with limits.raised(mesh_vertices=3), pytest.raises(SceneError,
                                                       match="has 4 vertices; the limit is 3"):
        M.load_obj(path)
