"""Elastic half-space contact: Love influence operators and LCP solvers, for any two bodies.

Nothing here knows about gears: the input is a gap field ``h`` (mm) on a tangent-plane
grid, a normal load (N) and the materials; the output is the contact pressure, the
approach and the contact ellipse fitted to the patch (docs/halfspace.md shows a sphere
on a flat). The gear LTCA (:mod:`gearcontact.ltca`) is built on this package.
Fields on a :class:`TangentGrid` are ``(ny, nx)`` arrays ``h[j, i]`` with x along axis 1.
"""

from ..deprecation import moved_names
from ..lazy_names import lazy_names

__all__ = ["TangentGrid", "love_rectangle_displacement", "dense_influence_matrix",
           "FftInfluence", "fft_influence", "ContactResult", "LcpConvergenceError",
           "solve_lcp", "SOLVERS", "PatchContact", "ContactAtEdgeWarning",
           "solve_patch", "patch_statistics", "plot_patch", "ContactEllipse",
           "CoarseGridWarning", "fit_contact_ellipse", "BlockCompliance", "SolveStatus"]

#: Each public name imports its module on first use (``import gearcontact.halfspace.grid``
#: stays free of the solvers' numba); deprecated for one release: every solver returns
#: :class:`ContactResult` (issue 24).
__getattr__ = lazy_names(__name__, {
    "compliance": ("BlockCompliance",),
    "ellipse": ("CoarseGridWarning", "ContactEllipse", "fit_contact_ellipse"),
    "grid": ("TangentGrid",),
    "influence": ("FftInfluence", "dense_influence_matrix", "fft_influence",
                  "love_rectangle_displacement"),
    "lcp": ("SOLVERS", "LcpConvergenceError", "solve_lcp"),
    "patch": ("ContactAtEdgeWarning", "PatchContact", "patch_statistics", "plot_patch",
              "solve_patch"),
    "result": ("ContactResult", "SolveStatus"),
}, fallback=moved_names(__name__, {"LcpResult": "gearcontact.halfspace.result:ContactResult"}))
