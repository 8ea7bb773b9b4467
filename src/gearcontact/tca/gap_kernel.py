"""Compiled (numba) line-surface intersections behind the gap fields of :mod:`.stencil`.

:func:`gearcontact.tca.stencil.gap_at` intersects, for every tangent-plane sample, the
normal line ``q + lambda n`` with both posed flanks by Newton's method on
``R r(u, v) + c - q - lambda n = 0``. For the flanks of :mod:`gearcontact.geometry`
this module runs that iteration (same update, clamping and stopping rule) per line in
compiled code, with the surfaces evaluated as their ``evaluate`` methods do:

* :class:`~gearcontact.geometry.sheet.RadialSheet` (pinion): the quintic
  tensor-product spline of ``psi(u, v)`` and its first derivatives from its
  piecewise-polynomial form (:attr:`~gearcontact.geometry.sheet.RadialSheet.pp_arrays`,
  :func:`gearcontact.geometry.spline_kernel.pp_point`; arguments clamped to the knot
  box as FITPACK does), then ``r = (v, R cos psi, R sin psi)``,
  ``r_u``, ``r_v`` (:func:`~gearcontact.geometry.sheet.sheet_vector`);
* :class:`~gearcontact.geometry.sheet.GearSheet` (a piece of a relieved generated
  gear, below; a smooth one keeps the numpy path, :func:`kernel_surface`): the same
  spline, then ``r = (R cos psi, R sin psi, z)`` and its derivatives
  (:func:`~gearcontact.geometry.sheet.gear_sheet_vector`; ``cos psi``, ``sin psi``
  compiled where ``evaluate`` takes numpy's);
* :class:`~gearcontact.geometry.formate.FormateFlank` (gear): the blade cone, a circular
  cone, which a line meets where a quadratic vanishes (:func:`cone_lines`: no Newton;
  the root nearest the tangent plane; (u, v) back from the point by the inverse of
  :func:`~gearcontact.geometry.formate.cone_vector`).

Three things make it converge in fewer steps without moving any root: each line starts
from the tangent-plane prediction at an already solved neighbour (order given by the
caller); beyond the knot box the Jacobian uses the derivative of FITPACK's constant
continuation (zero), so continuation points converge quadratically; with clamping, a
line pinned to one edge of the box is given up early (:data:`PINNED_ITERATIONS`).

* :class:`~gearcontact.geometry.kinked.KinkedFlank` of radial sheets (a pinion cut by
  a relieved blade) or of generated gear sheets (a generated gear cut by one): the same
  Newton iteration, every iterate evaluated on the piece
  that holds it, as :meth:`~gearcontact.geometry.kinked.KinkedFlank.evaluate` picks it
  (:func:`~gearcontact.geometry.kinked.kink_piece`, the same compiled function: the
  number of kink lines ``u = u_k(v)`` below ``(u, v)``, each the piecewise cubic of
  :attr:`~gearcontact.geometry.kinked.KinkLine.pp_table`). The step that ends Newton
  without a confirming evaluation is only taken when it stays on the evaluated piece
  (across a kink the other piece's continuation differs to first order in the step).

* :class:`~gearcontact.geometry.kinked.KinkedFlank` of blade cones (a formate gear cut
  by a relieved blade; piece ``k`` the cone at ``(u, scale_k v)``): every cone in
  closed form, the root kept whose ``(u, v)`` its own piece holds
  (:func:`cone_piece_lines`).

Other surfaces (analytic test surfaces, subclasses of these types, sheet pieces at
scaled ``v``) have no compiled form (:func:`kernel_surface` returns None) and use the vectorized numpy path
of :mod:`.stencil`. Results agree with that path to rounding (~1e-13 mm;
tests/tca/test_gap_kernel.py asserts 1e-9 mm). :func:`flank_vector` evaluates a kernel
form at one point as the flank's ``point`` does (the compiled ridge search of
:mod:`.edge_kernel`).

A surface is passed to the kernel as ``(kind, par, tx, ty, pc, kink_x, kink_c,
kink_n)``: ``kind`` 0 (radial sheet), 1 (cone) or 2 (generated gear sheet); per piece (first axis; one for a smooth
flank) a float parameter vector (a cone's with its ``v`` scale last) and the spline
arrays (knots and piecewise-polynomial coefficients of
:mod:`gearcontact.geometry.spline_kernel`; empty for a cone); per kink line (first
axis; none for a smooth flank) its breaks, cubic coefficients and break count
(:attr:`~gearcontact.geometry.kinked.KinkedFlank.kink_tables`).
"""

from __future__ import annotations

import weakref

import numpy as np
from numba import njit

from ..geometry.formate import FormateFlank, cone_vector
from ..geometry.kinked import KinkedFlank, kink_piece
from ..geometry.sheet import GearSheet, RadialSheet, gear_sheet_vector, sheet_vector
from ..geometry.spline_kernel import pp_point

__all__ = ["KIND_SHEET", "KIND_CONE", "KIND_GEAR_SHEET", "kernel_surface", "intersect_lines", "cone_lines",
           "cone_piece_lines", "flank_vector", "solve3"]

#: Surface kinds of the kernel.
KIND_SHEET = 0
KIND_CONE = 1
KIND_GEAR_SHEET = 2
#: With clamping, a line whose Newton target leaves the box across the same edge in
#: this many successive iterations after the first (every iterate clipped onto that
#: edge) is given up as off the flank - where the full iteration ends anyway.
PINNED_ITERATIONS = 3
#: Residual (mm) below which Newton is in its quadratic basin on the flanks (curvature
#: radii >= ~1 mm, parameter steps ~ residuals) ...
BASIN_MM = 1e-5
#: ... and the parameter / line step (mm) that ends it there without a confirming
#: evaluation: the error left is of order FINAL_STEP^2 |r''| / 2 (<= ~1e-12 mm for
#: flank curvatures <= 1/mm), below the line tolerance (1e-11 mm by default).
FINAL_STEP = 1e-6
_EMPTY2 = np.zeros((1, 0))
_EMPTY5 = np.zeros((1, 0, 0, 0, 0))
#: The kink tables of a smooth flank: no kink line.
_NO_KINKS = (np.zeros((0, 2)), np.zeros((0, 1, 4)), np.zeros(0, dtype=np.int64))
_CACHE: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()
#: Kernel kinds of the spline sheets.
_SHEET_KINDS = {RadialSheet: KIND_SHEET, GearSheet: KIND_GEAR_SHEET}


def kernel_surface(surface):
    """The kernel form ``(kind, par, tx, ty, pc, kink_x, kink_c, kink_n)`` of a
    flank (module docstring), or None.

    Sheet ``par[k]``: ``(kx, ky, apex_x, tan_delta, root_offset)`` of piece ``k``;
    generated gear sheet: ``(kx, ky, cos_delta, sin_delta, R2, h_f, z_A)``; cone
    ``par[k]``: :attr:`~gearcontact.geometry.formate.FormateFlank.kernel_parameters` of
    piece ``k`` and its ``v`` scale (19 entries; 1 for a smooth flank). A
    :class:`~gearcontact.geometry.kinked.KinkedFlank` has a form when its pieces are
    radial sheets or generated gear sheets on one knot grid (as
    :func:`~gearcontact.geometry.kinked.machine_flank` builds them) with ``v_scales`` 1,
    or blade cones (a relieved formate gear) with any ``v_scales``. A smooth generated
    gear sheet has none: a pair without machine settings whose formate gear would
    undercut its pinion runs on one (:mod:`gearcontact.geometry.gear_generation`), and
    its results stay those of the numpy path bit for bit.
    """
    try:
        return _CACHE[surface]
    except (KeyError, TypeError):
        pass
    if type(surface) is RadialSheet:
        par, tx, ty, pc = _sheet_arrays(surface)
        out = (KIND_SHEET, par[None], tx[None], ty[None], pc[None], *_NO_KINKS)
    elif type(surface) is FormateFlank:
        out = (KIND_CONE, _cone_arrays(surface, 1.0)[None], _EMPTY2, _EMPTY2, _EMPTY5,
               *_NO_KINKS)
    elif type(surface) is KinkedFlank:
        out = _kinked_form(surface)
        if out is None:
            return None
    else:
        return None
    _CACHE[surface] = out
    return out


def _sheet_arrays(sheet: RadialSheet) -> tuple:
    """``(par, tx, ty, pc)`` of one radial or generated gear sheet (:func:`kernel_surface`)."""
    tx, ty, pc, kx, ky = sheet.pp_arrays
    cone = sheet.cone
    if type(sheet) is GearSheet:
        par = np.array([kx, ky, cone.cos_delta, cone.sin_delta, cone.mean_cone_distance_mm,
                        cone.dedendum_mm, cone.apex_z_mm], float)
    else:
        par = np.array([kx, ky, cone.apex_x_mm, cone.tan_delta, cone.root_offset_mm], float)
    return par, tx, ty, pc


def _cone_arrays(cone: FormateFlank, scale: float) -> np.ndarray:
    """``par`` of one blade cone evaluated at ``scale v`` (:func:`kernel_surface`)."""
    return np.append(cone.kernel_parameters, float(scale))


def _kinked_form(flank: KinkedFlank):
    """The kernel form of a relieved flank of blade cones, or of radial (generated gear)
    sheets on one knot grid, else None (:func:`kernel_surface`)."""
    if all(type(p) is FormateFlank for p in flank.pieces):
        par = np.stack([_cone_arrays(p, sc) for p, sc in zip(flank.pieces, flank.v_scales)])
        return (KIND_CONE, par, _EMPTY2, _EMPTY2, _EMPTY5, *flank.kink_tables)
    kinds = {type(p) for p in flank.pieces}
    if (len(kinds) != 1 or next(iter(kinds)) not in _SHEET_KINDS
            or any(s != 1.0 for s in flank.v_scales)):
        return None
    arrays = [_sheet_arrays(p) for p in flank.pieces]
    if len({tuple(a.shape for a in got) for got in arrays}) != 1:
        return None
    return (_SHEET_KINDS[kinds.pop()], *(np.stack([got[j] for got in arrays])
                                          for j in range(4)), *flank.kink_tables)


@njit(cache=True, inline="always")
def sheet_point(par, tx, ty, pc, u, v, d, vec):
    """r, r_u, r_v of a radial sheet into ``vec[0:3]`` (``d``: (6,) scratch). psi is
    FITPACK's clamped continuation beyond the knot box, with zero derivatives there."""
    pp_point(tx, ty, pc, int(par[0]), int(par[1]), u, v, 1, True, d)
    sheet_vector(u, v, d, par[2], par[3], par[4], 1.0, False, vec)


@njit(cache=True, inline="always")
def gear_sheet_point(par, tx, ty, pc, u, v, nder, zero_outside, d, vec):
    """r, r_u, r_v of a generated gear sheet into ``vec[0:3]`` (psi to the order
    ``nder``, ``zero_outside`` as :func:`~gearcontact.geometry.spline_kernel.pp_point`)."""
    pp_point(tx, ty, pc, int(par[0]), int(par[1]), u, v, nder, zero_outside, d)
    gear_sheet_vector(u, v, d, np.cos(d[0]), np.sin(d[0]), par[2], par[3], par[4], par[5],
                      par[6], 1.0, False, vec)


@njit(cache=True)
def flank_vector(kind, par, tx, ty, pc, kink_x, kink_c, kink_n, u, v, d, vec):
    """r, r_u, r_v of a flank in kernel form (:func:`kernel_surface`) at ``(u, v)``
    into ``vec[0:3]`` (``d``: (6,) scratch), as its ``point`` method gives them: the
    piece that holds the point (:func:`~gearcontact.geometry.kinked.kink_piece`), a
    cone at ``(u, scale v)`` with ``r_v`` times the scale
    (:meth:`~gearcontact.geometry.kinked.KinkedFlank.point`), a sheet's psi and its
    first derivatives from the spline's second-order evaluation without the zero
    continuation derivatives (:meth:`~gearcontact.geometry.sheet.RadialSheet.point`;
    a generated gear sheet's ``cos psi``, ``sin psi`` compiled where its ``point`` takes
    numpy's).
    """
    k = kink_piece(kink_x, kink_c, kink_n, u, v) if kink_x.shape[0] > 0 else 0
    if kind == KIND_CONE:
        scale = par[k, 18]
        cone_vector(par[k], u, scale * v, False, vec)
        for a in range(3):
            vec[2, a] = scale * vec[2, a]
    elif kind == KIND_GEAR_SHEET:
        gear_sheet_point(par[k], tx[k], ty[k], pc[k], u, v, 2, False, d, vec)
    else:
        pp_point(tx[k], ty[k], pc[k], int(par[k, 0]), int(par[k, 1]), u, v, 2, False, d)
        sheet_vector(u, v, d, par[k, 2], par[k, 3], par[k, 4], 1.0, False, vec)


@njit(cache=True)
def solve3(a, b, x):
    """x = a^-1 b for a 3 x 3 system (Gaussian elimination, partial pivoting).
    Overwrites ``a`` and ``b``."""
    for col in range(3):
        piv = col
        for r in range(col + 1, 3):
            if abs(a[r, col]) > abs(a[piv, col]):
                piv = r
        if piv != col:
            for j in range(3):
                tmp = a[col, j]
                a[col, j] = a[piv, j]
                a[piv, j] = tmp
            tmp = b[col]
            b[col] = b[piv]
            b[piv] = tmp
        for r in range(col + 1, 3):
            f = a[r, col] / a[col, col]
            for j in range(col, 3):
                a[r, j] -= f * a[col, j]
            b[r] -= f * b[col]
    for r in range(2, -1, -1):
        acc = b[r]
        for j in range(r + 1, 3):
            acc -= a[r, j] * x[j]
        x[r] = acc / a[r, r]


@njit(cache=True, inline="always")
def _cone_root(par, scale, nb, rot, trans, qi, v0):
    """``(lambda, u, v)`` of the line ``qi + lambda n`` (``nb``: ``n`` in the body frame
    ``rot^T n``) on one posed blade cone evaluated at ``scale v`` (:func:`cone_lines`),
    NaNs where it meets none."""
    rho0, k, ded, kv = par[12], par[13], par[14], par[15]
    hm = nb[0] * par[3] + nb[1] * par[4] + nb[2] * par[5]
    pm0 = nb[0] - hm * par[3]
    pm1 = nb[1] - hm * par[4]
    pm2 = nb[2] - hm * par[5]
    rk = k * hm
    aa = pm0 * pm0 + pm1 * pm1 + pm2 * pm2 - rk * rk
    # body frame: x = rot^T (q - trans), w0 = x - C
    w00 = (rot[0, 0] * (qi[0] - trans[0]) + rot[1, 0] * (qi[1] - trans[1])
           + rot[2, 0] * (qi[2] - trans[2]) - par[0])
    w01 = (rot[0, 1] * (qi[0] - trans[0]) + rot[1, 1] * (qi[1] - trans[1])
           + rot[2, 1] * (qi[2] - trans[2]) - par[1])
    w02 = (rot[0, 2] * (qi[0] - trans[0]) + rot[1, 2] * (qi[1] - trans[1])
           + rot[2, 2] * (qi[2] - trans[2]) - par[2])
    h0 = w00 * par[3] + w01 * par[4] + w02 * par[5]
    p00 = w00 - h0 * par[3]
    p01 = w01 - h0 * par[4]
    p02 = w02 - h0 * par[5]
    r0 = rho0 + k * h0
    bb = 2.0 * (p00 * pm0 + p01 * pm1 + p02 * pm2 - rk * r0)
    cc = p00 * p00 + p01 * p01 + p02 * p02 - r0 * r0
    disc = bb * bb - 4.0 * aa * cc
    if disc < 0.0:
        return np.nan, np.nan, np.nan
    qq = -0.5 * (bb + np.copysign(np.sqrt(disc), bb))
    best = np.nan
    for lam in (qq / aa if aa != 0.0 else np.nan, cc / qq if qq != 0.0 else np.nan):
        if np.isfinite(lam) and r0 + rk * lam > 0.0 and not abs(lam) >= abs(best):
            best = lam
    if not np.isfinite(best):
        return np.nan, np.nan, np.nan
    u = ded - (h0 + hm * best)
    px = p00 + best * pm0
    py = p01 + best * pm1
    pz = p02 + best * pm2
    theta = np.arctan2(px * par[9] + py * par[10] + pz * par[11],
                       px * par[6] + py * par[7] + pz * par[8])
    t0 = kv * (scale * v0)
    theta = t0 + (theta - t0 + np.pi) % (2.0 * np.pi) - np.pi
    return best, u, theta / kv / scale


@njit(cache=True)
def cone_lines(par, rot, trans, q, n, uv0, lo, hi, clamp, uv_out):
    """Closed-form intersections of the lines ``q_i + lambda n`` with a posed blade
    cone (``par``: :attr:`~gearcontact.geometry.formate.FormateFlank.kernel_parameters`).

    In the body frame a cone point ``w = x - C`` has height ``h = w.a`` along the axis
    and radius ``|w - h a| = rho_0 + k h``; along a line ``w = w_0 + lambda m`` squaring
    gives ``A lambda^2 + B lambda + C = 0``, solved in the cancellation-free form
    (Press et al., *Numerical Recipes*, 3rd ed., sec. 5.6). Of the roots on the nappe
    (``rho_0 + k h > 0``) the one nearest ``lambda = 0`` (the tangent plane) is taken;
    ``u = dedendum - h``, ``v = theta / k_v`` with the polar angle ``theta`` of the
    point about the axis taken nearest ``k_v uv0[i, 1]``. Returns as
    :func:`intersect_lines` (``uv_out`` (N, 2): ``(u, v)`` of every line's root, NaN
    where it has none).
    """
    pieces = np.empty((1, 19))
    pieces[0, :18] = par[:18]
    pieces[0, 18] = 1.0
    return cone_piece_lines(pieces, np.zeros((0, 2)), np.zeros((0, 1, 4)),
                            np.zeros(0, dtype=np.int64), rot, trans, q, n, uv0, lo, hi,
                            clamp, uv_out)


@njit(cache=True)
def cone_piece_lines(par, kink_x, kink_c, kink_n, rot, trans, q, n, uv0, lo, hi, clamp,
                     uv_out):
    """:func:`cone_lines` on a flank of blade cones (``par`` (P, 19): each piece's
    kernel parameters and its ``v`` scale, :func:`kernel_surface`) separated by kink
    lines (one cone: none).

    Piece ``k`` is the cone evaluated at ``(u, scale_k v)``: each line meets each cone
    in closed form (``theta`` taken nearest ``k_v scale_k uv0[i, 1]``, then
    ``v = theta / k_v / scale_k``), and a root counts where the piece that holds its
    ``(u, v)`` (:func:`~gearcontact.geometry.kinked.kink_piece`) is its own cone. The
    tooth is the intersection of what the segment blades leave (a convex ridge at each
    kink), so a line entering it crosses exactly one piece where that piece holds the
    point (the other cones it meets outside their pieces); of several (a line within
    the kink lines' interpolation error of the ridge) the one nearest the tangent plane
    is taken, and none there leaves the line unsolved, as Newton's iteration on the
    pieces does when it alternates across the kink.
    """
    m = q.shape[0]
    lam_out = np.full(m, np.nan)
    inside = np.zeros(m, dtype=np.bool_)
    uv_out[:, :] = np.nan
    nb = np.empty(3)
    for a in range(3):
        nb[a] = rot[0, a] * n[0] + rot[1, a] * n[1] + rot[2, a] * n[2]
    several = par.shape[0] > 1
    for i in range(m):
        best = np.nan
        bu = np.nan
        bv = np.nan
        for k in range(par.shape[0]):
            lam, u, v = _cone_root(par[k], par[k, 18], nb, rot, trans, q[i], uv0[i, 1])
            if not np.isfinite(lam):
                continue
            if several and kink_piece(kink_x, kink_c, kink_n, u, v) != k:
                continue
            if not abs(lam) >= abs(best):
                best = lam
                bu = u
                bv = v
        if not np.isfinite(best):
            continue
        uv_out[i, 0] = bu
        uv_out[i, 1] = bv
        ins = lo[0] < bu < hi[0] and lo[1] < bv < hi[1]
        inside[i] = ins
        if ins or not clamp:
            lam_out[i] = best
    return lam_out, inside


@njit(cache=True)
def intersect_lines(kind, par, tx, ty, pc, kink_x, kink_c, kink_n, rot, trans, q, n,
                    uv0, lo, hi, clamp, tol_mm, max_iter, order, prev, uv_out):
    """Intersections of the lines ``q_i + lambda n`` with a posed surface: Newton on a
    sheet, :func:`cone_lines` (closed form) on a cone.

    Parameters
    ----------
    kind, par, tx, ty, pc, kink_x, kink_c, kink_n
        Kernel form of the surface (:func:`kernel_surface`): its pieces and kink lines.
    rot, trans : ndarray (3, 3), (3,)
        Pose ``x -> rot x + trans`` of the surface.
    q : ndarray (N, 3)
        Points of the lines; ``n`` (3,) their common direction.
    uv0 : ndarray (N, 2)
        Starting parameters (with ``lambda = 0``).
    lo, hi : ndarray (2,)
        Parameter box; with ``clamp`` every iterate is clipped into it.
    tol_mm : float
        Residual tolerance; an iteration also has to move the parameters < 1e-12.
    max_iter : int
        Iteration limit.
    order, prev : ndarray (N,) of int
        Lines are solved in the sequence ``order``; line ``i`` starts instead from the
        tangent-plane prediction at the solution of line ``prev[i]`` (solved earlier)
        if that converged (inside the box, with ``clamp``); ``-1``: no predecessor.
    uv_out : ndarray (N, 2)
        Filled with the parameters of every converged intersection (NaN elsewhere).

    Returns
    -------
    lam : ndarray (N,)
        Line parameter of the intersection (NaN where Newton did not converge or, with
        ``clamp``, where it lies outside the box).
    inside : ndarray (N,) of bool
        Converged strictly inside the box.

    Notes
    -----
    With ``clamp`` a line pinned to one edge of the box (:data:`PINNED_ITERATIONS`)
    stops early as not converged: its intersection lies beyond that edge.
    Beyond the knot box a sheet's psi is FITPACK's constant extension; its derivative
    there is taken as zero (consistent), so such continuation points converge
    quadratically too.
    """
    if kind == KIND_CONE:
        return cone_piece_lines(par, kink_x, kink_c, kink_n, rot, trans, q, n, uv0, lo, hi,
                                clamp, uv_out)
    m = q.shape[0]
    kinked = kink_x.shape[0] > 0
    piece = 0
    lam_out = np.empty(m)
    inside = np.zeros(m, dtype=np.bool_)
    ok = np.zeros(m, dtype=np.bool_)
    sol = np.empty((m, 3))        # converged (u, v, lambda)
    tang = np.empty((m, 6))       # posed r_u, r_v there
    pred = np.empty((m, 3))       # tangent-plane prediction of (u, v, lambda)
    has_pred = np.zeros(m, dtype=np.bool_)
    dpsi = np.zeros(6)
    vec = np.empty((7, 3))
    jac = np.empty((3, 3))
    rhs = np.empty(3)
    step = np.empty(3)
    x = np.empty(3)
    for i in order:
        u = uv0[i, 0]
        v = uv0[i, 1]
        lam = 0.0
        p = prev[i]
        if p >= 0 and ok[p]:
            for a in range(3):
                jac[a, 0] = tang[p, a]
                jac[a, 1] = tang[p, 3 + a]
                jac[a, 2] = -n[a]
                rhs[a] = q[i, a] - q[p, a]
            solve3(jac, rhs, step)
            u = sol[p, 0] + step[0]
            v = sol[p, 1] + step[1]
            lam = sol[p, 2] + step[2]
            pred[i, 0] = u
            pred[i, 1] = v
            pred[i, 2] = lam
            has_pred[i] = True
            # on a straight, evenly spaced chain pp -> p -> i the tangent-plane
            # prediction errs by about what it erred from pp to p (the second-order
            # term): adding that makes the start third-order accurate
            pp = prev[p]
            if has_pred[p] and pp >= 0:
                same = True
                for a in range(3):
                    d1 = q[i, a] - q[p, a]
                    d0 = q[p, a] - q[pp, a]
                    if abs(d1 - d0) > 1e-9 * (abs(d1) + abs(d0)) + 1e-15:
                        same = False
                if same:
                    u += sol[p, 0] - pred[p, 0]
                    v += sol[p, 1] - pred[p, 1]
                    lam += sol[p, 2] - pred[p, 2]
            if clamp:
                u = min(max(u, lo[0]), hi[0])
                v = min(max(v, lo[1]), hi[1])
        converged = False
        pinned = 0
        last_side = 0
        side = 0
        for _ in range(max_iter):
            if kinked:
                piece = kink_piece(kink_x, kink_c, kink_n, u, v)
            if kind == KIND_GEAR_SHEET:
                gear_sheet_point(par[piece], tx[piece], ty[piece], pc[piece], u, v, 1, True,
                                 dpsi, vec)
            else:
                sheet_point(par[piece], tx[piece], ty[piece], pc[piece], u, v, dpsi, vec)
            res_max = 0.0
            for a in range(3):
                x[a] = 0.0
                ju = 0.0
                jv = 0.0
                for b in range(3):
                    x[a] += rot[a, b] * vec[0, b]
                    ju += rot[a, b] * vec[1, b]
                    jv += rot[a, b] * vec[2, b]
                res = x[a] + trans[a] - q[i, a] - lam * n[a]
                res_max = max(res_max, abs(res))
                rhs[a] = -res
                jac[a, 0] = ju
                jac[a, 1] = jv
                jac[a, 2] = -n[a]
                tang[i, a] = ju
                tang[i, 3 + a] = jv
            solve3(jac, rhs, step)
            nu_ = u + step[0]
            nv_ = v + step[1]
            if clamp:
                side = ((nu_ < lo[0]) + 2 * (nu_ > hi[0]) + 4 * (nv_ < lo[1])
                        + 8 * (nv_ > hi[1]))
                pinned = pinned + 1 if side != 0 and side == last_side else 0
                last_side = side
                if pinned >= PINNED_ITERATIONS:
                    break
                nu_ = min(max(nu_, lo[0]), hi[0])
                nv_ = min(max(nv_, lo[1]), hi[1])
            moved = max(abs(nu_ - u), abs(nv_ - v))
            u = nu_
            v = nv_
            lam += step[2]
            if res_max < tol_mm and moved < 1e-12:
                converged = True
                break
            # quadratic basin: once the residual is below BASIN_MM a step below
            # FINAL_STEP leaves an error of order step^2 |r''| (<= ~1e-12 mm), so the
            # confirming evaluation is skipped (one to two per line); not across a kink
            if (res_max < BASIN_MM and moved < FINAL_STEP and abs(step[2]) < FINAL_STEP
                    and not (clamp and side != 0)
                    and not (kinked and kink_piece(kink_x, kink_c, kink_n, u, v)
                             != piece)):
                converged = True
                break
        ins = converged and lo[0] < u < hi[0] and lo[1] < v < hi[1]
        inside[i] = ins
        ok[i] = converged and (ins or not clamp)
        sol[i, 0] = u
        sol[i, 1] = v
        sol[i, 2] = lam
        uv_out[i, 0] = u if converged else np.nan
        uv_out[i, 1] = v if converged else np.nan
        lam_out[i] = lam if ok[i] else np.nan
    return lam_out, inside
