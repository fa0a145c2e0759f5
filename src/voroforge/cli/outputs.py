"""Checks on a command's output paths before any work: a failing run writes nothing.

Each file is written atomically (``io.atomic``), but a command with several ``-o`` wrote
the first and then failed on the second (a folder that does not exist, a PNG too large to
draw). Everything that can be known about the outputs is checked here first.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Iterable
from pathlib import Path


class OneOutput(argparse.Action):
    """``-o`` of a command that writes one file: a second ``-o`` is a usage error.

    argparse's plain ``store`` kept the last one and silently wrote only that file.
    """

    def __call__(self, parser, namespace, values, option_string=None):
        """Store ``values``; refuse a second ``-o`` (argparse prints usage, exit 2)."""
        given = getattr(namespace, self.dest, None)
        if given is not None:
            raise argparse.ArgumentError(
                self, f"given twice ({given} and {values}); this command writes one file"
            )
        setattr(namespace, self.dest, values)


def unused_option(option: str, used_by: str) -> None:
    """Say on stderr that ``option`` was given but none of the outputs uses it (not an error)."""
    from . import PROG

    print(
        f"{PROG}: warning: {option} is used only by {used_by}; no output uses it", file=sys.stderr
    )


def check_outputs(
    outputs: Iterable, *, png: Callable[[], object] | None = None, inputs: Iterable = ()
) -> list[Path]:
    """The output paths, after checking their folders (and the PNG size) up front.

    Parameters
    ----------
    outputs : iterable of str or Path
        The ``-o`` arguments.
    png : callable, optional
        Called once when an output is a ``.png``: the writer's own size check (raises
        ``ValueError`` naming the size).
    inputs : iterable of str or Path
        The files the command reads: an output may not be one of them (``-o points.csv``
        replaced the points with the cells).

    Returns
    -------
    list of Path

    Raises
    ------
    ValueError
        An output is given twice (the second write replaced the first), an output's folder
        does not exist or is not a folder, an output is a folder or one of ``inputs``, or
        ``png`` refused the size.
    """
    paths = [Path(o) for o in outputs]
    seen = {}
    for path in paths:
        key = path.resolve()  # './a.svg', 'a.svg' and a link to it are one file
        if key in seen:
            also = "" if str(seen[key]) == str(path) else f" (as {seen[key]} and {path})"
            raise ValueError(f"{path}: given twice as an output{also}; write each file once")
        seen[key] = path
    for path in paths:
        folder = path.parent if str(path.parent) else Path(".")
        if not folder.is_dir():
            raise ValueError(f"{path}: output folder does not exist: {folder}")
        if path.is_dir():
            raise ValueError(f"{path}: is a folder, not a file to write")
        for given in inputs:
            if path.exists() and Path(given).exists() and path.samefile(given):
                raise ValueError(f"{path}: is the input file {given}; write elsewhere")
    if png is not None and any(p.suffix.lower() == ".png" for p in paths):
        png()
    return paths
