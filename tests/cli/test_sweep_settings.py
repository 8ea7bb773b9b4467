"""``gearcontact sweep --vary`` over the machine and blade keys of a pair cut from
settings (:mod:`gearcontact.sweep.settings_keys`; docs/sweeps.md, "A pair cut from
machine settings").

Pair: examples/machine_settings/iso23509_f2_machine.toml (ISO 23509 F.2, all four flanks
cut from typed settings), the docs' example.

Truths:

1. a varied key's cell is ``gearcontact tca`` on the pair file with that value edited in
   (written as text into a tmp dir): the same numbers, bit for bit (``==``: the cell is
   read and cut through the reader's own path, so nothing may differ);
2. a one-point sweep at the typed value is ``gearcontact tca``, ``ltca`` and ``lte
   --rigid`` on the file itself (``==``; slow): the sweep's LTCA at P0 with its
   ``--cells``, its loaded TE with ``LTE_CELLS`` = 40 cells at every phase (its stride is
   1 at 11 phases), the commands given the same;
3. a bad key or value is exit 2 with the exact text, before any output (the console
   script, as a user types the README's line).
"""

import json
from pathlib import Path

import pytest

pytest.importorskip("distributed")
xr = pytest.importorskip("xarray")

from console_script import run_console  # noqa: E402
from gearcontact.cli import main  # noqa: E402
from gearcontact.sweep.cell import LTE_CELLS, lte_stride  # noqa: E402

F2 = Path(__file__).resolve().parents[2] / "examples" / "machine_settings" / \
    "iso23509_f2_machine.toml"
#: The lines of the file's [machine.pinion.drive] table the tests edit (found once).
PINION_DRIVE_TILT = "tilt_deg = 19.7468\nswivel_deg = -82.0712"


def _cell(out: Path, **index):
    return xr.open_zarr(out / "sweep.zarr", consolidated=False).load().isel(
        torque_nm=0, **index)


def test_varied_key_cell_is_tca_on_the_edited_file(tmp_path, capsys):
    """About 20 s: a one-point sweep, one ``tca``; 5 phases (the comparison is bit for
    bit at any phase count). That the edit moves the pair:
    tests/sweep/test_settings_keys.py."""
    key = "machine.pinion.drive.modified_roll_2c_per_rad"
    sweep = tmp_path / "sweep"
    assert main(["sweep", "--pair", str(F2), "--vary", f"{key}=0.02:0.02:1", "--phases", "5",
                 "--workers", "0", "--quiet", "--no-figures", "--out", str(sweep)]) == 0
    assert "1 computed, 0 already finished, 0 failed" in capsys.readouterr().out
    edited = tmp_path / "edited.toml"
    text = F2.read_text()
    assert text.count(PINION_DRIVE_TILT) == 1
    edited.write_text(text.replace(PINION_DRIVE_TILT,
                                   PINION_DRIVE_TILT + "\nmodified_roll_2c_per_rad = 0.02"))
    tca = tmp_path / "tca"
    assert main(["tca", "--pair", str(edited), "--phases", "5", "--no-figures", "--quiet",
                 "--out", str(tca)]) == 0
    want = json.loads((tca / "tca.json").read_text())
    field = key.replace(".", "_")
    got = _cell(sweep, **{field: 0})
    assert float(got[field]) == 0.02 and got[field].attrs == {"units": "1/rad", "key": key}
    assert float(got["te0_pp_arcsec"]) == want["te0_pp_arcsec"]
    assert float(got["paint_major_mm"]) == 2 * want["paint_ellipse"]["semi_major_mm"]
    assert bool(got["pattern_on_flank"]) == want["pattern_on_flank"]
    assert (got["error"].item(), got["settings_warning"].item()) == ("", "")


@pytest.mark.slow
def test_one_point_sweep_at_the_typed_value_is_tca_ltca_and_lte(tmp_path, capsys):
    """About 1 min: the sweep (TCA, LTCA at P0, loaded TE) and the three commands."""
    assert lte_stride(11) == 1 and LTE_CELLS == 40       # the lte command's options below
    sweep = tmp_path / "sweep"
    assert main(["sweep", "--pair", str(F2), "--vary",
                 "machine.pinion.drive.tilt_deg=19.7468:19.7468:1", "--phases", "11",
                 "--compute", "tca,ltca", "--cells", "32", "--workers", "0", "--quiet",
                 "--no-figures", "--out", str(sweep)]) == 0
    got = _cell(sweep, machine_pinion_drive_tilt_deg=0)
    runs = {"tca": [], "ltca": ["--cells", "32", "--torque", "64.5"],
            "lte": ["--rigid", "--cells", str(LTE_CELLS), "--torque", "64.5"]}
    want = {}
    for command, extra in runs.items():
        assert main([command, "--pair", str(F2), "--phases", "11", *extra, "--no-figures",
                     "--quiet", "--out", str(tmp_path / command)]) == 0
        want[command] = json.loads((tmp_path / command / f"{command}.json").read_text())
    pairs = {"te0_pp_arcsec": want["tca"]["te0_pp_arcsec"],
             "paint_major_mm": 2 * want["tca"]["paint_ellipse"]["semi_major_mm"],
             "preview_p_max_mpa": want["ltca"]["preview_p_max_mpa"],
             "lcp_p90_mpa": want["ltca"]["p90_mpa"],
             "lcp_peak_mpa": want["ltca"]["p_peak_mpa"],
             "lte_lcp_pp_arcsec": want["lte"]["te_lcp_pp_arcsec"],
             "lte_preview_pp_arcsec": want["lte"]["te_pre_pp_arcsec"]}
    assert {k: float(got[k]) for k in pairs} == pairs                  # bit for bit
    assert bool(got["pattern_on_flank"]) == want["tca"]["pattern_on_flank"]
    assert bool(got["ltca_edge_contact"]) == want["ltca"]["edge_contact"]
    assert (got["error"].item(), got["settings_warning"].item()) == ("", "")


@pytest.mark.parametrize("vary,message", [
    ("machine.pinion.drive.tilt=19:21:3",
     "--vary KEY = 'machine.pinion.drive.tilt' is outside the allowed range: one of the "
     "assembly errors E, P, G, alpha or a key of the pair's "
     "[machine.<gear|pinion>.<drive|coast>] tables: radial_distance_mm, cradle_angle_deg, "
     "machine_root_angle_deg, machine_centre_to_back_mm, sliding_base_mm, blank_offset_mm, "
     "ratio_of_roll, tilt_deg, swivel_deg, modified_roll_2c_per_rad, "
     "modified_roll_6d_per_rad2, modified_roll_24e_per_rad3, modified_roll_120f_per_rad4, "
     "helical_motion_mm_per_rad, helical_motion_mm_per_rad2; or of its "
     "[blade.<gear|pinion>.<drive|coast>] tables: blade_angle_deg, point_radius_mm, "
     "edge_radius_mm, profile_radius_mm, profile_reference_mm, profile_cubic_per_mm2, "
     "profile_quartic_per_mm3, toprem_angle_deg, toprem_depth_mm, flankrem_angle_deg, "
     "flankrem_depth_mm (e.g. machine.pinion.drive.tilt_deg); did you mean "
     "machine.pinion.drive.tilt_deg?"),
    # -5 (the first of -5, 0, 5) lies in the band a curved blade's radius cannot take
    ("blade.pinion.drive.profile_radius_mm=-5:5:3",
     "--vary blade.pinion.drive.profile_radius_mm=-5: blade.pinion.drive.profile_radius_mm"
     " = -5.0 is outside the allowed range: 0 (straight blade) or |r| >= 10 mm")],
    ids=["unknown key", "value outside its range"])
def test_bad_key_or_value_exits_2_with_the_exact_text(tmp_path, vary, message):
    out = tmp_path / "o"
    code, stdout, err = run_console("sweep", "--pair", F2, "--vary", vary, "--out", out)
    assert (code, stdout) == (2, "")
    assert err == f"gearcontact sweep: error: {message}\n"
    assert not out.exists()
