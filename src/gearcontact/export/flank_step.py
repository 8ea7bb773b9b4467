"""B-spline surfaces of the flanks and their STEP file (gmsh's OpenCASCADE kernel).

:func:`fit_bspline` interpolates a flank with a bicubic tensor-product B-spline in the
flank's own parameters ``(u, v)`` (not-a-knot end conditions, scipy's
:func:`~scipy.interpolate.make_interp_spline` along ``u`` then ``v``): the B-spline
evaluated at ``(u, v)`` is the flank at ``(u, v)`` within the fit error. The node grid
is refined (``n -> 2 n - 1`` nodes per direction) until the largest distance to the
flank on the check grid (every node and every cell centre and edge midpoint of the
node grid, evaluated through the Surface contract) is at most
:data:`FIT_TARGET_MM`, a tenth of the 0.5 um the export promises (docs/export.md).
The interpolation error of a cubic spline falls as h^4 (de Boor, *A Practical Guide
to Splines*, 2001, ch. V), so one refinement divides it by about 16.
:func:`fit_bsplines` fits the smooth pieces of a kinked flank on one node grid, the
pieces' shared kink edges given the same poles, and refines until their normals too are
within :data:`NORMAL_TARGET_RAD` of the pieces' (the tangent-plane jump at the kink is
what distinguishes the faces); :func:`fit_bspline_groups` does so for a flank split
along ``v`` too (a kink crossing the root or tip line), faces meeting across the split
given the same poles on it.

:func:`write_step` hands the control nets to ``gmsh.model.occ.addBSplineSurface``
(one face each, its natural boundary) and writes the STEP file (AP214, mm) with
OpenCASCADE's writer; the header's time stamp is then set to a fixed value, the
assembly occurrences are numbered per file (OpenCASCADE counts them over the whole
process) and the products get the flank names, so identical runs write identical files.

References
----------
C. de Boor, *A Practical Guide to Splines*, rev. ed., Springer, 2001, ch. V, XVII
(tensor-product interpolation).
ISO 10303-21 (the STEP file: header ``FILE_NAME``), ISO 10303-214.
"""

from __future__ import annotations

import contextlib
import ctypes
import dataclasses
import os
import re
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import ToolUnavailable
from ..validation import check_array_finite

__all__ = ["FIT_TARGET_MM", "NORMAL_TARGET_RAD", "STEP_TIMESTAMP", "BSplineFlank", "fit_bspline",
           "fit_bsplines", "fit_bspline_groups", "write_step", "gmsh_session"]

#: Largest fit error accepted, mm (a tenth of the export's 0.5 um promise).
FIT_TARGET_MM = 5e-5
#: Largest angle between a kinked flank's piece and its B-spline face's normals, rad
#: (the normal jump across the kink is the faces' to this; a probe of 2 mm radius
#: compensated along a normal off by it moves 0.2 um, below the export's 0.5 um).
NORMAL_TARGET_RAD = 1e-4
#: Node count per direction of the first fit and the largest one tried.
FIT_NODES_START, FIT_NODES_MAX = 9, 257
#: The fixed ``FILE_NAME`` time stamp of every STEP file written (ISO 8601).
STEP_TIMESTAMP = "2000-01-01T00:00:00"
DEGREE = 3


@dataclass(frozen=True)
class BSplineFlank:
    """A bicubic B-spline surface of one flank, in the export frame (mm).

    Attributes
    ----------
    name : str
        Flank name (``pinion_drive``, ``gear_fillet_cw``, ...), the STEP product name.
    knots_u, knots_v : ndarray
        Clamped knot vectors in the flank's own parameters.
    control_mm : ndarray (n_u, n_v, 3)
        Control points, mm.
    nodes : tuple of int
        Interpolation nodes (n_u, n_v) of the fit.
    fit_error_mm : float
        Largest distance between the B-spline and the flank on the check grid, mm.
    """

    name: str
    knots_u: np.ndarray
    knots_v: np.ndarray
    control_mm: np.ndarray
    nodes: tuple[int, int]
    fit_error_mm: float

    def evaluate(self, u, v) -> np.ndarray:
        """Points (len(u), len(v), 3) of the B-spline on the grid ``u x v``, mm."""
        from scipy.interpolate import BSpline

        bu = BSpline.design_matrix(np.asarray(u, float), self.knots_u, DEGREE,
                                   extrapolate=True).toarray()
        bv = BSpline.design_matrix(np.asarray(v, float), self.knots_v, DEGREE,
                                   extrapolate=True).toarray()
        along_u = np.tensordot(bu, self.control_mm, axes=(1, 0))      # (i, b, k)
        return np.moveaxis(np.tensordot(bv, along_u, axes=(1, 1)), 0, 1)

    def normals(self, u, v) -> np.ndarray:
        """Unit normals ``r_u x r_v / |r_u x r_v|`` (len(u), len(v), 3) on ``u x v`` (the
        face's orientation: compared with a flank's up to sign)."""
        from scipy.interpolate import BSpline

        n_u, n_v = self.control_mm.shape[:2]
        u, v = np.asarray(u, float), np.asarray(v, float)

        def grid(du, dv):
            along = BSpline(self.knots_u, self.control_mm.reshape(n_u, -1), DEGREE)
            a = (along.derivative(du) if du else along)(u).reshape(len(u), n_v, 3)
            across = BSpline(self.knots_v, np.moveaxis(a, 1, 0).reshape(n_v, -1), DEGREE)
            b = (across.derivative(dv) if dv else across)(v).reshape(len(v), len(u), 3)
            return np.moveaxis(b, 0, 1)

        n = np.cross(grid(1, 0), grid(0, 1))
        return n / np.linalg.norm(n, axis=-1, keepdims=True)


def _interpolate(u, v, points):
    from scipy.interpolate import make_interp_spline

    along_u = make_interp_spline(u, points, k=DEGREE, axis=0)
    along_v = make_interp_spline(v, along_u.c, k=DEGREE, axis=1)
    # scipy keeps the interpolation axis first in .c
    return along_u.t, along_v.t, np.moveaxis(along_v.c, 0, 1)


def fit_bspline(name: str, points_of, u_range, v_range) -> BSplineFlank:
    """Interpolate a flank with a bicubic B-spline to :data:`FIT_TARGET_MM`.

    Parameters
    ----------
    name : str
    points_of : callable
        ``points_of(U, V) -> (..., 3)`` flank points in the export frame, mm.
    u_range, v_range : tuple of float
        The flank's parameter box.

    Raises
    ------
    ArithmeticError
        If :data:`FIT_NODES_MAX` nodes per direction do not reach the target.
    """
    return fit_bsplines([name], [points_of], u_range, v_range)[0]


def fit_bsplines(names, points_ofs, u_range, v_range, *, normals_ofs=None
                 ) -> list[BSplineFlank]:
    """:func:`fit_bspline` of the smooth pieces of a kinked flank, stacked along ``u``
    (root -> tip), all on the same node grid (refined together until every piece is
    within :data:`FIT_TARGET_MM`, and with ``normals_ofs`` (callables as
    ``points_ofs`` giving the pieces' unit normals) until every normal of the
    B-splines is within :data:`NORMAL_TARGET_RAD` of the piece's on the check grid).

    Piece ``k``'s edge ``u = u_range[1]`` and piece ``k + 1``'s edge ``u = u_range[0]``
    are the kink between them: the upper piece's first row of poles is set to the lower
    piece's last (a clamped interpolant's edge row of poles is the interpolant of its
    edge points along ``v``, the same knots on both), so the two faces' edge curves are
    one B-spline curve, bit for bit; the fit error is measured after that.
    """
    return fit_bspline_groups([(names, points_ofs, v_range, normals_ofs)], u_range)[0]


def fit_bspline_groups(groups, u_range, *, joins=()) -> list[list[BSplineFlank]]:
    """:func:`fit_bsplines` of several stacks of faces side by side along ``v`` (a
    kinked flank split where a kink crosses the root or tip line), all on the same node
    grid, refined together.

    Parameters
    ----------
    groups : list of (names, points_ofs, v_range, normals_ofs)
        Each a :func:`fit_bsplines` stack over its own ``v_range``. A normal that
        ``normals_ofs`` gives as NaN is not checked (a face's collapsed edge, where its
        own normal is undefined).
    u_range : tuple of float
    joins : sequence of ((g, k), (h, l))
        Face ``k`` of group ``g`` and face ``l`` of group ``h`` (the next along ``v``)
        meet on the edge ``v = g's v_range[1] = h's v_range[0]``: the later face's first
        column of poles is set to the earlier's last (the same edge points along ``u``,
        the same knots: one curve, bit for bit).

    Returns
    -------
    list of list of BSplineFlank
        Per group, its faces.
    """
    n = FIT_NODES_START
    while True:
        u = np.linspace(*u_range, n)
        cu = np.linspace(*u_range, 2 * n - 1)
        fitted = []
        for h, (names, points_ofs, v_range, _) in enumerate(groups):
            v = np.linspace(*v_range, n)
            fits = []
            for m, (name, points_of) in enumerate(zip(names, points_ofs)):
                nodes = check_array_finite(f"{name} points",
                                           points_of(*np.meshgrid(u, v, indexing="ij")))
                tu, tv, control = _interpolate(u, v, nodes)
                # the split edge first, then the kink row (the face above reads this
                # face's last row with its corners as joined)
                for (g, k) in (before for before, after in joins if after == (h, m)):
                    control[:, 0] = fitted[g][k].control_mm[:, -1]
                if fits:
                    control[0] = fits[-1].control_mm[-1]
                fits.append(BSplineFlank(name, tu, tv, control, (n, n), 0.0))
            fitted.append(fits)
        errors, turns = [], [0.0]
        for fits, (names, points_ofs, v_range, normals_ofs) in zip(fitted, groups):
            cv = np.linspace(*v_range, 2 * n - 1)
            grid = np.meshgrid(cu, cv, indexing="ij")
            errors.append([float(np.linalg.norm(fit.evaluate(cu, cv) - points_of(*grid),
                                                axis=-1).max())
                           for fit, points_of in zip(fits, points_ofs)])
            for fit, normals_of in zip(fits, normals_ofs or ()):
                truth = normals_of(*grid)
                checked = np.isfinite(truth).all(axis=-1)
                with np.errstate(invalid="ignore"):     # 0 / 0 on a collapsed edge
                    cos = np.abs(np.einsum("...i,...i->...", fit.normals(cu, cv), truth))
                turns.append(float(np.arccos(np.clip(cos[checked], 0.0, 1.0)).max()))
        flat = [e for group in errors for e in group]
        if max(flat) <= FIT_TARGET_MM and max(turns) <= NORMAL_TARGET_RAD:
            return [[dataclasses.replace(f, fit_error_mm=e) for f, e in zip(fits, errs)]
                    for fits, errs in zip(fitted, errors)]
        if 2 * n - 1 > FIT_NODES_MAX:
            names = [name for group in groups for name in group[0]]
            worst = int(np.argmax(flat))
            raise ArithmeticError(f"{names[worst]}: the B-spline fit with {n} x {n} nodes "
                                  f"is {flat[worst] * 1e3:.3g} um off the flank (target "
                                  f"{FIT_TARGET_MM * 1e3:g} um), its normals "
                                  f"{max(turns):.3g} rad (target {NORMAL_TARGET_RAD:g})")
        n = 2 * n - 1


@contextlib.contextmanager
def gmsh_session(model: str):
    """gmsh initialized (no configuration files, no SIGINT handler, quiet) with a fresh
    model ``model``; finalized at the end if this session initialized it."""
    try:
        import gmsh
    except (ImportError, OSError) as exc:    # OSError: libgmsh's system libraries
        raise ToolUnavailable("gearcontact export flanks needs gmsh (OpenCASCADE): pip "
                              f"install 'gearcontact[export]' ({exc})") from None
    owner = not gmsh.isInitialized()
    if owner:
        gmsh.initialize(argv=[], readConfigFiles=False, interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add(model)
        yield gmsh
    finally:
        if owner:
            gmsh.finalize()
        else:
            gmsh.model.remove()


@contextlib.contextmanager
def _quiet_stdout():
    """OpenCASCADE's STEP writer prints its transfer statistics on the process's
    standard output (fd 1, not through gmsh's logger): discard them there, so that the
    command's own output stays what it prints."""
    sys.stdout.flush()
    libc = ctypes.CDLL(None)
    saved = os.dup(1)
    try:
        with open(os.devnull, "wb") as null:
            os.dup2(null.fileno(), 1)
            try:
                yield
            finally:
                libc.fflush(None)       # C++ iostreams share C stdio's buffer
                os.dup2(saved, 1)
    finally:
        os.close(saved)


def _add_surface(gmsh, fit: BSplineFlank) -> int:
    occ = gmsh.model.occ
    n_u, n_v = fit.control_mm.shape[:2]
    # gmsh takes the net with u running fastest
    tags = [occ.addPoint(*map(float, fit.control_mm[i, j]))
            for j in range(n_v) for i in range(n_u)]
    ku, mu = np.unique(fit.knots_u, return_counts=True)
    kv, mv = np.unique(fit.knots_v, return_counts=True)
    tag = occ.addBSplineSurface(tags, n_u, degreeU=DEGREE, degreeV=DEGREE,
                                knotsU=[float(k) for k in ku], knotsV=[float(k) for k in kv],
                                multiplicitiesU=[int(m) for m in mu],
                                multiplicitiesV=[int(m) for m in mv])
    occ.remove([(0, t) for t in tags])
    return tag


_PRODUCT = re.compile(r"PRODUCT\('([^']*)',\s*'([^']*)'")
_FILE_NAME = re.compile(r"(FILE_NAME\('[^']*',\s*)'[^']*'")
_OCCURRENCE = re.compile(r"NEXT_ASSEMBLY_USAGE_OCCURRENCE\('\d+'")


def _name_products(text: str, title: str, names: list[str]) -> str:
    """OpenCASCADE names the products ``<translator> 1`` (the file) and ``... 1.k``
    (face k in the order written): give them ``title`` and the flank names."""
    found = _PRODUCT.findall(text)
    if len(found) != len(names) + 1:
        raise ArithmeticError(f"STEP file: {len(found)} products for {len(names)} faces")
    labels = iter([title] + names)
    return _PRODUCT.sub(lambda m: (lambda s: f"PRODUCT('{s}','{s}'")(next(labels)), text)


def write_step(path, fits: list[BSplineFlank], *, title: str) -> Path:
    """Write the B-spline faces ``fits`` to the STEP file ``path`` (mm, AP214), one
    product per face named as the flank, the file's product named ``title``.

    The header's ``FILE_NAME`` carries ``title`` and the fixed time stamp
    :data:`STEP_TIMESTAMP` (identical runs write identical bytes).
    """
    path = Path(path)
    with gmsh_session("flanks") as gmsh:
        for fit in fits:
            _add_surface(gmsh, fit)
        gmsh.model.occ.synchronize()
        with _quiet_stdout():
            gmsh.write(str(path))
    text = path.read_text()
    text = _FILE_NAME.sub(lambda m: f"FILE_NAME('{title}','{STEP_TIMESTAMP}'", text, count=1)
    text = _name_products(text, title, [f.name for f in fits])
    # the occurrence ids come from a counter of the whole process: number them per file
    count = iter(range(1, len(fits) + 1))
    text = _OCCURRENCE.sub(lambda m: f"NEXT_ASSEMBLY_USAGE_OCCURRENCE('{next(count)}'", text)
    path.write_text(text)
    return path
