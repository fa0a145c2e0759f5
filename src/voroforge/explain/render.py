"""Frames of Fortune's sweep (pillow): sweep line, beach line, circle events, edges, sites.

Each frame shows the sweep line at one height and the state of :func:`trace` there:

* the sweep line (red),
* the beach line: each arc of the lower envelope of the swept sites' parabolas (blue),
* pending circle events: their circle (thin, violet) and the event point at its bottom,
* finished Voronoi edges (black) and the edges still growing at the breakpoints (orange),
* swept sites (black dots) and sites the sweep has not reached yet (grey dots).

The last frame shows the finished diagram. Frames are drawn in a fixed palette, so the GIF
has no dithering and every colour means one thing.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..config import GIF_MAX_SIDE, MAX_PIXELS
from ..io.atomic import write_atomically
from .fortune import FortuneTrace, breakpoint_x, parabola_y, trace

__all__ = ["COLORS", "frame_size", "render_frames", "sweep_positions", "write_gif"]

#: Palette index -> role and RGB colour.
COLORS = {
    "background": (255, 255, 255),
    "sweep": (220, 40, 40),
    "beach": (40, 90, 200),
    "circle": (170, 120, 210),
    "event": (120, 40, 170),
    "edge": (20, 20, 20),
    "growing": (240, 140, 20),
    "site": (20, 20, 20),
    "pending_site": (175, 175, 175),
    "text": (90, 90, 90),
}
_INDEX = {name: i for i, name in enumerate(COLORS)}


def frame_size(bounds, size: int) -> tuple[int, int]:
    """``(width, height)`` in pixels: the longer side of ``bounds`` gets ``size`` pixels."""
    bw = bounds[2] - bounds[0]
    bh = bounds[3] - bounds[1]
    if bw >= bh:
        return size, max(1, round(size * bh / bw))
    return max(1, round(size * bw / bh)), size


def sweep_positions(bounds, frames: int) -> np.ndarray:
    """Sweep height of each frame but the last: from the top of ``bounds`` to its bottom.

    Returns
    -------
    (frames - 1,) float64
        Decreasing heights; the last frame shows the finished diagram instead.
    """
    return np.linspace(bounds[3], bounds[1], frames - 1)


class _Canvas:
    """Data -> pixel mapping and drawing helpers over one pillow image in "P" mode."""

    def __init__(self, bounds, width, height):
        from PIL import Image, ImageDraw

        self.box = bounds
        self.w, self.h = width, height
        self.sx = width / (bounds[2] - bounds[0])
        self.sy = height / (bounds[3] - bounds[1])
        self.img = Image.new("P", (width, height), _INDEX["background"])
        flat = [v for rgb in COLORS.values() for v in rgb]
        self.img.putpalette(flat + [0] * (768 - len(flat)))
        self.draw = ImageDraw.Draw(self.img)
        # Coordinates far outside the picture are clamped to this band, in pixels.
        self.lim = 4.0 * max(width, height)

    def px(self, x, y):
        u = (x - self.box[0]) * self.sx
        v = (self.box[3] - y) * self.sy
        return (min(max(u, -self.lim), self.lim), min(max(v, -self.lim), self.lim))

    def line(self, p, q, color, width=1):
        self.draw.line([self.px(*p), self.px(*q)], fill=_INDEX[color], width=width)

    def polyline(self, xs, ys, color, width=1):
        pts = [self.px(x, y) for x, y in zip(xs, ys, strict=True)]
        if len(pts) >= 2:
            self.draw.line(pts, fill=_INDEX[color], width=width)

    def dot(self, p, r, color, outline=None):
        u, v = self.px(*p)
        self.draw.ellipse(
            [u - r, v - r, u + r, v + r],
            fill=_INDEX[color],
            outline=None if outline is None else _INDEX[outline],
        )

    def circle(self, centre, radius, color):
        u, v = self.px(*centre)
        ru, rv = radius * self.sx, radius * self.sy
        if ru < self.lim:
            self.draw.ellipse([u - ru, v - rv, u + ru, v + rv], outline=_INDEX[color])

    def text(self, xy, s):
        self.draw.text(xy, s, fill=_INDEX["text"])


def _piece_points(tr: FortuneTrace, i, j, start, end, sweep=None):
    """End points of an edge piece with infinite ends replaced by far points."""
    a, b = tr.sites[i], tr.sites[j]
    far = 4.0 * max(tr.bounds[2] - tr.bounds[0], tr.bounds[3] - tr.bounds[1])
    move = np.array([b[1] - a[1], a[0] - b[0]])
    move = move / math.hypot(*move)
    if start is None:  # sites on the first line: a vertical edge from above
        base = end if end is not None else (0.5 * (a[0] + b[0]), tr.bounds[3])
        start = (base[0] - far * move[0], max(base[1], tr.bounds[3]) + far)
    if end is None:
        end = (start[0] + far * move[0], start[1] + far * move[1])
    return start, end


def _breakpoint_point(tr, left, right, sweep):
    """Current position of the breakpoint ``left | right`` (None if above the picture)."""
    a, b = tuple(tr.sites[left]), tuple(tr.sites[right])
    x = breakpoint_x(a, b, sweep)
    top = a if a[1] - sweep >= b[1] - sweep else b  # the non-degenerate parabola
    if top[1] - sweep <= 0.0:
        return None
    return (x, float(parabola_y(top, x, sweep)))


def _draw_state(cv: _Canvas, tr: FortuneTrace, sweep: float):
    st = tr.state_at(sweep)
    xmin, ymin, xmax, ymax = tr.bounds
    step = 1.5 / cv.sx
    # finished edges
    for i, j, start, end in tr.segments[: st.finished]:
        p, q = _piece_points(tr, i, j, start, end)
        cv.line(p, q, "edge", 2)
    # growing edges: from where they started to the breakpoint's position now
    for k, start in enumerate(st.starts):
        left, right = st.arcs[k], st.arcs[k + 1]
        q = _breakpoint_point(tr, left, right, sweep)
        if q is None:
            x = breakpoint_x(tuple(tr.sites[left]), tuple(tr.sites[right]), sweep)
            q = (x, sweep)
        p = start if start is not None else (q[0], ymax + (ymax - ymin))
        cv.line(p, q, "growing", 2)
    # pending circle events
    for ev in st.pending:
        cv.circle(ev.centre, ev.radius, "circle")
        cv.dot((ev.centre[0], ev.y), 3, "event")
    # beach line
    n = len(st.arcs)
    for k, s in enumerate(st.arcs):
        site = tuple(tr.sites[s])
        lo = xmin if k == 0 else breakpoint_x(tuple(tr.sites[st.arcs[k - 1]]), site, sweep)
        hi = xmax if k == n - 1 else breakpoint_x(site, tuple(tr.sites[st.arcs[k + 1]]), sweep)
        lo, hi = max(lo, xmin), min(hi, xmax)
        if site[1] - sweep <= 0.0:  # a site on the sweep line: its "parabola" is a ray up
            neighbour = st.arcs[k - 1] if k > 0 else (st.arcs[k + 1] if n > 1 else None)
            top = ymax + (ymax - ymin)
            if neighbour is not None and tr.sites[neighbour][1] > sweep:
                top = float(parabola_y(tuple(tr.sites[neighbour]), site[0], sweep))
            cv.line(site, (site[0], top), "beach", 2)
            continue
        if hi <= lo:
            continue
        xs = np.append(np.arange(lo, hi, step), hi)
        cv.polyline(xs, parabola_y(site, xs, sweep), "beach", 2)
    # sweep line
    cv.line((xmin - (xmax - xmin), sweep), (xmax + (xmax - xmin), sweep), "sweep", 2)
    # sites
    swept = set(tr.order[: st.swept].tolist())
    for s, p in enumerate(tr.sites):
        cv.dot(tuple(p), 3, "site" if s in swept else "pending_site")
    cv.text(
        (4, 2),
        f"sites {st.swept}/{len(tr.sites)}  circle events pending {len(st.pending)}",
    )


def _draw_final(cv: _Canvas, tr: FortuneTrace):
    for p, q in tr.edges().coords:
        cv.line(tuple(p), tuple(q), "edge", 2)
    for p in tr.sites:
        cv.dot(tuple(p), 3, "site")
    cv.text((4, 2), f"Voronoi diagram of {len(tr.sites)} sites")


def render_frames(points_or_trace, *, frames: int = 60, size: int = 480) -> list:
    """Draw the sweep as a list of pillow images.

    Parameters
    ----------
    points_or_trace : (n, 2) array_like or FortuneTrace
        Sites (traced with :func:`voroforge.explain.fortune.trace`) or a finished trace.
    frames : int
        Number of frames, at least 2 and at most the picture's height in pixels (so the
        sweep line moves in every frame). The last frame shows the finished diagram.
    size : int
        Pixels along the longer side of the picture, 16 to ``GIF_MAX_SIDE`` (8192); all the
        frames together hold at most ``config.MAX_PIXELS`` pixels.

    Returns
    -------
    list of PIL.Image.Image
        ``frames`` images in "P" mode with the palette :data:`COLORS`.

    Raises
    ------
    ValueError
        For a bad ``frames`` or ``size``, or bad points.
    """
    if not isinstance(size, int) or isinstance(size, bool) or not 16 <= size <= GIF_MAX_SIDE:
        raise ValueError(f"size must be an int from 16 to {GIF_MAX_SIDE} pixels; got {size!r}")
    tr = points_or_trace if isinstance(points_or_trace, FortuneTrace) else trace(points_or_trace)
    width, height = frame_size(tr.bounds, size)
    if not isinstance(frames, int) or isinstance(frames, bool) or not 2 <= frames <= height:
        raise ValueError(
            f"frames must be an int from 2 to the picture's height ({height} px) so that the "
            f"sweep moves every frame; got {frames!r}"
        )
    if frames * width * height > MAX_PIXELS:
        raise ValueError(
            f"{frames} frames of {width} x {height} px are {frames * width * height:,} pixels, "
            f"at most {MAX_PIXELS:,}: use fewer frames or a smaller size"
        )
    out = []
    for sweep in sweep_positions(tr.bounds, frames):
        cv = _Canvas(tr.bounds, width, height)
        _draw_state(cv, tr, float(sweep))
        out.append(cv.img)
    cv = _Canvas(tr.bounds, width, height)
    _draw_final(cv, tr)
    out.append(cv.img)
    return out


def write_gif(
    points_or_trace, path, *, frames: int = 60, size: int = 480, duration_ms: int = 80
) -> Path:
    """Write the animation of Fortune's sweep as a looping GIF.

    Parameters
    ----------
    points_or_trace : (n, 2) array_like or FortuneTrace
        Sites, or a trace from :func:`voroforge.explain.fortune.trace`.
    path : str or os.PathLike
        Output ``.gif`` file.
    frames, size : int
        See :func:`render_frames`.
    duration_ms : int
        Display time of each frame; the last (finished diagram) stays 25 times longer.

    Returns
    -------
    pathlib.Path
        The path written.
    """
    images = render_frames(points_or_trace, frames=frames, size=size)
    durations = [duration_ms] * (len(images) - 1) + [25 * duration_ms]
    return write_atomically(
        path,
        lambda tmp: images[0].save(
            tmp,
            format="GIF",
            save_all=True,
            append_images=images[1:],
            duration=durations,
            loop=0,
            optimize=False,
            disposal=1,
        ),
    )
