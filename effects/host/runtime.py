"""Rendering an effect on a simulated card: `render()` and a D3DX-like begin/pass/end object.

    image = effects.render(effect, "geforce3", scene="scene.yaml", size=(320, 240))

The spine, per render:
  1. the parameters are copied (the caller's Effect is never changed) and given their values:
     the effect's own initialisers (an uninitialised one with a UIMin/UIMax range the middle
     of it, `semantics.ui_defaults`), then what the scene supplies by semantic
     (`effects.host.semantics.bind_scene`), then the scene's `params`, then `params=` (the command
     line's --set), each later source winning;
  2. the technique: the one named, rendered as asked whether or not the card can run it, or
     the one the card selects (`effects.validate.select.select`, policy as named); none is
     `NoValidTechnique` carrying every technique's reasons;
  3. every pass is lowered (`effects.lower.passes.lower_pass`) from Direct3D 9's default device state
     with the scene camera's WORLD/VIEW/PROJECTION transforms set (as an application sets them
     before Begin), states set by a pass persisting into the following passes, and drawn into
     one frame; a texture a pass samples that nothing supplies is drawn with a stand-in of its
     kind (a checker, a sky cube, a noise volume) and a warning (`Runtime.warnings`), an
     error when `strict`; when the card selected the technique, the device states are those its
     Validation checked;
  4. the frame comes back as H x W x 4 uint8 RGBA, row 0 at the top.

`Runtime` exposes the same steps as ID3DXEffect does: `begin()` (returns the pass count),
`begin_pass(i)`, `set_value()` + `commit_changes()`, `draw()`, `end_pass()`, `end()`. It keeps
its back end, textures and geometry between frames, which a viewer wants.
"""
from __future__ import annotations

import dataclasses
import os
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Mapping

import numpy as np

from effects.host.resources import (DEFAULT_TEXTURE_CACHE, Geometry, MissingTexture, TextureCache,
                                   TextureSource, check_texture_budget, declared_kind,
                                   effect_mesh_file, feeds_a_normal, geometry,
                                   procedural_parameters, resolve_texture, scene_mesh,
                                   stand_in_texture)
from effects.base import caches, limits
from effects.base.errors import EffectError, EffectWarning, Location, NoValidTechnique, SceneError
from effects.model import Effect, ParamRef, Parameter, SamplerState, Technique
from effects.host.scene import MAX_SIZE, InlineMesh, Scene, load_scene
from effects.host.semantics import bind_scene, coerce_value, lookup_parameter, ui_defaults
from effects.host.scripts import is_cube_target, is_render_target, target_extent, target_format
from effects.assets.textures import make_texture
from effects.program.texture import Texture
from effects.validate.technique import validate_technique

if TYPE_CHECKING:  # pragma: no cover
    from effects.d3d9.caps import CapsProfile
    from effects.program.passprogram import PassProgram
    from effects.validate.select import Selection
    from effects.validate.technique import Validation

_BACKENDS: dict[str, Any] = {}   # back ends by name, made once (a GL context is costly)


def get_backend(backend: Any) -> Any:
    """A back end instance: `backend` itself, or the shared one registered under that name."""
    if not isinstance(backend, str):
        return backend
    if backend not in _BACKENDS:
        from effects.program.backend import create_backend
        try:
            _BACKENDS[backend] = create_backend(backend)
        except EffectError:
            raise
        except Exception as exc:  # no GL context, a missing driver: the user's choice failed
            raise EffectError(f"cannot start the {backend!r} back end: {type(exc).__name__}: {exc}",
                              Location("<backend>", 1, 1)) from None
    return _BACKENDS[backend]


def _as_effect(effect: Effect | str | os.PathLike) -> Effect:
    if isinstance(effect, Effect):
        return effect
    from effects.frontend.loader import load_effect
    return load_effect(effect)


def _as_profile(profile: Any) -> "CapsProfile":
    if isinstance(profile, (str, os.PathLike)):
        from effects.d3d9.caps import load_profile
        return load_profile(os.fspath(profile))
    return profile


def _check_size(size: Any) -> tuple[int, int]:
    try:
        w, h = (int(v) for v in size)
        ok = (w, h) == tuple(size) and 1 <= w <= MAX_SIZE and 1 <= h <= MAX_SIZE
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise SceneError(f"size {size!r} must be (width, height), whole numbers from 1 to {MAX_SIZE}",
                         Location("<size>", 1, 1))
    return w, h


def _check_target(size: tuple[int, int], backend: str) -> None:
    """The render target against its back end's `target_pixels_<name>` limit, if it has one."""
    name = f"target_pixels_{backend}"
    if name in limits.LIMITS:
        limits.check(name, size[0] * size[1], Location("<size>", 1, 1),
                     f"a {size[0]} x {size[1]} render target on the {backend} back end", SceneError)


def no_valid_technique(effect: Effect, profile: "CapsProfile",
                       selection: "Selection") -> NoValidTechnique:
    """The error for a card that runs none of the effect's techniques, with every reason
    (`selection` chose nothing, so it validated every technique)."""
    reasons = {}
    lines = []
    for validation in selection.ranked:
        name = validation.technique.name or "<anonymous>"
        reasons[name] = list(validation.reasons)
        why = [str(r) for r in validation.reasons] or ["not chosen by the selection policy"]
        lines.append(f"  {name}:")
        lines.extend(f"    {line}" for line in why)
    card = profile.display_name or profile.name
    if not effect.techniques:
        message = f"the effect has no techniques, so {card} has nothing to render"
    else:
        message = f"no technique is valid on {card}:\n" + "\n".join(lines)
    return NoValidTechnique(message, Location(effect.path, 1, 1), reasons=reasons)


# A selection holds the chosen Validation and the reads it made: a few KB (tracemalloc:
# 3-8 KB for phong.fx and wood.fx)
_SELECTIONS = caches.declare(
    "host.selections", keys="the effect's technique list, the card and the policy (objects); "
    "on a hit, the same objects and the parameters validation read",
    entry_bytes=16 << 10, max_bytes=64 * (16 << 10))


def _selected(effect: Effect, profile: "CapsProfile", policy: Any) -> "Selection":
    """`select(effect, profile, policy)`, remembered across Runtimes: each
    `effects.render()` call makes a Runtime over a fresh copy of the parameters, and the copy
    shares the techniques. The selection is made again only when a parameter that validation
    read differs (`effects.model.RecordedReads`); the same Validation object comes back, so
    the lowering cache (which keys on it) hits too. A selection that fell past a technique
    with a language error (`Selection.passed_over`) raises that located error instead. A
    fidelity policy's scores (`Policy.likeness`, effects.host.fidelity.policy_for) are part of
    the key, by identity: a policy measured in another scene is another policy."""
    from effects.model import RecordedReads, still_holds
    from effects.validate.select import select
    likeness = getattr(policy, "likeness", None)
    try:
        key = (id(effect.techniques), id(profile), policy, id(likeness))
        hit = _SELECTIONS.get(key)
    except TypeError:   # an unhashable policy object: no memory
        hit, key = None, None
    if hit is not None and hit[0] is effect.techniques and hit[1] is profile and \
            hit[4] is likeness and still_holds(effect, hit[2]):
        selection = hit[3]
    else:
        reads = RecordedReads(effect)
        selection = select(reads, profile, policy)  # type: ignore[arg-type]
        if key is not None:
            _SELECTIONS.put(key, (effect.techniques, profile, reads.snapshot(), selection,
                                  likeness))
    error = selection.passed_over
    if error is not None:
        raise error.with_traceback(None)   # the same error each time
    return selection


@dataclass
class Frame:
    """A finished render and what made it."""

    image: np.ndarray          # H x W x 4 uint8 RGBA, row 0 at the top
    technique: Technique
    passes: int
    backend: str
    profile: "CapsProfile"
    warnings: list[EffectWarning] = dataclasses.field(default_factory=list)
    # what the picture shows and why (`effects.host.diagnostics`), when asked for
    diagnostics: list[EffectWarning] = dataclasses.field(default_factory=list)


class Runtime:
    """One effect bound to a card, a scene and parameter values, drawn D3DX-style.

    `params` maps parameter names to values (numbers, lists, arrays, strings as `--set`
    writes them; for textures a path relative to the current folder or a `Texture`).
    """

    def __init__(self, effect: Effect | str, profile: Any, *, scene: Any = None,
                 size: tuple[int, int] | None = None, params: Mapping[str, Any] | None = None,
                 backend: Any = "numpy", textures: TextureCache | None = None,
                 strict: bool = False) -> None:
        self.source_effect = _as_effect(effect)
        self.strict = strict
        # Located warnings about what the host had to stand in for (a texture nobody
        # supplies); printed by `effects render`, shown by the viewer; errors when strict.
        self.warnings: list[EffectWarning] = []
        self.profile = _as_profile(profile)
        self.scene: Scene = load_scene(scene)
        self.size = _check_size(size if size is not None else self.scene.size)
        _check_target(self.size, backend if isinstance(backend, str) else getattr(backend, "name", ""))
        # What an application sets with SetTransform before Begin, from the scene's camera
        # (EffectEdit and FX Composer do): a fixed-function pass that sets no transforms of
        # its own then draws the mesh where the camera sees it.
        m = self._matrices = self.scene.matrices(self.size)
        self.host_states = {"WorldTransform": m["world"], "ViewTransform": m["view"],
                            "ProjectionTransform": m["projection"]}
        self.backend = get_backend(backend)
        self.texture_cache = textures or DEFAULT_TEXTURE_CACHE
        # A copy of the parameter list (and of each Parameter): lowering reads Parameter.value.
        self.effect: Effect = dataclasses.replace(
            self.source_effect, parameters=[dataclasses.replace(p) for p in self.source_effect.parameters])
        self._given: dict[str, TextureSource] = {}
        self._textures: dict[str, Texture | None] = {}
        self._geometry: Geometry | None = None
        self._scene_runtime: Runtime | None = None
        self._copy_runtime: Runtime | None = None
        self._user_set: set[str] = set()         # names the scene's params or params= set
        self._timed: list[str] | None = None     # names bound to the scene's time (set_time)
        self._bind(params or {})
        self.technique: Technique | None = None
        self._programs: list["PassProgram"] = []
        self._pass: int | None = None
        self._program: "PassProgram | None" = None
        self.technique_drawn: Technique | None = None
        # The Validation of the technique being drawn, when one was made (the card's
        # selection, or given by a host that validated): lowering draws its device states.
        self.validation: "Validation | None" = None

    # -- parameter values ------------------------------------------------------------------
    def _param(self, name: str) -> Parameter:
        return self.effect.parameter(name)  # type: ignore[return-value]

    def _bind(self, params: Mapping[str, Any]) -> None:
        for name, value in ui_defaults(self.effect).items():
            self._param(name).value = value
        for name, value in bind_scene(self.effect, self.scene, self.size,
                                      matrices=self._matrices).items():
            self._param(name).value = value
        for name, value in self.scene.params.items():
            at = self.scene.location(f"params.{name}")
            self._set(lookup_parameter(self.effect, name, at, "scene params:"), value, at,
                      self.scene.base_dir, "scene params")
        for name, value in params.items():
            param = lookup_parameter(self.effect, name, None, "--set")
            self._set(param, value, param.location, os.getcwd(), "--set")
        # Untyped DX8 textures take the kind of what is bound, so lowering samples them right.
        for param in self.effect.parameters:
            if param.type.base == "texture" and declared_kind(param) is None:
                texture = self.texture(param.name)
                if texture is not None:
                    param.type = dataclasses.replace(param.type, dim=texture.kind.upper())

    def _set(self, param: Parameter, value: Any, at: Location, base_dir: str,
             source: str = "") -> None:
        coerced = coerce_value(param, value, at, source)
        self._user_set.add(param.name)
        if param.type.base == "sampler":
            named = param.value.get("Texture") if isinstance(param.value, SamplerState) else None
            if named is not None:
                texture = named.value.name if isinstance(named.value, ParamRef) else "its own"
                raise SceneError(f"{source} {param.name}: this sampler samples the texture its "
                                 f"sampler_state names ({texture}): set that one instead",
                                 named.location)
        if param.type.takes_image:
            self._given[param.name] = TextureSource(coerced, base_dir, at,
                                                    confined=source == "scene params")
            self._textures.pop(param.name, None)
        else:
            param.value = coerced
            # a Procedural texture made from this value is made again at its next use
            for other in self.effect.parameters:
                if other.type.takes_image and param.name in procedural_parameters(other):
                    self._textures.pop(other.name, None)

    def set_value(self, name: str, value: Any) -> None:
        """ID3DXEffect::SetValue: a parameter's value (as `params=` takes it); takes effect
        at the next begin_pass or commit_changes."""
        param = lookup_parameter(self.effect, name, None, "set_value")
        if param.type.base == "texture" and declared_kind(param) is None:
            raise SceneError(f"texture parameter {name} has no declared kind; set it before "
                             "the runtime is made (params=)", param.location)
        self._set(param, value, param.location, os.getcwd(), "set_value")

    def time_parameters(self) -> list[str]:
        """The parameters the scene's time feeds (TIME and whatever else the binding table
        derives from it), found by binding the scene at two times; a value the scene's
        params or params= gave is the user's and stays."""
        if self._timed is None:
            now = bind_scene(self.effect, self.scene, self.size, matrices=self._matrices)
            later = bind_scene(self.effect, dataclasses.replace(self.scene, time=self.scene.time + 1.25),
                               self.size, matrices=self._matrices)
            self._timed = [name for name, value in later.items() if name not in self._user_set
                           and not np.array_equal(value, now.get(name))]
        return self._timed

    def set_time(self, seconds: float) -> bool:
        """Move the scene's clock (a viewer's running TIME): the parameters it feeds take the
        new time at the next begin_pass. True when the effect reads the time at all."""
        timed = self.time_parameters()
        if timed and float(seconds) != self.scene.time:
            self.scene = dataclasses.replace(self.scene, time=float(seconds))
            values = bind_scene(self.effect, self.scene, self.size, matrices=self._matrices)
            for name in timed:
                self._param(name).value = values[name]
        return bool(timed)

    def texture(self, name: str) -> Texture | None:
        """The texture bound to texture parameter `name` (loaded on first use), or None."""
        if name not in self._textures:
            param = self._param(name)
            if param is None or not param.type.takes_image:
                self._textures[name] = None
            else:
                self._textures[name] = self._resolve(param)
                check_texture_budget(self._textures, param.location)
        return self._textures[name]

    def _resolve(self, param: Parameter) -> Texture | None:
        """The parameter's texture; a ResourceName file that is missing is a stand-in (a path
        the user gave that is missing stays an error: that is a typo to fix)."""
        given = self._given.get(param.name)
        try:
            return resolve_texture(param, self.effect, given, self.texture_cache)
        except MissingTexture as exc:
            if given is not None:
                raise
            return self._stand_in(param, exc.message, exc.location)

    def used_texture(self, name: str, sampled_as: str | None = None) -> Texture:
        """The texture a draw samples from parameter `name`: the bound one, or a stand-in of
        its kind with a warning when nothing supplies it (FX Composer shows a default
        texture too; the effect's author meant a picture there, not black). The kind is the
        parameter's type, else `sampled_as` (the sampler's: an untyped `texture` sampled by
        a sampler3D gets the noise volume), else 2D."""
        texture = self.texture(name)
        if texture is None and is_render_target(self._param(name)):
            # a render target sampled before anything was drawn into it: cleared to black.
            # Its size is checked as if it were drawn, but one black texel samples as any
            # number of them do, so that is all that is allocated.
            param = self._param(name)
            target_extent(param, self.size, str(getattr(self.backend, "name", "numpy")))
            cube = is_cube_target(param)
            texture = make_texture(np.zeros((6, 1, 1, 4) if cube else (1, 1, 4), np.float32),
                                   target_format(param), kind="cube" if cube else "2d",
                                   mips=False, name=name)
            self._textures[name] = texture
        elif texture is None:
            param = self._param(name)
            texture = self._stand_in(param, "nothing supplies it (no ResourceName, scene "
                                     "params or --set value)", param.location, sampled_as)
            self._textures[name] = texture
        return texture

    def _stand_in(self, param: Parameter, why: str, at: Location,
                  sampled_as: str | None = None) -> Texture:
        kind = declared_kind(param) or sampled_as or "2d"
        texture = stand_in_texture(kind, normal=feeds_a_normal(self.source_effect, param))
        what = f"texture parameter {param.name}" if param.type.base == "texture" else \
            f"sampler {param.name} (no texture in its sampler_state: the host sets one on its stage)"
        message = f"{what}: {why}; drawn with a stand-in ({texture.name}, {kind})"
        if self.strict:
            raise SceneError(message, at)
        warning = EffectWarning(message, at)
        if warning not in self.warnings:
            self.warnings.append(warning)
        return texture

    def lower(self, technique: Technique, index: int,
              host: Mapping[str, Any] | None = None) -> "PassProgram":
        """Pass `index` of `technique`, lowered with this runtime's parameter values and the
        transforms the host set (`host` replaces them: a script's full-screen quad is drawn
        with identities)."""
        from effects.lower.passes import lower_pass
        validation = self.validation if self.validation is not None \
            and self.validation.technique is technique else None
        return lower_pass(self.effect, technique, index, self.profile,
                          vertex_colors=self.geometry().has_diffuse,
                          host=self.host_states if host is None else host,
                          validation=validation)

    def set_target_texture(self, name: str, texture: Texture) -> None:
        """What a script drew into render-target texture parameter `name`."""
        self._textures[name] = texture

    def copy_runtime(self) -> "Runtime":
        """A runtime for the host's picture copy (`effects.host.scripts.COPY_PICTURE`)."""
        if self._copy_runtime is None:
            from effects.frontend.loader import load_effect
            from effects.host.scripts import COPY_PICTURE
            self._copy_runtime = Runtime(load_effect(COPY_PICTURE), self.profile,
                                         scene={"mesh": "quad"}, size=self.size, backend=None)
        return self._copy_runtime

    def scene_material_runtime(self) -> "Runtime":
        """A runtime drawing this scene with the host's plain material (`ScriptExternal`)."""
        if self._scene_runtime is None:
            from effects.frontend.loader import load_effect
            from effects.host.scripts import SCENE_MATERIAL
            self._scene_runtime = Runtime(load_effect(SCENE_MATERIAL), self.profile,
                                          scene=self.scene, size=self.size, backend=None,
                                          textures=self.texture_cache)
        return self._scene_runtime

    # -- technique -------------------------------------------------------------------------
    def select(self, technique: Technique | str | None = None, policy: Any = "first") -> Technique:
        """The named technique (valid or not), or the one the card selects."""
        if technique is not None:
            named = technique if isinstance(technique, Technique) else self.effect.technique(technique)
            if self.validation is not None and self.validation.technique is not named:
                self.validation = None
            return named
        selection = _selected(self.effect, self.profile, policy)
        if selection.chosen is None:
            raise no_valid_technique(self.effect, self.profile, selection)
        self.validation = selection.chosen
        return selection.chosen.technique

    # -- ID3DXEffect-like drawing ----------------------------------------------------------
    def begin(self, technique: Technique | str | None = None, policy: Any = "first") -> int:
        """Start a frame (cleared as the scene says) with a technique; returns its pass count."""
        self.technique = self.select(technique, policy)
        self._programs = []
        self.backend.begin_frame(self.size, self.scene.clear_color, self.scene.clear_depth,
                                 self.scene.clear_stencil)
        return len(self.technique.passes)

    def begin_pass(self, index: int) -> None:
        if self.technique is None:
            raise RuntimeError("begin_pass before begin")
        if not 0 <= index < len(self.technique.passes):
            raise EffectError(f"technique {self.technique.name} has no pass {index}",
                              self.technique.location)
        self._pass = index
        self.commit_changes()

    def commit_changes(self) -> None:
        """Lower the current pass with the parameter values now set."""
        if self._pass is None or self.technique is None:
            raise RuntimeError("commit_changes outside begin_pass/end_pass")
        try:
            self._program = self.lower(self.technique, self._pass)
        except EffectError:
            raise
        except Exception as exc:
            raise self._not_renderable(exc) from exc

    def _not_renderable(self, exc: Exception) -> Exception:
        """Lowering and the back ends assume a technique the card validates. A forced technique
        the card rejects may break that assumption anywhere (an `oT8` no stream feeds): then the
        error is the validator's first reason, located, not the internal exception. A valid
        technique that fails is our bug, and `exc` goes on as it is."""
        technique = self.technique or self.technique_drawn
        if technique is None:
            return exc
        validation = validate_technique(self.effect, technique, self.profile)
        if validation.ok or not validation.reasons:
            return exc
        reason = validation.reasons[0]
        card = self.profile.display_name or self.profile.name
        return EffectError(f"technique {technique.name or '<anonymous>'} cannot be rendered on {card}, "
                           f"which rejects it: {reason.message}", reason.location)

    def geometry(self) -> Geometry:
        """The scene's vertex streams for this effect (built once). A scene that names no
        mesh draws the one the effect names (EffectEdit's `string XFile`), if it loads."""
        if self._geometry is None:
            scene = self.scene
            if "mesh" not in scene.locations and not isinstance(scene.mesh, InlineMesh):
                scene = self._effect_mesh_scene(scene)
            self._geometry = geometry(scene, self.effect)
        return self._geometry

    def _effect_mesh_scene(self, scene: Scene) -> Scene:
        """`scene` with the effect's XFile as its mesh; a file that does not load leaves the
        scene's mesh, with a located warning (an error when strict): the effect still draws."""
        try:
            named = effect_mesh_file(self.effect)
            if named is None:
                return scene
            path, at = named
            with_file = dataclasses.replace(scene, mesh=path, base_dir=os.path.dirname(path) or ".",
                                            locations={**scene.locations, "mesh": at})
            scene_mesh(with_file)           # loads (and caches) it now, to fall back if it fails
            return with_file
        except SceneError as exc:
            if self.strict:
                raise
            warning = EffectWarning(f"{exc.message}; drawn on the scene's {scene.mesh} instead",
                                    exc.location)
            if warning not in self.warnings:
                self.warnings.append(warning)
            return scene

    def draw(self, geo: Geometry | None = None) -> None:
        """Draw the scene's mesh (or `geo`) with the current pass."""
        if self._program is None:
            raise RuntimeError("draw outside begin_pass/end_pass")
        self.draw_program(self._program, geo)

    def draw_program(self, program: "PassProgram", geo: Geometry | None = None,
                     backend: Any = None) -> None:
        """Draw `geo` (default the scene's mesh) with a lowered pass, its textures bound."""
        geo = geo or self.geometry()
        textures = {b.texture: self.used_texture(b.texture, b.kind) for b in program.textures
                    if b.texture is not None}
        try:
            (backend or self.backend).draw(program, geo.streams, geo.indices, geo.primitive, textures)
        except EffectError:
            raise
        except Exception as exc:
            raise self._not_renderable(exc) from exc

    def end_pass(self) -> None:
        self._pass, self._program = None, None

    def end(self) -> np.ndarray:
        """Finish the frame: H x W x 4 uint8 RGBA, row 0 at the top."""
        self.technique_drawn, self.technique = self.technique, None
        return self.backend.end_frame()

    def render(self, technique: Technique | str | None = None, policy: Any = "first") -> Frame:
        """A whole frame: every pass of the technique, drawn once each, or what its DXSAS
        `Script` annotation says (`effects.host.scripts`)."""
        from effects.host.scripts import ScriptRunner, technique_script
        chosen = self.select(technique, policy)
        if technique_script(chosen) is not None:
            runner = ScriptRunner(self, chosen)
            image = runner.run()
            self.technique_drawn = chosen
            return Frame(image, chosen, runner.passes_drawn,
                         getattr(self.backend, "name", str(self.backend)), self.profile,
                         list(self.warnings))
        passes = self.begin(chosen, policy)
        tech = self.technique
        try:
            for i in range(passes):
                self.begin_pass(i)
                self.draw()
                self.end_pass()
        except BaseException:
            self.end_pass()
            self.end()          # leave the back end ready for the next frame
            raise
        image = self.end()
        return Frame(image, tech, passes, getattr(self.backend, "name", str(self.backend)),
                     self.profile, list(self.warnings))


def render_frame(effect: Effect | str, profile: Any, *, technique: Technique | str | None = None,
                 backend: Any = "numpy", scene: Any = None, size: tuple[int, int] | None = None,
                 params: Mapping[str, Any] | None = None, policy: Any = "first",
                 strict: bool = False, diagnose: bool = False) -> Frame:
    """`render`, returning the Frame (image, technique, pass count, warnings) the command
    line reports; with `diagnose`, its `diagnostics` too (`effects.host.diagnostics`: what
    nothing sets, states that hide the mesh, a frame of one colour)."""
    runtime = Runtime(effect, profile, scene=scene, size=size, params=params, backend=backend,
                      strict=strict)
    frame = runtime.render(technique, policy)
    if diagnose:
        from effects.host.diagnostics import diagnose_frame
        frame.diagnostics = diagnose_frame(runtime, frame.technique, frame.image)
    return frame


def render(effect: Effect | str, profile: Any, *, technique: Technique | str | None = None,
           backend: Any = "numpy", scene: Any = None, size: tuple[int, int] | None = None,
           params: Mapping[str, Any] | None = None, policy: Any = "first",
           strict: bool = False) -> np.ndarray:
    """Render `effect` on the card `profile` (a CapsProfile or a name): H x W x 4 uint8 RGBA
    of an A8R8G8B8 target, row 0 at the top. See the module docstring for the steps;
    `scene` is a YAML path, a mapping or a Scene; an explicit `size` (w, h) wins over the
    scene's. `strict`: a texture nothing supplies is an error instead of a stand-in."""
    return render_frame(effect, profile, technique=technique, backend=backend, scene=scene,
                        size=size, params=params, policy=policy, strict=strict).image
