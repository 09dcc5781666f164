"""The on-disk compile store (effects/shaders/hlsl/store.py, in effects/base/disk_store.py's folder): a stored shader is the shader a
compile makes (every field, every location of its program), keys follow every input and no
other, hold across processes, and the folder is private, bounded and robust to bad files."""
from __future__ import annotations

from tests.paths import ROOT

import dataclasses
import glob
import json
import os
import subprocess
import sys

import numpy as np
import pytest

from effects.base import disk_store, limits
from effects.base.errors import EffectError
from effects.api import load_effect
from effects.model import CompileShader
from effects.shaders.hlsl import cache, store
from effects.shaders.hlsl.compiler import compile_shader

ROOT = str(ROOT)
FILES = sorted(glob.glob(os.path.join(ROOT, "fxfiles", "*.fx"))) + \
    sorted(glob.glob(os.path.join(ROOT, "tests", "data", "**", "*.fx"), recursive=True)) + \
    [os.path.join(ROOT, "benchmarks", "data", "lighting_ps20.fx")]


def _states(effect):
    seen = set()
    for t in effect.techniques:
        for p in t.passes:
            for a in p.states:
                if isinstance(a.value, CompileShader) and id(a.value) not in seen:
                    seen.add(id(a.value))
                    yield a.value


_BROKEN = """
float4 Bad(float2 uv : TEXCOORD0) : COLOR { return undeclared * uv.x; }
float4 Fine() : COLOR { return 1; }
technique A { pass P { PixelShader = compile ps_2_0 Missing(); } }
technique B { pass P { PixelShader = compile ps_2_0 Bad(); } }
technique C { pass P { PixelShader = compile ps_2_0 Fine(7); } }
"""


def _loadable():
    for path in FILES:
        try:
            yield path, load_effect(path)
        except EffectError:
            continue
    yield "<broken>", load_effect(_BROKEN)


def _same(a, b, path="", seen=None):
    """Deep equality of two object graphs, fields that dataclass equality skips included
    (locations, texts): what a caller can read from either is the same."""
    seen = set() if seen is None else seen
    if (id(a), id(b)) in seen:
        return
    seen.add((id(a), id(b)))
    assert type(a) is type(b), path
    if isinstance(a, np.ndarray):
        assert a.dtype == b.dtype and np.array_equal(a, b), path
    elif isinstance(a, (list, tuple)):
        assert len(a) == len(b), path
        for i, (x, y) in enumerate(zip(a, b)):
            _same(x, y, f"{path}[{i}]", seen)
    elif isinstance(a, dict):
        assert list(a) == list(b), path
        for k in a:
            _same(a[k], b[k], f"{path}.{k}", seen)
    elif hasattr(a, "__dict__") and not isinstance(a, type):
        keys = {k for k in vars(a) if not k.startswith("_")} | {k for k in vars(b) if not k.startswith("_")}
        for k in sorted(keys):
            _same(getattr(a, k, None), getattr(b, k, None), f"{path}.{k}", seen)
    else:
        assert a == b, path


def _key(effect, value):
    return store.key(cache.key_parts(effect, value, []), cache.declarations(effect), value.location)


def test_a_stored_shader_is_the_compiled_shader(tmp_path):
    """Every compile state of the bundled, test and benchmark effects: written out and read
    back, the shader equals a fresh compile field by field, its program instruction by
    instruction with every location; errors come back as the same class, message and place."""
    assert disk_store.enable(str(tmp_path))
    try:
        shaders = errors = 0
        for path, effect in _loadable():
            for value in _states(effect):
                try:
                    fresh = compile_shader(effect, value.function, value.profile, value.args,
                                           value.location)
                except EffectError as err:
                    fresh = err
                name = _key(effect, value)
                assert name is not None, (path, value.function)
                store.save(name, fresh)
                back = store.load(name)
                assert back is not None, (path, value.function)
                if isinstance(fresh, EffectError):
                    errors += 1
                    assert type(back) is type(fresh) and str(back) == str(fresh)
                    assert back.source_line == fresh.source_line
                else:
                    shaders += 1
                    assert back is not fresh
                    _same(fresh, back, f"{path}:{value.function}")
        assert shaders >= 40 and errors >= 1, (shaders, errors)
    finally:
        disk_store.disable()


def _wood():
    return load_effect(os.path.join(ROOT, "fxfiles", "wood.fx"))


def test_keys_follow_every_input_and_only_those():
    effect = _wood()
    value = next(_states(effect))
    first = _key(effect, value)
    assert first == _key(_wood(), next(_states(_wood())))       # a fresh load: the same key
    # the entry's own text
    f = next(f for f in effect.functions if f.name == value.function)
    edited = dataclasses.replace(f, source=f.source.replace("{", "{ ", 1))
    effect.functions[effect.functions.index(f)] = edited
    assert _key(effect, value) != first
    effect.functions[effect.functions.index(edited)] = f
    assert _key(effect, value) == first
    # any other declaration (fxc compiles the whole file: one that does not parse fails all)
    other = next(g for g in effect.functions if g.name != value.function)
    effect.functions.append(dataclasses.replace(other, name="Unrelated", source="float Unrelated() { return 1; }"))
    assert _key(effect, value) != first
    effect.functions.pop()
    # a resource limit
    with limits.raised(shader_loop_iterations=limits.get("shader_loop_iterations") + 1):
        assert _key(effect, value) != first
    # the compile state's place (errors are located there)
    moved = dataclasses.replace(value, location=dataclasses.replace(value.location, line=value.location.line + 1)) \
        if dataclasses.is_dataclass(value.location) else None
    if moved is None:
        from effects.base.errors import Location
        moved = dataclasses.replace(value, location=Location(value.location.path, value.location.line + 1, 1))
    assert _key(effect, moved) != first
    # the compiling code
    held = disk_store._state["fingerprint"]
    try:
        disk_store._state["fingerprint"] = "another version"
        assert _key(effect, value) != first
    finally:
        disk_store._state["fingerprint"] = held
    assert _key(effect, value) == first


def test_keys_are_the_same_in_every_process():
    """String hashing differs between processes; the key does not (the walk's order is sorted
    out of it)."""
    code = ("import os, sys; sys.path.insert(0, os.getcwd()); from tests.shaders.hlsl.test_hlsl_store import _wood, _states, _key; "
            "e = _wood(); print([_key(e, v) for v in _states(e)])")
    outs = set()
    for seed in ("1", "2", "3"):
        env = dict(os.environ, PYTHONHASHSEED=seed)
        outs.add(subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=env, check=True,
                                capture_output=True, text=True).stdout)
    assert len(outs) == 1 and "None" not in outs.pop()


def test_bad_files_are_misses_and_removed(tmp_path):
    assert disk_store.enable(str(tmp_path))
    try:
        effect = _wood()
        value = next(_states(effect))
        name = _key(effect, value)
        store.save(name, compile_shader(effect, value.function, value.profile, value.args, value.location))
        path = tmp_path / f"{name}.json"
        good = path.read_bytes()
        data = json.loads(good)
        for bad in (b"", b"{", b"\x00" * 10, json.dumps({**data, "entry": "0" * 64}).encode(),
                    json.dumps({**data, "lines": "x"}).encode(),
                    json.dumps({**data, "text": data["text"] + "bogus r0, r1\n"}).encode(),
                    json.dumps({"entry": name, "error": "SystemExit", "message": "x",
                                "location": None, "source_line": None}).encode(),
                    b" " * (disk_store.MAX_ENTRY_BYTES + 1)):
            path.write_bytes(bad)
            assert store.load(name) is None
            assert not path.exists()
        path.write_bytes(good)
        assert store.load(name) is not None
    finally:
        disk_store.disable()


def test_the_folder_must_be_private(tmp_path):
    open_folder = tmp_path / "open"
    open_folder.mkdir()
    os.chmod(open_folder, 0o777)
    assert not disk_store.enable(str(open_folder)) and not disk_store.enabled()
    link = tmp_path / "link"
    link.symlink_to(tmp_path / "private")
    assert not disk_store.enable(str(link)) and not disk_store.enabled()
    made = tmp_path / "made" / "here"
    assert disk_store.enable(str(made)) and oct(os.stat(made).st_mode & 0o777) == "0o700"
    disk_store.disable()


def test_off_switch(tmp_path, monkeypatch):
    monkeypatch.setenv("EFFECTS_CACHE", "off")
    assert not disk_store.enable(str(tmp_path))


def test_bounded(tmp_path, monkeypatch):
    monkeypatch.setattr(disk_store, "MAX_ENTRIES", 8)
    assert disk_store.enable(str(tmp_path))
    try:
        effect = _wood()
        value = next(_states(effect))
        shader = compile_shader(effect, value.function, value.profile, value.args, value.location)
        for k in range(30):
            store.save(f"{k:064x}", shader)
            assert len(list(tmp_path.glob("*.json"))) <= 8
        assert store.load(f"{29:064x}") is not None          # the newest stays
    finally:
        disk_store.disable()


def test_writes_count_the_folder_only_when_due(tmp_path, monkeypatch):
    """A write scans the folder at a process's first write, then only when a bound or the
    rescan interval comes near; entries other processes add are seen at that rescan."""
    monkeypatch.setattr(disk_store, "MAX_ENTRIES", 8)
    monkeypatch.setattr(disk_store, "RESCAN_WRITES", 3)
    scans = []
    real = disk_store._prune
    monkeypatch.setattr(disk_store, "_prune", lambda folder: scans.append(1) or real(folder))
    assert disk_store.enable(str(tmp_path))
    try:
        disk_store.write("a" * 64, {"k": 0})
        disk_store.write("b" * 64, {"k": 1})
        disk_store.write("c" * 64, {"k": 2})
        assert len(scans) == 1                        # the first write only
        for k in range(10):                           # another process fills the folder
            (tmp_path / f"{k:064x}.json").write_text("{}")
        disk_store.write("d" * 64, {"k": 3})          # the third write since: a rescan
        assert len(scans) == 2 and len(list(tmp_path.glob("*.json"))) <= 8
    finally:
        disk_store.disable()


def _command(cache_dir, *args):
    env = dict(os.environ, EFFECTS_CACHE_DIR=str(cache_dir))
    code = ("import sys, runpy; sys.argv = ['effects', *sys.argv[1:]]\n"
            "from effects.cli.main import main\n"
            "rc = main(sys.argv[1:])\n"
            "print('COMPILER', 'effects.shaders.hlsl.compiler' in sys.modules, file=sys.stderr)\n"
            "sys.exit(rc)")
    return subprocess.run([sys.executable, "-c", code, *args], cwd=ROOT, env=env,
                          capture_output=True, text=True)


def test_the_command_cold_and_warm(tmp_path):
    """`effects matrix` prints the same table and JSON with an empty store, a filled one, and
    without one (on worker processes); the warm run compiles nothing (the compiler is not even
    imported: --jobs 1 validates in the process that says so). The warm run names every card,
    in the order the default takes them: the same matrix, but not the rows the cold run kept
    (matrix_store), so its effects are loaded and validated again."""
    from effects.d3d9.caps import list_profiles
    files = sorted(os.path.relpath(f, ROOT) for f in glob.glob(os.path.join(ROOT, "fxfiles", "*.fx")))
    cards = [a for name in list_profiles() for a in ("-p", name)]
    for n, extra in enumerate(([], ["--json"])):
        cold = _command(tmp_path / str(n), "matrix", *files, *extra, "--jobs", "1")
        warm = _command(tmp_path / str(n), "matrix", *files, *extra, *cards, "--jobs", "1")
        off = subprocess.run([sys.executable, "-m", "effects", "matrix", *files, *extra], cwd=ROOT,
                             env=dict(os.environ, EFFECTS_CACHE="off"), capture_output=True,
                             text=True)
        assert cold.returncode == warm.returncode == off.returncode == 0
        assert cold.stdout == warm.stdout == off.stdout
        assert "COMPILER True" in cold.stderr and "COMPILER False" in warm.stderr
    assert len(list((tmp_path / "0").glob("*.json"))) >= 10
