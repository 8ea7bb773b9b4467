"""Unloaded tooth contact analysis (TCA) on the host, fp64.

Per mesh phase: the mating point of two flanks (Newton on position + normal
coincidence, :mod:`.solve`), the relative curvatures and the paint contact ellipse
(:mod:`.curvature`); over the mesh cycle: the neighbouring tooth pairs and the TE0
envelope (:mod:`.mesh`); around the mating point: the 80 x 80 gap field and the 7 x 7
hardware stencil (:mod:`.stencil`); the phase table for the device (:mod:`.phase_table`);
figures (:mod:`.plots`) and files (:mod:`.export`). :func:`analyze_pair` runs it all.
"""

from ..lazy_names import lazy_names

__all__ = ["TcaAnalysis", "analyze", "analyze_pair", "PAINT_THICKNESS_MM",
           "ContactEllipse", "RelativeCurvature", "contact_ellipse", "relative_curvature",
           "MeshCycle", "mesh_cycle", "PhaseTable", "decode_binary", "encode_binary",
           "phase_table", "ContactGuess", "EdgeContact", "MatingPoint",
           "TcaConvergenceError", "TcaPath", "solve_mating_point", "solve_tca", "GapField",
           "gap_at", "gap_field", "gap_field_80", "hardware_stencil"]

#: Each public name imports its module on first use: importing one module of the package
#: does not import the others (and their numpy, scipy and numba).
__getattr__ = lazy_names(__name__, {
    "analysis": ("TcaAnalysis", "analyze", "analyze_pair"),
    "curvature": ("PAINT_THICKNESS_MM", "ContactEllipse", "RelativeCurvature",
                  "contact_ellipse", "relative_curvature"),
    "mesh": ("MeshCycle", "mesh_cycle"),
    "phase_table": ("PhaseTable", "decode_binary", "encode_binary", "phase_table"),
    "mating": ("solve_mating_point",),
    "solve": ("solve_tca",),
    "types": ("ContactGuess", "EdgeContact", "MatingPoint", "TcaConvergenceError", "TcaPath"),
    "stencil": ("GapField", "gap_at", "gap_field", "gap_field_80", "hardware_stencil"),
})
