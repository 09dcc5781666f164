"""MojoShader (Debian's libmojoshader0, the library FNA and MonoGame's OpenGL path load fxc's
bytecode with) through ctypes: a consumer of our bytecode that is not ours.

The structures are the leading fields of MOJOSHADER_parseData (up to `outputs`), and
MOJOSHADER_error, _uniform, _constant, _sampler and _attribute, as mojoshader.h (hg revision
1314, Debian's libmojoshader-dev) declares them; only those are read."""
from __future__ import annotations

import ctypes
import ctypes.util
from dataclasses import dataclass


class Error(ctypes.Structure):
    _fields_ = [("error", ctypes.c_char_p), ("filename", ctypes.c_char_p),
                ("error_position", ctypes.c_int)]


class Uniform(ctypes.Structure):
    # type: MOJOSHADER_uniformType (0 float, 1 int, 2 bool); index: the register
    _fields_ = [("type", ctypes.c_int), ("index", ctypes.c_int), ("array_count", ctypes.c_int),
                ("constant", ctypes.c_int), ("name", ctypes.c_char_p)]


class Constant(ctypes.Structure):
    _fields_ = [("type", ctypes.c_int), ("index", ctypes.c_int), ("value", ctypes.c_float * 4)]


class Sampler(ctypes.Structure):
    # type: MOJOSHADER_samplerType (0 2D, 1 cube, 2 volume)
    _fields_ = [("type", ctypes.c_int), ("index", ctypes.c_int), ("name", ctypes.c_char_p),
                ("texbem", ctypes.c_int)]


class Attribute(ctypes.Structure):
    # usage: MOJOSHADER_usage, in USAGES' order
    _fields_ = [("usage", ctypes.c_int), ("index", ctypes.c_int), ("name", ctypes.c_char_p)]


class ParseData(ctypes.Structure):
    _fields_ = [("error_count", ctypes.c_int), ("errors", ctypes.POINTER(Error)),
                ("profile", ctypes.c_char_p), ("output", ctypes.POINTER(ctypes.c_char)),
                ("output_len", ctypes.c_int), ("instruction_count", ctypes.c_int),
                ("shader_type", ctypes.c_int), ("major_ver", ctypes.c_int),
                ("minor_ver", ctypes.c_int), ("mainfn", ctypes.c_char_p),
                ("uniform_count", ctypes.c_int), ("uniforms", ctypes.POINTER(Uniform)),
                ("constant_count", ctypes.c_int), ("constants", ctypes.POINTER(Constant)),
                ("sampler_count", ctypes.c_int), ("samplers", ctypes.POINTER(Sampler)),
                ("attribute_count", ctypes.c_int), ("attributes", ctypes.POINTER(Attribute)),
                ("output_count", ctypes.c_int), ("outputs", ctypes.POINTER(Attribute))]


# MOJOSHADER_usage, in its enum's order (POSITION = 0 ... SAMPLE), as the names our dcl uses.
USAGES = ("position", "blendweight", "blendindices", "normal", "psize", "texcoord", "tangent",
          "binormal", "tessfactor", "positiont", "color", "fog", "depth", "sample")
UNIFORM_TYPES = ("float", "int", "bool")
SAMPLER_TYPES = ("2d", "cube", "3d")


@dataclass(frozen=True)
class Translation:
    """What MOJOSHADER_parse says of one shader: its errors, its translation (the GLSL text
    for the glsl profiles) and the interface that translation declares: uniforms as (type,
    register, array_count, constant, name), samplers as (type, register, name), vertex
    inputs and outputs as (usage, index, name)."""

    errors: list[str]
    text: str
    version: tuple[int, int]
    uniforms: list[tuple[str, int, int, int, str]]
    samplers: list[tuple[str, int, str]]
    attributes: list[tuple[str, int, str]]
    outputs: list[tuple[str, int, str]]


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


def _text(value: bytes | None) -> str:
    return (value or b"").decode(errors="replace")


class SamplerMap(ctypes.Structure):
    _fields_ = [("index", ctypes.c_int), ("type", ctypes.c_int)]


def translate(lib: ctypes.CDLL, bytecode: bytes, profile: str = "glsl",
              sampler_types: dict[int, str] | None = None) -> Translation:
    """MOJOSHADER_parse with the interface of its translation (see `Translation`).
    `sampler_types`: register -> '2d' | 'cube' | '3d' for samplers the bytecode does not
    declare (ps_1_x), MOJOSHADER_parse's sampler map, which a host fills from the textures it
    binds (mojoshader.h: Shader Model 1 "uses whatever is bound to a given sampler at draw
    time"; MojoShader otherwise defaults to 2D)."""
    items = sorted((sampler_types or {}).items())
    smap = (SamplerMap * max(len(items), 1))(*[SamplerMap(i, SAMPLER_TYPES.index(t))
                                               for i, t in items])
    data = lib.MOJOSHADER_parse(profile.encode(), b"main", bytecode, len(bytecode), None, 0,
                                smap if items else None, len(items), None, None, None)
    d = data.contents

    def rows(pointer, count):
        return [pointer[k] for k in range(count)] if pointer and count > 0 else []

    uniforms = [(UNIFORM_TYPES[u.type], u.index, u.array_count, u.constant, _text(u.name))
                for u in rows(d.uniforms, d.uniform_count)]
    samplers = [(SAMPLER_TYPES[s.type], s.index, _text(s.name))
                for s in rows(d.samplers, d.sampler_count)]
    attributes = [(USAGES[a.usage], a.index, _text(a.name))
                  for a in rows(d.attributes, d.attribute_count)]
    outputs = [(USAGES[a.usage], a.index, _text(a.name)) for a in rows(d.outputs, d.output_count)]
    errors, output, version = _result(lib, data)
    return Translation(errors, output.decode(errors="replace"), version, uniforms, samplers,
                       attributes, outputs)


def assemble(lib: ctypes.CDLL, source: str) -> tuple[list[str], bytes]:
    """MOJOSHADER_assemble: (errors, bytecode)."""
    text = source.encode()
    data = lib.MOJOSHADER_assemble(b"t.asm", text, len(text), None, 0, None, 0, None, 0, None,
                                   None, None, None, None)
    errors, output, _ = _result(lib, data)
    return errors, output
