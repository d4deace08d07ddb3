"""Pictures from the rasterizer (aliasing.pictures), the render CLI, figure scripts."""

from __future__ import annotations

import importlib

import numpy as np
import pytest

from aliasing import cli
from aliasing import raster
from aliasing import pictures
from aliasing.raster import scenes


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
    box = scenes.builtin._box(np.array([[0.0, 0.0, 6.0]]), np.array([[1.0, 0.3, 1.0]]))  # floats 0.7 above the ground
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


def _ray_hits_box(p: np.ndarray, lo: np.ndarray, hi: np.ndarray, towards: np.ndarray) -> np.ndarray:
    """Exact shadow of an axis-aligned box: does the ray p + λ·towards (λ > 0) meet it? (slab test)"""
    with np.errstate(divide="ignore", invalid="ignore"):
        t1, t2 = (lo - p) / towards, (hi - p) / towards
    enter = np.nanmax(np.minimum(t1, t2), axis=-1)
    leave = np.nanmin(np.maximum(t1, t2), axis=-1)
    return leave >= np.maximum(enter, 1e-9)


@pytest.mark.parametrize("scheme", ["Standard", "LogP"])
def test_box_shadow_touches_the_box_and_ground_has_no_acne(scheme):
    """One box (1 high) on the ground, 256² texels, the raster-shadows light: Standard's texels are
    0.6 × 0.5 world units there, so a bias scaled by the texel's depth change (the former 1.5 texels)
    exceeded the box and its shadow came loose ("peter-panning"); the plane tests of
    pictures.shadow_test keep it attached, and planar ground still never shadows itself."""
    light = "gamma:110@azimuth:60"  # towards +x (and up, behind the eye): shadows fall towards −x
    ground = np.array([[[-200, -1, 0.5], [200, -1, 0.5], [200, -1, 150]], [[-200, -1, 0.5], [200, -1, 150], [-200, -1, 150]]], float)
    centre, half = np.array([1.5, -0.5, 6.0]), np.array([0.5, 0.5, 0.5])
    sc = scenes.Scene(np.concatenate([ground, scenes.builtin._box(centre[None], half[None])]), np.full(14, -1, np.int64))
    v = pictures.view(1.0, 100.0, 60.0, light, scheme, image_res=384, budget=256**2, scene=sc)
    on_ground = (v.triangle >= 0) & (v.triangle < 2)
    p = np.nan_to_num(v.position)
    shadow = on_ground & _ray_hits_box(p, centre - half, centre + half, v.light)
    # the ground along the box's base on the side away from the light (within 0.1 of the face x = 1)
    beside = on_ground & (p[..., 0] > 0.9) & (p[..., 0] < 1.0) & (np.abs(p[..., 2] - 6.0) < 0.25)
    assert beside.sum() >= 20 and shadow[beside].all()
    assert not v.lit[beside].any()
    # most of the exact shadow is drawn (what is missed lies within a texel of its outline)
    assert v.lit[shadow].mean() < 0.15
    # lit ground away from the box (the shadow reaches ≈ 2.6 from its centre): no acne
    open_ground = on_ground & ~shadow & (np.hypot(p[..., 0] - 1.5, p[..., 2] - 6.0) > 5.0)
    assert open_ground.sum() > 10000
    assert 1 - v.lit[open_ground].mean() < 0.01


def test_shadow_test_inputs():
    lm = raster.light_map(1.0, 10.0, 60.0, "overhead", "P")
    tri = np.array([[[-20, -1, 0.5], [20, -1, 0.5], [0, -1, 30]]], float)
    sm = raster.shadow_map(tri, lm, 8)
    p, n = np.array([[0.0, -1.0, 5.0]]), np.array([[0.0, 1.0, 0.0]])
    assert pictures.shadow_test(lm, sm, tri, p, n).tolist() == [True]
    with pytest.raises(ValueError, match=r"bias must be in \[0, inf\]"):
        pictures.shadow_test(lm, sm, tri, p, n, bias=-1.0)
    with pytest.raises(ValueError, match="same shape"):
        pictures.shadow_test(lm, sm, tri, p, n[:, :2])
    with pytest.raises(ValueError, match="scene of sm"):
        pictures.shadow_test(lm, sm, tri[:0], p, n)
    with pytest.raises(ValueError, match=r"bias must be in \[0, inf\]"):
        pictures.view(1.0, 10.0, 60.0, "overhead", image_res=8, budget=8**2, bias=-1.0)


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
    """One scheme on the built-in scene: a labelled figure (not a bare image) and the statistics table."""
    from matplotlib.image import imread

    out = tmp_path / "r.png"
    for what in ("shadows", "grid", "error"):
        assert _run(["render", "--scheme", "P", "--f-over-n", "50", "--fov", "60", "--light", "overhead", "--what", what,
                     "--out", str(out), "--res", "64", "--image-res", "48"], capsys) == 0
        assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        h, w = imread(out).shape[:2]
        assert h > 48 and w > 48 and (w > h) == (what == "error")  # a titled panel; the error's colour bar beside it
        text = capsys.readouterr().out
        assert text.splitlines()[0] == str(out) and "p99" in text and "analytic_max" in text  # the statistics, always
    assert _run(["render", "--scheme", "Nope", "--out", str(out), "--image-res", "16"], capsys) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    assert _run(["render", "--f-over-n", "1", "--out", str(out)], capsys) == 2
    assert "--f-over-n must be > 1" in capsys.readouterr().err
    (tmp_path / "folder.png").mkdir()
    assert _run(["render", "--out", str(tmp_path / "folder.png")], capsys) == 2 and "is a folder" in capsys.readouterr().err
    with pytest.raises(SystemExit) as e:
        _run(["render", "--what", "bad", "--out", str(out)], capsys)
    assert e.value.code == 2


@pytest.mark.parametrize("scheme, light", [("LogP", "gamma:60@azimuth:30"), ("ZP3+P", "overhead"), ("FPc+LogP", "gamma:150")])
def test_one_render_path_keeps_the_bare_images_pixels(scheme, light):
    """``render``'s single-scheme pictures once were the bare images of shadow_image, grid_image and error_image;
    every case now goes through the labelled figure (scenerender): the panels hold the same pixels, the grid's
    scene lightened under its lines and the error greyed where it is not measured, at full resolution."""
    from aliasing.pictures import scenerender

    kw = dict(image_res=48, budget=64**2, seed=1)
    r = scenerender.render(scenerender.builtin(1.0, 50.0, 60.0, light, seed=1), [scheme], budget=64**2, image_res=48)
    hit = r[0].view.triangle[::-1] >= 0
    panels = {}
    for what in ("shadows", "grid", "error"):
        fig = scenerender.figure(r, what, every=4)
        fig.canvas.draw()
        panels[what] = np.asarray(fig.axes[0].images[0].get_array())
        assert min(fig.axes[0].get_window_extent().size) >= 48  # no pixel of the render lost
        assert scheme in fig.axes[0].get_title() and "p99" in fig.axes[0].get_title()
    np.testing.assert_array_equal(panels["shadows"], pictures.shadow_image(1.0, 50.0, 60.0, light, scheme, **kw))
    old = pictures.grid_image(1.0, 50.0, 60.0, light, scheme, every=4, **kw)
    line = np.any(old != panels["shadows"], axis=-1)  # the grid's lines
    assert line.sum() > 100
    np.testing.assert_array_equal(panels["grid"][line], old[line])
    np.testing.assert_allclose(panels["grid"][~line], 0.55 * old[~line] + 0.45, rtol=0, atol=1e-15)
    old, err = pictures.error_image(1.0, 50.0, 60.0, light, scheme, **kw)
    measured = r[0].measured[::-1]
    assert 0.2 < measured.mean() < 0.8
    np.testing.assert_array_equal(panels["error"][measured], old[measured])
    np.testing.assert_array_equal(panels["error"][hit & ~measured], 0.6 * old[hit & ~measured] + 0.25)
    np.testing.assert_array_equal(panels["error"][~hit], old[~hit])
    np.testing.assert_array_equal(r[0].error[::-1][measured], err[measured])


def test_large_render_panel_keeps_every_pixel():
    from aliasing.pictures import scenerender

    r = scenerender.render(scenerender.builtin(1.0, 20.0, 60.0, "gamma:60", seed=1), ["P"], budget=64**2, image_res=400)
    fig = scenerender.figure(r, "shadows")
    fig.canvas.draw()
    assert min(fig.axes[0].get_window_extent().size) >= 400 and fig.dpi == scenerender.DPI


@pytest.mark.parametrize("mod", ["raster_shadows", "raster_grid", "raster_error", "raster_cdf"])
def test_figure_scripts_write_files(tmp_path, mod):
    m = importlib.import_module(f"aliasing.figures.{mod}")
    paths = m.main(tmp_path)
    assert {p.suffix for p in paths} == {".png", ".csv"} and all(p.stat().st_size > 0 for p in paths)


def test_render_cli_seeded_side_by_side_and_json(tmp_path, capsys):
    """Several schemes on the seeded scene (eye space), --what cdf, --splits and --format json."""
    import json

    out = tmp_path / "cdf.png"
    assert _run(["render", "--scheme", "Standard,ZP3+P", "--what", "cdf", "--f-over-n", "50", "--out", str(out), "--res", "64", "--image-res", "40"], capsys) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and "ZP3+P" in capsys.readouterr().out
    assert _run(["render", "--scheme", "LogP", "--splits", "practical", "-k", "3", "--lambda", "0.5", "--far", "50", "--res", "64", "--image-res", "40",
                 "--format", "json"], capsys) == 0
    rep = json.loads(capsys.readouterr().out)
    assert rep["schemes"][0]["scheme"] == "practical+LogP" and [c["far"] for c in rep["schemes"][0]["cascades"]][-1] == 50.0
    assert _run(["render", "--scheme", "P", "--eye", "0,0,0", "--out", str(out)], capsys) == 2
    assert "--eye needs --scene" in capsys.readouterr().err
