"""Attractor fields: values in [0, strength] that fall off with distance from points or curves.

An attractor's value at distance ``d`` is ``strength * falloff(d / radius)``, where every
falloff is exactly 1 at ``d = 0``, decreases monotonically and is exactly 0 for
``d >= radius``. Fields are plain callables ``field(xy (m, 2)) -> (m,)``; they drive seed
density (:func:`voroforge.design.populate.by_density`), Poisson spacing, cell scale, inset
distance, opening selection and recursion (map them to a range with :func:`remap`).

Examples
--------
>>> import numpy as np
>>> a = PointAttractor([[0, 0]], radius=10.0, falloff="linear")
>>> a(np.array([[0.0, 0.0], [5.0, 0.0], [20.0, 0.0]])).tolist()
[1.0, 0.5, 0.0]
"""

from __future__ import annotations

import math

import numpy as np
import shapely

__all__ = [
    "FALLOFFS",
    "CurveAttractor",
    "Field",
    "PointAttractor",
    "combine",
    "falloff",
    "power_weights",
    "remap",
]

#: Names accepted by ``falloff=``.
FALLOFFS = ("linear", "smoothstep", "gaussian", "inverse_power")

_GAUSS_A = 4.5  # exp(-4.5 t^2): sigma = radius / 3
_CHUNK = 65536  # query points per batch for attractors with per-point radii
_BRUTE = 64  # up to this many attractor points, distances by numpy (no KD-tree to import)
_INV_EPS = 0.1  # softening of 1 / (eps + t)^p so the value at the attractor is finite


def falloff(t, kind: str = "smoothstep", *, power: float = 2.0) -> np.ndarray:
    """Falloff profile of normalised distance ``t = d / radius``: 1 at 0, 0 for t >= 1.

    Parameters
    ----------
    t : (m,) array_like
        Normalised distances (>= 0).
    kind : {"linear", "smoothstep", "gaussian", "inverse_power"}
        ``linear``: ``1 - t``. ``smoothstep``: ``1 - (3 t^2 - 2 t^3)`` (flat at both
        ends). ``gaussian``: ``exp(-4.5 t^2)`` (sigma = radius / 3) shifted and rescaled to
        reach 0 at ``t = 1``. ``inverse_power``: ``1 / (0.1 + t)^power`` shifted and
        rescaled the same way (sharp peak, long tail).
    power : float
        Exponent of ``inverse_power`` (> 0).

    Returns
    -------
    (m,) float64
        Values in [0, 1], non-increasing in ``t``.
    """
    x = np.clip(np.asarray(t, dtype=np.float64), 0.0, 1.0)
    if kind == "linear":
        v = 1.0 - x
    elif kind == "smoothstep":
        v = 1.0 - x * x * (3.0 - 2.0 * x)
    elif kind == "gaussian":
        e1 = math.exp(-_GAUSS_A)
        v = (np.exp(-_GAUSS_A * x * x) - e1) / (1.0 - e1)
    elif kind == "inverse_power":
        p = float(power)
        if not (math.isfinite(p) and p > 0):
            raise ValueError(f"power must be a finite number > 0, got {power!r}")
        # ((eps + x)^-p - (1 + eps)^-p) / (eps^-p - (1 + eps)^-p) in logs, every exponent
        # <= 0: no overflow for a large p, and expm1 keeps a tiny p (1e-17 gave 0/0 = NaN)
        a = np.log(_INV_EPS + x)
        b = math.log1p(_INV_EPS)
        e = math.log(_INV_EPS)
        v = np.exp(-p * (a - e)) * np.expm1(-p * (b - a)) / math.expm1(-p * (b - e))
    else:
        raise ValueError(f"unknown falloff {kind!r}; choose one of {', '.join(FALLOFFS)}")
    v = np.clip(v, 0.0, 1.0)
    v[x >= 1.0] = 0.0
    v[x <= 0.0] = 1.0
    return v


def _xy(xy) -> np.ndarray:
    arr = np.asarray(xy, dtype=np.float64)
    if arr.ndim == 1 and arr.shape == (2,):
        arr = arr[None]
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"points must have shape (m, 2), got {arr.shape}")
    if not np.isfinite(arr).all():
        raise ValueError("points contain NaN or infinite coordinates")
    return arr


def _per_item(value, k: int, name: str, *, positive: bool) -> np.ndarray:
    arr = np.asarray(value, dtype=np.float64)
    if arr.ndim == 0:
        arr = np.full(k, float(arr))
    if arr.shape != (k,):
        raise ValueError(f"{name} must be a number or one per attractor point ({k},)")
    if not np.isfinite(arr).all():
        raise ValueError(f"{name} must be finite")
    if positive and (arr <= 0).any():
        raise ValueError(f"{name} must be > 0")
    if not positive and (arr < 0).any():
        raise ValueError(f"{name} must be >= 0")
    return arr


class Field:
    """A scalar field ``f(xy (m, 2)) -> (m,) float64``, with a few combinators.

    Parameters
    ----------
    func : callable
        ``func(xy) -> values``.
    """

    def __init__(self, func):
        if not callable(func):
            raise ValueError("a Field needs a callable func(xy) -> values")
        self._func = func

    def __call__(self, xy) -> np.ndarray:
        """Values at points ``xy (m, 2)``: ``(m,)`` float64."""
        pts = _xy(xy)
        values = np.asarray(self._func(pts), dtype=np.float64)
        if values.shape != (len(pts),):
            raise ValueError(f"field returned shape {values.shape}, expected ({len(pts)},)")
        return values

    def remap(self, lo: float, hi: float) -> Field:
        """The field mapped linearly from [0, 1] to [lo, hi] (see :func:`remap`)."""
        return Field(lambda xy: remap(self(xy), lo, hi))

    def invert(self) -> Field:
        """``1 - field``: large far from the attractors."""
        return Field(lambda xy: 1.0 - self(xy))


class _Attractor(Field):
    """Shared parts: radius, strength, falloff."""

    def __init__(self, k: int, radius, strength, falloff_kind, power):
        if falloff_kind not in FALLOFFS:
            raise ValueError(
                f"unknown falloff {falloff_kind!r}; choose one of {', '.join(FALLOFFS)}"
            )
        p = float(power)
        if not (math.isfinite(p) and p > 0):
            raise ValueError(f"power must be a finite number > 0, got {power!r}")
        self.radius = _per_item(radius, k, "radius", positive=True)
        self.strength = _per_item(strength, k, "strength", positive=False)
        self.falloff = falloff_kind
        self.power = p
        super().__init__(self._values)

    def _profile(self, d, radius, strength):
        return strength * falloff(d / radius, self.falloff, power=self.power)


class PointAttractor(_Attractor):
    """Attractor points: value ``max_i strength_i * falloff(|xy - p_i| / radius_i)``.

    Parameters
    ----------
    points : (k, 2) array_like
        Attractor positions.
    radius : float or (k,) array_like
        Distance at which the influence reaches 0 (> 0).
    strength : float or (k,) array_like
        Value at the attractor (>= 0).
    falloff : {"linear", "smoothstep", "gaussian", "inverse_power"}
        Profile, see :func:`falloff`.
    power : float
        Exponent for ``inverse_power``.
    """

    def __init__(self, points, *, radius, strength=1.0, falloff="smoothstep", power=2.0):
        pts = _xy(points).copy()
        if len(pts) == 0:
            raise ValueError("PointAttractor needs at least one point")
        self.points = pts
        self.points.setflags(write=False)
        super().__init__(len(pts), radius, strength, falloff, power)
        self._tree = None
        if len(pts) > _BRUTE:  # many points: a KD-tree (scipy is imported only then)
            from scipy.spatial import cKDTree

            self._tree = cKDTree(pts)

    def _distances(self, xy: np.ndarray) -> np.ndarray:
        """(m, k) distances from ``xy`` to every attractor point (few points only)."""
        dx = xy[:, 0, None] - self.points[None, :, 0]
        dy = xy[:, 1, None] - self.points[None, :, 1]
        return np.sqrt(dx * dx + dy * dy)

    def _nearest(self, xy: np.ndarray) -> np.ndarray:
        if self._tree is not None:
            return self._tree.query(xy, k=1)[0]
        out = np.zeros(len(xy))
        step = max(1, _CHUNK // len(self.points))
        for start in range(0, len(xy), step):
            out[start : start + step] = self._distances(xy[start : start + step]).min(axis=1)
        return out

    def distance(self, xy) -> np.ndarray:
        """Distance from each point of ``xy (m, 2)`` to the nearest attractor point."""
        return self._nearest(_xy(xy))

    def _values(self, xy: np.ndarray) -> np.ndarray:
        uniform = (self.radius == self.radius[0]).all() and (
            self.strength == self.strength[0]
        ).all()
        if uniform:  # monotone profile: the nearest point decides
            d = self._nearest(xy)
            return self._profile(np.minimum(d, self.radius[0]), self.radius[0], self.strength[0])
        out = np.zeros(len(xy))
        if self._tree is None:  # every pair; the profile is 0 beyond each point's radius
            step = max(1, _CHUNK // len(self.points))
            for start in range(0, len(xy), step):
                d = self._distances(xy[start : start + step])
                v = self._profile(d, self.radius[None, :], self.strength[None, :])
                out[start : start + step] = np.maximum(v.max(axis=1), 0.0)
            return out
        reach = float(self.radius.max())
        for start in range(0, len(xy), _CHUNK):  # chunks bound the number of close pairs
            part = xy[start : start + _CHUNK]
            pairs = type(self._tree)(part).sparse_distance_matrix(
                self._tree, reach, output_type="ndarray"
            )
            if len(pairs):
                j = pairs["j"]
                v = self._profile(pairs["v"], self.radius[j], self.strength[j])
                np.maximum.at(out, start + pairs["i"], v)
        return out


def _as_curve(curve):
    if isinstance(curve, shapely.Geometry):
        if isinstance(curve, shapely.Polygon | shapely.MultiPolygon):
            curve = curve.boundary
        if not isinstance(curve, shapely.LineString | shapely.MultiLineString | shapely.LinearRing):
            raise ValueError(
                f"curve must be a LineString, MultiLineString or polyline, got {curve.geom_type}"
            )
        if curve.is_empty:
            raise ValueError("curve is empty")
        return curve
    if isinstance(curve, list | tuple) and curve and np.asarray(curve[0], dtype=object).ndim == 2:
        return shapely.MultiLineString([_polyline(c) for c in curve])
    return shapely.LineString(_polyline(curve))


def _polyline(coords) -> np.ndarray:
    arr = np.asarray(coords, dtype=np.float64)
    if arr.ndim != 2 or arr.shape[1] != 2 or len(arr) < 2:
        raise ValueError(f"a polyline must be a (k >= 2, 2) array, got shape {arr.shape}")
    if not np.isfinite(arr).all():
        raise ValueError("polyline has NaN or infinite coordinates")
    return arr


class CurveAttractor(_Attractor):
    """Attractor curves: value ``strength * falloff(distance_to_curve / radius)``.

    Parameters
    ----------
    curve : LineString, MultiLineString, Polygon (its outline), (k, 2) polyline or list of them
        The attracting curve(s); distance is measured to the nearest point of any of them.
    radius : float
        Distance at which the influence reaches 0 (> 0).
    strength : float
        Value on the curve (>= 0).
    falloff : {"linear", "smoothstep", "gaussian", "inverse_power"}
        Profile, see :func:`falloff`.
    power : float
        Exponent for ``inverse_power``.
    """

    def __init__(self, curve, *, radius, strength=1.0, falloff="smoothstep", power=2.0):
        self.curve = _as_curve(curve)
        shapely.prepare(self.curve)
        super().__init__(1, radius, strength, falloff, power)

    def distance(self, xy) -> np.ndarray:
        """Distance from each point of ``xy (m, 2)`` to the curve."""
        pts = _xy(xy)
        return shapely.distance(self.curve, shapely.points(pts))

    def _values(self, xy: np.ndarray) -> np.ndarray:
        return self._profile(self.distance(xy), self.radius[0], self.strength[0])


_MODES = ("max", "min", "sum")


def combine(attractors, *, mode: str = "max", clip: bool = True) -> Field:
    """Combine several fields into one.

    Parameters
    ----------
    attractors : sequence of callables
        Attractors or any fields ``f(xy) -> (m,)``.
    mode : {"max", "min", "sum"}
        How values at a point are combined.
    clip : bool
        Clip the result to [0, 1] (a sum can exceed 1).

    Returns
    -------
    Field
    """
    fields = list(attractors)
    if not fields:
        raise ValueError("combine needs at least one attractor")
    if mode not in _MODES:
        raise ValueError(f"unknown mode {mode!r}; choose one of {', '.join(_MODES)}")
    for i, f in enumerate(fields):
        if not callable(f):
            raise ValueError(f"attractor {i} is not callable")
    reduce = {"max": np.maximum.reduce, "min": np.minimum.reduce, "sum": np.add.reduce}[mode]

    def values(xy):
        out = reduce([np.asarray(f(xy), dtype=np.float64) for f in fields])
        return np.clip(out, 0.0, 1.0) if clip else out

    return Field(values)


def remap(values, lo, hi, *, source=(0.0, 1.0)) -> np.ndarray:
    """Map values linearly from ``source`` (default [0, 1]) to [lo, hi], clipped to the source.

    Parameters
    ----------
    values : array_like
        Field values.
    lo, hi : float
        Output at ``source[0]`` and ``source[1]`` (``lo > hi`` reverses the direction).
    source : (2,) float
        Input range.

    Returns
    -------
    float64 array of the shape of ``values``

    Examples
    --------
    >>> remap([0.0, 0.5, 1.0], 2.0, 6.0).tolist()
    [2.0, 4.0, 6.0]
    """
    a, b = (float(s) for s in source)
    if not (math.isfinite(a) and math.isfinite(b) and a != b):
        raise ValueError(f"source range must be two different finite numbers, got {source!r}")
    lo, hi = float(lo), float(hi)
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise ValueError("lo and hi must be finite")
    v = np.asarray(values, dtype=np.float64)
    t = np.clip((v - a) / (b - a), 0.0, 1.0)
    return lo + (hi - lo) * t


def power_weights(field, points, lo, hi) -> np.ndarray:
    """Power-diagram weights from a field: ``r_i**2`` with ``r_i = remap(field(p_i), lo, hi)``.

    A weight ``r**2`` acts like a circle of radius ``r`` around its site in
    ``voroforge.power``, so cells grow where the field maps to a larger ``r``.

    Parameters
    ----------
    field : callable
        ``field(xy (n, 2)) -> (n,)`` values in [0, 1].
    points : (n, 2) array_like
        The sites.
    lo, hi : float
        Radius where the field is 0 and where it is 1 (>= 0).

    Returns
    -------
    (n,) float64

    Examples
    --------
    >>> import numpy as np, voroforge as vf
    >>> pts = np.random.default_rng(0).random((40, 2)) * 100
    >>> sun = PointAttractor([[50, 50]], radius=40.0)
    >>> d = vf.power(pts, power_weights(sun, pts, 0.0, 8.0), (0, 0, 100, 100))
    """
    if not callable(field):
        raise ValueError("field must be callable field(xy) -> values in [0, 1]")
    if not (float(lo) >= 0 and float(hi) >= 0):
        raise ValueError(f"lo and hi are radii and must be >= 0, got {lo!r}, {hi!r}")
    pts = _xy(points)
    values = np.asarray(field(pts), dtype=np.float64)
    if values.shape != (len(pts),):
        raise ValueError(f"field returned shape {values.shape}, expected ({len(pts)},)")
    return remap(values, lo, hi) ** 2
