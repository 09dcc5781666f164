"""Tables a person reads: techniques × cards with reasons, the selection matrix, the cards.

`matrix()` is also the JSON the command line prints (docs/design.md's shape):
    {effect: {profile: {"technique": name|null, "passes": n, "rejected": {technique: [reason, ...]}}}}
and, where fidelity is measured (`--fidelity`, `--policy fidelity`), "fidelity": the chosen
technique's picture against the effect's best technique's (effects.host.fidelity), as
{"ssim": 0.9312, "psnr": 27.41, "best": name} -- psnr null for identical pictures -- or null
where there is nothing to measure (no technique chosen, or none runs on refrast).
"rejected" lists every technique the card cannot run, with all its reasons, and each valid
technique the policy refused (max-passes, max-cost), with the policy's reason. A card whose
selection fell past a technique with a language error (HLSL that compiles for no target) has
"error": that located error, which the command prints as an error.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any, Mapping, Sequence

from effects.base.errors import EffectError

if TYPE_CHECKING:  # pragma: no cover
    # the cards' reader (and PyYAML) loads where cards are read: a matrix whose rows are all
    # stored (matrix_store) reads none
    from effects.d3d9.caps import CapsProfile
    # rich loads when a table is drawn (the command line's console is made on first use)
    from rich.console import Console
    # Validation (and numpy with it) loads when a table needs it: `effects profiles` does not.
    from effects.model import Effect, Technique
    from effects.validate.select import PolicyLike
    from effects.validate.technique import Validation
    from effects.cli.matrix_store import MatrixJob


def technique_name(tech: Technique | None) -> str:
    if tech is None:
        return "none"
    return tech.name or "<anonymous>"


def validate_all(effect: Effect, profile: CapsProfile) -> list[Validation]:
    """Every technique of `effect` validated on `profile`, in file order."""
    return validate_cards(effect, (profile,))[0]


def validate_cards(effect: Effect, profiles: Sequence[CapsProfile]) -> list[list[Validation]]:
    """`validate_all` on each of `profiles`, in order; what the checks read of a pass that no
    card changes is made once for all the cards (`validate_on_cards`)."""
    from effects.validate.technique import validate_on_cards
    per_technique = [validate_on_cards(effect, t, profiles) for t in effect.techniques]
    return [[results[k] for results in per_technique] for k in range(len(profiles))]


def _passes(n: int) -> str:
    return f"{n} pass{'es' if n != 1 else ''}"


def print_validation_table(effect: Effect, profiles: Sequence[CapsProfile], console: Console,
                           *, why: bool = False, policy: PolicyLike = "first",
                           meter: Any = None) -> bool:
    """Print techniques × cards (✓ with the pass count, ✗ with the first reason) and the
    technique each card selects; with `why`, then every reason, warning and note. A language
    error (HLSL that compiles for no target) is marked as an error in its cells and printed
    located, with its source line, after the table. With `meter` (effects.host.fidelity.Meter)
    the details give each valid technique's fidelity on the card. Returns whether every named card can run
    some technique and no card's selection fell past a language error."""
    from rich.table import Table
    from rich.text import Text
    if not effect.techniques:
        console.print(Text(f"{effect.path}: the effect has no techniques, so no card can render it"),
                      soft_wrap=True)
        return False
    from effects.validate.select import as_policy, select
    pol = as_policy(policy)
    results = dict(zip((p.name for p in profiles), validate_cards(effect, profiles)))
    table = Table(title=effect.path, show_lines=True, header_style="bold")
    table.add_column("technique", overflow="fold")
    for p in profiles:
        table.add_column(p.name, overflow="fold")
    for i, tech in enumerate(effect.techniques):
        row = [technique_name(tech)]
        for profile in profiles:
            v = results[profile.name][i]
            language = next((r for r in v.reasons if r.error is not None), None)   # the reason
            if v.ok:
                row.append(Text.assemble(("✓", "green"), f" {_passes(v.passes)}"))
            elif language is not None:
                row.append(Text.assemble(("✗ error", "bold red"), f" {language} (below)"))
            else:
                row.append(Text.assemble(("✗", "red"), f" {v.reasons[0]}"))
        table.add_row(*row)
    if meter is not None and pol.order == "fidelity" and pol.likeness is None:
        pol = pol.with_likeness(meter.likeness)
    selections = {p.name: select(effect, p, pol, validations=results[p.name]) for p in profiles}
    chosen = {name: s.chosen for name, s in selections.items()}
    table.add_row(Text("selected", style="bold"),
                  *[Text(technique_name(c.technique)) if c else Text("none", style="red")
                    for c in chosen.values()])
    console.print(table)
    from effects.validate.select import language_error
    errors = {(e.location, e.message): e for vs in results.values() for v in vs
              if (e := language_error(v)) is not None}
    for error in sorted(errors.values(), key=lambda e: e.location):
        console.print(Text(error.report(), style="red"), soft_wrap=True)
    fell_past = any(s.passed_over is not None for s in selections.values())
    if why:
        _print_details(effect, profiles, results, console, meter)
    return all(c is not None for c in chosen.values()) and not fell_past


def _print_details(effect: Effect, profiles: Sequence[CapsProfile],
                   results: Mapping[str, list[Validation]], console: Console,
                   meter: Any = None) -> None:
    """Every reason, warning and note, one line each, grouped by card and technique; with
    `meter`, each valid technique's fidelity against the best technique."""
    from rich.text import Text
    best = meter.best() if meter is not None else None
    if meter is not None:
        size = "x".join(map(str, meter.size))
        if best is not None and meter.blank is not None:
            said = (f"fidelity: {technique_name(best)} on refrast draws nothing here (every pixel "
                    f"the clear colour {meter.blank}), so there is no picture to measure "
                    "against; the fidelity policy keeps file order")
            best = None                   # no figure per technique
        elif best is not None:
            said = (f"fidelity: each valid technique's picture on the card against "
                    f"{technique_name(best)} on refrast ({size}, reference back end)")
        else:
            said = "fidelity: no technique runs on refrast, so there is no best picture to " \
                "measure against"
        console.print(Text(said), soft_wrap=True)
    for profile in profiles:
        console.print(Text(f"{profile.name} ({profile.display_name or profile.name}, {profile.generation})",
                           style="bold"))
        for v in results[profile.name]:
            name = technique_name(v.technique)
            if v.ok:
                figure = ""
                if best is not None:
                    found = meter.measure(v.technique, profile, v)
                    figure = f", {found}" if found is not None else ", fidelity: not drawn"
                console.print(Text.assemble("  ", ("✓", "green"),
                                            f" {name}: {_passes(v.passes)}{figure}"))
            else:
                console.print(Text.assemble("  ", ("✗", "red"), f" {name}:"))
            for r in v.reasons:
                console.print(Text(f"      {r}"), soft_wrap=True)
            for w in v.warnings:
                console.print(Text(f"      warning: {w}", style="yellow"), soft_wrap=True)
            for n in v.notes:
                console.print(Text(f"      note: {n}", style="dim"), soft_wrap=True)


def matrix(effects: Mapping[str, Effect], profiles: Sequence[CapsProfile],
           policy: PolicyLike = "first", *, fidelity: bool = False,
           scenes: Mapping[str, Any] | None = None, best: str | None = None) -> dict:
    """{effect: {profile: {"technique": name|None, "passes": n, "rejected": {tech: [reason...]}}}},
    and "error" in a card's entry where its selection fell past a technique with a language
    error (Selection.passed_over): that error as the console shows it, source line and caret.
    With `fidelity`, or under the fidelity policy, "fidelity" too, measured in the effect's
    scene from `scenes` (by path; None the default scene) against `best` (None: the first
    valid on refrast)."""
    from effects.validate.select import as_policy, select
    pol = as_policy(policy)
    measured = fidelity or pol.order == "fidelity"
    out: dict = {}
    for path, effect in effects.items():
        meter, ranked = None, pol
        if measured:
            from effects.host.fidelity import meter_for
            meter = meter_for(effect, scene=(scenes or {}).get(path), best=best)
            if pol.order == "fidelity" and pol.likeness is None:
                ranked = pol.with_likeness(meter.likeness)
        per_card: dict = {}
        for profile, results in zip(profiles, validate_cards(effect, profiles)):
            selection = select(effect, profile, ranked, validations=results)
            chosen = selection.chosen
            per_card[profile.name] = {
                "technique": technique_name(chosen.technique) if chosen else None,
                "passes": chosen.passes if chosen else 0,
                "rejected": selection.rejected(),
            }
            if meter is not None:
                per_card[profile.name]["fidelity"] = _figure(meter, chosen, profile)
            error = selection.passed_over
            if error is not None:   # the selection fell past a language error: said as one
                per_card[profile.name]["error"] = error.report()
        out[path] = per_card
    return out


def _figure(meter: Any, chosen: Validation | None, profile: CapsProfile) -> dict | None:
    """A cell's "fidelity": the chosen technique against the best, or None."""
    if chosen is None or meter.best() is None:
        return None
    found = meter.measure(chosen.technique, profile, chosen)
    return None if found is None else {**found.as_json(), "best": technique_name(meter.best())}


def matrix_job(job: "MatrixJob") -> dict | EffectError:
    """`matrix()`'s entry for one effect file, or the error its load raised (returned, not
    raised: the command reports the first failing file in the order given). Where the
    command line's store is on, the entry is kept for the next command (matrix_store), with
    the files a fidelity row's renders named."""
    from effects.base import untrusted
    from effects.d3d9.caps import list_profiles, load_profile
    from effects.cli import matrix_store
    from effects.validate.verdicts import load_effect   # strict: as D3DXCreateEffect
    found = matrix_store.inputs(job)
    try:
        effect = load_effect(job.path, defines=dict(job.defines),
                             include_dirs=list(job.include_dirs),
                             include_root=job.include_root, strict=job.strict)
        profiles = [load_profile(n) for n in (job.profiles or list_profiles())]
        with untrusted.recording() as named:
            row = matrix({job.path: effect}, profiles, job.policy, fidelity=job.fidelity,
                         scenes={job.path: job.scene}, best=job.best)[job.path]
        measured = any("fidelity" in cell for cell in row.values())
        matrix_store.keep(job, found, effect, row, named if measured else frozenset())
        return row
    except EffectError as err:
        # it travels pickled, and where tblib's pickling is installed (Dask's is) a traceback
        # and chained errors travel too, holding the parser's unpicklable frames: none needed
        err.__traceback__ = err.__cause__ = err.__context__ = None
        return err


def _matrix_cells(result: dict) -> tuple[list[str], list[list[str]]]:
    """The matrix table's header and rows as text: cards down, effects across."""
    profiles = list(next(iter(result.values())).keys()) if result else []
    header = ["card", *(_short(path) for path in result)]
    rows = []
    for name in profiles:
        row = [name]
        for path in result:
            cell = result[path][name]
            text = f"{cell['technique']} ({cell['passes']})" if cell["technique"] else "none"
            if cell.get("fidelity"):
                text += f" {figure_text(cell['fidelity'])}"
            row.append(text)
        rows.append(row)
    return header, rows


def figure_text(figure: Mapping[str, Any] | None) -> str:
    """A fidelity figure as a cell shows it: 'SSIM 0.934' ('= best' where the pictures are
    the same: SSIM 1 and no pixel differs)."""
    if not figure:
        return ""
    if figure["psnr"] is None:
        return "= best"
    return f"SSIM {figure['ssim']:.3f}"


def print_matrix(result: dict, console: Console) -> None:
    """Cards down, effects across: the chosen technique and its pass count. Names are never
    folded: on a terminal too narrow for the whole table, the table is split into tables of
    as many effects as fit, each led by the card column (as pandas prints a wide frame); where
    not even one effect fits beside the cards, one line per card and effect. (Folded to 80
    columns, eleven effects made each card nine lines of 3-letter name fragments.) Into a pipe
    or a file the table is as wide as its names, one line per card, for grep."""
    header, rows = _matrix_cells(result)
    if not console.is_terminal:
        from effects.cli.console import make_console
        # a table that does not expand is as wide as its cells: on a console this wide, all of it
        make_console(file=console.file, width=1 << 16).print(_matrix_table(header, rows))
        return
    groups = _column_groups(header, rows, console.width)
    if groups is None:
        _print_matrix_lines(header, rows, console)
        return
    for i, columns in enumerate(groups):
        if i:
            console.print()
        console.print(_matrix_table([header[c] for c in columns],
                                    [[row[c] for c in columns] for row in rows]))


def _matrix_table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> Any:
    from rich.table import Table
    from rich.text import Text
    table = Table(header_style="bold", show_lines=False)
    for title in header:
        table.add_column(title, no_wrap=True)
    for row in rows:
        table.add_row(row[0], *[Text(c) if c != "none" else Text("none", style="red")
                                for c in row[1:]])
    return table


def _column_groups(header: Sequence[str], rows: Sequence[Sequence[str]],
                   width: int) -> list[list[int]] | None:
    """The matrix's columns in groups whose tables fit `width`, each group led by the card
    column (0); None where the cards and one effect do not fit side by side."""
    from rich.cells import cell_len
    widths = [max(cell_len(text) for text in (header[c], *(row[c] for row in rows)))
              for c in range(len(header))]

    def fits(columns: list[int]) -> bool:
        # rich's default box: a rule left of each column and one at the end, a space each side
        return sum(widths[c] + 3 for c in columns) + 1 <= width

    groups = [[0]]
    for c in range(1, len(header)):
        if not fits(groups[-1] + [c]):
            if groups[-1] != [0]:
                groups.append([0])
            if not fits([0, c]):
                return None
        groups[-1].append(c)
    return groups


def _print_matrix_lines(header: Sequence[str], rows: Sequence[Sequence[str]],
                        console: Console) -> None:
    """The matrix one cell a line, under a line per effect: for a terminal too narrow for a
    table of one effect."""
    from rich.text import Text
    pad = max(len(row[0]) for row in rows) if rows else 0
    for c in range(1, len(header)):
        console.print(Text(header[c], style="bold"), soft_wrap=True)
        for row in rows:
            console.print(Text.assemble(f"  {row[0]:<{pad}}  ",
                                        (row[c], "red" if row[c] == "none" else "")),
                          soft_wrap=True)


def _short(path: str) -> str:
    """An effect's column title: its file name without folders or the .fx suffix."""
    name = path.replace("\\", "/").rsplit("/", 1)[-1]
    return name[:-3] if name.lower().endswith(".fx") else name


def _version(v: tuple[int, int]) -> str:
    return f"{v[0]}.{v[1]}" if v > (0, 0) else "-"


def profile_row(p: CapsProfile) -> dict[str, str]:
    """The key caps of a card, as `effects profiles` shows them."""
    from effects.validate.shaders import software_vs_version
    bump = [label for bit, label in (("BUMPENVMAP", "EMBM"), ("DOTPRODUCT3", "dot3"))
            if p.has("TextureOpCaps", bit)]
    maps = [label for bit, label in (("CUBEMAP", "cube"), ("VOLUMEMAP", "3D"))
            if p.has("TextureCaps", bit)]
    hw_vs, sw_vs = p.vertex_shader_version, software_vs_version(p)
    vs = _version(hw_vs) if hw_vs > (0, 0) else ("sw" if sw_vs > (0, 0) else "-")
    return {
        "card": p.name,
        "name": p.display_name or p.name,
        "st/tx": f"{p.get('MaxTextureBlendStages')}/{p.get('MaxSimultaneousTextures')}",
        "bump": " ".join(bump) or "-",
        "maps": " ".join(maps) or "-",
        "size": str(p.get("MaxTextureWidth", "?")),
        "ps": _version(p.pixel_shader_version),
        "vs": vs,
    }


def print_profiles(profiles: Sequence[CapsProfile], console: Console) -> None:
    """The cards grouped by generation (dx6 → dx9c), with their key caps: `st/tx` texture
    stages / textures per pass, `bump` EMBM and dot3 ops, `maps` cube and volume textures,
    `size` the largest texture side, `ps` and `vs` shader versions. `vs` is the
    hardware vertex shader version, or `sw` when vertex shaders run only in software (where
    software or mixed vertex processing is offered, it runs up to vs_3_0 on every card).
    On a terminal, a table with a heading per generation; into a pipe or a file, one card per
    line, the fields separated by tabs (card, generation, name, then the caps), for cut and
    awk: the table folded its names at the 80 columns rich assumes there."""
    from effects.d3d9.caps import GENERATIONS
    ordered = sorted(profiles, key=lambda p: (GENERATIONS.index(p.generation), p.name))
    rows = [profile_row(p) for p in ordered]
    if not console.is_terminal:
        for p, row in zip(ordered, rows):
            fields = [row["card"], p.generation, *list(row.values())[1:]]
            # a tab or line break inside a field (a YAML display_name) would split the record
            console.file.write("\t".join(" ".join(f.split()) for f in fields) + "\n")
        return
    from rich import box
    from rich.table import Table
    from rich.text import Text
    table = Table(header_style="bold", box=box.SIMPLE_HEAD, pad_edge=False)
    for col in (rows[0].keys() if rows else ()):
        if col == "name":
            table.add_column(col, min_width=12, ratio=1)
        else:
            table.add_column(col, no_wrap=True)
    previous = None
    for p, row in zip(ordered, rows):
        if p.generation != previous:   # a heading row per generation
            if previous is not None:
                table.add_section()
            table.add_row(Text(p.generation, style="bold"), *[""] * (len(row) - 1))
        table.add_row(*row.values())
        previous = p.generation
    console.print(table)
