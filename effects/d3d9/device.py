"""The simulated device's state as a technique's passes set it, and its typed readers.

Each technique starts from Direct3D 9's default device state, with what the host set before
`Begin` on top (`host`: the application's SetTransform calls, as EffectEdit and FX Composer set
WORLD/VIEW/PROJECTION from their camera); each pass applies its assignments on top, and what
a pass set persists into the following passes (as on a device, D3DX restoring state only at
End). Validation computes each pass's state once and keeps it in its answer
(`PassReport.state`); lowering draws from that same object (with the host's states added),
and both read values through the typed readers here (`get_int`, `get_float`, `get_bool`,
`get_enum`, `get_color`, `get_vector`, `get_matrix`), so "what was validated" and "what runs"
see the same values.

The readers' rules: an uninitialised parameter reads 0, as D3DX leaves it; a number is read as
the state's type (a float cast to a DWORD, the first element of an array); a value that cannot
be read as the type raises a located EffectError, or returns `default` when one is given (the
validator passes None and skips what it cannot read).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Iterator, Mapping

import numpy as np

from effects.base import caches
from effects.base.errors import EffectError, Location
from effects.model import (Effect, EnumValue, Expression, NullValue, ParamRef, Pass, SamplerState,
                           StateAssignment)
from effects.d3d9 import states as state_table

Color = tuple[float, float, float, float]
NO_DEFAULT: Any = object()   # a reader given no default raises (a public sentinel: validation
                              # passes it on through its own readers)


@dataclass
class DeviceState:
    """State values keyed by (canonical state name, index); missing keys read as D3D9 defaults."""

    effect: Effect
    values: dict[tuple[str, int | None], StateAssignment] = field(default_factory=dict)
    # Values the host set before Begin, keyed like `values` (canonical name, index): read
    # where no pass assigned the state, instead of the D3D9 default.
    host: Mapping[tuple[str, int | None], Any] = field(default_factory=dict)

    def copy(self) -> "DeviceState":
        return DeviceState(self.effect, dict(self.values), self.host)

    def for_effect(self, effect: Effect,
                   host: Mapping[tuple[str, int | None], Any] | None = None) -> "DeviceState":
        """The same assignments read against another copy of the effect (a runtime's, whose
        parameters hold the scene's values), with `host`'s states under them."""
        return DeviceState(effect, dict(self.values), self.host if host is None else host)

    # -- writing ----------------------------------------------------------------------------
    def apply_pass(self, p: Pass) -> None:
        for assignment in p.states:
            self.apply(assignment)

    def apply(self, assignment: StateAssignment, index_override: int | None = None) -> None:
        if not assignment.known:
            return
        index = assignment.index if index_override is None else index_override
        info = _info(assignment.name)
        if info is not None and info.kind == "sampler_object":
            # `Sampler[n] = <s>`: the sampler_state's own assignments land on sampler n.
            sampler = self.resolve(assignment.value)
            if isinstance(sampler, SamplerState):
                for inner in sampler.states:
                    self.apply(inner, index_override=index or 0)
            return
        if isinstance(assignment.value, NullValue) and info is not None and info.type == "matrix":
            return  # `WorldTransform[0] = 0;`: NULL sets nothing (see the effect builder)
        self.values[_key(assignment.name, index)] = assignment

    # -- reading ----------------------------------------------------------------------------
    def assignment(self, name: str, index: int | None = None) -> StateAssignment | None:
        """The assignment in force for a state, or None when it still has its default."""
        return self.values.get(_key(name, index))

    def get(self, name: str, index: int | None = None) -> Any:
        """The value in force: an assignment's value (parameters resolved) or the default."""
        a = self.assignment(name, index)
        if a is None:
            if self.host:
                key = _key(name, index)
                if key in self.host:
                    return self.host[key]
            info = _info(name)
            return state_table.default_value(info, index) if info else None
        return self.resolve(a.value)

    def enum_name(self, name: str, index: int | None = None) -> str | None:
        """The base enum name (upper case, no prefix) of an enum state, or None if unknown."""
        value = self.get(name, index)
        if isinstance(value, EnumValue):
            if value.names and not value.names[0].isdigit():
                return value.names[0]
            value = value.value
        info = _info(name)
        if info is not None and info.enum is not None and isinstance(value, (int, np.integer)):
            for enum_name, v in info.enum.values.items():
                if v == int(value):
                    return enum_name
        return None

    def resolve(self, value: Any) -> Any:
        """A parameter reference replaced by the parameter's current value (scalars unwrapped)."""
        if isinstance(value, ParamRef):
            param = self.effect.parameter(value.name)
            if param is None:
                return value
            v = param.value
            if value.index is not None and isinstance(v, (list, tuple, np.ndarray)) \
                    and param.array and value.index < len(v):
                v = v[value.index]   # `<g_vLightPos[0]>`: one element of an array parameter
            if isinstance(v, np.ndarray) and v.shape == ():
                return v.item()
            return v if v is not None else value
        return value

    def items(self) -> Iterator[tuple[tuple[str, int | None], StateAssignment]]:
        return iter(self.values.items())

    def int_constants(self, shader: str) -> dict[int, tuple[int, int, int, int]]:
        """The integer registers i# the pass sets for the 'Vertex' or 'Pixel' shader
        (`VertexShaderConstantI[n] = int4(...)` or `<param>`: four ints a register, padded
        with zeros). A register nothing sets, or a parameter without a value, is left out:
        it reads (0, 0, 0, 0), the device's initial value."""
        found: dict[int, tuple[int, int, int, int]] = {}
        for index, flat, _ in self._constant_rows(f"{shader}ShaderConstantI"):
            rows = np.zeros(-(-flat.size // 4) * 4, np.int64)
            rows[:flat.size] = np.rint(flat)
            for k in range(0, rows.size, 4):
                found[index + k // 4] = tuple(int(v) for v in rows[k:k + 4])  # type: ignore[misc]
        return found

    def bool_constants(self, shader: str) -> dict[int, bool]:
        """The boolean registers b# the pass sets (`PixelShaderConstantB[n] = true` or
        `<param>`: one BOOL a register); unset registers read FALSE, as on the device."""
        found: dict[int, bool] = {}
        for index, flat, _ in self._constant_rows(f"{shader}ShaderConstantB"):
            for k, v in enumerate(flat):
                found[index + k] = bool(v)
        return found

    def _constant_rows(self, name: str) -> Iterator[tuple[int, np.ndarray, Location]]:
        """(first register, the value as a flat float array, where) of each assignment of the
        constant state `name`, in the order the pass made them (later ones win)."""
        for (key, index), assignment in self.items():
            if key != name or index is None:
                continue
            value = self.resolve(assignment.value)
            if isinstance(value, (ParamRef, Expression, NullValue)) or value is None:
                continue
            try:
                flat = np.ravel(np.asarray(value, dtype=np.float64))
            except (TypeError, ValueError):
                raise EffectError(f"{name}[{index}] needs numbers, not "
                                  f"{type(value).__name__}", assignment.location) from None
            if not np.isfinite(flat).all():
                raise EffectError(f"{name}[{index}] needs finite numbers", assignment.location)
            yield index, flat, assignment.location

    # -- typed readers (see the module docstring) ------------------------------------------
    def where(self, name: str, index: int | None = None,
              fallback: Location | None = None) -> Location:
        """Where the value in force was assigned (`fallback`, or the file, for a default)."""
        a = self.assignment(name, index)
        if a is not None:
            return a.location
        return fallback if fallback is not None else Location(self.effect.path, 1, 1)

    def known(self, name: str, index: int | None = None) -> bool:
        """False while the value waits on the application: a parameter without a value, or a
        preshader expression."""
        return not isinstance(self.get(name, index), (ParamRef, Expression))

    def value(self, name: str, index: int | None = None) -> Any:
        """`get`, with a parameter that has no value reading 0 (D3DX leaves it zero)."""
        value = self.get(name, index)
        return 0 if isinstance(value, ParamRef) else value

    def _unread(self, name: str, index: int | None, what: str, value: Any, default: Any) -> Any:
        if default is not NO_DEFAULT:
            return default
        raise EffectError(f"{name}: expected {what}, got {value!r}", self.where(name, index))

    def read(self, name: str, index: int | None = None) -> Any:
        """The value in force read as its row in the states table types it: bool, int (dword,
        and flag enums such as ColorWriteEnable), float, enum name, colour, vector, matrix."""
        info = _info(name)
        kind = info.type if info is not None else None
        if kind == "enum" and info is not None and info.enum is not None and info.enum.flags:
            kind = "int"
        reader = _READERS.get(kind or "")
        if reader is None:
            raise ValueError(f"no typed reader for state {name!r} ({kind})")
        if kind in ("float3", "float4"):
            return self.get_vector(name, index, 3 if kind == "float3" else 4)
        return reader(self, name, index)

    def get_int(self, name: str, index: int | None = None, default: Any = NO_DEFAULT) -> int:
        """The value as a DWORD: enums and flags by number, TRUE as 1, a float truncated."""
        value = self.value(name, index)
        number = value.value if isinstance(value, EnumValue) else value
        if type(number) is int:   # the common case, without NumPy
            return number & state_table.DWORD_MASK
        try:
            return int(np.ravel(np.asarray(number, dtype=np.float64))[0]) & state_table.DWORD_MASK
        except (TypeError, ValueError, IndexError):
            return self._unread(name, index, "a number", value, default)

    def get_float(self, name: str, index: int | None = None, default: Any = NO_DEFAULT) -> float:
        value = self.value(name, index)
        if type(value) in (float, int):
            return float(value)
        try:
            return float(np.ravel(np.asarray(value, dtype=np.float64))[0])
        except (TypeError, ValueError, IndexError):
            return self._unread(name, index, "a float", value, default)

    def get_bool(self, name: str, index: int | None = None) -> bool:
        """Whether the state is on; a value the application has not set yet, or NULL, is off."""
        return is_on(self.get(name, index))

    def get_enum(self, name: str, index: int | None = None, default: Any = NO_DEFAULT) -> str:
        """The canonical enum name (upper case, no prefix) of the value in force."""
        found = self.enum_name(name, index)
        if found is not None:
            return found
        info = _info(name)
        table = info.enum if info is not None else None
        number = self.get_int(name, index, default=None)
        if table is not None and number is not None:
            for enum_name, v in table.values.items():
                if v == number:
                    return enum_name
        if default is not NO_DEFAULT:
            return default
        shown = name if index is None else f"{name}[{index}]"
        raise EffectError(f"{shown}: {number if number is not None else self.get(name, index)!r} "
                          f"is not a {table.name if table else 'known'} value",
                          self.where(name, index))

    def get_color(self, name: str, index: int | None = None, default: Any = NO_DEFAULT) -> Color:
        """(r, g, b, a): a D3DCOLOR DWORD unpacked, or a float3 / float4 colour parameter."""
        value = self.value(name, index)
        if type(value) is not int:
            try:
                array = np.ravel(np.asarray(value, dtype=np.float64))
            except (TypeError, ValueError):
                return self._unread(name, index, "a colour", value, default)
            if array.size >= 3:
                rgba = list(array[:4]) + [1.0] * (4 - min(4, array.size))
                return (float(rgba[0]), float(rgba[1]), float(rgba[2]), float(rgba[3]))
        number = self.get_int(name, index, default)
        return number if number is default else state_table.unpack_color(number)

    def get_vector(self, name: str, index: int | None, size: int,
                   default: Any = NO_DEFAULT) -> tuple[float, ...]:
        """`size` floats; a scalar (an unset parameter reads 0) fills every component, missing
        ones read 0."""
        value = self.value(name, index)
        try:
            array = np.ravel(np.asarray(value, dtype=np.float64))
        except (TypeError, ValueError):
            return self._unread(name, index, f"{size} numbers", value, default)
        if array.size == 1 and size > 1:
            array = np.full(size, array[0])
        out = list(array[:size]) + [0.0] * max(0, size - array.size)
        return tuple(float(x) for x in out)

    def get_matrix(self, name: str, index: int | None = None,
                   default: Any = NO_DEFAULT) -> np.ndarray:
        """A 4x4 matrix (row-major, as the effect writes it); an unset parameter reads zero."""
        value = self.value(name, index)
        try:
            array = np.ravel(np.asarray(value, dtype=np.float64))
        except (TypeError, ValueError):
            return self._unread(name, index, "a 4x4 matrix", value, default)
        if array.size == 1 and array[0] == 0:
            return np.zeros((4, 4))
        if array.size != 16:
            if default is not NO_DEFAULT:
                return default
            raise EffectError(f"{name}: expected a 4x4 matrix, got {array.size} value(s)",
                              self.where(name, index))
        return array.reshape(4, 4)


def is_on(value: Any) -> bool:
    """A bool state's value (as `DeviceState.get` gives it) read as on or off."""
    if type(value) is bool:
        return value
    if value is None or isinstance(value, (ParamRef, Expression, NullValue)):
        return False
    if isinstance(value, EnumValue):
        return bool(value.value)
    if isinstance(value, (int, float)):
        return bool(value)
    flat = np.ravel(np.asarray(value))
    return bool(flat.size) and bool(flat[0])


_READERS: dict[str, Any] = {
    "bool": DeviceState.get_bool, "int": DeviceState.get_int, "dword": DeviceState.get_int,
    "float": DeviceState.get_float, "enum": DeviceState.get_enum, "color": DeviceState.get_color,
    "float3": DeviceState.get_vector, "float4": DeviceState.get_vector,
    "matrix": DeviceState.get_matrix,
}


# unbounded before: the names come from the file
@caches.memo("d3d9.state_rows", keys="a state name", entry_bytes=128, max_bytes=4096 * 128)
def _info(name: str) -> state_table.StateInfo | None:
    """The states-table row of a name (cached: validation asks for the same few names often)."""
    return state_table.lookup_state(name)


@caches.memo("d3d9.state_keys", keys="state name, index", entry_bytes=128, max_bytes=4096 * 128)
def _key(name: str, index: int | None) -> tuple[str, int | None]:
    """The canonical state name, and index 0 for an indexed state written without one
    (`MinFilter = Linear` in a pass means sampler 0, as D3DX reads it)."""
    info = _info(name)
    if info is None:
        return name, index
    if index is None and info.index != "none":
        index = 0
    return info.name, index


def host_states(values: Mapping[str, Any]) -> dict[tuple[str, int | None], Any]:
    """{'WorldTransform': M, ...} as `DeviceState.host` keys them (canonical name, index)."""
    return {_key(name, None): value for name, value in values.items()}


def pass_states(effect: Effect, passes: list[Pass],
                host: Mapping[tuple[str, int | None], Any] | None = None
                ) -> Iterator[tuple[Pass, DeviceState]]:
    """Each pass with the device state in force while it draws (earlier passes persist);
    `host`: states the application set before Begin (see `host_states`)."""
    state = DeviceState(effect, host=host or {})
    for p in passes:
        state.apply_pass(p)
        yield p, state.copy()
