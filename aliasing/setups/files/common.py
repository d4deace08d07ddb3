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
        units], ``fov`` (vertical, [deg]), and ``aspect``/``height`` where the files fix them.
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


def sun_from_directions(towards_sun, camera_forward, up=(0.0, 1.0, 0.0)) -> tuple[float, float]:
    """(elevation, azimuth) [deg] of the world direction towards the sun, the azimuth from the camera's
    horizontal forward direction, positive to the camera's right (:mod:`aliasing.setups.spec`).

    A camera looking straight up or down has no horizontal forward: the azimuth is then 0.
    """
    s = np.asarray(towards_sun, float)
    f = np.asarray(camera_forward, float)
    u = np.asarray(up, float)
    s = s / np.linalg.norm(s)
    u = u / np.linalg.norm(u)
    elevation = math.degrees(math.asin(float(np.clip(s @ u, -1.0, 1.0))))
    fh = f - (f @ u) * u
    if np.linalg.norm(fh) < 1e-12:
        return round(elevation, 12), 0.0
    fh = fh / np.linalg.norm(fh)
    right = np.cross(fh, u)
    azimuth = math.degrees(math.atan2(float(s @ right), float(s @ fh)))
    return round(elevation, 12), round(azimuth, 12) + 0.0
