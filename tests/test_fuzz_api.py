"""API fuzz suite (issue 19 item 5): every public function, fed generated garbage, ends in a
result or a ValueError/TypeError whose message names one of its parameters.

Targets are discovered, not listed: every function in the ``__all__`` of the package and of
its modules and subpackages, plus the public functions of the modules in ``NO_ALL`` (modules
owned elsewhere that have no ``__all__`` yet).  Each target starts from a valid base call
(``BASE``; the test ``test_base_calls_succeed`` proves each one works, so mutations reach past
the first check) and Hypothesis replaces one to three of its arguments with generated values:
scalars, NaN/±inf, huge (10^400) and tiny numbers, complex, strings, None, booleans, empty,
0-d and mismatched arrays, nested lists.  Outcomes allowed:

* a result, which contains no NaN (a valid but overflowing input gives inf or a refusal);
* ``ValueError`` or ``TypeError`` whose message names a parameter of the function.

Anything else (another exception type, a numpy RuntimeWarning, which pytest turns into an
error) fails.  Sizes are bounded so nothing hangs.  The "ci" profile (default, derandomized)
runs ``CI_CALLS`` calls; ``ALIASING_HYPOTHESIS=long`` or ``--hypothesis-profile=long`` many more.
"""

from __future__ import annotations

import importlib
import inspect
import math
import re
from collections.abc import Callable

import numpy as np
import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

import aliasing  # noqa: E402
from aliasing.aliasing_matrix import Camera, camera_axes  # noqa: E402

# Modules whose functions are fuzzed.  Modules with an ``__all__`` contribute its functions;
# the ones in NO_ALL (owned by other work, no ``__all__`` yet) their public functions.
WITH_ALL = [
    "aliasing",
    "aliasing.error",
    "aliasing.budgets",
    "aliasing.partitioning",
    "aliasing.logpsm",
    "aliasing.gmnpr",
    "aliasing.face_factors",
    "aliasing.aliasing_matrix",
    "aliasing.parameterizations",
    "aliasing.raster",
    "aliasing.tune",
    "aliasing.tune.report",
]
# The engines' setups and their check: fuzzed by their own test below (their own draws, so that adding
# them does not move the draws of the targets above).
SETUP_MODULES = ["aliasing.setups", "aliasing.check"]
NO_ALL = ["aliasing.geometry", "aliasing.warping", "aliasing.schemes", "aliasing.directional", "aliasing.faces"]

# Left out, with the open problem each one has (see the report of issue 19):
EXCLUDED = {
    # registry decorators: they take a name and return a decorator; fuzzing them would
    # register garbage in the process-wide tables
    "aliasing.warping.register",
    # an unchecked inner-loop kernel by contract (its docstring): schemes validates at its edge
    "aliasing.warping.eta_checked",
    "aliasing.partitioning.register",
    # its messages name the kind of name it resolves (``what``: "split method", "stable preset"), as
    # the command line shows them; NAME@RELEASE is fuzzed by tests/test_split_properties.py
    "aliasing.partitioning.resolve_name",
    # reads a file path: covered by the file scenarios of tests/test_raster.py
    "aliasing.raster.scenes.loading.load_mesh",
    # one call searches for a second or more: fuzzed argument by argument in tests/test_tune_start.py
    "aliasing.tune.search.tune",
    # its name is the rasterizer's measure in BASE below; its garbage is refused in tests/test_tune_start.py
    "aliasing.tune.measure.measure",
    # reads a file path: covered by tests/test_check.py's settings files
    "aliasing.setups.spec.load_settings",
    # adds options to an argparse parser (the command line's own set-up, not a value): the CLI fuzz suites reach it
    "aliasing.setups.add_arguments",
}

EYE = Camera(axes=np.eye(3), position=[0.0, 0.0, 5.0])
LIGHT = Camera(axes=camera_axes([0.0, -1.0, -1.0]), position=[0.0, 5.0, 5.0])
TRI = np.array([[[-1.0, -1.0, 0.5], [1.0, -1.0, 0.5], [0.0, 1.0, 0.6]]])  # one (s, t, depth) triangle


def _lazy(make: Callable[[], object]) -> Callable[[], object]:
    """A base argument built on first use (light maps, scenes): shared by all calls."""
    cache: list = []

    def get():
        if not cache:
            cache.append(make())
        return cache[0]

    get.lazy = True  # type: ignore[attr-defined]
    return get


_LM = _lazy(lambda: aliasing.raster.light_map(1.0, 50.0, 60.0, "gamma:60", "P"))
_MAPS = _lazy(lambda: aliasing.raster.map_set(1.0, 50.0, 60.0, "gamma:60", "ZP2+P"))
_FIT = _lazy(lambda: aliasing.directional.fit(aliasing.geometry.frustum_vertices(1.0, 10.0, 60.0), [0.0, 1.0, 0.3]))
_FRAME = _lazy(lambda: aliasing.directional.light_frame(aliasing.View(1.0, 100.0, 60.0), [[0.0, 1.0, 0.3], [0.2, 0.5, -0.8]]))
_SLICES = _lazy(lambda: aliasing.directional.slice_fit(_FRAME(), [1.0, 10.0], [10.0, 100.0]))
_SETUP = _lazy(lambda: aliasing.setups.build("threejs", {"cascades": 2, "shadowMapSize": 512, "material.shadowSide": "FrontSide"},
                                              "near=0.5,far=60,fov=50,aspect=1,height=64", "30"))
_TUNED = _lazy(lambda: aliasing.tune.tune(_SETUP(), receivers=(1.0, 50.0), keep=("cascades", "shadowMapSize", "mode", "renderer.shadowMap.type")))
_ARGS = _lazy(lambda: __import__("argparse").Namespace(engine="threejs", settings=None, set_=["cascades=2"], camera="near=1,far=100", sun="30"))
_FACTORS = _lazy(lambda: aliasing.face_factors.face_factors("logp", 1.0, 10.0, 60.0, ly=[0.5, 1.0], lz=1.0, samples=9))

# A valid value per parameter name; BASE overrides it per function.
BY_NAME: dict[str, object] = {
    "near": 1.0, "far": 100.0, "fov": 60.0, "gamma": 60.0, "azimuth": 30.0, "z": 10.0, "n_prime": 5.0,
    "eta": 0.5, "res_image": 512.0, "res_s": 256.0, "res_t": 256.0, "budget": 1e6, "res_s_critical": 40.0,
    "res_t_critical": 30.0, "M_x": [[3.0, 2.0]], "M_z": [[4.0, 1.0]], "k": 3, "light": "overhead", "lam": 0.4,
    "y": 2.0, "y0": 1.0, "y1": 4.0, "a": 0.5, "b": 10.0, "v": 0.3, "u": 0.5, "t": 0.5, "coord": 0.5,
    "lx": 0.2, "ly": 0.5, "lz": 2.0, "count": 10, "resolution": 8, "x": 30.0, "depth": 50.0, "focus": 0.25,
    "line": 0.8, "point": [0.3, 0.0, -2.0], "normal": [0.0, 0.0, 1.0], "eye": EYE, "view": [0.0, 0.0, -1.0],
    "up": [0.0, 1.0, 0.0], "dF_du": [[1.0, 0.0], [0.5, 2.0]], "M": [[1.0, 0.5], [0.2, 2.0]],
    "lam_": 1.0, "samples": 9, "vertices": [[0.0, 0.0, 1.0], [1.0, 0.0, 5.0], [0.0, 1.0, 5.0]],
    "points": [[0.0, 0.0, 5.0]], "triangles": TRI, "lm": _LM, "lf": _FIT, "factors": _FACTORS,
}
BASE: dict[str, dict[str, object]] = {
    "warping_parameter": {"method": "lispsm"},
    "n_prime_tsm": {},
    "shaping_eta": {"shaping": "p"},
    "allocate": {"method": "error"},
    "max_error": {"res_s": [[100.0, 90.0]], "res_t": [[100.0, 80.0]]},
    "splits_report": {"method": "practical", "near": 1.0, "far": 100.0, "k": 2, "light": "overhead", "budget": 1e6, "res_image": 512.0},
    "split_distances": {"method": "practical", "k": 3},
    "partitions": {"method": "bgfx"},
    "aliasing_error": {"dG_dt": 1.0, "W_l": 2.0, "W_e": 2.0, "n_e": 1.0, "d_e": 5.0, "phi_l": 10.0, "phi_e": 20.0, "psi_e": 30.0, "psi_l": 40.0},
    "perspective_factor": {"W_l": 2.0, "W_e": 2.0, "n_e": 1.0, "d_e": 5.0, "phi_l": 10.0, "phi_e": 20.0},
    "zeta_bound": {"kind": "side_t", "lz": 2.0},
    "rho_bound": {"kind": "side_t", "lz": 2.0},
    "parameterization": {"kind": "logp_t"},
    "spacing": {"kind": "logp_t"},
    "critical_factor_side": {"kind": "logp", "direction": "t", "samples": 9},
    "face_factors": {"kind": "logp", "lz": 2.0},
    "optimal_factors": {"kind": "logp", "lz": 2.0},
    "optimal_root": {"lz": 2.0},
    "aliasing_matrix": {"light": LIGHT},
    "spacing_eye": {"light": LIGHT},
    "halfway_normal": {"light": LIGHT},
    "cross_sections": {"light": LIGHT},
    "error_metric": {"metric": "2"},
    "generalized_error": {"lam": 1.0, "z": 10.0},
    "direction_angles": {"light": [0.0, 1.0, 1.0]},
    "light_space": {"light": [0.0, 1.0, 1.0]},
    "parse": {"name": "ZP3+LogP"},
    "evaluate": {"scheme": "ZP2+P", "light": "sphere:4"},
    "fit": {"light": [0.0, 1.0, 0.3]},
    "max_errors": {"light": [0.0, 1.0, 0.3]},
    "folded_gamma": {"light": [0.0, 1.0, 0.3]},
    "chosen_faces": {"light": [[0.0, 1.0, 0.3]]},
    "partition_of": {"light": [[0.0, 1.0, 0.3]], "far": 10.0, "fov": 60.0},  # near may be a View: far, fov have defaults
    "face_frames": {"variant": "fpc", "parameterization": "perspective", "light": [[0.0, 1.0, 0.3]], "far": 10.0, "fov": 60.0},
    "face_errors": {"variant": "fpc", "parameterization": "perspective", "light": [[0.0, 1.0, 0.3]], "far": 10.0, "fov": 60.0},
    "lights": {"spec": "gamma:30@azimuth:10"},
    "eye_pass": {"resolution": 8},
    "frame_map": {"light": [0.0, 1.0, 0.3], "axis": [1.0, 0.0, 0.0], "y0": 1.0, "y1": 10.0, "a": 0.5, "s_lo": -1.0, "s_hi": 1.0, "parameterization": "perspective"},
    "ground_and_boxes": {"far": 30.0, "boxes": 2, "ground_cells": 2},
    "light_map": {"far": 50.0, "fov": 60.0, "light": "gamma:60", "scheme": "P"},
    "light_maps": {"far": 50.0, "fov": 60.0, "light": "gamma:60", "scheme": "ZP2+P"},
    "map_set": {"far": 50.0, "fov": 60.0, "light": "gamma:60", "scheme": "P"},
    "measure": {"far": 20.0, "fov": 60.0, "light": "gamma:60", "scheme": "P", "resolution": 16, "cells": 2, "map_resolution": 16},
    "near_face_map": {"light": [0.0, 1.0, 0.3], "fov": 60.0},  # near may be a View: fov has a default
    "probes": {"far": 20.0, "fov": 60.0, "light": "gamma:60", "cells": 2},
    "project": {"points": [[0.0, 0.0, 5.0]]},
    "rasterize": {"triangles": TRI, "resolution": 8},
    "shadow_map": {"resolution": 8},
    "shadow_maps": {"maps": _MAPS, "resolution": 8},
    "log_row_centres": {"resolution": 8},
    "side_frames": {}, "storage_factor": {"far": 100.0, "fov": 60.0, "n_prime": 5.0},
    # near may be a View (issue 11), so far and fov have defaults: give them
    "storage_factor_optimal": {"far": 100.0, "fov": 60.0},
    "max_error_z": {"far": 100.0, "fov": 60.0, "n_prime": 5.0},
    "critical_resolution": {"far": 100.0, "fov": 60.0, "n_prime": 5.0},
    "frustum_vertices": {"far": 100.0, "fov": 60.0},
    # the shared light frames of schemes.evaluate_many (issue 12)
    "light_frame": {"view": aliasing.View(1.0, 100.0, 60.0), "light": [[0.0, 1.0, 0.3], [0.2, 0.5, -0.8]]},
    "slice_fit": {"frame": _FRAME, "near": [1.0, 10.0], "far": [10.0, 100.0]},
    "slice_errors": {"sf": _SLICES, "n_prime": 5.0},
    "evaluate_many": {"names": ["P", "ZP2+LogP"], "light": "sphere:4"},
    # aliasing.tune: a small three.js setup and its tuned result
    "limits": {"setup": _SETUP},
    "closed_form_bias": {"setup": _SETUP, "key": "shadow.normalBias"},
    "compare_splits": {"tuned": _TUNED},
    "worse": {"tuned": _TUNED},
    "changes_text": {"tuned": _TUNED},
    "scene_receivers": {"scene": [[[-1.0, -1.0, 5.0], [1.0, -1.0, 5.0], [0.0, 1.0, 6.0]]], "setup": _SETUP},
    "equal_error_split": {"pipe": _lazy(lambda: _SETUP().pipeline), "cam": _lazy(lambda: _SETUP().camera), "lights": [[0.0, 0.5, 0.866]],
                          "k": 2, "near": 0.5, "far": 60.0, "receivers": (1.0, 50.0), "iterations": 8},
    # the engines' setups and their check (aliasing.setups, aliasing.check)
    "parse_camera": {"spec": "near=1,far=100,fov=50deg,aspect=1920x1080"},
    "parse_sun": {"spec": "15..60@30"},
    "parse_set": {"items": ["cascades=2"]},
    "get": {"spec": "threejs@r187"},
    "profiles": {"engine": "babylon"},
    "build": {"engine": "godot", "settings": {"directional_shadow_mode": 2}, "camera": "near=0.5,far=800,fov=0.8rad", "sun": "30"},
    "from_args": {"args": _ARGS},
    "aliasing.setups.project": {"args": _ARGS},
    "resolve": {"args": _ARGS},
    "check": {"setup": _SETUP, "samples": 2},
    "units": {"setup": _SETUP},
    "header": {"key": "gap_px", "unit": "px"},
    "fixed_face_map": {"far": 50.0, "fov": 60.0, "light": [0.0, 1.0, 0.3], "face": "bottom", "parameterization": "perspective"},
}
# Results that may hold NaN by contract (documented in the function's docstring).
NAN_BY_CONTRACT = {"lambda_glpr", "hemisphere_map", "splits_report", "eye_pass", "measure", "face_errors", "face_frames"}


def _targets(with_all: list[str] = WITH_ALL, no_all: list[str] = NO_ALL) -> dict[str, Callable]:
    found: dict[str, Callable] = {}
    for name in with_all:
        mod = importlib.import_module(name)
        for attr in mod.__all__:
            obj = getattr(mod, attr)
            if inspect.isfunction(obj):
                found.setdefault(f"{obj.__module__}.{obj.__name__}", obj)
    for name in no_all:
        mod = importlib.import_module(name)
        for attr, obj in vars(mod).items():
            if not attr.startswith("_") and inspect.isfunction(obj) and obj.__module__ == name:
                found.setdefault(f"{name}.{attr}", obj)
    return {key: f for key, f in sorted(found.items()) if key not in EXCLUDED}


TARGETS = _targets()
SETUP_TARGETS = _targets(SETUP_MODULES, [])
ALL_TARGETS = TARGETS | SETUP_TARGETS


def _params(func: Callable) -> list[inspect.Parameter]:
    return [p for p in inspect.signature(func).parameters.values() if p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]


def _base(func: Callable) -> dict[str, object]:
    """Keyword arguments of a valid call: every required parameter, plus BASE's overrides."""
    over = BASE.get(f"{func.__module__}.{func.__name__}", BASE.get(func.__name__, {}))  # a qualified key where two share a name
    kwargs = {}
    for p in _params(func):
        if p.name in over:
            kwargs[p.name] = over[p.name]
        elif p.default is p.empty:
            kwargs[p.name] = BY_NAME[p.name]
    for key, value in over.items():
        kwargs.setdefault(key, value)
    return {key: (v() if getattr(v, "lazy", False) else v) for key, v in kwargs.items()}


def _call(func: Callable, kwargs: dict[str, object]) -> object:
    """Call with positional-or-keyword parameters passed by position (as users do)."""
    args, rest = [], dict(kwargs)
    for p in _params(func):
        if p.kind is p.POSITIONAL_OR_KEYWORD and p.name in rest:
            args.append(rest.pop(p.name))
        else:
            break
    return func(*args, **rest)


def _has_nan(value: object, depth: int = 0) -> bool:
    if depth > 4:
        return False
    if isinstance(value, (float, np.floating)):
        return bool(np.isnan(value))
    if isinstance(value, np.ndarray):
        return value.dtype.kind in "fc" and bool(np.isnan(value).any())
    if isinstance(value, dict):
        return any(_has_nan(v, depth + 1) for v in value.values())
    if isinstance(value, (list, tuple)):
        return any(_has_nan(v, depth + 1) for v in value[:64])
    fields = getattr(value, "__dataclass_fields__", None)
    if fields:
        return any(_has_nan(getattr(value, f), depth + 1) for f in fields)
    return False


# --- generated values ---------------------------------------------------------------------------
VOCABULARY = ["overhead", "behind", "front", "gamma:30", "gamma:inf", "sphere:5", "sphere:1e400", "hemisphere:0", "P", "LogP",
              "ZP3+P", "log", "practical", "bgfx", "error", "pow2", "logp", "t", "s", "far", "side", "nan", "inf", "-inf", "1e400",
              "", " ", "ß∂", "10.5", "0"]
floats = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(-1e3, 1e3),
    st.sampled_from([0.0, -0.0, 1.0, -1.0, 0.5, 1e-308, 5e-324, 1e308, -1e308, 90.0, 180.0, 1 + 1e-15, math.inf, -math.inf, math.nan]),
)
ints = st.one_of(st.integers(-3, 12), st.sampled_from([10**30, -(10**30), 10**400, 2**63, 2**31]))
scalars = st.one_of(floats, ints, st.booleans(), st.complex_numbers(max_magnitude=1e3), st.just(1j), st.none(),
                    st.sampled_from(VOCABULARY), st.text(max_size=6), st.just(b"1.0"), st.just(object()))
shapes = st.sampled_from([(), (0,), (1,), (2,), (3,), (2, 3), (1, 3), (3, 3), (2, 2), (0, 3), (2, 1, 3)])
arrays = st.builds(
    lambda shape, fill: np.full(shape, fill), shapes,
    st.one_of(floats, st.sampled_from([1.0, 2.0, 60.0, 0.3]), st.complex_numbers(max_magnitude=10)),
)
nested = st.sampled_from([[], [[]], [1.0, [2.0]], [[1.0, 2.0], [3.0]], (1.0, 2.0), {"a": 1.0}, [None], ["1", "2", "3"],
                          [math.nan, 0.0, 1.0], [0.0, 0.0, 0.0], [math.inf, 0.0, 1.0], [1e308, 1e308, 1e308], [10**400, 0, 1]])
values = st.one_of(scalars, arrays, nested)

CI_CALLS = 2400
SETUP_CALLS = 400


# Names a message may use for a parameter: its symbol or its command-line option.
ALIASES = {"lam": {"lambda"}, "spec": {"light", "camera", "sun", "engine"}, "items": {"--set"}, "settings": {"setting"},
           "args": {"engine", "camera", "sun", "settings", "--set", "--settings"}}


def _names(func: Callable, kwargs: dict[str, object]) -> set[str]:
    names = {p.name for p in _params(func)} | set(kwargs)
    return names.union(*(ALIASES.get(n, set()) for n in names))


@st.composite
def calls(draw, targets=TARGETS):
    key = draw(st.sampled_from(sorted(targets)))
    func = targets[key]
    kwargs = _base(func)
    params = [p.name for p in _params(func)]
    var_kw = any(p.kind is p.VAR_KEYWORD for p in inspect.signature(func).parameters.values())
    if var_kw:
        params.append("unknown_option")
    chosen = draw(st.lists(st.sampled_from(params), min_size=1, max_size=min(3, len(params)), unique=True))
    for name in chosen:
        kwargs[name] = draw(values)
    return key, kwargs


def _check_outcome(key: str, kwargs: dict[str, object]) -> None:
    func = ALL_TARGETS[key]
    try:
        result = _call(func, kwargs)
    except (ValueError, TypeError) as exc:
        message = str(exc)
        names = _names(func, kwargs)
        assert any(re.search(rf"(?<![A-Za-z0-9_]){re.escape(n)}(?![A-Za-z0-9_])", message) for n in names), (
            f"{key}: {type(exc).__name__} names no parameter of {sorted(names)}: {message!r}")
        return
    assert func.__name__ in NAN_BY_CONTRACT or not _has_nan(result), f"{key} returned NaN for {kwargs!r}"


def test_targets_cover_the_public_api():
    # discovery works: the package's own __all__ and every fuzzed module are there
    assert len(TARGETS) >= 60
    for name in aliasing.__all__:
        if inspect.isfunction(getattr(aliasing, name)):
            assert any(key.endswith(f".{name}") for key in TARGETS), name


@pytest.mark.parametrize("key", sorted(ALL_TARGETS))
def test_base_calls_succeed(key):
    """Each base call is valid, so a mutated argument is what a refusal is about."""
    func = ALL_TARGETS[key]
    result = _call(func, _base(func))
    assert func.__name__ in NAN_BY_CONTRACT or not _has_nan(result)


@settings(max_examples=max(settings.default.max_examples, CI_CALLS), suppress_health_check=list(HealthCheck), deadline=None)
@given(call=calls())
def test_public_functions_fail_cleanly(call):
    key, kwargs = call
    _check_outcome(key, kwargs)


def test_setup_targets_cover_setups_and_check():
    for name in ("parse_camera", "parse_sun", "parse_set", "build", "get", "profiles", "from_args", "resolve", "check", "units", "header"):
        assert any(key.endswith(f".{name}") for key in SETUP_TARGETS), name


@settings(max_examples=SETUP_CALLS, suppress_health_check=list(HealthCheck), deadline=None)
@given(call=calls(SETUP_TARGETS))
def test_setups_and_check_fail_cleanly(call):
    """The engines' setups and check, fed garbage: a result, or a ValueError/TypeError naming a parameter
    (parse_camera({'aspect': None}), parse_set(5), parse_sun(None) and build with wrong types among them)."""
    key, kwargs = call
    _check_outcome(key, kwargs)


# --- the last bad-input kinds a generated harness found ------------------------------------------------
# Each property failed before its fix: a TypeError naming nothing (scheme lists), an OverflowError or
# ComplexWarning from numpy (raster validation's light), or a result where a refusal was due (n_prime
# below near beside an empty far; far=None beside a numeric near), which an outcome check cannot see.
# The sweep's entry points are not among the generic targets above: fed to them, sweep() and plan()
# still fail on other parameters (an empty or 2-d f_over_n, a scalar light, a list near: numpy's own
# TypeError or ValueError naming nothing), which is open work.

not_names = st.one_of(
    ints, floats, st.complex_numbers(max_magnitude=10), st.none(), st.just(object()), st.just(b"P"),
    st.lists(st.one_of(ints, floats, st.complex_numbers(max_magnitude=10), st.none(), st.lists(st.just("P"), max_size=2)), min_size=1, max_size=3),
)


@settings(max_examples=80, deadline=None, suppress_health_check=list(HealthCheck))
@given(value=not_names, which=st.sampled_from(["plan", "sweep", "table"]))
def test_scheme_lists_that_are_not_names_are_refused_by_name(value, which):
    from aliasing import sweep

    func, param = {"plan": (sweep.plan, "schemes"), "sweep": (sweep.sweep, "scheme_names"), "table": (sweep, "schemes")}[which]
    with pytest.raises((TypeError, ValueError), match=rf"\b{param}\b"):
        func(value, f_over_n=[10.0], fov=[60.0], light="overhead")


empty_or_not = st.one_of(st.just(np.array([])), st.just(np.zeros((0, 3))), st.floats(20.0, 1e4), st.lists(st.floats(20.0, 1e4), min_size=1, max_size=3).map(np.array))


@settings(max_examples=80, deadline=None, suppress_health_check=list(HealthCheck))
@given(near=st.floats(0.5, 10.0), fraction=st.floats(0.0, 0.999), far=empty_or_not, which=st.sampled_from(["critical_resolution", "max_error_z", "storage_factor", "max_error_x"]))
def test_n_prime_below_near_is_refused_whatever_far(near, fraction, far, which):
    from aliasing import error

    func = getattr(error, which)
    args = (near, far, near * fraction) if which == "max_error_x" else (near, far, 60.0, near * fraction)
    with pytest.raises(ValueError, match=r"\bn_prime\b"):
        func(*args)


@settings(max_examples=40, deadline=None, suppress_health_check=list(HealthCheck))
@given(near=st.one_of(st.floats(0.01, 100.0), st.integers(1, 100), st.just(np.array([1.0, 2.0]))), many=st.booleans())
def test_far_none_beside_a_numeric_near_is_refused(near, many):
    from aliasing import schemes

    call = (lambda: schemes.evaluate_many(["P"], near, None, 60.0, "overhead")) if many else (lambda: schemes.evaluate("P", near, None, 60.0, "overhead"))
    with pytest.raises(ValueError, match=r"\bfar\b"):
        call()


bad_lights = st.one_of(
    st.sampled_from([[], [[]], [[0.0, 1.0, 0.0], [1.0, 0.0]], [0.0, [1.0, 0.0], 0.0], [10**400, 0, 1], [0.0, 1.0, 10**400]]),
    st.builds(lambda shape: np.zeros(shape), st.sampled_from([(0,), (0, 3), (2, 0)])),
    st.builds(lambda z: np.array([0.0, 1.0, 0.0]) + z, st.complex_numbers(max_magnitude=10).filter(lambda z: z.imag != 0)),
    st.lists(st.lists(floats, max_size=4), min_size=2, max_size=3).filter(lambda rows: len({len(r) for r in rows}) > 1),
)


@settings(max_examples=60, deadline=None, suppress_health_check=list(HealthCheck))
@given(light=bad_lights)
def test_raster_validate_refuses_ragged_empty_complex_and_huge_lights_by_name(light):
    from aliasing.raster.validate import validate

    with pytest.raises(ValueError, match=r"\blight\b"):
        validate("P", 20.0, 60.0, light, res=16, probes=4)
