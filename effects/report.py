"""Tables a person reads: techniques × cards with reasons, the selection matrix, the cards."""
from __future__ import annotations

from typing import Mapping, Sequence

from rich.console import Console
from rich.table import Table

from .caps import CapsProfile
from .model import Effect
from .select import find_valid_technique
from .validate import validate_technique


def _tech_name(tech) -> str:
    return tech.name or "<anonymous>"


def print_validation_table(effect: Effect, profiles: Sequence[CapsProfile], console: Console,
                           *, why: bool = False) -> bool:
    """Print techniques × cards (✓ with pass count, ✗ with the first reason, or all with `why`).
    Returns whether any card can run any technique."""
    table = Table(title=effect.path, show_lines=True, header_style="bold")
    table.add_column("technique")
    for p in profiles:
        table.add_column(p.name)
    any_valid = False
    for tech in effect.techniques:
        row = [_tech_name(tech)]
        for profile in profiles:
            v = validate_technique(effect, tech, profile)
            if v.ok:
                any_valid = True
                row.append(f"[green]✓[/green] {v.passes} pass{'es' if v.passes != 1 else ''}")
            else:
                shown = v.reasons if why else v.reasons[:1]
                row.append("[red]✗[/red] " + "\n".join(_escape(str(r)) for r in shown))
        table.add_row(*row)
    selected = [find_valid_technique(effect, p) for p in profiles]
    table.add_row("[bold]selected[/bold]", *[_tech_name(t) if t else "[red]none[/red]" for t in selected])
    console.print(table)
    return any_valid


def _escape(text: str) -> str:
    return text.replace("[", "\\[")


def matrix(effects: Mapping[str, Effect], profiles: Sequence[CapsProfile], policy="first") -> dict:
    """{effect: {profile: {"technique": name|None, "passes": n, "rejected": {tech: [reason...]}}}}"""
    out: dict = {}
    for path, effect in effects.items():
        per_card: dict = {}
        for profile in profiles:
            chosen = find_valid_technique(effect, profile, policy)
            rejected = {}
            passes = 0
            for tech in effect.techniques:
                v = validate_technique(effect, tech, profile)
                if tech is chosen:
                    passes = v.passes
                elif not v.ok:
                    rejected[_tech_name(tech)] = [str(r) for r in v.reasons]
            per_card[profile.name] = {"technique": chosen.name if chosen else None,
                                      "passes": passes, "rejected": rejected}
        out[path] = per_card
    return out


def print_matrix(result: dict, console: Console) -> None:
    profiles = list(next(iter(result.values())).keys()) if result else []
    table = Table(header_style="bold")
    table.add_column("card")
    for path in result:
        table.add_column(path)
    for name in profiles:
        row = [name]
        for path in result:
            cell = result[path][name]
            row.append(f"{cell['technique']} ({cell['passes']})" if cell["technique"] else "[red]none[/red]")
        table.add_row(*row)
    console.print(table)


def print_profiles(profiles: Sequence[CapsProfile], console: Console) -> None:
    table = Table(header_style="bold")
    for col in ("card", "name", "generation", "stages/textures", "EMBM", "dot3", "ps", "vs",
                "vertex processing"):
        table.add_column(col)
    for p in profiles:
        ps = p.pixel_shader_version
        vs = p.vertex_shader_version
        table.add_row(p.name, p.display_name, p.generation,
                      f"{p.get('MaxTextureBlendStages')}/{p.get('MaxSimultaneousTextures')}",
                      "✓" if p.has("TextureOpCaps", "BUMPENVMAP") else "",
                      "✓" if p.has("TextureOpCaps", "DOTPRODUCT3") else "",
                      f"{ps[0]}.{ps[1]}" if ps > (0, 0) else "-",
                      f"{vs[0]}.{vs[1]}" if vs > (0, 0) else "-",
                      ", ".join(sorted(p.vertex_processing)))
    console.print(table)
