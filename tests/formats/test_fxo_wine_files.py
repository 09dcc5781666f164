"""The fx_2_0 effect binaries cut from Wine's d3dx9_36 tests (tests/data/fxo/MANIFEST.md): every
file there is in the manifest, each byte for byte what the manifest's sha256 says, each .fxo an
fx_2_0 binary of the size listed, each source beside its binary. (Loading them waits for the
effect-binary reader: pending/test_fxo_wine.py.)"""
from __future__ import annotations

import hashlib
import re

from tests.paths import TESTS

DATA = TESTS / "data" / "fxo"
FX_2_0 = 0xFEFF0901        # the version word fxc /Tfx_2_0 writes first (Wine's effect.c)


def _rows() -> dict[str, list[str]]:
    """The manifest's table rows by file: their cells."""
    rows = {}
    for line in (DATA / "MANIFEST.md").read_text().splitlines():
        m = re.match(r"\| `(wine/[^`]+)` \|", line)
        if m:
            rows[m.group(1)] = [c.strip() for c in line.strip("|").split("|")]
    return rows


def test_every_file_is_in_the_manifest():
    rows = _rows()
    manifest = (DATA / "MANIFEST.md").read_text()
    files = sorted(p for p in (DATA / "wine").iterdir())
    assert len([p for p in files if p.suffix == ".fxo"]) == 15
    for path in files:
        name = path.relative_to(DATA).as_posix()
        assert name in rows or f"`{name}`" in manifest, name


def test_every_fxo_and_its_source_match_their_sha256():
    assert sum(name.endswith(".fxo") for name in _rows()) == 15
    for name, cells in _rows().items():
        if not name.endswith(".fxo"):
            continue
        data = (DATA / name).read_bytes()
        assert int(cells[2]) == len(data), name
        assert f"`{hashlib.sha256(data).hexdigest()}`" == cells[3], name
        assert int.from_bytes(data[:4], "little") == FX_2_0 and len(data) % 4 == 0, name
        source = re.findall(r"`(wine/[^`]+\.fx)` `([0-9a-f]{64})`", cells[4])
        if source:
            (fx, sha), = source
            assert fx == name[:-1] and hashlib.sha256((DATA / fx).read_bytes()).hexdigest() == sha
        else:
            assert not (DATA / name[:-1]).exists(), name


def test_the_licence_is_beside_them():
    text = (DATA / "wine" / "COPYING.LIB").read_text()
    assert "GNU LESSER GENERAL PUBLIC LICENSE" in text and "Version 2.1" in text
