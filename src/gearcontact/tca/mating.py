"""Unloaded tooth contact analysis (TCA): the mating point of two flanks per mesh phase.

At a pinion rotation ``phi1`` the posed flanks touch where they share position and
normal (Litvin & Fuentes 2004, sec. 9.4 and ch. 15 "TCA"):

.. math::

    \\mathbf r_f^{(1)}(u_1, v_1, \\phi_1) - \\mathbf r_f^{(2)}(u_2, v_2, \\phi_2) = 0
    \\quad (3), \\qquad
    (\\mathbf n_f^{(1)} + \\mathbf n_f^{(2)}) \\cdot \\mathbf t_{a,b} = 0 \\quad (2),

with both unit normals pointing out of their own tooth (so ``n1 = -n2`` at contact) and
``t_a, t_b`` an orthonormal basis of the gear's tangent plane. The five unknowns are
``(u1, v1, u2, v2, phi2)`` for a given ``phi1``; :func:`solve_mating_point` can fix any
one of the six variables instead (e.g. the gear's profile parameter, to start the path
exactly at the mean point). Newton's method uses the analytic Jacobian from the
surface derivatives: ``d n / d(u, v) = -[r_u r_v] I^-1 II`` (Weingarten equations, do
Carmo 1976, sec. 3-3) and ``d X_f / d phi = w x (X_f - c)`` for a rotation about an
axis ``w`` through ``c``. The term ``(n1 + n2) . d t`` is dropped: it vanishes at the
solution, so convergence stays quadratic.

Member 1 is the pinion, member 2 the gear; poses come from
:class:`~gearcontact.geometry.kinematics.MeshKinematics` (assembly errors included).
Iterates are kept inside the flanks' parameter boxes: a solution that would lie
outside is reported as *edge contact* (:class:`EdgeContact`), never extrapolated.

Transmission error (docs/geometry.md sec. 4):
``TE0 = (phi2 - phi2_0) - (z1/z2)(phi1 - phi1_0)`` converted to arcsec
(x 206264.806), relative to the reference (mean) mating point ``(phi1_0, phi2_0)``.
"""


from __future__ import annotations

import numpy as np

from ..geometry.kinematics import MeshKinematics
from ..geometry.surface import Surface, SurfacePoint
from ..validation import check_positive
from .types import VARIABLES, ContactGuess, EdgeContact, MatingPoint, TcaConvergenceError

__all__ = ["solve_mating_point", "posed_point", "normal_derivatives"]


def normal_derivatives(sp: SurfacePoint) -> tuple[np.ndarray, np.ndarray]:
    """Derivatives ``(n_u, n_v)`` of the unit normal (Weingarten equations).

    ``[n_u n_v] = -[r_u r_v] I^-1 II`` with II taken w.r.t. ``sp.n``
    (do Carmo 1976, sec. 3-3, eq. 3).
    """
    first, second = sp.fundamental_forms()
    (e, f), (_, g) = first
    w = np.array([[g, -f], [-f, e]]) @ second / (e * g - f * f)   # I^-1 II (2 x 2)
    jac = np.column_stack([sp.r_u, sp.r_v])
    dn = -jac @ w
    return dn[:, 0], dn[:, 1]


def posed_point(surface: Surface, pose: tuple[np.ndarray, np.ndarray],
                u: float, v: float) -> tuple[SurfacePoint, np.ndarray, np.ndarray]:
    """Evaluate ``surface`` at ``(u, v)`` and pose it: ``(sp, X_f, n_f)``."""
    sp = surface.point(u, v)
    rot, t = pose
    return sp, rot @ sp.r + t, rot @ sp.n


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``a x b`` of two 3-vectors (np.cross without its per-call overhead)."""
    a0, a1, a2 = a
    b0, b1, b2 = b
    return np.array([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])


def _tangent_basis(n: np.ndarray) -> np.ndarray:
    """An orthonormal (3, 2) basis of the plane normal to unit ``n``."""
    a = np.array([1.0, 0.0, 0.0]) if abs(n[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    ta = a - (a @ n) * n
    ta /= np.linalg.norm(ta)
    return np.column_stack([ta, _cross(n, ta)])


_BOX_NAMES = ("pinion u", "pinion v", "gear u", "gear v")


def _clamp(x: np.ndarray, boxes) -> tuple[np.ndarray, list[str]]:
    """Clamp the flank parameters of the state ``x`` into their boxes (4 ``(lo, hi)``
    pairs, :func:`_boxes`)."""
    names = _BOX_NAMES
    hit = []
    y = x.copy()
    for i in range(4):
        lo, hi = boxes[i]
        if y[i] < lo:
            y[i] = lo
            hit.append(f"{names[i]} min")
        elif y[i] > hi:
            y[i] = hi
            hit.append(f"{names[i]} max")
    return y, hit


def _residual(pinion: Surface, gear: Surface, kin: MeshKinematics, x: np.ndarray):
    """Residual F (5,) of the contact equations at state x and what its Jacobian
    (:func:`_jacobian`) takes: ``(res, state)``."""
    u1, v1, u2, v2, phi1, phi2 = x
    pose1 = kin.pinion_pose(phi1)
    pose2 = kin.gear_pose(phi2)
    sp1, x1, n1 = posed_point(pinion, pose1, u1, v1)
    sp2, x2, n2 = posed_point(gear, pose2, u2, v2)
    basis = _tangent_basis(n2)
    res = np.concatenate([x1 - x2, basis.T @ (n1 + n2)])
    return res, (pose1, pose2, sp1, sp2, x1, x2, n1, n2, basis)


def _jacobian(kin: MeshKinematics, state) -> np.ndarray:
    """Jacobian dF/dx (5, 6) of the contact equations from :func:`_residual`'s state."""
    pose1, pose2, sp1, sp2, x1, x2, n1, n2, basis = state
    r1, r2 = pose1[0], pose2[0]
    w1 = -kin.pinion_axis            # the pinion turns about -x (tilted by alpha)
    w2 = kin.gear_axis
    n1u, n1v = normal_derivatives(sp1)
    n2u, n2v = normal_derivatives(sp2)
    jac = np.empty((5, 6))
    jac[:3, 0] = r1 @ sp1.r_u
    jac[:3, 1] = r1 @ sp1.r_v
    jac[:3, 2] = -(r2 @ sp2.r_u)
    jac[:3, 3] = -(r2 @ sp2.r_v)
    jac[:3, 4] = _cross(w1, x1 - pose1[1])
    jac[:3, 5] = -_cross(w2, x2 - pose2[1])
    dn = np.column_stack([r1 @ n1u, r1 @ n1v, r2 @ n2u, r2 @ n2v,
                          _cross(w1, n1), _cross(w2, n2)])
    jac[3:, :] = basis.T @ dn
    return jac


def _residual_and_jacobian(pinion: Surface, gear: Surface, kin: MeshKinematics,
                           x: np.ndarray, *, jacobian: bool = True):
    """Residual F (5,) and Jacobian dF/dx (5, 6) of the contact equations at state x."""
    res, state = _residual(pinion, gear, kin, x)
    return res, (state[5], state[7]), (_jacobian(kin, state) if jacobian else None)


def _boxes(pinion: Surface, gear: Surface) -> tuple:
    """The four parameter boxes ``(lo, hi)`` as Python floats (the float64 values
    themselves; scalar comparisons without numpy's per-element overhead)."""
    return tuple(map(tuple, np.array([pinion.u_range, pinion.v_range, gear.u_range,
                                      gear.v_range], float).tolist()))


def solve_mating_point(pinion: Surface, gear: Surface, kin: MeshKinematics,
                       guess: ContactGuess, *, fixed: str | tuple[str, ...] = "phi1",
                       tol_mm: float = 1e-10, max_iter: int = 40) -> MatingPoint:
    """Solve the five contact equations by Newton's method with one variable fixed.

    Parameters
    ----------
    pinion, gear : Surface
        Flanks of member 1 and member 2 in their body frames (normals out of the tooth).
    kin : MeshKinematics
        Poses of both members (assembly errors included).
    guess : ContactGuess
        Starting state; the variable named by ``fixed`` keeps its value.
    fixed : str or tuple of str
        Variable(s) of :data:`VARIABLES` held at their guessed values; ``"phi1"`` is
        ordinary TCA at a given mesh phase. With two fixed variables the five equations
        in four unknowns are solved by Gauss-Newton (least squares); they converge only
        if the system is consistent - e.g. along the contact line of a conjugate
        (line-contact) pair, ``fixed=("phi1", "v2")``.
    tol_mm : float
        Convergence tolerance on the position residual, mm; the normal residual must
        fall below ``tol_mm / 1 mm``.
    max_iter : int
        Newton iteration limit.

    Returns
    -------
    MatingPoint
        With ``te0_arcsec = 0`` (the path sets it relative to its reference).

    Raises
    ------
    EdgeContact
        The solution lies outside a parameter box (iterates are clamped to the boxes).
    TcaConvergenceError
        No convergence; the message names the mesh phase and the residual.
    """
    check_positive("tol_mm", tol_mm)
    names = (fixed,) if isinstance(fixed, str) else tuple(fixed)
    unknown = [n for n in names if n not in VARIABLES]
    if unknown or not 1 <= len(set(names)) <= 2:
        raise ValueError(f"fixed = {fixed!r}: give one or two of {VARIABLES}")
    free = [i for i, n in enumerate(VARIABLES) if n not in names]
    boxes = _boxes(pinion, gear)
    x, hit = _clamp(guess.vector(), boxes)
    res, (x2, n2), jac = _residual_and_jacobian(pinion, gear, kin, x)
    norm = np.linalg.norm(res)
    clamped_iters = 0
    for it in range(1, max_iter + 1):
        if len(free) == 5:
            try:
                step = np.linalg.solve(jac[:, free], -res)
            except np.linalg.LinAlgError:
                step = np.linalg.lstsq(jac[:, free], -res, rcond=None)[0]
        else:
            step = np.linalg.lstsq(jac[:, free], -res, rcond=None)[0]
        lam = 1.0
        while True:
            trial = x.copy()
            trial[free] += lam * step
            trial, hit = _clamp(trial, boxes)
            # the Jacobian only at the trial taken (a refused trial's is never used)
            res_t, state_t = _residual(pinion, gear, kin, trial)
            norm_t = np.linalg.norm(res_t)
            if norm_t < norm or lam < 1e-3:
                break
            lam *= 0.5
        x, res, norm = trial, res_t, norm_t
        x2, n2 = state_t[5], state_t[7]
        clamped_iters = clamped_iters + 1 if hit else 0
        if np.all(np.abs(res[:3]) < tol_mm) and np.all(np.abs(res[3:]) < tol_mm) and not hit:
            return MatingPoint(x[4], x[5], x[0], x[1], x[2], x[3], x2, n2,
                               residual=float(norm), iterations=it)
        if clamped_iters >= 3:
            raise EdgeContact(x[4], hit[0])
        if it < max_iter:       # the last iterate's Jacobian would not be used
            jac = _jacobian(kin, state_t)
    raise TcaConvergenceError(x[4], norm, max_iter)
