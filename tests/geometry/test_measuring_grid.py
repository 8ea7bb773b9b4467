"""Measuring grids in machine coordinates (axial position L, radius R) and measured
deviation files onto the flank (gearcontact.geometry.measuring_grid).

Independent truths: the pinion sheet's closed-form parameters of a point
(``v = x``, ``u = R - R_f(x)``, docs/geometry.md, :class:`PinionCone`) against the root
finder; the flank points of the mapped parameters against the grid's own points; a
pure pressure-angle change of the ease-off (``dE = c (u - u_m)``, exact in u) written as
measured deviations and read back as the pair's polynomial ease-off with the changed
coefficient.
"""

import dataclasses

import numpy as np
import pytest

from gearcontact.geometry.easeoff import EaseOff, apply_easeoff, max_relief_um
from gearcontact.geometry.measuring_grid import (
    AXIS_FRAMES, MeasuredFlank, flank_parameters_at, measuring_grid, read_measured_grid,
    read_target_flank, target_grids)
from gearcontact.validation import InputRangeError

D_PA = 8.0  # um/mm: the pressure-angle change of the round trip (s0003 coast: c_PA ~ -2)


def _measured_csv(path, grid, deviation_um, *, member="pinion"):
    rows = ["# a measured file: the nominal grid's L, R and a deviation",
            "member,flank,row,col,L_mm,R_mm,deviation_um"]
    rows += [f"{member},{grid.flank},{i},{j},{float(L)!r},{float(R)!r},{float(d)!r}"
             for i, j, L, R, d in zip(grid.row, grid.col, grid.L_mm, grid.R_mm, deviation_um)]
    path.write_text("\n".join(rows) + "\n")
    return path


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
    # deviations d = -D_PA (u - u_m) (material added = negative relief) at the nominal
    # grid points, u from the closed form, give the pair's ease-off with c_PA + D_PA:
    # the bicubic through the 5 x 9 samples of a quadratic is the quadratic (measured
    # 1e-13 um over a 21 x 21 grid of the box, asserted 1e-9 um)
    pair, flanks = s0003_calibrated
    sheet = flanks.pinion.coast
    g = measuring_grid(sheet, member="pinion", flank="coast", rows=5, cols=9)
    u_m, v_m = flanks.mean_contact["coast"]["pinion_uv"]
    u_cf, _ = sheet.cone.parameters(g.L_mm, g.R_mm)
    path = _measured_csv(tmp_path / "m.csv", g, -D_PA * (u_cf - u_m))
    grids = read_target_flank(path)
    assert list(grids) == ["coast"] and isinstance(grids["coast"], MeasuredFlank)
    target = target_grids(grids, pair, flanks)["coast"]
    c = pair.easeoff_coast
    want = EaseOff.from_coefficients(
        dataclasses.replace(c, profile_angle_um_per_mm=c.profile_angle_um_per_mm + D_PA),
        u_mean_mm=u_m, v_mean_mm=v_m)
    b = sheet.boundary
    U, V = np.meshgrid(np.linspace(b.u_root, b.u_tip, 21), np.linspace(b.v_toe, b.v_heel, 21))
    assert np.abs(1e3 * (target.relief_mm(U, V) - want.relief_mm(U, V))).max() < 1e-9
    # geometry: the target flank passes through the measured points (nominal point +
    # d n) up to the approximation of measured_easeoff_grid: the deviation field's
    # gradient D_PA times the shift between a conjugate point and its eased image, at
    # most |E_pair| (s0003 coast: 0.113 um measured, the bound D_PA max|E_pair|)
    eased = apply_easeoff(flanks.pinion_conjugate.coast, target,
                          limit_um=flanks.easeoff_limit_um)
    body = (g.xyz_mm + (-D_PA * (u_cf - u_m))[:, None] * 1e-3 * g.normal) @ AXIS_FRAMES["pinion"]
    u, v, _ = eased.locate(body)
    s = eased.evaluate(u, v)
    gap_um = 1e3 * np.einsum("ij,ij->i", body - s.r, s.n)
    bound_um = D_PA * 1e-3 * max_relief_um(
        EaseOff.from_coefficients(c, u_mean_mm=u_m, v_mean_mm=v_m), b)[0]
    assert 0.05 < np.abs(gap_um).max() < bound_um


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
