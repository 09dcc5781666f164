"""Occlusion of a height field by itself: the "pixel-to-pixel" occlusion term of Taylor's
three-term hemisphere lighting (Boyd and Taylor, "Hardware Shading with Direct3D": "firing rays
in a height field and storing the result in the alpha channel of a normal map").

From every texel, rays go out in `AZIMUTHS` directions over the (wrapping) height field, one
texel a step for `RADIUS` steps; the highest elevation angle a seen along each is that
direction's horizon. A cosine-weighted hemisphere loses sin^2(a) of its light in a slice under
a horizon a, so occlusion = mean over azimuths of sin^2(a). Heights are measured in the units
the Sobel normal map implies (`textures.sobel_normal_map`: a ramp h = a * column gives
dX = 8a, so the normals are those of the height 8 h in texels), so the shadowing agrees with
the relief the normal map draws.
"""
from __future__ import annotations

import numpy as np

AZIMUTHS = 8
RADIUS = 8            # texels
SOBEL_HEIGHT = 8.0    # texels of rise per unit of height, as the Sobel normal map implies


def horizon_occlusion(height: np.ndarray, *, scale: float = 1.0, azimuths: int = AZIMUTHS,
                      radius: int = RADIUS) -> np.ndarray:
    """(H, W) occlusion in [0, 1] of a (H, W) height field in [0, 1] (0 = open sky)."""
    h = np.asarray(height, np.float64) * SOBEL_HEIGHT * scale
    rows, cols = np.indices(h.shape)
    total = np.zeros_like(h)
    for k in range(azimuths):
        angle = 2 * np.pi * k / azimuths
        dx, dy = np.cos(angle), np.sin(angle)
        best = np.zeros_like(h)                           # tan of the horizon, at least 0
        for step in range(1, radius + 1):
            y = np.mod(np.rint(rows + dy * step).astype(np.int64), h.shape[0])
            x = np.mod(np.rint(cols + dx * step).astype(np.int64), h.shape[1])
            best = np.maximum(best, (h[y, x] - h) / step)
        total += best * best / (1.0 + best * best)          # sin^2 of the horizon angle
    return total / azimuths
