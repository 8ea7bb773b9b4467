"""Loaded contact of a cylindrical pair at the pitch-point phase: what ``gearcontact
ltca`` computes for a ``kind = "cylindrical"`` pair (docs/cylindrical.md sec. 12).

No solver of its own: it is one phase of the loaded TE over the mesh cycle
(:func:`~gearcontact.ltca.cylindrical_lte.cylindrical_loaded_te`, the same call with the
same options as ``gearcontact lte``, tooth bending by default), the phase at which pair 0
passes the pitch point, with the cell pressures of every pair in contact kept there
(``fields_at``). Every number is that loaded TE's own at the phase: load shares, load
per unit face width along each contact line, the gear rotation the load adds and the
normal approach ``delta = r_b2 cos(beta_b) theta``, the secant mesh stiffness.

The phase. The unloaded cycle's phases are centred on the pitch-point phase of pair 0
(:class:`~gearcontact.tca.cylindrical_cycle.CylindricalMeshCycle`): index
``(K - 1) // 2`` of ``K`` phases lies exactly on it for every ``K``
(:func:`pitch_point_phase`). On a helical pair the pitch point is that of the
transverse section through ``z = 0`` (mid-face of the pinion): the line of pair 0
crosses the pitch line there.

Torque balance: each pair's normal load times its lever about the gear axis
(``r_b2 cos(beta_b)`` for a line, a tip edge's own) sums to the gear torque (the mesh
LCP's constraint, to its tolerance).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..geometry.cylindrical.pair import CylindricalPair
from .cylindrical_lte import CylindricalLoadedTE, cylindrical_loaded_te, normal_load_n

__all__ = ["CylindricalPhaseContact", "cylindrical_ltca", "pitch_point_phase"]


def pitch_point_phase(phases: int) -> int:
    """Index of the pitch-point phase of pair 0 among ``phases`` phases per pitch."""
    return (int(phases) - 1) // 2


@dataclass(frozen=True)
class CylindricalPhaseContact:
    """The loaded contact of one phase of a cylindrical pair's loaded TE.

    Attributes
    ----------
    lte : CylindricalLoadedTE
        The loaded TE over the cycle (``phase_pressure_mpa`` kept at ``phase``).
    phase : int
        The phase index (:func:`pitch_point_phase`).
    """

    lte: CylindricalLoadedTE
    phase: int

    @property
    def gear_lever_mm(self) -> float:
        """``r_b2 cos(beta_b)``, mm: a line's lever about the gear axis (the loaded TE's
        torque over its normal load, :func:`~.cylindrical_lte.normal_load_n`)."""
        return 1e3 * self.lte.torque_nm / self.lte.normal_load_n

    @property
    def phi1_rad(self) -> float:
        """Pinion phase, rad, as the loaded TE's ``phi1_rad`` (the pinion's turn from its
        tooth centred on the line of centres: :func:`~gearcontact.tca.parallel_axes.
        pitch_point_guess`)."""
        return float(self.lte.phi1_rad[self.phase])

    @property
    def pressure_mpa(self) -> np.ndarray:
        """Cell pressures (P, N, M), MPa (rows along the face at ``lte.z_mm``)."""
        return self.lte.phase_pressure_mpa

    @property
    def across_mm(self) -> np.ndarray:
        """Cell centres across the lines (M,), mm, centred on the line."""
        m = self.pressure_mpa.shape[-1]
        return self.lte.grid_dx_mm * (np.arange(m) + 0.5 - 0.5 * m)

    @property
    def load_n(self) -> np.ndarray:
        """Normal load of each pair's line or tip edge (P,), N (beyond-line edge rows:
        :attr:`beyond_load_n`)."""
        return self.lte.load_share[:, self.phase] * self.lte.normal_load_n

    @property
    def beyond_load_n(self) -> np.ndarray:
        """Normal load of the tip edges beyond each pair's line (P, 2), N."""
        return self.lte.beyond_load_share[:, self.phase] * self.lte.normal_load_n

    @property
    def torque_from_loads_nm(self) -> float:
        """``sum load lever`` over lines, tip edges and beyond-line rows, N·m (equals the
        gear torque: the LCP's balance)."""
        k = self.phase
        return 1e-3 * float((self.load_n * self.lte.lever_mm[:, k]).sum()
                            + (self.beyond_load_n * self.lte.beyond_lever_mm[:, k]).sum())

    @property
    def p_max_mpa(self) -> float:
        """Largest cell pressure of the phase, MPa (a sharp edge's where
        ``lte.peak_at_edge[phase]``)."""
        return float(self.lte.max_pressure_mpa[self.phase])

    @property
    def rotation_rad(self) -> float:
        """Gear rotation the load adds, rad."""
        return float(self.lte.rotation_rad[self.phase])

    @property
    def approach_mm(self) -> float:
        """Normal approach from the unloaded rest, ``r_b2 cos(beta_b) theta``, mm."""
        return self.gear_lever_mm * self.rotation_rad


def cylindrical_ltca(pair: CylindricalPair, torque_nm: float, *, facing: str = "cw",
                     phases: int = 61, cells_along: int = 40, bending: bool = True
                     ) -> CylindricalPhaseContact:
    """The loaded contact at the pitch-point phase (module docstring).

    Parameters
    ----------
    pair : CylindricalPair
    torque_nm : float
        Gear torque, N·m (> 0).
    facing, phases, cells_along, bending
        As :func:`~gearcontact.ltca.cylindrical_lte.cylindrical_loaded_te` (defaults
        those of ``gearcontact lte``: 61 phases, 40 cells along the face, bending).
    """
    normal_load_n(pair, torque_nm)                       # checked before the cycle
    k = pitch_point_phase(phases)
    lte = cylindrical_loaded_te(pair, torque_nm, facing=facing, phases=phases,
                                cells_along=cells_along, bending=bending, fields_at=k)
    return CylindricalPhaseContact(lte=lte, phase=k)
