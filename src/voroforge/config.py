"""Numerical settings shared by every kernel: numba flags and tolerances live here only."""
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

from __future__ import annotations
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

import os
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: Flags for every ``@njit`` kernel. ``fastmath`` stays off everywhere: the robust
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: predicates rely on IEEE round-to-nearest and on no contraction into FMA.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

NJIT = {"cache": True, "nogil": True, "fastmath": False, "error_model": "numpy"}
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: Same, with ``parallel=True`` for kernels that use ``prange``.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

NJIT_PARALLEL = {**NJIT, "parallel": True}
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: Relative tolerance (of the domain's size) below which a clipped Voronoi edge counts as
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: a point contact rather than a shared edge. Exactly cocircular sites are detected with the
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: exact incircle predicate, so this only matters for nearly degenerate input.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

EDGE_LENGTH_RTOL = 1e-12
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: Relative tolerance (of the domain's size) used to snap vertices produced by clipping
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: back onto the exact coordinates of a rectangular domain.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

SNAP_RTOL = 4.0 * 2.0**-52
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: Below this many sites the engine does not bother with threads.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

PARALLEL_MIN_SITES = int(os.environ.get("VOROFORGE_PARALLEL_MIN_SITES", "20000"))
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

# ---------------------------------------------------------------------------------------------
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

# Tolerances. Each literal tolerance of the package lives below, one line saying what it guards.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

# ---------------------------------------------------------------------------------------------
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

# --- predicates, vertices, Delaunay-dual cells, power cells ----------------------------------
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: Relative size of a centre's float denominator (to the sum of its two products) below
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: which the adaptive orient2d replaces it (kernels/vertex.center)
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

VERTEX_DET_RTOL = 1e-8
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: Squared distance between two sites, relative to the squared radius of their circle,
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: below which a triple holding both is not a vertex's name (ill-conditioned centre)
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

VERTEX_PAIR_RTOL = 2.0**-40
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: A cocircular triple names a vertex only if its centre is this close to the vertex (L1,
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: relative to the vertex's magnitude and distance from its site; kernels/vertex)
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

VERTEX_SNAP_RTOL = 2.0**-40
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

# --- half-plane cells, bucket grid, raster ----------------------------------------------------
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

# --- engine (inputs, domains, periodic, describe, interpolation, Lloyd) ------------------------
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

# --- design layer and io ----------------------------------------------------------------------
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: mm: default SVG stroke width of a design build, a laser hairline (drivers cut only
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: hairlines, about 0.001 in or less, as vectors; 0.01 in would be engraved).
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

HAIRLINE_MM = 0.01
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: design.cellops.explode: vertices of neighbouring cells closer than this fraction of the
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: cells' bounding-box diagonal are one vertex (rounding-level differences double no edge).
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

EDGE_MERGE_RTOL = 1e-9
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: design.cellops: a single polygon is convex when its hull's area exceeds its own by at most
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: this fraction of the hull's (such cells are scaled and filleted on a fast path).
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

CONVEX_AREA_RTOL = 1e-12
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: design.compute: a corner_radius of half the boundary's width (a stadium, a disc) leaves a
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: core GEOS drops; the radius is made this fraction smaller to keep a sliver of it.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

CORNER_RADIUS_SHRINK = 1e-4
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: design.compute: cells.min_size measures openings' inscribed circles to this fraction of
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: min_size.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

MIN_SIZE_RTOL = 1e-3
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: design.recursive: cells tile their region when their areas sum to its area within this
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: fraction (else they are cut to the region again).
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

TILING_AREA_RTOL = 1e-9
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: design.fabrication.check: webs and openings within this (drawing units) of their limit pass
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: (a web inset to exactly min_web is no violation because of rounding).
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

FAB_LIMIT_ATOL = 1e-6
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: design.fabrication.check: uncut material thinner than this (drawing units) in a corner is
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: ignored (chord-vs-arc noise of fillets); also the design files' default corner_tolerance.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

FAB_CORNER_TOLERANCE = 0.02
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: design.fabrication: corner leftovers with area below (this x corner tolerance)^2 are noise.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

FAB_CORNER_AREA_RTOL = 0.1
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: design.fabrication.inscribed_circles: default precision, this fraction of each polygon's
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: smaller box side...
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

INSCRIBED_RTOL = 1e-3
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: ...and never below this (drawing units), nor a drawing's extent for marker sizes.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

INSCRIBED_FLOOR = 1e-9
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: design.fabrication: a frame part touches the outline when nearer than this fraction of the
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: outline's largest coordinate (at least 1); parts farther away are loose islands.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

ISLAND_TOUCH_RTOL = 1e-9
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: mm: default largest distance between a curve (SVG Bézier/arc, DXF bulge/circle) and the
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: polyline a boundary reader flattens it to; well below laser and CNC resolution.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

CURVE_TOLERANCE = 0.01
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: Floor on an SVG element's transform scale, so its flattening tolerance never divides by 0.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

SVG_MIN_SCALE = 1e-300
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: Radians: a DXF ELLIPSE whose parameter span is within this of a full turn is closed.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

ELLIPSE_FULL_TURN_ATOL = 1e-9
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: Default largest distance (drawing units) of a vertex from the circular arc that replaces
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: its run of chords in DXF bulges and SVG ``A`` arcs.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

ARC_TOLERANCE = 1e-6
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: Radians: a vertex turning less than this is straight, never inside an arc.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

ARC_MIN_TURN = 1e-9
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: Relative slack on the largest turning per chord that still counts as part of an arc.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

ARC_STEP_RTOL = 1e-9
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: Chords of one arc have equal length within this fraction of the longer one.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

ARC_CHORD_RTOL = 1e-3
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: Neighbouring vertices of one arc turn equally within this fraction of the turn...
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

ARC_TURN_RTOL = 1e-3
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: ...or within this many radians for tiny turns (the floor of that fraction's scale).
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

ARC_TURN_FLOOR = 1e-3
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: Floor of the arc-fit tolerance relative to the ring's largest coordinate (float64 noise).
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

ARC_FIT_RTOL = 1e-11
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12


#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

#: Radians of slack (over half a step) between an arc's fitted sweep and its chords' turning.
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

ARC_SWEEP_ATOL = 1e-6
#: Periodic margin proof: relative slack on the squared empty-disk radius (rounded distances)
PERIODIC_PROOF_RTOL = 1e-7
#: Periodic wrap: ulps of the box's magnitude below which an image's piece is a rounding sliver
PERIODIC_SLIVER_ULPS = 64.0
#: Periodic wrap: holes and parts below this fraction of a united cell's area are slivers
PERIODIC_SLIVER_RTOL = 1e-9
#: describe(): vertices closer than this (of the domain's diagonal) are one vertex
VERTEX_RTOL = 1e-13
#: describe(): a domain whose hull area exceeds its area by less than this (relative) is convex
CONVEX_DOMAIN_RTOL = 1e-12
#: locate(): a candidate this close (relative) to the best squared distance may be a tie
LOCATE_TIE_RTOL = 1e-9
#: locate(): absolute floor added to tie thresholds so a zero distance still admits ties
LOCATE_TIE_ATOL = 1e-300
#: Sibson Z1 gradients: smallest/largest eigenvalue ratio for a well-posed least-squares fit
GRADIENT_FIT_RTOL = 1e-9
#: Sibson Z1 gradients: floor on the largest eigenvalue (an all-zero fit is never well-posed)
GRADIENT_FIT_FLOOR = 1e-300
#: PowerDiagram.locate: relative slack before a site past the k-th KD candidate is checked
POWER_TIE_RTOL = 1e-9
#: power(): relative slack before a site that loses everywhere in the box is dropped
POWER_HIDDEN_RTOL = 1e-9
#: power(): cross products below this (of the squared span) make the sites collinear
POWER_FLAT_RTOL = 1e-12
#: power_fit(): target areas must sum to the domain's area to this relative tolerance
POWER_FIT_SUM_RTOL = 1e-6
#: power_fit(): default largest relative area error (``tol=``)
POWER_FIT_DEFAULT_RTOL = 1e-6
#: power_fit(): diagonal shift of the Newton Laplacian (relative to its mean degree)
POWER_NEWTON_SHIFT = 1e-12
#: power_fit(): polylabel precision (of the square root of the part's area) for the shrink start
POWER_LABEL_RTOL = 1e-3
#: lloyd(areas=): relative area error each iteration's weight refit goes to
LLOYD_REFIT_RTOL = 1e-9
#: lloyd(method="lbfgs"): Armijo sufficient-decrease constant of the line search
LBFGS_ARMIJO = 1e-4
#: lloyd(method="lbfgs"): curvature s.y below this (of |s| |y|) drops the pair from memory
LBFGS_CURVATURE_RTOL = 1e-12

