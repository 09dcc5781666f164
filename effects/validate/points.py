"""Point sizes against the card's MaxPointSize (D3DCAPS9): what the driver clamps.

The driver clamps a point's size to [PointSize_Min, PointSize_Max], and PointSize_Max must not
exceed MaxPointSize; a MaxPointSize of 1 means the card has no point-size control at all (the
D3D9 point-sprite docs and D3DCAPS9). Nothing fails to draw: a size the card cannot give is a
warning that names the size points are drawn at. Judged only where the caps profile states
MaxPointSize (most DX6-DX9 profiles here do not). PointSize = Size * 2 is judged as its value
(`effects.validate.expressions`).

A mixin of `validate._PassChecker`.
"""
from __future__ import annotations

_POINT_STATES = ("PointSize", "PointSize_Max")


class PointChecks:
    """The point-size checks of a pass."""

    def check_points(self) -> None:
        cap = self.profile.get("MaxPointSize")
        if cap is None:
            return
        cap = float(cap)
        for name in _POINT_STATES:
            if self.state.assignment(name) is None or self.unknown(name):
                continue
            size = self.state.get_float(name, default=None)
            if size is None or size <= cap:
                continue
            subject = f"{name} = {size:g}"
            if cap <= 1.0:
                message = (f"{subject}: the {self.card()} has no point-size control "
                           "(MaxPointSize 1); points are drawn 1 pixel wide")
            elif name == "PointSize":
                message = (f"{subject} is above the {self.card()}'s MaxPointSize {cap:g}; points "
                           f"are drawn at most {cap:g} pixels wide")
            else:
                message = (f"{subject} is above the {self.card()}'s MaxPointSize {cap:g}, which "
                           "PointSize_Max must not exceed; sizes are clamped to it")
            self.caution(self.where(name), subject, f"MaxPointSize >= {size:g}",
                         f"MaxPointSize {cap:g}", message)
