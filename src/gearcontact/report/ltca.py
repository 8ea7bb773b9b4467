"""Loaded single-pair contact files: the summary, the pressure map and its figure.

:func:`write_ltca_outputs` writes ``ltca.json`` (:meth:`~gearcontact.ltca.pair_ltca.
PairLoadCase.summary` without timings, plus the caller's ``extra`` keys),
``pressure_map.csv`` (``s_mm,t_mm,pressure_mpa`` over the principal-frame field),
``pressure_map.png`` (:func:`plot_pressure_map`) and, given the materials, the solved LCP
as ``ltca_problem.npz`` with ``ltca_problem.README.md``
(:func:`~gearcontact.ltca.problem_export.write_lcp_problem`); used by ``gearcontact ltca``.
"""

from __future__ import annotations

import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (backend must be chosen first)
import numpy as np  # noqa: E402

from ..halfspace.patch import plot_patch  # noqa: E402
from ..ltca.pair_ltca import preview_ellipse  # noqa: E402
from ..ltca.problem_export import write_lcp_problem  # noqa: E402
from ..tca.export import without_timings, write_csv  # noqa: E402

__all__ = ["plot_pressure_map", "write_pressure_csv", "write_ltca_outputs"]


def plot_pressure_map(case, path, *, title: str = "") -> Path:
    """The LCP pressure over the principal-frame field (s along the long axis, t across,
    mm) with the Hertzian preview ellipse overlaid in cyan; written as PNG at 120 dpi.

    Parameters
    ----------
    case : PairLoadCase
        The solved load case (:func:`~gearcontact.ltca.pair_ltca.single_pair_ltca`).
    path : str or Path
        Target PNG file.
    title : str
        Start of the figure title (pair and side); torque, load and pressures follow.

    Returns
    -------
    Path
        ``path``.
    """
    path = Path(path)
    g = case.patch.grid
    fig, ax = plt.subplots(figsize=(9, 3.2))
    plot_patch(case.patch, ax, ellipse=preview_ellipse(case.preview, g))
    ax.set_title(f"{title} {case.torque_nm:g} N·m, W = {case.load_n:.0f} N:"
                 f" LCP p90 {case.patch.p90_mpa:.0f}, peak {case.patch.p_peak_mpa:.0f};"
                 f" preview p_max {case.preview.p_max_mpa:.0f} MPa (cyan)", fontsize=9)
    ax.set_xlabel("s along the long axis (mm)")
    ax.set_ylabel("t (mm)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def write_pressure_csv(case, path) -> Path:
    """Write the LCP pressure of ``case`` over its principal-frame field as CSV, one row
    per cell: ``s_mm,t_mm,pressure_mpa`` (s along the long axis, mm; MPa).

    Parameters
    ----------
    case : PairLoadCase
        A solved load case (its ``patch``).
    path : str or Path
        Target CSV file.

    Returns
    -------
    Path
        ``path``.
    """
    g = case.patch.grid
    s, t = np.meshgrid(g.x_mm, g.y_mm)
    write_csv(path, ["s_mm", "t_mm", "pressure_mpa"],
              zip(map(float, s.ravel()), map(float, t.ravel()),
                  map(float, case.patch.pressure_mpa.ravel())))
    return Path(path)


def write_ltca_outputs(case, out, *, figures: bool = True, title: str = "",
                       extra: dict | None = None, problem_materials: tuple | None = None,
                       problem_title: str = "") -> dict:
    """Write the files of one loaded pair into ``out`` (created if missing).

    Parameters
    ----------
    case : PairLoadCase
        The solved load case.
    out : str or Path
        Output directory.
    figures : bool
        Also draw ``pressure_map.png``.
    title : str
        Start of the figure title (:func:`plot_pressure_map`).
    extra : dict, optional
        Keys appended to ``ltca.json`` in their order (e.g. the edges the loaded patch
        reaches and the assembly errors used).
    problem_materials : (Material, Material), optional
        Pinion and gear material: also write the solved LCP as ``ltca_problem.npz`` and
        ``ltca_problem.README.md``.
    problem_title : str
        Title of ``ltca_problem.README.md``.

    Returns
    -------
    dict
        The ``ltca.json`` content. Timings (``solve_ms``) stay out of the files, so
        identical runs write identical files.
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    summary, _ = without_timings(case.summary())    # the solve time goes to run.json
    summary.update(extra or {})
    (out / "ltca.json").write_text(json.dumps(summary, indent=2))
    write_pressure_csv(case, out / "pressure_map.csv")
    if figures:
        plot_pressure_map(case, out / "pressure_map.png", title=title)
    if problem_materials is not None:
        write_lcp_problem(case, problem_materials, out, title=problem_title)
    return summary
