"""Effects inside XNA's containers (effects/frontend/xnb.py): an .xnb file of XNA 4.0 (whose
effect bytes lead with the 0xBCF00BCF header) or XNA 3.1 (the fx_2_0 binary itself), and XNA
4.0's bare effect bytes, load as the fx_2_0 binary they hold; what cannot be read is a located
error at the file's byte. The containers are built here from the public layout (the XNB
format document's header, type readers and 7-bit counts), around our own compiled effects."""
from __future__ import annotations

import random
import struct

import pytest

import effects
from effects.base.errors import EffectError
from effects.d3d9.caps import load_profile
from effects.shaders.fxo import write_effect_binary
from effects.validate.select import find_valid_technique
from tests.paths import ROOT

READER4 = ("Microsoft.Xna.Framework.Content.EffectReader, Microsoft.Xna.Framework.Graphics, "
           "Version=4.0.0.0, Culture=neutral, PublicKeyToken=842cf8be1de50553")
READER31 = ("Microsoft.Xna.Framework.Content.EffectReader, Microsoft.Xna.Framework, "
            "Version=3.1.0.0, Culture=neutral, PublicKeyToken=6d5c3888ef60e27d")
CARDS = ["geforce3", "radeon9700", "tnt2"]


def _7bit(n: int) -> bytes:
    out = b""
    while True:
        low, n = n & 0x7F, n >> 7
        out += bytes([low | (0x80 if n else 0)])
        if not n:
            return out


def _string(text: str) -> bytes:
    raw = text.encode()
    return _7bit(len(raw)) + raw


def xna4_effect(blob: bytes, junk: int = 12) -> bytes:
    """XNA 4.0's effect bytes: the tag, the fx_2_0 binary's offset from it, `junk` bytes."""
    return struct.pack("<II", 0xBCF00BCF, 8 + junk) + b"\xAB" * junk + blob


def xnb(effect_bytes: bytes, *, version: int = 5, flags: int = 0,
        readers: tuple[str, ...] = (READER4,), asset: int = 1) -> bytes:
    body = _7bit(len(readers)) + b"".join(_string(r) + struct.pack("<i", 0) for r in readers)
    body += _7bit(0) + _7bit(asset) + struct.pack("<I", len(effect_bytes)) + effect_bytes
    return b"XNBw" + bytes([version, flags]) + struct.pack("<I", 10 + len(body)) + body


@pytest.fixture(scope="module")
def phong():
    source = effects.load_effect(str(ROOT / "fxfiles" / "phong.fx"))
    return source, write_effect_binary(source)


def _picks(effect) -> list[str | None]:
    out = []
    for card in CARDS:
        found = find_valid_technique(effect, load_profile(card))
        out.append(found.name if found is not None else None)
    return out


@pytest.mark.parametrize("wrap", [
    lambda b: xnb(xna4_effect(b)),                                  # XNA 4.0 .xnb
    lambda b: xnb(b, version=4, readers=(READER31,)),               # XNA 3.1 .xnb
    lambda b: xnb(xna4_effect(b, junk=0), readers=("Other.Reader", READER4), asset=2),
    lambda b: xna4_effect(b),                                       # XNA 4.0 effect bytes alone
], ids=["xnb4", "xnb31", "second-reader", "xna4-bytes"])
def test_a_wrapped_effect_loads_as_the_binary_it_holds(wrap, phong, tmp_path):
    source, blob = phong
    path = tmp_path / "phong.xnb"
    path.write_bytes(wrap(blob))
    for loaded in (effects.load_effect(str(path)), effects.load_effect(wrap(blob))):
        assert [t.name for t in loaded.techniques] == [t.name for t in source.techniques]
        assert [p.name for p in loaded.parameters] == [p.name for p in source.parameters]
        assert _picks(loaded) == _picks(source)


@pytest.mark.parametrize("change, words, column", [
    (lambda d: d[:7], "header is cut short", 8),
    (lambda d: d[:5] + b"\x80" + d[6:], "LZX-compressed, which is not read", 6),
    (lambda d: d[:4] + b"\x03" + d[5:], "format version 3", 5),
    (lambda d: d[:6] + struct.pack("<I", len(d) + 1) + d[10:], "the file has", 7),
], ids=["short", "lzx", "version", "size"])
def test_a_container_that_cannot_be_read_is_located(change, words, column, phong, tmp_path):
    data = change(xnb(xna4_effect(phong[1])))
    with pytest.raises(EffectError, match=words) as err:
        effects.load_effect(data)
    assert err.value.location.column == column


def test_an_asset_that_is_no_effect_names_its_reader(phong):
    data = xnb(xna4_effect(phong[1]), readers=(
        "Microsoft.Xna.Framework.Content.Texture2DReader, Microsoft.Xna.Framework.Graphics",))
    with pytest.raises(EffectError, match="holds a Microsoft.Xna.Framework.Content."
                                          "Texture2DReader asset, not an effect"):
        effects.load_effect(data)


def test_monogame_and_a_bad_xna4_offset_are_said(phong):
    with pytest.raises(EffectError, match="MonoGame's MGFX effect"):
        effects.load_effect(xnb(b"MGFX" + b"\0" * 16))
    bad = struct.pack("<II", 0xBCF00BCF, 1 << 20) + phong[1]
    with pytest.raises(EffectError, match="outside the") as err:
        effects.load_effect(bad)
    assert err.value.location.column == 5


def test_an_error_inside_the_effect_is_at_the_files_byte(phong):
    """The fx_2_0 reader's errors count from the file's first byte, not the effect's."""
    blob = phong[1]
    cut = blob[:len(blob) // 2]
    with pytest.raises(EffectError) as bare:
        effects.load_effect(cut)
    wrapped = xnb(xna4_effect(cut))
    start = len(wrapped) - len(cut)
    with pytest.raises(EffectError) as inside:
        effects.load_effect(wrapped)
    assert inside.value.location.column == bare.value.location.column + start
    assert f"(at byte {bare.value.location.column - 1 + start})" in str(inside.value)


def test_mutated_containers_give_located_errors_or_load(phong):
    data = bytearray(xnb(xna4_effect(phong[1])))
    rng = random.Random(7)
    head = 10 + 1 + len(_string(READER4)) + 4 + 1 + 1 + 4 + 8 + 12 + 16   # the wrapping
    for _ in range(200):
        mutated = bytearray(data)
        for _ in range(rng.randint(1, 3)):
            mutated[rng.randrange(head)] = rng.randrange(256)
        try:
            effects.load_effect(bytes(mutated))
        except EffectError as err:
            assert err.location is not None and err.location.column >= 1


def test_the_command_line_reads_and_lists_an_xnb(phong, tmp_path, capsys):
    from effects.cli.main import main
    path = tmp_path / "phong.xnb"
    path.write_bytes(xnb(xna4_effect(phong[1])))
    assert main(["compile", "--disassemble", str(path)]) == 0
    listed = capsys.readouterr().out
    assert "technique PerPixelPhong_ps20" in listed or "PerPixelPhong_ps20" in listed
    assert main(["validate", str(path), "-p", "geforce3"]) == 0
    assert "PerPixelPhong_ps11" in capsys.readouterr().out
