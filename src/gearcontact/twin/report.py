"""Twin outputs: ``twin.json`` (summary), ``twin.csv`` (time series) and the figures.

``twin.png``: mesh load, dynamic TE, contact-ellipse semi-axes ``a, b`` and ``p_max``
of the most loaded pair over time; ``twin_spectrum.png``: amplitude spectrum of the
dynamic TE after the transient with the mesh orders (multiples of the mesh frequency)
and the linearised natural frequencies marked.
"""

from __future__ import annotations

import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (backend must be chosen first)
import numpy as np  # noqa: E402

from ..tca.export import write_csv  # noqa: E402

__all__ = ["write_twin_outputs", "plot_time", "plot_spectrum", "CSV_COLUMNS"]

#: Columns of ``twin.csv`` (time series keys of :class:`~.simulate.TwinResult`).
CSV_COLUMNS = ("t_s", "te_arcsec", "theta_rad", "mesh_torque_nm", "mesh_load_n", "a_mm",
               "b_mm", "p_max_mpa", "pairs_loaded", "pinion_speed_rad_s", "gear_speed_rad_s",
               "kinetic_j", "shaft_energy_j", "mesh_energy_j", "dissipated_j",
               "input_work_j")


def plot_time(result, path, *, title: str = "") -> Path:
    """Four panels over time (ms): mesh load (N), dynamic TE (arcsec), a and b (mm),
    p_max (MPa)."""
    c, s = result.columns, result.summary
    t = 1e3 * c["t_s"]
    fig, axes = plt.subplots(4, 1, figsize=(8, 9), sharex=True)
    axes[0].plot(t, c["mesh_load_n"], lw=0.8)
    axes[0].axhline(s["static_mesh_load_n"], color="k", ls=":", lw=1, label="static")
    axes[0].set_ylabel("mesh load (N)")
    axes[0].legend(fontsize=8)
    axes[1].plot(t, c["te_arcsec"], lw=0.8, color="C1")
    axes[1].set_ylabel("dynamic TE (arcsec)")
    if s["backend"] != "table":
        axes[2].plot(t, c["a_mm"], lw=0.8, label="a")
        axes[2].plot(t, 10.0 * c["b_mm"], lw=0.8, label="10 b")
        axes[2].legend(fontsize=8)
        axes[3].plot(t, c["p_max_mpa"], lw=0.8, color="C3")
    else:
        for ax in axes[2:]:
            ax.text(0.5, 0.5, "table backend: no contact ellipse", ha="center",
                    transform=ax.transAxes)
    axes[2].set_ylabel("semi-axes (mm)")
    axes[3].set_ylabel("p_max (MPa)")
    axes[3].set_xlabel("time (ms)")
    axes[0].set_title(f"{title} {s['backend']}: {s['torque_nm']:g} N·m, {s['speed_rpm']:g} rpm,"
                      f" dynamic factor {s['dynamic_factor']:.3f}, contact loss "
                      f"{100 * s['contact_loss']:.1f} %", fontsize=10)
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.tight_layout()
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_spectrum(result, path, *, settle_fraction: float = 0.5, title: str = "") -> Path:
    """Amplitude spectrum of the dynamic TE after the transient (Hann window), mesh
    orders and natural frequencies marked."""
    c, s = result.columns, result.summary
    sel = c["t_s"] >= settle_fraction * s["duration_s"]
    te = c["te_arcsec"][sel]
    dt = float(np.median(np.diff(c["t_s"])))
    win = np.hanning(te.size)
    amp = 2.0 * np.abs(np.fft.rfft((te - te.mean()) * win)) / win.sum()
    freq = np.fft.rfftfreq(te.size, dt)
    fig, ax = plt.subplots(figsize=(8, 4))
    ax.semilogy(freq[1:], np.maximum(amp[1:], 1e-9), lw=0.8)
    fm = s["mesh_frequency_hz"]
    top = min(freq[-1], max(8 * fm, 1.2 * max(s["natural_frequencies_hz"])))
    if fm > 0:
        for order in range(1, int(top / fm) + 1):
            ax.axvline(order * fm, color="C1", ls=":", lw=0.8)
        ax.plot([], [], color="C1", ls=":", label=f"mesh orders ({fm:g} Hz)")
    for i, fn in enumerate(s["natural_frequencies_hz"][1:]):
        ax.axvline(fn, color="C2", ls="--", lw=0.8, label="linearised modes" if i == 0 else None)
    ax.set_xlim(0, top)
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel("TE amplitude (arcsec)")
    ax.set_title(f"{title} dynamic TE spectrum ({s['backend']})", fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def write_twin_outputs(result, out, *, figures: bool = True, title: str = "",
                       extra: dict | None = None) -> dict:
    """Write ``twin.json``, ``twin.csv`` and (``figures``) ``twin.png``,
    ``twin_spectrum.png`` into ``out``; returns the JSON dict (``extra`` merged in)."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    summary = dict(result.summary)
    summary.update(extra or {})
    (out / "twin.json").write_text(json.dumps(summary, indent=2))
    cols = result.columns
    rows = np.column_stack([cols[k] for k in CSV_COLUMNS]).tolist()
    write_csv(out / "twin.csv", list(CSV_COLUMNS), rows)
    if figures:
        plot_time(result, out / "twin.png", title=title)
        plot_spectrum(result, out / "twin_spectrum.png", title=title)
    return summary
