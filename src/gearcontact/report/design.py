"""Files of ``gearcontact design``: the calibrated pair, the synthesized ease-off, the
machine settings.

:func:`calibrate_to_published` calibrates a built-in pair to its published design point
(:func:`~gearcontact.tca.calibration.calibrate_pair` on the targets of
:func:`~gearcontact.report.analyze.published_values`); :func:`write_calibration` writes
its ``calibrated.toml`` and ``calibration.json``. :func:`write_easeoff_toml` writes
``easeoff.toml`` (:func:`~gearcontact.tca.synthesis.easeoff_toml`);
:func:`write_machine_settings_toml` writes ``machine_settings.toml``
(:func:`~gearcontact.geometry.pair.pair_to_toml` of the pair with its standard machine
settings, docs/machine_settings.md); :func:`write_easeoff_settings` writes it for
the settings fitted to a pair's ease-off (:func:`easeoff_settings_toml`) with the map
of their residual (``machine_settings_residual.png`` / ``.svg``) and, for scattered
measured points, the residual per point (``machine_settings_points.csv``).
"""

from __future__ import annotations

import json
from pathlib import Path

from ..figure_files import save_figure
from ..geometry.formate import SIDES
from ..geometry.pair import GearPair, pair_to_toml
from ..geometry.plots import plot_setting_residual
from ..tca.calibration import (Calibration, CalibrationTargets, calibrate_pair,
                               calibration_toml)
from ..validation import InputRangeError
from .analyze import published_values

__all__ = ["calibrate_to_published", "easeoff_settings_toml", "write_calibration",
           "write_easeoff_settings", "write_easeoff_toml", "write_machine_settings_toml"]


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


def local_synthesis_toml(cut, done: dict, *, typed: bool = False, notes=()) -> str:
    """The pair TOML of the settings from local synthesis
    (:func:`~gearcontact.tca.setting_synthesis.synthesized_machine_pair`), its head
    comment the target / achieved table at the mean point and the full TCA's check per
    side. ``typed``: the gear is the pair file's, kept as typed (``[print.gear]`` verbatim
    where the pair has one), the pinion synthesized against it. A side missing from
    ``done`` (no pivot on the flank) is named: its pinion is the standard one. ``notes``:
    further head lines (the blade curvatures written straight,
    :func:`~gearcontact.geometry.written_blade.written_pair`)."""
    from ..geometry.pair import pair_to_toml

    gear = ("formate" if all(s.settings.formate for s in cut.machine if s.member == "gear")
            else "generated")
    if typed:
        gear = ("typed ([print.gear], kept as typed), " if cut.print_gear else
                "typed ([machine.gear.*] / [blade.gear.*], kept as typed), ") + gear
    lines = [f"{cut.name}: machine settings from local synthesis at the mean point "
             "(gearcontact design --machine-settings --local-synthesis;",
             f"signs: docs/machine_settings.md); gear: {gear}"]
    for side in (s for s in SIDES if s not in done):
        lines.append(f"{side}: not synthesized: the base pinion's contact path has no "
                     "point inside the flank by the pivot's margin (no pivot M); the standard "
                     "pinion (crowning 25 / 10 um about the mean node), "
                     "docs/machine_settings.md sec. 5")
    for side, r in done.items():
        lines += r.table().splitlines()
        edges = sum(1 for e in r.edges if e)
        lines.append(f"{side}: full TCA TE0 p-p {r.tca_te0_pp_arcsec:.2f} arcsec, vertex "
                     f"{r.vertex_offset_mm:.1e} mm from M, paint ellipse at a flank edge at "
                     f"{edges} of {len(r.edges)} phases")
        if r.reach is not None:
            lines.append(r.reach_text())
        if getattr(r, "pivot", ""):
            lines.append(r.pivot_text())
    return pair_to_toml(cut, comments={"": "\n".join([*lines, *notes])})


def easeoff_settings_toml(fit, *, gear=None, notes=()) -> str:
    """The pair TOML of the settings fitted to a pair's ease-off
    (:class:`~gearcontact.geometry.easeoff_settings.EaseOffSettings`), its head comment the
    residual per side (and per corrected gear side, ``gear`` a
    :class:`~gearcontact.geometry.gear_correction.GearCorrection`); ``notes``: further
    head lines."""
    pair = fit.pair
    lines = [f"{pair.name}: machine settings that cut its ease-off (gearcontact design "
             "--machine-settings;", "signs: docs/machine_settings.md). Gear: the default "
             "flanks' gear; pinion: fitted from", "the conjugate pinion's settings "
             "(exact; a hypoid with a generated gear: its crown gear's pinion fitted to "
             "it first)", "to the conjugate pinion + ease-off" + (
                 " (fit objective: the largest deviation, --fit minimax)." if any(
                     r.fit.objective == "minimax" for r in fit.sides.values()) else ".")]
    for side, r in fit.sides.items():
        source = "measured grid (--target-flank)" if side in fit.measured_sides else \
            f"[easeoff.{side}] of the pair"
        where = "over the flank"
        if r.points is not None:
            source = f"{len(r.points.line)} measured points (--target-flank)"
            where = "at the points"
        lines.append(f"pinion {side} ({source}): ease-off max {r.easeoff_max_um:.2f} um, "
                     f"residual max {r.max_um:.3f} um, RMS {r.rms_um:.3f} um {where}")
    if gear is not None:
        lines += ["Gear sides measured (--target-flank): corrected from the nominal gear's "
                  "settings."] + gear.comment_lines()
    return pair_to_toml(pair, comments={"": "\n".join([*lines, *notes])})


def gear_correction_toml(pair, *corrections, notes=()) -> str:
    """The pair TOML of a pair cut from machine settings whose measured members were
    corrected to their measured flanks (``corrections``, one
    :class:`~gearcontact.geometry.gear_correction.GearCorrection` per member), the
    other member kept; the head comment the residual per corrected side (and
    ``notes``)."""
    from ..geometry.pair import pair_to_toml

    done = [c.member for c in corrections]
    kept = [m for m in ("pinion", "gear") if m not in done]
    lines = [f"{pair.name}: its machine settings with the {' and '.join(done)} corrected to "
             "the measured flank (gearcontact design", "--machine-settings --target-flank; "
             "signs: docs/machine_settings.md)" + "".join(f"; {m}: the pair's own"
                                                          for m in kept) + "."]
    for c in corrections:
        lines += c.comment_lines()
    return pair_to_toml(pair, comments={"": "\n".join([*lines, *notes])})


def write_gear_points(correction, out) -> Path:
    """Write the residual at each measured point of a corrected member
    (:meth:`~gearcontact.geometry.gear_correction.GearCorrection.points_csv`) into the
    directory ``out``: the gear's ``machine_settings_gear_points.csv``, the pinion's
    ``machine_settings_points.csv`` (the name of the pinion fit's points); returns its
    path."""
    name = "gear_points" if correction.member == "gear" else "points"
    path = Path(out) / f"machine_settings_{name}.csv"
    path.write_text(correction.points_csv())
    return path


def write_easeoff_settings(fit, out, *, gear=None, notes=()) -> Path:
    """Write ``machine_settings.toml`` (:func:`easeoff_settings_toml`), the residual
    map ``machine_settings_residual.png`` / ``.svg`` and, for a target of scattered
    measured points, the residual at each point ``machine_settings_points.csv``
    (:meth:`~gearcontact.geometry.easeoff_settings.EaseOffSettings.points_csv`) into
    the directory ``out`` (created if missing); returns the TOML's path."""
    path = write_machine_settings_toml(easeoff_settings_toml(fit, gear=gear, notes=notes),
                                       out)
    if gear is not None:
        write_gear_points(gear, out)
    save_figure(plot_setting_residual(fit), Path(out) / "machine_settings_residual.png")
    points = fit.points_csv()
    if points is not None:
        (Path(out) / "machine_settings_points.csv").write_text(points)
    return path
