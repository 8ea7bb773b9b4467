"""A derived blade's profile curvature as ``design`` writes it: what the blade can hold over
its working length (docs/machine_settings.md sec. 5, "The blade curvature written").

A circular blade of curvature ``k = 1 / r_b`` departs from its tangent at the reference
point by ``d(s) = (1 - cos(k s)) / k ~ k s^2 / 2`` at the arc distance ``s`` along it
(:mod:`.blade`). Derived blade curvatures are sums (the mate of a typed gear's curved
blade plus the crowning, :func:`~.blade_mate.recentred_blade`; the synthesis' or the
fit's corrections): where the terms cancel to rounding the sum is a curvature of order
1e-10 1/mm, a radius of 1e9-1e10 mm that no blade grinder makes and no measuring machine
sees, written so it claims a curved blade. Over the blade's working length ``L`` the
departure is at most ``|k| L^2 / 2``:

* below :data:`STRAIGHT_DEVIATION_MM` (1 nm, a hundredth of the 0.1 um a flank
  measurement resolves) the blade is straight: written ``profile_radius_mm = 0`` (the
  tangent line at the reference point, :func:`straight_blade`), the written flank equal
  to the derived one to that departure;
* below :data:`GRINDABLE_DEVIATION_MM` (0.1 um) the curvature is kept as computed and
  named (a real curvature, but one no grinder makes or measurement sees);
* above, nothing is said.

``L`` (:func:`working_length_mm`) is twice the blank's mean whole depth (working depth
plus clearance) along the blade: the tooth deepens towards the heel and the reference
point lies anywhere on the cutting part, so the distance from it to any cutting point is
below that. A blade with cubic / quartic terms (``c_3``, ``c_4``: the profile angle
``alpha(s) = alpha_0 + k s + c_3 s^2 / 2 + c_4 s^3 / 6``) departs by at most
``|k| L^2 / 2 + |c_3| L^3 / 6 + |c_4| L^4 / 24`` (``|sin x| <= |x|`` integrated): the
same bands hold for the whole profile, and a straightened blade loses all its terms (an
ease-off fit of a side with nothing to fit leaves terms of order 1e-10 there). A relieved
blade is written as it is.
"""

from __future__ import annotations

import dataclasses
import math

from .blade import BladeSettings, blade_profile, blade_through_point

__all__ = ["GRINDABLE_DEVIATION_MM", "STRAIGHT_DEVIATION_MM", "profile_deviation_mm",
           "straight_blade", "working_length_mm", "written_pair"]

#: Below this departure over the working length the blade is written straight, mm.
STRAIGHT_DEVIATION_MM = 1e-6
#: Below this departure a curvature kept is named in the written file's head, mm.
GRINDABLE_DEVIATION_MM = 1e-4


def working_length_mm(pair, blade: BladeSettings) -> float:
    """Bound on the arc distance from a blade's reference point to any point it cuts on
    ``pair``'s tooth (module docstring), mm."""
    whole = pair.blank.working_depth_mm + pair.blank.clearance_mm
    return 2.0 * whole / math.cos(math.radians(blade.blade_angle_deg))


def profile_deviation_mm(blade: BladeSettings, length_mm: float) -> float:
    """Bound on the departure of ``blade``'s profile from its tangent at the reference
    point within ``length_mm`` of it along the blade, ``|k| L^2 / 2 + |c_3| L^3 / 6 +
    |c_4| L^4 / 24`` (module docstring; 0 for a straight blade), mm."""
    k = 0.0 if blade.profile_radius_mm == 0.0 else 1.0 / abs(blade.profile_radius_mm)
    big_l = length_mm
    return big_l ** 2 * (0.5 * k + big_l * (abs(blade.profile_cubic_per_mm2) / 6.0
                                            + big_l * abs(blade.profile_quartic_per_mm3)
                                            / 24.0))


def straight_blade(blade: BladeSettings) -> BladeSettings:
    """The straight blade tangent to the curved ``blade`` at its reference point (same
    point, same profile angle there; no curvature, cubic or quartic term)."""
    rho, z, _, _ = blade_profile(blade, blade.profile_reference_mm)
    return blade_through_point(dataclasses.replace(blade, profile_radius_mm=0.0,
                                                   profile_cubic_per_mm2=0.0,
                                                   profile_quartic_per_mm3=0.0),
                               rho_mm=float(rho), z_mm=float(z))


def _derived_words(blade: BladeSettings, fmt: str) -> tuple[str, str]:
    """The written keys of ``blade``'s derived profile terms, and the words naming their
    values (formatted with ``fmt``)."""
    terms = [(key, name, value, unit) for key, name, value, unit in (
        ("profile_radius_mm", "radius", blade.profile_radius_mm, "mm"),
        ("profile_cubic_per_mm2", "cubic", blade.profile_cubic_per_mm2, "1/mm^2"),
        ("profile_quartic_per_mm3", "quartic", blade.profile_quartic_per_mm3, "1/mm^3"))
        if value != 0.0]
    keys = " / ".join(key for key, *_ in terms)
    if [name for _, name, _, _ in terms] == ["radius"]:
        return keys, f"the derived radius {blade.profile_radius_mm:{fmt}} mm"
    return keys, "the derived profile (" + ", ".join(
        f"{name} {value:{fmt}} {unit}" for _, name, value, unit in terms) + ")"


def written_pair(cut, *, members=("pinion",)):
    """``cut`` with the curved blades of ``members`` that cannot hold their curvature
    over their working length written straight (module docstring), and the lines for the
    written file's head naming each blade straightened or kept below
    :data:`GRINDABLE_DEVIATION_MM`.

    Returns
    -------
    (GearPair, list of str)
    """
    machine, notes = [], []
    for setup in cut.machine:
        b = setup.blade
        if setup.member not in members or (b.profile_radius_mm == 0.0
                                           and not b.higher_order) or b.relieved:
            machine.append(setup)
            continue
        length = working_length_mm(cut, b)
        dev = profile_deviation_mm(b, length)
        keys, words = _derived_words(b, ".3g")
        where = f"blade.{setup.member}.{setup.side}.{keys}"
        if dev < STRAIGHT_DEVIATION_MM:
            setup = dataclasses.replace(setup, blade=straight_blade(b))
            notes.append(f"{where}: {words} departs "
                         f"{dev * 1e3:.1g} um from a straight blade over its {length:.1f} mm "
                         f"working length (< {STRAIGHT_DEVIATION_MM * 1e3:g} um): written "
                         "straight (0), docs/machine_settings.md sec. 5")
        elif dev < GRINDABLE_DEVIATION_MM:
            notes.append(f"{where}: {_derived_words(b, '.6g')[1]} departs "
                         f"only {dev * 1e3:.2g} um from a straight blade over its "
                         f"{length:.1f} mm working length (< "
                         f"{GRINDABLE_DEVIATION_MM * 1e3:g} um: below what a grinder makes "
                         "or a measurement sees); kept as computed")
        machine.append(setup)
    return dataclasses.replace(cut, machine=tuple(machine)), notes
