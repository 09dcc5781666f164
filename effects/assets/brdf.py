"""BRDF factor cube maps by the homomorphic factorisation of McCool, Ang and Ahmad
("Homomorphic Factorization of BRDFs for High-Performance Rendering", SIGGRAPH 2001), the
method the chapter's DX8 BRDF effect (fxfiles/brdf.fx) was written for.

The effect multiplies three cube-map lookups per pixel, in tangent space: the view factor at
the view vector, the light factor at the light vector and the middle factor at the half angle:
    f(wi, wo) cos(theta_i) ~ p(wo) q(h) p(wi) cos(theta_i)
(one p for both directions: the BRDF is reciprocal). Taking logarithms makes the product a sum,
    log f(wi, wo) = P(wo) + Q(h) + P(wi),
linear in the unknown texel values P = log p, Q = log q: sampled at many direction pairs it is
a least-squares problem, solved here with the paper's smoothness term (neighbouring texels of a
cube face kept close, weight `SMOOTH`) by the normal equations. The cosine is folded into the
light factor, as the chapter's effect expects (its stand-ins were white, N.L, white).

The BRDFs (`MODELS`) are known closed forms; 'phong' is kd + ks (R.V)^n, whose lobe about the
mirror direction is not a function of h alone, so the factorisation approximates it (the paper's
point: few terms, small error). The three maps are scaled so each peaks at 1 (8-bit storage);
`factor_scale` gives the product's lost scale.
"""
from __future__ import annotations

from typing import Callable

import numpy as np

from effects.base import caches
from effects.assets.textures import PROCEDURAL, Procedural, cube_directions, cube_face_uv, make_texture

SIZE = 16            # cube face edge of the fit (the maps are resampled to their own size)
SAMPLES = 30000      # direction pairs fitted
SMOOTH = 0.3         # weight of the smoothness term (relative to one sample)


def _phong(wi: np.ndarray, wo: np.ndarray) -> np.ndarray:
    # kd + ks (R.V)^n, R = the mirror of wi about the normal (0, 0, 1); kd 0.5, ks 0.5, n 12
    r = wi * np.array([-1.0, -1.0, 1.0])
    return 0.5 + 0.5 * np.maximum(0.0, np.sum(r * wo, axis=-1)) ** 12


MODELS: dict[str, Callable[[np.ndarray, np.ndarray], np.ndarray]] = {"phong": _phong}
FACTORS = ("view", "light", "half")
FLOOR = 1e-3         # log f is taken of max(f, FLOOR)


def _hemisphere(rng: np.random.Generator, n: int) -> np.ndarray:
    z = rng.uniform(0.02, 1.0, n)
    phi = rng.uniform(0.0, 2 * np.pi, n)
    r = np.sqrt(1.0 - z * z)
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)


def _texel(d: np.ndarray, size: int) -> np.ndarray:
    """Index face * size^2 + row * size + column of the cube texel holding each direction."""
    face, u, v = cube_face_uv(d)
    col = np.clip((u * size).astype(np.int64), 0, size - 1)
    row = np.clip((v * size).astype(np.int64), 0, size - 1)
    return face * size * size + row * size + col


def _smoothness(size: int) -> tuple[np.ndarray, np.ndarray]:
    """Pairs of neighbouring texels within each face."""
    idx = np.arange(6 * size * size).reshape(6, size, size)
    right = np.stack([idx[:, :, :-1].ravel(), idx[:, :, 1:].ravel()], axis=1)
    down = np.stack([idx[:, :-1, :].ravel(), idx[:, 1:, :].ravel()], axis=1)
    pairs = np.concatenate([right, down])
    return pairs[:, 0], pairs[:, 1]


# eight fits of the default size (two 6 x 16 x 16 float64 arrays, 24 KiB)
_FACTORS = caches.declare("assets.brdf_factors", keys="model, cube edge, samples",
                          max_bytes=8 * (32 << 10))


def factorise(model: str, size: int = SIZE, samples: int = SAMPLES) -> tuple[np.ndarray, np.ndarray]:
    """(p, q): (6, size, size) texel values of the outer and middle factors (unscaled); kept,
    shared by every caller (read them, don't change them)."""
    return _FACTORS.get_or_make((model, size, samples), lambda: _factorise(model, size, samples))


def _factorise(model: str, size: int, samples: int) -> tuple[np.ndarray, np.ndarray]:
    f = MODELS[model]
    rng = np.random.default_rng(2001)
    wi, wo = _hemisphere(rng, samples), _hemisphere(rng, samples)
    h = wi + wo
    h /= np.linalg.norm(h, axis=1, keepdims=True)
    y = np.log(np.maximum(f(wi, wo), FLOOR))
    n = 6 * size * size
    cols = np.stack([_texel(wo, size), n + _texel(h, size), _texel(wi, size)], axis=1)
    normal = np.zeros((2 * n, 2 * n))
    for a in range(3):
        for b in range(3):
            np.add.at(normal, (cols[:, a], cols[:, b]), 1.0)
    rhs = np.zeros(2 * n)
    for a in range(3):
        np.add.at(rhs, cols[:, a], y)
    j, k = _smoothness(size)
    for offset in (0, n):                  # the same smoothness on P and on Q
        jj, kk = j + offset, k + offset
        np.add.at(normal, (jj, jj), SMOOTH)
        np.add.at(normal, (kk, kk), SMOOTH)
        np.add.at(normal, (jj, kk), -SMOOTH)
        np.add.at(normal, (kk, jj), -SMOOTH)
    normal[np.diag_indices(2 * n)] += 1e-4   # texels no sample reaches (the lower hemisphere) -> 0
    x = np.linalg.solve(normal, rhs)
    return np.exp(x[:n]).reshape(6, size, size), np.exp(x[n:]).reshape(6, size, size)


def _cosine(size: int) -> np.ndarray:
    d = cube_directions(size)
    return d[..., 2] / np.linalg.norm(d, axis=-1)


def _upsample(maps: np.ndarray, size: int) -> np.ndarray:
    """(6, n, n) face grids resampled to (6, size, size), bilinear between texel centres within
    each face (clamped at its edges): the fit's texels stay coarse, the map does not step."""
    n = maps.shape[1]
    c = np.clip((np.arange(size) + 0.5) * n / size - 0.5, 0, n - 1)
    i0 = np.minimum(np.floor(c).astype(np.int64), n - 2) if n > 1 else np.zeros(size, np.int64)
    t = c - i0
    i1 = np.minimum(i0 + 1, n - 1)
    rows = maps[:, i0] * (1 - t)[None, :, None] + maps[:, i1] * t[None, :, None]
    return rows[:, :, i0] * (1 - t)[None, None, :] + rows[:, :, i1] * t[None, None, :]


def _unscaled(model: str, size: int) -> dict[str, np.ndarray]:
    """The factors at `size`, in log space resampled from the fit; the view factor is 0 below
    the horizon (no visible surface is seen from there), the light factor carries max(0, cos)."""
    p, q = factorise(model)
    p, q = np.exp(_upsample(np.log(p), size)), np.exp(_upsample(np.log(q), size))
    cos = _cosine(size)
    return {"view": p * (cos > 0), "light": p * np.maximum(0.0, cos), "half": q}


def factor_maps(model: str, size: int = 64) -> dict[str, np.ndarray]:
    """The three (6, size, size, 4) RGBA cube maps, each peaking at 1: 'view' = p, 'light' =
    p * max(0, cos theta), 'half' = q (texel-centre directions; tangent space z = normal)."""
    out = {}
    for name, m in _unscaled(model, size).items():
        m = m / m.max()
        out[name] = np.concatenate([np.repeat(m[..., None], 3, -1), np.ones(m.shape + (1,))],
                                   axis=-1).astype(np.float32)
    return out


def factor_scale(model: str, size: int = 64) -> float:
    """What the product of the three peak-1 maps must be multiplied by to give f cos."""
    return float(np.prod([m.max() for m in _unscaled(model, size).values()]))


def brdf_factor_texture(arg: str, size: int) -> np.ndarray:
    """The 'brdf_factor:MODEL:FACTOR' procedural (FACTOR = view | light | half)."""
    model, _, factor = arg.partition(":")
    if model not in MODELS or factor not in FACTORS:
        raise ValueError(f"expected MODEL:FACTOR with MODEL in {', '.join(MODELS)} and FACTOR "
                         f"in {', '.join(FACTORS)}")
    return factor_maps(model, size)[factor]


def lookup(maps: np.ndarray, d: np.ndarray) -> np.ndarray:
    """Nearest-texel value of a (6, S, S) map at directions (..., 3) (for checking fits)."""
    size = maps.shape[1]
    return maps.reshape(-1)[_texel(d.reshape(-1, 3), size)].reshape(d.shape[:-1])


# The procedural row: 'brdf_factor:MODEL:FACTOR' (registered here, where the factorisation is;
# effects.host.resources imports this module).
PROCEDURAL["brdf_factor"] = Procedural(
    lambda a, s, h: make_texture(brdf_factor_texture(a, s), "X8R8G8B8", kind="cube", mips=False),
    64, "phong:light", "McCool-Ang-Ahmad factor cube map MODEL:view|light|half, X8R8G8B8")
