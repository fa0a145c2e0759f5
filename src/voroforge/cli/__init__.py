"""The ``voroforge`` command line: parse arguments, call the library, print what was written.

One module per group of commands (:mod:`.diagram`: voronoi and delaunay, :mod:`.demo`,
:mod:`.raster`, :mod:`.explain`, :mod:`.design`: build, new and check, ...). Each has
``add_parser(commands, formatter_class)`` (``add_parsers`` for several commands): it adds
its subcommands to ``commands``, the action of ``add_subparsers``, with that help
formatter, each with a ``run(args, stage)`` default, and :func:`main` calls it. No geometry
here: commands read with :mod:`voroforge.io`, compute with the library and write with
:mod:`voroforge.io`.
Nothing heavy is imported before a command runs, so ``--help`` and ``--version`` are quick.
"""

from __future__ import annotations

import argparse
import gc
import sys
from collections.abc import Sequence

from . import demo, design, diagram, explain, raster, studio
from . import scale as scale_cmd
from . import stipple as stipple_cmd
from . import voronoi3d as voronoi3d_cmd
from . import warmup as warmup_cmd
from .progress import progress

__all__ = ["PROG", "main"]

PROG = "voroforge"

_MAIN_EPILOG = """\
examples:
  voroforge demo -o out                      the flagship laser-cut panel: SVG, DXF, PNG
  voroforge voronoi points.csv -o cells.svg  Voronoi cells of points.csv as SVG
  voroforge voronoi points.csv -o cells.geojson --boundary domain.geojson
  voroforge delaunay points.csv -o triangles.svg
  voroforge raster points.csv -o cells.png --size 2048x2048 --method jfa
  voroforge explain fortune points.csv -o sweep.gif   animation of Fortune's sweep

Run 'voroforge COMMAND --help' for the options of one command.
"""


def _parser() -> argparse.ArgumentParser:
    from .. import __version__

    raw = argparse.RawDescriptionHelpFormatter
    parser = argparse.ArgumentParser(
        prog=PROG,
        description="Voronoi diagrams clipped to any domain, and Delaunay triangulations.",
        epilog=_MAIN_EPILOG,
        formatter_class=raw,
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    diagram.add_parsers(commands, raw)
    demo.add_parser(commands, raw)
    raster.add_parser(commands, raw)
    explain.add_parser(commands, raw)
    design.add_parsers(commands, raw)
    scale_cmd.add_parser(commands, raw)
    studio.add_parser(commands, raw)
    voronoi3d_cmd.add_parser(commands, raw)
    stipple_cmd.add_parser(commands, raw)
    warmup_cmd.add_parser(commands, raw)
    return parser


#: Commands that call no compiled kernel (``warmup`` runs its steps through :func:`main`).
_NO_KERNELS = frozenset({"new", "warmup"})


def _error(message: str) -> int:
    for line in str(message).splitlines() or [""]:  # a design file may have several issues
        print(f"{PROG}: error: {line}", file=sys.stderr)
    return 2


def entry() -> int:
    """The ``voroforge`` console script and ``python -m voroforge``: :func:`main`, then exit.

    Before the interpreter exits, the objects made so far are frozen out of the garbage
    collector: its final collection would otherwise walk everything numba and LLVM created
    (0.25-0.45 s of every command that ran a kernel, 0.04-0.05 s frozen). Nothing is lost:
    files are closed and written atomically before this point.
    """
    status = main()
    gc.freeze()
    return status


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments without the program name (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status: 0 on success, 2 on bad arguments or input (message on stderr), 1 from
        ``check --strict`` when the design breaks a fabrication limit.
    """
    try:
        args = _parser().parse_args(argv)
    except SystemExit as exc:  # --help, --version and argparse's own usage errors
        return exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 2)
    if args.command not in _NO_KERNELS:
        from .startup import preload_blas

        preload_blas()  # numba's first call then skips scipy.linalg's import (~0.13 s)
    try:
        with progress(sys.stderr.isatty()) as stage:
            written = args.run(args, stage)
    except ValueError as exc:
        return _error(str(exc))
    except OSError as exc:
        where = f": {exc.filename}" if exc.filename else ""
        return _error(f"{exc.strerror or exc}{where}")
    except KeyboardInterrupt:
        print(f"{PROG}: interrupted", file=sys.stderr)
        return 130
    if isinstance(written, int):  # commands that print their own report return a status
        return written
    for path in written:
        print(path)
    return 0
