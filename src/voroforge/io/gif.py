"""Animated GIF of a parameter sweep: one frame per set of cells, drawn by the PNG renderer."""

from __future__ import annotations

from pathlib import Path

from PIL import Image

from ..config import GIF_MAX_BYTES
from .atomic import write_atomically
from .png import render_image

__all__ = ["GIF_MAX_BYTES", "palette_frame", "sweep_frames", "write_gif"]


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


def palette_frame(image: Image.Image) -> Image.Image:
    """``image`` as one GIF frame, one byte a pixel.

    Its own adaptive palette of 255 colours, no dithering (crisp edges, deterministic
    bytes). :func:`write_gif` takes such frames as they are, so a caller that shows one
    frame several times keeps only this.
    """
    return image.convert("RGB").quantize(colors=255, method=Image.Quantize.MEDIANCUT, dither=0)


def write_gif(frames, path, *, fps: float = 8.0, loop: int = 0, size: int = 400, **options) -> Path:
    """Write an animated GIF.

    Parameters
    ----------
    frames : iterable of PIL images, or of cells (see :func:`sweep_frames`)
        The frames in order (a generator is consumed one frame at a time, each kept only
        as its palette image; a palette ("P") image is taken as it is, see
        :func:`palette_frame`); images of different sizes are centred on the largest.
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
        The file written, atomically: an interrupted write leaves the old file or none.

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
    if not fps > 0:
        raise ValueError(f"fps must be positive; got {fps!r}")
    # Each frame is quantized as it comes (1 byte a pixel): a generator of frames is never
    # held as full-colour images, only as the palette images the GIF is made of.
    canvas = []
    for f in frames:
        im = f if isinstance(f, Image.Image) else sweep_frames([f], size=size, **options)[0]
        canvas.append(im if im.mode == "P" else palette_frame(im))
        del im
    if not canvas:
        raise ValueError("write_gif needs at least one frame")
    w = max(im.width for im in canvas)
    h = max(im.height for im in canvas)
    for i, im in enumerate(canvas):
        if im.size != (w, h):  # centred on the largest, the rest in its own corner colour
            bg = Image.new("P", (w, h), im.getpixel((0, 0)))
            bg.putpalette(im.getpalette())
            bg.paste(im, ((w - im.width) // 2, (h - im.height) // 2))
            canvas[i] = bg
    duration = max(20, int(round(1000.0 / fps / 10.0)) * 10)
    first = canvas.pop(0)
    canvas.reverse()  # handed to Pillow one by one, so that only its copy stays held

    def rest():
        while canvas:
            yield canvas.pop()

    return write_atomically(
        path,
        lambda tmp: first.save(
            tmp,
            format="GIF",
            save_all=True,
            append_images=rest(),
            duration=duration,
            loop=loop,
            optimize=False,
            disposal=1,
        ),
    )
