"""Dynamic factor vs speed of a cylindrical pair's twin around its first mesh resonance,
the preview twin (the line chain as the law) beside the table twin, and ISO 6336-1's
resonance speed n_E1 (docs/cylindrical.md sec. 10).

The twins of ``examples/ev_reducer_helical_23x67.toml`` at ``--torque``
(:func:`gearcontact.twin.cylindrical.cylindrical_sweep_models`: ``--backend`` reference
or golden, and the loaded-TE table, rigid teeth, on one mesh) run a speed sweep
(:func:`gearcontact.twin.sweep.speed_sweep`) and print per speed the dynamic factor,
the DTE p-p and the contact loss of both, then each twin's linearised mesh mode speed
``60 f / z1`` against n_E1 (:func:`gearcontact.analytic.iso6336.resonance_speed_rpm`)
with the twin's own transverse mesh stiffness and with Method B's c_gamma_alpha.
``--csv FILE`` writes the table. Measured figures: docs/cylindrical.md sec. 10; the bound
the tests hold a twin's mesh mode to is 5 % of n_E1 with its own c_t.

Measured (session 19, defaults, f99ad27; docs/performance.md "Cylindrical pairs and
the resonance benchmark"): preview twin peak K_v 1.245 at 26,000 rpm, mode 26,109 rpm =
0.957 n_E1 (27,276 rpm, c_t 37.61 N/(mm·µm)), 1.400 x Method B's n_E1 (18,651 rpm);
table twin peak 1.264 at 26,000 rpm, mode 25,638 rpm = 0.957 n_E1 (26,779 rpm, c_t
36.25), 1.375 x Method B's. 11 s wall, 2.8 s CPU with the numba cache warm (load 9).

Run: ``python benchmarks/bench_twin_cylindrical_resonance.py [--torque 300]
[--speeds 17000:38000:1500] [--phases 21] [--backend reference] [--csv sweep.csv]``.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from gearcontact.analytic.iso6336 import (cylindrical_pair_stiffness, reduced_mass_kg_per_mm,
                                          resonance_speed_rpm)
from gearcontact.geometry.pair import load_pair
from gearcontact.twin.cylindrical import cylindrical_sweep_models
from gearcontact.twin.statics import linear_matrices, linearized_modes
from gearcontact.twin.sweep import parse_speed_range, speed_sweep

EV = Path(__file__).resolve().parents[1] / "examples" / "ev_reducer_helical_23x67.toml"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--torque", type=float, default=300.0, help="gear torque (N·m)")
    ap.add_argument("--speeds", default="17000:38000:1500", help="START:STOP:STEP rpm")
    ap.add_argument("--backend", default="reference", help="preview backend: reference, golden")
    ap.add_argument("--phases", type=int, default=21)
    ap.add_argument("--settle-s", type=float, default=0.05)
    ap.add_argument("--mesh-cycles", type=int, default=20)
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--csv", default=None, help="write the sweep table here")
    a = ap.parse_args()
    pair = load_pair(EV, kinds=("cylindrical",))
    g = pair.geometry
    models = cylindrical_sweep_models(pair, torque_nm=a.torque, backend=a.backend,
                                      phases=a.phases)
    speeds = parse_speed_range(a.speeds)
    sw = speed_sweep(models, speeds, settle_s=a.settle_s, mesh_cycles=a.mesh_cycles,
                     workers=a.workers)
    labels = list(models)
    lines = ["speed_rpm," + ",".join(f"{lb}_{c}" for lb in labels
                                     for c in ("dynamic_factor", "dte_pp_arcsec", "contact_loss"))]
    print(f"{'rpm':>8} " + " ".join(f"{lb + ' K_v':>14} {'DTE p-p':>8} {'loss':>6}"
                                    for lb in labels))
    for k, v in enumerate(speeds):
        cells = [(sw.rows[lb]["dynamic_factor"][k], sw.rows[lb]["dte_pp_arcsec"][k],
                  sw.rows[lb]["contact_loss"][k]) for lb in labels]
        print(f"{v:8.0f} " + " ".join(f"{kv:14.4f} {dte:8.3f} {loss:6.3f}"
                                      for kv, dte, loss in cells))
        lines.append(f"{v:g}," + ",".join(f"{kv:.6g},{dte:.6g},{loss:.6g}"
                                          for kv, dte, loss in cells))
    m_red = reduced_mass_kg_per_mm(
        mean_diameter_pinion_mm=0.5 * (g.tip_diameter_pinion_mm + g.root_diameter_pinion_mm),
        base_diameter_pinion_mm=g.base_diameter_pinion_mm, ratio=pair.ratio)
    geo = ("helix_angle_deg", "base_helix_angle_deg", "transverse_contact_ratio",
           "profile_shift_pinion", "profile_shift_gear")
    iso = cylindrical_pair_stiffness(pinion_teeth=pair.pinion_teeth, gear_teeth=pair.gear_teeth,
                                     dedendum_per_module=pair.dedendum_factor,
                                     **{k: getattr(g, k) for k in geo})
    iso_c = iso.c_gamma_alpha_n_per_mm_um
    for lb, model in models.items():
        _, _, k_th = linear_matrices(model)
        n_twin = 60.0 * linearized_modes(model)[-1] / pair.pinion_teeth
        c_t = k_th / (0.5e-3 * g.base_diameter_gear_mm) ** 2 * 1e-6 / g.face_width_mm
        for label, c in (("its c_t", c_t), ("Method B c_gamma_alpha", iso_c)):
            n = resonance_speed_rpm(pinion_teeth=pair.pinion_teeth, c_gamma_n_per_mm_um=c,
                                    reduced_mass_kg_per_mm=m_red)
            print(f"{lb}: n_E1 with {label} = {c:.2f} N/(mm·µm): {n:.0f} rpm; twin mesh mode "
                  f"{n_twin:.0f} rpm (ratio {n_twin / n:.3f})")
        rows = sw.rows[lb]
        peak = int(np.argmax(rows["dynamic_factor"]))
        print(f"{lb}: peak K_v {rows['dynamic_factor'][peak]:.3f} at {speeds[peak]:.0f} rpm")
    if a.csv:
        Path(a.csv).write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
