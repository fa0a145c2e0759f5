"""One design being edited: its state, the edits, undo/redo, save and export.

:class:`Session` holds the design file's mapping (``data``), the sites when they were edited
by hand (``sites``; ``None`` while they come from ``[seeds]``), the last good
:class:`~voroforge.design.compute.Result` (computed without its ``frame``, which the page
does not draw; exports rebuild everything) and the undo history. :meth:`Session.apply` takes
one message of the page (a ``dict``, already parsed) and returns a :class:`Reply`
(:mod:`voroforge.studio.replies`, with the checks of a message's values); the web server
and the Jupyter widget only move those messages. Nothing here draws or clips: the
geometry is :func:`voroforge.design.compute.compute`'s, reused per cell between edits.

Saving writes the design as TOML into the design's own folder (never elsewhere, never over
a file without ``overwrite``), with hand-edited sites in a ``<name>.seeds.csv`` beside it
that ``[seeds] method = "file"`` reads back bit for bit (a ``<name>.seeds.geojson`` when the
sites came from a seed file with attribute columns: each site keeps its row's properties,
added sites get nulls, JSON types kept); ``voroforge build`` of the saved
file gives the files the page exports, byte for byte (exports go through the same
:func:`voroforge.design.build.build`).
"""

from __future__ import annotations

import contextlib
import copy
import dataclasses
import json
import math
import re
import tempfile
import time
import tomllib
from pathlib import Path

import numpy as np
import shapely

from .. import config
from ..design.build import build, starter
from ..design.compute import compute, outline
from ..design.designfile import DesignError, apply_overrides, load
from .controls import controls
from .livecheck import LiveCheck
from .replies import EXPORTS, BadMessage, Reply, changed_cells, error_reply, number, plain, shown
from .tomlfile import dumps, write_atomic

__all__ = ["EXPORTS", "Reply", "Session"]

_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9 _.+-]{0,120}\.toml$")
#: Sections of a design that ``compute`` does not read (changing them keeps the cells).
_NOT_GEOMETRY = ("fabrication", "output", "animation")
#: Keys whose change means "new seeds" (hand-edited sites are dropped).
_RESEED = ("seeds", "relax", "design.seed")


class Session:
    """A design being edited (see the module docstring).

    Parameters
    ----------
    source : str, Path, dict or None
        A TOML design file, a design mapping, or None for the starter design.
    folder : str or Path, optional
        Where saves go and relative file names are read from (default: the file's folder,
        else the current folder).
    max_seeds : int
        The most sites an edit may ask for (a clear error above it).

    Raises
    ------
    DesignError
        When the design cannot be built at all (no last good drawing to keep).
    """

    def __init__(self, source=None, *, folder=None, max_seeds: int = config.STUDIO_MAX_SEEDS):
        self.path: Path | None = None
        if source is None:
            data = tomllib.loads(starter())
        elif isinstance(source, dict):
            data = copy.deepcopy(source)
        else:
            self.path = Path(source).resolve()
            # the file through the loader first: a bad design is reported with the file's name,
            # line and key (the mapping read below has no lines; the first compute loads it)
            load(self.path)
            data = tomllib.loads(self.path.read_text(encoding="utf-8-sig"))
        if folder is None:
            folder = self.path.parent if self.path is not None else Path.cwd()
        self.folder = Path(folder).resolve()
        self.max_seeds = int(max_seeds)
        self.data: dict = data
        self.sites: np.ndarray | None = None
        #: (attributes, row of each of ``sites``, -1 for added ones) when the edited sites
        #: came from a seed file with attribute columns (kept on save), else None
        self.rows: tuple[dict, np.ndarray] | None = None
        self.history: list[tuple[dict, np.ndarray | None, tuple | None]] = []
        self.future: list[tuple[dict, np.ndarray | None, tuple | None]] = []
        self.result = None
        self.design = None
        self.live = LiveCheck()
        self.compute_ms = 0.0
        self.check_ms = 0.0
        self.violations: list = []
        self.frame: int | None = None  # the animation frame shown (None: the design itself)
        self._anim: dict | None = None
        #: Seed drags update only the cells near the seed (:mod:`voroforge.studio.incremental`)
        self.incremental = True
        self.settle_ms = 0.0
        self._field_cache = None
        self._controls = None
        self._seeded = None  # (data, design, seeds) of the last _reseed_fast, for _compute
        #: (data, previous result, design, result, ms) of :meth:`compute_ahead`, for _compute
        self._ahead = None
        self.ahead_used = False  # whether the last _compute took the result computed ahead
        #: Threads for the cell operations of a full recompute (the same cells with any).
        #: One: the convex cells' inset and fillet are numpy over small arrays that hold the
        #: GIL, so a second thread mostly waits for it, and takes a core from the browser
        #: (design.seed, holed 2000-cell panel, load 3.3: 46-67 ms wall with one, 94-120
        #: with two; 36-40 against 44-59 ms CPU).
        self.workers = 1
        self.design, self.result = self._compute(self.data, None, reuse=False)

    # --- computing ---------------------------------------------------------------------

    def _compute(self, data: dict, sites, *, reuse: bool = True):
        seeded, self._seeded = self._seeded, None
        ahead, self._ahead = self._ahead, None
        self.ahead_used = False
        if (
            ahead is not None
            and reuse
            and sites is None
            and self.frame is None
            and ahead[1] is self.result
            and _same_data(ahead[0], data)
        ):
            # computed ahead from these very inputs (the design's mapping and the result it
            # reuses) by the same call as below: the same design and geometry
            self.compute_ms, self.ahead_used = ahead[4], True
            return ahead[2], ahead[3]
        if sites is None and seeded is not None and seeded[0] is data:
            design, seeds = seeded[1], seeded[2]  # what _reseed_fast loaded and sampled
        else:
            design, seeds = load(data)[0], None
            self._guard(design)
        if reuse and self._same_geometry(design, sites):
            # only [fabrication], [output] or [animation] changed: the cells are the same
            extra = {**self.result.extra, "redone": np.zeros(0, dtype=np.int64)}
            self.compute_ms = 0.0
            return design, dataclasses.replace(self.result, design=design, extra=extra)
        start = time.perf_counter()
        previous = self.result if reuse else None
        result = compute(
            design,
            self.folder,
            progress=self._stage(),
            sites=sites if seeds is None else seeds,
            reuse=previous,
            frame=False,
            workers=self.workers,
        )
        self.compute_ms = (time.perf_counter() - start) * 1e3
        shapely.prepare(result.domain)  # every click and drag asks whether it is inside
        return design, result

    def _stage(self, stale=None):
        """``compute``'s progress callback: the studio's seed limit (and ``stale()``)."""
        limit = self.max_seeds

        def stage(name: str) -> None:
            if stale is not None and stale():
                raise _Stale
            head = name.split(" ", 1)[0]
            if name.endswith("Voronoi cells") and head.isdigit() and int(head) > limit:
                raise DesignError.at(
                    "seeds", f"{head} seeds is more than the studio's limit of {limit}"
                )

        return stage

    def compute_ahead(self, data: dict, previous, key: str, value, stale=None) -> bool:
        """Compute the design ``data`` with ``key`` set to ``value`` before it is asked for.

        A slider steps through values in order, each a full computation of tens of
        milliseconds (``design.seed``: every seed new): the next value can be computed while
        the page draws this one. ``data`` and ``previous`` are the session's mapping and
        result when called (the caller takes them; this reads nothing else that an edit
        changes, so it may run in another thread); the result is kept for the ``set`` of
        that value on that result only, which then takes it instead of computing the same
        call again (:meth:`_compute`): the geometry is the same bytes either way. Nothing is
        kept when the edit would not recompute in full (hand-edited sites, an animation
        frame, only ``[fabrication]``-like sections), on any error, or when ``stale()``
        turns true first (checked between ``compute``'s stages).

        Returns
        -------
        bool
            Whether a result was kept.
        """
        if previous is None or self.sites is not None or self.frame is not None:
            return False
        try:
            data = apply_overrides(data, {key: value})
            design = load(data)[0]
            self._guard(design)
            prev = previous.design
            keep = {k: getattr(prev, k) for k in _NOT_GEOMETRY if hasattr(prev, k)}
            if design.model_copy(update=keep) == prev:
                return False  # the cells stay: nothing to compute
            start = time.perf_counter()
            result = compute(
                design,
                self.folder,
                progress=self._stage(stale),
                sites=None,
                reuse=previous,
                frame=False,
                workers=self.workers,
            )
            ms = (time.perf_counter() - start) * 1e3
            shapely.prepare(result.domain)
        except (_Stale, DesignError, TypeError, ValueError, KeyError, IndexError, OSError):
            return False
        self._ahead = (data, previous, design, result, ms)
        return True

    def _same_geometry(self, design, sites) -> bool:
        """Whether ``design`` with ``sites`` has the current result's geometry.

        True when they differ from the current ones only in sections that
        :func:`~voroforge.design.compute.compute` does not read (``[fabrication]``,
        ``[output]``, ``[animation]``) and the sites are the same.
        """
        prev = self.design
        if self.result is None or prev is None or self.frame is not None:
            return False
        if sites is not self.sites:
            return False
        keep = {k: getattr(prev, k) for k in _NOT_GEOMETRY if hasattr(prev, k)}
        return design.model_copy(update=keep) == prev

    def _guard(self, design) -> None:
        """Refuse seed settings that would make far more sites than the limit (before sampling)."""
        s = design.seeds
        if s.count is not None and s.method in ("random", "density") and s.count > self.max_seeds:
            raise DesignError.at(
                "seeds.count", f"{s.count} is more than the studio's limit of {self.max_seeds}"
            )
        spacing = s.spacing if s.method in ("grid", "hexgrid", "jittered") else None
        if s.method == "poisson":
            spacing = s.radius * 0.8
        if spacing and self.result is not None:
            # (area / spacing / spacing: spacing * spacing underflows to 0 below ~1e-162)
            with np.errstate(over="ignore"):
                estimate = float(np.float64(self.result.domain.area) / spacing / spacing)
            if estimate > 2 * self.max_seeds:
                key = "seeds.radius" if s.method == "poisson" else "seeds.spacing"
                many = f"about {estimate:.0f}" if math.isfinite(estimate) else "past 1e308"
                raise DesignError.at(key, f"{many} seeds, more than the limit of {self.max_seeds}")

    def warm(self) -> None:
        """Run one seed drag step on the current result and drop it (the result is kept).

        A server's first drag step otherwise pays for the incremental module's import and
        the first calls of its kernels and caches: 5.7-6.2 ms of CPU against 1.4-1.9 for
        the next steps (the holed 2,000-cell panel, in a fresh process). The server calls
        this once before it answers requests.
        """
        from . import incremental

        result = self.result
        if self.frame is not None or not self.incremental or not incremental.eligible(result):
            return
        n = len(result.sites)
        if not n:
            return
        i = n // 2
        x, y = result.sites[i]
        nudge = 1e-6 * math.sqrt(float(result.domain.area) / n)
        if not shapely.contains_xy(result.domain, x + nudge, y):
            return
        # only a warm-up: whatever fails here, the drag's own step meets (and answers) again
        with contextlib.suppress(Exception):
            incremental.move(result, i, (x + nudge, y), self._field_fn())

    def check(self, result=None, stale=None) -> list | None:
        """Run the live fabrication check (:class:`LiveCheck`) of ``result`` (default: current).

        Returns None, keeping the previous violations, when ``stale()`` turns true first.
        """
        if result is None:  # the current result, settled (a drag's cells made exact) first
            self.settle()
        start = time.perf_counter()
        found = self.live.run(self.result if result is None else result, stale)
        if found is not None:
            self.violations = found
            self.check_ms = (time.perf_counter() - start) * 1e3
        return found

    def controls(self) -> list[dict]:
        """The inputs of the current design (:func:`voroforge.studio.controls.controls`).

        Kept per design (a drag changes sites, not the design): the same list until it changes.
        """
        if self._controls is None or self._controls[0] is not self.design:
            self._controls = (self.design, controls(self.design))
        return self._controls[1]

    # --- edits -------------------------------------------------------------------------

    def _commit(self, data: dict, sites, *, remember: bool = True, rows=None) -> Reply:
        previous = self.result
        try:
            design, result = self._compute(data, sites)
            if sites is not None:  # a new boundary: hand-placed sites outside it go
                inside = shapely.contains_xy(result.domain, sites[:, 0], sites[:, 1])
                if not inside.all():
                    sites = sites[inside] if inside.any() else None
                    rows = None if rows is None or sites is None else (rows[0], rows[1][inside])
                    design, result = self._compute(data, sites)
        except DesignError as exc:
            return error_reply(exc)
        if remember:
            self._remember()
        self.data, self.sites, self.design, self.result = data, sites, design, result
        self.rows = rows if sites is not None else None
        self.frame = None
        return Reply("update", changed=changed_cells(previous, result))

    def _remember(self) -> None:
        self.history.append((self.data, self.sites, self.rows))
        del self.history[: -config.STUDIO_UNDO_DEPTH]
        self.future.clear()

    def _sites(self) -> np.ndarray:
        return (self.result.sites if self.sites is None else self.sites).copy()

    def _rows(self) -> tuple[dict, np.ndarray] | None:
        """:attr:`rows` of the sites an edit starts from (the seed file's rows at first)."""
        if self.sites is not None:
            return self.rows
        table = self.result.extra.get("seed_table")
        if table is None or not table.attributes or len(table.rows) != len(self.result.sites):
            return None
        return table.attributes, np.asarray(table.rows, dtype=np.int64)

    def _point(self, msg: dict) -> tuple[float, float]:
        x, y = number(msg.get("x"), "x"), number(msg.get("y"), "y")
        if not shapely.contains_xy(self.result.domain, x, y):
            raise BadMessage("", f"({x:g}, {y:g}) is outside the boundary")
        return x, y

    def _index(self, msg: dict, n: int, what: str = "i") -> int:
        i = msg.get(what)
        if not isinstance(i, int) or isinstance(i, bool) or not 0 <= i < n:
            raise BadMessage("", f"{what} must be an index below {n}; got {shown(i)}")
        return i

    def apply(self, msg) -> Reply:
        """Apply one message of the page.

        Messages (``op`` and its fields): ``set`` (``key``, ``value``), ``move`` (``i``, ``x``,
        ``y``, ``begin``), ``add`` (``x``, ``y``), ``remove`` (``i``), ``attractor`` (``a``,
        ``p``, ``x``, ``y``, ``begin``), ``undo``, ``redo``, ``save`` (``name``,
        ``overwrite``), ``export`` (``format``), ``reset_sites``.

        Returns
        -------
        Reply
            Errors for bad messages too: a message never raises.
        """
        self.ahead_used = False
        try:
            if not isinstance(msg, dict):
                raise BadMessage("", "a message is a JSON object with an 'op'")
            op = msg.get("op")
            handler = _OPS.get(op) if isinstance(op, str) else None
            if handler is None:
                raise BadMessage("", f"unknown op {shown(op, 30)}")
            return handler(self, msg)
        except BadMessage as exc:
            return Reply("error", issues=[{"key": exc.key, "message": exc.message}])
        except DesignError as exc:
            return error_reply(exc)
        except Exception as exc:  # noqa: BLE001 -- a message never raises
            # a message the checks above let through (an integer too large for a float, an
            # image over Pillow's limit, ...): answer it, keep the session as it was
            return Reply("error", issues=[{"key": "", "message": f"cannot apply: {exc}"[:300]}])

    def _op_set(self, msg: dict) -> Reply:
        key = msg.get("key")
        if not isinstance(key, str) or not re.fullmatch(r"[A-Za-z0-9_.]{1,80}", key):
            raise BadMessage("", "set needs a dotted key, e.g. seeds.count")
        value = plain(msg.get("value"), key)
        data = apply_overrides(self.data, {key: value})
        sites, rows = self.sites, self.rows
        if any(key == k or key.startswith(k + ".") for k in _RESEED):
            sites = None
            fast = self._reseed_fast(data) if self.frame is None else None
            if fast is not None:
                return fast
        reply = self._commit(data, sites, rows=rows)
        if reply.kind == "error":
            for it in reply.issues:
                it.setdefault("key", key)
                if not it["key"]:
                    it["key"] = key
        return reply

    def _reseed_fast(self, data: dict) -> Reply | None:
        """New seeds from ``[seeds]`` with only the cells near the changed ones recomputed.

        A random seed stream keeps its first seeds, so a ``seeds.count`` step adds or drops
        a few sites at the end (:func:`voroforge.studio.incremental.update`; provisional,
        settled like a drag). None when the design changed in more than how its seeds are
        made, when the seeds are relaxed (every site moves) or when too many sites changed:
        the caller recomputes in full (and reports any error).
        """
        from ..design import compute as dc
        from . import incremental

        if not self.incremental or not incremental.eligible(self.result):
            return None
        try:
            design, _ = load(data)
            self._guard(design)
        except DesignError:
            return None
        prev = self.result.design
        if design.relax.iterations or design.relax.tolerance is not None:
            return None
        keep = {"seeds": prev.seeds, "relax": prev.relax}
        keep["design"] = design.design.model_copy(update={"seed": prev.design.seed})
        if design.model_copy(update=keep) != prev:
            return None  # more than the seeds changed: the full computation
        start = time.perf_counter()
        field_fn = self._field_fn()
        try:
            points = dc.make_seeds(design, self.result.domain, field_fn, self.folder)
        except (DesignError, ValueError, OSError):
            return None
        if not 1 <= len(points) <= self.max_seeds:
            return None
        if design.seeds.method not in ("file", "curves"):
            # the full computation that follows a None takes these seeds as they are (the
            # same ones: no relax; a file's rows and curves' edges come only from [seeds])
            self._seeded = (data, design, points)
        fast = incremental.update(self.result, points, field_fn, design=design)
        if fast is None:
            return None
        self._seeded = None
        self.compute_ms = (time.perf_counter() - start) * 1e3
        self._remember()
        self.data, self.sites, self.rows, self.design, self.result = (
            data,
            None,
            None,
            design,
            fast[0],
        )
        self.frame = None
        return Reply("update", changed=fast[1])

    def _op_move(self, msg: dict) -> Reply:
        sites, rows = self._sites(), self._rows()
        i = self._index(msg, len(sites))
        sites[i] = self._point(msg)
        remember = bool(msg.get("begin", True))
        fast = self._move_fast(i, sites[i]) if self.frame is None else None
        if fast is None:
            return self._commit(self.data, sites, remember=remember, rows=rows)
        result, changed = fast
        if remember:
            self._remember()
        self.sites, self.rows, self.result = sites, rows, result
        return Reply("update", changed=changed)

    def _move_fast(self, i: int, xy):
        """:func:`voroforge.studio.incremental.move` of the current result, or None."""
        from . import incremental

        if not self.incremental or not incremental.eligible(self.result):
            return None
        start = time.perf_counter()
        try:
            fast = incremental.move(self.result, i, xy, self._field_fn())
        except (ValueError, DesignError):  # anything unusual: the full compute decides
            return None
        if fast is not None:
            self.compute_ms = (time.perf_counter() - start) * 1e3
        return fast

    def _field_fn(self):
        """The current design's attractor field (cached per design), or None."""
        from ..design.compute import attractor_field

        design = self.result.design
        if self._field_cache is None or self._field_cache[0] is not design:
            self._field_cache = (design, attractor_field(design, self.folder))
        return self._field_cache[1]

    @property
    def provisional(self) -> bool:
        """Whether the current result came from a seed drag not yet :meth:`settle`-d."""
        return bool(self.result.extra.get("provisional"))

    def settle(self) -> np.ndarray | None:
        """Replace a provisional result (a drag's) by the full computation's own.

        Cells whose raw ring is byte-identical keep their operated cells (``compute``'s
        ``reuse``), so this costs about one engine run. Returns the indices of the cells
        whose drawing differs from the provisional one (often none), or None when there was
        nothing to settle. :meth:`settle_compute` and :meth:`settle_finish` are the same in
        two steps, for a server that computes while edits go on.
        """
        if not self.provisional:
            return None
        previous = self.result
        return self.settle_finish(previous, self.settle_compute(previous))

    def settle_compute(self, previous):
        """The full computation of a provisional result ``previous`` (does not change self)."""
        start = time.perf_counter()
        sites = previous.sites
        result = compute(
            previous.design,
            self.folder,
            sites=sites,
            reuse=previous,
            frame=False,
            workers=self.workers,
        )
        self.settle_ms = (time.perf_counter() - start) * 1e3
        return result

    def settle_finish(self, previous, result) -> np.ndarray | None:
        """Put ``result`` (of :meth:`settle_compute`) in place of ``previous``.

        Returns the cells whose drawing differs, or None when an edit replaced ``previous``
        meanwhile (``result`` is then out of date and dropped).
        """
        if self.result is not previous:
            return None
        self.result = result
        if len(result.raw) != len(previous.raw):
            return np.arange(len(result.raw), dtype=np.int32)
        same = (result.extra["raw_wkb"] == previous.extra["raw_wkb"]) & (
            result.mask == previous.mask
        )
        redone = result.extra.get("redone")
        if redone is not None and len(redone):
            cells_same = shapely.to_wkb(result.cells[redone]) == shapely.to_wkb(
                previous.cells[redone]
            )
            same[redone] &= cells_same
        return np.flatnonzero(~same).astype(np.int32)

    def _op_add(self, msg: dict) -> Reply:
        sites, rows = self._sites(), self._rows()
        if len(sites) >= self.max_seeds:
            raise BadMessage("seeds", f"the studio's limit is {self.max_seeds} seeds")
        rows = None if rows is None else (rows[0], np.append(rows[1], -1))
        return self._commit(self.data, np.vstack((sites, [self._point(msg)])), rows=rows)

    def _op_remove(self, msg: dict) -> Reply:
        sites, rows = self._sites(), self._rows()
        i = self._index(msg, len(sites))
        if len(sites) <= 1:
            raise BadMessage("seeds", "the last seed cannot be removed")
        rows = None if rows is None else (rows[0], np.delete(rows[1], i))
        return self._commit(self.data, np.delete(sites, i, axis=0), rows=rows)

    def _op_attractor(self, msg: dict) -> Reply:
        attractors = self.data.get("attractors") or []
        a = self._index(msg, len(attractors), "a")
        points = attractors[a].get("points")
        if not isinstance(points, list) or not points:
            raise BadMessage(f"attractors.{a}", "this attractor has no points to drag")
        p = self._index(msg, len(points), "p")
        x, y = number(msg.get("x"), "x"), number(msg.get("y"), "y")
        data = apply_overrides(self.data, {f"attractors.{a}.points.{p}": [x, y]})
        return self._commit(data, self.sites, remember=bool(msg.get("begin", True)), rows=self.rows)

    def _op_frame(self, msg: dict) -> Reply:
        """Show frame ``k`` of the design's ``[animation]`` (not an edit: no undo step).

        The sites of frame 0 are kept for every frame (hand-edited ones if any);
        ``animation.relax`` Lloyd steps move them from the previous frame, as in
        :func:`~voroforge.studio.animation.frames`: a frame scrubbed to first has the sites of
        the frames before it relaxed in order (in each frame's own domain), so frame ``k``
        is the same in any order of scrubbing.
        """
        from .animation import frame_design, named_error

        section = self.design.animation
        if section is None:
            raise BadMessage("animation", "the design has no [animation] table")
        k = self._index(msg, section.frames, "k")
        key = (id(self.data), id(self.sites))
        if self._anim is None or self._anim["key"] != key:
            sites = self.sites
            if sites is None:
                sites = compute(frame_design(self.data, section, 0), self.folder).sites
            self._anim = {"key": key, "sites": {0: sites}, "domains": {}}
        known = self._anim["sites"]
        for i in range(max(known) + 1, k + 1):  # known holds frames 0 .. max(known)
            sites = known[i - 1]
            if section.relax:
                from ..design.relax import relax

                domain = self._frame_domain(section, i - 1)
                sites = relax(sites, domain, iterations=section.relax)
            known[i] = sites
        sites = known[k]
        previous = self.result
        start = time.perf_counter()
        try:
            result = compute(
                frame_design(self.data, section, k),
                self.folder,
                sites=sites,
                reuse=previous,
                frame=False,
            )
        except DesignError as exc:
            raise named_error(exc, section, k) from None
        self.compute_ms = (time.perf_counter() - start) * 1e3
        self.result, self.frame = result, k
        self._anim["domains"][k] = result.domain
        return Reply("update", changed=changed_cells(previous, result))

    def _frame_domain(self, section, i: int):
        """The domain of animation frame ``i``, whose sites are known (to relax them)."""
        from .animation import frame_design, named_error

        domains = self._anim["domains"]
        if i in domains:
            return domains[i]
        if not any(t.key.split(".")[0] in ("boundary", "design") for t in section.tracks):
            return self.result.domain  # no track moves the boundary: one domain for all
        try:  # the boundary moves: frame i's own, as animation.frames relaxes in
            _, domains[i] = outline(frame_design(self.data, section, i), self.folder)
        except DesignError as exc:
            raise named_error(exc, section, i) from None
        return domains[i]

    def _op_reset_sites(self, msg: dict) -> Reply:
        return self._commit(self.data, None)

    def _op_undo(self, msg: dict) -> Reply:
        return self._travel(self.history, self.future, "nothing to undo")

    def _op_redo(self, msg: dict) -> Reply:
        return self._travel(self.future, self.history, "nothing to redo")

    def _travel(self, source: list, target: list, empty: str) -> Reply:
        if not source:
            return Reply("info", note=empty)
        data, sites, rows = source[-1]
        previous = self.result
        try:
            design, result = self._compute(data, sites)
        except DesignError as exc:
            return error_reply(exc)
        source.pop()
        target.append((self.data, self.sites, self.rows))
        self.data, self.sites, self.rows, self.design, self.result = (
            data,
            sites,
            rows,
            design,
            result,
        )
        self.frame = None
        return Reply("update", changed=changed_cells(previous, result))

    # --- files -------------------------------------------------------------------------

    def saved_data(self, seeds_file: str | None) -> tuple[dict, str | None]:
        """The design mapping as saved, and the text of hand-edited sites (or None).

        The text is CSV (``x,y``) written to ``seeds_file``; when the sites came from a seed
        file with attributes it is GeoJSON, and ``data["seeds"]["file"]`` names
        ``seeds_file`` with the suffix ``.geojson`` (each site with its row's properties).
        """
        data = copy.deepcopy(self.data)
        if self.sites is None:
            return data, None
        data.pop("relax", None)
        if self.rows is None:
            data["seeds"] = {"method": "file", "file": seeds_file}
            lines = ["x,y", *(f"{float(x)!r},{float(y)!r}" for x, y in self.sites)]
            return data, "\n".join(lines) + "\n"
        data["seeds"] = {"method": "file", "file": str(Path(seeds_file).with_suffix(".geojson"))}
        return data, _points_geojson(self.sites, *self.rows)

    def _op_save(self, msg: dict) -> Reply:
        name = msg.get("name")
        if not isinstance(name, str) or not _NAME.fullmatch(name) or ".." in name:
            raise BadMessage(
                "save", "save as a plain file name ending in .toml, in the design's folder"
            )
        target = (self.folder / name).resolve()
        if target.parent != self.folder:
            raise BadMessage("save", "saves go only into the design's folder")
        data, csv = self.saved_data(target.stem + ".seeds.csv")
        text = dumps(data, comment="Saved by voroforge studio; build: voroforge build " + name)
        files = {target: text}
        if csv is not None:
            files = {self.folder / data["seeds"]["file"]: csv, target: text}
        exists = [p.name for p in files if p.exists() or p.is_symlink()]
        if exists and msg.get("overwrite") is not True:
            return Reply("confirm", files=exists, name=name)
        for p in files:
            if p.is_symlink():
                raise BadMessage("save", f"{p.name} is a link; not writing through it")
        for p, content in files.items():
            write_atomic(p, content)
        return Reply("saved", name=name, files=[p.name for p in files])

    def _op_export(self, msg: dict) -> Reply:
        fmt = msg.get("format")
        if not isinstance(fmt, str) or fmt not in EXPORTS:
            raise BadMessage("export", f"export as one of {', '.join(EXPORTS)}")
        name, raw = self.export(fmt)
        return Reply("file", name=name, mime=EXPORTS[fmt], data=raw)

    def export(self, fmt: str) -> tuple[str, bytes]:
        """Build the current design's ``fmt`` file as ``voroforge build`` would; (name, bytes)."""
        with tempfile.TemporaryDirectory(prefix="voroforge-studio-") as tmp:
            tmp = Path(tmp)
            data, csv = self.saved_data("studio.seeds.csv")
            _absolute_files(data, self.folder)
            if csv is not None:
                (tmp / data["seeds"]["file"]).write_text(csv, encoding="utf-8")
            data.setdefault("output", {})["formats"] = [fmt]
            data.setdefault("fabrication", {})["report"] = False
            (tmp / "studio.toml").write_text(dumps(data), encoding="utf-8")
            written = build(tmp / "studio.toml", tmp / "out")
            path = next(p for p in written if p.suffix == f".{fmt}")
            return path.name, path.read_bytes()


class _Stale(Exception):
    """A computation ahead given up: an edit came first."""


def _same_data(a, b) -> bool:
    """Whether two design mappings are the same, types included (3 is not 3.0 here)."""
    if type(a) is not type(b):
        return False
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(_same_data(a[k], b[k]) for k in a)
    if isinstance(a, list):
        return len(a) == len(b) and all(_same_data(x, y) for x, y in zip(a, b, strict=True))
    return a == b


def _points_geojson(sites: np.ndarray, attributes: dict, rows: np.ndarray) -> str:
    """GeoJSON of ``sites``, each with its file row's properties (nulls for row -1)."""
    features = []
    for (x, y), r in zip(sites.tolist(), rows.tolist(), strict=True):
        props = {k: (col[r] if r >= 0 else None) for k, col in attributes.items()}
        point = {"type": "Point", "coordinates": [float(x), float(y)]}
        features.append({"type": "Feature", "properties": props, "geometry": point})
    return json.dumps({"type": "FeatureCollection", "features": features}, indent=1) + "\n"


def _absolute_files(data: dict, folder: Path) -> None:
    """Make the design's file names absolute (for a copy of the design written elsewhere)."""

    def fix(table, key):
        if isinstance(table, dict) and isinstance(table.get(key), str):
            p = Path(table[key])
            if not p.is_absolute():
                table[key] = str(folder / p)

    fix(data.get("boundary"), "file")
    if (data.get("seeds") or {}).get("file") not in ("studio.seeds.csv", "studio.seeds.geojson"):
        fix(data.get("seeds"), "file")
    for a in data.get("attractors") or []:
        fix(a, "file")


_OPS = {
    "set": Session._op_set,
    "move": Session._op_move,
    "add": Session._op_add,
    "remove": Session._op_remove,
    "attractor": Session._op_attractor,
    "reset_sites": Session._op_reset_sites,
    "frame": Session._op_frame,
    "undo": Session._op_undo,
    "redo": Session._op_redo,
    "save": Session._op_save,
    "export": Session._op_export,
}
