"""Write the SpyGO reference flank points of tests/data/spygo/ (NOT run by the tests).

SpyGO (https://github.com/haomjc/SpyGO, fork of https://github.com/eGrabovic/SpyGO) is
an independent open Python implementation of cradle-type face-milling generation. This
script maps gearcontact's machine settings of a few pinion flanks (and one generated gear
flank) into SpyGO's settings
(the mapping: README.md beside this file, and ``spygo_settings`` below), asks SpyGO's own
sampler ``hypoid.main.geometry.rz_sampling_casadi`` for the flank point at given (radius,
axial position) of the work frame, checks SpyGO's residuals, and writes

- ``cases.json``: per case gearcontact's ``[machine.<member>.<side>]`` / ``[blade...]``
  tables (what the test cuts), the pair file they start from, the hand, and the SpyGO
  settings typed (what SpyGO cut);
- ``points.csv``: per case and node the work-frame point and normal SpyGO returns.

Run (SpyGO's dependencies in their own venv, never the system python)::

    python3 -m venv /work/wt/spygo-venv
    /work/wt/spygo-venv/bin/pip install numpy scipy casadi numba matplotlib
    PYTHONPATH=src /work/wt/spygo-venv/bin/python tests/data/spygo/make_reference.py \
        --spygo /work/wt/spygo_src

``/work/wt/spygo_src`` is haomjc/SpyGO at 417ac9a52915220192df9c905cbbe5c147e58529 (the
files of ``git archive``; the two blobs the mirror lacks, ``OriginalCode/CI_3_7_0/
calyx.pyd`` and ``OriginalCode/hypoid_solver.pth``, are not used). SpyGO's package
``__init__`` imports its plotting (pyvista); the script registers the packages ``hypoid``
and ``hypoid.main`` by path so that only the geometry modules are imported.

gearcontact is used for two things only: the pair files' settings (which become SpyGO's
settings through the mapping) and the (u, v) node grid inside the active flank box
(which becomes the (R, z) at which SpyGO is asked for a point). Nothing of
gearcontact's envelope solution enters SpyGO's: its initial guesses come from a coarse
search on SpyGO's own equations.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import sys
import types
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
F2 = "examples/machine_settings/iso23509_f2_machine.toml"
HYPOID = "tests/data/spygo/hypoid_10x41_standard.toml"

#: Cases: (name, pair file, member, side, changes to the pair's [machine.<member>.<side>]
#: table).
#: Values chosen so that every pinion word moves the flank by far more than the test's
#: tolerance (measured in the test) and the envelope stays regular over the box.
CASES = [
    ("f2_drive", F2, "pinion", "drive", {}),
    ("f2_coast_words", F2, "pinion", "coast", {
        "machine_centre_to_back_mm": 0.7, "blank_offset_mm": 1.2,
        "modified_roll_2c_per_rad": 0.06, "modified_roll_6d_per_rad2": 0.4,
        "helical_motion_mm_per_rad": 4.0, "helical_motion_mm_per_rad2": 10.0}),
    ("hypoid_drive_roll", HYPOID, "pinion", "drive", {
        "modified_roll_2c_per_rad": 0.04, "modified_roll_6d_per_rad2": 0.3}),
    ("hypoid_coast_tilt", HYPOID, "pinion", "coast", {
        "tilt_deg": 5.0, "swivel_deg": -60.0,
        "helical_motion_mm_per_rad": 3.0, "helical_motion_mm_per_rad2": -6.0}),
    # the printed right-hand hypoid gear (generated), its words added, and a curved blade
    # (SpyGO's straight blade is a circle of 2e6 mm: 2.5e-5 mm off a line over 10 mm)
    ("hypoid_gear_drive_words", HYPOID, "gear", "drive", {
        "tilt_deg": 3.0, "swivel_deg": 30.0,
        "modified_roll_2c_per_rad": 0.03, "modified_roll_6d_per_rad2": 0.2,
        "helical_motion_mm_per_rad": 2.0, "helical_motion_mm_per_rad2": 4.0,
        "blade": {"profile_radius_mm": 800.0, "profile_reference_mm": 2.0}}),
]
N_U, N_V = 5, 7          # nodes per case: profile x face width
FRACTION = 0.08          # nodes inset from the active box's edges by this fraction


def wrap_deg(a: float) -> float:
    """Angle in (-180, 180], degrees."""
    a = math.fmod(a, 360.0)
    if a <= -180.0:
        a += 360.0
    elif a > 180.0:
        a -= 360.0
    return a


def spygo_settings(settings, blade, hand: str, member: str = "pinion") -> tuple[dict, dict]:
    """SpyGO's MachineField and CutterField values of a gearcontact set-up (``hand``: the
    pinion's, SpyGO's system hand; a gear only of a left-hand-pinion pair).

    The mapping (README.md, term by term): SpyGO's frames equal gearcontact's with
    ``x_M = -z_m, y_M = y_m, z_M = x_m`` (machine) and the work frame identical; SpyGO's
    hand-dependent sign matrix (``DesignData.manage_machine_settings``, pinion rows) is
    undone here so that SpyGO's effective joint values are gearcontact's.
    """
    right = hand == "right"
    s = 1.0 if right else -1.0
    if member == "gear" and right:
        raise SystemExit("a left-hand gear's mapping is not written (README.md)")
    mr = tuple(settings.modified_roll) + (0.0,) * (4 - len(settings.modified_roll))
    hm = tuple(settings.helical_motion) + (0.0,) * (2 - len(settings.helical_motion))
    machine = {
        "RADIALSETTING": settings.radial_distance_mm,
        "TILTANGLE": settings.tilt_deg,
        # SpyGO tilts the cutter axis towards e(q - 90 - sw) (right; left: the mirror)
        "SWIVELANGLE": wrap_deg(-90.0 - s * settings.swivel_deg),
        "BLANKOFFSET": s * settings.blank_offset_mm,
        "SLIDINGBASE": settings.sliding_base_mm,
        "CRADLEANGLE": s * settings.cradle_angle_deg,
        "MACHCTRBACK": settings.machine_centre_to_back_mm,
        "ROOTANGLE": settings.machine_root_angle_deg,
        "RATIOROLL": settings.ratio_of_roll,
        "C2": -s * mr[0], "D6": mr[1], "E24": -s * mr[2], "F120": mr[3],
        "H1": -s * hm[0], "H2": hm[1],
    }
    if member == "gear":
        # SpyGO's gear rows, system hand left (a right-hand gear): tilt negated, swivel
        # not, so its cutter axis leans to e(q + 90 - sw); the roll and the sliding base
        # series enter with gearcontact's signs
        machine.update({"SWIVELANGLE": wrap_deg(90.0 - settings.swivel_deg),
                        "BLANKOFFSET": settings.blank_offset_mm,
                        "CRADLEANGLE": settings.cradle_angle_deg,
                        "C2": mr[0], "E24": mr[2], "H1": hm[0]})
    machine = {k: v + 0.0 for k, v in machine.items()}     # no -0.0 in the JSON
    k = 1.0 / blade.profile_radius_mm if blade.profile_radius_mm else 0.0
    cutter = {
        "POINTRADIUS": blade.point_radius_mm,
        "EDGERADIUS": blade.edge_radius_mm,
        "TYPE": "CURVED" if k else "STRAIGHT",
        "RHO": blade.profile_radius_mm if k else None,
        # SpyGO's blade angle holds at the tip plane; gearcontact's at profile_reference
        "BLADEANGLE": blade.blade_angle_deg - math.degrees(k * blade.profile_reference_mm),
    }
    return machine, cutter


def import_spygo(path: Path):
    """SpyGO's geometry modules without its plotting package ``__init__``."""
    sys.path.insert(0, str(path))
    for name, sub in (("hypoid", "hypoid"), ("hypoid.main", "hypoid/main")):
        mod = types.ModuleType(name)
        mod.__path__ = [str(path / sub)]
        sys.modules[name] = mod
    import hypoid.main.data_structs as ds
    import hypoid.main.geometry as geo
    import hypoid.main.kinematics as kin
    return ds, geo, kin


def our_case(pair_file: str, member: str, side: str, changes: dict):
    """gearcontact's pair, the changed set-up and its tables."""
    import dataclasses
    from gearcontact.geometry.machine import setup_from_tables, setup_to_tables
    from gearcontact.geometry.pair import load_pair
    pair = load_pair(ROOT / pair_file)
    base = next(s for s in pair.machine if s.member == member and s.side == side)
    machine, blade = setup_to_tables(base)
    changes = dict(changes)
    blade = {**blade, **changes.pop("blade", {})}
    machine = {**machine, **changes}
    setup = setup_from_tables(member, side, machine, blade)
    return pair, dataclasses.replace(setup), machine, blade


def node_grid(pair, setup):
    """(u, v) nodes inside the active box and their work-frame (R, z_w), mm."""
    from gearcontact.geometry.generated import generated_gear_box, generated_pinion_box
    if setup.member == "gear":
        solver, box, _ = generated_gear_box(setup, pair.blank,
                                            gear_face_width_mm=pair.gear_face_width_mm)
    else:
        solver, box, _ = generated_pinion_box(setup, pair.blank,
                                              pinion_face_width_mm=pair.pinion_face_width_mm)
    du, dv = box.u_tip - box.u_root, box.v_heel - box.v_toe
    us = np.linspace(box.u_root + FRACTION * du, box.u_tip - FRACTION * du, N_U)
    vs = np.linspace(box.v_toe + FRACTION * dv, box.v_heel - FRACTION * dv, N_V)
    uu, vv = np.meshgrid(us, vs, indexing="ij")
    radius = solver.cone.radius_mm(uu, vv)
    if setup.member == "gear":                 # X_body = Rz(theta_P) X_w + (0, 0, z_A2)
        z_w = solver.cone.height_mm(uu, vv) - pair.blank.gear_apex_z_mm
    else:                                      # X_body = Q X_w + (x_A1, 0, 0), Q: z_w -> x
        z_w = vv - pair.blank.pinion_apex_x_mm
    return uu, vv, radius, z_w


def solve(root, f, start, target):
    """SpyGO's equations solved from ``start``: CasADi's Newton, and where it fails from
    there, a least-squares step on the same equations first (scipy)."""
    from scipy.optimize import least_squares
    try:
        return np.array(root(start, target)).ravel()
    except RuntimeError:
        fit = least_squares(lambda q: np.array(f(q, target)).ravel(), start,
                            xtol=1e-15, ftol=1e-15, gtol=1e-15)
        return np.array(root(fit.x, target)).ravel()


def spygo_points(ds, geo, kin, machine: dict, cutter: dict, hand: str, member: str,
                 flank: str, radius, z_w):
    """SpyGO's flank points and normals at (R, z_w), with its parameters and residuals."""
    import casadi as ca
    data = ds.DesignData()
    data.system_data.hand = hand
    data.gear_common_data.gen_type = "generated"
    mf = ds.MachineField(**{k: v for k, v in machine.items()})
    cf = ds.CutterField(**cutter)
    setattr(getattr(data, f"{member}_machine_settings"), flank, mf)
    setattr(getattr(data, f"{member}_cutter_data"), flank, cf)
    mat = data.extract_machine_settings_matrix(member, flank)
    tool = np.array(data.extract_tool_settings(member, flank))
    ggt, _, vgt = kin.casadi_machine_kinematics(member, hand)
    p_t, n_t, _ = kin.casadi_tool_fun(flank)
    x = ca.SX.sym("x", 3)                 # csi, theta, phi
    g = ggt(mat, x[2])
    pg = g @ ca.vertcat(p_t(tool, x[:2]), 1)
    ng = g @ ca.vertcat(n_t(tool, x[:2]), 0)
    mesh = ng.T @ vgt(mat, x[2]) @ pg
    target = ca.SX.sym("t", 2)
    res = ca.vertcat(ca.sqrt(pg[0] ** 2 + pg[1] ** 2) - target[0], pg[2] - target[1], mesh)
    f = ca.Function("f", [x, target], [res])
    # coarse search of the first node on SpyGO's own equations (signed z: SpyGO's
    # sampler squares it), then continuation node by node
    csi = np.linspace(0.0, 30.0, 31)
    theta = np.radians(np.arange(-180.0, 180.0, 1.0))
    phi = np.radians(np.arange(-60.0, 60.0, 0.5))
    grid = np.array(np.meshgrid(csi, theta, phi, indexing="ij")).reshape(3, -1)
    i0, j0 = radius.shape[0] // 2, radius.shape[1] // 2
    fm = f.map(grid.shape[1])
    r = np.array(fm(grid, np.tile([[radius[i0, j0]], [z_w[i0, j0]]], grid.shape[1])))
    scale = np.array([[1.0], [1.0], [1.0 / max(1.0, float(np.median(np.abs(r[2]))))]])
    guess0 = grid[:, int(np.argmin(np.sum((r * scale) ** 2, axis=0)))]
    root = ca.rootfinder("r", "newton", {"x": x, "p": target, "g": res},
                         {"abstol": 1e-12, "max_iter": 100})
    guesses = np.full((3,) + radius.shape, np.nan)
    order = sorted(np.ndindex(radius.shape), key=lambda ij: abs(ij[0] - i0) + abs(ij[1] - j0))
    for ij in order:
        near = [guesses[(slice(None),) + nb] for nb in
                ((ij[0] - 1, ij[1]), (ij[0] + 1, ij[1]), (ij[0], ij[1] - 1), (ij[0], ij[1] + 1))
                if 0 <= nb[0] < radius.shape[0] and 0 <= nb[1] < radius.shape[1]
                and np.all(np.isfinite(guesses[(slice(None),) + nb]))]
        start = near[0] if near else guess0
        guesses[(slice(None),) + ij] = solve(root, f, start, [radius[ij], z_w[ij]])
    # SpyGO's own sampler from those guesses (its machine matrix, sign matrix, tool)
    xyz, nrm, trip = geo.rz_sampling_casadi(radius, z_w, data, member, flank,
                                            triplet_guess=guesses)
    resid = np.array([np.abs(np.array(f(trip[:, i, j], [radius[i, j], z_w[i, j]]))).max()
                      for i, j in np.ndindex(radius.shape)]).reshape(radius.shape)
    return xyz[:3], nrm[:3], trip, resid


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--spygo", type=Path, required=True, help="SpyGO source tree (417ac9a)")
    args = ap.parse_args()
    ds, geo, kin = import_spygo(args.spygo.resolve())
    cases, rows = {}, []
    for name, pair_file, member, side, changes in CASES:
        pair, setup, machine, blade = our_case(pair_file, member, side, changes)
        hand = pair.pinion_hand
        # pinion drive / gear coast: the outside blade, SpyGO's concave flank
        flank = "concave" if (side == "drive") == (member == "pinion") else "convex"
        sp_machine, sp_cutter = spygo_settings(setup.settings, setup.blade, hand, member)
        uu, vv, radius, z_w = node_grid(pair, setup)
        xyz, nrm, trip, resid = spygo_points(ds, geo, kin, sp_machine, sp_cutter, hand, member,
                                             flank, radius, z_w)
        worst = float(resid.max())
        if not worst < 1e-9:
            raise SystemExit(f"{name}: SpyGO residual {worst:.3e} (not converged)")
        print(f"{name}: {radius.size} points, SpyGO residual <= {worst:.2e}, "
              f"roll {np.degrees(trip[2].min()):.2f}..{np.degrees(trip[2].max()):.2f} deg")
        cases[name] = {"pair": pair_file, "member": member, "side": side, "hand": hand,
                       "spygo_flank": flank,
                       "changes": changes, "machine": machine, "blade": blade,
                       "spygo_machine": sp_machine, "spygo_cutter": sp_cutter}
        for i, j in np.ndindex(radius.shape):
            rows.append([name, i, j, *(f"{a:.12f}" for a in (
                uu[i, j], vv[i, j], radius[i, j], z_w[i, j], *xyz[:, i, j], *nrm[:, i, j],
                *trip[:, i, j])), f"{resid[i, j]:.1e}"])
    (HERE / "cases.json").write_text(json.dumps(cases, indent=2, sort_keys=True) + "\n")
    with open(HERE / "points.csv", "w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(["case", "i_u", "i_v", "u_mm", "v_mm", "radius_mm", "z_w_mm", "x_mm", "y_mm",
                    "z_mm", "n_x", "n_y", "n_z", "csi_mm", "theta_rad", "phi_rad",
                    "spygo_residual"])
        w.writerows(rows)


if __name__ == "__main__":
    main()
