"""The 3D kernels' helpers are compiled for one signature each, not one per literal argument.

numba types a constant argument (``f(..., 0)``, or a variable last assigned ``-1``, or a
loop variable on its first pass) as a literal and compiles the callee once per literal
value: :func:`.vertexdd3d._row` was compiled three times (rows 0, 1, 2) and
:func:`.predicates3d._dets` twice (``fresh`` omitted, and given). Each caller here is
compiled afresh (no cache) so that its callee's dispatcher sees the argument types the
caller passes, whatever the on-disk cache holds.
"""

from __future__ import annotations

import numba
import pytest
from numba import njit, types

from voroforge.kernels import predicates3d, vertexdd3d

pytestmark = pytest.mark.skipif(numba.config.DISABLE_JIT, reason="typing needs the JIT")

F1 = types.Array(types.float64, 1, "C")
F2 = types.Array(types.float64, 2, "C")
I1 = types.Array(types.int64, 1, "C")
I2 = types.Array(types.int64, 2, "C")
i8 = types.int64
f8 = types.float64


def _literal_free(dispatcher):
    """Every signature the dispatcher holds: no literal or omitted argument."""
    sigs = [tuple(s) for s in dispatcher.signatures]
    bad = [s for s in sigs if any(isinstance(t, (types.Literal, types.Omitted)) for t in s)]
    return sigs, bad


def test_vertex_dd_rows_one_signature():
    fresh = njit(cache=False)(vertexdd3d.vertex_dd.py_func)
    fresh.compile((i8, i8, i8, i8, F2, F1, F2, i8, f8, f8, f8, F1, F1))
    sigs, bad = _literal_free(vertexdd3d._row)
    assert sigs and not bad, sigs


def test_exact_dets_one_signature_of_dets():
    fresh = njit(cache=False)(predicates3d.exact_dets.py_func)
    fresh.compile((F1, I2, I1, types.boolean))
    sigs, bad = _literal_free(predicates3d._dets)
    assert sigs and not bad, sigs
