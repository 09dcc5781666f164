"""DirectX .x meshes (effects.assets.xfile): the SDK's own sample files, text and binary, frames
and their matrices, normals per face corner, and hostile files refused with located errors
within the limits; drawn by a scene, `--mesh`, and EffectEdit's `string XFile`, on both back
ends alike."""
from __future__ import annotations

from tests.paths import ROOT

import struct

import numpy as np
import pytest

import effects
from effects.assets.meshes import by_name
from effects.assets.meshes import load_x
from effects.base import limits
from effects.base.errors import SceneError

XMESHES = ROOT / "tests" / "data" / "xmeshes"
CUBE = XMESHES / "Cube.x"          # DirectX SDK Media/misc/Cube.x (tests/data/xmeshes/MANIFEST.md)
QUAD = XMESHES / "quadlow.x"       # DirectX SDK AntiAlias sample's quadlow.x


def outward(mesh) -> np.ndarray:
    """Per triangle: cross(b - a, c - a) . its vertex normals' sum (positive: wound outwards,
    the convention of effects.assets.meshes)."""
    p = mesh.positions[mesh.indices]
    n = mesh.normals[mesh.indices].sum(axis=1)
    return np.sum(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]) * n, axis=1)


def test_the_sdk_cube_its_faces_colours_and_flat_normals():
    mesh = load_x(CUBE)
    assert (mesh.vertex_count, mesh.triangle_count) == (24, 12)
    # vertices 0-3 are the -x face (dark green in the file's comment: (6, 25, 6)), 8-11 the
    # +x face (bright green (32, 255, 32)); no MeshNormals: each face's own normal, as
    # D3DXComputeNormals gives it over the file's separate face vertices
    assert np.allclose(mesh.colors[0], (0.024, 0.098, 0.024, 1.0))
    assert np.allclose(mesh.colors[8], (0.125, 1.0, 0.125, 1.0))
    assert np.allclose(mesh.normals[:4], (-1, 0, 0)) and np.allclose(mesh.normals[8:12], (1, 0, 0))
    assert np.allclose(mesh.positions.min(axis=0), -0.5) and np.allclose(mesh.positions.max(axis=0), 0.5)
    assert (outward(mesh) > 0).all()


def test_frames_compose_their_matrices_over_the_mesh():
    """quadlow.x: DXCC_ROOT flips z, pPlane1 turns (x, y, z) into (-y, x, z): the file's
    (-0.5, 0, 0.5) lands at (0, -0.5, -0.5); its normal (0, 1, 0) turns to (-1, 0, 0); the
    winding follows (Direct3D draws the file's order through the matrix)."""
    mesh = load_x(QUAD)
    assert np.allclose(mesh.positions, [(0, -0.5, -0.5), (0, 0.5, -0.5), (0, 0.5, 0.5),
                                        (0, -0.5, 0.5)])
    assert mesh.indices.tolist() == [[3, 1, 0], [3, 2, 1]]
    assert np.allclose(mesh.normals, (-1, 0, 0))
    assert np.allclose(mesh.uv, [(0, 1), (1, 1), (1, 0), (0, 0)])
    assert (outward(mesh) > 0).all()


HAND = """xof 0303txt 0032
// a square of two faces: one quad (fanned), one triangle whose corner 1 has its own normal
Mesh square {
  5;
  0;0;0;, 1;0;0;, 1;1;0;, 0;1;0;, 2;0;0;;
  2;
  4;0,3,2,1;,
  3;1,2,4;;
  MeshNormals {
    2;
    0;0;-1;, 1;0;0;;
    2;
    4;0,0,0,0;,
    3;1,0,1;;
  }
  MeshTextureCoords { 5; 0;0;, 1;0;, 1;1;, 0;1;, 0.5;0.25;; }
}
"""


def test_faces_are_fanned_and_a_vertex_with_two_normals_becomes_two(tmp_path):
    path = tmp_path / "hand.x"
    path.write_text(HAND)
    mesh = load_x(path)
    # the quad 0,3,2,1 fans into (0,3,2) and (0,2,1); the triangle's corners (1, n1),
    # (2, n0), (4, n1): vertex 1 has normal 0 in the quad and normal 1 here -> split
    assert mesh.triangle_count == 3
    corners = mesh.positions[mesh.indices].reshape(-1, 3).tolist()
    assert corners[:6] == [[0, 0, 0], [0, 1, 0], [1, 1, 0], [0, 0, 0], [1, 1, 0], [1, 0, 0]]
    assert corners[6:] == [[1, 0, 0], [1, 1, 0], [2, 0, 0]]
    normals = mesh.normals[mesh.indices].reshape(-1, 3)
    assert np.allclose(normals[:6], (0, 0, -1))
    assert np.allclose(normals[6:], [(1, 0, 0), (0, 0, -1), (1, 0, 0)])
    assert mesh.vertex_count == 6        # (1, n0) and (1, n1) are two vertices
    uv = mesh.uv[mesh.indices].reshape(-1, 2)
    assert np.allclose(uv[8], (0.5, 0.25))


def binary(tokens: list) -> bytes:
    """A binary .x from tokens: ('name', s), ('ints', [...]), ('floats', [...]), '{', '}'."""
    out = bytearray(b"xof 0303bin 0032")
    for token in tokens:
        if token == "{":
            out += struct.pack("<H", 10)
        elif token == "}":
            out += struct.pack("<H", 11)
        elif token[0] == "name":
            out += struct.pack("<HI", 1, len(token[1])) + token[1].encode()
        elif token[0] == "ints":
            out += struct.pack(f"<HI{len(token[1])}I", 6, len(token[1]), *token[1])
        elif token[0] == "floats":
            out += struct.pack(f"<HI{len(token[1])}f", 7, len(token[1]), *token[1])
    return bytes(out)


def test_the_binary_format_reads_as_the_text_one(tmp_path):
    text = load_x(CUBE)
    p = text.positions.reshape(-1).tolist()
    faces = [3, 0, 1, 2, 3, 2, 3, 0, 3, 4, 5, 6, 3, 6, 7, 4, 3, 8, 9, 10, 3, 10, 11, 8,
             3, 12, 13, 14, 3, 14, 15, 12, 3, 16, 17, 18, 3, 18, 19, 16, 3, 20, 21, 22, 3, 22, 23, 20]
    path = tmp_path / "cube_bin.x"
    path.write_bytes(binary([("name", "Frame"), "{", ("name", "Mesh"), ("name", "CubeMesh"), "{",
                             ("ints", [24]), ("floats", p), ("ints", [12, *faces]), "}", "}"]))
    mesh = load_x(path)
    assert np.array_equal(mesh.positions, text.positions)
    assert np.array_equal(mesh.indices, text.indices)
    assert np.allclose(mesh.normals, text.normals)


@pytest.mark.parametrize("text, where, message", [
    ("xof 0303txt 003", (1, 1), "not a DirectX .x file"),
    ("xof 0303tzip0032", (1, 1), "compressed .x files ('tzip') are not read"),
    ("xof 0303txt 0032\nMesh {\n 3;\n 0;0;0;, 1;0;0;;\n}\n", (2, 1),
     "Mesh: 3 vertices: 9 numbers needed, 6 left"),
    ("xof 0303txt 0032\nMesh {\n 3;\n 0;0;0;, 1;0;0;, 0;1;0;;\n 1;\n 3;0,1,7;;\n}\n", (2, 1),
     "Mesh: a face's vertex index is outside 0..2"),
    ("xof 0303txt 0032\nMesh {\n 3;\n 0;0;0;, 1;0;0;, 0;1;0;;\n 1;\n 2;0,1;;\n}\n", (2, 1),
     "Mesh: a face of 2 vertices"),
    ("xof 0303txt 0032\nFrame {\n Mesh {\n 3;\n", (3, 2), "ends inside Mesh"),
    ("xof 0303txt 0032\nMesh {\n 3; @\n}\n", (3, 5), "unexpected character b'@'"),
    ("xof 0303txt 0032\nMesh {\n -3;\n}\n", (2, 1), "nVertices is -3.0, not a count"),
    ("xof 0303txt 0032\n}\n", (2, 1), "'}' closes no object"),
    ("xof 0303txt 0032\nFrame {\n FrameTransformMatrix { 0,0,0,0, 0,0,0,0, 0,0,0,0, 0,0,0,1;; }\n"
     " Mesh { 3; 0;0;0;, 1;0;0;, 0;1;0;; 1; 3;0,1,2;; }\n}\n", (3, 2),
     "FrameTransformMatrix: not an invertible transform"),
    ("xof 0303txt 0032\nMaterial { 1;1;1;1;; 0; 0;0;0;; 0;0;0;; }\n", (1, 1),
     ".x file has no mesh with faces"),
])
def test_a_broken_file_is_refused_where_it_breaks(tmp_path, text, where, message):
    path = tmp_path / "broken.x"
    path.write_text(text)
    with pytest.raises(SceneError) as info:
        load_x(path)
    assert message in info.value.message
    assert (info.value.location.line, info.value.location.column) == where
    assert info.value.location.path == str(path)


def test_counts_are_held_to_the_limits_before_anything_is_made(tmp_path):
    path = tmp_path / "big.x"
    # a count of four billion vertices in a few bytes: refused on the count, not allocated
    path.write_text("xof 0303txt 0032\nMesh {\n 4000000000;\n 0;0;0;;\n}\n")
    with pytest.raises(SceneError) as info:
        load_x(path)
    assert "limit mesh_vertices" in str(info.value) and info.value.location.line == 2
    with limits.raised(mesh_indices=6):
        path.write_text("xof 0303txt 0032\nMesh { 4; 0;0;0;, 1;0;0;, 1;1;0;, 0;1;0;; "
                        "2; 4;0,1,2,3;, 3;0,1,2;; }\n")
        with pytest.raises(SceneError) as info:
            load_x(path)
        assert "limit mesh_indices" in str(info.value)


def test_nesting_is_bounded_without_recursion(tmp_path):
    path = tmp_path / "deep.x"
    depth = limits.get("mesh_nesting") + 1
    path.write_text("xof 0303txt 0032\n" + "Frame {\n" * depth + "}\n" * depth)
    with pytest.raises(SceneError) as info:
        load_x(path)
    assert "limit mesh_nesting" in str(info.value) and info.value.location.line == depth + 1


def test_a_truncated_binary_file_says_where(tmp_path):
    path = tmp_path / "cut.x"
    path.write_bytes(binary([("name", "Mesh"), "{", ("ints", [3])])[:-2])
    with pytest.raises(SceneError) as info:
        load_x(path)
    assert "ends inside a token" in info.value.message and "(offset 28)" in info.value.message


def test_by_name_and_scenes_take_x_files(tmp_path):
    assert by_name(str(CUBE)).triangle_count == 12
    from effects.host.scene import load_scene
    (tmp_path / "s.yaml").write_text(f"mesh: {CUBE}\n")
    assert load_scene(str(tmp_path / "s.yaml")).mesh == str(CUBE)


VERTEX_COLOURS = """
technique T { pass P { Lighting = false; ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse;
                        AlphaOp[0] = SelectArg1; AlphaArg1[0] = Diffuse; } }
"""
# from (2, 1.5, -2.5) the camera sees the cube's -z face (bright blue), +x face (bright green)
# and +y face (dark red), as the file's comments name them
CUBE_SCENE = {"camera": {"eye": [2.0, 1.5, -2.5]}, "size": [96, 96]}


def test_the_sdk_cube_draws_its_face_colours_on_both_back_ends_alike(tmp_path):
    fx = tmp_path / "colours.fx"
    fx.write_text(VERTEX_COLOURS)
    scene = {**CUBE_SCENE, "mesh": str(CUBE)}
    pictures = {b: effects.render(str(fx), "geforce2", scene=scene, backend=b)
                for b in ("numpy", "gl")}
    assert np.array_equal(pictures["numpy"], pictures["gl"])
    colours = {tuple(c[:3]) for c in pictures["numpy"].reshape(-1, 4) if c[3]}
    assert colours == {(32, 32, 255), (32, 255, 32), (25, 6, 6)}


def test_effectedit_xfile_names_the_mesh_and_a_missing_one_is_said(tmp_path):
    import shutil
    shutil.copy(CUBE, tmp_path / "Cube.x")
    fx = tmp_path / "edit.fx"
    fx.write_text('string XFile = "Cube.x";\n' + VERTEX_COLOURS)
    from effects.host.runtime import render_frame
    frame = render_frame(str(fx), "geforce2", scene=CUBE_SCENE)
    assert not frame.warnings
    assert {tuple(c[:3]) for c in frame.image.reshape(-1, 4) if c[3]} == \
        {(32, 32, 255), (32, 255, 32), (25, 6, 6)}
    # a scene that names its mesh wins over XFile
    sphere = render_frame(str(fx), "geforce2", scene={**CUBE_SCENE, "mesh": "sphere"})
    assert (sphere.image[..., 3] > 0).sum() != (frame.image[..., 3] > 0).sum()
    # a missing file: the sphere, with a located warning (an error when strict)
    fx.write_text('string XFile = "Tiger.x";\n' + VERTEX_COLOURS)
    missing = render_frame(str(fx), "geforce2", scene=CUBE_SCENE)
    assert [(w.location.line, w.location.column) for w in missing.warnings] == [(1, 8)]
    assert "mesh file not found" in missing.warnings[0].message
    assert "drawn on the scene's sphere instead" in missing.warnings[0].message
    with pytest.raises(SceneError):
        render_frame(str(fx), "geforce2", scene=CUBE_SCENE, strict=True)
    # under an include root, XFile stays inside it
    fx.write_text('string XFile = "../outside.x";\n' + VERTEX_COLOURS)
    effect = effects.load_effect(str(fx), include_root=str(tmp_path))
    confined = render_frame(effect, "geforce2", scene=CUBE_SCENE)
    assert "escapes the include root" in confined.warnings[0].message


def test_an_effect_with_shaders_on_an_sdk_mesh_agrees_across_back_ends():
    """phong.fx's ps_2_0 technique on the SDK quad, lit from its side (tangent frames from its UVs):
    the two back ends agree as they do on the built-in meshes."""
    scene = {**CUBE_SCENE, "mesh": str(QUAD), "camera": {"eye": [-2.0, 0.5, 0.3]},
             "light": {"position": [-2.0, 1.5, 0.8]}}
    pictures = {b: effects.render(str(ROOT / "fxfiles" / "phong.fx"), "radeon9700", scene=scene,
                                  backend=b, technique="PerPixelPhong_ps20")
                for b in ("numpy", "gl")}
    a, b = (pictures[k][..., :3].astype(int) for k in ("numpy", "gl"))
    covered = pictures["numpy"][..., 3] > 0
    assert covered.mean() > 0.2 and (covered == (pictures["gl"][..., 3] > 0)).mean() > 0.99
    d = np.abs(a - b).max(axis=-1)
    assert d.mean() < 1.0 and (d > 2).mean() < 0.01
    assert a[covered].std() > 10          # the stones texture, lit: not a flat colour


def test_the_kept_sample_files_are_the_ones_the_manifest_names():
    import hashlib
    import re
    manifest = (XMESHES / "MANIFEST.md").read_text()
    rows = re.findall(r"^\| `([^`]+\.x)` \|.*\| `([0-9a-f]{64})` \|$", manifest, re.M)
    assert sorted(name for name, _ in rows) == sorted(p.name for p in XMESHES.glob("*.x"))
    for name, digest in rows:
        assert hashlib.sha256((XMESHES / name).read_bytes()).hexdigest() == digest, name
