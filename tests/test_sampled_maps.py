"""Light depth maps drawn only at the texels looked up: the same values as the whole map, everywhere they are read.

* ``raster.draw.rasterize_at`` against ``rasterize`` at random texels of random triangles (Hypothesis);
* ``TexelStore`` with a slot table against the sorted one, and its tables handed on clean;
* each engine's factor function through sampled maps (``frames.lightmaps.sampled.gathered``) against the whole maps, bit for bit,
  on the reference scene at the engines' filters; the exact reference the same; a second run over drawn texels in one pass;
* ``frames.seen.count`` the same with its suns on threads as on one.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aliasing import setups
from aliasing.frames import predict, seen
from aliasing.frames.models import MODELS
from aliasing.frames.scenes import sun_direction
from aliasing.frames.seen import wrong
from aliasing.frames.seen.synth import eye_geometry, light_matrices
from aliasing.raster.draw import rasterize, rasterize_at
from aliasing.raster.draw import core

CAMERA = "near=0.5,far=60,fov=50,aspect=16:9,height=720"

_coord = st.floats(-0.2, 1.2, allow_nan=False)
_tri = st.tuples(*[st.tuples(_coord, _coord, st.floats(0, 1, allow_nan=False))] * 3)


@settings(max_examples=60, deadline=None)
@given(st.lists(_tri, min_size=1, max_size=8), st.integers(1, 48), st.data())
def test_rasterize_at_is_the_whole_map_at_those_texels(tris, res, data):
    tri = np.array(tris, float)
    whole = rasterize(tri, res)
    n = data.draw(st.integers(0, 40))
    row = np.array(data.draw(st.lists(st.integers(0, res - 1), min_size=n, max_size=n)), np.int64)
    col = np.array(data.draw(st.lists(st.integers(0, res - 1), min_size=n, max_size=n)), np.int64)
    d, t = rasterize_at(tri, res, row, col)
    assert np.array_equal(d, whole.depth[row, col]) and np.array_equal(t, whole.triangle[row, col])


@pytest.mark.parametrize("row, col", [([0.5], [1]), ([1], [-1]), ([1, 2], [1]), ([4], [0])])
def test_rasterize_at_refuses_texels_outside_the_map_by_name(row, col):
    with pytest.raises(ValueError, match="row and col"):
        rasterize_at([[[0, 0, 0], [1, 0, 0], [0, 1, 0]]], 4, np.array(row), np.array(col))


@settings(max_examples=40, deadline=None)
@given(st.lists(st.lists(st.integers(0, 63), max_size=30), min_size=1, max_size=6))
def test_texel_stores_with_and_without_a_table_agree(batches):
    table, keys = core.TexelStore(size=64), core.TexelStore()
    for batch in batches:
        flat = np.array(batch, np.int64)
        miss = keys.missing(flat)
        assert np.array_equal(table.missing(flat), miss) and miss.tolist() == sorted(set(batch) - set(keys._flat.tolist()))
        for s in (table, keys):
            s.add(miss, miss * 0.5, miss + 1)
        assert table.holds(flat) and keys.holds(flat)
        for a, b in zip(table.get(flat), keys.get(flat)):
            assert np.array_equal(a, b) and np.array_equal(a, flat * 0.5 if a.dtype.kind == "f" else flat + 1)


def test_a_released_table_serves_the_next_store_clean():
    size = 4099  # a size no other store uses
    first = core.TexelStore(size=size)
    first.missing(np.arange(0, size, 2))  # makes its mark table
    first.add(np.arange(0, size, 2), np.zeros(2050), np.zeros(2050, np.int64))
    table = first._slot
    first.release()
    second = core.TexelStore(size=size)
    assert second._slot is table and not table.any()  # the same memory, zeroed where it was written
    assert second.missing(np.array([0, 2, 4])).tolist() == [0, 2, 4] and len(first) == 0


def _frame(engine, settings, elevation=35.0, height=72):
    s = setups.build(engine, settings, CAMERA, elevation)
    where = seen.sample(s, height=height, suns=1)
    model, st_ = seen.synth.engine_settings(s)
    fs = where.scene
    sun = sun_direction(elevation, 0.0, fs.camera)
    mats = light_matrices(model, st_, fs, sun, where.width / where.height)
    pos, nrm, drawn = where.geometry
    depth = np.where(drawn, fs.camera.to_eye(np.nan_to_num(pos))[..., 2], np.nan)
    return model, st_, fs, sun, mats, np.nan_to_num(pos), np.nan_to_num(nrm), drawn, depth


@pytest.mark.parametrize("map_type, radius", [("PCFShadowMap", 1.0), ("PCFShadowMap", 3.0), ("BasicShadowMap", 1.0)])
def test_threejs_factor_through_sampled_maps_is_the_whole_maps(map_type, radius):
    model, s, fs, sun, mats, pts, nrm, drawn, depth = _frame("threejs", {"cascades": 3, "shadowMapSize": 1024})
    sel = model.select(s, fs.camera, depth)
    cast = fs.triangles[predict.casting(fs.triangles, sun, model.cast_side(s))]
    h, w = depth.shape
    fy, fx = np.mgrid[0:h, 0:w]

    def factor(maps):
        return predict.threejs_factor(maps, mats, sel, pts, nrm, fx + 0.5, (h - 1 - fy) + 0.5, bias=-1e-4, normal_bias=0.02,
                                      radius=radius, map_type=map_type)

    whole = factor([predict.light_depth_map(cast, m, 1024) for m in mats])
    sampled = [predict.sampled_depth_map(cast, m, 1024) for m in mats]
    assert np.array_equal(predict.gathered(lambda: factor(sampled), sampled), whole)
    assert 0 < sum(m.texels for m in sampled) < 3 * 1024**2 / 10  # a tenth of the texels at most


@pytest.mark.parametrize("quality", [0, 1, 2])
def test_babylon_factor_through_sampled_maps_is_the_whole_maps(quality):
    model, s, fs, sun, mats, pts, nrm, drawn, depth = _frame("babylon", {"numCascades": 3, "mapSize": 1024})
    sel = model.select(s, fs.camera, depth)
    edges = model.edges(s, fs.camera)
    cast = fs.triangles[predict.casting(fs.triangles, sun, model.cast_side(s))]

    def factor(maps):
        return predict.babylon_factor(maps, mats, sel, depth, pts, ends=edges[1:], lengths=np.diff(edges), blend_factor=10.0,
                                      bias=2e-4, quality=quality)

    whole = factor([predict.light_depth_map(cast, m, 1024) for m in mats])
    sampled = [predict.sampled_depth_map(cast, m, 1024) for m in mats]
    assert np.array_equal(predict.gathered(lambda: factor(sampled), sampled), whole)


@pytest.mark.parametrize("cascades, taps", [(1, 1), (4, 3), (4, 5), (2, 3)])
def test_playcanvas_atlas_through_sampled_maps_is_the_whole_atlas(cascades, taps):
    model, s, fs, sun, mats, pts, nrm, drawn, depth = _frame("playcanvas", {"numCascades": cascades, "shadowResolution": 1024})
    sel = model.select(s, fs.camera, depth)
    cast = fs.triangles[predict.casting(fs.triangles, sun, model.cast_side(s))]
    cells = model.cells(s)

    def factor(atlas):
        return predict.playcanvas_factor(atlas, mats, sel, pts, nrm, normal_offset=0.05, taps=taps)

    whole = factor(predict.playcanvas_atlas(cast, mats, cells, 1024, 0.2))
    atlas = predict.playcanvas_atlas(cast, mats, cells, 1024, 0.2, sampled=True)
    assert np.array_equal(predict.gathered(lambda: factor(atlas), [atlas]), whole)
    sub = predict.playcanvas_atlas(cast, mats, cells, 1024, 0.2, subpixel_bits=4)
    sub_sampled = predict.playcanvas_atlas(cast, mats, cells, 1024, 0.2, subpixel_bits=4, sampled=True)
    assert np.array_equal(predict.gathered(lambda: factor(sub_sampled), [sub_sampled]), factor(sub))


def test_a_second_run_over_drawn_texels_runs_once_and_a_first_records_then_draws():
    model, s, fs, sun, mats, pts, nrm, drawn, depth = _frame("threejs", {"cascades": 2, "shadowMapSize": 512})
    sel = model.select(s, fs.camera, depth)
    cast = fs.triangles[predict.casting(fs.triangles, sun, model.cast_side(s))]
    maps = [predict.sampled_depth_map(cast, m, 512) for m in mats]
    runs = []

    def factor(bias):
        runs.append(bias)
        return predict.threejs_factor(maps, mats, sel, pts, nrm, pts[..., 0] * 0, pts[..., 0] * 0, bias=bias, normal_bias=0.0, radius=1.0)

    predict.gathered(lambda: factor(0.0), maps)
    assert len(runs) == 3  # tried (a texel missing), recorded, run
    drawn_texels = [m.texels for m in maps]
    predict.gathered(lambda: factor(-1e-3), maps)  # another bias reads the same texels
    assert len(runs) == 4 and [m.texels for m in maps] == drawn_texels


def test_the_exact_reference_is_the_same_kept_or_not():
    s = setups.build("playcanvas", {"numCascades": 2}, CAMERA, "30..50")
    where = seen.sample(s, height=48, suns=2)
    first = wrong.count(s, where).total
    with seen.remember():
        kept = [wrong.count(s.with_settings(shadowBias=b), where).total for b in (0.2, 0.2, 0.05)]
    assert kept[0] == kept[1] and kept == [wrong.count(s.with_settings(shadowBias=b), where).total for b in (0.2, 0.2, 0.05)]
    assert first == wrong.count(s, where).total


def test_suns_on_threads_count_as_on_one(monkeypatch):
    s = setups.build("babylon", {"numCascades": 2, "mapSize": 512}, CAMERA, "20..60")
    where = seen.sample(s, height=48, suns=3)
    threads = wrong.count(s, where).to_dict()
    monkeypatch.setattr(wrong, "WORKERS", 1)
    assert wrong.count(s, where).to_dict() == threads
