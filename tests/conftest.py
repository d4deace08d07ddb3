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


# Hypothesis profiles (the sweep CLI fuzz test; another suite may register the same names):
# "ci" (default) is deterministic; ALIASING_HYPOTHESIS=long runs many more examples locally.
try:
    from hypothesis import settings as _hyp_settings
except ImportError:  # the test extra is not installed: the fuzz tests skip themselves
    _hyp_settings = None
if _hyp_settings is not None:
    import os as _os

    if "ci" not in _hyp_settings._profiles:
        _hyp_settings.register_profile("ci", derandomize=True, deadline=None)
    if "long" not in _hyp_settings._profiles:
        _hyp_settings.register_profile("long", max_examples=20_000, deadline=None)
    _hyp_settings.load_profile("long" if _os.environ.get("ALIASING_HYPOTHESIS") == "long" else "ci")
