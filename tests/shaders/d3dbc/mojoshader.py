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


# -- effects: MOJOSHADER_compileEffect (the fx_2_0 reader FNA and MonoGame load .fxo with) -------
# The layouts of hg revision 1314 (Debian's libmojoshader0), from mojoshader_effects.h of that
# era: the shader context has no context pointer (the GL/Vulkan back ends keep theirs current
# with *MakeContextCurrent), and MOJOSHADER_effect starts with error_count, errors,
# param_count, params, technique_count, techniques. Only those leading fields are read.

class SymbolTypeInfo(ctypes.Structure):
    _fields_ = [("parameter_class", ctypes.c_int), ("parameter_type", ctypes.c_int),
                ("rows", ctypes.c_uint), ("columns", ctypes.c_uint),
                ("elements", ctypes.c_uint), ("member_count", ctypes.c_uint),
                ("members", ctypes.c_void_p)]


class EffectValue(ctypes.Structure):
    _fields_ = [("name", ctypes.c_char_p), ("semantic", ctypes.c_char_p),
                ("type", SymbolTypeInfo), ("value_count", ctypes.c_uint),
                ("values", ctypes.c_void_p)]


class EffectParam(ctypes.Structure):
    _fields_ = [("value", EffectValue), ("annotation_count", ctypes.c_uint),
                ("annotations", ctypes.POINTER(EffectValue))]


class EffectState(ctypes.Structure):
    _fields_ = [("type", ctypes.c_int), ("value", EffectValue)]


class EffectPass(ctypes.Structure):
    _fields_ = [("name", ctypes.c_char_p), ("state_count", ctypes.c_uint),
                ("states", ctypes.POINTER(EffectState)), ("annotation_count", ctypes.c_uint),
                ("annotations", ctypes.POINTER(EffectValue))]


class EffectTechnique(ctypes.Structure):
    _fields_ = [("name", ctypes.c_char_p), ("pass_count", ctypes.c_uint),
                ("passes", ctypes.POINTER(EffectPass)), ("annotation_count", ctypes.c_uint),
                ("annotations", ctypes.POINTER(EffectValue))]


class Effect(ctypes.Structure):
    _fields_ = [("error_count", ctypes.c_int), ("errors", ctypes.POINTER(Error)),
                ("param_count", ctypes.c_int), ("params", ctypes.POINTER(EffectParam)),
                ("technique_count", ctypes.c_int),
                ("techniques", ctypes.POINTER(EffectTechnique))]


_COMPILE = ctypes.CFUNCTYPE(ctypes.c_void_p, ctypes.c_char_p, ctypes.c_void_p, ctypes.c_uint,
                            ctypes.c_void_p, ctypes.c_uint, ctypes.c_void_p, ctypes.c_uint)
_ONE = ctypes.CFUNCTYPE(None, ctypes.c_void_p)
_GET = ctypes.CFUNCTYPE(ctypes.c_void_p, ctypes.c_void_p)
_BIND = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_void_p)
_BOUND = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_void_p)
_MAP = ctypes.CFUNCTYPE(None, *[ctypes.c_void_p] * 6)
_UNMAP = ctypes.CFUNCTYPE(None)
_ERROR = ctypes.CFUNCTYPE(ctypes.c_char_p)


class ShaderContext(ctypes.Structure):
    _fields_ = [("compileShader", _COMPILE), ("shaderAddRef", _ONE), ("deleteShader", _ONE),
                ("getParseData", _GET), ("bindShaders", _BIND), ("getBoundShaders", _BOUND),
                ("mapUniformBufferMemory", _MAP), ("unmapUniformBufferMemory", _UNMAP),
                ("getError", _ERROR), ("m", ctypes.c_void_p), ("f", ctypes.c_void_p),
                ("malloc_data", ctypes.c_void_p)]


# the profile the effect's shaders are parsed with: "bytecode" passes them through (the GLSL
# profile lacks some ps_1_4 instructions; which shaders MojoShader translates is the d3dbc tests')
PROFILE = b"bytecode"


def compile_effect(lib: ctypes.CDLL, data: bytes) -> dict:
    """MOJOSHADER_compileEffect over an fx_2_0 binary, each shader parsed with MOJOSHADER_parse
    (profile PROFILE): {'errors', 'shader_errors', 'parameters': [(name, semantic, class,
    type, rows, columns, elements)], 'techniques': [(name, [pass names])]}. The effect is
    not deleted (its shaders are the parse results this context made; the process ends)."""
    shader_errors: list[str] = []
    keep: list = []

    def compile_shader(mainfn, tokens, size, swiz, swizcount, smap, smapcount):
        blob = ctypes.string_at(tokens, size)
        parsed = lib.MOJOSHADER_parse(PROFILE, mainfn or b"main", blob, len(blob), None, 0,
                                      None, 0, None, None, None)
        keep.append((blob, parsed))
        d = parsed.contents
        shader_errors.extend((d.errors[k].error or b"").decode(errors="replace")
                             for k in range(d.error_count))
        return ctypes.cast(parsed, ctypes.c_void_p).value

    callbacks = ShaderContext(
        _COMPILE(compile_shader), _ONE(lambda s: None), _ONE(lambda s: None),
        _GET(lambda s: s), _BIND(lambda v, p: None), _BOUND(lambda v, p: None),
        _MAP(lambda *a: None), _UNMAP(lambda: None), _ERROR(lambda: b""), None, None, None)
    lib.MOJOSHADER_compileEffect.restype = ctypes.POINTER(Effect)
    lib.MOJOSHADER_compileEffect.argtypes = [ctypes.c_char_p, ctypes.c_uint, ctypes.c_void_p,
                                             ctypes.c_uint, ctypes.c_void_p, ctypes.c_uint,
                                             ctypes.POINTER(ShaderContext)]
    result = lib.MOJOSHADER_compileEffect(data, len(data), None, 0, None, 0,
                                          ctypes.byref(callbacks))
    if not result:
        return {"errors": ["MOJOSHADER_compileEffect returned NULL"], "shader_errors": [],
                "parameters": [], "techniques": []}
    e = result.contents
    errors = [(e.errors[k].error or b"").decode(errors="replace") for k in range(e.error_count)]
    params = []
    for k in range(e.param_count if not errors else 0):
        v = e.params[k].value
        params.append(((v.name or b"").decode(), (v.semantic or b"").decode(),
                       v.type.parameter_class, v.type.parameter_type, v.type.rows,
                       v.type.columns, v.type.elements))
    techniques = []
    for k in range(e.technique_count if not errors else 0):
        t = e.techniques[k]
        techniques.append(((t.name or b"").decode(),
                           [(t.passes[j].name or b"").decode() for j in range(t.pass_count)]))
    return {"errors": errors, "shader_errors": shader_errors, "parameters": params,
            "techniques": techniques}


if __name__ == "__main__":   # python mojoshader.py FILE.fxo: the result as JSON (a crash stays here)
    import json
    import sys
    library = load()
    with open(sys.argv[1], "rb") as fh:
        print(json.dumps(compile_effect(library, fh.read())))
