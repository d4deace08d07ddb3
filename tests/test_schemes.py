"""Scheme grammar, z-partitions, storage sums and the closed forms of Lloyd et al. 2006/2007."""

from __future__ import annotations

import importlib
import pkgutil

import numpy as np
import pytest

import aliasing
from aliasing import directional, error, geometry, schemes, warping
from conftest import assert_close

RTOL = 1e-12
OVERHEAD = np.array([0.0, 1.0, 0.0])  # exactly perpendicular to the view direction


def approx(expected, **tolerance):
    """pytest.approx without its default absolute tolerance of 1e-12."""
    return pytest.approx(expected, **{"abs": 0.0, **tolerance})


def _tan(fov):
    return np.tan(np.radians(fov) / 2)


def _all_rules():
    """Every registered warping rule, after importing every module of the package.

    Modules other than aliasing.warping (e.g. aliasing.gmnpr) register rules when imported;
    the registry is read at test time so that rules added later are tested too.
    """
    for module in pkgutil.iter_modules(aliasing.__path__):
        if not module.ispkg:
            importlib.import_module(f"aliasing.{module.name}")
    return list(warping.WARPING_RULES)


# --- grammar ----------------------------------------------------------------------------


@pytest.mark.parametrize(
    "text, name, k, rule, parameterization",
    [
        ("Standard", "Standard", 1, "uniform", "uniform"),
        ("uniform", "Standard", 1, "uniform", "uniform"),
        ("STANDARD", "Standard", 1, "uniform", "uniform"),
        ("P", "P", 1, "p", "perspective"),
        ("p", "P", 1, "p", "perspective"),
        ("Po", "Po", 1, "po", "perspective"),
        ("PO", "Po", 1, "po", "perspective"),
        ("LogP", "LogP", 1, "logp", "logperspective"),
        ("log", "LogP", 1, "logp", "logperspective"),
        ("LOG", "LogP", 1, "logp", "logperspective"),
        ("Sopt", "Sopt", 1, "sopt", "perspective"),
        ("LogSopt", "LogSopt", 1, "sopt", "logperspective"),
        ("logsopt", "LogSopt", 1, "sopt", "logperspective"),
        ("lispsm", "lispsm", 1, "lispsm", "perspective"),
        ("LiSPSM", "lispsm", 1, "lispsm", "perspective"),
        ("psm", "psm", 1, "psm", "perspective"),
        ("tsm", "tsm", 1, "tsm", "perspective"),
        ("lispsm-dz", "lispsm-dz", 1, "lispsm-dz", "perspective"),
        ("eta", "eta", 1, "eta", "perspective"),
        ("ZP5", "ZP5", 5, "uniform", "uniform"),
        ("zp5", "ZP5", 5, "uniform", "uniform"),
        ("ZP1", "ZP1", 1, "uniform", "uniform"),
        ("ZP5+Standard", "ZP5", 5, "uniform", "uniform"),
        ("zp5+uniform", "ZP5", 5, "uniform", "uniform"),
        ("ZP5+P", "ZP5+P", 5, "p", "perspective"),
        ("ZP7+Log", "ZP7+LogP", 7, "logp", "logperspective"),
        ("zp7+logp", "ZP7+LogP", 7, "logp", "logperspective"),
        ("ZP3+Po", "ZP3+Po", 3, "po", "perspective"),
        ("ZP2+sopt", "ZP2+Sopt", 2, "sopt", "perspective"),
        ("ZP2+LogSopt", "ZP2+LogSopt", 2, "sopt", "logperspective"),
        ("ZP3+psm", "ZP3+psm", 3, "psm", "perspective"),
        ("ZP05+p", "ZP5+P", 5, "p", "perspective"),
        ("ZP12+tsm", "ZP12+tsm", 12, "tsm", "perspective"),
        ("  ZP5+LogP  ", "ZP5+LogP", 5, "logp", "logperspective"),
    ],
)
def test_parse_forms(text, name, k, rule, parameterization):
    s = schemes.parse(text)
    assert s == schemes.Scheme(name=name, k=k, rule=rule, parameterization=parameterization)
    # canonical names parse to themselves
    assert schemes.parse(s.name) == s


def test_every_registered_rule_is_a_scheme():
    for key in _all_rules():
        for text in (key, key.upper(), f"ZP3+{key}"):
            s = schemes.parse(text)
            assert s.rule == ("uniform" if key == "uniform" else key)
            assert s.k == (3 if text.startswith("ZP") else 1)


@pytest.mark.parametrize("bad", ["ZP0", "ZP00", "ZP-1", "ZP", "ZP5+", "XYZ", "ZP5+XYZ", "ZP5+ZP3", "", "Log P", "ZP 5"])
def test_parse_errors_show_the_grammar(bad):
    # parse(): "ValueError shows the grammar".
    # BUG (schemes.py line 83): ZP0 / ZP00 raise "k in 'ZP0' must be >= 1 (ZP<k> with k
    # z-partitions)" without the grammar, unlike every other malformed name.
    with pytest.raises(ValueError) as info:
        schemes.parse(bad)
    message = str(info.value)
    assert repr(bad) in message
    assert schemes.GRAMMAR in message


def test_parse_error_names_k_for_zero_partitions():
    with pytest.raises(ValueError, match=r"k in 'ZP0' must be >= 1"):
        schemes.parse("ZP0")


def test_evaluate_accepts_parsed_schemes():
    s = schemes.parse("ZP3+LogP")
    a = schemes.evaluate(s, 1.0, 100.0, 60.0, "hemisphere:20")
    b = schemes.evaluate("zp3+log", 1.0, 100.0, 60.0, "hemisphere:20")
    assert a.scheme == b.scheme == s
    np.testing.assert_array_equal(a.S, b.S)


# --- z-partitions (Lloyd et al. 2006 eqs. 15–16) ----------------------------------------


@pytest.mark.parametrize("near, far", [(1.0, 1000.0), (0.1, 2.0), (3.0, 3.0 + 1e-9), (1.0, 1e8)])
@pytest.mark.parametrize("k", [1, 2, 5, 7, 16])
def test_z_partitions_are_eqs_15_16_and_self_similar(near, far, k):
    n_i, f_i = schemes.z_partitions(near, far, k)
    i = np.arange(1, k + 1)
    assert_close(n_i, near * (far / near) ** ((i - 1) / k), rtol=RTOL)  # eq. (15)
    assert_close(f_i, near * (far / near) ** (i / k), rtol=RTOL)  # eq. (16)
    assert n_i[0] == near and f_i[-1] == far  # exact ends
    np.testing.assert_array_equal(n_i[1:], f_i[:-1])  # contiguous
    assert_close(f_i / n_i, (far / near) ** (1 / k), rtol=1e-12)  # self-similar: one ratio
    assert np.all(f_i > n_i)


@pytest.mark.parametrize("k", [0, -2])
def test_z_partitions_rejects_no_partitions(k):
    # BUG (schemes.py lines 97–102): z_partitions does not check k; k = 0 divides by zero
    # (a RuntimeWarning, an error under the suite's filterwarnings) and otherwise returns
    # empty arrays, k < 0 returns nonsense.  README: bad input raises ValueError naming it.
    with pytest.raises(ValueError, match="k"):
        schemes.z_partitions(1.0, 100.0, k)


# --- S̄ is additive over the maps --------------------------------------------------------


@pytest.mark.parametrize("base", ["Standard", "P", "Po", "LogP", "lispsm", "Sopt"])
def test_storage_is_the_sum_over_maps(base):
    light = geometry.lights("sphere:60")
    near, far, fov, k = 1.0, 1000.0, 60.0, 4
    zp = schemes.evaluate(f"ZP{k}+{base}", near, far, fov, light)
    assert zp.maps == k and zp.M_x.shape == zp.M_z.shape == (60, k) and zp.S.shape == (60,)
    assert_close(zp.S, (zp.M_x * zp.M_z).sum(axis=-1), rtol=RTOL)
    # each map is the single-map scheme on its own partition
    n_i, f_i = schemes.z_partitions(near, far, k)
    parts = [schemes.evaluate(base, n, f, fov, light) for n, f in zip(n_i, f_i)]
    assert_close(zp.S, sum(p.S for p in parts), rtol=1e-12)
    for j, p in enumerate(parts):
        assert_close(zp.M_x[:, j], p.M_x[:, 0], rtol=1e-12)
        assert_close(zp.M_z[:, j], p.M_z[:, 0], rtol=1e-12)


# --- overhead closed forms ---------------------------------------------------------------


@pytest.mark.parametrize("fov", [20.0, 60.0, 120.0])
@pytest.mark.parametrize("ratio", [1.5, 10.0, 1000.0, 1e6])
def test_zpk_logp_overhead_is_the_same_for_all_k(ratio, fov):
    # Lloyd et al. 2007 §7: "The minimum error for ZPk+LogP, which occurs for an overhead
    # directional light, is the same for all k": ln(f/n)/(2 tanθ) (Lloyd 2006 App. C).
    expected = np.log(ratio) / (2 * _tan(fov))
    for k in range(1, 11):
        r = schemes.evaluate(f"ZP{k}+LogP", 1.0, ratio, fov, OVERHEAD)
        assert float(r.S[0]) == approx(expected, rel=RTOL)
    assert float(schemes.evaluate("ZP5+LogP", 2.0, 2.0 * ratio, fov, OVERHEAD).S[0]) == approx(expected, rel=RTOL)


@pytest.mark.parametrize("fov", [20.0, 60.0, 120.0])
@pytest.mark.parametrize("ratio", [1.5, 10.0, 1000.0, 1e6])
def test_zpk_and_zpk_p_overhead(ratio, fov):
    for k in range(1, 11):
        r = ratio ** (1 / k)
        uniform = schemes.evaluate(f"ZP{k}", 1.0, ratio, fov, OVERHEAD)
        warped = schemes.evaluate(f"ZP{k}+P", 1.0, ratio, fov, OVERHEAD)
        assert float(uniform.S[0]) == approx(k * r * (r - 1) / (2 * _tan(fov)), rel=1e-12)  # Lloyd 2006 eq. 17
        assert float(warped.S[0]) == approx(k * (r - 1) / (2 * _tan(fov)), rel=1e-12)  # Lloyd 2006 eq. 18


@pytest.mark.parametrize("k", [1, 2, 5, 7])
def test_zpk_behind_is_eq_20(k):
    # Lloyd et al. 2006 eq. 20: S̄_ZP,behind = k (f/n)^(2/k)
    for light in ("behind", "front"):
        r = schemes.evaluate(f"ZP{k}", 1.0, 1000.0, 60.0, light)
        assert float(r.S[0]) == approx(k * 1000.0 ** (2 / k), rel=1e-12)


def test_overhead_storage_matches_error_module_for_single_maps():
    near, far, fov = 1.0, 100.0, 90.0
    for name in ("psm", "lispsm", "uniform", "tsm"):
        r = schemes.evaluate(name, near, far, fov, OVERHEAD)
        npr = warping.warping_parameter(name, near, far)
        assert float(r.n_prime[0, 0]) == approx(float(npr), rel=RTOL)
        assert float(r.S[0]) == approx(float(error.storage_factor(near, far, fov, npr)), rel=RTOL)


# --- S-optimal warping --------------------------------------------------------------------


@pytest.mark.parametrize("near, far, fov", [(1.0, 1000.0, 60.0), (1.0, 100.0, 60.0), (1.0, 10.0, 90.0), (1.0, 2.0, 120.0)])
def test_sopt_is_at_most_every_other_perspective_rule(near, far, fov):
    light = geometry.lights("hemisphere:200")
    s_opt = schemes.evaluate("Sopt", near, far, fov, light).S
    others = [key for key in _all_rules() if schemes.parse(key).parameterization != "logperspective"]
    assert {"p", "po", "lispsm", "psm", "uniform"} <= set(others)
    for other in others:
        s = schemes.evaluate(other, near, far, fov, light).S
        assert np.all(s_opt <= s * (1 + 1e-9)), other
    s_log_opt = schemes.evaluate("LogSopt", near, far, fov, light).S
    assert np.all(s_log_opt <= schemes.evaluate("LogP", near, far, fov, light).S * (1 + 1e-9))
    assert np.all(s_log_opt <= schemes.evaluate("Standard", near, far, fov, light).S * (1 + 1e-9))


def test_sopt_eta_is_in_range_and_zp_sopt_per_map():
    r = schemes.evaluate("ZP3+Sopt", 1.0, 1000.0, 60.0, "hemisphere:50")
    assert r.eta.shape == (50, 3)
    assert np.all((r.eta >= -1) & (r.eta <= 1))
    zp_p = schemes.evaluate("ZP3+P", 1.0, 1000.0, 60.0, "hemisphere:50")
    assert np.all(r.S <= zp_p.S * (1 + 1e-9))


# --- every registered rule over the sphere ---------------------------------------------


def test_every_registered_rule_evaluates_without_nan():
    # iterated at test time: rules registered by other modules (GMNPR, ...) are included
    light = "sphere:500"
    for key in _all_rules():
        for scheme in (key, f"ZP3+{key}"):
            r = schemes.evaluate(scheme, 1.0, 1000.0, 60.0, light)
            assert r.S.shape == (500,), scheme
            for field in ("M_x", "M_z", "S", "n_prime"):
                values = getattr(r, field)
                assert not np.isnan(values).any(), (scheme, field)
            assert np.isfinite(r.S).all() and np.all(r.S > 0), scheme
            assert np.all(r.n_prime > 0), scheme
            # η is NaN only where n′ is a stronger warp than PSM's n_γ
            assert np.all(np.isnan(r.eta) | ((r.eta >= -1 - 1e-12) & (r.eta <= 1 + 1e-12))), scheme


# --- the η of the shaping rules at the overhead light ----------------------------------


@pytest.mark.parametrize("scheme, eta", [("P", 0.0), ("LogP", 1.0), ("ZP5+P", 0.0), ("ZP7+LogP", 1.0), ("Po", 0.0)])
@pytest.mark.parametrize("c_fraction", [0.4, 0.3])
def test_shaping_rules_at_overhead_give_their_eta(scheme, eta, c_fraction):
    # Lloyd et al. 2007 eq. 79: η_c = 0 for P, 1 for LogP, reached for γ ≥ γ_c; Po is LiSPSM (η = 0) overhead
    options = {"c_fraction": c_fraction} if scheme != "Po" else {}
    for light in ("overhead", OVERHEAD):
        r = schemes.evaluate(scheme, 1.0, 1000.0, 60.0, light, **options)
        np.testing.assert_allclose(r.eta, eta, atol=1e-12)
    if scheme != "Po":
        assert warping.SHAPING["logp" if "LogP" in scheme else "p"].eta_c == eta


def test_shaping_rules_revert_to_uniform_towards_the_view_axis():
    # eq. 79: η = −1 (n′ = ∞) for γ ≤ γ_a (θ/3 for P, θ/2 for LogP), at θ = 30°; (at γ_a
    # itself the folded γ may round just above γ_a, giving a huge finite n′: continuous)
    for scheme, gamma_a in (("P", 10.0), ("LogP", 15.0)):
        light = geometry.light_direction(np.array([0.0, gamma_a / 2, gamma_a - 1e-3, 180.0 - gamma_a + 1e-3, 180.0]), 20.0)
        r = schemes.evaluate(scheme, 1.0, 1000.0, 60.0, light)
        assert np.isinf(r.n_prime).all()
        np.testing.assert_allclose(r.eta, -1.0, atol=0)


def test_sopt_is_the_minimum_over_a_dense_eta_grid():
    # the grid + golden-section search of schemes._s_optimal against 401 η samples per direction
    near, far, fov = 1.0, 1000.0, 60.0
    light = geometry.lights("hemisphere:100")
    lf = directional.fit(geometry.frustum_vertices(near, far, fov), light)
    for scheme, parameterization in (("Sopt", "perspective"), ("LogSopt", "logperspective")):
        best = np.full(len(light), np.inf)
        for eta in np.linspace(-1.0, 1.0, 401):
            mx, mz = directional.vertex_errors(lf, fov, warping.n_prime_from_eta(eta, near, far, lf.depth), parameterization)
            best = np.minimum(best, (mx.max(axis=-1) * mz.max(axis=-1))[:, 0])
        assert np.all(schemes.evaluate(scheme, near, far, fov, light).S <= best * (1 + 1e-9)), scheme
