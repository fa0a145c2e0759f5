"""Studio benchmark: one seed-drag step, incremental against the full recompute.

For a 2000-cell panel clipped to a polygon with a hole (2 mm webs, 1.5 mm fillets) and for
plain cells (2000 and 20000), times what the studio server does for one step of a seed
drag: ``Session.apply({"op": "move", ...})`` on the incremental path
(:mod:`voroforge.studio.incremental`: a window diagram around the seed, the changed cells'
inset and fillet) against the same step computed in full
(``voroforge.design.compute.compute`` with the previous result to reuse, which is what the
studio did before), plus the binary patch for the page. Both run in one process, warm,
on the same steps, best of N; the ratio is what to read (the machine may be shared).
Also prints the full recompute of a slider that makes all new seeds. Run from the
repository root:

    NUMBA_NUM_THREADS=1 .venv/bin/python benchmarks/bench_studio.py [--repeat K] [--steps S]
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "src"))

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
CASES = {
    "2,000 cells, hole, inset + fillet": HOLED,
    "2,000 plain cells": {**HOLED, "cells": {}},
    "20,000 plain cells": {**HOLED, "cells": {}, "seeds": {"method": "random", "count": 20000}},
}


def drag(session: Session, steps: int, incremental: bool) -> float:
    """Seconds per drag step (best over the steps' runs is taken by the caller)."""
    session.incremental = incremental
    i = len(session.result.sites) // 2
    sent: dict = {}
    geometry_message(session, None, seq=0, boundary=True, sent=sent)
    x0, y0 = session._sites()[i]
    start = time.perf_counter()
    for k in range(steps):
        x, y = x0 + 3.0 * np.sin(k / 3.0), y0 + 3.0 * np.cos(k / 4.0)
        reply = session.apply({"op": "move", "i": i, "x": float(x), "y": float(y)})
        assert reply.kind == "update", reply
        geometry_message(session, reply.changed, seq=k + 1, boundary=False, sent=sent)
    return (time.perf_counter() - start) / steps


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--steps", type=int, default=10)
    args = ap.parse_args(argv)
    print(f"python {sys.version.split()[0]}, load {os.getloadavg()[0]:.1f}, best of {args.repeat}")
    print("| case | drag step, incremental ms | drag step, full recompute ms | ratio |")
    print("|---|---|---|---|")
    slider = None
    for name, data in CASES.items():
        session = Session(data)
        session.apply({"op": "move", "i": 0, "x": float(session.result.sites[0, 0]), "y": 10.0})
        drag(session, 2, True)  # warm both paths
        drag(session, 2, False)
        fast = min(drag(session, args.steps, True) for _ in range(args.repeat))
        full = min(drag(session, max(2, args.steps // 3), False) for _ in range(args.repeat))
        print(f"| {name} | {fast * 1e3:.1f} | {full * 1e3:.1f} | {full / fast:.1f}x |")
        if data is HOLED:
            times = []
            for count in (1990, 2010, 1995, 2005, 2000)[: max(2, args.repeat)]:
                start = time.perf_counter()
                session.apply({"op": "set", "key": "seeds.count", "value": count})
                times.append(time.perf_counter() - start)
            slider = min(times)
    print(f"\nseeds.count slider (all 2,000 seeds new, inset + fillet): {slider * 1e3:.1f} ms")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
