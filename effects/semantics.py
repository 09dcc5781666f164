"""Parameter values the scene supplies, bound by semantic (as DXSAS-aware hosts did).

`float4x4 WorldViewProj : WORLDVIEWPROJECTION;` receives world·view·projection of the scene,
`: WORLDINVERSETRANSPOSE` its inverse transpose, and so on. DX8 files carry no semantics; for
them a short table of the parameter names the DirectX 8 SDK samples used stands in (documented
below), and anything else comes from the scene's `params` or `--set`.
Matrices are stored in Direct3D's row-vector convention (p' = p · M), exactly what the
application would pass to SetMatrix.
"""
from __future__ import annotations

from typing import Any, Callable

import numpy as np

from .model import Effect, Parameter
from .scene import Scene

_BASE = ("WORLDVIEWPROJECTION", "WORLDVIEW", "VIEWPROJECTION", "WORLD", "VIEW", "PROJECTION")

# Names, not semantics, that DirectX 8-era effects (the SDK samples, the seeds' BRDF effect)
# used for what the application set every frame.
DX8_NAME_SEMANTICS = {
    "mwld": "WORLD", "mworld": "WORLD", "mview": "VIEW", "mproj": "PROJECTION",
    "mtot": "WORLDVIEWPROJECTION", "mwvp": "WORLDVIEWPROJECTION", "mworldviewproj": "WORLDVIEWPROJECTION",
    "lhtr": "LIGHTDIRECTION", "vlightdir": "LIGHTDIRECTION", "veye": "CAMERAPOSITION",
}


def _matrix_for(semantic: str, m: dict[str, np.ndarray]) -> np.ndarray | None:
    key = semantic.upper()
    for base in _BASE:
        if key.startswith(base):
            rest = key[len(base):]
            if rest not in ("", "INVERSE", "TRANSPOSE", "INVERSETRANSPOSE"):
                continue
            value = {"WORLD": m["world"], "VIEW": m["view"], "PROJECTION": m["projection"],
                     "WORLDVIEW": m["world"] @ m["view"],
                     "VIEWPROJECTION": m["view"] @ m["projection"],
                     "WORLDVIEWPROJECTION": m["world"] @ m["view"] @ m["projection"]}[base]
            if "INVERSE" in rest:
                value = np.linalg.inv(value)
            if "TRANSPOSE" in rest:
                value = value.T
            return value
    return None


def _fit(value: np.ndarray, param: Parameter) -> np.ndarray:
    """Shape a vector to the parameter's components (float3 takes xyz, float4 xyzw)."""
    n = param.type.components
    v = np.zeros(max(n, 4), np.float32)
    flat = np.asarray(value, np.float32).reshape(-1)
    v[:flat.size] = flat[:v.size]
    return v[:n].reshape(param.type.rows, param.type.cols) if param.type.rows > 1 else v[:n]


def scene_values(scene: Scene) -> tuple[dict[str, Callable[[Parameter], Any]], dict[str, np.ndarray]]:
    """Semantic (upper case) → function giving that parameter's value in this scene, and the
    scene's world/view/projection matrices."""
    m = scene.matrices()
    eye = np.array([*scene.camera.eye, 1.0])
    light = np.array([*scene.light.position, 1.0])
    direction = np.array(scene.camera.target, np.float64) - light[:3]
    direction = direction / (np.linalg.norm(direction) or 1.0)
    values: dict[str, Callable[[Parameter], Any]] = {
        "CAMERAPOSITION": lambda p: _fit(eye, p),
        "VIEWPOSITION": lambda p: _fit(eye, p),
        "EYEPOSITION": lambda p: _fit(eye, p),
        "LIGHTPOSITION": lambda p: _fit(light, p),
        "LIGHT0POSITION": lambda p: _fit(light, p),
        "LIGHTDIRECTION": lambda p: _fit(np.array([*direction, 0.0]), p),
        "LIGHTCOLOR": lambda p: _fit(np.array(scene.light.color), p),
        "LIGHTDIFFUSE": lambda p: _fit(np.array(scene.light.color), p),
        "TIME": lambda p: np.float32(scene.time),
        "VIEWPORTPIXELSIZE": lambda p: _fit(np.array(scene.size, np.float32), p),
    }
    return values, m


def bind_scene(effect: Effect, scene: Scene) -> dict[str, Any]:
    """Values for every parameter the scene supplies: by semantic, or for DX8 files by the
    conventional names above. Returns name → value (matrices as float32 4x4)."""
    values, m = scene_values(scene)
    bound: dict[str, Any] = {}
    for param in effect.parameters:
        semantic = (param.semantic or DX8_NAME_SEMANTICS.get(param.name.lower(), "")).upper()
        if not semantic:
            continue
        matrix = _matrix_for(semantic, m)
        if matrix is not None and param.type.rows == 4 and param.type.cols == 4:
            bound[param.name] = matrix.astype(np.float32)
        elif semantic in values and param.type.is_numeric:
            bound[param.name] = values[semantic](param)
    return bound
