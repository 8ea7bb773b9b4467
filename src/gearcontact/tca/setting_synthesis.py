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
  ``phi'`` there only: the equation of meshing; :func:`~.setting_problem.roll_about`);
* ``blade_curvature_per_mm``: a circular pinion blade tangent to the straight one at the
  blade point that generates M
  (:func:`~gearcontact.geometry.basic_settings.crown_profile`);
* ``radius_delta_mm``: the pinion cutter radius changed with the cutter centre moved
  along the blade's radial line through that point
  (:func:`~gearcontact.geometry.basic_settings.mismatch_radius`).

The conditions are measured at M by a local TCA
(:func:`~.setting_problem.mean_point_contact`: five
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
(:mod:`.setting_problem`): a generated hypoid gear's crown-gear pinion (point contact, M
on its contact path; in :func:`synthesized_machine_pair` also with the ellipse shortened
and M moved along the path, as below) or the line-contact conjugate of a formate gear or a spiral bevel
(M the blank's mean point on the pinion or, in :func:`synthesized_machine_pair`, the
middle of the pinion's working depth, that with the paint ellipse no longer than the
contact line's room there, or the middle of the best one's pattern run, whichever keeps
the pattern off the flank edges at more phases).

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
from ..geometry.basic_settings import STANDARD_CROWNING, crowned_pinion_setups
from ..geometry.formate import SIDES
from ..geometry.gear_generation import gear_generation as default_gear_generation
from ..geometry.machine import MachineSetup, mirror_setup
from ..validation import InputRangeError
from .analysis import pattern_on_flank
from .design_point import DesignPoint
from .edges import pattern_edges
from .mesh import mesh_cycle
from .setting_band import DepthNeed, depth_need
from .setting_candidates import pivot_candidates
from .setting_problem import (MeanPointContact, PatternRun, SynthesisProblem,
                              corrected_setup, mean_point_contact, pattern_run, roll_about)
from .setting_reach import ReachPrediction, chord_step, reach_model, target_misses
from .synthesis_targets import (PATTERN_RATIO_RANGE, SynthesisTargets, TargetRows,
                                targets_rows)
from .types import EdgeContact

__all__ = ["PARAMETER_NAMES", "MeanPointContact", "SettingSynthesis", "SynthesisProblem",
           "mean_point_contact", "roll_about", "corrected_setup",
           "synthesize_settings", "synthesized_machine_pair"]

#: The three corrections (module docstring), in the order of :attr:`SettingSynthesis.x`.
PARAMETER_NAMES = ("roll_curvature", "blade_curvature_per_mm", "radius_delta_mm")
#: Least-squares scale steps of the corrections (1, 1/mm, mm): about a tenth of the
#: standard crowning's values on F.3-sized pairs.
_SCALE = np.array([1e-3, 2e-4, 0.2])
#: Chord steps of the reach model (:func:`~.setting_reach.chord_step`, one local TCA
#: each) before the search: measured on the 13/26 hypoid, four take the residual at
#: the model's corrections from 106-337 to 0.3-4.7 (tolerance units).
CHORD_STEPS = 4


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
    pivot : str
        Where M, the pivot, lies (:attr:`~.setting_problem.SynthesisProblem.pivot`).
    other_pivot : str
        Where several pivots of :func:`synthesized_machine_pair` were tried: the others
        and their full TCAs' checks ("" otherwise).
    run : PatternRun or None
        The run of the transmitting tooth pair's path (the full TCA's, pairs -2..2
        pitches) around M's phase whose paint ellipse lies on both flanks
        (:func:`~.setting_problem.pattern_run`); None where it has none.
    depth : DepthNeed or None
        The depth the bearing needs over one pitch against the pinion flank's, first
        order at M (:mod:`.setting_band`; docs/machine_settings.md sec. 5, "The
        bearing's depth"); None where the contact leaves a flank within two local steps
        of M.
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
    pivot: str = ""
    other_pivot: str = ""
    run: PatternRun | None = None
    depth: DepthNeed | None = None

    @property
    def edge_phases(self) -> int:
        """Phases of the full TCA whose paint ellipse reaches a flank edge."""
        return sum(1 for e in self.edges if e)

    def pivot_text(self) -> str:
        """Where M lies and, if tried, the other pivot's check; where the paint ellipse
        reaches a flank edge, the bearing's depth against the flank's
        (:meth:`~.setting_band.DepthNeed.text`: room against need)."""
        text = f"{self.side}: pivot M at {self.pivot}, pinion (u, v) = " + \
            ", ".join(f"{t:.3f}" for t in self.point.pinion_uv) + " mm"
        text += f"; kept against {self.other_pivot}" if self.other_pivot else ""
        if self.edge_phases and self.depth is not None:
            text += (f"\n{self.side}: the bearing's {self.depth.text()} (first order at M, "
                     "docs/machine_settings.md sec. 5)")
        return text

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
        the problem's M; ``centre_profile`` places the centred pivot of
        :func:`synthesized_machine_pair`), for every
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
        No contact at M at the starting settings, or a side without M
        (:attr:`SynthesisProblem.off_flank`), before any search.
    """
    for side in sides:
        if side not in SIDES:
            raise InputRangeError("side", side, f"one of {SIDES}")
    per_side = targets if isinstance(targets, dict) else dict.fromkeys(sides, targets)
    missing = [side for side in sides if side not in per_side]
    if missing:
        raise InputRangeError("targets", sorted(per_side), f"targets of the sides {sides}")
    prob = problem or SynthesisProblem(pair)
    for side in sides:
        if side in prob.off_flank:
            raise CheckFailed(f"setting synthesis of {pair.name} {side}: "
                              f"{prob.off_flank[side]}")
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

        # the Jacobian by forward steps of _JAC_STEP scale steps: scipy's relative
        # diff_step (1e-3 of z) is sqrt(eps) at the start z = 0 (scipy 1.17), 1.5e-8
        # scale steps, in the local TCA's noise there
        fun, jac = _forward_jacobian(residual)
        least_squares(fun, np.zeros(len(active)), jac=jac, method="trf",
                      max_nfev=int(max_evaluations))
        out[side] = dataclasses.replace(
            _checked(prob, side, runs["best"][1], targets, length, phases, runs["n"], t0),
            reach=reach, reach_residual=at_reach, start_residual=at_first,
            residual=math.sqrt(runs["best"][0]))
    return out


#: Forward-difference step of the search's Jacobian, in scale steps
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
    run = pattern_run(flank, gear, kin, cyc.path, phi1_rad=start.phi1_rad,
                      pinion_teeth=pair.pinion_teeth)
    try:
        depth = depth_need(flank, gear, pair, start,
                           shortest_mm=PATTERN_RATIO_RANGE[0] * pair.gear_face_width_mm)
    except (EdgeContact, ArithmeticError, ValueError):     # no local TCA about M
        depth = None
    return SettingSynthesis(side, prob.setup(side, x), x, local.point,
                            targets_rows(local.point, targets, None, length),
                            float(cyc.te0_pp_arcsec), tuple(edges),
                            float(np.hypot(vertex.u1 - u_m, vertex.v1 - v_m)), runs,
                            time.perf_counter() - t0, pivot=prob.pivot[side], run=run,
                            depth=depth)


def synthesized_machine_pair(pair, *, targets: SynthesisTargets | dict = SynthesisTargets(),
                             gear_generation: str | None = None, gear: dict | None = None,
                             standard_off_flank: bool = False, centre_pivot: bool = True,
                             bearing_room: bool = True, **options):
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
    is measured so that it means the same bearing for both hands).

    A typed gear ``gear`` (``{side: MachineSetup}``, as the user typed it: the pair file's
    ``[machine.gear.*]`` / ``[print.gear]``) replaces the blank's gear
    (:class:`SynthesisProblem`: its uncrowned pinion is the base) and is kept exactly as
    given in the result, ``pair.print_gear`` with it (written back as typed); a
    left-hand pair's twin gets it mirrored.

    The pivot (docs/machine_settings.md sec. 5, "The pivot's depth"): a line-contact
    base (a formate gear, or a generated gear at offset 0) is synthesized twice per side
    with ``centre_pivot``: M at the blank's mean node (the standard crowning's pivot) and
    M at the bearing centre's depth (``targets.centre_profile`` of the pinion's working
    depth on the mean section, :class:`SynthesisProblem` ``pivot_depth``: the middle by
    default, where the paint ellipse along the contact line has the most room), and
    the one whose full TCA puts the paint ellipse at a flank edge at fewer phases is
    kept (a tie: the lower TE0 p-p; :func:`~.setting_pivot.better_pivot`), the other's
    check in its ``other_pivot``. With ``bearing_room`` (docs/machine_settings.md sec. 5,
    "The bearing's room") up to three more candidates per side join the choice: the
    centre with the paint ellipse's target shortened to the contact line's room there
    (:func:`~.setting_pivot.room_targets`, where the target exceeds it), the pivot moved
    to the middle of the best candidate's pattern run (:func:`~.setting_pivot.run_pivot`)
    and the best one's pivot with the ellipse shortened for a pattern run of one pitch
    (:func:`~.setting_pivot.length_targets`); the result's rows and ``pivot`` name a
    shortened target. The kept ones of both sides must cut a pinion tooth that the
    readers accept (:func:`~gearcontact.geometry.settings_top_land.check_settings_top_land`:
    no pointed tooth, no folding flank); where they do not, the next combination of the
    sides' candidates is kept (:func:`~.setting_pivot.cuttable_choice`). A point-contact
    base pivots on its contact path: its candidates (with ``centre_pivot`` and
    ``bearing_room``; docs/machine_settings.md sec. 5, "The candidate choice for a
    point-contact base") are M with the asked targets, M with the paint ellipse no
    longer than its room along its major axis there, the pivot moved along the base's
    path to the pinion section of the best one's pattern run's middle
    (:class:`SynthesisProblem` ``pivot_uv``) and the best one's pivot with the ellipse
    shortened for a run of one pitch, chosen by the same rule (no working depth's centre:
    it is no point of the path); where the best one still has edge phases with the path
    free, its pivot moved along the base's path to the ellipse's room plus the contact's
    depth travel over half a pitch (:func:`~.setting_pivot.room_pivot`) and its path at M
    turned towards lengthwise (:func:`~.setting_pivot.turned_path_targets`) join it
    (sec. 5, "The print's drive bearing" and "a margin on lever 5's room"); the choice:
    :func:`~.setting_candidates.pivot_candidates`.

    A side without M (:attr:`SynthesisProblem.off_flank`: the base's contact path misses
    the pinion mean section on the flank) raises CheckFailed, or with
    ``standard_off_flank`` gets the base localized by the standard crowning
    (:func:`~gearcontact.geometry.basic_settings.crowned_pinion_setups`, 25 / 10 um: the
    standard pinion, :func:`~gearcontact.geometry.typed_pinion.typed_gear_machine_pair`'s
    for a typed gear) and no entry in the per-side results."""
    if pair.pinion_hand == "left":
        twin, done = synthesized_machine_pair(
            dataclasses.replace(pair, pinion_hand="right", machine=(), typed_gear=(),
                                print_gear=()), targets=targets,
            gear_generation=gear_generation, standard_off_flank=standard_off_flank,
            centre_pivot=centre_pivot, bearing_room=bearing_room,
            gear=None if gear is None else {s: mirror_setup(g) for s, g in gear.items()},
            **options)
        machine = tuple(mirror_setup(s) for s in twin.machine)
        if gear is not None:      # the gear as typed, not its twin's mirror image
            machine = tuple(gear[s] for s in SIDES) + machine[len(SIDES):]
        return dataclasses.replace(pair, machine=machine, typed_gear=(),
                                   easeoff_tables=twin.easeoff_tables), done
    if gear_generation is None and gear is None:
        gear_generation = default_gear_generation(pair)[0]
    grid = {"n_u": options.pop("n_u", 40), "n_v": options.pop("n_v", 50)}
    prob = SynthesisProblem(pair, gear_generation=gear_generation or "generated", gear=gear,
                            **grid)
    sides = tuple(s for s in SIDES if not (standard_off_flank and s in prob.off_flank))
    done = synthesize_settings(pair, targets=targets, problem=prob, sides=sides,
                               **options) if sides else {}
    if centre_pivot and sides and (bearing_room or not prob.point_contact):
        done = pivot_candidates(pair, done, targets, sides, options, bearing_room,
                                node=prob, problem=dict(
                                    gear_generation=gear_generation or "generated",
                                    gear=gear, **grid), synthesize=synthesize_settings)
    pinion = {s: r.setup for s, r in done.items()}
    pinion.update(crowned_pinion_setups(pair, {s: prob.base[s] for s in SIDES
                                               if s not in done},
                                        **STANDARD_CROWNING))
    machine = tuple(prob.gear_setups[s] for s in SIDES) + tuple(pinion[s] for s in SIDES)
    return dataclasses.replace(pair, machine=machine, typed_gear=(),
                               easeoff_tables=("drive", "coast")), done
