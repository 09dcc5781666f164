"""The scene a render draws: mesh, camera, light, clear values, size and parameter values.

A scene comes from YAML (every key optional: docs/guide/scene.md), from a mapping, or
from defaults. Every problem in a scene file is a `SceneError` at the line and column of the
offending value. Matrices follow Direct3D's conventions (row vectors, left-handed, clip z in
0..1), built as D3DXMatrixLookAtLH and D3DXMatrixPerspectiveFovLH build them.

Keys a reader of other hosts' scenes may not expect:
- `streams: {texcoord1: tangent, texcoord2: binormal}` — which mesh attribute feeds a vertex
  stream (see `effects.host.resources`); it overrides the effect's own `string VertexStreams`.
- `light: {direction: [x, y, z]}` — the direction the light travels (LIGHTDIRECTION); without
  it the light shines from its position towards the camera target.
- `world: [16 numbers]` (row-major, D3D row-vector convention) and `time: seconds`.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from typing import Any, Mapping

import numpy as np
import yaml

from effects.base import caches, untrusted, yaml_input
from effects.base.errors import Location, SceneError
from effects.host.scene_files import scene_for  # noqa: F401  (every command asks it here too)

Color = tuple[float, float, float, float]
MAX_SIZE = 8192

# ------------------------------------------------------------------------------------------------
# YAML with positions: mappings and sequences remember where each of their values starts.


class _Map(dict):
    """A YAML mapping that knows the location of itself and of each key's value."""

    start: Location
    marks: dict


class _Seq(list):
    """A YAML sequence that knows the location of itself and of each item."""

    start: Location
    marks: list


class _Loader(yaml_input.Loader):
    path = "<scene>"


def _mark(loader: _Loader, node: yaml.Node) -> Location:
    return Location(loader.path, node.start_mark.line + 1, node.start_mark.column + 1)


def _construct_map(loader: _Loader, node: yaml.MappingNode) -> _Map:
    loader.flatten_mapping(node)
    out = _Map()
    out.start, out.marks = _mark(loader, node), {}
    for key_node, value_node in node.value:
        key = loader.construct_object(key_node, deep=True)
        try:
            out[key] = loader.construct_object(value_node, deep=True)
        except TypeError:  # an unhashable key such as a list
            raise SceneError(f"a scene key must be a name, not {yaml_input.brief(key)}", _mark(loader, key_node)) from None
        out.marks[key] = _mark(loader, value_node)
    return out


def _construct_seq(loader: _Loader, node: yaml.SequenceNode) -> _Seq:
    out = _Seq(loader.construct_object(item, deep=True) for item in node.value)
    out.start, out.marks = _mark(loader, node), [_mark(loader, item) for item in node.value]
    return out


_Loader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _construct_map)
_Loader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_SEQUENCE_TAG, _construct_seq)


def where(container: Any, key: Any = None, default: Location | None = None) -> Location:
    """The location of `container[key]` (or of `container` itself) when it came from YAML."""
    fallback = default or Location("<scene>", 1, 1)
    if key is not None:
        marks = getattr(container, "marks", None)
        if isinstance(marks, dict) and key in marks:
            return marks[key]
        if isinstance(marks, list) and isinstance(key, int) and 0 <= key < len(marks):
            return marks[key]
    return getattr(container, "start", fallback)


# ------------------------------------------------------------------------------------------------
# Values


def parse_color(value: Any, at: Location) -> Color:
    """`[r, g, b]` / `[r, g, b, a]` floats or a D3DCOLOR string '0xAARRGGBB' (as r, g, b, a)."""
    if isinstance(value, str):
        text = value.strip().lower()
        if text.startswith("0x") and 3 <= len(text) <= 10:
            try:
                return d3dcolor(int(text, 16))
            except ValueError:
                pass
        raise SceneError(f"colour {yaml_input.brief(value)} is neither [r, g, b, a] nor '0xAARRGGBB'", at)
    if isinstance(value, (list, tuple)) and len(value) in (3, 4) and all(_is_number(c) for c in value):
        c = [float(x) for x in value]
        return (c[0], c[1], c[2], c[3] if len(c) == 4 else 1.0)
    raise SceneError(f"colour {yaml_input.brief(value)} is neither [r, g, b, a] nor '0xAARRGGBB'", at)


def d3dcolor(packed: int) -> Color:
    """A D3DCOLOR 0xAARRGGBB as (r, g, b, a) floats."""
    a, r, g, b = ((int(packed) >> s) & 0xFF for s in (24, 16, 8, 0))
    return (r / 255.0, g / 255.0, b / 255.0, a / 255.0)


def _is_number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _number(value: Any, what: str, at: Location) -> float:
    if not _is_number(value):
        raise SceneError(f"{what} needs a number, got {yaml_input.brief(value)}", at)
    return float(value)


def _vector(value: Any, sizes: tuple[int, ...], what: str, at: Location) -> np.ndarray:
    if not isinstance(value, (list, tuple)) or len(value) not in sizes or \
            not all(_is_number(c) for c in value):
        counts = " or ".join(str(n) for n in sizes)
        raise SceneError(f"{what} needs {counts} numbers, got {yaml_input.brief(value)}", at)
    return np.asarray(value, np.float64)


def _mapping(value: Any, what: str, keys: tuple[str, ...], at: Location) -> Mapping:
    if value is None:
        return {}
    if not isinstance(value, dict):
        raise SceneError(f"{what} takes a mapping of {', '.join(keys)}, got {yaml_input.brief(value)}", at)
    unknown = [k for k in value if k not in keys]
    if unknown:
        raise SceneError(f"unknown {what} key {yaml_input.brief(unknown[0])} (known: {', '.join(keys)})",
                         where(value, unknown[0], at))
    return value


# ------------------------------------------------------------------------------------------------
# D3DX-style matrices (row-vector convention: p' = p @ M)


def look_at_lh(eye, target, up) -> np.ndarray:
    """D3DXMatrixLookAtLH."""
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
    """D3DXMatrixPerspectiveFovLH (fov_y in radians)."""
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
    eye: tuple[float, float, float] = (0.0, 0.0, 3.0)    # the bundled effects assume +z
    target: tuple[float, float, float] = (0.0, 0.0, 0.0)
    up: tuple[float, float, float] = (0.0, 1.0, 0.0)
    fov: float = 45.0          # vertical, degrees
    near: float = 0.1
    far: float = 100.0

    def view(self) -> np.ndarray:
        """The view matrix (read-only: made once per camera placement, shared)."""
        return _view(tuple(map(float, self.eye)), tuple(map(float, self.target)),
                     tuple(map(float, self.up)))

    def projection(self, aspect: float) -> np.ndarray:
        """The projection matrix for `aspect` (read-only, shared like `view`)."""
        return _projection(float(self.fov), float(aspect), float(self.near), float(self.far))


# Every Runtime (and so every `effects.render()` call) takes its camera's matrices: made once
# per placement, as read-only arrays every caller shares (a caller that wants to change one
# makes its own; writing into the shared one raises).
@caches.memo("host.view_matrices", keys="eye, target, up", entry_bytes=256, max_bytes=256 * 256)
def _view(eye: tuple, target: tuple, up: tuple) -> np.ndarray:
    m = look_at_lh(eye, target, up)
    m.flags.writeable = False
    return m


@caches.memo("host.projection_matrices", keys="field of view, aspect, near, far", entry_bytes=256,
             max_bytes=256 * 256)
def _projection(fov: float, aspect: float, near: float, far: float) -> np.ndarray:
    m = perspective_fov_lh(math.radians(fov), aspect, near, far)
    m.flags.writeable = False
    return m


@dataclass
class Light:
    position: tuple[float, float, float] = (2.0, 2.0, 2.0)
    color: Color = (1.0, 1.0, 1.0, 1.0)
    direction: tuple[float, float, float] | None = None   # None: from position to the target


@dataclass
class InlineMesh:
    """Vertices written in the scene, in clip space (drawn with identity transforms).
    `attributes` maps a vertex key (position, normal, tangent, binormal, diffuse, specular,
    tex0..tex7) to an (N, k) float32 array; diffuse and specular are always present."""

    primitive: str
    attributes: dict[str, np.ndarray]
    location: Location

    @property
    def vertex_count(self) -> int:
        return len(self.attributes["position"])


@dataclass
class Scene:
    """Everything a render needs besides the effect and the card. `mesh` is a name (quad,
    sphere, cube, torus, teapot), a path to an .obj (relative to `base_dir`), or an
    `InlineMesh`. `locations` remembers where each scene value was written (key ->
    Location; params as 'params.NAME'), for errors found later."""

    mesh: str | InlineMesh = "sphere"
    size: tuple[int, int] = (256, 256)
    clear_color: Color = (0.0, 0.0, 0.0, 0.0)
    clear_depth: float = 1.0
    clear_stencil: int = 0
    camera: Camera = field(default_factory=Camera)
    light: Light = field(default_factory=Light)
    light_given: bool = False  # the scene says where the light is (else the effect's defaults stand)
    vertex_diffuse: Color = (1.0, 1.0, 1.0, 1.0)
    vertex_specular: Color = (0.0, 0.0, 0.0, 0.0)
    world: np.ndarray = field(default_factory=lambda: np.identity(4))
    time: float = 0.0
    params: dict[str, Any] = field(default_factory=dict)
    streams: dict[str, str] = field(default_factory=dict)
    base_dir: str = "."        # relative paths in the scene resolve against this folder
    path: str = "<scene>"
    locations: dict[str, Location] = field(default_factory=dict)

    @property
    def aspect(self) -> float:
        return self.size[0] / self.size[1]

    @property
    def untransformed(self) -> bool:
        """The quad and inline vertices are already in clip space."""
        return self.mesh == "quad" or isinstance(self.mesh, InlineMesh)

    def location(self, key: str) -> Location:
        return self.locations.get(key, Location(self.path, 1, 1))

    def matrices(self, size: tuple[int, int] | None = None) -> dict[str, np.ndarray]:
        """world, view and projection (for a frame of `size`, default the scene's); an
        untransformed mesh gets identities."""
        if self.untransformed:
            return {"world": np.identity(4), "view": np.identity(4), "projection": np.identity(4)}
        w, h = size or self.size
        return {"world": self.world, "view": self.camera.view(),
                "projection": self.camera.projection(w / h)}

    def light_direction(self) -> np.ndarray:
        """The unit direction the light travels (D3DLIGHT9.Direction)."""
        if self.light.direction is not None:
            d = np.asarray(self.light.direction, np.float64)
        else:
            d = np.asarray(self.camera.target, np.float64) - np.asarray(self.light.position)
        n = np.linalg.norm(d)
        return d / n if n else np.array([0.0, 0.0, 1.0])


SCENE_KEYS = ("mesh", "clear", "size", "camera", "light", "vertex", "params", "streams",
              "world", "time")
VERTEX_KEYS = ("position", "normal", "tangent", "binormal", "diffuse", "specular",
               *(f"tex{i}" for i in range(8)))
PRIMITIVES = ("strip", "list", "fan")


# ------------------------------------------------------------------------------------------------
# Loading


def load_scene(source: "str | os.PathLike[str] | Mapping[str, Any] | Scene | None") -> Scene:
    """A Scene from a YAML path, a mapping, a Scene (returned as is) or None (the defaults)."""
    if source is None:
        return Scene()
    if isinstance(source, Scene):
        return source
    if isinstance(source, (str, os.PathLike)):
        path = os.fspath(source)
        data = _read_yaml(path)
        base = os.path.dirname(os.path.abspath(path))
    elif isinstance(source, Mapping):
        path, data, base = "<scene>", dict(source), "."
    else:
        raise SceneError(f"a scene is a YAML path or a mapping, not {type(source).__name__}",
                         Location("<scene>", 1, 1))
    return scene_from_mapping(data, path=path, base_dir=base)


def _read_yaml(path: str) -> Any:
    text = untrusted.read_text(path, "scene file", SceneError, "yaml_bytes")
    loader, root = yaml_input.compose(text, path, SceneError, "scene file is not valid YAML",
                                      loader=_Loader)
    loader.path = path
    try:
        return None if root is None else loader.construct_document(root)
    except yaml.YAMLError as exc:
        raise yaml_input.located(exc, path, SceneError, "scene file is not valid YAML") from None
    finally:
        loader.dispose()


def scene_from_mapping(data: Any, *, path: str = "<scene>", base_dir: str = ".") -> Scene:
    """Build a Scene from parsed YAML (or a plain mapping), checking every key."""
    top = Location(path, 1, 1)
    if data is None:
        data = {}
    if not isinstance(data, dict):
        raise SceneError("a scene file is a mapping of keys such as mesh, camera, light", where(data, None, top))
    unknown = [k for k in data if k not in SCENE_KEYS]
    if unknown:
        raise SceneError(f"unknown scene key {yaml_input.brief(unknown[0])} (known: {', '.join(SCENE_KEYS)})",
                         where(data, unknown[0], top))
    scene = Scene(base_dir=base_dir, path=path)
    at = lambda key: where(data, key, top)  # noqa: E731
    scene.locations = {key: at(key) for key in data}

    if "mesh" in data:
        scene.mesh = _parse_mesh(data["mesh"], at("mesh"))
    if "size" in data:
        size = _vector(data["size"], (2,), "size", at("size"))
        if size.min() < 1 or size.max() > MAX_SIZE or np.any(size != np.round(size)):
            raise SceneError(f"size {yaml_input.brief(data['size'])} must be two whole numbers from 1 to {MAX_SIZE}", at("size"))
        scene.size = (int(size[0]), int(size[1]))
    clear = _mapping(data.get("clear"), "clear", ("color", "depth", "stencil"), at("clear"))
    if "color" in clear:
        scene.clear_color = parse_color(clear["color"], where(clear, "color", at("clear")))
    if "depth" in clear:
        depth = _number(clear["depth"], "clear depth", where(clear, "depth", at("clear")))
        if not 0.0 <= depth <= 1.0:
            raise SceneError(f"clear depth {depth} is outside 0..1", where(clear, "depth"))
        scene.clear_depth = depth
    if "stencil" in clear:
        stencil = clear["stencil"]
        if not isinstance(stencil, int) or isinstance(stencil, bool) or not 0 <= stencil <= 0xFF:
            raise SceneError(f"clear stencil must be an integer 0..255, got {yaml_input.brief(stencil)}",
                             where(clear, "stencil", at("clear")))
        scene.clear_stencil = stencil
    _parse_camera(scene, data.get("camera"), at("camera"))
    _parse_light(scene, data.get("light"), at("light"), "light" in data)
    vertex = _mapping(data.get("vertex"), "vertex", ("diffuse", "specular"), at("vertex"))
    if "diffuse" in vertex:
        scene.vertex_diffuse = parse_color(vertex["diffuse"], where(vertex, "diffuse", at("vertex")))
    if "specular" in vertex:
        scene.vertex_specular = parse_color(vertex["specular"], where(vertex, "specular", at("vertex")))
    if "world" in data:
        scene.world = _vector(data["world"], (16,), "world", at("world")).reshape(4, 4)
    if "time" in data:
        scene.time = _number(data["time"], "time", at("time"))
    params = data.get("params")
    if params is not None:
        if not isinstance(params, dict):
            raise SceneError("params is a mapping NAME: value", at("params"))
        for name, value in params.items():
            if not isinstance(name, str):
                raise SceneError(f"a parameter name must be text, not {yaml_input.brief(name)}", where(params, name, at("params")))
            scene.params[name] = value
            scene.locations[f"params.{name}"] = where(params, name, at("params"))
    streams = data.get("streams")
    if streams is not None:
        if not isinstance(streams, dict) or not all(isinstance(v, str) for v in streams.values()):
            raise SceneError("streams is a mapping STREAM: attribute, e.g. {texcoord1: tangent}",
                             at("streams"))
        for target, source in streams.items():
            scene.streams[str(target)] = source
            scene.locations[f"streams.{target}"] = where(streams, target, at("streams"))
    return scene


def _parse_camera(scene: Scene, value: Any, at: Location) -> None:
    camera = _mapping(value, "camera", ("eye", "target", "up", "fov", "near", "far"), at)
    c = Camera()
    for key in ("eye", "target", "up"):
        if key in camera:
            setattr(c, key, tuple(float(x) for x in _vector(camera[key], (3,), f"camera {key}",
                                                              where(camera, key, at))))
    for key in ("fov", "near", "far"):
        if key in camera:
            setattr(c, key, _number(camera[key], f"camera {key}", where(camera, key, at)))
    if not 0 < c.fov < 180:
        raise SceneError(f"camera fov {c.fov} must be between 0 and 180 degrees", where(camera, "fov", at))
    if not 0 < c.near < c.far:
        raise SceneError(f"camera near {c.near} and far {c.far} need 0 < near < far", where(camera, "near", at))
    forward = np.subtract(c.target, c.eye)
    if not np.linalg.norm(forward) or not np.linalg.norm(np.cross(c.up, forward)):
        raise SceneError("camera eye, target and up do not make a view (eye equals target, or up is "
                         "along the view direction)", at)
    scene.camera = c


def _parse_light(scene: Scene, value: Any, at: Location, given: bool) -> None:
    light = _mapping(value, "light", ("position", "color", "direction"), at)
    li = Light()
    if "position" in light:
        li.position = tuple(float(x) for x in _vector(light["position"], (3,), "light position",
                                                      where(light, "position", at)))
    if "color" in light:
        li.color = parse_color(light["color"], where(light, "color", at))
    if "direction" in light:
        d = _vector(light["direction"], (3,), "light direction", where(light, "direction", at))
        if not np.linalg.norm(d):
            raise SceneError("light direction must not be zero", where(light, "direction", at))
        li.direction = tuple(float(x) for x in d)
    scene.light, scene.light_given = li, given


def _parse_mesh(value: Any, at: Location) -> str | InlineMesh:
    if isinstance(value, str):
        from effects.assets.meshes import MESH_FILES, MESHES
        if value not in MESHES and not value.lower().endswith(MESH_FILES):
            raise SceneError(f"unknown mesh {yaml_input.brief(value)} (known: {', '.join(MESHES)}, a .obj "
                             "or .x file, or {primitive, vertices})", at)
        return value
    mesh = _mapping(value, "mesh", ("primitive", "vertices"), at)
    primitive = mesh.get("primitive", "list")
    if primitive not in PRIMITIVES:
        raise SceneError(f"mesh primitive must be one of {', '.join(PRIMITIVES)}, got {yaml_input.brief(primitive)}",
                         where(mesh, "primitive", at))
    vertices = mesh.get("vertices")
    vat = where(mesh, "vertices", at)
    if not isinstance(vertices, list) or len(vertices) < 3:
        raise SceneError("inline mesh vertices must be a list of at least 3 vertices", vat)
    if primitive == "list" and len(vertices) % 3:
        raise SceneError(f"a triangle list needs a multiple of 3 vertices, got {len(vertices)}", vat)
    columns: dict[str, list] = {}
    for i, vertex in enumerate(vertices):
        vloc = where(vertices, i, vat)
        vertex = _mapping(vertex, f"vertex {i}", VERTEX_KEYS, vloc)
        if "position" not in vertex:
            raise SceneError(f"vertex {i} has no position", vloc)
        for key in VERTEX_KEYS:
            kat = where(vertex, key, vloc)
            if key in ("diffuse", "specular"):
                default = "0xffffffff" if key == "diffuse" else "0x00000000"  # D3D9 defaults
                columns.setdefault(key, []).append(parse_color(vertex.get(key, default), kat))
                continue
            present = key in vertex
            if i and present != (key in columns):
                raise SceneError(f"vertex {i} {'has' if present else 'lacks'} {key}, unlike vertex 0: "
                                 "every vertex gives the same keys", kat)
            if present:
                sizes = {"position": (3, 4), "normal": (3,), "tangent": (3,), "binormal": (3,)}.get(key, (1, 2, 3, 4))
                v = _vector(vertex[key], sizes, f"vertex {i} {key}", kat)
                if i and len(v) != len(columns[key][0]):
                    raise SceneError(f"vertex {i} {key} has {len(v)} components, vertex 0 has "
                                     f"{len(columns[key][0])}", kat)
                columns.setdefault(key, []).append(v)
    attributes = {k: np.asarray(v, np.float32) for k, v in columns.items()}
    return InlineMesh(primitive, attributes, at)


def set_mesh(scene: Scene, value: str, at: Location) -> Scene:
    """`scene` drawing the mesh `value` (a built-in name or a mesh file, relative to the
    current folder) instead of its own: `effects render --mesh`. Checked as the scene's
    `mesh` key is, the error at `at`."""
    if value not in _builtin_meshes():
        value = os.path.abspath(value)
    scene.mesh = _parse_mesh(value, at)
    scene.locations["mesh"] = at
    return scene


def _builtin_meshes() -> tuple[str, ...]:
    from effects.assets.meshes import MESHES
    return tuple(MESHES)
