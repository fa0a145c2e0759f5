"""Sphinx configuration of the voroforge documentation site (``make docs``).

Sphinx with the PyData theme, numpydoc and MyST is what NumPy, SciPy, pandas and
scikit-image use: the API reference comes from the same numpydoc docstrings that ``help()``
shows, and the guides stay Markdown files that read well on GitHub too. The gallery and the
API page are generated at build time (``_ext/voroforge_docs.py``), so a new example or a new
public name appears without editing a list.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))
sys.path.insert(0, str(HERE.parent / "src"))

import voroforge  # noqa: E402

project = "voroforge"
author = "the voroforge developers"
copyright = "2026, the voroforge developers"  # noqa: A001
release = voroforge.__version__
version = release

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "numpydoc",
    "voroforge_docs",
]

source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
root_doc = "index"
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store", "**/README.md"]
myst_heading_anchors = 4
myst_enable_extensions = ["colon_fence"]
# The pages link to repository files outside docs/ (examples/, benchmarks/README.md) so that
# they read well on GitHub too; MyST cannot resolve those. tests/test_docs.py checks every
# relative link of every page instead, and fails on a broken one.
suppress_warnings = ["myst.xref_missing"]

autosummary_generate = True
autodoc_typehints = "none"  # numpydoc's Parameters sections carry the types
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False

html_theme = "pydata_sphinx_theme"
html_title = f"voroforge {release}"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "footer_start": ["copyright"],
    "footer_end": [],
}
html_static_path: list[str] = []
html_show_sourcelink = False
