"""Rebuild the README gallery: one small PNG per example in docs/gallery/.

Run from the repository root:  .venv/bin/python examples/gallery.py
"""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

from voroforge.design.pipeline import build

ROOT = Path(__file__).resolve().parent.parent
SIZE = 560


def main() -> None:
    """Build every example as a small PNG into docs/gallery/."""
    out = ROOT / "docs" / "gallery"
    out.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        for design in sorted((ROOT / "examples").glob("*.toml")):
            overrides = {
                "output.formats": '["png"]',
                "output.png_size": SIZE,
                "fabrication.report": "false",
            }
            (png,) = build(design, tmp, overrides=overrides)
            target = out / f"{design.stem}.png"
            shutil.copyfile(png, target)
            print(target.relative_to(ROOT), f"{target.stat().st_size // 1024} kB")


if __name__ == "__main__":
    main()
