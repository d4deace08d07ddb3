"""The setup value: an engine at a release, its settings, a camera with an image size, and a sun.

Built and validated once where it enters (:func:`build`, or :func:`from_args` on the command
line), then passed on as a value.  The one vocabulary of every command:

* ``--engine NAME[@RELEASE]``, or ``--project FILE`` (repeatable): the engine's own project files
  (:mod:`aliasing.setups.files`), whose settings, camera and sun the options below go over;
* ``--settings FILE`` (JSON or TOML, the engine's own keys) and repeatable ``--set KEY=VALUE``;
* ``--camera near=N,far=F,fov=DEG,aspect=A,height=PX``: the vertical field of view in degrees,
  the aspect as ``16:9`` or a number, the image height in pixels (the width is aspect·height);
* ``--sun ELEV[..ELEV][@AZ]``: the sun's elevation above the ground [deg], one value or a band,
  and its azimuth from the view direction [deg] (positive to the right).

The camera looks horizontally (eye space: x right, y up, z along the view), so a sun at
elevation e and azimuth a lies towards (cos e·sin a, sin e, cos e·cos a): a = 0 is a sun ahead,
a = 180 a sun behind the camera.

Example
-------
>>> cam = parse_camera("near=0.1,far=500,fov=50,aspect=16:9,height=1080")
>>> cam.width, round(cam.aspect, 4)
(1920, 1.7778)
>>> sun = parse_sun("15..60@30")
>>> sun.elevation, sun.azimuth
((15.0, 60.0), 30.0)
>>> sun.direction(90.0).round(12).tolist()
[0.0, 1.0, 0.0]
"""

from __future__ import annotations

import json
import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..view import View
from .profile import Pipeline, Profile

try:  # Python 3.11+
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib  # type: ignore[no-redef]

Array = NDArray[np.float64]

CAMERA_SPEC = "near=N,far=F,fov=DEG,aspect=W:H|A,height=PX"
SUN_SPEC = "ELEV[..ELEV][@AZ] (degrees above the ground; azimuth from the view direction)"
CAMERA_DEFAULTS = {"near": 0.1, "far": 500.0, "fov": 50.0, "aspect": 16 / 9, "height": 1080}
#: fields of view at or below this look like radians (π is 180°): a warning gives them in degrees
RADIANS_BELOW = math.pi


class RadiansWarning(UserWarning):
    """A field of view that looks like radians (the toolkit takes degrees)."""


def _number(text: str, name: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"{name} must be a number, got {text!r}") from None
    if not math.isfinite(value):
        raise ValueError(f"{name} must be finite, got {text!r}")
    return value


def _aspect(text: str | float) -> float:
    if isinstance(text, str) and ":" in text:
        w, _, h = text.partition(":")
        a, b = _number(w, "camera aspect width"), _number(h, "camera aspect height")
        if not (a > 0 and b > 0):
            raise ValueError(f"camera aspect must be W:H with W, H > 0 (16:9) or a number > 0, got {text!r}")
        return a / b
    value = _number(text, "camera aspect") if isinstance(text, str) else float(text)
    if not (value > 0 and math.isfinite(value)):
        raise ValueError(f"camera aspect must be W:H (16:9) or a number > 0, got {text!r}")
    return value


@dataclass(frozen=True)
class Camera:
    """A perspective camera with its image: near and far [world units], the VERTICAL full field of
    view [deg], the aspect (width/height) and the image height [pixels]; validated once.

    Example
    -------
    >>> Camera(0.1, 500.0, 50.0, 16 / 9, 1080).view.theta_deg
    25.0
    """

    near: float
    far: float
    fov: float
    aspect: float = 16 / 9
    height: int = 1080
    view: View = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        v = View(self.near, self.far, self.fov, self.aspect)  # names near, far, fov or aspect and the range
        if np.ndim(v.near) != 0:
            raise ValueError("camera near, far, fov and aspect must be single numbers")
        h = self.height
        if isinstance(h, bool) or not isinstance(h, (int, float, np.integer, np.floating)) or not (1 <= h <= 65536) or not float(h).is_integer():
            raise ValueError(f"camera height must be a whole number of pixels in [1, 65536], got {h!r}")
        for name in ("near", "far", "fov", "aspect"):
            object.__setattr__(self, name, float(getattr(v, name)))
        object.__setattr__(self, "height", int(h))
        object.__setattr__(self, "view", v)

    @property
    def width(self) -> int:
        """Image width [pixels]: round(aspect·height)."""
        return int(round(self.aspect * self.height))

    def spec(self) -> str:
        """The camera as a ``--camera`` text."""
        return f"near={self.near:g},far={self.far:g},fov={self.fov:g},aspect={self.aspect:.6g},height={self.height}"


def camera_items(spec: str | Mapping[str, Any] | None) -> dict[str, Any]:
    """The fields a camera spec gives, as written (``near=0.1,fov=50`` -> ``{'near': '0.1', 'fov': '50'}``), unchecked.

    Example
    -------
    >>> camera_items("near=0.5, FOV=40")
    {'near': '0.5', 'fov': '40'}
    """
    if spec is None:
        return {}
    if isinstance(spec, Mapping):
        return dict(spec)
    if not isinstance(spec, str):
        raise ValueError(f"camera must be {CAMERA_SPEC}, got {spec!r}")
    items: dict[str, Any] = {}
    for part in filter(None, (p.strip() for p in spec.split(","))):
        key, eq, value = part.partition("=")
        if not eq:
            raise ValueError(f"camera must be {CAMERA_SPEC}, got {spec!r} (a field without '=': {part!r})")
        items[key.strip().lower()] = value.strip()
    return items


def parse_camera(spec: str | Mapping[str, Any] | Camera | None, *, warn: bool = True) -> Camera:
    """A :class:`Camera` from ``near=N,far=F,fov=DEG,aspect=A,height=PX`` (any subset; the rest
    default to near 0.1, far 500, fov 50, aspect 16:9, height 1080) or a mapping of those keys.

    A fov at or below π (3.14…) looks like radians: a :class:`RadiansWarning` gives it in degrees.

    Raises
    ------
    ValueError
        Naming the field (``camera near`` …) and what it takes; unknown fields get a did-you-mean.
    """
    if isinstance(spec, Camera):
        return spec
    fields: dict[str, Any] = dict(CAMERA_DEFAULTS)
    items = camera_items(spec)
    from .. import _validation as check

    for key, value in items.items():
        if key not in CAMERA_DEFAULTS:
            raise ValueError(f"unknown camera field {key!r}{check.did_you_mean(key, CAMERA_DEFAULTS)}; the fields are: {', '.join(CAMERA_DEFAULTS)}")
        if key == "aspect":
            fields[key] = _aspect(value)
        elif key == "height":
            number = _number(value, "camera height") if isinstance(value, str) else value
            fields[key] = number
        else:
            fields[key] = _number(value, f"camera {key}") if isinstance(value, str) else value
    for key in ("near", "far", "fov"):
        v = fields[key]
        if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)):
            raise ValueError(f"camera {key} must be a number, got {v!r}")
    if warn and 0 < float(fields["fov"]) <= RADIANS_BELOW:
        warnings.warn(f"camera fov {float(fields['fov']):g} looks like radians ({math.degrees(float(fields['fov'])):.4g}°); "
                      "the field of view is in degrees", RadiansWarning, stacklevel=2)
    try:
        return Camera(fields["near"], fields["far"], fields["fov"], fields["aspect"], fields["height"])
    except ValueError as exc:
        text = str(exc)
        raise ValueError(text if text.startswith("camera") else f"camera {text}") from None


@dataclass(frozen=True)
class Sun:
    """The sun: an elevation band above the ground [deg] and an azimuth from the view direction [deg].

    ``elevation`` is ``(low, high)``, equal for one sun; 0 < low <= high <= 90.
    """

    elevation: tuple
    azimuth: float = 0.0

    def __post_init__(self) -> None:
        lo, hi = (self.elevation, self.elevation) if np.ndim(self.elevation) == 0 else tuple(self.elevation)
        for v in (lo, hi):
            if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)) or not (0 < v <= 90):
                raise ValueError(f"sun elevation must be in (0, 90] degrees above the ground, got {v!r}")
        if lo > hi:
            raise ValueError(f"sun elevation band must be LOW..HIGH with LOW <= HIGH, got {lo:g}..{hi:g}")
        az = self.azimuth
        if isinstance(az, bool) or not isinstance(az, (int, float, np.integer, np.floating)) or not math.isfinite(az):
            raise ValueError(f"sun azimuth must be a finite number of degrees, got {az!r}")
        object.__setattr__(self, "elevation", (float(lo), float(hi)))
        object.__setattr__(self, "azimuth", float(az))

    def elevations(self, n: int = 7) -> Array:
        """``n`` elevations over the band [deg] (one for a single sun)."""
        lo, hi = self.elevation
        return np.array([lo]) if lo == hi else np.linspace(lo, hi, n)

    def direction(self, elevation: float | Array | None = None) -> Array:
        """Eye-space unit vectors towards the sun (module docstring), shape ``(..., 3)``."""
        e = np.radians(np.asarray(self.elevation[0] if elevation is None else elevation, float))
        a = np.radians(self.azimuth)
        return np.stack([np.cos(e) * np.sin(a), np.sin(e), np.cos(e) * np.cos(a)], axis=-1)

    def light(self, elevation: float | None = None) -> str:
        """The sun at ``elevation`` (default the band's lowest) as the toolkit's eye-space light spec
        ``gamma:G@azimuth:A`` (:data:`aliasing.geometry.LIGHT_SPEC`: γ from the view direction, azimuth
        about it from up), the same direction as :meth:`direction`.

        Example
        -------
        >>> Sun((30.0, 30.0)).light(), Sun((30.0, 30.0), 90.0).light()
        ('gamma:30@azimuth:0', 'gamma:90@azimuth:60')
        """
        e = math.radians(self.elevation[0] if elevation is None else float(elevation))
        a = math.radians(self.azimuth)
        x, y, z = math.cos(e) * math.sin(a), math.sin(e), math.cos(e) * math.cos(a)
        gamma = math.degrees(math.atan2(math.hypot(x, y), z))
        az = math.degrees(math.atan2(x, y)) if math.hypot(x, y) > 0 else 0.0
        return f"gamma:{gamma:.12g}@azimuth:{az:.12g}"

    def spec(self) -> str:
        lo, hi = self.elevation
        band = f"{lo:g}" if lo == hi else f"{lo:g}..{hi:g}"
        return band + (f"@{self.azimuth:g}" if self.azimuth else "")


def parse_sun(spec: str | Sun | float) -> Sun:
    """A :class:`Sun` from ``ELEV``, ``LOW..HIGH`` and an optional ``@AZ`` [deg]."""
    if isinstance(spec, Sun):
        return spec
    if isinstance(spec, (int, float)) and not isinstance(spec, bool):
        return Sun((spec, spec))
    if not isinstance(spec, str) or not spec.strip():
        raise ValueError(f"sun must be {SUN_SPEC}, got {spec!r}")
    band, at, az = spec.strip().partition("@")
    lo, dots, hi = band.partition("..")
    low = _number(lo, "sun elevation")
    high = _number(hi, "sun elevation") if dots else low
    azimuth = _number(az, "sun azimuth") if at else 0.0
    return Sun((low, high), azimuth)


def load_settings(path: str | Path) -> dict[str, Any]:
    """The engine settings in a JSON or TOML file (by its suffix; ``.toml`` is TOML, anything else JSON).

    Raises
    ------
    ValueError
        A malformed file, naming it and the parser's first complaint, or a file that is not a
        table of settings.
    """
    p = Path(path)
    text = p.read_text(encoding="utf-8")  # OSError names the file
    try:
        data = tomllib.loads(text) if p.suffix.lower() == ".toml" else json.loads(text)
    except (ValueError, tomllib.TOMLDecodeError) as exc:
        kind = "TOML" if p.suffix.lower() == ".toml" else "JSON"
        raise ValueError(f"settings file {str(p)!r} is not valid {kind}: {str(exc).splitlines()[0]}") from None
    if not isinstance(data, dict):
        raise ValueError(f"settings file {str(p)!r} must hold a table of settings (KEY: VALUE), got {type(data).__name__}")
    return _flatten(data)


def _flatten(data: Mapping[str, Any], prefix: str = "") -> dict[str, Any]:
    """Nested tables as dotted keys: {"shadow": {"bias": 0}} -> {"shadow.bias": 0}."""
    out: dict[str, Any] = {}
    for key, value in data.items():
        name = f"{prefix}{key}"
        if isinstance(value, Mapping):
            out.update(_flatten(value, name + "."))
        else:
            out[name] = value
    return out


def parse_set(items: list[str] | None) -> dict[str, str]:
    """``--set KEY=VALUE`` texts as a dict (values stay text; the profile types them)."""
    out: dict[str, str] = {}
    for item in items or ():
        key, eq, value = str(item).partition("=")
        if not eq or not key.strip():
            raise ValueError(f"--set must be KEY=VALUE, got {item!r}")
        out[key.strip()] = value.strip()
    return out


@dataclass(frozen=True)
class Setup:
    """An engine's whole shadow setup: profile, settings (every key, validated), camera and sun.

    Build it with :func:`build`.  ``pipeline`` is what the engine makes of it.
    """

    profile: Profile
    settings: Mapping[str, Any]
    camera: Camera
    sun: Sun
    pipeline: Pipeline = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        full = self.profile.resolve(self.settings)
        object.__setattr__(self, "settings", MappingProxyType(full))
        object.__setattr__(self, "pipeline", self.profile.build(full, self.camera))

    @property
    def engine(self) -> str:
        return self.profile.engine

    @property
    def release(self) -> str:
        return self.profile.release

    def with_settings(self, **changes: Any) -> Setup:
        """The same setup with some settings changed (engine keys; dotted keys as ``**{"shadow.bias": v}``)."""
        return Setup(self.profile, {**self.settings, **changes}, self.camera, self.sun)

    def changed(self) -> dict[str, Any]:
        """The settings that differ from the engine's defaults."""
        d = self.profile.defaults()
        return {k: v for k, v in self.settings.items() if d.get(k) != v}
