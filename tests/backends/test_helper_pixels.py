"""Helper pixels run only what derivatives read (`evaluate(..., keep=)`): the kept rows' outputs
and kill mask equal those of running every row and taking the kept ones, bit for bit; texture
reads take their LOD from whole quads and read texels for the kept rows only; a frame drawn
this way equals one drawn with every helper pixel shaded in full."""
import numpy as np
import pytest

import backends.reference.evaluate as evaluate_module
from backends.reference.evaluate import evaluate
from backends.reference.renderer import _make_callback
from backends.reference.sampler import SamplerSettings, sample_2d, sample_cube
from effects.program.ir import Builder

MIPMAPPED = SamplerSettings(min_filter="LINEAR", mag_filter="LINEAR", mip_filter="LINEAR",
                            address_u="WRAP", address_v="MIRROR")


def _pyramid(size: int, seed: int) -> list[np.ndarray]:
    rng = np.random.default_rng(seed)
    levels = []
    while size >= 1:
        levels.append(rng.random((size, size, 4), dtype=np.float32))
        size //= 2
    return levels


def _quads(count: int, seed: int) -> tuple[dict, np.ndarray]:
    """Varyings over `count` quads whose texture coordinates change at quad scale (so the LOD
    differs quad to quad), and the kept rows: the covered pixels of a ragged edge."""
    rng = np.random.default_rng(seed)
    rows = count * 4
    base = np.repeat(rng.random((count, 4), dtype=np.float32) * 4, 4, axis=0)
    step = np.repeat(rng.random((count, 1), dtype=np.float32) ** 3 * 0.5, 4, axis=0)
    pixel = np.tile(np.array([[0, 0], [1, 0], [0, 1], [1, 1]], np.float32), (count, 1))
    uv = base.copy()
    uv[:, :2] += pixel * step
    inputs = {"texcoord0": uv,
              "texcoord1": rng.standard_normal((rows, 4)).astype(np.float32),
              "color0": rng.random((rows, 4), dtype=np.float32),
              "Light": np.array([0.6, 0.0, 0.8, 0.0], np.float32)}
    covered = rng.random(rows) < 0.45
    covered.reshape(-1, 4)[:, 0] |= ~covered.reshape(-1, 4).any(axis=1)   # >= 1 per quad
    return inputs, np.nonzero(covered)[0]


def _program():
    """A dependent read (the first texel moves the second read), a ddx, lighting that no
    derivative reads, and a kill."""
    b = Builder("fragment")
    uv = b.varying("texcoord0")
    normal = b.varying("texcoord1")
    diffuse = b.varying("color0")
    light = b.uniform("Light")
    first = b.sample(0, uv)
    moved = b.mad(first, b.const(0.25), uv)
    second = b.sample(1, moved)
    slope = b.emit("ddx", uv)
    lit = b.mul(b.saturate(b.dp3(b.nrm(normal), light)), diffuse)
    colour = b.mad(second, lit, b.mul(slope, b.const(0.5)))
    b.kill(b.add(lit, b.const(-0.2)), "x")
    b.output("color0", colour)
    b.output("color1", first)
    return b.build()


class _Recording:
    """A sampler callback that notes the rows of coordinates and `rows=` it was called with."""

    def __init__(self, callback) -> None:
        self.callback, self.calls = callback, []

    def __call__(self, coord, **kwargs):
        self.calls.append((len(coord), kwargs.get("rows")))
        return self.callback(coord, **kwargs)


def test_kept_rows_equal_every_row_then_taken():
    program = _program()
    inputs, keep = _quads(300, seed=1)
    samplers = {i: _Recording(_make_callback("2d", _pyramid(64, i), MIPMAPPED)) for i in (0, 1)}
    whole = evaluate(program, inputs, samplers, quads=True)
    for recorder in samplers.values():
        assert recorder.calls == [(1200, None)]
        recorder.calls.clear()
    kept = evaluate(program, inputs, samplers, quads=True, keep=keep)
    for name in ("color0", "color1"):
        assert kept.outputs[name].shape == (len(keep), 4)
        assert kept.outputs[name].tobytes() == whole.outputs[name][keep].tobytes()
    assert np.array_equal(kept.killed, whole.killed[keep]) and kept.killed.any()
    # the first read moves the second, so it runs over every row; the second reads texels
    # for the kept rows only, its LOD from every row's quad
    assert samplers[0].calls == [(1200, None)]
    assert len(samplers[1].calls) == 1
    count, rows = samplers[1].calls[0]
    assert count == 1200 and np.array_equal(rows, keep)


def test_only_what_derivatives_read_runs_over_every_row():
    program = _program()
    steps = evaluate_module._steps(program, frozenset())
    split = evaluate_module._split(program, steps, frozenset())
    op_of = {instr.dest: instr.op for instr in program.instrs if instr.dest is not None}
    every_ops = sorted(op_of[s[1]] for s in split.every if s[1] is not None)
    kept_ops = sorted(op_of[s[1]] for s in split.kept if s[1] is not None)
    # over every row: the coordinate, the first read, what moves the second read, the ddx
    assert every_ops == sorted(["input", "sample", "const", "mad", "ddx"])
    assert {"dp3", "nrm", "saturate", "input"} <= set(kept_ops) and "ddx" not in kept_ops
    # the second read is the one texel read for the kept rows
    assert [s[0] for s in split.kept if op_of.get(s[1]) == "sample"] == [evaluate_module._SPLIT]


def test_a_program_whose_every_step_feeds_a_derivative_runs_whole():
    b = Builder("fragment")
    b.output("color0", b.sample(0, b.varying("texcoord0")))
    program = b.build()
    inputs, keep = _quads(50, seed=2)
    callback = _make_callback("2d", _pyramid(32, 3), MIPMAPPED)
    whole = evaluate(program, inputs, {0: callback}, quads=True).outputs["color0"]
    kept = evaluate(program, inputs, {0: callback}, quads=True, keep=keep).outputs["color0"]
    assert kept.tobytes() == whole[keep].tobytes()


@pytest.mark.parametrize("settings", [
    MIPMAPPED,
    SamplerSettings(min_filter="POINT", mag_filter="LINEAR", mip_filter="POINT"),
    SamplerSettings(min_filter="LINEAR", mag_filter="LINEAR", mip_filter="NONE"),
])
def test_sampling_the_kept_rows_equals_sampling_every_row(settings):
    inputs, keep = _quads(200, seed=4)
    uv = inputs["texcoord0"]
    levels = _pyramid(64, 5)
    whole = sample_2d(levels, uv, settings)
    assert sample_2d(levels, uv, settings, rows=keep).tobytes() == whole[keep].tobytes()
    bias = inputs["texcoord1"][:, 3]
    whole = sample_2d(levels, uv, settings, bias=bias)
    assert (sample_2d(levels, uv, settings, bias=bias, rows=keep).tobytes()
            == whole[keep].tobytes())


def test_cube_reads_of_the_kept_rows_equal_every_row():
    inputs, keep = _quads(200, seed=6)
    direction = inputs["texcoord1"][:, :3] + inputs["texcoord0"][:, :3] * 0.05
    levels = [np.stack([lvl] * 6) for lvl in _pyramid(32, 7)]
    whole = sample_cube(levels, direction, MIPMAPPED)
    assert sample_cube(levels, direction, MIPMAPPED, rows=keep).tobytes() == whole[keep].tobytes()


def test_a_frame_with_helpers_cut_equals_one_with_every_helper_shaded(monkeypatch):
    import effects
    from effects.program.backend import create_backend
    from effects.d3d9.caps import load_profile
    from effects.host.runtime import Runtime

    def frame():
        evaluate_module._SPLIT_CACHE.clear()
        runtime = Runtime(effects.load_effect("fxfiles/phong.fx"), load_profile("radeon9700"),
                          size=(64, 64), backend=create_backend("numpy", threads=1))
        return runtime.render().image

    cut = frame()
    calls = []
    real = evaluate_module.evaluate

    def counting(program, inputs, samplers=None, **kwargs):
        calls.append(kwargs.get("keep") is not None)
        return real(program, inputs, samplers, **kwargs)

    with monkeypatch.context() as patched:
        patched.setattr("backends.reference.renderer.evaluate", counting)
        assert np.array_equal(frame(), cut)
        assert any(calls)          # the pass's fragments came with kept rows
        patched.setattr(evaluate_module, "_split", lambda *args: None)
        whole = frame()            # every helper pixel shaded in full, then the kept taken
    assert cut.mean() > 20 and np.array_equal(cut, whole)
