"""The registry of symbolic derivations and the paper's printed equations.

The paper modules register their derivations here (:func:`derivation`) and compare them
with what the papers printed (:class:`Printed`, :func:`equivalent`); the package
(:mod:`aliasing.symbolic`) loads them and looks them up by name.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import sympy as sp


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
