"""The report's statement of previews whose Hertz law lies beyond its range: one line
naming which previews, the largest curvature ratio and how far the Hamrock–Brewe law is
from exact Hertz there (docs/hertz.md sec. 7); ``analyze``'s warning and summary."""

from __future__ import annotations

from ..analytic.hertz import hamrock_brewe_error_table
from ..analytic.hertz_range import HB_RATIO_LIMIT, HB_TOLERANCE
from ..preview.hertz.reference import LAW_OK

__all__ = ["law_range_warning"]


def law_range_warning(reference, golden, chain) -> str | None:
    """One line naming the previews whose Hamrock–Brewe law lies beyond its 5 % range
    (:func:`~gearcontact.preview.hertz.reference.law_status`), the largest curvature
    ratio and the law's stiffness and p_max against exact Hertz there, or None.

    Parameters
    ----------
    reference, golden, chain : sequence of PreviewResult or None
        The fp64, golden stage-D and golden C -> D previews per torque (None: missing).

    Returns
    -------
    str or None
    """
    beyond = {name: [r for r in results if r is not None and r.law_status != LAW_OK]
              for name, results in (("fp64", reference), ("golden D", golden),
                                    ("golden C->D", chain))}
    if not any(beyond.values()):
        return None
    ratio = max(max(r.A_minus_per_mm, r.B_minus_per_mm) / min(r.A_minus_per_mm,
                                                               r.B_minus_per_mm)
                for rs in beyond.values() for r in rs)
    row = hamrock_brewe_error_table([ratio])[0]
    counts = ", ".join(f"{name} {len(rs)} of {n}" for (name, rs), n in
                       zip(beyond.items(), (len(reference), len(golden), len(chain))) if rs)
    return (f"Hertz law beyond its range: the Hamrock-Brewe ellipse at curvature ratio up "
            f"to {ratio:.4g} (> {HB_RATIO_LIMIT:g}, where it leaves {100 * HB_TOLERANCE:g} % "
            f"of exact Hertz) for {counts} torques; there the law's stiffness is "
            f"{100 * row['err_stiffness']:+.1f} %, its p_max {100 * row['err_p_max']:+.1f} % "
            "against exact Hertz (preview.csv *_law_status; docs/hertz.md sec. 7)")
