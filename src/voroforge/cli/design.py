"""``voroforge build``, ``new`` and ``check``: the design-file commands."""

from __future__ import annotations

import argparse
import sys
from contextlib import contextmanager
from pathlib import Path

from .progress import Stage

__all__ = [
    "add_parsers",
    "design_warnings",
    "overrides",
    "run_build",
    "run_check",
    "run_new",
]

_BUILD_EPILOG = """\
Writes every output the design file names (output.formats) into DIR and prints the paths.
Same file and seed -> byte-identical files.

examples:
  voroforge build examples/laser-panel.toml -o out
  voroforge build panel.toml --set seeds.radius=25 --set cells.web=4
  voroforge build panel.toml --preview          only the PNG preview, quickly
"""

_NEW_EPILOG = """\
examples:
  voroforge new                  writes design.toml
  voroforge new panel.toml       then: voroforge build panel.toml -o out
"""

_CHECK_EPILOG = """\
Checks the limits of the design's [fabrication] table: min_web, min_opening, tool_radius,
and loose islands. Prints one row per violation with its location, worst first (the 50
worst unless --all; a report = true build writes every row to DESIGN-check.txt).

examples:
  voroforge check panel.toml
  voroforge check panel.toml --strict --set fabrication.min_web=4
  voroforge check panel.toml --all
  voroforge check panel.toml --overlay check.svg   every violation marked, by kind
"""

#: Suffixes ``check --overlay`` can draw.
OVERLAY_SUFFIXES = (".png", ".svg")


def _add_set(sub: argparse.ArgumentParser) -> None:
    sub.add_argument(
        "--set",
        metavar="KEY=VALUE",
        action="append",
        default=[],
        help="override a key of the design file, e.g. seeds.count=500 (repeatable)",
    )


def add_parsers(commands, formatter_class) -> None:
    """Add ``build``, ``new`` and ``check`` to ``commands`` (see :mod:`voroforge.cli`)."""
    build = commands.add_parser(
        "build",
        help="build a TOML design file into SVG/DXF/PNG/GeoJSON/GIF",
        description="Build DESIGN (a TOML design file) and write the files it names.",
        epilog=_BUILD_EPILOG,
        formatter_class=formatter_class,
    )
    build.add_argument("design", metavar="DESIGN", help="design file (.toml)")
    build.add_argument(
        "-o", "--output", metavar="DIR", default="out", help="output folder (default: out)"
    )
    _add_set(build)
    build.add_argument(
        "--preview", action="store_true", help="write only the PNG preview (at most 800 px)"
    )
    build.set_defaults(run=run_build)

    new = commands.add_parser(
        "new",
        help="write a commented starter design file",
        description="Write a commented starter design file to PATH (default design.toml).",
        epilog=_NEW_EPILOG,
        formatter_class=formatter_class,
    )
    new.add_argument("path", metavar="PATH", nargs="?", default="design.toml")
    new.add_argument("--force", action="store_true", help="overwrite an existing file")
    new.set_defaults(run=run_new)

    check = commands.add_parser(
        "check",
        help="fabrication check of a design file (thin webs, small openings, corners)",
        description="Build DESIGN's geometry and check it against its [fabrication] limits.",
        epilog=_CHECK_EPILOG,
        formatter_class=formatter_class,
    )
    check.add_argument("design", metavar="DESIGN", help="design file (.toml)")
    _add_set(check)
    check.add_argument(
        "--strict", action="store_true", help="exit with status 1 when there are violations"
    )
    check.add_argument(
        "--all", action="store_true", help="list every violation (default: the worst 50)"
    )
    check.add_argument(
        "--overlay",
        metavar="FILE",
        help="also draw the panel with every violation circled (.png or .svg)",
    )
    check.set_defaults(run=run_check)


def overrides(pairs: list[str]) -> dict:
    """``["KEY=VALUE", ...]`` from ``--set`` -> ``{KEY: VALUE}`` (values stay strings).

    Parameters
    ----------
    pairs : list of str
        The ``--set`` arguments.

    Returns
    -------
    dict of str to str

    Raises
    ------
    ValueError
        For an argument without ``=`` or with an empty key.
    """
    out = {}
    for pair in pairs:
        key, sep, value = pair.partition("=")
        if not sep or not key.strip():
            raise ValueError(f"--set {pair!r}: expected KEY=VALUE, e.g. seeds.count=500")
        out[key.strip()] = value.strip()
    return out


@contextmanager
def design_warnings(design):
    """Print the design's warnings to stderr, one line each, once each, when the block ends.

    ``voroforge: warning: DESIGN: <message>`` for :class:`~voroforge.design.build.DesignWarning`
    and :class:`~voroforge.design.designfile.UnusedKeyWarning` (a key is named once, with its
    line: a GIF sweep loads the design again); other warnings are shown as Python shows them.
    Printed also when the block raises (before the error: a key the design does not read
    may be why it fails).
    """
    import warnings

    from ..design.build import DesignWarning
    from ..design.designfile import UnusedKeyWarning
    from . import PROG

    caught: list = []
    try:
        with warnings.catch_warnings(record=True) as recorded:
            warnings.simplefilter("always", DesignWarning)
            warnings.simplefilter("always", UnusedKeyWarning)
            try:
                yield
            finally:
                caught = list(recorded)
    finally:
        # shown once the recording is undone: inside it, showwarning appended to the list
        # being read and the loop never ended (a build with any other warning hung)
        seen = set()
        for w in caught:
            if issubclass(w.category, UnusedKeyWarning | DesignWarning):
                once = getattr(w.message, "issue", None)
                once = str(w.message) if once is None else once.key
                if once not in seen:
                    seen.add(once)
                    print(f"{PROG}: warning: {design}: {w.message}", file=sys.stderr)
            else:
                warnings.showwarning(w.message, w.category, w.filename, w.lineno)


def run_build(args: argparse.Namespace, stage: Stage) -> list[Path]:
    """Run ``voroforge build``; design warnings go to stderr as one line each."""
    from ..design.build import build

    with design_warnings(args.design):
        return build(
            args.design,
            args.output,
            overrides=overrides(args.set),
            preview=args.preview,
            progress=stage,
        )


def run_new(args: argparse.Namespace, stage: Stage) -> list[Path]:
    """Run ``voroforge new``; returns the file written."""
    from ..design.build import write_starter

    return [write_starter(args.path, overwrite=args.force)]


def run_check(args: argparse.Namespace, stage: Stage) -> int:
    """Run ``voroforge check``: print the report; 1 under ``--strict`` with violations."""
    from ..design.build import check_design

    suffix = Path(args.overlay).suffix.lower() if args.overlay else None
    if args.overlay and suffix not in OVERLAY_SUFFIXES:
        raise ValueError(f"{args.overlay}: the overlay must be a .png or .svg file")
    with design_warnings(args.design):
        report = check_design(args.design, overrides=overrides(args.set), progress=stage)
    print(report.table(max_rows=None if args.all else 50))
    if args.overlay:
        (report.write_png if suffix == ".png" else report.write_svg)(args.overlay)
    return 1 if (args.strict and not report.ok) else 0
