"""Surface Voronoi and surface CVT: the speed targets of the surfaces issue, and quality.

Run from the repository root:  .venv/bin/python benchmarks/bench_surface.py [--quick]

- restricted Voronoi (areas, pieces, neighbours) of 10k sites on a 100k-triangle torus
  (target <= 2 s), beside scipy's SphericalVoronoi of 10k sites on the sphere (a reference
  for the scale of the work, not the same problem);
- 100 CVT iterations of 1,000 cells on a 20k-triangle icosphere (target <= 5 s), Lloyd and
  L-BFGS, with the hexagon share of each (and of UV-space Lloyd on a UV sphere);
- 800 cells on a torus R = 1, r = 0.4.

Best of N wall times on a shared machine: compare ratios, not absolute numbers.
"""

from __future__ import annotations

import sys
import time

import numpy as np

from voroforge import surface


def best(fn, repeat=3):
    out, times = None, []
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return min(times), out


def main(quick: bool = False) -> None:
    rep = 1 if quick else 3
    T = surface.torus(1.0, 0.4, resolution=(224, 224))
    sites = T.sample(10_000, seed=1)
    surface.voronoi(surface.sphere(1, subdivisions=1), 20)  # compile
    t_rvd, vd = best(lambda: surface.voronoi(T, sites), rep)
    t_nb, _ = best(lambda: surface.voronoi(T, sites).neighbors, rep)
    from scipy.spatial import SphericalVoronoi

    P = np.random.default_rng(1).normal(size=(10_000, 3))
    P /= np.linalg.norm(P, axis=1, keepdims=True)
    t_sv, _ = best(lambda: SphericalVoronoi(P).calculate_areas(), rep)
    print(f"{'case':58s} {'seconds':>8s}  note")
    print(
        f"{'RVD 10k sites, 100,352-triangle torus (areas, pieces)':58s} {t_rvd:8.3f}  "
        f"target <= 2 s; area error {abs(vd.areas.sum() - T.area) / T.area:.1e}"
    )
    print(f"{'  + neighbours and cell rings named':58s} {t_nb:8.3f}")
    print(f"{'scipy SphericalVoronoi 10k (areas), for scale':58s} {t_sv:8.3f}")
    S = surface.sphere(1.0, subdivisions=5)
    iters = 100
    for method, init in (("lloyd", "random"), ("lbfgs", "random"), ("lbfgs", "multilevel")):
        t, vd = best(
            lambda m=method, i=init: surface.voronoi(
                S, 1000, relax=iters, method=m, init=i, seed=1
            ),
            1,
        )
        label = f"CVT {method} ({init}) 1,000 cells x {iters} it, 20,480-tri sphere"
        print(f"{label:58s} {t:8.3f}  target <= 5 s; hexagons {vd.hexagon_fraction():.1%}")
    U = surface.sphere_patch(1.0, polar=(0, np.pi), resolution=(160, 64))
    rng = np.random.default_rng(1)
    uv = rng.random((1000, 2))
    import voroforge as vf

    for _ in range(iters):  # Lloyd in UV space: the Grasshopper way (cells of the UV square)
        d = vf.voronoi(uv, (0, 0, 1, 1))
        uv = np.clip(d.centroids, 0, 1)
    uvd = surface.voronoi(U, U.evaluate(uv[:, 0], uv[:, 1]))
    print(
        f"{'UV-space Lloyd 1,000 x 100 on a UV sphere, cells on the sphere':58s} {'':8s}  "
        f"hexagons {uvd.hexagon_fraction():.1%}; "
        f"area spread {uvd.areas.std() / uvd.areas.mean():.2f}"
    )
    Tor = surface.torus(1.0, 0.4)
    for init in ("random", "multilevel"):
        t, vd = best(lambda i=init: surface.voronoi(Tor, 800, relax=iters, init=i, seed=1), 1)
        label = f"CVT lbfgs ({init}) 800 cells x {iters} it, torus ({len(Tor.faces)} tri)"
        print(f"{label:58s} {t:8.3f}  hexagons {vd.hexagon_fraction():.1%}")


if __name__ == "__main__":
    main("--quick" in sys.argv)
