"""Readable Markdown summary of the main job (``summary.md``)."""

from __future__ import annotations

import re
from pathlib import Path

from ..contract.stencil import STENCIL_SPACING_MM
from .law_range import law_range_warning
from .markdown import md_table, pct_diff
from .multitooth import multitooth_section

__all__ = ["DESIGN_POINT_HEADER", "TORQUE_HEADER", "cpu_latency_rows", "design_point_table_rows",
           "lte_rows", "torque_rows", "write_summary"]


def lte_rows(lte, pub: dict) -> list[list]:
    """Rows (quantity, ours, published) of the loaded-TE comparison
    (:class:`~gearcontact.ltca.lte.LoadedTE`; also the ``lte`` item of the
    reproduction report). The published column holds only what ``pub`` (the pair's
    published values, ``data/published/<pair>.json``) gives: None for a pair without."""
    pp, comp = pub.get("lte_pp_arcsec", {}), pub.get("compliance_mm_per_n", {})
    shares = pub.get("multi_tooth_load_share_pct")     # the published pairs with bending
    k0 = lte.reference_index
    share = lte.pair_loads_lcp_n[:, k0] / lte.pair_loads_lcp_n[:, k0].sum()
    return [
        ["TE0 peak-to-peak (arcsec)", lte.te0_pp_arcsec, pub.get("te0_pp_arcsec")],
        ["TE_LCP peak-to-peak (arcsec)", lte.te_lcp_pp_arcsec, pp.get("lcp")],
        ["TE_pre peak-to-peak (arcsec)", lte.te_pre_pp_arcsec, pp.get("preview")],
        ["TE_pre vs TE_LCP p-p (%)", pct_diff(lte.te_pre_pp_arcsec, lte.te_lcp_pp_arcsec),
         pct_diff(pp["preview"], pp["lcp"]) if pp else None],
        ["contact compliance LCP at P0 (mm/N)", lte.compliance_lcp_mm_per_n, comp.get("lcp")],
        ["contact compliance preview at P0 (mm/N)", lte.compliance_pre_mm_per_n,
         comp.get("preview")],
        ["mesh compliance LCP / preview at P0 (mm/N)",
         f"{lte.mesh_compliance_lcp_mm_per_n:.4g} / {lte.mesh_compliance_pre_mm_per_n:.4g}",
         None],
        ["mean loaded rotation LCP / preview (arcsec)",
         f"{lte.rotation_lcp_arcsec.mean():.4g} / {lte.rotation_pre_arcsec.mean():.4g}", None],
        ["active pairs (LCP)", f"{lte.active_lcp.min()}-{lte.active_lcp.max()}",
         f"{len(shares)} engaged" if shares else None],
        ["load shares at P0 (LCP, %)", ", ".join(
            f"{o:+d}: {100 * x:.1f}" for o, x in zip(lte.pair_offsets, share) if x > 0),
         " / ".join(f"{x:g}" for x in shares) + " (with bending)" if shares else None],
        ["phases with edge contact / all LCPs converged",
         f"{int(lte.edge_contact.sum())} / {lte.converged}", None],
        ["largest load dropped beyond the edge window (N)",
         float(lte.dropped_load_n.max()), None]]


#: Columns of :func:`torque_rows` (pressures in MPa).
TORQUE_HEADER = ["torque (N·m)", "W (N)", "W published (N)", "preview p_max", "LCP mean",
                 "LCP p90", "LCP peak", "preview vs p90 (%)", "peak / p90", "delta (um)",
                 "mesh rotation (arcsec)", "contact cells", "edge contact"]


def torque_rows(cases, pub: dict) -> list[list]:
    """Rows of the preview-vs-LCP table over the torques (:data:`TORQUE_HEADER`;
    cases are :class:`~gearcontact.ltca.pair_ltca.PairLoadCase`)."""
    loads = pub.get("loads_n", {})
    return [[c.torque_nm, c.load_n, loads.get(f"{c.torque_nm:g}"), c.preview.p_max_mpa,
             c.patch.p_mean_mpa, c.patch.p90_mpa, c.patch.p_peak_mpa,
             pct_diff(c.preview.p_max_mpa, c.patch.p90_mpa), c.patch.p_peak_mpa / c.patch.p90_mpa,
             1e3 * c.patch.delta_mm, c.mesh_rotation_arcsec, c.patch.n_contact_cells,
             c.edge_contact] for c in cases]


def _lte_section(lte, pub: dict) -> list[str]:
    """Markdown of the loaded-TE section (:class:`~gearcontact.ltca.lte.LoadedTE`)."""
    teeth = "with tooth bending" if lte.bending else "rigid teeth"
    out = [f"## Loaded transmission error at {lte.torque_nm:g} N·m ({teeth})", "",
           f"{len(lte.phi1_rad)} phases over one pinion pitch; every tooth pair within reach "
           "with its own gap field, one shared gear rotation, torque balance; TE_pre from "
           "the Hamrock–Brewe approach of each pair, scaled where a flank boundary cuts "
           "its patch by the LCP-calibrated compliance of the twin's edge law.", ""]
    out.append(md_table(["quantity", "ours", "published"], lte_rows(lte, pub)))
    return out + [
        "", "The contact compliance is d(delta)/dW of the transmitting pair alone; the mesh "
        "compliance lets the neighbouring pairs share the torque. Pairs up to half a pitch "
        "beyond the ends of their contact path stay in as edge contacts (LCP: field trimmed "
        "at the flank boundary; preview: Hertzian with the nearest interior curvatures, "
        "its approach scaled by the edge law's c).",
        "",
        "Figure: ![loaded TE](lte.png)", ""]


#: Columns of :func:`design_point_table_rows`.
DESIGN_POINT_HEADER = ["target", "published", "ours", "tolerance", "met"]


def design_point_table_rows(result, pub: dict) -> list[list] | None:
    """Rows (:data:`DESIGN_POINT_HEADER`) of the published design point against this
    set-up at the design torque (docs/calibration.md), or None without published P0.
    ``result`` is an :class:`~.analyze.Analysis`."""
    from ..tca.calibration import CalibrationTargets, design_point_rows
    from ..tca.design_point import design_point_at

    if "design_point_mm" not in pub:
        return None
    pair, tca = result.pair, result.tca
    targets = CalibrationTargets.from_published(pub)
    side = result.side
    dp = design_point_at(pair, result.flanks.flank("pinion", side),
                         result.flanks.flank("gear", side), tca.mean_point,
                         te0_pp_arcsec=tca.cycle.te0_pp_arcsec, torque_nm=targets.torque_nm)
    return [[f"{r.target} ({r.unit})", r.published, r.achieved, r.tolerance,
             "yes" if r.met else "NO"]
            for r in design_point_rows(dp, targets, offset_mm=pair.offset_mm)]


def _design_point_section(result, pub: dict) -> list[str]:
    """Published design point vs this set-up (docs/calibration.md) at the design torque."""
    rows = design_point_table_rows(result, pub)
    if rows is None:
        return []
    pair, side = result.pair, result.side
    note = ("the preset calibrated to the published design point: `gearcontact design "
            "--pair s0003-centred --calibrate` reproduces it; the targets it cannot meet "
            "together and why are in docs/calibration.md" if pair.name == "s0003" else
            "this set-up is not calibrated to the published design point (the centred "
            "set-up `s0003-centred` is the Hertzian reference case), so P0 differs by design")
    return [f"## Design point ({side} flank pair) vs the published one", "",
            md_table(DESIGN_POINT_HEADER, rows), "",
            f"P0 as frame invariants (radius / axial position on each member); ellipse "
            f"angle in the right-handed flank frame; {note}.", ""]


def _precision_section(precision) -> list[str]:
    """Gap-kernel error at the hardware widths and the worst error / bound ratio."""
    by_coord, by_normal = precision
    hw = next(p for p in by_coord if p.coord_frac == 16)
    worst = max(p.max_bound_ratio for p in by_coord + by_normal)
    return ["## Fixed-point precision of the gap kernel", "",
            md_table(["quantity", "value"], [
                ["max / RMS gap error at the hardware widths cf 16, rf 19 (um)",
                 f"{hw.max_error_mm * 1e3:.4g} / {hw.rms_error_mm * 1e3:.4g}"],
                ["first-order bound there (um)", hw.bound_mm * 1e3],
                ["largest error / bound over all widths (cf 8-24, rf 12-24)", worst]]),
            "", "Figure: ![precision](precision.png) (data: precision.csv)", ""]


def _latency_section(lat) -> list[str]:
    """RTL cycle counts (constants, zero spread); the CPU latency is in run.json."""
    from .latency import PAPER_JITTER, PAPER_US, core_cycles

    rows = [[name, cycles, 0] for name, cycles in core_cycles().items()]
    return ["## Determinism and latency", "",
            md_table(["RTL core", "cycles go -> done", "spread (cycles)"], rows), "",
            "Every RTL run in the test suite takes exactly these cycles (asserted), for "
            "any input.", "",
            f"The fp64 preview's CPU latency on this machine is a timing, so it is in "
            f"run.json (`timings_s.preview_cpu`: median, p99, jitter), not here; published "
            f"CPU: median {PAPER_US:g} us, jitter {100.0 * PAPER_JITTER:g} %.", ""]


def _existing_figures(text: str, folder: Path) -> str:
    """Drop the Markdown image links whose PNG is not in ``folder`` (``--no-figures``)
    and a "Figure(s):" label left without images."""
    def keep(m):
        return m.group(0) if (folder / m.group(1)).is_file() else ""

    lines = []
    for line in text.split("\n"):
        new = re.sub(r"!\[[^]]*\]\(([^)\s]+\.png)\)", keep, line)
        if new != line:
            new = " ".join(new.split())
            if "![" not in new:
                new = re.sub(r"^Figures?:\s*", "", new)
                new = re.sub(r"^\(data: ([^)]*)\)$", r"Data: \1", new)
            if not new:
                continue
        lines.append(new)
    return "\n".join(lines)


def cpu_latency_rows(lat) -> list[list]:
    """Rows (quantity, ours, published) of the fp64 preview's CPU latency
    (:class:`~.latency.ScalarLatency`; the reproduction report's latency item)."""
    from .latency import PAPER_JITTER, PAPER_US

    return [["median per call (us)", lat.p50_us, PAPER_US],
            ["p99 per call (us)", lat.p99_us, None],
            ["jitter p99/p50 - 1 (%)", 100.0 * lat.jitter, 100.0 * PAPER_JITTER]]


def _machine_lines(result) -> list[str]:
    """The line under the blank's table of a pair whose flanks are cut from machine
    settings: which flanks, formate or generated, and what the typed-settings check
    found (docs/machine_settings.md sec. 2); nothing for a pair without settings."""
    setups = getattr(result.pair, "machine", None) or ()
    if not setups:
        return []
    cuts: dict = {}
    for s in setups:
        cuts.setdefault((s.member, "formate" if s.settings.formate else "generated"),
                        []).append(s.side)
    what = ", ".join(f"{m} {' and '.join(sides)} {how}" for (m, how), sides in cuts.items())
    check = getattr(result, "settings_check", None)
    if check is not None and check.warnings:
        found = (f"{len(check.warnings)} of {len(setups)} flanks do not agree with the "
                 "blank (the warning above)")
    elif check is not None:
        found = "every flank agrees with the blank within its tolerance"
    else:
        found = "not run"
    return ["", f"Flanks cut from machine settings (the pair's [machine.*] / [blade.*] "
            f"tables): {what}. The typed-settings check: {found} "
            "(docs/machine_settings.md sec. 2)."]


def _warned(head: str, lines) -> list[str]:
    """``head`` and the warning ``lines`` as a list below it (nothing without lines)."""
    if not lines:
        return []
    return [head, "", *(f"- {line.removeprefix('warning: ')}" for line in lines), ""]


def write_summary(result, path, *, published: dict | None = None) -> Path:
    """Write the summary of an :class:`~.analyze.Analysis` as Markdown at ``path``."""
    from .. import __version__

    pub = published or {}
    pair, tca, cases = result.pair, result.tca, result.cases
    blank = pair.blank.as_dict()
    cyc, rc, ell = tca.cycle, tca.mean_curvature, tca.mean_ellipse
    out = [f"# {pair.name}: tooth-contact analysis", "",
           f"gearcontact {__version__}. Units: mm, N, MPa, arcsec. "
           "Published values (where given) are from the original study, for comparison.",
           ""]
    if getattr(result, "easeoff_note", ""):
        head, _, toml = result.easeoff_note.partition("\n")
        out += ["**Ease-off synthesized.** " + head, "", "```toml", toml.strip(), "```", ""]
    check = getattr(result, "settings_check", None)
    # the typed machine settings do not cut the blank's tooth: said before any result
    out += _warned("**Machine settings against the blank: warning.** The flanks cut from "
                   "the pair's [machine.*] tables do not all agree with its blank "
                   "(docs/machine_settings.md sec. 2):", getattr(check, "warnings", ()))
    # a different check: the pinion's ease-off against the typed gear's conjugate
    out += _warned("**Pinion ease-off: hollow.** A pinion flank cut from the pair's "
                   "[machine.*] tables is hollow against the typed gear's conjugate pinion "
                   "(docs/machine_settings.md sec. 2, \"The hollow ease-off warning\"):",
                   getattr(check, "hollow_warnings", ()))
    out += ["## Blank (ISO 23509 Method 1)", ""]
    out.append(md_table(["quantity", "ours", "published"], [
        ["pinion pitch angle (deg)", blank["pitch_angles_deg"][0], pub.get("pitch_angle_pinion_deg")],
        ["gear pitch angle (deg)", blank["pitch_angles_deg"][1], pub.get("pitch_angle_gear_deg")],
        ["pinion / gear spiral angle (deg)",
         f"{blank['spiral_angles_deg'][0]:.3f} / {blank['spiral_angles_deg'][1]:.3f}", None],
        ["gear mean cone distance (mm)", blank["mean_cone_distances_mm"][1],
         pub.get("mean_cone_distance_gear_mm")]]))
    out += _machine_lines(result)
    out += ["", "## Unloaded TCA", ""]
    out.append(md_table(["quantity", "ours", "published"], [
        ["TE0 peak-to-peak (arcsec)", cyc.te0_pp_arcsec, pub.get("te0_pp_arcsec")],
        ["max. pairs in contact", int(cyc.pairs_in_contact.max()), None],
        ["A-, B- at P0 (1/mm)", f"{rc.A_minus_per_mm:.5g}, {rc.B_minus_per_mm:.5g}", None],
        ["paint ellipse 2a x 2b (mm) at 6.35 um",
         f"{2 * ell.semi_major_mm:.3f} x {2 * ell.semi_minor_mm:.3f}", None],
        ["paint ellipse angle from lengthwise (deg)", ell.angle_deg, None],
        ["contact pattern inside the flank", bool(tca.pattern_on_flank.all()), None],
        ["edge contact (phases per flank edge)",
         ", ".join(f"{k} {v}" for k, v in tca.edge_counts.items()) or "none", None]]))
    out += ["", "Figures: ![TE0](te0.png) ![contact pattern](contact_pattern.png)", ""]
    out += _design_point_section(result, pub)
    out += ["## Loaded contact: preview vs LCP (single pair at P0, rigid teeth)", ""]
    out.append(md_table(TORQUE_HEADER, torque_rows(cases, pub)))
    if pub:
        out += ["", f"Published: preview vs p90 mean error {pub['preview_vs_p90_mean_error_pct']} % "
                f"(per torque {pub['preview_vs_p90_error_range_pct'][0]} % to "
                f"{pub['preview_vs_p90_error_range_pct'][1]} %), edge peak about "
                f"{pub['edge_peak_over_body']}x the body pressure, rigid-patch mesh rotation "
                f"{pub['mesh_rotation_rigid_arcsec_at_design']} arcsec at "
                f"{pub['design_torque_nm']} N·m."]
    design = min(cases, key=lambda c: abs(c.torque_nm - pub.get("design_torque_nm", 64.5)))
    p = design.preview
    out += ["", f"### Preview at the design torque {design.torque_nm:g} N·m", ""]
    out.append(md_table(["quantity", "ours", "published"], [
        ["2a x 2b (mm)", f"{2 * p.a_mm:.3f} x {2 * p.b_mm:.3f}",
         f"{pub['preview_ellipse_2a_mm']} x {pub['preview_ellipse_2b_mm']}" if pub else None],
        ["p_max (MPa)", p.p_max_mpa, pub.get("preview_p_max_mpa_at_design")],
        ["k = a/b", p.k, None]]))
    out += ["", "Figures: ![pressure maps](pressure_maps.png) "
            "![pressure vs load](pressure_vs_load.png)", "",
            "## Fixed-point preview (golden model = RTL specification)", ""]
    rows = []
    for c, ref, g, ch, g_st, ch_st in zip(cases, result.reference, result.golden,
                                          result.golden_chain, result.golden_status,
                                          result.chain_status):
        # a flagged or unevaluated fixed-point result has no value (its outputs read 0)
        g_ok, ch_ok = g_st == "ok", ch_st == "ok"
        rows.append([c.torque_nm, ref.p_max_mpa, ref.mode,
                     g.p_max_mpa if g_ok else f"missing ({g_st})",
                     pct_diff(g.p_max_mpa, ref.p_max_mpa) if g_ok else None,
                     g.mode if g_ok else None,
                     ch.p_max_mpa if ch_ok else f"missing ({ch_st})",
                     pct_diff(ch.p_max_mpa, c.preview.p_max_mpa) if ch_ok else None,
                     "none" if ch_ok else ch_st, ch.mode if ch_ok else None,
                     None if ch is None else ch.cycles])
    out.append(md_table(["torque (N·m)", "fp64 p_max", "fp64 mode", "golden D p_max",
                       "golden D vs fp64 (%)", "golden D mode",
                       "golden C->D p_max (stencil)", "C->D vs fp64 ellipse (%)",
                       "C->D flags", "C->D mode", "C->D cycles"], rows))
    beyond = law_range_warning(result.reference, result.golden, result.golden_chain)
    if beyond is not None:
        out += ["", f"**{beyond}.**"]
    out += ["", "Stage D here is the line core: the Hertz ellipse, or the Hertz line contact "
            "of the flank's contact line where the flank truncates a longer ellipse (mode "
            "`line`). The C->D chain is the line chain (the fit core into the line core, "
            "811 cycles) with the same contact line.", ""]
    if tca.stencil.on_flank.all():
        out += [f"The C->D column fits the 7 x 7 hardware stencil ({STENCIL_SPACING_MM:g} "
                "mm spacing) of the real gap field, so it also carries the curvature-fit "
                "error of a non-quadratic surface.", ""]
    else:       # tca.stencil.hardware_stencil: a window over the flank edge
        out += [f"The 7 x 7 hardware stencil ({STENCIL_SPACING_MM:g} mm spacing) at P0 "
                "reaches beyond the flank, so it is the osculating quadric of the gap there: "
                "the C->D column carries the TCA's curvatures, without a curvature-fit "
                "error.", ""]
    if getattr(tca.stencil, "kinks", ()):
        out += ["The hardware stencil at P0 straddles the blade-relief kink "
                f"({', '.join(tca.stencil.kinks)}): the flank's curvature is not defined "
                "across it and the gap there is no quadric, so the C->D column's fitted "
                "curvatures are not the flank's (docs/machine_settings.md sec. 1).", ""]
    if getattr(result, "lte", None) is not None:
        out += _lte_section(result.lte, pub)
    if getattr(result, "multitooth", None) is not None:

        out += multitooth_section(result.multitooth, pub)
    if getattr(result, "precision", None) is not None:
        out += _precision_section(result.precision)
    if getattr(result, "latency", None) is not None:
        out += _latency_section(result.latency)
    out += ["Run times: in run.json of `gearcontact analyze` (`Analysis.timings_s` in "
            "Python); no result file holds a timing, so two identical runs write identical "
            "files."]
    path = Path(path)
    path.write_text(_existing_figures("\n".join(out) + "\n", path.parent))
    return path
