"""Files of ``gearcontact rtl synth``: the synthesis results of one core.

:func:`write_synth_outputs` writes ``synth_<core>[_nodsp].csv`` (one row per
:class:`~gearcontact.hw.synth.SynthResult`, :func:`~gearcontact.hw.synth.write_csv`),
``synth_<core>[_nodsp].json`` (the results and, for a gap-core sweep over at least two lane
counts, the DSP48E1 line :func:`~gearcontact.hw.synth.dsp_fit`) and, for the gap cores,
the figure ``synth_<core>[_nodsp].png`` (:func:`~gearcontact.hw.synth.plot_sweep`).
"""

from __future__ import annotations

import json
from dataclasses import asdict
from pathlib import Path

from ..hw.synth import GAP_CORES, DspFit, dsp_fit, plot_sweep, write_csv

__all__ = ["write_synth_outputs"]


def write_synth_outputs(results, out, *, core: str, nodsp: bool = False
                        ) -> tuple[dict, DspFit | None]:
    """Write the synthesis files of ``results`` (of ``core``; ``nodsp``: synthesized
    without DSP blocks) into the directory ``out`` (created if missing).

    Returns
    -------
    summary : dict
        The JSON content.
    fit : DspFit or None
        The DSP48E1 line of a gap-core sweep over at least two lane counts.
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    tag = "_nodsp" if nodsp else ""
    write_csv(results, out / f"synth_{core}{tag}.csv")
    summary = {"results": [asdict(r) for r in results]}
    fit = None
    if core in GAP_CORES and len(results) >= 2:
        fit = dsp_fit(results)
        plot_sweep(results, out / f"synth_{core}{tag}.png", fit)
        summary["dsp_fit"] = asdict(fit)
    elif core in GAP_CORES:
        plot_sweep(results, out / f"synth_{core}{tag}.png")
    (out / f"synth_{core}{tag}.json").write_text(json.dumps(summary, indent=2))
    return summary, fit
