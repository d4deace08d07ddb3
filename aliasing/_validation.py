"""Input validation shared by every public function.

Each check raises :class:`ValueError` naming the parameter and its allowed range,
so that the CLI can print the message as one line.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np
from numpy.typing import ArrayLike, NDArray


def as_float_array(value: ArrayLike, name: str) -> NDArray[np.float64]:
    """Convert to a float array, rejecting NaN (inf is allowed where ranges allow it)."""
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number or an array of real numbers, got {value!r}") from None
    if np.isnan(arr).any():
        raise ValueError(f"{name} must not be NaN")
    return arr


def positive(value: ArrayLike, name: str, *, allow_inf: bool = False) -> NDArray[np.float64]:
    """Require ``0 < value`` (and finite unless ``allow_inf``)."""
    arr = as_float_array(value, name)
    upper = "inf]" if allow_inf else "inf)"
    if (arr <= 0).any() or (not allow_inf and np.isinf(arr).any()):
        raise ValueError(f"{name} must be in (0, {upper}, got {_show(arr)}")
    return arr


def frustum(near: ArrayLike, far: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Require ``0 < near < far < inf``."""
    n = positive(near, "near")
    f = positive(far, "far")
    if (f <= n).any():
        raise ValueError(f"far must be greater than near (far/near in (1, inf)), got near={_show(n)}, far={_show(f)}")
    return n, f


def depth_ratio(f_over_n: ArrayLike, name: str = "f_over_n") -> NDArray[np.float64]:
    """Require ``1 < f/n < inf``."""
    a = as_float_array(f_over_n, name)
    if (a <= 1).any() or np.isinf(a).any():
        raise ValueError(f"{name} must be in (1, inf), got {_show(a)}")
    return a


def fov(value: ArrayLike, name: str = "fov") -> NDArray[np.float64]:
    """Full field of view in degrees, require ``0 < fov < 180``; returns degrees."""
    arr = as_float_array(value, name)
    if ((arr <= 0) | (arr >= 180)).any():
        raise ValueError(f"{name} (full field of view) must be in (0, 180) degrees, got {_show(arr)}")
    return arr


def closed_range(value: ArrayLike, name: str, lo: float, hi: float, unit: str = "") -> NDArray[np.float64]:
    """Require ``lo <= value <= hi``."""
    arr = as_float_array(value, name)
    if ((arr < lo) | (arr > hi)).any():
        raise ValueError(f"{name} must be in [{lo:g}, {hi:g}]{unit}, got {_show(arr)}")
    return arr


def n_prime(value: ArrayLike, near: NDArray[np.float64]) -> NDArray[np.float64]:
    """Warping parameter n′: require ``near <= n′ <= inf`` (inf is the uniform map)."""
    arr = as_float_array(value, "n_prime")
    if (arr < near).any():
        raise ValueError(f"n_prime must be in [near, inf] (n′ = near is PSM, inf is a uniform map), got n_prime={_show(arr)}, near={_show(near)}")
    return arr


def choice(value: str, name: str, allowed: Iterable[str]) -> str:
    """Require ``value`` (case-insensitive) to be one of ``allowed``; returns the lower-case key."""
    allowed = list(allowed)
    key = str(value).lower()
    if key not in allowed:
        raise ValueError(f"unknown {name} {value!r}; choose one of: {', '.join(allowed)}")
    return key


def jobs(value: object, name: str = "jobs") -> int:
    """Require a whole number >= 1 of local worker processes; returns it as an int."""
    number = isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, (bool, np.bool_))
    if not (number and np.isfinite(value) and float(value).is_integer() and value >= 1):  # type: ignore[arg-type]
        raise ValueError(f"{name} must be a whole number >= 1 (local processes), got {value!r}")
    return int(value)


def _show(arr: NDArray[np.float64]) -> str:
    """Short text for an offending value (the scalar, or the range of an array)."""
    if arr.ndim == 0 or arr.size == 1:
        return f"{float(arr.reshape(-1)[0]):g}"
    return f"array with values in [{np.min(arr):g}, {np.max(arr):g}]"
