"""Types, constants and errors of the unloaded TCA (mating points, paths, edge contact).

Shared by the mating-point solver (:mod:`.mating`), the edge-contact solver
(:mod:`.edge_contact`), the curvatures and stencils built on a mating point and the
path continuation (:mod:`.solve`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import CheckFailed

__all__ = ["ARCSEC_PER_RAD", "EDGE_TE_LIMIT_ARCSEC", "VARIABLES", "ContactGuess",
           "MatingPoint", "TcaPath", "EdgeContact", "TcaConvergenceError"]

ARCSEC_PER_RAD = 206264.80624709636
#: Default limit of a path's edge tails: an edge contact whose TE0 lies this far behind
#: the path's first touch ends the path (arcsec); the nominal s0003 meshes have TE0 p-p
#: of ~3 arcsec, and :func:`~gearcontact.tca.mesh.mesh_cycle` widens the limit when a
#: mesh's TE0 p-p exceeds half of it.
EDGE_TE_LIMIT_ARCSEC = 20.0
#: Order of the six contact variables in every vector of this module.
VARIABLES = ("u1", "v1", "u2", "v2", "phi1", "phi2")


class EdgeContact(Exception):
    """The mating point left a flank's parameter box (edge contact).

    Attributes
    ----------
    phi1_rad : float
        Pinion mesh phase at which the contact left the flank, rad.
    where : str
        The boundary, e.g. ``"pinion v max"``.
    """

    def __init__(self, phi1_rad: float, where: str):
        self.phi1_rad = float(phi1_rad)
        self.where = where
        super().__init__(f"edge contact at phi1 = {np.degrees(phi1_rad):.6f} deg: the "
                         f"mating point leaves the flank at the {where} boundary")


class TcaConvergenceError(CheckFailed):
    """Newton's method did not converge at a mesh phase (a failed check, exit 4, when it
    escapes a run).

    Attributes
    ----------
    phi1_rad : float
        Pinion mesh phase, rad.
    residual : float
        Final residual norm (mm for position, dimensionless for the normal part).
    """

    def __init__(self, phi1_rad: float, residual: float, iterations: int):
        self.phi1_rad = float(phi1_rad)
        self.residual = float(residual)
        super().__init__(f"TCA Newton solve did not converge at mesh phase phi1 = "
                         f"{np.degrees(phi1_rad):.6f} deg: residual {residual:.3e} after "
                         f"{iterations} iterations")


@dataclass(frozen=True)
class ContactGuess:
    """A (guessed or known) contact state: both parameter pairs and both rotations.

    Parameters are the flank parameters of pinion (``u1, v1``) and gear (``u2, v2``)
    and the rotations ``phi1_rad`` (pinion, about -x) and ``phi2_rad`` (gear, about +z).
    """

    u1: float
    v1: float
    u2: float
    v2: float
    phi1_rad: float
    phi2_rad: float

    def vector(self) -> np.ndarray:
        """The state as a (6,) array in the order of :data:`VARIABLES`."""
        return np.array([self.u1, self.v1, self.u2, self.v2, self.phi1_rad, self.phi2_rad])

    @classmethod
    def from_vector(cls, x) -> "ContactGuess":
        return cls(*(float(xi) for xi in x))


@dataclass(frozen=True)
class MatingPoint:
    """TCA result at one mesh phase.

    Attributes
    ----------
    phi1_rad, phi2_rad : float
        Pinion and gear rotations, rad.
    u1, v1, u2, v2 : float
        Flank parameters of the mating point on pinion and gear.
    point_mm : ndarray (3,)
        Mating point in the meshing frame, mm.
    normal : ndarray (3,)
        Common unit normal in the meshing frame: the gear's normal, out of the gear
        tooth (into the pinion tooth).
    te0_arcsec : float
        Unloaded transmission error relative to the path's reference point, arcsec.
    residual : float
        Final residual norm of the five equations.
    iterations : int
        Newton iterations used.
    edge : bool
        True if the pair has no contact at this phase: no interior mating point and no
        edge touching the other flank (:mod:`gearcontact.tca.edge_contact`); all
        geometric fields are then NaN and ``edge_where`` names the boundary crossed.
    edge_where : str
        Boundary crossed (``""`` for interior contact).
    edge_contact : str
        ``""`` for surface-to-surface contact; else the flank edge (``"pinion toe"``,
        ...) whose point ``(u, v)`` (on that member's boundary) touches the other
        flank's surface: an edge contact, with finite fields (``normal``: the touched
        surface's, oriented like every mating normal).
    """

    phi1_rad: float
    phi2_rad: float
    u1: float
    v1: float
    u2: float
    v2: float
    point_mm: np.ndarray
    normal: np.ndarray
    te0_arcsec: float = 0.0
    residual: float = 0.0
    iterations: int = 0
    edge: bool = False
    edge_where: str = ""
    edge_contact: str = ""

    def as_guess(self) -> ContactGuess:
        return ContactGuess(self.u1, self.v1, self.u2, self.v2, self.phi1_rad, self.phi2_rad)

    @classmethod
    def edge_phase(cls, phi1_rad: float, where: str) -> "MatingPoint":
        nan3 = np.full(3, np.nan)
        nan = float("nan")
        return cls(float(phi1_rad), nan, nan, nan, nan, nan, nan3, nan3, nan, nan, 0,
                   True, where)


@dataclass(frozen=True)
class TcaPath:
    """Mating points of one tooth pair over a sequence of mesh phases.

    Attributes
    ----------
    points : tuple of MatingPoint
        One per requested phase, in the order requested (edge phases included).
    phi1_ref_rad, phi2_ref_rad : float
        Reference (mean-point) rotations of the TE0 definition, rad.
    ratio : float
        z2 / z1.
    """

    points: tuple[MatingPoint, ...]
    phi1_ref_rad: float
    phi2_ref_rad: float
    ratio: float
    _cache: dict = field(default_factory=dict, repr=False, compare=False)

    def _stack(self, name: str) -> np.ndarray:
        if name not in self._cache:
            self._cache[name] = np.array([getattr(p, name) for p in self.points])
        return self._cache[name]

    @property
    def phi1_rad(self) -> np.ndarray:
        return self._stack("phi1_rad")

    @property
    def phi2_rad(self) -> np.ndarray:
        return self._stack("phi2_rad")

    @property
    def te0_arcsec(self) -> np.ndarray:
        return self._stack("te0_arcsec")

    @property
    def points_mm(self) -> np.ndarray:
        """(N, 3) mating points in the meshing frame, mm (NaN at edge phases)."""
        return self._stack("point_mm")

    @property
    def normals(self) -> np.ndarray:
        return self._stack("normal")

    @property
    def edge(self) -> np.ndarray:
        return self._stack("edge")

    @property
    def surface(self) -> np.ndarray:
        """Per point: a surface-to-surface contact (neither a phase without contact nor
        an edge touching the other flank)."""
        if "surface" not in self._cache:
            self._cache["surface"] = ~self.edge & (self._stack("edge_contact") == "")
        return self._cache["surface"]

    def parameters(self, member: str) -> np.ndarray:
        """(N, 2) flank parameters (u, v) of ``"pinion"`` or ``"gear"``."""
        k = {"pinion": ("u1", "v1"), "gear": ("u2", "v2")}[member]
        return np.column_stack([self._stack(k[0]), self._stack(k[1])])
