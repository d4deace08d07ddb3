"""The ``bias-margin`` picture: per pixel, how far an engine preset's bias is from acne and from peter-panning.

Each pixel's colour is log₂ of :func:`aliasing.bias.scene.bias_margin` (the preset's bias as one
depth bias over the pixel's minimal bias): red below 1 (the surface shows acne), white at 1,
blue above (bias to spare, which at contacts with casters is lit gap: peter-panning), the
scale saturating at 1/4 and 4.  Faces turned from the light are dark grey, the sky white.

Example
-------
>>> img, margin = bias_margin_image(1.0, 20.0, 60.0, "gamma:60@azimuth:30", preset="bevy", image_res=24, budget=64**2, boxes=4)
>>> img.shape, margin.shape
((24, 24, 3), (24, 24))
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..bias.scene import bias_margin
from .images import _base_colour, _finish, view

Array = NDArray[np.float64]

#: log₂ of the margin at which the colour saturates.
SPAN = 2.0


def margin_colours(margin: ArrayLike) -> Array:
    """Colours (…, 3): red below a margin of 1, white at 1, blue above; mid grey for NaN.

    Example
    -------
    >>> margin_colours([0.25, 1.0, 4.0]).round(2).tolist()[1]
    [0.97, 0.97, 0.97]
    """
    from matplotlib import colormaps

    m = np.asarray(margin, float)
    with np.errstate(invalid="ignore", divide="ignore"):
        x = np.clip(np.log2(m) / (2 * SPAN) + 0.5, 0.0, 1.0)
    rgb = colormaps["RdBu"](np.nan_to_num(x, nan=0.5))[..., :3]
    return np.where(np.isfinite(m)[..., None], rgb, 0.5)


def bias_margin_image(near: float, far: float, fov: float, light: str | ArrayLike, scheme: str = "Standard", *, preset: str = "filament",
                      **kwargs) -> tuple[Array, Array]:
    """(image (R, R, 3), margin (R, R)) of the seeded scene, row 0 at the top; ``kwargs`` as :func:`~aliasing.pictures.view`."""
    return margin_of(view(near, far, fov, light, scheme, **kwargs), preset)


def margin_of(v, preset: str = "filament") -> tuple[Array, Array]:
    """(image (R, R, 3), margin (R, R)) of a rendered view (:func:`~aliasing.pictures.render_view`), row 0 at the top."""
    m = bias_margin(v, preset)
    img = margin_colours(m)
    _, lam, hit = _base_colour(v)
    img = np.where((hit & ~np.isfinite(m))[..., None], 0.25, img)  # turned from the light: in its own shadow
    img = np.where(hit[..., None], img * (0.8 + 0.2 * lam)[..., None], 1.0)
    return _finish(img), m[::-1]
