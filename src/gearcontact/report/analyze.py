"""The main job: design, unloaded TCA, single-pair LTCA at the operating torques and the
physics-direct preview beside it, written to one directory with a readable summary.

``run_analysis`` is what ``gearcontact analyze`` calls. Files written into ``out``:

============================  ==============================================================
``design.json``               blank data (ISO 23509 Method 1)
TCA files                     see :mod:`gearcontact.tca.export` (``tca.json``, ``te0.csv``,
                              ``contact_path.csv``, ``gap_stencil.csv``, ``gap_field.csv``,
                              ``phase_table.json``/``.bin``, ``te0.png``, ``contact_pattern.png``)
``ltca.json``                 per torque: load, LCP statistics, delta, mesh rotation, preview
``ltca_torques.csv``          the table "preview vs LCP mean / p90 / peak" over the torques
``preview.csv``               per torque: contact-line length on the flank, reference and
                              golden line-core previews (A-, B-, L -> D) and golden C -> D
                              (line chain, hardware stencil, same L) with codes, the stage-D
                              mode (elliptic | line) and a status each (``ok``, or why the
                              result is missing: then one :class:`PreviewDomainWarning`
                              line names the count), and whether each preview's Hertz
                              law holds there (``*_law_status``: ``ok`` or
                              ``beyond_hamrock_brewe_range``, then one
                              :class:`~gearcontact.preview.hertz.reference.HertzLawRangeWarning`
                              line; docs/hertz.md sec. 7)
``pressure_<T>Nm.csv``        pressure map at each torque (s_mm, t_mm, pressure_mpa)
``pressure_maps.png``         LCP pressure maps with the preview ellipse overlaid
``pressure_vs_load.png``      log-log preview p_max and LCP mean / p90 / peak vs W, W^(1/3)
``lte.json``, ``lte.csv``     loaded TE over one pitch at the design torque (TE0, TE_LCP,
                              TE_pre, active pairs, compliances; :mod:`gearcontact.ltca.lte`)
``lte.png``                   TE0, TE_LCP, TE_pre and active pairs along the phase
``precision.csv``, ``.png``   gap-kernel fixed-point error vs coordinate / normal width
                              beside the first-order bound (:mod:`.precision`)
``latency.json``              RTL cycle counts per core (:mod:`.latency`)
``summary.md``                readable summary with the published values beside ours
============================  ==============================================================

Every figure is written as PNG and as SVG beside it (:func:`gearcontact.figure_files.save_figure`:
identical runs write identical bytes, the SVG included), ``flanks_in_mesh`` too.

No file holds a timing (two identical runs write identical files): the stage times, the
LCP solve times and the fp64 preview's CPU latency and jitter on this machine are in
:attr:`Analysis.timings_s` (``gearcontact analyze`` writes them into ``run.json``).
"""

from __future__ import annotations

import json
import time
import warnings
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

from tqdm import tqdm

from ..halfspace.lcp import warm_up
from ..ltca.lte import loaded_te
from ..halfspace.line_peak import contact_line_length_mm
from ..ltca.pair_ltca import PairLoadCase, single_pair_ltca
from ..halfspace.patch import ContactAtEdgeWarning
from ..geometry.pair import load_pair
from ..geometry.settings_check import SettingsCheck
from ..preview.engine import PreviewResult, ReferenceEngine, get_engine
from ..preview.hertz.reference import LAW_OK, HertzLawRangeWarning
from ..contract.qformat import FixedPointOverflow
from ..tca.analysis import TcaAnalysis, analyze_pair
from ..tca.export import without_timings, write_csv, write_tca_outputs
from ..tca.synthesis import prepare_pair
from ..validation import InputRangeError, check_positive
from .figures import plot_pressure_maps, plot_pressure_vs_load
from .latency import core_cycles, scalar_latency
from .law_range import law_range_warning
from .lte_plot import write_lte_outputs
from .ltca import write_pressure_csv
from .precision import write_precision_outputs
from .summary import write_summary

__all__ = ["DEFAULT_TORQUES_NM", "Analysis", "PreviewDomainWarning", "run_analysis",
           "published_values"]

#: Operating torques of the s0003 evaluation (gear torque, N·m; docs/spec.md sec. 3).
DEFAULT_TORQUES_NM = (32.25, 64.5, 129.0, 258.0)


@dataclass(frozen=True, eq=False)
class Analysis:
    """Everything the main job computed (files are in ``out_dir``).

    Attributes
    ----------
    pair : GearPair
    tca : TcaAnalysis
    cases : tuple of PairLoadCase
        One per torque, ascending.
    golden : tuple of PreviewResult or None
        Golden preview (A-, B- from TCA -> the line core of stage D,
        :mod:`gearcontact.preview.hertz.line`, with the contact line's length in the
        case's field) at each case's load (None: not evaluated, see ``golden_status``).
    golden_chain : tuple of PreviewResult or None
        Golden C -> D on the hardware stencil at each case's load: the line chain
        (:func:`gearcontact.preview.chain.chain_line_golden`) with the case's contact
        line, the published chain where the case has none.
    timings_s : dict
        Wall-clock seconds per stage (``*_s``), LCP solve times (``ltca_solve_ms``) and
        the fp64 preview's CPU latency (``preview_cpu``: p50/p99 in us, jitter).
    out_dir : Path
    lte : LoadedTe or None
        Loaded TE at the design torque (None when skipped).
    precision : tuple or None
        Gap-kernel precision sweeps (by coordinate width, by normal width;
        :func:`.precision.precision_sweeps`).
    latency : ScalarLatency or None
        fp64 preview CPU latency measured on this machine (:mod:`.latency`).
    side : str
        Flank pair analysed ("drive" | "coast").
    flanks : FlankSet or None
        The flanks the analysis ran on.
    easeoff_note : str
        Non-empty when the pair came without an ease-off for ``side`` and it was
        synthesized (:attr:`gearcontact.tca.synthesis.PreparedPair.note`; no timing: it goes into
        summary.md).
    multitooth : MultiToothCase or None
        Multi-tooth LTCA at P0 at the LTE torque, rigid and with tooth bending
        (:mod:`gearcontact.ltca.multitooth`; None when the LTE is skipped).
    golden_status, chain_status : tuple of str
        Per torque, the status of ``golden`` / ``golden_chain``: ``ok``,
        ``flagged:<flags>`` (outputs 0), or ``outside_envelope`` / ``outside_registers``
        (then the result is None); the mode that evaluated a result is its ``mode``.
    reference : tuple of PreviewResult
        fp64 preview of the line core's rule at each case (ellipse, or the Hertz line
        contact where the flank truncates it; ``mode`` says which), the golden line
        core's counterpart.
    settings_check : SettingsCheck or None
        The check of the pair's typed machine settings against its blank
        (:func:`~gearcontact.geometry.settings_check.check_settings`; None for a pair
        without machine settings): summary.md says what it found and repeats its
        warnings.
    """

    pair: object
    tca: TcaAnalysis
    cases: tuple
    golden: tuple
    golden_chain: tuple
    timings_s: dict
    out_dir: Path
    lte: object = None
    precision: tuple | None = None
    latency: object = None
    side: str = "drive"
    flanks: object = None
    easeoff_note: str = ""
    multitooth: object = None
    golden_status: tuple = ()
    chain_status: tuple = ()
    reference: tuple = ()
    settings_check: SettingsCheck | None = None


class PreviewDomainWarning(UserWarning):
    """A fixed-point preview result is missing: the datapath flags the phase or its
    inputs lie outside the datapath's domain (reported, never an error)."""


def published_values(pair_name: str) -> dict | None:
    """Published reference values for a built-in pair (with provenance), or None.

    The variant ``s0003-centred`` (same pair, centred bearing) is compared with the
    published values of ``s0003``.
    """
    base = pair_name.removesuffix("-centred")
    res = resources.files("gearcontact").joinpath(f"data/published/{base}.json")
    if not res.is_file():
        return None
    return json.loads(res.read_text())


def _golden_preview(call, *args, **kwargs) -> tuple[PreviewResult | None, str]:
    """A golden-model preview and its status: ``ok``, ``flagged:<flags>`` when the
    datapath flags the input (outputs 0, not reported), or ``outside_envelope`` /
    ``outside_registers`` when the inputs do not reach the datapath at all (e.g. a
    curvature below the published core's range). A phase outside the datapath's domain
    is a result, not an error."""
    try:
        res = call(*args, **kwargs)
    except InputRangeError:
        return None, "outside_envelope"
    except FixedPointOverflow:
        return None, "outside_registers"
    return res, (f"flagged:{'|'.join(res.flags)}" if res.flags else "ok")


def _line_length(case) -> float | None:
    """Length of the contact line on the flank through P0 in the case's field, mm."""
    return None if case.on_flank is None else contact_line_length_mm(~case.on_flank,
                                                                     case.patch.grid)


def _values(res: PreviewResult | None, fields: tuple[str, ...]) -> list:
    """The numeric columns of a preview; empty cells where it gives none (its status
    column says why)."""
    if res is None or res.flags:
        return [""] * len(fields)
    return [res.codes["p_max"] if f == "p_max_code" else getattr(res, f) for f in fields]


def _mode(res: PreviewResult | None) -> str:
    return "none" if res is None or res.flags else res.mode


def _preview_rows(cases, reference, golden, chain) -> list[list]:
    rows = []
    for c, ref, (g, g_status), (ch, ch_status) in zip(cases, reference, golden, chain):
        length = _line_length(c)
        rows.append([c.torque_nm, c.load_n, "" if length is None else length, ref.mode,
                     ref.a_mm, ref.b_mm, ref.k, ref.p_max_mpa]
                    + _values(g, ("a_mm", "b_mm", "k", "p_max_mpa", "p_max_code"))
                    + [_mode(g), g_status]
                    + _values(ch, ("A_minus_per_mm", "B_minus_per_mm", "a_mm", "b_mm",
                                   "p_max_mpa", "p_max_code"))
                    + [_mode(ch), ch_status, "" if ch is None else ch.cycles]
                    + [_law(r) for r in (ref, g, ch)])
    return rows


def _law(res: PreviewResult | None) -> str:
    """A preview's law status (:func:`~gearcontact.preview.hertz.reference.law_status`);
    ``ok`` for a missing one (its status column says why)."""
    return LAW_OK if res is None else res.law_status


#: Columns of ``preview.csv`` (:func:`_preview_rows`).
PREVIEW_COLUMNS = [
    "torque_nm", "load_n", "line_length_mm", "ref_mode", "ref_a_mm", "ref_b_mm", "ref_k",
    "ref_p_max_mpa", "golden_a_mm", "golden_b_mm", "golden_k", "golden_p_max_mpa",
    "golden_p_max_code_q32_8", "golden_mode", "golden_status", "chain_A_minus_per_mm",
    "chain_B_minus_per_mm", "chain_a_mm", "chain_b_mm", "chain_p_max_mpa",
    "chain_p_max_code_q32_8", "chain_mode", "chain_status", "chain_cycles",
    "ref_law_status", "golden_law_status", "chain_law_status"]


def _missing_warning(golden, chain) -> str | None:
    """One line naming how many torques lack which fixed-point result, or None."""
    parts = []
    for name, results in (("golden D (line core)", golden),
                          ("golden C->D (line chain, hardware stencil)", chain)):
        bad = [status for res, status in results if status != "ok"]
        if bad:
            parts.append(f"{name} p_max missing for {len(bad)} of {len(results)} torques "
                         f"({', '.join(sorted(set(bad)))})")
    if not parts:
        return None
    return ("fixed-point preview outside the datapath's domain: " + "; ".join(parts)
            + " (preview.csv status columns; the fp64 preview and the LCP are complete)")



def _multi_tooth(tca, flanks, pair, torque_nm: float, side: str, out: Path, figures: bool,
                 timings: dict):
    """Multi-tooth LTCA at P0 (rigid and with tooth bending) and its files; solve times
    into ``timings``."""
    from ..ltca.mesh_lcp import warm_up_mesh_lcp
    from ..ltca.multitooth import multi_tooth_ltca
    from ..ltca.tooth_bending import tooth_bending
    from .multitooth import write_multitooth_outputs

    t0 = time.perf_counter()
    bending = tooth_bending(flanks, pair, side=side)
    timings["multi_tooth_jit_warm_up_s"] = warm_up_mesh_lcp()
    mt = multi_tooth_ltca(tca, flanks, pair, torque_nm, side=side, bending=bending)
    write_multitooth_outputs(mt, out, figures=figures, title=f"{pair.name} {side}",
                             published=published_values(pair.name))
    timings["multi_tooth_s"] = time.perf_counter() - t0
    timings["multi_tooth_solve_ms"] = mt.solve_ms
    timings["multi_tooth_solve_rigid_ms"] = mt.solve_rigid_ms
    return mt


def run_analysis(pair="s0003", *, out_dir, torques_nm=DEFAULT_TORQUES_NM, phases: int = 61,
                 side: str | None = None, solver: str = "pk_cg", figures: bool = True,
                 progress: bool = True, lte_torque_nm: float | None = 64.5,
                 lte_phases: int = 61, lte_bending: bool = True,
                 settings_check: SettingsCheck | None = None) -> Analysis:
    """Run the main job on ``pair`` (preset name, TOML path or GearPair) into ``out_dir``.

    Parameters
    ----------
    pair : str, Path or GearPair
    out_dir : str or Path
        Output directory (created if missing).
    torques_nm : sequence of float
        Gear torques, N·m (> 0).
    phases : int
        TCA phases per pinion pitch (>= 3; 61 for reports).
    side : str, optional
        ``"drive"`` or ``"coast"``; default the pair's ``design_side``.
    solver : str
        LCP solver for the loaded contact.
    figures : bool
        Write the PNG figures.
    progress : bool
        Show progress bars.
    lte_torque_nm : float or None
        Gear torque of the loaded TE (N·m; the design torque), None to skip it.
    lte_phases : int
        At most about this many LTE phases over the pitch: every
        ``ceil((phases - 1) / (lte_phases - 1))``-th TCA phase (the LTE costs one gap
        field per pair and phase; all 61 phases of s0003 take about 1 s).
    settings_check : SettingsCheck, optional
        The result of the typed machine settings' check against the blank
        (:func:`~gearcontact.geometry.settings_check.check_settings`) if the caller ran it
        on ``pair`` (the command line does, in its argument check); by default it is run
        here before any work (:func:`~gearcontact.tca.synthesis.prepare_pair`): a gross
        mismatch raises :class:`~gearcontact.validation.InputRangeError` naming the key
        before anything is written, any other disagreement is a
        :class:`~gearcontact.geometry.settings_check.SettingsWarning`. summary.md says
        what it found and repeats its warnings.
    """
    if isinstance(pair, (str, Path)):
        pair = load_pair(pair)
    side = pair.design_side if side is None else side
    # validate cheap inputs before the expensive stages
    torques = sorted(check_positive("torque_nm (N·m)", t) for t in torques_nm)
    if not torques:
        raise InputRangeError("torques_nm", torques_nm, "at least one torque")
    # design's checks first, before any flank work (named refusals; its gear flanks reused)
    prepared = prepare_pair(pair, side=side, settings_check=settings_check)
    pair, easeoff_note = prepared.pair, prepared.note
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    timings = dict(prepared.timings_s)
    steps = tqdm(total=5 + len(torques), desc=f"analyze {pair.name}", disable=not progress)

    (out / "design.json").write_text(json.dumps(pair.blank.as_dict(), indent=2))
    t0 = time.perf_counter()
    # the flanks the synthesis built, eased, else built on the check's gear flanks
    tca, flanks = analyze_pair(pair, side=side, phases=phases, flanks=prepared.flank_set(),
                               progress=False)
    write_tca_outputs(tca, flanks, pair, out, side=side, figures=figures)
    timings["tca_s"] = time.perf_counter() - t0
    steps.update(2)

    golden = get_engine("golden", material=pair.pinion_material, material2=pair.gear_material)
    stencil = tca.stencil.gap_mm.ravel()
    rc = tca.mean_curvature
    # host-side fp64 line-core rule (any positive input) beside the golden line core
    host = ReferenceEngine(material=pair.pinion_material, material2=pair.gear_material,
                           envelope=False)
    cases, reference, gold, chain = [], [], [], []
    # compile the LCP kernels first: solve_ms then times the solves alone
    timings["jit_warm_up_s"] = warm_up(solver)
    t0 = time.perf_counter()
    for torque in torques:
        steps.set_postfix_str(f"LTCA {torque:g} N·m")
        with warnings.catch_warnings():
            # edge contact is reported in the results, not as a console warning
            warnings.simplefilter("ignore", ContactAtEdgeWarning)
            # each torque solved cold: its row is a function of its torque alone, not
            # of the torques before it (a warm start ends within the LCP's tolerance of
            # the cold solution, not on it: p90 moved by 3.9e-6 MPa on s0003 at 64.5 N·m)
            case = single_pair_ltca(tca, flanks, pair, torque, side=side, solver=solver)
        cases.append(case)
        length = _line_length(case)
        reference.append(host.hertz(rc.A_minus_per_mm, rc.B_minus_per_mm, case.load_n,
                                    line_length_mm=length))
        gold.append(_golden_preview(golden.hertz, rc.A_minus_per_mm, rc.B_minus_per_mm,
                                    case.load_n, line_length_mm=length))
        chain.append(_golden_preview(golden.stencil, stencil, case.load_n,
                                     **({} if length is None else {"line_length_mm": length})))
        steps.update(1)
    timings["ltca_s"] = time.perf_counter() - t0

    # result files hold no timings (identical runs, identical files): solve times go to
    # Analysis.timings_s, which the command line writes into run.json
    timings["ltca_solve_ms"] = [c.patch.lcp.solve_time_ms for c in cases]
    (out / "ltca.json").write_text(json.dumps([without_timings(c.summary())[0]
                                               for c in cases], indent=2))
    write_csv(out / "ltca_torques.csv",
              ["torque_nm", "load_n", "preview_p_max_mpa", "p_mean_mpa", "p90_mpa",
               "p_peak_mpa", "preview_vs_mean_pct", "preview_vs_p90_pct",
               "peak_over_p90", "delta_mm", "mesh_rotation_arcsec",
               "preview_mesh_rotation_arcsec", "n_contact_cells", "edge_contact"],
              [[c.torque_nm, c.load_n, c.preview.p_max_mpa, c.patch.p_mean_mpa,
                c.patch.p90_mpa, c.patch.p_peak_mpa,
                100.0 * (c.preview.p_max_mpa / c.patch.p_mean_mpa - 1.0),
                100.0 * (c.preview.p_max_mpa / c.patch.p90_mpa - 1.0),
                c.patch.p_peak_mpa / c.patch.p90_mpa, c.patch.delta_mm,
                c.mesh_rotation_arcsec, c.preview_mesh_rotation_arcsec,
                c.patch.n_contact_cells, int(c.edge_contact)]
               for c in cases])
    write_csv(out / "preview.csv", PREVIEW_COLUMNS,
              _preview_rows(cases, reference, gold, chain))
    for c in cases:
        write_pressure_csv(c, out / f"pressure_{c.torque_nm:g}Nm.csv")
    if figures:
        plot_pressure_maps(cases, out / "pressure_maps.png", title=f"{pair.name} {side}")
        plot_pressure_vs_load(cases, out / "pressure_vs_load.png", title=f"{pair.name} {side}",
                              published=published_values(pair.name))
    steps.update(1)
    lte = multitooth = None
    if lte_torque_nm is not None:
        steps.set_postfix_str(f"LTE {lte_torque_nm:g} N·m")
        t0 = time.perf_counter()
        stride = max(1, -(-(len(tca.cycle.phi1_rad) - 1) // max(int(lte_phases) - 1, 1)))
        bending = None
        if lte_bending:
            from ..ltca.tooth_bending import tooth_bending

            bending = tooth_bending(flanks, pair, side=side)
        lte = loaded_te(tca, flanks, pair, lte_torque_nm, side=side, stride=stride,
                        bending=bending, progress=progress)
        write_lte_outputs(lte, out, figures=figures, title=f"{pair.name} {side}",
                          published=published_values(pair.name))
        timings["lte_s"] = time.perf_counter() - t0
        multitooth = _multi_tooth(tca, flanks, pair, lte_torque_nm, side, out, figures,
                                  timings)
    steps.update(1)
    steps.set_postfix_str("fixed-point precision")
    t0 = time.perf_counter()
    precision = write_precision_outputs(out, figures=figures)
    timings["precision_s"] = time.perf_counter() - t0
    latency = scalar_latency(20_000)
    # the cycle counts are results; the CPU latency is a timing of this machine
    (out / "latency.json").write_text(json.dumps(
        {"core_cycles": core_cycles(), "cycles_spread": 0}, indent=2))
    timings["preview_cpu"] = {"p50_us": latency.p50_us, "p99_us": latency.p99_us,
                              "jitter": latency.jitter, "calls": latency.calls}
    steps.update(1)
    steps.close()
    missing = _missing_warning(gold, chain)
    if missing is not None:      # after the progress bar: one clean line on stderr
        warnings.warn(missing, PreviewDomainWarning, stacklevel=2)
    beyond = law_range_warning(reference, [g for g, _ in gold], [ch for ch, _ in chain])
    if beyond is not None:
        warnings.warn(beyond, HertzLawRangeWarning, stacklevel=2)
    result = Analysis(pair, tca, tuple(cases), tuple(g for g, _ in gold),
                      tuple(ch for ch, _ in chain), timings, out, lte, precision, latency,
                      side, flanks, easeoff_note, multitooth,
                      golden_status=tuple(st for _, st in gold),
                      chain_status=tuple(st for _, st in chain), reference=tuple(reference),
                      settings_check=prepared.settings_check)
    write_summary(result, out / "summary.md", published=published_values(pair.name))
    return result
