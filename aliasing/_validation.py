"""Input validation shared by every public function.

Each check raises :class:`ValueError` naming the parameter and its allowed range,
so that the CLI can print the message as one line.
"""

from __future__ import annotations

import difflib
import functools
import inspect
import types
from collections.abc import Callable, Iterable

import numpy as np
from numpy.typing import ArrayLike, NDArray


def as_float_array(value: ArrayLike, name: str) -> NDArray[np.float64]:
    """Convert to a float array, rejecting NaN, complex numbers, strings and other non-numbers.

    inf is allowed here (ranges decide); a Python int beyond the float range is refused with
    that range rather than an OverflowError.
    """
    if isinstance(value, (str, bytes)) or value is None:
        raise ValueError(f"{name} must be a real number or an array of real numbers, got {_repr(value)}")
    try:
        raw = np.asarray(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number or an array of real numbers with a regular shape, got {_repr(value)}") from None
    if raw.dtype.kind == "c" or (raw.dtype.kind == "O" and any(isinstance(v, complex) for v in raw.reshape(-1)[:1000])):
        raise ValueError(f"{name} must be real, got a complex number: {_repr(value)}")
    if raw.dtype.kind not in "biuf" and not (raw.dtype.kind == "O" and all(_real(v) for v in raw.reshape(-1))):
        raise ValueError(f"{name} must be a real number or an array of real numbers, got {_repr(value)}")
    try:
        arr = np.asarray(raw, dtype=float)
    except OverflowError:
        raise ValueError(f"{name} is outside the float range [-1.8e308, 1.8e308], got {_repr(value)}") from None
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number or an array of real numbers, got {_repr(value)}") from None
    if np.isnan(arr).any():
        raise ValueError(f"{name} must not be NaN")
    return arr


def finite(value: ArrayLike, name: str) -> NDArray[np.float64]:
    """A real array without NaN or ±inf ("must be finite, got inf")."""
    arr = as_float_array(value, name)
    if np.isinf(arr).any():
        raise ValueError(f"{name} must be finite, got {_show(arr[np.isinf(arr)])}")
    return arr


def triangles(value: ArrayLike, name: str = "triangles", *, empty: bool = False) -> NDArray[np.float64]:
    """Finite triangles of shape (T, 3, 3) [world units], T ≥ 1 unless ``empty``."""
    arr = finite(value, name)
    if arr.ndim != 3 or arr.shape[1:] != (3, 3) or not (empty or len(arr)):
        raise ValueError(f"{name} must have shape (T, 3, 3), T >= {0 if empty else 1}, got {arr.shape}")
    return arr


def direction(value: ArrayLike, name: str = "sun") -> NDArray[np.float64]:
    """A finite non-zero 3-vector (a direction, not yet normalized)."""
    arr = finite(value, name) if not isinstance(value, str) else as_float_array(np.nan, name)
    if arr.shape != (3,) or not np.linalg.norm(arr) > 0:
        raise ValueError(f"{name} must be a finite non-zero 3-vector (a world direction), got {_repr(value)}")
    return arr


def scalar(value: ArrayLike, name: str) -> float:
    """One real number (a 0-d or one-element array is accepted); NaN refused, inf kept."""
    arr = as_float_array(value, name)
    if arr.size != 1:
        raise ValueError(f"{name} must be a single number, got an array of shape {arr.shape}")
    return float(arr.reshape(-1)[0])


def whole(value: object, name: str, lo: int = 1, hi: int | None = None, what: str = "") -> int:
    """A whole number in [lo, hi] (a float like 3.0 is accepted; bool, NaN, inf, 2.5 are not)."""
    ok = isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, (bool, np.bool_))
    if ok and not isinstance(value, (int, np.integer)):
        ok = bool(np.isfinite(value)) and float(value).is_integer()
    if not ok or value < lo:  # type: ignore[operator]
        raise ValueError(f"{name} must be a whole number >= {lo}{what}, got {_repr(value)}")
    if hi is not None and value > hi:  # type: ignore[operator]
        raise ValueError(f"{name} must be a whole number in [{lo}, {hi}]{what}, got {_repr(value)}")
    return int(value)  # type: ignore[arg-type]


def flag(value: object, name: str) -> bool:
    """A True/False switch (a Python or numpy bool, nothing else)."""
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be True or False, got {_repr(value)}")
    return bool(value)


def instance(value: object, name: str, kind: type | tuple[type, ...]) -> None:
    """Require an object of a given class (a Camera, a LightMap, …), naming the parameter."""
    if not isinstance(value, kind):
        names = " or ".join(k.__name__ for k in (kind if isinstance(kind, tuple) else (kind,)))
        raise TypeError(f"{name} must be a {names}, got {type(value).__name__}")


def names(value: object, name: str) -> list[str]:
    """Names given as one comma-separated str or as an iterable of str (a list of schemes).

    Anything else (a number, a complex, None) or an entry that is not a str is refused with
    a TypeError naming the parameter; the entries come back stripped, empty ones kept (the
    callers say what an empty item means).
    """
    if isinstance(value, str):
        return [part.strip() for part in value.split(",")]
    if isinstance(value, bytes) or not isinstance(value, Iterable):
        raise TypeError(f"{name} must be a comma-separated str or a list of str, got {type(value).__name__} {_repr(value)}")
    items = list(value.tolist() if isinstance(value, np.ndarray) else value)
    bad = [v for v in items if not isinstance(v, str)]
    if bad:
        raise TypeError(f"{name} entries must be str (names), got {type(bad[0]).__name__} {_repr(bad[0])}")
    return [v.strip() for v in items]


def broadcast(**arrays: ArrayLike) -> list[NDArray]:
    """``np.broadcast_arrays`` whose error names the parameters and their shapes."""
    try:
        return list(np.broadcast_arrays(*arrays.values()))
    except ValueError:
        shapes = ", ".join(f"{k} {np.shape(v)}" for k, v in arrays.items())
        raise ValueError(f"shapes do not broadcast together: {shapes}") from None


def public(func: Callable) -> Callable:
    """Decorator for public numeric functions.

    * numpy's "operands could not be broadcast together" inside ``func`` becomes a ValueError
      naming the array arguments and their shapes;
    * float overflow and division by zero give ±inf silently (a valid input whose answer
      exceeds 1.8e308, or a light grazing a face, has the answer inf); an invalid operation
      (inf − inf, 0·inf, 0/0 → NaN) still warns, so that a NaN is never returned quietly.
    """
    signature = inspect.signature(func)

    def rename(exc: ValueError, args: tuple, kwargs: dict) -> None:
        if "broadcast" not in str(exc) or "shapes do not broadcast" in str(exc):
            raise exc
        bound = signature.bind_partial(*args, **kwargs).arguments
        named = {k: v for k, v in bound.items() if not isinstance(v, dict)}
        for key in ("options", "params"):
            named.update(bound.get(key, {}))
        shapes = ", ".join(f"{k} {np.shape(v)}" for k, v in named.items() if _shaped(v))
        raise ValueError(f"shapes do not broadcast together: {shapes}") from None

    def wrapper(*args, **kwargs):
        try:
            with errstate(over="ignore", under="ignore", divide="ignore"):
                return func(*args, **kwargs)
        except ValueError as exc:
            rename(exc, args, kwargs)

    # rebuilt with the wrapped function's globals so that doctest still finds the function
    # as belonging to its module (it compares __globals__) and runs its Example
    errstate = np.errstate  # a closure variable: the wrapper may read no globals of this module
    wrapper = types.FunctionType(wrapper.__code__, func.__globals__, func.__name__, None, wrapper.__closure__)
    return functools.wraps(func)(wrapper)


def unit_rows(v: NDArray[np.float64]) -> NDArray[np.float64]:
    """Non-zero finite vectors (..., n) divided by their length.

    Vectors whose length overflows or underflows (components near 1e308 or 1e-300) are first
    divided by their largest component; all others take the plain v/|v|, bit for bit.
    """
    with np.errstate(over="ignore", under="ignore"):
        norm = np.linalg.norm(v, axis=-1, keepdims=True)
    odd = ~np.isfinite(norm) | (norm < 1e-150)
    if odd.any():
        v = np.where(odd, v / np.abs(v).max(axis=-1, keepdims=True), v)
        norm = np.linalg.norm(v, axis=-1, keepdims=True)
    return v / norm


def _shaped(value: object) -> bool:
    try:
        return np.ndim(value) > 0
    except Exception:  # noqa: BLE001  (ragged lists and the like: not a shape to show)
        return False


def _real(v: object) -> bool:
    return isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, complex)


def _repr(value: object) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def positive(value: ArrayLike, name: str, *, allow_inf: bool = False) -> NDArray[np.float64]:
    """Require ``0 < value`` (and finite unless ``allow_inf``)."""
    arr = as_float_array(value, name) if allow_inf else finite(value, name)
    upper = "inf]" if allow_inf else "inf)"
    if (arr <= 0).any():
        raise ValueError(f"{name} must be in (0, {upper}, got {_show(arr)}")
    return arr


def frustum(near: ArrayLike, far: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Require ``0 < near < far < inf``."""
    n = positive(near, "near")
    f = positive(far, "far")
    broadcast(near=n, far=f)
    if (f <= n).any():
        raise ValueError(f"far must be greater than near (far/near in (1, inf)), got near={_show(n)}, far={_show(f)}")
    with np.errstate(over="ignore"):
        if np.isinf(f / n).any():  # every formula works with f/n: an overflowing ratio is refused here, by name
            raise ValueError(f"far/near must be at most 1.8e308 (a float), got near={_show(n)}, far={_show(f)}")
    return n, f


def depth_ratio(f_over_n: ArrayLike, name: str = "f_over_n") -> NDArray[np.float64]:
    """Require ``1 < f/n < inf``."""
    a = finite(f_over_n, name)
    if (a <= 1).any():
        raise ValueError(f"{name} must be in (1, inf), got {_show(a)}")
    return a


# Narrowest full field of view [deg] the closed forms accept: below about 1e-300° tan θ and
# the face widths underflow and ratios of them become 0/0 (found by the API fuzz suite).
FOV_MIN = 1e-6


def fov(value: ArrayLike, name: str = "fov") -> NDArray[np.float64]:
    """Full field of view in degrees, require ``0 < fov < 180``; returns degrees."""
    arr = as_float_array(value, name)
    if ((arr <= 0) | (arr >= 180)).any():
        raise ValueError(f"{name} (full field of view) must be in (0, 180) degrees, got {_show(arr)}")
    if (arr < FOV_MIN).any():
        raise ValueError(f"{name} (full field of view) must be at least {FOV_MIN:g} degrees (narrower views underflow the closed forms), got {_show(arr)}")
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
    broadcast(n_prime=arr, near=near)
    if (arr < near).any():
        raise ValueError(f"n_prime must be in [near, inf] (n′ = near is PSM, inf is a uniform map), got n_prime={_show(arr)}, near={_show(near)}")
    return arr


def choice(value: str, name: str, allowed: Iterable[str]) -> str:
    """Require ``value`` (case-insensitive) to be one of ``allowed``; returns the lower-case key."""
    allowed = list(allowed)
    if not isinstance(value, str):
        raise ValueError(f"{name} must be a string, one of: {', '.join(allowed)}; got {_repr(value)}")
    key = value.lower()
    if key not in allowed:
        raise ValueError(f"unknown {name} {value!r}{did_you_mean(value, allowed)}; choose one of: {', '.join(allowed)}")
    return key


def did_you_mean(value: object, known: Iterable[str]) -> str:
    """``" (did you mean 'X'?)"`` for the known names closest to a misspelt ``value``, else ``""``.

    Case is ignored in the comparison; the suggestions keep the spelling of ``known``.

    Example
    -------
    >>> did_you_mean("practcal", ["log", "uniform", "practical"])
    " (did you mean 'practical'?)"
    >>> did_you_mean("lgp", ["P", "LogP", "Po"])
    " (did you mean 'LogP'?)"
    >>> did_you_mean("zzz", ["log", "uniform"])
    ''
    """
    if not isinstance(value, str) or not value:
        return ""
    names = list(dict.fromkeys(str(k) for k in known))
    by_key: dict[str, str] = {}
    for name in names:
        by_key.setdefault(name.lower(), name)
    close = difflib.get_close_matches(value.lower(), list(by_key), n=3, cutoff=0.6)
    if not close:
        return ""
    return " (did you mean " + " or ".join(repr(by_key[c]) for c in close) + "?)"


def jobs(value: object, name: str = "jobs") -> int:
    """Require a whole number >= 1 of local worker processes; returns it as an int."""
    return whole(value, name, 1, what=" (local processes)")


def _show(arr: NDArray[np.float64]) -> str:
    """Short text for an offending value (the scalar, or the range of an array)."""
    if arr.ndim == 0 or arr.size == 1:
        return f"{float(arr.reshape(-1)[0]):g}"
    return f"array with values in [{np.min(arr):g}, {np.max(arr):g}]"
