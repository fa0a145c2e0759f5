"""The README's "Parametric design (Python)" example runs as printed and makes a sound part."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import shapely

README = Path(__file__).resolve().parents[1] / "README.md"


def _example() -> str:
    text = README.read_text(encoding="utf-8")
    section = text.split("## Parametric design (Python)", 1)[1].split("\n## ", 1)[0]
    blocks = re.findall(r"```python\n(.*?)```", section, flags=re.S)
    assert blocks, "the README section lost its example"
    return blocks[0]


def test_readme_design_pipeline_runs(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    namespace: dict = {}
    exec(compile(_example(), str(README), "exec"), namespace)  # noqa: S102
    part, panel, holes, keep = (namespace[k] for k in ("part", "panel", "holes", "keep"))
    assert part.is_valid and part.within(panel.buffer(1e-9))
    openings = holes[keep]
    assert part.area == pytest.approx(panel.area - shapely.area(openings).sum(), rel=1e-9)
    assert 0.2 < part.area / panel.area < 0.9
    root = ET.parse(tmp_path / "panel.svg").getroot()
    assert root.get("width").endswith("mm")
    assert "openings" in capsys.readouterr().out
