"""Print checks on a solid: struts, pores, walls, voids, floating parts, pinches, overhangs.

:func:`check` returns a :class:`Report` whose ``violations`` list has one entry per problem,
each with its kind, location (x, y, z), measured value and the limit, like the 2D
fabrication report. Struts, pores and walls come from the builders' metadata (``lattice``
records its struts and radii, ``foam`` its bubbles and walls, ``shell`` its openings and
thickness, ``extrude`` its slabs); voids, parts and overhangs are measured on the mesh itself.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..config import IMPLICIT_SAG

__all__ = ["Report", "Violation", "check", "strut_widths"]


@dataclass(frozen=True)
class Violation:
    """One problem: ``kind``, ``location`` (x, y, z), measured ``value`` and the ``limit``."""

    kind: str
    location: tuple[float, float, float]
    value: float
    limit: float

    def __str__(self) -> str:
        x, y, z = self.location
        return (
            f"{self.kind} at ({x:.4g}, {y:.4g}, {z:.4g}): {self.value:.4g} (limit {self.limit:.4g})"
        )


@dataclass
class Report:
    """The result of :func:`check`: ``violations`` and summary figures (``stats``)."""

    violations: list[Violation] = field(default_factory=list)
    stats: dict = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        """True when nothing is violated."""
        return not self.violations

    def by_kind(self) -> dict[str, int]:
        """Number of violations of each kind."""
        out: dict[str, int] = {}
        for v in self.violations:
            out[v.kind] = out.get(v.kind, 0) + 1
        return out

    def to_dict(self) -> dict:
        """Plain data for JSON reports."""
        return {
            "ok": self.ok,
            "stats": self.stats,
            "violations": [
                {"kind": v.kind, "location": list(v.location), "value": v.value, "limit": v.limit}
                for v in self.violations
            ],
        }

    def table(self, max_rows: int | None = 50) -> str:
        """The report as text: a summary line, then one row per violation (``max_rows``)."""
        rows = self.violations if max_rows is None else self.violations[:max_rows]
        st = self.stats
        head = (
            f"print check: {'ok' if self.ok else f'{len(self.violations)} violations'}"
            f" ({st.get('bodies', '?')} bodies, {st.get('voids', '?')} voids, "
            f"volume {st.get('volume', float('nan')):.6g})"
        )
        lines = [head]
        if rows:
            lines.append(f"{'kind':<14} {'x':>10} {'y':>10} {'z':>10} {'value':>10} {'limit':>8}")
            for v in rows:
                x, y, z = v.location
                lines.append(
                    f"{v.kind:<14} {x:>10.4g} {y:>10.4g} {z:>10.4g} "
                    f"{v.value:>10.4g} {v.limit:>8.4g}"
                )
        if len(rows) < len(self.violations):
            lines.append(f"... {len(self.violations) - len(rows)} more (--all shows every row)")
        return "\n".join(lines)

    def write_png(self, path, **kwargs):
        """Overlays draw 2D reports; a solid's violations are 3D points (see :meth:`table`)."""
        raise ValueError("--overlay draws 2D fabrication reports; a solid's report is the table")

    write_svg = write_png

    def __str__(self) -> str:
        head = "print check: ok" if self.ok else f"print check: {len(self.violations)} violations"
        return "\n".join([head, *(f"  {v}" for v in self.violations[:50])])


def strut_widths(meta) -> np.ndarray:
    """The diameter of the widest round rod inside each strut of a lattice's metadata.

    Not the declared ``2 r``: a hull-route strut is a prism of ``segments`` sides whose
    corners are at ``r`` (``2 r cos(pi / k)``: 0.924 of it at 8 sides), and marching cubes
    cuts chords inside the implicit route's round struts, ``IMPLICIT_SAG * h**2 / r`` deep
    at voxel ``h`` (measured on cross sections: ``tests/test_solid_strut_widths.py``).
    """
    s = meta["struts"]
    r = np.minimum(np.asarray(s["ra"], np.float64), np.asarray(s["rb"], np.float64))
    method = (meta.get("parts") or {}).get("method")
    if method == "hull" and meta.get("segments"):
        r = r * np.cos(np.pi / int(meta["segments"]))
    elif method == "implicit" and meta.get("voxel"):
        h = float(meta["voxel"])
        r = np.maximum(r - IMPLICIT_SAG * h * h / r, 0.0)
    return 2.0 * r


def _loc(p) -> tuple[float, float, float]:
    return (float(p[0]), float(p[1]), float(p[2]))


def shell_volumes(t, fl, lo, n) -> np.ndarray:
    """Signed volume of each of ``n`` shells: triangles ``t`` (T, 3, 3), shell ``fl`` (T,).

    Each shell's tetrahedra are taken about its own lowest corner ``lo[fl]``, not the
    absolute origin: a shell far from the origin (5e5 away, a few hundredths across) has
    triple products about the origin of 1e17 whose rounding swamps its volume and flips its
    sign; its points minus a corner near them are exact (Sterbenz) or nearly so.
    """
    t = t - lo[fl][:, None, :]
    six = np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2]))
    return np.bincount(fl, six, n) / 6.0


def _bodies(m):
    """Connected components of the mesh with their signed volumes and centroids."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    f = np.asarray(m.faces)
    nv = len(m.vertices)
    rows = np.concatenate([f[:, 0], f[:, 1]])
    cols = np.concatenate([f[:, 1], f[:, 2]])
    g = coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(nv, nv))
    n, lab = connected_components(g, directed=False)
    flab = lab[f[:, 0]]
    t = np.asarray(m.vertices)[f]
    cen = t.mean(axis=1)
    area = 0.5 * np.linalg.norm(np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]), axis=1)
    a = np.bincount(flab, area, minlength=n)
    c = np.stack([np.bincount(flab, cen[:, i] * area, minlength=n) for i in range(3)], 1)
    c /= np.maximum(a, 1e-300)[:, None]
    lo = np.stack([np.full(n, np.inf)] * 3, 1)
    hi = -lo
    for i in range(3):
        np.minimum.at(lo[:, i], flab, t[:, :, i].min(axis=1))
        np.maximum.at(hi[:, i], flab, t[:, :, i].max(axis=1))
    # about each shell's own corner: far from the origin a small cavity's volume about the
    # origin is rounding noise of either sign (it was reported as a floating part)
    vol = shell_volumes(t, flab, lo, n)
    used = np.bincount(flab, minlength=n) > 0
    return vol[used], c[used], lo[used], hi[used]


def check(
    m,
    *,
    min_strut: float | None = None,
    min_pore: float | None = None,
    min_wall: float | None = None,
    max_overhang: float | None = 45.0,
    min_overhang_area: float | None = None,
) -> Report:
    """Check a solid for printing.

    Parameters
    ----------
    m : trimesh.Trimesh
        A solid from :mod:`voroforge.solid` (or any closed mesh).
    min_strut : float, optional
        Smallest printable strut diameter: lattice struts thinner than this are reported
        at their midpoint, each with the widest round rod inside it (:func:`strut_widths`:
        a hull-route prism's inscribed circle, an implicit strut less its meshing chords).
    min_pore : float, optional
        Smallest opening/pore diameter that drains (resin, powder): smaller foam bubbles and
        shell openings are reported at their centre.
    min_wall : float, optional
        Thinnest printable wall: walls the builder recorded thinner than this are reported
        at a point of the wall (a foam's walls between bubbles, ``wall`` thick, and its skin,
        half a wall; a shell's ``thickness``; an extruded slab's thickness or, with a
        relief, its lowest top; a lattice's ``skin``, once, at its point farthest out).
    max_overhang : float or None
        Largest overhang angle from the vertical (degrees) printable without supports:
        downward-facing regions beyond it (off the build plate) are reported, one entry per
        connected region at its area-weighted centre, the value its largest angle.
    min_overhang_area : float, optional
        Overhang regions smaller than this area are ignored (default: 1e-4 of the surface).

    Returns
    -------
    Report
        ``violations`` of kinds ``thin_strut``, ``small_pore``, ``thin_wall``, ``trapped_void``,
        ``floating_part``, ``pinch`` (separate sheets meeting at a point or an edge: the
        value is the number of vertex copies there), ``overhang``; ``stats`` with
        ``watertight``, ``volume``, ``bodies``, ``voids``, ``pinches``.
    """
    import trimesh

    if not isinstance(m, trimesh.Trimesh):
        raise ValueError(f"check: expected a trimesh.Trimesh, got {type(m).__name__}")
    out: list[Violation] = []
    meta = m.metadata or {}
    if min_strut is not None:
        s = meta.get("struts")
        if s is not None and len(s["a"]):
            dia = strut_widths(meta)
            for i in np.flatnonzero(dia < min_strut):
                mid = 0.5 * (s["a"][i] + s["b"][i])
                out.append(Violation("thin_strut", _loc(mid), float(dia[i]), float(min_strut)))
    if min_pore is not None:
        p = meta.get("pores")
        if p is not None and len(p["size"]):
            for i in np.flatnonzero(np.asarray(p["size"]) < min_pore):
                out.append(
                    Violation("small_pore", _loc(p["centre"][i]), float(p["size"][i]), min_pore)
                )
    if min_wall is not None:
        w = meta.get("walls")
        if w is not None and len(w["thickness"]):
            th = np.asarray(w["thickness"], dtype=np.float64)
            for i in np.flatnonzero(th < min_wall):
                out.append(Violation("thin_wall", _loc(w["at"][i]), float(th[i]), min_wall))
        skin = float(meta.get("skin") or 0.0) if meta.get("kind") == "lattice" else 0.0
        if 0.0 < skin < min_wall and len(m.vertices):
            # the skin lines the whole surface: reported once, at its point farthest out
            v = np.asarray(m.vertices)
            at = v[np.argmax(np.linalg.norm(v - 0.5 * (v.min(0) + v.max(0)), axis=1))]
            out.append(Violation("thin_wall", _loc(at), skin, float(min_wall)))
    vol, cen, lo, hi = _bodies(m)
    shells = vol > 0
    voids = np.flatnonzero(~shells)
    # a negative shell is a cavity; it is trapped when it lies inside a positive body
    for i in voids:
        out.append(Violation("trapped_void", _loc(cen[i]), float(-vol[i]), 0.0))
    pos = np.flatnonzero(shells)
    if len(pos) > 1:
        main = pos[np.argmax(vol[pos])]
        for i in pos:
            if i != main:
                out.append(Violation("floating_part", _loc(cen[i]), float(vol[i]), 0.0))
    pinches = _pinches(m)
    out.extend(Violation("pinch", _loc(p), float(c), 1.0) for p, c in pinches)
    if max_overhang is not None:
        out.extend(_overhangs(m, float(max_overhang), min_overhang_area))
    stats = {
        "watertight": bool(m.is_watertight),
        "volume": float(vol.sum()),
        "bodies": int(shells.sum()),
        "voids": int(len(voids)),
        "pinches": len(pinches),
    }
    return Report(out, stats)


def _pinches(m):
    """``[(position, copies)]`` of points where separate sheets of the mesh meet.

    Two vertices at one position (parts touching along an edge or at a point) keep the
    mesh watertight in memory, but STL has no vertex identity and OBJ/PLY readers weld by
    position: the file's mesh is then non-manifold there (an edge of four faces).
    """
    v = np.asarray(m.vertices)
    used = np.unique(np.asarray(m.faces).reshape(-1)) if len(m.faces) else np.zeros(0, int)
    if not len(used):
        return []
    pos, counts = np.unique(v[used], axis=0, return_counts=True)
    return [(pos[i], int(counts[i])) for i in np.flatnonzero(counts > 1)]


def _overhangs(m, max_angle: float, min_area):
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    n = np.asarray(m.face_normals)
    down = -n[:, 2]
    # the angle of the surface from the vertical; a face pointing straight down is 90 degrees
    ang = np.degrees(np.arcsin(np.clip(down, -1.0, 1.0)))
    t = np.asarray(m.triangles)
    zmin = float(m.bounds[0, 2])
    tol = 1e-6 * float(m.scale)
    on_bed = t[:, :, 2].max(axis=1) <= zmin + tol
    bad = (ang > max_angle) & ~on_bed
    if not bad.any():
        return []
    idx = np.flatnonzero(bad)
    adj = np.asarray(m.face_adjacency)
    keep = bad[adj[:, 0]] & bad[adj[:, 1]]
    nf = len(m.faces)
    g = coo_matrix((np.ones(keep.sum()), (adj[keep, 0], adj[keep, 1])), shape=(nf, nf))
    _, lab = connected_components(g, directed=False)
    area = np.asarray(m.area_faces)
    cen = np.asarray(m.triangles_center)
    labs = lab[idx]
    uniq, inv = np.unique(labs, return_inverse=True)
    a = np.bincount(inv, area[idx])
    c = np.stack([np.bincount(inv, cen[idx, i] * area[idx]) for i in range(3)], 1) / a[:, None]
    worst = np.full(len(uniq), -np.inf)
    np.maximum.at(worst, inv, ang[idx])
    floor = (1e-4 * float(m.area)) if min_area is None else float(min_area)
    return [
        Violation("overhang", _loc(c[i]), float(worst[i]), max_angle)
        for i in np.flatnonzero(a >= floor)
    ]


def fill_pockets(verts, tris, size):
    """Drop the union's closed cavities smaller than ``size``: ``(tris, volume, count)``.

    Convex parts that overlap can enclose tiny pockets (a few faces, a fraction of a strut
    across): sealed voids no printer resolves that ``check`` would list as trapped. A cavity
    is a connected shell of negative volume; its volume is added back to the solid's.
    """
    from scipy.sparse import coo_matrix  # scipy.sparse only: the implicit route's too
    from scipy.sparse.csgraph import connected_components

    if len(tris) == 0:
        return tris, 0.0, 0
    nv = len(verts)
    ij = tris.astype(np.int32)  # the vertex graph in int32 and bytes: bounded memory
    g = coo_matrix(
        (np.ones(2 * len(ij), dtype=np.int8), (ij[:, :2].ravel(), ij[:, 1:].ravel())),
        shape=(nv, nv),
    )
    n, lab = connected_components(g, directed=False)
    fl = lab[tris[:, 0]]
    t = verts[tris]
    lo = np.full((n, 3), np.inf)
    hi = np.full((n, 3), -np.inf)
    for i in range(3):
        np.minimum.at(lo[:, i], fl, t[:, :, i].min(axis=1))
        np.maximum.at(hi[:, i], fl, t[:, :, i].max(axis=1))
    vol = shell_volumes(t, fl, lo, n)
    pocket = (vol < 0) & ((hi - lo).max(axis=1) < size)
    return tris[~pocket[fl]], float(-vol[pocket].sum()), int(pocket.sum())
