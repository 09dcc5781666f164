"""`effects view FILE.fx`: look at an effect on a simulated card, flip cards, edit and see.

A moderngl-window (pyglet) window: the effect drawn by the GL back end on the left, an imgui
panel on the right (`viewer_panel`). The effect file, its #includes and its texture images are
watched (`effects.viewer.reload`); a change is rebuilt in a worker thread -- load, validate, select,
lower, textures -- and swapped in here, on the render thread, between two frames. Meshes and
unchanged textures stay loaded (the asset caches and the GL back end's texture cache key on
the unchanged objects). A failed build keeps the last good effect on screen and shows the
located error in the panel and on the console.

Console lines (stdout, one per event, flushed at once so scripts can follow):
    view: PATH on CARD: technique NAME (N passes)         the first frame is drawn
    reload: PATH ok in 12.3 ms (technique NAME)           a reload was swapped in
    reload: PATH failed: PATH:LINE:COL: error: MESSAGE    a reload failed; the last good stays
    scene: SCENE ok in 1.2 ms                             the scene file was edited: drawn again
    scene: SCENE failed: SCENE:LINE:COL: error: MESSAGE   a broken scene file; the last good stays
    select: CARD: technique NAME (N passes)               another card or forced technique
    screenshot: OUT.png
Scriptable: --exit-after SECONDS, --screenshot OUT.png (taken at exit), --profile, --technique,
--mesh, --view, --tour (draw every card once, then exit), --time SECONDS (TIME held there).

The effect is drawn in its scene (--scene, or NAME.yaml beside NAME.fx: mesh, camera, light,
params, time; watched and reloaded as the effect is, `effects.viewer.scene_reload`), with --set values over it and the panel's edits over those
(`effects.viewer.params`). TIME runs while the effect reads it: space pauses, . and , step.
"""
from __future__ import annotations

import os
import sys
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Sequence

import numpy as np

from effects.base.errors import EffectError
from effects.viewer.reload import LoadedEffect, Reloader, ReloadResult, build_effect, effect_builder, error_text, loaded_warnings
from effects.viewer.scene_reload import SceneReloader
from effects.viewer.state import DIFFERENCE_SCALE, MESHES, VIEWS, ViewerState

DEFAULT_CARD = "radeon9700"
WINDOW_SIZE = (1040, 600)
PANEL_WIDTH = 440
IDLE_WAIT_S = 0.03           # an idle frame waits this long for a reload (returns at once on one)
# ... and this long while a reload is building: redrawing the unchanged picture meanwhile would
# take the CPU (llvmpipe's threads, the GIL) from the build it waits for
BUILD_WAIT_S = 0.25


@dataclass
class ViewerOptions:
    path: str
    profile: str | None = None
    technique: str | None = None
    mesh: str | None = None          # None: the scene's, else the effect's XFile, else the sphere
    view: str = "gl"
    scene: str | None = None         # the scene file (the CLI resolves NAME.yaml beside NAME.fx)
    assignments: dict[str, str] = field(default_factory=dict)   # --set NAME=VALUE
    time: float | None = None        # --time: TIME held at this many seconds
    exit_after: float | None = None
    screenshot: str | None = None
    size: tuple[int, int] = WINDOW_SIZE
    tour: bool = False
    listing: bool = False            # start with the listing window shown (key C toggles it)
    polling: bool = False            # watch by polling only (file systems without inotify)
    defines: dict[str, str] = field(default_factory=dict)
    include_dirs: Sequence[str] = ()
    include_root: str | None = None  # confine every file the effect reads (load_effect's)
    strict: bool = False


@dataclass
class FrameEvent:
    """Told to `Viewer.on_frame` after each swapped frame (benchmarks, tests)."""

    number: int
    time: float                      # time.perf_counter() after the swap
    effect_generation: int           # increments each time a new build is swapped in
    result: ReloadResult | None      # the build first drawn in this frame, if any
    render_ms: float | None = None   # the effect's GL render in this frame (None: not redrawn)
    seconds: float = 0.0             # the clock TIME read in this frame


class NoDisplay(Exception):
    """No window can be opened: there is no display to open it on (str: why, in a few words)."""


def say(line: str) -> None:
    print(line, flush=True)


class Viewer:
    """The application. `run()` returns the exit code."""

    def __init__(self, options: ViewerOptions, *, on_frame: Callable[[FrameEvent], None] | None = None,
                 output: Callable[[str], None] = say) -> None:
        from effects.d3d9.caps import list_profiles, load_profile
        from effects.viewer.panel import Status
        self.options = options
        self.on_frame = on_frame
        self.say = output
        cards = list(list_profiles())
        card = options.profile or DEFAULT_CARD
        if card not in cards:
            load_profile(card)                       # a YAML path: fails located if bad
            cards.append(card)
        self.state = ViewerState(cards, cards.index(card), options.technique, options.view,
                                 options.mesh, show_listing=options.listing)
        self.state.assignments = dict(options.assignments)
        if options.time is not None:
            self.state.clock.seconds, self.state.clock.fixed = float(options.time), True
        from effects.host.scene import load_scene
        self.state.start_from_scene(load_scene(options.scene))   # a bad scene: said, located
        self.status = Status(options.path)
        self.loaded: LoadedEffect | None = None
        self.effect_generation = 0
        self._drawn_generation = (-1, -1)
        self._image: np.ndarray | None = None
        self._reference: tuple[object, np.ndarray] | None = None
        self._fresh_result: ReloadResult | None = None
        # (LoadedEffect, scene key, Runtime, the parameter values applied to it) last drawn
        self._runtime: tuple | None = None
        self._reads_time = False               # the effect drawn reads the clock (TIME)
        self._screenshot_requested = False
        self._shots = 0
        self._selection_seen = self.state.selection_generation
        self._announced = False
        self._warned: set[str] = set()
        self._load_options = {"defines": options.defines, "include_dirs": tuple(options.include_dirs),
                              "include_root": options.include_root, "strict": options.strict}

    # -- set-up -----------------------------------------------------------------------------
    def _initial_build(self) -> LoadedEffect | None:
        """The first build, here on the main thread: a broken file still opens the viewer (its
        error on screen, the file watched) so the user can fix it."""
        try:
            loaded = build_effect(self.options.path, self.state.profile,
                                  technique=self.state.technique,
                                  scene=self.state.scene(self.effect_size()),
                                  scene_key=self.state.scene_key(self.effect_size()),
                                  params=self.state.param_values,
                                  keep_prepare_error=True, **self._load_options)
        except EffectError as exc:
            self.status.error = exc.report()
            self.say(f"view: {self.options.path} failed: {exc}")
            return None
        self._swap(loaded)
        return loaded

    def _open_window(self) -> None:
        import moderngl_window as mglw
        from moderngl_window.conf import settings
        settings.WINDOW.update({
            "class": "moderngl_window.context.pyglet.Window", "gl_version": (3, 3),
            "size": tuple(self.options.size), "vsync": False, "resizable": True,
            "aspect_ratio": None, "title": f"effects view {os.path.basename(self.options.path)}",
        })
        try:
            self.window = mglw.create_window_from_settings()
        except Exception as exc:
            # pyglet's NoSuchDisplayException (a class in pyglet.display.xlib and another in
            # pyglet.window, raised as its window module loads): known by name, portably
            if type(exc).__name__ != "NoSuchDisplayException":
                raise
            display = os.environ.get("DISPLAY")
            raise NoDisplay(f"cannot connect to DISPLAY={display}" if display
                            else "DISPLAY is not set") from None
        mglw.activate_context(window=self.window)
        self.ctx = self.window.ctx
        from imgui_bundle import imgui
        from moderngl_window.integrations.imgui_bundle import ModernglWindowRenderer
        imgui.create_context()
        imgui.get_io().set_ini_filename("")
        self.imgui = ModernglWindowRenderer(self.window)
        w = self.window
        w.key_event_func = self._key
        w.mouse_drag_event_func = self._drag
        w.mouse_scroll_event_func = self._scroll
        w.mouse_press_event_func = self.imgui.mouse_press_event
        w.mouse_release_event_func = self.imgui.mouse_release_event
        w.mouse_position_event_func = self.imgui.mouse_position_event
        w.unicode_char_entered_func = self.imgui.unicode_char_entered
        w.resize_func = self._resize
        from effects.program.backend import create_backend
        from effects.viewer.draw import Blitter, ReferenceRenderer
        self.backend = create_backend("gl", context=self.ctx)
        self.blitter = Blitter(self.ctx)
        self.reference = ReferenceRenderer()

    # -- layout -----------------------------------------------------------------------------
    def effect_size(self) -> tuple[int, int]:
        """The effect's square, left of the panel, as large as the window allows."""
        w, h = (self.window.buffer_size if hasattr(self, "window") else self.options.size)
        side = max(16, min(h, w - PANEL_WIDTH))
        return (side, side)

    # -- the loop ---------------------------------------------------------------------------
    def run(self) -> int:
        self._open_window()
        initial = self._initial_build()
        builder = effect_builder(self.options.path,
                                 lambda: self.state.build_settings(self.effect_size()),
                                 **self._load_options)
        self.reloader = Reloader(self.options.path, builder, use_watchdog=not self.options.polling)
        self.reloader.start(initial, build_now=False)
        # the scene file is watched too: an edit is drawn, a broken one said (the last good stays)
        self.scenes = SceneReloader(self.options.scene, use_watchdog=not self.options.polling).start() \
            if self.options.scene else None
        start = time.perf_counter()
        last = start
        frame = 0
        tour = list(range(len(self.state.cards))) if self.options.tour else None
        if tour:
            tour = tour[self.state.card_index:] + tour[:self.state.card_index]
        try:
            while not self.window.is_closing:
                now = time.perf_counter()
                if self.options.exit_after is not None and now - start >= self.options.exit_after:
                    break
                idle = self._idle()
                result = self._wait_for_reload() if idle else self.reloader.poll()
                while result is not None:
                    self._take(result)
                    result = self.reloader.poll()
                self._take_scenes()
                if self.state.light.advance(now - last):
                    self.state.changed()
                if self._reads_time and self.state.clock.advance(now - last):
                    self.state.changed()
                last = now
                if self.state.selection_generation != self._selection_seen:
                    self._selection_seen = self.state.selection_generation
                    self.reloader.reselect()
                self._rendered_ms = None
                self._draw_frame()
                if self._screenshot_requested:
                    self._screenshot_requested = False
                    self._save_screenshot(self._next_screenshot_name())
                self.window.swap_buffers()
                frame += 1
                if frame == 1 and self.loaded is not None:
                    self.say(f"view: {self.options.path} on {self._selection_text()}")
                fresh, self._fresh_result = self._fresh_result, None
                if fresh is not None:
                    self.reloader.drawn()     # now the build's pending validations may run
                if self.on_frame is not None:
                    self.on_frame(FrameEvent(frame, time.perf_counter(), self.effect_generation, fresh,
                                             self._rendered_ms, self.state.clock.seconds))
                if tour is not None and self._tour_step(tour):
                    break
            # at exit: anything already rebuilt is drawn, so the screenshot shows the last effect
            result = self.reloader.poll()
            while result is not None:
                self._take(result)
                result = self.reloader.poll()
            if self.options.screenshot:
                self._draw_frame()
                self._save_screenshot(self.options.screenshot)
        finally:
            self.reloader.stop()
            if self.scenes is not None:
                self.scenes.stop()
            self.reference.stop()
            self.window.destroy()
        return self.exit_code()

    _screenshot_failed = False

    def exit_code(self) -> int:
        """As the other commands: 2 when the file or its scene file (as they are at exit) does
        not load or the screenshot could not be written, 1 when nothing could be drawn, else 0."""
        if self.status.error is not None or self.loaded is None or self._screenshot_failed \
                or self.status.scene_error is not None:
            return 2
        if self.loaded.technique is None or self.loaded.prepare_error is not None \
                or self.status.render_error is not None:
            return 1
        return 0

    def _wait_for_reload(self) -> ReloadResult | None:
        """An idle frame's wait: IDLE_WAIT_S, or up to BUILD_WAIT_S while a reload builds (one
        may start during the wait: then it goes on waiting)."""
        waited = 0.0
        while True:
            result = self.reloader.wait(IDLE_WAIT_S)
            waited += IDLE_WAIT_S
            if result is not None or not self.reloader.building or waited >= BUILD_WAIT_S:
                return result

    def _idle(self) -> bool:
        animating = self._reads_time and self.state.clock.running and not self.state.clock.fixed
        return (not self.state.light.animate and not animating and self._image is not None
                and self._drawn_generation == (self.effect_generation, self.state.generation)
                and not self.reference.busy and not self.options.tour)

    def _tour_step(self, tour: list[int]) -> bool:
        """--tour: once the current card's selection is drawn, go to the next; True when done."""
        if self.state.selection_generation != self._swapped_selection:
            return False                     # the reselect for this card is still building
        tour.pop(0)
        if not tour:
            return True
        self.state.set_card(tour[0])
        return False

    _swapped_selection = 0

    # -- builds -----------------------------------------------------------------------------
    def _take(self, result: ReloadResult) -> None:
        """A finished build, on the render thread: swap it in, or keep the last good one."""
        if self._scene_trial is not None and self._take_scene_build(result):
            return
        if result.kind == "reload":
            self.say(result.log_line())
            self.status.last_reload = result.log_line()
        if result.ok:
            self._swap(result.loaded)
            self._fresh_result = result
            if result.kind == "select":
                self.say(f"select: {self._selection_text()}")
        else:
            err = result.error
            self.status.error = err.report() if isinstance(err, EffectError) else error_text(err)
            if result.kind == "select":
                self.say(f"select: {self.state.card} failed: {error_text(err)}")
            self._swapped_selection = self.state.selection_generation

    scenes: "SceneReloader | None" = None
    # while the build for an edited scene file is on its way: the scene it replaced (state's
    # `reload_scene`), taken back if the effect cannot be drawn in the new one
    _scene_trial: tuple | None = None

    def _take_scenes(self) -> None:
        """Readings of the edited scene file, on the render thread: a good one is taken and the
        effect prepared in it (off this thread); a broken one is said and shown, and the last
        good scene stays."""
        result = self.scenes.poll() if self.scenes is not None else None
        while result is not None:
            self.say(result.log_line())
            if result.ok:
                before = self.state.reload_scene(result.scene)
                self._scene_trial = self._scene_trial or before
                self.status.scene_error = None
            else:
                self._scene_failed(result.error)
            result = self.scenes.poll()  # type: ignore[union-attr]

    def _scene_failed(self, err: BaseException | None) -> None:
        self.status.scene_error = err.report() if isinstance(err, EffectError) else error_text(err)

    def _take_scene_build(self, result: ReloadResult) -> bool:
        """The first build after a scene file was taken: True when it was taken here. Where it
        failed at the scene file (a mesh file that does not load, a param the effect does not
        have or of the wrong type: located there), the scene file is broken: the last good
        scene and effect stay, and the error is the scene's."""
        before, self._scene_trial = self._scene_trial, None
        failed = result.error if not result.ok else result.loaded.prepare_error  # type: ignore[union-attr]
        if not (isinstance(failed, EffectError) and self.options.scene is not None
                and os.path.abspath(failed.path) == os.path.abspath(self.options.scene)):
            return False
        self.state.restore_scene(before)  # type: ignore[arg-type]
        self._scene_failed(failed)
        self.say(f"scene: {self.options.scene} failed: {error_text(failed)}")
        self._swapped_selection = self.state.selection_generation
        return True

    def _swap(self, loaded: LoadedEffect) -> None:
        for warning in [*loaded_warnings(loaded), *self._unknown_assignments(loaded)]:
            if str(warning) not in self._warned:  # each once, not at every reselect
                self._warned.add(str(warning))
                self.say(str(warning))
        self.loaded = loaded
        self.status.loaded = loaded
        self.status.error = None
        self.effect_generation += 1
        self._swapped_selection = self.state.selection_generation

    def _unknown_assignments(self, loaded: LoadedEffect) -> list:
        """A --set name the effect does not have: `render` refuses it; the viewer, whose file
        may gain the parameter in the next edit, says so (once) and draws on."""
        from effects.base.errors import EffectWarning
        from effects.host.semantics import lookup_parameter
        out = []
        for name in self.state.assignments:
            try:
                lookup_parameter(loaded.effect, name, None, "--set")
            except EffectError as exc:
                out.append(EffectWarning(exc.message, exc.location))
        return out

    def _selection_text(self) -> str:
        loaded = self.loaded
        card = self.state.card
        if loaded is None:
            return f"{card}: no effect loaded"
        if loaded.technique is None:
            return f"{card}: no valid technique"
        n = len(loaded.technique.passes)
        text = f"{card}: technique {loaded.technique.name or '<anonymous>'} ({n} pass{'es' if n != 1 else ''})"
        if loaded.prepare_error is not None:
            text += f" cannot be drawn: {error_text(loaded.prepare_error)}"
        if loaded.forced_rejected is not None:
            reasons = loaded.forced_rejected.reasons
            text += (f"; forced {loaded.forced} is not valid here: "
                     f"{reasons[0] if reasons else 'not valid'}")
        return text

    def listing_text(self) -> str:
        """What the listing window shows: `effects compile --technique T` for the technique
        drawn (every pass), from the last good build -- a failed reload keeps it, with the
        error above it in the window."""
        loaded = self.loaded
        if loaded is None:
            return "// no effect loaded"
        if loaded.technique is None or loaded.listing is None:
            return f"// {self.state.card}: no valid technique, nothing to list"
        return "\n".join(line for lines in loaded.listing for line in lines)

    # -- drawing ----------------------------------------------------------------------------
    def _render_effect(self) -> None:
        """Draw the effect into the image shown, if anything it depends on changed."""
        key = (self.effect_generation, self.state.generation)
        if key == self._drawn_generation:
            return
        from effects.viewer.draw import render_effect
        self._drawn_generation = key
        self.status.render_error = None
        loaded = self.loaded
        size = self.effect_size()
        if loaded is not None and (loaded.profile is not self.state.profile
                                   or self._scene_trial is not None):
            self._drawn_generation = (-1, -1)   # the new card's or scene's build is on its way
            return
        if loaded is None or loaded.technique is None or loaded.prepare_error is not None:
            self._image = np.zeros((size[1], size[0], 4), np.uint8)
            self._image[..., :3] = 20
            self.blitter.upload(self._image)
            return
        scene = self.state.scene(size)
        scene_key = self.state.scene_key(size)
        wanted = self.state.param_values(loaded.effect)
        runtime, applied = None, {}
        if (self._runtime is not None and self._runtime[0] is loaded
                and self._runtime[1] == scene_key):
            runtime, applied = self._runtime[2], self._runtime[3]
        elif loaded.runtime is not None and loaded.scene_key == scene_key:
            # prepared by the reload worker for this very scene, with these values
            runtime, applied = loaded.runtime, dict(loaded.params)
        if runtime is not None and any(name not in wanted for name in applied):
            runtime = None     # an edit was reset: the file's value again, in a fresh runtime
        start = time.perf_counter()
        try:
            from effects.host.runtime import Runtime
            for _ in range(len(wanted) + 1):     # each pass refuses one edit, or is done
                if runtime is None:
                    assigned = {k: v for k, v in wanted.items() if k in self.state.assignments}
                    runtime = Runtime(loaded.effect, loaded.profile, scene=scene,
                                      backend=self.backend, params=assigned)
                    applied = dict(assigned)
                if self._apply_edits(loaded, runtime, applied, wanted):
                    break
                runtime, wanted = None, self.state.param_values(loaded.effect)
            self._reads_time = runtime.set_time(self.state.clock.seconds)
            self._runtime = (loaded, scene_key, runtime, applied)
            self.status.runtime, self.status.reads_time = runtime, self._reads_time
            image = render_effect(loaded, scene, self.backend, runtime)
        except Exception as exc:  # noqa: BLE001 - shown; the previous picture stays
            self.status.render_error = error_text(exc)
            self.say(f"render: {self.options.path} failed: {error_text(exc)}")
            return
        finally:
            self.backend.reset_shared_state()
        self.status.gl_ms = self._rendered_ms = (time.perf_counter() - start) * 1000.0
        self._image = image
        self.status.diagnostics = frame_diagnostics(runtime, loaded.technique, image)
        for text in self.status.diagnostics:     # on the console too, each once
            if text not in self._warned:
                self._warned.add(text)
                self.say(text)
        if self.state.view == "gl":
            self.blitter.upload(image)

    def _apply_edits(self, loaded: LoadedEffect, runtime, applied: dict, wanted: dict) -> bool:
        """Set on `runtime` the values in `wanted` it does not have yet (`applied` records
        them). A texture loads now, so a path that does not load is said beside its field
        and the edit dropped: False, and the caller starts again from a fresh runtime."""
        from effects.viewer.params import tweakables
        for name, value in wanted.items():
            if name in applied and applied[name] == value:
                continue
            try:
                runtime.set_value(name, value)
                if runtime.effect.parameter(name).type.takes_image:
                    runtime.texture(name)
            except EffectError as exc:
                item = next((t for t in tweakables(loaded.effect) if t.name == name), None)
                if item is None:           # a --set value: it fails the render, as in render
                    raise
                self.state.tweaks.refuse(name, item.key, str(exc))
                self.say(f"set: {exc}")
                return False
            applied[name] = value
        return True

    def _update_reference(self) -> None:
        if (self.state.view == "gl" or self.loaded is None or self.loaded.technique is None
                or self.loaded.prepare_error is not None):
            self.status.reference_busy = False
            return
        key = (self.effect_generation, self.state.camera_key(), self.effect_size())
        done = self.reference.take()
        if done is not None:
            rkey, image, ms, error = done
            self.status.reference_ms = ms
            self.status.reference_error = error_text(error) if error else None
            if image is not None:
                self._reference = (rkey, image)
        if self._reference is None or self._reference[0] != key:
            self.reference.request(key, self.loaded, self.state.scene(self.effect_size()),
                                   self.state.param_values(self.loaded.effect))
        self.status.reference_busy = self.reference.busy
        if self._reference is not None and self._image is not None:
            ref = self._reference[1]
            if self.state.view == "reference":
                self.blitter.upload(ref)
            elif ref.shape == self._image.shape:
                from effects.viewer.draw import DifferenceStats, difference_image
                self.blitter.upload(difference_image(self._image, ref, DIFFERENCE_SCALE))
                self.status.difference = DifferenceStats.of(self._image, ref)

    def _draw_frame(self) -> None:
        import moderngl
        from imgui_bundle import imgui
        from effects.viewer.panel import Actions, draw_listing, draw_panel
        self._render_effect()
        if self.state.view != "gl":
            self._update_reference()
        elif self._image is not None and self._last_view != "gl":
            self.blitter.upload(self._image)
        self._last_view = self.state.view
        self.window.use()
        self.ctx.scissor = None
        self.ctx.viewport = (0, 0, *self.window.buffer_size)
        self.ctx.clear(0.12, 0.12, 0.14, 1.0)
        side = self.effect_size()
        bw, bh = self.window.buffer_size
        self.blitter.draw((0, bh - side[1], side[0], side[1]))
        self.ctx.viewport = (0, 0, bw, bh)
        imgui.new_frame()
        ww, wh = self.window.size
        scale = ww / bw if bw else 1.0
        panel_x = side[0] * scale
        draw_panel(self.state, self.status, Actions(self.request_reload, self.request_screenshot),
                   (panel_x, 0, ww - panel_x, wh))
        if self.state.show_listing:
            draw_listing(self.status, self.listing_text(), (0, 0, panel_x, wh))
        imgui.render()
        self.imgui.render(imgui.get_draw_data())
        self.ctx.enable_only(moderngl.NOTHING)

    _last_view = "gl"
    _rendered_ms: float | None = None

    # -- actions ----------------------------------------------------------------------------
    def request_reload(self) -> None:
        self.reloader.request()

    def request_screenshot(self) -> None:
        self._screenshot_requested = True

    def _next_screenshot_name(self) -> str:
        self._shots += 1
        base = os.path.splitext(os.path.basename(self.options.path))[0]
        return f"{base}-{self.state.card}-{self._shots}.png"

    def _save_screenshot(self, path: str) -> None:
        from PIL import Image
        bw, bh = self.window.buffer_size
        data = self.window.fbo.read(viewport=(0, 0, bw, bh), components=3)
        # moderngl's read of the window's framebuffer leaves GL_INVALID_OPERATION queued
        # (it selects a colour attachment the default framebuffer does not have; the pixels
        # come back right): read it off here, or the GL back end's next check -- the next
        # frame drawn after an S key -- reports it as its own failure
        _ = self.ctx.error
        image = np.frombuffer(data, np.uint8).reshape(bh, bw, 3)[::-1]
        try:
            Image.fromarray(image).save(path)
        except (OSError, ValueError, KeyError) as exc:   # KeyError: Pillow knows no such extension
            self.say(f"screenshot: {path} failed: {exc}")
            self._screenshot_failed = True
            return
        self.say(f"screenshot: {path}")

    # -- input ------------------------------------------------------------------------------
    def _key(self, key, action, modifiers) -> None:
        self.imgui.key_event(key, action, modifiers)
        keys = self.window.keys
        if action != keys.ACTION_PRESS or self._imgui_wants_keyboard():
            return
        shift = bool(modifiers.shift)
        step = -1 if shift else 1
        names = [t.name for t in self.loaded.effect.techniques if t.name] if self.loaded else []
        actions = {
            keys.N: lambda: self.state.next_card(1), keys.P: lambda: self.state.next_card(-1),
            keys.T: lambda: self.state.cycle_technique(names, step),
            keys.V: self.state.cycle_view, keys.M: self.state.cycle_mesh,
            keys.NUMBER_1: lambda: self.state.set_view(VIEWS[0]),
            keys.NUMBER_2: lambda: self.state.set_view(VIEWS[1]),
            keys.NUMBER_3: lambda: self.state.set_view(VIEWS[2]),
            keys.C: self.state.toggle_listing,
            keys.L: self._toggle_light, keys.R: self.request_reload, keys.S: self.request_screenshot,
            keys.SPACE: self.state.toggle_clock,
            keys.PERIOD: lambda: self.state.step_clock(1),
            keys.COMMA: lambda: self.state.step_clock(-1),
        }
        action_fn = actions.get(key)
        if action_fn is not None:
            action_fn()

    def _toggle_light(self) -> None:
        self.state.light.animate = not self.state.light.animate

    def _imgui_wants_keyboard(self) -> bool:
        from imgui_bundle import imgui
        return bool(imgui.get_io().want_text_input)

    def _drag(self, x, y, dx, dy) -> None:
        self.imgui.mouse_drag_event(x, y, dx, dy)
        from imgui_bundle import imgui
        if imgui.get_io().want_capture_mouse:
            return
        states = self.window.mouse_states
        if states.left:
            self.state.orbit.drag(dx, dy)
            self.state.changed()
        elif states.right:
            self.state.light.angle -= dx * 0.01
            self.state.changed()

    def _scroll(self, x_offset, y_offset) -> None:
        self.imgui.mouse_scroll_event(x_offset, y_offset)
        from imgui_bundle import imgui
        if not imgui.get_io().want_capture_mouse:
            self.state.orbit.zoom(y_offset)
            self.state.changed()

    def _resize(self, width, height) -> None:
        self.imgui.resize(width, height)
        self.state.changed()               # redraw at the new size


def run_viewer(options: ViewerOptions) -> int:
    """Open the viewer; returns the process exit code."""
    from effects.assets.meshes import MESH_FILES
    if options.mesh is not None and options.mesh not in MESHES:
        from effects.base.errors import Location, SceneError
        if not options.mesh.lower().endswith(MESH_FILES):
            raise SceneError(f"unknown mesh {options.mesh!r} (meshes: {', '.join(MESHES)}, or a "
                             f"{' or '.join(MESH_FILES)} file)", Location("<--mesh>", 1, 1))
        if not os.path.isfile(options.mesh):
            raise SceneError(f"mesh file not found: {options.mesh}", Location(options.mesh, 1, 1))
        # the scene's base folder must not move it: a --mesh path is the command line's
        options.mesh = os.path.abspath(options.mesh)
    if options.view not in VIEWS:
        from effects.base.errors import Location, SceneError
        raise SceneError(f"unknown view {options.view!r} (views: {', '.join(VIEWS)})",
                         Location("<--view>", 1, 1))
    # a missing file is said before a window is opened (or found not to open): a broken one
    # opens the viewer, its error on screen, for the user to fix while it watches
    from effects.base import untrusted
    from effects.base.errors import PreprocessError
    untrusted.check_regular(options.path, "effect file", PreprocessError)
    viewer = Viewer(options)
    try:
        return viewer.run()
    except KeyboardInterrupt:
        return 130


if __name__ == "__main__":  # pragma: no cover
    sys.exit(run_viewer(ViewerOptions(sys.argv[1])))


def frame_diagnostics(runtime: Any, technique: Any, image: np.ndarray) -> list[str]:
    """What the picture drawn shows nothing of (`effects.host.diagnostics`), for the panel;
    a diagnosis that fails says so instead of failing the frame."""
    from effects.host.diagnostics import diagnose_frame
    try:
        return [str(w) for w in diagnose_frame(runtime, technique, image)]
    except Exception as exc:  # noqa: BLE001 - a view of the frame must not fail it
        return [f"the picture could not be diagnosed: {error_text(exc)}"]
