"""``gearcontact design --machine-settings --target-flank CSV`` with rows of the gear
(a measuring room's gear measurement, docs/export.md "The measuring grid"; the gear's
setting correction, geometry.gear_correction, docs/machine_settings.md sec. 6 "Gear
flanks"), through the installed console script with default options.

Truth: the gear of the ISO 23509 F.2 pair cut from its settings with known
perturbations, measured on the nominal CMM grid (tests/easeoff_grid.py): the written
settings are the perturbed ones (the library's recovery and its first-order bounds:
tests/geometry/test_gear_correction.py). Careless input exits 2 naming the field, the
value and the allowed range.
"""

import math

import pytest
from console_script import run_console
from easeoff_grid import member_pivot_length_mm, write_gear_measured_csv

from gearcontact.geometry.gear_correction import gear_seeds
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.setting_fit import apply_corrections

F2_MACHINE = "examples/machine_settings/iso23509_f2_machine.toml"
F2_BLANK = "examples/iso23509_f2_spiral_bevel.toml"
#: Known perturbations of the formate gear (its default subset; ~10-15 um on the flank).
_PERTURBATION = {"blade_radius_mm": 0.02, "blade_angle_deg": -0.05,
                 "machine_root_angle_deg": 0.01, "machine_centre_to_back_mm": -0.02,
                 "blank_offset_mm": 0.02}
_FIELDS = ("radial_distance_mm", "cradle_angle_deg", "machine_root_angle_deg",
           "machine_centre_to_back_mm", "sliding_base_mm", "blank_offset_mm", "ratio_of_roll")


def _measured(tmp_path, pair_file, sides=("drive", "coast")):
    """The CSV of both gear flanks cut with the perturbation; ``{side: true setup}``."""
    pair = load_pair(pair_file)
    text, truth = "", {}
    for side in sides:
        seed = gear_seeds(pair, "formate")[side]
        truth[side] = apply_corrections(seed, _PERTURBATION,
                                        pivot_length_mm=member_pivot_length_mm(seed, pair.blank))
        part = tmp_path / f"{side}.csv"
        write_gear_measured_csv(part, pair, seed, truth[side], side)
        lines = part.read_text().splitlines(keepends=True)
        text += "".join(lines if not text else lines[2:])     # one header
    path = tmp_path / "gear_measured.csv"
    path.write_text(text)
    return path, truth


def _check_gear(written, truth):
    # the written gear settings are the cut ones: within 1e-9 (mm, deg) of each; the
    # library's first-order bound from these data's own error (6e-11 um) is below
    # 2e-11 per setting (tests/geometry/test_gear_correction.py), the margin the fit's
    # stopping in another process (BLAS) may take; the TOML writes floats by repr
    for side, true in truth.items():
        got = next(s for s in written.machine if s.member == "gear" and s.side == side)
        for f in _FIELDS:
            assert math.isclose(getattr(got.settings, f), getattr(true.settings, f),
                                abs_tol=1e-9), (side, f)
        for f in ("blade_angle_deg", "point_radius_mm"):
            assert math.isclose(getattr(got.blade, f), getattr(true.blade, f),
                                abs_tol=1e-9), (side, f)


def _design(pair_file, path, out):
    """``design --machine-settings --target-flank`` through the console script, default
    options, exit 0; its stdout and the written pair."""
    code, stdout, err = run_console("design", "--pair", pair_file, "--machine-settings",
                                    "--target-flank", path, "--out", out)
    assert code == 0, err
    return stdout, load_pair(out / "machine_settings.toml")


def test_gear_rows_of_a_machine_pair_correct_its_gear_and_keep_its_pinion(tmp_path):
    # ~5 s: two formate gear fits at 99 points each, no pinion work
    path, truth = _measured(tmp_path, F2_MACHINE)
    out = tmp_path / "out"
    stdout, written = _design(F2_MACHINE, path, out)
    assert "| gear side | points |" in stdout and "| drive | 99 |" in stdout
    _check_gear(written, truth)
    own = load_pair(F2_MACHINE)
    assert [s for s in written.machine if s.member == "pinion"] == \
        [s for s in own.machine if s.member == "pinion"]          # exactly the pair's
    rows = (out / "machine_settings_gear_points.csv").read_text().splitlines()
    assert rows[0].startswith("member,flank,line,L_mm,R_mm,deviation_um") and len(rows) == 199
    # the residual at each point, < 0.01 um (measured ~6e-11 um)
    assert max(abs(float(r.split(",")[-1])) for r in rows[1:]) < 0.01


@pytest.mark.slow
def test_gear_rows_of_a_blank_pair_with_its_pinion_fitted(tmp_path):
    # ~25 s on 2 busy cores: the pinion fitted to the pair's (zero) ease-off as before
    # (both sides: the conjugate seed, residual 0) and the gear corrected from the
    # blank's formate gear
    path, truth = _measured(tmp_path, F2_BLANK)
    stdout, written = _design(F2_BLANK, path, tmp_path / "out")
    _check_gear(written, truth)
    assert "| correction | unit | drive | coast |" in stdout       # the pinion table too


@pytest.mark.slow
def test_export_flanks_measuring_grid_of_the_gear_back_through_design(tmp_path):
    # ~20 s (export flanks writes both members' STEP files): the user's loop. The
    # gear's nominal measuring grids (5 x 9, the default Gleason grid) of `export
    # flanks`, each point's deviation from the gear cut with the perturbation along the
    # grid's own normal (the exact cones, tests/easeoff_grid.py), typed into the
    # measured file and given to design: the written gear is the cut one.
    import numpy as np
    from easeoff_grid import line_deviations_mm

    from gearcontact.geometry.generated import gear_flank_of
    from gearcontact.geometry.measuring_grid import flank_parameters_at

    exported = tmp_path / "export"
    code, _, err = run_console("export", "flanks", "--pair", F2_MACHINE, "--out", exported)
    assert code == 0, err
    pair = load_pair(F2_MACHINE)
    rows, truth = ["member,flank,row,col,L_mm,R_mm,deviation_um"], {}
    for side in ("drive", "coast"):
        seed = gear_seeds(pair, "formate")[side]
        truth[side] = apply_corrections(seed, _PERTURBATION,
                                        pivot_length_mm=member_pivot_length_mm(seed, pair.blank))
        lines = [r.split(",") for r in (exported / f"gear_{side}_measuring.csv").read_text()
                 .splitlines() if not r.startswith("#")]
        head, data = lines[0], lines[1:]
        col = {h: i for i, h in enumerate(head)}
        num = np.array([[float(r[col[c]]) for c in ("L_mm", "R_mm", "x_mm", "y_mm", "z_mm",
                                                    "nx", "ny", "nz")] for r in data])
        nominal, cut = (gear_flank_of(s, pair.blank, gear_face_width_mm=pair.gear_face_width_mm)
                        for s in (seed, truth[side]))
        u, v = flank_parameters_at(nominal, member="gear", L_mm=num[:, 0], R_mm=num[:, 1],
                                   where="export")
        p = nominal.evaluate(u, v, second=False)
        # the exported grid is this nominal gear: points to 1e-9 mm, normals to 1e-12
        assert np.abs(p.r - num[:, 2:5]).max() < 1e-9
        assert np.abs(p.n - num[:, 5:8]).max() < 1e-12
        dev = 1e3 * line_deviations_mm(nominal, cut, u, v)
        rows += [f"gear,{side},{r[col['row']]},{r[col['col']]},{r[col['L_mm']]},"
                 f"{r[col['R_mm']]},{float(d)!r}" for r, d in zip(data, dev)]
    path = tmp_path / "measured.csv"
    path.write_text("\n".join(rows) + "\n")
    stdout, written = _design(F2_MACHINE, path, tmp_path / "out")
    assert "| drive | 45 |" in stdout and "| coast | 45 |" in stdout
    _check_gear(written, truth)


def _bad(tmp_path, rows):
    path = tmp_path / "bad.csv"
    path.write_text("member,flank,L_mm,R_mm,deviation_um\n" + "".join(rows))
    return path


@pytest.mark.parametrize("pair_file, rows, words", [
    # an unknown member name
    (F2_MACHINE, ["wheel,drive,30.0,70.0,1.0\n"],
     "line 2 member, flank = 'wheel, drive' is outside the allowed range: member one of "
     "('pinion', 'gear')"),
    # fewer gear points than the formate gear's five settings
    (F2_MACHINE, [f"gear,coast,{30.0 + k},{70.0 + k},0.0\n" for k in range(3)],
     "bad.csv: gear coast points = 3 is outside the allowed range: at least 5, one per "
     "fitted setting (blade_radius_mm, blade_angle_deg"),
    # a point far off the gear flank (L, R of no flank point)
    (F2_MACHINE, [f"gear,drive,{30.0 + k},{200.0 + k},0.0\n" for k in range(6)],
     "bad.csv: gear drive: line 2 (L = 30.0 mm, R = 200.0 mm) = 'off the flank' is "
     "outside the allowed range: a point on the gear flank's active box"),
])
def test_careless_gear_rows_exit_2(tmp_path, pair_file, rows, words):
    code, _, err = run_console("design", "--pair", pair_file, "--machine-settings",
                               "--target-flank", _bad(tmp_path, rows))
    assert code == 2
    assert words in err, err
