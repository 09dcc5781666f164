"""The chapter's BRDF effect (fxfiles/brdf.fx) with real factor cube maps: McCool, Ang and
Ahmad's homomorphic factorisation of a known BRDF (effects/assets/brdf.py), made at load time by
the `brdf_factor:MODEL:FACTOR` procedural (fxfiles/brdf.yaml names them)."""
from __future__ import annotations

from tests.paths import ROOT

import os

import numpy as np
import pytest

from effects.base.errors import SceneError
from effects.assets import brdf
from effects.assets.textures import procedural

from tests.looks import test_effect_pictures as pictures

FXFILES = os.path.join(str(ROOT), "fxfiles")


def test_the_factorisation_fits_the_brdf():
    # On direction pairs the fit never saw: log(p(wo) q(h) p(wi)) against log f. The product
    # of three direction maps explains most of the BRDF's variation (RMS of the log error
    # 0.12 against 0.30 for the best constant).
    p, q = brdf.factorise("phong")
    rng = np.random.default_rng(5)
    wi, wo = brdf._hemisphere(rng, 5000), brdf._hemisphere(rng, 5000)
    h = wi + wo
    h /= np.linalg.norm(h, axis=1, keepdims=True)
    fitted = brdf.lookup(p, wo) * brdf.lookup(q, h) * brdf.lookup(p, wi)
    exact = brdf.MODELS["phong"](wi, wo)
    error = np.sqrt(np.mean(np.log(fitted / exact) ** 2))
    assert error < 0.5 * np.std(np.log(exact))
    assert error < 0.16


def test_the_factored_brdf_draws_the_brdf():
    # The sphere lit by the default light (from (2, 2, 2)) on a GeForce3, white detail texture:
    # each pixel against f(wi, wo) cos(theta_i) computed here in the sphere's tangent frame,
    # over the pixels where light and eye are both above the surface, scaled by what the
    # peak-1 maps lose (factor_scale): mean error 2/255, correlation 0.996, the highlight
    # within 3 pixels of the exact one.
    params = {f"BRDFTexture{i}": procedural(f"brdf_factor:phong:{f}")
              for i, f in enumerate(brdf.FACTORS, start=1)}
    params.update(ObjectTexture=pictures.WHITE, MaterialColor=[1.0, 1.0, 1.0, 1.0])
    got = pictures.render("brdf", "tec0", "geforce3", None, params=params).mean(axis=-1)
    p = pictures.POINT
    t, b, n = pictures.tangent_frame(p)

    def tangent(w: np.ndarray) -> np.ndarray:
        return np.stack([np.sum(w * t, -1), np.sum(w * b, -1), np.sum(w * n, -1)], -1)

    wi = tangent(np.broadcast_to(pictures.unit(np.array([2.0, 2.0, 2.0])), p.shape))
    wo = tangent(pictures.unit(pictures.EYE - p))
    exact = (brdf.MODELS["phong"](wi, wo) * np.maximum(0.0, wi[..., 2])
             / brdf.factor_scale("phong") * 255)
    mask = pictures.DISC & (wi[..., 2] > 0.05) & (wo[..., 2] > 0.05)
    assert np.abs(got - exact)[mask].mean() < 4.0
    assert pictures.correlation(got, exact, mask) > 0.98
    peak = np.unravel_index(np.argmax(np.where(mask, got, 0)), got.shape)
    truth = np.unravel_index(np.argmax(np.where(mask, exact, 0)), got.shape)
    assert np.hypot(peak[0] - truth[0], peak[1] - truth[1]) < 3.0
    assert got[mask].max() > 150


def test_a_bad_factor_name_is_a_located_error():
    with pytest.raises(SceneError, match="brdf_factor"):
        procedural("brdf_factor:phong:diagonal")
