"""The grid of a sweep: ``--vary KEY=START:STOP:STEPS`` specs and the torques.

Keys are the assembly errors of :mod:`gearcontact.geometry.kinematics` by their short
names (``E``, ``P``, ``G`` in mm, ``alpha`` in deg; sign conventions there) or design
keys of the pair's TOML (``easeoff.<side>.<coefficient>``, ``cutter.<key>``;
:mod:`.design`); for a pair cut from machine settings the keys of its
``[machine.<member>.<flank>]`` / ``[blade.<member>.<flank>]`` tables
(:mod:`.settings_keys`); for a cylindrical pair the keys of its ``[modifications.*]`` and
``[assembly]`` tables (:mod:`.cylindrical`). Each spec spans
``numpy.linspace(START, STOP, STEPS)``, both ends included. The torques form the last
dimension. A grid point (one design variant and one set of assembly errors) is one
task; a cell is one point at one torque; a design variant is the set of points sharing
their design values (one flank build).
"""

from __future__ import annotations

import itertools
import json
from dataclasses import dataclass

import numpy as np

from ..geometry.kinematics import ASSEMBLY_KEYS, ASSEMBLY_LIMITS
from ..geometry.pair import BEVEL, CYLINDRICAL
from ..validation import InputRangeError, check_finite
from .cylindrical import CYLINDRICAL_KEYS
from .design import DESIGN_KEYS, design_key, design_unit
from .settings_keys import SETTING_KEYS, setting_keys, setting_keys_text, setting_unit, \
    unknown_setting_key

__all__ = ["MAX_STEPS", "MAX_CELLS", "VarySpec", "SweepGrid", "parse_vary"]

#: Steps of one ``--vary`` spec, at most (a 101 x 101 (E, P) map is finer than any
#: V/H chart needs).
MAX_STEPS = 101
#: Cells of a sweep, at most (about a day of LTCA cells on one core).
MAX_CELLS = 100_000


@dataclass(frozen=True)
class VarySpec:
    """One swept key over ``numpy.linspace(start, stop, steps)``.

    ``key`` is the short name of an assembly error (``E``) or a TOML design key
    (``easeoff.drive.lengthwise_crowning_um_per_mm2``); ``field`` the Dataset
    dimension (an AssemblyErrors field, or the design key with ``_`` for ``.``; the
    unit is in the name, ``unit`` spells it).
    """

    key: str
    field: str
    start: float
    stop: float
    steps: int
    unit: str = "mm"

    @property
    def design(self) -> bool:
        """True for a design key (the flanks change; every key of a cylindrical pair)."""
        return (self.key in DESIGN_KEYS or self.key in CYLINDRICAL_KEYS
                or self.key in SETTING_KEYS)

    @property
    def values(self) -> np.ndarray:
        return np.linspace(self.start, self.stop, self.steps)


def parse_vary(text: str, *, kind: str = BEVEL, pair=None) -> VarySpec:
    """``"E=-0.1:0.1:9"`` -> :class:`VarySpec`; ``kind``: the pair's (``"cylindrical"``:
    the keys of :data:`.cylindrical.CYLINDRICAL_KEYS`, ranges checked by
    :func:`.design.check_variants`); ``pair``: the bevel pair, if known (one cut from
    machine settings takes the assembly errors and its setting keys,
    :func:`.settings_keys.setting_keys`; its flanks take no ease-off or cutter key, which
    :func:`.design.check_variants` refuses, naming a relieved blade's kink).

    Raises
    ------
    InputRangeError
        Naming ``--vary`` and the spec: unknown key (the message lists the allowed
        ones), not ``START:STOP:STEPS``, bad number, STEPS outside [1, MAX_STEPS] (1
        needs START == STOP, and START == STOP needs 1), STOP < START, an assembly error beyond
        :data:`~gearcontact.geometry.kinematics.ASSEMBLY_LIMITS` (the range of a design
        key is the pair's: :func:`.design.check_variants`).
    """
    key, eq, rng = (s.strip() for s in str(text).partition("="))
    if not eq:
        raise InputRangeError("--vary", text, "KEY=START:STOP:STEPS")
    if kind == CYLINDRICAL:
        if key not in CYLINDRICAL_KEYS:
            raise InputRangeError("--vary KEY", key, "a key of the cylindrical pair's "
                                  "[modifications.pinion] / [modifications.gear] / "
                                  f"[assembly] tables: {', '.join(CYLINDRICAL_KEYS)}")
    elif setting_keys(pair):       # a design key: refused by check_variants, by name
        if key not in ASSEMBLY_KEYS and key not in setting_keys(pair) \
                and design_key(key) is None:
            raise InputRangeError("--vary KEY", key, "one of the assembly errors "
                                  f"{', '.join(ASSEMBLY_KEYS)} or {setting_keys_text(pair)}"
                                  + unknown_setting_key(pair, key))
    elif key not in ASSEMBLY_KEYS and design_key(key) is None:
        raise InputRangeError("--vary KEY", key, "one of the assembly errors "
                              f"{', '.join(ASSEMBLY_KEYS)} or a key of the pair's TOML "
                              f"[easeoff.*] / [cutter] tables: {', '.join(DESIGN_KEYS)}"
                              + ("; the [machine.*] / [blade.*] keys are a pair's cut from "
                                 "machine settings (this one has none)"
                                 if key in SETTING_KEYS else ""))
    parts = rng.split(":")
    if len(parts) != 3:
        raise InputRangeError(f"--vary {key}", rng, "START:STOP:STEPS (three fields)")
    try:
        start, stop = float(parts[0]), float(parts[1])
        steps = int(parts[2])
    except ValueError:
        raise InputRangeError(f"--vary {key}", rng, "START:STOP:STEPS with numbers START,"
                              " STOP and an integer STEPS") from None
    if not 1 <= steps <= MAX_STEPS:
        raise InputRangeError(f"--vary {key} STEPS", steps, f"an integer in [1, {MAX_STEPS}]")
    for name, x in (("START", start), ("STOP", stop)):   # nan, inf: not a reversed range
        check_finite(f"--vary {key} {name}", x)
    if not stop >= start:
        raise InputRangeError(f"--vary {key}", rng, "STOP >= START (a reversed range)")
    if steps == 1 and stop != start:
        raise InputRangeError(f"--vary {key}", rng, "STEPS >= 2 when STOP != START")
    if steps > 1 and stop == start:         # the same point computed STEPS times
        raise InputRangeError(f"--vary {key}", rng, "STEPS = 1 when STOP == START")
    if key in CYLINDRICAL_KEYS:
        return VarySpec(key, key.replace(".", "_"), start, stop, steps, design_unit(key))
    if key in SETTING_KEYS:
        return VarySpec(key, key.replace(".", "_"), start, stop, steps, setting_unit(key))
    if key not in ASSEMBLY_KEYS:
        key = design_key(key)
        return VarySpec(key, key.replace(".", "_"), start, stop, steps, design_unit(key))
    field = ASSEMBLY_KEYS[key]
    unit = "deg" if field.endswith("_deg") else "mm"
    lim = ASSEMBLY_LIMITS[field]
    for x in (start, stop):
        if not -lim <= x <= lim:
            raise InputRangeError(f"--vary {key} ({unit})", x, f"[{-lim:g}, {lim:g}] {unit}")
    return VarySpec(key, field, start, stop, steps, unit)


@dataclass(frozen=True)
class SweepGrid:
    """The swept keys (in ``--vary`` order) and the torques (N·m).

    Dimensions of the Dataset: the fields of ``vary`` (e.g. ``E_mm``, ``P_mm``,
    ``easeoff_drive_lengthwise_crowning_um_per_mm2``) then ``torque_nm``.
    ``points()`` lists the grid points (index tuple, AssemblyErrors overrides, design
    variant) in C order, ``variants()`` the distinct design variants.
    """

    vary: tuple[VarySpec, ...]
    torques_nm: tuple[float, ...]

    def __post_init__(self):
        fields = [v.field for v in self.vary]
        if len(set(fields)) != len(fields):
            raise InputRangeError("--vary", [v.key for v in self.vary],
                                  "each key at most once")
        n = self.cells
        if n > MAX_CELLS:
            raise InputRangeError("--vary x --torques (cells)", n, f"at most {MAX_CELLS}")

    @property
    def dims(self) -> tuple[str, ...]:
        return (*(v.field for v in self.vary), "torque_nm")

    @property
    def shape(self) -> tuple[int, ...]:
        return (*(v.steps for v in self.vary), len(self.torques_nm))

    @property
    def cells(self) -> int:
        return int(np.prod(self.shape))

    def points(self):
        """(index tuple, {AssemblyErrors field: value}, design) of every grid point;
        ``design`` is ``((TOML key, value), ...)`` of the swept design keys (``()``
        without any: the pair as given)."""
        for idx in itertools.product(*(range(v.steps) for v in self.vary)):
            values = [(v, float(v.values[i])) for v, i in zip(self.vary, idx)]
            yield (idx, {v.field: x for v, x in values if not v.design},
                   tuple((v.key, x) for v, x in values if v.design))

    def variants(self) -> list[tuple]:
        """The distinct design variants (``design`` of :meth:`points`), in C order."""
        design = [v for v in self.vary if v.design]
        return [tuple((v.key, float(x)) for v, x in zip(design, xs))
                for xs in itertools.product(*(v.values for v in design))]

    def as_dict(self) -> dict:
        return {"vary": [[v.key, v.start, v.stop, v.steps] for v in self.vary],
                "torques_nm": list(self.torques_nm)}

    def key(self) -> str:
        """Identity of the grid (stored with the results; a resume must match it)."""
        return json.dumps(self.as_dict(), sort_keys=True)
