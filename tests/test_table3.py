"""Lloyd et al. 2007, Table 3 (non-FP rows) reproduced: published values with their source.

Minima are exact (overhead light) and are tested at the printed precision (3 significant
figures).  Maxima and means are over sampled directions; the paper does not state its
sampling, so they are tested against what sampling can deliver: the sampled maximum is
below the supremum and within 1 % of it, and the reported differences are documented in
docs/ERRATA.md (L5, L6) and in the generated table.
"""

from __future__ import annotations

import math

import numpy as np

import pytest

from figures import lloyd2007_table3 as T3


def sig3(x: float) -> float:
    return round(x, -int(math.floor(math.log10(abs(x)))) + 2)


@pytest.fixture(scope="module")
def ours():
    return T3.data(4000)


@pytest.mark.parametrize("row", T3.ROWS)
def test_minimum_at_printed_precision(ours, row):
    # Lloyd et al. 2007, Table 3, column "Min S"
    assert sig3(ours[row]["S_min"]) == T3.PRINTED[row][0]


@pytest.mark.parametrize("row", ["Standard", "Log", "ZP5", "ZP5+Log", "ZP7", "ZP7+P", "ZP7+Log"])
def test_sampled_maximum_close_to_printed(ours, row):
    # Lloyd et al. 2007, Table 3, column "Max S": sampling approaches the supremum from below
    printed = T3.PRINTED[row][1]
    assert ours[row]["S_max"] == pytest.approx(printed, rel=0.01)


def test_standard_supremum_is_two_f_over_n_squared():
    # Table 3 "Standard" max 2.00e6 = 2 (f/n)²: the far face seen along the diagonal as γ → 0
    from aliasing import geometry, schemes

    light = geometry.light_direction(1e-6, 45.0)
    s = schemes.evaluate("Standard", 1.0, 1000.0, 60.0, light).S[0]
    assert sig3(s) == 2.00e6


def test_p_and_po_rows_are_swapped_in_print(ours):
    # ERRATA L5: our shaped P reproduces the printed Po row, our 1/sin γ Po the printed P row
    # (the text: "in contrast to Po, our improved shaping function keeps the maximum error of P
    # below that of a standard shadow map")
    assert ours["P"]["S_max"] <= ours["Standard"]["S_max"] * (1 + 1e-12)
    assert sig3(ours["P"]["S_max_over_min"]) == pytest.approx(T3.PRINTED["Po"][2], rel=0.01)
    assert ours["Po"]["S_max"] > ours["Standard"]["S_max"]
    # Po's supremum lies in the view's vertical plane, near γ = 11.3°: find it on a dense
    # γ grid and compare at the printed precision with the printed *P* row's 3.65e6
    import numpy as np

    from aliasing import geometry, schemes

    gamma = np.linspace(0.01, 90.0, 9000)
    s = schemes.evaluate("Po", 1.0, 1000.0, 60.0, geometry.light_direction(gamma, 0.0)).S
    assert sig3(s.max()) == T3.PRINTED["P"][1]


def test_zp5_p_row_repeats_zp5_log_in_print(ours):
    # ERRATA L6: from its own printed min and max, max/min = 159/12.9 = 12.3, not 26.4
    printed_min, printed_max = T3.PRINTED["ZP5+P"][:2]
    assert printed_max / printed_min == pytest.approx(12.3, abs=0.05)
    assert ours["ZP5+P"]["S_max_over_min"] == pytest.approx(printed_max / printed_min, rel=0.02)


def test_main_writes_table(tmp_path):
    paths = T3.main(tmp_path, directions=200)
    text = paths[1].read_text()
    assert all(f"| {row} |" in text for row in T3.ROWS)


# --- ERRATA L20: the means, tested against named hypotheses ----------------------------------------

from aliasing import table3_hypotheses as H  # noqa: E402


@pytest.fixture(scope="module")
def hypothesis_residuals():
    return {name: H.residuals(name, 2000) for name in H.HYPOTHESES}


def test_no_hypothesis_fits_the_means(hypothesis_residuals):
    # Lloyd 2007 Table 3 "Mean S" (3 significant figures): no hypothesis brings P's mean, or
    # FP's, within print, and none fits more than two rows
    for name, res in hypothesis_residuals.items():
        assert abs(res["P"]) > 0.03, name
        assert res["FP+P"] < -0.02 or res["FP+P"] > 0.015, name
        assert len(H.fits(res)) <= 2, (name, H.fits(res))
    base = hypothesis_residuals["baseline"]
    assert base["P"] == pytest.approx(-0.091, abs=0.003) and base["Standard"] == pytest.approx(0.010, abs=0.003)


def test_invariant_hypotheses_equal_the_baseline(hypothesis_residuals):
    # sphere = hemisphere by l ↔ −l; a dense frustum sampling = the vertices (the maxima lie there)
    light = H.equal_area(300)
    for row in ("Standard", "P", "LogP", "ZP5+P"):
        np.testing.assert_allclose(H.evaluate_row(row, light, points=5), H.evaluate_row(row, light), rtol=1e-9)
    for row in H.ROWS:
        assert hypothesis_residuals["sphere"][row] == pytest.approx(hypothesis_residuals["baseline"][row], abs=0.002)


def test_small_samples_do_not_fit_all_rows_at_once():
    spread = H.small_sample_spread(100, 40)
    within = np.all([np.abs(v) <= 0.005 for v in spread.values()], axis=0)
    assert not within.any()
    assert np.percentile(spread["FP+P"], 95) < 0  # FP stays below print whatever the sample


def test_every_cell_agrees_is_explained_or_flagged():
    ours = T3.data(20_000)
    cells = T3.cells(ours)
    import re

    for (row, col), (_, _, status) in cells.items():
        assert status == "agrees" or status.startswith("UNEXPLAINED") or re.match(r"L\d+", status), (row, col, status)
    flagged = {k for k, v in cells.items() if v[2].startswith("UNEXPLAINED")}
    means = {(r, "S_mean") for r in T3.ROWS} - {("FPcs+P", "S_mean"), ("ZP5+P", "S_mean")}
    assert flagged == means | {("ZP5+P", "S_max")}
    assert cells[("P", "S_mean")][1] == 1.80e5  # compared with the printed Po row (L5)


def test_hypothesis_validation():
    with pytest.raises(ValueError, match="hypothesis"):
        H.residuals("nope")
    with pytest.raises(ValueError, match="count"):
        H.residuals("baseline", 10)
