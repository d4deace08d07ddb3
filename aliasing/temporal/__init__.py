"""Shadows over time: the shimmer of a still world under a moving camera or a turning sun.

Modules
-------
paths
    The motions (translate, rotate, zoom, sun) and the per-frame camera poses and lights.
points
    A still world (built-in scene or file) and fixed points on the surfaces the first frame sees.
fits
    Per frame, every map's texel lattice in the world: stable fits and snapping, SDSM's
    per-frame depth bounds, VSM's world-fixed clipmap pages; which map each point uses.
render
    Depth maps of those lattices, reused while a lattice holds, and the shadow test.
measure
    The shimmer measured: flips per frame, flips from map changes apart, shadow-edge shift.
predict
    The shimmer predicted: grid motion (phase shift, scale change) × shadow-edge density.
command
    The ``aliasing shimmer`` subcommand.
"""
