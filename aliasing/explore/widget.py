"""The explorer widget: controls → ``compute`` (pure, a dict) → ``draw`` (matplotlib) → PNG.

The figure is drawn with matplotlib's object-oriented API on an Agg canvas and shown as
a PNG in an ``ipywidgets.Image``: it needs no live front end (explorers build headless in
tests and in nbmake), and the picture is what a saved notebook shows.  Changes are
debounced: inside a running kernel (an asyncio loop) the update runs ``debounce`` seconds
after the last change; without a loop (tests, scripts) it runs at once.  Any error of
``compute`` or ``draw`` goes to the message line; the last good data and picture stay.
"""

from __future__ import annotations

import asyncio
import html
import io
from typing import Any

import ipywidgets as widgets
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

#: Seconds after the last change before an update runs (in a live kernel).
DEBOUNCE = 0.15


class Explorer(widgets.VBox):
    """Base of the explorers: subclasses define ``make_controls()``, ``compute(**values)``, ``draw(fig, data)``
    and optionally ``redraw(artists, data)``.

    Attributes
    ----------
    controls : dict of str → ipywidgets.ValueWidget
        The parameters, by the name ``compute`` takes them.
    data : dict or None
        What the last successful update computed (and drew).
    error : str or None
        The message of the last failed update, None after a good one.
    figure : matplotlib.figure.Figure
        The figure drawn into ``image``.
    """

    title = ""
    figsize = (9.0, 3.6)
    dpi = 72

    def __init__(self, debounce: float = DEBOUNCE, **values: Any) -> None:
        self.controls = self.make_controls()
        self.debounce = float(debounce)
        self.data: dict | None = None
        self.error: str | None = None
        self.updates = 0
        self._pending: asyncio.TimerHandle | None = None
        self._hold = False
        self._artists: dict | None = None
        self.message = widgets.HTML(value="")
        self.image = widgets.Image(format="png")
        self.figure = Figure(figsize=self.figsize, dpi=self.dpi)
        FigureCanvasAgg(self.figure)
        for w in self.controls.values():
            w.observe(self._changed, names="value")
        boxes = [widgets.HBox(list(row)) for row in _rows(list(self.controls.values()), 3)]
        super().__init__([widgets.HTML(f"<b>{html.escape(self.title)}</b>"), *boxes, self.message, self.image])
        self.set_state(values) if values else self.update()

    # -- to be defined by each explorer ------------------------------------------------
    def make_controls(self) -> dict[str, widgets.ValueWidget]:  # pragma: no cover - abstract
        raise NotImplementedError

    def compute(self, **values: Any) -> dict:  # pragma: no cover - abstract
        raise NotImplementedError

    def draw(self, fig: Figure, data: dict) -> dict | None:  # pragma: no cover - abstract
        """Draw ``data`` on the cleared ``fig``; may return its artists for :meth:`redraw`."""
        raise NotImplementedError

    def redraw(self, artists: dict, data: dict) -> bool:
        """Update the artists :meth:`draw` returned in place (half the time of a new figure).

        Returns False when the picture must be drawn anew (the default).
        """
        return False

    # -- state ---------------------------------------------------------------------------
    def state(self) -> dict[str, Any]:
        """The controls' values ``{name: value}`` (what :meth:`set_state` takes back)."""
        return {name: w.value for name, w in self.controls.items()}

    def set_state(self, values: dict[str, Any]) -> bool:
        """Set several controls at once and update once; returns whether the update succeeded.

        Unknown names raise ``ValueError``; a value a control cannot hold (outside a slider's
        range, not an option) raises the widget's own ``TraitError``.
        """
        unknown = set(values) - set(self.controls)
        if unknown:
            raise ValueError(f"unknown control(s) {sorted(unknown)}; this explorer has {list(self.controls)}")
        self._hold = True
        try:
            for name, value in values.items():
                self.controls[name].value = value
        finally:
            self._hold = False
        return self.update()

    # -- updating ------------------------------------------------------------------------
    def _changed(self, change: dict) -> None:
        if self._hold:
            return
        try:
            loop = asyncio.get_running_loop()
        except RuntimeError:  # no kernel loop (tests, scripts): update now
            self.update()
            return
        if self._pending is not None:
            self._pending.cancel()
        self._pending = loop.call_later(self.debounce, self.update)

    def update(self) -> bool:
        """Recompute and redraw from the controls; on error show it and keep the last picture."""
        self._pending = None
        try:
            with np.errstate(all="ignore"):
                data = self.compute(**self.state())
                fig = self.figure
                if self._artists is None or not self.redraw(self._artists, data):
                    fig.clear()
                    self._artists = None
                    self._artists = self.draw(fig, data)
                    for ax in fig.axes:  # log axes' minor ticks cost most of a redraw
                        ax.minorticks_off()
                buf = io.BytesIO()
                fig.savefig(buf, format="png", dpi=self.dpi, pil_kwargs={"compress_level": 1})
        except Exception as exc:  # shown in the widget, never a traceback in the notebook
            text = str(exc) if isinstance(exc, ValueError) else f"{type(exc).__name__}: {exc}"
            self.error = text
            self.message.value = f'<span style="color:#b00020">&#9888; {html.escape(text)} (showing the last good state)</span>'
            return False
        self.data, self.error = data, None
        self.image.value = buf.getvalue()
        self.message.value = ""
        self.updates += 1
        return True

    def snapshot(self, path: str, dpi: float = 110.0) -> str:
        """Save the current picture with the controls' values written above it (a PNG for docs).

        Returns ``path``.  The controls are listed as ``description = value``.
        """
        if self.data is None:
            raise ValueError("nothing to save: no successful update yet")
        fig = self.figure
        values = "   ".join(f"{w.description} = {_shown(w)}" for w in self.controls.values())
        fig.subplots_adjust(top=fig.subplotpars.top - 0.06)
        label = fig.text(0.01, 0.985, f"{self.title}\n{values}", ha="left", va="top", fontsize=7.5, family="monospace",
                         bbox={"fc": "#eef2f7", "ec": "#9aa7b8", "boxstyle": "round,pad=0.4"})
        try:
            fig.savefig(path, dpi=dpi)
        finally:
            label.remove()
            fig.subplots_adjust(top=fig.subplotpars.top + 0.06)
        return path

    def png(self) -> bytes:
        """The PNG currently shown."""
        return bytes(self.image.value)


def _shown(widget: widgets.ValueWidget) -> str:
    """A control's value as its label shows it (the option's label for dropdowns)."""
    label = getattr(widget, "label", None)
    if label is not None:
        return str(label)
    value = widget.value
    return f"{value:.4g}" if isinstance(value, float) else str(value)


def _rows(items: list, n: int) -> list[list]:
    return [items[i:i + n] for i in range(0, len(items), n)]


def log_slider(description: str, value: float, lo: float, hi: float) -> widgets.FloatLogSlider:
    """A base-10 logarithmic slider from ``lo`` to ``hi`` (released-only updates)."""
    return widgets.FloatLogSlider(value=value, base=10, min=np.log10(lo), max=np.log10(hi), step=0.05, description=description,
                                  continuous_update=False, readout_format=".3g", style={"description_width": "initial"})


def slider(description: str, value: float, lo: float, hi: float, step: float = 1.0) -> widgets.FloatSlider:
    """A linear slider (released-only updates)."""
    return widgets.FloatSlider(value=value, min=lo, max=hi, step=step, description=description, continuous_update=False,
                               style={"description_width": "initial"})


def text(description: str, value: str, placeholder: str = "") -> widgets.Text:
    """A text box that updates on Enter or leaving it."""
    return widgets.Text(value=value, description=description, placeholder=placeholder, continuous_update=False,
                        style={"description_width": "initial"})


def dropdown(description: str, options: list, value: Any) -> widgets.Dropdown:
    return widgets.Dropdown(options=options, value=value, description=description, style={"description_width": "initial"})
