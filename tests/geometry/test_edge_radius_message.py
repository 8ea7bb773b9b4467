"""A blade edge radius that cuts into the active flank is named by its key, its value
and the largest radius that clears the node (geometry.generated; docs/machine_settings.md
sec. 5, "Ordinary pairs, measured": an edge radius typed 25.4 times too large passed
``design`` and ``tca`` named only the node and "lower the sliding base or the blade
point")."""

from __future__ import annotations

import dataclasses
import math
import re
from pathlib import Path

import pytest

from gearcontact.geometry.conjugate import UndercutError
from gearcontact.geometry.generated import generated_pinion_flank
from gearcontact.geometry.pair import load_pair

EXAMPLE = Path(__file__).parents[2] / "examples" / "machine_settings" / "iso23509_f2_machine.toml"


def test_edge_radius_named_with_its_closed_form_bound():
    """F.2's pinion drive blade made straight (blade angle 20 deg) with a 10.16 mm edge
    radius (0.4 mm x 25.4): refused at a node below the round, the message naming
    ``blade.pinion.drive.edge_radius_mm``, its value, the bound and the unit slip. Truth:
    on a straight blade the round of radius r is tangent at the blade arc length
    ``l = r (1 - sin a) / cos a`` from the tip (the circle tangent to the tip plane and
    the blade line), so the bound is ``l_node cos a / (1 - sin a)`` with the node's
    arc length read from the message; tolerance 2e-4 mm: the bisection's 1e-4 mm plus
    the 4 decimals printed (0.8 s)."""
    pair = load_pair(EXAMPLE)
    setup = next(s for s in pair.machine if s.member == "pinion" and s.side == "drive")
    blade = dataclasses.replace(setup.blade, edge_radius_mm=10.16, profile_radius_mm=0.0,
                                profile_reference_mm=0.0)
    setup = dataclasses.replace(setup, blade=blade)
    with pytest.raises(UndercutError) as err:
        generated_pinion_flank(setup, pair.blank, pinion_face_width_mm=pair.pinion_face_width_mm,
                               n_u=20, n_v=24)
    text = str(err.value)
    a = math.radians(blade.blade_angle_deg)
    l_node = float(re.search(r"blade arc length ([0-9.]+) mm", text).group(1))
    l_top = float(re.search(r">= ([0-9.]+) mm", text).group(1))
    assert l_top == pytest.approx(10.16 * (1 - math.sin(a)) / math.cos(a), abs=1e-4)
    assert "blade.pinion.drive.edge_radius_mm = 10.16 mm" in text
    bound = float(re.search(r"at most ([0-9.]+) mm", text).group(1))
    assert bound == pytest.approx(l_node * math.cos(a) / (1 - math.sin(a)), abs=2e-4)
    assert "25.4 times too large? 0.4 mm keeps it" in text
