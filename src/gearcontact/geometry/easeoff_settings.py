"""The machine settings that cut a pair's pinion ease-off (issue 27 item 4, the command
``design --machine-settings`` on a pair with an ease-off or a ``--target-flank``).

The gear keeps the flanks of the pair's default; each pinion flank's settings are
fitted to its target by :mod:`.setting_fit` (a target flank: the pair's ease-off, or a
measured grid) or :mod:`.point_fit` (scattered measured points), and the residual is
measured over the flank (or at the points). Blades with a Toprem / Flankrem keep their
relief (a fixed blade property, :func:`~.relief_setup.relieved_setup`): the fitted
pinion flank is then a :class:`~.kinked.KinkedFlank`, its residual measured over all
its pieces, its kink lines reported (:class:`KinkPosition`), and a measured grid of
such a flank is fitted at its points (no spline across the kink).
docs/machine_settings.md sec. 6.
"""

from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass

import numpy as np

from ..validation import InputRangeError
from .basic_settings import member_setups
from .easeoff import apply_easeoff
from .flank import build_flanks
from .formate import SIDES
from .generated import generated_pinion_box
from .kinked import KinkedFlank, machine_flank
from .machine import MEMBERS, mirror_setup
from .measuring_grid import RESIDUAL_COLUMNS, MeasuredPoints, residual_rows, target_grids
from .point_fit import check_point_count, point_deviation_um, point_problem
from .relief_setup import relieved_setup
from .residual_curvature import (CURVATURE_PARAMETERS, CurvedFitProblem, PathCurvature,
                                 PathResidual, path_residual, pressure_bound)
from .setting_fit import (DEFAULT_PARAMETERS, PARAMETERS, SettingFit, checked_options,
                          conjugate_seed, fit_grid, fit_pinion_setup, flank_deviation_um,
                          solve_fit)
from .settings_top_land import check_settings_top_land, member_box

__all__ = ["EaseOffSettings", "KinkPosition", "SideResidual", "easeoff_machine_pair"]

#: Slack of the relieved flank's box for measured points, mm (1 um, as the measured
#: points' check against the blank, :mod:`.measuring_grid`).
_ON_BOX_MM = 1e-3


@dataclass(frozen=True)
class KinkPosition:
    """A kink line of a cut relieved flank (:class:`~.kinked.KinkLine`; a pinion's, or a
    gear's of :mod:`.gear_correction`).

    Attributes
    ----------
    name : str
        ``"toprem"`` or ``"flankrem"``.
    v_mm, u_mm : ndarray
        The kink ``u = u_k(v)`` at lengthwise nodes over the active box, mm: a pinion's
        axial position and height over the root cone, a gear's flank parameters
        (:func:`~.kinked.machine_flank`; ``-inf`` / ``+inf`` where the kink lies below /
        above the active flank).
    """

    name: str
    v_mm: np.ndarray
    u_mm: np.ndarray

    def text(self, box) -> str:
        """Where the kink lies on the active flank ``box`` (a ``FlankBoundary``)."""
        u = self.u_mm[np.isfinite(self.u_mm)]
        where = (f"u {u.min():.3f}..{u.max():.3f} mm" if len(u) else
                 "below the active flank" if self.u_mm[0] < 0 else "above the active flank")
        part = "" if len(u) in (0, len(self.u_mm)) else (
            f" (on the flank at {len(u)} of {len(self.u_mm)} lengthwise nodes)")
        return (f"{self.name} kink at {where}{part}; active flank u {box.u_root:.3f}.."
                f"{box.u_tip:.3f} mm")


class _KinkedPsi:
    """The angular coordinate ``psi(u, v)`` of a pinion :class:`~.kinked.KinkedFlank`,
    each point on its piece (for :func:`~.point_fit.point_deviation_um`)."""

    def __init__(self, flank: KinkedFlank):
        self.flank = flank

    def psi(self, u, v):
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        k, out = self.flank.piece_index(u, v), np.empty(u.shape)
        for i, piece in enumerate(self.flank.pieces):    # generated: v_scales all 1
            out[k == i] = piece.psi(u[k == i], v[k == i])
        return out


@dataclass(frozen=True)
class SideResidual:
    """The fit of one pinion flank and its residual over the full flank.

    Attributes
    ----------
    side : str
    fit : SettingFit
    easeoff_max_um : float
        Largest |normal distance| of the target from the conjugate pinion over the
        residual grid, um (the ease-off to cut).
    max_um, rms_um : float
        Largest |residual| and RMS residual over the full flank, um (the final
        generated sheet, 120 x 150 nodes, against the target on a 60 x 75 grid over
        their common box).
    u_mm, v_mm, residual_um : ndarray (60, 75)
        The residual map (generated minus target along the target's outward normal).
    points : MeasuredPoints or None
        A target of scattered measured points (:mod:`.point_fit`): then the ease-off
        (distance of the points from the conjugate pinion) and the residual (of the
        points from the generated sheet, :func:`~.point_fit.point_deviation_um`) are
        at the points, ``u_mm``, ``v_mm``, ``residual_um`` arrays over them (file
        order).
    kinks : tuple of KinkPosition
        The kink lines of the cut flank (a relieved blade; empty for a smooth one);
        the residual is measured over all its pieces.
    box : FlankBoundary or None
        The cut flank's active box.
    path : PathResidual or None
        The residual's curvature at the target's contact path (a ``paths`` side of
        :func:`easeoff_machine_pair`, from the residual map): the relative curvature
        error and the pressure bound it implies (:mod:`.residual_curvature`).
    curvature_fitted : bool
        Whether the fit carried the curvature rows at that path.
    """

    side: str
    fit: SettingFit
    easeoff_max_um: float
    max_um: float
    rms_um: float
    u_mm: np.ndarray
    v_mm: np.ndarray
    residual_um: np.ndarray
    points: MeasuredPoints | None = None
    kinks: tuple = ()
    box: object = None
    path: PathResidual | None = None
    curvature_fitted: bool = False


@dataclass(frozen=True)
class EaseOffSettings:
    """Machine settings that cut a pair's pinion ease-off (:func:`easeoff_machine_pair`).

    Attributes
    ----------
    pair : GearPair
        The pair with the settings of all four flanks (``[machine.*]``/``[blade.*]``):
        the formate gear of today's flanks, the fitted pinion flanks.
    sides : dict
        ``{side: SideResidual}``, right-hand frame (a left-hand pair's twin).
    measured_sides : tuple of str
        Sides whose target was a measured grid (``easeoff_grid``), not the pair's
        ``[easeoff.<side>]``.
    """

    pair: object
    sides: dict
    measured_sides: tuple = ()

    def table(self) -> str:
        """The residual and the corrections per side, as a Markdown table."""
        rows = ["| side | ease-off max (um) | residual max (um) | residual RMS (um) | "
                "fit evaluations | fit time (s) |", "|---|---:|---:|---:|---:|---:|"]
        for side, r in self.sides.items():
            rows.append(f"| {side} | {r.easeoff_max_um:.2f} | {r.max_um:.3f} | "
                        f"{r.rms_um:.3f} | {r.fit.evaluations} | {r.fit.seconds:.1f} |")
        for side, r in self.sides.items():
            for k in r.kinks:
                rows += ["", f"{side}: the relieved blade's {k.text(r.box)} (the relief "
                         "kept as given; the residual is over both sides of the kink)"]
        for side, r in self.sides.items():
            if r.points is not None:
                rows += ["", f"{side}: target {len(r.points.line)} scattered measured points "
                         "(--target-flank): ease-off and residual at the points, not over "
                         "the flank"]
        rows += ["", "| correction | unit | " + " | ".join(self.sides) + " |",
                 "|---|---|" + "---:|" * len(self.sides)]
        names = dict.fromkeys(n for r in self.sides.values() for n in r.fit.corrections)
        for n in names:     # a side that does not fit ``n`` (curvature rows elsewhere): -
            rows.append(f"| {n} | {PARAMETERS[n][0]} | " + " | ".join(
                f"{r.fit.corrections[n]:+.6g}" if n in r.fit.corrections else "-"
                for r in self.sides.values()) + " |")
        rows += ["", "reach predicted before the fit (the target's part outside the span of "
                 "the settings' sensitivities at the seed, linear) against the fit, on the "
                 "fit grid, max / RMS: " + ", ".join(
                     f"{side} {r.fit.predicted_max_um:.3f} / {r.fit.predicted_rms_um:.3f} um "
                     f"predicted, {r.fit.fit_max_um:.3f} / {r.fit.fit_rms_um:.3f} um fitted"
                     for side, r in self.sides.items())]
        for side, r in self.sides.items():
            if r.path is not None:
                rows += ["", f"{side}: the residual's curvature at the target's contact path "
                         f"({len(r.path.error)} points): relative curvature error at P0 "
                         f"{r.path.reference_error:.4f} (Hertz pressure bound +-"
                         f"{100.0 * pressure_bound(r.path.reference_error):.2f} %), max "
                         f"{r.path.max_error:.4f} (+-{100.0 * r.path.pressure_bound:.2f} %; "
                         + ("fitted with curvature rows" if r.curvature_fitted else
                            "not fitted") + ")"]
        if any(r.fit.objective == "minimax" for r in self.sides.values()):
            rows += ["", "fit objective minimax: largest deviation on the fit grid " + ", ".join(
                f"{side} {r.fit.fit_max_um:.3f} um" + (
                    "" if r.points is None else f" at its {len(r.points.line)} points")
                + f" (least squares {r.fit.rms_fit_max_um:.3f})"
                for side, r in self.sides.items())]
        return "\n".join(rows)

    def points_csv(self) -> str | None:
        """The residual at each measured point of the sides fitted to scattered points,
        as CSV (``None`` without such a side): the file's member, flank, line, L, R and
        deviation, the measured point's sheet parameters ``u_mm`` (height over the
        root cone), ``v_mm`` (axial position) and ``residual_um`` (the cut flank minus
        the measured point along the nominal normal: positive = material left)."""
        sides = [r for r in self.sides.values() if r.points is not None]
        if not sides:
            return None
        rows = [RESIDUAL_COLUMNS]
        for r in sides:
            rows += residual_rows(r.points, r.residual_um)
        return "\n".join(rows) + "\n"


def _side_fit(side, seed, target, problem, pair, conjugate, *, parameters, n_u, n_v,
              objective, box=None, path: PathCurvature | None = None,
              fit_curvature: bool = False) -> tuple[SideResidual, dict]:
    """The fit of one pinion flank to its target flank (residual over the flank; the
    fit grid over ``box``, default the target's) or to measured points (``problem``:
    residual at the points), and the cut flank's :func:`~.settings_top_land.member_box`
    (its active box, as every reader of the settings traces it: a fold at the tip
    refused, :func:`~.generated_box.check_tip_margin`; the cut flank is built on it).
    ``path``: the target's contact path, the residual's curvature reported there and,
    with ``fit_curvature``, fitted (:class:`~.residual_curvature.CurvedFitProblem`, the
    subset with :data:`~.residual_curvature.CURVATURE_PARAMETERS`)."""
    if problem is not None:
        fit = solve_fit(problem, tolerance_um=1e-6, objective=objective,
                        started=time.perf_counter() - problem.setup_seconds)
    elif path is not None and fit_curvature:
        t0 = time.perf_counter()
        names = checked_options(seed, tuple(parameters) + tuple(
            n for n in CURVATURE_PARAMETERS if n not in parameters), tolerance_um=1e-6,
            objective=objective)
        curved = CurvedFitProblem(seed, pair.blank, target, names, *fit_grid(
            target.boundary if box is None else box, n_u, n_v), path)
        fit = solve_fit(curved, tolerance_um=1e-6, objective=objective, started=t0)
    else:
        fit = fit_pinion_setup(seed, pair.blank, target, parameters=parameters, n_u=n_u,
                               n_v=n_v, objective=objective, box=box)
    # the active box as the readers trace it (a fold at the tip refused), then the cut
    # flank on it; a relieved blade's: its pieces and kink lines (kinked.machine_flank)
    got = member_box(pair, fit.setup)
    cut = machine_flank(fit.setup, pair.blank, face_width_mm=pair.pinion_face_width_mm,
                        pinion_box=got["active_box"])
    kinked = isinstance(cut, KinkedFlank)
    if problem is not None:
        u, v, res = (target.u_mm, target.v_mm,
                     point_deviation_um(_KinkedPsi(cut) if kinked else cut, target))
        eased = point_deviation_um(conjugate, target)
    else:
        u, v, res = flank_deviation_um(cut, target)
        eased = flank_deviation_um(conjugate, target)[2]
    kinks = tuple(KinkPosition(k.name, k.v_nodes, k.u_nodes) for k in cut.kinks) if kinked else ()
    on_path = None if path is None or problem is not None else path_residual(
        target, path, u, v, res)
    return SideResidual(side=side, fit=fit, easeoff_max_um=float(np.abs(eased).max()),
                        max_um=float(np.abs(res).max()), rms_um=float(np.sqrt(np.mean(res ** 2))),
                        u_mm=u, v_mm=v, residual_um=res,
                        points=target if problem is not None else None, kinks=kinks,
                        box=cut.boundary, path=on_path,
                        curvature_fitted=on_path is not None and fit_curvature), got


def _relieved_box(seed, pair, target, *, where: str):
    """The fit box of the relieved pinion ``seed`` on ``target`` (a flank: its box from
    the root line the blade's tip segment traces, :func:`~.generated.generated_pinion_box`
    of the relieved set-up, as :func:`~.kinked.machine_flank` cuts it); measured points
    (:class:`~.measuring_grid.MeasuredPoints`) outside that box are refused (they lie
    on the fillet the relief's edge round cuts, not on the flank)."""
    cut = generated_pinion_box(seed, pair.blank, pinion_face_width_mm=pair.pinion_face_width_mm)[1]
    if isinstance(target, MeasuredPoints):
        off = ((target.u_mm < cut.u_root - _ON_BOX_MM) | (target.u_mm > cut.u_tip + _ON_BOX_MM)
               | (target.v_mm < cut.v_toe - _ON_BOX_MM) | (target.v_mm > cut.v_heel + _ON_BOX_MM))
        if off.any():
            k = int(np.argmax(off))
            raise InputRangeError(
                f"{where}: pinion {target.side} points", f"{int(off.sum())} of {len(off)} off "
                f"the relieved flank (first: line {int(target.line[k])}, u = "
                f"{float(target.u_mm[k]):.4f} mm, v = {float(target.v_mm[k]):.4f} mm)",
                f"points on the flank the relieved blade cuts: u {cut.u_root:.4f}..{cut.u_tip:.4f}"
                f" mm over the root cone, v {cut.v_toe:.4f}..{cut.v_heel:.4f} mm (below it the "
                "edge round of the blade's tip segment cuts the fillet)")
        return None
    b = target.boundary
    return dataclasses.replace(b, u_root=max(b.u_root, cut.u_root), u_tip=min(b.u_tip, cut.u_tip),
                               v_toe=max(b.v_toe, cut.v_toe), v_heel=min(b.v_heel, cut.v_heel))


def easeoff_machine_pair(pair, *, easeoff_grid: dict | None = None,
                         parameters=DEFAULT_PARAMETERS, n_u: int = 9, n_v: int = 11,
                         objective: str = "rms", where: str = "target flank",
                         reliefs: dict | None = None, paths: dict | None = None,
                         fit_curvature: bool = True) -> EaseOffSettings:
    """The machine settings that cut ``pair``'s flanks with its ease-off (issue item 4).

    The gear keeps the flanks of the pair's default (formate, or generated where the
    formate gear undercuts its pinion: :func:`~.basic_settings.member_setups`); each
    pinion flank is fitted (:func:`~.setting_fit.fit_pinion_setup`) from the settings
    of the exactly conjugate pinion (complementary, or the crown gear's of a spiral
    bevel pair: zero ease-off; of a hypoid with a generated gear the crown gear's
    pinion fitted to the conjugate first, :func:`~.setting_fit.conjugate_seed`) to the
    conjugate pinion with the pair's ease-off (:func:`~.flank.build_flanks`), and its
    residual measured over the full flank (a side of scattered measured points:
    fitted and measured at the points, :mod:`.point_fit`). A left-hand pair is fitted
    on its right-hand twin and its settings mirrored (:func:`~.machine.mirror_setup`).

    Parameters
    ----------
    pair : GearPair
        A pair defined by its blank, cutter and ease-off (no ``[machine.*]`` tables).
    easeoff_grid : dict, optional
        ``{side: GridEaseOff or MeasuredFlank}`` (a measured deviation grid,
        :func:`~.measuring_grid.read_target_flank`; a ``MeasuredFlank`` is mapped onto
        the pair's pinion flank, :func:`~.measuring_grid.target_grids`): the target of
        the sides it holds instead of the pair's ``[easeoff.<side>]``; each grid must
        cover its flank's active box. Scattered measured points (not a complete grid)
        are fitted at the points (:func:`~.point_fit.point_problem`), their residual
        reported there.
    parameters : tuple of str
        The fitted subset (:data:`~.setting_fit.PARAMETERS`; default
        :data:`~.setting_fit.DEFAULT_PARAMETERS`).
    n_u, n_v : int
        The coarse fit grid.
    objective : str
        ``"rms"`` or ``"minimax"`` (:func:`~.setting_fit.fit_pinion_setup`).
    where : str
        Names the measured file in messages.
    reliefs : dict, optional
        ``{(member, side): relief}`` (:func:`~.relief_setup.blade_reliefs` of the
        set-ups the pair was cut with): the Toprem / Flankrem kept on those blades as
        given (:func:`~.relief_setup.relieved_setup`; not fitted). A relieved pinion
        flank is fitted as the deepest of its pieces (:mod:`.setting_fit`), a complete
        measured grid of it at its points (:func:`~.measuring_grid.target_grids`), and
        its residual and kink lines are reported over all its pieces.
    paths : dict, optional
        ``{side: PathCurvature}``: the target pair's contact path on that side
        (:func:`gearcontact.tca.path_curvature.target_path_curvature`); the residual's
        curvature there is reported (:attr:`SideResidual.path`) and, with
        ``fit_curvature``, kept small by the fit's curvature rows
        (:mod:`.residual_curvature`). Ignored for a side of scattered measured points.
    fit_curvature : bool
        Whether the ``paths`` sides are fitted with the curvature rows (else reported
        only).

    Returns
    -------
    EaseOffSettings

    Raises
    ------
    InputRangeError
        A pair already cut from machine settings, an unknown side in ``easeoff_grid``,
        a grid short of its flank, measured points off the flank, fewer than the
        settings or leaving them unobservable (:mod:`.point_fit`), an unknown flank in
        ``reliefs`` or a pinion relief whose kink reaches the blade point that cuts the
        mean point (all before any fit); a fitted pinion whose tooth is pointed
        anywhere along its tip line (:func:`~.settings_top_land.check_settings_top_land`,
        after both fits).
    UndercutError
        A fitted flank the envelope does not generate over its box, or folds within
        its node grid above the tip (:func:`~.generated_box.check_tip_margin`).
        Both refusals are the readers' of the written settings
        (:func:`~.generation.check_generation`), word for word: nothing that a reader
        refuses is written.
    """
    if pair.machine:
        raise InputRangeError("pair", f"{pair.name} with [machine.*] tables",
                              "a pair with an ease-off and no machine tables (its flanks "
                              "are already the machine's)")
    twin = dataclasses.replace(pair, pinion_hand="right") if pair.pinion_hand == "left" else pair
    grids = dict(easeoff_grid or {})
    for side in grids:
        if side not in SIDES:
            raise InputRangeError("easeoff_grid", side, f"one of {SIDES}")
    reliefs = dict(reliefs or {})
    for key in reliefs:
        if key not in [(m, s) for m in MEMBERS for s in SIDES]:
            raise InputRangeError("reliefs", key, f"(member, side) of {MEMBERS} x {SIDES}")
    check_point_count(grids, parameters, where=where)
    flanks = build_flanks(twin)
    # measured files in machine coordinates onto the flanks (points off them refused
    # here): a complete grid as a target relief, scattered points as points; a relieved
    # flank's grid as points (a spline through it would smooth the kink)
    grids = target_grids(grids, twin, flanks, where=where,
                         as_points=tuple(s for m, s in reliefs if m == "pinion"))
    # the gear of the default flanks and the pinion conjugate to it, the blades'
    # reliefs kept (a pinion's checked against its mean point before any fit)
    gear, seeds = (
        {side: relieved_setup(s, reliefs.get((member, side), {}), twin.blank)
         for side, s in setups.items()}
        for member, setups in zip(MEMBERS, member_setups(twin, flanks.gear_generation)))
    targets, problems, boxes = {}, {}, {}
    for side in SIDES:          # every target checked before any fit
        conj = flanks.pinion_conjugate.side(side)
        targets[side] = flanks.pinion.side(side)
        if isinstance(grids.get(side), MeasuredPoints):
            targets[side] = grids[side]
        elif side in grids:
            grids[side].check_covers(conj.boundary, where=f"target flank {side}")
            targets[side] = apply_easeoff(conj, grids[side], limit_um=flanks.easeoff_limit_um)
    for side in SIDES:          # the seeds, and the points' rank checks before the fits
        if twin.offset_mm != 0.0 and flanks.gear_generation == "generated":
            # the crown pinion fitted to the conjugate with its smooth blade, then the
            # relief put back (checked again at the fitted seed's mean point)
            relief = reliefs.get(("pinion", side), {})
            smooth = relieved_setup(seeds[side], dict.fromkeys(relief, 0.0), twin.blank)
            seeds[side] = relieved_setup(conjugate_seed(
                smooth, twin.blank, flanks.pinion_conjugate.side(side), n_u=n_u,
                n_v=n_v).setup, relief, twin.blank)
        if seeds[side].blade.relieved:      # the part of the target the cut flank holds
            boxes[side] = _relieved_box(seeds[side], twin, targets[side], where=where)
        if isinstance(targets[side], MeasuredPoints):
            problems[side] = point_problem(seeds[side], twin.blank, targets[side],
                                           parameters=parameters, objective=objective,
                                           where=where)
    sides, cut_boxes = {}, {}
    for side in SIDES:
        sides[side], cut_boxes[side] = _side_fit(
            side, seeds[side], targets[side], problems.get(side), twin,
            flanks.pinion_conjugate.side(side), parameters=parameters, n_u=n_u, n_v=n_v,
            objective=objective, box=boxes.get(side), path=(paths or {}).get(side),
            fit_curvature=fit_curvature)
    pinion = {side: r.fit.setup for side, r in sides.items()}
    setups = [gear[s] for s in SIDES] + [pinion[s] for s in SIDES]
    # the fitted pinion's top land along its tip line on the boxes traced above, as every
    # reader of the settings checks it (generation._machine_boxes): a pointed tooth is
    # refused before the settings are written (docs/machine_settings.md sec. 6, "The
    # readers' checks before writing"); the gear is the default's, as the standard
    # settings' (basic_settings.standard_setups)
    check_settings_top_land(dataclasses.replace(twin, machine=tuple(setups)), boxes=cut_boxes)
    if pair.pinion_hand == "left":
        setups = [mirror_setup(s) for s in setups]
    return EaseOffSettings(pair=dataclasses.replace(pair, machine=tuple(setups),
                                                    easeoff_tables=("drive", "coast")),
                           sides=sides, measured_sides=tuple(s for s in SIDES if s in grids))
