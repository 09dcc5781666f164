"""Shader bytecode as a C header, as fxc /Fh writes it (the listing in `#if 0`, then
`const BYTE g_ps20_main[] = { ... };`), and back: the arrays of such a header, BYTE (newer
SDKs) or DWORD (older ones, `const DWORD g_ps11_main[] = { 0xffff0101, ... }`)."""
from __future__ import annotations

import re

from effects.base.errors import Location
from effects.shaders.d3dbc.reader import BytecodeError

_ARRAY = re.compile(r"(?:const\s+)?(?:static\s+)?(?:const\s+)?(BYTE|DWORD|uint8_t|uint32_t|"
                    r"unsigned\s+char|unsigned\s+int|char|int)\s+(\w+)\s*\[\s*\w*\s*\]\s*=\s*\{",
                    re.S)
_NUMBER = re.compile(r"0[xX][0-9a-fA-F]+|\d+")
_WIDTH = {"BYTE": 1, "uint8_t": 1, "unsigned char": 1, "char": 1}


def variable_name(target: str, entry: str) -> str:
    """fxc's default /Vn: g_ps20_main for ps_2_0's `main`."""
    return f"g_{target.replace('_', '')}_{entry}"


def write_header(data: bytes, name: str, listing: str = "") -> str:
    """The C header fxc /Fh writes for `data`: the listing commented out, then the bytes."""
    lines = ["#if 0", *listing.rstrip("\n").splitlines(), "#endif", "",
             f"const BYTE {name}[] =", "{"]
    numbers = [f"{b:3d}" for b in data]
    rows = [", ".join(numbers[k:k + 16]) for k in range(0, len(numbers), 16)]
    lines += [f"    {row}," if k + 1 < len(rows) else f"    {row}" for k, row in enumerate(rows)]
    return "\n".join(lines + ["};", ""])


def read_header(text: str, path: str = "<header>") -> list[tuple[str, bytes]]:
    """(name, bytes) of every array in a C header of shader bytecode, in file order. Raises
    BytecodeError, located at the array, for a number that does not fit its element type or
    an array without its closing brace."""
    out = []
    code = re.sub(r"#if\s+0\b.*?#endif", lambda m: "\n" * m.group().count("\n"), text, flags=re.S)
    code = re.sub(r"//[^\n]*|/\*.*?\*/", lambda m: "\n" * m.group().count("\n"), code, flags=re.S)
    for m in _ARRAY.finditer(code):
        kind = re.sub(r"\s+", " ", m.group(1))
        where = Location(path, code.count("\n", 0, m.start()) + 1, m.start() -
                         code.rfind("\n", 0, m.start()))
        end = code.find("}", m.end())
        if end < 0:
            raise BytecodeError(f"the array {m.group(2)} has no closing brace", where)
        width = _WIDTH.get(kind, 4)
        chunks = bytearray()
        for number in _NUMBER.findall(code[m.end():end]):
            value = int(number, 0)
            if value >= 1 << (8 * width):
                raise BytecodeError(f"{number} does not fit a {kind} (array {m.group(2)})", where)
            chunks += value.to_bytes(width, "little")
        out.append((m.group(2), bytes(chunks)))
    return out
