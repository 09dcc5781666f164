"""Shader checks: the version against the card (a vertex shader newer than the hardware's runs
in software vertex processing where the card offers it), every assembly rule of that version,
the card's own limits. HLSL `compile` shaders are compiled for their target
(effects.shaders.hlsl) and the assembly they compile to is judged by the same rules.

A mixin of `validate._PassChecker`: it uses the checker's state, profile, report
and reason helpers (fail, need_bit, where, unknown ...)."""
from __future__ import annotations

from typing import Any

from effects.d3d9.caps import CapsProfile
from effects.base.errors import EffectError, Location
from effects.model import CompileShader, ShaderBlock


def _version(text: str | None) -> tuple[int, int]:
    if not text:
        return (0, 0)
    digits = [int(p) for p in text.replace("_", ".").split(".") if p.isdigit()]
    return (digits + [0, 0])[0], (digits + [0, 0])[1]


def _version_text(v: tuple[int, int]) -> str:
    return f"{v[0]}.{v[1]}"


def software_vs_version(profile: CapsProfile) -> tuple[int, int]:
    """The vertex shader version the runtime runs on the CPU for this card ((0, 0): none).
    Software and mixed devices both offer it (mixed switches between the two pipelines)."""
    if not profile.vertex_processing & {"software", "mixed"}:
        return (0, 0)
    return _version(profile.get("SoftwareVertexShaderVersion", "3.0"))


class ShaderChecks:
    """The pixel and vertex shader checks of a pass."""

    def not_direct3d(self, value: Any, loc: Location, state_name: str) -> bool:
        """An asm block without a version token is not Direct3D assembly (an OpenGL ARB
        program `!!ARBfp1.0`, a body missing `ps.1.1`): D3DX cannot assemble it."""
        if not isinstance(value, ShaderBlock) or value.version is not None:
            return False
        first = value.source.strip().split(None, 1)[0][:20] if value.source.strip() else ""
        why = (f"is an OpenGL ARB program ('{first}'), not Direct3D shader assembly"
               if first.startswith("!!ARB") else
               "does not start with a version token (such as ps.1.1 or vs_2_0), so it is not "
               "Direct3D shader assembly")
        self.fail(_block_location(value, loc), state_name, "a Direct3D assembly shader",
                  "not Direct3D assembly", f"{state_name}: the asm block {why}")
        return True

    def check_pixel_shader(self, shader: tuple[Any, Location]) -> None:
        value, loc = shader
        have = self.profile.pixel_shader_version
        if self.not_direct3d(value, loc, "PixelShader"):
            return
        version = _shader_version(value)
        if version is None:
            return
        self.report.pixel_shader = _version_label("ps", version)
        if version > have:
            label = _written_label("ps", value, version)
            limit = (f"runs pixel shaders up to {_version_label('ps', have)}" if have > (0, 0)
                     else "has no pixel shader hardware")
            self.fail(_block_location(value, loc), f"PixelShader ({label})",
                      f"PixelShaderVersion >= {_version_text(version)}",
                      f"PixelShaderVersion {_version_text(have)}",
                      f"PixelShader is {label}; the {self.card()} {limit}")
            return
        self.check_assembly(value, "PixelShader")

    def check_vertex_shader(self, shader: tuple[Any, Location]) -> None:
        value, loc = shader
        if self.not_direct3d(value, loc, "VertexShader"):
            return
        version = _shader_version(value)
        if version is None:
            return
        label = _version_label("vs", version)
        self.report.vertex_shader = label
        hardware = self.profile.vertex_shader_version
        software = software_vs_version(self.profile)
        if version > hardware and version > software:
            label = _written_label("vs", value, version)
            limit = (f"runs vertex shaders up to {_version_label('vs', hardware)}" if hardware > (0, 0)
                     else "has no vertex shader hardware")
            offer = (f"its software vertex processing runs up to {_version_label('vs', software)}"
                     if software > (0, 0) else "it offers no software vertex processing")
            self.fail(_block_location(value, loc), f"VertexShader ({label})",
                      f"VertexShaderVersion >= {_version_text(version)} or software vertex processing",
                      f"VertexShaderVersion {_version_text(hardware)}, processing: "
                      f"{', '.join(sorted(self.profile.vertex_processing))}",
                      f"VertexShader is {label}; the {self.card()} {limit} and {offer}")
            return
        in_software = version > hardware
        if in_software:
            # valid, but not on the card's vertex hardware: said, so a ✓ on a DX8 card for a
            # vs_2_0 (every Kodu technique on the GeForce3 but for its ps_2_0) is not a surprise
            above = (f"above the {self.card()}'s {_version_label('vs', hardware)}"
                     if hardware > (0, 0) else f"and the {self.card()} has no vertex shader hardware")
            self.note(f"VertexShader is {label}, {above}: it runs in software vertex processing "
                      "(a device created with D3DCREATE_SOFTWARE_VERTEXPROCESSING or "
                      "D3DCREATE_MIXED_VERTEXPROCESSING)")
        if not in_software and software >= version and self.assembly_problems(value, software=False):
            # over the hardware's limits (constants, temporaries): software processing runs it
            if not self.assembly_problems(value, software=True):
                in_software = True
                self.note("the vertex shader exceeds the hardware's limits and runs in software "
                          "vertex processing")
        self.report.software_vertex_processing = in_software
        self.check_assembly(value, "VertexShader", software=in_software)

    def check_shader_model_3_pairing(self, ps: tuple[Any, Location] | None,
                                     vs: tuple[Any, Location] | None) -> None:
        """Shader Model 3 runs only with itself: a ps_3_0 needs a vs_3_0 (not an older vertex
        shader, nor the fixed-function pipeline), and a vs_3_0 in hardware a ps_3_0; a vs_3_0
        in software vertex processing goes with any pixel shader (DirectX 9 "Shader Model 3":
        "you may not use vs_3_0 or ps_3_0 with any other shader versions, and you may not use
        either shader type with the fixed function pipeline ... software-only vs_3_0 shaders
        may be used with any pixel shader version")."""
        report = self.report
        ps3, vs3 = report.pixel_shader == "ps_3_0", report.vertex_shader == "vs_3_0"
        if ps3 == vs3 or (vs3 and report.software_vertex_processing):
            return
        if ps3:
            shader, other = ps, (f"a {report.vertex_shader} vertex shader"
                                 if report.vertex_shader else "the fixed-function vertex pipeline")
            subject = "PixelShader (ps_3_0)"
        else:
            shader, other = vs, (f"a {report.pixel_shader} pixel shader"
                                 if report.pixel_shader else "the fixed-function pixel pipeline")
            subject = "VertexShader (vs_3_0)"
        if shader is None:
            return
        self.fail(_block_location(shader[0], shader[1]), subject,
                  "vs_3_0 with ps_3_0", other,
                  f"{subject} runs with {other}; Shader Model 3 shaders run only with each "
                  "other in hardware (a vs_3_0 in software vertex processing excepted)")

    def program(self, value: Any, state_name: str) -> Any:
        """The Shader of `value` (`effects.shaders.shader_value.shader_of`: its program and
        register bindings), made once per shader for all the cards one call validates on (the
        pass analysis keeps it) and recorded on the pass report under `state_name`, where
        lowering binds from it; None for a value that is no shader. An error is raised again."""
        memo = self.analysis.programs
        held = memo.get(id(value))
        if held is None or held[0] is not value:
            from effects.shaders.shader_value import shader_of
            try:
                result = shader_of(self.effect, value)
            except EffectError as err:
                result = err
            held = memo[id(value)] = (value, result)
        if isinstance(held[1], EffectError):
            raise held[1]
        if held[1] is not None:
            self.report.shaders[state_name] = held[1]
        return held[1]

    def assembly_problems(self, value: Any, software: bool) -> bool:
        """Whether a vertex shader breaks its version's rules or the card's limits."""
        from effects.shaders.asm import card_limit_violations, check_cached
        try:
            shader = self.program(value, "VertexShader")
        except EffectError:
            return True
        if shader is None:
            return False
        program = shader.program
        return bool(check_cached(program)) or any(
            True for _ in card_limit_violations(program, self.profile, software=software))

    def check_assembly(self, value: Any, state_name: str, software: bool = False) -> None:
        from effects.shaders.asm import card_limit_violations, check_cached
        try:
            shader = self.program(value, state_name)
        except EffectError as err:
            what = "HLSL that compiles" if isinstance(value, CompileShader) else "valid shader assembly"
            self.fail(err.location, state_name, what, "compile error" if isinstance(value, CompileShader)
                      else "assembly error", err.message)
            return
        if shader is None:
            return
        program = shader.program
        errors = check_cached(program)
        for err in errors:
            self.fail(err.location, state_name, "valid shader assembly", "assembly error", err.message)
        # The instruction table's `lowers` column: what does not lower cannot render, so it
        # is not valid on any card (valid means renders). Asked of well-formed programs only.
        from effects.shaders.asm.limits import lowering_cached
        try:
            ints = self.state.int_constants("Pixel" if state_name == "PixelShader" else "Vertex")
        except EffectError as err:
            self.fail(err.location, state_name, "integer constants", "not numbers", err.message)
            ints = {}
        for err in ([] if errors else lowering_cached(program, ints)):
            self.fail(err.location, state_name, "instructions this framework lowers",
                      "not lowered", err.message)
        if program.kind == "ps":
            self.report.render_targets = max(1, program.stats.highest.get("oC", 0) + 1)
        for loc, subject, requirement, card_value, message in card_limit_violations(
                program, self.profile, software=software):
            self.fail(loc, subject, requirement, card_value, f"{message}; the {self.card()} has {card_value}")


def _shader_version(value: Any) -> tuple[int, int] | None:
    if isinstance(value, ShaderBlock):
        return _version(value.version) if value.version else None
    if isinstance(value, CompileShader):
        return _version(value.profile)
    return None


def _version_label(kind: str, version: tuple[int, int]) -> str:
    return f"{kind}_{version[0]}_{version[1]}"


def _written_label(kind: str, value: Any, version: tuple[int, int]) -> str:
    """The shader's version as a reason names it: the profile as written where it is one of
    the 2_x family (ps_2_a, ps_2_b, vs_2_x: their version is 2.0, their limits are the
    card's 2.0 extended caps), else `_version_label`."""
    text = value.profile if isinstance(value, CompileShader) else getattr(value, "version", None)
    written = (text or "").strip().lower().replace(".", "_")
    if written.startswith(f"{kind}_2_") and written[5:] in ("a", "b", "x", "sw"):
        return written
    return _version_label(kind, version)


def _block_location(value: Any, fallback: Location) -> Location:
    """Where a shader's version is written (the first token of an asm block), else where the
    shader is (a `compile` expression), else the assignment."""
    loc = getattr(value, "location", None)
    if loc is None or not loc.line:
        return fallback
    if isinstance(value, ShaderBlock):
        text = value.source
        start = len(text) - len(text.lstrip())
        if start < len(text):
            before = text[:start]
            lines = before.count("\n")
            if lines == 0:
                return Location(loc.path, loc.line, loc.column + start)
            return Location(loc.path, loc.line + lines, start - before.rfind("\n"))
    return loc
