"""``Diagram3D.describe``: counts and checks of a 3D diagram."""

from __future__ import annotations

import numpy as np


def describe3d(d) -> dict:
    """V, E, F, C; the Euler check per cell; convexity; cells cut by a non-convex container.

    Returns a dict: ``vertices``, ``edges`` (unique undirected edges), ``faces`` (unique),
    ``cells`` (non-empty), ``euler_ok`` (every non-empty cell has ``V - E + F = 2``),
    ``euler_failures`` (cell numbers), ``convex`` (every face's vertices on the inner side of
    every other face of its cell, to 1e-9 of the cell's size; faces smaller than
    that squared are left out), ``cut_cells`` (cells cut by a
    mesh container, else 0), ``unmatched_vertices``, ``volume`` and ``container_volume``.
    """
    cf, lab, farea, roff, ring = d.cell_face_table()
    n = len(d)
    fails = []
    nonconvex = []
    edges = set()
    for i in range(n):
        f0, f1 = cf[i], cf[i + 1]
        if f1 == f0:
            continue
        cell_edges = set()
        verts = set()
        for f in range(f0, f1):
            r = ring[roff[f] : roff[f + 1]]
            for a, b in zip(r, np.roll(r, -1), strict=False):
                e = (min(a, b), max(a, b))
                cell_edges.add(e)
                edges.add(e)
            verts.update(r.tolist())
        if len(verts) - len(cell_edges) + (f1 - f0) != 2:
            fails.append(i)
        if d.container != "mesh" or d.cut_cells is None or not d.cut_cells[i]:
            V = d.vertices[list(verts)]
            size = float(np.ptp(V, axis=0).max()) if len(V) else 0.0
            for f in range(f0, f1):
                a = farea[f]
                na = np.linalg.norm(a)
                if na <= (1e-9 * size) ** 2:
                    continue  # a face below the doubles' resolution has no normal to test
                p0 = d.vertices[ring[roff[f]]]
                if ((V - p0) @ (a / na)).max() > 1e-9 * size:
                    nonconvex.append(i)
                    break
    return {
        "vertices": len(d.vertices),
        "edges": len(edges),
        "faces": len(d.faces),
        "cells": int((np.diff(cf) > 0).sum()),
        "euler_ok": not fails,
        "euler_failures": fails,
        "convex": not nonconvex,
        "nonconvex_cells": nonconvex,
        "cut_cells": 0 if d.cut_cells is None else int(np.count_nonzero(d.cut_cells)),
        "unmatched_vertices": d.unmatched_vertices,
        "volume": float(np.sum(d.volumes)),
        "container_volume": d.container_volume,
    }
