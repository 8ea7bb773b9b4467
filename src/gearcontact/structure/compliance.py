"""Flank compliance tables of one tooth: shell Rayleigh-Ritz beside 3D finite elements.

:func:`flank_compliance` evaluates the bending compliance matrix of one tooth of a pair
at a lattice of drive-flank points (the node lines of the FE mesh, so that the shell
and the FE see the same points) with the shell model of :mod:`.shell` and, optionally,
the FE model of :mod:`.fe`; :func:`write_compliance` writes ``compliance.json`` and the
figure of the deflection over the flank (``gearcontact bending``).

Besides the full matrices, the table carries the *through-thickness* compliance of each
point: the deflection of the coast-flank point behind it under a unit normal load on
the drive flank. That is the bending deflection under the load without the local
indentation at the loaded point (which is singular for a point load in 3D and is the
half-space part of the LTCA), so it is the quantity the shell is checked on against the
FE (``docs/bending.md``).
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..geometry.flank import FlankSet, build_flanks
from ..validation import InputRangeError
from .shell import RootFoundation, tooth_shell
from .tooth import LoadPoints

__all__ = ["FlankCompliance", "FeMesh", "flank_compliance", "write_compliance",
           "concat_points"]


@dataclass(frozen=True)
class FeMesh:
    """Cells of the FE mesh (:func:`~.fe.build_fe`): face, height, thickness, rim."""

    n_xi: int = 12
    n_eta: int = 6
    n_zeta: int = 3
    n_rim: int = 4


@dataclass(frozen=True)
class FlankCompliance:
    """Compliance of one tooth at a lattice of drive-flank points, mm/N.

    Attributes
    ----------
    member : str
    xi, eta : ndarray (n,)
        Tooth coordinates of the points.
    points_mm : ndarray (n, 3)
        Drive-flank points, body frame, mm.
    shell_mm_per_n : ndarray (n, n)
        Shell compliance between the points (deflection along the inward normal).
    shell_through_mm_per_n : ndarray (n,)
        Shell deflection of the coast point behind each point (along the drive load).
    fe_mm_per_n, fe_through_mm_per_n : ndarray or None
        The same from the FE model (None without FE).
    fe_nodes : int or None
        Nodes of the P2 FE mesh.
    fe_build_s : float or None
        FE meshing + assembly + factorization time, s.
    """

    member: str
    xi: np.ndarray
    eta: np.ndarray
    points_mm: np.ndarray
    shell_mm_per_n: np.ndarray
    shell_through_mm_per_n: np.ndarray
    fe_mm_per_n: np.ndarray | None = None
    fe_through_mm_per_n: np.ndarray | None = None
    fe_nodes: int | None = None
    fe_build_s: float | None = None

    def summary(self) -> dict:
        """JSON-ready dict (keys of ``compliance.json``)."""
        out = {"member": self.member, "xi": self.xi.tolist(), "eta": self.eta.tolist(),
               "points_mm": self.points_mm.tolist(),
               "shell_mm_per_n": self.shell_mm_per_n.tolist(),
               "shell_through_mm_per_n": self.shell_through_mm_per_n.tolist()}
        if self.fe_mm_per_n is not None:
            ratio = self.shell_through_mm_per_n / self.fe_through_mm_per_n
            out.update(fe_mm_per_n=self.fe_mm_per_n.tolist(),
                       fe_through_mm_per_n=self.fe_through_mm_per_n.tolist(),
                       fe_nodes=self.fe_nodes, fe_build_s=self.fe_build_s,
                       through_ratio_shell_to_fe=ratio.tolist())
        return out


def concat_points(a: LoadPoints, b: LoadPoints) -> LoadPoints:
    """The points of ``a`` followed by those of ``b``."""
    return LoadPoints(*(np.concatenate([getattr(a, f), getattr(b, f)])
                        for f in ("xi", "eta", "direction", "offset_mm", "position_mm")))


def flank_compliance(pair, member: str, *, flanks: FlankSet | None = None,
                     xi=(-0.5, 0.0, 0.5), eta=(-0.5, 0.0, 0.5), order: int = 8,
                     foundation: RootFoundation | None = None, fe: bool = False,
                     fe_mesh: FeMesh = FeMesh()) -> FlankCompliance:
    """Compliance of one tooth of ``member`` at the drive-flank lattice ``xi x eta``.

    The lattice values are snapped to the nearest node lines of the FE mesh
    (``fe_mesh``, also without ``fe``) so that shell and FE see the same points.

    Parameters
    ----------
    pair : GearPair
    member : str
        "pinion" or "gear".
    flanks : FlankSet or None
        The pair's flanks (built when None).
    xi, eta : sequence of float
        Tooth coordinates in [-1, 1] (face toe -> heel, height root -> tip).
    order : int
        Ritz order of the shell (:func:`~.shell.build_shell`).
    foundation : RootFoundation or None
        Root / rim coefficients (default: the calibrated ones of the member).
    fe : bool
        Also solve the 3D FE model (needs the ``fe`` extra).
    fe_mesh : FeMesh
    """
    if member not in ("pinion", "gear"):
        raise InputRangeError("member", member, "'pinion' or 'gear'")
    xi, eta = (np.asarray(a, float).ravel() for a in (xi, eta))
    for name, a in (("xi", xi), ("eta", eta)):
        if a.size == 0 or np.any(np.abs(a) > 1.0) or not np.all(np.isfinite(a)):
            raise InputRangeError(name, a.tolist(), "a non-empty list of values in [-1, 1]")
    flanks = build_flanks(pair) if flanks is None else flanks
    material = pair.pinion_material if member == "pinion" else pair.gear_material
    xl = np.linspace(-1.0, 1.0, fe_mesh.n_xi + 1)
    el = np.linspace(-1.0, 1.0, fe_mesh.n_eta + 1)
    XI, ETA = np.meshgrid(xl[np.abs(xi[:, None] - xl).argmin(1)],
                          el[np.abs(eta[:, None] - el).argmin(1)], indexing="ij")
    XI, ETA = XI.ravel(), ETA.ravel()
    shell = tooth_shell(flanks, member, material=material, order=order, foundation=foundation)
    tooth = shell.body
    drive, coast = tooth.points_at("drive", XI, ETA), tooth.points_at("coast", XI, ETA)
    n = len(XI)
    both = concat_points(drive, coast)
    Gs = shell.compliance(both).matrix()
    # the coast deflection is measured along -n_coast (into the tooth), opposite to the
    # drive load's sense: the through-thickness value is its negative
    kw = dict(member=member, xi=XI, eta=ETA, points_mm=drive.position_mm,
              shell_mm_per_n=Gs[:n, :n], shell_through_mm_per_n=-np.diag(Gs[n:, :n]))
    if fe:
        from .fe import build_fe

        model = build_fe(tooth, n_xi=fe_mesh.n_xi, n_eta=fe_mesh.n_eta, n_zeta=fe_mesh.n_zeta,
                         n_rim=fe_mesh.n_rim)
        pd, vd = model.node_points("drive", XI, ETA)
        pc, vc = model.node_points("coast", XI, ETA)
        G = model.compliance(concat_points(pd, pc), np.concatenate([vd, vc]))
        kw.update(fe_mm_per_n=G[:n, :n], fe_through_mm_per_n=-np.diag(G[n:, :n]),
                  fe_nodes=model.n_nodes, fe_build_s=model.build_s)
    return FlankCompliance(**kw)


def write_compliance(result: FlankCompliance, out, *, pair, flanks: FlankSet,
                     figures: bool = True, order: int = 8) -> list[Path]:
    """Write ``compliance.json`` and ``deflection.png`` into ``out`` (created)."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "compliance.json"
    path.write_text(json.dumps(result.summary(), indent=1))
    written = [path]
    if figures:
        from .plots import plot_deflection

        written.append(plot_deflection(result, out / "deflection.png", pair=pair,
                                       flanks=flanks, order=order))
    return written
