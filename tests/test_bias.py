"""Depth bias: the derivation (sympy) against the numeric code, and both against the rasterizer.

* ``plane_bias``, ``slope_factor`` and ``lit_gap`` equal the registered derivations of
  :mod:`aliasing.symbolic.bias` on grids (the corner maximum and the brute-force PCF maximum
  evaluated for every azimuth, not only the closed form's quadrant);
* in the rasterizer (``depth_test``: a plain depth compare as engines do it), on planes of
  several orientations and in each parameterization (uniform, perspective-warped,
  logarithmic), the derived minimum is the threshold: acne at 0.9× the minimum, none at 1.1×,
  for a constant depth bias and for a normal offset, with nearest lookup, 3×3 PCF and
  receiver-plane depth bias;
* the lit gap measured at the foot of a wall and of a box on the ground matches ``lit_gap``
  within the texel's sampling;
* bad input: a ValueError naming the parameter (Hypothesis).
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from aliasing import symbolic
from aliasing.figures.bias_threshold import tilted_plane  # the plane the figure draws, too
from aliasing.bias import kernel, lit_gap, map_bias, plane_bias, slope_factor
from aliasing.raster.draw import depth_test, light_map, shadow_map, texel_edges
from aliasing.symbolic import bias as sb

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

THETA = np.linspace(0.0, 89.0, 12)
PHI = np.linspace(-180.0, 360.0, 37)


def _grid():
    th, ph = np.meshgrid(THETA, PHI, indexing="ij")
    return th, ph


# --------------------------------------------------------------------------- derivation = numeric code


def test_derivations_are_registered():
    for name in ("bias.corners", "bias.depth", "bias.pcf", "bias.receiver_plane", "bias.offset_height", "bias.normal_offset", "bias.slope", "bias.lit_gap", "bias.projection_ground"):
        assert symbolic.get(name).name == name


def test_closed_form_is_the_corner_maximum_for_every_azimuth():
    th, ph = _grid()
    corners = sp.lambdify((sb.w, sb.theta, sb.phi), sb.corners(), "numpy")
    closed = sp.lambdify((sb.w, sb.theta, sb.phi), sb.depth(), "numpy")
    want = corners(0.3, np.radians(th), np.radians(ph))
    np.testing.assert_allclose(closed(0.3, np.radians(th), np.radians(ph)), want, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(plane_bias(0.3, th, ph).depth, want, rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize("k", [1, 2, 3, 4, 5])
def test_pcf_is_the_brute_force_tap_maximum(k):
    th, ph = _grid()
    brute = sp.lambdify((sb.w, sb.theta, sb.phi), sb.pcf_taps(k), "numpy")
    closed = sp.lambdify((sb.w, sb.theta, sb.phi), sb.pcf().subs(sb.k, k), "numpy")
    want = brute(0.2, np.radians(th), np.radians(ph))
    np.testing.assert_allclose(closed(0.2, np.radians(th), np.radians(ph)), want, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(plane_bias(0.2, th, ph, f"pcf{k}").depth, want, rtol=1e-12, atol=1e-15)


def test_receiver_plane_and_normal_offset_match_the_derivation():
    th, ph = _grid()
    args = (0.25, np.radians(th), np.radians(ph))
    rp = sp.lambdify((sb.w, sb.theta, sb.phi), sb.receiver_plane(), "numpy")(*args)
    np.testing.assert_allclose(plane_bias(0.25, th, ph, "receiver-plane").depth, rp, rtol=1e-12, atol=1e-15)
    no = sp.lambdify((sb.w, sb.theta, sb.phi), sb.normal_offset(), "numpy")(*args)
    np.testing.assert_allclose(plane_bias(0.25, th, ph).normal, no, rtol=1e-12, atol=1e-15)
    assert sp.simplify(sb.offset_height() - sb.o / sp.cos(sb.theta)) == 0


def test_slope_factor_matches_the_derivation_in_the_first_octant():
    ph = np.linspace(0.0, 45.0, 10)
    for k in (1, 3):
        want = sp.lambdify((sb.phi,), sb.slope().subs(sb.k, k), "numpy")(np.radians(ph))
        np.testing.assert_allclose(slope_factor(ph, f"pcf{k}"), want, rtol=1e-12)
    # the symmetry the numeric code uses for the other octants
    np.testing.assert_allclose(slope_factor(90.0 - ph), slope_factor(ph), rtol=1e-12)
    np.testing.assert_allclose(slope_factor(-ph + 180.0), slope_factor(ph), rtol=1e-12)


def test_lit_gap_matches_the_derivation():
    b, el, d = np.meshgrid([0.0, 0.1, 2.0], np.linspace(1.0, 89.0, 9), [0.0, 0.05], indexing="ij")
    f = sp.lambdify((sb.b, sb.alpha, sb.D), sb.lit_gap(), "numpy")
    np.testing.assert_allclose(lit_gap(b, el, d), np.maximum(f(b, np.radians(el), d), 0.0), rtol=1e-12, atol=1e-15)
    assert lit_gap(1.0, 90.0) == 0.0


# --------------------------------------------------------------------------- rasterizer thresholds


CASES = [(scheme, theta, phi) for scheme in ("Standard", "P", "LogP") for theta, phi in ((30.0, 0.0), (60.0, 30.0), (75.0, 100.0), (45.0, 225.0))]


@pytest.mark.parametrize("scheme,theta,phi", CASES)
@pytest.mark.parametrize("lookup,pcf", [("nearest", 1), ("pcf3", 3), ("receiver-plane", 3)])
def test_derived_minimum_is_the_acne_threshold(scheme, theta, phi, lookup, pcf):
    res = 128
    lm, sm, p, n = tilted_plane(scheme, theta, phi, res)
    mb = map_bias(lm, res, p, n, lookup)
    _, rp = kernel(lookup)
    acne = {}
    for f in (0.9, 1.1):
        acne["depth", f] = (depth_test(lm, sm, p, n, bias=f * mb.depth, pcf=pcf, receiver_plane=rp) < 1).mean()
        acne["normal", f] = (depth_test(lm, sm, p, n, normal_offset=f * mb.normal, pcf=pcf, receiver_plane=rp) < 1).mean()
    for kind in ("depth", "normal"):
        assert acne[kind, 0.9] > 1e-3, (kind, acne)  # some lit samples shadow themselves just below the minimum
        assert acne[kind, 1.1] == 0.0, (kind, acne)  # none just above it


def test_square_texel_map_bias_is_plane_bias():
    # a uniform map's texel at a point, the plane's angle and azimuth in light space: plane_bias
    lm, _, p, n = tilted_plane("Standard", 50.0, 0.0, 64, n=5)
    e_s, e_t = texel_edges(lm, 64, p)
    assert np.allclose(e_s[:, 1], 0) and np.allclose(e_t[:, 0], 0)
    np.testing.assert_allclose(map_bias(lm, 64, p, n).depth, plane_bias(e_s[:, 0], 50.0, 0.0).depth, rtol=1e-6)


def test_slope_scaled_bias_threshold():
    # a slope-scaled bias with the derived factor (and nothing else) clears acne at 1.1x, not at 0.9x
    res = 128
    for theta, phi in ((40.0, 0.0), (65.0, 90.0)):
        lm, sm, p, n = tilted_plane("Standard", theta, phi, res)
        f = slope_factor(phi)
        assert (depth_test(lm, sm, p, n, slope=0.9 * f) < 1).mean() > 1e-3
        assert (depth_test(lm, sm, p, n, slope=1.1 * f) < 1).mean() == 0.0


# --------------------------------------------------------------------------- peter-panning


def _quad(a, b, c, d):
    return [[a, b, c], [a, c, d]]


def _caster(thickness: float, height: float = 3.0):
    x0, x1, y0, y1, z0, z1 = -2.0, 2.0, -1.0, -1.0 + height, 10.0, 10.0 + thickness
    back = _quad([x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0])
    if thickness == 0:
        return back
    front = _quad([x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1])
    top = _quad([x0, y1, z0], [x1, y1, z0], [x1, y1, z1], [x0, y1, z1])
    sides = _quad([x0, y0, z0], [x0, y1, z0], [x0, y1, z1], [x0, y0, z1]) + _quad([x1, y0, z0], [x1, y1, z0], [x1, y1, z1], [x1, y0, z1])
    return back + front + top + sides


@pytest.mark.parametrize("elevation", [20.0, 45.0, 70.0])
@pytest.mark.parametrize("thickness", [0.0, 0.1])
def test_lit_gap_at_a_caster_foot(elevation, thickness):
    a = np.radians(elevation)
    lm = light_map(1.0, 20.0, 60.0, [0.0, np.sin(a), np.cos(a)], "Standard")  # shadows fall towards the eye (−z)
    ground = [[[-60.0, -1.0, 0.5], [60.0, -1.0, 0.5], [0.0, -1.0, 80.0]]]
    res = 512
    sm = shadow_map(np.array(ground + _caster(thickness), float), lm, res)
    gs = np.linspace(0.0, 1.0, 1001)
    X, G = np.meshgrid(np.linspace(-1.5, 1.5, 31), gs, indexing="ij")
    p = np.stack([X, np.full_like(X, -1.0), 10.0 - G], -1)  # the ground behind the caster's shadow-side face
    n = np.broadcast_to([0.0, 1.0, 0.0], p.shape)
    _, e_t = texel_edges(lm, res, [[0.0, -1.0, 10.0]])
    tol = 0.5 * np.hypot(*e_t[0]) * np.sin(a) + (gs[1] - gs[0])  # the stored texel is up to half a texel off the point
    for bias in (0.3, 0.6):
        assert bias > map_bias(lm, res, p, n).depth.max()  # the ground itself is free of acne
        shadowed = depth_test(lm, sm, p, n, bias=bias) < 1
        assert shadowed.any(1).all()
        measured = gs[np.argmax(shadowed, 1)]
        want = lit_gap(bias, elevation, thickness)
        assert np.abs(measured - want).max() <= tol, (measured.min(), measured.max(), want, tol)


# --------------------------------------------------------------------------- bad input

BAD_ANGLES = st.one_of(st.floats(max_value=-1e-9), st.floats(min_value=90.0), st.just(float("nan")), st.just(float("inf")))


@settings(max_examples=60, deadline=None)
@given(angle=BAD_ANGLES)
def test_bad_angle_names_angle(angle):
    with pytest.raises(ValueError, match="angle"):
        plane_bias(0.1, angle)


@settings(max_examples=60, deadline=None)
@given(texel=st.one_of(st.floats(max_value=0.0), st.just(float("nan")), st.just(float("inf"))))
def test_bad_texel_names_texel(texel):
    with pytest.raises(ValueError, match="texel"):
        plane_bias(texel, 30.0)


@settings(max_examples=60, deadline=None)
@given(lookup=st.text(max_size=10).filter(lambda s: s.strip().lower() not in ("nearest", "receiver-plane", "receiver_plane", "rpdb")
                                          and not (s.strip().lower().startswith("pcf") and s.strip()[3:].isdigit() and s.strip()[3:].isascii() and 1 <= int(s.strip()[3:]) <= 15 and len(s.strip()) <= 5)))
def test_bad_lookup_names_lookup(lookup):
    with pytest.raises(ValueError, match="lookup"):
        plane_bias(0.1, 30.0, lookup=lookup)


@settings(max_examples=60, deadline=None)
@given(elevation=st.one_of(st.floats(max_value=0.0), st.floats(min_value=90.0, exclude_min=True), st.just(float("nan"))),
       bias=st.floats(0.0, 10.0))
def test_bad_elevation_names_elevation(elevation, bias):
    with pytest.raises(ValueError, match="elevation"):
        lit_gap(bias, elevation)


@settings(max_examples=60, deadline=None)
@given(texel=st.floats(1e-6, 1e3), angle=st.floats(0.0, 89.9), azimuth=st.floats(-720.0, 720.0), k=st.integers(1, 15))
def test_plane_bias_properties(texel, angle, azimuth, k):
    nearest = plane_bias(texel, angle, azimuth)
    pcf = plane_bias(texel, angle, azimuth, f"pcf{k}")
    assert nearest.depth >= 0 and nearest.normal >= 0 and nearest.normal <= nearest.depth + 1e-300
    assert np.isclose(pcf.depth, k * nearest.depth, rtol=1e-12, atol=1e-300)
    assert np.isclose(plane_bias(texel, angle, azimuth, "receiver-plane").depth, nearest.depth, rtol=1e-12, atol=1e-300)
    assert nearest.depth <= texel * np.sqrt(2) / 2 * np.tan(np.radians(angle)) * (1 + 1e-12)


def test_bad_input_messages():
    with pytest.raises(ValueError, match="depth_bias"):
        lit_gap(-1.0, 30.0)
    with pytest.raises(ValueError, match="thickness"):
        lit_gap(1.0, 30.0, -0.1)
    with pytest.raises(ValueError, match="azimuth"):
        plane_bias(0.1, 30.0, float("nan"))
    lm = light_map(1.0, 20.0, 60.0, "overhead")
    sm = shadow_map(np.array([[[-40, -1, 0.5], [40, -1, 0.5], [0, -1, 60]]], float), lm, 8)
    for kwargs, name in (({"pcf": 0}, "pcf"), ({"pcf": 16}, "pcf"), ({"bias": -1.0}, "bias"), ({"slope": np.nan}, "slope"), ({"normal_offset": -0.1}, "normal_offset")):
        with pytest.raises(ValueError, match=name):
            depth_test(lm, sm, [[0, 0, 5.0]], [[0, 1, 0.0]], **kwargs)
    with pytest.raises(ValueError, match="normals"):
        depth_test(lm, sm, [[0, 0, 5.0]], [[0, 0, 0.0]])


def test_quantized_depth_adds_its_rounding_to_the_threshold():
    import dataclasses

    from aliasing.bias import quantization_bias

    res = 128
    lm, sm, p, n = tilted_plane("Standard", 30.0, 0.0, res, n=60000)
    d = sm.depth[np.isfinite(sm.depth)]
    lo, span = float(d.min()) - 1.0, 10000.0  # a light depth range of 10 000 world units around the plane
    q = quantization_bias(span, 16)
    step = span / (2**16 - 1)
    smq = dataclasses.replace(sm, depth=lo + np.round((sm.depth - lo) / step) * step)
    need = map_bias(lm, res, p, n).depth
    assert q > 0.2 * need.max()  # the rounding matters at this range
    assert (depth_test(lm, smq, p, n, bias=need + 1.1 * q) < 1).mean() == 0.0
    assert (depth_test(lm, smq, p, n, bias=need * 1.0001 + 0.9 * q) < 1).mean() > 0.0
    assert (depth_test(lm, smq, p, n, bias=1.1 * need) < 1).mean() > 0.0  # the geometric minimum alone no longer suffices


def test_projection_factor_matches_the_ground_closed_form_and_grazes_to_inf():
    from aliasing.bias.projection import ground_factor, projection_factor

    f = sp.lambdify((sp.Symbol("h", positive=True), sp.Symbol("d", positive=True), sb.alpha), sb.projection_ground(), "numpy")
    h, d, el = np.meshgrid([0.5, 2.0], [0.0, 3.0, 50.0], [5.0, 45.0, 90.0], indexing="ij")
    np.testing.assert_allclose(ground_factor(h, d, el), f(h, d, np.radians(el)), rtol=1e-12)
    # the general form on ground points ahead of an eye h above the ground, light ahead at elevation α
    for hh, dd, a in ((1.0, 10.0, 30.0), (2.0, 0.5, 70.0)):
        light = [0.0, np.sin(np.radians(a)), np.cos(np.radians(a))]
        got = projection_factor([[0.0, -hh, dd]], [[0.0, 1.0, 0.0]], light)[0]
        assert got == pytest.approx(ground_factor(hh, dd, a), rel=1e-12)
    # a wall along the light: no maximum (inf); a wall facing away from the light: NaN (self-shadowed)
    assert projection_factor([[1.0, 0.0, 5.0]], [[-1.0, 0.0, 0.0]], [0.0, 1.0, 1.0])[0] == np.inf
    assert np.isnan(projection_factor([[0.0, 0.0, 5.0]], [[0.0, 0.0, -1.0]], [0.0, 0.0, 1.0])[0])
    with pytest.raises(ValueError, match="elevation"):
        ground_factor(1.0, 1.0, 0.0)
