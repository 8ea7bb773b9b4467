"""Contact ratio of a bevel or hypoid pair: from its contact path inside the active
flanks (the check ``design`` runs before any flank work) and from its virtual
cylindrical gears in closed form (ISO 10300-1, reported beside it; docs/geometry.md
sec. 7.7).

The virtual cylindrical gears of ISO 10300-1:2014 (Method B) replace the
pair at its mean section by a helical pair in the transverse section of the mean
spiral angle ``beta_vm = (beta_m1 + beta_m2) / 2`` (the mean of pinion and gear for a
hypoid; ``beta_m`` for a spiral bevel pair)::

    d_v      = d_m / cos(delta)                     reference diameters (back cones)
    alpha_vet = atan(tan(alpha_e) / cos(beta_vm))   transverse pressure angle
    d_vb     = d_v cos(alpha_vet),  d_va = d_v + 2 h_am
    g_vai    = min(sqrt(d_vai^2 - d_vbi^2) / 2 - d_vi sin(alpha_vet) / 2,
                   d_vj sin(alpha_vet) / 2)                     reach of member i's tip
    g_va     = g_va1 + g_va2         (ISO 21771 eq. for the path length, each reach
                                      capped at the mate's interference point)
    eps_va   = g_va cos(beta_vm) / (pi m_mn cos(alpha_vet))      transverse
    eps_vb   = b sin(beta_vm) / (pi m_mn)                        face (overlap)
    eps_vg   = sqrt(eps_va^2 + eps_vb^2)                          ISO 10300-1 Method B

``alpha_e`` is the effective pressure angle of the flank in mesh (ISO 23509: the
nominal angle plus or minus ``f_alim alpha_lim``, the blank's
``pressure_angle_drive_deg`` / ``pressure_angle_coast_deg``), ``h_am`` the mean
addenda, ``b`` the gear face width and ``m_mn`` the mean normal module. The root
sum of squares, not the cylindrical gears' sum ``eps_alpha + eps_beta``, is Method B's
total for a crowned (localized) bearing: the path of a crowned pair crosses the
flank diagonally, its length the diagonal of the transverse and face spans.

The closed form cannot see where a crowned pair's contact path leaves the flanks: on
narrow, low-spiral faces it leaves through toe or heel, or runs along the profile from
tip to root, and the TCA's contact ratio falls to 0.69 eps_vg.
:func:`~.contact_path.path_contact_ratio` traces that path over the pinion's active box
(:func:`~.conjugate.pinion_active_box`, computed by
:func:`~.generation.check_generation`): the locus of least ease-off on each contact line
of the conjugate pair, inside both flanks, in gear pitches (eps_p). It
follows the TCA's interior contact to the TCA's own resolution (-0.033 .. +0.002 on
nine pairs). :func:`check_contact_ratio` refuses ``eps_p < MIN_CONTACT_RATIO`` (0.85:
the largest eps_p measured with a gap in the TCA is 0.752, a 13 % margin); a pair cut
from machine settings, whose path is not known here, keeps the closed form's
``eps_vg < MIN_VIRTUAL_CONTACT_RATIO`` (1.55) unless the path of its blank (the pair
without its settings) passes, as ``design --machine-settings`` checked it before
writing them. docs/geometry.md sec. 7.7 has the measurements. A pair cut from settings
whose prediction is short is not refused: the prediction is not the settings' bearing
(the TCA of standard settings measured on a family of pairs, docs/machine_settings.md
sec. 5, "The contact-ratio check of machine settings"); its TCA decides. A reader that
runs the pair's TCA next (``tca.synthesis.prepare_pair`` for every command with a mesh:
the TCA refuses a gap, ``tca.edges.ContactGap``) says nothing more (``mesh_follows``);
a reader that does not (``bending``, ``export flanks``, ``design`` reading a settings
file, the library's :func:`~.generation.check_generation`) warns, naming the prediction
and the TCA that decides (:func:`check_settings_ratio`). ``design --machine-settings``
runs that TCA before it writes settings whose blank's prediction is short
(``tca.settings_gap``, above this layer).

References
----------
ISO 10300-1:2014, *Calculation of load capacity of bevel gears — Part 1*: virtual
cylindrical gears, Method B. ISO 21771:2007, length of path of contact. ISO 23509:2016,
effective pressure angles ``alpha_eD``, ``alpha_eC`` (``geometry.blank``).
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 9.2
(TCA of localized contact), sec. 21.8 (local synthesis).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace

from ..validation import InputRangeError
from .contact_path import path_contact_ratio
from .pair import blank_key_error

__all__ = ["MIN_CONTACT_RATIO", "MIN_VIRTUAL_CONTACT_RATIO", "REVERSE_GAP_RATIO",
           "SETTINGS_GAP_RATIO", "SETTINGS_NO_GAP_RATIO", "ContactRatioWarning",
           "VirtualContactRatio", "check_contact_ratio", "check_settings_ratio",
           "reverse_side_warning", "virtual_contact_ratio"]


class ContactRatioWarning(UserWarning):
    """The predicted contact ratio of a pair cut from machine settings is below the
    threshold of the conjugate pinion with its synthesized ease-off, and the reader runs
    no TCA of the pair (docs/machine_settings.md sec. 5, "The contact-ratio check of
    machine settings"): a warning, not a refusal, the prediction not being the settings'
    own bearing (gapped and gap-free standard settings were measured from eps_p 0.303 to
    0.551). The settings' TCA decides: ``tca`` refuses a mesh with a gap
    (:class:`~gearcontact.tca.edges.ContactGap`), and ``design --machine-settings`` runs
    it before writing (``tca.settings_gap``). A reader whose own TCA follows does not
    warn (``mesh_follows``)."""


@dataclass(frozen=True)
class VirtualContactRatio:
    """Contact ratios of the virtual cylindrical gears of a pair (ISO 10300-1, Method B).

    Attributes
    ----------
    transverse : float
        eps_va, transverse contact ratio (1).
    face : float
        eps_vb, face (overlap) ratio (1).
    total : float
        eps_vg = sqrt(eps_va^2 + eps_vb^2) (1).
    spiral_angle_deg : float
        beta_vm, the mean spiral angle of the virtual gears, deg.
    transverse_pressure_angle_deg : float
        alpha_vet, deg.
    """

    transverse: float
    face: float
    total: float
    spiral_angle_deg: float
    transverse_pressure_angle_deg: float


def virtual_contact_ratio(blank, *, gear_face_width_mm: float,
                          side: str = "drive") -> VirtualContactRatio:
    """The contact ratios of ``blank``'s virtual cylindrical gears (module docstring).

    Parameters
    ----------
    blank : BlankDesign
        Pitch-cone data at the mean point (:func:`~.blank.design_blank`).
    gear_face_width_mm : float, keyword-only
        Gear face width b, mm.
    side : str, keyword-only
        ``"drive"`` or ``"coast"``: which effective pressure angle is in mesh.

    Returns
    -------
    VirtualContactRatio
    """
    if side not in ("drive", "coast"):
        raise ValueError(f"side = {side!r} is not 'drive' or 'coast'")
    alpha_e = math.radians(blank.pressure_angle_drive_deg if side == "drive"
                           else blank.pressure_angle_coast_deg)
    beta = math.radians(0.5 * (blank.spiral_angle_pinion_deg + blank.spiral_angle_gear_deg))
    mn = blank.mean_normal_module_mm
    alpha_t = math.atan(math.tan(alpha_e) / math.cos(beta))
    d_v1 = 2.0 * blank.mean_pitch_radius_pinion_mm / math.cos(
        math.radians(blank.pitch_angle_pinion_deg))
    d_v2 = 2.0 * blank.mean_pitch_radius_gear_mm / math.cos(
        math.radians(blank.pitch_angle_gear_deg))

    def reach(d_v: float, h_a: float, d_mate: float) -> float:
        # path from the pitch point to where this member's tip leaves the mate, mm; at
        # most to the mate's interference point T (its base circle's tangent point):
        # beyond T the mate is undercut and has no flank to contact
        tip = 0.5 * math.sqrt((d_v + 2.0 * h_a) ** 2 - (d_v * math.cos(alpha_t)) ** 2)
        return min(tip - 0.5 * d_v * math.sin(alpha_t), 0.5 * d_mate * math.sin(alpha_t))

    g_va = (reach(d_v1, blank.addendum_pinion_mm, d_v2)
            + reach(d_v2, blank.addendum_gear_mm, d_v1))
    eps_a = g_va * math.cos(beta) / (math.pi * mn * math.cos(alpha_t))
    eps_b = float(gear_face_width_mm) * math.sin(beta) / (math.pi * mn)
    return VirtualContactRatio(eps_a, eps_b, math.hypot(eps_a, eps_b), math.degrees(beta),
                               math.degrees(alpha_t))


#: Refusal threshold on the path contact ratio eps_p (:func:`path_contact_ratio`). Not a
#: fit: the largest eps_p measured with a gap in the TCA is 0.752 (8/8, E 0, beta1 20 deg,
#: face 0.15 R_m; TCA interior 0.750), and 0.85 keeps a 13 % margin over it, more than
#: the path's deviation from the TCA's interior contact (-0.033 .. +0.002). Between 0.85
#: and 1 the unloaded bearing leaves part of each pitch to edge contact, which the TCA
#: follows (every pair measured with eps_p >= 0.64 ran; none with a gap above 0.752;
#: docs/geometry.md sec. 7.7).
MIN_CONTACT_RATIO = 0.85

#: Path contact ratio of the side that is not the design side below which ``design``
#: warns (:func:`reverse_side_warning`): below one pair per pitch the unloaded mesh of
#: that side leaves part of each pitch to edge contact or to a gap, which ``twin``
#: meets when the load reverses. A warning, not a refusal: the design side carries the
#: load (docs/geometry.md sec. 7.7).
REVERSE_GAP_RATIO = 1.0

#: Refusal threshold on the closed form eps_vg where no contact path is known (a pair
#: cut from machine settings: its flanks are not a conjugate pinion plus an ease-off).
#: Not a fit: the closed form over-estimates the TCA's measured contact ratio by up to
#: 1 / 0.69 (a 10/15 hypoid, E = 0.3 r2, beta1 20 deg, face 0.15 R_m: eps_vg 1.524, TCA
#: 1.05), and 1.55 x 0.69 = 1.07 keeps a 7 % margin over a gap at the worst pair
#: measured (docs/geometry.md sec. 7.7).
MIN_VIRTUAL_CONTACT_RATIO = 1.55

#: The standard face-width limit F <= 0.3 R_e, R_e = R_m + F/2, as a fraction of R_m.
_FACE_LIMIT = 0.3 / 0.85
#: Trial values of one field by which :func:`check_contact_ratio` verifies a named fix.
_FIX_TRIALS = 3
#: Aim of a trial above the threshold (each trial scales the field by the deficit: the
#: path ratio is not exactly proportional to it).
_FIX_MARGIN = 0.02
#: Pinion spiral angles tried above the pair's, deg.
_SPIRAL_STEPS_DEG = (10.0, 20.0)
#: Largest pinion spiral angle a fix names, deg: above issue 28's design space (20-55
#: deg), below the blank's 70 deg limit (:func:`~.blank.design_blank`); a value named
#: is also one the pair's other checks accept (:func:`check_contact_ratio`).
MAX_FIX_SPIRAL_DEG = 60.0
#: Share of the threshold below which no fix but the tooth numbers is tried.
_FIX_REACH = 0.75


#: The smallest predicted eps_p (the blank's path with the synthesis' first-order
#: bearing, :func:`path_contact_ratio`) of a pair whose standard settings' TCA was
#: measured without a gap (14/14 spiral bevel, R_m 55 mm, face 5 mm, beta 50 deg,
#: working depth factor 1.3), of the 52 pairs run (docs/machine_settings.md sec. 5,
#: "The contact-ratio check of machine settings"); the one pair of the family below it
#: gapped (12/12, eps_p 0.272). Named by :class:`ContactRatioWarning`, no longer a
#: refusal: a weak bound (it fell from 0.487 to 0.303 as pairs were added), replaced by
#: the settings' TCA in ``design --machine-settings`` (``tca.settings_gap``, docs sec. 5).
SETTINGS_NO_GAP_RATIO = 0.303
#: The largest predicted eps_p of a pair of that family whose standard settings' TCA
#: had a gap (9/9, face 6 mm, beta 35 deg): between :data:`SETTINGS_NO_GAP_RATIO` and it
#: both were measured, above it (to :data:`MIN_CONTACT_RATIO`) no gap; the warning says
#: which.
SETTINGS_GAP_RATIO = 0.551


def check_contact_ratio(pair, *, boxes: dict | None = None, boxes_of=None,
                        threshold: float | None = None, bearing_of=None,
                        mesh_follows: bool = False):
    """Refuse ``pair`` if its contact ratio on the design side is below ``threshold``,
    before any flank work (docs/geometry.md sec. 7.7).

    With the active boxes of :func:`~.generation.check_generation` (``boxes``) the ratio
    is the contact path's, :func:`path_contact_ratio` (threshold default
    :data:`MIN_CONTACT_RATIO`); the named fix is verified: ``boxes_of(trial)`` gives a
    trial pair's boxes (the checks of :func:`~.generation.check_generation` without this
    one; a trial those checks refuse does not count) and the trial's path ratio must
    reach the threshold. In order: a wider gear face (the pinion face in the same
    proportion; within the standard limit ``F <= 0.3 R_e``) when the path leaves through
    toe or heel, up to ``_FIX_TRIALS`` trials each scaling the face by the deficit; a
    larger pinion spiral angle (``_SPIRAL_STEPS_DEG`` above the pair's, below
    :data:`MAX_FIX_SPIRAL_DEG`: eps_p is not monotonic in it, 10/15 E 0.3 r2 at 25, 35,
    45 deg: 0.778, 0.851, 0.692, so the angle verified is named, not a bound); else the tooth numbers. No trial is made below
    ``_FIX_REACH`` of the threshold (neither face nor spiral angle moved eps_p by a
    quarter in the measurements). ``bearing_of(pair, boxes)``, if given, is the
    ease-off the pair (and each trial) will carry on its design side where it differs
    from its table (a :class:`~.contact_path.Bearing`: the synthesis' predicted bearing,
    ``tca.predicted_bearing``), else None.

    Without boxes, or for a pair cut from machine settings (no conjugate pinion and
    ease-off whose path is known), the closed form eps_vg of
    :func:`virtual_contact_ratio` is checked against
    :data:`MIN_VIRTUAL_CONTACT_RATIO`, its fix found from the closed form: the gear face
    width that gives ``eps_vg = threshold`` if within the standard limit, else the
    pinion spiral angle (bisection below :data:`MAX_FIX_SPIRAL_DEG`), else the tooth
    numbers; with ``boxes_of`` a value named is one the other checks accept (else the
    next fix). A pair cut from machine settings that the closed form refuses is accepted
    where the contact path of its blank reaches :data:`MIN_CONTACT_RATIO` (with
    ``boxes_of``: :func:`_blank_path_or_warn`), the check ``design
    --machine-settings`` made before writing the settings.

    A pair cut from settings where both the closed form and its blank's path are below
    theirs is not refused: its TCA decides (docs/machine_settings.md sec. 5). With
    ``mesh_follows`` (the caller runs the pair's TCA next, which refuses a mesh with a
    gap: :class:`~gearcontact.tca.edges.ContactGap`) nothing is said; else
    :func:`check_settings_ratio` warns. The blank of ``design --machine-settings`` is not
    checked here (``check_generation(contact_ratio=False)``): the TCA of the settings
    about to be written decides there (``tca.settings_gap``).

    Returns
    -------
    ~.contact_path.PathContactRatio or VirtualContactRatio

    Raises
    ------
    InputRangeError
        The ratio is below ``threshold`` (a pair whose flanks are not cut from settings),
        the field named as the pair file spells it (``design.pinion_spiral_angle_deg``,
        ``teeth.pinion / teeth.gear``: :func:`~.pair.blank_key_error`).
    """
    try:
        return _contact_ratio(pair, boxes=boxes, boxes_of=boxes_of, threshold=threshold,
                              bearing_of=bearing_of, mesh_follows=mesh_follows)
    except InputRangeError as exc:
        raise blank_key_error(exc) from None


def _contact_ratio(pair, *, boxes, boxes_of, threshold, bearing_of, mesh_follows):
    """:func:`check_contact_ratio`, its fields named as the library spells them."""
    if boxes is None or pair.machine:
        try:
            # a pair cut from settings is warned, not refused: no fix is verified
            return _check_virtual(pair, MIN_VIRTUAL_CONTACT_RATIO if threshold is None
                                  else threshold, boxes_of=None if pair.machine else boxes_of)
        except InputRangeError:
            if not pair.machine or boxes_of is None:
                raise
            return _blank_path_or_warn(pair, boxes_of=boxes_of, warn=not mesh_follows)
    threshold = MIN_CONTACT_RATIO if threshold is None else threshold

    def path_of(p, p_boxes):
        return path_contact_ratio(p, boxes=p_boxes, bearing=None if bearing_of is None
                                  else bearing_of(p, p_boxes))

    got = path_of(pair, boxes)
    if got.total >= threshold:
        return got
    v = virtual_contact_ratio(pair.blank, gear_face_width_mm=pair.gear_face_width_mm,
                              side=got.side)
    why = (f"the contact path of {got.bearing} inside the flanks covers eps_p = "
           f"{got.total:.3f} pitches, "
           f"leaving through the {got.ends[0]} and the {got.ends[1]} (ISO 10300-1: eps_vg "
           f"{v.total:.3f}, eps_va {v.transverse:.3f}, eps_vb {v.face:.3f}), below "
           f"{threshold:g} (docs/geometry.md sec. 7.7): the unloaded mesh would leave "
           f"{1.0 - got.total:.0%} of each pitch to edge contact or to a gap")

    def path_ratio(trial):
        try:
            return path_of(trial, boxes_of(trial)).total
        except InputRangeError:   # the trial fails another check of design
            return None

    # trials need the boxes of a trial pair; without boxes_of only the teeth are named
    near = boxes_of is not None and got.total >= _FIX_REACH * threshold
    if near and any(e.endswith(("toe", "heel")) for e in got.ends):
        fixed = _face_fix(pair, got.total, threshold, path_ratio)
        if fixed is not None:
            raise InputRangeError("design.gear_face_width_mm", pair.gear_face_width_mm,
                                  f">= {fixed[0]:.3f} mm ({why}; with {fixed[0]:.3f} mm and "
                                  f"the pinion face in the same proportion eps_p = "
                                  f"{fixed[1]:.3f})")
    for step in _SPIRAL_STEPS_DEG if near else ():
        beta = pair.pinion_spiral_angle_deg + step
        ratio = (path_ratio(replace(pair, pinion_spiral_angle_deg=beta))
                 if beta < MAX_FIX_SPIRAL_DEG else None)
        if ratio is not None and ratio >= threshold:
            raise InputRangeError("pinion_spiral_angle_deg", pair.pinion_spiral_angle_deg,
                                  f"{beta:.2f} deg ({why}; with {beta:.2f} deg eps_p = "
                                  f"{ratio:.3f}; eps_p is not monotonic in the spiral angle)")
    raise InputRangeError("pinion_teeth / gear_teeth", (pair.pinion_teeth, pair.gear_teeth),
                          f"more teeth ({why}; no face width or spiral angle tried fixes it)")


def _blank_path_or_warn(pair, *, boxes_of, warn: bool = True):
    """A pair cut from machine settings that the closed form refuses: the contact path of
    its blank (the pair without its settings: conjugate pinion, the synthesis'
    first-order bearing at its default targets, :func:`path_contact_ratio` without a
    bearing), as ``design --machine-settings`` checks the blank before it writes the
    settings; accepted at :data:`MIN_CONTACT_RATIO`, else (``warn``) warned by
    :func:`check_settings_ratio` (the closed form's prediction alone where the blank's
    own generation check refuses it; the closed form's ratios are then returned). A gap
    the settings' TCA meets is named there (:class:`~gearcontact.tca.edges.ContactGap`).
    docs/machine_settings.md sec. 5, "The contact-ratio check of machine settings"."""
    blank = replace(pair, machine=(), print_gear=(), easeoff_tables=())
    try:
        got = path_contact_ratio(blank, boxes=boxes_of(blank))
    except InputRangeError:     # the blank's own generation check refuses it
        got = None
    if got is not None and got.total >= MIN_CONTACT_RATIO:
        return got
    if warn:
        check_settings_ratio(pair, got, threshold=MIN_CONTACT_RATIO)
    return got if got is not None else virtual_contact_ratio(
        pair.blank, gear_face_width_mm=pair.gear_face_width_mm, side=pair.design_side)


def check_settings_ratio(pair, path, *, threshold: float) -> None:
    """A :class:`ContactRatioWarning` for a pair cut from machine settings whose predicted
    contact ratio is below ``threshold``, read by a caller that runs no TCA of it
    (docs/machine_settings.md sec. 5, "The contact-ratio check of machine settings"),
    naming the face width and spiral angle typed, the predicted eps_p (``path``, the
    blank's :class:`~.contact_path.PathContactRatio`; None where the blank's own
    generation check refuses it), the closed form of :func:`virtual_contact_ratio`, and
    the TCA that decides (``gearcontact tca --pair FILE``, which ``design
    --machine-settings`` runs before it writes such settings). Never a refusal: the
    prediction does not separate gapped settings from gap-free ones (both measured from
    eps_p :data:`SETTINGS_NO_GAP_RATIO` to :data:`SETTINGS_GAP_RATIO`); the settings'
    TCA refuses a mesh with a gap."""
    v = virtual_contact_ratio(pair.blank, gear_face_width_mm=pair.gear_face_width_mm,
                              side=pair.design_side)
    what = (f"{pair.design_side} side: the blank's contact path with the synthesis' "
            f"first-order bearing covers eps_p = {path.total:.3f} pitches (leaving through "
            f"the {path.ends[0]} and the {path.ends[1]})" if path is not None else
            "the blank's contact path is not known (its own generation check refuses it)")
    what += (f"; ISO 10300-1 eps_vg {v.total:.3f}, eps_va {v.transverse:.3f}, eps_vb "
             f"{v.face:.3f}")
    fields = (f"design.gear_face_width_mm = {pair.gear_face_width_mm:g} mm, "
              f"design.pinion_spiral_angle_deg = {pair.pinion_spiral_angle_deg:g} deg")
    measured = ("the TCA of standard settings was measured both with and without a gap "
                f"between eps_p {SETTINGS_NO_GAP_RATIO:g} and {SETTINGS_GAP_RATIO:g}"
                if path is None or path.total <= SETTINGS_GAP_RATIO else
                "the TCA of standard settings was measured without a gap above eps_p "
                f"{SETTINGS_GAP_RATIO:g}")
    warnings.warn(ContactRatioWarning(
        f"{fields}: the predicted contact ratio of the machine settings is below "
        f"{threshold:g} ({what}); a prediction, not the settings' own mesh: {measured} "
        "(docs/machine_settings.md sec. 5). This reading runs no TCA of the pair; "
        "`gearcontact tca --pair FILE` measures the mesh and refuses it if it has a gap "
        "(every command with a TCA does; `design --machine-settings` ran it before "
        "writing settings predicted this short)"), stacklevel=3)


def _with_face(pair, face_mm: float):
    """``pair`` with the gear face ``face_mm`` and the pinion face in the same proportion."""
    return replace(pair, gear_face_width_mm=face_mm, pinion_face_width_mm=face_mm
                   * pair.pinion_face_width_mm / pair.gear_face_width_mm)


def _face_fix(pair, ratio: float, threshold: float, path_ratio):
    """``(gear face width, its eps_p)`` reaching ``threshold`` within the face limit, or
    None (:func:`check_contact_ratio`)."""
    limit = math.floor(_FACE_LIMIT * pair.blank.mean_cone_distance_gear_mm * 1e3) / 1e3
    face = pair.gear_face_width_mm
    for _ in range(_FIX_TRIALS):
        if face >= limit:
            return None
        # a path leaving through toe and heel grows with the face about in proportion
        face = min(limit, math.ceil(face * (threshold + _FIX_MARGIN) / ratio * 1e3) / 1e3)
        ratio = path_ratio(_with_face(pair, face))
        if ratio is None:
            return None
        if ratio >= threshold:
            return face, ratio
    return None


def _check_virtual(pair, threshold: float, *, boxes_of=None) -> VirtualContactRatio:
    """The closed-form check of :func:`check_contact_ratio` (no contact path known). With
    ``boxes_of`` a named face or spiral angle is also one the pair's other checks accept
    (a trial ``boxes_of`` refuses is not named: the next fix is)."""
    def accepted(trial) -> bool:
        if boxes_of is None:
            return True
        try:
            boxes_of(trial)
        except InputRangeError:
            return False
        return True

    def ratio(p):
        return virtual_contact_ratio(p.blank, gear_face_width_mm=p.gear_face_width_mm,
                                     side=p.design_side)

    got = ratio(pair)
    if got.total >= threshold:
        return got
    why = (f"the virtual contact ratio eps_vg = {got.total:.3f} (eps_va {got.transverse:.3f}, "
           f"eps_vb {got.face:.3f}; ISO 10300-1) is below {threshold:g}, the closed form's margin "
           "over a gap in the unloaded mesh (contact ratio < 1)")
    if got.transverse < threshold:
        need = math.sqrt(threshold ** 2 - got.transverse ** 2)
        face = need * math.pi * pair.blank.mean_normal_module_mm / math.sin(
            math.radians(got.spiral_angle_deg))
        face = math.ceil(face * 1e3) / 1e3      # the value named, rounded up
        if (face <= _FACE_LIMIT * pair.blank.mean_cone_distance_gear_mm
                and accepted(_with_face(pair, face))):
            raise InputRangeError("design.gear_face_width_mm", pair.gear_face_width_mm,
                                  f">= {face:.3f} mm ({why})")
    beta = _spiral_angle_fix(pair, ratio, threshold)
    if beta is not None and accepted(replace(pair, pinion_spiral_angle_deg=beta)):
        raise InputRangeError("pinion_spiral_angle_deg", pair.pinion_spiral_angle_deg,
                              f">= {beta:.2f} deg ({why})")
    raise InputRangeError("pinion_teeth / gear_teeth", (pair.pinion_teeth, pair.gear_teeth),
                          f"more teeth ({why}; no face width or spiral angle fixes it)")


def _spiral_angle_fix(pair, ratio, threshold) -> float | None:
    """The smallest pinion spiral angle (deg, below :data:`MAX_FIX_SPIRAL_DEG`, rounded up
    to 0.01 deg) at which ``ratio`` reaches ``threshold`` (bisection to 0.01 deg), or
    None."""
    def ok(beta):
        try:
            return ratio(replace(pair, pinion_spiral_angle_deg=beta)).total >= threshold
        except InputRangeError:
            return False
    lo, hi = pair.pinion_spiral_angle_deg, MAX_FIX_SPIRAL_DEG
    if not ok(hi):
        return None
    while hi - lo > 0.01:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if ok(mid) else (mid, hi)
    named = math.ceil(hi * 100.0) / 100.0       # the value named (2 decimals)
    return named if named <= MAX_FIX_SPIRAL_DEG and ok(named) else hi


def reverse_side_warning(ratio) -> str | None:
    """One line for ``design``'s stderr when ``ratio`` (the path contact ratio of the
    side that is not the design side, :func:`~.generation.reverse_side_contact_ratio`)
    is below :data:`REVERSE_GAP_RATIO`, else None. It names the side, eps_p, where the
    path leaves the flanks and what ``twin`` does with that flank: where the side's
    unloaded mesh has a gap, the reverse flank takes the loaded side's law mirrored
    about the backlash (``twin.json`` ``reverse_flank``)."""
    if ratio is None or ratio.total >= REVERSE_GAP_RATIO:
        return None
    return (f"warning: the {ratio.side} side (not the design side) has a contact ratio "
            f"eps_p = {ratio.total:.3f} < {REVERSE_GAP_RATIO:g} (its path leaves through "
            f"the {ratio.ends[0]} and the {ratio.ends[1]}; {ratio.bearing}): its unloaded "
            f"mesh leaves {1.0 - ratio.total:.0%} of each pitch to edge contact or a gap; "
            f"twin then gives its reverse flank the loaded side's law mirrored about "
            f"backlash_mm (twin.json reverse_flank)")
