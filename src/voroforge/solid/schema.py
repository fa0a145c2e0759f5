"""``[solid]``: a printable 3D product of a design file (the section's model).

``kind = "lattice" | "foam" | "shell"`` build from 3D cells (``cells`` sites in the
``container``, relaxed ``relax`` times, optionally subdivided); ``kind = "extrude"`` turns
the file's 2D design into a slab. The 3D kinds need no ``[boundary]``/``[seeds]`` tables.
"""

from __future__ import annotations

from typing import Annotated, ClassVar, Literal

from pydantic import BaseModel, ConfigDict, Field, model_validator

from ..config import SOLID_MAX_OPENINGS, SURFACE_COORD_RANGE
from ..design.numbers import Flag, Num, Whole

__all__ = ["PLACEHOLDER_2D", "SolidField", "SolidSection", "fill_2d"]

# numbers written as numbers (``"1.6"`` and ``true`` are refused with their key)
Positive = Annotated[Num, Field(gt=0)]
Finite = Num
NonNeg = Annotated[Num, Field(ge=0)]
Size = Positive | tuple[Positive, Positive]


class SolidField(BaseModel):
    """``[[solid.fields]]``: a 3D attractor (point, curve, plane) grading the sizes."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

    type: Literal["point", "curve", "plane"] = "point"
    points: list[tuple[Num, Num, Num]] | None = None
    origin: tuple[Num, Num, Num] = (0.0, 0.0, 0.0)
    normal: tuple[Num, Num, Num] = (0.0, 0.0, 1.0)
    radius: Positive
    strength: NonNeg = 1.0
    falloff: Literal["linear", "smoothstep", "gaussian", "inverse_power"] = "smoothstep"

    #: keys only some types read (see ``voroforge.design.schema.UsedBy``)
    USED_BY: ClassVar[dict] = {
        "points": ("type", ("point", "curve")),
        "origin": ("type", ("plane",)),
        "normal": ("type", ("plane",)),
    }

    @model_validator(mode="after")
    def _pts(self) -> SolidField:
        if self.type in ("point", "curve") and not self.points:
            raise ValueError(f"@points@ a {self.type} field needs points = [[x, y, z], ...]")
        if self.type == "curve" and len(self.points) < 2:
            raise ValueError(
                f"@points@ a curve field needs at least two points; got {len(self.points)}"
            )
        return self


#: The kinds built from 3D cells in a container.
_CELLS = ("lattice", "foam")


class SolidSection(BaseModel):
    """``[solid]``: what to build, from which cells, and the print limits."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

    kind: Literal["lattice", "foam", "shell", "extrude"]
    # cells (lattice, foam)
    container: tuple[Finite, Finite, Finite, Finite, Finite, Finite] | str | None = None
    cells: Annotated[Whole, Field(gt=0, le=200_000)] = 200
    relax: Annotated[Whole, Field(ge=0, le=200)] = 0
    seed: Annotated[Whole, Field(ge=0)] = 0
    subdivide: Annotated[Whole, Field(ge=0, le=3)] = 0
    subdivide_count: Size = 4.0
    # sizes
    radius: Size = 0.8
    nodes: Literal["sphere", "hull", "smooth"] = "sphere"
    skin: NonNeg = 0.0
    wall: Size = 1.2
    thickness: Positive = 2.0
    openings: Annotated[Whole, Field(ge=0, le=SOLID_MAX_OPENINGS)] = 60
    web: Size = 1.5
    rim: Positive | None = None
    # shell surfaces: a mesh file, or a profile [[r, z], ...] revolved about z
    surface: str | None = None
    profile: list[tuple[Num, Num]] | None = None
    sections: Annotated[Whole, Field(ge=8, le=1024)] = 96
    fields: list[SolidField] = []
    invert_field: Flag = False
    voxel: Positive | None = None
    smoothing: Annotated[Whole, Field(ge=0, le=200)] = 10
    # outputs and checks
    formats: list[Literal["3mf", "stl", "obj", "glb", "ply", "3dm", "png"]] = ["3mf", "png"]
    png_size: Annotated[Whole, Field(ge=64, le=4096)] = 900
    view: tuple[Num, Num] = (35.0, 25.0)
    min_strut: Positive | None = None
    min_pore: Positive | None = None
    #: thinnest printable wall: a foam's walls and skin, a shell's thickness, an extrude's
    #: slab (``check(min_wall=)``: ``thin_wall`` entries)
    min_wall: Positive | None = None
    max_overhang: Annotated[Num, Field(gt=0, lt=90)] | None = None

    #: keys only some kinds read (``solid/build.py``; see ``voroforge.design.schema.UsedBy``)
    USED_BY: ClassVar[dict] = {
        "container": ("kind", _CELLS),
        "cells": ("kind", _CELLS),
        "relax": ("kind", _CELLS),
        "seed": ("kind", (*_CELLS, "shell")),
        "subdivide": ("kind", _CELLS),
        "subdivide_count": ("kind", _CELLS),
        "radius": ("kind", ("lattice",)),
        "nodes": ("kind", ("lattice",)),
        "skin": ("kind", ("lattice",)),
        "wall": ("kind", ("foam",)),
        "thickness": ("kind", ("shell", "extrude")),
        "openings": ("kind", ("shell",)),
        "web": ("kind", ("shell",)),
        "rim": ("kind", ("shell",)),
        "surface": ("kind", ("shell",)),
        "profile": ("kind", ("shell",)),
        "sections": ("kind", ("shell",)),
        "fields": ("kind", (*_CELLS, "shell")),
        "invert_field": ("kind", (*_CELLS, "shell")),
        "voxel": ("kind", ("lattice", "shell")),
        "smoothing": ("kind", ("lattice", "shell")),
    }

    @model_validator(mode="after")
    def _kind(self) -> SolidSection:
        if self.kind == "shell" and self.surface is None and self.profile is None:
            raise ValueError("a shell needs surface = 'file.stl' or profile = [[r, z], ...]")
        if self.openings == 1:
            raise ValueError(
                "@openings@ openings must be 0 (a plain shell) or at least 2 seeds (one "
                "seed's cell is the whole surface: no web); got 1"
            )
        if self.profile is not None:
            big = max(abs(c) for q in self.profile for c in q)
            if big > SURFACE_COORD_RANGE[1]:
                raise ValueError(
                    f"@profile@ profile coordinates must lie within +-{SURFACE_COORD_RANGE[1]:g} "
                    f"(a surface's range; rescale the design's units); got {big:g}"
                )
            if len(self.profile) < 2:
                raise ValueError(
                    f"@profile@ profile must be [[r, z], ...] with at least 2 points; "
                    f"got {len(self.profile)}"
                )
            if all(tuple(q) == tuple(self.profile[0]) for q in self.profile):
                raise ValueError("@profile@ profile has no length: all its points are one point")
            if all(r == 0 for r, _ in self.profile):
                raise ValueError(
                    "@profile@ profile lies on the z axis (every r = 0): revolved, it has no area"
                )
            neg = [i for i, (r, _) in enumerate(self.profile) if r < 0]
            if neg:
                raise ValueError(
                    f"@profile@ profile radii must be >= 0 (revolved about the z axis); "
                    f"point {neg[0]} has r = {self.profile[neg[0]][0]:g}"
                )
        if self.kind in ("lattice", "foam") and self.container is None:
            raise ValueError(
                f"a {self.kind} needs container = [xmin, ymin, zmin, xmax, ymax, zmax] "
                "or a mesh file"
            )
        if isinstance(self.container, tuple):
            lo, hi = self.container[:3], self.container[3:]
            if not all(b > a for a, b in zip(lo, hi, strict=True)):
                raise ValueError("container box: each max must exceed its min")
        if not self.fields:  # a (far, near) pair is graded by the fields
            for key in ("radius", "wall", "web", "subdivide_count"):
                if isinstance(getattr(self, key), tuple):
                    raise ValueError(
                        f"@{key}@ (far, near) sizes need a [[solid.fields]] table to grade "
                        "them; give one number without fields"
                    )
        if self.skin > 0 and not isinstance(self.container, str):
            raise ValueError("skin lines a mesh container: give container = 'part.stl'")
        return self


#: A stand-in 2D design for the 3D kinds (their files have no [boundary]/[seeds]).
PLACEHOLDER_2D = {
    "boundary": {"shape": "rectangle", "width": 1.0, "height": 1.0},
    "seeds": {"method": "random", "count": 4},
}


def fill_2d(data):
    """Design-file data with the 2D tables a 3D ``[solid]`` does not use filled in."""
    if not isinstance(data, dict):
        return data
    sol = data.get("solid")
    kind = sol.get("kind") if isinstance(sol, dict) else getattr(sol, "kind", None)
    if sol is not None and kind != "extrude":  # a misspelt kind is no 2D design either
        missing = {k: v for k, v in PLACEHOLDER_2D.items() if k not in data}
        if missing:
            return {**data, **missing}
    return data
