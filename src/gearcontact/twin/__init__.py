"""Real-time torsional drivetrain twin with the contact preview as the mesh law.

motor J_m -- shaft (k1, c1) -- pinion -- mesh -- gear -- shaft (k2, c2) -- load J_l,
integrated at a fixed step by a compiled RK4 loop; the mesh acts along the normal of
every tooth pair in reach with the unloaded TE of the TCA as displacement excitation and
a Hertzian law per pair whose approach coefficient comes from the preview at the current
phase and load (fp64 or the bit-exact golden stage D, or the RTL in lockstep), or from
an offline loaded-TE table (the conventional twin).

Modules: :mod:`.params` (``[drivetrain]``), :mod:`.mesh` (per phase and pair),
:mod:`.ltca_table` (table twin), :mod:`.kernel` (compiled step loop), :mod:`.simulate`
(model, static point, modes, runs), :mod:`.cosim` (rtl backend), :mod:`.sweep` (dynamic
factor vs speed), :mod:`.report` (files and figures).
"""
