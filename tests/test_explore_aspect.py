"""The explorers' aspect control (width/height, fov vertical): aspect 1 is the old output, aspect ≠ 1 the library's."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

pytest.importorskip("ipywidgets")

from aliasing import View, budgets, error, explore, schemes, warping  # noqa: E402
from aliasing.bias.cascades import cascade_bias  # noqa: E402
from aliasing.explore import _bias, _cascades, _overhead, _raster, _shimmer  # noqa: E402
from aliasing import pictures  # noqa: E402
from aliasing.raster.validate import validate  # noqa: E402
from aliasing.temporal import measure, points  # noqa: E402

BAD_ASPECTS = st.one_of(st.floats(max_value=0.0, allow_nan=False), st.sampled_from([math.nan, math.inf, -math.inf]))

#: One setting per explorer with an aspect control (the positional arguments of its compute).
SETTINGS = {
    _overhead: ((300.0, 50.0, "lispsm", 0.0, "inf", 1024), ("rule", "eta")),
    _cascades: (("practical", 3, 0.5, 1.0, 300.0, 60.0, "P", 2048**2, "error", 1024), ()),
    _raster: (("ZP2+P", "gamma:60@azimuth:30", 50.0, 60.0, 32, 64 * 64, 8), ()),
    _bias: (("bevy", 30.0, 3, 0.5, 100.0, 1024, 1080), ()),
    _shimmer: (("boxes", "csm:log:k=3", "translate:0.05,0,0", 3, 1, 32, 64), ()),
}


def _same(a: dict, b: dict) -> None:
    """Equal key for key, arrays element for element, nested rows too (NaN equals NaN: np.testing.assert_equal)."""
    assert a.keys() == b.keys()
    for key in a:
        np.testing.assert_equal(a[key], b[key], err_msg=key)


@pytest.mark.parametrize("module", list(SETTINGS), ids=lambda m: m.__name__.rsplit(".", 1)[-1])
def test_aspect_one_is_the_output_without_it(module):
    args, _ = SETTINGS[module]
    _same(module.compute(*args), module.compute(*args, aspect=1.0))


@pytest.mark.parametrize("module", list(SETTINGS), ids=lambda m: m.__name__.rsplit(".", 1)[-1])
@settings(max_examples=15, deadline=None)
@given(aspect=BAD_ASPECTS)
def test_bad_aspect_is_refused_naming_it(module, aspect):
    args, _ = SETTINGS[module]
    with pytest.raises(ValueError, match="^aspect") as info:
        module.compute(*args, aspect=aspect)
    assert "\n" not in str(info.value)


def test_bad_aspect_is_shown_in_the_explorer_and_the_last_picture_kept():
    e = explore.overhead()
    good, picture = e.data, e.png()
    e.compute = lambda **values: _overhead.compute(**{**values, "aspect": -1.0})  # the slider cannot go there: a typed call can
    assert not e.update()
    assert e.error.startswith("aspect") and e.data is good and e.png() == picture


# ------------------------------------------------------------------------------------------- overhead


@pytest.mark.parametrize("rule", ["uniform", "psm", "lispsm"])
@pytest.mark.parametrize("aspect", [0.5, 2.0, 16 / 9])
def test_overhead_wide_view_is_the_general_evaluation_and_scales_m_x(rule, aspect):
    """symbolic/aspect.py: m_x and M_x times the aspect, m_z and M_z unchanged, S̄ times the
    aspect (overhead light); the explorer's numbers are the general evaluation's."""
    sq = _overhead.compute(300.0, 50.0, rule, 0.0, "inf", 1024)
    d = _overhead.compute(300.0, 50.0, rule, 0.0, "inf", 1024, aspect=aspect)
    assert sq["closed_form"] and not d["closed_form"] and d["aspect"] == aspect
    assert d["n_prime"] == sq["n_prime"]
    np.testing.assert_allclose(d["m_x"], aspect * sq["m_x"], rtol=1e-12)
    np.testing.assert_allclose(d["m_z"], sq["m_z"], rtol=1e-12)
    np.testing.assert_allclose(d["M_x_eta"], aspect * sq["M_x_eta"], rtol=1e-12)
    np.testing.assert_allclose(d["M_z_eta"], sq["M_z_eta"], rtol=1e-12)
    np.testing.assert_allclose(d["S_eta"], aspect * sq["S_eta"], rtol=1e-12)
    r = schemes.evaluate(rule, View(1.0, 300.0, 50.0, aspect), "overhead")
    assert d["n_prime"] == float(r.n_prime[0, 0])
    assert d["M_x"] == pytest.approx(float(r.M_x[0, 0]), rel=1e-13) and d["M_z"] == pytest.approx(float(r.M_z[0, 0]), rel=1e-13)
    assert d["S"] == pytest.approx(float(r.S[0]), rel=1e-13)
    assert (d["res_s"], d["res_t"]) == (d["M_x"] * 1024, d["M_z"] * 1024)  # the image's 1024 rows, square pixels


def test_overhead_general_path_at_aspect_one_is_the_closed_forms():
    """The general evaluation used at aspect ≠ 1 reduces to Lloyd 2006 eqs. 7–10 for a square view."""
    z = np.geomspace(1.0, 1000.0, 50)
    etas = np.linspace(-1.0, 1.0, 21)
    nps = warping.n_prime_from_eta(etas, 1.0, 1000.0)
    for npr in (np.inf, 1.0, 7.0, float(warping.n_prime_lispsm(1.0, 1000.0)), 1e4):
        g = _overhead.general_errors(View(1.0, 1000.0, 70.0), z, npr, nps)
        np.testing.assert_allclose(g["m_x"], error.m_x(z, 1.0, 1000.0, npr), rtol=1e-12)
        np.testing.assert_allclose(g["m_z"], error.m_z(z, 1.0, 1000.0, 70.0, npr), rtol=1e-12)
    np.testing.assert_allclose(g["M_x"], error.max_error_x(1.0, 1000.0, nps), rtol=1e-12)
    np.testing.assert_allclose(g["M_z"], error.max_error_z(1.0, 1000.0, 70.0, nps), rtol=1e-12)


def test_overhead_picture_says_when_the_closed_forms_do_not_apply():
    e = explore.overhead(aspect=2.0)
    assert e.error is None and not e.data["closed_form"]
    title = e.figure._suptitle.get_text()
    assert "aspect = 2" in title and "closed forms are square" in title and "general evaluation" in e.figure.axes[0].get_title()
    np.testing.assert_array_equal(e.figure.axes[0].lines[0].get_ydata(), e.data["m_x"])
    assert e.set_state({"aspect": 1.0}) and e.data["closed_form"]
    assert "aspect" not in e.figure._suptitle.get_text() and e.figure.axes[0].get_title().startswith("Lloyd 2006 Fig. 5")


# ------------------------------------------------------------------------------------------- cascades


def test_cascades_wide_view_equals_splits_report():
    aspect = 16 / 9
    sq = _cascades.compute("practical", 3, 0.5, 1.0, 300.0, 60.0, "P", 2048**2, "error", 1024)
    d = _cascades.compute("practical", 3, 0.5, 1.0, 300.0, 60.0, "P", 2048**2, "error", 1024, aspect=aspect)
    rows = budgets.splits_report("practical", 1.0, 300.0, 3, fov=60.0, aspect=aspect, light=_cascades.LIGHTS, warp="P",
                                 budget=2048.0**2, res_image=1024.0, allocations=("error",), lam=0.5)
    np.testing.assert_array_equal(d["S_max"], [r["S_max"] for r in rows[:-1]])
    np.testing.assert_array_equal(d["error"], [r["max_error[error]"] for r in rows[:-1]])
    assert d["worst"] == rows[-1]["max_error[error]"]
    np.testing.assert_array_equal(d["far_i"], sq["far_i"])  # the splits do not depend on the aspect
    assert (d["S_max"] > sq["S_max"]).all() and d["worst"] > sq["worst"]  # wider slices: larger maps for the same pixels
    e = explore.cascades(method="practical", k=3, far=300.0, warp="P", aspect=2.0)
    assert e.error is None and "aspect 2" in e.figure._suptitle.get_text()


# ------------------------------------------------------------------------------------------- raster


def test_raster_wide_view_equals_pictures_and_validate():
    d = _raster.compute("ZP2+P", "gamma:60@azimuth:30", 50.0, 60.0, 32, 64 * 64, 8, aspect=2.0)
    v = pictures.view(View(1.0, 50.0, 60.0, 2.0), "gamma:60@azimuth:30", "ZP2+P", image_res=32, budget=64 * 64)
    np.testing.assert_array_equal(d["shaded"], pictures.shade(v))
    np.testing.assert_array_equal(d["error"], pictures.error_field(v), strict=False)
    sq = _raster.compute("ZP2+P", "gamma:60@azimuth:30", 50.0, 60.0, 32, 64 * 64, 8)
    assert not np.array_equal(d["shaded"], sq["shaded"])  # a wider view of the same scene
    val = validate("ZP2+P", 50.0, 60.0, "gamma:60@azimuth:30", res=128, probes=8, aspect=2.0)  # 64 · max(aspect, 1/aspect) pixels
    np.testing.assert_array_equal(d["ratio_M_x"], val["ratio_M_x"])
    np.testing.assert_array_equal(d["ratio_M_z"], val["ratio_M_z"])
    ratios = np.concatenate([d["ratio_M_x"], d["ratio_M_z"]])
    assert np.all(ratios <= 1.0) and np.all(ratios >= 0.9), ratios  # measured within the general evaluation's bound, reaching it


@pytest.mark.parametrize("aspect", [0.25, 4.0])
def test_raster_extreme_aspects_measure_near_the_bound(aspect):
    """At 64 pixels a stretched view's probes measure nothing or too little; the explorer measures at 64·max(aspect, 1/aspect)."""
    d = _raster.compute("LogP", "gamma:60@azimuth:30", 100.0, 60.0, 32, 64 * 64, 8, aspect=aspect)
    assert 0.9 <= float(d["ratio_M_x"][0]) <= 1.0 and 0.9 <= float(d["ratio_M_z"][0]) <= 1.0


def test_raster_face_partitions_refuse_a_wide_view_in_one_line():
    e = explore.raster(scheme="FPc+LogP", image_res=32, budget=64 * 64)
    good = e.data
    assert not e.set_state({"aspect": 2.0})
    assert e.error.startswith("aspect must be 1") and e.data is good


def test_raster_picture_keeps_the_view_shape():
    e = explore.raster(scheme="P", image_res=32, budget=64 * 64, aspect=2.0)
    assert e.error is None
    a, b = e.figure.axes[:2]
    e.figure.canvas.draw()
    for ax in (a, b):
        box = ax.get_window_extent()
        assert box.width / box.height == pytest.approx(2.0, rel=0.02)
    assert "aspect = 2" in e.figure._suptitle.get_text()


# ------------------------------------------------------------------------------------------- bias


def test_bias_wide_view_equals_cascade_bias():
    d = _bias.compute("bevy", 30.0, 3, 0.5, 100.0, 1024, 1080, aspect=2.0)
    rows = cascade_bias(0.1, 100.0, 60.0, "gamma:30.0", "bevy", k=3, resolution=1024, image=1080, lam=0.5, aspect=2.0)
    np.testing.assert_equal(d["rows"], rows)
    sq = _bias.compute("bevy", 30.0, 3, 0.5, 100.0, 1024, 1080)
    for w, r in zip(d["rows"], sq["rows"]):  # a light ahead: the map's s axis is the view's width
        assert w["texel_s"] == pytest.approx(2.0 * r["texel_s"], rel=1e-12) and w["texel_t"] == pytest.approx(r["texel_t"], rel=1e-12)
    e = explore.bias(aspect=2.0, k=3)
    assert e.error is None and "aspect = 2" in e.figure._suptitle.get_text()


# ------------------------------------------------------------------------------------------- shimmer


def test_shimmer_wide_view_equals_the_temporal_measure():
    d = _shimmer.compute("boxes", "csm:log:k=3", "translate:0.05,0,0", 4, 2, 32, 64, aspect=2.0)
    w = points.world("boxes", aspect=2.0)
    r = measure.shimmer(w, points.sample(w, 32), "csm:log:k=3", "translate:0.05,0,0", 4, res=64)
    row, want = dict(d["row"]), r.row()
    row.pop("seconds"), want.pop("seconds")
    assert row == want and row["aspect"] == 2.0
    np.testing.assert_array_equal(d["flip_fraction"], r.flip_fraction)
    uv = d["uv"][np.isfinite(d["uv"][:, 0])]
    assert np.abs(uv[:, 0]).max() > 1.5 and np.abs(uv[:, 0]).max() <= 2.0 + 1e-9 and np.abs(uv[:, 1]).max() <= 1.0 + 1e-9  # the wide image


def test_shimmer_picture_keeps_the_view_shape_and_names_the_aspect():
    e = explore.shimmer(scheme="csm:log:k=3", frames=4, frame=2, image_res=48, shadow_res=128, aspect=2.0)
    assert e.error is None
    e.figure.canvas.draw()
    box = e.figure.axes[0].get_window_extent()
    assert box.width / box.height == pytest.approx(2.0, rel=0.02)
    assert "aspect = 2" in e.figure._suptitle.get_text()
    assert e.set_state({"aspect": 1.0}) and "aspect" not in e.figure._suptitle.get_text()


def test_shimmer_vsm_takes_a_wide_view():
    e = explore.shimmer(scheme="vsm:bias=0", frames=3, image_res=48, shadow_res=128)
    square = e.data
    assert e.set_state({"aspect": 2.0})
    assert e.error is None and e.data is not square
