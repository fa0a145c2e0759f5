"""The studio's inputs, generated from the design schema: one per numeric parameter.

:func:`controls` walks :class:`~voroforge.design.schema.Design` and the current design and
lists every number the design file can hold (counts, radii, webs, fillets, attractor
radius and strength, recursion depth, fabrication limits, ...) with its bounds from the
schema (``gt``/``ge``/``lt``/``le``) and a slider range around the current value. The page
draws a slider and a number box for each; a graded value (``{ near, far }``) gets two.
"""

from __future__ import annotations

import math
import sys
import types
import typing

import annotated_types as at
from pydantic import BaseModel

from ..design.schema import Design, Graded

__all__ = ["controls"]

#: Sections whose numbers are drawing or file options rather than the pattern's.
_SKIP = {("output", "gif"), ("output", "stroke_width"), ("output", "arc_tolerance")}

#: Bounds of graded values (``{ near, far }`` or a number), which the schema checks in model
#: validators rather than field metadata (schema.Recursion._probability, Voronoi._power);
#: the others are >= 0 by the slider's own 0 end. (Constant for the lead to move to config.)
_GRADED_BOUNDS = {"recursion.probability": {"min": 0, "max": 1}, "voronoi.power_radius": {"min": 0}}


def _kind(annotation) -> tuple[str | None, list]:
    """('int' | 'float' | 'graded' | None, constraint objects) of a field annotation."""
    found: list = []
    kind = None

    def walk(a):
        nonlocal kind
        origin = typing.get_origin(a)
        if origin is typing.Annotated:
            base, *meta = typing.get_args(a)
            for m in meta:
                found.extend(getattr(m, "metadata", [m]))
            walk(base)
        elif origin in (typing.Union, types.UnionType):
            for arg in typing.get_args(a):
                if arg is not type(None):
                    walk(arg)
        elif a is Graded:
            kind = "graded"
        elif a is bool:
            return
        elif a is int and kind is None:
            kind = "int"
        elif a is float and kind in (None, "int"):
            kind = "float"

    walk(annotation)
    return kind, found


def _bounds(meta: list, kind: str) -> dict:
    out: dict = {}
    for m in meta:
        if isinstance(m, at.Gt):
            out["min"], out["exclusive_min"] = m.gt, True
        elif isinstance(m, at.Ge):
            out["min"] = m.ge
        elif isinstance(m, at.Lt):
            out["max"], out["exclusive_max"] = m.lt, True
        elif isinstance(m, at.Le):
            out["max"] = m.le
    return out


def _range(value, bounds: dict, kind: str) -> tuple[float, float]:
    """A slider range: the schema's bounds where given, else around the current value."""
    v = abs(float(value)) if value is not None else 1.0
    lo = bounds.get("min", 0.0 if v >= 0 else -4 * v)
    hi = bounds.get("max", max(4.0 * v, float(lo) + (10 if kind == "int" else 1.0)))
    if kind == "int":
        hi = min(hi, max(4 * v, float(lo) + 10))
    return float(lo), float(hi)


def _entry(key: str, label: str, kind: str, meta: list, value) -> dict:
    bounds = _bounds(meta, kind)
    if kind == "graded":
        bounds = dict(_GRADED_BOUNDS.get(key, {}))
        nums = [value.value] if value.value is not None else [value.near, value.far]
        biggest = max(abs(float(n)) for n in nums)
        lo, hi = 0.0, max(4.0 * biggest, 1.0)
        # clipped to the schema's bounds: every position of the slider is a valid value
        lo, hi = max(lo, bounds.get("min", lo)), min(hi, bounds.get("max", hi))
        current = value.value if value.value is not None else {"near": value.near, "far": value.far}
    else:
        current = value
        lo, hi = _range(value, bounds, kind)
    # a huge value (the schema takes any finite float) must not make the range infinite:
    # JSON has no Infinity, and the slider's step is a power of ten of the span
    lo, hi = max(float(lo), -_FLOAT_MAX), min(float(hi), _FLOAT_MAX)
    step = 1 if kind == "int" else _step(hi - lo)
    # an exclusive bound (gt/lt) is not a value: the slider's end moves in by one step (or
    # to the current value, which is valid, where that is nearer the bound)
    if bounds.get("exclusive_min") and lo <= bounds["min"]:
        lo = min(lo + step, float(current)) if current > bounds["min"] else lo + step
    if bounds.get("exclusive_max") and hi >= bounds["max"]:
        hi = max(hi - step, float(current)) if current < bounds["max"] else hi - step
    return {
        "key": key,
        "label": label,
        "kind": kind,
        "value": current,
        "min": lo,
        "max": hi,
        "step": step,
        "bounds": bounds,
    }


_FLOAT_MAX = sys.float_info.max


def _step(span: float) -> float:
    if not span > 0:
        return 0.01
    # hi - lo of two finite bounds can still overflow to inf
    return 10.0 ** math.floor(math.log10(min(span, _FLOAT_MAX) / 200.0))


def _section(prefix: str, model: BaseModel, out: list[dict]) -> None:
    for name, info in type(model).model_fields.items():
        if (prefix.split(".")[0], name) in _SKIP:
            continue
        value = getattr(model, name)
        key = f"{prefix}.{name}"
        if isinstance(value, BaseModel) and not isinstance(value, Graded):
            _section(key, value, out)
            continue
        kind, meta = _kind(info.annotation)
        meta = [*info.metadata, *meta]
        if kind is None or value is None or isinstance(value, bool):
            continue
        out.append(_entry(key, key, kind, meta, value))


def controls(design: Design) -> list[dict]:
    """Every numeric parameter of ``design``, in file order, as input descriptions.

    Parameters
    ----------
    design : Design
        The validated design (defaults included).

    Returns
    -------
    list of dict
        ``key`` (dotted, as ``--set`` takes it), ``kind`` (``"int"``, ``"float"`` or
        ``"graded"``), ``value`` (a number, or ``{"near", "far"}``), slider ``min``/``max``/
        ``step``, and the schema's ``bounds``. Unset optional values are left out.
    """
    out: list[dict] = []
    for name in Design.model_fields:
        value = getattr(design, name)
        if isinstance(value, list):
            for i, item in enumerate(value):
                if isinstance(item, BaseModel):
                    _section(f"{name}.{i}", item, out)
        elif isinstance(value, BaseModel):
            _section(name, value, out)
    return out
