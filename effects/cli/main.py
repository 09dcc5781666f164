"""The `effects` command line: validate, matrix, render, view, profiles, doctor, compile.

Exit codes (docs/design.md): 0 ok, 1 invalid or not renderable, 2 bad input or usage, 141 when
the reader of the output left (`| head`), as a process ended by SIGPIPE.
No Python traceback reaches a user: every `EffectError` is printed located, with its line.
"""
from __future__ import annotations

import argparse
import math
import os
import sys

from effects import __version__
from effects.base.errors import EffectError

# typing itself is not imported: it is the largest import `effects --help` would make
# (9 ms of a 70 ms start on the 2-core VM). Type checkers read the block below.
TYPE_CHECKING = False
if TYPE_CHECKING:  # pragma: no cover
    from collections.abc import Sequence
    from typing import Any

    from rich.console import Console   # imported when a command runs: --help needs none of it

EXIT_OK, EXIT_INVALID, EXIT_BAD_INPUT = 0, 1, 2
EXIT_CLOSED_PIPE = 128 + 13   # the status of a process ended by SIGPIPE


class UsageError(Exception):
    pass


def _terminal_columns() -> int:
    """The width help is wrapped to, read as `shutil.get_terminal_size` reads it (COLUMNS,
    then the terminal, then 80): argparse's formatter imports shutil for it, and shutil loads
    zlib, bz2 and lzma (8 ms of `effects --help` on the 2-core VM)."""
    try:
        columns = int(os.environ.get("COLUMNS", "0"))
    except ValueError:
        columns = 0
    if columns <= 0:
        try:
            columns = os.get_terminal_size(sys.__stdout__.fileno()).columns
        except (AttributeError, ValueError, OSError):
            columns = 0
    return columns if columns > 0 else 80


class _HelpFormatter(argparse.HelpFormatter):
    def __init__(self, prog: str, **options) -> None:
        options.setdefault("width", _terminal_columns() - 2)   # as argparse narrows its own
        super().__init__(prog, **options)


class _Parser(argparse.ArgumentParser):
    """argparse that reports usage problems as exit code 2 without printing a traceback."""

    def __init__(self, *args, **options) -> None:
        options.setdefault("formatter_class", _HelpFormatter)
        super().__init__(*args, **options)

    def error(self, message: str) -> None:  # type: ignore[override]
        self.print_usage(sys.stderr)
        raise UsageError(f"{self.prog}: error: {message}")

    def _print_message(self, message: str, file=None) -> None:
        # argparse's own drops an OSError: `effects --help | head -1` exited 0, not 141 as
        # every other output does on a closed pipe (main fills a closed stream, not argparse)
        if message:
            (file or sys.stderr).write(message)


def _add_validate(sub) -> None:
    p = sub.add_parser("validate", help="load an effect and tell which techniques each card can run")
    p.add_argument("file", help="effect file (.fx, or an fx_2_0 binary: .fxo, or XNA's .xnb)")
    p.add_argument("--profile", "-p", action="append", default=[], metavar="P",
                   help="caps profile name or YAML path (repeatable; default: the model summary only)")
    p.add_argument("--why", action="store_true", help="list every reason, not just the first, "
                   "and each valid technique's fidelity (its picture on the card against the "
                   "best technique's)")
    p.add_argument("--strict", action="store_true", help="unknown state names are errors")
    _add_best(p)
    _add_scene(p, "scene the --why fidelity renders draw")
    _add_preprocessor_options(p)
    _add_confinement(p, strict=False)
    p.set_defaults(run=_cmd_validate)


def _add_best(p) -> None:
    p.add_argument("--best", metavar="NAME", default=None,
                   help="the technique fidelity is measured against (default: the first valid "
                        "on refrast)")


def _add_preprocessor_options(p) -> None:
    """-D and -I, for the commands that load effect files (matrix: for every file it names)."""
    p.add_argument("-D", dest="defines", action="append", default=[], metavar="NAME[=VALUE]",
                   help="preprocessor macro")
    p.add_argument("-I", dest="include_dirs", action="append", default=[], metavar="DIR",
                   help="include search folder")


def _add_confinement(p, strict: bool = True) -> None:
    """--include-root (and --strict) for every command that loads an effect (docs/design.md)."""
    p.add_argument("--include-root", metavar="DIR", default=None,
                   help="confine every file the effect reads (includes, ResourceName, Procedural "
                        "images, scene textures) to this folder")
    if strict:
        p.add_argument("--strict", action="store_true", help="unknown state names are errors")


def _include_root(args) -> str | None:
    root = getattr(args, "include_root", None)
    if root is not None and not os.path.isdir(root):
        raise UsageError(f"effects {args.command}: error: --include-root {root!r} is not a folder")
    return root


def _load_options(args) -> dict[str, tuple]:
    """-D and -I as a matrix job and a sheet cell carry them (hashable, in order)."""
    return {"defines": tuple(_defines(args.defines).items()),
            "include_dirs": tuple(args.include_dirs)}


def _defines(items: Sequence[str]) -> dict[str, str]:
    out = {}
    for item in items:
        name, _, value = item.partition("=")
        out[name] = value if _ else "1"
    return out


def _load(args):
    # with --strict a language error in any technique fails the load, as D3DXCreateEffect did
    from effects.validate.verdicts import load_effect
    return load_effect(args.file, defines=_defines(getattr(args, "defines", [])),
                       include_dirs=getattr(args, "include_dirs", []),
                       include_root=_include_root(args), strict=getattr(args, "strict", False))


def _profiles(names: Sequence[str]):
    from effects.d3d9.caps import list_profiles, load_profile
    return [load_profile(n) for n in (names or list_profiles())]


def _cmd_validate(args, console: Console) -> int:
    from effects.cli.report import print_validation_table
    from effects.cli.summary import print_effect_summary
    effect = _load(args)
    for warning in effect.warnings:
        console.print(warning.report(), markup=False, highlight=False, style="yellow", soft_wrap=True)
    if not args.profile:
        print_effect_summary(effect, console)
        console.print("Name cards with --profile P (see `effects profiles`) to see which can run "
                      "each technique and why not; `effects matrix` shows every card's choice.",
                      markup=False)
        return EXIT_OK
    told = len(effect.warnings)
    meter = None
    if args.why:
        from effects.host.fidelity import meter_for
        meter = meter_for(effect, scene=_scene(args, args.file), best=args.best)
    every_card_runs_it = print_validation_table(effect, _profiles(args.profile), console,
                                                why=args.why, meter=meter)
    # what compiling the shaders added (a write fxc allowed only under /Gec)
    for warning in effect.warnings[told:]:
        console.print(warning.report(), markup=False, highlight=False, style="yellow", soft_wrap=True)
    return EXIT_OK if every_card_runs_it else EXIT_INVALID


def _add_matrix(sub) -> None:
    p = sub.add_parser(
        "matrix", help="the technique each card selects, for one or more effects",
        description="The technique each card selects, for one or more effects: cards down, "
                    "effects across, each cell the technique and its pass count. On a terminal "
                    "too narrow for the whole table, it is printed as several tables of whole "
                    "columns, each led by the cards; into a pipe or a file, one line per card.")
    p.add_argument("files", nargs="+", metavar="FILE.fx")
    p.add_argument("--profile", "-p", action="append", default=[], metavar="P",
                   help="caps profile (repeatable; default: every bundled card)")
    p.add_argument("--policy", default="first", help="selection policy: first, quality, cost, "
                   "fidelity, max-passes=N, max-cost=X, comma-separated (default: first, as D3DX)")
    p.add_argument("--fidelity", action="store_true",
                   help="measure each card's choice against the best technique: SSIM and PSNR "
                        "of the two pictures on the reference back end, kept with the rows")
    _add_best(p)
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")
    p.add_argument("--render", metavar="SHEET.png",
                   help="also draw the contact sheet: each cell the picture the card draws, or why not")
    p.add_argument("--size", metavar="WxH", default="96x96", help="cell size for --render (default 96x96)")
    _add_scene(p, "scene for --render and the fidelity renders")
    p.add_argument("--backend", "-b", default="numpy", metavar="NAME", help="back end for --render")
    _add_batch(p)
    _add_preprocessor_options(p)
    _add_confinement(p)
    p.set_defaults(run=_cmd_matrix)


def _add_scene(p, what: str) -> None:
    """--scene and --no-scene: NAME.yaml beside NAME.fx is the effect's scene for every
    command (effects.host.scene.scene_for)."""
    p.add_argument("--scene", "-s", metavar="SCENE.yaml",
                   help=f"{what} (default: NAME.yaml beside NAME.fx, else the default scene)")
    p.add_argument("--no-scene", dest="scene_beside", action="store_false",
                   help="ignore NAME.yaml beside NAME.fx: the default scene")


def _scene(args, path: str) -> str | None:
    from effects.host.scene_files import scene_for   # without the scene reader's imports
    return scene_for(path, args.scene, beside=args.scene_beside)


def _add_batch(p) -> None:
    p.add_argument("--jobs", "-j", type=int, default=None, metavar="N",
                   help="worker processes, one effect or cell a job (default: every core)")
    p.add_argument("--scheduler", metavar="tcp://HOST:PORT",
                   help="run the jobs on this Dask distributed scheduler (pip install 'effects[dask]')")


def _cmd_matrix(args, console: Console) -> int:
    from effects.cli.report import print_matrix
    if args.jobs is not None and args.jobs < 1:
        raise UsageError("effects matrix: error: --jobs must be at least 1")
    root = _include_root(args)
    result, cards = _matrix(args, root, console)
    if args.json:
        import json
        print(json.dumps(result, indent=2))
    else:
        print_matrix(result, console)
    if args.render:
        from effects.cli.sheet import render_sheet
        size = _parse_size(args.size, "matrix")
        if min(size) < 1 or max(size) > 1024:
            raise UsageError(f"effects matrix: error: --size {args.size!r}: cells are 1 to 1024 pixels a side")
        names = list(args.profile) or cards   # as given: workers load them
        cells = render_sheet(list(args.files), names, args.render, size=size, scene=args.scene,
                             scene_beside=args.scene_beside, backend=args.backend,
                             policy=args.policy, jobs=args.jobs, scheduler=args.scheduler,
                             progress=not args.json,
                             figures=_figures(result, list(args.files), cards, names),
                             load={"include_root": root, **_load_options(args)})
        if not args.json:
            console.print(f"contact sheet: {len(args.files)} effects x {len(cards)} cards "
                          f"-> {args.render}", markup=False, highlight=False, soft_wrap=True)
        said = _cell_diagnostics(cells, args.strict)
        if said and args.strict:
            return EXIT_INVALID
    # a card's selection that fell past a language error: the error, once, and exit 1
    errors = list(dict.fromkeys(cell["error"] for row in result.values() for cell in row.values()
                                if "error" in cell))
    for text in errors:
        _stderr().print(text, markup=False, soft_wrap=True, style="red")
    return EXIT_INVALID if errors else EXIT_OK


def _figures(result: dict, files: list[str], cards: list[str],
             names: list[str]) -> dict[tuple[str, str], dict] | None:
    """The fidelity figure of each sheet cell, by (file, card as the sheet names it)."""
    if not any("fidelity" in cell for row in result.values() for cell in row.values()):
        return None
    return {(path, name): result[path][card].get("fidelity")
            for path in files for card, name in zip(cards, names)}


def _cell_diagnostics(cells: list, strict: bool) -> int:
    """Each drawn cell's diagnostics on stderr, led by its card (errors with --strict); a
    warning two cards share is said once. Returns how many were said."""
    err = _stderr()
    seen: set[str] = set()
    for cell in cells:
        for text in cell.diagnostics:
            if text in seen:
                continue
            seen.add(text)
            if strict:
                text = text.replace(": warning: ", ": error: ", 1)
            err.print(f"[{os.path.basename(cell.profile)}] {text}", markup=False, soft_wrap=True,
                      style="red" if strict else "yellow")
    return len(seen)


def _matrix(args, root: str | None, console: Console) -> tuple[dict, list[str]]:
    """The matrix of `args.files` on the cards, and the cards' names. A file whose row an
    earlier command kept (`effects.cli.matrix_store`: nothing it was made from has changed)
    is read back; the others are made by `_made_rows`. Errors are the serial command's: the
    first effect file that fails to load, in the order given, then a bad card or policy."""
    from effects.cli import matrix_store
    from effects.cli.matrix_store import MatrixJob
    # the fidelity order named as Policy.parse reads it (without loading it: stored rows
    # need no selection code); a bad policy is said by _made_rows, after the files' errors
    measured = args.fidelity or "fidelity" in (p.strip().lower() for p in args.policy.split(","))
    load = _load_options(args)
    shared = matrix_store.shared_key(tuple(args.profile), args.policy, args.strict, root,
                                     matrix_store.fidelity_options(measured, args.best),
                                     matrix_store.preprocessor_options(**load))
    jobs = [MatrixJob(path, tuple(args.profile), args.policy, root, args.strict, shared,
                      measured, _scene(args, path) if measured else None, args.best, **load)
            for path in args.files]
    rows = [matrix_store.stored_row(job) for job in jobs]
    todo = [job for job, row in zip(jobs, rows) if row is None]
    if todo:
        made = iter(_made_rows(args, todo, console))
        rows = [row if row is not None else next(made) for row in rows]
    for row in rows:
        if isinstance(row, EffectError):
            raise row
    return dict(zip(args.files, rows)), list(rows[0])


def _made_rows(args, todo: list, console: Console) -> list:
    """The rows of the effect files `todo` (report.matrix_job: an error is returned, not
    raised). They are independent jobs (`effects.host.batch.run_jobs`: --jobs workers, every
    core by default, or --scheduler), each loaded and validated by a worker; the cards and
    the policy are read here first, before the workers fork, and the table's console is made
    while they run. One file, or a process with other threads running (a fork copies locks
    they may hold: a host calling `main`), validates here."""
    import threading
    from effects.cli.report import matrix_job
    from effects.validate.select import as_policy
    try:
        _profiles(args.profile)
        as_policy(args.policy)
    except EffectError:
        from effects.frontend.loader import load_effect
        for job in todo:   # a file that fails to load is reported before the card or policy
            load_effect(job.path, defines=dict(job.defines), include_dirs=list(job.include_dirs),
                        include_root=job.include_root, strict=job.strict)
        raise
    if args.scheduler is None and (len(todo) < 2 or threading.active_count() > 1):
        rows = []
        for job in todo:
            rows.append(matrix_job(job))
            if isinstance(rows[-1], EffectError):
                break      # reported by _matrix: the files after it are not needed
        return rows + [None] * (len(todo) - len(rows))
    from effects.host.batch import run_jobs
    return run_jobs(matrix_job, todo, jobs=args.jobs, scheduler=args.scheduler,
                    meanwhile=None if args.json else lambda: _ready_for_table(console))


def _ready_for_table(console: Any) -> None:
    """Make the console and import rich's table, as printing one will."""
    import rich.table  # noqa: F401
    getattr(console, "ready", lambda: None)()


def _add_profiles(sub) -> None:
    p = sub.add_parser(
        "profiles", help="the simulated cards, by generation, with their key caps",
        description="The simulated cards, by generation then name, with their key caps: st/tx "
                    "texture stages / textures per pass, bump the EMBM and dot3 ops, maps cube "
                    "and volume (3D) textures, size the largest texture side, ps and vs the "
                    "shader versions (vs sw: vertex shaders in software only). On a terminal, a "
                    "table; into a pipe or a file, one card per line, its fields separated by "
                    "tabs: card, generation, name, st/tx, bump, maps, size, ps, vs "
                    "(`effects profiles | cut -f1` lists the names).")
    p.add_argument("cards", nargs="*", metavar="CARD",
                   help="show only these cards: a bundled card's name or a profile YAML path")
    p.set_defaults(run=_cmd_profiles)


def _cmd_profiles(args, console: Console) -> int:
    from effects.cli.report import print_profiles
    # the cards named load first: an unknown name says so (did you mean) before anything prints
    print_profiles(_profiles(args.cards), console)
    return EXIT_OK


def _add_render(sub) -> None:
    p = sub.add_parser("render", help="render an effect on a simulated card into a PNG")
    p.add_argument("file", help="effect file (.fx, or an fx_2_0 binary: .fxo, or XNA's .xnb)")
    p.add_argument("--profile", "-p", required=True, metavar="P", help="caps profile name or YAML path")
    p.add_argument("--technique", "-t", metavar="T",
                   help="render this technique, valid on the card or not (default: the card's choice)")
    p.add_argument("--backend", "-b", default="numpy", metavar="NAME",
                   help="numpy (the reference rasteriser, default) or gl")
    _add_scene(p, "mesh, camera, light, params ...")
    p.add_argument("--mesh", metavar="MESH",
                   help="sphere, torus, cube, teapot, quad or a mesh file such as FILE.obj "
                        "(wins over the scene's)")
    p.add_argument("--size", metavar="WxH", help="frame size, e.g. 320x240 (wins over the scene's)")
    p.add_argument("--set", dest="assignments", action="append", default=[], metavar="NAME=VALUE",
                   help="a parameter value: number, vector '1,0.5,0.25,1', true/false, "
                        "0xAARRGGBB, or an image path for a texture (repeatable)")
    p.add_argument("--policy", default="first", help="selection policy (see matrix)")
    p.add_argument("-o", "--output", required=True, metavar="OUT.png", help="the PNG to write")
    p.add_argument("--alpha", action="store_true",
                   help="keep the render target's alpha in the PNG (default: opaque; the "
                        "target's alpha is not a picture's transparency)")
    p.add_argument("--strict", action="store_true",
                   help="unknown state names, textures nothing supplies, and what the picture "
                        "shows nothing of (a parameter nothing sets, culled front faces, a "
                        "frame of one colour) are errors (exit 1)")
    _add_preprocessor_options(p)
    _add_confinement(p, strict=False)
    p.set_defaults(run=_cmd_render)


def _parse_size(text: str | None, command: str = "render") -> tuple[int, int] | None:
    if text is None:
        return None
    w, x, h = text.lower().partition("x")
    if not x or not w.strip().isdigit() or not h.strip().isdigit():
        raise UsageError(f"effects {command}: error: --size {text!r}: expected WxH, e.g. 320x240")
    return int(w), int(h)


def _check_output(path: str) -> None:
    """-o must name a .png file in an existing folder: said before any rendering is done."""
    if os.path.isdir(path):
        raise UsageError(f"effects render: error: -o {path!r} is a folder; name the PNG to write, "
                         "e.g. -o out.png")
    if os.path.splitext(path)[1].lower() != ".png":
        raise UsageError(f"effects render: error: -o {path!r}: the output is a PNG; name it "
                         "OUT.png")
    folder = os.path.dirname(path) or "."
    if not os.path.isdir(folder):
        raise UsageError(f"effects render: error: -o {path!r}: no folder {folder!r}")


def _check_backend(name: str) -> None:
    from effects.program.backend import available_backends
    known = available_backends()
    if name not in known:
        raise UsageError(f"effects render: error: unknown back end {name!r} "
                         f"(back ends: {', '.join(known)})")


def _cmd_render(args, console: Console) -> int:
    import time
    from PIL import Image
    from effects.base.errors import NoValidTechnique
    from effects.host.runtime import render_frame
    from effects.host.semantics import parse_assignments
    size = _parse_size(args.size)
    _check_output(args.output)
    _check_backend(args.backend)
    params = parse_assignments(args.assignments)
    effect = _load(args)
    profile = _profiles([args.profile])[0]
    start = time.perf_counter()
    scene = _scene(args, args.file)
    if args.mesh is not None:
        from effects.base.errors import Location
        from effects.host.scene import load_scene, set_mesh
        scene = set_mesh(load_scene(scene), args.mesh, Location("--mesh", 1, 1))
    try:
        from effects.host.fidelity import policy_for   # pictures for the fidelity order only
        frame = render_frame(effect, profile, technique=args.technique, backend=args.backend,
                             scene=scene, size=size, params=params,
                             policy=policy_for(effect, args.policy, scene=scene, params=params),
                             strict=args.strict, diagnose=True)
    except NoValidTechnique as exc:
        # the load warnings first: they may say why (a Direct3D 10/11 shader file, ...)
        for warning in effect.warnings:
            _stderr().print(warning.report(), markup=False, soft_wrap=True, style="yellow")
        _stderr().print(str(exc), markup=False, soft_wrap=True)
        return EXIT_INVALID
    except EffectError as exc:
        if not exc.language:
            raise
        # the technique the card would draw does not compile for any target: an error, not a
        # silent fallback to the next technique (effects.validate.verdicts)
        _stderr().print(exc.report(), markup=False, soft_wrap=True, style="red")
        return EXIT_INVALID
    ms = (time.perf_counter() - start) * 1000.0
    err = _stderr()
    for warning in [*effect.warnings, *frame.warnings]:
        err.print(warning.report(), markup=False, soft_wrap=True, style="yellow")
    if args.strict and frame.diagnostics:
        # what the picture shows nothing of, as errors: no PNG that would look finished
        for warning in frame.diagnostics:
            err.print(warning.report().replace(": warning: ", ": error: ", 1), markup=False,
                      soft_wrap=True, style="red")
        return EXIT_INVALID
    for warning in frame.diagnostics:
        err.print(warning.report(), markup=False, soft_wrap=True, style="yellow")
    image = frame.image if args.alpha else opaque(frame.image)
    try:
        Image.fromarray(image, "RGBA").save(args.output)
    except (OSError, ValueError) as exc:
        from effects.base.errors import Location, SceneError
        raise SceneError(f"cannot write the image: {exc}", Location(args.output, 1, 1)) from None
    card = profile.display_name or profile.name
    print(f"rendered {frame.technique.name or '<anonymous>'} on {card} ({frame.passes} "
          f"pass{'es' if frame.passes != 1 else ''}) with {frame.backend} in {ms:.1f} ms "
          f"-> {args.output}")
    return EXIT_OK


def opaque(image):
    """The picture without the target's alpha (alpha 255): what a window would show."""
    out = image.copy()
    out[..., 3] = 255
    return out


def _add_view(sub) -> None:
    p = sub.add_parser(
        "view", help="the viewer: an effect on a card, hot-reloaded as you edit it",
        description="The viewer: an effect on a card, hot-reloaded as you edit it. It opens a "
                    "window, so it needs a display (DISPLAY); without one, run it under a "
                    "virtual X server: xvfb-run -a effects view FILE.fx --exit-after 5 "
                    "--screenshot out.png.")
    p.add_argument("file", help="effect file (.fx, or an fx_2_0 binary: .fxo, or XNA's .xnb)")
    p.add_argument("--profile", "-p", metavar="P", default=None,
                   help="caps profile to start on (default: radeon9700)")
    p.add_argument("--technique", "-t", metavar="NAME", default=None,
                   help="force a technique (drawn if the card can run it; else its reasons are shown)")
    p.add_argument("--mesh", default=None,
                   help="sphere, torus, cube, teapot, quad, FILE.obj or FILE.x (default: the "
                        "scene's mesh, else the effect's `string XFile`, else sphere)")
    p.add_argument("--view", default="gl", choices=("gl", "reference", "difference"),
                   help="what the window shows first (default: gl)")
    _add_scene(p, "mesh, camera, light, params, time")
    p.add_argument("--set", dest="assignments", action="append", default=[], metavar="NAME=VALUE",
                   help="a parameter value, as render takes it (repeatable); the panel's "
                        "widgets start from it")
    p.add_argument("--time", type=float, metavar="SECONDS", default=None,
                   help="hold the clock TIME reads at SECONDS (screenshots, tests); without "
                        "it the clock runs from the scene's time")
    p.add_argument("--exit-after", type=float, metavar="SECONDS", default=None,
                   help="close after this many seconds of running")
    p.add_argument("--screenshot", metavar="OUT.png", default=None,
                   help="save the window to this PNG when the viewer closes")
    p.add_argument("--tour", action="store_true",
                   help="draw every card once, starting at --profile, then exit")
    p.add_argument("--size", default=None, metavar="WxH", help="window size (default: 1040x600)")
    p.add_argument("--listing", action="store_true",
                   help="start with the shader listing shown (as `effects compile`; key C toggles it)")
    p.add_argument("--poll", action="store_true",
                   help="watch files by polling (for file systems without change events)")
    _add_preprocessor_options(p)
    _add_confinement(p)
    p.set_defaults(run=_cmd_view)


def _cmd_view(args, console: Console) -> int:
    from effects.viewer.app import WINDOW_SIZE, NoDisplay, ViewerOptions, run_viewer
    size = WINDOW_SIZE
    if args.size:
        w, _, h = args.size.lower().partition("x")
        if not (w.isdigit() and h.isdigit() and 200 <= int(w) <= 8192 and 100 <= int(h) <= 8192):
            raise UsageError(f"effects view: error: --size {args.size!r} is not WxH "
                             "(at least 200x100)")
        size = (int(w), int(h))
    if args.exit_after is not None and args.exit_after < 0:
        raise UsageError("effects view: error: --exit-after must not be negative")
    if args.time is not None and not (math.isfinite(args.time) and args.time >= 0):
        raise UsageError(f"effects view: error: --time {args.time}: a number of seconds, 0 or more")
    from effects.host.semantics import parse_assignments
    assignments = parse_assignments(args.assignments)
    try:
        return run_viewer(ViewerOptions(
            args.file, profile=args.profile, technique=args.technique, mesh=args.mesh,
            scene=_scene(args, args.file), assignments=assignments, time=args.time,
            view=args.view, exit_after=args.exit_after, screenshot=args.screenshot, size=size,
            tour=args.tour, listing=args.listing, polling=args.poll,
            defines=_defines(args.defines), include_dirs=args.include_dirs,
            include_root=_include_root(args), strict=args.strict))
    except NoDisplay as exc:
        raise UsageError(f"effects view: error: no display to open the window on ({exc}); "
                         "run it in a desktop session, set DISPLAY, or under a virtual X "
                         f"server: xvfb-run -a effects view {args.file}") from None


def _add_doctor(sub) -> None:
    p = sub.add_parser("doctor", help="what an effect needs from a host that it does not get")
    p.add_argument("file", help="effect file (.fx, or an fx_2_0 binary: .fxo, or XNA's .xnb)")
    p.add_argument("--profile", "-p", default="radeon9700", metavar="P",
                   help="caps profile whose selected technique is examined (default: radeon9700)")
    p.add_argument("--technique", "-t", metavar="T", help="examine this technique instead")
    _add_scene(p, "the scene a render would use")
    p.add_argument("--set", dest="assignments", action="append", default=[], metavar="NAME=VALUE",
                   help="a parameter value, as render takes it (repeatable)")
    _add_preprocessor_options(p)
    _add_confinement(p)
    p.set_defaults(run=_cmd_doctor)


def _cmd_doctor(args, console: Console) -> int:
    from effects.cli.doctor import diagnose, print_diagnosis
    from effects.host.semantics import parse_assignments
    effect = _load(args)
    profile = _profiles([args.profile])[0]
    d = diagnose(effect, profile, scene=_scene(args, args.file),
                 params=parse_assignments(args.assignments),
                 technique=args.technique)
    print_diagnosis(d, args.file, profile.display_name or profile.name, console)
    return EXIT_OK


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="effects", description=__doc__.splitlines()[0],
                     epilog="exit status: 0 ok, 1 invalid or not renderable, 2 bad input or "
                            "usage, 141 the reader of the output left (| head)")
    parser.add_argument("--version", action="version", version=f"effects {__version__}",
                        help="print the version (effects X.Y.Z) and exit")
    # not required: `effects` alone prints this help (main)
    sub = parser.add_subparsers(dest="command", parser_class=_Parser)
    _add_validate(sub)
    _add_matrix(sub)
    _add_render(sub)
    _add_profiles(sub)
    _add_view(sub)
    _add_doctor(sub)
    from effects.cli.compile import add_compile
    add_compile(sub, _load)
    return parser


_BLAS_THREADS = ("OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS")


def _one_blas_thread(args) -> None:
    """Commands that only validate (matrix without --render, validate, profiles) multiply no
    matrix big enough for BLAS to thread: NumPy's OpenBLAS is loaded with one thread, so its
    pool of spinning threads is not started (~40 ms of CPU and ~70 ms of wall clock on the
    2-core VM, a fifth of `effects matrix`). Only in a fresh process (NumPy not loaded yet),
    and not where the user set a thread count."""
    validating = args.command in ("validate", "profiles") or (
        args.command == "matrix" and not getattr(args, "render", None))
    if validating and "numpy" not in sys.modules and not any(v in os.environ for v in _BLAS_THREADS):
        os.environ["OPENBLAS_NUM_THREADS"] = "1"


class _LazyConsole:
    """The console the commands print through: rich's `Console(highlight=False)`, made (and
    rich imported) on first use, so a command that prints nothing through it does not pay
    for rich."""

    def __init__(self) -> None:
        self._console: Any = None

    def __getattr__(self, name: str) -> Any:
        return getattr(self.ready(), name)

    def ready(self) -> "Console":
        """The console, made now if it was not."""
        if self._console is None:
            from effects.cli.console import make_console
            self._console = make_console()
        return self._console


def _stderr() -> "Console":
    from effects.cli.console import make_console
    return make_console(stderr=True)


def _fill_closed_streams() -> None:
    """`effects render ... -o out.png >&-`: a stream the shell closed is None in Python, and
    the first write to it was an internal error (AttributeError). Its lines are dropped, as
    the caller asked, and the command does its work: the PNG is its product, the line a
    report of it, so the exit status is the command's own (141 would say a reader left).
    The descriptor is filled with /dev/null too, so that no file the command opens takes
    it and receives what is meant for the stream."""
    for name, fd in (("stdout", 1), ("stderr", 2)):
        if getattr(sys, name) is not None:
            continue
        null = os.open(os.devnull, os.O_WRONLY)
        if null != fd:
            os.dup2(null, fd)
            os.close(null)
        setattr(sys, name, open(fd, "w", closefd=False))


def main(argv: Sequence[str] | None = None) -> int:
    _fill_closed_streams()
    try:
        return _main(argv)
    except BrokenPipeError:
        # `effects matrix --json | head`: the reader left (of stdout, or of stderr in `2>&1 |
        # head` while an error was said). Say nothing, as Unix tools do, and point both at
        # /dev/null so the interpreter's final flush does not complain.
        devnull = os.open(os.devnull, os.O_WRONLY)
        for stream in (sys.stdout, sys.stderr):
            os.dup2(devnull, stream.fileno())
        os.close(devnull)
        return EXIT_CLOSED_PIPE


def _main(argv: Sequence[str] | None) -> int:
    """The command, and what its errors say: main answers a closed pipe, here or while an
    error is said."""
    try:
        parser = build_parser()
        try:
            args = parser.parse_args(argv)
        except SystemExit as done:   # --help, --version: printed; flushed below, as any output
            sys.stdout.flush()
            return done.code if isinstance(done.code, int) else EXIT_OK
        if args.command is None:     # `effects` alone: what it can do, as pip and cargo say it
            parser.print_help()
            sys.stdout.flush()
            return EXIT_OK
        _one_blas_thread(args)
        # compiled shaders and matrix rows are kept on disk between commands (effects/base/disk_store.py)
        from effects.base import disk_store
        disk_store.enable()
        try:
            code = args.run(args, _LazyConsole())
        finally:
            disk_store.disable()
        sys.stdout.flush()   # a closed pipe is found here, inside the handlers below
        return code
    except UsageError as exc:
        _stderr().print(str(exc), markup=False, soft_wrap=True)   # one line, as argparse prints it
        return EXIT_BAD_INPUT
    except EffectError as exc:
        _stderr().print(exc.report(), markup=False, soft_wrap=True)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        raise                 # main's: not a bug of ours
    except Exception as exc:  # a bug of ours, not bad input: say so briefly
        if os.environ.get("EFFECTS_DEBUG"):
            raise
        _stderr().print(f"effects: internal error: {type(exc).__name__}: {exc} "
                  "(set EFFECTS_DEBUG=1 for the traceback)", markup=False)
        return EXIT_BAD_INPUT


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
