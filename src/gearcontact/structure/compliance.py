"""Flank compliance tables of one tooth: shell Rayleigh-Ritz beside 3D finite elements.

:func:`flank_compliance` evaluates the bending compliance of one tooth of a pair at a
lattice of points of its loaded flank, drive or coast (on the node lines of the FE
mesh, so that the shell and the FE see the same points) with the shell model of
:mod:`.shell` and, optionally, the FE model of :mod:`.fe`; :func:`write_compliance`
writes ``compliance.json`` and the figure of the deflection over the flank
(``gearcontact bending``).

Two kinds of numbers:

- point compliances between the lattice points (``shell_mm_per_n``, ``fe_mm_per_n``).
  Under a point load neither model has a converged local value: the Mindlin plate's
  deflection is logarithmically singular (it grows with the Ritz order) and the 3D
  solid's is 1/r singular (it grows as the mesh is refined) - the local part is the
  half-space's in the LTCA. They are reported, not compared;
- distributed loads, which both models resolve and which is what the LTCA applies:
  a *segment* load (unit total load spread evenly over 5 neighbouring node columns
  along the face, 4.3 mm on the pinion and 2.6 mm on the gear at the default mesh)
  around each lattice point, and a *line* load over the whole face at each lattice
  height. The compared deflection is the mean deflection of the coast-flank points
  behind the loaded ones (the bending deflection without the local indentation under
  the discrete nodal loads; the back flank is the other side's). These are checked
  against the FE (``docs/bending.md``).
"""

from __future__ import annotations

import json
import warnings
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from ..geometry.flank import FlankSet, build_flanks
from ..geometry.settings_check import checked_settings
from ..validation import InputRangeError
from .rim import RimSegment
from .shell import ORDER, ORDER_FACE, ShellModel, tooth_shell
from .tooth import LoadPoints

__all__ = ["FlankCompliance", "FeMesh", "EllipseRootWarning", "flank_compliance",
           "check_member_and_root", "compare_on_root", "shell_compliance",
           "write_compliance", "concat_points", "SEGMENT_NODES"]

#: Node columns of a segment load.
SEGMENT_NODES = 5


class EllipseRootWarning(UserWarning):
    """The FE of :func:`flank_compliance` meshes the quarter-ellipse root instead of the
    tooth's real root (no cutter for the member, or a real root the FE cannot mesh)."""


@dataclass(frozen=True)
class FeMesh:
    """Cells of the FE mesh (:func:`~.fe.build_fe`): face, height, thickness, rim; with a
    real root (:mod:`.root_fillet`) also the fillet zone's layers and each slot bottom's
    cells across."""

    n_xi: int = 12
    n_eta: int = 6
    n_zeta: int = 3
    n_rim: int = 4
    n_fillet: int = 3
    n_slot: int = 2


@dataclass(frozen=True)
class FlankCompliance:
    """Compliance of one tooth at a lattice of points of its loaded flank, mm/N.

    Attributes
    ----------
    member : str
    side : str
        The loaded flank, "drive" or "coast".
    xi, eta : ndarray (n,)
        Tooth coordinates of the lattice points.
    points_mm : ndarray (n, 3)
        Lattice points on the loaded flank, body frame, mm.
    shell_mm_per_n : ndarray (n, n)
        Shell point compliance between the lattice points (along the inward normal).
    segment_shell_mm_per_n : ndarray (n,)
        Shell deflection under a segment load around each lattice point.
    line_eta : ndarray (k,)
        Heights of the line loads (the lattice heights).
    line_shell_mm_per_n : ndarray (k,)
        Shell deflection under a line load over the face at each height.
    fe_mm_per_n, segment_fe_mm_per_n, line_fe_mm_per_n : ndarray or None
        The same from the FE model (None without FE).
    fe_nodes : int or None
        Nodes of the P2 FE mesh.
    fe_build_s : float or None
        FE meshing + assembly + factorization time, s.
    fe_root : str or None
        The root the FE meshed: "cutter" (the real root, :mod:`.root_fillet`) or
        "ellipse" (:mod:`.rim`); None without FE.
    fe_root_note : str or None
        Why the FE meshed the ellipse root where the real one was asked for (else None).
    """

    member: str
    side: str
    xi: np.ndarray
    eta: np.ndarray
    points_mm: np.ndarray
    shell_mm_per_n: np.ndarray
    segment_shell_mm_per_n: np.ndarray
    line_eta: np.ndarray
    line_shell_mm_per_n: np.ndarray
    fe_mm_per_n: np.ndarray | None = None
    segment_fe_mm_per_n: np.ndarray | None = None
    line_fe_mm_per_n: np.ndarray | None = None
    fe_nodes: int | None = None
    fe_build_s: float | None = None
    fe_root: str | None = None
    fe_root_note: str | None = None

    def ratios(self) -> np.ndarray:
        """Shell / FE for all segment and line loads (NaN-free; needs the FE)."""
        return np.concatenate([self.segment_shell_mm_per_n / self.segment_fe_mm_per_n,
                               self.line_shell_mm_per_n / self.line_fe_mm_per_n])

    def summary(self) -> dict:
        """JSON-ready dict (keys of ``compliance.json``)."""
        out = {"member": self.member, "side": self.side, "xi": self.xi.tolist(),
               "eta": self.eta.tolist(),
               "points_mm": self.points_mm.tolist(),
               "shell_mm_per_n": self.shell_mm_per_n.tolist(),
               "segment_shell_mm_per_n": self.segment_shell_mm_per_n.tolist(),
               "line_eta": self.line_eta.tolist(),
               "line_shell_mm_per_n": self.line_shell_mm_per_n.tolist()}
        if self.fe_mm_per_n is not None:
            out.update(fe_mm_per_n=self.fe_mm_per_n.tolist(),
                       segment_fe_mm_per_n=self.segment_fe_mm_per_n.tolist(),
                       line_fe_mm_per_n=self.line_fe_mm_per_n.tolist(),
                       fe_nodes=self.fe_nodes, fe_root=self.fe_root,
                       fe_root_note=self.fe_root_note,
                       ratio_shell_to_fe=self.ratios().tolist())
        return out


def concat_points(a: LoadPoints, b: LoadPoints) -> LoadPoints:
    """The points of ``a`` followed by those of ``b``."""
    return LoadPoints(*(np.concatenate([getattr(a, f), getattr(b, f)])
                        for f in ("xi", "eta", "direction", "offset_mm", "position_mm")))


def _load_sets(i_xi: np.ndarray, j_eta: np.ndarray, n_xi: int):
    """Node (xi-level, eta-level) index pairs of all loads and, per load, the positions
    of its nodes in that list: segments around each lattice point, then one line per
    lattice height (interior xi levels 1 .. n_xi - 1)."""
    interior = np.arange(1, n_xi)
    half = SEGMENT_NODES // 2
    loads = []
    for i, j in zip(i_xi, j_eta):
        c = int(np.clip(i, 1 + half, n_xi - 1 - half))
        cols = interior[(interior >= c - half) & (interior <= c + half)]
        loads.append([(int(a), int(j)) for a in cols])
    heights = np.unique(j_eta)
    for j in heights:
        loads.append([(int(a), int(j)) for a in interior])
    nodes = sorted({n for load in loads for n in load})
    where = {n: k for k, n in enumerate(nodes)}
    return np.array(nodes), [np.array([where[n] for n in load]) for load in loads], heights


def _distributed(G: np.ndarray, sets) -> np.ndarray:
    """Mean back-flank deflection under a unit load spread over each node set of the
    loaded flank: ``G`` holds the loaded-flank nodes then the back-flank nodes
    (directions into the tooth, so the back deflection along the load is the
    negative)."""
    n = G.shape[0] // 2
    return np.array([-np.mean(G[n:, :n][np.ix_(s, s)]) for s in sets])


def _check_lattice(side, xi, eta, fe_mesh: FeMesh):
    """The lattice (xi, eta) as flat arrays, after checking it, the side and the mesh."""
    if side not in ("drive", "coast"):
        raise InputRangeError("side", side, "'drive' or 'coast'")
    xi, eta = (np.asarray(a, float).ravel() for a in (xi, eta))
    for name, a in (("xi", xi), ("eta", eta)):
        if a.size == 0 or np.any(np.abs(a) > 1.0) or not np.all(np.isfinite(a)):
            raise InputRangeError(name, a.tolist(), "a non-empty list of values in [-1, 1]")
    if fe_mesh.n_xi < SEGMENT_NODES + 1:
        raise InputRangeError("fe_mesh.n_xi", fe_mesh.n_xi, f">= {SEGMENT_NODES + 1}")
    return xi, eta


def flank_compliance(pair, member: str, *, side: str = "drive",
                     flanks: FlankSet | None = None,
                     xi=(-0.5, 0.0, 0.5), eta=(-1 / 3, 0.0, 1 / 3), order: int = ORDER,
                     order_face: int = ORDER_FACE, rim: RimSegment | None = None,
                     fe: bool = False, fe_mesh: FeMesh = FeMesh(),
                     fe_root: str = "cutter") -> FlankCompliance:
    """Compliance of one tooth of ``member`` at the lattice ``xi x eta`` of its flank
    ``side`` (loaded there, normal into the tooth).

    The lattice values are snapped to the nearest node lines of the FE mesh
    (``fe_mesh``, also without ``fe``) so that shell and FE see the same points.

    Parameters
    ----------
    pair : GearPair
    member : str
        "pinion" or "gear".
    side : str
        The loaded flank, "drive" or "coast" (a pair's ``design_side`` is the one its
        contact uses).
    flanks : FlankSet or None
        The pair's flanks (a prepared pair's,
        :class:`~gearcontact.tca.synthesis.PreparedPair`); when None built here, after the pair's typed machine settings are checked
        against its blank (:func:`~gearcontact.geometry.settings_check.checked_settings`:
        a gross slip raises naming its key).
    xi, eta : sequence of float
        Tooth coordinates in [-1, 1] (face toe -> heel, height root -> tip).
    order, order_face : int
        Ritz orders of the shell over the height and along the face
        (:func:`~.shell.build_shell`).
    rim : RimSegment or None
        Fillet and rim of the shell (default: the member's calibrated one,
        :func:`~.shell.tooth_shell`); the FE meshes the same depth and fillet.
    fe : bool
        Also solve the 3D FE model (needs the ``fe`` extra).
    fe_mesh : FeMesh
    fe_root : str
        The FE's root below the tooth: ``"cutter"`` (default), the real root the
        member's cutter leaves (:mod:`.root_fillet`; the conjugate pinion's from the
        generating tool that cuts it, :func:`~gearcontact.geometry.fillet.pair_fillets`;
        the shell's calibration, ``docs/bending.md`` sec. 10), or ``"ellipse"``, the
        quarter-ellipse fillet and rim of :mod:`.rim` (sec. 3); a slot whose fillets
        cross above the root cone (the s0003 pinion's toe) closes in a V at their
        crossing (:meth:`~.root_fillet.FilletRoot.crossing`). Where the real root
        cannot be built (no fillet for the member, a slot closing above its fillets)
        the FE meshes the ellipse root, warns
        (:class:`EllipseRootWarning`) and says why in the result (``fe_root_note``).
    """
    check_member_and_root(member, fe_root)
    _check_lattice(side, xi, eta, fe_mesh)      # before the flanks and the shell
    if flanks is None:      # built here: the pair's typed settings checked first
        checked_settings(pair, stacklevel=2)
        flanks = build_flanks(pair)
    material = pair.pinion_material if member == "pinion" else pair.gear_material
    shell = tooth_shell(flanks, member, material=material, order=order,
                        order_face=order_face, rim=rim)
    return compare_on_root(shell, lambda: _cutter_fillets(pair, flanks, member), name=pair.name,
                           side=side, xi=xi, eta=eta, fe=fe, fe_mesh=fe_mesh,
                           fe_root=fe_root)


def check_member_and_root(member: str, fe_root: str) -> None:
    """Raise InputRangeError unless ``member`` is "pinion" | "gear" and ``fe_root``
    "cutter" | "ellipse" (:func:`flank_compliance`)."""
    if member not in ("pinion", "gear"):
        raise InputRangeError("member", member, "'pinion' or 'gear'")
    if fe_root not in ("ellipse", "cutter"):
        raise InputRangeError("fe_root", fe_root, "'ellipse' or 'cutter'")


def _cutter_fillets(pair, flanks, member: str):
    """``(fillets, None)`` of ``member``'s cutter (:func:`flank_compliance`), or ``(None,
    why)`` where the pair names none."""
    from ..geometry.fillet import pair_fillets

    fillets, why = pair_fillets(pair, flanks, conjugate_pinion=True)
    for key, reason in why.items():
        if key[0] == member:
            return None, f"no {key[1]} root fillet: {reason}"
    return fillets, None


def compare_on_root(shell: ShellModel, fillets, *, name: str, side: str, xi, eta, fe: bool,
                    fe_mesh: FeMesh, fe_root: str) -> FlankCompliance:
    """:func:`shell_compliance` of ``shell`` with the FE on the root ``fe_root`` names:
    with "cutter" the real root of the fillets ``fillets()`` gives (``(fillets, None)``,
    or ``(None, why)`` where there are none; called only when the FE runs), falling back
    to the ellipse root with an :class:`EllipseRootWarning` where it cannot be built or
    meshed (the result's ``fe_root_note`` says why). One path for bevel members
    (:func:`flank_compliance`) and cylindrical teeth
    (:func:`~.cylindrical_tooth.cylindrical_flank_compliance`)."""
    root, note = None, None
    if fe and fe_root == "cutter":
        root, note = _real_root(shell, fillets, fe_mesh)
        if note is not None:
            warnings.warn(f"{name} {shell.body.member}: FE on the ellipse root, not the "
                          f"real root ({note})", EllipseRootWarning, stacklevel=3)
    res = shell_compliance(shell, side=side, xi=xi, eta=eta, fe=fe, fe_mesh=fe_mesh,
                           fe_root=root)
    return res if note is None else replace(res, fe_root_note=note)


def _real_root(shell: ShellModel, fillets, fe_mesh: FeMesh):
    """``(FilletRoot, None)`` of the shell's tooth for the FE mesh ``fe_mesh``, or
    ``(None, why)`` where it cannot be built (:func:`compare_on_root`)."""
    from .root_fillet import fillet_root

    got, why = fillets()
    if why is not None:
        return None, why
    root = fillet_root(shell.body, got, depth_mm=shell.rim.depth_mm)
    try:
        root.check_meshable(np.linspace(-1.0, 1.0, fe_mesh.n_xi + 1), fe_mesh.n_slot)
    except InputRangeError as exc:
        return None, str(exc)
    return root, None


def shell_compliance(shell: ShellModel, *, side: str = "drive", xi=(-0.5, 0.0, 0.5),
                     eta=(-1 / 3, 0.0, 1 / 3), fe: bool = False,
                     fe_mesh: FeMesh = FeMesh(), fe_root=None) -> FlankCompliance:
    """:func:`flank_compliance` of any tooth's shell model (its body, a
    :class:`~.tooth.ToothGeometry`, and its rim; the FE meshes the same rim, or with
    ``fe_root`` the tooth's real root, a :class:`~.root_fillet.FilletRoot`)."""
    xi, eta = _check_lattice(side, xi, eta, fe_mesh)
    back = "coast" if side == "drive" else "drive"
    xl = np.linspace(-1.0, 1.0, fe_mesh.n_xi + 1)
    el = np.linspace(-1.0, 1.0, fe_mesh.n_eta + 1)
    I, J = np.meshgrid(np.abs(xi[:, None] - xl).argmin(1), np.abs(eta[:, None] - el).argmin(1),
                       indexing="ij")
    I, J = I.ravel(), J.ravel()
    nodes, sets, heights = _load_sets(I, J, fe_mesh.n_xi)
    tooth = shell.body
    lattice = tooth.points_at(side, xl[I], el[J])
    nx, ny = xl[nodes[:, 0]], el[nodes[:, 1]]
    both = concat_points(tooth.points_at(side, nx, ny), tooth.points_at(back, nx, ny))
    Gs = shell.compliance(both).matrix()
    n = len(I)
    kw = dict(member=tooth.member, side=side, xi=xl[I], eta=el[J],
              points_mm=lattice.position_mm,
              shell_mm_per_n=shell.compliance(lattice).matrix(),
              segment_shell_mm_per_n=_distributed(Gs, sets[:n]), line_eta=el[heights],
              line_shell_mm_per_n=_distributed(Gs, sets[n:]))
    if fe:
        from .fe import build_fe

        model = build_fe(tooth, n_xi=fe_mesh.n_xi, n_eta=fe_mesh.n_eta,
                         n_zeta=fe_mesh.n_zeta, n_rim=fe_mesh.n_rim,
                         rim_depth_mm=shell.rim.depth_mm, fillet_mm=shell.rim.fillet_mm,
                         root=fe_root, n_fillet=fe_mesh.n_fillet, n_slot=fe_mesh.n_slot)
        pd, vd = model.node_points(side, nx, ny)
        pc, vc = model.node_points(back, nx, ny)
        G = model.compliance(concat_points(pd, pc), np.concatenate([vd, vc]))
        pl, vl = model.node_points(side, xl[I], el[J])
        kw.update(fe_mm_per_n=model.compliance(pl, vl),
                  segment_fe_mm_per_n=_distributed(G, sets[:n]),
                  line_fe_mm_per_n=_distributed(G, sets[n:]),
                  fe_nodes=model.n_nodes, fe_build_s=model.build_s,
                  fe_root="ellipse" if fe_root is None else "cutter")
    return FlankCompliance(**kw)


def write_compliance(result: FlankCompliance, out, *, pair, flanks: FlankSet | None,
                     figures: bool = True, order: int = ORDER,
                     order_face: int = ORDER_FACE
                     ) -> list[Path]:
    """Write ``compliance.json`` and ``deflection.png`` into ``out`` (created);
    ``flanks``: a bevel pair's flank set (None for a cylindrical pair)."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "compliance.json"
    path.write_text(json.dumps(result.summary(), indent=1))
    written = [path]
    if figures:
        from .plots import plot_deflection

        written.append(plot_deflection(result, out / "deflection.png", pair=pair,
                                       flanks=flanks, order=order, order_face=order_face))
    return written
