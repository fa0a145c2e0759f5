"""``voroforge studio`` (edit a design live in the browser) and ``voroforge animate``."""

from __future__ import annotations

import argparse
import re

from .outputs import OneOutput
from .progress import Stage

__all__ = ["add_parser", "run", "run_animate"]

_ANIMATE_EPILOG = """\
Plays the design's [animation] table (keyframes of any key, e.g. an attractor moving along
a path) and writes the frames: the seeds of frame 0 stay (moved, not re-sampled), so the
pattern morphs; cell colours are stable from frame to frame.

Every file is written whole or not at all (Ctrl-C leaves the previous one). A folder gets
frame-0001.png ...: older frame-NNNN.png files past the new count are removed, so the folder
holds this animation only (other files are left alone). Frames are streamed to a folder or
an MP4; a GIF holds every frame (1 byte a pixel) until it is written, so frames x size^2
past 2 GB is refused: write a folder or an MP4 for longer, larger animations.

examples:
  voroforge animate examples/facade-panel.toml -o sun.gif
  voroforge animate panel.toml -o frames/ --frames 60      PNG frames frame-0001.png ...
  voroforge animate panel.toml -o sun.mp4 --fps 24         needs imageio-ffmpeg
"""

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
    """Add ``studio`` to ``commands`` (see :mod:`voroforge.cli`)."""
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

    a = commands.add_parser(
        "animate",
        help="write the frames of a design's [animation] as a GIF, MP4 or PNG frames",
        description="Play DESIGN's [animation] table and write the frames.",
        epilog=_ANIMATE_EPILOG,
        formatter_class=formatter_class,
    )
    a.add_argument("design", metavar="DESIGN", help="design file (.toml) with [animation]")
    a.add_argument(
        "-o",
        "--output",
        metavar="OUT",
        action=OneOutput,
        required=True,
        help="anim.gif, anim.mp4 or a folder",
    )
    a.add_argument("--frames", type=int, help="number of frames (default: animation.frames)")
    a.add_argument("--fps", type=float, help="frames per second (default: animation.fps)")
    a.add_argument("--size", type=int, default=480, help="frame size in pixels (default 480)")
    a.set_defaults(run=run_animate)


def run(args: argparse.Namespace, stage: Stage) -> int:
    """Run the studio until Ctrl+C; returns exit status 0."""
    if not 0 <= args.port <= 65535:
        raise ValueError(f"--port {args.port}: expected 0 to 65535")
    import warnings

    from ..design.designfile import UnusedKeyWarning, load
    from ..studio.server import serve
    from .design import design_warnings

    if args.design is not None:
        with design_warnings(args.design):
            load(args.design)  # errors with file and line; unused keys said once, here
    with warnings.catch_warnings():
        # the page shows them with each edit (state_message): not again on the console
        warnings.simplefilter("ignore", UnusedKeyWarning)
        try:
            serve(args.design, host=args.host, port=args.port, open_browser=not args.no_browser)
        except OSError as exc:
            if exc.filename is not None or not _address_error(exc):
                raise
            # "Address already in use" said which address (checker16 F9)
            raise ValueError(f"--host {args.host} --port {args.port}: {exc.strerror}") from None
    return 0


def _address_error(exc: OSError) -> bool:
    """Whether ``exc`` is about the address the studio listens on (in use, not there, ...)."""
    import errno
    import socket

    return isinstance(exc, socket.gaierror) or exc.errno in (
        errno.EADDRINUSE,
        errno.EADDRNOTAVAIL,
        errno.EACCES,
    )


def run_animate(args: argparse.Namespace, stage: Stage) -> list:
    """Run ``voroforge animate``; returns the files written."""
    import warnings

    from ..design.designfile import UnusedKeyWarning

    with warnings.catch_warnings():
        # said once, as the design is first loaded (design_warnings): each frame loads it again
        warnings.simplefilter("ignore", UnusedKeyWarning)
        return _animate(args, stage)


def _animate(args: argparse.Namespace, stage: Stage) -> list:
    from pathlib import Path

    out = Path(args.output)
    suffix = out.suffix.lower()
    if suffix not in ("", ".gif", ".mp4"):
        raise ValueError(f"{out}: write a .gif, an .mp4 or a folder of PNG frames")
    if args.frames is not None and not 2 <= args.frames <= 2000:
        raise ValueError(f"--frames {args.frames}: expected 2 to 2000")
    if args.fps is not None and not 0 < args.fps <= 60:
        raise ValueError(f"--fps {args.fps}: expected more than 0, at most 60")
    if not 32 <= args.size <= 4096:
        raise ValueError(f"--size {args.size}: expected 32 to 4096")
    if suffix == ".mp4":
        try:
            import imageio_ffmpeg  # noqa: F401
        except ImportError:
            raise ValueError(
                "MP4 needs imageio-ffmpeg (pip install imageio-ffmpeg); "
                "or write a .gif or a folder of PNG frames"
            ) from None
    from ..design.build import render_preview
    from ..design.designfile import load, located
    from ..io.atomic import write_atomically
    from ..studio.animation import frames
    from .design import design_warnings

    with design_warnings(args.design):  # its filter says them even under the caller's "ignore"
        design, _ = load(args.design)
    fps = args.fps or (design.animation.fps if design.animation else 12.0)
    count = args.frames or (design.animation.frames if design.animation else 0)
    if suffix == ".gif":
        from ..io.gif import GIF_MAX_BYTES, write_gif

        need = count * args.size**2  # at most: 1 byte a pixel, the longer side --size
        if need > GIF_MAX_BYTES:
            raise ValueError(
                f"a GIF of {count} frames of up to {args.size} x {args.size} px needs up to "
                f"{need / 1e9:.1f} GB of memory (at most {GIF_MAX_BYTES / 1e9:.1f} GB): "
                "use fewer --frames, a smaller --size, or write an .mp4 or a folder of PNG "
                "frames (streamed)"
            )

    def images():  # one frame at a time: nothing holds the rendered frames
        with located(args.design):
            for k, result in enumerate(frames(args.design, count=args.frames)):
                stage(f"frame {k + 1}")
                yield render_preview(result, size=args.size)

    if suffix == ".gif":
        return [write_gif(images(), out, fps=fps)]
    if suffix == ".mp4":
        import imageio.v2 as imageio
        import numpy as np

        def write_mp4(tmp):
            with imageio.get_writer(tmp, fps=fps, macro_block_size=1) as w:
                for im in images():
                    rgb = np.asarray(im.convert("RGB"))
                    # H.264 in yuv420p needs even sides: repeat the last row/column where odd
                    pad = ((0, rgb.shape[0] % 2), (0, rgb.shape[1] % 2), (0, 0))
                    w.append_data(np.pad(rgb, pad, mode="edge"))
            if Path(tmp).stat().st_size == 0:
                raise ValueError(f"{out}: ffmpeg wrote nothing (see its messages above)")

        return [write_atomically(out, write_mp4)]
    return _write_frames(images(), out)


_FRAME = re.compile(r"frame-(\d{4})\.png")


def _write_frames(images, out) -> list:
    """Write ``frame-0001.png ...`` into the folder ``out``; remove older frames past them.

    The frames are drawn into a hidden folder inside ``out`` and moved into place once all
    are drawn: Ctrl-C leaves the previous animation as it was. Files named like our frames
    (``frame-NNNN.png``) numbered past the new count are removed, so the folder holds this
    animation only; other files are left alone.
    """
    import shutil
    import tempfile
    from pathlib import Path

    out.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix=".frames-", dir=out))
    try:
        names = []
        for k, im in enumerate(images, start=1):
            names.append(f"frame-{k:04d}.png")
            im.save(work / names[-1], format="PNG")
        for name in names:
            (work / name).replace(out / name)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    for old in out.iterdir():
        m = _FRAME.fullmatch(old.name)
        if m and int(m.group(1)) > len(names) and old.is_file():
            old.unlink()
    return [out / name for name in names]
