"""Camera and sun paths: the motions of a shimmer sequence, one named entry per motion.

A motion is a text ``KIND:ARGS`` (:data:`MOTIONS`):

``translate:DX,DY,DZ``
    The camera moves by this eye-space step per frame [world units] (x right, y up, z along
    the view): ``translate:0.05,0,0`` is sideways, ``translate:0,0,0.05`` along the view.
``rotate:yaw|pitch,DEG``
    The camera turns about its own up (yaw) or right (pitch) axis by DEG per frame [deg].
``zoom:DEG``
    The full (vertical) field of view changes by DEG per frame [deg]; the aspect stays.
``sun:DEG``
    The light turns by DEG per frame [deg] about the world's vertical (y).

:func:`frames` turns a motion into per-frame camera poses, fields of view and lights: the
world itself never moves.

Example
-------
>>> m = parse_motion("translate:0.1,0,0")
>>> m.kind, m.step.tolist()
('translate', [0.1, 0.0, 0.0])
>>> eye, rot, fov, light = frames(m, [0, 1, 0], np.eye(3), 60.0, [0, 1, 0], 3)
>>> eye[:, 0].tolist(), fov.tolist()
([0.0, 0.1, 0.2], [60.0, 60.0, 60.0])
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _validation as check

Array = NDArray[np.float64]

#: Largest number of frames of a sequence (its per-frame states are held in memory: frames ×
#: points booleans and cascade indices); refused before any work beyond it.
MAX_FRAMES = 100_000
#: Largest per-frame turn or zoom [deg]: a larger step is not a motion but a cut.
MAX_STEP_DEG = 90.0


@dataclass(frozen=True)
class Motion:
    """A parsed motion: ``kind`` (a key of :data:`MOTIONS`), ``axis`` ("yaw"/"pitch" for
    rotate, else ""), ``step`` (the per-frame step: a 3-vector [world units] for translate,
    one angle [deg] otherwise) and the ``text`` it was read from."""

    kind: str
    axis: str
    step: Array
    text: str


@dataclass(frozen=True)
class _Entry:
    args: str
    help: str


MOTIONS: dict[str, _Entry] = {
    "translate": _Entry("DX,DY,DZ", "the camera moves by this eye-space step per frame [world units]"),
    "rotate": _Entry("yaw|pitch,DEG", "the camera turns about its up (yaw) or right (pitch) axis by DEG per frame"),
    "zoom": _Entry("DEG", "the full (vertical) field of view changes by DEG per frame"),
    "sun": _Entry("DEG", "the light turns by DEG per frame about the world's vertical"),
}


def _number(text: str, what: str, motion: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"motion {motion!r}: {what} must be a number, got {text!r}") from None
    if not np.isfinite(value):
        raise ValueError(f"motion {motion!r}: {what} must be finite, got {text!r}")
    return value


def parse_motion(text: str) -> Motion:
    """Read a motion spec (module docstring); ValueError naming the motion and what is wrong.

    Example
    -------
    >>> parse_motion("rotate:yaw,0.5").axis, parse_motion("sun:-1").step.tolist()
    ('yaw', [-1.0])
    """
    if not isinstance(text, str):
        raise ValueError(f"motion must be text such as translate:0.1,0,0, got {check._repr(text)}")
    spec = text.strip()
    kind, colon, args = spec.partition(":")
    kind = kind.lower()
    if kind not in MOTIONS:
        raise ValueError(f"motion {text!r}: unknown kind {kind!r}; allowed: " + ", ".join(f"{k}:{e.args}" for k, e in MOTIONS.items()))
    if not colon or not args.strip():
        raise ValueError(f"motion {text!r}: {kind} needs {MOTIONS[kind].args}")
    parts = [p.strip() for p in args.split(",")]
    if kind == "translate":
        if len(parts) != 3:
            raise ValueError(f"motion {text!r}: translate needs three numbers DX,DY,DZ [world units per frame]")
        step = np.array([_number(p, name, text) for p, name in zip(parts, ("DX", "DY", "DZ"))])
        if not np.abs(step).max() > 0:
            raise ValueError(f"motion {text!r}: the step is zero (a still camera shows no motion)")
        return Motion(kind, "", step, spec)
    if kind == "rotate":
        if len(parts) != 2 or parts[0].lower() not in ("yaw", "pitch"):
            raise ValueError(f"motion {text!r}: rotate needs yaw|pitch,DEG")
        axis, deg = parts[0].lower(), _number(parts[1], "DEG", text)
    else:
        if len(parts) != 1:
            raise ValueError(f"motion {text!r}: {kind} needs one number DEG")
        axis, deg = "", _number(parts[0], "DEG", text)
    if deg == 0 or abs(deg) > MAX_STEP_DEG:
        raise ValueError(f"motion {text!r}: DEG must be non-zero and at most {MAX_STEP_DEG:g} deg per frame, got {deg:g}")
    return Motion(kind, axis, np.array([deg]), spec)


def check_frames(count: object) -> int:
    """The number of frames: a whole number in [2, :data:`MAX_FRAMES`] (two frames make one change)."""
    if isinstance(count, bool) or not isinstance(count, (int, np.integer, float, np.floating)) or not np.isfinite(count) or float(count) != int(count):
        raise ValueError(f"frames must be a whole number in [2, {MAX_FRAMES}], got {check._repr(count)}")
    n = int(count)
    if not 2 <= n <= MAX_FRAMES:
        raise ValueError(f"frames must be in [2, {MAX_FRAMES}] (two frames make one change; more are not held in memory), got {n}")
    return n


def rotation(axis: ArrayLike, degrees: ArrayLike) -> Array:
    """Rotation matrices ``(..., 3, 3)`` by ``degrees`` [deg] about the unit ``axis`` (right-handed).

    Example
    -------
    >>> (rotation([0, 1, 0], 90.0) @ [1.0, 0.0, 0.0]).round(12).tolist()
    [0.0, 0.0, -1.0]
    """
    a = check.finite(axis, "axis")
    if a.shape != (3,) or not np.linalg.norm(a) > 0:
        raise ValueError(f"axis must be a non-zero vector (3,), got {check._repr(a)}")
    a = a / np.linalg.norm(a)
    ang = np.deg2rad(check.finite(degrees, "degrees"))[..., None, None]
    k = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.eye(3) + np.sin(ang) * k + (1 - np.cos(ang)) * (k @ k)  # Rodrigues


def frames(motion: Motion, eye: ArrayLike, rot: ArrayLike, fov: float, light: ArrayLike, count: int) -> tuple[Array, Array, Array, Array]:
    """Per-frame camera positions ``(F, 3)``, rotations ``(F, 3, 3)`` (rows right, up, forward),
    vertical full fields of view ``(F,)`` [deg] and unit world lights ``(F, 3)`` (towards the light).

    Frame 0 is the given pose; frame f has moved f steps.  ValueError when a zoom leaves
    (0, 180) deg within the sequence.
    """
    n = check_frames(count)
    f = np.arange(n, dtype=float)
    e0 = check.finite(eye, "eye").reshape(3)
    r0 = check.finite(rot, "rot").reshape(3, 3)
    lv = check.finite(light, "light").reshape(3)
    if not np.linalg.norm(lv) > 0:
        raise ValueError("light must be a non-zero direction")
    lv = lv / np.linalg.norm(lv)
    eyes, rots = np.repeat(e0[None], n, 0), np.repeat(r0[None], n, 0)
    fovs, lights = np.full(n, float(check.fov(fov))), np.repeat(lv[None], n, 0)
    if motion.kind == "translate":
        eyes = e0 + f[:, None] * (motion.step @ r0)  # eye-space step → world
    elif motion.kind == "rotate":
        q = rotation(r0[1] if motion.axis == "yaw" else r0[0], f * motion.step[0])  # (F, 3, 3)
        rots = np.einsum("ij,fkj->fik", r0, q)  # each row r ↦ Q r
    elif motion.kind == "zoom":
        fovs = fovs + f * motion.step[0]
        if not (fovs.min() > 0 and fovs.max() < 180):
            raise ValueError(f"motion {motion.text!r}: the field of view leaves (0, 180) deg within {n} frames (from {fov:g} to {fovs[-1]:g})")
    else:
        lights = np.einsum("fij,j->fi", rotation([0.0, 1.0, 0.0], f * motion.step[0]), lv)
    return eyes, rots, fovs, lights
