"""Curves to polylines: elliptical arcs and Béziers, within a given distance of the curve."""

from __future__ import annotations

import math

import numpy as np

from ...config import CURVE_MAX_POINTS

__all__ = ["arc_points", "bezier_points"]


def arc_points(cx, cy, rx, ry, phi, t0, dt, tol) -> np.ndarray:
    """Points of an elliptical arc, start point excluded, end point included.

    Parameters
    ----------
    cx, cy : float
        Centre.
    rx, ry : float
        Radii.
    phi : float
        Rotation of the x radius, radians.
    t0, dt : float
        Start angle and signed sweep (parameter angles, radians).
    tol : float
        Largest chord error.

    Returns
    -------
    (k, 2) float64
    """
    r = max(rx, ry)
    if r <= tol:
        n = 1
    else:
        # 2 acos(1 - x) ~ 2 sqrt(2 x) where 1 - x rounds to 1 (acos gave 0: a step of 0)
        x = tol / r
        step = 2.0 * math.acos(max(-1.0, 1.0 - x)) if x > 1e-8 else 2.0 * math.sqrt(2.0 * x)
        n = max(1, math.ceil(abs(dt) / step))
        if n > CURVE_MAX_POINTS:
            raise ValueError(
                f"an arc of radius {r:g} sweeping {math.degrees(abs(dt)):g} degrees needs "
                f"{n:g} points at tolerance {tol:g} (at most {CURVE_MAX_POINTS:,}); "
                "give a coarser tolerance or a smaller radius"
            )
    t = t0 + dt * np.arange(1, n + 1) / n
    c, s = math.cos(phi), math.sin(phi)
    x = rx * np.cos(t)
    y = ry * np.sin(t)
    return np.column_stack((cx + c * x - s * y, cy + s * x + c * y))


def bezier_points(ctrl: np.ndarray, tol: float) -> np.ndarray:
    """Flatten a quadratic (3 control points) or cubic (4) Bézier; start point excluded.

    The number of uniform parameter steps comes from the bound on the second derivative
    (deviation <= M / (8 n^2)), so the polyline is within ``tol`` of the curve.

    Parameters
    ----------
    ctrl : (3, 2) or (4, 2) float64
        Control points.
    tol : float
        Largest distance between the curve and the polyline.

    Returns
    -------
    (k, 2) float64
    """
    if len(ctrl) == 3:
        m = 2.0 * np.linalg.norm(ctrl[0] - 2 * ctrl[1] + ctrl[2])
    else:
        m = 6.0 * max(
            np.linalg.norm(ctrl[0] - 2 * ctrl[1] + ctrl[2]),
            np.linalg.norm(ctrl[1] - 2 * ctrl[2] + ctrl[3]),
        )
    n = max(1, math.ceil(math.sqrt(m / (8.0 * tol))))
    t = (np.arange(1, n + 1) / n)[:, None]
    u = 1.0 - t
    if len(ctrl) == 3:
        return u * u * ctrl[0] + 2 * u * t * ctrl[1] + t * t * ctrl[2]
    return u**3 * ctrl[0] + 3 * u * u * t * ctrl[1] + 3 * u * t * t * ctrl[2] + t**3 * ctrl[3]
