"""The fxc /Fc-style listing of a pass's shaders: one formatter for `effects compile` and the
viewer's listing window, so what the viewer shows for the pass it draws is what the command prints.

For each HLSL `compile` shader: the register table (parameter -> register, size), the assembly
with the HLSL source line above the instructions it produced, and the slots, temporaries and
constants used against the target's limits. An `asm` block is listed as written, with the same
counts.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

from effects.base.errors import EffectError, Location

if TYPE_CHECKING:  # pragma: no cover
    from effects.model import Effect, Technique


def pass_listing(effect: "Effect", technique: "Technique", index: int) -> list[str]:
    """The listing of pass `index` of `technique`: for its vertex then its pixel shader, a
    heading line and the shader's listing, then a blank line (passes listed one after another
    read apart)."""
    from effects.model import CompileShader, Expression, ParamRef, ShaderBlock
    if not 0 <= index < len(technique.passes):
        raise EffectError(f"technique '{technique.name}' has no pass {index} (it has "
                          f"{len(technique.passes)})", technique.location)
    p = technique.passes[index]
    out: list[str] = []
    for state in ("VertexShader", "PixelShader"):
        a = p.state(state)
        if a is None:
            continue
        value, picked = a.value, None
        if isinstance(value, Expression):
            # `VertexShader = (VSArray[VSIndex])`: the element the parameters pick now, as
            # validation judges it (a wrong index is the same located error)
            from effects.shaders.hlsl.preshader import expression_element
            element = expression_element(effect, value)
            if element is not None:
                picked = (f"// {state} = {value.text.strip()}: {element.name}[{element.index}] "
                          "at the parameters' current values")
                value = element
        if hasattr(value, "name") and not isinstance(value, (CompileShader, ShaderBlock)):
            param = effect.parameter(value.name)   # `VertexShader = <vs>`: the parameter's shader
            if param is not None:
                value = param.value
                index_of = getattr(a.value if picked is None else element, "index", None)
                if isinstance(index_of, int) and isinstance(value, (list, tuple)) \
                        and 0 <= index_of < len(value):
                    value = value[index_of]   # `VertexShader = <VSArray[1]>`: that element
        out.append(f"// technique {technique.name or '<anonymous>'}, pass "
                   f"{p.name or index}: {state}")
        if picked is not None:
            out.append(picked)
        out += shader_listing(effect, value)
        out.append("")
    if not out:   # said, so an empty listing is not mistaken for one that failed
        out = [f"// technique {technique.name or '<anonymous>'}, pass {p.name or index}: "
               "fixed function (no shaders)", ""]
    return out


def shader_listing(effect: "Effect", value: Any) -> list[str]:
    from effects.model import NullValue
    if isinstance(value, NullValue):
        return ["//   NULL: the fixed-function pipeline"]
    from effects.shaders.shader_value import shader_of
    shader = shader_of(effect, value)
    if shader is None:
        return [f"//   {type(value).__name__}: no shader"]
    if shader.compiled is not None:
        return listing(effect, shader.compiled)
    lines = ["//   (assembly written in the effect)"]
    lines += ["    " + line.strip() for line in value.source.strip().splitlines() if line.strip()]
    return lines + counts(shader.program)


def listing(effect: "Effect", shader: Any) -> list[str]:
    """The fxc-style listing of one compiled shader."""
    lines = [f"// {shader.function} compiled for {shader.target}", "//"]
    ints = getattr(shader, "int_registers", {})
    bools = getattr(shader, "bool_registers", {})
    if shader.constants or shader.samplers or ints or bools:
        lines += ["// Registers:", "//", f"//   {'Name':<24} {'Reg':<5} Size",
                  f"//   {'-' * 24} {'-' * 5} ----"]
        rows = sorted(((f"c{c}", name, n) for name, (c, n) in shader.constants.items()),
                      key=lambda r: int(r[0][1:]))
        count = getattr(shader, "register_count", lambda name: 1)
        rows += sorted(((f"i{k}", name, count(name)) for name, k in ints.items()),
                       key=lambda r: int(r[0][1:]))
        rows += sorted(((f"b{k}", name, count(name)) for name, k in bools.items()),
                       key=lambda r: int(r[0][1:]))
        table = getattr(shader, "sampler_table", None)
        samplers = table() if table is not None else {n: (s, 1) for n, s in shader.samplers.items()}
        rows += sorted(((f"s{s}", name, n) for name, (s, n) in samplers.items()),
                       key=lambda r: int(r[0][1:]))
        lines += [f"//   {name:<24} {reg:<5} {n:>4}" for reg, name, n in rows]
        lines.append("//")
    preshaders = getattr(shader, "preshaders", {})
    if preshaders:
        lines += ["// Preshader (computed on the host when the pass is drawn):", "//"]
        lines += [f"//   c{shader.constants[name][0]} = {preshaders[name].expression()}"
                  for name in sorted(preshaders, key=lambda n: shader.constants[n][0])]
        lines.append("//")
    for w in shader.warnings:
        lines.append(f"// {w}")
    source = _SourceLines(effect)
    last: tuple[str, int] | None = None
    for text, loc in zip(shader.text.rstrip("\n").split("\n"), shader.lines):
        if loc.line and (loc.path, loc.line) != last:
            last = (loc.path, loc.line)
            src = source.line(loc)
            lines.append(f"    // {loc.path}:{loc.line}: {src.strip() if src else ''}")
        lines.append(f"    {text}")
    return lines + counts(shader.program)


def counts(program: Any) -> list[str]:
    s, r = program.stats, program.rules
    parts = [f"{s.total_slots} instruction slots (the version holds {r.total_slots}, every card "
             f"{r.total_slots_min})"]
    if r.tex_slots is not None:
        parts.append(f"{s.texture_slots} texture (of {r.tex_slots})")
    if r.arith_slots is not None:
        parts.append(f"{s.arithmetic_slots} arithmetic (of {r.arith_slots})")
    parts.append(f"{s.temps_used} temporaries (of {r.registers.get('r', 0)})")
    parts.append(f"{s.constants_used} constants")
    return [f"// approximately {', '.join(parts)}"]


class _SourceLines:
    """The source line an instruction came from: from the effect's captured functions first
    (the text that was compiled, even when the file on disk has changed since -- the viewer
    lists its last good effect while a broken edit is on disk), else from the file."""

    def __init__(self, effect: "Effect") -> None:
        self.files: dict[str, list[str] | None] = {}
        self.captured: dict[str, dict[int, str]] = {}
        for f in effect.functions:
            lines = self.captured.setdefault(f.location.path, {})
            for k, text in enumerate(f.source.split("\n")):
                lines[f.location.line + k] = text

    def line(self, loc: Location) -> str | None:
        captured = self.captured.get(loc.path, {}).get(loc.line)
        if captured is not None:
            return captured
        if loc.path not in self.files:
            try:
                with open(loc.path, encoding="utf-8", errors="replace") as f:
                    self.files[loc.path] = f.read().split("\n")
            except OSError:
                self.files[loc.path] = None     # an effect given as text: only its functions
        text = self.files[loc.path]
        return text[loc.line - 1] if text and 0 < loc.line <= len(text) else None
