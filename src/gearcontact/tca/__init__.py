"""Unloaded tooth contact analysis (TCA) on the host, fp64.

Per mesh phase: the mating point of two flanks (Newton on position + normal
coincidence, :mod:`.solve`), the relative curvatures and the paint contact ellipse
(:mod:`.curvature`); over the mesh cycle: the neighbouring tooth pairs and the TE0
envelope (:mod:`.mesh`); around the mating point: the 80 x 80 gap field and the 7 x 7
hardware stencil (:mod:`.stencil`); the phase table for the device (:mod:`.phase_table`);
figures (:mod:`.plots`) and files (:mod:`.export`). :func:`analyze_pair` runs it all.
"""

from .analysis import TcaAnalysis, analyze, analyze_pair
from .curvature import (PAINT_THICKNESS_MM, ContactEllipse, RelativeCurvature,
                        contact_ellipse, relative_curvature)
from .mesh import MeshCycle, mesh_cycle
from .phase_table import PhaseTable, decode_binary, encode_binary, phase_table
from .mating import solve_mating_point
from .solve import solve_tca
from .types import ContactGuess, EdgeContact, MatingPoint, TcaConvergenceError, TcaPath
from .stencil import GapField, gap_at, gap_field, gap_field_80, hardware_stencil

__all__ = ["TcaAnalysis", "analyze", "analyze_pair", "PAINT_THICKNESS_MM",
           "ContactEllipse", "RelativeCurvature", "contact_ellipse", "relative_curvature",
           "MeshCycle", "mesh_cycle", "PhaseTable", "decode_binary", "encode_binary",
           "phase_table", "ContactGuess", "EdgeContact", "MatingPoint",
           "TcaConvergenceError", "TcaPath", "solve_mating_point", "solve_tca", "GapField",
           "gap_at", "gap_field", "gap_field_80", "hardware_stencil"]
