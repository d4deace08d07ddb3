"""Shared fixtures: parameter grids for numeric-vs-symbolic checks; progress callbacks that interrupt a run."""

from __future__ import annotations

import numpy as np
import pytest


@pytest.fixture(scope="session")
def grid():
    """Broadcastable grid over near, f/n, a position in [near, far], n′ offsets and fov.

    Axes: near (3) × f/n (4, including f/n → 1) × relative depth (5) × n′ choice (5) × fov (4).
    """
    near = np.array([0.1, 1.0, 3.0]).reshape(-1, 1, 1, 1, 1)
    ratio = np.array([1.0 + 1e-6, 1.5, 10.0, 1000.0]).reshape(1, -1, 1, 1, 1)
    far = near * ratio
    u = np.linspace(0.0, 1.0, 5).reshape(1, 1, -1, 1, 1)
    z = near + u * (far - near)
    n_l = near + np.sqrt(far * near)
    # n′ = n (PSM), between, n′_LiSPSM, above, far above
    choices = np.array([0.0, 0.5, 1.0, 3.0, 1e3]).reshape(1, 1, 1, -1, 1)
    n_prime = np.where(choices <= 1.0, near + choices * (n_l - near), n_l * choices)
    fov = np.array([10.0, 60.0, 120.0, 170.0]).reshape(1, 1, 1, 1, -1)
    return {"near": near, "far": far, "z": z, "n_prime": n_prime, "fov": fov}


def exact(expr, *symbols):
    """Evaluate a sympy expression elementwise in 40-digit arithmetic (mpmath), as floats.

    The reference for numeric-vs-symbolic checks: lambdified float64 forms of the raw
    sympy output can cancel catastrophically (f/n → 1), which would test round-off in the
    reference rather than the package.
    """
    import mpmath
    import sympy as sp

    func = sp.lambdify(symbols, expr, modules="mpmath")

    def evaluate(*args):
        with mpmath.workdps(40):
            return np.vectorize(lambda *a: float(func(*[mpmath.mpf(float(v)) for v in a])), otypes=[float])(*args)

    return evaluate


def assert_close(actual, desired, rtol=1e-12, atol=0.0):
    """assert_allclose after broadcasting both sides to a common shape."""
    a, d = np.broadcast_arrays(np.asarray(actual, float), np.asarray(desired, float))
    np.testing.assert_allclose(a, d, rtol=rtol, atol=atol)


class Stop(Exception):
    """Raised by :func:`stop_after`'s progress callback."""


def stop_after(n):
    """A ``progress(done, total)`` callback that stops a run (raises Stop) once ``n`` chunks are done."""

    def progress(done, total):
        if done >= n:
            raise Stop

    return progress


def interrupt_after(n):
    """A stand-in for ``aliasing.sweep.progress_bar`` whose bar is Ctrl-C after ``n`` chunks."""

    def progress_bar(stream):
        def progress(done, total):
            if done == n:
                raise KeyboardInterrupt

        return progress

    return progress_bar


# Hypothesis profiles (the API fuzz suite, tests/test_fuzz_api.py): "ci" is the default,
# derandomized so a run is reproducible; "long" runs many more cases locally
# (ALIASING_HYPOTHESIS=long, or pytest --hypothesis-profile=long).  Registered only if no
# other conftest registered the same names first with at least as many examples.
try:
    import os as _os

    from hypothesis import settings as _hsettings
except ImportError:  # the test extra is not installed: the fuzz suite skips itself
    _hsettings = None
if _hsettings is not None:
    for _name, _kwargs in {
        "ci": dict(max_examples=2400, derandomize=True, deadline=None, print_blob=True),
        "long": dict(max_examples=50_000, derandomize=False, deadline=None, print_blob=True),
    }.items():
        try:  # Hypothesis ships a "ci" profile of 100 examples; keep a registered one only if it runs more
            _keep = _hsettings.get_profile(_name).max_examples >= _kwargs["max_examples"]
        except Exception:  # not registered yet
            _keep = False
        if not _keep:
            _hsettings.register_profile(_name, **_kwargs)
    _hsettings.load_profile(_os.environ.get("ALIASING_HYPOTHESIS", "ci"))
