"""The ``seen`` block of :func:`aliasing.check.check`: what the user sees wrong, per cascade, predicted without a browser.

The numbers are :func:`aliasing.frames.seen.wrong_pixels` of the setup: the frame the engine
would draw, predicted by the toolkit's rasterizer with the engine's rules on the reference scene
(or the check's ``scene``: boxes, city or a file), for a few suns over the band; per cascade the
fractions of the pixels facing the sun that show acne, false shadow (shadow grown beyond the
exact one) and lost shadow, their sum ``wrong``, the fraction of the cascade's pixels whose map
texel is larger than a pixel (``blocky``) and the maps' ``memory`` [bytes].  Engines whose light
matrices the toolkit does not predict, and settings the frames' models do not model, get
``not_predicted`` with the reason instead.

Examples
--------
>>> from aliasing import setups
>>> block = seen_block(setups.build("bevy", {}, "near=0.5,far=60,fov=50,aspect=16:9,height=720", 30))
>>> block["not_predicted"].startswith("setup's engine must be one of threejs, babylon, playcanvas, godot")
True
>>> seen_block(setups.build("godot", {}, "near=0.5,far=60,fov=50,aspect=16:9,height=720", 30))["not_predicted"][:63]
'rendering/renderer/rendering_method must be gl_compatibility: G'
"""

from __future__ import annotations

import os

from .. import _table as _tables

#: The table's columns, in order, and the unit line printed above them.
COLUMNS = ("cascade", "pixels", "acne", "false_shadow", "lost_shadow", "wrong", "blocky", "memory")


def seen_block(setup, scene: object = None, eye=None, target=None, *, height: int = 144, suns: int = 3) -> dict:
    """The JSON-ready ``seen`` object of a check report (module docstring).

    Parameters
    ----------
    setup : aliasing.setups.Setup
        The checked setup.
    scene : {"boxes", "city"}, str or path, optional
        None: the reference scene (:func:`aliasing.frames.seen.reference_scene`); else a scene of
        :func:`aliasing.frames.scenes.frame_scene` (``eye`` and ``target`` [world units] for a city or a file).
    height : int
        Rows of the sample image [px], 16 to 1080.
    suns : int
        Suns over the band, 1 to 16.

    Returns
    -------
    dict
        ``cascades``, ``total``, ``sample`` and ``units`` (:meth:`aliasing.frames.seen.wrong.Wrong.to_dict`),
        or ``not_predicted`` (why not).

    Examples
    --------
    >>> from aliasing import setups
    >>> s = setups.build("playcanvas", {"shadowResolution": 512}, "near=0.5,far=60,fov=50,aspect=16:9,height=720", 30)
    >>> b = seen_block(s, height=36, suns=1)
    >>> [c["cascade"] for c in b["cascades"]], b["units"]["memory"]
    ([0, 'beyond'], 'bytes')
    """
    from ..frames.seen import wrong_pixels
    from ..frames.seen.synth import engine_settings

    try:
        engine_settings(setup)
    except ValueError as e:  # an engine or a setting the frames' models do not predict: said, not raised
        return {"not_predicted": str(e)}
    if scene is not None and not isinstance(scene, (str, os.PathLike)):
        return {"not_predicted": "the wrong-pixel measure draws the reference scene, boxes, city or a scene file (not given triangles)"}
    return wrong_pixels(setup, None if scene is None else os.fspath(scene), eye=eye, target=target, height=height, suns=suns).to_dict()


def seen_text(block: dict) -> str:
    """The ``seen`` block as text: a heading with the sample and the units, a row per cascade, the total.

    Examples
    --------
    >>> print(seen_text({"not_predicted": "setup's engine must be one of threejs, babylon, playcanvas"}), end="")
    what you see wrong: not predicted (setup's engine must be one of threejs, babylon, playcanvas)
    >>> from aliasing import setups
    >>> s = setups.build("threejs", {"cascades": 1, "shadowMapSize": 512}, "near=0.5,far=60,fov=50,aspect=16:9,height=720", 30)
    >>> print(seen_text(seen_block(s, height=36, suns=1)).splitlines()[2].split())
    ['cascade', 'pixels', 'acne', 'false_shadow', 'lost_shadow', 'wrong', 'blocky', 'memory']
    """
    if "not_predicted" in block:
        return f"what you see wrong: not predicted ({block['not_predicted']})\n"
    s = block["sample"]
    suns = s["elevations"]
    band = f"{suns[0]:g}°" if len(suns) == 1 else f"{len(suns)} suns {suns[0]:g}–{suns[-1]:g}°"
    head = (f"what you see wrong, predicted (the {s['scene']} scene, a {s['width_px']}x{s['height_px']} px sample of the view, {band}):\n"
            "acne, false_shadow, lost_shadow, wrong [fraction of the pixels facing the sun]; blocky [fraction of the cascade's pixels "
            f"whose texel is larger than a pixel of the {s['image_height_px']}-row image]; memory [bytes]\n")
    rows = [{k: c[k] for k in COLUMNS} for c in block["cascades"]]
    rows.append({"cascade": "total", **{k: block["total"].get(k) for k in COLUMNS[1:-1]}, "memory": s["memory"]})
    return head + _tables.table(rows)
