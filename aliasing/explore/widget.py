"""The explorer widget: controls → ``compute`` (pure, a dict) → ``draw`` (matplotlib) → PNG.

The figure is drawn with matplotlib's object-oriented API on an Agg canvas and shown as
a PNG in an ``ipywidgets.Image``: it needs no live front end (explorers build headless in
tests and in nbmake).  The PNG is drawn at :data:`PIXEL_RATIO` device pixels per CSS pixel
(``dpi`` = :data:`CSS_DPI` × :data:`PIXEL_RATIO`) and shown :data:`CSS_DPI` CSS pixels per
inch of the figure, sharp on high-density screens.  The display's MIME bundle
(:meth:`Explorer._repr_mimebundle_`) holds the live widget view and, beside it, the same
picture as ``image/png`` and the controls' values as ``text/plain``: a front end without
the widget manager (nbconvert, myst-nb, GitHub) shows the picture of the explorer's state.  Changes are
debounced: inside a running kernel (an asyncio loop) the update runs ``debounce`` seconds
after the last change; without a loop (tests, scripts) it runs at once.  Any error of
``compute`` or ``draw`` goes to the message line; the last good data and picture stay.
"""

from __future__ import annotations

import asyncio
import base64
import html
import io
from typing import Any

import ipywidgets as widgets
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.ticker import FuncFormatter, Locator, LogLocator, MaxNLocator

#: Seconds after the last change before an update runs (in a live kernel).
DEBOUNCE = 0.15
#: CSS pixels per inch of the figure as shown in the notebook (the CSS inch).
CSS_DPI = 96
#: Device pixels drawn per CSS pixel (a high-density screen's ratio); the figure's dpi is CSS_DPI × PIXEL_RATIO.
PIXEL_RATIO = 2
#: Fewest labelled ticks on a logarithmic axis (:class:`ReadableLogLocator`).
MIN_TICKS = 3


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
    dpi = CSS_DPI * PIXEL_RATIO

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
        self.image = widgets.Image(format="png", layout=widgets.Layout(width=f"{self.css_width()}px", max_width="100%", height="auto"))
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
                buf = _png(fig)
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

    def css_width(self) -> int:
        """Width [CSS pixels] the picture is shown at: the figure's width at :data:`CSS_DPI`."""
        return round(self.figsize[0] * CSS_DPI)

    def describe(self) -> str:
        """The explorer's title and its controls' values, one line of ``description = value`` each."""
        return "\n".join([self.title] + [f"  {w.description} = {_shown(w)}" for w in self.controls.values()])

    def _repr_mimebundle_(self, **kwargs: Any) -> tuple[dict, dict]:
        """The widget view (live in JupyterLab) with the picture of the current state beside it.

        ``image/png`` (base64, shown :meth:`css_width` CSS pixels wide) is what nbconvert,
        myst-nb and GitHub show where no widget manager runs; ``text/plain`` lists the
        controls' values (:meth:`describe`).
        """
        data = dict(super()._repr_mimebundle_(**kwargs))
        data["text/plain"] = self.describe()
        meta = {}
        if self.image.value:
            data["image/png"] = base64.b64encode(self.png()).decode("ascii")
            meta["image/png"] = {"width": self.css_width()}
        return data, meta


def _png(fig: Figure) -> io.BytesIO:
    """The figure drawn once on its Agg canvas, as an RGB PNG (fast zlib level 1; the figure is opaque)."""
    from PIL import Image  # matplotlib's own dependency

    fig.canvas.draw()
    buf = io.BytesIO()
    Image.fromarray(np.asarray(fig.canvas.buffer_rgba())[..., :3]).save(buf, format="png", compress_level=1)
    return buf


def _shown(widget: widgets.ValueWidget) -> str:
    """A control's value as its label shows it (the option's label for dropdowns)."""
    label = getattr(widget, "label", None)
    if label is not None:
        return str(label)
    value = widget.value
    return f"{value:.4g}" if isinstance(value, float) else str(value)


class ReadableLogLocator(Locator):
    """Ticks of a logarithmic axis with at least :data:`MIN_TICKS` inside any view range.

    Decades (1, 10, 100, …) when the range holds enough of them, else 1-2-5 steps, else
    (a range under a decade, e.g. f/n from 1 to 1.5) evenly spaced round values.

    Example
    -------
    >>> ReadableLogLocator().tick_values(1.0, 1e4).tolist()
    [1.0, 10.0, 100.0, 1000.0, 10000.0]
    >>> ReadableLogLocator().tick_values(1.0, 1.5).tolist()
    [1.0, 1.2, 1.4]
    """

    def __call__(self):
        lo, hi = self.axis.get_view_interval()
        return self.tick_values(lo, hi)

    def tick_values(self, vmin: float, vmax: float) -> np.ndarray:
        lo, hi = sorted((float(vmin), float(vmax)))
        if not (np.isfinite(lo) and np.isfinite(hi) and hi > lo > 0):
            return np.array([])
        inside = lambda t: t[(t >= lo * (1 - 1e-9)) & (t <= hi * (1 + 1e-9))]  # noqa: E731
        for subs in ((1.0,), (1.0, 2.0, 5.0)):
            ticks = inside(LogLocator(base=10.0, subs=subs, numticks=12).tick_values(lo, hi))
            if len(ticks) >= MIN_TICKS:
                return ticks
        return inside(MaxNLocator(nbins=4, steps=[1, 2, 2.5, 5, 10], min_n_ticks=MIN_TICKS).tick_values(lo, hi))


def _tick_label(x: float, pos: int | None = None) -> str:
    """A log axis's tick as a plain number from 0.001 to 9999 (1, 20, 0.5, 1.25, 1000), else m×10ᵏ (10⁵, 5×10⁴)."""
    if x <= 0 or not np.isfinite(x):
        return ""
    if 1e-3 <= x < 1e4:
        return f"{x:.4g}"
    k = int(np.floor(np.log10(x) + 1e-9))
    m = x / 10.0**k
    return f"$10^{{{k}}}$" if abs(m - 1) < 1e-6 else f"${m:.3g}\\times10^{{{k}}}$"


def short_number(x: float) -> str:
    """A number in at most 3 significant digits, exponents without sign or padding: for crowded labels.

    Example
    -------
    >>> [short_number(x) for x in (7.53e9, 0.25, 1.2e-4, 1448.0, 0.0)]
    ['7.53e9', '0.25', '1.2e-4', '1.45e3', '0']
    """
    if x == 0 or not np.isfinite(x):
        return f"{x:g}"
    if 1e-3 <= abs(x) < 1e3:
        return f"{x:.3g}"
    mantissa, exponent = f"{x:.2e}".split("e")
    return f"{float(mantissa):g}e{int(exponent)}"


def readable_log_ticks(*axes: Any) -> None:
    """Give each logarithmic matplotlib axis (``ax.xaxis``, ``ax.yaxis``) :class:`ReadableLogLocator`'s labelled ticks.

    Example
    -------
    >>> fig = Figure()
    >>> ax = fig.subplots()
    >>> ax.set_xscale("log"); ax.set_xlim(1.0, 1.5)
    (1.0, 1.5)
    >>> readable_log_ticks(ax.xaxis)
    >>> [t.get_text() for t in ax.xaxis.get_ticklabels()]
    ['1', '1.2', '1.4']
    """
    for axis in axes:
        axis.set_major_locator(ReadableLogLocator())
        axis.set_major_formatter(FuncFormatter(_tick_label))


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
