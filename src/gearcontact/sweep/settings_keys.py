"""Setting variants of a sweep: a pair cut from machine settings with keys of its
``[machine.<member>.<flank>]`` / ``[blade.<member>.<flank>]`` tables replaced, named as
the pair file spells them (``--vary machine.pinion.drive.tilt_deg=19:21:5``,
``--vary machine.pinion.drive.modified_roll_2c_per_rad=-0.05:0.05:5``, ``--vary
blade.pinion.drive.blade_angle_deg=19.5:20.5:3``; docs/sweeps.md, docs/machine_settings.md
for the keys and their signs).

A variant is the pair file with the values edited in: the pair's TOML
(:func:`~gearcontact.geometry.pair.pair_to_toml`, floats at full precision) with the keys
set in its tables is read back by the pair reader
(:func:`~gearcontact.geometry.pair.parse_pair`: every range check, naming the dotted
key), whose machine set-ups replace the pair's, then prepared as every pair command prepares a pair
(:func:`~gearcontact.tca.synthesis.prepare_pair`: the typed-settings check against the
blank, the generation check, the gear's pinion ease-off check) and its flanks cut
(:meth:`~gearcontact.tca.synthesis.PreparedPair.flank_set`). So a grid point's results
are those of ``gearcontact tca`` / ``analyze`` on the edited file. A variant that cannot
be cut (a gross slip against the blank, an undercut, a contact gap the reader refuses)
is the result of its cells, recorded with its reason; the warnings the reader gives a
variant that can be cut (a flank off its blank, a hollow pinion flank, pinion and gear
not mates) are kept beside its results (``settings_warning``), as the commands print
them beside theirs.

The variants a process builds share the flank work their inputs share
(:data:`VARIANT_FLANKS`, :mod:`~gearcontact.geometry.flank_reuse`): a variant is still
read and prepared whole, but a flank (and a generated flank's active box) whose set-up
(its member's and flank's ``[machine.*]`` and ``[blade.*]`` tables), blank, face width
and node grid are those of a flank cut before is served that flank instead of being cut
again. Only the flank itself is reused: what depends on its mate (the pinion's turn onto
the design side's mean contact, the mean contacts) and every check of the pair are
computed for each variant. The result is the fresh cut's bit for bit (tests: a pinion
key, a gear key, and values one digit apart).

A pair with a ``[print.gear]`` page cuts its gear from the print's words: only the
pinion's keys vary (a gear key edited beside the print would not be read).
"""

from __future__ import annotations

import dataclasses
import difflib
import tomllib

from ..geometry.flank_reuse import FlankCache, reusing_flanks
from ..geometry.machine import BLADE_KEYS, HELICAL_KEYS, MACHINE_KEYS, MEMBERS, MODIFIED_ROLL_KEYS
from ..geometry.pair import pair_to_toml, parse_pair
from ..geometry.print_blank import cuts_the_printed_gear

__all__ = ["BLADE_TABLE_KEYS", "MACHINE_TABLE_KEYS", "SETTING_KEYS", "VARIANT_FLANKS",
           "build_setting_variant",
           "setting_keys", "setting_keys_text", "setting_unit", "unit_by_suffix",
           "unknown_setting_key", "warning_lines", "with_settings"]

#: Numeric keys of a ``[machine.<member>.<flank>]`` table (the printed series spelt out).
MACHINE_TABLE_KEYS = (*MACHINE_KEYS, *MODIFIED_ROLL_KEYS, *HELICAL_KEYS)
#: Numeric keys of a ``[blade.<member>.<flank>]`` table (``kind`` is a word, not swept).
BLADE_TABLE_KEYS = tuple(k for k in BLADE_KEYS if k != "kind")
_SIDES = ("drive", "coast")
#: Every setting key a settings pair may have: dotted name -> (table, member, side, key).
SETTING_KEYS: dict[str, tuple[str, str, str, str]] = {
    f"{table}.{member}.{side}.{key}": (table, member, side, key)
    for table, keys in (("machine", MACHINE_TABLE_KEYS), ("blade", BLADE_TABLE_KEYS))
    for member in MEMBERS for side in _SIDES for key in keys}
#: The flank work this process keeps between the setting variants it builds
#: (:mod:`~gearcontact.geometry.flank_reuse`: each flank and active box by its exact
#: inputs; per variant at most four flanks and four boxes, so at least the last three
#: variants' worth; a generated flank is about 6 MB: at most about 140 MB); None: every
#: variant cut afresh.
VARIANT_FLANKS: FlankCache | None = FlankCache(max_entries=24)
#: Units by the end of a key's name, longest first (the TOML keys carry their unit).
_UNITS = (("_mm_per_rad2", "mm/rad^2"), ("_mm_per_rad", "mm/rad"), ("_per_rad4", "1/rad^4"),
          ("_per_rad3", "1/rad^3"), ("_per_rad2", "1/rad^2"), ("_per_rad", "1/rad"),
          ("_per_mm3", "1/mm^3"), ("_per_mm2", "1/mm^2"), ("_mm", "mm"), ("_deg", "deg"),
          ("ratio_of_roll", "1"))


def unit_by_suffix(key: str, suffixes, *, what: str) -> str:
    """Unit of ``key`` from the end of its name (``suffixes``: ``(suffix, unit)`` pairs,
    longest first; the TOML keys carry their unit); ``what`` names the kind of key in
    the error."""
    for suffix, unit in suffixes:
        if key.endswith(suffix):
            return unit
    raise ValueError(f"no unit in the {what} key {key!r}")


def setting_unit(key: str) -> str:
    """Unit of a setting key (``machine.pinion.drive.tilt_deg`` -> ``deg``; the ratio
    of roll, work / cradle: ``1``)."""
    return unit_by_suffix(key, _UNITS, what="setting")


def _members(pair) -> tuple[str, ...]:
    """The members whose tables ``pair`` takes as typed (a print's gear: none)."""
    return ("pinion",) if cuts_the_printed_gear(pair) else MEMBERS


def setting_keys(pair) -> tuple[str, ...]:
    """The setting keys ``pair`` can vary: every key of :data:`SETTING_KEYS` of its
    members (module docstring: a print's gear takes none); ``()`` for a pair without
    machine settings."""
    if not getattr(pair, "machine", None):
        return ()
    members = _members(pair)
    return tuple(k for k, (_, member, _, _) in SETTING_KEYS.items() if member in members)


def setting_keys_text(pair) -> str:
    """The keys of :func:`setting_keys` in words, for a message: the tables and the
    keys of each."""
    members = "|".join(_members(pair))
    note = " (the gear is cut from its [print.gear] page)" if len(_members(pair)) == 1 else ""
    return (f"a key of the pair's [machine.<{members}>.<drive|coast>] tables{note}: "
            f"{', '.join(MACHINE_TABLE_KEYS)}; or of its [blade.<{members}>.<drive|coast>] "
            f"tables: {', '.join(BLADE_TABLE_KEYS)} (e.g. "
            f"machine.pinion.drive.tilt_deg)")


#: Words a gear engineer may type for a key, by the key's table: the key they mean.
_SPOKEN = {"blade": {"pressure_angle_deg": "blade_angle_deg"},
           "machine": {"2c": "modified_roll_2c_per_rad", "6d": "modified_roll_6d_per_rad2",
                       "24e": "modified_roll_24e_per_rad3",
                       "120f": "modified_roll_120f_per_rad4"}}


def unknown_setting_key(pair, key: str) -> str:
    """``"; did you mean ..."`` naming the key ``pair`` can vary that ``key`` most likely
    means, or ``""``: only where its table, member and flank are the pair's and its name
    is a key of the other table, a word of ``_SPOKEN``, the start of exactly one
    key's name, or close to one (:func:`difflib.get_close_matches`, cutoff 0.8); a flank
    named otherwise than drive / coast gets none (concave / convex is the member's and
    hand's, not a spelling)."""
    parts = key.split(".")
    if len(parts) != 4 or parts[0] not in _SPOKEN or parts[1] not in _members(pair) \
            or parts[2] not in _SIDES:
        return ""
    table, name = parts[0], parts[3].lower()
    names = MACHINE_TABLE_KEYS if table == "machine" else BLADE_TABLE_KEYS
    other = "blade" if table == "machine" else "machine"
    if name in (BLADE_TABLE_KEYS if table == "machine" else MACHINE_TABLE_KEYS):
        return f"; did you mean {other}.{parts[1]}.{parts[2]}.{name}?"    # the other table
    starts = [n for n in names if n.startswith(name)]
    meant = (_SPOKEN[table].get(name) or (starts[0] if len(starts) == 1 else None)
             or next(iter(difflib.get_close_matches(name, names, n=1, cutoff=0.8)), None))
    return f"; did you mean {'.'.join(parts[:3])}.{meant}?" if meant else ""


def with_settings(pair, design) -> object:
    """``pair`` with the setting keys of ``design`` (dotted key -> value, or ``((key,
    value), ...)``) edited into its tables: its TOML with the values set read back by
    the pair reader, whose machine set-ups replace ``pair``'s (module docstring).

    Raises
    ------
    InputRangeError
        A value outside its key's range, named by the dotted key (the pair reader's
        check, :func:`~gearcontact.geometry.machine.setup_from_tables`).
    KeyError
        A key not in :func:`setting_keys` of ``pair``.
    """
    design = dict(design)
    allowed = setting_keys(pair)
    doc = tomllib.loads(pair_to_toml(pair))
    for key, value in design.items():
        if key not in allowed:
            raise KeyError(key)
        table, member, side, name = SETTING_KEYS[key]
        doc[table][member][side][name] = float(value)
    # the set-ups as the reader reads the edited tables; every other field as ``pair``
    # has it (the writer names a material the file left unnamed: not a setting)
    return dataclasses.replace(pair, machine=parse_pair(doc, name=pair.name).machine)


def build_setting_variant(pair, design) -> tuple:
    """``(prepared pair, flanks)`` of the variant ``design`` of ``pair``
    (:func:`with_settings`, then :func:`~gearcontact.tca.synthesis.prepare_pair` and its
    flanks, as a pair command reads a file), reusing the flanks of the variants built
    before in this process whose inputs it shares (:data:`VARIANT_FLANKS`; module
    docstring). The reader's warnings are emitted as it emits them (:func:`warning_lines`
    keeps them for the store).

    Raises
    ------
    Exception
        Whatever the reader raises on a variant it refuses (the caller records it).
    """
    from ..tca.synthesis import prepare_pair

    with reusing_flanks(VARIANT_FLANKS):
        prepared = prepare_pair(with_settings(pair, design))
        return prepared.pair, prepared.flank_set()


def warning_lines(caught) -> tuple[str, ...]:
    """The distinct warnings of ``caught`` (:func:`warnings.catch_warnings` records),
    each ``"Category: message"``, in order."""
    return tuple(dict.fromkeys(f"{w.category.__name__}: {w.message}" for w in caught))
