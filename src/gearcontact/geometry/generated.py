"""Flanks cut on a cradle machine: formate gear and generated pinion from machine settings.

The machine, its settings and the cutter -> work motion are :mod:`.machine`; this
module places the work frame in the member's body frame and builds the flanks behind
the :class:`~.surface.Surface` contract, so TCA and LTCA take them unchanged:

- **work -> body**: the work frame ``S_w`` (apex origin, ``z_w`` the work axis) maps
  to the body frames of :mod:`.kinematics` by a fixed rotation and the blank's apex:
  gear ``X_b = Rz(theta_P) X_w + (0, 0, z_A2)`` (``theta_P`` the azimuth of the blank's
  mean point P: at zero roll the machine's axial plane holds P), pinion
  ``X_b = Q X_w + (x_A1, 0, 0)`` with ``Q: x_w -> +z, y_w -> -y, z_w -> +x`` (at zero
  roll the machine's axial plane is the plane of the pinion axis and the gear axis).
- **formate gear** (``ratio_of_roll = 0``, straight blade): the blade cone placed in the
  gear body frame, an exact :class:`~.formate.FormateFlank` with the parameters and
  boundary of :func:`~.formate.gear_flank` (compiled TCA path).
- **generated gear** (roll or helical motion): the same envelope on the gear's
  :class:`~.sheet.GearSheet` (``u`` above the root along the pitch-cone normal, ``v``
  cone distance from the mean section).
- **generated pinion**: the envelope of the blade surface in the generating motion,
  ``n_w . dX_w/dpsi = 0`` (Litvin & Fuentes 2004, sec. 6.1), sampled exactly on the
  pinion's (u, v) node grid of :mod:`.sheet` (axial position ``v``, radius
  ``R_f(v) + u``; unknowns blade arc length ``l``, blade angle ``theta``, roll ``psi``;
  Newton with a central-difference Jacobian, continuation from the mean node) and
  interpolated by the C2 quintic :class:`~.sheet.RadialSheet`, the form of today's
  conjugate pinion.

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 6.1-6.4
(envelopes, limit lines), ch. 20-21 (face-milled spiral bevel and hypoid gears).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from ..validation import InputRangeError
from .blade import blade_segments
from .blank import BlankDesign
from .conjugate import NODE_MARGIN_MM, UndercutError, nominal_pinion_box
from .cutter import BladeCone, CutterPlacement
from .flank_reuse import reused
from .formate import FlankBoundary, FormateFlank, gear_flank
from .kinematics import MeshKinematics
from .generated_box import (LIMIT_FRACTION, active_box, edge_length_mm, edge_radius_bound_mm,
                            inch_hint)
from .machine import MachineKinematics, MachineSetup, blade_point
from .sheet import GearCone, GearSheet, RadialSheet

__all__ = ["ENVELOPE_MAX_STEP", "EnvelopeSolution", "EnvelopeSolver", "central_system",
           "damped_newton", "formate_gear_flank", "gear_cone", "gear_flank_of",
           "generated_gear_box", "generated_gear_flank", "generated_pinion_box",
           "generated_pinion_flank", "mean_contact_guess", "mean_uv", "solve_node_grid",
           "tip_setup", "work_to_body"]

_TOL = 1e-10          # node-equation residual, mm and mm/rad
_MAX_ITER = 40
#: Damping of the node solver: largest Newton step |dl| (mm), |dtheta|, |dpsi| (rad); a
#: warm-started node that moved farther than one such step left its branch
#: (:class:`~.setting_fit.FitProblem`).
ENVELOPE_MAX_STEP = np.array([0.5, 0.05, 0.05])
_FD = 1e-6            # central-difference step of the Jacobian (mm, rad)
#: |df/dpsi| or |det J| below this fraction of the mean node's: limit line / undercut.
_LIMIT_FRACTION = LIMIT_FRACTION
_PINION_Q = np.column_stack([[0.0, 0.0, 1.0], [0.0, -1.0, 0.0], [1.0, 0.0, 0.0]])


def central_system(residual, q: np.ndarray, step: float = _FD):
    """``(F, J)``: ``residual(q)`` (..., m) at parameters ``q`` (..., k) and its
    central-difference Jacobian (..., m, k), one batched evaluation of the ``2 k + 1``
    parameter sets."""
    k = q.shape[-1]
    d = step * np.vstack([np.zeros(k), np.eye(k), -np.eye(k)])
    F = residual(q[None] + d.reshape((2 * k + 1,) + (1,) * (q.ndim - 1) + (k,)))
    J = np.stack([(F[1 + i] - F[1 + k + i]) / (2.0 * step) for i in range(k)], axis=-1)
    return F[0], J


def damped_newton(system, q: np.ndarray, max_step: np.ndarray):
    """Batched Newton on ``system(q) -> (F, J)`` from ``q`` (..., k), each step scaled
    down to ``|dq_i| <= max_step[i]``, until every step is below 1e-13 (or
    ``_MAX_ITER`` steps): ``(q, F, J)`` at the result."""
    for _ in range(_MAX_ITER):
        F, J = system(q)
        step = -np.linalg.solve(J, F[..., None])[..., 0]
        scale = np.max(np.abs(step) / max_step, axis=-1, keepdims=True)
        q = q + step / np.maximum(scale, 1.0)
        if np.all(np.abs(step) < 1e-13):
            break
    F, J = system(q)
    return q, F, J


def work_to_body(member: str, blank: BlankDesign) -> tuple[np.ndarray, np.ndarray]:
    """``(Q, t)`` with ``X_body = Q X_w + t`` for ``member`` (module docstring)."""
    if member == "gear":
        p = blank.pitch_point_mm
        th = math.atan2(p[1], p[0])
        c, s = math.cos(th), math.sin(th)
        return (np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]),
                np.array([0.0, 0.0, blank.gear_apex_z_mm]))
    if member == "pinion":
        return _PINION_Q, np.array([blank.pinion_apex_x_mm, 0.0, 0.0])
    raise InputRangeError("member", member, "'gear' or 'pinion'")


def _cutter_in_body(setup: MachineSetup, blank: BlankDesign):
    """Tip-plane cutter centre and cutter axis in the member's body frame (zero roll)."""
    kin = MachineKinematics(setup.settings)
    q, t = work_to_body(setup.member, blank)
    x_w, n_w, _ = kin.to_work(np.zeros(3), np.array([0.0, 0.0, 1.0]), 0.0)
    return q @ x_w + t, q @ n_w


def formate_gear_flank(setup: MachineSetup, blank: BlankDesign, *, gear_face_width_mm: float
                       ) -> FormateFlank:
    """The gear flank a formate cut (no roll) with ``setup`` leaves: the blade cone in the
    gear body frame, with the parameters of :class:`~.formate.FormateFlank` (``u`` above
    the blade tip plane, ``h = h_f2 - u``) and the boundary of :func:`~.formate.gear_flank`.

    Raises
    ------
    InputRangeError
        A generated gear (ratio of roll or helical motion), a curved blade, or a blade
        kind that does not cut this flank (gear drive = convex = inside blade).
    """
    where = f"machine.gear.{setup.side}"
    if not setup.settings.formate:
        raise InputRangeError(f"{where}.ratio_of_roll", setup.settings.ratio_of_roll,
                              "0 with no helical motion (a formate gear; a rolled gear is "
                              "generated_gear_flank's)")
    want = "inside" if setup.side == "drive" else "outside"
    if setup.blade.kind != want:
        raise InputRangeError(f"blade.gear.{setup.side}.kind", setup.blade.kind,
                              f"'{want}' (the gear {setup.side} flank is "
                              f"{'convex' if want == 'inside' else 'concave'})")
    for key in ("profile_radius_mm", "profile_cubic_per_mm2", "profile_quartic_per_mm3"):
        if getattr(setup.blade, key) != 0.0:
            raise InputRangeError(f"blade.gear.{setup.side}.{key}", getattr(setup.blade, key),
                                  "0 for a formate gear (curved formate blades are not "
                                  "modelled)")
    tip, axis = _cutter_in_body(setup, blank)
    d = blank.dedendum_gear_mm
    centre = tip - d * axis          # the pitch plane of FormateFlank, h = 0
    P = np.asarray(blank.pitch_point_mm)
    e1 = (P - centre) - ((P - centre) @ axis) * axis
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(axis, e1)
    g2 = P - np.array([0.0, 0.0, blank.gear_apex_z_mm])
    placement = CutterPlacement(centre_mm=centre, axis=axis, e1=e1, e2=e2,
                                heel_sign=float(np.sign(e2 @ g2)))
    b = setup.blade
    alpha = math.radians(b.blade_angle_deg)
    cone = BladeCone(placement, b.point_radius_mm - b.sigma * d * math.tan(alpha),
                     b.blade_angle_deg, b.kind == "inside")
    return gear_flank(blank, cone, side=setup.side, gear_face_width_mm=gear_face_width_mm,
                      edge_radius_mm=b.edge_radius_mm,
                      blade_key=(f"blade.gear.{setup.side}.point_radius_mm", b.point_radius_mm))


@dataclass(frozen=True)
class EnvelopeSolution:
    """Solutions of the node equations of a generated flank (arrays).

    Attributes
    ----------
    l_mm, theta_rad, psi_rad : ndarray
        Blade arc length from the tip, blade angle and cradle roll of the generating point.
    x_mm, n : ndarray (..., 3)
        Flank point and unit normal out of the tooth, body frame.
    df_dpsi, jacobian_det : ndarray
        Derivative of the meshing function in the roll (limit-line indicator) and the
        determinant of the node Jacobian.
    residual : ndarray
        Largest |F| of the node equations.
    converged : ndarray of bool
    """

    l_mm: np.ndarray
    theta_rad: np.ndarray
    psi_rad: np.ndarray
    x_mm: np.ndarray
    n: np.ndarray
    df_dpsi: np.ndarray
    jacobian_det: np.ndarray
    residual: np.ndarray
    converged: np.ndarray

    @property
    def q(self) -> np.ndarray:
        """(..., 3) = (l, theta, psi), the next guess."""
        return np.stack([self.l_mm, self.theta_rad, self.psi_rad], axis=-1)


class EnvelopeSolver:
    """Node equations of a flank generated by ``setup`` on the sheet of ``cone``: the
    axial position and radius of the sheet point (u, v) and ``n . dX/dpsi = 0``
    (pinion, :class:`~.sheet.PinionCone`: ``X_x = v``, ``|X_yz| = R_f(v) + u``; gear,
    :class:`~.sheet.GearCone`: ``X_z = z(u, v)``, ``|X_xy| = R(u, v)``)."""

    def __init__(self, setup: MachineSetup, blank: BlankDesign, cone):
        self.setup, self.blank, self.cone = setup, blank, cone
        self.kin = MachineKinematics(setup.settings)
        self._q, self._t = work_to_body(setup.member, blank)
        # body axis of the member and the two radial components
        self._axes = (0, 1, 2) if setup.member == "pinion" else (2, 0, 1)

    def points(self, q: np.ndarray):
        """Body point, unit normal and meshing function ``f`` at (..., 3) = (l, theta, psi)."""
        x_t, n_t = blade_point(self.setup.blade, q[..., 0], q[..., 1])
        return self.place(x_t, n_t, q[..., 2])

    def place(self, x_t, n_t, psi_rad):
        """Cutter-frame points and normals (..., 3) at cradle roll ``psi`` -> body point,
        unit normal and meshing function ``f = n_w . dX_w/dpsi``."""
        x_w, n_w, v_w = self.kin.to_work(x_t, n_t, psi_rad)
        f = np.einsum("...i,...i->...", n_w, v_w)
        return x_w @ self._q.T + self._t, n_w @ self._q.T, f

    def sheet_parameters(self, x):
        """Sheet parameters ``(u, v)`` of body points ``x`` (..., 3) (``cone.parameters``
        of their axial position and radius)."""
        a, b, c = self._axes
        return self.cone.parameters(x[..., a], np.hypot(x[..., b], x[..., c]))

    def _residual(self, q, x_t, r_t):
        x, _, f = self.points(q)
        a, b, c = self._axes
        return np.stack([x[..., a] - x_t, np.hypot(x[..., b], x[..., c]) - r_t, f], axis=-1)

    def rotate(self, x, angle_rad: float):
        """Body vectors ``x`` (..., 3) turned about the member axis by ``angle_rad`` (their
        :meth:`angle` grows by it)."""
        _, b, c = self._axes
        cs, sn = math.cos(angle_rad), math.sin(angle_rad)
        out = np.array(x, dtype=float, copy=True)
        out[..., b], out[..., c] = cs * x[..., b] - sn * x[..., c], sn * x[..., b] + cs * x[..., c]
        return out

    def angle(self, x):
        """Angular coordinate of body points about the member axis (the sheet's psi)."""
        _, b, c = self._axes
        return np.arctan2(x[..., c], x[..., b])

    def _system(self, q, x_t, r_t):
        """Residual (..., 3) and central-difference Jacobian (..., 3, 3)."""
        return central_system(lambda qs: self._residual(qs, x_t, r_t), q)

    def initial_guess(self, u: float, v: float) -> np.ndarray:
        """(l, theta, psi) of the blade point nearest the sheet point (u, v) at zero roll."""
        rad, h = float(self.cone.radius_mm(u, v)), float(self.cone.height_mm(u, v))
        if self.setup.member == "pinion":
            p = np.array([h, 0.0, rad])   # near the pinion's mean azimuth (+z)
        else:
            th = self.cone.mean_azimuth_rad
            p = np.array([rad * math.cos(th), rad * math.sin(th), h])
        x_w = self._q.T @ (p - self._t)
        c0, t0, b, a0 = self.kin._fixed
        x_c = t0.T @ (b @ x_w + a0 - c0)
        alpha = math.radians(self.setup.blade.blade_angle_deg)
        return np.array([max(-x_c[2], 0.0) / math.cos(alpha), math.atan2(x_c[1], x_c[0]), 0.0])

    def solve(self, u, v, guess, *, strict: bool = True) -> EnvelopeSolution:
        """Solve the node equations at pinion (u, v) (arrays) from ``guess`` (..., 3).

        Raises
        ------
        UndercutError
            A node without a solution (``strict``): the envelope does not reach it.
        """
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        x_t, r_t = self.cone.height_mm(u, v), self.cone.radius_mm(u, v)
        q = np.array(np.broadcast_to(guess, u.shape + (3,)), dtype=float)
        q, F, J = damped_newton(lambda q: self._system(q, x_t, r_t), q, ENVELOPE_MAX_STEP)
        res = np.max(np.abs(F), axis=-1)
        ok = (res < _TOL) & np.all(np.isfinite(q), axis=-1)
        if strict and not np.all(ok):
            i = tuple(int(k) for k in np.argwhere(~ok)[0])
            raise UndercutError(f"{self.setup.member} {self.setup.side} flank at (u, v) = "
                                f"({u[i]:.4f}, {v[i]:.4f}) mm", f"residual {res[i]:.3e}",
                                "a node the generated envelope reaches (check "
                                f"[machine.{self.setup.member}.{self.setup.side}] and "
                                f"[blade.{self.setup.member}.{self.setup.side}])")
        x, n, _ = self.points(q)
        return EnvelopeSolution(l_mm=q[..., 0], theta_rad=q[..., 1], psi_rad=q[..., 2],
                                x_mm=x, n=n, df_dpsi=J[..., 2, 2],
                                jacobian_det=np.linalg.det(J), residual=res, converged=ok)


def generated_pinion_flank(setup: MachineSetup, blank: BlankDesign, *,
                           pinion_face_width_mm: float, n_u: int = 120, n_v: int = 150,
                           box: FlankBoundary | None = None
                           ) -> tuple[RadialSheet, EnvelopeSolution]:
    """The pinion flank ``setup`` generates, on an n_u x n_v exact node grid.

    The active box is the pinion's nominal one (clearance line to tip, pinion face
    width) with its root raised to the line generated by the top of the blade's edge
    round (:func:`~.generated_box.active_box`); the node grid carries the margin of
    :data:`~.conjugate.NODE_MARGIN_MM`.

    Returns
    -------
    flank : RadialSheet
    nodes : EnvelopeSolution
        The exact node solutions, shape (n_u, n_v).

    ``box`` replaces the active box traced with ``setup``'s blade (a piece of a
    relieved blade's flank takes the box its tip segment traces, :mod:`.kinked`).

    Raises
    ------
    InputRangeError
        Wrong blade kind for the flank (pinion drive = concave = outside blade).
    UndercutError
        A node the envelope does not reach, a limit line (df/dpsi changing sign or
        vanishing) or a singular envelope inside the node box, or an active flank
        reaching the blade's edge round.
    """
    if box is None:
        solver, box, mean = generated_pinion_box(setup, blank,
                                                 pinion_face_width_mm=pinion_face_width_mm)
    else:
        _check_kind(setup, "outside" if setup.side == "drive" else "inside")
        solver, mean = _solver_at_mean(setup, blank, nominal_pinion_box(
            blank, pinion_face_width_mm)[0])
    return _sheet_of(solver, box, mean, setup, n_u, n_v, RadialSheet)


def _solver_at_mean(setup: MachineSetup, blank: BlankDesign, cone):
    """The :class:`EnvelopeSolver` of ``setup`` on ``cone`` and its mean-node solution."""
    solver = EnvelopeSolver(setup, blank, cone)
    u_m, v_m = mean_uv(setup, blank, cone)
    return solver, solver.solve(u_m, v_m, solver.initial_guess(u_m, v_m))


def _sheet_of(solver, box, mean, setup, n_u, n_v, kind, node_box=None):
    """The node grid over ``node_box`` (default: ``box`` with the node margin) solved by
    continuation from the mean node, checked, and its spline sheet of class ``kind``."""
    if int(n_u) != n_u or n_u < 6 or int(n_v) != n_v or n_v < 6:
        raise InputRangeError("n_u, n_v", (n_u, n_v), "integers >= 6 (quintic spline)")
    cone = solver.cone
    u_m, v_m = mean_uv(setup, solver.blank, cone)
    nb = node_box or FlankBoundary(box.u_root - NODE_MARGIN_MM[0], box.u_tip + NODE_MARGIN_MM[0],
                                   box.v_toe - NODE_MARGIN_MM[1], box.v_heel + NODE_MARGIN_MM[1])
    us = np.linspace(nb.u_root, nb.u_tip, int(n_u))
    vs = np.linspace(nb.v_toe, nb.v_heel, int(n_v))
    try:
        nodes = solve_node_grid(solver, us, vs, u_m, v_m, mean.q)
    except UndercutError as exc:      # say where the node lies against the active flank
        raise UndercutError(exc.field, exc.value, (
            f"{exc.allowed}; the active flank is u = [{box.u_root:.4f}, {box.u_tip:.4f}] mm, "
            f"v = [{box.v_toe:.4f}, {box.v_heel:.4f}] mm, its node grid u = [{nb.u_root:.4f}, "
            f"{nb.u_tip:.4f}], v = [{nb.v_toe:.4f}, {nb.v_heel:.4f}] mm (the envelope folds "
            "or ends before that node: docs/machine_settings.md sec. 5)")) from None
    _check_regular(nodes, mean, setup, us, vs, box)
    psi = np.unwrap(np.unwrap(solver.angle(nodes.x_mm), axis=0), axis=1)
    flank = kind(side=setup.side, cone=cone, u_nodes=us, v_nodes=vs, psi_nodes=psi,
                 normal_sign=1.0, boundary=box)
    i0, j0 = int(np.argmin(np.abs(us - u_m))), int(np.argmin(np.abs(vs - v_m)))
    if float(flank.point(us[i0], vs[j0]).n @ nodes.n[i0, j0]) < 0.0:
        flank = kind(side=setup.side, cone=cone, u_nodes=us, v_nodes=vs, psi_nodes=psi,
                     normal_sign=-1.0, boundary=box)
    return flank, nodes


def mean_uv(setup: MachineSetup, blank: BlankDesign, cone) -> tuple[float, float]:
    """Sheet parameters of the mean node (pitch cone, mean section)."""
    if setup.member == "pinion":
        return float(cone.root_offset_mm), float(blank.pitch_point_mm[0])
    return float(blank.dedendum_gear_mm), 0.0


def generated_gear_flank(setup: MachineSetup, blank: BlankDesign, *, gear_face_width_mm: float,
                         n_u: int = 120, n_v: int = 150, node_box=None,
                         box: FlankBoundary | None = None
                         ) -> tuple[GearSheet, EnvelopeSolution]:
    """The gear flank ``setup`` generates (ratio of roll or helical motion), on an
    n_u x n_v exact node grid: a :class:`~.sheet.GearSheet` over the gear's pitch-cone
    coordinates (``u`` above the root along the pitch-cone normal, ``v`` cone distance
    from the mean section), box from the blade edge line
    (:func:`~.generated_box.active_box`) to the tip and over the gear face width; the
    nodes cover ``node_box`` (a :class:`~.formate.FlankBoundary` holding the box;
    default: the box with the node margin; a gear that generates a conjugate pinion needs
    more, a function of ``box`` and the solver: :mod:`.gear_generation`); ``box`` as
    :func:`generated_pinion_flank`'s.

    Raises
    ------
    InputRangeError
        A blade kind that does not cut this flank (gear drive = convex = inside blade).
    UndercutError
        As :func:`generated_pinion_flank`.
    """
    if box is None:
        solver, box, mean = generated_gear_box(setup, blank,
                                               gear_face_width_mm=gear_face_width_mm)
    else:
        _check_kind(setup, "inside" if setup.side == "drive" else "outside")
        solver, mean = _solver_at_mean(setup, blank, gear_cone(blank))
    if callable(node_box):
        node_box = node_box(solver, box, mean)
    return _sheet_of(solver, box, mean, setup, n_u, n_v, GearSheet, node_box)


@reused
def generated_gear_box(setup: MachineSetup, blank: BlankDesign, *, gear_face_width_mm: float
                       ) -> tuple[EnvelopeSolver, FlankBoundary, EnvelopeSolution]:
    """The cheap first step of :func:`generated_gear_flank` (as
    :func:`generated_pinion_box`; reused as it is)."""
    _check_kind(setup, "inside" if setup.side == "drive" else "outside")
    setup = tip_setup(setup)
    cone = gear_cone(blank)
    half = 0.5 * gear_face_width_mm
    nominal = FlankBoundary(u_root=0.0, u_tip=blank.dedendum_gear_mm + blank.addendum_gear_mm,
                            v_toe=-half, v_heel=half)
    solver, mean = _solver_at_mean(setup, blank, cone)
    u_m, v_m = mean_uv(setup, blank, cone)
    return solver, active_box(solver, nominal, u_m, v_m, mean, edge_length_mm(setup)), mean


def gear_cone(blank: BlankDesign) -> GearCone:
    """The :class:`~.sheet.GearCone` of the blank's gear flanks (pitch cone, mean
    section, the mean point's azimuth)."""
    d2 = math.radians(blank.pitch_angle_gear_deg)
    p = blank.pitch_point_mm
    return GearCone(apex_z_mm=blank.gear_apex_z_mm, sin_delta=math.sin(d2),
                    cos_delta=math.cos(d2),
                    mean_cone_distance_mm=blank.mean_cone_distance_gear_mm,
                    dedendum_mm=blank.dedendum_gear_mm,
                    mean_azimuth_rad=math.atan2(p[1], p[0]))


def tip_setup(setup: MachineSetup) -> MachineSetup:
    """``setup`` with a relieved blade replaced by its tip segment's smooth blade
    (:func:`~.blade.blade_segments`: it carries the edge round and generates the root of
    the active flank, hence its box and fillet); ``setup`` itself otherwise."""
    if not setup.blade.relieved:
        return setup
    return dataclasses.replace(setup, blade=blade_segments(setup.blade)[0].blade)


def gear_flank_of(setup: MachineSetup, blank: BlankDesign, *, gear_face_width_mm: float,
                  n_u: int = 120, n_v: int = 150):
    """The gear flank ``setup`` cuts: :func:`formate_gear_flank` for a formate cut (no
    roll, no helical motion), else :func:`generated_gear_flank`."""
    if setup.settings.formate:
        return formate_gear_flank(setup, blank, gear_face_width_mm=gear_face_width_mm)
    return generated_gear_flank(setup, blank, gear_face_width_mm=gear_face_width_mm,
                                n_u=n_u, n_v=n_v)[0]


def _check_kind(setup: MachineSetup, want: str) -> None:
    if setup.blade.kind != want:
        shape = "convex" if (want == "inside") else "concave"
        raise InputRangeError(f"blade.{setup.member}.{setup.side}.kind", setup.blade.kind,
                              f"'{want}' (the {setup.member} {setup.side} flank is {shape})")


@reused
def generated_pinion_box(setup: MachineSetup, blank: BlankDesign, *,
                         pinion_face_width_mm: float
                         ) -> tuple[EnvelopeSolver, FlankBoundary, EnvelopeSolution]:
    """The envelope solver, the active box and the mean-node solution of the pinion flank
    ``setup`` generates: the cheap first step of :func:`generated_pinion_flank` (a few
    lengthwise sections, no grid), run by :func:`~.generation.check_generation`.
    Within :func:`~.flank_reuse.reusing_flanks` a call with the same inputs is served
    the box traced before (:func:`~.flank_reuse.reused`: the reader's check and the
    flank's cut trace it once).

    Raises
    ------
    InputRangeError
        Wrong blade kind for the flank (pinion drive = concave = outside blade).
    UndercutError
        No mean node, or an active profile under 10 % of the nominal one.
    """
    _check_kind(setup, "outside" if setup.side == "drive" else "inside")
    setup = tip_setup(setup)
    cone, nominal = nominal_pinion_box(blank, pinion_face_width_mm)
    solver, mean = _solver_at_mean(setup, blank, cone)
    u_m, v_m = mean_uv(setup, blank, cone)
    return solver, active_box(solver, nominal, u_m, v_m, mean, edge_length_mm(setup)), mean


def solve_node_grid(solver: EnvelopeSolver, us, vs, u_m, v_m, q_mean) -> EnvelopeSolution:
    """Node solutions on the grid ``us`` x ``vs``, shape (n_u, n_v), by continuation
    from the mean node ``(u_m, v_m)`` (guess ``q_mean``): the profile column nearest
    the mean section first, then column by column with extrapolated guesses."""
    j0, i0 = int(np.argmin(np.abs(vs - v_m))), int(np.argmin(np.abs(us - u_m)))
    q = np.empty((len(us), len(vs), 3))
    q[i0, j0] = solver.solve(us[i0], vs[j0], q_mean).q
    for rng in (range(i0 + 1, len(us)), range(i0 - 1, -1, -1)):
        prev = q[i0, j0]
        for i in rng:
            q[i, j0] = prev = solver.solve(us[i], vs[j0], prev).q
    cols: list = [None] * len(vs)
    cols[j0] = solver.solve(us, np.full_like(us, vs[j0]), q[:, j0])
    for rng, back in ((range(j0 + 1, len(vs)), -1), (range(j0 - 1, -1, -1), 1)):
        for j in rng:
            done = abs(j - j0)
            if done >= 2:
                guess = 2.0 * q[:, j + back] - q[:, j + 2 * back]
            else:
                guess = q[:, j + back]
            cols[j] = s = solver.solve(us, np.full_like(us, vs[j]), guess)
            q[:, j] = s.q
    return EnvelopeSolution(**{f: np.stack([getattr(c, f) for c in cols], axis=1)
                               for f in EnvelopeSolution.__dataclass_fields__})


def _check_regular(nodes: EnvelopeSolution, mean: EnvelopeSolution, setup: MachineSetup,
                   us, vs, box: FlankBoundary) -> None:
    """Raise :class:`UndercutError` at a limit line, a singular envelope or an active
    flank cut by the blade's edge round."""
    where = f"{setup.member} {setup.side} flank"
    bad = nodes.df_dpsi / float(mean.df_dpsi) < _LIMIT_FRACTION
    sing = np.abs(nodes.jacobian_det) < _LIMIT_FRACTION * abs(float(mean.jacobian_det))
    for mask, what in ((bad, "df/dpsi of the mean node's sign (limit line of the envelope)"),
                       (sing, "a regular envelope (no limit line)")):
        if np.any(mask):
            i, j = (int(k) for k in np.argwhere(mask)[0])
            raise UndercutError(f"{where} at (u, v) = ({us[i]:.4f}, {vs[j]:.4f}) mm",
                                float(nodes.df_dpsi[i, j]), what)
    l_edge = edge_length_mm(setup) - 1e-9   # the box's root lies on l = l_edge
    inside = (us >= box.u_root)[:, None] & (vs >= box.v_toe)[None, :] & (vs <= box.v_heel)[None, :]
    if np.any(inside & (nodes.l_mm < l_edge)):
        i, j = (int(k) for k in np.argwhere(inside & (nodes.l_mm < l_edge))[0])
        raise UndercutError(f"{where} at (u, v) = ({us[i]:.4f}, {vs[j]:.4f}) mm",
                            f"blade arc length {nodes.l_mm[i, j]:.4f} mm",
                            f">= {l_edge:.4f} mm (above the blade edge round: the active "
                            f"flank would be cut by the edge; {_edge_fix(setup, nodes.l_mm[i, j])}"
                            "lower the sliding base or the blade point)")


def _edge_fix(setup: MachineSetup, l_node_mm: float) -> str:
    """The edge radius whose round ends at the blade arc length ``l_node_mm``
    (:func:`~.generated_box.edge_radius_bound_mm`), named as a fix of
    :func:`_check_regular`'s message: ``"<key> = r mm: at most r_max mm ..., or "`` (a
    value 25.4 times too large named so), or ``""`` for a sharp blade."""
    blade = setup.blade
    if blade.edge_radius_mm <= 0.0 or l_node_mm <= 0.0:
        return ""
    lo = edge_radius_bound_mm(setup, l_node_mm)
    return (f"{blade.where}.edge_radius_mm = {blade.edge_radius_mm:g} mm: at most "
            f"{lo:.4f} mm keeps its round below this node{inch_hint(blade, lo)}, or ")


def mean_contact_guess(pinion, gear, kinematics: MeshKinematics, *, pinion_uv, gear_uv
                       ) -> dict:
    """The contact of the pinion point ``pinion_uv`` with the gear flank, a starting guess
    for TCA: ``{"pinion_uv", "gear_uv", "phi1_rad", "phi2_rad", "gap_mm",
    "normal_angle_deg"}``.

    Least squares over (u2, v2, phi1, phi2) of the coincidence of the posed points and
    opposite normals (6 equations; exact for conjugate flanks, the nearest touch otherwise).
    ``gap_mm`` and ``normal_angle_deg`` are what is left at the nearest touch: the
    distance of the posed points and the angle between the pinion normal and the
    reversed gear normal (0 where the flanks touch there with a common normal, as mates
    do at the pinion's mean node).
    """
    u1, v1 = (float(x) for x in pinion_uv)
    p1 = pinion.point(u1, v1)

    def residual(z):
        u2, v2, phi1, phi2 = z
        r1, _ = kinematics.pinion_pose(phi1)
        r2, _ = kinematics.gear_pose(phi2)
        g = gear.point(u2, v2)
        x1 = r1 @ p1.r + kinematics.pinion_centre
        x2 = r2 @ g.r
        return np.concatenate([x1 - x2, r1 @ p1.n + r2 @ g.n])

    sol = least_squares(residual, np.array([*gear_uv, 0.0, 0.0]), xtol=1e-15, ftol=1e-15,
                        gtol=1e-15)
    u2, v2, phi1, phi2 = (float(x) for x in sol.x)
    left = residual(sol.x)              # (x1 - x2, n1 + n2) at the nearest touch
    n1 = kinematics.pinion_pose(phi1)[0] @ p1.n
    cos = float(np.clip(n1 @ (n1 - left[3:]), -1.0, 1.0))     # n1 . (-n2)
    return {"pinion_uv": (u1, v1), "gear_uv": (u2, v2), "phi2_rad": phi2,
            "phi1_rad": phi1, "gap_mm": float(np.linalg.norm(left[:3])),
            "normal_angle_deg": math.degrees(math.acos(cos))}
