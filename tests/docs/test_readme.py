"""The README is the front page, and it works when pasted: every shell command of its fenced
blocks runs in a fresh shell (the repository as the current folder, a PATH without the virtual
environment, an empty HOME, the files it writes moved into a temporary folder), every Python
block runs in a fresh interpreter, and each exits 0. Every document the README, the docs and the
code's comments name exists in the repository."""
from __future__ import annotations

from tests.paths import ROOT

import ast
import io
import os
import re
import shutil
import subprocess
import sys
import tokenize
from pathlib import Path

import pytest

README = ROOT / "README.md"
SETUP = "bash .ci/setup"
TEST_COMMAND = ".venv/bin/python -m pytest"
# options whose argument is a file a command writes: moved into the test's folder
OUTPUT_OPTIONS = ("-o", "--output", "--render", "--screenshot")
SHELLS = ("sh", "bash", "shell")


def fenced_blocks(text: str) -> list[tuple[str, str]]:
    """(language, body) of each fenced block, in order."""
    return re.findall(r"^```([\w-]*)\n(.*?)^```", text, re.S | re.M)


def shell_commands(text: str) -> list[str]:
    """Each command line of the shell blocks (continuations joined, blank lines left out)."""
    commands = []
    for language, body in fenced_blocks(text):
        if language in SHELLS:
            joined = body.replace("\\\n", " ")
            commands += [line.strip() for line in joined.splitlines()
                         if line.strip() and not line.strip().startswith("#")]
    return commands


def python_blocks(text: str) -> list[tuple[str, str | None]]:
    """(code, the plain block right after it: the output it prints, or None)."""
    blocks = fenced_blocks(text)
    return [(body, blocks[i + 1][1] if i + 1 < len(blocks) and blocks[i + 1][0] == "" else None)
            for i, (language, body) in enumerate(blocks) if language == "python"]


README_TEXT = README.read_text(encoding="utf-8")
COMMANDS = shell_commands(README_TEXT)
# the set-up and the test command are checked against .ci/run, not run here: the set-up is
# what made the environment this test runs in, and the test command is this run
RUN_HERE = [c.split("&&", 1)[1].strip() if c.startswith(SETUP + " &&") else c
            for c in COMMANDS if c != TEST_COMMAND]


def _fresh_env(home: Path) -> dict[str, str]:
    """A fresh login's environment: no virtual environment on the PATH, nothing of this run."""
    env = {"PATH": "/usr/local/bin:/usr/bin:/bin", "HOME": str(home), "LANG": "C.UTF-8"}
    if os.environ.get("DISPLAY"):
        env["DISPLAY"] = os.environ["DISPLAY"]
    return env


def _outputs_into(command: str, folder: Path) -> tuple[str, list[Path]]:
    """The command with each file it writes (`-o NAME`, `--render NAME` ...) moved into `folder`;
    the README promises they land in the current folder, so each is a bare file name."""
    written = []

    def move(match: re.Match) -> str:
        name = match.group(2)
        assert "/" not in name, f"{command}: writes {name} outside the current folder"
        written.append(folder / name)
        return match.group(1) + str(folder / name)

    options = "|".join(re.escape(o) for o in OUTPUT_OPTIONS)
    return re.sub(rf"(\s(?:{options})\s+)(\S+)", move, command), written


def test_the_two_commands_are_the_ones_ci_runs():
    """The set-up command comes first and renders in the same line; the test command is the one
    .ci/run runs after the same set-up."""
    assert COMMANDS[0].startswith(SETUP + " && .venv/bin/effects render ")
    assert TEST_COMMAND in COMMANDS
    ci = [line.strip() for line in (ROOT / ".ci" / "run").read_text().splitlines()
          if line.strip() and not line.lstrip().startswith("#")]
    assert SETUP in ci and ci[-1] == TEST_COMMAND
    assert ci.index(SETUP) < ci.index(TEST_COMMAND)


def test_every_command_names_the_program_in_the_venv():
    """A fresh shell has no `effects` on its PATH: the README names `.venv/bin/effects`."""
    for command in RUN_HERE:
        words = command.split("#")[0].split()
        assert "effects" not in words and "python" not in words, command


def test_the_readme_is_a_front_page():
    assert len(README_TEXT.splitlines()) <= 300
    assert "](docs/contact_sheet.png)" in README_TEXT
    assert any("effects.render(" in code and ".save(" in code for code, _ in python_blocks(README_TEXT))


@pytest.mark.slow
@pytest.mark.parametrize("command", RUN_HERE, ids=[c.split("#")[0][:60].strip() for c in RUN_HERE])
def test_each_readme_command_runs_as_pasted(command, tmp_path):
    command, written = _outputs_into(command, tmp_path)
    env = _fresh_env(tmp_path / "home")
    if " view " in command and "DISPLAY" not in env:
        if shutil.which("xvfb-run") is None:
            pytest.skip("no display and no xvfb-run (bash .ci/setup installs it as root)")
        command = "xvfb-run -a " + command    # the README says so for a machine without one
    done = subprocess.run(["bash", "-c", command], cwd=ROOT, env=env, capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 0, f"{command}\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}"
    for path in written:
        assert path.is_file() and path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", path


@pytest.mark.slow
@pytest.mark.parametrize("code, shown", python_blocks(README_TEXT),
                         ids=[f"python-{i}" for i, _ in enumerate(python_blocks(README_TEXT))])
def test_each_readme_python_example_runs(code, shown, tmp_path):
    written: list[Path] = []

    def move(match: re.Match) -> str:      # "name.png" and f"name_{x}.png": into tmp_path
        written.append(match.group(2))
        return f"{match.group(1)}{tmp_path}/{match.group(2)}{match.group(1)}"

    code = re.sub(r"""(["'])([\w{}.-]+\.png)\1""", move, code)
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=_fresh_env(tmp_path / "home"),
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, f"{code}\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}"
    if shown is not None:       # the output the README shows is the output, as the user sees it
        assert done.stdout == shown
    assert len(list(tmp_path.glob("*.png"))) >= len(written)


# ------------------------------------------------------------------------------------------------
# Every document named exists

TOP = ("effects/", "backends/", "fxfiles/", "caps_profiles/", "tests/", "benchmarks/", "docs/",
       ".ci/")
# Documents outside the repository that comments cite as sources, by name.
EXTERNAL = {"effect-states.md"}   # MicrosoftDocs/win32's "Effect States (Direct3D 9)" page


def _named_paths(text: str) -> list[str]:
    """Paths a Markdown page names: relative link targets, and `code` spans that are whole
    repository paths (no wildcard)."""
    links = [t for t in re.findall(r"\]\(([^)\s]+)\)", text) if not re.match(r"\w+:", t)]
    spans = [s for s in re.findall(r"`([\w./-]+)`", text) if s.startswith(TOP) or s.endswith(".md")]
    return [t.split("#")[0] for t in links if t.split("#")[0]] + spans


def _pages() -> list[Path]:
    """The README and the documentation written for users (docs/reference/ holds the sourced
    notes, whose `*.md` spans are their sources' file names: only their links are checked)."""
    return [README, *sorted((ROOT / "docs").glob("*.md")), *sorted((ROOT / "docs" / "guide").glob("*.md")),
            ROOT / "fxfiles" / "README.md", ROOT / "caps_profiles" / "README.md"]


@pytest.mark.parametrize("page", _pages(), ids=lambda p: str(p.relative_to(ROOT)))
def test_every_path_a_page_names_exists(page):
    text = page.read_text(encoding="utf-8")
    missing = []
    for name in _named_paths(text):
        # a link is relative to its page; a code span is a path from the repository's root
        if not ((page.parent / name).exists() or (ROOT / name).exists()):
            missing.append(name)
    assert missing == [], f"{page.relative_to(ROOT)} names {missing}"


def test_the_reference_pages_links_exist():
    for page in sorted((ROOT / "docs" / "reference").glob("*.md")):
        text = page.read_text(encoding="utf-8")
        links = [t.split("#")[0] for t in re.findall(r"\]\(([^)\s]+)\)", text)
                 if not re.match(r"\w+:", t) and t.split("#")[0]]
        assert all((page.parent / t).exists() for t in links), (page.name, links)


def _comments(path: Path) -> list[tuple[int, str]]:
    """(line, text) of the comments and docstrings of a Python file."""
    source = path.read_text(encoding="utf-8")
    found = [(tok.start[0], tok.string) for tok in tokenize.generate_tokens(io.StringIO(source).readline)
             if tok.type == tokenize.COMMENT]
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            doc = ast.get_docstring(node, clean=False)
            if doc:
                found.append((node.body[0].lineno, doc))
    return found


def _code_files() -> list[Path]:
    files = [p for folder in ("effects", "backends", "benchmarks", "tests", "docs")
             for p in (ROOT / folder).rglob("*.py") if "data" not in p.relative_to(ROOT).parts]
    return sorted(files)


def test_every_document_a_code_comment_names_exists():
    """`docs/reference/semantics.md §2.4`, `docs/design.md habit 11`, `fxfiles/README.md`: a
    comment's document is a path from the repository's root or from the file's folder."""
    missing = []
    for path in _code_files():
        for line, text in _comments(path):
            for name in re.findall(r"[\w./-]*\w\.md\b", text):
                if name in EXTERNAL or (ROOT / name).exists() or (path.parent / name).exists():
                    continue
                missing.append(f"{path.relative_to(ROOT)}:{line}: {name}")
    for path in (ROOT / "pyproject.toml", ROOT / ".ci" / "setup", ROOT / ".ci" / "run"):
        for line, text in enumerate(path.read_text().splitlines(), 1):
            comment = text.partition("#")[2]
            for name in re.findall(r"[\w./-]*\w\.md\b", comment):
                if not (ROOT / name).exists():
                    missing.append(f"{path.relative_to(ROOT)}:{line}: {name}")
    assert missing == []
