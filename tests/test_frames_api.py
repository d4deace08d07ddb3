"""The frames package's public API: every callable documented with a runnable example, bad input
refused by name, valid input giving finite results of the right shape (no browser; fast).

* ``test_every_public_callable_has_examples``: every public function, class and public method
  in ``aliasing/frames/*.py`` has a numpydoc ``Examples`` section with at least one doctest line
  that runs (``# doctest: +SKIP`` on every line only where the call needs a browser: ``BROWSER_ONLY``).
* ``test_bad_input_names_the_parameter``: Hypothesis draws one bad value (wrong shape, NaN or
  ±inf, out-of-range size) for one parameter of a valid call; the call must raise ``ValueError``
  whose message names that parameter.
* The property tests feed generated valid input to the pure functions (compare, run.flips,
  maps.tolerance, predict.to_map, ...) and check the results' shape, range and finiteness.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import numpy as np
import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402
from hypothesis.extra import numpy as hnp  # noqa: E402

from aliasing.frames import babylon_cascades, compare, maps, models, predict, readback, run, scenes, single  # noqa: E402
from aliasing.frames.models import MODELS  # noqa: E402
from aliasing.raster.scenes.camera import look_at  # noqa: E402

FRAMES = Path(predict.__file__).parent
#: callables whose every example line needs a browser (and so is marked +SKIP)
BROWSER_ONLY = {"browser.Browser.close"}
FAST = settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
BAD = settings(FAST, max_examples=10)  # each bad-value strategy is small: 10 draws reach its kinds


def _examples(doc: str) -> str | None:
    """The text of a numpydoc docstring's Examples section, None without one."""
    m = re.search(r"^Examples\n-{8}\n(.*?)(?=^\S[^\n]*\n-{3,}\n|\Z)", doc, re.S | re.M)
    return None if m is None else m.group(1)


def _public_callables():
    """(dotted name, its Examples text, its class's Examples text or None) of every public function, class and method."""
    for path in sorted(FRAMES.rglob("*.py")):
        tree = ast.parse(path.read_text())
        stem = ".".join(path.relative_to(FRAMES).with_suffix("").parts).removesuffix(".__init__")

        def walk(nodes, prefix, owner):
            for n in nodes:
                if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) and not n.name.startswith("_"):
                    own = _examples(ast.get_docstring(n) or "")
                    yield f"{stem}.{prefix}{n.name}", own, owner
                    if isinstance(n, ast.ClassDef):
                        yield from walk(n.body, f"{prefix}{n.name}.", own)

        yield from walk(tree.body, "", None)


def test_every_public_callable_has_examples():
    """A method may be shown by its class's Examples (which call it): the models' methods are, in
    one example per engine model (their module's 600-line limit leaves no room for one each)."""
    found = list(_public_callables())
    assert len(found) > 90  # the walk reaches the methods too
    missing, skipped_only = [], []
    for name, own, owner in found:
        if own is None and owner is not None and re.search(rf"\.{name.rsplit('.', 1)[1]}\(", owner):
            own = owner
        if own is None:
            missing.append(name)
            continue
        lines = [ln.strip() for ln in own.splitlines() if ln.strip().startswith(">>>")]
        if not any("doctest: +SKIP" not in ln for ln in lines) and name not in BROWSER_ONLY:
            skipped_only.append(name)
    assert not missing, f"public callables in aliasing/frames without a numpydoc Examples section: {missing}"
    assert not skipped_only, f"Examples with no line that runs (mark only browser calls +SKIP): {skipped_only}"


# ----------------------------------------------------------------------------- bad input is refused by name

M = np.array([[1.0, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0.5], [0, 0, 0, 1]])  # s = x, t = z, depth = 0.5 - y
ROOF = np.array([[[0.0, 0.25, 0.0], [2.0, 0.25, 0.0], [0.0, 0.25, 2.0]]])
PTS = np.array([[0.5, 0.0, 0.5], [0.5, 0.3, 0.5]])
UP = np.array([[0.0, 1.0, 0.0]] * 2)
DM = predict.light_depth_map(ROOF, M, 4)
CAM = look_at("0,0,0", "0,0,-1", near=1.0, far=100.0, fov=50.0)
SCENE = scenes.frame_scene("boxes", near=1.0, far=20.0, fov=50.0, aspect=1.0, boxes=1, ground_cells=1)

nonfinite = st.sampled_from([np.nan, np.inf, -np.inf])
bad_size = st.one_of(st.integers(-5, 0), st.integers(16385, 10**6), st.floats(0.5, 100).filter(lambda v: v != int(v)), nonfinite)


def _with(value, at):
    """A copy of a valid array with one entry replaced by ``value``."""
    def make(a):
        a = np.array(a, float)
        a.flat[at % a.size] = value
        return a
    return make


def _shape(draw, ndim, avoid):
    shape = tuple(draw.draw(st.lists(st.integers(1, 5), min_size=ndim, max_size=ndim)))
    return shape if shape != avoid else tuple(s + 1 for s in shape)


def _bad_triangles(draw):
    """An array of a shape other than (T, 3, 3)."""
    ndim = draw.draw(st.integers(1, 4))
    shape = list(draw.draw(st.lists(st.integers(1, 5), min_size=ndim, max_size=ndim)))
    if ndim == 3 and shape[1:] == [3, 3]:
        shape[2] = 4
    return np.zeros(shape)


# name -> (call(draw) returning a thunk, the parameter named in the error)
def _cases():
    mask = np.ones((3, 3), bool)
    fac = np.ones((3, 3))
    return {
        "compare.away_from_edges": (lambda d: lambda: compare.away_from_edges(mask, np.ones(_shape(d, d.draw(st.integers(1, 3)), (3, 3)), bool)), "b"),
        "compare.agreement": (lambda d: lambda: compare.agreement(fac, fac, np.ones(_shape(d, 2, (3, 3)), bool)), "drawn"),
        "compare.acne": (lambda d: lambda: compare.acne(fac, np.ones(_shape(d, 2, (3, 3)), bool)), "receivers"),
        "compare.gap": (lambda d: lambda: compare.gap(fac, mask, np.ones(_shape(d, 2, (3, 3)), bool), mask), "ground"),
        "compare.px_per_texel fov": (lambda d: lambda: compare.px_per_texel([1.0], [2.0], [1024], d.draw(st.one_of(
            st.floats(-1e3, 0), st.floats(180, 1e3), nonfinite)), 512), "fov"),
        "compare.px_per_texel sides": (lambda d: lambda: compare.px_per_texel(
            [1.0, 2.0], _with(d.draw(st.one_of(st.floats(-1e3, 0), nonfinite)), d.draw(st.integers(0, 1)))([2.0, 3.0]), [1024, 1024], 50.0, 512), "sides"),
        "compare.px_per_texel height": (lambda d: lambda: compare.px_per_texel([1.0], [2.0], [1024], 50.0, d.draw(st.integers(-5, 0))), "height"),
        "run.flips": (lambda d: lambda: run.flips(np.ones((3, 2, 2), bool), np.ones(_shape(d, 2, (2, 2)), bool)), "masks"),
        "run.make_job height": (lambda d: lambda: run.make_job(SCENE, [0.0, 1.0, 0.0], {}, d.draw(st.one_of(st.integers(-5, 15), st.integers(2161, 10**5)))), "height"),
        "run.make_job sun": (lambda d: lambda: run.make_job(SCENE, _with(d.draw(nonfinite), d.draw(st.integers(0, 2)))([0.0, 1.0, 0.0]), {}, 64), "sun"),
        "run.pose_camera": (lambda d: lambda: run.pose_camera(CAM, {"eye": _with(d.draw(nonfinite), d.draw(st.integers(0, 2)))([0.0, 0, 0]),
                                                                      "target": [0.0, 0, -1]}), "pose"),
        "run.make_job maps": (lambda d: lambda: run.make_job(SCENE, [0.0, 1.0, 0.0], {}, 64, maps=d.draw(st.one_of(st.integers(-5, 15), st.integers(4097, 10**5)))), "maps"),
        "maps.tolerance": (lambda d: lambda: maps.tolerance(ROOF, np.zeros((d.draw(st.integers(1, 4)), d.draw(st.integers(5, 8))), np.int64)), "triangle"),
        "maps.tolerance map_triangles": (lambda d: lambda: maps.tolerance(_bad_triangles(d), np.zeros((2, 2), np.int64)), "map_triangles"),
        "maps.compare": (lambda d: lambda: maps.compare(maps.EngineMap(np.ones((4, 4)), 4, 1), np.ones(_shape(d, 2, (4, 4))), np.zeros((4, 4), int),
                                                        np.ones((4, 4))), "depth"),
        "maps.snapped_depth_map": (lambda d: lambda: maps.snapped_depth_map(ROOF, M, 4, d.draw(st.one_of(st.integers(-5, -1), st.integers(17, 99)))), "subpixel_bits"),
        "maps.stored_depth": (lambda d: lambda: maps.stored_depth("threejs", MODELS["threejs"].settings(), ROOF, [0.0, 1.0, 0.0], M, d.draw(bad_size)), "size"),
        "predict.to_map matrix": (lambda d: lambda: predict.to_map(_with(d.draw(nonfinite), d.draw(st.integers(0, 15)))(M), PTS), "matrix"),
        "predict.to_map points": (lambda d: lambda: predict.to_map(M, _with(d.draw(nonfinite), d.draw(st.integers(0, 5)))(PTS)
                                                                   if d.draw(st.booleans()) else np.zeros((2, d.draw(st.sampled_from([1, 2, 4]))))), "points"),
        "predict.casting": (lambda d: lambda: predict.casting(ROOF, [0.0, 1.0, 0.0], d.draw(st.sampled_from(["up", "", "fronts", "none"]))), "side"),
        "predict.light_depth_map": (lambda d: lambda: predict.light_depth_map(ROOF, M, d.draw(bad_size)), "resolution"),
        "predict.threejs_factor radius": (lambda d: lambda: predict.threejs_factor(
            [DM], M[None], np.zeros(2, int), PTS, UP, np.ones(2), np.ones(2), bias=0.0, normal_bias=0.0,
            radius=d.draw(st.one_of(st.floats(-1e3, -1e-9), nonfinite))), "radius"),
        "predict.threejs_factor map_type": (lambda d: lambda: predict.threejs_factor(
            [DM], M[None], np.zeros(2, int), PTS, UP, np.ones(2), np.ones(2), bias=0.0, normal_bias=0.0, radius=1.0,
            map_type=d.draw(st.sampled_from(["VSMShadowMap", "pcf", ""]))), "map_type"),
        "predict.threejs_factor cascade": (lambda d: lambda: predict.threejs_factor(
            [DM], M[None], np.zeros(_shape(d, 1, (2,)), int), PTS, UP, np.ones(2), np.ones(2), bias=0.0, normal_bias=0.0, radius=1.0), "cascade"),
        "predict.babylon_factor blend_factor": (lambda d: lambda: predict.babylon_factor(
            [DM], M[None], np.zeros(2, int), np.ones(2), PTS, ends=np.ones(1), lengths=np.ones(1),
            blend_factor=d.draw(st.one_of(st.floats(-1e3, 0), nonfinite)), bias=0.0), "blend_factor"),
        "predict.playcanvas_factor": (lambda d: lambda: predict.playcanvas_factor(
            np.ones((4, 4)), M[None], np.zeros(2, int), PTS, UP, normal_offset=0.0, taps=d.draw(st.integers(-3, 9).filter(lambda t: t not in (1, 3, 5)))), "taps"),
        "single.babylon_single_factor": (lambda d: lambda: single.babylon_single_factor(DM, M, PTS, bias=d.draw(nonfinite)), "bias"),
        "predict.polygon_offset": (lambda d: lambda: predict.polygon_offset(predict.to_map(M, ROOF), d.draw(st.one_of(st.integers(-5, 0), st.floats(1.1, 9.9).filter(lambda v: v != int(v)))), 1.0, 1.0), "resolution"),
        "babylon_cascades.offset_casters": (lambda d: lambda: babylon_cascades.offset_casters(ROOF, np.array([0.0, 1.0, 0.0]), d.draw(nonfinite)), "normal_bias"),
        "models.tight_sides": (lambda d: lambda: models.tight_sides(CAM, np.array(d.draw(st.sampled_from([[1.0], [2.0, 1.0], [1.0, 1.0], [1.0, np.nan]]))),
                                                                      np.array([0.0, -1.0, 0.0]), np.array([0.0, 0.0, 1.0])), "edges"),
        "predict.reference": (lambda d: lambda: predict.reference(SCENE, np.array([0.0, 1.0, 0.0]), None, d.draw(bad_size)), "resolution"),
        "scenes.sun_direction": (lambda d: lambda: scenes.sun_direction(d.draw(st.one_of(st.floats(90.001, 1e3), st.floats(-1e3, -90.001), nonfinite)), 0.0, CAM), "elevation"),
        "scenes.wind_outward": (lambda d: lambda: scenes.wind_outward(_bad_triangles(d)), "triangles"),
        "babylon_cascades.look_at_lh": (lambda d: lambda: babylon_cascades.look_at_lh(_with(d.draw(nonfinite), d.draw(st.integers(0, 2)))([0.0, 0, -5]), np.zeros(3)), "eye"),
        "babylon_cascades.ortho_off_center_lh": (lambda d: lambda: babylon_cascades.ortho_off_center_lh(1.0, 1.0, -1.0, 1.0, 0.0, d.draw(st.floats(0.1, 10))), "right"),
        "readback.decode": (lambda d: lambda: readback.decode({"engine": "threejs", "width": d.draw(st.one_of(st.integers(-5, 0), st.floats(0.5, 9.5).filter(lambda v: v != int(v)))),
                                                              "height": 1, "shadow": "", "position": "", "normal": "", "cascades": [], "frame": ""}), "width"),
        "ThreeCSM.matrices": (lambda d: lambda: MODELS["threejs"].matrices(MODELS["threejs"].settings(), CAM, d.draw(st.sampled_from(
            [np.zeros(3), np.array([np.nan, 1.0, 0.0]), np.ones(2)]))), "sun"),
    }


CASES = _cases()


@pytest.mark.parametrize("case", sorted(CASES))
@BAD
@given(data=st.data())
def test_bad_input_names_the_parameter(case, data):
    make, name = CASES[case]
    with pytest.raises(ValueError) as err:
        make(data)()
    assert name in str(err.value), f"{case}: {err.value}"


# ----------------------------------------------------------------------------- valid input: finite results of the right shape

@st.composite
def images(draw, kind=float, n=2):
    """``n`` arrays of one (H, W) shape, H and W in [1, 6]."""
    shape = (draw(st.integers(1, 6)), draw(st.integers(1, 6)))
    if kind is bool:
        return [draw(hnp.arrays(bool, shape)) for _ in range(n)]
    return [draw(hnp.arrays(float, shape, elements=st.floats(0, 1))) for _ in range(n)]


@FAST
@given(images(bool, 2))
def test_away_from_edges_is_a_mask_of_the_image(ab):
    a, b = ab
    out = compare.away_from_edges(a, b)
    assert out.shape == a.shape and out.dtype == bool
    if not a.any() and not b.any():  # nothing shadowed: no edge anywhere
        assert out.all()


@FAST
@given(images(float, 2), st.data())
def test_agreement_and_acne_are_fractions(fp, data):
    f, p = fp
    drawn = data.draw(hnp.arrays(bool, f.shape))
    a = compare.agreement(f, p, drawn)
    assert np.isnan(a) or 0.0 <= a <= 1.0
    same = compare.agreement(f, f, drawn)
    assert np.isnan(same) or same == 1.0  # a mask agrees with itself
    c = compare.acne(f, drawn)
    assert (np.isnan(c) and not drawn.any()) or (0.0 <= c <= 1.0 and drawn.any())
    assert not drawn.any() or compare.acne(np.ones(f.shape), drawn) == 0.0  # all lit: no acne


@FAST
@given(hnp.arrays(bool, st.tuples(st.integers(2, 5), st.integers(1, 4), st.integers(1, 4))), st.data())
def test_flips_is_a_fraction(masks, data):
    keep = data.draw(hnp.arrays(bool, masks.shape[1:]))
    f = run.flips(masks, keep)
    if keep.any():
        assert 0.0 <= f <= 1.0
        assert run.flips(np.repeat(masks[:1], len(masks), 0), keep) == 0.0  # a still mask never flips
    else:
        assert np.isnan(f)


@FAST
@given(st.integers(1, 4), st.integers(1, 6), st.data())
def test_tolerance_shape_and_floor(t, r, data):
    tri = data.draw(hnp.arrays(float, (t, 3, 3), elements=st.floats(-2, 2)))
    tid = data.draw(hnp.arrays(np.int64, (r, r), elements=st.integers(-1, t - 1)))
    tol = maps.tolerance(tri, tid)
    assert tol.shape == (r, r) and not np.isnan(tol).any()
    assert (tol >= maps.FLOAT32_DEPTH).all()
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    assert np.isfinite(tol[(tid < 0) | (n[np.maximum(tid, 0), 2] != 0)]).all()  # inf only on edge-on triangles
    assert (tol[tid < 0] == maps.FLOAT32_DEPTH).all()


@FAST
@given(hnp.arrays(float, (3, 4), elements=st.floats(-10, 10)), hnp.arrays(float, st.tuples(st.integers(0, 3), st.just(3)), elements=st.floats(-100, 100)))
def test_to_map_is_finite_for_an_orthographic_light(top, pts):
    m = np.vstack([top, [0.0, 0.0, 0.0, 1.0]])
    c = predict.to_map(m, pts)
    assert c.shape == pts.shape and np.isfinite(c).all()
    np.testing.assert_allclose(c, pts @ top[:, :3].T + top[:, 3], atol=1e-9)


@FAST
@given(hnp.arrays(float, (2, 3, 3), elements=st.floats(0, 1)), st.integers(1, 4096), st.floats(0, 10), st.floats(0, 10))
def test_polygon_offset_is_finite_and_not_negative(tri, res, factor, units):
    off = predict.polygon_offset(tri, res, factor, units)
    assert off.shape == (2,) and np.isfinite(off).all() and (off >= 0).all()


@FAST
@given(st.lists(st.floats(0.1, 100), min_size=1, max_size=4), st.floats(1, 170), st.integers(1, 4000))
def test_px_per_texel_is_positive(starts, fov, height):
    sides = [2.0 * s for s in starts]
    out = compare.px_per_texel(starts, sides, [1024.0] * len(starts), fov, height)
    assert len(out) == len(starts) and all(np.isfinite(v) and v > 0 for v in out)


@FAST
@given(st.floats(-90, 90), st.floats(-720, 720))
def test_sun_direction_is_a_unit_vector(el, az):
    s = scenes.sun_direction(el, az, CAM)
    assert s.shape == (3,) and abs(np.linalg.norm(s) - 1) < 1e-12
    assert abs(s[1] - np.sin(np.radians(el))) < 1e-12


@FAST
@given(st.floats(-1e3, 1e3), st.floats(1e-3, 1e3), st.floats(-1e3, 1e3), st.floats(1e-3, 1e3), st.floats(-1e3, 1e3), st.floats(1e-3, 1e3))
def test_ortho_off_center_lh_maps_the_box_to_ndc(left, w, bottom, h, near, d):
    p = babylon_cascades.ortho_off_center_lh(left, left + w, bottom, bottom + h, near, near + d)
    lo = p @ [left, bottom, near, 1.0]
    hi = p @ [left + w, bottom + h, near + d, 1.0]
    np.testing.assert_allclose(lo, [-1, -1, -1, 1], atol=1e-6 * (1 + abs(left) / w + abs(bottom) / h + abs(near) / d))
    np.testing.assert_allclose(hi, [1, 1, 1, 1], atol=1e-6 * (1 + abs(left) / w + abs(bottom) / h + abs(near) / d))


@FAST
@given(st.floats(0.0, 1.0), st.floats(-0.2, 0.2))
def test_factors_on_a_4x4_map_are_in_0_1(y, bias):
    """The factor functions on the 4 × 4 roof map: in [0, 1], and 0 below the roof, 1 above it (no bias)."""
    pts = np.array([[0.5, y, 0.5]])
    c = np.zeros(1, int)
    f3 = predict.threejs_factor([DM], M[None], c, pts, UP[:1], np.ones(1), np.ones(1), bias=bias, normal_bias=0.0, radius=1.0)
    fb = predict.babylon_factor([DM], M[None], c, np.ones(1), pts, ends=np.ones(1), lengths=np.ones(1), blend_factor=10.0, bias=bias)
    fs = single.babylon_single_factor(DM, M, pts, bias=bias)
    atlas = predict.playcanvas_atlas(ROOF, M[None], [[0.0, 0.0, 1.0, 1.0]], 4, 0.0)
    fp = predict.playcanvas_factor(atlas, M[None], c, pts, UP[:1], normal_offset=0.0)
    for f in (f3, fb, fs, fp):
        assert f.shape == (1,) and 0.0 <= f[0] <= 1.0
    if bias == 0 and abs(y - 0.25) > 0.01:
        want = 1.0 if y > 0.25 else 0.0
        assert f3[0] == fb[0] == fs[0] == fp[0] == want
