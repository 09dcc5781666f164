"""`effects compile`: the assembly each shader of a pass runs, as fxc /Fc listed it.

    effects compile FILE.fx [--technique T] [--pass N]
    effects compile FILE.fx --entry F --target ps_2_0

The listing itself is `effects.shaders.listing` (the viewer's listing window shows the same
text for the pass it draws); this module is the command's arguments.
"""
from __future__ import annotations

from effects.base.errors import EffectError, Location

TYPE_CHECKING = False   # typing is not imported for `effects --help` (effects/cli/main.py)
if TYPE_CHECKING:  # pragma: no cover
    from typing import Any

    from rich.console import Console


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
    from effects.shaders.listing import listing, pass_listing
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
            out += pass_listing(effect, technique, i)
    console.print("\n".join(out), markup=False, highlight=False, soft_wrap=True)
    return 0
