"""Items of the evaluation report on the loaded contact (docs/spec.md sec. 8, items 1,
2, 6, 7): each builds one :class:`~.document.Section` from the main job's
:class:`~.analyze.Analysis` and the published values, adding only the measurements
that explain a difference (:mod:`.accuracy_studies`, the loaded TE with tooth bending).
Each item's status is computed from its headline quantities (:mod:`.headline`).
"""

from __future__ import annotations

import math
from dataclasses import asdict

import numpy as np

from .accuracy_studies import HERTZ_P90_OVER_P0, bearing_sweep, grid_study
from .document import Section, Table, format_cell, pct_diff
from .evaluation_sharing import sharing_explanation
from .headline import judge, judged_section

__all__ = ["accuracy_section", "design_case", "lte_section", "multitooth_section",
           "pressure_map_section"]


def design_case(analysis, pub):
    """The main job's load case nearest the published design torque."""
    t = pub.get("design_torque_nm", 64.5)
    return min(analysis.cases, key=lambda c: abs(c.torque_nm - t))


_STUDY_HEADER = ["case", "P0 pinion / gear radius (mm)", "preview p_max (MPa)",
                 "LCP p90 (MPa)", "LCP peak (MPa)", "preview vs p90 (%)", "peak / p90",
                 "contact cells", "mesh rotation (arcsec)"]


def _study_rows(rows, published) -> list[list]:
    return [[r.label, f"{r.pinion_radius_mm:.2f} / {r.gear_radius_mm:.2f}",
             r.preview_p_max_mpa, r.p90_mpa, r.p_peak_mpa, r.preview_vs_p90_pct,
             r.peak_over_p90, r.contact_cells, r.mesh_rotation_arcsec, published]
            for r in rows]


def accuracy_section(analysis, pub, settings) -> Section:
    from ..geometry.pair import load_pair
    from .summary import TORQUE_HEADER, torque_rows

    cases = analysis.cases
    lo, hi = pub.get("preview_vs_p90_error_range_pct", (None, None))
    header = TORQUE_HEADER + ["preview vs p90 published (%)", "peak / body published"]
    rows = [r + [f"{lo} to {hi}" if lo is not None else None,
                 f"~{pub['edge_peak_over_body']}" if "edge_peak_over_body" in pub else None]
            for r in torque_rows(cases, pub)]
    err = np.array([pct_diff(c.preview.p_max_mpa, c.patch.p90_mpa) for c in cases])
    design = design_case(analysis, pub)
    name = analysis.pair.name
    centred = analysis.pair if name.endswith("-centred") else load_pair(f"{name}-centred")
    sweep = bearing_sweep(centred, design.torque_nm, steps=settings["bearing_steps"])
    lengthwise = bearing_sweep(centred, design.torque_nm, steps=settings["lengthwise_steps"])
    worst = min(lengthwise, key=lambda r: r.preview_vs_p90_pct)
    end = "heel" if worst.gear_radius_mm > sweep[0].gear_radius_mm else "toe"
    grid = grid_study(analysis.tca, analysis.flanks, analysis.pair, design.torque_nm,
                      cells=settings["grid_cells"], side=analysis.side)
    hertz_err = 100.0 * (1.0 / HERTZ_P90_OVER_P0 - 1.0)
    pub_mean = pub.get("preview_vs_p90_mean_error_pct")
    if pub_mean is None or lo is None:
        depth = "the study published no error to compare the depth with"
    elif lo <= err.mean() <= hi:
        depth = (f"its mean error {err.mean():+.1f} % lies inside the published range, "
                 f"{'below' if err.mean() < pub_mean else 'above'} the published mean "
                 f"{pub_mean} %")
    elif err.mean() < lo:
        depth = (f"its mean error {err.mean():+.1f} % is below the published range: it lies "
                 f"further into the edge than the published bearing")
    else:
        depth = (f"its mean error {err.mean():+.1f} % is above the published range: it lies "
                 f"less far into the edge than the published bearing")
    first, last = sweep[0], sweep[-1]
    w_pub = pub["loads_n"][f"{design.torque_nm:g}"]
    cells_pub = pub.get("lcp_contact_cells_at_design")
    near = min(grid, key=lambda r: abs(r.contact_cells - cells_pub)) if cells_pub else None
    text = [
        f"Preview p_max against the LCP p90 of the single loaded pair at P0 over the four "
        f"torques: ours {err.mean():+.1f} % on average ({err.min():+.1f} % to "
        f"{err.max():+.1f} %), published {pub.get('preview_vs_p90_mean_error_pct')} % "
        f"({lo} % to {hi} %). The preview is Hertzian (p_max ~ W^(1/3)); the LCP is not "
        f"where the patch meets a flank edge.",
        f"Why: for a Hertz patch p90 = sqrt(0.9) p0, so an exact preview reads "
        f"{hertz_err:+.1f} % against p90. The centred set-up of the same pair ({centred.name}) "
        f"measures {first.preview_vs_p90_pct:+.1f} % (peak / p90 {first.peak_over_p90:.2f}) "
        f"at {design.torque_nm:g} N·m. Moving its bearing toward the pinion tip by the "
        f"ease-off alone (table 'bearing toward the tip': P0 from {first.pinion_radius_mm:.2f} "
        f"to {last.pinion_radius_mm:.2f} mm from the pinion axis) turns the error to "
        f"{last.preview_vs_p90_pct:+.1f} % while the cell peak grows from "
        f"{first.p_peak_mpa:.0f} to {last.p_peak_mpa:.0f} MPa (peak / p90 "
        f"{last.peak_over_p90:.1f})"
        + (": the published pattern (preview below p90, edge peak several times the body) "
           "appears as the patch reaches the flank edge."
           if last.preview_vs_p90_pct < 0 and last.peak_over_p90 > 3 else
           ", short of the published pattern (preview below p90, edge peak several times "
           "the body).")
        + f" The calibrated {name} bearing sits at the tip edge (peak / p90 "
        f"{design.patch.p_peak_mpa / design.patch.p90_mpa:.1f} at the design torque); "
        f"{depth}; how far beyond the edge the published bearing lay was not published "
        f"(docs/calibration.md), and we do not tune to the published error. Moving the "
        f"bearing lengthwise instead "
        f"(spiral angle; table 'bearing toward toe / heel') gives the same signature at "
        f"the {end}: {worst.preview_vs_p90_pct:+.1f} % with peak / p90 "
        f"{worst.peak_over_p90:.1f} and a mesh rotation of {worst.mesh_rotation_arcsec:.1f} "
        f"arcsec (published rigid-patch rotation "
        f"{pub.get('mesh_rotation_rigid_arcsec_at_design')} arcsec; the centred set-up "
        f"{first.mesh_rotation_arcsec:.1f}).",
        f"Our normal loads are {pct_diff(design.load_n, w_pub):+.1f} % off the published ones "
        f"at the same torques: the lever of the normal force about the gear axis at our P0 "
        f"is {design.lever_mm:.2f} mm against the {1e3 * design.torque_nm / w_pub:.2f} mm "
        f"the published loads imply (docs/geometry.md sec. 2).",
        (f"Grid resolution: the published adaptive grid has {cells_pub} contacting cells at "
         f"the design torque; on our uniform grid the closest count is {near.contact_cells} "
         f"cells ({near.label}), where the preview reads {near.preview_vs_p90_pct:+.1f} % "
         f"against p90 (table 'grid resolution').") if near else "",
    ]
    tables = [
        Table("Preview vs LCP over the torques (pressures in MPa)", header, rows),
        Table(f"Bearing toward the tip: {centred.name} with the {centred.design_side} "
              f"ease-off changed, {design.torque_nm:g} N·m",
              _STUDY_HEADER + ["published preview vs p90 (%)"],
              _study_rows(sweep, f"{lo} to {hi}")),
        Table(f"Bearing toward toe / heel: {centred.name} with the spiral-angle term of "
              f"the {centred.design_side} ease-off changed, {design.torque_nm:g} N·m",
              _STUDY_HEADER + ["published preview vs p90 (%)"],
              _study_rows(lengthwise, f"{lo} to {hi}")),
        Table(f"Grid resolution: {name} at {design.torque_nm:g} N·m",
              _STUDY_HEADER + ["published contact cells"], _study_rows(grid, cells_pub)),
    ]
    peak_ratio = [c.patch.p_peak_mpa / c.patch.p90_mpa for c in cases]
    heads = judge("accuracy", {
        "preview_vs_p90_mean_pct": (float(err.mean()), pub_mean),
        "preview_vs_p90_per_torque_pct": (err.tolist(), (lo, hi)),
        "peak_over_p90": (peak_ratio, pub.get("edge_peak_over_body"))}, pub)
    return judged_section(
        "accuracy", 1, "Accuracy: preview vs full LCP over the load", heads,
        [x for x in text if x], tables,
        [("pressure_vs_load.png", "preview p_max and LCP mean / p90 / peak over "
                                  "the load (log-log) with the W^(1/3) law")],
        {"torque_nm": [c.torque_nm for c in cases],
         "load_n": [c.load_n for c in cases],
         "preview_p_max_mpa": [c.preview.p_max_mpa for c in cases],
         "lcp_mean_mpa": [c.patch.p_mean_mpa for c in cases],
         "lcp_p90_mpa": [c.patch.p90_mpa for c in cases],
         "lcp_peak_mpa": [c.patch.p_peak_mpa for c in cases],
         "preview_vs_p90_pct": err.tolist(),
         "preview_vs_p90_mean_pct": float(err.mean()),
         "edge_contact": [bool(c.edge_contact) for c in cases],
         "hertz_patch_preview_vs_p90_pct": hertz_err,
         "bearing_sweep": {"pair": centred.name, "side": centred.design_side,
                           "rows": [asdict(r) for r in sweep]},
         "lengthwise_sweep": [asdict(r) for r in lengthwise],
         "grid_study": [asdict(r) for r in grid],
         "published": {k: pub.get(k) for k in (
             "preview_vs_p90_mean_error_pct", "preview_vs_p90_error_range_pct",
             "edge_peak_over_body", "loads_n", "lcp_contact_cells_at_design")}})


def pressure_map_section(analysis, pub) -> Section:
    from .summary import DESIGN_POINT_HEADER, design_point_table_rows

    c = design_case(analysis, pub)
    p, e = c.preview, c.patch.ellipse
    dp_rows = design_point_table_rows(analysis, pub) or []
    rows = [
        ["preview 2a at W (mm)", 2 * p.a_mm, pub.get("preview_ellipse_2a_mm")],
        ["preview 2b at W (mm)", 2 * p.b_mm, pub.get("preview_ellipse_2b_mm")],
        ["preview p_max (MPa)", p.p_max_mpa, pub.get("preview_p_max_mpa_at_design")],
        ["LCP moment ellipse 2a x 2b (mm)",
         f"{2 * e.semi_major_mm:.3f} x {2 * e.semi_minor_mm:.3f}", None],
        ["LCP contact cells", c.patch.n_contact_cells, pub.get("lcp_contact_cells_at_design")],
        ["LCP mesh rotation, rigid teeth (arcsec)", c.mesh_rotation_arcsec,
         pub.get("mesh_rotation_rigid_arcsec_at_design")],
        ["edge contact", c.edge_contact, "tip edge (peak ~5x body)"],
    ]
    missed = [r[0] for r in dp_rows if r[-1] != "yes"]
    pub_w = pub["loads_n"][f"{c.torque_nm:g}"]
    pub_pmax = pub["preview_p_max_mpa_at_design"]
    pub_ab = 0.25 * pub["preview_ellipse_2a_mm"] * pub["preview_ellipse_2b_mm"]
    text = [f"LCP pressure over the contact band at {c.torque_nm:g} N·m (W = "
            f"{c.load_n:.0f} N) with the preview ellipse overlaid (centred at P0, major axis "
            f"along s). Position, orientation and size of the ellipse are targets of the "
            f"calibration of the unpublished set-up (docs/calibration.md); the first table "
            f"gives each with its tolerance"
            + (f" (missed: {', '.join(missed)}; why they cannot all be met together is in "
               f"docs/calibration.md)." if missed else ".")
            + f" The preview p_max = 3 W / (2 pi a b) is {pct_diff(p.p_max_mpa, pub_pmax):+.0f} "
            f"% off the published one: our normal load at the design torque is "
            f"{pct_diff(c.load_n, pub_w):+.0f} % (lever {c.lever_mm:.2f} mm about the gear "
            f"axis) and our a b is {pct_diff(p.a_mm * p.b_mm, pub_ab):+.0f} % off the "
            f"published ellipse. The LCP patch "
            f"and the preview ellipse differ where the patch is cut by the flank edge (edge "
            f"contact: {format_cell(c.edge_contact)})."]
    tables = [Table("Design point: published target vs this set-up", DESIGN_POINT_HEADER,
                    dp_rows)] if dp_rows else []
    tables.append(Table(f"Loaded contact at the design torque {c.torque_nm:g} N·m",
                        ["quantity", "ours", "published"], rows))
    # the spatial targets of the design-point table (TE0 is judged in item 6)
    ids = {"P0 gear radius": "p0_gear_radius_mm", "P0 gear axial": "p0_gear_axial_mm",
           "P0 pinion radius": "p0_pinion_radius_mm", "P0 pinion axial": "p0_pinion_axial_mm",
           "Hertz 2a": "ellipse_2a_mm", "Hertz 2b": "ellipse_2b_mm",
           "ellipse angle": "ellipse_angle_deg"}
    heads = judge("pressure_map", {ids[k]: (r[2], r[1]) for r in dp_rows for k in ids
                                   if r[0].startswith(k)}, pub)
    return judged_section(
        "pressure_map", 2, "Spatial view: pressure map with the preview ellipse", heads,
        text, tables,
        [("pressure_maps.png", "LCP pressure maps at the four torques, preview "
                               "ellipse overlaid")],
        {"torque_nm": c.torque_nm, "load_n": c.load_n,
         "preview_2a_mm": 2 * p.a_mm, "preview_2b_mm": 2 * p.b_mm,
         "preview_p_max_mpa": p.p_max_mpa,
         "design_point": [dict(zip(("target", "published", "ours", "tolerance",
                                    "met"), r)) for r in dp_rows],
         "lcp": c.summary(),
         "published": {k: pub.get(k) for k in (
             "preview_ellipse_2a_mm", "preview_ellipse_2b_mm",
             "preview_ellipse_angle_deg", "preview_p_max_mpa_at_design",
             "lcp_contact_cells_at_design", "mesh_rotation_rigid_arcsec_at_design")}})


def lte_section(analysis, pub) -> Section:
    from .summary import lte_rows

    lte = analysis.lte
    if lte is None:
        return Section("lte", 6, "Loaded transmission error", "not available",
                       ["The loaded-TE run was skipped."], [], [], {})
    s = lte.summary()
    pp = pub.get("lte_pp_arcsec", {})
    lte_pp, te0_pp = lte.te_lcp_pp_arcsec, lte.te0_pp_arcsec
    pp_lcp, te0_pub = pp.get("lcp", math.nan), pub.get("te0_pp_arcsec", math.nan)
    text = [f"{len(lte.phi1_rad)} mesh phases over one pinion pitch at {lte.torque_nm:g} "
            f"N·m, {'with the shell bending of both teeth' if lte.bending else 'rigid teeth'}"
            f": every pair within reach with its own gap field, one shared "
            f"gear rotation, torque balance. TE_LCP peak-to-peak {lte.te_lcp_pp_arcsec:.2f} "
            f"arcsec against the published {pp.get('lcp')} arcsec (TE0 "
            f"{lte.te0_pp_arcsec:.2f} against {pub.get('te0_pp_arcsec')} arcsec). The loaded "
            f"rotation of our edge-loaded bearing varies along the path from "
            f"{lte.rotation_lcp_arcsec.min():.1f} to {lte.rotation_lcp_arcsec.max():.1f} "
            f"arcsec (edge contact in {int(lte.edge_contact.sum())} of {len(lte.phi1_rad)} "
            f"phases), which makes TE_LCP {'larger' if lte_pp > te0_pp else 'smaller'} than "
            f"TE0 here; the published TE_LCP, {pp_lcp / te0_pub:.2f} of its TE0, implies a "
            f"nearly constant rotation. Where along the path the published bearing meets the "
            f"edge was not published, so this difference is measured, not resolved. "
            + (f"TE0 meets the published {te0_pub} arcsec within the calibration's 10 %. "
               if abs(te0_pp / te0_pub - 1.0) <= 0.1 else
               f"TE0 is {pct_diff(te0_pp, te0_pub):+.0f} % off the published {te0_pub} "
               f"arcsec: {len(lte.phi1_rad)} phases (a quick run) under-sample its "
               f"peak-to-peak; the full run samples every TCA phase. "
               if len(lte.phi1_rad) < 30 else
               f"TE0 misses the published {te0_pub} arcsec by "
               f"{pct_diff(te0_pp, te0_pub):+.0f} %: the calibration trades it against P0 "
               f"and the ellipse (measured trade-off in docs/calibration.md). ")
            + "Tooth bending: item 7."]
    comp = pub.get("compliance_mm_per_n", {})
    heads = judge("lte", {
        "te0_pp_arcsec": (te0_pp, te0_pub),
        "te_lcp_pp_arcsec": (lte_pp, pp_lcp),
        "te_pre_pp_arcsec": (lte.te_pre_pp_arcsec, pp.get("preview")),
        "te_pre_over_te_lcp": (lte.te_pre_pp_arcsec / lte_pp, pp.get("preview") / pp_lcp),
        "compliance_lcp_mm_per_n": (lte.compliance_lcp_mm_per_n, comp.get("lcp")),
        "compliance_pre_mm_per_n": (lte.compliance_pre_mm_per_n, comp.get("preview"))}, pub)
    return judged_section("lte", 6, "Loaded transmission error along the mesh phase", heads,
                          text, [Table("Loaded TE and compliances",
                                       ["quantity", "ours", "published"], lte_rows(lte, pub))],
                          [("lte.png", "TE0, TE_LCP, TE_pre and active pairs along the phase")],
                          {**s, "published": {"lte_pp_arcsec": pp, "te0_pp_arcsec":
                                              pub.get("te0_pp_arcsec"),
                                              "compliance_mm_per_n": comp}})


def _multitooth_published(pub) -> dict:
    """The published multi-tooth figures at 64.5 N·m (docs/spec.md sec. 3, 5) from the
    pair's published values, under the names this item uses."""
    return {"shares_pct": list(pub["multi_tooth_load_share_pct"]),
            "rotation_rigid_arcsec": pub["mesh_rotation_rigid_arcsec_at_design"],
            "rotation_bending_arcsec": pub["mesh_rotation_bending_arcsec_at_design"],
            "bending_rotation_increase_pct": pub["mesh_rotation_bending_increase_pct"],
            "cp_max_mpa": pub["cp_max_mpa_at_design"]}


def multitooth_section(analysis, pub, settings) -> Section:
    from ..ltca.lte import loaded_te
    from ..ltca.tooth_bending import tooth_bending

    main = analysis.lte
    if main is None:
        reason = "The loaded-TE run of the main job was skipped."
        return Section("multitooth", 7, "Multi-tooth load sharing", "not available",
                       [reason], [], [], {"reason": reason})
    published = pub
    pub = _multitooth_published(published)
    n = len(analysis.tca.cycle.phi1_rad)
    stride = max(1, -(-(n - 1) // max(int(settings["lte_phases"]) - 1, 1)))  # as the main job
    # the main job's loaded TE is one of the two models (bending by default, rigid with
    # --rigid); the other is solved here on the same phases
    other = loaded_te(analysis.tca, analysis.flanks, analysis.pair, main.torque_nm,
                      side=analysis.side, stride=stride,
                      bending=None if main.bending else tooth_bending(
                          analysis.flanks, analysis.pair, side=analysis.side))
    rigid, bent = (other, main) if main.bending else (main, other)
    s_r, s_b = rigid.summary(), bent.summary()
    share_r, share_b = s_r["reference_load_share"], s_b["reference_load_share"]
    def ranked(share):
        return sorted(((v, k) for k, v in share.items() if v > 0), reverse=True)

    r_r, r_b = ranked(share_r), ranked(share_b)
    rows = [[f"{('largest', 'second', 'third', 'fourth', 'fifth')[i]} share at P0 (%)",
             f"{100 * r_r[i][0]:.1f} (pair {int(r_r[i][1]):+d})" if i < len(r_r) else None,
             f"{100 * r_b[i][0]:.1f} (pair {int(r_b[i][1]):+d})" if i < len(r_b) else None,
             pub["shares_pct"][i] if i < 3 else None]
            for i in range(min(5, max(len(r_r), len(r_b), 3)))]
    rot_r, rot_b = s_r["reference_rotation_lcp_arcsec"], s_b["reference_rotation_lcp_arcsec"]
    rows += [["loaded rotation at P0 (arcsec)", rot_r, rot_b,
              f"{pub['rotation_rigid_arcsec']} / {pub['rotation_bending_arcsec']}"],
             ["rotation increase from bending (%)", None, pct_diff(rot_b, rot_r),
              pub["bending_rotation_increase_pct"]],
             ["mesh compliance LCP at P0 (mm/N)", s_r["mesh_compliance_lcp_mm_per_n"],
              s_b["mesh_compliance_lcp_mm_per_n"], None],
             ["TE_LCP peak-to-peak (arcsec)", s_r["te_lcp_pp_arcsec"], s_b["te_lcp_pp_arcsec"],
              None],
             ["active pairs (LCP)", f"{s_r['active_pairs_lcp_min']}-"
              f"{s_r['active_pairs_lcp_max']}", f"{s_b['active_pairs_lcp_min']}-"
              f"{s_b['active_pairs_lcp_max']}", "3"]]
    text = [f"The coupled multi-pair LCP at {rigid.torque_nm:g} N·m over {len(bent.phi1_rad)} "
            f"phases, rigid teeth and with the shell bending "
            f"compliance of both teeth added to every pair (gearcontact.ltca."
            f"tooth_bending; the main job's loaded TE is the "
            f"{'bending' if main.bending else 'rigid'} one). Bending raises the loaded "
            f"rotation at P0 by "
            f"{pct_diff(rot_b, rot_r):+.0f} % (published +{pub['bending_rotation_increase_pct']} "
            f"%): the mesh compliance at P0 goes from {s_r['mesh_compliance_lcp_mm_per_n']:.3g} "
            f"to {s_b['mesh_compliance_lcp_mm_per_n']:.3g} mm/N ("
            f"{pct_diff(s_b['mesh_compliance_lcp_mm_per_n'], s_r['mesh_compliance_lcp_mm_per_n']):+.0f}"
            f" %), and the load redistributes among the pairs (the pair at P0 carries {100 * share_r.get('0', 0.0):.1f} % rigid, "
            f"{100 * share_b.get('0', 0.0):.1f} % with bending). The published sharing is "
            f"more concentrated (largest share {pub['shares_pct'][0]} %); where along the path "
            f"the published P0 lies relative to the neighbours' contacts was not published, "
            f"so this difference is measured, not resolved; the measurements that explain "
            f"it follow the tables (derivation: docs/bending.md sec. 7).",
            ]
    tables = [Table(f"Load sharing at {rigid.torque_nm:g} N·m", ["quantity", "rigid teeth",
                                                                "with bending", "published"],
                    rows)]
    data = {"rigid": s_r, "bending": s_b, "published": pub}
    figures = []
    mt = analysis.multitooth
    if mt is None:
        text.append(f"The published line-contact peak CP_max = {pub['cp_max_mpa']} MPa is "
                    "not compared: the main job's multi-tooth case was skipped.")
    else:
        summary = mt.summary()
        share_pct = mt.load_share_pct[summary["pair_offsets"].index(0)]
        # a line contact's peak grows as the square root of its load per length
        # (Johnson 1985, eq. 4.45): our CP_max at the published share of the pair at P0
        scaled = mt.cp_max_mpa * math.sqrt(pub["shares_pct"][0] / share_pct)
        tables.append(Table(
            f"Line-contact peak of the multi-tooth case at P0, {mt.torque_nm:g} N·m, "
            "with bending (MPa)", ["quantity", "ours", "published"],
            [["CP_max (edge cells trimmed, strip-wise line-contact peak)", mt.cp_max_mpa,
              pub["cp_max_mpa"]],
             ["largest cell pressure (edge cells kept)", mt.p_peak_cell_mpa, None],
             ["trimmed edge cells / their load (N)",
              f"{summary['trimmed_cells']} / {summary['trimmed_load_n']:.0f}", None],
             ["share of the pair at P0 (%)", share_pct, pub["shares_pct"][0]],
             ["CP_max scaled to the published share, sqrt(share ratio)", scaled, None],
             ["preview p_max", mt.preview_p_max_mpa, None]]))
        text.append(
            f"CP_max is computed as published: boundary-inadmissible edge cells trimmed, then "
            f"the strip-wise Hertz line-contact peak (gearcontact.halfspace.line_peak). Ours "
            f"{mt.cp_max_mpa:.0f} MPa against the published {pub['cp_max_mpa']} MPa "
            f"({pct_diff(mt.cp_max_mpa, pub['cp_max_mpa']):+.0f} %). Part of it is the load "
            f"sharing above: our pair at P0 carries {share_pct:.1f} % of the load, the "
            f"published one {pub['shares_pct'][0]} %; a line-contact peak grows as the square "
            f"root of the load per length (Johnson 1985, eq. 4.45), so at the published share "
            f"ours would read {scaled:.0f} MPa ({pct_diff(scaled, pub['cp_max_mpa']):+.0f} % "
            f"from the published value). The remaining difference is measured, not resolved "
            f"here.")
        data["line_peak"] = {"cp_max_mpa": mt.cp_max_mpa, "p_peak_cell_mpa": mt.p_peak_cell_mpa,
                             "reference_share_pct": share_pct,
                             "cp_max_at_published_share_mpa": scaled,
                             "published_cp_max_mpa": pub["cp_max_mpa"]}
        figures.append(("multitooth.png", "pressure of every engaged pair on the gear flank "
                        "(with bending) and the load share per pair beside the published"))
        why_tables, why_text, why_data = sharing_explanation(analysis, s_r, s_b, pub)
        tables += why_tables
        text += why_text
        data["sharing_explanation"] = why_data
    heads = judge("multitooth", {
        "reference_share_pct": (100.0 * share_b.get("0", 0.0), pub["shares_pct"][0]),
        "rotation_rigid_arcsec": (rot_r, pub["rotation_rigid_arcsec"]),
        "rotation_bending_arcsec": (rot_b, pub["rotation_bending_arcsec"]),
        "rotation_bending_over_rigid": (rot_b / rot_r, pub["rotation_bending_arcsec"]
                                        / pub["rotation_rigid_arcsec"]),
        "cp_max_mpa": (None if mt is None else mt.cp_max_mpa, pub["cp_max_mpa"])}, published)
    return judged_section("multitooth", 7, "Multi-tooth load sharing", heads, text, tables,
                          figures, data)
