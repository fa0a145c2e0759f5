"""``voroforge warmup``: compile and cache the kernels of the first commands, once."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

__all__ = ["add_parser", "run_warmup"]

_EPILOG = """\
examples:
  voroforge warmup                      build every example, raster and explain once
  voroforge warmup --list               show the steps without running them
  voroforge warmup my-panel.toml        warm the builds of your own design files
  voroforge warmup --time 3             then time each first run (fresh process, best of 3)

`make run` runs it. After it, the first build of every example and the first raster and
explain load their compiled kernels from numba's cache instead of compiling them.
"""


def add_parser(commands, formatter_class) -> None:
    """Add ``warmup`` to ``commands`` (see :mod:`voroforge.cli`)."""
    p = commands.add_parser(
        "warmup",
        help="compile and cache the kernels of the first commands (run once after install)",
        description="Run each example design's build, voroforge raster and voroforge explain "
        "once on small inputs in a scratch folder, so that numba compiles and caches their "
        "kernels now rather than on first use.",
        epilog=_EPILOG,
        formatter_class=formatter_class,
    )
    p.add_argument(
        "designs",
        nargs="*",
        metavar="DESIGN",
        help="design files to warm (default: examples/*.toml, or the starter design)",
    )
    p.add_argument("--list", action="store_true", help="print the steps and exit")
    p.add_argument(
        "--time",
        type=int,
        nargs="?",
        const=1,
        default=0,
        metavar="N",
        help="then run every step again in a fresh process (N times, the least kept) and "
        "print its wall and CPU time: what a first run costs once warm",
    )
    p.set_defaults(run=run_warmup)


def run_warmup(args: argparse.Namespace, stage=None) -> int:
    """Run the warm-up; exit status 1 when a step failed (the others still ran)."""
    import tempfile

    from ..warmup import example_designs, plan, warm_up

    designs = [Path(d) for d in args.designs] or example_designs()
    for d in designs:  # before any step runs (the steps took ~30 s to say so)
        if not d.is_file():
            raise ValueError(f"{d}: no such design file")
    if args.list:
        for step in plan(designs, Path(tempfile.gettempdir()) / "voroforge-warmup"):
            print(f"{step.label:<34} voroforge {' '.join(step.argv)}")
        return 0
    if args.time < 0:
        raise ValueError(f"--time needs a number of runs >= 1 (0: no timing), got {args.time}")
    done = warm_up(
        designs, report=lambda line: print(line, file=sys.stderr, flush=True), timed=args.time
    )
    n = len(done) // 2 if args.time else len(done)
    steps = done[:n]
    total = sum(s.seconds for s in steps)
    cpu = sum(s.cpu for s in steps)
    failed = [s for s in done if s.error]
    print(
        f"warm-up: {len(steps) - len([s for s in steps if s.error])}/{len(steps)} steps in "
        f"{total:.1f} s ({cpu:.1f} s CPU)",
        file=sys.stderr,
    )
    if args.time:
        slowest = max(done[n:], key=lambda s: s.seconds)
        print(
            f"first runs: the slowest is {slowest.label} ({slowest.seconds:.2f} s wall, "
            f"{slowest.cpu:.2f} s CPU)",
            file=sys.stderr,
        )
    return 1 if failed else 0
