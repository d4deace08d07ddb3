"""The View carried as a value: one validation of the field of view per public call, and the
field of view converted to radians only in aliasing/view.py."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

import aliasing._validation as check
import aliasing.view as view_module
from aliasing import View, raster, schemes
from aliasing import pictures
from aliasing.raster.draw.cascades import cascade_set
from aliasing.raster.validate.single import validate

ROOT = Path(__file__).resolve().parents[1] / "aliasing"
FIGURES = ROOT.parent / "figures"  # aliasing/figures links here


@pytest.fixture
def counts(monkeypatch):
    """Count Views built (``View.__post_init__``) and field-of-view validations (``check.fov``)."""
    seen = {"view": 0, "fov": 0}
    post, fov = view_module.View.__post_init__, check.fov

    def counted_post(self):
        seen["view"] += 1
        return post(self)

    def counted_fov(*args, **kwargs):
        seen["fov"] += 1
        return fov(*args, **kwargs)

    monkeypatch.setattr(view_module.View, "__post_init__", counted_post)
    monkeypatch.setattr(check, "fov", counted_fov)
    return seen


@pytest.mark.parametrize("scheme", ["P", "ZP3+LogP", "FPc+P", "FP+ZP2+LogP", "lispsm"])
def test_measure_builds_one_view(counts, scheme):
    raster.measure(1.0, 100.0, 60.0, "gamma:60@azimuth:30", scheme, resolution=64, cells=4)
    assert counts == {"view": 1, "fov": 1}


def test_measure_with_a_view_builds_none(counts):
    v = View(1.0, 100.0, 60.0)
    counts.update(view=0, fov=0)
    raster.measure(v, "overhead", "ZP2+P", resolution=64, cells=4)
    assert counts == {"view": 0, "fov": 0}


@pytest.mark.parametrize("scheme", ["ZP2+P", "FPcs+LogP"])
def test_validate_builds_one_view(counts, scheme):
    validate(scheme, 50, 60, "gamma:60", res=64, probes=4)
    assert counts == {"view": 1, "fov": 1}


@pytest.mark.parametrize("scheme", ["Standard", "ZP4+LogP", "FPc+P", "P"])
def test_evaluate_builds_one_view(counts, scheme):
    schemes.evaluate(scheme, 1.0, 1000.0, 60.0, "hemisphere:50")
    assert counts == {"view": 1, "fov": 1}


def test_render_view_and_cascades_build_one_view(counts):
    pictures.view(1.0, 50.0, 60.0, "gamma:40", "ZP2+P", image_res=32, budget=64**2, boxes=2, ground_cells=2)
    assert counts == {"view": 1, "fov": 1}
    counts.update(view=0, fov=0)
    cascade_set(1.0, 100.0, 60.0, "overhead", "P", splits="practical", k=3, lam=0.5)
    assert counts == {"view": 1, "fov": 1}


def test_view_and_loose_numbers_agree_bit_for_bit():
    v = View(1.0, 100.0, 60.0)
    for loose, with_view in [
        (raster.measure(1.0, 100.0, 60.0, "gamma:50", "ZP2+P", resolution=64, cells=4), raster.measure(v, "gamma:50", "ZP2+P", resolution=64, cells=4)),
        (raster.measure(1.0, 100.0, 60.0, "gamma:50", "FP+LogP", resolution=64, cells=4), raster.measure(v, light="gamma:50", scheme="FP+LogP", resolution=64, cells=4)),
    ]:
        for key in ("m_x", "m_z", "M_x", "M_z", "measured_x", "measured_z"):
            assert np.array_equal(getattr(loose, key), getattr(with_view, key), equal_nan=True), key
    a = raster.probes(1.0, 100.0, 60.0, "front", cells=3).triangles
    b = raster.probes(v, "front", cells=3).triangles
    assert np.array_equal(a, b)
    assert np.array_equal(raster.ground_and_boxes(v, boxes=3).triangles, raster.ground_and_boxes(1.0, 100.0, 60.0, boxes=3).triangles)
    tri = raster.ground_and_boxes(v, boxes=3).triangles
    assert np.array_equal(raster.eye_pass(tri, v, 32).position, raster.eye_pass(tri, 60.0, 32).position, equal_nan=True)
    r1, r2 = validate("P", 100, 60, "gamma:70", res=64, probes=4), validate("P", v, "gamma:70", res=64, probes=4)
    assert r1 == r2


def test_view_arguments_refused_twice():
    v = View(1.0, 100.0, 60.0)
    with pytest.raises(ValueError, match="once"):
        raster.light_map(v, "overhead", "P", light="front")
    with pytest.raises(ValueError, match="light required"):
        raster.map_set(v)
    with pytest.raises(ValueError, match="fov"):
        raster.map_set(1.0, 100.0, 200.0, "overhead")


# Angles other than the field of view that are converted to radians outside view.py, each
# with the reason (file, the text inside np.radians(...)).
OTHER_ANGLES = {
    ("faces.py", "angle"): "the eased axis rotation of the FPcs frames [deg]",
    ("scene.py", "np.asarray(elevations, float)"): "the sun's elevations above the ground (check on a scene)",
    ("scene.py", "azimuth"): "the sun's azimuth from the view direction (check on a scene)",
    ("scene.py", "CLASS_ANGLE"): "the receiver angle that tells ground from walls (check on a scene)",
    ("scenes.py", "el"): "the sun's elevation placed in the engines' frames",
    ("scenes.py", "az"): "the sun's azimuth placed in the engines' frames",
    ("playcanvas.py", "float(a)"): "an entity's Euler rotation angles in a PlayCanvas scene JSON",
    ("paths.py", "8.0"): "the largest angle between two poses' normals at a matched world point (Godot's camera paths)",
    ("paths.py", "i * step"): "the yaw of a turning camera path in the engines' frames (--path turn:DEG, degrees per frame)",
    ("profile.py", 'check.closed_range(angle, "angle", 0.0, 90.0, " degrees")'): "a receiver's angle θ to the light (bias terms)",
    ("profile.py", 'check.finite(azimuth, "azimuth")'): "a receiver's slope azimuth φ (slope bias terms)",
    ("spec.py", "np.asarray(self.elevation[0] if elevation is None else elevation, float)"): "the sun's elevation above the ground",
    ("spec.py", "self.azimuth"): "the sun's azimuth from the view direction",
    ("spec.py", "self.elevation[0] if elevation is None else float(elevation)"): "the sun's elevation above the ground",
    ("command.py", "sun.elevation[0]"): "the sun's elevation (shimmer --sun)",
    ("command.py", "sun.azimuth"): "the sun's azimuth (shimmer --sun)",
    ("table3_hypotheses.py", "(np.arange(n_lat) + 0.5) * 90.0 / n_lat"): "elevation of sampled light directions",
    ("table3_hypotheses.py", "(np.arange(4 * n_lat) + 0.5) * 360.0 / (4 * n_lat)"): "longitude of sampled light directions",
    ("table3_hypotheses.py", "np.linspace(-45.0, 45.0, angles, endpoint=False)"): "rotation angle ψ of the sampled lights",
    ("geometry.py", "r"): "light-direction angles γ, azimuth",
    ("gmnpr.py", "theta_deg"): "the light's angle θ of Gauthier's GMNPR (not the field of view)",
    ("adaptive_warping.py", "check.as_float_array(azimuth, \"azimuth\")"): "light azimuth",
    ("adaptive_warping.py", "g"): "the light angle γ",
    ("warping.py", "check.closed_range(gamma, \"gamma\", 0.0, 180.0, \" degrees\")"): "the light angle γ",
    ("logpsm.py", "ang"): "the light angles of the logpsm sample directions",
    ("lloyd2007_fig30.py", "g"): "the light angle γ of the figure's axis",
    ("plane.py", "_angle(angle, \"angle\", \"between the receiver's normal and the direction to the light\")"): "the receiver's angle to the light",
    ("plane.py", "check.finite(azimuth, \"azimuth\")"): "the receiver's azimuth on the map",
    ("plane.py", "el"): "the light's elevation above the ground",
    ("presets.py", "_angle(angle, \"angle\", \"between the receiver's normal and the direction to the light\")"): "the receiver's angle to the light",
    ("presets.py", "check.finite(azimuth, \"azimuth\")"): "the receiver's azimuth on the map",
    ("projection.py", "el"): "the light's elevation above the ground",
    ("cascades.py", "89.9"): "the grazing limit of the light over the ground",
    ("cascades.py", "ANGLES"): "the sampled receiver angles to the light",
    ("cascades.py", "AZIMUTHS"): "the sampled receiver azimuths",
    ("_bias.py", "np.arange(0.0, 91.0, 5.0)"): "the explorer's receiver azimuths",
    ("_bias.py", "ANGLES"): "the explorer's receiver angles to the light",
    ("bias_threshold.py", "theta"): "the receiver plane's angle to the light",
    ("bias_threshold.py", "phi"): "the receiver plane's azimuth",
}


def _sources():
    return sorted(ROOT.rglob("*.py")) + sorted(FIGURES.glob("*.py"))


def _radians_calls():
    for path in _sources():
        if path.name == "view.py" and path.parent == ROOT:
            continue
        text = path.read_text()
        for m in re.finditer(r"(?:np|math)\.radians\(", text):
            depth, i = 1, m.end()
            while depth:
                depth += {"(": 1, ")": -1}.get(text[i], 0)
                i += 1
            yield path, text[m.end(): i - 1]


def test_field_of_view_converted_only_in_view_py():
    found = list(_radians_calls())
    assert found, "the scan found no np.radians call at all: it is broken"
    for path, arg in found:
        assert "fov" not in arg.lower() and "fv" not in arg, f"{path}: np.radians({arg}) converts a field of view outside view.py"
        reason = OTHER_ANGLES.get((path.name, arg))
        assert reason, f"{path}: np.radians({arg}) is not in the allow-list of other angles"


def test_half_angle_called_only_in_view_py():
    for path in _sources():
        if path.name == "view.py" and path.parent == ROOT:
            continue
        assert "half_angle(" not in path.read_text(), f"{path} calls half_angle: use View.theta / tan_theta / theta_of"
