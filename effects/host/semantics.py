"""Parameter values: what the scene supplies by semantic, and values a user writes.

Scene binding (as DXSAS-aware hosts, FX Composer and EffectEdit did): `float4x4 WorldViewProj
: WORLDVIEWPROJECTION;` receives world·view·projection of the scene, `: WORLDINVERSETRANSPOSE`
its inverse transpose, `: CAMERAPOSITION` the eye, `float3 L : Position < string Object =
"PointLight0"; >` the light's position, and so on: one table (`MATRIX_SEMANTICS`,
`VALUE_SEMANTICS`, `OBJECT_LIGHT_SEMANTICS`), semantics matched case-insensitively. DX8 files carry no semantics; for them a short table of
the parameter names the DirectX 8 SDK samples (and the bundled DX8 files) used stands in.
Matrices are stored in Direct3D's row-vector convention (p' = p · M), exactly what the
application would pass to SetMatrix; how they reach constant registers is the lowering's job.
The light semantics are bound only when the scene has a `light` key or the parameter has no
initial value, so an effect's own light defaults show in a scene that does not place a light.

User values (`--set NAME=VALUE`, the scene's `params`, `render(params=...)`) go through
`coerce_value`: numbers, vectors ('1,0.5,0.25,1' or '[1, 0.5, 0.25, 1]'), booleans,
D3DCOLOR '0xAARRGGBB' (a colour for float3/float4, an integer for int/DWORD), strings, and
for texture parameters a path or a `Texture`. A value that does not fit is a `SceneError`
naming the parameter and where the effect declares it.
"""
from __future__ import annotations

import math
import re
from typing import Any, Callable, Iterable

import numpy as np

from effects.base import caches
from effects.base.errors import Location, SceneError
from effects.base.yaml_input import brief
from effects.model import Effect, Parameter
from effects.host.scene import Scene, d3dcolor

# What the scene binds, by semantic (matched case-insensitively): one row per semantic, read by
# `bind_scene`, by `effects doctor` and printed as the README's table (`binding_table`). The
# transform rows also bind with the suffixes INVERSE, TRANSPOSE and INVERSETRANSPOSE (and the
# NVIDIA shader library's short forms I, T, IT, INV), e.g. WORLDINVERSETRANSPOSE, VIEWI.
MATRIX_SEMANTICS = {
    "WORLD": "the scene's world matrix (the mesh's placement; identity for the built-in meshes)",
    "VIEW": "the camera's look-at view matrix (left-handed, as D3DXMatrixLookAtLH)",
    "PROJECTION": "the camera's perspective projection (D3DXMatrixPerspectiveFovLH: fov, aspect, near, far)",
    "WORLDVIEW": "world · view",
    "VIEWPROJECTION": "view · projection",
    "WORLDVIEWPROJECTION": "world · view · projection",
}
_MATRIX_ALIASES = {"WORLDVIEWPROJ": "WORLDVIEWPROJECTION", "VIEWPROJ": "VIEWPROJECTION",
                   "WVP": "WORLDVIEWPROJECTION", "PROJ": "PROJECTION"}
_SUFFIXES = {"": "", "INVERSE": "INVERSE", "TRANSPOSE": "TRANSPOSE",
             "INVERSETRANSPOSE": "INVERSETRANSPOSE", "I": "INVERSE", "INV": "INVERSE",
             "T": "TRANSPOSE", "IT": "INVERSETRANSPOSE", "INVTRANS": "INVERSETRANSPOSE"}

VALUE_SEMANTICS = {
    "CAMERAPOSITION": "the camera's eye (x, y, z, 1)",
    "VIEWPOSITION": "the camera's eye",
    "EYEPOSITION": "the camera's eye",
    "LIGHTPOSITION": "the scene light's position (x, y, z, 1)",
    "LIGHT0POSITION": "the scene light's position",
    "LIGHTDIRECTION": "the scene light's direction (towards where it shines, w = 0)",
    "LIGHT0DIRECTION": "the scene light's direction",
    "LIGHTCOLOR": "the scene light's colour (r, g, b, a)",
    "LIGHT0COLOR": "the scene light's colour",
    "LIGHTDIFFUSE": "the scene light's colour",
    "TIME": "the scene's time in seconds (`time:` key; 0 by default)",
    "VIEWPORTPIXELSIZE": "the frame's (width, height) in pixels",
    "VIEWPORTSIZE": "the frame's (width, height) in pixels",
    # RenderMonkey's predefined variables: its FX exporter writes the variable's name as the
    # semantic (`float fTime0_X : Time0_X;`, `float4 vViewPosition : ViewPosition;`); values as
    # the RenderMonkey documentation's "Predefined Variables" section gives them, with its
    # default cycle time of 120 seconds
    "TIME0_X": "the scene's time in seconds, cycling every 120 s (RenderMonkey's default cycle)",
    "COSTIME0_X": "cos of TIME0_X (RenderMonkey)",
    "SINTIME0_X": "sin of TIME0_X (RenderMonkey)",
    "TANTIME0_X": "tan of TIME0_X (RenderMonkey)",
    "TIME0_X_PACKED": "(TIME0_X, COSTIME0_X, SINTIME0_X, TANTIME0_X) (RenderMonkey)",
    "TIME0_1": "the scene's time as a fraction of the 120 s cycle, 0..1 (RenderMonkey)",
    "COSTIME0_1": "cos of TIME0_1 (RenderMonkey)",
    "SINTIME0_1": "sin of TIME0_1 (RenderMonkey)",
    "TANTIME0_1": "tan of TIME0_1 (RenderMonkey)",
    "TIME0_1_PACKED": "(TIME0_1, COSTIME0_1, SINTIME0_1, TANTIME0_1) (RenderMonkey)",
    "VIEWDIRECTION": "the camera's unit view direction, eye to target (w = 0) (RenderMonkey; "
                     "MikuMikuEffect's DIRECTION with `string Object = \"Camera\"`)",
    "VIEWPORTWIDTH": "the frame's width in pixels (RenderMonkey)",
    "VIEWPORTHEIGHT": "the frame's height in pixels (RenderMonkey)",
    "VIEWPORTDIMENSIONS": "the frame's (width, height) in pixels (RenderMonkey)",
    "VIEWPORTWIDTHINVERSE": "1 / the frame's width (RenderMonkey)",
    "VIEWPORTHEIGHTINVERSE": "1 / the frame's height (RenderMonkey)",
    "INVERSEVIEWPORTDIMENSIONS": "(1 / width, 1 / height) of the frame (RenderMonkey)",
}
# The direction toward the scene light: the DirectX SDK samples' g_LightDir / g_vLightDir
# ("Light's direction in world space", lit as max(0, dot(N, g_LightDir)) in BasicHLSL.fx: the
# application's vector points at the light, minus the D3DLIGHT9 direction). Not a semantic a
# file can write: bound only by those names (`SDK_NAME_SEMANTICS`).
TOWARD_LIGHT = "-LIGHTDIRECTION"
# RenderMonkey's cycle time: "by default this Cycle time is set to 120 seconds"
RENDERMONKEY_CYCLE = 120.0
# FX Composer's light binding: a parameter whose `string Object` annotation names a light
# ("PointLight0", "DirectionalLight0", "SpotLight0", "TargetLight", "Light0") takes the scene
# light's value of the kind its semantic says.
OBJECT_LIGHT_SEMANTICS = {
    "POSITION": "LIGHTPOSITION", "DIRECTION": "LIGHTDIRECTION", "DIFFUSE": "LIGHTCOLOR",
    "COLOR": "LIGHTCOLOR", "COLOUR": "LIGHTCOLOR", "SPECULAR": "LIGHTCOLOR",
}
# MikuMikuEffect (and DXSAS hosts) with `string Object = "Camera"`: the camera's position and
# view direction (`float3 CameraPosition : POSITION < string Object = "Camera"; >;`, as
# MME's sample full.fx declares it).
OBJECT_CAMERA_SEMANTICS = {"POSITION": "CAMERAPOSITION", "DIRECTION": "VIEWDIRECTION"}
# Names, not semantics, that DirectX 8-era effects (the SDK samples, the chapter's BRDF effect,
# fxfiles/sdk8_style.fx) used for what the application set every frame.
DX8_NAME_SEMANTICS = {
    "mwld": "WORLD", "mworld": "WORLD", "mview": "VIEW", "mviw": "VIEW", "mproj": "PROJECTION",
    "mprj": "PROJECTION", "mtot": "WORLDVIEWPROJECTION", "mwvp": "WORLDVIEWPROJECTION",
    "mworldviewproj": "WORLDVIEWPROJECTION", "mvin": "VIEWINVERSE",
    "lhtr": "LIGHTDIRECTION", "vlightdir": "LIGHTDIRECTION", "vlgt": "LIGHTDIRECTION",
    "veye": "CAMERAPOSITION",
}
# The DirectX 9 SDK samples' globals (BasicHLSL.fx, quoted by the "Effect Example" page of
# the Direct3D 9 documentation: g_MaterialAmbientColor, g_LightDir[3] "Light's direction in
# world space", g_LightDiffuse[3], g_fTime "App's time in seconds", g_mWorld,
# g_mWorldViewProjection): `g_` and a type letter (v vector, f float, m matrix), matched in any
# letter case. The matrices go by `name_semantic` (g_m prefix); these are the rest. Arrays
# (g_LightDir[3]) are not bound: the sample set as many lights as its technique drew.
SDK_NAME_SEMANTICS = {
    "lightdir": TOWARD_LIGHT, "lightdirection": TOWARD_LIGHT,
    "lightdiffuse": "LIGHTCOLOR", "lightcolor": "LIGHTCOLOR", "lightcolour": "LIGHTCOLOR",
    "time": "TIME", "eyept": "CAMERAPOSITION", "eyepos": "CAMERAPOSITION",
    "eyeposition": "CAMERAPOSITION", "camerapos": "CAMERAPOSITION",
}
# Parameters a host would have set from what it had (a model's material, the game's
# colours) where no convention says which value: left unset (they read 0) and named as such
# by `host_would_set`, so the warning says whose value is missing. No invented colours.
_MATERIAL_WORDS = ("diffuse", "ambient", "specular", "emissive", "emmisive", "power")
_GEOMETRY_SEMANTICS = {"DIFFUSE", "AMBIENT", "SPECULAR", "EMISSIVE", "SPECULARPOWER"}
_MME_MODEL_SEMANTICS = {"TOONCOLOR", "EDGECOLOR", "ADDINGTEXTURE", "MULTIPLYINGTEXTURE",
                        "ADDINGSPHERETEXTURE", "MULTIPLYINGSPHERETEXTURE"}
_XNA_MATERIAL_NAMES = {"diffusecolor", "emissivecolor", "specularcolor", "specularpower",
                       "ambientlightcolor", "alpha"}
# Names engines' shader APIs set, documented by them: Allegro 5's al_set_shader_* host sets
# `al_projview_matrix` (the transform times the projection, multiplied as mul(pos, M)).
ENGINE_NAME_SEMANTICS = {"al_projview_matrix": ("WORLDVIEWPROJECTION", "Allegro 5")}
# XNA-era effects (and engines' HLSL such as Irrlicht's example) declare `float4x4 World, View,
# Projection;` with no semantics and the game sets them by name every frame. A parameter with
# no semantic is bound by its name when, case-insensitively and after a conventional prefix
# (g_m, g_mat, g_, m_, mat, g, m, x: the SDK samples' g_mWorld, matWorld, mWorldViewProj,
# xView of Riemer's XNA tutorials), the name is a
# transform semantic (World, WorldViewProjection, WVP, ViewProj, WorldInverseTranspose,
# WorldIT ...), one with its inverse/transpose in front (InvWorld, TransWorld, as Irrlicht
# names them), or one of the vector names below.
_NAME_PREFIXES = ("g_mat", "g_m", "g_", "m_", "mat", "g", "m", "x")
_SDK_TYPE_LETTERS = ("v", "f", "")
# ... or a transform name with `Matrix` (or `Mtx`) after it: Kodu Game Lab's WorldMatrix and
# WorldViewProjMatrix, `worldMatrix` of many XNA samples
_NAME_MATRIX_SUFFIXES = ("matrix", "mtx")
_NAME_MATRIX_FORMS = {"invtrans": "INVERSETRANSPOSE", "inversetranspose": "INVERSETRANSPOSE",
                      "inverse": "INVERSE", "inv": "INVERSE", "transpose": "TRANSPOSE",
                      "trans": "TRANSPOSE"}
_NAME_MATRIX_FORMS_LONGEST_FIRST = sorted(_NAME_MATRIX_FORMS, key=len, reverse=True)
NAME_VALUES = {
    "cameraposition": "CAMERAPOSITION", "camerapos": "CAMERAPOSITION",
    "eyeposition": "CAMERAPOSITION", "eyepos": "CAMERAPOSITION",
    "lightposition": "LIGHTPOSITION", "lightpos": "LIGHTPOSITION",
    "lightdirection": "LIGHTDIRECTION", "lightdir": "LIGHTDIRECTION",
    "lightcolor": "LIGHTCOLOR", "lightcolour": "LIGHTCOLOR",
    # `Location` for position (Kodu Game Lab's EyeLocation), light 0 as the scene's light
    # (its LightDirection0, LightColor0)
    "eyelocation": "CAMERAPOSITION", "cameralocation": "CAMERAPOSITION",
    "lightlocation": "LIGHTPOSITION", "lightposition0": "LIGHT0POSITION",
    "lightpos0": "LIGHT0POSITION", "lightdirection0": "LIGHT0DIRECTION",
    "lightdir0": "LIGHT0DIRECTION", "lightcolor0": "LIGHT0COLOR", "lightcolour0": "LIGHT0COLOR",
    # XNA's BasicEffect: its first directional light (DirectionalLight0.Direction, the way the
    # light travels, as D3DLIGHT9's) and that light's diffuse and specular colours
    "dirlight0direction": "LIGHT0DIRECTION", "dirlight0diffusecolor": "LIGHT0COLOR",
    "dirlight0specularcolor": "LIGHT0COLOR",
}
_LIGHT_SEMANTICS = {"LIGHTPOSITION", "LIGHT0POSITION", "LIGHTDIRECTION", "LIGHT0DIRECTION",
                    "LIGHTCOLOR", "LIGHTDIFFUSE", "LIGHT0COLOR", TOWARD_LIGHT}


_MATRIX_BASES_LONGEST_FIRST = sorted([*MATRIX_SEMANTICS, *_MATRIX_ALIASES], key=len, reverse=True)


# matrix_semantic and name_semantic read only their string and the tables above: every Runtime
# binds the scene by them, once for each parameter of the effect
@caches.memo("host.matrix_semantics", keys="a semantic", entry_bytes=128, max_bytes=4096 * 128)
def matrix_semantic(semantic: str) -> tuple[str, str] | None:
    """(base row of MATRIX_SEMANTICS, 'INVERSE' / 'TRANSPOSE' / 'INVERSETRANSPOSE' / '') of a
    transform semantic, or None. The longest base that leaves a known suffix wins, so
    WORLDVIEWI is WORLDVIEW inverse, not WORLD + 'VIEWI'."""
    key = semantic.upper()
    for base in _MATRIX_BASES_LONGEST_FIRST:
        if key.startswith(base) and key[len(base):] in _SUFFIXES:
            return _MATRIX_ALIASES.get(base, base), _SUFFIXES[key[len(base):]]
    return None


def _matrix_for(semantic: str, m: dict[str, np.ndarray]) -> np.ndarray | None:
    found = matrix_semantic(semantic)
    if found is None:
        return None
    base, rest = found
    value = {"WORLD": m["world"], "VIEW": m["view"], "PROJECTION": m["projection"],
             "WORLDVIEW": m["world"] @ m["view"],
             "VIEWPROJECTION": m["view"] @ m["projection"],
             "WORLDVIEWPROJECTION": m["world"] @ m["view"] @ m["projection"]}[base]
    if "INVERSE" in rest:
        value = np.linalg.inv(value)
    if "TRANSPOSE" in rest:
        value = value.T
    return value


def _fit(value: Any, param: Parameter) -> np.ndarray:
    """Shape a vector to the parameter's components (float3 takes xyz, float4 xyzw)."""
    n = param.type.components
    flat = np.asarray(value, np.float32).reshape(-1)
    v = np.zeros(n, np.float32)
    v[:min(n, flat.size)] = flat[:n]
    if param.type.rows > 1:
        return v.reshape(param.type.rows, param.type.cols)
    return v if n > 1 else v.reshape(())


def scene_values(scene: Scene, size: tuple[int, int] | None = None, *,
                 matrices: dict[str, np.ndarray] | None = None
                 ) -> tuple[dict[str, Callable[[Parameter], Any]], dict[str, np.ndarray]]:
    """Semantic (upper case) -> function giving that parameter's value in this scene, and the
    scene's world/view/projection matrices for a frame of `size` (`matrices`: those already
    made by `scene.matrices(size)`, which a Runtime has)."""
    m = scene.matrices(size) if matrices is None else matrices
    eye = np.array([*scene.camera.eye, 1.0])
    light = np.array([*scene.light.position, 1.0])
    direction = np.array([*scene.light_direction(), 0.0])
    color = np.array(scene.light.color)
    frame = np.array(size or scene.size, np.float32)
    view_dir = np.asarray(scene.camera.target, np.float64) - np.asarray(scene.camera.eye)
    view_dir = view_dir / (np.linalg.norm(view_dir) or 1.0)
    cycle = scene.time % RENDERMONKEY_CYCLE
    unit = cycle / RENDERMONKEY_CYCLE

    def packed(t: float) -> np.ndarray:
        return np.array([t, math.cos(t), math.sin(t), math.tan(t)])

    by_kind = {"eye": eye, "light": light, "direction": direction, "color": color,
               "time": np.float32(scene.time), "frame": frame, "toward": -direction,
               "view_dir": np.array([*view_dir, 0.0]),
               "t0x": packed(cycle), "t01": packed(unit)}
    kinds = {"CAMERAPOSITION": "eye", "VIEWPOSITION": "eye", "EYEPOSITION": "eye",
             "LIGHTPOSITION": "light", "LIGHT0POSITION": "light", "LIGHTDIRECTION": "direction",
             "LIGHT0DIRECTION": "direction", "LIGHTCOLOR": "color", "LIGHT0COLOR": "color",
             "LIGHTDIFFUSE": "color", "TIME": "time", "VIEWPORTPIXELSIZE": "frame",
             "VIEWPORTSIZE": "frame", TOWARD_LIGHT: "toward", "VIEWDIRECTION": "view_dir",
             "TIME0_X_PACKED": "t0x", "TIME0_1_PACKED": "t01", "VIEWPORTDIMENSIONS": "frame"}
    values: dict[str, Callable[[Parameter], Any]] = {
        semantic: (lambda p, v=by_kind[kind]: _fit(v, p)) for semantic, kind in kinds.items()}
    # one component of a packed value, and the frame's sides and their inverses
    for semantic, (kind, k) in {"TIME0_X": ("t0x", 0), "COSTIME0_X": ("t0x", 1),
                                "SINTIME0_X": ("t0x", 2), "TANTIME0_X": ("t0x", 3),
                                "TIME0_1": ("t01", 0), "COSTIME0_1": ("t01", 1),
                                "SINTIME0_1": ("t01", 2), "TANTIME0_1": ("t01", 3),
                                "VIEWPORTWIDTH": ("frame", 0), "VIEWPORTHEIGHT": ("frame", 1)
                                }.items():
        values[semantic] = lambda p, v=by_kind[kind][k]: _fit(v, p)
    inverse = 1.0 / np.maximum(frame, 1.0)
    values["VIEWPORTWIDTHINVERSE"] = lambda p: _fit(inverse[0], p)
    values["VIEWPORTHEIGHTINVERSE"] = lambda p: _fit(inverse[1], p)
    values["INVERSEVIEWPORTDIMENSIONS"] = lambda p: _fit(inverse, p)
    return values, m


def _light_object(param: Parameter) -> bool:
    obj = param.annotation("Object")
    return obj is not None and isinstance(obj.value, str) and "light" in obj.value.lower()


@caches.memo("host.name_semantics", keys="a parameter name", entry_bytes=128,
             max_bytes=4096 * 128)
def name_semantic(name: str) -> str | None:
    """The semantic a parameter without one is bound by for its name (XNA convention, see
    `_NAME_PREFIXES`): 'World' -> WORLD, 'g_mWVP' -> WORLDVIEWPROJECTION, 'mInvWorld' ->
    WORLDINVERSE, or None."""
    key = name.lower()
    for rest in [key, *(key[len(p):] for p in _NAME_PREFIXES if key.startswith(p) and len(key) > len(p))]:
        if rest in NAME_VALUES:
            return NAME_VALUES[rest]
        for suffix in _NAME_MATRIX_SUFFIXES:   # `WorldViewProjMatrix`: the matrix names only
            if rest.endswith(suffix) and len(rest) > len(suffix):
                rest = rest[:-len(suffix)]
                break
        found = matrix_semantic(rest)
        if found is not None:
            return found[0] + found[1]
        for form in _NAME_MATRIX_FORMS_LONGEST_FIRST:
            found = matrix_semantic(rest[len(form):]) if rest.startswith(form) else None
            if found is not None and found[1] == "":
                return found[0] + _NAME_MATRIX_FORMS[form]
    return None


def binding_source(param: Parameter) -> tuple[str, str]:
    """(semantic the scene binds the parameter by, upper case, or '' for none; how it was
    found: 'semantic', 'light object', 'DX8 name', 'XNA name', '<engine> name')."""
    semantic = (param.semantic or "").upper()
    if semantic.startswith("REGISTER("):   # `: register(vs, c0)` binds a register, not a value
        semantic = ""
    if semantic in OBJECT_LIGHT_SEMANTICS and _light_object(param):
        return OBJECT_LIGHT_SEMANTICS[semantic], "light object"
    if semantic in OBJECT_CAMERA_SEMANTICS and _object(param) == "camera":
        return OBJECT_CAMERA_SEMANTICS[semantic], "camera object"
    if semantic == "CONTROLOBJECT":
        # MikuMikuEffect: "(self)" as a matrix is the model's world matrix; another object's
        # value is 0 (false) when that object is not loaded, and the scene loads none
        self_ = _annotation_text(param, "name") == "(self)"
        if self_ and param.type.rows == 4 and param.type.cols == 4:
            return "WORLD", "MikuMikuEffect CONTROLOBJECT"
        return ("CONTROLOBJECT", "MikuMikuEffect CONTROLOBJECT")
    if semantic:
        return semantic, "semantic"
    if param.name.lower() in DX8_NAME_SEMANTICS:
        return DX8_NAME_SEMANTICS[param.name.lower()].upper(), "DX8 name"
    if param.name in ENGINE_NAME_SEMANTICS:
        semantic, engine = ENGINE_NAME_SEMANTICS[param.name]
        return semantic, f"{engine} name"
    sdk = sdk_name_semantic(param.name)
    if sdk:
        return sdk, "DirectX SDK name"
    by_name = name_semantic(param.name)
    return (by_name, "XNA name") if by_name else ("", "")


def sdk_name_semantic(name: str) -> str | None:
    """The semantic a DirectX SDK sample's global stands for (`SDK_NAME_SEMANTICS`):
    'g_vLightDir' -> the direction toward the light, 'g_fTime' -> TIME; or None."""
    key = name.lower()
    if not key.startswith("g_"):
        return None
    for letter in _SDK_TYPE_LETTERS:
        rest = key[2:]
        if rest.startswith(letter) and rest[len(letter):] in SDK_NAME_SEMANTICS:
            return SDK_NAME_SEMANTICS[rest[len(letter):]]
    return None


def _object(param: Parameter) -> str:
    return (_annotation_text(param, "Object") or "").lower()


def _annotation_text(param: Parameter, name: str) -> str | None:
    a = param.annotation(name)
    return a.value if a is not None and isinstance(a.value, str) else None


def host_would_set(param: Parameter) -> str | None:
    """Whose value a parameter nothing sets was: the tool or game that would have set it
    where no convention says which value (a model's material, a game's colour), or None."""
    semantic = (param.semantic or "").upper()
    name = param.name.lower()
    if semantic in _GEOMETRY_SEMANTICS and _object(param) == "geometry":
        return ("MikuMikuEffect sets it from the model's material (Object = \"Geometry\"); "
                "the scene has no material")
    if semantic in _MME_MODEL_SEMANTICS:
        return f"MikuMikuEffect sets {semantic} from the model; the scene has none"
    if semantic.startswith("MATERIAL") or (semantic in _GEOMETRY_SEMANTICS and not _object(param)):
        return f"a host sets {semantic} from the object's material; the scene has none"
    if name.startswith("g_material") or (name.startswith("g_") and "material" in name):
        return "the DirectX SDK sample set its material colours in code; no convention says which"
    if name in _XNA_MATERIAL_NAMES:
        return "XNA's BasicEffect took the game's material colours; no convention says which"
    if "light" in name and any(w in name for w in ("dir", "pos", "color", "colour", "diffuse")):
        return ("a light the application placed: the scene's light is bound only where a "
                "convention names it (docs/guide/host.md)")
    return None


def parameter_semantic(param: Parameter) -> str:
    """The semantic the scene binds the parameter by (upper case): its own, FX Composer's
    light-object form (`: Position < string Object = "PointLight0"; >` is LIGHTPOSITION), for
    DX8 files the one its conventional name stands for, and for a parameter with no semantic
    the one its name says in the XNA convention (`name_semantic`)."""
    return binding_source(param)[0]


def binds(semantic: str) -> bool:
    """Whether the scene supplies a value for this (upper-case) semantic."""
    return semantic in VALUE_SEMANTICS or matrix_semantic(semantic) is not None


def bind_transforms(effect: Effect, m: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """Values of the parameters with a transform semantic (WORLDVIEWPROJECTION, VIEWI...) for
    the world/view/projection matrices `m`: the scene's camera, or a cube render target's
    face view while a script draws into it (`effects.host.scripts`)."""
    bound: dict[str, np.ndarray] = {}
    for param in effect.parameters:
        semantic = parameter_semantic(param)
        if not semantic or param.array:
            continue
        matrix = _matrix_for(semantic, m)
        if matrix is None:
            continue
        if param.type.rows == 4 and param.type.cols == 4:
            bound[param.name] = matrix.astype(np.float32)
        elif param.type.rows >= 3 and param.type.cols >= 3:  # float4x3, float3x3
            bound[param.name] = matrix[:param.type.rows, :param.type.cols].astype(np.float32)
    return bound


def bind_scene(effect: Effect, scene: Scene, size: tuple[int, int] | None = None, *,
               matrices: dict[str, np.ndarray] | None = None) -> dict[str, Any]:
    """Values for every parameter the scene supplies: by semantic, or for DX8 files by the
    conventional names above. Returns name -> value (matrices as float32 4x4). `matrices`:
    `scene.matrices(size)`, when the caller has made them."""
    values, m = scene_values(scene, size, matrices=matrices)
    bound: dict[str, Any] = bind_transforms(effect, m)
    for param in effect.parameters:
        semantic = parameter_semantic(param)
        if not semantic or param.array or param.name in bound:
            continue
        if semantic == "CONTROLOBJECT" and param.type.is_numeric:
            self_ = _annotation_text(param, "name") == "(self)"
            # "(self)" as a vector: the model's position (the world matrix's translation)
            bound[param.name] = _fit(m["world"][3, :3] if self_ else 0.0, param) \
                if param.type.base in ("float", "half") else \
                np.zeros(param.type.components, bool if param.type.base == "bool" else np.int32
                         ).reshape(_fit(0.0, param).shape)
            continue
        if matrix_semantic(semantic) is None and semantic in values and param.type.is_numeric:
            if semantic in _LIGHT_SEMANTICS and not scene.light_given and _gives_light(param):
                continue
            bound[param.name] = _in_space(values[semantic](param), param, semantic, m)
    return bound


def _gives_light(param: Parameter) -> bool:
    """Whether the file gives its own light in `param` (kept where the scene gives none): a
    value that is not all zeros. Zeros are what fxc writes for a parameter declared without
    one, so an fx_2_0 binary and its source bind alike; an all-zero colour or position is
    no light to keep."""
    if param.value is None:
        return False
    try:
        return bool(np.any(np.asarray(param.value, dtype=np.float64) != 0))
    except (TypeError, ValueError):
        return True          # an expression or object: the file's own, whatever it gives


# DXSAS / FX Composer: a light's or the camera's position or direction with `string Space =
# "View"` (or "Object") is given in that space (`float3 L : DIRECTION < string Object =
# "DirectionalLight"; string Space = "VIEW"; >`); "World", or no annotation, is world space.
_SPACE_POINTS = {"LIGHTPOSITION", "LIGHT0POSITION", "CAMERAPOSITION", "VIEWPOSITION",
                 "EYEPOSITION"}
_SPACE_VECTORS = {"LIGHTDIRECTION", "LIGHT0DIRECTION", TOWARD_LIGHT, "VIEWDIRECTION"}


def _in_space(value: np.ndarray, param: Parameter, semantic: str,
              m: dict[str, np.ndarray]) -> np.ndarray:
    space = (_annotation_text(param, "Space") or "world").lower()
    if space not in ("view", "object") or semantic not in _SPACE_POINTS | _SPACE_VECTORS:
        return value
    to = m["view"] if space == "view" else np.linalg.inv(m["world"])
    v = np.zeros(4)
    flat = np.asarray(value, np.float64).reshape(-1)
    v[:min(3, flat.size)] = flat[:3]
    v[3] = 1.0 if semantic in _SPACE_POINTS else 0.0
    return _fit((v @ to)[:flat.size] if flat.size < 4 else np.append((v @ to)[:3], flat[3:]),
                param)


def ui_defaults(effect: Effect) -> dict[str, np.ndarray]:
    """Values a tool's UI would show for numeric parameters the file leaves uninitialised
    and the scene does not bind: the middle of the `UIMin`..`UIMax` range when both are given,
    else `UIMin` (FX Composer's slider starts inside its range; an uninitialised value would
    read 0, which may be outside it)."""
    out: dict[str, np.ndarray] = {}
    for param in effect.parameters:
        if param.value is not None or not param.type.is_numeric or param.array:
            continue
        lo, hi = param.annotation("UIMin"), param.annotation("UIMax")
        numbers = [np.asarray(a.value, np.float64) for a in (lo, hi)
                   if a is not None and not isinstance(a.value, str)]
        if not numbers:
            continue
        value = (numbers[0] + numbers[1]) / 2 if len(numbers) == 2 else numbers[0]
        out[param.name] = _fit(value, param) if param.type.base in ("float", "half") else \
            _fit(value, param).astype(np.int32 if param.type.base == "int" else np.float32)
    return out


def binding_table() -> list[tuple[str, str]]:
    """(semantic, what the scene binds) rows, as the README lists them."""
    rows = [(name, text) for name, text in MATRIX_SEMANTICS.items()]
    rows.append(("…INVERSE, …TRANSPOSE, …INVERSETRANSPOSE (also …I, …T, …IT)",
                 "the inverse / transpose / inverse transpose of the matrix above"))
    rows.extend(VALUE_SEMANTICS.items())
    rows.extend((f"{s} with `string Object = \"…Light…\"`", VALUE_SEMANTICS[t])
                for s, t in OBJECT_LIGHT_SEMANTICS.items())
    rows.append(("no semantic, named World, View, Projection, WorldView, ViewProjection, "
                 "WorldViewProjection, WVP, WorldInverseTranspose, InvWorld … (any case; "
                 "prefix g_m, g_mat, g_, m_, mat, g, m or x allowed)",
                 "bound by name (XNA convention): the matrix that name stands for"))
    rows.extend((f"no semantic, named {name}", f"bound by name ({engine} convention): "
                 f"{VALUE_SEMANTICS.get(semantic) or MATRIX_SEMANTICS[semantic]}")
                for name, (semantic, engine) in ENGINE_NAME_SEMANTICS.items())
    rows.append(("no semantic, named CameraPosition, EyePosition, LightPosition, LightDirection, "
                 "LightColor (or …Pos, …Dir)", "bound by name (XNA convention): the camera's "
                 "eye, the scene light's position / direction / colour"))
    rows.append(("no semantic, named DirLight0Direction, DirLight0DiffuseColor, "
                 "DirLight0SpecularColor", "bound by name (XNA BasicEffect's first directional "
                 "light, Microsoft.Xna.Framework.Graphics.BasicEffect): the scene light's "
                 "direction (the way it travels) and colour"))
    rows.append(("no semantic, named g_LightDir, g_vLightDir, g_LightDirection (any case)",
                 "bound by name (DirectX SDK samples, BasicHLSL.fx): the direction toward the "
                 "scene light, minus LIGHTDIRECTION, as the samples' N·L reads it"))
    rows.append(("no semantic, named g_LightDiffuse, g_vLightColor, g_fTime, g_vEyePt …",
                 "bound by name (DirectX SDK samples): the scene light's colour, the time, "
                 "the camera's eye"))
    rows.extend((f"{s} with `string Object = \"Camera\"`",
                 f"{VALUE_SEMANTICS[t]} (MikuMikuEffect)")
                for s, t in OBJECT_CAMERA_SEMANTICS.items())
    rows.append(("a light's or the camera's position or direction with `string Space = "
                 "\"View\"` or `\"Object\"`", "that value in view (object) space, as DXSAS "
                 "and FX Composer give it; `\"World\"` or none: world space"))
    rows.append(("CONTROLOBJECT with `string name = \"(self)\"`", "the world matrix (a "
                 "float4x4) or the model's position (a vector) (MikuMikuEffect)"))
    rows.append(("CONTROLOBJECT naming another object", "0 (false): MikuMikuEffect's value "
                 "for an object that is not loaded, and the scene loads none"))
    rows.append(("DIFFUSE, AMBIENT, SPECULAR, EMISSIVE, SPECULARPOWER with `string Object = "
                 "\"Geometry\"`, TOONCOLOR, EDGECOLOR; MATERIAL… semantics; g_Material… and "
                 "XNA's DiffuseColor … names", "nothing: the model's or game's material, which "
                 "no convention gives; the render warns where one is read (it reads 0)"))
    return rows


# ------------------------------------------------------------------------------------------------
# Values a user writes


def describe(param: Parameter, at: Location | None = None) -> str:
    """'float4 LightColor (declared at fxfiles/phong.fx:51:8)': the parameter, and where the
    effect declares it unless the error is reported there anyway (`at`)."""
    spelling = param.type.spelling or param.type.base
    array = "".join(f"[{n}]" for n in param.array)
    declared = "" if at == param.location else f" (declared at {param.location})"
    return f"{spelling} {param.name}{array}{declared}"


def parse_assignments(items: Iterable[str]) -> dict[str, str]:
    """`NAME=VALUE` strings (the command line's --set) as name -> value text."""
    out: dict[str, str] = {}
    for item in items:
        name, eq, value = item.partition("=")
        if not eq or not name.strip():
            raise SceneError(f"--set {item!r}: expected NAME=VALUE", Location("--set", 1, 1))
        out[name.strip()] = value.strip()
    return out


_BOOL_WORDS = {"true": True, "false": False, "yes": True, "no": False, "on": True, "off": False}
_SPLIT = re.compile(r"[,\s]+")


def _text_numbers(text: str) -> list[Any]:
    body = text.strip()
    if body.startswith(("[", "(", "{")) and body.endswith(("]", ")", "}")):
        body = body[1:-1]
    parts = [p for p in _SPLIT.split(body.strip()) if p]
    out: list[Any] = []
    for part in parts:
        low = part.lower()
        if low in _BOOL_WORDS:
            out.append(_BOOL_WORDS[low])
        elif low.startswith("0x"):
            out.append(int(low, 16))  # ValueError reaches the caller
        elif re.fullmatch(r"[-+]?\d+", low):
            out.append(int(low))
        else:
            out.append(float(low[:-1] if low.endswith("f") else low))  # '1.0f', as in effect files
    return out


def coerce_value(param: Parameter, value: Any, at: Location | None = None, source: str = "") -> Any:
    """A user's value as the parameter holds it: a numpy array shaped like the parameter's
    type (float32 for float/half, int32 int, int64 DWORD, bool bool), a str for strings, and
    for textures the value unchanged (a path or a Texture; `effects.host.resources` loads it).
    A value that does not fit raises SceneError at `at` (default: the declaration), its
    message starting with `source` ('--set', 'scene params') when given."""
    at = at or param.location
    base = param.type.base
    # brief: a value is shown cut short and a few levels deep (a list nested 100,000 deep
    # has a repr that overflows the stack)
    prefix = f"{source} {param.name}={brief(value)}: " if source else ""

    def fail(why: str) -> SceneError:
        return SceneError(f"{prefix}{describe(param, at)}: {why}", at)

    if param.type.takes_image:
        from effects.program.texture import Texture
        if isinstance(value, Texture) or (isinstance(value, str) and value.strip()):
            return value.strip() if isinstance(value, str) else value
        raise fail(f"a {base} parameter takes an image path, not {brief(value)}")
    if base == "string":
        if isinstance(value, str):
            return value
        raise fail(f"a string parameter takes text, not {brief(value)}")
    if not param.type.is_numeric:
        raise fail(f"a {base} parameter cannot be set from a scene or the command line")
    return _coerce_numeric(param, value, fail)


def _coerce_numeric(param: Parameter, value: Any, fail: Callable[[str], SceneError]) -> np.ndarray:
    base = param.type.base
    components = param.type.components
    count = components * int(np.prod(param.array or (1,)))
    colour = param.type.rows == 1 and param.type.cols in (3, 4) and not param.array
    if isinstance(value, str):
        text = value.strip()
        if colour and re.fullmatch(r"0[xX][0-9a-fA-F]{1,8}", text):
            items: list[Any] = list(d3dcolor(int(text, 16)))[:param.type.cols]
        else:
            try:
                items = _text_numbers(text)
            except ValueError:
                raise fail(f"{brief(value)} is not a number or a list of numbers") from None
    else:
        items = _leaves(value, count + 1)
    if colour and param.type.cols == 4 and len(items) == 3:
        items = [*items, 1.0]  # [r, g, b] is an opaque colour, as in the scene's colours
    if len(items) != count:
        shape = "a number" if count == 1 else f"{count} numbers"
        capped = not isinstance(value, str) and len(items) > count   # _leaves stopped
        got = f"more than {count}" if capped else str(len(items))
        raise fail(f"takes {shape}, got {got} ({brief(value)})")
    numbers = []
    for item in items:
        if isinstance(item, (bool, np.bool_)):
            numbers.append(float(item))
        elif isinstance(item, (int, float, np.integer, np.floating)) and _finite(item):
            numbers.append(item)
        else:
            raise fail(f"{brief(item)} is not a finite number")
    shape = (*param.array, *((param.type.rows, param.type.cols) if param.type.rows > 1 else
                             (param.type.cols,) if param.type.cols > 1 else ()))
    if base in ("float", "half"):
        return np.asarray(numbers, np.float32).reshape(shape)
    if base == "bool":
        return (np.asarray(numbers, np.float64) != 0).reshape(shape)
    if any(float(n) != int(n) for n in numbers):
        raise fail(f"an {base} parameter takes whole numbers, got {brief(value)}")
    if base == "dword":
        if any(not 0 <= int(n) <= 0xFFFFFFFF for n in numbers):
            raise fail(f"a DWORD is 0..0xFFFFFFFF, got {brief(value)}")
        return np.asarray([int(n) for n in numbers], np.int64).reshape(shape)
    if any(not -2**31 <= int(n) < 2**31 for n in numbers):
        raise fail(f"an int is 32 bits, got {brief(value)}")
    return np.asarray([int(n) for n in numbers], np.int32).reshape(shape)


def _leaves(value: Any, most: int) -> list[Any]:
    """The items of a value given as a number or (nested) lists, tuples and arrays, in order,
    without recursion (a list nested 100,000 deep is data, not a stack) and no more than
    `most` of them (lists that share sublists can stand for more items than memory holds)."""
    out: list[Any] = []
    stack: list[Any] = [value]
    while stack and len(out) < most:
        item = stack.pop()
        if isinstance(item, np.ndarray):
            item = item.reshape(-1)[:most].tolist() if item.ndim else item.item()
        if isinstance(item, (list, tuple)):
            stack.extend(reversed(item[:most]))
        else:
            out.append(item)
    return out


def _finite(number: Any) -> bool:
    """A number that is finite as a float (a huge Python int is not, and float() refuses it)."""
    try:
        return math.isfinite(float(number))
    except OverflowError:
        return False


def lookup_parameter(effect: Effect, name: str, at: Location | None = None,
                     source: str = "parameter") -> Parameter:
    """The effect's parameter `name`, or a SceneError listing the ones a user can set."""
    param = effect.parameter(name)
    if param is not None:
        return param
    settable = [p.name for p in effect.parameters if p.type.is_numeric or p.type.base in ("texture", "string")]
    raise SceneError(f"{source} {name!r}: {effect.path} has no parameter of that name "
                     f"(settable: {', '.join(settable) or 'none'})", at or Location(effect.path, 1, 1))
