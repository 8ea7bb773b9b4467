"""The pinion of a typed spiral bevel gear cut with modified roll or helical motion, fitted
to the gear's conjugate pinion (docs/machine_settings.md sec. 5, "A typed spiral bevel
gear with modified roll: the pinion fitted to its conjugate").

The pinion :mod:`.typed_pinion` derives (the gear's generating surface in the gear's
motion reversed) is conjugate to the gear where the surface's contact lines with the
two cross. With intersecting axes (offset 0) and a generated gear whose roll is not
linear (a modified roll or a helical motion), they cross only where the surface's normal
lies in the plane of the axes, off the face: that pinion is not conjugate
(docs/machine_settings.md sec. 5, measured). For such a flank the
pinion settings are fitted (:func:`~.setting_fit.fit_pinion_setup`, the default subset)
from the derived pinion to the gear's numerically conjugate pinion
(:func:`~.conjugate.conjugate_pinion_flank` of the gear flank's generating sheet,
:func:`~.gear_generation.generating_sheet`) at its exact meshing nodes
(:class:`ExactConjugate`: the fit's target and the residual's reference, not the
conjugate's quintic sheet), and the residual is measured over the flank,
as a normal deviation ``d`` (um) and as the angle ``dpsi = d / lever`` about the pinion
axis (:func:`~.member_envelope.angle_lever`). A side still above
:data:`RESIDUAL_BOUND_UM` is fitted again (:data:`REFIT_STAGES`: every setting, then the
minimax objective), the lowest residual kept. The TE0 bound each fit reports
(:attr:`ConjugateFit.te_bound_arcsec`, :func:`contact_line_bound_arcsec`): with ``m``
the fitted pinion's angle off the exact conjugate (material positive, exact nodes of
both), a pair's advance at gear phase ``phi`` is at least ``m`` at every point of the
conjugate's contact line ``L(phi)`` whose gear point lies on the gear's active flank,
and at most the largest ``m`` over the flank; the mesh carries the pair of largest
advance, so

    TE0 p-p <= (z1 / z2) (max m - min_phi max_k max_{L(phi + k tau2)} m)

(gear angle, as TE0 is defined: docs/geometry.md; ``tau2 = 2 pi / z2``; the derivation:
docs/machine_settings.md sec. 5, "The bound on the contact lines, and more freedoms for a
refused fit"). A fit whose
residual exceeds :data:`RESIDUAL_BOUND_UM` is not a conjugate pinion:
:func:`conjugate_fitted_setups` refuses it. Every other typed gear keeps its derived
pinion untouched (:func:`needs_conjugate_fit`).

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 20.2
(three-surface tangency), ch. 21 (machine-tool settings, modified roll).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np

from ..errors import CheckFailed
from .conjugate import ConjugateFlank, UndercutError, conjugate_pinion_flank
from .easeoff_shape import HOLLOW_BOUND_UM
from .formate import SIDES
from .gear_generation import SheetGenerator, generating_sheet
from .generated import generated_pinion_box
from .kinked import machine_flank
from .machine import MachineSetup
from .member_envelope import angle_lever
from .setting_fit import (DEFAULT_PARAMETERS, PARAMETERS, FitProblem, SettingFit,
                          fit_pinion_setup, flank_deviation_um)

__all__ = ["BOUND_PHASES", "CONJUGATE_GRID", "REFIT_STAGES", "RESIDUAL_BOUND_UM",
           "ConjugateFit", "ExactConjugate", "conjugate_fitted_setups", "conjugate_target",
           "contact_line_bound_arcsec", "fit_to_conjugate", "line_envelope_min",
           "needs_conjugate_fit", "residual_angles", "spline_error_rad"]

#: Exact meshing nodes of the conjugate target (profile x lengthwise), a quintic sheet
#: between them (its error against exact nodes at the cell centres is part of each fit's
#: report, :attr:`ConjugateFit.spline_error_rad`).
CONJUGATE_GRID = (30, 40)
#: The largest residual |d| over the flank, um, of a pinion called conjugate: the bound B
#: of the hollow ease-off warning (:data:`~.easeoff_shape.HOLLOW_BOUND_UM`: below it no
#: edge contact worth a warning), declared before measuring (docs sec. 5).
RESIDUAL_BOUND_UM = HOLLOW_BOUND_UM
#: The fits after the default one, for a side still above :data:`RESIDUAL_BOUND_UM`
#: (stage 2, 3: ``fit_pinion_setup`` options, each from the previous stage's set-up):
#: every setting and blade parameter the fit knows, least squares, then minimax
#: (docs sec. 5, declared before measuring).
REFIT_STAGES = (dict(parameters=tuple(PARAMETERS)),
                dict(parameters=tuple(PARAMETERS), objective="minimax"))
#: Gear phases per pitch sampled by :func:`contact_line_bound_arcsec`.
BOUND_PHASES = 2000
_ARCSEC = 180.0 * 3600.0 / math.pi


@dataclass(frozen=True)
class ConjugateFit:
    """The pinion of one typed gear flank fitted to the gear's conjugate pinion.

    Attributes
    ----------
    side : str
    fit : SettingFit
        The fit from the derived pinion (:func:`~.setting_fit.fit_pinion_setup`).
    max_um, rms_um : float
        Largest |normal deviation| and RMS over the full cut flank against the conjugate
        at exact meshing nodes (:class:`ExactConjugate`; their common box, 60 x 75
        nodes), um.
    dpsi_min_rad, dpsi_max_rad : float
        The residual as an angle about the pinion axis, ``d / lever``, its extremes, rad.
    spline_error_rad : float
        Largest |psi| of the conjugate's sheet against exact meshing nodes at the cell
        centres of its node grid, rad.
    te_bound_arcsec : float
        The bound of the uncrowned pair's TE0 p-p on the contact lines (gear arcsec,
        :func:`contact_line_bound_arcsec`; module docstring).
    seed_max_um : float
        The derived (reversed-motion) pinion's largest |normal deviation| on the fit grid,
        um (over the part of the conjugate's box it covers, if ``seed_trimmed``).
    seed_trimmed : bool
        The derived pinion's envelope does not reach the whole of the conjugate's box: the
        fit started over the part it covers (:func:`fit_to_conjugate`); ``fit`` is the
        second stage, from that fit's set-up.
    te_bound_flank_arcsec : float
        The flank-wide first-order bound ``(z1/z2) (dpsi_max - dpsi_min + 2
        spline_error)``, gear arcsec (session 26's).
    stage : int
        The fit kept: 1 the default parameters, 2 and 3 :data:`REFIT_STAGES`.
    """

    side: str
    fit: SettingFit
    max_um: float
    rms_um: float
    dpsi_min_rad: float
    dpsi_max_rad: float
    spline_error_rad: float
    te_bound_arcsec: float
    seed_max_um: float
    seed_trimmed: bool = False
    te_bound_flank_arcsec: float = math.inf
    stage: int = 1

    @property
    def within_bound(self) -> bool:
        """The residual within :data:`RESIDUAL_BOUND_UM`."""
        return self.max_um <= RESIDUAL_BOUND_UM

    def line(self) -> str:
        """One line: the residual, the TE0 bound and the derived pinion's deviation."""
        return (f"{self.side}: pinion fitted to the typed gear's conjugate pinion: residual "
                f"max {self.max_um:.3f} um, RMS {self.rms_um:.3f} um over the flank (bound "
                f"{RESIDUAL_BOUND_UM:g} um"
                + ("" if self.stage == 1 else f"; every setting fitted, stage {self.stage}")
                + f"); TE0 p-p bound (uncrowned, first order) {self.te_bound_arcsec:.3f} "
                f"arcsec on the contact lines while contact stays within the conjugate's "
                f"box, {self.te_bound_flank_arcsec:.3f} arcsec flank-wide; the reversed-motion "
                f"pinion was "
                f"{self.seed_max_um:.2f} um off"
                + (" where it reached the conjugate's flank" if self.seed_trimmed else ""))


def needs_conjugate_fit(pair, setup: MachineSetup) -> bool:
    """Whether the typed gear flank ``setup`` of ``pair`` gets its pinion fitted to its
    conjugate: intersecting axes (offset 0) and a generated gear with a non-zero modified
    roll or helical motion term (module docstring); a hypoid's derived pinion is
    conjugate, a formate gear's modified roll moves nothing."""
    st = setup.settings
    return (pair.offset_mm == 0.0 and not st.formate
            and any(x != 0.0 for x in (*st.modified_roll, *st.helical_motion)))


def conjugate_target(pair, setup: MachineSetup, *, n_u: int = CONJUGATE_GRID[0],
                     n_v: int = CONJUGATE_GRID[1]) -> ConjugateFlank:
    """The pinion flank conjugate to the generated gear flank ``setup`` cuts (right-hand
    ``pair``): :func:`~.conjugate.conjugate_pinion_flank` of its generating sheet."""
    gen = SheetGenerator(generating_sheet(setup, pair.blank,
                                          gear_face_width_mm=pair.gear_face_width_mm))
    return conjugate_pinion_flank(gen, blank=pair.blank,
                                  kinematics=pair.kinematics(with_errors=False),
                                  pinion_face_width_mm=pair.pinion_face_width_mm,
                                  n_u=n_u, n_v=n_v)[0]


def residual_angles(flank, target) -> tuple[np.ndarray, ...]:
    """``(u, v, d_um, dpsi_rad)`` of the pinion sheet ``flank`` against ``target``
    (:func:`~.setting_fit.flank_deviation_um`, 60 x 75 over their common box) and the
    deviation as an angle about the pinion axis, ``d / lever``."""
    u, v, d = flank_deviation_um(flank, target)
    t = target.evaluate(u, v, second=False)
    return u, v, d, d / angle_lever("pinion", t.r, t.n)[1]


@dataclass(frozen=True, eq=False)
class ExactConjugate:
    """The conjugate pinion flank ``flank`` at exact meshing nodes: the fit's target and
    the residual's reference (docs/machine_settings.md sec. 5, "Why V_1 = 3 was
    refused"). ``boundary`` is the flank's box; :meth:`evaluate` solves the node
    equations at each (u, v) (:meth:`~.conjugate.ConjugateFlank.exact`), with no quintic
    sheet between nodes (its error reached 5 um at a corner)."""

    flank: ConjugateFlank

    @property
    def boundary(self):
        return self.flank.boundary

    def evaluate(self, u, v, *, second: bool = False) -> SimpleNamespace:
        """Point ``r`` (mm) and unit outward normal ``n`` of the exact conjugate at
        pinion sheet parameters (u, v) (``second`` is accepted for the sheet's
        signature; no second derivatives)."""
        s = self.flank.exact(u, v)
        return SimpleNamespace(r=s.x1_mm, n=s.n1)


def spline_error_rad(target: ConjugateFlank) -> float:
    """Largest |psi_sheet - psi_exact|, rad, of ``target``'s quintic sheet against exact
    meshing nodes at the centres of its node grid's cells."""
    uc, vc = (0.5 * (a[1:] + a[:-1]) for a in (target.u_nodes, target.v_nodes))
    U, V = np.meshgrid(uc, vc, indexing="ij")
    d = target.exact(U, V).psi_rad - target.psi(U, V)
    return float(np.abs((d + math.pi) % (2.0 * math.pi) - math.pi).max())


def _grid_deviation_um(setup: MachineSetup, pair, target, box) -> np.ndarray:
    """Normal deviation (um) of the flank ``setup`` cuts from ``target`` on the fit's 9 x 11
    grid over ``box`` (:class:`~.setting_fit.FitProblem` with no parameter)."""
    return FitProblem(setup, pair.blank, target, (), np.linspace(box.u_root, box.u_tip, 9),
                      np.linspace(box.v_toe, box.v_heel, 11)).deviation_um(np.zeros(0))


def _edge_lines(phi, m, ok):
    """``(lo, hi, phi_a, m_a, slope)`` of every grid edge (along either index) whose two
    nodes are ``ok``: the phase interval it spans and ``m`` linear in the phase on it."""
    parts = []
    for a, b in ((np.s_[:-1, :], np.s_[1:, :]), (np.s_[:, :-1], np.s_[:, 1:])):
        keep = ok[a] & ok[b] & (phi[a] != phi[b])
        pa, pb, ma, mb = phi[a][keep], phi[b][keep], m[a][keep], m[b][keep]
        parts.append((np.minimum(pa, pb), np.maximum(pa, pb), pa, ma, (mb - ma) / (pb - pa)))
    return tuple(np.concatenate(x) for x in zip(*parts))


def line_envelope_min(phi, m, ok, *, pitch_rad: float, phases: int = BOUND_PHASES) -> float:
    """``min_phi max_k M(phi + k pitch_rad)`` over one pitch, ``M(phi)`` the largest ``m``
    on the level line ``phi`` of the node grid's ``phi`` through nodes ``ok`` (linear on
    each edge whose two nodes are ``ok``; ``phases`` samples per pitch); ``-inf`` where
    some phase of the pitch meets no line (module docstring)."""
    lo, hi, pa, ma, slope = _edge_lines(np.asarray(phi, float), np.asarray(m, float),
                                        np.asarray(ok, bool))
    if lo.size == 0:
        return -math.inf
    step = pitch_rad / phases
    start = float(lo.min())
    first = np.ceil((lo - start) / step).astype(int)
    count = np.maximum(np.floor((hi - start) / step).astype(int) - first + 1, 0)
    edge = np.repeat(np.arange(lo.size), count)
    k = np.repeat(first, count) + (np.arange(count.sum()) - np.repeat(np.cumsum(count) - count,
                                                                       count))
    envelope = np.full(-(-(int(k.max()) + 1) // phases) * phases, -np.inf)
    np.maximum.at(envelope, k, ma[edge] + slope[edge] * (start + k * step - pa[edge]))
    return float(envelope.reshape(-1, phases).max(axis=0).min())


def _exact_m(pair, setup: MachineSetup, target, us, vs):
    """``(m, exact)``: the angle (rad, material positive) of the flank ``setup`` cuts off
    ``target``'s exact meshing nodes on the grid ``us x vs``, and those nodes
    (:class:`~.conjugate.MeshingSolution`)."""
    U, V = np.meshgrid(us, vs, indexing="ij")
    exact = target.exact(U, V)
    nodes = SimpleNamespace(boundary=target.boundary, evaluate=lambda *a, **k: SimpleNamespace(
        r=exact.x1_mm, n=exact.n1))
    prob = FitProblem(setup, pair.blank, nodes, (), us, vs)
    return prob.deviation_um(np.zeros(0)).reshape(U.shape) / np.abs(prob.lever_um), exact


def contact_line_bound_arcsec(pair, setup: MachineSetup, target, cut) -> float:
    """The bound of the uncrowned pair's TE0 p-p (gear arcsec) of the pinion flank
    ``setup`` (``cut``, the flank it cuts) against the gear's conjugate ``target``
    (right-hand ``pair``; module docstring, docs sec. 5): ``m`` the flank's angle off
    the exact conjugate (both at exact nodes: the cut envelope's and
    :meth:`~.conjugate.ConjugateFlank.exact`; material positive) on
    :func:`residual_angles`' grid (their common box); the upper term its largest value,
    the lower term :func:`line_envelope_min` over the nodes whose gear point lies in the
    gear flank's active box; ``inf`` where a phase of the pitch meets no contact line
    there. A bound while the pair touches within the common box: a pinion flank reaching
    past the conjugate's box can be touched there by a gear edge, beyond its reach (docs
    sec. 5, measured)."""
    u, v = residual_angles(cut, target)[:2]
    us, vs = u[:, 0], v[0]
    m, exact = _exact_m(pair, setup, target, us, vs)
    gear = target.solver.gear
    u2, v2 = gear.surface_parameters(exact.h_mm, exact.theta_rad)
    g = gear.boundary
    on_gear = (u2 >= g.u_root) & (u2 <= g.u_tip) & (v2 >= g.v_toe) & (v2 <= g.v_heel)
    lower = line_envelope_min(exact.phi2_rad, m, on_gear,
                              pitch_rad=2.0 * math.pi / pair.gear_teeth)
    return pair.pinion_teeth / pair.gear_teeth * (float(m.max()) - lower) * _ARCSEC


def _measured(pair, setup: MachineSetup, target):
    """``(cut, d_um, dpsi_rad)``: the flank the pinion ``setup`` cuts and its residual
    against ``target`` (:func:`residual_angles`; the fit passes :class:`ExactConjugate`)."""
    cut = machine_flank(setup, pair.blank, face_width_mm=pair.pinion_face_width_mm)
    return (cut, *residual_angles(cut, target)[2:])


def fit_to_conjugate(pair, gear: MachineSetup, seed: MachineSetup) -> ConjugateFit:
    """The pinion flank ``seed`` (the derived pinion of the typed gear flank ``gear``,
    right-hand ``pair``) fitted to the gear's conjugate pinion (module docstring). Where
    the seed's envelope does not reach the whole of the conjugate's box (a large modified
    roll), it is first fitted over the part its own active box covers
    (:func:`~.generated.generated_pinion_box`), then from there over the whole box
    (``seed_trimmed``). A fit above :data:`RESIDUAL_BOUND_UM` continues through
    :data:`REFIT_STAGES` while it stays above, the lowest residual kept (``stage``; a
    stage that moves no setting is the same pinion, not kept).

    Raises
    ------
    UndercutError
        The seed's envelope or the fitted one does not reach the fit grid.
    """
    target = conjugate_target(pair, gear)
    exact = ExactConjugate(target)     # fit and residual at exact nodes (docs sec. 5)
    box, start = target.boundary, seed
    try:
        seed_dev = _grid_deviation_um(seed, pair, exact, box)
    except UndercutError:       # the derived pinion short of the conjugate's box
        own = generated_pinion_box(seed, pair.blank,
                                   pinion_face_width_mm=pair.pinion_face_width_mm)[1]
        box = dataclasses.replace(box, u_root=max(box.u_root, own.u_root),
                                  u_tip=min(box.u_tip, own.u_tip),
                                  v_toe=max(box.v_toe, own.v_toe),
                                  v_heel=min(box.v_heel, own.v_heel))
        seed_dev = _grid_deviation_um(seed, pair, exact, box)
        start = fit_pinion_setup(seed, pair.blank, exact, parameters=DEFAULT_PARAMETERS,
                                 box=box).setup
    fit = fit_pinion_setup(start, pair.blank, exact, parameters=DEFAULT_PARAMETERS)
    best, stage = (fit, *_measured(pair, fit.setup, exact)), 1
    for k, options in enumerate(REFIT_STAGES, start=2):
        if np.abs(best[2]).max() <= RESIDUAL_BOUND_UM:
            break
        fit = fit_pinion_setup(fit.setup, pair.blank, exact, **options)
        if not any(fit.corrections.values()):      # no setting moved: the same pinion
            continue
        trial = (fit, *_measured(pair, fit.setup, exact))
        if np.abs(trial[2]).max() < np.abs(best[2]).max():
            best, stage = trial, k
    fit, cut, d, dpsi = best
    spline = spline_error_rad(target)
    ratio = pair.pinion_teeth / pair.gear_teeth
    return ConjugateFit(
        side=gear.side, fit=fit, max_um=float(np.abs(d).max()),
        rms_um=float(np.sqrt(np.mean(d ** 2))), dpsi_min_rad=float(dpsi.min()),
        dpsi_max_rad=float(dpsi.max()), spline_error_rad=spline,
        te_bound_arcsec=contact_line_bound_arcsec(pair, fit.setup, target, cut),
        seed_max_um=float(np.abs(seed_dev).max()), seed_trimmed=start is not seed,
        te_bound_flank_arcsec=ratio * (float(dpsi.max() - dpsi.min()) + 2.0 * spline)
        * _ARCSEC, stage=stage)


def conjugate_fitted_setups(pair, gear: dict, pinion: dict) -> tuple[dict, dict]:
    """``(pinion, fits)``: the derived pinion ``pinion`` (``{side: MachineSetup}``,
    uncrowned, right-hand ``pair``) with each flank whose typed gear flank ``gear[side]``
    :func:`needs_conjugate_fit` replaced by its fit to the gear's conjugate, and
    ``{side: ConjugateFit}`` of those flanks (the others untouched, not in ``fits``).

    Raises
    ------
    CheckFailed
        A fitted flank whose residual exceeds :data:`RESIDUAL_BOUND_UM` (named with its
        residual and bound): no cuttable pinion conjugate to the gear within the bound.
    """
    fits = {side: fit_to_conjugate(pair, gear[side], pinion[side]) for side in SIDES
            if needs_conjugate_fit(pair, gear[side])}
    bad = [f for f in fits.values() if not f.within_bound]
    if bad:
        raise CheckFailed(
            "pinion of the typed gear: no cuttable pinion conjugate to the gear within "
            f"{RESIDUAL_BOUND_UM:g} um: " + "; ".join(f.line() for f in bad)
            + " (docs/machine_settings.md sec. 5)")
    return {side: fits[side].fit.setup if side in fits else p
            for side, p in pinion.items()}, fits
