"""Depth bias: the acne a bias leaves and the peter-panning it costs, derived, measured and per engine.

One concern, modules by source and method:

* :mod:`.plane`: the minimal depth bias and normal offset of a planar receiver
  (:func:`plane_bias`, :func:`map_bias`) and the lit gap a bias leaves (:func:`lit_gap`),
  derived in :mod:`aliasing.symbolic.bias`;
* :mod:`.quantization`: the depth step of 16-, 24- and 32-bit depth buffers;
* :mod:`.projection`: projection aliasing, the full error m·cos ψ_e / cos ψ_l;
* :mod:`.presets`: the engines' bias rules, read from their source;
* :mod:`.cascades`: per cascade of a setup, the minimal biases against a preset's;
* :mod:`.filtering`: the filter's reach and the cascade seams: PCF footprints, the texel step at a
  boundary, the blend band that hides it, kernels fixed in texels or in world units;
* :mod:`.scene`: a preset's acne and peter-panning pixels per cascade of a rendered scene,
  and the per-pixel margin;
* :mod:`.command`: the ``aliasing bias`` command.

Example
-------
>>> plane_bias(0.1, 45.0)
PlaneBias(depth=0.05, normal=0.035355339059327376)
"""

from __future__ import annotations

from .plane import LOOKUPS, PlaneBias, edge_shift, kernel, lit_gap, map_bias, plane_bias, slope_factor
from .quantization import quantization_bias

__all__ = ["LOOKUPS", "PlaneBias", "edge_shift", "kernel", "lit_gap", "map_bias", "plane_bias", "quantization_bias", "slope_factor"]
