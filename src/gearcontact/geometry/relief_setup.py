"""Relieved blades (Toprem / Flankrem) in the setting fit: the relief kept as given.

A relieved blade (:mod:`.blade`) keeps its relief through every correction of the
setting fit (:mod:`.setting_fit`): the relief keys (:data:`RELIEF_KEYS`) are a fixed
blade property, never fitted; the corrections act on the blade's main profile, whose
point that cuts the member's mean node is the blade pivot (a relief reaching it is
refused, :func:`check_pivot_on_main`; a pinion's already by :func:`relieved_setup`, a
gear's by the gear's fit: a gear kept as given may carry any relief), and the flank is
cut piece by piece, one smooth set-up per blade segment (:func:`piece_setups`,
:mod:`.kinked`).
docs/machine_settings.md sec. 6, "Relieved blades".
"""

from __future__ import annotations

import dataclasses

from ..validation import InputRangeError
from .blade import blade_segments
from .blank import BlankDesign
from .conjugate import nominal_pinion_box
from .generated import EnvelopeSolver
from .machine import BladeSettings, MachineSetup, blade_profile

__all__ = ["RELIEF_KEYS", "blade_relief", "blade_reliefs", "check_pivot_on_main",
           "piece_setups", "relieved_setup", "with_relief"]

#: The blade's relief keys (:class:`~.blade.BladeSettings`): fixed blade properties,
#: carried through every correction, never fitted (module docstring).
RELIEF_KEYS = ("toprem_angle_deg", "toprem_depth_mm", "flankrem_angle_deg",
               "flankrem_depth_mm")


def blade_relief(blade) -> dict:
    """``{key: value}`` of :data:`RELIEF_KEYS` of a relieved blade (Toprem / Flankrem),
    ``{}`` for a smooth one (a relief angle of 0 is no relief)."""
    return {k: getattr(blade, k) for k in RELIEF_KEYS} if blade.relieved else {}


def with_relief(setup: MachineSetup, relief: dict) -> MachineSetup:
    """``setup`` with its blade's relief keys set to ``relief`` (:func:`blade_relief`;
    the blade's checks run: a relief the new blade cannot carry names its key,
    ``blade.<member>.<side>.<key>``)."""
    return dataclasses.replace(setup, blade=dataclasses.replace(
        setup.blade, where=f"blade.{setup.member}.{setup.side}", **relief))


def blade_reliefs(setups) -> dict:
    """``{(member, side): relief}`` (:func:`blade_relief`) of the relieved blades among
    the set-ups ``setups`` (a pair's ``machine`` tables)."""
    return {(s.member, s.side): blade_relief(s.blade) for s in setups if s.blade.relieved}


def relieved_setup(setup: MachineSetup, relief: dict, blank: BlankDesign) -> MachineSetup:
    """``setup`` with ``relief`` kept on its blade (:func:`with_relief`), a pinion's
    checked to leave the blade point that cuts its mean point on the main profile (the
    pivot of the setting fit; refused naming the relief depth)."""
    if not relief:
        return setup
    out = with_relief(setup, relief)
    if setup.member == "pinion" and out.blade.relieved:
        main = with_relief(out, dict.fromkeys(relief, 0.0))
        cone, _ = nominal_pinion_box(blank, 1.0)
        u_m, v_m = float(cone.root_offset_mm), float(blank.pitch_point_mm[0])
        solver = EnvelopeSolver(main, blank, cone)
        mean = solver.solve(u_m, v_m, solver.initial_guess(u_m, v_m))
        check_pivot_on_main(out.blade, float(blade_profile(main.blade, mean.l_mm)[1]))
    return out


def piece_setups(setup: MachineSetup) -> list:
    """``[(name, set-up)]`` of the smooth pieces a (relieved) blade generates: one per
    blade segment (:func:`~.blade.blade_segments`), ``[("main", setup)]`` for a smooth
    blade (the set-up itself)."""
    if not setup.blade.relieved:
        return [("main", setup)]
    return [(seg.name, dataclasses.replace(setup, blade=seg.blade))
            for seg in blade_segments(setup.blade)]


def check_pivot_on_main(blade: BladeSettings, depth_mm: float, *,
                        member: str = "pinion") -> None:
    """Refuse a relief whose kink lies beyond the depth ``depth_mm`` behind the tip plane
    of the blade point that cuts ``member``'s mean point: the blade corrections pivot
    there, on the main profile (a Toprem reaching it would make the relief the
    profile the blank's pressure angle is cut with)."""
    for seg in blade_segments(blade):
        lo, hi = seg.depth_mm
        if seg.name == "main" and not lo < depth_mm < hi:
            key = "toprem" if depth_mm <= lo else "flankrem"
            raise InputRangeError(
                f"{blade.where}.{key}_depth_mm", getattr(blade, f"{key}_depth_mm"),
                f"{'<' if key == 'toprem' else '>'} {depth_mm:.4f} mm, the depth behind the "
                f"tip plane of the blade point that cuts the {member}'s mean point (the "
                "settings are solved there on the blade's main profile: the standard "
                "settings' pressure angle, the setting fit's blade pivot; the relief is "
                "kept as given, not fitted)")
