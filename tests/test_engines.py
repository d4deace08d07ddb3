"""Engine schemes (issue 18): stable fits, VSM clipmaps, limits, SDSM, the comparison and CLI."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import sympy as sp

from aliasing import cli, directional, geometry, partitioning, schemes
from aliasing.engines import compare, limits, sdsm, stable, vsm
from aliasing.symbolic import engines as sym

# --- closed forms (aliasing.symbolic.engines) against the numeric code -------------------


def test_sphere_centre_is_equidistant_from_both_corner_rings():
    zc = sym.sphere_centre()
    near_sq = (zc - sym.a) ** 2 + 2 * sym.t**2 * sym.a**2
    far_sq = (zc - sym.b) ** 2 + 2 * sym.t**2 * sym.b**2
    assert sp.simplify(near_sq - far_sq) == 0
    assert sp.simplify(zc - (sym.a + sym.b) * (1 + 2 * sym.t**2) / 2) == 0


@pytest.mark.parametrize("a,b,fov", [(1.0, 100.0, 10.0), (5.0, 6.0, 30.0), (1.0, 3.0, 90.0), (10.0, 50.0, 60.0), (0.5, 0.6, 120.0)])
def test_sphere_radius_matches_sympy_and_encloses_the_slice(a, b, fov):
    t = np.tan(np.radians(fov) / 2)
    r = float(stable.sphere_radius(a, b, fov))
    zc = (a + b) * (1 + 2 * t**2) / 2
    if zc < b:
        expect = float(sym.sphere_radius().subs({sym.a: a, sym.b: b, sym.t: t}))
    else:  # the far ring alone decides
        expect, zc = np.sqrt(2) * t * b, b
    assert r == pytest.approx(expect, rel=1e-12)
    corners = geometry.frustum_vertices(a, b, fov)
    dist = np.linalg.norm(corners - [0, 0, zc], axis=-1)
    assert dist.max() == pytest.approx(r, rel=1e-12)  # every corner inside, the farthest on it: minimal


def test_diagonal_square_covers_every_light_direction_and_is_at_most_the_sphere():
    a, b, fov = 3.0, 40.0, 60.0
    lf = directional.fit(geometry.frustum_vertices(a, b, fov), geometry.lights("sphere:400"))
    d = float(stable.diagonal(a, b, fov))
    assert np.ptp(lf.x, axis=-1).max() <= d * (1 + 1e-12)
    assert lf.depth.max() <= d * (1 + 1e-12)
    assert np.ptp(lf.x, axis=-1).max() > 0.95 * d  # and the bound is nearly reached
    assert d <= 2 * float(stable.sphere_radius(a, b, fov)) * (1 + 1e-12)


def test_vsm_axis_error_closed_form_and_sawtooth():
    expr = sym.vsm_m_axis()
    assert sp.simplify(expr - 2 ** (1 + sym.bias - sym.phi)) == 0
    for fov, width, bias in [(90.0, 1920, 0.0), (60.0, 1280, -1.5), (40.0, 3840, -0.5), (100.0, 800, 1.0)]:
        c = vsm.Clipmap(fov=fov, width=width, bias=bias, first=-40, last=40)  # no clamps in range
        d = np.geomspace(30.0, 3e6, 5001)
        m = vsm.m_axis(c, d)
        phi = np.log2(d) + c.lod_bias - np.floor(np.log2(d) + c.lod_bias)
        # the engine clamps B′ at 0: the effective bias is then larger than the cvar's
        b_eff = c.lod_bias - np.log2(0.5 * np.tan(np.radians(fov) / 2) * 16384 / width)
        assert b_eff == pytest.approx(bias) if bias + np.log2(0.5 * np.tan(np.radians(fov) / 2) * 16384 / width) >= 0 else b_eff > bias
        np.testing.assert_allclose(m, 2.0 ** (1 + b_eff - phi), rtol=1e-9)
        assert m.min() > 2.0**b_eff and m.max() <= 2.0 ** (1 + b_eff) * (1 + 1e-12)
        lo, hi = vsm.m_axis_range(c, 30.0, 3e6)
        assert lo == pytest.approx(2.0**b_eff, rel=1e-9) and hi == pytest.approx(2.0 ** (1 + b_eff), rel=1e-9)


def test_vsm_levels_and_texels_follow_the_engine_constants():
    c = vsm.Clipmap(fov=90.0, width=2048, bias=0.0)  # LodScale = 0.5·1·16384/2048 = 4: B′ = 2
    assert c.lod_bias == pytest.approx(2.0)
    assert vsm.level(c, [1.0, 16.0, 1000.0, 2.0**21]).tolist() == [6.0, 6.0, 11.0, 22.0]
    assert np.isnan(vsm.level(c, [2.0**23 + 1])[0])  # beyond the last level's radius 2^23
    assert float(vsm.texel(c, 11)) == 1.0  # 2^(11+3)/16384 cm
    m = vsm.Clipmap(fov=90.0, width=2048, bias=0.0, unit="m")
    assert float(vsm.texel(m, 11)) == pytest.approx(0.01)
    assert vsm.level(m, [10.0])[0] == vsm.level(c, [1000.0])[0]
    clamped = vsm.Clipmap(fov=10.0, width=8192, bias=-1.0)  # bias + log2(LodScale) < 0: clamped to 0
    assert clamped.lod_bias == 0.0


def test_vsm_frustum_max_is_the_corner_factor_times_the_axis_sup():
    c = vsm.Clipmap(fov=60.0, width=1920, bias=-1.0, first=-40, last=40)
    k = np.sqrt(1 + 2 * np.tan(np.radians(30.0)) ** 2)
    assert vsm.frustum_max(c, 100.0, 1e5) == pytest.approx(2.0 ** (1 - 1.0) * k, rel=1e-9)


def test_vsm_pages_bound_and_pool():
    c = vsm.Clipmap(fov=60.0, width=1920, bias=0.0)
    p = vsm.pages(c, 10.0, 1e5, "hemisphere:20")
    assert p.shape == (20,) and (p > 0).all()
    finer = vsm.pages(vsm.Clipmap(fov=60.0, width=1920, bias=-1.0), 10.0, 1e5, "hemisphere:20")
    assert (finer >= p).all() and finer.sum() > 2 * p.sum()  # one octave finer: about 4x the texels per level
    small = vsm.pool_check(c, 10.0, 1e5, "overhead", 128)
    assert small["overflow"] and small["extra_bias"] > 0
    relieved = vsm.Clipmap(fov=60.0, width=1920, bias=small["extra_bias"])
    assert vsm.pages(relieved, 10.0, 1e5, "overhead").max() <= 0.85 * 128
    assert vsm.pool_check(c, 10.0, 1e5, "overhead", 32)["extra_bias"] == float("inf")  # 16 coarse pages + 1 per level > 27
    assert not vsm.pool_check(c, 10.0, 1e5, "overhead", 10**7)["overflow"]


# --- stable fits ---------------------------------------------------------------------------


def test_tight_fit_equals_the_papers_standard_zp():
    edges = partitioning.split_distances("practical", 1.0, 1000.0, 4)
    r = stable.evaluate(edges, 1.0, 1000.0, 60.0, "hemisphere:64")
    s = schemes.evaluate("Standard", 1.0, 1000.0, 60.0, "hemisphere:64", edges=edges)
    np.testing.assert_allclose(r.M_x, s.M_x, rtol=1e-12)
    np.testing.assert_allclose(r.M_z, s.M_z, rtol=1e-12)
    np.testing.assert_allclose(r.S, s.S, rtol=1e-12)


def test_stable_fits_cost_more_than_tight_and_do_not_depend_on_the_light():
    lights = geometry.lights("hemisphere:100")
    for fit in ("sphere", "diagonal"):
        r = stable.evaluate("filament", 0.5, 500.0, 60.0, lights, fit=fit)
        assert np.ptp(r.S) == 0.0  # rotation-invariant size
        c = stable.cost("filament", 0.5, 500.0, 60.0, lights, fit=fit)
        assert c["S_ratio_min"] >= 1.0 and c["M_ratio_min"] >= 1.0
    pad = stable.evaluate("log", 1.0, 100.0, 60.0, "overhead", k=3, fit="sphere", snap="pad", resolution=1024)
    plain = stable.evaluate("log", 1.0, 100.0, 60.0, "overhead", k=3, fit="sphere")
    np.testing.assert_allclose(pad.M_x / plain.M_x, 1024 / 1023)


def test_fit_to_scene_and_overlap_ranges():
    (a, b), (u, v) = stable.cascade_ranges("log", 1.0, 1000.0, 3, scene=True)
    assert a.tolist() == [1.0, 1.0, 1.0] and u.tolist() == pytest.approx([1.0, 10.0, 100.0])
    (a, b), _ = stable.cascade_ranges("log", 1.0, 1000.0, 3, overlap=0.2)
    assert a.tolist() == pytest.approx([1.0, 8.0, 80.0])
    (a, b), (u, v) = stable.cascade_ranges("bgfx", 1.0, 1000.0)
    assert (b[:-1] > v[:-1]).all()  # the engine's overlap: each map fitted past its split
    tight = stable.evaluate("log", 1.0, 1000.0, 60.0, "overhead", k=3)
    scene = stable.evaluate("log", 1.0, 1000.0, 60.0, "overhead", k=3, scene=True)
    assert (scene.S >= tight.S).all()


# --- limits, SDSM --------------------------------------------------------------------------


def test_matched_texels_per_pixel():
    assert sp.simplify(sym.matched_texels() - 3 / sp.log(4)) == 0
    assert limits.MATCHED_TEXELS_PER_PIXEL == pytest.approx(float(3 / sp.log(4)), rel=1e-15)
    phi = np.linspace(0, 1, 200001)
    assert np.mean(4.0**phi) == pytest.approx(limits.MATCHED_TEXELS_PER_PIXEL, rel=1e-4)


def test_sdsm_narrower_occupied_range_costs_less():
    full = stable.evaluate(sdsm.log_partitions(1.0, 1000.0, 1.0, 1000.0, 4), 1.0, 1000.0, 60.0, "hemisphere:50")
    occ = stable.evaluate(sdsm.log_partitions(1.0, 1000.0, 5.0, 200.0, 4), 5.0, 200.0, 60.0, "hemisphere:50")
    assert (occ.S < full.S).all()


@pytest.mark.parametrize(
    "call, word",
    [
        (lambda: sdsm.log_partitions(1.0, 100.0, 0.5, 50.0, 2), "z_min"),
        (lambda: sdsm.log_partitions(1.0, 100.0, 50.0, 50.0, 2), "occupied"),
        (lambda: sdsm.log_partitions(1.0, 100.0, 2.0, 50.0, 0), "k"),
        (lambda: vsm.Clipmap(bias=-9.0), "bias"),
        (lambda: vsm.Clipmap(first=10, last=8), "first"),
        (lambda: vsm.pool_check(vsm.Clipmap(), 10.0, 100.0, "overhead", 0), "pool"),
        (lambda: stable.evaluate("log", 1.0, 10.0, 60.0, k=2, fit="cube"), "fit"),
        (lambda: compare.compare(["nope"]), "family"),
        (lambda: compare.compare(["vsm:ultra"]), "preset"),
    ],
)
def test_bad_input_names_the_parameter(call, word):
    with pytest.raises(ValueError, match=word):
        call()


# --- comparison and CLI --------------------------------------------------------------------


def test_compare_rows_and_ratios():
    rows = compare.compare(["csm:threejs-csm", "csm-stable:filament", "csm-stable:bevy", "sdsm:k=4", "vsm:high", "vsm:epic", "vsm:bias=-0.5", "matched", "exact"], near=10.0, far=1e5, lights="hemisphere:30")
    by = {r["scheme"]: r for r in rows}
    assert by["matched"]["storage_ratio"] == 1.0 and by["exact"]["storage_ratio"] == pytest.approx(1 / limits.MATCHED_TEXELS_PER_PIXEL)
    assert by["csm-stable:filament"]["max_error"] == pytest.approx(by["csm-stable:filament"]["median_error"])  # stable: no light dependence
    tight = compare.compare(["csm:filament"], near=10.0, far=1e5, lights="hemisphere:30")[0]
    assert by["csm-stable:filament"]["max_error"] >= tight["max_error"] and by["csm-stable:filament"]["S_bar"] >= tight["S_bar"]
    log_scale = np.log2(0.5 * np.tan(np.radians(30.0)) * 16384 / 1920)  # 1.30: Epic's −1.5 is clamped to B′ = 0 (−1.30)
    assert by["vsm:epic"]["m_axis_min"] == pytest.approx(2.0 ** -log_scale, rel=1e-9)
    assert by["vsm:high"]["m_axis_min"] == pytest.approx(1.0, rel=1e-9)
    assert by["vsm:epic"]["pages"] > by["vsm:high"]["pages"]
    for r in rows:
        assert set(r) == set(compare.FIELDS)
        assert r["max_error"] >= r["median_error"] > 0 and r["m_axis_max"] >= r["m_axis_min"] > 0


def test_cli_engines_json_and_errors(capsys):
    assert cli.main(["engines", "--schemes", "csm:log:k=4,vsm:epic,matched", "--light", "overhead,gamma:45", "--format", "json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert [r["scheme"] for r in rows] == ["csm:log:k=4", "vsm:epic", "matched"]
    assert cli.main(["engines", "--schemes", "vsm:bias=0:first=9:last=3"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "first" in err
    assert cli.main(["engines", "--list"]) == 0
    assert "vsm:PRESET" in capsys.readouterr().out


def test_dxsdk_body_diagonal_square_misses_corners_at_wide_fov():
    # DirectX SDK FIT_TO_SCENE pads to the body diagonal only: below the far-face diagonal at fov 60
    assert float(stable.body_diagonal(10.0, 1e4, 60.0)) < float(stable.diagonal(10.0, 1e4, 60.0))
    assert stable.coverage("log", 10.0, 1e5, 60.0, "hemisphere:200", k=4, fit="body", scene=True) < 0.5
    assert stable.coverage("log", 10.0, 1e5, 30.0, "hemisphere:200", k=4, fit="body", scene=True) == 1.0
    for fit in ("diagonal", "sphere"):
        assert stable.coverage("log", 10.0, 1e5, 90.0, "hemisphere:200", k=4, fit=fit, scene=True) == 1.0
    rows = compare.compare(["csm-stable:dxsdk-scene", "csm-stable:bevy"], lights="hemisphere:100")
    assert rows[0]["coverage"] < 0.5 and rows[1]["coverage"] == 1.0


def test_sdsm_histogram_partitions():
    e = np.geomspace(1.0, 1024.0, 11)
    counts = [0, 0, 5, 5, 0, 0, 0, 0, 5, 5]
    lo, hi = sdsm.adaptive_log(e, counts, 2)
    assert lo.tolist() == [4.0, 256.0] and hi.tolist() == [16.0, 1024.0]  # the empty octaves get no map
    lo, hi = sdsm.kmeans(e, counts, 2)
    assert lo.tolist() == [4.0, 256.0] and hi.tolist() == [16.0, 1024.0]
    one = sdsm.adaptive_log(e, counts, 1)
    assert one[0].tolist() == [4.0] and one[1].tolist() == [1024.0]
    gaps = stable.evaluate((lo, hi), 1.0, 1024.0, 60.0, "hemisphere:20")
    whole = stable.evaluate(sdsm.log_partitions(1.0, 1024.0, 4.0, 1024.0, 2), 4.0, 1024.0, 60.0, "hemisphere:20")
    assert (gaps.S < whole.S).all()  # fitting the populated ranges only costs less
    with pytest.raises(ValueError, match="no samples"):
        sdsm.kmeans(e, np.zeros(10), 2)
    with pytest.raises(ValueError, match="k"):
        sdsm.adaptive_log(e, counts, 0)


def test_figure_data_shows_the_documented_ranges():
    from aliasing.figures import engines_comparison as fig

    cols = fig.data(samples=400, gammas=7)
    assert ((cols["m_matched"] > 0.5) & (cols["m_matched"] <= 1.0)).all()
    far = cols["d"] > 100.0  # beyond the first level's clamp (level 6 reaches 2^(6 − B′) cm)
    assert cols["m_vsm_high"][far].max() <= 2.0 + 1e-9 and cols["m_vsm_high"][far].min() > 1.0
    assert np.ptp(cols["S_csm_stable_filament"]) == 0.0 and (cols["S_csm_stable_filament"] >= cols["S_csm_filament"]).all()


def test_ground_area_against_monte_carlo():
    rng = np.random.default_rng(7)
    h, fov, R = 170.0, 60.0, 3000.0
    t = np.tan(np.radians(30.0))
    x, z = rng.uniform(-R, R, 400_000), rng.uniform(0, R, 400_000)
    seen = (np.abs(x) <= z * t) & (h <= z * t)
    for r in (320.0, 340.0, 1000.0, 3000.0):  # segment branch (z0 = 294 < r <= 340), wedge beyond
        mc = (seen & (np.hypot(x, z) <= r)).mean() * 2 * R * R
        assert float(vsm.ground_area(r, h, fov)) == pytest.approx(mc, rel=0.05, abs=2000.0)


def test_ground_pages_against_a_page_count():
    """Second method: enumerate the light-space pages that sampled ground points fall in."""
    c = vsm.Clipmap(fov=60.0, width=1920, bias=0.0)
    h, far = 170.0, 2e4
    for light in ("overhead", "gamma:60@azimuth:30"):
        lv = geometry.lights(light)[0]
        basis = geometry.light_space(lv[None])[0]
        estimate = float(vsm.ground_pages(c, h, far, light)[0])
        pages = set()
        t = np.tan(np.radians(30.0))
        for L in range(c.first, c.last + 1):
            p = vsm.PAGE * float(vsm.texel(c, L))
            d_hi = min(2.0 ** (L + 1 - c.lod_bias), far)  # the level's ring only: a few thousand points
            if d_hi < np.hypot(h, h / t):
                continue
            xs = np.arange(-d_hi, d_hi, p / 3)
            zs = np.arange(h / t, d_hi, p / 3)
            X, Z = np.meshgrid(xs, zs)
            d = np.sqrt(X**2 + Z**2 + h**2)
            keep = (np.abs(X) <= Z * t) & (d <= far) & (vsm.level(c, d) == L)
            if not keep.any():
                continue
            pts = np.stack([X[keep], np.full(keep.sum(), -h), Z[keep]], axis=-1)
            u, v = pts @ basis[0], pts @ basis[2]
            pages |= set(zip([L] * len(u), np.floor(u / p).astype(int), np.floor(v / p).astype(int)))
        assert estimate <= len(pages) <= 1.6 * estimate  # the area's worth, plus partial border pages


def test_ground_plane_pages_in_the_comparison():
    rows = compare.compare(["vsm:low", "vsm:epic"], lights="overhead", ground=170.0)
    low, epic = rows
    assert low["overflow"] and low["extra_bias"] > 0  # 512 pages: the ground to 1 km needs about 540
    assert not epic["overflow"] and epic["pages"] > 4 * low["pages"]  # −1.30 octaves: 2^(2·1.30) ≈ 6x the pages
    assert epic["pages"] == pytest.approx(float(vsm.ground_pages(vsm.Clipmap(60.0, 1920, -1.5), 170.0, 1e5, "overhead")[0]))
    relieved = vsm.ground_pages(vsm.Clipmap(60.0, 1920, low["extra_bias"]), 170.0, 1e5, "overhead")[0]
    assert relieved <= 0.85 * 512


def test_slice_extent_closed_form_matches_the_vertex_fit():
    a, b = np.array([1.0, 10.0, 100.0]), np.array([10.0, 100.0, 1000.0])
    lv = geometry.lights("sphere:300")
    lf = directional.fit(geometry.frustum_vertices(a, b, 70.0), lv)
    basis = geometry.light_space(lv)
    t = np.tan(np.radians(35.0))
    np.testing.assert_allclose(vsm.slice_extent(a, b, t, basis[:, 0]), np.ptp(lf.x, axis=-1), rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(vsm.slice_extent(a, b, t, basis[:, 2]), lf.depth, rtol=1e-12, atol=1e-9)


def test_bevy_bounds_follow_the_source_defaults():
    # CascadeShadowConfigBuilder::default: 4 cascades, minimum 0.1, maximum 1000, first bound 5
    e = stable.bevy_bounds(0.1, 1000.0)
    assert e[:2].tolist() == [0.1, 5.0] and e[-1] == 1000.0
    np.testing.assert_allclose(np.diff(np.log(e[1:])), np.log(200.0) / 3)
    with pytest.raises(ValueError, match="first"):
        stable.bevy_bounds(10.0, 1000.0, 4, 5.0)


def test_godot_centroid_sphere_contains_the_minimal_sphere():
    for a, b, fov in [(1.0, 100.0, 10.0), (5.0, 6.0, 30.0), (1.0, 3.0, 90.0), (10.0, 50.0, 60.0)]:
        r = float(stable.centroid_radius(a, b, fov))
        corners = geometry.frustum_vertices(a, b, fov)
        assert np.linalg.norm(corners - corners.mean(axis=0), axis=-1).max() == pytest.approx(r, rel=1e-12)
        assert r >= float(stable.sphere_radius(a, b, fov)) * (1 - 1e-12)
    g = stable.evaluate("godot", 10.0, 1e4, 60.0, "overhead", fit="centroid", snap="godot", resolution=4096)
    c = stable.evaluate("godot", 10.0, 1e4, 60.0, "overhead", fit="centroid")
    np.testing.assert_allclose(g.M_x / c.M_x, 4096 / 4094)
    assert compare.compare(["csm-stable:godot"], lights="overhead")[0]["coverage"] == 1.0


@pytest.mark.parametrize("light, bias, unit, near, far", [("overhead", 0.0, "cm", 100.0, 1e4), ("gamma:150@azimuth:40", -1.0, "cm", 100.0, 1e4), ("gamma:60", -0.5, "m", 1.0, 100.0)])
def test_vsm_levels_in_the_rasterizer_reach_the_bound(light, bias, unit, near, far):
    from aliasing.engines.validate import validate_vsm

    r = validate_vsm(near, far, 60.0, light, bias=bias, resolution=256, cells=16, unit=unit)
    assert r["levels"] >= 6 and r["pixels"] > 1000
    assert 0.9 <= r["ratio"] <= 1.0 + r["tolerance"]  # measured max within the analytic bound and reaching it


@pytest.mark.parametrize("fit", ["tight", "sphere", "diagonal", "centroid"])
def test_stable_fits_in_the_rasterizer(fit):
    from aliasing.engines.validate import validate_stable

    r = validate_stable("log", 10.0, 1e5, 60.0, "gamma:150@azimuth:40", k=4, fit=fit, resolution=256, cells=16)
    assert all(0.9 <= x <= 1 + r["tolerance"] for x in r["ratio_x"] + r["ratio_z"])
    assert r["inside"] == [1.0] * 4  # every pixel of a cascade falls inside its map


def test_dxsdk_body_fit_misses_pixels_in_the_rasterizer():
    from aliasing.engines.validate import validate_stable

    r = validate_stable("log", 10.0, 1e5, 60.0, "gamma:20@azimuth:45", k=4, fit="body", scene=True, resolution=256, cells=16)
    assert min(r["inside"]) < 0.95  # pixels outside the map: the shadow is lost there
    assert stable.coverage("log", 10.0, 1e5, 60.0, "gamma:20@azimuth:45", k=4, fit="body", scene=True) == 0.0


def test_sdsm_from_the_rasterizer_eye_pass_and_its_partitions_in_the_rasterizer():
    from aliasing import raster
    from aliasing.engines.validate import eye_histogram, validate_stable

    sc = raster.ground_and_boxes(near=1.0, far=1000.0, boxes=30, seed=3)
    e, c = eye_histogram(sc.triangles, 1.0, 1000.0, 60.0, resolution=96, bins=48)
    filled = np.nonzero(c)[0]
    for method in (sdsm.adaptive_log, sdsm.kmeans):
        lo, hi = method(e, c, 4)
        assert lo[0] == e[filled[0]] and hi[-1] == e[filled[-1] + 1]  # the occupied range, not [near, far]
        assert (hi > lo).all() and (np.diff(lo) > 0).all()
    lo, hi = sdsm.adaptive_log(e, c, 3)
    full = stable.evaluate(sdsm.log_partitions(1.0, 1000.0, 1.0, 1000.0, 3), 1.0, 1000.0, 60.0, "gamma:60")
    fitted = stable.evaluate((lo, hi), 1.0, 1000.0, 60.0, "gamma:60")
    assert fitted.S[0] <= full.S[0]
    occupied = sdsm.log_partitions(1.0, 1000.0, 5.0, 400.0, 3)
    r = validate_stable(occupied, 5.0, 400.0, 60.0, "gamma:60", fit="tight", resolution=192, cells=12)
    assert all(0.9 <= x <= 1 + r["tolerance"] for x in r["ratio_x"] + r["ratio_z"]) and r["inside"] == [1.0] * 3


def test_cli_sdsm_histogram(tmp_path, capsys):
    e = np.geomspace(10.0, 1e5, 9)
    path = tmp_path / "h.csv"
    path.write_text("z_lo,z_hi,count\n" + "".join(f"{a},{b},{c}\n" for a, b, c in zip(e[:-1], e[1:], [0, 4, 9, 0, 0, 3, 1, 0])))
    assert cli.main(["engines", "--schemes", "sdsm:method=adaptive:k=2,sdsm:method=kmeans:k=3", "--histogram", str(path), "--light", "overhead", "--format", "json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert [r["scheme"] for r in rows] == ["sdsm:method=adaptive:k=2", "sdsm:method=kmeans:k=3"] and all(r["max_error"] > 0 for r in rows)
    empty = tmp_path / "empty.csv"
    empty.write_text("z_lo,z_hi,count\n10,100,0\n100,1000,0\n")
    assert cli.main(["engines", "--schemes", "sdsm:method=kmeans", "--histogram", str(empty)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "no samples" in err
    assert cli.main(["engines", "--schemes", "sdsm:method=kmeans"]) == 2
    assert "histogram" in capsys.readouterr().err


def test_derive_lists_the_engine_closed_forms(capsys):
    assert cli.main(["derive", "engines.vsm_m_axis", "engines.matched_texels"]) == 0
    out = capsys.readouterr().out
    assert "2**(bias - phi + 1)" in out and "log(2)" in out


def test_scene_pages_of_a_ground_quad_against_the_closed_form():
    from aliasing.engines.validate import scene_pages

    h, far = 170.0, 1e5
    quad = np.array([[[-far, -h, 1.0], [far, -h, 1.0], [far, -h, far]], [[-far, -h, 1.0], [far, -h, far], [-far, -h, far]]])
    engine, bare = vsm.Clipmap(60.0, 512, -2.0), vsm.Clipmap(60.0, 512, -2.0, dilation=0.0, coarse=None)
    for c, light, measured in ((engine, "overhead", 0.887), (engine, "gamma:60@azimuth:30", 1.046), (bare, "overhead", 0.861), (bare, "gamma:60@azimuth:30", 0.995)):  # the docstring's ratios
        ratio = scene_pages(quad, c, light, resolution=512) / float(vsm.ground_pages(c, h, far, light)[0])
        assert ratio == pytest.approx(measured, abs=0.005)
    for light in ("overhead", "gamma:60@azimuth:30"):  # dilation and coarse pages only add pages
        assert scene_pages(quad, bare, light, resolution=256) + 16 <= scene_pages(quad, engine, light, resolution=256)


def test_sdsm_occupancy_overhead_closed_form():
    n, f, k, t = 10.0, 1e5, 4, np.tan(np.radians(30.0))
    rows = sdsm.occupancy(n, f, 60.0, "overhead", k, [0.5, 0.1, 0.01])
    for row in rows:
        rho = ((n + row["q"] * (f - n)) / n) ** (1 / k)
        assert row["S"] == pytest.approx(k * rho * (rho - 1) / (2 * t), rel=1e-9)
        assert row["M"] == pytest.approx(max(rho, (rho - 1) / (2 * t)), rel=1e-9)
    far_rows = sdsm.occupancy(n, f, 60.0, "hemisphere:50", k, [0.5, 0.1], anchor="far")
    assert all(r["S_ratio"] < 0.05 for r in far_rows)  # nothing near the eye: the first partition no longer starts at near
    with pytest.raises(ValueError, match="fractions"):
        sdsm.occupancy(n, f, 60.0, "overhead", k, [0.0])


# --- second pass: engine stable presets read from source (Filament, Babylon.js) -----------


def test_filament_stable_preset_is_the_corner_centroid_sphere_with_a_texel_border():
    # ShadowMap.cpp computeBoundingSphere: centre = mean of the 8 slice corners, radius = max distance
    near, far, fov, res = 10.0, 1e5, 60.0, 2048
    (a, b), _ = stable.cascade_ranges("filament", near, far, 4)
    for ai, bi in zip(a, b):
        corners = geometry.frustum_vertices(ai, bi, fov)
        r = np.linalg.norm(corners - corners.mean(axis=0), axis=-1).max()
        assert float(stable.centroid_radius(ai, bi, fov)) == pytest.approx(r, rel=1e-12)
    p = stable.PRESETS["filament"]
    assert (p.split, p.fit, p.snap, p.overlap, p.scene) == ("filament", "centroid", "border", 0.0, False)
    got = stable.evaluate("filament", near, far, fov, "hemisphere:30", k=4, fit="centroid", snap="border", resolution=res)
    bare = stable.evaluate("filament", near, far, fov, "hemisphere:30", k=4, fit="centroid")
    np.testing.assert_allclose(got.M_x / bare.M_x, res / (res - 2))  # shadowDimension = mapSize − 2
    np.testing.assert_allclose(got.width_x, np.broadcast_to(2 * stable.centroid_radius(a, b, fov) * res / (res - 2), got.width_x.shape))
    row = compare.compare(["csm-stable:filament"], near=near, far=far, fov=fov, lights="hemisphere:30", shadow_res=res)[0]
    assert row["coverage"] == 1.0
    assert row["max_error"] == pytest.approx(float(np.maximum(got.M_x, got.M_z).max()) * 1920 / res, rel=1e-12)


def test_filament_shadowfar_sphere_misses_the_far_corners():
    # shadowFar > 0: every cascade gets the sphere {camera, shadowFar}; the far corners lie at far·√(1 + 2t²)
    near, far, fov = 10.0, 1e5, 60.0
    r = stable.evaluate("filament", near, far, fov, "overhead", k=4, fit="far")
    np.testing.assert_allclose(r.width_x, 2 * far)  # all cascades alike: the first is as coarse as the last
    assert stable.coverage("filament", near, far, fov, "overhead", k=4, fit="far") == 1.0  # overhead: |x|, |z| <= far
    assert stable.coverage("filament", near, far, fov, "hemisphere:200", k=4, fit="far") < 0.5
    # x along (1, 0, −1)/√2 reaches (t + 1)·far/√2 > far at the corner (−t far, ·, far)
    assert (np.tan(np.radians(30.0)) + 1) / np.sqrt(2) > 1.0


def test_babylon_stable_preset_rounds_the_centroid_radius_to_sixteenths():
    near, far, fov = 1.0, 100.0, 60.0
    p = stable.PRESETS["babylon"]
    assert (p.split, p.fit, p.snap) == ("babylon", "centroid16", "origin")
    (a, b), _ = stable.cascade_ranges("babylon", near, far, 4)
    r = stable.centroid_radius(a, b, fov)
    got = stable.evaluate("babylon", near, far, fov, "gamma:60", k=4, fit="centroid16", snap="origin")
    side = got.width_x[0]
    np.testing.assert_allclose(side * 8, np.round(side * 8))  # 2·(whole sixteenths)
    assert (side >= 2 * r).all() and (side < 2 * r + 2 / 16).all()
    same = stable.evaluate("babylon", near, far, fov, "gamma:60", k=4, fit="centroid16", snap="none")
    np.testing.assert_array_equal(got.M_x, same.M_x)  # the origin snap keeps the size
    assert compare.compare(["csm-stable:babylon"], near=near, far=far, lights="hemisphere:50")[0]["coverage"] == 1.0


def test_no_unity_stable_preset_is_invented():
    assert not any(name.startswith("unity") for name in stable.PRESETS)  # StableFit is in Unity's closed native code


@pytest.mark.parametrize("fit, snap", [("centroid16", "origin"), ("centroid", "border")])
def test_engine_stable_fits_in_the_rasterizer(fit, snap):
    from aliasing.engines.validate import validate_stable

    r = validate_stable("babylon", 10.0, 1e4, 60.0, "gamma:150@azimuth:40", k=4, fit=fit, snap=snap, resolution=192, cells=12)
    assert all(0.9 <= x <= 1 + r["tolerance"] for x in r["ratio_x"] + r["ratio_z"])
    assert r["inside"] == [1.0] * 4


def test_filament_shadowfar_loses_pixels_in_the_rasterizer():
    from aliasing.engines.validate import validate_stable

    r = validate_stable("filament", 10.0, 1e4, 60.0, "gamma:120@azimuth:45", k=4, fit="far", resolution=128, cells=8)
    assert min(r["inside"]) < 1.0 and max(r["ratio_x"]) <= 1 + r["tolerance"]


# --- second pass: Intel's SDSM sample's border, dilation and power-of-two quantisation ----


def _intel_scale(lo, hi, border, dilation, quantize):
    """ComputePartitionDataFromBounds step by step, in the light's [0, 1] texture space (second method)."""
    lo, hi = lo - border, hi + border
    scale = 1.0 / (hi - lo)
    bias = -lo * scale
    f = 1.0 - 2.0 * dilation
    scale, bias = scale * f, dilation + f * bias
    target = max(1.0, 2.0 ** np.floor(np.log2(scale))) if quantize else scale
    bias = (target / scale) * (bias - 0.5) + 0.5
    return target, bias


@pytest.mark.parametrize("lo, hi, border, dilation, quantize", [(0.1, 0.13, 0.0, 10 / 1024, False), (0.1, 0.13, 0.0, 10 / 1024, True), (0.3, 0.9, 0.02, 0.01, True), (0.0, 0.99, 0.01, 0.01, True), (0.42, 0.4201, 0.0, 0.0, True)])
def test_sdsm_sample_bounds_follow_the_hlsl_steps(lo, hi, border, dilation, quantize):
    L = 250.0  # world units of the light's texture space
    scale, bias = _intel_scale(lo, hi, border, dilation, quantize)
    side = float(sdsm.sample_bounds((hi - lo) * L, L, border=border * L, dilation=dilation, quantize=quantize))
    assert side == pytest.approx(L / scale, rel=1e-12)
    # the samples [lo, hi] land inside [0, 1] of the partition's map unless quantising clamps the scale at 1
    u_lo, u_hi = lo * scale + bias, hi * scale + bias
    if L / side * (hi - lo + 2 * border) / (1 - 2 * dilation) <= 1 + 1e-12:
        assert -1e-12 <= u_lo and u_hi <= 1 + 1e-12
    if quantize:
        exact = float(sdsm.sample_bounds((hi - lo) * L, L, border=border * L, dilation=dilation))
        assert np.log2(L / side) == pytest.approx(round(np.log2(L / side)))  # a power-of-two fraction of L
        assert (exact <= side * (1 + 1e-12) < 2 * exact) or side == pytest.approx(L)  # at most L: scale >= 1


def test_sdsm_sample_bounds_bad_input():
    with pytest.raises(ValueError, match="dilation"):
        sdsm.sample_bounds(1.0, 10.0, dilation=0.5)
    with pytest.raises(ValueError, match="border"):
        sdsm.sample_bounds(1.0, 10.0, border=-1.0)
    assert cli.main(["engines", "--schemes", "sdsm:k=2:dilation=0.7"]) == 2


def test_sdsm_sample_options_in_the_comparison_and_the_rasterizer():
    from aliasing.engines.validate import validate_stable

    base, dil, quant = compare.compare(["sdsm:k=3:zmin=100:zmax=5000", "sdsm:k=3:zmin=100:zmax=5000:dilation=0.01", "sdsm:k=3:zmin=100:zmax=5000:dilation=0.01:quantize=1"], lights="hemisphere:40")
    assert dil["max_error"] == pytest.approx(base["max_error"] / 0.98, rel=1e-12)  # W/(1 − 2δ)
    assert dil["max_error"] <= quant["max_error"] < 2 * dil["max_error"]
    edges = sdsm.log_partitions(10.0, 1e4, 100.0, 5000.0, 3)
    r = validate_stable(edges, 100.0, 5000.0, 60.0, "gamma:60@azimuth:20", fit="tight", dilation=0.01, quantize=True, resolution=192, cells=12)
    assert all(0.9 <= x <= 1 + r["tolerance"] for x in r["ratio_x"] + r["ratio_z"]) and r["inside"] == [1.0] * 3


# --- second pass: VSM page-marking dilation and coarse pages ------------------------------


def test_vsm_coarse_pages_and_dilation_in_the_frustum_bound():
    c = vsm.Clipmap(60.0, 1920, 0.0)
    assert vsm.coarse_pages(c) == 16  # levels 15…18, 4 pages each
    assert vsm.coarse_pages(vsm.Clipmap(60.0, 1920, 0.0, first=17)) == 8 and vsm.coarse_pages(vsm.Clipmap(last=14)) == 0
    bare = vsm.Clipmap(60.0, 1920, 0.0, dilation=0.0, coarse=None)
    only_coarse = vsm.Clipmap(60.0, 1920, 0.0, dilation=0.0)
    lights = "hemisphere:30"
    np.testing.assert_array_equal(vsm.pages(only_coarse, 10.0, 1e5, lights), vsm.pages(bare, 10.0, 1e5, lights) + 16)
    assert (vsm.pages(c, 10.0, 1e5, lights) >= vsm.pages(only_coarse, 10.0, 1e5, lights)).all()
    # the dilated box of extent E pages touches at most ceil(E + 2δ) + 1 pages per axis: check on a slice
    a, b, tan = np.array([100.0]), np.array([200.0]), np.tan(np.radians(30.0))
    basis = geometry.light_space(geometry.lights("overhead"))
    page = vsm.PAGE * float(vsm.texel(c, 8))
    ext = vsm.slice_extent(a, b, tan, basis[:, 0])[0, 0] / page
    rng = np.random.default_rng(3)
    for shift in rng.uniform(0, 1, 50):  # any placement of the box on the page grid
        lo, hi = shift - 0.05, shift + ext + 0.05
        assert np.floor(hi) - np.floor(lo) + 1 <= np.ceil(ext + 0.1) + 1
    with pytest.raises(ValueError, match="dilation"):
        vsm.Clipmap(dilation=0.7)
    with pytest.raises(ValueError, match="coarse"):
        vsm.Clipmap(coarse=(18, 15))


# --- second pass: the engine schemes on a loaded scene (the procedural city) --------------


@pytest.fixture(scope="module")
def city_setup():
    from aliasing.raster import scenes
    from aliasing.raster.scenes import procedural

    return scenes.setup(procedural.city(2000, seed=1, size=60.0), eye="-40,6,-35", target="0,0,0", near=0.5, far=90.0, light_dir="-1,0.8,0.3")


def _dense_checks(r):
    live = [i for i, p in enumerate(r["pixels"]) if p]
    assert r["passed"] and r["max_ratio"] <= 1 + r["tolerance"]  # within the analytic bound on every map
    assert all(abs(r["reach_x"][i] - 1) <= r["tolerance"] and abs(r["reach_z"][i] - 1) <= r["tolerance"] for i in live)  # reached where sampled
    assert all(1 - r["tolerance"] <= r["pointwise_min"][i] <= r["pointwise_max"][i] <= 1 + r["tolerance"] for i in live)
    assert all(r["inside"][i] == 1.0 for i in live)


@pytest.mark.parametrize("preset", ["filament", "babylon", "godot", "bevy", "dxsdk-scene"])
def test_stable_presets_on_the_city(city_setup, preset):
    from aliasing.engines.scene import cascades_on_scene

    p = stable.PRESETS[preset]
    split = stable.bevy_bounds(0.5, 90.0, 4, 5.0) if p.split == "bevy-bounds" else p.split
    r = cascades_on_scene(city_setup, split, k=None if p.split == "bevy-bounds" else 4, fit=p.fit, snap=p.snap, overlap=p.overlap, scene=p.scene, resolution=1024, res=128)
    _dense_checks(r)


@pytest.mark.parametrize("method, options", [("log", {}), ("adaptive", {}), ("kmeans", {}), ("adaptive", {"dilation": 10 / 1024, "quantize": True}), ("kmeans", {"border": 0.5})])
def test_sdsm_partitions_on_the_city(city_setup, method, options):
    from aliasing.engines.scene import sdsm_on_scene

    r = sdsm_on_scene(city_setup, method, 4, res=128, **options)
    z_min, z_max = r["occupied"]
    assert 0.5 < z_min < z_max < 90.0  # the city occupies part of [near, far]
    assert r["near_i"][0] >= z_min * (1 - 1e-12) and r["far_i"][-1] <= z_max * (1 + 1e-12)
    _dense_checks(r)
    # the first partition starts at the first populated bin's lower edge: its nearest sample is
    # at most one log bin (ratio (far/near)^(1/64)) deeper, so the bound is reached to that factor
    assert min(r["ratio_x"][0], r["ratio_z"][0]) >= (90.0 / 0.5) ** (-1 / 64)


@pytest.mark.parametrize("bias", [0.0, -1.0, -2.0])
def test_vsm_levels_on_the_city(city_setup, bias):
    from aliasing.engines.scene import vsm_on_scene

    r = vsm_on_scene(city_setup, bias=bias, res=128, unit="m")
    assert len(r["levels"]) >= 2 and r["bound"] == pytest.approx(vsm.frustum_max(vsm.Clipmap(60.0, 128, bias, unit="m"), 0.5, 90.0))
    live = range(len(r["levels"]))
    assert r["passed"] and r["max_ratio"] <= 1 + r["tolerance"]
    assert all(abs(r["reach_x"][i] - 1) <= r["tolerance"] for i in live)
    assert all(1 - r["tolerance"] <= r["pointwise_min"][i] <= r["pointwise_max"][i] <= 1 + r["tolerance"] for i in live)



# --- a wide camera on the city: the fits take the camera's aspect, the error is measured through its View


def _city(aspect):
    from aliasing.raster import scenes
    from aliasing.raster.scenes import procedural

    return scenes.setup(procedural.city(2000, seed=1, size=60.0), eye="-40,6,-35", target="0,0,0", near=0.5, far=90.0, light_dir="-1,0.8,0.3", aspect=aspect)


def test_square_camera_on_the_city_is_the_square_path_bit_for_bit(city_setup):
    """aspect 1 given explicitly: every result as without it; and each call that now takes the camera's
    View (the slices' corners, the measured error, SDSM's eye histogram) gives the float-fov numbers."""
    from aliasing import View
    from aliasing.engines import scene
    from aliasing.engines.validate import eye_histogram
    from aliasing.raster.draw import frame_map
    from aliasing.raster.validate.measure import pixel_errors
    from aliasing.raster.validate.scene import measurable_pixels

    one = _city(1.0)
    assert one.camera.view == city_setup.camera.view and one.camera.aspect == 1.0
    for run in (lambda st: scene.cascades_on_scene(st, "bevy", k=4, fit="diagonal", snap="bevy", overlap=0.2, resolution=1024, res=96),
                lambda st: scene.cascades_on_scene(st, "log", k=3, res=96),
                lambda st: scene.sdsm_on_scene(st, "kmeans", 3, res=96),
                lambda st: scene.vsm_on_scene(st, bias=-1.0, res=96, unit="m")):
        plain, given = run(city_setup), run(one)
        assert json.dumps(given) == json.dumps(plain) and "aspect" not in plain
    np.testing.assert_array_equal(geometry.frustum_vertices(View(0.5, 7.5, 60.0, 1.0)), geometry.frustum_vertices(0.5, 7.5, 60.0))
    _, pos, part, ok = measurable_pixels(one, 96, lambda pos, hit: np.zeros(hit.shape, np.int64))
    basis = geometry.light_space(one.light[None])[0]
    lm = frame_map(one.light, basis[2], -40.0, 40.0, np.inf, -40.0, 40.0, "uniform")
    by_view, by_fov = pixel_errors(lm, pos, ok, 96, one.camera.view), pixel_errors(lm, pos, ok, 96, 60.0)
    for key in by_fov:
        np.testing.assert_array_equal(by_view[key], by_fov[key])
    tri = one.scene.triangles
    for a, b in zip(eye_histogram(tri, 0.5, 90.0, one.camera.view, resolution=96), eye_histogram(tri, 0.5, 90.0, 60.0, resolution=96)):
        np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("aspect", [2.0, 16 / 9])
@pytest.mark.parametrize("preset", ["filament", "babylon", "bevy", "dxsdk-scene"])
def test_stable_presets_on_the_city_with_a_wide_camera(preset, aspect):
    """A wide camera: the measured error stays within the analytic bound and reaches it, pointwise the
    uniform map's W/(2 tanθ_y d), every measured pixel inside its map; each cascade's fitted box is at
    least as wide as the square camera's (wider across the view for every fit)."""
    from aliasing.engines.scene import cascades_on_scene

    st = _city(aspect)
    p = stable.PRESETS[preset]
    split = stable.bevy_bounds(0.5, 90.0, 4, 5.0) if p.split == "bevy-bounds" else p.split
    kw = dict(k=None if p.split == "bevy-bounds" else 4, fit=p.fit, snap=p.snap, overlap=p.overlap, scene=p.scene, resolution=1024)
    r = cascades_on_scene(st, split, res=128, **kw)
    assert r["aspect"] == aspect and sum(r["pixels"]) > 500
    _dense_checks(r)
    wide = stable.evaluate(split, 0.5, 90.0, 60.0, st.light[None], aspect=aspect, **kw)
    square = stable.evaluate(split, 0.5, 90.0, 60.0, st.light[None], **kw)
    assert r["near_i"] == wide.used[0].tolist() and r["far_i"] == wide.used[1].tolist()  # the same splits as the square camera's
    assert (wide.width_x >= square.width_x).all() and (wide.width_y >= square.width_y).all()
    assert (wide.width_x > square.width_x).all()


@pytest.mark.parametrize("aspect", [2.0, 16 / 9])
@pytest.mark.parametrize("method", ["log", "adaptive", "kmeans"])
def test_sdsm_partitions_on_the_city_with_a_wide_camera(method, aspect):
    from aliasing.engines.scene import sdsm_on_scene

    r = sdsm_on_scene(_city(aspect), method, 4, res=128)
    assert r["aspect"] == aspect and 0.5 < r["occupied"][0] < r["occupied"][1] < 90.0
    _dense_checks(r)


def test_wide_camera_on_the_city_needs_the_wide_fit(monkeypatch):
    """The control: the same wide camera with the fits of the square view (stable.evaluate at aspect 1)
    leaves pixels of the last tight log cascade outside its map; with the camera's aspect none."""
    from aliasing.engines.scene import cascades_on_scene

    st = _city(2.0)
    good = cascades_on_scene(st, "log", k=4, res=128)
    _dense_checks(good)
    evaluate = stable.evaluate
    monkeypatch.setattr(stable, "evaluate", lambda *a, aspect=1.0, **kw: evaluate(*a, aspect=1.0, **kw))
    bad = cascades_on_scene(st, "log", k=4, res=128)
    assert not bad["passed"] and bad["inside"][-1] < 0.95 and good["inside"][-1] == 1.0


def test_vsm_on_the_city_with_a_wide_camera(city_setup):
    """A 2:1 camera: W = 2·res pixels across, tan θ_x = 2 tan θ_y.  The measured error per level is
    t_L·W/(2 tanθ_x d) pixel by pixel, and the bound is the clipmap's wide supremum
    2^(1+bias)·√(1 + tan²θ_x + tan²θ_y), reached within the level flips the scene has."""
    from aliasing.engines.scene import cascades_on_scene, vsm_on_scene

    st = _city(2.0)
    for bias in (0.0, -1.0):
        r = vsm_on_scene(st, bias=bias, res=96, unit="m")
        t = math.tan(math.radians(30.0))
        assert r["aspect"] == 2.0 and r["passed"] and len(r["levels"]) >= 2
        assert r["bound"] == pytest.approx(vsm.frustum_max(vsm.Clipmap(60.0, 192, bias, unit="m", aspect=2.0), 0.5, 90.0))
        assert r["bound"] == pytest.approx(2.0 ** (1 + bias) * math.sqrt(1 + 5 * t**2), rel=1e-9)
        live = range(len(r["levels"]))
        assert all(1 - r["tolerance"] <= r["pointwise_min"][i] <= r["pointwise_max"][i] <= 1 + r["tolerance"] for i in live)
    assert repr(vsm_on_scene(_city(1.0), bias=-1.0, res=96, unit="m")) == repr(vsm_on_scene(city_setup, bias=-1.0, res=96, unit="m"))  # aspect 1: bit for bit
    with pytest.raises(ValueError, match=r"^aspect is the camera's"):
        cascades_on_scene(st, "log", k=3, res=96, aspect=2.0)

def test_centroid_sphere_and_far_corner_closed_forms():
    r = sym.centroid_radius()
    near_sq = ((sym.b - sym.a) / 2) ** 2 + 2 * sym.t**2 * sym.a**2
    assert sp.expand(r**2 - near_sq - 2 * sym.t**2 * (sym.b**2 - sym.a**2)) == 0  # the far corners are farthest (b > a)
    assert sp.simplify(r**2 - (((sym.b - sym.a) / 2) ** 2 + 2 * sym.t**2 * sym.b**2)) == 0
    for a, b, fov in [(1.0, 3.0, 90.0), (10.0, 50.0, 60.0), (0.5, 0.6, 120.0)]:
        t = np.tan(np.radians(fov) / 2)
        assert float(stable.centroid_radius(a, b, fov)) == pytest.approx(float(r.subs({sym.a: a, sym.b: b, sym.t: t})), rel=1e-12)
    f = sp.Symbol("f", positive=True)
    dist = sym.far_corner_distance()
    assert sp.simplify(dist - f * sp.sqrt(1 + 2 * sym.t**2)) == 0 and sp.simplify(dist**2 - f**2) == 2 * sym.t**2 * f**2


def test_cli_vsm_dilation_and_coarse_options(capsys):
    assert cli.main(["engines", "--schemes", "vsm:high,vsm:high:dilation=0:coarse=0", "--light", "overhead", "--format", "json"]) == 0
    full, bare = json.loads(capsys.readouterr().out)
    assert full["pages"] >= bare["pages"] + 16
    assert cli.main(["engines", "--schemes", "vsm:high:dilation=0.9"]) == 2
    assert "dilation" in capsys.readouterr().err


def test_threejs_stable_preset_is_the_unrounded_longer_diagonal():
    # CSM.js _updateShadowBounds: side = max(|far0 − far2|, |far0 − near2|), not rounded (Bevy rounds it up)
    from aliasing.engines import stable as st

    p = st.PRESETS["threejs"]
    assert (p.split, p.fit, p.snap, p.overlap, p.k) == ("threejs-csm", "diagonal-unrounded", "bevy", 0.0, 3)
    assert st.PRESETS["threejs@r184"].split == "threejs-csm@r184"
    (a, b), _ = st.cascade_ranges("threejs-csm", 0.1, 100.0, 3)
    r = st.evaluate("threejs-csm", 0.1, 100.0, 50.0, "hemisphere:20", k=3, fit="diagonal-unrounded")
    np.testing.assert_array_equal(r.width_x, np.broadcast_to(st.diagonal(a, b, 50.0), r.width_x.shape))
    rounded = st.evaluate("threejs-csm", 0.1, 100.0, 50.0, "hemisphere:20", k=3, fit="diagonal")
    assert np.all(rounded.width_x >= r.width_x) and np.all(rounded.width_x - r.width_x < 1.0)
    assert st.coverage("threejs-csm", 0.1, 100.0, 50.0, "hemisphere:100", k=3, fit="diagonal-unrounded") == 1.0
