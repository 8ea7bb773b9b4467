"""The shape of a pinion flank's ease-off against the typed gear's conjugate pinion, and
the hollow ease-off warning (docs/machine_settings.md sec. 2, "The hollow ease-off
warning").

The ease-off of a pinion flank cut from machine settings is measured against the
pinion its own pair's gear flank generates exactly (:func:`~.conjugate.conjugate_pinion_flank`
of the gear the typed ``[machine.gear.*]`` / ``[blade.gear.*]`` tables cut): the normal
deviation, generated minus conjugate along the conjugate's outward normal (positive =
material left; :class:`~.setting_fit.FitProblem` with no parameter, the envelope of the
pinion's settings solved at the grid nodes), on a ``FIT_GRID`` grid over the
conjugate's active box, with the pinion turned about its axis so that it touches the
conjugate at the box centre (its angular position is a mounting choice, as in
:func:`~.flank.build_machine_flanks`: a turn ``dpsi`` moves the flank by
``lever dpsi`` along its normal, :func:`~.member_envelope.angle_lever`, which is not
flat and would otherwise read as crowning, up to 0.4 um per mrad). A least-squares
quadratic in the sheet's ``u`` (height) and ``v`` (axial) coordinates about the box
centre,

    d(x, y) = c0 + c1 x + c2 y + k_uu x^2 / 2 + k_uv x y + k_vv y^2 / 2,

gives the crowning at the box edges against the tangent plane at its centre, relief
positive (:class:`EaseOffShape`):

    C_p = -k_uu (h/2)^2 / 2   (profile),   C_l = -k_vv (L/2)^2 / 2   (lengthwise),
    bias = -k_uv (h/2) (L/2)  (twist: the relief at the heel-tip corner),

``h``, ``L`` the box's extents. A real pinion is crowned (its ease-off grows towards the
edges: the pinion is mismatched to localize the bearing, Litvin & Fuentes 2004, ch. 21);
a flank hollow by more than ``HOLLOW_BOUND_UM`` in profile or lengthwise touches the
gear at the edges of its active box first (edge contact), whatever setting made it so:
:class:`HollowEaseOffWarning`.
This is not a check of the modified roll's sign (a 2C of either sign may leave a
standard pinion crowned; docs, "The pinion's modified roll").

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 21
(formate hypoid gears: the mismatched pinion, local synthesis).
"""

from __future__ import annotations

import dataclasses
import time
import warnings
from dataclasses import dataclass, field

import numpy as np

from .blade import blade_segments
from .conjugate import MeshingError, UndercutError, conjugate_pinion_flank
from .flank import right_hand_twin
from .formate import SIDES
from .gear_generation import SheetGenerator, generating_sheet
from .generated import generated_pinion_box
from .kinked import machine_flank
from .machine import MachineSetup
from .member_envelope import angle_lever
from .setting_fit import FitProblem, flank_deviation_um

__all__ = ["HOLLOW_BOUND_UM", "FIT_GRID", "CONJUGATE_GRID", "GENERATOR_GRID", "EaseOffShape",
           "EaseOffShapeCheck", "HollowEaseOffWarning", "check_easeoff_shape",
           "easeoff_shape", "quadratic_shape"]

#: The bound B of the hollow ease-off warning, um: a flank is flagged when its profile or
#: lengthwise crowning is below -B (hollow by more than B at the box edges). A model
#: bound, declared in session 22 before any legitimate pinion was measured against it
#: (docs/machine_settings.md sec. 2): a hollow under 2 um is within the quadratic fit's
#: own residual (up to 1.4 um RMS on the pinions measured there) and no edge contact
#: worth a warning.
HOLLOW_BOUND_UM = 2.0
#: The deviation grid over the conjugate's active box (profile x lengthwise), the
#: setting fit's coarse grid (:func:`~.setting_fit.fit_member_setup`).
FIT_GRID = (9, 11)
#: The node grid of the gear flank's conjugate pinion (profile x lengthwise): its
#: quintic spline departs from a 60 x 75 one's by far less than the bound on the
#: crowning (docs, "The hollow ease-off warning").
CONJUGATE_GRID = (12, 15)
#: The envelope node grid of a generated gear flank as the conjugate's generator
#: (:func:`~.gear_generation.generating_sheet`; the pinion's own flanks take 40 x 60):
#: its crowning within 0.005 um of a 40 x 60 generator's on F.3 and the 11 x 41 (12 x 15:
#: 0.5 um), docs "The hollow ease-off warning".
GENERATOR_GRID = (20, 25)


class HollowEaseOffWarning(UserWarning):
    """A pinion flank cut from a pair's machine settings is hollow against the typed
    gear's conjugate pinion beyond :data:`HOLLOW_BOUND_UM` at its active box's edges:
    edge contact expected (not a check of the settings against the blank)."""


@dataclass(frozen=True)
class EaseOffShape:
    """The quadratic shape of one pinion flank's ease-off (module docstring).

    Attributes
    ----------
    side : str
        ``"drive"`` or ``"coast"``.
    C_p_um, C_l_um : float
        Profile and lengthwise crowning at the box edges against the tangent plane at
        its centre, um, relief positive (negative: hollow).
    bias_um : float
        The twist term's relief at the heel-tip corner of the box, um.
    fit_rms_um : float
        RMS residual of the quadratic fit on the grid, um.
    height_mm, length_mm : float
        The box's extents ``h`` (profile, sheet ``u``) and ``L`` (axial, sheet ``v``), mm.
    bound_um : float
        The bound B the flank is compared with, um.
    trimmed : bool
        The box is the part of the conjugate's active box that the pinion's own active
        box covers (its envelope does not reach the whole of the conjugate's).
    relieved_gear : bool
        The gear flank is cut by a relieved blade: measured against the conjugate of its
        main segment's flank, the relief not counted (:func:`check_easeoff_shape`).
    """

    side: str
    C_p_um: float
    C_l_um: float
    bias_um: float
    fit_rms_um: float
    height_mm: float
    length_mm: float
    bound_um: float = HOLLOW_BOUND_UM
    trimmed: bool = False
    relieved_gear: bool = False

    @property
    def hollowness(self) -> float:
        """``max(0, -min(C_p, C_l)) / B``: 0 for a crowned flank, above 1 flagged."""
        return max(0.0, -min(self.C_p_um, self.C_l_um)) / self.bound_um

    @property
    def flagged(self) -> bool:
        """``C_p < -B`` or ``C_l < -B``: hollow beyond the bound (edge contact)."""
        return min(self.C_p_um, self.C_l_um) < -self.bound_um


@dataclass(frozen=True)
class EaseOffShapeCheck:
    """:func:`check_easeoff_shape` of a pair: each pinion flank's shape, or why it was
    not measured.

    Attributes
    ----------
    flanks : tuple of EaseOffShape
        The measured pinion flanks.
    missing : dict
        ``{side: reason}`` of the flanks not checked (a generated gear flank left to the
        reader's generation check, an envelope that does not reach the grid), as
        sentences.
    seconds : float
        Wall time, s (a timing: run.json only; not compared).
    deferred : tuple of str
        The sides of :attr:`missing` whose gear flank is generated and was left for a
        check on the reader's gear boxes (``generated=False``;
        :func:`~.settings_check.completed_settings`).
    """

    flanks: tuple[EaseOffShape, ...]
    missing: dict = field(default_factory=dict)
    seconds: float = field(default=0.0, compare=False)
    deferred: tuple[str, ...] = ()

    def completed(self, other: "EaseOffShapeCheck") -> "EaseOffShapeCheck":
        """This check with its :attr:`deferred` sides replaced by ``other``'s result for
        them (flanks in the order drive, coast; seconds added)."""
        flanks = {s.side: s for s in (*self.flanks, *other.flanks)}
        missing = {side: why for side, why in self.missing.items() if side not in self.deferred}
        missing.update(other.missing)
        return EaseOffShapeCheck(tuple(flanks[side] for side in SIDES if side in flanks),
                                 {side: missing[side] for side in SIDES if side in missing},
                                 self.seconds + other.seconds, other.deferred)

    def warnings(self) -> tuple[str, ...]:
        """One ``"warning: ..."`` line per flagged flank (member, flank, C_p and C_l in
        um, the bound, what to change)."""
        return tuple(f"warning: {_message(s)}" for s in self.flanks if s.flagged)

    def warn(self, *, stacklevel: int = 2) -> None:
        """Emit each of :meth:`warnings` as a :class:`HollowEaseOffWarning` (without its
        ``"warning: "`` prefix); ``stacklevel`` counted from the caller."""
        for line in self.warnings():
            warnings.warn(line.removeprefix("warning: "), HollowEaseOffWarning,
                          stacklevel=stacklevel + 1)


def _message(s: EaseOffShape) -> str:
    hollow = [name for name, c in (("profile", s.C_p_um), ("lengthwise", s.C_l_um))
              if c < -s.bound_um]
    change = {"lengthwise": "the lengthwise crowning comes from the pinion's cutter radius "
                            "against the gear's and its modified roll 2C (a sign typed "
                            "wrong makes it hollow)",
              "profile": "the profile crowning comes from the pinion blade's profile "
                         "curvature and its modified roll"}
    return (f"the pinion {s.side} flank cut from [machine.pinion.{s.side}] is hollow "
            f"against the conjugate of the typed gear's {s.side} flank"
            + (" (its main blade segment: the relief not counted)" if s.relieved_gear else "")
            + f": crowning {s.C_p_um:+.1f} um in profile, {s.C_l_um:+.1f} um lengthwise at "
            f"the edges of its active box (relief positive; {' and '.join(hollow)} below -"
            f"{s.bound_um:g} um): edge contact expected, the pinion touching the gear first "
            "at the edges of its flank. "
            f"Crown it: {'; '.join(change[h] for h in hollow)} "
            "(docs/machine_settings.md sec. 2, \"The hollow ease-off warning\")")


def quadratic_shape(u_mm: np.ndarray, v_mm: np.ndarray, deviation_um: np.ndarray, *,
                    side: str, bound_um: float = HOLLOW_BOUND_UM) -> EaseOffShape:
    """The least-squares quadratic of a normal deviation (generated minus conjugate,
    positive = material left) on a grid ``(u_mm, v_mm)`` over a box (its first and last
    lines are the box's edges), as an :class:`EaseOffShape` (module docstring)."""
    u, v, d = (np.asarray(a, dtype=float).ravel() for a in (u_mm, v_mm, deviation_um))
    h, length = float(u.max() - u.min()), float(v.max() - v.min())
    x, y = u - 0.5 * (u.max() + u.min()), v - 0.5 * (v.max() + v.min())
    a = np.column_stack([np.ones_like(x), x, y, 0.5 * x * x, x * y, 0.5 * y * y])
    c = np.linalg.lstsq(a, d, rcond=None)[0]
    rest = d - a @ c
    return EaseOffShape(side=side, C_p_um=float(-0.5 * c[3] * (h / 2) ** 2),
                        C_l_um=float(-0.5 * c[5] * (length / 2) ** 2),
                        bias_um=float(-c[4] * (h / 2) * (length / 2)),
                        fit_rms_um=float(np.sqrt(np.mean(rest ** 2))),
                        height_mm=h, length_mm=length, bound_um=bound_um)


def easeoff_shape(pinion, conjugate, blank, *, side: str,
                  bound_um: float = HOLLOW_BOUND_UM, box=None) -> EaseOffShape:
    """The :class:`EaseOffShape` of ``pinion`` against ``conjugate`` (right-hand frame)
    on a :data:`FIT_GRID` grid over ``conjugate``'s box (or ``box``, a
    :class:`~.formate.FlankBoundary` inside it: then ``trimmed``), turned about the
    pinion axis to touch it at the box centre (module docstring).

    Parameters
    ----------
    pinion : MachineSetup or RadialSheet
        The pinion flank: a pinion set-up (its envelope solved at the grid nodes,
        :class:`~.setting_fit.FitProblem`), or a pinion sheet on the same cone (an
        eased conjugate, :func:`~.easeoff.apply_easeoff`; evaluated there,
        :func:`~.setting_fit.flank_deviation_um`, over the part of the box it covers).
    conjugate : ConjugateFlank
        The pinion flank conjugate to the gear flank of ``side``.
    blank : BlankDesign
    side : str

    Raises
    ------
    UndercutError
        The set-up's envelope does not reach a node of the grid.
    """
    trimmed = box is not None
    box = conjugate.boundary if box is None else box
    if isinstance(pinion, MachineSetup):
        us = np.linspace(box.u_root, box.u_tip, FIT_GRID[0])
        vs = np.linspace(box.v_toe, box.v_heel, FIT_GRID[1])
        prob = FitProblem(pinion, blank, conjugate, (), us, vs)
        u, v, d = prob.U, prob.V, prob.deviation_um(np.zeros(0)).reshape(prob.U.shape)
    else:
        u, v, d = flank_deviation_um(pinion, conjugate, n_u=FIT_GRID[0], n_v=FIT_GRID[1])
    t = conjugate.evaluate(u, v, second=False)
    lever = angle_lever("pinion", t.r, t.n)[1]
    i, j = FIT_GRID[0] // 2, FIT_GRID[1] // 2          # the box centre: both counts odd
    return dataclasses.replace(
        quadratic_shape(u, v, d - d[i, j] / lever[i, j] * lever, side=side,
                        bound_um=bound_um), trimmed=trimmed)


def check_easeoff_shape(pair, *, generated: bool = True, gear_boxes: dict | None = None,
                        sides: tuple[str, ...] = SIDES) -> EaseOffShapeCheck | None:
    """Each pinion flank of ``pair`` cut from machine settings against the conjugate of
    the typed gear flank of its side (module docstring): None for a pair without both
    members' settings. A left-hand pair is measured on its right-hand twin (the
    crowning is the same). Nothing is warned here (:meth:`EaseOffShapeCheck.warn`).

    Where the pinion's envelope does not reach the whole of the conjugate's active box,
    the part its own active box covers (:func:`~.generated.generated_pinion_box`) is
    measured (``trimmed``). A gear flank cut by a relieved blade (Toprem / Flankrem) is
    taken as the flank of its main segment's blade (:func:`~.blade.blade_segments`,
    continued past its kinks; ``relieved_gear``): a relief only removes gear material, so
    it adds relief to the pinion's ease-off where the gear's relieved piece meshes and
    the verdict errs towards a warning (docs, "The hollow ease-off warning"). A flank is
    not checked, with the reason in ``missing``, where the conjugate or the pinion's
    envelope does not reach even the pinion's own box.
    A generated gear flank generates its conjugate as a sheet continued beyond the face
    (:func:`~.gear_generation.generating_sheet` on :data:`GENERATOR_GRID`), over its
    active box: ``gear_boxes[side]`` where given (the reader's
    :func:`~.settings_top_land.member_box` of the right-hand twin's gear flank,
    ``generation.check_generation``'s ``"gear_box"``: the same box bit for bit, not
    traced again; a relieved gear blade's box is its tip segment's, so its main segment's
    is traced here), else traced here. With ``generated=False`` it is named not checked
    instead and listed in ``deferred`` (that sheet costs about three times a formate
    gear's whole check: the settings check runs it after the reader's generation check,
    on its gear boxes, :func:`~.settings_check.completed_settings`). ``sides``: the sides
    measured (the others are left out).
    """
    setups = {(s.member, s.side): s for s in getattr(pair, "machine", ()) or ()}
    if not all((m, s) in setups for m in ("gear", "pinion") for s in SIDES):
        return None
    t0 = time.perf_counter()
    twin = right_hand_twin(pair) if pair.pinion_hand == "left" else pair
    setups = {(s.member, s.side): s for s in twin.machine}
    kin = twin.kinematics(with_errors=False)
    shapes, missing, deferred = [], {}, []
    for side in sides:
        gear, relieved = _main_segment(setups["gear", side])
        if not (generated or gear.settings.formate):
            missing[side] = ("not checked by the settings check alone: the gear flank is "
                             "generated (its conjugate needs the gear's generating sheet, "
                             "measured on the gear box the pair's generation check traces: "
                             "every pair command does; `gearcontact design --pair FILE` "
                             "measures it)")
            deferred.append(side)
            continue
        box = (gear_boxes[side]["active_box"] if gear_boxes is not None and not relieved
               and not gear.settings.formate else None)
        try:
            conj, _ = conjugate_pinion_flank(
                _generator(gear, twin, box=box), blank=twin.blank, kinematics=kin,
                pinion_face_width_mm=twin.pinion_face_width_mm,
                n_u=CONJUGATE_GRID[0], n_v=CONJUGATE_GRID[1])
            shapes.append(dataclasses.replace(_measured(setups["pinion", side], conj, twin),
                                              relieved_gear=relieved))
        except (UndercutError, MeshingError) as err:
            missing[side] = ("not checked: the conjugate pinion or the pinion's envelope "
                             f"does not reach the conjugate's box ({err})")
    return EaseOffShapeCheck(tuple(shapes), missing, time.perf_counter() - t0, tuple(deferred))


def _measured(setup, conj, pair) -> EaseOffShape:
    """:func:`easeoff_shape` of the pinion ``setup`` over ``conj``'s box, or over the part
    the pinion's own active box covers where its envelope does not reach the whole."""
    try:
        return easeoff_shape(setup, conj, pair.blank, side=setup.side)
    except UndercutError:
        own = generated_pinion_box(setup, pair.blank,
                                   pinion_face_width_mm=pair.pinion_face_width_mm)[1]
    b = conj.boundary
    box = dataclasses.replace(b, u_root=max(own.u_root, b.u_root), u_tip=min(own.u_tip, b.u_tip),
                              v_toe=max(own.v_toe, b.v_toe), v_heel=min(own.v_heel, b.v_heel))
    return easeoff_shape(setup, conj, pair.blank, side=setup.side, box=box)


def _main_segment(setup) -> tuple[MachineSetup, bool]:
    """``setup`` with a relieved blade replaced by its main segment's smooth blade (the
    blade's own profile continued past its kinks, :func:`~.blade.blade_segments`), and
    whether it was relieved; ``setup`` itself otherwise."""
    segments = blade_segments(setup.blade)
    if len(segments) == 1:
        return setup, False
    main = next(seg.blade for seg in segments if seg.name == "main")
    return dataclasses.replace(setup, blade=main), True


def _generator(setup, pair, *, box=None):
    """The gear flank ``setup`` cuts as the generator of its conjugate pinion: a formate
    flank itself, a generated one's sheet continued beyond the face (over ``box``, its
    active box, where already traced)."""
    if setup.settings.formate:
        return machine_flank(setup, pair.blank, face_width_mm=pair.gear_face_width_mm)
    return SheetGenerator(generating_sheet(setup, pair.blank,
                                           gear_face_width_mm=pair.gear_face_width_mm,
                                           n_u=GENERATOR_GRID[0], n_v=GENERATOR_GRID[1],
                                           box=box))
