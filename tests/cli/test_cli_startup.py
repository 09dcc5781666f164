"""What the command line does before its work: validation-only commands load NumPy's BLAS
with one thread."""
from __future__ import annotations

from tests.paths import ROOT

import os
import subprocess
import sys

ROOT = str(ROOT)


def test_validation_commands_load_blas_with_one_thread():
    """matrix (without --render), validate and profiles start NumPy's OpenBLAS with one thread
    (its thread pool is a fifth of the command's time); render, matrix --render and a thread
    count the user set are left alone."""
    code = ("import os, sys\n"
            "from effects.cli import main as m\n"
            "m._one_blas_thread(m.build_parser().parse_args(sys.argv[1:]))\n"
            "print(os.environ.get('OPENBLAS_NUM_THREADS'), 'numpy' in sys.modules)")
    def run(*args, **env):
        base = {k: v for k, v in os.environ.items() if k not in m_vars}
        return subprocess.run([sys.executable, "-c", code, *args], cwd=ROOT, env={**base, **env},
                              capture_output=True, text=True, check=True).stdout.split()
    m_vars = ("OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS")
    assert run("matrix", "fxfiles/phong.fx") == ["1", "False"]
    assert run("validate", "fxfiles/phong.fx") == ["1", "False"]
    assert run("profiles") == ["1", "False"]
    assert run("matrix", "fxfiles/phong.fx", "--render", "x.png") == ["None", "False"]
    assert run("render", "fxfiles/phong.fx", "-p", "geforce3", "-o", "x.png") == ["None", "False"]
    assert run("matrix", "fxfiles/phong.fx", OMP_NUM_THREADS="2") == ["None", "False"]
    assert run("matrix", "fxfiles/phong.fx", OPENBLAS_NUM_THREADS="2") == ["2", "False"]


def test_help_imports_only_what_it_prints():
    """`effects --help` is argparse and the parser's text: none of the libraries the commands
    use, nor typing or shutil (argparse's own width lookup pulls in zlib, bz2 and lzma), and
    the text is what argparse's own formatter wraps at that COLUMNS."""
    code = ("import argparse, contextlib, io, sys\n"
            "from effects.cli import main as m\n"
            "out = io.StringIO()\n"
            "with contextlib.redirect_stdout(out), contextlib.suppress(SystemExit):\n"
            "    m.main(['--help'])\n"
            "heavy = ('numpy', 'rich', 'yaml', 'lark', 'typing', 'shutil')\n"
            "print([name for name in heavy if name in sys.modules])\n"
            "stock = m.build_parser()\n"
            "stock.formatter_class = argparse.HelpFormatter\n"
            "print(out.getvalue() == stock.format_help(), len(out.getvalue().splitlines()))")
    def run(columns: str) -> list[str]:
        env = {**os.environ, "COLUMNS": columns}
        return subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=env, capture_output=True,
                              text=True, check=True).stdout.splitlines()
    narrow, wide = run("50"), run("200")
    assert narrow[0] == wide[0] == "[]"
    assert narrow[1].startswith("True ") and wide[1].startswith("True ")
    assert int(narrow[1].split()[1]) > int(wide[1].split()[1])   # the width was read
