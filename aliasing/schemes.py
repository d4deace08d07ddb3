"""Scheme names → evaluation: one grammar for the API and the CLI.

Grammar (case-insensitive)::

    scheme := base | "ZP" k | "ZP" k "+" base | faces ["+ZP" k] "+" fbase
    faces  := "FP" | "FPc" | "FPcs"   face partitioning (Lloyd 2007 §6.1.3, §6.5; aliasing.faces)
    fbase  := "P" | "LogP" | "Log" | "Standard"   the side faces' parameterization
    base   := "Standard"            uniform map (alias "Uniform")
            | "P"                   perspective, Lloyd 2007 eq. 79 shaping (rule "p")
            | "Po"                  perspective, LiSPSM's 1/sin γ as in Lloyd 2007 Table 3 (rule "po")
            | "LogP" | "Log"        log+perspective, eq. 79 shaping (rule "logp")
            | "Sopt" | "LogSopt"    perspective / log+perspective with the S-optimal n′ per direction
            | RULE                  perspective with any registered warping rule (see WARPING_RULES)

``ZP<k>`` splits the frustum into k self-similar partitions (Lloyd 2006 eqs. 15–16), each
with its own map fitted separately; a scheme's S̄ is the sum over its maps.  Face-partitioned
schemes need a different number of maps per direction (``Result.maps_used``); inside them
``ZP<k>`` splits each side face into k depth ranges (Lloyd 2006's FP+ZP+W).

Example
-------
>>> r = evaluate("ZP5+LogP", near=1.0, far=1000.0, fov=60.0, light="overhead")
>>> round(float(r.S[0]), 3), r.maps
(5.982, 5)
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _validation as check
from . import directional, faces, geometry, warping
from .view import View, split_view

Array = NDArray[np.float64]
GRAMMAR = "Standard | P | Po | LogP (Log) | Sopt | LogSopt | <warping rule> | ZP<k> | ZP<k>+<any of these> | FP|FPc|FPcs[+ZP<k>]+P|LogP|Standard"
_FACE_VARIANTS = {"fp": "FP", "fpc": "FPc", "fpcs": "FPcs"}
_FACE_BASES = {"p": ("p", "perspective", "P"), "logp": ("logp", "logperspective", "LogP"), "log": ("logp", "logperspective", "LogP"), "standard": ("uniform", "uniform", "Standard"), "uniform": ("uniform", "uniform", "Standard")}
_BASES = {
    "standard": ("uniform", "uniform"),
    "uniform": ("uniform", "uniform"),
    "p": ("p", "perspective"),
    "po": ("po", "perspective"),
    "logp": ("logp", "logperspective"),
    "log": ("logp", "logperspective"),
    "sopt": ("sopt", "perspective"),
    "logsopt": ("sopt", "logperspective"),
    "pyramid-log": ("pyramid-log", "logperspective"),  # the registered rule's log+perspective form
}
_NAMED = ("Standard", "P", "Po", "LogP", "Sopt", "LogSopt")  # the named schemes, as suggested for a misspelt one


@dataclass(frozen=True)
class Scheme:
    """A parsed scheme: ``k`` z-partitions, a warping ``rule`` and a ``parameterization``."""

    name: str
    k: int
    rule: str
    parameterization: str
    faces: str = ""  # "", "fp", "fpc" or "fpcs"


@dataclass(frozen=True)
class Result:
    """Evaluation of a scheme over N light directions and its K maps (unit resolutions)."""

    scheme: Scheme
    M_x: Array  # (N, K)
    M_z: Array  # (N, K)
    S: Array  # (N,): Σ_k M_x M_z
    n_prime: Array  # (N, K) [world units, light-plane]
    eta: Array  # (N, K); NaN where n′ lies outside η's range (warps stronger than PSM)
    maps: int  # K map slots (columns); face partitions use only some of them per direction

    @property
    def maps_used(self) -> NDArray[np.int_]:
        """Shadow maps each direction needs ``(N,)`` (Lloyd 2007 Table 3's "# SMs").

        A used map has M_x > 0; the unused slots of face partitions hold 0.
        """
        return np.count_nonzero(self.M_x > 0, axis=-1)


def parse(name: str) -> Scheme:
    """Parse a scheme name; ``ValueError`` shows the grammar.

    Example
    -------
    >>> parse("zp7+log")
    Scheme(name='ZP7+LogP', k=7, rule='logp', parameterization='logperspective', faces='')
    """
    check.instance(name, "name (scheme name)", str)
    text = name.strip()
    fm = re.fullmatch(r"(fp|fpc|fpcs)(?:\+zp(\d+))?\+(.+)", text, flags=re.IGNORECASE)
    if fm:
        return _parse_faces(name, fm)
    m = re.fullmatch(r"zp(\d+)(?:\+(.+))?", text, flags=re.IGNORECASE)
    k, base = (int(m.group(1)), m.group(2) or "standard") if m else (1, text)
    if m and k < 1:
        raise ValueError(f"k in {name!r} must be >= 1 (ZP<k> has k z-partitions); grammar: {GRAMMAR}")
    key = base.strip().lower()
    if key in _BASES:
        rule, param = _BASES[key]
    elif key in warping.WARPING_RULES:
        rule, param = key, "perspective"
    else:
        prefix = text[: len(text) - len(base)] if m and m.group(2) else ""  # the typed "ZP<k>+" stays in the suggestion
        hint = check.did_you_mean(text, [prefix + known for known in (*_NAMED, *warping.WARPING_RULES)])
        raise ValueError(f"unknown scheme name {name!r}{hint}; grammar: {GRAMMAR}; rules: {', '.join(warping.WARPING_RULES)}")
    # the canonical name (docs/cli.rst, "Scheme names"): the named schemes in their own spelling,
    # a warping rule by its registered name (lower case), aliases (Log, uniform) resolved
    label = {"uniform": "Standard", "p": "P", "po": "Po", "logp": "LogP", "sopt": "Sopt"}.get(rule, rule)
    if rule == "sopt" and param == "logperspective":
        label = "LogSopt"
    return Scheme(name=(f"ZP{k}" if label == "Standard" else f"ZP{k}+{label}") if m else label, k=k, rule=rule, parameterization=param)


def _parse_faces(name: str, fm: re.Match) -> Scheme:
    variant, k, base = fm.group(1).lower(), int(fm.group(2) or 1), fm.group(3).strip().lower()
    if k < 1:
        raise ValueError(f"k in {name!r} must be >= 1; grammar: {GRAMMAR}")
    if base not in _FACE_BASES:
        hint = check.did_you_mean(fm.group(3).strip(), ["P", "LogP", "Standard"])
        raise ValueError(f"unknown side-face parameterization in {name!r}{hint}: face partitions take P, LogP or Standard; grammar: {GRAMMAR}")
    rule, param, label = _FACE_BASES[base]
    zp = f"+ZP{k}" if fm.group(2) else ""
    return Scheme(name=f"{_FACE_VARIANTS[variant]}{zp}+{label}", k=k, rule=rule, parameterization=param, faces=variant)


def z_partitions(near: float, far: float, k: int) -> tuple[Array, Array]:
    """Self-similar split depths n_i = n (f/n)^((i−1)/k), f_i = n (f/n)^(i/k) (Lloyd 2006 eqs. 15–16)."""
    n, f = check.frustum(check.scalar(near, "near"), check.scalar(far, "far"))
    k = check.whole(k, "k", 1, 1024, " (number of z-partitions)")
    edges = float(n) * (float(f) / float(n)) ** (np.arange(k + 1) / k)  # eqs. (15), (16)
    edges[-1] = float(f)
    return edges[:-1], edges[1:]


def evaluate(scheme: str | Scheme | Sequence[str | Scheme], near: float | View | None = None, far: float | None = None, fov: float | None = None, light: str | ArrayLike | None = None, *, edges: ArrayLike | None = None, **options: ArrayLike) -> Result | list[Result]:
    """M_x, M_z, S̄ of a scheme for every light direction (vectorized over directions).

    Parameters
    ----------
    scheme : str or Scheme, or a list of them
        A name in the grammar of this module; a list evaluates every scheme on the same
        directions (:func:`evaluate_many`) and returns a list of Results.
    near, far : float
        Eye near and far distances [world units], 0 < near < far (default 1 and 1000).
        Or a :class:`aliasing.View` in ``near``: ``evaluate("P", view, light)``.
    fov : float
        Full field of view [deg] (default 60).
    light : str or array_like
        A light spec (:data:`aliasing.geometry.LIGHT_SPEC`) or vectors ``(N, 3)`` towards
        the light (default ``"overhead"``).
    edges : array_like, optional
        Explicit split distances C_0 = near < … < C_k = far (e.g. from
        :func:`aliasing.partitioning.split_distances`), or a pair of arrays
        ``(near_i, far_i)`` for padded or overlapping maps (from
        :func:`aliasing.partitioning.partitions`), instead of ``ZP<k>``'s self-similar
        ones; k is then the number of maps and the scheme's own k is ignored.
    **options
        Passed to the warping rule (e.g. ``c_fraction`` for P/LogP, ``focus`` for TSM).
    """
    if isinstance(scheme, (list, tuple)):
        return evaluate_many(scheme, near, far, fov, light, edges=edges, **options)
    check.instance(scheme, "scheme", (str, Scheme))
    return evaluate_many([scheme], near, far, fov, light, edges=edges, **options)[0]


CHUNK = 4096
"""Directions per block in :func:`evaluate_many`: keeps each ``(N, K)`` temporary in cache."""


@check.public  # overflow at extreme frusta gives inf (not a warning); broadcast errors name the parameters
def evaluate_many(names: Sequence[str | Scheme], near: float | View | None = None, far: float | None = None, fov: float | None = None, light: str | ArrayLike | None = None, *, edges: ArrayLike | None = None, chunk: int = CHUNK, **options: ArrayLike) -> list[Result]:
    """:func:`evaluate` for several schemes on the same directions: one Result per name.

    Every name is parsed before any work (an unknown one fails as it does alone).  The
    light frame of each direction and the corner rays' light-space coordinates are computed
    once (:func:`aliasing.directional.light_frame`) and shared by every scheme and every
    z-partition; schemes with the same partitions share the map fits too.  Directions are
    processed in blocks of ``chunk``.

    Example
    -------
    >>> [round(float(r.S[0]), 3) for r in evaluate_many(["P", "ZP5+LogP"], 1.0, 1000.0, 60.0, "overhead")]
    [865.159, 5.982]
    """
    if isinstance(names, (str, Scheme)):
        raise ValueError("names must be a list of scheme names (use evaluate for one)")
    check.instance(names, "names", (list, tuple))
    parsed = [parse(s) if isinstance(s, str) else s for s in names]
    for sch in parsed:
        check.instance(sch, "names entry (a scheme)", Scheme)  # a name or a parsed Scheme, nothing else
    if not parsed:
        raise ValueError("names must list at least one scheme")
    if isinstance(chunk, bool) or not isinstance(chunk, (int, np.integer)) or chunk < 1:
        raise ValueError(f"chunk must be a whole number >= 1 (directions per block), got {chunk!r}")
    view, light = split_view(near, far, fov, light, (1.0, 1000.0, 60.0, "overhead"))
    lv = geometry.lights(light)
    if view.shape != ():
        raise ValueError(f"evaluate takes one view: near, far and fov must be scalars, got shape {view.shape}")
    if edges is not None:
        n_e, f_e = _explicit_partitions(edges, view.near, view.far)
    results: list[Result | None] = [None] * len(parsed)
    groups: dict[int, list[int]] = {}
    for i, sch in enumerate(parsed):
        if sch.faces:
            results[i] = _evaluate_faces(sch, view, lv, edges, chunk, **options)
        else:
            groups.setdefault(-1 if edges is not None else sch.k, []).append(i)
    parts = {k: (n_e, f_e) if k == -1 else z_partitions(view.near, view.far, k) for k in groups}
    out = {i: np.empty((4, len(parts[k][0]), len(lv))) for k, ids in groups.items() for i in ids}  # M_x, M_z, n′, η as (K, N)
    for start in range(0, len(lv) if groups else 0, chunk):
        block = lv[start : start + chunk]
        frame = directional.light_frame(view, block)
        gamma = directional.folded_gamma(block)[None]
        azimuth = geometry.direction_angles(block)[1][None]  # for rules of the full geometry (warping.CONTEXT)
        for k, ids in groups.items():
            n_i, f_i = parts[k]
            sf = directional.slice_fit(frame, n_i, f_i)
            for i in ids:
                out[i][:, :, start : start + chunk] = _maps(parsed[i], sf, gamma, azimuth, options)
    for k, ids in groups.items():
        n_i, _ = parts[k]
        for i in ids:
            sch = parsed[i]
            if k == -1:
                sch = Scheme(name=sch.name, k=len(n_i), rule=sch.rule, parameterization=sch.parameterization)
            M_x, M_z, npr, eta = out[i]
            S = (M_x * M_z).sum(axis=0)  # Σ over maps in map order, as a sum over the last axis of (N, K)
            results[i] = Result(sch, M_x.T, M_z.T, S, npr.T, eta.T, sch.k)  # (N, K) views of (K, N) memory
    return results  # type: ignore[return-value]


def _maps(sch: Scheme, sf: directional.SliceFit, gamma: Array, azimuth: Array, options: dict) -> tuple[Array, ...]:
    """M_x, M_z, n′, η ``(K, N)`` of one scheme's maps on fitted slices."""
    n_i, f_i, fov = sf.near, sf.far, sf.frame.view  # the View itself: its fov is validated once, there
    if sch.rule == "sopt":
        npr = _s_optimal(sf, sch.parameterization)
    else:
        npr = np.broadcast_to(warping.warping_parameter(sch.rule, n_i, f_i, fov=fov, gamma=gamma, depth=sf.depth, azimuth=azimuth, **options), sf.depth.shape)
    M_x, M_z = directional.slice_errors(sf, npr, sch.parameterization)
    rule = warping.WARPING_RULES.get(sch.rule)
    if rule is not None and rule.bounded:
        # never above Standard, by construction: each map keeps the rule's n′ only where its
        # S̄ is at most the uniform map's (n′ = ∞, which both parameterizations reduce to)
        u_x, u_z = directional.slice_errors(sf, np.inf, "uniform")
        above = M_x * M_z > u_x * u_z
        if above.any():
            npr = np.where(above, np.inf, npr)
            M_x, M_z = np.where(above, u_x, M_x), np.where(above, u_z, M_z)
    return M_x, M_z, npr, _eta_or_nan(npr, n_i, f_i, sf.depth)


def _evaluate_faces(sch: Scheme, view: View, light: Array, edges: ArrayLike | None, chunk: int = CHUNK, **options: ArrayLike) -> Result:
    """Face partitioning through :func:`aliasing.faces.face_errors` (options: tau0, tau1)."""
    if edges is not None:
        raise ValueError(f"edges apply to z-partitions, not to the face partitions of {sch.name}")
    unknown = set(options) - {"tau0", "tau1"}
    if unknown:
        raise ValueError(f"unknown options for {sch.name}: {', '.join(sorted(unknown))}; face partitions take tau0, tau1")
    opts = {k: float(v) for k, v in options.items()}
    # blocks of directions bound the (N, 4, H, k, 4, 3) vertex temporaries of the face frames
    parts = [faces.face_errors(sch.faces, sch.parameterization, view, light[s : s + chunk], k=sch.k, **opts) for s in range(0, len(light), chunk)]
    M_x, M_z, S = (np.concatenate([getattr(r, a) for r in parts]) for a in ("M_x", "M_z", "S"))
    nan = np.full(M_x.shape, np.nan)
    return Result(sch, M_x, M_z, S, nan, nan, M_x.shape[1])


def _explicit_partitions(edges: ArrayLike | tuple[ArrayLike, ArrayLike], near: float, far: float) -> tuple[Array, Array]:
    if isinstance(edges, tuple) and len(edges) == 2:
        lo = check.as_float_array(edges[0], "edges").ravel()
        hi = check.as_float_array(edges[1], "edges").ravel()
        if lo.shape != hi.shape or lo.size == 0 or np.any(hi <= lo):
            raise ValueError("edges as (near_i, far_i) need equal lengths and near_i < far_i")
    else:
        c = check.as_float_array(edges, "edges").ravel()
        if c.size < 2 or np.any(np.diff(c) <= 0):
            raise ValueError("edges must be at least two increasing split distances")
        lo, hi = c[:-1], c[1:]
    if not (np.isclose(lo.min(), near, rtol=1e-12) and np.isclose(hi.max(), far, rtol=1e-12)):
        raise ValueError(f"edges must start at near ({near:g}) and end at far ({far:g})")
    return lo, hi


def _eta_or_nan(npr: Array, n_i: Array, f_i: Array, depth: Array) -> Array:
    if np.isinf(npr).all():  # uniform maps: eq. 120 inverted gives exactly −1 (n′/f′ = 1)
        return np.full(np.broadcast(npr, depth).shape, -1.0)
    ng = depth * n_i / (f_i - n_i)
    inside = npr >= ng * (1 - 1e-12)
    return np.where(inside, warping.eta_checked(np.where(inside, npr, ng), n_i, f_i, ng), np.nan)


def _s_optimal(sf: directional.SliceFit, parameterization: str) -> Array:
    """n′ minimising S̄ of each map, over η ∈ [−1, 1] (n′ from n_γ to ∞), per direction.

    Lloyd 2007 App. B calls this optimum involved to compute; here: a grid over η, then a
    golden-section refinement around the best grid point (S̄ is evaluated at the vertices).
    Vectorized over directions and partitions; the loops run over η samples only.
    """

    n_i, f_i = sf.near, sf.far

    def storage(eta: Array) -> Array:
        mx, mz = directional.slice_errors(sf, warping.n_prime_from_eta(eta, n_i, f_i, sf.depth), parameterization)
        return mx * mz

    grid = np.linspace(-1.0, 1.0, 41)
    best_eta = np.full(sf.depth.shape, -1.0)
    best_s = storage(best_eta)
    for e in grid[1:]:
        s = storage(np.full(sf.depth.shape, e))
        better = s < best_s
        best_eta, best_s = np.where(better, e, best_eta), np.where(better, s, best_s)
    step = grid[1] - grid[0]
    lo, hi = np.clip(best_eta - step, -1, 1), np.clip(best_eta + step, -1, 1)
    ratio = (np.sqrt(5) - 1) / 2
    for _ in range(40):  # bracket shrinks by 0.618 each step: 2·0.05·0.618⁴⁰ ≈ 4e-10 in η
        a, b = hi - ratio * (hi - lo), lo + ratio * (hi - lo)
        left = storage(a) <= storage(b)
        lo, hi = np.where(left, lo, a), np.where(left, b, hi)
    mid = (lo + hi) / 2
    eta = np.where(storage(mid) < best_s, mid, best_eta)
    return warping.n_prime_from_eta(eta, n_i, f_i, sf.depth)
