"""aliasing validate --scene FILE (aliasing.raster.validate.scene)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from aliasing import cli
from aliasing.raster import scenes
from aliasing.raster.scenes import camera, procedural
from aliasing.raster.validate import scene as scene_validate
from aliasing.pictures import scenerender

pytest.importorskip("trimesh")


@pytest.fixture(scope="module")
def glb(tmp_path_factory):
    path = tmp_path_factory.mktemp("vscene") / "city.glb"
    cam = camera.look_at([-40.0, 6.0, -35.0], [0.0, 0.0, 0.0], near=0.5, far=90.0, fov=60.0)
    procedural.to_glb(procedural.city(2000, seed=2, size=60.0), path, {"view": cam})
    return path


@pytest.mark.parametrize("scheme,splits", [("Standard", None), ("ZP3+LogP", None), ("FPc+P", None), ("P", "bgfx")])
def test_scene_within_analytic_bound(glb, scheme, splits):
    st = scenes.setup(str(glb), camera="view", light_dir="-1,0.8,0.3")
    r = scene_validate.validate_scene(st, scheme, res=96, splits=splits)
    assert r["passed"] and sum(r["pixels"]) > 1000
    measured = np.array(r["measured_M_x"] + r["measured_M_z"], float)
    assert np.nanmax(measured) > 0
    # not half-way oriented surfaces: projection factors spread around 1, reported apart
    assert r["projection_p10"] < r["projection_median"] < r["projection_p90"]


def test_validate_cli_scene(glb, capsys):
    code = cli.main(["validate", "--scheme", "P", "--splits", "threejs-csm", "--scene", str(glb), "--camera", "view",
                     "--light-dir=-1,0.8,0.3", "--res", "64", "--format", "json"])
    out, err = capsys.readouterr()
    assert code == 0, err
    r = json.loads(out)
    assert r["scheme"] == "threejs-csm+P" and r["maps"] == 3 and r["passed"]
    code = cli.main(["validate", "--scheme", "ZP2+P", "--scene", str(glb), "--camera", "view", "--res", "64"])
    out, _ = capsys.readouterr()
    assert code == 0 and "projection factor" in out and "PASS" in out
    for args, message in ((["--scene", str(glb), "--camera", "nope"], "camera 'nope'"), (["--splits", "log"], "--splits needs --scene"),
                          ([], "--f-over-n is required"), (["--scene", str(glb), "--camera", "view", "--splits", "nope"], "split method")):
        assert cli.main(["validate", "--scheme", "P", "--res", "32", *args]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and message in err, err
