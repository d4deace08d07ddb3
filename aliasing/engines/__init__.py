"""Today's engine shadow schemes beside the papers'.

Modules
-------
stable
    Cascade fits: tight (the papers'), bounding sphere, fixed diagonal (Bevy), fit to
    scene; texel snapping; cascade overlap; cost as a ratio to the tight fit.
sdsm
    Sample-distribution shadow maps: log partitions on an occupied depth range,
    adaptive-log and k-means partitions from a depth histogram (Intel's sample).
vsm
    Unreal Engine 5 virtual shadow-map clipmaps for a directional light: level selection,
    texel size per level, the error's saw-tooth, pages and the page pool.
limits
    Resolution-matched (power-of-two levels) and exact sampling.
compare
    One row per scheme for ``aliasing engines``.
validate
    The rasterizer as witness: VSM clipmap levels and stable/SDSM cascades rendered on the
    probes, measured error against the analytic bounds; depth histograms from the eye pass.
scene
    The same on a loaded scene (a glTF file, the procedural city): stable presets, SDSM
    partitions from the scene's own depth histogram, VSM levels.

Every module works in the scene's length unit; the VSM model's constants are the
engine's, which works in centimetres.
"""
