"""The design-file schema: pydantic models of every section, and errors that point at lines.

A design file is TOML (see ``docs/design-files.md``). :func:`load` reads it, applies
``--set``-style overrides, validates it against :class:`Design` and raises
:class:`DesignError` with one :class:`Issue` per problem: the dotted key, the line of that
key in the file and what was expected. Unknown keys are errors with a "did you mean" hint.
"""

from __future__ import annotations

import difflib
import re
import tomllib
import typing
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

__all__ = [
    "Attractor",
    "Boundary",
    "Cells",
    "Design",
    "DesignError",
    "Fabrication",
    "Gif",
    "Graded",
    "Issue",
    "Openings",
    "Output",
    "PRODUCTS",
    "Recursion",
    "Seeds",
    "apply_overrides",
    "key_lines",
    "load",
    "parse_value",
]

#: What an output layer can hold.
PRODUCTS = ("frame", "openings", "cells", "edges", "sites", "boundary")
Product = Literal["frame", "openings", "cells", "edges", "sites", "boundary"]

PositiveFloat = Annotated[float, Field(gt=0)]
NonNegFloat = Annotated[float, Field(ge=0)]
Point = tuple[float, float]
#: Random seeds: numpy's generators take non-negative integers only.
Seed = Annotated[int, Field(ge=0)]


def _need(field: str, message: str) -> ValueError:
    """A validator error that names a field of the model (see :func:`_issues`)."""
    return ValueError(f"@{field}@ {message}")


class _Model(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class Graded(_Model):
    """A number, or a range driven by the attractor field.

    ``inset = 1.5`` is a constant; ``inset = { near = 6, far = 1.5 }`` is 6 where the field is 1
    (at an attractor) and 1.5 where it is 0, linear in between.
    """

    value: float | None = None
    near: float | None = None
    far: float | None = None

    @model_validator(mode="before")
    @classmethod
    def _from_number(cls, data: Any) -> Any:
        if isinstance(data, int | float) and not isinstance(data, bool):
            return {"value": data}
        if not isinstance(data, dict | Graded):
            raise ValueError(f"expected a number or {{ near = ..., far = ... }}; got {_show(data)}")
        return data

    @model_validator(mode="after")
    def _complete(self) -> Graded:
        if self.value is None and (self.near is None or self.far is None):
            raise _need("near", "give a number, or both near and far, e.g. { near = 6, far = 1 }")
        if self.value is not None and (self.near is not None or self.far is not None):
            raise _need("value", "give a number or near/far, not both")
        return self

    @property
    def graded(self) -> bool:
        """True when the value follows the field."""
        return self.value is None

    def bounds(self) -> tuple[float, float]:
        """The smallest and largest value it can take."""
        if self.value is not None:
            return self.value, self.value
        return min(self.near, self.far), max(self.near, self.far)


class Info(_Model):
    """``[design]``: name, units and the master random seed."""

    name: str = "design"
    description: str = ""
    units: Literal["mm", "cm", "m", "in"] = "mm"
    seed: Seed = 0

    @model_validator(mode="after")
    def _name(self) -> Info:
        if re.search(r"[\\/]", self.name) or not self.name.strip():
            raise _need("name", "must be a file name without folders (it names the outputs)")
        return self


class Part(_Model):
    """One polygon of ``boundary.parts``."""

    points: Annotated[list[Point], Field(min_length=3)]
    holes: list[list[Point]] = []


class Boundary(_Model):
    """``[boundary]``: the outline the pattern fills."""

    shape: Literal["rectangle", "circle", "polygon", "polygons", "file"] = "rectangle"
    width: PositiveFloat | None = None
    height: PositiveFloat | None = None
    origin: Point = (0.0, 0.0)
    radius: PositiveFloat | None = None
    center: Point = (0.0, 0.0)
    segments: Annotated[int, Field(ge=8)] = 256
    points: list[Point] | None = None
    holes: list[list[Point]] = []
    parts: list[Part] | None = None
    file: str | None = None
    corner_radius: NonNegFloat = 0.0
    margin: NonNegFloat = 0.0

    @model_validator(mode="after")
    def _shape_fields(self) -> Boundary:
        need = {
            "rectangle": ("width", "height"),
            "circle": ("radius",),
            "polygon": ("points",),
            "polygons": ("parts",),
            "file": ("file",),
        }[self.shape]
        for name in need:
            if getattr(self, name) is None:
                raise _need(name, f"shape = {self.shape!r} needs {name}")
        return self


class Seeds(_Model):
    """``[seeds]``: where the Voronoi sites go."""

    method: Literal["random", "grid", "hexgrid", "jittered", "poisson", "density", "file"] = (
        "random"
    )
    count: Annotated[int, Field(gt=0)] | None = None
    spacing: PositiveFloat | None = None
    radius: PositiveFloat | None = None
    radius_max: PositiveFloat | None = None
    jitter: Annotated[float, Field(ge=0, le=1)] = 0.5
    angle: float = 0.0
    offset: Point = (0.0, 0.0)
    file: str | None = None
    seed: Seed | None = None
    use_field: bool = False

    @model_validator(mode="after")
    def _method_fields(self) -> Seeds:
        need = {
            "random": ("count",),
            "grid": ("spacing",),
            "hexgrid": ("spacing",),
            "jittered": ("spacing",),
            "poisson": ("radius",),
            "density": ("count",),
            "file": ("file",),
        }[self.method]
        for name in need:
            if getattr(self, name) is None:
                raise _need(name, f"method = {self.method!r} needs {name}")
        if (
            self.radius_max is not None
            and self.radius is not None
            and self.radius_max < self.radius
        ):
            raise _need("radius_max", "must be at least radius")
        return self


class Relax(_Model):
    """``[relax]``: Lloyd relaxation of the seeds."""

    iterations: Annotated[int, Field(ge=0, le=1000)] = 0
    tolerance: PositiveFloat | None = None


class Voronoi(_Model):
    """``[voronoi]``: engine options."""

    algorithm: Literal["delaunay", "fortune", "halfplane"] = "delaunay"
    periodic: bool = False
    power_radius: Graded | None = None

    @model_validator(mode="after")
    def _power(self) -> Voronoi:
        if self.power_radius is not None and self.periodic:
            raise _need("power_radius", "power (weighted) cells and periodic tiles do not combine")
        if self.power_radius is not None and self.power_radius.bounds()[0] < 0:
            raise _need("power_radius", "must be >= 0")
        return self


class Attractor(_Model):
    """``[[attractors]]``: a point or curve attractor."""

    type: Literal["point", "curve"] = "point"
    name: str | None = None
    points: Annotated[list[Point], Field(min_length=1)] | None = None
    path: str | None = None
    file: str | None = None
    radius: PositiveFloat
    strength: NonNegFloat = 1.0
    falloff: Literal["linear", "smoothstep", "gaussian", "inverse_power"] = "smoothstep"
    power: PositiveFloat = 2.0

    @model_validator(mode="after")
    def _curve(self) -> Attractor:
        given = [k for k in ("points", "path", "file") if getattr(self, k) is not None]
        if self.type == "point":
            if given != ["points"]:
                raise _need("points", "a point attractor needs points = [[x, y], ...] (only)")
        elif len(given) != 1:
            raise _need(
                "points", "a curve needs exactly one of points, path (SVG path data) or file"
            )
        elif self.points is not None and len(self.points) < 2:
            raise _need("points", "a curve needs at least two points")
        return self


class FieldSpec(_Model):
    """``[field]``: how the attractors combine."""

    combine: Literal["max", "min", "sum"] = "max"
    invert: bool = False


class Cells(_Model):
    """``[cells]``: operations on every cell, in the order inset, scale, smooth, fillet."""

    web: Graded | None = None
    inset: Graded | None = None
    join: Literal["mitre", "round"] = "mitre"
    scale: Graded = Graded(value=1.0)
    smooth: Annotated[int, Field(ge=0, le=8)] = 0
    fillet: Graded = Graded(value=0.0)
    min_area: NonNegFloat = 0.0
    min_size: NonNegFloat = 0.0

    @model_validator(mode="after")
    def _one_of(self) -> Cells:
        if self.web is not None and self.inset is not None:
            raise _need("inset", "give web (the full width between openings) or inset, not both")
        return self

    def inset_amount(self) -> Graded | None:
        """The inset per cell: ``web / 2`` or ``inset``."""
        if self.web is None:
            return self.inset
        w = self.web
        if w.value is not None:
            return Graded(value=w.value / 2.0)
        return Graded(near=w.near / 2.0, far=w.far / 2.0)


class Openings(_Model):
    """``[openings]``: which cells are cut out."""

    select: Literal["all", "area", "random", "every_kth", "largest", "field"] = "all"
    min_area: NonNegFloat | None = None
    max_area: NonNegFloat | None = None
    probability: Annotated[float, Field(ge=0, le=1)] | None = None
    k: Annotated[int, Field(gt=0)] | None = None
    start: Annotated[int, Field(ge=0)] = 0
    count: Annotated[int, Field(ge=0)] | None = None
    threshold: float | None = None
    invert: bool = False
    seed: Seed | None = None

    @model_validator(mode="after")
    def _select_fields(self) -> Openings:
        need = {
            "all": (),
            "area": (),
            "random": ("probability",),
            "every_kth": ("k",),
            "largest": ("count",),
            "field": ("threshold",),
        }[self.select]
        for name in need:
            if getattr(self, name) is None:
                raise _need(name, f"select = {self.select!r} needs {name}")
        if self.select == "area" and self.min_area is None and self.max_area is None:
            raise _need("min_area", "select = 'area' needs min_area or max_area")
        return self


class Recursion(_Model):
    """``[recursion]``: subdivide chosen cells again, level by level."""

    depth: Annotated[int, Field(ge=0, le=6)] = 0
    count: Graded = Graded(value=6.0)
    probability: Annotated[float, Field(ge=0, le=1)] = 1.0
    web: list[NonNegFloat] = []

    @model_validator(mode="before")
    @classmethod
    def _scalar_web(cls, data: Any) -> Any:
        if isinstance(data, dict) and isinstance(data.get("web"), int | float):
            return {**data, "web": [data["web"]]}
        return data


class Gif(_Model):
    """``[output.gif]``: an animated sweep of one key."""

    key: str
    values: Annotated[list[Any], Field(min_length=1)] | None = None
    start: float | None = None
    stop: float | None = None
    frames: Annotated[int, Field(ge=2, le=200)] = 12
    fps: Annotated[float, Field(gt=0, le=50)] = 8.0
    size: Annotated[int, Field(ge=32, le=2048)] = 400
    bounce: bool = True

    @model_validator(mode="after")
    def _range(self) -> Gif:
        if self.values is None and (self.start is None or self.stop is None):
            raise _need("values", "give values = [...] or start and stop")
        return self

    def sweep(self) -> list:
        """The values of the swept key, frame by frame (numbers, or any TOML values)."""
        if self.values is not None:
            vals = list(self.values)
        else:
            n = self.frames
            vals = [self.start + (self.stop - self.start) * i / (n - 1) for i in range(n)]
        if self.bounce and len(vals) > 2:
            vals = vals + vals[-2:0:-1]
        return vals


class Output(_Model):
    """``[output]``: files to write and what goes on each layer."""

    stem: str | None = None
    formats: list[Literal["svg", "dxf", "png", "geojson", "gif"]] = ["svg", "png"]
    layers: dict[str, Product | list[Product]] = {"CUT": "frame"}
    kerf: NonNegFloat = 0.0
    png_size: Annotated[int, Field(ge=32, le=8192)] = 1200
    png: Literal["cells", "layers"] = "cells"
    png_sites: bool = False
    geojson: Product = "cells"
    stroke_width: PositiveFloat | None = None  # None: 0.01 mm in the design's units
    arc_tolerance: PositiveFloat = 1e-6
    gif: Gif | None = None

    @model_validator(mode="after")
    def _gif(self) -> Output:
        if "gif" in self.formats and self.gif is None:
            raise _need("gif", "formats includes 'gif': add an [output.gif] table")
        if re.search(r"[\\/]", self.stem or ""):
            raise _need("stem", "must be a file name without folders")
        seen: dict[str, str] = {}
        for name in self.layers:
            key = name.strip().upper()  # SVG and DXF layers are upper-cased
            if not key or any(c in '<>/\\":;?*|=`' for c in key):
                raise _need(
                    "layers", f'{name!r} is not a valid layer name (DXF forbids <>/\\":;?*|=`)'
                )
            if key in seen:
                raise _need("layers", f"{seen[key]!r} and {name!r} are the same layer {key!r}")
            seen[key] = name
        return self


class Fabrication(_Model):
    """``[fabrication]``: limits checked by ``voroforge check`` (and written as a report)."""

    min_web: NonNegFloat | None = None
    min_opening: NonNegFloat | None = None
    tool_radius: NonNegFloat | None = None
    corner_tolerance: NonNegFloat = 0.02
    islands: bool = True
    report: bool = False


class Design(_Model):
    """A whole design file."""

    design: Info = Info()
    boundary: Boundary
    seeds: Seeds
    relax: Relax = Relax()
    voronoi: Voronoi = Voronoi()
    attractors: list[Attractor] = []
    field: FieldSpec = FieldSpec()
    cells: Cells = Cells()
    openings: Openings = Openings()
    recursion: Recursion = Recursion()
    output: Output = Output()
    fabrication: Fabrication = Fabrication()


# --- errors -------------------------------------------------------------------------------


@dataclass(frozen=True)
class Issue:
    """One problem in a design file.

    Attributes
    ----------
    key : str
        Dotted key path (``"seeds.count"``, ``"attractors.1.radius"``).
    line : int or None
        1-based line of the key in the file (``None`` for dicts and ``--set`` values).
    message : str
        What is wrong and what was expected.
    """

    key: str
    line: int | None
    message: str


class DesignError(ValueError):
    """A design file that cannot be used; ``issues`` lists each problem.

    ``str(error)`` is one line per issue, ``<file>:<line>: <key>: <message>``.
    """

    def __init__(self, issues: list[Issue], source: str | None = None):
        self.issues = list(issues)
        self.source = source
        super().__init__(self.format())

    def format(self) -> str:
        """One line per issue: ``file:line: key: message``."""
        lines = []
        for it in self.issues:
            where = self.source or "<design>"
            if it.line is not None:
                where += f":{it.line}"
            lines.append(f"{where}: {it.key or '(top level)'}: {it.message}")
        return "\n".join(lines)


_HEADER = re.compile(r"^\s*(\[\[?)\s*([^\]]+?)\s*\]\]?\s*(#.*)?$")
_KEY = re.compile(
    r"""^\s*((?:[A-Za-z0-9_\-]+|"[^"]*"|'[^']*')(?:\s*\.\s*(?:[A-Za-z0-9_\-]+|"[^"]*"|'[^']*'))*)\s*="""
)
_INLINE_KEY = re.compile(r"[{,]\s*([A-Za-z0-9_\-]+)\s*=")


def _split_key(text: str) -> tuple[str, ...]:
    parts = re.findall(r"""[A-Za-z0-9_\-]+|"[^"]*"|'[^']*'""", text)
    return tuple(p.strip("\"'") for p in parts)


def key_lines(text: str) -> dict[tuple, int]:
    """Map each key path of a TOML document to its 1-based line (tomllib has no positions).

    Tables ``[a.b]``, arrays of tables ``[[a]]`` (path ``("a", index)``), dotted keys and
    the keys of one-line inline tables are found; a path maps to the line where it starts.

    Parameters
    ----------
    text : str
        The TOML source.

    Returns
    -------
    dict of tuple to int
    """
    lines: dict[tuple, int] = {}
    arrays: dict[tuple, int] = {}
    current: tuple = ()
    depth = 0  # open brackets of a multi-line value
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        if depth == 0:
            head = _HEADER.match(line)
            if head and "=" not in line.split("]")[0]:
                path = _split_key(head.group(2))
                if head.group(1) == "[[":
                    index = arrays.get(path, -1) + 1
                    arrays[path] = index
                    current = (*path, index)
                else:
                    # [a.b] below [[a]] belongs to the last a.
                    for n in range(len(path), 0, -1):
                        if path[:n] in arrays:
                            path = (*path[:n], arrays[path[:n]], *path[n:])
                            break
                    current = path
                lines.setdefault(current, number)
                continue
            key = _KEY.match(line)
            if key:
                path = (*current, *_split_key(key.group(1)))
                lines.setdefault(path, number)
                rest = line[key.end() :]
                for inner in _INLINE_KEY.finditer(rest):
                    lines.setdefault((*path, inner.group(1)), number)
        depth += _bracket_balance(line)
        depth = max(depth, 0)
    return lines


def _bracket_balance(line: str) -> int:
    """Open minus closed brackets outside strings and comments (for multi-line arrays)."""
    balance, quote = 0, None
    for ch in line:
        if quote:
            if ch == quote:
                quote = None
            continue
        if ch in "\"'":
            quote = ch
        elif ch == "#":
            break
        elif ch in "[{":
            balance += 1
        elif ch in "]}":
            balance -= 1
    return balance


def _line_of(lines: dict[tuple, int], loc: tuple) -> int | None:
    for n in range(len(loc), 0, -1):
        if loc[:n] in lines:
            return lines[loc[:n]]
    return None


def _model_at(loc: tuple) -> type[BaseModel] | None:
    """The model class that holds the key at ``loc`` (for "did you mean" hints)."""
    model: Any = Design
    for part in loc:
        if isinstance(part, int):
            continue
        if not (isinstance(model, type) and issubclass(model, BaseModel)):
            return None
        info = model.model_fields.get(part)
        if info is None:
            return None
        model = _inner_model(info.annotation)
    return model if isinstance(model, type) and issubclass(model, BaseModel) else None


def _inner_model(annotation) -> Any:
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation
    for arg in typing.get_args(annotation):
        found = _inner_model(arg)
        if found is not None:
            return found
    return None


def _expected(error: dict) -> str:
    kind = error["type"]
    msg = error["msg"]
    if kind == "extra_forbidden":
        return "unknown key"
    if kind == "missing":
        return "required key is missing"
    got = error.get("input")
    if kind.startswith(
        ("float", "int", "bool", "string", "literal", "greater", "less", "list", "tuple", "too_")
    ):
        return f"{msg[0].lower()}{msg[1:]}; got {_show(got)}"
    return msg


def _show(value) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def _issues(exc: ValidationError, lines: dict[tuple, int]) -> list[Issue]:
    out = []
    for err in exc.errors():
        loc = tuple(p for p in err["loc"] if not (isinstance(p, str) and "[" in p))
        message = _expected(err)
        text = err["msg"]
        field = re.search(r"@(\w+)@ (.*)$", text)
        if field:  # a model validator naming its field
            loc = (*loc, field.group(1))
            message = field.group(2)
        elif text.startswith("Value error, "):
            message = text[len("Value error, ") :]
        if err["type"] == "extra_forbidden":
            model = _model_at(loc[:-1])
            if model is not None:
                close = difflib.get_close_matches(str(loc[-1]), list(model.model_fields), n=1)
                if close:
                    message += f"; did you mean {close[0]!r}?"
                else:
                    message += f"; known keys: {', '.join(model.model_fields)}"
        key = ".".join(str(p) for p in loc)
        if any(it.key == key for it in out):
            continue  # the other branches of a union say the same thing again
        out.append(Issue(key, _line_of(lines, loc), message))
    return out


# --- loading ------------------------------------------------------------------------------


def parse_value(text: str) -> Any:
    """Read a ``--set`` value as TOML (``500``, ``true``, ``[1, 2]``, ``"x"``); else a string."""
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text


def apply_overrides(data: dict, overrides: dict | None) -> dict:
    """Return a copy of ``data`` with each ``"dotted.key": value`` set (list items by index).

    Raises
    ------
    DesignError
        When a path runs through a value that is not a table or list.
    """
    import copy

    out = copy.deepcopy(data)
    for dotted, value in (overrides or {}).items():
        parts = [p for p in str(dotted).split(".") if p]
        if not parts:
            raise DesignError([Issue(str(dotted), None, "empty key in --set")], "--set")
        node: Any = out
        for i, part in enumerate(parts[:-1]):
            node = _step(node, part, dotted, parts[i + 1])
        last = parts[-1]
        if isinstance(value, str):
            value = parse_value(value)
        if isinstance(node, list):
            index = _index(node, last, dotted)
            node[index] = value
        elif isinstance(node, dict):
            node[last] = value
        else:
            raise DesignError([Issue(dotted, None, "not a table")], "--set")
    return out


def _index(node: list, part: str, dotted: str) -> int:
    if not part.lstrip("-").isdigit() or not -len(node) <= int(part) < len(node):
        raise DesignError(
            [Issue(dotted, None, f"{part!r} is not an index of a list of {len(node)}")], "--set"
        )
    return int(part)


def _step(node, part: str, dotted: str, following: str):
    if isinstance(node, list):
        return node[_index(node, part, dotted)]
    if not isinstance(node, dict):
        raise DesignError(
            [Issue(dotted, None, f"{part!r} is inside a value, not a table")], "--set"
        )
    if part not in node:
        node[part] = [] if following.isdigit() else {}
    return node[part]


def _error_line(text: str, error: str) -> int | None:
    """The line of a TOML error that tomllib places "at end of document" (a key given twice).

    The parser stops at the first error, so every prefix of the document that reaches the
    bad line fails with the same message: bisect for the shortest one.
    """
    lines = text.splitlines()

    def fails(n: int) -> bool:
        try:
            tomllib.loads("\n".join(lines[:n]))
        except tomllib.TOMLDecodeError as exc:
            return str(exc).split(" (at ")[0] == error.split(" (at ")[0]
        return False

    if not lines or not fails(len(lines)):
        return None
    lo, hi = 0, len(lines)  # fails(hi) holds, fails(lo) does not
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if fails(mid):
            hi = mid
        else:
            lo = mid
    return hi


def load(source, *, overrides: dict | None = None) -> tuple[Design, Path | None]:
    """Read and validate a design.

    Parameters
    ----------
    source : str, Path or dict
        A TOML file, or the already parsed mapping.
    overrides : dict, optional
        ``{"seeds.count": 500, "cells.web": "3"}``; strings are read as TOML values.

    Returns
    -------
    design : Design
        The validated design.
    base : Path or None
        The file's folder (relative paths in the design are resolved against it).

    Raises
    ------
    DesignError
        For TOML syntax errors and every schema problem, with key and line.
    FileNotFoundError
        For a missing file.
    """
    lines: dict[tuple, int] = {}
    name = None
    base = None
    if isinstance(source, dict):
        data = source
    else:
        path = Path(source)
        name = str(path)
        base = path.resolve().parent
        raw = path.read_bytes()
        try:
            text = raw.decode("utf-8-sig")  # a BOM (Windows Notepad) is not TOML's business
        except UnicodeDecodeError as exc:
            line = raw.count(b"\n", 0, exc.start) + 1
            message = f"not UTF-8 text (byte 0x{raw[exc.start]:02x}); save the file as UTF-8"
            raise DesignError([Issue("", line, message)], name) from None
        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            m = re.search(r"\(at line (\d+), column (\d+)\)", str(exc))
            line = int(m.group(1)) if m else _error_line(text, str(exc))
            message = re.sub(r"\s*\(at (line \d+, column \d+|end of document)\)", "", str(exc))
            raise DesignError([Issue("", line, f"TOML syntax: {message}")], name) from None
        lines = key_lines(text)
    data = apply_overrides(data, overrides)
    try:
        design = Design.model_validate(data)
    except ValidationError as exc:
        issues = _issues(exc, lines)
        if overrides:
            touched = {str(k) for k in overrides}
            issues = [
                Issue(
                    i.key,
                    None if i.key in touched else i.line,
                    i.message + (" (from --set)" if i.key in touched else ""),
                )
                for i in issues
            ]
        raise DesignError(issues, name) from None
    return design, base
