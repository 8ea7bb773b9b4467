"""Benchmark: time-varying mesh stiffness of the standard 20/40 spur pair, gearcontact's
loaded contact with tooth bending beside ``ross-rotordynamics``' gear mesh (an
independent code: the potential-energy method with Hertz, bending, shear, axial and
fillet-foundation terms, Sainsot et al. 2004), same pair, same run.

gearcontact: :func:`gearcontact.ltca.cylindrical_lte.cylindrical_loaded_te` with bending
at ``--torque`` (default T2 = 400 N·m, 333 N/mm), the secant stiffness per unit face width
F_n / (b delta) at each phase (docs/cylindrical.md sec. 7). ROSS: ``GearElementTVMS`` of
both members (module, teeth, width, 20 deg, ROSS steel E = 211 GPa, bores 30 / 60 mm)
and ``Mesh.stiffness_range`` (N/m along the line of action, linear) over one mesh period,
divided by the face width. The two waveforms start at different phases: ROSS's is
shifted circularly to the best match (least squares) before its difference is printed;
the mean, minimum, maximum, their ratios and the CPU times are printed beside it.

``ross-rotordynamics`` is a benchmark-only peer (``pip install ross-rotordynamics``; its
plotly theme needs plotly < 6). Not a test: the two models differ (ours: half-space
contact, shell teeth on a calibrated rim; ROSS: 1D beam-energy teeth on Sainsot's body).

Run: ``python benchmarks/bench_mesh_stiffness_ross.py [--torque N·m] [--phases N]``.
"""

from __future__ import annotations

import argparse
import math
import os
import time
from pathlib import Path

import numpy as np

from gearcontact.geometry.pair import CYLINDRICAL, load_pair
from gearcontact.ltca.cylindrical_lte import cylindrical_loaded_te
from gearcontact.ltca.mesh_lcp import warm_up_mesh_lcp
from gearcontact.tca.cylindrical_cycle import cylindrical_mesh_cycle

PAIR = Path(__file__).resolve().parents[1] / "examples" / "spur_20x40_m3.toml"


def ross_stiffness(pair, points: int):
    """ROSS's mesh stiffness over one period, N/(mm·µm) per unit face (points,), and the
    CPU seconds it took. From the pair's normal module, pressure angle, teeth and common
    face width only: ROSS's energy method (``GearElementTVMS``, version 2.3) is that of a
    spur tooth without profile shift, tip shortening or micro-geometry (its helix angle
    is stored on the mesh, not used in the stiffness)."""
    try:
        from ross.gear_element import GearElementTVMS, Mesh
        from ross.materials import steel
    except ImportError as exc:     # pragma: no cover - optional peer
        raise SystemExit(f"needs ross-rotordynamics (pip install ross-rotordynamics): {exc}")
    g = pair.geometry
    b = g.face_width_mm * 1e-3
    c0 = time.process_time()
    kw = dict(material=steel, width=b, module=g.normal_module_mm * 1e-3,
              pr_angle=math.radians(g.normal_pressure_angle_deg))
    mesh = Mesh(GearElementTVMS(n=0, bore_diameter=0.03, n_teeth=pair.pinion_teeth, **kw),
                GearElementTVMS(n=2, bore_diameter=0.06, n_teeth=pair.gear_teeth, **kw))
    _, k = mesh.get_stiffness_for_mesh_period(n_points=points)
    return np.asarray(k) / b / 1e9, time.process_time() - c0, mesh.contact_ratio


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--torque", type=float, default=400.0, help="gear torque, N·m")
    ap.add_argument("--phases", type=int, default=61)
    args = ap.parse_args()
    pair = load_pair(PAIR, kinds=(CYLINDRICAL,))
    warm_up_mesh_lcp()
    cycle = cylindrical_mesh_cycle(pair, phases=args.phases)
    cylindrical_loaded_te(pair, args.torque, cycle=cycle)          # tooth models, once
    c0 = time.process_time()
    ours = cylindrical_loaded_te(pair, args.torque, cycle=cycle)
    t_ours = time.process_time() - c0
    k = ours.stiffness_n_per_mm_um[:-1]                            # one period
    ross, t_ross, eps = ross_stiffness(pair, len(k))
    shifts = [np.roll(ross, s) for s in range(len(k))]
    best = min(shifts, key=lambda r: float(np.sum((r - k) ** 2)))
    print(f"{pair.name}, T2 = {args.torque:g} N·m, {len(k)} phases per mesh period "
          f"(ROSS contact ratio {eps:.3f}, ours {pair.geometry.transverse_contact_ratio:.3f})")
    print(f"  gearcontact (bending): mean {k.mean():.2f}, min {k.min():.2f}, max {k.max():.2f} "
          f"N/(mm·µm); loaded TE {t_ours:.3f} s CPU")
    print(f"  ROSS (energy method):  mean {ross.mean():.2f}, min {ross.min():.2f}, max "
          f"{ross.max():.2f} N/(mm·µm); {t_ross:.3f} s CPU")
    print(f"  ratio ours / ROSS: mean {k.mean() / ross.mean():.3f}, "
          f"min {k.min() / ross.min():.3f}, max {k.max() / ross.max():.3f}; waveform (best "
          f"shift) rms difference {np.sqrt(np.mean((best - k) ** 2)):.2f} N/(mm·µm); "
          f"load average {os.getloadavg()[0]:.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
