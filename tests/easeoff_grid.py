"""A pair's polynomial ease-off sampled as a measured deviation grid CSV (the format of
``gearcontact.geometry.easeoff.read_easeoff_grid``), and a flank measured in machine
coordinates on the nominal grid or at scattered points (docs/export.md "The measuring
grid"), shared by the setting-fit tests of the library and the command line."""

import numpy as np

from gearcontact.geometry.easeoff import EaseOff


def write_grid_csv(path, pair, flanks, side, n_u=6, n_v=9, pad=0.0):
    """The pair's ease-off of ``side`` sampled on a grid over the active box, as CSV."""
    b = flanks.pinion_conjugate.side(side).boundary
    u_m, v_m = flanks.mean_contact[side]["pinion_uv"]
    eo = EaseOff.from_coefficients(getattr(pair, f"easeoff_{side}"), u_mean_mm=u_m,
                                   v_mean_mm=v_m)
    rows = ["side,v_mm,u_mm,easeoff_um"]
    for u in np.linspace(b.u_root, b.u_tip - pad, n_u):
        for v in np.linspace(b.v_toe, b.v_heel, n_v):
            rows.append(f"{side},{float(v)!r},{float(u)!r},{1e3 * float(eo.relief_mm(u, v))!r}")
    path.write_text("\n".join(rows) + "\n")
    return path


def measured_pressure_angle_csv(path, pair, flanks, side, d_pa_um_per_mm, rows=5, cols=9):
    """The pinion flank ``side`` of ``pair`` measured on its nominal ``rows x cols``
    measuring grid (machine coordinates, docs/export.md "The measuring grid") when it is
    cut with the profile-angle coefficient changed by ``d_pa_um_per_mm``: each
    deviation is the distance along the nominal normal from the nominal point to that
    flank (``apply_easeoff`` of the changed polynomial, found by iterating the point
    onto it along the normal: 3 steps to 1e-12 mm). Returns ``(path, grid, truth)``
    with the true eased flank ``truth``."""
    import dataclasses

    from gearcontact.geometry.easeoff import apply_easeoff
    from gearcontact.geometry.measuring_grid import measuring_grid

    nominal = flanks.pinion.side(side)
    c = getattr(pair, f"easeoff_{side}")
    u_m, v_m = flanks.mean_contact[side]["pinion_uv"]
    changed = EaseOff.from_coefficients(dataclasses.replace(
        c, profile_angle_um_per_mm=c.profile_angle_um_per_mm + d_pa_um_per_mm),
        u_mean_mm=u_m, v_mean_mm=v_m)
    truth = apply_easeoff(flanks.pinion_conjugate.side(side), changed,
                          limit_um=flanks.easeoff_limit_um)
    g = measuring_grid(nominal, member="pinion", flank=side, rows=rows, cols=cols)
    d = deviations_mm(nominal, truth, g.u_mm, g.v_mm)
    lines = ["# measured on the nominal grid (a comment line, skipped)",
             "member,flank,row,col,L_mm,R_mm,deviation_um"] + [
        f"pinion,{side},{i},{j},{float(L)!r},{float(R)!r},{1e3 * float(x)!r}"
        for i, j, L, R, x in zip(g.row, g.col, g.L_mm, g.R_mm, d)]
    path.write_text("\n".join(lines) + "\n")
    return path, g, truth


def deviations_mm(nominal, truth, u, v):
    """Distance (mm) along the normal of the pinion sheet ``nominal`` at its points
    ``(u, v)`` to the pinion sheet ``truth``, found by iterating the point onto
    ``truth``'s tangent plane along the normal (3 steps to 1e-12 mm)."""
    p = nominal.evaluate(u, v)
    d = np.zeros(len(u))
    for _ in range(8):      # Newton along the normal onto the truth's tangent plane
        q = p.r + d[:, None] * p.n
        uq, vq, _ = truth.locate(q)
        t = truth.evaluate(uq, vq)
        step = np.einsum("ij,ij->i", t.r - q, t.n) / np.einsum("ij,ij->i", p.n, t.n)
        d += step
        if np.abs(step).max() < 1e-13:
            break
    return d


def write_points_csv(path, nominal, truth, side, u, v, *, noise_um=None):
    """The pinion flank ``truth`` measured at the points ``(u, v)`` of the nominal flank
    ``nominal`` (scattered, file order as given): the measured file of
    docs/export.md "The measuring grid" (no row/col), each deviation the distance along
    the nominal normal to ``truth`` (:func:`deviations_mm`) plus ``noise_um`` (an
    array, um) if given. Returns the deviations (um)."""
    p = nominal.evaluate(u, v, second=False)
    dev = 1e3 * deviations_mm(nominal, truth, u, v)
    if noise_um is not None:
        dev = dev + noise_um
    path.write_text("member,flank,L_mm,R_mm,deviation_um\n" + "".join(
        f"pinion,{side},{float(x)!r},{float(np.hypot(y, z))!r},{float(d)!r}\n"
        for (x, y, z), d in zip(p.r, dev)))
    return dev


def pivot_length_mm(seed, blank):
    """The blade arc length of the seed's mean node (the pivot of blade corrections,
    geometry.setting_fit.apply_corrections), solved here from the envelope."""
    from gearcontact.geometry.conjugate import nominal_pinion_box
    from gearcontact.geometry.generated import EnvelopeSolver

    cone, _ = nominal_pinion_box(blank, 1.0)
    s = EnvelopeSolver(seed, blank, cone)
    u, v = float(cone.root_offset_mm), float(blank.pitch_point_mm[0])
    return float(s.solve(u, v, s.initial_guess(u, v)).l_mm)


#: A known correction of s0003's coast seed (none of the round trip's values of
#: tests/geometry/test_setting_fit.py, of the same size: tens of um on the flank).
KNOWN_CORRECTION = {"cradle_angle_deg": -0.12, "radial_distance_mm": 0.15,
                    "ratio_of_roll": 0.04, "modified_roll_2c_per_rad": 0.008,
                    "modified_roll_6d_per_rad2": -0.015, "blade_angle_deg": -1.1,
                    "blade_curvature_per_mm": 0.004, "blade_cubic_per_mm2": 0.006}


def cut_from_known(pair, side="coast"):
    """``(seed, true, truth)``: the complementary seed of ``pair``'s pinion ``side``, the
    seed with :data:`KNOWN_CORRECTION` and the flank it cuts (30 x 40 sheet)."""
    from gearcontact.geometry.basic_settings import complementary_pinion_setups
    from gearcontact.geometry.generated import generated_pinion_flank
    from gearcontact.geometry.setting_fit import apply_corrections

    seed = complementary_pinion_setups(pair)[side]
    true = apply_corrections(seed, KNOWN_CORRECTION,
                             pivot_length_mm=pivot_length_mm(seed, pair.blank))
    truth, _ = generated_pinion_flank(true, pair.blank, n_u=30, n_v=40,
                                      pinion_face_width_mm=pair.pinion_face_width_mm)
    return seed, true, truth


#: Known perturbations of a formate gear's default subset and of a generated gear's
#: (~10 um on the flank: a measured gear's size; tests/geometry/test_gear_correction.py).
GEAR_FORMATE_PERTURBATION = {"blade_radius_mm": 0.02, "blade_angle_deg": -0.05,
                             "machine_root_angle_deg": 0.01,
                             "machine_centre_to_back_mm": -0.02, "blank_offset_mm": 0.02}
GEAR_GENERATED_PERTURBATION = {"cradle_angle_deg": -0.002, "radial_distance_mm": 0.004,
                               "ratio_of_roll": -0.0004, "modified_roll_2c_per_rad": 0.0002,
                               "blade_angle_deg": -0.01, "blade_radius_mm": 0.004,
                               "machine_root_angle_deg": 0.002}


def member_pivot_length_mm(seed, blank):
    """The blade arc length of ``seed``'s mean node on its member's sheet (pinion or
    gear: the pivot of blade corrections, geometry.setting_fit.apply_corrections)."""
    from gearcontact.geometry.member_envelope import mean_node_uv, member_cone, member_solver

    cone = member_cone(seed.member, blank)
    s = member_solver(seed, blank, cone)
    u, v = mean_node_uv(seed.member, blank, cone)
    return float(s.solve(u, v, s.initial_guess(u, v)).l_mm)


def line_deviations_mm(nominal, truth, u, v):
    """Distance (mm) along the normal of the flank ``nominal`` at its points ``(u, v)``
    to the flank ``truth`` (same parameterization: two formate flanks, or two gear
    sheets): Newton on ``truth(u', v') = p + t n`` in ``(u', v', t)`` from ``(u, v,
    0)``, to steps below 1e-14."""
    p = nominal.evaluate(u, v, second=False)
    uu, vv, t = np.array(u, dtype=float), np.array(v, dtype=float), np.zeros(len(u))
    for _ in range(20):
        s = truth.evaluate(uu, vv, second=False)
        jac = np.stack([s.r_u, s.r_v, -p.n], axis=-1)
        d = np.linalg.solve(jac, (p.r + t[:, None] * p.n - s.r)[..., None])[..., 0]
        uu, vv, t = uu + d[:, 0], vv + d[:, 1], t + d[:, 2]
        if np.abs(d).max() < 1e-14:
            break
    return t


def write_gear_measured_csv(path, pair, seed, true, side, *, rows=9, cols=11, n_u=60,
                            n_v=75):
    """The gear flank ``true`` cuts, measured on the nominal ``rows x cols`` CMM grid of
    the flank ``seed`` cuts (docs/export.md "The measuring grid", ``member = gear``):
    each deviation the distance along the nominal normal to the cut flank
    (:func:`line_deviations_mm`; a formate gear: both exact cones of
    geometry.generated.formate_gear_flank; a generated gear: both n_u x n_v sheets;
    a relieved blade: geometry.kinked.machine_flank's pieces, each point on its own,
    for a smooth blade the same flanks as before). Returns ``(grid, deviation_um)``."""
    from gearcontact.geometry.kinked import machine_flank
    from gearcontact.geometry.measuring_grid import measuring_grid

    fw = pair.gear_face_width_mm
    nominal = machine_flank(seed, pair.blank, face_width_mm=fw, n_u=n_u, n_v=n_v)
    truth = machine_flank(true, pair.blank, face_width_mm=fw, n_u=n_u, n_v=n_v)
    g = measuring_grid(nominal, member="gear", flank=side, rows=rows, cols=cols)
    dev = 1e3 * line_deviations_mm(nominal, truth, g.u_mm, g.v_mm)
    path.write_text("# a gear measured on its nominal grid\nmember,flank,row,col,L_mm,R_mm,"
                    "deviation_um\n" + "".join(
                        f"gear,{side},{i},{j},{float(L)!r},{float(R)!r},{float(d)!r}\n"
                        for i, j, L, R, d in zip(g.row, g.col, g.L_mm, g.R_mm, dev)))
    return g, dev
