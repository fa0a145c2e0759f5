"""Keys a design's choices do not read are warned about, with key and line (checker16 F4).

``[boundary] shape = "rectangle"`` with ``points``, or ``[seeds] method = "random"`` with
``spacing``: the key is ignored. It is not an error (a design switched between shapes in the
studio keeps building); ``designfile.load`` warns (``UnusedKeyWarning``) and ``voroforge
build``/``check`` print it. Each warned key is checked against the geometry itself: the
design computes the same cells, bit for bit, with the key and without it (so the warning
is true), and a key its choice does read is not warned about.
"""

from __future__ import annotations

import copy
import glob
import json
import warnings
from pathlib import Path

import numpy as np
import pytest
import shapely

from voroforge.cli import main
from voroforge.design.compute import compute
from voroforge.design.designfile import UnusedKeyWarning, load, unused_keys
from voroforge.design.schema import Attractor, Boundary, Openings, Seeds

ROOT = Path(__file__).resolve().parents[1]

#: a valid value other than the default for every key of the 2D tables' USED_BY
SAMPLES = {
    "boundary": {
        "width": 50,
        "height": 40,
        "origin": [1, 2],
        "radius": 7,
        "center": [3, 3],
        "segments": 64,
        "points": [[0, 0], [10, 0], [0, 10]],
        "holes": [[[1, 1], [2, 1], [1, 2]]],
        "parts": [{"points": [[0, 0], [10, 0], [0, 10]]}],
        "file": "no-such-outline.geojson",
        "close_tolerance": 0.5,
    },
    "seeds": {
        "count": 17,
        "spacing": 13,
        "radius": 11,
        "radius_max": 30,
        "jitter": 0.3,
        "angle": 10,
        "offset": [1, 1],
        "file": "no-such-points.csv",
        "seed": 5,
        "use_field": True,
        "curves": [[[0, 0], [50, 50]]],
        "path": "M 0 0 L 50 50",
        "distance": 3,
    },
    "openings": {
        "min_area": 5,
        "max_area": 1e9,
        "probability": 0.3,
        "seed": 9,
        "k": 3,
        "start": 1,
        "count": 2,
        "threshold": 0.5,
    },
}

#: each choice's table, complete (keys it reads only)
BOUNDARIES = {
    "rectangle": {"shape": "rectangle", "width": 100, "height": 80},
    "circle": {"shape": "circle", "radius": 45, "center": [50, 40]},
    "polygon": {"shape": "polygon", "points": [[0, 0], [100, 0], [60, 80]]},
    "polygons": {
        "shape": "polygons",
        "parts": [
            {"points": [[0, 0], [40, 0], [0, 40]]},
            {"points": [[50, 50], [90, 50], [50, 90]]},
        ],
    },
    "file": {"shape": "file", "file": "outline.geojson"},
}
SEEDS = {
    "random": {"method": "random", "count": 20},
    "grid": {"method": "grid", "spacing": 20},
    "hexgrid": {"method": "hexgrid", "spacing": 20},
    "jittered": {"method": "jittered", "spacing": 20},
    "poisson": {"method": "poisson", "radius": 15},
    "file": {"method": "file", "file": "points.csv"},
    "curves": {"method": "curves", "spacing": 12, "curves": [[[5, 5], [90, 60]]]},
}
OPENINGS = {
    "all": {"select": "all"},
    "area": {"select": "area", "min_area": 200},
    "random": {"select": "random", "probability": 0.5},
    "every_kth": {"select": "every_kth", "k": 2},
    "largest": {"select": "largest", "count": 3},
}


@pytest.fixture
def folder(tmp_path):
    outline = {"type": "Polygon", "coordinates": [[[0, 0], [100, 0], [100, 80], [0, 0]]]}
    (tmp_path / "outline.geojson").write_text(json.dumps(outline))
    pts = np.random.default_rng(3).uniform([5, 5], [95, 75], size=(15, 2))
    (tmp_path / "points.csv").write_text(
        "x,y\n" + "\n".join(f"{x!r},{y!r}" for x, y in pts.tolist())
    )
    return tmp_path


def _design(section: str, table: dict) -> dict:
    d = {
        "boundary": BOUNDARIES["rectangle"],
        "seeds": SEEDS["random"],
        "cells": {"web": 2},
        "openings": {"select": "every_kth", "k": 2},
    }
    return {**copy.deepcopy(d), section: copy.deepcopy(table)}


def _geometry(data: dict, base: Path):
    r = compute(load(data)[0], base)
    cells = shapely.to_wkb(np.asarray(r.cells, dtype=object)).tolist()
    frame = None if r.frame is None else shapely.to_wkb(r.frame)
    return r.sites.tobytes(), cells, r.mask.tolist(), frame


def _cases():
    tables = {"boundary": BOUNDARIES, "seeds": SEEDS, "openings": OPENINGS}
    models = {"boundary": Boundary, "seeds": Seeds, "openings": Openings}
    for section, choices in tables.items():
        used_by = models[section].USED_BY
        for choice, table in choices.items():
            selector = next(iter(table))
            for key, (sel, readers) in used_by.items():
                assert sel == selector
                if choice not in readers and key not in table:
                    yield section, choice, key


@pytest.mark.parametrize(("section", "choice", "key"), list(_cases()))
def test_unused_key_warned_and_changes_nothing(section, choice, key, folder):
    table = {"boundary": BOUNDARIES, "seeds": SEEDS, "openings": OPENINGS}[section][choice]
    plain = _design(section, table)
    given = _design(section, {**table, key: SAMPLES[section][key]})
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        load(given)
    said = [w.message for w in caught if issubclass(w.category, UnusedKeyWarning)]
    assert [w.issue.key for w in said] == [f"{section}.{key}"]
    assert str(type(said[0])(*said[0].args)) == str(said[0])  # pytest-xdist rebuilds it so
    assert f"is not used by {next(iter(table))} = {choice!r}" in str(said[0])
    # the warning is true: the key changes nothing of the geometry
    assert _geometry(given, folder) == _geometry(plain, folder)


@pytest.mark.parametrize("section", ["boundary", "seeds", "openings"])
def test_keys_a_choice_reads_are_not_warned(section):
    models = {"boundary": Boundary, "seeds": Seeds, "openings": Openings}
    tables = {"boundary": BOUNDARIES, "seeds": SEEDS, "openings": OPENINGS}[section]
    for choice, table in tables.items():
        with warnings.catch_warnings():
            warnings.simplefilter("error", UnusedKeyWarning)
            design = load(_design(section, table))[0]
        assert unused_keys(design) == []
        # the key sets say the same: every key the complete table gives is read by its choice
        for key in table:
            if key in models[section].USED_BY:
                assert choice in models[section].USED_BY[key][1]


def test_power_is_read_by_inverse_power_only(folder):
    attractor = {"type": "point", "points": [[30, 30]], "radius": 40}
    data = _design("seeds", SEEDS["random"])
    data["cells"] = {"web": {"near": 6, "far": 1}}
    smooth = {**data, "attractors": [attractor]}
    powered = {**data, "attractors": [{**attractor, "power": 3.0}]}
    issues = unused_keys(load(powered)[0])
    assert [(i.key, i.message) for i in issues] == [
        (
            "attractors.0.power",
            "is not used by falloff = 'smoothstep'; it is used by falloff = 'inverse_power'",
        )
    ]
    assert _geometry(powered, folder) == _geometry(smooth, folder)
    inverse = {**attractor, "falloff": "inverse_power"}
    a = _geometry({**data, "attractors": [{**inverse, "power": 3.0}]}, folder)
    b = _geometry({**data, "attractors": [inverse]}, folder)
    assert a != b  # read there: power changes the cells
    assert "power" in Attractor.USED_BY


F4 = """\
[design]
name = "z"
[boundary]
shape = "rectangle"
width = 100
height = 100
points = [[0, 0], [100, 0], [50, 30]]
file = "missing.geojson"
radius = 5
[seeds]
method = "random"
count = 20
file = "nothing.csv"
spacing = 3
"""


def test_build_and_check_say_key_line_and_choice(tmp_path, capsys):
    design = tmp_path / "r.toml"
    design.write_text(F4)
    plain = tmp_path / "plain.toml"
    plain.write_text("\n".join(x for x in F4.splitlines() if x.split(" =")[0] not in _GONE))
    assert main(["build", str(design), "-o", str(tmp_path / "a")]) == 0
    err = capsys.readouterr().err
    expected = [
        ("boundary.points", 7, "shape = 'rectangle'; it is used by shape = 'polygon'"),
        ("boundary.file", 8, "shape = 'rectangle'; it is used by shape = 'file'"),
        ("boundary.radius", 9, "shape = 'rectangle'; it is used by shape = 'circle'"),
        ("seeds.file", 13, "method = 'random'; it is used by method = 'file', 'image' or 'curves'"),
        ("seeds.spacing", 14, "method = 'random'; it is used by method = 'grid', 'hexgrid', "),
    ]
    lines = [x for x in err.splitlines() if "is not used by" in x]
    assert len(lines) == len(expected)
    for line, (key, number, text) in zip(lines, expected, strict=True):
        assert line.startswith(f"voroforge: warning: {design}: {key} (line {number}) ")
        assert F4.splitlines()[number - 1].startswith(key.split(".")[1] + " =")
        assert f"is not used by {text}" in line
    # the warnings change nothing: the same files as the design without those keys
    assert main(["build", str(plain), "-o", str(tmp_path / "b")]) == 0
    for name in ("z.svg", "z.png"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()
    capsys.readouterr()
    assert main(["check", str(design), "--set", "openings.k=3"]) == 0
    err = capsys.readouterr().err
    assert f"{design}: boundary.points (line 7) is not used" in err
    assert f"{design}: openings.k (from --set) is not used by select = 'all'" in err
    assert err.count("boundary.points") == 1


_GONE = {"points", "file", "radius", "spacing"}


def test_solid_and_surface_kinds():
    foam = {
        "solid": {
            "kind": "foam",
            "container": [0, 0, 0, 10, 10, 10],
            "radius": 0.5,
            "nodes": "hull",
        }
    }
    keys = {i.key: i.message for i in unused_keys(load(foam)[0])}
    assert keys == {
        "solid.radius": "is not used by kind = 'foam'; it is used by kind = 'lattice'",
        "solid.nodes": "is not used by kind = 'foam'; it is used by kind = 'lattice'",
    }
    shell = {"solid": {"kind": "shell", "profile": [[5, 0], [6, 9]], "wall": 2.0, "cells": 50}}
    assert {i.key for i in unused_keys(load(shell)[0])} == {"solid.wall", "solid.cells"}
    plane = {"kind": "lattice", "container": [0, 0, 0, 9, 9, 9], "fields": []}
    plane["fields"] = [{"type": "plane", "radius": 3, "points": [[1, 1, 1]]}]
    assert [i.key for i in unused_keys(load({"solid": plane})[0])] == ["solid.fields.0.points"]
    surf = _design("seeds", SEEDS["random"])
    surf["surface"] = {"shape": "cylinder", "radius": 30, "height": 50, "major": 9, "count": 40}
    assert {i.key: i.message for i in unused_keys(load(surf)[0])} == {
        "surface.major": "is not used by shape = 'cylinder'; it is used by shape = 'torus'",
        "surface.count": "is not used by mode = 'morph'; it is used by mode = 'voronoi'",
    }


def test_shipped_designs_warn_about_nothing():
    files = sorted(glob.glob(str(ROOT / "examples" / "*.toml")))
    files.append(str(ROOT / "src" / "voroforge" / "design" / "data" / "starter.toml"))
    assert len(files) > 10
    for f in files:
        with warnings.catch_warnings():
            warnings.simplefilter("error", UnusedKeyWarning)
            load(f)


def test_studio_state_lists_them():
    from voroforge.studio.messages import state_message
    from voroforge.studio.session import Session

    data = _design("seeds", SEEDS["random"])
    s = Session(data)
    assert state_message(s)["warnings"] == []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnusedKeyWarning)
        reply = s.apply({"op": "set", "key": "boundary.radius", "value": 12})
    assert reply.kind == "update"  # not an error: switching shapes keeps working
    assert state_message(s)["warnings"] == [
        {
            "key": "boundary.radius",
            "message": "boundary.radius is not used by shape = 'rectangle'; it is used by "
            "shape = 'circle'",
        }
    ]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnusedKeyWarning)
        assert s.apply({"op": "set", "key": "boundary.shape", "value": "circle"}).kind == "update"
    warned = {w["key"] for w in state_message(s)["warnings"]}
    assert warned == {"boundary.width", "boundary.height"}


def test_conditional_keys(folder):
    """Keys read only under a condition: recursion at depth >= 1, a sweep's start/stop."""
    plain = {**_design("seeds", SEEDS["random"]), "cells": {}}  # recursion gives its own webs
    rec = {**plain, "recursion": {"count": 4, "web": [1.0], "probability": 0.5}}
    keys = [i.key for i in unused_keys(load(rec)[0])]
    assert keys == ["recursion.count", "recursion.probability", "recursion.web"]
    assert _geometry(rec, folder) == _geometry(plain, folder)
    deep = {**rec, "recursion": {**rec["recursion"], "depth": 1, "web": [1.0, 0.5]}}
    assert unused_keys(load(deep)[0]) == []
    assert _geometry(deep, folder) != _geometry(plain, folder)  # read there
    gif = {"key": "cells.web", "values": [1, 2, 3]}
    swept = {**plain, "output": {"formats": ["gif"], "gif": {**gif, "start": 0, "stop": 9}}}
    issues = unused_keys(load(swept)[0])
    assert [i.key for i in issues] == ["output.gif.start", "output.gif.stop"]
    assert issues[0].message == "is not used by values = [1, 2, 3]; it is used without values"
    bare = {**plain, "output": {"formats": ["gif"], "gif": gif}}
    assert load(swept)[0].output.gif.sweep() == load(bare)[0].output.gif.sweep()
    # an [output.gif] table without "gif" in formats: no sweep is made
    unswept = {**plain, "output": {"formats": ["svg"], "gif": gif}}
    issues = unused_keys(load(unswept)[0])
    assert [(i.key, i.message) for i in issues] == [
        ("output.gif", "is not used by formats = ['svg']; add 'gif' to it")
    ]


def test_power_cells_and_page(folder, tmp_path):
    """algorithm beside power_radius (power cells have one builder); page without an SVG."""
    plain = {**_design("seeds", SEEDS["random"]), "voronoi": {"power_radius": 2.0}}
    other = {**plain, "voronoi": {"power_radius": 2.0, "algorithm": "fortune"}}
    issues = unused_keys(load(other)[0])
    assert [(i.key, i.message) for i in issues] == [
        ("voronoi.algorithm", "is not used with power_radius given; it is used without it")
    ]
    assert _geometry(other, folder) == _geometry(plain, folder)
    from voroforge.design.build import build

    png = {**plain, "output": {"formats": ["png"], "png_size": 64}}
    paged = {**png, "output": {**png["output"], "page": "source"}}
    assert [i.key for i in unused_keys(load(paged)[0])] == ["output.page"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnusedKeyWarning)
        a = build(paged, tmp_path / "a")[0].read_bytes()
    assert a == build(png, tmp_path / "b")[0].read_bytes()


def test_corner_tolerance_needs_tool_radius(folder):
    from voroforge.design.build import check_design

    plain = {**_design("seeds", SEEDS["random"]), "fabrication": {"min_web": 3, "min_opening": 9}}
    tol = {**plain, "fabrication": {**plain["fabrication"], "corner_tolerance": 0.5}}
    issues = unused_keys(load(tol)[0])
    assert [(i.key, i.message) for i in issues] == [
        ("fabrication.corner_tolerance", "is not used without tool_radius; it is used with it > 0")
    ]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnusedKeyWarning)
        a = check_design(tol).table(max_rows=None)
    assert a == check_design(plain).table(max_rows=None)
    tooled = {**tol, "fabrication": {**tol["fabrication"], "tool_radius": 1.0}}
    assert unused_keys(load(tooled)[0]) == []


def test_cells_scale_is_bounded(tmp_path):
    """cells.scale past 100 is refused at its key and line (1e200 was a GEOS traceback)."""
    from voroforge.design.designfile import DesignError

    f = tmp_path / "s.toml"
    head = '[boundary]\nshape = "rectangle"\nwidth = 10\nheight = 8\n[seeds]\ncount = 5\n'
    for value in ("1e200", "{ near = 1e300, far = 1 }", "100.5"):
        f.write_text(head + f"[cells]\nscale = {value}\n")
        with pytest.raises(DesignError) as err:
            load(f)
        assert (
            str(err.value) == f"{f}:8: cells.scale: must be at most 100 (1 keeps each cell's size)"
        )
    f.write_text(head + "[cells]\nscale = 100\n")
    assert load(f)[0].cells.scale.value == 100


def test_whole_2d_tables_a_3d_product_or_surface_voronoi_does_not_read(tmp_path):
    from voroforge.surface.build import surface_panels

    # a 3D [solid] reads [design], [output] and [solid]: a 2D table given beside it is named
    foam = {"solid": {"kind": "foam", "container": [0, 0, 0, 10, 10, 10]}}
    assert unused_keys(load(foam)[0]) == []
    given = {**foam, "cells": {"web": 2}, "boundary": BOUNDARIES["rectangle"]}
    assert {i.key for i in unused_keys(load(given)[0])} == {"cells", "boundary"}
    extrude = {**_design("seeds", SEEDS["random"]), "solid": {"kind": "extrude", "thickness": 3}}
    assert unused_keys(load(extrude)[0]) == []  # extrude is the 2D design made thick
    # [surface] mode = "voronoi" makes its own cells: [cells]/[openings] change nothing
    surf = _design("seeds", SEEDS["random"])
    surf["surface"] = {"shape": "cylinder", "radius": 30, "height": 50, "mode": "voronoi"}
    surf["surface"]["count"] = 12
    issues = {i.key: i.message for i in unused_keys(load(surf)[0])}
    assert set(issues) == {"cells", "openings"}
    assert "surface.mode = 'voronoi'" in issues["cells"]
    plain = {k: v for k, v in surf.items() if k not in ("cells", "openings")}
    assert unused_keys(load(plain)[0]) == []
    a = surface_panels(load(surf)[0])[1]
    b = surface_panels(load(plain)[0])[1]
    assert np.array_equal(a.vertices, b.vertices)  # the warning is true
    morph = copy.deepcopy(surf)
    morph["surface"]["mode"] = "morph"
    assert "cells" not in {i.key for i in unused_keys(load(morph)[0])}
    # the CLI names the table with its line
    path = tmp_path / "foam.toml"
    path.write_text(
        '[solid]\nkind = "foam"\ncontainer = [0, 0, 0, 10, 10, 10]\n\n[cells]\nweb = 2\n'
    )
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", UnusedKeyWarning)
        load(path)
    said = [str(w.message) for w in caught if issubclass(w.category, UnusedKeyWarning)]
    assert said == [
        "cells (line 5) is not used by solid.kind = 'foam' (a 3D product reads [solid])"
    ]
