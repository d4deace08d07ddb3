"""The numpy rasterizer (aliasing.raster): correctness on hand-made triangles, the loader,
and the validation of the analytic bounds M_x, M_z by measurement on probes."""

from __future__ import annotations

import sys

import numpy as np
import pytest

from aliasing import geometry, raster, schemes
from aliasing.raster import scenes
from aliasing.raster.validate import raycast

R = sys.modules["aliasing.raster.draw"]


# ----------------------------------------------------------------------------- references


def brute_force(tri: np.ndarray, res: int) -> tuple[np.ndarray, np.ndarray]:
    """Coverage count and min depth by testing every texel centre against every triangle.

    Independent of the rasterizer's span logic: barycentric coordinates solved per texel.
    Centres exactly on an edge are excluded here (tests avoid them with random vertices).
    """
    c = (np.arange(res) + 0.5) / res
    s, t = np.meshgrid(c, c)
    p = np.stack([s.ravel(), t.ravel()], -1)  # (P, 2)
    a, b, cc = tri[:, 0, :2], tri[:, 1, :2], tri[:, 2, :2]
    m = np.stack([b - a, cc - a], -1)  # (T, 2, 2)
    inv = np.linalg.inv(m)
    lam = np.einsum("tij,tpj->tpi", inv, p[None] - a[:, None])  # (T, P, 2)
    l0 = 1 - lam[..., 0] - lam[..., 1]
    inside = (l0 > 0) & (lam[..., 0] > 0) & (lam[..., 1] > 0)
    d = l0 * tri[:, None, 0, 2] + lam[..., 0] * tri[:, None, 1, 2] + lam[..., 1] * tri[:, None, 2, 2]
    depth = np.where(inside, d, np.inf).min(0).reshape(res, res)
    return inside.sum(0).reshape(res, res), depth


def random_triangles(n: int, seed: int, lo: float = -0.2, hi: float = 1.2) -> np.ndarray:
    rng = np.random.default_rng(seed)
    tri = rng.uniform(lo, hi, (n, 3, 3))
    tri[..., 2] = rng.uniform(0, 1, (n, 3))
    return tri


# ----------------------------------------------------------------------------- rasterizer


@pytest.mark.parametrize("chunk", [R.CHUNK, 7])
def test_matches_brute_force(chunk):
    tri = random_triangles(60, seed=1)
    m = raster.rasterize(tri, 48, chunk=chunk)
    count, depth = brute_force(tri, 48)
    assert m.degenerate == 0 and m.rasterized == 60
    np.testing.assert_array_equal(np.isfinite(m.depth), count > 0)
    np.testing.assert_allclose(m.depth[count > 0], depth[count > 0], rtol=0, atol=1e-12)
    hit = m.triangle >= 0
    # the id map names a triangle whose interpolated depth is the minimum
    np.testing.assert_array_equal(hit, count > 0)


def test_coverage_is_area_within_edge_pixels():
    rng = np.random.default_rng(7)
    res = 256
    for _ in range(5):
        tri = np.concatenate([rng.uniform(0.05, 0.95, (1, 3, 2)), np.zeros((1, 3, 1))], -1)
        a, b, c = tri[0, :, :2]
        area = abs((b - a)[0] * (c - a)[1] - (b - a)[1] * (c - a)[0]) / 2
        perimeter = sum(np.linalg.norm(p - q) for p, q in ((a, b), (b, c), (c, a)))
        covered = np.isfinite(raster.rasterize(tri, res).depth).sum()
        assert abs(covered - area * res**2) <= perimeter * res  # within one texel along the edges


def test_shared_edges_cover_once_even_through_texel_centres():
    """A triangulated grid whose edges pass exactly through texel centres: every texel once."""
    res, k = 32, 4
    g = (np.arange(k + 1) * (res // k) + 0.5) / res  # vertices on texel centres
    g[0], g[-1] = 0.0, 1.0
    xx, yy = np.meshgrid(g, g)
    p = np.stack([xx, yy, np.zeros_like(xx)], -1)
    a, b, c, d = p[:-1, :-1], p[:-1, 1:], p[1:, 1:], p[1:, :-1]
    tri = np.concatenate([np.stack([a, b, c], -2).reshape(-1, 3, 3), np.stack([a, c, d], -2).reshape(-1, 3, 3)])
    total = sum(np.isfinite(raster.rasterize(t[None], res).depth).astype(int) for t in tri)
    np.testing.assert_array_equal(total, np.ones((res, res), int))
    # reversed winding gives the same coverage
    total_rev = sum(np.isfinite(raster.rasterize(t[None, ::-1], res).depth).astype(int) for t in tri)
    np.testing.assert_array_equal(total_rev, total)


def test_depth_exact_for_planes_affine_and_perspective():
    rng = np.random.default_rng(3)
    tri = random_triangles(20, seed=4, lo=0.0, hi=1.0)
    coef = rng.normal(size=(20, 3))
    tri[..., 2] = coef[:, None, 0] * tri[..., 0] + coef[:, None, 1] * tri[..., 1] + coef[:, None, 2]
    for t, cf in zip(tri, coef):
        m = raster.rasterize(t[None], 64)
        j, i = np.nonzero(np.isfinite(m.depth))
        s_c, t_c = (i + 0.5) / 64, (j + 0.5) / 64
        np.testing.assert_allclose(m.depth[j, i], cf[0] * s_c + cf[1] * t_c + cf[2], rtol=0, atol=1e-12)
    # perspective-correct: the points are (X/W, Y/W) of a 3D plane depth D = a X + b Y + c W
    tri = random_triangles(1, seed=5, lo=0.1, hi=0.9)
    w = np.array([[1.0, 3.0, 7.0]])
    a, b, c = 0.3, -0.7, 0.2
    big_x, big_y = tri[..., 0] * w, tri[..., 1] * w
    tri[..., 2] = (a * big_x + b * big_y + c * w) / 1.0  # D, not affine in (s, t)
    m = raster.rasterize(tri, 64, w=w)
    j, i = np.nonzero(np.isfinite(m.depth))
    s_c, t_c = (i + 0.5) / 64, (j + 0.5) / 64
    # on the plane's points: 1/W is affine in (s, t); D/W = a s + b t + c
    inv_w_plane = np.linalg.solve(np.c_[tri[0, :, :2], np.ones(3)], 1.0 / w[0])
    inv_w = inv_w_plane[0] * s_c + inv_w_plane[1] * t_c + inv_w_plane[2]
    np.testing.assert_allclose(m.depth[j, i], (a * s_c + b * t_c + c) / inv_w, rtol=1e-12)


def test_degenerate_triangles_skipped_and_counted():
    tri = np.array([
        [[0.1, 0.1, 0], [0.9, 0.2, 0], [0.3, 0.8, 0]],  # fine
        [[0.1, 0.1, 0], [0.5, 0.5, 0], [0.9, 0.9, 0]],  # collinear
        [[0.2, 0.2, 0], [0.2, 0.2, 0], [0.6, 0.1, 0]],  # repeated vertex
        [[0.2, np.nan, 0], [0.7, 0.2, 0], [0.6, 0.9, 0]],  # not finite
    ])
    m = raster.rasterize(tri, 32)
    assert (m.rasterized, m.degenerate) == (1, 3)
    assert set(np.unique(m.triangle)) == {-1, 0}


@pytest.mark.parametrize("res", [0, -3, 2.5, R.MAX_RESOLUTION + 1, True])
def test_bad_resolution(res):
    with pytest.raises(ValueError, match="resolution"):
        raster.rasterize(random_triangles(1, 0), res)


def test_bad_scene_input():
    with pytest.raises(ValueError, match="empty"):
        raster.rasterize(np.zeros((0, 3, 3)), 8)
    with pytest.raises(ValueError, match=r"shape \(T, 3, 3\)"):
        raster.rasterize(np.zeros((4, 3)), 8)
    with pytest.raises(ValueError, match="w must be in"):
        raster.rasterize(random_triangles(1, 0), 8, w=[[1.0, 0.0, 1.0]])
    with pytest.raises(ValueError, match="at least 1 triangle"):
        scenes.Scene(np.zeros((0, 3, 3)), np.zeros(0, np.int64))


def test_rows_outside_and_huge_triangles_bounded_by_chunk():
    tri = np.array([[[-50.0, -50.0, 1.0], [60.0, -40.0, 1.0], [0.0, 80.0, 1.0]]])  # covers the map
    m = raster.rasterize(tri, 64, chunk=100)
    assert np.isfinite(m.depth).all()


# ----------------------------------------------------------------------------- shadow maps


@pytest.mark.parametrize("scheme", ["Standard", "P", "LogP"])
def test_inverse_map_round_trip(scheme):
    """LightMap.inverse undoes LightMap.coordinates (eqs. 5–6, 77) both ways; texel_centres are its grid."""
    lm = raster.light_map(1.0, 100.0, 60.0, "gamma:70@azimuth:10", scheme)
    rng = np.random.default_rng(3)
    s, t = rng.uniform(-0.1, 1.1, (2, 500))
    x, y = lm.inverse(s, t)
    xl, _, zl = lm.basis
    pts = x[:, None] * xl + (y + lm.y_offset)[:, None] * zl + rng.normal(size=(500, 1)) * lm.basis[1]
    s2, t2, _, _ = lm.coordinates(pts)
    np.testing.assert_allclose(s2, s, atol=1e-12)
    np.testing.assert_allclose(t2, t, atol=1e-12)
    pv = rng.dirichlet(np.ones(8), 200) @ geometry.frustum_vertices(1.0, 100.0, 60.0)  # points in the view frustum
    sv, tv, _, _ = lm.coordinates(pv)
    xv, yv, _ = lm.light_plane(pv)
    np.testing.assert_allclose(np.stack(lm.inverse(sv, tv)), np.stack([xv, yv]), rtol=1e-10, atol=1e-10)
    cx, cy = lm.texel_centres(8)
    ex, ey = lm.inverse((np.arange(8) + 0.5) / 8, ((np.arange(8) + 0.5) / 8)[:, None])
    np.testing.assert_array_equal(cx, ex)
    np.testing.assert_array_equal(cy, ey)
    with pytest.raises(ValueError, match="must not be NaN"):
        lm.inverse(np.nan, 0.5)


@pytest.mark.parametrize("scheme", ["Standard", "P", "LogP"])
def test_shadow_map_depth_is_exact_light_height(scheme):
    """A slanted plane: each texel stores the height of the plane on the texel's light ray."""
    lm = raster.light_map(1.0, 50.0, 60.0, "gamma:60@azimuth:20", scheme)
    n = np.array([0.2, 1.0, 0.1])
    n /= np.linalg.norm(n)
    cpl = -1.0  # plane n·p = c
    # a big triangle on the plane, around the frustum
    e1 = np.cross(n, [0, 0, 1.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(n, e1)
    o = n * cpl + 25 * e2
    tri = np.array([[o + 500 * e1 - 300 * e2, o - 500 * e1 - 300 * e2, o + 600 * e2]])
    res = 96
    m = raster.shadow_map(tri, lm, res)
    x, y = lm.texel_centres(res)
    xl, yl, zl = lm.basis
    base = x[..., None] * xl + (y + lm.y_offset)[..., None] * zl
    height = (cpl - base @ n) / (yl @ n)
    j, i = np.nonzero(np.isfinite(m.depth))
    assert j.size > res * res // 2
    assert set(np.unique(m.triangle)) <= {-1, 0}  # ids name the input triangle, also after clipping
    np.testing.assert_allclose(-m.depth[j, i], height[j, i], rtol=1e-9, atol=1e-9)


def test_logarithmic_rasterization_against_straight_edges():
    """LogP coverage: a texel is covered iff its centre, mapped back to the light plane by the
    inverse of the log map (eq. 77/84), lies inside the (straight-edged) light-plane triangle."""
    lm = raster.light_map(1.0, 100.0, 60.0, "gamma:70@azimuth:10", "LogP")
    rng = np.random.default_rng(11)
    verts = geometry.frustum_vertices(1.0, 100.0, 60.0)
    res = 128
    x, y = lm.texel_centres(res)
    mismatches = 0
    for _ in range(6):
        w = rng.dirichlet(np.ones(8), size=3)
        tri = (w @ verts)[None]  # a triangle inside the frustum
        m = raster.shadow_map(tri, lm, res)
        tx, ty, _ = lm.light_plane(tri[0])
        a, b, c = np.stack([tx, ty], -1)
        def side(p, q):
            return (q[0] - p[0]) * (y - p[1]) - (q[1] - p[1]) * (x - p[0])
        s1, s2, s3 = side(a, b), side(b, c), side(c, a)
        inside = ((s1 > 0) & (s2 > 0) & (s3 > 0)) | ((s1 < 0) & (s2 < 0) & (s3 < 0))
        covered = np.isfinite(m.depth)
        assert covered.sum() > 20
        mismatches += int((covered != inside).sum())
    assert mismatches <= 2  # rounding at centres within ~1e-12 of an edge


def test_log_row_centres_invert_the_log_map():
    lm = raster.light_map(1.0, 100.0, 60.0, "overhead", "LogP")
    res = 64
    tp = raster.log_row_centres(lm, res)
    depth, npr = float(lm.frustum.depth[0, 0]), lm.n_prime
    y = tp * npr * depth / (npr + depth - tp * depth)
    np.testing.assert_allclose(np.log1p(y / npr) / np.log1p(depth / npr), (np.arange(res) + 0.5) / res, rtol=1e-12)


# ----------------------------------------------------------------------------- eye pass


def test_eye_pass_positions_normals_and_clipping():
    fov, res = 60.0, 32
    tan = np.tan(np.radians(fov / 2))
    # a tilted plane through (0, 0, 5), crossing behind the eye (must be clipped)
    n = np.array([0.0, 0.6, -0.8])
    e1 = np.array([1.0, 0.0, 0.0])
    e2 = np.cross(n, e1)
    o = np.array([0.0, 0.0, 5.0])
    tri = np.array([[o - 100 * e1 - 10 * e2, o + 100 * e1 - 10 * e2, o + 60 * e2]])
    assert (tri[..., 2] < 0).any()
    eb = raster.eye_pass(tri, fov, res)
    hit = eb.triangle >= 0
    assert hit.sum() > res
    pos = eb.position[hit]
    np.testing.assert_allclose((pos - o) @ n, 0, atol=1e-9)
    u, v, z = raster.project(pos, fov)
    j, i = np.nonzero(hit)
    np.testing.assert_allclose(u, (i + 0.5) / res, atol=1e-12)
    np.testing.assert_allclose(v, (j + 0.5) / res, atol=1e-12)
    assert (z > 0).all()
    assert (np.einsum("ij,ij->i", eb.normal[hit], pos) < 0).all()  # facing the eye
    # nearest surface wins
    front = np.array([[[-1, -1, 3.0], [1, -1, 3.0], [0, 1, 3.0]]]) * [tan, tan, 1]
    eb2 = raster.eye_pass(np.concatenate([tri, front]), fov, res)
    assert (eb2.triangle == 1).sum() > 0 and np.allclose(eb2.position[eb2.triangle == 1][:, 2], 3.0)


# ----------------------------------------------------------------------------- scenes, loader


def test_scenes_seeded_and_probes_inside_frustum():
    a = raster.ground_and_boxes(1.0, 100.0, boxes=20, seed=5)
    b = raster.ground_and_boxes(1.0, 100.0, boxes=20, seed=5)
    c = raster.ground_and_boxes(1.0, 100.0, boxes=20, seed=6)
    np.testing.assert_array_equal(a.triangles, b.triangles)
    assert not np.array_equal(a.triangles, c.triangles)
    assert len(a.triangles) == 2 * 20**2 + 12 * 20
    pr = raster.probes(1.0, 100.0, 60.0, "gamma:30@azimuth:40", cells=8)
    assert pr.triangles[..., 2].min() >= 1.0 and pr.triangles[..., 2].max() <= 100.0
    # normals bisect the directions to the eye and to the light
    centre = (pr.triangles[:64, 0] + pr.triangles[:64, 2]) / 2  # first triangle of each square: corners 0 and 2 are opposite
    to_eye = -centre / np.linalg.norm(centre, axis=-1, keepdims=True)
    light = geometry.lights("gamma:30@azimuth:40")[0]
    np.testing.assert_allclose(pr.normals @ light, np.einsum("ij,ij->i", pr.normals, to_eye), atol=1e-12)
    with pytest.raises(ValueError, match="cells"):
        raster.probes(1.0, 10.0, 60.0, "overhead", cells=1)
    with pytest.raises(ValueError, match="far"):
        raster.ground_and_boxes(1.0, 0.5)


def test_load_obj_and_ply(tmp_path):
    obj = tmp_path / "m.obj"
    obj.write_text("# quad and triangle\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/4/1\nf -4 -3 -1\n")
    sc = raster.load_mesh(obj)
    assert sc.triangles.shape == (3, 3, 3)
    np.testing.assert_array_equal(sc.triangles[2], [[0, 0, 1], [1, 0, 1], [0, 1, 1]])
    ply = tmp_path / "m.ply"
    ply.write_text("ply\nformat ascii 1.0\ncomment x\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                   "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 2\n1 0 2\n1 1 2\n0 1 2\n4 0 1 2 3\n")
    sp = raster.load_mesh(ply)
    assert sp.triangles.shape == (2, 3, 3) and (sp.triangles[..., 2] == 2).all()
    # and it renders
    assert (raster.eye_pass(sp.triangles, 60.0, 16).triangle >= 0).any()


@pytest.mark.parametrize("name, text, match", [
    ("bad.obj", "v 0 0\nf 1 2 3\n", "bad.obj:1"),
    ("idx.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "out of range"),
    ("empty.obj", "# nothing\nv 0 0 0\n", "no faces"),
    ("bin.ply", "ply\nformat binary_little_endian 1.0\nend_header\n", "ascii"),
    ("short.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n", "ends early"),
    ("m.stl", "solid", "must end in .obj or .ply"),
])
def test_loader_errors(tmp_path, name, text, match):
    p = tmp_path / name
    p.write_text(text)
    with pytest.raises(ValueError, match=match):
        raster.load_mesh(p)


def test_loader_missing_file(tmp_path):
    with pytest.raises(ValueError, match="cannot read"):
        raster.load_mesh(tmp_path / "none.obj")


# ----------------------------------------------------------------------------- validation

# f/n = 100, fov 60°; a light above and to the side, one behind the viewer where P is still
# warped (n' ≈ 39 at γ = 150°), and one nearly behind the viewer (there P's rule gives n' = ∞)
CASES = [(scheme, light) for scheme in ("Standard", "P", "LogP", "ZP4+P") for light in ("gamma:60@azimuth:30", "gamma:150", "gamma:170")]


@pytest.mark.parametrize("scheme, light", CASES)
def test_measured_perspective_error_reaches_but_never_exceeds_the_bound(scheme, light):
    r = raster.measure(1.0, 100.0, 60.0, light, scheme, resolution=512, cells=40)
    ref = schemes.evaluate(scheme, 1.0, 100.0, 60.0, light)
    np.testing.assert_array_equal(r.M_x, ref.M_x[0])
    np.testing.assert_array_equal(r.M_z, ref.M_z[0])
    np.testing.assert_allclose(r.n_prime, ref.n_prime[0], rtol=1e-12)
    assert r.pixels > 5000 and r.tolerance <= 1e-3
    # never above the bound beyond the stated central-difference tolerance, pixel by pixel
    ok = np.isfinite(r.m_x)
    assert np.all(r.m_x[ok] <= r.M_x[r.partition[ok]] * (1 + r.tolerance))
    assert np.all(r.m_z[ok] <= r.M_z[r.partition[ok]] * (1 + r.tolerance))
    # and the maximum over the probes reaches it within a few percent, in every map
    assert np.all(r.ratio_x >= 0.97) and np.all(r.ratio_z >= 0.97)


def test_image_error_includes_projection_and_off_axis_factors():
    """The image-space error (texel extent in the image) exceeds the model's perspective error
    off-axis: the model uses w_i = 2 d tanθ everywhere (no 1/cos² factor).  On axis, on a
    probe facing the bisector, the two agree (projection factor 1)."""
    r = raster.measure(1.0, 100.0, 60.0, "overhead", "Standard", resolution=256, cells=16)
    ok = np.isfinite(r.m_s) & np.isfinite(r.m_x)
    ratio = r.m_s[ok] / r.m_x[ok]
    assert ratio.min() >= 1 - 1e-6  # overhead: the s edge keeps its x extent, gains a v component
    res = r.m_s.shape[0]
    c = res // 2
    centre = np.zeros_like(ok)
    centre[c - res // 16: c + res // 16, c - res // 16: c + res // 16] = True
    near_axis = ok & centre
    assert near_axis.any()
    np.testing.assert_allclose(r.m_t[near_axis] / r.m_z[near_axis], 1.0, atol=0.05)
    assert r.image_ratio_t > 1.1  # the bottom corners: reported, not hidden


def test_measure_rejects_probe_free_scenes_and_light_map_single():
    with pytest.raises(ValueError, match="single map"):
        raster.light_map(1.0, 100.0, 60.0, "overhead", "ZP4+P")
    sc = raster.ground_and_boxes(1.0, 100.0, boxes=2, ground_cells=2)
    with pytest.raises(ValueError, match="probes"):
        raster.measure(1.0, 100.0, 60.0, "overhead", "P", resolution=32, scene=sc)
    with pytest.raises(ValueError, match="resolution"):
        raster.measure(1.0, 100.0, 60.0, "overhead", "P", resolution=0)


def test_partition_maps_match_the_scheme():
    maps, edges = raster.light_maps(1.0, 1000.0, 60.0, "gamma:50@azimuth:70", "ZP3+LogP")
    n_i, f_i = schemes.z_partitions(1.0, 1000.0, 3)
    np.testing.assert_allclose(edges, np.append(n_i, f_i[-1]))
    ref = schemes.evaluate("ZP3+LogP", 1.0, 1000.0, 60.0, "gamma:50@azimuth:70")
    np.testing.assert_allclose([m.n_prime for m in maps], ref.n_prime[0], rtol=1e-12)
    assert all(m.parameterization == "logperspective" for m in maps)


# ----------------------------------------------------------------------------- ray-casting reference


@pytest.mark.parametrize("scheme", ["Standard", "P", "LogP"])
def test_raycast_reference_agrees_with_the_rasterizer(scheme):
    """One Embree ray per texel (centre mapped back by the inverse map) sees what the rasterizer stored."""
    pytest.importorskip("embreex", reason="the ray-casting reference needs embreex (optional extra: pip install \".[bench]\")")
    sc = raster.ground_and_boxes(1.0, 100.0, 60.0, boxes=60, ground_cells=8, seed=4)
    lm = raster.light_map(1.0, 100.0, 60.0, "gamma:60@azimuth:20", scheme)
    a = raster.shadow_map(sc.triangles, lm, 64)
    b = raycast.raycast_shadow_map(sc.triangles, lm, 64, chunk=1000)  # several Embree calls
    boxes = a.triangle >= 2 * 8**2
    assert np.isfinite(a.depth).sum() > 1000 and boxes.sum() > 50
    assert raycast.agreement(a, b, sc.triangles) >= 1 - 2 / 64**2  # at most 2 centres within rounding of an edge
    assert (a.triangle == b.triangle)[boxes].mean() > 0.99
    # the check can fail: a depth map off by a millionth of the scene's extent on the boxes does not agree
    extent = np.ptp(sc.triangles.reshape(-1, 3), axis=0).max()
    shifted = raster.DepthMap(np.where(boxes, a.depth + 2e-6 * extent, a.depth), a.triangle, 64, a.rasterized, a.degenerate)
    assert raycast.agreement(shifted, b, sc.triangles) < 1 - boxes.mean() / 2


def test_raycast_reference_inputs(monkeypatch):
    lm = raster.light_map(1.0, 10.0, 60.0, "overhead", "P")
    tri = np.array([[[-20, -1, 0.5], [20, -1, 0.5], [0, -1, 30]]], float)
    m = raster.shadow_map(tri, lm, 4)
    with pytest.raises(ValueError, match="same resolution"):
        raycast.agreement(m, raster.shadow_map(tri, lm, 8), tri)
    with pytest.raises(ValueError, match="tolerance must be >= 0"):
        raycast.agreement(m, m, tri, tolerance=-1.0)
    assert raycast.agreement(m, m, tri) == 1.0
    monkeypatch.setitem(sys.modules, "embreex", None)  # as if the extra were not installed
    assert raycast.available() is False
    with pytest.raises(ValueError, match=r'pip install "\.\[bench\]"'):
        raycast.raycast_shadow_map(tri, lm, 4)
    with pytest.raises(ValueError, match="chunk must be"):
        raycast.raycast_shadow_map(tri, lm, 4, chunk=0)
    with pytest.raises(ValueError, match="lm must be a LightMap"):
        raycast.raycast_shadow_map(tri, "P", 4)


def test_pixel_errors_is_public_and_checks_its_input():
    from aliasing.raster.validate.measure import pixel_errors

    lm = raster.light_map(1.0, 100.0, 60.0, "overhead", "P")
    pos = np.tile([0.0, 0.0, 10.0], (8, 8, 1))
    ok = np.zeros((8, 8), bool)
    assert sorted(pixel_errors(lm, pos, ok, 8, 60.0)) == ["m_s", "m_t", "m_x", "m_z", "s", "t"]
    for args, match in [
        (("map", pos, ok, 8, 60.0), "lm must be a LightMap"),
        ((lm, pos[:4], ok, 8, 60.0), r"position must have shape .* \(8, 8, 3\)"),
        ((lm, pos, ok.astype(int), 8, 60.0), "ok must be a boolean array"),
        ((lm, pos, ok, 0, 60.0), "resolution must be in"),
        ((lm, pos, ok, 8, 180.0), r"fov .* must be in \(0, 180\)"),
        ((lm, -pos, ~ok, 8, 60.0), "z > 0"),
    ]:
        with pytest.raises(ValueError, match=match):
            pixel_errors(*args)


def test_projection_factor_is_one_on_bisector_normals_and_cos_psi_e_facing_the_light():
    from aliasing.raster.validate.measure import projection_factors

    rng = np.random.default_rng(5)
    pos = rng.uniform([-5, -5, 1], [5, 5, 50], size=(200, 3))
    lv = geometry.lights("gamma:60@azimuth:30")[0]
    to_eye = -pos / np.linalg.norm(pos, axis=-1, keepdims=True)
    half = to_eye + lv
    half /= np.linalg.norm(half, axis=-1, keepdims=True)
    np.testing.assert_allclose(projection_factors(pos, half, "gamma:60@azimuth:30"), 1.0, rtol=1e-12)
    facing = np.broadcast_to(lv, pos.shape)  # normal towards the light: cos ψ_l = 1
    np.testing.assert_allclose(projection_factors(pos, facing, lv), to_eye @ lv, rtol=1e-12)
    assert np.isnan(projection_factors(pos, -facing, lv)).all()  # facing away from the light
    with pytest.raises(ValueError, match="same shape"):
        projection_factors(pos, half[:3], lv)
    with pytest.raises(ValueError, match="single direction"):
        projection_factors(pos, half, "sphere:3")


def test_projection_factor_about_one_on_probes_far_from_one_on_the_ground():
    r = raster.measure(1.0, 100.0, 60.0, "gamma:150", "P", resolution=128, cells=8)
    on = np.isfinite(r.m_x)
    assert np.array_equal(np.isfinite(r.projection), on)
    assert abs(np.median(r.projection[on]) - 1) < 5e-3 and np.all(np.abs(r.projection[on] - 1) < 0.08)
    # the ground seen from 1 unit above, lit from overhead: grazing to the eye, facing the light
    from aliasing.raster.validate.measure import projection_factors

    ground = raster.ground_and_boxes(1.0, 100.0, 60.0, boxes=0, ground_cells=4)
    eb = raster.eye_pass(ground.triangles, 60.0, 64)
    hit = eb.triangle >= 0
    f = projection_factors(eb.position, eb.normal, "overhead")[hit]
    assert hit.sum() > 500 and np.all(f < 0.6) and np.median(f) < 0.35
