"""Pinion rows of a pair cut from machine settings (geometry.gear_correction.
measured_correction with member="pinion"; issue 27 item 4, docs/machine_settings.md
sec. 6 "Gear flanks" / "Pinion rows of a machine pair").

The rows of a pair with ``[machine.pinion.*]`` tables are deviations from the pinion
those tables cut (the flank the user measured), not from the blank's conjugate pinion.

Truths:
- zero rows: the machine-cut pinion's own points (its nominal CMM grid, deviation 0)
  lie on the flank the typed settings cut, solved independently at each point by the
  envelope (setting_fit's node solver, not the 120 x 150 sheet the rows are read
  against), to that sheet's interpolation error; the fit then returns the typed
  settings, each within the first-order bound of that error;
- self-consistency: the pinion cut with known perturbations, measured on the nominal
  grid of the typed settings' pinion (each deviation along the nominal normal to the
  perturbed flank), gives back the perturbed settings within the same bounds.
"""

import dataclasses

import numpy as np
import pytest
from easeoff_grid import deviations_mm, pivot_length_mm

from gearcontact.geometry.gear_correction import machine_seeds, measured_correction
from gearcontact.geometry.kinked import machine_flank
from gearcontact.geometry.measuring_grid import measuring_grid, read_member_targets
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.point_fit import PointProblem
from gearcontact.geometry.setting_fit import DEFAULT_PARAMETERS, apply_corrections

F2 = "examples/machine_settings/iso23509_f2_machine.toml"
#: Known perturbations of the default eight (~29 um on the F.2 drive pinion).
_PERTURBATION = {"cradle_angle_deg": -0.01, "radial_distance_mm": 0.02,
                 "ratio_of_roll": -0.004, "modified_roll_2c_per_rad": 0.001,
                 "modified_roll_6d_per_rad2": -0.002, "blade_angle_deg": 0.05,
                 "blade_curvature_per_mm": 0.0005, "blade_cubic_per_mm2": 0.001}


def _rows(path, pair, nominal, truth, side):
    """The CSV of ``truth`` measured on ``nominal``'s 9 x 11 CMM grid (zero rows for
    ``truth is nominal``), read back: ``({side: MeasuredFlank}, deviation_um)``."""
    g = measuring_grid(nominal, member="pinion", flank=side, rows=9, cols=11)
    dev = (np.zeros(len(g.u_mm)) if truth is nominal else
           1e3 * deviations_mm(nominal, truth, g.u_mm, g.v_mm))
    path.write_text("member,flank,row,col,L_mm,R_mm,deviation_um\n" + "".join(
        f"pinion,{side},{i},{j},{float(L)!r},{float(R)!r},{float(d)!r}\n"
        for i, j, L, R, d in zip(g.row, g.col, g.L_mm, g.R_mm, dev)))
    rows, gear_rows = read_member_targets(path, pair=pair)
    assert gear_rows == {} and set(rows) == {side}
    return rows, dev


def _within_bounds(pair, seed, true, r, want):
    # each setting within |row_i(J^+)| |e|: e the data's own error (the points against
    # the flank ``true`` cuts, solved at the points), J the scaled Jacobian at the
    # solution (first order; as tests/geometry/test_gear_correction.py)
    names = DEFAULT_PARAMETERS
    prob = PointProblem(seed, pair.blank, r.points, names)
    jac = prob.jacobian(np.array([r.fit.corrections[n] for n in names]) / prob.scale)
    e = PointProblem(true, pair.blank, r.points, names).deviation_um(np.zeros(len(names)))
    bound = prob.scale * np.linalg.norm(np.linalg.pinv(jac), axis=1) * np.linalg.norm(e)
    for name, b in zip(names, bound):
        assert abs(r.fit.corrections[name] - want.get(name, 0.0)) <= b, (
            name, r.fit.corrections[name], want.get(name, 0.0), b)
    return e


def test_zero_rows_of_the_machine_cut_pinion_give_the_typed_settings(tmp_path):
    # ~6 s: the F.2 machine pair's drive pinion (tilted standard settings) measured on
    # its own nominal grid with deviation 0
    pair = load_pair(F2)
    own = machine_seeds(pair, "pinion")["drive"]
    blank_pair = dataclasses.replace(pair, machine=())     # as design reads the rows
    nominal = machine_flank(own, pair.blank, face_width_mm=pair.pinion_face_width_mm)
    rows, _ = _rows(tmp_path / "zero.csv", blank_pair, nominal, nominal, "drive")
    done = measured_correction(blank_pair, rows, member="pinion", seeds={"drive": own})
    r = done.sides["drive"]
    assert r.fit.status > 0 and done.member == "pinion"
    # the points against the typed settings' envelope at the points: the 120 x 150
    # sheet's interpolation error, < 1e-3 um (measured 1.6e-4 um; rounding alone
    # would be ~1e-9 um: the sheet, not the reading, sets it)
    e = _within_bounds(blank_pair, own, own, r, {})
    assert np.abs(e).max() < 1e-3
    assert r.fit.fit_max_um < 1e-3          # measured 3.3e-5 um
    assert r.deviation_max_um == 0.0
    # the flank the pair's settings cut is what the user measured: the blank's
    # conjugate pinion (what the rows were read against before) is microns away here
    from gearcontact.geometry.flank import build_flanks

    conj = build_flanks(blank_pair).pinion.drive
    g = measuring_grid(nominal, member="pinion", flank="drive", rows=9, cols=11)
    assert np.abs(1e3 * deviations_mm(nominal, conj, g.u_mm, g.v_mm)).max() > 1.0


def test_perturbed_machine_pinion_recovered(tmp_path):
    # ~10 s: the drive pinion cut with the perturbation (29 um off the typed one),
    # fitted from the typed settings: the perturbed settings within their bounds
    # (measured 0.03-0.53 of each), the residual at the points < 1e-3 um (the data
    # error, measured 1.7e-4 um; residual 3.5e-5 um)
    pair = load_pair(F2)
    own = machine_seeds(pair, "pinion")["drive"]
    blank_pair = dataclasses.replace(pair, machine=())
    fw = pair.pinion_face_width_mm
    true = apply_corrections(own, _PERTURBATION, pivot_length_mm=pivot_length_mm(own, pair.blank))
    nominal = machine_flank(own, pair.blank, face_width_mm=fw)
    truth = machine_flank(true, pair.blank, face_width_mm=fw)
    rows, dev = _rows(tmp_path / "pert.csv", blank_pair, nominal, truth, "drive")
    assert np.abs(dev).max() > 20.0
    r = measured_correction(blank_pair, rows, member="pinion",
                            seeds={"drive": own}).sides["drive"]
    assert r.fit.status > 0
    e = _within_bounds(blank_pair, own, true, r, _PERTURBATION)
    assert np.abs(e).max() < 1e-3
    assert r.fit.fit_max_um < 1e-3


def test_unknown_member_and_rows_of_the_other_member_are_refused():
    from gearcontact.geometry.measuring_grid import MeasuredFlank
    from gearcontact.validation import InputRangeError

    pair = load_pair(F2)
    with pytest.raises(InputRangeError, match="member = 'wheel'.*'pinion' or 'gear'"):
        measured_correction(pair, {}, member="wheel", seeds={})
    gear_rows = {"drive": MeasuredFlank(member="gear", flank="drive", L_mm=np.zeros(9),
                                        R_mm=np.zeros(9), deviation_um=np.zeros(9),
                                        line=np.arange(9))}
    with pytest.raises(InputRangeError, match="pinion rows = 'drive'.*measured pinion flanks"):
        measured_correction(pair, gear_rows, member="pinion",
                            seeds=machine_seeds(pair, "pinion"))
