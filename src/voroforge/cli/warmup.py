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

`make run` runs it. After it, the first build of every example and the first raster and
explain load their compiled kernels from numba's cache instead of compiling them.
"""


def add_parser(commands, formatter_class) -> None:
    """Add ``warmup`` to argparse ``commands`` (from ``add_subparsers``).

    Parameters
    ----------
    commands : argparse subparsers action
        Where to add it.
    formatter_class : type
        Help formatter of the subcommand.
    """
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
    p.set_defaults(run=run_warmup)


def run_warmup(args: argparse.Namespace, stage=None) -> int:
    """Run the warm-up; exit status 1 when a step failed (the others still ran)."""
    import tempfile

    from ..warmup import example_designs, plan, warm_up

    designs = [Path(d) for d in args.designs] or example_designs()
    if args.list:
        for step in plan(designs, Path(tempfile.gettempdir()) / "voroforge-warmup"):
            print(f"{step.label:<34} voroforge {' '.join(step.argv)}")
        return 0
    steps = warm_up(designs, report=lambda line: print(line, file=sys.stderr, flush=True))
    total = sum(s.seconds for s in steps)
    cpu = sum(s.cpu for s in steps)
    failed = [s for s in steps if s.error]
    print(
        f"warm-up: {len(steps) - len(failed)}/{len(steps)} steps in {total:.1f} s "
        f"({cpu:.1f} s CPU)",
        file=sys.stderr,
    )
    return 1 if failed else 0
