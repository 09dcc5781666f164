"""Batch work: run_jobs in-process, on a process pool and on a Dask LocalCluster give the same
results in job order; the contact sheet's cells are the pictures `effects.render` draws, or the
reason a card draws none; `effects matrix --render` writes it."""
from __future__ import annotations

from tests.paths import ROOT

import os

import numpy as np
import pytest
from PIL import Image

import effects
from effects.cli.main import main
from effects.cli.sheet import compose, sheet_jobs
from effects.host.batch import CellJob, render_cell, run_jobs

ROOT = str(ROOT)
PHONG = os.path.join(ROOT, "fxfiles", "phong.fx")
WOOD = os.path.join(ROOT, "fxfiles", "wood.fx")      # HLSL ps_2_0 only: a DX9 card draws it
CARDS = ["tnt2", "geforce3", "radeon9700"]


def _square(x: int) -> int:   # module level: a process pool pickles it by name
    return x * x


def _blas_threads(_: int) -> list[int]:
    from threadpoolctl import threadpool_info
    return [pool["num_threads"] for pool in threadpool_info() if pool["user_api"] == "blas"]


def _dask():
    if os.environ.get("CI"):
        import distributed   # the test extra installs it: CI must test it
    else:
        distributed = pytest.importorskip(
            "distributed", reason="Dask distributed is in the test extra: pip install -e '.[test]'")
    return distributed


def test_run_jobs_keeps_job_order_on_every_engine():
    seen = []
    assert run_jobs(_square, range(7), jobs=1, progress=lambda d, t: seen.append((d, t))) == \
        [x * x for x in range(7)]
    assert seen == [(n, 7) for n in range(1, 8)]
    assert run_jobs(_square, range(7), jobs=2) == [x * x for x in range(7)]
    with pytest.raises(ValueError):
        run_jobs(_square, [1], jobs=0)


def test_pool_workers_share_the_cores_blas_threads():
    # a worker per core, each with a BLAS thread per core, oversubscribes the machine
    from effects.host.batch import default_jobs
    here = _blas_threads(0)
    if not here:
        pytest.skip("NumPy here links no BLAS that threadpoolctl knows")
    for workers in (2, 3):
        share = max(1, default_jobs() // workers)
        assert run_jobs(_blas_threads, range(workers * 2), jobs=workers) == \
            [[share] * len(here)] * (workers * 2)
    assert _blas_threads(0) == here          # this process keeps its own


def test_a_cell_is_the_render_or_the_reason():
    cell = render_cell(CellJob(PHONG, "radeon9700", (24, 16)))
    expected = effects.render(effects.load_effect(PHONG), "radeon9700", size=(24, 16))
    assert cell.technique == "PerPixelPhong_ps20" and cell.reason is None
    np.testing.assert_array_equal(cell.image, expected)
    none = render_cell(CellJob(WOOD, "tnt2", (24, 16)))
    assert none.image is None and none.technique is None
    assert "PixelShader" in none.reason


def test_process_pool_and_dask_draw_the_same_cells():
    distributed = _dask()
    jobs = sheet_jobs([PHONG, WOOD], CARDS, (16, 16))
    alone = run_jobs(render_cell, jobs, jobs=1)
    pooled = run_jobs(render_cell, jobs, jobs=2)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        on_dask = run_jobs(render_cell, jobs, scheduler=client)
        by_address = run_jobs(render_cell, jobs[:2], scheduler=cluster.scheduler_address)
    for other in (pooled, on_dask, by_address):
        for a, b in zip(alone, other):
            assert (a.effect, a.profile, a.technique, a.reason) == (b.effect, b.profile, b.technique, b.reason)
            if a.image is not None:
                np.testing.assert_array_equal(a.image, b.image)
    # phong.fx on all three cards, wood.fx's HLSL Wood_ps20 on the Radeon 9700 only
    drawn = [(c.effect, c.profile) for c in alone if c.image is not None]
    assert len(drawn) == 4 and sum(c.reason is not None for c in alone) == 2, drawn


def test_the_sheet_hands_out_one_effect_a_job(tmp_path, monkeypatch):
    """Each job is one effect's row, cards in order (a worker then pays an effect's first-cell
    costs once); render_row draws what render_cell draws, cell by cell."""
    import effects.cli.sheet as sheet
    handed = []
    real = sheet.run_jobs
    monkeypatch.setattr(sheet, "run_jobs", lambda fn, items, **k: handed.append(list(items)) or real(fn, items, **k))
    cells = sheet.render_sheet([PHONG, WOOD], CARDS, str(tmp_path / "s.png"), size=(12, 10),
                               jobs=1, progress=False)
    assert [[(j.effect, j.profile) for j in row] for row in handed[0]] == \
        [[(f, c) for c in CARDS] for f in (PHONG, WOOD)]
    alone = [render_cell(j) for j in sheet_jobs([PHONG, WOOD], CARDS, (12, 10))]
    for a, b in zip(alone, cells):
        assert (a.effect, a.profile, a.technique, a.reason) == (b.effect, b.profile, b.technique, b.reason)
        if a.image is not None:
            np.testing.assert_array_equal(a.image, b.image)
    assert len(cells) == len(alone) == 2 * len(CARDS)


def test_sheet_layout_places_each_cell_under_its_card():
    cells = run_jobs(render_cell, sheet_jobs([PHONG, WOOD], CARDS, (20, 18)), jobs=1)
    sheet = np.asarray(compose(cells, [PHONG, WOOD], CARDS, (20, 18)))
    assert sheet.shape == (14 + 2 * (18 + 14), 120 + 3 * 20, 3)
    top = 14
    picture = sheet[top:top + 18, 120 + 2 * 20:120 + 3 * 20]      # phong on the radeon9700
    np.testing.assert_array_equal(picture, cells[2].image[..., :3])


def test_matrix_render_writes_the_sheet(tmp_path, capsys):
    out = tmp_path / "sheet.png"
    code = main(["matrix", PHONG, WOOD, "-p", "tnt2", "-p", "radeon9700", "--render", str(out),
                 "--size", "24x20", "--jobs", "1"])
    assert code == 0
    assert f"contact sheet: 2 effects x 2 cards -> {out}" in capsys.readouterr().out
    image = np.asarray(Image.open(out))
    assert image.shape == (14 + 2 * (20 + 14), 120 + 2 * 24, 3)
    assert main(["matrix", PHONG, "--render", str(out), "--jobs", "0"]) == 2
    assert main(["matrix", PHONG, "--render", str(out), "--size", "0x9"]) == 2


def test_meanwhile_runs_once_after_the_jobs_are_handed_out():
    for jobs in (1, 2):
        calls = []
        done = []
        out = run_jobs(_square, range(5), jobs=jobs, meanwhile=lambda: calls.append(len(done)),
                       progress=lambda d, t: done.append(d))
        assert out == [x * x for x in range(5)]
        assert calls == [0], (jobs, calls)     # once, before any result was taken


FXFILES = sorted(os.path.join(ROOT, "fxfiles", f) for f in os.listdir(os.path.join(ROOT, "fxfiles"))
                 if f.endswith(".fx"))


def test_matrix_jobs_on_a_pool_are_the_serial_matrix():
    from effects.d3d9.caps import list_profiles, load_profile
    from effects.cli.matrix_store import MatrixJob
    from effects.cli.report import matrix, matrix_job
    serial = matrix({f: effects.load_effect(f) for f in FXFILES},
                    [load_profile(p) for p in list_profiles()])
    pooled = run_jobs(matrix_job, [MatrixJob(f, ()) for f in FXFILES], jobs=2)
    assert dict(zip(FXFILES, pooled)) == serial
    # each file's rows name a technique or none on every card, with every rejection's reasons
    assert sum(cell["technique"] is not None for rows in pooled for cell in rows.values()) > 100


def _broken(tmp_path, name: str, line: int) -> str:
    path = tmp_path / name
    path.write_text("float4 Tint = {1, 1, 1, 1};\n" * (line - 1) + "technique T { pass P { ColorOp[0] = ; } }\n")
    return str(path)


@pytest.mark.parametrize("threads", [False, True])
def test_matrix_command_reports_the_first_bad_file_in_order(tmp_path, capsys, monkeypatch, threads):
    """Workers or not (a process with other threads running validates in place), the error is
    the one the serial command reports: the first failing file in the order given. (The rows
    earlier commands kept are off: each command here loads and validates every file.)"""
    import threading
    import effects.host.batch as batch
    monkeypatch.setenv("EFFECTS_CACHE", "off")
    used = []
    real = batch.run_jobs
    monkeypatch.setattr(batch, "run_jobs", lambda *a, **k: used.append(k["jobs"]) or real(*a, **k))
    if not threads:
        monkeypatch.setattr(threading, "active_count", lambda: 1)
    stop = threading.Event()
    other = threading.Thread(target=stop.wait)
    other.start()
    try:
        bad = [_broken(tmp_path, "b1.fx", 3), _broken(tmp_path, "b2.fx", 1)]
        assert main(["matrix", PHONG, *bad, "--jobs", "2"]) == 2
        err = capsys.readouterr().err
        assert f"{bad[0]}:3:" in err.replace("\n", "") and "b2.fx" not in err
        assert main(["matrix", PHONG, WOOD, "--jobs", "2", "--json"]) == 0
        pooled = capsys.readouterr().out
    finally:
        stop.set()
        other.join()
    assert used == ([] if threads else [2, 2])
    assert main(["matrix", PHONG, WOOD, "--jobs", "1", "--json"]) == 0
    assert capsys.readouterr().out == pooled


def test_sheet_labels_are_cut_only_where_they_do_not_fit():
    """Names are measured in the font the sheet draws with: whole where they fit, else cut
    with ".." to fit (a count of 6-pixel characters cut geforcefx5900 at 64 px, with room)."""
    from PIL import Image, ImageDraw

    from effects.d3d9.caps import list_profiles
    from effects.cli.sheet import _fit
    draw = ImageDraw.Draw(Image.new("RGB", (8, 8)))
    for name in list_profiles() + ["PerPixelPhong_ps20", "a" * 60]:
        room = draw.textlength(name)
        assert _fit(draw, name, int(room) + 1) == name
        for width in (61, 45, 20):
            cut = _fit(draw, name, width)
            assert cut == name or (cut.endswith("..") and name.startswith(cut[:-2]))
            assert draw.textlength(cut) <= width or len(cut) == 3, (name, width, cut)
