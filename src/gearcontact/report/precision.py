"""Fixed-point precision of the gap kernel in the report (docs/spec.md sec. 8, item 8).

Measures the golden model's signed-gap error against the fp64 reference over the word
widths (:func:`gearcontact.preview.gap.precision.gap_precision_sweep`): the coordinate
word width ``cw = 8 + cf`` = 14..32 bits with the 8 integer bits of the contract fixed
(fraction bits ``cf`` = 6..24: the published 14–24-bit sweep and on to the golden
model's widest word) at the hardware's normal width
(``rf`` = 19), and normal fraction bits ``rf`` = 12..24 at the hardware's coordinate
width (``cf`` = 16), each beside the first-order bound

    |e_g| <= sqrt(3) 2^-cf + 3 ||d||_inf 2^-(rf+1) + 2^-(cf+1).

Writes ``precision.csv`` (one row per setting) and ``precision.png`` (two log panels:
max and RMS error and the bound against each word width).
"""

from __future__ import annotations

from pathlib import Path

from ..figure_files import save_figure
from ..preview.gap.golden import GapFormat
from ..preview.gap.precision import PrecisionPoint, gap_precision_sweep
from ..tca.export import write_csv

__all__ = ["COORD_FRACS", "NORMAL_FRACS", "plot_precision", "precision_sweeps",
           "write_precision_outputs"]

#: Coordinate fraction bits swept at the hardware normal width (word widths 14..32 bits
#: with the contract's 8 integer bits; the published figure covers 14..24).
COORD_FRACS = tuple(range(6, 25))
#: Normal fraction bits swept at the hardware coordinate width.
NORMAL_FRACS = tuple(range(12, 25, 2))


def precision_sweeps(*, n_samples: int = 1000, seed: int = 0
                     ) -> tuple[tuple[PrecisionPoint, ...], tuple[PrecisionPoint, ...]]:
    """(sweep over cf at the hardware rf, sweep over rf at the hardware cf)."""
    hw = GapFormat()
    by_coord = gap_precision_sweep(coord_fracs=COORD_FRACS, normal_fracs=(hw.normal_frac,),
                                   n_samples=n_samples, seed=seed)
    by_normal = gap_precision_sweep(coord_fracs=(hw.coord_frac,), normal_fracs=NORMAL_FRACS,
                                    n_samples=n_samples, seed=seed)
    return by_coord, by_normal


def write_precision_outputs(out_dir, *, figures: bool = True, n_samples: int = 1000
                            ) -> tuple[tuple[PrecisionPoint, ...], tuple[PrecisionPoint, ...]]:
    """Run :func:`precision_sweeps` and write ``precision.csv`` (+ ``precision.png``)."""
    out = Path(out_dir)
    by_coord, by_normal = precision_sweeps(n_samples=n_samples)
    ci = GapFormat().coord_int
    rows = [["coord", ci + p.coord_frac, p.coord_frac, p.normal_frac, p.max_error_mm * 1e3,
             p.rms_error_mm * 1e3, p.bound_mm * 1e3, p.max_bound_ratio]
            for p in by_coord + by_normal]
    for r in rows[len(by_coord):]:
        r[0] = "normal"
    write_csv(out / "precision.csv", ["swept", "coord_width_bits", "coord_frac_bits",
                                      "normal_frac_bits", "max_error_um", "rms_error_um",
                                      "bound_um", "max_error_over_bound"], rows)
    if figures:
        plot_precision(by_coord, by_normal, out / "precision.png")
    return by_coord, by_normal


def plot_precision(by_coord, by_normal, path) -> Path:
    """Two log panels: max / RMS gap error and the first-order bound against the
    coordinate word width and the normal fraction bits (format from the suffix)."""
    from matplotlib.ticker import MaxNLocator

    from .figures import plt

    hw = GapFormat()
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    for ax, pts, attr, fixed, label in (
            (axes[0], by_coord, "coord_frac", f"rf = {hw.normal_frac}",
             f"coordinate word width {hw.coord_int} + cf (bits)"),
            (axes[1], by_normal, "normal_frac", f"cf = {hw.coord_frac}",
             "normal fraction bits rf")):
        offset = hw.coord_int if attr == "coord_frac" else 0
        x = [getattr(p, attr) + offset for p in pts]
        ax.semilogy(x, [p.bound_mm * 1e3 for p in pts], "k-", label="first-order bound")
        ax.semilogy(x, [p.max_error_mm * 1e3 for p in pts], "o-", color="C3",
                    label="max |golden - fp64|")
        ax.semilogy(x, [p.rms_error_mm * 1e3 for p in pts], "s--", color="C0", label="RMS")
        hw_x = hw.coord_bits if attr == "coord_frac" else hw.normal_frac
        ax.axvline(hw_x, color="0.6", lw=0.8, ls=":", label="hardware width")
        if attr == "coord_frac":
            # the published figure sweeps the coordinate word over 14..24 bits
            ax.axvspan(14, 24, color="C2", alpha=0.08, label="published sweep 14-24 bits")
        ax.xaxis.set_major_locator(MaxNLocator(integer=True))     # bits, not 17.5
        ax.set_xlabel(label)
        ax.set_title(f"signed gap error vs {label.split(' ')[0]} width ({fixed})", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("gap error (um)")
    axes[0].legend(fontsize=8)
    fig.suptitle("Gap kernel fixed-point precision (golden model vs fp64, 1000 samples)")
    fig.tight_layout()
    path = save_figure(fig, path)
    plt.close(fig)
    return path
