"""Effect-level HLSL values read on the host: a parameter initialiser kept as text (a struct's
`{ {..}, {..}, 32.0 }`) as the flat list of its numbers."""
from __future__ import annotations

from effects.errors import Location
from effects.model import Effect
from effects.shaders.hlsl.parse import Origin, parse


def initializer_numbers(text: str, location: Location, effect: Effect | None = None) -> list[float]:
    """The numbers of a constant initialiser, in order (X3013 if it is not constant)."""
    from effects.shaders.hlsl.context import Context, Target, type_names
    from effects.shaders.asm.versions import VERSIONS
    from effects.shaders.hlsl.evaluate import Evaluator
    origin = Origin(location, text)
    tree = parse(text, "initializer", origin, type_names(effect) if effect else frozenset())
    ctx = Context(effect or Effect(location.path), Target("vs_3_0", VERSIONS["vs_3_0"]))
    ev = Evaluator(ctx, origin)
    comps = ev.flatten_list(tree)
    out = []
    for c in comps:
        v = c.const_values()
        if v is None:
            raise origin.error("X3013: the initializer is not a compile-time constant", tree)
        out.append(float(v[0]))
    return out
