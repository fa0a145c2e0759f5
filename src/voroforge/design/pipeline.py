"""Temporary re-export while the CLI moves to :mod:`compute` and :mod:`build` (issue 10)."""

from .build import DesignWarning, build, check_design, products, render_preview, write_starter
from .compute import Result, compute

__all__ = [
    "DesignWarning",
    "Result",
    "build",
    "check_design",
    "compute",
    "products",
    "render_preview",
    "write_starter",
]
