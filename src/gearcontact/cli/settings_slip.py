"""Typed machine settings that do not cut their blank, named by their likely slip where
the work on them fails: the typed-settings check (docs/machine_settings.md sec. 2, "The
check when a pair is loaded") finds a flank off its blank and the likely key (a sign
word, a unit), but a gross mismatch alone is refused; any other is a warning, and the
flank work after it (the ease-off shape's flanks, a kept gear's standard pinion) can fail
first on a key the user never typed (a derived blade, an envelope node, a correct point
radius). Such an input error is renamed here to the check's slip, the failure kept in
the message."""

from __future__ import annotations

import sys

from ..geometry.blank_verdict import slip_renamed  # the one renaming, also the library's
from ..geometry.formate import SIDES
from ..validation import InputRangeError

__all__ = ["slip_renamed", "checked_blank_named", "checked_typed_gear", "work_slip_renamed"]


def work_slip_renamed(exc, args, command: str):
    """``exc`` (a :class:`~gearcontact.errors.BadInput`), an input error of
    ``gearcontact command``'s work, renamed by
    :func:`slip_renamed` where the pair's typed settings were checked before the work
    (``args.settings_check`` of the pair commands, ``args.blank_check`` of ``design``)
    and a flank did not agree (its warning printed then, the run gone on). An option's
    error (a field ``--...``) is the option's, unchanged."""
    check = getattr(args, "settings_check", None) or getattr(args, "blank_check", None)
    blank = getattr(check, "blank", None)
    if blank is None or not isinstance(exc, InputRangeError) or exc.field.startswith("--"):
        return exc
    return slip_renamed(exc, blank, failed=f"gearcontact {command}")


def checked_blank_named(pair, **options):
    """:func:`~gearcontact.report.design_mean_point.checked_blank` of ``pair``
    (``options`` its keywords; its warnings printed before its flank work); an input
    error of that work renamed by :func:`slip_renamed` from the comparison the check
    made first (not measured again)."""
    from ..report.design_mean_point import checked_blank

    first = []
    try:
        return checked_blank(pair, on_blank=first.append, **options)
    except InputRangeError as exc:
        if not first:       # the check's own refusal, before its flank work
            raise
        raise slip_renamed(exc, first[0].blank, failed="the check of its flanks") from None


def checked_typed_gear(pair, gear: dict):
    """The typed gear that ``design --machine-settings`` keeps
    (:func:`~.design_options.kept_gear`) against the blank it is meant to cut, before its
    standard pinion is derived: the typed-settings check of its two flanks
    (:func:`~gearcontact.geometry.blank_check.check_flanks`; a ``[print.gear]`` against
    its page's printed blank), its warnings on stderr, a gross mismatch an input error
    naming the likely key (exit 2); returns the
    :class:`~gearcontact.geometry.blank_verdict.BlankCheck` (what :func:`slip_renamed`
    names when the derivation fails). The pair's own check cannot see this gear: its
    tables are replaced before it runs (``design.check``), and a gear typed alone has no
    pinion to check beside it (docs/machine_settings.md sec. 2 and 5)."""
    from ..geometry.blank_check import check_flanks
    from ..geometry.blank_statement import printed_stated_blank, stated_blank

    printed = printed_stated_blank(pair)
    got = check_flanks(tuple(gear[side] for side in SIDES), stated_blank(pair),
                       member_stated=None if printed is None else {"gear": printed})
    for line in got.warnings():
        print(line, file=sys.stderr)
    got.raise_if_gross()
    return got
