"""The design point of an ease-off: TCA at the continuous TE0 vertex.

The calibration (:mod:`.calibration`) and the local synthesis (:mod:`.synthesis`) both
run the TCA in the loop and judge an ease-off by its results at the mean contact: the
mating point, TE0 peak-to-peak over one pinion pitch, the Hertz and paint ellipses and
the direction of the contact path there (:class:`DesignPoint`). The reference point is
the *continuous* TE0 vertex (parabolic interpolation of the path's TE0 at the discrete
vertex, then a mating-point solve at that phase), so that these results are smooth in
the ease-off coefficients (docs/calibration.md).

The ease-off is searched in its centre form (:func:`centred_coefficients`: bearing
centre, profile and lengthwise crowning, bias), in which the bearing position and the
three second-order terms are nearly independent.

Frame invariants (:func:`point_invariants`): gear radius ``sqrt(x^2 + y^2)`` and axial
position ``z``; pinion radius ``sqrt((y + E)^2 + z^2)`` and axial position ``x``
(meshing frame of :mod:`gearcontact.geometry.kinematics`). They do not depend on the
rotation phase at which a point is reported, so they compare design points across
frames.

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 9
(TCA), sec. 21.8 (local synthesis: bearing position, path, TE level prescribed at the
mean point).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from ..analytic.hertz import hamrock_brewe_hertz
from ..geometry.easeoff import EaseOff, apply_easeoff, max_relief_um
from ..geometry.pair import EaseOffCoefficients, GearPair
from ..materials import effective_modulus_mpa
from .curvature import contact_ellipse, relative_curvature
from .load import normal_load_from_torque
from .mesh import mesh_cycle
from .types import ContactGuess, EdgeContact
from .mating import solve_mating_point

__all__ = ["point_invariants", "DesignPoint", "conjugate_contact", "design_point_at",
           "evaluate_design_point", "eased_design_point", "centred_coefficients",
           "surface_contact_ratio", "turn_relief"]



def point_invariants(point_mm, offset_mm: float) -> np.ndarray:
    """Frame-invariant coordinates of a meshing-frame point, mm.

    Returns ``(gear radius, gear axial z, pinion radius, pinion axial x)``.
    """
    x, y, z = (float(c) for c in point_mm)
    return np.array([np.hypot(x, y), z, np.hypot(y + offset_mm, z), x])


@dataclass(frozen=True)
class DesignPoint:
    """TCA results at the (continuous) TE0 vertex of one ease-off.

    Attributes
    ----------
    point_mm, normal : ndarray (3,)
        Mating point (meshing frame, mm) and common unit normal.
    invariants_mm : ndarray (4,)
        :func:`point_invariants` of ``point_mm``.
    pinion_uv, gear_uv : (float, float)
        Flank parameters of the mating point, mm.
    te0_pp_arcsec : float
        TE0 peak-to-peak over one pinion pitch (61 phases), arcsec.
    load_n : float
        Normal load at the design torque, N.
    ellipse_length_mm, ellipse_width_mm : float
        Hamrock–Brewe Hertz ellipse 2a x 2b at ``load_n``, mm.
    ellipse_angle_deg : float
        Major axis from the lengthwise direction, deg, positive towards the profile
        direction in the right-handed flank frame ``(l, p, n)``: the angle of
        :func:`~gearcontact.tca.curvature.contact_ellipse` on the side where that frame
        is right-handed, its negative on the other side, so that mirror-image bearings
        on the two sides have the same angle; a left-hand pair reports the angle of its
        right-hand mirror image.
    easeoff_max_um : float
        Largest |E| of the ease-off over the pinion flank, um.
    paint_length_mm : float
        Major axis 2a of the paint ellipse (6.35 um, :mod:`.curvature`), mm.
    surface_contact_ratio : float
        Phase span of the design point's own surface contact (the run of surface-to-
        surface mating points of its pair around it, edge contacts and phases without
        contact excluded) over one pinion pitch, measured on the TCA's phase grid to
        one step (:func:`surface_contact_ratio`); NaN if not evaluated.
    path_angle_deg : float
        Direction of the contact path on the gear flank at the point (phase increasing;
        the path the bearing draws on the gear tooth, Litvin & Fuentes 2004 sec. 21.8,
        not the contact point's motion in space), deg from the lengthwise direction, in the same right-handed frame as ``ellipse_angle_deg``,
        folded into (-90, 90]; NaN if the path has no interior neighbour there. A
        left-hand pair reports the angle of its right-hand mirror image.
    """

    point_mm: np.ndarray
    normal: np.ndarray
    invariants_mm: np.ndarray
    pinion_uv: tuple[float, float]
    gear_uv: tuple[float, float]
    te0_pp_arcsec: float
    load_n: float
    ellipse_length_mm: float
    ellipse_width_mm: float
    ellipse_angle_deg: float
    easeoff_max_um: float
    paint_length_mm: float = float("nan")
    path_angle_deg: float = float("nan")
    surface_contact_ratio: float = float("nan")



def conjugate_contact(conj, gear, pair: GearPair, u1: float, v1: float) -> ContactGuess:
    """Contact state of the conjugate pinion point (u1, v1) with its generating gear."""
    ms = conj.exact(np.array(float(u1)), np.array(float(v1)))
    u2, v2 = gear.surface_parameters(ms.h_mm, ms.theta_rad)
    phi2 = float(ms.phi2_rad)
    return ContactGuess(float(u1), float(v1), float(u2), float(v2), pair.ratio * phi2, phi2)



def _fold_deg(angle: float) -> float:
    """An axis direction in (-90, 90] deg."""
    return float((angle + 90.0) % 180.0 - 90.0) if (angle + 90.0) % 180.0 != 0.0 else 90.0



def design_point_at(pair: GearPair, pinion, gear, mp, *, te0_pp_arcsec: float,
                    torque_nm: float, path_tangent=None) -> DesignPoint:
    """:class:`DesignPoint` of the mating point ``mp`` of ``pinion`` and ``gear`` (the
    pair's kinematics), with the Hamrock–Brewe ellipse at the gear torque ``torque_nm``
    and, given the meshing-frame ``path_tangent`` (3,), the path angle (the tangent of
    the path on the gear flank, posed at ``mp``'s phase)."""
    kin = pair.kinematics()
    rc = relative_curvature(pinion, gear, kin, mp)
    ell = contact_ellipse(rc)
    # the flank frame (l, p, n) is right-handed on one side and left-handed on the other
    # (tca.curvature); compare orientations in the right-handed frame of either side
    # a left-hand pair is the mirror image (geometry.mirror): the reflection turns the
    # frame's handedness while the path and the ellipse axes keep their (l, p)
    # components, so the hand's sign gives the angles of the right-hand mirror image
    handed = float(np.sign(np.cross(rc.lengthwise, rc.profile) @ rc.normal))
    handed *= -1.0 if pair.pinion_hand == "left" else 1.0
    path_angle = float("nan")
    if path_tangent is not None and np.all(np.isfinite(path_tangent)):
        path_angle = _fold_deg(handed * float(np.degrees(np.arctan2(
            path_tangent @ rc.profile, path_tangent @ rc.lengthwise))))
    load = normal_load_from_torque(torque_nm, mp.point_mm, mp.normal)
    hb = hamrock_brewe_hertz(rc.A_minus_per_mm, rc.B_minus_per_mm, load,
                             e_prime_mpa=effective_modulus_mpa(pair.pinion_material,
                                                               pair.gear_material))
    return DesignPoint(point_mm=np.asarray(mp.point_mm), normal=np.asarray(mp.normal),
                       invariants_mm=point_invariants(mp.point_mm, pair.offset_mm),
                       pinion_uv=(mp.u1, mp.v1), gear_uv=(mp.u2, mp.v2),
                       te0_pp_arcsec=float(te0_pp_arcsec), load_n=float(load),
                       ellipse_length_mm=2.0 * hb.a_mm, ellipse_width_mm=2.0 * hb.b_mm,
                       ellipse_angle_deg=handed * float(ell.angle_deg),
                       easeoff_max_um=float(np.nan), paint_length_mm=2.0 * ell.semi_major_mm,
                       path_angle_deg=path_angle)



def evaluate_design_point(eased, gear, pair: GearPair, start: ContactGuess, *,
                          torque_nm: float, phases: int = 61, pairs: int = 2,
                          edge_contact: bool = True) -> DesignPoint:
    """TCA of one eased pinion flank against ``gear`` at the continuous TE0 vertex.

    ``start`` is a contact guess whose pinion height ``u1`` the first solve holds (the
    phase is free), then the mesh cycle continues along the phase.
    """
    kin = pair.kinematics()
    cycle = mesh_cycle(eased, gear, kin, pinion_teeth=pair.pinion_teeth, start=start,
                       start_fixed="u1", phases=phases, pairs=pairs,
                       edge_contact=edge_contact)
    path = cycle.path
    i = int(np.argmin(np.abs(path.phi1_rad - path.phi1_ref_rad)))
    te = path.te0_arcsec
    mp = path.points[i]
    if 0 < i < len(te) - 1 and np.all(np.isfinite(te[i - 1:i + 2])):
        # vertex of the parabola through the three phases around the discrete vertex
        y0, y1, y2 = te[i - 1], te[i], te[i + 1]
        den = y0 - 2.0 * y1 + y2
        if den != 0.0:
            h = float(np.clip(0.5 * (y0 - y2) / den, -0.5, 0.5))
            step = path.phi1_rad[i + 1] - path.phi1_rad[i]
            g = mp.as_guess()
            guess = ContactGuess.from_vector(g.vector() + h * (path.points[i + 1].as_guess().vector()
                                                               - g.vector()))
            mp = solve_mating_point(eased, gear, kin, dataclasses.replace(
                guess, phi1_rad=g.phi1_rad + h * step))
    tangent = None
    if 0 < i < len(te) - 1 and not (path.points[i - 1].edge or path.points[i + 1].edge):
        # the path on the gear flank (its body frame, posed at the point's phase), not
        # the contact point's motion in space: that adds the gear's rotation of the
        # point and stays near the contact line's direction (docs/synthesis.md)
        a, b = path.points[i - 1], path.points[i + 1]
        tangent = kin.gear_pose(mp.phi2_rad)[0] @ (gear.point(b.u2, b.v2).r
                                                   - gear.point(a.u2, a.v2).r)
    dp = design_point_at(pair, eased, gear, mp, te0_pp_arcsec=float(cycle.te0_pp_arcsec),
                         torque_nm=torque_nm, path_tangent=tangent)
    return dataclasses.replace(dp, surface_contact_ratio=surface_contact_ratio(
        path, i, steps_per_pitch=cycle.step_index))


def surface_contact_ratio(path, index: int, *, steps_per_pitch: int) -> float:
    """Phase span of the surface contact of ``path`` (one tooth pair) through its point
    ``index``, in pinion pitches: the run of surface mating points (``path.surface``)
    around ``index`` times the phase step (each point stands for one step; the run's
    true ends lie within a step of its outer points, so the span is good to one step,
    ``1 / steps_per_pitch``); 0 if the point is no surface contact.

    Below 1 the pair's surface contact leaves the flank before the next pair's begins
    (the path of one pitch is longer than the flank along it): the contact passes
    through an edge contact, whose TE the ease-off's crownings do not set."""
    surface = np.asarray(path.surface, bool)
    if not surface[index]:
        return 0.0
    lo = index
    while lo > 0 and surface[lo - 1]:
        lo -= 1
    hi = index
    while hi < len(surface) - 1 and surface[hi + 1]:
        hi += 1
    return float((hi - lo + 1) / steps_per_pitch)



def eased_design_point(coeffs: EaseOffCoefficients, conj, gear, pair: GearPair, starts, *,
                       mean_uv: tuple[float, float], limit_um: float, torque_nm: float,
                       phases: int = 61, pairs: int = 2, edge_contact: bool = True
                       ) -> DesignPoint:
    """:func:`evaluate_design_point` of the conjugate pinion flank ``conj`` eased by
    ``coeffs`` (about the pinion mean node ``mean_uv``, within ``limit_um``), from the
    first of ``starts`` (contact guesses, ``u1`` held) that reaches an interior contact;
    ``easeoff_max_um`` is filled in.

    Raises
    ------
    EdgeContact, ArithmeticError, ValueError
        From the last start if none succeeds (edge, no pair in mesh, relief limit).
    """
    eo = EaseOff.from_coefficients(coeffs, u_mean_mm=mean_uv[0], v_mean_mm=mean_uv[1])
    eased = apply_easeoff(conj, eo, limit_um=limit_um)
    for k, start in enumerate(starts):
        try:
            dp = evaluate_design_point(eased, gear, pair, start, torque_nm=torque_nm,
                                       phases=phases, pairs=pairs, edge_contact=edge_contact)
            break
        except (EdgeContact, ArithmeticError, ValueError):
            if k == len(starts) - 1:
                raise
    return dataclasses.replace(dp, easeoff_max_um=max_relief_um(eo, conj.boundary)[0])



def centred_coefficients(eta_c: float, xi_c: float, profile_crowning: float,
                         lengthwise_crowning: float, bias: float, *,
                         turn: np.ndarray | None = None) -> EaseOffCoefficients:
    """Five-term coefficients of the ease-off written about its centre (mm, um/mm^2):

    ``E = c_PC (eta - eta_c)^2 + c_LC (xi - xi_c)^2 + c_TW (xi - xi_c)(eta - eta_c) + const``

    i.e. ``c_PA = -2 c_PC eta_c - c_TW xi_c`` and ``c_SA = -2 c_LC xi_c - c_TW eta_c``.
    The pair format has no constant: the relief is zero at the mean node, so the form
    above carries ``const = -Q0``, ``Q0 = c_PC eta_c^2 + c_LC xi_c^2 + c_TW xi_c eta_c``
    (the relief at the centre). A uniform relief is no rigid turn of the pinion: a turn
    by ``d psi`` relieves the flank by ``d psi L(p)``, ``L = n . (e_x x r)`` the lever
    of the normal about the pinion axis, which grows from toe to heel (cone radius), so
    ``-Q0`` tilts the TE function like a spiral-angle term and moves the TE0 vertex off
    the centre by about ``Q0 (dL/dv / L) / (2 c_LC)`` lengthwise (20/20 miter of ISO
    23509 F.2's data, centre 3.7 mm above the mean node: 5.7 mm at c_LC = 0.035,
    beyond the toe at the c_LC that TE0 = 3 arcsec needs; docs/synthesis.md). With
    ``turn`` (:func:`turn_relief`) the constant is made a rigid turn instead,
    ``-Q0 L(p) / L(mean)``: its first- and second-order parts enter the coefficients,
    and the TE0 vertex stays at the centre. Without it (the calibration's form) the
    constant is dropped.
    """
    c = np.array([-2.0 * profile_crowning * eta_c - bias * xi_c,
                  -2.0 * lengthwise_crowning * xi_c - bias * eta_c,
                  profile_crowning, lengthwise_crowning, bias], dtype=float)
    if turn is not None:
        q0 = (profile_crowning * eta_c ** 2 + lengthwise_crowning * xi_c ** 2
              + bias * xi_c * eta_c)
        c = c - q0 * np.asarray(turn, dtype=float)
    return EaseOffCoefficients(
        profile_angle_um_per_mm=float(c[0]), spiral_angle_um_per_mm=float(c[1]),
        profile_crowning_um_per_mm2=float(c[2]), lengthwise_crowning_um_per_mm2=float(c[3]),
        bias_um_per_mm2=float(c[4]))


#: Nodes per direction of the grid over the active box on which :func:`turn_relief`
#: fits the lever (the fit's residual is what the five terms cannot hold).
_TURN_GRID = 9


def turn_relief(conj, mean_uv: tuple[float, float]) -> np.ndarray:
    """The relief of a rigid turn of the pinion about its axis, relative to its value at
    the mean node, as the five ease-off terms about the mean node ``(u_m, v_m)``:
    ``(a_eta, a_xi, a_eta2, a_xi2, a_xieta)`` of ``L(p) / L(mean) - 1`` (1/mm, 1/mm^2),
    ``L = n . (e_x x r)`` the lever of the flank normal about the pinion axis ``x`` of
    the body frame (a turn ``d psi`` moves the flank by ``d psi L`` along its normal;
    the TE of a relief is the relief over this lever, Litvin & Fuentes 2004, sec. 9.4).
    Least squares over a ``_TURN_GRID`` square grid of the flank's active box (the
    five terms vanish at the mean node, as the ratio does): the lever is far from
    quadratic across the profile of a small pinion (s0003: a Taylor polynomial at the
    mean node is 1e-2 off 1 mm away), and the bearing centre lies anywhere on the box
    (see :func:`centred_coefficients`)."""
    u_m, v_m = (float(x) for x in mean_uv)
    b = conj.boundary
    U, V = np.meshgrid(np.linspace(b.u_root, b.u_tip, _TURN_GRID),
                       np.linspace(b.v_toe, b.v_heel, _TURN_GRID), indexing="ij")
    u = np.append(U.ravel(), u_m)
    v = np.append(V.ravel(), v_m)
    s = conj.evaluate(u, v, second=False)
    lever = s.n[:, 1] * -s.r[:, 2] + s.n[:, 2] * s.r[:, 1]
    eta, xi = u[:-1] - u_m, v[:-1] - v_m
    basis = np.column_stack([eta, xi, eta * eta, xi * xi, xi * eta])
    return np.linalg.lstsq(basis, lever[:-1] / lever[-1] - 1.0, rcond=None)[0]
