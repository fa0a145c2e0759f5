"""Solid previews: a z-buffered software render of a closed mesh, optionally cut open.

Every triangle is drawn, however many (a lattice has half a million): a numba kernel keeps
each pixel's nearest triangle, so the preview needs no simplification and no mesh boolean.
The cut is a plane across the line of sight through the mesh's centre: fragments nearer
than it are discarded, and a pixel whose nearest remaining fragment is a back face looks
into the solid's material through the cut, so it is painted as the flat cap the cut would
leave (exact for a closed mesh). Shading is :func:`voroforge.io.render3d.render`'s: flat
Lambert per face, the same light, colour and 2x supersampling.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from numba import njit

from .. import config

__all__ = ["preview"]

_SS = 2  # supersampling, as io.render3d
_LIGHT = np.array([-0.4, -0.8, 0.6]) / np.linalg.norm([-0.4, -0.8, 0.6])  # io.render3d's
_EPS = 1e-9  # barycentric slack: pixel centres on a shared edge belong to both triangles


@njit(**config.NJIT)
def _zbuffer(sx, sy, depth, faces, keep, cut, nearest, zbuf):
    """Write into ``nearest`` the nearest triangle (of those ``keep``) at every pixel centre.

    ``sx, sy`` are screen coordinates (pixel ``(i, j)`` has its centre at ``(i + 0.5,
    j + 0.5)``), ``depth`` grows away from the camera; fragments nearer than ``cut`` are
    dropped. ``zbuf`` (filled with +inf) holds the depths; ``nearest`` (filled with -1) the
    triangle indices.
    """
    hgt, wid = nearest.shape
    for t in range(faces.shape[0]):
        if not keep[t]:
            continue
        a, b, c = faces[t, 0], faces[t, 1], faces[t, 2]
        x0, y0, z0 = sx[a], sy[a], depth[a]
        x1, y1, z1 = sx[b], sy[b], depth[b]
        x2, y2, z2 = sx[c], sy[c], depth[c]
        if max(z0, z1, z2) < cut:
            continue
        area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
        if area == 0.0:
            continue
        i0 = max(int(np.ceil(min(x0, x1, x2) - 0.5)), 0)
        i1 = min(int(np.floor(max(x0, x1, x2) - 0.5)), wid - 1)
        j0 = max(int(np.ceil(min(y0, y1, y2) - 0.5)), 0)
        j1 = min(int(np.floor(max(y0, y1, y2) - 0.5)), hgt - 1)
        for j in range(j0, j1 + 1):
            py = j + 0.5
            for i in range(i0, i1 + 1):
                px = i + 0.5
                w0 = ((x1 - px) * (y2 - py) - (x2 - px) * (y1 - py)) / area
                w1 = ((x2 - px) * (y0 - py) - (x0 - px) * (y2 - py)) / area
                w2 = 1.0 - w0 - w1
                if w0 < -_EPS or w1 < -_EPS or w2 < -_EPS:
                    continue
                z = w0 * z0 + w1 * z1 + w2 * z2
                if z < cut or z >= zbuf[j, i]:
                    continue
                zbuf[j, i] = z
                nearest[j, i] = t


def _rgb(col, normals):
    """io.render3d's flat Lambert shade of unit ``normals`` in colour ``col`` (0..255)."""
    shade = 0.35 + 0.65 * np.maximum(0.0, normals @ _LIGHT)
    return np.minimum(255.0, col[None, :] * shade[:, None] + 20.0).astype(np.uint8)


def preview(m, path, *, size=900, view=(35.0, 25.0), cut=None, color=(196, 205, 214)) -> Path:
    """A shaded PNG of a solid (software renderer, no GPU or display).

    Parameters
    ----------
    m : trimesh.Trimesh
        A closed mesh, outward faces.
    path : str or Path
        The PNG to write (atomically).
    size : int
        Width in pixels; the height is 0.8 of it.
    view : (float, float)
        Azimuth about +z and elevation, degrees (as :func:`voroforge.io.render3d.render`).
    cut : bool, optional
        Render the half away from the camera, cut open through the mesh's centre, so the
        cells show. Default: when the solid hides its inside (a foam's closed voids, a skin).

    Returns
    -------
    Path
        ``path``.
    """
    from PIL import Image

    from ..io.atomic import write_atomically
    from ..io.render3d import _rotation

    if cut is None:
        meta = m.metadata or {}
        cut = meta.get("kind") == "foam" or bool(meta.get("skin"))
    v = np.asarray(m.vertices, dtype=np.float64)
    f = np.ascontiguousarray(m.faces, dtype=np.int64)
    w = int(size)
    h = int(w * 0.8)
    W, H = w * _SS, h * _SS
    rot = _rotation(view)
    r = v @ rot.T  # x' right, y' away from the camera (depth), z' up
    t = v[f]
    n = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    nn = np.linalg.norm(n, axis=1)
    ok = nn > 0
    n[ok] /= nn[ok, None]
    front = (n @ rot.T)[:, 1] <= 0
    if cut:
        z_cut = float(m.bounds.mean(axis=0) @ rot[1])  # the plane through the centre
        keep = ok  # back faces show the cap through the cut
        framed = r[r[:, 1] >= z_cut]
    else:
        z_cut = -np.inf
        keep = ok & front  # a closed mesh's back faces are always hidden
        framed = r
    lo, hi = framed.min(axis=0), framed.max(axis=0)
    span = max((hi[0] - lo[0]) / (0.9 * W), (hi[2] - lo[2]) / (0.9 * H), 1e-300)
    sx = np.ascontiguousarray((r[:, 0] - 0.5 * (lo[0] + hi[0])) / span + 0.5 * W)
    sy = np.ascontiguousarray(0.5 * H - (r[:, 2] - 0.5 * (lo[2] + hi[2])) / span)
    nearest = np.full((H, W), -1, dtype=np.int64)
    zbuf = np.full((H, W), np.inf)
    _zbuffer(sx, sy, np.ascontiguousarray(r[:, 1]), f, keep, z_cut, nearest, zbuf)
    col = np.asarray(color, dtype=np.float64)
    # a colour per face (front: its own shade; back: the cap's, facing the camera), then
    # one row more for the white background, which index -1 picks
    faces_rgb = _rgb(col, n)
    cap = _rgb(col, -rot[1][None, :])[0]
    faces_rgb[~front] = cap
    table = np.vstack([faces_rgb, np.full((1, 3), 255, dtype=np.uint8)])
    img = Image.fromarray(table[nearest]).resize((w, h), Image.LANCZOS)
    return write_atomically(path, lambda tmp: img.save(tmp, format="PNG", compress_level=3))
