"""Textures the effects sample: mip chains, quantisation, procedural
generators (so no large image is committed); files load through `effects.assets.texture_files`.

Conventions (all of this module and `effects.assets.dds`; what a `Texture` holds is said in
`effects.program.texture`):
- Cube faces follow Direct3D (the same layout as OpenGL's): a direction (x, y, z) picks the
  face of its largest component and
      +X: u = (-z/|x| + 1)/2, v = (-y/|x| + 1)/2      -X: u = ( z/|x| + 1)/2, v = (-y/|x| + 1)/2
      +Y: u = ( x/|y| + 1)/2, v = ( z/|y| + 1)/2      -Y: u = ( x/|y| + 1)/2, v = (-z/|y| + 1)/2
      +Z: u = ( x/|z| + 1)/2, v = (-y/|z| + 1)/2      -Z: u = (-x/|z| + 1)/2, v = (-y/|z| + 1)/2
  `cube_face_uv` and `cube_directions` are that mapping and its inverse.
- Normal maps store 0.5 + 0.5 * n with n in tangent space (T = dP/du, B = dP/dv, N): the
  frame `effects.assets.meshes` computes. A height field h(u, v) raises the surface along N, so its
  normal is proportional to (-dh/du, -dh/dv, 1) whatever the handedness of (T, B, N).
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Callable

import numpy as np

from effects.base import caches, limits
from effects.base.untrusted import confine
from effects.program.formats import pixel_format
from effects.program.texture import Texture
from effects.program.texels import quantize
from effects.assets.images import read_image
from effects.base.lru import DEFAULT_TEXTURE_BYTES, texture_bytes
from effects.base.errors import Location, SceneError

# ---------------------------------------------------------------------------------------------
# Quantisation and mip chains


def encode(values: np.ndarray, format: str) -> np.ndarray:
    """`values` (..., 4) as `format` stores them: the decoded values a card would sample.

    Channels the format lacks read as the format's defaults (see `effects.program.formats`).
    """
    return quantize(values, pixel_format(format))


def _area_weights(n: int, m: int) -> np.ndarray:
    """(m, n) matrix: destination texel i averages the source interval [i*n/m, (i+1)*n/m)."""
    edges = np.arange(m + 1) * (n / m)
    lo, hi = edges[:-1, None], edges[1:, None]
    src = np.arange(n)[None, :]
    overlap = np.clip(np.minimum(hi, src + 1) - np.maximum(lo, src), 0.0, None)
    return overlap / overlap.sum(axis=1, keepdims=True)


def _downsample(img: np.ndarray, axes: tuple[int, ...]) -> np.ndarray:
    for axis in axes:
        n = img.shape[axis]
        m = max(1, n // 2)
        if m == n:
            continue
        if n % 2 == 0:
            # even: each texel is the mean of two, the same sums as the weight matrix below
            # (0.5 a + 0.5 b, exact scaling), in O(n) rather than an (n/2 x n) product
            pairs = img.reshape(img.shape[:axis] + (m, 2) + img.shape[axis + 1:])
            first = (slice(None),) * (axis + 1)
            img = 0.5 * pairs[first + (0,)] + 0.5 * pairs[first + (1,)]
            continue
        img = np.moveaxis(np.tensordot(_area_weights(n, m), np.moveaxis(img, axis, 0), axes=1), 0, axis)
    return img


def _soft_blur(img: np.ndarray, axes: tuple[int, ...], wrap: bool) -> np.ndarray:
    """Separable [1, 2, 1] / 4 blur; wraps for tiling textures, clamps at cube face edges."""
    for axis in axes:
        if img.shape[axis] < 2:
            continue
        if wrap:
            before, after = np.roll(img, 1, axis), np.roll(img, -1, axis)
        else:
            pad = np.concatenate([np.take(img, [0], axis), img, np.take(img, [-1], axis)], axis)
            n = img.shape[axis]
            before, after = np.take(pad, range(0, n), axis), np.take(pad, range(2, n + 2), axis)
        img = 0.25 * before + 0.5 * img + 0.25 * after
    return img


_SPATIAL_AXES = {"1d": (1,), "2d": (0, 1), "cube": (1, 2), "3d": (0, 1, 2)}


def mip_chain(level0: np.ndarray, *, blur: bool = False, kind: str = "2d") -> list[np.ndarray]:
    """All mip levels from `level0` down to 1 x 1 (x 1), each half the size (floor, at least 1).

    Each texel is the area average of the texels it covers: a 2 x 2 (x 2) box where sizes are
    even; for odd sizes the edge texels are shared with fractional weights. With `blur`, each
    level after the first also gets a soft [1, 2, 1] / 4 blur: Persson's advice for normal and
    gloss maps, whose lower levels alias under per-pixel lighting. Measured against a
    supersampled render it does not help (tests/looks/test_mip_blur.py: phong.fx's normal map
    blurred is further from the 8 x 8 average, RMS 11.2 against 10.1 levels at 64 x 64), so
    the bundled generators leave it off.
    """
    level = np.asarray(level0, np.float32)
    axes = _SPATIAL_AXES[kind]
    levels = [level]
    while any(level.shape[a] > 1 for a in axes):
        level = _downsample(levels[-1].astype(np.float64), axes)
        if blur:
            level = _soft_blur(level, axes, wrap=kind != "cube")
        level = level.astype(np.float32)
        levels.append(level)
    return levels


def make_texture(values: np.ndarray, format: str = "A8R8G8B8", *, kind: str = "2d",
                 mips: bool = True, blur: bool = False, name: str = "") -> Texture:
    """A `Texture` of `format` from level-0 float RGBA values, with a full (quantised) mip chain."""
    values = np.asarray(values, np.float32)
    chain = mip_chain(values, blur=blur, kind=kind) if mips else [values]
    return Texture(kind, format, [encode(level, format) for level in chain], name)


# ---------------------------------------------------------------------------------------------
# D3DXFill*-style evaluation


def texel_centres(width: int, height: int) -> tuple[np.ndarray, np.ndarray]:
    """(u, v) of every texel centre, each (H, W): u = (j + 0.5) / W, v = (i + 0.5) / H."""
    u = (np.arange(width) + 0.5) / width
    v = (np.arange(height) + 0.5) / height
    return np.broadcast_to(u[None, :], (height, width)), np.broadcast_to(v[:, None], (height, width))


def fill_texture(fn: Callable[[np.ndarray, np.ndarray, tuple[float, float]], np.ndarray],
                 width: int, height: int, *, levels: int = 1) -> list[np.ndarray]:
    """Evaluate `fn(u, v, texel_size)` at every texel centre of each level, as D3DXFillTexture does.

    `fn` is vectorised: u and v are (H, W) arrays; it returns (H, W, 4) RGBA. D3DXFillTexture
    evaluates the function afresh for each mip level rather than filtering level 0.
    """
    out = []
    for level in range(levels):
        w, h = max(1, width >> level), max(1, height >> level)
        u, v = texel_centres(w, h)
        out.append(np.asarray(fn(u, v, (1.0 / w, 1.0 / h)), np.float32).reshape(h, w, 4))
    return out


def cube_directions(size: int) -> np.ndarray:
    """(6, N, N, 3) unnormalised directions through each cube texel centre (face order +X..-Z)."""
    u, v = texel_centres(size, size)
    s, t = 2 * u - 1, 2 * v - 1
    one = np.ones_like(s)
    faces = [(one, -t, -s), (-one, -t, s), (s, one, t), (s, -one, -t), (s, -t, one), (-s, -t, -one)]
    return np.stack([np.stack(f, axis=-1) for f in faces]).astype(np.float64)


def cube_face_uv(directions: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Face index (0..5 = +X..-Z) and (u, v) in [0, 1] for directions (..., 3), as D3D picks them.

    Ties between equal largest components go to X, then Y, as the reference rasterizer does.
    """
    d = np.asarray(directions, np.float64)
    x, y, z = d[..., 0], d[..., 1], d[..., 2]
    ax, ay, az = np.abs(x), np.abs(y), np.abs(z)
    major = np.where((ax >= ay) & (ax >= az), 0, np.where(ay >= az, 1, 2))
    face = np.where(major == 0, np.where(x >= 0, 0, 1),
                    np.where(major == 1, np.where(y >= 0, 2, 3), np.where(z >= 0, 4, 5)))
    ma = np.where(major == 0, ax, np.where(major == 1, ay, az))
    ma = np.where(ma == 0, 1.0, ma)
    sc = np.choose(face, [-z, z, x, x, x, -x])
    tc = np.choose(face, [-y, -y, z, -z, -y, -y])
    return face, (sc / ma + 1) / 2, (tc / ma + 1) / 2


def fill_cube_texture(fn: Callable[[np.ndarray], np.ndarray], size: int) -> np.ndarray:
    """(6, N, N, 4): `fn(directions)` at every cube texel centre, as D3DXFillCubeTexture passes
    the (unnormalised, components in [-1, 1]) direction through the texel centre."""
    d = cube_directions(size)
    return np.asarray(fn(d), np.float32).reshape(6, size, size, 4)


# ---------------------------------------------------------------------------------------------
# Noise (seeded, tileable)


def _lattice_noise(coords: np.ndarray, table: np.ndarray) -> np.ndarray:
    """Smooth value noise: multilinear, smoothstep-weighted interpolation of a periodic lattice.

    coords (..., D) are in lattice units; the lattice `table` (P,)*D wraps, so the noise tiles
    with period P.
    """
    dim = coords.shape[-1]
    period = table.shape[0]
    base = np.floor(coords).astype(np.int64)
    frac = coords - base
    weight = frac * frac * (3 - 2 * frac)
    out = np.zeros(coords.shape[:-1])
    for corner in range(2 ** dim):
        offs = [(corner >> k) & 1 for k in range(dim)]
        idx = tuple((base[..., k] + offs[k]) % period for k in range(dim))
        w = np.ones(coords.shape[:-1])
        for k in range(dim):
            w = w * (weight[..., k] if offs[k] else 1 - weight[..., k])
        out += w * table[idx]
    return out


def fbm(coords: np.ndarray, *, seed: int, cells: int = 4, octaves: int = 5, gain: float = 0.5) -> np.ndarray:
    """Fractal value noise in [0, 1] at coords (..., D) given in [0, 1) units; tiles with period 1."""
    rng = np.random.default_rng(seed)
    dim = coords.shape[-1]
    total = np.zeros(coords.shape[:-1])
    amplitude, norm = 1.0, 0.0
    for octave in range(octaves):
        period = cells * 2 ** octave
        table = rng.random((period,) * dim)
        total += amplitude * _lattice_noise(coords * period, table)
        norm += amplitude
        amplitude *= gain
    return total / norm


def _grid(size: int) -> np.ndarray:
    """(N, N, 2) texel-centre (u, v) coordinates in [0, 1)."""
    u, v = texel_centres(size, size)
    return np.stack([u, v], axis=-1)


def _normalise01(a: np.ndarray) -> np.ndarray:
    lo, hi = float(a.min()), float(a.max())
    return (a - lo) / (hi - lo) if hi > lo else np.zeros_like(a)


def _wrapped_delta(a: np.ndarray) -> np.ndarray:
    return (a + 0.5) % 1.0 - 0.5


# ---------------------------------------------------------------------------------------------
# Procedural images (level-0 float values)


def _rgba(rgb: np.ndarray, alpha: float | np.ndarray = 1.0) -> np.ndarray:
    rgb = np.asarray(rgb, np.float32)
    a = np.broadcast_to(np.asarray(alpha, np.float32), rgb.shape[:-1])[..., None]
    return np.concatenate([rgb, a], axis=-1)


def _lerp(a, b, t):
    t = np.asarray(t)[..., None]
    return np.asarray(a) * (1 - t) + np.asarray(b) * t


def earth_base(size: int = 128) -> np.ndarray:
    """An Earth-like colour map, (size, 2*size, 4), equirectangular: u = longitude, v = 0 at the
    north pole. Oceans, green-to-brown land, ice caps; continents from seeded 3D noise on the
    sphere, so there is no seam at u = 0/1 and no pinching at the poles."""
    u, v = texel_centres(2 * size, size)
    lon, lat = u * 2 * np.pi, (0.5 - v) * np.pi
    p = np.stack([np.cos(lat) * np.cos(lon), np.sin(lat), np.cos(lat) * np.sin(lon)], axis=-1)
    elevation = fbm((p + 1.0) / 2.0, seed=7, cells=4, octaves=6)
    sea = 0.53
    land = elevation > sea
    depth = np.clip((sea - elevation) / 0.15, 0, 1)
    ocean = _lerp([0.10, 0.32, 0.60], [0.02, 0.07, 0.30], depth)
    height = np.clip((elevation - sea) / 0.2, 0, 1)
    dry = np.clip(1 - np.abs(np.abs(np.degrees(lat)) - 25) / 15, 0, 1) * 0.6
    ground = _lerp(_lerp([0.16, 0.42, 0.12], [0.62, 0.52, 0.32], dry), [0.45, 0.38, 0.28], height)
    rgb = np.where(land[..., None], ground, ocean)
    ice = np.clip((np.abs(np.degrees(lat)) - 68 + 8 * (elevation - 0.5)) / 4, 0, 1)
    rgb = _lerp(rgb, [0.93, 0.95, 0.97], ice)
    return _rgba(rgb)


HEIGHT_KINDS = ("bumps", "stones", "craters", "noise")


def height_field(size: int = 128, kind: str = "bumps") -> np.ndarray:
    """A tileable (size, size) height field in [0, 1] (1 = high).

    'bumps': 4 x 4 round bumps, 0.5 + 0.5 sin(8 pi u) sin(8 pi v); 'stones': cobbles (cellular
    noise F2 - F1, flat tops with grooves between); 'craters': bowls with raised rims on a
    plain; 'noise': fractal value noise.
    """
    uv = _grid(size)
    if kind == "bumps":
        return (0.5 + 0.5 * np.sin(8 * np.pi * uv[..., 0]) * np.sin(8 * np.pi * uv[..., 1])).astype(np.float32)
    if kind == "noise":
        return fbm(uv, seed=3, cells=4, octaves=5).astype(np.float32)
    rng = np.random.default_rng({"stones": 11, "craters": 13}.get(kind, 0))
    if kind == "stones":
        cells = 6
        centres = (np.stack(np.meshgrid(np.arange(cells), np.arange(cells)), -1).reshape(-1, 2)
                   + 0.15 + 0.7 * rng.random((cells * cells, 2))) / cells
        delta = _wrapped_delta(uv[:, :, None, :] - centres[None, None])
        dist = np.sort(np.sqrt((delta ** 2).sum(-1)), axis=-1)
        groove = np.clip((dist[..., 1] - dist[..., 0]) * cells / 0.35, 0, 1)
        h = np.sqrt(groove) * 0.85 + 0.15 * fbm(uv, seed=5, cells=8, octaves=3)
        return _normalise01(h).astype(np.float32)
    if kind == "craters":
        h = np.full(uv.shape[:-1], 0.0)
        for _ in range(14):
            centre, radius = rng.random(2), 0.04 + 0.1 * rng.random()
            d = np.sqrt((_wrapped_delta(uv - centre) ** 2).sum(-1)) / radius
            bowl = np.where(d < 1, d * d - 1, 0.0)
            rim = 0.35 * np.exp(-((d - 1) / 0.18) ** 2)
            h += bowl + rim
        h += 0.1 * fbm(uv, seed=17, cells=8, octaves=3)
        return _normalise01(h).astype(np.float32)
    raise ValueError(f"unknown height field kind {kind!r} (known: {', '.join(HEIGHT_KINDS)})")


def sobel_gradients(height: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Persson's Sobel sums (dX, dY) of a (H, W) height field, wrapping at the edges.

    dX uses [-1 0 1; -2 0 2; -1 0 1] (right minus left), dY the transpose (row below minus row
    above, i.e. along +v). For a ramp h = a * column, dX = 8a.
    """
    h = np.asarray(height, np.float64)

    def at(dy: int, dx: int) -> np.ndarray:   # h[y + dy, x + dx] with wrap
        return np.roll(h, (-dy, -dx), axis=(0, 1))

    dx = (at(-1, 1) - at(-1, -1)) + 2 * (at(0, 1) - at(0, -1)) + (at(1, 1) - at(1, -1))
    dy = (at(1, -1) - at(-1, -1)) + 2 * (at(1, 0) - at(-1, 0)) + (at(1, 1) - at(-1, 1))
    return dx, dy


def sobel_normal_map(height: np.ndarray, scale: float = 1.0) -> np.ndarray:
    """Tangent-space normal map (H, W, 4) of a height field: rgb = 0.5 + 0.5 * n, alpha 1.

    n = normalize(-scale * dX, -scale * dY, 1) from the Sobel sums (`sobel_gradients`). Persson
    forms (dX, dY, 1); the minus signs make the normal lean away from rising height in the
    tangent frame T = dP/du, B = dP/dv that `effects.assets.meshes` computes (bumps look raised).
    """
    dx, dy = sobel_gradients(height)
    n = np.stack([-scale * dx, -scale * dy, np.ones_like(dx)], axis=-1)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    return _rgba(0.5 + 0.5 * n)


def bump_map_du_dv(height: np.ndarray, scale: float = 0.05) -> np.ndarray:
    """A V8U8 bump map (H, W, 4) = (du, dv, 1, 1) for BumpEnvMap (EMBM), already quantised.

    du = -scale * dh/du and dv = -scale * dh/dv, with the derivatives per whole texture (central
    differences times the size), so the offsets tilt like the normal does and do not depend on
    the resolution.
    """
    h = np.asarray(height, np.float64)
    rows, cols = h.shape
    dhdu = (np.roll(h, -1, axis=1) - np.roll(h, 1, axis=1)) * cols / 2
    dhdv = (np.roll(h, -1, axis=0) - np.roll(h, 1, axis=0)) * rows / 2
    values = np.stack([-scale * dhdu, -scale * dhdv, np.ones_like(h), np.ones_like(h)], axis=-1)
    return encode(np.clip(values, -1, 1), "V8U8")


def gloss_map(size: int = 128) -> np.ndarray:
    """A gloss map (size, size, 4), grey in rgb, alpha 1: shiny metal (0.9) with soft dull,
    rusty patches (0.15). Smooth transitions, as Persson advises, to keep speculars from aliasing."""
    n = fbm(_grid(size), seed=21, cells=4, octaves=4)
    t = np.clip((n - 0.42) / 0.2, 0, 1)
    g = 0.15 + 0.75 * t * t * (3 - 2 * t)
    return _rgba(np.repeat(g[..., None], 3, axis=-1))


SUN_DIRECTION = np.array([0.5, 0.6, 0.62]) / np.linalg.norm([0.5, 0.6, 0.62])


def environment_colour(directions: np.ndarray) -> np.ndarray:
    """The environment's RGBA for directions (..., 3): a blue sky with a sun, a checkered ground
    (y < 0) whose squares lie on the plane y = -1, so reflections visibly move."""
    d = np.asarray(directions, np.float64)
    d = d / np.linalg.norm(d, axis=-1, keepdims=True)
    up = d[..., 1]
    sky = _lerp([0.85, 0.90, 1.0], [0.20, 0.40, 0.85], np.sqrt(np.clip(up, 0, 1)))
    sun = np.clip(np.dot(d, SUN_DIRECTION), 0, 1) ** 200 * 3.0
    sky = np.clip(sky + sun[..., None] * np.array([1.0, 0.9, 0.7]), 0, 1)
    safe = np.where(up < -1e-3, -up, 1e-3)
    gx, gz = d[..., 0] / safe, d[..., 2] / safe
    checker = (np.floor(gx * 2) + np.floor(gz * 2)) % 2
    fade = np.clip(-up * 4, 0, 1)
    ground = _lerp([0.55, 0.5, 0.45], _lerp([0.45, 0.36, 0.25], [0.80, 0.78, 0.72], checker), fade)
    return _rgba(np.where((up >= 0)[..., None], sky, ground))


def environment_cube(size: int = 64) -> np.ndarray:
    """A cube environment map (6, size, size, 4) of `environment_colour`."""
    return fill_cube_texture(environment_colour, size)


def normalization_cube(size: int = 32) -> np.ndarray:
    """A normalisation cube map (6, size, size, 4): rgb = 0.5 + 0.5 * normalize(d), alpha 1,
    d the direction through the texel centre (D3D face orientation, module doc)."""
    def fn(d: np.ndarray) -> np.ndarray:
        return _rgba(0.5 + 0.5 * d / np.linalg.norm(d, axis=-1, keepdims=True))
    return fill_cube_texture(fn, size)


def power_table(size: int = 256, exponent: float = 16.0, *, levels: int = 1,
                rows: int | None = None) -> list[np.ndarray]:
    """The table-lookup specular texture of Boyd and Taylor's chapter, filled like their
    D3DXFillTexture callback: at texel centre (u, v), rgb = v ** exponent and alpha = u;
    `size` columns and `rows` rows (default `size`).

    In their ps.1.1 shader texm3x2pad/texm3x2tex form u = N.L (first row, t1) and v = N.H
    (second row, t2): columns (u) index N.L, rows (v, top = 0) index N.H. The last row's
    centre is 1 - 0.5 / rows, so N.H = 1 reads (1 - 0.5 / rows) ** exponent, about
    exp(-exponent / (2 rows)): 0.82 for 100 over the chapter's 256 rows, 0.91 for 400 over 2048.
    """
    def fn(u, v, _texel):
        p = np.power(v, exponent)
        return np.stack([p, p, p, u], axis=-1)
    return fill_texture(fn, size, rows or size, levels=levels)


def power_table_1d(size: int = 256, exponent: float = 16.0) -> np.ndarray:
    """A 1D power table (1, size, 4): rgb = u ** exponent at the texel centre u, alpha 1."""
    u, _ = texel_centres(size, 1)
    p = np.power(u, exponent)
    return _rgba(np.stack([p, p, p], axis=-1))


def power_range_table(size: int = 256, max_exponent: float = 128.0) -> np.ndarray:
    """A 2D table for a per-pixel exponent: columns u = N.H, rows v = exponent / max_exponent;
    rgb = u ** (v * max_exponent) at texel centres, alpha 1."""
    def fn(u, v, _texel):
        p = np.power(u, v * max_exponent)
        return np.stack([p, p, p, np.ones_like(p)], axis=-1)
    return fill_texture(fn, size, size)[0]


def noise_volume(size: int = 32, channels: int = 4) -> np.ndarray:
    """A tileable noise volume (size, size, size, 4): four independent fractal value noises in
    R, G, B, A, each in [0, 1]. Axis 0 is w (depth), then v, then u."""
    c = (np.arange(size) + 0.5) / size
    w, v, u = np.meshgrid(c, c, c, indexing="ij")
    coords = np.stack([u, v, w], axis=-1)
    # `channels` < 4: only the first ones (noise3d reads R alone), the same values
    return np.stack([fbm(coords, seed=31 + k, cells=4, octaves=3) for k in range(channels)],
                    axis=-1).astype(np.float32)


def checker(size: int = 64, squares: int = 8) -> np.ndarray:
    """A black and white checkerboard (size, size, 4), `squares` per side, top-left white."""
    u, v = texel_centres(size, size)
    c = 1.0 - (np.floor(u * squares) + np.floor(v * squares)) % 2
    return _rgba(np.repeat(c[..., None], 3, axis=-1))


# ---------------------------------------------------------------------------------------------
# The procedural registry: procedural("NAME[:ARG]", size=N, base_dir=DIR)
#
# ARG means what each entry says: a height-field kind or an image path ('height', 'sobel_normals',
# 'sobel_dudv', 'dudv'), an exponent ('power', 'power_table', 'power1d', 'power_range'), a
# number of squares ('checker'), or the edge length itself ('normalization_cube', 'sky_cube',
# 'noise3d', which is how the bundled effect files ask for them: fxfiles/README.md).


@dataclass(frozen=True)
class Procedural:
    """One named procedural texture: `make(arg, size, heights) -> Texture`, its default size and
    argument; `heights` is the height field the argument names (for the entries that take one).
    `arg_is_size`: the argument, when given, is the edge length."""

    make: Callable[[str, int, "np.ndarray | None"], Texture]
    size: int
    default_arg: str = ""
    doc: str = ""
    arg_is_size: bool = False
    takes_height: bool = False
    kind: str = "2d"     # with `aspect`, how many texels a size makes (checked before making)
    aspect: int = 1      # width / height
    # `make_rows(arg, width, rows)`: the entries whose height may differ from their width (a
    # `Height` annotation); the others are square (or `aspect`)
    make_rows: Callable[[str, int, int], Texture] | None = None

    def extent(self, size: int, rows: int | None = None) -> tuple[int, int, int]:
        """(width, height, layers) of the top level at edge length `size` (`rows` high)."""
        layers = {"cube": 6, "3d": size}.get(self.kind, 1)
        if rows is not None and self.make_rows is not None:
            return size, rows, layers
        return size * self.aspect, size, layers


def _freeze(texture: Texture) -> Texture:
    for level in texture.levels:
        level.setflags(write=False)
    return texture


def _normal_scale(size: int) -> float:
    # Keep the bump steepness of the built-in height fields independent of resolution
    # (Sobel sums shrink as 1/size); an image's heights are used as they are (scale 1).
    return size / 128.0


def _sobel_dudv(heights: np.ndarray, scale: float) -> np.ndarray:
    """(du, dv) = (n.x, n.y) of the Sobel normal, as V8U8 (fxfiles/README.md 'sobel_dudv')."""
    n = 2 * sobel_normal_map(heights, scale)[..., :2] - 1
    return np.concatenate([n, np.ones(n.shape[:-1] + (2,))], axis=-1)


def _with_openness(normals: np.ndarray, heights: np.ndarray, scale: float) -> np.ndarray:
    """The normal map with alpha = 1 - occlusion (`heightfield.horizon_occlusion`)."""
    from effects.assets.heightfield import horizon_occlusion
    out = normals.copy()
    out[..., 3] = 1.0 - horizon_occlusion(heights, scale=scale)
    return out


def _grey(h: np.ndarray) -> np.ndarray:
    return _rgba(np.repeat(np.asarray(h)[..., None], 3, -1))


PROCEDURAL: dict[str, Procedural] = {
    "earth": Procedural(lambda a, s, h: make_texture(earth_base(s), "X8R8G8B8"), 128,
                        doc="Earth-like colour map, size x 2*size, X8R8G8B8", aspect=2),
    "height": Procedural(lambda a, s, h: make_texture(_grey(h), "L8"), 128, "bumps",
                         "height field KIND (bumps|stones|craters|noise) or image, L8", takes_height=True),
    "height_alpha": Procedural(lambda a, s, h: make_texture(_rgba(np.zeros(h.shape + (3,)), h), "A8"),
                               128, "bumps", "height field in alpha, A8 (emboss)", takes_height=True),
    "sobel_normals": Procedural(
        lambda a, s, h: make_texture(sobel_normal_map(h, 1.0 if _is_path(a) else _normal_scale(s)),
                                     "X8R8G8B8"),
        128, "bumps", "tangent-space normal map of a height field, X8R8G8B8", takes_height=True),
    "sobel_normals_ao": Procedural(
        lambda a, s, h: make_texture(_with_openness(sobel_normal_map(h, 1.0 if _is_path(a) else _normal_scale(s)),
                                                    h, 1.0 if _is_path(a) else _normal_scale(s)),
                                     "A8R8G8B8"),
        128, "bumps", "sobel_normals with alpha = 1 - the height field's self-occlusion, A8R8G8B8",
        takes_height=True),
    "sobel_dudv": Procedural(
        lambda a, s, h: make_texture(_sobel_dudv(h, 1.0 if _is_path(a) else _normal_scale(s)), "V8U8"),
        128, "bumps", "EMBM (du, dv) = (n.x, n.y) of the Sobel normal, V8U8", takes_height=True),
    "dudv": Procedural(lambda a, s, h: Texture("2d", "V8U8", [encode(level, "V8U8") for level in
                                                            mip_chain(bump_map_du_dv(h))]),
                       128, "bumps", "EMBM (du, dv) = -0.05 * height gradient, V8U8", takes_height=True),
    "gloss": Procedural(lambda a, s, h: make_texture(gloss_map(s), "L8"), 128,
                        doc="gloss map, L8"),
    "environment": Procedural(lambda a, s, h: make_texture(environment_cube(s), "X8R8G8B8", kind="cube"), 64,
                              doc="sky and checkered ground cube map, X8R8G8B8", arg_is_size=True,
                              kind="cube"),
    "normalization_cube": Procedural(
        lambda a, s, h: Texture("cube", "X8R8G8B8", [encode(normalization_cube(s), "X8R8G8B8")]), 32,
        doc="normalisation cube map, X8R8G8B8, one level", arg_is_size=True, kind="cube"),
    "power": Procedural(lambda a, s, h: Texture("2d", "A8R8G8B8", [encode(power_table(s, float(a))[0], "A8R8G8B8")]),
                        256, "16", "Boyd-Taylor table: rgb = v^N (rows N.H), alpha = u (N.L); A8R8G8B8",
                        make_rows=lambda a, s, r: Texture("2d", "A8R8G8B8", [
                            encode(power_table(s, float(a), rows=r)[0], "A8R8G8B8")])),
    "power1d": Procedural(lambda a, s, h: Texture("1d", "L8", [encode(power_table_1d(s, float(a)), "L8")]),
                          256, "16", "1D table rgb = u^N, L8"),
    "power_range": Procedural(lambda a, s, h: Texture("2d", "L8", [encode(power_range_table(s, float(a)), "L8")]),
                              256, "128", "rgb = u^(v*MAX): columns N.H, rows exponent/MAX; L8"),
    "noise_volume": Procedural(lambda a, s, h: make_texture(noise_volume(s), "A8R8G8B8", kind="3d"), 32,
                               doc="tileable 4-channel noise volume, A8R8G8B8", arg_is_size=True,
                               kind="3d"),
    "noise3d": Procedural(lambda a, s, h: make_texture(_grey(noise_volume(s, channels=1)[..., 0]), "L8", kind="3d"), 32,
                          doc="tileable value-noise volume, L8", arg_is_size=True, kind="3d"),
    "checker": Procedural(lambda a, s, h: make_texture(checker(s, int(a)), "X8R8G8B8"), 64, "8",
                          "checkerboard with N squares a side, X8R8G8B8"),
    # a normal map's "no bump": (0.5, 0.5, 1) decodes (x 2 - 1) to the unperturbed normal
    "flat_normal": Procedural(lambda a, s, h: make_texture(
        np.broadcast_to(np.array([0.5, 0.5, 1.0, 1.0], np.float32), (s, s, 4)), "X8R8G8B8"), 4,
        doc="flat normal map, every texel (0.5, 0.5, 1), X8R8G8B8", arg_is_size=True),
}
# The names the bundled effect files use (fxfiles/README.md).
PROCEDURAL["power_table"] = PROCEDURAL["power"]
PROCEDURAL["sky_cube"] = PROCEDURAL["environment"]


def _is_path(arg: str) -> bool:
    return "/" in arg or "\\" in arg or "." in os.path.basename(arg)


def _height_from_image(path: str, where: Location) -> np.ndarray:
    if not os.path.isfile(path):
        raise SceneError(f"height image not found: {path}", where)
    return read_image(path, "L", where, "height image").astype(np.float32) / 255.0


# by bytes: a 64-entry bound thrashed on effects with many small textures
_PROCEDURAL = caches.declare(
    "assets.procedural", keys="generator, argument, edge length, image path and its "
    "modification time", max_bytes=DEFAULT_TEXTURE_BYTES, size_of=texture_bytes)


def _procedural_cached(base: str, arg: str, size: int, path: str, stamp: float,
                       rows: int | None = None) -> Texture:
    key = (base, arg, size, path, stamp, rows)
    hit = _PROCEDURAL.get(key)
    if hit is None:
        hit = _make_procedural(base, arg, size, path, rows)
        _PROCEDURAL.put(key, hit)
    return hit


def _make_procedural(base: str, arg: str, size: int, path: str, rows: int | None = None) -> Texture:
    entry = PROCEDURAL[base]
    if rows is not None and entry.make_rows is not None:
        texture = entry.make_rows(arg, size, rows)
        texture.name = f"{base}:{arg}"
        return _freeze(texture)
    heights = None
    if entry.takes_height:
        heights = _height_from_image(path, Location(path, 1, 1)) if path else height_field(size, arg)
    texture = entry.make(arg, size, heights)
    texture.name = f"{base}:{arg}" if arg else base
    return _freeze(texture)


def procedural(name: str, *, size: int | None = None, base_dir: str | None = None,
               location: Location | None = None, root: str | None = None,
               rows: int | None = None) -> Texture:
    """A procedural texture by name, 'NAME' or 'NAME:ARG' (see `PROCEDURAL` and the table above),
    e.g. 'sobel_normals:stones', 'sobel_normals:textures/h.png' (an image path, relative to
    `base_dir`), 'power_table:16', 'normalization_cube:32'. `size` overrides the default edge
    length (an edge-length argument wins over it); `rows` the height of the entries that may
    be taller or wider than square (`make_rows`: the power table). Results are cached (image arguments by file
    modification time) and read-only. With `root` (the effect's include root) an image argument
    must lie inside it (`effects.base.untrusted.confine`). Problems raise `SceneError` at `location`."""
    where = location or Location(f"procedural:{name}", 1, 1)
    base, _, arg = name.partition(":")
    entry = PROCEDURAL.get(base)
    if entry is None:
        raise SceneError(f"unknown procedural texture {base!r} (known: {', '.join(sorted(PROCEDURAL))})", where)
    arg = arg.strip() or entry.default_arg
    size = entry.size if size is None else size
    if entry.arg_is_size and arg:
        if not (arg.isascii() and arg.isdigit()):
            raise SceneError(f"bad argument {arg[:40]!r} for procedural texture {base!r}: "
                             "expected an edge length", where)
        limits.check_digits(arg, where, SceneError)
        size = int(arg)
    if int(size) < 1:
        raise SceneError(f"procedural texture size {size} must be at least 1", where)
    if rows is not None and int(rows) < 1:
        raise SceneError(f"procedural texture height {rows} must be at least 1", where)
    rows = int(rows) if rows is not None and entry.make_rows is not None else None
    width, height, layers = entry.extent(int(size), rows)
    limits.check_texture(width, height, layers, where, f"procedural texture {base!r}", SceneError)
    limits.check("procedural_texels", width * height * layers, where,
                 f"procedural texture {base!r} ({width} x {height} x {layers})", SceneError)
    path, stamp = "", 0.0
    if entry.takes_height and _is_path(arg):
        path = confine(arg, base_dir or os.getcwd(), root, "procedural image", SceneError, where)
        stamp = os.path.getmtime(path) if os.path.isfile(path) else -1.0
    try:
        return _procedural_cached(base, arg, int(size), path, stamp, rows)
    except SceneError as exc:
        raise SceneError(exc.message, where) from None
    except ValueError as exc:
        raise SceneError(f"bad argument {arg!r} for procedural texture {base!r}: {exc}", where) from None
