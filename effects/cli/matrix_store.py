"""Rows of `effects matrix` kept on disk between commands, found by everything that made them.

A row is one effect file's column of the matrix: for each card, the technique it selects, its
passes and every rejected technique's reasons (`report.matrix_job`). Run again over files
that did not change, the command reads its rows back instead of loading and validating the
effects again, as a linter keeps its results per file; a file that changed is loaded and
validated as ever, and its new row kept. Entries live in the command line's store
(`effects.base.disk_store`: the folder, its bounds and safety, `EFFECTS_CACHE=off`).

Correctness: a row is found by the SHA-256 of everything its making read: the effect file's
bytes, its path as given and its real path, the folder the command runs in (paths in reasons
are as given); the cards -- their names, and the bytes of every bundled profile file (a card
may inherit from any of them); the policy, `--strict`, the include root as given and its real
path; every resource limit in force; and the code (`disk_store.fingerprint`). A row is not
kept when it cannot be found again exactly:
- the load read an `#include`: which file an `#include` opens can change while every file the
  load read stays the same (a file created under the letter case the `#include` spells);
- a card named by a YAML path (it may inherit from files outside the bundled folder);
- the effect file or a profile file was written less than two seconds before the command
  read it, or while the row was made (it may be being saved: ccache's rule). A profile file
  is known by its bytes and its inode, size and modification time;
- the load or a card failed (errors are reported by loading again).

A row with fidelity figures (`--fidelity`, `--policy fidelity`: effects.host.fidelity) was
also made from every file its renders named -- the scene, meshes, textures, images a
procedural texture reads (`effects.base.untrusted.recording`, which notes a name also when a
cache supplies its contents): the entry lists them with their SHA-256, and a row whose files
do not all read back the same is a miss. Its key adds the scene as given, the best
technique's name and the measure's size.

What an entry holds is data: the row as JSON, every field checked when read; a file that
does not read back as a row is a miss (and removed).
"""
from __future__ import annotations

import hashlib
import os
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from effects.base import disk_store, limits, untrusted
from effects.base.errors import EffectError

if TYPE_CHECKING:  # pragma: no cover
    from effects.model import Effect


@dataclass(frozen=True)
class MatrixJob:
    """One effect file's rows of `effects matrix`, as a worker process makes them: the cards by
    name (a forked worker finds them loaded; another loads them), the policy as written."""

    path: str
    profiles: tuple[str, ...]
    policy: str = "first"
    include_root: str | None = None
    strict: bool = False
    store_key: str | None = None    # shared_key: where the row is kept (None: not)
    fidelity: bool = False          # measure each card's choice against the best technique
    scene: str | None = None        # the scene the fidelity renders draw (None: the default)
    best: str | None = None         # the technique they are measured against (None: refrast's)
    defines: tuple[tuple[str, str], ...] = ()   # -D NAME=VALUE, in order
    include_dirs: tuple[str, ...] = ()          # -I DIR, in order



FORMAT = 2                        # 2: cells may hold "fidelity"
SETTLED_NS = 2_000_000_000        # a file written this recently may still be being written


@dataclass(frozen=True)
class Inputs:
    """What a job's row is found by, read before its effect is loaded."""

    name: str                      # the entry's name: the SHA-256 of the key
    path: str
    signature: tuple[int, ...]     # the effect file's device, inode, size and mtime when read
    settled: bool                  # written at least SETTLED_NS before it was read


def _signature(path: str) -> tuple[int, ...]:
    st = os.stat(path)
    return st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns


def shared_key(profiles: tuple[str, ...], policy: str, strict: bool,
               include_root: str | None, fidelity: tuple = (),
               preprocessor: tuple = ((), ())) -> str | None:
    """What every row of one command is found by besides its effect file (`MatrixJob.
    store_key`): the code, the limits, the folder, the cards and the options. None: the
    store is off, or a card is named by path (its rows are not kept). `fidelity`: what the
    fidelity figures are measured with besides the scene (`fidelity_options`). `preprocessor`:
    the -D macros and the -I folders (by their real paths)."""
    from effects.base.bundled import PROFILE_FOLDER, names_a_profile_file
    if not disk_store.enabled() or any(names_a_profile_file(n) for n in profiles):
        return None
    from effects.base.errors import ProfileError
    try:
        now = time.time_ns()
        cards = []
        for f in sorted(f for f in os.listdir(PROFILE_FOLDER) if f.endswith(".yaml")):
            path = os.path.join(PROFILE_FOLDER, f)
            signature = _signature(path)
            if now - signature[3] < SETTLED_NS:
                return None
            data = untrusted.read_file(path, "profile", ProfileError, "yaml_bytes")
            cards.append((f, signature, _sha256(data)))
        root = include_root
        return disk_store.digest((
            "effects-matrix-rows", FORMAT, disk_store.fingerprint(),
            tuple((name, limits.get(name)) for name in sorted(limits.LIMITS)), os.getcwd(),
            profiles, tuple(cards), policy, strict, root,
            None if root is None else os.path.realpath(root), fidelity, preprocessor))
    except (OSError, EffectError, disk_store.Unkeyable):
        return None


def preprocessor_options(defines: tuple[tuple[str, str], ...],
                         include_dirs: tuple[str, ...]) -> tuple:
    """The shared key's part for -D and -I: the macros, and the folders by their real paths."""
    return (tuple(defines), tuple(os.path.realpath(d) for d in include_dirs))


def fidelity_options(measured: bool, best: str | None) -> tuple:
    """The shared key's part for fidelity rows: whether measured, against what, at what size
    and by which measure (effects.host.fidelity's constants)."""
    if not measured:
        return ()
    from effects.host import fidelity
    return ("fidelity", best, fidelity.SIZE, fidelity.REFERENCE_CARD, fidelity.SSIM_SIGMA,
            fidelity.DATA_RANGE)


def inputs(job: MatrixJob) -> Inputs | None:
    """The key of `job`'s row, or None: a job whose row is not kept."""
    if job.store_key is None or not disk_store.enabled():
        return None
    try:
        signature = _signature(job.path)
        source = untrusted.read_file(job.path, "effect file", EffectError, "source_bytes")
        name = disk_store.digest(("effects-matrix-row", job.store_key, job.path,
                                  os.path.realpath(job.path), _sha256(source),
                                  job.fidelity, job.scene, job.best))
    except (OSError, EffectError):
        return None
    settled = time.time_ns() - signature[3] >= SETTLED_NS
    return Inputs(name, job.path, signature, settled)


def _sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def stored_row(job: MatrixJob) -> dict | None:
    """The row an earlier command kept for `job`, or None."""
    found = inputs(job)
    if found is None:
        return None
    entry = disk_store.read(found.name)
    if entry is None:
        return None
    try:
        row = _checked_row(entry["row"])
        named = _checked_files(entry.get("files", []))
    except (KeyError, TypeError, ValueError, AttributeError):
        disk_store.discard(found.name)
        return None
    for path, digest in named:      # a file the renders named has changed: made again
        if _file_digest(path) != digest:
            return None
    return row


def _checked_files(files: Any) -> list[tuple[str, str]]:
    if type(files) is not list or any(type(f) is not list or len(f) != 2 or
                                      any(type(x) is not str for x in f) for f in files):
        raise ValueError("bad files")
    return [(f[0], f[1]) for f in files]


def _file_digest(path: str) -> str | None:
    """The SHA-256 of a file a fidelity row's renders named, None when it is not a readable
    regular file (then, too, it is compared as such: a file that appears is a change)."""
    try:
        return _sha256(untrusted.read_file(path, "file", EffectError, "texture_file_bytes"))
    except EffectError:
        return None


def keep(job: MatrixJob, found: Inputs | None, effect: Effect, row: dict,
         named: frozenset[str] | set[str] = frozenset()) -> None:
    """Store `row`, made from `effect` after `found` was read, when it can be found again:
    the load read no other file, and neither the effect file nor a card changed meanwhile.
    `named`: the files the row's renders named (fidelity rows), kept with their digests;
    one written in the last two seconds keeps the row out, as the effect file does."""
    if found is None or not found.settled or list(effect.files) != [found.path]:
        return
    files = []
    now = time.time_ns()
    for path in sorted(named - {os.path.abspath(found.path)}):
        try:
            if now - os.stat(path).st_mtime_ns < SETTLED_NS:
                return
        except OSError:
            pass
        files.append([path, _file_digest(path)])
    if any(digest is None for _, digest in files):
        return
    try:
        if _signature(found.path) != found.signature:   # written while it loaded
            return
    except OSError:
        return
    if shared_key(job.profiles, job.policy, job.strict, job.include_root,
                  fidelity_options(job.fidelity, job.best),
                  preprocessor_options(job.defines, job.include_dirs)) != job.store_key:
        return
    disk_store.write(found.name, {"row": row, "files": files})


def _checked_row(row: Any) -> dict:
    """`row` when it has the shape `report.matrix` gives each effect; else ValueError."""
    if type(row) is not dict or not row:
        raise ValueError("not a row")
    for card, cell in row.items():
        if type(card) is not str or type(cell) is not dict or \
                set(cell) - {"error", "fidelity"} != {"technique", "passes", "rejected"} or \
                type(cell.get("error", "")) is not str:
            raise ValueError("not a cell")
        if "fidelity" in cell:
            _check_figure(cell["fidelity"])
        technique, passes, rejected = cell["technique"], cell["passes"], cell["rejected"]
        if (technique is not None and type(technique) is not str) or type(passes) is not int \
                or type(rejected) is not dict:
            raise ValueError("bad cell")
        for name, reasons in rejected.items():
            if type(name) is not str or type(reasons) is not list or \
                    any(type(r) is not str for r in reasons):
                raise ValueError("bad reasons")
    return row


def _check_figure(figure: Any) -> None:
    """A cell's "fidelity": null, or {"ssim": number, "psnr": number|null, "best": name}."""
    if figure is None:
        return
    if type(figure) is not dict or set(figure) != {"ssim", "psnr", "best"} or \
            type(figure["ssim"]) is not float or type(figure["best"]) is not str or \
            (figure["psnr"] is not None and type(figure["psnr"]) is not float):
        raise ValueError("bad fidelity")
