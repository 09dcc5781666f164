"""`effects matrix --render SHEET.png`: the contact sheet of effects × cards.

One row per effect, one column per card; each cell is the picture the card draws with the
technique it selects (its name under it, and with fidelity figures its SSIM and PSNR against
the best technique: effects.host.fidelity), or the reason it draws none, as text. The cells
are independent renders, an effect's row of them a job (`effects.host.batch.render_row`), run
by `effects.host.batch.run_jobs` on a process pool (`--jobs`) or
on Dask (`--scheduler`), with a progress bar on stderr.
"""
from __future__ import annotations

import os
import textwrap
from typing import Any, Mapping, Sequence

from effects.base.errors import Location, SceneError
from effects.host.batch import Cell, CellJob, render_row, run_jobs
from effects.host.scene import scene_for

_LABEL_H = 14           # a line of PIL's default bitmap font, with spacing
_HEADER_W = 120         # the effect-name column
_BACKGROUND, _INK, _FAINT = (32, 32, 36), (230, 230, 230), (150, 150, 160)


def sheet_jobs(files: Sequence[str], profiles: Sequence[str], size: tuple[int, int],
               scene: str | None = None, backend: str = "numpy",
               policy: str = "first", scene_beside: bool = True,
               load: Mapping[str, Any] | None = None) -> list[CellJob]:
    """A cell job per (file, card). `load`: CellJob's load options (include_root, defines,
    include_dirs), as the command that asked for the sheet loaded the files."""
    return [CellJob(f, p, size, scene_for(f, scene, beside=scene_beside), backend, policy,
                    **(load or {}))
            for f in files for p in profiles]


def render_sheet(files: Sequence[str], profiles: Sequence[str], out: str, *,
                 size: tuple[int, int] = (96, 96), scene: str | None = None,
                 scene_beside: bool = True, backend: str = "numpy", policy: str = "first", jobs: int | None = None,
                 scheduler: Any = None, progress: bool = True,
                 figures: Mapping[tuple[str, str], Any] | None = None,
                 load: Mapping[str, Any] | None = None) -> list[Cell]:
    """Render every cell, compose the sheet and write it to `out` (PNG); returns the cells.
    A job is one effect's row (`render_row`): cell by cell, both workers of `--jobs 2` drew
    cards of every effect, so each paid every effect's first-cell costs, and the command was
    1.2-1.3x faster than `--jobs 1`, not 2x. `figures`: the matrix's fidelity figure of each
    cell, by (file, card), drawn under its technique's name. `load`: how each file is loaded
    (`sheet_jobs`)."""
    rows = [sheet_jobs([f], profiles, size, scene, backend, policy, scene_beside, load)
            for f in files]
    if progress:
        from rich.console import Console
        from rich.progress import Progress
        with Progress(console=Console(stderr=True), transient=True) as bar:
            task = bar.add_task(f"{len(files)} effects × {len(profiles)} cards",
                                total=len(files) * len(profiles))
            drawn = run_jobs(render_row, rows, jobs=jobs, scheduler=scheduler,
                             progress=lambda done, total: bar.update(
                                 task, completed=done * len(profiles)))
    else:
        drawn = run_jobs(render_row, rows, jobs=jobs, scheduler=scheduler)
    cells = [cell for row in drawn for cell in row]
    image = compose(cells, files, profiles, size, figures)
    try:
        image.save(out)
    except (OSError, ValueError) as exc:
        raise SceneError(f"cannot write the sheet: {exc}", Location(out, 1, 1)) from None
    return cells


def compose(cells: Sequence[Cell], files: Sequence[str], profiles: Sequence[str],
            size: tuple[int, int], figures: Mapping[tuple[str, str], Any] | None = None):
    """The sheet as a PIL image: a header row of card names, then a row per effect; with
    `figures`, a second line under each picture: its fidelity."""
    from PIL import Image, ImageDraw
    w, h = size
    cell_h = h + _LABEL_H * (2 if figures else 1)
    sheet = Image.new("RGB", (_HEADER_W + w * len(profiles), _LABEL_H + cell_h * len(files)),
                      _BACKGROUND)
    draw = ImageDraw.Draw(sheet)
    for c, name in enumerate(profiles):
        draw.text((_HEADER_W + c * w + 2, 1), _fit(draw, os.path.basename(name), w - 3), fill=_INK)
    by_key = {(cell.effect, cell.profile): cell for cell in cells}
    for r, path in enumerate(files):
        top = _LABEL_H + r * cell_h
        draw.text((2, top + h // 2), _fit(draw, os.path.basename(path), _HEADER_W - 3), fill=_INK)
        for c, profile in enumerate(profiles):
            left = _HEADER_W + c * w
            cell = by_key[(path, profile)]
            if cell.image is not None:
                # RGBA render target shown opaque, as `effects render` writes it
                picture = Image.fromarray(cell.image, "RGBA").convert("RGB")
                sheet.paste(picture, (left, top))
                draw.text((left + 2, top + h), _fit(draw, cell.technique or "", w - 3), fill=_FAINT)
                if figures:
                    draw.text((left + 2, top + h + _LABEL_H),
                              _fit(draw, _figure_line(figures.get((path, profile))), w - 3),
                              fill=_INK)
            else:
                _reason(draw, cell.reason or "", left, top, w, cell_h)
    return sheet


def _figure_line(figure: Any) -> str:
    """'0.934 27.4dB' (SSIM, PSNR), '= best', or '-' where nothing was measured."""
    if not figure:
        return "-"
    if figure["psnr"] is None:
        return "= best"
    return f"{figure['ssim']:.3f} {figure['psnr']:.1f}dB"


def _fit(draw, text: str, width: int) -> str:
    """`text` as drawn in `width` pixels: whole, or cut with ".." where it is wider. Measured
    in the font `draw` draws with (Pillow's default is proportional where FreeType is
    there: a count of characters cut "geforcefx5900" to "geforcef.." with room to spare)."""
    text = _latin1(text)
    if draw.textlength(text) <= width:
        return text
    while len(text) > 1 and draw.textlength(text + "..") > width:
        text = text[:-1]
    return text + ".."


def _char_width(draw) -> float:
    """The font's mean width of a letter or digit, in pixels (for wrapping by characters)."""
    sample = "abcdefghijklmnopqrstuvwxyz0123456789"
    return max(1.0, draw.textlength(sample) / len(sample))


def _latin1(text: str) -> str:
    # PIL's default bitmap font draws Latin-1 only
    return text.encode("latin-1", "replace").decode("latin-1")


def _reason(draw, text: str, left: int, top: int, w: int, h: int) -> None:
    """The reason a card draws nothing, wrapped into the cell."""
    chars = max(4, int((w - 4) / _char_width(draw)))
    lines = textwrap.wrap(_latin1(text), chars)[: max(1, (h - 2) // 11)]
    for k, line in enumerate(lines):
        draw.text((left + 2, top + 2 + 11 * k), line, fill=(220, 120, 110))
