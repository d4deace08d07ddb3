"""What the user sees wrong, predicted without a browser.

:mod:`.synth` synthesizes the read-back an engine's page would return (the toolkit's eye pass,
the model's light matrices and cascades) and predicts the frame from it by the same functions
that predict an engine's real read-back (:func:`aliasing.frames.run.measure`).

Examples
--------
>>> from aliasing.frames import seen
>>> seen.ENGINES
('threejs', 'babylon', 'playcanvas')
"""

from .synth import ENGINES, synthetic_frame

__all__ = ["ENGINES", "synthetic_frame"]
