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
    with pytest.raises(InputRangeError):
        plot_flanks_in_mesh(flanks, side="sideways")
