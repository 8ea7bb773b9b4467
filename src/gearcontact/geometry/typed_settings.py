"""The typed keys of one flank's ``[machine.<member>.<flank>]`` / ``[blade.<member>.<flank>]``
tables as the typed-settings check sees them (:mod:`.blank_check`,
:mod:`.slip_attribution`): read one, move one, its typed rounding and its full name
(docs/machine_settings.md sec. 2, "The check when a pair is loaded").

The keys are the settings whose rounding the check propagates: the machine's numeric
settings, the printed series (modified roll 2C..120F, helical motion) and the blade's
angle and point radius. The attribution of a disagreeing flank
(:mod:`.slip_attribution`) tries the blade's profile keys as well
(:func:`attributed_keys`: a curved blade's radius and reference, a typed higher-order
term), whose rounding is not propagated (a clean sheet's check costs what it did).
"""

from __future__ import annotations

import dataclasses
from decimal import Decimal

from .machine import HELICAL_KEYS, MODIFIED_ROLL_KEYS, MachineSetup

__all__ = ["BLADE", "NUMERIC", "PROFILE", "SERIES", "attributed_keys", "full_key", "moved",
           "roundings", "setting", "typed_keys", "typed_resolution"]

#: The machine's numeric keys.
NUMERIC = ("radial_distance_mm", "cradle_angle_deg", "machine_root_angle_deg",
           "machine_centre_to_back_mm", "sliding_base_mm", "blank_offset_mm",
           "ratio_of_roll", "tilt_deg", "swivel_deg")
#: The blade keys.
BLADE = ("blade_angle_deg", "point_radius_mm")
#: The blade's profile keys (:func:`attributed_keys`).
PROFILE = ("profile_radius_mm", "profile_reference_mm", "profile_cubic_per_mm2",
           "profile_quartic_per_mm3")
#: The printed series, key -> (MachineSettings field, index).
SERIES = {**{k: ("modified_roll", i) for i, k in enumerate(MODIFIED_ROLL_KEYS)},
          **{k: ("helical_motion", i) for i, k in enumerate(HELICAL_KEYS)}}


def typed_resolution(x: float) -> float:
    """Half a unit of the last decimal of ``x`` as typed (its shortest repr: ``94.9385``
    -> 5e-5, ``20.0`` -> 0.05); 0 for 0 (a zero is a set-up choice, no offset or no
    tilt, not a rounded value)."""
    if x == 0.0:
        return 0.0
    return 0.5 * 10.0 ** Decimal(repr(float(x))).as_tuple().exponent


def setting(setup: MachineSetup, key: str) -> float:
    """The typed value of ``key`` (a machine, printed-series or blade key); 0 for a
    series term not typed."""
    if key in BLADE or key in PROFILE:
        return getattr(setup.blade, key)
    if key in SERIES:
        name, i = SERIES[key]
        vals = getattr(setup.settings, name)
        return vals[i] if i < len(vals) else 0.0
    return getattr(setup.settings, key)


def moved(setup: MachineSetup, key: str, fn) -> MachineSetup:
    """``setup`` with ``key`` set to ``fn(value)`` (a series term: a typed one); raises
    :class:`~gearcontact.validation.InputRangeError` where the new value is outside the
    key's range."""
    if key in BLADE or key in PROFILE:
        return dataclasses.replace(setup, blade=dataclasses.replace(
            setup.blade, **{key: fn(getattr(setup.blade, key))}))
    if key in SERIES:
        name, i = SERIES[key]
        vals = list(getattr(setup.settings, name))
        vals[i] = fn(vals[i])
        return dataclasses.replace(setup, settings=dataclasses.replace(
            setup.settings, **{name: tuple(vals)}))
    return dataclasses.replace(setup, settings=dataclasses.replace(
        setup.settings, **{key: fn(getattr(setup.settings, key))}))


def full_key(setup: MachineSetup, key: str) -> str:
    """``machine.<member>.<flank>.<key>`` or ``blade.<member>.<flank>.<key>``."""
    table = "blade" if key in BLADE or key in PROFILE else "machine"
    return f"{table}.{setup.member}.{setup.side}.{key}"


def roundings(setup: MachineSetup, source: dict | None, keys=None) -> dict:
    """``{key: half unit}`` of ``keys`` (default: every key whose rounding the check
    propagates, module docstring): ``source``'s (a print's rounding, 0 for a key it does
    not give) or, for None, each typed value's own (:func:`typed_resolution`)."""
    return {k: (source.get(k, 0.0) if source is not None else typed_resolution(setting(setup, k)))
            for k in (keys if keys is not None else (*NUMERIC, *SERIES, *BLADE))}


def typed_keys(setup: MachineSetup) -> list[str]:
    """The keys ``setup`` types: every numeric and blade key (the ratio of roll of a
    formate cut, 0 for no roll, excepted) and the series terms typed."""
    keys = [k for k in (*NUMERIC, *BLADE) if k != "ratio_of_roll" or not setup.settings.formate]
    return keys + [k for k, (name, i) in SERIES.items() if i < len(getattr(setup.settings, name))]


def attributed_keys(setup: MachineSetup) -> list[str]:
    """The keys the attribution of a disagreeing flank moves (:mod:`.slip_attribution`):
    :func:`typed_keys` and the blade's profile keys where moving one alone is well posed:
    a curved blade's (``profile_radius_mm != 0``: a straight blade's radius cannot move
    continuously, ``|r| >= 10 mm``, and its reference then sets nothing) radius and
    reference, and a higher-order term typed non-zero (with its reference)."""
    b = setup.blade
    keys = ["profile_radius_mm"] if b.profile_radius_mm != 0.0 else []
    if b.profile_radius_mm != 0.0 or b.higher_order:
        keys.append("profile_reference_mm")
    keys += [k for k in PROFILE[2:] if getattr(b, k) != 0.0]
    return typed_keys(setup) + keys
