"""Test helper: the cylindrical loaded TE without its edge rows beyond the helical lines
(``ltca.cylindrical_lte``'s ``beyond_line_edge_gaps`` with every gap NaN), as before
those rows existed; shared by the loaded-TE and the twin's edge tests."""

from dataclasses import replace

import numpy as np

from gearcontact.ltca import cylindrical_lte as lte_module


def without_lte_edges(monkeypatch) -> None:
    """Patch the loaded TE so that its edges beyond the lines never close."""
    real = lte_module.beyond_line_edge_gaps

    def none(*args, **kwargs):
        return tuple(replace(b, gap_mm=np.full_like(b.gap_mm, np.nan))
                     for b in real(*args, **kwargs))
    monkeypatch.setattr(lte_module, "beyond_line_edge_gaps", none)
