"""The floors (docs/architecture.md), checked: import-linter's contracts (pyproject.toml:
every module of `effects` in a named layer, each importing only those below it) and no import
cycle among the modules at all, with nothing whitelisted. Imports made only for type checkers
are left out, as in the contracts."""
from __future__ import annotations

from tests.paths import ROOT

import os
import subprocess
import sys

import grimp

ROOT = str(ROOT)


def test_import_linter_contracts_hold():
    lint = os.path.join(os.path.dirname(sys.executable), "lint-imports")
    run = subprocess.run([lint, "--no-cache"], cwd=ROOT, capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 0, run.stdout[-4000:] + run.stderr[-2000:]
    assert "0 broken" in run.stdout


def _cycles(graph: grimp.ImportGraph, skip: set[tuple[str, str]]) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan), without `skip` edges."""
    modules = sorted(graph.modules)
    edges = {m: sorted(n for n in graph.find_modules_directly_imported_by(m)
                       if (m, n) not in skip) for m in modules}
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in edges[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    sys.setrecursionlimit(max(sys.getrecursionlimit(), 10000))
    for m in modules:
        if m not in index:
            visit(m)
    return found


def test_no_import_cycle():
    graph = grimp.build_graph("effects", "backends", cache_dir=None,
                              exclude_type_checking_imports=True)
    # a package's __init__ re-exporting its children is not a cycle of the spine
    skip = {(m, n) for m in graph.modules for n in graph.modules if n.startswith(m + ".")}
    assert _cycles(graph, skip) == []


def test_the_model_is_data():
    """The model imports nothing above the ground floor: validation, selection and printing
    are functions over it, and `effects.Effect` (effects.api) is where they become methods."""
    graph = grimp.build_graph("effects", cache_dir=None, exclude_type_checking_imports=False)
    assert graph.find_modules_directly_imported_by("effects.model") == {"effects.base.errors"}
    import effects
    effect = effects.load_effect("technique T { pass P { } }")
    assert isinstance(effect, effects.Effect)
    assert effect.validate("T", effects.load_profile("tnt2")).ok
    assert effect.find_valid_technique(effects.load_profile("tnt2")).name == "T"
    assert effects.load_effect(effect.to_source()) == effect
