"""Lowering a pass to a PassProgram: the entry point and dispatcher.

`lower_pass` reads the device state in force for the pass (`effects.device.pass_states`:
D3D9 defaults, earlier passes persisting), resolves it into plain setups, and hands them to
the lowerings: the texture-stage cascade (`lower_stages`), the fixed-function vertex pipeline
(`lower_vertex`), or the shader-assembly lowering (`effects.shaders.asm.lower`) for passes with
shaders. The profile picks the precision (`effects.precision`).

Decisions both back ends rely on:
- **Fog and the specular add are folded into the fragment program.** The vertex program
  writes the `fog` output (the fog factor for vertex fog, the fog distance for table fog: the
  eye depth |z|, or clip z under an orthographic projection, as Wine does), and the fragment
  program blends towards the `fog_color` uniform. This is the one implementation of both:
  `RenderState` has no fog or specular fields and a back end applies neither. Alpha test,
  blending, depth and stencil stay in RenderState.
- Uniform values come from the state and the effect's parameters at lowering time
  (`PassProgram.uniforms`); the names are documented in `lower_stages` and `lower_vertex`.
- An uninitialised parameter reads as zero, as in D3DX.

Passes with shaders assemble them (`effects.shaders.asm`) and lower them with `effects.shaders.asm.lower`;
this module supplies what the pass state says: the constant registers c# (from
VertexShaderConstant[n] / PixelShaderConstant[n]; a matrix parameter fills four registers with
its columns, i.e. transposed, so `m4x4 oPos, v0, c4` computes the row-vector product p·M that
the DX8 files expect; uniforms `vs_c<n>` and `ps_c<n>`, as the two shaders have separate
constant files), the bump-environment state of each stage (uniforms `bumpenv<n>` and
`bumpenvl<n>`), the kind of texture bound to each sampler, and TTFF_PROJECTED per stage.
Fixed-function fog after a pixel shader is not lowered yet (a clear error, not a wrong picture).
"""
from __future__ import annotations

import threading
from dataclasses import dataclass, fields
from typing import TYPE_CHECKING, Any, Callable, Mapping

import numpy as np

from effects import states as state_table
from effects.device import DeviceState, host_states, pass_states
from effects.errors import EffectError, Location
from effects.shaders.asm import assemble_cached
from effects.shaders.asm import lower as asm_lower
from effects.ir import Builder, Program
from effects.lower.stages import (MAX_STAGES, FogSetup, FragmentInputs, StageSetup, apply_fog,
                           lower_cascade)
from effects.lower.vertex import TCI_MODES, LightSetup, TexCoordSetup, VertexSetup, lower_vertex
from effects.model import (CompileShader, Effect, EnumValue, NullValue, Parameter, ParamRef,
                    ShaderBlock, Technique)
from effects.passprogram import PassProgram, RenderState, TextureBinding
from effects.precision import LoweringOptions, lowering_options

if TYPE_CHECKING:  # pragma: no cover
    from effects.shaders.asm import AsmProgram
    from effects.caps import CapsProfile

Color = tuple[float, float, float, float]
CACHE_SIZE = 256


# --------------------------------------------------------------------------------------------
# Public API


def lower_pass(effect: Effect, technique: Technique, pass_index: int,
               profile: "CapsProfile", *, vertex_colors: bool = True,
               host: Mapping[str, Any] | None = None) -> PassProgram:
    """Lower pass `pass_index` of `technique` for `profile` (cached; see `_cache_key`).
    `vertex_colors`: whether the vertices drawn carry a diffuse colour. Without one, the
    fixed-function lighting takes every colour from the material, whatever ColorVertex and
    the *MaterialSource states say (D3D's rule for a vertex format without the colour; Wine's
    wined3d_ffp_get_vs_settings does the same). `host`: states the application set before
    Begin, by state name (the scene camera's 'WorldTransform', 'ViewTransform',
    'ProjectionTransform'); a pass's own assignments win over them."""
    host_key = tuple(sorted((k, np.asarray(v).tobytes()) for k, v in (host or {}).items()))
    key = _cache_key(effect, technique, pass_index, profile) + (vertex_colors, host_key)
    hit = _CACHE.get(key)
    if hit is not None and hit[0] is effect:
        return hit[1]
    if not 0 <= pass_index < len(technique.passes):
        raise EffectError(f"technique '{technique.name}' has no pass {pass_index} (it has "
                          f"{len(technique.passes)})", technique.location)
    state = None
    for i, (_, s) in enumerate(pass_states(effect, technique.passes,
                                           host_states(host) if host else None)):
        if i == pass_index:
            state = s
            break
    program = _lower(effect, state, profile, vertex_colors)  # type: ignore[arg-type]
    with _CACHE_LOCK:  # the viewer lowers on a worker thread and on the render thread
        if len(_CACHE) >= CACHE_SIZE:
            _CACHE.pop(next(iter(_CACHE)))
        _CACHE[key] = (effect, program)
    return program


def lower_technique(effect: Effect, technique: Technique,
                    profile: "CapsProfile") -> list[PassProgram]:
    """Every pass of `technique`, lowered."""
    return [lower_pass(effect, technique, i, profile) for i in range(len(technique.passes))]


def clear_cache() -> None:
    with _CACHE_LOCK:
        _CACHE.clear()


_CACHE: dict[tuple, tuple[Effect, PassProgram]] = {}
_CACHE_LOCK = threading.Lock()


def _cache_key(effect: Effect, technique: Technique, pass_index: int,
               profile: "CapsProfile") -> tuple:
    """(id(effect), technique, pass, profile, parameter values): uniforms are baked from the
    parameters, so a parameter the runtime changes must miss the cache. The effect object is
    kept with the entry and compared on a hit, so a recycled id cannot match."""
    return (id(effect), technique.name, pass_index, profile.name,
            _parameter_digest(effect.parameters))


def _parameter_digest(parameters: list[Parameter]) -> tuple:
    items = []
    for p in parameters:
        v = p.value
        if isinstance(v, np.ndarray):
            items.append((p.name, v.dtype.str, v.shape, v.tobytes()))
        elif v is None or isinstance(v, (str, int, float, bool)):
            items.append((p.name, v))
        else:
            items.append((p.name, id(v)))
    return tuple(items)


# --------------------------------------------------------------------------------------------
# The dispatcher


def _lower(effect: Effect, state: DeviceState, profile: "CapsProfile",
           vertex_colors: bool = True) -> PassProgram:
    options = lowering_options(profile)
    uniforms: dict[str, tuple[float, ...]] = {}
    fog = read_fog(state)
    pixel_shader = _shader(state, "PixelShader")
    vertex_shader = _shader(state, "VertexShader")

    if pixel_shader is None:
        fb = Builder("fragment")
        stages = read_stages(effect, state)
        inputs = FragmentInputs(tfactor=_color(state, "TextureFactor"),
                                specular_enable=_bool(state, "SpecularEnable"),
                                uniforms=uniforms)
        color = lower_cascade(fb, stages, inputs, options)
        fb.output("color0", apply_fog(fb, color, fog, uniforms, options))
        fragment = fb.build()
    else:
        if fog.source != "none":
            raise EffectError("fog after a pixel shader is not lowered yet",
                              _where(state, "FogEnable"))
        program = _assemble(pixel_shader, "pixel")
        ctx = asm_lower.ShaderContext(
            options, sampler_kinds={s: k for s in range(MAX_STAGES)
                                    if (k := _texture_kind(effect, state, s))},
            projected={s: bool(_int(state, "TextureTransformFlags", s) & _TTFF_PROJECTED)
                       for s in range(MAX_STAGES)},
            constant_prefix=PIXEL_CONSTANT_PREFIX)
        fragment = asm_lower.lower_pixel_shader(program, ctx)
        uniforms.update(_shader_constants(state, "PixelShaderConstant",
                                          asm_lower.constant_registers(program),
                                          PIXEL_CONSTANT_PREFIX))
        uniforms.update(_bump_uniforms(state))

    needed = sorted(int(i.name[len("texcoord"):]) for i in fragment.inputs
                    if i.kind == "varying" and i.name.startswith("texcoord"))
    if vertex_shader is None:
        vertex = lower_vertex(read_vertex(effect, state, needed, fog, vertex_colors), uniforms)
    else:
        program = _assemble(vertex_shader, "vertex")
        ctx = asm_lower.ShaderContext(options, decl=getattr(vertex_shader, "decl", None),
                                      constant_prefix=VERTEX_CONSTANT_PREFIX)
        vertex = asm_lower.lower_vertex_shader(program, ctx)
        uniforms.update(_shader_constants(state, "VertexShaderConstant",
                                          asm_lower.constant_registers(program),
                                          VERTEX_CONSTANT_PREFIX))

    declared = {i.name for prog in (fragment, vertex) for i in prog.inputs if i.kind == "uniform"}
    textures = tuple(texture_binding(effect, state, s.index, s.kind) for s in fragment.samplers)
    return PassProgram(fragment=fragment, vertex=vertex, render_state=read_render_state(state),
                       textures=textures,
                       uniforms=PassProgram.pack_uniforms(
                           {k: v for k, v in uniforms.items() if k in declared}))


def _shader(state: DeviceState, name: str) -> Any:
    a = state.assignment(name)
    if a is None:
        return None
    value = state.resolve(a.value)
    if isinstance(value, NullValue) or value is None:
        return None
    if isinstance(value, ParamRef):
        raise EffectError(f"{name} = <{value.name}>: the parameter holds no shader",
                          a.location)
    return value


def _assemble(shader: Any, stage: str) -> "AsmProgram":
    """The assembled program of a shader value; HLSL is compiled by a later stage."""
    location = getattr(shader, "location", None) or Location("<effect>", 1, 1)
    if isinstance(shader, CompileShader):
        raise EffectError(f"lowering of HLSL (compile {shader.profile} {shader.function}) is "
                          "not available yet", location)
    if not isinstance(shader, ShaderBlock):
        raise EffectError(f"cannot lower a {stage} shader given as {type(shader).__name__}",
                          location)
    return assemble_cached(shader)


_TTFF_PROJECTED = 256
_CONSTANT_FAMILIES = {"VertexShaderConstant": ("VertexShaderConstant", "VertexShaderConstantF",
                                               "VertexShaderConstant1", "VertexShaderConstant2",
                                               "VertexShaderConstant3", "VertexShaderConstant4"),
                      "PixelShaderConstant": ("PixelShaderConstant", "PixelShaderConstantF",
                                              "PixelShaderConstant1", "PixelShaderConstant2",
                                              "PixelShaderConstant3", "PixelShaderConstant4")}


def constant_rows(value: Any) -> np.ndarray:
    """A constant-register value as rows of 4 floats. A 4x4 (or 4x3...) matrix goes in by
    columns (transposed), as shader constants expect; shorter vectors pad with zeros."""
    v = np.asarray(value, dtype=np.float32)
    if v.ndim >= 2 and v.shape[-2:] in ((4, 4), (4, 3), (3, 4), (3, 3)):
        v = np.swapaxes(v, -1, -2)
    flat = v.reshape(-1)
    rows = -(-flat.size // 4)
    out = np.zeros(rows * 4, np.float32)
    out[:flat.size] = flat
    return out.reshape(rows, 4)


# Vertex and pixel shaders have separate constant files: uniforms vs_c<n> and ps_c<n>.
VERTEX_CONSTANT_PREFIX, PIXEL_CONSTANT_PREFIX = "vs_c", "ps_c"


def _shader_constants(state: DeviceState, family: str, needed: set[int],
                      prefix: str) -> dict[str, tuple[float, ...]]:
    """Uniforms `c<n>` from the pass's constant-register assignments (later ones win, as the
    device applies them in order); a register no assignment sets reads zero, as D3DX leaves it."""
    names = {state_table.lookup_state(n).name for n in _CONSTANT_FAMILIES[family]
             if state_table.lookup_state(n) is not None}
    registers: dict[int, tuple[float, ...]] = {}
    for (name, index), assignment in state.items():
        if name not in names or index is None:
            continue
        value = state.resolve(assignment.value)
        if isinstance(value, (ParamRef, NullValue)) or value is None:
            continue
        try:
            rows = constant_rows(value)
        except (TypeError, ValueError):
            raise EffectError(f"{name}[{index}] needs numbers, not {type(value).__name__}",
                              assignment.location) from None
        for k, row in enumerate(rows):
            registers[index + k] = tuple(float(x) for x in row)
    return {f"{prefix}{n}": registers.get(n, (0.0, 0.0, 0.0, 0.0)) for n in sorted(needed)}


def _bump_uniforms(state: DeviceState) -> dict[str, tuple[float, ...]]:
    """Each stage's bump-environment matrix and luminance scale/offset (texbem, texbeml, bem)."""
    out = {}
    for n in range(MAX_STAGES):
        out[f"bumpenv{n}"] = tuple(_float(state, f"BumpEnvMat{ij}", n) for ij in ("00", "01", "10", "11"))
        out[f"bumpenvl{n}"] = (_float(state, "BumpEnvLScale", n), _float(state, "BumpEnvLOffset", n), 0.0, 0.0)
    return out


# --------------------------------------------------------------------------------------------
# Reading the device state


def _value(state: DeviceState, name: str, index: int | None = None) -> Any:
    value = state.get(name, index)
    if isinstance(value, ParamRef):  # an uninitialised parameter: zero, as in D3DX
        return 0
    return value


def _where(state: DeviceState, name: str, index: int | None = None) -> Location:
    a = state.assignment(name, index)
    return a.location if a is not None else Location(state.effect.path, 1, 1)


def _int(state: DeviceState, name: str, index: int | None = None) -> int:
    value = _value(state, name, index)
    if isinstance(value, EnumValue):
        value = value.value
    try:
        return int(np.ravel(np.asarray(value, dtype=np.float64))[0]) & 0xFFFFFFFF
    except (TypeError, ValueError, IndexError):
        raise EffectError(f"{name}: expected a number, got {value!r}",
                          _where(state, name, index)) from None


def _float(state: DeviceState, name: str, index: int | None = None) -> float:
    value = _value(state, name, index)
    try:
        return float(np.ravel(np.asarray(value, dtype=np.float64))[0])
    except (TypeError, ValueError, IndexError):
        raise EffectError(f"{name}: expected a float, got {value!r}",
                          _where(state, name, index)) from None


def _bool(state: DeviceState, name: str, index: int | None = None) -> bool:
    value = _value(state, name, index)
    return bool(np.ravel(np.asarray(value))[0]) if value is not None else False


def decode_color(value: int) -> Color:
    """D3DCOLOR 0xAARRGGBB as (r, g, b, a) floats."""
    v = int(value) & 0xFFFFFFFF
    return ((v >> 16 & 0xFF) / 255, (v >> 8 & 0xFF) / 255, (v & 0xFF) / 255, (v >> 24) / 255)


def _color(state: DeviceState, name: str, index: int | None = None) -> Color:
    value = _value(state, name, index)
    array = np.ravel(np.asarray(value, dtype=np.float64))
    if array.size >= 3:  # a float3/float4 colour parameter
        rgba = list(array[:4]) + [1.0] * (4 - min(4, array.size))
        return (float(rgba[0]), float(rgba[1]), float(rgba[2]), float(rgba[3]))
    return decode_color(_int(state, name, index))


def _vector(state: DeviceState, name: str, index: int | None, size: int) -> tuple[float, ...]:
    value = _value(state, name, index)
    array = np.ravel(np.asarray(value, dtype=np.float64))
    if array.size == 1 and size > 1:  # a scalar (an uninitialised parameter reads 0)
        array = np.full(size, array[0])
    out = list(array[:size]) + [0.0] * max(0, size - array.size)
    return tuple(float(x) for x in out)


def _matrix(state: DeviceState, name: str, index: int | None = None) -> np.ndarray:
    value = _value(state, name, index)
    array = np.ravel(np.asarray(value, dtype=np.float64))
    if array.size == 1 and array[0] == 0:
        return np.zeros((4, 4))
    if array.size != 16:
        raise EffectError(f"{name}: expected a 4x4 matrix, got {array.size} value(s)",
                          _where(state, name, index))
    return array.reshape(4, 4)


def _enum(state: DeviceState, name: str, index: int | None = None) -> str:
    found = state.enum_name(name, index)
    if found is None:
        info = state_table.lookup_state(name)
        number = _int(state, name, index)
        table = info.enum if info is not None else None
        names = [k for k, v in (table.values.items() if table else ()) if v == number]
        if not names:
            raise EffectError(f"{name}{'' if index is None else f'[{index}]'}: {number} is not "
                              f"a {table.name if table else 'known'} value",
                              _where(state, name, index))
        found = names[0]
    return found


def _texture_param(effect: Effect, state: DeviceState, sampler: int) -> Parameter | None:
    a = state.assignment("Texture", sampler)
    if a is None or not isinstance(a.value, ParamRef):
        return None
    return effect.parameter(a.value.name)


def _texture_kind(effect: Effect, state: DeviceState, sampler: int) -> str | None:
    """The IR sampler kind of the texture on `sampler` (from the parameter's type or its
    `string Type` / `TextureType` annotation), or None when nothing is bound."""
    param = _texture_param(effect, state, sampler)
    if param is None:
        return None
    # 1D textures sample as 2D rows here; an untyped texture is 2D until a file says otherwise
    return {"cube": "cube", "3d": "3d"}.get(param.declared_texture_kind or "", "2d")


def read_stages(effect: Effect, state: DeviceState) -> list[StageSetup]:
    """The eight texture stages as the cascade lowering needs them."""
    stages = []
    for n in range(MAX_STAGES):
        args = [(_int(state, f"ColorArg{k}", n), _int(state, f"AlphaArg{k}", n)) for k in range(3)]
        stages.append(StageSetup(
            index=n,
            color_op=_enum(state, "ColorOp", n),
            color_args=(args[0][0], args[1][0], args[2][0]),
            alpha_op=_enum(state, "AlphaOp", n),
            alpha_args=(args[0][1], args[1][1], args[2][1]),
            result_arg=_int(state, "ResultArg", n),
            transform_flags=_int(state, "TextureTransformFlags", n),
            texture_kind=_texture_kind(effect, state, n),
            bump_matrix=tuple(_float(state, f"BumpEnvMat{ij}", n)  # type: ignore[arg-type]
                              for ij in ("00", "01", "10", "11")),
            bump_lscale=_float(state, "BumpEnvLScale", n),
            bump_loffset=_float(state, "BumpEnvLOffset", n),
            constant=_color(state, "Constant", n),
            location=_where(state, "ColorOp", n)))
    return stages


def read_fog(state: DeviceState) -> FogSetup:
    if not _bool(state, "FogEnable"):
        return FogSetup()
    table, vertex = _enum(state, "FogTableMode"), _enum(state, "FogVertexMode")
    source = "table" if table != "NONE" else "vertex" if vertex != "NONE" else "specular"
    return FogSetup(source=source, table_mode=table, vertex_mode=vertex,
                    color=_color(state, "FogColor"), start=_float(state, "FogStart"),
                    end=_float(state, "FogEnd"), density=_float(state, "FogDensity"),
                    range_fog=_bool(state, "RangeFogEnable"))


def _enabled_lights(state: DeviceState) -> list[int]:
    indices = sorted({index for (name, index), _ in state.items()
                      if name == "LightEnable" and index is not None})
    return [i for i in indices if _bool(state, "LightEnable", i)]


def read_vertex(effect: Effect, state: DeviceState, stages: list[int],
                fog: FogSetup, vertex_colors: bool = True) -> VertexSetup:
    """The fixed-function vertex state; `stages` are the stages whose coordinates the
    fragment program reads; without `vertex_colors` the material sources are forced."""
    lights = tuple(LightSetup(
        index=i, type=_enum(state, "LightType", i),
        diffuse=_vector(state, "LightDiffuse", i, 4),  # type: ignore[arg-type]
        specular=_vector(state, "LightSpecular", i, 4),  # type: ignore[arg-type]
        ambient=_vector(state, "LightAmbient", i, 4),  # type: ignore[arg-type]
        position=_vector(state, "LightPosition", i, 3),  # type: ignore[arg-type]
        direction=_vector(state, "LightDirection", i, 3),  # type: ignore[arg-type]
        range=_float(state, "LightRange", i),
        attenuation=(_float(state, "LightAttenuation0", i), _float(state, "LightAttenuation1", i),
                     _float(state, "LightAttenuation2", i)),
        falloff=_float(state, "LightFalloff", i), theta=_float(state, "LightTheta", i),
        phi=_float(state, "LightPhi", i)) for i in _enabled_lights(state))
    texcoords = []
    for n in stages:
        tci = _int(state, "TexCoordIndex", n)
        mode = TCI_MODES.get(tci >> 16)
        if mode is None:
            raise EffectError(f"TexCoordIndex[{n}]: {tci:#x} names no texture-coordinate "
                              "generation mode", _where(state, "TexCoordIndex", n))
        texcoords.append(TexCoordSetup(stage=n, set_index=tci & 0xFFFF, texgen=mode,
                                       transform_flags=_int(state, "TextureTransformFlags", n),
                                       matrix=_matrix(state, "TextureTransform", n)))
    return VertexSetup(
        world=_matrix(state, "WorldTransform", 0), view=_matrix(state, "ViewTransform"),
        projection=_matrix(state, "ProjectionTransform"),
        lighting=_bool(state, "Lighting"), lights=lights,
        material_diffuse=_vector(state, "MaterialDiffuse", None, 4),  # type: ignore[arg-type]
        material_ambient=_vector(state, "MaterialAmbient", None, 4),  # type: ignore[arg-type]
        material_specular=_vector(state, "MaterialSpecular", None, 4),  # type: ignore[arg-type]
        material_emissive=_vector(state, "MaterialEmissive", None, 4),  # type: ignore[arg-type]
        material_power=_float(state, "MaterialPower"), ambient=_color(state, "Ambient"),
        color_vertex=_bool(state, "ColorVertex") and vertex_colors,
        diffuse_source=_enum(state, "DiffuseMaterialSource"),
        specular_source=_enum(state, "SpecularMaterialSource"),
        ambient_source=_enum(state, "AmbientMaterialSource"),
        emissive_source=_enum(state, "EmissiveMaterialSource"),
        specular_enable=_bool(state, "SpecularEnable"), local_viewer=_bool(state, "LocalViewer"),
        normalize_normals=_bool(state, "NormalizeNormals"), texcoords=tuple(texcoords), fog=fog)


def texture_binding(effect: Effect, state: DeviceState, sampler: int, kind: str) -> TextureBinding:
    """The texture on `sampler` and the sampler states in force there."""
    param = _texture_param(effect, state, sampler)
    return TextureBinding(
        sampler=sampler, texture=param.name if param is not None else None, kind=kind,
        address_u=_enum(state, "AddressU", sampler), address_v=_enum(state, "AddressV", sampler),
        address_w=_enum(state, "AddressW", sampler),
        border_color=_color(state, "BorderColor", sampler),
        mag_filter=_enum(state, "MagFilter", sampler), min_filter=_enum(state, "MinFilter", sampler),
        mip_filter=_enum(state, "MipFilter", sampler),
        mip_lod_bias=_float(state, "MipMapLodBias", sampler),
        max_mip_level=_int(state, "MaxMipLevel", sampler),
        max_anisotropy=_int(state, "MaxAnisotropy", sampler),
        srgb_texture=_bool(state, "SRGBTexture", sampler))


# RenderState field -> (state name, reader). Fog and SpecularEnable are folded into the
# programs (module docstring), so RenderState has no fields for them.
_RENDER_FIELDS: dict[str, tuple[str, Callable[[DeviceState, str], Any]]] = {
    "z_enable": ("ZEnable", lambda s, n: _enum(s, n) != "FALSE"),
    "z_write_enable": ("ZWriteEnable", _bool), "z_func": ("ZFunc", _enum),
    "depth_bias": ("DepthBias", _float), "slope_scale_depth_bias": ("SlopeScaleDepthBias", _float),
    "cull_mode": ("CullMode", _enum), "fill_mode": ("FillMode", _enum),
    "shade_mode": ("ShadeMode", _enum), "scissor_test_enable": ("ScissorTestEnable", _bool),
    "clip_plane_enable": ("ClipPlaneEnable", _int),
    "alpha_test_enable": ("AlphaTestEnable", _bool), "alpha_func": ("AlphaFunc", _enum),
    "alpha_ref": ("AlphaRef", lambda s, n: _int(s, n) & 0xFF),
    "alpha_blend_enable": ("AlphaBlendEnable", _bool), "src_blend": ("SrcBlend", _enum),
    "dest_blend": ("DestBlend", _enum), "blend_op": ("BlendOp", _enum),
    "separate_alpha_blend_enable": ("SeparateAlphaBlendEnable", _bool),
    "src_blend_alpha": ("SrcBlendAlpha", _enum), "dest_blend_alpha": ("DestBlendAlpha", _enum),
    "blend_op_alpha": ("BlendOpAlpha", _enum), "blend_factor": ("BlendFactor", _color),
    "color_write_enable": ("ColorWriteEnable", lambda s, n: _int(s, n) & 0xF),
    "dither_enable": ("DitherEnable", _bool), "srgb_write_enable": ("SRGBWriteEnable", _bool),
    "stencil_enable": ("StencilEnable", _bool), "stencil_func": ("StencilFunc", _enum),
    "stencil_ref": ("StencilRef", _int), "stencil_mask": ("StencilMask", _int),
    "stencil_write_mask": ("StencilWriteMask", _int), "stencil_fail": ("StencilFail", _enum),
    "stencil_zfail": ("StencilZFail", _enum), "stencil_pass": ("StencilPass", _enum),
    "two_sided_stencil_mode": ("TwoSidedStencilMode", _bool),
    "ccw_stencil_func": ("CCW_StencilFunc", _enum), "ccw_stencil_fail": ("CCW_StencilFail", _enum),
    "ccw_stencil_zfail": ("CCW_StencilZFail", _enum),
    "ccw_stencil_pass": ("CCW_StencilPass", _enum),
}


def read_render_state(state: DeviceState) -> RenderState:
    known = {f.name for f in fields(RenderState)}
    values = {name: read(state, state_name)
              for name, (state_name, read) in _RENDER_FIELDS.items() if name in known}
    return RenderState(**values)
