"""`effects doctor FILE.fx`: what the file needs from a host that it does not get.

A host (FX Composer, EffectEdit, a game) sets parameters, supplies textures and runs DXSAS
scripts around an effect; this framework does what `effects.host` does and no more. The doctor
says, for the technique a card selects, which parameters the host binds (and by what), which
ones nothing sets (they read 0), which textures are drawn with a stand-in and why, and which
script commands are not run, so a user knows why a picture looks as it does.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from effects.base.errors import EffectError, NoValidTechnique
from effects.host.diagnostics import parameters_read
from effects.model import Effect, Technique


@dataclass
class Diagnosis:
    technique: Technique | None
    why_no_technique: str | None = None
    bound: list[tuple[str, str]] = field(default_factory=list)      # (parameter, by what)
    unbound: list[tuple[str, str]] = field(default_factory=list)    # (parameter, where)
    unread: list[str] = field(default_factory=list)    # set by nothing, and not read either
    defaults: list[tuple[str, str]] = field(default_factory=list)   # (parameter, file's value)
    textures: list[tuple[str, str]] = field(default_factory=list)   # (parameter, source)
    stand_ins: list[str] = field(default_factory=list)              # warnings
    unsupported: list[str] = field(default_factory=list)            # script commands
    warnings: list[str] = field(default_factory=list)               # load warnings

    @property
    def missing(self) -> bool:
        return bool(self.unbound or self.stand_ins or self.unsupported)


def diagnose(effect: Effect, profile: Any, *, scene: Any = None, params: dict | None = None,
             technique: str | None = None) -> Diagnosis:
    from effects.host.runtime import Runtime
    from effects.host.scripts import is_render_target, unsupported_commands
    from effects.host.semantics import bind_scene, binding_source, host_would_set, ui_defaults
    runtime = Runtime(effect, profile, scene=scene, params=params or {}, backend=None)
    try:
        chosen = runtime.select(technique)
        why = None
    except NoValidTechnique as exc:
        chosen = effect.techniques[0] if effect.techniques else None
        why = str(exc).splitlines()[0]
    d = Diagnosis(chosen, why, warnings=[str(w) for w in effect.warnings])
    scene_bound = bind_scene(effect, runtime.scene, runtime.size)
    ui = ui_defaults(effect)
    given = set(params or {}) | set(runtime.scene.params)
    # with the values given (--set PSIndex=1 picks another shader of an array)
    read = parameters_read(runtime.effect, chosen) if chosen is not None else set()
    for p in effect.parameters:
        if p.name in given:
            d.bound.append((p.name, "--set / scene params"))
        elif p.name in scene_bound:
            semantic, how = binding_source(p)
            convention = {"XNA name": "XNA", "DX8 name": "DirectX 8 SDK"}.get(how) or \
                (how[:-len(" name")] if how.endswith(" name") else None)
            d.bound.append((p.name, f"bound by name ({convention} convention) as {semantic}"
                            if convention else f"semantic {semantic}" if how == "semantic"
                            else f"{how} ({semantic})"))
        elif p.name in ui:
            d.bound.append((p.name, "the middle of its UIMin..UIMax range"))
        elif p.type.is_numeric and p.value is None:
            if p.name in read:       # arrays too: Weights[4] that nothing sets reads 0
                whose = host_would_set(p)
                d.unbound.append((p.name, str(p.location) + (f"; {whose}" if whose else "")))
            else:
                d.unread.append(p.name)
        elif p.type.is_numeric and p.name in read:
            d.defaults.append((p.name, _shown(p.value)))
    if chosen is None:
        return d
    for index in range(len(chosen.passes)):
        try:
            program = runtime.lower(chosen, index)
        except EffectError as exc:
            d.stand_ins.append(f"pass {index} cannot be lowered: {exc}")
            continue
        for binding in program.textures:
            name = binding.texture
            if name is None or any(name == t for t, _ in d.textures):
                continue
            param = effect.parameter(name)
            before = len(runtime.warnings)
            texture = runtime.used_texture(name, binding.kind)
            if len(runtime.warnings) > before:
                d.textures.append((name, f"stand-in {texture.name}"))
            elif is_render_target(param):
                d.textures.append((name, "render target (drawn by the script)"))
            else:
                d.textures.append((name, texture.name or "loaded"))
    d.stand_ins.extend(str(w) for w in runtime.warnings)
    d.unsupported = [f"{c.location}: {c.name}={c.value}" for c in unsupported_commands(effect, chosen)]
    return d


def _shown(value: Any) -> str:
    """A parameter's value as the file would write it: '0.3, 0.12, 0.03' (float32 shown to
    its own precision, not as the double it widens to)."""
    import numpy as np
    flat = np.asarray(value).reshape(-1)
    if flat.dtype.kind not in "biuf":
        return str(value)
    shown = [f"{float(np.float32(x)):.7g}" if flat.dtype.kind == "f" else str(x) for x in flat[:16]]
    return ", ".join(shown) + (", ..." if flat.size > 16 else "")


def print_diagnosis(d: Diagnosis, path: str, card: str, out) -> None:
    def line(text: str = "") -> None:
        out.print(text, markup=False, highlight=False, soft_wrap=True)

    line(f"{path} on {card}:")
    for w in d.warnings:
        line(f"  load warning: {w}")
    if d.technique is None:
        line("  the effect has no techniques: nothing to draw")
        return
    name = d.technique.name or "<anonymous>"
    if d.why_no_technique:
        line(f"  {d.why_no_technique}; looking at the first technique, {name}")
    else:
        line(f"  technique {name} ({len(d.technique.passes)} pass"
             f"{'es' if len(d.technique.passes) != 1 else ''})")
    line("  bound by the host:" if d.bound else "  bound by the host: nothing")
    for param, how in d.bound:
        line(f"    {param} <- {how}")
    line("  set by nothing (they read 0):" if d.unbound else "  set by nothing: none")
    for param, where in d.unbound:
        line(f"    {param} (declared at {where})")
    if d.unread:
        line(f"  set by nothing, but {name} does not read them: {', '.join(d.unread)}")
    if d.defaults:
        line("  keep the file's default (nothing binds them):")
        for param, value in d.defaults:
            line(f"    {param} = {value}")
    if d.textures:
        line("  textures the passes sample:")
        for param, source in d.textures:
            line(f"    {param}: {source}")
    for text in d.stand_ins:
        line(f"  {text}")
    if d.unsupported:
        line("  script commands not run:")
        for text in d.unsupported:
            line(f"    {text}")
    if not d.missing:
        line("  nothing missing: the host supplies everything this technique reads")
