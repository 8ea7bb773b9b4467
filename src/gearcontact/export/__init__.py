"""Export of the preview datapath for use outside Python (issue 25).

:mod:`.c_library` writes the self-contained C99 library (golden fixed point and fp64)
with its checker program; :mod:`.c_constants` and :mod:`.c_checker` collect what the
templates print from the package's own tables and vector layouts. :mod:`.fmu` writes the
FMI 3.0 FMU of one gear mesh (its law in Python: :mod:`.mesh_law`) and builds every FMU
kind; :mod:`.fmu_drivetrain` the FMU of the whole drivetrain twin.
:mod:`.flanks` and :mod:`.flank_step` write the flanks of a pair as STEP B-spline faces
and CMM point grids (issue 27).
"""

from .c_library import export_c_library, render_c_library

__all__ = ["export_c_library", "render_c_library"]
