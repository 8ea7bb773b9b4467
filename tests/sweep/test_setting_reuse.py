"""A settings sweep reuses the flanks whose inputs a variant leaves as they were
(:data:`gearcontact.sweep.settings_keys.VARIANT_FLANKS`,
:mod:`gearcontact.geometry.flank_reuse`; docs/sweeps.md, "A pair cut from machine
settings").

Pair: examples/machine_settings/iso23509_f2_machine.toml (ISO 23509 F.2). Grid: the
pinion's drive 2C (0, 0.01) x the gear's drive sliding base typed and one digit off
(-5.6403 and as typed, -5.6402: a key collision attempt) x E (-0.02, 0.02), TCA and LTCA at 64.5 N·m,
5 phases, in this process.

Truths (``==``, no tolerance):

1. the store with reuse is the store with every variant cut afresh (reuse off), every
   variable bit for bit but the build timings: a variant whose pinion key changed (the
   gear flanks reused), one whose gear key changed (the pinion flanks reused, turned
   onto the new gear) and one whose every flank is reused;
2. the variants one digit apart are two results (a served stale flank would make them
   one);
3. only the changed flanks are cut: 4 for the first variant, then one per changed
   (member, flank); E is an assembly error and cuts nothing (each variant built once
   for both E);
4. a print's generated gear (the 10 x 41 hypoid print, its gear set-ups read from the
   page's words for every variant) is reused for a pinion key, the flank set equal to
   the fresh cut.
"""

from pathlib import Path

import pytest

xr = pytest.importorskip("xarray")

from gearcontact.geometry.flank_reuse import FlankCache  # noqa: E402
from gearcontact.geometry.pair import load_pair  # noqa: E402
from gearcontact.sweep import settings_keys  # noqa: E402
from gearcontact.sweep.grid import SweepGrid, parse_vary  # noqa: E402
from gearcontact.sweep.run import run_sweep  # noqa: E402

F2 = Path(__file__).resolve().parents[2] / "examples" / "machine_settings" / \
    "iso23509_f2_machine.toml"
MACHINE_FLANK = "gearcontact.geometry.kinked.machine_flank"


@pytest.mark.slow
def test_reused_variants_are_the_fresh_cuts(tmp_path, monkeypatch):
    """About 90 s at load 16."""
    pair = load_pair(F2)
    grid = SweepGrid((parse_vary("machine.pinion.drive.modified_roll_2c_per_rad=0:0.01:2",
                                 pair=pair),
                      parse_vary("machine.gear.drive.sliding_base_mm=-5.6403:-5.6402:2",
                                 pair=pair),
                      parse_vary("E=-0.02:0.02:2")), (64.5,))
    got = {}
    for name, cache in (("fresh", None), ("reused", FlankCache())):
        monkeypatch.setattr(settings_keys, "VARIANT_FLANKS", cache)
        rep = run_sweep(pair, grid, out=tmp_path / name, side="drive", compute=("tca", "ltca"),
                        phases=5, cells=24, workers=0, progress=False)
        assert (rep.computed, rep.failed) == (8, 0)
        got[name] = xr.open_zarr(rep.store, consolidated=False).load().drop_vars(
            "flank_build_s")
    xr.testing.assert_identical(got["fresh"], got["reused"])
    # variants in grid order (2C, sliding base): 4 cut, + gear drive (typed), + pinion
    # drive, + 0
    assert cache.misses[MACHINE_FLANK] == 4 + 1 + 1 + 0
    te = got["reused"]["te0_pp_arcsec"].values[..., 0]        # (2C, sliding base, E)
    assert (te[:, 0] != te[:, 1]).all()         # one digit apart: two results
    assert (te[0] != te[1]).all()


@pytest.mark.slow
def test_a_print_s_generated_gear_is_reused_for_a_pinion_key(monkeypatch):
    """The published 10 x 41 hypoid print's pair (tests/geometry/summary_sheets; its
    gear generated, cut from the [print.gear] page's words read for each variant): a
    pinion tilt changed after the typed one cuts the pinion's drive flank alone, and the
    flank set equals the variant's fresh cut (every field, :func:`exact_key`, whose
    bit-exactness tests/geometry/test_flank_reuse.py tests). About 40 s at load 17."""
    import warnings

    from gearcontact.geometry.flank_reuse import exact_key
    from gearcontact.sweep.settings_keys import build_setting_variant

    path = Path(__file__).resolve().parents[1] / "geometry" / "summary_sheets" / \
        "hypoid_10x41_no16_pair.toml"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")       # the print's datum and settings check
        pair = load_pair(path)
        tilt = next(s for s in pair.machine
                    if (s.member, s.side) == ("pinion", "drive")).settings.tilt_deg
        key = "machine.pinion.drive.tilt_deg"
        cache = FlankCache()
        monkeypatch.setattr(settings_keys, "VARIANT_FLANKS", cache)
        build_setting_variant(pair, ((key, tilt),))
        assert cache.misses[MACHINE_FLANK] == 4
        _, got = build_setting_variant(pair, ((key, tilt + 0.1),))
        assert cache.misses[MACHINE_FLANK] == 5
        monkeypatch.setattr(settings_keys, "VARIANT_FLANKS", None)
        _, fresh = build_setting_variant(pair, ((key, tilt + 0.1),))
    assert exact_key(got) == exact_key(fresh)
