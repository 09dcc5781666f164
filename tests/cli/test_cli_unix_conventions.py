"""The command line as a shell user meets it: help with no arguments, --version, output for
pipes and terminals, a reader that leaves (exit 141), a closed stdout, no display. Each runs
`python -m effects` in a child process, where the streams are what a shell gives."""
from __future__ import annotations

from tests.paths import ROOT

import errno
import json
import os
import pty
import re
import select
import shlex
import subprocess
import sys
import tomllib
from importlib import metadata
from io import StringIO
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import effects
from effects.d3d9.caps import list_profiles

PHONG = str(ROOT / "fxfiles" / "phong.fx")
BUNDLED = sorted(str(p) for p in (ROOT / "fxfiles").glob("*.fx"))
ANSI = re.compile(r"\x1b\[[0-9;?]*[A-Za-z]")


def _env(**changes: str | None) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in ("COLUMNS", "LINES", "FORCE_COLOR",
                                                            "TTY_COMPATIBLE", "NO_COLOR")}
    for name, value in changes.items():
        if value is None:
            env.pop(name, None)
        else:
            env[name] = value
    return env


def effects_cmd(*argv: str, **env: str | None) -> subprocess.CompletedProcess:
    """`effects ARGV...` with its stdout into a pipe that is read to the end."""
    return subprocess.run([sys.executable, "-m", "effects", *argv], cwd=ROOT, env=_env(**env),
                          capture_output=True, text=True, timeout=180)


def on_a_terminal(*argv: str, columns: int) -> tuple[int, str]:
    """`effects ARGV...` with stdout on a pseudo-terminal COLUMNS wide: (status, what it
    printed there, ANSI colours removed)."""
    leader, follower = pty.openpty()
    proc = subprocess.Popen([sys.executable, "-m", "effects", *argv], cwd=ROOT,
                            env=_env(COLUMNS=str(columns)), stdout=follower,
                            stderr=subprocess.PIPE)
    os.close(follower)
    chunks = []
    while True:
        ready, _, _ = select.select([leader], [], [], 180)
        assert ready, "no output within 180 s"
        try:
            chunk = os.read(leader, 65536)
        except OSError as exc:     # EIO: the child ended and closed the terminal
            assert exc.errno == errno.EIO
            break
        if not chunk:
            break
        chunks.append(chunk)
    os.close(leader)
    assert proc.stderr is not None
    err = proc.stderr.read().decode()
    code = proc.wait(60)
    assert err == "", err
    text = b"".join(chunks).decode().replace("\r\n", "\n")
    return code, ANSI.sub("", text)


# --- help and version ----------------------------------------------------------------------------

def test_effects_alone_prints_the_help_to_stdout_and_exits_0():
    """As pip and cargo do: asking for nothing is not an error; the help says what there is."""
    alone, helped = effects_cmd(), effects_cmd("--help")
    assert (alone.returncode, alone.stderr) == (0, "")
    assert alone.stdout == helped.stdout
    assert alone.stdout.startswith("usage: effects [-h] [--version]")
    for command in ("validate", "matrix", "render", "profiles", "view", "doctor", "compile"):
        assert f"    {command} " in alone.stdout


def test_version_is_the_one_the_package_carries():
    proc = effects_cmd("--version")
    assert (proc.returncode, proc.stderr) == (0, "")
    assert proc.stdout == f"effects {effects.__version__}\n"
    assert re.fullmatch(r"\d+\.\d+\.\d+", effects.__version__)
    # one source: pyproject.toml reads the package's, and the installed metadata is it
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())
    assert "version" not in project["project"] and "version" in project["project"]["dynamic"]
    assert project["tool"]["setuptools"]["dynamic"]["version"] == {"attr": "effects.__version__"}
    assert metadata.version("effects") == effects.__version__


# --- profiles ------------------------------------------------------------------------------------

GEFORCE3 = ["geforce3", "dx8", "GeForce3", "8/4", "EMBM dot3", "cube 3D", "4096", "1.1", "1.1"]
TNT2 = ["tnt2", "dx6", "RIVA TNT2", "2/2", "-", "-", "2048", "-", "sw"]   # caps_profiles/tnt2.yaml


def test_profiles_into_a_pipe_is_one_card_a_line_in_tab_separated_fields():
    proc = effects_cmd("profiles", COLUMNS="40")   # narrow: nothing may wrap for it
    assert (proc.returncode, proc.stderr) == (0, "")
    records = [line.split("\t") for line in proc.stdout.splitlines()]
    assert [r[0] for r in records] == list_profiles()    # `cut -f1`: the names, by generation
    assert all(len(r) == 9 for r in records)
    assert not re.search("[\u2500-\u257f]", proc.stdout)   # no box drawing
    assert records[list_profiles().index("geforce3")] == GEFORCE3
    assert records[list_profiles().index("tnt2")] == TNT2


def test_profiles_names_cards_or_profile_files_and_shows_those_only():
    proc = effects_cmd("profiles", "geforce3", str(ROOT / "caps_profiles" / "tnt2.yaml"))
    assert (proc.returncode, proc.stderr) == (0, "")
    assert [line.split("\t") for line in proc.stdout.splitlines()] == [TNT2, GEFORCE3]


def test_profiles_with_an_unknown_card_says_which_it_meant():
    proc = effects_cmd("profiles", "geforce3", "geforc3")
    assert (proc.returncode, proc.stdout) == (2, "")
    assert proc.stderr.startswith("geforc3:1:1: error: unknown profile 'geforc3'; did you mean "
                                  "'geforce3'?; known profiles: g400, ")
    assert len(proc.stderr.splitlines()) == 1


def test_profiles_on_a_terminal_is_the_table_by_generation():
    code, text = on_a_terminal("profiles", "tnt2", "geforce3", columns=100)
    assert code == 0
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    assert lines[0].split() == ["card", "name", "st/tx", "bump", "maps", "size", "ps", "vs"]
    assert set(lines[1]) == {"─"}
    assert len(lines) == 6 and (lines[2], lines[4]) == ("dx6", "dx8")   # a heading a generation
    assert lines[3].split() == ["tnt2", "RIVA", "TNT2", "2/2", "-", "-", "2048", "-", "sw"]
    assert lines[5].split() == ["geforce3", "GeForce3", "8/4", "EMBM", "dot3", "cube", "3D",
                                "4096", "1.1", "1.1"]


# --- matrix at 80 columns ------------------------------------------------------------------------

def _cells_of_tables(text: str) -> dict[tuple[str, str], str]:
    """{(card, effect): cell} read from the boxed tables in `text`, however many."""
    cells: dict[tuple[str, str], str] = {}
    header: list[str] = []
    for line in text.splitlines():
        if line.startswith("┃"):
            header = [c.strip() for c in line.split("┃")[1:-1]]
        elif line.startswith("│"):
            row = [c.strip() for c in line.split("│")[1:-1]]
            assert len(row) == len(header) and header[0] == "card"
            for effect, cell in zip(header[1:], row[1:]):
                assert (row[0], effect) not in cells
                cells[row[0], effect] = cell
    return cells


def _expected_cells() -> dict[tuple[str, str], str]:
    """Every cell as the JSON gives it: what the table must show whole."""
    got = json.loads(effects_cmd("matrix", *BUNDLED, "--json").stdout)
    return {(card, Path(f).stem): (f"{c['technique']} ({c['passes']})" if c["technique"] else "none")
            for f in BUNDLED for card, c in got[f].items()}


@pytest.mark.slow
def test_matrix_on_an_80_column_terminal_keeps_every_name_whole():
    """The bundled effects at COLUMNS=80: the table does not fit, so it is printed as tables of
    whole columns, each led by the cards, every line within 80 columns (folded, each card took
    nine lines of 3-letter fragments)."""
    code, text = on_a_terminal("matrix", *BUNDLED, columns=80)
    assert code == 0
    assert max(len(line) for line in text.splitlines()) <= 80
    tables = sum(line.startswith("┃") for line in text.splitlines())
    assert tables > 1
    assert sum(line.startswith("│") for line in text.splitlines()) == tables * len(list_profiles())
    assert _cells_of_tables(text) == _expected_cells()


def test_matrix_too_narrow_for_one_effect_is_one_line_per_cell():
    from effects.cli.console import make_console
    from effects.cli.report import print_matrix
    result = {"a/phong.fx": {"tnt2": {"technique": "SingleTexture", "passes": 1, "rejected": {}},
                             "geforce3": {"technique": "PerPixelPhong_ps11", "passes": 2,
                                          "rejected": {}}},
              "wood.fx": {"tnt2": {"technique": None, "passes": 0, "rejected": {}},
                          "geforce3": {"technique": None, "passes": 0, "rejected": {}}}}
    out = StringIO()
    print_matrix(result, make_console(file=out, force_terminal=True, color_system=None, width=24))
    assert out.getvalue().splitlines() == [
        "phong",
        "  tnt2      SingleTexture (1)",
        "  geforce3  PerPixelPhong_ps11 (2)",
        "wood",
        "  tnt2      none",
        "  geforce3  none",
    ]


# --- a reader that leaves: 141 -------------------------------------------------------------------

@pytest.mark.slow
@pytest.mark.parametrize("argv", [
    ["validate", PHONG, "-p", "geforce3"],
    ["validate", PHONG],
    ["doctor", PHONG],
    ["matrix", PHONG, str(ROOT / "fxfiles" / "wood.fx")],
    ["matrix", PHONG, "--json"],
    ["profiles"],
    ["profiles", "geforce3"],
    ["compile", PHONG],
    ["render", PHONG, "-p", "geforce3", "--size", "8x8", "-o", "{tmp}/out.png"],
    ["--help"],
    ["validate", "--help"],
    ["--version"],
    [],
], ids=lambda argv: " ".join(os.path.basename(a) for a in argv) or "(none)")
def test_every_command_that_prints_exits_141_quietly_when_the_reader_leaves(argv, tmp_path):
    """`effects ... | head -1`: as a Unix tool ended by SIGPIPE, status 128+13 and nothing on
    stderr (rich's own answer was exit 1; argparse's, for help, exit 0)."""
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    proc = subprocess.Popen([sys.executable, "-m", "effects", *argv], cwd=ROOT, env=_env(),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert proc.stdout is not None and proc.stderr is not None
    proc.stdout.close()              # the reader leaves before anything is written
    err = proc.stderr.read().decode()
    assert proc.wait(120) == 141, err
    assert err == ""


@pytest.mark.parametrize("argv", [["validate", "missing.fx"], ["frobnicate"]])
def test_an_error_said_into_a_pipe_the_reader_left_exits_141(argv):
    """`effects validate missing.fx 2>&1 | head -1`: the error itself meets the closed pipe
    (it was rich's SystemExit(1), raised while the error was said)."""
    proc = subprocess.Popen([sys.executable, "-m", "effects", *argv], cwd=ROOT, env=_env(),
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    assert proc.stdout is not None
    proc.stdout.close()
    assert proc.wait(120) == 141


# --- a closed stdout -----------------------------------------------------------------------------

def test_render_with_stdout_closed_writes_the_png_and_drops_the_line(tmp_path):
    """`effects render ... >&-` was an internal error (AttributeError); the PNG is the
    command's product, so it is written and the command succeeds, its report line dropped."""
    command = [sys.executable, "-m", "effects", "render", PHONG, "-p", "geforce3",
               "--size", "12x8"]
    shell = shlex.join(command + ["-o", str(tmp_path / "closed.png")]) + " >&-"
    proc = subprocess.run(["sh", "-c", shell], cwd=ROOT, env=_env(), capture_output=True,
                          text=True, timeout=180)
    assert (proc.returncode, proc.stderr) == (0, "")
    opened = subprocess.run(command + ["-o", str(tmp_path / "open.png")], cwd=ROOT, env=_env(),
                            capture_output=True, text=True, timeout=180)
    assert opened.returncode == 0 and opened.stdout.startswith("rendered ")
    closed = np.asarray(Image.open(tmp_path / "closed.png"))
    assert closed.shape == (8, 12, 4)
    assert np.array_equal(closed, np.asarray(Image.open(tmp_path / "open.png")))


def test_validate_with_stdout_closed_keeps_its_status(tmp_path):
    """The table is dropped; the status still says whether the card can run the effect."""
    dot3 = tmp_path / "dot3.fx"
    dot3.write_text("technique t { pass p { ColorOp[0] = DotProduct3; } }\n")
    for path, status in ((PHONG, 0), (str(dot3), 1)):
        proc = subprocess.run(["sh", "-c", f'"{sys.executable}" -m effects validate "$1" -p tnt2 >&-',
                               "sh", path], cwd=ROOT, env=_env(), capture_output=True, text=True,
                              timeout=180)
        assert (proc.returncode, proc.stderr) == (status, ""), path


# --- no display ----------------------------------------------------------------------------------

def test_view_without_a_display_says_so_in_one_line():
    proc = effects_cmd("view", PHONG, DISPLAY=None, WAYLAND_DISPLAY=None)
    assert (proc.returncode, proc.stdout) == (2, "")
    assert proc.stderr == (
        "effects view: error: no display to open the window on (DISPLAY is not set); run it in "
        "a desktop session, set DISPLAY, or under a virtual X server: xvfb-run -a effects view "
        f"{PHONG}\n")
    proc = effects_cmd("view", PHONG, DISPLAY=":4321", WAYLAND_DISPLAY=None)
    assert proc.returncode == 2
    assert proc.stderr.startswith("effects view: error: no display to open the window on "
                                  "(cannot connect to DISPLAY=:4321); ")


def test_view_of_a_missing_file_says_the_file_is_missing_first(tmp_path):
    missing = tmp_path / "missing.fx"
    proc = effects_cmd("view", str(missing), DISPLAY=None, WAYLAND_DISPLAY=None)
    assert (proc.returncode, proc.stdout) == (2, "")
    assert proc.stderr == f"{missing}:1:1: error: cannot read effect file: No such file or directory\n"
