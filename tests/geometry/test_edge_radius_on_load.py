"""An edge radius whose round reaches above its flank's mean point is refused when the
pair is loaded (geometry.edge_check, in the typed-settings check), before any flank is
generated (docs/machine_settings.md sec. 5, "Ordinary pairs, measured": an edge radius
25.4 times too large passed ``design`` silently; only ``tca`` named it)."""

from __future__ import annotations

import math
import re

import pytest

from gearcontact.cli import main

from .f2_variants import retyped

STRAIGHT = {"profile_radius_mm": "0.0", "profile_reference_mm": "0.0"}


@pytest.mark.parametrize("table, changes", [
    ("blade.pinion.drive", {"edge_radius_mm": "10.16", **STRAIGHT}),
    ("blade.gear.coast", {"edge_radius_mm": "10.16"})])
def test_edge_radius_refused_by_design(tmp_path, capsys, table, changes):
    """F.2 with a straight blade's edge radius 10.16 mm (0.4 x 25.4; the pinion drive
    blade made straight, the gear coast blade is): ``design`` exits 2 naming the key,
    the value and the bound (was exit 0). Truth: on a straight blade of angle ``a`` the
    round of radius ``r`` ends at the blade arc length ``l = r (1 - sin a) / cos a``
    (the circle tangent to the tip plane and the blade line), so the round's end is that
    of 10.16 mm and the bound ``l_m cos a / (1 - sin a)`` of the mean point's arc length
    ``l_m`` read from the message; tolerance 2e-4 mm: the bisection's 1e-4 mm plus the
    4 decimals printed. ~2 s."""
    path = retyped(tmp_path, table, changes)
    assert main(["design", "--pair", str(path)]) == 2
    err = capsys.readouterr().err
    assert f"{table}.edge_radius_mm = 10.16 is outside the allowed range: <= " in err
    a = math.radians(20.0)                        # both blades' angle in the example
    l_m = float(re.search(r"blade arc length ([0-9.]+) mm from the tip", err).group(1))
    l_e = float(re.search(r"this round ends at ([0-9.]+) mm", err).group(1))
    bound = float(re.search(r"<= ([0-9.]+) mm", err).group(1))
    assert l_e == pytest.approx(10.16 * (1 - math.sin(a)) / math.cos(a), abs=1e-4)
    assert bound == pytest.approx(l_m * math.cos(a) / (1 - math.sin(a)), abs=2e-4)
    assert l_m < l_e
    assert "25.4 times too large? 0.4 mm keeps it" in err
