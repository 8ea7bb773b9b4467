"""Benchmark of the mesh table's reach (twin.mesh ``out_of_reach``): CPU time of
:func:`gearcontact.twin.mesh.mesh_table` (best of ``--repeat``, the twin's own set-up:
edge-contact TCA, edge law, 64.5 N·m, rigid) on s0003 coast, the ISO 23509 F.2
machine-settings pair (drive) and MITER_PAIR (drive), with the number of edge rows whose
touch was searched and of rows out of reach, the calls and points of the touch search's
and edge law's gap evaluations (``gap_at`` as ``ltca.patch_field`` and
``ltca.flank_touch`` call it: deterministic, unlike the time) and the load average (the
machine is shared). The TCA is built once per pair, outside the timing.

Run: ``python benchmarks/bench_mesh_reach.py [--phases 61] [--repeat 3] [--pairs
s0003,f2,miter] [--surface]`` (``--surface``: the surface TCA, as tests/twin's F.2
fixture). Runs against whichever ``gearcontact`` is imported (PYTHONPATH), so
that two trees compare on the same machine in the same session.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
F2 = ROOT / "examples" / "machine_settings" / "iso23509_f2_machine.toml"


def _setup(name: str, phases: int, edge_contact: bool):
    from gearcontact.geometry.flank import build_flanks
    from gearcontact.geometry.pair import load_pair, pair_to_toml
    from gearcontact.tca.analysis import analyze_pair
    from gearcontact.tca.synthesis import prepare_pair

    if name == "s0003":
        pair, side = load_pair("s0003"), "coast"
        flanks = build_flanks(pair)
    elif name == "f2":
        pair, side = load_pair(F2), "drive"
        flanks = build_flanks(pair)
    else:
        sys.path.insert(0, str(ROOT / "tests"))
        from design_space import MITER_PAIR, design_space_pair
        path = Path(tempfile.mkdtemp()) / "miter.toml"
        path.write_text(pair_to_toml(design_space_pair(*MITER_PAIR)))
        prepared = prepare_pair(path)
        pair, side, flanks = prepared.pair, "drive", prepared.flank_set()
    tca, flanks = analyze_pair(pair, side=side, phases=phases, edge_contact=edge_contact,
                               flanks=flanks)
    return pair, tca, flanks, side


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--phases", type=int, default=61)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--pairs", default="s0003,f2,miter")
    ap.add_argument("--surface", action="store_true",
                    help="the surface TCA (tests/twin's F.2 fixture) instead of the "
                         "edge-contact one")
    args = ap.parse_args()
    import gearcontact
    import gearcontact.ltca.lte_pairs as lte_pairs
    from gearcontact.twin.mesh import mesh_table

    name = "touch_search" if hasattr(lte_pairs, "touch_search") else "touch_gap_mm"
    search = getattr(lte_pairs, name)
    count = [0]

    def counted(*a, **k):
        count[0] += 1
        return search(*a, **k)

    setattr(lte_pairs, name, counted)
    gaps = [0, 0]           # calls, points of gap_at in the touch search and edge law
    for module in ("gearcontact.ltca.patch_field", "gearcontact.ltca.flank_touch"):
        try:
            mod = importlib.import_module(module)
        except ImportError:     # a tree before the global search
            continue

        def gap_counted(*a, _gap_at=mod.gap_at, **k):
            gaps[0] += 1
            gaps[1] += np.size(a[4])
            return _gap_at(*a, **k)

        mod.gap_at = gap_counted
    print(f"gearcontact from {Path(gearcontact.__file__).parent}")
    for pair_name in args.pairs.split(","):
        pair, tca, flanks, side = _setup(pair_name, args.phases, not args.surface)
        best = float("inf")
        for _ in range(args.repeat):
            count[0] = gaps[0] = gaps[1] = 0
            c = time.process_time()
            mesh = mesh_table(tca, flanks, pair, side=side, torque_nm=64.5)
            best = min(best, time.process_time() - c)
        rows = int(mesh.valid.sum())
        far = int((mesh.valid & mesh.out_of_reach).sum())
        tca_name = "surface" if args.surface else "edge"
        print(f"{pair_name:6s} {side:5s} {tca_name} TCA {args.phases} phases: mesh_table {best:6.2f} s CPU "
              f"(best of {args.repeat}); {rows} rows, {count[0]} touch searches, {far} out "
              f"of reach; gap_at {gaps[0]} calls, {gaps[1]} points; load average "
              f"{os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
