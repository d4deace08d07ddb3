"""The reproduced figures show what the papers' text says about them."""

from __future__ import annotations

import numpy as np
import pytest

from aliasing.figures import lloyd2006_fig5, lloyd2006_fig6, wimmer2004_fig6


def test_lloyd2006_fig5_maxima_locations():
    cols = lloyd2006_fig5.data()
    n_l = 1 + np.sqrt(20)
    for label, npr in lloyd2006_fig5.curves():
        mx, mz = cols[f"mx[{label}]"], cols[f"mz[{label}]"]
        assert mx[0] == pytest.approx(mx.max(), rel=1e-12)  # x error maximal at z = n for every n′
        if npr > n_l + 1e-9:
            assert mz[0] > mz[-1]  # near plane dominates above n′_LiSPSM
        elif npr < n_l - 1e-9:
            assert mz[-1] > mz[0]
        else:
            assert mz[0] == pytest.approx(mz[-1], rel=1e-12)
            assert mz[0] == pytest.approx(1 / np.sqrt(20), rel=1e-12)


def test_lloyd2006_fig6_shapes():
    cols = lloyd2006_fig6.data()
    eta, mz, s, mx = cols["eta"], cols["M_z"], cols["S"], cols["M_x"]
    left, right = eta <= 0, eta >= 0
    # M_z piecewise linear in η with its minimum 1/√(f/n) of the maximum at η = 0
    for part in (left, right):
        coef = np.polyfit(eta[part], mz[part], 1)
        np.testing.assert_allclose(np.polyval(coef, eta[part]), mz[part], rtol=1e-10)
    assert mz.min() / mz.max() == pytest.approx(0.1, rel=1e-12)
    # M_x from f/n down to 1; S flat for η ≥ 0
    assert mx[0] == pytest.approx(100.0) and mx[-1] == pytest.approx(1.0)
    assert np.all(np.diff(mx) < 0)
    np.testing.assert_allclose(s[right], s[right][0], rtol=1e-12)
    assert s[0] / s[right][0] == pytest.approx(100.0, rel=1e-12)


def test_wimmer2004_fig6_values():
    cols = wimmer2004_fig6.data()
    z = cols["z"]
    assert cols["uniform"][0] == pytest.approx(99.0) and cols["PSM"][-1] == pytest.approx(99.0)
    lis = cols["LiSPSM"]
    assert lis[0] == pytest.approx(lis[-1], rel=1e-12) and lis[0] == pytest.approx(9.9, rel=1e-12)
    assert abs(z[np.argmin(lis)] - 10.0) < z[1] - z[0]  # minimum at √(z_n z_f)
