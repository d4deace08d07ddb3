"""Non-square views in the engines package: stable.evaluate / coverage / cost with ``aspect``.

``fov`` is vertical and ``aspect`` = width/height, as in :class:`aliasing.View`.  Aspect 1
must give the square view's numbers bit for bit; other aspects are checked against corners
written out by hand and against the general analysis (:func:`aliasing.schemes.evaluate`).
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aliasing import View, geometry, partitioning, schemes
from aliasing.engines import compare, stable

BAD_ASPECTS = st.one_of(st.floats(max_value=0.0, allow_nan=False), st.sampled_from([math.nan, math.inf, -math.inf]))
LIGHTS = geometry.lights("sphere:60")
FIELDS = ("M_x", "M_z", "S", "width_x", "width_y")


def _same(a: stable.StableResult, b: stable.StableResult) -> bool:
    return all(np.array_equal(getattr(a, f), getattr(b, f)) for f in FIELDS) and all(
        np.array_equal(x, y) for x, y in zip(a.used + a.fit_range, b.used + b.fit_range)
    )


@pytest.mark.parametrize("near, far, fov", [(1.0, 1000.0, 60.0), (0.1, 50.0, 90.0), (2.0, 3.0, 20.0), (0.5, 1e4, 120.0)])
def test_aspect_one_is_bit_for_bit_on_a_grid(near, far, fov):
    splits: tuple = ("log", "practical", "babylon", "threejs-csm", "bevy", np.geomspace(near, far, 4))
    for split, fit, snap in itertools.product(splits, stable.FITS, ("none", "border", "pad")):
        if isinstance(split, str) and split == "bevy" and not near < 10.0 < far:
            continue  # Bevy's first bound (10 m) must lie inside (near, far)
        k = None if isinstance(split, np.ndarray) else 3
        loose = stable.evaluate(split, near, far, fov, LIGHTS, k=k, fit=fit, snap=snap)
        one = stable.evaluate(split, near, far, fov, LIGHTS, k=k, fit=fit, snap=snap, aspect=1.0)
        assert _same(one, loose), (split, fit, snap)
    for options in ({"scene": True, "fit": "body"}, {"overlap": 0.2, "fit": "diagonal"}, {"border": 0.1, "dilation": 0.05, "quantize": True}):
        loose = stable.evaluate("log", near, far, fov, LIGHTS, k=4, **options)
        assert _same(stable.evaluate("log", near, far, fov, LIGHTS, k=4, aspect=1, **options), loose), options
    for fit in ("far", "body", "sphere"):
        assert stable.coverage("log", near, far, fov, LIGHTS, k=3, fit=fit, aspect=1.0) == stable.coverage("log", near, far, fov, LIGHTS, k=3, fit=fit)
        assert stable.cost("log", near, far, fov, LIGHTS, k=3, fit=fit, aspect=1.0) == stable.cost("log", near, far, fov, LIGHTS, k=3, fit=fit)


@settings(max_examples=40, deadline=None)
@given(BAD_ASPECTS, st.sampled_from(["evaluate", "coverage", "cost"]))
def test_bad_aspect_is_refused_naming_it(aspect, what):
    fn = getattr(stable, what)
    with pytest.raises(ValueError, match="^aspect") as info:
        fn("log", 1.0, 100.0, 60.0, "overhead", k=3, fit="sphere", aspect=aspect)
    assert "\n" not in str(info.value)


def test_an_array_of_aspects_is_refused_naming_it():
    with pytest.raises(ValueError, match="^aspect must be a single number"):
        stable.evaluate("log", 1.0, 100.0, 60.0, "overhead", k=3, aspect=[1.0, 2.0])


def _hand_slices(a, b, fov, aspect):
    """(K, 8, 3) slice corners written out from the definition (not through View)."""
    ty = math.tan(math.radians(fov) / 2)
    return np.array([[[sx * aspect * ty * d, sy * ty * d, d] for d in (lo, hi) for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))] for lo, hi in zip(a, b)]), ty


@pytest.mark.parametrize("aspect", [0.5, 16 / 9, 2.0, 3.7])
def test_tight_fit_against_hand_written_corners(aspect):
    near, far, fov = 1.0, 300.0, 60.0
    r = stable.evaluate("practical", near, far, fov, LIGHTS, k=4, aspect=aspect)
    (a, b), (u, _) = r.fit_range, r.used
    verts, ty = _hand_slices(a, b, fov, aspect)
    basis = geometry.light_space(LIGHTS)
    wx = np.ptp(np.einsum("kvj,nj->nkv", verts, basis[:, 0]), axis=-1)
    wy = np.ptp(np.einsum("kvj,nj->nkv", verts, basis[:, 2]), axis=-1)
    np.testing.assert_allclose(r.width_x, wx, rtol=1e-12, atol=0)
    np.testing.assert_allclose(r.width_y, wy, rtol=1e-12, atol=0)
    np.testing.assert_allclose(r.M_x, wx / (2 * ty * u), rtol=1e-12, atol=0)  # the beam of a square pixel: tan θ_y


@pytest.mark.parametrize("aspect", [0.5, 16 / 9, 2.0])
def test_tight_fit_is_the_general_analysis_standard_zp(aspect):
    edges = partitioning.split_distances("practical", 1.0, 1000.0, 4)
    r = stable.evaluate(edges, 1.0, 1000.0, 60.0, "hemisphere:64", aspect=aspect)
    s = schemes.evaluate("Standard", View(1.0, 1000.0, 60.0, aspect), "hemisphere:64", edges=edges)
    np.testing.assert_allclose(r.M_x, s.M_x, rtol=1e-12)
    np.testing.assert_allclose(r.M_z, s.M_z, rtol=1e-12)
    np.testing.assert_allclose(r.S, s.S, rtol=1e-12)


@pytest.mark.parametrize("aspect", [0.5, 16 / 9, 2.0])
def test_light_independent_fits_take_the_radii_at_aspect(aspect):
    near, far, fov = 0.5, 400.0, 75.0
    radii = {
        "sphere": lambda a, b: 2 * stable.sphere_radius(a, b, fov, aspect),
        "centroid": lambda a, b: 2 * stable.centroid_radius(a, b, fov, aspect),
        "centroid16": lambda a, b: 2 * np.ceil(16 * stable.centroid_radius(a, b, fov, aspect)) / 16,
        "diagonal": lambda a, b: np.ceil(stable.diagonal(a, b, fov, aspect)),
        "diagonal-unrounded": lambda a, b: stable.diagonal(a, b, fov, aspect),
        "body": lambda a, b: stable.body_diagonal(a, b, fov, aspect),
        "far": lambda a, b: np.full_like(a, 2 * far),
    }
    for fit, side in radii.items():
        r = stable.evaluate("log", near, far, fov, LIGHTS, k=4, fit=fit, aspect=aspect)
        want = np.broadcast_to(side(*r.fit_range), r.width_x.shape)
        assert np.array_equal(r.width_x, want) and np.array_equal(r.width_y, want), fit
    wider, square = (stable.evaluate("log", near, far, fov, LIGHTS, k=4, fit="sphere", aspect=x) for x in (max(aspect, 1 / aspect), 1.0))
    assert (wider.width_x > square.width_x).all()  # a wider (or taller) image has farther corners


def test_wide_view_coverage_uses_the_wide_corners():
    # the sphere fits cover every slice at any aspect; Filament's camera sphere {eye, far} misses the far
    # corners at distance far·√(1 + tan²θ_x + tan²θ_y) for some lights, more of them at aspect 2
    for aspect in (0.5, 2.0):
        assert stable.coverage("log", 1.0, 100.0, 60.0, "hemisphere:200", k=3, fit="sphere", aspect=aspect) == 1.0
        assert stable.coverage("log", 1.0, 100.0, 60.0, "hemisphere:200", k=3, fit="centroid", aspect=aspect) == 1.0
    square = stable.coverage("log", 1.0, 100.0, 60.0, "hemisphere:200", k=3, fit="far")
    wide = stable.coverage("log", 1.0, 100.0, 60.0, "hemisphere:200", k=3, fit="far", aspect=2.0)
    assert wide < square < 1.0
    c = stable.cost("log", 1.0, 100.0, 60.0, "hemisphere:100", k=3, fit="sphere", aspect=2.0)
    assert c["S_ratio_min"] > 1.0


# --- aliasing engines --aspect ---------------------------------------------------------------

SCHEMES = ["csm:log:k=4", "csm-stable:babylon", "csm-stable:threejs", "csm:bevy-bounds", "sdsm:k=3", "sdsm:k=3:border=1:dilation=0.05:quantize=1", "vsm:high", "matched", "exact"]


def test_engines_aspect_one_is_byte_identical(capsys):
    from aliasing import cli

    base = ["engines", "--schemes", ",".join(SCHEMES), "--light", "hemisphere:40,gamma:30", "--format", "json"]
    assert cli.main(base) == 0
    loose = capsys.readouterr().out
    assert cli.main(base + ["--aspect", "1"]) == 0
    assert capsys.readouterr().out == loose
    rows = compare.compare(SCHEMES, lights="hemisphere:40", near=1.0, far=1000.0, unit="m")
    assert rows == compare.compare(SCHEMES, lights="hemisphere:40", near=1.0, far=1000.0, unit="m", aspect=1.0)


@pytest.mark.parametrize("aspect", [2.0, 16 / 9, 0.5])
def test_engines_aspect_overhead_as_derived(aspect):
    """Overhead light, image W pixels wide and W/aspect high (square pixels, fov vertical).

    Tight maps: the x-extent of every slice is 2 b tan θ_x = aspect × the square one, the
    z-extent unchanged; the pixel is aspect × larger (W/aspect rows over 2 d tan θ_y).  So
    m_x is unchanged, m_z is divided by aspect, S_bar (per image area) is unchanged and
    the matched limit's storage is divided by aspect.  Babylon's sphere: side 2·ceil16(r)
    with r the wide centroid radius, m = side/(2 tan θ_y u_1) × (W/aspect)/R.
    """
    near, far, fov, W, R = 1.0, 500.0, 60.0, 1920, 2048
    kw = {"near": near, "far": far, "fov": fov, "lights": "overhead", "image_res": W, "shadow_res": R, "unit": "m"}
    sq = {r["scheme"]: r for r in compare.compare(["csm:log:k=4", "csm-stable:babylon", "matched", "exact"], **kw)}
    wide = {r["scheme"]: r for r in compare.compare(["csm:log:k=4", "csm-stable:babylon", "matched", "exact"], aspect=aspect, **kw)}
    t = math.tan(math.radians(fov) / 2)
    res = stable.evaluate("log", near, far, fov, "overhead", k=4)
    m_x, m_z = res.M_x.max() * W / R, res.M_z.max() * W / R
    assert wide["csm:log:k=4"]["max_error"] == pytest.approx(max(m_x, m_z / aspect), rel=1e-12)
    assert sq["csm:log:k=4"]["max_error"] == pytest.approx(max(m_x, m_z), rel=1e-12)
    for key in ("m_axis_min", "m_axis_max", "S_bar"):
        assert wide["csm:log:k=4"][key] == pytest.approx(sq["csm:log:k=4"][key], rel=1e-12), key
    for name in ("matched", "exact"):
        assert wide[name]["storage_texels"] == pytest.approx(sq[name]["storage_texels"] / aspect, rel=1e-15)
        assert wide[name]["max_error"] == sq[name]["max_error"] == 1.0
    assert wide["csm:log:k=4"]["storage_ratio"] == pytest.approx(aspect * sq["csm:log:k=4"]["storage_ratio"], rel=1e-12)
    u1 = partitioning.split_distances("babylon", near, far, 4)[0]
    side = 2 * math.ceil(16 * float(stable.centroid_radius(u1, partitioning.split_distances("babylon", near, far, 4)[1], fov, aspect))) / 16
    assert wide["csm-stable:babylon"]["max_error"] == pytest.approx(side / (2 * t * u1) * (W / aspect) / R, rel=1e-12)


def test_engines_aspect_refusals(capsys):
    from aliasing import cli

    for bad in ("0", "-1", "nan", "inf"):
        for chosen in ("csm:log:k=3", "vsm:epic"):
            assert cli.main(["engines", "--schemes", chosen, "--aspect", bad]) == 2
            err = capsys.readouterr().err
            assert err.count("\n") == 1 and "aspect" in err and "Traceback" not in err


def test_vsm_takes_the_wide_camera(capsys):
    """vsm at aspect 1.5 (no longer refused): the clipmap's LOD from tan θ_x (tests/test_vsm_aspect.py
    checks the model); the row's frustum maximum is 2^(1+bias)·√(1 + tan²θ_x + tan²θ_y)."""
    from aliasing import cli
    from aliasing.engines import vsm

    row = compare.compare(["vsm:high"], near=100.0, aspect=1.5, lights="hemisphere:20")[0]
    t = math.tan(math.radians(30.0))
    assert row["max_error"] == pytest.approx(2.0 * math.sqrt(1 + (1.5 * t) ** 2 + t**2), rel=1e-9)
    assert row["pages"] == float(vsm.pages(vsm.Clipmap(60.0, 1920, 0.0, aspect=1.5), 100.0, 1e5, "hemisphere:20").max())
    assert cli.main(["engines", "--schemes", "vsm:epic", "--aspect", "1.5"]) == 0
    out, err = capsys.readouterr()
    assert err == "" and out.count("vsm:epic") == 1
