"""A mesh container that crosses itself is refused (:func:`crossing_report`).

The edge checks of :func:`mesh3d.as_mesh_container` (each edge on two faces, consistent
orientation) pass two overlapping shells concatenated, or a shell through itself; the cut
then counts the overlap twice (two unit cubes offset by half a side: volumes summing to 2.0
where the solid is 1.875) or finds no site inside. Nested shells that do not cross (a cavity)
stay valid.
"""

from __future__ import annotations

import numpy as np


def crossing_report(V: np.ndarray, F: np.ndarray) -> str | None:
    """None when no two triangles of the mesh cross, else a message naming two that do.

    ``V (k, 3)`` merged vertices, ``F (m, 3)`` faces in the caller's order (their numbers
    are the caller's). Shells are numbered by their first face.
    """
    from ..kernels.meshcross3d import first_crossing

    V = np.ascontiguousarray(V, np.float64)
    t, u = first_crossing(V, np.ascontiguousarray(F, np.int64))
    if t < 0:
        return None
    shell = _shells(F, len(V))
    if shell[t] != shell[u]:
        a, b = sorted((int(shell[t]), int(shell[u])))
        what = f"shells {a} and {b} overlap (faces {t} and {u} cross)"
    else:
        what = f"faces {t} and {u} of shell {int(shell[t])} cross"
    return (
        f"the container mesh intersects itself: {what}; union the shells (e.g. with "
        "manifold3d) or repair the mesh"
    )


def _shells(F, nv):
    """``(m,)``: each face's shell (faces joined by vertices), numbered by first face."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    e = np.concatenate([F[:, [0, 1]], F[:, [1, 2]]])
    g = coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(nv, nv))
    _, comp = connected_components(g, directed=False)
    fc = comp[F[:, 0]]
    first = np.full(int(fc.max()) + 1, len(F))
    np.minimum.at(first, fc, np.arange(len(F)))
    rank = np.argsort(np.argsort(first))
    return rank[fc]


def nesting_report(V: np.ndarray, F: np.ndarray) -> str | None:
    """None when the shells nest as a solid's do, else what is wrong.

    ``F`` oriented (the whole mesh outward). A shell facing outwards must lie inside no
    other shell's solid (winding 0 from the others at each of its faces' centroids), one
    facing inwards (a cavity) inside exactly one (winding 1): elsewhere some region is
    counted twice (shells that overlap without crossing a triangle properly, e.g. two boxes
    whose edges meet the other's faces on their diagonals, or a box inside a box facing the
    same way). Centroids on another shell's face are skipped (shells that touch). The
    winding is signed ray crossings along +x (:func:`meshcross3d.others_winding`).
    """
    from ..kernels.inside3d import yz_grid
    from ..kernels.meshcross3d import others_winding
    from .threads import serial_below

    shell = _shells(F, len(V))
    k = int(shell.max()) + 1
    if k == 1:
        return None
    centre = 0.5 * (V.min(axis=0) + V.max(axis=0))
    a, b, c = (V[F[:, q]] - centre for q in range(3))
    with np.errstate(over="ignore", invalid="ignore"):  # only the signs are used
        vol = np.bincount(shell, np.einsum("ij,ij->i", a, np.cross(b, c)), minlength=k)
    g, start, items = yz_grid(V, F, int(max(1, min(512, np.sqrt(len(F) / 4)))))
    out = np.zeros((len(F), 2), np.int64)
    with serial_below(len(F)):
        others_winding(V, F, shell, g, start, items, out)
    want = np.where(vol[shell] > 0, 0, 1)
    bad = np.flatnonzero((out[:, 0] != want) & (out[:, 0] > -(1 << 40)))
    if not len(bad):
        return None
    f = int(bad[0])
    s, o = int(shell[f]), int(out[f, 1])
    if o < 0:
        return (
            f"the container mesh is not a valid solid: shell {s} (face {f}) faces "
            "inwards but lies inside no other shell"
        )
    lo, hi = sorted((s, o))
    return (
        f"the container mesh intersects itself: shells {lo} and {hi} overlap or nest facing "
        f"the same way (face {f} lies inside the other; shells that overlap: union them, "
        "e.g. with manifold3d; a cavity: face it inwards)"
    )
