"""The units of what ``check`` reports, and the one name of its error.

The **aliasing error** (Lloyd et al. 2006's m = dp/ds, "the perspective aliasing error") is the
width of one shadow-map texel as it lands on the camera's image, in image pixels: **pixels per
texel** [px/texel].  At 1 a texel covers one pixel; at 8 one texel spans 8 pixels (the blocky
shadows the papers fight); below 1 several texels share a pixel.  ``check``, ``bias``, ``tune`` and
the docs say it with :data:`ERROR_NAME` and :data:`ERROR_UNIT`, and the frames' reports measure the
same quantity in the engines' own frames as ``px_per_texel`` (:mod:`aliasing.frames.compare`).

Every field of the report has a unit (:func:`units`), or is unitless by declaration
(:data:`UNITLESS`): the table's and the CSV's headers carry it in brackets (``texel_s [m]``,
``error_max [px/texel]``, ``memory [MiB]``, ``needed_shadowBias [normalized light depth]``), the
JSON keeps its keys and adds a ``units`` object with the same units (``memory`` there in bytes).

Example
-------
>>> from aliasing import setups
>>> u = units(setups.build("godot"))
>>> u["near"], u["error_max"], u["memory"], u["needed"]["shadow_normal_bias"]
('m', 'px/texel', 'bytes', 'texels')
>>> header("gap_px", "px"), header("texel_s", "m"), header("cascade", "")
('gap [px]', 'texel_s [m]', 'cascade')
"""

from __future__ import annotations

from typing import Any

from ..setups import Setup

__all__ = ["ERROR_NAME", "ERROR_UNIT", "ERROR_WORDS", "UNITLESS", "header", "units"]

#: The name of the perspective error ``check`` reports (``error_max``, ``error_median``).
ERROR_NAME = "aliasing error"
#: Its unit: image pixels per shadow-map texel (a texel's width on the image, in pixels).
ERROR_UNIT = "px/texel"
#: The unit in words, for sentences.
ERROR_WORDS = "pixels per texel"
#: The fields that are counts or labels, unitless by declaration.
UNITLESS = ("cascade",)
#: Units of the fields that do not depend on the engine (the lengths take the engine's world unit).
FIXED = {"error_max": ERROR_UNIT, "error_median": ERROR_UNIT, "stable_cost": "×", "acne": "fraction", "gap_px": "px",
         "seam_step": "×", "footprint_px": "px", "shimmer_px": "px/frame", "memory": "bytes", "memory_mib": "MiB",
         "acne_px": "px", "receiver_px": "px"}
LENGTHS = ("near", "far", "texel", "texel_s", "texel_t", "blend", "blend_start", "blend_end")
#: The bracket's word for a setting without a unit of its own.
NO_UNIT = "unitless"


def units(setup: Any) -> dict[str, Any]:
    """The unit of every field of :func:`aliasing.check.check`'s cascades, for ``setup``'s engine:
    lengths in its world unit (:attr:`aliasing.setups.Profile.length_unit`), ``needed`` a mapping of
    each bias setting to its own unit, ``""`` for :data:`UNITLESS`.

    Raises
    ------
    ValueError
        Where ``setup`` is not an :class:`aliasing.setups.Setup`.
    """
    if not isinstance(setup, Setup):
        raise ValueError(f"setup must be an aliasing.setups.Setup (aliasing.setups.build(...)), got {type(setup).__name__}")
    world = setup.profile.length_unit
    known = {s.key: s for s in setup.profile.settings}
    needed = {t.key: (known[t.key].unit or NO_UNIT) for t in setup.pipeline.bias.terms if t.key in known}
    return {k: "" for k in UNITLESS} | {k: world for k in LENGTHS} | FIXED | {"needed": needed} | {f"needed_{k}": v for k, v in needed.items()}


def header(key: str, unit: str) -> str:
    """A column's header: the key without a unit suffix of its own (``gap_px`` → ``gap``,
    ``memory_mib`` → ``memory``) and the unit in brackets; a unitless key as it is."""
    if not isinstance(key, str) or not isinstance(unit, str):
        raise ValueError(f"key and unit must be text, got {key!r}, {unit!r}")
    if not unit:
        return key
    base = {"acne_px": "acne_pixels", "receiver_px": "receiver_pixels"}.get(key)
    if base is None:
        base = key.removesuffix("_px").removesuffix("_mib")
    return f"{base} [{unit}]"
