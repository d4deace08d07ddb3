"""Maps drawn where they are looked up (:class:`aliasing.raster.draw.MapSampler`), maps kept on
the gl device (:mod:`aliasing.raster.draw.resident`), and the memory bound of an engine-sized
shimmer run.

* numpy: the sampled texels are the whole map's, bit for bit (uniform, warped with near
  clipping, logarithmic rows), however the questions are split;
* gl: the fetched texels are ``shadow_map(..., backend="gl")``'s, bit for bit, and a map
  bigger than the device allows is refused in one line before any work; the shadow test run
  on the device is the host's test of the same texels, bit for bit, and a gl shimmer run gets
  only bits back;
* a shimmer run of 4 cascades of 1024² stays under 0.5 GB of peak resident memory (a
  subprocess measures its own peak): whole-map temporaries would take about 1 GB.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aliasing import raster
from aliasing.cli import main
from aliasing.raster.draw import MapSampler, depth_test, gl, light_map, resident, shadow_map, shadow_test
from aliasing.raster.scenes import ground_and_boxes, procedural
from aliasing.temporal import measure, points

ON_CI = os.environ.get("CI") == "true"
GL = pytest.mark.skipif(not gl.available() and not ON_CI, reason=f"the gl backend cannot draw here: {gl._setup()[1]}")
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

SCENE = ground_and_boxes(near=1.0, far=60.0, boxes=30, seed=3).triangles
CITY = procedural.city(4_000, 2) + np.array([0.0, -20.0, 220.0])


def _maps():
    """(name, scene, light map): uniform, perspective (clipped behind the warp's centre), logarithmic rows, a city."""
    return [
        ("Standard", SCENE, light_map(1.0, 60.0, 60.0, "gamma:50@azimuth:20", "Standard")),
        ("P", SCENE, light_map(1.0, 60.0, 60.0, "gamma:120", "P")),
        ("LogP", SCENE, light_map(1.0, 60.0, 60.0, "gamma:70@azimuth:-40", "LogP")),
        ("city", CITY, light_map(1.0, 600.0, 60.0, "gamma:40@azimuth:30", "Standard")),
    ]


@pytest.mark.parametrize("name, scene, lm", _maps(), ids=[m[0] for m in _maps()])
def test_numpy_samples_are_the_whole_maps_texels_bit_for_bit(name, scene, lm):
    res = 512
    full = shadow_map(scene, lm, res)
    assert (full.triangle >= 0).mean() > 0.05  # the map sees the scene
    rng = np.random.default_rng(7)
    row, col = rng.integers(0, res, 4000), rng.integers(0, res, 4000)
    ms = MapSampler(scene, lm, res, chunk=1000)  # small chunks: the questions are cut in many steps
    d, i = ms.at(row[:1500], col[:1500])
    d2, i2 = ms.at(row, col)  # partly known, partly new
    assert np.array_equal(d2[:1500], d) and np.array_equal(i2[:1500], i)
    assert np.array_equal(d2, full.depth[row, col]) and np.array_equal(i2, full.triangle[row, col])
    every = np.indices((res, res)).reshape(2, -1)
    d3, i3 = MapSampler(scene, lm, res).at(*every)  # every texel: the whole map
    assert np.array_equal(d3.reshape(res, res), full.depth) and np.array_equal(i3.reshape(res, res), full.triangle)


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2**16), res=st.integers(1, 300), count=st.integers(0, 300))
def test_any_texels_of_any_map_are_the_whole_maps(seed, res, count):
    rng = np.random.default_rng(seed)
    name, scene, lm = _maps()[seed % 4]
    row, col = rng.integers(0, res, count), rng.integers(0, res, count)
    full = shadow_map(scene, lm, res)
    d, i = MapSampler(scene, lm, res).at(row, col)
    assert np.array_equal(d, full.depth[row, col]) and np.array_equal(i, full.triangle[row, col])


def test_shadow_test_through_a_sampler_is_the_test_through_the_map():
    name, scene, lm = _maps()[1]
    rng = np.random.default_rng(2)
    p = np.stack([rng.uniform(-20, 20, 3000), np.full(3000, -1.0), rng.uniform(2, 58, 3000)], -1)  # on the ground, some in shadow
    nrm = np.tile([0.0, 1.0, 0.0], (3000, 1))
    want = shadow_test(lm, shadow_map(scene, lm, 256), scene, p, nrm)
    assert 0.05 < want.mean() < 0.99
    assert np.array_equal(shadow_test(lm, MapSampler(scene, lm, 256), scene, p, nrm), want)


@pytest.mark.parametrize("call, error, words", [
    (lambda: MapSampler(SCENE, "P", 64), TypeError, "lm must be a LightMap"),
    (lambda: MapSampler(SCENE, _maps()[0][2], 0), ValueError, "resolution"),
    (lambda: MapSampler(SCENE, _maps()[0][2], 64, backend="vulkan"), ValueError, "backend"),
    (lambda: MapSampler(SCENE, _maps()[0][2], 64, chunk=0), ValueError, "chunk"),
    (lambda: MapSampler(SCENE[:0], _maps()[0][2], 64), ValueError, "triangles"),
    (lambda: MapSampler(SCENE, _maps()[0][2], 64).at([0, 64], [0, 1]), ValueError, "row and col"),
    (lambda: MapSampler(SCENE, _maps()[0][2], 64).at([0.5], [1]), ValueError, "row and col"),
    (lambda: MapSampler(SCENE, _maps()[0][2], 64).at([0, 1], [1]), ValueError, "row and col"),
    (lambda: shadow_test(_maps()[0][2], "map", SCENE, [[0, 0, 1]], [[0, 1, 0]]), TypeError, "sm must be"),
])
def test_bad_input_is_named(call, error, words):
    with pytest.raises(error, match=words):
        call()


# --- gl: maps kept on the device -------------------------------------------------------------

@GL
@pytest.mark.parametrize("name, scene, lm", _maps()[:2] + _maps()[3:], ids=["Standard", "P", "city"])
def test_gl_fetched_texels_are_the_gl_maps_bit_for_bit(name, scene, lm):
    res = 512
    full = shadow_map(scene, lm, res, backend="gl")
    rng = np.random.default_rng(5)
    row, col = rng.integers(100, 300, 3000), rng.integers(50, 400, 3000)
    ms = MapSampler(scene, lm, res, backend="gl")
    d, i = ms.at(row, col)  # drawn over the box of these texels
    assert np.array_equal(d, full.depth[row, col]) and np.array_equal(i, full.triangle[row, col])
    row2, col2 = rng.integers(0, res, 3000), rng.integers(0, res, 3000)
    d2, i2 = ms.at(row2, col2)  # outside the box: drawn again over a larger one
    ms.release()
    assert np.array_equal(d2, full.depth[row2, col2]) and np.array_equal(i2, full.triangle[row2, col2])
    m = resident.draw_device_map(scene, lm.matrix(), res)
    depth, ident = m.read()  # the whole map, read back only when asked
    m.release()
    assert np.array_equal(depth, full.depth) and np.array_equal(ident, full.triangle)
    with pytest.raises(ValueError, match="released"):
        m.fetch(np.array([0]))


@GL
def test_gl_device_maps_stay_within_their_budget():
    lm = _maps()[0][2]
    maps = [resident.draw_device_map(SCENE, lm.matrix(), 1024) for _ in range(3 + resident.DEVICE_BYTES // (resident.DEVICE_TEXEL_BYTES * 1024**2))]
    live = [m for m in maps if not m.released]
    assert 0 < len(live) * resident.DEVICE_TEXEL_BYTES * 1024**2 <= resident.DEVICE_BYTES and maps[0].released
    gl.release()
    assert all(m.released for m in maps)


@GL
def test_gl_map_bigger_than_the_device_allows_is_refused_in_one_line_before_work(monkeypatch, capsys):
    limit = resident.max_resolution()
    assert limit >= 1024
    monkeypatch.setattr(resident, "max_resolution", lambda: 512)
    lm = _maps()[0][2]
    w = points.world("boxes", boxes=5)
    drawn = []
    monkeypatch.setattr(resident, "_Scene", lambda *a: drawn.append(a))
    monkeypatch.setattr(gl, "_Scene", lambda *a: drawn.append(a))
    with pytest.raises(ValueError, match=r"resolution 1024 is over the largest map the gl device draws, 512² texels"):
        MapSampler(SCENE, lm, 1024, backend="gl")
    with pytest.raises(ValueError, match="512²"):
        shadow_map(SCENE, lm, 1024, backend="gl")
    with pytest.raises(ValueError, match="512²"):
        raster.shadow_maps(SCENE, [lm, lm], [256, 1024], backend="gl")
    with pytest.raises(ValueError, match="512²"):
        measure.shimmer(w, points.sample(w, 16), "csm:log:k=2", "translate:0.05,0,0", 2, res=1024, backend="gl")
    code = main(["shimmer", "--schemes", "csm:log:k=2", "--motion", "translate:0.05,0,0", "--frames", "2", "--image-res", "16", "--shadow-res", "1024", "--backend", "gl"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and "512²" in err[0] and not drawn


# --- gl: the shadow test run on the device ---------------------------------------------------

def _on_surfaces(scene: np.ndarray, count: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """Points spread over the scene's triangles (barycentric), with their triangles' normals."""
    rng = np.random.default_rng(seed)
    k = rng.integers(0, len(scene), count)
    p = np.einsum("pi,pij->pj", rng.dirichlet([1.0, 1.0, 1.0], count), scene[k])
    return p, np.cross(scene[k, 1] - scene[k, 0], scene[k, 2] - scene[k, 0])


@GL
@pytest.mark.parametrize("name, scene, lm", _maps()[:2] + _maps()[3:] + [("lispsm", CITY, light_map(1.0, 600.0, 60.0, "gamma:30", "lispsm"))],
                         ids=["Standard", "P", "city", "lispsm"])
def test_gl_device_shadow_test_is_the_host_test_of_the_gl_texels_bit_for_bit(name, scene, lm, monkeypatch):
    from aliasing.raster.draw import lookup

    p, nrm = _on_surfaces(scene, 6000, 6)
    p[:50] += 1e4  # outside the map: lit
    calls = []
    test = resident.DeviceMap.test
    monkeypatch.setattr(resident.DeviceMap, "test", lambda self, *a: calls.append(len(a[0])) or test(self, *a))
    for res, bias in ((64, lookup.BIAS), (512, 0.05)):
        ms = MapSampler(scene, lm, res, backend="gl")
        got = shadow_test(lm, ms, scene, p, nrm, bias=bias)
        assert ms.texels == 0 and calls[-1] <= len(p) - 50  # no texel came back, only the bits of the points in the map
        want = shadow_test(lm, shadow_map(scene, lm, res, backend="gl"), scene, p, nrm, bias=bias)  # the host's comparisons
        ms.release()
        assert 0.05 < want.mean() < 0.95 and want[:50].all()
        assert np.array_equal(got, want), int((got != want).sum())


@GL
@settings(max_examples=8, deadline=None)
@given(scheme=st.sampled_from(["Standard", "P", "lispsm", "tsm"]), gamma=st.floats(5.0, 175.0), azimuth=st.floats(-180.0, 180.0),
       res=st.sampled_from([32, 128, 300]), bias=st.sampled_from([0.0, 1e-3, 0.2]), seed=st.integers(0, 2**16))
def test_gl_device_shadow_test_is_the_host_test_for_any_map(scheme, gamma, azimuth, res, bias, seed):
    lm = light_map(1.0, 60.0, 60.0, f"gamma:{gamma}@azimuth:{azimuth}", scheme)
    p, nrm = _on_surfaces(SCENE, 1500, seed)
    ms = MapSampler(SCENE, lm, res, backend="gl")
    got = shadow_test(lm, ms, SCENE, p, nrm, bias=bias)
    ms.release()
    assert np.array_equal(got, shadow_test(lm, shadow_map(SCENE, lm, res, backend="gl"), SCENE, p, nrm, bias=bias))


@GL
@pytest.mark.parametrize("call, words", [
    (lambda ms: MapSampler(SCENE, _maps()[0][2], 64).device_test(np.array([0]), np.zeros((1, 4)), np.zeros(1), SCENE, 0.0), "drawn by numpy"),
    (lambda ms: ms.device_test(np.array([64 * 64]), np.zeros((1, 4)), np.zeros(1), SCENE, 0.0), "texels must be"),
    (lambda ms: ms.device_test(np.array([0.5]), np.zeros((1, 4)), np.zeros(1), SCENE, 0.0), "texels must be"),
    (lambda ms: ms.device_test(np.array([0]), np.zeros((2, 4)), np.zeros(1), SCENE, 0.0), "points must have shape"),
    (lambda ms: ms.device_test(np.array([0]), np.zeros((1, 4)), np.zeros(1), SCENE[:3], 0.0), "triangles must be"),
    (lambda ms: ms.device_test(np.array([0]), np.zeros((1, 4)), np.zeros(1), SCENE, -1.0), "bias"),
])
def test_gl_device_test_bad_input_is_named(call, words):
    ms = MapSampler(SCENE, _maps()[0][2], 64, backend="gl")
    with pytest.raises(ValueError, match=words):
        call(ms)
    ms.release()


@GL
def test_gl_shimmer_gets_only_bits_back_and_the_host_tests_states(monkeypatch):
    from aliasing.raster.draw import lookup

    w = points.world("boxes", boxes=20)
    pts = points.sample(w, 32)
    fetched = []
    fetch = resident.DeviceMap.fetch
    monkeypatch.setattr(resident.DeviceMap, "fetch", lambda self, texels: fetched.append(len(texels)) or fetch(self, texels))
    run = lambda: measure.shimmer(w, pts, "csm:log:k=2", "translate:0.05,0,0", 3, res=256, shifts=2, backend="gl")
    on = run()
    assert not fetched  # the states came back as bits, no texel
    monkeypatch.setattr(lookup, "_ON_DEVICE", False)
    off = run()
    assert fetched and np.array_equal(on.lit, off.lit) and 0 < on.lit.mean() < 1
    assert np.array_equal(on.flips, off.flips) and np.array_equal(on.g, off.g, equal_nan=True)


@GL
def test_gl_render_shades_with_the_host_tests_states(monkeypatch):
    from aliasing.raster.draw import lookup
    from aliasing.pictures import images

    on = images.view(1.0, 100.0, 60.0, "gamma:50@azimuth:30", "P", image_res=64, budget=256**2, backend="gl").lit
    monkeypatch.setattr(lookup, "_ON_DEVICE", False)
    off = images.view(1.0, 100.0, 60.0, "gamma:50@azimuth:30", "P", image_res=64, budget=256**2, backend="gl").lit
    assert np.array_equal(on, off) and 0.05 < on.mean() < 0.95


# --- memory: the shimmer case at engine scale ------------------------------------------------

# The child's own peak: VmHWM of its address space (Linux).  ru_maxrss is not used: after a
# fork and exec it keeps the forking parent's peak (a pytest process that ran the gl tests).
PEAK = """
import resource, sys
from aliasing.cli import main
code = main(sys.argv[1:])
try:
    peak = next(int(line.split()[1]) * 1024 for line in open("/proc/self/status") if line.startswith("VmHWM:"))
except OSError:
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * (1 if sys.platform == "darwin" else 1024)
print(peak, file=sys.stderr)
sys.exit(code)
"""


def shimmer_peak(backend: str, res: int, frames: int) -> tuple[dict, int]:
    """(summary row, peak resident bytes) of the engine-scale shimmer case run in a subprocess."""
    argv = ["shimmer", "--schemes", "csm:threejs-csm:k=4", "--motion", "translate:0.05,0,0", "--frames", str(frames), "--near", "0.1", "--far", "500",
            "--fov", "50", "--aspect", "1.7778", "--image-res", "96", "--shadow-res", str(res), "--backend", backend, "--format", "json"]
    env = {**os.environ, "PYTHONPATH": ROOT + os.pathsep + os.environ.get("PYTHONPATH", "")}
    run = subprocess.run([sys.executable, "-c", PEAK, *argv], capture_output=True, text=True, env=env, timeout=600)
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout)[0], int(run.stderr.strip().splitlines()[-1])


@pytest.mark.parametrize("backend", ["numpy", pytest.param("gl", marks=GL)])
def test_shimmer_at_4_x_1024_squared_stays_under_half_a_gigabyte(backend):
    row, peak = shimmer_peak(backend, 1024, 3)
    assert row["maps_drawn"] >= 4 * 3 and row["predicted_over_measured"] is not None  # the maps and the prediction's were drawn
    assert peak <= 0.5 * 2**30, f"peak resident memory {peak / 2**30:.2f} GiB"


@GL
def test_gl_depth_maps_are_read_back_only_when_asked_and_before_the_device_frees_them():
    lm = _maps()[1][2]
    (depth, ident), = gl.draw_maps(SCENE, [lm.matrix()], [1024])[0]  # the eager reference
    first = shadow_map(SCENE, lm, 1024, backend="gl")
    assert first._arrays is None  # drawn, still on the device
    crowd = raster.shadow_maps(SCENE, [lm] * (2 + resident.DEVICE_BYTES // (resident.DEVICE_TEXEL_BYTES * 1024**2)), 1024, backend="gl")
    assert first._arrays is not None and first._device.released  # the device needed the room: read back first
    later = crowd[-1]
    assert later._arrays is None
    assert np.array_equal(later.depth, depth) and np.array_equal(later.triangle, ident) and later._device.released
    assert all(np.array_equal(m.depth, depth) and np.array_equal(m.triangle, ident) for m in [first] + crowd)


@pytest.mark.parametrize("options", [{}, {"bias": 0.01, "pcf": 3}, {"slope": 1.5, "normal_offset": 0.02, "pcf": 5, "receiver_plane": True}])
def test_the_engines_depth_test_through_a_sampler_is_the_test_through_the_map(options):
    name, scene, lm = _maps()[0]
    rng = np.random.default_rng(4)
    p = np.stack([rng.uniform(-20, 20, 2000), np.full(2000, -1.0), rng.uniform(2, 58, 2000)], -1)
    nrm = np.tile([0.0, 1.0, 0.0], (2000, 1))
    want = depth_test(lm, shadow_map(scene, lm, 256), p, nrm, **options)
    assert 0.0 < want.mean() < 1.0
    assert np.array_equal(depth_test(lm, MapSampler(scene, lm, 256), p, nrm, **options), want)
