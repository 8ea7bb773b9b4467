"""Elastic half-space contact: Love influence operators and LCP solvers, for any two bodies.

Nothing here knows about gears: the input is a gap field ``h`` (mm) on a tangent-plane
grid, a normal load (N) and the materials; the output is the contact pressure, the
approach and the contact ellipse fitted to the patch (docs/halfspace.md shows a sphere
on a flat). The gear LTCA (:mod:`gearcontact.ltca`) is built on this package.
Fields on a :class:`TangentGrid` are ``(ny, nx)`` arrays ``h[j, i]`` with x along axis 1.
"""

from ..deprecation import moved_names
from .compliance import BlockCompliance
from .ellipse import CoarseGridWarning, ContactEllipse, fit_contact_ellipse
from .grid import TangentGrid
from .influence import (FftInfluence, dense_influence_matrix, fft_influence,
                        love_rectangle_displacement)
from .lcp import SOLVERS, LcpConvergenceError, solve_lcp
from .patch import (ContactAtEdgeWarning, PatchContact, patch_statistics, plot_patch,
                    solve_patch)
from .result import ContactResult, SolveStatus

__all__ = ["TangentGrid", "love_rectangle_displacement", "dense_influence_matrix",
           "FftInfluence", "fft_influence", "ContactResult", "LcpConvergenceError",
           "solve_lcp", "SOLVERS", "PatchContact", "ContactAtEdgeWarning",
           "solve_patch", "patch_statistics", "plot_patch", "ContactEllipse",
           "CoarseGridWarning", "fit_contact_ellipse", "BlockCompliance", "SolveStatus"]

#: Deprecated for one release: every solver returns :class:`ContactResult` (issue 24).
__getattr__ = moved_names(__name__, {"LcpResult": "gearcontact.halfspace.result:ContactResult"})
