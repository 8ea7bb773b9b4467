"""Design variants of a sweep: the pair with keys of its TOML ``[easeoff.drive]``,
``[easeoff.coast]`` or ``[cutter]`` tables replaced (``--vary
easeoff.drive.lengthwise_crowning_um_per_mm2=0.08:0.16:5``, ``--vary
cutter.radius_mm=44:46:5``; ``ease-off.`` is accepted for ``easeoff.``).

A variant changes the cut flanks, so its flanks are built anew -- once per variant, on
a worker, and shared by every assembly-error point and torque of that variant
(:mod:`.run`). A variant of ease-off keys only keeps the conjugate flanks of the
nominal pair and applies its ease-off to them
(:func:`~gearcontact.geometry.flank.with_easeoff`, about a tenth of a full build); a
cutter key rebuilds everything (the blank, the gear, the conjugate pinion). A variant whose flanks cannot be built (an undercut, an ease-off beyond
its limit) is the result of its cells, recorded by name like a wild assembly error.
A pair cut from machine settings varies the keys of its ``[machine.*]`` / ``[blade.*]``
tables instead (:mod:`.settings_keys`: each variant read and cut as the pair file with
the values edited in, its unchanged flanks reused from the variants built before on
that worker).
"""

from __future__ import annotations

import dataclasses
import time
import warnings
from dataclasses import dataclass

from ..geometry.pair import CYLINDRICAL, CutterSpec, EaseOffCoefficients
from ..validation import InputRangeError
from .cylindrical import CYLINDRICAL_KEYS
from .settings_keys import (SETTING_KEYS, build_setting_variant, setting_keys_text,
                            unit_by_suffix, warning_lines, with_settings)

__all__ = ["DESIGN_KEYS", "Variant", "build_variant", "check_variants", "design_key",
           "design_unit", "easeoff_only", "vary_design"]

#: TOML key (``table.key``) -> (GearPair attribute, field of that attribute).
DESIGN_KEYS: dict[str, tuple[str, str]] = {
    **{f"easeoff.{side}.{name}": (f"easeoff_{side}", name)
       for side in ("drive", "coast") for name in EaseOffCoefficients.__dataclass_fields__},
    **{f"cutter.{name}": ("cutter", name) for name in CutterSpec.__dataclass_fields__},
}
_ALIASES = {"ease-off.": "easeoff."}
_UNIT_SUFFIXES = (("_um_per_mm2", "um/mm^2"), ("_um_per_mm", "um/mm"), ("_um", "um"),
                  ("_mm", "mm"),
                  ("_deg", "deg"), ("_factor", "1"))


def design_key(key: str) -> str | None:
    """The TOML key ``key`` names (``ease-off.`` spelt ``easeoff.``), or None if it is
    not a design key."""
    for alias, name in _ALIASES.items():
        if key.startswith(alias):
            key = name + key[len(alias):]
    return key if key in DESIGN_KEYS else None


def design_unit(key: str) -> str:
    """Unit of a design key, from its name (the TOML keys carry their unit)."""
    return unit_by_suffix(key, _UNIT_SUFFIXES, what="design")


def easeoff_only(keys) -> bool:
    """True when every key of ``keys`` is an ease-off coefficient (the conjugate flanks
    of the nominal pair serve every variant)."""
    return all(k in DESIGN_KEYS and DESIGN_KEYS[k][0].startswith("easeoff_") for k in keys)


def vary_design(pair, design: dict):
    """``pair`` with the design keys of ``design`` (TOML key -> value) replaced; the
    pair's own checks run again (named :class:`InputRangeError` on an impossible
    value or design). A cylindrical pair: the keys of
    :data:`.cylindrical.CYLINDRICAL_KEYS`."""
    keys = CYLINDRICAL_KEYS if pair.kind == CYLINDRICAL else DESIGN_KEYS
    changes: dict = {}
    for key, value in design.items():
        attr, name = keys[key]
        changes[attr] = dataclasses.replace(changes.get(attr, getattr(pair, attr)),
                                            **{name: float(value)})
    return dataclasses.replace(pair, **changes) if changes else pair


def check_variants(pair, grid) -> None:
    """Every design variant of ``grid`` is a valid pair (cheap: the blank design, no
    flanks), or :class:`InputRangeError` naming the ``--vary`` keys and values. The
    setting keys of a pair cut from machine settings: every variant read as its edited
    file (:func:`.settings_keys.with_settings`: the reader's checks, a blade's reliefs
    checked together).

    A pair cut from machine settings takes no design key: its flanks are the settings'
    (:func:`~gearcontact.geometry.flank.build_machine_flanks` reads neither
    ``[easeoff.*]`` nor ``[cutter]``), and an ease-off variant would be laid on its
    generated pinion (:func:`~gearcontact.geometry.flank.with_easeoff`), which smooths
    the kink of a relieved blade's flank."""
    design_keys = [v.key for v in grid.vary if v.design and v.key not in SETTING_KEYS]
    if design_keys and pair.kind != CYLINDRICAL and pair.machine:
        from ..geometry.machine import relieved_blade_keys

        kinks = relieved_blade_keys(pair.machine)
        raise InputRangeError(
            f"--vary {design_keys[0]}", f"pair {pair.name} (cut from [machine.*] / "
            "[blade.*] settings" + ("; relieved blades: " + ", ".join(f"{k} = {v:g}" for k, v in kinks) if kinks else "")
            + ")", "a pair without machine settings: the flanks cut from settings take no "
            "[easeoff.*] / [cutter] key" + (" (an ease-off laid on the relieved pinion "
                                             "would smooth its kink)" if kinks else "")
            + f"; such a pair varies {setting_keys_text(pair)}")
    # setting keys: every variant read as the edited file (about 1 ms each, against
    # seconds for its flanks; the reader's checks of one blade join several keys)
    vary = with_settings if any(v.key in SETTING_KEYS for v in grid.vary) else vary_design
    for design in grid.variants():
        try:
            vary(pair, dict(design))
        except InputRangeError as exc:
            keys = ", ".join(f"{k}={v:g}" for k, v in design)
            raise InputRangeError(f"--vary {keys}: {exc.field}", exc.value,
                                  exc.allowed) from None


@dataclass(frozen=True)
class Variant:
    """One design variant, built: its pair and flanks, or the error that stopped the
    build.

    Attributes
    ----------
    pair : GearPair or None
    flanks : FlankSet or None
    build_s : float
        Wall time of the flank build, s (on the worker that built it).
    error : str
        ``""`` or ``"Type: message"`` of a failed build.
    warnings : tuple of str
        A setting variant's: the pair reader's warnings (``"Category: message"``,
        :func:`.settings_keys.build_setting_variant`); else ``()``.
    """

    pair: object
    flanks: object
    build_s: float
    error: str = ""
    warnings: tuple = ()


def build_variant(pair, design: tuple, base: Variant | None = None) -> Variant:
    """Build the flanks of ``pair`` with ``design`` (``((TOML key, value), ...)``)
    replaced; an error of the build is the variant's result.

    ``base``: the nominal pair's built variant; with ease-off keys only, its conjugate
    flanks are reused and only the variant's ease-off is applied. A cylindrical pair has
    no flanks to build (its TCA builds them): ``flanks`` is None. Setting keys
    (:mod:`.settings_keys`): the pair file with the values edited in, read and cut as a
    pair command does (:func:`.settings_keys.build_setting_variant`; the reader's
    warnings kept in ``warnings``).
    """
    from ..geometry.flank import build_flanks, with_easeoff

    t0 = time.perf_counter()
    setting = bool(design) and all(k in SETTING_KEYS for k, _ in design)
    error = ""
    # a setting variant's warnings are kept for the store, failed or not (its error may
    # refer to the warning that names the likely slip)
    with warnings.catch_warnings(record=setting) as caught:
        if setting:
            warnings.simplefilter("always")
        try:
            if setting:
                varied, flanks = build_setting_variant(pair, design)
            elif pair.kind == CYLINDRICAL:
                varied, flanks = vary_design(pair, dict(design)), None
            elif base is not None and easeoff_only(k for k, _ in design):
                varied = vary_design(pair, dict(design))
                flanks = with_easeoff(base.flanks, varied)
            else:
                varied = vary_design(pair, dict(design))
                flanks = build_flanks(varied)
        except Exception as exc:  # noqa: BLE001  (recorded by type for every cell of it)
            varied = flanks = None
            error = f"{type(exc).__name__}: {exc}"
    return Variant(varied, flanks, time.perf_counter() - t0, error,
                   warning_lines(caught) if setting else ())
