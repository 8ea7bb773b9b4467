"""Running a sweep on Dask distributed: a LocalCluster (worker processes, one thread
each) by default, an existing cluster by its scheduler address, or in this process
(``workers=0``, the plain loop the Dask path is measured against).

Without design keys the flanks are built once here and scattered to every worker
(broadcast); with them, one task per design variant builds its flanks on a worker and
the points of that variant depend on it (:mod:`.design`). One task is one grid point
(one TCA, then per torque one LTCA and one loaded TE). A cylindrical pair's points
each run their own mesh cycle and loaded TEs (:mod:`.cylindrical`). Results are
written into the zarr store (:mod:`.store`) by this process as tasks finish, so an interrupted sweep keeps
every finished point and its rerun computes only the rest.

References
----------
M. Rocklin, "Dask: parallel computation with blocked algorithms and task scheduling",
*Proc. 14th Python in Science Conf.*, 2015, 126-132.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import os
import time
from dataclasses import dataclass, field
from pathlib import Path

from tqdm import tqdm

from ..geometry.pair import CYLINDRICAL
from .cell import LTE_CELLS, compute_point, lte_stride
from .cylindrical import compute_cylindrical_point
from .design import Variant, build_variant, easeoff_only
from .store import FAILED, PENDING, STORE_NAME, WARNING_VARIABLE, prepare_store, write_point

__all__ = ["SweepReport", "run_sweep", "sweep_settings"]


@dataclass
class SweepReport:
    """What one run of a sweep did.

    Attributes
    ----------
    store : Path
        The zarr store.
    cells : int
        Cells of the grid (points x torques).
    computed, skipped, failed : int
        Cells computed by this run, found finished (done or failed) by it, and failed
        (recorded with their error) among all cells.
    wall_s : float
        Wall time of the computation (flanks, cluster start-up and tasks), s.
    flanks_s : float
        Of it, the nominal flank build in this process, s (0 with cutter keys: each
        variant's build is timed on its worker, ``flank_build_s`` in the store).
    first_s, last_s : float
        From after the flanks to the first and the last point written, s (the first
        includes the cluster start-up, the scatter and the workers' first call; points
        per second in steady state = (points - 1) / (last_s - first_s)).
    errors : list of str
        The distinct errors of the failed cells.
    """

    store: Path
    cells: int
    computed: int = 0
    skipped: int = 0
    failed: int = 0
    wall_s: float = 0.0
    flanks_s: float = 0.0
    first_s: float = float("nan")
    last_s: float = float("nan")
    errors: list = field(default_factory=list)


def run_sweep(pair, grid, *, out, side: str, compute=("tca",), phases: int = 61,
              cells: int = 80, solver: str = "pk_cg", scheduler: str | None = None,
              workers: int | None = None, client=None, flanks=None,
              progress: bool = True, options: dict | None = None,
              settings_check=None) -> SweepReport:
    """Compute the pending cells of ``grid`` into ``out/sweep.zarr``.

    Parameters
    ----------
    pair : GearPair or CylindricalPair
        The nominal pair (a grid with design keys varies it, :mod:`.design`; a
        cylindrical pair's keys: :mod:`.cylindrical`).
    grid : SweepGrid
    out : path
        Directory of the store.
    side, compute, phases, cells, solver
        As :func:`~gearcontact.sweep.cell.compute_point`.
    scheduler : str, optional
        Address of a running Dask scheduler (``tcp://HOST:PORT``).
    workers : int, optional
        Worker processes of the LocalCluster (default: the CPU count); 0 runs the
        cells in this process without Dask.
    client : distributed.Client, optional
        A client to use (then neither ``scheduler`` nor ``workers`` apply).
    flanks : FlankSet, optional
        ``build_flanks(pair)`` if already built (a prepared pair's,
        :class:`~gearcontact.tca.synthesis.PreparedPair`); without them the pair's
        typed machine settings are checked against its blank first
        (:func:`~gearcontact.geometry.settings_check.checked_settings`: a gross slip
        raises naming its key, before the store is touched). Not used, and not needed,
        when the grid varies setting keys (:mod:`.settings_keys`: each variant builds
        its own).
    progress : bool
        Progress bar of cells done / total.
    options : dict, optional
        A cylindrical pair: further keyword options of its loaded TE
        (:func:`~gearcontact.ltca.cylindrical_lte.cylindrical_loaded_te`; part of the
        settings a resumed sweep must share).
    settings_check : SettingsCheck, optional
        The typed-settings check of ``pair``, if the caller ran it (the command line, in
        its argument check): not run again without ``flanks``.
    """
    from ..geometry.flank import build_flanks
    from ..geometry.settings_check import checked_settings

    if flanks is None and settings_check is None:   # a raw pair: checked before the store
        checked_settings(pair, stacklevel=2)
    t0 = time.perf_counter()
    store = Path(out) / STORE_NAME
    settings = sweep_settings(pair, side=side, compute=compute, phases=phases, cells=cells,
                              solver=solver, options=options)
    status = prepare_store(store, grid, compute, settings)
    todo = [p for p in grid.points() if (status[p[0]] == PENDING).any()]
    n_t = len(grid.torques_nm)
    report = SweepReport(store, grid.cells, skipped=grid.cells - n_t * len(todo))
    bar = tqdm(total=grid.cells, initial=report.skipped, desc="sweep cells",
               unit="cell", disable=not progress)
    kwargs = dict(side=side, compute=tuple(compute), phases=phases, cells=cells)
    if pair.kind == CYLINDRICAL:
        kwargs["options"] = dict(options or {})
    else:
        kwargs["solver"] = solver
    if todo:
        tf = time.perf_counter()
        design_keys = [v.key for v in grid.vary if v.design]
        nominal = None
        # built here once and shipped to the workers: the flanks of every point, or
        # (ease-off keys only) the conjugate flanks every variant's ease-off goes on
        if pair.kind == CYLINDRICAL:       # no flanks to build: the TCA makes them
            nominal = Variant(pair, None, 0.0)
        elif not design_keys or easeoff_only(design_keys):
            nominal = Variant(pair, build_flanks(pair) if flanks is None else flanks,
                              time.perf_counter() - tf)
        t1 = time.perf_counter()
        report.flanks_s = t1 - tf
        for idx, result in _results(pair, nominal, grid, todo, kwargs, scheduler=scheduler,
                                    workers=workers, client=client):
            write_point(store, grid, idx, result)
            report.last_s = time.perf_counter() - t1
            if report.computed == 0:
                report.first_s = report.last_s
            report.computed += n_t
            bar.update(n_t)
    bar.close()
    import xarray as xr

    final = xr.open_zarr(store, consolidated=False)
    report.failed = int((final["status"].values == FAILED).sum())
    report.errors = sorted({str(e) for e in final["error"].values.ravel() if e})
    report.wall_s = time.perf_counter() - t0
    return report


def sweep_settings(pair, *, side: str, compute, phases: int, cells: int, solver: str,
                   options: dict | None = None) -> dict:
    """Settings a resumed sweep must share with the run that began its store (the
    pair by name and by the SHA-256 of its TOML, which holds every design value; a
    cylindrical pair by the SHA-256 of its fields, with its ``kind`` and ``options``)."""
    from ..geometry.pair import pair_to_toml

    if pair.kind == CYLINDRICAL:
        fields = json.dumps(dataclasses.asdict(pair), sort_keys=True, default=str)
        ltca = ({"cells": cells, "options": dict(options or {})} if "ltca" in compute
                else {})
        return {"kind": CYLINDRICAL, "pair": pair.name,
                "pair_sha256": hashlib.sha256(fields.encode()).hexdigest(), "side": side,
                "phases": phases, **ltca}

    a = pair.assembly
    digest = hashlib.sha256(pair_to_toml(pair).encode()).hexdigest()
    ltca = ({"cells": cells, "solver": solver, "lte_cells": LTE_CELLS,
             "lte_stride": lte_stride(phases)} if "ltca" in compute else {})
    return {"pair": pair.name, "pair_sha256": digest,
            "assembly": [a.E_mm, a.P_mm, a.G_mm, a.alpha_deg],
            "side": side, "phases": phases, **ltca}


def _by_variant(todo) -> dict:
    """The points of ``todo`` grouped by design variant (first-seen order)."""
    groups: dict = {}
    for idx, assembly, design in todo:
        groups.setdefault(design, []).append((idx, assembly))
    return groups


def _results(pair, nominal, grid, todo, kwargs, *, scheduler, workers, client):
    """(index, result) of every point of ``todo``, in the order they finish.

    ``nominal``: the pair's own :class:`~.design.Variant` (built by the caller and
    broadcast to the workers) or None. Without design keys it serves every point.
    With them every design variant is built by one task on a worker (on ``nominal``'s
    conjugate flanks when given: ease-off keys only), and the tasks of its points depend
    on it (Dask runs them where the flanks are, or moves them once), submitted variant
    by variant so that few variants' flanks are held at a time.
    """
    torques = list(grid.torques_nm)
    groups = _by_variant(todo)
    if workers == 0 and client is None and scheduler is None:
        for design, points in groups.items():
            variant = build_variant(pair, design, nominal) if design else nominal
            for idx, a in points:
                yield idx, _guarded(variant, a, torques, kwargs)
        return
    from distributed import Client, LocalCluster, as_completed

    own = None
    if client is None:
        if scheduler is not None:
            own = client = Client(scheduler)
        else:
            n = workers or os.cpu_count() or 1
            cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                   dashboard_address=None)
            own = client = Client(cluster)
    try:
        futures = {}
        shared = client.scatter(nominal, broadcast=True) if nominal is not None else None
        for design, points in groups.items():
            variant = (client.submit(build_variant, pair, design, shared, pure=False)
                       if design else shared)
            for idx, a in points:
                futures[client.submit(_guarded, variant, a, torques, kwargs,
                                      pure=False)] = idx
            del variant        # held by its points' tasks until they finish
        for fut in as_completed(futures):
            yield futures[fut], fut.result()
            fut.release()
    finally:
        if own is not None:
            cluster = getattr(own, "cluster", None)
            own.close()
            if cluster is not None and scheduler is None:
                cluster.close()


def _guarded(variant, assembly, torques, kwargs) -> dict:
    """:func:`compute_point` on a built design variant, with the variant's flank build
    time and reader warnings (:func:`compute_cylindrical_point` on a cylindrical pair,
    without: it has no flank build); a failed build or any unexpected exception
    recorded as the point's error (a sweep of hundreds of points must not die of one)."""
    n = len(torques)
    cylindrical = "options" in kwargs
    extra = {} if cylindrical else {"flank_build_s": [variant.build_s] * n}
    if variant.warnings:       # a setting variant's (the store keeps them beside)
        extra[WARNING_VARIABLE] = ["; ".join(variant.warnings)] * n
    if variant.error:
        return {"error": [variant.error] * n, **extra}
    try:
        if cylindrical:
            return compute_cylindrical_point(variant.pair, torques, **kwargs)
        return {**compute_point(variant.pair, variant.flanks, assembly, torques, **kwargs),
                **extra}
    except Exception as exc:  # noqa: BLE001  (recorded with its type; see the store)
        return {"error": [f"{type(exc).__name__}: {exc}"] * n, **extra}
