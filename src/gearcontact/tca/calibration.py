"""Calibration of a pair's unpublished set-up against a published design point.

A published study usually gives the pitch-cone data and a handful of results of its
design mesh phase (mating point, TE0, contact ellipse) but not the tooth proportions
and ease-off that produced them. This module closes that gap by TCA in the loop
(docs/calibration.md):

1. **Design flank.** The published mating point P0 must lie on the surface of action
   of one flank pair; :func:`surface_of_action_offset` measures, for each side, the
   invariant distance of P0 from the contact of the *conjugate* flanks (no ease-off):
   the side with the smaller offset is the design side.
2. **Tip.** P0 must lie on the pinion flank: :func:`working_depth_for_tip` chooses the
   working-depth factor ``k_d`` so that the pinion tip cone passes ``tip_margin_mm``
   above P0 at P0's axial position (the published bearing is a tip-edge bearing: the
   loaded ellipse reaches over the tip at every torque).
3. **Ease-off.** The five ease-off coefficients of the design side are solved by
   bounded least squares (``scipy.optimize.least_squares``) against the targets in
   their order of priority - the four frame-invariant coordinates of P0 (radius and
   axial position on both members), TE0 peak-to-peak, the Hertz ellipse 2a x 2b at the
   design torque, its angle from the lengthwise direction - with weights that encode
   that order (:class:`CalibrationTargets`).

The objective is evaluated at the design point of each ease-off, the TCA at the
continuous TE0 vertex, compared in frame-invariant coordinates
(:mod:`.design_point`).

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 9
(TCA), sec. 21.8 (local synthesis: bearing position, path, TE level prescribed at the
mean point).
"""

from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import least_squares, minimize_scalar

from ..errors import CheckFailed
from ..geometry.easeoff import mean_normal_thickness_mm
from ..geometry.flank import build_flanks
from ..geometry.formate import SIDES
from ..geometry.pair import EaseOffCoefficients, GearPair
from ..validation import InputRangeError, check_positive
from .design_point import (DesignPoint, centred_coefficients, conjugate_contact,
                           eased_design_point, point_invariants)
from .types import EdgeContact

__all__ = ["calibration_toml", "CalibrationTargets", "CalibrationRow", "Calibration",
           "calibrate_pair", "surface_of_action_offset", "working_depth_for_tip",
           "PRIORITY_WEIGHTS", "design_point_rows", "face_widths_for_room", "top_land_mm",
           "tip_margin_for_top_land", "MIN_TOP_LAND_MODULES"]

_INVARIANTS = ("gear radius", "gear axial", "pinion radius", "pinion axial")


@dataclass(frozen=True)
class CalibrationTargets:
    """Published design-point results and the tolerance each is met to.

    Parameters
    ----------
    mean_point_mm : (3,) float
        Published TCA mating point P0 in the meshing frame, mm.
    te0_pp_arcsec : float
        Unloaded TE peak-to-peak over one pinion pitch, arcsec.
    ellipse_length_mm, ellipse_width_mm : float
        Hertz contact ellipse 2a x 2b at ``torque_nm``, mm.
    ellipse_angle_deg : float
        Angle of the major axis from the lengthwise direction, deg.
    torque_nm : float
        Design gear torque, N·m.
    tol_point_mm, tol_te0_rel, tol_length_rel, tol_width_rel, tol_angle_deg : float
        Tolerances: invariant coordinates of P0 (mm), TE0 (relative), 2a and 2b
        (relative), angle (deg). Divided by :data:`PRIORITY_WEIGHTS` they are the
        least-squares scales, so a target weighs by how tightly it is asked for and by
        its priority.
    """

    mean_point_mm: tuple[float, float, float]
    te0_pp_arcsec: float
    ellipse_length_mm: float
    ellipse_width_mm: float
    ellipse_angle_deg: float
    torque_nm: float
    tol_point_mm: float = 0.1
    tol_te0_rel: float = 0.10
    tol_length_rel: float = 0.10
    tol_width_rel: float = 0.10
    tol_angle_deg: float = 3.0

    def __post_init__(self):
        check_positive("te0_pp_arcsec", self.te0_pp_arcsec)
        check_positive("ellipse_length_mm", self.ellipse_length_mm)
        check_positive("ellipse_width_mm", self.ellipse_width_mm)
        check_positive("torque_nm (N·m)", self.torque_nm)
        for name in ("tol_point_mm", "tol_te0_rel", "tol_length_rel", "tol_width_rel",
                     "tol_angle_deg"):
            check_positive(name, getattr(self, name))

    @classmethod
    def from_published(cls, published: dict) -> "CalibrationTargets":
        """Targets from a ``data/published/<pair>.json`` document."""
        try:
            return cls(mean_point_mm=tuple(float(c) for c in published["design_point_mm"]),
                       te0_pp_arcsec=float(published["te0_pp_arcsec"]),
                       ellipse_length_mm=float(published["preview_ellipse_2a_mm"]),
                       ellipse_width_mm=float(published["preview_ellipse_2b_mm"]),
                       ellipse_angle_deg=float(published["preview_ellipse_angle_deg"]),
                       torque_nm=float(published["design_torque_nm"]))
        except KeyError as exc:
            raise InputRangeError("published values", str(exc),
                                  "a document with design_point_mm, te0_pp_arcsec, "
                                  "preview_ellipse_2a_mm/2b_mm/angle_deg, design_torque_nm"
                                  ) from None


@dataclass(frozen=True)
class CalibrationRow:
    """One line of the target / achieved / tolerance table (units in ``unit``)."""

    target: str
    unit: str
    published: float
    achieved: float
    tolerance: float
    met: bool


@dataclass(frozen=True)
class Calibration:
    """Result of :func:`calibrate_pair`.

    Attributes
    ----------
    pair : GearPair
        The calibrated pair (``design_side`` set, working depth and ease-off solved).
    side : str
        Design side (the flank pair P0 lies on).
    soa_offset_mm : dict
        Per side: largest invariant offset of P0 from the conjugate contact, mm.
    tip_margin_mm : float
        Pinion tip radius above P0 at P0's axial position, mm.
    point : DesignPoint
        TCA at the calibrated set-up.
    rows : tuple of CalibrationRow
        Target / achieved / tolerance table in the order of priority.
    evaluations : int
        TCA runs of the search (every ease-off evaluated, finite-difference steps
        included).
    seconds : float
        Wall time, s.
    """

    pair: GearPair
    side: str
    soa_offset_mm: dict
    tip_margin_mm: float
    point: DesignPoint
    rows: tuple[CalibrationRow, ...]
    evaluations: int
    seconds: float
    notes: tuple[str, ...] = field(default=())

    def as_dict(self) -> dict:
        """Plain-JSON view: side, offsets, tip margin, coefficients and the table."""
        c = getattr(self.pair, f"easeoff_{self.side}")
        return {"side": self.side, "surface_of_action_offset_mm": self.soa_offset_mm,
                "tip_margin_mm": self.tip_margin_mm,
                "working_depth_factor": self.pair.working_depth_factor,
                f"pressure_angle_{self.side}_deg":
                    getattr(self.pair.cutter, f"pressure_angle_{self.side}_deg"),
                "easeoff": dataclasses.asdict(c), "easeoff_max_um": self.point.easeoff_max_um,
                "mating_point_mm": [float(x) for x in self.point.point_mm],
                "evaluations": self.evaluations,
                "rows": [dataclasses.asdict(r) for r in self.rows]}

    def table(self) -> str:
        """The target / achieved / tolerance table as Markdown."""
        lines = ["| target | published | achieved | tolerance | met |",
                 "|---|---:|---:|---:|---|"]
        for r in self.rows:
            lines.append(f"| {r.target} ({r.unit}) | {r.published:.4g} | {r.achieved:.4g} | "
                         f"{r.tolerance:.3g} | {'yes' if r.met else 'NO'} |")
        return "\n".join(lines)


def surface_of_action_offset(pair: GearPair, point_mm, *, side: str, flanks=None
                             ) -> tuple[float, np.ndarray]:
    """Invariant offset of ``point_mm`` from the conjugate contact of ``side``.

    The pinion point with the same radius and axial position as ``point_mm`` is put in
    conjugate contact with its generating gear flank (equation of meshing); the result
    is the largest difference of the four :func:`point_invariants`, mm, and the
    meshing-frame contact point. An ease-off moves the bearing over the surface of
    action, not off it, so an offset much larger than the tolerance rules the side out.
    """
    if flanks is None:
        flanks = build_flanks(dataclasses.replace(pair, easeoff_drive=EaseOffCoefficients(),
                                                  easeoff_coast=EaseOffCoefficients()))
    conj = flanks.pinion_conjugate.side(side)
    target = point_invariants(point_mm, pair.offset_mm)
    u_t = target[2] - conj.cone.radius_mm(0.0, target[3])
    u_m, v_m = flanks.mean_contact[side]["pinion_uv"]
    q = np.zeros(3)
    # continuation from the mean node: the node equations have several roots
    for t in np.linspace(0.0, 1.0, 21)[1:]:
        s = conj.solver.solve(np.array(u_m + t * (u_t - u_m)),
                              np.array(v_m + t * (target[3] - v_m)), q)
        q = np.array([float(s.h_mm), float(s.theta_rad), float(s.phi2_rad)])
    x = np.asarray(s.x_f_mm, dtype=float)
    return float(np.max(np.abs(point_invariants(x, pair.offset_mm) - target))), x


def working_depth_for_tip(pair: GearPair, point_mm, *, tip_margin_mm: float) -> float:
    """Working-depth factor ``k_d`` whose pinion tip passes ``tip_margin_mm`` above P0.

    With uniform depth (ISO 23509 clause 7) the pinion tip cone is
    ``R_a(x) = (x - x_A1) tan(delta1) + h_am1 / cos(delta1)`` and
    ``h_am1 = (1 - c_ham) k_d m_mn``; the pitch cone (and so ``x_A1``, ``delta1`` and
    ``m_mn``) does not depend on ``k_d``, so ``k_d`` follows in closed form.
    """
    b = pair.blank
    inv = point_invariants(point_mm, pair.offset_mm)
    d1 = np.radians(b.pitch_angle_pinion_deg)
    r_pitch = (inv[3] - b.pinion_apex_x_mm) * np.tan(d1)
    h_am1 = (inv[2] + tip_margin_mm - r_pitch) * np.cos(d1)
    return float(h_am1 / ((1.0 - pair.gear_addendum_factor) * b.mean_normal_module_mm))


#: Smallest pinion top land accepted by the default tip choice, in mean normal modules:
#: common practice for case-hardened bevel and hypoid gears keeps the top land at about
#: 0.25-0.3 m_mn so that the tip is not hardened through and does not chip.
MIN_TOP_LAND_MODULES = 0.25


def top_land_mm(flanks) -> float:
    """Smallest normal top-land thickness of the pinion tooth along the face, mm
    (drive and coast conjugate flanks at the tip, toe / middle / heel)."""
    d, c = flanks.pinion_conjugate.drive, flanks.pinion_conjugate.coast
    b = d.boundary
    u_tip = min(b.u_tip, c.boundary.u_tip)
    return min(mean_normal_thickness_mm(d, c, u_mm=u_tip, v_mm=v,
                                        spiral_angle_deg=flanks.blank.spiral_angle_pinion_deg)
               for v in (b.v_toe, 0.5 * (b.v_toe + b.v_heel), b.v_heel))


def tip_margin_for_top_land(pair: GearPair, point_mm, *, lo_mm: float = 0.01,
                            hi_mm: float = 0.5) -> float:
    """Largest tip margin (mm, to 0.01 mm, in [lo_mm, hi_mm]) whose pinion keeps a top
    land of :data:`MIN_TOP_LAND_MODULES` x m_mn (bisection; the top land shrinks as the
    working depth grows). ``lo_mm`` if even that margin thins the top land below it."""
    need = MIN_TOP_LAND_MODULES * pair.blank.mean_normal_module_mm

    def land(margin):
        k_d = working_depth_for_tip(pair, point_mm, tip_margin_mm=margin)
        return top_land_mm(build_flanks(dataclasses.replace(pair, working_depth_factor=k_d)))

    if land(hi_mm) >= need:
        return hi_mm
    if land(lo_mm) < need:
        return lo_mm
    a, b = lo_mm, hi_mm
    while b - a > 0.01:
        m = 0.5 * (a + b)
        a, b = (m, b) if land(m) >= need else (a, m)
    return float(np.floor(100.0 * a) / 100.0)


#: Least-squares weight of each target group, in the order of priority of the targets
#: (P0, TE0, 2a, 2b, angle): a miss of one tolerance on P0 costs 10x one on the ellipse.
PRIORITY_WEIGHTS = (10.0, 3.0, 1.0, 1.0, 1.0)


#: Start grid of the search (um/mm^2): profile and lengthwise crowning.
_GRID_PROFILE_CROWNING = (4.0, 8.0, 12.0, 16.0, 20.0)
_GRID_LENGTHWISE_CROWNING = (0.06, 0.1, 0.15)


def _residuals(dp: DesignPoint, targets: CalibrationTargets, offset_mm: float) -> np.ndarray:
    inv0 = point_invariants(targets.mean_point_mm, offset_mm)
    w = PRIORITY_WEIGHTS
    return np.concatenate([
        w[0] * (dp.invariants_mm - inv0) / targets.tol_point_mm,
        [w[1] * (dp.te0_pp_arcsec / targets.te0_pp_arcsec - 1.0) / targets.tol_te0_rel,
         w[2] * (dp.ellipse_length_mm / targets.ellipse_length_mm - 1.0) / targets.tol_length_rel,
         w[3] * (dp.ellipse_width_mm / targets.ellipse_width_mm - 1.0) / targets.tol_width_rel,
         w[4] * (dp.ellipse_angle_deg - targets.ellipse_angle_deg) / targets.tol_angle_deg]])


def design_point_rows(dp: DesignPoint, targets: CalibrationTargets, *, offset_mm: float
                      ) -> tuple[CalibrationRow, ...]:
    """Target / achieved / tolerance rows of a design point, in the order of priority
    (the calibration's table and the summary's)."""
    inv0 = point_invariants(targets.mean_point_mm, offset_mm)
    rows = [CalibrationRow(f"P0 {name}", "mm", float(p), float(a), targets.tol_point_mm,
                           bool(abs(a - p) <= targets.tol_point_mm))
            for name, p, a in zip(_INVARIANTS, inv0, dp.invariants_mm)]
    for name, unit, p, a, tol in (
            ("TE0 peak-to-peak", "arcsec", targets.te0_pp_arcsec, dp.te0_pp_arcsec,
             targets.tol_te0_rel * targets.te0_pp_arcsec),
            (f"Hertz 2a at {targets.torque_nm:g} N·m", "mm", targets.ellipse_length_mm,
             dp.ellipse_length_mm, targets.tol_length_rel * targets.ellipse_length_mm),
            (f"Hertz 2b at {targets.torque_nm:g} N·m", "mm", targets.ellipse_width_mm,
             dp.ellipse_width_mm, targets.tol_width_rel * targets.ellipse_width_mm),
            ("ellipse angle from lengthwise", "deg", targets.ellipse_angle_deg,
             dp.ellipse_angle_deg, targets.tol_angle_deg)):
        rows.append(CalibrationRow(name, unit, float(p), float(a), float(tol),
                                   bool(abs(a - p) <= tol)))
    return tuple(rows)


def face_widths_for_room(pair: GearPair, point_mm, *, heel_room_mm: float
                         ) -> tuple[float, float]:
    """Face widths (gear F2, pinion b1; mm, up to 0.1 mm) that end ``heel_room_mm`` or
    more beyond the point along both pitch cones (never narrower than the pair's).

    The faces stay centred on the mean cone distances (which are published); the
    position of the point along a pitch cone is its projection on the cone's generatrix
    in the axial plane, ``R = r sin(delta) + (a - a_apex) cos(delta)`` (r radius, a axial
    position, from the pitch apex).
    """
    b = pair.blank
    inv = point_invariants(point_mm, pair.offset_mm)
    d1, d2 = np.radians(b.pitch_angle_pinion_deg), np.radians(b.pitch_angle_gear_deg)
    r_gear = inv[0] * np.sin(d2) + (inv[1] - b.gear_apex_z_mm) * np.cos(d2)
    r_pinion = inv[2] * np.sin(d1) + (inv[3] - b.pinion_apex_x_mm) * np.cos(d1)
    f2 = 2.0 * (r_gear + heel_room_mm - b.mean_cone_distance_gear_mm)
    f1 = 2.0 * (r_pinion + heel_room_mm - b.mean_cone_distance_pinion_mm)
    f2 = max(pair.gear_face_width_mm, np.ceil(10.0 * f2) / 10.0)
    f1 = max(pair.pinion_face_width_mm, f2, np.ceil(10.0 * f1) / 10.0)
    return float(f2), float(f1)


def calibrate_pair(pair: GearPair, targets: CalibrationTargets, *,
                   tip_margin_mm: float | None = None,
                   heel_room_mm: float = 2.0, side: str | None = None,
                   max_evaluations: int = 120, progress: bool = False) -> Calibration:
    """Calibrate the working depth and the design-side ease-off of ``pair``.

    Parameters
    ----------
    pair : GearPair
        Starting pair; its pitch-cone inputs are kept exactly.
    targets : CalibrationTargets
    tip_margin_mm : float, optional
        Pinion tip radius above P0 at P0's axial position, mm, in [0.01, 0.5]. By
        default the largest margin whose pinion top land keeps
        :data:`MIN_TOP_LAND_MODULES` x m_mn everywhere along the face
        (:func:`tip_margin_for_top_land`); docs/calibration.md shows what the margin
        changes in the loaded results.
    heel_room_mm : float
        Length of both faces beyond P0 towards the heel, mm, in [0, 5]
        (:func:`face_widths_for_room`): room for the contact path on the heel side of
        the TE0 vertex, about half a pitch of path (s0003: ~2 mm).
    side : str, optional
        Force the design side; by default the side whose conjugate surface of action
        passes nearest P0.
    max_evaluations : int
        Budget of objective evaluations of the five-coefficient least squares (each a
        surface-only TCA run, ~0.3 s CPU; finite-difference steps not counted).
    progress : bool
        Print one line per improvement.

    Returns
    -------
    Calibration
    """
    t_start = time.perf_counter()
    if tip_margin_mm is not None and not 0.01 <= tip_margin_mm <= 0.5:
        raise InputRangeError("tip_margin_mm", tip_margin_mm, "[0.01, 0.5] mm")
    if not 0.0 <= heel_room_mm <= 5.0:
        raise InputRangeError("heel_room_mm", heel_room_mm, "[0, 5] mm")
    if side is not None and side not in SIDES:
        raise InputRangeError("side", side, f"one of {SIDES}")
    f2, f1 = face_widths_for_room(pair, targets.mean_point_mm, heel_room_mm=heel_room_mm)
    zero = dataclasses.replace(pair, easeoff_drive=EaseOffCoefficients(),
                               easeoff_coast=EaseOffCoefficients(), gear_face_width_mm=f2,
                               pinion_face_width_mm=f1)
    flanks0 = build_flanks(zero)
    offsets = {s: surface_of_action_offset(zero, targets.mean_point_mm, side=s, flanks=flanks0)[0]
               for s in SIDES}
    if side is None:
        side = min(SIDES, key=lambda s: offsets[s])
    # the blade pressure angle of the design side moves the surface of action: choose it
    # (to 0.1 deg) so that the conjugate contact passes through P0
    key = f"pressure_angle_{side}_deg"

    def soa(angle_deg):
        trial = dataclasses.replace(zero, cutter=dataclasses.replace(zero.cutter,
                                                                     **{key: float(angle_deg)}))
        return surface_of_action_offset(trial, targets.mean_point_mm, side=side)[0]

    best = minimize_scalar(soa, bounds=(15.0, 30.0), method="bounded",
                           options={"xatol": 0.05})
    angle = round(float(best.x), 1)
    zero = dataclasses.replace(zero, cutter=dataclasses.replace(zero.cutter, **{key: angle}))
    offsets[f"{side} at {angle:g} deg"] = soa(angle)
    if tip_margin_mm is None:
        tip_margin_mm = tip_margin_for_top_land(zero, targets.mean_point_mm)
    k_d = working_depth_for_tip(zero, targets.mean_point_mm, tip_margin_mm=tip_margin_mm)
    deep = dataclasses.replace(zero, working_depth_factor=round(k_d, 4), design_side=side)
    flanks = build_flanks(deep)
    conj, gear = flanks.pinion_conjugate.side(side), flanks.flank("gear", side)
    u_m, v_m = flanks.mean_contact[side]["pinion_uv"]
    inv0 = point_invariants(targets.mean_point_mm, pair.offset_mm)
    u_c = float(inv0[2] - conj.cone.radius_mm(0.0, inv0[3]))
    v_c = float(inv0[3])
    box = conj.boundary
    # starts: conjugate contacts of pinion points below P0; the TCA holds their height
    # (u1) and finds the phase, since the eased path need not cross P0's conjugate line
    starts = [conjugate_contact(conj, gear, deep, u_c - d, v_c) for d in (0.1, 0.3, 0.6)]
    limit = flanks.easeoff_limit_um
    # search in the centre form of the ease-off (:func:`centred_coefficients`): the
    # bearing centre (eta_c, xi_c) and the three second-order terms are nearly
    # independent there, so crowning changes do not drag the bearing off P0
    eta_c, xi_c = u_c - u_m, v_c - v_m
    lo = np.array([eta_c - 1.5, xi_c - 6.0, 0.5, 0.01, -2.0])
    hi = np.array([eta_c + 1.5, xi_c + 6.0, 40.0, 1.0, 2.0])
    scale = np.array([0.05, 0.2, 0.5, 0.01, 0.05])
    evals = {"n": 0, "best": (np.inf, None)}

    def run(x):
        evals["n"] += 1
        coeffs = centred_coefficients(*x)
        # surface-only TCA: the published TE0 is compared with the surface contact's
        # (docs/calibration.md); an edge contact at the pair switch lowers TE0 p-p and
        # doubles the cost of each run
        return coeffs, eased_design_point(coeffs, conj, gear, deep, starts, mean_uv=(u_m, v_m),
                                          limit_um=limit, torque_nm=targets.torque_nm,
                                          edge_contact=False)

    def fun(x):
        try:
            _, dp = run(x)
        except (ArithmeticError, ValueError, EdgeContact) as exc:  # edge, no pair in mesh, limit
            if progress:
                print(f"  calibration eval {evals['n']}: rejected ({exc})")
            return np.full(8, 1e3)
        r = _residuals(dp, targets, pair.offset_mm)
        cost = float(r @ r)
        if cost < evals["best"][0]:
            evals["best"] = (cost, np.array(x, dtype=float))
            if progress:
                print(f"  calibration eval {evals['n']}: cost {cost:.4g}, P0 off "
                      f"{np.abs(dp.invariants_mm - inv0).max():.3f} mm, TE0 "
                      f"{dp.te0_pp_arcsec:.2f} arcsec, ellipse {dp.ellipse_length_mm:.2f} x "
                      f"{dp.ellipse_width_mm:.3f} mm at {dp.ellipse_angle_deg:.1f} deg")
        return r

    def place(x, max_nfev=20):
        """``x`` with its bearing centre moved so that the TE0 vertex lands on P0 (the
        first-priority target; the surface of action's two coordinates fix all four
        invariants)."""
        def off(y):
            try:
                _, dp = run(np.concatenate([y, x[2:]]))
            except (ArithmeticError, ValueError, EdgeContact):
                return np.full(4, 1e2)
            return (dp.invariants_mm - inv0) / targets.tol_point_mm

        r = least_squares(off, np.clip(x[:2], lo[:2], hi[:2]), bounds=(lo[:2], hi[:2]),
                          x_scale=scale[:2], diff_step=1e-3, max_nfev=max_nfev)
        return np.concatenate([r.x, x[2:]])

    # a coarse grid over the two crownings first, each with its bearing placed on P0:
    # the objective has several basins (the path turns with the profile crowning) and a
    # local search alone stays in the first
    centre = np.array([eta_c, xi_c])
    for pc in _GRID_PROFILE_CROWNING:
        for lc in _GRID_LENGTHWISE_CROWNING:
            x = place(np.array([*centre, pc, lc, 0.0]), max_nfev=8)
            fun(x)
    if evals["best"][1] is None:
        raise CheckFailed("calibration: no ease-off of the start grid gave a TCA with the "
                          "mean contact on the flanks")
    least_squares(fun, np.clip(evals["best"][1], lo, hi), bounds=(lo, hi), x_scale=scale,
                  diff_step=1e-2, max_nfev=int(max_evaluations))
    x_best = place(evals["best"][1], max_nfev=30)
    coeffs, dp = run(x_best)
    calibrated = dataclasses.replace(deep, **{f"easeoff_{side}": coeffs})
    tip = float(conj.cone.radius_mm(box.u_tip, inv0[3]) - inv0[2])
    return Calibration(pair=calibrated, side=side, soa_offset_mm=offsets, tip_margin_mm=tip,
                       point=dp, rows=design_point_rows(dp, targets, offset_mm=pair.offset_mm),
                       evaluations=evals["n"], seconds=time.perf_counter() - t_start)



def calibration_toml(cal: Calibration, *, name: str | None = None) -> str:
    """TOML of the calibrated pair (renamed ``name`` if given) with the calibration's
    provenance as comments."""
    from ..geometry.pair import pair_to_toml

    source = cal.pair.name
    pair = cal.pair if name is None else dataclasses.replace(cal.pair, name=name)
    head = (f"{pair.name}: calibrated by gearcontact.tca.calibration (gearcontact design "
            f"--pair {source} --calibrate) to the published design point.\n"
            f"Design side {cal.side}: the published mating point lies on its surface of "
            "action (offsets, mm: " + ", ".join(f"{k} {v:.3f}" for k, v in
                                                  cal.soa_offset_mm.items()) + ").\n"
            f"working_depth_factor: pinion tip {cal.tip_margin_mm:.3f} mm above P0 at P0's "
            "axial position (a tip-edge bearing).\n"
            f"easeoff.{cal.side}: bounded least squares, {cal.evaluations} TCA runs, "
            f"max |E| {cal.point.easeoff_max_um:.1f} um.\n"
            "target / achieved / tolerance:\n" + cal.table())
    return pair_to_toml(pair, comments={"": head})
