"""The studio's messages to the page: the binary geometry and the JSON state and violations.

:func:`geometry_message` packs the session's cells for the page (:mod:`voroforge.studio.wire`),
at the page's pixel size; :func:`state_message` and :func:`violations_message` are the JSON
beside it. The web server (:mod:`voroforge.studio.server`) and the Jupyter widget send them.
"""

from __future__ import annotations

import operator
import time

import numpy as np
import shapely

from .. import config
from . import wire
from .session import Session

__all__ = ["geometry_message", "state_message", "violations_message"]

_KIND_COLOURS = {"web": "#e6194b", "opening": "#f58231", "corner": "#911eb4", "island": "#4363d8"}
_KIND_TEXT = {  # the words of `voroforge check`'s table
    "web": "web width between cuts",
    "opening": "opening size (inscribed circle diameter)",
    "corner": "material left in an inside corner by the tool",
    "island": "loose part (area)",
}


def geometry_message(
    session: Session, changed, *, seq: int, boundary: bool, extra=None, sent=None, px=None
) -> bytes:
    """The binary geometry message of the session's current result.

    Parameters
    ----------
    session : Session
    changed : (k,) int array or None
        Cells that changed since the previous message (None: all, a full redraw).
    seq : int
        Message number.
    boundary : bool
        Include the boundary and domain rings.
    extra : dict, optional
        More header fields.
    sent : dict, optional
        What the pages were sent last (updated here): with it, a patch carries only the
        sites that moved (``si``, ``sv``; every site where most moved) and the opening
        flags of its cells (``m``) instead of every site and flag; cells whose flag
        changed are added to the patch.
    px : float, optional
        The pages' pixel size in design units: the operated cells (drawn only) are
        thinned to within a quarter of a pixel (:func:`wire.rings`: a fillet's arcs become
        the few chords a pixel shows) and travel as uint16 steps of 1/64 to 1/8 of a pixel
        (:func:`wire.quantize`, the header's ``cq``); the raw cells travel whole.
        Operated cells that are their raw cells (a design without web, fillet, ...) are
        not sent again: the header says ``cells_raw``.

    Returns
    -------
    bytes
    """
    start = time.perf_counter()
    r = session.result
    n = len(r.raw)
    mask = r.mask.astype(np.uint8)
    sites = np.ascontiguousarray(r.sites, dtype=np.float64)
    full = changed is None
    patch = not full and sent is not None and sent.get("n") == n
    every = not full and len(changed) == n  # all the cells (new seeds): no flips to add
    if patch and not every and sent.get("mask") is not None and len(sent["mask"]) == n:
        flips = np.flatnonzero(sent["mask"] != mask)
        changed = np.union1d(np.asarray(changed, np.int64), flips)
    idx = np.arange(n, dtype=np.int32) if full else np.asarray(changed, np.int32)
    raw, cells = r.raw[idx], r.cells[idx]
    rg, rr, rc = wire.rings(raw)
    # cells without operations (no web, no fillet) are their raw cells: sent once
    cells_raw = _same_geoms(cells, raw)
    cq = None
    if not cells_raw:
        cg, cr, cc = wire.rings(cells, tol=0.5 * px if px else None)
        # drawn only: uint16 steps of a fraction of a pixel, half the bytes of float32
        cq = wire.quantize(cc, px) if px else None
    arrays = {"idx": idx}
    old_sites = sent.get("sites") if patch else None
    moved = None
    if old_sites is not None and old_sites.shape == sites.shape:
        moved = np.flatnonzero((old_sites != sites).any(axis=1)).astype(np.int32)
    # the sites that moved (an index and two float64 each), or all of them where that is
    # fewer bytes (most moved: new seeds)
    if moved is not None and 5 * len(moved) < 4 * n:
        arrays["si"], arrays["sv"] = moved, sites[moved].reshape(-1)
    else:
        arrays["sites"] = sites.reshape(-1)
    if full or not patch:  # the page's flags may be of another cell count: all of them
        arrays["mask"] = mask
    else:
        arrays["m"] = mask[idx]
    arrays.update(rg=rg, rr=rr, rc=rc.reshape(-1))
    if not cells_raw:
        arrays.update(cg=cg, cr=cr, cc=cc.reshape(-1) if cq is None else cq[1])
    if sent is not None:
        sent.update(n=n, mask=mask, sites=sites.copy())
    if boundary:
        for name, geom in (("b", r.boundary), ("d", r.domain)):
            g, rr_, c = wire.rings(np.asarray([geom], dtype=object))
            arrays[name + "g"], arrays[name + "r"], arrays[name + "c"] = g, rr_, c.reshape(-1)
    header = {
        "op": "geom",
        "seq": seq,
        "full": full,
        "n": n,
        "bounds": [float(v) for v in r.boundary.bounds],
        "cells_raw": cells_raw,
        "cq": None if cq is None else cq[0],  # cc as uint16 codes: x = cq[0] + code * cq[2]
        "compute_ms": round(session.compute_ms, 2),
        "sites_edited": session.sites is not None,
        "attractors": _attractors(session),
        "encode_ms": round((time.perf_counter() - start) * 1e3, 2),
        "sent_at": round(time.time() * 1e3, 2),  # wall clock: the page splits the wire time
        **(extra or {}),
    }
    return wire.pack(header, arrays)


def _same_geoms(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether geometries ``a`` are ``b`` (the same objects, or the same WKB where not)."""
    same = np.fromiter(map(operator.is_, a, b), dtype=bool, count=len(a))
    rest = np.flatnonzero(~same)
    if not len(rest):
        return True
    if len(rest) > len(a) // 8 + 8:  # an operated cell is a new object: not worth comparing
        return False
    return bool((shapely.to_wkb(a[rest]) == shapely.to_wkb(b[rest])).all())


def _attractors(session: Session) -> list[dict]:
    out = []
    for a in session.result.design.attractors:  # an animation frame's, while playing
        pts = [[float(x), float(y)] for x, y in (a.points or [])]
        out.append({"type": a.type, "points": pts, "radius": float(a.radius), "name": a.name})
    return out


def state_message(session: Session) -> dict:
    """The page's state besides geometry: inputs, undo/redo, file name, legend."""
    return {
        "op": "state",
        "controls": session.controls(),
        "can_undo": bool(session.history),
        "can_redo": bool(session.future),
        "file": session.path.name if session.path else "design.toml",
        "folder": str(session.folder),
        "name": session.design.design.name,
        "units": session.design.design.units,
        "legend": _legend(),
        "limits": {"max_seeds": session.max_seeds, "max_message": config.STUDIO_MAX_MESSAGE},
        "animation": _animation(session),
        "warnings": _unused(session),
    }


def _unused(session: Session) -> list[dict]:
    """The design's keys that its choices do not read (``boundary.points`` on a rectangle).

    Not errors: a design switched between shapes keeps the other shape's keys. Key and
    message each, as an ``"error"`` reply's issues (:func:`designfile.unused_keys`).
    """
    from ..design.designfile import unused_keys

    return [
        {"key": it.key, "message": f"{it.key} {it.message}"} for it in unused_keys(session.design)
    ]


def _animation(session: Session) -> dict | None:
    a = session.design.animation
    if a is None:
        return None
    keys = [t.key for t in a.tracks]
    return {"frames": a.frames, "fps": a.fps, "loop": a.loop, "frame": session.frame, "keys": keys}


def _legend() -> list[dict]:
    """Kinds with the marker shape and colour of ``voroforge check``'s overlays (where given)."""
    from ..design import fabrication

    styles = getattr(fabrication, "MARK_STYLES", {})
    out = []
    for kind in fabrication.KINDS:
        shape, rgb = styles.get(kind, ("circle", None))
        colour = "#" + "".join(f"{int(c):02x}" for c in rgb) if rgb else _KIND_COLOURS[kind]
        out.append({"kind": kind, "shape": shape, "colour": colour, "text": _KIND_TEXT[kind]})
    return out


def violations_message(session: Session, seq: int) -> dict:
    """The live fabrication check's violations (at most 2000 listed)."""
    vs = session.violations
    counts = {k: 0 for k in _KIND_COLOURS}
    for v in vs:
        counts[v.kind] += 1
    listed = [
        {
            "kind": v.kind,
            "x": float(v.location[0]),
            "y": float(v.location[1]),
            "value": float(v.value),
            "limit": float(v.limit),
            "items": list(v.items),
            "text": v.describe(),
        }
        for v in vs[:2000]
    ]
    return {
        "op": "violations",
        "seq": seq,
        "list": listed,
        "counts": counts,
        "total": len(vs),
        "check_ms": round(session.check_ms, 2),
    }
