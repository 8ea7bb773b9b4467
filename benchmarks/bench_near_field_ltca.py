"""The near-field split in the LTCA (docs/bending.md sec. 13, session 27): its measurements.

``--widths``: criterion 1, the split at narrow patches. Set A's 12 patches on a gear made
blockless (rim depth = fillet, session 26's set-up), each ``2 / n_eta`` high in eta (two
FE cells of a mesh ``n_xi x n_eta x n_zeta + 4 (3, 2)``, n_zeta 3 by default), the combined loaded-flank compliance
(HS_s + far_solid) / C_FE_front and the plate's (HS_s + plate) / C_FE_front.

``--ltca``: criterion 4 (reported, no truth): the multi-tooth LTCA at P0 and the loaded TE
over a pitch (64.5 N·m, 40 cells) of the pair with its gear blockless, with the gear's
no-block plate (today's operator) and with the split (``ToothBending(near_field=True)``
on the Ritz solid tooth): shares, rotations, CP_max, TE p-p, and the least eigenvalue
of the total compliance on the contact cells (from the solves' messages).

Usage: python3 benchmarks/bench_near_field_ltca.py --widths --pair s0003 --n-eta 24 48
       python3 benchmarks/bench_near_field_ltca.py --ltca --pair s0003-centred
(``--pair`` a preset or TOML file; the F.2 gear: examples/machine_settings/iso23509_f2_machine.toml.)
"""

from __future__ import annotations

import argparse
import json
import os
import re
import sys
import time
import warnings
from pathlib import Path

import numpy as np

from gearcontact.geometry.flank import build_flanks
from gearcontact.geometry.pair import load_pair
from gearcontact.structure.rim import rim_segment
from gearcontact.structure.rim_block import BLOCK_RIM_STIFFENING
from gearcontact.structure.shell import tooth_shell
from gearcontact.structure.tooth import tooth_geometry

ROOT = Path(__file__).resolve().parents[1]


def widths(pair, flanks, n_etas, n_xi, n_zeta):
    sys.path.insert(0, str(ROOT))
    from gearcontact.structure.compliance import FeMesh
    from tests.structure.test_near_field import far_field_table

    for n_eta in n_etas:
        t0 = time.process_time()
        t = far_field_table(pair, flanks, "gear", FeMesh(n_xi, n_eta, n_zeta, 4, 3, 2),
                            half_height=2.0 / n_eta)
        split = (t["halfspace_surface"] + t["far"]) / t["fe_flank"]
        plate = (t["halfspace_surface"] + t["plate"]) / t["fe_flank"]
        print(json.dumps({"n_eta": n_eta, "n_xi": n_xi, "n_zeta": n_zeta, "width_mm": round(float(
            t["width_mm"].mean()), 4), "split": split.round(4).tolist(),
            "plate": plate.round(4).tolist(), "cpu_s": round(time.process_time() - t0, 1)}))


def ltca(pair, flanks, torque, phases):
    import gearcontact.ltca.mesh_lcp as mesh_lcp
    from gearcontact.ltca.lte import loaded_te
    from gearcontact.ltca.tooth_bending import ToothBending, solid_tooth
    from gearcontact.tca.analysis import analyze_pair

    side = pair.design_side
    tca = analyze_pair(pair, side=side, phases=phases, flanks=flanks)[0]
    tooth = tooth_geometry(flanks, "gear", material=pair.gear_material)
    rim = rim_segment(tooth, depth_mm=rim_segment(tooth).fillet_mm,
                      stiffening=BLOCK_RIM_STIFFENING)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")       # NoBlockWarning: the plate is today's operator
        plate = tooth_shell(flanks, "gear", material=pair.gear_material, rim=rim)
    pin = tooth_shell(flanks, "pinion", material=pair.pinion_material)
    import gearcontact.ltca.lte_phase as lte_phase
    import gearcontact.ltca.multitooth as multitooth

    least, modules = [], (mesh_lcp, lte_phase, multitooth)
    solve = mesh_lcp.solve_mesh_lcp

    def recording(*a, **k):   # the least eigenvalue each signed solve reports
        res = solve(*a, **k)
        m = re.search(r"least eigenvalue ([-0-9.e+]+)", res.message)
        if m:
            least.append(float(m.group(1)))
        return res

    for label, bend in (("plate", ToothBending(pinion=pin, gear=plate, side=side)),
                        ("split", ToothBending(pinion=pin, gear=solid_tooth(plate),
                                               side=side, near_field=True))):
        least.clear()
        for mod in modules:
            mod.solve_mesh_lcp = recording
        t0 = time.process_time()
        mt = multitooth.multi_tooth_ltca(tca, flanks, pair, torque, side=side, bending=bend).summary()
        te = loaded_te(tca, flanks, pair, torque, side=side, cells=40, bending=bend)
        for mod in modules:
            mod.solve_mesh_lcp = solve
        d = np.asarray(te.te_lcp_arcsec)
        print(json.dumps({
            "operator": label, "load_share_pct": np.round(mt["load_share_pct"], 2).tolist(),
            "load_share_rigid_pct": np.round(mt["load_share_rigid_pct"], 2).tolist(),
            "rotation_rigid_arcsec": round(mt["mesh_rotation_rigid_arcsec"], 3),
            "rotation_arcsec": round(mt["mesh_rotation_arcsec"], 3),
            "cp_max_mpa": round(mt["cp_max_mpa"], 1),
            "p_peak_cell_mpa": round(mt["p_peak_cell_mpa"], 1),
            "te_lcp_pp_arcsec": round(float(d.max() - d.min()), 3),
            "rotation_lcp_mean_arcsec": round(float(np.mean(te.rotation_lcp_arcsec)), 3),
            "status": str(mt["status"]), "signed_solves": len(least),
            "least_eigenvalue_mm_per_n": min(least) if least else None,
            "cpu_s": round(time.process_time() - t0, 1)}))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pair", default="s0003-centred")
    ap.add_argument("--widths", action="store_true")
    ap.add_argument("--n-eta", type=int, nargs="+", default=[24, 48])
    ap.add_argument("--n-xi", type=int, default=24)
    ap.add_argument("--n-zeta", type=int, default=3)
    ap.add_argument("--ltca", action="store_true")
    ap.add_argument("--torque", type=float, default=64.5)
    ap.add_argument("--phases", type=int, default=61)
    args = ap.parse_args(argv)
    pair = load_pair(Path(args.pair) if args.pair.endswith(".toml") else args.pair)
    flanks = build_flanks(pair)
    print(f"pair {args.pair}; load average {os.getloadavg()}")
    if args.widths:
        widths(pair, flanks, args.n_eta, args.n_xi, args.n_zeta)
    if args.ltca:
        ltca(pair, flanks, args.torque, args.phases)


if __name__ == "__main__":
    main()
