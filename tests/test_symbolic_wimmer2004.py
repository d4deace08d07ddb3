"""Wimmer et al. 2004 §4.2–4.4: derived expressions against the printed ones."""

from __future__ import annotations

import sympy as sp

from aliasing.symbolic import equivalent, get
from aliasing.symbolic import lloyd2006 as L
from aliasing.symbolic import wimmer2004 as W

P = W.PRINTED


def test_eq3_dp_ds_equals_printed():
    assert equivalent(W.dp_ds(), P["eq3"].expr)


def test_printed_ds_dz_is_the_derivative_of_the_corrected_eq2():
    assert equivalent(sp.diff(W.s_of_z_prime().subs(W.z_p, W.z - W.z_n + W.n), W.z), P["ds_dz"].expr)


def test_uniform_and_psm_limits_equal_printed():
    assert equivalent(W.dp_ds_uniform(), P["uniform"].expr)
    assert equivalent(W.dp_ds_psm(), P["psm"].expr)


def test_minimum_location_and_n_opt_equal_printed():
    assert equivalent(W.dp_ds_minimum(), P["minimum"].expr)
    assert equivalent(W.n_opt(), P["n_opt"].expr)


def test_n_opt_general_equals_printed():
    assert equivalent(W.n_opt_general(), P["n_opt_general"].expr)


def test_wimmer_n_opt_is_lloyd_lispsm():
    assert equivalent(W.n_opt().subs({W.z_n: L.n, W.z_f: L.f}), L.n_prime_lispsm())


def test_dp_ds_is_lloyd_m_z_times_2_tan_theta_near():
    # the two papers' normalisations: viewport of height 1 on the near plane vs 2 tanθ wide
    mz = L.m_z().subs({L.res_i: 1, L.res_t: 1})
    dpds = W.dp_ds().subs({W.z: L.z, W.z_n: L.n, W.z_f: L.f, W.n: L.n_p})
    assert sp.simplify(dpds - 2 * sp.tan(L.theta) * L.n * mz) == 0


def test_E4_eq2_printed_sign():
    # as printed, s(z′ = n) = 2f/(f − n) instead of 0; the printed ds/dz is positive,
    # which only the corrected (minus) sign gives
    f = W.n + W.z_f - W.z_n
    assert sp.simplify(P["eq2"].expr.subs(W.z_p, W.n) - 2 * f / (f - W.n)) == 0
    assert sp.simplify(W.s_of_z_prime().subs(W.z_p, W.n)) == 0
    assert not equivalent(sp.diff(P["eq2"].expr, W.z_p), sp.diff(W.s_of_z_prime(), W.z_p))


def test_E5_gamma_giving_the_original_formula_is_pi_over_2_not_pi():
    general = W.n_opt_general()
    assert equivalent(general.subs(W.gamma, sp.pi / 2), W.n_opt())
    assert general.subs(W.gamma, P["gamma_original"].expr) is sp.zoo  # 1/sin π: no warping


def test_registry_lookup():
    assert get("wimmer2004.n_opt").func is W.n_opt
