"""Dynamic factor vs speed of a cylindrical pair's twin around its first mesh resonance,
beside ISO 6336-1's resonance speed n_E1 (docs/cylindrical.md sec. 10).

The twin of ``examples/ev_reducer_helical_23x67.toml`` on its loaded-TE table
(:func:`gearcontact.twin.cylindrical.cylindrical_model`, rigid teeth) at ``--torque``
runs a speed sweep (:func:`gearcontact.twin.sweep.speed_sweep`) and prints per speed the
dynamic factor, the DTE p-p and the contact loss, then the linearised mesh mode's speed
``60 f / z1`` against n_E1 (:func:`gearcontact.analytic.iso6336.resonance_speed_rpm`)
with the twin's own transverse mesh stiffness and with Method B's c_gamma_alpha.
``--csv FILE`` writes the table. On the shared 2-core machine the default sweep (12
speeds) took 456 s (table law, 21 phases): the peak was K = 1.264 at 26,000 rpm, the
mode at 25,638 rpm.

Run: ``python benchmarks/bench_twin_cylindrical_resonance.py [--torque 300]
[--speeds 17000:34000:1500] [--phases 21] [--csv sweep.csv]``.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from gearcontact.analytic.iso6336 import (cylindrical_pair_stiffness, reduced_mass_kg_per_mm,
                                          resonance_speed_rpm)
from gearcontact.geometry.pair import load_pair
from gearcontact.twin.cylindrical import cylindrical_model
from gearcontact.twin.statics import linear_matrices, linearized_modes
from gearcontact.twin.sweep import parse_speed_range, speed_sweep

EV = Path(__file__).resolve().parents[1] / "examples" / "ev_reducer_helical_23x67.toml"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--torque", type=float, default=300.0, help="gear torque (N·m)")
    ap.add_argument("--speeds", default="17000:34000:1500", help="START:STOP:STEP rpm")
    ap.add_argument("--phases", type=int, default=21)
    ap.add_argument("--settle-s", type=float, default=0.05)
    ap.add_argument("--mesh-cycles", type=int, default=20)
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--csv", default=None, help="write the sweep table here")
    a = ap.parse_args()
    pair = load_pair(EV, kinds=("cylindrical",))
    g = pair.geometry
    model = cylindrical_model(pair, torque_nm=a.torque, phases=a.phases)
    speeds = parse_speed_range(a.speeds)
    sw = speed_sweep({"table": model}, speeds, settle_s=a.settle_s,
                     mesh_cycles=a.mesh_cycles, workers=a.workers)
    rows = sw.rows["table"]
    lines = ["speed_rpm,dynamic_factor,dte_pp_arcsec,contact_loss"]
    print(f"{'rpm':>8} {'K_v':>7} {'DTE p-p':>8} {'loss':>6}")
    for k, v in enumerate(speeds):
        print(f"{v:8.0f} {rows['dynamic_factor'][k]:7.4f} {rows['dte_pp_arcsec'][k]:8.3f} "
              f"{rows['contact_loss'][k]:6.3f}")
        lines.append(f"{v:g},{rows['dynamic_factor'][k]:.6g},{rows['dte_pp_arcsec'][k]:.6g},"
                     f"{rows['contact_loss'][k]:.6g}")
    _, _, k_th = linear_matrices(model)
    n_twin = 60.0 * linearized_modes(model)[-1] / pair.pinion_teeth
    c_t = k_th / (0.5e-3 * g.base_diameter_gear_mm) ** 2 * 1e-6 / g.face_width_mm
    m_red = reduced_mass_kg_per_mm(
        mean_diameter_pinion_mm=0.5 * (g.tip_diameter_pinion_mm + g.root_diameter_pinion_mm),
        base_diameter_pinion_mm=g.base_diameter_pinion_mm, ratio=pair.ratio)
    geo = ("helix_angle_deg", "base_helix_angle_deg", "transverse_contact_ratio",
           "profile_shift_pinion", "profile_shift_gear")
    iso = cylindrical_pair_stiffness(pinion_teeth=pair.pinion_teeth, gear_teeth=pair.gear_teeth,
                                     dedendum_per_module=pair.dedendum_factor,
                                     **{k: getattr(g, k) for k in geo})
    for label, c in (("twin's c_t", c_t), ("Method B c_gamma_alpha", iso.c_gamma_alpha_n_per_mm_um)):
        n = resonance_speed_rpm(pinion_teeth=pair.pinion_teeth, c_gamma_n_per_mm_um=c,
                                reduced_mass_kg_per_mm=m_red)
        print(f"n_E1 with {label} = {c:.2f} N/(mm·µm): {n:.0f} rpm; twin mesh mode "
              f"{n_twin:.0f} rpm (ratio {n_twin / n:.3f})")
    peak = int(np.argmax(rows["dynamic_factor"]))
    print(f"peak K_v {rows['dynamic_factor'][peak]:.3f} at {speeds[peak]:.0f} rpm")
    if a.csv:
        Path(a.csv).write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
