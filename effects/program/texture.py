"""The texture the back ends sample: kind, D3DFORMAT name and mip levels of decoded texels.

- A `Texture` holds DECODED texel values, float32, RGBA in the last axis: what a card's sampler
  returns for each stored texel ([0, 1] for unsigned formats, [-1, 1] for the signed bump
  formats, any float for the float formats). Where the format quantises, the values are exactly
  the quantised ones (`effects.assets.textures.encode`), so a procedural V8U8 map equals what a card would sample.
- Level shapes: '2d' (H, W, 4); '1d' (1, W, 4); 'cube' (6, H, W, 4) in D3D face order +X, -X,
  +Y, -Y, +Z, -Z; '3d' (D, H, W, 4). Row 0 is the top row of the image, v = 0, as Direct3D
  addresses textures; column 0 is u = 0. Texel (row i, column j) has its centre at
  u = (j + 0.5) / W, v = (i + 0.5) / H.

Textures are made by `effects.assets` (files, .dds, procedural generators) and by render
targets; the back ends read them and nothing else of how they were made.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from effects.program import formats

KINDS = ("1d", "2d", "3d", "cube")


@dataclass
class Texture:
    """A texture: kind, D3D format name and its mip levels of decoded texel values (see module doc)."""

    kind: str
    format: str
    levels: list[np.ndarray]
    name: str = ""

    @property
    def width(self) -> int:
        return int(self.levels[0].shape[-2])

    @property
    def height(self) -> int:
        return int(self.levels[0].shape[-3])

    @property
    def depth(self) -> int:
        return int(self.levels[0].shape[0]) if self.kind == "3d" else 1

    @property
    def signed(self) -> bool:
        """True for the bump formats whose channels decode to [-1, 1]."""
        return formats.pixel_format(self.format).signed
