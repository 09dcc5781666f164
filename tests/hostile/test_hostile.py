"""Hostile and broken input (issue 14): every door of README "Untrusted effects" gives a located
`EffectError` or a correct result, within bounded work and 1 GiB.

- The cases of tests/hostile/hostile_cases.py run in child processes holding at most 1 GiB of data
  (RLIMIT_DATA). The framework bounds work, not time (effects/base/limits.py), so each case
  asserts work: the limit that stopped it is the one its located error names, and what it
  spent, read from limits.py's meter, is a hand count (WORK). The clock is only a hang
  detector (hostile_cases.CPU_SECONDS of CPU time, WALL_SECONDS of wall time), far above any
  case's cost: the 5 s of wall time it was failed when eight test suites shared two cores.
  A child that hangs or dies is killed and the case it was running fails. One child runs many
  cases (a child costs ~1 s to start).
- Fuzzing with hypothesis (in this process; each input is small): DDS headers, .npy headers,
  YAML profiles and scenes built from hostile fragments, truncated and mutated files.
- Confinement: an effect under an include root tries every way out and reads nothing outside
  (an audit hook records every file opened).
- The command line: exit codes and messages of each command for bad input, and a closed pipe.
"""
from __future__ import annotations

from tests.paths import ROOT

import json
import os
import re
import struct
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import effects
from effects.base import limits
from effects.cli.main import main
from effects.base.errors import EffectError, SceneError

from tests.hostile import hostile_cases

# case -> (outcome, words the text must contain)
EXPECTED: dict[str, tuple[str, str]] = {
    "effect_fifo": ("error", "is a FIFO (named pipe); only regular files are read"),
    "effect_dev_zero": ("error", "/dev/zero is a device"),
    "effect_directory": ("error", "is a directory"),
    "effect_text_over_source_bytes": ("error", "limit source_bytes: raise it with EFFECTS_LIMIT_SOURCE_BYTES"),
    "effect_file_over_source_bytes": ("error", "limit source_bytes"),
    "effect_path_with_braces_and_semicolons": ("value", "['t']"),
    "effect_utf16_with_bom": ("value", "['t', 't']"),
    "effect_utf16_without_bom": ("error", "UTF-16/UTF-32 without a byte-order mark"),
    "effect_utf16_bom_broken": ("error", "is not valid UTF-16-LE"),
    "include_fan_out": ("error", "limit include_count"),
    "include_total_bytes": ("error", "limit included_bytes"),
    "include_fifo": ("error", "cannot read include file 'pipe.fxh': "),
    "if_integer_5000_digits": ("error", "limit literal_digits"),
    "array_size_5000_digits": ("error", "number literal is too long"),
    "asm_register_5000_digits": ("value", "limit literal_digits"),
    "string_annotation_of_one_mib": ("value", "1000000"),
    "profile_fifo": ("error", "is a FIFO"),
    "profile_empty_name": ("error", "<profile>:1:1: error: the profile name is empty"),
    "profile_tag_int": ("error", ":3:18: error: YAML value error: cannot read 'abc' as int"),
    "profile_tag_float": ("error", "cannot read 'abc' as float"),
    "profile_tag_timestamp": ("error", "cannot read 'x' as timestamp"),
    "profile_tag_custom": ("error", "could not determine a constructor for the tag '!custom'"),
    "profile_integer_5000_digits": ("error", "limit literal_digits"),
    "profile_alias_bomb": ("error", "YAML aliases (*name) are not accepted"),
    "profile_inherit_chain_2000": ("error", "limit inherit_depth"),
    "profile_nan_in_range": ("error", "MaxPixelShaderValue must be a number, not NaN"),
    "profile_exponent_is_a_number": ("value", "1e+308"),
    "profile_invalid_utf8": ("error", ":3:17: error: the file is not valid UTF-8 (byte 0xe9"),
    "scene_fifo": ("error", "is a FIFO"),
    "scene_alias_bomb": ("error", "YAML aliases (*name) are not accepted"),
    "scene_100000_nested_brackets": ("error", "exceeded maximum nesting depth"),
    "scene_deep_but_closed": ("error", "limit yaml_depth"),
    "scene_invalid_utf8": ("error", ":2:10: error: the file is not valid UTF-8"),
    "scene_invalid_utf16": ("error", "is not valid UTF-16-LE"),
    "scene_tag_int": ("error", ":1:8: error: scene file is not valid YAML: cannot read 'abc' as int"),
    "scene_tag_custom": ("error", "could not determine a constructor for the tag '!python/object:os.system'"),
    "scene_integer_5000_digits": ("error", "limit literal_digits"),
    "scene_long_value_in_message": ("error", "unknown mesh 'xxxxxxxxxxxxxxxxxxxxxxxxxxx...xxx"),
    "dds_2_to_the_32_mips": ("error", "DDS header claims 4,294,967,295 mip levels; a 4 x 4 texture has at most 3"),
    "dds_255_mips": ("error", "a 64 x 64 texture has at most 7"),
    "dds_huge_surface": ("error", "limit texture_edge"),
    "dds_huge_volume": ("error", "limit texture_texels"),
    "png_12000_squared": ("error", "image t.png (12000 x 12000 x 1) has 12,000 texels along an edge"),
    "png_past_pillows_bomb_limit": ("error", "Pillow's decompression-bomb guard"),
    "png_truncated": ("error", "cannot read image"),
    "npy_huge_shape": ("error", "limit texture_edge"),
    "npy_fifty_digit_dimension": ("error", "limit texture_edge"),
    "npy_truncated": ("error", ".npy texture is truncated"),
    "texture_fifo": ("error", "is a FIFO"),
    "procedural_noise3d_4096": ("error", "(4096 x 4096 x 4096) has 68,719,476,736 texels"),
    "procedural_noise3d_51": ("error", "limit procedural_texels"),
    "procedural_sky_cube_huge": ("error", "limit texture_edge"),
    "procedural_width_annotation_huge": ("error", "limit texture_edge"),
    "effect_texel_budget": ("error", "limit effect_texels"),
    "obj_600k_vertices": ("error", "limit mesh_vertices"),
    "render_target_8192_squared": ("error", "limit target_pixels_numpy"),
    "forced_oT8": ("error", ":4:6: error: technique t cannot be rendered on Radeon 9700, which rejects it: oT8 is out of range"),
    "forced_ps14_on_a_ps11_card": ("error", "which rejects it: PixelShader is ps_1_4"),
    "undeclared_reference": ("value", "warning: Texture[0] = <Nope> names no parameter of the effect', "
                                      "'pass p (line 1): Texture[0] = <Nope> names no parameter"),
    "wrongly_typed_reference": ("value", "Texture[0] = <Tint> needs a texture parameter; Tint (line 1) is a float4"),
    "phase_in_ps11": ("value", "phase is not available in ps_1_1"),
    "png_at_the_texel_limit": ("value", "(2048, 2048, 4)"),
    "dds_cube_at_the_texel_limit": ("value", "(6, 836, 836, 4)"),
    "procedural_volume_at_the_texel_limit": ("value", "(8, 8, 4)"),
    "procedural_stones_at_the_texel_limit": ("value", "(8, 8, 4)"),
    "render_at_the_numpy_target_limit": ("value", "(1024, 2048, 4)"),
}


# case -> what it spent, read from limits.py's meter: per limit, the largest amount measured
# (asked for, or refused when over the limit): an exact hand count, or (low, high] where the
# count depends on the compiler's accounting
WORK: dict[str, dict[str, int | tuple[int, int]]] = {
    "effect_text_over_source_bytes": {"source_bytes": 200_000 * 9},     # refused before parsing
    "include_fan_out": {"include_count": 257},                          # the first one past 256
    "include_total_bytes": {"included_bytes": 2 * 900_000},             # the second include
    "string_annotation_of_one_mib": {"source_bytes": 22 + 1_000_000 + 4},
    "profile_inherit_chain_2000": {"inherit_depth": 17},                # not 2,000 files read
    "scene_deep_but_closed": {"yaml_depth": 65},
    "dds_huge_volume": {"texture_texels": 2048 ** 3},                   # asked for, not allocated
    "procedural_noise3d_51": {"procedural_texels": 51 ** 3},
    "effect_texel_budget": {"effect_texels": 2 * 64 * 64},
    "obj_600k_vertices": {"mesh_vertices": 600_000},
    "render_target_8192_squared": {"target_pixels_numpy": 8192 ** 2},
    # just inside the limits: the work they allow
    "png_at_the_texel_limit": {"texture_texels": 2048 * 2048},
    "dds_cube_at_the_texel_limit": {"texture_texels": 6 * 836 * 836},
    "procedural_volume_at_the_texel_limit": {"procedural_texels": 50 ** 3, "effect_texels": 50 ** 3},
    "procedural_stones_at_the_texel_limit": {"procedural_texels": 362 ** 2},
    "render_at_the_numpy_target_limit": {"target_pixels_numpy": 2048 * 1024},
}


def test_every_case_has_an_expectation():
    assert set(EXPECTED) == set(hostile_cases.CASES)
    assert set(WORK) <= set(hostile_cases.CASES)


def assert_bounded(result: dict, words: str, work: dict[str, int | tuple[int, int]]) -> None:
    """The bounds the framework enforces, as the child measured them: every limit refused is
    named by the answer, and the limit the expected words name was refused (the one that
    stopped the input); `work` is what the meter read; the clock only detects a hang."""
    for name, amount in result["refused"].items():
        assert f"limit {name}" in result["text"], (name, amount, result["text"])
    for name in set(re.findall(r"limit (\w+)", words)) & set(limits.LIMITS):
        assert name in result["refused"], (name, result)
    for name, expected in work.items():
        amount = result["measured"].get(name)
        if isinstance(expected, tuple):
            assert amount is not None and expected[0] < amount <= expected[1], (name, result)
        else:
            assert amount == expected, (name, amount, expected)
    assert result["cpu_seconds"] < hostile_cases.CPU_SECONDS, result


def _run_children(names: list[str], module=hostile_cases) -> dict[str, dict]:
    """Run `names` (cases of `module`, a script like hostile_cases) in as few limited children
    as hangs allow: a child killed while running a case fails that case; the rest go on in a
    fresh child."""
    results: dict[str, dict] = {}
    left = list(names)
    script = str(Path(module.__file__))
    while left:
        proc = subprocess.run([sys.executable, script, *left], capture_output=True, text=True,
                              timeout=120 + 10 * len(left), cwd=ROOT,
                              env=dict(os.environ, OPENBLAS_NUM_THREADS="1"))
        running = None
        for line in proc.stdout.splitlines():
            record = json.loads(line)
            if record.get("started"):
                running = record["case"]
            else:
                results[record["case"]] = record
                running = None
        if running is not None or proc.returncode != 0:
            dead = running or left[len(results) - (len(names) - len(left))]
            results[dead] = {"case": dead, "outcome": "crash", "seconds": None,
                             "text": f"the child died (status {proc.returncode}): {proc.stderr[-1500:]}"}
        left = [n for n in left if n not in results]
    return results


@pytest.fixture(scope="module")
def outcomes() -> dict[str, dict]:
    return _run_children(list(hostile_cases.CASES))


@pytest.mark.slow
@pytest.mark.parametrize("name", list(EXPECTED))
def test_hostile_input_gives_a_located_answer_in_bounded_work_and_memory(name, outcomes):
    result = outcomes[name]
    outcome, words = EXPECTED[name]
    assert result["outcome"] == outcome, result["text"]
    assert words in result["text"], result["text"]
    assert_bounded(result, words, WORK.get(name, {}))


# ---------------------------------------------------------------------------------------------
# Fuzzing: whatever the bytes, a located SceneError/ProfileError or a value

def _assert_located(exc: EffectError) -> None:
    assert exc.line >= 1 and exc.column >= 1
    assert str(exc).startswith(f"{exc.path}:{exc.line}:{exc.column}: error: ")
    exc.report()


FUZZ = settings(max_examples=60, deadline=None, derandomize=True,
                suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])


@FUZZ
@given(width=st.integers(0, 1 << 32 - 1), height=st.integers(0, 1 << 32 - 1),
       depth=st.integers(0, 1 << 32 - 1), mips=st.integers(0, 1 << 32 - 1),
       caps2=st.sampled_from([0, 0x200, 0xFE00, 0x200000]), body=st.binary(max_size=300))
def test_fuzzed_dds_headers(tmp_path, width, height, depth, mips, caps2, body):
    from effects.assets.dds import read_dds
    path = tmp_path / "f.dds"
    path.write_bytes(hostile_cases._dds(width, height, mips, body, depth=depth, caps2=caps2))
    try:
        texture = read_dds(path)
    except SceneError as exc:
        _assert_located(exc)
    else:
        assert texture.width * texture.height <= limits.get("texture_texels")


@FUZZ
@given(shape=st.lists(st.integers(-3, 10 ** 12), min_size=0, max_size=5),
       dtype=st.sampled_from(["|u1", "<f4", "<i8", "|O", "<U3", "|V7"]), body=st.binary(max_size=200))
def test_fuzzed_npy_headers(tmp_path, shape, dtype, body):
    from effects.assets.texture_files import load_texture
    header = "{'descr': '%s', 'fortran_order': False, 'shape': (%s), }" % (
        dtype, "".join(f"{n}, " for n in shape))
    header += " " * (-(len(header) + 11) % 64) + "\n"
    path = tmp_path / "f.npy"
    path.write_bytes(b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode() + body)
    try:
        load_texture(path)
    except SceneError as exc:
        _assert_located(exc)


YAML_BITS = ["size: ", "mesh: ", "clear: ", "camera: ", "params: ", "light: ", "{", "}", "[", "]",
             ", ", ": ", "\n", "  ", "- ", "&a ", "*a ", "!!int ", "!!float ", "!!binary ",
             "!custom ", "!!timestamp ", ".nan", ".inf", "-.inf", "1e308", "9" * 300, "'0xff'",
             "0x1F", "~", "null", "true", "\"", "'", "#", "%YAG 1.1\n", "---\n", "...\n", "?",
             "\t", "\x00", "\xe9", "<<: ", "quad", "sphere", "x.obj", "[1, 2]", "[8, 8]",
             "{eye: [0, 0, 3]}"]


@FUZZ
@given(st.lists(st.sampled_from(YAML_BITS), max_size=30))
def test_fuzzed_scenes(tmp_path, bits):
    from effects.host.scene import load_scene
    path = tmp_path / "s.yaml"
    path.write_bytes("".join(bits).encode("utf-8", "surrogatepass"))
    try:
        load_scene(str(path))
    except SceneError as exc:
        _assert_located(exc)


PROFILE_LINES = (ROOT / "caps_profiles" / "geforce3.yaml").read_text().splitlines()


@FUZZ
@given(st.lists(st.tuples(st.integers(0, len(PROFILE_LINES) - 1), st.sampled_from(YAML_BITS)),
                max_size=6))
def test_fuzzed_profiles(tmp_path, edits):
    from effects.d3d9.caps import load_profile
    from effects.base.errors import ProfileError
    lines = list(PROFILE_LINES)
    for index, bit in edits:
        at = len(lines[index]) // 2
        lines[index] = lines[index][:at] + bit + lines[index][at:]
    path = tmp_path / "card.yaml"
    path.write_bytes("\n".join(lines).encode("utf-8", "surrogatepass"))
    try:
        load_profile(str(path))
    except ProfileError as exc:
        _assert_located(exc)


@FUZZ
@given(cut=st.integers(0, 400), flip=st.integers(0, 400), byte=st.integers(0, 255))
def test_truncated_and_mutated_images(tmp_path, cut, flip, byte):
    from PIL import Image
    from effects.assets.texture_files import load_texture
    source = tmp_path / "src.png"
    Image.fromarray(np.arange(16 * 16 * 3, dtype=np.uint8).reshape(16, 16, 3)).save(source)
    data = bytearray(source.read_bytes())
    data = data[:max(1, len(data) - cut)]
    data[flip % len(data)] = byte
    path = tmp_path / "f.png"
    path.write_bytes(bytes(data))
    try:
        texture = load_texture(path)
    except SceneError as exc:
        _assert_located(exc)
    else:
        assert texture.levels[0].shape[-1] == 4


# ---------------------------------------------------------------------------------------------
# Confinement: an effect under include_root reads nothing outside it

SECRET = "secret.png"


@pytest.fixture
def jail(tmp_path):
    """root/ (the include root) with an image and a header inside; outside/ with the secrets;
    root/link -> outside (a symlink out)."""
    from PIL import Image
    root, outside = tmp_path / "root", tmp_path / "outside"
    root.mkdir()
    outside.mkdir()
    for folder in (root, outside):
        Image.new("RGB", (4, 4), (255, 0, 0)).save(folder / SECRET)
        (folder / "inc.fxh").write_text("float Included;\n")
    (root / "link").symlink_to(outside, target_is_directory=True)
    (root / "sub").mkdir()
    return root, outside


def _opened_files():
    opened: list[str] = []

    def hook(event, args):
        if event == "open" and args and isinstance(args[0], (str, bytes, os.PathLike)):
            opened.append(os.path.realpath(os.fsdecode(args[0])))
    sys.addaudithook(hook)
    return opened


_OPENED = _opened_files()   # audit hooks cannot be removed: one for the module, read by slices

TEXTURE_USE = "technique t { pass p { Texture[0] = <T>; ColorOp[0] = SelectArg1; } }\n"


def _ways_out(root: Path, outside: Path) -> dict[str, str]:
    secret = outside / SECRET
    return {
        "include ..": '#include "../outside/inc.fxh"\n' + TEXTURE_USE,
        "include absolute": f'#include "{outside / "inc.fxh"}"\n' + TEXTURE_USE,
        "include backslashes": '#include "..\\outside\\inc.fxh"\n' + TEXTURE_USE,
        "include symlink": '#include "link/inc.fxh"\n' + TEXTURE_USE,
        "include <..> angled": '#include <../outside/inc.fxh>\n' + TEXTURE_USE,
        "ResourceName ..": f'texture T < string ResourceName = "../outside/{SECRET}"; >;\n' + TEXTURE_USE,
        "ResourceName sub/../..": f'texture T < string ResourceName = "sub/../../outside/{SECRET}"; >;\n'
                                  + TEXTURE_USE,
        "ResourceName absolute": f'texture T < string ResourceName = "{secret}"; >;\n' + TEXTURE_USE,
        "ResourceName backslashes": f'texture T < string ResourceName = "..\\\\outside\\\\{SECRET}"; >;\n'
                                    + TEXTURE_USE,
        "ResourceName symlink": f'texture T < string ResourceName = "link/{SECRET}"; >;\n' + TEXTURE_USE,
        "Procedural ..": f'texture T < string Procedural = "sobel_normals:../outside/{SECRET}"; >;\n'
                         + TEXTURE_USE,
        "Procedural absolute": f'texture T < string Procedural = "height:{secret}"; >;\n' + TEXTURE_USE,
        "Procedural backslashes": f'texture T < string Procedural = "height:..\\\\outside\\\\{SECRET}"; >;\n'
                                  + TEXTURE_USE,
        "Procedural symlink": f'texture T < string Procedural = "sobel_dudv:link/{SECRET}"; >;\n'
                              + TEXTURE_USE,
    }


def test_an_effect_under_include_root_reads_nothing_outside(jail):
    root, outside = jail
    refused = {}
    for name, source in _ways_out(root, outside).items():
        path = root / "e.fx"
        path.write_text(source)
        start = len(_OPENED)
        with pytest.raises(EffectError) as info:
            effect = effects.load_effect(str(path), include_root=str(root))
            effects.render(effect, "radeon9700", technique="t", size=(4, 4))
        _assert_located(info.value)
        refused[name] = info.value.message
        leaked = [p for p in _OPENED[start:] if p.startswith(os.path.realpath(outside))]
        assert leaked == [], (name, leaked)
        assert Path(info.value.path).resolve() == path.resolve(), (name, str(info.value))
    for name, message in refused.items():
        assert ("escapes the include root" in message or "backslash" in message
                or "absolute path" in message), (name, message)


def test_a_scene_under_include_root_reads_nothing_outside(jail):
    root, outside = jail
    (root / "e.fx").write_text("texture T;\n" + TEXTURE_USE)
    for value in (f"../outside/{SECRET}", str(outside / SECRET), f"link/{SECRET}",
                  f"sobel_normals:../outside/{SECRET}"):
        (root / "s.yaml").write_text(f"params: {{T: '{value}'}}\n")
        start = len(_OPENED)
        effect = effects.load_effect(str(root / "e.fx"), include_root=str(root))
        with pytest.raises(SceneError) as info:
            effects.render(effect, "radeon9700", scene=str(root / "s.yaml"), size=(4, 4))
        assert info.value.path == str(root / "s.yaml") and info.value.line == 1, str(info.value)
        assert [p for p in _OPENED[start:] if p.startswith(os.path.realpath(outside))] == []


def test_inside_the_root_everything_loads(jail):
    """The control: the same doors, pointing inside the root, read their files."""
    root, _ = jail
    source = ('#include "inc.fxh"\n'
              f'texture T < string ResourceName = "sub/../{SECRET}"; >;\n'
              f'texture H < string Procedural = "sobel_normals:{SECRET}"; >;\n'
              "technique t { pass p { Texture[0] = <T>; Texture[1] = <H>; ColorOp[0] = SelectArg1;\n"
              "ColorArg1[0] = Texture; ColorOp[1] = SelectArg1; ColorArg1[1] = Current; } }\n")
    (root / "e.fx").write_text(source)
    effect = effects.load_effect(str(root / "e.fx"), include_root=str(root))
    assert effect.parameter("Included") is not None
    image = effects.render(effect, "radeon9700", technique="t", size=(4, 4),
                           scene={"mesh": "quad"})
    assert (image[..., :3] == (255, 0, 0)).all()   # the red image inside the root, drawn


# ---------------------------------------------------------------------------------------------
# The command line

def _cli(*argv, capsys) -> tuple[int, str, str]:
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


FLAT = "technique t { pass p { Lighting = False; } }\n"


@pytest.mark.parametrize("argv, words", [
    (["render", "{fx}", "-p", "geforce3", "-b", "vulkan", "-o", "{tmp}/o.png"],
     "effects render: error: unknown back end 'vulkan' (back ends: gl, numpy, reference)"),
    (["render", "{fx}", "-p", "", "-o", "{tmp}/o.png"], "<profile>:1:1: error: the profile name is empty"),
    (["render", "{fx}", "-p", "geforce3", "-o", "{tmp}/x.jpg"], "the output is a PNG; name it OUT.png"),
    (["render", "{fx}", "-p", "geforce3", "-o", "."], "-o '.' is a folder"),
    (["render", "{fx}", "-p", "geforce3", "-o", "{tmp}/no/such/o.png"], "no folder"),
    (["render", "{fx}", "-p", "geforce3", "--size", "8192x8192", "-o", "{tmp}/o.png"],
     "limit target_pixels_numpy"),
    (["render", "{fx}", "-p", "geforce3", "--include-root", "{tmp}/nowhere", "-o", "{tmp}/o.png"],
     "--include-root '{tmp}/nowhere' is not a folder"),
    (["validate", "{tmp}/pipe.fx"], "is a FIFO"),
    (["validate", "{tmp}/u16.fx"], "without a byte-order mark"),
    (["validate", "{escape}", "--include-root", "{tmp}/root"], "escapes the include root"),
    (["matrix", "{escape}", "--include-root", "{tmp}/root"], "escapes the include root"),
    (["render", "{escape}", "-p", "geforce3", "--include-root", "{tmp}/root", "-o", "{tmp}/o.png"],
     "escapes the include root"),
    (["doctor", "{escape}", "--include-root", "{tmp}/root"], "escapes the include root"),
    (["validate", "{fx}", "-p", "{tmp}/pipe.fx"], "is a FIFO"),
    (["matrix", "{fx}", "-p", "/dev/zero"], "/dev/zero is a device"),
])
def test_bad_input_exits_2_with_a_clear_message(argv, words, tmp_path, capsys):
    (tmp_path / "e.fx").write_text(FLAT)
    (tmp_path / "root").mkdir()
    (tmp_path / "root" / "escape.fx").write_text('#include "../e.fx"\n')
    (tmp_path / "u16.fx").write_bytes(FLAT.encode("utf-16-le"))
    os.mkfifo(tmp_path / "pipe.fx")
    fill = {"fx": str(tmp_path / "e.fx"), "tmp": str(tmp_path), "escape": str(tmp_path / "root" / "escape.fx")}
    code, out, err = _cli(*[a.format(**fill) for a in argv], capsys=capsys)
    assert code == 2, (out, err)
    assert words.format(**fill) in err, err
    assert "Traceback" not in err and "<unknown>:0:0" not in err


def test_every_command_that_loads_an_effect_takes_include_root_and_strict():
    from effects.cli.main import build_parser
    parser = build_parser()
    commands = next(a for a in parser._actions if a.dest == "command").choices
    loading = {name: sub for name, sub in commands.items()
               if any(a.dest in ("file", "files") for a in sub._actions)}
    assert {"validate", "matrix", "render", "view", "doctor"} <= set(loading)
    for name, sub in loading.items():
        options = {o for a in sub._actions for o in a.option_strings}
        assert {"--include-root", "--strict"} <= options, name


def test_include_root_on_the_command_line_lets_inside_files_load(tmp_path, capsys):
    (tmp_path / "inc.fxh").write_text("float X;\n")
    (tmp_path / "e.fx").write_text('#include "inc.fxh"\n' + FLAT)
    code, out, err = _cli("validate", tmp_path / "e.fx", "-p", "geforce3", "--include-root", tmp_path,
                          capsys=capsys)
    assert code == 0, err


def test_warnings_of_bad_references_reach_the_user(tmp_path, capsys):
    (tmp_path / "e.fx").write_text("float4 Tint;\ntechnique t { pass p { Texture[0] = <Tint>; } }\n")
    code, out, err = _cli("validate", tmp_path / "e.fx", "-p", "radeon9700", capsys=capsys)
    assert code == 1
    assert f"{tmp_path / 'e.fx'}:2:37: warning: Texture[0] = <Tint> needs a texture parameter" in out + err


def test_a_closed_pipe_ends_quietly_as_unix_tools_do():
    proc = subprocess.Popen([sys.executable, "-m", "effects", "matrix", "--json", "-p", "tnt2",
                             str(ROOT / "fxfiles" / "phong.fx")],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, cwd=ROOT)
    assert proc.stdout is not None and proc.stderr is not None
    proc.stdout.close()            # the reader leaves before the table is written (`| true`)
    err = proc.stderr.read().decode()
    assert proc.wait(60) == 141, err
    assert err == ""


@pytest.mark.parametrize("argv, code", [
    (["validate", "{fx}"], 0),
    (["validate", "{fx}", "-p", "tnt2"], 0),
    (["validate", "{dot3}", "-p", "tnt2"], 1),
    (["validate", "{tmp}/missing.fx"], 2),
    (["matrix", "{fx}", "-p", "tnt2", "--json"], 0),
    (["matrix", "{tmp}/missing.fx"], 2),
    (["render", "{fx}", "-p", "tnt2", "--size", "4x4", "-o", "{tmp}/o.png"], 0),
    (["render", "{dot3}", "-p", "tnt2", "--size", "4x4", "-o", "{tmp}/o.png"], 1),
    (["render", "{fx}", "-p", "tnt2", "-t", "Nope", "-o", "{tmp}/o.png"], 2),
    (["profiles"], 0),
    (["profiles", "extra"], 2),
    (["frobnicate"], 2),
    ([], 0),        # `effects` alone prints the help, as pip and cargo do
])
def test_every_command_exits_0_1_or_2(argv, code, tmp_path, capsys):
    (tmp_path / "e.fx").write_text(FLAT)
    (tmp_path / "dot3.fx").write_text("technique t { pass p { ColorOp[0] = DotProduct3; } }\n")
    fill = {"fx": str(tmp_path / "e.fx"), "dot3": str(tmp_path / "dot3.fx"), "tmp": str(tmp_path)}
    got, out, err = _cli(*[a.format(**fill) for a in argv], capsys=capsys)
    assert got == code, (out, err)
    assert "Traceback" not in err and "internal error" not in err


@pytest.mark.slow
def test_every_bundled_technique_forced_on_a_card_that_rejects_it_renders_or_says_why():
    """Rendering a technique validation rejects (render's --technique): a picture or a located
    EffectError naming the reason, never an internal exception."""
    outcomes = {"rendered": 0, "refused": 0}
    for path in sorted((ROOT / "fxfiles").glob("*.fx")):
        effect = effects.load_effect(str(path))
        for technique in effect.techniques:
            for name in ("tnt2", "geforce3"):
                card = effects.load_profile(name)
                if effect.validate(technique, card).ok:
                    continue
                try:
                    image = effects.render(effect, card, technique=technique.name, size=(8, 8))
                    assert image.shape == (8, 8, 4)
                    outcomes["rendered"] += 1
                except EffectError as exc:
                    _assert_located(exc)
                    outcomes["refused"] += 1
    # Since HLSL compiles (effects.shaders.hlsl), every bundled technique forced on these cards
    # lowers and renders; what refused before were the `compile` shaders.
    assert outcomes["rendered"] > 25, outcomes


def test_the_guide_states_every_limit_and_its_default():
    page = (ROOT / "docs" / "guide" / "limits.md").read_text()
    section = page.split("## Every limit", 1)[1].split("\n## ", 1)[0]
    for limit in limits.LIMITS.values():
        assert f"| `{limit.name}` | {limit.default:,} {limit.unit} | {limit.what} |" in section, limit.name


def test_a_limit_is_raised_by_the_environment_or_in_code(monkeypatch):
    default = limits.LIMITS["literal_digits"].default
    assert limits.get("literal_digits") == default
    monkeypatch.setenv("EFFECTS_LIMIT_LITERAL_DIGITS", "3000")
    assert limits.get("literal_digits") == 3000
    effects.load_effect("#if " + "1" * 2500 + "\n#endif\n" + FLAT)
    monkeypatch.setenv("EFFECTS_LIMIT_LITERAL_DIGITS", "6000")   # past Python's own 4,300
    assert limits.get("literal_digits") == min(6000, sys.get_int_max_str_digits() or 6000)
    monkeypatch.setenv("EFFECTS_LIMIT_LITERAL_DIGITS", "not a number")
    assert limits.get("literal_digits") == default
    with limits.raised(literal_digits=3):
        assert limits.get("literal_digits") == 3
        with pytest.raises(EffectError, match="limit literal_digits"):
            effects.load_effect("#if 1234\n#endif\n")
    assert limits.get("literal_digits") == default
    with pytest.raises(KeyError):
        limits.set_limit("no_such_limit", 1)


def test_the_contact_sheet_reads_files_only_inside_the_include_root(jail, capsys, monkeypatch):
    """`matrix --render` draws each cell by loading the effect again: with --include-root, a
    texture named outside the root is refused in the cell (its reason), never read."""
    from PIL import Image
    from effects.cli import sheet as sheet_module
    drawn_cells = []
    real = sheet_module.render_sheet
    monkeypatch.setattr(sheet_module, "render_sheet",
                        lambda *a, **k: drawn_cells.extend(real(*a, **k)) or drawn_cells)
    root, outside = jail
    Image.new("RGB", (4, 4), (0, 255, 0)).save(outside / "green.png")
    (root / "e.fx").write_text(
        'texture T < string ResourceName = "../outside/green.png"; >;\n'
        "technique t { pass p { Texture[0] = <T>; ColorOp[0] = SelectArg1;\n"
        "ColorArg1[0] = Texture; } }\n")
    sheet = root.parent / "sheet.png"
    code, out, err = _cli("matrix", root / "e.fx", "-p", "geforce3", "--include-root", root,
                          "--render", sheet, "--size", "8x8", "--jobs", "1", capsys=capsys)
    assert "Traceback" not in err
    cell, = drawn_cells
    assert cell.image is None and "include root" in cell.reason, cell
    from effects.cli.sheet import sheet_jobs
    from effects.host.batch import render_cell
    job, = sheet_jobs([str(root / "e.fx")], ["geforce3"], (8, 8),
                      load={"include_root": str(root)})
    cell = render_cell(job)
    assert cell.image is None and "include root" in cell.reason, cell
    # the same cell without the root reads the file: the green is drawn
    free, = sheet_jobs([str(root / "e.fx")], ["geforce3"], (8, 8))
    drawn = render_cell(free).image
    assert drawn is not None and (drawn[..., 1] > 200).any()


def test_matrix_takes_d_and_i_as_validate_does(tmp_path, capsys):
    (tmp_path / "inc").mkdir()
    (tmp_path / "inc" / "flags.fxh").write_text("#define PASS_STATE Lighting = False;\n")
    (tmp_path / "e.fx").write_text(
        '#include "flags.fxh"\n'
        "#ifdef WANT_SECOND\ntechnique second { pass p { PASS_STATE } }\n#endif\n"
        "technique first { pass p { PASS_STATE } }\n")
    code, out, err = _cli("matrix", tmp_path / "e.fx", "-p", "geforce3", "-I", tmp_path / "inc",
                          "--json", capsys=capsys)
    assert code == 0, err
    assert json.loads(out)[str(tmp_path / "e.fx")]["geforce3"]["technique"] == "first"
    code, out, err = _cli("matrix", tmp_path / "e.fx", "-p", "geforce3", "-I", tmp_path / "inc",
                          "-D", "WANT_SECOND", "--json", capsys=capsys)
    assert code == 0, err
    assert json.loads(out)[str(tmp_path / "e.fx")]["geforce3"]["technique"] == "second"
    code, out, err = _cli("matrix", tmp_path / "e.fx", "-p", "geforce3", capsys=capsys)
    assert code == 2 and "flags.fxh" in err
