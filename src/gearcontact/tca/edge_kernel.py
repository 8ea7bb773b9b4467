"""Compiled (numba) Newton solve of the edge-contact search of a pair with a relieved flank.

:class:`gearcontact.tca.edge_contact._EdgeSolver` finds, for a point ``s`` of an edge
of one member's flank, the gear rotation ``phi2`` and the other flank's parameters
``(a, b)`` that bring the point onto the other flank: Newton's method on
``X_1 - X_2 = 0`` with the Jacobian ``[r_a, r_b, -w_2 x (X_2 - c_2)]``
(:mod:`.edge_contact`). A relieved flank's kink line is a convex ridge that carries
the contact over whole stretches of the path (:func:`~.edge_contact.flank_edges`):
there the search samples every edge (the box's eight and the ridge) and refines the
best by Brent's method, thousands of such solves per path. :func:`edge_newton` runs
the same iteration in compiled code, step for step, when both flanks have a compiled
form (:func:`~gearcontact.tca.gap_kernel.kernel_surface`: a radial sheet, a blade
cone, or a relieved flank of radial sheets, cones or generated gear sheets):

* the edge point: ``(s, v_toe)``, ``(s, v_heel)``, ``(u_root, s)``, ``(u_tip, s)`` or
  on a ridge ``(u_k(s), s)`` from the kink line's piecewise cubic
  (:func:`~gearcontact.geometry.kinked.kink_u`, the sum
  :meth:`~gearcontact.geometry.kinked.KinkLine.u` evaluates), clipped to the box
  (:func:`~.edge_contact.edge_parameters`);
* every flank point as the flank's ``point`` method gives it
  (:func:`~gearcontact.tca.gap_kernel.flank_vector`: the piece that holds it);
* the gear pose ``R_z(sign phi2)``, ``c_2 = (0, 0, G)``
  (:meth:`~gearcontact.geometry.kinematics.MeshKinematics.gear_pose`);
* the same stopping rule (every residual component below the tolerance), the same
  refusal (a step of more than 50 mm in a parameter or 0.1 rad in ``phi2``: no touch
  nearby; a singular Jacobian), the same iteration limit.

The 3 x 3 systems are solved by Gaussian elimination with partial pivoting
(:func:`~gearcontact.tca.gap_kernel.solve3`) where the Python solve calls LAPACK, so
the two agree to rounding, not bit for bit (tests/tca/test_edge_kernel.py). The edge
search of a pair of smooth flanks keeps the Python iteration, so that its results
stay those of every earlier run bit for bit (:meth:`.edge_contact._EdgeSolver`).
"""

from __future__ import annotations

import time

import numpy as np
from numba import njit

from ..geometry.kinked import kink_u
from .gap_kernel import KIND_CONE, flank_vector, solve3

__all__ = ["EDGE_CODES", "EDGE_TOE", "EDGE_HEEL", "EDGE_ROOT", "EDGE_TIP", "EDGE_KINK",
           "edge_point", "edge_newton", "warm_up"]

#: Edge codes of :func:`edge_newton`: the box edges of
#: :data:`~.edge_contact.EDGE_NAMES` and a kink line.
EDGE_TOE, EDGE_HEEL, EDGE_ROOT, EDGE_TIP, EDGE_KINK = 0, 1, 2, 3, 4
EDGE_CODES = {"toe": EDGE_TOE, "heel": EDGE_HEEL, "root": EDGE_ROOT, "tip": EDGE_TIP}


@njit(cache=True, inline="always")
def edge_point(edge, kink, kink_x, kink_c, kink_n, box, s):
    """Flank parameters ``(u, v)`` of the point ``s`` of an edge (:data:`EDGE_CODES`,
    a kink line ``kink`` of the tables ``kink_x``, ``kink_c``, ``kink_n``) of a flank
    with the box ``(u_root, u_tip, v_toe, v_heel)``, as
    :func:`~.edge_contact.edge_parameters` gives them (a ridge point clipped into the
    box's ``u``), mm."""
    if edge == EDGE_KINK:
        return min(max(kink_u(kink_x[kink], kink_c[kink], kink_n[kink], s), box[0]),
                   box[1]), s
    if edge == EDGE_TOE or edge == EDGE_HEEL:
        return s, (box[2] if edge == EDGE_TOE else box[3])
    return (box[0] if edge == EDGE_ROOT else box[1]), s


@njit(cache=True)
def edge_newton(own_kind, own_par, own_tx, own_ty, own_pc, own_kx, own_kc, own_kn,
                oth_kind, oth_par, oth_tx, oth_ty, oth_pc, oth_kx, oth_kc, oth_kn,
                edge, kink, box, s, y0, on_pinion, rot1, t1, gear_sign, g_mm, tol_mm,
                max_iter, y_out):
    """Newton's solve of the edge point ``s`` of one flank touching the other flank
    (module docstring).

    Parameters
    ----------
    own_kind ... own_kn, oth_kind ... oth_kn
        Kernel forms (:func:`~gearcontact.tca.gap_kernel.kernel_surface`) of the flank
        whose edge it is and of the flank it touches.
    edge : int
        :data:`EDGE_TOE`, :data:`EDGE_HEEL`, :data:`EDGE_ROOT`, :data:`EDGE_TIP` or
        :data:`EDGE_KINK`.
    kink : int
        Index of the kink line in ``own_kx`` / ``own_kc`` / ``own_kn`` (a kink edge).
    box : ndarray (4,)
        The own flank's box ``(u_root, u_tip, v_toe, v_heel)`` (a ridge point is
        clipped into its ``u``).
    s : float
        Edge point: the edge's free parameter (:func:`~.edge_contact.edge_parameters`),
        mm.
    y0 : ndarray (3,)
        Start ``(a, b, phi2)``: other flank's parameters (mm) and gear rotation (rad).
    on_pinion : bool
        The ridge is the pinion's (its point fixed by the held pinion pose).
    rot1, t1 : ndarray (3, 3), (3,)
        Pinion pose at the held phase.
    gear_sign, g_mm : float
        Sign of the gear axis (+z: 1) and the gear's axial error G, mm.
    tol_mm : float
        Residual tolerance, mm.
    max_iter : int
        Iteration limit.
    y_out : ndarray (3,)
        The solution ``(a, b, phi2)`` when converged.

    Returns
    -------
    bool
        Converged (else no touch near ``y0``).
    """
    u, v = edge_point(edge, kink, own_kx, own_kc, own_kn, box, s)
    d = np.zeros(6)
    vec = np.empty((7, 3))
    flank_vector(own_kind, own_par, own_tx, own_ty, own_pc, own_kx, own_kc, own_kn,
                 u, v, d, vec)
    pt = np.empty(3)               # the posed pinion edge point, or the gear's in body
    for a in range(3):
        if on_pinion:
            pt[a] = (rot1[a, 0] * vec[0, 0] + rot1[a, 1] * vec[0, 1]
                     + rot1[a, 2] * vec[0, 2]) + t1[a]
        else:
            pt[a] = vec[0, a]
    y = np.empty(3)
    for a in range(3):
        y[a] = y0[a]
    jac = np.empty((3, 3))
    res = np.empty(3)
    rhs = np.empty(3)
    step = np.empty(3)
    x1 = np.empty(3)
    x2 = np.empty(3)
    for _ in range(max_iter):
        c = np.cos(gear_sign * y[2])
        sn = np.sin(gear_sign * y[2])
        rot2 = np.array([[c, -sn, 0.0], [sn, c, 0.0], [0.0, 0.0, 1.0]])
        # the touched point: on the gear (posed by rot2) or on the pinion (by rot1)
        flank_vector(oth_kind, oth_par, oth_tx, oth_ty, oth_pc, oth_kx, oth_kc, oth_kn,
                     y[0], y[1], d, vec)
        rot = rot2 if on_pinion else rot1
        for a in range(3):
            xr = rot[a, 0] * vec[0, 0] + rot[a, 1] * vec[0, 1] + rot[a, 2] * vec[0, 2]
            ju = rot[a, 0] * vec[1, 0] + rot[a, 1] * vec[1, 1] + rot[a, 2] * vec[1, 2]
            jv = rot[a, 0] * vec[2, 0] + rot[a, 1] * vec[2, 1] + rot[a, 2] * vec[2, 2]
            if on_pinion:
                x1[a] = pt[a]
                x2[a] = xr + (g_mm if a == 2 else 0.0)
                jac[a, 0] = -ju
                jac[a, 1] = -jv
            else:
                x1[a] = xr + t1[a]
                x2[a] = (rot2[a, 0] * pt[0] + rot2[a, 1] * pt[1]
                         + rot2[a, 2] * pt[2]) + (g_mm if a == 2 else 0.0)
                jac[a, 0] = ju
                jac[a, 1] = jv
            res[a] = x1[a] - x2[a]
        # -w2 x (X2 - c2) with w2 = (0, 0, gear_sign), c2 = (0, 0, G)
        dz = x2[2] - g_mm
        jac[0, 2] = -(0.0 * dz - gear_sign * x2[1])
        jac[1, 2] = -(gear_sign * x2[0] - 0.0 * dz)
        jac[2, 2] = -(0.0 * x2[1] - 0.0 * x2[0])
        if abs(res[0]) < tol_mm and abs(res[1]) < tol_mm and abs(res[2]) < tol_mm:
            for a in range(3):
                y_out[a] = y[a]
            return True
        for a in range(3):
            rhs[a] = -res[a]
        solve3(jac, rhs, step)
        if not (np.isfinite(step[0]) and np.isfinite(step[1]) and np.isfinite(step[2])):
            return False
        # a step of more than a tooth or a tenth of a radian: no touch nearby
        if max(abs(step[0]), abs(step[1])) > 50.0 or abs(step[2]) > 0.1:
            return False
        for a in range(3):
            y[a] = y[a] + step[a]
    return False


def warm_up() -> float:
    """Compile (or load from numba's on-disk cache) :func:`edge_newton` for the one
    signature the edge search calls, so that ``gearcontact warm-up`` covers it (its
    fixed s0003 runs have no relieved flank): one call on a synthetic blade cone with
    no iteration. Returns the wall-clock seconds it took, s."""
    t0 = time.perf_counter()
    par = np.zeros((1, 19))
    par[0, 3] = par[0, 6] = par[0, 10] = par[0, 18] = 1.0     # axis, e1, e2, v scale
    cone = (KIND_CONE, par, np.zeros((1, 0)), np.zeros((1, 0)), np.zeros((1, 0, 0, 0, 0)),
            np.zeros((0, 2)), np.zeros((0, 1, 4)), np.zeros(0, dtype=np.int64))
    edge_newton(*cone, *cone, EDGE_TIP, -1, np.zeros(4), 0.0, np.zeros(3), True, np.eye(3),
                np.zeros(3), 1.0, 0.0, 1e-10, 0, np.zeros(3))
    return time.perf_counter() - t0
