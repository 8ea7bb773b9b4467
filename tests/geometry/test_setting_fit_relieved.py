"""The setting fit with relieved (Toprem / Flankrem) blades (geometry.setting_fit,
issue 27 item 4; docs/machine_settings.md sec. 6 "Relieved blades").

Truths:
- relief 0: the fit is bit for bit the fit of the same blade without relief keys
  (the smooth path; compared in one process, not against recorded floats, which
  another machine's BLAS would not reproduce);
- self-consistency: the relieved test pair's own pinion (tests/data/toprem, 2 deg
  Toprem from 2 mm), measured as a deviation CSV against a flank cut from perturbed
  settings, gives back its settings from those perturbed settings (each within the
  first-order bound of the data's own error through the fit's Jacobian), its flank
  over both pieces within 0.01 um and its kink line;
- the same with a Flankrem added (three pieces, two kinks) on the fit grid of the
  kinked target flank itself;
- refusals: a relief reaching the blade point that cuts the mean point (the pivot of
  the blade corrections), a relief as a fitted parameter.
"""

import dataclasses
from pathlib import Path

import numpy as np
import pytest
from easeoff_grid import deviations_mm, pivot_length_mm

from gearcontact.geometry.conjugate import nominal_pinion_box
from gearcontact.geometry.generated import generated_pinion_flank
from gearcontact.geometry.kinked import machine_flank
from gearcontact.geometry.measuring_grid import measured_points, measuring_grid, read_target_flank
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.point_fit import PointProblem, fit_points
from gearcontact.geometry.relief_setup import blade_relief, relieved_setup
from gearcontact.geometry.setting_fit import (DEFAULT_PARAMETERS, apply_corrections,
                                              fit_pinion_setup, flank_deviation_um)
from gearcontact.validation import InputRangeError

TOPREM = Path(__file__).resolve().parents[1] / "data" / "toprem" / "iso23509_f2_toprem.toml"


def _pinion(pair, side):
    return next(s for s in pair.machine if s.member == "pinion" and s.side == side)


#: Known corrections of the relief-0 fit: a fifth of these (the tilted F.2 pinion's
#: envelope leaves the grid's root corner at the full size), as the golden run scaled them.
_SMOOTH_TRUE = {k: 0.2 * v for k, v in {
    "cradle_angle_deg": -0.05, "radial_distance_mm": 0.1, "ratio_of_roll": -0.02,
    "modified_roll_2c_per_rad": 0.005, "modified_roll_6d_per_rad2": -0.01,
    "blade_angle_deg": -0.5, "blade_curvature_per_mm": 0.002,
    "blade_cubic_per_mm2": -0.003}.items()}
@pytest.mark.parametrize("relief", [{"toprem_angle_deg": 0.0},          # depth 2.0 kept
                                    {"toprem_angle_deg": 0.0, "toprem_depth_mm": 0.0}])
def test_relief_zero_is_the_smooth_fit_bit_for_bit(relief):
    # the relieved pair's drive pinion with its relief angle set to 0 (no relief: the
    # depth alone is ignored, docs/machine_settings.md sec. 1) against the same blade
    # with no relief keys at all, a target cut by known corrections, the default fit
    # (~2 x 3 s): every number equal (exact equality, no tolerance: the smooth path is
    # the one taken; compared in the same process, so not tied to one machine's BLAS)
    pair = load_pair(TOPREM)
    own = _pinion(pair, "drive")
    smooth_blade = dataclasses.replace(own.blade, toprem_angle_deg=0.0, toprem_depth_mm=0.0,
                                       flankrem_angle_deg=0.0, flankrem_depth_mm=0.0)
    fits = []
    for blade in (smooth_blade, dataclasses.replace(smooth_blade, **relief)):
        seed = dataclasses.replace(own, blade=blade)
        true = apply_corrections(seed, _SMOOTH_TRUE,
                                 pivot_length_mm=pivot_length_mm(seed, pair.blank))
        target, _ = generated_pinion_flank(true, pair.blank, n_u=30, n_v=40,
                                           pinion_face_width_mm=pair.pinion_face_width_mm)
        fits.append(fit_pinion_setup(seed, pair.blank, target))
    smooth, relieved = fits
    assert {n: float(v).hex() for n, v in relieved.corrections.items()} == \
        {n: float(v).hex() for n, v in smooth.corrections.items()}
    assert (relieved.fit_max_um.hex(), relieved.fit_rms_um.hex(), relieved.evaluations) == \
        (smooth.fit_max_um.hex(), smooth.fit_rms_um.hex(), smooth.evaluations)
    assert smooth.fit_max_um < 0.05       # the known corrections are recovered


#: Perturbation of the pair's machine settings (the blade as the pair's: so the pair's
#: own settings are a point of the fitted family exactly, blade terms 0).
_PERTURBATION = {"cradle_angle_deg": -0.01, "radial_distance_mm": 0.02, "ratio_of_roll": -0.004,
                 "modified_roll_2c_per_rad": 0.001, "modified_roll_6d_per_rad2": -0.002}


def test_relieved_pair_recovers_its_own_settings_from_a_measured_csv(tmp_path):
    # The pair's own relieved drive pinion (kink at u = 1.83..2.15 mm) is the target:
    # measured on the 9 x 11 nominal grid of a flank cut from perturbed settings
    # (the deviation along the nominal normal to the target, tests/easeoff_grid.py),
    # written as the measured-deviation CSV design --target-flank takes, read back as
    # measured points; the fit starts from the perturbed settings with the relief as
    # given (~7 s: three relieved flanks of 80 x 100 nodes per piece, the fit)
    pair = load_pair(TOPREM)
    own = _pinion(pair, "drive")
    fw = pair.pinion_face_width_mm
    seed = apply_corrections(own, _PERTURBATION, pivot_length_mm=0.0)   # no blade term
    target = machine_flank(own, pair.blank, face_width_mm=fw, n_u=80, n_v=100)
    nominal = machine_flank(seed, pair.blank, face_width_mm=fw, n_u=80, n_v=100)
    g = measuring_grid(nominal, member="pinion", flank="drive", rows=9, cols=11)
    dev_um = 1e3 * deviations_mm(nominal, target, g.u_mm, g.v_mm)
    path = tmp_path / "measured.csv"
    path.write_text("member,flank,row,col,L_mm,R_mm,deviation_um\n" + "".join(
        f"pinion,drive,{i},{j},{float(L)!r},{float(R)!r},{float(d)!r}\n"
        for i, j, L, R, d in zip(g.row, g.col, g.L_mm, g.R_mm, dev_um)))
    points = measured_points(read_target_flank(path)["drive"], nominal, where=str(path))
    pieces = target.piece_index(points.u_mm, points.v_mm)
    assert 5 <= (pieces == 0).sum() <= len(pieces) - 5       # both sides of the kink
    assert np.abs(dev_um).max() > 20.0                        # a target far off the seed

    fit = fit_points(seed, pair.blank, points)
    assert fit.status > 0
    assert blade_relief(fit.setup.blade) == blade_relief(own.blade)   # kept as given
    # Tolerance of each setting from the fit's convergence: the data's own error e
    # (the exact envelope of the pair's settings at the measured points, against the
    # points taken from its 80 x 100 spline pieces: measured 2.5e-4 um max) moves the
    # least-squares solution by J^+ e to first order, so |x_i - x_true,i| <=
    # |row_i(J^+)| |e| (Cauchy-Schwarz), J the scaled Jacobian at the solution; the
    # fit stops at a relative step of 1e-12. Measured: 0.03 to 0.37 of that bound.
    # (With 60 x 75 pieces the data error is 5.5e-3 um and the settings stay within
    # 0.03 to 0.4 of their larger bounds.)
    names = DEFAULT_PARAMETERS
    prob = PointProblem(seed, pair.blank, points, names)
    x = np.array([fit.corrections[n] for n in names]) / prob.scale
    jac = prob.jacobian(x)
    e = PointProblem(own, pair.blank, points, names).deviation_um(np.zeros(len(names)))
    bound = prob.scale * np.linalg.norm(np.linalg.pinv(jac), axis=1) * np.linalg.norm(e)
    for name, b in zip(names, bound):
        want = -_PERTURBATION.get(name, 0.0)
        assert abs(fit.corrections[name] - want) <= b, (name, fit.corrections[name], want, b)
    st, want = fit.setup.settings, own.settings
    for f in ("radial_distance_mm", "cradle_angle_deg", "ratio_of_roll"):
        assert getattr(st, f) == pytest.approx(getattr(want, f), abs=1e-4), f
    # the whole flank, both pieces: the flank the fitted settings cut against the target
    # on 60 x 75 points of their common box, < 0.01 um (measured 1.9e-4 um max, on the
    # Toprem piece: the two flanks' spline interpolation, 80 x 100 nodes per piece;
    # 4.9e-3 um with 60 x 75)
    cut = machine_flank(fit.setup, pair.blank, face_width_mm=fw, n_u=80, n_v=100)
    u, v, res = flank_deviation_um(cut, target)
    on = target.piece_index(u, v)
    for piece in (0, 1):
        assert (on == piece).sum() > 100
        assert np.abs(res[on == piece]).max() < 0.01, piece
    # the kink line: a normal deviation d moves the crossing of two pieces whose slopes
    # differ by >= 2.26 deg (docs/machine_settings.md sec. 1) by <= d / tan(2.26 deg):
    # 0.01 um -> 2.5e-4 mm (measured 2.0e-7 mm)
    k_cut, k_target = cut.kinks[0].u_nodes, target.kinks[0].u_nodes
    assert np.all(np.isfinite(k_target)) and 1.8 < k_target.min() < k_target.max() < 2.2
    assert np.abs(k_cut - k_target).max() < 2.5e-4


@pytest.mark.slow       # ~8 s: the three-piece companion of the default test above
def test_toprem_and_flankrem_three_pieces_recovered_on_the_fit_grid():
    # the pair's drive pinion with a Flankrem added (1.5 deg from 5 mm: kink at u
    # 5.38..5.84 mm, above the mean point) is the target flank itself (the kinked sheet,
    # 80 x 100 nodes per piece) on the 9 x 11 fit grid, from the perturbed settings
    # (~7 s). Truths as above: each setting within the first-order bound of the data's
    # error at the grid nodes (the exact envelopes of the pair's settings against the
    # kinked sheet), the flank on each of its three pieces within 0.01 um (measured
    # 2.1e-4 / 5.9e-5 / 1.6e-5 um, toprem / main / flankrem), both kink lines within
    # 2.5e-4 mm (measured 1.3e-7 / 1.6e-8 mm)
    from gearcontact.geometry.relief_setup import with_relief
    from gearcontact.geometry.setting_fit import FitProblem, fit_grid

    pair = load_pair(TOPREM)
    own = _pinion(pair, "drive")
    own = with_relief(own, {**blade_relief(own.blade), "flankrem_angle_deg": 1.5,
                            "flankrem_depth_mm": 5.0})
    fw = pair.pinion_face_width_mm
    seed = apply_corrections(own, _PERTURBATION, pivot_length_mm=0.0)
    target = machine_flank(own, pair.blank, face_width_mm=fw, n_u=80, n_v=100)
    assert target.names == ("toprem", "main", "flankrem")
    fit = fit_pinion_setup(seed, pair.blank, target)
    assert fit.status > 0 and blade_relief(fit.setup.blade) == blade_relief(own.blade)
    names, grid = DEFAULT_PARAMETERS, fit_grid(target.boundary, 9, 11)
    prob = FitProblem(seed, pair.blank, target, names, *grid)
    jac = prob.jacobian(np.array([fit.corrections[n] for n in names]) / prob.scale)
    e = FitProblem(own, pair.blank, target, names, *grid).deviation_um(np.zeros(len(names)))
    bound = prob.scale * np.linalg.norm(np.linalg.pinv(jac), axis=1) * np.linalg.norm(e)
    for name, b in zip(names, bound):
        want = -_PERTURBATION.get(name, 0.0)
        assert abs(fit.corrections[name] - want) <= b, (name, fit.corrections[name], want, b)
    cut = machine_flank(fit.setup, pair.blank, face_width_mm=fw, n_u=80, n_v=100)
    u, v, res = flank_deviation_um(cut, target)
    on = target.piece_index(u, v)
    for piece in (0, 1, 2):
        assert (on == piece).sum() > 100
        assert np.abs(res[on == piece]).max() < 0.01, piece
    for a, b in zip(cut.kinks, target.kinks):
        assert np.abs(a.u_nodes - b.u_nodes).max() < 2.5e-4, a.name


class _BoxOnly:
    """A stand-in target with the pinion's nominal box (the refusal comes first)."""

    def __init__(self, pair):
        self.boundary = nominal_pinion_box(pair.blank, pair.pinion_face_width_mm)[1]


def test_relief_reaching_the_mean_point_is_refused():
    # the blade corrections pivot about the blade point that cuts the mean point (at a
    # depth of 2.4 mm behind the tip plane on the F.2 pinion): a Toprem from deeper (or a
    # Flankrem from shallower) would put the mean point on the relief. Refused by the fit
    # and by relieved_setup (standard settings, design --machine-settings), naming the
    # key and the depth it must stay below / above
    pair = load_pair(TOPREM)
    own = _pinion(pair, "drive")
    smooth = dataclasses.replace(own, blade=dataclasses.replace(own.blade, toprem_angle_deg=0.0))
    for relief, key, sign in (({"toprem_angle_deg": 2.0, "toprem_depth_mm": 3.0}, "toprem", "<"),
                              ({"toprem_angle_deg": 2.0, "toprem_depth_mm": 10.0}, "toprem", "<"),
                              ({"flankrem_angle_deg": 1.0, "flankrem_depth_mm": 2.0}, "flankrem",
                               ">")):
        with pytest.raises(InputRangeError, match=rf"blade.pinion.drive.{key}_depth_mm.*"
                                                  rf"{sign} 2\.4\d* mm"):
            relieved_setup(smooth, relief, pair.blank)
        bad = dataclasses.replace(smooth, blade=dataclasses.replace(smooth.blade, **relief))
        with pytest.raises(InputRangeError, match=rf"{key}_depth_mm"):
            fit_pinion_setup(bad, pair.blank, _BoxOnly(pair))
    # the relief is a blade property, not a fitted setting
    with pytest.raises(InputRangeError, match="parameters"):
        fit_pinion_setup(own, pair.blank, None, parameters=("toprem_angle_deg",))
