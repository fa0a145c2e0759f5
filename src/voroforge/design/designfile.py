"""Design files: reading TOML, ``--set`` overrides, and error reports that point at lines.

:func:`load` reads a TOML design, applies ``--set``-style overrides, validates it against
:class:`~voroforge.design.schema.Design` and raises :class:`DesignError` with one
:class:`Issue` per problem: the dotted key, the line of that key in the file and what was
expected. Unknown keys are errors with a "did you mean" hint; keys the design's choices do not
read (``points`` on a rectangle) are warnings (:func:`unused_keys`, :class:`UnusedKeyWarning`),
so that a design switched between shapes keeps building. tomllib keeps no positions, so
:func:`key_lines` maps key paths back to lines, and :func:`located` gives errors raised while
computing a design (a missing file, say) the file name and line of their key.
"""

from __future__ import annotations

import difflib
import functools
import re
import tomllib
import typing
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ValidationError

from ..config import DESIGN_FILE_MAX_BYTES
from ..solid.schema import PLACEHOLDER_2D
from .schema import Design, Graded, short_repr

__all__ = [
    "DesignError",
    "Issue",
    "UnusedKeyWarning",
    "apply_overrides",
    "find_file",
    "key_lines",
    "load",
    "located",
    "parse_value",
    "unused_keys",
]


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

    @classmethod
    def at(cls, key: str, message: str) -> DesignError:
        """One issue at a dotted key, with no line yet (:func:`located` adds file and line)."""
        return cls([Issue(key, None, message)])

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
        (
            "float",
            "int",
            "bool",
            "string",
            "literal",
            "greater",
            "less",
            "list",
            "tuple",
            "too_",
            "finite",
        )
    ):
        return f"{msg[0].lower()}{msg[1:]}; got {short_repr(got)}"
    return msg


#: The names pydantic gives the branches of a union in an error's location
#: (``constrained-float``, ``function-after[...]``, ``tuple[...]``): not keys of the file.
_BRANCH = re.compile(r"\[|^(constrained|function|lax-or-strict|json-or-python|tagged)-")


def _loc(err: dict) -> tuple:
    return tuple(p for p in err["loc"] if not (isinstance(p, str) and _BRANCH.search(p)))


def _issues(exc: ValidationError, lines: dict[tuple, int]) -> list[Issue]:
    out = []
    for err in exc.errors():
        loc = _loc(err)
        message = _expected(err)
        text = err["msg"]
        field = re.search(r"@([\w.]+)@ (.*)$", text)
        if field:  # a model validator naming its field (a dotted path: tracks.1.key)
            parts = field.group(1).split(".")
            loc = (*loc, *(int(p) if p.isdigit() else p for p in parts))
            message = field.group(2)
        elif text.startswith("Value error, "):
            message = text[len("Value error, ") :]
        if loc and loc[-1] == "value" and _model_at(loc[:-1]) is Graded:
            loc = loc[:-1]  # ``web = nan``: a Graded given as a bare number is its key
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
    # a union's plain-type branch ("solid.container.str: input should be a valid string")
    # beside its other branch's error at the same key says nothing new
    keys = [it.key for it in out]
    return [
        it
        for it in out
        if not (
            it.key.rsplit(".", 1)[-1] in _TYPE_BRANCHES
            and any(k != it.key and k.startswith(it.key.rsplit(".", 1)[0] + ".") for k in keys)
        )
    ]


#: The branch names pydantic gives a union's plain types.
_TYPE_BRANCHES = {"str", "int", "float", "bool", "none", "list", "dict", "bytes"}


def _is_selector(loc: tuple) -> bool:
    """Whether the key at ``loc`` picks among choices (``shape``, ``method``: a Literal)."""
    model = _model_at(loc[:-1])
    info = None if model is None else model.model_fields.get(str(loc[-1]))
    if info is None:
        return True  # unknown: treat as deciding the section's other rules
    ann = info.annotation
    return typing.get_origin(ann) is typing.Literal or any(
        typing.get_origin(a) is typing.Literal for a in typing.get_args(ann)
    )


def _cross_field_issues(
    data: dict, exc: ValidationError, issues: list[Issue], lines: dict[tuple, int]
) -> list[Issue]:
    """The checks between keys that pydantic skipped because a key of the section was bad.

    A section's checks between its keys (``formats`` includes "gif" but no ``[output.gif]``)
    run only once every key of it is valid, so one bad value hid them and the user met them
    one run later. Validate again with the bad keys left out and keep the new problems,
    except those at a left-out key (``radius = -2`` then "needs radius") or in a section
    whose left-out key picked its rules (a bad ``method`` or ``shape``).
    """
    import copy

    from ..solid.schema import fill_2d

    # the 2D stand-ins a 3D [solid] gets, before its bad keys (its kind perhaps) are left out
    pruned = copy.deepcopy(fill_2d(data))
    gone: list[tuple] = []
    for err in exc.errors():
        loc = _loc(err)
        if err["type"] == "missing" or not loc:
            continue
        if isinstance(loc[-1], int):
            loc = loc[:-1]  # a bad list item: leave the whole list out (indices stay put)
        node = pruned
        for part in loc[:-1]:
            try:
                node = node[part]
            except (KeyError, IndexError, TypeError):
                node = None
                break
        if isinstance(node, dict) and loc and loc[-1] in node:
            del node[loc[-1]]
            gone.append(loc)
    if not gone:
        return []
    try:
        Design.model_validate(pruned)
        return []
    except ValidationError as again:
        fresh = _issues(again, lines)
    except Exception:  # noqa: BLE001 - a second look only adds; it never replaces the first
        return []
    keys = {it.key for it in issues}
    dotted = [".".join(map(str, g)) for g in gone]
    ruled = {".".join(map(str, g[:-1])) for g in gone if _is_selector(g)}
    out = []
    for it in fresh:
        section = it.key.rsplit(".", 1)[0] if "." in it.key else ""
        if it.key in keys or section in ruled:
            continue
        if any(
            it.key == d or it.key.startswith(d + ".") or d.startswith(it.key + ".") for d in dotted
        ):
            continue
        out.append(it)
    return out


# --- keys the design's choices do not read -------------------------------------------------


class UnusedKeyWarning(UserWarning):
    """A key that the design's choices do not read (``points`` with ``shape = "rectangle"``).

    Not an error: a design switched between shapes (in the studio, say) keeps the other
    shape's keys and builds. ``issue`` is the :class:`Issue` (key, line, message); the text
    is :meth:`text` of it. (Built from the text alone too, as pytest-xdist rebuilds it.)
    """

    def __init__(self, message: str, issue: Issue | None = None):
        super().__init__(message)
        self.issue = issue

    @staticmethod
    def text(issue: Issue) -> str:
        """``boundary.points (line 7) is not used by shape = 'rectangle'; ...``."""
        set_here = issue.message.endswith(" (from --set)")
        where = f" (line {issue.line})" if issue.line else " (from --set)" if set_here else ""
        return f"{issue.key}{where} {issue.message.removesuffix(' (from --set)')}"


def _choices(values: tuple) -> str:
    quoted = [repr(v) for v in values]
    return quoted[0] if len(quoted) == 1 else ", ".join(quoted[:-1]) + " or " + quoted[-1]


@functools.cache
def _key_sets(cls: type[BaseModel]) -> tuple[tuple, tuple[str, ...]]:
    """``cls``'s ``USED_BY`` as ``(key, selector, choices, default)`` rows, and its fields."""
    used_by = cls.__dict__.get("USED_BY", {})
    used_when = cls.__dict__.get("USED_WHEN", {})
    rules = [*used_by.items(), *((k, (sel, (f, text))) for k, (sel, f, text) in used_when.items())]
    rows = tuple(
        (key, sel, values, cls.model_fields[key].get_default(call_default_factory=True))
        for key, (sel, values) in rules
    )
    return rows, tuple(cls.model_fields)


def _unused(model: BaseModel, loc: tuple, out: list[tuple[tuple, str]]) -> None:
    rows, names = _key_sets(type(model))
    for key, selector, values, default in rows:  # values: USED_BY's choices, USED_WHEN's rule
        if getattr(model, key) == default:
            continue  # not given, or given as the default: nothing is lost
        chosen = getattr(model, selector)
        if callable(values[0]):  # USED_WHEN: (reads, when)
            if values[0](chosen):
                continue
            if chosen is None:
                given = f"without {selector}"
            elif isinstance(chosen, BaseModel):
                given = f"with {selector} given"
            else:
                given = f"by {selector} = {short_repr(chosen)}"
            message = f"is not used {given}; it is used {values[1]}"
        elif isinstance(chosen, list):  # output.formats: read when any of them reads it
            if set(chosen) & set(values):
                continue
            message = f"is not used by {selector} = {chosen!r}; add {_choices(values)} to it"
        elif chosen in values:
            continue
        else:
            message = (
                f"is not used by {selector} = {chosen!r}; it is used by {selector} = "
                + _choices(values)
            )
        out.append(((*loc, key), message))
    for name in names:
        value = getattr(model, name)
        if isinstance(value, BaseModel):
            _unused(value, (*loc, name), out)
        elif isinstance(value, list | tuple) and value and isinstance(value[0], BaseModel):
            for i, item in enumerate(value):  # (not a list of points: only tables hold keys)
                if isinstance(item, BaseModel):
                    _unused(item, (*loc, name, i), out)


#: The 2D tables a design does not read when its ``[solid]`` is a 3D product (every kind but
#: ``extrude``) or its ``[surface]`` makes its own cells (``mode = "voronoi"``). A surface
#: design still needs ``[boundary]``/``[seeds]`` (and ``voroforge check`` runs the 2D
#: ``[fabrication]`` check), so those are not listed there.
_TABLES_2D = ("voronoi", "attractors", "field", "cells", "openings", "recursion")


def _unused_tables(design: Design) -> list[tuple[tuple, str]]:
    """Whole 2D tables a 3D ``[solid]`` or a ``[surface]`` in voronoi mode does not read."""
    solid, surface = design.solid, design.surface
    if solid is not None and solid.kind != "extrude":
        filled = PLACEHOLDER_2D
        names = ("boundary", "seeds", "relax", *_TABLES_2D, "fabrication")
        why = f"is not used by solid.kind = {solid.kind!r} (a 3D product reads [solid])"
    elif surface is not None and surface.mode == "voronoi":
        filled = {}
        names = _TABLES_2D
        why = "is not used by surface.mode = 'voronoi' (the cells are made on the surface)"
    else:
        return []
    out = []
    for name in names:
        value = getattr(design, name)
        field = type(design).model_fields[name]
        if name in filled:
            default = field.annotation.model_validate(filled[name])
        else:
            default = field.get_default(call_default_factory=True)
        if value != default:
            out.append(((name,), why))
    return out


def unused_keys(
    design: Design, lines: dict[tuple, int] | None = None, overrides: dict | None = None
) -> list[Issue]:
    """The keys of ``design`` that its choices do not read, one :class:`Issue` each.

    A table's discriminator (``boundary.shape``, ``seeds.method``, ``openings.select``,
    ``attractors.N.falloff``, ``solid.kind``, ``surface.shape``/``mode``, ...) decides which
    of its keys are read (the models' ``USED_BY``); a key given with another value than its
    default under a choice that does not read it is listed: ``boundary.points`` with
    ``shape = "rectangle"``.

    Parameters
    ----------
    design : Design
        A validated design.
    lines : dict, optional
        :func:`key_lines` of the file, for the line of each key.
    overrides : dict, optional
        ``--set`` keys: an issue at one of them says ``(from --set)`` instead of a line.

    Returns
    -------
    list of Issue
        In the file's order.
    """
    found: list[tuple[tuple, str]] = []
    _unused(design, (), found)
    found += _unused_tables(design)
    touched = {str(k) for k in (overrides or {})}
    out = []
    for loc, message in found:
        key = ".".join(map(str, loc))
        if key in touched:
            out.append(Issue(key, None, message + " (from --set)"))
        else:
            out.append(Issue(key, _line_of(lines or {}, loc), message))
    out.sort(key=lambda i: (i.line is None, i.line or 0))
    return out


# --- loading ------------------------------------------------------------------------------


def parse_value(text: str) -> Any:
    """Read a ``--set`` value as TOML (``500``, ``true``, ``[1, 2]``, ``"x"``); else a string."""
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except (tomllib.TOMLDecodeError, RecursionError):
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


def _deepest_line(text: str) -> int:
    """The line where ``[`` / ``{`` nesting is deepest (quoted text and comments skipped)."""
    depth = best = 0
    line = best_line = 1
    quote = None
    comment = escaped = False
    for ch in text:
        if ch == "\n":
            line += 1
            comment = False
        elif comment:
            continue
        elif escaped:
            escaped = False
        elif quote:
            escaped = quote == '"' and ch == "\\"
            quote = None if ch == quote else quote
        elif ch in "\"'":
            quote = ch
        elif ch == "#":
            comment = True
        elif ch in "[{":
            depth += 1
            if depth > best:
                best, best_line = depth, line
        elif ch in "]}":
            depth -= 1
    return best_line


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
        except RecursionError:
            pass
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

    Warns
    -----
    UnusedKeyWarning
        For each key the design's choices do not read (:func:`unused_keys`), with its line.
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
        except RecursionError:  # tomllib recurses once a level of [..] / {..}
            message = "TOML syntax: arrays or tables nested too deeply to read"
            raise DesignError([Issue("", _deepest_line(text), message)], name) from None
        lines = key_lines(text)
    data = apply_overrides(data, overrides)
    try:
        design = Design.model_validate(data)
    except ValidationError as exc:
        issues = _issues(exc, lines)
        issues += _cross_field_issues(data, exc, issues, lines)
        issues.sort(key=lambda i: (i.line is None, i.line or 0))  # in the file's order
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
    import warnings

    for issue in unused_keys(design, lines, overrides):
        warnings.warn(UnusedKeyWarning(UnusedKeyWarning.text(issue), issue), stacklevel=2)
    return design, base


def find_file(base: Path | None, name: str, key: str) -> Path:
    """The file a design names, relative to the design's folder ``base``.

    Raises
    ------
    DesignError
        At ``key`` when the file does not exist, is not a regular file (a directory, a pipe,
        a device: reading one hung or filled the memory) or is larger than
        ``config.DESIGN_FILE_MAX_BYTES``.
    """
    p = Path(name)
    if not p.is_absolute() and base is not None:
        p = base / p
    if not p.exists():
        raise DesignError.at(key, f"file not found: {p}")
    if not p.is_file():
        raise DesignError.at(key, f"not a regular file (a directory, pipe or device): {p}")
    size = p.stat().st_size
    if size > DESIGN_FILE_MAX_BYTES:
        raise DesignError.at(
            key, f"{p} is {size / 2**30:.1f} GiB, more than {DESIGN_FILE_MAX_BYTES / 2**30:g} GiB"
        )
    return p


@contextmanager
def located(source, overrides: dict | None = None):
    """Give DesignErrors raised inside the design file's name and the lines of their keys.

    Errors about keys set by ``overrides`` get no line and say ``(from --set)`` instead.
    Errors from a mapping or a validated design (no file) and errors that already name
    their source pass unchanged.
    """
    try:
        yield
    except DesignError as exc:
        if not isinstance(source, str | Path) or exc.source is not None:
            raise
        try:
            lines = key_lines(Path(source).read_text(encoding="utf-8-sig"))
        except OSError:
            lines = {}
        touched = {str(k) for k in (overrides or {})}
        issues = []
        for it in exc.issues:
            path = tuple(int(p) if p.isdigit() else p for p in it.key.split(".") if p)
            if any(
                it.key == t or it.key.startswith(t + ".") or t.startswith(it.key + ".")
                for t in touched
            ):
                issues.append(Issue(it.key, None, it.message + " (from --set)"))
            else:
                issues.append(Issue(it.key, _line_of(lines, path), it.message))
        raise DesignError(issues, str(source)) from None
