"""Loaded-TE figure and files: TE0, TE_LCP, TE_pre and the active pairs along the phase.

:func:`write_lte_outputs` writes ``lte.json`` (:meth:`~gearcontact.ltca.lte.LoadedTE.
summary`), ``lte.csv`` (one row per phase) and ``lte.png`` (:func:`plot_lte`); used by
``gearcontact lte`` and the main job.
"""

from __future__ import annotations

import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (backend must be chosen first)
import numpy as np  # noqa: E402

from ..figure_files import save_figure  # noqa: E402
from ..tca.export import TIMING_KEYS, without_timings, write_csv  # noqa: E402

__all__ = ["plot_lte", "write_lte_outputs"]


def plot_lte(lte, path, *, title: str = "", published: dict | None = None) -> Path:
    """Two panels over the pinion phase (deg): top TE0, TE_LCP and TE_pre (arcsec, each
    relative to its own mean so that the peak-to-peaks compare), bottom the active pairs
    (LCP, preview) and the load share of each pair (LCP)."""
    phase = np.degrees(lte.phi1_rad - lte.phi1_rad[lte.reference_index])
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(10, 6.5), sharex=True,
                                  gridspec_kw={"height_ratios": [3, 2]})
    pub = (published or {}).get("lte_pp_arcsec", {})
    for te, label, style in (
            (lte.te0_arcsec, f"TE0 (p-p {lte.te0_pp_arcsec:.2f})", "k-"),
            (lte.te_lcp_arcsec, f"TE_LCP (p-p {lte.te_lcp_pp_arcsec:.2f}"
             + (f"; published {pub['lcp']})" if "lcp" in pub else ")"), "C0.-"),
            (lte.te_pre_arcsec, f"TE_pre (p-p {lte.te_pre_pp_arcsec:.2f}"
             + (f"; published {pub['preview']})" if "preview" in pub else ")"), "C1.--")):
        ax.plot(phase, te - te.mean(), style, label=label, ms=3)
    ax.set_ylabel("TE - mean (arcsec)")
    ax.set_title(f"{title} {lte.torque_nm:g} N·m: mean loaded rotation LCP "
                 f"{lte.rotation_lcp_arcsec.mean():.1f}, preview "
                 f"{lte.rotation_pre_arcsec.mean():.1f} arcsec", fontsize=10)
    # legends right of the axes: inside they cover the curves
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.12, 1.0))
    ax.grid(alpha=0.3)
    ax.tick_params(labelbottom=True)
    ax.set_xlabel("pinion phase from P0 (deg)")
    ax2.step(phase, lte.active_lcp, "C0-", where="mid", label="active pairs LCP")
    ax2.step(phase, lte.active_pre, "C1--", where="mid", label="active pairs preview")
    ax2.set_ylabel("active pairs")
    ax2.set_ylim(0, max(int(lte.active_lcp.max()), int(lte.active_pre.max())) + 1)
    share = ax2.twinx()
    total = lte.pair_loads_lcp_n.sum(axis=0)
    for row, off in enumerate(lte.pair_offsets):
        if lte.pair_loads_lcp_n[row].any():
            share.plot(phase, 100.0 * lte.pair_loads_lcp_n[row] / total, ":", lw=1,
                       label=f"pair {off:+d} share")
    share.set_ylabel("LCP load share (%)")
    share.set_ylim(0, 105)
    edge = np.flatnonzero(lte.edge_contact)
    if edge.size:
        ax2.plot(phase[edge], np.full(edge.size, 0.3), "rx", ms=4,
                 label="phase with edge contact (LCP)")
    lines = ax2.get_legend_handles_labels()
    lines2 = share.get_legend_handles_labels()
    ax2.legend(lines[0] + lines2[0], lines[1] + lines2[1], fontsize=7, loc="upper left",
               bbox_to_anchor=(1.12, 1.0))
    ax2.set_xlabel("pinion phase from P0 (deg)")
    fig.tight_layout()
    path = save_figure(fig, path, tight=True)
    plt.close(fig)
    return path


def write_lte_outputs(lte, out, *, figures: bool = True, title: str = "",
                      published: dict | None = None, extra: dict | None = None) -> dict:
    """Write ``lte.json``, ``lte.csv`` and (``figures``) ``lte.png`` into ``out``;
    returns the JSON dict (``extra`` keys added, e.g. the assembly errors used).
    Timings (:data:`~gearcontact.tca.export.TIMING_KEYS`) stay out of the files."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    summary, _ = without_timings(lte.summary())     # identical runs, identical files
    summary.update(extra or {})
    (out / "lte.json").write_text(json.dumps(summary, indent=2))
    header, rows = lte.table()
    keep = [i for i, h in enumerate(header) if h not in TIMING_KEYS]
    write_csv(out / "lte.csv", [header[i] for i in keep],
              [[row[i] for i in keep] for row in rows])
    if figures:
        plot_lte(lte, out / "lte.png", title=title, published=published)
    return summary
