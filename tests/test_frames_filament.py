"""Filament 1.53.4 (npm, WebGL 2) drawn in headless Chromium on SwiftShader, against the exact shadows.

The page draws the frame twice (receivers on and off) and the shadow factor is the ratio of the
two 8-bit colours (aliasing.frames.single.Filament); positions and normals are the toolkit's eye
pass through the camera Filament holds.  Checked here, at 256 × 144 with one browser:

* the page renders, the camera Filament holds is the toolkit's, and the pixels it drew are the
  eye pass's but for the silhouettes;
* the factor is 1 to 1/255 on every pixel of a face-on, fully lit ground;
* the engine's shadow mask agrees with the exact shadows on >= 99 % of the pixels away from edges,
  with acne under 1 % and a lit gap under 1 px at the boxes' feet;
* what the frames refuse for Filament (a camera path, the map read-back, a ShadowOptions value the
  binding cannot set) is one line and exit 2, before any browser starts.

Without Chromium, npm or Playwright the browser tests skip with one line, except under CI
(``CI=true``), where that is a failure.
"""

from __future__ import annotations


import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from hypothesis.extra import numpy as hnp
from scipy import ndimage

from aliasing import cli, setups
from aliasing.frames import browser as fb
from aliasing.frames import predict, scenes
from aliasing.frames.models import FILAMENT
from aliasing.frames.run import frame_setup
from conftest import need_frames

CAMERA = dict(near=0.5, far=60.0, fov=50.0, aspect=16 / 9)
SPEC = "near=0.5,far=60,fov=50,aspect=16:9,height=144"


@pytest.fixture(scope="module")
def frames():
    need_frames("filament", "Filament")
    setup = setups.build("filament", {}, SPEC, "35@30")
    boxes = scenes.frame_scene("boxes", **CAMERA)
    ground = scenes.frame_scene("boxes", **CAMERA, boxes=0, ground_cells=2)
    with fb.Browser(timeout=120) as b:
        return {"boxes": frame_setup(b, setup, boxes), "overhead": frame_setup(b, setup, ground, sun=[0.0, 1.0, 0.0])}


def test_the_page_renders_with_the_toolkits_camera(frames):
    for r in frames.values():
        d = r.report["details"]
        assert r.report["engine"] == "filament" and d["engine_revision"] == "1.53.4" and "SwiftShader" in d["renderer"]
        assert d["relit_changed"] == 0                       # the lit frame drawn again is the same, byte for byte
        assert d["view_vs_toolkit"] == 0 and d["projection_vs_toolkit"] < 5e-8
        assert d["pixels"] > 10_000
    assert 0 < frames["boxes"].report["details"]["coverage_vs_engine"] < 0.0006   # silhouette pixels only (0.05 %)
    assert frames["overhead"].report["details"]["coverage_vs_engine"] == 0
    # the normals: the unshadowed colour per n·l is one number on the ground and on the boxes' sides
    p5, p50, p95 = frames["boxes"].report["details"]["unlit_per_ndotl"]
    assert 0.84 <= p50 <= 0.86 and p5 >= 0.82 and p95 <= 0.93          # the docs: 0.85 (0.83-0.92)
    rb = frames["boxes"].readback
    assert np.nanmin(rb.shadow) == 0 and np.nanmax(rb.shadow) == 1


def test_the_factor_is_one_on_a_fully_lit_face_on_receiver(frames):
    rb = frames["overhead"].readback
    f = rb.shadow[rb.drawn]
    assert rb.drawn.sum() > 10_000
    assert np.all(np.abs(f - 1) <= 1 / 255)
    assert frames["overhead"].report["details"]["unlit_min_facing"] >= 208   # precision of the ratio: better than 1/128


def test_the_shadows_agree_with_the_exact_ones(frames):
    r = frames["boxes"]
    m = r.report["measured"]
    assert r.report["details"]["agreement_vs_exact"] >= 0.995    # the docs: 100 % (asked: >= 99 %)
    assert 0.0025 <= m["acne"] < 0.0035 and 0.18 <= m["gap_px"] < 0.28   # the docs: 0.3 %, 0.23 px
    assert m["shadow_agreement"] is None and r.report["predicted"]["acne"] is None    # not predicted: said why
    assert "LiSPSM" in r.report["details"]["not_predicted"]
    # the ratio sees shading below the 1/2 threshold: lit ground far from any exact shadow that reads 0.97-0.99
    rb, ref = r.readback, r.reference
    far = ref & ~ndimage.binary_dilation(~ref & rb.drawn, iterations=3) & ndimage.binary_erosion(rb.drawn, iterations=3)
    part = np.mean(rb.shadow[far] < 1 - 1 / 255)
    assert 0.205 <= part < 0.215 and np.min(rb.shadow[far]) > 0.6     # the docs: 21 %, none below 0.6


@pytest.mark.parametrize("extra, message", [
    (["--path", "sideways:0.1"], "--path: the camera path is rendered for threejs, babylon, playcanvas, godot only (not for filament)"),
    (["--maps", "64"], "--maps: the shadow maps are read back for three.js's CSM, Babylon.js's CascadedShadowGenerator and PlayCanvas's directional light only (not yet for filament)"),
    (["--set", "mapSize=2048"], "mapSize: Filament 1.53.4's JavaScript binding cannot set ShadowOptions"),
    (["--set", "lispsm=false"], "lispsm: Filament 1.53.4's JavaScript binding cannot set ShadowOptions"),
])
def test_cli_refusals_are_one_line(extra, message, capsys, tmp_path):
    code = cli.main(["frames", "--engine", "filament", "--scene", "boxes", "--camera", SPEC, "--sun", "35@30", "--out", str(tmp_path), *extra])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and message in err


def test_cli_refuses_an_odd_width_minus_height(capsys, tmp_path):
    code = cli.main(["frames", "--engine", "filament", "--scene", "boxes", "--camera", "near=0.5,far=60,fov=50,aspect=1.5,height=101",
                     "--sun", "35@30", "--out", str(tmp_path)])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and "need an even width − height" in err and "got 152×101" in err


@settings(max_examples=60, deadline=None)
@given(st.dictionaries(st.sampled_from(sorted(FILAMENT.defaults) + ["lispsm", "bias"]),
                       st.one_of(st.integers(-5, 5000), st.floats(allow_nan=True), st.booleans(), st.text(max_size=3)), max_size=3))
def test_settings_are_the_defaults_or_one_refusal(given_settings):
    try:
        got = FILAMENT.settings(given_settings)
    except ValueError as e:
        assert "\n" not in str(e)
    else:
        assert got == FILAMENT.defaults and all(FILAMENT.defaults[k] == v for k, v in given_settings.items())


@settings(max_examples=60, deadline=None)
@given(hnp.arrays(np.float64, (4, 3, 3), elements=st.floats(-1e3, 1e3)),
       hnp.arrays(np.float64, 3, elements=st.floats(-1, 1)))
def test_the_reference_box_holds_the_scene(tri, sun):
    if not np.linalg.norm(sun) > 0:
        with pytest.raises(ValueError, match="sun must be"):
            FILAMENT.reference_matrix(tri, sun)
        return
    m = FILAMENT.reference_matrix(tri, sun)
    p = predict.to_map(m, tri)
    assert np.all(p >= -1e-9) and np.all(p <= 1 + 1e-9)
    # the depth axis runs along the light: nearer the sun, smaller depth
    a, b = np.zeros(3), np.asarray(sun) / np.linalg.norm(sun)
    assert predict.to_map(m, b)[2] < predict.to_map(m, a)[2]
