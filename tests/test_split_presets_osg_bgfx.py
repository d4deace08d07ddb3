"""The OpenSceneGraph PSSM split and bgfx's current cascade split (issue 15 item 5), as read
from their public sources (cited in aliasing/partitioning.py)."""

from __future__ import annotations

import numpy as np
import pytest

from aliasing import partitioning as P
from aliasing import schemes
from aliasing.cli import main


def test_osg_pssm_is_a_power_law_of_i_over_k():
    n, f, k = 1.0, 800.0, 4
    c = P.split_distances("osg-pssm", n, f, k)
    np.testing.assert_allclose(c, n + (f - n) * (np.arange(5) / 4) ** 1.66, rtol=1e-12)
    np.testing.assert_allclose(P.split_distances("osg-pssm", n, f, k, bias=0.0), P.split_distances("uniform", n, f, k), rtol=1e-12)
    # a larger bias pulls every inner split towards the eye
    assert np.all(P.split_distances("osg-pssm", n, f, k, bias=2.0)[1:-1] < c[1:-1])


@pytest.mark.parametrize("bias", [-0.1, 3.5])
def test_osg_pssm_bias_range(bias):
    with pytest.raises(ValueError, match="bias"):
        P.split_distances("osg-pssm", 1.0, 100.0, 3, bias=bias)


def test_osg_pssm_needs_k():
    with pytest.raises(ValueError, match="needs k"):
        P.split_distances("osg-pssm", 1.0, 100.0)


def test_bgfx_current_ends_before_its_far_plane():
    # the example's defaults: n = 1, m_far = 550, 4 cascades, λ = 0.6: s_i = 1/10, 3/10, 5/10, 7/10
    s = np.array([0.1, 0.3, 0.5, 0.7])
    ends = 0.6 * 550.0**s + 0.4 * (1 + 549 * s)
    assert ends[-1] == pytest.approx(203.8256, abs=1e-4)  # shadows end at 37 % of m_far
    c = P.split_distances("bgfx-current", 1.0, ends[-1])
    np.testing.assert_allclose(c, np.concatenate([[1.0], ends]), rtol=1e-9)
    assert P.bgfx_current_setting_far(1.0, ends[-1]) == pytest.approx(550.0, rel=1e-9)
    lo, hi = P.partitions("bgfx-current", 1.0, ends[-1])
    np.testing.assert_array_equal(lo[1:], hi[:-1])  # contiguous: the 1.005 overlap of the old splitFrustum is gone


def test_bgfx_current_differs_from_the_long_standing_split():
    old = P.split_distances("bgfx", 1.0, 200.0)
    new = P.split_distances("bgfx-current", 1.0, 200.0)
    assert not np.allclose(old, new, rtol=1e-3)
    assert np.all(np.diff(new) > 0)
    with pytest.raises(ValueError, match="at most 4"):
        P.split_distances("bgfx-current", 1.0, 200.0, 5)
    with pytest.raises(ValueError, match="lambda"):
        P.split_distances("bgfx-current", 1.0, 200.0, 4, lam=1.5)


@pytest.mark.parametrize("method", ["osg-pssm", "bgfx-current"])
def test_presets_evaluate_and_are_listed(method, capsys):
    lo, hi = P.partitions(method, 0.5, 500.0, 4)
    r = schemes.evaluate("Standard", 0.5, 500.0, 60.0, "overhead", edges=(lo, hi))
    assert r.maps == 4 and np.isfinite(r.S).all()
    assert main(["splits", "--list"]) == 0
    assert method in capsys.readouterr().out
