"""Input coercion and validation shared by the engine's public functions."""

from __future__ import annotations

import numpy as np

from ..kernels.dedupe import duplicate_of


def as_points(points, *, name: str = "points") -> np.ndarray:
    """Return a new C-contiguous ``(n, 2) float64`` copy of ``points`` or raise ``ValueError``.

    Parameters
    ----------
    points : (n, 2) array_like
        Coordinates. Lists of pairs, tuples and arrays of any real dtype are accepted.
    name : str
        Name used in error messages.

    Returns
    -------
    (n, 2) float64
        A fresh array (the caller's data is never aliased, so it can never be mutated).
    """
    try:
        raw = np.asarray(points)
        if raw.dtype.kind == "c":
            raise TypeError("complex values are not coordinates")
        arr = np.array(raw, dtype=np.float64, copy=True)
    except (TypeError, ValueError) as exc:
        raise ValueError(
            f"{name} must be an (n, 2) array of real numbers; could not convert it ({exc})"
        ) from None
    if arr.ndim == 1 and arr.size == 0:
        arr = arr.reshape(0, 2)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{name} must have shape (n, 2); got shape {arr.shape}")
    finite = np.isfinite(arr)
    if not finite.all():
        bad = int(np.flatnonzero(~finite.all(axis=1))[0])
        kind = "NaN" if np.isnan(arr[bad]).any() else "infinite"
        raise ValueError(
            f"{name} contains {kind} coordinates (first at row {bad}: {arr[bad].tolist()})"
        )
    return np.ascontiguousarray(arr)


def duplicate_map(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Find exact duplicates.

    Returns
    -------
    duplicate_of : (n,) int64
        -1 for the first occurrence of a coordinate pair, else the index of that first occurrence.
    unique : (u,) int64
        Indices of first occurrences, increasing.
    """
    dup = duplicate_of(np.ascontiguousarray(points[:, 0]), np.ascontiguousarray(points[:, 1]))
    return dup, np.flatnonzero(dup < 0)
