"""Face-partitioned map sets in the rasterizer (FP, FPc, FPcs) against aliasing.faces (issue 6 item 4, issue 15 item 4)."""

from __future__ import annotations

import numpy as np
import pytest

from aliasing import faces, geometry, raster, schemes
from aliasing.raster.validate import validate

GENERIC, BEHIND = "gamma:60@azimuth:30", "gamma:170"


@pytest.mark.parametrize("scheme", ["FPc+P", "FPc+LogP"])
@pytest.mark.parametrize("light", [GENERIC, BEHIND])
def test_face_maps_measured_error_never_exceeds_and_reaches_the_bound(scheme, light):
    r = raster.measure(1.0, 100.0, 60.0, light, scheme, resolution=512, cells=40)
    ms = raster.map_set(1.0, 100.0, 60.0, light, scheme)
    ref = faces.face_errors("fpc", schemes.parse(scheme).parameterization, 1.0, 100.0, 60.0, geometry.lights(light))
    np.testing.assert_array_equal(r.M_x, ref.M_x[0, ms.slots])
    np.testing.assert_array_equal(r.M_z, ref.M_z[0, ms.slots])
    assert len(ms.maps) == ref.maps[0] and np.all(ref.M_x[0, ms.slots] > 0)
    ok = np.isfinite(r.m_x)
    assert all((ok & (r.partition == i)).sum() > 300 for i in range(len(ms.maps)))
    # never above the per-map bound beyond the stated central-difference tolerance, pixel by pixel
    assert np.all(r.m_x[ok] <= r.M_x[r.partition[ok]] * (1 + r.tolerance))
    assert np.all(r.m_z[ok] <= r.M_z[r.partition[ok]] * (1 + r.tolerance))
    if scheme == "FPc+P" and light == BEHIND:
        # P's side-face maxima lie at the faces' near vertices (d = n, 10x the far ones), which
        # a side face's partition only reaches in a thin wedge along the near plane: the
        # near and top maps reach, the others approach the bound as the probes densify.
        assert r.ratio_x[0] >= 0.97 and r.ratio_x[2] >= 0.97 and r.ratio_z[2] >= 0.97
        dense = raster.measure(1.0, 100.0, 60.0, light, scheme, resolution=1024, cells=80)
        lag = [1, 3, 4]
        assert np.all(dense.ratio_x[lag] > r.ratio_x[lag] + 0.01) and np.all(dense.ratio_x[lag] >= 0.94)
        assert np.all(dense.ratio_x <= 1 + dense.tolerance) and np.all(dense.ratio_z <= 1 + dense.tolerance)
    else:
        assert np.all(r.ratio_x >= 0.97) and np.all(r.ratio_z >= 0.97)


@pytest.mark.parametrize("scheme, options", [("FPc+P", {}), ("FPc+LogP", {}), ("FPc+Standard", {}), ("FPcs+LogP", {"tau0": 95.0, "tau1": 100.0}), ("FPc+ZP3+P", {}),
                                             ("FP+P", {}), ("FP+LogP", {}), ("FP+Standard", {}), ("FP+ZP3+LogP", {})])
@pytest.mark.parametrize("light", [GENERIC, BEHIND, "gamma:120@azimuth:75", "gamma:20@azimuth:200"])
def test_every_frustum_point_lands_in_its_map(scheme, options, light):
    # a map spans its (half) face: the points it shades map into [0, 1]², and the face's
    # corners onto the map's edges
    ms = raster.map_set(1.0, 100.0, 60.0, light, scheme, **options)
    rng = np.random.default_rng(0)
    uv = rng.uniform(-1, 1, (20000, 2)) * np.tan(np.radians(30))
    z = 100.0 ** rng.uniform(0, 1, 20000)
    pts = np.column_stack([uv * z[:, None], z])
    which = ms.assign(pts)
    assert np.all(which >= 0) and set(which.tolist()) <= set(range(len(ms.maps)))
    for i, lm in enumerate(ms.maps):
        s, t, _, _ = lm.coordinates(pts[which == i])
        assert s.size and np.all((s >= -1e-9) & (s <= 1 + 1e-9) & (t >= -1e-9) & (t <= 1 + 1e-9))
    sch = schemes.parse(scheme)
    ref = faces.face_errors(sch.faces, sch.parameterization, 1.0, 100.0, 60.0, geometry.lights(light), k=sch.k, **options)
    assert len(ms.maps) == ref.maps[0] and np.all(ref.M_x[0, ms.slots] > 0)
    if sch.faces == "fpcs" and light == "gamma:20@azimuth:200":
        assert len(ms.maps) > faces.chosen_faces(geometry.lights(light), 60.0)[0].sum()  # a face was split in two


@pytest.mark.parametrize("scheme", ["FPc+LogP", "FP+P", "FP+LogP"])
def test_validate_and_cli_path_for_face_schemes(scheme):
    r = validate(scheme, 100, 60, GENERIC, res=256, probes=16)
    assert r["maps"] == 3 and r["passed"] and r["max_ratio"] <= 1 + r["tolerance"]
    assert r["S_total"] == pytest.approx(float(schemes.evaluate(scheme, 1.0, 100.0, 60.0, GENERIC).S[0]), rel=1e-12)


@pytest.mark.parametrize("scheme", ["FP+P", "FP+LogP"])
@pytest.mark.parametrize("light", [GENERIC, BEHIND])
def test_face_fixed_maps_measured_error_never_exceeds_and_reaches_the_bound(scheme, light):
    # FP: each side face parameterized in its own plane (Lloyd 2007 §6.1.3); the bound is
    # aliasing.faces.face_errors("fp", ...) per map, which carries cos φ_lx, cos φ_ly (eqs. 55, 61-62)
    r = raster.measure(1.0, 100.0, 60.0, light, scheme, resolution=512, cells=40)
    ms = raster.map_set(1.0, 100.0, 60.0, light, scheme)
    ref = faces.face_errors("fp", schemes.parse(scheme).parameterization, 1.0, 100.0, 60.0, geometry.lights(light))
    np.testing.assert_array_equal(r.M_x, ref.M_x[0, ms.slots])
    np.testing.assert_array_equal(r.M_z, ref.M_z[0, ms.slots])
    assert len(ms.maps) == ref.maps[0] and ms.faces == "fp" and np.all(ref.M_x[0, ms.slots] > 0)
    ok = np.isfinite(r.m_x)
    assert all((ok & (r.partition == i)).sum() > 300 for i in range(len(ms.maps)))
    assert np.all(r.m_x[ok] <= r.M_x[r.partition[ok]] * (1 + r.tolerance))
    assert np.all(r.m_z[ok] <= r.M_z[r.partition[ok]] * (1 + r.tolerance))
    if scheme == "FP+P" and light == BEHIND:
        # as for FPc+P: P's across maximum is at a side face's near end (d = n), which its
        # partition reaches only in a thin wedge along the near plane; denser probes approach it
        assert r.ratio_x[0] >= 0.97 and np.all(r.ratio_z >= 0.9)
        dense = raster.measure(1.0, 100.0, 60.0, light, scheme, resolution=1024, cells=80)
        lag = [1, 3]
        assert np.all(r.ratio_x[lag] < 0.9) and np.all(dense.ratio_x[lag] > r.ratio_x[lag] + 0.05)
        assert np.all(dense.ratio_x >= 0.94) and np.all(dense.ratio_z >= 0.94)
        assert np.all(dense.ratio_x <= 1 + dense.tolerance) and np.all(dense.ratio_z <= 1 + dense.tolerance)
    else:
        assert np.all(r.ratio_x >= 0.94) and np.all(r.ratio_z >= 0.94)


def test_face_fixed_map_is_the_face_frame_scaled_by_the_light_angles():
    # a point on the face plane maps like (x, y) in the face's own frame: X = x cos φ_lx, Y = y cos φ_ly
    lv = geometry.lights(GENERIC)[0]
    normal, centre, across, _ = faces.side_frames(60.0)
    lm = raster.fixed_face_map(1.0, 100.0, 60.0, lv, "left", "perspective")
    x, y = np.meshgrid(np.linspace(-3, 3, 5), np.linspace(2, 90, 6))
    on_face = x[..., None] * across[2] + y[..., None] * centre[2]
    lifted = on_face + 7.0 * lv  # the same light ray, 7 units nearer the light
    X, Y, h = lm.light_plane(lifted)
    lx, ly, lz = lv @ across[2], lv @ centre[2], abs(lv @ normal[2])
    np.testing.assert_allclose(X, x * lz / np.hypot(lx, lz), atol=1e-12)
    np.testing.assert_allclose(Y + lm.y_offset, y * lz / np.hypot(ly, lz), atol=1e-12)
    # P's t is Lloyd 2006 eq. 6 in y with the centre of projection at y = -a, a = sqrt(y0 y1)
    y0, y1 = 1.0 / np.cos(np.radians(30)), 100.0 / np.cos(np.radians(30))
    a = np.sqrt(y0 * y1)
    _, t, _, _ = lm.coordinates(lifted)
    np.testing.assert_allclose(t, (y1 + a) * (y - y0) / ((y + a) * (y1 - y0)), rtol=1e-12)


def test_face_map_bad_input():
    with pytest.raises(ValueError, match="face is then edge-on"):
        raster.fixed_face_map(1.0, 100.0, 60.0, faces.side_frames(60.0)[1][0], "bottom", "perspective")
    with pytest.raises(ValueError, match="face"):
        raster.fixed_face_map(1.0, 100.0, 60.0, [0.0, 1.0, 0.0], "far", "perspective")
    with pytest.raises(ValueError, match="unknown options"):
        raster.map_set(1.0, 100.0, 60.0, GENERIC, "FP+P", c_fraction=0.5)
    with pytest.raises(ValueError, match="unknown options"):
        raster.map_set(1.0, 100.0, 60.0, GENERIC, "FPc+P", c_fraction=0.5)
    with pytest.raises(ValueError, match="near face is then edge-on"):
        raster.near_face_map(1.0, 60.0, [0.0, 1.0, 0.0])
    with pytest.raises(ValueError, match="perpendicular to light"):
        raster.frame_map([0.0, 1.0, 0.0], [0.0, 1.0, 1.0], 1.0, 2.0, 1.0, 0.0, 1.0, "perspective")
    with pytest.raises(ValueError, match="y1 > y0"):
        raster.frame_map([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], 2.0, 1.0, 1.0, 0.0, 1.0, "perspective")
    with pytest.raises(ValueError, match="y0 \\+ a > 0"):
        raster.frame_map([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], -2.0, 1.0, 1.0, 0.0, 1.0, "logperspective")
    with pytest.raises(ValueError, match="parameterization"):
        raster.frame_map([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], 1.0, 2.0, 1.0, 0.0, 1.0, "log")
    with pytest.raises(ValueError, match="variant"):
        faces.face_frames("fp", "perspective", 1.0, 100.0, 60.0, [0.0, 1.0, 0.0])
