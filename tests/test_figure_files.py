"""``gearcontact.figure_files.save_figure``: PNG + SVG, identical bytes on every run.

Truth: the output-directory contract (identical runs write identical files). The same
figure drawn twice and saved into two directories must give byte-identical PNG and SVG
files; the SVG carries no creation date; the PNG has the size figsize x dpi. No
tolerance: bytes are equal or not.
"""

import struct

import numpy as np

from gearcontact.figure_files import save_figure
from gearcontact.report.figures import plt


def _draw():
    fig, ax = plt.subplots(figsize=(4, 3))
    x = np.linspace(0.0, 1.0, 30)
    ax.plot(x, x**2, label="x^2")
    ax.pcolormesh(np.arange(6), np.arange(5), np.arange(20.0).reshape(4, 5))
    ax.set_xlabel("x (mm)")
    ax.legend()
    return fig


def test_png_and_svg_identical_across_runs(tmp_path):
    paths = []
    for run in ("a", "b"):
        (tmp_path / run).mkdir()
        fig = _draw()
        paths.append(save_figure(fig, tmp_path / run / "fig.png", dpi=100))
        plt.close(fig)
    (a, b) = paths
    assert a.suffix == ".png" and a.with_suffix(".svg").is_file()
    assert a.read_bytes() == b.read_bytes()
    svg_a, svg_b = (p.with_suffix(".svg").read_text() for p in paths)
    assert svg_a == svg_b
    assert "<dc:date>" not in svg_a and svg_a.lstrip().startswith("<?xml")
    # PNG IHDR: width, height = figsize * dpi
    w, h = struct.unpack(">II", a.read_bytes()[16:24])
    assert (w, h) == (400, 300)


def test_suffix_is_replaced(tmp_path):
    fig = _draw()
    png = save_figure(fig, tmp_path / "name.svg", tight=True)
    plt.close(fig)
    assert png == tmp_path / "name.png"
    assert png.is_file() and (tmp_path / "name.svg").is_file()
