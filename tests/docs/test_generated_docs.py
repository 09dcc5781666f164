"""The parts of docs/ that follow the code stay true to it: the tables docs/make_guide.py writes
(limits, bindings, the command-line reference, the HLSL intrinsics), the import graph
docs/make_layers.py draws, and the scene file example, which loads and renders."""
from __future__ import annotations

from tests.paths import ROOT

import argparse
import importlib.util
import re
from types import ModuleType

import numpy as np
import pytest
import yaml

import effects
from effects.base import limits
from effects.host.scene import SCENE_KEYS, scene_from_mapping

DOCS = ROOT / "docs"


def _script(name: str) -> ModuleType:
    spec = importlib.util.spec_from_file_location(name, DOCS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


MAKE_GUIDE = _script("make_guide")


@pytest.mark.parametrize("name", list(MAKE_GUIDE.GENERATED))
def test_each_generated_part_of_the_guide_is_up_to_date(name):
    path, now, wanted = MAKE_GUIDE.page_text(name)
    assert now == wanted, (f"{path.relative_to(ROOT)} ({name}) differs from the code: run "
                           ".venv/bin/python docs/make_guide.py and read the diff")


def test_the_limits_page_states_every_limit_its_default_and_how_to_raise_it():
    page = (DOCS / "guide" / "limits.md").read_text(encoding="utf-8")
    for limit in limits.LIMITS.values():
        assert f"| `{limit.name}` | {limit.default:,} {limit.unit} | {limit.what} |" in page
    assert "EFFECTS_LIMIT_<NAME>=N" in page and limits.env_name("source_bytes") in page
    # the breach the page shows is the one a user gets
    with pytest.raises(effects.EffectError) as caught:
        effects.load_effect("//" + "x" * 2_000_000 + "\n")
    assert str(caught.value) in page


def _sections(page: str) -> dict[str, str]:
    """`### \\`effects NAME\\`` section texts of the CLI reference, by command name."""
    parts = re.split(r"^### `effects (\w+)`$", page, flags=re.M)
    return dict(zip(parts[1::2], parts[2::2]))


def test_the_cli_reference_has_every_command_and_option():
    """Walked from the parser itself, apart from the generator: each command has a section,
    and each of its options and arguments appears in it."""
    from effects.cli.main import build_parser
    sections = _sections((DOCS / "guide" / "cli.md").read_text(encoding="utf-8"))
    parser = build_parser()
    commands = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    assert sorted(sections) == sorted(commands.choices)
    for name, sub in commands.choices.items():
        for action in sub._actions:
            if isinstance(action, argparse._HelpAction):
                continue
            for spelling in action.option_strings or [action.metavar or action.dest]:
                assert f"`{spelling}" in sections[name], (name, spelling)


def test_the_binding_table_lists_what_the_host_binds():
    from effects.host.semantics import DX8_NAME_SEMANTICS, MATRIX_SEMANTICS, VALUE_SEMANTICS
    page = (DOCS / "guide" / "host.md").read_text(encoding="utf-8")
    for semantic in [*MATRIX_SEMANTICS, *VALUE_SEMANTICS]:
        assert f"| `{semantic}` |" in page, semantic
    for name in DX8_NAME_SEMANTICS:
        assert f"| `{name}` |" in page, name


MAKE_LAYERS = _script("make_layers")


def test_the_layers_graph_is_up_to_date():
    now = (DOCS / "layers.dot").read_text(encoding="utf-8")
    assert now == MAKE_LAYERS.make_dot(), "run .venv/bin/python docs/make_layers.py"
    assert (DOCS / "layers.svg").is_file()


def test_the_layers_graph_draws_every_floor_and_only_downward_imports():
    """Each arrow between two floors points down (a floor imports only those below it); the
    back ends import only the program floor and the ground floor."""
    dot = (DOCS / "layers.dot").read_text(encoding="utf-8")
    floors = MAKE_LAYERS.floors(MAKE_LAYERS._config())
    level = {name: len(floors) - i for i, floor in enumerate(floors) for name in floor}
    edges = re.findall(r'^  "([\w.]+)" -> "([\w.]+)" \[label="\d+"\];$', dot, re.M)
    assert edges
    for source, target in edges:
        if source in level and target in level:
            assert level[source] > level[target], (source, target)
        elif source.startswith("backends."):
            assert target in ("program", "base") or target not in level, (source, target)
    assert {name for floor in floors for name in floor} <= set(re.findall(r'^  "([\w.]+)" \[', dot, re.M))


def _scene_examples() -> list[str]:
    page = (DOCS / "guide" / "scene.md").read_text(encoding="utf-8")
    return re.findall(r"^```yaml\n(.*?)^```", page, re.S | re.M)


def test_the_complete_scene_example_sets_every_key_and_renders():
    """The first example sets every key a scene file takes, as saved in fxfiles/ beside
    phong.fx; it draws a torus on the 320 x 240 frame it asks for, cleared to its colour."""
    example = yaml.safe_load(_scene_examples()[0])
    assert sorted(example) == sorted(SCENE_KEYS)
    scene = scene_from_mapping(example, path="docs/guide/scene.md", base_dir=str(ROOT / "fxfiles"))
    image = effects.render(effects.load_effect(str(ROOT / "fxfiles" / "phong.fx")), "radeon9700",
                           scene=scene)
    assert image.shape == (240, 320, 4)
    assert tuple(image[0, 0]) == (0x20, 0x30, 0x40, 0xFF)     # clear: '0xff203040'
    drawn = np.any(image != image[0, 0], axis=-1)
    assert 0.05 < drawn.mean() < 0.9


def test_the_inline_vertices_example_draws_its_colours():
    """A strip over clip space, unlit: each pixel of the first triangle (red, green, blue at
    (-1, -1), (-1, 1), (1, -1)) is its corners' colours weighted by the barycentric coordinates
    of where Direct3D 9 samples the pixel (its integer coordinates: the half-pixel offset)."""
    scene = scene_from_mapping(yaml.safe_load(_scene_examples()[1]), path="docs/guide/scene.md")
    effect = effects.load_effect("technique T { pass P { Lighting = false; } }")
    image = effects.render(effect, "tnt2", scene=scene, size=(16, 16))
    assert np.all(image[..., 3] == 255)                      # the whole frame is drawn
    for row, col in [(15, 0), (0, 0), (15, 15), (8, 3)]:
        x, y = col / 8 - 1, 1 - row / 8                     # where D3D9 samples, in clip space
        green, blue = (y + 1) / 2, (x + 1) / 2               # weights of (-1, 1) and (1, -1)
        expected = np.array([1 - green - blue, green, blue]) * 255
        assert np.abs(image[row, col, :3] - expected).max() <= 1, (row, col, image[row, col])
