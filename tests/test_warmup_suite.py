"""The test suite's compile step (``python -m voroforge.warmup --suite``, run by ``make test``)."""

from __future__ import annotations

import pytest

from voroforge import warmup
from voroforge.warmup import SUITE_GROUPS, compile_for_suite, main


def test_the_groups_are_disjoint_and_each_workload_runs_without_error():
    works = [w for g in SUITE_GROUPS for w in g]
    assert len(SUITE_GROUPS) >= 2 and all(SUITE_GROUPS)
    assert len(set(works)) == len(works)
    # make test runs these first, so the kernels are cached here and this is quick; a
    # workload that failed there would only have been reported
    for g in range(1, len(SUITE_GROUPS) + 1):
        done = compile_for_suite(g)
        assert [s.label for s in done] == [w.__name__.lstrip("_") for w in SUITE_GROUPS[g - 1]]
        assert all(not s.error and s.seconds >= 0 and s.cpu >= 0 for s in done), done


def test_a_failing_workload_is_reported_and_the_rest_still_run(monkeypatch):
    ran = []

    def broken():
        raise RuntimeError("no kernel today")

    def fine():
        ran.append(1)

    monkeypatch.setattr(warmup, "SUITE_GROUPS", ((broken, fine),))
    lines = []
    done = compile_for_suite(1, report=lines.append)
    assert ran == [1]
    assert [s.error for s in done] == ["RuntimeError: no kernel today", ""]
    assert "FAILED: RuntimeError: no kernel today" in lines[0] and lines[1].endswith("ok")
    with pytest.raises(ValueError, match="group must be 1..1, got 2"):
        compile_for_suite(2)


def test_main_runs_one_group_and_always_exits_0(monkeypatch, capsys):
    ran = []
    monkeypatch.setattr(warmup, "SUITE_GROUPS", ((lambda: ran.append(1),), (ran.clear,)))
    assert main(["--suite-group", "1"]) == 0
    assert ran == [1]
    assert "compile 1: <lambda>" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        main([])  # --suite or --suite-group is required
