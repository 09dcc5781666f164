"""Direct3D 10/11 effect files (fx_4_0 / fx_5_0), told apart from the D3DX9 effects this
framework loads.

Engines that moved to Direct3D 11 kept the `.fx` extension (Kodi's `system/shaders/*_d3d.fx`,
the SDK's Direct3D 11 tutorials), so a user opens one expecting a picture. Their syntax is not
D3DX9's: `technique11 { pass { SetPixelShader(CompileShader(ps_4_0, PS())); } }`,
`SamplerState S { Filter = MIN_MAG_MIP_LINEAR; };`, state objects. Parsed as a
D3DX9 effect, the first of these is a syntax error that names a brace, which says nothing
useful. `d3d10_error` turns such a failure into an error at the Direct3D 10/11 construct that
caused it; `d3d10_shader_warning` flags a file with no techniques whose shaders use Direct3D 10
system-value semantics (a D3D11 shader source compiled on its own, not an effect).

Some files carry both: a `technique10` for the Direct3D 10 renderer next to the `technique` a
Direct3D 9 renderer loads (foo_wave_seekbar's Direct3D 9 front end hands such a file to
`D3DXCreateEffect` as it is). D3DX9 loads the `technique` blocks and passes over the others, so
`skip_d3d10_techniques` blanks each `technique10`/`technique11` block of a file that also has a
Direct3D 9 technique, with a located warning per block; a file with none keeps the error.
Keyword lists from the Direct3D 10/11 effect-format documentation (Effect Format, "Effect
Technique Syntax (Direct3D 11)", "Sampler Type", "Shader Semantics").
"""
from __future__ import annotations

import re
from dataclasses import replace

from effects.base.errors import EffectError, EffectWarning, ParseError
from effects.frontend.source import Preprocessed

# Words only Direct3D 10/11 effects use: technique keywords, state objects,
# and the pass-state functions. Case-sensitive, as HLSL keywords are. (The lower-case
# `texture2D` is a D3D9 type too, so texture object names are not in the list.) Not in it:
# `cbuffer`, `tbuffer` (whose members shader models 1-3 cannot read: X3546, at the read),
# `SamplerState` and `Texture2D.Sample`, which the later fxc (d3dcompiler_43/47)
# compiled in plain HLSL for vs_2_0-ps_3_0 as well (docs/guide/hlsl.md): a D3D10/11 *effect* is
# told by its effect syntax. A `SamplerState S { Filter = ...; }` with a state block is a
# Direct3D 10 state object (`_STATE_OBJECT`); `SamplerState S;` alone is a sampler.
D3D10_WORDS = ("technique10", "technique11", "fxgroup",
               "SamplerComparisonState", "BlendState", "DepthStencilState", "RasterizerState",
               "SetVertexShader", "SetPixelShader", "SetGeometryShader", "SetHullShader",
               "SetDomainShader", "SetComputeShader", "CompileShader", "ConstructGSWithSO")
# `SamplerState Name [N] : SEMANTIC {`: a state object's block (Kodi's `SamplerState
# KernelSampler : IMMUTABLE { Filter = MIN_MAG_MIP_LINEAR; }`)
_STATE_OBJECT = (r"SamplerState(?=\s+[A-Za-z_]\w*\s*(?:\[[^\]]*\]\s*)?"
                 r"(?::\s*\w+(?:\s*\([^)]*\))?\s*)*\{)")
_WORD = re.compile(r"\b(" + "|".join(D3D10_WORDS) + "|" + _STATE_OBJECT + r")\b")
# A system-value semantic after a colon: `: SV_POSITION`, `: SV_Target0`.
_SV_SEMANTIC = re.compile(r":\s*(SV_[A-Za-z]+\d*)\b")
# Strings hold no syntax; blank them (keeping offsets) before looking.
_STRING = re.compile(r'"(?:[^"\\\n]|\\.)*"')


_TECHNIQUE10 = re.compile(r"\b(technique1[01])\b")
# The Direct3D 9 keyword (case-insensitive, as this framework's effect lexer reads keywords).
_TECHNIQUE9 = re.compile(r"\btechnique\b", re.IGNORECASE)
_NAME = re.compile(r"\s*([A-Za-z_]\w*)?")
_BRACE = re.compile(r"[{}]")


def skip_d3d10_techniques(pre: Preprocessed) -> tuple[Preprocessed, list[EffectWarning]]:
    """`pre` with its Direct3D 10/11 technique blocks blanked (lines kept, so every location
    still maps), and a warning at each, when the file also has a Direct3D 9 technique; `pre`
    unchanged otherwise."""
    blanked = _STRING.sub(lambda m: " " * len(m.group(0)), pre.text)
    spans: list[tuple[int, int, str]] = []
    for m in _TECHNIQUE10.finditer(blanked):
        if spans and m.start(1) < spans[-1][1]:
            continue                       # inside the block before (one scan of the text)
        span = _block_span(blanked, m.start(1))
        if span is None:                   # unbalanced: the parser says where
            return pre, []
        spans.append(span)
    if not spans:
        return pre, []
    rest = "".join(blanked[a:b] for a, b in zip([0] + [e for _, e, _ in spans],
                                                  [s for s, _, _ in spans] + [len(blanked)]))
    if _TECHNIQUE9.search(rest) is None:
        return pre, []
    text, warnings, end, line = [], [], 0, 1
    for start, stop, name in spans:
        text += [pre.text[end:start], re.sub(r"[^\n]", " ", pre.text[start:stop])]
        line += pre.text.count("\n", end, start)      # counted on from the block before
        end = stop
        column = start - (pre.text.rfind("\n", 0, start) + 1) + 1
        word = pre.text[start:start + 11]
        label = f" '{name}'" if name else ""
        warnings.append(pre.source_map.warning_at(
            f"{word}{label} skipped: a Direct3D 10/11 technique, which D3DX9 passes over; "
            f"the file's Direct3D 9 techniques are loaded", pre.source_map.locate(line, column)))
        line += pre.text.count("\n", start, stop)
    text.append(pre.text[end:])
    return replace(pre, text="".join(text)), warnings


def _block_span(text: str, start: int) -> tuple[int, int, str] | None:
    """(start, end, name) of the `technique10 Name <annotations> { ... }` block at `start`:
    the braces matched, or None when the block does not close."""
    m = _NAME.match(text, start + len("technique10"))
    name = m.group(1) or ""
    depth = 0
    for brace in _BRACE.finditer(text, m.end()):
        if brace.group() == "{":
            depth += 1
            continue
        if depth == 0:                     # a '}' before the block opens
            return None
        depth -= 1
        if depth == 0:
            return start, brace.end(), name
    return None


def _find(pattern: re.Pattern[str], text: str) -> tuple[str, int, int] | None:
    """The first match's word and its 1-based (line, column) in `text`."""
    blanked = _STRING.sub(lambda m: " " * len(m.group(0)), text)
    m = pattern.search(blanked)
    if m is None:
        return None
    start = m.start(1)
    line = blanked.count("\n", 0, start) + 1
    column = start - (blanked.rfind("\n", 0, start) + 1) + 1
    return m.group(1), line, column


def d3d10_error(pre: Preprocessed, error: EffectError) -> EffectError:
    """`error` (a parse failure) replaced by an error at the first Direct3D 10/11 word, when
    one comes at or before the place the parse failed; else `error` unchanged."""
    found = _find(_WORD, pre.text)
    if found is None:
        return error
    word, line, column = found
    if not _before(pre, line, error):
        return error
    return pre.source_map.error(
        ParseError, f"'{word}' is Direct3D 10/11 effect syntax: this is a Direct3D 10/11 "
        f"effect (fx_4_0/fx_5_0), not a Direct3D 9 (D3DX9, fx_2_0) one, which is what this "
        f"framework loads; a D3D9 effect writes "
        f"technique, sampler_state and compile vs_/ps_ targets", line, column)


def _before(pre: Preprocessed, line: int, error: EffectError) -> bool:
    """Whether output line `line` comes before the error's place in the preprocessed text."""
    for n, origin in enumerate(pre.source_map.lines, start=1):
        if origin == (error.location.path, error.location.line):
            return line <= n
    return False


def d3d10_shader_warning(pre: Preprocessed) -> EffectWarning | None:
    """For a file with no techniques: a warning at its first SV_ semantic, if it has one."""
    found = _find(_SV_SEMANTIC, pre.text)
    if found is None:
        return None
    word, line, column = found
    where = pre.source_map.locate(line, column)
    return pre.source_map.warning_at(
        f"'{word}' is a Direct3D 10/11 system-value semantic and the file has no techniques: "
        f"it looks like a Direct3D 10/11 shader source compiled on its own (vs_4_0/ps_4_0), "
        f"not a D3DX9 effect; an effect needs a technique whose passes compile its functions",
        where)
