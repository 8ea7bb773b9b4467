"""Root fillets of bevel and hypoid members: the surface the blade's edge round cuts.

Below the active flank the blade's tip edge round (:class:`~.machine.EdgeRound`, radius
``r_e``, tangent to the tip plane and to the blade profile) cuts the root fillet
(docs/machine_settings.md sec. 4). Parameters of a :class:`RootFillet` (mm):

- ``u = s``, the arc length on the round from its bottom (the tip plane: the member's
  root) up to the profile, ``s_top = r_e (pi/2 - alpha_top)``: the fillet's top row is
  the flank's lower limit line (the line the profile's tangent point cuts), where the
  round's point and normal are the profile's;
- ``v``, the flank's own lengthwise parameter (formate gear: arc length on the blade
  circle in the pitch plane; generated gear: cone distance from the mean section;
  pinion: axial position), over the flank's box.

**Formate gear**: the fillet is the torus of the edge round itself, the round revolved
about the cutter axis (a surface of revolution: no envelope), at the flank's blade
angle ``theta = k_v v``.

**Generated member**: the envelope of the torus in the generating motion of the
flank's machine settings, ``n_w . dX_w/dpsi = 0`` (Litvin & Fuentes 2004, sec. 6.1),
solved at each (s, v) for the blade angle ``theta`` and the cradle roll ``psi``
(equations: the sheet's ``v`` of the work point and the equation of meshing; Newton
with a central-difference Jacobian). A node grid is found by continuation from the
flank's mean node down the profile to its tangent point and on down the round; any
(s, v) is then solved from the grid's interpolated guess (exact, not interpolated).
A fillet can be turned about the member axis onto a flank whose angular position is a
mounting choice (the machine-cut pinion, :func:`~.flank.build_machine_flanks`) and
mirrored for a left-hand member (:mod:`.mirror`).

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 6.1
(envelopes), ch. 20-21 (head cutters with edge round: the fillet of face-milled gears).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import RegularGridInterpolator

from ..validation import InputRangeError
from .conjugate import UndercutError
from .formate import SIDES, FormateFlank
from .generated import (EnvelopeSolver, central_system, damped_newton, generated_gear_box,
                        generated_pinion_box)
from .machine import BladeSettings, EdgeRound, MachineSetup, blade_point, edge_round
from .mirror import MIRROR

__all__ = ["FilletArrays", "FormateFillet", "GeneratedFillet", "RootFillet",
           "formate_fillet", "generated_fillet", "pair_fillets"]

_TOL = 1e-10          # residual of the fillet equations, mm and mm/rad
_MAX_STEP = np.array([0.05, 0.05])   # damping: |dtheta|, |dpsi|, rad
#: Steps down the blade profile from the mean node to the round's tangent point.
_PROFILE_STEPS = 8


@dataclass(frozen=True)
class FilletArrays:
    """Fillet points at arrays of parameters (shapes broadcast, vectors (..., 3)).

    Attributes
    ----------
    u, v : ndarray
        Arc length on the edge round from the root (mm) and the flank's lengthwise
        parameter (mm).
    r, n : ndarray
        Point (mm) and unit normal out of the tooth material, member body frame.
    theta_rad, psi_rad : ndarray
        Blade angle and cradle roll of the generating cutter point (formate: roll 0).
    """

    u: np.ndarray
    v: np.ndarray
    r: np.ndarray
    n: np.ndarray
    theta_rad: np.ndarray
    psi_rad: np.ndarray


@dataclass(frozen=True, eq=False)
class RootFillet:
    """The root fillet below one flank (module docstring): ``evaluate(u, v)`` over
    ``u_range x v_range``. Not a contact :class:`~.surface.Surface` (no second
    derivatives): what the export and the structure take."""

    member: str
    side: str
    edge: EdgeRound
    v_range: tuple
    mirrored: bool

    @property
    def u_range(self) -> tuple[float, float]:
        """``(0, s_top)``: root -> flank, mm."""
        return (0.0, self.edge.top_arc_mm)

    @property
    def width_mm(self) -> float:
        """Arc length of the edge round from the root to the flank, mm."""
        return self.edge.top_arc_mm

    def evaluate(self, u, v) -> FilletArrays:
        """Points and normals at arrays ``u`` (mm on the round from the root) and ``v``."""
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        lo, hi = self.u_range
        if np.any((u < lo - 1e-9) | (u > hi + 1e-9)):
            raise InputRangeError(f"{self.member} {self.side} fillet u", float(
                u[(u < lo - 1e-9) | (u > hi + 1e-9)][0]), f"[{lo}, {hi}] mm (the edge round)")
        r, n, th, psi = self._points(u, v)
        if self.mirrored:
            r, n = r @ MIRROR, n @ MIRROR
        return FilletArrays(u=u, v=v, r=r, n=n, theta_rad=th, psi_rad=psi)


@dataclass(frozen=True, eq=False)
class FormateFillet(RootFillet):
    """The torus of the edge round of a formate gear's blade, in the gear body frame:
    cutter frame origin ``origin`` (the tip plane's centre), axes ``frame`` (columns
    ``e1, e2, a``), blade angle ``theta = k_v v`` as ``flank``'s."""

    origin: np.ndarray
    frame: np.ndarray
    flank: FormateFlank

    def _points(self, u, v):
        th = self.flank.blade_parameters(u, v)[1]
        x_t, n_t = self.edge.point(u, th)
        return x_t @ self.frame.T + self.origin, n_t @ self.frame.T, th, np.zeros_like(th)


@dataclass(frozen=True, eq=False)
class GeneratedFillet(RootFillet):
    """The envelope of the edge round in the generating motion of ``solver``'s set-up:
    node grid ``(s_nodes, v_nodes)`` of ``(theta, psi)`` (the guesses), turned about the
    member axis by ``turn_rad`` (the sheet's angle grows by it)."""

    solver: EnvelopeSolver
    s_nodes: np.ndarray
    v_nodes: np.ndarray
    q_nodes: np.ndarray        # (n_s, n_v, 2): theta, psi
    turn_rad: float

    def _points(self, u, v):
        guess = RegularGridInterpolator((self.s_nodes, self.v_nodes), self.q_nodes,
                                        bounds_error=False, fill_value=None)(
            np.stack([u, v], axis=-1))
        q, res, _ = _solve(self.solver, self.edge.point, u, v, guess)
        if not np.all(res < _TOL):
            k = tuple(int(i) for i in np.argwhere(~(res < _TOL))[0])
            raise UndercutError(f"{self.member} {self.side} fillet at (s, v) = "
                                f"({u[k]:.4f}, {v[k]:.4f}) mm", f"residual {res[k]:.3e}",
                                "a point the edge round's envelope reaches")
        x, n = _placed(self.solver, self.edge.point, u, q)[:2]
        return (self.solver.rotate(x, self.turn_rad), self.solver.rotate(n, self.turn_rad),
                q[..., 0], q[..., 1])


def _placed(solver: EnvelopeSolver, cut, a, q):
    """Body point, normal and meshing function of cutter point ``cut(a, theta)`` at roll
    ``psi`` (``q = (theta, psi)``), and the sheet's ``v`` of the point."""
    x_t, n_t = cut(a, q[..., 0])
    x, n, f = solver.place(x_t, n_t, q[..., 1])
    return x, n, f, solver.sheet_parameters(x)[1]


def _solve(solver: EnvelopeSolver, cut, a, v, guess):
    """Solve ``v(X) = v``, ``f = 0`` for ``(theta, psi)`` at the cutter points
    ``cut(a, theta)`` (arrays; :func:`~.generated.damped_newton` with a central-difference
    Jacobian from ``guess`` (..., 2)): ``(q, residual, det J)``."""
    a, v = np.broadcast_arrays(np.asarray(a, dtype=float), np.asarray(v, dtype=float))
    q = np.array(np.broadcast_to(guess, a.shape + (2,)), dtype=float)

    def residual(qs):
        _, _, f, vv = _placed(solver, cut, a, qs)
        return np.stack([vv - v, f], axis=-1)

    q, F, J = damped_newton(lambda q: central_system(residual, q), q, _MAX_STEP)
    res = np.where(np.all(np.isfinite(q), axis=-1), np.max(np.abs(F), axis=-1), np.inf)
    return q, res, np.linalg.det(J)


def _check(res, where: str, what: str) -> None:
    if not np.all(res < _TOL):
        raise UndercutError(where, f"residual {float(np.max(res)):.3e}", what)


def formate_fillet(flank: FormateFlank, *, edge_radius_mm: float, where: str = "cutter"
                   ) -> FormateFillet:
    """The fillet below a formate gear flank: the torus of the edge round of radius
    ``edge_radius_mm`` of the flank's blade cone (``where``: the table naming the edge
    radius in an error).

    Raises
    ------
    InputRangeError
        A zero edge radius (:func:`~.machine.edge_round`).
    """
    cone, pl = flank.blade, flank.blade.placement
    d = flank.dedendum_mm               # the blade tips lie at depth h = d (the root)
    blade = BladeSettings(kind="inside" if cone.inside else "outside",
                          blade_angle_deg=cone.pressure_angle_deg,
                          point_radius_mm=float(cone.radius_mm(d)),
                          edge_radius_mm=edge_radius_mm, where=where)
    a = np.asarray(pl.axis, dtype=float)
    return FormateFillet(member="gear", side=flank.side, edge=edge_round(blade),
                         v_range=flank.v_range, mirrored=False,
                         origin=np.asarray(pl.centre_mm, dtype=float) + d * a,
                         frame=np.column_stack([pl.e1, pl.e2, a]), flank=flank)


def generated_fillet(setup: MachineSetup, blank, *, face_width_mm: float, flank=None,
                     n_s: int = 9, n_v: int = 25) -> GeneratedFillet:
    """The fillet ``setup`` generates below its flank (module docstring), with an
    ``n_s`` x ``n_v`` node grid over the flank's box.

    ``flank``: the member's flank sheet (:class:`~.sheet.RadialSheet` /
    :class:`~.sheet.GearSheet`) whose angular position the fillet takes (its angle at
    the mean node against the envelope's; default: the envelope's own).

    Raises
    ------
    InputRangeError
        A zero edge radius, a wrong blade kind (:mod:`.generated`).
    UndercutError
        A point the edge round's envelope does not reach from the flank's mean node.
    """
    if setup.blade.edge_radius_mm == 0.0:
        raise InputRangeError(f"blade.{setup.member}.{setup.side}.edge_radius_mm", 0.0,
                              "> 0 for a root fillet (a sharp blade tip cuts no fillet "
                              "surface: the flank runs into the root)")
    rnd = edge_round(setup.blade)
    box_of = generated_pinion_box if setup.member == "pinion" else generated_gear_box
    key = "pinion_face_width_mm" if setup.member == "pinion" else "gear_face_width_mm"
    solver, box, mean = box_of(setup, blank, **{key: face_width_mm})
    where = f"{setup.member} {setup.side} fillet"
    v_m = float(solver.sheet_parameters(mean.x_mm)[1])
    vs = np.linspace(box.v_toe, box.v_heel, int(n_v))
    profile = lambda l_mm, th: blade_point(setup.blade, l_mm, th)  # noqa: E731
    # the mean node's blade line across the face (continuation from the mean section)
    q = np.empty((len(vs), 2))
    j0 = int(np.argmin(np.abs(vs - v_m)))
    for order in (range(j0, len(vs)), range(j0 - 1, -1, -1)):
        prev, v_prev = np.array([mean.theta_rad, mean.psi_rad], dtype=float), v_m
        for j in order:
            for v in np.linspace(v_prev, vs[j], 3)[1:]:
                prev, res, _ = _solve(solver, profile, mean.l_mm, v, prev)
                _check(res, f"{where} at v = {v:.4f} mm", "the mean node's blade line")
            q[j], v_prev = prev, vs[j]
    # down the profile to the round's tangent point, then down the round
    for l_mm in np.linspace(float(mean.l_mm), rnd.top_length_mm, _PROFILE_STEPS + 1)[1:]:
        q, res, _ = _solve(solver, profile, l_mm, vs, q)
        _check(res, f"{where} at blade arc {l_mm:.4f} mm", "the flank's lower limit line")
    ss = np.linspace(rnd.top_arc_mm, 0.0, int(n_s))
    rows, sign = [], None
    for s in ss:
        q, res, det = _solve(solver, rnd.point, s, vs, q)
        _check(res, f"{where} at s = {s:.4f} mm", "the edge round's envelope")
        sign = np.sign(det[0]) if sign is None else sign
        if np.any(np.sign(det) != sign):     # the envelope folds: a limit line
            j = int(np.argmax(np.sign(det) != sign))
            raise UndercutError(f"{where} at (s, v) = ({s:.4f}, {vs[j]:.4f}) mm",
                                f"Jacobian determinant {det[j]:.3e}",
                                "a regular envelope of the edge round (no limit line on "
                                "the fillet: check the settings and the edge radius)")
        rows.append(q)
    turn = 0.0
    if flank is not None:
        u_m = float(solver.sheet_parameters(mean.x_mm)[0])
        turn = float(flank.psi(u_m, v_m)) - float(solver.angle(mean.x_mm))
        turn = (turn + math.pi) % (2.0 * math.pi) - math.pi
    return GeneratedFillet(member=setup.member, side=setup.side, edge=rnd,
                           v_range=(box.v_toe, box.v_heel), mirrored=False, solver=solver,
                           s_nodes=ss[::-1].copy(), v_nodes=vs, q_nodes=np.stack(rows[::-1]),
                           turn_rad=turn)


def pair_fillets(pair, flanks, *, conjugate_pinion: bool = False) -> tuple[dict, dict]:
    """The root fillets of ``pair``'s members whose cutter is known, as built into
    ``flanks`` (:func:`~.flank.build_flanks`): ``({(member, side): RootFillet},
    {(member, side): why none})``.

    Machine settings: every member (formate gear: the torus; generated gear and pinion:
    the envelope, turned onto the flank). Without: the formate gear with the
    ``[cutter]`` edge radius, or the generated default gear with the settings of
    :func:`~.basic_settings.generated_gear_setups`; the conjugate pinion has no cutter
    of its own (it is solved from the gear, not cut).

    ``conjugate_pinion``: give the conjugate pinion the fillet of the generating tool
    that cuts its flanks exactly, the pinion set-up of
    :func:`~.basic_settings.member_setups` (formate gear: the complementary generating
    gear, the gear's own blade cones with the ``[cutter]`` edge radius rolled in the
    meshing motion, their tips on the pinion's root cone; generated gear: the crown
    gear). Why this surface (``docs/bending.md`` sec. 10): it is how such a pinion is
    cut, and the generating gear is the mating gear deepened by the clearance in the same
    relative motion, so the space it sweeps contains the mating gear tip's: of the two
    candidate roots (the tool's fillet, the envelope of the mating gear's tip edge) it
    leaves the thinner, more compliant one, the conservative choice for bending. It
    meets the flank below the flank box (``u_range[0]``) of the conjugate / eased-off
    sheet, through the strip of generated flank the sheet does not cover.

    A left-hand pair's fillets are its right-hand twin's, mirrored.
    """
    from .basic_settings import generated_gear_setups, member_setups
    from .flank import right_hand_twin

    if pair.pinion_hand == "left":
        got, why = pair_fillets(right_hand_twin(pair), flanks.right_hand_twin,
                                conjugate_pinion=conjugate_pinion)
        return ({k: _mirrored(f) for k, f in got.items()}, why)
    setups = {(s.member, s.side): s for s in pair.machine}
    if not setups and flanks.gear_generation == "generated":
        setups = {("gear", side): s for side, s in generated_gear_setups(pair).items()}
    if conjugate_pinion and not pair.machine:
        setups.update({("pinion", side): s for side, s in
                       member_setups(pair, flanks.gear_generation)[1].items()})
    got, why = {}, {}
    for member in ("pinion", "gear"):
        for side in SIDES:
            flank, setup = flanks.flank(member, side), setups.get((member, side))
            # a relieved blade's edge round is tangent to its tip segment, whose piece
            # holds the root of a kinked flank (geometry.kinked)
            tip = getattr(flank, "pieces", (flank,))[0]
            try:
                if isinstance(tip, FormateFlank):
                    r_e, at = ((setup.blade.edge_radius_mm, setup.blade.where) if setup
                               else (pair.cutter.edge_radius_mm, "cutter"))
                    got[member, side] = formate_fillet(tip, edge_radius_mm=r_e, where=at)
                elif setup is not None:
                    width = getattr(pair, f"{member}_face_width_mm")
                    got[member, side] = generated_fillet(setup, pair.blank,
                                                         face_width_mm=width, flank=flank)
                else:
                    why[member, side] = ("no cutter (the conjugate pinion is solved from the "
                                         "gear, not cut)")
            except InputRangeError as err:
                why[member, side] = str(err)
    return got, why


def _mirrored(fillet: RootFillet) -> RootFillet:
    return dataclasses.replace(fillet, mirrored=not fillet.mirrored)
