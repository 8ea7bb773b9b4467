"""Local synthesis of the ease-off: a bearing for a pair that comes without one.

Litvin's local synthesis prescribes, at the mean point M of the flank, the position of
the bearing, the direction of the contact path, the length of the instantaneous contact
ellipse (paint thickness 6.35 um) and the level of the parabolic transmission error,
and solves the machine-tool settings for them (Litvin & Fuentes 2004, sec. 21.8; Litvin
et al. 2006). gearcontact's flanks carry the relief as the 5-term pinion ease-off, so
the unknowns are its five coefficients, written in the centre form of
:func:`~gearcontact.tca.design_point.centred_coefficients` (bearing centre
``(eta_c, xi_c)``, profile and lengthwise crowning, bias), and the conditions are met
with TCA in the loop: :func:`~gearcontact.tca.design_point.eased_design_point` (the TCA
at the continuous TE0 vertex) and bounded least squares, the machinery of the
calibration (docs/calibration.md), here with design targets instead of published ones.

Targets (:class:`SynthesisTargets`) and their defaults, from common practice:

* **bearing centre** mid-face and mid working depth of the pinion flank
  (``centre_face = centre_profile = 0.5``); practice centres the unloaded bearing or
  places it slightly towards the toe, since it moves heelwards under load (Stadtfeld
  1993, ch. 6; ANSI/AGMA 2005-D03, clause 8 "tooth contact pattern");
* **pattern length** ``2a`` of the paint ellipse = ``0.35`` x the gear face width:
  practice asks for a pattern over 1/3 to 1/2 of the face (Stadtfeld 1993, ch. 6;
  AGMA 2005-D03, clause 8);
* **TE0 level** ``3`` arcsec peak-to-peak over one pinion pitch: a few arcsec keep the
  parabolic TE function that absorbs misalignment without a large mesh excitation
  (Litvin & Fuentes 2004, sec. 21.8 use 6-8 arcsec; Stadtfeld 1993 recommends the
  smallest level that keeps the bearing inside under the mounting tolerances; s0003's
  published design has 3.4 arcsec);
* **path angle** optional: without it the bias (twist) is free but drawn weakly
  towards zero (a regularizing residual of weight :data:`BIAS_WEIGHT`), so that a
  path along the relief valley is preferred where it meets the targets, and a twisted
  one is used where TE0 and the ellipse length cannot be met together without it.
  Where the zero-bias path's surface contact lasts less than a pinion pitch (TE0 then
  an edge contact's, which no crowning sets: the 20/20 miter), the reachable path angle
  of the longest overlap is taken as the target (:func:`~.path_reach.overlap_path_angle`),
  or TE0 is named unreachable before the search (:func:`~.path_reach.te0_unreachable`).

The relief at the bearing centre is carried as a rigid turn of the pinion
(:func:`~gearcontact.tca.design_point.centred_coefficients` with ``turn``), so that the
TE0 vertex stays at the centre (docs/synthesis.md, "Low ratios").

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 21.8.
F. L. Litvin, A. Fuentes, K. Hayasaka, "Design, manufacture, stress analysis, and
experimental tests of low-noise high endurance spiral bevel gears", *Mech. Mach.
Theory* 41 (2006) 83-118.
H. J. Stadtfeld, *Handbook of Bevel and Hypoid Gears*, RIT, 1993, ch. 6.
ANSI/AGMA 2005-D03, *Design Manual for Bevel Gears*, clause 8.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from ..errors import CheckFailed
from ..geometry.flank import FlankSet, build_flanks, with_easeoff
from ..geometry.formate import SIDES
from ..geometry.kinematics import AssemblyErrors
from ..geometry.generation import check_generation
from ..geometry.pair import BEVEL, EaseOffCoefficients, GearPair, load_pair
from ..geometry.settings_check import SettingsCheck, checked_settings, completed_settings
from ..validation import InputRangeError
from .design_point import (DesignPoint, centred_coefficients, conjugate_contact,
                           eased_design_point)
from .path_reach import check_path_angle, overlap_choice, short_overlap, te0_unreachable
from .predicted_bearing import BearingPredictor, synthesis_start
from .synthesis_rounds import polish, recentred
from .synthesis_targets import (SynthesisTargets, TargetRows, angle_diff, targets_rows,
                                targets_table)
from .types import EdgeContact

__all__ = ["SynthesisTargets", "Synthesis", "TargetRows", "targets_rows", "targets_table", "synthesize_easeoff", "synthesize_pair",
           "easeoff_toml", "PreparedPair", "prepare_pair"]

#: Design torque of the Hertz ellipse reported beside the paint ellipse, N·m (not a
#: target of the synthesis; the pattern length is the paint ellipse).
_REPORT_TORQUE_NM = 64.5

#: Weight of the residual ``c_TW / scale`` that draws the bias towards zero when no
#: path angle is prescribed (one bias scale step costs 0.02 of a tolerance: with 0.1
#: the spiral bevel example kept its ellipse 6 % long, with 0.02 it meets all targets).
BIAS_WEIGHT = 0.02


#: Lengthwise-crowning scale steps of the successive local-search passes, um/mm^2 per
#: (12 mm / face)^2.
_LC_SCALES = (0.05, 0.01)

#: Convergence of the decoupled rounds of the first stage, in tolerances (a fraction of
#: the acceptance, so that the full TCA's check at the end meets every target).
_ROUND_TOL = 0.3

#: Largest difference of the reduced and the full TCA's residuals (in tolerances) at
#: which the reduced one still stands for the full one: beyond it the search is redone
#: on the full TCA.
_FAITHFUL_TOL = 0.1


class _BudgetSpent(Exception):
    """The search's budget of TCA runs is spent (its best point is the result)."""


@dataclass(frozen=True)
class Synthesis(TargetRows):
    """Result of :func:`synthesize_easeoff`.

    Attributes
    ----------
    side : str
    coefficients : EaseOffCoefficients
        The synthesized ease-off of ``side``.
    targets : SynthesisTargets
    point : DesignPoint
        TCA at the synthesized ease-off (continuous TE0 vertex).
    centre_uv_mm : (float, float)
        Target bearing centre (pinion u, v), mm.
    pattern_length_mm : float
        Target paint-ellipse 2a, mm.
    rows : tuple of (str, str, float, float, float, bool)
        (quantity, unit, target, achieved, tolerance, met).
    evaluations : int
        TCA runs.
    seconds : float
    unreachable : str
        Why a target cannot be met on this pair, found at the search's first full TCA
        (:func:`~.path_reach.te0_unreachable`; the search then stops after the
        decoupled rounds); ``""`` if none.
    path_choice : str
        Why the synthesis chose the path angle of ``targets`` itself (none was given:
        the zero-bias path's surface contact lasts less than a pitch,
        :func:`synthesize_easeoff`); ``""`` if it did not.
    """

    side: str
    coefficients: EaseOffCoefficients
    targets: SynthesisTargets
    point: DesignPoint
    centre_uv_mm: tuple[float, float]
    pattern_length_mm: float
    rows: tuple
    evaluations: int
    seconds: float
    unreachable: str = ""
    path_choice: str = ""

    def table(self) -> str:
        """Target / achieved / tolerance as Markdown, with the path choice and what is
        unreachable."""
        text = targets_table(self.rows, prefix=self.table_prefix)
        if self.path_choice:
            text += f"\n\nPath angle chosen: {self.path_choice}"
        if self.unreachable:
            text += f"\n\nNot reachable: {self.unreachable}"
        return text


def synthesize_easeoff(pair: GearPair, *, side: str | None = None,
                       targets: SynthesisTargets = SynthesisTargets(), flanks=None,
                       phases: int = 31, max_evaluations: int = 150) -> Synthesis:
    """Solve the ease-off of ``side`` (default the pair's design side) for ``targets``.

    The search runs on a reduced TCA (surface contact only, pairs -1..1): first, without
    a path-angle target, decoupled fixed-point rounds from one start; then, if they do
    not meet the targets, the start grid and the least squares. Its best point is run
    through the full TCA (edge contact, pairs -2..2), which gives the reported
    :attr:`Synthesis.point` and decides whether the targets are met; where the two TCAs
    disagree there, the search is redone on the full TCA (docs/synthesis.md).

    Parameters
    ----------
    pair : GearPair
        Its ease-off of ``side`` is ignored (the synthesis starts from the conjugate
        flanks) and so are its assembly errors: the ease-off is designed for the
        nominal mounting, so that a misalignment check shows the pattern move.
    flanks : FlankSet, optional
        ``build_flanks(pair)``, if already built.
    phases : int
        TCA phases per pitch of each evaluation (31: TE0 p-p within ~1 % of 61).
    max_evaluations : int
        Budget of TCA runs of each local-search pass (two at most per TCA model; the
        best point found is returned when it is spent).

    Raises
    ------
    InputRangeError
        Bad side, or a path angle the synthesis cannot reach on ``side``
        (:func:`~.path_reach.check_path_angle`, before any TCA).
    ArithmeticError
        If no start of the search reaches an interior contact.
    """
    t_start = time.perf_counter()
    side = pair.design_side if side is None else side
    pair = dataclasses.replace(pair, assembly=AssemblyErrors())
    if side not in SIDES:
        raise InputRangeError("side", side, f"one of {SIDES}")
    if flanks is None:
        flanks = build_flanks(pair)
    conj, gear = flanks.pinion_conjugate.side(side), flanks.flank("gear", side)
    # the start (a path angle the synthesis cannot reach is refused there, before any
    # TCA; one it can starts from its first-order design, .path_reach)
    first_x = synthesis_start(pair, side=side, targets=targets, flanks=flanks)
    (u_m, v_m), turn, centre = first_x.mean_uv_mm, first_x.turn, first_x.centre_uv_mm
    b = conj.boundary
    face = pair.gear_face_width_mm
    length = targets.pattern_length_ratio * face
    # starts of the mating-point solve: conjugate contacts at and below the centre (u1
    # held, the phase free)
    depth = b.u_tip - b.u_root
    starts = [conjugate_contact(conj, gear, pair, centre[0] - f * depth, centre[1])
              for f in (0.0, 0.03, 0.1, 0.25)]
    limit = flanks.easeoff_limit_um
    with_bias = targets.path_angle_deg is not None
    # curvature scale: the ellipse length scales with the face, its curvature with
    # 1 / length^2 (s0003-centred: 8 and 0.124 um/mm^2 for a 12 mm face)
    k = first_x.curvature_scale
    eta_c, xi_c = centre[0] - u_m, centre[1] - v_m
    lo = np.array([eta_c - 0.5 * depth, xi_c - 0.4 * face, 0.05 * k, 0.002 * k, -2.0 * k])
    hi = np.array([eta_c + 0.5 * depth, xi_c + 0.4 * face, 60.0 * k, 2.0 * k, 2.0 * k])
    x_mid = first_x.x.copy()
    if with_bias:
        # the box widened to hold the path angle's first-order design
        lo[2:] = np.minimum(lo[2:], [0.5 * x_mid[2], 0.5 * x_mid[3], x_mid[4] - abs(x_mid[4])])
        hi[2:] = np.maximum(hi[2:], [2.0 * x_mid[2], 2.0 * x_mid[3], x_mid[4] + abs(x_mid[4])])
    scale = np.array([0.02 * depth, 0.02 * face, 0.5 * k, 0.05 * k, 0.05 * k])
    budget = 9 + 2 * int(max_evaluations)
    runs = {"n": 0}

    def model(tca: dict):
        """Residual function of the TCA options ``tca`` and its record: the best point
        so far ``(cost, x, (coeffs, point))`` and the number of runs."""
        state = {"n": 0, "best": (np.inf, None, None), "r": None, "seen": {}, "points": {}}

        def residual(x):
            key = tuple(float(c) for c in x)
            if key in state["seen"]:            # a point evaluated before (same TCA)
                return state["seen"][key]
            if state["n"] >= budget:
                raise _BudgetSpent
            state["n"] += 1
            runs["n"] += 1
            coeffs = centred_coefficients(*x, turn=turn)
            try:
                dp = eased_design_point(coeffs, conj, gear, pair, starts, mean_uv=(u_m, v_m),
                                        limit_um=limit, torque_nm=_REPORT_TORQUE_NM,
                                        phases=phases, **tca)
            except (EdgeContact, ArithmeticError, ValueError):
                state["seen"][key] = np.full(5, 1e3)
                return state["seen"][key]
            r = [(dp.pinion_uv[0] - centre[0]) / targets.tol_centre_mm,
                 (dp.pinion_uv[1] - centre[1]) / targets.tol_centre_mm,
                 (dp.te0_pp_arcsec / targets.te0_pp_arcsec - 1.0) / targets.tol_te0_rel,
                 (dp.paint_length_mm / length - 1.0) / targets.tol_length_rel]
            if with_bias:
                ang = dp.path_angle_deg if np.isfinite(dp.path_angle_deg) else 90.0
                r.append(angle_diff(ang, targets.path_angle_deg) / targets.tol_angle_deg)
            else:
                r.append(BIAS_WEIGHT * x[4] / scale[4])
            r = np.asarray(r)
            cost = float(r @ r)
            if cost < state["best"][0]:
                state["best"] = (cost, np.array(x, float), (coeffs, dp))
                state["r"] = r
            state["seen"][key], state["points"][key] = r, dp
            return r

        return residual, state

    def met(state) -> bool:
        return (state["best"][1] is not None and
                all(r[5] for r in targets_rows(state["best"][2][1], targets, centre, length)))

    def refine(residual, state) -> bool:
        """Levenberg-Marquardt passes from the best point so far; True if met."""
        # the local search runs in variables normalized by ``scale`` (each of order one
        # per scale step), so that the finite-difference step (1 % of max(1, |z|) scale
        # steps) is a small, comparable change of every coefficient. A pass that stalls
        # short of the targets is restarted from the best point so far with a finer
        # lengthwise-crowning scale (measured: the coarse scale meets F3, the 11/41
        # hypoid and the s0003 tip-edge preset; the F2 spiral bevel needs the fine one)
        for lc_scale in _LC_SCALES:
            x0 = np.clip(state["best"][1], lo, hi)
            step = scale.copy()
            step[3] = lc_scale * k
            least_squares(lambda z, x0=x0, step=step: residual(x0 + z * step), np.zeros(5),
                          method="lm", diff_step=1e-2, max_nfev=int(max_evaluations))
            if met(state):
                return True
        return False

    def search(residual, state) -> None:
        """(With a path-angle target: its first-order design, refined.) Start grid,
        Levenberg-Marquardt passes, decoupled rounds (docs/synthesis.md)."""
        if with_bias:
            recentred(residual, x_mid, centre, targets.tol_centre_mm, lo, hi)
            if state["best"][1] is not None and refine(residual, state):
                return
        # start grid over the two crownings (the objective has several basins: the path
        # turns with the profile crowning), each start re-centred before it is ranked:
        # the TE0 vertex moves with the crownings along an inclined path (F2 spiral bevel
        # coast: 5 mm towards the toe at 4x the profile crowning), so a start ranked with
        # its ease-off centre at the target bearing centre is ranked by that drift, not
        # by the TE0 and pattern length it gives
        for pc in (4.0, 8.0, 16.0, 24.0, 32.0):
            for lc in (0.06, 0.15, 0.4):
                recentred(residual, np.array([eta_c, xi_c, pc * k, lc * k, 0.0]), centre,
                           targets.tol_centre_mm, lo, hi)
        if state["best"][1] is None:
            return
        if not refine(residual, state):
            polish(residual, state["best"][1], lo, hi, targets)

    def stages(residual, state) -> None:
        """Without a path-angle target, the decoupled rounds from the middle of the
        start grid, converged to a fraction of the tolerances (the full TCA's check must
        meet them); then, if they miss and the targets are reachable, :func:`search`."""
        try:
            if not with_bias:
                polish(residual, x_mid, lo, hi, targets, rounds=12, within=_ROUND_TOL)
                # met with room for the full TCA's difference from the reduced one
                if unreachable or (state["r"] is not None
                                   and np.max(np.abs(state["r"][0:4])) <= 1.0 - _FAITHFUL_TOL):
                    return
            search(residual, state)
        except _BudgetSpent:
            pass

    def agree(r_reduced, r_full) -> bool:
        """Both TCAs reach an interior contact and their residuals agree."""
        return bool(max(r_reduced[0], r_full[0]) < 1e3
                    and np.max(np.abs(r_full - r_reduced)) <= _FAITHFUL_TOL)

    # The search runs on the surface-only TCA of pairs -1..1 (``reduced``: the design
    # point, the TE0 level over the pitch and the paint ellipse at the vertex are the
    # same wherever the contact that carries stays off the edges, at 1/2 to 1/5 of the
    # cost of the full TCA with its edge-contact tails) if the two agree at the first
    # start; its best point is checked by the full TCA (``full``, edge contact, pairs
    # -2..2), which gives the reported point. Where they disagree (a bearing at an edge)
    # the search runs on the full TCA.
    reduced, on_reduced = model({"pairs": 1, "edge_contact": False})
    full, on_full = model({"pairs": 2, "edge_contact": True})
    faithful = agree(reduced(x_mid), full(x_mid))
    # a zero-bias path whose surface contact lasts less than a pitch is turned to the
    # path angle of the longest overlap (closed form), or the TE0 target is named
    # unreachable, here at the first full TCA
    first = on_full["points"].get(tuple(float(c) for c in x_mid))
    short = None if with_bias else short_overlap(first, phases)
    unreachable = ""
    if short is not None:
        angle, ratio, overlaps = overlap_choice(pair, side=side, targets=targets, flanks=flanks)
        if overlaps:
            again = synthesize_easeoff(
                pair, side=side, targets=dataclasses.replace(targets, path_angle_deg=angle),
                flanks=flanks, phases=phases, max_evaluations=max_evaluations)
            return dataclasses.replace(
                again, evaluations=again.evaluations + runs["n"],
                seconds=time.perf_counter() - t_start, path_choice=(
                    f"{angle:.1f} deg on the {side} side: with the bias near zero (path "
                    f"angle {first.path_angle_deg:.1f} deg) one pair's surface contact "
                    f"lasts {short:.2f} of a pinion pitch, so TE0 would be set by the "
                    "edge contact that passes it to the next pair; along "
                    f"{angle:.1f} deg it lasts {ratio:.2f} pitches (first order, the "
                    "longest of the reachable path angles; docs/synthesis.md)"))
        unreachable = te0_unreachable(short, targets.te0_pp_arcsec, side=side,
                                      best=(angle, ratio))
    if faithful:
        stages(reduced, on_reduced)
        faithful = on_reduced["best"][1] is not None
        if faithful:
            try:
                faithful = agree(on_reduced["r"], full(on_reduced["best"][1]))
            except _BudgetSpent:
                pass
    if not faithful and not met(on_full):
        stages(full, on_full)
    if on_full["best"][1] is None:
        raise CheckFailed(f"ease-off synthesis of {pair.name} {side}: no start of the "
                          "search gave an interior TCA contact")
    _, _, (coeffs, dp) = on_full["best"]
    return Synthesis(side, coeffs, targets, dp, centre, length,
                     targets_rows(dp, targets, centre, length), runs["n"],
                     time.perf_counter() - t_start, unreachable)


def easeoff_toml(synth: dict, *, pair_name: str) -> str:
    """``[easeoff.<side>]`` TOML tables of ``synth`` (side -> :class:`Synthesis`), with
    the targets and what was achieved as comments, ready to paste into a pair file."""
    out = []
    for side, s in synth.items():
        t = s.targets
        out.append(f"[easeoff.{side}]")
        out.append(f"# synthesized by gearcontact (local synthesis, {pair_name}): TE0 "
                   f"{t.te0_pp_arcsec:g} arcsec, paint ellipse {t.pattern_length_ratio:g} x face, "
                   + ("path angle free" if t.path_angle_deg is None
                      else f"path angle {t.path_angle_deg:g} deg")
                   + f", centre at {t.centre_face:g} face / {t.centre_profile:g} depth.")
        out.append(f"# achieved: TE0 {s.point.te0_pp_arcsec:.2f} arcsec, 2a "
                   f"{s.point.paint_length_mm:.2f} mm, path angle {s.point.path_angle_deg:.1f} "
                   f"deg, max |E| {s.point.easeoff_max_um:.1f} um"
                   + ("" if s.met else " (NOT all targets met: see the table)"))
        for what, text in (("path angle chosen", s.path_choice),
                           ("not reachable", s.unreachable)):
            if text:
                out.append(f"# {what}: {text}")
        for k, v in dataclasses.asdict(s.coefficients).items():
            out.append(f"{k} = {float(v):.6g}")
        out.append("")
    return "\n".join(out)


def synthesize_pair(pair: GearPair, *, sides=SIDES,
                    targets: SynthesisTargets | Mapping = SynthesisTargets(),
                    flanks=None) -> tuple[GearPair, dict]:
    """``pair`` with the ease-off of each of ``sides`` synthesized, and the
    :class:`Synthesis` of each side.

    ``targets`` is one :class:`SynthesisTargets` for every side or a mapping side ->
    targets (a path angle of each side: the sides' reachable ranges differ, s0003 drive
    [-7.8, 42.9] deg, coast [-6.8, 43.6] deg). Every side's path angle is checked
    before any TCA (:func:`~.path_reach.check_path_angle`).
    """
    per_side = targets if isinstance(targets, Mapping) else dict.fromkeys(sides, targets)
    missing = [s for s in sides if s not in per_side]
    if missing:
        raise InputRangeError("targets", sorted(per_side), f"a mapping with the sides {sides}")
    if flanks is None:
        flanks = build_flanks(pair)
    for s in sides:                                                    # every side first
        check_path_angle(pair, targets=per_side[s], flanks=flanks, sides=(s,))
    done = {s: synthesize_easeoff(pair, side=s, targets=per_side[s], flanks=flanks)
            for s in sides}
    return dataclasses.replace(pair, **{f"easeoff_{s}": r.coefficients
                                        for s, r in done.items()}), done


@dataclass(frozen=True)
class PreparedPair:
    """A pair ready for TCA (:func:`prepare_pair`).

    Attributes
    ----------
    pair : GearPair
        The pair with an ease-off table of ``side`` (the synthesized one if its file
        had none: ``side`` is then added to ``easeoff_tables``).
    side : str
        The flank side prepared.
    synthesis : Synthesis or None
        The local synthesis of ``side``, None if the pair brought its table.
    flanks : FlankSet or None
        ``build_flanks(pair)`` (bit for bit) if the synthesis built the flanks, so that
        a command does not build them again; None if nothing was synthesized.
    checked : dict or None
        :func:`~gearcontact.geometry.generation.check_generation`'s result for the pair,
        if the command ran it (its gear flanks are reused by :meth:`flank_set`).
    settings_check : SettingsCheck or None
        The typed-settings check of the pair as loaded
        (:func:`~gearcontact.geometry.settings_check.check_settings`); None for a pair
        without machine settings.
    """

    pair: GearPair
    side: str
    synthesis: Synthesis | None = None
    flanks: FlankSet | None = None
    checked: dict | None = dataclasses.field(default=None, compare=False, repr=False)
    settings_check: SettingsCheck | None = dataclasses.field(default=None, compare=False,
                                                             repr=False)

    def flank_set(self) -> FlankSet:
        """The flanks of :attr:`pair`: those the synthesis built (its ease-off applied),
        else ``build_flanks(pair)`` (reusing :attr:`checked`), so that a command builds
        them once."""
        return (self.flanks if self.flanks is not None
                else build_flanks(self.pair, checked=self.checked))

    @property
    def synthesized(self) -> bool:
        """The ease-off of ``side`` was synthesized (the pair had no table)."""
        return self.synthesis is not None

    @property
    def note(self) -> str:
        """What the output says about a synthesized ease-off (``""`` if none was): one
        line, then the ``[easeoff.<side>]`` TOML block. Deterministic (the synthesis
        time is in :attr:`timings_s`, not here), so result files holding it are
        identical across identical runs."""
        s = self.synthesis
        if s is None:
            return ""
        name = self.pair.name
        return (f"{name} has no [easeoff.{self.side}] table: ease-off synthesized (local "
                f"synthesis, {s.evaluations} TCA runs): TE0 {s.point.te0_pp_arcsec:.2f} "
                f"arcsec, paint ellipse {s.point.paint_length_mm:.2f} mm (targets "
                f"{s.targets.te0_pp_arcsec:g} arcsec, {s.pattern_length_mm:.2f} mm); keep it "
                f"with `gearcontact design --pair FILE --synthesize-easeoff`:\n"
                + easeoff_toml({self.side: s}, pair_name=name))

    @property
    def timings_s(self) -> dict:
        """Wall time of the synthesis, s (``{"easeoff_synthesis_s": ...}``; empty if
        nothing was synthesized): a timing, for run.json only."""
        return {} if self.synthesis is None else {"easeoff_synthesis_s": self.synthesis.seconds}


def prepare_pair(pair, *, side: str | None = None, checked: dict | None = None,
                 settings_check: SettingsCheck | None = None,
                 mesh_follows: bool = True) -> PreparedPair:
    """The one pair preparation of every command that takes a pair: ``pair`` (a
    :class:`GearPair`, preset name or TOML path) with, if it has no ease-off table of
    ``side`` (default its design side), the ease-off of that side synthesized with the
    default :class:`SynthesisTargets` (deterministic: the same pair gives the same
    coefficients in every command). The other side is left as given.

    Before any flank work a bevel pair passes ``design``'s checks: first a pair cut from
    machine settings its typed-settings check against its blank
    (:func:`~gearcontact.geometry.settings_check.check_settings`: a gross mismatch
    refused naming the likely key, any other flank outside its tolerance a
    :class:`~gearcontact.geometry.settings_check.SettingsWarning`; docs/machine_settings.md
    sec. 2), then :func:`~gearcontact.geometry.generation.check_generation` (undercut,
    pointed teeth, contact ratio), so that every command refuses a pair that cannot be
    made first, with the same named condition and fix as ``design`` (the contact path
    of the bearing the synthesis will make, :class:`~.predicted_bearing.BearingPredictor`,
    where the pair has no table). ``settings_check``: the typed-settings check's result
    for ``pair``, if the caller already ran it (the command line, in its argument
    check; nothing is warned again), else run here. ``checked``: the generation
    check's result for ``pair``, if the command already ran it (else run here); the
    flanks reuse its gear flanks (:meth:`PreparedPair.flank_set`; a generated gear's
    sheets are built once, :func:`~gearcontact.geometry.flank.build_flanks`). A pair
    cut from settings with a generated gear then has its pinion ease-off measured on the
    gear boxes that check traced
    (:func:`~gearcontact.geometry.settings_check.completed_settings`: a hollow flank is a
    :class:`~gearcontact.geometry.easeoff_shape.HollowEaseOffWarning`).
    ``mesh_follows``: the caller runs the pair's TCA, which refuses a mesh with a gap
    (:class:`~.edges.ContactGap`), so a pair cut from settings whose predicted contact
    ratio is short is not warned; False (a command without a TCA: ``bending``,
    ``export flanks``): a :class:`~gearcontact.geometry.contact_ratio.ContactRatioWarning`
    names the prediction and the TCA that decides (docs/machine_settings.md sec. 5).

    Raises
    ------
    InputRangeError
        A bad pair file or side, typed machine settings that do not cut the blank's
        tooth (a gross mismatch), or a pair ``design`` refuses (before any flank work).
    ArithmeticError
        If the synthesis finds no interior contact (:func:`synthesize_easeoff`).
    """
    if not isinstance(pair, GearPair):
        pair = load_pair(pair)
    side = pair.design_side if side is None else side
    if side not in SIDES:
        raise InputRangeError("side", side, f"one of {SIDES}")
    if settings_check is None:      # None for a pair without settings
        settings_check = checked_settings(pair, stacklevel=2, deferred=True)
    if checked is None and pair.kind == BEVEL:
        # the contact path of the bearing the synthesis below will make (default targets)
        checked = check_generation(pair, bearing_of=BearingPredictor(),
                                   mesh_follows=mesh_follows)
    if checked is not None:     # a generated gear's pinions, on the boxes just traced
        settings_check = completed_settings(pair, settings_check, checked, stacklevel=2)
    if side in pair.easeoff_tables:
        return PreparedPair(pair, side, checked=checked, settings_check=settings_check)
    base = build_flanks(pair, checked=checked)
    new, done = synthesize_pair(pair, sides=(side,), flanks=base)
    new = dataclasses.replace(new, easeoff_tables=tuple(pair.easeoff_tables) + (side,))
    # the conjugate flanks do not depend on the ease-off: only the ease-off is applied
    # again (geometry.flank.with_easeoff, the last step of build_flanks)
    return PreparedPair(new, side, done[side], with_easeoff(base, new), checked=checked,
                        settings_check=settings_check)
