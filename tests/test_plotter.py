"""Paths for machines (io/plotter): each segment once, merged strokes, short pen-up travel."""

import warnings

import ezdxf
import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

import voroforge as vf
from reference_plotter import nn_two_opt, segment_multiset, tour_length
from voroforge.io import plotter
from voroforge.io.dxf import write_dxf


def dxf_segments(path, layers=None):
    """Every segment of the LWPOLYLINE/LINE entities of a DXF, per layer (rounded ends)."""
    out: dict[str, list] = {}
    for e in ezdxf.readfile(path).modelspace():
        if layers is not None and e.dxf.layer not in layers:
            continue
        if e.dxftype() == "LWPOLYLINE":
            xy = np.array([p[:2] for p in e.get_points()])
            if e.closed:
                xy = np.vstack((xy, xy[:1]))
        elif e.dxftype() == "LINE":
            xy = np.array([tuple(e.dxf.start)[:2], tuple(e.dxf.end)[:2]])
        else:
            continue
        segs = out.setdefault(e.dxf.layer, [])
        for a, b in zip(np.round(xy[:-1], 6).tolist(), np.round(xy[1:], 6).tolist(), strict=True):
            if a != b:
                segs.append(tuple(sorted((tuple(a), tuple(b)))))
    return out


def duplicate_segments(path, layers=None) -> int:
    """Segments drawn more than once within a layer, plus collinear overlaps (by length)."""
    dups = 0
    for segs in dxf_segments(path, layers).values():
        dups += len(segs) - len(set(segs))
        lines = shapely.MultiLineString([list(s) for s in set(segs)])
        total = sum(np.hypot(*np.subtract(*s)) for s in set(segs))
        union = shapely.union_all(shapely.get_parts(lines)).length if segs else 0.0
        dups += int(total - union > 1e-6 * max(total, 1.0))
    return dups


# --- merging ----------------------------------------------------------------------------------


def test_merge_through_junctions_gives_the_fewest_strokes():
    t = [[[0, 0], [1, 0]], [[1, 0], [2, 0]], [[1, 0], [1, 1]]]
    assert len(plotter.merge_lines([np.array(s) for s in t])) == 2  # 2 odd ends + junction
    star = [[[0, 0], [1, 0]], [[0, 0], [-1, 0]], [[0, 0], [0, 1]], [[0, 0], [0, -1]]]
    assert len(plotter.merge_lines([np.array(s) for s in star])) == 2  # degree 4 passes
    square = [np.array([[0, 0], [1, 0]]), np.array([[1, 1], [1, 0]]), np.array([[1, 1], [0, 1]])]
    square.append(np.array([[0, 0], [0, 1]]))
    (loop,) = plotter.merge_lines(square)
    assert len(loop) == 5 and (loop[0] == loop[-1]).all()  # one closed stroke
    assert plotter.merge_lines([]) == []


def _components_min_trails(segs: list) -> int:
    pts = sorted({p for s in segs for p in s})
    index = {p: i for i, p in enumerate(pts)}
    e = np.array([[index[a], index[b]] for a, b in segs]).reshape(-1, 2)
    n = len(pts)
    g = coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(n, n))
    _, label = connected_components(g, directed=False)
    deg = np.bincount(e.reshape(-1), minlength=n)
    total = 0
    for c in np.unique(label[e[:, 0]]):
        odd = int(((deg % 2 == 1) & (label == c)).sum())
        total += max(1, odd // 2)
    return total


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 5), st.integers(0, 5), st.integers(0, 3)), max_size=40))
def test_merged_strokes_cover_each_segment_once_with_the_euler_minimum(raw):
    steps = [(1, 0), (0, 1), (1, 1), (1, -1)]
    segs = []
    for x, y, k in raw:  # segments on a small lattice: many junctions and repeats
        dx, dy = steps[k]
        segs.append(tuple(sorted(((float(x), float(y)), (float(x + dx), float(y + dy))))))
    trails = plotter.merge_lines([np.array(s) for s in segs])
    unique = sorted(set(segs))
    assert segment_multiset(trails, [False] * len(trails)) == unique
    assert len(trails) == (_components_min_trails(unique) if unique else 0)


# --- ordering ---------------------------------------------------------------------------------


def _strokes(n, seed):
    rng = np.random.default_rng(seed)
    a = rng.random((n, 2)) * 100
    return [np.array([p, p + d]) for p, d in zip(a, rng.normal(size=(n, 2)) * 4, strict=True)]


@pytest.mark.parametrize("seed", range(4))
def test_order_is_within_ten_percent_of_nearest_neighbour_plus_full_two_opt(seed):
    paths = _strokes(70, seed)
    order, flipped = plotter.order_paths(paths, start=(0, 100))
    assert sorted(order.tolist()) == list(range(70))
    ours = tour_length(paths, order.tolist(), flipped.tolist(), (0, 100))
    ref = tour_length(paths, *nn_two_opt(paths, (0, 100)), (0, 100))
    nn = tour_length(
        paths, *map(list, plotter.order_paths(paths, start=(0, 100), improve=False)), (0, 100)
    )
    file_order = tour_length(paths, list(range(70)), [False] * 70, (0, 100))
    assert ours <= 1.10 * ref and ours <= nn + 1e-9 and nn < file_order


def test_order_options_and_errors():
    paths = _strokes(30, 9)
    _, flipped = plotter.order_paths(paths, reverse=False)
    assert not flipped.any()
    closed = np.zeros(30, dtype=bool)
    closed[::3] = True
    order, flipped = plotter.order_paths(paths, closed=closed)
    assert not flipped[closed[order]].any()
    with pytest.raises(ValueError, match="at least one point"):
        plotter.order_paths([np.zeros((0, 2))])
    with pytest.raises(ValueError, match="finite"):
        plotter.order_paths([np.array([[0, np.nan], [1, 1]])])
    with pytest.raises(ValueError, match="order"):
        plotter.layer_paths([shapely.box(0, 0, 1, 1)], order="random")
    assert plotter.order_paths([])[0].size == 0


# --- each segment once ------------------------------------------------------------------------


def test_frame_and_openings_on_one_layer_cut_each_ring_once():
    holes = [shapely.box(10, 10, 20, 20), shapely.box(30, 10, 40, 20)]
    frame = shapely.box(0, 0, 50, 30).difference(shapely.union_all(holes))
    p = plotter.layer_paths([frame, *holes])
    assert len(p) == 3 and p.closed.all()
    before = [np.asarray(h.exterior.coords) for h in holes]
    assert [b.tolist() for b in before] == [np.asarray(h.exterior.coords).tolist() for h in holes]


def test_neighbouring_cells_share_each_edge_once_and_node_back(tmp_path):
    pts = np.random.default_rng(3).random((40, 2)) * 10
    d = vf.voronoi(pts, (0, 0, 10, 10))
    p = plotter.layer_paths(list(d.cells))
    segs = segment_multiset(p.paths, p.closed)
    assert len(segs) == len(set(segs))
    faces = shapely.polygonize(
        shapely.get_parts(
            shapely.node(
                shapely.MultiLineString(
                    [
                        np.vstack((x, x[:1])) if c else x
                        for x, c in zip(p.paths, p.closed, strict=True)
                    ]
                )
            )
        )
    )
    assert np.allclose(np.sort(shapely.area(shapely.get_parts(faces))), np.sort(d.areas))
    path = write_dxf(list(d.cells), tmp_path / "cells.dxf")
    assert duplicate_segments(path) == 0
    assert plotter.coincident_segments(list(d.cells), list(d.cells)) == len(set(segs))


def test_order_file_keeps_the_given_order_and_travel_shortens_it():
    cells = list(vf.voronoi(np.random.default_rng(5).random((60, 2)), (0, 0, 1, 1)).cells)
    keep = plotter.layer_paths(cells, order="file", dedupe=False, merge=False)
    assert [x.tolist() for x in keep.paths] == [
        np.asarray(shapely.orient_polygons(c).exterior.coords)[:-1].tolist() for c in cells
    ]
    short = plotter.layer_paths(cells, order="travel", dedupe=False, merge=False)
    assert short.travel()[0] < 0.5 * keep.travel()[0]
    assert short.travel()[1] == pytest.approx(keep.travel()[1])


def test_build_orders_plotter_lines_and_warns_about_coincident_layers(tmp_path):
    from voroforge.design.build import DesignWarning, build

    design = {
        "boundary": {"shape": "rectangle", "width": 100, "height": 60},
        "seeds": {"method": "random", "count": 120},
        "output": {"formats": ["svg", "dxf"], "layers": {"ENGRAVE": "edges", "CUT": "boundary"}},
    }
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        svg, dxf = build(design, tmp_path / "a")
    msgs = [str(w.message) for w in caught if issubclass(w.category, DesignWarning)]
    assert any("ENGRAVE and CUT share" in m for m in msgs)
    segs = dxf_segments(dxf)["ENGRAVE"]
    assert len(segs) == len(set(segs))
    n_travel = len(ezdxf.readfile(dxf).modelspace().query("LWPOLYLINE[layer=='ENGRAVE']"))
    design["output"]["order"] = "file"
    design["output"]["merge_lines"] = False
    design["output"]["layers"] = {"ENGRAVE": "edges"}
    _, dxf2 = build(design, tmp_path / "b")
    n_file = len(ezdxf.readfile(dxf2).modelspace().query("LWPOLYLINE[layer=='ENGRAVE']"))
    assert n_travel < n_file / 2  # merged strokes
    assert sorted(dxf_segments(dxf2)["ENGRAVE"]) == sorted(segs)  # the same lines


def test_frame_and_openings_on_cut_give_no_duplicate_segments(tmp_path):
    from voroforge.design.build import build

    design = {
        "boundary": {"shape": "rectangle", "width": 120, "height": 80},
        "seeds": {"method": "poisson", "radius": 14},
        "cells": {"web": 3, "fillet": 1},
        "output": {"formats": ["dxf", "svg"], "layers": {"CUT": ["frame", "openings"]}},
    }
    dxf, svg = build(design, tmp_path)
    assert duplicate_segments(dxf) == 0
    arcs = ezdxf.readfile(dxf).modelspace().query("LWPOLYLINE")
    assert all(e.closed for e in arcs)  # each ring once, kept whole (fillets as arcs)
    assert svg.read_text().count("<path") == len(arcs)


@pytest.mark.parametrize("offset", [0.0, 1e6, 5e8, 3e11])
def test_fillet_arcs_survive_far_from_the_origin(tmp_path, offset):
    # the merge tolerance follows the drawing's size, not its distance from the origin: a
    # rounded rectangle 46 x 26 (corner radius 3) at 5e8 had its fillet chords merged into
    # its corners (4 straight vertices, area 998 instead of 1188.27)
    part = shapely.box(offset, offset, offset + 40, offset + 20).buffer(3, quad_segs=16)
    (e,) = ezdxf.readfile(write_dxf([part], tmp_path / "p.dxf")).modelspace()
    pts = e.get_points("xyb")
    xy = np.array([(p[0] - offset, p[1] - offset) for p in pts])
    nxt = np.roll(xy, -1, axis=0)
    area = 0.5 * np.sum(xy[:, 0] * nxt[:, 1] - nxt[:, 0] * xy[:, 1])
    for (_, _, b), a, c in zip(pts, xy, nxt, strict=True):
        if b:  # the circular segment a bulge adds (its chord, its sweep 4 atan b)
            th = 4 * np.arctan(b)
            r = np.linalg.norm(c - a) / (2 * np.sin(th / 2))
            area += 0.5 * r * r * (th - np.sin(th))
    assert sum(1 for p in pts if p[2]) == 4
    true = 46 * 26 - (4 - np.pi) * 9
    assert abs(area - true) < 1e-6 * true + 64 * np.spacing(offset + 46) * 46


def test_rings_smaller_than_the_merge_tolerance_are_named_not_dropped_silently():
    big = shapely.box(0, 0, 100, 80)
    tiny = shapely.box(50, 40, 50 + 2e-8, 40 + 2e-8)  # 2e-10 of the drawing
    with pytest.warns(UserWarning, match="1 closed paths are no bigger than the vertex merge"):
        paths = plotter.layer_paths([big, tiny])
    assert len(paths.paths) == 1
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert len(plotter.layer_paths([big, tiny], tolerance=1e-12).paths) == 2


@pytest.mark.parametrize(
    "offset, step",
    [(1e14, 1.0), (1e15, 0.5), (2.0**52, 2.0)],  # 64, 4 and 2 ulps a step
)
def test_exact_lattice_cells_far_out_keep_every_edge(tmp_path, offset, step):
    # checker23 F4: the merge tolerance far out was 64 ulps of the coordinates whatever the
    # drawing, so exact cells one unit wide at 1e14 were merged to points and left out of
    # the DXF (121 of 144), at 1e15 with steps of 4 ulps all of them. It stays below a
    # quarter of the shortest drawn segment: every engine edge is drawn, no cell dropped.
    g = np.array([(i + j / 2, j) for i in range(8) for j in range(8)], float) * step + offset
    lo, hi = offset - step / 4, offset + 12 * step
    d = vf.voronoi(g, (lo, lo, hi, hi))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        p = plotter.layer_paths(list(d.cells))
    drawn = set()  # exact end points (segment_multiset's rounding moves values near 1e14)
    for q, closed in zip(p.paths, p.closed, strict=True):
        q = np.vstack((q, q[:1])) if closed else np.asarray(q)
        drawn |= {
            tuple(sorted((tuple(a), tuple(b))))
            for a, b in zip(q[:-1].tolist(), q[1:].tolist(), strict=True)
        }
    ends = np.asarray(d.edges.coords).reshape(-1, 2, 2)
    want = {tuple(sorted((tuple(a), tuple(b)))) for a, b in ends.tolist()}
    assert want <= drawn
    path = write_dxf(list(d.cells), tmp_path / "cells.dxf", dedupe=False, merge=False)
    assert len(ezdxf.readfile(path).modelspace().query("LWPOLYLINE")) == len(d)
