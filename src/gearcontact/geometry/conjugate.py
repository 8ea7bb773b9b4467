"""The conjugate pinion: envelope of the formate gear flank (equation of meshing).

With the gear turned by phi2 about +z, ``X_f = Rz(phi2) X(h, theta)`` and
``N_f = Rz(phi2) n(h, theta)``; the gear flank generates the pinion where the equation
of meshing holds (Litvin & Fuentes 2004, sec. 6.1, eq. (6.1.10)):

    f(h, theta, phi2) = N_f . v12(X_f) = 0,    v12 = w1 x (X_f - C1) - w2 x X_f

(:meth:`~.kinematics.MeshKinematics.relative_velocity`). The pinion point is
``X1 = Rx(u phi2) (X_f - C1)`` with the normal out of the pinion tooth
``N1 = -Rx(u phi2) N_f`` (u = z2/z1). To sample the pinion on its own (u, v) grid
(:mod:`.sheet`: axial position v = X1_x, radius R = R_f(v) + u) the three equations

    X1_x = v,   |X1_yz| = R(u, v),   f = 0

are solved for (h, theta, phi2) by Newton's method with the analytic Jacobian (blade
derivatives, ``d/dphi2 Rz(phi2) V = z x V``); the meshing equation has several roots in
phi2, and the one continuing from the neighbouring node is taken (continuation from the
mean point outwards, first along the profile, then column by column along the face).
The angular coordinate ``psi = atan2(X1_z, X1_y)`` of the nodes feeds the quintic
spline of :class:`~.sheet.RadialSheet`.

Regularity (Litvin & Fuentes 2004, sec. 6.3-6.4): the envelope exists and is free of
undercut where ``df/dphi2 != 0`` (no limit line) and the Jacobian of the node equations
is non-singular (``r_u x r_v != 0`` on the generated sheet); both are checked on the
whole grid and a violation raises :class:`UndercutError` naming flank and location.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import RectBivariateSpline

from ..validation import InputRangeError
from .blank import BlankDesign
from .flank import FlankBoundary, FormateFlank
from .kinematics import MeshKinematics
from .sheet import PinionCone, RadialSheet

__all__ = ["UndercutError", "MeshingError", "MeshingSolution", "MeshingSolver",
           "ConjugateFlank", "conjugate_pinion_flank"]

_TOL = 1e-13          # Newton step tolerance (mm, rad): well below 1 nm
_MAX_ITER = 40
_MAX_STEP = (0.5, 0.05, 0.05)   # damping: |dh| mm, |dtheta| rad, |dphi2| rad per step
#: Node grid margin beyond the active box (u, v), mm: room for the ease-off mapping
#: (:mod:`.easeoff`), which evaluates the conjugate sheet up to ~|E| outside its nodes.
NODE_MARGIN_MM = (0.08, 0.16)
#: |df/dphi2| below this fraction of its mean-point value is treated as the limit line.
_LIMIT_FRACTION = 1e-3


class UndercutError(InputRangeError):
    """The generated pinion flank has a limit line / undercut inside its active box."""


class MeshingError(ArithmeticError):
    """Newton's method on the node equations did not converge (names node and residual)."""


@dataclass(frozen=True)
class MeshingSolution:
    """Solutions of the node equations for arrays of pinion (u, v).

    Attributes
    ----------
    h_mm, theta_rad, phi2_rad : ndarray
        Gear blade parameters and gear rotation of the generating contact.
    psi_rad : ndarray
        Angular coordinate of the pinion point about its axis.
    x1_mm, n1 : ndarray (..., 3)
        Pinion point and unit outward pinion normal (pinion body frame).
    x_f_mm, n_f : ndarray (..., 3)
        Contact point and gear normal in the meshing frame.
    meshing_residual : ndarray
        f = N_f . v12 at the solution (mm/rad).
    df_dphi2 : ndarray
        Partial derivative of f w.r.t. phi2 (limit-line indicator).
    jacobian_det : ndarray
        Determinant of the node-equation Jacobian.
    converged : ndarray of bool
        Node converged (always all True from a strict solve).
    """

    h_mm: np.ndarray
    theta_rad: np.ndarray
    phi2_rad: np.ndarray
    psi_rad: np.ndarray
    x1_mm: np.ndarray
    n1: np.ndarray
    x_f_mm: np.ndarray
    n_f: np.ndarray
    meshing_residual: np.ndarray
    df_dphi2: np.ndarray
    jacobian_det: np.ndarray
    converged: np.ndarray


def _rotz(v: np.ndarray, c: np.ndarray, s: np.ndarray) -> np.ndarray:
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1], v[..., 2]],
                    axis=-1)


def _zcross(v: np.ndarray) -> np.ndarray:
    return np.stack([-v[..., 1], v[..., 0], np.zeros_like(v[..., 0])], axis=-1)


class MeshingSolver:
    """Node equations of one gear flank against the pinion sheet parameterization.

    Parameters
    ----------
    gear : FormateFlank
        The generating gear flank (gear body frame).
    kinematics : MeshKinematics
        Nominal meshing kinematics (no assembly errors).
    cone : PinionCone
        Pinion sheet parameterization.
    """

    def __init__(self, gear: FormateFlank, kinematics: MeshKinematics, cone: PinionCone):
        self.gear, self.kin, self.cone = gear, kinematics, cone
        # v12 is affine in X: v12(X) = M X + v0, M and v0 read off relative_velocity once
        self._v0 = kinematics.relative_velocity(np.zeros(3))
        self._m_t = (kinematics.relative_velocity(np.eye(3)) - self._v0)  # rows: M e_k

    def _v12(self, x: np.ndarray) -> np.ndarray:
        """v12 at points x (..., 3), identical to ``kinematics.relative_velocity``."""
        return x @ self._m_t + self._v0

    def _lin(self, d: np.ndarray) -> np.ndarray:
        """Linear part of v12: v12(X + d) - v12(X)."""
        return d @ self._m_t

    def meshing_function(self, h, theta, phi2) -> np.ndarray:
        """f(h, theta, phi2) = N_f . v12(X_f), mm/rad (vectorized)."""
        b = self.gear.blade.evaluate(h, theta)
        c, s = np.cos(phi2), np.sin(phi2)
        xf, nf = _rotz(b.x, c, s), _rotz(b.n, c, s)
        return np.einsum("...i,...i->...", nf, self.kin.relative_velocity(xf))

    def _system(self, q, x_t, r_t):
        h, th, ph = q[..., 0], q[..., 1], q[..., 2]
        b = self.gear.blade.evaluate(h, th)
        c, s = np.cos(ph), np.sin(ph)
        xf, nf = _rotz(b.x, c, s), _rotz(b.n, c, s)
        dx = np.stack([_rotz(b.x_h, c, s), _rotz(b.x_t, c, s), _zcross(xf)], axis=-2)
        dn = np.stack([np.zeros_like(nf), _rotz(b.n_t, c, s), _zcross(nf)], axis=-2)
        y = xf - self.kin.pinion_centre
        rho = np.hypot(y[..., 1], y[..., 2])
        v12 = self._v12(xf)
        F = np.stack([y[..., 0] - x_t, rho - r_t, np.einsum("...i,...i->...", nf, v12)], axis=-1)
        J = np.empty(F.shape + (3,))
        J[..., 0, :] = dx[..., :, 0]
        J[..., 1, :] = (y[..., None, 1] * dx[..., :, 1] + y[..., None, 2] * dx[..., :, 2]) / rho[..., None]
        J[..., 2, :] = (np.einsum("...ki,...i->...k", dn, v12)
                        + np.einsum("...i,...ki->...k", nf, self._lin(dx)))
        return F, J, xf, nf, y

    def solve(self, u, v, guess: np.ndarray, *, strict: bool = True) -> MeshingSolution:
        """Solve the node equations at pinion (u, v) from ``guess`` (..., 3) = (h, theta, phi2).

        With ``strict=False`` non-convergent nodes are only flagged
        (``MeshingSolution.converged``) instead of raising.

        Raises
        ------
        MeshingError
            If a node does not converge (message names the node and the residual).
        """
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        x_t, r_t = v, self.cone.radius_mm(u, v)
        q = np.array(np.broadcast_to(guess, u.shape + (3,)), dtype=float)
        lim = np.array(_MAX_STEP)
        for _ in range(_MAX_ITER):
            F, J, *_ = self._system(q, x_t, r_t)
            try:
                step = np.linalg.solve(J, -F[..., None])[..., 0]
            except np.linalg.LinAlgError:  # an exactly singular node: pseudo-inverse step
                step = -(np.linalg.pinv(J) @ F[..., None])[..., 0]
            scale = np.max(np.abs(step) / lim, axis=-1, keepdims=True)
            step = step / np.maximum(scale, 1.0)
            q = q + step
            if np.all(np.abs(step) < _TOL):
                break
        F, J, xf, nf, y = self._system(q, x_t, r_t)
        bad = ~(np.all(np.abs(F) < 1e-9, axis=-1) & np.all(np.isfinite(q), axis=-1))
        if strict and np.any(bad):
            i = tuple(int(k) for k in np.argwhere(bad)[0])
            raise MeshingError(f"equation of meshing did not converge at pinion node "
                               f"u = {u[i]:.6f} mm, v = {v[i]:.6f} mm "
                               f"(gear flank {self.gear.side}): residual {np.abs(F[i]).max():.3e}")
        phi1 = self.kin.ratio * q[..., 2]
        cr, sr = np.cos(phi1)[..., None], np.sin(phi1)[..., None]
        rotx = lambda w: np.stack([w[..., 0], (cr * w[..., 1:2] - sr * w[..., 2:3])[..., 0],  # noqa: E731
                                   (sr * w[..., 1:2] + cr * w[..., 2:3])[..., 0]], axis=-1)
        x1, n1 = rotx(y), -rotx(nf)
        psi = np.arctan2(y[..., 2], y[..., 1]) + phi1
        return MeshingSolution(h_mm=q[..., 0], theta_rad=q[..., 1], phi2_rad=q[..., 2],
                               psi_rad=psi, x1_mm=x1, n1=n1, x_f_mm=xf, n_f=nf,
                               meshing_residual=F[..., 2], df_dphi2=J[..., 2, 2],
                               jacobian_det=np.linalg.det(J), converged=~bad)


@dataclass(frozen=True, eq=False)
class ConjugateFlank(RadialSheet):
    """Exactly conjugate pinion flank: spline sheet plus the exact node solutions.

    Extra attributes: ``solver`` (:class:`MeshingSolver`) and ``nodes``
    (:class:`MeshingSolution` on the grid, shape (n_u, n_v)).
    """

    solver: MeshingSolver = None
    nodes: MeshingSolution = None

    def exact(self, u, v) -> MeshingSolution:
        """Exact solve of the node equations at arbitrary (u, v) (guess from the nodes)."""
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        guess = np.stack([RectBivariateSpline(self.u_nodes, self.v_nodes, g, kx=3, ky=3)(
            u.ravel(), v.ravel(), grid=False).reshape(u.shape)
            for g in (self.nodes.h_mm, self.nodes.theta_rad, self.nodes.phi2_rad)], axis=-1)
        return self.solver.solve(u, v, guess)


def _nominal_pinion_box(blank: BlankDesign, pinion_face_width_mm: float) -> tuple[PinionCone, FlankBoundary]:
    d1 = np.radians(blank.pitch_angle_pinion_deg)
    cone = PinionCone(apex_x_mm=blank.pinion_apex_x_mm, tan_delta=float(np.tan(d1)),
                      root_offset_mm=blank.dedendum_pinion_mm / np.cos(d1))
    x_m = blank.pitch_point_mm[0]
    half = 0.5 * pinion_face_width_mm * np.cos(d1)
    # nominal profile: from the clearance above the root to the pinion tip
    box = FlankBoundary(u_root=float(blank.clearance_mm / np.cos(d1)),
                        u_tip=float((blank.dedendum_pinion_mm + blank.addendum_pinion_mm) / np.cos(d1)),
                        v_toe=float(x_m - half), v_heel=float(x_m + half))
    return cone, box


def conjugate_pinion_flank(gear: FormateFlank, *, blank: BlankDesign, kinematics: MeshKinematics,
                           pinion_face_width_mm: float, n_u: int = 120,
                           n_v: int = 150) -> tuple[ConjugateFlank, dict]:
    """Generate the pinion flank conjugate to ``gear`` on an n_u x n_v exact grid.

    Returns
    -------
    flank : ConjugateFlank
    mean_contact : dict
        ``{"pinion_uv", "gear_uv", "phi2_rad"}`` of the conjugate contact at the pinion
        mean point (pitch radius, mean section).

    Raises
    ------
    UndercutError
        Limit line (df/dphi2 = 0 or changing sign), singular envelope, or a node of the
        box that the envelope does not reach (non-convergent node equations; the
        :class:`MeshingError` naming node and residual is chained as the cause).
    """
    if int(n_u) != n_u or n_u < 6 or int(n_v) != n_v or n_v < 6:
        raise InputRangeError("n_u, n_v", (n_u, n_v), "integers >= 6 (quintic spline)")
    cone, nominal = _nominal_pinion_box(blank, pinion_face_width_mm)
    solver = MeshingSolver(gear, kinematics, cone)
    try:
        box = _active_box(solver, nominal, blank)
        us, vs, U, V, nodes, mean, (i0, j0), u_m, v_m = _solve_grid(solver, box, blank, n_u, n_v)
    except MeshingError as exc:
        # for an envelope, a pinion point without a solution lies beyond the limit line
        raise UndercutError(f"pinion {gear.side} flank", str(exc),
                            "a pinion box fully covered by the regular envelope (no limit "
                            "line / undercut: change pressure angles, addenda or cutter)") from exc
    _check_regular(nodes, mean, gear.side, U, V)
    psi = np.unwrap(np.unwrap(nodes.psi_rad, axis=0), axis=1)
    flank = ConjugateFlank(side=gear.side, cone=cone, u_nodes=us, v_nodes=vs, psi_nodes=psi,
                           normal_sign=1.0, boundary=box, solver=solver, nodes=nodes)
    s = flank.evaluate(us[i0], vs[j0])
    sign = float(np.sign(s.n @ nodes.n1[i0, j0]))
    flank = ConjugateFlank(side=gear.side, cone=cone, u_nodes=us, v_nodes=vs, psi_nodes=psi,
                           normal_sign=sign, boundary=box, solver=solver, nodes=nodes)
    gear_uv = gear.surface_parameters(mean.h_mm, mean.theta_rad)
    return flank, {"pinion_uv": (u_m, v_m), "gear_uv": tuple(float(x) for x in gear_uv),
                   "phi2_rad": float(mean.phi2_rad)}


#: Lengthwise sections used to trace the lines generated by the gear tip and root.
_SECTIONS = 9
_MARCH_STEPS = 24


def _active_box(solver: MeshingSolver, nominal: FlankBoundary, blank: BlankDesign) -> FlankBoundary:
    """Shrink the nominal pinion box to the part generated by the active gear flank.

    The pinion flank is generated by gear flank points with ``-h_a2 <= h <= h_root``
    (gear tip to the start of the blade edge round); below the line generated by the
    gear tip the pinion has its fillet, above the line generated by the gear root it
    would interfere. Both lines are traced on ``_SECTIONS`` lengthwise sections by
    marching along the profile from the mean radius (Litvin & Fuentes 2004, sec. 6.3),
    and the rectangular (u, v) box is the intersection over the sections. If the
    envelope ends (folds, limit line) before reaching a line, the flank is undercut:
    :class:`UndercutError`; if it folds within the node margin beyond the line, the
    active edge moves inwards so that the nodes keep their margin.
    """
    gear = solver.gear
    h_lo = -blank.addendum_gear_mm
    h_hi = float(gear.blade_parameters(gear.boundary.u_root, 0.0)[0])
    u_m, v_m = float(solver.cone.root_offset_mm), float(blank.pitch_point_mm[0])
    vs = np.linspace(nominal.v_toe - NODE_MARGIN_MM[1], nominal.v_heel + NODE_MARGIN_MM[1],
                     _SECTIONS)
    # mean-radius guesses on every section: continuation along the face from the mean
    q_m = solver.solve(u_m, v_m, np.zeros(3))
    q_mean = np.array([q_m.h_mm, q_m.theta_rad, q_m.phi2_rad], dtype=float)
    guess = np.empty((len(vs), 3))
    for order in (np.arange(len(vs))[vs >= v_m], np.arange(len(vs))[vs < v_m][::-1]):
        q, v_prev = q_mean, v_m
        for k in order:
            for v in np.linspace(v_prev, vs[k], 5)[1:]:
                s = solver.solve(u_m, v, q)
                q = np.array([s.h_mm, s.theta_rad, s.phi2_rad])
            guess[k], v_prev = q, vs[k]
    limits = []
    margin = NODE_MARGIN_MM[0]
    for u_end, h_target in ((nominal.u_root - margin, h_lo), (nominal.u_tip + margin, h_hi)):
        q = guess.copy()
        u_prev = np.full(len(vs), u_m)
        h_prev = q[:, 0].copy()
        found = np.full(len(vs), np.nan)
        alive = np.ones(len(vs), dtype=bool)
        for u in np.linspace(u_m, u_end, _MARCH_STEPS + 1)[1:]:
            s = solver.solve(np.full(len(vs), u), vs, q, strict=False)
            lost = alive & ~s.converged
            for k in np.flatnonzero(lost & np.isnan(found)):
                # the step lost the envelope before a crossing was seen: retrace it finely
                u_ok, h_ok, u_cross = _retrace(solver, u_prev[k], u, vs[k], q[k], h_prev[k], h_target)
                u_prev[k], h_prev[k], found[k] = u_ok, h_ok, u_cross
            folded = lost & np.isnan(found)
            if folded.any():  # the envelope ends inside the generated region: undercut
                k = int(np.argmax(folded))
                raise UndercutError(
                    f"pinion {gear.side} flank at (u, v) = ({u_prev[k]:.4f}, {vs[k]:.4f}) mm",
                    f"gear h = {h_prev[k]:.4f} mm",
                    f"an envelope reaching the line generated by the gear "
                    f"{'tip' if h_target == h_lo else 'root'} (h = {h_target:.4f} mm); it ends "
                    "before (limit line / undercut: change pressure angles, addenda or cutter)")
            # the envelope folds within the node margin beyond the gear line: move the
            # active edge so that the nodes keep their margin inside the envelope
            sign = np.sign(u_end - u_m)
            found = np.where(lost, u_prev - sign * margin, found)
            alive &= ~lost
            h = s.h_mm
            crossed = alive & np.isnan(found) & ((h - h_target) * (h_prev - h_target) <= 0.0)
            frac = (h_target - h_prev) / np.where(h == h_prev, 1.0, h - h_prev)
            found = np.where(crossed, u_prev + frac * (u - u_prev), found)
            ok = alive & s.converged
            q = np.where(ok[:, None], np.stack([s.h_mm, s.theta_rad, s.phi2_rad], axis=-1), q)
            u_prev, h_prev = np.where(ok, u, u_prev), np.where(ok, h, h_prev)
            alive &= ~(~np.isnan(found) & (np.abs(u - found) >= margin))
            if not alive.any():
                break
        limits.append(np.where(np.isnan(found), u_end, found))
    u_root = max(nominal.u_root, float(np.max(limits[0])))
    u_tip = min(nominal.u_tip, float(np.min(limits[1])))
    if not u_tip - u_root > 0.1 * (nominal.u_tip - nominal.u_root):
        raise UndercutError("pinion flank active profile", (u_root, u_tip),
                            "a generated profile of at least 10 % of the working depth")
    return FlankBoundary(u_root=u_root, u_tip=u_tip, v_toe=nominal.v_toe, v_heel=nominal.v_heel)


def _retrace(solver: MeshingSolver, u_from: float, u_to: float, v: float, q: np.ndarray,
             h_from: float, h_target: float, substeps: int = 32):
    """March one section finely from ``u_from`` towards ``u_to`` until the envelope is lost.

    Returns (last converged u, its gear h, u where h crosses ``h_target`` or NaN).
    """
    u_ok, h_ok, q = u_from, h_from, np.array(q, dtype=float)
    for u in np.linspace(u_from, u_to, substeps + 1)[1:]:
        s = solver.solve(u, v, q, strict=False)
        if not bool(s.converged):
            break
        h = float(s.h_mm)
        if (h - h_target) * (h_ok - h_target) <= 0.0:
            return u, h, u_ok + (h_target - h_ok) / (h - h_ok) * (u - u_ok) if h != h_ok else u
        u_ok, h_ok, q = u, h, np.array([s.h_mm, s.theta_rad, s.phi2_rad], dtype=float)
    return u_ok, h_ok, np.nan


def _solve_grid(solver: MeshingSolver, box: FlankBoundary, blank: BlankDesign, n_u: int, n_v: int):
    """Continuation over the node grid (see module docstring)."""
    cone = solver.cone
    u_m, v_m = float(cone.root_offset_mm), float(blank.pitch_point_mm[0])
    mean = solver.solve(u_m, v_m, np.zeros(3))
    us = np.linspace(box.u_root - NODE_MARGIN_MM[0], box.u_tip + NODE_MARGIN_MM[0], int(n_u))
    vs = np.linspace(box.v_toe - NODE_MARGIN_MM[1], box.v_heel + NODE_MARGIN_MM[1], int(n_v))
    q = np.empty((len(us), len(vs), 3))
    # continuation: profile column nearest the mean section, then column by column
    j0, i0 = int(np.argmin(np.abs(vs - v_m))), int(np.argmin(np.abs(us - u_m)))
    g = np.array([mean.h_mm, mean.theta_rad, mean.phi2_rad], dtype=float)
    start = solver.solve(us[i0], vs[j0], g)
    q[i0, j0] = [start.h_mm, start.theta_rad, start.phi2_rad]
    for rng in (range(i0 + 1, len(us)), range(i0 - 1, -1, -1)):
        prev = q[i0, j0]
        for i in rng:
            s = solver.solve(us[i], vs[j0], prev)
            q[i, j0] = prev = [s.h_mm, s.theta_rad, s.phi2_rad]
    cols: list = [None] * len(vs)
    cols[j0] = solver.solve(us, np.full_like(us, vs[j0]), q[:, j0])
    for rng, back in ((range(j0 + 1, len(vs)), -1), (range(j0 - 1, -1, -1), 1)):
        for j in rng:
            done = abs(j - j0)  # solved columns behind j on this side (incl. j0)
            if done >= 3:   # quadratic extrapolation from the last three columns
                guess = 3.0 * q[:, j + back] - 3.0 * q[:, j + 2 * back] + q[:, j + 3 * back]
            elif done == 2:
                guess = 2.0 * q[:, j + back] - q[:, j + 2 * back]
            else:
                guess = q[:, j + back]
            cols[j] = s = solver.solve(us, np.full_like(us, vs[j]), guess)
            q[:, j] = np.stack([s.h_mm, s.theta_rad, s.phi2_rad], axis=-1)
    U, V = np.meshgrid(us, vs, indexing="ij")
    nodes = MeshingSolution(**{f: np.stack([getattr(c, f) for c in cols], axis=1)
                               for f in MeshingSolution.__dataclass_fields__})
    return us, vs, U, V, nodes, mean, (i0, j0), u_m, v_m


def _check_regular(nodes: MeshingSolution, mean: MeshingSolution, side: str, U, V) -> None:
    """Raise :class:`UndercutError` at a limit line or singular envelope in the box."""
    ref = float(mean.df_dphi2)
    ratio = nodes.df_dphi2 / ref
    bad = ratio < _LIMIT_FRACTION
    if np.any(bad):
        i = tuple(int(k) for k in np.argwhere(bad)[0])
        raise UndercutError(f"pinion {side} flank at (u, v) = ({U[i]:.4f}, {V[i]:.4f}) mm",
                            float(nodes.df_dphi2[i]),
                            f"df/dphi2 of the mean-point sign and > {_LIMIT_FRACTION:g} of its "
                            f"mean-point value {ref:.4g} (limit line / undercut: change the "
                            "pressure angles, addenda or cutter)")
    det = np.abs(nodes.jacobian_det)
    sing = det < _LIMIT_FRACTION * abs(float(mean.jacobian_det))
    if np.any(sing):
        i = tuple(int(k) for k in np.argwhere(sing)[0])
        raise UndercutError(f"pinion {side} flank at (u, v) = ({U[i]:.4f}, {V[i]:.4f}) mm",
                            float(det[i]), "a regular envelope (r_u x r_v != 0)")
