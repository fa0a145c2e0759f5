"""The studio without a browser: sessions, incremental compute, live check, save, server safety."""

from __future__ import annotations

import json
import os
import random
import tomllib
from pathlib import Path

import numpy as np
import pytest
import shapely
from hypothesis import example, given, settings
from hypothesis import strategies as st

pytest.importorskip("starlette")

from voroforge.design.compute import compute  # noqa: E402
from voroforge.design.designfile import DesignError, load  # noqa: E402
from voroforge.design.fabrication import check  # noqa: E402
from voroforge.studio import tomlfile, wire  # noqa: E402
from voroforge.studio.controls import controls  # noqa: E402
from voroforge.studio.livecheck import LiveCheck, limits_of  # noqa: E402
from voroforge.studio.session import Session  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]

HOLED = {
    "design": {"name": "holed", "seed": 3},
    "boundary": {
        "shape": "polygon",
        "points": [[0, 0], [300, 0], [300, 200], [0, 200]],
        "holes": [[[120, 70], [180, 70], [180, 130], [120, 130]]],
    },
    "seeds": {"method": "random", "count": 60},
    "cells": {"web": 2.0, "fillet": 1.5},
    "output": {"formats": ["svg", "dxf", "png"], "png_size": 200},
    "fabrication": {"min_web": 2.5, "min_opening": 8, "tool_radius": 1.0},
}


@pytest.fixture
def folder(tmp_path):
    path = tmp_path / "holed.toml"
    path.write_text(tomlfile.dumps(HOLED), encoding="utf-8")
    return tmp_path


def _wkb(geoms):
    return list(shapely.to_wkb(np.asarray(geoms, dtype=object)))


def _same_result(a, b):
    assert np.array_equal(a.sites, b.sites)
    assert _wkb(a.raw) == _wkb(b.raw)
    assert _wkb(a.cells) == _wkb(b.cells)
    assert np.array_equal(a.mask, b.mask)
    assert shapely.to_wkb(a.frame) == shapely.to_wkb(b.frame)


# --- incremental compute -------------------------------------------------------------------


def test_reuse_gives_the_fresh_geometry_and_redoes_only_the_neighbourhood():
    design, _ = load(HOLED)
    first = compute(design)
    sites = first.sites.copy()
    sites[10] += (2.0, -1.5)
    again = compute(design, sites=sites, reuse=first)
    fresh = compute(design, sites=sites)
    _same_result(again, fresh)
    redone = again.extra["redone"]
    assert 10 in redone and 0 < len(redone) < len(sites) // 4
    # a changed [cells] section reuses nothing, and is still right
    d2, _ = load({**HOLED, "cells": {"web": 3.0, "fillet": 1.0}})
    _same_result(compute(d2, sites=sites, reuse=again), compute(d2, sites=sites))


def test_reuse_with_attractor_values_and_a_changed_boundary():
    data = {
        **HOLED,
        "attractors": [{"type": "point", "points": [[50, 50]], "radius": 150}],
        "cells": {"web": {"near": 1, "far": 4}},
    }
    design, _ = load(data)
    first = compute(design)
    moved, _ = load(
        {**data, "attractors": [{"type": "point", "points": [[60, 80]], "radius": 150}]}
    )
    _same_result(compute(moved, sites=first.sites, reuse=first), compute(moved, sites=first.sites))
    margin, _ = load({**data, "boundary": {**data["boundary"], "margin": 6}})
    inside = shapely.contains_xy(compute(margin).domain, *first.sites.T)
    pts = first.sites[inside]
    _same_result(compute(margin, sites=pts, reuse=first), compute(margin, sites=pts))


def _normalized(geoms):
    return list(shapely.to_wkb(shapely.normalize(np.asarray(geoms, dtype=object))))


def _close(a, b, tol=1e-9):
    """The same rings and vertices to ``tol`` (any first vertex, any part order)."""
    a, b = shapely.normalize(a), shapely.normalize(b)
    return bool(shapely.equals_exact(a, b, tolerance=tol).all())


MANY = {**HOLED, "seeds": {"method": "random", "count": 200}}
DRAGGED = {  # designs whose seed drags take the incremental path, one per kind of selection
    "holed, inset + fillet": MANY,
    "field-graded webs, field openings": {
        **MANY,
        "attractors": [{"type": "point", "points": [[60, 60]], "radius": 160}],
        "cells": {"web": {"near": 1.0, "far": 3.0}},
        "openings": {"select": "field", "threshold": 0.2},
    },
    "largest openings, margin": {
        **MANY,
        "boundary": {**HOLED["boundary"], "margin": 4},
        "openings": {"select": "largest", "count": 30},
        "cells": {"inset": 1.0},
    },
    "area window, plain cells": {
        **MANY,
        "cells": {},
        "openings": {"select": "area", "min_area": 150},
    },
    "circle with a curved outline, fillet": {  # cells cut by a 256-gon: GEOS, not the engine
        **MANY,
        "boundary": {"shape": "circle", "radius": 110, "center": [150, 100]},
        "cells": {"fillet": 2.0},
    },
}


@pytest.mark.parametrize("name", list(DRAGGED))
def test_drag_recomputes_the_neighbourhood_and_settles_to_the_full_compute(name):
    s = Session(DRAGGED[name])
    rng = np.random.default_rng(len(name))
    fast = tried = 0
    for step in range(16):
        before = s.result
        n = len(before.sites)
        i = int(rng.integers(n))
        scale = 40.0 if step % 5 == 3 else 4.0  # now and then a long jump
        x, y = before.sites[i] + rng.normal(0.0, scale, 2)
        if not shapely.contains_xy(before.domain, x, y):
            continue
        reply = s.apply({"op": "move", "i": i, "x": float(x), "y": float(y), "begin": step == 0})
        assert reply.kind == "update"
        tried += 1
        now = s.result
        fast += s.provisional
        full = compute(s.design, s.folder, sites=s.sites, frame=False)
        # the cells are the full diagram's point for point (a ring may start elsewhere, and
        # where GEOS cuts a cell with the domain's outline a vertex may be an ulp away)
        assert _close(now.raw, full.raw)
        assert np.array_equal(now.sites, full.sites) and np.array_equal(now.mask, full.mask)
        assert np.allclose(now.values, full.values, rtol=1e-12, atol=1e-12)
        gap = shapely.area(shapely.symmetric_difference(now.cells, full.cells))
        assert (gap <= 1e-9 * (1.0 + shapely.area(full.cells))).all()
        # what the page is sent: every cell that changed, nothing else changed
        moved = np.flatnonzero(np.array(_normalized(before.raw)) != np.array(_normalized(now.raw)))
        moved = np.union1d(moved, np.flatnonzero(before.mask != now.mask))
        assert set(moved.tolist()) <= set(reply.changed.tolist())
        others = np.setdiff1d(np.arange(n), reply.changed)
        assert _wkb(before.raw[others]) == _wkb(now.raw[others])
        assert _wkb(before.cells[others]) == _wkb(now.cells[others])
        if step % 5 == 4 or step == 15:  # the edits pause: exactly the full computation
            s.settle()
            assert not s.provisional
            settled = s.result
            assert _wkb(settled.raw) == _wkb(full.raw)
            assert _wkb(settled.cells) == _wkb(full.cells)
            assert np.array_equal(settled.values, full.values)
            assert np.array_equal(settled.mask, full.mask)
            assert _wkb(settled.openings) == _wkb(full.openings)
    assert fast >= 0.7 * tried > 8  # the drags took the incremental path
    # undo from a provisional result is the full computation of the earlier sites
    s.apply(
        {"op": "move", "i": 0, "x": float(s.result.sites[0, 0]), "y": 1.0 + s.result.sites[0, 1]}
    )
    assert s.apply({"op": "undo"}).kind == "update" and not s.provisional
    _same = compute(s.design, s.folder, sites=s.sites, frame=False)
    assert _wkb(s.result.cells) == _wkb(_same.cells)


def test_compute_workers_give_the_same_cells():
    design, _ = load({**HOLED, "seeds": {"method": "random", "count": 700}})
    one = compute(design, frame=False)
    three = compute(design, frame=False, workers=3)  # threads split the cells
    assert _wkb(one.cells) == _wkb(three.cells) and len(one.cells) >= 3 * 200
    # a negative web is refused by the schema (with its line), before any worker runs
    with pytest.raises(DesignError, match=r"cells\.web"):
        load({**HOLED, "seeds": {"method": "random", "count": 700}, "cells": {"web": -1}})


@pytest.mark.parametrize("name", ["holed, inset + fillet", "field-graded webs, field openings"])
def test_count_steps_recompute_only_the_cells_near_the_added_or_dropped_seeds(name):
    s = Session({**DRAGGED[name], "seeds": {"method": "random", "count": 600}})
    fast = 0
    for count in (603, 598, 599, 640, 639, 560):
        before = s.result
        reply = s.apply({"op": "set", "key": "seeds.count", "value": count})
        assert reply.kind == "update" and s.sites is None  # the seeds still come from [seeds]
        fast += s.provisional
        now = s.result
        full = compute(s.design, s.folder, frame=False)
        assert len(now.raw) == count and np.array_equal(now.sites, full.sites)
        assert _close(now.raw, full.raw) and np.array_equal(now.mask, full.mask)
        gap = shapely.area(shapely.symmetric_difference(now.cells, full.cells))
        assert (gap <= 1e-9 * (1.0 + shapely.area(full.cells))).all()
        m = min(len(before.raw), count)  # the page is sent every cell that changed
        moved = np.flatnonzero(np.array(_normalized(before.raw[:m])) != _normalized(now.raw[:m]))
        assert set(moved.tolist()) | set(range(m, count)) <= set(reply.changed.tolist())
        s.settle()
        assert _wkb(s.result.cells) == _wkb(full.cells) and _wkb(s.result.raw) == _wkb(full.raw)
    assert fast >= 4  # the small steps took the incremental path (560: 79 dropped, in full)
    # hand-moved seeds, then a count step: the seeds come from [seeds] again
    x, y = s.result.sites[7]
    s.apply({"op": "move", "i": 7, "x": float(x) + 2.0, "y": float(y)})
    assert s.sites is not None
    s.apply({"op": "set", "key": "seeds.count", "value": 562})
    assert s.sites is None and s.provisional
    full = compute(s.design, s.folder, frame=False)
    assert np.array_equal(s.result.sites, full.sites) and _close(s.result.raw, full.raw)
    # every seed new, or more than the seeds changed: the full computation
    assert s.apply({"op": "set", "key": "design.seed", "value": 9}).kind == "update"
    assert not s.provisional  # computed on the seeds the fast path had sampled: the same
    full = compute(s.design, s.folder, frame=False)
    assert np.array_equal(s.result.sites, full.sites) and s.sites is None
    assert _wkb(s.result.cells) == _wkb(full.cells) and _wkb(s.result.raw) == _wkb(full.raw)
    s.apply({"op": "set", "key": "seeds.count", "value": 561})
    assert s.provisional
    s.apply({"op": "set", "key": "cells.fillet", "value": 0.5})
    assert not s.provisional
    assert s.apply({"op": "undo"}).kind == "update" and len(s.result.raw) == 561


def test_fabrication_limits_keep_the_cells():
    s = Session(MANY)
    s.apply({"op": "move", "i": 4, "x": float(s.result.sites[4, 0]) + 0.5, "y": 50.0})
    before = s.result
    reply = s.apply({"op": "set", "key": "fabrication.min_web", "value": 3.5})
    assert reply.kind == "update" and len(reply.changed) == 0
    assert s.result.raw is before.raw and s.result.design.fabrication.min_web == 3.5
    s.settle()
    full = compute(s.design, s.folder, sites=s.sites, frame=False)
    assert _wkb(s.result.cells) == _wkb(full.cells) and s.result.design == full.design
    # a geometry key is computed again
    again = s.apply({"op": "set", "key": "cells.fillet", "value": 1.0})
    assert again.kind == "update" and (again.changed is None or len(again.changed))
    assert _wkb(s.result.cells) != _wkb(full.cells)


def test_a_settling_overtaken_by_an_edit_is_dropped():
    s = Session(MANY)
    x, y = s.result.sites[9]
    s.apply({"op": "move", "i": 9, "x": float(x) + 0.5, "y": float(y)})
    first = s.result
    late = s.settle_compute(first)  # the server computes this while the next step arrives
    s.apply({"op": "move", "i": 9, "x": float(x) + 1.0, "y": float(y)})
    assert s.settle_finish(first, late) is None and s.provisional and s.result is not late
    assert s.settle() is not None and not s.provisional
    full = compute(s.design, s.folder, sites=s.sites, frame=False)
    assert _wkb(s.result.cells) == _wkb(full.cells)


def test_drag_onto_another_seed_and_across_the_panel():
    from voroforge.studio import incremental

    s = Session(HOLED)
    other = s.result.sites[7].copy()
    s.apply({"op": "move", "i": 3, "x": float(other[0]), "y": float(other[1])})  # a duplicate
    full = compute(s.design, s.folder, sites=s.sites, frame=False)
    assert _close(s.result.raw, full.raw)
    assert shapely.is_empty(s.result.raw[[3, 7]]).sum() == 1  # the later copy has no cell
    s.settle()
    far = incremental.move(s.result, 5, (295.0, 195.0))  # a jump across the whole panel
    if far is not None:
        sites = s.result.sites.copy()
        sites[5] = (295.0, 195.0)
        full = compute(s.design, s.folder, sites=sites, frame=False)
        assert _close(far[0].raw, full.raw)


def test_warm_runs_a_drag_step_and_keeps_the_session_as_it_was():
    s = Session(HOLED)
    result, raw, cells = s.result, _wkb(s.result.raw), _wkb(s.result.cells)
    assert "domain_box" not in result.extra  # what a drag step's first call computes
    s.warm()
    assert s.result is result and not s.provisional and not s.history and s.sites is None
    assert _wkb(s.result.raw) == raw and _wkb(s.result.cells) == cells
    assert "domain_box" in result.extra and "raw_bounds" in result.extra
    # the first drag step after it: the same cells as without it
    x, y = result.sites[4]
    s.apply({"op": "move", "i": 4, "x": float(x) + 0.5, "y": float(y), "begin": True})
    cold = Session(HOLED)
    cold.apply({"op": "move", "i": 4, "x": float(x) + 0.5, "y": float(y), "begin": True})
    assert s.provisional and _wkb(s.result.raw) == _wkb(cold.result.raw)
    assert _wkb(s.result.cells) == _wkb(cold.result.cells)


def test_a_warm_up_that_fails_does_not_stop_the_server(monkeypatch):
    from voroforge.studio import incremental

    def broken(*args, **kwargs):
        raise RuntimeError("a kernel that fails")

    s = Session(HOLED)
    result = s.result
    monkeypatch.setattr(incremental, "move", broken)
    s.warm()  # no exception: the server starts anyway
    assert s.result is result and not s.provisional


def test_a_bad_design_file_is_reported_with_its_name_line_and_key(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('[boundary]\nshape = "rectangle"\nwidth = 10\nheight = 5\n[cells]\nfilet = 2\n')
    with pytest.raises(DesignError, match=r"bad\.toml:6: cells\.filet: unknown key"):
        Session(bad)
    bad.write_text("[design]\n[cells\n")
    with pytest.raises(DesignError, match=r"bad\.toml:2: .*TOML syntax"):
        Session(bad)


def test_sites_must_be_finite_pairs():
    design, _ = load(HOLED)
    with pytest.raises(ValueError, match="sites"):
        compute(design, sites=np.array([[1.0, np.nan]]))
    with pytest.raises(ValueError, match="sites"):
        compute(design, sites=np.zeros((3, 3)))


# --- live fabrication check ----------------------------------------------------------------


def _full_check(result):
    lim = limits_of(result.design)
    return check(openings=result.openings, boundary=result.boundary, **lim).violations


def _key(vs):
    """Violations as a sorted list (check's order is its own business; the set must match)."""
    return sorted(
        (v.kind, tuple(v.items), round(v.value, 9), tuple(np.round(v.location, 9)).__repr__())
        for v in vs
    )


def test_live_check_equals_the_full_check_after_edits(folder):
    s = Session(folder / "holed.toml")
    assert _key(s.check()) == _key(_full_check(s.result))
    rng = np.random.default_rng(1)
    for _ in range(1):
        i = int(rng.integers(len(s.result.sites)))
        x, y = s.result.sites[i] + rng.normal(0, 4, 2)
        if shapely.contains_xy(s.result.domain, x, y):
            assert s.apply({"op": "move", "i": i, "x": float(x), "y": float(y)}).kind == "update"
        assert _key(s.check()) == _key(_full_check(s.result))
    # tighter limits: many webs, the same list as check()
    assert s.apply({"op": "set", "key": "fabrication.min_web", "value": 4.5}).kind == "update"
    live = s.check()
    assert live and _key(live) == _key(_full_check(s.result))


def test_live_check_reports_islands():
    data = {  # whole cells cut out (no web): a cell between openings falls out
        "boundary": {"shape": "rectangle", "width": 100, "height": 100},
        "seeds": {"method": "random", "count": 30},
        "openings": {"select": "every_kth", "k": 3},
    }
    design, _ = load(data)
    r = compute(design, frame=False)
    live = LiveCheck().run(r)
    assert any(v.kind == "island" for v in live)
    assert _key(live) == _key(check(openings=r.openings, boundary=r.boundary).violations)


def test_live_check_leaves_the_results_boundary_alone():
    """The check runs in a worker thread while drag steps test containment in the domain (the
    boundary object, prepared): it must not prepare or query that object itself (two threads
    on one prepared GEOS polygon crashed the server)."""
    data = {
        "boundary": {"shape": "rectangle", "width": 100, "height": 100},
        "seeds": {"method": "random", "count": 30},
        "openings": {"select": "every_kth", "k": 3},
    }
    r = compute(load(data)[0], frame=False)
    shapely.destroy_prepared(r.boundary)
    live = LiveCheck()
    found = live.run(r)
    assert any(v.kind == "island" for v in found)  # the islands' frame was cut
    assert not shapely.is_prepared(r.boundary)
    assert live.run(r) == found  # and the copy is kept


# --- sessions ------------------------------------------------------------------------------


def test_edits_undo_redo(folder):
    s = Session(folder / "holed.toml")
    n = len(s.result.sites)
    x, y = s.result.sites[0]
    assert s.apply({"op": "add", "x": 5.0, "y": 5.0}).kind == "update"
    assert len(s.result.sites) == n + 1 and len(s.result.raw) == n + 1
    assert s.apply({"op": "remove", "i": 0}).kind == "update"
    assert len(s.result.sites) == n and not np.array_equal(s.result.sites[0], (x, y))
    assert s.apply({"op": "undo"}).kind == "update"
    assert len(s.result.sites) == n + 1
    assert s.apply({"op": "undo"}).kind == "update"
    assert s.sites is None and len(s.result.sites) == n
    assert s.apply({"op": "undo"}).kind == "info"
    assert s.apply({"op": "redo"}).kind == "update" and len(s.result.sites) == n + 1
    r = s.apply({"op": "set", "key": "seeds.count", "value": 60})
    assert r.kind == "update" and len(s.result.sites) == 60 and s.sites is None
    assert not s.future


def test_bad_values_keep_the_last_good_drawing_and_name_the_key(folder):
    s = Session(folder / "holed.toml")
    good = s.result
    for key, value, words in [
        ("seeds.count", -5, "greater than 0"),
        ("cells.web", -1, ">= 0"),
        ("seeds.count", 10**7, "limit"),
        ("relax.iterations", 5000, "less than or equal"),
        ("seeds.count", "many", "integer"),
        ("seeds.radius", 2**70, "64-bit"),  # no design file could hold it (checker21)
    ]:
        r = s.apply({"op": "set", "key": key, "value": value})
        assert r.kind == "error", (key, value)
        assert r.issues[0]["key"] == key and words in r.issues[0]["message"], r.issues
        assert s.result is good
    assert s.apply({"op": "set", "key": "seeds.method", "value": "poisson"}).kind == "error"
    r = s.apply({"op": "set", "key": "seeds", "value": {"method": "poisson", "radius": 0.001}})
    assert r.kind == "error" and "limit" in r.issues[0]["message"]
    assert s.result is good
    # a spacing whose square underflows: the limit at its key (was "float division by zero")
    r = s.apply({"op": "set", "key": "seeds", "value": {"method": "grid", "spacing": 1e-300}})
    assert r.kind == "error" and r.issues[0]["key"] == "seeds.spacing", r.issues
    assert "limit" in r.issues[0]["message"]
    assert s.result is good


def test_dragging_an_attractor_point_or_a_curve_handle(folder):
    curve = {
        **HOLED,
        "attractors": [
            {"type": "curve", "points": [[10, 10], [150, 190], [290, 10]], "radius": 60},
            {"type": "point", "points": [[250, 150]], "radius": 50},
        ],
        "cells": {"web": {"near": 1, "far": 4}},
    }
    s = Session(curve, folder=folder)
    before = _wkb(s.result.cells)
    r = s.apply({"op": "attractor", "a": 0, "p": 1, "x": 150.0, "y": 20.0, "begin": True})
    assert r.kind == "update" and s.design.attractors[0].points[1] == (150.0, 20.0)
    assert s.data["attractors"][0]["points"][0] == [10, 10]  # the other handles stay
    moved = _wkb(s.result.cells)
    assert moved != before
    full = compute(s.design, s.folder, frame=False)
    assert moved == _wkb(full.cells)  # the same as building the edited design
    r = s.apply({"op": "attractor", "a": 1, "p": 0, "x": 20.0, "y": 20.0})
    assert r.kind == "update" and s.design.attractors[1].points[0] == (20.0, 20.0)
    for bad in ({"a": 2, "p": 0}, {"a": 0, "p": 3}, {"a": 0, "p": 0, "x": "far"}):
        assert s.apply({"op": "attractor", "x": 1.0, "y": 1.0, **bad}).kind == "error"
    s.apply({"op": "undo"})
    s.apply({"op": "undo"})
    assert _wkb(s.result.cells) == before


def test_malformed_messages_never_raise(folder):
    s = Session(folder / "holed.toml")
    good = s.result
    rng = random.Random(5)
    ops = ["move", "add", "remove", "set", "attractor", "save", "export", "undo", "nope", None, 3]
    junk = [None, -1, 10**9, 1e308, "x", [], {}, [1, 2], True, "../../etc", float("nan")]
    for _ in range(300):
        msg = {"op": rng.choice(ops)}
        for k in rng.sample(["i", "x", "y", "key", "value", "name", "format", "a", "p"], 3):
            msg[k] = rng.choice(junk)
        if rng.random() < 0.1:
            msg = rng.choice(junk)
        r = s.apply(msg)
        assert r.kind in ("error", "info", "update", "confirm", "file"), msg
    assert len(s.result.raw) >= 1
    assert s.apply({"op": "move", "i": 0, "x": 1e9, "y": 0}).kind == "error"
    del good


def test_controls_cover_every_numeric_parameter():
    design, _ = load(ROOT / "examples" / "facade-panel.toml")
    keys = {c["key"]: c for c in controls(design)}
    for key in ("seeds.radius", "seeds.radius_max", "attractors.0.radius", "attractors.0.strength"):
        assert key in keys
    assert keys["cells.web"]["kind"] == "graded" and keys["cells.web"]["value"] == {
        "near": 8.0,
        "far": 40.0,
    }
    assert keys["recursion.depth"]["max"] == 6 and keys["seeds.jitter"]["max"] == 1
    assert keys["boundary.segments"]["min"] == 8
    assert all(c["min"] < c["max"] for c in keys.values())
    assert "design.units" not in keys and "fabrication.islands" not in keys


# --- save and export -----------------------------------------------------------------------


def test_save_rejects_paths_outside_the_folder(folder):
    s = Session(folder / "holed.toml")
    for name in [
        "../x.toml",
        "..\\x.toml",
        "/tmp/x.toml",
        "sub/x.toml",
        "x.txt",
        ".hidden.toml",
        "a/../x.toml",
        "",
        5,
        None,
        "x" * 300 + ".toml",
    ]:
        r = s.apply({"op": "save", "name": name})
        assert r.kind == "error", name
    assert sorted(p.name for p in folder.iterdir()) == ["holed.toml"]
    outside = folder.parent / f"outside-{os.getpid()}.toml"
    (folder / "link.toml").symlink_to(outside)
    r = s.apply({"op": "save", "name": "link.toml", "overwrite": True})
    assert r.kind == "error" and not outside.exists()


def test_save_confirms_before_overwriting(folder):
    s = Session(folder / "holed.toml")
    before = (folder / "holed.toml").read_bytes()
    r = s.apply({"op": "save", "name": "holed.toml"})
    assert r.kind == "confirm" and r.files == ["holed.toml"]
    assert (folder / "holed.toml").read_bytes() == before
    assert s.apply({"op": "save", "name": "holed.toml", "overwrite": True}).kind == "saved"
    assert tomllib.loads((folder / "holed.toml").read_text()) == HOLED
    assert not [p for p in folder.iterdir() if p.name.endswith(".tmp")]


def test_saved_file_builds_to_the_exported_bytes(folder):
    from voroforge.cli import main

    s = Session(folder / "holed.toml")
    x, y = s.result.sites[4]
    assert s.apply({"op": "move", "i": 4, "x": float(x) + 1.25, "y": float(y)}).kind == "update"
    assert s.apply({"op": "add", "x": 33.3, "y": 44.4}).kind == "update"
    assert s.apply({"op": "set", "key": "cells.fillet", "value": 0.75}).kind == "update"
    r = s.apply({"op": "save", "name": "edited.toml"})
    assert r.kind == "saved" and r.files == ["edited.seeds.csv", "edited.toml"]
    exported = {fmt: s.export(fmt) for fmt in ("svg", "dxf", "png")}
    out = folder / "out"
    assert main(["build", str(folder / "edited.toml"), "-o", str(out)]) == 0
    for fmt, (name, raw) in exported.items():
        assert (out / name).read_bytes() == raw, fmt
    # and the saved sites are the edited ones, bit for bit
    design, base = load(folder / "edited.toml")
    assert np.array_equal(compute(design, base).sites, s.result.sites)


# --- TOML writer ---------------------------------------------------------------------------

_scalars = st.one_of(
    st.integers(-(2**62), 2**62),
    st.floats(allow_nan=False, allow_infinity=False),
    st.booleans(),
    st.text(max_size=12),
)
_keys = st.text(min_size=1, max_size=8)
_values = st.recursive(_scalars, lambda inner: st.lists(inner, max_size=4), max_leaves=8)
_tables = st.dictionaries(_keys, _values, max_size=4)
_docs = st.dictionaries(
    _keys,
    st.one_of(
        _values,
        _tables,
        st.dictionaries(_keys, st.one_of(_values, _tables), max_size=3),
        st.lists(_tables.filter(bool), min_size=1, max_size=3),
        # items of an array of tables that hold sub-tables only, or nested arrays of tables
        st.lists(
            st.dictionaries(
                _keys, st.one_of(_tables, st.lists(_tables.filter(bool), min_size=1, max_size=2))
            ).filter(bool),
            min_size=1,
            max_size=3,
        ),
    ),
    max_size=5,
)


@settings(max_examples=40)
@given(_docs)
@example(doc={"0\n": [{"0": []}]})  # a key ending in a newline is not bare ("$" let it be)
# an item of sub-tables only kept its own [[a]] line (it was merged into the item before it,
# or two [a.b] tables made the file unreadable)
@example(doc={"a": [{"x": 1}, {"b": {"c": {"d": 1}}}]})
@example(doc={"a": [{"b": {"c": {"d": 1}}}, {"b": {"c": {"d": 2}}}]})
def test_toml_writer_round_trips(doc):
    assert tomllib.loads(tomlfile.dumps(doc)) == doc


def test_toml_writer_refuses_what_toml_cannot_hold():
    for bad in ({"a": float("nan")}, {"a": None}, {"a": object()}):
        with pytest.raises(ValueError):
            tomlfile.dumps(bad)


def test_examples_round_trip_through_the_writer():
    for path in sorted((ROOT / "examples").glob("*.toml")):
        data = tomllib.loads(path.read_text(encoding="utf-8"))
        assert tomllib.loads(tomlfile.dumps(data)) == data, path.name


# --- wire format ---------------------------------------------------------------------------


def test_wire_rings_and_pack_round_trip():
    geoms = np.asarray(
        [
            shapely.box(0, 0, 2, 1),
            shapely.Polygon(),
            shapely.box(0, 0, 4, 4).difference(shapely.box(1, 1, 2, 2)),
            shapely.MultiPolygon([shapely.box(5, 5, 6, 6), shapely.box(7, 7, 8, 8)]),
        ],
        dtype=object,
    )
    g, r, c = wire.rings(geoms)
    assert g.tolist() == [0, 1, 1, 3, 5]
    assert np.diff(r).tolist() == [5, 5, 5, 5, 5]
    # against taking every geometry apart, on mixed cells
    mixed = np.concatenate((geoms, compute(load(HOLED)[0]).cells, geoms[::-1]))
    parts, part_of = shapely.get_parts(mixed, return_index=True)
    ring_geoms, ring_of_part = shapely.get_rings(parts, return_index=True)
    coords, coord_ring = shapely.get_coordinates(ring_geoms, return_index=True)
    want_g = np.searchsorted(part_of[ring_of_part], np.arange(len(mixed) + 1))
    want_r = np.searchsorted(coord_ring, np.arange(len(ring_geoms) + 1))
    got_g, got_r, got_c = wire.rings(mixed)
    assert np.array_equal(got_g, want_g) and np.array_equal(got_r, want_r)
    assert np.array_equal(got_c, coords.astype(np.float32))
    header, arrays = wire.unpack(wire.pack({"op": "x"}, {"g": g, "r": r, "c": c.reshape(-1)}))
    assert header["op"] == "x"
    assert np.array_equal(arrays["g"], g) and np.array_equal(arrays["c"].reshape(-1, 2), c)
    with pytest.raises(ValueError):
        wire.unpack(b"nope")


def test_wire_rings_thinned_for_drawing_stay_within_the_tolerance():
    cells = compute(load(HOLED)[0]).cells  # filleted: arcs with many vertices
    cells = np.concatenate((cells, [shapely.box(0, 0, 0.01, 0.01), shapely.Polygon()]))
    g0, r0, c0 = wire.rings(cells)
    for tol in (0.05, 0.3, 1.0):
        g, r, c = wire.rings(cells, tol=tol)
        assert np.array_equal(g, g0) and len(r) == len(r0)  # every ring stays
        assert len(c) < len(c0) and (np.diff(r) >= 4).all()
        for j in range(len(r) - 1):
            ring, full = c[r[j] : r[j + 1]], c0[r0[j] : r0[j + 1]]
            assert (ring[0] == full[0]).all() and (ring[-1] == full[-1]).all()  # closed
            gap = shapely.hausdorff_distance(shapely.LineString(ring), shapely.LineString(full))
            assert gap <= tol * np.sqrt(2) + 1e-4, (tol, j, gap)
    assert np.array_equal(wire.rings(cells, tol=None)[2], c0)


def _thin_reference(ring: np.ndarray, tol: float) -> np.ndarray:
    """Slow Douglas-Peucker of one closed ring (wire.rings' thinning, written out plainly)."""
    n = len(ring)
    if n <= 4:
        return ring
    keep = [False] * n
    keep[0] = keep[-1] = True
    for t in range(n - 1):  # both ends of every edge longer than tol
        if float(np.hypot(*(ring[t + 1] - ring[t]))) ** 2 > tol * tol:
            keep[t] = keep[t + 1] = True
    eps2 = (tol / 2) ** 2

    def split(a, b):
        (ax, ay), (bx, by) = ring[a], ring[b]
        dx, dy = bx - ax, by - ay
        ll = dx * dx + dy * dy
        far, at = -1.0, -1
        for t in range(a + 1, b):
            px, py = ring[t][0] - ax, ring[t][1] - ay
            dot = px * dx + py * dy
            if dot <= 0:
                d2 = px * px + py * py
            elif dot >= ll:
                d2 = (px - dx) ** 2 + (py - dy) ** 2
            else:
                d2 = (px * dy - py * dx) ** 2 * (1.0 / ll)
            if d2 > far:
                far, at = d2, t
        if far > eps2:
            keep[at] = True
            split(a, at)
            split(at, b)

    anchors = [t for t in range(n) if keep[t]]
    for a, b in zip(anchors[:-1], anchors[1:], strict=True):
        split(a, b)
    out = ring[np.array(keep)]
    return ring if len(out) < 4 else out


def test_wire_rings_thin_fillets_within_half_the_tolerance_keeping_long_edges():
    """Douglas-Peucker per ring: a quarter pixel off at most, the edges a pixel shows kept."""
    cells = compute(load(HOLED)[0]).cells  # filleted: arcs of many short chords
    zigzag = shapely.Polygon([(x * 0.1, (x % 2) * 0.3) for x in range(40)] + [(3.9, 5), (0, 5)])
    cells = np.concatenate((cells, [zigzag, shapely.box(0, 0, 0.01, 0.01), shapely.Polygon()]))
    g0, r0, c0 = wire.rings(cells)
    full = shapely.get_coordinates(cells)  # float64, in the order of c0
    for tol in (0.05, 0.3, 1.0):
        g, r, c = wire.rings(cells, tol=tol)
        assert np.array_equal(g, g0) and len(r) == len(r0) and len(c) < len(c0)
        for j in range(len(r) - 1):
            ring = full[r0[j] : r0[j + 1]]
            want = _thin_reference(ring, tol).astype(np.float32)
            got = c[r[j] : r[j + 1]]
            assert np.array_equal(got, want), (tol, j)
            gap = shapely.hausdorff_distance(
                shapely.LineString(got), shapely.LineString(ring), densify=0.1
            )
            assert gap <= tol / 2 + 1e-4, (tol, j, gap)
            long = np.flatnonzero(np.hypot(*np.diff(ring, axis=0).T) > tol * (1 + 1e-6))
            ends = {tuple(p) for p in ring[np.union1d(long, long + 1)].astype(np.float32)}
            assert ends <= {tuple(p) for p in got}, (tol, j)
    # at the pages' half-pixel tolerance a fillet's arc is a few chords: far fewer vertices
    # than a half-pixel grid kept (each vertex whose grid square is not its predecessor's)
    _, r, c = wire.rings(cells[:-3], tol=0.5)  # pixels of 1 (the fillets' radius is 1.5)
    square = np.floor(full[: r0[-3]] / 0.5)  # the panel's rings (not the last two)
    grid = 1 + int(np.count_nonzero((square[1:] != square[:-1]).any(axis=1)))
    assert len(c) < 0.6 * grid, (len(c), grid)


def test_drawn_cells_travel_quantized_within_a_fraction_of_a_pixel():
    from voroforge.studio.server import geometry_message

    xy = np.random.default_rng(3).random((500, 2)) * (1000.0, 700.0) + (-20.0, 5.0)
    px = 1000.0 / 959.0
    q, codes = wire.quantize(xy, px)
    assert codes.dtype == np.uint16 and q[2] <= px / 16
    assert np.abs(wire.dequantize(q, codes) - xy).max() <= q[2] / 2 + 1e-9
    assert wire.quantize(xy, 1e-3) is None  # 10^6 steps do not fit in 16 bits
    assert wire.quantize(xy[:0], px) is None
    assert wire.quantize(xy, 5e-324) is None  # px / 16 underflows: not a division by zero
    # the page's drawing of the operated cells: the thinned rings, a fraction of a pixel off
    s = Session(HOLED)
    h, a = wire.unpack(geometry_message(s, None, seq=1, boundary=False, px=px))
    assert h["cq"] and a["cc"].dtype == np.uint16
    g, r, c = wire.rings(s.result.cells, tol=0.5 * px)
    assert np.array_equal(a["cg"], g) and np.array_equal(a["cr"], r)
    err = np.abs(wire.dequantize(h["cq"], a["cc"]) - c).max()
    assert err <= h["cq"][2] / 2 + 1e-3 * px, err
    # without the page's pixel size they travel as float32
    h, a = wire.unpack(geometry_message(s, None, seq=2, boundary=False))
    assert h["cq"] is None and a["cc"].dtype == np.float32


def test_patches_carry_the_moved_sites_and_flags_only():
    from voroforge.studio.server import geometry_message

    s = Session(MANY)
    sent: dict = {}
    h, a = wire.unpack(geometry_message(s, None, seq=1, boundary=True, sent=sent))
    assert h["full"] and len(a["sites"]) == 2 * len(s.result.sites) and len(a["mask"]) == h["n"]
    page_sites, page_mask = a["sites"].reshape(-1, 2).copy(), a["mask"].copy()
    for step, i in enumerate((5, 17, 5)):
        x, y = s.result.sites[i] + (0.5, -0.25 - 0.25 * step)
        reply = s.apply({"op": "move", "i": i, "x": float(x), "y": float(y)})
        assert reply.kind == "update" and s.provisional
        if step == 2:  # a flag the move did not touch: it travels too
            s.result.mask[40] = not s.result.mask[40]
        h, a = wire.unpack(
            geometry_message(s, reply.changed, seq=2 + step, boundary=False, sent=sent)
        )
        assert not h["full"] and "sites" not in a and "mask" not in a
        assert a["si"].tolist() == [i] and len(a["m"]) == len(a["idx"])
        assert set(reply.changed.tolist()) <= set(a["idx"].tolist())
        assert step < 2 or 40 in a["idx"]
        page_sites[a["si"]] = a["sv"].reshape(-1, 2)
        page_mask[a["idx"]] = a["m"]
        # the page, patched, holds the session's sites and flags
        assert np.array_equal(page_sites, s.result.sites)
        assert np.array_equal(page_mask, s.result.mask.astype(np.uint8))


def test_new_seeds_patch_every_cell_with_all_the_sites():
    """design.seed makes every seed new: all cells change, and the sites travel whole."""
    from voroforge.studio.server import geometry_message

    s = Session(MANY)
    sent: dict = {}
    geometry_message(s, None, seq=1, boundary=True, sent=sent)
    reply = s.apply({"op": "set", "key": "design.seed", "value": 8})
    n = len(s.result.raw)
    assert reply.kind == "update" and np.array_equal(reply.changed, np.arange(n))
    assert reply.changed.dtype == np.int32 and len(s.result.extra["redone"]) == n
    h, a = wire.unpack(geometry_message(s, reply.changed, seq=2, boundary=False, sent=sent))
    assert not h["full"] and np.array_equal(a["idx"], np.arange(n))
    assert "si" not in a and np.array_equal(a["sites"].reshape(-1, 2), s.result.sites)
    assert np.array_equal(a["m"], s.result.mask.astype(np.uint8))


def _same_step(a: Session, b: Session):
    """Two sessions hold the same design, geometry, flags and undo depth."""
    _same_result(a.result, b.result)
    assert np.array_equal(a.result.mask, b.result.mask)
    assert a.data == b.data and a.design == b.design and len(a.history) == len(b.history)
    assert a.result.extra.keys() == b.result.extra.keys()
    for k in ("raw_wkb", "open_cells"):
        assert np.array_equal(a.result.extra[k], b.result.extra[k])


def test_a_slider_step_computed_ahead_is_the_step_computed_when_asked():
    """compute_ahead: the next value, computed before it is asked for, the same bytes."""
    a, b = Session(HOLED), Session(HOLED)
    for v in (4, 5):
        assert b.compute_ahead(b.data, b.result, "design.seed", v)
        ra = a.apply({"op": "set", "key": "design.seed", "value": v})
        rb = b.apply({"op": "set", "key": "design.seed", "value": v})
        assert rb.kind == ra.kind == "update" and b.ahead_used and not a.ahead_used
        assert np.array_equal(ra.changed, rb.changed)
        _same_step(a, b)
    assert a.apply({"op": "undo"}).kind == b.apply({"op": "undo"}).kind == "update"
    _same_step(a, b)
    # a guess that misses is dropped: the step computes as it would have
    assert b.compute_ahead(b.data, b.result, "design.seed", 9)
    a.apply({"op": "set", "key": "design.seed", "value": 7})
    b.apply({"op": "set", "key": "design.seed", "value": 7})
    assert not b.ahead_used and b._ahead is None
    _same_step(a, b)
    # the same number of another type is another value (7.0 may not validate as 7 does)
    assert b.compute_ahead(b.data, b.result, "design.seed", 8)
    b.apply({"op": "set", "key": "design.seed", "value": 8.0})
    assert not b.ahead_used
    # kept for the result it was computed from only: another edit came between
    assert b.compute_ahead(b.data, b.result, "design.seed", 9)
    b.apply({"op": "set", "key": "cells.web", "value": 2.5})
    b.apply({"op": "set", "key": "design.seed", "value": 9})
    assert not b.ahead_used
    # given up when stale; nothing to compute ahead for hand-placed sites or unchanged cells
    assert not b.compute_ahead(b.data, b.result, "design.seed", 10, stale=lambda: True)
    assert not b.compute_ahead(b.data, b.result, "fabrication.min_web", 3.0)
    assert not b.compute_ahead(b.data, b.result, "seeds.count", -5)  # invalid: nothing kept
    assert b._ahead is None
    x, y = b.result.sites[1]
    assert b.apply({"op": "move", "i": 1, "x": float(x) + 0.5, "y": float(y)}).kind == "update"
    assert not b.compute_ahead(b.data, b.result, "design.seed", 11)


def test_the_server_computes_a_sliders_next_step_ahead(folder, monkeypatch):
    """After each step of a slider the next one (the same way) is computed while the page
    draws; the step that asks for it takes it (the reply says so), the same geometry."""
    import time

    from starlette.testclient import TestClient

    from voroforge.studio import server

    monkeypatch.setattr(server, "AHEAD_MS", 0.0)  # the small panel computes in milliseconds
    app = server.create_app(Session(folder / "holed.toml"))
    hub, plain = app.state.hub, Session(folder / "holed.toml")
    with TestClient(app, base_url="http://127.0.0.1:8765") as c, _ws(c) as ws:
        _greet(ws)
        before = 3
        for k, v in enumerate((4, 5, 6, 8)):  # design.seed is 3: 4 makes 5 next, ...
            ws.send_text(json.dumps({"op": "set", "key": "design.seed", "value": v, "id": k}))
            h, _ = _geom(ws)
            assert h["reply_to"] == k and h["ahead"] == (k in (1, 2)), (k, h["ahead"])
            plain.apply({"op": "set", "key": "design.seed", "value": v})
            _same_step(plain, hub.session)
            guess, before = 2 * v - before, v  # one more step the same way
            deadline = time.monotonic() + 30  # its computation has started
            while (hub.ahead or (None, None))[1] != guess and time.monotonic() < deadline:
                time.sleep(0.005)
            assert hub.ahead[:2] == ("design.seed", guess)


def test_an_input_about_to_be_used_gets_its_first_step_computed_ahead(folder, monkeypatch):
    """A page's hint (a slider pressed, a number box focused): the step up is computed."""
    import time

    from starlette.testclient import TestClient

    from voroforge.studio import server

    monkeypatch.setattr(server, "AHEAD_MS", 0.0)  # the small panel computes in milliseconds
    app = server.create_app(Session(folder / "holed.toml"))
    hub, plain = app.state.hub, Session(folder / "holed.toml")
    with TestClient(app, base_url="http://127.0.0.1:8765") as c, _ws(c) as ws:
        _greet(ws)
        for key, value in (("seeds.count", 61), ("fabrication.min_web", 3.0), ("design.seed", 4.0)):
            ws.send_text(json.dumps({"op": "ahead", "key": key, "value": value}))  # not these
        ws.send_text(json.dumps({"op": "ahead", "key": "design.seed", "value": 4}))
        deadline = time.monotonic() + 30
        while (hub.ahead is None or not hub.ahead[2].done()) and time.monotonic() < deadline:
            time.sleep(0.005)
        assert hub.ahead[:2] == ("design.seed", 4) and hub.ahead[2].result() is True
        ws.send_text(json.dumps({"op": "set", "key": "design.seed", "value": 4, "id": 9}))
        h, _ = _geom(ws)
        assert h["reply_to"] == 9 and h["ahead"]
        plain.apply({"op": "set", "key": "design.seed", "value": 4})
        _same_step(plain, hub.session)


def _page_cells(arrays, prefix):
    """Per cell of a geometry message: its flat float32 coordinates (the page's rawData)."""
    g, r, c = arrays[prefix + "g"], arrays[prefix + "r"], arrays[prefix + "c"]
    return [c[2 * r[g[k]] : 2 * r[g[k + 1]]].copy() for k in range(len(g) - 1)]


def test_a_count_slider_patches_only_the_cells_that_changed():
    from voroforge.studio.server import geometry_message

    s = Session({**HOLED, "seeds": {"method": "random", "count": 150}})
    sent: dict = {}
    h, a = wire.unpack(geometry_message(s, None, seq=1, boundary=True, sent=sent))
    raw, cells = _page_cells(a, "r"), _page_cells(a, "c")
    mask, sites = a["mask"].copy(), a["sites"].copy()
    for count in (160, 140, 141, 150):
        reply = s.apply({"op": "set", "key": "seeds.count", "value": count})
        assert reply.kind == "update" and reply.changed is not None
        h, a = wire.unpack(geometry_message(s, reply.changed, seq=2, boundary=False, sent=sent))
        assert not h["full"] and h["n"] == count and len(a["idx"]) < count
        if count == 141:  # one more seed: its cell and its neighbours
            assert 140 in a["idx"] and len(a["idx"]) <= 12
        del raw[count:], cells[count:]  # the page drops the cells past the count...
        raw += [None] * (count - len(raw))
        cells += [None] * (count - len(cells))
        for k, (rc, cc) in enumerate(zip(_page_cells(a, "r"), _page_cells(a, "c"), strict=True)):
            raw[a["idx"][k]], cells[a["idx"][k]] = rc, cc  # ...and patches the changed ones
        mask, sites = a["mask"], a["sites"]
        _, whole = wire.unpack(geometry_message(s, None, seq=3, boundary=False))
        assert all(np.array_equal(x, y) for x, y in zip(raw, _page_cells(whole, "r"), strict=True))
        assert all(
            np.array_equal(x, y) for x, y in zip(cells, _page_cells(whole, "c"), strict=True)
        )
        assert np.array_equal(mask, whole["mask"]) and np.array_equal(sites, whole["sites"])


# --- the server ----------------------------------------------------------------------------


@pytest.fixture
def client(folder):
    from starlette.testclient import TestClient

    from voroforge.studio.server import create_app

    app = create_app(Session(folder / "holed.toml"))
    with TestClient(app, base_url="http://127.0.0.1:8765") as c:
        yield c


def _ws(client, origin=None, query=""):
    headers = {"host": "127.0.0.1:8765"}
    if origin:
        headers["origin"] = origin
    return client.websocket_connect("/ws" + query, headers=headers)


def _reply(ws):
    """The next JSON reply, skipping the live check's broadcasts."""
    while True:
        msg = ws.receive_json()
        if msg["op"] != "violations":
            return msg


def _greet(ws):
    state = ws.receive_json()
    geom = ws.receive_bytes()
    return state, wire.unpack(geom)


def test_page_and_static_files_are_served(client):
    page = client.get("/")
    assert page.status_code == 200 and "studio.js" in page.text
    assert "default-src 'self'" in page.headers["content-security-policy"]
    js = client.get("/static/studio.js")
    assert js.status_code == 200 and "VoroStudio" in js.text
    assert client.get("/static/../session.py").status_code == 404
    assert client.get("/", headers={"host": "evil.example"}).status_code == 400


def test_websocket_origin_is_checked(client):
    from starlette.testclient import WebSocketDenialResponse
    from starlette.websockets import WebSocketDisconnect

    with pytest.raises((WebSocketDisconnect, WebSocketDenialResponse)):
        with _ws(client, "http://evil.example") as ws:
            ws.receive_json()
    with _ws(client, "http://127.0.0.1:8765") as ws:
        state, (header, arrays) = _greet(ws)
        assert state["op"] == "state" and header["full"] and header["n"] == len(arrays["mask"])


def test_websocket_edit_gives_a_patch(client):
    with _ws(client) as ws:
        _, (header, arrays) = _greet(ws)
        sites = arrays["sites"].reshape(-1, 2)
        ws.send_text(
            json.dumps({"op": "move", "i": 2, "x": sites[2, 0] + 1, "y": sites[2, 1], "id": 7})
        )
        msg = ws.receive()
        while "bytes" not in msg or msg["bytes"] is None:
            msg = ws.receive()
        h, a = wire.unpack(msg["bytes"])
        assert h["reply_to"] == 7 and not h["full"] and 2 in a["idx"] and len(a["idx"]) < h["n"]


def _geom(ws):
    msg = ws.receive()
    while msg.get("bytes") is None:
        msg = ws.receive()
    return wire.unpack(msg["bytes"])


def test_a_page_gets_the_violations_checked_at_start_up(client):
    """The first check runs before the server answers (not beside a page's first edits): a
    page that connects gets its violations with the drawing, for the drawing's seq."""
    import time

    hub = client.app.state.hub
    deadline = time.monotonic() + 30  # a loaded machine may take longer than the server waits
    while hub.checked is None and time.monotonic() < deadline:
        time.sleep(0.01)
    assert hub.checked is hub.session.result
    with _ws(client) as ws:
        _, (h, _) = _greet(ws)
        msg = ws.receive_json()
        assert msg["op"] == "violations" and msg["seq"] == h["seq"]
        assert msg["total"] == len(hub.session.violations)


def test_the_server_warms_the_drag_before_it_answers(folder):
    from starlette.testclient import TestClient

    from voroforge.studio.server import create_app

    session = Session(folder / "holed.toml")
    app = create_app(session)
    assert "domain_box" not in session.result.extra
    with TestClient(app, base_url="http://127.0.0.1:8765"):
        assert "domain_box" in session.result.extra  # the lifespan ran a drag step


def test_a_page_that_comes_before_the_first_check_ends_gets_its_violations(folder, monkeypatch):
    from starlette.testclient import TestClient

    from voroforge.studio import server

    monkeypatch.setattr(server, "FIRST_CHECK_WAIT", 0.0)  # a big design: answered at once
    app = server.create_app(Session(folder / "holed.toml"))
    with TestClient(app, base_url="http://127.0.0.1:8765") as c, _ws(c) as ws:
        _, (h, _) = _greet(ws)
        msg = ws.receive_json()
        assert msg["op"] == "violations" and msg["seq"] == h["seq"]
        assert app.state.hub.checked is app.state.hub.session.result


def test_subnormal_view_and_huge_coordinates_get_clear_errors(client):
    """A subnormal px had made the quantisation step 0: no reply to any later edit."""
    with _ws(client) as ws:
        _greet(ws)
        ws.send_text(json.dumps({"op": "view", "px": 5e-324, "id": 1}))
        assert "1e-300" in _reply(ws)["issues"][0]["message"]
        ws.send_text(json.dumps({"op": "move", "i": 0, "x": 1e300, "y": 0.0, "id": 2}))
        assert "at most 1e15" in _reply(ws)["issues"][0]["message"]
        ws.send_text(json.dumps({"op": "set", "key": "cells.fillet", "value": 2.0, "id": 3}))
        assert _geom(ws)[0]["reply_to"] == 3


def test_websocket_view_sets_the_drawing_resolution(client):
    with _ws(client) as ws:
        _greet(ws)
        ws.send_text(json.dumps({"op": "view", "px": 2.0}))  # coarse pixels: no reply
        ws.send_text(json.dumps({"op": "set", "key": "cells.fillet", "value": 2.5, "id": 3}))
        h, coarse = _geom(ws)
        assert h["reply_to"] == 3 and len(coarse["idx"]) == h["n"]  # every fillet changed
        session = client.app.state.hub.session
        _, _, exact = wire.rings(session.result.cells[coarse["idx"]])
        assert 0 < len(coarse["cc"]) < 0.8 * exact.size  # fewer vertices than the fillets have
        assert np.array_equal(
            coarse["rc"].reshape(-1, 2), wire.rings(session.result.raw[coarse["idx"]])[2]
        )
        ws.send_text(json.dumps({"op": "view", "px": 0.01}))  # a finer page: all again
        h, again = _geom(ws)
        assert h["full"] and len(again["cc"]) // 2 == len(wire.rings(session.result.cells)[2])
    # a page that says its canvas (/ws?w=&h=) gets its first drawing at its resolution,
    # thinned and quantized as every later one (not whole)
    from voroforge.studio.server import canvas_px

    session = client.app.state.hub.session
    x0, y0, x1, y1 = session.result.boundary.bounds
    px = canvas_px(session, "959", "699")  # the page's view(): the bounds + 4% each side
    assert px == pytest.approx(max((x1 - x0) * 1.08 / 959, (y1 - y0) * 1.08 / 699))
    assert canvas_px(session, "0", "699") is None and canvas_px(session, "a", None) is None
    with _ws(client) as ws:
        _, (whole_h, whole) = _greet(ws)
    with _ws(client, query="?w=959&h=699") as ws:
        _, (h, drawn) = _greet(ws)
        expect = wire.rings(session.result.cells, tol=0.5 * px)[2]
        ws.send_text(json.dumps({"op": "view", "px": px}))  # the page's own figure: no resend
        ws.send_text(json.dumps({"op": "set", "key": "cells.fillet", "value": 3.0, "id": 4}))
        assert _geom(ws)[0]["reply_to"] == 4
    assert whole_h["cq"] is None and h["cq"] is not None and h["cq"][2] <= px / 8
    # uint16 codes of thinned rings: fewer vertices, half the bytes each
    assert len(drawn["cc"]) < len(whole["cc"]) and drawn["cc"].nbytes < 0.5 * whole["cc"].nbytes
    got = wire.dequantize(h["cq"], drawn["cc"])
    assert got.shape == expect.shape and np.abs(got - expect).max() < px / 8


def test_edit_replies_count_the_server_threads_context_switches(client):
    """Beside its CPU time, an edit's reply says how often its thread slept or was preempted."""
    import sys

    with _ws(client) as ws:
        _greet(ws)
        ws.send_text(json.dumps({"op": "set", "key": "cells.fillet", "value": 2.0, "id": 5}))
        h, _ = _geom(ws)
    assert h["reply_to"] == 5 and h["cpu_ms"] > 0
    if sys.platform.startswith("linux"):
        assert len(h["switches"]) == 2 and all(isinstance(k, int) and k >= 0 for k in h["switches"])
    else:
        assert h["switches"] is None or len(h["switches"]) == 2


def test_integers_too_large_for_a_float_get_an_error_and_the_connection_stays(client):
    """JSON integers have no size limit: 10**400 is an error reply, not a dropped page."""
    s = client.app.state.hub.session
    for msg in (
        {"op": "set", "key": "cells.web", "value": 10**400},
        {"op": "move", "i": 0, "x": 10**400, "y": 1.0},
    ):
        assert s.apply(msg).kind == "error"
    with _ws(client) as ws:
        _greet(ws)
        ws.send_text(json.dumps({"op": "ahead", "key": "cells.web", "value": 10**400}))
        ws.send_text(json.dumps({"op": "set", "key": "cells.web", "value": 10**400, "id": 1}))
        assert _reply(ws)["op"] == "error"
        ws.send_text(json.dumps({"op": "set", "key": "cells.web", "value": 2.5, "id": 2}))
        assert _geom(ws)[0]["reply_to"] == 2


def test_the_check_waits_for_a_pause_in_the_edits_rhythm():
    """A slider's steps 0.5 s apart: the check waits twice that, not 0.35 s (between steps)."""
    from voroforge import config
    from voroforge.studio.server import RHYTHM_WINDOW, check_delay

    base = config.STUDIO_CHECK_DELAY
    assert check_delay(None) == base and check_delay(0.01) == base  # a drag's steps
    assert check_delay(0.5) == pytest.approx(1.0) and base < 1.0
    assert check_delay(RHYTHM_WINDOW + 0.1) == base  # edits that far apart: already a pause


def test_websocket_survives_malformed_messages(client):
    rng = random.Random(11)
    pieces = [
        '{"op":',
        "[]",
        "null",
        '{"op":"move","i":"a"}',
        "NaN",
        '{"op":"set","key":"x"}',
        '{"op":"add","x":Infinity,"y":0}',
        "\x00\x01",
        '{"op":"save","name":"../a.toml"}',
        '{"op":"export","format":"exe"}',
        '{"op":"view","px":-1}',
        '{"op":"view","px":"1"}',
        '{"op":"view"}',
        '{"op":"view","px":5e-324}',
        '{"op":"move","i":0,"x":1e300,"y":0}',
        "[" * 5000,
        # checker9 F5: an unhashable op (a list, an object) closed the connection silently
        '{"op":["set"],"key":"seeds.count","value":3}',
        '{"op":{"a":1}}',
        '{"op":5}',
    ]
    with _ws(client) as ws:
        _greet(ws)
        for k in range(300):
            text = rng.choice(pieces) if k % 3 else "".join(rng.choices(pieces, k=3))
            ws.send_text(text)
            reply = _reply(ws)
            assert reply["op"] in ("error", "info"), reply
        ws.send_text("x" * 70_000)
        assert "limit" in _reply(ws)["issues"][0]["message"]
        ws.send_bytes(b"\x00" * 10)
        assert _reply(ws)["op"] == "error"
        ws.send_text(json.dumps({"op": "undo", "id": 1}))
        assert _reply(ws)["op"] == "info"
    # a closed tab leaves the server working for the next one
    with _ws(client) as ws:
        state, (header, _) = _greet(ws)
        assert header["full"] and state["op"] == "state"


def test_cli_studio_help_and_port_check(capsys):
    from voroforge.cli import main

    assert main(["studio", "--help"]) == 0
    assert "--no-browser" in capsys.readouterr().out
    assert main(["studio", "--port", "70000", "--no-browser"]) == 2


def test_widget_speaks_the_page_protocol_and_exposes_the_design():
    pytest.importorskip("anywidget")
    from voroforge.studio import widget

    w = widget(HOLED)
    sent = []
    w.send = lambda content, buffers=None: sent.append((content, buffers))
    w._on_msg(w, {"text": '{"op":"hello","id":1}'}, [])
    ops = [c["op"] for c, _ in sent]
    assert ops == ["state", "geom"]
    header, arrays = wire.unpack(sent[1][1][0])
    assert header["full"] and header["n"] == len(w.result.raw) == w.cells
    x, y = w.sites[3]
    sent.clear()
    w._on_msg(w, {"text": json.dumps({"op": "move", "i": 3, "x": x + 1.0, "y": y, "id": 2})}, [])
    header, arrays = wire.unpack(sent[-1][1][0])
    assert not header["full"] and header["reply_to"] == 2 and 3 in arrays["idx"]
    assert "bg" not in arrays  # the boundary travels only when it changes
    assert w.sites[3, 0] == x + 1.0 and w.design.cells.web.value == 2.0
    sent.clear()
    w._on_msg(w, {"text": '{"op":"view","px":0.5}'}, [])
    w._on_msg(w, {"text": '{"op":"view","px":0.6}'}, [])
    assert not sent  # no reply; a finer view than before gets the whole drawing again
    w._on_msg(w, {"text": '{"op":"view","px":0.1}'}, [])
    assert wire.unpack(sent[-1][1][0])[0]["full"]
    assert w.apply({"op": "set", "key": "cells.web", "value": 3}).kind == "update"
    assert w.design.cells.web.value == 3 and "web = 3" in w.toml
    w._on_msg(w, {"text": "NaN"}, [])
    assert sent[-1][0]["op"] == "error"
    assert "VoroStudio" in w._esm and "export default" in w._esm


# --- animation -----------------------------------------------------------------------------

ANIMATED = {
    **HOLED,
    "seeds": {"method": "random", "count": 40},
    "attractors": [{"type": "point", "points": [[20, 20]], "radius": 120}],
    "cells": {"web": {"near": 1, "far": 5}},
    "fabrication": {},
    "animation": {
        "frames": 4,
        "tracks": [
            {"key": "attractors.0.points.0", "values": [[20, 20], [280, 180]]},
            {"key": "attractors.0.radius", "values": [120, 150]},
        ],
    },
}


def test_keyframes_interpolate_and_seeds_stay_coherent():
    from voroforge.studio.animation import Track, frames, value_at

    t = Track(key="a", values=[[0, 0], [10, 20], [0, 0]], times=[0, 0.25, 1])
    assert value_at(t, 0.125) == [5.0, 10.0] and value_at(t, 1) == [0, 0]
    assert value_at(Track(key="a", values=[1, 4]), 0.5) == 2  # integers stay integers
    assert value_at(Track(key="a", values=["x", "y"]), 0.9) == "x"
    results = list(frames(ANIMATED))
    assert len(results) == 4
    assert all(np.array_equal(r.sites, results[0].sites) for r in results)  # moved, not re-sampled
    webs = [shapely.area(r.cells).sum() for r in results]
    assert len(set(np.round(webs, 6))) == 4  # the pattern morphs
    relaxed = list(frames({**ANIMATED, "animation": {**ANIMATED["animation"], "relax": 2}}))
    assert len({len(r.sites) for r in relaxed}) == 1
    assert not np.array_equal(relaxed[1].sites, relaxed[0].sites)


def test_animation_errors_name_the_track():
    from voroforge.design.designfile import DesignError
    from voroforge.studio.animation import frames

    bad = {**ANIMATED, "animation": {"tracks": [{"key": "cells.web", "values": [1, -4]}]}}
    with pytest.raises(DesignError, match=r"animation\.tracks\.0"):
        list(frames(bad))
    with pytest.raises(DesignError, match="times"):
        load(
            {**ANIMATED, "animation": {"tracks": [{"key": "a", "values": [1, 2], "times": [0, 2]}]}}
        )
    with pytest.raises(DesignError, match=r"\[animation\]"):
        list(frames(HOLED))


def test_session_plays_frames_without_touching_the_design(folder):
    s = Session(ANIMATED, folder=folder)
    base = s.result.sites.copy()
    data = s.data
    for k in (1, 2, 3, 0):
        r = s.apply({"op": "frame", "k": k})
        assert r.kind == "update" and s.frame == k
        assert np.array_equal(s.result.sites, base)
    assert s.data is data and not s.history
    assert s.apply({"op": "frame", "k": 9}).kind == "error"
    assert (
        s.apply({"op": "set", "key": "cells.web", "value": 2}).kind == "update" and s.frame is None
    )


def test_cli_animate_writes_gif_and_frames(tmp_path):
    from PIL import Image

    from voroforge.cli import main

    path = tmp_path / "anim.toml"
    path.write_text(tomlfile.dumps(ANIMATED), encoding="utf-8")
    assert main(["animate", str(path), "-o", str(tmp_path / "a.gif"), "--size", "64"]) == 0
    with Image.open(tmp_path / "a.gif") as im:
        assert im.n_frames == 4
    assert (
        main(["animate", str(path), "-o", str(tmp_path / "f"), "--frames", "2", "--size", "48"])
        == 0
    )
    assert sorted(p.name for p in (tmp_path / "f").iterdir()) == [
        "frame-0001.png",
        "frame-0002.png",
    ]
    assert main(["animate", str(path), "-o", str(tmp_path / "a.avi")]) == 2


def test_cli_animate_writes_mp4(tmp_path):
    pytest.importorskip("imageio_ffmpeg", reason="MP4 needs imageio-ffmpeg (the studio extra)")
    import imageio.v2 as imageio

    from voroforge.cli import main

    path = tmp_path / "anim.toml"
    path.write_text(tomlfile.dumps(ANIMATED), encoding="utf-8")
    assert main(["animate", str(path), "-o", str(tmp_path / "a.mp4"), "--size", "64"]) == 0
    with imageio.get_reader(tmp_path / "a.mp4") as reader:
        shown = [np.asarray(f, dtype=np.int16) for f in reader]
    assert len(shown) == 4
    assert all(np.abs(a - b).mean() > 0.5 for a, b in zip(shown, shown[1:], strict=False))


def test_serve_listens_before_printing_and_warns_off_loopback(folder, monkeypatch, capsys):
    import socket as socketlib

    import uvicorn

    from voroforge.studio.server import serve

    seen = {}

    def fake_run(self, sockets=None):
        sock = sockets[0]
        seen["app"] = self.config.app
        seen["listening"] = sock.getsockopt(socketlib.SOL_SOCKET, socketlib.SO_ACCEPTCONN)
        sock.close()

    monkeypatch.setattr(uvicorn.Server, "run", fake_run)
    serve(session=Session(folder / "holed.toml"), host="0.0.0.0", port=0, open_browser=False)
    out, err = capsys.readouterr()
    assert out.startswith("voroforge studio: http://127.0.0.1:") and seen["listening"] == 1
    assert "warning: listening on 0.0.0.0" in err
    serve(session=Session(folder / "holed.toml"), port=0, open_browser=False)
    out, err = capsys.readouterr()
    assert "http://127.0.0.1:" in out and not err


def test_scrubbed_relaxed_frames_equal_the_animation_in_any_order(folder):
    # the sites of frame k are frame k-1's relaxed in frame k-1's domain (the margin moves it)
    from voroforge.studio.animation import frames

    data = {
        **ANIMATED,
        "animation": {
            "frames": 5,
            "relax": 2,
            "tracks": [
                *ANIMATED["animation"]["tracks"],
                {"key": "boundary.margin", "values": [0, 3]},
            ],
        },
    }
    still = {**data, "animation": {**data["animation"], "tracks": ANIMATED["animation"]["tracks"]}}
    for case in (data, still):
        played = [r.sites for r in frames(case, base=folder, frame=False)]
        assert not np.array_equal(played[4], played[3])
        for order in ([4, 2, 0, 4, 3], [2, 1, 4], [0, 1, 2, 3, 4]):
            s = Session(case, folder=folder)
            for k in order:
                assert s.apply({"op": "frame", "k": k}).kind == "update"
                assert np.array_equal(s.result.sites, played[k]), (order, k)


@pytest.mark.parametrize("key", ["seeds.count", "seeds", "relax.iterations", "design.seed"])
def test_animation_refuses_tracks_on_the_sites(key):
    bad = {**ANIMATED, "animation": {"tracks": [{"key": key, "values": [1, 9]}]}}
    with pytest.raises(DesignError, match=r"animation\.tracks\.0\.key.*cannot be animated"):
        load(bad)
    ok = {**ANIMATED, "animation": {"tracks": [{"key": "seeds_x", "values": [1, 9]}]}}
    assert load(ok)[0].animation.tracks[0].key == "seeds_x"  # only the keys themselves


def test_slider_ends_are_valid_values():
    # every control's slider ends load as a design (exclusive bounds, graded bounds)
    from voroforge.design.designfile import apply_overrides

    data = {
        **ANIMATED,
        "seeds": {"method": "poisson", "radius": 12.0},
        "cells": {"inset": 1.0},
        "voronoi": {"power_radius": {"near": 2, "far": 0.5}},
        "recursion": {"depth": 1, "probability": 0.5, "web": [1.0]},
        "openings": {"select": "every_kth", "k": 2},
    }
    entries = controls(load(data)[0])
    keys = {c["key"] for c in entries}
    assert {"attractors.0.radius", "attractors.0.power", "animation.fps"} <= keys
    assert {"seeds.radius", "recursion.probability", "openings.k"} <= keys
    for c in entries:
        for end in (c["min"], c["max"]):
            value = int(end) if c["kind"] == "int" else float(end)
            try:
                load(apply_overrides(data, {c["key"]: value}))
            except DesignError as exc:
                raise AssertionError(f"{c['key']} = {value}: {exc}") from None
    prob = next(c for c in entries if c["key"] == "recursion.probability")
    assert (prob["min"], prob["max"]) == (0.0, 1.0)


def test_widget_gives_the_seeds_csv_its_toml_names(tmp_path):
    pytest.importorskip("anywidget")
    from voroforge.studio import widget

    path = tmp_path / "holed.toml"
    path.write_text(tomlfile.dumps(HOLED), encoding="utf-8")
    w = widget(str(path))
    w.send = lambda content, buffers=None: None
    assert w.seeds_csv is None
    x, y = w.sites[3]
    assert w.apply({"op": "move", "i": 3, "x": x + 1.0, "y": y}).kind == "update"
    sites = w.sites
    other = tmp_path / "other"
    other.mkdir()
    (other / "mine.toml").write_text(w.toml, encoding="utf-8")
    (other / "design.seeds.csv").write_text(w.seeds_csv, encoding="utf-8")
    assert np.array_equal(Session(other / "mine.toml").result.sites, sites)
    assert w.save("kept.toml").kind == "saved"
    assert np.array_equal(Session(tmp_path / "kept.toml").result.sites, sites)
    assert (tmp_path / "kept.seeds.csv").read_text(encoding="utf-8") == w.seeds_csv
    assert w.save("kept.toml").kind == "confirm"  # nothing overwritten without asking
    for bad in ("../x.toml", "x.toml\n", "/tmp/x.toml", "x.toml\x00"):  # ($ matched before \n)
        with pytest.raises(ValueError, match="file name"):
            w.save(bad)
    assert not any(p.name.startswith("x.toml") for p in tmp_path.iterdir())
