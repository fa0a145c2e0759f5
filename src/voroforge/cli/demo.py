"""``voroforge demo``: build the flagship laser-cut panel."""

from __future__ import annotations

import argparse
from pathlib import Path

from .progress import Stage

__all__ = ["add_parser", "run_demo"]

_DEMO_EPILOG = """\
examples:
  voroforge demo               writes out/laser-panel.svg, .dxf and .png
  voroforge demo -o /tmp/vf    the same files in /tmp/vf
"""


def add_parser(commands, formatter_class) -> None:
    """Add ``demo`` to ``commands`` (see :mod:`voroforge.cli`)."""
    demo = commands.add_parser(
        "demo",
        help="build the flagship design: a laser-cut panel (SVG, DXF, PNG)",
        description="Build the flagship design (examples/laser-panel.toml: a 600 x 400 mm "
        "laser-cut panel, 3 mm webs, 2 mm fillets): writes laser-panel.svg, .dxf and .png.",
        epilog=_DEMO_EPILOG,
        formatter_class=formatter_class,
    )
    demo.add_argument(
        "-o", "--output", metavar="DIR", default="out", help="output folder (default: out)"
    )
    demo.set_defaults(run=run_demo)


def run_demo(args: argparse.Namespace, stage: Stage) -> list[Path]:
    """Run ``voroforge demo``; returns the files written."""
    from ..demo import build_demo

    return build_demo(args.output, progress=stage)
