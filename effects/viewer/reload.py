"""Hot reload: rebuild an effect off the render thread when the files it was built from change.

The habit (docs/design.md habit 11, after glslViewer's file-watcher thread): watch + debounce +
content hash + build in a worker + swap on the render thread + keep the last good effect. Watching,
debouncing and hashing are `effects.viewer.watch` (its names are re-exported here); this module is
the rest:

- `watched_files` lists what a reload depends on: the effect, its #includes, its images.
- `Reloader` owns a Watcher and a worker thread. The worker runs a `build` (for the viewer:
  load, validate, select, lower; see `build_effect`) and puts a `ReloadResult` -- the new
  effect and its selection, or the located error -- on a queue. The render thread calls
  `poll()` each frame, swaps in a good result, keeps drawing the last good effect after a
  failed one, and prints `result.log_line()`. A build may leave the techniques after the
  drawn one to validate (`LoadedEffect.pending`): the worker does that once the render thread
  says it drew the new effect (`drawn()`), so a reload's first frame waits only for what it
  draws. It prints:
      reload: PATH ok in 12.3 ms (technique NAME)
      reload: PATH failed: ERROR
Nothing here opens a window, so all of it is tested without a display.
"""
from __future__ import annotations

import os
import queue
import threading
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable

from effects.base.errors import EffectError, Location
# Re-exported: the viewer, tests and benchmarks import the watcher's names from here.
from effects.viewer.watch import (DEBOUNCE_S, MAX_DELAY_S, POLL_ONLY_S, POLL_SAFETY_S,  # noqa: F401
                    SETTLE_S, Watcher, content_hash)

if TYPE_CHECKING:  # pragma: no cover
    from effects.d3d9.caps import CapsProfile
    from effects.model import Effect, Technique
    from effects.program.passprogram import PassProgram
    from effects.validate.technique import Validation

# ---------------------------------------------------------------------------------------------
# Which files an effect depends on


def _annotation_text(param: Any, name: str) -> str | None:
    a = param.annotation(name)
    return a.value if a is not None and isinstance(a.value, str) else None


def referenced_files(effect: "Effect") -> list[str]:
    """Image files the effect's texture parameters name, resolved against the effect's folder:
    `string ResourceName = "file"` and the image argument of `string Procedural = "gen:file"`.
    Missing files are listed too (creating one is a change worth seeing)."""
    from effects.assets.textures import PROCEDURAL, _is_path
    base = os.path.dirname(os.path.abspath(effect.files[0])) if effect.files else os.getcwd()
    found: list[str] = []
    for param in effect.parameters:
        name = _annotation_text(param, "ResourceName")
        if name:
            found.append(name)
        proc = _annotation_text(param, "Procedural")
        if proc:
            gen, _, arg = proc.partition(":")
            entry = PROCEDURAL.get(gen.strip())
            if entry is not None and entry.takes_height and _is_path(arg.strip()):
                found.append(arg.strip())
    out: list[str] = []
    for name in found:
        path = os.path.normpath(name if os.path.isabs(name) else os.path.join(base, name))
        if path not in out:
            out.append(path)
    return out


def watched_files(effect: "Effect") -> list[str]:
    """Every file a reload depends on: the effect, each #include it read, its texture images."""
    paths = [os.path.abspath(p) for p in effect.files if not p.startswith("<")]
    for p in referenced_files(effect):
        if p not in paths:
            paths.append(p)
    return paths


# ---------------------------------------------------------------------------------------------
# What a build produces


@dataclass
class LoadedEffect:
    """An effect ready to draw on one card: what the render thread swaps in.

    `technique` is what is drawn: the forced one when it is valid on the card, else the one
    the card selects (None when no technique is valid). `validations` holds every technique's
    answer in file order -- but for `pending`: a build that defers (the viewer's reloads)
    validates in file order only until the drawn technique is known, and the techniques after
    it wait in `pending` until `complete_validations()` (the reload worker's, after the first
    frame). `programs` are the lowered passes of `technique` (None when there is nothing to
    draw); `forced_rejected` is set when a forced technique is not valid here. `fidelity`
    (by technique position) holds each valid technique's picture on the card against the
    best technique's (effects.host.fidelity), measured by the worker after the validations,
    one technique at a time (`measure_next`), so a reload asked for meanwhile goes first."""

    path: str
    effect: "Effect"
    profile: "CapsProfile"
    validations: list["Validation"]
    technique: "Technique | None"
    programs: list["PassProgram"] | None
    forced: str | None = None
    forced_rejected: "Validation | None" = None
    files: list[str] = field(default_factory=list)
    prepare_error: Exception | None = None   # the chosen technique cannot be drawn (kept, not raised)
    runtime: Any = None        # the effects.host.runtime.Runtime that prepared it (no back end yet)
    scene_key: Any = None      # BuildSettings.scene_key of the scene it was prepared for
    listing: list[list[str]] | None = None   # per pass of `technique`: `effects compile`'s lines
    pending: list["Technique"] = field(default_factory=list)   # not validated yet (see above)
    scene: Any = None          # the scene it was built for: the fidelity renders draw it
    fidelity: dict[int, Any] = field(default_factory=dict)   # position -> Likeness | None
    fidelity_best: str | None = None     # the technique measured against, once known
    fidelity_done: bool = False
    params: dict[str, Any] = field(default_factory=dict)   # the values `runtime` was made with

    def unfinished(self) -> bool:
        """Whether the worker has validations or fidelity measures left to make."""
        return bool(self.pending) or not self.fidelity_done

    def measure_next(self) -> None:
        """Measure the next valid technique not measured yet (after the validations)."""
        from effects.host.fidelity import meter_for
        meter = meter_for(self.effect, scene=self.scene)
        best = meter.best()
        if best is None:                 # nothing runs on refrast: nothing to measure against
            self.fidelity_done = True
            return
        self.fidelity_best = best.name or "<anonymous>"
        for i, v in enumerate(self.validations):
            if v.ok and i not in self.fidelity:
                self.fidelity[i] = meter.measure(v.technique, self.profile, v)
                return
        self.fidelity_done = True

    def complete_validations(self) -> None:
        """Validate the techniques still pending and list every answer in file order. Run off
        the render thread; the panel reads `validations` each frame, so the full list replaces
        it in one assignment (before `pending` is emptied)."""
        if not self.pending:
            return
        from effects.validate.technique import validate_technique
        done = {id(v.technique): v for v in self.validations}
        for t in self.pending:
            done[id(t)] = validate_technique(self.effect, t, self.profile)
        self.validations = [done[id(t)] for t in self.effect.techniques]
        self.pending = []

    @property
    def selected(self) -> "Validation | None":
        if self.technique is None:
            return None
        return next(v for v in self.validations if v.technique is self.technique)


@dataclass
class ReloadResult:
    """One finished build. `kind` is 'reload' (files changed, or asked for) or 'select' (the
    card or forced technique changed; the effect was not read again)."""

    path: str
    kind: str
    loaded: LoadedEffect | None
    error: BaseException | None
    build_ms: float
    changed: tuple[str, ...] = ()
    requested_at: float = 0.0          # time.perf_counter() of the first event seen (or request)

    @property
    def ok(self) -> bool:
        return self.error is None

    def log_line(self) -> str:
        """The one line each reload prints."""
        if self.ok:
            assert self.loaded is not None
            tech = self.loaded.technique.name if self.loaded.technique is not None else "none valid"
            return f"reload: {self.path} ok in {self.build_ms:.1f} ms (technique {tech})"
        return f"reload: {self.path} failed: {error_text(self.error)}"


def error_text(error: BaseException | None) -> str:
    """A located one-line description: EffectErrors as `PATH:LINE:COL: error: MESSAGE`; a bug of
    ours named as such (the viewer must survive it, and say what it was)."""
    if error is None:
        return ""
    if isinstance(error, EffectError):
        return str(error)
    return f"internal error: {type(error).__name__}: {error}"


def build_effect(path: str, profile: "CapsProfile", *, technique: str | None = None,
                 policy: Any = "first", scene: Any = None, lower: bool = True,
                 previous: "Effect | None" = None, keep_prepare_error: bool = False,
                 scene_key: Any = None, defer: bool = False,
                 params: "dict[str, Any] | Callable[[Effect], dict[str, Any]] | None" = None,
                 **load_options: Any) -> LoadedEffect:
    """Load (unless `previous` is given), validate every technique, select, and prepare the
    chosen one for drawing in `scene` (a Scene, mapping, YAML path or None for the defaults):
    lower its passes with the scene's parameter values, load the textures they sample (into
    the shared cache, so the render thread finds them loaded) and build the vertex streams.

    A forced `technique` is drawn when valid on the card; otherwise the card's selection is
    drawn and `forced_rejected` carries the forced one's reasons. Raises EffectError (located)
    for a broken file, a language error in the forced technique or in one the selection fell
    past (`Selection.passed_over`; with `strict`, in any technique), a missing texture,
    or a pass that cannot be lowered -- the last two are kept in `prepare_error` instead with
    `keep_prepare_error` (a card change: the file is fine, the panel shows why this card
    cannot draw it). `defer`: under the default policy, stop
    validating once the technique to draw is known (the first valid one in file order, or a
    valid forced one) and leave the rest `pending` (see LoadedEffect): a reload draws sooner
    when the fallbacks compile the edited function again for their own targets. `params`:
    parameter values over the scene's (the viewer's --set and panel edits), as `Runtime`
    takes them, or a function of the loaded effect giving them; those naming no parameter of
    this effect are left out."""
    from effects.validate.select import language_error, select
    from effects.validate.verdicts import load_effect   # strict: as D3DXCreateEffect
    effect = previous if previous is not None else load_effect(path, **load_options)
    forced = None
    if technique:
        try:
            forced = effect.technique(technique)
        except (KeyError, EffectError):
            raise EffectError(f"no technique named '{technique}' (the effect has: "
                              f"{', '.join(t.name or '<anonymous>' for t in effect.techniques)})",
                              Location(path, 1, 1)) from None
    # Every technique is validated once (the panel lists them all), and selection chooses
    # among these same answers; `defer` leaves those after the drawn one pending.
    from effects.host.fidelity import policy_for   # draws pictures for the fidelity order only
    selection = select(effect, profile, policy_for(effect, policy, scene=scene), forced=forced,
                       lazy=defer)
    chosen, chosen_validation = selection.technique, selection.chosen
    # A language error in the technique asked for, or in one the selection fell past, fails
    # the reload: shown in red like a parse error, the last good effect stays on screen.
    error = language_error(selection.forced_rejected) if selection.forced_rejected else None
    error = error or selection.passed_over
    if error is not None:
        raise error.with_traceback(None)
    programs = None
    prepare_error = None
    runtime = None
    names = {p.name for p in effect.parameters}
    params = params(effect) if callable(params) else params
    params = {k: v for k, v in (params or {}).items() if k in names}
    if chosen is not None and lower:
        try:
            runtime, programs = prepare(effect, chosen, profile, scene, chosen_validation,
                                        strict=bool(load_options.get("strict")), params=params)
        except Exception as exc:  # noqa: BLE001 - a bug of ours must not close the viewer either
            if not keep_prepare_error:
                raise
            prepare_error = exc
    listing = technique_listing(effect, chosen) if chosen is not None else None
    return LoadedEffect(path, effect, profile, selection.validations, chosen, programs, technique,
                        selection.forced_rejected, watched_files(effect), prepare_error, runtime,
                        scene_key, listing, selection.pending, scene=scene, params=params)


def technique_listing(effect: "Effect", technique: "Technique") -> list[list[str]]:
    """Each pass's listing, made here in the build (off the render thread, and while the source
    lines it quotes are those the shaders were compiled from) by the function `effects compile`
    prints with. A pass that cannot be listed says why in its place."""
    from effects.shaders.listing import pass_listing
    out = []
    for i in range(len(technique.passes)):
        try:
            out.append(pass_listing(effect, technique, i))
        except Exception as exc:  # noqa: BLE001 - the listing is a view: it must not fail a build
            out.append([f"// pass {i}: no listing: {error_text(exc)}", ""])
    return out


def loaded_warnings(loaded: LoadedEffect) -> list:
    """The effect's load warnings and what the host stood in for (a texture nobody supplies),
    which the panel lists and the console prints once each."""
    runtime_warnings = getattr(loaded.runtime, "warnings", None) or []
    return [*loaded.effect.warnings, *runtime_warnings]


def prepare(effect: "Effect", technique: "Technique", profile: "CapsProfile",
            scene: Any = None, validation: "Validation | None" = None, *, strict: bool = False,
            params: dict[str, Any] | None = None) -> tuple[Any, list["PassProgram"]]:
    """Everything that can fail before a technique draws, done now (off the render thread):
    bind the scene, lower every pass (from `validation`'s device states when given), load the
    textures the passes sample, build the streams. Returns the Runtime that did it (its
    lowered passes cached, its validation kept, its textures and streams loaded; it has no
    back end) and the lowered passes. `strict`: a texture nothing supplies is an error (kept
    as the prepare error: the panel shows it) instead of a stand-in with a warning."""
    from effects.host.runtime import Runtime
    runtime = Runtime(effect, profile, scene=scene, backend=None, strict=strict, params=params)
    runtime.validation = validation
    programs = [runtime.lower(technique, i) for i in range(len(technique.passes))]
    for program in programs:
        for binding in program.textures:
            if binding.texture is not None:
                runtime.used_texture(binding.texture, binding.kind)
    runtime.geometry()
    return runtime, programs


# ---------------------------------------------------------------------------------------------
# Reloader


def _unfinished(loaded: Any) -> bool:
    """Whether a build (a LoadedEffect, or a test's stand-in without the worker's steps) has
    validations or measures left for the worker."""
    unfinished = getattr(loaded, "unfinished", None)
    return bool(unfinished()) if unfinished is not None else bool(getattr(loaded, "pending", None))


Build = Callable[["Effect | None"], LoadedEffect]
# How long techniques a build left pending wait for the render thread's first frame before
# the worker validates them anyway (a Reloader with no viewer drawing)
COMPLETE_AFTER_S = 0.25


class Reloader:
    """Rebuild in a worker thread when watched files change; hand results to the render thread.

    `build(previous)` makes a LoadedEffect: with `previous` None it reads the files (a reload),
    with an Effect it only re-selects (after `reselect()`). The render thread calls `poll()`
    (never blocks) and swaps in what it gets. The watcher follows the files of the last good
    build, so a new #include or texture is watched from the next good reload on.
    """

    def __init__(self, path: str, build: Build, *, use_watchdog: bool = True,
                 debounce: float = DEBOUNCE_S, max_delay: float = MAX_DELAY_S,
                 settle: float = SETTLE_S, poll_interval: float | None = None) -> None:
        self.path = path
        self._build = build
        self.results: "queue.Queue[ReloadResult]" = queue.Queue()
        self._jobs: "queue.Queue[tuple[str, tuple[str, ...], float] | None]" = queue.Queue()
        self._good: LoadedEffect | None = None
        self._pending_since: float | None = None
        self._pending_lock = threading.Lock()
        self._builds_queued = 0        # reload/select jobs not answered yet (under _pending_lock)
        self.watcher = Watcher([os.path.abspath(path)], self._files_changed, debounce=debounce,
                               max_delay=max_delay, settle=settle, use_watchdog=use_watchdog,
                               poll_interval=poll_interval)
        self._worker = threading.Thread(target=self._work, name="effects-reload", daemon=True)
        self._started = False

    @property
    def last_good(self) -> LoadedEffect | None:
        return self._good

    @property
    def building(self) -> bool:
        """A reload or re-selection is queued or running: its result is on its way."""
        return self._builds_queued > 0

    def _queue_build(self, kind: str, changed: tuple[str, ...]) -> None:
        with self._pending_lock:
            self._builds_queued += 1
        self._jobs.put((kind, changed, time.perf_counter()))

    def start(self, initial: LoadedEffect | None = None, *, build_now: bool = True) -> "Reloader":
        """Start watching. `initial`: the build the caller already made (its files are watched);
        without it a first build is queued at once, unless `build_now` is False (the caller
        tried and failed: the next change builds)."""
        if initial is not None:
            self._good = initial
            self.watcher.set_paths([os.path.abspath(self.path), *initial.files])
        self.watcher.start()
        self._worker.start()
        self._started = True
        if initial is None and build_now:
            self.request()
        return self

    def stop(self) -> None:
        self.watcher.stop()
        self._jobs.put(None)
        if self._started:
            self._worker.join(timeout=5)

    def request(self) -> None:
        """Reload now (the viewer's reload key), whether or not the files changed."""
        self._queue_build("reload", ())

    def reselect(self) -> None:
        """Select and lower again for the current settings without reading the files (the
        viewer changed card or forced technique)."""
        self._queue_build("select", ())

    def poll(self) -> ReloadResult | None:
        """The next finished build, or None. For the render thread; never blocks."""
        try:
            return self.results.get_nowait()
        except queue.Empty:
            return None

    def wait(self, timeout: float) -> ReloadResult | None:
        """Block up to `timeout` seconds for the next finished build (tests, idle render loops)."""
        try:
            return self.results.get(timeout=timeout)
        except queue.Empty:
            return None

    # -- threads

    def _files_changed(self, paths: list[str]) -> None:
        self._queue_build("reload", tuple(paths))

    def drawn(self) -> None:
        """The render thread drew its first frame with the last result: the worker may now
        validate the techniques that build left pending (the panel lists them)."""
        self._jobs.put(("drawn", (), time.perf_counter()))

    def _complete(self) -> None:
        """Validate what the last good build left pending, else measure one more technique's
        fidelity. A failure is reported as a failed reload would be (the drawn effect stays)."""
        good = self._good
        if good is None or not _unfinished(good):
            return
        start = time.perf_counter()
        try:
            if good.pending:
                good.complete_validations()
            else:
                good.measure_next()
        except BaseException as exc:  # noqa: BLE001 - reported; what is drawn stays
            good.pending = []
            good.fidelity_done = True
            self.results.put(ReloadResult(self.path, "reload", None, exc,
                                          (time.perf_counter() - start) * 1000.0, (), start))

    def _work(self) -> None:
        while True:
            waiting = self._good is not None and _unfinished(self._good)
            try:
                # validations left pending wait for the first frame (or, with no render
                # thread to say so, a short while); a build queued before then goes first
                job = self._jobs.get(timeout=COMPLETE_AFTER_S if waiting else None)
            except queue.Empty:
                self._complete()
                continue
            if job is None:
                return
            if job[0] == "drawn":
                self._complete()
                continue
            kind, changed, requested = job
            answered = 1
            # Coalesce: if more reload jobs queued up meanwhile, one build reads the newest files.
            while True:
                try:
                    nxt = self._jobs.get_nowait()
                except queue.Empty:
                    break
                if nxt is None:
                    return
                if nxt[0] == "drawn":       # drawn: an older build; this one replaces it
                    continue
                answered += 1
                if nxt[0] == "reload" or kind == "reload":
                    kind = "reload"
                changed = tuple(sorted(set(changed) | set(nxt[1])))
            previous = self._good.effect if (kind == "select" and self._good is not None) else None
            start = time.perf_counter()
            try:
                loaded = self._build(previous)
                error = None
            except BaseException as exc:  # noqa: BLE001 - reported, and the last good stays
                loaded, error = None, exc
            elapsed = (time.perf_counter() - start) * 1000.0
            if loaded is not None:
                self._good = loaded
                self.watcher.set_paths([os.path.abspath(self.path), *getattr(loaded, 'files', ())])
            self.results.put(ReloadResult(self.path, kind, loaded, error, elapsed, changed, requested))
            with self._pending_lock:
                self._builds_queued -= answered


@dataclass
class BuildSettings:
    """What a build depends on besides the files: the card, a forced technique name, the
    selection policy, and the scene the effect will be drawn in."""

    profile: "CapsProfile"
    technique: str | None = None
    policy: Any = "first"
    scene: Any = None
    scene_key: Any = None      # equal keys: the same scene (lets the viewer reuse the Runtime)
    # --set values and the panel's edits, or a function of the loaded effect giving them
    params: Any = None


def effect_builder(path: str, settings: Callable[[], BuildSettings], **load_options: Any) -> Build:
    """The viewer's build: `settings()` is read when the build runs, so a reload after a card
    change uses the new card. A reload whose technique cannot be prepared fails (the last good
    effect stays); a re-selection keeps the error to show it."""
    def build(previous: "Effect | None") -> LoadedEffect:
        s = settings()
        return build_effect(path, s.profile, technique=s.technique, policy=s.policy,
                            scene=s.scene, previous=previous, scene_key=s.scene_key,
                            params=s.params,
                            keep_prepare_error=previous is not None, defer=True, **load_options)
    return build
