"""Figure of a tooth's bending deflection over its loaded flank (``gearcontact bending``)."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (backend must be chosen first)
import numpy as np  # noqa: E402

from ..geometry.cylindrical.pair import CylindricalPair  # noqa: E402
from .cylindrical_tooth import cylindrical_tooth_shell  # noqa: E402
from .shell import ORDER, ORDER_FACE, tooth_shell  # noqa: E402

__all__ = ["plot_deflection"]


def plot_deflection(result, path, *, pair, flanks, order: int = ORDER,
                    order_face: int = ORDER_FACE) -> Path:
    """Left: shell deflection (um per kN) over the loaded flank (face position v, height
    u, mm) under a unit normal load at the lattice point nearest the flank centre;
    right: deflection under the segment loads around the lattice points and the line
    loads, shell and (if solved) FE."""
    member = result.member
    if isinstance(pair, CylindricalPair):       # its shell needs no flank set
        shell = cylindrical_tooth_shell(pair, member, order=order, order_face=order_face)
    else:
        material = pair.pinion_material if member == "pinion" else pair.gear_material
        shell = tooth_shell(flanks, member, material=material, order=order,
                            order_face=order_face)
    tooth = shell.body
    k = int(np.argmin(result.xi ** 2 + result.eta ** 2))
    XI, ETA = np.meshgrid(np.linspace(-1, 1, 61), np.linspace(-1, 1, 25), indexing="ij")
    field = tooth.points_at(result.side, XI.ravel(), ETA.ravel())
    load = tooth.points_at(result.side, result.xi[k:k + 1], result.eta[k:k + 1])
    defl = shell.cross_compliance(field, load)[:, 0].reshape(XI.shape) * 1e6  # mm/N -> um/kN
    U, V = tooth.flank_parameters(result.side, XI, ETA)
    u_pts, v_pts = tooth.flank_parameters(result.side, result.xi, result.eta)
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11, 4.2),
                                  gridspec_kw={"width_ratios": [3, 2]})
    mesh = ax.pcolormesh(V, U, defl, shading="gouraud", cmap="viridis")
    fig.colorbar(mesh, ax=ax, label="deflection (um per kN)")
    ax.plot(v_pts, u_pts, "w.", ms=6)
    ax.plot(v_pts[k], u_pts[k], "r*", ms=12, label="unit load")
    ax.set_xlabel("v, face position (mm)")
    ax.set_ylabel("u, height above root (mm)")
    ax.set_title(f"{pair.name} {member} {result.side} flank: shell (orders {shell.order} / "
                 f"{shell.order_face})")
    ax.legend(loc="upper right", fontsize=8)
    n_seg = len(result.xi)
    idx = np.arange(n_seg + len(result.line_eta))
    labels = [f"seg {k}" for k in range(n_seg)] + [f"line eta={e:+.2f}" for e in result.line_eta]
    shell_vals = np.concatenate([result.segment_shell_mm_per_n, result.line_shell_mm_per_n])
    ax2.plot(idx, shell_vals * 1e6, "C0o", label="shell")
    if result.segment_fe_mm_per_n is not None:
        fe_vals = np.concatenate([result.segment_fe_mm_per_n, result.line_fe_mm_per_n])
        ax2.plot(idx, fe_vals * 1e6, "C1s", label=f"3D FE P2 ({result.fe_nodes} nodes)")
    ax2.set_xticks(idx, labels, rotation=60, fontsize=7)
    ax2.set_ylabel("deflection (um per kN)")
    ax2.set_title("distributed loads: segments around the points, lines over the face",
                  fontsize=9)
    ax2.legend(fontsize=8)
    fig.tight_layout()
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
