"""Batch work: run_jobs in-process, on a process pool and on a Dask LocalCluster give the same
results in job order; the contact sheet's cells are the pictures `effects.render` draws, or the
reason a card draws none; `effects matrix --render` writes it."""
from __future__ import annotations

import os

import numpy as np
import pytest
from PIL import Image

import effects
from effects.cli.main import main
from effects.cli.sheet import compose, sheet_jobs
from effects.host.batch import CellJob, render_cell, run_jobs

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PHONG = os.path.join(ROOT, "fxfiles", "phong.fx")
WOOD = os.path.join(ROOT, "fxfiles", "wood.fx")      # HLSL ps_2_0 only: a DX9 card draws it
CARDS = ["tnt2", "geforce3", "radeon9700"]


def _square(x: int) -> int:   # module level: a process pool pickles it by name
    return x * x


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
