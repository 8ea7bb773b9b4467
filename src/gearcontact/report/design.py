"""Files of ``gearcontact design``: the calibrated pair, the synthesized ease-off, the
machine settings.

:func:`calibrate_to_published` calibrates a built-in pair to its published design point
(:func:`~gearcontact.tca.calibration.calibrate_pair` on the targets of
:func:`~gearcontact.report.analyze.published_values`); :func:`write_calibration` writes
its ``calibrated.toml`` and ``calibration.json``. :func:`write_easeoff_toml` writes
``easeoff.toml`` (:func:`~gearcontact.tca.synthesis.easeoff_toml`);
:func:`write_machine_settings_toml` writes ``machine_settings.toml``
(:func:`~gearcontact.geometry.pair.pair_to_toml` of the pair with its standard machine
settings, docs/machine_settings.md).
"""

from __future__ import annotations

import json
from pathlib import Path

from ..geometry.pair import GearPair
from ..tca.calibration import (Calibration, CalibrationTargets, calibrate_pair,
                               calibration_toml)
from ..validation import InputRangeError
from .analyze import published_values

__all__ = ["calibrate_to_published", "write_calibration", "write_easeoff_toml",
           "write_machine_settings_toml"]


def calibrate_to_published(pair: GearPair, *, tip_margin_mm: float | None = None,
                           progress: bool = False) -> Calibration:
    """Calibrate ``pair``'s unpublished set-up to its published design point.

    Parameters
    ----------
    pair : GearPair
        A built-in pair with published values (``s0003``, ``s0003-centred``).
    tip_margin_mm : float, optional
        Pinion tip radius above the published mating point, mm (default: the largest
        margin that keeps a top land of 0.25 m_mn; see
        :func:`~gearcontact.tca.calibration.calibrate_pair`).
    progress : bool
        Show a progress bar.

    Returns
    -------
    Calibration

    Raises
    ------
    InputRangeError
        If the pair has no published values.
    """
    published = published_values(pair.name)
    if published is None:
        raise InputRangeError("pair", pair.name, "a built-in pair with published values "
                              "(s0003, s0003-centred)")
    return calibrate_pair(pair, CalibrationTargets.from_published(published),
                          tip_margin_mm=tip_margin_mm, progress=progress)


def write_calibration(cal: Calibration, out) -> Path:
    """Write ``calibrated.toml`` (the calibrated pair, named as the preset it
    regenerates: ``s0003-centred`` -> ``s0003``, with the calibration's provenance as
    comments) and ``calibration.json`` (:meth:`Calibration.as_dict`, indented by 2) into
    the directory ``out`` (created if missing); returns the TOML's path."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "calibrated.toml"
    path.write_text(calibration_toml(cal, name=cal.pair.name.removesuffix("-centred")))
    (out / "calibration.json").write_text(json.dumps(cal.as_dict(), indent=2))
    return path


def write_easeoff_toml(text: str, out) -> Path:
    """Write the ease-off tables ``text`` as ``easeoff.toml`` into the directory ``out``
    (created if missing); returns its path."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "easeoff.toml"
    path.write_text(text)
    return path


def write_machine_settings_toml(text: str, out) -> Path:
    """Write the pair TOML ``text`` (with its machine and blade tables) as
    ``machine_settings.toml`` into the directory ``out`` (created if missing); returns
    its path."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "machine_settings.toml"
    path.write_text(text)
    return path
