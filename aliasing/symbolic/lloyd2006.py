"""Lloyd, Tuft, Yoon, Manocha 2006: overhead directional light, derived with sympy.

*Warping and Partitioning for Low Error Shadow Maps*, EGSR 2006, §4.1–4.2 and
Appendices A–C.

Symbol map (paper → here → numeric API):

=======================  ==============  ==========================================
paper                    sympy symbol    numeric API (:mod:`aliasing.error`)
=======================  ==============  ==========================================
θ (half field of view)   ``theta``       ``fov`` = 2θ in degrees
n, f (eye near, far)     ``n``, ``f``    ``near``, ``far``
n′ (warp parameter)      ``n_p``         ``n_prime`` (``inf`` = uniform map)
η ∈ [−1, 1]              ``eta``         ``eta``
a = f/n                  ``a``           ``far / near``
res_i, res_s, res_t      same            ``res_image``, ``res_s``, ``res_t``
=======================  ==============  ==========================================

The light is overhead: it shines along −y of light space, perpendicular to the view
direction (γ = 90° in the package convention).  The warping frustum has its centre of
projection a distance n′ before the eye's near plane, so an eye depth z has warping
depth z′ = n′ + z − n and the far plane f′ = n′ + f − n.

Every function derives its result from the definitions; :data:`PRINTED` holds the
equations as printed, for comparison (see docs/ERRATA.md for where they differ).
"""

from __future__ import annotations

import sympy as sp

from .registry import Printed, derivation
from .rewrite import linear_solve, polynomial_roots

z, n, f, theta = sp.symbols("z n f theta", positive=True)
n_p = sp.Symbol("n'", positive=True)
res_i, res_s, res_t = sp.symbols("res_i res_s res_t", positive=True)
x = sp.Symbol("x", real=True)
eta = sp.Symbol("eta", real=True)
a = sp.Symbol("a", positive=True)
S0 = sp.Symbol("S_0", positive=True)
z_p = sp.Symbol("z'", positive=True)

SOURCE = "Lloyd et al. 2006"


def _on_domain(expr: sp.Expr) -> sp.Expr:
    """Rewrite ``expr`` on the physical domain f > n, n′ > n, 0 < θ < 90° for sign tests."""
    gap, d, tan_t = sp.symbols("gap d T", positive=True)
    # factor, not simplify: a product/quotient of positive symbols and sums of them is
    # all a sign test needs (and all that the sympy assumptions system can read).
    return sp.factor(sp.together(expr.subs(sp.tan(theta), tan_t).subs({f: n + gap, n_p: n + d})))


def warping_frustum() -> dict[str, sp.Expr]:
    """The warping frustum around the view frustum (Lloyd 2006 Fig. 3, §4.1).

    Its half-angle θ′ is fixed by the tightest fit in x: the frustum must contain the
    view frustum's half-width z·tanθ at every depth, and z/(z′) grows with z when
    n′ ≥ n, so the far plane binds: f′·tanθ′ = f·tanθ.
    """
    zp = n_p + z - n
    fp = n_p + f - n
    tp = sp.Symbol("T", positive=True)
    tan_tp = linear_solve([fp * tp - f * sp.tan(theta)], [tp])[tp]
    return {"z'": zp, "f'": fp, "tan(theta')": tan_tp}


def image_beam_width() -> sp.Expr:
    """Width of one image pixel's beam at eye depth z (Lloyd 2006 eq. 2, corrected).

    The image's res_i pixels span the frustum's full width 2·z·tanθ at depth z.
    """
    return 2 * z * sp.tan(theta) / res_i


@derivation("lloyd2006.shadow_map_coordinates", f"{SOURCE}, eqs. 5-6", "s(x, z') and t(z') of the warping frustum mapped to [0, 1]")
def shadow_map_coordinates() -> sp.Matrix:
    """s(x, z′) and t(z′) of the warping frustum, normalised to [0, 1] (eqs. 5–6).

    s is linear in x/z′ and maps the frustum's side planes x = ±z′tanθ′ to 0 and 1;
    t is the projective depth α + β/z′ of an OpenGL frustum matrix, mapping the warping
    near plane z′ = n′ to 0 and the far plane z′ = f′ to 1.
    """
    wf = warping_frustum()
    fp, tan_tp = wf["f'"], wf["tan(theta')"]
    A, B, alpha, beta = sp.symbols("A B alpha beta")
    s_gen = A * x / z_p + B
    sol_s = linear_solve([s_gen.subs(x, -z_p * tan_tp), s_gen.subs(x, z_p * tan_tp) - 1], [A, B])
    t_gen = alpha + beta / z_p
    sol_t = linear_solve([t_gen.subs(z_p, n_p), t_gen.subs(z_p, fp) - 1], [alpha, beta])
    # both are rational in their symbols: one common denominator is the whole simplification
    return sp.Matrix([sp.together(s_gen.subs(sol_s)), sp.together(t_gen.subs(sol_t))])


def light_beam_widths() -> tuple[sp.Expr, sp.Expr]:
    """w_lx = (1/res_s)·dx/ds and w_lz = (1/res_t)·dz/dt at eye depth z (eqs. 3–4)."""
    s_map, t_map = shadow_map_coordinates()
    zp = warping_frustum()["z'"]
    ds_dx = sp.diff(s_map, x).subs(z_p, zp)
    dt_dz = sp.diff(t_map.subs(z_p, zp), z)
    return sp.factor(1 / (res_s * ds_dx)), sp.factor(1 / (res_t * dt_dz))  # rational: factor suffices


def _m_xz() -> tuple[sp.Expr, sp.Expr]:
    """m_x and m_z from one derivation of the beam widths (see :func:`m_x`, :func:`m_z`)."""
    w_lx, w_lz = light_beam_widths()
    w_i = image_beam_width()
    return sp.factor(w_lx / w_i), sp.factor(w_lz / w_i)


@derivation("lloyd2006.m_x", f"{SOURCE}, eq. 7", "perspective aliasing error in x, overhead light")
def m_x() -> sp.Expr:
    """m_x(z, n′) = w_lx / w_i (Lloyd 2006 eq. 7)."""
    return _m_xz()[0]


@derivation("lloyd2006.m_z", f"{SOURCE}, eq. 8", "perspective aliasing error in z, overhead light")
def m_z() -> sp.Expr:
    """m_z(z, n′) = w_lz / w_i (Lloyd 2006 eq. 8)."""
    return _m_xz()[1]


@derivation("lloyd2006.m_z_minimum", f"{SOURCE}, §4.1 (text after eq. 8)", "the only stationary point of m_z over z > 0, a minimum")
def m_z_minimum() -> sp.Expr:
    """Location of the single stationary point of m_z in z > 0: z = n′ − n.

    m_z ∝ (z + n′ − n)²/z is convex in z > 0, so this is a minimum and the maxima over
    [n, f] lie at the end points (the text after eq. 8).
    """
    mz = m_z()
    # the roots are z = ±(n′ − n); keep the positive one and check convexity there
    (zs,) = [r for r in polynomial_roots(sp.diff(mz, z), z) if _on_domain(r).is_positive]
    assert _on_domain(sp.diff(mz, z, 2)).is_positive
    return zs


@derivation("lloyd2006.n_prime_lispsm", f"{SOURCE}, §4.1; Wimmer 2004 §4.3", "n' equating the near- and far-plane maxima of m_z")
def n_prime_lispsm() -> sp.Expr:
    """n′ with m_z(n) = m_z(f): the equal-maxima (L∞-optimal) warp, n + √(fn)."""
    return _n_prime_lispsm(m_z())


def _n_prime_lispsm(mz: sp.Expr) -> sp.Expr:
    """The root n′ ≥ n of m_z(n) = m_z(f), from ``mz`` = m_z(z, n′).

    The difference's numerator is a quadratic in n′ (its denominator is positive), so the
    equation is solved on that polynomial directly.
    """
    roots = polynomial_roots(mz.subs(z, n) - mz.subs(z, f), n_p)
    (root,) = [r for r in roots if _on_domain(r - n).is_positive]  # n′ ≥ n by definition
    return root


def _cancel_roots(expr: sp.Expr) -> sp.Expr:
    """``cancel`` for a rational function of √f, √n (and other symbols).

    With f = F², n = N² the expression is rational in F and N, so ``cancel`` finds the
    common factors (such as √f − √n) that it cannot see through the square roots.
    """
    F, N = sp.symbols("F N", positive=True)
    return sp.cancel(expr.subs({f: F**2, n: N**2})).subs({F: sp.sqrt(f), N: sp.sqrt(n)})


@derivation("lloyd2006.M_x", f"{SOURCE}, eq. 9", "maximum of m_x over z in [n, f]")
def max_error_x() -> sp.Expr:
    """M_x: m_x decreases in z for n′ ≥ n (dm_x/dz ∝ −(n′ − n)), so its maximum is at z = n."""
    return _max_error_x(m_x())


def _max_error_x(mx: sp.Expr) -> sp.Expr:
    """M_x from ``mx`` = m_x(z, n′)."""
    assert _on_domain(sp.diff(mx, z)).is_negative
    return sp.factor(mx.subs(z, n))


@derivation("lloyd2006.M_z", f"{SOURCE}, eq. 10", "maximum of m_z over z in [n, f], piecewise in n'")
def max_error_z() -> sp.Piecewise:
    """M_z: the larger end value; the far plane for n′ ≤ n′_LiSPSM, the near plane above."""
    return _max_error_z(m_z())


def _max_error_z(mz: sp.Expr) -> sp.Piecewise:
    """M_z from ``mz`` = m_z(z, n′)."""
    return sp.Piecewise(
        (sp.factor(mz.subs(z, f)), n_p <= _n_prime_lispsm(mz)),
        (sp.factor(mz.subs(z, n)), True),
    )


def _mz_max(value: sp.Expr, mz: sp.Expr, n_l: sp.Expr) -> sp.Expr:
    """M_z at the warping parameter ``value`` (∞ allowed), from ``mz`` = m_z and ``n_l`` = n′_LiSPSM."""
    if value is sp.oo:
        return sp.limit(mz.subs(z, n), n_p, sp.oo)
    near_branch = mz.subs(z, n).subs(n_p, value)
    far_branch = mz.subs(z, f).subs(n_p, value)
    return far_branch if value in (n, n_l) else sp.Piecewise((far_branch, value <= n_l), (near_branch, True))


@derivation("lloyd2006.eta_of_n_prime", f"{SOURCE}, Appendix B", "eta linearly interpolating M_z between n'=inf, n'_LiSPSM and n'=n")
def eta_of_n_prime() -> sp.Piecewise:
    """η(n′) from its definition in Appendix B: M_z interpolated linearly.

    η = −1 at n′ = ∞ (M_z maximal at the near plane), 0 at n′_LiSPSM (M_z minimal), and
    1 at n′ = n (M_z maximal at the far plane).
    """
    mz = m_z().subs({res_i: 1, res_t: 1})
    n_l = _n_prime_lispsm(mz)
    m_near, m_far = mz.subs(z, n), mz.subs(z, f)
    m_l, m_inf, m_psm = (_mz_max(v, mz, n_l) for v in (n_l, sp.oo, n))
    return sp.Piecewise(
        (sp.factor(_cancel_roots((m_l - m_near) / (m_inf - m_l))), n_p > n_l),
        (sp.factor(_cancel_roots((m_far - m_l) / (m_psm - m_l))), True),
    )


@derivation("lloyd2006.n_prime_of_eta", f"{SOURCE}, eq. 11", "the eta -> n' map, solved from Appendix B (a = f/n)")
def n_prime_of_eta() -> sp.Piecewise:
    """n′(η), Lloyd 2006 eq. 11, by solving each branch of Appendix B's η(n′) for n′."""
    upper, lower = eta_of_n_prime().args
    branches = []
    r = sp.Symbol("r", positive=True)  # a = r² keeps √a out of the algebra
    for expr, cond in (upper, (eta <= 0)), (lower, True):
        # each branch is a Möbius map of n′: its numerator minus η times its denominator is linear in n′
        num, den = sp.fraction(sp.together(expr[0].subs(f, a * n).subs(a, r**2)))
        root = linear_solve([num - eta * den], [n_p])[n_p]
        branches.append((sp.factor(sp.cancel(root)).subs(r, sp.sqrt(a)), cond))
    return sp.Piecewise(*branches)


@derivation("lloyd2006.storage_factor", f"{SOURCE}, eq. 12", "S = M_x M_z at unit resolutions")
def storage_factor() -> sp.Piecewise:
    """S̄ = M_x·M_z with res_i = res_s = res_t = 1 (Lloyd 2006 eq. 12)."""
    unit = {res_i: 1, res_s: 1, res_t: 1}
    mx, mz = _m_xz()
    m_x_max = _max_error_x(mx).subs(unit)
    # both maxima are rational in n, f, n′ and tanθ: factor finds the cancellations
    return sp.Piecewise(*[(sp.factor(m_x_max * e.subs(unit)), c) for e, c in _max_error_z(mz).args])


@derivation("lloyd2006.critical_resolutions", f"{SOURCE}, §4.2", "res_s*, res_t* at which M_x = M_z = 1")
def critical_resolutions() -> sp.Matrix:
    """Critical resolutions res*_s, res*_t: the resolutions with M_x = 1 and M_z = 1."""
    mx, mz = _m_xz()
    # each maximum is (a factor)/resolution: M = 1 is linear in the resolution once multiplied out
    (rs,) = polynomial_roots(_max_error_x(mx) - 1, res_s)
    return sp.Matrix([rs, sp.Piecewise(*[(polynomial_roots(e - 1, res_t)[0], c) for e, c in _max_error_z(mz).args])])


@derivation("lloyd2006.budget_resolutions", f"{SOURCE}, eqs. 13-14", "res_s, res_t for a texel budget S0 keeping res_s/res_t = res_s*/res_t*")
def budget_resolutions() -> sp.Matrix:
    """Split a budget S0: res_s·res_t = S0 and res_s/res_t = res*_s/res*_t (eqs. 13–14)."""
    rs_c, rt_c = sp.symbols("res_s^* res_t^*", positive=True)
    # the ratio condition is linear in res_s: res_s = res_t res*_s/res*_t; then res_t² = S0 res*_t/res*_s
    rs_of_rt = linear_solve([res_s * rt_c - res_t * rs_c], [res_s])[res_s]
    (rt,) = [r for r in polynomial_roots(rs_of_rt * res_t - S0, res_t) if r.is_positive is not False]
    return sp.Matrix([rs_of_rt.subs(res_t, rt), rt])


@derivation("lloyd2006.log_parameterization", f"{SOURCE}, Appendix C", "t(z) with dz/dt proportional to z, normalised to [0, 1]")
def log_parameterization() -> sp.Expr:
    """t(z) = ∫_n^z dζ/ζ normalised to [0, 1]: the logarithmic map (Appendix C)."""
    zeta = sp.Symbol("zeta", positive=True)
    t_tilde = sp.integrate(1 / zeta, (zeta, n, z))  # log(z) − log(n)
    combine = lambda q: sp.logcombine(sp.expand_log(q, force=True), force=True)  # noqa: E731
    return combine(t_tilde) / combine(t_tilde.subs(z, f))


@derivation("lloyd2006.storage_factor_optimal", f"{SOURCE}, Appendix C", "S of the logarithmic parameterization")
def storage_factor_optimal() -> sp.Expr:
    """S̄_optimal of the logarithmic map: m_x with n′ = n (PSM in x) times m_z of t = ln(z/n)/ln(f/n)."""
    t_log = log_parameterization()
    w_lz = 1 / (res_t * sp.diff(t_log, z))
    mz = sp.factor(w_lz / image_beam_width())
    mx = m_x().subs(n_p, n)
    return sp.factor(sp.expand_log((mx * mz).subs({res_i: 1, res_s: 1, res_t: 1}), force=True))


@derivation("lloyd2006.projective_spacing", f"{SOURCE}, Appendix A", "dz/dt of a general projective t(z)")
def projective_spacing() -> sp.Expr:
    """dz/dt of t = (αz + β)/(γz + δ): proportional to (z + δ/γ)² (Appendix A)."""
    al, be, ga, de = sp.symbols("alpha beta gamma delta")
    t = (al * z + be) / (ga * z + de)
    return sp.factor(1 / sp.diff(t, z))


def _printed() -> dict[str, Printed]:
    """The printed equations, read from the text extraction (see docs/ERRATA.md)."""
    tan = sp.tan(theta)
    fp = n_p + f - n
    n_l = n + sp.sqrt(f * n)
    tan_tp_printed = (fp / f) * tan
    return {
        "eq2": Printed("eq. (2)", 2 * tan / res_i * z / n, "w_i(z) = (2 tanθ / res_i)(z / n)"),
        "eq5": Printed("eq. (5)", x / (z_p * tan_tp_printed) + sp.Rational(1, 2), "s = x/(z′ tanθ′) + 1/2 with tanθ′ = (f′/f) tanθ"),
        "eq6": Printed("eq. (6)", (fp + n_p) / (2 * (fp - n_p)) + fp * n_p / (z_p * (fp - n_p)) + sp.Rational(1, 2), "t = (f′+n′)/(2(f′−n′)) + f′n′/(z′(f′−n′)) + 1/2"),
        "eq7": Printed("eq. (7)", res_i / res_s * f * (n_p + z - n) / (z * fp), ""),
        "eq8": Printed("eq. (8)", res_i / res_t * (f - n) / (2 * tan) * (n_p + z - n) ** 2 / (z * n_p * fp), ""),
        "eq9": Printed("eq. (9)", res_i / res_s * f * n_p / fp, "M_x = (res_i/res_s) f n′/(n′ + f − n)"),
        "eq10": Printed(
            "eq. (10)",
            sp.Piecewise(
                (res_i / res_t * n * (f - n) / (2 * tan) * fp / (n_p * f), n_p <= n_l),
                (res_i / res_t * n * (f - n) / (2 * tan) * n_p / (n * fp), True),
            ),
            "M_z = (res_i/res_t) n (f−n)/(2 tanθ) · {(n′+f−n)/(n′f) ; n′/(n(n′+f−n))}",
        ),
        "n_lispsm": Printed("§4.1", n + sp.sqrt(f * n), "n′_LSPSM = n + √(fn)"),
        "eq11": Printed(
            "eq. (11)",
            sp.Piecewise(
                (n * (sp.sqrt(a) + 1 - eta * (a - 1)) / (eta + 1), eta <= 0),
                (n * (sp.sqrt(a) + 1) / (eta * sp.sqrt(a) + 1), True),
            ),
            "",
        ),
        "eq12": Printed(
            "eq. (12)",
            sp.Piecewise(
                ((f / n - 1) / (2 * tan), n_p <= n_l),
                ((f / n - 1) / (2 * tan) * n_p**2 * f / (n * fp**2), True),
            ),
            "",
        ),
        "eq13": Printed("eqs. (13)-(14)", sp.Matrix(sp.symbols("res_s^* res_t^*", positive=True)), "res_s = √(S0 res*_s/res*_t), res_t = √(S0 res*_t/res*_s)"),
        "appC_t": Printed("App. C", sp.log(z / n) / sp.log(f / n), "t = ln(z/n)/ln(f/n)"),
        "appC_S": Printed("App. C", sp.log(f / n) / (2 * tan), "S̄ = ln(f/n)/(2 tanθ)"),
        "appA": Printed("App. A", sp.Symbol("c_0"), "dz/dt ∝ (z + c0)², c0 a constant"),
    }


PRINTED = _printed()
# eqs. 13-14 in closed form, built from the placeholders above.
_rs_c, _rt_c = PRINTED["eq13"].expr
PRINTED["eq13"] = Printed("eqs. (13)-(14)", sp.Matrix([sp.sqrt(S0 * _rs_c / _rt_c), sp.sqrt(S0 * _rt_c / _rs_c)]), PRINTED["eq13"].reading)


# --- §5.3: storage factors of z-partitioned schemes (eqs. 17–20, App. C) ----------------

k = sp.Symbol("k", positive=True, integer=True)


def _partition_ratio() -> sp.Expr:
    """f_i/n_i of the self-similar partitions (eqs. 15–16), the same for every i: (f/n)^(1/k)."""
    i = sp.Symbol("i", positive=True, integer=True)
    n_i = n * (f / n) ** ((i - 1) / k)  # eq. (15)
    f_i = n * (f / n) ** (i / k)  # eq. (16)
    return sp.powsimp(sp.powdenest(sp.powsimp(f_i / n_i, force=True), force=True), force=True)


def _storage_per_partition(warped: bool) -> sp.Expr:
    """Eq. 12 on one partition: its minimal branch (warped) or its n′ → ∞ limit (uniform)."""
    (low, _), (high, _) = storage_factor().args
    r = _partition_ratio()
    expr = low if warped else sp.limit(high, n_p, sp.oo)
    return sp.factor(sp.powsimp(expr.subs(f, r * n), force=True))


@derivation("lloyd2006.S_zp_overhead", f"{SOURCE}, eq. 17", "S of k self-similar z-partitions, uniform maps, light overhead")
def storage_zp_overhead() -> sp.Expr:
    """k maps, each eq. 12 with n′ → ∞ on a partition of ratio (f/n)^(1/k)."""
    return sp.factor(k * _storage_per_partition(warped=False))


@derivation("lloyd2006.S_zp_w_overhead", f"{SOURCE}, eq. 18", "S of k self-similar z-partitions, warped (n' <= n'_LiSPSM), light overhead")
def storage_zp_w_overhead() -> sp.Expr:
    """k maps, each eq. 12's minimal branch: warping removes the factor (f/n)^(1/k)."""
    return sp.factor(k * _storage_per_partition(warped=True))


@derivation("lloyd2006.S_zp_behind", f"{SOURCE}, eq. 20", "S of k z-partitions with the light behind the viewer (no warping possible)")
def storage_zp_behind() -> sp.Expr:
    """Light behind: each partition is seen as the square of its far face.

    A critical map has the image's texel spacing at the partition's near plane, so in each
    direction it needs (far-face width)/(near-face width) = f_i/n_i times the image
    resolution: S_i = (f_i/n_i)², summed over the k maps.
    """
    width = lambda depth: 2 * depth * sp.tan(theta)  # noqa: E731  frustum width at a depth
    r = _partition_ratio()
    per_map = (width(r * n) / width(n)) ** 2
    return k * per_map  # the widths' common factors cancel on construction


@derivation("lloyd2006.S_fp_zp_w_behind", f"{SOURCE}, eq. 21", "FP+ZP+W with the light behind: four warped side faces plus the near face")
def storage_fp_zp_w_behind() -> sp.Expr:
    """Light behind: each side face, seen from behind, is the overhead case at θ = 45°.

    Seen along the view direction, a side face projects to the trapezoid |x| ≤ y between
    y = n tanθ and y = f tanθ (its half-width equals its distance from the axis: 45° sides,
    whatever θ), and a pixel at eye depth d = y/tanθ is 2d tanθ/res_i = 2y/res_i wide.  That
    is exactly the whole frustum seen from overhead with θ = 45° (|x| ≤ z, pixel 2z/res_i),
    so for any θ each of the four faces costs S̄_ZP+W,overhead(θ = 45°), and the near face,
    seen head-on with the image's own spacing, costs 1: eq. 21's "θ = 45°" is not a
    restriction on the view.  (The check against a general face-partition evaluation comes
    with face partitioning.)
    """
    return sp.factor(4 * storage_zp_w_overhead().subs(theta, sp.pi / 4) + 1)


def _printed_53() -> dict[str, Printed]:
    a = f / n
    tan = sp.tan(theta)
    return {
        "eq17": Printed("eq. (17)", k * a ** (1 / k) * (a ** (1 / k) - 1) / (2 * tan), ""),
        "eq18": Printed("eq. (18)", k * (a ** (1 / k) - 1) / (2 * tan), ""),
        "eq20": Printed("eq. (20)", k * a ** (2 / k), "k (f/n)^(2/k) with k ≥ 1"),
        "eq21": Printed("eq. (21)", 4 * (k * (a ** (1 / k) - 1) / (2 * tan)).subs(theta, sp.pi / 4) + 1, "4 S̄_ZP+W,overhead + 1 with θ = 45°"),
    }


PRINTED.update(_printed_53())
