"""Non-square views: what changes in Lloyd et al. 2006's overhead closed forms when θ_x ≠ θ_y.

Lloyd, Tuft, Yoon, Manocha 2006 (*Warping and Partitioning for Low Error Shadow Maps*)
assume a square view frustum: one half angle θ both for the frustum's half-width z·tanθ,
which the shadow map must cover (the warping frustum's fit in x, §4.1, Fig. 3), and for the
image's beam width w_i = 2z·tanθ/res_i (eq. 2).  An engine camera has a vertical field of
view 2θ_y and an aspect ratio A = tanθ_x/tanθ_y (width/height).  With square pixels the
image has res_i rows and A·res_i columns, so a pixel's beam is 2z·tanθ_y/res_i in both
directions, while the frustum's half-width in x is z·tanθ_x.

Derived here from :mod:`.lloyd2006`'s definitions (overhead light, light plane spanned by
the eye's x and z axes):

* the warping frustum is fitted to the half-width z·tanθ_x, so the light beam width in x
  (eq. 3) is Lloyd's with θ → θ_x, and in z (eq. 4) it does not involve θ at all;
* the image beam (eq. 2) keeps θ_y.

Hence m_x (eq. 7) gains the factor A and m_z (eq. 8) is unchanged; their maxima at the
frustum's ends (eqs. 9–10), S̄ = M_x·M_z and every n′ that equates m_z at the near and far
planes (eq. 11's LiSPSM parameter) follow: M_x·A, M_z, S̄·A.  For other light directions no
closed form is derived: the general evaluation (:func:`aliasing.schemes.evaluate` on a
:class:`aliasing.View` with ``aspect``) fits the map to the non-square frustum's vertices
and takes over; it is tested against these forms for the overhead light and against an
independent fit of hand-written corners for every direction.
"""

from __future__ import annotations

import sympy as sp

from . import lloyd2006 as base
from .registry import derivation

theta_x = sp.Symbol("theta_x", positive=True)
A = sp.Symbol("A", positive=True)  # aspect = tan θ_x / tan θ_y

SOURCE = "Lloyd et al. 2006, eqs. 2-4, 7-8, with theta_x != theta_y (this toolkit)"


def _beam_widths() -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """(w_lx, w_lz, w_i) of a non-square view; θ (``base.theta``) is the vertical θ_y."""
    w_lx, w_lz = base.light_beam_widths()
    assert not w_lz.has(base.theta)  # eq. 4: the depth mapping never sees the half angle
    return w_lx.subs(base.theta, theta_x), w_lz, base.image_beam_width()


@derivation("aspect.m_x", SOURCE, "m_x(z, n') of a view with half angles theta_x (width) and theta (height), overhead light")
def m_x() -> sp.Expr:
    """m_x = w_lx(θ_x) / w_i(θ_y) (Lloyd 2006 eq. 7 with the frustum's width from θ_x)."""
    w_lx, _, w_i = _beam_widths()
    return sp.factor(sp.simplify(w_lx / w_i))


@derivation("aspect.m_z", SOURCE, "m_z(z, n') of a view with half angles theta_x (width) and theta (height), overhead light")
def m_z() -> sp.Expr:
    """m_z = w_lz / w_i(θ_y) (Lloyd 2006 eq. 8: unchanged by the width)."""
    _, w_lz, w_i = _beam_widths()
    return sp.factor(sp.simplify(w_lz / w_i))


@derivation("aspect.ratios", SOURCE, "m_x and m_z of a non-square view over the square view's of the same vertical angle: (A, 1)")
def ratios() -> sp.Matrix:
    """(m_x/m_x^square, m_z/m_z^square) at every depth, with tanθ_x = A·tanθ_y: (A, 1).

    So M_x → A·M_x, M_z → M_z and S̄ = M_x·M_z → A·S̄ (eqs. 9–10 and the storage factor).
    """
    rx = (m_x() / base.m_x()).subs(sp.tan(theta_x), A * sp.tan(base.theta))
    rz = m_z() / base.m_z()
    return sp.Matrix([sp.simplify(rx), sp.simplify(rz)])
