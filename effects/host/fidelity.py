"""How much of the look a fallback keeps: each technique of an effect, drawn on a card, against
the effect's best technique.

    meter = meter_for(effect, scene="fxfiles/shadows.yaml")
    meter.measure(effect.technique("Shadow4_Linear8"), load_profile("geforcefx5900"))
    # Likeness(ssim=0.97..., psnr=31.2...)

The best technique is the first valid one on `refrast` (the reference rasteriser runs every
technique, so it is the author's first choice), or the one the user names (`--best NAME`).
Every picture is drawn on the reference (NumPy) back end -- the ground truth -- in the same
scene with the same parameters: the best one with `refrast`'s caps, each other one with the
caps of the card that runs it (so a DX8 card's fixed-point precision is in its picture).

The measure (`likeness`):
- SSIM (Wang, Bovik, Sheikh and Simoncelli 2004), scikit-image's `structural_similarity`: a
  well-kept, documented implementation of the published measure, with the paper's constants
  (K1 0.01, K2 0.03, an 11 x 11 Gaussian window of sigma 1.5, population covariance:
  `gaussian_weights=True, use_sample_covariance=False`, as scikit-image's documentation says
  matches the paper). FLIP (NVIDIA's `flip-evaluator`) models viewing distance and colour
  better, but it is a single-maintainer binding with its own native build, for a figure per
  cell that SSIM's structure term already answers; the pictures here are small and
  synthetic, where SSIM's window is what decides.
- PSNR over the same pixels (scikit-image's `peak_signal_noise_ratio`), infinite for identical
  pictures (JSON has no infinity: `Likeness.as_json` writes null).
Colour is compared as shown (the target's RGB, alpha dropped as `effects render` writes it),
each channel in [0, 1] (`data_range=1`: an 8-bit target's full range, so a black picture
against a white one is the worst case, whatever the effect draws), SSIM averaged over the
three channels.

The size is fixed, `SIZE` (128 x 128), whatever the window or cell drawn: a choice must not
change when a window is resized. At 128 px the 11 px window spans about a tenth of the
bundled objects, so a highlight or a shadow edge counts as structure, and a bundled
technique is drawn and measured in 50-235 ms (the mean of each effect, two runs: 56-206 and
51-233 ms; brdf.fx's pictures pay its compiles, 0.9-1.2 s) on the shared 2-core VM
(`benchmarks/bench_fidelity.py`).
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Mapping, Sequence

from effects.base import caches
from effects.base.errors import EffectError

if TYPE_CHECKING:  # pragma: no cover
    # NumPy and the scene's reader load when something is measured: the command line's key for
    # stored fidelity rows reads the constants below, and a row read back needs no more
    import numpy as np
    from effects.host.scene import Scene
    from effects.d3d9.caps import CapsProfile
    from effects.model import Effect, Technique
    from effects.validate.select import Policy, PolicyLike
    from effects.validate.technique import Validation

SIZE = (128, 128)
REFERENCE_CARD = "refrast"
SSIM_SIGMA = 1.5          # the paper's Gaussian window (11 x 11 at scikit-image's 3.5 sigma)
DATA_RANGE = 1.0          # pixels in [0, 1]: the 8-bit target's full range


@dataclass(frozen=True)
class Likeness:
    """One picture against the best technique's: SSIM (1 the same) and PSNR in dB (inf the
    same)."""

    ssim: float
    psnr: float

    def as_json(self) -> dict[str, float | None]:
        return {"ssim": round(self.ssim, 4),
                "psnr": None if math.isinf(self.psnr) else round(self.psnr, 2)}

    def __str__(self) -> str:
        psnr = "inf" if math.isinf(self.psnr) else f"{self.psnr:.1f}"
        return f"SSIM {self.ssim:.3f}, PSNR {psnr} dB"


def likeness(picture: np.ndarray, reference: np.ndarray) -> Likeness:
    """`picture` against `reference` (H x W x 3 or 4 uint8, the same size), as the module
    docstring says."""
    import numpy as np
    from skimage.metrics import peak_signal_noise_ratio, structural_similarity
    a = np.asarray(picture)[..., :3].astype(np.float64) / 255.0
    b = np.asarray(reference)[..., :3].astype(np.float64) / 255.0
    ssim = float(structural_similarity(b, a, data_range=DATA_RANGE, channel_axis=-1,
                                       gaussian_weights=True, sigma=SSIM_SIGMA,
                                       use_sample_covariance=False))
    # identical pictures: infinite, said so rather than divided by zero
    psnr = math.inf if np.array_equal(a, b) else \
        float(peak_signal_noise_ratio(b, a, data_range=DATA_RANGE))
    return Likeness(ssim, psnr)


class Meter:
    """One effect in one scene with one set of parameter values, measured technique by
    technique against its best. Each (technique, card) is drawn and measured once."""

    def __init__(self, effect: "Effect", *, scene: Any = None,
                 params: Mapping[str, Any] | None = None, best: str | None = None,
                 size: tuple[int, int] = SIZE) -> None:
        from effects.host.scene import load_scene
        self.effect = effect
        self.scene: Scene = load_scene(scene)    # once: every picture in the same scene
        self.params = dict(params or {})
        self.size = size
        self.best_name = best
        if best is not None:
            effect.technique(best)               # a name the effect lacks: said now, located
        self._best: tuple["Technique | None", np.ndarray | None] | None = None
        # the best picture's one colour where it shows nothing (`blank`), once drawn
        self._blank: tuple[int, int, int] | None = None
        self._measured: dict[tuple[int, int], tuple[Any, Likeness | None]] = {}

    def best(self) -> "Technique | None":
        """The technique every other is measured against (None: none runs on `refrast`)."""
        return self._reference()[0]

    def _reference(self) -> tuple["Technique | None", np.ndarray | None]:
        if self._best is None:
            from effects.d3d9.caps import load_profile
            from effects.validate.select import select
            card = load_profile(REFERENCE_CARD)
            if self.best_name is not None:
                tech = self.effect.technique(self.best_name)
                validation = None
            else:
                validation = select(self.effect, card).chosen
                tech = validation.technique if validation is not None else None
            picture = self.picture(tech, card, validation) if tech is not None else None
            if picture is not None:
                self._blank = _shows_nothing(picture, self.scene.clear_color)
                if self._blank is not None:
                    picture = None        # nothing to measure against: every technique unmeasured
            self._best = (tech, picture)
        return self._best

    @property
    def blank(self) -> tuple[int, int, int] | None:
        """The clear colour (r, g, b) where the best technique's picture is that colour
        everywhere -- it shows nothing, so no technique is measured (`measure` gives None and
        the fidelity order keeps file order); None otherwise. Against an empty frame every
        technique that also draws nothing would score SSIM 1, and the cheapest of them would
        win: a fixed-function fallback over the ps.2.0 technique a DX9 card runs (a mod's
        effect whose host sets its colour and textures, drawn here without them)."""
        self._reference()
        return self._blank

    def picture(self, technique: "Technique", profile: "CapsProfile",
                validation: "Validation | None" = None) -> np.ndarray | None:
        """`technique` drawn as `profile` draws it, on the reference back end at `size`
        (H x W x 4 uint8), or None where it cannot be drawn (its error is the validator's or
        the renderer's to report, by the commands that draw it)."""
        from effects.host.runtime import Runtime
        try:
            runtime = Runtime(self.effect, profile, scene=self.scene, size=self.size,
                              params=self.params, backend="numpy")
            if validation is not None and validation.technique is technique and validation.ok:
                runtime.validation = validation   # the device states the card's checks saw
            return runtime.render(technique).image
        except EffectError:
            return None

    def measure(self, technique: "Technique", profile: "CapsProfile",
                validation: "Validation | None" = None) -> Likeness | None:
        """`technique` on `profile` against the best technique on `refrast`; None where
        either cannot be drawn."""
        index = next(i for i, t in enumerate(self.effect.techniques) if t is technique)
        key = (index, id(profile))
        hit = self._measured.get(key)
        if hit is not None and hit[0] is profile:
            return hit[1]
        reference = self._reference()[1]
        picture = None if reference is None else self.picture(technique, profile, validation)
        found = None if picture is None else likeness(picture, reference)
        self._measured[key] = (profile, found)   # the profile held: its id stays its own
        return found

    def likeness(self, validations: Sequence["Validation | None"]) -> dict[int, float | None]:
        """The fidelity order's scores (`effects.validate.select.Likeness`): each valid
        technique's SSIM on the card that validated it, by position."""
        out: dict[int, float | None] = {}
        for i, v in enumerate(validations):
            if v is not None and v.ok:
                found = self.measure(v.technique, v.profile, v)
                out[i] = None if found is None else found.ssim
        return out


def _shows_nothing(picture: np.ndarray, clear: Sequence[float]) -> tuple[int, int, int] | None:
    """The clear colour (r, g, b) where every pixel of `picture` is that colour, else None.
    A picture of one other colour is a look (a full-screen fill) and is measured."""
    from effects.host.diagnostics import uniform_colour
    colour = uniform_colour(picture)
    target = tuple(int(round(min(max(float(c), 0.0), 1.0) * 255)) for c in tuple(clear)[:3])
    return colour if colour is not None and colour == target else None


# A meter holds its measures (two floats a technique and card) and the best picture
# (128 x 128 x 4 bytes): ~70 KB with its effect's references
_METERS = caches.declare("host.fidelity_meters", keys="the effect object, the scene (a YAML "
                         "path with its modification time, a mapping's text, a Scene object), "
                         "the parameter values' text, the best technique's name and the size",
                         entry_bytes=96 << 10, max_bytes=64 * (96 << 10))


def _scene_key(scene: Any) -> Any:
    if scene is None:
        return None
    if isinstance(scene, (str, os.PathLike)):
        path = os.path.abspath(os.fspath(scene))
        try:
            st = os.stat(path)
        except OSError:
            return ("path", path)           # the load says what is wrong with it
        return ("path", path, st.st_mtime_ns, st.st_size, st.st_ino)
    if isinstance(scene, Mapping):
        return ("mapping", repr(sorted(scene.items(), key=lambda kv: str(kv[0]))))
    return ("object", id(scene))


def meter_for(effect: "Effect", *, scene: Any = None, params: Mapping[str, Any] | None = None,
              best: str | None = None, size: tuple[int, int] = SIZE) -> Meter:
    """The meter of `effect` in `scene` with `params`, made once per process for the same
    objects: the runtime, the viewer, the matrix and the API ask for the same measures."""
    key = (id(effect), _scene_key(scene),
           repr(sorted((params or {}).items())) if params else None, best, size)
    hit = _METERS.get(key)
    # the key's ids are the effect's and the scene object's: held by the meter, checked here
    if hit is not None and hit.effect is effect and (key[1] is None or key[1][0] != "object"
                                                     or hit.scene is scene):
        return hit
    meter = Meter(effect, scene=scene, params=params, best=best, size=size)
    _METERS.put(key, meter)
    return meter


def policy_for(effect: "Effect", policy: "PolicyLike" = "fidelity", *, scene: Any = None,
               params: Mapping[str, Any] | None = None, best: str | None = None) -> "Policy":
    """`policy` (a Policy or its text) ready to select `effect`'s techniques: under the fidelity
    order, with the scores of the effect's meter in `scene` (`meter_for`) unless it has its
    own; any other policy as it is (no picture is drawn to select). Every route handed the returned object ranks
    the same measures (effects.validate.select)."""
    from effects.validate.select import as_policy
    pol = as_policy(policy)
    if pol.order != "fidelity" or pol.likeness is not None:   # measured already: as it is
        return pol
    return pol.with_likeness(meter_for(effect, scene=scene, params=params, best=best).likeness)
