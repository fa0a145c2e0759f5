"""Periodic diagrams: vf.voronoi(points, box, periodic=True, wrap=...)."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import given
from hypothesis import strategies as st

import voroforge as vf
from voroforge.io import write_png, write_svg

BOX = (-1.0, 2.0, 2.0, 4.0)  # w = 3, h = 2
W, H = 3.0, 2.0


def _tiled(sites, reps):
    """Sites replicated ``(2 reps + 1)**2`` times; the middle copy first."""
    shifts = [(a, b) for a in range(-reps, reps + 1) for b in range(-reps, reps + 1)]
    shifts.remove((0, 0))
    shifts.insert(0, (0, 0))
    return np.concatenate([sites + [a * W, b * H] for a, b in shifts])


def _ring(cell):
    """Exterior vertices of a polygon, sorted (order-insensitive comparison)."""
    xy = shapely.get_coordinates(shapely.normalize(cell))[:-1]
    return xy[np.lexsort(xy.T[::-1])]


def _assert_same_cells(ours, ref, atol):
    np.testing.assert_allclose(shapely.area(ours), shapely.area(ref), rtol=1e-11, atol=atol**2)
    for a, b in zip(ours, ref, strict=True):
        if a.is_empty:
            assert b.is_empty
            continue
        ra, rb = _ring(a), _ring(b)
        assert ra.shape == rb.shape
        # each vertex has one within atol in the other ring (sorted rows can pair vertices
        # differently: a vertex whose x is an ulp off its image's sorts after it)
        gap = np.abs(ra[:, None, :] - rb[None, :, :]).max(axis=2)
        assert (gap.min(axis=1) <= atol).all() and (gap.min(axis=0) <= atol).all(), (ra, rb)


@pytest.mark.parametrize("n", [1, 2, 3, 5, 40])
def test_middle_copy_of_tiled_sites(n):
    sites = np.random.default_rng(n).random((n, 2)) * [W, H] + BOX[:2]
    d = vf.voronoi(sites, BOX, periodic=True)
    reps = 1 if n >= 40 else 3
    big = (BOX[0] - reps * W, BOX[1] - reps * H, BOX[2] + reps * W, BOX[3] + reps * H)
    ref = vf.voronoi(_tiled(sites, reps), big)
    middle = ref.cells[:n]
    # the reference's middle cells are not clipped by its box, so they are the torus cells
    assert not shapely.intersects(middle, shapely.box(*big).exterior).any()
    _assert_same_cells(d.cells, middle, 1e-12)
    assert d.periodic and not d.wrapped
    assert d.areas.sum() == pytest.approx(W * H, rel=1e-13)
    # neighbours are those of the middle copy, taken modulo the tile
    pairs = ref.edges.pairs
    mid = (pairs < n).any(axis=1)
    want = {tuple(sorted(p)) for p in (pairs[mid] % n).tolist()}
    assert {tuple(p) for p in d.edges.pairs.tolist()} == want
    indptr, nbrs = d.neighbors
    for i in range(n):
        got = set(nbrs[indptr[i] : indptr[i + 1]].tolist())
        assert got == {b if a == i else a for a, b in want if i in (a, b)}


def test_edges_counted_once_and_placed_at_lower_cell():
    n = 60
    sites = np.random.default_rng(7).random((n, 2)) * [W, H] + BOX[:2]
    d = vf.voronoi(sites, BOX, periodic=True)
    pairs = d.edges.pairs
    # trivalent torus graph: V - E + F = 0 and 2 E = 3 V give E = 3 F
    assert len(pairs) == 3 * n
    cells = d.cells
    for (i, _), seg in zip(pairs, d.edges.coords, strict=True):
        assert shapely.dwithin(cells[i].exterior, shapely.points(seg), 1e-12).all()
    # every cell's perimeter is made of its edges (each shared edge seen from both sides)
    length = np.hypot(*(d.edges.coords[:, 1] - d.edges.coords[:, 0]).T)
    per = np.bincount(pairs[:, 0], length, n) + np.bincount(pairs[:, 1], length, n)
    np.testing.assert_allclose(per, shapely.length(cells), rtol=1e-12)


def test_one_site_is_the_whole_tile_and_borders_itself():
    d = vf.voronoi([[0.5, 3.5]], BOX, periodic=True)
    cell = d.cells[0]
    assert cell.area == pytest.approx(W * H, rel=1e-14)
    np.testing.assert_allclose(cell.bounds, (0.5 - W / 2, 3.5 - H / 2, 0.5 + W / 2, 3.5 + H / 2))
    # the left/right and the top/bottom sides are one torus edge each
    assert d.edges.pairs.tolist() == [[0, 0], [0, 0]]
    assert d.neighbors[1].tolist() == [0]
    w = vf.voronoi([[0.5, 3.5]], BOX, periodic=True, wrap=True)
    assert shapely.equals(w.cells[0], shapely.box(*BOX))


@pytest.mark.parametrize("n", [1, 2, 7, 200])
def test_wrap_cells_tile_the_box(n):
    sites = np.random.default_rng(10 + n).random((n, 2)) * [W, H] + BOX[:2]
    d = vf.voronoi(sites, BOX, periodic=True)
    w = vf.voronoi(sites, BOX, periodic=True, wrap=True)
    assert w.wrapped
    box = shapely.box(*BOX)
    cells = w.cells
    assert shapely.is_valid(cells).all()
    assert shapely.covered_by(cells, box.buffer(1e-12)).all()
    assert w.areas.sum() == pytest.approx(W * H, rel=1e-13)
    assert shapely.union_all(cells).area == pytest.approx(W * H, rel=1e-13)  # no overlaps
    np.testing.assert_allclose(w.areas, d.areas, rtol=1e-11)
    # each wrapped cell is its unwrapped cell folded into the box
    for a, b in zip(d.cells, cells, strict=True):
        folded = shapely.union_all(
            [
                shapely.affinity.translate(
                    a.intersection(shapely.affinity.translate(box, i * W, j * H)), -i * W, -j * H
                )
                for i in (-1, 0, 1)
                for j in (-1, 0, 1)
            ]
        )
        assert folded.symmetric_difference(b).area < 1e-12
    # edges cut into the box: the same total length as the torus edges
    lw = np.hypot(*(w.edges.coords[:, 1] - w.edges.coords[:, 0]).T).sum()
    ld = np.hypot(*(d.edges.coords[:, 1] - d.edges.coords[:, 0]).T).sum()
    assert lw == pytest.approx(ld, rel=1e-12)
    assert (
        shapely.covered_by(shapely.points(w.edges.coords.reshape(-1, 2)), box.buffer(1e-12))
    ).all()


def _seam_cases():
    hexes = [((i + 0.5 * (j % 2)) / 4, (j + 0.5) / 4) for j in range(4) for i in range(4)]
    return {
        "centred_grid": (
            np.array([(i / 3 + 1 / 6, j / 3 + 1 / 6) for i in range(3) for j in range(3)]),
            (0, 0, 1, 1),
        ),
        "row": (np.column_stack([np.arange(7) / 7, np.full(7, 0.5)]), (0, 0, 1, 1)),
        "hex_tile": (np.array(hexes), (0, 0, 1, 1)),
        "far_grid": (
            4e6
            + 3 * np.array([(i / 4 + 0.125, j / 4 + 0.125) for i in range(4) for j in range(4)]),
            (4e6, 4e6, 4e6 + 3, 4e6 + 3),
        ),
    }


@pytest.mark.parametrize("algorithm", ["delaunay", "fortune", "halfplane"])
@pytest.mark.parametrize("case", ["centred_grid", "row", "hex_tile", "far_grid"])
def test_wrap_keeps_the_torus_edges_lying_on_the_box_sides(case, algorithm):
    # tiles whose seams are the box's sides: wrapped, the same neighbours and the same total
    # edge length as the unwrapped torus (each side edge once, not dropped on both sides)
    pts, box = _seam_cases()[case]

    def length(d):
        seg = np.asarray(d.edges.coords).reshape(-1, 2, 2)
        return np.hypot(*(seg[:, 1] - seg[:, 0]).T).sum()

    def neighbours(d):
        ip, ix = d.neighbors
        return [set(ix[ip[i] : ip[i + 1]].tolist()) for i in range(len(pts))]

    u = vf.voronoi(pts, box, periodic=True, algorithm=algorithm)
    w = vf.voronoi(pts, box, periodic=True, wrap=True, algorithm=algorithm)
    assert neighbours(w) == neighbours(u)
    assert length(w) == pytest.approx(length(u), rel=1e-12)
    if case == "centred_grid":  # every square borders four others across the torus
        assert all(len(nb) == 4 for nb in neighbours(w))
        assert length(w) == pytest.approx(6.0, rel=1e-12)


def test_crossing_cell_becomes_multipolygon():
    rng = np.random.default_rng(3)
    sites = np.concatenate(
        ([[BOX[0] + 1e-3, BOX[1] + 1e-3]], rng.random((30, 2)) * [W, H] + BOX[:2])
    )
    w = vf.voronoi(sites, BOX, periodic=True, wrap=True)
    assert w.cells[0].geom_type == "MultiPolygon"
    assert len(w.cells[0].geoms) == 4  # the corner cell is cut into four pieces


@given(st.integers(0, 2**32 - 1), st.floats(-50, 50), st.floats(-50, 50))
def test_translation_modulo_the_box(seed, tx, ty):
    n = 25
    sites = np.random.default_rng(seed).random((n, 2)) * [W, H] + BOX[:2]
    d = vf.voronoi(sites, BOX, periodic=True)
    d2 = vf.voronoi(sites + [tx, ty], BOX, periodic=True)
    # sites are taken modulo the box
    lo = np.array(BOX[:2])
    assert ((d2.sites >= lo) & (d2.sites < lo + [W, H])).all()
    shift = d2.sites - d.sites
    moved = shapely.transform(d.cells, lambda xy: xy)  # copies
    moved = np.array([shapely.affinity.translate(c, *s) for c, s in zip(moved, shift, strict=True)])
    np.testing.assert_allclose(d2.areas, d.areas, rtol=1e-9)
    assert (shapely.hausdorff_distance(moved, d2.cells) < 1e-9).all()


def test_inputs_validation_duplicates_and_wrapping():
    with pytest.raises(ValueError, match="periodic=True needs boundary"):
        vf.voronoi([[0.5, 0.5]], None, periodic=True)
    with pytest.raises(ValueError, match="periodic=True needs boundary"):
        vf.voronoi([[0.5, 0.5]], shapely.box(0, 0, 1, 1), periodic=True)
    with pytest.raises(ValueError, match="wrap=True"):
        vf.voronoi([[0.5, 0.5]], (0, 0, 1, 1), wrap=True)
    with pytest.raises(ValueError, match="xmin < xmax"):
        vf.voronoi([[0.5, 0.5]], (1, 0, 0, 1), periodic=True)
    pts = np.array([[0.25, 0.5], [1.25, 0.5], [0.75, 1.5], [-0.25, 0.5]])
    keep = pts.copy()
    d = vf.voronoi(pts, (0, 0, 1, 1), periodic=True)
    np.testing.assert_array_equal(pts, keep)
    np.testing.assert_array_equal(d.duplicate_of, [-1, 0, -1, 2])
    np.testing.assert_allclose(d.sites, [[0.25, 0.5], [0.25, 0.5], [0.75, 0.5], [0.75, 0.5]])
    assert d.cells[1].is_empty and d.cells[3].is_empty
    assert d.areas.sum() == pytest.approx(1.0, rel=1e-14)
    empty = vf.voronoi(np.zeros((0, 2)), (0, 0, 1, 1), periodic=True)
    assert len(empty) == 0 and empty.periodic


def test_locate_and_describe_on_the_torus():
    rng = np.random.default_rng(12)
    sites = rng.random((50, 2)) * [W, H] + BOX[:2]
    d = vf.voronoi(sites, BOX, periodic=True)
    q = rng.random((500, 2)) * [3 * W, 3 * H] + [BOX[0] - W, BOX[1] - H]
    diff = np.abs(q[:, None, :] - sites[None])
    diff = np.minimum(diff % [W, H], [W, H] - diff % [W, H])
    want = np.argmin((diff**2).sum(-1), axis=1)
    np.testing.assert_array_equal(d.locate(q), want)
    r = d.describe()
    assert r.euler_ok and r.euler_expected == 0 and r.convex_ok
    assert (r.vertices, r.edges, r.faces, r.voronoi_vertices) == (100, 150, 50, 100)
    r1 = vf.voronoi([[0.0, 3.0]], BOX, periodic=True).describe()
    assert (r1.vertices, r1.edges, r1.faces, r1.euler_ok) == (1, 2, 1, True)
    rw = vf.voronoi(sites, BOX, periodic=True, wrap=True).describe()
    assert rw.euler_ok and rw.euler_expected == 1 and rw.convex_ok


def test_writers_accept_periodic_cells(tmp_path):
    sites = np.random.default_rng(1).random((30, 2)) * [W, H] + BOX[:2]
    for wrap in (False, True):
        d = vf.voronoi(sites, BOX, periodic=True, wrap=wrap)
        svg = tmp_path / f"p{wrap}.svg"
        png = tmp_path / f"p{wrap}.png"
        write_svg(d.cells, svg, sites=d.sites, boundary=d.boundary)
        write_png(d.cells, png, sites=d.sites, boundary=d.boundary, size=200)
        assert svg.stat().st_size > 0 and png.stat().st_size > 0


def test_margin_grows_until_proved(monkeypatch):
    import voroforge.engine.periodic as per

    calls = []
    real = per._proved

    def counting(*args):
        ok = real(*args)
        calls.append(ok)
        return ok

    monkeypatch.setattr(per, "_proved", counting)
    # a tight cluster leaves most of the torus to a few huge cells
    rng = np.random.default_rng(5)
    sites = np.array(BOX[:2]) + [0.2, 0.3] + rng.random((60, 2)) * 0.1
    d = vf.voronoi(sites, BOX, periodic=True)
    assert calls[0] is False and calls[-1] is True
    reps = 2
    big = (BOX[0] - reps * W, BOX[1] - reps * H, BOX[2] + reps * W, BOX[3] + reps * H)
    ref = vf.voronoi(_tiled(sites, reps), big)
    assert not shapely.intersects(ref.cells[:60], shapely.box(*big).exterior).any()
    _assert_same_cells(d.cells, ref.cells[:60], 1e-11)


@pytest.mark.parametrize(
    ("w", "n", "seed"), [(50.0, 1, 29), (10.0, 2, 1), (0.1, 3, 2), (50.0, 7, 3)]
)
def test_thin_boxes_against_tiled_reference(w, n, seed):
    h = 1.0
    sites = np.random.default_rng(seed).random((n, 2)) * [w, h]
    d = vf.voronoi(sites, (0, 0, w, h), periodic=True)
    rx = int(np.ceil(3 * max(w, h) / w))
    ry = int(np.ceil(3 * max(w, h) / h))
    shifts = [(a, b) for a in range(-rx, rx + 1) for b in range(-ry, ry + 1)]
    shifts.remove((0, 0))
    shifts.insert(0, (0, 0))
    tiled = np.concatenate([sites + [a * w, b * h] for a, b in shifts])
    ref = vf.voronoi(tiled, (-rx * w, -ry * h, (rx + 1) * w, (ry + 1) * h))
    np.testing.assert_allclose(d.areas, ref.areas[:n], rtol=1e-10)
    assert (shapely.hausdorff_distance(d.cells, ref.cells[:n]) < 1e-9 * max(w, h)).all()
    wr = vf.voronoi(sites, (0, 0, w, h), periodic=True, wrap=True)
    assert shapely.is_valid(wr.cells).all()
    assert shapely.union_all(wr.cells).area == pytest.approx(w * h, rel=1e-10)
    assert wr.areas.sum() == pytest.approx(w * h, rel=1e-10)
    for r in (d.describe(), wr.describe()):
        assert r.euler_ok, str(r)


# --- regressions from the QA pass of issue 4 ------------------------------------------------


@pytest.mark.parametrize("k", [5, 10])
def test_periodic_wrap_has_no_rounding_slivers(k):
    # a grid whose cell edges fall on the box edges: 0.9 - 1 is not -0.1 in floats, so an
    # image's cell crossed the edge by 1e-17 and each wrapped cell of the last column got a
    # second, 1e-17-wide polygon part (describe(): Euler FAILED)
    h = 1.0 / k
    g = np.stack(np.meshgrid(np.arange(k) * h, np.arange(k) * h), -1).reshape(-1, 2) + h / 2
    w = vf.voronoi(g, (0, 0, 1, 1), periodic=True, wrap=True)
    assert all(len(shapely.get_parts(c)) == 1 for c in w.cells)
    assert abs(w.areas.sum() - 1.0) <= 1e-14
    assert w.describe().euler_ok
    # the seams, each once: k vertical and k horizontal lines (the box's lower sides are
    # seams of the torus too; its upper sides are the same lines)
    length = np.hypot(*(w.edges.coords[:, 1] - w.edges.coords[:, 0]).T)
    assert length.min() > 0.5 * h and abs(length.sum() - 2 * k) <= 1e-12
    # the tiled reference: each site's cell is the h x h square around it
    ref = shapely.box(*(g - h / 2).T, *(g + h / 2).T)
    assert np.allclose(w.areas, shapely.area(ref), rtol=1e-12, atol=0)


# --- regressions from the independent check of 2026-12-04 -----------------------------------


@pytest.mark.parametrize(
    ("off", "delta"), [(1e9, 0.003), (1e9, 0.0045), (1e6, 1e-5), (0.0, 1e-8), (4e12, 0.25)]
)
def test_wrap_keeps_thin_pieces_that_are_wider_than_rounding(off, delta):
    # a 2 x 2 grid shifted by delta: the last cell's corner piece is delta wide (25,000 ulps
    # at 1e9); it was dropped as a sliver because its area was compared with a length
    p = off + np.array([[0.25, 0.25], [0.75, 0.25], [0.25, 0.75], [0.75, 0.75]]) + delta
    w = vf.voronoi(p, (off, off, off + 1.0, off + 1.0), periodic=True, wrap=True)
    assert w.areas.sum() == pytest.approx(1.0, rel=1e-12)
    q = shapely.Point(off + delta / 2, off + delta / 2)
    assert [i for i in range(4) if w.cells[i].covers(q)] == [3]
    assert w.describe().euler_ok


@pytest.mark.parametrize("off", [4e12, 5e13])
def test_wrap_of_an_exact_lattice_far_out_tiles_the_box(off):
    # pieces half a cell wide are 64 ulps at 5e13: the old 64-ulp sliver rule dropped them
    x, y = np.meshgrid(np.arange(4), np.arange(4))
    p = np.column_stack((x.ravel(), y.ravel())) + off
    w = vf.voronoi(p, (off, off, off + 4.0, off + 4.0), periodic=True, wrap=True)
    assert w.areas.sum() == 16.0
    assert (w.areas == 1.0).all()


def test_periodic_flags_the_sites_its_construction_could_not_resolve():
    # sites on a 1-ulp lattice at 1e15 (still open: such vertices are not float64 numbers):
    # every site has a cell or is listed in unresolved, wrapped or not
    off = 1e15
    p = np.random.default_rng(3).random((25, 2)) * 2 + off
    for wrap in (False, True):
        d = vf.voronoi(p, (off, off, off + 2, off + 2), periodic=True, wrap=wrap)
        empty = set(np.flatnonzero(d.areas == 0).tolist())
        assert empty <= set(d.unresolved.tolist())


def test_describe_counts_a_vertex_lying_on_another_cells_side():
    # 20,000 sites in a 3 x 2 box at 4e12 (cells ~35 ulps): a Voronoi vertex rounded onto
    # the straight side of a fourth cell whose ring lacks it; describe() counted that side
    # as one edge against the two ring sides along it: Euler 1 where the torus has 0 (V and
    # E by exact offsets: a T-junction). The same on a 4 x 4 torus: the left half's sides
    # pass the corners of the two cells on its right (and, across the wrap, on its left)
    from voroforge.engine.assemble import from_shapely
    from voroforge.engine.diagram import Diagram, domain_of

    box = (0.0, 0.0, 4.0, 4.0)
    d = vf.voronoi([[1.0, 2.0], [3.0, 1.0], [3.0, 3.0]], box, periodic=True)
    halves = [shapely.box(0, 0, 2, 4), shapely.box(2, 0, 4, 2), shapely.box(2, 2, 4, 4)]
    bufs = from_shapely(np.array(halves, dtype=object))
    t = Diagram(d.sites.copy(), d.duplicate_of.copy(), domain_of(d), bufs, d.edges, "delaunay")
    t.periodic = True
    t.wrapped = False
    r = t.describe()
    # vertices (0, 0), (2, 0), (0, 2), (2, 2) modulo the box; edges: two along y = 0, one
    # along y = 2, two along x = 2 and two along x = 0
    assert (r.vertices, r.edges, r.faces, r.euler) == (4, 7, 3, 0)
    assert r.euler_ok


def _torus_nearest_exact(q, sites, box):
    """Slow reference: lowest index of the exactly nearest minimum-image site (rationals)."""
    from fractions import Fraction

    per = [Fraction(float(box[2] - box[0])), Fraction(float(box[3] - box[1]))]
    keys = []
    for i, s in enumerate(sites):
        t = Fraction(0)
        for a in range(2):
            d = (Fraction(float(q[a])) - Fraction(float(s[a]))) % per[a]
            t += min(d, per[a] - d) ** 2
        keys.append((t, i))
    return min(keys)[1]


@pytest.mark.parametrize("offset", [0.0, 1e6, 4e6, 1e12])
@pytest.mark.parametrize("size", [1.0, 3.0, 1e-3])
def test_locate_on_the_torus_settles_ties_exactly(offset, size):
    # a g x g lattice (bisectors through the queries) in a far-out box: queries at
    # midpoints between sites and their images, on sites, and outside the box; the old
    # float comparison gave another site on 27 of 6,000 such queries
    rng = np.random.default_rng(int(offset) % 97 + int(size * 10))
    for g in (3, 5, 6):
        xs = np.arange(g) * (size / g)
        sites = np.array([(x, y) for x in xs for y in xs]) + offset
        box = (offset, offset, offset + size, offset + size)
        d = vf.voronoi(sites, box, periodic=True)
        i, j = rng.integers(0, len(sites), (2, 40))
        shift = rng.integers(-1, 2, (40, 2)) * size
        q = np.vstack([(sites[i] + sites[j] + shift) / 2, sites[i] + shift])
        q = np.vstack([q, rng.uniform(offset - size, offset + 2 * size, (10, 2))])
        got = d.locate(q)
        want = [_torus_nearest_exact(p, d.sites, box) for p in q]
        # a duplicate's owner answers for it (none here: the lattice is distinct)
        assert (d.duplicate_of < 0).all()
        np.testing.assert_array_equal(got, want)
