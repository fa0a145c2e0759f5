"""Strut lattices: voroforge.solid.lattice against a manifold3d union of the same primitives.

The reference is what designers do today: every strut a cylinder, every node a sphere, all
unioned with manifold3d (``Manifold.batch_boolean``). Ours: ``solid.lattice`` on the same
cells (node hulls where the cells allow, else the implicit capsule union meshed by slabbed
marching cubes). Both outputs are checked: watertight (``is_volume``) and manifold3d status.

Run::

    python benchmarks/bench_solid.py            # 1,000 cells, ours best of 3, reference once
    python benchmarks/bench_solid.py --big      # also 10,000 cells (time and peak memory)

The machine is shared and noisy: read the ratio, not the seconds.
"""

from __future__ import annotations

import argparse
import resource
import subprocess
import sys
import time

import numpy as np

SEED = 20240611


def cells(n: int):
    import voroforge as vf

    pts = np.random.default_rng(SEED).random((n, 3)) * 100.0
    return vf.voronoi3d(pts, (0, 0, 0, 100, 100, 100))


def radius(n: int) -> float:
    return 0.06 * 100.0 / n ** (1 / 3)  # 6% of the mean cell size


def ours(c, r):
    from voroforge import solid

    return solid.lattice(c, radius=r, smoothing=0)  # default voxel: 0.5 radius


def reference(c, r, segments=8):
    import manifold3d as mf

    from voroforge.solid.graph import strut_graph

    g = strut_graph(c)
    parts = []
    for a, b in g.edges:
        p, q = g.nodes[a], g.nodes[b]
        d = q - p
        L = float(np.linalg.norm(d))
        cyl = mf.Manifold.cylinder(L, r, r, segments)
        z = d / L
        x = np.cross(z, [1.0, 0, 0] if abs(z[0]) < 0.9 else [0, 1.0, 0])
        x /= np.linalg.norm(x)
        y = np.cross(z, x)
        m = np.column_stack([x, y, z, p])
        parts.append(cyl.transform(m.tolist()))
    for p in g.nodes:
        parts.append(mf.Manifold.sphere(r, segments).translate(tuple(p)))
    return mf.Manifold.batch_boolean(parts, mf.OpType.Add)


def verdict_ours(m):
    from voroforge.solid.booleans import manifold_status

    return bool(m.is_volume), manifold_status(m)


def verdict_ref(man):
    import trimesh

    mesh = man.to_mesh()
    t = trimesh.Trimesh(np.asarray(mesh.vert_properties)[:, :3], mesh.tri_verts, process=True)
    return bool(t.is_volume), str(man.status()).split(".")[-1]


def best(fn, repeat):
    times, out = [], None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return min(times), out


def big(n: int) -> None:
    """One run in this process; prints seconds and peak RSS (for the subprocess call)."""
    c = cells(n)
    t = time.perf_counter()
    m = ours(c, radius(n))
    dt = time.perf_counter() - t
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2
    print(f"{n} {dt:.1f} {rss:.2f} {m.is_volume} {len(m.faces)}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=1000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--big", action="store_true", help="also 10,000 cells in a subprocess")
    ap.add_argument("--no-reference", action="store_true")
    ap.add_argument("--_big", type=int, help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a._big:
        big(a._big)
        return
    n, r = a.n, radius(a.n)
    c = cells(n)
    ours(cells(20), radius(20))  # compile
    t_ours, m = best(lambda: ours(c, r), a.repeat)
    ok, status = verdict_ours(m)
    print(f"{'method':<34} {'cells':>6} {'seconds':>8} {'faces':>9} {'is_volume':>9} status")
    print(
        f"{'solid.lattice (' + m.metadata['parts']['method'] + ')':<34} {n:>6} {t_ours:>8.2f} "
        f"{len(m.faces):>9} {ok!s:>9} {status}"
    )
    if not a.no_reference:
        t_ref, man = best(lambda: reference(c, r), 1)
        ok_r, status_r = verdict_ref(man)
        print(
            f"{'manifold3d union (cyl + spheres)':<34} {n:>6} {t_ref:>8.2f} "
            f"{man.num_tri():>9} {ok_r!s:>9} {status_r}"
        )
        print(f"ratio ours / manifold3d: {t_ours / t_ref:.3f}")
    if a.big:
        out = subprocess.run(
            [sys.executable, __file__, "--_big", "10000"], capture_output=True, text=True
        )
        nn, sec, gb, vol, faces = out.stdout.split()
        print(f"10,000 cells: {sec} s, peak RSS {gb} GB, is_volume {vol}, {faces} faces")


if __name__ == "__main__":
    main()
