"""``[surface]``: a design built onto a curved surface (the design-file section's model).

Two modes: ``"morph"`` lays the 2D design (boundary, seeds, cells, openings) into the
surface's UV square (Grasshopper's Surface Morph); ``"voronoi"`` grows the cells on the surface
itself (restricted Voronoi, relaxed to a surface CVT: ``seeds.count`` cells, ``relax.iterations``
steps, unless ``count``/``relax`` are given here). Any surface of :mod:`voroforge.surface`:
the analytic shapes, a height field (``heights`` inline or a ``file``), a parametric one
(``x``, ``y``, ``z`` expressions in ``u, v``, see :mod:`voroforge.surface.expr`) or a mesh.
"""

from __future__ import annotations

from typing import Annotated, ClassVar, Literal

from pydantic import AfterValidator, BaseModel, ConfigDict, Field, StrictBool, model_validator

from ..config import SURFACE_COORD_RANGE, SURFACE_EXPR_SAMPLES
from ..design.numbers import Num, Whole

__all__ = ["SurfaceSection"]


_BIG = SURFACE_COORD_RANGE[1]
# lengths and coordinates: finite (the model forbids inf/nan) and within the surfaces' range


def _in_range(x: float) -> float:
    if abs(x) > _BIG:
        raise ValueError(
            f"{x:g} is past the surfaces' coordinate range (magnitude up to {_BIG:g}; scale "
            "the design by a power of ten)"
        )
    return x


# numbers written as numbers (``"5"`` and ``true`` are refused with their key)
Positive = Annotated[Num, Field(gt=0), AfterValidator(_in_range)]
Coord = Annotated[Num, AfterValidator(_in_range)]
Fraction = Annotated[Num, Field(gt=0, lt=1)]


class SurfaceSection(BaseModel):
    """``[surface]``: the surface, how the pattern gets onto it, and the panel products."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

    shape: Literal[
        "cylinder", "sphere_patch", "sphere", "saddle", "torus", "heightfield", "parametric", "mesh"
    ]
    mode: Literal["morph", "voronoi"] = "morph"
    radius: Positive | None = None
    height: Positive | None = None
    width: Positive | None = None
    depth: Positive | None = None
    rise: Coord = 0.0
    major: Positive | None = None
    minor: Positive | None = None
    polar: tuple[Num, Num] = (0.0, 90.0)  # degrees from the top
    azimuth: tuple[Num, Num] = (0.0, 360.0)  # degrees
    resolution: Annotated[Whole, Field(ge=3, le=2000)] | None = None
    file: str | None = None
    heights: list[list[Coord]] | None = None
    x: str | None = None
    y: str | None = None
    z: str | None = None
    what: Literal["panels", "cells", "openings", "frame"] = "panels"
    count: Annotated[Whole, Field(ge=2)] | None = None
    relax: Annotated[Whole, Field(ge=0, le=2000)] | None = None
    method: Literal["lbfgs", "lloyd"] = "lbfgs"
    planarize: Positive | None = None
    openings: Fraction | None = None
    openings_near: Fraction | None = None
    openings_far: Fraction | None = None
    attractors: list[tuple[Coord, Coord, Coord]] = []
    attractor_radius: Positive | None = None
    thickness: Positive | None = None
    frame: Positive | None = None
    unroll: StrictBool = False
    sheet: tuple[Positive, Positive] | None = None
    meshes: list[Literal["3mf", "obj", "glb", "stl", "ply", "3dm"]] = []
    view: tuple[Num, Num] = (35.0, 30.0)

    #: keys only some shapes or modes read (``surface/build.py``; see
    #: ``voroforge.design.schema.UsedBy``)
    USED_BY: ClassVar[dict] = {
        "radius": ("shape", ("cylinder", "sphere_patch", "sphere")),
        "height": ("shape", ("cylinder",)),
        "width": ("shape", ("saddle", "heightfield")),
        "depth": ("shape", ("saddle", "heightfield")),
        "rise": ("shape", ("saddle", "heightfield")),
        "major": ("shape", ("torus",)),
        "minor": ("shape", ("torus",)),
        "polar": ("shape", ("sphere_patch",)),
        "azimuth": ("shape", ("sphere_patch",)),
        "resolution": (
            "shape",
            ("cylinder", "sphere_patch", "sphere", "saddle", "torus", "parametric"),
        ),
        "file": ("shape", ("heightfield", "mesh")),
        "what": ("mode", ("morph",)),
        "count": ("mode", ("voronoi",)),
        "relax": ("mode", ("voronoi",)),
        "method": ("mode", ("voronoi",)),
    }

    @model_validator(mode="after")
    def _shape_fields(self) -> SurfaceSection:
        need = {
            "cylinder": ("radius", "height"),
            "sphere_patch": ("radius",),
            "sphere": ("radius",),
            "saddle": ("width",),
            "torus": ("major", "minor"),
            "heightfield": ("width",),
            "parametric": ("x", "y", "z"),
            "mesh": ("file",),
        }[self.shape]
        for name in need:
            if getattr(self, name) is None:
                raise ValueError(f"@{name}@ shape = {self.shape!r} needs {name}")
        if self.shape == "heightfield":
            if (self.heights is None) == (self.file is None):
                raise ValueError("@heights@ shape = 'heightfield' needs heights or file (one)")
            if self.heights is not None:
                rows = {len(r) for r in self.heights}
                if len(self.heights) < 2 or len(rows) != 1 or min(rows) < 2:
                    raise ValueError(
                        "@heights@ heights must be rows of equal length, at least 2 x 2"
                    )
        elif self.heights is not None:
            raise ValueError("@heights@ heights is for shape = 'heightfield'")
        for name in ("x", "y", "z"):
            text = getattr(self, name)
            if text is None:
                continue
            if self.shape != "parametric":
                raise ValueError(f"@{name}@ {name} is for shape = 'parametric'")
            from .expr import compile_expression

            try:
                f = compile_expression(text)
            except ValueError as exc:
                raise ValueError(f"@{name}@ {exc}") from None
            _finite_on_grid(name, text, f)
        if self.shape == "sphere_patch":
            t0, t1 = self.polar
            if not 0 <= t0 < t1 <= 180:
                raise ValueError(
                    f"@polar@ polar must be [start, stop] degrees from the top with "
                    f"0 <= start < stop <= 180; got [{t0:g}, {t1:g}]"
                )
            p0, p1 = self.azimuth
            if not p0 < p1 <= p0 + 360:
                raise ValueError(
                    f"@azimuth@ azimuth must be [start, stop] degrees with start < stop <= "
                    f"start + 360; got [{p0:g}, {p1:g}]"
                )
        if self.shape == "torus" and not self.minor < self.major:
            raise ValueError(
                f"@minor@ a torus needs minor < major; got minor = {self.minor:g}, "
                f"major = {self.major:g}"
            )
        if self.mode == "morph" and self.shape == "sphere":
            raise ValueError("@shape@ morph needs a UV map: use sphere_patch, not sphere")
        graded = (self.openings_near is None) + (self.openings_far is None)
        if graded == 1:
            raise ValueError("@openings_near@ give both openings_near and openings_far")
        if graded == 0 and (not self.attractors or self.attractor_radius is None):
            raise ValueError("@attractors@ graded openings need attractors and attractor_radius")
        return self


def _finite_on_grid(name: str, text: str, f) -> None:
    """Raise (at ``name``) where the expression is not finite on a UV grid over [0, 1]^2."""
    import numpy as np

    t = np.linspace(0.0, 1.0, SURFACE_EXPR_SAMPLES)
    u, v = np.meshgrid(t, t, indexing="ij")
    try:
        val = f(u, v)
    except (ArithmeticError, ValueError) as exc:  # defensive: the walker is numpy
        raise ValueError(f"@{name}@ {text!r} cannot be evaluated: {exc}") from None
    bad = ~np.isfinite(val) | (np.abs(val) > _BIG)
    if bad.any():
        i, j = np.argwhere(bad)[0]
        raise ValueError(
            f"@{name}@ {text!r} gives {float(val[i, j]):g} at (u, v) = ({t[i]:g}, {t[j]:g}); "
            f"it must be finite (magnitude up to {_BIG:g}) on 0 <= u, v <= 1"
        )
