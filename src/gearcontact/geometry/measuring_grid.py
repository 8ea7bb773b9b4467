"""Measuring grids in a gear measuring machine's own coordinates: axial position L, radius R.

A gear measuring machine (Gleason GMM, Klingelnberg P-series, Zeiss) reports a bevel
flank as a grid of nominal points given by their axial position ``L`` along the
member's axis and their radius ``R`` about it, with the measured deviation along the
nominal normal at each point (docs/export.md, "The measuring grid"). Here:

- frame: the member's axis frame of ``gearcontact export flanks`` (axis +Z,
  :data:`AXIS_FRAMES`): gear body frame; pinion body frame turned ``(X, Y, Z) = (y, z,
  x)``. Its origin is the member's crossing point (the foot of the common perpendicular
  of the axes on the member's axis, docs/geometry.md sec. 1), so ``L = Z`` (mm, signed
  along +Z) and ``R = sqrt(X^2 + Y^2)`` (mm);
- grid: ``rows`` lines along the face (row 1 at the root, the last at the tip) by
  ``cols`` points on each (col 1 at the toe), uniform in the flank's own ``(u, v)``
  over its active box, edges included (the pinion's rows lie at constant height over
  the root cone, :mod:`.sheet`);
- deviation: ``deviation_um`` along the nominal unit normal (out of the tooth), positive
  = material added (the measured flank stands proud of the nominal), the opposite sign
  of an ease-off (:mod:`.easeoff`).

A measured file's points may form such a grid (any rows x cols, at least 4 x 4: then
its deviations are interpolated as a target relief, :func:`measured_easeoff_grid`) or
be scattered (missing points, irregular positions: :func:`measured_points`, the points
in space that :mod:`.point_fit` fits the settings at).

A measured point ``(L, R)`` is mapped onto the flank's parameters by solving
``(L(u, v), R(u, v)) = (L, R)`` (``scipy.optimize.root``, Powell hybrid method with the
analytic Jacobian from ``r_u``, ``r_v``), started from the nearest of 11 x 11 samples of
the box; the root is kept to 1e-11 mm in L and R.

References
----------
ANSI/AGMA 2009-B01 (bevel gear inspection: the flank topography grid).
J. J. Moré, B. S. Garbow, K. E. Hillstrom, *User guide for MINPACK-1*, ANL-80-74, 1980
(the hybrid method of ``scipy.optimize.root``).
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import root
from scipy.spatial import cKDTree

from ..validation import InputRangeError, read_text_file

__all__ = ["AXIS_FRAMES", "MEASURED_COLUMNS", "NOMINAL_COLUMNS", "MeasuringGrid",
           "MeasuredFlank", "MeasuredPoints", "measuring_grid", "flank_parameters_at",
           "read_measured_grid", "is_measured_header", "is_complete_grid",
           "measured_easeoff_grid", "measured_points", "check_on_blank",
           "check_deviation_size", "grid_values", "read_member_targets", "read_target_flank",
           "residual_rows", "RESIDUAL_COLUMNS", "target_grids"]

#: Body frame -> member axis frame (axis +Z): gear unchanged, pinion (X, Y, Z) = (y, z, x).
AXIS_FRAMES = {"pinion": np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]),
               "gear": np.eye(3)}
#: Columns of a measured deviation file (:func:`read_measured_grid`); ``row``, ``col``
#: may be added (grid indices, not used), any other column is refused.
MEASURED_COLUMNS = ("member", "flank", "L_mm", "R_mm", "deviation_um")
_INDEX_COLUMNS = ("row", "col")
#: Columns of the nominal measuring grid (:func:`measuring_grid`).
NOMINAL_COLUMNS = ("member", "flank", "row", "col", "L_mm", "R_mm", "x_mm", "y_mm", "z_mm",
                   "nx", "ny", "nz")
_ON_FLANK_MM = 1e-3     # slack of the active box (as GridEaseOff.check_covers)
_ROOT_TOL_MM = 1e-11    # |L, R residual| of an accepted root
_SAME_LINE_MM = 1e-6    # mapped u (or v) within this of each other: one grid line
_SAME_POINT_MM = 1e-3   # two measured points closer in L and R: one point given twice


@dataclass(frozen=True)
class MeasuringGrid:
    """The nominal measuring grid of one flank (arrays over the points, row-major:
    root -> tip rows, toe -> heel columns; 1-based indices; lengths mm)."""

    member: str
    flank: str
    row: np.ndarray
    col: np.ndarray
    u_mm: np.ndarray
    v_mm: np.ndarray
    L_mm: np.ndarray
    R_mm: np.ndarray
    xyz_mm: np.ndarray      # (n, 3), member axis frame
    normal: np.ndarray      # (n, 3), unit, out of the tooth


def _axis_point(surface, to_axis, u, v):
    """Point, r_u, r_v and normal at arrays (u, v) in the axis frame, each (..., 3)."""
    s = surface.evaluate(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
    return tuple(a @ to_axis.T for a in (s.r, s.r_u, s.r_v, s.n))


def measuring_grid(surface, *, member: str, flank: str, rows: int, cols: int) -> MeasuringGrid:
    """The nominal ``rows x cols`` measuring grid of ``surface`` (a flank in the body
    frame of ``member``, Surface contract), module docstring."""
    u = np.linspace(*surface.u_range, rows)
    v = np.linspace(*surface.v_range, cols)
    U, V = (a.ravel() for a in np.meshgrid(u, v, indexing="ij"))
    r, _, _, n = _axis_point(surface, AXIS_FRAMES[member], U, V)
    i, j = (a.ravel() + 1 for a in np.meshgrid(np.arange(rows), np.arange(cols), indexing="ij"))
    return MeasuringGrid(member=member, flank=flank, row=i, col=j, u_mm=U, v_mm=V,
                         L_mm=r[:, 2], R_mm=np.hypot(r[:, 0], r[:, 1]), xyz_mm=r, normal=n)


def _flank_range(surface, to_axis) -> str:
    """'L a..b mm, R c..d mm' of the flank's active box (21 x 21 samples)."""
    U, V = np.meshgrid(np.linspace(*surface.u_range, 21), np.linspace(*surface.v_range, 21))
    r = _axis_point(surface, to_axis, U.ravel(), V.ravel())[0]
    rad = np.hypot(r[:, 0], r[:, 1])
    return (f"L {r[:, 2].min():.4f}..{r[:, 2].max():.4f} mm, R {rad.min():.4f}.."
            f"{rad.max():.4f} mm")


def flank_parameters_at(surface, *, member: str, L_mm, R_mm, where: str, lines=None
                        ) -> tuple[np.ndarray, np.ndarray]:
    """The parameters (u, v) of the points of ``surface`` at axial positions ``L_mm``
    and radii ``R_mm`` (arrays, mm, member axis frame; module docstring).

    Raises
    ------
    InputRangeError
        A point with no flank point at its (L, R) inside the active box (1 um slack):
        the message names ``where``, the point's file line (``lines``, else its
        1-based index), L and R, and the flank's range.
    """
    to_axis = AXIS_FRAMES[member]
    (u0, u1), (v0, v1) = surface.u_range, surface.v_range
    su, sv = (a.ravel() for a in np.meshgrid(np.linspace(u0, u1, 11), np.linspace(v0, v1, 11)))
    sr = _axis_point(surface, to_axis, su, sv)[0]
    sL, sR = sr[:, 2], np.hypot(sr[:, 0], sr[:, 1])
    L_mm, R_mm = np.atleast_1d(np.asarray(L_mm, dtype=float)), np.atleast_1d(np.asarray(R_mm, dtype=float))
    out = np.empty((len(L_mm), 2))
    for k, (L, R) in enumerate(zip(L_mm, R_mm)):
        def residual(x, L=L, R=R):
            r, ru, rv, _ = (a[0] for a in _axis_point(surface, to_axis, x[:1], x[1:]))
            rad = math.hypot(r[0], r[1])
            jac = [[ru[2], rv[2]], [(r[0] * ru[0] + r[1] * ru[1]) / rad,
                                    (r[0] * rv[0] + r[1] * rv[1]) / rad]]
            return np.array([r[2] - L, rad - R]), np.array(jac)

        start = int(np.argmin((sL - L) ** 2 + (sR - R) ** 2))
        sol = root(residual, [su[start], sv[start]], jac=True, method="hybr",
                   options={"xtol": 1e-14})
        u, v = sol.x
        ok = (np.abs(residual(sol.x)[0]).max() < _ROOT_TOL_MM
              and u0 - _ON_FLANK_MM <= u <= u1 + _ON_FLANK_MM
              and v0 - _ON_FLANK_MM <= v <= v1 + _ON_FLANK_MM)
        if not ok:
            name = f"point {k + 1}" if lines is None else f"line {int(lines[k])}"
            raise InputRangeError(f"{where}: {name} (L = {float(L)!r} mm, R = {float(R)!r} mm)",
                                  "off the flank", f"a point on the {member} flank's active "
                                  f"box: {_flank_range(surface, to_axis)}")
        out[k] = u, v
    return out[:, 0], out[:, 1]


@dataclass(frozen=True)
class MeasuredFlank:
    """Measured deviations of one flank in machine coordinates (arrays over the points,
    file order; ``line`` the file line of each point)."""

    member: str
    flank: str
    L_mm: np.ndarray
    R_mm: np.ndarray
    deviation_um: np.ndarray
    line: np.ndarray


def _data_lines(text: str) -> list[tuple[int, list[str]]]:
    """(file line, cells) of the non-comment, non-blank CSV lines."""
    out = []
    for k, row in enumerate(csv.reader(io.StringIO(text)), start=1):
        if row and "".join(row).strip() and not row[0].lstrip().startswith("#"):
            out.append((k, [c.strip() for c in row]))
    return out


def is_measured_header(text: str) -> bool:
    """True if the first data line of ``text`` names a column only a measured file has
    (``member``, ``L_mm``, ``R_mm`` or ``deviation_um``: a measured file missing one of
    the others is then refused naming it, :func:`read_measured_grid`, not read as a
    (u, v) ease-off grid)."""
    lines = _data_lines(text)
    return bool(lines) and bool({"member", "L_mm", "R_mm", "deviation_um"}
                                & {h.strip() for h in lines[0][1]})


def read_measured_grid(path, *, members=("pinion", "gear"),
                       flanks=("drive", "coast")) -> dict:
    """A measured deviation file: ``{(member, flank): MeasuredFlank}``.

    CSV with ``#`` comment lines allowed, a header of the columns
    :data:`MEASURED_COLUMNS` in any order (``row``, ``col`` optional), then one line per
    point: the member and flank it belongs to, its nominal ``L_mm``, ``R_mm`` (module
    docstring) and ``deviation_um`` (positive = material added).

    Raises
    ------
    InputRangeError
        An unknown or missing column, a line of the wrong length, a non-numeric or
        non-finite number, an unknown member or flank, or a point given twice on a flank
        (two within 1 um in L and R; each names the file line), or no points.
    """
    text = read_text_file(path, field="target flank", what="a CSV measured grid")
    lines = _data_lines(text)
    if not lines:
        raise InputRangeError(f"{path}", "no header", ",".join(MEASURED_COLUMNS))
    k0, head = lines[0]
    allowed = set(MEASURED_COLUMNS) | set(_INDEX_COLUMNS)
    unknown = [h for h in head if h not in allowed]
    missing = [c for c in MEASURED_COLUMNS if c not in head]
    if unknown or missing or len(set(head)) != len(head):
        raise InputRangeError(f"{path}: header (line {k0}) columns",
                              ",".join(unknown or missing or head),
                              f"each of {','.join(MEASURED_COLUMNS)} once "
                              f"(optional {','.join(_INDEX_COLUMNS)})")
    col = {h: i for i, h in enumerate(head)}
    found: dict = {}
    for k, row in lines[1:]:
        if len(row) != len(head):
            raise InputRangeError(f"{path}: line {k}", ",".join(row), f"{len(head)} values "
                                  f"({','.join(head)})")
        member, flank = row[col["member"]], row[col["flank"]]
        if member not in members or flank not in flanks:
            raise InputRangeError(f"{path}: line {k} member, flank", f"{member}, {flank}",
                                  f"member one of {members}, flank one of {flanks}")
        values = []
        for c in MEASURED_COLUMNS[2:]:      # each number named by its column
            try:
                x = float(row[col[c]])
            except ValueError:
                x = None
            if x is None or not math.isfinite(x):
                raise InputRangeError(f"{path}: line {k} {c}", row[col[c]],
                                      "a finite number (mm; deviation_um in um)")
            values.append(x)
        L, R, d = values
        found.setdefault((member, flank), []).append((L, R, d, k))
    if not found:
        raise InputRangeError(f"{path}", "no points", "at least one measured point")
    out = {}
    for (member, flank), pts in found.items():
        L, R, d, k = (np.array(c) for c in zip(*pts))
        _check_distinct(L, R, k, where=f"{path}", name=f"{member} {flank}")
        out[member, flank] = MeasuredFlank(member=member, flank=flank, L_mm=L, R_mm=R,
                                           deviation_um=d, line=k)
    return out


def _check_distinct(L, R, line, *, where: str, name: str) -> None:
    """Refuse two points of a flank within :data:`_SAME_POINT_MM` of each other in both
    L and R (one point given twice: the fit would weigh it double, or two deviations
    contradict each other), naming the later line and the earlier."""
    pairs = cKDTree(np.column_stack([L, R])).query_pairs(_SAME_POINT_MM, p=np.inf,
                                                          output_type="ndarray")
    if len(pairs):
        i, j = sorted(pairs[np.argmin(pairs.max(axis=1))])
        raise InputRangeError(f"{where}: line {int(line[j])}", f"{name} L = {float(L[j])!r}, "
                              f"R = {float(R[j])!r} (also line {int(line[i])}: L = "
                              f"{float(L[i])!r}, R = {float(R[i])!r})",
                              f"each (L, R) once per flank: points more than "
                              f"{_SAME_POINT_MM} mm apart in L or R")


def _grid_lines(x: np.ndarray) -> np.ndarray:
    """Index of each value's grid line: values within :data:`_SAME_LINE_MM` are one."""
    order = np.argsort(x)
    line = np.cumsum(np.r_[0, np.diff(x[order]) > _SAME_LINE_MM])
    out = np.empty(len(x), dtype=int)
    out[order] = line
    return out


def measured_easeoff_grid(measured: MeasuredFlank, nominal, conjugate, easeoff, *,
                          where: str, uv=None):
    """The target relief of a measured pinion flank as a :class:`~.easeoff.GridEaseOff`.

    Parameters
    ----------
    measured : MeasuredFlank
        A pinion flank's deviations in machine coordinates.
    nominal : RadialSheet
        The pinion flank they are measured against (the pair's: ``conjugate`` eased by
        ``easeoff``).
    conjugate : RadialSheet
        The conjugate pinion flank the relief is measured from (:mod:`.easeoff`).
    easeoff : EaseOff
        The pair's ease-off of that flank.
    where : str
        Names the file in messages.
    uv : tuple of ndarray, optional
        The points' nominal parameters if known (:func:`flank_parameters_at`).

    Returns
    -------
    GridEaseOff
        On the grid ``(u_i, v_j)`` of the mapped points' parameters:
        ``E(u, v) = E_pair(u, v) - d(u', v')`` (um), ``(u', v')`` the nominal
        parameters of the eased image ``r - E_pair n`` of the conjugate point ``(u,
        v)`` and ``d`` the bicubic through the measured deviations over the nominal
        grid: the relief that moves that image by the deviation measured there. Both
        ends are along nearly the same normal (they differ by the slope of E_pair,
        ~1e-2 rad): the target passes within ~1e-4 |d| of the measured points.

    Raises
    ------
    InputRangeError
        A point off the flank (:func:`flank_parameters_at`), or mapped points that are
        not a complete grid of at least 4 x 4 lines of constant u and v.
    """
    from .easeoff import GridEaseOff

    u, v = uv if uv is not None else flank_parameters_at(
        nominal, member="pinion", L_mm=measured.L_mm, R_mm=measured.R_mm, where=where,
        lines=measured.line)
    if not is_complete_grid(u, v):
        nu, nv = _grid_lines(u).max() + 1, _grid_lines(v).max() + 1
        raise InputRangeError(f"{where}: pinion {measured.flank} points",
                              f"{len(u)} points on {nu} lines of constant u x {nv} of v",
                              "a complete grid of at least 4 x 4 (rows at constant height "
                              "over the root cone: the nominal grid of export flanks)")
    um, vm, dev = grid_values(u, v, measured.deviation_um)
    U, V = np.meshgrid(um, vm, indexing="ij")
    s = conjugate.evaluate(U, V)
    e_mm = easeoff.relief_mm(U, V)
    u_img, v_img, _ = nominal.locate(s.r - e_mm[..., None] * s.n)
    # the deviation field over the nominal (u, v): the bicubic of GridEaseOff
    d_um = 1e3 * GridEaseOff(u_mm=um, v_mm=vm, relief_um=dev).relief_mm(u_img, v_img)
    return GridEaseOff(u_mm=um, v_mm=vm, relief_um=1e3 * e_mm - d_um)


def grid_values(u, v, values) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(u_lines, v_lines, table)`` of values at the nodes ``(u, v)`` of a complete
    grid (:func:`is_complete_grid`): the increasing grid lines (each the mean of its
    nodes' parameter) and the values on them, shape (n_u, n_v)."""
    u, v = np.asarray(u), np.asarray(v)
    iu, iv = _grid_lines(u), _grid_lines(v)
    nu, nv = iu.max() + 1, iv.max() + 1
    table = np.empty((nu, nv))
    table[iu, iv] = values
    return (np.array([u[iu == i].mean() for i in range(nu)]),
            np.array([v[iv == j].mean() for j in range(nv)]), table)


def is_complete_grid(u, v) -> bool:
    """True if the parameters ``(u, v)`` (arrays, mm) are the nodes of a complete grid
    of at least 4 x 4 lines of constant u and v (:data:`_SAME_LINE_MM`), each once."""
    iu, iv = _grid_lines(np.asarray(u)), _grid_lines(np.asarray(v))
    nu, nv = iu.max() + 1, iv.max() + 1
    return bool(nu >= 4 and nv >= 4 and len(u) == nu * nv
                and len(set(zip(iu.tolist(), iv.tolist()))) == len(u))


@dataclass(frozen=True)
class MeasuredPoints:
    """Measured points of one flank on its member's sheet: the target of the point fit
    (:mod:`.point_fit`). Arrays over the points, file order.

    Attributes
    ----------
    side : str
    line : ndarray of int
        File line of each point.
    L_mm, R_mm, deviation_um : ndarray
        As read (:class:`MeasuredFlank`).
    u_mm, v_mm, psi_rad : ndarray
        Sheet parameters and angular coordinate of the measured point: the nominal point
        at (L, R) moved by the deviation along its normal (body frame; pinion
        :class:`~.sheet.PinionCone`, gear :class:`~.sheet.GearCone`).
    lever_um : ndarray
        ``1e3 R (e_psi . n)`` there with the nominal normal n, um per rad: a flank
        turned by ``dpsi`` about the axis moves ``lever_um * dpsi`` along n.
    box : FlankBoundary
        Pinion: the nominal flank's active box (the points lie on it, 1 um slack);
        gear: the points' extent on the gear sheet (the node box of the fit's
        continuation grid).
    member : str
        ``"pinion"`` or ``"gear"``.
    """

    side: str
    line: np.ndarray
    L_mm: np.ndarray
    R_mm: np.ndarray
    deviation_um: np.ndarray
    u_mm: np.ndarray
    v_mm: np.ndarray
    psi_rad: np.ndarray
    lever_um: np.ndarray
    box: object
    member: str = "pinion"


#: Columns of the residual at measured points (:func:`residual_rows`).
RESIDUAL_COLUMNS = "member,flank,line,L_mm,R_mm,deviation_um,u_mm,v_mm,residual_um"


def residual_rows(points: MeasuredPoints, residual_um) -> list[str]:
    """CSV rows (:data:`RESIDUAL_COLUMNS`) of the residual at each measured point: the
    file's member, flank, line, L, R and deviation, the point's sheet parameters and
    ``residual_um`` (the cut flank minus the measured point along the nominal normal:
    positive = material left), floats by ``repr``."""
    p = points
    return [f"{p.member},{p.side},{int(k)},{float(L)!r},{float(R)!r},{float(d)!r},"
            f"{float(u)!r},{float(v)!r},{float(e)!r}" for k, L, R, d, u, v, e in
            zip(p.line, p.L_mm, p.R_mm, p.deviation_um, p.u_mm, p.v_mm, residual_um)]


def measured_points(measured: MeasuredFlank, nominal, *, where: str, uv=None, cone=None
                    ) -> MeasuredPoints:
    """The measured points of a flank as points in space: each nominal point at its
    (L, R) (:func:`flank_parameters_at`; ``uv`` its parameters if known) moved by the
    deviation along the nominal normal (the point the probe touched), located on the
    pinion sheet of ``nominal`` (a :class:`~.sheet.RadialSheet`), or for a gear flank
    (``measured.member``; ``nominal`` any gear flank, formate or generated) on the
    gear sheet ``cone`` (:class:`~.sheet.GearCone`: ``(u, v)`` from the point's height
    and radius, ``psi`` its angle about the gear axis)."""
    u, v = uv if uv is not None else flank_parameters_at(
        nominal, member=measured.member, L_mm=measured.L_mm, R_mm=measured.R_mm,
        where=where, lines=measured.line)
    s = nominal.evaluate(u, v, second=False)
    q = s.r + 1e-3 * measured.deviation_um[:, None] * s.n
    if measured.member == "gear":
        from .formate import FlankBoundary
        from .member_envelope import angle_lever

        uq, vq = cone.parameters(q[:, 2], np.hypot(q[:, 0], q[:, 1]))
        psi, lever = angle_lever("gear", q, s.n)
        return MeasuredPoints(side=measured.flank, line=measured.line, L_mm=measured.L_mm,
                              R_mm=measured.R_mm, deviation_um=measured.deviation_um,
                              u_mm=uq, v_mm=vq, psi_rad=psi, lever_um=lever,
                              box=FlankBoundary(float(uq.min()), float(uq.max()),
                                                float(vq.min()), float(vq.max())),
                              member="gear")
    uq, vq, psi = nominal.locate(q)
    rad = np.hypot(q[:, 1], q[:, 2])
    lever = 1e3 * rad * (-np.sin(psi) * s.n[:, 1] + np.cos(psi) * s.n[:, 2])
    return MeasuredPoints(side=measured.flank, line=measured.line, L_mm=measured.L_mm,
                          R_mm=measured.R_mm, deviation_um=measured.deviation_um, u_mm=uq,
                          v_mm=vq, psi_rad=psi, lever_um=lever, box=nominal.boundary)


def check_on_blank(grids: dict, pair, *, where: str) -> None:
    """Refuse, before any flank is built, a measured pinion point (:class:`MeasuredFlank`
    values of ``grids``) outside the pinion blank's nominal flank box (clearance line to
    tip over the face width, :func:`~.conjugate.nominal_pinion_box`, which holds every
    active box), 1 um slack; the message names the file line, L, R and the blank's
    range at that L. Its parameters are the sheet's closed form ``v = L``,
    ``u = R - R_f(L)`` (:class:`~.sheet.PinionCone`)."""
    from .conjugate import nominal_pinion_box

    cone, box = nominal_pinion_box(pair.blank, pair.pinion_face_width_mm)
    for side, data in grids.items():
        if not isinstance(data, MeasuredFlank):
            continue
        u, v = cone.parameters(data.L_mm, data.R_mm)
        off = ((u < box.u_root - _ON_FLANK_MM) | (u > box.u_tip + _ON_FLANK_MM)
               | (v < box.v_toe - _ON_FLANK_MM) | (v > box.v_heel + _ON_FLANK_MM))
        if off.any():
            k = int(np.argmax(off))
            L, R = float(data.L_mm[k]), float(data.R_mm[k])
            r0, r1 = (float(cone.radius_mm(x, min(max(L, box.v_toe), box.v_heel)))
                      for x in (box.u_root, box.u_tip))
            raise InputRangeError(
                f"{where}: line {int(data.line[k])} (pinion {side}, L = {L!r} mm, R = {R!r} mm)",
                "off the flank of the pinion blank", f"L {box.v_toe:.4f}..{box.v_heel:.4f} mm and "
                f"R {r0:.4f}..{r1:.4f} mm at that L (clearance line to tip)")


def check_deviation_size(grids: dict, pair, *, where: str) -> None:
    """Refuse, before any flank is built, a measured deviation (:class:`MeasuredFlank`
    values of ``grids``, either member) of at least a quarter of the blank's mean normal
    circular pitch, ``pi m_mn / 4`` (half a tooth's thickness: the probed point lies
    on the next tooth or in the slot, not on the measured flank; a wrong nominal or a
    unit slip), naming the file line and the value."""
    limit_um = 1e3 * math.pi * pair.blank.mean_normal_module_mm / 4.0
    for side, data in grids.items():
        if not isinstance(data, MeasuredFlank):
            continue
        big = np.abs(data.deviation_um) >= limit_um
        if big.any():
            k = int(np.argmax(big))
            raise InputRangeError(f"{where}: line {int(data.line[k])} ({data.member} "
                                  f"{data.flank}) deviation_um", float(data.deviation_um[k]),
                                  f"|deviation| < {limit_um:.0f} um, pi m_mn / 4 (half the "
                                  "tooth: a larger one lies on the next tooth or in the "
                                  "slot; um, not mm)")


def read_target_flank(path, *, pair=None) -> dict:
    """A ``--target-flank`` file, its format told by its header: ``{side: grid}``.

    A header with ``L_mm`` and ``R_mm`` is a measured file in machine coordinates
    (:func:`read_measured_grid`, pinion flanks only: the settings fit corrects the
    pinion), its values :class:`MeasuredFlank` (mapped onto the flanks by
    :func:`target_grids` once they are built); any other is a deviation grid in the
    flank's (u, v) (:func:`~.easeoff.read_easeoff_grid`), its values
    :class:`~.easeoff.GridEaseOff`. With ``pair``, measured points are checked
    against its pinion blank (:func:`check_on_blank`), every deviation against the
    blank's tooth (:func:`check_deviation_size`).

    Raises
    ------
    InputRangeError
        As the reader of the format, or a measured point off the blank's flank.
    """
    from .easeoff import read_easeoff_grid

    text = read_text_file(path, field="target flank", what="a CSV deviation grid")
    if not is_measured_header(text):
        return read_easeoff_grid(path)
    grids = {side: m for (_, side), m in read_measured_grid(path, members=("pinion",)).items()}
    if pair is not None:
        check_deviation_size(grids, pair, where=str(path))
        check_on_blank(grids, pair, where=str(path))
    return grids


def read_member_targets(path, *, pair=None) -> tuple[dict, dict]:
    """A ``--target-flank`` file whose rows may name either member: ``(pinion, gear)``.

    ``pinion`` is :func:`read_target_flank`'s ``{side: grid}`` of the pinion rows (a
    (u, v) ease-off grid is the pinion's), ``gear`` the ``{side: MeasuredFlank}`` of
    the gear rows of a measured file (:func:`read_measured_grid` with both members:
    the gear's setting correction, :mod:`.gear_correction`). With ``pair``, measured
    pinion points are checked against its pinion blank (:func:`check_on_blank`), every
    deviation against the blank's tooth (:func:`check_deviation_size`).

    Raises
    ------
    InputRangeError
        As :func:`read_target_flank` (an unknown member is named with the two allowed).
    """
    from .easeoff import read_easeoff_grid

    text = read_text_file(path, field="target flank", what="a CSV deviation grid")
    if not is_measured_header(text):
        return read_easeoff_grid(path), {}
    found = read_measured_grid(path)
    pinion = {side: m for (member, side), m in found.items() if member == "pinion"}
    gear = {side: m for (member, side), m in found.items() if member == "gear"}
    if pair is not None:
        check_deviation_size(found, pair, where=str(path))
        check_on_blank(pinion, pair, where=str(path))
    return pinion, gear


def target_grids(grids: dict, pair, flanks, *, where: str = "target flank",
                 as_points: tuple = ()) -> dict:
    """``grids`` (:func:`read_target_flank`) with every :class:`MeasuredFlank` mapped
    onto the pinion flank of ``flanks`` (built for ``pair``) it was measured against:
    points on a complete grid (:func:`is_complete_grid`) as a target relief
    (:func:`measured_easeoff_grid` with the pair's ease-off of that side), scattered
    points, and every point of the sides ``as_points`` (a flank cut with a relieved
    blade: no spline across its kink), as :class:`MeasuredPoints`
    (:func:`measured_points`)."""
    from .easeoff import EaseOff

    out = dict(grids)
    for side, data in grids.items():
        if not isinstance(data, MeasuredFlank):
            continue
        nominal, at = flanks.pinion.side(side), f"{where} {side}"
        uv = flank_parameters_at(nominal, member="pinion", L_mm=data.L_mm, R_mm=data.R_mm,
                                 where=at, lines=data.line)
        if side in as_points or not is_complete_grid(*uv):
            out[side] = measured_points(data, nominal, where=at, uv=uv)
            continue
        u_m, v_m = flanks.mean_contact[side]["pinion_uv"]
        easeoff = EaseOff.from_coefficients(getattr(pair, f"easeoff_{side}"),
                                            u_mean_mm=u_m, v_mean_mm=v_m)
        out[side] = measured_easeoff_grid(data, nominal, flanks.pinion_conjugate.side(side),
                                          easeoff, where=at, uv=uv)
    return out
