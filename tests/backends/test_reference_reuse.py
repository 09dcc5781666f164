"""What the NumPy reference back end keeps from one frame to the next (the last frame's
buffers, a program's evaluation steps, a sampler plan) must never show in a picture: a frame
drawn after a change of parameter, state, technique, size, texture or program by a back end
that has drawn before equals the frame a fresh back end draws."""
import numpy as np
import pytest

import effects
from effects.program.backend import create_backend
from effects.host.runtime import Runtime
from effects.program.ir import Builder
from backends.reference.evaluate import evaluate

PHONG = "fxfiles/phong.fx"


def _fresh(effect, card, size=(64, 64), technique=None, **values):
    runtime = Runtime(effect, card, size=size, backend=create_backend("numpy", threads=1))
    for name, value in values.items():
        runtime.set_value(name, value)
    return runtime.render(technique).image


def test_second_frame_equals_the_first_and_a_fresh_runtimes():
    effect = effects.load_effect(PHONG)
    runtime = Runtime(effect, "radeon9700", size=(64, 64), backend=create_backend("numpy", threads=1))
    first = runtime.render().image
    second = runtime.render().image
    np.testing.assert_array_equal(first, second)
    np.testing.assert_array_equal(second, _fresh(effect, "radeon9700"))
    assert len(np.unique(first.reshape(-1, 4), axis=0)) > 100      # a lit, textured sphere


@pytest.mark.parametrize("name, value", [
    ("LightColor", (1.0, 0.2, 0.1, 1.0)),        # a uniform of the fragment program
    ("LightPosition", (-2.0, 1.0, 3.0, 1.0)),    # a uniform of the vertex program
    ("SpecularPower", 4.0),
])
def test_a_changed_parameter_shows_in_the_next_frame(name, value):
    effect = effects.load_effect(PHONG)
    runtime = Runtime(effect, "radeon9700", size=(64, 64), backend=create_backend("numpy", threads=1))
    before = runtime.render().image
    runtime.set_value(name, value)
    after = runtime.render().image
    assert not np.array_equal(before, after)
    np.testing.assert_array_equal(after, _fresh(effect, "radeon9700", **{name: value}))


def test_one_backend_across_techniques_sizes_and_effects_draws_what_fresh_ones_draw():
    # one back end object (its spare frame buffer, the evaluator's steps, the sampler's last
    # plan all kept) drawing a sequence of different frames, each against a fresh back end
    phong = effects.load_effect(PHONG)
    wood = effects.load_effect("fxfiles/wood.fx")
    backend = create_backend("numpy", threads=1)
    frames = [(phong, "radeon9700", (64, 64), None), (phong, "geforce3", (64, 64), None),
              (phong, "radeon9700", (48, 32), "PerPixelPhong_ps20"),
              (phong, "radeon9700", (48, 32), "SingleTexture"),
              (wood, "radeon9700", (48, 32), None), (phong, "radeon9700", (64, 64), None)]
    kept = []
    for effect, card, size, technique in frames:
        image = Runtime(effect, card, size=size, backend=backend).render(technique).image
        kept.append(image.copy())
        np.testing.assert_array_equal(image, _fresh(effect, card, size, technique))
    # the images handed out are the caller's: later frames into the same buffers change none
    for (effect, card, size, technique), image in zip(frames, kept):
        np.testing.assert_array_equal(image, _fresh(effect, card, size, technique))


def test_a_reused_frame_buffer_is_cleared_to_the_new_clear_values():
    backend = create_backend("numpy", threads=1)
    backend.begin_frame((8, 4), clear_color=(1, 0, 0, 1))
    red = backend.end_frame()
    backend.begin_frame((8, 4), clear_color=(0, 0, 1, 0.5), clear_depth=0.25, clear_stencil=7)
    fb = backend.framebuffer
    assert (fb.depth == np.float32(0.25)).all() and (fb.stencil == 7).all()
    blue = backend.end_frame()
    assert (red == [255, 0, 0, 255]).all()
    assert (blue == [0, 0, 255, 128]).all()
    backend.begin_frame((8, 4), format="A32B32G32R32F", clear_color=(0.5, 0.25, 0, 1))
    assert backend.end_frame().dtype == np.float32


def test_evaluation_steps_belong_to_their_program():
    # two programs evaluated in turn, and the same program with and without a given value:
    # each result is the one evaluating it first would give
    def program(scale):
        b = Builder("fragment")
        b.output("color0", b.mul(b.varying("texcoord0"), b.const((scale,) * 4)))
        return b.build()

    rows = np.arange(16, dtype=np.float32).reshape(4, 4)
    p1, p2 = program(2.0), program(3.0)
    for _ in range(2):
        np.testing.assert_array_equal(evaluate(p1, {"texcoord0": rows}).outputs["color0"], rows * 2)
        np.testing.assert_array_equal(evaluate(p2, {"texcoord0": rows}).outputs["color0"], rows * 3)
    mul = next(i.dest for i in p1.instrs if i.op == "mul")
    given = np.full((4, 4), 5, np.float32)
    np.testing.assert_array_equal(
        evaluate(p1, {"texcoord0": rows}, given={mul: given}).outputs["color0"], given)
    np.testing.assert_array_equal(evaluate(p1, {"texcoord0": rows}).outputs["color0"], rows * 2)
