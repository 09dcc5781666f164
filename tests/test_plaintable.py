"""effects.cli.plaintable draws the selection matrix as rich does when the output is not a
terminal: compared with rich itself on random tables and widths, and on the bundled effects."""
from __future__ import annotations

import glob
import io
import os
import subprocess
import sys

from hypothesis import given, settings, strategies as st
from rich.console import Console
from rich.table import Table
from rich.text import Text

from effects.cli import plaintable

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _rich(header, rows, width):
    """What report.print_matrix's rich table prints at `width` (not a terminal)."""
    table = Table(header_style="bold", show_lines=False)
    for h in header:
        table.add_column(h, overflow="fold")
    for row in rows:
        table.add_row(row[0], *[Text(c) if c != "none" else Text(c, style="red") for c in row[1:]])
    out = io.StringIO()
    Console(file=out, width=width, highlight=False).print(table)
    return out.getvalue()


_word = st.text(alphabet="abcdefghijklmnopqrstuvwxyzABCDEFGHIJ_0123456789()<>.-", min_size=1, max_size=30)
_cell = st.lists(_word, min_size=1, max_size=4).map(" ".join) | st.sampled_from(
    ["none", "  lead", "trail  ", "a  b", "x" * 45, " ", "MultiLight_ff (1)"])


@settings(max_examples=600, deadline=None)
@given(data=st.data(), n=st.integers(1, 14), m=st.integers(1, 8), width=st.integers(1, 260))
def test_same_text_as_rich(data, n, m, width):
    header = data.draw(st.lists(_cell, min_size=n, max_size=n))
    rows = [data.draw(st.lists(_cell, min_size=n, max_size=n)) for _ in range(m)]
    mine = plaintable.render(header, rows, width)
    if mine is None:   # refused: rich prints it
        return
    assert mine == _rich(header, rows, width)


def test_the_bundled_matrix_is_drawn_here_at_common_widths():
    """Not a vacuous comparison: the real table takes the plain path at 80 and wider."""
    from effects.caps import list_profiles, load_profile
    from effects.cli.report import matrix, _matrix_cells
    from effects.frontend.loader import load_effect
    files = sorted(glob.glob(os.path.join(ROOT, "fxfiles", "*.fx")))
    result = matrix({f: load_effect(f) for f in files}, [load_profile(p) for p in list_profiles()])
    header, rows = _matrix_cells(result)
    for width in (80, 120, 200, 300):
        mine = plaintable.render(header, rows, width)
        assert mine is not None, width
        assert mine == _rich(header, rows, width)


def test_refused_cells_and_widths():
    assert plaintable.render(["a[b]"], [["x"]], 80) is None          # markup
    assert plaintable.render([":smile:"], [["x"]], 80) is None       # emoji
    assert plaintable.render(["é"], [["x"]], 80) is None             # not ASCII
    assert plaintable.render(["a"], [[""]], 80) is None              # empty
    assert plaintable.render(["a", "b"], [["x", "y"]], 5) is None    # too narrow


def _run(env_extra, *args):
    env = dict(os.environ, **env_extra)
    for name in ("FORCE_COLOR", "TTY_COMPATIBLE", "COLUMNS", "LINES"):
        if name not in env_extra:
            env.pop(name, None)
    return subprocess.run([sys.executable, "-m", "effects", *args], cwd=ROOT, env=env,
                          capture_output=True, text=True, stdin=subprocess.DEVNULL)


def test_the_command_prints_what_rich_prints():
    """`effects matrix` through the plain path, against the same command made to print through
    rich (FORCE_COLOR= set empty: rich then decides 'not a terminal' itself, so the text is the
    same and the plain path steps aside), at the default width and at COLUMNS=137."""
    files = ["fxfiles/phong.fx", "fxfiles/wood.fx", "fxfiles/sdk9_hlsl.fx"]
    for extra in ({}, {"COLUMNS": "137"}):
        plain = _run(extra, "matrix", *files)
        via_rich = _run({**extra, "FORCE_COLOR": ""}, "matrix", *files)
        assert plain.returncode == via_rich.returncode == 0
        assert plain.stdout == via_rich.stdout
        assert "┏" in plain.stdout and "phong" in plain.stdout

