"""The CLI shows a build's other warnings and ends (checker21 F2), and says why a surface
design makes no panel (F2b).

``design_warnings`` re-showed a warning that is not a design warning while still recording
warnings: ``showwarning`` appended to the list being read, and ``voroforge build`` never
ended (memory grew) on any build that emitted, say, a ``MissingPanelWarning``.
"""

from __future__ import annotations

import subprocess
import sys

from voroforge.cli import main

SHOW = """
import warnings
from voroforge.cli.design import design_warnings
with design_warnings("d.toml"):
    warnings.warn("plain warning", UserWarning)
    warnings.warn("plain warning 2", RuntimeWarning)
print("ended")
"""


def test_other_warnings_are_shown_and_the_block_ends():
    # in a child process with a timeout: the bug was an endless loop
    r = subprocess.run(
        [sys.executable, "-c", SHOW], capture_output=True, text=True, timeout=120, check=False
    )
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "ended"
    assert "UserWarning: plain warning" in r.stderr
    assert "RuntimeWarning: plain warning 2" in r.stderr


TORUS = """
[design]
name = "t"
seed = 1
[boundary]
shape = "rectangle"
width = 1
height = 1
[seeds]
method = "random"
count = 2
[output]
formats = ["png"]
png_size = 100
[surface]
shape = "torus"
major = 1
minor = 0.4
mode = "voronoi"
"""


def test_a_surface_design_without_panels_says_so(tmp_path, capsys):
    path = tmp_path / "t.toml"
    path.write_text(TORUS)
    assert main(["build", str(path), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert f"{path}:11: seeds.count: none of the 2 cells makes a panel" in err
    assert not list(tmp_path.glob("out/*.png"))  # nothing half-made was written
