"""Watch files for content changes: watchdog events plus a polling fallback, debounced.

`Watcher` watches the folders of a set of files with watchdog (created, modified, moved and
deleted events, so an editor's atomic save -- write `x.tmp`, rename it onto `x` -- counts; it
arrives as `created x.tmp` ... `moved x.tmp -> x`, never as `modified x`), plus a polling
thread as the fallback (the only mechanism when watchdog cannot start, a slow safety net
otherwise). Events are debounced: the change is reported once the files have been quiet for
`debounce` seconds (`settle` seconds when the last event ends a save: the writer closed the
file, or renamed its temporary file onto it), or at the latest `max_delay` after the first
event, so autosave cannot starve it. A change is reported only for files whose content hash
(`content_hash`) differs from the last one seen, so a save without edits, a `touch`, or a burst that ends where it
began does nothing. `effects.viewer.reload` builds hot reload on top of this
(docs/design.md habit 11).
"""
from __future__ import annotations

import hashlib
import os
import threading
import time
from typing import Any, Callable, Iterable

# Quiet time before a change counts. One save's events (truncate, write, close; or create a temp
# file, write, rename) arrive within a millisecond or two, so 10 ms groups them while keeping
# the edit-to-picture latency low; a writer slower than that shows as a failed reload followed
# by a good one (the last good effect stays on screen meanwhile).
DEBOUNCE_S = 0.010
# ... unless the last event says a save is complete -- the writer closed the file it wrote
# (inotify's IN_CLOSE_WRITE) or renamed its temporary file onto it: then only this long, for
# the events that follow a save at once (a second file of a save-all, an editor's chmod)
SETTLE_S = 0.002
MAX_DELAY_S = 0.25        # ... but never wait longer than this after the first event
POLL_ONLY_S = 0.1         # polling interval when watchdog is not available
POLL_SAFETY_S = 1.0       # polling interval as a safety net beside watchdog


def content_hash(path: str) -> str | None:
    """BLAKE2 digest of a file's bytes; None when it cannot be read (missing, mid-rename)."""
    try:
        with open(path, "rb") as f:
            return hashlib.blake2b(f.read(), digest_size=16).hexdigest()
    except OSError:
        return None


class Watcher:
    """Report changed files, debounced and filtered by content hash, to `on_change(paths)`.

    `on_change` runs on the watcher's own thread with the absolute paths whose content hash
    changed since the last report (a file that vanished has hash None: that is a change too).
    `mode` says what watches: 'watchdog' (with a polling safety net) or 'polling'.
    """

    def __init__(self, paths: Iterable[str], on_change: Callable[[list[str]], None], *,
                 debounce: float = DEBOUNCE_S, max_delay: float = MAX_DELAY_S,
                 settle: float = SETTLE_S, use_watchdog: bool = True,
                 poll_interval: float | None = None) -> None:
        self._on_change = on_change
        self.debounce = debounce
        self.settle = min(settle, debounce)
        self.max_delay = max(max_delay, debounce)
        self._use_watchdog = use_watchdog
        self._poll_interval = poll_interval
        self._lock = threading.Condition()
        self._paths: set[str] = set()
        self._hashes: dict[str, str | None] = {}
        self._stats: dict[str, tuple | None] = {}
        self._first_event: float | None = None   # monotonic time of the first pending event
        self._last_event = 0.0
        self._saved = False                      # the last event ended a save
        self._stopping = False
        self._stop_polling = threading.Event()
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
        self._stop_polling.set()
        if self._observer is not None:
            try:
                self._observer.stop()
                self._observer.join(timeout=2)
            except Exception:  # noqa: BLE001 - shutting down; nothing useful to report
                pass
        for t in self._threads:
            t.join(timeout=2)

    def touched(self, path: str, saved: bool = False) -> None:
        """Something happened to `path` (an event or a poll saw it): (re)start the debounce.
        `saved`: the event ends a save (closed after writing, or renamed onto `path`)."""
        path = os.path.abspath(path)
        with self._lock:
            if path not in self._paths:
                return
            now = time.monotonic()
            if self._first_event is None:
                self._first_event = now
            self._last_event = now
            self._saved = saved
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
        from watchdog.events import (FileClosedEvent, FileCreatedEvent, FileDeletedEvent,
                                     FileModifiedEvent, FileMovedEvent, FileSystemEventHandler)

        watcher = self
        # Only what changes content: an open or a read-only close (this watcher's own hashing,
        # the reload reading the effect) would restart the debounce, whose hashing reads the
        # file again -- a re-hash every `debounce` seconds for as long as the watcher runs.
        changes = [FileCreatedEvent, FileModifiedEvent, FileMovedEvent, FileDeletedEvent,
                   FileClosedEvent]

        class _Handler(FileSystemEventHandler):
            def on_any_event(self, event) -> None:  # created, modified, moved, deleted, closed
                if event.is_directory:
                    return
                dest = getattr(event, "dest_path", "")
                watcher.touched(os.fsdecode(event.src_path), event.event_type == "closed")
                if dest:                              # renamed onto a watched file: saved
                    watcher.touched(os.fsdecode(dest), True)

        with self._lock:
            dirs = {os.path.dirname(p) for p in self._paths}
        for d in dirs - set(self._watched_dirs):
            if not os.path.isdir(d):
                continue   # the polling thread still sees the file appear
            try:
                self._watched_dirs[d] = self._observer.schedule(_Handler(), d, recursive=False,
                                                                event_filter=changes)
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
            # its own event, not the lock's condition: every `touched` notifies that one, and a
            # poll woken by watchdog's event would report the same change again, as not saved
            if self._stop_polling.wait(interval):
                return
            with self._lock:
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
                quiet = self.settle if self._saved else self.debounce
                due = min(self._last_event + quiet, self._first_event + self.max_delay)
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
