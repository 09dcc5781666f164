"""The parameter panel's model, apart from any window: which of an effect's parameters a user
can tweak and with which widget, the user's edits, and the clock TIME reads.

What FX Composer, RenderMonkey and EffectEdit showed (the DXSAS UI annotations, as the
bundled files and the real-world sets write them):
- `string UIName` labels the widget; `string UIWidget` picks it: "Slider", "Spinner",
  "Color", "CheckBox" (any case); "None" hides the parameter; one we do not know (FX
  Composer's "Direction", ...) gets the widget it would get without the annotation.
- `UIMin`/`UIMax` bound a slider (a spinner too), `UIStep` is its step.
- Without UIWidget: a bool is a checkbox, a float3/float4 named or bound as a colour
  (`*Color*`, `*Colour*`, diffuse/specular/ambient/emissive; the semantics of those names) is
  a colour picker, a number with both UIMin and UIMax a slider, anything else a spinner.
- A parameter the scene binds (WORLD, LIGHTPOSITION, TIME ... the host's binding table,
  `effects.host.semantics`) is the host's, not the user's: no widget, as FX Composer binds
  such a parameter to its scene and leaves it out of the material's tweakables. Matrices,
  arrays, strings and shaders get none either. Textures get a file path field.

Edits are keyed by the parameter's name and type (`Tweakable.key`): after a hot reload the
edit applies again to the parameter of that name if its type is unchanged, and waits (kept,
not applied) while it is not.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    from effects.model import Effect, Parameter

WIDGETS = ("slider", "spinner", "color", "checkbox", "texture")
_NAMED_WIDGETS = {"slider": "slider", "spinner": "spinner", "numeric": "spinner",
                  "color": "color", "colour": "color", "checkbox": "checkbox"}
_COLOUR_WORDS = ("color", "colour", "diffuse", "specular", "ambient", "emissive")
SPINNER_STEP = 0.01        # a float spinner's step per pixel dragged, where UIStep says none


@dataclass(frozen=True)
class Tweakable:
    """One widget of the panel."""

    name: str
    label: str                    # UIName, else the parameter's name
    widget: str                   # one of WIDGETS
    base: str                     # float, half, int, dword, bool; 'texture' for images
    components: int               # 1..4 (textures 1)
    lo: float | None = None       # UIMin / UIMax (first component when given as vectors)
    hi: float | None = None
    step: float | None = None     # UIStep
    key: tuple = ()               # (name, base, rows, cols, dim): what an edit is kept by

    @property
    def integral(self) -> bool:
        return self.base in ("int", "dword")


def _annotation(param: "Parameter", name: str) -> Any:
    a = param.annotation(name)
    return None if a is None else a.value


def _number(value: Any) -> float | None:
    """The first component of an annotation's number (UIMin = {0, 0, 0} bounds each alike)."""
    if value is None or isinstance(value, str):
        return None
    flat = np.asarray(value, np.float64).reshape(-1)
    return float(flat[0]) if flat.size and np.isfinite(flat[0]) else None


def _looks_like_colour(param: "Parameter") -> bool:
    words = (param.name.lower(), (param.semantic or "").lower())
    return any(w in text for w in _COLOUR_WORDS for text in words)


def tweakable(param: "Parameter") -> Tweakable | None:
    """The widget for one parameter, or None when it gets none (see the module docstring)."""
    from effects.host.semantics import binds, parameter_semantic
    kind = _annotation(param, "UIWidget")
    named = kind.strip().lower() if isinstance(kind, str) else ""
    if named == "none" or param.array:
        return None
    label = _annotation(param, "UIName")
    label = label if isinstance(label, str) and label.strip() else param.name
    t = param.type
    if t.base == "texture":
        return Tweakable(param.name, label, "texture", "texture", 1,
                         key=(param.name, "texture", 1, 1, t.dim))
    if not t.is_numeric or t.rows > 1 or not 1 <= t.cols <= 4:
        return None
    if binds(parameter_semantic(param)):
        return None
    lo, hi = _number(_annotation(param, "UIMin")), _number(_annotation(param, "UIMax"))
    if lo is not None and hi is not None and hi < lo:
        lo, hi = hi, lo
    step = _number(_annotation(param, "UIStep"))
    step = step if step is not None and step > 0 else None
    widget = _NAMED_WIDGETS.get(named)
    if t.base == "bool":
        widget = "checkbox"
    elif widget == "checkbox":
        widget = None                          # a checkbox for a float: the default instead
    if widget == "color" and t.cols not in (3, 4):
        widget = None
    if widget == "slider" and (lo is None or hi is None or hi == lo):
        widget = "spinner"                     # a slider needs both ends
    if widget is None:
        if t.cols in (3, 4) and t.base in ("float", "half") and _looks_like_colour(param):
            widget = "color"
        elif lo is not None and hi is not None and hi > lo:
            widget = "slider"
        else:
            widget = "spinner"
    return Tweakable(param.name, label, widget, t.base, t.cols, lo, hi, step,
                     key=(param.name, t.base, t.rows, t.cols, t.dim))


def tweakables(effect: "Effect") -> list[Tweakable]:
    """The panel's widgets for `effect`, in declaration order."""
    return [w for w in (tweakable(p) for p in effect.parameters) if w is not None]


def current_value(param: "Parameter | None", item: Tweakable) -> list[float] | bool | None:
    """The value a widget shows: the parameter's (as the runtime drawing it holds it) as a
    list of `components` numbers, a bool for a checkbox, None when it has none."""
    if param is None or param.value is None or item.widget == "texture":
        return None
    try:
        flat = np.asarray(param.value, np.float64).reshape(-1)
    except (TypeError, ValueError):
        return None
    if flat.size < item.components:
        return None
    if item.widget == "checkbox":
        return bool(flat[0])
    return [float(v) for v in flat[:item.components]]


@dataclass
class Tweaks:
    """The user's edits by `Tweakable.key`: numbers (a list), a bool, or a texture path.
    `generation` counts changes; `errors` holds, by parameter name, why the last edit of it
    could not be applied (a texture file that does not load): shown beside its widget."""

    values: dict[tuple, Any] = field(default_factory=dict)
    errors: dict[str, str] = field(default_factory=dict)
    generation: int = 0

    def set(self, item: Tweakable, value: Any) -> None:
        if isinstance(value, np.ndarray):
            value = value.tolist()
        if self.values.get(item.key) == value:
            return
        self.values[item.key] = value
        self.errors.pop(item.name, None)
        self.generation += 1

    def reset(self, item: Tweakable) -> None:
        if self.values.pop(item.key, None) is not None:
            self.generation += 1
        self.errors.pop(item.name, None)

    def get(self, item: Tweakable) -> Any:
        return self.values.get(item.key)

    def refuse(self, name: str, key: tuple, why: str) -> None:
        """An edit that could not be applied: dropped (the effect's value stands), and why."""
        self.values.pop(key, None)
        self.errors[name] = why
        self.generation += 1

    def for_effect(self, items: list[Tweakable]) -> dict[str, Any]:
        """Parameter name -> edited value, for the edits whose key matches one of `items`
        (the effect drawn now): an edit of a parameter since renamed or retyped waits."""
        return {item.name: self.values[item.key] for item in items if item.key in self.values}


@dataclass
class Clock:
    """The time the TIME semantic reads, in seconds. It runs while the viewer draws an effect
    that reads it (pause and step with the keys); `fixed` (`effects view --time S`) holds it
    for screenshots and tests."""

    seconds: float = 0.0
    running: bool = True
    fixed: bool = False
    step_s: float = 1.0 / 30.0     # one step key: a frame at 30 frames per second

    def advance(self, elapsed: float) -> bool:
        """Wall time `elapsed` passed: True if the clock moved."""
        if self.running and not self.fixed and elapsed > 0:
            self.seconds += elapsed
            return True
        return False

    def toggle(self) -> None:
        """Pause or run; a held clock (--time) starts running from where it was held."""
        if self.fixed:
            self.fixed, self.running = False, True
        else:
            self.running = not self.running

    def step(self, frames: int = 1) -> None:
        """Step (pausing first): a frame forward, or back with a negative count (not below 0)."""
        self.running = False
        self.seconds = max(0.0, self.seconds + frames * self.step_s)
