"""Files of the cylindrical mesh-cycle TCA: what ``gearcontact tca`` writes for a
``kind = "cylindrical"`` pair (docs/cylindrical.md sec. 6).

``write_cylindrical_tca_outputs`` writes into one directory: ``tca.json`` (summary with
the ISO 21771 contact ratios beside the TCA's), ``te0.csv`` (per phase; ``contact``:
``line`` or the tip edge that touches first, docs/cylindrical.md sec. 6),
``contact_lines.csv`` (per phase and tooth pair in the zone of action) and the figures
``te0.png`` and ``contact_pattern.png`` (with their SVGs). No timings: identical runs
write identical files.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from .cylindrical_cycle import CONTACT_TOLERANCE_MM, CylindricalMeshCycle
from .export import write_csv

__all__ = ["write_cylindrical_tca_outputs", "cylindrical_summary"]


def cylindrical_summary(cycle: CylindricalMeshCycle, pair, *, side: str) -> dict:
    """The ``tca.json`` dict of ``cycle`` (a TCA of ``pair``)."""
    g = pair.geometry
    beta_b = math.radians(g.base_helix_angle_deg)
    return {
        "pair": pair.name, "kind": "cylindrical", "side": side, "facing": cycle.facing,
        "phases_per_pitch": len(cycle.phi1_rad),
        "te0_pp_arcsec": cycle.te0_pp_arcsec,
        "te0_min_arcsec": float(cycle.envelope_arcsec.min()),
        "te0_max_arcsec": float(cycle.envelope_arcsec.max()),
        "pair_offsets": list(cycle.pair_offsets),
        "pairs_in_zone_min_max": [int(cycle.pairs_in_zone.min()), int(cycle.pairs_in_zone.max())],
        "pairs_in_contact_min_max": [int(cycle.pairs_in_contact.min()),
                                     int(cycle.pairs_in_contact.max())],
        "mean_pairs_in_zone": cycle.mean_pairs_in_zone,
        "transverse_contact_ratio": g.transverse_contact_ratio,
        "overlap_ratio": g.overlap_ratio,
        "total_contact_ratio": g.total_contact_ratio,
        "mean_line_length_mm": cycle.mean_line_length_mm,
        # ISO 21771: the lines of unmodified flanks average b eps_alpha / cos beta_b
        "line_length_iso_mean_mm": g.face_width_mm * g.transverse_contact_ratio / math.cos(beta_b),
        "line_length_min_max_mm": [float(cycle.line_length_mm.min()),
                                   float(cycle.line_length_mm.max())],
        # a tip edge touching first: premature / prolonged contact beyond the path
        "tip_contact_phases": sum(bool(mp.edge_contact) for mp in cycle.contact),
        "tip_contact_edges": sorted({mp.edge_contact for mp in cycle.contact
                                     if mp.edge_contact}),
        "paint_mm": cycle.paint_mm, "contact_tolerance_mm": CONTACT_TOLERANCE_MM,
        "assembly": {"axis_inclination_um": pair.assembly.axis_inclination_um,
                     "axis_deviation_um": pair.assembly.axis_deviation_um},
        "te0_reference": "perfect involute mesh at the working centre distance, backlash "
                         "split evenly between the facings (docs/cylindrical.md sec. 6)",
    }


def write_cylindrical_tca_outputs(cycle: CylindricalMeshCycle, pair, out, *, side: str,
                                  figures: bool = True) -> dict:
    """Write the files of the module docstring into ``out`` (created if missing);
    returns the ``tca.json`` dict."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    phi_deg = np.degrees(cycle.phi1_rad)
    write_csv(out / "te0.csv",
              ["phi1_deg"] + [f"te0_pair{j:+d}_arcsec" for j in cycle.pair_offsets]
              + ["te0_arcsec", "active_pair", "contact", "pairs_in_zone", "pairs_in_contact",
                 "line_length_mm", "painted_length_mm"],
              [[float(phi_deg[k])] + [float(x) for x in cycle.te0_pairs_arcsec[:, k]]
               + [float(cycle.envelope_arcsec[k]), int(cycle.active_pair[k]),
                  cycle.contact[k].edge_contact or "line",
                  int(cycle.pairs_in_zone[k]), int(cycle.pairs_in_contact[k]),
                  float(cycle.line_length_mm[k]), float(cycle.painted_length_mm[k])]
               for k in range(len(phi_deg))])
    rows = []
    for k in range(len(phi_deg)):
        for p, j in enumerate(cycle.pair_offsets):
            ends = cycle.line_ends_mm[p, k]
            if not np.all(np.isfinite(ends)):
                continue
            zu, c, pz = (cycle.line_ends_zu_mm[p, k], cycle.contact_zu_mm[p, k],
                         cycle.painted_ends_zu_mm[p, k])
            rows.append([float(phi_deg[k]), j, float(cycle.gap_min_mm[p, k] * 1e3),
                         float(cycle.te0_pairs_arcsec[p, k]), *map(float, ends.ravel()),
                         *map(float, zu.ravel()), *map(float, c), *map(float, pz.ravel())])
    write_csv(out / "contact_lines.csv",
              ["phi1_deg", "pair", "gap_min_um", "te0_pair_arcsec",
               "start_x_mm", "start_y_mm", "start_z_mm", "end_x_mm", "end_y_mm", "end_z_mm",
               "start_pinion_z_mm", "start_pinion_u_mm", "end_pinion_z_mm", "end_pinion_u_mm",
               "contact_pinion_z_mm", "contact_pinion_u_mm",
               "painted_start_z_mm", "painted_start_u_mm", "painted_end_z_mm",
               "painted_end_u_mm"], rows)
    summary = cylindrical_summary(cycle, pair, side=side)
    (out / "tca.json").write_text(json.dumps(summary, indent=2))
    if figures:
        from .cylindrical_plots import plot_cylindrical_pattern, plot_cylindrical_te0

        label = f"{pair.name} {side} ({cycle.facing} flanks)"
        plot_cylindrical_te0(cycle, out / "te0.png", title=f"{label}: unloaded TE")
        plot_cylindrical_pattern(cycle, out / "contact_pattern.png",
                                 title=f"{label}: pinion flank")
    return summary
