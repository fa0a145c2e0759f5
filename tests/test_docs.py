"""The documentation: every link resolves, every design key is documented, the site builds.

The site (``make docs``, Sphinx) is built with warnings as errors, so a docstring that
numpydoc cannot parse or a page missing from the navigation fails here, not on a reader.
"""

from __future__ import annotations

import importlib.util
import re
import subprocess
import sys
import types
import typing
from pathlib import Path

import pytest
from pydantic import BaseModel

from voroforge.design.schema import Design

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
PAGES = sorted(
    [*DOCS.glob("*.md"), ROOT / "README.md", ROOT / "BENCHMARKS.md", *ROOT.glob("*/README.md")]
)
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
HEADING = re.compile(r"^(#+)\s+(.*)$")
#: Pages that docs/_ext/voroforge_docs.py generates when the site is built.
GENERATED = {"_generated/gallery.md", "_generated/api.md", "_generated/guides.md"}


def _links(text: str) -> list[str]:
    text = re.sub(r"```.*?```", "", text, flags=re.S)  # not inside code blocks
    return [m.group(1) for m in LINK.finditer(text)]


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_relative_link_resolves(page):
    broken = []
    for target in _links(page.read_text(encoding="utf-8")):
        if re.match(r"^[a-z]+:", target) or target.startswith("#"):
            continue  # a web address, or an anchor on the same page
        path = target.split("#", 1)[0]
        if page.parent == DOCS and path in GENERATED:
            continue  # written by docs/_ext at build time (test_site_builds_without_warnings)
        if not (page.parent / path).exists():
            broken.append(target)
    assert not broken, f"{page.relative_to(ROOT)}: broken links {broken}"


def _model_of(annotation) -> tuple[type[BaseModel] | None, bool]:
    """The model class behind ``X``, ``X | None`` or ``list[X]``, and whether it is a list."""
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation, False
    origin = typing.get_origin(annotation)
    if origin in (typing.Union, types.UnionType):
        for arg in typing.get_args(annotation):
            model, many = _model_of(arg)
            if model is not None:
                return model, many
    if origin is list:
        model, _ = _model_of(typing.get_args(annotation)[0])
        return model, model is not None
    return None, False


def _sections() -> dict[str, str]:
    """Heading text (``[cells]``, ``[[attractors]]``, ``[output.gif]``) -> its block of docs."""
    blocks: dict[str, str] = {}
    for page in DOCS.glob("*.md"):
        lines = page.read_text(encoding="utf-8").splitlines()
        for i, line in enumerate(lines):
            m = HEADING.match(line)
            if not m or not (key := re.search(r"`(\[\[?[\w.]+\]\]?)`", m.group(2))):
                continue
            level, end = len(m.group(1)), len(lines)
            for j in range(i + 1, len(lines)):
                n = HEADING.match(lines[j])
                if n and len(n.group(1)) <= level:
                    end = j
                    break
            blocks[key.group(1)] = "\n".join(lines[i:end])
    return blocks


def _undocumented(model: type[BaseModel], name: str, many: bool, blocks) -> list[str]:
    heading = f"[[{name}]]" if many else f"[{name}]"
    if heading not in blocks:
        return [f"{heading} (no section heading in docs/)"]
    missing = []
    for field, info in model.model_fields.items():
        key = info.alias or field
        sub, sub_many = _model_of(info.annotation)
        if sub is not None and f"[{name}.{key}]" in blocks:
            missing += _undocumented(sub, f"{name}.{key}", sub_many, blocks)
        elif f"`{key}`" not in blocks[heading]:
            missing.append(f"{name}.{key}")
    return missing


def test_every_design_key_is_documented():
    blocks = _sections()
    missing = []
    for field, info in Design.model_fields.items():
        model, many = _model_of(info.annotation)
        assert model is not None, field
        missing += _undocumented(model, info.alias or field, many, blocks)
    assert not missing, f"design keys missing from docs/*.md: {missing}"


@pytest.mark.skipif(importlib.util.find_spec("sphinx") is None, reason="sphinx not installed")
def test_site_builds_without_warnings(tmp_path):
    cmd = [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html"]
    done = subprocess.run(
        [*cmd, "-d", str(tmp_path / "doctrees"), str(DOCS), str(tmp_path / "html")],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stderr[-4000:]
    front = (tmp_path / "html" / "index.html").read_text(encoding="utf-8")
    assert "Getting started" in front and "Gallery" in front
    api = tmp_path / "html" / "_generated" / "api" / "voroforge.voronoi.html"
    assert "Parameters" in api.read_text(encoding="utf-8")
    for example in (ROOT / "examples").glob("*.toml"):
        gallery = (tmp_path / "html" / "_generated" / "gallery.html").read_text(encoding="utf-8")
        assert example.name in gallery or example.stem in gallery, example.name
