"""Split schemes, storage factors of z-partitions (Lloyd 2006 §5.3) and resolution budgets."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from aliasing import budgets, error, partitioning, schemes
from aliasing.cli import main
from aliasing.symbolic import equivalent
from aliasing.symbolic import lloyd2006 as L


# --- symbolic §5.3 against the printed equations --------------------------------------------


@pytest.mark.parametrize(
    "derive, key",
    [(L.storage_zp_overhead, "eq17"), (L.storage_zp_w_overhead, "eq18"), (L.storage_zp_behind, "eq20"), (L.storage_fp_zp_w_behind, "eq21")],
)
def test_section_5_3_derived_equals_printed(derive, key):
    assert equivalent(derive(), L.PRINTED[key].expr)


def test_zp_closed_forms_equal_general_evaluation():
    # eqs. 17, 18 (overhead) and 20 (behind) against the vertex evaluation of aliasing.schemes
    S17 = sp.lambdify((L.f, L.n, L.k, L.theta), L.storage_zp_overhead())
    S18 = sp.lambdify((L.f, L.n, L.k, L.theta), L.storage_zp_w_overhead())
    S20 = sp.lambdify((L.f, L.n, L.k), L.storage_zp_behind())
    for ratio, fov in ((1000.0, 60.0), (37.0, 100.0)):
        for k in (1, 2, 5, 9):
            th = np.radians(fov / 2)
            assert schemes.evaluate(f"ZP{k}", 1.0, ratio, fov, "overhead").S[0] == pytest.approx(S17(ratio, 1.0, k, th), rel=1e-12)
            assert schemes.evaluate(f"ZP{k}+LiSPSM", 1.0, ratio, fov, "overhead").S[0] == pytest.approx(S18(ratio, 1.0, k, th), rel=1e-12)
            assert schemes.evaluate(f"ZP{k}", 1.0, ratio, fov, "behind").S[0] == pytest.approx(S20(ratio, 1.0, k), rel=1e-12)


def test_zp_w_approaches_the_optimal_log_storage():
    # Lloyd 2006 Fig. 10: S_ZP+W,overhead → ln(f/n)/(2 tanθ) as k → ∞ (App. C), from above
    S18 = sp.lambdify((L.f, L.n, L.k, L.theta), L.storage_zp_w_overhead())
    opt = float(error.storage_factor_optimal(1.0, 1000.0, 60.0))
    values = np.array([S18(1000.0, 1.0, k, np.radians(30.0)) for k in (1, 4, 16, 64, 4096)])
    assert np.all(np.diff(values) < 0) and np.all(values > opt)
    assert values[-1] == pytest.approx(opt, rel=1e-3)


# --- split schemes ------------------------------------------------------------------------


def test_log_splits_are_eqs_15_16_and_self_similar():
    c = partitioning.split_distances("log", 2.0, 2000.0, 6)
    i = np.arange(7)
    np.testing.assert_allclose(c, 2.0 * 1000.0 ** (i / 6), rtol=1e-14)
    np.testing.assert_allclose(c[1:] / c[:-1], 1000.0 ** (1 / 6), rtol=1e-13)


def test_uniform_and_practical_splits():
    u = partitioning.split_distances("uniform", 1.0, 101.0, 4)
    np.testing.assert_allclose(u, [1, 26, 51, 76, 101])
    lg = partitioning.split_distances("log", 1.0, 101.0, 4)
    for lam in (0.0, 0.3, 1.0):
        p = partitioning.split_distances("practical", 1.0, 101.0, 4, lam=lam)
        np.testing.assert_allclose(p, lam * lg + (1 - lam) * u, rtol=1e-14)
        assert np.all(np.diff(p) > 0)


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: partitioning.split_distances("log", 1.0, 10.0, 0), "k must be a whole number >= 1"),
        (lambda: partitioning.split_distances("log", 1.0, 10.0, 2.5), "k must be a whole number >= 1"),
        (lambda: partitioning.split_distances("log", 0.0, 10.0, 2), r"near must be in \(0, inf\)"),
        (lambda: partitioning.split_distances("log", 5.0, 5.0, 2), "far must be greater than near"),
        (lambda: partitioning.split_distances("practical", 1.0, 10.0, 2, lam=-0.1), r"lambda must be in \[0, 1\]"),
        (lambda: partitioning.split_distances("log", 1.0, 10.0, 2, lam=0.5), "takes no parameters"),
        (lambda: partitioning.split_distances("cascades", 1.0, 10.0, 2), "unknown split method 'cascades'"),
        (lambda: schemes.evaluate("P", 1.0, 10.0, 60.0, edges=[1.0, 5.0, 4.0, 10.0]), "increasing"),
        (lambda: schemes.evaluate("P", 1.0, 10.0, 60.0, edges=[1.0, 5.0, 9.0]), "end at far"),
    ],
)
def test_bad_split_input(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_explicit_edges_equal_zp():
    e = partitioning.split_distances("log", 1.0, 500.0, 4)
    a = schemes.evaluate("ZP4+P", 1.0, 500.0, 70.0, "sphere:60")
    b = schemes.evaluate("P", 1.0, 500.0, 70.0, "sphere:60", edges=e)
    np.testing.assert_array_equal(a.S, b.S)
    assert b.maps == 4


# --- budgets --------------------------------------------------------------------------------


def test_error_allocation_equalises_and_is_minimax():
    r = schemes.evaluate("P", 1.0, 1000.0, 60.0, "hemisphere:50", edges=partitioning.split_distances("practical", 1.0, 1000.0, 4, lam=0.7))
    budget, res = 4096.0**2, 1024.0
    rs, rt = budgets.allocate("error", r.M_x, r.M_z, budget)
    np.testing.assert_allclose((rs * rt).sum(axis=-1), budget, rtol=1e-12)
    err = budgets.max_error(r.M_x, r.M_z, rs, rt, res)
    np.testing.assert_allclose(err, res * np.sqrt(r.S / budget)[:, None] * np.ones_like(err), rtol=1e-12)
    # no other allocation of the same budget does better: the equal shares are worse or equal
    for other in ("equal", "equal-balanced"):
        rs2, rt2 = budgets.allocate(other, r.M_x, r.M_z, budget)
        np.testing.assert_allclose((rs2 * rt2).sum(axis=-1), budget, rtol=1e-12)
        assert np.all(budgets.max_error(r.M_x, r.M_z, rs2, rt2, res).max(axis=-1) >= err.max(axis=-1) * (1 - 1e-12))


def test_single_map_error_allocation_is_eqs_13_14():
    rs_c, rt_c = error.critical_resolution(1.0, 100.0, 60.0, 11.0, res_image=1.0)
    rs, rt = budgets.allocate("error", np.array([[rs_c]]), np.array([[rt_c]]), 2048.0**2)
    es, et = error.resolution_for_budget(2048.0**2, rs_c, rt_c)
    assert rs[0, 0] == pytest.approx(es, rel=1e-12) and rt[0, 0] == pytest.approx(et, rel=1e-12)


def test_budget_validation():
    with pytest.raises(ValueError, match="at least one texel per map"):
        budgets.allocate("equal", np.ones((1, 4)), np.ones((1, 4)), 3.0)
    with pytest.raises(ValueError, match="unknown allocation"):
        budgets.allocate("fair", np.ones((1, 2)), np.ones((1, 2)), 30.0)
    with pytest.raises(ValueError, match="go together"):
        budgets.splits_report("log", 1.0, 10.0, 2, budget=100.0)


def test_splits_cli(capsys):
    code = main(["splits", "--method", "log", "--near", "1", "--far", "1000", "-k", "4", "--warp", "P", "--budget", "16777216", "--image-res", "1024", "--format", "csv"])
    out = capsys.readouterr().out.splitlines()
    assert code == 0 and out[0].startswith("partition,near,far,S_max")
    last = out[-1].split(",")
    assert last[0] == "all"
    # ZP4+P overhead: S = 4((f/n)^(1/4) − 1)/(2 tan 30°); error = 1024 √(S / 4096²)
    s = 4 * (1000 ** 0.25 - 1) / (2 * np.tan(np.radians(30)))
    assert float(last[3]) == pytest.approx(s, rel=1e-9)


@pytest.mark.parametrize(
    "argv, needle",
    [
        (["--near", "1", "--far", "10"], "needs k (number of partitions)"),
        (["--method", "nope", "--near", "1", "--far", "10", "-k", "2"], "unknown split method"),
        (["--method", "practical", "--lambda", "2", "--near", "1", "--far", "10", "-k", "2"], "lambda must be in [0, 1]"),
        (["--near", "1", "--far", "10", "-k", "3", "--budget", "2", "--image-res", "64"], "at least one texel per map"),
        (["--near", "-1", "--far", "10", "-k", "3"], "near must be in (0, inf)"),
        (["--near", "1", "--far", "10", "-k", "x"], "invalid int value"),
    ],
)
def test_splits_cli_bad_input(argv, needle, capsys):
    try:
        code = main(["splits", *argv])
    except SystemExit as exc:
        code = exc.code
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1 and needle in err


# --- engine presets: worked examples from the engines' own defaults ---------------------------


@pytest.mark.parametrize(
    "method, near, far, expected",
    [
        # Ogre PSSMShadowCameraSetup constructor: calculateSplitPoints(3, 100, 100000), λ = 0.95
        ("ogre-pssm", 100.0, 100000.0, [100.0, 2620.0, 12835.0, 100000.0]),
        # bgfx example 16 splitFrustum: n = 1, f = 550, 4 splits, λ = 0.6, s = (2i − 1)/(2k)
        ("bgfx", 1.0, 550.0, [1.0, 29.17, 89.14, 168.62, 550.0]),
        # Godot 4: split_1..3 = 0.1, 0.2, 0.5 of (max_distance − near), near 0.05, max_distance 100
        ("godot", 0.05, 100.0, [0.05, 10.045, 20.04, 50.025, 100.0]),
        # Filament cascadeSplitPositions {0.125, 0.25, 0.5}
        ("filament", 0.0 + 1.0, 801.0, [1.0, 101.0, 201.0, 401.0, 801.0]),
        # Unreal: E = 3, k = 3: fractions 0, 1/13, 4/13, 1 of (F − n)
        ("unreal", 1.0, 14.0, [1.0, 2.0, 5.0, 14.0]),
    ],
)
def test_presets_reproduce_engine_defaults(method, near, far, expected):
    np.testing.assert_allclose(partitioning.split_distances(method, near, far), expected, rtol=5e-4)


def test_threejs_r184_applies_breaks_as_fractions_from_near():
    # up to r184 CSM.js stores C/F and CSMFrustum.split lerps near → far corners by it: n + (C/F)(F − n)
    n, f = 0.1, 1000.0
    textbook = 0.5 * partitioning.split_distances("log", n, f, 3) + 0.5 * partitioning.split_distances("uniform", n, f, 3)
    got = partitioning.split_distances("threejs-csm@r184", n, f)
    np.testing.assert_allclose(got[1:-1], (n + textbook / f * (f - n))[1:-1], rtol=1e-14)  # ends are n and F
    assert got[0] == n and got[-1] == f


def test_threejs_current_ends_cascades_at_break_times_far():
    # since r185 split() lerps by (b·F − n)/(F − n): cascade i ends at b_i·F = C_i, the practical split
    n, f = 1.0, 100.0
    textbook = partitioning.split_distances("practical", n, f, 8, lam=0.5)
    np.testing.assert_allclose(partitioning.split_distances("threejs-csm", n, f, 8), textbook, rtol=1e-14)
    np.testing.assert_array_equal(partitioning.split_distances("threejs-csm@r187", n, f, 8), partitioning.split_distances("threejs-csm", n, f, 8))
    old = partitioning.split_distances("threejs-csm@r184", n, f, 8)
    assert 0.10 < float(np.max(old / textbook - 1)) < 0.13  # up to 12 % apart at near 1, far 100, 8 cascades


@pytest.mark.parametrize(
    "name, message",
    [
        ("threejs-csm@r100", r"unknown release 'r100' of 'threejs-csm'; known releases: r184, r185, r186, r187"),
        ("babylon@8.0.0", r"known releases: 9\.35\.0"),
        ("log@r1", "not pinned to engine releases"),
        ("nosuch@r1", "unknown split method 'nosuch'"),
    ],
)
def test_unknown_release_is_refused_with_the_known_ones(name, message):
    with pytest.raises(ValueError, match=message):
        partitioning.split_distances(name, 1.0, 100.0, 3)


def test_every_engine_preset_names_its_release():
    engines = [m for m in partitioning.SPLIT_METHODS.values() if m.default_k is not None or m.name in ("osg-pssm",)]
    assert {"threejs-csm", "threejs-csm@r184", "babylon", "bevy"} <= {m.name for m in engines}
    for m in engines:
        assert m.release, m.name
    from aliasing.engines import stable

    for p in stable.PRESETS.values():
        assert p.release, p.name


def test_babylon_cascade_count_is_its_engines_range():
    # CascadedShadowGenerator clamps numCascades to [MIN_CASCADES_COUNT, MAX_CASCADES_COUNT] = [2, 4]: refused outside
    for k in (2, 3, 4):
        assert partitioning.split_distances("babylon", 1.0, 100.0, k).size == k + 1
    for k in (1, 5):
        with pytest.raises(ValueError, match="k must be at least 2 and at most 4 for 'babylon'"):
            partitioning.split_distances("babylon", 1.0, 100.0, k)


def test_bevy_split_is_geometric_from_the_first_bound_with_overlap():
    # cascade.rs: bounds first·(max/first)^(i/(n − 1)); near bounds minimum_distance, then (1 − 0.2)·previous far bound
    e = partitioning.split_distances("bevy", 0.1, 150.0)
    np.testing.assert_allclose(e, [0.1, *(10.0 * 15.0 ** (np.arange(4) / 3))], rtol=1e-14)
    lo, hi = partitioning.partitions("bevy", 0.1, 150.0)
    np.testing.assert_allclose(lo, [0.1, *(0.8 * e[1:-1])], rtol=1e-14)
    np.testing.assert_array_equal(hi, e[1:])
    np.testing.assert_array_equal(partitioning.split_distances("bevy", 0.1, 150.0, 1), [0.1, 150.0])
    np.testing.assert_allclose(partitioning.split_distances("bevy", 0.1, 150.0, 3, first=5.0)[1:], 5.0 * 30.0 ** (np.arange(3) / 2), rtol=1e-14)
    with pytest.raises(ValueError, match=r"first \(Bevy's first_cascade_far_bound\) must be in \(near, far\)"):
        partitioning.split_distances("bevy", 0.1, 5.0)
    with pytest.raises(ValueError, match=r"overlap must be in \[0, 0.99\]"):
        partitioning.partitions("bevy", 0.1, 150.0, overlap=1.0)


def test_padding_and_overlaps():
    lo, hi = partitioning.partitions("ogre-pssm", 1.0, 1000.0)
    e = partitioning.split_distances("ogre-pssm", 1.0, 1000.0)
    np.testing.assert_allclose(lo, [e[0], e[1] - 1, e[2] - 1])
    np.testing.assert_allclose(hi, [e[1] + 1, e[2] + 1, e[3]])
    lo, hi = partitioning.partitions("bgfx", 1.0, 550.0)
    np.testing.assert_allclose(hi[:-1], 1.005 * lo[1:])
    lo, hi = partitioning.partitions("unreal", 1.0, 14.0)
    np.testing.assert_allclose(hi, [2.1, 5.3, 14.0])
    # an overlapping preset evaluates every map over its real extent
    r = schemes.evaluate("Standard", 1.0, 550.0, 60.0, "overhead", edges=partitioning.partitions("bgfx", 1.0, 550.0))
    assert r.maps == 4 and np.isfinite(r.S).all()


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: partitioning.split_distances("babylon", 1.0, 10.0, 5), "at most 4"),
        (lambda: partitioning.split_distances("godot", 1.0, 10.0, 3), "1, 2 or 4"),
        (lambda: partitioning.split_distances("log", 1.0, 10.0), "needs k"),
        (lambda: partitioning.partitions("ogre-pssm", 1.0, 10.0, padding=-1.0), r"padding must be in \[0, inf\]"),
    ],
)
def test_preset_bad_input(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_splits_list_shows_every_method(capsys):
    assert main(["splits", "--list"]) == 0
    out = capsys.readouterr().out
    listed = [line.split()[0] for line in out.splitlines() if not line.startswith(" ")]
    assert listed == list(partitioning.SPLIT_METHODS)
    for m in partitioning.SPLIT_METHODS.values():  # each engine preset's release on the line below it
        if m.release:
            assert f"release: {m.release}" in out, m.name
    assert "threejs-csm@r185, threejs-csm@r186, threejs-csm@r187" in out


def test_pow2_allocation_is_zhang_2006_section_3_5():
    # PSSM(3) with k = 10: 512², 256², 128² texels (Zhang 2006 §3.5, Fig. 3 caption)
    budget = 512**2 + 256**2 + 128**2
    rs, rt = budgets.allocate("pow2", np.ones((1, 3)), np.ones((1, 3)), budget)
    np.testing.assert_allclose(rs[0], [512, 256, 128], rtol=1e-12)
    np.testing.assert_array_equal(rs, rt)


def test_E6_eqs_22_23_hold_as_proportionalities():
    # Lloyd 2006 eqs. 22–23 for large f/n: S_ZP,overhead ≈ j (f/n)^(2/j) and S_FP+ZP+W,overhead ≈ j (f/n)^(4/j),
    # each up to a constant: 1/(2 tanθ), and (1/4)/(2 tanθ) with one z-partitioning per four maps (ERRATA E6)
    a, j = sp.Symbol("a", positive=True), sp.Symbol("j", positive=True)
    zp = L.storage_zp_overhead().subs({L.f: a * L.n, L.k: j})
    fp = L.storage_zp_w_overhead().subs({L.f: a * L.n, L.k: j / 4})
    for value in (3, 8):
        assert sp.limit((zp / (j * a ** (2 / j))).subs(j, value), a, sp.oo) == 1 / (2 * sp.tan(L.theta))
        assert sp.limit((fp / (j * a ** (4 / j))).subs(j, 4 * value), a, sp.oo) == sp.Rational(1, 4) / (2 * sp.tan(L.theta))


def test_engines_page_commands_print_what_the_page_shows(capsys):
    # docs/guide/engines.rst: every "$ aliasing …" console example prints the output shown under it
    import re
    import shlex
    from pathlib import Path

    page = (Path(__file__).resolve().parents[1] / "docs" / "guide" / "engines.rst").read_text()
    blocks = re.findall(r"\.\. code-block:: console\n\n((?:   .*\n|\n)+)", page)
    assert len(blocks) == 3
    for block in blocks:
        lines = [line[3:] for line in block.rstrip("\n").splitlines()]
        command, rest = lines[0], lines[1:]
        while command.endswith("\\"):
            command = command[:-1] + rest.pop(0).strip()
        assert len(rest) >= 4, command  # the output table follows the command
        args = shlex.split(command.removeprefix("$ "))
        assert args[0] == "aliasing"
        assert main(args[1:]) == 0
        got = [line.rstrip() for line in capsys.readouterr().out.splitlines()]
        assert got == [line.rstrip() for line in rest], command
