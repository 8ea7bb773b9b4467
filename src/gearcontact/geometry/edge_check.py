"""The blade edge round against the flank it cuts, checked when a pair cut from machine
settings is loaded (:func:`~.settings_check.check_settings`; docs/machine_settings.md
sec. 2, "The check when a pair is loaded"), before any flank is generated.

The flank a set-up cuts starts above the top of its blade's edge round (the round cuts
the root fillet, :mod:`.fillet`): the blade point that generates the flank's mean point
lies at the blade arc length ``l_m`` from the tip (measured by the typed-settings check,
:class:`~.flank_angles.MeanPointAngles` ``blade_length_mm``), and the round ends at
``l_e`` (:func:`~.generated_box.edge_length_mm`; ``l_e = r (1 - sin a) / cos a`` on a
straight blade of angle ``a``). A round that ends above the mean point (``l_e > l_m``)
would cut the active flank there: refused, naming the edge radius and the largest one
that keeps the round below the mean point (:func:`~.generated_box.edge_radius_bound_mm`,
the bound the envelope's node check names, :mod:`.generated`). A round below the mean
point that still reaches a node of the active flank elsewhere (the edge line above the
mean height at the toe or heel only) is refused later by that node check.
"""

from __future__ import annotations

from ..validation import InputRangeError
from .generated import tip_setup
from .generated_box import edge_length_mm, edge_radius_bound_mm, inch_hint

__all__ = ["check_edge_rounds"]


def check_edge_rounds(setups, measured) -> None:
    """Raise :class:`~gearcontact.validation.InputRangeError` for the first set-up of
    ``setups`` (:class:`~.machine.MachineSetup`) whose blade edge round ends above its
    flank's mean point (module docstring); ``measured``: one
    :class:`~.flank_angles.FlankMeanPoint` per set-up (a flank that does not reach its
    mean point is the typed-settings check's, skipped here)."""
    for setup, m in zip(setups, measured):
        if m.pitch_cone is None or setup.blade.edge_radius_mm == 0.0:
            continue
        tip = tip_setup(setup)                  # a relieved blade's round: its tip segment's
        l_m, l_e = m.pitch_cone.blade_length_mm, edge_length_mm(tip)
        if l_e <= l_m:
            continue
        bound = edge_radius_bound_mm(tip, l_m)
        blade = setup.blade
        raise InputRangeError(
            f"{blade.where}.edge_radius_mm", blade.edge_radius_mm,
            f"<= {bound:.4f} mm, a round that ends below the blade point cutting the "
            f"{setup.member} {setup.side} flank's mean point (blade arc length {l_m:.4f} mm "
            f"from the tip; this round ends at {l_e:.4f} mm and would cut the active flank)"
            f"{inch_hint(blade, bound)}")
