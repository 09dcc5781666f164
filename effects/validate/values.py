"""State values as the validator shows them: enum spellings as the docs write them, and
whether a state is indexed. (Values are read with the device state's typed readers,
`effects.d3d9.device.DeviceState.get_*`, the ones lowering uses.)"""
from __future__ import annotations


from effects.base import caches
from effects.d3d9 import states as state_table


@caches.memo("validate.enum_spellings", keys="state name, enum value name", entry_bytes=128,
             max_bytes=4096 * 128)
def spelled(state_name: str, enum_name: str) -> str:
    """An enum value of a state as the D3D docs spell it ('BUMPENVMAP' → 'BumpEnvMap')."""
    info = state_table.lookup_state(state_name)
    if info is None or info.enum is None:
        return enum_name
    return info.enum.spelling(enum_name)


def _is_indexed(name: str) -> bool:
    info = state_table.lookup_state(name)
    return info is not None and info.index != "none"
