"""Measuring and validating: the rasterizer as the witness of the analytic bounds.

* :mod:`.measure`: perspective aliasing measured from sampled positions by finite
  differences (:func:`measure`, :func:`pixel_errors`, :func:`projection_factors`);
* :mod:`.single`: one validation of a scheme's bounds for one light (:func:`validate`) and
  its text/CSV/JSON formats;
* :mod:`.grid`: validation grids over schemes × f/n × fov × lights, run through the sweep
  engine (:func:`plan`, :func:`validate_sweep`), and the ``aliasing validate`` command;
* :mod:`.scene`: the error measured on a loaded scene's own surfaces (:func:`validate_scene`);
* :mod:`.raycast`: a ray-casting reference for the depth maps (one Embree ray per texel;
  optional, the ``bench`` extra; not imported here).

Example
-------
>>> r = validate("P", 100, 60, "gamma:150", res=96, probes=6)
>>> r["passed"], r["maps"]
(True, 1)
"""

from __future__ import annotations

from .measure import Measurement, measure, pixel_errors, projection_factors
from .single import FORMATS, format_rows, format_text, validate
from .grid import (
    GRID_FORMATS, PER_MAP, ValidationGrid, ValidationTable, ValidationTask, add_validate_parser, expand_light_specs, plan,
    validate_rows, validate_sweep,
)
from .scene import measurable_pixels, validate_scene

__all__ = [
    "FORMATS", "GRID_FORMATS", "Measurement", "PER_MAP", "ValidationGrid", "ValidationTable", "ValidationTask", "add_validate_parser",
    "expand_light_specs", "format_rows", "format_text", "measurable_pixels", "measure", "pixel_errors", "plan", "projection_factors",
    "validate", "validate_rows", "validate_scene", "validate_sweep",
]
