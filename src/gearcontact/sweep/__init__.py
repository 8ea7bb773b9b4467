"""Sweeps of the contact analysis over assembly errors and torque on Dask distributed
(docs/sweeps.md): :mod:`.grid` (the ``--vary`` grid), :mod:`.design` and
:mod:`.settings_keys` (design variants; a pair cut from settings: its machine and blade
keys), :mod:`.cell` (one grid point's results; a cylindrical pair's:
:mod:`.cylindrical`), :mod:`.store` (the zarr Dataset, resumable), :mod:`.run` (the
scheduler)."""

from ..lazy_names import lazy_names

__all__ = ["CELL_VARIABLES", "SweepGrid", "SweepReport", "compute_cylindrical_point",
           "compute_point", "parse_vary", "run_sweep"]

#: Each public name imports its module on first use: importing one module of the package
#: does not import the others (and their numpy, scipy and numba).
__getattr__ = lazy_names(__name__, {
    "cell": ("CELL_VARIABLES", "compute_point"),
    "cylindrical": ("compute_cylindrical_point",),
    "grid": ("SweepGrid", "parse_vary"),
    "run": ("SweepReport", "run_sweep"),
})
