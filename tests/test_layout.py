"""The package's layout rules (issue 10, DESIGN.md "Layers").

No module reaches into another module's private names: an import of a leading-underscore
name (dunders excepted) from another module of the package, or ``module._name`` through a
module imported from the package, is a finding. No module is past ``MAX_LINES`` lines.
Every finding names its file and line.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import voroforge

ROOT = Path(voroforge.__file__).resolve().parent
MAX_LINES = 800


def _private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def _module_name(path: Path, root: Path) -> str:
    parts = [root.name, *path.relative_to(root).with_suffix("").parts]
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _is_module(name: str, root: Path) -> bool:
    """Whether the dotted ``name`` is a module or package of the tree at ``root``."""
    rel = Path(*name.split(".")[1:]) if "." in name else Path()
    p = root / rel
    return p.with_suffix(".py").is_file() or (p / "__init__.py").is_file()


def _absolute(current: str, is_package: bool, level: int, module: str | None) -> str:
    """The absolute name of a ``from`` import's module (``level`` dots, then ``module``)."""
    if level == 0:
        return module or ""
    base = current.split(".")
    if not is_package:
        base = base[:-1]
    base = base[: len(base) - (level - 1)]
    return ".".join(base + ([module] if module else []))


def private_uses(source: str, path: Path, root: Path) -> list[str]:
    """``"file:line: what"`` for each use of another package module's private name."""
    current = _module_name(path, root)
    package = root.name
    is_package = path.name == "__init__.py"
    where = path.relative_to(root.parent)
    tree = ast.parse(source, str(path))
    modules: dict[str, str] = {}  # local name -> package module it is bound to
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            src = _absolute(current, is_package, node.level, node.module)
            if src != package and not src.startswith(package + "."):
                continue
            for alias in node.names:
                if _private(alias.name) and src != current:
                    found.append(f"{where}:{node.lineno}: imports {alias.name} from {src}")
                if _is_module(f"{src}.{alias.name}", root):
                    modules[alias.asname or alias.name] = f"{src}.{alias.name}"
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name == package or alias.name.startswith(package + "."):
                    # ``import voroforge.x.y`` binds ``voroforge``; ``as m`` binds the module
                    modules[alias.asname or package] = alias.name if alias.asname else package
    for node in ast.walk(tree):
        if not (isinstance(node, ast.Attribute) and _private(node.attr)):
            continue
        through = _dotted(node.value)
        head = through.split(".")[0] if through else None
        if head not in modules:
            continue
        module = modules[head] + through[len(head) :]
        if module != current and _is_module(module, root):
            found.append(f"{where}:{node.lineno}: uses {module}.{node.attr} (through {through})")
    return found


def _dotted(node) -> str | None:
    """``a.b.c`` for a chain of names, else None."""
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        inner = _dotted(node.value)
        return None if inner is None else f"{inner}.{node.attr}"
    return None


def _sources(root: Path):
    return sorted(p for p in root.rglob("*.py") if "__pycache__" not in p.parts)


def test_no_module_uses_another_modules_private_names():
    found = []
    for path in _sources(ROOT):
        found += private_uses(path.read_text(encoding="utf-8"), path, ROOT)
    assert not found, "private names used across modules:\n" + "\n".join(found)


def test_no_module_past_max_lines():
    long = []
    for path in _sources(ROOT):
        n = len(path.read_text(encoding="utf-8").splitlines())
        if n > MAX_LINES:
            long.append(f"{path.relative_to(ROOT.parent)}:{n}: {n} lines > {MAX_LINES}")
    assert not long, "modules past the size limit:\n" + "\n".join(long)


@pytest.mark.parametrize(
    ("where", "source", "expected"),
    [
        # a multi-line relative import of a private name, in a function
        (
            "a/b.py",
            "def f():\n    from ..c import (\n        public,\n        _hidden,\n    )\n",
            ["pkg/a/b.py:2: imports _hidden from pkg.c"],
        ),
        # through a module alias, relative and absolute
        ("a/b.py", "from .. import c as m\nm._x\n", ["pkg/a/b.py:2: uses pkg.c._x (through m)"]),
        ("a/b.py", "import pkg.c as m\nm._x\n", ["pkg/a/b.py:2: uses pkg.c._x (through m)"]),
        ("a/b.py", "import pkg.c\npkg.c._x\n", ["pkg/a/b.py:2: uses pkg.c._x (through pkg.c)"]),
        # allowed: dunders, public names, own names, other packages
        ("a/b.py", "from ..c import __version__, public\nfrom numpy import _x\n", []),
        ("c.py", "from .c import _own\nfrom . import c\nc._own\n", []),
    ],
)
def test_the_rule_finds_planted_violations(tmp_path, where, source, expected):
    root = tmp_path / "pkg"
    for d in (root, root / "a"):
        d.mkdir(exist_ok=True)
        (d / "__init__.py").write_text("")
    (root / "c.py").write_text("_hidden = _x = _own = public = 1\n")
    path = root / where
    path.write_text(source)
    assert private_uses(source, path, root) == expected
