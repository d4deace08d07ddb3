"""The ``gl`` backend against the numpy reference, and the maps' 4×4 matrices.

Agreement, on seeded scenes of several parameterizations, light directions and sizes:
coverage differs on at most 1e-5 of the texels, the same triangle is visible in at least
0.998 of the texels both cover, and there the depths agree within 1e-5 of the map's depth
range; the backend's own, tighter bound (``gl.DEPTH_ERROR`` of the scene's depth range) is tested too.  Without an EGL device these tests skip, with the reason; under CI (CI=true) they run.
"""

from __future__ import annotations

import os

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aliasing import geometry, raster
from aliasing.cli import main
from aliasing.raster.draw import backends, budget_shares, cascade_set, gl
from aliasing.raster.scenes import procedural

ON_CI = os.environ.get("CI") == "true"
GL = pytest.mark.skipif(not gl.available() and not ON_CI, reason=f"the gl backend cannot draw here: {gl._setup()[1]}")

NEAR, FAR, FOV = 1.0, 600.0, 60.0


def city(triangles: int = 10_000, seed: int = 1) -> np.ndarray:
    """The procedural city in eye space: the eye 20 above the ground, 220 before the block."""
    return procedural.city(triangles, seed) + np.array([0.0, -20.0, 220.0])


def agreement(ref: raster.DepthMap, got: raster.DepthMap) -> tuple[float, float, float]:
    """(coverage difference, same-triangle fraction, depth difference / depth range)."""
    a, b = ref.triangle >= 0, got.triangle >= 0
    both = a & b
    same = both & (ref.triangle == got.triangle)
    span = float(np.ptp(ref.depth[a])) or 1.0
    depth = float(np.abs(ref.depth[same] - got.depth[same]).max()) / span if same.any() else 0.0
    return float((a != b).mean()), float(same.sum() / max(both.sum(), 1)), depth


def assert_agree(ref: raster.DepthMap, got: raster.DepthMap) -> None:
    coverage, same, depth = agreement(ref, got)
    assert (ref.triangle >= 0).mean() > 0.01  # the map sees the scene
    assert coverage <= 1e-5, coverage
    assert same >= 0.998, same
    assert depth <= 1e-5, depth


# --- the 4×4 matrices (no GL needed) -------------------------------------------------------

PROJECTIVE = ["Standard", "P", "Po", "lispsm", "tsm", "pyramid", "ZP3+P", "ZP2+lispsm", "FPc+P", "FPcs+Standard", "FP+P", "FPc+ZP2+P", "FP+Standard"]


@settings(max_examples=30, deadline=None)
@given(scheme=st.sampled_from(PROJECTIVE), gamma=st.floats(1.0, 179.0), azimuth=st.floats(-180.0, 180.0), seed=st.integers(0, 2**16))
def test_matrix_gives_the_coordinates_of_every_projective_map(scheme, gamma, azimuth, seed):
    try:
        ms = raster.map_set(NEAR, 100.0, FOV, f"gamma:{gamma}@azimuth:{azimuth}", scheme)
    except ValueError:  # a light this scheme has no map for (e.g. edge-on faces)
        return
    rng = np.random.default_rng(seed)
    corners = geometry.frustum_vertices(NEAR, 100.0, FOV)
    points = rng.dirichlet(np.ones(8), 200) @ corners  # inside the view frustum
    for lm in ms.maps:
        h = np.c_[points, np.ones(len(points))] @ lm.matrix().T
        s, t, d, w = lm.coordinates(points)
        ok = w > 0.1  # in front of the warp's centre of projection (face maps see part of the frustum)
        np.testing.assert_allclose(h[ok, 3], w[ok], rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(h[ok, 0] / h[ok, 3], s[ok], rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(h[ok, 1] / h[ok, 3], t[ok], rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(h[ok, 2], d[ok], rtol=1e-9, atol=1e-9 * float(np.abs(d).max()))


def test_log_maps_have_no_matrix():
    lm = raster.light_map(NEAR, FAR, FOV, "gamma:60", "LogP")
    with pytest.raises(ValueError, match="lm must be a projective map"):
        lm.matrix()


# --- the backend seam ------------------------------------------------------------------------

@pytest.mark.parametrize("operation", ["shadow_map", "eye_pass"])
def test_gl_is_a_backend_of_the_drawing_operations(operation):
    assert "gl" in backends.SUPPORTED[operation]
    with pytest.raises(ValueError, match=f"backend must be one of .* for {operation}"):
        backends.check("opengl", operation)


@settings(max_examples=20, deadline=None)
@given(backend=st.one_of(st.text(max_size=6), st.integers(), st.none()))
def test_a_bad_backend_is_named(backend):
    tri = np.array([[[-20, -1, 0.5], [20, -1, 0.5], [0, -1, 30]]], float)
    lm = raster.light_map(NEAR, 10.0, FOV, "overhead", "P")
    if backend in backends.SUPPORTED["shadow_map"]:
        return
    with pytest.raises(ValueError, match="backend must be one of"):
        raster.shadow_map(tri, lm, 8, backend=backend)


def test_no_egl_device_is_one_clear_line(monkeypatch, capsys):
    monkeypatch.setattr(gl, "_setup", lambda: (None, "no EGL device could be opened (test); install Mesa's llvmpipe"))
    tri = np.array([[[-20, -1, 0.5], [20, -1, 0.5], [0, -1, 30]]], float)
    lm = raster.light_map(NEAR, 10.0, FOV, "overhead", "P")
    with pytest.raises(ValueError, match="backend 'gl' cannot draw here: no EGL device"):
        raster.shadow_map(tri, lm, 8, backend="gl")
    with pytest.raises(ValueError, match="backend 'gl' cannot draw here"):
        raster.eye_pass(tri, FOV, 8, backend="gl")
    for argv in (["validate", "--scheme", "P", "--f-over-n", "100", "--light", "overhead", "--res", "64", "--backend", "gl"],
                 ["render", "--scheme", "P", "--out", "/nonexistent/x.png", "--backend", "gl"]):
        code = main(argv)
        err = capsys.readouterr().err
        assert code == 2 and len(err.strip().splitlines()) == 1 and "backend 'gl' cannot draw here: no EGL device" in err


@pytest.mark.parametrize("argv", [["validate", "--scheme", "P", "--f-over-n", "100", "--backend", "cuda"], ["render", "--scheme", "P", "--out", "x.png", "--backend", "cuda"],
                                  ["validate", "--scheme", "P", "--f-over-n", "100", "--grid", "--backend", "gl"]])
def test_backend_option_errors_are_one_line(argv, capsys):
    code = main(argv)
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1 and "backend" in err


# --- agreement with numpy ---------------------------------------------------------------------

# Lights above the city's ground (y > 0 towards the light).  From below, the ground and the
# buildings' bottom faces coincide (z-fighting): which of two coplanar triangles a texel keeps
# is decided by rounding in either backend (see the z-fighting test).
CASES = [
    # scheme, light, resolution, scene seed
    ("Standard", "gamma:50@azimuth:20", 1024, 1),
    ("P", "gamma:70@azimuth:-30", 1024, 2),
    ("Po", "overhead", 1024, 3),
    ("lispsm", "gamma:130@azimuth:60", 1024, 4),
    ("tsm", "gamma:100@azimuth:60", 1024, 5),
    ("P", "gamma:120@azimuth:80", 1024, 12),  # grazing: 9° above the ground
    ("P", "gamma:30@azimuth:10", 2048, 6),
]


@GL
@pytest.mark.parametrize("scheme, light, res, seed", CASES)
def test_single_maps_agree_with_numpy(scheme, light, res, seed):
    tri = city(10_000, seed)
    lm = raster.light_map(NEAR, FAR, FOV, light, scheme)
    assert_agree(raster.shadow_map(tri, lm, res), raster.shadow_map(tri, lm, res, backend="gl"))


@GL
@pytest.mark.parametrize("scheme, light", [("ZP3+P", "gamma:120@azimuth:10"), ("FPc+P", "gamma:60@azimuth:30"), ("FPcs+Standard", "gamma:80@azimuth:-50"), ("FP+P", "gamma:45@azimuth:70")])
def test_map_sets_agree_with_numpy(scheme, light):
    tri = city(10_000, 7)
    ms = raster.map_set(NEAR, FAR, FOV, light, scheme)
    res = [1024] * len(ms.maps)
    ref, got = raster.shadow_maps(tri, ms, res), raster.shadow_maps(tri, ms, res, backend="gl")
    seen = 0
    for a, b in zip(ref, got):
        if (a.triangle >= 0).mean() > 0.01:
            assert_agree(a, b)
            seen += 1
    assert seen >= 2


@GL
def test_cascades_agree_with_numpy():
    sc = raster.ground_and_boxes(NEAR, 1000.0, FOV, boxes=150, ground_cells=30, seed=8)
    cs = cascade_set(NEAR, 1000.0, FOV, "gamma:40@azimuth:25", "P", splits="practical", k=3, lam=0.5)
    res = budget_shares(cs, 3 * 1024**2, "equal")
    for a, b in zip(raster.shadow_maps(sc.triangles, cs.maps, res), raster.shadow_maps(sc.triangles, cs.maps, res, backend="gl")):
        assert_agree(a, b)


@GL
@pytest.mark.parametrize("scheme, light", [("P", "gamma:70@azimuth:-30"), ("Standard", "gamma:20"), ("ZP3+P", "gamma:120@azimuth:10"), ("FP+P", "gamma:45@azimuth:70")])
def test_depth_is_within_the_backends_bound_of_the_scene_depth_range(scheme, light):
    # the depth at each texel is the visible plane's, computed in double precision and stored
    # as float32: within gl.DEPTH_ERROR (5e-7) of the scene's depth range through that map.
    # The hardware's interpolated depth (from snapped vertices) was 1.6e-4 off on this city
    tri = city(20_000, 3)
    ms = raster.map_set(NEAR, FAR, FOV, light, scheme)
    refs, gots = raster.shadow_maps(tri, ms, 1024), raster.shadow_maps(tri, ms, 1024, backend="gl")
    seen = 0
    for lm, ref, got in zip(ms.maps, refs, gots):
        same = (ref.triangle >= 0) & (ref.triangle == got.triangle)
        if not same.any():  # a face of FP that sees none of the city
            continue
        seen += 1
        depth = tri.reshape(-1, 3) @ lm.matrix()[2, :3] + lm.matrix()[2, 3]
        assert np.abs(ref.depth[same] - got.depth[same]).max() <= gl.DEPTH_ERROR * np.ptp(depth)
    assert seen >= 1


@GL
def test_edges_through_texel_centres_follow_the_numpy_rule():
    # a rectangle of two triangles whose edges run exactly through texel centres: the left
    # and bottom edges own them, the shared diagonal goes to one triangle only
    c = (np.arange(8) + 0.5) / 8
    x0, x1, y0, y1 = c[2], c[5], c[1], c[4]
    tri = np.array([[[x0, y0, 0.5], [x1, y0, 0.5], [x1, y1, 0.5]], [[x0, y0, 0.6], [x1, y1, 0.6], [x0, y1, 0.6]]])
    ((depth, ident),), _ = gl.draw_maps(tri, [np.eye(4)], [8])
    ref = raster.rasterize(tri, 8)
    np.testing.assert_array_equal(ident, ref.triangle)
    np.testing.assert_allclose(depth, ref.depth, rtol=0, atol=gl.DEPTH_ERROR * 0.1)  # the depths span 0.5 to 0.6


@GL
def test_log_maps_are_drawn_by_numpy_whatever_the_backend():
    tri = city(2_000, 9)
    lm = raster.light_map(NEAR, FAR, FOV, "gamma:60@azimuth:20", "LogP")
    a, b = raster.shadow_map(tri, lm, 256), raster.shadow_map(tri, lm, 256, backend="gl")
    np.testing.assert_array_equal(a.depth, b.depth)
    np.testing.assert_array_equal(a.triangle, b.triangle)


@GL
def test_non_finite_triangles_are_skipped_and_ids_index_the_input():
    tri = city(2_000, 10)
    tri[5, 1, 0] = np.nan
    tri[17, 2, 2] = np.inf
    lm = raster.light_map(NEAR, FAR, FOV, "gamma:50", "Standard")  # numpy refuses NaN weights w of warped maps
    got = raster.shadow_map(tri, lm, 1024, backend="gl")
    assert got.degenerate == 2 and got.rasterized == len(tri) - 2
    with np.errstate(invalid="ignore"):  # the numpy path transforms the NaN corners before skipping them
        ref = raster.shadow_map(tri, lm, 1024)
    assert_agree(ref, got)


@GL
@pytest.mark.parametrize("res", [512, 2048])
def test_eye_pass_g_buffer_agrees_with_numpy(res):
    # coverage at silhouettes against the empty sky, where the far ground's tiny triangles put
    # many edges in a pixel: measured 0 to 2.3e-5 of the pixels (512² to 2048²); bound 1e-4
    tri = city(10_000, 11)
    ref, got = raster.eye_pass(tri, FOV, res), raster.eye_pass(tri, FOV, res, backend="gl")
    a, b = ref.triangle >= 0, got.triangle >= 0
    assert 0.3 < a.mean() < 1
    assert (a != b).mean() <= 1e-4
    same = a & b & (ref.triangle == got.triangle)
    assert same.sum() / (a & b).sum() >= 0.998
    np.testing.assert_array_equal(got.position[same], ref.position[same])  # computed from the id, as numpy does
    np.testing.assert_array_equal(got.normal[same], ref.normal[same])
    assert np.isnan(got.position[~b]).all()


@GL
def test_z_fighting_from_below_the_ground_is_a_tie_of_coincident_surfaces():
    # lit from below, the ground and the buildings' bottom faces coincide: texels where the
    # backends keep different triangles (about 5 % here) hold the same depth there
    tri = city(10_000, 5)
    lm = raster.light_map(NEAR, FAR, FOV, "gamma:100@azimuth:-120", "tsm")
    ref, got = raster.shadow_map(tri, lm, 1024), raster.shadow_map(tri, lm, 1024, backend="gl")
    coverage, same, _ = agreement(ref, got)
    assert coverage <= 1e-5 and same < 0.998
    differ = (ref.triangle >= 0) & (got.triangle >= 0) & (ref.triangle != got.triangle)
    gap = np.abs(ref.depth[differ] - got.depth[differ]) / np.ptp(ref.depth[ref.triangle >= 0])
    assert (gap <= 1e-5).mean() >= 0.999


@GL
def test_validate_and_render_draw_through_gl(tmp_path, capsys):
    assert main(["validate", "--scheme", "ZP2+P", "--f-over-n", "100", "--light", "gamma:60", "--res", "128", "--probes", "8", "--backend", "gl", "--format", "json"]) == 0
    import json

    assert json.loads(capsys.readouterr().out)["passed"] is True
    out = tmp_path / "gl.png"
    assert main(["render", "--scheme", "P", "--res", "256", "--image-res", "96", "--out", str(out), "--backend", "gl"]) == 0
    assert out.stat().st_size > 1000
