"""The evaluation of docs/spec.md sec. 8 regenerated into one report.

:func:`run_reproduce` is what ``gearcontact reproduce`` calls. It runs the main job
(:func:`gearcontact.report.analyze.run_analysis`: TCA, single-pair LTCA at the four
torques, loaded TE, fixed-point precision, latency) once and builds the eight items of
the evaluation from its results, adding only what the main job does not compute: the
neural-surrogate study (:mod:`.surrogate`), the explanation studies of the accuracy
item (:mod:`.accuracy_studies`), the loaded TE with tooth bending for the multi-tooth item
(:mod:`gearcontact.ltca.tooth_bending`) and, with ``synth=True``, the synthesis sweep
(:mod:`gearcontact.hw.synth`; otherwise the committed ``data/synth/resources.json``).
The items themselves are built in :mod:`.evaluation_contact` (1, 2, 6, 7) and
:mod:`.evaluation_datapath` (3, 4, 5, 8); the document and its renderings are in
:mod:`.document`.

Files written into ``out`` (besides those of the main job, which the report shows):

=======================  ===================================================================
``report.html``          one page with a table of contents; figures beside it (PNG, SVG)
``report.md``            the same report as Markdown
``report.json``          every number of the report; one top-level key per item
                         (:data:`ITEMS`) plus ``meta``
``surrogate.png/.svg``   the two-panel surrogate figure
``resources.json``       synthesis results with provenance (only with ``synth=True``)
=======================  ===================================================================

Every table has a ``published`` column (values of ``data/published/s0003.json``; empty
where the study gave none). Each item's status is computed from its headline quantities
and their published tolerances (:mod:`.headline`, ``data/published/s0003_headlines.json``):
``reproduced``, ``partial`` or ``differs``; an item that measured nothing (its physics or
data missing) is ``not available`` with the reason; nothing is filled in. ``meta``
counts the statuses (``status_counts``, ``summary``).
"""

from __future__ import annotations

import importlib.util
import json
import time
import warnings
from pathlib import Path

from tqdm import tqdm

from ..validation import InputRangeError
from .accuracy_studies import (BEARING_STEPS_FULL, BEARING_STEPS_QUICK,
                               LENGTHWISE_STEPS_FULL, LENGTHWISE_STEPS_QUICK)
from .analyze import published_values, run_analysis
from .document import Reproduction, Section, jsonable, render_html, render_markdown
from .evaluation_contact import (accuracy_section, lte_section, multitooth_section,
                                 pressure_map_section)
from .evaluation_datapath import (committed_resources, latency_section, precision_section,
                                  resources_section, surrogate_section)
from .headline import status_counts, summary_line

__all__ = ["ITEMS", "run_reproduce", "committed_resources", "QUICK", "FULL"]

#: Report items in the order of docs/spec.md sec. 8 (the keys of ``report.json``).
ITEMS = ("accuracy", "pressure_map", "surrogate", "latency", "resources", "lte",
         "multitooth", "precision")
#: Settings of the quick run (``--quick``: under 2 minutes on 2 cores).
QUICK = {"phases": 15, "lte_phases": 8, "n_train": 1000, "n_test": 400,
         "anchored_train": 4, "grid_cells": (40, 80), "bearing_steps": BEARING_STEPS_QUICK,
         "lengthwise_steps": LENGTHWISE_STEPS_QUICK, "synth_lanes": (8,)}
#: Settings of the full run.
FULL = {"phases": 61, "lte_phases": 61, "n_train": 2000, "n_test": 1000,
        "anchored_train": 6, "grid_cells": (40, 80, 120), "bearing_steps": BEARING_STEPS_FULL,
        "lengthwise_steps": LENGTHWISE_STEPS_FULL, "synth_lanes": (8, 16, 32, 64)}


def _unique_messages(caught) -> list[str]:
    out = []
    for w in caught:
        msg = f"{w.category.__name__}: {w.message}"
        if msg not in out:
            out.append(msg)
    return out


def _note_warnings(section: Section, caught) -> None:
    """Warnings raised while building an item go into the report, not the console."""
    msgs = _unique_messages(caught)
    if msgs:
        section.data["warnings"] = msgs
        section.text.append("Warnings while computing this item: " + "; ".join(msgs) + ".")


def run_reproduce(out_dir, *, quick: bool = False, synth: bool = False,
                  progress: bool = True, pair: str = "s0003") -> Reproduction:
    """Regenerate the evaluation of docs/spec.md sec. 8 for ``pair`` into ``out_dir``.

    Parameters
    ----------
    out_dir : str or Path
        Output directory (created if missing).
    quick : bool
        Reduced sizes (:data:`QUICK`: 15 TCA phases, 8 loaded-TE phases, smaller
        surrogate sets, two grid resolutions); under 2 minutes on 2 cores.
    synth : bool
        Run the synthesis sweep (slow; needs the ``synth`` extra) instead of reading
        committed results.
    progress : bool
        Show a progress bar over the items.
    pair : str
        Built-in pair with published values (``s0003``).
    """
    pub = published_values(pair)
    if pub is None:
        raise InputRangeError("pair", pair, "a built-in pair with published values (s0003)")
    missing = [m for m in ("sklearn", "jinja2") if importlib.util.find_spec(m) is None]
    if missing:      # before the expensive work
        raise ModuleNotFoundError(f"gearcontact reproduce needs {', '.join(missing)}: "
                                  "pip install 'gearcontact[report]'")
    if synth:
        from ..hw.synth import require_yosys
        try:
            require_yosys()
        except RuntimeError as exc:
            raise ModuleNotFoundError(str(exc)) from None
    settings = QUICK if quick else FULL
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    t_start = time.perf_counter()
    times = {}
    bar = tqdm(total=1 + len(ITEMS), desc="reproduce", disable=not progress)
    bar.set_postfix_str("main job (TCA, LTCA, LTE, precision, latency)")
    t0 = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        analysis = run_analysis(pair, out_dir=out, phases=settings["phases"],
                                lte_phases=settings["lte_phases"], progress=False)
    main_warnings = _unique_messages(caught)
    times["analysis_s"] = time.perf_counter() - t0
    times["main_job"] = analysis.timings_s         # its stages, as `gearcontact analyze`
    bar.update(1)
    builders = {
        "accuracy": lambda: accuracy_section(analysis, pub, settings),
        "pressure_map": lambda: pressure_map_section(analysis, pub),
        "surrogate": lambda: surrogate_section(analysis, pub, settings, out),
        "latency": lambda: latency_section(analysis, pub),
        "resources": lambda: resources_section(synth, settings, out, pub),
        "lte": lambda: lte_section(analysis, pub),
        "multitooth": lambda: multitooth_section(analysis, pub, settings),
        "precision": lambda: precision_section(analysis, pub),
    }
    sections = []
    for key in ITEMS:
        bar.set_postfix_str(key)
        t0 = time.perf_counter()
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            sec = builders[key]()
        _note_warnings(sec, caught)
        sections.append(sec)
        times[f"{key}_s"] = time.perf_counter() - t0
        bar.update(1)
    bar.close()
    from .. import __version__

    times["total_s"] = time.perf_counter() - t_start
    counts = status_counts(s.status for s in sections)
    meta = {"title": f"{pair}: the evaluation of docs/spec.md sec. 8 beside the published "
                     "values",
            "intro": (f"gearcontact {__version__}, pair {pair} ({analysis.side} flank pair), "
                      f"{'quick' if quick else 'full'} run. Units: mm, N, MPa, arcsec. "
                      "Published values are those of the original study "
                      "(data/published/s0003.json); differences beyond their tolerance are "
                      "explained in the text of each item with a measurement."),
            "status_counts": counts,
            "summary": (f"{len(sections)} items: {summary_line(counts)}. A status is "
                        "computed from the item's headline quantities and their published "
                        "tolerances (data/published/s0003_headlines.json): reproduced = "
                        "every headline within its tolerance, differs = no key headline "
                        "within, partial otherwise; each item's first paragraph names what "
                        "is outside, measured against published."),
            "version": __version__, "pair": pair, "quick": bool(quick), "synth": bool(synth),
            "settings": {k: list(v) if isinstance(v, tuple) else v
                         for k, v in settings.items()},
            "main_job_warnings": main_warnings,
            "run_text": (f"{'Quick' if quick else 'Full'} run, settings "
                         + ", ".join(f"{k} {v}" for k, v in settings.items())
                         + ". Run times (per item and in total) and the date are in run.json "
                         "of `gearcontact reproduce` (Reproduction.timings_s in Python): the "
                         "report files hold only the timings that are results of the "
                         "evaluation (item 3's training cost, item 4's CPU latency).")}
    rep = Reproduction(tuple(sections), meta, out, analysis, times)
    (out / "report.json").write_text(json.dumps(jsonable(rep.as_json()), indent=2,
                                                allow_nan=False))
    (out / "report.md").write_text(render_markdown(rep))
    (out / "report.html").write_text(render_html(rep))
    return rep
