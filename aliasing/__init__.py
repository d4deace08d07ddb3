"""aliasing: analytic study of shadow-map perspective aliasing.

Symbolic derivations (sympy) of the papers' error formulas, fast vectorized numpy
evaluation, and reproductions of the papers' figures.

Conventions (the one place they are written; every module follows them)
-------------------------------------------------------------------------
Angles
    Every angle in the public API and the CLI is in **degrees**.

    * ``fov`` is the **full** field of view of the (square) eye image, 0 < fov < 180.
      Lloyd et al. 2006/2007 and Wimmer et al. 2004 write θ for the *half* field of
      view, θ = fov/2; Zhang et al. 2007 write φ for the half field of view.
    * ``gamma`` (γ) is the angle between the view direction and the direction *towards*
      the light, 0 ≤ γ ≤ 180: γ = 90° is an overhead light (perpendicular to the view
      direction), γ = 0° has the viewer looking straight into the light, γ = 180° has
      the light directly behind the viewer.  This is Lloyd 2007's and Wimmer 2004's γ;
      Zhang et al. 2007 call the light–view angle θ.
Lengths
    ``near`` and ``far`` (the papers' n, f or z_n, z_f) are eye-space distances in
    world units, 0 < near < far.  ``n_prime`` (n′) is the distance from the warping
    frustum's centre of projection to the near plane: ``near`` is PSM, ``inf`` a uniform
    (orthographic) map.
Resolutions
    Pixels or texels per side; error metrics default to unit resolutions, where the
    storage factor S̄ = M_x·M_z is the critical shadow-map area in image areas.

Each paper module's docstring maps that paper's symbols to these names.

Example
-------
>>> import aliasing
>>> float(aliasing.storage_factor(near=1, far=100, fov=90, n_prime=aliasing.n_prime_lispsm(1, 100)))
49.5
"""

from .error import (
    critical_resolution,
    dp_ds,
    m_x,
    m_z,
    max_error_x,
    max_error_z,
    resolution_for_budget,
    storage_factor,
    storage_factor_optimal,
)
from ._version import __version__
from .view import View
from .warping import WARPING_RULES, eta_from_n_prime, n_prime_from_eta, n_prime_lispsm, warping_parameter

from . import gmnpr  # noqa: E402,F401  (registers the gmnpr, glpr and lispsm-zhang warping rules)
from . import adaptive_warping  # noqa: E402,F401  (registers the pyramid warping rules)
from . import sweep  # noqa: E402,F401  (a callable module: aliasing.sweep(...) runs a sweep grid into a table)


__all__ = [
    "View",
    "WARPING_RULES",
    "critical_resolution",
    "dp_ds",
    "eta_from_n_prime",
    "m_x",
    "m_z",
    "max_error_x",
    "max_error_z",
    "n_prime_from_eta",
    "n_prime_lispsm",
    "resolution_for_budget",
    "storage_factor",
    "storage_factor_optimal",
    "warping_parameter",
]
