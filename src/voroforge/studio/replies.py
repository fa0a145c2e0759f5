"""What the studio session answers a page message, and the checks of a message's values.

:class:`Reply` is what :meth:`voroforge.studio.session.Session.apply` returns for every
message (the web server and the Jupyter widget send it on); :data:`EXPORTS` the formats the
page can export. A message's values are checked here before they reach the design
(:func:`number`, :func:`plain`): a bad one raises :class:`BadMessage`, which the session
answers as an ``"error"`` reply (:func:`error_reply` does the same for a design's errors).
:func:`changed_cells` names the cells a new result redraws.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..design.designfile import DesignError

__all__ = [
    "EXPORTS",
    "BadMessage",
    "Reply",
    "changed_cells",
    "error_reply",
    "number",
    "plain",
]

#: What the page can export, and the MIME type of each.
EXPORTS = {
    "svg": "image/svg+xml",
    "dxf": "application/dxf",
    "png": "image/png",
    "geojson": "application/geo+json",
}


@dataclass
class Reply:
    """What :meth:`~voroforge.studio.session.Session.apply` answers.

    ``kind`` is ``"update"`` (new geometry: ``changed`` cell indices or None for all),
    ``"error"`` (``issues``: key and message each; the last good geometry stays),
    ``"confirm"`` (a save would overwrite ``files``), ``"saved"``, ``"file"`` (an export:
    ``name``, ``mime``, ``data``) or ``"info"``.
    """

    kind: str
    issues: list[dict] = field(default_factory=list)
    changed: np.ndarray | None = None
    name: str = ""
    mime: str = ""
    data: bytes = b""
    files: list[str] = field(default_factory=list)
    note: str = ""


class BadMessage(Exception):
    """A message the session refuses: ``key`` (the design key it concerns, or "") and why."""

    def __init__(self, key: str, message: str):
        super().__init__(message)
        self.key, self.message = key, message


def shown(value, most: int = 20) -> str:
    """``value`` for an error message: as sent, or visibly shortened (never another number).

    ``str(i)[:20]`` of ``10**30`` read "10000000000000000000", a value nobody sent.
    """
    if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 60:
        digits = int(value.bit_length() * math.log10(2)) + 1  # str() of 5,000 digits raises
        return f"an integer of about {digits} digits"
    text = repr(value)
    return text if len(text) <= most else text[:most] + "..."


def error_reply(exc: DesignError) -> Reply:
    """The ``"error"`` reply of a design's errors, one issue each."""
    return Reply("error", issues=[{"key": it.key, "message": it.message} for it in exc.issues])


def number(value, name: str) -> float:
    """``value`` as a finite float of magnitude at most 1e15 (``name`` for the error)."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise BadMessage("", f"{name} must be a number")
    v = float(value)
    if not math.isfinite(v):
        raise BadMessage("", f"{name} must be a finite number")
    if abs(v) > 1e15:
        raise BadMessage("", f"{name} must be at most 1e15 in magnitude; got {v:g}")
    return v


def plain(value, key: str, depth: int = 0):
    """A value a design file can hold (numbers, strings, booleans, lists, small tables)."""
    if depth > 4:
        raise BadMessage(key, "value nested too deeply")
    if isinstance(value, bool | str):
        if isinstance(value, str) and len(value) > 1000:
            raise BadMessage(key, "text value too long")
        return value
    if isinstance(value, int) and not -(2**63) <= value < 2**63:
        # a design file could not hold it: TOML's integers are 64-bit
        raise BadMessage(key, "integer outside the 64-bit range a design file holds")
    if isinstance(value, int | float):
        if not math.isfinite(value):
            raise BadMessage(key, "must be a finite number")
        return value
    if isinstance(value, list) and len(value) <= 10000:
        return [plain(v, key, depth + 1) for v in value]
    if isinstance(value, dict) and len(value) <= 50:
        return {str(k): plain(v, key, depth + 1) for k, v in value.items()}
    raise BadMessage(key, "expected a number, text, true/false, a list or a table")


def changed_cells(previous, result) -> np.ndarray | None:
    """Indices of the cells that differ from ``previous`` (None: redraw everything).

    ``compute``'s reuse compares cell ``i`` with the previous cell ``i``, so with another cell
    count (a count slider: the random stream keeps its first seeds) the cells past the old
    count are new and the others changed only where ``redone`` or their flag says.
    """
    redo = result.extra.get("redone")
    if previous is None or redo is None:
        return None
    n0, n1 = len(previous.raw), len(result.raw)
    if len(redo) >= n1:  # every cell redone (new seeds): all of them, without the unions
        return np.arange(n1, dtype=np.int32)
    m = min(n0, n1)
    flipped = np.flatnonzero(previous.mask[:m] != result.mask[:m])
    out = np.union1d(np.union1d(redo, flipped), np.arange(n0, n1))
    return out[out < n1].astype(np.int32)
