"""Critical resolution and storage factors of a frustum face over light positions.

Lloyd et al. 2007 §5.1 and App. A: for a parameterization with spacing δ_l on a face and the
error-bound spacing δ_b of a light (eqs. 55–69, with the general cos φ_l terms),

* R_t = max_v δ_l,t/δ_b,t (eq. 47), R_s = max over the face of δ_l,s/δ_b,s (eq. 71),
  S = R_s R_t (eq. 70); for the error-bound parameterization itself R_b = ρ_b (eqs. 63–65,
  R_b,s = max_v ρ_b,s(v));
* their maxima over light positions Ω, 𝐑 = max_Ω R and 𝐒 = max_Ω S (eqs. 72–73).

The paper's claim below eq. 73, that 𝐑 and 𝐒 are those of a light at infinity straight above
the face, follows from cos φ_l ≤ 1: δ_b is smallest, pointwise, when cos φ_l = 1 everywhere,
so every ratio δ_l/δ_b, every ρ_b = ∫1/δ_b and every minimum over a parameter of them is
largest there.  The closed forms at that light are eqs. 87–103
(:func:`aliasing.logpsm_critical.critical_factors`).

Parameterizations (``kind``; a is the perspective parameter, the centre of projection at
y = −a; b the second root of δ_lp,t):

=============  ======================================  ======================================
kind           s (across the face)                     t (along the face)
=============  ======================================  ======================================
bound          F_b,s: R = max_v ρ_b,s(v) (eq. 64)      F_b,t: R = ρ_b,t (eqs. 63, 65)
uniform        δ = 1 (eq. 90)                          δ = 1
perspective    δ_p,s (eq. 96)                          δ_p,t (eq. 97)
log            δ_p,s (F_lp,s = F_p,s, eq. 78)          δ_log,t (eq. 102)
logp           δ_p,s                                   δ_lp,t (eq. 109; b = inf is δ_log,t)
=============  ======================================  ======================================

``log`` takes F_p,s across the face as the LogPSM does (eq. 78; eq. 77 defines t only), so
that S^side is O(log f/n) as in Table 2.  End faces (``face="near"`` or ``"far"``) have
``bound`` and ``uniform`` only (Table 2), with δ_b,s^end = δ_b,t^end in x (§4.4).

Lights, in the face's frame (Fig. 5; side face: origin at the eye, y along the face, z its
normal; end face: origin at the face's centre): a point light at (``lx``, ``ly``, ``lz``),
0 ≤ lz ≤ inf — ``lz = inf`` is the directional light straight above the face and ``lz = 0``
a light in the face's plane, taken as the limit lz → 0+ (R_b → 0; for the other kinds
cos φ_l → 1 at the light's foot point and 0 elsewhere) — or, with ``directional=True``, a
directional light shining from the direction (``lx``, ``ly``, ``lz``), lz > 0 (cos φ_lx and
cos φ_ly constant).  The cos θ of δ_b is included (App. A's figures factor it out of
R_b,t^end, R_b,s^side and R_un,s).

Example
-------
>>> f = face_factors("log", 1.0, 1000.0, 90.0)  # overhead: eq. 99 × eq. 103
>>> [round(float(f[k]), 4) for k in ("R_s", "R_t", "S")]
[1.4142, 6.9078, 9.769]
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _validation as check
from . import logpsm

__all__ = [
    "face_factors",
    "max_over_lights",
    "optimal_factors",
    "optimal_root",
]

Array = NDArray[np.float64]
KINDS = ("bound", "uniform", "perspective", "log", "logp")
FACES = ("side", "near", "far")
GOLDEN = (np.sqrt(5.0) - 1.0) / 2.0


# --- maximisation over a bracket, vectorized over everything else ----------------------------------
def _golden(func: Callable[[Array], Array], lo: Array, hi: Array, iterations: int, sign: float) -> tuple[Array, Array]:
    """Golden-section search for the maximum (sign = 1) or minimum (sign = −1) of func on [lo, hi]."""
    a, b = np.broadcast_arrays(np.asarray(lo, float), np.asarray(hi, float))
    a, b = a.copy(), b.copy()
    c, d = b - GOLDEN * (b - a), a + GOLDEN * (b - a)
    fc, fd = sign * func(c), sign * func(d)
    for _ in range(iterations):
        left = fc >= fd  # keep [a, d]
        b = np.where(left, d, b)
        a = np.where(left, a, c)
        c_new = b - GOLDEN * (b - a)
        d_new = a + GOLDEN * (b - a)
        x_new = np.where(left, c_new, d_new)
        f_new = sign * func(x_new)
        c, d, fc, fd = np.where(left, c_new, d), np.where(left, c, d_new), np.where(left, f_new, fd), np.where(left, fc, f_new)
    best = np.where(fc >= fd, c, d)
    return best, sign * np.maximum(fc, fd)


def _extremum(func: Callable[[Array], Array], lo: ArrayLike, hi: ArrayLike, samples: int, sign: float = 1.0, iterations: int = 32) -> tuple[Array, Array]:
    """(argmax, max) (sign = 1) or (argmin, min) of func on [lo, hi]: samples, then golden-section
    refinement between the best sample's neighbours.  ``func`` broadcasts its argument against
    its own parameters; the result has their broadcast shape with lo and hi."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    grid = np.linspace(0.0, 1.0, samples).reshape((-1,) + (1,) * max(lo.ndim, hi.ndim))
    xs = lo + (hi - lo) * grid
    out = sign * func(xs)
    vals = np.broadcast_to(out, np.broadcast_shapes(np.shape(out), xs.shape))  # func may not depend on its argument
    xs = np.broadcast_to(xs, vals.shape)
    k = np.argmax(vals, axis=0)[None]
    step = (hi - lo) / (samples - 1)
    x_best = np.take_along_axis(xs, k, axis=0)[0]
    v_best = sign * np.take_along_axis(vals, k, axis=0)[0]
    x_ref, v_ref = _golden(func, np.maximum(x_best - step, lo), np.minimum(x_best + step, hi), iterations, sign)
    better = sign * v_ref > sign * v_best
    return np.where(better, x_ref, x_best), np.where(better, v_ref, v_best)


# --- light positions ---------------------------------------------------------------------------------
def _light(lx: ArrayLike, ly: ArrayLike, lz: ArrayLike, directional: bool) -> tuple[Array, Array, Array]:
    lx_ = check.as_float_array(lx, "lx")
    ly_ = check.as_float_array(ly, "ly")
    if np.isinf(lx_).any() or np.isinf(ly_).any():
        raise ValueError("lx and ly must be finite (a light far away is lz = inf or directional=True)")
    if check.flag(directional, "directional"):
        lz_ = check.positive(lz, "lz")
    else:
        lz_ = check.closed_range(lz, "lz", 0.0, np.inf, " (0: the light in the face's plane, inf: overhead)")
    return lx_, ly_, lz_


def _kind_face(kind: str, face: str) -> tuple[str, str]:
    key = check.choice(kind, "kind", KINDS)
    fkey = check.choice(face, "face", FACES)
    if fkey != "side" and key not in ("bound", "uniform"):
        raise ValueError(f"kind {kind!r} is defined on side faces only; on an end face choose one of: bound, uniform")
    return key, fkey


def _t_spacing(key: str, v: Array, near, far, fov, a, b) -> Array:
    name = {"uniform": "uniform", "perspective": "perspective_t", "log": "log_t", "logp": "logp_t"}[key]
    return logpsm.spacing(name, v, near, far, fov, a=a, b=b)


def _ratio_t(key: str, fkey: str, v: Array, near, far, fov, ly, lz, directional: bool, a, b) -> Array:
    """δ_l,t/δ_b,t at v (eq. 47's argument) for a light with lz > 0."""
    if fkey == "side":
        bound = logpsm.delta_bound_side_t(v, near, far, fov, ly=ly, lz=lz, directional=directional)  # eq. (62)
        return _t_spacing(key, v, near, far, fov, a, b) / bound  # eq. (47)
    return 1.0 / logpsm.delta_bound_end(v, near, far, fov, ly=ly, lz=lz, face=fkey, directional=directional)  # eqs. (47), (58), (92)


def _ratio_s(key: str, fkey: str, v: Array, near, far, fov, lx, lz, directional: bool, a) -> Array:
    """max over the face's row at v of δ_l,s/δ_b,s (eq. 71's argument) for a light with lz > 0.

    δ_l,s is constant along a row, so the maximum is where cos φ_lx is largest: at the row's
    point nearest to l_x (u* of the clamped x*).
    """
    if fkey != "side":  # end face: δ_b,s^end is δ_b,t^end in x (§4.4)
        return _ratio_t(key, fkey, v, near, far, fov, lx, lz, directional, a, np.inf)
    y0, y1, We, _ = logpsm.side_face(near, far, fov)
    yy = y0 + (y1 - y0) * v
    half = We * yy / (2 * y0)  # x1(y), eq. (60)
    u_star = np.clip(lx, -half, half) / (We * y1 / y0) + 0.5
    u_star = np.clip(u_star, 0.0, 1.0)
    bound = logpsm.delta_bound_side_s(u_star, v, near, far, fov, lx=lx, lz=lz, directional=directional)  # eq. (61)
    spacing = 1.0 if key == "uniform" else logpsm.spacing("perspective_s", v, near, far, fov, a=a)  # eqs. (90), (96)
    return spacing / bound  # eq. (71)


def _rho(fkey: str, direction: str, v: Array, near, far, fov, lx, ly, lz, directional: bool) -> Array:
    """ρ_b (eqs. 63–65) for lz > 0: closed forms ζ for a point light, cos φ_l × eqs. 87–89 otherwise."""
    cf = logpsm.critical_factors(near, far, fov)
    coord = lx if direction == "s" else ly
    overhead = cf["bound_t_end"] if fkey != "side" else cf["bound_s_side" if direction == "s" else "bound_t_side"]  # eqs. (87)-(89)
    if directional:
        return overhead * logpsm._cos_phi(0.0, coord, lz, directional=True)
    finite = np.isfinite(lz)
    safe = np.where(finite, lz, 1.0)
    if fkey == "side":
        kind = "side_s" if direction == "s" else "side_t"
        rho = logpsm.rho_bound(kind, near, far, fov, lx=lx, ly=ly, lz=safe, v=v)
    else:
        rho = logpsm.rho_bound("end", near, far, fov, ly=coord, lz=safe, face=fkey)
    return np.where(finite, rho, overhead)


@dataclass(frozen=True)
class _Setup:
    """Validated inputs of one evaluation: the parameterization, face, frustum and light."""

    key: str
    fkey: str
    near: Array
    far: Array
    fov: Array
    lx: Array
    ly: Array
    lz: Array  # lz with the in-plane lights (lz = 0) replaced by 1 (they are handled as a limit)
    in_plane: Array
    directional: bool
    samples: int


# Most samples per face coordinate (each holds one float per light position and sample).
MAX_SAMPLES = 100_000
# Largest f/n the face factors accept: found by sweeping f/n to 1e308, the golden-section
# searches of optimal_root and optimal_factors meet inf/inf from about f/n = 1e160 on.
MAX_DEPTH_RATIO = 1e100


def _setup(kind, near, far, fov, lx, ly, lz, directional, face, samples) -> _Setup:
    key, fkey = _kind_face(kind, face)
    lx_, ly_, lz_ = _light(lx, ly, lz, directional)
    samples = check.whole(samples, "samples", 3, MAX_SAMPLES)
    near_, far_ = check.frustum(near, far)
    if (far_ / near_ > MAX_DEPTH_RATIO).any():  # the optimisations' ratios overflow float64 beyond
        raise ValueError(f"far/near must be at most {MAX_DEPTH_RATIO:g} for the face factors, got near={check._show(near_)}, far={check._show(far_)}")
    in_plane = np.zeros(lz_.shape, bool) if directional else lz_ == 0
    return _Setup(key, fkey, near_, far_, check.fov(fov), lx_, ly_, np.where(in_plane, 1.0, lz_), in_plane, directional, int(samples))


def _R_t(c: _Setup, a, b, zeros: Array) -> Array:
    """R_t = max_v δ_l,t/δ_b,t (eq. 47), or ρ_b,t (eqs. 63, 65) for the bound."""
    if c.key == "bound":
        return np.where(c.in_plane, 0.0, _rho(c.fkey, "t", 0.0, c.near, c.far, c.fov, c.lx, c.ly, c.lz, c.directional) + zeros)  # ∫ cos φ_l → 0

    def ratio(q, lz_used=c.lz):
        return _ratio_t(c.key, c.fkey, q, c.near, c.far, c.fov, c.ly, lz_used, c.directional, a, b)

    _, R = _extremum(ratio, zeros, zeros + 1.0, c.samples)
    if c.directional:
        return R
    lo, hi = _coordinate_range(c.fkey, "t", c.near, c.far, c.fov)
    v_ly = np.clip((c.ly - lo) / (hi - lo), 0.0, 1.0)
    R = np.maximum(R, ratio(v_ly))  # cos φ_l = 1 under a point light: that point is a candidate
    if c.in_plane.any():  # the limit lz → 0+: cos φ_l → 1 at the foot point, 0 elsewhere
        R = np.where(c.in_plane, np.where((c.ly >= lo) & (c.ly <= hi), ratio(v_ly, np.inf), 0.0), R)
    return R


def _R_s(c: _Setup, a, zeros: Array) -> Array:
    """R_s = max over the face of δ_l,s/δ_b,s (eq. 71), or max_v ρ_b,s(v) (eq. 64) for the bound."""
    if c.key == "bound":
        if c.fkey == "side":
            _, R = _extremum(lambda q: _rho(c.fkey, "s", q, c.near, c.far, c.fov, c.lx, c.ly, c.lz, c.directional), zeros, zeros + 1.0, c.samples)
        else:
            R = _rho(c.fkey, "s", 0.0, c.near, c.far, c.fov, c.lx, c.ly, c.lz, c.directional)
        return np.where(c.in_plane, 0.0, R + zeros)

    def ratio(q, lz_used=c.lz):
        return _ratio_s(c.key, c.fkey, q, c.near, c.far, c.fov, c.lx, lz_used, c.directional, a)

    _, R = _extremum(ratio, zeros, zeros + 1.0, c.samples)
    if c.directional:
        return R
    if c.fkey != "side":
        lo, hi = _coordinate_range(c.fkey, "s", c.near, c.far, c.fov)
        R = np.maximum(R, ratio(np.clip((c.lx - lo) / (hi - lo), 0.0, 1.0)))
    if c.in_plane.any():  # the limit lz → 0+: only the rows containing x = l_x keep cos φ_l = 1
        v_lo = _first_row_under(c.fkey, c.lx, c.near, c.far, c.fov)
        _, R_plane = _extremum(lambda q: ratio(q, np.inf), np.where(np.isfinite(v_lo), v_lo, 0.0) + zeros, zeros + 1.0, c.samples)
        R = np.where(c.in_plane, np.where(np.isfinite(v_lo), R_plane, 0.0), R)
    return R + zeros


@check.public
def face_factors(kind: str, near: ArrayLike, far: ArrayLike, fov: ArrayLike, *, lx: ArrayLike = 0.0, ly: ArrayLike = 0.0, lz: ArrayLike = np.inf,
                 directional: bool = False, a: ArrayLike = 0.0, b: ArrayLike = np.inf, face: str = "side", samples: int = 257) -> dict[str, Array]:
    """R_s, R_t and S = R_s R_t of a face for a light, Lloyd et al. 2007, eqs. 47, 63–65, 70–71.

    Parameters
    ----------
    kind : {"bound", "uniform", "perspective", "log", "logp"}
        The parameterization (see the module docstring).
    near, far : array_like
        Eye near and far distances [world units], 0 < near < far.
    fov : array_like
        Full field of view [degrees], in (0, 180).
    lx, ly, lz : array_like, optional
        Light position in the face's frame [world units], 0 ≤ lz ≤ inf, or with
        ``directional`` the direction towards the light (lz > 0).
    directional : bool, optional
        A directional light from direction (lx, ly, lz) instead of a point light.
    a, b : array_like, optional
        Perspective parameter a ≥ 0 and second root b of δ_lp,t [world units] (as in
        :func:`aliasing.logpsm.spacing`).
    face : {"side", "near", "far"}
        A side face or an end face.
    samples : int, optional
        Samples of v (≥ 3) before the golden-section refinement of each maximum.

    Returns
    -------
    dict of str to ndarray
        ``R_s``, ``R_t`` (texels per pixel, dimensionless) and ``S``, broadcast over all inputs.

    Examples
    --------
    >>> f = face_factors("uniform", 1.0, 100.0, 90.0, ly=50.0, lz=20.0)
    >>> bool(f["R_t"] < face_factors("uniform", 1.0, 100.0, 90.0)["R_t"])  # eq. 72: overhead is the worst
    True
    """
    c = _setup(kind, near, far, fov, lx, ly, lz, directional, face, samples)
    a, b = check.closed_range(a, "a", 0.0, np.inf), check.as_float_array(b, "b")  # b's range: logpsm.spacing
    zeros = np.zeros(np.broadcast(c.near, c.far, c.fov, c.lx, c.ly, c.lz, a, b).shape)
    R_s, R_t = _R_s(c, a, zeros), _R_t(c, a, b, zeros)
    return {"R_s": R_s, "R_t": R_t, "S": R_s * R_t}


def _coordinate_range(fkey: str, direction: str, near, far, fov) -> tuple[Array, Array]:
    """The face's extent [lo, hi] along y (t) or x (s) in its frame [world units]."""
    y0, y1, We, _ = logpsm.side_face(near, far, fov)
    if fkey == "side" and direction == "t":
        return y0, y1
    width = We * (far if fkey == "far" else near) / near if fkey != "side" else We * y1 / y0
    return -width / 2, width / 2


def _first_row_under(fkey: str, lx: Array, near, far, fov) -> Array:
    """The smallest v whose row of the face contains x = lx (inf if none), for a light in the face's plane."""
    if fkey != "side":
        lo, hi = _coordinate_range(fkey, "s", near, far, fov)
        return np.where((lx >= lo) & (lx <= hi), 0.0, np.inf)
    y0, y1, We, _ = logpsm.side_face(near, far, fov)
    y_needed = np.maximum(2 * y0 * np.abs(lx) / We, y0)  # |lx| ≤ W_e y/(2 y0), eq. (60)
    return np.where(y_needed <= y1, (y_needed - y0) / (y1 - y0), np.inf)


@check.public
def optimal_factors(kind: str, near: ArrayLike, far: ArrayLike, fov: ArrayLike, *, minimize: str = "S", lx: ArrayLike = 0.0, ly: ArrayLike = 0.0,
                    lz: ArrayLike = np.inf, directional: bool = False, b: ArrayLike = np.inf, a_max: float = 1e4, samples: int = 129) -> dict[str, Array]:
    """R_s, R_t, S with the perspective parameter a chosen per light to minimise one of them.

    Lloyd et al. 2007 App. A: the optimal R_p,s, R_p,t and S_p (Fig. 23, eqs. 98–101), the
    optimal R_log,t (Fig. 25, eq. 103) and S_lp (Fig. 26, "we find the optimal a parameter
    numerically").  a is searched over [0, a_max·y1] (a sampled logarithmic grid in
    ln(1 + a/y0), then a golden-section refinement).

    Parameters
    ----------
    kind : {"perspective", "log", "logp"}
    minimize : {"S", "R_s", "R_t"}
    a_max : float, optional
        Upper end of the search in units of y1, > 0.
    Other parameters as in :func:`face_factors` (side faces).

    Returns
    -------
    dict of str to ndarray
        ``R_s``, ``R_t``, ``S`` at the optimum and the optimal ``a`` [world units].

    Examples
    --------
    >>> f = optimal_factors("perspective", 1.0, 1000.0, 90.0, minimize="R_t")  # eq. 100 at a = √(y0 y1)
    >>> round(float(f["R_t"]), 4), round(float(f["a"] / np.sqrt(2) / np.sqrt(1000.0)), 4)
    (31.5911, 1.0)
    """
    key = check.choice(kind, "kind", ["perspective", "log", "logp"])
    target = {"s": "S", "r_s": "R_s", "r_t": "R_t"}[check.choice(minimize, "minimize", ["s", "r_s", "r_t"])]
    a_top = check.positive(a_max, "a_max")
    y0, y1, _, _ = logpsm.side_face(near, far, fov)
    tau_max = np.logaddexp(0.0, np.log(a_top) + np.log(y1) - np.log(y0))  # log1p(a_top·y1/y0), finite where the ratio overflows

    def value(tau):
        return face_factors(key, near, far, fov, lx=lx, ly=ly, lz=lz, directional=directional, a=y0 * np.expm1(tau), b=b, samples=samples)[target]

    _light(lx, ly, lz, directional)  # checked before the shapes are taken
    shape = np.broadcast(*check.broadcast(near=check.as_float_array(near, "near"), far=check.as_float_array(far, "far"), fov=check.as_float_array(fov, "fov"),
                                          lx=lx, ly=ly, lz=lz, b=check.as_float_array(b, "b"))).shape
    tau, _ = _extremum(value, np.zeros(shape), np.zeros(shape) + tau_max, 49, sign=-1.0, iterations=40)
    a_opt = y0 * np.expm1(tau)
    out = face_factors(key, near, far, fov, lx=lx, ly=ly, lz=lz, directional=directional, a=a_opt, b=b, samples=samples)
    return {**out, "a": a_opt + np.zeros(np.shape(out["S"]))}  # broadcast; 0·S would be NaN where S is inf (a grazing light)


@check.public
def optimal_root(near: ArrayLike, far: ArrayLike, fov: ArrayLike, *, lx: ArrayLike = 0.0, ly: ArrayLike = 0.0, lz: ArrayLike = np.inf,
                 directional: bool = False, a: ArrayLike = 0.0, samples: int = 129) -> dict[str, Array]:
    """R_s, R_t, S of the log+perspective parameterization with its second root b chosen per light.

    Lloyd et al. 2007 App. A (eqs. 104–110, Fig. 26): with b finite, δ_lp,t ∝ (y + a)(y + b)
    is a parabola, which can fit the curved δ_b,t^side of a near light better than the linear
    b = ∞; "a closed-form solution for the optimal parameter b_opt … does not exist.
    Therefore b_opt must be computed numerically".  b minimises R_t (R_s does not depend on
    it) over both families the root may form: b > 0 or b < −y1 (a convex or a concave
    parabola, joined through b = ±∞, the linear form) and −y0 < b < 0.  Parameters as in
    :func:`face_factors` (side face, ``kind = "logp"``).

    Returns
    -------
    dict of str to ndarray
        ``R_s``, ``R_t``, ``S`` and the optimal ``b`` [world units] (±inf: the linear form).

    Examples
    --------
    >>> f = optimal_root(1.0, 1000.0, 90.0)  # overhead: the linear b = inf is optimal (eq. 103)
    >>> round(float(f["R_t"]), 4), bool(abs(f["b"]) > 1e6)
    (6.9078, True)
    """
    c = _setup("logp", near, far, fov, lx, ly, lz, directional, "side", samples)
    y0, y1, _, _ = logpsm.side_face(c.near, c.far, c.fov)
    aa = check.closed_range(a, "a", 0.0, np.inf)
    shape = np.broadcast(c.near, c.far, c.fov, c.lx, c.ly, c.lz, aa).shape
    piece = np.arange(2).reshape((2,) + (1,) * len(shape))

    def root(xi):
        lam = -10.0 + 22.0 * xi  # piece 0: b = y1/(e^λ − 1): concave (λ < 0), linear (λ = 0), convex (λ > 0)
        mu = -12.0 + 24.0 * xi  # piece 1: −y0 < b < 0
        with np.errstate(divide="ignore"):
            b0 = np.where(lam == 0.0, np.inf, y1 / np.expm1(lam))
        b = np.where(piece == 0, b0, -y0 / (1.0 + np.exp(-mu)))
        return np.where(b == aa, b * (1 + 1e-12), b)

    zeros = np.zeros((2,) + shape)
    xi, R_t = _extremum(lambda q: _R_t(c, aa, root(q), np.zeros(np.broadcast(q, zeros).shape)), zeros, zeros + 1.0, 49, sign=-1.0, iterations=40)
    best = np.argmin(R_t, axis=0)[None]
    b_opt = np.take_along_axis(np.broadcast_to(root(xi), R_t.shape), best, axis=0)[0]
    R_t = np.take_along_axis(R_t, best, axis=0)[0]
    R_s = _R_s(c, aa, np.zeros(shape))
    return {"R_s": R_s, "R_t": R_t, "S": R_s * R_t, "b": b_opt}


@check.public
def max_over_lights(factors: dict[str, Array], axis: int | tuple[int, ...] | None = None) -> dict[str, Array]:
    """𝐑 = max_Ω R and 𝐒 = max_Ω S over the light positions, Lloyd et al. 2007, eqs. 72–73.

    Parameters
    ----------
    factors : dict of str to ndarray
        The output of :func:`face_factors` or :func:`optimal_factors` over a set of light
        positions Ω (the ``axis`` axes; all by default).
    axis : int or tuple of int, optional

    Returns
    -------
    dict of str to ndarray
        ``R_s``, ``R_t`` and ``S``, each the maximum of its own values (S is the maximum of the
        per-light products, eq. 73, not the product of the maxima).

    Examples
    --------
    >>> sigma = np.array([0.5, 1.0, np.inf])
    >>> f = face_factors("bound", 1.0, 1000.0, 90.0, ly=500.0, lz=sigma * 999 * np.sqrt(2))
    >>> round(float(max_over_lights(f)["R_t"]), 4)  # eq. 89: ln(f/n)/sin 2θ
    6.9078
    """
    check.instance(factors, "factors", dict)
    missing = {"R_s", "R_t", "S"} - set(factors)
    if missing:
        raise ValueError(f"factors must hold R_s, R_t and S (the output of face_factors), missing {sorted(missing)}")
    try:
        return {k: np.max(np.asarray(factors[k], float), axis=axis) for k in ("R_s", "R_t", "S")}
    except (TypeError, ValueError, OverflowError, IndexError) as exc:  # numpy's AxisError is a ValueError and IndexError
        raise ValueError(f"axis must be None, an axis or a tuple of axes of the factors, got {axis!r:.60}; factors R_s, R_t, S must be real arrays ({exc})") from None
