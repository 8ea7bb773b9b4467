"""Benchmark: the typed-settings check's parts in the order it runs them
(docs/machine_settings.md sec. 2, "The order of the check" and "Library calls given no
flanks"): on the F.2 example with one warned slip, the blank comparison (what the
warnings wait for now; the command line's error path makes it once, it made it twice
before session 27) and the ease-off shape's flank work (what they also waited for
before); on F.3's standard settings with a generated gear, the check with the pinions
deferred (the reader's), measured (``checked_settings``, the library calls given no
flanks) and ``design``'s.

CPU seconds (``time.process_time``), best of ``--repeat`` warm calls in one process; the
load average printed before and after (the machine is shared).

Usage::

    python benchmarks/bench_settings_check_order.py [--repeat 3]
"""

from __future__ import annotations

import argparse
import tempfile
import warnings
from pathlib import Path

from cpu_timing import best_cpu_s, load_average

ROOT = Path(__file__).resolve().parents[1]
F2 = ROOT / "examples" / "machine_settings" / "iso23509_f2_machine.toml"
#: (name, typed right, typed wrong): slips the check warns about (not gross).
SLIPS = (("gear MD -0.24", "machine_centre_to_back_mm = 0.0",
          "machine_centre_to_back_mm = -0.24"),
         ("pinion sliding base sign", "sliding_base_mm = 2.2936", "sliding_base_mm = -2.2936"),
         ("pinion ratio of roll typed cradle / work", "ratio_of_roll = 2.785714",
          "ratio_of_roll = 0.358974"))


def main() -> None:
    from gearcontact.geometry.basic_settings import standard_machine_pair
    from gearcontact.geometry.blank_check import check_pair_blank
    from gearcontact.geometry.easeoff_shape import check_easeoff_shape
    from gearcontact.geometry.flank_angles import measure_pair_mean_points
    from gearcontact.geometry.pair import load_pair
    from gearcontact.geometry.settings_check import check_settings, checked_settings

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    print(f"load average {load_average()}")
    print("| slip (a warning) | blank comparison CPU s | ease-off shape CPU s |")
    print("|---|---:|---:|")
    text = F2.read_text()
    with tempfile.TemporaryDirectory() as tmp, warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name, right, wrong in SLIPS:
            assert right in text, right
            path = Path(tmp) / "slip.toml"
            path.write_text(text.replace(right, wrong, 1))
            pair = load_pair(path)
            check_easeoff_shape(pair)                                   # warm
            blank = best_cpu_s(lambda: check_pair_blank(
                pair, measured=measure_pair_mean_points(pair)), args.repeat)[0]
            shape = best_cpu_s(lambda: check_easeoff_shape(pair), args.repeat)[0]
            print(f"| {name} | {blank:.2f} | {shape:.2f} |", flush=True)
        pair = standard_machine_pair(load_pair(ROOT / "examples" / "iso23509_f3.toml"),
                                     gear_generation="generated")
        check_settings(pair, easeoff_generated=True)                    # warm
        deferred = best_cpu_s(lambda: check_settings(pair), args.repeat)[0]
        library = best_cpu_s(lambda: checked_settings(pair), args.repeat)[0]
        design = best_cpu_s(lambda: check_settings(pair, easeoff_generated=True), args.repeat)[0]
    print(f"F.3, generated gear: deferred {deferred:.2f} s, checked_settings {library:.2f} s, "
          f"design's {design:.2f} s CPU")
    print(f"load average {load_average()}")


if __name__ == "__main__":
    main()
