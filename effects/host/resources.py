"""What a render loads: textures for the effect's texture parameters, and vertex streams.

Texture parameters, first source that applies wins:
  1. a value the user gives (`render(params=)`, `--set Name=path` relative to the current
     folder, the scene's `params` relative to the scene file), a path or a `Texture`;
  2. `string ResourceName = "file"`, relative to the effect file;
  3. `string Procedural = "generator:argument"` (`effects.assets.textures.procedural`; an `int Width`
     annotation gives the size of generators that take one). The argument may name a numeric
     parameter as `<Name>`, optionally scaled, `k*<Name>` or `<Name>*k`: its current value is
     written there, and a runtime makes the texture again when that parameter changes (a table
     of pow(v, SpecularPower) follows SpecularPower, as a host refilling it with
     D3DXFillTexture on SetValue would);
  4. nothing: the parameter stays unbound; the runtime draws a stand-in of its kind
     (`stand_in_texture`) with a warning, or fails when strict. A `ResourceName` file that is
     missing raises `MissingTexture`, which the runtime treats the same way.
The kind comes from the parameter's type (`textureCUBE`) or its `string Type` annotation
("2D", "CUBE", "3D"/"VOLUME"); a file of another kind is an error. An untyped DX8 `texture`
takes the kind of what was loaded. Loaded files are cached by (path, modification time), so a
viewer reload does not read unchanged images again.

Vertex streams from a mesh (names as in `effects.program.backend`): position, normal, tangent,
binormal; color0 = the scene's vertex diffuse (default opaque white) and color1 = its vertex
specular (default 0), as a D3D9 vertex without those components reads; texcoord0..7 = the
mesh's uv. Which attribute feeds a stream can be changed:
  - by the effect, with a top-level `string VertexStreams = "texcoord1=tangent"` parameter
    (comma- or space-separated `stream=attribute` pairs): the part of the application that
    built the vertex buffer for a DX8 vertex shader (fxfiles/brdf.fx reads its tangent from
    v8, the TEXCOORD1 register of a DX8 declaration);
  - by the scene, with `streams: {texcoord1: tangent}`, which wins over the effect.
Attributes: position, normal, tangent, binormal, uv (texture coordinates), diffuse,
specular, uv_occlusion (u, v and the vertex's ambient occlusion, the layout of the chapter's
hemisphere shaders, which read the occlusion from v7.z; cast over the mesh on first use by
`effects.assets.occlusion`, 0 for inline vertices), and for inline scene vertices also tex0..tex7.
"""
from __future__ import annotations


import os
import re
from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from effects.base.errors import Location, SceneError
from effects.assets.meshes import MESH_FILES, Mesh, by_name
from effects.assets.occlusion import vertex_occlusion
from effects.assets import brdf as _brdf  # noqa: F401  (registers the brdf_factor procedural)
from effects.model import Effect, Parameter
from effects.host.scene import InlineMesh, Scene
from effects.base import caches, limits
from effects.base.lru import DEFAULT_TEXTURE_BYTES, ByteLRU, texture_bytes
from effects.assets.texture_files import load_texture
from effects.assets.textures import PROCEDURAL, procedural
from effects.program.texture import Texture
from effects.base import untrusted
from effects.base.untrusted import confine

STREAM_NAMES = ("position", "normal", "tangent", "binormal", "color0", "color1",
                "blendweight", "blendindices", "psize",   # DX8 v1, v2, v4 without dcl
                *(f"texcoord{i}" for i in range(8)))
ATTRIBUTES = ("position", "normal", "tangent", "binormal", "uv", "diffuse", "specular",
              "uv_occlusion", *(f"tex{i}" for i in range(8)))


# ------------------------------------------------------------------------------------------------
# Textures


def declared_kind(param: Parameter) -> str | None:
    """'2d', 'cube', '3d' or '1d' as the parameter's type or `Type` annotation says; None
    for an untyped `texture` without annotation."""
    return param.declared_texture_kind


def effect_dir(effect: Effect) -> str:
    """The folder the effect's relative paths resolve against (the cwd for text effects)."""
    if effect.path and os.path.isfile(effect.path):
        return os.path.dirname(os.path.abspath(effect.path))
    return os.getcwd()


class MissingTexture(SceneError):
    """A texture file an annotation names is not there (a host may draw a stand-in)."""


# The stand-in a host draws for a texture nobody supplies, by kind (procedural generators).
STAND_INS = {"2d": "checker", "1d": "checker", "cube": "sky_cube", "3d": "noise_volume"}


def stand_in_texture(kind: str, normal: bool = False) -> Texture:
    """A checker for 2D (and 1D), a sky for CUBE, noise for 3D; for a 2D texture that feeds a
    normal (`feeds_a_normal`) a flat normal map, (0.5, 0.5, 1) everywhere: a checker there
    lit the surface in blocks."""
    if normal and kind == "2d":
        return procedural("flat_normal")
    texture = procedural(STAND_INS.get(kind, "checker"))
    if kind == "1d":  # one row of the checker
        texture = Texture("1d", texture.format, [level[:1] for level in texture.levels],
                          texture.name)
    return texture


# A texture feeds a normal when its parameter or a sampler of it is named so (normalMap,
# BumpSampler, g_MeshNormalMap, NrmTex) or a shader expands what it samples from [0, 1] to
# [-1, 1]: `tex2D(S, uv) * 2 - 1`, `2 * tex2D(S, uv) - 1`, `expand(tex2D(S, uv))` in HLSL,
# `tN_bx2` of the stage it is bound to in ps.1.x assembly.
_NORMAL_NAME = re.compile(r"normal|bump|nrm|nmap", re.IGNORECASE)
_SAMPLE = r"tex\w*\s*\(\s*{s}\b[^;]*?\)"
_EXPANDS = (r"{sample}(?:\.\w+)?\s*\*\s*2(?:\.0*)?f?\s*-\s*1",
            r"2(?:\.0*)?f?\s*\*\s*{sample}(?:\.\w+)?\s*-\s*1",
            r"expand\s*\(\s*{sample}")


def feeds_a_normal(effect: Effect, param: Parameter) -> bool:
    """Whether texture (or sampler) parameter `param` is a normal map, by its name, its
    samplers' names, or the way the shaders use what they sample (see `_NORMAL_NAME`)."""
    samplers = [param.name] + [p.name for p in effect.parameters if _samples(p, param.name)]
    if any(_NORMAL_NAME.search(name) for name in samplers):
        return True
    sources = "\n".join(f.source for f in effect.functions)
    for name in samplers:
        sample = _SAMPLE.format(s=re.escape(name))
        if any(re.search(form.format(sample=sample), sources) for form in _EXPANDS):
            return True
    for technique in effect.techniques:
        for pass_ in technique.passes:
            stages = [a.index or 0 for a in pass_.states if a.name.lower() == "texture"
                      and getattr(a.value, "name", None) in samplers]
            shaders = [a.value.source for a in pass_.states if a.name.lower() == "pixelshader"
                       and hasattr(a.value, "source") and isinstance(a.value.source, str)]
            if any(re.search(rf"\bt{i}_bx2\b", text) for i in stages for text in shaders):
                return True
    return False


def _samples(sampler: Parameter, texture: str) -> bool:
    """`sampler` is a sampler_state whose Texture is `texture`."""
    from effects.model import SamplerState
    if not isinstance(sampler.value, SamplerState):
        return False
    named = sampler.value.get("Texture")
    return named is not None and getattr(named.value, "name", None) == texture


class TextureCache:
    """Texture files by (absolute path, modification time, kind): a changed file reloads.
    Bounded by the bytes of the textures kept (least recently used out first), so an effect
    with many small textures does not thrash it and a few big ones do not pin memory.
    `name`: the name it is declared by in the cache registry (effects.base.caches); a host's
    own cache may go without one."""

    KEYS = "absolute path, modification time, size, inode, the kind asked for"

    def __init__(self, max_bytes: int = DEFAULT_TEXTURE_BYTES, name: str | None = None) -> None:
        self._entries = ByteLRU(max_bytes) if name is None else \
            caches.declare(name, keys=self.KEYS, max_bytes=max_bytes, size_of=texture_bytes)
        self.loads = 0   # files actually read (tests and the viewer's log use it)

    def load(self, path: str, kind: str | None, at: Location) -> Texture:
        full = os.path.abspath(path)
        try:
            info = os.stat(full)
        except OSError:
            raise MissingTexture(f"texture file not found: {path}", at) from None
        # The mtime alone is not enough: Linux stamps files with a coarse clock (a few ms), so
        # two saves in one tick look alike; size and inode (an atomic save makes a new one) too.
        key = (full, info.st_mtime_ns, info.st_size, info.st_ino, kind)
        hit = self._entries.get(key)
        if hit is not None:
            return hit
        try:
            texture = load_texture(full, kind=kind)
        except SceneError as exc:
            # Say which parameter wanted it: the error's own location is the image file.
            raise SceneError(f"{exc.message} ({full})", at) from None
        self.loads += 1
        self._entries.put(key, texture)
        return texture


DEFAULT_TEXTURE_CACHE = TextureCache(name="host.texture_files")


@dataclass(frozen=True)
class TextureSource:
    """A user's value for a texture parameter: a path (relative to `base_dir`) or a Texture,
    and where it was written (for errors). A scene's paths obey the effect's include root;
    a value the host itself gives (`--set`, `params=`) does not (`confined=False`)."""

    value: str | Texture
    base_dir: str
    location: Location
    confined: bool = True   # under the effect's include root (False: the command line's --set)


def resolve_texture(param: Parameter, effect: Effect, given: TextureSource | None = None,
                    cache: TextureCache | None = None) -> Texture | None:
    """The texture for one texture parameter (module docstring order), or None if unbound."""
    cache = cache or DEFAULT_TEXTURE_CACHE
    kind = declared_kind(param)
    root = effect.include_root   # with one, every file the effect (or its scene) names stays inside
    if given is not None:
        if isinstance(given.value, Texture):
            texture = given.value
        elif _names_procedural(given.value):
            # 'sobel_normals:textures/h.png', 'sky_cube:64': a generator, as the annotation
            # `string Procedural = "..."` names one (fxfiles/README.md)
            texture = procedural(given.value, base_dir=given.base_dir, location=given.location,
                                 root=root if given.confined else None)
        else:
            path = confine(given.value, given.base_dir, root if given.confined else None,
                           "texture", SceneError, given.location)
            texture = cache.load(path, kind, given.location)
        _check_kind(param, texture, kind, given.location)
        return texture
    base = effect_dir(effect)
    resource = param.annotation("ResourceName")
    if resource is not None and isinstance(resource.value, str) and resource.value.strip():
        name = resource.value.strip()
        path = confine(name, base, root, "ResourceName", SceneError, resource.location)
        return cache.load(path, kind, resource.location)
    generator = param.annotation("Procedural")
    if generator is not None and isinstance(generator.value, str):
        size, rows = _size_annotation(param, "Width"), _size_annotation(param, "Height")
        text = expand_parameters(generator.value, effect, generator.location)
        texture = procedural(text, size=size, base_dir=base, location=generator.location,
                             root=root, rows=rows)
        _check_kind(param, texture, kind, generator.location)
        return texture
    return None


def _size_annotation(param: Parameter, name: str) -> int | None:
    """A texture parameter's `int Width` / `int Height` annotation, checked; None if absent."""
    given = param.annotation(name)
    if given is None or isinstance(given.value, str):
        return None
    first = np.asarray(given.value, np.float64).reshape(-1)
    if first.size == 0 or not np.isfinite(first[0]) or not 1 <= first[0] <= 1 << 20:
        raise SceneError(f"{name} annotation {str(given.value)[:40]} is not a texture size",
                         given.location)
    return int(first[0])


# `<Name>`, `k*<Name>` or `<Name>*k` in a Procedural argument (k a plain decimal number)
_NUMBER = r"[0-9]+(?:\.[0-9]*)?"
_REFERENCE = re.compile(rf"(?:({_NUMBER})\s*\*\s*)?<\s*([A-Za-z_][A-Za-z0-9_]*)\s*>(?:\s*\*\s*({_NUMBER}))?")


def procedural_parameters(param: Parameter) -> set[str]:
    """The parameters a texture parameter's `Procedural` annotation names as `<Name>`: the
    values its texture is made from."""
    generator = param.annotation("Procedural")
    if generator is None or not isinstance(generator.value, str):
        return set()
    return {m.group(2) for m in _REFERENCE.finditer(generator.value)}


def expand_parameters(text: str, effect: Effect, at: Location) -> str:
    """`text` with each `<Name>` (times its factor) replaced by the numeric parameter's current
    value, written so that reading it back gives the same float (a whole number without a
    decimal point)."""
    def value(match: re.Match) -> str:
        before, name, after = match.groups()
        param = effect.parameter(name)
        if param is None:
            raise SceneError(f"Procedural argument names <{name}>, which is no parameter of "
                             "this effect", at)
        number = np.asarray(param.value if param.value is not None else np.nan, dtype=object)
        try:
            scalar = float(number.reshape(-1)[0]) if number.size == 1 else float("nan")
        except (TypeError, ValueError):
            scalar = float("nan")
        if not np.isfinite(scalar):
            raise SceneError(f"Procedural argument <{name}>: {name} is not a finite number "
                             f"(declared at {param.location})", at)
        for factor in (before, after):
            if factor is not None:
                scalar *= float(factor)
        # a whole number as one (a generator may want an integer: checker:<Squares>)
        return str(int(scalar)) if scalar.is_integer() and abs(scalar) < 2 ** 53 else repr(scalar)
    return _REFERENCE.sub(value, text)


def check_texture_budget(textures: Mapping[str, "Texture | None"], at: Location) -> None:
    """All textures one render binds against the `effect_texels` limit."""
    total = sum(t.width * t.height * (6 if t.kind == "cube" else t.depth)
                for t in textures.values() if t is not None)
    limits.check("effect_texels", total, at, "the textures this render binds", SceneError)


def _names_procedural(value: str) -> bool:
    """Whether a given texture value names a generator ('NAME' or 'NAME:ARG') rather than a
    file: its part before the first ':' is a known generator (a Windows drive letter is not)."""
    head = value.split(":", 1)[0]
    return head in PROCEDURAL and (":" in value or not os.path.splitext(value)[1])


def _check_kind(param: Parameter, texture: Texture, kind: str | None, at: Location) -> None:
    if kind is not None and texture.kind != kind:
        raise SceneError(f"texture parameter {param.name} (declared at {param.location}) needs a "
                         f"{kind} texture; {texture.name or 'the texture'} is {texture.kind}", at)


# ------------------------------------------------------------------------------------------------
# Meshes and vertex streams


@dataclass
class Geometry:
    """A draw's vertex data: `streams` by usage name, `indices`, and the primitive type.
    `has_diffuse` says whether the vertices really carry a diffuse colour (inline vertices,
    a mesh with colours, a scene `vertex` key); the color0 stream of one that does not holds
    D3D's default white, and fixed-function lighting then uses the material's colours."""

    streams: dict[str, np.ndarray]
    indices: np.ndarray
    primitive: str
    has_diffuse: bool = True


# By the bytes of their arrays: a count bound (16, before) pinned 16 meshes of any size
_MESHES = caches.declare("host.meshes", keys="a built-in mesh's name; an .obj file's absolute "
                         "path and modification time", max_bytes=256 << 20)


def scene_mesh(scene: Scene) -> Mesh | InlineMesh:
    """The scene's mesh, built or loaded (built-in meshes and .obj and .x files are cached; a
    file by its modification time)."""
    if isinstance(scene.mesh, InlineMesh):
        return scene.mesh
    name = scene.mesh
    at = scene.location("mesh")
    key: tuple = (name,)
    if name.lower().endswith(MESH_FILES):
        path = name if os.path.isabs(name) else os.path.join(scene.base_dir, name)
        untrusted.note(path)   # also when the cache holds it (untrusted.recording)
        try:
            key = (os.path.abspath(path), os.stat(path).st_mtime_ns)
        except OSError:
            raise SceneError(f"mesh file not found: {path}", at) from None
    mesh = _MESHES.get(key)
    if mesh is None:
        mesh = by_name(name, base_dir=scene.base_dir, location=at)
        _MESHES.put(key, mesh)
    return mesh


def parse_stream_map(text: str, at: Location) -> dict[str, str]:
    """'texcoord1=tangent, texcoord2=binormal' as {stream: attribute}."""
    out = {}
    for item in text.replace(",", " ").replace(";", " ").split():
        target, eq, source = item.partition("=")
        if not eq:
            raise SceneError(f"VertexStreams entry {item!r} is not STREAM=ATTRIBUTE", at)
        out[target.strip()] = source.strip()
    return out


def stream_map(effect: Effect, scene: Scene) -> dict[str, str]:
    """stream -> attribute overrides: the effect's `VertexStreams`, then the scene's `streams`
    (each checked, errors at the place that wrote them)."""
    merged: dict[str, tuple[str, Location]] = {}
    param = effect.parameter("VertexStreams")
    if param is not None and param.type.base == "string" and isinstance(param.value, str):
        for target, source in parse_stream_map(param.value, param.location).items():
            merged[target] = (source, param.location)
    for target, source in scene.streams.items():
        merged[target] = (source, scene.location(f"streams.{target}"))
    for target, (source, at) in merged.items():
        if target not in STREAM_NAMES:
            raise SceneError(f"unknown vertex stream {target!r} (streams: {', '.join(STREAM_NAMES)})", at)
        if source not in ATTRIBUTES:
            raise SceneError(f"unknown vertex attribute {source!r} for stream {target} "
                             f"(attributes: {', '.join(ATTRIBUTES)})", at)
    return {target: source for target, (source, _) in merged.items()}


def effect_mesh_file(effect: Effect) -> tuple[str, Location] | None:
    """The mesh file the effect names for its preview: the DirectX SDK's EffectEdit drew the
    model a global `string XFile = "tiger.x";` names (its samples' "Constants for
    EffectEdit"). The path, resolved against the effect's folder and kept inside its include
    root, and where it was written; None when it names none."""
    param = effect.parameter("XFile")
    if param is None or param.type.base != "string" or not isinstance(param.value, str) \
            or not param.value.strip():
        return None
    name = param.value.strip()
    if not name.lower().endswith(MESH_FILES):
        raise SceneError(f"XFile {name!r}: the mesh files read are {', '.join(MESH_FILES)}",
                         param.location)
    path = confine(name, effect_dir(effect), effect.include_root, "XFile", SceneError,
                   param.location)
    return path, param.location


def geometry(scene: Scene, effect: Effect, mesh: Mesh | InlineMesh | None = None) -> Geometry:
    """Vertex streams, indices and primitive for drawing the scene's mesh with `effect`."""
    mesh = scene_mesh(scene) if mesh is None else mesh
    overrides = stream_map(effect, scene)
    if isinstance(mesh, InlineMesh):
        attributes = _inline_attributes(mesh)
        count = mesh.vertex_count
        indices = np.arange(count, dtype=np.int64)
        primitive = mesh.primitive
        has_diffuse = True
    else:
        attributes = _mesh_attributes(mesh, scene)
        if "uv_occlusion" in overrides.values():
            attributes["uv_occlusion"] = _uv_occlusion(mesh)
        indices, primitive = np.asarray(mesh.indices), "list"
        has_diffuse = mesh.colors is not None or _scene_gives_colors(scene)
    streams = {name: attributes[source] for name, source in _default_sources(attributes).items()}
    for target, source in overrides.items():
        if source not in attributes:
            raise SceneError(f"stream {target} = {source}: the mesh has no {source}",
                             scene.location(f"streams.{target}") if target in scene.streams
                             else _vertex_streams_location(effect))
        streams[target] = attributes[source]
    return Geometry(streams, indices, primitive, has_diffuse)


def _scene_gives_colors(scene: Scene) -> bool:
    """The scene writes per-vertex colours (its `vertex` key, or values set in code)."""
    return ("vertex" in scene.locations or tuple(scene.vertex_diffuse) != (1.0, 1.0, 1.0, 1.0)
            or tuple(scene.vertex_specular) != (0.0, 0.0, 0.0, 0.0))


def _vertex_streams_location(effect: Effect) -> Location:
    param = effect.parameter("VertexStreams")
    return param.location if param is not None else Location(effect.path, 1, 1)


def _default_sources(attributes: Mapping[str, Any]) -> dict[str, str]:
    sources = {"position": "position", "color0": "diffuse", "color1": "specular"}
    for name in ("normal", "tangent", "binormal"):
        if name in attributes:
            sources[name] = name
    for i in range(8):
        if f"tex{i}" in attributes:
            sources[f"texcoord{i}"] = f"tex{i}"
        elif "uv" in attributes:
            sources[f"texcoord{i}"] = "uv"
    return sources


def _mesh_attributes(mesh: Mesh, scene: Scene) -> dict[str, np.ndarray]:
    n = mesh.vertex_count
    diffuse = mesh.colors if mesh.colors is not None else np.tile(
        np.asarray(scene.vertex_diffuse, np.float32), (n, 1))
    return {"position": mesh.positions, "normal": mesh.normals, "tangent": mesh.tangents,
            "binormal": mesh.binormals, "uv": mesh.uv, "diffuse": np.asarray(diffuse, np.float32),
            "specular": np.tile(np.asarray(scene.vertex_specular, np.float32), (n, 1))}


def _uv_occlusion(mesh: Mesh) -> np.ndarray:
    """(N, 3): u, v, ambient occlusion; the occlusion is cast once per mesh (meshes are cached
    by `scene_mesh`, so a viewer reload does not cast again)."""
    if mesh.occlusion is None:
        mesh.occlusion = vertex_occlusion(mesh.positions, mesh.normals, mesh.indices)
    return np.concatenate([mesh.uv, mesh.occlusion[:, None]], axis=1).astype(np.float32)


def _inline_attributes(mesh: InlineMesh) -> dict[str, np.ndarray]:
    attributes = dict(mesh.attributes)
    if "tex0" in attributes:
        attributes["uv"] = attributes["tex0"]
    if "uv" in attributes:       # inline vertices carry no occlusion: 0, open sky
        uv = np.asarray(attributes["uv"], np.float32)
        uv = np.concatenate([uv, np.zeros((len(uv), 2), np.float32)], axis=1)[:, :2]
        attributes["uv_occlusion"] = np.concatenate([uv, np.zeros((len(uv), 1), np.float32)], 1)
    return attributes
