"""Compile ahead of time: run every command a new user meets first, once, into a scratch folder.

voroforge's kernels are numba functions compiled on their first call and cached on disk
(``__pycache__`` beside the sources, or ``NUMBA_CACHE_DIR`` when set). A fresh install
therefore pays the compile of a feature the first time it is used: seconds per feature,
about a minute for everything. :func:`warm_up` pays it up front: it runs each example
design's build, ``voroforge raster`` (exact and Jump Flooding) and ``voroforge explain``
on small inputs, in this process, writing into a temporary folder it deletes. Afterwards
every one of those first runs loads its kernels from the cache. ``make run`` calls it
(``voroforge warmup``); a ``pip install`` user runs ``voroforge warmup`` once.

The plan (:func:`plan`) is a list of command lines for :func:`voroforge.cli.main`, so the
warm-up compiles exactly what those commands compile (numba caches per function and
argument types, and the commands reach the same functions with the same types whatever
the size of the input). A step that fails (an example needing an optional extra that is
not installed, say) is reported and the others still run.
"""

from __future__ import annotations

import contextlib
import io
import tempfile
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

__all__ = [
    "SUITE_GROUPS",
    "Step",
    "compile_for_suite",
    "compile_suite",
    "example_designs",
    "plan",
    "run_plan",
    "time_first_runs",
    "warm_up",
]

#: Points of the raster and explain steps: enough for every code path, small enough to be
#: instant once compiled.
_POINTS = 40


@dataclass(frozen=True)
class Step:
    """One warm-up command and what came of it.

    Attributes
    ----------
    label : str
        What it warms, e.g. ``"build laser-panel.toml"``.
    argv : tuple of str
        The command line given to :func:`voroforge.cli.main` (without the program name).
    seconds : float
        Wall time of the step (compile plus run); NaN before it ran.
    error : str
        Empty when the command succeeded, else its message (the last line of it).
    cpu : float
        CPU time of this process during the step (numba compiles in this process, so this is
        the compile's cost whatever the machine's load); NaN before it ran.
    """

    label: str
    argv: tuple[str, ...]
    seconds: float = float("nan")
    error: str = ""
    cpu: float = float("nan")


def example_designs(root: Path | None = None) -> list[Path]:
    """The design files to warm: ``examples/*.toml`` of a source checkout, else the starter.

    Parameters
    ----------
    root : Path, optional
        Folder holding ``examples/`` (default: the checkout this package was installed
        from in editable mode, if any).

    Returns
    -------
    list of Path
        Sorted example designs; the packaged starter design when there are none (an
        installed wheel ships no examples).
    """
    if root is None:
        root = Path(__file__).resolve().parents[2]
    found = [d for d in sorted((root / "examples").glob("*.toml")) if not needs_missing_extra(d)]
    if found:
        return found
    return [Path(__file__).resolve().parent / "design" / "data" / "starter.toml"]


def needs_missing_extra(design: Path) -> bool:
    """Whether a design has a ``[solid]`` or ``[surface]`` table and the mesh extra is missing.

    ``make run`` installs the base package only; such examples are left out of its warm-up
    instead of failing there (``pip install 'voroforge[mesh]'`` brings them back).
    """
    import importlib.util
    import tomllib

    if all(importlib.util.find_spec(m) for m in ("trimesh", "manifold3d", "skimage")):
        return False
    try:
        data = tomllib.loads(design.read_text(encoding="utf-8"))
    except (OSError, tomllib.TOMLDecodeError, RecursionError):
        return False  # the build step reports it
    return "solid" in data or "surface" in data


def plan(designs: Sequence[Path], scratch: Path) -> list[Step]:
    """The warm-up commands: each design's build, then raster, explain and voronoi3d.

    Parameters
    ----------
    designs : sequence of Path
        Design files to build (outputs go to ``scratch``).
    scratch : Path
        Folder for every output and for the small point file the steps read.

    Returns
    -------
    list of Step
        Not yet run.
    """
    pts = scratch / "warmup-points.csv"
    steps = []
    for d in designs:
        out = scratch / d.stem
        steps.append(Step(f"build {d.name}", ("build", str(d), "-o", str(out))))
    for method in ("exact", "jfa"):
        argv = ("raster", str(pts), "-o", str(scratch / f"raster-{method}.png"))
        steps.append(
            Step(f"raster --method {method}", (*argv, "--size", "64x64", "--method", method))
        )
    gif = str(scratch / "sweep.gif")
    steps.append(
        Step(
            "explain fortune",
            ("explain", "fortune", str(pts), "-o", gif, "--frames", "4", "--size", "64"),
        )
    )
    # the 3D cells' kernels (~60 s of compile on a first vf.voronoi3d, checker8)
    pts3 = str(scratch / "warmup-points3d.csv")
    steps.append(Step("voronoi3d", ("voronoi3d", pts3, "-o", str(scratch / "cells3d.csv"))))
    return steps


def _write_points(path: Path, dims: int = 2) -> None:
    # a fixed, irregular set (no numpy needed to write it): a low-discrepancy sequence
    steps = (0.6180339887498949, 0.7548776662466927, 0.5698402909980532)[:dims]
    lines = [",".join("xyz"[:dims])]
    for k in range(1, _POINTS + 1):
        lines.append(",".join(f"{(k * a) % 1.0:.12f}" for a in steps))
    path.write_text("\n".join(lines) + "\n")


def run_plan(steps: Sequence[Step], report: Callable[[str], None] | None = None) -> list[Step]:
    """Run warm-up steps in this process, one after the other; never raises for a step.

    Parameters
    ----------
    steps : sequence of Step
        From :func:`plan` (the point file they read must exist).
    report : callable, optional
        Called with one line per finished step (progress), e.g. ``print``.

    Returns
    -------
    list of Step
        The steps with their times and errors filled in.
    """
    from .cli import main

    done = []
    for k, step in enumerate(steps, 1):
        sink = io.StringIO()
        t0 = time.perf_counter()
        c0 = time.process_time()
        try:
            with contextlib.redirect_stdout(sink), contextlib.redirect_stderr(sink):
                rc = main(list(step.argv))
            error = "" if rc == 0 else (sink.getvalue().strip().splitlines() or [f"exit {rc}"])[-1]
        except SystemExit as exc:  # argparse
            error = (
                ""
                if exc.code in (0, None)
                else (sink.getvalue().strip().splitlines() or [f"exit {exc.code}"])[-1]
            )
        except Exception as exc:  # a warm-up reports a broken step and goes on
            error = f"{type(exc).__name__}: {exc}"
        dt = time.perf_counter() - t0
        step = Step(step.label, step.argv, dt, error, time.process_time() - c0)
        done.append(step)
        if report is not None:
            status = "ok" if not error else f"FAILED: {error}"
            report(
                f"warm-up {k}/{len(steps)}: {step.label:<34} {dt:6.1f} s "
                f"({step.cpu:5.1f} s CPU)  {status}"
            )
    return done


def time_first_runs(
    steps: Sequence[Step], report: Callable[[str], None] | None = None, *, repeat: int = 1
) -> list[Step]:
    """Run each step's command in a fresh interpreter, as a user's first run would be.

    Each command runs as ``python -m voroforge ARGV`` in a new process (every import and
    every cached kernel load paid again), ``repeat`` times; the least wall and CPU time
    are kept. Run it after :func:`run_plan`, so that nothing is left to compile.

    Parameters
    ----------
    steps : sequence of Step
        From :func:`plan` (the point file they read must exist).
    report : callable, optional
        Called with one line per finished step.
    repeat : int
        Runs per step (>= 1).

    Returns
    -------
    list of Step
        ``seconds`` is the wall time and ``cpu`` the user + system time of the child
        process; ``error`` the last line of its error output if it failed. Each report
        line also gives the machine's load average: on a busy machine the wall time
        exceeds the CPU time.
    """
    import resource
    import subprocess
    import sys

    if int(repeat) < 1:
        raise ValueError(f"repeat must be >= 1, got {repeat!r}")
    done = []
    for k, step in enumerate(steps, 1):
        walls, cpus, error = [], [], ""
        for _ in range(int(repeat)):
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            t0 = time.perf_counter()
            run = subprocess.run(
                [sys.executable, "-m", "voroforge", *step.argv], capture_output=True, text=True
            )
            walls.append(time.perf_counter() - t0)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpus.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
            if run.returncode:
                error = (run.stderr.strip().splitlines() or [f"exit {run.returncode}"])[-1]
        step = Step(step.label, step.argv, min(walls), error, min(cpus))
        done.append(step)
        if report is not None:
            status = "ok" if not error else f"FAILED: {error}"
            report(
                f"first run {k}/{len(steps)}: {step.label:<34} {step.seconds:5.2f} s wall "
                f"{step.cpu:5.2f} s CPU  load {_load()}  {status}"
            )
    return done


def _load() -> str:
    """The 1-minute load average (wall times mean little without it), or ``?``."""
    import os

    try:
        return f"{os.getloadavg()[0]:.1f}"
    except (AttributeError, OSError):  # not on Windows
        return "?"


def warm_up(
    designs: Sequence[Path] | None = None,
    report: Callable[[str], None] | None = None,
    *,
    timed: int = 0,
) -> list[Step]:
    """Compile and cache every kernel the first commands of a new user need.

    Parameters
    ----------
    designs : sequence of Path, optional
        Design files whose builds to warm (default: :func:`example_designs`).
    report : callable, optional
        Progress: called with one line per step.
    timed : int
        After warming, run every step again this many times in fresh interpreters
        (:func:`time_first_runs`): what a user's first run costs now.

    Returns
    -------
    list of Step
        Every step with its wall time and error (empty when it succeeded), then, with
        ``timed``, the timed first runs. A second call is quick: everything then loads
        from the cache.
    """
    if designs is None:
        designs = example_designs()
    with tempfile.TemporaryDirectory(prefix="voroforge-warmup-") as tmp:
        scratch = Path(tmp)
        _write_points(scratch / "warmup-points.csv")
        _write_points(scratch / "warmup-points3d.csv", dims=3)
        steps = plan([Path(d) for d in designs], scratch)
        done = run_plan(steps, report)
        if timed:
            done += time_first_runs(steps, report, repeat=timed)
        return done


# The test suite's compile step (`make test`). On a fresh numba cache about half of the
# suite's CPU time is compilation (cold run 2026-12-06, 2 workers: 724 of 1311 s), and
# pytest-xdist's two workers compiled 176 of the same kernels twice (86 s: the 2D
# diagrams' and the 3D cells' largest kernels, which both workers meet first). These
# workloads reach those kernels through the public functions, with the argument types the
# engine gives them, in groups of roughly equal compile time: `make test` runs one group per
# process, side by side, before pytest, whose workers then load them from the cache (cold
# run with it: groups 157 and 166 s CPU, workers 471 and 458 s (639 and 672 without), 19 s
# compiled twice; kernels reached only by rarer paths still compile in the tests). A closed
# mesh container (2026-12-07: ~50 s of compile, met by the 3D tests of both workers) runs
# after the 3D box workload, whose cell kernels it reuses (cold run 2026-12-07 with it in
# group 1: groups 270 and 204 s; 218 and 256 expected this way). Session 60 (fresh caches,
# load ~12, CPU s): group 1 289 s and group 2 339 s, so group 1 took the fold rounds (the
# far circle: ~34 s that both test workers compiled) and the small kernels of
# `_suite_paths` (~10 s): ~347 s there against ~340 s.


def _suite_points(n: int = 60, dims: int = 2, seed: int = 7):
    import numpy as np

    return np.random.default_rng(seed).random((n, dims))


def _suite_2d_delaunay() -> None:
    import numpy as np

    import voroforge as vf

    p = _suite_points()
    d = vf.voronoi(p, (-0.5, -0.5, 1.5, 1.5))
    d.areas, d.centroids, d.neighbors, d.edges  # noqa: B018 (their kernels)
    # exactly cocircular and rounded cocircular sites far out: the merge and fold rounds
    t = np.linspace(0.0, 2.0 * np.pi, 64, endpoint=False)
    ring = np.column_stack([1e6 + np.cos(t), 1e6 + np.sin(t)])
    vf.voronoi(np.vstack([ring, [[1e6, 1e6]]]))
    grid = np.stack(np.meshgrid(np.arange(6.0), np.arange(6.0)), -1).reshape(-1, 2)
    vf.voronoi(grid)
    # a rounded circle far from the origin: its rings fold, so the fold rounds run
    # (kernels.folds, kernels.centers.contract_by: ~34 CPU s that both test workers paid)
    ring = np.column_stack([1e5 + 3.0 * np.cos(t), -2e5 + 3.0 * np.sin(t)])
    vf.voronoi(ring).areas  # noqa: B018


def _suite_2d_fortune() -> None:
    import voroforge as vf

    vf.voronoi(_suite_points(), algorithm="fortune")


def _suite_2d_halfplane() -> None:
    import voroforge as vf

    vf.voronoi(_suite_points(), algorithm="halfplane")


def _suite_power() -> None:
    import numpy as np

    import voroforge as vf

    p = _suite_points()
    vf.power(p, np.linspace(0.0, 0.01, len(p)))


def _suite_raster() -> None:
    import voroforge as vf

    for method in ("exact", "jfa"):
        vf.rasterize(_suite_points(), (32, 32), method=method)


def _suite_paths() -> None:
    # small kernels that both test workers compiled (kernels.plotter.two_opt ~8 s,
    # io.parquet._pairs_csr ~4 s); no diagram needed, so they fit in either group
    import numpy as np

    from .io.parquet import neighbor_lists
    from .io.plotter import order_paths

    rng = np.random.default_rng(7)
    order_paths([rng.random((3, 2)) for _ in range(12)])
    neighbor_lists(np.array([[0, 1], [1, 2], [0, 2]], np.int64), 3)


def _suite_3d() -> None:
    import numpy as np

    import voroforge as vf

    p = _suite_points(80, 3)
    d = vf.voronoi3d(p)
    d.volumes, d.neighbors, d.face_areas  # noqa: B018
    d.describe()  # engine.describe3d's convexity kernel, met by both test workers
    vf.voronoi3d(p, weights=np.linspace(0.0, 0.001, len(p)))
    d = vf.voronoi3d(p, (0.0, 0.0, 0.0, 1.0, 1.0, 1.0), periodic=True)
    d.unmatched_vertices  # noqa: B018 (engine.describe3d, met by both test workers)


def _suite_mesh3d() -> None:
    # a closed-mesh container (the mesh cut's kernels, ~50 s of compile met by the 3D tests
    # of both workers); after `_suite_3d`, whose cell kernels it reuses
    import importlib.util

    import voroforge as vf

    if importlib.util.find_spec("trimesh") is None:  # the mesh extra is not installed
        return
    import trimesh

    ball = trimesh.creation.icosphere(subdivisions=1)
    d = vf.voronoi3d(_suite_points(40, 3) - 0.5, ball)
    d.volumes, d.neighbors, d.face_areas, d.centroids  # noqa: B018


#: The compile step's groups (each of roughly equal compile time, one process each).
SUITE_GROUPS: tuple[tuple[Callable[[], None], ...], ...] = (
    (_suite_2d_delaunay, _suite_2d_fortune, _suite_2d_halfplane, _suite_paths),
    (_suite_3d, _suite_mesh3d, _suite_power, _suite_raster),
)


def compile_for_suite(group: int, report: Callable[[str], None] | None = None) -> list[Step]:
    """Run one group of :data:`SUITE_GROUPS` (1-based), compiling its kernels into the cache.

    Parameters
    ----------
    group : int
        Which group, ``1 .. len(SUITE_GROUPS)``.
    report : callable, optional
        Called with one line per workload.

    Returns
    -------
    list of Step
        One per workload (``argv`` empty), with its times and error; a failed workload is
        reported and the others still run (its kernels then compile in the tests).
    """
    if not 1 <= group <= len(SUITE_GROUPS):
        raise ValueError(f"group must be 1..{len(SUITE_GROUPS)}, got {group!r}")
    done = []
    for work in SUITE_GROUPS[group - 1]:
        t0, c0, error = time.perf_counter(), time.process_time(), ""
        try:
            work()
        except Exception as exc:  # the tests compile what a broken workload did not
            error = f"{type(exc).__name__}: {exc}"
        dt, cpu = time.perf_counter() - t0, time.process_time() - c0
        step = Step(work.__name__.lstrip("_"), (), dt, error, cpu)
        done.append(step)
        if report is not None:
            status = "ok" if not error else f"FAILED: {error}"
            report(
                f"compile {group}: {step.label:<20} {step.seconds:6.1f} s "
                f"({step.cpu:5.1f} s CPU)  {status}"
            )
    return done


def compile_suite(report: Callable[[str], None] | None = None) -> int:
    """Run every group of :data:`SUITE_GROUPS` at once, each in its own interpreter.

    ``make test`` calls it (``python -m voroforge.warmup --suite``) before pytest. Each
    group's lines go to ``report`` as it ends. Returns the number of failed workloads (their
    kernels then compile in the tests, which report the failure themselves).
    """
    import subprocess
    import sys

    t0 = time.perf_counter()
    runs = [
        subprocess.Popen(
            [sys.executable, "-m", "voroforge.warmup", "--suite-group", str(g)],
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
        )
        for g in range(1, len(SUITE_GROUPS) + 1)
    ]
    failed = 0
    for run in runs:
        out, _ = run.communicate()
        failed += out.count("FAILED") + (run.returncode != 0)
        if report is not None:
            for line in out.splitlines():
                report(line)
    if report is not None:
        report(f"compile step: {len(runs)} groups in {time.perf_counter() - t0:.1f} s")
    return failed


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m voroforge.warmup --suite``: the test suite's compile step (always exits 0).

    ``--suite-group G`` runs group ``G`` alone in this process.
    """
    import argparse
    import sys

    parser = argparse.ArgumentParser(prog="python -m voroforge.warmup")
    which = parser.add_mutually_exclusive_group(required=True)
    which.add_argument("--suite", action="store_true", help="every group, side by side")
    which.add_argument("--suite-group", type=int, metavar="G", help="group G alone")
    args = parser.parse_args(argv)

    def say(line: str) -> None:
        print(line, file=sys.stderr, flush=True)

    if args.suite:
        compile_suite(say)
    else:
        compile_for_suite(args.suite_group, say)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
