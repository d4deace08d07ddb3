"""Targeted rewrites that the derivations use instead of a general ``simplify``, and how a
result is shown.

:func:`linear_solve` and :func:`polynomial_roots` find what :func:`sympy.solve` would, without
its general search; :func:`display` prints a result, naming the common subexpressions of a very
large one (the 3D aliasing matrices).
"""

from __future__ import annotations

import sympy as sp


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
