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


def sweep_cli(argv, capsys):
    """Run ``aliasing sweep ARGV``: (exit code, stdout, stderr)."""
    from aliasing.cli import main

    try:
        code = main(["sweep", *argv])
    except SystemExit as exc:
        code = exc.code
    out, err = capsys.readouterr()
    return code, out, err


def sweep_one_line_error(argv, capsys, needle):
    """``aliasing sweep ARGV`` must fail with exit code 2 and one line on stderr containing ``needle``."""
    code, out, err = sweep_cli(argv, capsys)
    assert code == 2 and len(err.strip().splitlines()) == 1 and needle in err, err
    return err


# Hypothesis profiles (issue 11 item 6, issue 19 item 5): "ci" is the default, derandomized
# so that a run is reproducible (each test sets its own example count); "long" runs many more
# cases locally (ALIASING_HYPOTHESIS=long, or pytest --hypothesis-profile=long).
try:
    import os as _os

    from hypothesis import settings as _hsettings
except ImportError:  # the test extra is not installed: the property tests skip themselves
    _hsettings = None
if _hsettings is not None:
    _hsettings.register_profile("ci", derandomize=True, deadline=None, print_blob=True)
    _hsettings.register_profile("long", max_examples=50_000, derandomize=False, deadline=None, print_blob=True)
    _hsettings.load_profile(_os.environ.get("ALIASING_HYPOTHESIS", "ci"))


def need(what: str, how: str) -> None:
    """A tool the engines' frames need is missing: fail under CI (``CI=true``), skip in one line elsewhere."""
    import os

    if os.environ.get("CI", "").lower() == "true":
        pytest.fail(f"{what} missing under CI: {how}")
    pytest.skip(f"{what} missing: the engines' frames are not rendered ({how})")


def need_frames(engine: str, title: str) -> None:
    """Playwright, the system Chromium, npm and ``engine``'s pinned package (installed from its lockfile), or :func:`need`."""
    import shutil

    from aliasing.frames import browser, install

    try:
        import playwright  # noqa: F401
    except ImportError:
        need("Playwright for Python", "pip install '.[frames]'")
    if browser.chromium_path() is None:
        need("Chromium", "Debian: apt-get install chromium")
    if shutil.which("npm") is None:
        need("npm", "Debian: apt-get install nodejs npm")
    try:
        install.install(engine)
    except install.MissingTool as e:
        need(f"the pinned {title} package", str(e))
