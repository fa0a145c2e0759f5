"""Input coercion and validation shared by the engine's public functions.

Every public entry point turns user input into fresh contiguous float64 arrays here, with
the same error messages everywhere: :func:`as_points` (any ``dim``), :func:`as_query`,
:func:`as_weights`, :func:`as_values`; then :func:`duplicate_map` and the exact
power-of-two :func:`working_frame`.
"""

from __future__ import annotations

import numpy as np

from ..kernels.dedupe import duplicate_of


def as_points(points, *, dim: int = 2, name: str = "points") -> np.ndarray:
    """Return a new C-contiguous ``(n, dim) float64`` copy of ``points`` or raise ``ValueError``.

    Parameters
    ----------
    points : (n, dim) array_like
        Coordinates. Lists of pairs (triples), tuples and arrays of any real dtype.
    dim : int
        Number of coordinates per point (2 or 3).
    name : str
        Name used in error messages.

    Returns
    -------
    (n, dim) float64
        A fresh array (the caller's data is never aliased, so it can never be mutated).
    """
    try:
        raw = np.asarray(points)
        if raw.dtype.kind == "c":
            raise TypeError("complex values are not coordinates")
        if raw.dtype.kind in "mM":
            raise TypeError("dates and durations are not coordinates (convert them first)")
        if raw.dtype.kind in "USb" or (
            raw.dtype.kind == "O" and any(isinstance(v, str | bytes | bool) for v in raw.flat)
        ):
            raise TypeError("text and true/false are not coordinates (parse them first)")
        arr = np.array(raw, dtype=np.float64, copy=True)
        if raw.dtype.kind != "b" and _nested_bool(points, arr):
            raise TypeError("a true/false among the numbers is not a coordinate")
    except (TypeError, ValueError) as exc:
        raise ValueError(
            f"{name} must be an (n, {dim}) array of real numbers; could not convert it ({exc})"
        ) from None
    if arr.ndim == 1 and arr.size == 0:
        arr = arr.reshape(0, dim)
    if arr.ndim != 2 or arr.shape[1] != dim:
        raise ValueError(f"{name} must have shape (n, {dim}); got shape {arr.shape}")
    finite = np.isfinite(arr)
    if not finite.all():
        bad = int(np.flatnonzero(~finite.all(axis=1))[0])
        kind = "NaN" if np.isnan(arr[bad]).any() else "infinite"
        raise ValueError(
            f"{name} contains {kind} coordinates (first at row {bad}: {arr[bad].tolist()})"
        )
    return np.ascontiguousarray(arr)


def _nested_bool(points, arr: np.ndarray) -> bool:
    """Whether a nested list gave numpy a ``True``/``False`` that it turned into 1.0/0.0.

    ``np.asarray([[True, 2.0]])`` is a float array, so the mix is invisible in its dtype. A
    boolean can only have become 0.0 or 1.0: ordinary float input costs one comparison per
    value, and only input holding 0.0 or 1.0 is read again as Python objects.
    """
    if isinstance(points, np.ndarray):
        return False
    mask = (arr == 0.0) | (arr == 1.0)
    if not mask.any():
        return False
    try:
        items = np.array(points, dtype=object)
    except (TypeError, ValueError):
        return False
    if items.shape != arr.shape:
        return False
    return any(isinstance(v, bool | np.bool_) for v in items[mask])


def as_query(xy, *, dim: int = 2, name: str = "xy") -> tuple[np.ndarray, bool]:
    """Query points as ``(q (m, dim) float64, single)``; one point ``(dim,)`` gives ``m = 1``.

    Parameters
    ----------
    xy : (dim,) or (m, dim) array_like
        One query point or many.
    dim : int
        Number of coordinates per point.
    name : str
        Name used in error messages.

    Returns
    -------
    q : (m, dim) float64
        A fresh array.
    single : bool
        True when ``xy`` was one point (callers then return a scalar).
    """
    arr = np.asarray(xy)
    if arr.ndim == 1 and arr.size == 0:  # ``[]``: no queries (it read "got shape (1, 0)")
        return np.zeros((0, dim)), False
    single = arr.ndim == 1
    if single and arr.shape[0] != dim:  # reshaped, it would read "got shape (1, 2)"
        raise ValueError(f"{name} must be ({dim},) or (n, {dim}); got shape {arr.shape}")
    return as_points(arr.reshape(1, -1) if single else arr, dim=dim, name=name), single


def _real_copy(values, what: str) -> np.ndarray:
    """A float64 copy of ``values`` (complex refused); ``what`` says why in the error."""
    raw = np.asarray(values)
    if raw.dtype.kind == "c":
        raise TypeError(what)
    if raw.dtype.kind in "mM":
        raise TypeError("dates and durations are not numbers (convert them first)")
    out = np.array(raw, dtype=np.float64, copy=True)
    if raw.dtype.kind != "b" and _nested_bool(values, out):
        raise TypeError("a true/false among the numbers is not a number")
    return out


def as_weights(weights, n: int, *, name: str = "weights") -> np.ndarray:
    """Return a new ``(n,) float64`` copy of per-site values or raise ``ValueError``.

    Parameters
    ----------
    weights : (n,) array_like
        One finite real number per site (power weights, target areas).
    n : int
        Number of sites.
    name : str
        Name used in error messages.

    Returns
    -------
    (n,) float64
    """
    try:
        w = _real_copy(weights, "complex values")
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be an (n,) array of real numbers ({exc})") from None
    if w.shape != (n,):
        raise ValueError(f"{name} must have shape ({n},) to match the points; got {w.shape}")
    if not np.isfinite(w).all():
        bad = int(np.flatnonzero(~np.isfinite(w))[0])
        raise ValueError(f"{name} contains a non-finite value (first at index {bad}: {w[bad]})")
    return w


def as_values(values, n: int) -> tuple[np.ndarray, bool]:
    """Data at ``n`` sites as ``(vals (n, k) float64, flat)`` or raise ``ValueError``.

    Parameters
    ----------
    values : (n,) or (n, k) array_like
        Finite real data, one row per site.
    n : int
        Number of sites.

    Returns
    -------
    vals : (n, k) float64
        A fresh C-contiguous array (``k = 1`` for one field).
    flat : bool
        True when ``values`` was one-dimensional.
    """
    try:
        vals = _real_copy(values, "complex values are not supported")
    except (TypeError, ValueError) as exc:
        raise ValueError(f"values must be an (n,) or (n, k) real array ({exc})") from None
    flat = vals.ndim == 1
    if vals.ndim not in (1, 2) or len(vals) != n:
        raise ValueError(
            f"values must have shape ({n},) or ({n}, k) to match the points; got {vals.shape}"
        )
    if not np.isfinite(vals).all():
        bad = int(np.flatnonzero(~np.isfinite(vals.reshape(n, -1)).all(axis=1))[0])
        raise ValueError(f"values contains a non-finite value (first at row {bad})")
    return np.ascontiguousarray(vals.reshape(n, -1)), flat


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


def unit_exponent(big: float, beyond: int) -> int:
    """0, or the binary exponent ``e`` of ``big`` (``big < 2**e``) where it is past ``2**±beyond``.

    Dividing by ``2**e`` (exact) brings ``big`` near 1: the frame the entry points that scale
    a whole problem by a power of two work in (power diagrams, ``power_fit``, rasters, GEOS's
    checks of polygon domains, Lloyd). Non-positive or non-finite ``big`` gives 0.
    """
    if not (big > 0.0 and np.isfinite(big)):
        return 0
    e = int(np.frexp(big)[1])
    return e if abs(e) > beyond else 0


def require_distinct(pts: np.ndarray, need: str) -> None:
    """Raise ``ValueError`` naming two equal rows of ``pts``: ``need`` needs distinct sites."""
    dup, _ = duplicate_map(pts)
    if (dup >= 0).any():
        i = int(np.flatnonzero(dup >= 0)[0])
        raise ValueError(
            f"points has duplicate sites (rows {int(dup[i])} and {i}); {need} needs distinct sites"
        )


def working_frame(
    pts: np.ndarray, extra: np.ndarray | None = None, cap: int = 900
) -> tuple[np.ndarray, int]:
    """Coordinates the kernels can compute on exactly: ``(work, k)`` with ``work ≈ pts * 2**k``.

    Scaling by a power of two is exact, so ordinary input (largest magnitude between
    ``2**-40`` and ``2**200``, no nonzero value below ``2**-188``) comes back unchanged with
    ``k = 0`` and no copy. Otherwise the points are scaled so their largest magnitude lies in
    ``[0.5, 1)`` (less if ``extra``, e.g. the clipping box, would pass ``2**cap``), and
    nonzero values below ``2**-188`` of that are rounded to multiples of ``2**-240``: a
    relative change below ``1e-72`` of the points' extent, the resolution the exact
    predicates work at.
    """
    big = float(np.abs(pts).max(initial=0.0))
    if big == 0.0:
        return pts, 0
    exp = int(np.frexp(big)[1])  # big < 2**exp
    k = 0 if -40 <= exp <= SAFE_EXP else -exp
    if extra is not None:
        ebig = float(np.abs(extra).max(initial=0.0))
        if ebig > 0.0:
            k = min(k, cap - int(np.frexp(ebig)[1]))
    work = np.ldexp(pts, k) if k else pts
    tiny = (work != 0.0) & (np.abs(work) < _SNAP_LIMIT)
    if tiny.any():
        work = work.copy() if work is pts else work
        work[tiny] = np.ldexp(np.round(np.ldexp(work[tiny], RES_BITS)), -RES_BITS)
    return work, k


def from_working(work: np.ndarray, k: int) -> np.ndarray:
    """Undo :func:`working_frame`'s scaling (exact)."""
    return np.ldexp(work, -k) if k else work
