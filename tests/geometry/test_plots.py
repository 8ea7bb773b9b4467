"""Flank figure: renders a PNG with both sheets."""

import pytest

from gearcontact.geometry.plots import plot_flanks_in_mesh
from gearcontact.validation import InputRangeError


def test_flanks_in_mesh_png(s0003_centred, tmp_path):
    flanks = s0003_centred[1]
    out = tmp_path / "flanks.png"
    fig = plot_flanks_in_mesh(flanks, side="drive", path=out)
    assert out.stat().st_size > 10_000  # a real 1050 x 825 px raster
    ax = fig.axes[0]
    assert len(ax.collections) >= 3  # two sheets + the P0 marker
    # s0003: 7/70, offset 19 mm, a hypoid; a pair without offset is a spiral bevel
    # (the F.2 pair's figure was titled "hypoid")
    assert ax.get_title().startswith("7/70 hypoid, drive flanks in mesh")
    with pytest.raises(InputRangeError):
        plot_flanks_in_mesh(flanks, side="sideways")


def test_flanks_in_mesh_names_a_spiral_bevel(tmp_path):
    from pathlib import Path

    from gearcontact.geometry.flank import build_flanks
    from gearcontact.geometry.pair import load_pair

    root = Path(__file__).resolve().parents[2]
    pair = load_pair(root / "examples" / "iso23509_f2_spiral_bevel.toml")
    assert pair.blank.offset_mm == 0.0
    fig = plot_flanks_in_mesh(build_flanks(pair), side="drive")
    assert fig.axes[0].get_title().startswith("14/39 spiral bevel, drive flanks in mesh")


def test_setting_residual_map_is_labelled_and_its_svg_small(tmp_path):
    # the residual map `design --machine-settings --out` writes: axes and colour bar
    # named with units, the value range symmetric about 0 (a diverging map), and the
    # SVG holding the map as an image. Before, the gouraud mesh went into the SVG as
    # vector triangles: 57 MB for s0003's map, 623 MB for this 200 x 240 one (measured
    # without the fix). Bound: 2 MB (the PNG of such a figure is ~0.2 MB; the SVG embeds
    # the rasterized map base64-encoded)
    from types import SimpleNamespace

    import numpy as np

    from gearcontact.figure_files import save_figure
    from gearcontact.geometry.plots import plot_setting_residual

    v, u = np.meshgrid(np.linspace(28.0, 44.0, 240), np.linspace(0.4, 2.9, 200))
    res = 0.5 * np.sin(v) * np.cos(3.0 * u)
    sides = {s: SimpleNamespace(side=s, points=None, v_mm=v, u_mm=u, residual_um=f * res,
                                max_um=float(np.abs(f * res).max()), rms_um=0.1,
                                easeoff_max_um=22.9)
             for s, f in (("drive", 0.0), ("coast", 1.0))}
    fig = plot_setting_residual(SimpleNamespace(sides=sides))
    png = save_figure(fig, tmp_path / "map.png")
    assert png.with_suffix(".svg").stat().st_size < 2_000_000
    axes = [ax for ax in fig.axes if ax.get_title()]
    assert [ax.get_title().split(":")[0] for ax in axes] == ["pinion drive", "pinion coast"]
    for ax in axes:
        assert "(mm)" in ax.get_xlabel() and "(mm)" in ax.get_ylabel()
        mesh = ax.collections[0]
        assert mesh.norm.vmin == -mesh.norm.vmax == -float(np.abs(res).max())
        assert mesh.colorbar.ax.get_ylabel() == "residual (um)"
