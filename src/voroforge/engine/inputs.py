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


#: Working coordinates keep every magnitude below ``2**SAFE_EXP`` and snap values smaller than
#: ``2**(SNAP_BITS - RES_BITS)`` to multiples of ``2**-RES_BITS``. Then every nonzero coordinate
#: difference is at least ``2**-RES_BITS``, so the degree-4 incircle terms stay above the
#: normal range (``2**-960``) and below overflow: the filters' error bounds and the exact
#: expansions hold without underflow (Shewchuk's arithmetic is exact only without it).
RES_BITS = 240
SAFE_EXP = 200
_SNAP_LIMIT = 2.0 ** (52 - RES_BITS)


def working_frame(pts: np.ndarray, extra: np.ndarray | None = None) -> tuple[np.ndarray, int]:
    """Coordinates the kernels can compute on exactly: ``(work, k)`` with ``work ≈ pts * 2**k``.

    Scaling by a power of two is exact, so ordinary input (largest magnitude between
    ``2**-40`` and ``2**200``, no nonzero value below ``2**-188``) comes back unchanged with
    ``k = 0`` and no copy. Otherwise the points are scaled so their largest magnitude lies in
    ``[0.5, 1)`` (less if ``extra``, e.g. the clipping box, would overflow), and nonzero values
    below ``2**-188`` of that are rounded to multiples of ``2**-240``: a relative change below
    ``1e-72`` of the points' extent, the resolution the exact predicates work at.
    """
    big = float(np.abs(pts).max(initial=0.0))
    if big == 0.0:
        return pts, 0
    exp = int(np.frexp(big)[1])  # big < 2**exp
    k = 0 if -40 <= exp <= SAFE_EXP else -exp
    if extra is not None:
        ebig = float(np.abs(extra).max(initial=0.0))
        if ebig > 0.0:
            k = min(k, 900 - int(np.frexp(ebig)[1]))
    work = np.ldexp(pts, k) if k else pts
    tiny = (work != 0.0) & (np.abs(work) < _SNAP_LIMIT)
    if tiny.any():
        work = work.copy() if work is pts else work
        work[tiny] = np.ldexp(np.round(np.ldexp(work[tiny], RES_BITS)), -RES_BITS)
    return work, k


def from_working(work: np.ndarray, k: int) -> np.ndarray:
    """Undo :func:`working_frame`'s scaling (exact)."""
    return np.ldexp(work, -k) if k else work
