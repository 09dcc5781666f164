"""What a card adds to a shader version's own rules: its PS20Caps/VS20Caps and constant count.

`check()` enforces what every card of a version guarantees; this compares an assembled program's
resource use with one card's values (the caps validator turns each violation into a Reason).
"""
from __future__ import annotations

from typing import Any, Iterator, Mapping

from effects.base import caches
from effects.base.errors import AsmError, Location
from effects.model import ShaderBlock
from effects.shaders.asm.parser import assemble
from effects.shaders.asm.program import AsmProgram

Violation = tuple[Location, str, str, str, str]  # location, subject, requirement, card value, message

# D3DCAPS9.MaxVertexShaderConst under software vertex processing (the runtime's emulation).
SOFTWARE_VS_CONSTANTS = 8192


def _program_bytes(result: Any) -> int:
    """About what an assembled program holds: ~1.5 KB an instruction (tracemalloc: the bundled
    effects' blocks, 1.4-2.9 KB), an error a few KB."""
    return 2048 + 1600 * len(getattr(result, "instructions", ()))


# 512 programs before; 8 MiB holds ~500 of ten instructions
_ASSEMBLED = caches.declare("shaders.asm.programs", keys="stage, version, source text, location "
                            "of an asm block", max_bytes=8 << 20, size_of=_program_bytes)


def _assemble_key(stage: str, version: str | None, source: str, path: str, line: int,
                  column: int) -> AsmProgram | AsmError:
    key = (stage, version, source, path, line, column)
    hit = _ASSEMBLED.get(key)
    if hit is None:
        block = ShaderBlock(stage, version, source, location=Location(path, line, column))
        try:
            hit = assemble(block)
        except AsmError as err:
            hit = err
        _ASSEMBLED.put(key, hit)
    return hit


def assemble_cached(block: ShaderBlock) -> AsmProgram:
    """`assemble`, memoised on the block's text and position (validation runs per card).
    The result is kept on the block itself (`ShaderBlock._assembled`, with the key it was made
    from, checked on a hit): the process-wide cache behind it is bounded, and an effect with
    more blocks than it holds would otherwise parse every block again on every validation and
    lowering (a 30k-line effect has ~1,000). The memo goes with the effect."""
    loc = block.location
    key = (block.stage, block.version, block.source, loc)
    memo = block._assembled
    if memo is not None and memo[0] == key:
        result = memo[1]
    else:
        result = _assemble_key(block.stage, block.version, block.source, loc.path, loc.line,
                               loc.column)
        block._assembled = (key, result)
    if isinstance(result, AsmError):
        raise result
    return result


def lowering_cached(program: AsmProgram, int_constants: Mapping[int, Any] | None = None
                    ) -> list[AsmError]:
    """`lower.lowering_problems`, once per program object and set of pass integer constants
    (kept on the program, so it goes with it): validation asks per card, and a compiled HLSL
    shader is one program for every card."""
    key = tuple(sorted((int_constants or {}).items()))
    hits = program._lowering_problems
    hit = hits.get(key)
    if hit is None:
        from effects.shaders.asm.lower import lowering_problems
        if len(hits) >= 16:     # a viewer editing the counts: keep a few
            hits.clear()
        hit = hits[key] = lowering_problems(program, int_constants)
    return hit


def _caps_flags(profile, field: str) -> set[str]:
    caps = profile.get(field) or {}
    return {str(c).upper() for c in caps.get("Caps", [])}


def card_limit_violations(program: AsmProgram, profile, *, software: bool = False) -> Iterator[Violation]:
    """Ways `program` exceeds this card's shader caps (beyond the version's own limits)."""
    stats = program.stats
    first = program.instructions[0].location if program.instructions else Location("<asm>", 0, 0)
    if program.kind == "ps" and program.version >= (2, 0):
        caps = profile.get("PS20Caps") or {}
        flags = _caps_flags(profile, "PS20Caps")
        slots = caps.get("NumInstructionSlots")
        if slots is not None and stats.total_slots > slots:
            yield (first, program.name, f"PS20Caps.NumInstructionSlots >= {stats.total_slots}",
                   f"NumInstructionSlots {slots}",
                   f"the pixel shader takes {stats.total_slots} instruction slots")
        temps = caps.get("NumTemps")
        highest_r = stats.highest.get("r", -1) + 1
        if temps is not None and highest_r > temps:
            yield (first, program.name, f"PS20Caps.NumTemps >= {highest_r}", f"NumTemps {temps}",
                   f"the pixel shader uses temporaries up to r{highest_r - 1}")
        depth = caps.get("DependentReadDepth")
        if (depth is not None and "NODEPENDENTREADLIMIT" not in flags
                and stats.dependent_read_depth > depth):
            yield (first, program.name, f"DependentReadDepth >= {stats.dependent_read_depth}",
                   f"DependentReadDepth {depth}",
                   f"the pixel shader has {stats.dependent_read_depth} levels of dependent texture reads")
        for used, flag, what in ((stats.uses_arbitrary_swizzle, "ARBITRARYSWIZZLE", "an arbitrary swizzle"),
                                 (stats.uses_predication, "PREDICATION", "predication"),
                                 (stats.uses_gradients, "GRADIENTINSTRUCTIONS", "gradient instructions")):
            if used and program.version < (3, 0) and flag not in flags:
                yield (first, program.name, f"D3DPS20CAPS_{flag}", "not in PS20Caps.Caps",
                       f"the pixel shader uses {what}")
    yield from _flow_depths(program, profile, first, software)
    if program.kind == "ps":
        outputs = stats.highest.get("oC", 0) + 1
        rts = profile.get("NumSimultaneousRTs", 1) or 1
        if outputs > rts:
            yield (first, program.name, f"NumSimultaneousRTs >= {outputs}",
                   f"NumSimultaneousRTs {rts}",
                   f"the pixel shader writes oC{outputs - 1}, so {outputs} render targets at once")
        if program.version >= (3, 0):
            yield from _slot_limit(program, profile, "MaxPixelShader30InstructionSlots", "pixel", first)
    if program.kind == "vs":
        if program.version >= (3, 0) and not software:
            yield from _slot_limit(program, profile, "MaxVertexShader30InstructionSlots", "vertex", first)
        if (program.version >= (2, 0) and program.version < (3, 0) and not software
                and stats.uses_predication and "PREDICATION" not in _caps_flags(profile, "VS20Caps")):
            yield (first, program.name, "D3DVS20CAPS_PREDICATION", "not in VS20Caps.Caps",
                   "the vertex shader uses predication")
        limit = SOFTWARE_VS_CONSTANTS if software else profile.get("MaxVertexShaderConst")
        highest_c = stats.highest.get("c", -1) + 1
        if limit is not None and highest_c > limit:
            yield (first, program.name, f"MaxVertexShaderConst >= {highest_c}",
                   f"MaxVertexShaderConst {limit}",
                   f"the vertex shader reads constants up to c{highest_c - 1}")
        if program.version >= (2, 0) and not software:
            caps = profile.get("VS20Caps") or {}
            temps = caps.get("NumTemps")
            highest_r = stats.highest.get("r", -1) + 1
            if temps is not None and highest_r > temps:
                yield (first, program.name, f"VS20Caps.NumTemps >= {highest_r}", f"NumTemps {temps}",
                       f"the vertex shader uses temporaries up to r{highest_r - 1}")


def _flow_depths(program: AsmProgram, profile, first: Location, software: bool
                 ) -> Iterator[Violation]:
    """The card's flow-control nesting depths for 2_x shaders (PS20Caps / VS20Caps
    StaticFlowControlDepth and DynamicFlowControlDepth; 3_0 requires the maxima)."""
    if program.version < (2, 0) or program.version >= (3, 0) or (software and
                                                                 program.kind == "vs"):
        return
    field = "PS20Caps" if program.kind == "ps" else "VS20Caps"
    caps = profile.get(field) or {}
    static, dynamic = program.flow_nesting
    what = "pixel" if program.kind == "ps" else "vertex"
    for name, used in (("StaticFlowControlDepth", static), ("DynamicFlowControlDepth", dynamic)):
        limit = caps.get(name)
        if limit is not None and used > limit:
            kind = "static" if name.startswith("Static") else "dynamic"
            yield (first, program.name, f"{field}.{name} >= {used}", f"{name} {limit}",
                   f"the {what} shader nests {kind} flow control {used} deep")


def _slot_limit(program: AsmProgram, profile, field: str, what: str,
                first: Location) -> Iterator[Violation]:
    slots = profile.get(field)
    if slots is not None and program.stats.total_slots > slots:
        yield (first, program.name, f"{field} >= {program.stats.total_slots}", f"{field} {slots}",
               f"the {what} shader takes {program.stats.total_slots} instruction slots")
