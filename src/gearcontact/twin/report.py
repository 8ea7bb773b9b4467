"""Twin outputs: ``twin.json`` (summary), ``twin.csv`` (time series), ``mesh.csv`` (the
loaded side's mesh table: per phase and pair the mode that found its opening) and the
figures.

``twin.png``: mesh load, dynamic TE, contact-ellipse semi-axes ``a, b`` and ``p_max``
of the most loaded pair over time; ``twin_spectrum.png``: amplitude spectrum of the
dynamic TE after the transient with the mesh orders (multiples of the mesh frequency)
and the linearised natural frequencies marked.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from ..figure_files import pyplot
from ..tca.export import write_csv
from .mesh import CONTACT_MODES

__all__ = ["write_twin_outputs", "write_sweep_outputs", "write_mesh_csv", "plot_time",
           "plot_spectrum", "plot_sweep", "CSV_COLUMNS", "MESH_COLUMNS"]

#: Columns of ``twin.csv`` (time series keys of :class:`~.simulate.TwinResult`).
CSV_COLUMNS = ("t_s", "te_arcsec", "theta_rad", "mesh_torque_nm", "mesh_load_n", "a_mm",
               "b_mm", "p_max_mpa", "pairs_loaded", "pinion_speed_rad_s", "gear_speed_rad_s",
               "kinetic_j", "shaft_energy_j", "mesh_energy_j", "dissipated_j",
               "input_work_j")

#: Columns of ``mesh.csv`` (:func:`write_mesh_csv`).
MESH_COLUMNS = ("row", "psi_rad", "phi1_rad", "te0_arcsec", "pair", "mode", "edge",
                "lever_mm", "opening_um", "A_minus_per_mm", "B_minus_per_mm",
                "compliance_scale")


def write_mesh_csv(mesh, path) -> Path:
    """``mesh.csv``: one line per valid row of ``mesh`` (a :class:`~.mesh.MeshTable`
    with contact modes), phase by phase along the motion: ``pair`` the offset ``j``,
    ``mode`` one of :data:`~.mesh.CONTACT_MODES` (which mode found the opening; an
    ``edge`` row names its ``edge`` and carries the nearest surface contact's
    curvatures, docs/twin.md "Edge contact"), ``opening_um`` the initial separation,
    ``compliance_scale`` the row's LCP compliance scale ``c`` (:mod:`gearcontact.ltca.edge_law`; its
    A-, B- are the equivalent curvatures, ``c^3`` times the Hertzian ones; 1 for a row
    no flank boundary cuts)."""
    n_p = mesh.valid.shape[0]
    scale = (np.ones(mesh.valid.shape) if mesh.edge_compliance_scale is None
             else mesh.edge_compliance_scale)
    rows = [[k, float(mesh.psi_rad[k]), float(mesh.phi1_rad[k]), float(mesh.te0_arcsec[k]),
             i - (n_p - 1) // 2, CONTACT_MODES[mesh.contact_mode[i, k]], mesh.edge_label[i, k],
             float(mesh.lever_mm[i, k]), 1e3 * float(mesh.opening_mm[i, k]),
             float(mesh.A_minus_per_mm[i, k]), float(mesh.B_minus_per_mm[i, k]),
             float(scale[i, k])]
            for k in range(mesh.valid.shape[1]) for i in range(n_p) if mesh.valid[i, k]]
    path = Path(path)
    write_csv(path, list(MESH_COLUMNS), rows)
    return path


def _save(fig, axes, path) -> Path:
    """Grid every axis, lay out, write the PNG and close the figure."""
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.tight_layout()
    path = Path(path)
    fig.savefig(path, dpi=110)
    pyplot().close(fig)
    return path


def plot_time(result, path, *, title: str = "") -> Path:
    """Four panels over time (ms): mesh load (N), dynamic TE (arcsec), a and b (mm),
    p_max (MPa)."""
    c, s = result.columns, result.summary
    t = 1e3 * c["t_s"]
    fig, axes = pyplot().subplots(4, 1, figsize=(8, 9), sharex=True)
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
    return _save(fig, axes, path)


def plot_spectrum(result, path, *, settle_fraction: float = 0.5, title: str = "") -> Path:
    """Amplitude spectrum of the dynamic TE after the transient (Hann window), mesh
    orders and natural frequencies marked."""
    plt = pyplot()
    c, s = result.columns, result.summary
    sel = c["t_s"] >= settle_fraction * s["duration_s"]
    te = c["te_arcsec"][sel]
    if te.size < 16:        # a few steps (lockstep runs): no spectrum to speak of
        fig, ax = plt.subplots(figsize=(8, 4))
        ax.text(0.5, 0.5, f"{te.size} samples after the transient: too short a run for a "
                "spectrum", ha="center", va="center", transform=ax.transAxes)
        ax.set_axis_off()
        ax.set_title(f"{title} dynamic TE spectrum ({s['backend']})", fontsize=10)
        return _save(fig, [ax], path)
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
    return _save(fig, [ax], path)


def write_twin_outputs(result, out, *, figures: bool = True, title: str = "",
                       extra: dict | None = None, mesh=None) -> dict:
    """Write ``twin.json``, ``twin.csv``, ``mesh.csv`` (``mesh``: the loaded side's
    :class:`~.mesh.MeshTable`, if it has contact modes) and (``figures``) ``twin.png``,
    ``twin_spectrum.png`` into ``out``; returns the JSON dict (``extra`` merged in)."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    summary = dict(result.summary)
    summary.update(extra or {})
    (out / "twin.json").write_text(json.dumps(summary, indent=2))
    cols = result.columns
    rows = np.column_stack([cols[k] for k in CSV_COLUMNS]).tolist()
    write_csv(out / "twin.csv", list(CSV_COLUMNS), rows)
    if mesh is not None and mesh.contact_mode is not None:
        write_mesh_csv(mesh, out / "mesh.csv")
    if figures:
        plot_time(result, out / "twin.png", title=title)
        plot_spectrum(result, out / "twin_spectrum.png", title=title)
    return summary


def plot_sweep(sweep, path, *, title: str = "") -> Path:
    """Dynamic factor and DTE p-p vs pinion speed for every model, the resonance speeds
    ``60 f_n / (k z1)`` (mesh orders k = 1..6, labelled) marked."""
    fig, (ax, ax2) = pyplot().subplots(2, 1, figsize=(8, 7), sharex=True)
    v = sweep.speeds_rpm
    for i, (label, rows) in enumerate(sweep.rows.items()):
        ax.plot(v, rows["dynamic_factor"], f"C{i}.-", ms=3, label=f"{label} twin")
        ax2.plot(v, rows["dte_pp_arcsec"], f"C{i}.-", ms=3, label=f"{label} twin")
    first = True
    for (k, fn), n in sweep.resonance_speeds_rpm(orders=range(1, 7)).items():
        if v[0] <= n <= v[-1]:
            for a in (ax, ax2):
                a.axvline(n, color="gray", ls="--", lw=0.7,
                          label="k f_z = f_n" if (first and a is ax) else None)
            ax.annotate(f"k={k}", (n, 0.98), xycoords=("data", "axes fraction"),
                        ha="left", va="top", fontsize=7, color="gray")
            first = False
    ax.set_ylabel("dynamic factor (max / static mesh torque)")
    ax2.set_ylabel("DTE peak-to-peak (arcsec)")
    ax2.set_xlabel("pinion speed (rpm)")
    ax.set_title(f"{title} speed sweep; modes "
                 + ", ".join(f"{f:.0f}" for f in sweep.natural_frequencies_hz) + " Hz",
                 fontsize=10)
    ax.legend(fontsize=8)
    ax2.legend(fontsize=8)
    return _save(fig, [ax, ax2], path)


def write_sweep_outputs(sweep, out, *, figures: bool = True, title: str = "",
                        extra: dict | None = None) -> dict:
    """Write ``sweep.json`` (per model: speed of the largest dynamic factor and its value,
    resonance speeds), ``sweep.csv`` (one row per speed) and ``sweep.png``."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    summary = {"speeds_rpm": [float(sweep.speeds_rpm[0]), float(sweep.speeds_rpm[-1]),
                              len(sweep.speeds_rpm)],
               "natural_frequencies_hz": [float(f) for f in sweep.natural_frequencies_hz],
               "resonance_speeds_rpm": [{"order": k, "mode_hz": fn, "speed_rpm": n}
                                        for (k, fn), n in sweep.resonance_speeds_rpm().items()]}
    for label, rows in sweep.rows.items():
        i = int(np.argmax(rows["dynamic_factor"]))
        summary[label] = {"max_dynamic_factor": float(rows["dynamic_factor"][i]),
                          "at_speed_rpm": float(sweep.speeds_rpm[i]),
                          "max_contact_loss": float(rows["contact_loss"].max())}
    summary.update(extra or {})
    (out / "sweep.json").write_text(json.dumps(summary, indent=2))
    header = ["speed_rpm"] + [f"{label}_{k}" for label in sweep.rows
                              for k in ("dynamic_factor", "dte_pp_arcsec", "contact_loss")]
    rows = [[float(v)] + [float(sweep.rows[label][k][i]) for label in sweep.rows
                          for k in ("dynamic_factor", "dte_pp_arcsec", "contact_loss")]
            for i, v in enumerate(sweep.speeds_rpm)]
    write_csv(out / "sweep.csv", header, rows)
    if figures:
        plot_sweep(sweep, out / "sweep.png", title=title)
    return summary
