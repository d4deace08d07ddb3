"""What the user sees wrong, predicted without a browser.

:mod:`.synth` synthesizes the read-back an engine's page would return (the toolkit's eye pass,
the model's light matrices and cascades) and predicts the frame from it by the same functions
that predict an engine's real read-back (:func:`aliasing.frames.run.measure`); :mod:`.wrong` counts
the pixels it gets wrong (acne, false and lost shadow, blockiness, memory) per cascade, by default
on the reference scene of :mod:`.scene`.

Examples
--------
>>> from aliasing.frames import seen
>>> seen.ENGINES
('threejs', 'babylon', 'playcanvas', 'godot')
"""

from .memo import remember
from .scene import reference_scene
from .synth import ENGINES, synthetic_frame
from .wrong import UNITS, Sample, Wrong, count, fractions, sample, wrong_pixels

__all__ = ["ENGINES", "UNITS", "Sample", "Wrong", "count", "fractions", "reference_scene", "remember", "sample", "synthetic_frame", "wrong_pixels"]
