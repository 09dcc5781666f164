"""Cut the fx_2_0 effect binaries (fxc /Tfx_2_0, magic 0xfeff0901) out of Wine's
dlls/d3dx9_36/tests/effect.c into wine/NAME.fxo, and the HLSL source Wine keeps beside each
(the `#if 0 ... #endif` block right before the array) into wine/NAME.fx, byte for byte; then
print the manifest rows (tests/data/fxo/MANIFEST.md). Run by hand on the Debian copy:
`python tests/data/fxo/extract_wine.py wine-8.0/dlls/d3dx9_36/tests/effect.c`."""
from __future__ import annotations

import hashlib
import re
import sys
from pathlib import Path

from effects.shaders.d3dbc import read_header

HERE = Path(__file__).parent / "wine"
MAGIC = 0xFEFF0901
# `#if 0`, its lines (no other #if/#endif), `#endif`, then (blank lines only) the array's
# declaration; or the declaration, its brace, then the block (Wine writes both)
_BLOCK = r"#if 0\n((?:(?!#if|#endif).)*)#endif\n"
_DECL = r"(?:static\s+)?const\s+DWORD\s+(\w+)\s*\[\s*\]\s*="
SOURCE_BEFORE = re.compile(_BLOCK + r"\s*" + _DECL, re.S)
SOURCE_INSIDE = re.compile(_DECL + r"\s*\{\s*" + _BLOCK, re.S)


def extract(text: str) -> list[tuple[str, bytes, str | None]]:
    sources = {m.group(2): m.group(1) for m in SOURCE_BEFORE.finditer(text)}
    sources.update({m.group(1): m.group(2) for m in SOURCE_INSIDE.finditer(text)})
    return [(name, data, sources.get(name)) for name, data in read_header(text)
            if len(data) >= 4 and int.from_bytes(data[:4], "little") == MAGIC]


def main(path: str) -> None:
    raw = Path(path).read_bytes()
    text = raw.decode("latin-1")
    HERE.mkdir(exist_ok=True)
    print(f"effect.c sha256 {hashlib.sha256(raw).hexdigest()}")
    for name, data, source in extract(text):
        (HERE / f"{name}.fxo").write_bytes(data)
        line = text[:text.index(f" {name}[]")].count("\n") + 1
        fx = ""
        if source is not None:
            (HERE / f"{name}.fx").write_bytes(source.encode("latin-1"))
            fx = f"`wine/{name}.fx` `{hashlib.sha256(source.encode('latin-1')).hexdigest()}`"
        print(f"| `wine/{name}.fxo` | `{name}` (line {line}) | {len(data)} | "
              f"`{hashlib.sha256(data).hexdigest()}` | {fx or 'none given'} |")


if __name__ == "__main__":
    main(sys.argv[1])
