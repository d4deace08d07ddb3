"""Symbolic (sympy) derivations: the source of truth for every closed form.

One module per paper.  Each module exposes

* derivation functions that build a result from the paper's definitions (never by
  restating the printed formula), and
* ``PRINTED``: the paper's printed equations, transcribed from the text (our reading of
  the extraction, with notes), so that tests and ``aliasing derive --printed`` can
  compare the two.

The registry :data:`DERIVATIONS` (:mod:`.registry`) names every derivation for the CLI
(``aliasing derive lloyd2006.m_z --latex``).
"""

from __future__ import annotations

from .. import _validation as check
from .registry import DERIVATIONS, Derivation, Printed, derivation, equivalent
from .rewrite import display, linear_solve, polynomial_roots

__all__ = ["DERIVATIONS", "Derivation", "Printed", "derivation", "display", "equivalent", "get", "linear_solve", "polynomial_roots"]


def get(name: str) -> Derivation:
    """Look up a derivation; ``ValueError`` lists the valid names."""
    _load()
    if name not in DERIVATIONS:
        raise ValueError(f"unknown derivation {name!r}{check.did_you_mean(name, sorted(DERIVATIONS))}; choose from: {', '.join(sorted(DERIVATIONS))}")
    return DERIVATIONS[name]


def _load() -> None:
    """Import the paper modules so that their derivations register."""
    from . import lloyd2006, lloyd2007, lloyd2007_jacobians, lloyd2007_matrix, wimmer2004, zhang2007  # noqa: F401
    from . import aspect, bias, engines  # noqa: F401
