"""Invariants of the analytic core, property-tested with Hypothesis (issue 11 item 6).

Profiles (tests/conftest.py): "ci" is derandomized; ALIASING_HYPOTHESIS=long runs 2,000 examples.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from aliasing import View, schemes, warping
from aliasing.geometry import light_direction

near = st.floats(1e-2, 1e2)
ratio = st.floats(1.5, 1e4)
fov = st.floats(10.0, 150.0)
gamma = st.floats(0.0, 180.0)
azimuth = st.floats(-180.0, 180.0)
# Sopt's optimiser: a 41-point grid in η, then golden section to 4e-10 in η (schemes._s_optimal);
# S̄ is smooth in η, so the optimum it returns is within a relative 1e-9 of the grid's basin minimum.
SOPT_RTOL = 1e-9


@settings(max_examples=25)
@given(near=near, ratio=ratio, fov=fov, gamma=gamma, azimuth=azimuth)
def test_perspective_rules_never_beat_sopt(near, ratio, fov, gamma, azimuth):
    light = light_direction(gamma, azimuth)
    view = View(near, near * ratio, fov)
    rows = ["P", "Po", "LiSPSM", "PSM", "Standard", "Sopt", "LogP", "LogSopt"]
    r = dict(zip(rows, (x.S[0] for x in schemes.evaluate_many(rows, view, light))))
    for name in ("P", "Po", "LiSPSM", "PSM", "Standard"):
        assert r[name] >= r["Sopt"] * (1 - SOPT_RTOL), name
    assert r["LogP"] >= r["LogSopt"] * (1 - SOPT_RTOL)


@given(near=near, ratio=ratio, fov=fov, gamma=gamma, azimuth=azimuth, scale=st.floats(1e-3, 1e3))
def test_scaling_near_and_far_together_leaves_s_unchanged(near, ratio, fov, gamma, azimuth, scale):
    light = light_direction(gamma, azimuth)
    rows = ["Standard", "P", "Po", "LogP", "ZP3+P", "FPc+LogP"]
    a = schemes.evaluate_many(rows, near, near * ratio, fov, light)
    b = schemes.evaluate_many(rows, near * scale, near * ratio * scale, fov, light)
    for name, x, y in zip(rows, a, b):
        np.testing.assert_allclose(y.S, x.S, rtol=1e-9, err_msg=name)


@given(eta=st.floats(-1.0, 1.0), near=near, ratio=st.floats(1.0 + 1e-6, 1e6), depth=st.floats(1e-3, 1e3))
def test_eta_n_prime_round_trip(eta, near, ratio, depth):
    far = near * ratio
    npr = warping.n_prime_from_eta(eta, near, far, depth)
    back = float(warping.eta_from_n_prime(npr, near, far, depth))
    # conditioning: eq. 120 inverted divides differences of O(1) terms by 1 − 1/√a (a = f/n), which
    # vanishes as f/n → 1, and n′ carries a relative error amplified by up to √a + 1
    eps, ra = np.finfo(float).eps, np.sqrt(ratio)
    assert abs(back - eta) <= 64 * eps * (ra + 1) / (1 - 1 / ra)
    assert npr >= depth * near / (far - near) * (1 - 1e-12)
