"""What every reader does first: find the file, and check numbers and options."""

from __future__ import annotations

import math
import warnings
from pathlib import Path

__all__ = ["existing_file", "finite_number", "open_image", "parse_number", "positive_number"]


def existing_file(path) -> Path:
    """Return ``path`` as a ``Path`` after checking that it is an existing file.

    Parameters
    ----------
    path : str or Path
        The file to read.

    Returns
    -------
    Path

    Raises
    ------
    ValueError
        ``"<path>: no such file"`` or ``"<path>: is a directory, not a file"``.
    """
    path = Path(path)
    if not path.exists():
        raise ValueError(f"{path}: no such file")
    if path.is_dir():
        raise ValueError(f"{path}: is a directory, not a file")
    return path


def parse_number(token: str) -> float | None:
    """``float(token)``, or ``None`` when the token is not a number.

    Parameters
    ----------
    token : str
        One field of a text file.

    Returns
    -------
    float or None
    """
    try:
        return float(token)
    except ValueError:
        return None


def finite_number(value, name: str) -> float:
    """``float(value)``, checked to be a finite number.

    Parameters
    ----------
    value : object
        The candidate.
    name : str
        How error messages call it.

    Returns
    -------
    float

    Raises
    ------
    ValueError
        ``"<name> must be a number"`` or ``"<name> must be finite"``.
    """
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return v


def positive_number(value, name: str) -> float:
    """:func:`finite_number`, checked to be ``> 0`` (a tolerance, a radius, a width).

    Parameters
    ----------
    value : object
        The candidate.
    name : str
        How error messages call it.

    Returns
    -------
    float

    Raises
    ------
    ValueError
        Not a finite number, or ``"<name> must be > 0"``.
    """
    v = finite_number(value, name)
    if v <= 0:
        raise ValueError(f"{name} must be > 0, got {value!r}")
    return v


def open_image(path):
    """``PIL.Image.open(path)`` up to Pillow's pixel limit, without its warning.

    Past the limit a ValueError naming the file (Pillow's DecompressionBombError is neither a
    ValueError nor an OSError: it gave tracebacks, and a studio message raised).
    """
    from PIL import Image

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", Image.DecompressionBombWarning)
            return Image.open(path)
    except Image.DecompressionBombError as exc:
        raise ValueError(f"{path}: {exc}") from None
