"""`effects compile`: the assembly each shader of a pass runs, as fxc /Fc listed it; one
shader's Direct3D 9 bytecode, as fxc /Fo and /Fh wrote it; a bytecode file's listing.

    effects compile FILE.fx [--technique T] [--pass N]
    effects compile FILE.fx --entry F --target ps_2_0 [-o out.pso] [--header]
    effects compile FILE.fx -o out.fxo              (the whole effect, fxc /T fx_2_0 /Fo)
    effects compile --disassemble X.pso|X.h|X.fxo

The listing itself is `effects.shaders.listing` (the viewer's listing window shows the same
text for the pass it draws); the bytecode `effects.shaders.d3dbc`, the fx_2_0 effect binary
`effects.shaders.fxo`; this module is the
command's arguments.
"""
from __future__ import annotations

from effects.base.errors import EffectError, Location

TYPE_CHECKING = False   # typing is not imported for `effects --help` (effects/cli/main.py)
if TYPE_CHECKING:  # pragma: no cover
    from typing import Any

    from rich.console import Console

_COMMAND_LINE = Location("<command line>", 1, 1)


def add_compile(sub: Any, load: Any) -> None:
    p = sub.add_parser("compile", help="the assembly each shader of a pass runs (fxc /Fc "
                       "listing); one shader's bytecode (fxc /Fo, /Fh); a bytecode's listing")
    p.add_argument("file", help="effect file (.fx or .fxo); with --disassemble a shader's bytecode "
                   "(.pso, .vso, .cso), an fxc /Fh header (.h) or an effect binary (.fxo)")
    p.add_argument("--technique", "-t", metavar="T", help="technique (default: the first)")
    p.add_argument("--pass", dest="pass_index", type=int, default=None, metavar="N",
                   help="pass number from 0 (default: every pass)")
    p.add_argument("--entry", metavar="F", help="compile this function instead of a pass's shaders")
    p.add_argument("--target", metavar="PROFILE", help="with --entry: vs_1_1 ... ps_3_0")
    p.add_argument("-o", "--output", metavar="OUT",
                   help="with --entry and --target: write the shader's bytecode here (fxc "
                   "/Fo); without them the whole effect as an fx_2_0 binary (fxc /T fx_2_0 /Fo)")
    p.add_argument("--header", action="store_true",
                   help="write the bytecode as a C array (fxc /Fh) instead, to OUT or stdout")
    p.add_argument("--name", metavar="VAR", help="the --header array's name (default: fxc's "
                   "g_<target>_<entry>)")
    p.add_argument("--disassemble", action="store_true",
                   help="FILE is compiled bytecode or an fx_2_0 effect binary (.fxo): print "
                   "its listing")
    p.add_argument("--include-root", metavar="DIR", default=None,
                   help="confine every file the effect reads to this folder")
    p.add_argument("--strict", action="store_true", help="unknown state names are errors")
    p.set_defaults(run=lambda args, console: run_compile(args, console, load))


def _say(console: "Console", text: str) -> None:
    # emoji=False: a listing line `wood.fx:100:` is no :100: emoji code
    console.print(text, markup=False, highlight=False, soft_wrap=True, emoji=False)


def run_compile(args: Any, console: "Console", load: Any) -> int:
    if args.disassemble:
        if _is_effect_binary(args.file):
            from effects.shaders.fxo import listing as effect_listing
            _say(console, effect_listing(load(args)))
            return 0
        from effects.shaders.d3dbc import binary_listing, load_shader
        from effects.shaders.listing import counts
        binary = load_shader(args.file)
        _say(console, binary_listing(binary) + "\n".join(counts(binary.program)))
        return 0
    from effects.shaders.listing import listing, pass_listing
    if args.header and not (args.entry and args.target):
        raise EffectError("--header writes one shader: name it with --entry and "
                          "--target (e.g. --entry main --target ps_2_0 --header)", _COMMAND_LINE)
    effect = load(args)
    if args.output and not (args.entry or args.target):
        from effects.shaders.fxo import write_effect_binary
        _save(args.output, write_effect_binary(effect))
        return 0
    out: list[str] = []
    if args.entry or args.target:
        if not (args.entry and args.target):
            raise EffectError("--entry and --target go together (e.g. --entry main --target ps_2_0)",
                              _COMMAND_LINE)
        from effects.shaders.hlsl import compile_shader
        compiled = compile_shader(effect, args.entry, args.target.lower())
        if args.output or args.header:
            return _write(args, console, effect, compiled)
        out += listing(effect, compiled)
    else:
        technique = effect.technique(args.technique) if args.technique else (
            effect.techniques[0] if effect.techniques else None)
        if technique is None:
            raise EffectError("the effect has no techniques", Location(effect.path, 1, 1))
        indices = range(len(technique.passes)) if args.pass_index is None else [args.pass_index]
        for i in indices:
            out += pass_listing(effect, technique, i)
    _say(console, "\n".join(out))
    return 0


def _write(args: Any, console: "Console", effect: Any, compiled: Any) -> int:
    from effects.shaders.d3dbc import variable_name, write_header, write_shader
    from effects.shaders.listing import listing
    data = write_shader(compiled.program, compiled)
    if args.header:
        name = args.name or variable_name(compiled.target, compiled.function)
        text = write_header(data, name, "\n".join(listing(effect, compiled)))
        if not args.output:
            _say(console, text)
            return 0
        payload = text.encode()
    else:
        payload = data
    _save(args.output, payload)
    return 0


def _save(path: str, payload: bytes) -> None:
    try:
        with open(path, "wb") as f:
            f.write(payload)
    except OSError as exc:
        raise EffectError(f"cannot write {path}: {exc.strerror or exc}",
                          _COMMAND_LINE) from None


def _is_effect_binary(path: str) -> bool:
    """Whether `path` is an fx_2_0 effect binary, bare or in XNA's containers (by its tag,
    whatever its name)."""
    try:
        with open(path, "rb") as f:
            head = f.read(4)
    except OSError:
        return False            # the shader reader says why it cannot be read
    from effects.frontend.fxo import is_effect_binary
    from effects.frontend.xnb import is_wrapped_effect
    return is_effect_binary(head) or is_wrapped_effect(head)
