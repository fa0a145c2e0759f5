"""Numbers as a design file writes them: the strict field types every section's model uses.

TOML has typed values, and pydantic's lax mode reads ``"10"`` as 10 and ``true`` as 1; a
design file that says ``seed = true`` or ``thickness = "1.6"`` has a typo, which is reported
with its key rather than built. The 2D sections, ``[solid]`` and ``[surface]`` share these.
"""

from __future__ import annotations

from typing import Annotated, Any

from pydantic import BeforeValidator, Field, Strict

__all__ = ["Flag", "Num", "Whole", "short_repr"]


def short_repr(value) -> str:
    """``repr(value)`` cut to 40 characters, for error messages that quote a given value."""
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def _whole(value: Any) -> Any:
    """A count or seed is a TOML number: refuse ``"3"`` and ``true`` (pydantic reads 3 and 1).

    ``seed = true`` is a typo, not the seed 1.
    """
    if isinstance(value, bool):
        raise ValueError("expected an integer, not true/false")
    if isinstance(value, str):
        raise ValueError(f"expected an integer, not the text {short_repr(value)}")
    return value


#: A finite number written as a number: ``"10"`` and ``true`` are refused, not read as 10 and
#: 1; ``nan`` and ``inf`` too (``web = nan`` reached the cell offsets without its key).
Num = Annotated[float, Strict(), Field(allow_inf_nan=False)]
#: A whole number written as a number (``100.0`` is still 100).
Whole = Annotated[int, BeforeValidator(_whole)]
#: true or false, not ``"yes"`` or 1.
Flag = Annotated[bool, Strict()]
