"""The attribution of a disagreeing flank tries a curved blade's profile keys
(geometry.typed_settings.attributed_keys; docs/machine_settings.md sec. 5, "Ordinary
pairs, measured": a pinion coast ``profile_reference_mm`` typed 50 was explained by three
other keys only)."""

from __future__ import annotations

import re

from gearcontact.geometry import blank_check
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.typed_settings import typed_keys

from .f2_variants import EXAMPLE, retyped

SHIPPED_REFERENCE_MM = 2.5774     # the example's pinion coast profile_reference_mm


def test_profile_reference_slip_is_named(tmp_path):
    """F.2's pinion coast blade (curved, r_b 516.2753 mm) with its profile reference typed
    50 mm for 2.5774: the pressure angle 13.89 deg against 20 (warning). The key is now
    among those that alone make the flank agree, its agreeing interval holding the
    shipped value and not the typed one. Truth: the shipped example agrees with its
    blank (test_basic_settings.py); no tolerance (an inclusion of values printed to 2
    digits of the half-width: the interval's ends are brentq roots to 1e-3 of the
    narrowest band, far inside the 20 mm half-width measured). ~6 s."""
    pair = load_pair(retyped(tmp_path, "blade.pinion.coast", {"profile_reference_mm": "50.0"}))
    got = blank_check.check_pair_blank(pair)
    coast = next(f for f in got.flanks if f.member == "pinion" and f.side == "coast")
    assert not coast.agrees and not coast.slip
    ref = next(k for k in coast.single_keys if k.key == "blade.pinion.coast.profile_reference_mm")
    assert ref.typed == 50.0
    assert ref.low <= SHIPPED_REFERENCE_MM <= ref.high and not ref.low <= 50.0 <= ref.high
    line = next(w for w in got.warnings() if "pinion coast" in w)
    needs = re.search(r"blade\.pinion\.coast\.profile_reference_mm typed 50; the blank needs "
                      r"([0-9.]+) \+- ([0-9.]+)", line)
    assert needs, line
    assert abs(float(needs.group(1)) - SHIPPED_REFERENCE_MM) <= float(needs.group(2))


def test_clean_sheet_costs_what_it_did(monkeypatch):
    """The shipped example agrees: its check measures the same flanks with the profile
    keys tried as without them (their rounding is not propagated; the attribution runs
    on disagreeing flanks only). Truth: the solve count of the check with the
    attribution's keys replaced by the propagated ones (the code before); exact (a
    count)."""
    pair = load_pair(EXAMPLE)
    calls = []
    for name in ("measure_mean_point", "measure_generating_angles"):
        real = getattr(blank_check, name)
        monkeypatch.setattr(blank_check, name,
                            lambda *a, real=real, **k: calls.append(1) or real(*a, **k))
    assert blank_check.check_pair_blank(pair).agrees
    with_profile = len(calls)
    calls.clear()
    monkeypatch.setattr(blank_check, "attributed_keys", typed_keys)
    assert blank_check.check_pair_blank(pair).agrees
    assert with_profile == len(calls) > 0
