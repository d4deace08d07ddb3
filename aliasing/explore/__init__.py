"""Interactive explorers for Jupyter: drag a parameter, watch the papers' quantities change.

Each explorer is a function returning a displayable ipywidgets container (an
:class:`~aliasing.explore.widget.Explorer`): controls, a message line and the figure.

* :func:`overhead`: m_x, m_z along z and M_x, M_z, S̄ over η (Lloyd et al. 2006 Figs. 5–6);
* :func:`directions`: S̄ over the hemisphere of light directions (Lloyd 2006 Fig. 7 style)
  and Lloyd et al. 2007 Table 3's statistics for any scheme of :mod:`aliasing.schemes`;
* :func:`cascades`: split methods and engine presets, texel budgets and allocations;
* :func:`faces`: the face partition (FP, FPc, FPcs; Lloyd 2007 §6.1.3, §6.5) for a light;
* :func:`raster`: the rasterizer's shadows, texel grid, per-pixel error and measured/bound;
* :func:`bias`: an engine's depth bias per cascade against the derived minimum (acne, lit gap);
* :func:`shimmer`: a camera or sun path played over a still scene, the points whose shadow flips;
* :func:`tune`: an engine's tuned settings (:func:`aliasing.tune.tune`) as the camera and the limits move.

The computation of every explorer is a plain function (``compute``, returning a dict) kept
apart from its drawing, so what is drawn can be checked against the API.  Needs the
``explore`` extra (``pip install ".[explore]"``: JupyterLab, ipywidgets ≥ 8, ipympl);
without it ``import aliasing`` works and calling an explorer says which extra to install.

Example
-------
>>> from aliasing import explore
>>> w = explore.overhead()
>>> w.set_state({"f_over_n": 1000.0, "rule": "lispsm"}), round(w.data["S"], 1)
(True, 865.2)
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # the widget base needs ipywidgets (the explore extra)
    from .widget import Explorer

EXTRA_MESSAGE = "aliasing.explore needs the 'explore' extra: pip install \".[explore]\" (ipywidgets>=8, ipympl, jupyterlab)"

__all__ = ["EXTRA_MESSAGE", "available", "bias", "cascades", "directions", "faces", "overhead", "raster", "shimmer", "tune"]


def __getattr__(name: str) -> Any:
    if name == "Explorer":  # the widget base class, imported on first use (it needs ipywidgets)
        from .widget import Explorer

        return Explorer
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


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


def overhead(**values: Any) -> Explorer:
    """Overhead-light explorer: m_x, m_z along z and M_x, M_z, S̄ over η (Lloyd et al. 2006 Figs. 5–6).

    Parameters
    ----------
    **values
        Initial control values: ``f_over_n`` (log slider, 1.5–10⁵), ``fov`` [deg, vertical],
        ``aspect`` (width/height, log slider 0.25–4; ≠ 1: the general evaluation, Lloyd 2006's
        closed forms being square), ``rule`` (``uniform``, ``psm``, ``lispsm``, ``eta``,
        ``n_prime``), ``eta`` (−1…1), ``n_prime`` (text [world units] or ``inf``),
        ``res_image`` [pixels]; ``debounce`` [s].

    Returns
    -------
    Explorer
        An ipywidgets VBox; ``.data`` holds :func:`aliasing.explore._overhead.compute`'s result.

    Example
    -------
    >>> e = overhead(f_over_n=100.0, fov=90.0, rule="lispsm")
    >>> round(e.data["S"], 1), e.error
    (49.5, None)
    """
    return _module("_overhead").OverheadExplorer(**values)


def directions(**values: Any) -> Explorer:
    """Light-direction explorer: S̄ over the hemisphere (Lloyd 2006 Fig. 7) and Lloyd 2007 Table 3's statistics.

    Parameters
    ----------
    **values
        ``scheme`` (text, :data:`aliasing.schemes.GRAMMAR`), ``f_over_n``, ``fov`` [deg, vertical],
        ``aspect`` (width/height, 0.25–4), ``gamma``, ``azimuth`` [deg] (the chosen direction),
        ``resolution`` (map cells per side).

    Returns
    -------
    Explorer
        ``.pick(u, v)`` chooses the direction at a map position.

    Example
    -------
    >>> e = directions(scheme="LogP", gamma=90.0, azimuth=0.0, resolution=16)
    >>> round(e.data["S"], 3)
    5.982
    >>> e.set_state({"scheme": "nonsense"}), e.data["scheme"]   # the message is shown, the last picture kept
    (False, 'LogP')
    """
    return _module("_directions").DirectionsExplorer(**values)


def cascades(setup: Any = None, **values: Any) -> Explorer:
    """Cascade explorer: splits (Lloyd 2006 eqs. 15–16, Zhang 2006, engine presets), budgets, allocations (Lloyd 2007 eq. 83).

    Parameters
    ----------
    setup : aliasing.setups.Setup, optional
        An engine's setup (:func:`aliasing.setups.build`): its split, cascade count, shadow
        range, camera (near, vertical fov, aspect, rows) and texel budget (cascades × map
        size²) start the controls; ``values`` given beside it win.
    **values
        ``method`` (split method or engine preset), ``k``, ``lam`` (λ), ``near``, ``far``
        [world units], ``fov`` [deg, vertical], ``aspect`` (width/height, 0.25–4), ``warp``
        (text), ``budget`` [texels], ``allocation``, ``res_image`` [pixels, rows].

    Returns
    -------
    Explorer

    Example
    -------
    >>> e = cascades(method="log", k=4, warp="P", allocation="error")
    >>> e.data["far_i"].round(3).tolist()
    [5.623, 31.623, 177.828, 1000.0]
    >>> from aliasing import setups
    >>> s = setups.build("threejs", {"cascades": 4}, "near=0.1,far=500,fov=50,aspect=16:9,height=1080")
    >>> e = cascades(setup=s)
    >>> e.data["far_i"].round(6).tolist() == [round(f, 6) for f in s.pipeline.far_i], e.data["budget"]
    (True, 16777216)
    """
    if setup is not None:
        values = {**_setup_values(setup), **values}
    return _module("_cascades").CascadesExplorer(**values)


def _setup_values(setup: Any) -> dict[str, Any]:
    """The cascade explorer's controls from an engine's :class:`aliasing.setups.Setup`."""
    from .. import partitioning
    from ..setups import Setup

    if not isinstance(setup, Setup):
        raise ValueError(f"setup must be an aliasing.setups.Setup (aliasing.setups.build(...)), got {type(setup).__name__}")
    pl, cam = setup.pipeline, setup.camera
    try:
        method = partitioning.resolve_name({"logarithmic": "log"}.get(pl.split, pl.split))
    except ValueError:
        raise ValueError(f"setup: {setup.profile.name}'s split {pl.split!r} is not a split method of the explorer") from None
    out = {"method": method, "k": pl.k, "near": cam.near, "far": max(pl.far_i), "fov": cam.fov, "aspect": cam.aspect,
           "res_image": cam.height}
    budget = pl.k * pl.resolution**2
    if budget in dict(_module("_cascades").BUDGETS).values():
        out["budget"] = budget
    return out


def faces(**values: Any) -> Explorer:
    """Face-partition explorer: chosen faces (Lloyd 2007 eq. 54), frames and per-map S of FP, FPc, FPcs (§6.1.3, §6.5).

    Parameters
    ----------
    **values
        ``variant`` (``fp``, ``fpc``, ``fpcs``), ``parameterization`` of the side faces,
        ``f_over_n``, ``fov`` [deg], ``gamma``, ``azimuth`` [deg].  No aspect: face partitions
        are of a square frustum.

    Returns
    -------
    Explorer

    Example
    -------
    >>> e = faces(variant="fp", gamma=90.0, azimuth=0.0, f_over_n=1000.0)
    >>> e.data["maps"], round(e.data["S"], 3)     # overhead: the bottom face only
    (1, 5.982)
    """
    return _module("_faces").FacesExplorer(**values)


def raster(**values: Any) -> Explorer:
    """Rasterizer explorer: shadows, texel grid, per-pixel error and measured/bound ratios.

    Parameters
    ----------
    **values
        ``scheme`` (text), ``light`` (text, one direction), ``f_over_n``, ``fov`` [deg, vertical],
        ``aspect`` (width/height, 0.25–4: the R × R pixels aspect : 1 wide), ``image_res``
        [pixels], ``budget`` [texels over all maps], ``every`` [texels between grid lines].

    Returns
    -------
    Explorer

    Example
    -------
    >>> e = raster(scheme="P", light="gamma:60", image_res=32, budget=64 * 64)
    >>> e.data["map_res"], e.error
    (64, None)
    """
    return _module("_raster").RasterExplorer(**values)


def bias(**values: Any) -> Explorer:
    """Depth-bias explorer: per cascade, an engine preset's bias against the derived minimum, the ground's margin and the lit gap.

    Parameters
    ----------
    **values
        ``preset`` (:data:`aliasing.bias.presets.PRESETS`), ``elevation`` (light above the
        ground [deg]), ``k`` (cascades), ``lam`` (λ), ``far`` [world units], ``aspect``
        (width/height, 0.25–4), ``resolution`` (texels per cascade side), ``image`` [pixels,
        the image's rows].

    Returns
    -------
    Explorer
        ``.data`` holds :func:`aliasing.explore._bias.compute`'s result.

    Example
    -------
    >>> e = bias(preset="bevy", elevation=20.0, k=4)
    >>> [round(r["margin"], 2) for r in e.data["rows"]]
    [1.24, 1.02, 0.93, 0.87]
    """
    return _module("_bias").BiasExplorer(**values)


def shimmer(**values: Any) -> Explorer:
    """Shimmer explorer: plays a camera or sun path over a still scene and marks the points whose shadow flips.

    Parameters
    ----------
    **values
        ``scene`` (a built-in scene), ``scheme`` (the engines grammar), ``motion``
        (:func:`aliasing.temporal.paths.parse_motion`), ``frames``, ``frame``, ``image_res``
        (points: one per pixel of the first frame), ``shadow_res`` [texels per cascade].  No
        aspect: :mod:`aliasing.temporal` follows a square view.

    Returns
    -------
    Explorer
        With a play button stepping the ``frame`` control.

    Example
    -------
    >>> e = shimmer(scheme="csm-stable:log:k=3:fit=sphere:snap=origin", frames=4, frame=2, image_res=48, shadow_res=128)
    >>> int(e.data["flipped"].sum()), e.error     # a snapped sphere under sideways motion: no flips
    (0, None)
    """
    return _module("_shimmer").ShimmerExplorer(**values)


def tune(**values: Any) -> Explorer:
    """Tune explorer: the engine's own settings, searched again as the camera, the sun and the limits move.

    Parameters
    ----------
    **values
        ``engine`` (one whose profile declares tunable settings), ``near``, ``far`` [world units],
        ``fov`` [deg, vertical], ``aspect``, ``height`` [pixels], ``sun_low``, ``sun_high`` [deg],
        ``receivers_near``, ``receivers_far`` [world units], ``budget`` [texels], ``max_slope``
        [deg], ``max_gap_px`` (text; empty: no limit), ``moving``, ``keep_budget_shape`` (keep
        the count and the map size).

    Returns
    -------
    Explorer
        ``.data`` holds :func:`aliasing.explore._tune.compute`'s result.

    Example
    -------
    >>> e = tune(receivers_near=1.0, receivers_far=200.0)
    >>> e.data["changed"]["customSplitsLambda"], e.data["binding"]
    (0.9132, [])
    >>> e.set_state({"receivers_near": 0.1}), e.data["changed"]["mode"]   # receivers at the near plane: the log split
    (True, 'logarithmic')
    """
    return _module("_tune").TuneExplorer(**values)
