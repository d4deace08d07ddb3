"""Benchmark of the Jupyter explorers' update time (aliasing.explore); run by hand, not under pytest.

Target: at default sizes each analytic explorer (overhead, directions, cascades,
faces) recomputes and redraws within 100 ms of a change, the rasterizer one within 1 s.  An
update is what a slider change triggers once the debounce has elapsed: ``compute`` (the
toolkit's numbers), ``draw`` (a fresh matplotlib figure) and the PNG the widget shows.
Each explorer is built with its defaults; one control is toggled between two values and
each toggle's full update is timed (``Explorer.update`` through ``set_state``,
time.perf_counter), median and best of ``--repeats``.  The plain baseline, timed side by
side in the same run and the same way, is ``compute`` alone (the API call, no drawing):
the ratio update/compute is the cost of drawing.  The CPU time of the update (this
process, time.process_time) is printed too: on a loaded machine it shows what an update
costs on a free core (numpy and the PNG encoder run on one thread here).  The 1-minute load average (``uptime``)
is printed before and after; on this 2-core machine other jobs may be running.

``--baseline-dpi D`` times, interleaved in the same run, each explorer drawn at D dpi too
(the explorers draw at ``aliasing.explore.widget.Explorer.dpi``, 192 = 2 device pixels per
CSS pixel; they drew at 72 before): the CPU ratio is the cost of the sharper picture.

Usage::

    python benchmarks/explore.py                # 15 updates each
    python benchmarks/explore.py --repeats 30
    python benchmarks/explore.py --baseline-dpi 72
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

from aliasing import explore

#: (explorer, control toggled, two values); defaults everywhere else.
CASES = [
    ("overhead", "f_over_n", (1000.0, 100.0)),
    ("directions", "f_over_n", (1000.0, 100.0)),
    ("cascades", "k", (4, 3)),
    ("cascades", "lam", (0.5, 0.3)),
    ("faces", "gamma", (60.0, 50.0)),
    ("raster", "fov", (60.0, 50.0)),
]
TARGET_MS = {"raster": 1000.0}


def _time(fn, repeats: int) -> tuple[list[float], list[float]]:
    """Wall-clock and CPU (this process) times [ms] of ``repeats`` calls."""
    wall, cpu = [], []
    for i in range(repeats):
        t, c = time.perf_counter(), time.process_time()
        fn(i)
        wall.append((time.perf_counter() - t) * 1e3)
        cpu.append((time.process_time() - c) * 1e3)
    return wall, cpu


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=15)
    ap.add_argument("--baseline-dpi", type=float, default=None, help="also time each update at this dpi, interleaved")
    args = ap.parse_args()
    if args.baseline_dpi is not None:
        return baseline(args.repeats, args.baseline_dpi)
    print(f"load average before: {os.getloadavg()[0]:.2f} (cores: {os.cpu_count()})")
    print(f"{'explorer':11s} {'control':9s} {'update med':>11s} {'best':>7s} {'CPU med':>8s} {'compute med':>12s} {'ratio':>6s} {'target':>7s}")
    for name, control, values in CASES:
        e = getattr(explore, name)()
        state = e.state()

        def update(i, e=e, control=control, values=values):
            assert e.set_state({control: values[(i + 1) % 2]}), e.error

        def compute(i, e=e, control=control, values=values, state=state):
            e.compute(**{**state, control: values[(i + 1) % 2]})

        up, up_cpu = _time(update, args.repeats)
        co, _ = _time(compute, args.repeats)
        med, cmed, cpu = statistics.median(up), statistics.median(co), statistics.median(up_cpu)
        target = TARGET_MS.get(name, 100.0)
        print(f"{name:11s} {control:9s} {med:9.0f}ms {min(up):5.0f}ms {cpu:6.0f}ms {cmed:10.1f}ms {med / cmed:6.1f} {target:5.0f}ms"
              f"{'' if med <= target else '  (over)'}")
    print(f"load average after: {os.getloadavg()[0]:.2f}")


def baseline(repeats: int, dpi: float) -> None:
    """CPU median of an update at the explorers' dpi and at ``dpi``, the two toggled in turn."""
    from aliasing.explore import widget

    own = widget.Explorer.dpi
    print(f"load average before: {os.getloadavg()[0]:.2f} (cores: {os.cpu_count()})")
    print(f"{'explorer':11s} {'control':9s} {f'CPU med {dpi:g} dpi':>16s} {f'CPU med {own:g} dpi':>16s} {'ratio':>6s}")
    for name, control, values in CASES:
        made = {}
        for d in (dpi, own):
            widget.Explorer.dpi = d
            made[d] = getattr(explore, name)()
        widget.Explorer.dpi = own
        cpu: dict[float, list[float]] = {dpi: [], own: []}
        for i in range(repeats):
            for d, e in made.items():
                c = time.process_time()
                assert e.set_state({control: values[(i + 1) % 2]}), e.error
                cpu[d].append((time.process_time() - c) * 1e3)
        base, mine = statistics.median(cpu[dpi]), statistics.median(cpu[own])
        print(f"{name:11s} {control:9s} {base:14.0f}ms {mine:14.0f}ms {mine / base:6.2f}")
    print(f"load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
