"""The scene a render draws: mesh, camera, light, clear values, size and parameter values.

A scene comes from YAML (every key optional, DESIGN.md gives the shape), from a dict, or from
defaults. Matrices follow Direct3D's conventions (row vectors, left-handed, clip z in 0..1),
built as D3DXMatrixLookAtLH and D3DXMatrixPerspectiveFovLH build them.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from typing import Any, Mapping

import numpy as np
import yaml

from .errors import Location, SceneError

Color = tuple[float, float, float, float]


def parse_color(value: Any, where: Location) -> Color:
    """`[r, g, b, a]` floats (a optional) or a D3DCOLOR string '0xAARRGGBB'."""
    if isinstance(value, str):
        text = value.strip().lower()
        try:
            packed = int(text, 16) if text.startswith("0x") else int(text)
        except ValueError:
            raise SceneError(f"colour '{value}' is neither [r, g, b, a] nor '0xAARRGGBB'", where) from None
        a, r, g, b = ((packed >> s) & 0xFF for s in (24, 16, 8, 0))
        return (r / 255.0, g / 255.0, b / 255.0, a / 255.0)
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        v = float(value)
        return (v, v, v, 1.0)
    if isinstance(value, (list, tuple)) and len(value) in (3, 4) and all(
            isinstance(c, (int, float)) and not isinstance(c, bool) for c in value):
        c = [float(x) for x in value]
        return (c[0], c[1], c[2], c[3] if len(c) == 4 else 1.0)
    raise SceneError(f"colour {value!r} is neither [r, g, b, a] nor '0xAARRGGBB'", where)


def _vector(value: Any, n: int, what: str, where: Location) -> np.ndarray:
    try:
        v = np.asarray(value, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        v = np.zeros(0)
    if v.size != n or not np.all(np.isfinite(v)):
        raise SceneError(f"{what} needs {n} numbers, got {value!r}", where)
    return v


# ------------------------------------------------------------------------------------------------
# D3DX-style matrices (row-vector convention: p' = p @ M)

def look_at_lh(eye, target, up) -> np.ndarray:
    eye, target, up = (np.asarray(v, np.float64) for v in (eye, target, up))
    z = target - eye
    z /= np.linalg.norm(z)
    x = np.cross(up, z)
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    m = np.identity(4)
    m[:3, 0], m[:3, 1], m[:3, 2] = x, y, z
    m[3, :3] = (-x @ eye, -y @ eye, -z @ eye)
    return m


def perspective_fov_lh(fov_y: float, aspect: float, near: float, far: float) -> np.ndarray:
    y_scale = 1.0 / math.tan(fov_y / 2)
    m = np.zeros((4, 4))
    m[0, 0] = y_scale / aspect
    m[1, 1] = y_scale
    m[2, 2] = far / (far - near)
    m[2, 3] = 1.0
    m[3, 2] = -near * far / (far - near)
    return m


@dataclass
class Camera:
    eye: tuple[float, float, float] = (0.0, 0.0, -3.0)
    target: tuple[float, float, float] = (0.0, 0.0, 0.0)
    up: tuple[float, float, float] = (0.0, 1.0, 0.0)
    fov: float = 45.0          # vertical, degrees
    near: float = 0.1
    far: float = 100.0

    def view(self) -> np.ndarray:
        return look_at_lh(self.eye, self.target, self.up)

    def projection(self, aspect: float) -> np.ndarray:
        return perspective_fov_lh(math.radians(self.fov), aspect, self.near, self.far)


@dataclass
class Light:
    position: tuple[float, float, float] = (2.0, 2.0, -2.0)
    color: Color = (1.0, 1.0, 1.0, 1.0)


@dataclass
class Scene:
    """Everything a render needs besides the effect and the card. `mesh` is a name
    (quad, sphere, cube, torus, teapot), a path to an .obj, or an inline dict of vertices."""

    mesh: Any = "sphere"
    size: tuple[int, int] = (256, 256)
    clear_color: Color = (0.0, 0.0, 0.0, 0.0)
    clear_depth: float = 1.0
    clear_stencil: int = 0
    camera: Camera = field(default_factory=Camera)
    light: Light = field(default_factory=Light)
    vertex_diffuse: Color = (1.0, 1.0, 1.0, 1.0)
    vertex_specular: Color = (0.0, 0.0, 0.0, 0.0)
    world: np.ndarray = field(default_factory=lambda: np.identity(4))
    time: float = 0.0
    params: dict[str, Any] = field(default_factory=dict)
    base_dir: str = "."        # relative paths in the scene resolve against this folder

    @property
    def aspect(self) -> float:
        return self.size[0] / self.size[1]

    def matrices(self) -> dict[str, np.ndarray]:
        """world, view and projection; an untransformed mesh (the quad, inline clip-space
        vertices) gets identities."""
        if self.untransformed:
            return {"world": np.identity(4), "view": np.identity(4), "projection": np.identity(4)}
        return {"world": self.world, "view": self.camera.view(),
                "projection": self.camera.projection(self.aspect)}

    @property
    def untransformed(self) -> bool:
        return self.mesh == "quad" or isinstance(self.mesh, dict)


_SCENE_KEYS = {"mesh", "clear", "size", "camera", "light", "vertex", "params", "world", "time"}


def load_scene(source: str | Mapping[str, Any] | None) -> Scene:
    """A Scene from a YAML path, a mapping, or None (the defaults)."""
    if source is None:
        return Scene()
    if isinstance(source, Scene):
        return source
    path = "<scene>"
    base = "."
    if isinstance(source, (str, os.PathLike)):
        path = os.fspath(source)
        base = os.path.dirname(os.path.abspath(path))
        try:
            with open(path, encoding="utf-8") as f:
                data = yaml.safe_load(f)
        except OSError as exc:
            raise SceneError(f"cannot read scene file: {exc.strerror}", Location(path, 1, 1)) from None
        except yaml.YAMLError as exc:
            mark = getattr(exc, "problem_mark", None)
            line, col = (mark.line + 1, mark.column + 1) if mark else (1, 1)
            raise SceneError(f"scene file is not valid YAML: {getattr(exc, 'problem', exc)}",
                             Location(path, line, col)) from None
    else:
        data = dict(source)
    data = data or {}
    where = Location(path, 1, 1)
    if not isinstance(data, dict):
        raise SceneError("a scene file is a mapping of keys such as mesh, camera, light", where)
    unknown = set(data) - _SCENE_KEYS
    if unknown:
        raise SceneError(f"unknown scene key(s): {', '.join(sorted(unknown))} "
                         f"(known: {', '.join(sorted(_SCENE_KEYS))})", where)
    scene = Scene(base_dir=base)
    if "mesh" in data:
        scene.mesh = data["mesh"]
    if "size" in data:
        size = _vector(data["size"], 2, "size", where)
        if size.min() < 1 or size.max() > 8192:
            raise SceneError(f"size {data['size']!r} must be two numbers from 1 to 8192", where)
        scene.size = (int(size[0]), int(size[1]))
    clear = data.get("clear") or {}
    if not isinstance(clear, dict):
        raise SceneError("clear takes {color, depth, stencil}", where)
    if "color" in clear:
        scene.clear_color = parse_color(clear["color"], where)
    if "depth" in clear:
        scene.clear_depth = float(clear["depth"])
    if "stencil" in clear:
        scene.clear_stencil = int(clear["stencil"])
    camera = data.get("camera") or {}
    if camera:
        c = Camera()
        for key in ("eye", "target", "up"):
            if key in camera:
                setattr(c, key, tuple(_vector(camera[key], 3, f"camera {key}", where)))
        for key in ("fov", "near", "far"):
            if key in camera:
                setattr(c, key, float(camera[key]))
        scene.camera = c
    light = data.get("light") or {}
    if light:
        scene.light = Light(tuple(_vector(light.get("position", Light.position), 3, "light position", where)),
                            parse_color(light.get("color", [1, 1, 1, 1]), where))
    vertex = data.get("vertex") or {}
    if "diffuse" in vertex:
        scene.vertex_diffuse = parse_color(vertex["diffuse"], where)
    if "specular" in vertex:
        scene.vertex_specular = parse_color(vertex["specular"], where)
    if "world" in data:
        scene.world = _vector(data["world"], 16, "world", where).reshape(4, 4)
    if "time" in data:
        scene.time = float(data["time"])
    params = data.get("params") or {}
    if not isinstance(params, dict):
        raise SceneError("params is a mapping NAME: value", where)
    scene.params = dict(params)
    return scene
