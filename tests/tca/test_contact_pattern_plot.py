"""The TCA contact-pattern figure (tca.plots): the paint never shows off the flank.

Truths: the flank boundary is the surface's own (its points along the four edges of its
(u, v) box, computed here from ``Surface.point``); the drawn image is read back pixel
by pixel: no paint-coloured pixel outside the boundary (the boundary polygon widened by
3 px for its own 1 pt line and anti-aliasing), while the same figure with the clip
removed has some there (the ISO 23509 F.2 example cut from machine settings,
examples/machine_settings/: its edge-phase ellipses reach past the flank, the audit
measured one ~37 mm across its 25 mm face), so the pixel test sees what it tests.
Identical runs write identical files (PNG and SVG, byte for byte).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib
import numpy as np
import pytest
from matplotlib.path import Path as MplPath

from gearcontact.geometry.pair import load_pair
from gearcontact.tca.analysis import analyze_pair
from gearcontact.tca.plots import axial_projection, contact_pattern_figure, plot_contact_pattern

ROOT = Path(__file__).resolve().parents[2]
PAINT_ALPHA = 0.12              # the paint's alpha in tca.plots
MARGIN_PX = 3.0                 # the boundary line (1 pt = 1.8 px at 130 dpi) + AA


@pytest.fixture(scope="module")
def f2():
    pair = load_pair(ROOT / "examples" / "machine_settings" / "iso23509_f2_machine.toml")
    res, flanks = analyze_pair(pair, phases=21)
    side = pair.design_side
    return (flanks.flank("pinion", side), flanks.flank("gear", side), pair.kinematics(),
            res)


def _outline(surface, member, n=40):
    """The flank boundary in the axial projection, from the surface's (u, v) box."""
    (u0, u1), (v0, v1) = surface.u_range, surface.v_range
    u, v = np.linspace(u0, u1, n), np.linspace(v0, v1, n)
    uv = ([(a, v0) for a in u] + [(u1, b) for b in v] + [(a, v1) for a in u[::-1]]
          + [(u0, b) for b in v[::-1]])
    return axial_projection(np.array([surface.point(a, b).r for a, b in uv]), member)


def _paint(ax):
    return [p for p in ax.patches if p.get_alpha() == PAINT_ALPHA]


def _paint_pixels_off_flank(fig, outlines) -> int:
    """Pixels inside an axes, outside its flank outline widened by MARGIN_PX, with the
    paint's colour cast: one layer of paint over white has R - B = 0.12 (R - B of the
    colour) = 21/255 (tab:red) or 29/255 (tab:orange), so 8/255 is below any painted
    pixel; the grid, the boundary and the markers are grey or black (R = B), the
    contact path (red) runs inside the flank."""
    fig.canvas.draw()
    img = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(int)
    h = img.shape[0]
    count = 0
    for ax, outline in zip(fig.axes, outlines):
        x0, y0, x1, y1 = ax.bbox.extents
        ys, xs = np.mgrid[int(h - y1) + 2:int(h - y0) - 2, int(x0) + 2:int(x1) - 2]
        px = np.column_stack([xs.ravel() + 0.5, h - ys.ravel() - 0.5])
        boundary = MplPath(ax.transData.transform(outline))
        # outside the widened boundary: not within MARGIN_PX of the inside
        inside = boundary.contains_points(px, radius=2 * MARGIN_PX) | \
            boundary.contains_points(px, radius=-2 * MARGIN_PX)
        rgb = img[ys.ravel(), xs.ravel()]
        cast = rgb[:, 0] - rgb[:, 2] > 8
        count += int((cast & ~inside).sum())
    return count


def test_paint_is_clipped_to_the_flank_boundary(f2):
    pinion, gear, kin, res = f2
    assert any(res.edges), "the F.2 example has edge phases at 21 phases"
    fig = contact_pattern_figure(pinion, gear, kin, res.cycle, edges=res.edges)
    outlines = [_outline(gear, "gear"), _outline(pinion, "pinion")]
    for ax, outline in zip(fig.axes, outlines):
        paint = _paint(ax)
        assert paint
        for patch in paint:
            clip = patch.get_clip_path()
            assert clip is not None
            # the clip path is the flank boundary, through the axes' data transform
            # (display pixels; 1e-6 px: the same points through the same transform; the
            # outline ends where it starts, at (u0, v0): closed)
            got = clip.get_fully_transformed_path().vertices
            want = ax.transData.transform(outline)
            assert got.shape == want.shape
            assert np.allclose(got, want, rtol=0.0, atol=1e-6)
    assert _paint_pixels_off_flank(fig, outlines) == 0
    for ax in fig.axes:                 # the same figure unclipped: paint off the flank
        for patch in _paint(ax):
            patch.set_clip_path(None)
            patch.set_clip_box(ax.bbox)
    assert _paint_pixels_off_flank(fig, outlines) > 0
    matplotlib.pyplot.close(fig)


def test_contact_pattern_png_is_byte_identical_between_runs(f2, tmp_path):
    pinion, gear, kin, res = f2
    a = plot_contact_pattern(pinion, gear, kin, res.cycle, tmp_path / "a.png",
                             edges=res.edges)
    b = plot_contact_pattern(pinion, gear, kin, res.cycle, tmp_path / "b.png",
                             edges=res.edges)
    assert Path(a).read_bytes() == Path(b).read_bytes()
    # and its SVG (figure_files: a fixed hash salt, the clip paths' ids included)
    assert Path(a).with_suffix(".svg").read_bytes() == Path(b).with_suffix(".svg").read_bytes()
