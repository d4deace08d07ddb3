"""Interactive explorers for Jupyter: drag a parameter, watch the papers' quantities change.

Each explorer is a function returning a displayable ipywidgets container (an
:class:`~aliasing.explore._widget.Explorer`): controls, a message line and the figure.

* :func:`overhead`: m_x, m_z along z and M_x, M_z, S̄ over η (Lloyd et al. 2006 Figs. 5–6);
* :func:`directions`: S̄ over the hemisphere of light directions (Lloyd 2006 Fig. 7 style)
  and Lloyd et al. 2007 Table 3's statistics for any scheme of :mod:`aliasing.schemes`;
* :func:`cascades`: split methods and engine presets, texel budgets and allocations;
* :func:`faces`: the face partition (FP, FPc, FPcs; Lloyd 2007 §6.1.3, §6.5) for a light;
* :func:`raster`: the rasterizer's shadows, texel grid, per-pixel error and measured/bound.

The computation of every explorer is a plain function (``compute``, returning a dict) kept
apart from its drawing, so what is drawn can be checked against the API.  Needs the
``explore`` extra (``pip install 'aliasing[explore]'``: JupyterLab, ipywidgets ≥ 8, ipympl);
without it ``import aliasing`` works and calling an explorer says which extra to install.

Example
-------
>>> from aliasing import explore
>>> w = explore.overhead()                      # doctest: +SKIP
>>> w.set_state({"f_over_n": 1000.0, "rule": "lispsm"})  # doctest: +SKIP
"""

from __future__ import annotations

import importlib.util

EXTRA_MESSAGE = "aliasing.explore needs the 'explore' extra: pip install 'aliasing[explore]' (ipywidgets>=8, ipympl, jupyterlab)"

__all__ = ["EXTRA_MESSAGE", "available", "cascades", "directions", "faces", "overhead", "raster"]


def available() -> bool:
    """True when ipywidgets (the ``explore`` extra) can be imported."""
    try:
        import ipywidgets  # noqa: F401
    except ImportError:
        return False
    return True


def _module(name: str):
    if not available():
        raise ImportError(EXTRA_MESSAGE)
    return importlib.import_module(f"{__name__}.{name}")


def overhead(**values):
    """Overhead-light explorer (Lloyd et al. 2006 Figs. 5–6); see :mod:`aliasing.explore._overhead`."""
    return _module("_overhead").OverheadExplorer(**values)


def directions(**values):
    """Light-direction explorer (Lloyd 2006 Fig. 7, Lloyd 2007 Table 3); see :mod:`aliasing.explore._directions`."""
    return _module("_directions").DirectionsExplorer(**values)


def cascades(**values):
    """Cascade/split explorer (Lloyd 2007 eqs. 80–83, Zhang 2006, engine presets); see :mod:`aliasing.explore._cascades`."""
    return _module("_cascades").CascadesExplorer(**values)


def faces(**values):
    """Face-partition explorer (Lloyd 2007 §6.1.3, §6.5); see :mod:`aliasing.explore._faces`."""
    return _module("_faces").FacesExplorer(**values)


def raster(**values):
    """Rasterizer explorer (shadows, texel grid, per-pixel error); see :mod:`aliasing.explore._raster`."""
    return _module("_raster").RasterExplorer(**values)
