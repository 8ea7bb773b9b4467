"""Machine-setting correction of a cut member from its measured flank (issue 27 item 4:
the gear rows of ``design --machine-settings --target-flank``, and the pinion rows of a
pair cut from machine settings).

A measuring room measures the gear too: the deviations of its flank on the CMM grid
(docs/export.md "The measuring grid"; rows ``member = gear``) against the nominal gear
the pair's settings cut. Each measured gear flank is fitted at its points
(:mod:`.point_fit`, the same least squares as the pinion's, :mod:`.setting_fit`; the
cut flank solved at each point on the gear sheet, :mod:`.member_envelope`) from the
settings of that nominal gear: the pair's ``[machine.gear.*]`` tables, or for a pair
without them the gear of its default flanks (formate, or generated where the formate
gear undercuts its pinion: :func:`~.basic_settings.member_setups`, the exact settings
of that gear). The corrected set is chosen by the gear's cutting method
(:func:`~.setting_fit.default_parameters`). The pinion rows of a pair cut from
machine settings are deviations from the pinion its ``[machine.pinion.*]`` tables cut
(the flank the user measured), fitted the same way from those tables
(:func:`measured_correction` with ``member="pinion"``; the pinion rows of a pair
without tables are read against its conjugate pinion, :mod:`.easeoff_settings`).
A relieved blade (Toprem / Flankrem) keeps its relief (:mod:`.relief_setup`): the
nominal and the cut flanks are :func:`~.kinked.machine_flank`'s pieces, each point on
its own.

Identifiability: a flank measurement cannot separate every setting. A formate gear
with a straight blade and no tilt cuts a cone of revolution: of its settings the
flank sees five independent combinations (docs/machine_settings.md sec. 6, "Gear
flanks": the sliding base moves the cone along its axis exactly as the cutter radius
does; the cradle angle, radial distance and blank offset translate it in the same
three directions as the machine centre to back and the cutter radius). Before the fit
the sensitivity at the points is checked (:func:`~.point_fit.check_observable`: the
column-normalized Jacobian's smallest singular value relative to the largest at least
:data:`~.point_fit.RANK_TOLERANCE`), so a degenerate subset is refused naming its
settings, never fitted silently; the fit reports that singular value and the
condition at the solution.

The residual is reported at the measured points (the cut flank's normal distance from
each measured point, exact envelope, no spline) and, for a complete grid (the CMM grid
of ``export flanks``, :func:`~.measuring_grid.is_complete_grid`) of a smooth blade's
flank, over the flank as the pinion's ease-off fit's is: the measured flank the bicubic
spline through the grid's deviations over the nominal flank's (u, v)
(:class:`~.easeoff.GridEaseOff`) on 60 x 75 points of the grid's box, the cut flank
solved at each (not for a relieved blade: the spline would smooth its kink).
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass

import numpy as np

from ..validation import InputRangeError
from .basic_settings import member_setups
from .formate import SIDES
from .kinked import machine_flank
from .machine import mirror_setup
from .easeoff import GridEaseOff
from .easeoff_settings import KinkPosition
from .measuring_grid import (RESIDUAL_COLUMNS, MeasuredFlank, MeasuredPoints,
                             flank_parameters_at, grid_values, is_complete_grid,
                             measured_points, residual_rows)
from .member_envelope import member_cone
from .point_fit import RANK_TOLERANCE, PointProblem, check_observable, check_point_count
from .setting_fit import PARAMETERS, SettingFit, checked_options, solve_fit

__all__ = ["GearCorrection", "GearSideFit", "corrected_pair", "gear_correction", "gear_seeds",
           "machine_seeds", "measured_correction", "measured_corrections"]


@dataclass(frozen=True)
class GearSideFit:
    """The fit of one measured flank (gear or pinion) at its points.

    Attributes
    ----------
    side : str
    fit : SettingFit
        ``fit_max_um`` / ``fit_rms_um``: the residual at the points, um.
    points : MeasuredPoints
    deviation_max_um : float
        Largest |measured deviation| from the nominal gear, um (what was corrected).
    residual_um : ndarray
        The cut flank's normal distance from each measured point (file order), um,
        positive = material left.
    relative_singular_value : float
        Smallest singular value of the column-normalized sensitivity at the seed,
        relative to the largest (:func:`~.point_fit.check_observable`).
    flank_max_um, flank_rms_um : float
        Largest |residual| and RMS over the flank (a complete grid, module docstring;
        NaN for scattered points and a relieved blade), um.
    kinks : tuple of KinkPosition
        A relieved blade's kink lines on the cut flank (:class:`~.easeoff_settings.
        KinkPosition`; empty for a smooth blade).
    box : FlankBoundary or None
        The cut flank's active box (a relieved blade's; None for a smooth one).
    """

    side: str
    fit: SettingFit
    points: MeasuredPoints
    deviation_max_um: float
    residual_um: np.ndarray
    relative_singular_value: float
    flank_max_um: float = math.nan
    flank_rms_um: float = math.nan
    kinks: tuple = ()
    box: object = None


@dataclass(frozen=True)
class GearCorrection:
    """Corrected settings of one member (:func:`measured_correction`; the gear's:
    :func:`gear_correction`).

    Attributes
    ----------
    setups : dict
        ``{side: MachineSetup}`` of both flanks of ``member``: the fitted ones, the
        seed where the side was not measured.
    sides : dict
        ``{side: GearSideFit}`` of the measured sides.
    mirrored : bool
        A left-hand pair: fitted on its right-hand twin (the corrections are the
        twin's), ``setups`` mirrored back.
    member : str
        ``"gear"`` or ``"pinion"``.
    """

    setups: dict
    sides: dict
    mirrored: bool = False
    member: str = "gear"

    def comment_lines(self) -> list[str]:
        """One line per measured side for a TOML head comment."""
        return [f"{self.member} {side} ({len(r.points.line)} measured points, --target-flank): "
                f"deviation max {r.deviation_max_um:.2f} um, residual max "
                f"{r.fit.fit_max_um:.3g} um, RMS {r.fit.fit_rms_um:.3g} um at the points"
                + ("" if math.isnan(r.flank_max_um) else f", max {r.flank_max_um:.3g} um, "
                   f"RMS {r.flank_rms_um:.3g} um over the flank")
                for side, r in self.sides.items()]

    def table(self) -> str:
        """Residual, identifiability and corrections per measured side (Markdown)."""
        rows = [f"| {self.member} side | points | deviation max (um) | residual max / RMS at the "
                "points (um) | over the flank (um) | smallest rel. singular value | "
                "condition | fit evaluations |", "|---|---:|---:|---:|---:|---:|---:|---:|"]
        for side, r in self.sides.items():
            flank = ("-" if math.isnan(r.flank_max_um) else
                     f"{r.flank_max_um:.3g} / {r.flank_rms_um:.3g}")
            rows.append(f"| {side} | {len(r.points.line)} | {r.deviation_max_um:.2f} | "
                        f"{r.fit.fit_max_um:.3g} / {r.fit.fit_rms_um:.3g} | {flank} | "
                        f"{r.relative_singular_value:.1e} | {r.fit.condition_number:.3g} | "
                        f"{r.fit.evaluations} |")
        for side, r in self.sides.items():
            for k in r.kinks:
                rows += ["", f"{side}: the relieved blade's {k.text(r.box)} (the relief kept "
                         "as given; the residual at the points on both sides of it)"]
        rows += ["", f"| {self.member} correction | unit | " + " | ".join(self.sides) + " |",
                 "|---|---|" + "---:|" * len(self.sides)]
        names = list(dict.fromkeys(n for r in self.sides.values() for n in r.fit.corrections))
        for n in names:
            rows.append(f"| {n} | {PARAMETERS[n][0]} | " + " | ".join(
                f"{r.fit.corrections[n]:+.6g}" if n in r.fit.corrections else "-"
                for r in self.sides.values()) + " |")
        if self.mirrored:
            rows += ["", "left-hand pair: the corrections of its right-hand twin; the "
                     "written settings mirrored (cradle angle, swivel, blank offset, 2C, "
                     "V_1 change sign)"]
        return "\n".join(rows)

    def points_csv(self) -> str:
        """The residual at each measured point as CSV (the columns of
        :meth:`~.easeoff_settings.EaseOffSettings.points_csv`)."""
        rows = [RESIDUAL_COLUMNS]
        for r in self.sides.values():
            rows += residual_rows(r.points, r.residual_um)
        return "\n".join(rows) + "\n"


def machine_seeds(pair, member: str) -> dict:
    """``{side: MachineSetup}`` of ``pair``'s ``[machine.<member>.*]`` tables (``{}``
    without them)."""
    return {s.side: s for s in pair.machine if s.member == member}


def gear_seeds(pair, gear_generation: str) -> dict:
    """``{side: MachineSetup}`` of the nominal gear of ``pair``: its ``[machine.gear.*]``
    tables, else the gear of its default flanks (``gear_generation`` ``"formate"`` or
    ``"generated"``, :func:`~.basic_settings.member_setups`; a left-hand pair's: its
    twin's mirrored, :func:`~.machine.mirror_setup`)."""
    own = machine_seeds(pair, "gear")
    if own:
        return own
    default = member_setups(pair, gear_generation)[0]     # the right-hand twin's
    if pair.pinion_hand == "left":
        return {side: mirror_setup(s) for side, s in default.items()}
    return default


def gear_correction(pair, measured: dict, *, seeds: dict, parameters=None,
                    objective: str = "rms", where: str = "target flank") -> GearCorrection:
    """:func:`measured_correction` of the gear (``member="gear"``)."""
    return measured_correction(pair, measured, member="gear", seeds=seeds,
                               parameters=parameters, objective=objective, where=where)


def measured_correction(pair, measured: dict, *, member: str, seeds: dict, parameters=None,
                        objective: str = "rms", where: str = "target flank"
                        ) -> GearCorrection:
    """:func:`measured_corrections` of one member: ``{member: measured}`` from
    ``{member: seeds}``."""
    return measured_corrections(pair, {member: measured}, seeds={member: seeds},
                                parameters=parameters, objective=objective,
                                where=where)[member]


def measured_corrections(pair, measured: dict, *, seeds: dict, parameters=None,
                         objective: str = "rms", where: str = "target flank") -> dict:
    """Correct each member's settings ``seeds[member]`` to its measured flanks
    ``measured[member]``; every measured flank of every member is checked before any
    fit.

    Parameters
    ----------
    pair : GearPair
        A bevel pair (its blank and face widths); a left-hand pair is fitted on its
        right-hand twin (the measured L, R and normal deviations of a mirror image are
        the same, docs/export.md) and its settings mirrored back; the reported
        corrections are the twin's.
    measured : dict
        ``{member: {side: MeasuredFlank}}`` (member ``"gear"`` or ``"pinion"``; its rows
        of :func:`~.measuring_grid.read_member_targets`): deviations against the flank
        ``seeds[member][side]`` cuts.
    seeds : dict
        ``{member: {side: MachineSetup}}`` of the nominal members (the gear's:
        :func:`gear_seeds`; a pair's own tables: :func:`machine_seeds`), in the pair's
        own hand; a relieved blade keeps its relief (module docstring).
    parameters : tuple of str, optional
        The fitted subset (default by member and cutting method,
        :func:`~.setting_fit.default_parameters`).
    objective : str
        ``"rms"`` or ``"minimax"``.
    where : str
        Names the measured file in messages.

    Returns
    -------
    dict
        ``{member: GearCorrection}``, its ``setups`` in the pair's own hand.

    Raises
    ------
    InputRangeError
        An unknown side or member, a measured point off the nominal flank (a relieved
        blade's: off the flank it cuts),
        fewer points than settings, settings the points cannot separate (named), a
        formate gear asked for a roll or blade-curvature correction, a relief whose
        kink reaches the blade point that cuts the member's mean point: all before any
        fit.
    """
    left = pair.pinion_hand == "left"
    if left:        # fitted on the right-hand twin (L, R and deviations are the same)
        pair = dataclasses.replace(pair, pinion_hand="right")
        seeds = {m: {side: mirror_setup(s) for side, s in own.items()}
                 for m, own in seeds.items()}
    for member, rows in measured.items():
        if member not in ("pinion", "gear"):
            raise InputRangeError("member", member, "'pinion' or 'gear'")
        for side, data in rows.items():
            if side not in SIDES or not isinstance(data, MeasuredFlank) or \
                    (data.member, data.flank) != (member, side):
                raise InputRangeError(f"{where}: {member} rows", side,
                                      f"measured {member} flanks of {SIDES}")
    problems = {}
    for member, rows in measured.items():      # every flank checked before any fit
        for side, data in rows.items():
            problems[member, side] = _problem(pair, member, seeds[member][side], data,
                                              parameters=parameters, objective=objective,
                                              where=where)
    out = {}
    for member, rows in measured.items():
        sides, setups = {}, dict(seeds[member])
        for side in rows:
            sides[side] = _side_fit(pair, member, seeds[member][side], rows[side],
                                    *problems[member, side], objective=objective)
            setups[side] = sides[side].fit.setup
        if left:
            setups = {side: mirror_setup(s) for side, s in setups.items()}
        out[member] = GearCorrection(setups=setups, sides=sides, mirrored=left, member=member)
    return out


def _problem(pair, member: str, seed, data: MeasuredFlank, *, parameters, objective: str,
             where: str):
    """The checked point problem of one measured flank (:func:`measured_corrections`):
    ``(problem, points, relative singular value, seconds, nominal flank, (u, v))``."""
    names = checked_options(seed, parameters, tolerance_um=1e-6, objective=objective)
    at = f"{where}: {member} {data.flank}"
    check_point_count({data.flank: data}, names, where=where, member=member)
    nominal = machine_flank(seed, pair.blank, face_width_mm=_face_width_mm(pair, member))
    uv = flank_parameters_at(nominal, member=member, L_mm=data.L_mm, R_mm=data.R_mm,
                             where=at, lines=data.line)
    points = measured_points(data, nominal, where=at, uv=uv,
                             cone=member_cone(member, pair.blank))
    started = time.perf_counter()
    prob = PointProblem(seed, pair.blank, points, names)
    try:
        rel = check_observable(prob.jacobian(np.zeros(len(names))), names, where=at)
    except InputRangeError as exc:     # on a CMM grid: the settings, not the points
        raise InputRangeError(f"{at}: settings", exc.value, "settings a flank "
                              f"measurement separates (relative singular value >= "
                              f"{RANK_TOLERANCE:g}): drop one of those named (a formate "
                              "gear's sliding base is its cutter radius; "
                              "docs/machine_settings.md sec. 6, \"Gear flanks\"), or "
                              "points spread over the flank") from None
    return prob, points, rel, time.perf_counter() - started, nominal, uv


def _face_width_mm(pair, member: str) -> float:
    return getattr(pair, f"{member}_face_width_mm")


def _side_fit(pair, member: str, seed, data: MeasuredFlank, prob, points, rel, took,
              nominal, uv, *, objective: str) -> GearSideFit:
    """The fit of one checked flank (:func:`_problem`) and its residuals and kinks."""
    fit = solve_fit(prob, tolerance_um=1e-6, objective=objective,
                    started=time.perf_counter() - took)
    x = np.array([fit.corrections[n] for n in prob.names]) / prob.scale
    res = prob.deviation_um(x)
    over = (_flank_residual_um(fit.setup, pair.blank, data, nominal, uv,
                               member_cone(member, pair.blank))
            if is_complete_grid(*uv) and not seed.blade.relieved else np.array([math.nan]))
    kinks, box = (), None
    if seed.blade.relieved:     # the kink lines of the cut flank
        cut = machine_flank(fit.setup, pair.blank, face_width_mm=_face_width_mm(pair, member))
        kinks = tuple(KinkPosition(k.name, k.v_nodes, k.u_nodes) for k in cut.kinks)
        box = cut.boundary
    return GearSideFit(side=data.flank, fit=fit, points=points,
                       deviation_max_um=float(np.abs(points.deviation_um).max()),
                       residual_um=res, relative_singular_value=rel,
                       flank_max_um=float(np.abs(over).max()),
                       flank_rms_um=float(np.sqrt(np.mean(over ** 2))), kinks=kinks, box=box)


def _flank_residual_um(setup, blank, data: MeasuredFlank, nominal, uv, cone, *,
                       n_u: int = 60, n_v: int = 75) -> np.ndarray:
    """The flank ``setup`` cuts against the measured flank over the grid's box (module
    docstring): the deviations' bicubic over the nominal (u, v) on n_u x n_v points,
    each moved off the nominal by it, the cut flank's normal distance there, um."""
    u, v, table = grid_values(*uv, data.deviation_um)
    dev = GridEaseOff(u_mm=u, v_mm=v, relief_um=table)
    U, V = (a.ravel() for a in np.meshgrid(np.linspace(u[0], u[-1], n_u),
                                           np.linspace(v[0], v[-1], n_v), indexing="ij"))
    dense = dataclasses.replace(data, L_mm=np.zeros(len(U)), R_mm=np.zeros(len(U)),
                                deviation_um=1e3 * dev.relief_mm(U, V),
                                line=np.zeros(len(U), dtype=int))
    points = measured_points(dense, nominal, where="", uv=(U, V), cone=cone)
    return PointProblem(setup, blank, points, ("blade_angle_deg",)).deviation_um(np.zeros(1))


def corrected_pair(pair, correction: GearCorrection):
    """``pair`` (with machine tables) with its set-ups of ``correction.member`` replaced
    by the corrected."""
    return dataclasses.replace(pair, machine=tuple(
        correction.setups[s.side] if s.member == correction.member else s
        for s in pair.machine))

