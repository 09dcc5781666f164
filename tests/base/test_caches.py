"""The one cache policy (effects.base.caches): every cache declared by name, bounded by bytes,
least recently used out first, listed and cleared through one registry."""
from __future__ import annotations

import importlib
import os
import pkgutil

import numpy as np
import pytest

import effects
from effects.base import caches, disk_store
from tests.paths import ROOT

# Every cache of the package and its back ends, by name (LAYER.WHAT). A new cache is declared
# through effects.base.caches and named here.
DECLARED = [
    "assets.brdf_factors", "assets.procedural",
    "base.yaml_tags",
    "d3d9.cap_bits", "d3d9.profile_folders", "d3d9.profiles", "d3d9.state_keys", "d3d9.state_rows",
    "disk_store",
    "frontend.type_names",
    "host.batch_effects", "host.fidelity_meters", "host.matrix_semantics", "host.meshes",
    "host.name_semantics",
    "host.projection_matrices", "host.selections", "host.texture_files", "host.view_matrices",
    "lower.passes", "lower.shader_ir",
    "reference.clip_planes", "reference.demand", "reference.flow", "reference.levels",
    "reference.pyramids", "reference.split", "reference.steps", "reference.varyings_read",
    "shaders.asm.programs", "shaders.asm.registers", "shaders.asm.swizzles",
    "shaders.hlsl.builtin_types", "shaders.hlsl.compiles", "shaders.hlsl.declaration_loads",
    "shaders.hlsl.field_names",
    "shaders.hlsl.first_characters", "shaders.hlsl.identifiers", "shaders.hlsl.lanes",
    "shaders.hlsl.lexer_patterns", "shaders.hlsl.stored", "shaders.hlsl.trees",
    "shaders.hlsl.types", "shaders.hlsl.unit_checks",
    "validate.enum_spellings",
]


def _import_everything() -> None:
    import backends
    for package in (effects, backends):
        for found in pkgutil.walk_packages(package.__path__, package.__name__ + "."):
            if not found.name.endswith("__main__"):    # that one runs the command line
                importlib.import_module(found.name)


def test_every_cache_is_declared_by_name_with_its_keys_and_a_bound_in_bytes():
    _import_everything()
    rows = effects.cache_report()
    assert [r.name for r in rows] == DECLARED
    for r in rows:
        assert r.keys and r.max_bytes > 0, r.name
        assert r.kind == "disk" if r.name == "disk_store" else r.kind in ("memory", "memo")
        assert 0 <= r.bytes and 0 <= r.entries, r.name


def test_a_cache_is_bounded_by_bytes_least_recently_used_first():
    kept = caches.Cache("test.kept", "a letter", max_bytes=3 * 1024 + 3 * caches.OBJECT_BYTES,
                        size_of=caches.nbytes)
    for key in "abc":
        kept.put(key, np.zeros(256, np.float32))          # 1 KiB each
    assert kept.get("a") is not None                       # a is now the most recent
    kept.put("d", np.zeros(256, np.float32))               # b, the least recent, goes
    assert "b" not in kept and all(k in kept for k in "acd")
    assert kept.bytes == 3 * (1024 + caches.OBJECT_BYTES)
    kept.put("huge", np.zeros(4096, np.float32))           # bigger than the bound: not kept
    assert "huge" not in kept and len(kept) == 3
    assert kept.get_or_make("e", lambda: np.ones(2)) is kept.get("e")
    assert kept.stats() == caches.CacheStats("test.kept", "memory", "a letter", 3, kept.bytes,
                                             kept.max_bytes, hits=2, misses=1)
    kept.clear()
    assert (len(kept), kept.bytes, kept.hits, kept.misses) == (0, 0, 0, 0)


def test_sizes_are_the_arrays_a_value_holds_or_a_declared_estimate(monkeypatch):
    monkeypatch.setattr(caches, "_REGISTRY", dict(caches._REGISTRY))
    pair = (np.zeros((6, 16, 16)), np.zeros((6, 16, 16)))
    assert caches.nbytes(pair) == 2 * 6 * 16 * 16 * 8 + caches.OBJECT_BYTES
    assert caches.nbytes({"a": [np.zeros(10, np.uint8)]}) == 10 + caches.OBJECT_BYTES
    estimated = caches.declare("test.estimated", keys="anything", entry_bytes=100, max_bytes=250)
    for k in range(3):
        estimated.put(k, "value")
    assert (len(estimated), estimated.bytes) == (2, 200)          # the first one went
    assert caches.named("test.estimated") is estimated


def test_a_memo_keeps_max_bytes_over_entry_bytes_results(monkeypatch):
    monkeypatch.setattr(caches, "_REGISTRY", dict(caches._REGISTRY))
    calls = []

    @caches.memo("test.memo", keys="x", entry_bytes=64, max_bytes=128)
    def square(x):
        calls.append(x)
        return x * x

    assert [square(2), square(2), square(3), square(4), square(2)] == [4, 4, 9, 16, 4]
    assert calls == [2, 3, 4, 2]                     # 2 was the least recent when 4 came
    row = caches.named("test.memo").stats()
    assert (row.kind, row.entries, row.bytes, row.hits, row.misses) == ("memo", 2, 128, 1, 4)
    caches.clear("test.memo")
    assert caches.named("test.memo").stats().entries == 0


def test_a_render_fills_the_caches_it_uses_and_clear_gives_them_back():
    fx = effects.load_effect(str(ROOT / "fxfiles" / "phong.fx"))
    card = effects.load_profile("radeon9700")
    effects.clear_caches()
    first = effects.render(fx, card, size=(16, 16))
    second = effects.render(fx, card, size=(16, 16))
    assert np.array_equal(first, second)
    rows = {r.name: r for r in effects.cache_report()}
    # the second render finds the selection and its lowered pass (each made once)
    for name in ("host.selections", "lower.passes"):
        assert (rows[name].entries, rows[name].hits, rows[name].misses) == (1, 1, 1), name
    assert rows["host.texture_files"].bytes > 0
    effects.clear_caches()
    rows = {r.name: r for r in effects.cache_report()}
    assert all(r.entries == 0 for r in rows.values() if r.kind != "disk")
    with pytest.raises(KeyError):
        effects.clear_caches("no.such.cache")


def test_the_disk_store_is_listed_and_cleared_only_when_named(tmp_path):
    assert disk_store.enable(str(tmp_path))
    try:
        disk_store.write("a" * 64, {"row": [1, 2, 3]})
        assert disk_store.read("a" * 64)["row"] == [1, 2, 3]
        assert disk_store.read("b" * 64) is None
        row = caches.named("disk_store").stats()
        size = os.path.getsize(tmp_path / f"{'a' * 64}.json")
        assert (row.kind, row.entries, row.bytes, row.max_bytes) == ("disk", 1, size,
                                                                     disk_store.MAX_BYTES)
        assert row.hits >= 1 and row.misses >= 1
        effects.clear_caches()                              # the in-memory ones only
        assert os.listdir(tmp_path) == [f"{'a' * 64}.json"]
        effects.clear_caches("disk_store")
        assert os.listdir(tmp_path) == []
        assert caches.named("disk_store").stats().entries == 0
    finally:
        disk_store.disable()
