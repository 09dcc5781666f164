"""What the viewer shows, apart from any window: card, technique, view, mesh, camera, light.

Kept free of GL and imgui so the keys' effects are plain method calls (tested directly), and
so the render thread and the reload worker agree on one `BuildSettings` snapshot.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from effects.viewer.reload import BuildSettings
from effects.host.scene import Camera, Light, Scene

if TYPE_CHECKING:  # pragma: no cover
    from effects.d3d9.caps import CapsProfile

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

    def advance(self, seconds: float) -> bool:
        if self.animate:
            self.angle = (self.angle + self.speed * seconds) % (2 * math.pi)
        return self.animate


@dataclass
class ViewerState:
    """The user's choices. `generation` counts changes that need the effect drawn again;
    `selection_generation` those that need a new selection (card, forced technique)."""

    cards: list[str]
    card_index: int = 0
    technique: str | None = None          # forced technique name; None = the card's choice
    view: str = "gl"
    mesh: str = "sphere"
    orbit: Orbit = field(default_factory=Orbit)
    light: LightPath = field(default_factory=LightPath)
    show_listing: bool = False            # the listing window over the picture (key C)
    generation: int = 0
    selection_generation: int = 0
    _profiles: dict[str, "CapsProfile"] = field(default_factory=dict)

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

    def set_mesh(self, mesh: str) -> None:
        if mesh != self.mesh:
            self.mesh = mesh
            self._selection_changed()   # streams are checked (and built) off the render thread

    def cycle_mesh(self) -> None:
        i = MESHES.index(self.mesh) if self.mesh in MESHES else -1
        self.set_mesh(MESHES[(i + 1) % len(MESHES)])

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
        scene = Scene(mesh=self.mesh, size=size, clear_color=(0.08, 0.08, 0.1, 1.0))
        scene.camera = Camera(eye=self.orbit.eye(), target=self.orbit.target)
        scene.light = Light(self.light.position(), (1.0, 1.0, 1.0, 1.0))
        scene.light_given = True
        return scene

    def build_settings(self, size: tuple[int, int] = (256, 256)) -> BuildSettings:
        return BuildSettings(self.profile, self.technique, "first", self.scene(size),
                             self.scene_key(size))

    def scene_key(self, size: tuple[int, int]) -> tuple:
        """Equal keys, equal scenes: what a prepared Runtime may be reused for."""
        return (self.mesh, tuple(size), round(self.orbit.yaw, 9), round(self.orbit.pitch, 9),
                round(self.orbit.distance, 9), round(self.light.angle, 9))

    def camera_key(self) -> tuple:
        """Everything a picture depends on besides the effect (for the reference view's cache)."""
        return (self.card, self.technique, self.mesh, round(self.orbit.yaw, 6),
                round(self.orbit.pitch, 6), round(self.orbit.distance, 6), round(self.light.angle, 6))
