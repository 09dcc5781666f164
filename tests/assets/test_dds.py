"""The .dds reader/writer and the texel codec: hand-built bytes decoded by the rules of
docs/reference/semantics.md §1.7, DXT blocks built by hand, and round trips of every
uncompressed format."""
import struct

import numpy as np
import pytest

from effects.assets import dds
from effects.program import formats as pf
from effects.program.texels import unpack
from effects.base.errors import SceneError
from effects.assets.textures import encode, mip_chain
from effects.program.texture import Texture


def decode_words(fmt: str, words, nbytes: int) -> np.ndarray:
    raw = b"".join(int(w).to_bytes(nbytes, "little") for w in words)
    return unpack(np.frombuffer(raw, np.uint8), pf.pixel_format(fmt), (1, len(words)))[0]


# ---- signed formats, by hand ----------------------------------------------------------------

def test_v8u8_byte_patterns():
    # U in the low byte, V in the high byte; 0x7f -> 1, 0x81 (-127) -> -1, 0x80 (-128) clamps to -1
    got = decode_words("V8U8", [0x817F, 0x0080, 0x4000], 2)
    assert got[0].tolist() == [1.0, -1.0, 1.0, 1.0]
    assert got[1].tolist() == [-1.0, 0.0, 1.0, 1.0]
    assert got[2, 1] == pytest.approx(64 / 127)
    assert got[2, 0] == 0.0


def test_l6v5u5_asymmetric_five_bit_rule():
    def word(u, v, l):
        return (u & 31) | ((v & 31) << 5) | (l << 10)
    got = decode_words("L6V5U5", [word(15, -16, 63), word(-15, 1, 0), word(0, -1, 21)], 2)
    assert got[0].tolist() == pytest.approx([1.0, -1.0, 1.0, 1.0])
    assert got[1].tolist() == pytest.approx([-15 / 16, 1 / 15, 0.0, 1.0])   # -15 -> -0.9375
    assert got[2].tolist() == pytest.approx([0.0, -1 / 16, 21 / 63, 1.0])


def test_x8l8v8u8_and_q8w8v8u8():
    got = decode_words("X8L8V8U8", [0x12FFC040], 4)[0]   # X=0x12 ignored, L=0xff, V=0xc0, U=0x40
    assert got.tolist() == pytest.approx([64 / 127, -64 / 127, 1.0, 1.0])
    got = decode_words("Q8W8V8U8", [0x8000817F], 4)[0]   # Q=0x80, W=0x00, V=0x81, U=0x7f
    assert got.tolist() == pytest.approx([1.0, -1.0, 0.0, -1.0])


def test_v16u16():
    got = decode_words("V16U16", [0x80017FFF, 0x80004000], 4)
    assert got[0].tolist() == pytest.approx([1.0, -1.0, 1.0, 1.0])
    assert got[1].tolist() == pytest.approx([16384 / 32767, -1.0, 1.0, 1.0])


def test_missing_channels_of_unsigned_and_float_formats():
    assert decode_words("X8R8G8B8", [0x00FF8000], 4)[0].tolist() == pytest.approx([1, 128 / 255, 0, 1])
    assert decode_words("R5G6B5", [0xF800, 0x07E0], 2).tolist() == [[1, 0, 0, 1], [0, 1, 0, 1]]
    assert decode_words("A1R5G5B5", [0x801F, 0x7C00], 2).tolist() == [[0, 0, 1, 1], [1, 0, 0, 0]]
    assert decode_words("L8", [0x33], 1)[0].tolist() == pytest.approx([0.2, 0.2, 0.2, 1.0])
    assert decode_words("A8", [0x33], 1)[0].tolist() == pytest.approx([0, 0, 0, 0.2])
    assert decode_words("A8L8", [0x3366], 2)[0].tolist() == pytest.approx([0.4, 0.4, 0.4, 0.2])
    r32 = np.frombuffer(struct.pack("<f", -2.5), np.uint8)
    assert unpack(r32, pf.pixel_format("R32F"), (1, 1))[0, 0].tolist() == [-2.5, 1, 1, 1]
    g16r16 = np.frombuffer(np.array([0.5, -3.0], "<f2").tobytes(), np.uint8)
    assert unpack(g16r16, pf.pixel_format("G16R16F"), (1, 1))[0, 0].tolist() == [0.5, -3.0, 1, 1]


def test_encode_is_the_stored_value():
    got = encode(np.array([[1.0, -1.0, 0.3, 0.0], [-0.5, 0.5, 0, 0]]), "V8U8")
    assert got[0].tolist() == pytest.approx([1.0, -1.0, 1.0, 1.0])
    assert got[1, 0] == pytest.approx(-64 / 127) and got[1, 1] == pytest.approx(64 / 127)
    got = encode(np.array([[-1.0, -0.5, 0.5, 0.0]]), "L6V5U5")[0]
    assert got.tolist() == pytest.approx([-1.0, -0.5, 32 / 63, 1.0])   # v: -8/16; L: rint(31.5)=32


# ---- DDS files --------------------------------------------------------------------------------

def dds_bytes(width, height, fourcc: bytes, surfaces: bytes, mips=1, caps2=0, depth=0) -> bytes:
    """A DDS file assembled here from the documented layout (independent of the writer)."""
    flags = 0x1 | 0x2 | 0x4 | 0x1000 | (0x20000 if mips > 1 else 0) | (0x800000 if depth else 0)
    header = struct.pack("<7I", 124, flags, height, width, 0, depth, mips) + b"\0" * 44
    header += struct.pack("<2I4s5I", 32, 0x4, fourcc, 0, 0, 0, 0, 0)
    header += struct.pack("<5I", 0x1000, caps2, 0, 0, 0)
    assert len(header) == 124
    return b"DDS " + header + surfaces


def colour_block(c0: int, c1: int, indices: list[int]) -> bytes:
    bits = sum(i << (2 * k) for k, i in enumerate(indices))
    return struct.pack("<HHI", c0, c1, bits)


def test_dxt1_four_and_three_colour_blocks(tmp_path):
    red, blue = 0xF800, 0x001F
    # Block A (c0 > c1): texels 0..3 pick palette entries 0..3, the rest entry 0.
    block_a = colour_block(red, blue, [0, 1, 2, 3] + [0] * 12)
    # Block B (c0 < c1): 3 colours and transparent black; row 1 picks entries 2 and 3.
    block_b = colour_block(blue, red, [0] * 4 + [2, 3, 2, 3] + [1] * 8)
    path = tmp_path / "a.dds"
    path.write_bytes(dds_bytes(8, 4, b"DXT1", block_a + block_b))
    tex = dds.read_dds(path)
    assert (tex.kind, tex.format, tex.width, tex.height) == ("2d", "DXT1", 8, 4)
    img = tex.levels[0]
    assert img[0, 0].tolist() == [1, 0, 0, 1]
    assert img[0, 1].tolist() == [0, 0, 1, 1]
    assert img[0, 2].tolist() == pytest.approx([2 / 3, 0, 1 / 3, 1])
    assert img[0, 3].tolist() == pytest.approx([1 / 3, 0, 2 / 3, 1])
    assert img[3, 3].tolist() == [1, 0, 0, 1]
    assert img[0, 4].tolist() == [0, 0, 1, 1]                       # block B, texel 0: c0 = blue
    assert img[1, 4].tolist() == pytest.approx([0.5, 0, 0.5, 1])    # midpoint
    assert img[1, 5].tolist() == [0, 0, 0, 0]                       # transparent black
    assert img[2, 7].tolist() == [1, 0, 0, 1]


def test_dxt1_small_mips_are_cropped(tmp_path):
    green = 0x07E0
    level0 = colour_block(green, 0, [0] * 16)
    level1 = colour_block(0xFFFF, 0, [0] * 16)   # a 2x2 level still takes a whole block
    level2 = colour_block(0, 0xFFFF, [1] * 16)   # 1x1
    path = tmp_path / "m.dds"
    path.write_bytes(dds_bytes(4, 4, b"DXT1", level0 + level1 + level2, mips=3))
    tex = dds.read_dds(path)
    assert [lv.shape for lv in tex.levels] == [(4, 4, 4), (2, 2, 4), (1, 1, 4)]
    assert tex.levels[1][1, 1].tolist() == [1, 1, 1, 1]
    assert tex.levels[2][0, 0].tolist() == [1, 1, 1, 1]


def test_dxt3_explicit_alpha(tmp_path):
    alpha = sum(k << (4 * k) for k in range(16)).to_bytes(8, "little")   # texel k has alpha k
    block = alpha + colour_block(0xFFFF, 0x0000, [1] * 16)               # colours: black
    path = tmp_path / "a3.dds"
    path.write_bytes(dds_bytes(4, 4, b"DXT3", block))
    img = dds.read_dds(path).levels[0]
    assert img[..., 3].ravel().tolist() == pytest.approx([k / 15 for k in range(16)])
    assert np.all(img[..., :3] == 0)


def test_dxt5_interpolated_alpha_both_modes(tmp_path):
    def alpha_block(a0, a1, indices):
        bits = sum(i << (3 * k) for k, i in enumerate(indices))
        return bytes([a0, a1]) + bits.to_bytes(6, "little")
    white = colour_block(0xFFFF, 0xFFFF, [0] * 16)
    eight = alpha_block(255, 0, [0, 1, 2, 7] + [0] * 12)      # a0 > a1: 6 interpolants
    six = alpha_block(0, 255, [2, 5, 6, 7] + [0] * 12)        # a0 <= a1: 4 interpolants, 0, 1
    path = tmp_path / "a5.dds"
    path.write_bytes(dds_bytes(8, 4, b"DXT5", eight + white + six + white))
    img = dds.read_dds(path).levels[0]
    assert img[0, :4, 3].tolist() == pytest.approx([1.0, 0.0, 6 / 7, 1 / 7])
    assert img[0, 4:8, 3].tolist() == pytest.approx([0.2, 0.8, 0.0, 1.0])   # (4*0+255)/5, (1*0+4*255)/5
    assert np.all(img[..., :3] == 1.0)


UNCOMPRESSED = [name for name, f in pf.FORMATS.items() if not f.compressed]


def random_values(fmt: str, shape, rng) -> np.ndarray:
    f = pf.pixel_format(fmt)
    lo = -1.0 if f.signed else (-4.0 if f.float_dtype else 0.0)
    hi = 4.0 if f.float_dtype else 1.0
    return rng.uniform(lo, hi, shape + (4,)).astype(np.float32)


@pytest.mark.parametrize("fmt", UNCOMPRESSED)
def test_round_trip_2d_with_mips(tmp_path, fmt):
    rng = np.random.default_rng(1)
    values = random_values(fmt, (4, 8), rng)
    levels = [encode(lv, fmt) for lv in mip_chain(values)]
    path = tmp_path / "t.dds"
    dds.write_dds(path, Texture("2d", fmt, levels))
    back = dds.read_dds(path)
    assert (back.kind, back.format, len(back.levels)) == ("2d", fmt, 4)
    for want, got in zip(levels, back.levels):
        np.testing.assert_array_equal(got, want)


@pytest.mark.parametrize("fmt", UNCOMPRESSED)
def test_round_trip_cube_and_volume_with_mips(tmp_path, fmt):
    rng = np.random.default_rng(2)
    cube = [encode(lv, fmt) for lv in mip_chain(random_values(fmt, (6, 4, 4), rng), kind="cube")]
    vol = [encode(lv, fmt) for lv in mip_chain(random_values(fmt, (4, 2, 8), rng), kind="3d")]
    for kind, levels in (("cube", cube), ("3d", vol)):
        path = tmp_path / f"{kind}.dds"
        dds.write_dds(path, Texture(kind, fmt, levels))
        back = dds.read_dds(path)
        assert back.kind == kind and len(back.levels) == len(levels)
        for want, got in zip(levels, back.levels):
            np.testing.assert_array_equal(got, want)
    assert [lv.shape[:3] for lv in vol] == [(4, 2, 8), (2, 1, 4), (1, 1, 2), (1, 1, 1)]


def test_written_v8u8_header_is_the_bump_dudv_layout(tmp_path):
    path = tmp_path / "b.dds"
    dds.write_dds(path, Texture("2d", "V8U8", [np.zeros((2, 2, 4), np.float32)]))
    data = path.read_bytes()
    flags, fourcc, bits, rmask, gmask = struct.unpack_from("<5I", data, 80)
    assert (flags, fourcc, bits, rmask, gmask) == (0x80000, 0, 16, 0xFF, 0xFF00)
    assert len(data) == 128 + 2 * 2 * 2


def test_float_format_uses_numeric_fourcc(tmp_path):
    path = tmp_path / "f.dds"
    dds.write_dds(path, Texture("2d", "A16B16G16R16F", [np.ones((1, 1, 4), np.float32)]))
    assert struct.unpack_from("<2I", path.read_bytes(), 80) == (0x4, 113)


@pytest.mark.parametrize("data, message", [
    (b"XXXX" + b"\0" * 200, "not a DDS file"),
    (dds_bytes(4, 4, b"DXT1", b"\0" * 4), "truncated"),
    (dds_bytes(4, 4, b"ABCD", b"\0" * 64), "unsupported DDS pixel format"),
])
def test_bad_files_are_located_scene_errors(tmp_path, data, message):
    path = tmp_path / "bad.dds"
    path.write_bytes(data)
    with pytest.raises(SceneError) as info:
        dds.read_dds(path)
    assert message in str(info.value)
    assert (info.value.path, info.value.line, info.value.column) == (str(path), 1, 1)
