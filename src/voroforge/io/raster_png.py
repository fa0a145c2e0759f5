"""Raster Voronoi results to files: PNG images (pillow) and raw ``.npy`` fields."""

from __future__ import annotations

import colorsys
from pathlib import Path

import numpy as np

from ..engine.csr import unique

#: Fields of a raster result that can be drawn or saved.
FIELDS = ("labels", "distance", "f2", "edge")

#: Suffixes :func:`write_raster` understands: an image, or the field's raw values.
RASTER_SUFFIXES = (".png", ".npy")


def _base_colors(k: int = 12) -> np.ndarray:
    """``k`` soft colours with hues ``360 / k`` degrees apart, alternating in lightness."""
    out = []
    for i in range(k):
        hue = i / k
        sat, val = (0.30, 0.98) if i % 2 == 0 else (0.42, 0.88)
        out.append(colorsys.hsv_to_rgb(hue, sat, val))
    return np.round(np.array(out) * 255.0).astype(np.uint8)


#: Twelve soft, clearly different colours (RGB); touching cells never share one unless a
#: cell touches twelve or more differently coloured cells.
BASE_COLORS = _base_colors()


def label_adjacency(labels: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Which labels touch in an image (4- and 8-neighbourhood).

    Parameters
    ----------
    labels : (h, w) int
        Label of each pixel, in ``[0, n)``.
    n : int
        Number of labels.

    Returns
    -------
    indptr : (n + 1,) int64
        CSR row pointers: the neighbours of label ``i`` are ``indices[indptr[i]:indptr[i + 1]]``.
    indices : (k,) int64
        Neighbouring labels, sorted within each row, each pair listed from both sides.
    """
    lab = np.asarray(labels, dtype=np.int64)
    pairs = [
        (lab[:, :-1], lab[:, 1:]),
        (lab[:-1, :], lab[1:, :]),
        (lab[:-1, :-1], lab[1:, 1:]),
        (lab[:-1, 1:], lab[1:, :-1]),
    ]
    a = np.concatenate([p[0].ravel() for p in pairs])
    b = np.concatenate([p[1].ravel() for p in pairs])
    keep = a != b
    a, b = a[keep], b[keep]
    keys = unique(np.concatenate([a * n + b, b * n + a]))
    rows, cols = keys // n, keys % n
    indptr = np.zeros(n + 1, dtype=np.int64)
    np.add.at(indptr, rows + 1, 1)
    return np.cumsum(indptr), cols


def cell_colors(labels, *, seed: int = 0) -> np.ndarray:
    """One colour per label such that touching cells get different colours.

    A greedy colouring over :data:`BASE_COLORS` in increasing label order: label ``i`` takes
    the first colour, cycling from a start that depends on ``i`` and ``seed``, that no
    already coloured neighbour uses (if all twelve are taken, the least used among them).
    The result depends only on the image and ``seed``.

    Parameters
    ----------
    labels : (h, w) int
        Non-negative labels (site indices).
    seed : int
        Shifts the colour choice; the same seed always gives the same colours.

    Returns
    -------
    (n, 3) uint8
        RGB colour of each label ``0 .. labels.max()``.
    """
    lab = np.asarray(labels)
    n = int(lab.max()) + 1 if lab.size else 0
    k = len(BASE_COLORS)
    indptr, indices = label_adjacency(lab, n)
    choice = np.full(n, -1, dtype=np.int64)
    ip, ix = indptr.tolist(), indices.tolist()
    for i in range(n):
        used = [0] * k
        for j in ix[ip[i] : ip[i + 1]]:
            c = choice[j]
            if c >= 0:
                used[c] += 1
        first = (i * 5 + seed * 7) % k
        order = [(first + t) % k for t in range(k)]
        free = [c for c in order if used[c] == 0]
        choice[i] = free[0] if free else min(order, key=lambda c: used[c])
    return BASE_COLORS[choice]


def colorize(result, *, field: str = "labels", seed: int = 0) -> np.ndarray:
    """Image array of one field of a raster result.

    Parameters
    ----------
    result : RasterVoronoi
        From :func:`voroforge.rasterize`.
    field : {"labels", "distance", "f2", "edge"}
        ``labels``: one colour per cell (:func:`cell_colors`). ``distance`` (F1), ``f2`` and
        ``edge`` (F2 - F1): greyscale, black at 0 and white at the field's largest finite value
        (inf is white).
    seed : int
        Colour seed for ``labels``.

    Returns
    -------
    (h, w, 3) uint8 or (h, w) uint8
        RGB for labels, greyscale for distance fields.

    Raises
    ------
    ValueError
        For an unknown field, or ``f2``/``edge`` on a result computed without ``f2=True``.
    """
    values = field_values(result, field)  # checks the field
    if field == "labels":
        return cell_colors(values, seed=seed)[values]
    finite = np.isfinite(values)
    top = float(values[finite].max()) if finite.any() else 0.0
    scaled = np.ones(values.shape) if top <= 0.0 else np.where(finite, values / top, 1.0)
    return np.round(np.clip(scaled, 0.0, 1.0) * 255.0).astype(np.uint8)


def field_values(result, field: str) -> np.ndarray:
    """The raw array of one field: ``labels``, ``distance``, ``f2`` or ``edge``.

    Raises
    ------
    ValueError
        For an unknown field, or ``f2``/``edge`` on a result computed without ``f2=True``.
    """
    if field not in FIELDS:
        raise ValueError(f"field must be one of {FIELDS}; got {field!r}")
    if field in ("f2", "edge") and result.f2 is None:
        raise ValueError(f"field {field!r} needs a result computed with rasterize(..., f2=True)")
    return {
        "labels": lambda: result.labels,
        "distance": lambda: result.distance,
        "f2": lambda: result.f2,
        "edge": lambda: result.edge,
    }[field]()


def write_raster_png(result, path, *, field: str = "labels", seed: int = 0) -> Path:
    """Write one field of a raster result as a PNG.

    Parameters
    ----------
    result : RasterVoronoi
        From :func:`voroforge.rasterize`; row 0 is the top of the image.
    path : str or os.PathLike
        Output file.
    field : {"labels", "distance", "f2", "edge"}
        What to draw; see :func:`colorize`.
    seed : int
        Palette seed for ``labels``.

    Returns
    -------
    pathlib.Path
        The path written.

    Examples
    --------
    >>> import voroforge as vf, tempfile, os
    >>> from voroforge.io.raster_png import write_raster_png
    >>> r = vf.rasterize([[0, 0], [1, 1]], (8, 8))
    >>> p = write_raster_png(r, os.path.join(tempfile.mkdtemp(), "cells.png"))
    >>> p.suffix
    '.png'
    """
    from PIL import Image

    from .atomic import write_atomically

    img = Image.fromarray(np.ascontiguousarray(colorize(result, field=field, seed=seed)))
    return write_atomically(path, lambda tmp: img.save(tmp, format="PNG"))  # RGB or L


def write_raster(result, path, *, field: str = "labels", seed: int = 0) -> Path:
    """Write one field of a raster result as a PNG image or a raw ``.npy`` array, by suffix.

    Parameters
    ----------
    result : RasterVoronoi
        From :func:`voroforge.rasterize`.
    path : str or os.PathLike
        ``.png`` (:func:`write_raster_png`) or ``.npy`` (the field's values: ``(h, w)`` int32
        site indices for labels, float64 distances otherwise).
    field : {"labels", "distance", "f2", "edge"}
        What to write.
    seed : int
        Palette seed for a labels PNG.

    Returns
    -------
    pathlib.Path
        The path written.

    Raises
    ------
    ValueError
        For another suffix, an unknown field, or ``f2``/``edge`` without ``f2=True``.
    """
    out = Path(path)
    suffix = out.suffix.lower()
    if suffix not in RASTER_SUFFIXES:
        raise ValueError(f"{out}: raster output must be a .png or .npy file")
    if suffix == ".npy":
        from .atomic import write_atomically

        values = np.asarray(field_values(result, field))
        return write_atomically(out, lambda tmp: np.save(tmp, values))
    return write_raster_png(result, out, field=field, seed=seed)
