"""The drawing backends: one table of who can draw, and the one check of a ``backend=`` keyword.

The numpy kernels are the reference: every map and eye buffer of the toolkit is defined by
them (the conventions of :mod:`aliasing.raster.draw.core`: texel centres at (i + ½)/R, row 0
at the bottom, left and bottom edges own the centres on them, the nearest depth kept, ties
to the highest triangle index).  Another backend stands beside them by adding an entry here
and a kernel where the drawing function dispatches; it must reproduce the reference's
buffers: ``numba`` bit for bit, ``gl`` (OpenGL through moderngl, :mod:`.gl`) up to the
hardware's sub-texel vertex snapping at triangle edges.

Example
-------
>>> check("numpy", "eye_pass")
'numpy'
>>> check("cuda", "eye_pass")
Traceback (most recent call last):
...
ValueError: backend must be one of ['gl', 'numba', 'numpy'] for eye_pass, got 'cuda'
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from . import compiled, gl


@dataclass(frozen=True)
class Backend:
    """A drawing backend: its ``name``, what it is, and whether it can run here."""

    name: str
    summary: str
    available: Callable[[], bool]
    require: Callable[[], None]


def _always() -> bool:
    return True


def _nothing() -> None:
    return None


#: Backends by name.  ``numpy`` is the default and the reference.
BACKENDS: dict[str, Backend] = {
    "numpy": Backend("numpy", "the reference: vectorized numpy kernels", _always, _nothing),
    "numba": Backend("numba", "compiled loops of the eye pass (the fast extra), bit-identical to numpy", compiled.available, compiled.require),
    "gl": Backend("gl", "OpenGL through moderngl and headless EGL (the gl extra): a GPU, or Mesa's llvmpipe on the CPU", gl.available, gl.require),
}

#: Which backends each drawing operation has.
SUPPORTED: dict[str, tuple[str, ...]] = {
    "eye_pass": ("numpy", "numba", "gl"),
    "shadow_map": ("numpy", "gl"),
}

#: What the command line offers (``--backend``): every backend of some operation.
NAMES: tuple[str, ...] = tuple(BACKENDS)


def pair(backend: object) -> tuple[str, str]:
    """(eye-pass backend, map backend) of a picture or a measurement drawn with ``backend``.

    The maps use ``backend`` where it draws maps, numpy otherwise (``numba`` compiles the eye
    pass only).  Raises ``ValueError`` naming ``backend`` as :func:`check` does.

    Example
    -------
    >>> pair("numba") if BACKENDS["numba"].available() else ("numba", "numpy")
    ('numba', 'numpy')
    """
    eye = check(backend, "eye_pass")
    return eye, eye if eye in SUPPORTED["shadow_map"] else "numpy"


def check(backend: object, operation: str) -> str:
    """``backend`` validated for ``operation``: a known name this operation supports, runnable here.

    Raises ``ValueError`` naming ``backend`` and the allowed names, or what to install.
    """
    names = SUPPORTED[operation]
    if not isinstance(backend, str) or backend not in names:
        raise ValueError(f"backend must be one of {sorted(names)} for {operation}, got {backend!r}")
    BACKENDS[backend].require()
    return backend
