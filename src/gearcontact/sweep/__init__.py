"""Sweeps of the contact analysis over assembly errors and torque on Dask distributed
(docs/sweeps.md): :mod:`.grid` (the ``--vary`` grid), :mod:`.cell` (one grid point's
results; a cylindrical pair's: :mod:`.cylindrical`), :mod:`.store` (the zarr Dataset,
resumable), :mod:`.run` (the scheduler)."""

from .cell import CELL_VARIABLES, compute_point
from .cylindrical import compute_cylindrical_point
from .grid import SweepGrid, parse_vary
from .run import SweepReport, run_sweep

__all__ = ["CELL_VARIABLES", "SweepGrid", "SweepReport", "compute_cylindrical_point",
           "compute_point", "parse_vary", "run_sweep"]
