"""Measuring grids in machine coordinates (axial position L, radius R) and measured
deviation files onto the flank (gearcontact.geometry.measuring_grid).

Independent truths: the pinion sheet's closed-form parameters of a point
(``v = x``, ``u = R - R_f(x)``, docs/geometry.md, :class:`PinionCone`) against the root
finder; the flank points of the mapped parameters against the grid's own points; the
flank cut with a changed profile-angle coefficient, its deviations from the nominal
measured in the test (distances along the nominal normals), read back as the pair's
polynomial ease-off with the changed coefficient and as that flank.
"""

import dataclasses

import numpy as np
import pytest

from gearcontact.geometry.easeoff import EaseOff, apply_easeoff
from gearcontact.geometry.measuring_grid import (
    AXIS_FRAMES, MeasuredFlank, flank_parameters_at, measuring_grid, read_measured_grid,
    read_target_flank, target_grids)
from gearcontact.validation import InputRangeError

from easeoff_grid import measured_pressure_angle_csv

D_PA = 8.0  # um/mm: the profile-angle change of the round trip


@pytest.mark.parametrize("member", ["pinion", "gear"])
def test_nominal_grid_maps_back_onto_its_points(s0003_calibrated, member):
    # the (u, v) solved at each grid point's (L, R) reproduce its point: measured
    # 1.1e-14 mm (pinion and formate gear), asserted 1e-9 mm; L and R are the axis
    # frame's z and radius of the point
    _, flanks = s0003_calibrated
    for side in ("drive", "coast"):
        surface = flanks.flank(member, side)
        g = measuring_grid(surface, member=member, flank=side, rows=5, cols=9)
        assert (g.row[[0, 8, 9, -1]].tolist(), g.col[[0, 8, 9, -1]].tolist()) == (
            [1, 1, 2, 5], [1, 9, 1, 9])
        assert np.array_equal(g.L_mm, g.xyz_mm[:, 2])
        assert np.array_equal(g.R_mm, np.hypot(g.xyz_mm[:, 0], g.xyz_mm[:, 1]))
        u, v = flank_parameters_at(surface, member=member, L_mm=g.L_mm, R_mm=g.R_mm,
                                   where="test")
        r = surface.evaluate(u, v).r @ AXIS_FRAMES[member].T
        assert np.abs(r - g.xyz_mm).max() < 1e-9


def test_pinion_parameters_are_the_closed_form(s0003_calibrated):
    # the pinion sheet: v = x (the axial position), u = R - R_f(v): the root finder's
    # parameters equal the closed form to 1e-10 mm (measured 2e-15)
    _, flanks = s0003_calibrated
    sheet = flanks.pinion.coast
    g = measuring_grid(sheet, member="pinion", flank="coast", rows=5, cols=9)
    u, v = flank_parameters_at(sheet, member="pinion", L_mm=g.L_mm, R_mm=g.R_mm, where="t")
    u_cf, v_cf = sheet.cone.parameters(g.L_mm, g.R_mm)
    assert np.abs(u - u_cf).max() < 1e-10 and np.abs(v - v_cf).max() < 1e-10


def test_pressure_angle_change_reads_back_as_the_changed_easeoff(s0003_calibrated, tmp_path):
    # s0003's coast pinion cut with c_PA + 8 um/mm, measured on the nominal 5 x 9 grid
    # (deviations = distances along the nominal normals to that flank, found in the
    # test: tests/easeoff_grid.py), reads back as the changed ease-off: the relief over
    # a 21 x 21 grid of the box within 0.01 um of the polynomial (measured 2.8e-4 um:
    # the deviations are a quadratic of the conjugate's parameters, interpolated by the
    # bicubic over the nominal's, |E_pair| ~ 0.03 mm apart)
    pair, flanks = s0003_calibrated
    path, g, truth = measured_pressure_angle_csv(tmp_path / "m.csv", pair, flanks,
                                                 "coast", D_PA)
    grids = read_target_flank(path, pair=pair)   # the grid's edges lie on the blank
    assert list(grids) == ["coast"] and isinstance(grids["coast"], MeasuredFlank)
    target = target_grids(grids, pair, flanks)["coast"]
    c = pair.easeoff_coast
    u_m, v_m = flanks.mean_contact["coast"]["pinion_uv"]
    want = EaseOff.from_coefficients(
        dataclasses.replace(c, profile_angle_um_per_mm=c.profile_angle_um_per_mm + D_PA),
        u_mean_mm=u_m, v_mean_mm=v_m)
    b = flanks.pinion.coast.boundary
    U, V = np.meshgrid(np.linspace(b.u_root, b.u_tip, 21), np.linspace(b.v_toe, b.v_heel, 21))
    assert np.abs(1e3 * (target.relief_mm(U, V) - want.relief_mm(U, V))).max() < 0.01
    # the target flank is the flank that was cut: normal distance R dpsi (e_psi . n)
    # over the box within 0.01 um (measured 2.6e-4 um)
    eased = apply_easeoff(flanks.pinion_conjugate.coast, target,
                          limit_um=flanks.easeoff_limit_um)
    s = truth.evaluate(U, V)
    rad = np.hypot(s.r[..., 1], s.r[..., 2])
    e_psi = np.stack([0 * rad, -s.r[..., 2] / rad, s.r[..., 1] / rad], axis=-1)
    gap_um = 1e3 * rad * (eased.psi(U, V) - truth.psi(U, V)) * np.einsum("...i,...i", e_psi, s.n)
    print("gap", np.abs(gap_um).max())
    assert np.abs(gap_um).max() < 0.01


def test_point_off_the_flank_is_named_with_the_flank_range(s0003_calibrated):
    _, flanks = s0003_calibrated
    sheet = flanks.pinion.coast
    g = measuring_grid(sheet, member="pinion", flank="coast", rows=5, cols=9)
    L = g.L_mm.copy()
    L[44] += 0.5    # the heel/tip corner: 0.5 mm past the heel
    with pytest.raises(InputRangeError, match=r"m.csv: point 45 \(L = 44\.41314.* mm, R = "
                       r"8\.76.*off the flank.*L 27\.7045\.\.43\.9131 mm, R 4\.5694\.\.8\.7673"):
        flank_parameters_at(sheet, member="pinion", L_mm=L, R_mm=g.R_mm, where="m.csv")


@pytest.mark.parametrize("body, match", [
    ("member,flank,L_mm,R_mm,deviation_um,probe\npinion,coast,1,2,3,4\n", "probe"),
    ("member,flank,L_mm,R_mm\npinion,coast,1,2\n", "deviation_um"),
    ("member,flank,L_mm,R_mm,deviation_um\npinion,coast,1,2,nan\n", "line 2.*finite"),
    ("member,flank,L_mm,R_mm,deviation_um\npinion,coast,1,2,3\npinion,coast,1,2,4\n",
     "line 3.*also line 2"),
    ("member,flank,L_mm,R_mm,deviation_um\npinion,tip,1,2,3\n", "flank"),
    ("member,flank,L_mm,R_mm,deviation_um\npinion,coast,1,2\n", "line 2"),
    ("# nothing\n", "no header"),
])
def test_bad_measured_files_are_refused_naming_the_field(tmp_path, body, match):
    path = tmp_path / "bad.csv"
    path.write_text(body)
    with pytest.raises(InputRangeError, match=match):
        read_measured_grid(path)


def test_the_old_grid_format_is_still_told_by_its_header(tmp_path):
    path = tmp_path / "g.csv"
    path.write_text("side,v_mm,u_mm,easeoff_um\n" + "".join(
        f"coast,{v},{u},0\n" for u in range(4) for v in range(4)))
    assert type(read_target_flank(path)["coast"]).__name__ == "GridEaseOff"
    # a gear flank cannot be a target of the (pinion) settings fit
    path.write_text("member,flank,L_mm,R_mm,deviation_um\ngear,coast,1,2,3\n")
    with pytest.raises(InputRangeError, match="member one of \\('pinion',\\)"):
        read_target_flank(path)
