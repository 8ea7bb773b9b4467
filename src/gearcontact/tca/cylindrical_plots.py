"""Figures of the cylindrical mesh-cycle TCA (matplotlib, Agg): TE0 and the total
contact-line length over the pitch, and the contact pattern on the pinion flank.

The flank view is the usual one of cylindrical gear practice (ISO 21771 / ISO 1328
profile and helix charts): face width z across, diameter up; a contact line of a helical
pair is a straight diagonal in (z, roll length) and a curve in (z, diameter).
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ..figure_files import save_figure  # noqa: E402
from .cylindrical_cycle import CylindricalMeshCycle  # noqa: E402

__all__ = ["plot_cylindrical_te0", "plot_cylindrical_pattern"]


def _diameter(cycle: CylindricalMeshCycle, u):
    return 2.0 * np.hypot(u, cycle.pinion_base_radius_mm)


def plot_cylindrical_te0(cycle: CylindricalMeshCycle, path, *, title: str = ""):
    """TE0 of each tooth pair and the envelope over one pitch (top), total contact-line
    length and pairs in contact (bottom); PNG (and SVG) at ``path``."""
    phi = np.degrees(cycle.phi1_rad)
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
    for j, te in zip(cycle.pair_offsets, cycle.te0_pairs_arcsec):
        ax.plot(phi, te, lw=1.0, alpha=0.7, label=f"pair {j:+d} alone")
    ax.plot(phi, cycle.envelope_arcsec, color="k", lw=2.2,
            label=f"TE0, p-p {cycle.te0_pp_arcsec:.3f} arcsec")
    lo, hi = float(np.min(cycle.envelope_arcsec)), float(np.max(cycle.envelope_arcsec))
    pad = max(hi - lo, 0.5)
    ax.set_ylim(lo - 1.5 * pad, hi + 1.5 * pad)
    ax.set_ylabel("TE0 (arcsec)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax2.plot(phi, cycle.line_length_mm, color="tab:blue", lw=1.8, label="contact lines (zone)")
    ax2.plot(phi, cycle.painted_length_mm, color="tab:orange", lw=1.2,
             label=f"painted ({cycle.paint_mm * 1e3:.2f} um)")
    ax2.set_ylabel("total line length (mm)")
    ax2.set_xlabel("pinion rotation phi1 (deg)")
    ax2.grid(alpha=0.3)
    right = ax2.twinx()
    right.step(phi, cycle.pairs_in_contact, where="mid", color="0.3", lw=1.0,
               label="pairs touching")
    right.set_ylabel("pairs touching")
    right.set_ylim(0, max(int(cycle.pairs_in_zone.max()), 1) + 1)
    h1, l1 = ax2.get_legend_handles_labels()
    h2, l2 = right.get_legend_handles_labels()
    ax2.legend(h1 + h2, l1 + l2, fontsize=8, loc="upper left", bbox_to_anchor=(1.08, 1.0))
    fig.suptitle(title or f"unloaded TE over one pinion pitch ({len(phi)} phases)")
    fig.tight_layout()
    out = save_figure(fig, path, dpi=130, tight=True)
    plt.close(fig)
    return out


def plot_cylindrical_pattern(cycle: CylindricalMeshCycle, path, *, title: str = ""):
    """Contact lines and the painted pattern on the pinion flank (z across, diameter
    up) over one pitch of every pair: thin grey the lines in the zone of action, thick
    orange their painted parts, dots the least-gap points of the transmitting pair."""
    fig, ax = plt.subplots(figsize=(8, 5))
    (z0, z1), (u0, u1) = cycle.pinion_v_range_mm, cycle.pinion_u_range_mm
    d0, d1 = _diameter(cycle, u0), _diameter(cycle, u1)
    ax.plot([z0, z1, z1, z0, z0], [d0, d0, d1, d1, d0], color="0.2", lw=1.0,
            label="flank (form to tip circle)")
    t = np.linspace(0.0, 1.0, 25)
    for p in range(len(cycle.pair_offsets)):
        for k in range(len(cycle.phi1_rad)):
            for ends, style in ((cycle.line_ends_zu_mm[p, k], dict(color="0.6", lw=0.5)),
                                (cycle.painted_ends_zu_mm[p, k],
                                 dict(color="tab:orange", lw=2.0, alpha=0.8))):
                if not np.all(np.isfinite(ends)):
                    continue
                z = ends[0, 0] + t * (ends[1, 0] - ends[0, 0])
                u = ends[0, 1] + t * (ends[1, 1] - ends[0, 1])   # affine along the line
                ax.plot(z, _diameter(cycle, u), **style)
    ax.plot([], [], color="0.6", lw=0.5, label="contact lines in the zone")
    ax.plot([], [], color="tab:orange", lw=2.0,
            label=f"painted ({cycle.paint_mm * 1e3:.2f} um)")
    act = np.array([[mp.v1, mp.u1] for mp in cycle.contact])
    ax.plot(act[:, 0], _diameter(cycle, act[:, 1]), "k.", ms=3,
            label="transmitting contact (least gap)")
    ax.set_xlabel("pinion face position z (mm)")
    ax.set_ylabel("pinion diameter (mm)")
    ax.set_title(title or "contact pattern on the pinion flank")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    out = save_figure(fig, path, dpi=130, tight=True)
    plt.close(fig)
    return out
