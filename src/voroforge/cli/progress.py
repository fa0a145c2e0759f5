"""Progress for long commands: a transient spinner on a terminal, silence otherwise."""

from __future__ import annotations

from collections.abc import Callable
from contextlib import contextmanager

__all__ = ["Stage", "progress"]

#: ``stage(name)``: called by a command with what it is doing now.
Stage = Callable[[str], None]


@contextmanager
def progress(enabled: bool):
    """Yield ``stage(name)``; shows a transient spinner on stderr when ``enabled``.

    Parameters
    ----------
    enabled : bool
        Show the spinner (the CLI passes ``sys.stderr.isatty()``).

    Yields
    ------
    Stage
        Call it with the name of each step.
    """
    if not enabled:
        yield lambda name: None
        return
    from rich.console import Console
    from rich.progress import Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

    bar = Progress(
        SpinnerColumn(),
        TextColumn("{task.description}"),
        TimeElapsedColumn(),
        console=Console(stderr=True),
        transient=True,
    )
    with bar:
        task = bar.add_task("starting", total=None)
        yield lambda name: bar.update(task, description=name)
