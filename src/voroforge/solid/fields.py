"""3D fields: values in [0, strength] falling off with distance from points, curves, planes.

Also from a mesh surface: the 2D attractors of :mod:`voroforge.design.attractors`, in 3D.

A field is a callable ``field(xyz (m, 3)) -> (m,)``. The solids take them wherever a size
may vary: ``solid.lattice(c, radius=(0.4, 1.5), field=f)`` grades the strut radius from 0.4
(field 0, far) to 1.5 (field 1, at the attractor). Fields combine with :func:`combine` and
map to sizes with :meth:`Field3.remap`.

Examples
--------
>>> import numpy as np
>>> f = point([[0, 0, 0]], radius=10.0, falloff="linear")
>>> f(np.array([[0.0, 0, 0], [5.0, 0, 0], [0, 0, 20.0]])).tolist()
[1.0, 0.5, 0.0]
>>> plane((0, 0, 0), (0, 0, 1), radius=4.0, falloff="linear")(np.array([[9.0, 9, 1]])).tolist()
[0.75]
"""

from __future__ import annotations

import numpy as np

from ..design.attractors import FALLOFFS, falloff

__all__ = ["Field3", "as_size", "combine", "curve", "mesh", "plane", "point"]

_CHUNK = 1 << 16
_BRUTE = 64  # up to this many points, distances by numpy (no KD-tree, no scipy.spatial)


def _xyz(xyz) -> np.ndarray:
    a = np.asarray(xyz, dtype=np.float64)
    if a.ndim != 2 or a.shape[1] != 3:
        raise ValueError(f"field points must be (m, 3), got shape {a.shape}")
    return a


class Field3:
    """A 3D field: a callable ``(m, 3) -> (m,)`` with :meth:`remap` and :meth:`invert`."""

    def __init__(self, func):
        self._func = func

    def __call__(self, xyz) -> np.ndarray:
        """Values at points ``(m, 3)``."""
        return np.asarray(self._func(_xyz(xyz)), dtype=np.float64)

    def remap(self, lo: float, hi: float) -> Field3:
        """Values 0..1 mapped linearly to ``lo..hi`` (a radius or a wall thickness)."""
        return Field3(lambda x: lo + (hi - lo) * np.clip(self(x), 0.0, 1.0))

    def invert(self) -> Field3:
        """``1 - value``: dense far from the attractor, open near it."""
        return Field3(lambda x: 1.0 - self(x))


class _Distance(Field3):
    def __init__(self, radius, strength, kind, power):
        radius = float(radius)
        if not (np.isfinite(radius) and radius > 0):
            raise ValueError(f"radius must be a finite number > 0, got {radius!r}")
        if kind not in FALLOFFS:
            raise ValueError(f"unknown falloff {kind!r}; choose one of {', '.join(FALLOFFS)}")
        self.radius, self.strength, self.kind, self.power = radius, float(strength), kind, power
        super().__init__(self._values)

    def distance(self, xyz) -> np.ndarray:  # pragma: no cover - overridden
        raise NotImplementedError

    def _values(self, xyz):
        d = self.distance(xyz)
        return self.strength * falloff(d / self.radius, self.kind, power=self.power)


class _Point(_Distance):
    def __init__(self, pts, **kw):
        self.points = _xyz(pts).copy()
        self._tree = None
        if len(self.points) > _BRUTE:
            from scipy.spatial import cKDTree

            self._tree = cKDTree(self.points)
        super().__init__(**kw)

    def distance(self, xyz):
        xyz = _xyz(xyz)
        if self._tree is not None:
            return self._tree.query(xyz)[0]
        # the KD-tree's sum (dx^2 + dy^2 + dz^2, in that order): the same bits
        out = np.zeros(len(xyz))
        step = max(1, _CHUNK // max(len(self.points), 1))
        p = self.points
        for s in range(0, len(xyz), step):
            x = xyz[s : s + step]
            dx = x[:, 0, None] - p[None, :, 0]
            dy = x[:, 1, None] - p[None, :, 1]
            dz = x[:, 2, None] - p[None, :, 2]
            out[s : s + step] = np.sqrt(dx * dx + dy * dy + dz * dz).min(axis=1)
        return out


def _seg_distance(x, a, b):
    """Distance from each row of ``x`` to the nearest of the segments ``a[i] -> b[i]``."""
    out = np.full(len(x), np.inf)
    ab = b - a
    ll = np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300)
    for s in range(0, len(x), _CHUNK):
        xs = x[s : s + _CHUNK, None, :]
        t = np.clip(np.einsum("mij,ij->mi", xs - a[None], ab) / ll, 0.0, 1.0)
        d = np.linalg.norm(xs - (a[None] + t[..., None] * ab[None]), axis=2)
        out[s : s + _CHUNK] = d.min(axis=1)
    return out


class _Curve(_Distance):
    def __init__(self, polylines, **kw):
        segs = []
        for pl in polylines:
            pl = _xyz(pl)
            if len(pl) < 2:
                raise ValueError("a curve needs at least two points")
            segs.append(np.stack([pl[:-1], pl[1:]], axis=1))
        s = np.vstack(segs)
        self.a, self.b = s[:, 0].copy(), s[:, 1].copy()
        super().__init__(**kw)

    def distance(self, xyz):
        return _seg_distance(_xyz(xyz), self.a, self.b)


class _Plane(_Distance):
    def __init__(self, origin, normal, **kw):
        n = np.asarray(normal, dtype=np.float64).reshape(3)
        nn = np.linalg.norm(n)
        if not (np.isfinite(nn) and nn > 0):
            raise ValueError(f"plane normal must be a non-zero vector, got {normal!r}")
        self.normal = n / nn
        self.origin = np.asarray(origin, dtype=np.float64).reshape(3)
        super().__init__(**kw)

    def distance(self, xyz):
        # by columns, not ``@ self.normal``: a multithreaded BLAS call (dgemv on a shell's
        # 0.45M samples) is 5x slower here and leaves its threads spinning ~0.05 s of CPU
        x, o, n = _xyz(xyz), self.origin, self.normal
        return np.abs((x[:, 0] - o[0]) * n[0] + (x[:, 1] - o[1]) * n[1] + (x[:, 2] - o[2]) * n[2])


class _Mesh(_Distance):
    def __init__(self, m, **kw):
        import trimesh

        if not isinstance(m, trimesh.Trimesh):
            raise ValueError(f"mesh field: expected a trimesh.Trimesh, got {type(m).__name__}")
        self.mesh = m
        super().__init__(**kw)

    def distance(self, xyz):
        from .sdf import mesh_distance

        return mesh_distance(self.mesh, _xyz(xyz))


def point(points, *, radius, strength=1.0, falloff="smoothstep", power=2.0) -> Field3:
    """Field falling off with distance from the nearest of ``points`` ``(k, 3)``."""
    return _Point(points, radius=radius, strength=strength, kind=falloff, power=power)


def curve(polylines, *, radius, strength=1.0, falloff="smoothstep", power=2.0) -> Field3:
    """Field falling off with distance from 3D polylines (one ``(k, 3)`` array or a list)."""
    arr = polylines if isinstance(polylines, list | tuple) else [polylines]
    if len(arr) and np.ndim(arr[0]) == 1:
        arr = [np.asarray(arr)]
    return _Curve(arr, radius=radius, strength=strength, kind=falloff, power=power)


def plane(origin, normal, *, radius, strength=1.0, falloff="smoothstep", power=2.0) -> Field3:
    """Field falling off with distance from the plane through ``origin`` with ``normal``."""
    return _Plane(origin, normal, radius=radius, strength=strength, kind=falloff, power=power)


def mesh(m, *, radius, strength=1.0, falloff="smoothstep", power=2.0) -> Field3:
    """Field falling off with distance from a triangle mesh's surface."""
    return _Mesh(m, radius=radius, strength=strength, kind=falloff, power=power)


def combine(fields, *, mode: str = "max") -> Field3:
    """Pointwise ``max``, ``min`` or ``sum`` (clipped to [0, 1]) of several fields."""
    fields = list(fields)
    if not fields:
        raise ValueError("combine: no fields given")
    if mode not in ("max", "min", "sum"):
        raise ValueError(f"combine mode must be max, min or sum, got {mode!r}")

    def f(x):
        vals = np.stack([np.asarray(g(x), dtype=np.float64) for g in fields])
        if mode == "max":
            return vals.max(axis=0)
        if mode == "min":
            return vals.min(axis=0)
        return np.clip(vals.sum(axis=0), 0.0, 1.0)

    return Field3(f)


def _checked(f, name: str):
    """``f`` wrapped so that its values are one finite, positive float per point."""

    def sized(x):
        m = len(x)
        try:
            v = np.asarray(f(x), dtype=np.float64)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"{name}: the field's values are not numbers ({exc})") from None
        if v.ndim == 0:
            v = np.full(m, float(v))
        if v.shape != (m,):
            raise ValueError(f"{name}: the field gave {v.shape} values for {m} points")
        if not (np.isfinite(v).all() and (v > 0).all()):
            raise ValueError(f"{name}: the field gave non-positive or non-finite values")
        return v

    return sized


def as_size(value, field, name: str):
    """A size argument as a callable ``xyz -> (m,)`` of positive values.

    ``value`` is a number, a callable (its values checked at each call: one finite value
    > 0 per point), or with ``field`` a pair ``(far, near)`` mapped by the field's 0..1
    values. Raises ``ValueError`` naming ``name`` otherwise.
    """
    if field is not None:
        if callable(value):
            raise ValueError(f"{name}: give (far, near) sizes with field=, not a callable")
        lo, hi = (value, value) if np.ndim(value) == 0 else tuple(value)
        lo, hi = float(lo), float(hi)
        if not (lo > 0 and hi > 0 and np.isfinite(lo) and np.isfinite(hi)):
            raise ValueError(f"{name}: sizes must be finite and > 0, got {value!r}")
        return _checked(
            lambda x: lo + (hi - lo) * np.clip(np.asarray(field(x), dtype=np.float64), 0, 1), name
        )
    if callable(value):
        return _checked(value, name)
    if np.ndim(value) != 0:
        raise ValueError(f"{name}: a number, a callable field, or (far, near) with field=")
    v = float(value)
    if not (np.isfinite(v) and v > 0):
        raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    return lambda x: np.full(len(x), v)
