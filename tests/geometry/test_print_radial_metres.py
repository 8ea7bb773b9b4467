"""A print's radial typed in metres (geometry.known_slips.PRINT_UNIT_SLIPS;
docs/machine_settings.md sec. 2, "A print's radial typed in metres").

The No. 16 page's `radial_in = 4.108` typed as metres to 4 decimals, 0.1043 (the slip
made here from the page's value, so the key and the conversion are known in advance).
The gear flanks miss their mean point (the generating gear 85.91 deg, 115.65 mm against
26.95 deg, 92.685 mm): session 28 refused it naming the whole `[print.gear]` table,
because no known slip of the converted millimetres (2.649 mm) gives the page's 104.3.

Truths: 0.1043 m x 1000 / 25.4 = 4.1063 in, within the metres' half unit (5e-5 m =
0.00197 in) of the page's 4.108, so the conversion is the slip and its rounding; the
refusal names the print's key as typed, its value and that conversion, before any flank
is built (the check measures the mean point only).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from gearcontact.geometry.blank_check import check_flanks
from gearcontact.geometry.blank_statement import printed_stated_blank, stated_blank
from gearcontact.geometry.known_slips import INCH_MM
from gearcontact.geometry.pair import load_pair
from gearcontact.validation import InputRangeError

ROOT = Path(__file__).resolve().parents[2]
PRINT_GEAR = ROOT / "examples" / "machine_settings" / "hypoid_10x41_print_gear.toml"


def test_radial_in_metres_is_refused_naming_the_unit(tmp_path):
    text = PRINT_GEAR.read_text()
    assert text.count("\nradial_in = 4.108") == 1
    typed = round(4.108 * INCH_MM / 1000.0, 4)
    assert typed == 0.1043 and abs(typed * 1000.0 / INCH_MM - 4.108) <= 0.5e-4 * 1000 / INCH_MM
    path = tmp_path / "print_radial_m.toml"
    path.write_text(text.replace("\nradial_in = 4.108", f"\nradial_in = {typed}"))
    with pytest.warns(Warning):           # the page's blank against the pair's (a note)
        pair = load_pair(path, gear_alone=True)
    gear = {s.side: s for s in pair.typed_gear}
    got = check_flanks((gear["drive"], gear["coast"]), stated_blank(pair),
                       member_stated={"gear": printed_stated_blank(pair)})
    for f in got.flanks:
        assert f.missing and f.slip == "print.gear.radial_in" and f.slip_value == typed
        assert f.slip_word == "unit corrected (typed in metres: x 1000 / 25.4 in)"
    with pytest.raises(InputRangeError) as err:
        got.raise_if_gross()
    assert (err.value.field, err.value.value) == ("print.gear.radial_in", typed)
    words = str(err.value)
    assert "the unit that cuts the printed blank's tooth" in words
    assert "with the unit corrected (typed in metres: x 1000 / 25.4 in) the flank agrees" \
        in words
    assert "; also" not in words            # the coast's key is the same print key
