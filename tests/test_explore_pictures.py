"""The explorers' pictures: in static renders (the display's MIME bundle), sharp, nothing clipped, readable ticks."""

from __future__ import annotations

import base64
import io

import numpy as np
import pytest

pytest.importorskip("ipywidgets")

from matplotlib.image import imread  # noqa: E402
from matplotlib.text import Text  # noqa: E402

from aliasing import explore  # noqa: E402
from aliasing.explore import widget  # noqa: E402

WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"

#: Settings at the ends of the sliders' ranges (and the defaults, {}), per explorer.
EXTREMES = {
    "overhead": [{}, {"f_over_n": 1.5}, {"f_over_n": 1e5, "fov": 150.0}, {"f_over_n": 1.5, "fov": 5.0, "rule": "eta", "eta": 1.0},
                 {"rule": "eta", "eta": -1.0}, {"aspect": 4.0, "f_over_n": 1e5, "fov": 150.0}, {"aspect": 0.25, "f_over_n": 1.5, "fov": 5.0, "rule": "uniform"}],
    "directions": [{"resolution": 16}, {"f_over_n": 1.5, "fov": 5.0, "gamma": 0.0, "azimuth": -90.0, "resolution": 8},
                   {"f_over_n": 1e5, "fov": 150.0, "gamma": 180.0, "azimuth": 90.0, "resolution": 16},
                   {"scheme": "FPcs+ZP4+LogP", "resolution": 16}, {"scheme": "ZP4+LogP", "aspect": 4.0, "f_over_n": 1e5, "fov": 150.0, "resolution": 16},
                   {"aspect": 0.25, "f_over_n": 1.5, "fov": 5.0, "resolution": 8}],
    "cascades": [{}, {"k": 1}, {"k": 8, "far": 1e6}, {"k": 8, "near": 1e-3, "far": 1.5e-3, "fov": 150.0}, {"method": "log", "k": 8, "budget": 512**2},
                 {"k": 8, "far": 1e6, "aspect": 4.0, "fov": 150.0}, {"aspect": 0.25, "k": 1}],
    "faces": [{}, {"variant": "fp"}, {"variant": "fpcs", "gamma": 0.0, "azimuth": -180.0, "f_over_n": 1.5, "fov": 150.0},
              {"variant": "fpcs", "gamma": 30.0, "azimuth": 45.0, "f_over_n": 1e5, "fov": 150.0},
              {"variant": "fpc", "gamma": 180.0, "azimuth": 180.0, "f_over_n": 1e5, "fov": 5.0},
              {"variant": "fpcs", "gamma": 20.0, "azimuth": 30.0, "f_over_n": 100.0}],  # the notebook's: arrows past the outline
    "raster": [{"image_res": 32}, {"f_over_n": 1.5, "fov": 10.0, "image_res": 32, "every": 1},
               {"f_over_n": 1e4, "fov": 120.0, "image_res": 32, "scheme": "FPcs+LogP", "budget": 64**2, "every": 64},
               {"aspect": 4.0, "image_res": 32, "scheme": "ZP3+P", "f_over_n": 1e4, "fov": 120.0}, {"aspect": 0.25, "image_res": 32, "fov": 10.0}],
    "bias": [{}, {"aspect": 4.0, "k": 6, "far": 1e5, "elevation": 5.0}, {"aspect": 0.25, "k": 1, "far": 1.0, "elevation": 85.0}],
    "shimmer": [{"frames": 6, "image_res": 48, "shadow_res": 128}, {"aspect": 2.0, "frames": 6, "image_res": 48, "shadow_res": 128},
                {"aspect": 4.0, "frames": 6, "image_res": 48, "shadow_res": 128, "scheme": "csm-stable:log:k=4:fit=sphere:snap=origin", "motion": "zoom:1"},
                {"aspect": 0.25, "frames": 6, "image_res": 48, "shadow_res": 128, "scene": "city", "scheme": "sdsm:k=3"}],
}
CASES = [(name, values) for name, settings in EXTREMES.items() for values in settings]


def _drawn_texts(fig) -> list[Text]:
    """The text artists drawn in the figure: titles, labels, legends, annotations and the tick labels in view."""
    fig.canvas.draw()
    tick_labels, drawn = set(), set()
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            for tick in axis.majorTicks + axis.minorTicks:
                tick_labels |= {id(tick.label1), id(tick.label2)}
            for tick in axis._update_ticks():  # the ticks inside the view, the ones drawn
                drawn |= {id(tick.label1), id(tick.label2)}
    return [t for t in fig.findobj(Text) if t.get_visible() and t.get_text().strip() and (id(t) not in tick_labels or id(t) in drawn)]


def _bundle_png(e) -> tuple[np.ndarray, bytes, dict, dict]:
    data, meta = e._repr_mimebundle_()
    raw = base64.b64decode(data["image/png"])
    return imread(io.BytesIO(raw), format="png"), raw, data, meta


@pytest.mark.parametrize("name", list(EXTREMES))
def test_display_bundle_holds_the_widget_view_a_png_of_the_state_and_text(name):
    e = getattr(explore, name)(**EXTREMES[name][0])
    img, raw, data, meta = _bundle_png(e)
    assert set(data) == {WIDGET_VIEW, "image/png", "text/plain"}
    assert data[WIDGET_VIEW]["model_id"] == e.model_id  # the live view in JupyterLab
    assert raw == e.png() and raw.startswith(b"\x89PNG\r\n\x1a\n")
    h, w = img.shape[:2]
    assert (w, h) == (int(e.figsize[0] * e.dpi), int(e.figsize[1] * e.dpi))
    assert meta["image/png"]["width"] == e.css_width() and w / e.css_width() >= 2.0  # drawn at 2 device pixels per CSS pixel
    assert img[..., :3].std() > 0.05  # a picture, not a blank canvas
    assert e.title in data["text/plain"]
    for control in e.controls.values():
        assert f"{control.description} = {widget._shown(control)}" in data["text/plain"]


def test_display_bundle_follows_a_control_change():
    e = explore.overhead()
    before, raw_before, _, _ = _bundle_png(e)
    e.controls["f_over_n"].value = 10.0
    after, raw_after, data, _ = _bundle_png(e)
    assert e.error is None and raw_after == e.png() and raw_after != raw_before
    assert before.shape == after.shape and np.abs(after - before).max() > 0.5  # the curves moved
    assert "f/n = 10" in data["text/plain"] and "f/n = 1000" not in data["text/plain"]


def test_ipython_publishes_the_png_beside_the_widget_view():
    """What a kernel sends for ``display(e)``: IPython's formatter reads the bundle."""
    formatters = pytest.importorskip("IPython.core.formatters")
    e = explore.faces()
    data, meta = formatters.DisplayFormatter().format(e)
    assert WIDGET_VIEW in data and base64.b64decode(data["image/png"]) == e.png()
    assert meta["image/png"]["width"] == e.css_width()


@pytest.mark.parametrize("name, values", CASES, ids=[f"{n}-{i}" for n, s in EXTREMES.items() for i in range(len(s))])
def test_no_text_outside_the_figure_or_overlapping_and_log_axes_readable(name, values):
    e = getattr(explore, name)(**values)
    assert e.error is None, e.error
    fig = e.figure
    renderer = fig.canvas.get_renderer()
    width, height = fig.bbox.width, fig.bbox.height
    texts = _drawn_texts(fig)
    assert len(texts) >= 3  # at least the titles
    outside = []
    for t in texts:
        bb = t.get_window_extent(renderer)
        if bb.x0 < 0 or bb.y0 < 0 or bb.x1 > width or bb.y1 > height:
            outside.append(f"{t.get_text()[:40]!r} at {np.round(bb.extents).tolist()} (figure {width:.0f} × {height:.0f})")
    assert not outside, outside
    drawn = {id(t) for t in texts}
    crossing = []
    for ax in fig.axes:  # one panel's tick labels never run into another panel's axis labels or title
        ticks = [lab for axis in (ax.xaxis, ax.yaxis) for tick in axis._update_ticks() for lab in (tick.label1, tick.label2) if id(lab) in drawn]
        for other in fig.axes:
            if other is ax:
                continue
            for label in (other.xaxis.label, other.yaxis.label, other.title):
                if id(label) in drawn:
                    box = label.get_window_extent(renderer)
                    crossing += [f"{t.get_text()!r} on {label.get_text()!r}" for t in ticks if t.get_window_extent(renderer).overlaps(box)]
    assert not crossing, crossing
    for ax in fig.axes:  # nor do the tick labels of one axis run into each other
        for axis in (ax.xaxis, ax.yaxis):
            boxes = [lab.get_window_extent(renderer) for tick in axis._update_ticks() for lab in (tick.label1, tick.label2) if id(lab) in drawn]
            hits = [(i, j) for i in range(len(boxes)) for j in range(i + 1, len(boxes)) if boxes[i].overlaps(boxes[j])]
            assert not hits, (axis.axis_name, [lab.get_text() for lab in axis.get_ticklabels()])
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            if axis.get_scale() == "log" and axis.get_visible():
                labels = [lab.get_text() for t in axis._update_ticks() for lab in (t.label1, t.label2) if lab.get_visible() and lab.get_text()]
                assert len(labels) >= widget.MIN_TICKS, (axis.axis_name, labels)


@pytest.mark.parametrize("values", EXTREMES["faces"])
def test_faces_arrow_labels_clear_of_the_legend(values):
    e = explore.faces(**values)
    fig = e.figure
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    a = fig.axes[0]
    legend = a.get_legend().get_window_extent(renderer)
    title = a.title.get_window_extent(renderer)
    for _, label in e._artists["arrows"]:
        box = label.get_window_extent(renderer)
        assert not box.overlaps(legend) and not box.overlaps(title), label.get_text()


@pytest.mark.parametrize("lo, hi", [(1.0, 1.5), (1.0, 1.01), (0.3, 0.5), (1.0, 1e5), (2.0, 9.0), (1e-3, 1.5e-3), (5e4, 6e5), (1e8, 1.1e8)])
def test_log_locator_gives_three_labelled_ticks_on_any_range(lo, hi):
    ticks = widget.ReadableLogLocator().tick_values(lo, hi)
    assert len(ticks) >= widget.MIN_TICKS and (ticks >= lo * (1 - 1e-9)).all() and (ticks <= hi * (1 + 1e-9)).all()
    labels = [widget._tick_label(t) for t in ticks]
    assert len(set(labels)) == len(labels) and all(labels), labels  # distinct, none empty
