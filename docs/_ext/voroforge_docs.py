"""Pages of the documentation site that are generated from the code and the examples.

When Sphinx loads this extension it writes, under ``docs/_generated/`` (not committed):
``gallery.md`` (one section per ``examples/*.toml``: its description, its picture from
``docs/gallery/`` and the file itself), ``guides.md`` (every other page of ``docs/``) and
``api.md`` (autosummary tables of the public names: ``voroforge._EXPORTS``, the design
functions, and each optional subsystem that exists in the tree).
"""

from __future__ import annotations

import importlib
import tomllib
from pathlib import Path

DOCS = Path(__file__).resolve().parents[1]
ROOT = DOCS.parent
OUT = DOCS / "_generated"

#: Design-layer entry points, documented beside the engine: the design-file functions, then
#: the steps a Python user composes (the Grasshopper components of grasshopper.md).
DESIGN_API = {
    "voroforge.design.build": ["build", "check_design"],
    "voroforge.design.compute": ["compute"],
    "voroforge.design.designfile": ["load"],
    "voroforge.design.populate": [
        "random",
        "grid",
        "hexgrid",
        "jittered",
        "poisson",
        "by_density",
        "along_curves",
        "crossing_edges",
        "from_file",
    ],
    "voroforge.design.attractors": [
        "PointAttractor",
        "CurveAttractor",
        "Field",
        "combine",
        "falloff",
        "remap",
        "power_weights",
    ],
    "voroforge.design.relax": ["relax"],
    "voroforge.design.cellops": [
        "inset",
        "web",
        "offset",
        "scale",
        "smooth",
        "fillet",
        "clean",
        "explode",
        "edges_to_lines",
        "frame",
        "openings",
        "by_area",
        "by_field",
        "random",
        "every_kth",
        "largest",
    ],
    "voroforge.design.recursive": ["subdivide", "Level", "count_by_area", "count_by_field"],
    "voroforge.design.fabrication": ["check", "Report", "Violation", "kerf", "pack_pieces"],
    "voroforge.design.stipple": ["stipple", "stipple_svg", "image_seeds"],
}
#: Files in and out, for machines and for GIS.
IO_API = {
    "voroforge.io": [
        "write",
        "write_svg",
        "write_layers",
        "write_dxf",
        "write_png",
        "write_geojson",
        "write_gif",
        "read_points",
        "read_boundary",
    ],
    "voroforge.io.readers": ["read_point_table", "read_svg", "read_svg_curves", "read_dxf"],
    "voroforge.io.plotter": ["layer_paths", "merge_lines", "order_paths", "travel", "Paths"],
}
#: Optional subsystems: documented when their package exists.
SUBSYSTEMS = {
    "voroforge.solid": "Printable solids",
    "voroforge.surface": "Voronoi on surfaces",
    "voroforge.scale": "Tiled diagrams on a cluster",
    "voroforge.studio": "The studio",
}


def _write(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists() or path.read_text(encoding="utf-8") != text:  # keep Sphinx's cache
        path.write_text(text, encoding="utf-8")


def _table(module: str, names: list[str]) -> list[str]:
    lines = ["```{eval-rst}", f".. currentmodule:: {module}", "", ".. autosummary::"]
    lines += ["   :toctree: api", "", *(f"   {name}" for name in names), "```", ""]
    return lines


def gallery_page() -> str:
    """The gallery: every example design with its picture and its file."""
    lines = [
        "# Gallery",
        "",
        "Every design in `examples/`, built by the test suite with `voroforge build`. Copy one",
        "as the start of your own (`voroforge build examples/NAME.toml -o out`).",
        "",
    ]
    for path in sorted((ROOT / "examples").glob("*.toml")):
        data = tomllib.loads(path.read_text(encoding="utf-8"))
        info = data.get("design", {})
        title = info.get("name", path.stem)
        lines += [f"## {title}", ""]
        if info.get("description"):
            lines += [info["description"].strip(), ""]
        image = DOCS / "gallery" / f"{path.stem}.png"
        if image.exists():
            lines += [f"![{title}](../gallery/{image.name})", ""]
        lines += [
            f"```{{literalinclude}} ../../examples/{path.name}",
            ":language: toml",
            "```",
            "",
        ]
    return "\n".join(lines)


def api_page() -> str:
    """The API reference: autosummary tables, one stub page per public name."""
    import voroforge

    lines = [
        "# API reference",
        "",
        "Everything below is importable as shown; `import voroforge as vf` loads nothing until",
        "a name is used. The arrays and their layout: [architecture](../architecture.md).",
        "",
        "## Engine: `voroforge`",
        "",
    ]
    lines += _table("voroforge", sorted(voroforge._EXPORTS))
    lines += ["## Design files and the design layer", ""]
    for module, names in DESIGN_API.items():
        lines += _table(module, names)
    lines += ["## Files in and out: `voroforge.io`", ""]
    for module, names in IO_API.items():
        lines += _table(module, names)
    for module, title in SUBSYSTEMS.items():
        package = ROOT / "src" / Path(*module.split("."))
        if not (package / "__init__.py").exists():
            continue
        names = sorted(getattr(importlib.import_module(module), "__all__", []))
        if names:
            lines += [f"## {title}: `{module}`", ""]
            lines += _table(module, names)
    return "\n".join(lines)


#: Pages with a fixed place in the site's navigation; every other ``docs/*.md`` is a guide.
FIXED_PAGES = {"index", "getting-started", "grasshopper", "design-files", "benchmarks"}


def guides_page() -> str:
    """A toctree of every guide page in ``docs/`` (one per subsystem), found by name."""
    pages = sorted(p.stem for p in DOCS.glob("*.md") if p.stem not in FIXED_PAGES)
    lines = ["# Guides", "", "One page per part of voroforge.", ""]
    lines += ["```{toctree}", ":maxdepth: 1", ""]
    return "\n".join([*lines, *(f"../{page}" for page in pages), "```", ""])


def _generate(app) -> None:  # noqa: ANN001 (Sphinx application)
    _write(OUT / "gallery.md", gallery_page())
    _write(OUT / "api.md", api_page())
    _write(OUT / "guides.md", guides_page())


def setup(app):  # noqa: ANN001, D103
    _generate(app)  # before autosummary looks for its tables (at builder-inited)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
