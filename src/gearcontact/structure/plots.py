"""Figure of a tooth's bending deflection over its drive flank (``gearcontact bending``)."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (backend must be chosen first)
import numpy as np  # noqa: E402

from .shell import tooth_shell  # noqa: E402

__all__ = ["plot_deflection"]


def plot_deflection(result, path, *, pair, flanks, order: int = 8) -> Path:
    """Left: shell deflection (um per kN) over the drive flank (face position v, height
    u, mm) under a unit normal load at the lattice point nearest the flank centre;
    right: through-thickness compliance of every lattice point, shell and (if solved)
    FE."""
    member = result.member
    material = pair.pinion_material if member == "pinion" else pair.gear_material
    shell = tooth_shell(flanks, member, material=material, order=order)
    tooth = shell.body
    k = int(np.argmin(result.xi ** 2 + result.eta ** 2))
    XI, ETA = np.meshgrid(np.linspace(-1, 1, 61), np.linspace(-1, 1, 25), indexing="ij")
    field = tooth.points_at("drive", XI.ravel(), ETA.ravel())
    load = tooth.points_at("drive", result.xi[k:k + 1], result.eta[k:k + 1])
    defl = shell.cross_compliance(field, load)[:, 0].reshape(XI.shape) * 1e6  # mm/N -> um/kN
    U, V = tooth.flank_parameters("drive", XI, ETA)
    u_pts, v_pts = tooth.flank_parameters("drive", result.xi, result.eta)
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11, 4.2),
                                  gridspec_kw={"width_ratios": [3, 2]})
    mesh = ax.pcolormesh(V, U, defl, shading="gouraud", cmap="viridis")
    fig.colorbar(mesh, ax=ax, label="deflection (um per kN)")
    ax.plot(v_pts, u_pts, "w.", ms=6)
    ax.plot(v_pts[k], u_pts[k], "r*", ms=12, label="unit load")
    ax.set_xlabel("v, face position (mm)")
    ax.set_ylabel("u, height above root (mm)")
    ax.set_title(f"{pair.name} {member} drive flank: shell (order {shell.order})")
    ax.legend(loc="upper right", fontsize=8)
    idx = np.arange(len(result.xi))
    ax2.plot(idx, result.shell_through_mm_per_n * 1e6, "C0o-", label="shell")
    if result.fe_through_mm_per_n is not None:
        ax2.plot(idx, result.fe_through_mm_per_n * 1e6, "C1s--",
                 label=f"3D FE P2 ({result.fe_nodes} nodes)")
    ax2.set_xlabel("lattice point (xi-major)")
    ax2.set_ylabel("through-thickness compliance (um per kN)")
    ax2.set_title("coast-side deflection under a drive-flank load")
    ax2.legend(fontsize=8)
    fig.tight_layout()
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
