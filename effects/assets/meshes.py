"""Meshes the effects draw, with the tangent frames per-pixel lighting needs.

A `Mesh` is an indexed triangle list. Conventions:
- Winding: for every triangle (a, b, c), cross(b - a, c - a) points out of the surface. With
  Direct3D's left-handed transforms (D3DX ...LH) such triangles appear clockwise on screen and
  survive the default CULLMODE = CCW; with right-handed ones they appear counter-clockwise.
- Texture coordinates follow Direct3D: (0, 0) is the top-left of the image, v grows downwards.
- Tangent frames (Boyd and Taylor, "Hardware shading with Direct3D"): per triangle the
  directions in which u and v grow, dP/du and dP/dv, from the edge vectors and the UV
  differences; summed per vertex, weighted by triangle area; then each frame is made
  orthonormal: tangent T = normalize(dP/du - N (N . dP/du)), binormal B = s * (N x T) with
  s = +1 or -1 so that B points the way v grows (s is -1 where the mapping is mirrored).
  Normal maps therefore store (-dh/du, -dh/dv, 1) in (T, B, N) (see `effects.assets.textures`).
- Seams: vertices duplicated at a texture seam (same position, same normal, UVs that differ by
  whole numbers, as at u = 0 and u = 1 of a sphere) pool their sums, so the frame is continuous
  across the seam, as the chapter warns ("tangents need to be averaged, and be careful about
  texture wrapping"). Vertices at a crease (different normals) or where the UV mapping really
  jumps keep their own frames.
"""
from __future__ import annotations

import dataclasses
import os
from dataclasses import dataclass

import numpy as np

from effects.base import limits, untrusted
from effects.base.errors import Location, SceneError
from effects.assets import obj_fast
from effects.assets.xfile import read_x
from effects.assets.tangents import tangent_frames


@dataclass
class Mesh:
    """An indexed triangle list with per-vertex attributes (all float32; indices uint32).

    `space` is 'object' for models, or 'clip' for `quad()`, whose positions are already clip
    coordinates (w = 1) and are drawn with identity transforms.
    """

    positions: np.ndarray                 # (N, 3)
    normals: np.ndarray                   # (N, 3) unit
    uv: np.ndarray                        # (N, 2)
    tangents: np.ndarray                  # (N, 3) unit, along dP/du
    binormals: np.ndarray                 # (N, 3) unit, along dP/dv (orthogonalised)
    indices: np.ndarray                   # (M, 3) uint32, a triangle list
    colors: np.ndarray | None = None      # (N, 4) RGBA or None (the D3D default diffuse)
    occlusion: np.ndarray | None = None   # (N,) ambient occlusion, made on first use
    primitive: str = "triangle_list"
    space: str = "object"
    name: str = ""

    @property
    def vertex_count(self) -> int:
        return len(self.positions)

    @property
    def triangle_count(self) -> int:
        return len(self.indices)


def make_mesh(positions, uv, indices, normals=None, *, name: str = "", space: str = "object",
              colors=None) -> Mesh:
    """A mesh from vertex arrays and a triangle list, with tangent frames computed (and smooth
    normals, when `normals` is None). Triangles must follow the winding convention above."""
    positions = np.asarray(positions, np.float32).reshape(-1, 3)
    n = len(positions)
    mesh = Mesh(positions=positions,
                normals=np.zeros((n, 3), np.float32) if normals is None else np.asarray(normals, np.float32),
                uv=np.asarray(uv, np.float32).reshape(-1, 2),
                tangents=np.zeros((n, 3), np.float32), binormals=np.zeros((n, 3), np.float32),
                indices=np.asarray(indices, np.uint32).reshape(-1, 3),
                colors=None if colors is None else np.asarray(colors, np.float32),
                space=space, name=name)
    return compute_tangent_frames(mesh, recompute_normals=normals is None)


# ---------------------------------------------------------------------------------------------
# Tangent frames


def compute_tangent_frames(mesh: Mesh, *, recompute_normals: bool = False) -> Mesh:
    """A copy of `mesh` with tangents and binormals computed (and normals, if asked or absent).

    Normals, when computed, are area-weighted face normals summed over every vertex at the same
    position (smooth shading; a model wanting creases supplies its own normals). Tangent frames
    are computed as the module docstring says (`effects.assets.tangents`).
    """
    given = None if recompute_normals or not np.any(mesh.normals) else mesh.normals
    normals, tangents, binormals = tangent_frames(mesh.positions, mesh.uv, mesh.indices, given)
    return dataclasses.replace(mesh, normals=normals, tangents=tangents, binormals=binormals)


# ---------------------------------------------------------------------------------------------
# Generators


def quad() -> Mesh:
    """A full-screen quad for screen-space passes, already in clip space (drawn untransformed).

    Positions (-1, 1, 0.5) top-left to (1, -1, 0.5) bottom-right, z = 0.5 (inside the default
    depth range, in front of the cleared depth 1.0); uv (0, 0) top-left to (1, 1)
    bottom-right, so texel rows run down the screen; normals face the viewer (0, 0, -1), with
    T = +x and B = -y (v grows downwards). Two triangles, clockwise on screen (front-facing
    under D3D's default cull mode).
    """
    positions = [[-1, 1, 0.5], [1, 1, 0.5], [-1, -1, 0.5], [1, -1, 0.5]]
    uv = [[0, 0], [1, 0], [0, 1], [1, 1]]
    normals = [[0, 0, -1]] * 4
    return make_mesh(positions, uv, [[0, 1, 2], [2, 1, 3]], normals, name="quad", space="clip")


def _drop_degenerate(tris: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """The triangles of non-zero area (patch and pole corners collapse to points)."""
    p = positions[tris]
    area = np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1)
    return tris[area > 1e-10 * float(area.max())]


def _orient(tris: np.ndarray, positions: np.ndarray, normals: np.ndarray) -> np.ndarray:
    """Drop zero-area triangles and wind the rest outwards (towards their vertex normals)."""
    tris = _drop_degenerate(tris, positions).copy()
    p = positions[tris]
    cross = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    inward = np.sum(cross * normals[tris].sum(axis=1), axis=1) < 0
    tris[inward] = tris[inward][:, [0, 2, 1]]
    return tris


def _grid_triangles(rows: int, cols: int, *, pole_top: bool = False) -> np.ndarray:
    """Two triangles per cell of a (rows+1) x (cols+1) vertex grid (row-major indices).

    With `pole_top` the first row of cells is split along the other diagonal, so each cell's
    non-degenerate triangle uses the pole vertex of its own column.
    """
    idx = np.arange((rows + 1) * (cols + 1)).reshape(rows + 1, cols + 1)
    a, b, c, d = idx[:-1, :-1], idx[:-1, 1:], idx[1:, :-1], idx[1:, 1:]
    split_bc = np.concatenate([np.stack([a, b, c], -1), np.stack([b, d, c], -1)], axis=1)
    if pole_top:
        split_ad = np.concatenate([np.stack([a, b, d], -1), np.stack([a, d, c], -1)], axis=1)
        split_bc[0] = split_ad[0]
    return split_bc.reshape(-1, 3)


def sphere(rings: int = 24, segments: int = 48, radius: float = 1.0) -> Mesh:
    """A UV sphere: v = 0 at the north pole (+y) to 1 at the south pole; u = 0..1 around.

    Position at (u, v): (sin(pi v) cos(2 pi u), cos(pi v), sin(pi v) sin(2 pi u)) * radius.
    The seam column u = 1 duplicates u = 0 (bit-identical positions and normals), and each
    pole has one vertex per segment at the segment's middle u, so no UV triangle is
    degenerate. Normals are exact.
    """
    v = np.arange(rings + 1) / rings
    u = np.arange(segments + 1) / segments
    theta = np.pi * v[:, None]
    phi = np.where(u == 1.0, 0.0, 2 * np.pi * u)[None, :]   # the seam repeats u = 0 exactly
    nrm = np.stack(np.broadcast_arrays(np.sin(theta) * np.cos(phi), np.cos(theta),
                                       np.sin(theta) * np.sin(phi)), axis=-1).copy()
    nrm[0], nrm[-1] = (0.0, 1.0, 0.0), (0.0, -1.0, 0.0)
    uu = np.broadcast_to(u[None, :], (rings + 1, segments + 1)).copy()
    uu[0, :-1] = uu[-1, :-1] = (np.arange(segments) + 0.5) / segments   # pole vertices
    vv = np.broadcast_to(v[:, None], (rings + 1, segments + 1))
    nrm, pos = nrm.reshape(-1, 3), nrm.reshape(-1, 3) * radius
    tris = _orient(_grid_triangles(rings, segments, pole_top=True), pos, nrm)
    return make_mesh(pos, np.stack([uu, vv], -1).reshape(-1, 2), tris, nrm, name="sphere")


def cube(size: float = 1.0) -> Mesh:
    """An axis-aligned cube from -size/2 to size/2: 24 vertices (4 per face, flat normals),
    each face mapped to the whole texture. Seen from outside, the side faces stand upright
    (v grows towards -y); +Y has v growing towards +z and -Y towards -z."""
    h = size / 2
    # face: (normal, direction of +u, direction of +v)
    faces = [((1, 0, 0), (0, 0, -1), (0, -1, 0)), ((-1, 0, 0), (0, 0, 1), (0, -1, 0)),
             ((0, 1, 0), (1, 0, 0), (0, 0, 1)), ((0, -1, 0), (1, 0, 0), (0, 0, -1)),
             ((0, 0, 1), (-1, 0, 0), (0, -1, 0)), ((0, 0, -1), (1, 0, 0), (0, -1, 0))]
    positions, normals, uv = [], [], []
    for n, r, d in faces:
        n, r, d = (np.array(x, float) for x in (n, r, d))
        for cu, cv in ((0, 0), (1, 0), (0, 1), (1, 1)):
            positions.append(h * (n + (2 * cu - 1) * r + (2 * cv - 1) * d))
            normals.append(n)
            uv.append((cu, cv))
    pos, nrm = np.array(positions), np.array(normals)
    quads = np.arange(24).reshape(6, 4)
    tris = np.concatenate([quads[:, [0, 1, 2]], quads[:, [2, 1, 3]]])
    return make_mesh(pos, uv, _orient(tris, pos, nrm), nrm, name="cube")


def torus(major: int = 48, minor: int = 24, radius: float = 0.7, tube: float = 0.3) -> Mesh:
    """A torus around the y axis: u = 0..1 around the ring, v = 0..1 around the tube (starting
    on the outer equator, going up). Both seams duplicate vertices exactly; normals exact."""
    u = np.arange(major + 1) / major
    v = np.arange(minor + 1) / minor
    phi = np.where(u == 1.0, 0.0, 2 * np.pi * u)[:, None]
    psi = np.where(v == 1.0, 0.0, 2 * np.pi * v)[None, :]
    ring = np.stack(np.broadcast_arrays(np.cos(phi), 0 * phi, np.sin(phi)), -1)
    nrm = np.cos(psi)[..., None] * ring + np.sin(psi)[..., None] * np.array([0.0, 1.0, 0.0])
    pos = (radius * ring + tube * nrm).reshape(-1, 3)
    nrm = nrm.reshape(-1, 3)
    uv = np.stack(np.meshgrid(u, v, indexing="ij"), -1).reshape(-1, 2)
    return make_mesh(pos, uv, _orient(_grid_triangles(major, minor), pos, nrm), nrm, name="torus")


# Newell's Utah teapot (1975), public-domain data: 306 control points (x y z, z up) and 32
# bicubic patches of 16 one-based point indices, rows of 4 (rim 0-3, body 4-11, handle 12-15,
# spout 16-19, lid 20-27, bottom 28-31). Transcribed from the classic published table.
_TEAPOT_POINTS = """
    1.4 0 2.4, 1.4 -0.784 2.4, 0.784 -1.4 2.4, 0 -1.4 2.4, 1.3375 0 2.53125,
    1.3375 -0.749 2.53125, 0.749 -1.3375 2.53125, 0 -1.3375 2.53125, 1.4375 0 2.53125, 1.4375 -0.805 2.53125,
    0.805 -1.4375 2.53125, 0 -1.4375 2.53125, 1.5 0 2.4, 1.5 -0.84 2.4, 0.84 -1.5 2.4,
    0 -1.5 2.4, -0.784 -1.4 2.4, -1.4 -0.784 2.4, -1.4 0 2.4, -0.749 -1.3375 2.53125,
    -1.3375 -0.749 2.53125, -1.3375 0 2.53125, -0.805 -1.4375 2.53125, -1.4375 -0.805 2.53125, -1.4375 0 2.53125,
    -0.84 -1.5 2.4, -1.5 -0.84 2.4, -1.5 0 2.4, -1.4 0.784 2.4, -0.784 1.4 2.4,
    0 1.4 2.4, -1.3375 0.749 2.53125, -0.749 1.3375 2.53125, 0 1.3375 2.53125, -1.4375 0.805 2.53125,
    -0.805 1.4375 2.53125, 0 1.4375 2.53125, -1.5 0.84 2.4, -0.84 1.5 2.4, 0 1.5 2.4,
    0.784 1.4 2.4, 1.4 0.784 2.4, 0.749 1.3375 2.53125, 1.3375 0.749 2.53125, 0.805 1.4375 2.53125,
    1.4375 0.805 2.53125, 0.84 1.5 2.4, 1.5 0.84 2.4, 1.75 0 1.875, 1.75 -0.98 1.875,
    0.98 -1.75 1.875, 0 -1.75 1.875, 2 0 1.35, 2 -1.12 1.35, 1.12 -2 1.35,
    0 -2 1.35, 2 0 0.9, 2 -1.12 0.9, 1.12 -2 0.9, 0 -2 0.9,
    -0.98 -1.75 1.875, -1.75 -0.98 1.875, -1.75 0 1.875, -1.12 -2 1.35, -2 -1.12 1.35,
    -2 0 1.35, -1.12 -2 0.9, -2 -1.12 0.9, -2 0 0.9, -1.75 0.98 1.875,
    -0.98 1.75 1.875, 0 1.75 1.875, -2 1.12 1.35, -1.12 2 1.35, 0 2 1.35,
    -2 1.12 0.9, -1.12 2 0.9, 0 2 0.9, 0.98 1.75 1.875, 1.75 0.98 1.875,
    1.12 2 1.35, 2 1.12 1.35, 1.12 2 0.9, 2 1.12 0.9, 2 0 0.45,
    2 -1.12 0.45, 1.12 -2 0.45, 0 -2 0.45, 1.5 0 0.225, 1.5 -0.84 0.225,
    0.84 -1.5 0.225, 0 -1.5 0.225, 1.5 0 0.15, 1.5 -0.84 0.15, 0.84 -1.5 0.15,
    0 -1.5 0.15, -1.12 -2 0.45, -2 -1.12 0.45, -2 0 0.45, -0.84 -1.5 0.225,
    -1.5 -0.84 0.225, -1.5 0 0.225, -0.84 -1.5 0.15, -1.5 -0.84 0.15, -1.5 0 0.15,
    -2 1.12 0.45, -1.12 2 0.45, 0 2 0.45, -1.5 0.84 0.225, -0.84 1.5 0.225,
    0 1.5 0.225, -1.5 0.84 0.15, -0.84 1.5 0.15, 0 1.5 0.15, 1.12 2 0.45,
    2 1.12 0.45, 0.84 1.5 0.225, 1.5 0.84 0.225, 0.84 1.5 0.15, 1.5 0.84 0.15,
    -1.6 0 2.025, -1.6 -0.3 2.025, -1.5 -0.3 2.25, -1.5 0 2.25, -2.3 0 2.025,
    -2.3 -0.3 2.025, -2.5 -0.3 2.25, -2.5 0 2.25, -2.7 0 2.025, -2.7 -0.3 2.025,
    -3 -0.3 2.25, -3 0 2.25, -2.7 0 1.8, -2.7 -0.3 1.8, -3 -0.3 1.8,
    -3 0 1.8, -1.5 0.3 2.25, -1.6 0.3 2.025, -2.5 0.3 2.25, -2.3 0.3 2.025,
    -3 0.3 2.25, -2.7 0.3 2.025, -3 0.3 1.8, -2.7 0.3 1.8, -2.7 0 1.575,
    -2.7 -0.3 1.575, -3 -0.3 1.35, -3 0 1.35, -2.5 0 1.125, -2.5 -0.3 1.125,
    -2.65 -0.3 0.9375, -2.65 0 0.9375, -2 -0.3 0.9, -1.9 -0.3 0.6, -1.9 0 0.6,
    -3 0.3 1.35, -2.7 0.3 1.575, -2.65 0.3 0.9375, -2.5 0.3 1.125, -1.9 0.3 0.6,
    -2 0.3 0.9, 1.7 0 1.425, 1.7 -0.66 1.425, 1.7 -0.66 0.6, 1.7 0 0.6,
    2.6 0 1.425, 2.6 -0.66 1.425, 3.1 -0.66 0.825, 3.1 0 0.825, 2.3 0 2.1,
    2.3 -0.25 2.1, 2.4 -0.25 2.025, 2.4 0 2.025, 2.7 0 2.4, 2.7 -0.25 2.4,
    3.3 -0.25 2.4, 3.3 0 2.4, 1.7 0.66 0.6, 1.7 0.66 1.425, 3.1 0.66 0.825,
    2.6 0.66 1.425, 2.4 0.25 2.025, 2.3 0.25 2.1, 3.3 0.25 2.4, 2.7 0.25 2.4,
    2.8 0 2.475, 2.8 -0.25 2.475, 3.525 -0.25 2.49375, 3.525 0 2.49375, 2.9 0 2.475,
    2.9 -0.15 2.475, 3.45 -0.15 2.5125, 3.45 0 2.5125, 2.8 0 2.4, 2.8 -0.15 2.4,
    3.2 -0.15 2.4, 3.2 0 2.4, 3.525 0.25 2.49375, 2.8 0.25 2.475, 3.45 0.15 2.5125,
    2.9 0.15 2.475, 3.2 0.15 2.4, 2.8 0.15 2.4, 0 0 3.15, 0 -0.002 3.15,
    0.002 0 3.15, 0.8 0 3.15, 0.8 -0.45 3.15, 0.45 -0.8 3.15, 0 -0.8 3.15,
    0 0 2.85, 0.2 0 2.7, 0.2 -0.112 2.7, 0.112 -0.2 2.7, 0 -0.2 2.7,
    -0.002 0 3.15, -0.45 -0.8 3.15, -0.8 -0.45 3.15, -0.8 0 3.15, -0.112 -0.2 2.7,
    -0.2 -0.112 2.7, -0.2 0 2.7, 0 0.002 3.15, -0.8 0.45 3.15, -0.45 0.8 3.15,
    0 0.8 3.15, -0.2 0.112 2.7, -0.112 0.2 2.7, 0 0.2 2.7, 0.45 0.8 3.15,
    0.8 0.45 3.15, 0.112 0.2 2.7, 0.2 0.112 2.7, 0.4 0 2.55, 0.4 -0.224 2.55,
    0.224 -0.4 2.55, 0 -0.4 2.55, 1.3 0 2.55, 1.3 -0.728 2.55, 0.728 -1.3 2.55,
    0 -1.3 2.55, 1.3 0 2.4, 1.3 -0.728 2.4, 0.728 -1.3 2.4, 0 -1.3 2.4,
    -0.224 -0.4 2.55, -0.4 -0.224 2.55, -0.4 0 2.55, -0.728 -1.3 2.55, -1.3 -0.728 2.55,
    -1.3 0 2.55, -0.728 -1.3 2.4, -1.3 -0.728 2.4, -1.3 0 2.4, -0.4 0.224 2.55,
    -0.224 0.4 2.55, 0 0.4 2.55, -1.3 0.728 2.55, -0.728 1.3 2.55, 0 1.3 2.55,
    -1.3 0.728 2.4, -0.728 1.3 2.4, 0 1.3 2.4, 0.224 0.4 2.55, 0.4 0.224 2.55,
    0.728 1.3 2.55, 1.3 0.728 2.55, 0.728 1.3 2.4, 1.3 0.728 2.4, 0 0 0,
    1.5 0 0.15, 1.5 0.84 0.15, 0.84 1.5 0.15, 0 1.5 0.15, 1.5 0 0.075,
    1.5 0.84 0.075, 0.84 1.5 0.075, 0 1.5 0.075, 1.425 0 0, 1.425 0.798 0,
    0.798 1.425 0, 0 1.425 0, -0.84 1.5 0.15, -1.5 0.84 0.15, -1.5 0 0.15,
    -0.84 1.5 0.075, -1.5 0.84 0.075, -1.5 0 0.075, -0.798 1.425 0, -1.425 0.798 0,
    -1.425 0 0, -1.5 -0.84 0.15, -0.84 -1.5 0.15, 0 -1.5 0.15, -1.5 -0.84 0.075,
    -0.84 -1.5 0.075, 0 -1.5 0.075, -1.425 -0.798 0, -0.798 -1.425 0, 0 -1.425 0,
    0.84 -1.5 0.15, 1.5 -0.84 0.15, 0.84 -1.5 0.075, 1.5 -0.84 0.075, 0.798 -1.425 0,
    1.425 -0.798 0
"""
_TEAPOT_PATCHES = """
    1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16
    4 17 18 19 8 20 21 22 12 23 24 25 16 26 27 28
    19 29 30 31 22 32 33 34 25 35 36 37 28 38 39 40
    31 41 42 1 34 43 44 5 37 45 46 9 40 47 48 13
    13 14 15 16 49 50 51 52 53 54 55 56 57 58 59 60
    16 26 27 28 52 61 62 63 56 64 65 66 60 67 68 69
    28 38 39 40 63 70 71 72 66 73 74 75 69 76 77 78
    40 47 48 13 72 79 80 49 75 81 82 53 78 83 84 57
    57 58 59 60 85 86 87 88 89 90 91 92 93 94 95 96
    60 67 68 69 88 97 98 99 92 100 101 102 96 103 104 105
    69 76 77 78 99 106 107 108 102 109 110 111 105 112 113 114
    78 83 84 57 108 115 116 85 111 117 118 89 114 119 120 93
    121 122 123 124 125 126 127 128 129 130 131 132 133 134 135 136
    124 137 138 121 128 139 140 125 132 141 142 129 136 143 144 133
    133 134 135 136 145 146 147 148 149 150 151 152 69 153 154 155
    136 143 144 133 148 156 157 145 152 158 159 149 155 160 161 69
    162 163 164 165 166 167 168 169 170 171 172 173 174 175 176 177
    165 178 179 162 169 180 181 166 173 182 183 170 177 184 185 174
    174 175 176 177 186 187 188 189 190 191 192 193 194 195 196 197
    177 184 185 174 189 198 199 186 193 200 201 190 197 202 203 194
    204 204 204 204 207 208 209 210 211 211 211 211 212 213 214 215
    204 204 204 204 210 217 218 219 211 211 211 211 215 220 221 222
    204 204 204 204 219 224 225 226 211 211 211 211 222 227 228 229
    204 204 204 204 226 230 231 207 211 211 211 211 229 232 233 212
    212 213 214 215 234 235 236 237 238 239 240 241 242 243 244 245
    215 220 221 222 237 246 247 248 241 249 250 251 245 252 253 254
    222 227 228 229 248 255 256 257 251 258 259 260 254 261 262 263
    229 232 233 212 257 264 265 234 260 266 267 238 263 268 269 242
    270 270 270 270 279 280 281 282 275 276 277 278 271 272 273 274
    270 270 270 270 282 289 290 291 278 286 287 288 274 283 284 285
    270 270 270 270 291 298 299 300 288 295 296 297 285 292 293 294
    270 270 270 270 300 305 306 279 297 303 304 275 294 301 302 271
"""


def _teapot_data() -> tuple[np.ndarray, np.ndarray]:
    points = np.array([[float(c) for c in t.split()] for t in _TEAPOT_POINTS.split(",")])
    patches = np.array([[int(i) for i in line.split()] for line in _TEAPOT_PATCHES.strip().splitlines()])
    return points, patches - 1


# Per group of four patches: the first patch, how their UVs are laid out ('ring': a quarter
# turn each along u; 'grid': 2 x 2), and the v range of the group.
_TEAPOT_LAYOUT = [(0, "ring", 0.0, 1 / 3), (4, "ring", 1 / 3, 1 / 3), (8, "ring", 2 / 3, 1 / 3),
                  (12, "grid", 0.0, 1.0), (16, "grid", 0.0, 1.0),
                  (20, "ring", 0.0, 0.5), (24, "ring", 0.5, 0.5), (28, "ring", 0.0, 1.0)]


def teapot(divisions: int = 8) -> Mesh:
    """The Utah teapot (Newell's 32 bicubic Bezier patches), tessellated `divisions` x
    `divisions` per patch; y up, spout towards +x, scaled by 0.3 and centred on its height.

    UVs: the four patches around the rim, body, lid and bottom continue each other in u (a
    quarter turn each), so each ring has one seam; v follows the profile. Handle and spout lay
    their four patches out 2 x 2. Normals are smooth (averaged by position), so patch borders
    do not show; degenerate triangles at the lid knob and the bottom centre are dropped.
    (Like the original, the teapot is not closed: there is a gap between lid and rim.)
    """
    points, patches = _teapot_data()
    n = divisions
    s = np.linspace(0.0, 1.0, n + 1)
    bern = np.stack([(1 - s) ** 3, 3 * s * (1 - s) ** 2, 3 * s * s * (1 - s), s ** 3], axis=1)
    grids, uvs = [], []
    for first, arrangement, v0, vspan in _TEAPOT_LAYOUT:
        for k in range(4):
            ctrl = points[patches[first + k]].reshape(4, 4, 3)          # [row][column]
            grids.append(np.einsum("ai,bj,ijc->abc", bern, bern, ctrl).reshape(-1, 3))
            if arrangement == "ring":
                uu, vv = (k + s[None, :]) / 4, v0 + vspan * s[:, None]
            else:
                uu, vv = (k % 2 + s[None, :]) / 2, (k // 2 + s[:, None]) / 2
            uvs.append(np.stack(np.broadcast_arrays(uu, vv), -1).reshape(-1, 2))
    per_patch = _grid_triangles(n, n)
    tris = np.concatenate([per_patch + i * (n + 1) ** 2 for i in range(len(grids))])
    p = np.concatenate(grids)
    # Newell's data is z-up; rotate to y-up, (x, y, z) -> (x, z, -y), centre and scale.
    p = np.stack([p[:, 0], p[:, 2] - 1.575, -p[:, 1]], axis=1) * 0.3
    # In Newell's data every patch's (column, row) parametrisation faces outwards, so the grid
    # winding needs no per-patch flip (tests/assets/test_meshes.py checks that each patch faces out).
    tris = _drop_degenerate(tris, p)
    return make_mesh(p, np.concatenate(uvs), tris, None, name="teapot")


# ---------------------------------------------------------------------------------------------
# Wavefront .obj


def _obj_error(path: str, line_no: int, column: int, message: str, line: str) -> SceneError:
    return SceneError(message, Location(path, line_no, column), source_line=line)


def load_obj(path: str | os.PathLike[str]) -> Mesh:
    """Read a Wavefront .obj: `v`, `vt`, `vn` and `f` (triangles, quads and convex polygons,
    fanned; `v`, `v/vt`, `v//vn`, `v/vt/vn`; negative indices count back from the end).
    Other statements (o, g, s, usemtl, mtllib ...) are ignored.

    .obj texture coordinates have v = 0 at the bottom of the image; they are flipped
    (v -> 1 - v) to Direct3D's top-left origin. Missing normals are computed smooth; missing
    texture coordinates are (0, 0) (tangents then fall back to any unit vector perpendicular to
    the normal). Errors are `SceneError`s at the offending line and column.

    Limits (checked before what they bound is allocated): `mesh_vertices` for the `v` lines
    and for the mesh's vertices (one per distinct v/vt/vn corner), `mesh_indices` for the
    indices the faces make (3 per triangle: a face of k corners fans into k - 2 triangles).
    """
    path = os.fspath(path)
    raw = untrusted.read_file(path, ".obj file", SceneError, "mesh_file_bytes")
    where = Location(path, 1, 1)

    # the common, regular shape, read whole with numpy; it checks the counts as soon as it
    # has told the lines apart (from the same line starts as check_obj_counts); all its faces
    # are triangles, so 3 indices a face line is the count
    fast = obj_fast.parse(raw, lambda vertices, faces: _check_counts(vertices, 3 * faces, where))
    if fast is not None:
        positions, uv, tris, normals = fast
        _check_mesh_vertices(len(positions), where)
        return make_mesh(positions, uv, tris, normals, name=os.path.basename(path))
    check_obj_counts(raw, where)
    return _read_obj_lines(path, raw)


def _read_obj_lines(path: str, raw: bytes) -> Mesh:
    """The per-line reader: any .obj, every error located. The counts are checked again as
    the lines are read, exactly, before anything they bound is kept."""
    lines = raw.decode("utf-8", errors="replace").splitlines()
    most_indices, most_vertices = limits.get("mesh_indices"), limits.get("mesh_vertices")
    v, vt, vn = [], [], []
    corners: dict[tuple[int, int, int], int] = {}
    known: dict[str, int] = {}      # a corner's text -> its number, while v/vt/vn stay as they are
    out_p, out_t, out_n = [], [], []
    tris: list[int] = []            # flat: three corner numbers a triangle
    any_vt = any_vn = False

    def number_list(parts, count, line_no, line, what):
        if len(parts) - 1 < count:
            raise _obj_error(path, line_no, len(line) + 1, f"'{parts[0]}' needs {count} numbers", line)
        values = []
        for k, token in enumerate(parts[1:count + 1], start=1):
            try:
                values.append(float(token))
            except ValueError:
                raise _obj_error(path, line_no, _column(line, parts, k),
                                 f"bad {what} number {token!r}", line) from None
        return values

    def resolve(token, size, line_no, line, parts, k, what):
        try:
            i = int(token)
        except ValueError:
            raise _obj_error(path, line_no, _column(line, parts, k), f"bad {what} index {token!r}",
                             line) from None
        index = i - 1 if i > 0 else size + i
        if i == 0 or not 0 <= index < size:
            raise _obj_error(path, line_no, _column(line, parts, k),
                             f"{what} index {i} is out of range (1..{size} defined so far)", line)
        return index

    def corner(parts, k, line_no, line):
        """The mesh vertex of corner `parts[k]` of a face, made when it is new (a column is
        worked out only for an error: a face line may have a million corners)."""
        nonlocal any_vt, any_vn
        token = parts[k]
        fields = token.split("/")
        if len(fields) > 3 or fields[0] == "":
            raise _obj_error(path, line_no, _column(line, parts, k), f"bad face vertex {token!r}", line)
        vi = resolve(fields[0], len(v), line_no, line, parts, k, "vertex")
        ti = resolve(fields[1], len(vt), line_no, line, parts, k, "texture coordinate") \
            if len(fields) > 1 and fields[1] else -1
        ni = resolve(fields[2], len(vn), line_no, line, parts, k, "normal") \
            if len(fields) > 2 and fields[2] else -1
        any_vt |= ti >= 0
        any_vn |= ni >= 0
        key = (vi, ti, ni)
        number = corners.get(key)
        if number is None:
            if len(out_p) >= most_vertices:
                raise _obj_error(path, line_no, _column(line, parts, k), limits.message(
                    "mesh_vertices", len(out_p) + 1,
                    "the .obj file's mesh (a vertex for each distinct v/vt/vn corner)"), line)
            number = corners[key] = len(out_p)
            out_p.append(v[vi])
            out_t.append(vt[ti] if ti >= 0 else [0.0, 0.0])
            out_n.append(vn[ni] if ni >= 0 else [0.0, 0.0, 0.0])
        return number

    for line_no, line in enumerate(lines, start=1):
        parts = line.split("#", 1)[0].split()
        if not parts:
            continue
        op = parts[0]
        if op in ("v", "vt", "vn") and known:
            known.clear()           # a negative index now names another element
        if op == "v":
            v.append(number_list(parts, 3, line_no, line, "vertex")[:3])
        elif op == "vt":
            t = number_list(parts, 1, line_no, line, "texture coordinate")
            vt.append([t[0], float(parts[2]) if len(parts) > 2 and _is_float(parts[2]) else 0.0])
        elif op == "vn":
            vn.append(number_list(parts, 3, line_no, line, "normal"))
        elif op == "f":
            if len(parts) < 4:
                raise _obj_error(path, line_no, 1, "a face needs at least 3 vertices", line)
            if len(tris) + 3 * (len(parts) - 3) > most_indices:
                raise _obj_error(path, line_no, 1, limits.message(
                    "mesh_indices", len(tris) + 3 * (len(parts) - 3), _FACES), line)
            face = []
            for k in range(1, len(parts)):
                number = known.get(parts[k])
                if number is None:
                    number = known[parts[k]] = corner(parts, k, line_no, line)
                face.append(number)
            first = face[0]
            for i in range(1, len(face) - 1):
                tris += (first, face[i], face[i + 1])
    if not tris:
        raise SceneError(".obj file has no faces", Location(path, max(1, len(lines)), 1))
    uv = np.asarray(out_t, np.float64)
    uv[:, 1] = 1.0 - uv[:, 1]
    normals = np.asarray(out_n) if any_vn and all(np.any(n) for n in out_n) else None
    return make_mesh(out_p, uv, np.asarray(tris, np.uint32), normals, name=os.path.basename(path))


def _column(line: str, parts: list[str], k: int) -> int:
    """The 1-based column of `parts[k]`, the k-th whitespace-separated token of `line`."""
    col = 0
    for token in parts[:k + 1]:
        col = line.index(token, col) + len(token)
    return col - len(parts[k]) + 1


def check_obj_counts(raw: bytes, where: Location) -> None:
    """The limits, from a count of the `v`, `vt` and `vn` lines (each list against
    `mesh_vertices`) and of the indices the `f` lines make (`mesh_indices`, located at the face
    line that passes it), made with numpy over the bytes before any line is parsed: a
    10M-vertex file, or one face of a million corners, is refused, not half read."""
    counts = obj_fast.count(raw)
    for amount, what in ((counts.vertices, "vertex list"), (counts.coords, "texture-coordinate list"),
                         (counts.normals, "normal list")):
        limits.check("mesh_vertices", amount, where, f"the .obj file's {what}", SceneError)
    total = int(counts.indices[-1]) if len(counts.indices) else 0
    limits.measure("mesh_indices", total)   # the meter (limits.py) sees an allowed count too
    if total > limits.get("mesh_indices"):
        line = int(counts.face_lines[np.searchsorted(counts.indices, limits.get("mesh_indices"),
                                                     side="right")])
        limits.check("mesh_indices", total, Location(where.path, line, 1), _FACES, SceneError)


_FACES = "the .obj file's face list (3 indices a triangle; a face of k corners makes k - 2 triangles)"


def _check_counts(vertices: int, indices: int, where: Location) -> None:
    limits.check("mesh_vertices", vertices, where, "the .obj file's vertex list", SceneError)
    limits.check("mesh_indices", indices, where, _FACES, SceneError)


def _check_mesh_vertices(count: int, where: Location) -> None:
    limits.check("mesh_vertices", count, where,
                 "the .obj file's mesh (a vertex for each distinct v/vt/vn corner)", SceneError)


def _is_float(token: str) -> bool:
    try:
        float(token)
        return True
    except ValueError:
        return False


# ---------------------------------------------------------------------------------------------
# By name

MESHES = {"quad": quad, "sphere": sphere, "cube": cube, "torus": torus, "teapot": teapot}
MESH_FILES = (".obj", ".x")     # the mesh files read: Wavefront .obj, DirectX .x (effects.assets.xfile)


def load_x(path: str | os.PathLike[str]) -> Mesh:
    """A DirectX .x file (text or binary; `effects.assets.xfile`) as one Mesh."""
    x = read_x(path)
    return make_mesh(x.positions, x.uv, x.triangles, x.normals, name=x.name, colors=x.colors)


def load_mesh_file(path: str) -> Mesh:
    """An .obj or .x file by its extension."""
    return load_x(path) if path.lower().endswith(".x") else load_obj(path)


def by_name(name: str, *, base_dir: str | None = None, location: Location | None = None) -> Mesh:
    """A built-in mesh ('quad', 'sphere', 'cube', 'torus', 'teapot') or an .obj or .x path
    (relative to `base_dir`). An unknown name is a `SceneError` at `location`."""
    if name in MESHES:
        return MESHES[name]()
    if name.lower().endswith(MESH_FILES):
        path = name if base_dir is None or os.path.isabs(name) else os.path.join(base_dir, name)
        if not os.path.isfile(path):
            raise SceneError(f"mesh file not found: {path}", location or Location(path, 1, 1))
        return load_mesh_file(path)
    raise SceneError(f"unknown mesh {name!r} (known: {', '.join(MESHES)}, or a .obj or .x file)",
                     location or Location("<scene>", 1, 1))
