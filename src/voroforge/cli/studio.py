"""``voroforge studio``: edit a design live in the browser."""

from __future__ import annotations

import argparse

from .progress import Stage

__all__ = ["add_parser", "run"]

_EPILOG = """\
Opens a local page (http://127.0.0.1:PORT/) that draws the design and redraws it as you
edit: drag seeds, click to add one, shift-click to remove one, drag attractor points and
curve handles, move the sliders (one per numeric parameter). Fabrication violations are
drawn live; Save writes TOML (and a seeds CSV for hand-placed seeds) into the design's
folder that `voroforge build` turns into the files the page exports, byte for byte.

examples:
  voroforge studio examples/laser-panel.toml
  voroforge studio panel.toml --port 9000 --no-browser
  voroforge studio                       the starter design, saved into this folder
"""


def add_parser(commands, formatter_class) -> None:
    """Add ``studio`` to argparse ``commands``.

    Parameters
    ----------
    commands : argparse subparsers action
        Where to add it.
    formatter_class : type
        Help formatter of the subcommand.
    """
    p = commands.add_parser(
        "studio",
        help="edit a design live in the browser (drag seeds, sliders, live checks)",
        description="Serve a local page that edits DESIGN live.",
        epilog=_EPILOG,
        formatter_class=formatter_class,
    )
    p.add_argument("design", metavar="DESIGN", nargs="?", help="design file (.toml)")
    p.add_argument("--port", type=int, default=8765, help="TCP port (default 8765; 0: any)")
    p.add_argument(
        "--host",
        default="127.0.0.1",
        help="address to listen on (default 127.0.0.1; others print a warning)",
    )
    p.add_argument("--no-browser", action="store_true", help="do not open a browser")
    p.set_defaults(run=run)


def run(args: argparse.Namespace, stage: Stage) -> int:
    """Run the studio until Ctrl+C; returns exit status 0."""
    if not 0 <= args.port <= 65535:
        raise ValueError(f"--port {args.port}: expected 0 to 65535")
    from ..studio.server import serve

    serve(args.design, host=args.host, port=args.port, open_browser=not args.no_browser)
    return 0
