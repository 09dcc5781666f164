"""Hot reload: watch the files an effect was built from, rebuild it off the render thread.

The habit (STYLE.md 11, after glslViewer's file-watcher thread): watch + debounce + content
hash + build in a worker + swap on the render thread + keep the last good effect.

- `Watcher` watches the folders of a set of files with watchdog (created, modified, moved and
  deleted events, so an editor's atomic save -- write `x.tmp`, rename it onto `x` -- counts; it
  arrives as `created x.tmp` ... `moved x.tmp -> x`, never as `modified x`), plus a polling
  thread as the fallback (the only mechanism when watchdog cannot start, a slow safety net
  otherwise). Events are debounced: the change is reported once the files have been quiet for
  `debounce` seconds, or at the latest `max_delay` after the first event, so autosave cannot
  starve it. A change is reported only for files whose content hash differs from the last one
  seen, so a save without edits, a `touch`, or a burst that ends where it began does nothing.
- `Reloader` owns a Watcher and a worker thread. The worker runs a `build` (for the viewer:
  load, validate, select, lower; see `build_effect`) and puts a `ReloadResult` -- the new
  effect and its selection, or the located error -- on a queue. The render thread calls
  `poll()` each frame, swaps in a good result, keeps drawing the last good effect after a
  failed one, and prints `result.log_line()`:
      reload: PATH ok in 12.3 ms (technique NAME)
      reload: PATH failed: ERROR
Nothing here opens a window, so all of it is tested without a display.
"""
from __future__ import annotations

import hashlib
import os
import queue
import threading
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable, Iterable

from .errors import EffectError, Location

if TYPE_CHECKING:  # pragma: no cover
    from .caps import CapsProfile
    from .model import Effect, Technique
    from .passprogram import PassProgram
    from .validate import Validation

# Quiet time before a change counts. One save's events (truncate, write, close; or create a temp
# file, write, rename) arrive within a millisecond or two, so 10 ms groups them while keeping
# the edit-to-picture latency low; a writer slower than that shows as a failed reload followed
# by a good one (the last good effect stays on screen meanwhile).
DEBOUNCE_S = 0.010
MAX_DELAY_S = 0.25        # ... but never wait longer than this after the first event
POLL_ONLY_S = 0.1         # polling interval when watchdog is not available
POLL_SAFETY_S = 1.0       # polling interval as a safety net beside watchdog


# ---------------------------------------------------------------------------------------------
# Which files an effect depends on


def content_hash(path: str) -> str | None:
    """BLAKE2 digest of a file's bytes; None when it cannot be read (missing, mid-rename)."""
    try:
        with open(path, "rb") as f:
            return hashlib.blake2b(f.read(), digest_size=16).hexdigest()
    except OSError:
        return None


def _annotation_text(param: Any, name: str) -> str | None:
    a = param.annotation(name)
    return a.value if a is not None and isinstance(a.value, str) else None


def referenced_files(effect: "Effect") -> list[str]:
    """Image files the effect's texture parameters name, resolved against the effect's folder:
    `string ResourceName = "file"` and the image argument of `string Procedural = "gen:file"`.
    Missing files are listed too (creating one is a change worth seeing)."""
    from .textures import PROCEDURAL, _is_path
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
# Watcher


class Watcher:
    """Report changed files, debounced and filtered by content hash, to `on_change(paths)`.

    `on_change` runs on the watcher's own thread with the absolute paths whose content hash
    changed since the last report (a file that vanished has hash None: that is a change too).
    `mode` says what watches: 'watchdog' (with a polling safety net) or 'polling'.
    """

    def __init__(self, paths: Iterable[str], on_change: Callable[[list[str]], None], *,
                 debounce: float = DEBOUNCE_S, max_delay: float = MAX_DELAY_S,
                 use_watchdog: bool = True, poll_interval: float | None = None) -> None:
        self._on_change = on_change
        self.debounce = debounce
        self.max_delay = max(max_delay, debounce)
        self._use_watchdog = use_watchdog
        self._poll_interval = poll_interval
        self._lock = threading.Condition()
        self._paths: set[str] = set()
        self._hashes: dict[str, str | None] = {}
        self._stats: dict[str, tuple | None] = {}
        self._first_event: float | None = None   # monotonic time of the first pending event
        self._last_event = 0.0
        self._stopping = False
        self._observer = None
        self._watched_dirs: dict[str, Any] = {}
        self._threads: list[threading.Thread] = []
        self.mode = "polling"
        self.set_paths(paths)

    # -- public

    @property
    def paths(self) -> list[str]:
        with self._lock:
            return sorted(self._paths)

    def set_paths(self, paths: Iterable[str]) -> None:
        """Watch exactly these files (folders are watched as needed). Files already watched keep
        their last hash; new ones take their current content as the baseline."""
        new = {os.path.abspath(p) for p in paths}
        with self._lock:
            for p in new - self._paths:
                self._hashes[p] = content_hash(p)
                self._stats[p] = _stat(p)
            for p in self._paths - new:
                self._hashes.pop(p, None)
                self._stats.pop(p, None)
            self._paths = new
        self._schedule_dirs()

    def start(self) -> "Watcher":
        if self._use_watchdog:
            self._start_watchdog()
        interval = self._poll_interval or (POLL_SAFETY_S if self.mode == "watchdog" else POLL_ONLY_S)
        for target, name in ((self._debounce_loop, "effects-watch-debounce"),
                             (lambda: self._poll_loop(interval), "effects-watch-poll")):
            t = threading.Thread(target=target, name=name, daemon=True)
            t.start()
            self._threads.append(t)
        return self

    def stop(self) -> None:
        with self._lock:
            self._stopping = True
            self._lock.notify_all()
        if self._observer is not None:
            try:
                self._observer.stop()
                self._observer.join(timeout=2)
            except Exception:  # noqa: BLE001 - shutting down; nothing useful to report
                pass
        for t in self._threads:
            t.join(timeout=2)

    def touched(self, path: str) -> None:
        """Something happened to `path` (an event or a poll saw it): (re)start the debounce."""
        path = os.path.abspath(path)
        with self._lock:
            if path not in self._paths:
                return
            now = time.monotonic()
            if self._first_event is None:
                self._first_event = now
            self._last_event = now
            self._lock.notify_all()

    # -- watchdog

    def _start_watchdog(self) -> None:
        try:
            from watchdog.observers import Observer
            observer = Observer()
            observer.start()
        except Exception:  # noqa: BLE001 - no inotify (limits, odd file systems): poll instead
            return
        self._observer = observer
        self.mode = "watchdog"
        self._schedule_dirs()

    def _schedule_dirs(self) -> None:
        if self._observer is None:
            return
        from watchdog.events import FileSystemEventHandler

        watcher = self

        class _Handler(FileSystemEventHandler):
            def on_any_event(self, event) -> None:  # created, modified, moved, deleted, closed
                if event.is_directory:
                    return
                for p in (event.src_path, getattr(event, "dest_path", "")):
                    if p:
                        watcher.touched(os.fsdecode(p))

        with self._lock:
            dirs = {os.path.dirname(p) for p in self._paths}
        for d in dirs - set(self._watched_dirs):
            if not os.path.isdir(d):
                continue   # the polling thread still sees the file appear
            try:
                self._watched_dirs[d] = self._observer.schedule(_Handler(), d, recursive=False)
            except Exception:  # noqa: BLE001 - e.g. out of inotify watches: polling covers it
                pass
        for d in set(self._watched_dirs) - dirs:
            try:
                self._observer.unschedule(self._watched_dirs.pop(d))
            except Exception:  # noqa: BLE001
                pass

    # -- threads

    def _poll_loop(self, interval: float) -> None:
        """Stat every watched file; a changed (mtime, size, inode) counts as an event. Also
        catches a folder that did not exist when watching started."""
        while True:
            with self._lock:
                if self._stopping:
                    return
                self._lock.wait(interval)
                if self._stopping:
                    return
                paths = list(self._paths)
            for p in paths:
                st = _stat(p)
                with self._lock:
                    if p in self._stats and self._stats[p] != st:
                        self._stats[p] = st
                        changed = True
                    else:
                        changed = False
                if changed:
                    self.touched(p)
            if self._observer is not None:
                self._schedule_dirs()

    def _debounce_loop(self) -> None:
        while True:
            with self._lock:
                while not self._stopping and self._first_event is None:
                    self._lock.wait()
                if self._stopping:
                    return
                now = time.monotonic()
                due = min(self._last_event + self.debounce, self._first_event + self.max_delay)
                if now < due:
                    self._lock.wait(due - now)
                    continue
                self._first_event = None
                paths = list(self._paths)
            changed = []
            for p in paths:
                h, st = content_hash(p), _stat(p)
                with self._lock:
                    if p not in self._hashes:
                        continue
                    self._stats[p] = st
                    if self._hashes[p] != h:
                        self._hashes[p] = h
                        changed.append(p)
            if changed:
                try:
                    self._on_change(sorted(changed))
                except Exception:  # noqa: BLE001 - the callback's problem must not kill watching
                    import traceback
                    traceback.print_exc()


def _stat(path: str) -> tuple | None:
    try:
        st = os.stat(path)
    except OSError:
        return None
    return (st.st_mtime_ns, st.st_size, st.st_ino)


# ---------------------------------------------------------------------------------------------
# What a build produces


@dataclass
class LoadedEffect:
    """An effect ready to draw on one card: what the render thread swaps in.

    `technique` is what is drawn: the forced one when it is valid on the card, else the one
    the card selects (None when no technique is valid). `validations` holds every technique's
    answer in file order. `programs` are the lowered passes of `technique` (None when there is
    nothing to draw); `forced_rejected` is set when a forced technique is not valid here."""

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
    runtime: Any = None        # the effects.runtime.Runtime that prepared it (no back end yet)
    scene_key: Any = None      # BuildSettings.scene_key of the scene it was prepared for

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
                 scene_key: Any = None, **load_options: Any) -> LoadedEffect:
    """Load (unless `previous` is given), validate every technique, select, and prepare the
    chosen one for drawing in `scene` (a Scene, mapping, YAML path or None for the defaults):
    lower its passes with the scene's parameter values, load the textures they sample (into
    the shared cache, so the render thread finds them loaded) and build the vertex streams.

    A forced `technique` is drawn when valid on the card; otherwise the card's selection is
    drawn and `forced_rejected` carries the forced one's reasons. Raises EffectError (located)
    for a broken file, a missing texture, or a pass that cannot be lowered -- the last two are
    kept in `prepare_error` instead with `keep_prepare_error` (a card change: the file is fine,
    the panel shows why this card cannot draw it)."""
    from .loader import load_effect
    from .select import find_valid_technique
    from .validate import validate_technique
    effect = previous if previous is not None else load_effect(path, **load_options)
    validations = [validate_technique(effect, t, profile) for t in effect.techniques]
    chosen = None
    forced_rejected = None
    if technique:
        try:
            forced = effect.technique(technique)
        except (KeyError, EffectError):
            raise EffectError(f"no technique named '{technique}' (the effect has: "
                              f"{', '.join(t.name or '<anonymous>' for t in effect.techniques)})",
                              Location(path, 1, 1)) from None
        v = next(v for v in validations if v.technique is forced)
        if v.ok:
            chosen = forced
        else:
            forced_rejected = v
    if chosen is None:
        chosen = find_valid_technique(effect, profile, policy)
    programs = None
    prepare_error = None
    runtime = None
    if chosen is not None and lower:
        try:
            runtime, programs = prepare(effect, chosen, profile, scene)
        except Exception as exc:  # noqa: BLE001 - a bug of ours must not close the viewer either
            if not keep_prepare_error:
                raise
            prepare_error = exc
    return LoadedEffect(path, effect, profile, validations, chosen, programs, technique,
                        forced_rejected, watched_files(effect), prepare_error, runtime, scene_key)


def prepare(effect: "Effect", technique: "Technique", profile: "CapsProfile",
            scene: Any = None) -> tuple[Any, list["PassProgram"]]:
    """Everything that can fail before a technique draws, done now (off the render thread):
    bind the scene, lower every pass, load the textures the passes sample, build the streams.
    Returns the Runtime that did it (its lowered passes cached, its textures and streams
    loaded; it has no back end) and the lowered passes."""
    from .lower import lower_pass
    from .runtime import Runtime
    runtime = Runtime(effect, profile, scene=scene, backend=None)
    has_diffuse = runtime.geometry().has_diffuse   # lowered as the Runtime will draw them
    programs = [lower_pass(runtime.effect, technique, i, profile, vertex_colors=has_diffuse)
                for i in range(len(technique.passes))]
    for program in programs:
        for binding in program.textures:
            if binding.texture is not None:
                runtime.texture(binding.texture)
    runtime.geometry()
    return runtime, programs


# ---------------------------------------------------------------------------------------------
# Reloader


Build = Callable[["Effect | None"], LoadedEffect]


class Reloader:
    """Rebuild in a worker thread when watched files change; hand results to the render thread.

    `build(previous)` makes a LoadedEffect: with `previous` None it reads the files (a reload),
    with an Effect it only re-selects (after `reselect()`). The render thread calls `poll()`
    (never blocks) and swaps in what it gets. The watcher follows the files of the last good
    build, so a new #include or texture is watched from the next good reload on.
    """

    def __init__(self, path: str, build: Build, *, use_watchdog: bool = True,
                 debounce: float = DEBOUNCE_S, max_delay: float = MAX_DELAY_S,
                 poll_interval: float | None = None) -> None:
        self.path = path
        self._build = build
        self.results: "queue.Queue[ReloadResult]" = queue.Queue()
        self._jobs: "queue.Queue[tuple[str, tuple[str, ...], float] | None]" = queue.Queue()
        self._good: LoadedEffect | None = None
        self._pending_since: float | None = None
        self._pending_lock = threading.Lock()
        self.watcher = Watcher([os.path.abspath(path)], self._files_changed, debounce=debounce,
                               max_delay=max_delay, use_watchdog=use_watchdog,
                               poll_interval=poll_interval)
        self._worker = threading.Thread(target=self._work, name="effects-reload", daemon=True)
        self._started = False

    @property
    def last_good(self) -> LoadedEffect | None:
        return self._good

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
        self._jobs.put(("reload", (), time.perf_counter()))

    def reselect(self) -> None:
        """Select and lower again for the current settings without reading the files (the
        viewer changed card or forced technique)."""
        self._jobs.put(("select", (), time.perf_counter()))

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
        self._jobs.put(("reload", tuple(paths), time.perf_counter()))

    def _work(self) -> None:
        while True:
            job = self._jobs.get()
            if job is None:
                return
            kind, changed, requested = job
            # Coalesce: if more reload jobs queued up meanwhile, one build reads the newest files.
            while True:
                try:
                    nxt = self._jobs.get_nowait()
                except queue.Empty:
                    break
                if nxt is None:
                    return
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


@dataclass
class BuildSettings:
    """What a build depends on besides the files: the card, a forced technique name, the
    selection policy, and the scene the effect will be drawn in."""

    profile: "CapsProfile"
    technique: str | None = None
    policy: Any = "first"
    scene: Any = None
    scene_key: Any = None      # equal keys: the same scene (lets the viewer reuse the Runtime)


def effect_builder(path: str, settings: Callable[[], BuildSettings], **load_options: Any) -> Build:
    """The viewer's build: `settings()` is read when the build runs, so a reload after a card
    change uses the new card. A reload whose technique cannot be prepared fails (the last good
    effect stays); a re-selection keeps the error to show it."""
    def build(previous: "Effect | None") -> LoadedEffect:
        s = settings()
        return build_effect(path, s.profile, technique=s.technique, policy=s.policy,
                            scene=s.scene, previous=previous, scene_key=s.scene_key,
                            keep_prepare_error=previous is not None, **load_options)
    return build
