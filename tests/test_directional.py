"""The vertex model of aliasing.directional for lights in any direction.

Checked against the overhead closed forms of aliasing.error, the light-behind/in-front
values of Lloyd et al. 2006, the light-plane depth of Lloyd et al. 2007 App. B (eq. 111
with corrected eqs. 116–119), a brute-force maximisation over the frustum's interior, and
Lloyd et al. 2007 Table 3.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from aliasing import directional as D
from aliasing import error
from aliasing import geometry as G
from aliasing import schemes, warping
from conftest import assert_close

RTOL = 1e-12
OVERHEAD = np.array([0.0, 1.0, 0.0])  # exactly perpendicular to the view direction
PARAMS = ("uniform", "perspective", "logperspective")


def approx(expected, **tolerance):
    """pytest.approx without its default absolute tolerance of 1e-12 (tiny values matter here)."""
    return pytest.approx(expected, **{"abs": 0.0, **tolerance})


def _tan(fov):
    return np.tan(np.radians(fov) / 2)


# --- (a) overhead light: the closed forms of aliasing.error (Lloyd et al. 2006 eqs. 9, 10, 12)


@pytest.mark.parametrize("fov", [1.0, 10.0, 60.0, 120.0, 170.0, 179.0])
def test_overhead_vertex_model_equals_closed_forms(fov):
    near = np.array([0.1, 1.0, 3.0])[:, None, None]
    ratio = np.array([1 + 1e-9, 1 + 1e-6, 1.001, 1.5, 10.0, 1000.0, 1e6])[None, :, None]
    far = near * ratio
    n_l = near + np.sqrt(far * near)  # n′_LiSPSM
    # n′ = n (PSM), inside the S-flat range, n′_LiSPSM, above, far above, uniform
    choices = np.array([0.0, 0.5, 1.0, 3.0, 1e3, np.inf])[None, None, :]
    n_prime = np.where(choices <= 1.0, near + choices * (n_l - near), n_l * choices)
    n, f, npr = (np.broadcast_to(a, n_prime.shape).ravel() for a in (near, far, n_prime))

    verts = G.frustum_vertices(n, f, fov)  # (K, 8, 3)
    mx, mz = D.max_errors(verts, OVERHEAD, fov, npr[None, :])
    assert mx.shape == mz.shape == (1, n.size)
    assert_close(mx[0], error.max_error_x(n, f, npr), rtol=RTOL)
    assert_close(mz[0], error.max_error_z(n, f, fov, npr), rtol=RTOL)
    assert_close(mx[0] * mz[0], error.storage_factor(n, f, fov, npr), rtol=RTOL)
    # and pointwise: m_x, m_z at the near and far vertices are eq. 7, eq. 8
    ex, ez = D.vertex_errors(D.fit(verts, OVERHEAD), fov, npr[None, :])
    depth = verts[..., 2]
    assert_close(ex[0], error.m_x(depth, n[:, None], f[:, None], npr[:, None]), rtol=RTOL)
    assert_close(ez[0], error.m_z(depth, n[:, None], f[:, None], fov, npr[:, None]), rtol=RTOL)


def test_overhead_uniform_parameterization_ignores_n_prime():
    verts = G.frustum_vertices(1.0, 100.0, 60.0)
    for npr in (1.0, 11.0, np.inf):
        mx, mz = D.max_errors(verts, OVERHEAD, 60.0, npr, "uniform")
        assert mx.item() == approx(error.max_error_x(1.0, 100.0), rel=RTOL)
        assert mz.item() == approx(error.max_error_z(1.0, 100.0, 60.0), rel=RTOL)


def test_overhead_spec_equals_closed_forms_near_a_slab():
    # BUG (geometry.py line 79): light_direction(90°) = (0, 1, 6.1e-17), since
    # cos(radians(90)) = 6.1e-17, so lights("overhead") is tilted by 6e-17 rad.  The tilt
    # adds ~6e-17·2f·tanθ to the light-plane depth W_ly = f − n, which for f/n → 1 and a
    # wide fov is a relative error of 1.3e-6 (f/n = 1 + 1e-9, fov 170°) in M_z and S̄.
    # Exact trigonometry in degrees (e.g. cos γ = sin(radians(90° − γ))) gives (0, 1, 0).
    n, f, fov = 1.0, 1.0 + 1e-9, 170.0
    for npr in (n, 2.0, np.inf):
        mx, mz = D.max_errors(G.frustum_vertices(n, f, fov), G.lights("overhead"), fov, npr)
        assert mz.item() == approx(error.max_error_z(n, f, fov, npr), rel=RTOL)
        assert (mx * mz).item() == approx(error.storage_factor(n, f, fov, npr), rel=RTOL)


# --- (b) log+perspective at n′ = n: the optimal storage factor (Lloyd et al. 2006 App. C)


@pytest.mark.parametrize("fov", [10.0, 60.0, 120.0, 170.0])
@pytest.mark.parametrize("ratio", [1 + 1e-9, 1.5, 10.0, 1000.0, 1e6])
@pytest.mark.parametrize("near", [0.1, 1.0, 7.0])
def test_logp_at_psm_parameter_is_optimal_storage(near, ratio, fov):
    far = near * ratio
    mx, mz = D.max_errors(G.frustum_vertices(near, far, fov), OVERHEAD, fov, near, "logperspective")
    assert mx.item() == approx(1.0, rel=RTOL)  # the warping frustum is the view frustum
    assert (mx * mz).item() == approx(error.storage_factor_optimal(near, far, fov), rel=RTOL)
    # m_z is constant over the vertices: the logarithmic spacing matches the eye's 1/z
    _, ez = D.vertex_errors(D.fit(G.frustum_vertices(near, far, fov), OVERHEAD), fov, near, "logperspective")
    assert_close(ez, ez.max(), rtol=1e-12)


def test_logp_scheme_at_overhead_is_optimal_storage():
    for near, far, fov in [(1.0, 1000.0, 60.0), (0.5, 20.0, 90.0), (2.0, 2.0 + 1e-6, 120.0)]:
        r = schemes.evaluate("LogP", near, far, fov, OVERHEAD)
        assert float(r.S[0]) == approx(error.storage_factor_optimal(near, far, fov), rel=RTOL)


# --- (c) light behind and in front: S̄ = (f/n)² (Lloyd et al. 2006 eq. 20, k = 1) -----


@pytest.mark.parametrize("light", ["behind", "front", [0.0, 0.0, -1.0], [0.0, 0.0, 3.0], "gamma:0@azimuth:45", "gamma:180@azimuth:-120"])
@pytest.mark.parametrize("near, far, fov", [(1.0, 1000.0, 60.0), (0.3, 20.0, 90.0), (2.0, 3.0, 150.0), (1.0, 1.0 + 1e-9, 60.0)])
def test_behind_and_in_front_uniform_is_depth_ratio_squared(light, near, far, fov):
    lv = G.lights(light)
    mx, mz = D.max_errors(G.frustum_vertices(near, far, fov), lv, fov)
    # the light sees a square: both extents are the far face's width 2 f tanθ
    assert mx.item() == approx(far / near, rel=RTOL)
    assert mz.item() == approx(far / near, rel=RTOL)
    assert (mx * mz).item() == approx((far / near) ** 2, rel=RTOL)


@pytest.mark.parametrize("scheme", ["Standard", "P", "Po", "LogP", "lispsm"])
def test_warping_schemes_revert_to_uniform_behind_and_in_front(scheme):
    # Lloyd 2006 §4.4: no warping is possible when the frustum looks square to the light
    for light in ("behind", "front"):
        r = schemes.evaluate(scheme, 1.0, 1000.0, 60.0, light)
        assert np.isinf(r.n_prime).all()
        assert float(r.S[0]) == approx(1000.0**2, rel=RTOL)


# --- (d) Lloyd et al. 2007 App. B: W_ly, eq. 111 with corrected eqs. 116–119 ----------


def _w_ly_corrected(near, far, theta, gamma):
    """Eq. 111 with eqs. 116 and 119 as printed and 117–118 corrected (angles in rad)."""
    w_n = 2 * near * np.tan(theta)  # eq. (119): W_n = W_e = 2 n tanθ
    w_s = (far - near) / np.cos(theta)  # eq. (119)
    w_n_l = w_n * np.cos(gamma)  # eq. (116)
    w_s1 = w_s * np.abs(np.sin(theta - gamma))  # eq. (117) corrected
    w_s2 = w_s * np.sin(theta + gamma)  # eq. (118) corrected
    return w_n_l + w_s2 + np.where(gamma < theta, w_s1, 0.0)  # eq. (111): s1 is a back face only for γ < θ


def _w_ly_printed(near, far, theta, gamma):
    """Eq. 111 with eqs. 117–118 as printed: W′_s1 = W_s(1 − cos(θ−γ)), W′_s2 = W_s sin(θ−γ)."""
    w_n = 2 * near * np.tan(theta)
    w_s = (far - near) / np.cos(theta)
    w_s1 = w_s * (1 - np.cos(theta - gamma))  # eq. (117) as printed
    w_s2 = w_s * np.sin(theta - gamma)  # eq. (118) as printed
    return w_n * np.cos(gamma) + w_s2 + np.where(gamma < theta, w_s1, 0.0)


@pytest.mark.parametrize("near, far, fov", [(1.0, 1000.0, 60.0), (1.0, 1024.0, 60.0), (0.5, 3.0, 90.0), (2.0, 50.0, 20.0), (1.0, 100.0, 150.0)])
def test_light_plane_depth_is_eq111_corrected(near, far, fov):
    theta = np.radians(fov / 2)
    gamma = np.linspace(0.0, 90.0, 361)
    gamma = np.union1d(gamma, [fov / 2 - 1e-6, fov / 2, fov / 2 + 1e-6])
    expected = _w_ly_corrected(near, far, theta, np.radians(gamma))
    verts = G.frustum_vertices(near, far, fov)
    # lights in the view's vertical (yz) plane, above the viewer ...
    assert_close(D.fit(verts, G.light_direction(gamma, 0.0)).depth[:, 0], expected, rtol=RTOL)
    # ... below it (the frustum is symmetric up/down) ...
    assert_close(D.fit(verts, G.light_direction(gamma, 180.0)).depth[:, 0], expected, rtol=RTOL)
    # ... and reversed, l → −l (γ → 180° − γ): the projection does not see the difference
    assert_close(D.fit(verts, G.light_direction(180.0 - gamma, 0.0)).depth[:, 0], expected, rtol=RTOL)


def test_light_plane_depth_limits():
    near, far, fov = 1.0, 1000.0, 60.0
    verts = G.frustum_vertices(near, far, fov)
    w = lambda g: float(D.fit(verts, G.light_direction(g, 0.0)).depth[0, 0])  # noqa: E731
    assert w(90.0) == approx(far - near, rel=RTOL)  # overhead: f − n
    # γ ≤ θ: the far face hides exactly the back faces, W_ly = W_f cos γ
    for g in (0.0, 10.0, 29.0):
        assert w(g) == approx(2 * far * _tan(fov) * math.cos(math.radians(g)), rel=RTOL)


def test_L4_printed_eqs_117_118_give_negative_depth():
    # docs/ERRATA.md L4: Lloyd et al. 2007 eqs. 117–118 as printed make W_ly negative for
    # γ > θ (−(f − n) at γ = 90°).  Not for *every* γ > θ, as L4 says: just above θ the
    # W_n cos γ term keeps it positive, up to γ = 30.0496° for f/n = 1000, θ = 30°.  The
    # corrected forms are the frustum's projected extent (previous tests).
    near, far, fov = 1.0, 1000.0, 60.0
    theta = np.radians(fov / 2)
    gamma = np.radians(np.linspace(30.5, 90.0, 120))
    printed = _w_ly_printed(near, far, theta, gamma)
    assert np.all(printed < 0)
    assert printed[-1] == approx(-(far - near), rel=RTOL)
    assert _w_ly_printed(near, far, theta, np.radians(30.04)) > 0 > _w_ly_printed(near, far, theta, np.radians(30.06))
    projected = D.fit(G.frustum_vertices(near, far, fov), G.light_direction(np.degrees(gamma), 0.0)).depth[:, 0]
    assert np.all(projected > 0)
    # and for γ < θ the printed W′_s1 = W_s(1 − cos(θ − γ)) is not the projected extent
    g_low = np.radians(np.array([5.0, 15.0, 25.0]))
    low = D.fit(G.frustum_vertices(near, far, fov), G.light_direction(np.degrees(g_low), 0.0)).depth[:, 0]
    assert not np.allclose(_w_ly_printed(near, far, theta, g_low), low, rtol=1e-3)


# --- (e) brute force: the vertex maxima are the maxima over the whole frustum ----------


def _interior_points(verts, steps=11):
    """Trilinear interpolation of the 8 corners: convex combinations, so inside the frustum."""
    u = np.linspace(0.0, 1.0, steps)
    a, b, c = (w.ravel()[:, None] for w in np.meshgrid(u, u, u, indexing="ij"))

    def quad(q):  # corners in the order (−,−), (+,−), (+,+), (−,+)
        return (1 - a) * (1 - b) * q[0] + a * (1 - b) * q[1] + a * b * q[2] + (1 - a) * b * q[3]

    return (1 - c) * quad(verts[:4]) + c * quad(verts[4:])


def _pointwise_errors(points, verts, basis, fov, n_prime, parameterization):
    """m_x, m_z at arbitrary points, from the module docstring's formulas."""
    y_v = verts @ basis[2]
    y0 = y_v.min()
    w_ly = y_v.max() - y0
    y = points @ basis[2] - y0
    w_i = 2 * _tan(fov) * points[:, 2]  # eq. (2), corrected: w_i = 2 tanθ · eye depth
    if parameterization == "uniform" or np.isinf(n_prime):
        w_lx = np.full_like(y, np.ptp(verts @ basis[0]))
        w_lz = np.full_like(y, w_ly)
    else:
        near_width = np.ptp((verts @ basis[0]) / (1 + (y_v - y0) / n_prime))  # on the warping near plane
        w_lx = (y + n_prime) / n_prime * near_width
        if parameterization == "perspective":
            w_lz = (y + n_prime) ** 2 * w_ly / (n_prime * (n_prime + w_ly))
        else:
            w_lz = (y + n_prime) * np.log((n_prime + w_ly) / n_prime)
    return w_lx / w_i, w_lz / w_i


@pytest.mark.parametrize("parameterization", PARAMS)
@pytest.mark.parametrize("near, far, fov", [(1.0, 50.0, 70.0), (0.5, 2.0, 120.0), (3.0, 300.0, 30.0)])
def test_vertex_maxima_are_maxima_over_the_frustum(near, far, fov, parameterization):
    rng = np.random.default_rng(11)
    lights = rng.normal(size=(25, 3))
    lights = np.vstack([lights, G.lights("front"), G.lights("overhead"), G.light_direction(1e-3, 45.0)])
    verts = G.frustum_vertices(near, far, fov)
    points = _interior_points(verts)
    basis = G.light_space(lights)
    lf = D.fit(verts, lights)
    for npr_scale in (0.3, 1.0, 4.0, np.inf):  # n′ below, at and above the frustum's depth scale
        npr = npr_scale * near * (1 + np.sqrt(far / near))
        mx, mz = D.max_errors(verts, lights, fov, npr, parameterization)
        vx, vz = D.vertex_errors(lf, fov, npr, parameterization)
        for i in range(len(lights)):
            px, pz = _pointwise_errors(points, verts, basis[i], fov, npr, parameterization)
            # no interior point exceeds the vertex maximum, and the vertices (in the sample) attain it
            assert px.max() == approx(mx[i, 0], rel=1e-10)
            assert pz.max() == approx(mz[i, 0], rel=1e-10)
            # the module's vertex values are the pointwise formula at the vertices
            vx_i, vz_i = _pointwise_errors(verts, verts, basis[i], fov, npr, parameterization)
            assert_close(vx[i, 0], vx_i, rtol=1e-10)
            assert_close(vz[i, 0], vz_i, rtol=1e-10)


# --- (f) Lloyd et al. 2007 Table 3 (f/n = 1000, θ = 30°: fov 60°), overhead light -----


def _three_figures(value):
    """The value rounded as Table 3 prints it: 3 significant figures."""
    return round(value, -int(math.floor(math.log10(abs(value)))) + 2)


@pytest.mark.parametrize(
    "scheme, printed",
    [
        ("Standard", 8.65e5),  # Lloyd et al. 2007, Table 3, Standard, Min S
        ("P", 865.0),  # Lloyd et al. 2007, Table 3, P (and Po), Min S
        ("Po", 865.0),  # Lloyd et al. 2007, Table 3, Po, Min S
        ("LogP", 5.98),  # Lloyd et al. 2007, Table 3, Log, Min S
        ("ZP5", 51.4),  # Lloyd et al. 2007, Table 3, ZP5, Min S
        ("ZP5+P", 12.9),  # Lloyd et al. 2007, Table 3, ZP5+P, Min S
        ("ZP5+LogP", 5.98),  # Lloyd et al. 2007, Table 3, ZP5+Log, Min S
        ("ZP7", 27.4),  # Lloyd et al. 2007, Table 3, ZP7, Min S
        ("ZP7+P", 10.2),  # Lloyd et al. 2007, Table 3, ZP7+P, Min S
        ("ZP7+LogP", 5.98),  # Lloyd et al. 2007, Table 3, ZP7+Log, Min S
    ],
)
def test_table3_overhead_minima(scheme, printed):
    r = schemes.evaluate(scheme, near=1.0, far=1000.0, fov=60.0, light="overhead")
    assert _three_figures(float(r.S[0])) == printed


def test_table3_overhead_minima_closed_forms():
    # the same minima in closed form (f/n = 1000, tanθ = tan 30°): Lloyd 2006 eqs. 12, 17, 18, App. C
    a, t = 1000.0, _tan(60.0)
    closed = {
        "Standard": a * (a - 1) / (2 * t),
        "P": (a - 1) / (2 * t),
        "LogP": math.log(a) / (2 * t),
        "ZP5": 5 * a**0.2 * (a**0.2 - 1) / (2 * t),
        "ZP5+P": 5 * (a**0.2 - 1) / (2 * t),
        "ZP7": 7 * a ** (1 / 7) * (a ** (1 / 7) - 1) / (2 * t),
        "ZP7+P": 7 * (a ** (1 / 7) - 1) / (2 * t),
    }
    for scheme, value in closed.items():
        assert float(schemes.evaluate(scheme, 1.0, 1000.0, 60.0, OVERHEAD).S[0]) == approx(value, rel=1e-12)


def test_table3_standard_supremum_along_the_diagonal():
    # Lloyd et al. 2007, Table 3, Standard, Max S: 2.00e6.  The supremum 2(f/n)² is approached
    # as γ → 0 with the frustum's diagonal along the light plane's y axis (azimuth 45°): the
    # square far face then spans √2·W_f in both directions.
    r = schemes.evaluate("Standard", 1.0, 1000.0, 60.0, G.light_direction(1e-6, 45.0))
    s = float(r.S[0])
    assert _three_figures(s) == 2.00e6
    assert s == approx(2 * 1000.0**2, rel=1e-6)
    # it is a supremum: no direction exceeds it, and γ = 0 exactly (a square, axis-aligned) gives (f/n)²
    sweep = schemes.evaluate("Standard", 1.0, 1000.0, 60.0, "sphere:4000").S
    assert sweep.max() <= 2 * 1000.0**2 * (1 + 1e-12)
    assert float(schemes.evaluate("Standard", 1.0, 1000.0, 60.0, "front").S[0]) == approx(1e6, rel=RTOL)


# --- (g) shapes, n′ = ∞ continuity and input checks -----------------------------------


def test_shapes():
    v1 = G.frustum_vertices(1.0, 100.0, 60.0)  # (8, 3)
    vk = G.frustum_vertices(*schemes.z_partitions(1.0, 100.0, 4), 60.0)  # (4, 8, 3)
    lv = G.lights("sphere:10")
    assert D.max_errors(v1, OVERHEAD, 60.0)[0].shape == (1, 1)
    assert D.max_errors(v1, lv, 60.0)[0].shape == (10, 1)
    assert D.max_errors(vk, OVERHEAD, 60.0)[1].shape == (1, 4)
    assert D.max_errors(vk, lv, 60.0, 5.0)[1].shape == (10, 4)
    lf = D.fit(vk, lv)
    assert lf.x.shape == lf.y.shape == (10, 4, 8) and lf.depth.shape == (10, 4) and lf.eye_depth.shape == (4, 8)
    # n′ per direction and partition, per partition, per direction
    for npr in (np.full((10, 4), 7.0), np.full(4, 7.0), np.full((10, 1), 7.0)):
        mx, mz = D.vertex_errors(lf, 60.0, npr)
        assert mx.shape == mz.shape == (10, 4, 8)
        assert_close(mx, D.vertex_errors(lf, 60.0, 7.0)[0], rtol=0)
    # partitions are independent: each equals the single frustum on its own
    mx, mz = D.max_errors(vk, lv, 60.0, 5.0, "logperspective")
    for k in range(4):
        mxk, mzk = D.max_errors(vk[k], lv, 60.0, 5.0, "logperspective")
        assert_close(mx[:, k], mxk[:, 0], rtol=0)
        assert_close(mz[:, k], mzk[:, 0], rtol=0)
    # a direction in a batch gives what it gives alone
    mx1, _ = D.max_errors(v1, lv[3], 60.0, 5.0)
    assert_close(D.max_errors(v1, lv, 60.0, 5.0)[0][3], mx1[0], rtol=0)


@pytest.mark.parametrize("parameterization", ["perspective", "logperspective"])
def test_infinite_n_prime_is_the_limit(parameterization):
    lv = np.vstack([G.lights("sphere:200"), G.lights("front"), G.lights("overhead")])
    verts = G.frustum_vertices(*schemes.z_partitions(1.0, 1000.0, 3), 60.0)
    lf = D.fit(verts, lv)
    inf_x, inf_z = D.vertex_errors(lf, 60.0, np.inf, parameterization)
    big_x, big_z = D.vertex_errors(lf, 60.0, 1e15, parameterization)
    assert np.isfinite(inf_x).all() and np.isfinite(inf_z).all()
    assert_close(big_x, inf_x, rtol=1e-10)
    assert_close(big_z, inf_z, rtol=1e-10)
    # and n′ = ∞ is the uniform map
    ux, uz = D.vertex_errors(lf, 60.0, 3.0, "uniform")
    assert_close(inf_x, ux, rtol=0)
    assert_close(inf_z, uz, rtol=0)


def test_vertex_errors_rejects_bad_input():
    lf = D.fit(G.frustum_vertices(1.0, 10.0, 60.0), OVERHEAD)
    with pytest.raises(ValueError, match="n_prime"):
        D.vertex_errors(lf, 60.0, 0.0)
    with pytest.raises(ValueError, match="n_prime"):
        D.vertex_errors(lf, 60.0, -1.0)
    with pytest.raises(ValueError, match="parameterization"):
        D.vertex_errors(lf, 60.0, 2.0, "cubic")
    with pytest.raises(ValueError, match="fov"):
        D.vertex_errors(lf, 180.0, 2.0)


def test_folded_gamma():
    g = np.array([0.0, 10.0, 45.0, 90.0, 135.0, 170.0, 180.0])
    folded = D.folded_gamma(G.light_direction(g, 33.0))
    np.testing.assert_allclose(folded, np.minimum(g, 180.0 - g), atol=1e-12)
    assert folded.shape == (7,)
    np.testing.assert_allclose(D.folded_gamma([0.0, 0.0, -4.0]), [0.0], atol=0)


def test_n_prime_from_eta_depth_is_light_plane_depth():
    # Lloyd 2007 eq. 120 at the overhead light: W_ly = f − n, so n_γ = n and η → n′ is eq. 11
    lf = D.fit(G.frustum_vertices(1.0, 100.0, 60.0), OVERHEAD)
    eta = np.array([-0.5, 0.0, 0.5, 1.0])
    assert_close(warping.n_prime_from_eta(eta, 1.0, 100.0, lf.depth[0, 0]), warping.n_prime_from_eta(eta, 1.0, 100.0), rtol=RTOL)
