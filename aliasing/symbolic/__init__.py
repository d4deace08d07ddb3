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


def linear_solve(equations: list[sp.Expr], unknowns: list[sp.Symbol]) -> dict[sp.Symbol, sp.Expr]:
    """Solve equations (expressions equal to zero) that are linear in ``unknowns``.

    Gaussian elimination on the coefficient matrix, each solution put over one common
    denominator: what :func:`sympy.solve` would find, without its general search.
    ``linear_eq_to_matrix`` refuses an equation that is not linear in the unknowns.

    Example
    -------
    >>> import sympy as sp
    >>> a, b, x = sp.symbols("a b x")
    >>> linear_solve([a * x - b], [x])
    {x: b/a}
    """
    matrix, rhs = sp.linear_eq_to_matrix(equations, unknowns)
    return {u: sp.cancel(value) for u, value in zip(unknowns, matrix.LUsolve(rhs))}


def polynomial_roots(expr: sp.Expr, var: sp.Symbol) -> list[sp.Expr]:
    """The roots in ``var`` of the numerator of ``expr`` (with multiplicity).

    For an expression that is rational in ``var`` and whose denominator does not vanish
    where it is used: its zeros are those of the numerator polynomial, found in closed form
    by :func:`sympy.roots` (asserted: every root of the polynomial).

    Example
    -------
    >>> import sympy as sp
    >>> x, c = sp.symbols("x c", positive=True)
    >>> sorted(polynomial_roots((x**2 - c) / x, x), key=str)
    [-sqrt(c), sqrt(c)]
    """
    poly = sp.Poly(sp.numer(sp.together(expr)), var)
    roots = sp.roots(poly, multiple=True)
    assert len(roots) == poly.degree(), f"not every root of {poly} in closed form"
    return roots


LARGE = 5000
"""Expression-tree nodes above which :func:`display` names the common subexpressions."""


def _larger_than(expr: sp.Basic, limit: int) -> bool:
    """True when ``expr`` has more than ``limit`` tree nodes (stops counting there)."""
    for count, _ in enumerate(sp.preorder_traversal(expr)):
        if count >= limit:
            return True
    return False


def display(expr: sp.Basic, latex: bool = False) -> str:
    """A derivation's result as text: sympy's ``sstr`` (or LaTeX) of it.

    A result of more than :data:`LARGE` tree nodes (the 3D aliasing matrices: a few
    hundred thousand characters written out) is shown with its common subexpressions
    named: the result in terms of ``w1, w2, ...``, then ``where`` and one line per name,
    each in terms of the earlier ones.  Substituting them back gives the same expression.

    Example
    -------
    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> display(x**2 + 1)
    'x**2 + 1'
    >>> display(x**2 + 1, latex=True)
    'x^{2} + 1'
    """
    show = sp.latex if latex else sp.sstr
    if not _larger_than(expr, LARGE):
        return show(expr)
    taken = {str(sym) for sym in expr.free_symbols}
    names = (w for w in sp.numbered_symbols("w", start=1) if str(w) not in taken)
    defs, (reduced,) = sp.cse(expr, symbols=names, order="none")  # no canonical sort: 3x faster
    lines = [show(reduced), "where"]
    lines += [f"  {show(name)} = {show(value)}" for name, value in defs]
    return "\n".join(lines)


def get(name: str) -> Derivation:
    """Look up a derivation; ``ValueError`` lists the valid names."""
    _load()
    if name not in DERIVATIONS:
        raise ValueError(f"unknown derivation {name!r}; choose from: {', '.join(sorted(DERIVATIONS))}")
    return DERIVATIONS[name]


def _load() -> None:
    """Import the paper modules so that their derivations register."""
    from . import lloyd2006, lloyd2007, lloyd2007_matrix, wimmer2004, zhang2007  # noqa: F401
    from . import engines  # noqa: F401  (issue 18)
