"""What to set: an engine's own shadow settings, searched for a camera, a sun band and limits.

:func:`tune` takes a :class:`aliasing.setups.Setup` (the engine, the settings the user fixes,
the camera and the sun band) and the limits (receivers' depths, a texel budget, the steepest
receiver that must stay free of acne, the largest lit gap in pixels, a moving camera), and
searches only the settings the engine's profile declares tunable
(the ``tunable`` of :class:`aliasing.setups.Profile`) for the lowest worst-case perspective error.
Biases are not searched there: they are set to the closed-form minimum that leaves no acne.  For
the engines whose frames are predicted (three.js, Babylon.js, PlayCanvas, Godot's Compatibility renderer), :func:`aliasing.tune.pixels.refine`
then searches the same levers, the biases included, for the fewest pixels the user sees wrong
(the ``aliasing tune`` command's objective), with a Pareto front of wrong pixels, px/texel
and memory, and :func:`aliasing.tune.proof.prove` renders the best in the engine.  Where
the limits cannot all be met, :attr:`Tuned.binding` says which break and
:attr:`Tuned.tradeoff` gives the curve between acne and gap.

Modules
-------
measure
    The objective and the constraints of one setup.
search
    The search and the closed-form bias.
receivers
    The receivers' depths of a scene.
report
    What changed and what got worse, start against tuned.
theory
    The tuned split against the papers' splits for the same budget.
pixels
    The wrong-pixel objective: the coordinate search, the Pareto front.
explain
    The why lines: what each change of the pick fixes and costs.
proof
    ``--frames N``: the best candidates rendered in the engine itself.
command
    The ``aliasing tune`` subcommand.

Example
-------
>>> from aliasing import setups
>>> s = setups.build("threejs", {"cascades": 4}, "near=0.1,far=500,fov=50,aspect=16:9,height=1080", "15..60")
>>> t = tune(s, keep=("cascades", "shadowMapSize"))
>>> t.feasible, t.changed, round(t.before.objective), round(t.objective, 2)   # px/texel, before and after
(True, {'mode': 'logarithmic'}, 677, 9.05)
"""

from __future__ import annotations

from .measure import LIMITS, MAX_ANGLE, Limits, Measure, limits, measure
from .receivers import scene_receivers
from .search import Tuned, closed_form_bias, tune
from .theory import compare_splits, equal_error_split

__all__ = ["LIMITS", "MAX_ANGLE", "Limits", "Measure", "Tuned", "closed_form_bias", "compare_splits", "equal_error_split", "limits",
           "measure", "scene_receivers", "tune"]
