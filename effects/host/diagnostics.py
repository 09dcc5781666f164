"""Why a picture looks as it does: located warnings about what a render drew (issue 32).

A technique that reads a parameter nothing sets reads 0; a pass state can cull the mesh's
front faces, test every pixel away or write no colour; and the frame that comes back is then
one colour. A previewer that says nothing about it leaves a user with a black frame, exit 0.
`diagnose_frame` looks at a finished frame and the runtime that drew it and returns one
`EffectWarning` per cause found, each at the line of the parameter or the state involved:

- a parameter the technique reads that nothing sets (no initialiser, no host convention,
  scene params or --set): which state or shader constant it feeds and what 0 does there
  ("ColorWriteEnable reads colorWriteEnable = 0: no colour is written");
- a cull mode that culls the faces of the scene's mesh that face the camera (Direct3D's front
  faces are clockwise on screen; `effects.assets.meshes` winds every mesh that way);
- an alpha test, blend, depth or stencil test that no pixel can pass, and ColorWriteEnable = 0;
- a frame that is one colour, with the likely causes (the ones above, texture stand-ins, the
  fixed-function lighting with no light).

`effects render`, `effects matrix --render` and the viewer print them; `--strict` makes them
errors. `parameters_read` (what a technique reads) is shared with `effects doctor`.
"""
from __future__ import annotations

import re
from typing import TYPE_CHECKING, Any, Iterable

import numpy as np

from effects.base.errors import EffectError, EffectWarning, Location
from effects.host.semantics import host_would_set
from effects.model import (CompileShader, Effect, Expression, NullValue, Parameter, ParamRef,
                           SamplerState, ShaderBlock, StateAssignment, Technique)

if TYPE_CHECKING:  # pragma: no cover
    from effects.host.runtime import Runtime

_NAME = re.compile(r"[A-Za-z_]\w*")


def parameters_read(effect: Effect, technique: Technique) -> set[str]:
    """The parameters the technique's passes read: the uniforms of each compiled shader (its
    register table, int and bool registers), a shader picked from an array by an expression
    (the element the values pick, and what the index reads), and the parameters its states
    name (`<Light>`, `VertexShaderConstant[4] = Bias * 2`), sampler states included."""
    read: set[str] = set()
    for p in technique.passes:
        for a in p.states:
            for name, _ in _reads(effect, a.value):
                read.add(name)
    return read


def _reads(effect: Effect, v: Any) -> Iterable[tuple[str, Any]]:
    """(parameter name, the compiled shader that reads it as a uniform, or None) for a state
    value: see `parameters_read`."""
    names = {p.name for p in effect.parameters}
    if isinstance(v, (CompileShader, ShaderBlock)):
        from effects.shaders.shader_value import shader_of
        try:
            shader = shader_of(effect, v)
        except EffectError:
            return                       # validation says why; nothing is read
        compiled = getattr(shader, "compiled", None)
        if compiled is None:
            return
        for n in (*compiled.constants, *compiled.int_registers, *compiled.bool_registers):
            if not n.startswith("$") and n not in compiled.preshaders:
                yield n, compiled
        for preshader in compiled.preshaders.values():   # what the host computes from
            for n in preshader.uniforms():
                if not n.startswith("$"):
                    yield n, compiled
        if isinstance(v, CompileShader):
            for arg in v.args:
                for n in _NAME.findall(arg):
                    if n in names:
                        yield n, None
    elif isinstance(v, ParamRef):
        yield v.name, None
        param = effect.parameter(v.name)
        inner = None if param is None else param.value
        if isinstance(inner, (list, tuple)) and v.index is not None and 0 <= v.index < len(inner):
            yield from _reads(effect, inner[v.index])
        elif not isinstance(inner, (list, tuple, np.ndarray)) and inner is not None:
            yield from _reads(effect, inner)      # `VertexShader = <vs>`, `Sampler = <S>`
    elif isinstance(v, Expression):
        for n in _NAME.findall(v.text):
            if n in names:
                yield n, None
        from effects.shaders.hlsl.preshader import expression_element
        try:
            element = expression_element(effect, v)
        except EffectError:
            element = None
        if element is not None:
            yield from _reads(effect, element)
    elif isinstance(v, SamplerState):
        for a in v.states:
            yield from _reads(effect, a.value)


# What 0 does in a state that reads a parameter nothing sets (D3DRENDERSTATETYPE and the
# effect states' documentation): one row per state whose 0 shows in the picture.
STATE_ZERO = {
    "colorwriteenable": "no colour is written",
    "worldtransform": "a zero world matrix: every vertex lands on one point, nothing is drawn",
    "viewtransform": "a zero view matrix: every vertex lands on one point, nothing is drawn",
    "projectiontransform": "a zero projection: every vertex has w = 0, nothing is drawn",
    "materialdiffuse": "a black diffuse material",
    "materialambient": "a black ambient material",
    "materialemissive": "no emissive colour",
    "lightdiffuse": "a black light",
    "lightdirection": "a zero light direction: the light lights nothing",
    "lightenable": "the light is off",
    "lighting": "the fixed-function lighting is off",
    "texturefactor": "a black texture factor (TFACTOR is 0)",
    "alphablendenable": "blending is off",
    "alphatestenable": "the alpha test is off",
    "alpharef": "the alpha test compares with 0",
    "zenable": "the depth test is off",
    "vertexshaderconstant": "the vertex shader's constant is 0",
    "pixelshaderconstant": "the pixel shader's constant is 0",
}
_COLOUR_WORDS = ("color", "colour", "diffuse", "ambient", "specular", "emissive", "tint", "albedo")
_FACTOR_WORDS = ("intensity", "strength", "scale", "amount", "opacity", "brightness", "power")


def zero_meaning(param: Parameter, stage: str | None = None) -> str:
    """What a shader reading 0 from `param` likely shows, from its type and name (a guess,
    said as one): a matrix, a light direction, a colour, a factor; '' when nothing is known."""
    name = param.name.lower()
    if param.type.rows > 1 and param.type.cols > 1:
        return ("a zero matrix: the positions it transforms are all 0 (nothing is drawn)"
                if stage == "vertex" else "a zero matrix: what it transforms is 0")
    if "light" in name and ("dir" in name or "vec" in name):
        return "a zero light direction: every lit term (N·L) is 0"
    if any(w in name for w in _COLOUR_WORDS):
        return "a zero colour: black (alpha 0)"
    if any(w in name for w in _FACTOR_WORDS):
        return "a zero factor: what it scales is 0"
    return ""


def _state_key(name: str) -> str:
    return re.sub(r"\[.*$", "", name).lower()


def _unset(runtime: "Runtime") -> dict[str, Parameter]:
    """Numeric parameters nothing set: no initialiser, no host convention, no scene params or
    --set (they read 0)."""
    return {p.name: p for p in runtime.effect.parameters
            if p.value is None and p.type.is_numeric}


def unset_parameter_warnings(runtime: "Runtime", technique: Technique
                             ) -> tuple[list[EffectWarning], set[str]]:
    """One warning for each state, and each shader, that reads a parameter nothing sets; and
    the states (lower case, no index) so warned."""
    effect = runtime.effect
    unset = _unset(runtime)
    out: list[EffectWarning] = []
    said: set[tuple[str, str]] = set()
    states: set[str] = set()
    for pass_ in technique.passes:
        where = f"pass {pass_.name}" if pass_.name else "a pass"
        for a in pass_.states:
            for name, compiled in _reads(effect, a.value):
                if name not in unset:
                    continue
                param = unset[name]
                if compiled is None:
                    key = (name, a.name)
                    if key in said:
                        continue
                    said.add(key)
                    states.add(_state_key(a.name))
                    state = a.name if a.index is None else f"{a.name}[{a.index}]"
                    what = STATE_ZERO.get(_state_key(a.name), "the state takes 0")
                    out.append(EffectWarning(
                        f"{where}: {state} reads {name} = 0, which nothing sets: {what}"
                        f" (declared at {param.location}; set it with --set {name}=...)",
                        a.location))
                else:
                    key = (name, compiled.target)
                    if key in said:
                        continue
                    said.add(key)
                    reg = compiled.constants.get(name)
                    register = f" (c{reg[0]})" if reg else ""
                    meaning = zero_meaning(param, compiled.stage)
                    whose = host_would_set(param)
                    out.append(EffectWarning(
                        f"parameter {name} is set by nothing (no initialiser, no semantic or "
                        f"name a host binds, no scene params or --set): the {compiled.target} "
                        f"{compiled.stage} shader of {where} reads it{register} as 0"
                        f"{': ' + meaning if meaning else ''}{'; ' + whose if whose else ''}",
                        param.location))
    return out, states


def _assignment(technique: Technique, index: int, state: str) -> StateAssignment | None:
    """The assignment of `state` that holds in pass `index` (states persist into later passes)."""
    for p in reversed(technique.passes[:index + 1]):
        for a in reversed(p.states):
            if a.name.lower() == state.lower():
                return a
    return None


def _at(technique: Technique, index: int, state: str) -> Location:
    a = _assignment(technique, index, state)
    return a.location if a is not None else technique.passes[index].location


_CULL_COUNTS: dict[tuple, tuple[Any, tuple[int, int]]] = {}   # the viewer redraws often


def _culled_front(runtime: "Runtime", mode: str) -> tuple[int, int] | None:
    """(faces toward the camera the cull mode culls, faces toward the camera) of the scene's
    mesh seen by the scene camera, or None for a mesh written in the scene."""
    from effects.host.resources import scene_mesh
    from effects.host.scene import InlineMesh
    mesh = scene_mesh(runtime.scene)
    if isinstance(mesh, InlineMesh) or len(mesh.indices) == 0:
        return None
    m = runtime.scene.matrices(runtime.size)
    key = (id(mesh), mode, tuple(runtime.scene.camera.eye),
           *(np.asarray(m[k], np.float64).tobytes() for k in ("world", "view", "projection")))
    hit = _CULL_COUNTS.get(key)
    if hit is not None and hit[0] is mesh:        # the mesh kept: its id is not reused
        return hit[1]
    counts = _count_culled(mesh, m, runtime.scene.camera.eye, mode)
    if len(_CULL_COUNTS) >= 64:
        _CULL_COUNTS.clear()
    _CULL_COUNTS[key] = (mesh, counts)
    return counts


def _count_culled(mesh: Any, m: dict[str, np.ndarray], eye_at: Any, mode: str) -> tuple[int, int]:
    tri = np.asarray(mesh.indices, np.int64)
    pos = np.asarray(mesh.positions, np.float64)
    if mesh.space == "clip":
        clip = np.concatenate([pos, np.ones((len(pos), 1))], axis=1)
        facing = np.ones(len(tri), bool)     # the quad faces the screen (meshes.quad)
    else:
        world = np.concatenate([pos, np.ones((len(pos), 1))], axis=1) @ m["world"]
        clip = world @ m["view"] @ m["projection"]
        # the outward normal (cross(b - a, c - a), the meshes' convention) in world space
        a, b, c = (pos[tri[:, k]] for k in range(3))
        normal = np.cross(b - a, c - a) @ np.linalg.inv(m["world"][:3, :3]).T
        centre = world[tri].mean(axis=1)[:, :3] / world[tri].mean(axis=1)[:, 3:4]
        eye = np.asarray(eye_at, np.float64)
        facing = np.einsum("ij,ij->i", normal, eye - centre) > 0
    w = clip[:, 3]
    ok = (w[tri] > 1e-9).all(axis=1)
    ndc = clip[:, :2] / np.where(np.abs(w) > 1e-9, w, 1.0)[:, None]
    a, b, c = (ndc[tri[:, k]] for k in range(3))
    area = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    # NDC has y up: a triangle clockwise on screen has a negative signed area here
    culled = area > 0 if mode == "CCW" else area < 0
    front = facing & ok & (area != 0)
    return int((front & culled).sum()), int(front.sum())


def state_warnings(runtime: "Runtime", technique: Technique,
                   unset_states: set[str] = frozenset()) -> list[EffectWarning]:
    """Pass states that leave nothing to see: front faces culled, every pixel tested away,
    no colour written."""
    out: list[EffectWarning] = []
    mesh_name = runtime.scene.mesh if isinstance(runtime.scene.mesh, str) else "inline mesh"
    for index, pass_ in enumerate(technique.passes):
        where = f"pass {pass_.name}" if pass_.name else f"pass {index}"
        try:
            rs = runtime.lower(technique, index).render_state
        except (EffectError, RuntimeError):
            continue                       # the render said why
        if rs.color_write_enable == 0 and "colorwriteenable" not in unset_states:
            out.append(EffectWarning(f"{where}: ColorWriteEnable = 0: no colour is written",
                                     _at(technique, index, "ColorWriteEnable")))
        if rs.cull_mode in ("CW", "CCW"):
            counts = _culled_front(runtime, rs.cull_mode)
            if counts is not None and counts[0] * 2 > counts[1]:
                out.append(EffectWarning(
                    f"{where}: CullMode = {rs.cull_mode} culls the front faces of the scene's "
                    f"{mesh_name} ({counts[0]} of the {counts[1]} faces toward the camera): "
                    "its inside is what shows, or nothing. Direct3D's front faces are clockwise "
                    "on screen and CullMode = CCW (the default) culls the back ones; a file "
                    "written for a right-handed tool (3ds Max) sets CW for its own meshes",
                    _at(technique, index, "CullMode")))
        if rs.alpha_test_enable and _alpha_test_passes_nothing(rs.alpha_func, rs.alpha_ref):
            out.append(EffectWarning(
                f"{where}: AlphaFunc = {rs.alpha_func} with AlphaRef = {rs.alpha_ref}: the alpha "
                "test discards every pixel", _at(technique, index, "AlphaFunc")))
        if rs.alpha_blend_enable and rs.blend_op == "ADD" and rs.src_blend == "ZERO" \
                and rs.dest_blend == "ONE":
            out.append(EffectWarning(
                f"{where}: SrcBlend = ZERO, DestBlend = ONE: the blend keeps the target as it "
                "was, nothing drawn shows", _at(technique, index, "SrcBlend")))
        if rs.z_enable and rs.z_func == "NEVER":
            out.append(EffectWarning(f"{where}: ZFunc = NEVER: every pixel fails the depth test",
                                     _at(technique, index, "ZFunc")))
        if rs.stencil_enable and rs.stencil_func == "NEVER":
            out.append(EffectWarning(
                f"{where}: StencilFunc = NEVER: every pixel fails the stencil test",
                _at(technique, index, "StencilFunc")))
    return out


def _alpha_test_passes_nothing(func: str, ref: int) -> bool:
    """No 8-bit alpha (0..255) passes `alpha func ref` (D3DCMPFUNC)."""
    return func == "NEVER" or (func == "GREATER" and ref >= 255) or (func == "LESS" and ref <= 0)


def _likely_causes(runtime: "Runtime", technique: Technique) -> list[str]:
    """What else may make a picture one colour: states that can discard or hide what is
    drawn, stand-in textures, the fixed-function lighting with no light."""
    causes: list[str] = []
    for index, pass_ in enumerate(technique.passes):
        try:
            rs = runtime.lower(technique, index).render_state
        except (EffectError, RuntimeError):
            continue
        if rs.alpha_test_enable and rs.alpha_func not in ("ALWAYS",):
            causes.append(f"the alpha test (AlphaFunc = {rs.alpha_func}, AlphaRef = "
                          f"{rs.alpha_ref}) discards pixels whose alpha fails it")
        if rs.alpha_blend_enable and "SRCALPHA" in (rs.src_blend, rs.dest_blend):
            causes.append(f"blending with SrcBlend = {rs.src_blend}, DestBlend = "
                          f"{rs.dest_blend}: a pixel whose alpha is 0 leaves the target as it was")
        if _unlit_fixed_function(technique, index):
            causes.append("the fixed-function lighting is on (Lighting defaults to TRUE) and "
                          "no light is enabled: vertex colours are the material's ambient times "
                          "Ambient, black unless the effect sets them")
    return list(dict.fromkeys(causes))


def _stand_in_cause(runtime: "Runtime", technique: Technique) -> list[str]:
    """The textures drawn with stand-ins, as a (weak) cause: a checker rarely makes a frame
    one colour, but a stand-in where a mask or a look-up table was meant can."""
    if not runtime.warnings or not technique.passes:
        return []
    return ["textures drawn with stand-ins (warned above): "
            + ", ".join(sorted({w.message.split(":")[0] for w in runtime.warnings}))]


def _unlit_fixed_function(technique: Technique, index: int) -> bool:
    """The pass has no vertex shader, Lighting is on and no LightEnable is true."""
    vs = _assignment(technique, index, "VertexShader")
    if vs is not None and not isinstance(vs.value, NullValue) and vs.value is not None:
        return False
    lighting = _assignment(technique, index, "Lighting")
    if lighting is not None and not _truthy(lighting.value):
        return False
    for p in technique.passes[:index + 1]:
        if any(a.name.lower() == "lightenable" and _truthy(a.value) for a in p.states):
            return False
    return True


def _truthy(value: Any) -> bool:
    if isinstance(value, (ParamRef, Expression)):
        return True                  # set by the effect: not judged here
    if isinstance(value, str):
        return value.strip().upper() not in ("FALSE", "0")
    try:
        return bool(np.asarray(value).any())
    except (TypeError, ValueError):
        return True


def uniform_colour(image: np.ndarray) -> tuple[int, int, int] | None:
    """The frame's one colour (r, g, b), or None when it has more than one. The viewer asks
    after every redraw: a sparse look first (a picture rarely agrees there), then every
    pixel as one 32-bit word each, alpha masked off."""
    if image.size == 0:
        return None
    first = image[0, 0, :3]
    if not (image[::17, ::13, :3] == first).all():
        return None
    words = np.ascontiguousarray(image).view(np.uint32) & np.uint32(
        0xFFFFFF if np.little_endian else 0xFFFFFF00)
    if not (words == words.flat[0]).all():
        return None
    return tuple(int(c) for c in first)  # type: ignore[return-value]


def diagnose_frame(runtime: "Runtime", technique: Technique, image: np.ndarray) -> list[EffectWarning]:
    """The located warnings about a frame `runtime` drew with `technique` (see the module
    docstring). The viewer calls it after each redraw; `render_frame(diagnose=True)` too."""
    unset, unset_states = unset_parameter_warnings(runtime, technique)
    out = unset + state_warnings(runtime, technique, unset_states)
    if not technique.passes:
        out.append(EffectWarning(f"technique {technique.name or '<anonymous>'} has no passes: it "
                                 "draws nothing (a host's placeholder, such as MikuMikuEffect's "
                                 "empty shadow and edge techniques)", technique.location))
    colour = uniform_colour(image)
    if colour is not None:
        clear_rgba = np.array([int(round(min(max(c, 0.0), 1.0) * 255))
                               for c in runtime.scene.clear_color[:4]], np.uint8)
        clear = tuple(int(c) for c in clear_rgba[:3])
        drawn = "the clear colour: nothing was drawn, or drawn in that colour" \
            if colour == clear else "what was drawn is that colour everywhere"
        causes = [w.message.split(" (")[0] for w in out] + _likely_causes(runtime, technique)
        weak = _stand_in_cause(runtime, technique)
        if not causes and technique.passes and \
                (image.reshape(-1, image.shape[-1]) == clear_rgba).all():
            # not even the alpha changed, and nothing else explains it: likely no pixel was
            # written at all (a pixel drawn in the clear colour, alpha too, looks the same)
            causes.append("no pixel was written: the mesh may lie outside the view (past the "
                          f"near or far plane, {runtime.scene.camera.near:g} and "
                          f"{runtime.scene.camera.far:g} here, or behind the camera) as the "
                          "vertex shader places it, or every pixel was discarded")
        causes += weak
        said = "; ".join(dict.fromkeys(causes)) if causes else (
            "no cause found by these checks: the shaders compute this colour from the values "
            "bound (`effects doctor` lists them)")
        out.append(EffectWarning(f"the frame is one colour {colour} ({drawn}); likely causes: {said}",
                                 technique.location))
    return list(dict.fromkeys(out))
