"""Local synthesis of the pinion machine settings at the mean point.

Litvin's local synthesis of face-milled hypoid gears (Litvin & Fuentes 2004, sec. 21.5
to 21.8; Argyris, Fuentes & Litvin 2002) keeps the pinion and gear in tangency at the
mean point M (same point, same normal, the nominal ratio there) and chooses the
pinion's second-order surface at M, three numbers (two principal curvatures and their
direction), so that three conditions hold at M: the direction of the contact path on
the gear flank, the length of the instantaneous contact ellipse and the level of the
parabolic transmission error. Here the three second-order unknowns are three pinion
corrections, each of which keeps M (a pinion node) and its normal exactly:

* ``roll_curvature``: the second derivative of the work roll at the cradle roll
  ``psi_m`` that generates M, as ``-phi''(psi_m) / R_a0`` (the 2C of a roll
  about ``psi_m``). Written as cradle angle, ratio of roll and 2C whose roll keeps its
  value and slope at ``psi_m`` (the envelope at the mean node depends on ``phi`` and
  ``phi'`` there only: the equation of meshing; :func:`roll_about`);
* ``blade_curvature_per_mm``: a circular pinion blade tangent to the straight one at the
  blade point that generates M
  (:func:`~gearcontact.geometry.basic_settings.crown_profile`);
* ``radius_delta_mm``: the pinion cutter radius changed with the cutter centre moved
  along the blade's radial line through that point
  (:func:`~gearcontact.geometry.basic_settings.mismatch_radius`).

The conditions are measured at M by a local TCA (:func:`mean_point_contact`: five
phases about M, the TE curvature there and its parabolic level over one pitch, the paint
ellipse and the path direction at M) and met by least squares on the corrections from
the standard settings' crowning (``scipy.optimize.least_squares``, a solver in the loop,
not Litvin's closed-form second-order relations). The targets are those of the ease-off
synthesis (:class:`~.synthesis.SynthesisTargets`): TE0 level, paint-ellipse length and,
if given, the path angle (all three corrections); without a path angle the blade
curvature stays the standard crowning's and the roll curvature and the cutter radius
meet the other two. The bearing centre is not a target: the corrected pinion keeps M,
its normal and so the nominal ratio there (the TE slope at M is 0), so the TE0 vertex
stays at M. The result is checked by the full TCA over one pitch (edge contact, pairs
-2..2): TE0 peak-to-peak, the vertex's distance from M and the phases whose paint
ellipse reaches a flank edge (:class:`SettingSynthesis`). With a path angle the reach
model (:mod:`.setting_reach`) predicts the target's corrections first: a target out of
reach for certain is refused before the search, and the search starts from the
predicted corrections where they miss less than the standard crowning. The base pinion and M
(:class:`SynthesisProblem`): the pinion conjugate to the pair's gear
(:func:`~gearcontact.geometry.basic_settings.member_setups`). For a hypoid whose gear is
generated it is the crown gear's pinion, point contact with TE0 = 0 along a path, and M
the point of that path on the pinion's mean section. For a formate gear (hypoid or
spiral bevel: the complementary pinion) and a generated spiral bevel gear (the crown
gear's pinion) it is line-contact conjugate: every flank point lies on a contact line,
and M is the blank's mean point on the pinion (the point the standard crowning keeps).

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 20-21.
J. Argyris, A. Fuentes, F. L. Litvin, "Computerized integrated approach for design and
stress analysis of spiral bevel gears", *Comput. Methods Appl. Mech. Engrg.* 191 (2002)
1057-1095.
F. L. Litvin et al., *Local synthesis and tooth contact analysis of face-milled spiral
bevel gears*, NASA CR-4342, 1991.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from ..errors import CheckFailed
from ..geometry.basic_settings import (crown_profile, crowning_corrections, member_setups,
                                       mismatch_radius)
from ..geometry.flank import build_machine_flanks
from ..geometry.formate import SIDES
from ..geometry.gear_generation import gear_generation as default_gear_generation
from ..geometry.generated import EnvelopeSolver, generated_pinion_flank
from ..geometry.machine import MachineSetup, mirror_setup
from ..validation import InputRangeError
from .design_point import DesignPoint, design_point_at
from .setting_reach import ReachPrediction, chord_step, reach_model, target_misses
from .analysis import pattern_on_flank
from .edges import pattern_edges
from .mesh import mesh_cycle
from .mating import solve_mating_point
from .solve import solve_tca
from .synthesis_targets import SynthesisTargets, TargetRows, targets_rows
from .types import ContactGuess, EdgeContact

__all__ = ["PARAMETER_NAMES", "MeanPointContact", "SettingSynthesis", "SynthesisProblem",
           "mean_point_contact", "roll_about", "corrected_setup",
           "synthesize_settings", "synthesized_machine_pair"]

#: The three corrections (module docstring), in the order of :attr:`SettingSynthesis.x`.
PARAMETER_NAMES = ("roll_curvature", "blade_curvature_per_mm", "radius_delta_mm")
#: Least-squares scale steps of the corrections (1, 1/mm, mm): about a tenth of the
#: standard crowning's values on F.3-sized pairs.
_SCALE = np.array([1e-3, 2e-4, 0.2])
_REPORT_TORQUE_NM = 64.5
#: Chord steps of the reach model (:func:`~.setting_reach.chord_step`, one local TCA
#: each) before the search: measured on the 13/26 hypoid, four take the residual at
#: the model's corrections from 106-337 to 0.3-4.7 (tolerance units).
CHORD_STEPS = 4


def roll_about(settings, *, psi_m: float, roll_curvature: float):
    """``settings`` with cradle angle, ratio of roll and 2C such that the work roll as a
    function of the cradle's position keeps its value and slope at the roll ``psi_m`` of
    ``settings`` and gets the second derivative ``-R_a0 roll_curvature`` there (``R_a0``:
    the linear roll of ``settings``, which must have no modified roll).

    The cradle angle changed by ``d`` with the swivel kept is the cradle rolled by ``d``
    (the cutter turns rigidly about the cradle axis), so the new roll, in the base's
    cradle position ``psi``, is ``W(psi) = R_a (s - C s^2/2)``, ``s = psi - d``. The three
    conditions at ``psi_m`` give ``R_a C = R_a0 c``, ``R_a = R_a0 (1 + c s_m)`` and
    ``s_m + c s_m^2/2 = psi_m`` (``c = roll_curvature``, ``s_m = psi_m - d``): closed form,
    ``d = O(c psi_m^2)``. A 2C about ``psi = 0`` alone would move the mean node (its roll
    ``psi_m`` is not 0); a cubic about 0 keeping it needs a 6D of order ``3 c / psi_m``."""
    if any(settings.modified_roll) or any(settings.helical_motion):
        raise InputRangeError("modified_roll", settings.modified_roll,
                              "a linear roll (no modified roll, no helical motion) as base")
    r0, p, c = settings.ratio_of_roll, float(psi_m), float(roll_curvature)
    if 1.0 + 2.0 * c * p <= 0.0:
        raise InputRangeError("roll_curvature", c, f"1 + 2 c psi_m > 0 (psi_m = {p:.6g} rad)")
    s_m = 2.0 * p / (1.0 + math.sqrt(1.0 + 2.0 * c * p))     # root of s + c s^2/2 = psi_m
    r_a = r0 * (1.0 + c * s_m)
    q = settings.cradle_angle_deg + math.degrees(p - s_m)
    q = (q + 180.0) % 360.0 - 180.0 if (q + 180.0) % 360.0 != 0.0 else 180.0
    return dataclasses.replace(settings, cradle_angle_deg=q, ratio_of_roll=float(r_a),
                               modified_roll=(float(r0 * c / r_a),) if c else ())


def _generation_at(setup: MachineSetup, blank, cone, uv) -> tuple[float, float, float]:
    """(l, theta, psi) of the blade point and roll that generate the pinion node ``uv``."""
    solver = EnvelopeSolver(setup, blank, cone)
    m = solver.solve(uv[0], uv[1], solver.initial_guess(*uv))
    return float(m.l_mm), float(m.theta_rad), float(m.psi_rad)


def corrected_setup(base: MachineSetup, x, *, mean) -> MachineSetup:
    """The pinion ``base`` (straight blade, linear roll) with the corrections ``x``
    (:data:`PARAMETER_NAMES`), all pivoting on the generation ``mean = (l, theta, psi)``
    of the mean point (:class:`SynthesisProblem`)."""
    l_m, th_m, psi_m = mean
    c_roll, k_blade, delta = (float(v) for v in x)
    setup = mismatch_radius(base, delta_mm=delta, theta_rad=th_m) if delta else base
    if k_blade:
        setup = dataclasses.replace(setup, blade=crown_profile(
            setup.blade, radius_mm=1.0 / k_blade, at_length_mm=l_m))
    return dataclasses.replace(setup, settings=roll_about(setup.settings, psi_m=psi_m,
                                                          roll_curvature=c_roll))


#: Phase step of the local TCA at M, in pinion pitches (five phases, -2..2 steps: the TE
#: curvature by the five-point difference, the path tangent by the central one).
_LOCAL_STEP_PITCH = 1.0 / 30.0
_ARCSEC = math.pi / (180.0 * 3600.0)


@dataclass(frozen=True)
class MeanPointContact:
    """Litvin's quantities at the mean point M (:func:`mean_point_contact`).

    Attributes
    ----------
    point : DesignPoint
        At M: paint and Hertz ellipses and the path angle on the gear flank; its
        ``te0_pp_arcsec`` is the parabolic level ``te_level_arcsec``.
    te_curvature_arcsec_per_rad2 : float
        ``d^2 TE0 / d phi1^2`` at M (TE0 in arcsec of gear rotation, phi1 in rad).
    te_slope_arcsec_per_rad : float
        ``d TE0 / d phi1`` at M (0 for tangency with the nominal ratio at M).
    te_level_arcsec : float
        Peak-to-peak over one pinion pitch of the parabola of that curvature,
        ``|TE''| (pi / z1)^2 / 2`` (pairs changing at half a pitch either side of M).
    """

    point: DesignPoint
    te_curvature_arcsec_per_rad2: float
    te_slope_arcsec_per_rad: float
    te_level_arcsec: float


def mean_point_contact(pinion, gear, pair, start: ContactGuess, *,
                       torque_nm: float = _REPORT_TORQUE_NM) -> MeanPointContact:
    """Contact of ``pinion`` and ``gear`` at the mean point: a local TCA over five phases
    (``start``, the exact contact at M, and two steps of :data:`_LOCAL_STEP_PITCH` either
    side), from which the TE curvature, the parabolic TE level and the path direction at M
    follow (Litvin & Fuentes 2004, sec. 21.8: the second-order conditions of local
    synthesis are posed at M, not at the TE vertex of a whole pitch)."""
    kin = pair.kinematics()
    h = 2.0 * math.pi / pair.pinion_teeth * _LOCAL_STEP_PITCH
    path = solve_tca(pinion, gear, kin, start.phi1_rad + h * np.arange(-2, 3), start=start,
                     start_fixed="phi1", edges=False)
    te = np.asarray(path.te0_arcsec, dtype=float)
    if not np.all(np.isfinite(te)):
        raise ArithmeticError("the contact leaves a flank within two local steps of M")
    curv = float((-te[0] + 16.0 * te[1] - 30.0 * te[2] + 16.0 * te[3] - te[4]) / (12.0 * h * h))
    slope = float((te[0] - 8.0 * te[1] + 8.0 * te[3] - te[4]) / (12.0 * h))
    level = 0.5 * abs(curv) * (math.pi / pair.pinion_teeth) ** 2
    a, mp, b = path.points[1], path.points[2], path.points[3]
    tangent = kin.gear_pose(mp.phi2_rad)[0] @ (gear.point(b.u2, b.v2).r
                                               - gear.point(a.u2, a.v2).r)
    dp = design_point_at(pair, pinion, gear, mp, te0_pp_arcsec=level, torque_nm=torque_nm,
                         path_tangent=tangent)
    return MeanPointContact(dp, curv, slope, level)


@dataclass(frozen=True)
class SettingSynthesis(TargetRows):
    """Result of :func:`synthesize_settings` for one side.

    Attributes
    ----------
    side : str
    setup : MachineSetup
        The synthesized pinion settings of ``side``.
    x : ndarray (3,)
        The corrections (:data:`PARAMETER_NAMES`).
    point : DesignPoint
        At the mean point M (:func:`mean_point_contact`; ``te0_pp_arcsec`` is the
        parabolic level of the TE curvature at M).
    rows : tuple of (str, str, float, float, float, bool)
        (quantity, unit, target, achieved, tolerance, met) at M.
    tca_te0_pp_arcsec : float
        TE0 peak-to-peak of the full TCA over one pitch (edge contact, pairs -2..2).
    edges : tuple of str
        Per phase of that pitch (centred on its TE0 vertex): the flank edge the paint
        ellipse reaches, ``""`` inside (:func:`~.edges.pattern_edges`).
    vertex_offset_mm : float
        Distance of the full TCA's TE0 vertex from M on the pinion flank (u, v), mm.
    evaluations : int
        Local TCA runs of the search (the reach model's included).
    seconds : float
    reach : ReachPrediction or None
        With a path-angle target: the corrections the reach model predicted before the
        search (:mod:`.setting_reach`), the synthesis' start where they did better than the
        standard crowning.
    reach_residual : float
        The synthesis' normalized residual (root sum of squares of each target's miss
        over its tolerance) measured at the reach model's corrections (nan without).
    start_residual : float
        The same where the search started: the better of the standard crowning and the
        model's corrections after its chord steps (nan without a reach model).
    residual : float
        The same at the result (the achieved one).
    """

    side: str
    setup: MachineSetup
    x: np.ndarray
    point: DesignPoint
    rows: tuple
    tca_te0_pp_arcsec: float
    edges: tuple
    vertex_offset_mm: float
    evaluations: int
    seconds: float
    reach: ReachPrediction | None = None
    reach_residual: float = float("nan")
    start_residual: float = float("nan")
    residual: float = float("nan")

    def reach_text(self) -> str:
        """The reach model's prediction beside the achieved residual ("" without one)."""
        if self.reach is None:
            return ""
        return (f"{self.reach.text()}; at its corrections {self.reach_residual:.2f}, "
                f"search started at {self.start_residual:.2f}, achieved {self.residual:.2f}")

    @property
    def table_prefix(self) -> str:
        """The side, before each quantity of :meth:`table`."""
        return f"{self.side} "


def _path_point_at(pinion, gear, pair, guess: ContactGuess, *, v1_mm: float):
    """The mating point of the path through ``guess`` whose pinion ``v1`` is ``v1_mm``
    within 1e-6 mm: secant on the phase, started from a local TCA over +-2 steps of
    :data:`_LOCAL_STEP_PITCH` (the system with ``v1`` held is singular where TE0 is
    constant along the path, as on the crown gear's pinion)."""
    kin = pair.kinematics()
    h = 2.0 * math.pi / pair.pinion_teeth * _LOCAL_STEP_PITCH
    path = solve_tca(pinion, gear, kin, guess.phi1_rad + h * np.arange(-2, 3), start=guess,
                     start_fixed="phi1", edges=False)
    k = int(np.argmin([abs(p.v1 - v1_mm) for p in path.points]))
    prev, mp = path.points[k - 1 if k else 1], path.points[k]
    for _ in range(20):
        if abs(mp.v1 - v1_mm) < 1e-6:
            return mp
        slope = (mp.v1 - prev.v1) / (mp.phi1_rad - prev.phi1_rad)
        prev, mp = mp, solve_mating_point(pinion, gear, kin, dataclasses.replace(
            mp.as_guess(), phi1_rad=mp.phi1_rad - (mp.v1 - v1_mm) / slope))
    raise ArithmeticError(f"no point of the contact path at v1 = {v1_mm:.4f} mm (secant "
                          f"stopped at {mp.v1:.4f} mm)")


class SynthesisProblem:
    """The fixed part of the synthesis of one pair: the gear flanks, the base pinion
    (:func:`~gearcontact.geometry.basic_settings.member_setups` of ``gear_generation``:
    the complementary pinion of a formate gear, the crown gear's pinion of a generated
    one), the mean point M of each side, its generation and its exact contact, and the
    pinion's mounting turn, so that :meth:`flank` gives the mounted pinion flank of any
    corrections.

    Point contact (:attr:`point_contact`: a hypoid, offset != 0, whose gear is
    generated): M is the point of the base pinion's contact path on the pinion's mean
    section (``v`` of the blank's mean point, :func:`_path_point_at`): the crown gear's
    pinion of a hypoid has point contact with TE0 = 0 along a path, which passes near,
    not through, the pinion's mean node (13/26 hypoid: 0.68 / 2.30 mm above it, drive /
    coast). Line contact (a formate gear, or a generated gear with offset 0): the base
    pinion touches the gear along a line through every flank point, so M is the
    blank's mean point on the pinion, the node ``(root offset, pitch point x)`` that
    :func:`~gearcontact.geometry.flank.build_machine_flanks` starts the TCA from and
    whose generation the standard crowning keeps in place; its exact contact is that
    flank set's mean contact. The corrections pivot on the generation of M, so the
    corrected pinion keeps M, its normal and the nominal ratio there: tangency at M.

    The mounting turn is the one :func:`~gearcontact.geometry.flank.build_machine_flanks`
    gives the base pinion (the corrections keep M, so the same turn mounts every
    corrected pinion).
    """

    def __init__(self, pair, *, gear_generation: str = "generated", n_u: int = 40,
                 n_v: int = 50):
        if pair.pinion_hand != "right":
            raise InputRangeError("pinion_hand", pair.pinion_hand, "'right' (synthesize the "
                                  "right-hand twin and mirror its settings)")
        #: the base pinion has point contact (the crown gear's pinion of a hypoid), not
        #: line contact (module docstring)
        self.point_contact = gear_generation == "generated" and pair.offset_mm != 0.0
        self.pair, self.n_u, self.n_v = pair, int(n_u), int(n_v)
        blank = pair.blank
        self.gear_setups, self.base = member_setups(pair, gear_generation)
        fs = build_machine_flanks(dataclasses.replace(
            pair, machine=tuple(self.gear_setups[s] for s in SIDES)
            + tuple(self.base[s] for s in SIDES), easeoff_tables=("drive", "coast")),
            n_u=n_u, n_v=n_v)
        d = pair.design_side
        self.turn = 0.0
        self.turn = float(fs.pinion.side(d).psi_nodes[0, 0]
                          - self._generated(self.base[d]).psi_nodes[0, 0])
        self.gear = {side: fs.gear.side(side) for side in SIDES}
        #: the pinion sheet's cone (both sides), mm
        self.cone = fs.pinion.side(d).cone
        self.start, self.mean_uv, self.means = {}, {}, {}
        for side in SIDES:
            m = fs.mean_contact[side]
            guess = ContactGuess(*m["pinion_uv"], *m["gear_uv"], pair.ratio * m["phi2_rad"],
                                 m["phi2_rad"])
            if self.point_contact:
                mp = _path_point_at(fs.pinion.side(side), self.gear[side], pair, guess,
                                    v1_mm=float(blank.pitch_point_mm[0]))
                self.start[side] = mp.as_guess()
                self.mean_uv[side] = (float(mp.u1), float(mp.v1))
            else:       # line contact: the pinion's mean node lies on a contact line
                self.start[side] = guess
                self.mean_uv[side] = tuple(float(t) for t in m["pinion_uv"])
            self.means[side] = _generation_at(self.base[side], blank, self.cone,
                                              self.mean_uv[side])
        # the standard crowning (25 / 10 um, standard_setups): the search's start
        self.standard = {side: np.array([0.0, *crowning_corrections(
            pair, self.base[side], l_mm=self.means[side][0], lengthwise_crowning_um=25.0,
            blade_profile_crowning_um=10.0)])[[0, 2, 1]] for side in SIDES}

    def setup(self, side: str, x) -> MachineSetup:
        """The pinion settings of ``side`` with the corrections ``x``."""
        return corrected_setup(self.base[side], x, mean=self.means[side])

    def _generated(self, setup):
        f = generated_pinion_flank(setup, self.pair.blank,
                                   pinion_face_width_mm=self.pair.pinion_face_width_mm,
                                   n_u=self.n_u, n_v=self.n_v)[0]
        return dataclasses.replace(f, psi_nodes=f.psi_nodes + self.turn)

    def flank(self, side: str, x):
        """The mounted pinion flank of ``side`` with the corrections ``x``."""
        return self._generated(self.setup(side, x))

    def contact(self, side: str, x) -> MeanPointContact:
        """:func:`mean_point_contact` of the corrections ``x``."""
        return mean_point_contact(self.flank(side, x), self.gear[side], self.pair,
                                  self.start[side])


def synthesize_settings(pair, *, targets: SynthesisTargets | dict = SynthesisTargets(),
                        sides=SIDES, phases: int = 31, max_evaluations: int = 40,
                        problem: SynthesisProblem | None = None) -> dict:
    """Pinion settings of ``sides`` from local synthesis at the mean point (module
    docstring), against the pair's gear (:class:`SynthesisProblem`: a hypoid's generated
    gear, point contact; a formate gear or a spiral bevel's generated one, line
    contact).

    Parameters
    ----------
    pair : GearPair
        A right-hand pair (a left-hand pair is refused: mirror its twin's settings).
    targets : SynthesisTargets or dict
        TE0 level, paint-ellipse length and optional path angle (the bearing centre is
        the mean point; ``centre_*`` only place the first-order path angle), for every
        side or per side (``{side: SynthesisTargets}``: the sides reach different path
        angles).
    phases : int
        Phases per pitch of the full TCA that checks the result.
    max_evaluations : int
        Budget of local TCA runs of the least squares per side.
    problem : SynthesisProblem, optional
        Built for ``pair`` (40 x 50 nodes) if not given.

    Returns
    -------
    dict
        ``{side: SettingSynthesis}``.

    Raises
    ------
    InputRangeError
        A left-hand pair or a bad side, before any flank; a path angle the reach model finds out of reach for
        certain (:mod:`.setting_reach`: a hard limit of the settings crossed within half
        the predicted step), after its seven local TCAs, before the search.
    CheckFailed
        No contact at M at the starting settings.
    """
    for side in sides:
        if side not in SIDES:
            raise InputRangeError("side", side, f"one of {SIDES}")
    per_side = targets if isinstance(targets, dict) else dict.fromkeys(sides, targets)
    missing = [side for side in sides if side not in per_side]
    if missing:
        raise InputRangeError("targets", sorted(per_side), f"targets of the sides {sides}")
    prob = problem or SynthesisProblem(pair)
    out = {}
    for side in sides:
        t0 = time.perf_counter()
        targets = per_side[side]
        length = targets.pattern_length_ratio * pair.gear_face_width_mm
        angle = targets.path_angle_deg
        # without a path angle the blade curvature stays the standard crowning's and the
        # roll curvature and the cutter radius meet the TE level and the ellipse length
        active = [0, 1, 2] if angle is not None else [0, 2]
        x_start = prob.standard[side]
        try:
            first = prob.contact(side, x_start)
        except (EdgeContact, ArithmeticError, ValueError) as exc:
            raise CheckFailed(f"setting synthesis of {pair.name} {side}: no contact at the "
                              f"mean point with the standard crowning ({exc})") from exc
        # the parabola of a localized bearing: the sign of the standard crowning's
        sign = math.copysign(1.0, first.te_curvature_arcsec_per_rad2)
        runs = {"n": 0, "best": (np.inf, x_start)}

        def misses(x):
            """The normalized residual of the targets at the corrections ``x``."""
            runs["n"] += 1
            runs["last"] = None
            try:
                m = prob.contact(side, x)
            except (EdgeContact, ArithmeticError, ValueError):
                return np.full(len(active), 1e3)
            level = sign * math.copysign(m.te_level_arcsec, m.te_curvature_arcsec_per_rad2)
            runs["last"] = (level, m.point.paint_length_mm, m.point.path_angle_deg)
            r = target_misses(targets, length, level, m.point.paint_length_mm,
                              None if angle is None else m.point.path_angle_deg)
            if r @ r < runs["best"][0]:
                runs["best"] = (float(r @ r), x.copy())
            return r

        reach, at_reach, at_first = None, math.nan, math.nan
        if angle is not None:
            model, reach = _reach_of(prob, side, targets, length, pair.name)
            runs["n"] += 7
            at_start = float(np.linalg.norm(misses(x_start)))
            at_reach = float(np.linalg.norm(misses(reach.x)))
            # the search starts from the better of the standard crowning and the model's
            # corrections after up to CHORD_STEPS chord steps (the path angle is far from
            # linear in the corrections: from the standard crowning the least squares
            # can leave the target's basin); the chord stops where it stops gaining
            x, miss = reach.x, at_reach
            for _ in range(CHORD_STEPS):
                if runs["last"] is None or miss <= 1.0:
                    break
                x_next = chord_step(model, reach, x, runs["last"], targets=targets,
                                    length_mm=length)
                miss_next = float(np.linalg.norm(misses(x_next)))
                if not miss_next < miss:
                    break
                x, miss = x_next, miss_next
            if miss < at_start:
                x_start = x
            at_first = min(miss, at_start)

        def residual(z):
            x = x_start.copy()
            x[active] += z * _SCALE[active]
            return misses(x)

        # the Jacobian of a line-contact base pinion by forward steps of _JAC_STEP scale
        # steps (scipy's relative diff_step is sqrt(eps) at z = 0: 1e-8 scale steps, in
        # the local TCA's noise there); the point-contact path as before
        fun, jac = (residual, "2-point") if prob.point_contact else _forward_jacobian(residual)
        least_squares(fun, np.zeros(len(active)), jac=jac, method="trf", diff_step=1e-3,
                      max_nfev=int(max_evaluations))
        out[side] = dataclasses.replace(
            _checked(prob, side, runs["best"][1], targets, length, phases, runs["n"], t0),
            reach=reach, reach_residual=at_reach, start_residual=at_first,
            residual=math.sqrt(runs["best"][0]))
    return out


#: Forward-difference step of the line-contact search's Jacobian, in scale steps
#: (:data:`_SCALE`): the TE level moves ~1e-3 arcsec per such step on F.2, its noise
#: (node solves, interpolation) is ~1e-8 arcsec.
_JAC_STEP = 1e-3


def _forward_jacobian(fun, *, step: float = _JAC_STEP):
    """``(fun, jac)`` for ``least_squares``: ``fun`` remembering its last value, ``jac``
    the forward differences of absolute ``step`` from it (one call of ``fun`` per
    column)."""
    last = {}

    def value(z):
        last["z"], last["r"] = np.array(z, dtype=float), fun(z)
        return last["r"]

    def jac(z):
        r0 = last["r"] if "z" in last and np.array_equal(last["z"], z) else value(z)
        cols = []
        for i in range(len(z)):
            zi = np.array(z, dtype=float)
            zi[i] += step
            cols.append((fun(zi) - r0) / step)
        return np.column_stack(cols)

    return value, jac


def _reach_of(prob: SynthesisProblem, side: str, targets, length: float, name: str):
    """The reach model of ``side`` and its prediction of ``targets``
    (:mod:`.setting_reach`), refused where it is certain that the settings cannot reach
    it."""
    try:
        model = reach_model(prob, side, scales=_SCALE)
    except (EdgeContact, ArithmeticError, ValueError) as exc:
        raise CheckFailed(f"setting synthesis of {name} {side}: no contact at the mean "
                          f"point within the reach model's steps ({exc})") from exc
    reach = model.predict(targets, length_mm=length)
    if reach.certain:
        raise InputRangeError(
            "path_angle_deg", targets.path_angle_deg,
            f"a path angle the {side} settings can reach: at {targets.path_angle_deg:g} deg "
            f"(the contact line at {model.line_angle_deg:.1f} deg) the reach model "
            f"(docs/machine_settings.md sec. 5) needs roll curvature {reach.x[0]:+.3g}, "
            f"blade curvature {reach.x[1]:+.3g} /mm, cutter radius {reach.x[2]:+.3g} mm "
            f"before the limit, {reach.limit}; predicted residual {reach.residual:.1f} "
            f"(1 = the tolerances)")
    return model, reach


def _checked(prob: SynthesisProblem, side, x, targets, length, phases, runs, t0):
    """:class:`SettingSynthesis` of the corrections ``x``: the local contact at M and
    the full TCA over one pitch (edge contact, pairs -2..2) with its pattern edges."""
    pair = prob.pair
    flank, gear, start = prob.flank(side, x), prob.gear[side], prob.start[side]
    local = mean_point_contact(flank, gear, pair, start)
    kin = pair.kinematics()
    cyc = mesh_cycle(flank, gear, kin, pinion_teeth=pair.pinion_teeth, start=start,
                     start_fixed="phi1", phases=phases, pairs=2)
    edges = pattern_edges(flank, gear, kin, cyc, pattern_on_flank(flank, gear, kin, cyc))
    u_m, v_m = prob.mean_uv[side]
    vertex = cyc.contact[len(cyc.contact) // 2]
    return SettingSynthesis(side, prob.setup(side, x), x, local.point,
                            targets_rows(local.point, targets, None, length),
                            float(cyc.te0_pp_arcsec), tuple(edges),
                            float(np.hypot(vertex.u1 - u_m, vertex.v1 - v_m)), runs,
                            time.perf_counter() - t0)


def synthesized_machine_pair(pair, *, targets: SynthesisTargets | dict = SynthesisTargets(),
                             gear_generation: str | None = None, **options):
    """``pair`` with its gear's settings and the pinion settings of
    :func:`synthesize_settings` (``targets``: for both sides or per side) for both
    sides, and the per-side results. ``gear_generation``: ``"formate"`` or
    ``"generated"`` (:class:`SynthesisProblem`), by default the gear of the pair's
    default flanks (:func:`~gearcontact.geometry.gear_generation.gear_generation`, as
    ``design --machine-settings`` writes it). A left-hand pair is the mirror image of its
    right-hand twin (:mod:`~gearcontact.geometry.mirror`): the twin is synthesized and
    its settings mirrored (:func:`~gearcontact.geometry.machine.mirror_setup`; signs:
    docs/machine_settings.md), so the left-hand pair's TCA is the twin's mirrored (same
    TE0, the pattern reflected) and the per-side results are the twin's (the path angle
    is measured so that it means the same bearing for both hands)."""
    if pair.pinion_hand == "left":
        twin, done = synthesized_machine_pair(
            dataclasses.replace(pair, pinion_hand="right", machine=()), targets=targets,
            gear_generation=gear_generation, **options)
        return dataclasses.replace(pair, machine=tuple(mirror_setup(s) for s in twin.machine),
                                   easeoff_tables=twin.easeoff_tables), done
    if gear_generation is None:
        gear_generation = default_gear_generation(pair)[0]
    prob = SynthesisProblem(pair, gear_generation=gear_generation,
                            n_u=options.pop("n_u", 40), n_v=options.pop("n_v", 50))
    done = synthesize_settings(pair, targets=targets, problem=prob, **options)
    machine = tuple(prob.gear_setups[s] for s in SIDES) + tuple(done[s].setup for s in SIDES)
    return dataclasses.replace(pair, machine=machine, easeoff_tables=("drive", "coast")), done
