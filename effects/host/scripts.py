"""DXSAS `Script` annotations: the render-target chain of post-processing effects.

FX Composer and NVIDIA's shader library write, on a technique and its passes, a
`string Script = "Cmd=Value;Cmd=Value;..."` annotation that tells the host what to draw where
(the DirectX SDK's "DXSAS" convention, version 0.8 / 1.0). The commands run here:

| command | what the host does |
|---|---|
| `RenderColorTarget0=Tex` / `RenderColorTarget=Tex` | draw into texture parameter `Tex` from now on; empty: the back buffer |
| `RenderDepthStencilTarget=Tex` | accepted: every target here has its own depth-stencil buffer |
| `ClearSetColor=P`, `ClearSetDepth=P` | the clear colour / depth, from parameter `P` |
| `Clear=Color`, `Clear=Depth`, `Clear=Stencil` | clear the current target |
| `Pass=P` | run pass `P`: its own `Script` (default `Draw=Geometry`) |
| `Draw=Geometry` | draw the scene's mesh with the current pass |
| `Draw=Buffer` | draw a full-screen quad (clip space, identity transforms; uv 0..1, row 0 at v = 0) |
| `LoopByCount=P` … `LoopEnd=` | repeat the commands between, `P` (a parameter or a number) times |
| `ScriptExternal=color` | draw the scene there: the mesh with a plain lit, checker-textured material (`SCENE_MATERIAL`), as FX Composer draws the rest of its scene; `ScriptExternal=` (empty) draws nothing |
| `Technique=T`, `ScriptSignature=`, `ScriptOrder=`… | not run (a warning; `effects doctor` lists them) |

Render-target textures are texture parameters with the `RenderColorTarget` or
`RenderDepthStencilTarget` semantic; their size is `float2 ViewportRatio = {x, y}` times the
frame size, or `int2 Dimensions = {w, h}` (or `Width`/`Height`), default the frame's; their
format `string Format = "..."` where a back end can render it (else A8R8G8B8). A technique with
a `Script` annotation draws only what its script says; without one, every pass once, as D3DX.
Each target is drawn in one back-end frame (`effects.program.backend`): switching targets ends the
frame and the finished picture becomes that texture parameter's texture (one mip level).

Scripts are effect data from strangers: they run without recursion (a stack of running
scripts), a `Pass=` leading back to a pass still running is an error naming the chain, every
command counts against the `script_commands` limit and every draw against `script_draws`,
each command's numbers are checked (finite; a clear depth from 0 to 1), and a target's size
is checked against `texture_edge` and `target_pixels_<back end>` before a frame is begun for
it (`target_extent`).

Cube render targets (FX Composer's spelling: `string ResourceType = "Cube"` on the target, or a
`textureCUBE` declaration) are drawn face by face, as a host draws an omni light's shadow map:
their size is `int Width` (or `Dimensions`, square; default 256), and `string CubeOrigin = "P"`
names the float3/float4 parameter the faces look out from (a light position).
The draws a script makes into the cube are kept until the target is switched, then replayed
into each of the six faces (`effects.program.backend.render_cube_faces`, D3D face order) with the host's
view transform and every parameter with a transform semantic (WORLDVIEWPROJECTION, VIEW, ...)
set to the face's: a left-handed look-at from the origin along CUBE_FACE_VIEWS, and a 90° square
perspective over `float2 CubeDepthRange = {near, far}` (default {0.05, 100}).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Mapping, Protocol

import numpy as np

import math

from effects.program.backend import CUBE_FACE_VIEWS, render_cube_faces
from effects.program.formats import TARGET_FORMATS
from effects.base import limits
from effects.base.errors import EffectError, EffectWarning, Location
from effects.model import Annotation, Effect, Parameter, Technique
from effects.host.resources import Geometry
from effects.host.scene import look_at_lh, perspective_fov_lh
from effects.host.semantics import bind_transforms
from effects.assets.textures import make_texture
from effects.program.texture import Texture
from effects.host.scene import Scene

if TYPE_CHECKING:  # pragma: no cover
    from effects.program.passprogram import PassProgram


class ScriptHost(Protocol):
    """What a script needs of the runtime that runs it (`effects.host.runtime.Runtime`): the
    effect with this render's values, the scene, the back end, and the draws it asks for."""

    effect: Effect
    scene: Scene
    size: tuple[int, int]
    strict: bool
    warnings: list[EffectWarning]
    backend: Any

    def lower(self, technique: Technique, index: int,
              host: Mapping[str, Any] | None = None) -> "PassProgram": ...
    def draw_program(self, program: "PassProgram", geo: Geometry | None = None,
                     backend: Any = None) -> None: ...
    def used_texture(self, name: str, sampled_as: str | None = None) -> Texture: ...
    def set_target_texture(self, name: str, texture: Texture) -> None: ...
    def copy_runtime(self) -> "ScriptHost": ...
    def scene_material_runtime(self) -> "ScriptHost": ...

MAX_LOOP_COUNT = 256          # LoopByCount above this is an error, not a hang
# What one frame's script may spend is bounded by the named limits `script_commands` and
# `script_draws` (effects.base.limits); its render targets by `texture_edge` and
# `target_pixels_<back end>`, checked before a target is allocated.

COMMANDS = {
    "rendercolortarget0": "RenderColorTarget0", "rendercolortarget": "RenderColorTarget0",
    "renderdepthstenciltarget": "RenderDepthStencilTarget", "clearsetcolor": "ClearSetColor",
    "clearsetdepth": "ClearSetDepth", "clearsetstencil": "ClearSetStencil", "clear": "Clear",
    "pass": "Pass", "draw": "Draw", "loopbycount": "LoopByCount", "loopend": "LoopEnd",
    "scriptexternal": "ScriptExternal",
}
TARGET_SEMANTICS = ("RENDERCOLORTARGET", "RENDERDEPTHSTENCILTARGET")

# What `ScriptExternal=color` draws: the rest of the scene, with the plain material a tool
# gives objects that have none (a lit white checker). Itself an effect, so it goes through
# the same front end and lowering as any other.
SCENE_MATERIAL = """
texture SceneChecker < string Procedural = "checker"; >;
float3 SceneLightDirection : LIGHTDIRECTION = {0.577, -0.577, -0.577};
technique Scene { pass P0 {
    Lighting = true; LightEnable[0] = true; LightType[0] = Directional;
    LightDirection[0] = <SceneLightDirection>; LightDiffuse[0] = {1, 1, 1, 1};
    LightAmbient[0] = {0.2, 0.2, 0.2, 1}; MaterialDiffuse = {1, 1, 1, 1};
    MaterialAmbient = {1, 1, 1, 1}; Texture[0] = <SceneChecker>; MinFilter[0] = Linear;
    MagFilter[0] = Linear; MipFilter[0] = Linear;
    ColorOp[0] = Modulate; ColorArg1[0] = Texture; ColorArg2[0] = Diffuse;
    AlphaOp[0] = SelectArg1; AlphaArg1[0] = Diffuse;
} }
"""


# The host's copy of a target's earlier picture back into it (see ScriptRunner._restore).
COPY_PICTURE = """
texture Picture;
technique Copy { pass P0 {
    Lighting = false; ZEnable = false; CullMode = None; AlphaBlendEnable = false;
    Texture[0] = <Picture>; MinFilter[0] = Point; MagFilter[0] = Point; MipFilter[0] = None;
    AddressU[0] = Clamp; AddressV[0] = Clamp;
    ColorOp[0] = SelectArg1; ColorArg1[0] = Texture; AlphaOp[0] = SelectArg1; AlphaArg1[0] = Texture;
} }
"""


@dataclass(frozen=True)
class Command:
    name: str            # canonical name (COMMANDS), or as written when unknown
    value: str
    known: bool
    location: Location   # the Script annotation's


def _shown(text: str) -> str:
    """A script's text in a message, cut short (a script may be as long as its effect)."""
    return text if len(text) <= 60 else text[:57] + "..."


def parse_script(text: str, at: Location) -> list[Command]:
    """'Cmd=Value;...' as commands (blank entries skipped; a missing '=' is an error)."""
    out = []
    for item in text.split(";"):
        item = item.strip()
        if not item:
            continue
        name, eq, value = item.partition("=")
        if not eq:
            raise EffectError(f"script command {item!r} is not NAME=VALUE", at)
        canonical = COMMANDS.get(name.strip().lower())
        out.append(Command(canonical or name.strip(), value.strip(), canonical is not None, at))
    return out


def script_of(annotations: list[Annotation]) -> list[Command] | None:
    """The commands of a `string Script` annotation, or None when there is none."""
    for a in annotations:
        if a.name.lower() == "script" and isinstance(a.value, str):
            return parse_script(a.value, a.location)
    return None


def technique_script(technique: Technique) -> list[Command] | None:
    return script_of(technique.annotations)


def is_render_target(param: Parameter) -> bool:
    return param.type.base == "texture" and (param.semantic or "").upper() in TARGET_SEMANTICS


def unsupported_commands(effect: Effect, technique: Technique) -> list[Command]:
    """Script commands of the technique and its passes that are not run."""
    commands = list(technique_script(technique) or [])
    for p in technique.passes:
        commands.extend(script_of(p.annotations) or [])
    return [c for c in commands if not c.known or
            (c.name == "ScriptExternal" and c.value.lower() not in ("", "color"))]


def _numbers(value: Any) -> list[float]:
    return [float(x) for x in np.asarray(value, np.float64).reshape(-1)]


def _size_numbers(param: Parameter, name: str) -> tuple[Annotation, list[float]] | None:
    """The numbers of size annotation `name` of render target `param` (None when it is absent
    or a string), each finite and not negative, else a located error at the annotation."""
    ann = param.annotation(name)
    if ann is None or isinstance(ann.value, str):
        return None
    try:
        values = _numbers(ann.value)
    except (TypeError, ValueError):
        values = [math.nan]
    if not values or not all(math.isfinite(v) and v >= 0 for v in values):
        shown = ", ".join(f"{v:g}" for v in values[:4]) + (", ..." if len(values) > 4 else "")
        raise EffectError(f"render target {param.name}: {name} = {{{shown}}} must be finite "
                          "numbers, not negative", ann.location)
    return ann, values


def _edge(value: float, ann: Annotation, param: Parameter) -> int:
    """One edge in pixels (at least 1), within `texture_edge`: the target becomes a texture."""
    edge = max(1, int(value))
    if edge > limits.get("texture_edge"):
        raise EffectError(limits.message("texture_edge", edge, f"render target {param.name}"),
                          ann.location)
    return edge


def target_size(param: Parameter, frame: tuple[int, int]) -> tuple[int, int]:
    """A render target's size: Dimensions, Width/Height, ViewportRatio × frame, or the frame's.
    A size that is not finite, is negative or has an edge over `texture_edge` is a located
    error at its annotation."""
    dims = _size_numbers(param, "Dimensions")
    if dims is not None and len(dims[1]) >= 2:
        (ann, (w, h)) = dims[0], dims[1][:2]
        return _edge(w, ann, param), _edge(h, ann, param)
    width, height = _size_numbers(param, "Width"), _size_numbers(param, "Height")
    if width is not None and height is not None:
        return _edge(width[1][0], width[0], param), _edge(height[1][0], height[0], param)
    ratio = _size_numbers(param, "ViewportRatio")
    if ratio is not None:
        ann, r = ratio
        rx, ry = r[0], r[1] if len(r) > 1 else r[0]
        return _edge(round(frame[0] * rx), ann, param), _edge(round(frame[1] * ry), ann, param)
    return frame


DEFAULT_CUBE_SIZE = 256
DEFAULT_CUBE_RANGE = (0.05, 100.0)


def is_cube_target(param: Parameter) -> bool:
    """A render target drawn as a cube map: `ResourceType = "Cube"` or a textureCUBE."""
    return param.declared_texture_kind == "cube"


def cube_size(param: Parameter) -> int:
    """A cube target's edge: Dimensions or Width (square), default 256; checked as target_size."""
    size = _size_numbers(param, "Dimensions") or _size_numbers(param, "Width")
    if size is not None:
        return _edge(size[1][0], size[0], param)
    return DEFAULT_CUBE_SIZE


def target_extent(param: Parameter, frame: tuple[int, int], backend: str) -> tuple[int, int, int]:
    """(width, height, faces) of render target `param` on back end `backend` (a cube has six
    faces), all its pixels checked against `target_pixels_<backend>` before anything is
    allocated for it (a back end without a limit of its own is held to the numpy one's)."""
    if is_cube_target(param):
        w = h = cube_size(param)
        faces = 6
    else:
        (w, h), faces = target_size(param, frame), 1
    name = f"target_pixels_{backend}"
    name = name if name in limits.LIMITS else "target_pixels_numpy"
    shape = f"{w} x {h}" + (" x 6 cube" if faces == 6 else "")
    limits.check(name, w * h * faces, _size_location(param), f"render target {param.name} ({shape})")
    return w, h, faces


def _size_location(param: Parameter) -> Location:
    """Where a target's size is written: its size annotation, else its declaration."""
    for name in ("Dimensions", "Width", "ViewportRatio"):
        ann = param.annotation(name)
        if ann is not None and not isinstance(ann.value, str):
            return ann.location
    return param.location


def cube_face_matrices(param: Parameter, effect: Effect, world: np.ndarray) -> list[dict[str, np.ndarray]]:
    """world/view/projection of each face (D3D order) of cube target `param`."""
    at = param.location
    origin_ann = param.annotation("CubeOrigin")
    if origin_ann is None or not isinstance(origin_ann.value, str):
        raise EffectError(f"cube render target {param.name} needs string CubeOrigin = \"P\" "
                          "naming the parameter its faces look out from", at)
    origin_param = effect.parameter(origin_ann.value)
    if origin_param is None or origin_param.value is None or not origin_param.type.is_numeric:
        raise EffectError(f"cube render target {param.name}: CubeOrigin {origin_ann.value!r} is "
                          "not a numeric parameter with a value", origin_ann.location)
    origin = (_numbers(origin_param.value) + [0.0, 0.0, 0.0])[:3]
    near, far = DEFAULT_CUBE_RANGE
    rng = param.annotation("CubeDepthRange")
    if rng is not None and not isinstance(rng.value, str) and len(_numbers(rng.value)) >= 2:
        near, far = _numbers(rng.value)[:2]
    if not 0 < near < far:
        raise EffectError(f"cube render target {param.name}: CubeDepthRange needs 0 < near < far",
                          rng.location if rng is not None else at)
    projection = perspective_fov_lh(math.pi / 2, 1.0, near, far)
    eye = np.asarray(origin, np.float64)
    return [{"world": world, "view": look_at_lh(eye, eye + look, up), "projection": projection}
            for look, up in CUBE_FACE_VIEWS]


def target_format(param: Parameter) -> str:
    fmt = param.annotation("Format")
    if fmt is not None and isinstance(fmt.value, str):
        name = fmt.value.strip().upper().removeprefix("D3DFMT_")
        if name in TARGET_FORMATS:
            return name
    return "A8R8G8B8"


def quad_geometry(half_pixel: tuple[int, int] | None = None) -> Geometry:
    """The full-screen quad of `Draw=Buffer`: clip-space corners, uv (0, 0) at the top left;
    with `half_pixel` = (w, h), moved half a pixel up-left so pixel centres meet texel centres
    (the D3D9 offset an application applies for a 1:1 copy)."""
    position = np.array([[-1, 1, 0, 1], [1, 1, 0, 1], [-1, -1, 0, 1], [1, -1, 0, 1]], np.float32)
    if half_pixel is not None:
        position[:, 0] -= 1.0 / half_pixel[0]
        position[:, 1] += 1.0 / half_pixel[1]
    uv = np.array([[0, 0], [1, 0], [0, 1], [1, 1]], np.float32)
    streams = {"position": position, "normal": np.tile([0, 0, -1], (4, 1)).astype(np.float32),
               "color0": np.ones((4, 4), np.float32), "color1": np.zeros((4, 4), np.float32),
               **{f"texcoord{i}": uv for i in range(8)}}
    return Geometry(streams, np.arange(4), "strip", False)


IDENTITY_HOST = {"WorldTransform": np.identity(4), "ViewTransform": np.identity(4),
                 "ProjectionTransform": np.identity(4)}


class ScriptRunner:
    """Runs one technique's script on a Runtime, frame by frame of the back end."""

    def __init__(self, runtime: ScriptHost, technique: Technique) -> None:
        self.rt = runtime
        self.technique = technique
        self.target: str | None = None          # the colour target (None: the back buffer)
        self.open = False                       # a back-end frame is open for `target`
        self.drawn_since_open = False
        self.clear_color = tuple(runtime.scene.clear_color)
        self.clear_depth = float(runtime.scene.clear_depth)
        self.clear_pending = True               # the first frame of each target is cleared
        self.back_buffer: np.ndarray | None = None
        self.kept: set[str | None] = set()      # targets holding a finished picture
        self.draws = 0
        self.passes_drawn = 0
        self.cube_draws: list[tuple[int, bool]] = []   # (pass, full-screen?) kept for the faces
        self.commands_run = 0
        # read once a frame: a script may run tens of thousands of commands
        self.command_budget = limits.get("script_commands")
        self.draw_budget = limits.get("script_draws")
        self.backend_name = str(getattr(runtime.backend, "name", "numpy"))

    # -- targets ---------------------------------------------------------------------------
    def _target_param(self, name: str, at: Location) -> Parameter:
        param = self.rt.effect.parameter(name)
        if param is None or param.type.base != "texture":
            raise EffectError(f"script: {repr(_shown(name))} is not a texture parameter of the effect", at)
        return param

    def _frame_of(self, name: str | None) -> tuple[tuple[int, int], str]:
        """The size and format of target `name` (None: the back buffer), its size checked
        against the render-target limits before any frame is begun for it."""
        if name is None:
            return self.rt.size, "A8R8G8B8"
        param = self.rt.effect.parameter(name)
        w, h, _ = target_extent(param, self.rt.size, self.backend_name)
        return (w, h), target_format(param)

    def _cube(self) -> Parameter | None:
        """The current target's parameter when it is a cube target."""
        if self.target is None:
            return None
        param = self.rt.effect.parameter(self.target)
        return param if is_cube_target(param) else None

    def _open(self) -> None:
        if self.open:
            return
        size, fmt = self._frame_of(self.target)
        resume = self.target in self.kept and not self.clear_pending
        if self._cube() is None:
            self.rt.backend.begin_frame(size, self.clear_color, self.clear_depth, 0, format=fmt)
        else:   # drawn at _close, face by face, with the clear values set now
            if resume:
                self.warn(f"script draws into cube target {self.target} again without "
                          "clearing it; its earlier faces are not kept", self.technique.location)
                resume = False
            self.cube_draws, self.cube_clear = [], (self.clear_color, self.clear_depth)
        self.open, self.drawn_since_open, self.clear_pending = True, False, False
        if resume:
            self._restore(size)

    def _restore(self, size: tuple[int, int]) -> None:
        """Drawing into a target again without clearing it: its earlier picture is still
        there on a device, so it is copied back first (a point-sampled quad shifted by half a
        pixel, so each pixel centre reads its own texel). Its depth is not kept."""
        if self.target is None:
            image = self.back_buffer
            picture = make_texture(image.astype(np.float32) / 255.0, mips=False)
        else:
            picture = self.rt.used_texture(self.target)
        copier = self.rt.copy_runtime()
        copier.set_target_texture("Picture", picture)
        program = copier.lower(copier.effect.techniques[0], 0, host=IDENTITY_HOST)
        copier.draw_program(program, quad_geometry(size), backend=self.rt.backend)

    def _abandon(self) -> None:
        """Drop the open frame (a Clear after drawing, or an error)."""
        if self.open and self._cube() is None:
            self.rt.backend.end_frame()
        self.open, self.cube_draws = False, []

    def _close_cube(self, param: Parameter) -> None:
        faces = cube_face_matrices(param, self.rt.effect, self.rt.scene.world)
        saved = {p.name: p.value for p in self.rt.effect.parameters}
        draws = list(self.cube_draws)

        def draw_face(face: int) -> None:
            m = faces[face]
            for name, value in bind_transforms(self.rt.effect, m).items():
                self.rt.effect.parameter(name).value = value
            host = {"WorldTransform": m["world"], "ViewTransform": m["view"],
                    "ProjectionTransform": m["projection"]}
            for index, buffer in draws:
                program = self.rt.lower(self.technique, index,
                                        host=IDENTITY_HOST if buffer else host)
                self.rt.draw_program(program, quad_geometry() if buffer else None)

        _, fmt = self._frame_of(self.target)
        color, depth = self.cube_clear
        try:
            texels = render_cube_faces(self.rt.backend, cube_size(param), draw_face, format=fmt,
                                       clear_color=color, clear_depth=depth)
        finally:
            for p in self.rt.effect.parameters:
                p.value = saved[p.name]
        self.open, self.cube_draws = False, []
        self.kept.add(self.target)
        values = texels.astype(np.float32) / 255.0 if texels.dtype == np.uint8 else texels
        self.rt.set_target_texture(self.target, make_texture(values, fmt, kind="cube", mips=False,
                                                             name=self.target))

    def _close(self) -> None:
        if not self.open:
            return
        cube = self._cube()
        if cube is not None:
            self._close_cube(cube)
            return
        image = self.rt.backend.end_frame()
        self.open = False
        self.kept.add(self.target)
        if self.target is None:
            self.back_buffer = image
            return
        values = image.astype(np.float32) / 255.0 if image.dtype == np.uint8 else image
        _, fmt = self._frame_of(self.target)
        self.rt.set_target_texture(self.target, make_texture(values, fmt, mips=False,
                                                            name=self.target))

    def warn(self, message: str, at: Location) -> None:
        warning = EffectWarning(message, at)
        if self.rt.strict:
            raise EffectError(message, at)
        if warning not in self.rt.warnings:
            self.rt.warnings.append(warning)

    # -- commands --------------------------------------------------------------------------
    def run(self) -> np.ndarray:
        try:
            self.execute(technique_script(self.technique) or [], None)
            if self.target is not None or not self.open:
                self._close()
                self.target = None
                self._open()             # a script that never drew to the screen: cleared
            self._close()
        except BaseException:
            self._abandon()
            raise
        finally:   # what the frame spent of its budgets, on the meter (limits.py)
            limits.measure("script_commands", self.commands_run)
            limits.measure("script_draws", self.draws)
        return self.back_buffer  # type: ignore[return-value]

    def execute(self, commands: list[Command], pass_index: int | None) -> None:
        """Run `commands` (a technique's script when `pass_index` is None, else that pass's),
        and the scripts of the passes they run, without recursion: a stack of running
        scripts, each with its position and its open loops. Every command counts against
        `script_commands`; a `Pass=` that leads back to a pass still running is an error
        naming the chain."""
        stack = [_Running(commands, _loop_ends(commands), pass_index)]
        while stack:
            frame = stack[-1]
            if frame.pc >= len(frame.commands):
                stack.pop()
                if stack and frame.pass_index is not None:
                    self.passes_drawn += 1
                continue
            c = frame.commands[frame.pc]
            self._spend(c)
            if c.name == "LoopByCount":
                end = frame.ends[frame.pc]
                count = self._count(c)
                if count == 0:
                    frame.pc = end + 1
                    continue
                frame.loops.append([frame.pc, count])
                frame.pc += 1
            elif c.name == "LoopEnd":
                loop = frame.loops[-1]       # _loop_ends paired every LoopEnd with its start
                loop[1] -= 1
                if loop[1] > 0:
                    frame.pc = loop[0] + 1
                else:
                    frame.loops.pop()
                    frame.pc += 1
            elif c.name == "Pass":
                index = self._pass_index(c)
                self._refuse_cycle(c, index, stack)
                p = self.technique.passes[index]
                script = script_of(p.annotations) or [Command("Draw", "Geometry", True, p.location)]
                frame.pc += 1
                stack.append(_Running(script, _loop_ends(script), index))
            else:
                self.command(c, frame.pass_index)
                frame.pc += 1

    def _spend(self, c: Command) -> None:
        self.commands_run += 1
        if self.commands_run > self.command_budget:
            raise EffectError(limits.message("script_commands", self.commands_run,
                                             f"script of technique {self.technique.name}"),
                              c.location)

    def _refuse_cycle(self, c: Command, index: int, stack: list["_Running"]) -> None:
        """`Pass=P` inside a script that P's own script (directly or through others) runs."""
        running = [f.pass_index for f in stack if f.pass_index is not None]
        if index not in running:
            return
        names = [self._pass_name(i) for i in running[running.index(index):]]
        chain = " -> ".join([*names, self._pass_name(index)])
        raise EffectError(f"script: Pass={_shown(c.value)} runs pass {self._pass_name(index)}, which is "
                          f"already running ({chain}): a pass's Script cannot lead back to "
                          "itself", c.location)

    def _pass_name(self, index: int) -> str:
        return self.technique.passes[index].name or f"<pass {index}>"

    def _count(self, c: Command) -> int:
        param = self.rt.effect.parameter(c.value)
        try:
            n = int(_numbers(param.value)[0]) if param is not None else int(c.value)
        except (TypeError, ValueError, IndexError, OverflowError):
            raise EffectError(f"script: LoopByCount={_shown(c.value)}: not a number or a numeric "
                              "parameter with a value", c.location) from None
        if not 0 <= n <= MAX_LOOP_COUNT:
            raise EffectError(f"script: LoopByCount={_shown(c.value)} is {n}; at most {MAX_LOOP_COUNT}",
                              c.location)
        return n

    def command(self, c: Command, pass_index: int | None) -> None:
        """One command other than LoopByCount, LoopEnd and Pass (`execute` runs those)."""
        name, value = c.name, c.value
        if not c.known:
            self.warn(f"script command {name}={value} is not supported; ignored", c.location)
        elif name == "RenderColorTarget0":
            target = value or None
            if target is not None:
                self._target_param(target, c.location)
            if target != self.target:
                self._close()
                self.target, self.clear_pending = target, False
        elif name == "RenderDepthStencilTarget":
            if value:
                self._target_param(value, c.location)
        elif name == "ClearSetColor":
            self.clear_color = tuple((self._numbers_of(c, 1, 4) + [0.0] * 4)[:4])
        elif name == "ClearSetDepth":
            depth = self._numbers_of(c, 1, 1)[0]
            if not 0.0 <= depth <= 1.0:   # IDirect3DDevice9::Clear takes Z from 0 to 1
                raise EffectError(f"script: ClearSetDepth={_shown(value)} is {depth:g}; a depth is "
                                  "from 0 to 1", c.location)
            self.clear_depth = depth
        elif name == "ClearSetStencil":
            self._numbers_of(c, 1, 1)   # checked; targets clear stencil to 0
        elif name == "Clear":
            what = value.lower()
            if what not in ("color", "depth", "stencil"):
                raise EffectError(f"script: Clear={value}: expected Color, Depth or Stencil",
                                  c.location)
            if self.open and self.drawn_since_open:
                if what == "color":
                    self._abandon()               # what was drawn is cleared away
                else:
                    self.warn(f"script: Clear={value} after drawing into the same target is "
                              "not supported (the colour would be lost); ignored", c.location)
                    return
            self.clear_pending = True
            if self.open and not self.drawn_since_open:
                self._abandon()                   # reopen with the clear values now set
        elif name == "Draw":
            self.draw(c, pass_index)
        elif name == "ScriptExternal":
            if value.lower() == "color":
                self.draw_scene(c)
            elif not value:
                pass  # `ScriptExternal=;`: hands control back to the host, nothing to draw
            else:
                self.warn(f"script command ScriptExternal={value} is not supported; ignored",
                          c.location)

    def _numbers_of(self, c: Command, least: int, most: int) -> list[float]:
        """The value of `c`: a numeric parameter's value, or numbers written out; `least` of
        them at least, finite (only the first `most` are used)."""
        param = self.rt.effect.parameter(c.value)
        try:
            if param is None or param.value is None:
                numbers = [float(x) for x in c.value.replace(",", " ").split()]
            else:
                numbers = _numbers(param.value)
        except (TypeError, ValueError):
            numbers = None
        if numbers is None or (param is None and not numbers):
            raise EffectError(f"script: {c.name}={_shown(c.value)}: no parameter of that name with "
                              "a value, nor numbers", c.location)
        if len(numbers) < least or not all(math.isfinite(x) for x in numbers[:most]):
            raise EffectError(f"script: {c.name}={_shown(c.value)} needs "
                              f"{least if least == most else f'{least} to {most}'} finite "
                              f"number{'s' if most > 1 else ''}", c.location)
        return numbers[:most]

    def _pass_index(self, c: Command) -> int:
        for match in (lambda n: n == c.value, lambda n: (n or "").lower() == c.value.lower()):
            for i, p in enumerate(self.technique.passes):
                if match(p.name):
                    return i
        names = ", ".join(p.name or "<anonymous>" for p in self.technique.passes)
        raise EffectError(f"script: Pass={c.value}: technique {self.technique.name} has no "
                          f"such pass (passes: {names})", c.location)

    def draw(self, c: Command, pass_index: int | None) -> None:
        what = c.value.lower()
        if what not in ("geometry", "buffer"):
            raise EffectError(f"script: Draw={c.value}: expected Geometry or Buffer", c.location)
        if pass_index is None:
            raise EffectError(f"script: Draw={c.value} outside a pass (write it in a pass's "
                              "Script, or after Pass=)", c.location)
        self._count_draw(c)
        self._open()
        buffer = what == "buffer"
        if self._cube() is not None:      # drawn into every face when the target closes
            self.cube_draws.append((pass_index, buffer))
            self.drawn_since_open = True
            return
        program = self.rt.lower(self.technique, pass_index, host=IDENTITY_HOST if buffer else None)
        self.rt.draw_program(program, quad_geometry() if buffer else None)
        self.drawn_since_open = True

    def draw_scene(self, c: Command) -> None:
        if self._cube() is not None:
            self.warn("script: ScriptExternal into a cube render target is not supported; "
                      "ignored", c.location)
            return
        self._count_draw(c)
        self._open()
        scene_rt = self.rt.scene_material_runtime()
        program = scene_rt.lower(scene_rt.effect.techniques[0], 0)
        scene_rt.draw_program(program, backend=self.rt.backend)
        self.drawn_since_open = True

    def _count_draw(self, c: Command) -> None:
        self.draws += 1
        if self.draws > self.draw_budget:
            raise EffectError(limits.message("script_draws", self.draws,
                                             f"script of technique {self.technique.name}"),
                              c.location)


@dataclass
class _Running:
    """A script being run: its commands, where each LoopByCount's LoopEnd is, the position
    and the open loops ([position of the LoopByCount, rounds left]), and the pass it is the
    script of (None: the technique's)."""

    commands: list[Command]
    ends: dict[int, int]
    pass_index: int | None
    pc: int = 0
    loops: list[list[int]] = field(default_factory=list)


def _loop_ends(commands: list[Command]) -> dict[int, int]:
    """Each LoopByCount's position -> its LoopEnd's, in one pass; an unpaired one is an error."""
    ends: dict[int, int] = {}
    opened: list[int] = []
    for j, c in enumerate(commands):
        if c.name == "LoopByCount":
            opened.append(j)
        elif c.name == "LoopEnd":
            if not opened:
                raise EffectError("script: LoopEnd without LoopByCount", c.location)
            ends[opened.pop()] = j
    if opened:
        raise EffectError("script: LoopByCount without LoopEnd", commands[opened[-1]].location)
    return ends


def render_targets(effect: Effect) -> list[Parameter]:
    return [p for p in effect.parameters if is_render_target(p)]


__all__ = ["Command", "parse_script", "script_of", "technique_script", "ScriptRunner",
           "render_targets", "target_size", "target_extent", "target_format", "is_cube_target",
           "cube_size",
           "cube_face_matrices", "unsupported_commands",
           "quad_geometry", "SCENE_MATERIAL"]
