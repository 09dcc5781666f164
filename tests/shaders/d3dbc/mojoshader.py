"""MojoShader (Debian's libmojoshader0, the library FNA and MonoGame's OpenGL path load fxc's
bytecode with) through ctypes: a consumer of our bytecode that is not ours.

The structures are the leading fields of MOJOSHADER_parseData and MOJOSHADER_error as
mojoshader.h (hg revision 1314) declares them; only those are read."""
from __future__ import annotations

import ctypes
import ctypes.util


class Error(ctypes.Structure):
    _fields_ = [("error", ctypes.c_char_p), ("filename", ctypes.c_char_p),
                ("error_position", ctypes.c_int)]


class ParseData(ctypes.Structure):
    _fields_ = [("error_count", ctypes.c_int), ("errors", ctypes.POINTER(Error)),
                ("profile", ctypes.c_char_p), ("output", ctypes.POINTER(ctypes.c_char)),
                ("output_len", ctypes.c_int), ("instruction_count", ctypes.c_int),
                ("shader_type", ctypes.c_int), ("major_ver", ctypes.c_int),
                ("minor_ver", ctypes.c_int)]


def load() -> ctypes.CDLL | None:
    """The library, or None where it is not installed."""
    for name in (ctypes.util.find_library("mojoshader"), "libmojoshader.so.0"):
        if not name:
            continue
        try:
            lib = ctypes.CDLL(name)
        except OSError:
            continue
        lib.MOJOSHADER_parse.restype = ctypes.POINTER(ParseData)
        lib.MOJOSHADER_parse.argtypes = [
            ctypes.c_char_p, ctypes.c_char_p, ctypes.c_char_p, ctypes.c_uint, ctypes.c_void_p,
            ctypes.c_uint, ctypes.c_void_p, ctypes.c_uint, ctypes.c_void_p, ctypes.c_void_p,
            ctypes.c_void_p]
        lib.MOJOSHADER_assemble.restype = ctypes.POINTER(ParseData)
        lib.MOJOSHADER_assemble.argtypes = [
            ctypes.c_char_p, ctypes.c_char_p, ctypes.c_uint, ctypes.c_void_p, ctypes.c_uint,
            ctypes.c_void_p, ctypes.c_uint, ctypes.c_void_p, ctypes.c_uint, ctypes.c_void_p,
            ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p]
        lib.MOJOSHADER_freeParseData.argtypes = [ctypes.POINTER(ParseData)]
        return lib
    return None


def _result(lib: ctypes.CDLL, data) -> tuple[list[str], bytes, tuple[int, int]]:
    d = data.contents
    errors = [(d.errors[k].error or b"").decode(errors="replace")
              + f" (at {d.errors[k].error_position})" for k in range(d.error_count)]
    output = ctypes.string_at(d.output, d.output_len) if d.output and d.output_len > 0 else b""
    version = (d.major_ver, d.minor_ver)
    lib.MOJOSHADER_freeParseData(data)
    return errors, output, version


def parse(lib: ctypes.CDLL, bytecode: bytes, profile: str = "glsl") -> tuple[list[str], bytes,
                                                                              tuple[int, int]]:
    """MOJOSHADER_parse: (errors, the translation, the shader's version)."""
    data = lib.MOJOSHADER_parse(profile.encode(), b"main", bytecode, len(bytecode), None, 0,
                                None, 0, None, None, None)
    return _result(lib, data)


def assemble(lib: ctypes.CDLL, source: str) -> tuple[list[str], bytes]:
    """MOJOSHADER_assemble: (errors, bytecode)."""
    text = source.encode()
    data = lib.MOJOSHADER_assemble(b"t.asm", text, len(text), None, 0, None, 0, None, 0, None,
                                   None, None, None, None)
    errors, output, _ = _result(lib, data)
    return errors, output
