"""Draw the floors of the house and the imports between them: docs/layers.dot, and
docs/layers.svg from it where Graphviz's `dot` is installed.

    .venv/bin/python docs/make_layers.py            # rewrite docs/layers.dot (and .svg)
    .venv/bin/python docs/make_layers.py --check    # exit 1 when docs/layers.dot is out of date

The floors are the layers contract of pyproject.toml (top floor first; `a | b` are siblings
that may not import each other); the imports are grimp's graph of `effects` and `backends`,
leaving out imports made only for type checkers, as the contracts do. Each arrow is one floor
importing another, labelled with the number of module-to-module imports it stands for. The
outside packages the contracts place (lark, moderngl, rich …) are drawn with the floors that
import them directly. tests/docs/test_generated_docs.py compares docs/layers.dot with what
this script makes; it needs grimp (a test dependency), not Graphviz.
"""
from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
from collections import Counter
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
DOT = DOCS / "layers.dot"
SVG = DOCS / "layers.svg"


def _config() -> dict:
    try:
        import tomllib
    except ImportError:  # Python 3.10: the same parser, as a package
        import tomli as tomllib  # type: ignore[no-redef]
    with open(ROOT / "pyproject.toml", "rb") as f:
        return tomllib.load(f)["tool"]["importlinter"]


def floors(config: dict) -> list[list[str]]:
    """The layers contract's floors, top first, each a list of sibling packages."""
    contract = next(c for c in config["contracts"] if c.get("type") == "layers")
    return [[part.strip() for part in layer.split("|")] for layer in contract["layers"]]


def placed_packages(config: dict) -> list[str]:
    """The outside packages a forbidden contract places (lark, moderngl, rich ...)."""
    found: list[str] = []
    for contract in config["contracts"]:
        if contract.get("type") == "forbidden":
            found += [m for m in contract["forbidden_modules"]
                      if m.split(".")[0] not in ("effects", "backends") and m not in found]
    return found


def _node(module: str, packages: list[str]) -> str | None:
    """The node a module is drawn in: its floor (effects.host.runtime -> host), its back end
    (backends.gl.glsl -> backends.gl), its outside package, or None (not drawn)."""
    parts = module.split(".")
    if parts[0] == "effects":
        return parts[1] if len(parts) > 1 else None   # the package's own __init__: no floor
    if parts[0] == "backends":
        return ".".join(parts[:2]) if len(parts) > 1 else None
    return parts[0] if parts[0] in packages else None


def make_dot() -> str:
    import grimp
    config = _config()
    layers = floors(config)
    packages = placed_packages(config)
    graph = grimp.build_graph("effects", "backends", cache_dir=None, include_external_packages=True,
                              exclude_type_checking_imports=True)
    sizes: Counter[str] = Counter()
    edges: Counter[tuple[str, str]] = Counter()
    for module in graph.modules:
        source = _node(module, packages)
        if source is None or source in packages:
            continue
        sizes[source] += 1
        for imported in graph.find_modules_directly_imported_by(module):
            target = _node(imported, packages)
            if target is not None and target != source:
                edges[source, target] += 1
    out = [
        "// Written by docs/make_layers.py from pyproject.toml's contracts and grimp's import",
        "// graph; do not edit. `dot -Tsvg docs/layers.dot -o docs/layers.svg` draws it.",
        "digraph layers {",
        '  graph [rankdir=TB, nodesep=0.35, ranksep=0.45, fontname="Helvetica", fontsize=11];',
        '  node [shape=box, style="rounded,filled", fillcolor="#eef3fb", fontname="Helvetica", fontsize=11];',
        '  edge [color="#5a6b86", fontname="Helvetica", fontsize=9, fontcolor="#5a6b86", arrowsize=0.6];',
    ]
    for i, floor in enumerate(layers):
        names = " ".join(f'"{name}"' for name in floor)
        out.append(f"  {{ rank=same; {names} }}  // floor {len(layers) - i}")
        for name in floor:
            count = sizes.get(name, 0)
            label = f"{name}\\n{count} module{'s' if count != 1 else ''}"
            out.append(f'  "{name}" [label="{label}"];')
    backends = sorted(n for n in sizes if n.startswith("backends."))
    for name in backends:
        out.append(f'  "{name}" [label="{name}\\n{sizes[name]} modules", fillcolor="#f6efe4"];')
    for name in packages:
        if any(target == name for _, target in edges):
            out.append(f'  "{name}" [shape=ellipse, style="dashed", fillcolor="white", fontsize=10];')
    # invisible arrows from each floor to the next hold the floors in their order on the page
    for upper, lower in zip(layers, layers[1:]):
        out.append(f'  "{upper[0]}" -> "{lower[0]}" [style=invis];')
    for (source, target), count in sorted(edges.items()):
        out.append(f'  "{source}" -> "{target}" [label="{count}"];')
    out.append("}")
    return "\n".join(out) + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="change nothing; exit 1 if layers.dot is out of date")
    args = ap.parse_args(argv)
    text = make_dot()
    current = DOT.read_text(encoding="utf-8") if DOT.exists() else ""
    if args.check:
        print("docs/layers.dot is up to date" if current == text else "docs/layers.dot is out of date")
        return 0 if current == text else 1
    DOT.write_text(text, encoding="utf-8")
    print(f"wrote {DOT.relative_to(ROOT)}")
    dot = shutil.which("dot")
    if dot is None:
        print("no Graphviz `dot` here: docs/layers.svg not drawn (apt-get install graphviz)")
        return 0
    subprocess.run([dot, "-Tsvg", str(DOT), "-o", str(SVG)], check=True)
    print(f"wrote {SVG.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
