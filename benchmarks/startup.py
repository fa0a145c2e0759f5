"""Start-up cost of voroforge in fresh processes: import time and first-call time.

Each measurement runs ``python -c ...`` that times ``import voroforge`` and then the first
``vf.voronoi(points, (0, 0, 1, 1)).cells`` on a small input (plus a second call, to show
the steady-state cost of the same input).

warm
    numba's on-disk cache is populated (one untimed run first), then the best of
    ``--repeat`` fresh processes is reported: what a user sees on every run after the
    first one.
cold
    ``NUMBA_CACHE_DIR`` points at a new empty temporary directory for every process, so
    every kernel is compiled from scratch (numba otherwise caches next to the sources, in
    ``__pycache__``; ``NUMBA_CACHE_DIR`` overrides that location): what a user sees on the
    very first run after installing.

Examples::

    python benchmarks/startup.py
    python benchmarks/startup.py --repeat 5 --cold-repeat 2 --n 1000
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import textwrap
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from common import command_line, fmt_seconds, machine_info, print_table  # noqa: E402

CHILD = textwrap.dedent(
    """
    import time
    t0 = time.perf_counter()
    import voroforge as vf
    t1 = time.perf_counter()
    import json
    import numpy as np
    points = np.random.default_rng(0).random(({n}, 2))
    t2 = time.perf_counter()
    cells = vf.voronoi(points, (0.0, 0.0, 1.0, 1.0)).cells
    t3 = time.perf_counter()
    cells = vf.voronoi(points, (0.0, 0.0, 1.0, 1.0)).cells
    t4 = time.perf_counter()
    print(json.dumps({{"import": t1 - t0, "first_call": t3 - t2, "second_call": t4 - t3}}))
    """
)


def run_child(n: int, env: dict[str, str]) -> dict:
    """One fresh interpreter: its timings, plus the whole process wall time."""
    t0 = time.perf_counter()
    proc = subprocess.run(
        [sys.executable, "-c", CHILD.format(n=n)],
        capture_output=True,
        text=True,
        env=env,
        check=False,
    )
    wall = time.perf_counter() - t0
    if proc.returncode != 0:
        tail = (proc.stderr or proc.stdout).strip().splitlines()[-5:]
        raise RuntimeError(f"child exited {proc.returncode}: " + " | ".join(tail))
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    out["process"] = wall
    return out


def best(runs: list[dict]) -> dict:
    """Field-wise minimum over runs."""
    return {k: min(r[k] for r in runs) for k in runs[0]}


def main(argv: list[str] | None = None) -> None:
    """Parse the options, run the warm and cold measurements and print a table."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, default=1000, help="points in the small input")
    ap.add_argument("--repeat", type=int, default=3, help="warm runs (best of)")
    ap.add_argument(
        "--cold-repeat", type=int, default=1, help="cold runs (best of); each compiles all"
    )
    ap.add_argument("--skip-cold", action="store_true", help="only the warm-cache runs")
    args = ap.parse_args(argv)

    print("command: " + command_line())
    print(machine_info())
    env = dict(os.environ)
    where = env.get("NUMBA_CACHE_DIR", "next to the sources (__pycache__)")
    print(f"warm numba cache location: {where}")

    rows = []
    run_child(args.n, env)  # populate the cache; not reported
    warm = best([run_child(args.n, env) for _ in range(max(1, args.repeat))])
    rows.append(["warm cache", warm])

    if not args.skip_cold:
        cold_runs = []
        for _ in range(max(1, args.cold_repeat)):
            with tempfile.TemporaryDirectory(prefix="vf-numba-cold-") as tmp:
                cold_runs.append(run_child(args.n, {**env, "NUMBA_CACHE_DIR": tmp}))
        rows.append(["cold compile", best(cold_runs)])

    print_table(
        ["case", "import s", "first call s", "second call s", "process s"],
        [
            [
                name,
                fmt_seconds(r["import"]),
                fmt_seconds(r["first_call"]),
                fmt_seconds(r["second_call"]),
                fmt_seconds(r["process"]),
            ]
            for name, r in rows
        ],
        title=(
            f"start-up, vf.voronoi(uniform {args.n}, box).cells in fresh processes "
            f"(warm: best of {args.repeat}; cold: best of {args.cold_repeat})"
        ),
    )
    print("process s = whole child process wall time, interpreter start-up included")


if __name__ == "__main__":
    main()
