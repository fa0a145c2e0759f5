"""Strut lattices: voroforge.solid.lattice against a manifold3d union of the same primitives.

The reference is what designers do today: every strut a cylinder, every node a sphere, all
unioned with manifold3d (``Manifold.batch_boolean``). Ours: ``solid.lattice`` on the same
cells (node hulls, joints of several nodes where struts are too short for rings), and with
``--implicit`` also the implicit route (the plain union of round struts and spherical nodes
on a voxel grid, meshed by slabbed marching cubes). Every output is checked: watertight
(``is_volume``) and manifold3d status.

Run::

    python benchmarks/bench_solid.py            # 1,000 cells, ours best of 3, reference once
    python benchmarks/bench_solid.py --implicit # also the implicit route, once
    python benchmarks/bench_solid.py --big      # also 10,000 cells (time and peak memory)

The machine is shared and noisy: read the ratio, not the seconds.
"""

from __future__ import annotations

import argparse
import os
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

    return solid.lattice(c, radius=r)


def implicit(m):
    from voroforge.solid.implicit import capsules_mesh

    # the same struts, round, spherical nodes (a plain union); default voxel: 0.5 radius
    return capsules_mesh(m.metadata["struts"], smoothing=0, smooth=0.0)


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
    out = mf.Manifold.batch_boolean(parts, mf.OpType.Add)
    out.num_tri()  # manifold3d is lazy: the union runs here, inside the timing
    return out


def verdict_ours(m):
    from voroforge.solid.booleans import manifold_status

    return bool(m.is_volume), manifold_status(m)


def verdict_ref(man):
    import trimesh

    mesh = man.to_mesh()
    t = trimesh.Trimesh(np.asarray(mesh.vert_properties)[:, :3], mesh.tri_verts, process=True)
    return bool(t.is_volume), str(man.status()).split(".")[-1]


def best(fn, repeat):
    """Best wall seconds of ``repeat`` runs, the CPU seconds of that run, and its result."""
    times, out = [], None
    for _ in range(repeat):
        t, cpu = time.perf_counter(), time.process_time()
        out = fn()
        times.append((time.perf_counter() - t, time.process_time() - cpu))
    wall, cpu = min(times)
    return wall, cpu, out


def big(n: int) -> None:
    """One run in this process; prints seconds and peak RSS (for the subprocess call)."""
    c = cells(n)
    t, cpu = time.perf_counter(), time.process_time()
    m = ours(c, radius(n))
    dt, dcpu = time.perf_counter() - t, time.process_time() - cpu
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2
    p = m.metadata["parts"]
    load = os.getloadavg()[0]
    joints = f"{p['method']}:{p.get('joints', '-')}"  # the route that ran (hull: its joints)
    print(f"{n} {dt:.1f} {dcpu:.1f} {rss:.2f} {m.is_volume} {len(m.faces)} {joints} {load:.1f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=1000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--big", action="store_true", help="also 10,000 cells in a subprocess")
    ap.add_argument("--no-reference", action="store_true")
    ap.add_argument("--implicit", action="store_true", help="also the implicit route, once")
    ap.add_argument("--_big", type=int, help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a._big:
        big(a._big)
        return
    n, r = a.n, radius(a.n)
    c = cells(n)
    ours(cells(20), radius(20))  # compile
    head = f"{'method':<36} {'cells':>6} {'wall s':>8} {'CPU s':>8} {'faces':>9} {'is_volume':>9}"
    print(head + " status")

    def row(name, wall, cpu, faces, ok, status):
        print(f"{name:<36} {n:>6} {wall:>8.2f} {cpu:>8.2f} {faces:>9} {ok!s:>9} {status}")

    t_ours, c_ours, m = best(lambda: ours(c, r), a.repeat)
    row(f"solid.lattice ({m.metadata['parts']['method']})", t_ours, c_ours, len(m.faces),
        *verdict_ours(m))  # fmt: skip
    p = m.metadata["parts"]
    print(f"  {p['merged']} nodes merged into {p['joints']} joints, {p['rounds']} rounds")
    if a.implicit:
        t_imp, c_imp, mi = best(lambda: implicit(m), 1)
        row("implicit route (plain union)", t_imp, c_imp, len(mi.faces), *verdict_ours(mi))
    if not a.no_reference:
        t_ref, c_ref, man = best(lambda: reference(c, r), 1)
        row("manifold3d union (cyl + spheres)", t_ref, c_ref, man.num_tri(), *verdict_ref(man))
        print(f"ratio ours / manifold3d: wall {t_ours / t_ref:.3f}, CPU {c_ours / c_ref:.3f}")
    print(f"load average: {os.getloadavg()[0]:.1f}")
    if a.big:
        out = subprocess.run(
            [sys.executable, __file__, "--_big", "10000"], capture_output=True, text=True
        )
        nn, sec, cpu, gb, vol, faces, joints, load = out.stdout.split()
        print(
            f"10,000 cells: {sec} s ({cpu} s CPU), peak RSS {gb} GB, is_volume {vol}, "
            f"{faces} faces, route:joints {joints} (load {load})"
        )


if __name__ == "__main__":
    main()
