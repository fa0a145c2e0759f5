"""The design-file schema: pydantic models of every section of a design file.

A design file is TOML (see ``docs/design-files.md``); :class:`Design` is the whole file and
each section is a model of its own. Reading a file, overrides and the error reports that
point at a key's line live beside this in :mod:`voroforge.design.designfile`.

Model validators name the field they complain about (``_need``), so a report can point at
that key's line.
"""

from __future__ import annotations

import re
from typing import Annotated, Any, ClassVar, Literal

from pydantic import (
    AfterValidator,
    BaseModel,
    ConfigDict,
    Field,
    model_validator,
)

from .. import config
from ..solid.schema import SolidSection, fill_2d
from ..studio.animation import AnimationSection
from ..surface.schema import SurfaceSection
from .numbers import Flag, Num, Whole, short_repr

__all__ = [
    "Attractor",
    "Boundary",
    "Cells",
    "Design",
    "Fabrication",
    "Gif",
    "Graded",
    "Openings",
    "Output",
    "PRODUCTS",
    "Recursion",
    "Seeds",
    "short_repr",
]

#: What an output layer can hold.
PRODUCTS = ("frame", "openings", "cells", "edges", "sites", "boundary", "labels")
Product = Literal["frame", "openings", "cells", "edges", "sites", "boundary", "labels", "curves"]


PositiveFloat = Annotated[Num, Field(gt=0)]
NonNegFloat = Annotated[Num, Field(ge=0)]
#: A boundary's width, height or radius: at most 1e100, so areas and squared distances stay
#: finite (width = 1e308 had reached the seeding as NaN)
_MAX_SIZE = 1e100


def _size(v: float) -> float:
    if v > _MAX_SIZE:
        raise ValueError(f"must be at most {_MAX_SIZE:g}")
    if v < 1.0 / _MAX_SIZE:  # 1e-200 x 1e-200 had an area of 0 ("seeds: ... zero area")
        raise ValueError(f"must be at least {1.0 / _MAX_SIZE:g}")
    return v


Size = Annotated[Num, Field(gt=0), AfterValidator(_size)]


def _coordinate(v: float) -> float:
    if abs(v) > _MAX_SIZE:  # a polygon at 1e155 overflowed its area to NaN in the seeding
        raise ValueError(f"must be at most {_MAX_SIZE:g} in magnitude")
    return v


def _path_data(d: str | None) -> None:
    """SVG path data that parses and draws finite points, checked by the model holding it.

    (A model validator, not a field type: a field's error had the section's cross-field
    pass report the path as missing too.)
    """
    if d is None:
        return
    from ..io.readers.svg import path_lines

    try:
        lines = path_lines(d)
    except ValueError as exc:
        raise _need("path", f"SVG path data: {exc}") from None
    if not lines:
        raise _need("path", "the SVG path data draws nothing")
    if any(not (abs(v) <= _MAX_SIZE) for x in lines for v in x.ravel().tolist()):
        raise _need("path", f"SVG path data: coordinates must be finite, at most {_MAX_SIZE:g}")


#: A coordinate: finite and at most 1e100 in magnitude.
Coordinate = Annotated[Num, AfterValidator(_coordinate)]
Point = tuple[Coordinate, Coordinate]


#: Random seeds: numpy's generators take non-negative integers only.
Seed = Annotated[Whole, Field(ge=0)]


def _need(field: str, message: str) -> ValueError:
    """A validator error that names a field of the model (``designfile`` reads the name back)."""
    return ValueError(f"@{field}@ {message}")


class _Model(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


#: ``USED_BY`` of a model: the keys that only some choices of another key (its
#: discriminator: ``shape``, ``method``, ...) read, as ``key -> (discriminator, choices)``.
#: :func:`voroforge.design.designfile.unused_keys` warns about such a key given (other than
#: its default) with a choice that does not read it: ``points`` on a rectangle is ignored.
UsedBy = ClassVar[dict[str, tuple[str, tuple[str, ...]]]]
#: ``USED_WHEN``: the same for a condition on another key's value, as
#: ``key -> (other key, whether its value reads key, when it is read)``.
UsedWhen = ClassVar[dict[str, tuple[str, Any, str]]]


class Graded(_Model):
    """A number, or a range driven by the attractor field.

    ``inset = 1.5`` is a constant; ``inset = { near = 6, far = 1.5 }`` is 6 where the field is 1
    (at an attractor) and 1.5 where it is 0, linear in between.
    """

    value: Num | None = None
    near: Num | None = None
    far: Num | None = None

    @model_validator(mode="before")
    @classmethod
    def _from_number(cls, data: Any) -> Any:
        if isinstance(data, int | float) and not isinstance(data, bool):
            return {"value": data}
        if not isinstance(data, dict | Graded):
            raise ValueError(
                f"expected a number or {{ near = ..., far = ... }}; got {short_repr(data)}"
            )
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


def _at_least_zero(value: Graded) -> Graded:
    lo = value.bounds()[0]
    if lo < 0:
        raise ValueError("must be >= 0" if not value.graded else "near and far must be >= 0")
    return value


def _probability(value: Graded) -> Graded:
    lo, hi = value.bounds()
    if lo < 0 or hi > 1:
        raise ValueError("must be between 0 and 1")
    return value


def _scale_bound(value: Graded) -> Graded:
    if value.bounds()[1] > config.DESIGN_MAX_CELL_SCALE:
        top = config.DESIGN_MAX_CELL_SCALE
        raise ValueError(f"must be at most {top:g} (1 keeps each cell's size)")
    return value


#: A graded key that cannot go below 0 (web, inset, fillet, scale, power_radius): checked
#: here, with the other values, so that ``voroforge check`` lists it with every other problem
#: (it was checked while computing, and a schema error elsewhere hid it).
NonNegGraded = Annotated[Graded, AfterValidator(_at_least_zero)]
#: A graded chance, 0..1.
ChanceGraded = Annotated[Graded, AfterValidator(_probability)]


class Info(_Model):
    """``[design]``: name, units and the master random seed."""

    name: str = "design"
    description: str = ""
    units: Literal["mm", "cm", "m", "in"] = "mm"
    seed: Seed = 0

    @model_validator(mode="after")
    def _name(self) -> Info:
        if re.search(r"[\\/\x00-\x1f\x7f]", self.name) or not self.name.strip():
            raise _need(
                "name",
                "must be a file name without folders or control characters (it names the outputs)",
            )
        return self


class Part(_Model):
    """One polygon of ``boundary.parts``."""

    points: Annotated[list[Point], Field(min_length=3)]
    holes: list[list[Point]] = []


class Boundary(_Model):
    """``[boundary]``: the outline the pattern fills."""

    shape: Literal["rectangle", "circle", "polygon", "polygons", "file"] = "rectangle"
    width: Size | None = None
    height: Size | None = None
    origin: Point = (0.0, 0.0)
    radius: Size | None = None
    center: Point = (0.0, 0.0)
    segments: Annotated[Whole, Field(ge=8, le=config.BOUNDARY_MAX_SEGMENTS)] = 256
    points: list[Point] | None = None
    holes: list[list[Point]] = []
    parts: list[Part] | None = None
    file: str | None = None
    corner_radius: NonNegFloat = 0.0
    margin: NonNegFloat = 0.0
    # an SVG file's open subpaths are errors unless their ends are at most this far apart
    close_tolerance: NonNegFloat = 0.0

    USED_BY: UsedBy = {
        "width": ("shape", ("rectangle",)),
        "height": ("shape", ("rectangle",)),
        "origin": ("shape", ("rectangle",)),
        "radius": ("shape", ("circle",)),
        "center": ("shape", ("circle",)),
        "segments": ("shape", ("circle",)),
        "points": ("shape", ("polygon",)),
        "holes": ("shape", ("polygon",)),
        "parts": ("shape", ("polygons",)),
        "file": ("shape", ("file",)),
        "close_tolerance": ("shape", ("file",)),
    }

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

    method: Literal[
        "random", "grid", "hexgrid", "jittered", "poisson", "density", "file", "image", "curves"
    ] = "random"
    count: Annotated[Whole, Field(gt=0)] | None = None
    spacing: PositiveFloat | None = None
    radius: PositiveFloat | None = None
    radius_max: PositiveFloat | None = None
    jitter: Annotated[Num, Field(ge=0, le=1)] = 0.5
    angle: Num = 0.0
    offset: Point = (0.0, 0.0)
    file: str | None = None
    seed: Seed | None = None
    use_field: Flag = False
    # method = "curves": the curves the cell edges trace (polylines, SVG path data or file)
    curves: list[Annotated[list[Point], Field(min_length=2)]] | None = None
    path: str | None = None
    distance: PositiveFloat | None = None  # of each site from its curve (spacing / 2)

    USED_BY: UsedBy = {
        "count": ("method", ("random", "density", "image")),
        "spacing": ("method", ("grid", "hexgrid", "jittered", "curves")),
        "radius": ("method", ("poisson", "curves")),
        "radius_max": ("method", ("poisson",)),
        "jitter": ("method", ("jittered",)),
        "angle": ("method", ("grid", "hexgrid", "jittered")),
        "offset": ("method", ("grid", "hexgrid", "jittered")),
        "file": ("method", ("file", "image", "curves")),
        "seed": ("method", ("random", "jittered", "poisson", "density", "curves", "image")),
        "use_field": ("method", ("poisson",)),
        "curves": ("method", ("curves",)),
        "path": ("method", ("curves",)),
        "distance": ("method", ("curves",)),
    }

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
            "image": ("file", "count"),  # dots by an image's darkness (design/stipple.py)
            "curves": ("spacing",),  # pairs mirrored along curves (populate.along_curves)
        }[self.method]
        for name in need:
            if getattr(self, name) is None:
                raise _need(name, f"method = {self.method!r} needs {name}")
        if self.method == "curves":
            given = [k for k in ("curves", "path", "file") if getattr(self, k) is not None]
            if len(given) != 1:
                raise _need(
                    "curves",
                    "method = 'curves' needs exactly one of curves = [[[x, y], ...], ...], "
                    "path (SVG path data) or file (SVG or GeoJSON lines)",
                )
            _path_data(self.path)
        if (
            self.radius_max is not None
            and self.radius is not None
            and self.radius_max < self.radius
        ):
            raise _need("radius_max", "must be at least radius")
        return self


class Relax(_Model):
    """``[relax]``: Lloyd relaxation of the seeds."""

    iterations: Annotated[Whole, Field(ge=0, le=1000)] = 0
    tolerance: PositiveFloat | None = None


class Voronoi(_Model):
    """``[voronoi]``: engine options."""

    algorithm: Literal["delaunay", "fortune", "halfplane"] = "delaunay"
    periodic: Flag = False
    power_radius: NonNegGraded | None = None

    # power cells are cut from the box (vf.power): the algorithm picks the Voronoi builder
    USED_WHEN: UsedWhen = {"algorithm": ("power_radius", lambda r: r is None, "without it")}

    @model_validator(mode="after")
    def _power(self) -> Voronoi:
        if self.power_radius is not None and self.periodic:
            raise _need("power_radius", "power (weighted) cells and periodic tiles do not combine")
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

    USED_BY: UsedBy = {"power": ("falloff", ("inverse_power",))}

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
        _path_data(self.path)
        return self


class FieldSpec(_Model):
    """``[field]``: how the attractors combine."""

    combine: Literal["max", "min", "sum"] = "max"
    invert: Flag = False


class Cells(_Model):
    """``[cells]``: operations on every cell, in the order inset, scale, smooth, fillet."""

    web: NonNegGraded | None = None
    inset: NonNegGraded | None = None
    join: Literal["mitre", "round"] = "mitre"
    scale: Annotated[NonNegGraded, AfterValidator(_scale_bound)] = Graded(value=1.0)
    smooth: Annotated[Whole, Field(ge=0, le=8)] = 0
    fillet: NonNegGraded = Graded(value=0.0)
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
    probability: Annotated[Num, Field(ge=0, le=1)] | None = None
    k: Annotated[Whole, Field(gt=0)] | None = None
    start: Annotated[Whole, Field(ge=0)] = 0
    count: Annotated[Whole, Field(ge=0)] | None = None
    threshold: Num | None = None
    invert: Flag = False
    seed: Seed | None = None

    USED_BY: UsedBy = {
        "min_area": ("select", ("area",)),
        "max_area": ("select", ("area",)),
        "probability": ("select", ("random",)),
        "seed": ("select", ("random",)),
        "k": ("select", ("every_kth",)),
        "start": ("select", ("every_kth",)),
        "count": ("select", ("largest",)),
        "threshold": ("select", ("field",)),
    }

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
        if self.select == "area" and None not in (self.min_area, self.max_area):
            if self.min_area > self.max_area:  # an empty range: no opening, no warning
                raise _need("max_area", f"must be at least min_area ({self.min_area:g})")
        return self


class Recursion(_Model):
    """``[recursion]``: subdivide chosen cells again, level by level."""

    depth: Annotated[Whole, Field(ge=0, le=6)] = 0
    count: Graded = Graded(value=6.0)
    # a number, or { near = 1, far = 0.5 }: the chance that a cell is subdivided, by the field
    probability: ChanceGraded = Graded(value=1.0)
    web: list[NonNegFloat] = []

    USED_WHEN: UsedWhen = {
        k: ("depth", lambda depth: depth > 0, "with depth >= 1")
        for k in ("count", "probability", "web")
    }

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
    start: Num | None = None
    stop: Num | None = None
    frames: Annotated[Whole, Field(ge=2, le=200)] = 12
    fps: Annotated[Num, Field(gt=0, le=50)] = 8.0
    size: Annotated[Whole, Field(ge=32, le=2048)] = 400
    bounce: Flag = True

    USED_WHEN: UsedWhen = {
        k: ("values", lambda values: values is None, "without values") for k in ("start", "stop")
    }

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
    formats: list[Literal["svg", "dxf", "png", "geojson", "gif", "parquet"]] = ["svg", "png"]
    layers: dict[str, Product | list[Product]] = {"CUT": "frame"}
    kerf: NonNegFloat = 0.0
    png_size: Annotated[Whole, Field(ge=32, le=8192)] = 1200
    png: Literal["cells", "layers"] = "cells"
    png_sites: Flag = False
    geojson: Product = "cells"
    stroke_width: PositiveFloat | None = None  # None: 0.01 mm in the design's units
    arc_tolerance: PositiveFloat = config.ARC_TOLERANCE
    gif: Gif | None = None
    # paths for the machine (voroforge.io.plotter): pen-up travel order, merged strokes
    order: Literal["travel", "file"] = "travel"
    merge_lines: Flag = True
    site_marks: Literal["circle", "cross"] = "circle"
    # cell numbers as single-stroke text (voroforge.io.labels) and cut-apart pieces
    label_height: PositiveFloat | None = None
    pieces: Flag = False
    # "source": the SVG page is the boundary file's page (same size and origin)
    page: Literal["boundary", "source"] = "boundary"

    # the [output.gif] sweep is made only for a "gif" in formats (build, check)
    # (page: the SVG's page; the surface's cut sheets have their own)
    USED_BY: UsedBy = {"gif": ("formats", ("gif",)), "page": ("formats", ("svg",))}

    @model_validator(mode="after")
    def _gif(self) -> Output:
        if not self.formats:
            raise _need(
                "formats", "is empty: list at least one of svg, dxf, png, geojson, gif, parquet"
            )
        if "gif" in self.formats and self.gif is None:
            raise _need("gif", "formats includes 'gif': add an [output.gif] table")
        if re.search(r"[\\/\x00-\x1f\x7f]", self.stem or ""):
            raise _need("stem", "must be a file name without folders or control characters")
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
    corner_tolerance: NonNegFloat | None = None  # FAB_CORNER_TOLERANCE_MM in design.units
    islands: Flag = True
    report: Flag = False

    # the inside-corner check runs only with a tool radius (fabrication.check)
    USED_WHEN: UsedWhen = {
        "corner_tolerance": ("tool_radius", lambda r: r is not None and r > 0, "with it > 0")
    }


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
    animation: AnimationSection | None = None  # voroforge.studio.animation: keyframes to play
    surface: SurfaceSection | None = None  # voroforge.surface: the design on a curved surface
    solid: SolidSection | None = None  # voroforge.solid: a printable 3D product

    @model_validator(mode="before")
    @classmethod
    def _solid_2d(cls, data):
        return fill_2d(data)  # 3D [solid] kinds need no [boundary]/[seeds]
