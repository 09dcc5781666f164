"""Make the thumbnails of docs/gallery.md: every technique of the bundled effects on a card
that runs it, drawn by the NumPy reference back end on the default scene (the unit sphere seen from
(0, 0, 3)) at 256 x 256 and reduced to 128 x 128 (Lanczos), plus the specular-only close-ups
of the banding comparison. Deterministic; run from anywhere:

    python docs/thumbs/make_thumbs.py
"""
from __future__ import annotations

import os
import tempfile

import numpy as np
from PIL import Image

import effects
from effects.assets.texture_files import load_texture
from effects.assets import brdf  # noqa: F401  (registers the brdf_factor procedural)
from effects.assets.textures import make_texture, procedural

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
FX = os.path.join(ROOT, "fxfiles")
TEXTURES = os.path.join(FX, "textures")


def solid(rgb) -> effects.program.texture.Texture:
    return make_texture(np.broadcast_to(np.array([*rgb, 1.0], np.float32), (4, 4, 4)).copy(),
                        "X8R8G8B8")


# DX8 files carry no texture annotations: their textures come from the caller.
gloss = load_texture(os.path.join(TEXTURES, "stones_gloss.png")).levels[0]
DIRT = make_texture(np.concatenate([1.0 - gloss[..., :3], gloss[..., 3:]], axis=-1), "X8R8G8B8")
SDK8 = {"tBas": os.path.join(TEXTURES, "stones_base.png"),
        "tNrm": procedural("sobel_normals:textures/stones_height.png", base_dir=FX),
        "tEnv": procedural("sky_cube:64"), "tDrt": DIRT}
# The chapter's BRDF application set the factor cube maps: fxfiles/brdf.yaml's, the
# homomorphic factorisation of a known BRDF (effects/assets/brdf.py).
BRDF = {"BRDFTexture1": procedural("brdf_factor:phong:view"),
        "BRDFTexture2": procedural("brdf_factor:phong:light"),
        "BRDFTexture3": procedural("brdf_factor:phong:half"),
        "ObjectTexture": os.path.join(TEXTURES, "earth_base.png"),
        "MaterialColor": [1.0, 1.0, 1.0, 1.0]}

# (effect, technique, card, policy, params): technique None = the one the card selects.
THUMBS = [
    ("phong", "PerPixelPhong_ps20", "radeon9700", None),
    ("phong", "PerPixelPhong_ps11", "geforce3", None),
    ("phong", "Dot3_dx7", "geforce2", None),
    ("phong", "SingleTexture", "tnt2", None),
    ("specular_bump", "Specular_ps20", "radeon9700", None),
    ("specular_bump", "SpecularTable_ps11", "geforce3", None),
    ("specular_bump", "SpecularMultiply_ps11", "geforce3", None),
    ("specular_bump", "Dot3_dx7", "geforce2", None),
    ("specular_bump", "BumpEnvMap_dx6", "g400", None),
    ("specular_bump", "Emboss_dx6", "tnt2", None),
    ("specular_bump", "SingleTexture", "tnt2", None),
    ("hemisphere", "HemisphereOcclusion_ps11", "geforce3", None),
    ("hemisphere", "HemispherePerPixel_ps11", "geforce3", None),
    ("hemisphere", "HemisphereVertex_vs11", "tnt2", None),
    ("sdk8_style", "TPS4", "radeon8500", SDK8),
    ("sdk8_style", "TPS1", "geforce3", SDK8),
    ("sdk8_style", "TFF7", "geforce2", SDK8),
    ("sdk8_style", "TDX6", "tnt2", SDK8),
    ("sdk9_style", "Marble_ps11", "geforce3", None),
    ("sdk9_style", "Marble_dx7", "geforce2", None),
    ("sdk9_style", "Marble_dx6", "tnt2", None),
    ("fast_phong", "Phong", "refrast", None),
    ("fast_phong", "Gouraud", "radeon9700", None),
    ("fast_phong", "Gouraud", "tnt2", None),
    ("hemisphere", "HemisphereVertex_vs11", "geforce2", None),
    ("brdf", "tec0", "geforce3", BRDF),
    ("brdf", "tec0", "radeon8500", BRDF),
    ("brdf", "tec0", "radeon9700", BRDF),
]

# The same techniques on the teapot, whose handle and spout occlude it (file name + _teapot).
TEAPOT = [("hemisphere", "HemisphereOcclusion_ps11", "geforce3"),
          ("hemisphere", "HemispherePerPixel_ps11", "geforce3")]

# shadows.fx in its own occluder scene (a floor and a cube under a point light; the default
# sphere would shadow only its own unlit side): file name + _scene.
SHADOWS = [("Shadow4_R32F", "refrast"), ("Shadow4_R32F", "radeon9700"),
           ("Shadow1_R32F", "refrast"), ("Shadow4_R16F", "geforce6800"),
           ("Shadow4_Linear8", "geforcefx5900"), ("Lit_ff", "geforce3")]

# Drawn through the command line, as a user would (`effects render`): (effect, technique, card,
# extra arguments, file name suffix). wood.fx reads its colours and vectors from wood.yaml,
# what the chapter's application set.
WOOD = ["--scene", os.path.join(FX, "wood.yaml")]
COARSE = ["--scene", os.path.join(FX, "fast_phong_coarse.yaml")]
CLI = [
    ("fast_phong", "Phong", "refrast", COARSE, "_coarse"),
    ("fast_phong", "Phong", "refrast", COARSE + ["--backend", "gl"], "_coarse_gl"),
    ("fast_phong", "Gouraud", "refrast", COARSE, "_coarse"),
    ("wood", "Wood_ps20", "radeon9700", WOOD, ""),
    ("wood", "Wood_ps20", "geforcefx5900", WOOD, ""),
    ("wood", "Wood_ps20", "geforce6800", WOOD, ""),
    ("wood", "WoodRings_ps20", "radeon9700", WOOD, ""),
    ("wood", "WoodRings_ps20", "radeon9700", WOOD + ["--set", "turbulence=0.1"], "_turbulence0.1"),
    ("multilight", "MultiLight_ps30", "geforce6800", [], ""),
    ("multilight", "MultiLight_ps20", "radeon9700", [], ""),
    ("multilight", "MultiLight_ff", "geforce3", [], ""),
    ("multilight", "MultiLight_ff", "tnt2", [], ""),
    ("sdk9_hlsl", "Scene_ps20", "radeon9700", [], ""),
    ("sdk9_hlsl", "Scene_ps14", "radeon8500", [], ""),
    ("sdk9_hlsl", "Scene_ps11", "geforce3", [], ""),
    ("sdk9_hlsl", "Scene_ff", "tnt2", [], ""),
]

# The banding close-ups: the specular term alone (black Earth, flat normal map, white
# specular colour), the 32 x 32 pixels around the highlight of a 128 x 128 render, enlarged
# four times without filtering so each pixel shows.
SPECULAR_ONLY = {"NormalMap": solid((0.5, 0.5, 1.0)), "EarthTexture": solid((0.0, 0.0, 0.0)),
                 "SpecularColor": [1.0, 1.0, 1.0, 1.0]}
CLOSE_UPS = [("SpecularMultiply_ps11", "geforce3"), ("SpecularTable_ps11", "geforce3"),
             ("Specular_ps20", "radeon9700"), ("SpecularMultiply_ps11", "modern")]


def save(image: np.ndarray, name: str) -> None:
    Image.fromarray(np.ascontiguousarray(image[..., :3])).save(
        os.path.join(HERE, name), optimize=True)


def main() -> None:
    for effect, technique, card, params in THUMBS:
        fx = effects.load_effect(os.path.join(FX, f"{effect}.fx"))
        image = effects.render(fx, card, technique=technique, size=(256, 256), params=params)
        small = Image.fromarray(image[..., :3]).resize((128, 128), Image.LANCZOS)
        save(np.asarray(small), f"{effect}_{technique}_{card}.png")
    for effect, technique, card in TEAPOT:
        fx = effects.load_effect(os.path.join(FX, f"{effect}.fx"))
        image = effects.render(fx, card, technique=technique, size=(256, 256),
                               scene={"mesh": "teapot"})
        small = Image.fromarray(image[..., :3]).resize((128, 128), Image.LANCZOS)
        save(np.asarray(small), f"{effect}_{technique}_{card}_teapot.png")
    shadows()
    command_line()
    fx = effects.load_effect(os.path.join(FX, "specular_bump.fx"))
    for technique, card in CLOSE_UPS:
        image = effects.render(fx, card, technique=technique, size=(128, 128),
                               params=SPECULAR_ONLY)
        y, x = np.unravel_index(np.argmax(image[..., 1]), image.shape[:2])
        y0, x0 = int(np.clip(y - 16, 0, 96)), int(np.clip(x - 16, 0, 96))
        crop = image[y0:y0 + 32, x0:x0 + 32]
        save(np.repeat(np.repeat(crop, 4, axis=0), 4, axis=1), f"highlight_{technique}_{card}.png")


def shadows() -> None:
    fx = effects.load_effect(os.path.join(FX, "shadows.fx"))
    for technique, card in SHADOWS:
        image = effects.render(fx, card, technique=technique, size=(256, 256),
                               scene=os.path.join(FX, "shadows.yaml"))
        small = Image.fromarray(image[..., :3]).resize((128, 128), Image.LANCZOS)
        save(np.asarray(small), f"shadows_{technique}_{card}_scene.png")


def command_line() -> None:
    from effects.cli.main import main as effects_main
    with tempfile.TemporaryDirectory() as tmp:
        for effect, technique, card, extra, suffix in CLI:
            out = os.path.join(tmp, "frame.png")
            code = effects_main(["render", os.path.join(FX, f"{effect}.fx"), "-p", card,
                                 "-t", technique, "--size", "256x256", *extra, "-o", out])
            if code != 0:
                raise SystemExit(f"effects render {effect}.fx -t {technique} -p {card}: exit {code}")
            small = Image.open(out).convert("RGB").resize((128, 128), Image.LANCZOS)
            save(np.asarray(small), f"{effect}_{technique}_{card}{suffix}.png")


if __name__ == "__main__":
    main()
