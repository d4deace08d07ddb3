"""The engines' own frames: what three.js draws, read back and measured against the toolkit's prediction.

An engine (a pinned npm release, :mod:`.install`) renders a scene (:mod:`.scenes`) in the
system's headless Chromium with WebGL 2 on SwiftShader (:mod:`.browser`, Playwright for
Python: the optional ``frames`` extra).  Its page (``pages/<engine>.mjs``) reads back, per
pixel, the raw shadow factor the engine multiplied into the sun's light, the cascade it
sampled, the world position and normal, and per cascade the light matrix and map size
(:mod:`.readback`).  The toolkit predicts the same pixels with its own rasterizer and the
engine's rules (:mod:`.models`, :mod:`.predict`; its light depth maps, whole or drawn only
where the pixels read them, :mod:`.lightmaps`), and both are measured alike
(:mod:`.compare`, :mod:`.run`); the shadow maps themselves can be read back and checked texel
for texel (:mod:`.maps`), and Babylon.js's cascade matrices are predicted (:mod:`.babylon_cascades`).
Filament (npm, WebGL 2) is rendered and measured against the exact shadows, not predicted: its
factor is the ratio of two 8-bit frames (:class:`.models.Filament`);
Godot 4.6 (its official web export template: the Compatibility renderer) is rendered from a
main pack written per frame (:mod:`.godot`) and predicted (:class:`.models.Godot`);
``aliasing frames`` is the command (:mod:`.command`).

``import aliasing.frames`` needs neither Playwright nor Chromium: they are looked for when a
frame is rendered.

Examples
--------
>>> from aliasing import frames
>>> sorted(frames.PINS)
['babylon', 'filament', 'godot', 'playcanvas', 'threejs']
"""

from .install import PINS, MissingTool

__all__ = ["PINS", "MissingTool"]
