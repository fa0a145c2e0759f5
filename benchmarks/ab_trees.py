"""A/B timings of this tree against another checkout of voroforge (by default 00169d7).

Two modes, both alternating the trees so that load changes hit them alike:

``kernel``
    One process imports both trees (the other one under the alias ``vfbase``, through a
    symbolic link in a temporary folder; the package's imports are relative) and times,
    on fixed-seed inputs, the Delaunay-dual cells kernel alone
    (``kernels.cells.cells_from_triangulation`` on each tree's own triangulation) and
    ``vf.voronoi(p, (0, 0, 1, 1))``. Each round times A then B, or B then A (alternately);
    the figure is the best over ``--repeat`` rounds, as CPU time of the process (use
    ``NUMBA_NUM_THREADS=1`` for a single-thread figure) and as wall time.

``calls``
    One process, both trees, like ``kernel``: the calls the benchmark scripts time
    (``bench_2d``: ``vf.voronoi`` and ``.cells`` on uniform/clustered/grid, the polygon with
    holes, ``vf.delaunay``; ``bench_algorithms``: the three algorithms; ``bench_design_build``:
    the 2000-cell DXF panel; ``bench_lloyd``: 200 Lloyd steps, L-BFGS, one step at 1e5,
    ``power_fit``), each on the same fixed-seed input in both trees, A and B alternated,
    best of ``--repeat``, CPU and wall. While A runs, ``sys.modules["voroforge"]`` is A's
    package, so A's own ``import voroforge`` inside functions (its design pipeline) reaches
    A's engine, not B's. Ends with a Markdown table and the ratios past ``--flag``.

``scripts``
    Runs benchmark scripts of both trees in fresh subprocesses, each tree its own copy of the
    script with ``PYTHONPATH=<tree>/src`` and its own ``NUMBA_CACHE_DIR``, alternating
    A B B A ... for ``--rounds``. Saves every output under ``--out`` and prints, for each
    output line whose text apart from the numbers is the same in both trees, the numbers of
    A and of B side by side (each round's).

Run from the repository root::

    git worktree add /tmp/base 00169d7
    NUMBA_NUM_THREADS=1 .venv/bin/python benchmarks/ab_trees.py kernel --base /tmp/base
    NUMBA_NUM_THREADS=1 .venv/bin/python benchmarks/ab_trees.py calls --base /tmp/base --repeat 5
    .venv/bin/python benchmarks/ab_trees.py scripts --base /tmp/base --rounds 2 \\
        --script "bench_algorithms.py --sizes 1e5 --repeat 5"
"""

from __future__ import annotations

import argparse
import contextlib
import gc
import hashlib
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(ROOT / "src"))

from common import (  # noqa: E402
    DISTRIBUTIONS,
    command_line,
    machine_info,
    polygon_with_holes,
    uniform,
)

BOX = (0.0, 0.0, 1.0, 1.0)
NUMBER = re.compile(r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?")


def _import_base(tree: Path):
    """The package of ``tree`` imported as ``vfbase`` (a link to ``tree/src/voroforge``)."""
    target = (tree / "src" / "voroforge").resolve()
    # one folder per tree, kept: numba's cache is keyed by the source path
    tag = hashlib.sha1(str(target).encode()).hexdigest()[:12]
    link_dir = Path(tempfile.gettempdir()) / f"vf-ab-{tag}"
    link_dir.mkdir(exist_ok=True)
    if not (link_dir / "vfbase").exists():
        (link_dir / "vfbase").symlink_to(target)
    sys.path.insert(0, str(link_dir))
    import vfbase

    return vfbase


def _kernel_call(pkg, p):
    """A function running ``pkg``'s cells kernel on ``p`` (triangulated once, outside)."""
    from importlib import import_module

    tri_mod = import_module(pkg.__name__ + ".kernels.delaunay")
    cells_mod = import_module(pkg.__name__ + ".kernels.cells")
    xs = np.ascontiguousarray(p[:, 0])
    ys = np.ascontiguousarray(p[:, 1])
    order, sx, sy, tri, he, _, ok = tri_mod.triangulate_sorted(xs, ys)
    if not ok:
        raise ValueError("the input has no triangulation")
    box = np.array(BOX)
    kmap = np.arange(len(xs), dtype=np.int64)[order]
    return lambda: cells_mod.cells_from_triangulation(sx, sy, tri, he, box, order, kmap)


def _timed(fn):
    gc.collect()
    w = time.perf_counter()
    c = time.process_time()
    fn()
    return time.process_time() - c, time.perf_counter() - w


def kernel(args) -> None:
    import voroforge as vf

    base = _import_base(args.base)
    print(f"A = {args.base} ({base.__file__}), B = {ROOT} ({vf.__file__})")
    rows = []
    for dist in args.dists.split(","):
        p = DISTRIBUTIONS[dist](args.n)
        cases = {
            "cells kernel": (_kernel_call(base, p), _kernel_call(vf, p)),
            "vf.voronoi": (
                lambda p=p: base.voronoi(p, BOX),
                lambda p=p: vf.voronoi(p, BOX),
            ),
        }
        for what, (fa, fb) in cases.items():
            fa()
            fb()  # warm: compiled or loaded from the cache
            best = {"A": [np.inf, np.inf], "B": [np.inf, np.inf]}
            for r in range(args.repeat):
                pair = (("A", fa), ("B", fb)) if r % 2 == 0 else (("B", fb), ("A", fa))
                for name, fn in pair:
                    cpu, wall = _timed(fn)
                    best[name][0] = min(best[name][0], cpu)
                    best[name][1] = min(best[name][1], wall)
            (ca, wa), (cb, wb) = best["A"], best["B"]
            rows.append((f"{what}, {dist} {args.n:g}", ca, cb, wa, wb))
            print(
                f"{what:>12}, {dist:>9}: CPU A {ca * 1e3:7.1f} ms  B {cb * 1e3:7.1f} ms  "
                f"B/A {cb / ca:5.2f} | wall A {wa * 1e3:7.1f} ms  B {wb * 1e3:7.1f} ms  "
                f"B/A {wb / wa:5.2f}",
                flush=True,
            )
    print(f"load average after: {os.getloadavg()[0]:.2f}")


@contextlib.contextmanager
def _as_voroforge(pkg):
    """``import voroforge`` gives ``pkg`` inside the block (A's function-level imports)."""
    saved = sys.modules.get("voroforge")
    sys.modules["voroforge"] = pkg
    try:
        yield
    finally:
        if saved is not None:
            sys.modules["voroforge"] = saved


def _design_build(pkg, out: Path):
    """``build`` of the 2000-cell panel of ``bench_design_build`` with ``pkg``'s design layer."""
    from importlib import import_module

    try:
        build = import_module(pkg.__name__ + ".design.build").build
    except ImportError:  # before the architecture step
        build = import_module(pkg.__name__ + ".design.pipeline").build
    spec = {
        "design": {"name": "bench", "seed": 1},
        "boundary": {"shape": "rectangle", "width": 1000, "height": 700},
        "seeds": {"method": "random", "count": 2000},
        "cells": {"web": 2, "fillet": 1},
        "output": {"formats": ["dxf"]},
    }
    return lambda: build(spec, out)


def _call_cases(vf, n: int, big: bool):
    """(benchmark, line, function of the package) for every timed call."""
    p = {d: DISTRIBUTIONS[d](n) for d in ("uniform", "clustered", "grid")}
    holes = polygon_with_holes()
    lloyd_pts = np.random.default_rng(0).random((1000, 2))
    step_pts = np.random.default_rng(1).random((n, 2))
    fit_pts = np.random.default_rng(2).random((10_000, 2))
    equal = np.full(len(fit_pts), 1.0 / len(fit_pts))
    by_x = 1.0 + 3.0 * (fit_pts[:, 0] > 0.5)
    by_x /= by_x.sum()
    tag = f"{n:g}"
    cases = []
    for d, q in p.items():
        cases.append(("bench_2d", f"vf.voronoi {d} {tag}", lambda m, q=q: m.voronoi(q, BOX)))
        cases.append(
            ("bench_2d", f"vf.voronoi +cells {d} {tag}", lambda m, q=q: m.voronoi(q, BOX).cells)
        )
    for d in ("uniform", "grid"):
        cases.append(("bench_2d", f"vf.delaunay {d} {tag}", lambda m, q=p[d]: m.delaunay(q)))
    cases.append(
        (
            "bench_2d",
            f"vf.voronoi holes +cells uniform {tag}",
            lambda m: m.voronoi(p["uniform"], holes).cells,
        )
    )
    if big:
        u6 = uniform(1_000_000)
        cases.append(("bench_2d", "vf.voronoi uniform 1e6", lambda m: m.voronoi(u6, BOX)))
    for alg, d in (("fortune", "uniform"), ("halfplane", "uniform"), ("halfplane", "grid")):
        cases.append(
            (
                "bench_algorithms",
                f"vf.voronoi {alg} {d} {tag}",
                lambda m, a=alg, q=p[d]: m.voronoi(q, BOX, algorithm=a),
            )
        )
    cases.append(("bench_design_build", "build, 2000 cells, DXF", None))
    cases += [
        (
            "bench_lloyd",
            "vf.lloyd 1000 sites, 200 steps",
            lambda m: m.lloyd(lloyd_pts, BOX, iterations=200),
        ),
        (
            "bench_lloyd",
            "vf.lloyd lbfgs 1000 sites, 33 steps",
            lambda m: m.lloyd(lloyd_pts, BOX, iterations=33, method="lbfgs"),
        ),
        (
            "bench_lloyd",
            f"vf.lloyd 1 step, {tag} sites",
            lambda m: m.lloyd(step_pts, BOX, iterations=1),
        ),
        ("bench_lloyd", "vf.power_fit 10k equal", lambda m: m.power_fit(fit_pts, equal, BOX)),
        ("bench_lloyd", "vf.power_fit 10k 1:4 by x", lambda m: m.power_fit(fit_pts, by_x, BOX)),
    ]
    return cases


def _profile(line: str, fa, fb, top: int) -> None:
    """cProfile of three calls of each tree: the ``top`` functions by own time."""
    import cProfile
    import io
    import pstats

    for name, f in (("A", fa), ("B", fb)):
        prof = cProfile.Profile()
        prof.enable()
        for _ in range(3):
            f()
        prof.disable()
        text = io.StringIO()
        pstats.Stats(prof, stream=text).sort_stats("tottime").print_stats(top)
        body = text.getvalue().split("ncalls", 1)[-1]
        print(f"--- profile {name}, {line} (3 calls, by own time)\n   ncalls{body}", flush=True)


def calls(args) -> None:
    import voroforge as vf

    base = _import_base(args.base)
    print(f"A = {args.base} ({base.__file__}), B = {ROOT} ({vf.__file__})")
    only = args.only.split(",") if args.only else None
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for bench, line, fn in _call_cases(vf, args.n, args.big):
            if only and not any(o in bench or o in line for o in only):
                continue
            if fn is None:  # the design build: each tree its own function and folder
                (Path(tmp) / "A").mkdir(exist_ok=True)
                (Path(tmp) / "B").mkdir(exist_ok=True)
                ba, bb = _design_build(base, Path(tmp) / "A"), _design_build(vf, Path(tmp) / "B")

                def fa(ba=ba):
                    with _as_voroforge(base):
                        ba()

                fb = bb
            else:

                def fa(fn=fn):
                    with _as_voroforge(base):
                        fn(base)

                def fb(fn=fn):
                    fn(vf)

            fa()
            fb()  # warm: compiled or loaded from the cache
            best = {"A": [np.inf, np.inf], "B": [np.inf, np.inf]}
            for r in range(args.repeat):
                pair = (("A", fa), ("B", fb)) if r % 2 == 0 else (("B", fb), ("A", fa))
                for name, f in pair:
                    cpu, wall = _timed(f)
                    best[name][0] = min(best[name][0], cpu)
                    best[name][1] = min(best[name][1], wall)
            (ca, wa), (cb, wb) = best["A"], best["B"]
            rows.append((bench, line, ca, cb, wa, wb))
            if args.profile and cb / ca > args.flag:
                _profile(line, fa, fb, args.profile)
            print(
                f"{bench:>18} | {line:<38}: CPU A {ca * 1e3:8.1f} ms  B {cb * 1e3:8.1f} ms  "
                f"B/A {cb / ca:5.2f} | wall B/A {wb / wa:5.2f}  (load {os.getloadavg()[0]:.2f})",
                flush=True,
            )
    print(
        f"\nbest of {args.repeat}, A and B alternated; load average after: "
        f"{os.getloadavg()[0]:.2f}\n"
    )
    print("| benchmark | line | A CPU ms | B CPU ms | B/A CPU | B/A wall |")
    print("|---|---|---|---|---|---|")
    for bench, line, ca, cb, wa, wb in rows:
        mark = " **" if cb / ca > args.flag else ""
        print(
            f"| {bench} | {line} | {ca * 1e3:.1f} | {cb * 1e3:.1f} | {cb / ca:.2f}{mark} | "
            f"{wb / wa:.2f} |"
        )
    worse = [(b, ln, cb / ca) for b, ln, ca, cb, _, _ in rows if cb / ca > args.flag]
    print(
        f"\nCPU ratios past {args.flag}: "
        + (", ".join(f"{b}: {ln} {r:.2f}" for b, ln, r in worse) or "none")
    )


def _skeleton(line: str) -> str:
    """The line without its numbers and with runs of blanks as one (columns move with widths)."""
    return " ".join(NUMBER.sub("#", line).split())


def scripts(args) -> None:
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    trees = {"A": args.base.resolve(), "B": ROOT}
    caches = {k: args.cache_prefix + k for k in trees}
    outputs: dict[str, dict[str, list[list[str]]]] = {}
    for s, script in enumerate(args.script):
        outputs[script] = {"A": [], "B": []}
        if args.report:  # the outputs of an earlier run, from --out
            for r in range(args.rounds):
                for name in ("A", "B"):
                    text = (out / f"{s}-{name}-{r}.txt").read_text()
                    outputs[script][name].append(text.splitlines())
            continue
        for r in range(args.rounds):
            order = ("A", "B") if r % 2 == 0 else ("B", "A")
            for name in order:
                tree = trees[name]
                argv = [sys.executable, str(tree / "benchmarks" / script.split()[0])]
                argv += script.split()[1:]
                env = dict(os.environ, PYTHONPATH=str(tree / "src"), NUMBA_CACHE_DIR=caches[name])
                load = os.getloadavg()[0]
                t = time.perf_counter()
                res = subprocess.run(argv, cwd=tree, env=env, capture_output=True, text=True)
                took = time.perf_counter() - t
                text = res.stdout + (res.stderr if res.returncode else "")
                (out / f"{s}-{name}-{r}.txt").write_text(text)
                print(
                    f"[{script}] round {r} {name}: rc {res.returncode}, {took:.0f} s, "
                    f"load before {load:.2f}",
                    flush=True,
                )
                outputs[script][name].append(text.splitlines())
    print()
    for script, runs in outputs.items():
        print(f"## {script}   (A = {trees['A']}, B = {trees['B']}; each round's numbers)")
        a_lines = runs["A"][0]
        b_lines = runs["B"][0]
        b_index: dict[str, list[int]] = {}
        for i, line in enumerate(b_lines):
            b_index.setdefault(_skeleton(line), []).append(i)
        used: dict[str, int] = {}
        for i, line in enumerate(a_lines):
            nums = NUMBER.findall(line)
            key = _skeleton(line)
            if not nums or key not in b_index:
                continue
            k = used.get(key, 0)
            if k >= len(b_index[key]):
                continue
            used[key] = k + 1
            j = b_index[key][k]
            a_vals = [NUMBER.findall(run[i]) if i < len(run) else [] for run in runs["A"]]
            b_vals = [NUMBER.findall(run[j]) if j < len(run) else [] for run in runs["B"]]
            if all(v == a_vals[0] for v in a_vals + b_vals):
                continue  # nothing measured on this line (sizes, versions, labels)
            label = _skeleton(line)[:70]
            a_txt = " / ".join(" ".join(v) for v in a_vals)
            b_txt = " / ".join(" ".join(v) for v in b_vals)
            print(f"{label}\n    A: {a_txt}\n    B: {b_txt}")
        print()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    sub = ap.add_subparsers(dest="mode", required=True)
    k = sub.add_parser("kernel", help="both trees in one process, alternated")
    k.add_argument("--base", type=Path, default=Path("/tmp/base"), help="the other checkout (A)")
    k.add_argument("--n", type=int, default=100_000)
    k.add_argument("--dists", default="uniform,clustered,grid")
    k.add_argument("--repeat", type=int, default=7, help="rounds; best of these per tree")
    c = sub.add_parser("calls", help="the benchmark scripts' calls, both trees in one process")
    c.add_argument("--base", type=Path, default=Path("/tmp/base"), help="the other checkout (A)")
    c.add_argument("--n", type=int, default=100_000)
    c.add_argument("--repeat", type=int, default=5, help="rounds; best of these per tree")
    c.add_argument("--big", action="store_true", help="also vf.voronoi on 1e6 uniform points")
    c.add_argument("--only", default="", help="comma-separated parts of benchmark or line names")
    c.add_argument("--flag", type=float, default=1.10, help="list CPU ratios B/A past this")
    c.add_argument("--profile", type=int, default=0, help="profile flagged cases: top N lines")
    s = sub.add_parser("scripts", help="benchmark scripts of both trees, alternated processes")
    s.add_argument("--base", type=Path, default=Path("/tmp/base"), help="the other checkout (A)")
    s.add_argument("--script", action="append", required=True, help="script and its arguments")
    s.add_argument("--rounds", type=int, default=2)
    s.add_argument("--out", default="/tmp/ab-trees", help="folder for the raw outputs")
    s.add_argument("--cache-prefix", default="/tmp/nb-ab-", help="NUMBA_CACHE_DIR per tree")
    s.add_argument("--report", action="store_true", help="only compare the outputs in --out")
    args = ap.parse_args()
    print(command_line())
    print(machine_info())
    {"kernel": kernel, "calls": calls, "scripts": scripts}[args.mode](args)


if __name__ == "__main__":
    main()
