"""Benchmark: the cost of the coupled slice law (ltca.coupled_slice_law; tooth bending
along the line) in the cylindrical preview and in the twin, beside the same work on
rigid teeth.

1. ``analyze``'s cylindrical preview of the helical EV-reducer example over one pinion
   pitch (61 phases, 64.5 N·m, the reference and golden backends, the loads from the
   line lengths), with bending (the coupled law per loaded pair and phase) and without
   (the slice law alone): wall-clock and process CPU, best of ``--repeat``, and the
   coupled law's Newton steps summed over the pairs and phases (a deterministic count:
   each step was ``m + 2`` slice-law solves with the forward-difference Jacobian of
   session 19, ``m`` = 16 slices, and is one solve and one ``m x m`` elimination with
   the exact Jacobian).
2. The twin (fp64 reference backend) on the EV example without tip relief at 400 N·m
   (its tip edges carry: 32 slices per line), 13 phases, 20 ms at 10 us, with bending
   and rigid: the median step time (simulate's ``step_time_p50_us``).

3. One Newton step of the coupled law on the twin's inputs (the same run's mesh table,
   the first line pair at the middle row, at its loaded TE share-sized load): the exact
   Jacobian (:func:`gearcontact.ltca.coupled_slice_law.coupled_solve`'s step: one
   evaluation of the slice law, the ``|A| x |A|`` reduced system) against the forward
   differences of session 19 (``m + 1`` evaluations of the compiled slice law and an
   ``m x m`` solve; the same evaluation function, timed from Python); only on a tree
   with the exact Jacobian.

The tooth models (timed on their own: the first preview with bending in a process
builds them) and the numba kernels are built and compiled before timing. The
machine's load average is printed (other processes share the cores: compare the two
columns of one run, not runs of different days). The script uses only APIs that the
tree before the exact Jacobian had too, so it measures both (run it with that tree on
``PYTHONPATH``).

Run: ``python benchmarks/bench_coupled_law.py [--repeat N]``.
"""

from __future__ import annotations

import argparse
import os
import time
from dataclasses import replace
from pathlib import Path

from gearcontact.geometry.pair import CYLINDRICAL, load_pair
from gearcontact.ltca.cylindrical_bending import cylindrical_bending
from gearcontact.ltca.cylindrical_preview import cylindrical_preview
from gearcontact.tca.cylindrical_cycle import cylindrical_mesh_cycle
from gearcontact.tca.cylindrical_stencil import cylindrical_stencils
from gearcontact.twin.cylindrical import cylindrical_model
from gearcontact.twin.simulate import simulate

PAIR = Path(__file__).resolve().parents[1] / "examples" / "ev_reducer_helical_23x67.toml"


def _best(fn, repeat):
    best = None
    for _ in range(max(repeat, 1)):
        w0, c0 = time.perf_counter(), time.process_time()
        out = fn()
        t = (time.perf_counter() - w0, time.process_time() - c0)
        best = t if best is None or t[1] < best[1] else best
    return best, out


def _newton_steps(pair, cycle, stencils, prev):
    """The coupled law's Newton steps over the preview's loaded pairs and phases."""
    import numpy as np

    from gearcontact.ltca.coupled_slice_law import coupled_line, line_bending_compliance
    from gearcontact.ltca.slice_law import line_easeoff_mm
    from gearcontact.materials import effective_modulus_mpa
    from gearcontact.preview.fit.reference import fitted_coefficients, principal_curvatures

    teeth = cylindrical_bending(pair, facing=cycle.facing)
    ease, slices = line_easeoff_mm(pair, cycle, stencils.valid)
    coeff = fitted_coefficients(stencils.gaps_mm)
    e_prime = effective_modulus_mpa(pair.pinion_material, pair.gear_material)
    steps = calls = 0
    for j, k in zip(*np.nonzero(prev.loaded)):
        b_max = max(principal_curvatures(*map(float, coeff[j, k]))[:2])
        if b_max <= 0.0:
            continue
        line = coupled_line(ease[j, k], float(stencils.line_length_mm[j, k]),
                            float(prev.load_n[j, k]), b_max, e_prime,
                            line_bending_compliance(teeth, slices, j, k))
        steps += line.steps
        calls += 1
    return steps, calls


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args()
    pair = load_pair(PAIR, kinds=(CYLINDRICAL,))
    cycle = cylindrical_mesh_cycle(pair, phases=61)
    stencils = cylindrical_stencils(pair, cycle)
    w0, c0 = time.perf_counter(), time.process_time()
    cylindrical_bending(pair, facing=cycle.facing)      # the shells, once per pair
    print(f"tooth shells (once per pair and process): {time.perf_counter() - w0:.2f} s wall, "
          f"{time.process_time() - c0:.2f} s CPU")
    cylindrical_preview(pair, 64.5, cycle=cycle, stencils=stencils, bending=True)  # compile
    for bending in (True, False):
        (wall, cpu), prev = _best(lambda: cylindrical_preview(
            pair, 64.5, cycle=cycle, stencils=stencils, bending=bending), args.repeat)
        label = "coupled law (bending)" if bending else "slice law (rigid)"
        print(f"preview, 61 phases, 64.5 N·m, reference + golden, {label}: {wall:.2f} s "
              f"wall, {cpu:.2f} s CPU; load average {os.getloadavg()[0]:.2f}")
        if bending:
            steps, calls = _newton_steps(pair, cycle, stencils, prev)
            print(f"  the coupled law: {calls} lines, {steps} Newton steps")
    bare = replace(pair, modifications_pinion=replace(pair.modifications_pinion,
                                                      tip_relief_um=0.0),
                   modifications_gear=replace(pair.modifications_gear, tip_relief_um=0.0))
    for bending in (True, False):
        model = cylindrical_model(bare, torque_nm=400.0, phases=13, bending=bending)
        run = simulate(model, speed_rpm=3000.0, duration_s=0.02, step_s=10e-6)
        t = run.timings if hasattr(run, "timings") else run.summary
        label = "coupled law (bending)" if bending else "slice law (rigid)"
        print(f"twin reference, EV without tip relief, 400 N·m, 13 phases, {label}: "
              f"{t['step_time_p50_us']:.2f} us per step (median; p99 "
              f"{t['step_time_p99_us']:.2f}); load average {os.getloadavg()[0]:.2f}")
        if bending:
            _newton_step_times(model)
    return 0


def _newton_step_times(model, reps=300):
    """Part 3 of the module docstring."""
    import numpy as np

    try:
        from gearcontact.ltca import coupled_slice_law as core
    except ImportError:
        return
    if not hasattr(core, "_newton_step"):
        print("  (no exact Jacobian on this tree: part 3 skipped)")
        return
    from gearcontact.preview.fit.reference import fitted_coefficients, principal_curvatures

    m_t = model.mesh
    k = len(m_t.psi_rad) // 2
    j = int(np.flatnonzero(m_t.valid[:, k] & (m_t.contact_mode[:, k] == 0))[0])
    h = np.concatenate([m_t.line_gap_mm[j, k], m_t.beyond_gap_mm[j, k].ravel()])
    g = m_t.line_bending_gram_mm_per_n[j, k]
    nb = m_t.beyond_gap_mm.shape[-1]
    wb = m_t.beyond_width_mm * m_t.beyond_stiffness
    b_max = max(principal_curvatures(*map(float, fitted_coefficients(
        m_t.stencil_gaps_mm[j, k])))[:2])
    m, length, e_p = h.size, float(m_t.line_length_mm[j, k]), m_t.e_prime_mpa
    n, load = m - 2 * nb, 3000.0
    line = core.coupled_line(h, length, load, b_max, e_p, g, edge_slices=nb,
                             edge_width_mm=wb)
    x = h + g @ line.slice_load_n
    d = 1.001 * (line.approach_mm + x.min())        # a step's move from the solution
    buf = np.zeros(core.core_scratch(m))
    buf[:m], buf[m:m + m * m] = h, g.ravel()
    ox, of = core.start_offset(0, m), core._at(0, m, core._F)
    buf[ox:ox + m] = x
    res = core._evaluate(buf, 0, m, n, length, b_max, e_p, nb, wb, d, True, load)
    core._newton_step(buf, 0, m, res[6], res[7])
    t0 = time.perf_counter()
    for _ in range(reps):
        core._newton_step(buf, 0, m, res[6], res[7])
    t_exact = (time.perf_counter() - t0) / reps
    exact = buf[core._at(0, m, core._DEL):][:m].copy()
    t0 = time.perf_counter()
    for _ in range(max(reps // 10, 1)):
        buf[ox:ox + m] = x
        core._evaluate(buf, 0, m, n, length, b_max, e_p, nb, wb, d, True, load)
        f0, r0 = buf[of:of + m].copy(), buf[core._at(0, m, core._R):][:m].copy()
        jac = np.eye(m)
        for i in range(m):
            buf[ox:ox + m] = x
            buf[ox + i] += 1e-9
            core._evaluate(buf, 0, m, n, length, b_max, e_p, nb, wb, d, True, load)
            jac[:, i] -= g @ ((buf[of:of + m] - f0) / 1e-9)
        fd = np.linalg.solve(jac, -r0)
    t_fd = (time.perf_counter() - t0) / max(reps // 10, 1)
    print(f"  one Newton step, {m} slices ({n} line, {2 * nb} edge), active "
          f"{int(np.count_nonzero(line.slice_load_n))}: exact Jacobian {t_exact * 1e6:.1f} us, "
          f"forward differences ({m + 1} evaluations) {t_fd * 1e6:.1f} us (x "
          f"{t_fd / t_exact:.1f}); steps agree to {np.abs(fd - exact).max() / np.abs(exact).max():.1e}"
          f" of the step; load average {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    raise SystemExit(main())
