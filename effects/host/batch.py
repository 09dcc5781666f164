"""Batch work that scales out: independent renders run on a process pool or on Dask.

    cells = run_jobs(render_cell, [CellJob("fxfiles/phong.fx", "geforce3"), ...], jobs=4)

`run_jobs` hands each job to `fn` and returns the results in job order:
- `jobs=1`: in this process, one after another;
- `jobs=N` (default: every core): a `concurrent.futures.ProcessPoolExecutor` of N workers
  (NumPy work holds the GIL between kernels, so processes, not threads, scale it);
- `scheduler="tcp://HOST:PORT"` (or a `distributed.Client`): on an existing Dask distributed
  cluster (the optional extra `effects[dask]`); the jobs and results travel pickled.
`progress(done, total)` is called as jobs finish, in whatever order they finish;
`meanwhile()` once every job is handed out, before the first result is waited for (the
command line imports and sets up what it prints with while the workers run).

`render_cell` is one cell of the contact sheet: the picture a card draws for an effect (the
technique it selects), or why it draws none. A worker loads each effect and card once;
`render_row` draws one effect's cells on one worker, so that what an effect's first cell makes
(its load, compiles and textures: two thirds of a sheet's cold cost) is made once per effect,
not once in every worker that draws one of its cards.
"""
from __future__ import annotations

import os
import threading
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass
from typing import Any, Callable, Iterable, Sequence, TypeVar

from effects.base import caches
from effects.base.errors import EffectError, Location

J = TypeVar("J")
R = TypeVar("R")


def default_jobs() -> int:
    """Every core this process may run on."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover (not Linux)
        return max(1, os.cpu_count() or 1)


def run_jobs(fn: Callable[[J], R], items: Iterable[J], *, jobs: int | None = None,
             scheduler: Any = None,
             progress: Callable[[int, int], None] | None = None,
             meanwhile: Callable[[], None] | None = None) -> list[R]:
    """`[fn(item) for item in items]`, run as the module docstring says."""
    todo = list(items)
    report = progress or (lambda done, total: None)
    handed_out = meanwhile or (lambda: None)
    if scheduler is not None:
        return _on_dask(fn, todo, scheduler, report, handed_out)
    workers = default_jobs() if jobs is None else int(jobs)
    if workers < 1:
        raise ValueError(f"jobs must be at least 1, not {jobs}")
    workers = min(workers, max(1, len(todo)))
    if workers == 1:
        handed_out()
        results = []
        for n, item in enumerate(todo, 1):
            results.append(fn(item))
            report(n, len(todo))
        return results
    out: list[Any] = [None] * len(todo)
    with ProcessPoolExecutor(max_workers=workers, initializer=_share_cores,
                             initargs=(workers,)) as pool:
        # (with the fork start method every worker is forked at the first submit, before the
        # pool's own thread starts: `handed_out` runs after the last fork)
        futures = {pool.submit(fn, item): i for i, item in enumerate(todo)}
        handed_out()
        for n, future in enumerate(as_completed(futures), 1):
            out[futures[future]] = future.result()
            report(n, len(todo))
    return out


def _share_cores(workers: int) -> None:
    """A pool worker's BLAS threads: its share of the cores, not every core. OpenBLAS runs
    a large matrix-vector product on a thread per core and its threads then spin for a while
    waiting for more work, so with a worker per core each worker's spinning threads take the
    others' cores (measured: a 2-worker contact sheet 10-20 % slower than with one BLAS
    thread a worker, at more CPU). Dask's workers have one already (its nanny sets
    OPENBLAS_NUM_THREADS=1)."""
    from threadpoolctl import threadpool_limits
    threadpool_limits(limits=max(1, default_jobs() // workers), user_api="blas")


def _on_dask(fn: Callable[[J], R], todo: Sequence[J], scheduler: Any,
             report: Callable[[int, int], None], handed_out: Callable[[], None]) -> list[R]:
    try:
        from distributed import Client, as_completed as dask_completed
    except ImportError:
        raise EffectError("--scheduler needs Dask distributed: pip install 'effects[dask]'",
                          Location("<scheduler>", 1, 1)) from None
    own = not isinstance(scheduler, Client)
    try:
        client = Client(scheduler, timeout=10) if own else scheduler
    except (OSError, TimeoutError, ValueError) as exc:
        raise EffectError(f"cannot reach the Dask scheduler {scheduler}: {exc}",
                          Location("<scheduler>", 1, 1)) from None
    try:
        futures = client.map(fn, list(todo), pure=False)
        handed_out()
        index = {f.key: i for i, f in enumerate(futures)}
        out: list[Any] = [None] * len(todo)
        for n, future in enumerate(dask_completed(futures), 1):
            out[index[future.key]] = future.result()
            report(n, len(todo))
        return out
    finally:
        if own:
            client.close()


# --------------------------------------------------------------------------------------------
# One cell of the contact sheet


@dataclass(frozen=True)
class CellJob:
    effect: str                      # path of the .fx file
    profile: str                     # card name or YAML path
    size: tuple[int, int] = (96, 96)
    scene: str | None = None         # scene YAML path, or None for the default scene
    backend: str = "numpy"
    policy: str = "first"
    # how the effect is loaded: the command's --include-root (which confines every file the
    # render reads too: textures, meshes), -D and -I
    include_root: str | None = None
    defines: tuple[tuple[str, str], ...] = ()
    include_dirs: tuple[str, ...] = ()


@dataclass(frozen=True)
class Cell:
    """What a card draws: `image` (H x W x 4 uint8) and the technique, or `reason` (text)."""

    effect: str
    profile: str
    technique: str | None
    image: Any = None
    reason: str | None = None
    # what the picture shows nothing of, reported (`effects.host.diagnostics`)
    diagnostics: tuple[str, ...] = ()


def render_row(cells: Sequence[CellJob]) -> list[Cell]:
    """`render_cell` of each of `cells` (one effect's, as the sheet gives them), in order."""
    return [render_cell(job) for job in cells]


# unbounded before; a loaded effect holds 24-144 KB (tracemalloc: the bundled ones)
_EFFECTS = caches.declare("host.batch_effects", keys="an effect file's absolute path, "
                          "modification time and load options", entry_bytes=256 << 10, max_bytes=64 << 20)


def _effect(job: CellJob):
    """The effect of `job`, loaded once per worker (again when the file changes)."""
    from effects.frontend.loader import load_effect
    key = (os.path.abspath(job.effect), os.stat(job.effect).st_mtime, job.include_root,
           job.defines, job.include_dirs)
    return _EFFECTS.get_or_make(key, lambda: load_effect(
        job.effect, defines=dict(job.defines), include_dirs=list(job.include_dirs),
        include_root=job.include_root))


_LOCAL = threading.local()


def _backend(name: str) -> Any:
    """A back end of this thread's own: a back end holds the frame being drawn, and a Dask
    worker runs several cells at once on threads. The NumPy one shades on one thread, as the
    pool already keeps every core busy."""
    backends = getattr(_LOCAL, "backends", None)
    if backends is None:
        backends = _LOCAL.backends = {}
    if name not in backends:
        from effects.program.backend import create_backend
        try:
            backends[name] = create_backend(name, threads=1) if name in ("numpy", "reference") \
                else create_backend(name)
        except EffectError:
            raise
        except Exception as exc:  # no GL context, a missing driver
            raise EffectError(f"cannot start the {name!r} back end: {type(exc).__name__}: {exc}",
                              Location("<backend>", 1, 1)) from None
    return backends[name]


def render_cell(job: CellJob) -> Cell:
    """The picture `job.profile` draws for `job.effect`, or the reason it draws none (the first
    reason of the first technique, or the error the render raised)."""
    from effects.d3d9.caps import load_profile
    from effects.base.errors import NoValidTechnique
    from effects.host.runtime import render_frame
    try:
        effect = _effect(job)
        profile = load_profile(job.profile)
        from effects.host.fidelity import policy_for   # pictures for the fidelity order only
        frame = render_frame(effect, profile, backend=_backend(job.backend), scene=job.scene,
                             size=job.size, policy=policy_for(effect, job.policy, scene=job.scene),
                             diagnose=True)
    except NoValidTechnique as exc:
        reasons = [r for rs in exc.reasons.values() for r in rs]
        why = str(reasons[0]) if reasons else str(exc).splitlines()[0]
        return Cell(job.effect, job.profile, None, reason=why)   # the first reason, as cells are small
    except (EffectError, OSError) as exc:
        return Cell(job.effect, job.profile, None, reason=str(exc).splitlines()[0])
    return Cell(job.effect, job.profile, frame.technique.name or "<anonymous>", image=frame.image,
                diagnostics=tuple(w.report() for w in frame.diagnostics))
