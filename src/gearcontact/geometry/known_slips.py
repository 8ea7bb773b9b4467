"""The known slips of a typed summary sheet, tried on a flank that disagrees with its
blank (:mod:`.blank_check`; docs/machine_settings.md sec. 2, "The check when a pair is
loaded"): a sign word misread (:data:`SLIPS`, the MD read from the crossing point), a
unit (:data:`UNIT_SLIPS`), both on one key (:data:`UNIT_SIGN_SLIPS`), and two slips on
two keys (:func:`pair_slip`). Of the slips under which every value of the flank agrees
the best fit is named, the others listed.

The flank is compared by the caller's ``compare`` (:class:`Compare`: the check's own
comparison), so this module holds the slips and the search only; a candidate
``compare.outside`` shows cannot agree is not compared (docs/machine_settings.md sec. 2,
"The cost of the slip search").
"""

from __future__ import annotations

import math
from itertools import combinations
from typing import Protocol

from ..validation import InputRangeError
from .machine import MODIFIED_ROLL_KEYS, MachineSetup
from .print_words import INCH_MM  # the one inch (a print's unit)
from .typed_settings import full_key, moved, setting

__all__ = ["INCH_MM", "PRINT_UNIT_SLIPS", "SLIPS", "UNIT_SIGN_SLIPS", "UNIT_SLIPS", "Compare",
           "applicable",
           "pair_slip", "single_slip", "slip_fix", "with_slip"]


class Compare(Protocol):
    """``compare(setup, rounding)``: the check's comparison of the flank ``setup`` cuts
    with the blank, a FlankCheck (``agrees``, ``missing``, ``comparisons``): with the
    typed flank's tolerances for ``rounding`` None, else with the tolerances
    re-propagated from the settings' rounding ``{key: half unit}``;
    ``compare.roundings(setup)`` the typed rounding of ``setup``'s keys;
    ``compare.outside(setup, rounding)`` True only where ``compare(setup, rounding)``
    cannot agree, known without its solve (a screen; False when unsure)."""

    def __call__(self, setup: MachineSetup, rounding: dict | None): ...

    def roundings(self, setup: MachineSetup) -> dict: ...

    def outside(self, setup: MachineSetup, rounding: dict | None) -> bool: ...


_SAME = 1e-9                      # a slip that moves a value less than this is no slip
#: The sign slips tried on a flank outside its tolerance: (machine key, the slip, what
#: the sheet word is), docs sec. 2's table; the MD word read from the crossing point
#: (``datum``, :func:`applicable`) is tried after them.
SLIPS = (("blank_offset_mm", lambda x: -x, "blank offset UP / DN"),
         ("sliding_base_mm", lambda x: -x, "sliding base WITH / AWAY"),
         ("cradle_angle_deg", lambda x: -x, "cradle angle sign"),
         ("swivel_deg", lambda x: -x, "swivel sign"),
         ("machine_centre_to_back_mm", lambda x: -x, "machine centre to back MD +-"),
         ("ratio_of_roll", lambda x: 1.0 / x, "ratio of roll, work / cradle against "
                                              "cradle / work"),
         *((k, lambda x: -x, f"modified roll {k.split('_')[2].upper()} sign")
           for k in MODIFIED_ROLL_KEYS))
#: The unit slips (:data:`INCH_MM`), tried with :data:`SLIPS`: (key, the slip, what
#: the slip is): a length typed in inches (x 25.4) or converted twice (/ 25.4), the
#: radial distance typed in metres (x 1000), an angle typed in radians. The words read
#: "with the unit corrected (...)".
UNIT_SLIPS = (*((k, lambda x: x * INCH_MM, "unit corrected (typed in inches: x 25.4 mm)")
                for k in ("radial_distance_mm", "machine_centre_to_back_mm",
                          "sliding_base_mm", "blank_offset_mm", "point_radius_mm")),
              *((k, lambda x: x / INCH_MM, "unit corrected (converted to mm twice: / 25.4)")
                for k in ("radial_distance_mm", "machine_centre_to_back_mm",
                          "sliding_base_mm", "blank_offset_mm", "point_radius_mm")),
              ("radial_distance_mm", lambda x: x * 1000.0,
               "unit corrected (typed in metres: x 1000 mm)"),
              *((k, math.degrees, "unit corrected (typed in radians: to degrees)")
                for k in ("blade_angle_deg", "cradle_angle_deg", "machine_root_angle_deg",
                          "tilt_deg", "swivel_deg")))
#: A unit slip and the sign word of the same key at once (a length typed in inches
#: from a print whose UP / DN, WITH / AWAY or MD word was misread as well), tried with
#: :data:`UNIT_SLIPS`.
UNIT_SIGN_SLIPS = tuple((k, lambda x, fn=fn: -fn(x), f"{word} and the other sign")
                        for k, fn, word in UNIT_SLIPS
                        if k in ("blank_offset_mm", "sliding_base_mm", "cradle_angle_deg",
                                 "machine_centre_to_back_mm"))
_UNIT = (*UNIT_SLIPS, *UNIT_SIGN_SLIPS)
#: The unit slips of a gear typed as a print (``[print.gear]``, lengths in inches,
#: converted to the mm keys x 25.4), tried with :data:`UNIT_SLIPS` where the statement
#: is a print's: the radial typed in metres (``radial_in = 0.1043`` for 4.108 in; its
#: mm key 2.649 mm, which neither x 1000 nor x 25.4 brings to the page's 104.3 mm).
PRINT_UNIT_SLIPS = (("radial_distance_mm", lambda x: x * 1000.0 / INCH_MM,
                     "unit corrected (typed in metres: x 1000 / 25.4 in)"),)


def slip_fix(word: str) -> str:
    """What a slip's word changes: ``"unit"`` (:data:`UNIT_SLIPS`) or ``"sign"``."""
    return "unit" if word.startswith("unit") else "sign"


def with_slip(word: str) -> str:
    """``"with the other <sign word>"`` or ``"with the unit corrected (...)"`` (a word
    of two slips is its own, :func:`_best`)."""
    if word.startswith("with "):
        return word
    return f"with the {word}" if slip_fix(word) == "unit" else f"with the other {word}"



def applicable(setup: MachineSetup, datum: float, *, printed: bool = False) -> list:
    """The slips of :data:`SLIPS`, the MD word read from the crossing point (``datum``:
    the member's pitch apex from the crossing point towards its back, mm; tried where
    non-zero: ``X_D -> 2 datum - X_D``) and :data:`UNIT_SLIPS` / :data:`UNIT_SIGN_SLIPS`
    (and, ``printed``: settings converted from a print, :data:`PRINT_UNIT_SLIPS`) that
    change a typed value of ``setup`` within its range."""
    md = ("machine_centre_to_back_mm", lambda x: 2.0 * datum - x,
          f"MD sign, MD read from the crossing point (X_D = MD {datum:+.4f} mm, the pitch "
          "apex's offset)")
    out = []
    for slip in (*SLIPS, *((md,) if datum != 0.0 else ()), *_UNIT,
                 *(PRINT_UNIT_SLIPS if printed else ())):
        key, fn, _ = slip
        value = setting(setup, key)
        if value == 0.0 and slip is not md or abs(fn(value) - value) <= _SAME:
            continue       # no sign to slip (a ratio 0 is formate), or the slip is no change
        try:
            moved(setup, key, fn)
        except InputRangeError:
            continue
        out.append(slip)
    return out


def _undone(setup: MachineSetup, compare: Compare, slips):
    """The flank (a FlankCheck) with ``slips`` (of distinct keys) undone; a unit slip's
    typed digits were the other unit's, so is their rounding: where the flank reaches
    its mean point but is outside, compared again with it re-propagated (the costly
    part). None where ``compare.outside`` shows it cannot agree under either rounding
    (no solve)."""
    fixed = setup
    for key, fn, _ in slips:
        fixed = moved(fixed, key, fn)
    units = [s for s in slips if _is_unit(s)]
    rounding = None
    if units:
        rounding = compare.roundings(setup)
        for key, fn, _ in units:
            value = setting(setup, key)
            rounding[key] = abs(fn(value + rounding[key]) - fn(value))
    if compare.outside(fixed, None) and (not units or compare.outside(fixed, rounding)):
        return None
    got = compare(fixed, None)
    if units and not got.agrees and not got.missing:
        got = compare(fixed, rounding)
    return got


def _best(setup: MachineSetup, compare: Compare, fixes) -> tuple:
    """``(key, typed value, word, other keys)`` of the fix of ``fixes`` (tuples of
    slips) under which the flank agrees with the blank best (the smallest largest
    difference relative to its tolerance), with the keys of the other fixes under which
    it agrees (a small setting's sign may bring a flank just outside back inside), or
    ``("", None, "", ())``. A fix of two slips is named by its first key, its word
    naming the second."""
    found = []
    for fix in fixes:
        got = _undone(setup, compare, fix)
        if got is not None and got.agrees:
            score = max((abs(c.measured - c.stated) / c.tolerance for c in got.comparisons
                         if c.tolerance), default=0.0)
            names = [full_key(setup, k) for k, _, _ in fix]
            word = fix[0][2] if len(fix) == 1 else (
                f"{with_slip(fix[0][2])}, and {names[1]} {with_slip(fix[1][2])}")
            found.append((score, names[0], setting(setup, fix[0][0]), word,
                          " and ".join(names)))
    if not found:
        return "", None, "", ()
    found.sort(key=lambda x: x[0])
    return (*found[0][1:4], tuple(f[4] for f in found[1:]))


def _is_unit(slip) -> bool:
    """A unit slip (:data:`UNIT_SLIPS`, :data:`UNIT_SIGN_SLIPS`, :data:`PRINT_UNIT_SLIPS`)."""
    return slip in _UNIT or slip in PRINT_UNIT_SLIPS


def single_slip(setup: MachineSetup, datum: float, compare: Compare, *,
                printed: bool = False) -> tuple:
    """``(key, typed value, word, other keys)`` of the single slip (:func:`applicable`;
    ``printed``: settings converted from a print) under which the flank agrees best
    (:func:`_best`), or ``("", None, "", ())``: the sign words first, the unit slips only
    where no sign word explains the flank (each costs a solve from the grid of starts
    where the flank misses: 3x the check's time, docs sec. 2)."""
    slips = applicable(setup, datum, printed=printed)
    got = _best(setup, compare, [(s,) for s in slips if not _is_unit(s)])
    return got if got[0] else _best(setup, compare, [(s,) for s in slips if _is_unit(s)])


def pair_slip(setup: MachineSetup, datum: float, compare: Compare, *,
              printed: bool = False) -> tuple:
    """As :func:`single_slip`, of two slips of distinct keys: a sign word and a sign word
    or a unit slip (two unit slips, and :data:`UNIT_SIGN_SLIPS`, are not paired: ~3
    times the cost, docs sec. 2). The key is the first slip's, the word names the
    second's; the other keys read ``"<key> and <key>"``."""
    slips = [s for s in applicable(setup, datum, printed=printed) if s not in UNIT_SIGN_SLIPS]
    return _best(setup, compare, [(a, b) for a, b in combinations(slips, 2)
                                  if a[0] != b[0] and not (_is_unit(a) and _is_unit(b))])
