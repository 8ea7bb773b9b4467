"""The zarr store of a sweep: one xarray Dataset over the grid's named dimensions,
created with every cell pending and filled one grid point at a time (region writes by
the single client process, so no two writers share a chunk; the point's ``status`` is
written after its values). ``status`` says what each
cell holds (0 pending, 1 done, 2 failed with ``error``); a rerun reads it and computes
only the pending cells. The grid and the settings are stored in the attributes: a rerun
with other ones is refused rather than mixed into the store.

References
----------
S. Hoyer, J. Hamman, "xarray: N-D labeled arrays and datasets in Python", *J. Open
Research Software* 5(1), 2017, 10 (the Dataset, zarr region writes).
"""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

import numpy as np

from ..validation import InputRangeError
from ..geometry.pair import CYLINDRICAL
from .cell import BOOL_VARIABLES, CELL_VARIABLES, LTCA_VARIABLES, TCA_VARIABLES
from .cylindrical import (CYLINDRICAL_BOOL_VARIABLES, CYLINDRICAL_LTCA_VARIABLES,
                          CYLINDRICAL_TCA_VARIABLES)
from .settings_keys import SETTING_KEYS

__all__ = ["STORE_NAME", "CREATING_NAME", "TIMING_VARIABLES", "WARNING_VARIABLE", "PENDING", "DONE", "FAILED", "empty_dataset", "check_store",
           "prepare_store", "write_point"]

#: Name of the store inside ``--out``.
STORE_NAME = "sweep.zarr"
#: Name of the store while it is created (renamed to STORE_NAME when complete).
CREATING_NAME = ".sweep.zarr.creating"
PENDING, DONE, FAILED = 0, 1, 2
#: With design keys swept: the flank build time of each cell's design variant (a
#: timing, not a result: it differs between runs; one build per variant).
TIMING_VARIABLES = {"flank_build_s": ("s", "wall time of the flank build of this cell's "
                                           "design variant (once per variant)")}


#: With setting keys swept (:mod:`.settings_keys`): the pair reader's warnings of each
#: cell's variant (text, ``""`` for none), as the commands print them beside their results.
WARNING_VARIABLE = "settings_warning"


def _warned(grid) -> bool:
    """The store of ``grid`` keeps :data:`WARNING_VARIABLE` (setting keys swept)."""
    return any(v.key in SETTING_KEYS for v in grid.vary)


def _variables(grid, compute, settings: dict) -> dict:
    if settings.get("kind") == CYLINDRICAL:      # no flank build, so no timing either
        return {**CYLINDRICAL_TCA_VARIABLES,
                **(CYLINDRICAL_LTCA_VARIABLES if "ltca" in compute else {})}
    timing = TIMING_VARIABLES if any(v.design for v in grid.vary) else {}
    return {**TCA_VARIABLES, **(LTCA_VARIABLES if "ltca" in compute else {}), **timing}


def empty_dataset(grid, compute, settings: dict):
    """All cells pending: NaN / False, ``error`` empty, ``status`` 0."""
    import xarray as xr

    coords = {v.field: (v.field, v.values, {"units": v.unit, "key": v.key})
              for v in grid.vary}
    coords["torque_nm"] = ("torque_nm", np.asarray(grid.torques_nm, float),
                           {"units": "N m"})
    data = {}
    for name, (unit, text) in _variables(grid, compute, settings).items():
        fill = (np.zeros(grid.shape, bool)
                if name in BOOL_VARIABLES or name in CYLINDRICAL_BOOL_VARIABLES
                else np.full(grid.shape, np.nan))
        data[name] = (grid.dims, fill, {"units": unit, "long_name": text})
    data["error"] = (grid.dims, np.full(grid.shape, "", dtype=object),
                     {"long_name": "error of a failed cell (type: message)"})
    if _warned(grid):
        data[WARNING_VARIABLE] = (grid.dims, np.full(grid.shape, "", dtype=object),
                                  {"long_name": "the pair reader's warnings of the cell's "
                                                "setting variant (category: message; ...)"})
    data["status"] = (grid.dims, np.zeros(grid.shape, np.int8),
                      {"long_name": "0 pending, 1 done, 2 failed"})
    return xr.Dataset(data, coords=coords,
                      attrs={"gearcontact_sweep": _identity(grid, compute, settings)})


def _identity(grid, compute, settings: dict) -> str:
    return json.dumps({"grid": grid.as_dict(), "compute": list(compute), **settings},
                      sort_keys=True)


def check_store(path, grid, compute, settings: dict) -> None:
    """Nothing, or :class:`InputRangeError` on ``--out`` when ``path`` holds a sweep of
    another grid or other settings (cheap: reads the attributes only)."""
    import xarray as xr

    path = Path(path)
    if not path.exists():
        return
    have = xr.open_zarr(path, consolidated=False).attrs.get("gearcontact_sweep")
    if have != _identity(grid, compute, settings):
        raise InputRangeError("--out", str(path.parent), "a directory without a sweep or "
                              f"with a sweep of the same grid and settings (it holds {have};"
                              " use another directory)")


def prepare_store(path, grid, compute, settings: dict) -> np.ndarray:
    """Create the store (all pending) or open the one a previous run left; returns the
    ``status`` array.

    Raises
    ------
    InputRangeError
        ``--out`` holds a sweep of another grid or other settings.
    """
    import xarray as xr

    path = Path(path)
    check_store(path, grid, compute, settings)
    if path.exists():
        return xr.open_zarr(path, consolidated=False)["status"].values
    want = empty_dataset(grid, compute, settings)
    # created beside and renamed into place: a kill during the creation leaves no
    # half-made store (the next run starts the creation again)
    tmp = path.with_name(CREATING_NAME)
    shutil.rmtree(tmp, ignore_errors=True)
    want.to_zarr(tmp, mode="w", consolidated=False, zarr_format=3)
    os.replace(tmp, path)
    return want["status"].values


def write_point(path, grid, index: tuple, result: dict) -> int:
    """Write one grid point's results (every torque) into the store; returns its
    status (DONE, or FAILED when a torque of it recorded an error)."""
    import xarray as xr

    errors = np.asarray(result["error"], dtype=object)
    status = np.where(errors == "", DONE, FAILED).astype(np.int8)
    shape = (1,) * len(index) + (len(grid.torques_nm),)
    # a cylindrical point returns its own variables and no timing
    names = {*CELL_VARIABLES, *CYLINDRICAL_TCA_VARIABLES, *CYLINDRICAL_LTCA_VARIABLES,
             *(TIMING_VARIABLES if any(v.design for v in grid.vary) else ()),
             *((WARNING_VARIABLE,) if _warned(grid) else ())}
    data = {k: (grid.dims, np.asarray(v, dtype=object if k == WARNING_VARIABLE else None
                                      ).reshape(shape))
            for k, v in result.items() if k in names}
    data["error"] = (grid.dims, errors.reshape(shape))
    region = {d: slice(i, i + 1) for d, i in zip(grid.dims, index)}
    region["torque_nm"] = slice(0, len(grid.torques_nm))
    # each chunk file is replaced atomically (zarr's local store); ``status`` goes last,
    # so that a kill between two files leaves the point pending, never half done
    xr.Dataset(data).to_zarr(path, region=region, consolidated=False)
    xr.Dataset({"status": (grid.dims, status.reshape(shape))}).to_zarr(
        path, region=region, consolidated=False)
    return int(status.max())
