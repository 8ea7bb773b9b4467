"""The gear's setting correction with a relieved (Toprem / Flankrem) gear blade
(geometry.gear_correction, geometry.setting_fit; issue 27 item 4; docs/machine_settings.md
sec. 6 "Gear flanks", "Relieved blades").

Truths:
- self-consistency: a relieved gear cut from its nominal settings with known
  perturbations (the relief kept as given, the main profile corrected), its own flank
  (geometry.kinked.machine_flank: one piece per blade segment, each point on its own)
  measured on the nominal CMM grid with points on both pieces, written as the
  deviation CSV ``design --target-flank`` takes and fitted from the nominal settings:
  every correction within the first-order bound of the data's own error through the
  fit's Jacobian, the relief as given, the residual at the points and the kink line
  within the tolerances stated (and why) at each assertion;
- the blade pivot: a gear relief reaching the blade point that cuts the gear's mean
  point is refused, naming the key and that depth, before any fit.

The residuals were predicted before the first run from the smooth gear's (the same
node solvers, tests/geometry/test_gear_correction.py): a formate gear (exact cones)
below 1e-8 um at the points, a generated gear (60 x 75 spline pieces) below 1e-6 um;
measured: formate 6.1e-11 / 5.4e-11 um (drive Toprem / coast Flankrem), generated
2.1e-9 um.
"""

import numpy as np
import pytest
from easeoff_grid import (GEAR_FORMATE_PERTURBATION, GEAR_GENERATED_PERTURBATION,
                         line_deviations_mm, member_pivot_length_mm, write_gear_measured_csv)

from gearcontact.geometry.basic_settings import generated_gear_setups
from gearcontact.geometry.gear_correction import gear_correction, gear_seeds
from gearcontact.geometry.kinked import machine_flank
from gearcontact.geometry.measuring_grid import read_member_targets
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.point_fit import PointProblem
from gearcontact.geometry.relief_setup import blade_relief, with_relief
from gearcontact.geometry.setting_fit import apply_corrections, default_parameters
from gearcontact.validation import InputRangeError

F2 = "examples/machine_settings/iso23509_f2_machine.toml"
HYPOID = "examples/hypoid_11x41_rear_axle.toml"

#: The reliefs: a Toprem on the drive blade (kink 3.0 mm over the root, below the mean
#: point, whose blade point lies 5.61 mm behind the tip plane) and a Flankrem on the
#: coast blade (kink 6.6 mm over the root, above it; tooth depth 7.23 mm).
_RELIEF = {"drive": {"toprem_angle_deg": 2.0, "toprem_depth_mm": 3.0},
           "coast": {"flankrem_angle_deg": 2.0, "flankrem_depth_mm": 6.6}}
#: Known perturbations (those of tests/geometry/test_gear_correction.py: ~10 um).
_FORMATE, _GENERATED = GEAR_FORMATE_PERTURBATION, GEAR_GENERATED_PERTURBATION


def _recover(tmp_path, pair, smooth, relief, pert, *, n_u=60, n_v=75):
    """The relieved gear cut with ``pert``, measured as a CSV on the nominal 9 x 11 grid
    and fitted: ``(seed, true, truth flank, GearCorrection)``."""
    side = smooth.side
    seed = with_relief(smooth, relief)
    true = apply_corrections(seed, pert, pivot_length_mm=member_pivot_length_mm(smooth,
                                                                              pair.blank))
    assert blade_relief(true.blade) == blade_relief(seed.blade)     # kept by the cut too
    assert {k: v for k, v in blade_relief(seed.blade).items() if v} == relief
    path = tmp_path / "gear.csv"
    _, dev = write_gear_measured_csv(path, pair, seed, true, side, n_u=n_u, n_v=n_v)
    assert np.abs(dev).max() > 5.0                                  # well off the nominal
    _, rows = read_member_targets(path, pair=pair)
    truth = machine_flank(true, pair.blank, face_width_mm=pair.gear_face_width_mm,
                          n_u=n_u, n_v=n_v)
    return seed, true, truth, gear_correction(pair, rows, seeds={side: seed})


def _check(pair, seed, true, truth, done, pert, *, residual_um):
    side = seed.side
    r = done.sides[side]
    assert r.fit.status > 0
    # points on both pieces (each side of the kink enters the fit)
    on = truth.piece_index(r.points.u_mm, r.points.v_mm)
    assert min(np.bincount(on, minlength=2)) >= 5, np.bincount(on)
    assert r.fit.fit_max_um < residual_um
    assert np.isnan(r.flank_max_um)      # a relieved gear: at the points only (no spline)
    assert blade_relief(done.setups[side].blade) == blade_relief(seed.blade)
    # each setting within the first-order bound |row_i(J^+)| |e| of the data's own
    # error e (the points against the true settings' cut flank as the fit solves it),
    # J the scaled Jacobian at the solution (as tests/geometry/test_gear_correction.py)
    names = default_parameters(seed)
    prob = PointProblem(seed, pair.blank, r.points, names)
    jac = prob.jacobian(np.array([r.fit.corrections[n] for n in names]) / prob.scale)
    e = PointProblem(true, pair.blank, r.points, names).deviation_um(np.zeros(len(names)))
    bound = prob.scale * np.linalg.norm(np.linalg.pinv(jac), axis=1) * np.linalg.norm(e)
    for name, b in zip(names, bound):
        assert abs(r.fit.corrections[name] - pert[name]) <= b, (name, r.fit.corrections[name],
                                                                 pert[name], b)
    # the kink line of the cut flank as reported: a normal deviation d moves the
    # crossing of two pieces whose profile slopes differ by the 2 deg relief by <= d /
    # tan(2 deg) along the profile; d <= the residual bound -> 3e-8 mm (measured
    # 1.3e-12 .. 1.7e-11 mm)
    assert [k.name for k in r.kinks] == [k.name for k in truth.kinks]
    for a, b in zip(r.kinks, truth.kinks):
        assert np.all(np.isfinite(b.u_nodes)) and np.all(np.isfinite(a.u_mm))
        # at the reported nodes (each flank's own box: the nodes differ by 2e-13 mm),
        # the truth's kink line there (its cubic through 41 nodes)
        assert np.abs(a.u_mm - b.u(a.v_mm)).max() < residual_um * 1e-3 / np.tan(np.radians(2.0))
        assert f"{side}: the relieved blade's {a.name} kink at u " in done.table()


@pytest.mark.parametrize("side", ["drive", "coast"])
def test_relieved_formate_gear_recovered_from_its_csv(tmp_path, side):
    # the F.2 formate gear with a Toprem (drive) / Flankrem (coast), ~1 s. Residual at
    # the points < 1e-6 um: the formate node solver is solved to 1e-10 mm in height and
    # radius (~1e-7 um along the normal, tests/geometry/test_gear_correction.py), the
    # data exact cones (measured 6.1e-11 / 5.4e-11 um)
    pair = load_pair(F2)
    smooth = gear_seeds(pair, "formate")[side]
    seed, true, truth, done = _recover(tmp_path, pair, smooth, _RELIEF[side], _FORMATE)
    _check(pair, seed, true, truth, done, _FORMATE, residual_um=1e-6)
    cut = machine_flank(done.setups[side], pair.blank, face_width_mm=pair.gear_face_width_mm)
    # over the whole flank, both pieces: the cut flank against the truth along the
    # truth's normal on 30 x 40 points of its box, each on its piece (two exact kinked
    # cones; Newton, tests/easeoff_grid.py): < 1e-6 um as at the points (measured
    # 4.3e-11 / 3.7e-11 um)
    b = truth.boundary
    U, V = (a.ravel() for a in np.meshgrid(np.linspace(b.u_root, b.u_tip, 30),
                                           np.linspace(b.v_toe, b.v_heel, 40), indexing="ij"))
    res_um = 1e3 * line_deviations_mm(truth, cut, U, V)
    on = truth.piece_index(U, V)
    for piece in (0, 1):
        assert (on == piece).sum() > 100
        assert np.abs(res_um[on == piece]).max() < 1e-6, piece


def test_relieved_generated_gear_recovered_from_its_csv(tmp_path):
    # ~6 s: the relieved generated flanks (60 x 75, the reported kinks' 120 x 150) and
    # the fit. The 11/41 hypoid's
    # generated gear (drive) with a 2 deg Toprem from 3 mm (kink at u
    # 3.23..3.40 mm). Residual at the points < 1e-6 um: the data are 60 x 75 spline
    # pieces, whose error against the exact envelope was 1e-9 um on the smooth gear
    # (measured here 2.1e-9 um, data error 4.3e-9 um)
    pair = load_pair(HYPOID)
    smooth = generated_gear_setups(pair)["drive"]
    assert not smooth.settings.formate
    seed, true, truth, done = _recover(tmp_path, pair, smooth, _RELIEF["drive"], _GENERATED)
    _check(pair, seed, true, truth, done, _GENERATED, residual_um=1e-6)


def test_gear_relief_reaching_the_mean_point_is_refused(tmp_path):
    # the F.2 gear's blade point that cuts its mean point lies 5.61 mm behind the tip
    # plane: a Toprem from 6 mm puts the mean point on the relief (the blade pivot of
    # the fit); refused before any fit naming the key and that depth (the relieved
    # gear's own zero-deviation rows: the refusal comes from the relief alone)
    pair = load_pair(F2)
    bad = with_relief(gear_seeds(pair, "formate")["drive"],
                      {"toprem_angle_deg": 2.0, "toprem_depth_mm": 6.0})
    write_gear_measured_csv(tmp_path / "zero.csv", pair, bad, bad, "drive")
    _, rows = read_member_targets(tmp_path / "zero.csv", pair=pair)
    with pytest.raises(InputRangeError, match=r"blade.gear.drive.toprem_depth_mm = 6.0 .*"
                                              r"< 5\.61\d* mm.*the gear's mean point"):
        gear_correction(pair, rows, seeds={"drive": bad})
