"""Images through Pillow, bounded: the size is checked before any pixel is decoded.

Pillow opens lazily (`Image.open` reads the header only), so a 17 KB PNG that claims
12000 x 12000 pixels is refused by the `texture_edge`/`texture_texels` limits before it would
decompress 576 MB. Pillow's own decompression-bomb guard (a warning from 89 M pixels, an
error from 179 M) is turned into the same located error instead of reaching stderr raw.
"""
from __future__ import annotations

import os
import struct
import warnings

import numpy as np

from effects.base import limits, untrusted
from effects.base.errors import Location, SceneError


def read_image(path: str, mode: str, where: Location, what: str = "image") -> np.ndarray:
    """The image at `path` converted to Pillow `mode` ('RGBA', 'L'), as a uint8 array."""
    from PIL import Image, UnidentifiedImageError
    untrusted.check_regular(path, what, SceneError, where, "texture_file_bytes")
    try:
        with warnings.catch_warnings():
            # our own limits below are far stricter than Pillow's warning; keep it off stderr
            warnings.simplefilter("ignore", Image.DecompressionBombWarning)
            with Image.open(path) as img:
                width, height = img.size
                limits.check_texture(width, height, 1, where, f"{what} {os.path.basename(path)}", SceneError)
                return np.asarray(img.convert(mode))
    except Image.DecompressionBombError as exc:   # raised by Image.open itself, past 179 M pixels
        raise SceneError(f"cannot read {what}: {exc} (Pillow's decompression-bomb guard, beyond "
                         f"this framework's texture_texels limit of {limits.get('texture_texels'):,})",
                         where) from None
    except (OSError, UnidentifiedImageError, ValueError, SyntaxError, EOFError, struct.error) as exc:
        raise SceneError(f"cannot read {what}: {exc}", where) from None
