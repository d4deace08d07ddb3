"""Lloyd et al. 2007 §5.1, App. A (eqs. 47, 63–73): R_s, R_t, S of a face over light positions.

The maxima over v are checked against scipy maximisation of the lambdified symbolic ratios
δ_l/δ_b (general cos φ_l); the claim below eq. 73 (the maxima over light positions are those of
the overhead directional light, eqs. 87–103) on the App. A grid of light positions.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from scipy import integrate, optimize

from aliasing import logpsm
from aliasing.face_factors import face_factors, max_over_lights, optimal_factors, optimal_root
from aliasing.symbolic import lloyd2007 as L

NEAR, FAR, FOV = 1.0, 1000.0, 90.0  # App. A's frustum
Y0, Y1, W_E, CT = (float(q) for q in logpsm.side_face(NEAR, FAR, FOV))
SPAN = Y1 - Y0
CF = logpsm.critical_factors(NEAR, FAR, FOV)
SIGMA = np.array([0.1, 0.2, 0.5, 1.0, np.inf])[:, None]
KAPPA = np.linspace(-1.0, 2.0, 31)[None, :]


def _frame(expr):
    sf = L.side_face()
    return expr.subs({L.y0: sf["y0"], L.y1: sf["y1"], L.W_e: sf["W_e"]}).subs({L.n: NEAR, L.f: FAR, L.theta: sp.pi / 4})


def _symbolic_ratio_t(kind):
    """δ_l,t/δ_b,t^side (eqs. 47, 62, 96–109) as a function of y, l_y, l_z, a, b."""
    spacing = {"uniform": sp.Integer(1), "perspective": L.spacing_p()[1], "log": L.spacing_log(),
               "logp": L.spacing_lp().subs(L.c0_s, L.lp_constants()[L.c0_s])}[kind]
    expr = _frame(spacing / L.delta_b_side_t())
    if kind == "log":
        expr = sp.expand_log(expr, force=True)  # log(x)(a + y), not log(x**(a + y)), which overflows
    return sp.lambdify((L.y, L.l_y, L.l_z, L.a, L.b), expr, "numpy")


def _scipy_max(func, lo, hi):
    res = optimize.minimize_scalar(lambda q: -func(q), bounds=(lo, hi), method="bounded", options={"xatol": 1e-10})
    grid = np.linspace(lo, hi, 4001)
    k = int(np.argmax(func(grid)))
    res2 = optimize.minimize_scalar(lambda q: -func(q), bounds=(grid[max(k - 1, 0)], grid[min(k + 1, 4000)]), method="bounded", options={"xatol": 1e-12})
    return max(-res.fun, -res2.fun, func(lo), func(hi))


LIGHTS = [(-0.5, 0.1), (0.3, 0.1), (0.5, 0.2), (0.97, 0.1), (1.3, 0.5), (2.0, 1.0)]


@pytest.mark.parametrize("kind, a, b", [("uniform", 0.0, np.inf), ("perspective", 0.0, np.inf), ("perspective", 44.7, np.inf), ("log", 3.0, np.inf), ("logp", 0.0, -2500.0), ("logp", 1.0, 40.0)])
def test_R_t_equals_maximised_symbolic_ratio(kind, a, b):
    ratio = _symbolic_ratio_t(kind)
    bb = 1e300 if np.isinf(b) else b  # b → ∞ in the symbolic form
    for kappa, sigma in LIGHTS:
        ly, lz = kappa * SPAN, sigma * SPAN
        ref = _scipy_max(lambda y: ratio(y, ly, lz, a, bb) + 0 * y, Y0, Y1)
        got = face_factors(kind, NEAR, FAR, FOV, ly=ly, lz=lz, a=a, b=b)["R_t"]
        assert float(got) == pytest.approx(ref, rel=1e-9), (kappa, sigma)


@pytest.mark.parametrize("kind, a", [("uniform", 0.0), ("perspective", 0.0), ("perspective", 20.0)])
def test_R_s_equals_maximised_symbolic_ratio_over_the_face(kind, a):
    spacing = sp.Integer(1) if kind == "uniform" else L.spacing_p()[0]
    f = sp.lambdify((L.x, L.y, L.l_x, L.l_z, L.a), _frame(spacing / L.delta_b_side_s()), "numpy")
    for lx, sigma in ((0.0, 0.1), (0.6, 0.1), (300.0, 0.2), (-900.0, 0.5), (1500.0, 1.0)):
        lz = sigma * SPAN

        def row_max(y):  # eq. 71: maximise over the face's row x ∈ [x0(y), x1(y)] (eq. 60)
            half = W_E * y / (2 * Y0)
            return max(f(np.clip(lx, -half, half), y, lx, lz, a), f(-half, y, lx, lz, a), f(half, y, lx, lz, a))

        ref = _scipy_max(np.vectorize(row_max), Y0, Y1)
        assert float(face_factors(kind, NEAR, FAR, FOV, lx=lx, lz=lz, a=a)["R_s"]) == pytest.approx(ref, rel=1e-9)


def test_bound_R_equals_rho_by_quadrature_of_the_symbolic_spacing():
    inv_t = sp.lambdify((L.y, L.l_y, L.l_z), _frame(1 / (L.delta_b_side_t() * (L.y1 - L.y0))), "numpy")
    inv_s = sp.lambdify((L.x, L.y, L.l_x, L.l_z), _frame(1 / (L.delta_b_side_s() * (L.x1_of(L.y1) - L.x0_of(L.y1)))), "numpy")
    inv_end = sp.lambdify((L.y, L.l_y, L.l_z), _frame(1 / L.delta_b_end()), "numpy")
    for kappa, sigma in LIGHTS:
        ly, lz = kappa * SPAN, sigma * SPAN
        f = face_factors("bound", NEAR, FAR, FOV, lx=ly / 3, ly=ly, lz=lz)
        rho_t, _ = integrate.quad(lambda y: inv_t(y, ly, lz), Y0, Y1, epsrel=1e-12, limit=200, points=[min(max(ly, Y0), Y1)])  # eq. (65)
        assert float(f["R_t"]) == pytest.approx(rho_t, rel=1e-9)
        rows = np.linspace(Y0, Y1, 41)  # eq. 64: ρ_b,s(v) = ∫ over the row; R_b,s = max_v (sampled here, so ≥)
        rho_s = [integrate.quad(lambda x: inv_s(x, y, ly / 3, lz), -W_E * y / (2 * Y0), W_E * y / (2 * Y0), epsrel=1e-12)[0] for y in rows]
        assert float(f["R_s"]) >= max(rho_s) * (1 - 1e-12) and float(f["R_s"]) == pytest.approx(max(rho_s), rel=1e-3)
        width = W_E * FAR / NEAR  # far end face: v ∈ [0, 1] ↦ y ∈ [−width/2, width/2] (eq. 66)
        rho_end, _ = integrate.quad(lambda y: inv_end(y, ly, lz) / width, -width / 2, width / 2, epsrel=1e-12, limit=200)
        assert float(face_factors("bound", NEAR, FAR, FOV, ly=ly, lz=lz, face="far")["R_t"]) == pytest.approx(rho_end, rel=1e-9)


# --- eqs. 72–73 and the claim below eq. 73 ---------------------------------------------------------


@pytest.mark.parametrize("kind", ["bound", "uniform", "perspective", "log", "logp"])
def test_eq73_claim_maxima_over_light_positions_are_the_overhead_values(kind):
    light = dict(lx=0.4 * KAPPA * SPAN, ly=KAPPA * SPAN, lz=SIGMA * SPAN)
    grid = face_factors(kind, NEAR, FAR, FOV, **light)
    top = max_over_lights(grid)
    over = face_factors(kind, NEAR, FAR, FOV)  # lz = inf: the directional light straight above
    for key in ("R_s", "R_t", "S"):
        assert top[key] == pytest.approx(float(over[key]), rel=1e-12), key
        assert np.all(grid[key][:-1] <= over[key] * (1 + 1e-12))
    closed = {"bound": ("bound_s_side", "bound_t_side"), "uniform": ("uniform_s_side", "uniform_t_side"), "perspective": ("perspective_s_side", None),
              "log": ("perspective_s_side", "log_t_side"), "logp": ("perspective_s_side", "log_t_side")}[kind]
    assert float(over["R_s"]) == pytest.approx(float(CF[closed[0]]), rel=1e-12)  # eqs. 88, 94, 99
    if closed[1]:
        assert float(over["R_t"]) == pytest.approx(float(CF[closed[1]]), rel=1e-12)  # eqs. 89, 95, 103
    # a directional light from any other direction: cos φ_l is a constant < 1 on the face
    d = face_factors(kind, NEAR, FAR, FOV, lx=0.3, ly=np.array([-2.0, 0.5, 1.0]), lz=1.0, directional=True)
    np.testing.assert_allclose(d["R_t"], over["R_t"] / np.sqrt(1 + np.array([4.0, 0.25, 1.0])), rtol=1e-12)
    np.testing.assert_allclose(d["R_s"], over["R_s"] / np.sqrt(1.09), rtol=1e-12)


@pytest.mark.parametrize("kind", ["bound", "uniform"])
def test_eq73_claim_on_end_faces(kind):
    for face in ("near", "far"):
        grid = face_factors(kind, NEAR, FAR, FOV, lx=KAPPA * SPAN / 2, ly=KAPPA * SPAN, lz=SIGMA * SPAN, face=face)
        top = max_over_lights(grid)
        assert top["R_t"] == pytest.approx(float(CF[f"{kind}_t_end"]), rel=1e-12)  # eqs. 87, 93
        assert top["R_s"] == pytest.approx(float(CF[f"{kind}_t_end"]), rel=1e-12)  # δ_b,s^end: δ_b,t^end in x
        assert top["S"] == pytest.approx(1 / CT**2, rel=1e-12)


@pytest.mark.parametrize("kind, minimize, key", [("perspective", "R_s", "perspective_s_side"), ("perspective", "R_t", "perspective_t_side"),
                                                 ("perspective", "S", "perspective_S_side"), ("log", "R_t", "log_t_side")])
def test_eq73_claim_for_the_optimal_parameter_matches_eqs_99_103(kind, minimize, key):
    light = dict(ly=KAPPA[:, ::3] * SPAN, lz=SIGMA * SPAN)
    best = optimal_factors(kind, NEAR, FAR, FOV, minimize=minimize, samples=129, **light)
    assert max_over_lights(best)[minimize] == pytest.approx(float(CF[key]), rel=1e-8)  # eqs. 99–101 (corrected, L16), 103
    assert np.all(best[minimize][:-1] <= CF[key] * (1 + 1e-8))
    if key == "perspective_t_side":
        np.testing.assert_allclose(best["a"][-1], np.sqrt(Y0 * Y1), rtol=1e-4)  # LiSPSM's a at σ = ∞
    if key in ("perspective_s_side", "log_t_side"):
        np.testing.assert_array_equal(best["a"][-1], 0.0)  # eqs. 99, 103: a_opt = 0 overhead


def test_L19_R_un_is_maximal_over_the_end_face_but_not_over_the_side_face():
    ly = np.array([Y0, 0.25 * SPAN, 0.5 * SPAN, 0.75 * SPAN, Y1])
    side = face_factors("uniform", NEAR, FAR, FOV, ly=ly, lz=0.1 * SPAN)["R_t"]
    assert side[0] == pytest.approx(float(CF["uniform_t_side"]), rel=1e-12)  # over the near edge only
    assert np.all(side[1:] < 0.4 * CF["uniform_t_side"]) and side[2] == pytest.approx(196.298, rel=1e-5)
    end = face_factors("uniform", NEAR, FAR, FOV, ly=np.array([-900.0, 0.0, 500.0]), lz=0.1 * SPAN, face="far")["R_t"]
    np.testing.assert_allclose(end, CF["uniform_t_end"], rtol=1e-12)  # "whenever the light is over the face"


# --- degenerate inputs, shapes, validation -----------------------------------------------------------


@pytest.mark.parametrize("kind", ["bound", "uniform", "perspective", "log"])
def test_light_in_the_face_plane_is_the_limit(kind):
    ly = np.array([-300.0, 0.3 * SPAN, 0.8 * SPAN, 2.0 * SPAN])
    lx = np.array([5.0, 0.5, 600.0, 3000.0])
    flat = face_factors(kind, NEAR, FAR, FOV, lx=lx, ly=ly, lz=0.0, a=2.0)
    near_plane = face_factors(kind, NEAR, FAR, FOV, lx=lx, ly=ly, lz=1e-12 * SPAN, a=2.0)
    over = face_factors(kind, NEAR, FAR, FOV, a=2.0)  # the scale; R → its limit like O(l_z) (O(l_z log l_z) for the bound)
    np.testing.assert_allclose(flat["R_t"], near_plane["R_t"], rtol=1e-6, atol=1e-7 * over["R_t"])
    np.testing.assert_allclose(flat["R_s"], near_plane["R_s"], rtol=1e-6, atol=1e-7 * over["R_s"])
    if kind == "bound":
        assert np.all(flat["S"] == 0)
    else:
        assert flat["R_t"][0] == 0 and flat["R_t"][3] == 0 and flat["R_t"][1] > 0  # only a light over the face
        assert flat["R_s"][3] == 0 and flat["R_s"][0] > 0  # |lx| beyond the widest row


def test_overhead_light_three_ways():
    for kind in ("bound", "uniform", "log"):
        over = face_factors(kind, NEAR, FAR, FOV, ly=123.0, lz=np.inf)
        d = face_factors(kind, NEAR, FAR, FOV, ly=0.0, lz=1.0, directional=True)
        high = face_factors(kind, NEAR, FAR, FOV, ly=123.0, lz=1e8 * SPAN)
        for key in ("R_s", "R_t", "S"):
            assert float(over[key]) == pytest.approx(float(d[key]), rel=1e-14)
            assert float(high[key]) == pytest.approx(float(over[key]), rel=1e-6)


def test_scalar_and_nd_inputs():
    one = face_factors("perspective", NEAR, FAR, FOV, ly=500.0, lz=100.0, a=3.0)
    assert all(np.ndim(v) == 0 for v in one.values())
    grid = face_factors("perspective", NEAR, np.array([100.0, 1000.0])[:, None, None], FOV, ly=np.array([0.0, 500.0])[None, :, None], lz=np.array([50.0, 100.0, np.inf]), a=3.0)
    assert grid["S"].shape == (2, 2, 3)
    assert float(grid["S"][1, 1, 1]) == pytest.approx(float(one["S"]), rel=1e-12)
    np.testing.assert_allclose(grid["S"], grid["R_s"] * grid["R_t"], rtol=1e-15)
    top = max_over_lights(grid, axis=(1, 2))
    assert top["S"].shape == (2,)


def test_optimal_root_beats_a_scan_of_b_and_is_linear_overhead():
    ly = np.array([0.5, 0.97, 1.5]) * SPAN
    best = optimal_root(NEAR, FAR, FOV, ly=ly, lz=0.1 * SPAN)
    bs = np.concatenate([-np.geomspace(Y1 * 1.001, 1e8, 120), np.geomspace(1e-2, 1e8, 120), -np.geomspace(1e-3, Y0 * 0.999, 40)])
    scan = face_factors("logp", NEAR, FAR, FOV, ly=ly[:, None], lz=0.1 * SPAN, b=bs[None, :], samples=129)["R_t"].min(axis=1)
    assert np.all(best["R_t"] <= scan * (1 + 1e-9))
    lin = face_factors("logp", NEAR, FAR, FOV, ly=ly, lz=0.1 * SPAN)["R_t"]
    assert np.all(best["R_t"] < lin)
    over = optimal_root(NEAR, FAR, FOV)
    assert float(over["R_t"]) == pytest.approx(float(CF["log_t_side"]), rel=1e-9) and abs(float(over["b"])) > 1e6


@pytest.mark.parametrize("b", [-0.5, -2000.0, -np.inf, 3.0])
def test_logpsm_spacing_with_a_negative_root_equals_symbolic_and_is_normalised(b):
    # the concave (b < −y1) and the strongly convex (−y0 < b < 0) parabolas of eq. 106
    v = np.linspace(0.0, 1.0, 9)
    got = logpsm.spacing("logp_t", v, NEAR, FAR, FOV, a=0.0, b=b)
    assert np.all(got > 0)
    assert integrate.quad(lambda q: 1 / float(logpsm.spacing("logp_t", q, NEAR, FAR, FOV, b=b)), 0, 1, epsrel=1e-12)[0] == pytest.approx(1.0, rel=1e-10)
    if np.isfinite(b):
        expr = _frame(L.spacing_lp().subs(L.c0_s, L.lp_constants()[L.c0_s]).subs(L.y, L.y_of_v))
        ref = sp.lambdify((L.v, L.a, L.b), expr, "mpmath")
        np.testing.assert_allclose(got, [float(ref(q, 0, b)) for q in v], rtol=1e-12)


@pytest.mark.parametrize(
    "call, word",
    [
        (lambda: face_factors("nope", NEAR, FAR, FOV), "unknown kind 'nope'"),
        (lambda: face_factors("log", NEAR, FAR, FOV, face="far"), "side faces only"),
        (lambda: face_factors("uniform", NEAR, FAR, FOV, face="top"), "unknown face 'top'"),
        (lambda: face_factors("uniform", NEAR, FAR, FOV, lz=-1.0), "lz must be in [0, inf]"),
        (lambda: face_factors("uniform", NEAR, FAR, FOV, lz=0.0, directional=True), "lz must be in (0, inf)"),
        (lambda: face_factors("uniform", NEAR, FAR, FOV, ly=np.inf), "lx and ly must be finite"),
        (lambda: face_factors("uniform", NEAR, FAR, FOV, samples=2), "samples must be a whole number >= 3"),
        (lambda: face_factors("uniform", FAR, NEAR, FOV), "far must be greater than near"),
        (lambda: face_factors("logp", NEAR, FAR, FOV, b=-100.0), "b must be > −y0 or < −y1"),
        (lambda: face_factors("uniform", NEAR, FAR, FOV, a=-1.0), "a must be in [0, inf]"),
        (lambda: optimal_factors("uniform", NEAR, FAR, FOV), "unknown kind 'uniform'"),
        (lambda: optimal_factors("log", NEAR, FAR, FOV, minimize="area"), "unknown minimize 'area'"),
        (lambda: optimal_factors("log", NEAR, FAR, FOV, a_max=0.0), "a_max must be in (0, inf)"),
        (lambda: max_over_lights({"R_s": 1.0}), "missing ['R_t', 'S']"),
    ],
)
def test_validation(call, word):
    with pytest.raises(ValueError) as err:
        call()
    assert word in str(err.value)


def test_eq68_numeric_is_stable_for_a_light_near_the_face_plane():
    # eq. 68's log argument cancels for y beyond a low light; the package uses an equivalent form
    import mpmath

    def rho_ref(ly, lz):
        with mpmath.workdps(60):
            ly_, lz_ = mpmath.mpf(ly), mpmath.mpf(lz)
            L_ = mpmath.sqrt(ly_**2 + lz_**2)
            zeta = lambda y: -mpmath.mpf(Y0) / (mpmath.mpf(W_E) * mpmath.mpf(CT)) * lz_ / L_ * mpmath.log(  # noqa: E731  eq. (68), printed
                2 / y * ((ly_ * (ly_ - y) + lz_**2) / (lz_ * L_) + mpmath.sqrt((y - ly_) ** 2 + lz_**2) / lz_))
            return float(zeta(mpmath.mpf(Y1)) - zeta(mpmath.mpf(Y0)))

    for lz in (1e-9, 1e-4, 1.0, 100.0):
        for ly in (-300.0, 700.0, 1300.0, 2000.0):
            assert float(logpsm.rho_bound("side_t", NEAR, FAR, FOV, ly=ly, lz=lz)) == pytest.approx(rho_ref(ly, lz), rel=1e-13)


def test_optimal_factors_of_a_grazing_light_are_inf_not_nan():
    """A directional light almost in the face's plane (lz = 6.1e-281) has S = inf; the optimal a stays a number
    (the API fuzz found a + 0·S warning there)."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = optimal_factors("logp", 1.0, 10.0, 60.0, lz=6.1e-281, b=1.0, directional=True)
    assert np.isinf(r["S"]) and np.isfinite(r["a"]) and not any(np.isnan(v).any() for v in r.values())
