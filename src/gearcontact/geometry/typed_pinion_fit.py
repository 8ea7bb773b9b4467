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
:func:`~.gear_generation.generating_sheet`), and the residual is measured over the flank,
as a normal deviation ``d`` (um) and as the angle ``dpsi = d / lever`` about the pinion
axis (:func:`~.member_envelope.angle_lever`). To first order the fitted pinion touches
the gear at each phase where ``dpsi`` is largest along the conjugate's contact line, so

    TE0 p-p <= (z1 / z2) (max dpsi - min dpsi)

(gear angle, as TE0 is defined: docs/geometry.md), the bound each fit reports
(:attr:`ConjugateFit.te_bound_arcsec`). A fit whose residual exceeds
:data:`RESIDUAL_BOUND_UM` is not a conjugate pinion: :func:`conjugate_fitted_setups`
refuses it. Every other typed gear keeps its derived pinion untouched
(:func:`needs_conjugate_fit`).

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 20.2
(three-surface tangency), ch. 21 (machine-tool settings, modified roll).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

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
from .setting_fit import (DEFAULT_PARAMETERS, FitProblem, SettingFit, fit_pinion_setup,
                          flank_deviation_um)

__all__ = ["CONJUGATE_GRID", "RESIDUAL_BOUND_UM", "ConjugateFit", "conjugate_fitted_setups",
           "conjugate_target", "fit_to_conjugate", "needs_conjugate_fit", "residual_angles",
           "spline_error_rad"]

#: Exact meshing nodes of the conjugate target (profile x lengthwise), a quintic sheet
#: between them (its error against exact nodes at the cell centres is part of each fit's
#: report, :attr:`ConjugateFit.spline_error_rad`).
CONJUGATE_GRID = (30, 40)
#: The largest residual |d| over the flank, um, of a pinion called conjugate: the bound B
#: of the hollow ease-off warning (:data:`~.easeoff_shape.HOLLOW_BOUND_UM`: below it no
#: edge contact worth a warning), declared before measuring (docs sec. 5).
RESIDUAL_BOUND_UM = HOLLOW_BOUND_UM
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
        (their common box, 60 x 75 nodes), um.
    dpsi_min_rad, dpsi_max_rad : float
        The residual as an angle about the pinion axis, ``d / lever``, its extremes, rad.
    spline_error_rad : float
        Largest |psi| of the conjugate's sheet against exact meshing nodes at the cell
        centres of its node grid, rad.
    te_bound_arcsec : float
        ``(z1/z2) (dpsi_max - dpsi_min + 2 spline_error)`` (gear arcsec): the first-order
        bound of the uncrowned pair's TE0 p-p (module docstring).
    seed_max_um : float
        The derived (reversed-motion) pinion's largest |normal deviation| on the fit grid,
        um (over the part of the conjugate's box it covers, if ``seed_trimmed``).
    seed_trimmed : bool
        The derived pinion's envelope does not reach the whole of the conjugate's box: the
        fit started over the part it covers (:func:`fit_to_conjugate`); ``fit`` is the
        second stage, from that fit's set-up.
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

    @property
    def within_bound(self) -> bool:
        """The residual within :data:`RESIDUAL_BOUND_UM`."""
        return self.max_um <= RESIDUAL_BOUND_UM

    def line(self) -> str:
        """One line: the residual, the TE0 bound and the derived pinion's deviation."""
        return (f"{self.side}: pinion fitted to the typed gear's conjugate pinion: residual "
                f"max {self.max_um:.3f} um, RMS {self.rms_um:.3f} um over the flank (bound "
                f"{RESIDUAL_BOUND_UM:g} um); TE0 p-p bound {self.te_bound_arcsec:.3f} arcsec "
                f"(uncrowned, first order); the reversed-motion pinion was "
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


def fit_to_conjugate(pair, gear: MachineSetup, seed: MachineSetup) -> ConjugateFit:
    """The pinion flank ``seed`` (the derived pinion of the typed gear flank ``gear``,
    right-hand ``pair``) fitted to the gear's conjugate pinion (module docstring). Where
    the seed's envelope does not reach the whole of the conjugate's box (a large modified
    roll), it is first fitted over the part its own active box covers
    (:func:`~.generated.generated_pinion_box`), then from there over the whole box
    (``seed_trimmed``).

    Raises
    ------
    UndercutError
        The seed's envelope or the fitted one does not reach the fit grid.
    """
    target = conjugate_target(pair, gear)
    box, start = target.boundary, seed
    try:
        seed_dev = _grid_deviation_um(seed, pair, target, box)
    except UndercutError:       # the derived pinion short of the conjugate's box
        own = generated_pinion_box(seed, pair.blank,
                                   pinion_face_width_mm=pair.pinion_face_width_mm)[1]
        box = dataclasses.replace(box, u_root=max(box.u_root, own.u_root),
                                  u_tip=min(box.u_tip, own.u_tip),
                                  v_toe=max(box.v_toe, own.v_toe),
                                  v_heel=min(box.v_heel, own.v_heel))
        seed_dev = _grid_deviation_um(seed, pair, target, box)
        start = fit_pinion_setup(seed, pair.blank, target, parameters=DEFAULT_PARAMETERS,
                                 box=box).setup
    fit = fit_pinion_setup(start, pair.blank, target, parameters=DEFAULT_PARAMETERS)
    cut = machine_flank(fit.setup, pair.blank, face_width_mm=pair.pinion_face_width_mm)
    _, _, d, dpsi = residual_angles(cut, target)
    spline = spline_error_rad(target)
    ratio = pair.pinion_teeth / pair.gear_teeth
    return ConjugateFit(
        side=gear.side, fit=fit, max_um=float(np.abs(d).max()),
        rms_um=float(np.sqrt(np.mean(d ** 2))), dpsi_min_rad=float(dpsi.min()),
        dpsi_max_rad=float(dpsi.max()), spline_error_rad=spline,
        te_bound_arcsec=ratio * (float(dpsi.max() - dpsi.min()) + 2.0 * spline) * _ARCSEC,
        seed_max_um=float(np.abs(seed_dev).max()), seed_trimmed=start is not seed)


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
