"""UE5 virtual shadow-map clipmaps seen by a non-square camera (``fov`` vertical, ``aspect`` = width/height).

The engine's LOD takes the projection's horizontal entry (1/tan θ_x) and the view rect's
width W (module docstring of :mod:`aliasing.engines.vsm`).  Aspect 1 must give the square
model's numbers bit for bit; at aspect ≠ 1 the tests check what that rule predicts, each
against a second computation (sampled rays, frustum vertices, a Monte Carlo count, the
square model at the equivalent horizontal field of view).
"""

from __future__ import annotations

import contextlib
import io
import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aliasing import View, cli, geometry
from aliasing.engines import compare, vsm

BAD_ASPECTS = st.one_of(st.floats(max_value=0.0, allow_nan=False), st.sampled_from([math.nan, math.inf, -math.inf]))
FOVS = (10.0, 37.3, 60.0, 90.0, 120.0, 170.0)
WIDTHS = (64, 1920, 2048)
BIASES = (-1.5, 0.0, 0.7)
DEPTHS = np.geomspace(0.5, 1e7, 997)
LIGHTS = "hemisphere:30"


def _results(c: vsm.Clipmap) -> list:
    return [
        c.lod_bias, vsm.level(c, DEPTHS), vsm.m_axis(c, DEPTHS), vsm.m_at(c, DEPTHS, DEPTHS * 1.3),
        vsm.m_axis_range(c, 3.0, 1e6), vsm.frustum_max(c, 10.0, 1e5), vsm.pages(c, 10.0, 1e5, LIGHTS),
        vsm.ground_pages(c, 170.0, 1e5, LIGHTS), vsm.pool_check(c, 10.0, 1e5, "hemisphere:10", 2048),
    ]


# ---------------------------------------------------------------- aspect 1: the square model, bit for bit

@pytest.mark.parametrize("fov", FOVS)
def test_aspect_one_is_the_square_clipmap_bit_for_bit(fov):
    for w in WIDTHS:
        for b in BIASES:
            square, one = vsm.Clipmap(fov=fov, width=w, bias=b), vsm.Clipmap(fov=fov, width=w, bias=b, aspect=1.0)
            for x, y in zip(_results(square), _results(one)):
                if isinstance(x, dict):
                    assert x == y
                else:
                    assert np.array_equal(np.asarray(x), np.asarray(y), equal_nan=True)
    rho = np.geomspace(1.0, 1e5, 501)
    assert np.array_equal(vsm.ground_area(rho, 170.0, fov), vsm.ground_area(rho, 170.0, fov, 1.0))


@pytest.mark.parametrize("fov", FOVS)
def test_aspect_one_keeps_the_square_closed_forms(fov):
    """The square model's own formulas (one tan θ for both axes), written out here: equal bit for bit."""
    t = float(np.tan(np.radians(fov) / 2))
    th = float(np.radians(fov) / 2)
    c = vsm.Clipmap(fov=fov, width=1920, aspect=1.0)
    assert c.tan == c.tan_x == c.tan_y == t
    assert c.corner == float(np.sqrt(1 + 2 * t**2))
    assert c.lod_bias == max(0.0, 0.0 + float(np.log2(0.5 * t * vsm.VIRTUAL_RES / 1920)))
    a, b = np.array([1.0, 10.0, 100.0]), np.array([10.0, 100.0, 1000.0])
    e = geometry.light_space(geometry.lights(LIGHTS))[:, 0][:, None, :]
    q = t * (np.abs(e[..., 0]) + np.abs(e[..., 1]))
    square = np.maximum(a * (e[..., 2] + q), b * (e[..., 2] + q)) - np.minimum(a * (e[..., 2] - q), b * (e[..., 2] - q))
    assert np.array_equal(vsm.slice_extent(a, b, t, e[:, 0], 1.0), square)
    rho = np.geomspace(1.0, 1e5, 501)
    z0 = 170.0 / np.tan(th)
    with np.errstate(invalid="ignore"):
        seg = rho**2 * np.arccos(np.clip(z0 / np.maximum(rho, z0), -1, 1)) - z0 * np.sqrt(np.maximum(rho**2 - z0**2, 0))
    old = np.where(rho <= z0, 0.0, np.where(rho <= z0 / np.cos(th), seg, th * rho**2 - z0**2 * np.tan(th)))
    assert np.array_equal(vsm.ground_area(rho, 170.0, fov, 1.0), old)


# ---------------------------------------------------------------- bad aspect

@settings(max_examples=40, deadline=None)
@given(BAD_ASPECTS)
def test_bad_aspect_is_one_clear_error(bad):
    for call in (lambda: vsm.Clipmap(aspect=bad), lambda: vsm.ground_area(10.0, 1.0, 60.0, bad), lambda: vsm.slice_extent(1.0, 2.0, 1.0, [[1.0, 0.0, 0.0]], bad)):
        with pytest.raises(ValueError, match="^aspect") as info:
            call()
        assert "\n" not in str(info.value)


def test_an_array_of_aspects_is_refused():
    with pytest.raises(ValueError, match="^aspect must be a single number"):
        vsm.Clipmap(aspect=[1.0, 2.0])


@pytest.mark.parametrize("aspect", ["1e-300", "1e-8", "1e8", "1e300", "1.7e308"])
def test_extreme_aspects_on_the_command_line(aspect):
    """A sliver or a band of a view: a row of numbers (inf where they are), or one line naming aspect."""
    for extra in ([], ["--ground", "170"]):
        code, out, err = _run(["engines", "--schemes", "vsm:high,vsm:epic", "--light", "sphere:5", "--aspect", aspect, *extra])
        assert "Traceback" not in err and (code == 0 and err == "" or code == 2 and err.count("\n") == 1 and "aspect" in err), (aspect, err)
        if code == 0:
            assert "nan" not in out
    with pytest.raises(ValueError, match="^aspect .* too large"):
        vsm.Clipmap(fov=120.0, aspect=1.7e308)


def test_frustum_max_is_taken_over_the_covered_receivers():
    """Corner rays beyond the last level's radius R get no clipmap: the supremum is over the covered points
    (at a depth, m grows with d_c up to R), checked by sampled rays; NaN only when nothing is covered."""
    for aspect, near in ((1e8, 10.0), (1.0, 7e6), (2.0, 4e6)):
        c = vsm.Clipmap(fov=60.0, width=1920, aspect=aspect)
        R = 2.0 ** (c.last + 1)
        bound = vsm.frustum_max(c, near, 1e8)
        v = View(near, 1e8, 60.0, aspect)
        rng = np.random.default_rng(5)
        s = rng.uniform(-1, 1, (2, 40000)) ** 5  # many rays near the axis
        rays = np.stack([s[0] * v.tan_theta_x, s[1] * v.tan_theta, np.ones(40000)], -1)
        pts = np.geomspace(near, 1e8, 400)[:, None, None] * rays[None]
        m = vsm.m_at(c, pts[..., 2], np.linalg.norm(pts, axis=-1))
        assert np.isfinite(bound) and np.nanmax(m) <= bound * (1 + 1e-12) and np.nanmax(m) >= 0.999 * bound, (aspect, near)
        assert np.isnan(vsm.frustum_max(c, R, 2 * R))


# ---------------------------------------------------------------- aspect ≠ 1: what the engine's rule predicts

@pytest.mark.parametrize("aspect", [2.0, 0.5, 16 / 9])
def test_the_lod_takes_the_horizontal_scale(aspect):
    """LodScale = ½·tanθ_x·16384/W: at the same W and vertical fov, B′ grows by log2(aspect)."""
    for fov in (30.0, 60.0, 90.0):
        sq, wide = vsm.Clipmap(fov=fov, width=256), vsm.Clipmap(fov=fov, width=256, aspect=aspect)
        assert wide.tan_x == pytest.approx(aspect * sq.tan_y, rel=1e-15) and wide.tan_y == sq.tan_y
        assert wide.lod_bias == pytest.approx(sq.lod_bias + math.log2(aspect), rel=1e-12, abs=1e-12)
        # the same rows (W = aspect·256 pixels across): tan θ_x/W as the square camera's, the same levels
        same_rows = vsm.Clipmap(fov=fov, width=round(256 * aspect), aspect=aspect)
        assert same_rows.lod_bias == pytest.approx(sq.lod_bias + math.log2(aspect * 256 / round(256 * aspect)), rel=1e-12, abs=1e-12)


@pytest.mark.parametrize("aspect", [2.0, 0.5])
def test_the_axis_saw_tooth_is_the_square_one_at_the_horizontal_fov(aspect):
    """On the axis m = t_L·W/(2 tanθ_x d): the wide camera is the square model at fov_x, same W.

    Its range is (2^bias, 2^(1+bias)] in W-pixels whatever the aspect."""
    fov, w, bias = 50.0, 256, -0.5  # B′ unclamped at both aspects (at W = 1920 a 1:2 view clamps it at 0)
    fov_x = float(np.degrees(2 * np.arctan(aspect * np.tan(np.radians(fov / 2)))))
    wide = vsm.Clipmap(fov=fov, width=w, bias=bias, first=-40, last=40, aspect=aspect)
    sq = vsm.Clipmap(fov=fov_x, width=w, bias=bias, first=-40, last=40)
    d = np.geomspace(10.0, 1e7, 4001)
    phase = np.log2(d) + wide.lod_bias
    d = d[np.abs(phase - np.round(phase)) > 1e-6]  # off the flips (the two B′ differ in the last bits)
    np.testing.assert_allclose(vsm.m_axis(wide, d), vsm.m_axis(sq, d), rtol=1e-12)
    m = vsm.m_axis(wide, d)
    assert m.min() > 2.0**bias and m.max() <= 2.0 ** (1 + bias) * (1 + 1e-12)
    assert vsm.m_axis_range(wide, 10.0, 1e7)[1] == pytest.approx(2.0 ** (1 + bias), rel=1e-9)


@pytest.mark.parametrize("aspect", [2.0, 0.5, 16 / 9])
def test_frustum_max_grows_with_the_corner_factor_and_sampled_rays_reach_it(aspect):
    fov, bias = 60.0, -1.0
    c = vsm.Clipmap(fov=fov, width=256, bias=bias, first=-40, last=40, aspect=aspect)
    assert c.lod_bias > 0  # unclamped: the saw-tooth's top is 2^(1+bias)
    t = math.tan(math.radians(fov / 2))
    k = math.sqrt(1 + (aspect * t) ** 2 + t**2)
    assert c.corner == pytest.approx(k, rel=1e-15)
    bound = vsm.frustum_max(c, 100.0, 1e5)
    assert bound == pytest.approx(2.0 ** (1 + bias) * k, rel=1e-9)
    # second method: rays through the wide image (View's corner rays and random pixels), no corner formula
    rng = np.random.default_rng(3)
    v = View(100.0, 1e5, fov, aspect)
    rays = np.concatenate([v.corner_rays, np.stack([rng.uniform(-1, 1, 20000) * v.tan_theta_x, rng.uniform(-1, 1, 20000) * v.tan_theta, np.ones(20000)], -1)])
    depth = np.geomspace(100.0, 1e5, 3000)
    pts = depth[:, None, None] * rays[None]  # (D, P, 3)
    m = vsm.m_at(c, pts[..., 2], np.linalg.norm(pts, axis=-1))
    assert np.nanmax(m) <= bound * (1 + 1e-12) and np.nanmax(m) >= 0.99 * bound
    square = vsm.frustum_max(vsm.Clipmap(fov=fov, width=256, bias=bias, first=-40, last=40), 100.0, 1e5)
    assert bound / square == pytest.approx(k / math.sqrt(1 + 2 * t**2), rel=1e-9)


@pytest.mark.parametrize("aspect", [2.0, 0.5])
def test_slice_extent_matches_the_wide_frustum_vertices(aspect):
    a, b = np.array([1.0, 10.0, 100.0]), np.array([10.0, 100.0, 1000.0])
    basis = geometry.light_space(geometry.lights("sphere:300"))
    verts = geometry.frustum_vertices(View(a, b, 70.0, aspect))  # (3, 8, 3)
    t = math.tan(math.radians(35.0))
    for j in (0, 2):
        proj = np.einsum("kvi,ni->nkv", verts, basis[:, j])
        np.testing.assert_allclose(vsm.slice_extent(a, b, t, basis[:, j], aspect), np.ptp(proj, axis=-1), rtol=1e-12, atol=1e-9)


def test_pages_per_level_grow_across_the_view():
    """Same rows and tanθ_x/W (W = aspect·rows): the same levels, each slice wider in x."""
    lights = geometry.lights("hemisphere:40")
    sq = vsm.Clipmap(fov=60.0, width=960, coarse=None)
    wide = vsm.Clipmap(fov=60.0, width=1920, coarse=None, aspect=2.0)
    assert wide.lod_bias == pytest.approx(sq.lod_bias, rel=1e-12)
    p_sq, p_wide = vsm.pages(sq, 10.0, 1e5, lights), vsm.pages(wide, 10.0, 1e5, lights)
    assert (p_wide >= p_sq).all() and (p_wide > p_sq).sum() >= 0.9 * len(lights)
    over = vsm.pages(wide, 10.0, 1e5, "overhead")[0] / vsm.pages(sq, 10.0, 1e5, "overhead")[0]
    assert 1.3 < over < 2.0  # overhead the x extent roughly doubles (far corners), y is the same depth range; +1 page per axis


@pytest.mark.parametrize("aspect", [2.0, 0.5])
def test_ground_area_of_a_wide_camera_against_monte_carlo(aspect):
    rng = np.random.default_rng(11)
    h, fov, R = 170.0, 60.0, 3000.0
    ty = math.tan(math.radians(30.0))
    tx = aspect * ty
    x, z = rng.uniform(-R, R, 600_000), rng.uniform(0, R, 600_000)
    seen = (np.abs(x) <= z * tx) & (h <= z * ty)
    z0 = h / ty
    for r in (z0 * 1.05, z0 * math.sqrt(1 + tx**2) * 0.98, z0 * math.sqrt(1 + tx**2) * 1.5, 1000.0, 3000.0):  # segment, then wedge
        mc = (seen & (np.hypot(x, z) <= r)).mean() * 2 * R * R
        assert float(vsm.ground_area(r, h, fov, aspect)) == pytest.approx(mc, rel=0.03, abs=400.0), r
    assert float(vsm.ground_area(3000.0, h, fov, aspect)) == pytest.approx(math.atan(tx) * 3000.0**2 - z0**2 * tx, rel=1e-12)


# ---------------------------------------------------------------- the engines command

def _run(args: list[str]) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = cli.main(args)
    return code, out.getvalue(), err.getvalue()


def test_engines_command_at_aspect_one_is_byte_identical():
    for base in (["engines", "--schemes", "vsm:epic,vsm:bias=-2:first=4:pool=512,vsm:high:coarse=0,matched", "--light", "hemisphere:40"],
                 ["engines", "--schemes", "vsm:low,vsm:epic", "--ground", "170", "--format", "csv"]):
        plain = _run(base)
        assert plain[0] == 0 and plain[1]
        for one in ("1", "1.0"):
            assert _run(base + ["--aspect", one]) == plain


def test_engines_command_takes_a_wide_camera_for_vsm():
    fov, near, far, W, aspect = 60.0, 100.0, 1e5, 1920, 2.0
    code, out, err = _run(["engines", "--schemes", "vsm:high,vsm:epic", "--aspect", "2", "--near", "100", "--light", "hemisphere:20", "--format", "json"])
    assert code == 0 and err == ""
    rows = {r["scheme"]: r for r in json.loads(out)}
    t = math.tan(math.radians(fov / 2))
    k = math.sqrt(1 + (aspect * t) ** 2 + t**2)
    assert rows["vsm:high"]["max_error"] == pytest.approx(2.0 * k, rel=1e-9)  # bias 0: 2^(1+0)·√(1 + tan²θx + tan²θy)
    c = vsm.Clipmap(fov, W, 0.0, aspect=aspect)
    assert rows["vsm:high"]["pages"] == float(vsm.pages(c, near, far, "hemisphere:20").max())
    S = rows["vsm:high"]["pages"] * vsm.PAGE**2 * rows["vsm:high"]["max_error"] ** 2 / (W * (W / aspect))
    assert rows["vsm:high"]["S_bar"] == pytest.approx(S, rel=1e-12)  # per image area: W × W/aspect pixels
    sq = compare.compare(["vsm:high"], near=near, far=far, lights="hemisphere:20")[0]
    assert sq["max_error"] == pytest.approx(2.0 * math.sqrt(1 + 2 * t**2), rel=1e-9)
    assert rows["vsm:high"]["m_axis_max"] == sq["m_axis_max"] == pytest.approx(2.0, rel=1e-9)  # the axis saw-tooth is the square one


@settings(max_examples=30, deadline=None)
@given(st.floats(0.2, 5.0), st.floats(20.0, 150.0), st.integers(64, 4096), st.floats(-3.0, 2.0), st.floats(1.0, 1e4))
def test_generated_wide_clipmaps_bound_their_sampled_receivers(aspect, fov, width, bias, near):
    """Any valid aspect: every receiver sampled in the wide frustum stays under frustum_max, the axis
    stays under it too, and B′ moves by log2(aspect) against the square camera unless clamped at 0."""
    c = vsm.Clipmap(fov=fov, width=width, bias=bias, aspect=aspect)
    sq = vsm.Clipmap(fov=fov, width=width, bias=bias)
    raw = lambda k: k.bias + math.log2(0.5 * k.tan_x * vsm.VIRTUAL_RES / k.width)  # noqa: E731
    assert raw(c) == pytest.approx(raw(sq) + math.log2(aspect), abs=1e-9) and c.lod_bias == max(0.0, raw(c))
    far = near * 1e3
    bound = vsm.frustum_max(c, near, far)
    v = View(near, far, fov, aspect)
    rng = np.random.default_rng(0)
    rays = np.concatenate([v.corner_rays, np.stack([rng.uniform(-1, 1, 500) * v.tan_theta_x, rng.uniform(-1, 1, 500) * v.tan_theta, np.ones(500)], -1)])
    pts = np.geomspace(near, far, 200)[:, None, None] * rays[None]
    m = vsm.m_at(c, pts[..., 2], np.linalg.norm(pts, axis=-1))
    assert np.nanmax(m) <= bound * (1 + 1e-12)
    assert vsm.m_axis_range(c, near, far)[1] <= bound * (1 + 1e-12)
