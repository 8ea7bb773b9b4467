"""The main job for a cylindrical pair: TE0, loaded TE, Harris map, mesh stiffness,
pressure and the preview on the cylindrical contact, written to one directory with a
readable summary (docs/cylindrical.md sec. 9).

:func:`run_cylindrical_analysis` is what ``gearcontact analyze`` calls for a
``kind = "cylindrical"`` pair. Files written into ``out``:

=========================================  ==================================================
``tca.json``, ``te0.csv``,                 the unloaded cycle (``tca.cylindrical_export``):
``contact_lines.csv``, ``te0.png``,        TE0 per pair and envelope, contact lines,
``contact_pattern.png``                    pattern
``lte.json``, ``lte.csv``,                 the loaded TE at the torque, load sharing, peak
``line_load.csv``, ``harris_map.csv``,     pressure, line loads, secant mesh stiffness
``lte.png``, ``harris_map.png``            beside ISO 6336-1 Method B, and the Harris map
                                           (``report.cylindrical_lte``)
``preview.csv``                            per phase and loaded pair: load, line length,
                                           loaded length ``L_c`` (the slice law, coupled
                                           with the teeth's bending under a loaded TE with
                                           bending: ``ltca.coupled_slice_law``),
                                           exact and fitted curvatures, the fp64 and golden
                                           line chain (mode, p_max, b, flags) beside the
                                           LCP's peak pressure on that line, its loaded
                                           length and whether it loads a line end; the
                                           slice law's line load (end-loaded, equivalent
                                           length, peak line load, K_Hbeta, its Hertz
                                           pressure:
                                           ``ltca.cylindrical_preview.LineFaceLoad``)
``preview.png``                            p_max along the phase: LCP, fp64 and golden
``analyze.json``                           the headline numbers of ``summary.md``
``summary.md``                             readable summary
=========================================  ==================================================

No file holds a timing (identical runs write identical files): the stage times are in
:attr:`CylindricalAnalysis.timings_s` (``gearcontact analyze`` writes them into
``run.json``).
"""

from __future__ import annotations

import json
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..figure_files import save_figure
from ..geometry.cylindrical.pair import CylindricalPair
from ..ltca.cylindrical_lte import (CylindricalLoadedTE, HarrisMap, cylindrical_loaded_te,
                                    harris_map, harris_tip_reliefs_um, harris_torques_nm)
from ..ltca.cylindrical_preview import CylindricalPreview, cylindrical_preview
from ..tca.cylindrical_cycle import FACING_OF_SIDE, CylindricalMeshCycle, cylindrical_mesh_cycle
from ..tca.cylindrical_export import write_cylindrical_tca_outputs
from ..tca.export import write_csv
from ..validation import InputRangeError
from .cylindrical_lte import write_cylindrical_lte_outputs

__all__ = ["CylindricalAnalysis", "end_loaded_note", "run_cylindrical_analysis"]

#: The preview backends the job evaluates (fp64 and the bit-exact fixed point).
BACKENDS = ("reference", "golden")


@dataclass(frozen=True)
class CylindricalAnalysis:
    """Everything one run computed (files in ``out_dir``)."""

    pair: CylindricalPair
    out_dir: Path
    cycle: CylindricalMeshCycle
    lte: CylindricalLoadedTE
    harris: HarrisMap
    preview: CylindricalPreview
    summary: dict
    timings_s: dict = field(default_factory=dict)


def _preview_rows(pv: CylindricalPreview, lte: CylindricalLoadedTE) -> list[list]:
    st = pv.stencils
    phi = np.degrees(st.phi1_rad)
    vals = {b: {n: pv.values(b, n) for n in ("p_max_mpa", "b_mm", "A_minus_per_mm",
                                               "B_minus_per_mm")} for b in BACKENDS}
    modes = {b: pv.modes(b) for b in BACKENDS}
    fl = pv.face_load
    rows = []
    for k in range(len(phi)):
        for j, off in enumerate(st.pair_offsets):
            if not pv.loaded[j, k]:
                continue
            gold = pv.results["golden"][j][k]
            rows.append([float(phi[k]), off, float(pv.load_n[j, k]),
                         float(st.line_length_mm[j, k]), float(pv.loaded_length_mm[j, k]),
                         float(st.A_minus_per_mm[j, k]),
                         float(st.B_minus_per_mm[j, k]), bool(st.on_flank[j, k]),
                         float(vals["reference"]["A_minus_per_mm"][j, k]),
                         float(vals["reference"]["B_minus_per_mm"][j, k])]
                        + [x for b in BACKENDS for x in (
                            str(modes[b][j, k]), float(vals[b]["p_max_mpa"][j, k]),
                            float(vals[b]["b_mm"][j, k]))]
                        + ["|".join(gold.flags) if gold is not None else "refused",
                           float(lte.line_pressure_mpa[j, k].max()),
                           float(lte.loaded_length_mm[j, k]), bool(lte.line_end_loaded[j, k])]
                        + [_csv_value(getattr(fl, n)[j, k]) for n in _FACE_LOAD])
    return rows


#: The preview's line load (ltca.cylindrical_preview.LineFaceLoad: the slice law's; its
#: loaded length is the row's ``loaded_length_mm``) in preview.csv.
_FACE_LOAD = ("end_loaded", "equivalent_length_mm", "peak_line_load_n_per_mm",
              "face_load_factor", "hertz_pressure_mpa")


def _csv_value(x):
    return bool(x) if isinstance(x, (bool, np.bool_)) else float(x)


_PREVIEW_HEADER = (["phi1_deg", "pair", "load_n", "line_length_mm", "loaded_length_mm",
                    "A_minus_exact_per_mm",
                    "B_minus_exact_per_mm", "stencil_on_flank", "A_minus_fit_per_mm",
                    "B_minus_fit_per_mm"]
                   + [f"{b}_{n}" for b in BACKENDS for n in ("mode", "p_max_mpa", "b_mm")]
                   + ["golden_flags", "lcp_peak_mpa", "lcp_loaded_length_mm",
                      "lcp_line_end_loaded"]
                   + ["end_loaded", "equivalent_length_mm", "peak_line_load_n_per_mm",
                      "face_load_factor", "peak_hertz_pressure_mpa"])


def _plot_preview(pv: CylindricalPreview, lte: CylindricalLoadedTE, path, *, title: str):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    phi = np.degrees(pv.stencils.phi1_rad)
    fig, ax = plt.subplots(figsize=(7.0, 4.0))
    ax.plot(phi, lte.max_pressure_mpa, "k-", label="LCP peak (tooth bending)" if lte.bending else "LCP peak (rigid teeth)")
    for b, style in zip(BACKENDS, ("C0--", "C1:")):
        ax.plot(phi, pv.max_pressure_mpa(b), style, label=f"preview {b} (line chain)")
    ax.set_xlabel("pinion phase, deg")
    ax.set_ylabel("peak pressure, MPa")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title)
    return save_figure(fig, path, tight=True)


def _headline(cycle, lte, harris, pv, lte_json) -> dict:
    k0 = int(np.argmin(np.abs(cycle.phi1_rad - 0.5 * (cycle.phi1_rad[0] + cycle.phi1_rad[-1]))))
    ref, gold = pv.max_pressure_mpa("reference"), pv.max_pressure_mpa("golden")
    best = np.argmin(harris.lte_pp_arcsec, axis=0)
    modes = {b: sorted({str(m) for m in pv.modes(b)[pv.loaded]}) for b in BACKENDS}
    return {
        "te0_pp_arcsec": float(cycle.te0_pp_arcsec),
        "torque_nm": lte.torque_nm, "normal_load_n": lte.normal_load_n,
        "lte_pp_arcsec": lte.lte_pp_arcsec,
        "mesh_stiffness_n_per_mm_um": {
            "mean": lte.mean_stiffness_n_per_mm_um,
            "min": float(lte.stiffness_n_per_mm_um.min()),
            "max": float(lte.stiffness_n_per_mm_um.max())},
        "iso6336": lte_json.get("iso6336_method_b"),
        "lcp_max_pressure_mpa": float(lte.max_pressure_mpa.max()),
        "lcp_peak_at_edge": bool(lte.peak_at_edge[int(np.argmax(lte.max_pressure_mpa))]),
        "end_loaded_lines": _end_loaded_headline(pv),
        "preview_max_pressure_mpa": {"reference": float(ref.max()), "golden": float(gold.max())},
        "pitch_phase": {"phi1_deg": float(np.degrees(cycle.phi1_rad[k0])),
                        "lcp_max_pressure_mpa": float(lte.max_pressure_mpa[k0]),
                        "preview_reference_mpa": float(ref[k0]),
                        "preview_golden_mpa": float(gold[k0])},
        "preview_modes": modes, "preview_load_source": pv.load_source,
        "preview_evaluations": int(pv.loaded.sum()), "preview_refused": len(pv.errors),
        "harris_best_tip_relief_um": {f"{t:g}": float(harris.tip_reliefs_um[r])
                                      for t, r in zip(harris.torques_nm, best)},
        "converged": bool(lte.converged and harris.converged),
        "edge_touch": bool(lte.edge_touch or harris.edge_touch),
        "teeth": "bending" if lte.bending else "rigid"}


def _end_loaded_headline(pv: CylindricalPreview) -> dict | None:
    """The preview's end-loaded lines over the pitch (None without one): how many
    previews, the shortest loaded length, the largest peak line load, face load factor
    and Hertz pressure of the peak line load."""
    fl = pv.face_load
    if fl is None or not fl.end_loaded.any():
        return None
    on = fl.end_loaded
    return {"previews": int(on.sum()),
            "min_loaded_length_mm": float(fl.loaded_length_mm[on].min()),
            "max_peak_line_load_n_per_mm": float(fl.peak_line_load_n_per_mm[on].max()),
            "max_face_load_factor": float(fl.face_load_factor[on].max()),
            "max_hertz_pressure_mpa": float(fl.hertz_pressure_mpa[on].max())}


def end_loaded_note(h: dict) -> str:
    """One line for the user on the headline ``h``'s end-loaded lines and a peak
    pressure at a line end (what ``gearcontact analyze`` prints on stderr)."""
    out = []
    end = h["end_loaded_lines"]
    if end is not None:
        out.append(
            f"end-loaded contact lines (the gap opens along the line from a face end: "
            f"misalignment or helix slope): loaded length down to "
            f"{end['min_loaded_length_mm']:.2f} mm, peak line load "
            f"{end['max_peak_line_load_n_per_mm']:.0f} N/mm = "
            f"{end['max_face_load_factor']:.1f} x the mean, its Hertz pressure "
            f"{end['max_hertz_pressure_mpa']:.0f} MPa (slice law, preview.csv)")
    if h["lcp_peak_at_edge"]:
        out.append(f"the LCP's p_max {h['lcp_max_pressure_mpa']:.0f} MPa sits on a sharp "
                   "edge (a loaded line end or a tip edge), where the half-space pressure is "
                   "singular (it grows with the grid): no design value")
    if end is not None:
        out.append("lead crowning or a helix slope that cancels the misalignment "
                   "([modifications.pinion] lead_crowning_um / helix_slope_um) centres "
                   "the load")
    return "; ".join(out)


def _summary_md(pair, side, facing, h, harris) -> str:
    ms = h["mesh_stiffness_n_per_mm_um"]
    iso = h["iso6336"] or {}
    pp = h["pitch_phase"]
    lines = [
        f"# {pair.name}: cylindrical pair, {side} ({facing} flanks)", "",
        ("Tooth bending of both teeth beside the Love half-space (docs/bending.md sec. 9)"
         if h["teeth"] == "bending" else "Rigid teeth (the Love half-space alone)")
        + "; docs/cylindrical.md.", "",
        "| quantity | value |", "|---|---|",
        f"| TE0 p-p | {h['te0_pp_arcsec']:.3f} arcsec |",
        f"| gear torque, F_n | {h['torque_nm']:g} N·m, {h['normal_load_n']:.1f} N |",
        f"| loaded TE p-p | {h['lte_pp_arcsec']:.3f} arcsec |",
        f"| mesh stiffness mean / min / max | {ms['mean']:.2f} / {ms['min']:.2f} / "
        f"{ms['max']:.2f} N/(mm·µm) |"]
    if iso:
        lines.append(f"| ISO 6336-1 Method B c_γα (c′) | {iso['c_gamma_alpha_n_per_mm_um']:.2f} "
                     f"({iso['c_single_n_per_mm_um']:.2f}) N/(mm·µm) at F_t/b = "
                     f"{iso['line_load_ft_per_b_n_per_mm']:.0f} N/mm |")
    lines += [
        f"| LCP peak pressure (max over the pitch) | {h['lcp_max_pressure_mpa']:.1f} MPa |",
        f"| preview p_max fp64 / golden (max) | "
        f"{h['preview_max_pressure_mpa']['reference']:.1f} / "
        f"{h['preview_max_pressure_mpa']['golden']:.1f} MPa |",
        f"| at the pitch-point phase ({pp['phi1_deg']:.3f} deg): LCP / fp64 / golden | "
        f"{pp['lcp_max_pressure_mpa']:.1f} / {pp['preview_reference_mpa']:.1f} / "
        f"{pp['preview_golden_mpa']:.1f} MPa |",
        f"| preview modes (fp64; golden) | {', '.join(h['preview_modes']['reference'])}; "
        f"{', '.join(h['preview_modes']['golden'])} |",
        ]
    end = h["end_loaded_lines"]
    if end is not None:
        lines.append(
            f"| end-loaded lines (slice law, {end['previews']} previews): loaded length "
            f"min / peak line load max / K_Hβ max / its Hertz pressure max | "
            f"{end['min_loaded_length_mm']:.2f} mm / {end['max_peak_line_load_n_per_mm']:.0f}"
            f" N/mm / {end['max_face_load_factor']:.2f} / {end['max_hertz_pressure_mpa']:.0f}"
            " MPa |")
    if h["lcp_peak_at_edge"]:
        lines += ["", "The LCP's peak pressure sits on a sharp edge (a loaded line's end at "
                  "a face end or a tip or form circle, or a tip edge touching the mating "
                  "flank): the half-space pressure there is "
                  "singular and grows with the grid's rows, so it is no design value; the "
                  "loaded length and the approach converge (docs/cylindrical.md sec. 7)."]
    lines += [
        "", "The preview is the datapath's line chain (stage C fit -> line core of stage D) "
        "on each loaded pair's 7 x 7 stencil with its LCP load share, run on the "
        "equivalent length L_eq = W / w_peak of the slice law's peak line load (the "
        "ease-off along the line, with the teeth's bending where the loaded TE has it): "
        "its p_max is the Hertz line pressure of that peak. The LCP peak also holds the "
        "half-space's end effects of a finite line (the pressure rising towards a loaded "
        "line's ends), which the slice law's foundation does not (docs/cylindrical.md "
        "sec. 8).", "",
        "## Harris map: loaded TE p-p (arcsec)", "",
        "| C_a µm | TE0 p-p | " + " | ".join(f"{t:g} N·m" for t in harris.torques_nm) + " |",
        "|---" * (2 + len(harris.torques_nm)) + "|"]
    for r, c in enumerate(harris.tip_reliefs_um):
        lines.append(f"| {c:g} | {harris.te0_pp_arcsec[r]:.3f} | "
                     + " | ".join(f"{x:.3f}" for x in harris.lte_pp_arcsec[r]) + " |")
    lines += ["", "Files: tca.json, te0.csv, contact_lines.csv, lte.json, lte.csv, "
                  "line_load.csv, harris_map.csv, preview.csv, analyze.json (+ figures)."]
    return "\n".join(lines) + "\n"


def run_cylindrical_analysis(pair: CylindricalPair, *, out_dir, torque_nm: float = 64.5,
                             phases: int = 61, side: str = "drive", cells: int = 40,
                             figures: bool = True, bending: bool = True) -> CylindricalAnalysis:
    """TE0, loaded TE, Harris map, mesh stiffness, pressure and the preview of a
    cylindrical pair into ``out_dir`` (module docstring).

    Parameters
    ----------
    pair : CylindricalPair
    out_dir : path
        Created if missing.
    torque_nm : float
        Gear torque of the loaded TE and the preview, N·m (> 0).
    phases : int
        Phases per pinion pitch of every cycle (the Harris map's too), >= 3.
    side : str
        ``"drive"`` (cw flanks) or ``"coast"`` (ccw).
    cells : int
        LCP cells along the face (>= 4).
    figures : bool
        Write the figures.
    bending : bool
        Tooth bending in the loaded TE and the Harris map (default), else rigid teeth.
    """
    if side not in FACING_OF_SIDE:
        raise InputRangeError("side", side, f"one of {sorted(FACING_OF_SIDE)}")
    facing = FACING_OF_SIDE[side]
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    times = {}
    t = time.process_time()
    cycle = cylindrical_mesh_cycle(pair, facing=facing, phases=phases)
    write_cylindrical_tca_outputs(cycle, pair, out, side=side, figures=figures)
    times["tca_cpu_s"], t = time.process_time() - t, time.process_time()
    lte = cylindrical_loaded_te(pair, torque_nm, cycle=cycle, cells_along=cells,
                                bending=bending)
    times["lte_cpu_s"], t = time.process_time() - t, time.process_time()
    harris = harris_map(pair, harris_torques_nm(pair), harris_tip_reliefs_um(pair),
                        facing=facing, phases=phases, cells_along=cells, bending=bending)
    times["harris_map_cpu_s"], t = time.process_time() - t, time.process_time()
    lte_json = write_cylindrical_lte_outputs(lte, harris, pair, out, side=side,
                                             figures=figures)
    pv = cylindrical_preview(pair, torque_nm, cycle=cycle, loaded_te=lte, backends=BACKENDS)
    times["preview_cpu_s"] = time.process_time() - t
    write_csv(out / "preview.csv", _PREVIEW_HEADER, _preview_rows(pv, lte))
    if figures:
        _plot_preview(pv, lte, out / "preview.png",
                      title=f"{pair.name} {side}: preview (line chain) vs LCP, "
                            f"{torque_nm:g} N·m")
    head = _headline(cycle, lte, harris, pv, lte_json)
    (out / "analyze.json").write_text(json.dumps(head, indent=2))
    (out / "summary.md").write_text(_summary_md(pair, side, facing, head, harris))
    return CylindricalAnalysis(pair=pair, out_dir=out, cycle=cycle, lte=lte, harris=harris,
                               preview=pv, summary=head, timings_s=times)
