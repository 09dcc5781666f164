"""`effects compile`: the assembly each shader of a pass runs, as fxc /Fc listed it.

    effects compile FILE.fx [--technique T] [--pass N]
    effects compile FILE.fx --entry F --target ps_2_0

For each HLSL `compile` shader: the register table (parameter -> register, size), the
assembly with the HLSL source line above the instructions it produced, and the slots,
temporaries and constants used against the target's limits. An `asm` block is listed as
assembled, with the same counts.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

from effects.errors import EffectError, Location

if TYPE_CHECKING:  # pragma: no cover
    from rich.console import Console

    from effects.model import Effect   # the model is imported when the command runs: --help
                                       # (which adds this command's options) needs none of it


def add_compile(sub: Any, load: Any) -> None:
    p = sub.add_parser("compile", help="the assembly each shader of a pass runs (fxc /Fc listing)")
    p.add_argument("file", help="effect file (.fx)")
    p.add_argument("--technique", "-t", metavar="T", help="technique (default: the first)")
    p.add_argument("--pass", dest="pass_index", type=int, default=None, metavar="N",
                   help="pass number from 0 (default: every pass)")
    p.add_argument("--entry", metavar="F", help="compile this function instead of a pass's shaders")
    p.add_argument("--target", metavar="PROFILE", help="with --entry: vs_1_1 ... ps_3_0")
    p.add_argument("--include-root", metavar="DIR", default=None,
                   help="confine every file the effect reads to this folder")
    p.add_argument("--strict", action="store_true", help="unknown state names are errors")
    p.set_defaults(run=lambda args, console: run_compile(args, console, load))


def run_compile(args: Any, console: "Console", load: Any) -> int:
    from effects.model import CompileShader, ShaderBlock
    effect = load(args)
    out: list[str] = []
    if args.entry or args.target:
        if not (args.entry and args.target):
            raise EffectError("--entry and --target go together (e.g. --entry main --target ps_2_0)",
                              Location("<command line>", 1, 1))
        from effects.shaders.hlsl import compile_shader
        out += listing(effect, compile_shader(effect, args.entry, args.target.lower()))
    else:
        technique = effect.technique(args.technique) if args.technique else (
            effect.techniques[0] if effect.techniques else None)
        if technique is None:
            raise EffectError("the effect has no techniques", Location(effect.path, 1, 1))
        indices = range(len(technique.passes)) if args.pass_index is None else [args.pass_index]
        for i in indices:
            if not 0 <= i < len(technique.passes):
                raise EffectError(f"technique '{technique.name}' has no pass {i} (it has "
                                  f"{len(technique.passes)})", technique.location)
            p = technique.passes[i]
            for state in ("VertexShader", "PixelShader"):
                a = p.state(state)
                if a is None:
                    continue
                value = a.value
                if hasattr(value, "name") and not isinstance(value, (CompileShader, ShaderBlock)):
                    param = effect.parameter(value.name)
                    value = param.value if param is not None else value
                out.append(f"// technique {technique.name or '<anonymous>'}, pass "
                           f"{p.name or i}: {state}")
                out += shader_listing(effect, value)
                out.append("")
    console.print("\n".join(out), markup=False, highlight=False, soft_wrap=True)
    return 0


def shader_listing(effect: "Effect", value: Any) -> list[str]:
    from effects.model import CompileShader, ShaderBlock
    if isinstance(value, CompileShader):
        from effects.shaders.hlsl import compile_state
        return listing(effect, compile_state(effect, value))
    if isinstance(value, ShaderBlock):
        from effects.shaders.asm import assemble_cached
        program = assemble_cached(value)
        lines = ["//   (assembly written in the effect)"]
        lines += ["    " + line.strip() for line in value.source.strip().splitlines() if line.strip()]
        return lines + counts(program)
    return [f"//   {type(value).__name__}: no shader"]


def listing(effect: "Effect", shader: Any) -> list[str]:
    """The fxc-style listing of one compiled shader."""
    lines = [f"// {shader.function} compiled for {shader.target}", "//"]
    if shader.constants or shader.samplers:
        lines += ["// Registers:", "//", f"//   {'Name':<24} {'Reg':<5} Size",
                  f"//   {'-' * 24} {'-' * 5} ----"]
        rows = sorted(((f"c{c}", name, n) for name, (c, n) in shader.constants.items()),
                      key=lambda r: int(r[0][1:]))
        rows += sorted(((f"s{s}", name, 1) for name, s in shader.samplers.items()),
                       key=lambda r: int(r[0][1:]))
        lines += [f"//   {name:<24} {reg:<5} {n:>4}" for reg, name, n in rows]
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
    def __init__(self, effect: "Effect") -> None:
        self.files: dict[str, list[str] | None] = {}
        self.effect = effect

    def line(self, loc: Location) -> str | None:
        if loc.path not in self.files:
            try:
                with open(loc.path, encoding="utf-8", errors="replace") as f:
                    self.files[loc.path] = f.read().split("\n")
            except OSError:
                self.files[loc.path] = self._from_functions(loc.path)
        text = self.files[loc.path]
        return text[loc.line - 1] if text and 0 < loc.line <= len(text) else None

    def _from_functions(self, path: str) -> list[str] | None:
        # an effect given as text: rebuild its lines from the captured functions
        lines: dict[int, str] = {}
        for f in self.effect.functions:
            if f.location.path == path:
                for k, text in enumerate(f.source.split("\n")):
                    lines[f.location.line + k] = text
        if not lines:
            return None
        return [lines.get(i, "") for i in range(1, max(lines) + 1)]
