"""Pictures from the rasterizer (aliasing.raster.pictures), the render CLI, figure scripts."""

from __future__ import annotations

import importlib

import numpy as np
import pytest

from aliasing import cli
from aliasing.raster import pictures, scenes


def test_pictures_deterministic():
    a = pictures.shadow_image(1.0, 50.0, 60.0, "gamma:60@azimuth:30", "LogP", image_res=64, budget=64**2, boxes=5)
    b = pictures.shadow_image(1.0, 50.0, 60.0, "gamma:60@azimuth:30", "LogP", image_res=64, budget=64**2, boxes=5)
    np.testing.assert_array_equal(a, b)
    e1 = pictures.error_image(1.0, 50.0, 60.0, "overhead", "ZP2+P", image_res=64, budget=64**2, boxes=5)[1]
    e2 = pictures.error_image(1.0, 50.0, 60.0, "overhead", "ZP2+P", image_res=64, budget=64**2, boxes=5)[1]
    np.testing.assert_array_equal(e1, e2)


def test_overhead_box_shadow_under_the_box():
    """A box above the ground, light overhead: ground pixels under it are shadowed, others lit."""
    ground = np.array([[[-20, -1, 1.5], [20, -1, 1.5], [20, -1, 40]], [[-20, -1, 1.5], [20, -1, 40], [-20, -1, 40]]], float)
    box = scenes._box(np.array([[0.0, 0.0, 6.0]]), np.array([[1.0, 0.3, 1.0]]))  # floats 0.7 above the ground
    sc = scenes.Scene(np.concatenate([ground, box]), np.full(14, -1, np.int64))
    v = pictures.view(1.0, 40.0, 60.0, "overhead", "Standard", image_res=128, budget=512**2, scene=sc)
    on_ground = v.triangle >= 0
    on_ground &= v.triangle < 2
    p = v.position
    under = on_ground & (np.abs(p[..., 0]) < 0.9) & (np.abs(p[..., 2] - 6.0) < 0.9)
    away = on_ground & ((np.abs(p[..., 0]) > 1.2) | (np.abs(p[..., 2] - 6.0) > 1.2))
    assert under.sum() > 20 and away.sum() > 1000
    assert not v.lit[under].any()
    assert v.lit[away].all()


def test_grid_and_error_values():
    img = pictures.grid_image(1.0, 100.0, 60.0, "overhead", "ZP4+P", image_res=96, budget=128**2, every=4, boxes=3)
    assert img.shape == (96, 96, 3) and (img == 0).all(-1).any()
    _, err = pictures.error_image(1.0, 100.0, 60.0, "overhead", "P", image_res=96, budget=96**2, boxes=0)
    assert np.nanmax(err) > 0.1 and np.isfinite(err).sum() > 1000
    with pytest.raises(ValueError, match="every"):
        pictures.grid_image(1.0, 10.0, 60.0, "overhead", every=0)


def _run(argv, capsys):
    parser = cli._Parser(prog="aliasing")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=cli._Parser)
    pictures.add_render_parser(sub)
    try:
        args = parser.parse_args(argv)
        return args.run(args)
    except ValueError as exc:
        print(f"aliasing render: error: {exc}", file=__import__("sys").stderr)
        return 2


def test_render_cli(tmp_path, capsys):
    out = tmp_path / "r.png"
    for what in ("shadows", "grid", "error"):
        assert _run(["render", "--scheme", "P", "--f-over-n", "50", "--fov", "60", "--light", "overhead", "--what", what,
                     "--out", str(out), "--res", "64", "--image-res", "48"], capsys) == 0
        assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    capsys.readouterr()
    assert _run(["render", "--scheme", "Nope", "--out", str(out), "--image-res", "16"], capsys) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    with pytest.raises(SystemExit) as e:
        _run(["render", "--what", "bad", "--out", str(out)], capsys)
    assert e.value.code == 2


@pytest.mark.parametrize("mod", ["raster_shadows", "raster_grid", "raster_error", "raster_cdf"])
def test_figure_scripts_write_files(tmp_path, mod):
    m = importlib.import_module(f"aliasing.figures.{mod}")
    paths = m.main(tmp_path)
    assert {p.suffix for p in paths} == {".png", ".csv"} and all(p.stat().st_size > 0 for p in paths)
