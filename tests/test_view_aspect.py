"""Non-square views: View(near, far, fov, aspect), fov vertical, aspect = width/height."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import minimize_scalar

from aliasing import View, error, geometry, schemes
from aliasing.engines import stable
from aliasing import raster
from aliasing.raster.draw.eye import eye_pass

BAD_ASPECTS = st.one_of(st.floats(max_value=0.0, allow_nan=False), st.sampled_from([math.nan, math.inf, -math.inf]))


@settings(max_examples=60, deadline=None)
@given(BAD_ASPECTS)
def test_bad_aspect_is_refused_naming_it(aspect):
    with pytest.raises(ValueError, match="^aspect") as info:
        View(1.0, 10.0, 60.0, aspect)
    assert "\n" not in str(info.value)
    with pytest.raises(ValueError, match="^aspect"):
        stable.sphere_radius(1.0, 2.0, 60.0, aspect)


@settings(max_examples=40, deadline=None)
@given(st.floats(min_value=1e-3, max_value=1e3))
def test_good_aspect_widens_x_only(aspect):
    v, sq = View(1.0, 10.0, 60.0, aspect), View(1.0, 10.0, 60.0)
    got, ref = v.slice_vertices(), sq.slice_vertices()
    assert np.array_equal(got[:, 1:], ref[:, 1:])
    assert np.allclose(got[:, 0], aspect * ref[:, 0], rtol=1e-15, atol=0)


def _hand_vertices(n, f, fov, aspect):
    """The 8 corners written out from the definition (not through View)."""
    ty = math.tan(math.radians(fov) / 2)
    tx = aspect * ty
    return np.array([[sx * tx * d, sy * ty * d, d] for d in (n, f) for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))]), ty


def test_aspect_one_is_bit_for_bit():
    lights = geometry.lights("sphere:300")
    for n, f, fov in [(1.0, 1000.0, 60.0), (0.1, 50.0, 90.0), (2.0, 3.0, 20.0), (1.0, 1e5, 120.0)]:
        one, loose = View(n, f, fov, 1.0), View(n, f, fov)
        assert one == loose and repr(one) == repr(loose)
        assert np.array_equal(one.slice_vertices(), loose.slice_vertices())
        for name in ("Standard", "ZP4+LogP", "lispsm", "FPc+P"):
            a, b = schemes.evaluate(name, one, lights), schemes.evaluate(name, n, f, fov, lights)
            assert np.array_equal(a.M_x, b.M_x) and np.array_equal(a.M_z, b.M_z) and np.array_equal(a.S, b.S)
        for fn in (stable.sphere_radius, stable.centroid_radius, stable.diagonal, stable.body_diagonal):
            assert np.array_equal(fn(n, f, fov, 1.0), fn(n, f, fov))


@pytest.mark.parametrize("aspect", [0.5, 16 / 9, 2.0, 3.7])
def test_uniform_map_against_an_independent_fit(aspect):
    """Standard (uniform) maps at aspect ≠ 1: M = extent along the light axis / (2 n tan θ_y),
    the extents taken from hand-written corners; general evaluation over many directions."""
    n, f, fov = 1.0, 100.0, 60.0
    lights = geometry.lights("sphere:400")
    verts, ty = _hand_vertices(n, f, fov, aspect)
    basis = geometry.light_space(lights)
    wx = np.ptp(verts @ basis[:, 0].T, axis=0)
    wz = np.ptp(verts @ basis[:, 2].T, axis=0)
    r = schemes.evaluate("Standard", View(n, f, fov, aspect), lights)
    assert np.allclose(r.M_x[:, 0], wx / (2 * n * ty), rtol=1e-11, atol=0)
    assert np.allclose(r.M_z[:, 0], wz / (2 * n * ty), rtol=1e-11, atol=0)


@pytest.mark.parametrize("aspect", [0.5, 16 / 9, 2.0])
@pytest.mark.parametrize("name", ["Standard", "lispsm", "ZP3+lispsm", "LogP"])
def test_overhead_scales_m_x_by_aspect(name, aspect):
    """Overhead light: the map's x-extent is ∝ tan θ_x at every depth and the eye beam is 2 d tan θ_y,
    so M_x(aspect) = aspect·M_x(1) and M_z is unchanged (n′ = n + √(fn) does not depend on θ)."""
    sq = schemes.evaluate(name, View(1.0, 300.0, 60.0), "overhead")
    wide = schemes.evaluate(name, View(1.0, 300.0, 60.0, aspect), "overhead")
    assert np.allclose(wide.M_x, aspect * sq.M_x, rtol=1e-12, atol=0)
    assert np.allclose(wide.M_z, sq.M_z, rtol=1e-12, atol=0)


@pytest.mark.parametrize("aspect", [0.6, 16 / 9, 2.5])
@pytest.mark.parametrize("a, b", [(1.0, 3.0), (1.0, 1.2), (10.0, 100.0), (0.1, 1000.0)])
def test_stable_radii_against_numeric_corners(a, b, aspect):
    fov = 60.0
    verts, _ = _hand_vertices(a, b, fov, aspect)
    worst = lambda zc: np.max(np.linalg.norm(verts - [0.0, 0.0, zc], axis=1))  # noqa: E731
    best = minimize_scalar(worst, bounds=(0.0, 2 * b * (1 + aspect**2)), method="bounded", options={"xatol": 1e-12 * b})
    assert float(stable.sphere_radius(a, b, fov, aspect)) == pytest.approx(best.fun, rel=1e-7)
    centre = verts.mean(axis=0)
    assert float(stable.centroid_radius(a, b, fov, aspect)) == pytest.approx(np.max(np.linalg.norm(verts - centre, axis=1)), rel=1e-12)
    body = np.linalg.norm(verts[0] - verts[6])
    face = np.linalg.norm(verts[4] - verts[6])
    assert float(stable.body_diagonal(a, b, fov, aspect)) == pytest.approx(body, rel=1e-12)
    assert float(stable.diagonal(a, b, fov, aspect)) == pytest.approx(max(body, face), rel=1e-12)


def test_square_only_parts_refuse_a_wide_view():
    wide = View(1.0, 100.0, 60.0, 2.0)
    with pytest.raises(ValueError, match="^aspect must be 1 for face partitions"):
        schemes.evaluate("FPc+P", wide, "overhead")
    with pytest.raises(ValueError, match="^aspect must be 1 for the closed forms"):
        error.max_error_z(wide, 5.0)
    with pytest.raises(ValueError, match="^aspect must be 1"):
        schemes.evaluate("pyramid", wide, "gamma:40")


def test_symbolic_ratios_and_the_general_evaluation():
    """aspect.ratios is (A, 1); aspect.m_x, aspect.m_z at the frustum's ends equal the general
    evaluation's M_x, M_z of a wide view (overhead, LiSPSM's n′ read from the evaluation)."""
    import sympy as sp

    from aliasing.symbolic import aspect as sym
    from aliasing.symbolic import get
    from aliasing.symbolic import lloyd2006 as base

    assert list(get("aspect.ratios").func()) == [sym.A, 1]
    n, f, fov, a = 1.0, 300.0, 60.0, 16 / 9
    r = schemes.evaluate("lispsm", View(n, f, fov, a), "overhead")
    npr = float(r.n_prime[0, 0])
    ty = math.tan(math.radians(fov) / 2)
    values = {base.n: n, base.f: f, base.n_p: npr, base.res_i: 1, base.res_s: 1, base.res_t: 1, sym.theta_x: math.atan(a * ty), base.theta: math.atan(ty)}
    mx = sp.lambdify(base.z, get("aspect.m_x").func().subs(values))
    mz = sp.lambdify(base.z, get("aspect.m_z").func().subs(values))
    assert float(r.M_x[0, 0]) == pytest.approx(max(mx(n), mx(f)), rel=1e-9)
    assert float(r.M_z[0, 0]) == pytest.approx(max(mz(n), mz(f)), rel=1e-9)


@pytest.mark.parametrize("aspect", [0.5, 2.0])
@pytest.mark.parametrize("scheme, light", [("ZP2+P", "gamma:50@azimuth:30"), ("LogP", "gamma:120"), ("Standard", "overhead")])
def test_rasterizer_measures_the_wide_view_bound(scheme, light, aspect):
    """The eye pass over a non-square frustum (R × R pixels, aspect : 1 wide) and probes across
    its width: the measured perspective error stays within the general evaluation's M_x, M_z
    and reaches them (an independent check of the non-square analysis)."""
    r = raster.measure(View(1.0, 100.0, 60.0, aspect), light, scheme, resolution=192, cells=10)
    ratios = np.concatenate([r.ratio_x, r.ratio_z])
    assert np.all(ratios <= 1 + r.tolerance) and np.all(ratios >= 0.9), ratios


def test_eye_pass_spans_the_wide_frustum():
    wall = np.array([[[-1e3, -1e3, 10.0], [1e3, -1e3, 10.0], [0.0, 1e3, 10.0]]])
    res = 8
    eb = eye_pass(wall, View(1.0, 100.0, 60.0, 2.0), res)
    t = math.tan(math.radians(30.0))
    c = (np.arange(res) + 0.5) / res
    assert np.allclose(eb.position[0, :, 0], (2 * c - 1) * 2 * t * 10.0, rtol=1e-12)  # columns over 2 tan θ_y
    assert np.allclose(eb.position[:, -1, 1], (2 * c - 1) * t * 10.0, rtol=1e-12)
    assert eb.aspect == 2.0
