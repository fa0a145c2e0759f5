"""Studio benchmark: what the server does per edit, in CPU time and wall time.

For a 2000-cell panel clipped to a polygon with a hole (2 mm webs, 1.5 mm fillets), for
plain cells (2000 and 20000) and for two sliders that make new seeds (``seeds.count``,
whose random stream keeps the first seeds, and ``design.seed``: all 2000 new), times one edit
as the studio server handles it: ``Session.apply`` (a seed drag on the incremental path of
:mod:`voroforge.studio.incremental`, or a full recompute) plus the binary message for the
page (``geometry_message``, cells at the page's pixel size). A seed drag is also timed on
the full-recompute path (``Session.incremental = False``: ``compute`` with the previous
result to reuse), for the ratio, and the sliders with the cell operations in one thread
(``Session.workers = 1``), and ``design.seed`` steps computed ahead as the server computes
them between a slider's steps (``Session.compute_ahead``, untimed: what is left for the
step). CPU time (``time.process_time``, all threads) is what to read on a shared machine;
wall time is printed beside it. Median and best over the steps.
The page's side (parse, draw, frame) is measured in the browser by
``tests/test_studio_browser.py::test_latency_table``. Run from the repository root:

    NUMBA_NUM_THREADS=1 .venv/bin/python benchmarks/bench_studio.py [--steps S] [--split]

``--split`` prints only where a ``design.seed`` step of the holed panel goes (the cell
operations ``cellops.inset``, ``cellops.fillet`` and ``cellops.inset_fillet`` against the
whole step, one thread; ``inset_fillet``'s time includes the two on the cells it leaves to
them). Memory is kept for reuse as the server keeps it
(``studio.heap.keep_heap``: big numpy arrays are not page-faulted in anew every step);
``--system-malloc`` leaves glibc's default.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "src"))

from voroforge.studio.heap import keep_heap  # noqa: E402
from voroforge.studio.server import geometry_message  # noqa: E402
from voroforge.studio.session import Session  # noqa: E402

HOLED = {
    "design": {"name": "holed-2000", "seed": 1},
    "boundary": {
        "shape": "polygon",
        "points": [[0, 0], [1000, 0], [1000, 700], [0, 700]],
        "holes": [[[400, 250], [600, 250], [600, 450], [400, 450]]],
    },
    "seeds": {"method": "random", "count": 2000},
    "cells": {"web": 2.0, "fillet": 1.5},
}
PLAIN = {**HOLED, "cells": {}}
CASES = {
    "2,000 cells, hole, inset + fillet": HOLED,
    "2,000 plain cells": PLAIN,
    "20,000 plain cells": {**PLAIN, "seeds": {"method": "random", "count": 20000}},
}
#: A page 960 pixels wide showing the 1000-unit panel (its `view` message)
PX = 1000 / 960


def _timed(session: Session, msg: dict, sent: dict) -> tuple[float, float, float]:
    """(cpu ms, wall ms, message KiB) of one edit and its message."""
    c0, w0 = time.process_time(), time.perf_counter()
    reply = session.apply(msg)
    assert reply.kind == "update", reply
    payload = geometry_message(session, reply.changed, seq=1, boundary=False, sent=sent, px=PX)
    cpu, wall = time.process_time() - c0, time.perf_counter() - w0
    return cpu * 1e3, wall * 1e3, len(payload) / 1024


def drag(session: Session, steps: int, incremental: bool) -> np.ndarray:
    """(steps, 3) timings of a seed drag (see _timed)."""
    session.incremental = incremental
    i = len(session.result.sites) // 2
    sent: dict = {}
    geometry_message(session, None, seq=0, boundary=True, sent=sent, px=PX)
    x0, y0 = session._sites()[i]
    out = []
    for k in range(steps):
        x, y = x0 + 3.0 * np.sin(k / 3.0), y0 + 3.0 * np.cos(k / 4.0)
        out.append(_timed(session, {"op": "move", "i": i, "x": float(x), "y": float(y)}, sent))
    return np.array(out)


#: Slider values: seeds.count (the random stream keeps its first seeds: the cells near the
#: added or dropped ones change) and design.seed (every seed new)
SLIDERS = {
    "seeds.count": [1990, 2010, 1995, 2005, 2000, 1985, 2015, 2001],
    "design.seed": [2, 3, 4, 5, 6, 7, 8, 9],
}


def slider(session: Session, steps: int, key: str) -> np.ndarray:
    """(steps, 3) timings of a slider that makes new seeds (see SLIDERS)."""
    sent: dict = {}
    geometry_message(session, None, seq=0, boundary=True, sent=sent, px=PX)
    values = SLIDERS[key] * (1 + steps // 8)
    return np.array(
        [_timed(session, {"op": "set", "key": key, "value": v}, sent) for v in values[:steps]]
    )


def slider_ahead(session: Session, steps: int, key: str) -> np.ndarray:
    """(steps, 3) timings of slider steps each computed ahead (as the server does between
    steps, :meth:`Session.compute_ahead`, not timed): what is left for the step itself."""
    sent: dict = {}
    geometry_message(session, None, seq=0, boundary=True, sent=sent, px=PX)
    values = SLIDERS[key] * (1 + steps // 8)
    out = []
    for v in values[:steps]:
        session.compute_ahead(session.data, session.result, key, v)
        out.append(_timed(session, {"op": "set", "key": key, "value": v}, sent))
        assert session.ahead_used
    return np.array(out)


def split(steps: int) -> None:
    """Where a design.seed step of the holed panel goes: the cell operations and the rest."""
    from voroforge.design import cellops

    spent: dict[str, float] = {}

    def timed(name, fn):
        def run(*args, **kwargs):
            c0 = time.process_time()
            try:
                return fn(*args, **kwargs)
            finally:
                spent[name] = spent.get(name, 0.0) + time.process_time() - c0

        return run

    saved = {k: getattr(cellops, k) for k in ("inset", "fillet", "inset_fillet")}
    for k, fn in saved.items():
        setattr(cellops, k, timed(k, fn))
    try:
        session = Session(HOLED)
        session.workers = 1
        slider(session, 2, "design.seed")
        spent.clear()
        t = slider(session, steps, "design.seed")
    finally:
        for k, fn in saved.items():
            setattr(cellops, k, fn)
    total = t[:, 0].sum()
    print(f"design.seed, holed 2000, 1 thread, {steps} steps: {total / steps:.1f} ms CPU per step")
    for k, v in spent.items():
        print(f"  cellops.{k}: {v * 1e3 / steps:.1f} ms ({100 * v * 1e3 / total:.0f}%)")


def _row(name: str, t: np.ndarray) -> str:
    cpu, wall = t[:, 0], t[:, 1]
    return (
        f"| {name} | {np.median(cpu):.1f} | {cpu.min():.1f} | {np.median(wall):.1f} "
        f"| {np.median(t[:, 2]):.1f} |"
    )


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=20)
    ap.add_argument(
        "--split", action="store_true", help="only the design.seed step's cell operations"
    )
    ap.add_argument(
        "--system-malloc", action="store_true", help="glibc's default (not the server's)"
    )
    args = ap.parse_args(argv)
    if not args.system_malloc:
        keep_heap()
    print(f"python {sys.version.split()[0]}, {os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f}")
    if args.split:
        split(args.steps)
        return 0
    print("| edit | CPU ms median | CPU ms best | wall ms median | message KiB |")
    print("|---|---|---|---|---|")
    for name, data in CASES.items():
        session = Session(data)
        drag(session, 3, True)  # warm both paths
        drag(session, 2, False)
        print(_row(f"seed drag, {name}", drag(session, args.steps, True)), flush=True)
        full = drag(session, max(3, args.steps // 4), False)
        print(_row(f"seed drag, {name}, full recompute", full), flush=True)
        if data in (HOLED, PLAIN):
            for key in SLIDERS:
                session = Session(data)
                slider(session, 2, key)
                steps = max(4, args.steps // 2)
                print(_row(f"{key} slider, {name}", slider(session, steps, key)), flush=True)
                session.workers = 1
                print(_row(f"{key} slider, {name}, 1 thread", slider(session, 4, key)), flush=True)
                if key == "design.seed":  # a full computation each: the server computes ahead
                    t = slider_ahead(session, steps, key)
                    print(_row(f"{key} slider, {name}, computed ahead", t), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
