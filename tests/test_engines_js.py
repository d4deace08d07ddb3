"""The engines' own JavaScript, run in node, against the toolkit's engine presets.

three.js (``three``, the current release and 0.184.0, the last with the older split) and
Babylon.js (``@babylonjs/core``) ship their cascade code on npm.  These tests install pinned
versions into a cache (``~/.cache/aliasing-engines-js/<package>@<version>``, or
``$ALIASING_ENGINES_JS_CACHE``) with ``npm ci`` from the lockfiles committed under
``tests/engines_js/pins/`` (npm checks each tarball's sha512 against the lockfile), check the
installed tree against its committed SHA-256 every time it is reused, run the engines' classes
in node (``tests/engines_js/*.mjs``) and compare, at 1e-9 relative:

* the cascade ends with :func:`aliasing.partitioning.split_distances` of the preset;
* the cascades' 8 corners with :meth:`aliasing.view.View.slice_vertices` between those ends;
* the stabilized box sides (Babylon's sphere rounded to 1/16, three.js's longer diagonal) and
  Babylon's light-space tight box, for several light directions, with
  :func:`aliasing.engines.stable.evaluate` of the stable preset;
* the engines' cascade counts (default, and Babylon's clamp to 2–4) with the presets'.

Non-square views (aspect 16:9 and 2:1) are run in the engines too and compared the same way
(:class:`aliasing.view.View` and :func:`aliasing.engines.stable.evaluate` take ``aspect``).
Without node (or npm) the tests skip with one line, except under CI (``CI=true``), where a
missing node is a failure.
"""

from __future__ import annotations

import fcntl
import json
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from aliasing import partitioning
from aliasing.engines import stable
from aliasing.frames.install import tree_digest  # the frames' digest of an installed npm tree, one definition
from aliasing.view import View

HERE = Path(__file__).parent / "engines_js"
PINS = HERE / "pins"
THREE_CURRENT, THREE_R184, BABYLON = "three@0.187.0", "three@0.184.0", "@babylonjs+core@9.35.0"
RTOL = 1e-9  # relative to the largest magnitude compared; float64 in both (observed: about 1e-15)

# towards the light, in the eye frame (x right, y up, z along the view); none parallel to the view
LIGHTS = np.array([[0.0, 1.0, 0.0], [0.3, 0.8, 0.2], [-0.6, 0.3, -0.74], [0.9, -0.1, 0.42], [0.05, 0.2, -0.98]])
LIGHTS = LIGHTS / np.linalg.norm(LIGHTS, axis=1, keepdims=True)

# near, shadow far, vertical full fov [deg], aspect (width, height), cascades (None: the engine's default)
CASES = [
    (1.0, 100.0, 60.0, (1, 1), None),
    (0.5, 250.0, 45.0, (1, 1), 3),
    (0.1, 1000.0, 90.0, (1, 1), 2),
    (1.0, 100.0, 60.0, (16, 9), 4),
    (2.0, 500.0, 75.0, (2, 1), 3),
]
THREE_CASES = CASES + [(1.0, 100.0, 60.0, (1, 1), 8), (0.1, 50.0, 50.0, (1, 1), 1)]
BABYLON_CLAMPED = [(1.0, 100.0, 60.0, (1, 1), 1), (1.0, 100.0, 60.0, (1, 1), 6)]


def _cache() -> Path:
    return Path(os.environ.get("ALIASING_ENGINES_JS_CACHE", Path.home() / ".cache" / "aliasing-engines-js"))


def _tools() -> tuple[str, str]:
    node, npm = shutil.which("node"), shutil.which("npm")
    missing = [name for name, path in (("node", node), ("npm", npm)) if path is None]
    if missing:
        what = " and ".join(missing)
        if os.environ.get("CI", "").lower() == "true":
            pytest.fail(f"{what} not found under CI: .ci/run installs Debian's nodejs and npm packages")
        pytest.skip(f"{what} not installed: the engines' own JavaScript is not run (Debian: apt-get install nodejs npm)")
    return node, npm  # type: ignore[return-value]


def _install(pin: str, npm: str) -> Path:
    """The pinned package's directory in the cache: reused only if its tree has the committed digest."""
    src = PINS / pin
    want = (src / "tree.sha256").read_text().split()[0]
    root = _cache() / pin
    root.mkdir(parents=True, exist_ok=True)
    with open(_cache() / f"{pin.replace('/', '+')}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        same = all((root / f).is_file() and (root / f).read_bytes() == (src / f).read_bytes() for f in ("package.json", "package-lock.json"))
        if same and (root / "node_modules").is_dir() and tree_digest(root) == want:
            return root
        for f in ("package.json", "package-lock.json"):
            shutil.copyfile(src / f, root / f)
        # npm ci installs exactly the lockfile and checks each tarball's sha512 (its "integrity")
        cmd = [npm, "ci", "--ignore-scripts", "--no-audit", "--no-fund", "--loglevel=error"]
        done = subprocess.run(cmd, cwd=root, capture_output=True, text=True, timeout=600)
        if done.returncode != 0:
            message = f"npm ci for {pin} failed: {(done.stderr or done.stdout).strip().splitlines()[-1:]}"
            if os.environ.get("CI", "").lower() == "true":
                pytest.fail(message)
            pytest.skip(message + " (no registry access?)")
        got = tree_digest(root)
        assert got == want, f"{pin}: installed files differ from the committed tree digest ({got} != {want})"
    return root


def _run(script: str, pin: str, payload: dict) -> dict:
    node, npm = _tools()
    root = _install(pin, npm)
    done = subprocess.run([node, str(HERE / script), str(root), json.dumps(payload)], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    return json.loads(done.stdout)


def _cases(cases: list) -> list[dict]:
    return [{"near": n, "far": f, "fov": fov, "aspect": w / h, "width": 100 * w, "height": 100 * h, "k": k, "map_size": 2048} for n, f, fov, (w, h), k in cases]


@pytest.fixture(scope="module")
def three_runs() -> dict:
    out = {}
    for pin in (THREE_CURRENT, THREE_R184):
        payload = {"lights": LIGHTS.tolist(), "cases": []}
        for c in _cases(THREE_CASES):
            # the camera's far plane beyond CSM's maxFar in one case, at it in the others: shadows end at the smaller
            payload["cases"].append({**c, "far": 2 * c["far"] if c["k"] == 2 else c["far"], "max_far": c["far"]})
        out[pin] = _run("three_csm.mjs", pin, payload)
    return out


@pytest.fixture(scope="module")
def babylon_run() -> dict:
    return _run("babylon_csm.mjs", BABYLON, {"lights": LIGHTS.tolist(), "cases": _cases(CASES + BABYLON_CLAMPED)})


def _view(near: float, far: float, fov: float, aspect: float) -> View:
    return View(near, far, fov) if aspect == 1.0 else View(near, far, fov, aspect=aspect)


def _fit_options(aspect: float) -> dict:
    return {} if aspect == 1.0 else {"aspect": aspect}  # aspect 1: the square defaults, as before


def _rel(got, want) -> float:
    got, want = np.asarray(got, float), np.asarray(want, float)
    assert got.shape == want.shape, (got.shape, want.shape)
    return float(np.max(np.abs(got - want)) / np.max(np.abs(want)))


def _corners_in_view_order(corners) -> np.ndarray:
    """(8, 3) engine corners reordered as View.slice_vertices: near then far, each (−,−) (+,−) (+,+) (−,+)."""
    c = np.asarray(corners, float)
    near = np.argsort(c[:, 2], kind="stable")[:4]
    out = []
    for ring in (np.sort(near), np.setdiff1d(np.arange(8), near)):
        for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            hit = [i for i in ring if np.sign(c[i, 0]) == sx and np.sign(c[i, 1]) == sy]
            assert len(hit) == 1, c
            out.append(c[hit[0]])
    return np.array(out)


def _check_cascades(cascades: list, edges: np.ndarray, view: View) -> float:
    """Largest relative difference of the ends and corners; asserts the count."""
    assert len(cascades) == len(edges) - 1
    worst = _rel([c["end"] for c in cascades], edges[1:])
    for i, c in enumerate(cascades):
        worst = max(worst, _rel(_corners_in_view_order(c["corners"]), view.slice_vertices(edges[i], edges[i + 1])))
    return worst


@pytest.mark.parametrize("pin, preset", [(THREE_CURRENT, "threejs"), (THREE_R184, "threejs@r184")])
@pytest.mark.parametrize("case", range(len(THREE_CASES)))
def test_threejs_csm_matches_its_presets(three_runs, pin, preset, case):
    near, far, fov, (w, h), k = THREE_CASES[case]
    run = three_runs[pin]["cases"][case]
    p = stable.PRESETS[preset]
    view = _view(near, far, fov, w / h)
    kk = p.k if k is None else k
    edges = partitioning.split_distances(p.split, near, far, kk)
    assert {row["k"] for row in run["rows"]} == {kk} and partitioning.SPLIT_METHODS[p.split].default_k == 3 == p.k
    options = _fit_options(w / h)
    box = stable.evaluate(p.split, near, far, fov, LIGHTS, k=kk, fit=p.fit, snap=p.snap, overlap=p.overlap, **options)
    for row, wx, wy in zip(run["rows"], box.width_x, box.width_y):  # one row per light direction
        assert _check_cascades(row["cascades"], edges, view) <= RTOL
        assert _rel([c["side_x"] for c in row["cascades"]], wx) <= RTOL
        assert _rel([c["side_y"] for c in row["cascades"]], wy) <= RTOL


def test_threejs_r185_changed_the_split(three_runs):
    # the comparison tells the two forms apart: near 1, far 100, 8 cascades, each preset is
    # 10–12 % off the other release's cascade ends
    case = THREE_CASES.index((1.0, 100.0, 60.0, (1, 1), 8))
    for pin, other in ((THREE_CURRENT, "threejs-csm@r184"), (THREE_R184, "threejs-csm")):
        ends = np.array([c["end"] for c in three_runs[pin]["cases"][case]["rows"][0]["cascades"]])
        off = np.abs(ends / partitioning.split_distances(other, 1.0, 100.0, 8)[1:] - 1).max()
        assert 0.10 < off < 0.14, (pin, other, off)
    assert three_runs[THREE_CURRENT]["float64"] and three_runs[THREE_CURRENT]["revision"] == "187"
    assert three_runs[THREE_R184]["revision"] == "184"


@pytest.mark.parametrize("case", range(len(CASES)))
def test_babylon_csm_matches_its_presets(babylon_run, case):
    near, far, fov, (w, h), k = CASES[case]
    run = babylon_run["cases"][case]
    assert run["float64"] and run["aspect"] == pytest.approx(w / h, rel=1e-15)
    p = stable.PRESETS["babylon"]
    view = _view(near, far, fov, w / h)
    kk = babylon_run["counts"]["default"] if k is None else k
    assert kk == partitioning.SPLIT_METHODS["babylon"].default_k == p.k or k is not None
    edges = partitioning.split_distances(p.split, near, far, kk)
    options = _fit_options(w / h)
    sphere = stable.evaluate(p.split, near, far, fov, LIGHTS, k=kk, fit=p.fit, **options)
    tight = stable.evaluate(p.split, near, far, fov, LIGHTS, k=kk, fit="tight", **options)
    for rows, box in ((run["stable"], sphere), (run["tight"], tight)):
        for row, wx, wy in zip(rows, box.width_x, box.width_y):  # one row per light direction
            assert _check_cascades(row["cascades"], edges, view) <= RTOL
            side = np.array([np.subtract(c["max"], c["min"])[:2] for c in row["cascades"]])
            assert _rel(side[:, 0], wx) <= RTOL and _rel(side[:, 1], wy) <= RTOL


def test_babylon_cascade_count_clamp_is_the_presets(babylon_run):
    counts = babylon_run["counts"]
    entry = partitioning.SPLIT_METHODS["babylon"]
    assert (counts["default"], counts["min"], counts["max"]) == (entry.default_k, entry.min_k, entry.max_k) == (4, 2, 4)
    for (near, far, _, _, k), run in zip(BABYLON_CLAMPED, babylon_run["cases"][len(CASES):]):
        clamped = min(max(k, counts["min"]), counts["max"])
        assert {row["k"] for row in run["stable"]} == {clamped}  # the engine changes the count silently...
        with pytest.raises(ValueError, match="k must be at least 2 and at most 4 for 'babylon'"):
            partitioning.split_distances("babylon", near, far, k)  # ...the toolkit refuses it


def test_missing_node_skips_outside_ci_and_fails_under_ci(monkeypatch):
    monkeypatch.setattr(shutil, "which", lambda name: None if name == "node" else f"/usr/bin/{name}")
    monkeypatch.delenv("CI", raising=False)
    with pytest.raises(pytest.skip.Exception, match=r"^node not installed: the engines' own JavaScript is not run"):
        _tools()
    monkeypatch.setenv("CI", "true")
    with pytest.raises(pytest.fail.Exception, match="node not found under CI"):
        _tools()


# ---------------------------------------------------------------------------------------------
# The engine profiles (aliasing.setups) against the engines' own objects: each cascade's texel
# from aliasing.engines.pipeline.texels (what `aliasing check` uses) equals the engine's shadow
# camera extent ÷ map size, the depth range a bias term scales with equals the engine's, and
# every setting's default is the engine's own default object's.

PLAYCANVAS = "playcanvas@2.23.3"
# near, far, vertical fov [deg], aspect (width, height)
PROFILE_CAMERAS = [(0.1, 500.0, 50.0, (16, 9)), (1.0, 100.0, 60.0, (1, 1)), (0.5, 250.0, 45.0, (2, 1))]
THREE_SETTINGS = [
    {},
    {"cascades": 4, "mode": "logarithmic", "shadowMapSize": 1024},
    {"mode": "custom", "customSplitsLambda": 0.8, "fade": True},
    {"maxFar": 80.0, "cascades": 5, "mode": "uniform", "shadowMapSize": 0, "lightNear": 5.0, "lightFar": 900.0},
    {"class": "DirectionalLight"},
    {"class": "DirectionalLight", "shadow.camera.left": -20.0, "shadow.camera.right": 30.0, "shadow.camera.top": 10.0,
     "shadow.camera.bottom": -30.0, "shadow.camera.near": 1.0, "shadow.camera.far": 300.0, "shadow.mapSize.width": 1024},
]
BABYLON_SETTINGS = [
    {},
    {"stabilizeCascades": True},
    {"numCascades": 2, "lambda": 0.8, "mapSize": 2048},
    {"numCascades": 3, "shadowMaxZ": 80.0, "minDistance": 0.05, "maxDistance": 0.9, "stabilizeCascades": True},
    {"numCascades": 6, "lambda": 1.5},
    {"class": "ShadowGenerator", "light.shadowFrustumSize": 120.0, "light.shadowMaxZ": 300.0},
]
PLAYCANVAS_SETTINGS = [
    {},
    {"numCascades": 4},
    {"numCascades": 3, "cascadeDistribution": 0.8, "shadowDistance": 120.0, "shadowResolution": 2048},
    {"numCascades": 2, "cascadeDistribution": 0.0},
    {"numCascades": 7, "cascadeDistribution": 1.5},
]
# keys of the profiles that are no engine property (the toolkit's choice of class, or a callback's λ)
NOT_ENGINE_KEYS = {"class", "customSplitsLambda", "mapSize"}  # Babylon's mapSize is a required constructor argument


def _profile_cases(settings: list[dict]) -> list[tuple]:
    return [(cam, s) for cam in PROFILE_CAMERAS for s in settings]


def _setup(engine: str, cam: tuple, settings: dict):
    from aliasing import setups

    near, far, fov, (w, h) = cam
    return setups.build(engine, settings, setups.Camera(near, far, fov, w / h, 100 * h))


@pytest.fixture(scope="module")
def three_profile_runs() -> dict:
    out = {}
    for pin in (THREE_CURRENT, THREE_R184):
        cases = [{"near": n, "far": f, "fov": fov, "aspect": w / h, "settings": s} for (n, f, fov, (w, h)), s in _profile_cases(THREE_SETTINGS)]
        out[pin] = _run("three_profile.mjs", pin, {"lights": LIGHTS.tolist(), "cases": cases})
    return out


@pytest.fixture(scope="module")
def babylon_profile_run() -> dict:
    cases = [{"near": n, "far": f, "fov": fov, "width": 120 * w, "height": 120 * h, "settings": {"mapSize": 1024, **s}}
             for (n, f, fov, (w, h)), s in _profile_cases(BABYLON_SETTINGS)]
    return _run("babylon_profile.mjs", BABYLON, {"lights": LIGHTS.tolist(), "cases": cases})


@pytest.fixture(scope="module")
def playcanvas_profile_run() -> dict:
    cases = [{"near": n, "far": f, "fov": fov, "aspect": w / h, "settings": s} for (n, f, fov, (w, h)), s in _profile_cases(PLAYCANVAS_SETTINGS)]
    return _run("playcanvas_profile.mjs", PLAYCANVAS, {"cases": cases})


def _check_texels(setup, rows: list) -> None:
    from aliasing.engines import pipeline

    got = pipeline.texels(setup.pipeline, setup.camera, LIGHTS)  # (N, K, 2)
    want = np.array([row["texels"] for row in rows])
    assert got.shape == want.shape, (setup.settings, got.shape, want.shape)
    assert _rel(got, want) <= RTOL
    assert _rel(pipeline.extents(setup.pipeline, setup.camera, LIGHTS), [row["depth"] for row in rows]) <= RTOL


@pytest.mark.parametrize("pin, release", [(THREE_CURRENT, "r187"), (THREE_R184, "r184")])
@pytest.mark.parametrize("case", range(len(PROFILE_CAMERAS) * len(THREE_SETTINGS)))
def test_threejs_profile_texels_are_the_engines(three_profile_runs, pin, release, case):
    cam, settings = _profile_cases(THREE_SETTINGS)[case]
    _check_texels(_setup(f"threejs@{release}", cam, settings), three_profile_runs[pin]["cases"][case]["rows"])


@pytest.mark.parametrize("pin, release", [(THREE_CURRENT, "r187"), (THREE_R184, "r184")])
def test_threejs_profile_defaults_are_the_engines(three_profile_runs, pin, release):
    from aliasing import setups

    d = three_profile_runs[pin]["defaults"]
    profile = setups.get(f"threejs@{release}")
    checked = set()
    for s in profile.settings:
        if s.key in NOT_ENGINE_KEYS:
            continue
        engine = d["values"][s.key]
        want = {"null": None, **d["constants"]}.get(s.default, s.default) if s.kind == "choice" else s.default  # THREE's constants
        assert engine == want, (s.key, engine, s.default)
        checked.add(s.key)
    assert checked == {s.key for s in profile.settings} - NOT_ENGINE_KEYS
    # CSM hands its shadowBias, shadowMapSize, lightNear and lightFar to each cascade's light
    p = profile.defaults()
    assert d["handed"] == {"bias": p["shadowBias"], "mapSize": p["shadowMapSize"], "near": p["lightNear"], "far": p["lightFar"],
                           "normalBias": p["shadow.normalBias"], "radius": p["shadow.radius"]}


@pytest.mark.parametrize("case", range(len(PROFILE_CAMERAS) * len(BABYLON_SETTINGS)))
def test_babylon_profile_texels_are_the_engines(babylon_profile_run, case):
    cam, settings = _profile_cases(BABYLON_SETTINGS)[case]
    _check_texels(_setup("babylon", cam, settings), babylon_profile_run["cases"][case]["rows"])


def test_babylon_profile_defaults_and_clamps_are_the_engines(babylon_profile_run):
    from aliasing import setups
    from aliasing.setups import babylon

    d = babylon_profile_run["defaults"]
    profile = setups.get("babylon")
    values, other, clamps = d["values"], d["other"], d["clamps"]
    for s in profile.settings:
        if s.key in NOT_ENGINE_KEYS:
            continue
        if s.key == "shadowMaxZ":  # null: the camera's maxZ
            assert s.default is None and values[s.key] == other["cameraMaxZ"]
        elif s.key == "filter":  # null: the class's default
            assert s.default is None
            assert values["filter"] == babylon.filter_name(profile.defaults())
            assert other["shadowGeneratorFilter"] == babylon.filter_name({**profile.defaults(), "class": "ShadowGenerator"})
        else:
            assert values[s.key] == s.default, (s.key, values[s.key], s.default)
    assert other["filterValues"] == babylon.FILTER_VALUES and list(other["qualityValues"]) == list(babylon.QUALITIES)
    assert tuple(other["counts"]) == babylon.CASCADES
    n, lam = profile.setting("numCascades"), profile.setting("lambda")
    for v in (1, 6, -3):
        assert clamps[f"numCascades={v}"] == n.clamped(v)
    for v in (2, -1, 0.3):
        assert clamps[f"lambda={v}"] == lam.clamped(v)
    for v in (3, -0.5, 0.4):
        assert clamps[f"darkness={v}"] == profile.setting("darkness").clamped(v)
    # shadowMaxZ outside [minZ, maxZ] is ignored by the setter: the profile ends the cascades at the camera's far then
    assert clamps["shadowMaxZ=0.01"] == clamps["shadowMaxZ=900"] == other["cameraMaxZ"] and clamps["shadowMaxZ=250"] == 250
    base = profile.defaults()
    for cut in (0.01, 900.0):
        assert np.array_equal(babylon.splits({**base, "shadowMaxZ": cut}, 0.1, 500.0)[1], babylon.splits(base, 0.1, 500.0)[1])
    assert clamps["minMax=0.7,0.3"] == clamps["minMax=-1,2"] == [0, 1] and clamps["minMax=0.1,0.6"] == [0.1, 0.6]
    assert clamps["csmFilterESM"] == babylon.filter_name({**base, "filter": "FILTER_EXPONENTIALSHADOWMAP"}) == "FILTER_NONE"


@pytest.mark.parametrize("case", range(len(PROFILE_CAMERAS) * len(PLAYCANVAS_SETTINGS)))
def test_playcanvas_profile_texels_are_the_engines(playcanvas_profile_run, case):
    from aliasing.engines import pipeline

    cam, settings = _profile_cases(PLAYCANVAS_SETTINGS)[case]
    setup = _setup("playcanvas", cam, settings)
    run = playcanvas_profile_run["cases"][case]["cascades"]
    assert _rel(setup.pipeline.far_i, [c["end"] for c in run]) <= RTOL  # the float32 ends
    got = pipeline.texels(setup.pipeline, setup.camera, LIGHTS)
    want = np.array([[c["texel"], c["texel_y"]] for c in run])
    assert got.shape == (len(LIGHTS),) + want.shape
    assert _rel(got, np.broadcast_to(want, got.shape)) <= RTOL


def test_playcanvas_profile_defaults_and_clamps_are_the_engines(playcanvas_profile_run):
    from aliasing import setups
    from aliasing.setups import playcanvas

    d = playcanvas_profile_run["defaults"]
    profile = setups.get("playcanvas")
    for s in profile.settings:
        assert d["values"][s.key] == s.default, (s.key, d["values"][s.key], s.default)
    assert d["constants"] == playcanvas.SHADOW_TYPES
    # the light's bias and the caster pass's depth bias (constant and slope) from the component's shadowBias
    bias = profile.setting("shadowBias")
    assert d["bias"] == {"light": -0.01 * bias.default, "constant": 10 * bias.default, "slope": 10 * bias.default}
    rule = setups.build("playcanvas").pipeline.bias
    assert rule.term("shadowBias").scale == 10.0 and rule.term("shadowBias").kind == "slope"
    for key, got in d["clamps"].items():
        name, _, value = key.partition("=")
        v = float(value)
        if name == "shadowBias":
            assert got == pytest.approx([-0.01 * bias.clamped(v), 10 * bias.clamped(v)], rel=1e-15, abs=0)
        elif name == "numCascades":
            assert got == profile.setting(name).clamped(int(np.floor(v)))
        else:
            assert got == profile.setting(name).clamped(v)
