"""A readable summary of a loaded effect: what `effects validate FILE.fx` shows."""
from __future__ import annotations

from rich.console import Console
from rich.table import Table

from effects.model import Effect, ShaderBlock, CompileShader


def _shader_label(value, effect_path: str) -> str | None:
    if isinstance(value, ShaderBlock):
        return (f"asm {value.version or '(not D3D assembly)'} "
                f"({value.location.line_in(effect_path)})")
    if isinstance(value, CompileShader):
        return f"compile {value.profile} {value.function}()"
    return None


def print_effect_summary(effect: Effect, console: Console) -> None:
    console.print(f"[bold]{effect.path}[/bold]: {len(effect.parameters)} parameters, "
                  f"{len(effect.techniques)} techniques, {len(effect.functions)} functions")
    table = Table(show_header=True, header_style="bold")
    table.add_column("technique")
    table.add_column("pass")
    table.add_column("states", justify="right")
    table.add_column("shaders")
    for tech in effect.techniques:
        for i, p in enumerate(tech.passes):
            shaders = [s for s in (_shader_label(a.value, effect.path) for a in p.states) if s]
            table.add_row(tech.name or "<anonymous>" if i == 0 else "", p.name or f"#{i}",
                          str(len(p.states)), ", ".join(shaders))
        if not tech.passes:
            table.add_row(tech.name or "<anonymous>", "(no passes)", "0", "")
    console.print(table)
    if effect.warnings:
        console.print(f"{len(effect.warnings)} warning(s)", style="yellow")
