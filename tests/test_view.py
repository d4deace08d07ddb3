"""aliasing.View: validated once, accepted wherever (near, far, fov) is; evaluate_many's sharing."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from aliasing import View, directional, faces, geometry, schemes
from aliasing.view import as_view

finite = st.floats(allow_nan=False, allow_infinity=False, width=64)
good_near = st.floats(1e-3, 1e3)
good_fov = st.floats(0.5, 179.5)
garbage = st.one_of(st.just(float("nan")), st.just("abc"), st.just(None), st.just([1.0, "x"]), st.just(object()))


@given(near=st.one_of(st.floats(max_value=0.0, allow_nan=False), st.just(math.inf), garbage), fov=good_fov)
def test_bad_near_names_near(near, fov):
    with pytest.raises(ValueError, match="near"):
        View(near, 1e6, fov)


@given(near=good_near, factor=st.floats(0.0, 1.0), fov=good_fov)
def test_far_not_beyond_near_names_far(near, factor, fov):
    with pytest.raises(ValueError, match="far"):
        View(near, near * factor, fov)


@given(near=good_near, far=st.one_of(st.just(math.inf), garbage), fov=good_fov)
def test_bad_far_names_far(near, far, fov):
    with pytest.raises(ValueError, match="far"):
        View(near, far, fov)


@given(fov=st.one_of(st.floats(max_value=0.0, allow_nan=False), st.floats(min_value=180.0), garbage))
def test_bad_fov_names_fov(fov):
    with pytest.raises(ValueError, match="fov"):
        View(1.0, 10.0, fov)


@given(near=good_near, ratio=st.floats(1.0 + 1e-9, 1e6), fov=good_fov)
def test_valid_views_hold_their_derived_values(near, ratio, fov):
    v = View(near, near * ratio, fov)
    assert v.theta == np.radians(fov) / 2
    assert v.tan_theta == np.tan(np.radians(fov) / 2)
    assert v.ratio == v.far / v.near > 1
    np.testing.assert_array_equal(v.corner_rays[:, 2], 1.0)
    np.testing.assert_array_equal(np.abs(v.corner_rays[:, :2]), v.tan_theta)


def test_arrays_broadcast_and_bad_shapes_are_refused():
    v = View([1.0, 2.0], 10.0, [[30.0], [60.0]])
    assert v.shape == (2, 2)
    np.testing.assert_array_equal(geometry.frustum_vertices(v), geometry.frustum_vertices([1.0, 2.0], 10.0, [[30.0], [60.0]]))
    with pytest.raises(ValueError, match="broadcast"):
        View([1.0, 2.0], [10.0, 20.0, 30.0], 60.0)
    with pytest.raises(ValueError, match="one view"):
        schemes.evaluate("P", v, "overhead")


def test_frozen_equal_and_hashable():
    v = View(1.0, 100.0, 60.0)
    with pytest.raises(AttributeError):
        v.near = 2.0  # type: ignore[misc]
    assert v == View(1, 100, 60) and hash(v) == hash(View(1, 100, 60))
    assert v != View(1.0, 100.0, 61.0)
    assert as_view(v) is v


def test_slice_vertices_are_the_frustum_vertices():
    v = View(2.0, 50.0, 70.0)
    np.testing.assert_array_equal(v.slice_vertices(), geometry.frustum_vertices(2.0, 50.0, 70.0))
    np.testing.assert_array_equal(v.slice_vertices(3.0, 7.0), geometry.frustum_vertices(3.0, 7.0, 70.0))
    with pytest.raises(ValueError, match="z1"):
        v.slice_vertices(7.0, 3.0)


LIGHTS = geometry.sphere_directions(300)


@pytest.mark.parametrize("name", ["Standard", "P", "Po", "LogP", "ZP3+P", "ZP4+LogP", "LiSPSM", "Sopt", "FP+P", "FPc+LogP", "FPcs+ZP2+P"])
def test_view_and_numbers_give_identical_results(name):
    a = schemes.evaluate(name, 0.5, 400.0, 75.0, LIGHTS)
    b = schemes.evaluate(name, View(0.5, 400.0, 75.0), LIGHTS)
    c = schemes.evaluate(name, View(0.5, 400.0, 75.0), light=LIGHTS)
    for r in (b, c):
        for field in ("M_x", "M_z", "S", "n_prime", "eta"):
            np.testing.assert_array_equal(getattr(r, field), getattr(a, field))


def test_view_in_faces_and_directional():
    v = View(1.0, 300.0, 50.0)
    a = faces.face_errors("fpc", "perspective", 1.0, 300.0, 50.0, LIGHTS[:40])
    b = faces.face_errors("fpc", "perspective", v, LIGHTS[:40])
    np.testing.assert_array_equal(a.S, b.S)
    lf = directional.fit(geometry.frustum_vertices(v), LIGHTS[:40])
    for p, q in zip(directional.vertex_errors(lf, 50.0, 20.0), directional.vertex_errors(lf, v, 20.0)):
        np.testing.assert_array_equal(p, q)
    with pytest.raises(ValueError, match="View"):
        schemes.evaluate("P", v, 300.0, 50.0, "overhead")
    with pytest.raises(ValueError, match="light"):
        faces.face_errors("fp", "perspective", v)


@pytest.mark.parametrize("ratio", [1.0 + 1e-12, 1.0 + 1e-9, 1.0 + 1e-6])
def test_thin_frusta_are_domain_not_error(ratio):
    """f/n → 1: every scheme still evaluates; a uniform map's S̄ → 0 like (f − n)."""
    v = View(1.0, ratio, 60.0)
    for name in ("Standard", "P", "Po", "LogP", "ZP3+P", "FP+P"):
        r = schemes.evaluate(name, v, "hemisphere:50")
        assert np.all(np.isfinite(r.S)) and np.all(r.S >= 0), name
    s = schemes.evaluate("Standard", v, "overhead").S[0]
    assert s == pytest.approx((ratio - 1) / (2 * np.tan(np.radians(30.0))), rel=1e-3)


# --- evaluate_many and the shared frames -------------------------------------------------------


def test_evaluate_many_is_evaluate_per_scheme():
    names = ["Standard", "P", "ZP5+LogP", "Sopt", "FPc+P", "ZP2+TSM"]
    many = schemes.evaluate_many(names, 1.0, 1000.0, 60.0, LIGHTS)
    assert [r.scheme.name for r in many] == [schemes.parse(n).name for n in names]
    for name, r in zip(names, many):
        one = schemes.evaluate(name, 1.0, 1000.0, 60.0, LIGHTS)
        for field in ("M_x", "M_z", "S", "n_prime", "eta"):
            np.testing.assert_array_equal(getattr(r, field), getattr(one, field), err_msg=f"{name}.{field}")
    assert [r.scheme.name for r in schemes.evaluate(names[:2], 1.0, 1000.0, 60.0, "overhead")] == ["Standard", "P"]


@pytest.mark.parametrize("chunk", [1, 7, 299, 300, 10_000])
def test_chunking_does_not_change_a_bit(chunk):
    ref = schemes.evaluate_many(["P", "ZP7+LogP"], 1.0, 1000.0, 60.0, LIGHTS)
    for a, b in zip(ref, schemes.evaluate_many(["P", "ZP7+LogP"], 1.0, 1000.0, 60.0, LIGHTS, chunk=chunk)):
        np.testing.assert_array_equal(a.S, b.S)
        np.testing.assert_array_equal(a.eta, b.eta)


def test_unknown_name_fails_before_any_work(monkeypatch):
    def no_work(*args, **kwargs):
        raise AssertionError("work started")

    monkeypatch.setattr(directional, "light_frame", no_work)
    monkeypatch.setattr(faces, "face_errors", no_work)
    with pytest.raises(ValueError, match="'Bogus'"):
        schemes.evaluate_many(["FP+P", "P", "Bogus"], 1.0, 100.0, 60.0, "hemisphere:1000")
    with pytest.raises(ValueError, match="'ZP0'"):
        schemes.evaluate(["P", "ZP0"], 1.0, 100.0, 60.0)
    with pytest.raises(ValueError, match="chunk"):
        schemes.evaluate_many(["P"], 1.0, 100.0, 60.0, chunk=0)
    with pytest.raises(ValueError, match="at least one"):
        schemes.evaluate_many([], 1.0, 100.0, 60.0)


def test_evaluate_many_with_edges():
    edges = [1.0, 5.0, 80.0, 1000.0]
    a, b = schemes.evaluate_many(["P", "LogP"], 1.0, 1000.0, 60.0, LIGHTS, edges=edges)
    assert a.maps == b.maps == 3 and a.M_x.shape == (len(LIGHTS), 3)
    np.testing.assert_array_equal(a.S, schemes.evaluate("P", 1.0, 1000.0, 60.0, LIGHTS, edges=edges).S)


def test_slice_errors_equal_the_vertex_maxima_exactly():
    """The fast path takes maxima at the corners of largest y: the same numbers as all 8 vertices."""
    view = View(1.0, 1000.0, 60.0)
    fr = directional.light_frame(view, LIGHTS)
    n_i, f_i = schemes.z_partitions(1.0, 1000.0, 5)
    sf = directional.slice_fit(fr, n_i, f_i)
    lf = sf.light_fit()
    rng = np.random.default_rng(3)
    npr = np.where(rng.random(sf.depth.shape) < 0.2, np.inf, sf.depth * rng.uniform(0.01, 50.0, sf.depth.shape))
    for kind in directional.PARAMETERIZATIONS:
        mx, mz = directional.vertex_errors(lf, view, npr.T, kind)
        fx, fz = directional.slice_errors(sf, npr, kind)
        np.testing.assert_array_equal(fx.T, mx.max(axis=-1))
        np.testing.assert_array_equal(fz.T, mz.max(axis=-1))
    # and the shared frame is the per-map rotation up to rounding
    ref = directional.fit(geometry.frustum_vertices(n_i, f_i, 60.0), LIGHTS)
    np.testing.assert_allclose(lf.x, ref.x, rtol=0, atol=1e-12 * 1000)
    np.testing.assert_allclose(lf.y, ref.y, rtol=0, atol=1e-12 * 1000)
    np.testing.assert_array_equal(lf.eye_depth, ref.eye_depth)


def test_error_closed_forms_accept_a_view():
    from aliasing import error

    v = View([1.0, 2.0], 100.0, 90.0)
    np.testing.assert_array_equal(error.storage_factor(v, 11.0), error.storage_factor([1.0, 2.0], 100.0, 90.0, 11.0))
    np.testing.assert_array_equal(error.storage_factor(v), error.storage_factor([1.0, 2.0], 100.0, 90.0))
    np.testing.assert_array_equal(error.max_error_z(v, n_prime=11.0), error.max_error_z([1.0, 2.0], 100.0, 90.0, 11.0))
    np.testing.assert_array_equal(error.storage_factor_optimal(v), error.storage_factor_optimal([1.0, 2.0], 100.0, 90.0))
    for a, b in zip(error.critical_resolution(v, 11.0, res_image=1024), error.critical_resolution([1.0, 2.0], 100.0, 90.0, 11.0, res_image=1024)):
        np.testing.assert_array_equal(a, b)
    with pytest.raises(ValueError, match="View"):
        error.storage_factor_optimal(v, 100.0)
    with pytest.raises(ValueError, match="fov"):
        error.storage_factor(1.0, 100.0)
