"""Figure files: every figure of a command as PNG and SVG, identical on every run.

:func:`save_figure` writes a matplotlib figure as ``<name>.png`` (for reading) and
``<name>.svg`` (vector, for print and editing) beside each other. Identical runs must
write identical files (the output-directory contract, README "Command line"): the SVG
backend otherwise stamps the creation date into its metadata and derives its element ids
from a random salt, so the date is left out and the salt fixed (matplotlib rcParam
``svg.hashsalt``); PNG output is deterministic already.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["SVG_HASHSALT", "save_figure", "pyplot"]

#: Fixed salt of the SVG element ids (any constant makes them reproducible).
SVG_HASHSALT = "gearcontact"


def pyplot():
    """``matplotlib.pyplot`` on the Agg backend, imported on the first call: a process
    that draws nothing (a refused option, ``--no-figures``) never pays its 0.5 s of CPU
    (docs/performance.md, "Test suite budget")."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_figure(fig, path, *, dpi: int = 120, tight: bool = False) -> Path:
    """Write ``fig`` as PNG and SVG and return the PNG path.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure (left open: the caller closes it).
    path : str or Path
        Target file; its suffix is replaced by ``.png`` and ``.svg``.
    dpi : int
        Resolution of the PNG, dots per inch (the SVG is resolution-free).
    tight : bool
        Crop to the drawn content (``bbox_inches="tight"``), e.g. for legends placed
        outside the axes.

    Returns
    -------
    Path
        The PNG file; the SVG is the same path with suffix ``.svg``.
    """
    import matplotlib   # here: a process that draws nothing never loads it

    path = Path(path)
    png, svg = path.with_suffix(".png"), path.with_suffix(".svg")
    extra = {"bbox_inches": "tight"} if tight else {}
    with matplotlib.rc_context({"svg.hashsalt": SVG_HASHSALT}):
        fig.savefig(png, dpi=dpi, **extra)
        fig.savefig(svg, metadata={"Date": None}, **extra)
    return png
