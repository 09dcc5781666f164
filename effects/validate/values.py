"""State values as the validator reads and shows them: enum spellings, integer values, and
the D3DTA argument encoding the fixed-function checks share."""
from __future__ import annotations

from typing import Any

import numpy as np

from effects import states as state_table
from effects.model import EnumValue

# D3DTA_* argument values (d3d9types.h as documented): the select mask, the two modifiers,
# and the selections the checks care about.
_TA_SELECT_MASK, _TA_COMPLEMENT, _TA_ALPHAREPLICATE = 0x0F, 0x10, 0x20
_TA_CURRENT, _TA_TEXTURE, _TA_TEMP, _TA_CONSTANT = 1, 2, 5, 6


def spelled(state_name: str, enum_name: str) -> str:
    """An enum value of a state as the D3D docs spell it ('BUMPENVMAP' → 'BumpEnvMap')."""
    info = state_table.lookup_state(state_name)
    if info is None or info.enum is None:
        return enum_name
    return info.enum.spelling(enum_name)


def _is_indexed(name: str) -> bool:
    info = state_table.lookup_state(name)
    return info is not None and info.index != "none"


def _int_value(value: Any) -> int | None:
    """An integer state value (enum, flags, bool, number) or None when it is not one."""
    if isinstance(value, EnumValue):
        value = value.value
    if isinstance(value, np.ndarray):
        if value.size != 1 or value.dtype.kind not in "biuf":
            return None
        value = value.reshape(-1)[0].item()
    if isinstance(value, (bool, int, np.integer)):
        return int(value)
    if isinstance(value, float) and value.is_integer():
        return int(value)
    return None


def _ta_select(value: Any) -> int | None:
    v = _int_value(value)
    return None if v is None else v & _TA_SELECT_MASK
