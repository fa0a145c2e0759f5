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

``scripts``
    Runs benchmark scripts of both trees in fresh subprocesses, each tree its own copy of the
    script with ``PYTHONPATH=<tree>/src`` and its own ``NUMBA_CACHE_DIR``, alternating
    A B B A ... for ``--rounds``. Saves every output under ``--out`` and prints, for each
    output line whose text apart from the numbers is the same in both trees, the numbers of
    A and of B side by side (each round's).

Run from the repository root::

    git worktree add /tmp/base 00169d7
    NUMBA_NUM_THREADS=1 .venv/bin/python benchmarks/ab_trees.py kernel --base /tmp/base
    .venv/bin/python benchmarks/ab_trees.py scripts --base /tmp/base --rounds 2 \\
        --script "bench_algorithms.py --sizes 1e5 --repeat 5"
"""

from __future__ import annotations

import argparse
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

from common import DISTRIBUTIONS, command_line, machine_info  # noqa: E402

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
    {"kernel": kernel, "scripts": scripts}[args.mode](args)


if __name__ == "__main__":
    main()
