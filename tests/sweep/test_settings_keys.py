"""Setting keys of a sweep on a pair cut from machine settings
(:mod:`gearcontact.sweep.settings_keys`; docs/sweeps.md, "A pair cut from machine
settings").

Pair: examples/machine_settings/iso23509_f2_machine.toml (ISO 23509 F.2, all four flanks
cut from typed settings).

Truths:

1. a variant is the pair file with the value edited in: every key at the value the file
   types (0 for a key it does not type) reads back as the file's own pair, and an
   edited value equals the file edited as text and loaded by the pair reader (``==`` on
   the GearPair: every field);
2. the keys offered are exactly the tables' numeric keys (the reader's key lists), each
   with its unit;
3. a bad key or value is a named InputRangeError before any flank work: an unknown key
   lists the valid ones (and the nearest), a value outside its key's range names the
   key, the value and the reader's range, an ease-off key is refused naming the setting
   keys instead, a setting key is refused on a pair without settings;
4. a variant the reader refuses is a failed cell whose error is the reader's refusal of
   the edited file, word for word, and the other cells are computed.
"""

import tomllib
from pathlib import Path

import numpy as np
import pytest

from gearcontact.geometry.machine import (BLADE_KEYS, HELICAL_KEYS, MACHINE_KEYS,
                                          MODIFIED_ROLL_KEYS)
from gearcontact.geometry.pair import load_pair
from gearcontact.sweep.design import check_variants
from gearcontact.sweep.grid import SweepGrid, parse_vary
from gearcontact.sweep.settings_keys import (SETTING_KEYS, setting_keys, setting_unit,
                                             with_settings)
from gearcontact.validation import InputRangeError

F2 = Path(__file__).resolve().parents[2] / "examples" / "machine_settings" / \
    "iso23509_f2_machine.toml"
#: Lines only the pinion's drive tables hold in the file.
PINION_DRIVE_TILT = "tilt_deg = 19.7468\nswivel_deg = -82.0712"
PINION_DRIVE_BLADE = 'kind = "outside"\nblade_angle_deg = 20.0\npoint_radius_mm = 114.2202'
PINION_DRIVE_PROFILE = "profile_radius_mm = 516.2753\nprofile_reference_mm = 2.5762"


@pytest.fixture(scope="module")
def f2():
    return load_pair(F2)


def edited_file(tmp_path, *edits) -> Path:
    """F.2's file with each ``(old, new)`` of ``edits`` replaced, ``old`` found once (as a
    user edits it)."""
    text = F2.read_text()
    for old, new in edits:
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    path = tmp_path / "edited.toml"
    path.write_text(text)
    return path


def test_every_key_at_its_typed_value_reads_back_as_the_file(f2):
    doc = tomllib.loads(F2.read_text())
    keys = setting_keys(f2)
    for key in keys:
        table, member, side, name = SETTING_KEYS[key]
        typed = doc[table][member][side].get(name, 0.0)       # absent: not typed, 0
        assert with_settings(f2, {key: typed}) == f2, key


def test_edited_value_is_the_file_edited_as_text(f2, tmp_path):
    key = "machine.pinion.drive.modified_roll_2c_per_rad"
    want = load_pair(edited_file(tmp_path, (PINION_DRIVE_TILT, PINION_DRIVE_TILT
                                            + "\nmodified_roll_2c_per_rad = 0.02")))
    got = with_settings(f2, {key: 0.02})
    assert got == want and got != f2
    # two keys of two tables at once
    path = edited_file(tmp_path, (PINION_DRIVE_TILT, "tilt_deg = 19.5\nswivel_deg = -82.0712"),
                       (PINION_DRIVE_BLADE, PINION_DRIVE_BLADE.replace("20.0", "20.5")))
    assert with_settings(f2, {"blade.pinion.drive.blade_angle_deg": 20.5,
                              "machine.pinion.drive.tilt_deg": 19.5}) == load_pair(path)


def test_offered_keys_are_the_tables_numeric_keys_with_units(f2):
    machine = [*MACHINE_KEYS, *MODIFIED_ROLL_KEYS, *HELICAL_KEYS]
    blade = [k for k in BLADE_KEYS if k != "kind"]
    want = [f"{t}.{m}.{s}.{k}" for t, ks in (("machine", machine), ("blade", blade))
            for m in ("gear", "pinion") for s in ("drive", "coast") for k in ks]
    assert list(setting_keys(f2)) == want and len(want) == 4 * (15 + 11)
    units = {"machine.pinion.drive.tilt_deg": "deg", "machine.gear.coast.ratio_of_roll": "1",
             "machine.pinion.drive.modified_roll_2c_per_rad": "1/rad",
             "machine.pinion.drive.modified_roll_120f_per_rad4": "1/rad^4",
             "machine.pinion.coast.helical_motion_mm_per_rad": "mm/rad",
             "machine.pinion.coast.helical_motion_mm_per_rad2": "mm/rad^2",
             "blade.pinion.drive.profile_cubic_per_mm2": "1/mm^2",
             "blade.gear.drive.point_radius_mm": "mm"}
    assert {k: setting_unit(k) for k in units} == units
    for key in want:                        # every key has its unit
        setting_unit(key)
    assert setting_keys(load_pair("s0003")) == ()
    spec = parse_vary("machine.pinion.drive.modified_roll_2c_per_rad=-0.02:0.02:3", pair=f2)
    assert (spec.field, spec.unit, spec.design) == (
        "machine_pinion_drive_modified_roll_2c_per_rad", "1/rad", True)


def test_unknown_key_names_the_valid_keys_and_the_nearest(f2):
    with pytest.raises(InputRangeError) as exc:
        parse_vary("machine.pinion.drive.modified_roll_2c=0:0.02:2", pair=f2)
    assert str(exc.value) == (
        "--vary KEY = 'machine.pinion.drive.modified_roll_2c' is outside the allowed range: "
        "one of the assembly errors E, P, G, alpha or a key of the pair's "
        "[machine.<gear|pinion>.<drive|coast>] tables: radial_distance_mm, cradle_angle_deg, "
        "machine_root_angle_deg, machine_centre_to_back_mm, sliding_base_mm, "
        "blank_offset_mm, ratio_of_roll, tilt_deg, swivel_deg, modified_roll_2c_per_rad, "
        "modified_roll_6d_per_rad2, modified_roll_24e_per_rad3, "
        "modified_roll_120f_per_rad4, helical_motion_mm_per_rad, helical_motion_mm_per_rad2; "
        "or of its [blade.<gear|pinion>.<drive|coast>] tables: blade_angle_deg, "
        "point_radius_mm, edge_radius_mm, profile_radius_mm, profile_reference_mm, "
        "profile_cubic_per_mm2, profile_quartic_per_mm3, toprem_angle_deg, toprem_depth_mm, "
        "flankrem_angle_deg, flankrem_depth_mm (e.g. machine.pinion.drive.tilt_deg); did you "
        "mean machine.pinion.drive.modified_roll_2c_per_rad?")
    # the ease-off / cutter keys are not offered for it ...
    assert "easeoff." not in str(exc.value) and "cutter." not in str(exc.value)
    # ... and a setting key is not offered to a pair without settings: it is told why
    with pytest.raises(InputRangeError, match=r"\[easeoff\.\*\] / \[cutter\] tables") as exc:
        parse_vary("machine.pinion.drive.tilt_deg=19:21:2", pair=load_pair("s0003"))
    listed, _, why = str(exc.value).split("tables: ")[1].partition("; ")
    assert "machine." not in listed
    assert why == ("the [machine.*] / [blade.*] keys are a pair's cut from machine settings "
                   "(this one has none)")


@pytest.mark.parametrize("typed,meant", [
    # the engineer's word for the blade's angle; the printed 2C; a key's start
    ("blade.pinion.drive.pressure_angle_deg", "blade.pinion.drive.blade_angle_deg"),
    ("machine.pinion.drive.2C", "machine.pinion.drive.modified_roll_2c_per_rad"),
    ("machine.pinion.coast.tilt", "machine.pinion.coast.tilt_deg"),
    # a key of the other table; a near spelling
    ("blade.pinion.drive.tilt_deg", "machine.pinion.drive.tilt_deg"),
    ("machine.gear.drive.machine_root_deg", "machine.gear.drive.machine_root_angle_deg"),
    # none where a guess could mislead: a flank named concave (the member's and hand's
    # to map), a start shared by four keys, a name close to none
    ("machine.pinion.concave.tilt_deg", None), ("machine.pinion.drive.modified_roll", None),
    ("machine.pinion.drive.radial_mm", None)])
def test_the_nearest_key_is_named_only_where_it_is_clear(f2, typed, meant):
    with pytest.raises(InputRangeError) as exc:
        parse_vary(f"{typed}=0:1:2", pair=f2)
    tail = str(exc.value).rpartition("(e.g. machine.pinion.drive.tilt_deg)")[2]
    assert tail == (f"; did you mean {meant}?" if meant else "")


@pytest.mark.parametrize("spec,message", [
    ("machine.pinion.drive.tilt_deg=50:70:3",           # 50, 60 inside [0, 60]
     "--vary machine.pinion.drive.tilt_deg=70: machine.pinion.drive.tilt_deg = 70.0 is "
     "outside the allowed range: [0, 60]"),
    ("machine.pinion.drive.ratio_of_roll=0:2.785714:2",
     "--vary machine.pinion.drive.ratio_of_roll=0: machine.pinion.drive.ratio_of_roll = 0.0 "
     "is outside the allowed range: > 0: the pinion is generated (work / cradle rotation, "
     "the same sense for both hands; 0 would be a formate pinion, which is not cut), "
     "docs/machine_settings.md sec. 2 and 4"),
    ("machine.pinion.drive.modified_roll_6d_per_rad2=-200:0:3",
     "--vary machine.pinion.drive.modified_roll_6d_per_rad2=-200: "
     "machine.pinion.drive.modified_roll_6d_per_rad2 = -200.0 is outside the allowed "
     "range: [-100, 100]")])
def test_value_outside_its_range_is_named_before_any_flank(f2, spec, message):
    grid = SweepGrid((parse_vary(spec, pair=f2),), (64.5,))
    with pytest.raises(InputRangeError) as exc:
        check_variants(f2, grid)
    assert str(exc.value) == message


def test_keys_of_one_blade_are_checked_together(f2):
    # a Toprem angle needs its depth: the variant (2 deg, 0 mm) is refused naming both
    # keys' values; with a depth every variant reads
    grid = SweepGrid((parse_vary("blade.pinion.drive.toprem_angle_deg=0:2:2", pair=f2),
                      parse_vary("blade.pinion.drive.toprem_depth_mm=0:1:2", pair=f2)),
                     (64.5,))
    with pytest.raises(InputRangeError) as exc:
        check_variants(f2, grid)
    assert str(exc.value) == (
        "--vary blade.pinion.drive.toprem_angle_deg=2, blade.pinion.drive.toprem_depth_mm=0: "
        "blade.pinion.drive.toprem_depth_mm = 0.0 is outside the allowed range: (0, 50] mm "
        "with toprem_angle_deg > 0 (the kink's depth behind the blade tip plane)")
    check_variants(f2, SweepGrid(
        (grid.vary[0], parse_vary("blade.pinion.drive.toprem_depth_mm=1:2:2", pair=f2)),
        (64.5,)))


def test_easeoff_key_on_a_settings_pair_names_the_setting_keys(f2):
    grid = SweepGrid((parse_vary("easeoff.drive.bias_um_per_mm2=0:0.1:2", pair=f2),), (64.5,))
    with pytest.raises(InputRangeError) as exc:
        check_variants(f2, grid)
    msg = str(exc.value)
    assert msg.startswith("--vary easeoff.drive.bias_um_per_mm2 = 'pair iso23509_f2_machine "
                          "(cut from [machine.*] / [blade.*] settings)'"), msg
    assert "such a pair varies a key of the pair's [machine.<gear|pinion>." in msg, msg


def test_variant_the_reader_refuses_is_a_failed_cell_with_its_refusal(f2, tmp_path):
    """profile_radius_mm 10 on the pinion's drive blade (a strongly curved blade) makes a
    pointed pinion the reader refuses (exit 2 of every command on that file): the sweep
    returns with the cell failed and the refusal as its error. About 8 s."""
    from gearcontact.sweep.run import run_sweep
    from gearcontact.tca.synthesis import prepare_pair

    xr = pytest.importorskip("xarray")
    grid = SweepGrid((parse_vary("blade.pinion.drive.profile_radius_mm=10:10:1", pair=f2),),
                     (64.5,))
    check_variants(f2, grid)                   # inside the key's range
    rep = run_sweep(f2, grid, out=tmp_path / "s", side="drive", phases=5, workers=0,
                    progress=False)
    ds = xr.open_zarr(rep.store, consolidated=False).load()
    assert (rep.computed, rep.failed) == (1, 1)
    assert ds["status"].values.ravel().tolist() == [2]
    edited = edited_file(tmp_path, (PINION_DRIVE_PROFILE,
                                    PINION_DRIVE_PROFILE.replace("516.2753", "10.0")))
    with pytest.raises(InputRangeError) as refusal:
        prepare_pair(load_pair(edited))
    assert ds["error"].values.ravel()[0] == f"InputRangeError: {refusal.value}"
    assert "pointed pinion tooth" in str(refusal.value)
    assert np.isnan(ds["te0_pp_arcsec"].values[0, 0])


def test_store_keeps_each_variant_s_reader_warnings(f2, tmp_path):
    """The reader's warnings of a variant (long lines) go into ``settings_warning`` beside
    its cells, a failed one's too; a variant without any leaves ``""``. No flank is
    built: the variants are given as built (:class:`~gearcontact.sweep.design.Variant`)."""
    from gearcontact.sweep.design import Variant
    from gearcontact.sweep.run import _guarded
    from gearcontact.sweep.store import prepare_store, write_point

    xr = pytest.importorskip("xarray")
    grid = SweepGrid((parse_vary("machine.pinion.drive.tilt_deg=19:20:3", pair=f2),),
                     (32.25, 64.5))
    path = tmp_path / "sweep.zarr"
    prepare_store(path, grid, ("tca",), {"pair": f2.name})
    said = ("SettingsWarning: " + "x" * 600, "HollowEaseOffWarning: y")
    failed = Variant(None, None, 1.5, "InputRangeError: z", said)
    write_point(path, grid, (2,), _guarded(failed, {}, [32.25, 64.5], {}))
    write_point(path, grid, (0,), _guarded(Variant(None, None, 1.0, "InputRangeError: w"),
                                           {}, [32.25, 64.5], {}))
    ds = xr.open_zarr(path, consolidated=False).load()
    assert ds["settings_warning"].values.tolist() == [["", ""], ["", ""], ["; ".join(said)] * 2]
    assert ds["error"].values.tolist() == [["InputRangeError: w"] * 2, ["", ""],
                                           ["InputRangeError: z"] * 2]
    assert ds["status"].values.tolist() == [[2, 2], [0, 0], [2, 2]]


@pytest.mark.slow
def test_hollow_pinion_variant_is_computed_with_the_reader_s_warning(f2, tmp_path):
    """profile_radius_mm -300 on the pinion's drive blade (a hollow profile) makes a
    pinion the reader warns hollow and the commands analyse: the cell is the TCA of the
    edited file, bit for bit, and keeps the reader's warning word for word. About 30 s."""
    from gearcontact.geometry.easeoff_shape import HollowEaseOffWarning
    from gearcontact.sweep.cell import TCA_VARIABLES, _tca_values
    from gearcontact.sweep.run import run_sweep
    from gearcontact.tca.analysis import analyze_pair
    from gearcontact.tca.synthesis import prepare_pair

    xr = pytest.importorskip("xarray")
    grid = SweepGrid((parse_vary("blade.pinion.drive.profile_radius_mm=-300:-300:1",
                                 pair=f2),), (64.5,))
    rep = run_sweep(f2, grid, out=tmp_path / "s", side="drive", phases=5, workers=0,
                    progress=False)
    ds = xr.open_zarr(rep.store, consolidated=False).load().isel(torque_nm=0)
    edited = edited_file(tmp_path, (PINION_DRIVE_PROFILE,
                                    PINION_DRIVE_PROFILE.replace("516.2753", "-300.0")))
    with pytest.warns(HollowEaseOffWarning) as caught:
        prepared = prepare_pair(load_pair(edited))
    res, _ = analyze_pair(prepared.pair, side="drive", phases=5,
                          flanks=prepared.flank_set())
    want = _tca_values(res)
    for name in TCA_VARIABLES:
        assert ds[name].values.tolist() == [want[name]], name
    hollow = [str(w.message) for w in caught if w.category is HollowEaseOffWarning]
    assert len(hollow) == 1 and "hollow" in hollow[0]
    assert ds["error"].values.tolist() == [""]
    assert f"HollowEaseOffWarning: {hollow[0]}" in ds["settings_warning"].values[0]


@pytest.mark.slow
def test_cluster_equals_serial_for_setting_variants(f2, client, tmp_path):
    """Two tilt variants × two offsets on the LocalCluster of tests/sweep/conftest.py
    and in this process: the same Dataset, bit for bit but the build timings. About
    1.5 min at load 20."""
    from gearcontact.sweep.run import run_sweep

    xr = pytest.importorskip("xarray")
    grid = SweepGrid((parse_vary("machine.pinion.drive.tilt_deg=19.5:20:2", pair=f2),
                      parse_vary("E=-0.02:0.02:2")), (64.5,))
    got = {}
    for name, kw in (("serial", {"workers": 0}), ("cluster", {"client": client})):
        rep = run_sweep(f2, grid, out=tmp_path / name, side="drive", phases=5,
                        progress=False, **kw)
        assert (rep.computed, rep.failed) == (4, 0)
        got[name] = xr.open_zarr(rep.store, consolidated=False).load().drop_vars(
            "flank_build_s")
    xr.testing.assert_identical(got["serial"], got["cluster"])
    te = got["serial"]["te0_pp_arcsec"].values[:, :, 0]
    assert te[0, 0] != te[1, 0]                # another tilt, other flanks


def test_a_print_s_gear_offers_only_the_pinion_keys():
    """The published 10 x 41 hypoid print's pair file (tests/geometry/summary_sheets):
    its gear is cut from the [print.gear] page, whose words the writer keeps, so a gear
    key edited beside it would not be read: only the pinion's keys are offered, and one
    of them edited reads back as the file edited."""
    import warnings

    path = Path(__file__).resolve().parents[1] / "geometry" / "summary_sheets" / \
        "hypoid_10x41_no16_pair.toml"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")       # the print's datum and settings check
        pair = load_pair(path)
        keys = setting_keys(pair)
        assert keys and all(".pinion." in k for k in keys) and len(keys) == 2 * (15 + 11)
        with pytest.raises(InputRangeError) as exc:
            parse_vary("machine.gear.drive.tilt_deg=0:1:2", pair=pair)
        assert ("a key of the pair's [machine.<pinion>.<drive|coast>] tables (the gear is "
                "cut from its [print.gear] page): radial_distance_mm") in str(exc.value)
        doc = tomllib.loads(path.read_text())
        typed = doc["machine"]["pinion"]["coast"]["tilt_deg"]
        assert with_settings(pair, {"machine.pinion.coast.tilt_deg": typed}) == pair
        moved = with_settings(pair, {"machine.pinion.coast.tilt_deg": typed + 0.5})
        assert moved.machine != pair.machine and moved.print_gear == pair.print_gear
