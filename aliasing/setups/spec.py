"""The setup value: an engine at a release, its settings, a camera with an image size, and a sun.

Built and validated once where it enters (:func:`build`, or :func:`from_args` on the command
line), then passed on as a value.  The one vocabulary of every command:

* ``--engine NAME[@RELEASE]``, or ``--project FILE`` (repeatable): the engine's own project files
  (:mod:`aliasing.setups.files`), whose settings, camera and sun the options below go over;
* ``--settings FILE`` (JSON or TOML, the engine's own keys) and repeatable ``--set KEY=VALUE``;
* ``--camera near=N,far=F,fov=DEG,aspect=A,height=PX``: the vertical field of view in degrees
  (or radians with ``rad``: ``fov=0.8rad``; ``hfov=`` for the horizontal one), the aspect as
  ``16:9``, ``1920x1080`` or a number, the image height in pixels (the width is aspect·height);
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
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..view import View, vertical_fov
from .profile import Pipeline, Profile

try:  # Python 3.11+
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib  # type: ignore[no-redef]

Array = NDArray[np.float64]

CAMERA_SPEC = "near=N,far=F,fov=DEG|RADrad,aspect=W:H|WxH|A,height=PX"
SUN_SPEC = "ELEV[..ELEV][@AZ] (degrees above the ground; azimuth from the view direction)"
CAMERA_DEFAULTS = {"near": 0.1, "far": 500.0, "fov": 50.0, "aspect": 16 / 9, "height": 1080}
#: Other names of the camera's fields, as engines spell them (lower case): Babylon.js ``minZ``/``maxZ``,
#: PlayCanvas ``nearClip``/``farClip``, Unity ``nearClipPlane``/``farClipPlane``/``fieldOfView``, ``znear``/``zfar``.
CAMERA_ALIASES = {"minz": "near", "znear": "near", "nearclip": "near", "nearclipplane": "near",
                  "maxz": "far", "zfar": "far", "farclip": "far", "farclipplane": "far", "fieldofview": "fov"}
#: Fields besides :data:`CAMERA_DEFAULTS`: ``hfov`` (the horizontal field of view, converted to the vertical
#: one with the aspect) and ``size`` (``WxH`` pixels: the aspect and the height at once).
CAMERA_EXTRA = ("hfov", "size")
#: A field of view written without a unit at or below this [deg] reads as radians (π is 180°) and is refused.
RADIANS_BELOW = math.pi
_ANGLE = re.compile(r"^\s*(.*?)\s*(rad|deg|°)?\s*$", re.IGNORECASE)


def _number(text: str, name: str) -> float:
    if isinstance(text, bool) or not isinstance(text, (str, int, float, np.integer, np.floating)):
        raise ValueError(f"{name} must be a number, got {text!r}")
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"{name} must be a number, got {text!r}") from None
    if not math.isfinite(value):
        raise ValueError(f"{name} must be finite, got {text!r}")
    return value


def _angle(value: object, name: str) -> float:
    """A field of view [deg] from a number or a text with a unit (``0.8rad``, ``50deg``, ``50°``).

    A number without a unit is degrees, but one at or below π (3.14…) reads as radians and is refused
    with both spellings (``fov=45.84`` or ``fov=0.8rad``); a narrow field of view in degrees is written
    with ``deg`` (``fov=2deg``).
    """
    unit = ""
    if isinstance(value, str):
        m = _ANGLE.match(value)
        if m is None or not m.group(1):
            raise ValueError(f"camera {name} must be a number of degrees or a number with rad or deg (0.8rad, 50deg), got {value!r}")
        text, unit = m.group(1), (m.group(2) or "").lower()
        number = _number(text, f"camera {name}")
    else:
        number = _number(value, f"camera {name}")  # type: ignore[arg-type]
    if unit == "rad":
        return math.degrees(number)
    if not unit and 0 < number <= RADIANS_BELOW:
        shown = f"{number:g}"
        raise ValueError(f"camera {name} {shown} looks like radians ({math.degrees(number):.2f}°): write {name}={math.degrees(number):.2f} "
                         f"(degrees) or {name}={shown}rad; a field of view this narrow in degrees is written {name}={shown}deg")
    return number


def _pair(text: str) -> tuple[str, str] | None:
    """``W:H``, ``WxH`` or ``W×H`` as its two texts (None for a plain number)."""
    for sep in (":", "x", "X", "×"):
        if sep in text:
            w, _, h = text.partition(sep)
            return w, h
    return None


def _aspect(text: object) -> float:
    if isinstance(text, str) and (pair := _pair(text)) is not None:
        a, b = _number(pair[0], "camera aspect width"), _number(pair[1], "camera aspect height")
        if not (a > 0 and b > 0):
            raise ValueError(f"camera aspect must be W:H or WxH with W, H > 0 (16:9, 1920x1080) or a number > 0, got {text!r}")
        return a / b
    value = _number(text, "camera aspect")  # type: ignore[arg-type]
    if not value > 0:
        raise ValueError(f"camera aspect must be W:H or WxH (16:9, 1920x1080) or a number > 0, got {text!r}")
    return value


def _size(text: object) -> tuple[float, float]:
    """``size=WxH`` [pixels]: (aspect, height)."""
    pair = _pair(text) if isinstance(text, str) else None
    if pair is None:
        raise ValueError(f"camera size must be WxH in pixels (1920x1080), got {text!r}")
    w, h = _number(pair[0], "camera size width"), _number(pair[1], "camera size height")
    if not (w >= 1 and h >= 1):
        raise ValueError(f"camera size must be WxH with W, H >= 1 pixels (1920x1080), got {text!r}")
    return w / h, h


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
        for name in ("near", "far", "fov", "aspect"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)):
                raise ValueError(f"camera {name} must be a single number, got {v!r}")
        v = View(self.near, self.far, self.fov, self.aspect)  # names near, far, fov or aspect and the range
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
        """The camera as a ``--camera`` text (a field of view at or below π degrees carries ``deg``)."""
        fov = f"{self.fov:g}" + ("deg" if self.fov <= RADIANS_BELOW else "")
        return f"near={self.near:g},far={self.far:g},fov={fov},aspect={self.aspect:.6g},height={self.height}"


def camera_items(spec: str | Mapping[str, Any] | None) -> dict[str, Any]:
    """The fields a camera spec gives, as written, under their canonical names (:data:`CAMERA_ALIASES`: ``minZ`` is ``near``),
    the values unchecked.

    Raises
    ------
    ValueError
        A spec that is neither text nor a mapping, a field without ``=``, a key that is not text, or one field given twice.

    Example
    -------
    >>> camera_items("near=0.5, FOV=40")
    {'near': '0.5', 'fov': '40'}
    >>> camera_items({"minZ": 0.5, "maxZ": 800})
    {'near': 0.5, 'far': 800}
    """
    if spec is None:
        return {}
    if isinstance(spec, Mapping):
        pairs = []
        for key, value in spec.items():
            if not isinstance(key, str):
                raise ValueError(f"camera fields must be named by text ({', '.join(CAMERA_DEFAULTS)}), got the key {key!r}")
            pairs.append((key.strip(), value))
    elif isinstance(spec, str):
        pairs = []
        for part in filter(None, (p.strip() for p in spec.split(","))):
            key, eq, value = part.partition("=")
            if not eq:
                raise ValueError(f"camera must be {CAMERA_SPEC}, got {spec!r} (a field without '=': {part!r})")
            pairs.append((key.strip(), value.strip()))
    else:
        raise ValueError(f"camera must be {CAMERA_SPEC} or a mapping of those fields, got {type(spec).__name__}")
    items: dict[str, Any] = {}
    given: dict[str, str] = {}
    for key, value in pairs:
        name = CAMERA_ALIASES.get(key.lower(), key.lower())
        if name in given:
            raise ValueError(f"camera {name} given twice (as {given[name]!r} and {key!r})")
        given[name] = key
        items[name] = value
    return items


def parse_camera(spec: str | Mapping[str, Any] | Camera | None) -> Camera:
    """A :class:`Camera` from ``near=N,far=F,fov=DEG,aspect=A,height=PX`` (any subset; the rest
    default to near 0.1, far 500, fov 50°, aspect 16:9, height 1080) or a mapping of those keys.

    Parameters
    ----------
    spec : str, mapping, Camera or None
        The fields, as text or a mapping (keys case-insensitive):

        * ``near``, ``far`` [world units] (also ``minZ``/``maxZ``, ``znear``/``zfar``,
          ``nearClip``/``farClip``, ``nearClipPlane``/``farClipPlane``: :data:`CAMERA_ALIASES`);
        * ``fov``: the vertical full field of view, degrees (``50``, ``50deg``, ``50°``) or radians
          with ``rad`` (``0.8rad``, Babylon.js's ``fov``); a number without a unit at or below π
          reads as radians and is refused: write ``deg`` for a narrow one (``fov=2deg``);
        * ``hfov``: the horizontal full field of view instead (same units), converted with the
          aspect: tan(fov/2) = tan(hfov/2)/aspect;
        * ``aspect``: width/height as ``16:9``, ``1920x1080`` (``1920×1080``) or a number; the
          ratio only: the height stays its own field;
        * ``height``: the image's rows [pixels]; or ``size=1920x1080`` for the aspect and the
          height at once.

    Returns
    -------
    Camera

    Raises
    ------
    ValueError
        Naming the field (``camera near`` …) and what it takes; unknown fields get a did-you-mean.

    Example
    -------
    >>> parse_camera("minZ=0.5,maxZ=800,fov=0.8rad")
    Camera(near=0.5, far=800.0, fov=45.836623610465864, aspect=1.7777777777777777, height=1080)
    >>> round(parse_camera("hfov=90,aspect=1920x1080").fov, 4), parse_camera("size=1280x720").height
    (58.7155, 720)
    >>> parse_camera("fov=0.8")
    Traceback (most recent call last):
    ...
    ValueError: camera fov 0.8 looks like radians (45.84°): write fov=45.84 (degrees) or fov=0.8rad; a field of view this narrow in degrees is written fov=0.8deg
    """
    if isinstance(spec, Camera):
        return spec
    fields: dict[str, Any] = dict(CAMERA_DEFAULTS)
    items = camera_items(spec)
    from .. import _validation as check

    known = (*CAMERA_DEFAULTS, *CAMERA_EXTRA)
    given: dict[str, str] = {}  # field -> the name it was given as
    for key, value in items.items():
        name = CAMERA_ALIASES.get(key, key)
        if name not in known:
            raise ValueError(f"unknown camera field {key!r}{check.did_you_mean(key, [*known, *CAMERA_ALIASES])}; the fields are: "
                             f"{', '.join(known)} (also {', '.join(CAMERA_ALIASES)})")
        if name in given:
            raise ValueError(f"camera {name} given twice (as {given[name]!r} and {key!r})")
        given[name] = key
        if value is None:
            raise ValueError(f"camera {key} must be a value, got None")
        if name == "aspect":
            fields[name] = _aspect(value)
        elif name == "size":
            fields["aspect"], fields["height"] = _size(value)
        elif name in ("fov", "hfov"):
            fields[name] = _angle(value, key)
        else:
            fields[name] = _number(value, f"camera {key}")
    for a, b in (("fov", "hfov"), ("size", "aspect"), ("size", "height")):
        if a in given and b in given:
            raise ValueError(f"camera takes {a} or {b}, not both (got {given[a]} and {given[b]})")
    if "hfov" in fields:
        h = fields.pop("hfov")
        if not 0 < h < 180:
            raise ValueError(f"camera hfov must be a horizontal field of view in (0, 180) degrees, got {h:g}")
        fields["fov"] = float(vertical_fov(h, fields["aspect"]))
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
    """A :class:`Sun` from ``ELEV``, ``LOW..HIGH`` and an optional ``@AZ`` [deg], or one elevation [deg].

    Raises
    ------
    ValueError
        Naming the sun's elevation or azimuth and what it takes.

    Example
    -------
    >>> parse_sun("15..60@30").spec(), parse_sun(45).elevation
    ('15..60@30', (45.0, 45.0))
    """
    if isinstance(spec, Sun):
        return spec
    if isinstance(spec, (int, float, np.integer, np.floating)) and not isinstance(spec, (bool, np.bool_)):
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
    """``--set KEY=VALUE`` texts as a dict (values stay text; the profile types them).

    Raises
    ------
    ValueError
        Naming ``--set`` (``items``) where ``items`` is not a list of ``KEY=VALUE`` texts.

    Example
    -------
    >>> parse_set(["cascades=4", "shadow.bias = -0.001"])
    {'cascades': '4', 'shadow.bias': '-0.001'}
    """
    if items is not None and (isinstance(items, (str, bytes)) or not isinstance(items, (list, tuple))):
        raise ValueError(f"items (--set) must be a list of KEY=VALUE texts, got {type(items).__name__}")
    out: dict[str, str] = {}
    for item in items or ():
        if not isinstance(item, str):
            raise ValueError(f"items (--set) must be KEY=VALUE texts, got {item!r}")
        key, eq, value = item.partition("=")
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
        if not isinstance(self.profile, Profile) or not isinstance(self.camera, Camera) or not isinstance(self.sun, Sun):
            raise ValueError("profile, camera and sun must be an aliasing.setups Profile, Camera and Sun (aliasing.setups.build(...)), got "
                             f"{type(self.profile).__name__}, {type(self.camera).__name__}, {type(self.sun).__name__}")
        full = self.profile.resolve(self.settings)
        object.__setattr__(self, "settings", MappingProxyType(full))
        try:
            pipeline = self.profile.build(full, self.camera)
        except ValueError as exc:  # a message from below that names no setting: say which settings led there
            changed = [k for k, v in full.items() if self.profile.defaults().get(k) != v]
            if any(k in str(exc) for k in full):
                raise
            raise ValueError(f"{self.profile.title} builds no cascades from the settings {', '.join(changed) or '(the defaults)'} "
                             f"with camera {self.camera.spec()}: {exc}") from None
        object.__setattr__(self, "pipeline", pipeline)

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
