"""``[[animation.tracks]]`` that could not change a frame are refused at their line (checker21 F3).

A track on ``animation.*`` (the table being played) or on an ``[output]`` key a frame's
picture does not read (``formats``) gave identical frames; two tracks on one key (or one
inside the other) silently played only the last; ``inf`` in values was reported as the
``nan`` it turns into between keyframes.
"""

from __future__ import annotations

import pytest

from voroforge.design.designfile import DesignError, load
from voroforge.studio.animation import overrides_at

HEAD = """[design]
name = "a"
[boundary]
shape = "rectangle"
width = 200
height = 100
[seeds]
method = "random"
count = 10
[[attractors]]
type = "point"
points = [[80, 50]]
radius = 100
[animation]
frames = 5
"""
TRACK = '[[animation.tracks]]\nkey = "{}"\nvalues = {}\n'


def _load(tmp_path, *tracks):
    path = tmp_path / "a.toml"
    path.write_text(HEAD + "".join(TRACK.format(k, v) for k, v in tracks))
    return load(path)[0]


@pytest.mark.parametrize(
    ("key", "values", "said"),
    [
        ("animation.frames", "[2, 5]", "it is the table being played"),
        ("animation", "[1, 2]", "it is the table being played"),
        (
            "output.formats",
            '[["svg"], ["png"]]',
            "a frame's picture reads only output.layers and output.png",
        ),
        (
            "output.png_size",
            "[100, 400]",
            "a frame's picture reads only output.layers and output.png",
        ),
    ],
)
def test_tracks_that_change_no_frame_are_refused(tmp_path, key, values, said):
    with pytest.raises(DesignError) as err:
        _load(tmp_path, ("cells.web", "[1, 3]"), (key, values))
    # the second track's key line: the head's 15 lines, 3 of the first track, its header
    assert f"a.toml:20: animation.tracks.1.key: {key!r} cannot be animated: {said}" in str(
        err.value
    )


def test_one_track_a_key(tmp_path):
    for first, second in [
        ("attractors.0.points.0", "attractors.0.points.0"),
        ("attractors.0", "attractors.0.points.0"),
        ("attractors.0.points.0", "attractors.0"),
    ]:
        with pytest.raises(DesignError, match=r"a\.toml:20: animation\.tracks\.1\.key: .* is "):
            _load(tmp_path, (first, "[[0, 50], [200, 50]]"), (second, "[[10, 50], [20, 50]]"))
    # different keys, and keys that only share a prefix of their name, are two tracks
    d = _load(tmp_path, ("cells.web", "[1, 3]"), ("cells.web_x", "[1, 3]"))
    assert [t.key for t in d.animation.tracks] == ["cells.web", "cells.web_x"]
    d = _load(tmp_path, ("cells.web", "[1, 3]"), ("output.png", '["cells", "layers"]'))
    assert overrides_at(d.animation, 4) == {"cells.web": 3, "output.png": "layers"}


def test_values_must_be_finite(tmp_path):
    with pytest.raises(DesignError, match=r"value 1 \(\[inf, 50\]\) is not finite"):
        _load(tmp_path, ("attractors.0.points.0", "[[0, 50], [inf, 50]]"))
