"""Symbolic (sympy) derivations: the source of truth for every closed form.

One module per paper.  Each module exposes

* derivation functions that build a result from the paper's definitions (never by
  restating the printed formula), and
* ``PRINTED``: the paper's printed equations, transcribed from the text (our reading of
  the extraction, with notes), so that tests and ``aliasing derive --printed`` can
  compare the two.

The registry :data:`DERIVATIONS` names every derivation for the CLI
(``aliasing derive lloyd2006.m_z --latex``).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import sympy as sp

from .. import _validation as check


@dataclass(frozen=True)
class Derivation:
    """A registered symbolic result."""

    name: str
    func: Callable[[], sp.Basic]
    source: str
    summary: str


DERIVATIONS: dict[str, Derivation] = {}


@dataclass(frozen=True)
class Printed:
    """A paper's equation as printed (our reading of the text extraction)."""

    label: str
    expr: sp.Basic
    reading: str = ""


def derivation(name: str, source: str, summary: str) -> Callable:
    """Decorator registering a zero-argument derivation under ``name``."""

    def wrap(func: Callable[[], sp.Basic]) -> Callable[[], sp.Basic]:
        if name in DERIVATIONS:
            raise RuntimeError(f"derivation {name!r} registered twice")
        DERIVATIONS[name] = Derivation(name, func, source, summary)
        return func

    return wrap


def equivalent(a: sp.Basic, b: sp.Basic) -> bool:
    """True when two expressions (or two Piecewise with matching branches) are equal.

    Piecewise results are compared branch by branch, expressions and conditions, since
    sympy cannot always simplify the difference of two Piecewise objects to zero.
    """
    if isinstance(a, sp.Piecewise) or isinstance(b, sp.Piecewise):
        if not (isinstance(a, sp.Piecewise) and isinstance(b, sp.Piecewise)) or len(a.args) != len(b.args):
            return False
        return all(
            equivalent(ea, eb) and (ca == cb or sp.simplify(sp.Equivalent(ca, cb)) is sp.true)
            for (ea, ca), (eb, cb) in zip(a.args, b.args)
        )
    return sp.simplify(sp.expand_log(sp.sympify(a) - sp.sympify(b), force=True)) == 0


def get(name: str) -> Derivation:
    """Look up a derivation; ``ValueError`` lists the valid names."""
    _load()
    if name not in DERIVATIONS:
        raise ValueError(f"unknown derivation {name!r}{check.did_you_mean(name, sorted(DERIVATIONS))}; choose from: {', '.join(sorted(DERIVATIONS))}")
    return DERIVATIONS[name]


def _load() -> None:
    """Import the paper modules so that their derivations register."""
    from . import lloyd2006, lloyd2007, lloyd2007_matrix, wimmer2004, zhang2007  # noqa: F401
    from . import engines  # noqa: F401  (today's engine schemes)
