"""Surface Voronoi and surface CVT: the speed targets of the surfaces issue, and quality.

Run from the repository root:  .venv/bin/python benchmarks/bench_surface.py [--quick]

- restricted Voronoi (areas, pieces, neighbours) of 10k sites on a 100k-triangle torus
  (target <= 2 s), beside scipy's SphericalVoronoi of 10k sites on the sphere (a reference
  for the scale of the work, not the same problem);
- 100 CVT iterations of 1,000 cells on a 20k-triangle icosphere (target <= 5 s), Lloyd and
  L-BFGS, with the hexagon share of each (and of UV-space Lloyd on a UV sphere);
- 800 cells on a torus R = 1, r = 0.4.

Best of N wall and CPU times (the CPU time is what one core spends: on a shared machine the wall
time waits for others); compare ratios, not absolute numbers. Hexagon shares per seed.
"""

from __future__ import annotations

import os
import sys
import time

import numpy as np

from voroforge import surface


def best(fn, repeat=3):
    """``(best wall seconds, best CPU seconds, result)`` over ``repeat`` runs."""
    out, walls, cpus = None, [], []
    for _ in range(repeat):
        t, c = time.perf_counter(), time.process_time()
        out = fn()
        walls.append(time.perf_counter() - t)
        cpus.append(time.process_time() - c)
    return min(walls), min(cpus), out


def main(quick: bool = False) -> None:
    rep = 1 if quick else 3
    seeds = (1,) if quick else (1, 2, 3)
    print(f"load average {os.getloadavg()[0]:.1f}; wall and CPU seconds, best of {rep}")
    T = surface.torus(1.0, 0.4, resolution=(224, 224))
    sites = T.sample(10_000, seed=1)
    surface.voronoi(surface.sphere(1, subdivisions=1), 50, relax=12)  # compile
    t_rvd, c_rvd, vd = best(lambda: surface.voronoi(T, sites), rep)
    t_nb, c_nb, _ = best(lambda: surface.voronoi(T, sites).neighbors, rep)
    from scipy.spatial import SphericalVoronoi

    P = np.random.default_rng(1).normal(size=(10_000, 3))
    P /= np.linalg.norm(P, axis=1, keepdims=True)
    t_sv, c_sv, _ = best(lambda: SphericalVoronoi(P).calculate_areas(), rep)
    print(f"{'case':58s} {'wall':>7s} {'CPU':>7s}  note")
    err = abs(vd.areas.sum() - T.area) / T.area
    print(
        f"{'RVD 10k sites, 100,352-triangle torus (areas, pieces)':58s} {t_rvd:7.3f} {c_rvd:7.3f}"
        f"  target <= 2 s; area error {err:.1e}; CPU / SphericalVoronoi {c_rvd / c_sv:.2f}"
    )
    print(f"{'  + neighbours and cell rings named':58s} {t_nb:7.3f} {c_nb:7.3f}")
    print(f"{'scipy SphericalVoronoi 10k (areas), for scale':58s} {t_sv:7.3f} {c_sv:7.3f}")
    S = surface.sphere(1.0, subdivisions=5)
    iters = 100
    for method, init in (("lloyd", "random"), ("lbfgs", "random"), ("lbfgs", "multilevel")):
        hexes, walls, cpus = [], [], []
        for seed in seeds:
            t, c, vd = best(
                lambda m=method, i=init, s=seed: surface.voronoi(
                    S, 1000, relax=iters, method=m, init=i, seed=s
                ),
                1,
            )
            hexes.append(vd.hexagon_fraction())
            walls.append(t)
            cpus.append(c)
        label = f"CVT {method} ({init}) 1,000 cells x {iters} it, 20,480-tri sphere"
        print(
            f"{label:58s} {min(walls):7.3f} {min(cpus):7.3f}  target <= 5 s; hexagons "
            + " / ".join(f"{h:.1%}" for h in hexes)
            + f" (seeds {', '.join(map(str, seeds))})"
        )
    U = surface.sphere_patch(1.0, polar=(0, np.pi), resolution=(160, 64))
    rng = np.random.default_rng(1)
    uv = rng.random((1000, 2))
    import voroforge as vf

    for _ in range(iters):  # Lloyd in UV space: the Grasshopper way (cells of the UV square)
        d = vf.voronoi(uv, (0, 0, 1, 1))
        uv = np.clip(d.centroids, 0, 1)
    uvd = surface.voronoi(U, U.evaluate(uv[:, 0], uv[:, 1]))
    print(
        f"{'UV-space Lloyd 1,000 x 100 on a UV sphere, cells on the sphere':58s} {'':15s}  "
        f"hexagons {uvd.hexagon_fraction():.1%}; "
        f"area spread {uvd.areas.std() / uvd.areas.mean():.2f}"
    )
    Tor = surface.torus(1.0, 0.4)
    for init in ("random", "multilevel"):
        hexes, walls, cpus = [], [], []
        for seed in seeds:
            t, c, vd = best(
                lambda i=init, s=seed: surface.voronoi(Tor, 800, relax=iters, init=i, seed=s), 1
            )
            hexes.append(vd.hexagon_fraction())
            walls.append(t)
            cpus.append(c)
        label = f"CVT lbfgs ({init}) 800 cells x {iters} it, torus ({len(Tor.faces)} tri)"
        print(
            f"{label:58s} {min(walls):7.3f} {min(cpus):7.3f}  hexagons "
            + " / ".join(f"{h:.1%}" for h in hexes)
        )


if __name__ == "__main__":
    main("--quick" in sys.argv)
