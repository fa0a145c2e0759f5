"""The studio: live editing of a design in the browser, and the same editor in Jupyter.

``voroforge studio DESIGN.toml`` (or :func:`serve`) runs a local page where seeds are
dragged, added (click) and removed (shift-click), attractors and curve handles are moved,
every numeric parameter has a slider generated from the design schema, and the fabrication
check runs live. :func:`widget` is the same editor as a Jupyter widget (anywidget).
Everything heavy (starlette, uvicorn, anywidget) is imported only when used.

Examples
--------
>>> from voroforge.studio import Session
>>> s = Session({"boundary": {"shape": "rectangle", "width": 100, "height": 60},
...              "seeds": {"method": "random", "count": 40}})
>>> s.apply({"op": "remove", "i": 0}).kind, len(s.result.sites)
('update', 39)
"""

from __future__ import annotations

from typing import TYPE_CHECKING

__all__ = ["Session", "create_app", "serve", "widget"]

_LAZY = {
    "Session": ".session",
    "create_app": ".server",
    "serve": ".server",
    "widget": ".widget",
}

if TYPE_CHECKING:
    from .server import create_app, serve
    from .session import Session
    from .widget import widget


def __getattr__(name: str):
    if name in _LAZY:
        import importlib

        value = getattr(importlib.import_module(_LAZY[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
