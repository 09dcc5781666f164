"""Lowering a pass to a PassProgram: the entry point and dispatcher.

`lower_pass` takes the device state in force for the pass from the technique's `Validation`
(`PassReport.state`: the state the validator checked, D3D9 defaults with earlier passes
persisting), or, for a technique drawn without one (named by the caller, valid or not), plays
the passes through `effects.d3d9.device.pass_states` itself; it reads that state with the device
state's typed readers, resolves it into plain setups, and hands them to
the lowerings: the texture-stage cascade (`lower_stages`), the fixed-function vertex pipeline
(`lower_vertex`), or the shader-assembly lowering (`effects.shaders.asm.lower`) for passes with
shaders. The profile picks the precision (`effects.d3d9.precision`).

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
constant files), the integer and boolean registers i# / b# (VertexShaderConstantI/B,
PixelShaderConstantI/B: static values lowered into the program, see asm.lower), the
bump-environment state of each stage (uniforms `bumpenv<n>` and
`bumpenvl<n>`), the kind of texture bound to each sampler, and TTFF_PROJECTED per stage.
A vs_3_0 shader's samplers are the vertex texture samplers 257-260 (`Sampler[257] = <s>`, or an
HLSL vertex shader's sampler registers + 257, as D3DX binds them), bound like pixel ones.
Fixed-function fog is blended after a ps_1_x/2_x pixel shader, as Direct3D 9 did, and not after
ps_3_0 (`_fog_after_pixel_shader`); pixel (table) fog after a vertex shader is a located error.
"""
from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING, Any, Callable, Mapping

import numpy as np

from effects.d3d9 import states as state_table
from effects.d3d9.device import DeviceState, host_states, pass_states
from effects.base import caches
from effects.base.errors import EffectError, Location
from effects.lower.preshaders import evaluate_expressions, evaluate_into
from effects.shaders.asm import lower as asm_lower
from effects.shaders.shader_value import shader_of
from effects.program.ir import Builder
from effects.lower.stages import (FogSetup, FragmentInputs, StageSetup, active_stages, apply_fog,
                                  lower_cascade)
from effects.lower.vertex import (PHONG_SLOTS, LightSetup, TexCoordSetup, VertexSetup,
                                   lower_pixel_lighting, lower_vertex, pixel_lighting)
from effects.model import (BytecodeShader, CompileShader, Effect, NullValue, Parameter, ParamRef,
                    RecordedReads, StateAssignment, Technique, still_holds)
from effects.program.passprogram import PassProgram, RenderState, TextureBinding
from effects.d3d9.precision import lowering_options
from effects.d3d9.stage_ops import MAX_STAGES, TCI_MODES, TCI_SET_MASK, TCI_SHIFT, TTFF_PROJECTED

if TYPE_CHECKING:  # pragma: no cover
    from effects.shaders.asm import AsmProgram
    from effects.shaders.shader_value import Shader
    from effects.d3d9.caps import CapsProfile
    from effects.validate.technique import Validation

# A lowered pass holds ~40 KB (tracemalloc: phong.fx and wood.fx on the radeon9700, 38-50 KB).
_LOWERED = caches.declare(
    "lower.passes", keys="technique object, pass index, card name, vertex colours, the host's "
    "states; on a hit, the same technique and validation objects and the parameters it read",
    entry_bytes=32 << 10, max_bytes=256 * (32 << 10))


# A shader's IR depends on its program and the ShaderContext, not on the float constants the
# pass sets (uniforms, read apart by `_shader_constants` / `_compiled_constants`): a pass
# lowered again because a parameter feeding only a constant changed (a viewer's slider,
# TIME each frame) takes the IR it had, and the GL back end the program it built from it.
# Asm lowering was ~80 % of such a frame's lowering (phong.fx's ps_2_0, benchmarks/bench_viewer.py).
_SHADER_IR = caches.declare(
    "lower.shader_ir", keys="the assembled program object, vertex or pixel, and the shader "
    "context (precision, sampler kinds, projection, declaration, integer and bool registers)",
    entry_bytes=16 << 10, max_bytes=256 * (16 << 10))


def _shader_ir(program: "AsmProgram", ctx: "asm_lower.ShaderContext", stage: str) -> Any:
    key = (id(program), stage, ctx.options, tuple(sorted(ctx.sampler_kinds.items())),
           tuple(sorted(ctx.projected.items())), ctx.decl, ctx.constant_prefix,
           tuple(sorted(ctx.int_constants.items())), tuple(sorted(ctx.bool_constants.items())))
    hit = _SHADER_IR.get(key)
    if hit is not None and hit[0] is program:        # the program kept: a recycled id misses
        return hit[1]
    lower = asm_lower.lower_pixel_shader if stage == "pixel" else asm_lower.lower_vertex_shader
    ir = lower(program, ctx)
    _SHADER_IR.put(key, (program, ir))
    return ir


# --------------------------------------------------------------------------------------------
# Public API


def lower_pass(effect: Effect, technique: Technique, pass_index: int,
               profile: "CapsProfile", *, vertex_colors: bool = True,
               host: Mapping[str, Any] | None = None,
               validation: "Validation | None" = None) -> PassProgram:
    """Lower pass `pass_index` of `technique` for `profile` (cached; see `_cache_key`).
    `validation`: the technique's Validation, whose per-pass device state is drawn (see the
    module docstring); its parameter references read `effect`'s values (a runtime's copy).
    `vertex_colors`: whether the vertices drawn carry a diffuse colour. Without one, the
    fixed-function lighting takes every colour from the material, whatever ColorVertex and
    the *MaterialSource states say (D3D's rule for a vertex format without the colour; Wine's
    wined3d_ffp_get_vs_settings does the same). `host`: states the application set before
    Begin, by state name (the scene camera's 'WorldTransform', 'ViewTransform',
    'ProjectionTransform'); a pass's own assignments win over them."""
    host_key = tuple(sorted((k, np.asarray(v).tobytes()) for k, v in (host or {}).items()))
    key = _cache_key(technique, pass_index, profile, vertex_colors) + (host_key,)
    hit = _LOWERED.get(key)
    # A validation's device state was applied when the technique was validated (sampler states
    # included): the program is good for that validation object only.
    if hit is not None and hit[0] is technique and hit[3] is validation \
            and still_holds(effect, hit[1]):
        return hit[2]
    if not 0 <= pass_index < len(technique.passes):
        raise EffectError(f"technique '{technique.name}' has no pass {pass_index} (it has "
                          f"{len(technique.passes)})", technique.location)
    reads = RecordedReads(effect)
    state = _pass_state(reads, technique, pass_index, validation,  # type: ignore[arg-type]
                        host_states(host) if host else None)
    state = evaluate_expressions(reads, state)  # type: ignore[arg-type]
    judged = validation.pass_reports[pass_index].shaders if validation is not None else {}
    program = _lower(reads, state, profile, vertex_colors, judged)  # type: ignore[arg-type]
    _LOWERED.put(key, (technique, reads.snapshot(), program, validation))
    return program


def lower_technique(effect: Effect, technique: Technique, profile: "CapsProfile", *,
                    validation: "Validation | None" = None) -> list[PassProgram]:
    """Every pass of `technique`, lowered."""
    return [lower_pass(effect, technique, i, profile, validation=validation)
            for i in range(len(technique.passes))]


def _pass_state(effect: Effect, technique: Technique, pass_index: int,
                validation: "Validation | None", host: Mapping | None) -> DeviceState:
    """The device state pass `pass_index` draws with: the validation's (read against `effect`,
    with the host's states under the passes'), or played through when there is none."""
    if validation is not None:
        if validation.technique is not technique:
            raise ValueError(f"the validation is of technique '{validation.technique.name}', "
                             f"not '{technique.name}'")
        state = validation.pass_reports[pass_index].state
        if state is not None:
            if state.effect is effect and not host and not state.host:
                return state
            return state.for_effect(effect, host or {})
    for i, (_, s) in enumerate(pass_states(effect, technique.passes, host)):
        if i == pass_index:
            return s
    raise AssertionError("pass index checked by the caller")


def clear_cache() -> None:
    _LOWERED.clear()
    _SHADER_IR.clear()


def _cache_key(technique: Technique, pass_index: int, profile: "CapsProfile",
               vertex_colors: bool) -> tuple:
    """(technique, pass, profile, vertex colours). The technique object is kept with the entry
    and compared on a hit, so a recycled id cannot match. The effect is not in the key: a
    Runtime's copy of an effect shares its techniques, so `effects.render()` called again hits.
    What the program depends on beyond that, the parameters it read, is checked by
    `still_holds` on a hit: only those, so the check costs what the pass reads, not what the
    file declares."""
    return (id(technique), pass_index, profile.name, vertex_colors)


# --------------------------------------------------------------------------------------------
# The dispatcher


def _lower(effect: Effect, state: DeviceState, profile: "CapsProfile",
           vertex_colors: bool = True, judged: Mapping[str, "Shader"] | None = None) -> PassProgram:
    """`judged`: the shaders validation judged for this pass, by state name (each one's
    program and bindings); a shader not among them is made here (`shader_of`)."""
    options = lowering_options(profile)
    uniforms: dict[str, tuple[float, ...]] = {}
    fog = read_fog(state)
    pixel_shader = _shader(state, "PixelShader")
    vertex_shader = _shader(state, "VertexShader")
    if isinstance(pixel_shader, (CompileShader, BytecodeShader)) \
            or isinstance(vertex_shader, (CompileShader, BytecodeShader)):
        state = state.copy()   # the compiled shader binds its samplers (may be the validation's state)
    judged = judged or {}

    lit = lighting = None
    if pixel_shader is None:
        fb = Builder("fragment")
        stages = read_stages(effect, state)
        if vertex_shader is None and _per_pixel_lighting(state):
            lit_setup = read_vertex(effect, state, [], fog, vertex_colors)
            lit = lower_pixel_lighting(lit_setup, uniforms, fb)
        inputs = FragmentInputs(tfactor=state.get_color("TextureFactor"),
                                specular_enable=state.get_bool("SpecularEnable"),
                                uniforms=uniforms, lit=lit)
        color = lower_cascade(fb, stages, inputs, options)
        fb.output("color0", apply_fog(fb, color, fog, uniforms, options))
        fragment = fb.build()
        if lit is not None:     # the lit values by their numbers in the built program
            lighting = pixel_lighting(lit_setup, *(fb.renumbered.get(v) for v in lit))
    else:
        program, compiled = _assemble(effect, state, pixel_shader, "pixel",
                                      judged.get("PixelShader"))
        fog = _fog_after_pixel_shader(fog, program, vertex_shader, state)
        ctx = asm_lower.ShaderContext(
            options, sampler_kinds={s: k for s in range(MAX_STAGES)
                                    if (k := _texture_kind(effect, state, s))},
            projected={s: bool(state.get_int("TextureTransformFlags", s) & TTFF_PROJECTED)
                       for s in range(MAX_STAGES)},
            constant_prefix=PIXEL_CONSTANT_PREFIX,
            int_constants=_int_constants(state, "Pixel", compiled),
            bool_constants=state.bool_constants("Pixel"))
        fragment = _shader_ir(program, ctx, "pixel")
        uniforms.update(_shader_constants(state, "PixelShaderConstant",
                                          asm_lower.constant_registers(program),
                                          PIXEL_CONSTANT_PREFIX))
        uniforms.update(_compiled_constants(effect, compiled, PIXEL_CONSTANT_PREFIX))
        uniforms.update(_bump_uniforms(state))
        if fog.source != "none":
            fb = Builder.resume(fragment)
            fb.output("color0", apply_fog(fb, fb.output_value("color0"), fog, uniforms, options))
            fragment = fb.build()

    needed = sorted(int(i.name[len("texcoord"):]) for i in fragment.inputs
                    if i.kind == "varying" and i.name.startswith("texcoord"))
    if pixel_shader is None and lit is not None:   # the Phong varyings are not stage coordinates
        used = len(active_stages(stages))
        if used > PHONG_SLOTS[0]:
            raise EffectError(f"ShadeMode = Phong interpolates the normal and position in texture "
                              f"coordinates {PHONG_SLOTS[0]} and {PHONG_SLOTS[1]}: a Phong pass "
                              f"may use {PHONG_SLOTS[0]} texture stages, this one uses {used}",
                              state.where("ShadeMode"))
        needed = [n for n in needed if n not in PHONG_SLOTS]
    if vertex_shader is None:
        vertex = lower_vertex(read_vertex(effect, state, needed, fog, vertex_colors), uniforms)
    else:
        program, compiled = _assemble(effect, state, vertex_shader, "vertex",
                                      judged.get("VertexShader"))
        ctx = asm_lower.ShaderContext(options, decl=getattr(vertex_shader, "decl", None),
                                      constant_prefix=VERTEX_CONSTANT_PREFIX,
                                      int_constants=_int_constants(state, "Vertex", compiled),
                                      bool_constants=state.bool_constants("Vertex"))
        vertex = _shader_ir(program, ctx, "vertex")
        if fog.source == "vertex" and "fog" not in vertex.output_map:
            raise EffectError("fog blending after the pixel shader takes its factor from the "
                              "vertex shader's oFog, which this vertex shader does not write",
                              state.where("FogEnable"))
        uniforms.update(_shader_constants(state, "VertexShaderConstant",
                                          asm_lower.constant_registers(program),
                                          VERTEX_CONSTANT_PREFIX))
        uniforms.update(_compiled_constants(effect, compiled, VERTEX_CONSTANT_PREFIX))

    declared = {i.name for prog in (fragment, vertex) for i in prog.inputs if i.kind == "uniform"}
    textures = tuple(texture_binding(effect, state, s.index, s.kind)
                     for s in (*fragment.samplers, *vertex.samplers))
    return PassProgram(fragment=fragment, vertex=vertex, render_state=read_render_state(state),
                       textures=textures,
                       uniforms=PassProgram.pack_uniforms(
                           {k: v for k, v in uniforms.items() if k in declared}),
                       lighting=lighting)


def _shader(state: DeviceState, name: str) -> Any:
    a = state.assignment(name)
    if a is None:
        return None
    value = state.resolve(a.value)
    if isinstance(value, NullValue) or value is None:
        return None
    if isinstance(value, ParamRef):
        param = state.effect.parameter(value.name)
        if param is not None and param.value is None and param.array and value.index is not None:
            return None     # an element of a shader array declared without one: NULL, as in D3DX
        raise EffectError(f"{name} = <{value.name}>: the parameter holds no shader",
                          a.location)
    return value


def _assemble(effect: Effect, state: DeviceState, shader: Any, stage: str,
              judged: "Shader | None" = None) -> tuple["AsmProgram", Any]:
    """The assembled program of a shader value, and the compiled HLSL shader (or None): the
    Shader validation judged when it is of this value, else made now (`shader_of`). An HLSL
    shader's registers are bound as its bindings say, as D3DX does when it sets the shader:
    each sampler parameter to its sampler (`Sampler[s#] = (param)` in effect terms)."""
    location = getattr(shader, "location", None) or Location("<effect>", 1, 1)
    found = judged if judged is not None and judged.value is shader else shader_of(effect, shader)
    if found is None:
        raise EffectError(f"cannot lower a {stage} shader given as {type(shader).__name__}",
                          location)
    if found.compiled is None:
        return found.program, None
    for binding in found.samplers:
        if binding.parameter is None:
            continue
        state.apply(StateAssignment("Sampler", _sampler_ref(binding.parameter),
                                    index=binding.unit, location=location))
        if binding.texture is not None:
            # `Tex.Sample(S, uv)`: S's states with Tex's picture, whatever S's block names
            state.apply(StateAssignment("Texture", ParamRef(binding.texture),
                                        index=binding.unit, location=location))
        elif state.assignment("Texture", binding.unit) is None:
            # its sampler_state names no texture: the host sets one on the stage
            # (SetTexture), named after the sampler (`--set S=image`; else a stand-in)
            state.apply(StateAssignment("Texture", _sampler_ref(binding.parameter),
                                        index=binding.unit, location=location))
    # an int parameter counting a rep sits in the i# the compiler gave it (D3DX sets it
    # with the shader, as VertexShaderConstantI / PixelShaderConstantI would)
    family = "PixelShaderConstantI" if stage == "pixel" else "VertexShaderConstantI"
    for name, register in found.int_registers.items():
        _set_components(effect, state, family, name, register, found.compiled, location)
    # a bool parameter an `if b#` tests sits in its b# (VertexShaderConstantB / Pixel...)
    family = "PixelShaderConstantB" if stage == "pixel" else "VertexShaderConstantB"
    for name, register in found.bool_registers.items():
        _set_components(effect, state, family, name, register, found.compiled, location)
    evaluate_into(effect, state)   # expressions in those samplers' sampler_state blocks
    return found.program, found.compiled


def _set_components(effect: Effect, state: DeviceState, family: str, name: str, register: int,
                    compiled: Any, location: Location) -> None:
    """An int or bool parameter into its registers, one per component from `register` (as
    fxc laid them out: effects/shaders/hlsl/components.py), as many as the register table
    gives it. A scalar is the parameter itself (no value: the register is left unset)."""
    count = compiled.register_count(name) if compiled is not None else 1
    p = effect.parameter(name)
    if count == 1 and (p is None or (p.type.rows == 1 and p.type.cols == 1 and not p.array
                                     and not p.type.struct)):
        state.apply(StateAssignment(family, ParamRef(name), index=register, location=location))
        return
    from effects.shaders.hlsl.preshader import parameter_numbers
    numbers = parameter_numbers(effect, name)
    if numbers is None:
        return
    for k in range(min(count, len(numbers))):
        state.apply(StateAssignment(family, (numbers[k],), index=register + k, location=location))


def _sampler_ref(name: str) -> ParamRef:
    """A compiled shader's sampler as a parameter reference: `S[1]` (an element of a sampler
    array the shader indexed by a constant) is element 1 of parameter S."""
    if name.endswith("]") and "[" in name:
        base, index = name[:-1].split("[", 1)
        return ParamRef(base, index=int(index))
    return ParamRef(name)


def _int_constants(state: DeviceState, shader: str, compiled: Any
                   ) -> dict[int, tuple[int, int, int, int]]:
    """The i# the pass sets; an int parameter a compiled shader's loop counts (its
    int_registers) as D3DX's constant table sets an int4 register from an int: the value,
    then 0, 1, 0 in the components it does not give (Wine's d3dx9 constant table, `set`:
    INT vec[4] = {0, 0, 1, 0}). So `loop aL, i#` runs aL = 0, 1, ... N - 1 (count, start,
    step, unused); `rep i#` reads only the count."""
    found = state.int_constants(shader)
    for name, first in getattr(compiled, "int_registers", {}).items():
        for register in range(first, first + compiled.register_count(name)):
            found[register] = (found.get(register, (0, 0, 0, 0))[0], 0, 1, 0)
    return found


def _compiled_constants(effect: Effect, compiled: Any, prefix: str) -> dict[str, tuple[float, ...]]:
    """Uniforms c# of a compiled HLSL shader from the parameters its register table names
    (these win over PixelShaderConstant assignments, as the shader sets them when it runs)."""
    if compiled is None:
        return {}
    from effects.shaders.hlsl.registers import constant_values
    return {f"{prefix}{n}": row for n, row in constant_values(effect, compiled).items()}


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
        out[f"bumpenv{n}"] = tuple(state.get_float(f"BumpEnvMat{ij}", n) for ij in ("00", "01", "10", "11"))
        out[f"bumpenvl{n}"] = (state.get_float("BumpEnvLScale", n), state.get_float("BumpEnvLOffset", n), 0.0, 0.0)
    return out


# --------------------------------------------------------------------------------------------
# Reading the device state


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
        args = [(state.get_int(f"ColorArg{k}", n), state.get_int(f"AlphaArg{k}", n)) for k in range(3)]
        stages.append(StageSetup(
            index=n,
            color_op=state.get_enum("ColorOp", n),
            color_args=(args[0][0], args[1][0], args[2][0]),
            alpha_op=state.get_enum("AlphaOp", n),
            alpha_args=(args[0][1], args[1][1], args[2][1]),
            result_arg=state.get_int("ResultArg", n),
            transform_flags=state.get_int("TextureTransformFlags", n),
            texture_kind=_texture_kind(effect, state, n),
            bump_matrix=tuple(state.get_float(f"BumpEnvMat{ij}", n)  # type: ignore[arg-type]
                              for ij in ("00", "01", "10", "11")),
            bump_lscale=state.get_float("BumpEnvLScale", n),
            bump_loffset=state.get_float("BumpEnvLOffset", n),
            constant=state.get_color("Constant", n),
            location=state.where("ColorOp", n)))
    return stages


def _fog_after_pixel_shader(fog: FogSetup, program: "AsmProgram", vertex_shader: Any,
                            state: DeviceState) -> FogSetup:
    """The fog Direct3D 9 blends after a pixel shader: none after ps_3_0 (a ps_3_0 shader does
    its own fog); after ps_1_x/2_x the fixed-function blend, whose factor comes from the
    vertex side: the fixed-function vertex pipeline's as without a pixel shader, a vertex
    shader's oFog whatever FogVertexMode says (wined3d's find_ps_compile_args does both)."""
    if fog.source == "none" or program.version[0] >= 3:
        return FogSetup()
    if vertex_shader is None:
        return fog
    if fog.source == "table":
        raise EffectError("FogTableMode (pixel fog) after a vertex shader and a pixel shader is "
                          "not lowered yet: its factor comes from each pixel's depth, which "
                          "the lowered pixel program does not read", state.where("FogTableMode"))
    return replace(fog, source="vertex")


def read_fog(state: DeviceState) -> FogSetup:
    if not state.get_bool("FogEnable"):
        return FogSetup()
    table, vertex = state.get_enum("FogTableMode"), state.get_enum("FogVertexMode")
    source = "table" if table != "NONE" else "vertex" if vertex != "NONE" else "specular"
    return FogSetup(source=source, table_mode=table, vertex_mode=vertex,
                    color=state.get_color("FogColor"), start=state.get_float("FogStart"),
                    end=state.get_float("FogEnd"), density=state.get_float("FogDensity"),
                    range_fog=state.get_bool("RangeFogEnable"))


def _enabled_lights(state: DeviceState) -> list[int]:
    indices = sorted({index for (name, index), _ in state.items()
                      if name == "LightEnable" and index is not None})
    return [i for i in indices if state.get_bool("LightEnable", i)]


def read_vertex(effect: Effect, state: DeviceState, stages: list[int],
                fog: FogSetup, vertex_colors: bool = True) -> VertexSetup:
    """The fixed-function vertex state; `stages` are the stages whose coordinates the
    fragment program reads; without `vertex_colors` the material sources are forced."""
    lights = tuple(LightSetup(
        index=i, type=state.get_enum("LightType", i),
        diffuse=state.get_vector("LightDiffuse", i, 4),  # type: ignore[arg-type]
        specular=state.get_vector("LightSpecular", i, 4),  # type: ignore[arg-type]
        ambient=state.get_vector("LightAmbient", i, 4),  # type: ignore[arg-type]
        position=state.get_vector("LightPosition", i, 3),  # type: ignore[arg-type]
        direction=state.get_vector("LightDirection", i, 3),  # type: ignore[arg-type]
        range=state.get_float("LightRange", i),
        attenuation=(state.get_float("LightAttenuation0", i), state.get_float("LightAttenuation1", i),
                     state.get_float("LightAttenuation2", i)),
        falloff=state.get_float("LightFalloff", i), theta=state.get_float("LightTheta", i),
        phi=state.get_float("LightPhi", i)) for i in _enabled_lights(state))
    texcoords = []
    for n in stages:
        tci = state.get_int("TexCoordIndex", n)
        mode = TCI_MODES.get(tci >> TCI_SHIFT)
        if mode is None:
            raise EffectError(f"TexCoordIndex[{n}]: {tci:#x} names no texture-coordinate "
                              "generation mode", state.where("TexCoordIndex", n))
        texcoords.append(TexCoordSetup(stage=n, set_index=tci & TCI_SET_MASK, texgen=mode,
                                       transform_flags=state.get_int("TextureTransformFlags", n),
                                       matrix=state.get_matrix("TextureTransform", n)))
    return VertexSetup(
        world=state.get_matrix("WorldTransform", 0), view=state.get_matrix("ViewTransform"),
        projection=state.get_matrix("ProjectionTransform"),
        lighting=state.get_bool("Lighting"), lights=lights,
        material_diffuse=state.get_vector("MaterialDiffuse", None, 4),  # type: ignore[arg-type]
        material_ambient=state.get_vector("MaterialAmbient", None, 4),  # type: ignore[arg-type]
        material_specular=state.get_vector("MaterialSpecular", None, 4),  # type: ignore[arg-type]
        material_emissive=state.get_vector("MaterialEmissive", None, 4),  # type: ignore[arg-type]
        material_power=state.get_float("MaterialPower"), ambient=state.get_color("Ambient"),
        color_vertex=state.get_bool("ColorVertex") and vertex_colors,
        diffuse_source=state.get_enum("DiffuseMaterialSource"),
        specular_source=state.get_enum("SpecularMaterialSource"),
        ambient_source=state.get_enum("AmbientMaterialSource"),
        emissive_source=state.get_enum("EmissiveMaterialSource"),
        specular_enable=state.get_bool("SpecularEnable"), local_viewer=state.get_bool("LocalViewer"),
        normalize_normals=state.get_bool("NormalizeNormals"),
        per_pixel_lighting=_per_pixel_lighting(state), texcoords=tuple(texcoords), fog=fog)


def _per_pixel_lighting(state: DeviceState) -> bool:
    """ShadeMode = Phong with the fixed-function lighting on: the pass lights per pixel."""
    return state.get_enum("ShadeMode") == "PHONG" and state.get_bool("Lighting")


def texture_binding(effect: Effect, state: DeviceState, sampler: int, kind: str) -> TextureBinding:
    """The texture on `sampler` and the sampler states in force there."""
    param = _texture_param(effect, state, sampler)
    return TextureBinding(
        sampler=sampler, texture=param.name if param is not None else None, kind=kind,
        address_u=state.get_enum("AddressU", sampler), address_v=state.get_enum("AddressV", sampler),
        address_w=state.get_enum("AddressW", sampler),
        border_color=state.get_color("BorderColor", sampler),
        mag_filter=state.get_enum("MagFilter", sampler), min_filter=state.get_enum("MinFilter", sampler),
        mip_filter=state.get_enum("MipFilter", sampler),
        mip_lod_bias=state.get_float("MipMapLodBias", sampler),
        max_mip_level=state.get_int("MaxMipLevel", sampler),
        max_anisotropy=state.get_int("MaxAnisotropy", sampler),
        srgb_texture=state.get_bool("SRGBTexture", sampler))


# RenderState field -> (state name, conversion of the value the state's row types). Fog and
# SpecularEnable are folded into the programs (module docstring), so RenderState has no fields
# for them. ZEnable's D3DZB_USEW draws with a depth buffer too (as z).
_RENDER_FIELDS: dict[str, tuple[str, Callable[[Any], Any] | None]] = {
    "z_enable": ("ZEnable", lambda v: v != "FALSE"), "z_write_enable": ("ZWriteEnable", None),
    "z_func": ("ZFunc", None), "depth_bias": ("DepthBias", None),
    "slope_scale_depth_bias": ("SlopeScaleDepthBias", None), "cull_mode": ("CullMode", None),
    "fill_mode": ("FillMode", None), "shade_mode": ("ShadeMode", None),
    "scissor_test_enable": ("ScissorTestEnable", None),
    "clip_plane_enable": ("ClipPlaneEnable", None), "alpha_test_enable": ("AlphaTestEnable", None),
    "alpha_func": ("AlphaFunc", None), "alpha_ref": ("AlphaRef", lambda v: v & 0xFF),
    "alpha_blend_enable": ("AlphaBlendEnable", None), "src_blend": ("SrcBlend", None),
    "dest_blend": ("DestBlend", None), "blend_op": ("BlendOp", None),
    "separate_alpha_blend_enable": ("SeparateAlphaBlendEnable", None),
    "src_blend_alpha": ("SrcBlendAlpha", None), "dest_blend_alpha": ("DestBlendAlpha", None),
    "blend_op_alpha": ("BlendOpAlpha", None), "blend_factor": ("BlendFactor", None),
    "color_write_enable": ("ColorWriteEnable", lambda v: v & 0xF),
    "dither_enable": ("DitherEnable", None), "srgb_write_enable": ("SRGBWriteEnable", None),
    "stencil_enable": ("StencilEnable", None), "stencil_func": ("StencilFunc", None),
    "stencil_ref": ("StencilRef", None), "stencil_mask": ("StencilMask", None),
    "stencil_write_mask": ("StencilWriteMask", None), "stencil_fail": ("StencilFail", None),
    "stencil_zfail": ("StencilZFail", None), "stencil_pass": ("StencilPass", None),
    "two_sided_stencil_mode": ("TwoSidedStencilMode", None),
    "ccw_stencil_func": ("CCW_StencilFunc", None), "ccw_stencil_fail": ("CCW_StencilFail", None),
    "ccw_stencil_zfail": ("CCW_StencilZFail", None), "ccw_stencil_pass": ("CCW_StencilPass", None),
}


def read_render_state(state: DeviceState) -> RenderState:
    """The pass's RenderState from the device state; every RenderState field has a row above
    (tests/d3d9/test_states.py checks that the defaults agree with the states table)."""
    values = {}
    for name, (state_name, convert) in _RENDER_FIELDS.items():
        value = state.read(state_name)
        values[name] = convert(value) if convert is not None else value
    return RenderState(**values)
