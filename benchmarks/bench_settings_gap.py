"""Benchmark: ``design --machine-settings``' contact-ratio check on the family of
docs/machine_settings.md sec. 5 ("The contact-ratio check of machine settings"):
:func:`gearcontact.tca.settings_gap.check_settings_gap` on each pair's standard
settings, its verdict and its cost (CPU seconds, ``time.process_time``), against the
truth recorded in the doc (``tca`` with its defaults on the same settings: gap or not).

For each pair whose settings' mesh has a gap the gap is measured again at finer and
coarser phase counts (:func:`~gearcontact.tca.settings_gap.settings_mesh_gap`, 121, 31
and 16 phases): its width in phase steps, and whether the coarse counts find it.

Usage::

    python benchmarks/bench_settings_gap.py            # the 39 pairs below eps_p 0.85
    python benchmarks/bench_settings_gap.py --all      # the 52 pairs

One process, the pairs in the doc's order (the first pays the numba cache loads; its
cost is printed apart). Wall seconds depend on the load of the shared machine (printed
before and after); CPU seconds are the fairer figures.
"""

from __future__ import annotations

import argparse
import tempfile
import time
import warnings
from pathlib import Path

from cpu_timing import load_average

#: The family (docs/machine_settings.md sec. 5): (z1, z2, offset E mm, gear face mm,
#: pinion spiral angle deg, pressure angle of both sides deg, working depth factor,
#: eps_p recorded, ``tca`` gap recorded). R_m 55 mm, cutter 57.15 mm, gear addendum
#: factor 0.5, pinion face = gear face, right hand, drive side.
FAMILY = (
    (12, 12, 0, 5, 50, 20, 1.3, 0.272, True),
    (14, 14, 0, 5, 50, 20, 1.3, 0.303, False),
    (10, 10, 0, 5, 35, 28, 2, 0.338, True),
    (12, 18, 0, 5, 50, 20, 1.3, 0.352, False),
    (16, 16, 0, 5, 50, 20, 1.3, 0.356, False),
    (8, 8, 0, 6, 45, 20, 2, 0.376, True),
    (16, 16, 0, 5, 45, 20, 1.4, 0.396, False),
    (9, 9, 0, 6, 45, 20, 2, 0.421, True),
    (12, 12, 0, 6, 45, 20, 1.4, 0.424, True),
    (16, 16, 0, 6, 50, 25, 1.3, 0.436, True),
    (16, 16, 0, 5, 50, 20, 2, 0.441, False),
    (16, 16, 0, 5, 55, 20, 1.3, 0.441, True),
    (10, 10, 0, 6, 45, 20, 2, 0.462, True),
    (20, 20, 0, 5, 50, 20, 1.3, 0.463, False),
    (10, 15, 14, 5, 20, 20, 2, 0.472, True),
    (10, 10, 0, 5, 35, 20, 1.5, 0.483, True),
    (10, 10, 0, 5, 35, 20, 2, 0.487, False),
    (8, 8, 0, 6, 35, 20, 2, 0.492, True),
    (8, 12, 0, 5, 45, 20, 1.5, 0.506, True),
    (16, 16, 0, 6, 55, 28, 1.3, 0.509, True),
    (9, 9, 0, 6, 35, 20, 2, 0.551, True),
    (16, 16, 0, 5, 45, 20, 2, 0.567, False),
    (12, 12, 0, 5, 35, 20, 2, 0.584, False),
    (16, 16, 0, 5, 35, 25, 2, 0.59, False),
    (16, 16, 0, 5, 35, 20, 1.3, 0.611, False),
    (10, 10, 0, 5, 20, 20, 2, 0.621, False),
    (10, 10, 0, 8, 35, 20, 2, 0.633, False),
    (10, 15, 14, 8, 30, 20, 2, 0.662, False),
    (16, 16, 0, 5, 35, 30, 2, 0.672, False),
    (10, 15, 14, 8, 20, 20, 2, 0.677, False),
    (16, 16, 0, 5, 35, 20, 1.6, 0.688, False),
    (16, 16, 0, 16, 35, 20, 2, 0.703, False),
    (12, 12, 0, 8, 35, 20, 2, 0.738, False),
    (12, 12, 0, 5, 20, 20, 2, 0.743, False),
    (16, 16, 0, 5, 35, 20, 2, 0.765, False),
    (10, 15, 0, 6, 30, 20, 2, 0.789, False),
    (10, 15, 0, 10, 30, 20, 2, 0.803, False),
    (10, 10, 0, 8, 20, 20, 2, 0.809, False),
    (16, 16, 0, 12, 35, 20, 2, 0.844, False),
    (16, 16, 0, 8, 35, 20, 2, 0.863, False),
    (10, 15, 0, 6, 20, 20, 2, 0.869, False),
    (16, 16, 0, 20, 35, 20, 2, 0.899, False),
    (16, 16, 0, 5, 25, 20, 2, 0.921, False),
    (10, 15, 0, 10, 20, 20, 2, 0.929, False),
    (12, 12, 0, 8, 20, 20, 2, 0.965, False),
    (16, 16, 0, 5, 20, 20, 2, 0.979, False),
    (16, 16, 0, 8, 25, 20, 2, 1.058, False),
    (16, 16, 0, 12, 25, 20, 2, 1.068, False),
    (16, 16, 0, 8, 20, 20, 2, 1.144, False),
    (16, 16, 0, 16, 20, 20, 2, 1.152, False),
    (16, 16, 0, 12, 20, 20, 2, 1.177, False),
    (16, 16, 0, 16, 50, 20, 2, 1.209, False),
)

#: The pair file of one member of the family.
TEMPLATE = """name = "family_{z1}x{z2}"
[teeth]
pinion = {z1}
gear = {z2}
[axes]
shaft_angle_deg = 90.0
offset_mm = {E}
[design]
pinion_hand = "right"
gear_mean_cone_distance_mm = 55.0
pinion_spiral_angle_deg = {beta}
gear_face_width_mm = {face}
pinion_face_width_mm = {face}
working_depth_factor = {kd}
gear_addendum_factor = 0.5
[cutter]
radius_mm = 57.15
point_width_mm = 2.0
edge_radius_mm = 0.4
pressure_angle_drive_deg = {alpha}
pressure_angle_coast_deg = {alpha}
"""


def family_pair(spec, directory: Path):
    """The blank of one ``FAMILY`` row, loaded from a file written in ``directory``."""
    from gearcontact.geometry.pair import load_pair

    z1, z2, E, face, beta, alpha, kd = spec[:7]
    path = directory / f"family_{z1}x{z2}_E{E}_b{face}_{beta}_{alpha}_{kd}.toml"
    path.write_text(TEMPLATE.format(z1=z1, z2=z2, E=float(E), face=float(face),
                                    beta=float(beta), alpha=float(alpha), kd=float(kd)))
    return load_pair(path)


def main() -> None:
    from gearcontact.geometry.basic_settings import standard_machine_pair
    from gearcontact.geometry.contact_path import path_contact_ratio
    from gearcontact.geometry.gear_generation import generation_of
    from gearcontact.geometry.generation import check_generation
    from gearcontact.tca.settings_gap import check_settings_gap, settings_mesh_gap
    from gearcontact.validation import InputRangeError

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--all", action="store_true", help="also the pairs at eps_p >= 0.85")
    args = ap.parse_args()
    rows = [r for r in FAMILY if args.all or r[7] < 0.85]
    print(f"load average {load_average()}")
    print("| z1/z2 | E | face | beta | alpha | k_d | eps_p | doc gap | check CPU s (path) | design "
          "| gap steps of 120 / 60 / 30 / 15 |")
    print("|" + "---|" * 11)
    tally = {"refused gapped": 0, "missed gap": 0, "false refusal": 0, "passed": 0}
    cpu = []
    with tempfile.TemporaryDirectory() as tmp, warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for spec in rows:
            blank = family_pair(spec, Path(tmp))
            boxes = check_generation(blank, contact_ratio=False)
            cut = standard_machine_pair(blank, gear_generation=generation_of(boxes))
            c0 = time.process_time()
            path_contact_ratio(blank, boxes=boxes)      # the prediction alone (right hand)
            path_s = time.process_time() - c0
            c0 = time.process_time()
            try:
                got = check_settings_gap(blank, cut, boxes=boxes)
                verdict = "written" + ("" if got.mesh is None else
                                       f", no gap ({got.mesh.mean_pairs_in_contact:.2f})")
                refused = False
                eps = got.predicted.total
            except InputRangeError as exc:
                refused = True
                verdict = "refused"
                eps = float(str(exc).split("eps_p = ")[1].split(" ")[0])
            seconds = time.process_time() - c0
            cpu.append(seconds - path_s)
            widths = ""
            if refused or spec[8]:
                widths = " / ".join(str(settings_mesh_gap(cut, phases=p).gap_phases)
                                    for p in (121, 61, 31, 16))
            key = ("refused gapped" if refused and spec[8] else "false refusal" if refused
                   else "missed gap" if spec[8] else "passed")
            tally[key] += 1
            z1, z2, E, face, beta, alpha, kd = spec[:7]
            print(f"| {z1}/{z2} | {E} | {face} | {beta} | {alpha} | {kd} | {eps:.3f} | "
                  f"{'gap' if spec[8] else '-'} | {seconds:.2f} ({path_s:.2f}) | {verdict} | {widths} |",
                  flush=True)
    print(f"load average {load_average()}")
    print(tally)
    if len(cpu) > 1:
        rest = sorted(cpu[1:])
        print(f"check CPU s beyond the prediction (the TCA where it ran): first pair "
              f"{cpu[0]:.2f}, the others min {rest[0]:.2f} median {rest[len(rest) // 2]:.2f} "
              f"max {rest[-1]:.2f}")


if __name__ == "__main__":
    main()
