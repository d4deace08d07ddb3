"""View frusta, light directions, light space, direction sampling and the light-spec parser.

Degenerate geometry (lights exactly or nearly parallel to the view direction) is part of
the domain and is tested alongside general positions.
"""

from __future__ import annotations

import numpy as np
import pytest

from aliasing import geometry as G

RTOL = 1e-12


def approx(expected, **tolerance):
    """pytest.approx without its default absolute tolerance of 1e-12 (tiny values matter here)."""
    return pytest.approx(expected, **{"abs": 0.0, **tolerance})


def _random_units(count, seed):
    v = np.random.default_rng(seed).normal(size=(count, 3))
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


# --- frustum_vertices -----------------------------------------------------------------


def test_frustum_vertices_corners():
    v = G.frustum_vertices(2.0, 50.0, 90.0)  # tan 45° = 1: corners at ±d
    assert v.shape == (8, 3)
    np.testing.assert_allclose(v[:4, 2], 2.0, rtol=0)
    np.testing.assert_allclose(v[4:, 2], 50.0, rtol=0)
    np.testing.assert_allclose(np.abs(v[:4, :2]), 2.0, rtol=RTOL)
    np.testing.assert_allclose(np.abs(v[4:, :2]), 50.0, rtol=RTOL)
    # 4 distinct corners per plane, one in each quadrant, near and far in the same order
    signs = np.sign(v[:, :2])
    assert len({tuple(s) for s in signs[:4]}) == 4
    np.testing.assert_array_equal(signs[:4], signs[4:])
    # far corners lie on the rays through the near corners (the eye is the apex)
    np.testing.assert_allclose(v[4:] / 50.0, v[:4] / 2.0, rtol=RTOL)


@pytest.mark.parametrize("fov", [1.0, 60.0, 120.0, 179.0])
def test_frustum_vertices_half_angle_is_half_fov(fov):
    v = G.frustum_vertices(1.0, 10.0, fov)
    t = np.tan(np.radians(fov) / 2)
    np.testing.assert_allclose(np.abs(v[..., 0]), t * v[..., 2], rtol=RTOL)
    np.testing.assert_allclose(np.abs(v[..., 1]), t * v[..., 2], rtol=RTOL)


def test_frustum_vertices_broadcasting():
    near = np.array([1.0, 2.0]).reshape(2, 1)
    far = np.array([10.0, 20.0, 30.0])
    v = G.frustum_vertices(near, far, 60.0)
    assert v.shape == (2, 3, 8, 3)
    np.testing.assert_array_equal(v[1, 2], G.frustum_vertices(2.0, 30.0, 60.0))
    assert G.frustum_vertices([1.0, 2.0], [5.0, 6.0], [30.0, 90.0]).shape == (2, 8, 3)
    assert G.frustum_vertices(1.0, 5.0, np.array([[30.0], [60.0], [90.0]])).shape == (3, 1, 8, 3)


@pytest.mark.parametrize("near, far, fov", [(0.0, 1.0, 60.0), (2.0, 1.0, 60.0), (1.0, 1.0, 60.0), (1.0, 2.0, 0.0), (1.0, 2.0, 180.0)])
def test_frustum_vertices_rejects_bad_input(near, far, fov):
    with pytest.raises(ValueError, match="near|far|fov"):
        G.frustum_vertices(near, far, fov)


# --- light_direction / direction_angles -----------------------------------------------


def test_light_direction_named_directions():
    np.testing.assert_allclose(G.light_direction(90.0, 0.0), [0, 1, 0], atol=1e-15)  # overhead
    np.testing.assert_allclose(G.light_direction(0.0), [0, 0, 1], atol=1e-15)  # into the light
    np.testing.assert_allclose(G.light_direction(180.0), [0, 0, -1], atol=1e-15)  # behind
    np.testing.assert_allclose(G.light_direction(90.0, 90.0), [1, 0, 0], atol=1e-15)  # from the right
    assert G.light_direction([[10.0], [20.0]], [0.0, 30.0, 60.0]).shape == (2, 3, 3)


def test_light_direction_rejects_gamma_out_of_range():
    for bad in (-1.0, 180.5, np.nan):
        with pytest.raises(ValueError, match="gamma"):
            G.light_direction(bad)


def test_light_direction_is_unit_and_gamma_is_angle_to_view():
    g = np.linspace(0.0, 180.0, 37)[:, None]
    a = np.linspace(-180.0, 180.0, 25)[None, :]
    lv = G.light_direction(g, a)
    np.testing.assert_allclose(np.linalg.norm(lv, axis=-1), 1.0, rtol=RTOL)
    np.testing.assert_allclose(np.degrees(np.arctan2(np.hypot(lv[..., 0], lv[..., 1]), lv[..., 2])), np.broadcast_to(g, lv.shape[:-1]), atol=1e-12)


def test_direction_angles_round_trip():
    rng = np.random.default_rng(1)
    g = rng.uniform(1.0, 179.0, 500)
    a = rng.uniform(-179.9, 179.9, 500)
    gg, aa = G.direction_angles(G.light_direction(g, a))
    np.testing.assert_allclose(gg, g, atol=1e-10)
    np.testing.assert_allclose(aa, a, atol=1e-10)
    # and from vectors: not normalised is fine
    lv = _random_units(200, 2) * 3.7
    gg, aa = G.direction_angles(lv)
    np.testing.assert_allclose(G.light_direction(gg, aa) * 3.7, lv, atol=1e-12)


def test_direction_angles_of_parallel_lights():
    gg, _ = G.direction_angles(np.array([[0.0, 0.0, 1.0], [0.0, 0.0, -2.0]]))
    np.testing.assert_array_equal(gg, [0.0, 180.0])


@pytest.mark.parametrize("gamma", [1e-9, 1e-6, 1e-4])
def test_direction_angles_round_trip_nearly_parallel(gamma):
    # BUG (geometry.py line 85): γ = arccos(l_z) loses all relative precision as γ → 0° or
    # 180° (cos γ rounds to ±1): γ = 1e-9° comes back as 0, γ = 1e-4° with a relative
    # error 2.7e-5.  arctan2(hypot(l_x, l_y), l_z) is accurate everywhere.
    gg, aa = G.direction_angles(G.light_direction(gamma, 30.0))
    assert float(gg) == approx(gamma, rel=1e-9)
    assert float(aa) == approx(30.0, rel=1e-12)
    gg, aa = G.direction_angles(-G.light_direction(gamma, 30.0))  # γ' = 180° − γ, azimuth + 180°
    assert 180.0 - float(gg) == approx(gamma, abs=1e-12)  # the ulp of 180 is 2.8e-14
    assert float(aa) == approx(-150.0, rel=1e-12)


def test_direction_angles_rejects_bad_vectors():
    with pytest.raises(ValueError, match="non-zero"):
        G.direction_angles([0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match=r"\(\.\.\., 3\)"):
        G.direction_angles([1.0, 0.0])


# --- light_space ------------------------------------------------------------------------


def _assert_right_handed_orthonormal(basis, light, atol=1e-12):
    basis = np.asarray(basis)
    eye = np.broadcast_to(np.eye(3), basis.shape)
    np.testing.assert_allclose(basis @ np.swapaxes(basis, -1, -2), eye, atol=atol)
    np.testing.assert_allclose(np.linalg.det(basis), 1.0, atol=atol)
    np.testing.assert_allclose(np.cross(basis[..., 0, :], basis[..., 1, :]), basis[..., 2, :], atol=atol)  # x × y = z
    lv = np.asarray(light, float)
    np.testing.assert_allclose(basis[..., 1, :], lv / np.linalg.norm(lv, axis=-1, keepdims=True), atol=atol)  # y_L = light


def test_light_space_random_directions():
    lv = _random_units(2000, 3)
    basis = G.light_space(lv)
    assert basis.shape == (2000, 3, 3)
    _assert_right_handed_orthonormal(basis, lv)
    # z_L lies in the plane of v and the light, oriented like v (Wimmer et al. 2004 §3.4)
    np.testing.assert_allclose(np.einsum("ni,ni->n", basis[:, 2], np.cross(lv, G.VIEW)), 0.0, atol=1e-12)
    assert np.all(basis[:, 2] @ G.VIEW > 0)


def test_light_space_overhead_is_eye_space():
    np.testing.assert_allclose(G.light_space([0.0, 1.0, 0.0]), np.eye(3), atol=1e-15)
    np.testing.assert_allclose(G.light_space(G.lights("overhead")), np.eye(3)[None], atol=1e-15)


@pytest.mark.parametrize("light", [[0.0, 0.0, 1.0], [0.0, 0.0, -1.0], [0.0, 0.0, 5.0]])
def test_light_space_exactly_parallel(light):
    basis = G.light_space(light)
    _assert_right_handed_orthonormal(basis, light)
    np.testing.assert_allclose(basis[2], G.UP, atol=1e-15)  # documented choice: z_L = up


@pytest.mark.parametrize("spec", ["front", "behind", "gamma:0", "gamma:180", "gamma:180@azimuth:77"])
def test_light_space_parallel_from_specs(spec):
    lv = G.lights(spec)
    _assert_right_handed_orthonormal(G.light_space(lv), lv)


def test_light_space_degenerate_choice_is_the_limit_at_azimuth_0():
    # module docstring: z_L = up is the limit γ → 180° at azimuth 0 (and −up as γ → 0°)
    np.testing.assert_allclose(G.light_space(G.light_direction(180.0 - 1e-3, 0.0))[2], G.UP, atol=1e-4)
    np.testing.assert_allclose(G.light_space(G.light_direction(1e-3, 0.0))[2], -G.UP, atol=1e-4)


@pytest.mark.parametrize("gamma", [1e-9, 1e-6, 180.0 - 1e-6, 180.0 - 1e-9])
def test_light_space_nearly_parallel(gamma):
    # BUG (geometry.py line 105): z_L = v − (v·y_L) y_L cancels catastrophically when the light
    # is nearly parallel to v (1 − cos²γ with cos γ rounded to ±1): the basis is then
    # orthogonal only to ~1e-16/sin γ (1.7e-11 at γ = 1e-9°, 4.7e-9 at γ = 1e-6°).
    # z_L = (y_L × v) × y_L, normalised, has no cancellation.
    rng = np.random.default_rng(4)
    lv = G.light_direction(gamma, rng.uniform(-180.0, 180.0, 50))
    _assert_right_handed_orthonormal(G.light_space(lv), lv)


def test_light_space_rejects_zero_light():
    with pytest.raises(ValueError, match="light"):
        G.light_space([0.0, 0.0, 0.0])


# --- sphere / hemisphere sampling -------------------------------------------------------


@pytest.mark.parametrize("count", [1, 2, 7, 1000, 4096])
def test_sampling_count_and_unit_norm(count):
    for sample in (G.sphere_directions, G.hemisphere_directions):
        d = sample(count)
        assert d.shape == (count, 3)
        np.testing.assert_allclose(np.linalg.norm(d, axis=-1), 1.0, rtol=RTOL)
        assert np.isfinite(d).all()


def test_hemisphere_is_above_the_viewer():
    d = G.hemisphere_directions(5000)
    assert np.all(d[:, 1] >= 0)
    assert len(np.unique(d.round(12), axis=0)) == 5000  # no duplicates


def test_sampling_is_deterministic():
    np.testing.assert_array_equal(G.sphere_directions(777), G.sphere_directions(777))
    np.testing.assert_array_equal(G.hemisphere_directions(777), G.hemisphere_directions(777))
    np.testing.assert_array_equal(G.lights("sphere:300"), G.sphere_directions(300))


def test_hemisphere_equal_solid_angle():
    d = G.hemisphere_directions(10_000)
    # uniform in solid angle ⇔ uniform in height (Archimedes): E[y] = 1/2, E[y²] = 1/3
    assert d[:, 1].mean() == approx(0.5, abs=1e-4)
    assert (d[:, 1] ** 2).mean() == approx(1 / 3, abs=1e-4)
    # fraction inside the polar cap y > cos α is the cap's share 1 − cos α of the hemisphere
    for c in (0.95, 0.8, 0.5, 0.2):
        assert (d[:, 1] > c).mean() == approx(1 - c, abs=1e-3)
    # no preferred azimuth: the horizontal mean vanishes, and left/right, front/back halves balance
    assert np.abs(d[:, [0, 2]].mean(axis=0)).max() < 1e-3
    assert (d[:, 0] > 0).mean() == approx(0.5, abs=2e-3)
    assert (d[:, 2] > 0).mean() == approx(0.5, abs=2e-3)


def test_sphere_equal_solid_angle():
    d = G.sphere_directions(10_000)
    assert np.abs(d.mean(axis=0)).max() < 1e-4
    np.testing.assert_allclose((d**2).mean(axis=0), 1 / 3, atol=1e-3)
    # caps about arbitrary axes hold their area fraction (1 − cos α)/2
    for axis in _random_units(20, 5):
        for c in (0.9, 0.5, 0.0, -0.5):
            assert (d @ axis > c).mean() == approx((1 - c) / 2, abs=3e-3)


@pytest.mark.parametrize("bad", [0, -3, 2.5, True])
def test_sampling_rejects_bad_counts(bad):
    for sample in (G.sphere_directions, G.hemisphere_directions):
        with pytest.raises(ValueError, match="whole number"):
            sample(bad)


# --- hemisphere_map ---------------------------------------------------------------------


def test_hemisphere_map_layout():
    u, v, light = G.hemisphere_map(41)
    assert u.shape == v.shape == (41, 41) and light.shape == (41, 41, 3)
    r2 = u**2 + v**2
    assert np.isnan(light[r2 > 1 + 1e-12]).all()
    inside = r2 < 1 - 1e-12  # points on the rim may fall either side by rounding
    assert np.isfinite(light[inside]).all()
    np.testing.assert_allclose(np.linalg.norm(light[inside], axis=-1), 1.0, rtol=RTOL)
    assert np.all(light[inside][:, 1] >= 0)
    # orthographic view from above: the light's horizontal components are the map position
    np.testing.assert_array_equal(light[inside][:, 2], u[inside])
    np.testing.assert_array_equal(light[inside][:, 0], v[inside])
    c = 20
    np.testing.assert_allclose(light[c, c], [0, 1, 0], atol=1e-15)  # centre: overhead
    np.testing.assert_allclose(light[c, 0], [0, 0, -1], atol=1e-15)  # left (u = −1): behind the viewer
    np.testing.assert_allclose(light[c, -1], [0, 0, 1], atol=1e-15)  # right (u = +1): in front


def test_hemisphere_map_rejects_bad_resolution():
    with pytest.raises(ValueError, match="resolution"):
        G.hemisphere_map(0)


# --- lights() spec parser ---------------------------------------------------------------


@pytest.mark.parametrize(
    "spec, expected",
    [
        ("overhead", [[0, 1, 0]]),
        ("behind", [[0, 0, -1]]),
        ("front", [[0, 0, 1]]),
        ("  OverHead ", [[0, 1, 0]]),
        ("gamma:90", [[0, 1, 0]]),
        ("gamma:0", [[0, 0, 1]]),
        ("GAMMA:180", [[0, 0, -1]]),
        ("gamma:90@azimuth:90", [[1, 0, 0]]),
        ("gamma:90@azimuth:-90", [[-1, 0, 0]]),
        ("gamma:45@azimuth:90", [[np.sqrt(0.5), 0, np.sqrt(0.5)]]),
        ("gamma:60.5", G.light_direction(60.5)[None]),
    ],
)
def test_lights_named_and_gamma(spec, expected):
    lv = G.lights(spec)
    assert lv.shape == (1, 3)
    np.testing.assert_allclose(lv, expected, atol=1e-15)


@pytest.mark.parametrize("spec, count", [("sphere:1", 1), ("sphere:500", 500), ("hemisphere:20", 20), ("Hemisphere:3000", 3000)])
def test_lights_sampled(spec, count):
    lv = G.lights(spec)
    assert lv.shape == (count, 3)
    expected = G.sphere_directions(count) if spec.lower().startswith("sphere") else G.hemisphere_directions(count)
    np.testing.assert_array_equal(lv, expected)


def test_lights_pass_vectors_through_normalised():
    np.testing.assert_allclose(G.lights([0.0, 2.0, 0.0]), [[0.0, 1.0, 0.0]], rtol=0)
    lv = _random_units(10, 6) * 5
    np.testing.assert_allclose(G.lights(lv), lv / 5, rtol=RTOL)
    with pytest.raises(ValueError, match="non-zero"):
        G.lights([[0.0, 1.0, 0.0], [0.0, 0.0, 0.0]])


@pytest.mark.parametrize(
    "spec, message",
    [
        ("gamma:abc", r"malformed light 'gamma:abc'; expected overhead \| behind"),
        ("sphere:0", r"light 'sphere:0': N must be a whole number >= 1, got 0"),
        ("sphere:-3", r"light 'sphere:-3': N must be a whole number >= 1, got -3"),
        ("sphere:2.5", r"malformed light 'sphere:2.5'"),
        ("hemisphere:", r"malformed light 'hemisphere:'"),
        ("hemisphere", r"malformed light 'hemisphere'"),
        ("gamma:200", r"light 'gamma:200': gamma must be in \[0, 180\] degrees, got 200"),
        ("gamma:-1", r"light 'gamma:-1': gamma must be in \[0, 180\] degrees"),
        ("gamma:nan", r"light 'gamma:nan': gamma must not be NaN"),
        ("gamma:", r"malformed light 'gamma:'"),
        ("gamma:45@azimuth:", r"malformed light"),
        ("gamma:45@azimuth:x", r"malformed light"),
        ("gamma:45@elevation:10", r"malformed light"),
        ("sideways", r"malformed light 'sideways'; expected overhead \| behind \| front \| gamma:DEG\[@azimuth:DEG\] \| sphere:N \| hemisphere:N"),
        ("", r"malformed light ''"),
    ],
)
def test_lights_malformed_specs_raise_clear_errors(spec, message):
    with pytest.raises(ValueError, match=message):
        G.lights(spec)
