"""Fixes of the lead's session s51 (checker findings), each against an independent expectation."""

from __future__ import annotations

import numpy as np
import pytest

import voroforge as vf
from voroforge import solid


@pytest.fixture(scope="module")
def cells20():
    return vf.voronoi3d(np.random.default_rng(0).random((20, 3)), (0, 0, 0, 1, 1, 1))


@pytest.mark.parametrize(
    ("wall", "words"),
    [
        (lambda x: np.full(len(x), -0.1), "non-positive or non-finite"),
        (lambda x: np.full(len(x), np.nan), "non-positive or non-finite"),
        (lambda x: np.full(3, 0.01), "values for"),
        (lambda x: ["a"] * len(x), "not numbers"),
    ],
)
def test_a_callable_wall_is_checked_like_a_number(cells20, wall, words):
    # checker28 F1: a negative wall made bubbles larger than their cells (volume -1.09)
    with pytest.raises(ValueError, match=f"wall: .*{words}"):
        solid.foam(cells20, wall=wall)


def test_a_callable_wall_equal_to_a_number_gives_the_same_foam(cells20):
    a = solid.foam(cells20, wall=0.02)
    b = solid.foam(cells20, wall=lambda x: np.full(len(x), 0.02))
    assert a.is_volume and b.is_volume
    assert np.isclose(a.volume, b.volume, rtol=1e-12, atol=0)


SHELL_TOML = """[design]
name = "s"
units = "mm"

[solid]
kind = "shell"
profile = {profile}
openings = {openings}
thickness = 1.6
formats = ["stl"]
"""


@pytest.mark.parametrize(
    ("profile", "openings", "where"),
    [
        ("[[30, 0], [22, 40]]", 1, ":8: solid.openings: .*at least 2"),  # checker28 F3
        ("[[1e300, 0], [2e300, 1e300]]", 60, ":7: solid.profile: .*within"),  # checker28 F4
    ],
)
def test_shell_keys_out_of_range_name_their_line(tmp_path, profile, openings, where):
    from voroforge.design.designfile import DesignError, load

    path = tmp_path / "s.toml"
    path.write_text(SHELL_TOML.format(profile=profile, openings=openings))
    with pytest.raises(DesignError, match=where):
        load(path)
