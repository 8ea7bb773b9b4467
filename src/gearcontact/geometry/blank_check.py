"""The check of typed machine settings against the blank they are meant to cut: each
flank of a pair cut from machine settings measured at its blank's mean point
(:mod:`.flank_angles`) and compared with what the pair's blank tables state, before any
expensive work (docs/machine_settings.md sec. 2, "The check when a pair is loaded").

A summary sheet typed into ``[machine.*]`` / ``[blade.*]`` (docs sec. 2-3) carries sign
words (UP / DN, WITH / AWAY, MD +-, the cradle angle's sign, the ratio of roll as work /
cradle or cradle / work, the hand); one wrong word cuts a flank that is not the blank's
tooth, and everything downstream is silently wrong. Compared per flank:

- gear flanks (the generating gear in the cradle plane, what a sheet prints,
  :func:`~.flank_angles.measure_generating_angles`): the spiral angle against the
  blank's ``beta_m2``, the pressure angle against the side's, the mean cone distance
  against ``R_m2``; a generated gear's **pitch point** of the generating roll
  (:func:`~.flank_angles.pitch_offset`, what the ratio of roll and the modified roll
  set) against the mean point, within :data:`PITCH_POINT_FRACTION` of the dedendum (a
  model bound);
- pinion flanks: the pressure angle on the pitch cone at the mean point
  (:func:`~.flank_angles.measure_mean_point`) against the blank's of the side, within
  the typed rounding plus :data:`PINION_PRESSURE_DEG` (a model bound: the settings cut
  the mismatch, not the blank's tooth);
- every flank: the hand on its pitch cone against the blank's, and the **root datum**:
  the depth behind the cutter's tip plane of the blade point that cuts the mean point
  against the blank's mean dedendum (the blade tips cut the root, so the mean point lies
  a dedendum behind the tip plane, up to the spread of a slot and a tilted cutter),
  which sees the sliding base and the machine
  centre to back; a root datum shallower than the dedendum by more than the blank's
  clearance beyond its tolerance lies above the mate's tip (a gross mismatch, docs sec.
  2, "A root above the mating tip");
- a flank that does not reach its mean point is a reported result.

Tolerances: the typed settings' rounding propagated (each non-zero setting moved by half
a unit of its last typed decimal, the changes of the measured value summed: the worst
case to first order, as tests/geometry/test_flank_angles.py propagates a print's
rounding), plus the stated value's own rounding (0 for a pair's blank: its values are
the design's definitions), plus the solve's 1e-7; the root datum adds
:data:`ROOT_DATUM_FRACTION` of the dedendum (a model bound, not a rounding). A flank
outside its tolerance is tried against the known slips (:mod:`.known_slips`: the sign
words, the unit slips with the typed rounding in the other unit, both on one key, the
MD word read from the crossing point; and the blank's hand): of the slips under which
every value of the flank agrees the best fit is named, the others listed. Where none
does, the keys that alone make it agree are named with the values the blank needs
(:mod:`.slip_attribution`); where none does either, two slips on two keys are tried.
A slip's candidate on a gear flank whose closed-form generating spiral angle or mean
cone distance is outside its tolerance is not solved (:meth:`_Compare.outside`: it
cannot agree; docs sec. 2, "The cost of the slip search").

References
----------
docs/machine_settings.md sec. 2 (sign conventions; the published sheet), sec. 3.
"""

from __future__ import annotations

import dataclasses
import re

from ..validation import InputRangeError
from .blank_statement import StatedBlank, printed_stated_blank, stated_blank
from .blank_verdict import (GROSS_FACE_QUANTITY, GROSS_ROOT_QUANTITY, BlankCheck, Comparison,
                            FlankCheck)
from .conjugate import UndercutError
from .flank_angles import (FlankMeanPoint, GeneratingGearAngles, generating_circle,
                           measure_generating_angles, measure_mean_point, require_machine)
from ..deprecation import moved_names
from .known_slips import pair_slip, single_slip
from .machine import MachineSetup
from .print_blank import print_key
from .slip_attribution import explaining_values
from .typed_settings import attributed_keys, full_key, moved, roundings, setting

__all__ = ["GROSS_CONE_FACE_FRACTION", "GROSS_PRESSURE_DEG", "GROSS_SPIRAL_DEG", "PINION_PRESSURE_DEG",
           "PITCH_POINT_FRACTION", "ROOT_DATUM_FRACTION", "SCREEN_MARGIN",
           "check_flanks", "check_pair_blank"]
__getattr__ = moved_names(__name__, {
    "typed_resolution": "gearcontact.geometry.typed_settings:typed_resolution",
    **{n: f"gearcontact.geometry.known_slips:{n}" for n in ("INCH_MM", "SLIPS", "UNIT_SLIPS")}})

#: A gear flank whose generating spiral angle differs from the blank's by more than
#: this (deg) is an input error (exit 2), as is a hand against the blank's: no
#: correction moves a spiral angle by degrees (the reasons and the measured slips:
#: docs/machine_settings.md sec. 2).
GROSS_SPIRAL_DEG = 3.0
#: The root datum's model bound, a fraction of the blank's mean dedendum (what the
#: spread of a slot, a tilted cutter and a fitted pinion leave, measured in
#: docs/machine_settings.md sec. 2).
ROOT_DATUM_FRACTION = 0.1
#: The generated gear's pitch point of generation (:func:`~.flank_angles.pitch_offset`,
#: 0 where the roll is the blank's): its model bound, a fraction of the blank's mean
#: dedendum (a hypoid gear's generating gear with a blank offset, and one ratio of roll
#: for both flanks of a spread slot, leave it off the mean point; measured in
#: docs/machine_settings.md sec. 2).
PITCH_POINT_FRACTION = 0.1
#: A pinion flank's pressure angle at its mean point (on its pitch cone) against the
#: blank's of its side: the model bound (deg) added to the typed rounding propagated.
#: The settings cut the mismatch, not the blank's tooth: a standard hypoid pinion's
#: angles at the mean point differ from its mate's by up to about 1 deg, and a pinion
#: fitted to a target (docs/machine_settings.md sec. 6) moves its blade by degrees; a
#: blade angle typed in radians (20 deg -> 0.349) moves it by about 20 deg. Declared
#: before the margins were measured (docs sec. 2).
PINION_PRESSURE_DEG = 5.0
#: A pressure angle (either member) off the blank's by more than this (deg) is an input
#: error (exit 2), as a spiral angle past :data:`GROSS_SPIRAL_DEG`: no correction or
#: mismatch moves a pressure angle by 10 deg, a unit slip (radians) does. Declared with
#: :data:`PINION_PRESSURE_DEG`.
GROSS_PRESSURE_DEG = 10.0
#: A gear flank's generating mean cone distance off the blank's by more than this
#: fraction of the gear face width is an input error (exit 2): the generating gear's
#: mean point then lies off the gear's face (the blank's own extent along the cone), so
#: the flank is not the blank's tooth. No correction or rounding moves it by a
#: millimetre (the largest deviation measured on a typed sheet, a radial distance with
#: a digit misread, 0.30 mm on a 31.75 mm face), a unit slip does (a machine root angle
#: in radians: 146 mm on F.2's 25.4 mm face). Declared in docs/machine_settings.md sec.
#: 2, "A mean point off the face".
GROSS_CONE_FACE_FRACTION = 0.5
#: A slip's candidate on a gear flank is screened out without a solve where its closed-
#: form spiral angle or mean cone distance is outside its tolerance by more than this
#: fraction of it (:meth:`_Compare.outside`; the same floats as the solved comparison,
#: so the margin only keeps a tie on the solved side; docs/machine_settings.md sec. 2,
#: "The cost of the slip search").
SCREEN_MARGIN = 1e-9
_GROSS = {"spiral angle": GROSS_SPIRAL_DEG, "pressure angle": GROSS_PRESSURE_DEG}
_FLOOR = 1e-7                     # the solve's resolution, deg / mm (flank_angles)


def _values(setup: MachineSetup, stated: StatedBlank, start=None) -> tuple[dict, object]:
    """``({quantity: value}, start)`` of one flank at its mean point; raises
    UndercutError where it does not reach it."""
    m = setup.member
    cone = dict(pitch_angle_deg=stated.pitch_angle_deg[m],
                cone_distance_mm=stated.mean_cone_distance_mm[m], start=start)
    if m == "gear":
        return _quantities(measure_generating_angles(
            setup, **cone, cutter_radius_mm=stated.cutter_radius_mm))
    return _quantities(measure_mean_point(setup, **cone))


def _quantities(measured) -> tuple[dict, object]:
    """``({quantity: value}, pitch-cone solution)`` of a gear flank's
    :class:`~.flank_angles.GeneratingGearAngles` or a pinion flank's
    :class:`~.flank_angles.MeanPointAngles`."""
    if isinstance(measured, GeneratingGearAngles):
        at = measured.pitch_cone
        values = {"spiral angle": measured.spiral_angle_deg,
                  "pressure angle": measured.pressure_angle_deg,
                  "mean cone distance": measured.cone_distance_mm}
        if measured.pitch_offset_mm is not None:
            values["pitch point"] = measured.pitch_offset_mm
    else:
        at, values = measured, {"pressure angle": measured.pressure_angle_deg}
    values["root depth"] = at.depth_mm
    values["hand"] = at.hand
    return values, at


_UNITS = {"spiral angle": "deg", "pressure angle": "deg", "mean cone distance": "mm",
          "pitch point": "mm", "root depth": "mm", "hand": ""}
_STATED_ROUNDING = {"spiral angle": "spiral_angle_deg", "pressure angle": "pressure_angle_deg",
                    "mean cone distance": "cone_distance_mm"}


def _tolerances(setup: MachineSetup, stated: StatedBlank, values: dict, at,
                measure=None) -> dict:
    """The typed settings' rounding propagated (module docstring), per quantity of
    ``values``: each typed key moved by its half unit, up, or down where up leaves the
    key's range (a value typed at its limit: the range error would name a value nobody
    typed); each move measured by ``measure(setup, stated, at)`` (``({quantity: value},
    solution)``; :func:`_values` by default)."""
    measure = measure or _values
    tol = {q: _FLOOR + stated.rounding.get(_STATED_ROUNDING.get(q, ""), 0.0)
           for q in values if q != "hand"}
    moves = [(k, r) for k, r in roundings(setup, stated.setting_rounding).items() if r > 0.0]
    if setup.member == "gear":
        r_c = stated.rounding.get("cutter_radius_mm", 0.0)
        if r_c > 0.0:
            moves.append(("cutter_radius_mm", r_c))
    for key, r in moves:
        if key == "cutter_radius_mm":
            shifted = setup, dataclasses.replace(stated,
                                                 cutter_radius_mm=stated.cutter_radius_mm + r)
        else:
            try:
                shifted = moved(setup, key, lambda x, r=r: x + r), stated
            except InputRangeError:     # typed at the top of its range: round the other way
                shifted = moved(setup, key, lambda x, r=r: x - r), stated
        try:
            got, _ = measure(*shifted, at)
        except UndercutError:       # the warm start lost the point: the full solve
            got, _ = measure(*shifted)
        for q in tol:
            tol[q] += abs(got[q] - values[q])
    if "root depth" in tol:
        tol["root depth"] += ROOT_DATUM_FRACTION * stated.dedendum_mm[setup.member]
    if setup.member == "pinion" and "pressure angle" in tol:
        tol["pressure angle"] += PINION_PRESSURE_DEG
    if "pitch point" in tol:
        tol["pitch point"] += PITCH_POINT_FRACTION * stated.dedendum_mm[setup.member]
    return tol


def _stated_values(member: str, side: str, stated: StatedBlank, hand: str | None = None) -> dict:
    gear = member == "gear"
    other = {"right": "left", "left": "right"}
    hand = hand or stated.gear_hand
    out = {"spiral angle": stated.spiral_angle_gear_deg,
           "pressure angle": stated.pressure_angle_deg[side],
           "mean cone distance": stated.mean_cone_distance_mm["gear"],
           "pitch point": 0.0} if gear else {"pressure angle": stated.pressure_angle_deg[side]}
    out["root depth"] = stated.dedendum_mm[member]
    out["hand"] = hand if gear else other[hand]
    return out


def _remembered(setup: MachineSetup, stated: StatedBlank, memo: dict | None):
    """:func:`_values` of ``setup`` (from the grid of starts), kept in ``memo`` (what it
    raised as well) for a second comparison of the same set-up object against a
    statement that differs in its rounding only (a unit slip's re-propagated tolerance,
    :class:`_Compare`: the rounding does not enter the measurement)."""
    if memo is not None and memo.get("setup") is setup:
        got = memo["got"]
    else:
        try:
            got = _values(setup, stated)
        except (UndercutError, InputRangeError) as exc:
            got = exc
        if memo is not None:
            memo.update(setup=setup, got=got)
    if isinstance(got, Exception):
        raise got
    return got


def _compare(setup, stated, tol=None, hand=None, measured: FlankMeanPoint | None = None,
             start=None, memo: dict | None = None):
    """``(FlankCheck without slip, tolerances)``; tolerances of a flank that does not
    reach its mean point: None. ``measured``: the flank already measured at the same
    mean point (:func:`~.flank_angles.measure_pair_mean_points`), else it is measured
    (from ``start``, a nearby flank's solution, when given; else kept in ``memo``,
    :func:`_remembered`)."""
    where = (f"the blank's mean point (cone distance "
             f"{stated.mean_cone_distance_mm[setup.member]:.4f} mm on the pitch cone)")
    reached, circle = True, None
    if measured is None:
        try:
            values, at = (_values(setup, stated, start) if start is not None or memo is None
                          else _remembered(setup, stated, memo))
        except UndercutError:
            reached = False
        except InputRangeError as exc:
            if exc.field != "cutter_radius_mm":
                raise
            circle = exc.allowed
    elif measured.pitch_cone is None:
        reached = False
    elif setup.member == "gear" and measured.generating_gear is None:
        circle = measured.cutter_circle
    else:
        values, at = _quantities(measured.generating_gear or measured.pitch_cone)
    if not reached:
        return FlankCheck(setup.member, setup.side, (),
                          missing=f"the flank does not reach {where}"), tol
    if circle is not None:
        return FlankCheck(setup.member, setup.side, (), missing=(
            f"[cutter] radius_mm = {stated.cutter_radius_mm:g}: its circle does not cross "
            f"the root line of the settings ({circle})")), tol
    try:
        tol = tol if tol is not None else _tolerances(setup, stated, values, at)
    except UndercutError:
        return FlankCheck(setup.member, setup.side, (), missing=(
            f"the flank reaches {where} only at the edge: a setting moved by its typed "
            "rounding loses it")), tol
    want = _stated_values(setup.member, setup.side, stated, hand)
    rows = tuple(Comparison(q, _UNITS[q], values[q], want[q], tol.get(q),
                            _gross_bound(q, stated, tol.get(q))) for q in values)
    return FlankCheck(setup.member, setup.side, rows), tol


def _gross_bound(quantity: str, stated: StatedBlank, tol: float | None = None
                 ) -> float | None:
    """The :attr:`Comparison.gross_bound` of ``quantity`` against ``stated`` (``tol``:
    its tolerance; the root datum's bound is the clearance beyond it, docs sec. 2, "A
    root above the mating tip")."""
    if quantity == GROSS_FACE_QUANTITY:
        face = stated.gear_face_width_mm
        return None if face is None else GROSS_CONE_FACE_FRACTION * face
    if quantity == GROSS_ROOT_QUANTITY:
        c = stated.clearance_mm
        return None if c is None or tol is None else c + tol
    return _GROSS.get(quantity)


def _circle(setup: MachineSetup, stated: StatedBlank, start=None) -> tuple[dict, None]:
    """``({quantity: value}, None)``: a gear flank's generating spiral angle and mean cone
    distance, closed form in the settings (:func:`~.flank_angles.generating_circle`, the
    values :func:`_values` measures; ``start`` unused: no solve)."""
    spiral, cone, _ = generating_circle(setup, pitch_angle_deg=stated.pitch_angle_deg["gear"],
                                        cone_distance_mm=stated.mean_cone_distance_mm["gear"],
                                        cutter_radius_mm=stated.cutter_radius_mm)
    return {"spiral angle": spiral, "mean cone distance": cone}, None


def _reach(setup: MachineSetup, stated: StatedBlank, f: FlankCheck) -> FlankCheck:
    """``f`` with :attr:`~.blank_verdict.FlankCheck.reach`: a gear flank that does not
    reach its mean point compared in closed form (:func:`_circle`: its generating gear's
    spiral angle and mean cone distance, the tolerance propagated in closed form as
    :meth:`_Compare.outside` does), with the gross bounds (docs sec. 2, "A mean point not
    reached"); ``f`` itself for a pinion, a flank with values, or a cutter circle that
    misses the root line (its ``missing`` says so)."""
    if setup.member != "gear" or not f.missing:
        return f
    try:
        values, _ = _circle(setup, stated)
    except InputRangeError:
        return f
    try:
        tol = _tolerances(setup, stated, values, None, measure=_circle)
    except InputRangeError:      # a move of the rounding loses the circle: the solve's floor
        tol = {q: _FLOOR for q in values}
    want = _stated_values("gear", setup.side, stated)
    return dataclasses.replace(f, reach=tuple(
        Comparison(q, _UNITS[q], values[q], want[q], tol[q], _gross_bound(q, stated))
        for q in values))


class _Compare:
    """The check's comparison of one flank (:class:`~.known_slips.Compare`);
    ``screened``: :meth:`outside` screens gear candidates without a solve (False: it
    screens nothing, and a unit slip's second comparison measures again: the unpruned
    search, the reference of tests/geometry/test_slip_screen.py)."""

    def __init__(self, stated: StatedBlank, tol, *, screened: bool = True):
        self.stated, self.tol, self.screened = stated, tol, screened
        self._memo = {} if screened else None

    def __call__(self, setup: MachineSetup, rounding: dict | None) -> FlankCheck:
        if rounding is None:
            return _compare(setup, self.stated, self.tol, memo=self._memo)[0]
        return _compare(setup, dataclasses.replace(self.stated, setting_rounding=rounding),
                        memo=self._memo)[0]

    def roundings(self, setup: MachineSetup) -> dict:
        return roundings(setup, self.stated.setting_rounding)

    def outside(self, setup: MachineSetup, rounding: dict | None) -> bool:
        """True where ``self(setup, rounding)`` cannot agree, known without a solve: a
        gear flank's generating spiral angle or mean cone distance (closed form,
        :func:`_circle`) outside the tolerance the comparison would use (the typed
        flank's, else re-propagated in closed form as :func:`_tolerances` does from the
        solved values), by more than :data:`SCREEN_MARGIN` of it, or its cutter circle
        not crossing the root line (the comparison's ``missing``). False for a pinion
        flank and whenever unsure (a move of the re-propagation out of the circle)."""
        if not self.screened or setup.member != "gear":
            return False
        try:
            values, _ = _circle(setup, self.stated)
        except InputRangeError:
            return True            # the circle misses: the comparison's `missing`
        stated = (self.stated if rounding is None
                  else dataclasses.replace(self.stated, setting_rounding=rounding))
        tol = self.tol if rounding is None else None
        if tol is None:
            try:
                tol = _tolerances(setup, stated, values, None, measure=_circle)
            except InputRangeError:
                return False
        want = _stated_values("gear", setup.side, stated)
        return any(abs(values[q] - want[q]) > tol[q] * (1.0 + SCREEN_MARGIN) for q in values)


def _single_keys(setup: MachineSetup, stated: StatedBlank, tol, flank: FlankCheck) -> tuple:
    """The keys of ``setup``'s tables that alone explain ``flank``, which disagrees
    (:func:`~.slip_attribution.explaining_values`; the typed tolerances ``tol``);
    ``()`` for a flank that does not reach its mean point."""
    if flank.missing:
        return ()
    _, at = _values(setup, stated)              # the warm start of every move
    keys = attributed_keys(setup)
    half = roundings(setup, stated.setting_rounding, keys)

    def compare(name: str, value: float):
        key = name.rsplit(".", 1)[1]
        try:
            other = moved(setup, key, lambda _: value)
            got, _ = _compare(other, stated, tol, start=at)
            if got.missing:         # the warm start lost the point: the grid of starts
                got, _ = _compare(other, stated, tol)
        except InputRangeError:
            return None
        return None if got.missing else got.comparisons

    return explaining_values([(full_key(setup, k), setting(setup, k), half[k])
                              for k in keys], flank.comparisons, compare)


_CONVERTED = re.compile(r"\b(?:machine|blade)\.gear\.(?:drive|coast)\.\w+")


def _print_named(f: FlankCheck, printed: tuple) -> FlankCheck:
    """``f`` with the keys its slips and single keys name renamed to the print's keys as
    typed (:func:`~.print_blank.print_key`: ``machine.gear.coast.blank_offset_mm`` ->
    ``print.gear.blank_offset``, the value the print's text); a single key keeps its
    converted name beside (its values are the converted unit's)."""
    table = dict(printed)

    def name(text: str) -> str:
        return _CONVERTED.sub(lambda m: (print_key(m.group(0), table) or (m.group(0),))[0], text)

    got = print_key(f.slip, table) if f.slip else None
    return dataclasses.replace(
        f, printed=True, slip=got[0] if got else f.slip, slip_value=got[1] if got else f.slip_value,
        slip_word=name(f.slip_word), slip_also=tuple(name(k) for k in f.slip_also),
        single_keys=tuple(dataclasses.replace(k, key=f"{name(k.key)} (converted: {k.key})")
                          if print_key(k.key, table) else k for k in f.single_keys),
        typed=tuple(dict(print_key(k, table) or (k, v) for k, v in f.typed).items()))


def check_flanks(setups, stated: StatedBlank, *, measured=None,
                 member_stated: dict | None = None, screened: bool = True) -> BlankCheck:
    """Each flank of ``setups`` (:class:`~.machine.MachineSetup`) at its mean point
    against ``stated`` (module docstring): the comparisons, with the likely sign slip of
    a flank that does not agree. ``measured``: the flanks already measured at the
    stated mean points, one :class:`~.flank_angles.FlankMeanPoint` per set-up
    (:func:`~.flank_angles.measure_pair_mean_points`, what ``design`` prints), else
    each is measured here. ``member_stated``: ``{member: StatedBlank}``
    (:mod:`.blank_statement`), a member's flanks against a statement of their own (a
    gear typed as a print: :func:`~.blank_statement.printed_stated_blank`; measured here
    at its mean point, its slips named by the print's keys); ``stated`` is the others',
    and its hand key names a hand slip. ``screened``: the slips' candidates on a gear
    flank screened without a solve (:meth:`_Compare.outside`; False: every candidate
    solved, the same result at a higher cost, docs sec. 2, "The cost of the slip
    search")."""
    measured = measured if measured is not None else (None,) * len(setups)
    if len(measured) != len(setups):
        raise InputRangeError("measured", len(measured),
                              f"one measured flank per set-up ({len(setups)})")
    own = member_stated or {}
    states = [own.get(s.member, stated) for s in setups]
    first = [_compare(s, st, measured=None if s.member in own else m)
             for s, st, m in zip(setups, states, measured)]
    bad = [f for f, _ in first if not f.agrees]
    flipped = {"right": "left", "left": "right"}
    hand_slip = bool(bad) and len(bad) == len(first) and all(
        _compare(s, st, tol, flipped[st.gear_hand])[0].agrees
        for s, st, (_, tol) in zip(setups, states, first))
    out = []
    for s, st, (f, tol) in zip(setups, states, first):
        f = _reach(s, st, f)
        if not f.agrees and not hand_slip:
            datum = st.mctb_datum_mm.get(s.member, 0.0)
            compare = _Compare(st, tol, screened=screened)
            key, value, word, also = single_slip(s, datum, compare, printed=bool(st.printed))
            f = dataclasses.replace(f, slip=key, slip_value=value, slip_word=word,
                                    slip_also=also)
            if not key:
                f = dataclasses.replace(f, single_keys=_single_keys(s, st, tol, f))
            if not key and not f.single_keys:
                key, value, word, also = pair_slip(s, datum, compare,
                                                   printed=bool(st.printed))
                f = dataclasses.replace(f, slip=key, slip_value=value, slip_word=word,
                                        slip_also=also, typed=() if key else tuple(
                                            (full_key(s, k), setting(s, k)) for k in attributed_keys(s)))
        if st.printed:
            f = _print_named(f, st.printed)
        out.append(f)
    return BlankCheck(tuple(out), stated, hand_slip)


def check_pair_blank(pair, *, measured=None) -> BlankCheck:
    """:func:`check_flanks` of a pair cut from machine settings against its own blank
    tables (:func:`~.blank_statement.stated_blank`), a gear typed as a print
    (``[print.gear]``) against what its page prints
    (:func:`~.blank_statement.printed_stated_blank`); ``measured``: the pair's
    :func:`~.flank_angles.measure_pair_mean_points`, when already measured (a printed
    gear's flanks are measured again, at the print's mean point).

    Raises
    ------
    InputRangeError
        A pair without machine settings.
    """
    require_machine(pair)
    printed = printed_stated_blank(pair)
    return check_flanks(pair.machine, stated_blank(pair), measured=measured,
                        member_stated=None if printed is None else {"gear": printed})
