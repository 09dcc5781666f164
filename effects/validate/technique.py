"""Technique validation against a caps profile, collecting every reason a card cannot run it.

This plays the part of D3DX's ValidateTechnique + the driver's ValidateDevice: for each pass,
with the device state as the technique leaves it (earlier passes persist), every stage op,
argument, texture, filter, blend, compare, stencil op, render target, shader version, shader
limit and card quirk is checked, and each failure becomes a `Reason` that names the pass, the
state or instruction, where it is, what it needs and what the card has.

What is checked, and what is not:
- Fixed-function stages: the highest enabled stage against MaxTextureBlendStages, each
  ColorOp/AlphaOp against TextureOpCaps, Temp/Constant arguments and ResultArg against
  PrimitiveMiscCaps, and the argument rules every card shares (ResultArg is Current or Temp,
  without modifiers, and the last active stage writes Current). The argument modifiers
  Complement and AlphaReplicate have no caps bit in D3DCAPS9: every card accepts them.
- Textures read in a pass: how many (MaxSimultaneousTextures, fixed function only: a pixel
  shader's version sets its own sampler count), the kind (cube, volume) against TextureCaps
  (declared by `string Type`, the texture or sampler type, or, for DX8 files that cannot
  declare it, implied by the lookup: `dcl_cube`, texm3x3tex/spec/vspec, or 3-component
  camera-space texture coordinates in a fixed-function stage),
  `int Width/Height/Depth` against the size limits, power-of-two and square rules, `string
  Format` (and `bool RenderTarget`) against the formats the card lists, and each sampler's
  filters, mip filter, anisotropy and address modes.
- Frame-buffer states a pass assigns: blend factors and ops, separate alpha blending, write
  masks, alpha test, depth test, stencil, culling, depth bias, scissor, table fog.
- Shaders: the version (a vertex shader newer than the hardware's runs when the card offers
  software or mixed vertex processing, up to the runtime's software version), every
  assembly rule of that version, and the card's own limits (instruction slots, temporaries,
  constants, dependent reads, render-target outputs; a vertex shader over the hardware's
  limits runs in software where the card offers it); shader constant states against the
  register files they write (`constants`). An HLSL `compile ps_2_0 f()` is compiled for
  its profile (effects.shaders.hlsl) and its assembly is judged by the same rules; a
  function that does not compile rejects the technique, as D3DX rejects a technique whose
  shader fails to create.
- Card quirks (caps.py's vocabulary): severity `error` rejects, `warning` is reported in
  `Validation.warnings` and rejects nothing.
A state whose value is a parameter without a value cannot be checked before the application
sets it: it is skipped with a note, never a crash. A preshader expression is judged at the
parameters' current values (`expressions`), and left with a note where it reads a parameter
without a value. Point sizes are judged against MaxPointSize where the profile gives it
(`points`).

The checks live in one module per job, each a mixin of the pass checker here: `stages`
(fixed-function stages), `textures` (textures, samplers, formats), `framebuffer` (one loop
over the states whose row in `effects.d3d9.states` names the caps field that limits them: blend,
compare, stencil, cull, depth and raster states), `shaders` (shader versions, assembly,
limits); `values` spells state values. Values are read with the device state's typed readers
(`effects.d3d9.device`), the ones lowering uses, and each pass's device state is kept in its
PassReport for lowering to draw from. This module holds the answer types, the pass checker's
helpers and run order, and the card quirk rules.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Iterable, Sequence

from effects.d3d9.caps import FIELDS, CapsProfile, Quirk, bit_prefix
from effects.d3d9.device import NO_DEFAULT, DeviceState, pass_states
from effects.base.errors import EffectError, Location
from effects.frontend.references import pass_reference_problems
from effects.model import Effect, EnumValue, Expression, NullValue, ParamRef, Pass, Technique
from effects.shaders.shader_value import Shader
from effects.validate.constants import ConstantChecks
from effects.validate.expressions import ExpressionValues
from effects.validate.framebuffer import FrameBufferChecks
from effects.validate.points import PointChecks
from effects.validate.shaders import ShaderChecks, software_vs_version
from effects.validate.stages import StageChecks
from effects.validate.textures import TextureChecks, texture_kind
from effects.validate.vertex_textures import VertexTextureChecks
from effects.d3d9.stage_ops import TA_TEXTURE
from effects.validate.values import _is_indexed, spelled

__all__ = ["PassReport", "Reason", "Validation", "software_vs_version", "spelled", "texture_kind",
           "validate_on_cards", "validate_technique"]


@dataclass(frozen=True)
class Reason:
    """Why a card cannot run a technique (or, as a warning, what misbehaves): one requirement, located."""

    technique: str | None
    pass_name: str
    location: Location
    subject: str       # what asked for it: "ColorOp[1] = BumpEnvMap", "PixelShader (ps_1_4)"
    requirement: str   # what it needs: "D3DTEXOPCAPS_BUMPENVMAP"
    card_value: str    # what the card has: "not in TextureOpCaps", "PixelShaderVersion 1.1"
    message: str       # one plain sentence
    effect_path: str = ""   # the effect file validated: a location in another (an #include)
                            # names its file
    # The language error (EffectError.language: fxc refuses the program for every target)
    # this reason stands for, None for a refusal by this card or target: the commands print
    # it as a located error, with its source line, rather than as one card's reason.
    error: EffectError | None = field(default=None, compare=False, repr=False)

    @property
    def language(self) -> bool:
        return self.error is not None

    def __str__(self) -> str:
        return f"pass {self.pass_name} ({self.location.line_in(self.effect_path)}): {self.message}"


@dataclass
class PassReport:
    """One pass on one card: its reasons and the resources it uses."""

    name: str
    index: int
    location: Location
    reasons: list[Reason] = field(default_factory=list)
    warnings: list[Reason] = field(default_factory=list)   # quirks of severity 'warning'
    notes: list[str] = field(default_factory=list)         # what could not be checked, and why
    stages: int = 0             # fixed-function texture stages in use
    textures: int = 0           # textures read at once
    render_targets: int = 1     # colour outputs written (oC0..oC3)
    pixel_shader: str | None = None     # 'ps_1_1', ...
    vertex_shader: str | None = None    # 'vs_1_1', ...
    software_vertex_processing: bool = False   # the vertex shader runs on the CPU
    # The device state this pass draws with (earlier passes persisting): what was checked is
    # what lowering draws from (`effects.lower.passes.lower_pass(..., validation=)`).
    state: DeviceState | None = field(default=None, repr=False, compare=False)
    # The shaders the checks judged, by state name ('PixelShader', 'VertexShader'): each one's
    # program and register bindings (`effects.shaders.shader_value.Shader`), which lowering
    # binds from rather than working them out again.
    shaders: dict[str, Shader] = field(default_factory=dict, repr=False, compare=False)

    @property
    def ok(self) -> bool:
        return not self.reasons


@dataclass
class Validation:
    """The validator's answer for one technique on one card (naga's ModuleInfo, in spirit):
    per pass its reasons, the resources it uses and the device state it draws with."""

    technique: Technique
    profile: CapsProfile
    pass_reports: list[PassReport]

    @property
    def ok(self) -> bool:
        return all(p.ok for p in self.pass_reports)

    @property
    def passes(self) -> int:
        """The pass count: what D3DX's Begin() returns."""
        return len(self.pass_reports)

    @property
    def reasons(self) -> list[Reason]:
        return [r for p in self.pass_reports for r in p.reasons]

    @property
    def warnings(self) -> list[Reason]:
        return [r for p in self.pass_reports for r in p.warnings]

    @property
    def notes(self) -> list[str]:
        return [f"pass {p.name}: {n}" for p in self.pass_reports for n in p.notes]


class _Reads(DeviceState):
    """A pass's device state as the checks read it, each answer kept: every card's checker
    asks the same questions of the same state (nothing here depends on the card), so on the
    cards after the first they are dictionary lookups. Read only: it shares the state's
    values (no check writes to the state it judges); a reader that raises is asked again."""

    def __init__(self, state: DeviceState) -> None:
        super().__init__(state.effect, state.values, state.host)
        self._got: dict = {}
        self._enums: dict = {}
        self._ints: dict = {}

    def copy(self) -> DeviceState:
        return DeviceState(self.effect, dict(self.values), self.host)

    def get(self, name: str, index: int | None = None) -> Any:
        key = (name, index)
        try:
            return self._got[key]
        except KeyError:
            value = self._got[key] = DeviceState.get(self, name, index)
            return value

    def get_enum(self, name: str, index: int | None = None, default: Any = NO_DEFAULT) -> Any:
        return self._kept(self._enums, DeviceState.get_enum, name, index, default)

    def get_int(self, name: str, index: int | None = None, default: Any = NO_DEFAULT) -> Any:
        return self._kept(self._ints, DeviceState.get_int, name, index, default)

    def _kept(self, answers: dict, read: Any, name: str, index: int | None, default: Any) -> Any:
        """`read`'s answer for (name, index, default), asked once (no default: the reader's)."""
        key = (name, index, default)
        try:
            return answers[key]
        except KeyError:
            value = read(self, name, index) if default is NO_DEFAULT \
                else read(self, name, index, default)
            answers[key] = value
            return value


class _PassAnalysis:
    """What the checks of one pass read that no card changes, made once for every card the
    pass is validated on in one call (`validate_on_cards`): the device state the pass draws
    with, its expression-valued states evaluated at the parameters' current values, the
    state as the checks read it (`_Reads`) and the pass's bad parameter references. Made
    afresh for each call: between calls a host may set other parameter values."""

    __slots__ = ("state", "expressions", "reads", "programs", "kept", "_references")

    def __init__(self, effect: Effect, state: DeviceState, programs: dict, cards: int) -> None:
        self.state = state
        # the checks read expression-valued states as their values now (the report keeps the
        # state as written: lowering evaluates again when it draws)
        self.expressions = ExpressionValues(effect, state)
        self.reads = _Reads(self.expressions.state)
        # shader value id -> (value, its program or EffectError), for every pass of the call
        self.programs = programs
        # the card-free part of a check, by key (`_PassChecker.card_free`); None for one card
        self.kept: dict[Any, tuple[Any, list[str]]] | None = {} if cards > 1 else None
        self._references: list[tuple[Location, str]] | None = None

    def references(self, effect: Effect, p: Pass) -> list[tuple[Location, str]]:
        if self._references is None:
            self._references = pass_reference_problems(effect, p)
        return self._references


class _PassChecker(StageChecks, TextureChecks, FrameBufferChecks, ShaderChecks,
                   VertexTextureChecks, PointChecks, ConstantChecks):
    """Runs every check for one pass and collects its reasons."""

    def __init__(self, effect: Effect, technique: Technique, p: Pass, index: int,
                 analysis: _PassAnalysis, profile: CapsProfile) -> None:
        self.effect, self.technique, self.pass_, self.profile = effect, technique, p, profile
        self.analysis = analysis
        # each report holds its own copy of the pass's state, as when every card played the
        # passes through itself
        self.report = PassReport(p.name or str(index), index, p.location,
                                 state=analysis.state.copy())
        self.expressions = analysis.expressions
        self.state = analysis.reads
        # quirks that make a reported caps bit or format unusable: (field, bit) / (format, usage)
        self.unreliable_bits, self.unreliable_formats = profile.unreliable

    # -- reason helpers ---------------------------------------------------------------------
    def fail(self, location: Location, subject: str, requirement: str, card_value: str,
             message: str, error: EffectError | None = None) -> None:
        """A reason this pass cannot run; `error` when it is a language error (Reason.error)."""
        self.report.reasons.append(Reason(self.technique.name, self.report.name, location,
                                          subject, requirement, card_value, message,
                                          self.effect.path,
                                          error if error is not None and error.language else None))

    def warn(self, location: Location, subject: str, quirk: Quirk) -> None:
        reason = Reason(self.technique.name, self.report.name, location, subject,
                        f"driver rule {quirk.id}", quirk.text,
                        f"{subject}: {quirk.text} ({self.card()})", self.effect.path)
        if reason not in self.report.warnings:
            self.report.warnings.append(reason)

    def caution(self, location: Location, subject: str, requirement: str, card_value: str,
                message: str) -> None:
        """A warning that is no driver quirk: what the card does differently, rejecting nothing."""
        reason = Reason(self.technique.name, self.report.name, location, subject, requirement,
                        card_value, message, self.effect.path)
        if reason not in self.report.warnings:
            self.report.warnings.append(reason)

    def note(self, text: str) -> None:
        if text not in self.report.notes:
            self.report.notes.append(text)

    def card_free(self, key: Any, make: Callable[[], Any]) -> Any:
        """`make()`: the part of a check that reads nothing of the card (what to ask of it),
        made once per pass for all the cards one call validates on (the pass analysis keeps
        it under `key`). The notes it makes are kept with it and told on every card, at the
        same point and in the same order, as if it ran again."""
        if self.analysis.kept is None:
            return make()
        kept = self.analysis.kept.get(key)
        if kept is None:
            notes, self.report.notes = self.report.notes, []
            try:
                made = make()
            finally:
                told, self.report.notes = self.report.notes, notes
            kept = self.analysis.kept[key] = (made, told)
        for text in kept[1]:
            self.note(text)
        return kept[0]

    def where(self, name: str, index: int | None = None) -> Location:
        return self.state.where(name, index, self.pass_.location)

    def card(self) -> str:
        return self.profile.display_name or self.profile.name

    def has_reliable_bit(self, caps_field: str, bit: str) -> bool:
        """Whether `need_bit` would pass without a word: the card has the bit, no quirk on it."""
        return (bit in (FIELDS[caps_field].table or {}) and self.profile.has(caps_field, bit)
                and (caps_field, bit) not in self.unreliable_bits)

    def need_bit(self, caps_field: str, bit: str, subject: str, location: Location) -> None:
        """Fail unless the card reports `bit` in `caps_field` and no error quirk disowns it;
        messages name the bit with its header prefix (`effects.d3d9.caps.bit_prefix`)."""
        table = FIELDS[caps_field].table or {}
        prefix = bit_prefix(caps_field)
        if bit not in table:  # a value no caps bit covers (Direct3D 9Ex additions ...)
            self.fail(location, subject, f"{prefix}{bit}", f"not in {caps_field}",
                      f"{subject} needs {prefix}{bit}, which no Direct3D 9 caps report; "
                      f"the {self.card()} does not have it")
            return
        if not self.profile.has(caps_field, bit):
            self.fail(location, subject, f"{prefix}{bit}", f"not in {caps_field}",
                      f"{subject} needs {prefix}{bit}; the {self.card()} does not have it")
            return
        quirk = self.unreliable_bits.get((caps_field, bit))
        if quirk is not None:
            self.quirk_hit(quirk, location, subject)

    def quirk_hit(self, quirk: Quirk, location: Location, subject: str) -> None:
        if quirk.severity == "error":
            self.fail(location, subject, f"driver rule {quirk.id}", quirk.text,
                      f"{subject}: {quirk.text} ({self.card()})")
        else:
            self.warn(location, subject, quirk)

    def unknown(self, name: str, index: int | None = None) -> bool:
        """True (with a note) when the value in force cannot be known before the application
        sets it: an uninitialised parameter or a preshader expression."""
        value = self.state.get(name, index)
        if not isinstance(value, (ParamRef, Expression)):
            return False
        shown = f"{name}[{index}]" if index is not None and _is_indexed(name) else name
        what = (f"parameter {value.name}, which has no value" if isinstance(value, ParamRef)
                else f"the expression '{value.text}'")
        a = self.state.assignment(name, index)
        pending = self.expressions.pending.get(a.location) if a is not None else None
        if pending is None:
            self.note(f"{shown} is set from {what}: not checked until the application sets it")
        elif pending:
            self.note(pending)
        return True

    # -- the checks -------------------------------------------------------------------------
    def run(self) -> PassReport:
        for shown, err in self.expressions.errors:
            self.fail(err.location, shown, "a value its expression evaluates to", "no value",
                      err.message)
        ps = self.shader("PixelShader")
        vs = self.shader("VertexShader")
        if ps is None:
            self.check_texture_stages()
        else:
            self.check_pixel_shader(ps)
        if vs is not None:
            self.check_vertex_shader(vs)
            self.check_vertex_textures(vs)
        self.check_shader_model_3_pairing(ps, vs)
        self.check_constant_registers()
        self.check_textures(ps is not None)
        self.check_framebuffer()
        self.check_quirks()
        self.check_points()
        self.check_references()
        self.report.reasons = self.expressions.annotate(self.report.reasons)
        self.report.warnings = self.expressions.annotate(self.report.warnings)
        return self.report

    def check_references(self) -> None:
        """`Texture[0] = <Nope>`, `<Tint>` a float4: no card runs a pass naming what is not there."""
        for location, message in self.analysis.references(self.effect, self.pass_):
            self.fail(location, message.split(" = ", 1)[0], "a declared parameter of the state's type",
                      "not in the effect", message)

    def shader(self, name: str) -> tuple[Any, Location] | None:
        """The shader in force (None for the fixed-function pipeline), with its location."""
        a = self.state.assignment(name)
        if a is None:
            return None
        value = self.state.resolve(a.value)
        if isinstance(value, Expression):
            # `(PSArray[ShaderIndex])`: judged as the shader the parameters pick now, as
            # D3DX's ValidateTechnique runs the preshader with the current values
            from effects.shaders.hlsl.preshader import expression_element   # lark: when needed
            try:
                element = expression_element(self.effect, value)
            except EffectError as err:
                self.fail(err.location, name, "a shader the parameters pick", "no shader",
                          err.message)
                return None
            if element is not None:
                self.note(f"{name} = {value.text.strip()}: {element.name}[{element.index}] at "
                          f"the parameters' current values is checked")
                value = self.state.resolve(element)
        if isinstance(value, (NullValue, type(None))):
            return None
        if isinstance(value, (ParamRef, Expression)):
            self.unknown(name)
        return value, a.location


    # -- values as the docs spell them (every check's messages use these) ----------------------
    def _shown(self, name: str, index: int | None = None) -> str:
        """A state's value as the docs spell it ('BumpEnvMap')."""
        return spelled(name, self.state.get_enum(name, index, default=None) or "default")

    def _shown_flags(self, name: str, index: int | None = None) -> str:
        value = self.state.get(name, index)
        if isinstance(value, EnumValue) and value.names:
            return " | ".join(spelled(name, n) for n in value.names)
        return self._shown(name, index)


    # card quirks ---------------------------------------------------------------------------------
    def check_quirks(self) -> None:
        """Driver rules beyond the caps bits (caps.py documents the rule vocabulary). Rules of
        severity 'error' (ValidateDevice failed on the card) reject a technique; 'warning'
        rules are reported as warnings. cap_unreliable and format_unreliable are applied where
        the bit or format is checked."""
        for quirk in self.profile.quirks:
            rule = _QUIRK_CHECKS.get(quirk.rule)
            if rule is None:
                continue
            for loc, subject in rule(self, quirk):
                self.quirk_hit(quirk, loc, subject)

    def _quirk_arg_not_texture(self, quirk: Quirk) -> Iterable[tuple[Location, str]]:
        if self.shader("PixelShader") is not None:
            return
        channel = quirk.get("channel") or "both"
        prefixes = {"color": [("ColorOp", "ColorArg")], "alpha": [("AlphaOp", "AlphaArg")]}.get(
            channel, [("ColorOp", "ColorArg"), ("AlphaOp", "AlphaArg")])
        for stage in self.active_stages():
            for op_state, arg_prefix in prefixes:
                if self.state.get_enum(op_state, stage, default=None) != quirk.get("op"):
                    continue
                arg = f"{arg_prefix}{quirk.get('arg')}"
                if self.arg_select(arg, stage) == TA_TEXTURE:
                    yield (self.where(arg, stage),
                           f"{op_state}[{stage}] = {self._shown(op_state, stage)} with {arg}[{stage}] = Texture")

    def _quirk_textures_need_op(self, quirk: Quirk) -> Iterable[tuple[Location, str]]:
        if self.shader("PixelShader") is not None:
            return
        units = self.sampled_units(False)
        if len(units) <= int(quirk.get("max_textures")):
            return
        ops = set(quirk.get("ops") or ())
        if not any(self.state.get_enum("ColorOp", s, default=None) in ops for s in self.active_stages()):
            yield self.where("Texture", units[-1]), f"{len(units)} textures in one pass"

    def _quirk_op_stages(self, quirk: Quirk) -> Iterable[tuple[Location, str]]:
        if self.shader("PixelShader") is not None:
            return
        allowed = set(quirk.get("stages") or ())
        for stage in self.active_stages():
            for op_state in ("ColorOp", "AlphaOp"):
                if self.state.get_enum(op_state, stage, default=None) == quirk.get("op") and stage not in allowed:
                    yield self.where(op_state, stage), f"{op_state}[{stage}] = {self._shown(op_state, stage)}"

    def _quirk_max_textures(self, quirk: Quirk) -> Iterable[tuple[Location, str]]:
        units = self.sampled_units(self.shader("PixelShader") is not None)
        if len(units) > int(quirk.get("count")):
            yield self.where("Texture", units[-1]), f"{len(units)} textures in one pass"


_QUIRK_CHECKS: dict[str, Callable[[_PassChecker, Quirk], Iterable[tuple[Location, str]]]] = {
    "arg_not_texture": _PassChecker._quirk_arg_not_texture,
    "textures_need_op": _PassChecker._quirk_textures_need_op,
    "op_stages": _PassChecker._quirk_op_stages,
    "max_textures": _PassChecker._quirk_max_textures,
}


def validate_technique(effect: Effect, technique: Technique, profile: CapsProfile) -> Validation:
    """Validate every pass of `technique` on `profile`, collecting all reasons."""
    return validate_on_cards(effect, technique, (profile,))[0]


def validate_on_cards(effect: Effect, technique: Technique,
                      profiles: Sequence[CapsProfile]) -> list[Validation]:
    """`validate_technique` on each of `profiles`, in order: the same answers, with what the
    checks read of each pass that no card changes (`_PassAnalysis`) made once for all of them."""
    programs: dict = {}
    analyses = [(p, _PassAnalysis(effect, state, programs, len(profiles)))
                for p, state in pass_states(effect, technique.passes)]
    return [Validation(technique, profile,
                       [_PassChecker(effect, technique, p, i, analysis, profile).run()
                        for i, (p, analysis) in enumerate(analyses)])
            for profile in profiles]
