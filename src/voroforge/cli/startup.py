"""Start-up of a command that runs compiled kernels: what numba's first call need not pay.

The first call of any numba function in a process, cached or not, installs numba's
implementation registries. One of them, ``numba.np.arraymath``, checks at import that BLAS
is present by importing ``scipy.linalg.cython_blas``; importing that name runs
``scipy.linalg``'s package ``__init__`` first (its solvers, ``scipy._lib._util``, the array
API layer, ``numpy.testing``): about 0.13 s of CPU, a tenth of a 2D design's first build,
for a check that needs only the extension module. :func:`preload_blas` loads that module
alone (about 0.015 s) under its full name, so numba's check finds it in ``sys.modules``.

Nothing else changes: the module object is the one ``scipy.linalg`` would load (scipy's
own Cython modules import it by name, and find it), BLAS is present either way, and a
later ``import scipy.linalg`` runs its ``__init__`` as usual. One difference remains: that
later import does not set the attribute ``scipy.linalg.cython_blas`` (``from scipy.linalg
import cython_blas`` and ``import scipy.linalg.cython_blas as blas`` still work; scipy and
numba reach it only by name). When anything is off (scipy already imported, numba already
set up, another layout of scipy) it does nothing.
"""

from __future__ import annotations

import importlib.machinery
import importlib.util
import sys
from pathlib import Path

__all__ = ["preload_blas"]

_NAME = "scipy.linalg.cython_blas"


def preload_blas() -> bool:
    """Load ``scipy.linalg.cython_blas`` without ``scipy.linalg``'s ``__init__``.

    Returns
    -------
    bool
        Whether it was loaded here (False when it was there already, or when numba or
        ``scipy.linalg`` are set up already, or the module was not found).
    """
    if _NAME in sys.modules or "scipy.linalg" in sys.modules or "numba.np.arraymath" in sys.modules:
        return False
    spec = importlib.util.find_spec("scipy")  # the package's location; its __init__ is light
    if spec is None or not spec.submodule_search_locations:
        return False
    for folder in spec.submodule_search_locations:
        for suffix in importlib.machinery.EXTENSION_SUFFIXES:
            path = Path(folder) / "linalg" / f"cython_blas{suffix}"
            if path.is_file():
                return _load(path)
    return False


def _load(path: Path) -> bool:
    import scipy  # noqa: F401  (the parent package, as the import system would have it)

    loader = importlib.machinery.ExtensionFileLoader(_NAME, str(path))
    spec = importlib.util.spec_from_file_location(_NAME, path, loader=loader)
    if spec is None:
        return False
    module = importlib.util.module_from_spec(spec)
    sys.modules[_NAME] = module
    try:
        loader.exec_module(module)
    except Exception:  # a scipy whose module wants its package: let numba import it its way
        sys.modules.pop(_NAME, None)
        return False
    return True
