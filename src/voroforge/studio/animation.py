"""Animated designs: keyframes for any key of a design file, frames that morph.

A design file's ``[animation]`` table (:class:`AnimationSection`) lists tracks: a dotted key
(as ``--set`` takes it) and its values at keyframes, e.g. an attractor moving along a path
or a web width breathing::

    [animation]
    frames = 36
    fps = 12

    [[animation.tracks]]
    key = "attractors.0.points.0"
    values = [[100, 300], [500, 100], [100, 300]]

Numbers and lists of numbers are interpolated linearly between keyframes (integers stay
integers), anything else steps. **The seeds stay coherent:** the sites of frame 0 are kept
(the same random stream, moved not re-sampled) and, with ``relax = k``, moved by ``k``
Lloyd steps per frame, so the pattern morphs instead of jumping; cell ``i`` is the same
site in every frame, so its colour is stable. :func:`frames` yields each frame's geometry
(:func:`voroforge.design.compute.compute`, reused per cell between frames); ``voroforge
animate`` writes them as a GIF or PNG frames, and the studio plays them on a timeline.
"""

from __future__ import annotations

import math
from typing import Annotated, Any

from pydantic import BaseModel, ConfigDict, Field, field_validator, model_validator

__all__ = [
    "AnimationSection",
    "Track",
    "frame_design",
    "frames",
    "named_error",
    "overrides_at",
    "value_at",
]


class _Model(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


#: Keys that choose the sites: every frame keeps frame 0's sites, so a track on them would
#: do nothing (design.seed also reseeds the openings and recursion: animate openings.seed)
_SITE_KEYS = ("seeds", "relax", "design.seed")
#: Of ``[output]``, what a frame's picture reads (``design.build.render_preview``): a track
#: on any other output key (formats, stem, sizes of files) changes no frame
_OUTPUT_DRAWN = ("output.layers", "output.png")


def _under(key: str, prefix: str) -> bool:
    return key == prefix or key.startswith(prefix + ".")


class Track(_Model):
    """``[[animation.tracks]]``: one key's keyframes.

    Not on ``seeds.*``, ``relax.*`` or ``design.seed``: every frame keeps frame 0's sites.
    """

    key: Annotated[str, Field(min_length=1, pattern=r"^[A-Za-z0-9_]+(\.[A-Za-z0-9_]+)*$")]
    values: Annotated[list[Any], Field(min_length=2)]
    times: list[float] | None = None

    @field_validator("key")
    @classmethod
    def _not_sites(cls, key: str) -> str:
        if any(_under(key, k) for k in _SITE_KEYS):
            raise ValueError(
                f"{key!r} cannot be animated: every frame keeps the sites of frame 0 "
                "(moved by animation.relax), so seeds.*, relax.* and design.seed stay as "
                "frame 0 has them; animate openings.seed for a random choice of openings"
            )
        if _under(key, "animation"):
            raise ValueError(f"{key!r} cannot be animated: it is the table being played")
        if _under(key, "output") and not any(_under(key, k) for k in _OUTPUT_DRAWN):
            raise ValueError(
                f"{key!r} cannot be animated: a frame's picture reads only "
                + " and ".join(_OUTPUT_DRAWN)
                + " of [output]"
            )
        return key

    @field_validator("values")
    @classmethod
    def _finite(cls, values: list) -> list:
        # inf between keyframes is nan (0 + (inf - 0) * 0): named here, as the file holds it
        def bad(v):
            if isinstance(v, list):
                return any(bad(x) for x in v)
            return isinstance(v, float) and not math.isfinite(v)

        for k, v in enumerate(values):
            if bad(v):
                raise ValueError(f"value {k} ({v!r}) is not finite")
        return values

    @model_validator(mode="after")
    def _times(self) -> Track:
        if self.times is not None:
            t = self.times
            if len(t) != len(self.values):
                raise ValueError(f"@times@ give one time per value ({len(self.values)})")
            if t[0] != 0 or t[-1] != 1 or any(b <= a for a, b in zip(t, t[1:], strict=False)):
                raise ValueError("@times@ must rise from 0 to 1, e.g. [0, 0.3, 1]")
        return self


class AnimationSection(_Model):
    """``[animation]``: frames interpolated between keyframes (see the module docstring)."""

    frames: Annotated[int, Field(ge=2, le=2000)] = 24
    fps: Annotated[float, Field(gt=0, le=60)] = 12.0
    relax: Annotated[int, Field(ge=0, le=20)] = 0
    loop: bool = True
    tracks: Annotated[list[Track], Field(min_length=1)]

    @model_validator(mode="after")
    def _one_track_a_key(self) -> AnimationSection:
        # a second track on a key (or inside it: attractors.0 and attractors.0.points)
        # silently replaced the first: the frames played one of them
        for j, t in enumerate(self.tracks):
            for i, s in enumerate(self.tracks[:j]):
                if _under(t.key, s.key) or _under(s.key, t.key):
                    raise ValueError(
                        f"@tracks.{j}.key@ {t.key!r} is animated by track {i} ({s.key!r}) "
                        "already: one track a key"
                    )
        return self


def _lerp(a, b, w: float):
    if isinstance(a, bool) or isinstance(b, bool):
        return a if w < 1 else b
    if isinstance(a, int | float) and isinstance(b, int | float):
        v = a + (b - a) * w
        return int(round(v)) if isinstance(a, int) and isinstance(b, int) else float(v)
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        return [_lerp(x, y, w) for x, y in zip(a, b, strict=True)]
    return a if w < 1 else b


def value_at(track: Track, u: float):
    """The track's value at time ``u`` in [0, 1] (linear between keyframes, else steps).

    Examples
    --------
    >>> t = Track(key="cells.web", values=[2, 6, 2])
    >>> [value_at(t, u) for u in (0, 0.25, 0.5, 1)]
    [2, 4, 6, 2]
    """
    n = len(track.values)
    times = track.times or [k / (n - 1) for k in range(n)]
    u = min(max(float(u), 0.0), 1.0)
    for k in range(n - 1):
        if u <= times[k + 1] or k == n - 2:
            span = times[k + 1] - times[k]
            w = (u - times[k]) / span if span > 0 else 1.0
            return _lerp(track.values[k], track.values[k + 1], min(max(w, 0.0), 1.0))
    return track.values[-1]


def overrides_at(section: AnimationSection, frame: int) -> dict:
    """``{key: value}`` of every track at frame ``frame`` (0 .. frames - 1)."""
    u = frame / (section.frames - 1)
    return {t.key: value_at(t, u) for t in section.tracks}


def frame_design(data: dict, section: AnimationSection, frame: int):
    """The validated design of one frame (the tracks' values set into ``data``).

    Raises
    ------
    DesignError
        Naming the track whose value does not fit (``animation.tracks.N``).
    """
    from ..design.designfile import DesignError, load

    overrides = overrides_at(section, frame)
    try:
        return load(data, overrides=overrides)[0]
    except DesignError as exc:
        raise named_error(exc, section, frame) from None


def named_error(exc, section: AnimationSection, frame: int):
    """A frame's DesignError with its issues moved to the track that set the key."""
    from ..design.designfile import DesignError, Issue

    keys = {t.key: i for i, t in enumerate(section.tracks)}
    issues = []
    for it in exc.issues:
        i = next((keys[k] for k in keys if it.key == k or it.key.startswith(k + ".")), None)
        where = f"animation.tracks.{i}" if i is not None else it.key
        message = it.message.removesuffix(" (from --set)")
        issues.append(Issue(where, None, f"frame {frame}: {it.key}: {message}"))
    return DesignError(issues)


def frames(source, *, base=None, sites=None, count: int | None = None, frame: bool = True):
    """The geometry of every frame of an animated design, in order.

    Parameters
    ----------
    source : str, Path or dict
        A design file with an ``[animation]`` table, or its mapping.
    base : Path, optional
        Folder for relative file names (default: the file's folder).
    sites : (n, 2) array_like, optional
        The sites of frame 0 (default: the design's own, from its ``[seeds]``).
    count : int, optional
        Number of frames (default: ``animation.frames``).
    frame : bool
        Compute each result's frame (boundary minus openings); False is faster.

    Yields
    ------
    Result
        One per frame; ``result.sites`` has the same rows in every frame.

    Raises
    ------
    DesignError
        Without an ``[animation]`` table, or for a frame whose values do not fit.
    """
    import tomllib
    from pathlib import Path

    import numpy as np

    from ..design.compute import compute
    from ..design.designfile import DesignError, load
    from ..design.relax import relax

    if isinstance(source, dict):
        data = source
    else:
        path = Path(source)
        load(path)  # file errors with lines
        data = tomllib.loads(path.read_text(encoding="utf-8-sig"))
        base = base or path.resolve().parent
    design, _ = load(data)
    section = design.animation
    if section is None:
        raise DesignError.at("animation", "the design has no [animation] table to play")
    if count is not None:
        section = section.model_copy(update={"frames": int(count)})
    previous = None
    for k in range(section.frames):
        d = frame_design(data, section, k)
        try:
            if k == 0 and sites is None:
                result = compute(d, base, frame=frame)
                sites = result.sites
            else:
                if k and section.relax:
                    sites = relax(sites, previous.domain, iterations=section.relax)
                result = compute(d, base, sites=np.asarray(sites), reuse=previous, frame=frame)
        except DesignError as exc:
            raise named_error(exc, section, k) from None
        previous = result
        yield result
