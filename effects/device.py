"""The simulated device's state as a technique's passes set it.

Each technique starts from Direct3D 9's default device state, with what the host set before
`Begin` on top (`host`: the application's SetTransform calls, as EffectEdit and FX Composer set
WORLD/VIEW/PROJECTION from their camera); each pass applies its assignments on top, and what a pass set persists into the following passes (as on a device,
D3DX restoring state only at End). Validation and lowering both read state through this, so
"what was validated" and "what runs" see the same values.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any, Iterator, Mapping

import numpy as np

from effects.model import Effect, EnumValue, ParamRef, Pass, SamplerState, StateAssignment
from effects import states as state_table

# How many units each indexed kind has on a D3D9 device (stages, samplers, lights).
MAX_STAGES = 8
MAX_SAMPLERS = 16


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
            if value.index is not None and isinstance(v, (list, tuple)) and value.index < len(v):
                v = v[value.index]
            if isinstance(v, np.ndarray) and v.shape == ():
                return v.item()
            return v if v is not None else value
        return value

    def items(self) -> Iterator[tuple[tuple[str, int | None], StateAssignment]]:
        return iter(self.values.items())


@lru_cache(maxsize=None)
def _info(name: str) -> state_table.StateInfo | None:
    """The states-table row of a name (cached: validation asks for the same few names often)."""
    return state_table.lookup_state(name)


@lru_cache(maxsize=4096)
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
