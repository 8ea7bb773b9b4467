"""Benchmark: the typed-settings check's slip search (geometry.known_slips,
geometry.slip_attribution, called by geometry.blank_check) on flanks that disagree with
their blank, screened (the default) against unscreened (``check_flanks(...,
screened=False)``: every candidate solved, as before the screen).

Deterministic counts first: the least-squares solves of the check
(``flank_angles.least_squares`` calls, each one start of the mean-point solve), those of
the known-slip search (``single_slip`` / ``pair_slip``) and of the single-key search
(``slip_attribution``); then CPU seconds of the check (one process, one BLAS thread
asked for through the environment), with the load average before and after. Both
variants must give the same :class:`~gearcontact.geometry.blank_verdict.BlankCheck`
(compared with ``==`` here; tests/geometry/test_slip_screen.py asserts it on
documented cases).

Cases: the published 10 x 41 print's gear typed as ``[machine.gear.*]`` /
``[blade.gear.*]`` tables (tests/geometry/summary_sheets/hypoid_10x41_no16_pair.toml
without its ``[print.gear]``: checked against the pair's ISO 23509 blank, spiral angle
26.94 against 26.80 deg); the generated 13/26 hypoid's gear with modified roll, helical
motion and curved blades (tests/cli/test_design_typed_motion.py's file, its pinion
derived as ``design --machine-settings`` derives it); the shipped
examples/machine_settings/ files (agreeing: no search).

Run: ``OPENBLAS_NUM_THREADS=1 python benchmarks/bench_slip_search.py [--only TEXT]
[--no-unscreened]``. Measured: docs/machine_settings.md sec. 2, "The cost of the slip
search".
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import os
import sys
import time
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

import gearcontact.geometry.blank_check as blank_check  # noqa: E402
import gearcontact.geometry.flank_angles as flank_angles  # noqa: E402
from gearcontact.geometry.blank_statement import printed_stated_blank, stated_blank  # noqa: E402
from gearcontact.geometry.pair import load_pair  # noqa: E402

_COUNT = {"all": 0}
_SOLVE = flank_angles.least_squares


def _counted_solve(*args, **kwargs):
    _COUNT["all"] += 1
    return _SOLVE(*args, **kwargs)


def _counting(module, name: str, label: str):
    """Wrap ``module.name`` so that the solves made inside it add to ``_COUNT[label]``."""
    inner = getattr(module, name)

    def wrapped(*args, **kwargs):
        n0 = _COUNT["all"]
        try:
            return inner(*args, **kwargs)
        finally:
            _COUNT[label] = _COUNT.get(label, 0) + _COUNT["all"] - n0
    setattr(module, name, wrapped)


def _quiet_load(path, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return load_pair(path, **kw)


def print_gear_as_tables():
    """The 10 x 41 print's pair without its ``[print.gear]``: its gear's converted
    settings as tables, checked against the pair's own (ISO 23509) blank."""
    pair = _quiet_load(ROOT / "tests/geometry/summary_sheets/hypoid_10x41_no16_pair.toml")
    return dataclasses.replace(pair, print_gear=())


def hypoid_13x26_typed_motion():
    """tests/cli/test_design_typed_motion.py's gear (HYPOID_TERMS) with the pinion
    ``design --machine-settings`` derives for it (uncrowned)."""
    from cli.test_design_typed_motion import HYPOID_TERMS
    from design_space import generated_hypoid
    from geometry.test_typed_pinion_motion import modified_gear

    from gearcontact.geometry.basic_settings import standard_machine_pair
    from gearcontact.geometry.typed_pinion import typed_gear_machine_pair
    pair = standard_machine_pair(generated_hypoid(), gear_generation="generated")
    gear = {s.side: s for s in pair.machine if s.member == "gear"}
    changes = {side: (st, {"profile_reference_mm": pair.blank.dedendum_gear_mm / math.cos(
        math.radians(gear[side].blade.blade_angle_deg)), **bl} if bl else bl)
        for side, (st, bl) in HYPOID_TERMS.items()}
    return typed_gear_machine_pair(pair, modified_gear(gear, changes),
                                   lengthwise_crowning_um=0.0, blade_profile_crowning_um=0.0)


def shipped(name: str):
    """A shipped example; a file typing the gear alone with the standard pinion ``design
    --machine-settings`` writes beside it (what every other command reads)."""
    def build():
        from gearcontact.geometry.typed_pinion import typed_gear_machine_pair
        pair = _quiet_load(ROOT / "examples" / "machine_settings" / name, gear_alone=True)
        return typed_gear_machine_pair(pair) if pair.typed_gear else pair
    return build


CASES = {"10x41 print gear as tables": print_gear_as_tables,
         "13/26 hypoid, typed motion": hypoid_13x26_typed_motion,
         "examples iso23509_f2_machine": shipped("iso23509_f2_machine.toml"),
         "examples hypoid_10x41_print_gear": shipped("hypoid_10x41_print_gear.toml")}


def run_check(pair, *, screened: bool):
    """``(BlankCheck, solve counts, CPU s)`` of check_pair_blank's flanks."""
    printed = printed_stated_blank(pair)
    for k in list(_COUNT):
        _COUNT[k] = 0
    t0 = time.process_time()
    got = blank_check.check_flanks(pair.machine, stated_blank(pair), screened=screened,
                                   member_stated=None if printed is None else {"gear": printed})
    return got, dict(_COUNT), time.process_time() - t0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--only", default="", help="run the cases whose name contains this")
    ap.add_argument("--no-unscreened", action="store_true",
                    help="skip the unscreened reference (the slow variant)")
    args = ap.parse_args(argv)
    flank_angles.least_squares = _counted_solve
    import gearcontact.geometry.known_slips as known_slips
    _counting(known_slips, "single_slip", "known slips")
    _counting(known_slips, "pair_slip", "two slips")
    blank_check.single_slip = known_slips.single_slip
    blank_check.pair_slip = known_slips.pair_slip
    _counting(blank_check, "_single_keys", "single keys")
    print(f"load average before: {os.getloadavg()}; OPENBLAS_NUM_THREADS="
          f"{os.environ.get('OPENBLAS_NUM_THREADS')}")
    print("| case | variant | solves (all / known slips / two slips / single keys) "
          "| CPU s | flanks agreeing | same result |")
    print("|---|---|---|---|---|---|")
    for name, build in CASES.items():
        if args.only not in name:
            continue
        pair = build()
        results = {}
        for screened in (True, False) if not args.no_unscreened else (True,):
            got, n, cpu = run_check(pair, screened=screened)
            results[screened] = got
            same = "" if screened else str(got == results[True])
            print(f"| {name} | {'screened' if screened else 'unscreened'} | {n['all']} / "
                  f"{n.get('known slips', 0)} / {n.get('two slips', 0)} / "
                  f"{n.get('single keys', 0)} | {cpu:.2f} | "
                  f"{sum(f.agrees for f in got.flanks)} of {len(got.flanks)} | {same} |",
                  flush=True)
    print(f"load average after: {os.getloadavg()}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
