"""Animated GIF of a parameter sweep: one frame per set of cells, drawn by the PNG renderer."""

from __future__ import annotations

from pathlib import Path

from PIL import Image

from .png import render_image

__all__ = ["sweep_frames", "write_gif"]


def sweep_frames(frames, *, size: int = 400, **options) -> list[Image.Image]:
    """Render each frame's cells with :func:`voroforge.io.png.render_image`.

    Parameters
    ----------
    frames : sequence of (sequence of shapely geometries) or of dict
        Each item is the cells of one frame, or a dict of ``render_image`` arguments with
        at least ``geoms``.
    size : int
        Longer side of each frame in pixels.
    **options
        Passed to ``render_image`` for every frame (``colors``, ``boundary``, ...).

    Returns
    -------
    list of PIL.Image.Image
    """
    images = []
    for i, frame in enumerate(frames):
        args = dict(options)
        if isinstance(frame, dict):
            if "geoms" not in frame:
                raise ValueError(f"frame {i} has no 'geoms'")
            args.update(frame)
            geoms = args.pop("geoms")
        else:
            geoms = frame
        images.append(render_image(geoms, size=size, **args))
    return images


def write_gif(frames, path, *, fps: float = 8.0, loop: int = 0, size: int = 400, **options) -> Path:
    """Write an animated GIF.

    Parameters
    ----------
    frames : sequence of PIL images, or of cells (see :func:`sweep_frames`)
        The frames in order; images of different sizes are centred on the largest.
    path : str or Path
        Output file.
    fps : float
        Frames per second (GIF stores whole hundredths of a second per frame).
    loop : int
        Times to loop; 0 loops forever.
    size, **options
        Used to render frames that are not images yet.

    Returns
    -------
    Path
        The file written.

    Raises
    ------
    ValueError
        Without frames or with a non-positive ``fps``.

    Examples
    --------
    >>> import shapely, tempfile, pathlib
    >>> frames = [[shapely.box(0, 0, 1, 1).buffer(-r)] for r in (0.1, 0.2, 0.3)]
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "sweep.gif"
    >>> write_gif(frames, out, size=64).name
    'sweep.gif'
    """
    items = list(frames)
    if not items:
        raise ValueError("write_gif needs at least one frame")
    if not fps > 0:
        raise ValueError(f"fps must be positive; got {fps!r}")
    if all(isinstance(f, Image.Image) for f in items):
        images = items
    else:
        images = [
            f if isinstance(f, Image.Image) else sweep_frames([f], size=size, **options)[0]
            for f in items
        ]
    w = max(im.width for im in images)
    h = max(im.height for im in images)
    canvas = []
    for im in images:
        rgb = im.convert("RGB")
        if rgb.size != (w, h):
            bg = Image.new("RGB", (w, h), rgb.getpixel((0, 0)))
            bg.paste(rgb, ((w - rgb.width) // 2, (h - rgb.height) // 2))
            rgb = bg
        # One adaptive palette per frame, no dithering: crisp edges, deterministic bytes.
        canvas.append(rgb.quantize(colors=255, method=Image.Quantize.MEDIANCUT, dither=0))
    path = Path(path)
    duration = max(20, int(round(1000.0 / fps / 10.0)) * 10)
    canvas[0].save(
        path,
        save_all=True,
        append_images=canvas[1:],
        duration=duration,
        loop=loop,
        optimize=False,
        disposal=1,
    )
    return path
