"""The filter's reach and the cascade seams (aliasing.bias.filtering) and ``aliasing bias --filter``.

* closed forms against the sympy derivations (``bias.pcf_footprint``, ``bias.blend_band``) and
  against a numeric evaluation (the mixture of two kernels ramped over N pixels, its per-pixel change);
* the seam step measured on the texel grid: texel-index crossings of the two cascades' maps
  counted along the light plane's axes at their boundary, against ``step``;
* filter biases: plain PCF k times receiver-plane, which equals nearest, at every angle;
* the command: the default table unchanged by the new option, the filter table's columns,
  and generated bad input ending in exit 2 with one line naming the parameter.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from aliasing.bias import filtering, plane_bias
from aliasing.bias.cascades import cascade_bias
from aliasing.cli import main
from aliasing.raster.draw import cascade_set
from aliasing.symbolic import bias as sym

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402


def test_closed_forms_match_the_derivations():
    band = sp.lambdify((sym.s_step, sym.f_rate), sym.blend_band())
    foot = sp.lambdify((sym.k, sym.w, sym.p_px), sym.pcf_footprint())
    for s in (1.0, 1.3, 2.0, 4.5):
        for f in (0.05, 0.1, 0.5, 1.0):
            assert filtering.blend_band(s, f) == pytest.approx(band(s, f), rel=1e-12)
    for k in (1, 2, 5):
        assert filtering.pcf_footprint(k, 0.02, 0.003) == pytest.approx(foot(k, 0.02, 0.003), rel=1e-12)


@pytest.mark.parametrize("s", [0.4, 0.8, 1.0, 1.7, 3.0])
@pytest.mark.parametrize("f", [0.05, 0.2])
def test_blend_band_keeps_the_blur_change_per_pixel_within_the_fraction(s, f):
    """Numeric: ramp the mixture (1 − t)K_i + t K_{i+1} of two box kernels over N pixels; measure the
    mean radius pixel by pixel; its largest change per pixel is f of the narrower width at N, more below."""
    k, w = 3, 1.0
    n = filtering.blend_band(s, f)
    if s == 1.0:
        assert n == 0.0
        return
    x = np.linspace(-1.0, 1.0, 20001)  # a box kernel of unit half-width: mean |x| = 1/2 of its half-width
    def mean_radius(t: float) -> float:
        a, b = 0.5 * k * w, 0.5 * k * w * s  # half-widths of the two kernels
        dens = (1 - t) * (np.abs(x * max(a, b)) <= a) / (2 * a) + t * (np.abs(x * max(a, b)) <= b) / (2 * b)
        xs = x * max(a, b)
        return float(np.trapezoid(np.abs(xs) * dens, xs) / np.trapezoid(dens, xs))
    for pixels, ok in ((n, True), (0.8 * n, False)):
        steps = int(np.ceil(pixels))
        r = np.array([mean_radius(min(1.0, i / pixels)) for i in range(steps + 1)])
        change = np.abs(np.diff(4 * r)).max()  # a box k·w wide has mean |x| = k·w/4: the blur width is 4 × the mean radius
        narrow = min(1.0, s) * k * w
        assert bool(change <= f * narrow * (1 + 1e-3)) is ok


def _grid_width(lm, point, axis: int, res: int) -> float:
    """Texel width along the light plane's s (0) or t (1) axis, counted on the texel grid."""
    d = lm.basis[0] if axis == 0 else lm.basis[2]
    length = 2.0
    x = np.linspace(-length / 2, length / 2, 400001)
    s, t, _, _ = lm.coordinates(point + x[:, None] * d)
    cross = x[1:][np.diff(np.floor((s if axis == 0 else t) * res)) != 0]  # where the texel index changes
    return (cross[-1] - cross[0]) / (len(cross) - 1)  # first to last crossing: exact to the 5 µm sampling


def test_seam_step_measured_on_the_texel_grid():
    res = 2048
    rows = cascade_bias(0.1, 100.0, 60.0, "gamma:45", "filament", k=4, resolution=res)
    cs = cascade_set(0.1, 100.0, 60.0, "gamma:45", "Standard", splits="practical", k=4, lam=0.5)
    for i in range(3):
        at = np.array([0.0, 0.0, float(cs.far_i[i])])
        here = max(_grid_width(cs.maps.maps[i], at, a, res) for a in (0, 1))
        there = max(_grid_width(cs.maps.maps[i + 1], at, a, res) for a in (0, 1))
        # 35-280 texels between the first and last crossing, each crossing located to 5e-6 world units
        assert filtering.seam_step(here, there) == pytest.approx(rows[i]["step"], rel=1e-4)
    assert np.isnan(rows[3]["step"])


def test_kernel_rules_and_pcf_footprint_per_cascade():
    rows = cascade_bias(0.1, 100.0, 60.0, "gamma:45", "bevy", k=4, resolution=2048)
    out = filtering.filter_rows(rows, 60.0, 1080, 0.1)
    w = np.array([max(r["texel_s"], r["texel_t"]) for r in rows])
    assert [r["k"] for r in out] == [5] * 4
    np.testing.assert_allclose([r["pcf_world"] for r in out], 5 * w, rtol=1e-12)
    np.testing.assert_allclose([r["world_texels"] for r in out], 5 * w[0] / w, rtol=1e-12)
    assert all(out[i]["world_texels"] > out[i + 1]["world_texels"] for i in range(3))  # fewer texels each cascade
    for r, o in zip(rows, out):
        pix = filtering.pixel_size(0.5 * (r["near"] + r["far"]), 60.0, 1080)
        assert o["pcf_px"] == pytest.approx(filtering.pcf_footprint(5, max(r["texel_s"], r["texel_t"]), pix), rel=1e-12)
    for o in out[:3]:
        assert o["band_px"] == pytest.approx((o["step"] - 1) / 0.1, rel=1e-12)
        assert o["band_world"] == pytest.approx(o["band_px"] * filtering.pixel_size(o["far"], 60.0, 1080), rel=1e-12)
        assert o["need_rp"] == pytest.approx(o["need_pcf"] / 5, rel=1e-12)


@given(st.floats(0.001, 1.0), st.floats(0.0, 89.0), st.floats(0.0, 360.0), st.integers(1, 15))
@settings(max_examples=60, deadline=None)
def test_filter_bias_is_k_times_receiver_plane(w, angle, azimuth, k):
    plain, rp = filtering.filter_bias(w, angle, azimuth, k)
    near = plane_bias(w, angle, azimuth)
    assert plain.depth == pytest.approx(k * rp.depth, rel=1e-12, abs=1e-300)
    assert rp.depth == near.depth and rp.normal == near.normal


BAD = st.sampled_from([0.0, -1.0, float("nan"), float("inf")])


@given(BAD)
@settings(max_examples=20, deadline=None)
def test_bad_input_names_the_parameter(bad):
    cases = [
        (lambda: filtering.pcf_footprint(3, bad, 0.01), "texel"),
        (lambda: filtering.pcf_footprint(3, 0.01, bad), "pixel"),
        (lambda: filtering.seam_step(bad, 0.01), "texel_here"),
        (lambda: filtering.seam_step(0.01, bad), "texel_there"),
        (lambda: filtering.blend_band(bad, 0.1), "step"),
        (lambda: filtering.blend_band(2.0, bad), "fraction"),
        (lambda: filtering.kernel_rules(0.01, 3, bad), "radius"),
        (lambda: filtering.pixel_size(bad, 60.0, 1080), "depth"),
    ]
    for call, name in cases:
        with pytest.raises(ValueError, match=name):
            call()


@given(st.one_of(st.floats(-5, 0.999), st.just(2.5), st.just(float("nan"))))
@settings(max_examples=20, deadline=None)
def test_bad_kernel_names_k(k):
    with pytest.raises(ValueError, match="k must"):
        filtering.kernel_rules(0.01, k, 0.1)
    with pytest.raises(ValueError, match="k"):
        filtering.filter_bias(0.01, 30.0, 0.0, k)


def test_command_filter_table(capsys):
    assert main(["bias", "--presets", "filament", "-k", "3", "--resolution", "1024", "--filter", "--format", "csv"]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert lines[0].split(",")[:6] == ["preset", "cascade", "near", "far", "k", "texel"]
    assert "band_px" in lines[0] and "need_rp" in lines[0] and len(lines) == 4


@pytest.mark.parametrize("argv, word", [
    (["--filter", "--fraction", "0"], "--fraction"),
    (["--filter", "--fraction", "1.5"], "--fraction"),
    (["--filter", "--radius", "-1"], "--radius"),
    (["--fraction", "0.2"], "--filter"),
    (["--plane", "--texel", "0.1", "--angle", "30", "--filter"], "--filter"),
])
def test_command_bad_filter_input(argv, word, capsys):
    assert main(["bias", "--presets", "filament", *argv]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and word in err[0]


@given(st.one_of(st.floats(-1.0, 0.0), st.floats(1.0001, 10.0)))
@settings(max_examples=20, deadline=None)
def test_filter_rows_validates_fraction_even_without_a_boundary(bad):
    rows = cascade_bias(1.0, 100.0, 60.0, "gamma:60", "filament", k=1, resolution=256)
    with pytest.raises(ValueError, match="fraction"):
        filtering.filter_rows(rows, 60.0, fraction=bad)
