"""The verdict of the blank check (:mod:`.blank_check`): each measured quantity against
the blank's (:class:`Comparison`), each flank's comparisons and the slip found for it
(:class:`FlankCheck`), and all flanks (:class:`BlankCheck`) with the refusal of a gross
mismatch and the warning lines, in the words of the pair file (docs/machine_settings.md
sec. 2).

Examples
--------
>>> from gearcontact.geometry.blank_verdict import Comparison
>>> c = Comparison("mean cone distance", "mm", 227.0645, 81.2730, 0.00097, 12.7)
>>> c.within, c.gross
(False, True)
"""

from __future__ import annotations

from dataclasses import dataclass

from ..validation import InputRangeError
from .blank_statement import StatedBlank
from .known_slips import slip_fix, with_slip
from .slip_attribution import describe, interval

__all__ = ["GROSS_FACE_QUANTITY", "GROSS_ROOT_QUANTITY", "BlankCheck", "Comparison", "FlankCheck", "slip_renamed"]

#: The quantity whose gross bound is a fraction of the gear face
#: (:data:`~.blank_check.GROSS_CONE_FACE_FRACTION`).
GROSS_FACE_QUANTITY = "mean cone distance"
#: The quantity whose gross bound is one-sided: a root datum shallower than the stated
#: dedendum by more than the clearance plus its tolerance lies above the mate's tip
#: (docs/machine_settings.md sec. 2, "A root above the mating tip"); deeper is no gross
#: mismatch.
GROSS_ROOT_QUANTITY = "root depth"


@dataclass(frozen=True)
class Comparison:
    """One measured value against the stated one: ``quantity``, ``unit``, ``measured``,
    ``stated``, ``tolerance`` (None for the hand) and ``within``; ``gross_bound``: the
    difference beyond which the flank is not the blank's tooth (an input error,
    :attr:`gross`; for :data:`GROSS_ROOT_QUANTITY` a root datum below the stated one
    only), None where there is none."""

    quantity: str
    unit: str
    measured: float | str
    stated: float | str
    tolerance: float | None
    gross_bound: float | None = None

    @property
    def within(self) -> bool:
        if self.tolerance is None:
            return self.measured == self.stated
        return abs(self.measured - self.stated) <= self.tolerance

    @property
    def gross(self) -> bool:
        """Outside: a hand against the blank's, a value off by more than
        :attr:`gross_bound`."""
        if self.within:
            return False
        if self.tolerance is None:
            return True
        off = self.measured - self.stated
        if self.quantity == GROSS_ROOT_QUANTITY:
            off = min(off, 0.0)           # one-sided: a root shallower than the blank's
        return self.gross_bound is not None and abs(off) > self.gross_bound


@dataclass(frozen=True)
class FlankCheck:
    """One flank: its comparisons, ``missing`` (why there are none: the flank does not
    reach its mean point, "" otherwise), ``slip`` (the key of the sign slip under which
    it agrees best, "" when none or when it agrees), ``slip_value``, ``slip_word`` and
    ``slip_also`` (the keys of the other slips under which it agrees, best first);
    ``single_keys``: where no known slip explains it, the keys that alone do, with the
    values the blank needs (:class:`~.slip_attribution.KeyValue`, ranked); ``printed``:
    the flank's settings were converted from ``[print.gear]`` and compared with the
    page's printed blank (:func:`~.blank_statement.printed_stated_blank`), its keys the
    print's; ``typed``: where neither a slip nor a single key explains it, its typed keys and
    values ``((full key, value), ...)``, what a refusal names; ``reach``: a gear flank that
    does not reach its mean point, its generating gear's spiral angle and mean cone
    distance in closed form (:func:`~.flank_angles.generating_circle`, which needs no
    point of the flank) against the blank's, with their gross bounds (docs sec. 2, "A
    mean point not reached")."""

    member: str
    side: str
    comparisons: tuple
    missing: str = ""
    slip: str = ""
    slip_value: float | str | None = None
    slip_word: str = ""
    slip_also: tuple = ()
    single_keys: tuple = ()
    printed: bool = False
    typed: tuple = ()
    reach: tuple = ()

    @property
    def agrees(self) -> bool:
        return not self.missing and all(c.within for c in self.comparisons)

    @property
    def gross(self) -> bool:
        """The hand against the blank's, a spiral angle off by more than
        :data:`~.blank_check.GROSS_SPIRAL_DEG`, a pressure angle by more than :data:`~.blank_check.GROSS_PRESSURE_DEG`,
        a gear's mean cone distance by more than :data:`~.blank_check.GROSS_CONE_FACE_FRACTION` of
        the face or a root datum above the mating tip (:data:`GROSS_ROOT_QUANTITY`) (:attr:`Comparison.gross`; of a flank that does not reach its mean point,
        its generating gear's in closed form, :attr:`reach`); or a flank that does not
        reach its mean point and that a unit slip of one key makes agree (:attr:`slip`, a
        unit word: the typed value a unit factor from one that cuts the blank's tooth;
        docs sec. 2, "A mean point not reached")."""
        return (any(c.gross for c in self.comparisons + self.reach)
                or bool(self.missing and self.slip and slip_fix(self.slip_word) == "unit"))


@dataclass(frozen=True)
class BlankCheck:
    """All flanks (:class:`FlankCheck`); ``hand_slip``: every flank agrees once the
    stated hand is the other (the key then is ``stated.hand_key``)."""

    flanks: tuple
    stated: StatedBlank
    hand_slip: bool = False

    @property
    def agrees(self) -> bool:
        return all(f.agrees for f in self.flanks)

    @property
    def gross(self) -> bool:
        return any(f.gross for f in self.flanks)

    def raise_if_gross(self) -> None:
        """:class:`~gearcontact.validation.InputRangeError` naming the likely key for a
        gross mismatch (module docstring), else nothing."""
        if not self.gross:
            return
        bad = [f for f in self.flanks if f.gross]
        what = "; ".join(f"{f.member} {f.side}: {_describe(f)}" for f in bad)
        if self.hand_slip:
            raise InputRangeError(self.stated.hand_key, self.stated.hand_value,
                                  f"the hand the machine settings cut ({what}; every flank "
                                  "agrees with the other hand, docs/machine_settings.md "
                                  "sec. 2)")
        f = next((f for f in bad if f.slip), bad[0])
        if f.slip:
            also = list(dict.fromkeys(g.slip for g in bad if g.slip and g.slip != f.slip))
            raise InputRangeError(f.slip, f.slip_value,
                                  f"the {slip_fix(f.slip_word)} that cuts {_blank(f)}'s "
                                  f"tooth ({what}; {with_slip(f.slip_word)} the flank agrees "
                                  f"with {_blank(f)}" + _also(f)
                                  + (f"; also {', '.join(also)}" if also else "")
                                  + ", docs/machine_settings.md sec. 2)")
        one = f.single_keys[0] if f.single_keys else None
        table = "print.gear" if f.printed else f"machine.{f.member}.{f.side}"
        raise InputRangeError(one.key if one else f"[{table}]",
                              one.typed if one else dict(f.typed),
                              (f"{interval(one)} (this key alone moved), or " if one else "")
                              + f"settings that cut {_blank(f)}'s tooth ({what}; no known sign "
                              "or unit slip explains it" + "".join(
                                  f"; {g.member} {g.side}: {describe(g.single_keys)}"
                                  for g in bad if not g.missing)
                              + ", docs/machine_settings.md sec. 2)")

    def warnings(self) -> list[str]:
        """One line per flank outside its tolerance, naming the likely key."""
        out = []
        for f in self.flanks:
            if f.agrees:
                continue
            key = self.stated.hand_key if self.hand_slip else f.slip
            word = "hand" if self.hand_slip else f.slip_word
            hint = (f"; likely {key} ({with_slip(word)} the flank agrees)" if key
                    else "; no known sign or unit slip explains it" + (
                        "" if f.missing else f"; {describe(f.single_keys)}"))
            if key and not self.hand_slip:
                hint += _also(f)
            table = "print.gear" if f.printed else f"machine.{f.member}.{f.side}"
            out.append(f"warning: the {f.member} {f.side} flank cut from [{table}] does not "
                       f"agree with {_blank(f)}: {_describe(f)}{hint} "
                       "(docs/machine_settings.md sec. 2)")
        return out


def slip_renamed(exc: InputRangeError, check, *, failed: str) -> InputRangeError:
    """``exc`` (raised by the work ``failed`` names) renamed to the likely slip of the
    first flank of ``check`` (a :class:`BlankCheck`) that does not agree with its blank:
    its key and value as typed, and the slip's words (the unit or sign under which the
    flank agrees), else its table. The library's check names a blade edge round's
    refusal so (:func:`~.settings_check.check_settings`), the command line the failures
    of the work after it (``cli.settings_slip``).
    ``exc`` unchanged where every flank agrees, or where ``exc`` names a key of the check
    already (its own refusal of a gross mismatch)."""
    bad = [f for f in check.flanks if not f.agrees] if check is not None else []
    if not bad:
        return exc
    # the check's own refusal names a key it found (its slip, another slip, one of the
    # single keys of a flank that two keys explain, the hand): unchanged
    named = {k for f in bad for k in (f.slip, *f.slip_also, *(kv.key for kv in f.single_keys))}
    if exc.field in named | {check.stated.hand_key}:
        return exc
    f = next((f for f in bad if f.slip), bad[0])
    table = "print.gear" if f.printed else f"machine.{f.member}.{f.side}"
    field, value = (f.slip, f.slip_value) if f.slip else (f"[{table}]", dict(f.typed) or "table")
    return InputRangeError(field, value, (
        f"settings that cut their blank's tooth: the {f.member} {f.side} flank does not "
        f"agree with its blank (the warning above; likely {f.slip or table}"
        + (f", {with_slip(f.slip_word)} the flank agrees" if f.slip else "") + f"), and {failed} "
        f"failed on it ({exc.field} = {exc.value!r}: {exc.allowed}); "
        "docs/machine_settings.md sec. 2"))


def _also(f: FlankCheck) -> str:
    """``"; it agrees as well with the other sign of <keys>"`` (the slips of two keys:
    ``"with the slips of <key> and <key>, ..."``), or ""."""
    if not f.slip_also:
        return ""
    what = "slips of" if f.slip_word.startswith("with ") else "other sign of"
    return f"; it agrees as well with the {what} {', '.join(f.slip_also)}"


def _blank(f: FlankCheck) -> str:
    """What ``f`` was compared with: ``"the blank"`` or (a gear typed as a print) ``"the
    printed blank"``."""
    return "the printed blank" if f.printed else "the blank"


def _describe(f: FlankCheck) -> str:
    """The values of ``f`` outside their tolerance; of a flank that does not reach its
    mean point, why, and its generating gear's gross values in closed form
    (:attr:`FlankCheck.reach`; none where none is gross: a warning's words as before)."""
    if f.missing:
        gross = [c for c in f.reach if c.gross]
        return f.missing + (f"; its generating gear's {_rows(f, gross)}" if gross else "")
    return _rows(f, [c for c in f.comparisons if not c.within])


def _rows(f: FlankCheck, rows) -> str:
    """``"<quantity> <measured> <unit>, the blank's <stated> (tolerance ...)"``, joined."""
    return ", ".join(
        f"{c.quantity} {c.measured}, {_blank(f)}'s {c.stated}" if c.tolerance is None else
        f"{c.quantity} {c.measured:.4f} {c.unit}, {_blank(f)}'s {c.stated:.4f} (tolerance "
        f"{c.tolerance:.2g}{_gross_words(c)})" for c in rows)


def _gross_words(c: Comparison) -> str:
    """``"; off the gear's face, <from> to <to> mm"`` for a gross mean cone distance,
    ``"; above the mating tip: ..."`` for a gross root datum, else ""."""
    if not c.gross or c.quantity not in (GROSS_FACE_QUANTITY, GROSS_ROOT_QUANTITY):
        return ""
    if c.quantity == GROSS_ROOT_QUANTITY:
        clearance = c.gross_bound - c.tolerance
        return (f"; the root above the mating tip, which runs {c.stated - clearance:.4f} "
                f"{c.unit} deep (the dedendum less the clearance {clearance:.4f} "
                f"{c.unit}): shallower than {c.stated - c.gross_bound:.4f} {c.unit} the "
                "pair cannot mesh")
    return (f"; off the gear's face, {c.stated - c.gross_bound:.4f} to "
            f"{c.stated + c.gross_bound:.4f} {c.unit}")
