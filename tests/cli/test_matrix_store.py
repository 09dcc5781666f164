"""Rows of `effects matrix` kept between commands (effects/cli/matrix_store.py): a row read
back is the row a fresh command makes, it is found again only while nothing it was made from
has changed, rows that could not be found again exactly are not kept, and a bad entry is a
miss."""
from __future__ import annotations

from tests.paths import ROOT

import glob
import json
import os
import shutil
import subprocess
import sys
import time

import pytest

from effects.base import bundled, disk_store, limits
from effects.cli import matrix_store
from effects.cli.main import main
from effects.cli.matrix_store import MatrixJob
from effects.cli.report import matrix_job

ROOT = str(ROOT)
PHONG = os.path.join(ROOT, "fxfiles", "phong.fx")


def _settle(*paths: str) -> None:
    """Date files 10 s back: a file written in the last 2 s is not kept (it may be being saved)."""
    then = time.time() - 10
    for p in paths:
        os.utime(p, (then, then))


@pytest.fixture
def store(tmp_path):
    folder = tmp_path / "store"
    assert disk_store.enable(str(folder))
    yield folder
    disk_store.disable()


def _job(path: str, *, profiles=(), policy="first", root=None, strict=False, defines=(),
         include_dirs=()) -> MatrixJob:
    shared = matrix_store.shared_key(tuple(profiles), policy, strict, root, (),
                                     matrix_store.preprocessor_options(defines, include_dirs))
    return MatrixJob(path, tuple(profiles), policy, root, strict, shared,
                     defines=defines, include_dirs=include_dirs)


def _name(job: MatrixJob) -> str | None:
    found = matrix_store.inputs(job)
    return None if found is None else found.name


def _rows(folder) -> int:
    return sum(1 for f in glob.glob(os.path.join(folder, "*.json"))
               if "row" in json.loads(open(f).read()))


def _copy(tmp_path, name="effect.fx", source=PHONG) -> str:
    path = str(tmp_path / name)
    shutil.copyfile(source, path)
    _settle(path)
    return path


def _command(cache_dir, *args, env=None):
    """`effects ARGS` in a fresh process; stderr's last line lists which heavy modules loaded."""
    code = ("import sys\n"
            "from effects.cli.main import main\n"
            "rc = main(sys.argv[1:])\n"
            "print('LOADED', *sorted(m for m in ('numpy', 'yaml', 'lark', 'effects.d3d9.caps', "
            "'effects.model', 'effects.validate') if m in sys.modules), file=sys.stderr)\n"
            "sys.exit(rc)")
    return subprocess.run([sys.executable, "-c", code, *args], cwd=ROOT,
                          env={**os.environ, "EFFECTS_CACHE_DIR": str(cache_dir), **(env or {})},
                          capture_output=True, text=True)


def test_rows_read_back_print_the_matrix_a_fresh_command_prints(tmp_path):
    """Every bundled effect on every card, as a table and as JSON, on worker processes: the run
    that keeps the rows, the run that reads them back and a run with the store off print the
    same; the run that reads them loads no effect, card, NumPy, lark or PyYAML."""
    files = sorted(os.path.relpath(f, ROOT) for f in glob.glob(os.path.join(ROOT, "fxfiles", "*.fx")))
    for n, extra in enumerate(([], ["--json"])):
        made = _command(tmp_path / str(n), "matrix", *files, *extra)
        read = _command(tmp_path / str(n), "matrix", *files, *extra)
        off = _command(tmp_path / "off", "matrix", *files, *extra, env={"EFFECTS_CACHE": "off"})
        assert made.returncode == read.returncode == off.returncode == 0, made.stderr
        assert made.stdout == read.stdout == off.stdout
        assert "effects.validate" in made.stderr.splitlines()[-1]
        assert read.stderr.splitlines()[-1] == "LOADED"
        assert _rows(tmp_path / str(n)) == len(files)
    assert not (tmp_path / "off").exists()


def test_an_edited_effect_is_validated_again(tmp_path):
    path = _copy(tmp_path)
    first = _command(tmp_path / "store", "matrix", path, "--json")
    assert first.returncode == 0 and "PerPixelPhong_ps20" in first.stdout
    with open(path) as f:
        text = f.read()
    with open(path, "w") as f:
        f.write(text.replace("PerPixelPhong_ps20", "Renamed_ps20"))
    _settle(path)
    again = _command(tmp_path / "store", "matrix", path, "--json")
    assert again.returncode == 0
    assert "Renamed_ps20" in again.stdout and "PerPixelPhong_ps20" not in again.stdout
    assert "effects.validate" in again.stderr.splitlines()[-1]


def test_a_row_is_found_by_every_input_and_only_those(tmp_path, store, monkeypatch):
    path = _copy(tmp_path)
    first = _name(_job(path))
    assert first is not None and first == _name(_job(path))
    # the effect's bytes (not its dates)
    with open(path, "a") as f:
        f.write("// edited\n")
    _settle(path)
    assert _name(_job(path)) != first
    shutil.copyfile(PHONG, path)
    _settle(path)
    assert _name(_job(path)) == first
    # the options and the cards as named
    for other in (dict(policy="quality"), dict(strict=True), dict(root=str(tmp_path)),
                  dict(profiles=("geforce3",)), dict(profiles=("geforce3", "tnt2")),
                  dict(defines=(("X", "1"),)), dict(include_dirs=(str(tmp_path),))):
        assert _name(_job(path, **other)) not in (None, first), other
    # the path as given, and the folder it is given from
    monkeypatch.chdir(tmp_path)
    assert _name(_job("effect.fx")) not in (None, first)
    monkeypatch.chdir(ROOT)
    assert _name(_job(os.path.relpath(path))) not in (None, first)
    # a resource limit, the code
    with limits.raised(source_bytes=limits.get("source_bytes") + 1):
        assert _name(_job(path)) != first
    held = disk_store._state["fingerprint"]
    monkeypatch.setitem(disk_store._state, "fingerprint", "another version")
    assert _name(_job(path)) != first
    monkeypatch.setitem(disk_store._state, "fingerprint", held)
    # a bundled profile's bytes (any card may inherit from it), or its file replaced
    cards = tmp_path / "cards"
    shutil.copytree(bundled.PROFILE_FOLDER, cards)
    _settle(*glob.glob(str(cards / "*.yaml")))
    monkeypatch.setattr(bundled, "PROFILE_FOLDER", str(cards))
    copied = _name(_job(path))
    assert copied is not None
    tnt2 = cards / "tnt2.yaml"
    tnt2.write_text(tnt2.read_text() + "# edited\n")
    _settle(str(tnt2))
    edited = _name(_job(path))
    assert edited not in (None, copied)
    dated = os.stat(tnt2).st_mtime_ns      # the same size and dates, another byte
    tnt2.write_text(tnt2.read_text().replace("# edited", "# Edited"))
    os.utime(tnt2, ns=(dated, dated))
    assert _name(_job(path)) not in (None, copied, edited)
    # a profile written in the last two seconds: nothing is kept
    tnt2.write_text(tnt2.read_text())
    assert matrix_store.shared_key((), "first", False, None) is None
    assert _name(_job(path)) is None
    monkeypatch.setattr(bundled, "PROFILE_FOLDER", os.path.join(ROOT, "caps_profiles"))
    # a card named by its file, and the store off: nothing is kept
    assert _name(_job(path, profiles=(os.path.join(ROOT, "caps_profiles", "tnt2.yaml"),))) is None
    disk_store.disable()
    assert _name(_job(path)) is None


def test_rows_that_cannot_be_found_again_exactly_are_not_kept(tmp_path, store, monkeypatch):
    # kept: a settled file that includes nothing
    plain = _copy(tmp_path)
    row = matrix_job(_job(plain))
    assert isinstance(row, dict) and matrix_store.stored_row(_job(plain)) == row
    assert _rows(store) == 1
    # a file written just now
    fresh = str(tmp_path / "fresh.fx")
    shutil.copyfile(PHONG, fresh)
    assert isinstance(matrix_job(_job(fresh)), dict) and matrix_store.stored_row(_job(fresh)) is None
    # a load that read an #include
    (tmp_path / "common.fxh").write_text("float4 Tint = {1, 1, 1, 1};\n")
    including = str(tmp_path / "including.fx")
    with open(including, "w") as f:
        f.write('#include "common.fxh"\n' + open(PHONG).read())
    _settle(including, str(tmp_path / "common.fxh"))
    assert isinstance(matrix_job(_job(including)), dict)
    assert matrix_store.stored_row(_job(including)) is None
    # a load that failed
    broken = str(tmp_path / "broken.fx")
    with open(broken, "w") as f:
        f.write("technique T { pass P { ColorOp[0] = ; } }\n")
    _settle(broken)
    assert not isinstance(matrix_job(_job(broken)), dict)
    assert matrix_store.stored_row(_job(broken)) is None
    # a file written while its row was made
    changing = _copy(tmp_path, "changing.fx")
    job = _job(changing)
    found = matrix_store.inputs(job)
    with open(changing, "a") as f:
        f.write("// saved meanwhile\n")
    _settle(changing)
    from effects.frontend.loader import load_effect
    matrix_store.keep(job, found, load_effect(changing), row)
    assert matrix_store.stored_row(_job(changing)) is None
    # a card's file written while the row was made
    cards = tmp_path / "cards"
    shutil.copytree(bundled.PROFILE_FOLDER, cards)
    _settle(*glob.glob(str(cards / "*.yaml")))
    monkeypatch.setattr(bundled, "PROFILE_FOLDER", str(cards))
    job = _job(plain)
    found = matrix_store.inputs(job)
    (cards / "tnt2.yaml").write_text((cards / "tnt2.yaml").read_text() + "# saved meanwhile\n")
    _settle(str(cards / "tnt2.yaml"))
    matrix_store.keep(job, found, load_effect(plain), row)
    assert matrix_store.stored_row(job) is None
    assert _rows(store) == 1


def test_a_bad_entry_is_a_miss_and_removed(tmp_path, store):
    path = _copy(tmp_path)
    job = _job(path)
    row = matrix_job(job)
    name = _name(job)
    entry = store / f"{name}.json"
    good = entry.read_bytes()
    data = json.loads(good)
    cell = next(iter(data["row"].values()))
    bad_cells = [{**cell, "passes": "2"}, {**cell, "technique": 3}, {"technique": None},
                 {**cell, "rejected": {"T": ["ok", 4]}}, {**cell, "rejected": ["T"]},
                 {**cell, "extra": 1}]
    for bad in [b"", b"{", json.dumps({**data, "row": []}).encode(),
                json.dumps({**data, "row": {}}).encode(), json.dumps({"entry": name}).encode(),
                *(json.dumps({**data, "row": {"tnt2": c}}).encode() for c in bad_cells)]:
        entry.write_bytes(bad)
        assert matrix_store.stored_row(job) is None, bad
        assert not entry.exists()
    entry.write_bytes(good)
    assert matrix_store.stored_row(job) == row


def test_the_command_reports_errors_after_kept_rows(tmp_path, capsys, monkeypatch):
    """A kept row does not hide the error of a file that fails, nor a bad card or policy."""
    monkeypatch.setenv("EFFECTS_CACHE_DIR", str(tmp_path / "store"))
    path = _copy(tmp_path)
    assert main(["matrix", path, "--json"]) == 0
    capsys.readouterr()
    broken = str(tmp_path / "broken.fx")
    with open(broken, "w") as f:
        f.write("\ntechnique T { pass P { ColorOp[0] = ; } }\n")
    assert main(["matrix", path, broken]) == 2
    assert f"{broken}:2:" in capsys.readouterr().err.replace("\n", "")
    assert main(["matrix", path, "--policy", "fastest"]) == 2
    assert "fastest" in capsys.readouterr().err
    assert main(["matrix", path, "-p", "nosuchcard"]) == 2
    assert "nosuchcard" in capsys.readouterr().err
