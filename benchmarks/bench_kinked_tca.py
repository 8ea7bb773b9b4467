"""Benchmark: the TCA of ``gearcontact analyze`` on relieved (Toprem / Flankrem) pairs
against smooth peers, with the compiled kernels and on the numpy / Python paths they
replace.

Pairs (flanks built once, outside the timing): s0003 (the default pair), the ISO 23509
F.2 pair cut from machine settings (``examples/machine_settings``, smooth blades), the
Toprem pair of ``tests/data/toprem`` (the same F.2 settings, both pinion blades 2 deg
from 2 mm: a ``KinkedFlank`` pinion) and the Flankrem gear pair there (both gear
blades 2 deg from 5.5 mm: a ``KinkedFlank`` of blade cones; docs/machine_settings.md).
Each relieved pair runs on the compiled line intersections (``tca.gap_kernel``) and
compiled edge search (``tca.edge_kernel``), the defaults, and on the numpy / Python
paths they replace (``kernel_surface`` forced to None in ``tca.stencil`` and in
``tca.edge_contact``); the Flankrem pair also with one of the two replaced at a time
(``numpy gaps``: the gap fields' numpy path only; ``Python edges``: the edge search's
Python iteration only), so every gain is measured against its own peer in the same
process and load.

Stages per pair, best of ``--repeat`` runs (runs interleaved over the pairs, so every
pair sees the same load): ``analyze_pair`` (what ``analyze``'s TCA stage runs: mesh
cycle with edge contact, 80 x 80 gap field, stencil, pattern check), its stage split
(``TcaAnalysis.timings_s``) and, with ``--lte``, the loaded TE at 64.5 N m over the 61
phases with tooth bending (``analyze``'s default LTE stage, which builds one gap field
per pair and phase); the start-point search (``reference_start``, part of
``analyze_pair``: on the Flankrem pair, whose mean point lies on the gear's ridge, the
candidates that fail after the full Newton iteration) is timed on its own too. Wall and process CPU seconds (CPU is the fairer figure on a shared
machine); the load average before and after. The numba cache should be warm
(``gearcontact warm-up``); a first call per kernel is made before the timing.

Run: ``python benchmarks/bench_kinked_tca.py [--repeat N] [--lte]``. Figures:
docs/machine_settings.md, "Toprem and Flankrem".
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

from gearcontact.geometry.flank import build_flanks
from gearcontact.geometry.pair import load_pair
from gearcontact.tca import stencil
from gearcontact.tca.analysis import analyze_pair, reference_start

ROOT = Path(__file__).resolve().parents[1]
TOPREM = str(ROOT / "tests/data/toprem/iso23509_f2_toprem.toml")
FLANKREM = str(ROOT / "tests/data/toprem/iso23509_f2_gear_flankrem.toml")
#: (label, pair, (numpy gap fields, Python edge search))
PAIRS = (("s0003", "s0003", (False, False)),
         ("F.2 from settings", str(ROOT / "examples/machine_settings/iso23509_f2_machine.toml"),
          (False, False)),
         ("F.2 Toprem (compiled)", TOPREM, (False, False)),
         ("F.2 Toprem (numpy path)", TOPREM, (True, True)),
         ("F.2 gear Flankrem (compiled)", FLANKREM, (False, False)),
         ("F.2 gear Flankrem (numpy gaps)", FLANKREM, (True, False)),
         ("F.2 gear Flankrem (Python edges)", FLANKREM, (False, True)),
         ("F.2 gear Flankrem (numpy path)", FLANKREM, (True, True)))
LTE_TORQUE_NM = 64.5


def _timed(fn):
    w, c = time.perf_counter(), time.process_time()
    out = fn()
    return out, time.perf_counter() - w, time.process_time() - c


def _numpy_path(mode=(False, False)):
    """Force the numpy path of the line intersections and / or the Python iteration of
    the edge search (``mode``), or restore the kernels (the default)."""
    from gearcontact.tca import edge_contact
    from gearcontact.tca.gap_kernel import kernel_surface

    def none(surface):
        return None

    stencil.kernel_surface = none if mode[0] else kernel_surface
    edge_contact.kernel_surface = none if mode[1] else kernel_surface


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=3, help="runs; the best is reported")
    ap.add_argument("--lte", action="store_true",
                    help=f"also time the loaded TE at {LTE_TORQUE_NM:g} N m (61 phases)")
    args = ap.parse_args(argv)
    print(f"load average (1, 5, 15 min) before: {os.getloadavg()}")
    built = {}
    for label, source, _ in PAIRS:
        pair = load_pair(source)
        flanks = built[source][1] if source in built else build_flanks(pair)
        built.setdefault(source, (pair, flanks))
    jobs = {}
    for label, source, numpy_path in PAIRS:
        pair, flanks = built[source]

        def tca(pair=pair, flanks=flanks, numpy_path=numpy_path):
            _numpy_path(numpy_path)
            try:
                return analyze_pair(pair, flanks=flanks)[0]
            finally:
                _numpy_path()
        jobs[label] = (pair, flanks, numpy_path, tca)
    best: dict = {}
    results = {}
    for label, (pair, flanks, numpy_path, tca) in jobs.items():
        results[label] = tca()            # first calls (kernels loaded or compiled)
    bending = {}
    if args.lte:
        from gearcontact.ltca.lte import loaded_te
        from gearcontact.ltca.tooth_bending import tooth_bending
        for label, (pair, flanks, _, _) in jobs.items():
            bending[label] = tooth_bending(flanks, pair, side=pair.design_side)
    for _ in range(args.repeat):
        for label, (pair, flanks, numpy_path, tca) in jobs.items():
            res, w, c = _timed(tca)
            _, ws, cs = _timed(lambda pair=pair, flanks=flanks: reference_start(
                pair, flanks, pair.design_side))
            stages = {"analyze_pair (TCA)": (w, c), "  reference_start": (ws, cs), **{
                f"  {k}": (v, float("nan")) for k, v in res.timings_s.items()}}
            if args.lte:
                def lte(pair=pair, flanks=flanks, res=res, numpy_path=numpy_path,
                        label=label):
                    _numpy_path(numpy_path)
                    try:
                        return loaded_te(res, flanks, pair, LTE_TORQUE_NM,
                                         side=pair.design_side, bending=bending[label])
                    finally:
                        _numpy_path()
                _, w, c = _timed(lte)
                stages[f"loaded TE {LTE_TORQUE_NM:g} N m, 61 phases"] = (w, c)
            for stage, (w, c) in stages.items():
                old = best.get((label, stage))
                if old is None or w < old[0]:
                    best[(label, stage)] = (w, c)
    print(f"{'pair':<32} {'stage':<36} {'wall [s]':>9} {'cpu [s]':>9}")
    for (label, stage), (w, c) in best.items():
        print(f"{label:<32} {stage:<36} {w:>9.3f} {c:>9.3f}")
    for label, res in results.items():
        print(f"{label:<32} TE0 p-p {res.cycle.te0_pp_arcsec:.3f} arcsec, edge contacts "
              f"{res.edge_contact_counts}, stencil kinks {list(res.stencil.kinks)}")
    print(f"load average (1, 5, 15 min) after: {os.getloadavg()}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
