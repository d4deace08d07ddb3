"""``tune --frames N``: tune's best candidates rendered in the engine itself, the pick kept or bettered by what they draw.

The N candidates are the search's pick, then the Pareto front in the pick rule's order
(:func:`aliasing.tune.pixels.front`), then the other candidates by the same rule.  Each is rendered by the engine at its pinned release
(:func:`aliasing.frames.run.frame_setup`, one shared :class:`aliasing.frames.browser.Browser`) on the same scene
as the search (the reference scene or the user's), at :data:`HEIGHT` rows and under :data:`SUNS` suns over the band;
the engine's read-back shadow and the toolkit's prediction of the same frame are counted alike
(:func:`aliasing.frames.seen.fractions`: acne, false and lost shadow of the sun-facing pixels; Godot draws one frame per
sun, the split per pixel from its own split offsets, not the second frame of its shader's choice: the counts need
the split only for a texel's size).  The pick is the
search's pick (the first) unless another candidate measures significantly fewer wrong pixels
(:func:`aliasing.tune.pixels.significant`: beyond the noise of the frames' counts), then the fewest
measured.
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from .. import _validation as check
from ..frames import seen
from ..frames.scenes import FrameScene, frame_scene, sun_direction
from ..setups import Setup, spec
from ..view import tan_theta
from .pixels import PREFER, Point, significant

#: Rows of each rendered frame [px].
HEIGHT = 144
#: Suns over the band per candidate.
SUNS = 2
_KEYS = ("acne", "false_shadow", "lost_shadow", "wrong")


def candidates(points, prefer: str, n: int, first: Point | None = None) -> list[Point]:
    """The first ``n`` points: ``first`` (the search's pick), then the others in ``prefer``'s order.

    Examples
    --------
    >>> a = Point({"k": 1}, 0.01, 0.0, 0.0, 0.01, 5.0, 64.0); b = Point({"k": 2}, 0.02, 0.0, 0.0, 0.02, 9.0, 64.0)
    >>> [p.settings["k"] for p in candidates([b, a], "wrong", 2)], [p.settings["k"] for p in candidates([b, a], "wrong", 2, first=b)]
    ([1, 2], [2, 1])
    """
    rule = check.choice(prefer, "prefer", tuple(PREFER))
    k = check.whole(n, "n", 1, 64, " (candidates rendered)")
    if first is not None and not isinstance(first, Point):
        raise ValueError(f"first must be a Point (the search's pick) or None, got {type(first).__name__}")
    unique: dict = {} if first is None else {first.axes(rule): first}
    for p in sorted((p for p in points if isinstance(p, Point)), key=lambda p: p.axes(rule)):
        unique.setdefault(p.axes(rule), p)  # one of the points equal on every axis (they differ in a digit of a bias or a setting that does nothing here)
    return list(unique.values())[:k]


def ready(engine: str) -> None:
    """Refuse, before any search, where ``engine``'s frames cannot be rendered: Playwright, Chromium or its pinned package missing.

    Raises
    ------
    aliasing.frames.MissingTool
        One line saying what is missing and how to install it.
    ValueError
        ``engine`` is not an engine with pinned frames.

    Examples
    --------
    >>> ready("filament")
    Traceback (most recent call last):
    ...
    ValueError: engine must be one of threejs, babylon, playcanvas, godot (the engines whose frames tune renders), got 'filament'
    """
    from ..frames import MissingTool, browser, install

    if engine not in seen.ENGINES:
        raise ValueError(f"engine must be one of {', '.join(seen.ENGINES)} (the engines whose frames tune renders), got {engine!r}")
    try:
        import playwright  # noqa: F401
    except ImportError:
        raise MissingTool("Playwright for Python is not installed: pip install 'aliasing[frames]'") from None
    if browser.chromium_path() is None:
        raise MissingTool("Chromium not found: install it (Debian: apt-get install chromium) or set ALIASING_CHROMIUM to its path")
    install.package_root(engine)


def _scene(setup: Setup, scene: Any):
    cam = setup.camera
    if isinstance(scene, FrameScene):
        return scene
    if scene is None:
        return seen.reference_scene(cam.near, cam.far, cam.fov, cam.aspect)
    return frame_scene(scene, near=cam.near, far=cam.far, fov=cam.fov, aspect=cam.aspect)


def prove(start: Setup, points, *, prefer: str = "wrong", n: int = 8, scene: Any = None, height: int | None = None,
          suns: int | None = None, first: Point | None = None) -> dict:
    """Render the search's pick and the next ``n`` − 1 candidates in the engine (module docstring) and keep the pick or a significantly better one.

    Parameters
    ----------
    start : Setup
        The user's setup (engine threejs, babylon, playcanvas or godot; its camera and sun band).
    points : iterable of Point
        The wrong-pixel search's candidates (:attr:`aliasing.tune.pixels.Seen.points`).
    prefer : str
        The order in which candidates are taken (:data:`aliasing.tune.pixels.PREFER`).
    n : int
        Candidates rendered, 1 to 64.
    scene : str, optional
        The scene (None: the reference scene).
    height : int, optional
        Rows of each frame [px], 16 to 1080 (default :data:`HEIGHT`).
    suns : int, optional
        Suns over the band per candidate, 1 to 16 (default :data:`SUNS`).
    first : Point, optional
        The search's pick (:attr:`aliasing.tune.pixels.Seen.pareto`'s first), rendered first and kept unless
        another candidate measures significantly fewer wrong pixels.

    Returns
    -------
    dict
        ``candidates`` (each: ``settings``, ``measured`` and ``predicted`` fractions of the sun-facing pixels
        summed over the suns), ``pick`` (the index picked: module docstring), ``height_px``, ``suns``,
        ``seconds``.

    Raises
    ------
    aliasing.frames.MissingTool
        Playwright, Chromium or the engine's pinned package is missing (one line saying how to install).
    ValueError
        Naming the parameter.

    Examples
    --------
    The engine draws in a browser, so the example is not run here:

    >>> from aliasing import setups
    >>> from aliasing.tune import pixels
    >>> s = setups.build("playcanvas", {}, "near=0.5,far=60,fov=50,aspect=16:9,height=720", "30..50")
    >>> got = prove(s, [pixels.Point(dict(s.settings), 0.1, 0.1, 0.0, 0.0, 5.0, 4.0)], n=1)    # doctest: +SKIP
    >>> got["candidates"][0]["measured"]["wrong"] >= 0                                          # doctest: +SKIP
    True
    """
    if not isinstance(start, Setup):
        raise ValueError(f"start must be an aliasing.setups.Setup (setups.build(...)), got {type(start).__name__}")
    picks = candidates(points, prefer, n, first)
    if not picks:
        raise ValueError("points: no candidate to render")
    t0 = time.perf_counter()
    got = render(start, [p.settings for p in picks], scene=scene, height=height, suns=suns)
    rows = [{"settings": r["settings"], "search": p.to_dict(start.settings), "measured": r["measured"], "predicted": r["predicted"]}
            for p, r in zip(picks, got["rows"])]
    best = pick(rows)
    return {"candidates": rows, "pick": best, "height_px": got["height_px"], "suns": got["suns"], "seconds": round(time.perf_counter() - t0, 3),
            "scene": got["scene"], "units": "fractions of the sun-facing pixels, summed over the suns"}


def pick(rows: list) -> int:
    """The index kept of rendered ``rows`` (each with ``measured`` ``wrong`` and ``pixels``): the first unless another
    measures significantly fewer wrong pixels (:func:`aliasing.tune.pixels.significant`), then the fewest of those.

    Examples
    --------
    >>> row = lambda w: {"measured": {"wrong": w, "pixels": 20000}}
    >>> pick([row(0.0010), row(0.0008)]), pick([row(0.0010), row(0.0002), row(0.0001)])    # 20 against 16 pixels; 2 against 20
    (0, 2)
    """
    def wrong(i: int) -> float:
        w = rows[i]["measured"]["wrong"]
        return math.inf if w is None else w

    if not rows:
        raise ValueError("rows: nothing rendered")
    better = [i for i in range(1, len(rows)) if rows[0]["measured"]["wrong"] is None
              or (wrong(i) < wrong(0) and significant(wrong(i), wrong(0), int(rows[0]["measured"]["pixels"])))]
    return min(better, key=lambda i: (wrong(i), i)) if better else 0


def render(start: Setup, settings: list, *, scene: Any = None, height: int | None = None, suns: int | None = None) -> dict:
    """Each of ``settings`` (the engine's settings, dicts) rendered in the engine on one scene: measured and predicted fractions.

    Parameters
    ----------
    start : Setup
        The engine, camera and sun band (its settings are not rendered unless listed).
    settings : list of dict
        The settings rendered, in order.
    scene : FrameScene or str, optional
        None: the reference scene; a FrameScene built with ``start``'s camera at ``height`` rows; or a scene name or file.
    height, suns : int, optional
        Rows of each frame [px] and suns over the band (defaults :data:`HEIGHT`, :data:`SUNS`).

    Returns
    -------
    dict
        ``rows`` (each: ``settings``, ``measured``, ``predicted``: fractions of the sun-facing pixels), ``height_px``,
        ``suns``, ``scene``.

    Raises
    ------
    aliasing.frames.MissingTool
        Playwright, Chromium or the engine's pinned package is missing.
    ValueError
        Naming the parameter.

    Examples
    --------
    The engine draws in a browser, so the example is not run here:

    >>> from aliasing import setups
    >>> s = setups.build("playcanvas", {}, "near=0.5,far=60,fov=50,aspect=16:9,height=720", "30..50")
    >>> render(s, [dict(s.settings)])["rows"][0]["measured"]["wrong"] >= 0          # doctest: +SKIP
    True
    """
    from ..frames import install
    from ..frames.browser import Browser
    from ..frames.run import frame_setup

    if not isinstance(start, Setup):
        raise ValueError(f"start must be an aliasing.setups.Setup (setups.build(...)), got {type(start).__name__}")
    if not isinstance(settings, (list, tuple)) or not settings or not all(isinstance(x, dict) for x in settings):
        raise ValueError("settings must be a non-empty list of the engine's settings (dicts)")
    h = check.whole(HEIGHT if height is None else height, "height", 16, 1080, " [px] (rows of each frame)")
    k = check.whole(SUNS if suns is None else suns, "suns", 1, 16, " (suns per candidate)")
    install.package_root(start.engine)  # MissingTool: how to install, before the browser starts
    cam = start.camera
    small_cam = spec.Camera(cam.near, cam.far, cam.fov, cam.aspect, h)
    fs = _scene(Setup(start.profile, dict(start.settings), small_cam, start.sun), scene)
    rows = []
    with Browser() as browser:
        for given in settings:
            s = Setup(start.profile, dict(given), small_cam, start.sun)
            taps = max(1, int(s.pipeline.filter.taps))
            tally = {"measured": np.zeros(5), "predicted": np.zeros(5)}
            for e in s.sun.elevations(k):
                sun = sun_direction(float(e), s.sun.azimuth, fs.camera)
                r = frame_setup(browser, s, fs, sun, probe=False)  # Godot: the split from its offsets (no second frame)
                rb, pred = r.readback, r.prediction
                depth = np.where(rb.drawn, fs.camera.to_eye(np.nan_to_num(rb.position))[..., 2], np.nan)
                pixel = 2 * depth * tan_theta(cam.fov) / rb.shadow.shape[0]
                sides = np.append(pred.sides / pred.resolution, np.nan)
                for name, factor, cascade in (("measured", rb.shadow, rb.cascade), ("predicted", pred.factor, pred.cascade)):
                    texel = sides[np.where((cascade >= 0) & (cascade < len(pred.sides)), cascade, len(pred.sides))]
                    f = seen.fractions(factor, r.reference, rb.drawn, rb.normal, sun, texel, pixel, taps)
                    tally[name] += [f["pixels"]] + [0.0 if f[key] is None else f[key] * f["pixels"] for key in _KEYS]
            row: dict[str, Any] = {"settings": dict(s.settings)}
            for name, t in tally.items():
                row[name] = {"pixels": int(t[0]), **{key: (float(t[i + 1] / t[0]) if t[0] else None) for i, key in enumerate(_KEYS)}}
            rows.append(row)
    return {"rows": rows, "height_px": h, "suns": k, "scene": fs.name}
