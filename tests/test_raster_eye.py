"""The eye pass with occlusion culling gives the buffers of the plain z-buffer (issue 12 item 5)."""

from __future__ import annotations

import numpy as np
import pytest

from aliasing import raster
from aliasing.raster.draw import compiled, core, eye, occlusion
from reference_eye import reference_eye_pass  # tests/reference_eye.py: the pre-issue-12 eye pass


def assert_same(eb, ref):
    position, normal, ident = ref
    np.testing.assert_array_equal(eb.triangle, ident)
    np.testing.assert_array_equal(eb.position, position)  # bit for bit (NaN where empty)
    np.testing.assert_array_equal(eb.normal, normal)


NUMBA = pytest.mark.skipif(not compiled.available(), reason="numba (the fast extra) is not installed")
BACKENDS = ["numpy", pytest.param("numba", marks=NUMBA)]


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("res, chunk", [(256, core.CHUNK), (250, 5000)])
def test_eye_pass_identical_to_the_plain_z_buffer_on_a_seeded_scene(res, chunk, backend):
    # the benchmark's kind of scene (ground grid plus boxes over f/n = 1000): much overdraw;
    # 250 is not a multiple of the culling block, and chunk = 5000 forces many groups and batches
    sc = raster.ground_and_boxes(1.0, 1000.0, 60.0, boxes=120, ground_cells=20, seed=3)
    eb = raster.eye_pass(sc.triangles, 60.0, res, chunk=chunk, backend=backend)
    assert_same(eb, reference_eye_pass(sc.triangles, 60.0, res))
    assert 0.3 < (eb.triangle >= 0).mean() < 1


@pytest.mark.parametrize("backend", BACKENDS)
def test_eye_pass_identical_with_ties_and_near_clipping(backend):
    # coplanar duplicates (exact depth ties: the highest index must win, as in triangle order),
    # interpenetrating random triangles and triangles crossing the near plane
    rng = np.random.default_rng(7)
    centre = np.column_stack([rng.uniform(-3, 3, (300, 2)), rng.uniform(3, 9, 300)])
    tri = centre[:, None, :] + rng.uniform(-1, 1, (300, 3, 3))
    crossing = np.column_stack([rng.uniform(-0.05, 0.05, (10, 2)), np.full(10, 0.05)])[:, None, :] + rng.uniform(-0.1, 0.1, (10, 3, 3))
    tri = np.concatenate([tri, crossing, tri[:50], tri[10:20][:, ::-1]])  # 310 + 50 exact duplicates + 10 reversed
    eb = raster.eye_pass(tri, 70.0, 128, backend=backend)
    assert_same(eb, reference_eye_pass(tri, 70.0, 128))
    seen = set(np.unique(eb.triangle).tolist())
    assert seen & set(range(300, 310)) and seen & set(range(310, 360)) and not seen & set(range(50))


@pytest.mark.parametrize("backend", BACKENDS)
def test_culled_z_buffer_matches_plain_one_for_perspective_and_log_rows(backend):
    # the culling bounds are exact for perspective-correct depth (weights w) and uneven rows too
    rng = np.random.default_rng(11)
    tri = rng.uniform(0, 1, (400, 3, 3))
    w = rng.uniform(0.2, 3.0, (400, 3))
    rows = np.sort(rng.uniform(0, 1, 96))
    plain = raster.rasterize(tri, 96, w=w, row_centres=rows, chunk=3000)
    draw = eye.KERNELS[backend]()[0]
    culled = core.zbuffer(tri, 96, 1.0 / w, rows, False, 3000, front_to_back=True, draw=draw)
    np.testing.assert_array_equal(culled.depth, plain.depth)
    np.testing.assert_array_equal(culled.triangle, plain.triangle)
    assert (culled.rasterized, culled.degenerate) == (plain.rasterized, plain.degenerate)


def test_culling_skips_hidden_work(monkeypatch):
    # a near wall hides a far grid: the culled pass sets up the spans of the wall only (hidden
    # triangles and rows are dropped before their spans are computed)
    wall = np.array([[[-9, -9, 2], [9, -9, 2], [0, 9, 2]], [[-9, 9, 2], [9, 9, 2], [9, -9, 2]]], float)
    g = np.linspace(-20, 20, 21)
    far = np.array([[[x, y, 50], [x + 2, y, 50], [x, y + 2, 50]] for x in g for y in g])  # half the image
    tri = np.concatenate([far, wall])
    texels = []
    real_spans = occlusion.row_spans
    monkeypatch.setattr(occlusion, "row_spans", lambda *a: (lambda sp: (texels.append(int(sp.width.sum())), sp)[1])(real_spans(*a)))

    def count(scene):
        texels.clear()
        eb = raster.eye_pass(scene, 60.0, 64, chunk=64)  # groups of 64 rows: the nearest triangles first, alone
        return eb, sum(texels)

    eb, culled = count(tri)
    assert set(np.unique(eb.triangle).tolist()) == {len(far), len(far) + 1}
    assert culled == count(wall)[1]
    assert count(far)[1] > 64 * 64 / 4  # drawn alone, the grid covers a quarter of the image


def test_row_test_drops_the_hidden_rows_of_a_partly_visible_triangle(monkeypatch):
    # a near wall over the lower half of the image and a far backdrop over all of it: the
    # backdrop's box is not hidden, but its rows behind the wall are never set up
    low = np.array([[[-9, -9, 2], [9, -9, 2], [9, 0, 2]], [[-9, -9, 2], [9, 0, 2], [-9, 0, 2]]], float)
    back = np.array([[[-99, -99, 50], [99, -99, 50], [0, 99, 50]]], float)
    rows = []
    real = occlusion.row_spans
    monkeypatch.setattr(occlusion, "row_spans", lambda idx, x0, x1, y0, h, *a: (rows.append(np.repeat(idx, h)), real(idx, x0, x1, y0, h, *a))[1])
    eb = raster.eye_pass(np.concatenate([back, low]), 60.0, 64, chunk=64)
    assert (eb.triangle[:32] >= 1).all() and (eb.triangle[32:] == 0).all()
    assert (np.concatenate(rows) == 0).sum() == 32  # the backdrop's upper 32 rows only


def test_eye_pass_bad_chunk():
    with pytest.raises(ValueError, match="chunk must be"):
        raster.eye_pass(np.zeros((1, 3, 3)) + [[0, 0, 1], [1, 0, 1], [0, 1, 1]], 60.0, 8, chunk=0)


@NUMBA
def test_numba_merge_keeps_nan_and_ties_as_numpy():
    # exact ties (highest index wins) and a NaN depth (sticks, as np.minimum.at leaves it)
    # through both merges on the same spans
    from aliasing.raster.draw.coverage import Spans

    one = np.ones(4)
    sp = Spans(np.array([0, 0, 0, 1]), np.array([5, 2, 7, 3]), np.array([0, 2, 1, 0]), np.array([4, 2, 3, 2]),
               np.array([1.0, 1.0, 2.0, np.nan]), np.zeros(4), one, np.zeros(4))
    out = []
    for merge in (occlusion.merge_visible, compiled.merge):
        depth, ident = np.full(16, np.inf), np.full(16, -1, np.int64)
        far = occlusion._block_far(depth, 4)
        with np.errstate(invalid="ignore"):  # numpy warns on the NaN
            merge(sp, 4, 100, depth, ident, far, np.full(8, 10.0))  # scale: per triangle index
        out.append((depth, ident, far))
    np.testing.assert_array_equal(out[1][0], out[0][0])
    np.testing.assert_array_equal(out[1][1], out[0][1])
    np.testing.assert_array_equal(out[1][1][:8], [5, 5, 5, 5, -1, -1, -1, -1])
    assert np.isnan(out[1][0][4]) and np.isnan(out[1][2][1, 0])


def test_eye_pass_bad_backend(monkeypatch):
    tri = np.zeros((1, 3, 3)) + [[0, 0, 1], [1, 0, 1], [0, 1, 1]]
    with pytest.raises(ValueError, match="backend must be one of"):
        raster.eye_pass(tri, 60.0, 8, backend="cuda")
    monkeypatch.setattr(compiled, "numba", None)  # as without the fast extra
    with pytest.raises(ValueError, match="needs numba"):
        raster.eye_pass(tri, 60.0, 8, backend="numba")


@NUMBA
@pytest.mark.parametrize("seed", range(6))
def test_numba_eye_pass_identical_on_random_scenes(seed):
    # random sizes from slivers to screen-filling, near-plane crossings, exact duplicates,
    # zero-area triangles (a domain case: no warning), odd resolutions, fovs and chunks
    rng = np.random.default_rng(seed)
    n = int(rng.integers(20, 300))
    c = np.column_stack([rng.uniform(-6, 6, (n, 2)), rng.uniform(-1, 12, n)])
    tri = c[:, None, :] + rng.uniform(-3, 3, (n, 3, 3)) * rng.choice([0.02, 0.5, 2], n)[:, None, None]
    tri = np.concatenate([tri, tri[: n // 3]])
    tri[::7, 1] = tri[::7, 0]
    res, fov, chunk = int(rng.integers(1, 150)), float(rng.uniform(30, 150)), int(rng.choice([50, 1 << 20]))
    a = raster.eye_pass(tri, fov, res, chunk=chunk)
    b = raster.eye_pass(tri, fov, res, chunk=chunk, backend="numba")
    np.testing.assert_array_equal(b.triangle, a.triangle)
    np.testing.assert_array_equal(b.position, a.position)
    np.testing.assert_array_equal(b.normal, a.normal)
    np.testing.assert_array_equal(np.signbit(b.position), np.signbit(a.position))  # signed zeros too


@pytest.mark.parametrize("seed", range(4))
def test_numpy_eye_pass_identical_to_the_reference_on_random_scenes(seed):
    # the numpy path alone (row test, piece test, merge steps) against the plain z-buffer:
    # slivers to screen-filling triangles, near-plane crossings, duplicates (exact ties),
    # odd resolutions, fovs and chunks (small chunks: many groups and steps)
    rng = np.random.default_rng(100 + seed)
    n = int(rng.integers(50, 400))
    c = np.column_stack([rng.uniform(-6, 6, (n, 2)), rng.uniform(-1, 12, n)])
    tri = c[:, None, :] + rng.uniform(-3, 3, (n, 3, 3)) * rng.choice([0.02, 0.5, 2], n)[:, None, None]
    tri = np.concatenate([tri, tri[: n // 4]])
    res, fov, chunk = int(rng.integers(20, 160)), float(rng.uniform(30, 150)), int(rng.choice([64, 700, 1 << 20]))
    assert_same(raster.eye_pass(tri, fov, res, chunk=chunk), reference_eye_pass(tri, fov, res))
