"""The viewer's on-screen panel, drawn with imgui (imgui-bundle 1.6 through moderngl-window's
integration): card, technique and pass count, every other technique with its first reason
(expand for all), each valid technique's fidelity (its picture on the card against the best
technique's: effects.host.fidelity), the effect's parameters as widgets
(`effects.viewer.params`), the clock, render times, the last reload and its error, and the
controls.

The panel only reads `Status` and calls `ViewerState` methods; the keys do the same things
(`KEYS`, listed in the panel's help).
"""
from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable

from imgui_bundle import imgui

from effects.viewer.params import Tweakable, current_value, tweakables
from effects.viewer.reload import error_text, loaded_warnings
from effects.viewer.state import DIFFERENCE_SCALE, MESHES, VIEW_TITLES, VIEWS, ViewerState

if TYPE_CHECKING:  # pragma: no cover
    from effects.viewer.reload import LoadedEffect
    from effects.viewer.draw import DifferenceStats
    from effects.validate.technique import Validation

KEYS = (
    ("N / P", "next / previous card"),
    ("T / shift+T", "force the next / previous technique (first: the card's choice)"),
    ("V or 1 2 3", "view: GL, NumPy reference, difference"),
    ("M", "next mesh"),
    ("C", "show / hide the shader listing of the technique drawn (as `effects compile`)"),
    ("L", "animate the light; right-drag moves it"),
    ("space", "pause / run the clock TIME reads (a --time clock runs from there)"),
    (". / ,", "step the clock a frame forward / back (pauses it)"),
    ("left-drag, wheel", "orbit, zoom"),
    ("R", "reload now"),
    ("S", "screenshot"),
    ("Esc", "quit"),
)
RED = imgui.ImVec4(1.0, 0.45, 0.4, 1.0)
GREEN = imgui.ImVec4(0.5, 0.9, 0.5, 1.0)
GREY = imgui.ImVec4(0.65, 0.65, 0.65, 1.0)
YELLOW = imgui.ImVec4(1.0, 0.85, 0.4, 1.0)


@dataclass
class Status:
    """What the viewer knows besides the user's choices."""

    path: str
    loaded: "LoadedEffect | None" = None
    error: str | None = None              # the located error report of the last failed build
    scene_error: str | None = None        # ... and of the scene file's last failed reading
    render_error: str | None = None
    last_reload: str = ""
    gl_ms: float | None = None
    reference_ms: float | None = None
    reference_busy: bool = False
    reference_error: str | None = None
    difference: "DifferenceStats | None" = None
    messages: list[str] = field(default_factory=list)
    # what the picture shows nothing of and why (`effects.host.diagnostics`), located
    diagnostics: list[str] = field(default_factory=list)
    runtime: Any = None                   # the Runtime last drawn: the values the widgets show
    reads_time: bool = False              # the effect drawn reads the clock (TIME)
    # each parameter widget's rectangle (x0, y0, x1, y1), window coordinates, as last drawn:
    # tests and benchmarks click and drag them as a user would
    widget_rects: dict[str, tuple[float, float, float, float]] = field(default_factory=dict)
    texture_text: dict[str, str] = field(default_factory=dict)   # the path fields' text
    tweakables: "tuple[Any, list[Tweakable]] | None" = None     # (effect, its widgets)


@dataclass
class Actions:
    reload: Callable[[], None]
    screenshot: Callable[[], None]


def draw_panel(state: ViewerState, status: Status, actions: Actions,
               rect: tuple[float, float, float, float]) -> None:
    """Draw the panel in rect = (x, y, w, h), window coordinates from the top left."""
    x, y, w, h = rect
    imgui.set_next_window_pos(imgui.ImVec2(x, y), imgui.Cond_.always)
    imgui.set_next_window_size(imgui.ImVec2(w, h), imgui.Cond_.always)
    flags = (imgui.WindowFlags_.no_move | imgui.WindowFlags_.no_resize
             | imgui.WindowFlags_.no_collapse | imgui.WindowFlags_.no_saved_settings)
    imgui.begin("effects view", None, flags)
    imgui.text_wrapped(status.path)
    _card(state)
    _techniques(state, status)
    imgui.separator()
    _parameters(state, status)
    imgui.separator()
    _view(state, status)
    changed, shown = imgui.checkbox("listing (C)", state.show_listing)
    if changed and shown != state.show_listing:
        state.toggle_listing()
    imgui.separator()
    _reload(status, actions)
    if imgui.collapsing_header("Keys"):
        for key, what in KEYS:
            imgui.text_colored(GREY, f"{key:>16}")
            imgui.same_line()
            imgui.text(what)
    imgui.end()


def _card(state: ViewerState) -> None:
    profile = state.profile
    name = getattr(profile, "display_name", None) or state.card
    if imgui.button("<"):
        state.next_card(-1)
    imgui.same_line()
    if imgui.button(">"):
        state.next_card(1)
    imgui.same_line()
    imgui.set_next_item_width(-1)
    changed, index = imgui.combo("##card", state.card_index, state.cards)
    if changed:
        state.set_card(index)
    imgui.text(f"Card: {name}")


def _techniques(state: ViewerState, status: Status) -> None:
    loaded = status.loaded
    if loaded is None:
        imgui.text_colored(RED, "no effect loaded")
        return
    names = [t.name or "<anonymous>" for t in loaded.effect.techniques]
    options = ["(the card's choice)", *names]
    current = options.index(state.technique) if state.technique in options else 0
    imgui.set_next_item_width(-1)
    changed, index = imgui.combo("##technique", current, options)
    if changed:
        state.force_technique(None if index == 0 else options[index])
    selected = loaded.selected
    if selected is None:
        imgui.text_colored(RED, "No technique is valid on this card: nothing to draw.")
    else:
        how = "forced" if loaded.forced and loaded.technique.name == loaded.forced else "selected"
        imgui.text_colored(GREEN, f"Drawing {selected.technique.name or '<anonymous>'} "
                                  f"({how}), {selected.passes} pass{'es' if selected.passes != 1 else ''}"
                                  f"{fidelity_note(loaded, selected)}")
    imgui.text_colored(GREY, fidelity_heading(loaded))
    if loaded.prepare_error is not None:
        imgui.text_colored(RED, "...but it cannot be drawn:")
        imgui.text_wrapped(error_text(loaded.prepare_error))
    warnings = loaded_warnings(loaded)
    if warnings:
        imgui.text_colored(YELLOW, f"{len(warnings)} warning{'s' if len(warnings) != 1 else ''}:")
        for warning in warnings:
            imgui.bullet()
            imgui.text_wrapped(str(warning))
    if status.diagnostics:
        imgui.text_colored(YELLOW, "What the picture shows nothing of:")
        for text in status.diagnostics:
            imgui.bullet()
            imgui.text_wrapped(text)
    if loaded.forced_rejected is not None:
        v = loaded.forced_rejected
        imgui.text_colored(YELLOW, f"Forced {v.technique.name} is not valid on this card:")
        for reason in v.reasons:
            imgui.bullet()
            imgui.text_wrapped(str(reason))
    imgui.text("Other techniques:")
    pending = loaded.pending        # read first: the worker fills validations, then empties it
    for v in loaded.validations:
        if selected is not None and v.technique is selected.technique:
            continue
        label = v.technique.name or "<anonymous>"
        if v.ok:
            imgui.bullet()
            imgui.text_wrapped(f"{label}: valid, {v.passes} pass{'es' if v.passes != 1 else ''} "
                               f"(not chosen){fidelity_note(loaded, v)}")
            continue
        reasons = [str(r) for r in v.reasons] or ["not valid"]
        more = len(reasons) - 1
        opened = False
        if more > 0:
            opened = imgui.tree_node(f"{label}  (+{more} more reason{'s' if more > 1 else ''})##{label}")
        else:
            imgui.bullet()
            imgui.text(label)
        imgui.indent()
        for reason in reasons[:1 + more * opened]:
            imgui.text_wrapped(reason)
        imgui.unindent()
        if opened:
            imgui.tree_pop()
    if pending:
        imgui.bullet()
        imgui.text_wrapped(f"{', '.join(t.name or '<anonymous>' for t in pending)}: being "
                           "validated (after the first frame of this reload)")


def fidelity_note(loaded: "LoadedEffect", validation: "Validation") -> str:
    """', SSIM 0.934, PSNR 27.4 dB' for a measured valid technique; '' until it is."""
    position = next((i for i, v in enumerate(loaded.validations) if v is validation), None)
    found = getattr(loaded, "fidelity", {}).get(position)
    return f", {found}" if found is not None else ""


def fidelity_heading(loaded: "LoadedEffect") -> str:
    """What the figures are measured against, or that they are being measured."""
    best = getattr(loaded, "fidelity_best", None)
    if getattr(loaded, "fidelity_done", True):
        return f"fidelity: against {best} on refrast" if best is not None else \
            "fidelity: nothing runs on refrast to measure against"
    return "fidelity: measuring..." if best is None else \
        f"fidelity: against {best} on refrast (measuring...)"


def _view(state: ViewerState, status: Status) -> None:
    for view in VIEWS:
        if imgui.radio_button(view, state.view == view):
            state.set_view(view)
        imgui.same_line()
    imgui.new_line()
    imgui.text(VIEW_TITLES[state.view].format(scale=DIFFERENCE_SCALE))
    imgui.set_next_item_width(140)
    options = list(MESHES)
    if state.mesh not in MESHES:     # the scene's or --mesh's file, or the effect's own
        options.append(os.path.basename(state.mesh) if state.mesh else "(default)")
    mesh_index = options.index(state.mesh) if state.mesh in MESHES else len(options) - 1
    changed, index = imgui.combo("mesh", mesh_index, options)
    if changed and index < len(MESHES):
        state.set_mesh(MESHES[index])
    imgui.same_line()
    changed, animate = imgui.checkbox("move light", state.light.animate)
    if changed:
        state.light.animate = animate
    gl = f"{status.gl_ms:.1f} ms" if status.gl_ms is not None else "-"
    ref = f"{status.reference_ms:.0f} ms" if status.reference_ms is not None else "-"
    imgui.text(f"Render time: GL {gl}   reference {ref}")
    if state.view != "gl":
        if status.reference_busy:
            imgui.text_colored(YELLOW, "reference: rendering...")
        if status.reference_error:
            imgui.text_colored(RED, "reference failed:")
            imgui.text_wrapped(status.reference_error)
        if state.view == "difference" and status.difference is not None:
            d = status.difference
            imgui.text(f"|GL - ref|: max {d.max}, mean {d.mean:.2f}, "
                       f"{100 * d.over_2:.1f}% of pixels off by > 2")
    if status.render_error:
        imgui.text_colored(RED, "render failed:")
        imgui.text_wrapped(status.render_error)


def _parameters(state: ViewerState, status: Status) -> None:
    """The clock, when the effect reads it, and a widget for each tweakable parameter."""
    clock = state.clock
    if status.reads_time:
        what = "held (--time)" if clock.fixed else "running" if clock.running else "paused"
        imgui.text(f"TIME {clock.seconds:8.3f} s, {what}")
        imgui.same_line()
        if imgui.button("Run" if clock.fixed or not clock.running else "Pause"):
            state.toggle_clock()
        imgui.same_line()
        if imgui.button("Step"):
            state.step_clock(1)
    loaded = status.loaded
    if loaded is None:
        return
    if status.tweakables is None or status.tweakables[0] is not loaded.effect:
        status.tweakables = (loaded.effect, tweakables(loaded.effect))   # once per build
    items = status.tweakables[1]
    if not items or not imgui.collapsing_header("Parameters", imgui.TreeNodeFlags_.default_open):
        return
    effect = getattr(status.runtime, "effect", None) or loaded.effect
    status.widget_rects.clear()
    for item in items:
        imgui.push_id(item.name)
        _parameter(state, status, item, effect.parameter(item.name))
        imgui.pop_id()


def _parameter(state: ViewerState, status: Status, item: Tweakable, param: Any) -> None:
    edited = state.tweaks.get(item)
    imgui.text(item.label)
    if edited is not None:
        imgui.same_line()
        if imgui.small_button("reset"):
            state.reset_param(item)
    imgui.set_next_item_width(-1)
    label = f"##{item.name}"
    if item.widget == "texture":
        text = status.texture_text.get(item.name, edited if isinstance(edited, str) else "")
        hint = "(a stand-in)"
        scene_value = state.base_scene.params.get(item.name)
        if isinstance(scene_value, str):
            hint = f"{scene_value} (the scene's)"
        for name in ("ResourceName", "Procedural"):     # the file's own image, or generator
            own = param.annotation(name) if param is not None else None
            if scene_value is None and own is not None and isinstance(own.value, str) \
                    and own.value.strip():
                hint = own.value
                break
        entered, text = imgui.input_text_with_hint(label, hint, text,
                                                   imgui.InputTextFlags_.enter_returns_true)
        status.texture_text[item.name] = text
        if entered:
            if text.strip():
                state.set_param(item, text.strip())
            else:
                state.reset_param(item)
        if imgui.is_item_hovered():
            imgui.set_tooltip("an image file (Enter applies it); empty: the effect's own")
    else:
        value = current_value(param, item)
        if value is None:
            imgui.text_colored(GREY, "(no value)")
            return
        changed, new = _numeric_widget(label, item, value)
        if changed:
            state.set_param(item, new)
    lo, hi = imgui.get_item_rect_min(), imgui.get_item_rect_max()
    status.widget_rects[item.name] = (lo.x, lo.y, hi.x, hi.y)
    error = state.tweaks.errors.get(item.name)
    if error:
        imgui.text_colored(RED, "not applied:")
        imgui.text_wrapped(error)


_SLIDERS = {1: imgui.slider_float, 2: imgui.slider_float2, 3: imgui.slider_float3,
            4: imgui.slider_float4}
_DRAGS = {1: imgui.drag_float, 2: imgui.drag_float2, 3: imgui.drag_float3, 4: imgui.drag_float4}
_INT_SLIDERS = {1: imgui.slider_int, 2: imgui.slider_int2, 3: imgui.slider_int3,
                4: imgui.slider_int4}
_INT_DRAGS = {1: imgui.drag_int, 2: imgui.drag_int2, 3: imgui.drag_int3, 4: imgui.drag_int4}


def _numeric_widget(label: str, item: Tweakable, value: Any) -> tuple[bool, Any]:
    """One imgui widget for a number, a vector, a colour or a bool: (changed, new value)."""
    if item.widget == "checkbox":
        return imgui.checkbox(label, bool(value))
    n = item.components
    if item.widget == "color":
        edit = imgui.color_edit4 if n == 4 else imgui.color_edit3
        return edit(label, value)
    one = (lambda v: v[0]) if n == 1 else (lambda v: v)
    back = (lambda v: [v]) if n == 1 else (lambda v: list(v))
    if item.integral:
        ints = [int(round(v)) for v in value]
        if any(not -2**31 <= v < 2**31 for v in ints):
            return _hex_field(label, ints)   # a DWORD past imgui's int (EffectEdit's BCLR colour)
        if item.widget == "slider":
            changed, new = _INT_SLIDERS[n](label, one(ints), int(item.lo), int(item.hi))
        else:
            changed, new = _INT_DRAGS[n](label, one(ints), float(item.step or 1.0),
                                         int(item.lo or 0), int(item.hi or 0))
        return changed, back(new)
    if item.widget == "slider":
        changed, new = _SLIDERS[n](label, one(value), float(item.lo), float(item.hi))
    else:
        # a spinner: dragged by UIStep per pixel; bounded when the file gives both ends
        bounded = item.lo is not None and item.hi is not None
        changed, new = _DRAGS[n](label, one(value), float(item.step or 0.01),
                                 float(item.lo) if bounded else 0.0,
                                 float(item.hi) if bounded else 0.0)
    return changed, back(new)


def _hex_field(label: str, ints: list[int]) -> tuple[bool, Any]:
    """Whole numbers as hexadecimal text, applied on Enter (0x... or decimal, 32 bits each)."""
    text = " ".join(f"0x{v & 0xFFFFFFFF:08X}" for v in ints)
    entered, text = imgui.input_text(label, text, imgui.InputTextFlags_.enter_returns_true)
    if not entered:
        return False, ints
    try:
        values = [int(part, 0) for part in text.replace(",", " ").split()]
    except ValueError:
        return False, ints
    if len(values) != len(ints) or any(not 0 <= v <= 0xFFFFFFFF for v in values):
        return False, ints
    return True, values


def _reload(status: Status, actions: Actions) -> None:
    if imgui.button("Reload (R)"):
        actions.reload()
    imgui.same_line()
    if imgui.button("Screenshot (S)"):
        actions.screenshot()
    if status.last_reload:
        imgui.text_wrapped(status.last_reload)
    if status.error:
        imgui.text_colored(RED, "Last reload failed; still drawing the last good effect:")
        first, *rest = status.error.splitlines()
        imgui.text_wrapped(first)
        for line in rest:          # the source line and its caret: unwrapped, so they align
            imgui.text(line)
    if status.scene_error:
        imgui.text_colored(RED, "The scene file failed; still drawing the last good scene:")
        first, *rest = status.scene_error.splitlines()
        imgui.text_wrapped(first)
        for line in rest:
            imgui.text(line)
    for message in status.messages[-3:]:
        imgui.text_colored(GREY, message)


def draw_listing(status: Status, text: str, rect: tuple[float, float, float, float]) -> None:
    """The listing window over the picture, in rect = (x, y, w, h): the text the viewer holds
    for the technique drawn (`Viewer.listing_text`), scrollable; after a failed reload the
    error first, since the listing is the last good effect's."""
    x, y, w, h = rect
    imgui.set_next_window_pos(imgui.ImVec2(x, y), imgui.Cond_.always)
    imgui.set_next_window_size(imgui.ImVec2(w, h), imgui.Cond_.always)
    imgui.set_next_window_bg_alpha(0.92)
    flags = (imgui.WindowFlags_.no_move | imgui.WindowFlags_.no_resize
             | imgui.WindowFlags_.no_collapse | imgui.WindowFlags_.no_saved_settings
             | imgui.WindowFlags_.horizontal_scrollbar)
    imgui.begin("listing (C hides)", None, flags)
    if status.error:
        imgui.text_colored(RED, "Last reload failed; the listing of the last good effect:")
        imgui.text_wrapped(status.error.splitlines()[0])
        imgui.separator()
    imgui.text_unformatted(text)
    imgui.end()
