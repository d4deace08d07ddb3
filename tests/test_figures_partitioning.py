"""Partitioning figures (Lloyd 2006 Figs. 10, 12, 13; Zhang 2006 splits; engine presets) show what the text says.

Checkpoint values are from the papers' closed forms as re-derived in the research notes
(f/n = 1000, θ = 30°); the sympy forms are lambdified once (``lloyd2006_fig12.closed_forms``).
"""

from __future__ import annotations

import numpy as np
import pytest

from aliasing import error, partitioning
from aliasing.figures import engine_presets, lloyd2006_fig10, lloyd2006_fig12, lloyd2006_fig13, zhang2006_splits

TAN30 = np.tan(np.radians(30.0))


# --- Lloyd et al. 2006 Fig. 10: S̄ over k, light overhead ------------------------------------


@pytest.fixture(scope="module")
def fig10():
    return lloyd2006_fig10.data()


def test_fig10_general_evaluation_equals_eqs_17_18(fig10):
    assert list(fig10) == ["k", "ZP", "ZPW", "optimal", "general_ZP", "general_ZPW"]
    np.testing.assert_allclose(fig10["general_ZP"], fig10["ZP"], rtol=1e-12)
    np.testing.assert_allclose(fig10["general_ZPW"], fig10["ZPW"], rtol=1e-12)


def test_fig10_zp_w_decreases_towards_and_stays_above_the_optimum(fig10):
    opt = fig10["optimal"][0]
    assert opt == pytest.approx(np.log(1000.0) / (2 * TAN30), rel=1e-12)  # App. C
    assert opt == pytest.approx(float(error.storage_factor_optimal(1.0, 1000.0, 60.0)), rel=1e-12)
    zpw = fig10["ZPW"]
    assert np.all(np.diff(zpw) < 0) and np.all(zpw > opt)
    assert np.all(fig10["ZP"] > zpw)  # warping removes the factor (f/n)^(1/k) > 1 (eq. 17 → 18)
    # the notes' checkpoints for k = 1 … 10 (f/n = 1000, θ = 30°)
    printed = [865.2, 53.0, 23.4, 16.0, 12.9, 11.2, 10.2, 9.50, 9.00, 8.62]
    np.testing.assert_allclose(zpw[:10], printed, rtol=0, atol=0.05)  # rounded to the digits shown
    # "as k increases, the storage factor approaches that of the optimal": eqs. 17 and 18 → App. C
    cf = lloyd2006_fig12.closed_forms()
    for key in ("eq17", "eq18"):
        assert cf[key](1000.0, 1.0, 1e7, np.radians(30.0)) == pytest.approx(opt, rel=1e-5)


# --- Lloyd et al. 2006 Fig. 12: S̄ over the number of shadow maps --------------------------


@pytest.fixture(scope="module")
def fig12():
    return lloyd2006_fig12.data()


def test_fig12_general_evaluation_equals_closed_forms(fig12):
    for light in ("overhead", "behind"):
        for key in ("ZP", "ZPW"):
            np.testing.assert_allclose(fig12[f"general_{key}_{light}"], fig12[f"{key}_{light}"], rtol=1e-12)
    # no warping from behind ("the view frustum is square"): ZP+W = ZP
    np.testing.assert_array_equal(fig12["ZPW_behind"], fig12["ZP_behind"])
    # eq. 21 (FP+ZP+W behind) against the general face-partition evaluation at j = 4k + 1
    fp = np.isfinite(fig12["FPZPW_behind"])
    assert fp.sum() == 9
    np.testing.assert_allclose(fig12["general_FPZPW_behind"][fp], fig12["FPZPW_behind"][fp], rtol=1e-12)


def test_fig12_map_counting(fig12):
    j = fig12["j"]
    over, behind = fig12["FPZPW_overhead"], fig12["FPZPW_behind"]
    # overhead: one z-partitioning per four maps (eq. 23), eq. 19 = eq. 18 at k = j/4
    assert np.array_equal(np.isfinite(over), j % 4 == 0)
    np.testing.assert_allclose(over[j % 4 == 0], fig12["ZPW_overhead"][: int(j[-1]) // 4], rtol=1e-12)
    # behind: eq. 21 with j = 4k + 1 maps (the near face counted) = 4 S̄_ZP+W,overhead(θ = 45°) + 1
    k = (j - 1) / 4
    fp_maps = ((j - 1) % 4 == 0) & (j >= 5)
    assert np.array_equal(np.isfinite(behind), fp_maps)
    eq18_45 = lloyd2006_fig12.closed_forms()["eq18"](1000.0, 1.0, k[fp_maps], np.pi / 4)
    np.testing.assert_allclose(behind[fp_maps], 4 * eq18_45 + 1, rtol=1e-12)
    np.testing.assert_allclose(behind[[4, 8, 16, 24]], [1999.0, 123.5, 38.0, 27.0], rtol=3e-3)  # j = 5, 9, 17, 25


def test_fig12_what_the_text_says(fig12):
    j = fig12["j"]
    over = fig12["FPZPW_overhead"]
    fp = np.isfinite(over)
    # "even ZP without warping does better than FP+ZP+W in the overhead case"
    assert np.all(fig12["ZP_overhead"][fp] < over[fp])
    np.testing.assert_allclose(fig12["ZP_overhead"][[0, 4, 8]], [865159.4, 51.39, 19.39], rtol=3e-4)
    # behind, ZP "decreases rapidly and then begins to grow slowly": minimum 37.56 at j = 14
    zp = fig12["ZP_behind"]
    assert int(j[np.argmin(zp)]) == 14 and zp.min() == pytest.approx(37.56, rel=1e-3)
    assert np.all(np.diff(zp[:14]) < 0) and np.all(np.diff(zp[13:]) > 0)
    # FP+ZP+W "eventually has lower error than the ZP schemes": from j = 17 on
    behind = fig12["FPZPW_behind"]
    wins = j[np.isfinite(behind) & (behind < zp)]
    assert wins.min() == 17 and np.all(behind[np.isfinite(behind) & (j >= 17)] < zp[np.isfinite(behind) & (j >= 17)])


# --- Lloyd et al. 2006 Fig. 13: lowest error with the light behind ---------------------------


def test_fig13_crossover_values():
    # continuous roots of j (f/n)^(2/j) = 2k((f/n)^(1/k) − 1) + 1, k = (j − 1)/4 (notes §2)
    for a, root in ((10.0, 6.4), (100.0, 11.7), (1000.0, 16.9), (1e4, 22.1), (1e6, 32.6)):
        assert lloyd2006_fig13.crossover(a) == pytest.approx(root, abs=0.05)
    zp, fp = lloyd2006_fig13._forms()
    j = lloyd2006_fig13.crossover(1000.0)
    assert zp(1000.0, j) == pytest.approx(fp(1000.0, (j - 1) / 4), rel=1e-10)
    # the asymptote 2 ln(f/n)/ln(1 + √2) ≈ 2.27 ln(f/n)
    assert lloyd2006_fig13.ASYMPTOTE == pytest.approx(2.269, abs=1e-3)
    assert lloyd2006_fig13.crossover(1e100) / np.log(1e100) == pytest.approx(lloyd2006_fig13.ASYMPTOTE, rel=5e-3)


def test_fig13_region_map():
    a = np.array([10.0, 100.0, 1000.0, 1e4, 1e5])
    cols = lloyd2006_fig13.data(a)
    maps = lloyd2006_fig13.MAPS
    win = cols["FPZPW_lower"].reshape(a.size, maps).astype(bool)
    first = cols["j_first_FPZPW"][::maps]
    # whole numbers of maps at which FP+ZP+W first wins: 9, 13, 17, 25 (= 4k + 1); 1000 → 17 as in Fig. 12
    np.testing.assert_array_equal(first[:4], [9, 13, 17, 25])
    for row, f in zip(win, first):
        np.testing.assert_array_equal(row, np.arange(1, maps + 1) >= f)  # one switch, then FP+ZP+W stays lower
    assert np.all(first >= cols["j_star"][::maps])  # the whole-j boundary lies on or above the curve
    # "z-partitioning is the best scheme for high depth range with few shadow maps"
    assert not win[-1, 4] and win[0, -1]
    assert np.all(np.isnan(cols["S_FPZPW"].reshape(a.size, maps)[:, :4]))  # FP+ZP+W needs j ≥ 5


# --- Zhang et al. 2006: split ladders ---------------------------------------------------------


def test_zhang_ladders_equal_split_distances():
    cols = zhang2006_splits.data()
    assert (zhang2006_splits.NEAR, zhang2006_splits.FAR) == (1.0, 800.0)  # §4: near = 1 m, far = 800 m
    for m in zhang2006_splits.SPLITS:
        rows = cols["m"] == m
        np.testing.assert_array_equal(cols["i"][rows], np.arange(m + 1))
        for key, (method, params, _) in zhang2006_splits.METHODS.items():
            np.testing.assert_array_equal(cols[key][rows], partitioning.split_distances(method, 1.0, 800.0, m, **params))
    three = cols["m"] == 3
    expected = {
        "log": (9.28, 86.2),
        "uniform": (267.3, 533.7),
        "practical": (138.3, 309.9),
        "pssm": (200.75, 400.5),
        "pssm-transition": (457.6, 685.9),
        "pssm-transition-log": (45.6, 307.9),
    }
    for key, planes in expected.items():
        np.testing.assert_allclose(cols[key][three][1:3], planes, rtol=1e-3)


def test_zhang_eq4_rules_halve_e1_at_every_plane():
    cols = zhang2006_splits.data()
    for m in zhang2006_splits.SPLITS:
        rows = cols["m"] == m
        length = np.diff(cols["pssm-transition"][rows])
        np.testing.assert_allclose(length[:-1] / length[1:], 2.0, rtol=1e-12)  # uniform maps: l_i = 2 l_(i+1)
        log_ratio = np.diff(np.log(cols["pssm-transition-log"][rows]))
        np.testing.assert_allclose(log_ratio[:-1] / log_ratio[1:], 2.0, rtol=1e-12)  # log maps: ln a_i = 2 ln a_(i+1)


# --- engine presets: equal shares vs error-based allocation -----------------------------------


@pytest.fixture(scope="module")
def presets():
    return engine_presets.data()


def test_engine_presets_cover_the_registry(presets):
    # the current release of each: NAME@RELEASE forms (threejs-csm@r184) stay out of the figure
    expected = [name for name, entry in partitioning.SPLIT_METHODS.items() if entry.default_k is not None and "@" not in name]
    assert presets["preset"] == expected and len(expected) == 10  # nine engines + bgfx-current; osg-pssm has no default k
    assert presets["k"] == [partitioning.SPLIT_METHODS[name].default_k for name in expected]
    for far_i in presets["far_i"] + presets["log_far_i"]:
        assert float(far_i.split(";")[-1]) == engine_presets.FAR


def test_error_allocation_never_worse_than_equal(presets):
    for prefix in ("", "log_"):
        equal = np.array(presets[f"{prefix}max_error_equal"])
        err = np.array(presets[f"{prefix}max_error_error"])
        assert np.all(err <= equal * (1 + 1e-12))
        # eq. 83 gives every map the error res_i √(ΣS/T): at the worst direction, from S_max
        expected = engine_presets.RES_IMAGE * np.sqrt(np.array(presets[f"{prefix}S_max"]) / engine_presets.BUDGET)
        np.testing.assert_allclose(err, expected, rtol=1e-9)


def test_log_split_beats_every_preset(presets):
    for alloc in ("equal", "error"):
        assert np.all(np.array(presets[f"log_max_error_{alloc}"]) < np.array(presets[f"max_error_{alloc}"]))


# --- every script writes its PNG and CSV --------------------------------------------------------


@pytest.mark.parametrize("module", [lloyd2006_fig10, lloyd2006_fig12, lloyd2006_fig13, zhang2006_splits, engine_presets])
def test_main_writes_png_and_csv(module, tmp_path):
    paths = module.main(tmp_path)
    assert sorted(p.name for p in paths) == sorted([f"{module.NAME}.png", f"{module.NAME}.csv"])
    assert all(p.stat().st_size > 100 for p in paths)
    header = (tmp_path / f"{module.NAME}.csv").read_text().splitlines()[0]
    assert "," in header
