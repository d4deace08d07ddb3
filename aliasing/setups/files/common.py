"""What every reader of an engine's own project files returns, and the helpers they share.

A reader (one module per engine in :mod:`aliasing.setups.files`) turns the files an engine keeps
its shadow setup in into a :class:`Found`: the settings under the engine's own keys (values already
in the profile's types and spellings, converted from the file's own encoding: Godot's enum
integers, Babylon's constants), the camera in the toolkit's convention (vertical field of view in
degrees: each conversion from the engine's convention is said in ``notes``), the sun from the light's
transform, and where in the file each value was found (so a patch can touch that line or key alone).

Every reader module defines::

    ENGINE: str                      # the toolkit's engine name (aliasing.setups.ENGINES)
    TITLE: str                       # the format in words ("Godot 4 project.godot and .tscn/.tres")
    SOURCE: str                      # where the format is documented, at the pinned release (file and line)
    def sniff(path: Path, text: str) -> bool          # is this file of this format?
    def read(files: list[tuple[Path, str]], light: str | None, camera: str | None) -> Found
    def patch(path: Path, text: str, changes: Mapping[str, Any], found: Found) -> str
    PROFILE: Profile                 # optional: the engine's profile; patch() checks each changed value against it

``read`` gets every file of its engine that the user named (an engine may split its settings over
files: Godot's ``project.godot`` and a scene); ``light`` and ``camera`` name the node or object to
take where a file holds more than one (refused, naming the candidates, where one is needed and not
given).  ``patch`` returns ``text`` with ``changes`` (engine keys to new values) written in the
file's own format, touching nothing else; reading the patched text back gives those values exactly.

Examples
--------
>>> f = Found("godot", {"shadow_bias": 0.05}, camera={"near": 0.05, "far": 4000.0, "fov": 75.0})
>>> f.engine, f.settings["shadow_bias"], f.camera["fov"]
('godot', 0.05, 75.0)
>>> sun_from_directions([0.0, 1.0, 1.0], [0.0, 0.0, -1.0])     # towards the sun, camera forward: behind and up
(45.0, 180.0)
>>> round(vertical_fov(90.0, 16 / 9), 4)                        # a horizontal 90° at 16:9
58.7155
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ...view import vertical_fov
from ..spec import CAMERA_DEFAULTS, _aspect


class FileError(ValueError):
    """A damaged or foreign project file: one line naming the file, the line or key, and what was expected.

    Examples
    --------
    >>> str(FileError("scene.babylon", "cameras[0].fov", "a number [rad]", "'wide'"))
    "scene.babylon: cameras[0].fov: expected a number [rad], got 'wide'"
    """

    def __init__(self, path: str | Path, where: str, expected: str, got: str | None = None) -> None:
        text = f"{Path(path).name if isinstance(path, Path) else path}: {where}: expected {expected}"
        super().__init__(text + (f", got {got}" if got is not None else ""))


@dataclass(frozen=True)
class Found:
    """An engine's shadow setup as found in its own files.

    Attributes
    ----------
    engine : str
        The toolkit's engine name (``godot``, ``babylon``, ``threejs``, ``playcanvas``, ``unity-urp``,
        ``unreal``, ``filament``).
    settings : dict
        The engine's own keys (those of its :class:`aliasing.setups.Profile`) and values in the
        profile's types; only the keys the files set.
    camera : dict or None
        The camera in the toolkit's fields (:data:`aliasing.setups.CAMERA_SPEC`): ``near``, ``far`` [world
        units], ``fov`` (vertical, [deg]), and ``aspect``/``height`` where the files fix them; a camera whose
        file fixes its horizontal field of view gives ``horizontal_fov`` [deg] instead of ``fov``
        (:func:`merge_camera` converts it at the final aspect).
    sun : tuple or None
        (elevation [deg], azimuth from the view direction [deg]) where the light's direction (and the
        camera's, for the azimuth) is in the files.
    light, camera_name : str or None
        The light (or shadow generator) and the camera the values were taken from, as the file names them.
    where : dict
        Setting key (or ``camera.near`` …) -> where in which file it was found (``project.godot line 12``).
    notes : tuple of str
        Each conversion from the engine's convention, in words (``camera.fov 0.8 rad (vertical) = 45.8366°``).
    """

    engine: str
    settings: dict[str, Any]
    camera: dict[str, Any] | None = None
    sun: tuple[float, float] | None = None
    light: str | None = None
    camera_name: str | None = None
    where: dict[str, str] = field(default_factory=dict)
    notes: tuple[str, ...] = ()


def _direction3(value: Any, name: str) -> np.ndarray:
    """``value`` as a unit 3-vector, else a ValueError naming ``name``."""
    try:
        v = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        v = np.empty(0)
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        raise ValueError(f"{name} must be 3 finite numbers (a direction), got {value!r}")
    n = float(np.linalg.norm(v))
    if not (n > 0 and math.isfinite(n)):
        raise ValueError(f"{name} must be a non-zero direction of finite length, got {value!r}")
    return v / n


def sun_from_directions(towards_sun, camera_forward, up=(0.0, 1.0, 0.0)) -> tuple[float, float]:
    """(elevation, azimuth) [deg] of the world direction towards the sun, the azimuth from the camera's
    horizontal forward direction, positive to the camera's right (:mod:`aliasing.setups.spec`), in a
    right-handed world with ``up`` (a left-handed one, Babylon's, is mirrored first).

    A camera looking straight up or down has no horizontal forward: the azimuth is then 0.

    Examples
    --------
    >>> sun_from_directions([1.0, 1.0, 0.0], [0.0, 0.0, -1.0])       # three.js: forward −z, right +x
    (45.0, 90.0)
    """
    s, f, u = (_direction3(v, name) for v, name in ((towards_sun, "towards_sun"), (camera_forward, "camera_forward"), (up, "up")))
    elevation = math.degrees(math.asin(float(np.clip(s @ u, -1.0, 1.0))))
    fh = f - (f @ u) * u
    if np.linalg.norm(fh) < 1e-12:
        return round(elevation, 12), 0.0
    fh = fh / np.linalg.norm(fh)
    right = np.cross(fh, u)
    azimuth = math.degrees(math.atan2(float(s @ right), float(s @ fh)))
    return round(elevation, 12), round(azimuth, 12) + 0.0


def merge_camera(found: Mapping[str, Any] | None, user: Mapping[str, Any] | None) -> tuple[dict[str, Any], tuple[str, ...]]:
    """The camera fields of a project's camera (``found``) with the user's own fields over them.

    A file may give a horizontal field of view (``horizontal_fov`` [deg]: Godot's KEEP_WIDTH, Babylon's
    FOVMODE_HORIZONTAL_FIXED, PlayCanvas's ``horizontalFov``): it becomes the vertical ``fov`` at the
    final aspect (the user's, else the file's, else the toolkit's 16:9), unless the user gives ``fov``.
    Returns (the fields for :func:`aliasing.setups.parse_camera`, notes on the conversion).

    Examples
    --------
    >>> merge_camera({"near": 0.5, "far": 800.0, "fov": 45.0}, {"far": 100})[0]    # the file's fov in degrees, said so
    {'near': 0.5, 'far': 100, 'fov': '45.0deg'}
    >>> fields, notes = merge_camera({"horizontal_fov": 90.0}, {"aspect": "1"})
    >>> fields["fov"], notes
    ('90.0deg', ('camera.fov: the horizontal 90° at aspect 1 is a vertical 90°',))
    """
    for name, value in (("found", found), ("user", user)):
        if value is not None and not isinstance(value, Mapping):
            raise ValueError(f"{name} must be a mapping of camera fields (near, far, fov, aspect, height, horizontal_fov), got {value!r}")
    out = dict(found or {})
    fov = out.get("fov")
    if isinstance(fov, (int, float)) and not isinstance(fov, bool):
        out["fov"] = f"{float(fov)!r}deg"  # the file's degrees, said so: a narrow one is not read as radians
    if user and ("fov" in user or "hfov" in user):  # the user's field of view, either way, replaces the file's
        out.pop("fov", None)
        out.pop("horizontal_fov", None)
    out.update(user or {})
    horizontal = out.pop("horizontal_fov", None)
    if horizontal is None or (user and "fov" in user):
        return out, ()
    aspect = _aspect(out["aspect"]) if "aspect" in out else CAMERA_DEFAULTS["aspect"]
    if isinstance(horizontal, bool) or not isinstance(horizontal, (int, float)) or not 0 < float(horizontal) < 180:
        raise ValueError(f"camera horizontal_fov must be in (0, 180) degrees, got {horizontal!r}")
    vertical = float(vertical_fov(float(horizontal), aspect))
    out["fov"] = f"{vertical!r}deg"
    return out, (f"camera.fov: the horizontal {float(horizontal):.12g}° at aspect {aspect:.6g} is a vertical {vertical:.12g}°",)


def number(path: str | Path, where: str, value: Any, expected: str = "a finite number") -> float:
    """``value`` as a finite float, else a :class:`FileError` naming ``where``.

    Examples
    --------
    >>> number("a.json", "fov", 0.8)
    0.8
    """
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(float(value)):
        raise FileError(path, where, expected, repr(value)[:60])
    return float(value)


def vector(path: str | Path, where: str, value: Any, n: int = 3) -> np.ndarray:
    """``value`` as ``n`` finite floats, else a :class:`FileError` naming ``where``.

    Examples
    --------
    >>> vector("a.json", "position", [0, 1, 2]).tolist()
    [0.0, 1.0, 2.0]
    """
    if not isinstance(value, (list, tuple)) or len(value) != n:
        raise FileError(path, where, f"{n} numbers", repr(value)[:60])
    return np.array([number(path, f"{where}[{i}]", v) for i, v in enumerate(value)])


def direction(path: str | Path, where: str, v: np.ndarray) -> np.ndarray:
    """``v`` normalised, else a :class:`FileError` (a zero direction).

    Examples
    --------
    >>> direction("a.json", "direction", np.array([0.0, 3.0, 4.0])).tolist()
    [0.0, 0.6, 0.8]
    """
    n = float(np.linalg.norm(v))
    if not n > 1e-12 or not math.isfinite(n):
        raise FileError(path, where, "a non-zero direction", str(v.tolist()))
    return v / n


def pick(path: str | Path, kind: str, names: list[str], want: str | None, flag: str) -> int:
    """The index of the one ``kind`` to take among ``names`` (``want`` picks by name), else a FileError naming the candidates.

    Examples
    --------
    >>> pick("s.tscn", "Camera3D", ["A", "B"], "B", "--camera-node")
    1
    >>> pick("s.tscn", "Camera3D", ["A", "B"], None, "--camera-node")
    Traceback (most recent call last):
    ...
    aliasing.setups.files.common.FileError: s.tscn: Camera3D: expected one Camera3D, or --camera-node NAME to pick one of: 'A', 'B', got 2
    """
    if want is not None:
        if want not in names:
            raise FileError(path, f"{kind} {want!r}", f"one of: {', '.join(map(repr, names)) or 'none in the file'}")
        return names.index(want)
    if len(names) > 1:
        raise FileError(path, kind, f"one {kind}, or {flag} NAME to pick one of: {', '.join(map(repr, names))}", f"{len(names)}")
    return 0


def sun_above(towards, forward, notes: list[str]) -> tuple[float, float] | None:
    """:func:`sun_from_directions` where both directions are known and the light is above the horizon; else None
    (a light from below the horizon is said in ``notes``: the sun is then ``--sun``'s).

    Examples
    --------
    >>> notes = []
    >>> sun_above([0.0, -1.0, 1.0], [0.0, 0.0, -1.0], notes), notes
    (None, ["the light shines from below the horizon (elevation -45°): the sun is --sun's"])
    """
    if towards is None or forward is None:
        return None
    sun = sun_from_directions(towards, forward)
    if not sun[0] > 0:
        notes.append(f"the light shines from below the horizon (elevation {sun[0]:.6g}°): the sun is --sun's")
        return None
    return sun


def one_file(files: list, what: str) -> tuple[Path, str]:
    """The one (path, text) of a format kept in one file, else a ValueError naming ``project``.

    Examples
    --------
    >>> one_file([(Path("a.babylon"), "{}")], "one .babylon scene")[0].name
    'a.babylon'
    """
    if len(files) != 1:
        raise ValueError(f"project must be {what}, got {len(files)} files")
    return files[0]
