"""Benchmark of ``aliasing derive``: every symbolic derivation, and the slowest one alone; run by hand.

Targets: all derivations within 10 s, any single one within 2 s, on this 2-core machine, as
the command line runs them (a fresh process: Python, the sympy import, the derivation and
its printing).  Each figure is the median of ``--repeats`` runs of the command in a fresh
process (time.perf_counter around ``subprocess.run``; the CPU time of the child,
``resource.getrusage(RUSAGE_CHILDREN)``, beside it: on a loaded machine it is what the run
costs on a free core).  The baseline, timed side by side the same way, is
``aliasing derive --list``: the interpreter, the package, sympy and the registry, no
derivation; ``all − baseline`` is what the derivations themselves cost.

The slowest single derivation is found first, by running every name once (CPU time), and
then timed alone.  The 1-minute load average (``os.getloadavg``) is printed before and
after; on this 2-core machine other jobs may be running.

Usage::

    python benchmarks/derive.py                 # 3 runs of all, 5 of the slowest one and of the baseline
    python benchmarks/derive.py --repeats 5
    python benchmarks/derive.py --skip-search --name lloyd2007.m_point_far_limit
    git archive b54a15a aliasing | tar -x -C /tmp/before   # an older tree, timed side by side:
    python benchmarks/derive.py --skip-search --name zhang2007.psi --against /tmp/before
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import time


AGAINST: str | None = None
"""With ``--against DIR``: the package tree (a folder holding ``aliasing/``) that every run imports."""


def _command() -> list[str]:
    if AGAINST is not None:
        code = "import sys; sys.path.insert(0, sys.argv.pop(1)); from aliasing.cli import main; sys.exit(main())"
        return [sys.executable, "-c", code, AGAINST]
    exe = shutil.which("aliasing", path=os.path.dirname(sys.executable)) or shutil.which("aliasing")
    return [exe] if exe else [sys.executable, "-m", "aliasing.cli"]


def _run(args: list[str]) -> tuple[float, float]:
    """Wall and child CPU (user + system) time [s] of one run of ``aliasing <args>``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(_command() + args, check=True, stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def _median(args: list[str], repeats: int) -> tuple[float, float]:
    runs = [_run(args) for _ in range(repeats)]
    return statistics.median(w for w, _ in runs), statistics.median(c for _, c in runs)


def _names() -> list[str]:
    out = subprocess.run(_command() + ["derive", "--list"], check=True, capture_output=True, text=True).stdout
    return [line.split()[0] for line in out.splitlines() if line.strip()]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3, help="runs of all derivations (the single one and the baseline get 2 more)")
    ap.add_argument("--name", help="the single derivation to time (default: the slowest, found by running each once)")
    ap.add_argument("--skip-search", action="store_true", help="with --name: do not run every derivation once")
    ap.add_argument("--against", metavar="DIR", help="time the package tree in DIR (e.g. an older commit's, from git archive) instead of the installed one")
    args = ap.parse_args()
    global AGAINST
    AGAINST = args.against
    if AGAINST is not None:
        print(f"package tree: {AGAINST}")
    print(f"load average before: {os.getloadavg()[0]:.2f} (cores: {os.cpu_count()})")
    names = _names()
    name = args.name
    if not args.skip_search:
        singles = {n: _run(["derive", n]) for n in names}
        ranked = sorted(singles.items(), key=lambda kv: kv[1][1], reverse=True)
        print(f"{len(names)} derivations, one run each; the five slowest (wall / CPU [s]):")
        for n, (w, c) in ranked[:5]:
            print(f"  {n:40s} {w:6.2f} {c:6.2f}")
        name = name or ranked[0][0]
    if name is None:
        raise SystemExit("--skip-search needs --name")
    base = _median(["derive", "--list"], args.repeats + 2)
    every = _median(["derive"], args.repeats)
    one = _median(["derive", name], args.repeats + 2)
    print(f"{'run':42s} {'wall med':>9s} {'CPU med':>8s} {'target':>7s}")
    print(f"{'baseline: derive --list':42s} {base[0]:9.2f} {base[1]:8.2f} {'':>7s}")
    print(f"{'all ' + str(len(names)) + ' derivations':42s} {every[0]:9.2f} {every[1]:8.2f} {10.0:7.1f}")
    print(f"{'slowest alone: ' + name:42s} {one[0]:9.2f} {one[1]:8.2f} {2.0:7.1f}")
    print(f"all − baseline: {every[0] - base[0]:.2f} s wall, {every[1] - base[1]:.2f} s CPU; slowest − baseline: {one[0] - base[0]:.2f} s wall, {one[1] - base[1]:.2f} s CPU")
    print(f"load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
