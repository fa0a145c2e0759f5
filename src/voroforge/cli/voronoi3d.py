"""``voroforge voronoi3d``: 3D Voronoi cells of a point file, as a table, meshes or a picture."""

from __future__ import annotations

import argparse
import importlib.util
import os
from pathlib import Path

from .progress import Stage

__all__ = ["add_parser", "run_voronoi3d"]

EPILOG = """\
examples:
  voroforge voronoi3d points.csv -o cells.csv                    volumes, centroids, neighbours
  voroforge voronoi3d points.npy -o cells.parquet --container 0,0,0,1,1,1
  voroforge voronoi3d points.csv -o cells.glb --container part.stl   cells cut by a mesh
  voroforge voronoi3d points.csv -o cells.png --periodic --container 0,0,0,1,1,1
  voroforge voronoi3d points.csv -o cells.csv --container=-1,-1,-1,1,1,1   (negative: use =)

POINTS is a .csv/.txt (three numeric columns, or columns named x, y, z in a header row) or
an .npy (n, 3) array. OUT's suffix picks the format: .csv/.parquet (one row per cell: id,
volume, centroid, neighbours; walls are -1 - w), .obj/.glb (one object per cell), .ply (all
cells in one mesh, a 'cell' id per face) or .png (a shaded picture, cells exploded slightly).
"""

MESH_SUFFIXES = (".obj", ".glb", ".ply")


def add_parser(commands, formatter_class) -> argparse.ArgumentParser:
    """Add ``voronoi3d`` to ``commands`` (see :mod:`voroforge.cli`): :func:`run_voronoi3d`."""
    p = commands.add_parser(
        "voronoi3d",
        help="3D Voronoi cells of a point file in a box, convex hull or closed mesh",
        description="3D Voronoi cells of POINTS, clipped to a box or a closed mesh.",
        epilog=EPILOG,
        formatter_class=formatter_class,
    )
    p.add_argument("points", metavar="POINTS", help="point file: .csv/.txt (x,y,z) or .npy")
    p.add_argument(
        "-o",
        "--output",
        metavar="OUT",
        action="append",
        required=True,
        help="output: .csv, .parquet, .obj, .glb, .ply or .png; repeatable",
    )
    p.add_argument(
        "--container",
        metavar="FILE|BOX",
        default=None,
        help="xmin,ymin,zmin,xmax,ymax,zmax or a closed mesh file (.stl/.obj/.ply/.off/.3mf); "
        "write --container=-1,... when the first number is negative; "
        "default: the points' bounding box padded 10%%",
    )
    p.add_argument("--periodic", action="store_true", help="the box is a 3-torus")
    p.add_argument("--size", default=None, help="PNG size WIDTHxHEIGHT (default 1000x800)")
    p.add_argument(
        "--explode", type=float, default=None, help="PNG: push cells apart (0.15; 0 to 5)"
    )
    p.set_defaults(run=run_voronoi3d)
    return p


def read_points3d(path):
    """``(n, 3)`` points from a .npy or a delimited text file (header with x, y, z optional).

    The 2D commands' readers with three coordinates: the same delimiters, comments, header
    names and errors (naming the file and line).
    """
    from ..io.readers.points import read_npy_points, read_text_point_table

    if Path(path).suffix.lower() == ".npy":
        return read_npy_points(path, dims=3)
    return read_text_point_table(path, dims=3)[0]


def _container(text):
    if text is None:
        return None
    parts = text.split(",")
    if len(parts) == 6:
        try:
            return tuple(float(v) for v in parts)
        except ValueError:
            pass
    if not os.path.exists(text):
        raise ValueError(f"--container is neither 6 numbers nor an existing mesh file: {text!r}")
    return text


def _table(d):
    import numpy as np

    # the cells of d.neighbors (faces of positive area; a torus cell's face with its own
    # image is no neighbour), then the walls it touches with positive area as -1 - w
    indptr, idx = d.neighbors
    cf, lab, area, _, _ = d.cell_face_table()
    wall = (np.asarray(lab) < 0) & np.any(np.asarray(area) != 0, axis=1)
    nbs = []
    for i in range(len(d)):
        walls = set(np.asarray(lab[cf[i] : cf[i + 1]])[wall[cf[i] : cf[i + 1]]].tolist())
        nbs.append(sorted(walls) + sorted(idx[indptr[i] : indptr[i + 1]].tolist()))
    c = np.asarray(d.centroids)
    return {
        "id": np.arange(len(d)),
        "volume": np.asarray(d.volumes),
        "cx": c[:, 0],
        "cy": c[:, 1],
        "cz": c[:, 2],
        "neighbors": nbs,
    }


def write_outputs(d, outputs, *, size=(1000, 800), explode=0.15, stage=None):
    """Write diagram ``d`` to each path of ``outputs`` by suffix; returns the paths."""
    from ..io.atomic import write_atomically

    written = []
    for out in outputs:
        path = Path(out)
        suf = path.suffix.lower()
        if not path.parent.exists():
            raise ValueError(f"output folder does not exist: {path.parent}")
        if stage:
            stage(f"writing {path.name}")
        if suf == ".csv":
            t = _table(d)

            def w(tmp, t=t):
                with open(tmp, "w") as fh:
                    fh.write("id,volume,cx,cy,cz,neighbors\n")
                    for i in range(len(t["id"])):
                        nb = " ".join(str(v) for v in t["neighbors"][i])
                        fh.write(
                            f"{i},{float(t['volume'][i])!r},{float(t['cx'][i])!r},{float(t['cy'][i])!r},"
                            f"{float(t['cz'][i])!r},{nb}\n"
                        )

            write_atomically(path, w)
        elif suf == ".parquet":
            import pyarrow as pa
            import pyarrow.parquet as pq

            t = _table(d)
            tab = pa.table(
                {
                    k: (pa.array(v, pa.list_(pa.int64())) if k == "neighbors" else pa.array(v))
                    for k, v in t.items()
                }
            )
            write_atomically(path, lambda tmp, tab=tab: pq.write_table(tab, tmp))
        elif suf in MESH_SUFFIXES:
            from ..io.mesh import glb_bytes, obj_text, ply_bytes

            if suf == ".ply":  # float64 vertices, each face's cell as a face property
                import trimesh

                verts, faces, cell = d.triangles()  # all cells at once (not mesh by mesh)
                data = ply_bytes(trimesh.Trimesh(verts, faces, process=False), cell)
            elif suf == ".glb":  # float32 by the standard: relative to a node translation
                data = glb_bytes([(f"cell_{i}", m) for i, m in _live_meshes(d)])
            else:  # .obj: text with every digit of the float64 vertices (repr)
                data = items = [(f"cell_{i}", m) for i, m in _live_meshes(d)]
                data = obj_text(items, groups=True).encode()

            def w(tmp, data=data):
                Path(tmp).write_bytes(data)

            write_atomically(path, w)
        elif suf == ".png":
            from ..io.render3d import diagram_edges, diagram_meshes, render

            meshes = diagram_meshes(d, explode=explode)
            flags = diagram_edges(d)
            write_atomically(
                path, lambda tmp, m=meshes, f=flags: render(m, tmp, size=size, edges=f)
            )
        else:
            raise ValueError(
                f"unknown output suffix {suf!r}: use .csv, .parquet, .obj, .glb, .ply or .png"
            )
        written.append(str(path))
    return written


def _live_meshes(d):
    """``(i, mesh)`` of every non-empty cell of ``d`` (``to_trimesh``), in input order."""
    return [(i, m) for i, m in enumerate(d.to_trimesh()) if len(m.faces)]


def run_voronoi3d(args, stage: Stage) -> list[str]:
    """Compute and write the cells (the ``voronoi3d`` command)."""
    from .. import voronoi3d
    from ..io.render3d import check_explode, check_render_size
    from .outputs import check_outputs, unused_option
    from .raster import parse_size

    suffixes = [Path(out).suffix.lower() for out in args.output]
    for suf in suffixes:
        if suf not in (".csv", ".parquet", ".png") + MESH_SUFFIXES:
            raise ValueError(
                f"unknown output suffix {suf!r}: use .csv, .parquet, .obj, .glb, .ply or .png"
            )
    # every output's needs checked before any is written: a failing run writes nothing
    for suf, module in ((".parquet", "pyarrow"), (".ply", "trimesh")):
        if suf in suffixes and importlib.util.find_spec(module) is None:
            raise ValueError(f"{suf} output needs {module} (pip install {module}); nothing written")
    for option, value in (("--size", args.size), ("--explode", args.explode)):
        if value is not None and ".png" not in suffixes:
            unused_option(f"{option} {value}", ".png outputs")
    h, w = parse_size(args.size if args.size is not None else "1000x800")
    explode = args.explode if args.explode is not None else 0.15
    if ".png" in suffixes:
        check_explode(explode)  # before the cells are computed
    given = [args.points] + ([args.container] if args.container else [])
    check_outputs(args.output, png=lambda: check_render_size((w, h)), inputs=given)
    stage("reading points")
    pts = read_points3d(args.points)
    stage(f"computing {len(pts)} cells")
    d = voronoi3d(
        pts,
        _container(args.container),
        periodic=args.periodic,
        progress=lambda done, total: stage(f"cells {done}/{total}"),
    )
    return write_outputs(d, args.output, size=(w, h), explode=explode, stage=stage)
