"""The fabrication check while editing: :func:`voroforge.design.fabrication.check`, per change.

Every limit of ``check`` is a property of one opening (opening size, tool corners), of a
pair of openings (the web between them) or of an opening and the outline (the web to the
rim), plus the outline's own corners and loose islands. :class:`LiveCheck` keeps those
results keyed by the openings' WKB and runs ``check`` only on openings that are new since
the last call (and, for webs, on their neighbours within ``min_web``), so dragging one seed
re-checks a handful of openings. The violations are the ones ``voroforge check`` reports
for the same geometry (a test compares them), worst first.

The check runs in a worker thread while edits go on in the server's event loop, which
tests containment in the result's domain (the boundary itself, prepared) on every drag
step. GEOS's prepared geometries build their indexes lazily and without a lock, so the
check works on its own copy of the boundary: two threads on one prepared polygon crashed
the process (``cellops.frame`` prepares the boundary it is given).
"""

from __future__ import annotations

import numpy as np
import shapely

from ..design.fabrication import KINDS, Violation, check, design_corner_tolerance

__all__ = ["LiveCheck", "limits_of"]

#: New openings checked per step (a newer edit can stop a long check between steps)
_CHUNK = 16


def limits_of(design) -> dict:
    """The ``check`` keywords of a design's ``[fabrication]`` table (as ``voroforge check``)."""
    f = design.fabrication
    return {
        "min_web": f.min_web,
        "min_opening": f.min_opening,
        "min_inside_radius": f.tool_radius,
        "corner_tolerance": design_corner_tolerance(design),
        "islands": f.islands,
    }


class LiveCheck:
    """Incremental fabrication check of successive results of one design being edited."""

    def __init__(self) -> None:
        self._key = None
        self._boundary = None  # this check's own copy of the boundary (see the module)
        self._single: dict[bytes, list[Violation]] = {}  # opening, corner, web to the rim
        self._pairs: dict[tuple[bytes, bytes], Violation] = {}
        self._outline: list[Violation] = []
        self._island_cache: tuple[object, list[Violation]] | None = None  # (result, its islands)

    def run(self, result, stale=None) -> list[Violation] | None:
        """The violations of ``result`` (a :class:`~voroforge.design.compute.Result`).

        Parameters
        ----------
        result : Result
        stale : callable, optional
            Asked between chunks of new openings; when it returns true the run stops and
            returns None (what was checked so far stays cached for the next run).

        Returns
        -------
        list of Violation or None
            Items index ``result.openings``, worst first.
        """
        limits = limits_of(result.design)
        key = (tuple(sorted(limits.items())), shapely.to_wkb(result.boundary))
        per = {k: v for k, v in limits.items() if k not in ("islands", "corner_tolerance")}
        if key != self._key or self._boundary is None:
            self._key = key
            self._boundary = boundary = shapely.from_wkb(key[1])
            self._single.clear()
            self._pairs.clear()
            self._outline = []
            if per.get("min_inside_radius"):
                rim = check(
                    openings=[],
                    boundary=boundary,
                    min_inside_radius=per["min_inside_radius"],
                    corner_tolerance=limits["corner_tolerance"],
                    islands=False,
                )
                self._outline = list(rim.violations)
        boundary = self._boundary
        holes = np.asarray(result.openings, dtype=object).reshape(-1)
        if "tile" in result.extra:  # periodic tiles are checked across seams by build
            holes = holes[:0]
        wkb = list(shapely.to_wkb(holes)) if len(holes) else []
        index = {w: i for i, w in enumerate(wkb)}
        new = [i for i, w in enumerate(wkb) if w not in self._single]
        tree = shapely.STRtree(holes) if new and limits["min_web"] else None
        for start in range(0, len(new), _CHUNK):
            if stale is not None and stale():
                return None
            self._check_new(holes, wkb, new[start : start + _CHUNK], boundary, limits, tree)
        found: list[Violation] = []
        for i, w in enumerate(wkb):
            found += [_renumber(v, (i, *v.items[1:])) for v in self._single[w]]
        for (a, b), v in list(self._pairs.items()):
            if a in index and b in index:
                i, j = sorted((index[a], index[b]))
                found.append(_renumber(v, (i, j)))
            else:
                del self._pairs[(a, b)]
        found += self._outline
        if limits["islands"]:  # the frame's loose parts, once per result
            if self._island_cache is None or self._island_cache[0] is not result:
                self._island_cache = (result, _islands(result, boundary))
            found += self._island_cache[1]
        found.sort(key=_order)
        return found

    def _check_new(self, holes, wkb, new, boundary, limits, tree) -> None:
        tol = limits["corner_tolerance"]
        sub = holes[new]
        for i in new:
            self._single[wkb[i]] = []
        if limits["min_opening"] is not None or limits["min_inside_radius"] is not None:
            # (without either limit check() finds nothing here: 175 of a 2,000-opening
            # check's 220 ms went to building its frame for nothing)
            one = check(
                openings=sub,
                boundary=boundary,
                min_opening=limits["min_opening"],
                min_inside_radius=limits["min_inside_radius"],
                corner_tolerance=tol,
                islands=False,
            )
            for v in one.violations:
                if v.items and v.items[0] >= 0:
                    self._single[wkb[new[v.items[0]]]].append(v)
        web = limits["min_web"]
        if not web:
            return
        _, hits = tree.query(sub, predicate="dwithin", distance=web)
        near = np.union1d(np.asarray(new), hits)
        fresh = set(new)
        webs = check(openings=holes[near], boundary=boundary, min_web=web, islands=False)
        for v in webs.violations:
            i, j = (int(near[k]) if k >= 0 else -1 for k in v.items)
            if j < 0:
                if i in fresh:
                    self._single[wkb[i]].append(v)
            elif i in fresh or j in fresh:
                self._pairs[(wkb[i], wkb[j])] = v


def _order(v: Violation):
    """Worst first: by severity where violations have one, then kind, value and place."""
    severity = getattr(v, "severity", 0.0)
    value = -v.value if v.kind == "island" else v.value
    return (-severity, KINDS.index(v.kind), value, v.location)


def _renumber(v: Violation, items: tuple[int, ...]) -> Violation:
    return Violation(v.kind, v.location, v.value, v.limit, items)


def _islands(result, b) -> list[Violation]:
    """Loose parts of the frame; a one-part frame with the boundary's own rim has none.

    ``b`` is the result's boundary (the check's own copy of it).
    """
    frame = result.frame
    if frame is None:  # computed without it: the same frame, from the public operation
        from ..design.cellops import frame as cut

        frame = cut(b, result.openings)
    if (
        frame.geom_type == "Polygon"
        and b.geom_type == "Polygon"
        and frame.exterior.equals_exact(b.exterior, 0.0)
    ):
        return []
    return list(check(frame=frame, boundary=b).violations)
