"""Machine settings from a target flank: the settings of either member that cut it.

The inverse of :mod:`.generated` ("machine-setting correction", issue item 4): given a
target flank (today's conjugate pinion with its ease-off, :mod:`.easeoff`, any pinion
:class:`~.sheet.RadialSheet`, a gear :class:`~.sheet.GearSheet`, or measured points of
either member, :mod:`.point_fit`), find the corrections ``x`` of a chosen subset of one
flank's machine and blade settings, from a seed set-up, whose cut flank reproduces
the target:

    min_x  sum_k d_k(x)^2,   d_k = R_k (psi_gen(u_k, v_k; x) - psi_t(u_k, v_k)) (e_psi . n_t)

the normal deviation (um, generated minus target along the target's outward normal n_t:
positive = material left, the opposite sign of an ease-off, :mod:`.easeoff`) at the
nodes ``(u_k, v_k)`` of a coarse grid over the target's active box. Both flanks live on
the same sheet of the seed's member (pinion: axial position ``v``, radius ``R_f(v) +
u``; gear: pitch-cone coordinates, :mod:`.sheet`), so the cut node solution
(:func:`~.member_envelope.member_solver`: the generated envelope, or a formate gear's
blade surface at zero roll; warm-started from the previous iterate, solved again by
continuation from the mean node where a node moved more than one Newton step: another
branch) differs from the target only in its angle ``psi`` about the member's axis; to
first order in the deviation ``d_k`` is the normal distance of the two surfaces. One
code path serves both members: only the sheet, the node solver and the default subset
(:func:`default_parameters`, by member and cutting method) differ.
``scipy.optimize.least_squares`` (trust-region reflective) solves it with a
forward-difference Jacobian in scaled parameters (:data:`PARAMETERS`); the residual
over the full flank is then measured on a dense grid of the final generated sheet
(:func:`flank_deviation_um`).

Parameters (:data:`PARAMETERS`): the machine settings of :class:`~.machine.MachineSettings`
by name, the modified roll 2C / 6D / 24E, the helical motion V_1, and five blade
parameters pivoting about the blade point P that generates the mean node at the seed
(so that a blade change does not move the mean point): ``blade_angle_deg`` (profile
angle at P), ``blade_curvature_per_mm`` (``1/r_b``, 0 = straight),
``blade_cubic_per_mm2`` and ``blade_quartic_per_mm3`` (the higher-order profile terms
``c_3``, ``c_4`` of :class:`~.machine.BladeSettings` at P) and ``blade_radius_mm`` (the
blade's radius at P: a cutter radius change with the cutter centre kept). The cradle
angle with the swivel kept turns the whole generating gear about the cradle axis,
which for a linear roll is a rigid turn of the generated flank about the work axis
(``q -> q + d`` at roll ``psi + d`` gives ``phi -> phi + R_a d``): it sets the flank's
angular position (tooth thickness) and belongs in every subset.

The default subsets (:func:`default_parameters`; the sensitivity studies that chose
them are docs/machine_settings.md sec. 6): pinion :data:`DEFAULT_PARAMETERS` (cradle
angle, radial distance, ratio of roll, modified roll 2C and 6D, blade angle, blade
curvature and the blade's cubic profile term); formate gear
:data:`FORMATE_GEAR_PARAMETERS` (the flank of a straight blade without tilt is a cone
of revolution: five separable combinations of its settings); generated gear
:data:`GENERATED_GEAR_PARAMETERS`. Settings that duplicate a subset's directions (on a
formate gear the sliding base is the cutter radius exactly) are left out; a subset a
flank measurement cannot separate is refused by :func:`~.point_fit.check_observable`.

A relieved blade (Toprem / Flankrem, :mod:`.blade`) keeps its relief as given
(:data:`~.relief_setup.RELIEF_KEYS`: a fixed blade property, never fitted): the corrections act on its
main profile, the pivot is the main profile's point that cuts the mean node (a relief
reaching it is refused, naming its depth), and the generated flank at each node is the
deepest of the blade's pieces, one envelope per blade segment (the smallest deviation,
the least material: :mod:`.kinked`), so nodes on both sides of the kink enter the same
least squares. Without a relief the code path is the smooth one, bit for bit
(docs/machine_settings.md sec. 6, "Relieved blades").

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 6.1,
ch. 21 (envelopes, machine-tool settings, modified roll).
M. Artoni, M. Gabiccini, M. Guiggiani, "Nonlinear identification of machine settings
for flank form modifications in hypoid gears", *ASME J. Mech. Des.* 130 (2008) 112602.
Q. Fan, R. S. DaFoe, J. W. Swanger, "Higher-order tooth flank form error correction for
face-milled spiral bevel and hypoid gears", *ASME J. Mech. Des.* 129 (2007) 31-37.
G. H. Golub, C. F. Van Loan, *Matrix Computations*, 4th ed., 2013, sec. 5.4.6 (QR with
column pivoting, subset selection).
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from ..validation import InputRangeError, check_range
from .blank import BlankDesign
from .conjugate import UndercutError
from .generated import ENVELOPE_MAX_STEP, EnvelopeSolver, solve_node_grid
from .machine import BladeSettings, MachineSetup, blade_profile, blade_through_point
from .member_envelope import angle_lever, mean_node_uv, member_cone, member_solver
from .relief_setup import blade_relief, check_pivot_on_main, piece_setups, with_relief
from .minimax_fit import minimize_max_abs

__all__ = ["DEFAULT_PARAMETERS", "FORMATE_GEAR_PARAMETERS", "FitProblem",
           "GENERATED_GEAR_PARAMETERS", "PARAMETERS", "SEED_PARAMETERS", "SettingFit",
           "apply_corrections", "checked_options", "conjugate_seed", "default_parameters",
           "fit_grid", "fit_member_setup", "fit_pinion_setup", "flank_deviation_um", "sensitivity",
           "solve_fit"]

#: Fit parameters -> (unit, scale): one unit of the scaled variable is ``scale`` of the
#: setting, chosen so that it moves a 7/70 hypoid or a 14/39 spiral bevel pinion flank
#: by roughly 1-10 um (so that the trust region starts balanced).
PARAMETERS = {
    "cradle_angle_deg": ("deg", 1e-3),
    "radial_distance_mm": ("mm", 1e-3),
    "swivel_deg": ("deg", 1e-2),
    "tilt_deg": ("deg", 1e-2),
    "machine_root_angle_deg": ("deg", 1e-2),
    "machine_centre_to_back_mm": ("mm", 1e-3),
    "sliding_base_mm": ("mm", 1e-3),
    "blank_offset_mm": ("mm", 1e-3),
    "ratio_of_roll": ("-", 1e-4),
    "modified_roll_2c_per_rad": ("1/rad", 1e-3),
    "modified_roll_6d_per_rad2": ("1/rad^2", 1e-2),
    "modified_roll_24e_per_rad3": ("1/rad^3", 1e-1),
    "helical_motion_mm_per_rad": ("mm/rad", 1e-2),
    "blade_angle_deg": ("deg", 1e-2),
    "blade_curvature_per_mm": ("1/mm", 1e-4),
    "blade_radius_mm": ("mm", 1e-3),
    "blade_cubic_per_mm2": ("1/mm^2", 1e-3),
    "blade_quartic_per_mm3": ("1/mm^3", 1e-2),
}
#: The default subset (module docstring).
DEFAULT_PARAMETERS = ("cradle_angle_deg", "radial_distance_mm", "ratio_of_roll",
                      "modified_roll_2c_per_rad", "modified_roll_6d_per_rad2",
                      "blade_angle_deg", "blade_curvature_per_mm", "blade_cubic_per_mm2")
#: The seed of a hypoid with a generated gear (:func:`conjugate_seed`): the default
#: subset and the crown pinion's bias directions, blank offset and helical motion.
SEED_PARAMETERS = DEFAULT_PARAMETERS + ("blank_offset_mm", "helical_motion_mm_per_rad")
#: The default subset of a formate gear (docs/machine_settings.md sec. 6, "Gear flanks"):
#: the cutter radius at the blade pivot, the blade angle, the machine root angle, the
#: machine centre to back and the blank offset.
FORMATE_GEAR_PARAMETERS = ("blade_radius_mm", "blade_angle_deg", "machine_root_angle_deg",
                           "machine_centre_to_back_mm", "blank_offset_mm")
#: The default subset of a generated gear: the cutter centre on the cradle (cradle
#: angle, radial distance), the ratio of roll, the modified roll 2C, the blade angle,
#: the cutter radius and the machine root angle (the formate subset's machine centre
#: to back and blank offset added: not separable, docs/machine_settings.md sec. 6).
GENERATED_GEAR_PARAMETERS = ("cradle_angle_deg", "radial_distance_mm", "ratio_of_roll",
                             "modified_roll_2c_per_rad", "blade_angle_deg",
                             "blade_radius_mm", "machine_root_angle_deg")
#: Settings a formate gear's fit refuses: a roll or a helical motion would make it a
#: generated gear, a curved blade profile is not modelled for a formate gear
#: (:func:`~.generated.formate_gear_flank`).
FORMATE_FIXED = ("ratio_of_roll", "modified_roll_2c_per_rad", "modified_roll_6d_per_rad2",
                 "modified_roll_24e_per_rad3", "helical_motion_mm_per_rad",
                 "blade_curvature_per_mm", "blade_cubic_per_mm2", "blade_quartic_per_mm3")
#: Objectives of the fit (:func:`fit_pinion_setup`).
OBJECTIVES = ("rms", "minimax")
_ROLL = {"modified_roll_2c_per_rad": 0, "modified_roll_6d_per_rad2": 1,
         "modified_roll_24e_per_rad3": 2}
_HELICAL = {"helical_motion_mm_per_rad": 0}
_BLADE = ("blade_angle_deg", "blade_curvature_per_mm", "blade_radius_mm",
          "blade_cubic_per_mm2", "blade_quartic_per_mm3")
_FD_STEP = 1e-3          # forward-difference step of the scaled variables
#: Deviation (um) returned at every node for a trial step whose envelope does not reach
#: the grid: the trust-region step is then rejected and shortened (a seed far from the
#: target, e.g. the crown gear's pinion of a hypoid, 115 um off its conjugate).
_UNREACHED_UM = 1e6


@dataclass(frozen=True)
class _Pivot:
    """The blade point P that generates the seed's mean node: radius and depth in the
    cutter frame (mm) and the seed's profile angle (rad), curvature (1/mm) and cubic
    term ``d^2 alpha/dl^2`` (1/mm^2) there."""

    rho_mm: float
    z_mm: float
    alpha_rad: float
    curvature_per_mm: float
    cubic_per_mm2: float = 0.0


def _pivot(setup: MachineSetup, l_mm: float) -> _Pivot:
    b = setup.blade
    rho, z, alpha, k = (float(a) for a in blade_profile(b, l_mm))
    c3 = b.profile_cubic_per_mm2 + b.profile_quartic_per_mm3 * (l_mm - b.profile_reference_mm)
    return _Pivot(rho, z, alpha, k, c3)


def _blade_through(blade: BladeSettings, pivot: _Pivot, *, alpha: float, k: float,
                   rho: float, c3: float = 0.0, c4: float = 0.0) -> BladeSettings:
    """The blade of ``blade``'s kind and edge through the point (``rho``, ``pivot.z``) of
    the cutter frame with profile angle ``alpha``, curvature ``k`` and higher-order
    terms ``c3``, ``c4`` there (:func:`~.machine.blade_profile`; circular blades in
    closed form, ``z(l) = (sin alpha - sin(alpha - k l)) / k``)."""
    sig, z = blade.sigma, pivot.z_mm
    if c3 != 0.0 or c4 != 0.0:
        shape = dataclasses.replace(blade, blade_angle_deg=math.degrees(alpha),
                                    profile_radius_mm=0.0 if k == 0.0 else 1.0 / k,
                                    profile_cubic_per_mm2=c3, profile_quartic_per_mm3=c4)
        return blade_through_point(shape, rho_mm=rho, z_mm=z)
    if k == 0.0:
        l_p = z / math.cos(alpha)
        return dataclasses.replace(blade, blade_angle_deg=math.degrees(alpha),
                                   point_radius_mm=rho + sig * math.sin(alpha) * l_p,
                                   profile_radius_mm=0.0, profile_reference_mm=0.0)
    s_tip = math.sin(alpha) - k * z
    if not abs(s_tip) < 1.0:
        raise InputRangeError("blade_curvature_per_mm", k, "a profile circle that reaches "
                              "the blade tip plane")
    # cos(alpha_tip) - cos(alpha) = k z t with t below: the arc k l_p and the tip
    # radius without the cancellation of the plain closed forms as k -> 0
    t = (math.sin(alpha) + s_tip) / (math.cos(alpha) + math.sqrt(1.0 - s_tip ** 2))
    l_p = math.asin(k * z * (math.sin(alpha) * t + math.cos(alpha))) / k
    return dataclasses.replace(blade, blade_angle_deg=math.degrees(alpha),
                               point_radius_mm=rho + sig * z * t,
                               profile_radius_mm=1.0 / k, profile_reference_mm=l_p)


def apply_corrections(setup: MachineSetup, corrections: dict, *, pivot_length_mm: float
                      ) -> MachineSetup:
    """``setup`` with the corrections ``{parameter: delta}`` (:data:`PARAMETERS`, in their
    units) added; blade parameters pivot about the blade point at arc length
    ``pivot_length_mm`` from the tip (module docstring). A relieved blade's main profile
    is corrected (``pivot_length_mm`` its own arc length) and its relief
    (:data:`~.relief_setup.RELIEF_KEYS`) kept as given.

    Raises
    ------
    InputRangeError
        An unknown parameter, or a corrected value out of its range (the message names
        the setting).
    """
    for name in corrections:
        if name not in PARAMETERS:
            raise InputRangeError("parameters", name, f"one of {tuple(PARAMETERS)}")
    relief = blade_relief(setup.blade)
    if relief:      # the main profile corrected, its relief kept (module docstring)
        return with_relief(apply_corrections(with_relief(setup, dict.fromkeys(relief, 0.0)),
                                             corrections, pivot_length_mm=pivot_length_mm),
                           relief)
    st, blade = setup.settings, setup.blade
    fields = {n: getattr(st, n) + float(d) for n, d in corrections.items()
              if n not in _ROLL and n not in _HELICAL and n not in _BLADE}
    series = {}
    for attr, keys in (("modified_roll", _ROLL), ("helical_motion", _HELICAL)):
        vals = list(getattr(st, attr))
        for n, k in keys.items():
            if n in corrections:
                vals += [0.0] * (k + 1 - len(vals))
                vals[k] += float(corrections[n])
        while vals and vals[-1] == 0.0:
            vals.pop()
        series[attr] = tuple(vals)
    st = dataclasses.replace(st, **fields, **series)
    if any(n in corrections for n in _BLADE):
        p = _pivot(setup, pivot_length_mm)
        get = corrections.get
        blade = _blade_through(blade, p,
                               alpha=p.alpha_rad + math.radians(get("blade_angle_deg", 0.0)),
                               k=p.curvature_per_mm + get("blade_curvature_per_mm", 0.0),
                               rho=p.rho_mm + get("blade_radius_mm", 0.0),
                               c3=p.cubic_per_mm2 + get("blade_cubic_per_mm2", 0.0),
                               c4=(blade.profile_quartic_per_mm3
                                   + get("blade_quartic_per_mm3", 0.0)))
    return dataclasses.replace(setup, settings=st, blade=blade)


class FitProblem:
    """Residual and Jacobian of the fit on a coarse node grid (module docstring): the
    target's angle ``psi_t`` and lever ``R (e_psi . n_t)`` (um/rad) at nodes ``(U, V)``
    of the seed member's sheet (:mod:`.point_fit` places them at measured points)."""

    def __init__(self, seed: MachineSetup, blank: BlankDesign, target, names, us, vs):
        solver, mean = self._start(seed, blank, names)
        self.U, self.V = np.meshgrid(us, vs, indexing="ij")
        self._grid = (us, vs)
        self.q = self._restart(solver, mean.q).q
        t = target.evaluate(self.U, self.V, second=False)
        self.psi_t, self.lever_um = angle_lever(seed.member, t.r, t.n)

    def _start(self, seed: MachineSetup, blank: BlankDesign, names):
        """Set the parameters and the pivot: the seed's solver and mean node (a relieved
        blade's: its main profile's, checked to hold the mean node)."""
        self.seed, self.blank, self.names = seed, blank, tuple(names)
        self.scale = np.array([PARAMETERS[n][1] for n in self.names])
        self.cone = member_cone(seed.member, blank)
        self.evaluations = 0
        relief = blade_relief(seed.blade)
        main = with_relief(seed, dict.fromkeys(relief, 0.0)) if relief else seed
        solver = member_solver(main, blank, self.cone)
        self.mean_uv = mean_node_uv(seed.member, blank, self.cone)
        mean = self._mean(solver)
        self.pivot_length_mm = float(mean.l_mm)
        if relief:
            check_pivot_on_main(seed.blade, float(blade_profile(main.blade, mean.l_mm)[1]),
                                member=seed.member)
        self._piece_q = {}      # the other pieces' node solutions (relieved blades)
        return solver, mean

    def _mean(self, solver: EnvelopeSolver):
        u_m, v_m = self.mean_uv
        return solver.solve(u_m, v_m, solver.initial_guess(u_m, v_m))

    def _restart(self, solver: EnvelopeSolver, q_mean):
        """The node solutions by continuation from the mean node (guess ``q_mean``)."""
        us, vs = self._grid
        return solve_node_grid(solver, us, vs, *self.mean_uv, q_mean)

    def setup(self, x) -> MachineSetup:
        return apply_corrections(self.seed, dict(zip(self.names, np.asarray(x) * self.scale)),
                                 pivot_length_mm=self.pivot_length_mm)

    def deviation_um(self, x, *, keep: bool = False) -> np.ndarray:
        """Normal deviation (um) at the grid nodes of the flank the corrections ``x``
        (scaled) generate; ``keep`` stores the node solutions as the next guesses. A
        relieved blade's flank is, node by node, the deepest of its pieces (the
        smallest deviation: the least material, :mod:`.kinked`)."""
        self.evaluations += 1
        try:
            pieces = self._nodes(x)
        except (UndercutError, ValueError):   # no envelope (or no blade) at a trial step
            if not np.any(x):                # the seed itself: the caller's error
                raise
            return np.full(self.U.size, _UNREACHED_UM)
        dev = None
        for name, s, solver in pieces:
            if keep and name == "main":
                self.q = s.q
            elif keep:
                self._piece_q[name] = s.q
            d = (solver.angle(s.x_mm) - self.psi_t + math.pi) % (2.0 * math.pi) - math.pi
            dev = d * self.lever_um if dev is None else np.minimum(dev, d * self.lever_um)
        return dev.ravel()

    def _nodes(self, x):
        """``[(piece name, node solutions, solver)]`` of the flank ``x`` generates."""
        out = []
        for name, setup in piece_setups(self.setup(x)):
            solver = member_solver(setup, self.blank, self.cone)
            q = self.q if name == "main" else self._piece_q.get(name)
            s = None if q is None else solver.solve(self.U, self.V, q, strict=False)
            if s is None or not np.all(s.converged) or _jumped(s.q, q):   # a long step:
                s = self._restart(solver, self._mean(solver).q)          # from the mean node
            out.append((name, s, solver))
        return out

    def jacobian(self, x) -> np.ndarray:
        f0 = self.deviation_um(x, keep=True)
        cols = []
        for k in range(len(x)):
            xk = np.array(x, dtype=float)
            xk[k] += _FD_STEP
            cols.append((self.deviation_um(xk) - f0) / _FD_STEP)
        jac = np.column_stack(cols)
        if getattr(self, "first", None) is None:     # at the seed: the reach prediction
            self.first = (f0, jac)
        return jac


def _jumped(q, guess) -> bool:
    """Whether a warm-started node solution ``q`` moved farther than one damped Newton
    step (:data:`~.generated.ENVELOPE_MAX_STEP`) from its ``guess`` at some node: it may
    have left the envelope branch of the mean node's continuation (a trial step of a
    fit with every setting, docs/machine_settings.md sec. 5), so it is not kept."""
    return bool(np.any(np.abs(q - guess) > ENVELOPE_MAX_STEP))


def sensitivity(seed: MachineSetup, blank: BlankDesign, target, *, names=tuple(PARAMETERS),
                n_u: int = 9, n_v: int = 11) -> tuple[np.ndarray, tuple]:
    """The sensitivity matrix of the flank's normal deviation (um per scaled unit,
    :data:`PARAMETERS`) at the seed on the coarse fit grid, columns ``names``:
    ``(J, names)``. Its singular values and a column-pivoted QR show which subsets are
    well conditioned (docs/machine_settings.md sec. 6)."""
    prob = FitProblem(seed, blank, target, names, *fit_grid(target.boundary, n_u, n_v))
    return prob.jacobian(np.zeros(len(names))), prob.names


def fit_grid(box, n_u: int, n_v: int):
    """The fit grid's node coordinates ``(us, vs)`` over ``box`` (n_u x n_v, each >= 3)."""
    if int(n_u) != n_u or n_u < 3 or int(n_v) != n_v or n_v < 3:
        raise InputRangeError("n_u, n_v (fit grid)", (n_u, n_v), "integers >= 3")
    return (np.linspace(box.u_root, box.u_tip, int(n_u)),
            np.linspace(box.v_toe, box.v_heel, int(n_v)))


@dataclass(frozen=True)
class SettingFit:
    """A fitted pinion flank set-up and its residual against the target.

    Attributes
    ----------
    setup : MachineSetup
        The fitted settings and blade.
    seed : MachineSetup
    corrections : dict
        ``{parameter: delta}`` in the units of :data:`PARAMETERS` (setup - seed).
    fit_rms_um, fit_max_um : float
        RMS and largest |normal deviation| on the coarse fit grid, um.
    evaluations : int
        Flank evaluations (coarse grid) of the fit, Jacobian columns included.
    condition_number : float
        Of the scaled Jacobian at the solution.
    seconds : float
    status : int
        ``least_squares`` status (> 0: converged).
    objective : str
        ``"rms"`` (least squares) or ``"minimax"`` (the largest deviation minimized from
        the least-squares solution, :mod:`.minimax_fit`).
    rms_fit_max_um : float
        Largest |normal deviation| on the fit grid of the least-squares solution, um
        (equal to ``fit_max_um`` for ``"rms"``): what the minimax objective improved on.
    predicted_rms_um, predicted_max_um : float
        The reach predicted before the search: the part of the seed's deviation on the
        fit grid outside the span of the parameters' sensitivities there (the linear
        least-squares projection residual, from the search's first Jacobian, no extra
        evaluation), RMS and largest, um; the fitted residual differs from it by the
        fit's nonlinearity (docs/machine_settings.md sec. 6).
    """

    setup: MachineSetup
    seed: MachineSetup
    corrections: dict
    fit_rms_um: float
    fit_max_um: float
    evaluations: int
    condition_number: float
    seconds: float
    status: int
    objective: str = "rms"
    rms_fit_max_um: float = math.nan
    predicted_rms_um: float = math.nan
    predicted_max_um: float = math.nan


def default_parameters(seed: MachineSetup) -> tuple:
    """The default fitted subset of ``seed``'s member and cutting method: pinion
    :data:`DEFAULT_PARAMETERS`, formate gear :data:`FORMATE_GEAR_PARAMETERS`, generated
    gear :data:`GENERATED_GEAR_PARAMETERS`."""
    if seed.member == "pinion":
        return DEFAULT_PARAMETERS
    return FORMATE_GEAR_PARAMETERS if seed.settings.formate else GENERATED_GEAR_PARAMETERS


def fit_pinion_setup(seed: MachineSetup, blank: BlankDesign, target, *,
                     parameters=DEFAULT_PARAMETERS, n_u: int = 9, n_v: int = 11,
                     tolerance_um: float = 1e-6, objective: str = "rms", box=None
                     ) -> SettingFit:
    """:func:`fit_member_setup` of a pinion set-up (``seed.member`` other than
    ``"pinion"`` refused: ``InputRangeError`` naming ``seed.member``)."""
    if seed.member != "pinion":
        raise InputRangeError("seed.member", seed.member, "'pinion' (fit_member_setup "
                              "fits either member)")
    return fit_member_setup(seed, blank, target, parameters=parameters, n_u=n_u, n_v=n_v,
                            tolerance_um=tolerance_um, objective=objective, box=box)


def fit_member_setup(seed: MachineSetup, blank: BlankDesign, target, *,
                     parameters=None, n_u: int = 9, n_v: int = 11,
                     tolerance_um: float = 1e-6, objective: str = "rms", box=None
                     ) -> SettingFit:
    """Fit the ``parameters`` of the set-up ``seed`` (pinion or gear) so that its cut
    flank reproduces ``target`` on an n_u x n_v grid over the target's active box.

    Parameters
    ----------
    seed : MachineSetup
        A flank set-up that cuts the target's box: a pinion's (the complementary
        settings of :func:`~.basic_settings.complementary_pinion_setups` or the
        standard ones of :func:`~.basic_settings.standard_setups`) or a gear's
        (formate or generated; a relieved blade keeps its relief, module docstring).
    blank : BlankDesign
    target : RadialSheet
        The target flank on the sheet of ``seed``'s member (with ``evaluate`` and
        ``boundary``: a pinion :class:`~.sheet.RadialSheet`, a gear
        :class:`~.sheet.GearSheet`), same side as ``seed``, right-hand body frame.
    parameters : tuple of str, optional
        Names from :data:`PARAMETERS` (default :func:`default_parameters` of the
        seed; a formate gear refuses :data:`FORMATE_FIXED`).
    n_u, n_v : int
        Fit grid (profile x lengthwise), each >= 3.
    tolerance_um : float
        Stop when the step changes the residual's sum of squares by less than
        ``tolerance_um**2`` relative (``ftol``), um-scaled, in (0, 1].
    objective : str
        ``"rms"``: minimize the sum of squared deviations (``least_squares``, trust-region
        reflective); ``"minimax"``: then, from that solution, the largest |deviation| on
        the fit grid (sequential linear programming, :func:`~.minimax_fit.minimize_max_abs`,
        to ``tolerance_um``; docs/machine_settings.md sec. 6).
    box : FlankBoundary, optional
        The box the fit grid covers (default the target's): a relieved blade's flank
        starts at the root line its tip segment traces (:mod:`.kinked`), its part of
        the target's box.

    Returns
    -------
    SettingFit

    Raises
    ------
    InputRangeError
        An unknown or repeated parameter, a roll, helical-motion or blade-curvature
        parameter for a formate gear, a relief whose kink reaches the blade point that
        cuts the mean node (either member, :func:`~.relief_setup.check_pivot_on_main`),
        a gear target that is not a sheet on the blank's gear cone, or a fit grid
        smaller than 3 x 3.
    UndercutError
        The seed's envelope does not reach a node of the grid.
    """
    names = checked_options(seed, parameters, tolerance_um=tolerance_um, objective=objective)
    if seed.member == "gear" and getattr(target, "cone", None) != member_cone("gear", blank):
        raise InputRangeError("target", type(target).__name__, "a gear sheet on the blank's "
                              "gear cone (GearSheet: its (u, v) are the fit's nodes; a "
                              "formate FormateFlank is measured at points, "
                              "geometry.gear_correction)")
    t0 = time.perf_counter()
    prob = FitProblem(seed, blank, target, names,
                      *fit_grid(target.boundary if box is None else box, n_u, n_v))
    return solve_fit(prob, tolerance_um=tolerance_um, objective=objective, started=t0)


def checked_options(seed: MachineSetup, parameters, *, tolerance_um: float,
                    objective: str) -> tuple:
    """The fitted ``parameters`` (``None``: :func:`default_parameters`) as a tuple,
    after the checks of :func:`fit_member_setup` (seed, names, tolerance,
    objective)."""
    if seed.member not in ("pinion", "gear"):
        raise InputRangeError("seed.member", seed.member, "'pinion' or 'gear'")
    names = tuple(default_parameters(seed) if parameters is None else parameters)
    if not names or len(set(names)) != len(names) or any(n not in PARAMETERS for n in names):
        raise InputRangeError("parameters", names, f"distinct names from {tuple(PARAMETERS)}")
    if seed.member == "gear":
        where = f"machine.gear.{seed.side}"
        bad = [n for n in names if n in FORMATE_FIXED] if seed.settings.formate else []
        if bad:
            raise InputRangeError(f"parameters ({where}: a formate gear)", ", ".join(bad),
                                  f"settings of a formate gear, not {FORMATE_FIXED} (a roll "
                                  "or helical motion would make it generated; curved "
                                  "formate blades are not modelled)")
    check_range("tolerance_um", tolerance_um, 0.0, 1.0, lo_open=True)
    if objective not in OBJECTIVES:
        raise InputRangeError("objective", objective, f"one of {OBJECTIVES}")
    return names


def solve_fit(prob: FitProblem, *, tolerance_um: float, objective: str, started: float
              ) -> SettingFit:
    """The fit of ``prob`` from its seed (:func:`fit_pinion_setup`): least squares, then
    the minimax objective if asked; ``started`` the ``perf_counter`` of its start."""
    names = prob.names
    sol = least_squares(lambda x: prob.deviation_um(x, keep=True), np.zeros(len(names)),
                        jac=prob.jacobian, method="trf", x_scale="jac",
                        ftol=tolerance_um ** 2, xtol=1e-12, gtol=1e-12, max_nfev=200)
    s = np.linalg.svd(sol.jac, compute_uv=False)
    x = sol.x
    gap = getattr(prob, "gap_rows", None)   # rows past it: not deviations (their own fit)
    dev = prob.deviation_um(x)[:gap]
    rms_fit_max = float(np.abs(dev).max())
    if objective == "minimax":
        x = minimize_max_abs(lambda y: prob.deviation_um(y, keep=True), prob.jacobian, x,
                             tol=tolerance_um).x
        dev = prob.deviation_um(x)[:gap]
    f0, j0 = prob.first
    left = (f0 - j0 @ np.linalg.lstsq(j0, f0, rcond=None)[0])[:gap]
    return SettingFit(setup=prob.setup(x), seed=prob.seed,
                      corrections={n: float(v * sc) for n, v, sc in zip(names, x, prob.scale)},
                      fit_rms_um=float(np.sqrt(np.mean(dev ** 2))),
                      fit_max_um=float(np.abs(dev).max()), evaluations=prob.evaluations,
                      condition_number=float(s[0] / s[-1]) if s[-1] > 0 else math.inf,
                      seconds=time.perf_counter() - started, status=int(sol.status),
                      objective=objective, rms_fit_max_um=rms_fit_max,
                      predicted_rms_um=float(np.sqrt(np.mean(left ** 2))),
                      predicted_max_um=float(np.abs(left).max()))


def conjugate_seed(seed: MachineSetup, blank: BlankDesign, conjugate, *, n_u: int = 9,
                   n_v: int = 11) -> SettingFit:
    """The crown gear's pinion ``seed`` of a hypoid with a generated gear (a point-contact
    conjugate, up to 115 um off the line-contact ``conjugate`` at a corner) fitted to
    ``conjugate``: first its rigid turn (cradle angle alone), then
    :data:`SEED_PARAMETERS` (docs/machine_settings.md sec. 6). The fit of an ease-off
    starts from its ``setup``."""
    turned = fit_pinion_setup(seed, blank, conjugate, parameters=("cradle_angle_deg",),
                              n_u=n_u, n_v=n_v).setup
    return fit_pinion_setup(turned, blank, conjugate, parameters=SEED_PARAMETERS,
                            n_u=n_u, n_v=n_v)


def flank_deviation_um(flank, target, *, n_u: int = 60, n_v: int = 75):
    """Normal deviation of ``flank`` from ``target`` (two pinion sheets on the same
    cone), um, on an n_u x n_v grid over the part of ``target``'s box that ``flank``
    covers: ``(u, v, deviation)`` arrays (n_u, n_v) (generated minus target along the
    target's outward normal, module docstring)."""
    a, b = flank.boundary, target.boundary
    box = dataclasses.replace(b, u_root=max(a.u_root, b.u_root), u_tip=min(a.u_tip, b.u_tip),
                              v_toe=max(a.v_toe, b.v_toe), v_heel=min(a.v_heel, b.v_heel))
    U, V = np.meshgrid(*fit_grid(box, n_u, n_v), indexing="ij")
    f, t = flank.evaluate(U, V, second=False), target.evaluate(U, V, second=False)
    return U, V, 1e3 * np.einsum("...i,...i->...", f.r - t.r, t.n)

