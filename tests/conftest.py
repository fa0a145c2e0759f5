"""Shared fixtures: the algorithms every 2D diagram test runs over, and hypothesis profiles."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings

# The helper modules (reference, validate, catalogue) are imported by their plain names.
sys.path.insert(0, str(Path(__file__).parent))

#: Every ``algorithm=`` that must produce the same cells; engines add themselves here.
ALGORITHMS = ["delaunay", "fortune", "halfplane"]

settings.register_profile(
    "default",
    deadline=None,
    max_examples=30,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile(
    "ci",
    deadline=None,
    max_examples=30,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow],
)
# a longer bug hunt: pytest --hypothesis-profile=thorough
settings.register_profile(
    "thorough",
    deadline=None,
    max_examples=500,
    suppress_health_check=[HealthCheck.too_slow],
)
# `make coverage` runs the kernels as plain Python (NUMBA_DISABLE_JIT=1): fewer examples
settings.register_profile(
    "coverage",
    deadline=None,
    max_examples=5,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile("ci" if os.environ.get("CI") else "default")


@pytest.fixture(params=ALGORITHMS)
def algorithm(request) -> str:
    """Name of a 2D Voronoi algorithm (``vf.voronoi(..., algorithm=...)``)."""
    return request.param


@pytest.fixture
def periodic_builds(monkeypatch) -> list:
    """The site counts of each periodic build (``engine.periodic.build``) in the test."""
    import voroforge.engine.periodic as per

    sizes = []
    real = per.build

    def counting(pts, *args, **kw):
        sizes.append(len(pts))
        return real(pts, *args, **kw)

    monkeypatch.setattr(per, "build", counting)
    return sizes


def _first_outputs(monkeypatch, module, name: str) -> list:
    """The first output of every call of ``module.name`` in the test (a status array)."""
    seen = []
    inner = getattr(module, name)

    def spy(*args):
        got = inner(*args)
        seen.append(got[0])
        return got

    monkeypatch.setattr(module, name, spy)
    return seen


@pytest.fixture
def clip_statuses(monkeypatch) -> list:
    """The polygon-clip kernel's status array for every call in the test.

    (The engine turns LOOPS cells to DONE in place after the kernel returns.)
    """
    from voroforge.engine import polyclip

    return _first_outputs(monkeypatch, polyclip, "clip_cells")


@pytest.fixture
def edge_statuses(monkeypatch) -> list:
    """The shared-edge clip kernel's status array for every call in the test."""
    from voroforge.engine import polyclip

    return _first_outputs(monkeypatch, polyclip, "edge_kernel")


@pytest.fixture(scope="module")
def dask_client():
    """An in-process LocalCluster of two single-threaded workers, one per test module."""
    distributed = pytest.importorskip("distributed")
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=False, dashboard_address=":0"
        ) as cluster,
        distributed.Client(cluster) as c,
    ):
        yield c
