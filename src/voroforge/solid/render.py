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
def _zbuffer(r, faces, scale, shift, light, cut, cap, col, zbuf, rgb):
    """Draw every triangle into the depth buffer ``zbuf`` and its flat colour into ``rgb``.

    ``r`` holds the vertices in the camera frame (x right, y away from the camera: the
    depth, z up); screen coordinates are ``(x * scale + shift[0], shift[1] - z * scale)``
    and pixel ``(i, j)`` has its centre at ``(i + 0.5, j + 0.5)``. Back faces are skipped
    unless ``cut`` is finite; then fragments nearer than ``cut`` are dropped and back faces
    drawn in the shade ``cap`` (seen through the cut: the solid's material). Front faces
    are shaded ``0.35 + 0.65 * max(0, n . light)``, coloured ``min(255, col * shade + 20)``
    (io.render3d's). ``zbuf`` starts at +inf, ``rgb`` as the background.
    """
    hgt, wid = zbuf.shape
    cutting = cut > -np.inf
    for t in range(faces.shape[0]):
        a, b, c = faces[t, 0], faces[t, 1], faces[t, 2]
        ux, uy, uz = r[b, 0] - r[a, 0], r[b, 1] - r[a, 1], r[b, 2] - r[a, 2]
        vx, vy, vz = r[c, 0] - r[a, 0], r[c, 1] - r[a, 1], r[c, 2] - r[a, 2]
        nx, ny, nz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
        nn = np.sqrt(nx * nx + ny * ny + nz * nz)
        if nn == 0.0:
            continue
        if ny <= 0.0:  # faces the camera
            sh = 0.35 + 0.65 * max(0.0, (nx * light[0] + ny * light[1] + nz * light[2]) / nn)
        elif cutting:
            sh = cap
        else:
            continue
        cr = min(255.0, col[0] * sh + 20.0)
        cg = min(255.0, col[1] * sh + 20.0)
        cb = min(255.0, col[2] * sh + 20.0)
        z0, z1, z2 = r[a, 1], r[b, 1], r[c, 1]
        if max(z0, z1, z2) < cut:
            continue
        x0, y0 = r[a, 0] * scale + shift[0], shift[1] - r[a, 2] * scale
        x1, y1 = r[b, 0] * scale + shift[0], shift[1] - r[b, 2] * scale
        x2, y2 = r[c, 0] * scale + shift[0], shift[1] - r[c, 2] * scale
        area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
        if area == 0.0:
            continue
        inv = 1.0 / area
        i0 = max(int(np.ceil(min(x0, x1, x2) - 0.5)), 0)
        i1 = min(int(np.floor(max(x0, x1, x2) - 0.5)), wid - 1)
        j0 = max(int(np.ceil(min(y0, y1, y2) - 0.5)), 0)
        j1 = min(int(np.floor(max(y0, y1, y2) - 0.5)), hgt - 1)
        # the barycentric weights as affine functions of the pixel centre
        a0, b0 = (y1 - y2) * inv, (x2 - x1) * inv
        c0 = (x1 * y2 - x2 * y1) * inv
        a1, b1 = (y2 - y0) * inv, (x0 - x2) * inv
        c1 = (x2 * y0 - x0 * y2) * inv
        for j in range(j0, j1 + 1):
            py = j + 0.5
            for i in range(i0, i1 + 1):
                px = i + 0.5
                w0 = a0 * px + b0 * py + c0
                w1 = a1 * px + b1 * py + c1
                w2 = 1.0 - w0 - w1
                if w0 < -_EPS or w1 < -_EPS or w2 < -_EPS:
                    continue
                z = w0 * z0 + w1 * z1 + w2 * z2
                if z < cut or z >= zbuf[j, i]:
                    continue
                zbuf[j, i] = z
                rgb[j, i, 0] = np.uint8(cr)
                rgb[j, i, 1] = np.uint8(cg)
                rgb[j, i, 2] = np.uint8(cb)


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
    from ..io.render3d import check_render_size, view_rotation

    if cut is None:
        meta = m.metadata or {}
        cut = meta.get("kind") == "foam" or bool(meta.get("skin"))
    if isinstance(size, bool) or not isinstance(size, int | np.integer):
        raise ValueError(f"size must be an integer width in pixels; got {size!r}")
    w, h = check_render_size((int(size), int(int(size) * 0.8)))
    rot = view_rotation(view)  # checked before any drawing
    v = np.asarray(m.vertices, dtype=np.float64)
    f = np.ascontiguousarray(m.faces, dtype=np.int64)
    W, H = w * _SS, h * _SS
    # x' right, y' away from the camera (depth), z' up; by columns, not ``v @ rot.T``: a
    # multithreaded BLAS call leaves its worker threads spinning for ~0.05 s of CPU
    r = np.stack([v[:, 0] * q[0] + v[:, 1] * q[1] + v[:, 2] * q[2] for q in rot], axis=1)
    if cut:
        z_cut = float(m.bounds.mean(axis=0) @ rot[1])  # the plane through the centre
        framed = r[r[:, 1] >= z_cut]
    else:
        z_cut = -np.inf
        framed = r
    lo, hi = framed.min(axis=0), framed.max(axis=0)
    span = max((hi[0] - lo[0]) / (0.9 * W), (hi[2] - lo[2]) / (0.9 * H), 1e-300)
    shift = np.array(
        [0.5 * W - 0.5 * (lo[0] + hi[0]) / span, 0.5 * H + 0.5 * (lo[2] + hi[2]) / span]
    )
    light = rot @ _LIGHT  # in the camera frame
    cap = 0.35 + 0.65 * max(0.0, -float(light[1]))  # the cut faces the camera: normal -y'
    zbuf = np.full((H, W), np.inf)
    rgb = np.full((H, W, 3), 255, dtype=np.uint8)  # the white background
    col = np.asarray(color, dtype=np.float64)
    _zbuffer(r, f, 1.0 / span, shift, light, z_cut, cap, col, zbuf, rgb)
    img = Image.fromarray(rgb).resize((w, h), Image.LANCZOS)
    return write_atomically(path, lambda tmp: img.save(tmp, format="PNG", compress_level=3))
