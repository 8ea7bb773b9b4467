"""Speed sweep: the classic dynamic factor vs speed curve, preview twin beside table twin.

Each speed is an independent run from the static start (:func:`.simulate.simulate`)
long enough for the transient of the least damped mode to decay (``settle_s``) plus
``mesh_cycles`` mesh periods over which the statistics are taken; the speeds run in
parallel worker processes (each loads the compiled loop from numba's cache).

Resonances: the mesh excites the chain at the mesh frequency ``f_z = z1 n / 60`` and its
harmonics ``k f_z`` (the unloaded TE and the phase-varying stiffness are not
sinusoidal), so the dynamic factor peaks where ``k f_z`` meets a natural frequency of
the linearised chain: speeds ``n = 60 f_n / (k z1)`` (Kahraman & Singh, J. Sound Vib.
142 (1990) 49-75: primary resonance and super-harmonics at 1/2, 1/3 of it).
"""

from __future__ import annotations

import os
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass

import numpy as np
from tqdm import tqdm

from ..validation import InputRangeError, check_range
from .simulate import MAX_SPEED_RPM, TwinModel, check_step, linearized_modes, simulate

__all__ = ["SweepResult", "speed_sweep", "parse_speed_range"]


@dataclass(frozen=True)
class SweepResult:
    """Per speed and model: dynamic factor, DTE p-p (arcsec), contact loss (fraction).

    Attributes
    ----------
    speeds_rpm : ndarray (S,)
        Pinion speeds, rpm.
    rows : dict of str -> dict of str -> ndarray (S,)
        ``rows[label]["dynamic_factor" | "dte_pp_arcsec" | "contact_loss" |
        "real_time_factor"]``.
    natural_frequencies_hz : ndarray
        Linearised modes of the first model (rigid mode dropped), Hz.
    pinion_teeth : int
        z1.
    """

    speeds_rpm: np.ndarray
    rows: dict
    natural_frequencies_hz: np.ndarray
    pinion_teeth: int

    def resonance_speeds_rpm(self, orders=(1, 2, 3)) -> dict:
        """``{(k, f_n): 60 f_n / (k z1)}`` for the modes and mesh orders ``k``."""
        return {(k, float(f)): 60.0 * float(f) / (k * self.pinion_teeth)
                for f in self.natural_frequencies_hz for k in orders}


def parse_speed_range(text: str) -> np.ndarray:
    """``"start:stop:step"`` (rpm, stop included when on the grid) -> speeds.

    Raises
    ------
    InputRangeError
        Not three numbers, start <= 0, stop < start or step <= 0 (field ``--speed-sweep``).
    """
    try:
        a, b, c = (float(x) for x in str(text).split(":"))
    except ValueError:
        raise InputRangeError("--speed-sweep", text, "start:stop:step in rpm") from None
    if not (a > 0 and b >= a and c > 0):
        raise InputRangeError("--speed-sweep", text, "0 < start <= stop, step > 0 (rpm)")
    n = int(np.floor((b - a) / c + 1e-9)) + 1
    if n > 2000:
        raise InputRangeError("--speed-sweep", text, "at most 2000 speeds")
    return a + c * np.arange(n)


def _one(model: TwinModel, speed: float, step_s: float, settle_s: float,
         mesh_cycles: int) -> dict:
    f_mesh = model.mesh.pinion_teeth * speed / 60.0
    duration = settle_s + mesh_cycles / f_mesh
    res = simulate(model, speed_rpm=speed, duration_s=duration, step_s=step_s,
                   record_every=1, settle_fraction=settle_s / duration)
    return {**{k: res.summary[k] for k in ("dynamic_factor", "dte_pp_arcsec",
                                             "contact_loss")},
            "real_time_factor": res.timings["real_time_factor"]}


def _task(args):
    label, model, speed, step_s, settle_s, cycles = args
    return label, speed, _one(model, speed, step_s, settle_s, cycles)


def speed_sweep(models: dict, speeds_rpm, *, step_s: float = 10e-6, settle_s: float = 0.1,
                mesh_cycles: int = 10, workers: int | None = None,
                progress: bool = False) -> SweepResult:
    """Run every model at every speed (module docstring).

    Parameters
    ----------
    models : dict of str -> TwinModel
        Labelled models (e.g. ``{"preview": ..., "table": ...}``).
    speeds_rpm : array_like
        Pinion speeds, rpm (> 0).
    step_s : float
        Fixed step, s.
    settle_s : float
        Transient time left out of the statistics, s (>= 0).
    mesh_cycles : int
        Mesh periods after the transient (>= 2).
    workers : int or None
        Worker processes (default: the CPU count; 1 runs in this process); at most one
        per task (model x speed) is started.
    """
    speeds = np.asarray(speeds_rpm, float).ravel()
    if speeds.size == 0 or not np.all(speeds > 0):
        raise InputRangeError("speeds_rpm", speeds_rpm, "one or more speeds > 0 rpm")
    for v in speeds:            # every speed before the workers start, as simulate checks it
        check_range("speeds_rpm", v, 0.0, MAX_SPEED_RPM)
    check_range("settle_s", settle_s, 0.0, 10.0)
    if int(mesh_cycles) != mesh_cycles or mesh_cycles < 2:
        raise InputRangeError("mesh_cycles", mesh_cycles, "an integer >= 2")
    if not models:
        raise InputRangeError("models", models, "at least one labelled model")
    # check the step (stability) once per model before the workers start
    for model in models.values():
        check_step(model, step_s)
    tasks = [(label, model, float(v), step_s, settle_s, int(mesh_cycles))
             for label, model in models.items() for v in speeds]
    # no idle processes: never more workers than tasks
    n_workers = min(int(workers or os.cpu_count() or 1), len(tasks))
    index = {float(v): i for i, v in enumerate(speeds)}
    keys = ("dynamic_factor", "dte_pp_arcsec", "contact_loss", "real_time_factor")
    rows = {label: {k: np.zeros(speeds.size) for k in keys} for label in models}
    bar = tqdm(total=len(tasks), desc="speed sweep", unit="run", disable=not progress,
               leave=False)
    if n_workers == 1:
        results = (_task(t) for t in tasks)
        for label, speed, out in results:
            for k in keys:
                rows[label][k][index[speed]] = out[k]
            bar.update(1)
    else:
        with ProcessPoolExecutor(max_workers=n_workers) as pool:
            for fut in as_completed([pool.submit(_task, t) for t in tasks]):
                label, speed, out = fut.result()
                for k in keys:
                    rows[label][k][index[speed]] = out[k]
                bar.update(1)
    bar.close()
    first = next(iter(models.values()))
    return SweepResult(speeds, rows, linearized_modes(first)[1:], first.mesh.pinion_teeth)
