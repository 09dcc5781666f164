"""What the viewer shows, apart from any window: card, technique, view, mesh, camera, light,
the user's parameter edits and the clock TIME reads (`effects.viewer.params`), over the
effect's scene (NAME.yaml beside NAME.fx, or --scene: `effects.host.scene.scene_for`).

Kept free of GL and imgui so the keys' effects are plain method calls (tested directly), and
so the render thread and the reload worker agree on one `BuildSettings` snapshot.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from effects.base.errors import Location
from effects.viewer.params import Clock, Tweakable, Tweaks, tweakables
from effects.viewer.reload import BuildSettings
from effects.host.scene import Camera, Light, Scene

if TYPE_CHECKING:  # pragma: no cover
    from effects.d3d9.caps import CapsProfile
    from effects.model import Effect

MESHES = ("sphere", "torus", "cube", "teapot", "quad")
VIEWS = ("gl", "reference", "difference")
VIEW_TITLES = {"gl": "GL back end", "reference": "NumPy reference",
               "difference": "|GL - reference| x {scale}"}
DIFFERENCE_SCALE = 8      # differences of a few LSB become visible


@dataclass
class Orbit:
    """A camera circling `target`: yaw 0 looks from +z, as the scene's default eye (0, 0, 3)
    does, so the viewer starts on the side `effects render` and the thumbnails show (an
    effect that fixes its light in the file is lit alike in both)."""

    yaw: float = 0.0          # radians, around +y
    pitch: float = 0.35       # radians above the horizon
    distance: float = 3.0
    target: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def eye(self) -> tuple[float, float, float]:
        c = math.cos(self.pitch)
        return (self.target[0] - self.distance * c * math.sin(self.yaw),
                self.target[1] + self.distance * math.sin(self.pitch),
                self.target[2] + self.distance * c * math.cos(self.yaw))

    def drag(self, dx: float, dy: float) -> None:
        """Mouse drag in pixels: 0.01 rad per pixel; the pitch stops short of the poles."""
        self.yaw -= dx * 0.01
        self.pitch = max(-1.5, min(1.5, self.pitch + dy * 0.01))

    def zoom(self, steps: float) -> None:
        self.distance = max(1.2, min(20.0, self.distance * 0.9 ** steps))

    @classmethod
    def looking(cls, camera: Camera) -> "Orbit":
        """The orbit whose eye is a scene camera's (its eye around its target, y up)."""
        offset = [e - t for e, t in zip(camera.eye, camera.target)]
        distance = math.sqrt(sum(c * c for c in offset)) or 3.0
        pitch = max(-1.5, min(1.5, math.asin(max(-1.0, min(1.0, offset[1] / distance)))))
        return cls(math.atan2(-offset[0], offset[2]), pitch, distance,
                   tuple(float(c) for c in camera.target))


@dataclass
class LightPath:
    """A point light circling the y axis; the viewer animates `angle` or the user drags it.
    It starts above, right and in front, where the scene's default light (2, 2, 2) is."""

    angle: float = math.radians(-45.0)
    height: float = 2.0
    radius: float = 2.8
    animate: bool = False
    speed: float = 1.0        # radians per second

    def position(self) -> tuple[float, float, float]:
        return (-self.radius * math.sin(self.angle), self.height, self.radius * math.cos(self.angle))

    @classmethod
    def through(cls, position: tuple[float, float, float]) -> "LightPath":
        """The path through a scene light's position."""
        x, y, z = position
        return cls(math.atan2(-x, z), float(y), math.hypot(x, z) or 2.8)

    def advance(self, seconds: float) -> bool:
        if self.animate:
            self.angle = (self.angle + self.speed * seconds) % (2 * math.pi)
        return self.animate


def param_values(effect: "Effect", assignments: dict[str, str],
                 edits: dict[tuple, Any]) -> dict[str, Any]:
    """--set values for the names `effect` has, then the edits whose name and type fit it."""
    names = {p.name for p in effect.parameters}
    values: dict[str, Any] = {k: v for k, v in assignments.items() if k in names}
    values.update(Tweaks(edits).for_effect(tweakables(effect)))
    return values


@dataclass
class ViewerState:
    """The user's choices. `generation` counts changes that need the effect drawn again;
    `selection_generation` those that need a new selection (card, forced technique)."""

    cards: list[str]
    card_index: int = 0
    technique: str | None = None          # forced technique name; None = the card's choice
    view: str = "gl"
    # a built-in name or a mesh file; None: the scene's, else the effect's XFile, else the sphere
    mesh: str | None = None
    orbit: Orbit = field(default_factory=Orbit)
    light: LightPath = field(default_factory=LightPath)
    show_listing: bool = False            # the listing window over the picture (key C)
    generation: int = 0
    selection_generation: int = 0
    base_scene: Scene = field(default_factory=Scene)  # the effect's scene (--scene, NAME.yaml)
    assignments: dict[str, str] = field(default_factory=dict)   # --set NAME=VALUE
    tweaks: Tweaks = field(default_factory=Tweaks)
    clock: Clock = field(default_factory=Clock)
    _profiles: dict[str, "CapsProfile"] = field(default_factory=dict)

    # the mesh is the scene file's (not --mesh nor the M key): a scene reload may change it
    mesh_from_scene: bool = False
    scene_generation: int = 0             # counts scene files taken (reloads included)

    def start_from_scene(self, scene: Scene) -> None:
        """Take the effect's scene: its mesh (unless one was chosen), camera, light, time."""
        self.base_scene = scene
        if self.mesh is None and "mesh" in scene.locations:
            self.mesh = scene.mesh if isinstance(scene.mesh, str) else None
            self.mesh_from_scene = True
        if "camera" in scene.locations:
            self.orbit = Orbit.looking(scene.camera)
        if scene.light_given:
            self.light = LightPath.through(scene.light.position)
        if not self.clock.fixed:
            self.clock.seconds = scene.time

    def reload_scene(self, scene: Scene) -> tuple:
        """Take an edited scene file: what it says now is drawn. Its mesh unless the user chose
        one; its camera, light and time where the file changed them (the orbit the user
        dragged to stays while the file's camera is as it was); everything else (params,
        clear colour, ...) is read from `base_scene` by `scene()`. A new build follows: the
        mesh's streams and the parameters are prepared off the render thread. Returns what it
        replaced, for `restore_scene` (a scene the effect cannot be drawn in)."""
        before = (self.base_scene, self.mesh, self.mesh_from_scene, self.orbit, self.light,
                  self.clock.seconds, self.scene_generation)
        old, self.base_scene = self.base_scene, scene
        if self.mesh is None or self.mesh_from_scene:
            given = "mesh" in scene.locations and isinstance(scene.mesh, str)
            self.mesh = scene.mesh if given else None     # type: ignore[assignment]
            self.mesh_from_scene = given
        if (scene.camera, "camera" in scene.locations) != (old.camera, "camera" in old.locations):
            self.orbit = Orbit.looking(scene.camera)
        if (scene.light.position, scene.light_given) != (old.light.position, old.light_given):
            animate = self.light.animate
            self.light = LightPath.through(scene.light.position) if scene.light_given else LightPath()
            self.light.animate = animate
        if scene.time != old.time and not self.clock.fixed:
            self.clock.seconds = scene.time
        self.scene_generation += 1
        self._selection_changed()
        return before

    def restore_scene(self, before: tuple) -> None:
        """Back to the scene `reload_scene` replaced (its scene key too: what was prepared for
        it is drawn again as it was)."""
        (self.base_scene, self.mesh, self.mesh_from_scene, self.orbit, self.light,
         self.clock.seconds, self.scene_generation) = before
        self.changed()

    # -- card
    @property
    def card(self) -> str:
        return self.cards[self.card_index]

    @property
    def profile(self) -> "CapsProfile":
        from effects.d3d9.caps import load_profile
        if self.card not in self._profiles:
            self._profiles[self.card] = load_profile(self.card)
        return self._profiles[self.card]

    def set_card(self, index: int) -> None:
        index %= len(self.cards)
        if index != self.card_index:
            self.card_index = index
            self._selection_changed()

    def next_card(self, step: int = 1) -> None:
        self.set_card(self.card_index + step)

    # -- technique
    def force_technique(self, name: str | None) -> None:
        if name != self.technique:
            self.technique = name
            self._selection_changed()

    def cycle_technique(self, names: list[str], step: int = 1) -> None:
        """Step through (card's choice, each technique in file order)."""
        options: list[str | None] = [None, *names]
        i = options.index(self.technique) if self.technique in options else 0
        self.force_technique(options[(i + step) % len(options)])

    # -- view, mesh, camera, light
    def set_view(self, view: str) -> None:
        if view not in VIEWS:
            raise ValueError(f"unknown view {view!r}")
        if view != self.view:
            self.view = view
            self.changed()

    def cycle_view(self) -> None:
        self.set_view(VIEWS[(VIEWS.index(self.view) + 1) % len(VIEWS)])

    def set_mesh(self, mesh: str | None) -> None:
        if mesh != self.mesh:
            self.mesh = mesh
            self.mesh_from_scene = False
            self._selection_changed()   # streams are checked (and built) off the render thread

    def cycle_mesh(self) -> None:
        i = MESHES.index(self.mesh) if self.mesh in MESHES else -1
        self.set_mesh(MESHES[(i + 1) % len(MESHES)])

    # -- parameters and time
    def set_param(self, item: Tweakable, value: Any) -> None:
        """A widget's new value (the panel calls this; so do tests and benchmarks)."""
        before = self.tweaks.generation
        self.tweaks.set(item, value)
        if self.tweaks.generation != before:
            self.changed()

    def reset_param(self, item: Tweakable) -> None:
        before = self.tweaks.generation
        self.tweaks.reset(item)
        if self.tweaks.generation != before:
            self.changed()

    def param_values(self, effect: "Effect") -> dict[str, Any]:
        """What the effect's parameters are set to besides the scene: --set values (for the
        names this effect has), then the panel's edits that fit it."""
        return param_values(effect, self.assignments, self.tweaks.values)

    def toggle_clock(self) -> None:
        self.clock.toggle()

    def step_clock(self, frames: int = 1) -> None:
        self.clock.step(frames)
        self.changed()

    def toggle_listing(self) -> None:
        # the listing covers the picture; nothing is drawn again (the panel is drawn each frame)
        self.show_listing = not self.show_listing

    def changed(self) -> None:
        self.generation += 1

    def _selection_changed(self) -> None:
        self.selection_generation += 1
        self.changed()

    # -- what the renderers and the reload worker use
    def scene(self, size: tuple[int, int]) -> Scene:
        """The scene drawn: the effect's scene with the viewer's mesh, camera, light and time
        (its clear colour a dark grey unless it gives one). A mesh left to the scene keeps
        its place in the scene file; with none anywhere the scene has no `mesh` location, and
        the host draws the effect's own (EffectEdit's XFile) or the sphere."""
        base = self.base_scene
        locations = dict(base.locations)
        mesh: Any = base.mesh
        if self.mesh is not None:
            mesh = self.mesh
            if "mesh" not in locations or mesh != base.mesh:
                locations["mesh"] = Location("<the viewer's mesh>", 1, 1)
        camera = base.camera
        camera = Camera(eye=self.orbit.eye(), target=self.orbit.target, fov=camera.fov,
                        near=camera.near, far=camera.far)
        light = Light(self.light.position(), base.light.color if base.light_given
                      else (1.0, 1.0, 1.0, 1.0), base.light.direction)
        clear = base.clear_color if "clear" in base.locations else (0.08, 0.08, 0.1, 1.0)
        return dataclasses.replace(base, mesh=mesh, size=size, camera=camera, light=light,
                                   light_given=True, clear_color=clear, time=self.clock.seconds,
                                   locations=locations, params=dict(base.params))

    def build_settings(self, size: tuple[int, int] = (256, 256)) -> BuildSettings:
        """What the reload worker builds with (read on its thread: the edits are copied, and
        applied to the effect it loads as they fit it)."""
        assignments, edits = dict(self.assignments), dict(self.tweaks.values)
        return BuildSettings(self.profile, self.technique, "first", self.scene(size),
                             self.scene_key(size),
                             lambda effect: param_values(effect, assignments, edits))

    def scene_key(self, size: tuple[int, int]) -> tuple:
        """Equal keys, equal scenes: what a prepared Runtime may be reused for (the clock is
        not in it: a runtime follows the time by `Runtime.set_time`)."""
        return (str(self.mesh), tuple(size), round(self.orbit.yaw, 9), round(self.orbit.pitch, 9),
                round(self.orbit.distance, 9), round(self.light.angle, 9), self.scene_generation)

    def camera_key(self) -> tuple:
        """Everything a picture depends on besides the effect (for the reference view's cache)."""
        return (self.card, self.technique, str(self.mesh), round(self.orbit.yaw, 6),
                round(self.orbit.pitch, 6), round(self.orbit.distance, 6), round(self.light.angle, 6),
                self.tweaks.generation, round(self.clock.seconds, 6), self.scene_generation)
