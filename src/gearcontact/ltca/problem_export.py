"""The solved single-pair LCP as a self-contained file, so that anyone can re-solve it
with another solver (``gearcontact ltca --export-problem``).

The problem (Johnson 1985, ch. 5; Polonsky & Keer 1999): on a uniform tangent-plane
grid of rectangular cells, find pressures ``p >= 0`` and the rigid approach ``delta``
with

    u = C p  (Love 1929: normal displacement of a half-space under uniform pressure on
    each rectangular cell, combined modulus E*), g = h + u - delta >= 0,
    p g = 0 cellwise, and sum(p) dx dy = W.

``write_lcp_problem`` writes ``<name>.npz`` (arrays listed in :data:`FIELDS`) and
``<name>.README.md`` (the formulation, every array with its unit, and a re-check recipe).
"""

from __future__ import annotations

import zipfile
from pathlib import Path

import numpy as np

from ..materials import reduced_modulus_mpa

__all__ = ["FIELDS", "write_lcp_problem", "lcp_problem_arrays"]

#: Arrays of the .npz: name -> description with unit.
FIELDS = {
    "gap_mm": "unloaded gap h[j, i] at (x_mm[i], y_mm[j]), mm; cells off a flank hold "
              "the off-flank separation (no material there)",
    "on_flank": "bool, the cell's normal line meets both flanks",
    "x_mm": "cell centres along s (the long axis of the preview ellipse), mm",
    "y_mm": "cell centres along t, mm",
    "dx_mm": "cell size along s, mm",
    "dy_mm": "cell size along t, mm",
    "load_n": "normal load W, N",
    "e_star_mpa": "combined modulus E* = 1 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2), MPa",
    "pressure_mpa": "the solution p[j, i], MPa",
    "delta_mm": "the solution's rigid approach delta, mm",
    "contact_mask": "bool, cells with p > 0 in the solution",
    "torque_nm": "gear torque, N·m (W = 1000 torque / lever)",
    "lever_mm": "effective lever of the normal force about the gear axis, mm",
}


def lcp_problem_arrays(case, materials) -> dict:
    """The arrays of :data:`FIELDS` for a :class:`~.pair_ltca.PairLoadCase` solved
    between ``materials`` (pinion, gear)."""
    if case.gap_mm is None or case.on_flank is None:
        raise ValueError("the load case carries no gap field (made by an older version)")
    g, p = case.patch.grid, case.patch
    return {"gap_mm": np.asarray(case.gap_mm, dtype=float),
            "on_flank": np.asarray(case.on_flank, dtype=bool),
            "x_mm": np.asarray(g.x_mm, dtype=float), "y_mm": np.asarray(g.y_mm, dtype=float),
            "dx_mm": np.float64(np.mean(g.dx_mm)), "dy_mm": np.float64(np.mean(g.dy_mm)),
            "load_n": np.float64(case.load_n),
            "e_star_mpa": np.float64(reduced_modulus_mpa(*materials)),
            "pressure_mpa": np.asarray(p.pressure_mpa, dtype=float),
            "delta_mm": np.float64(p.delta_mm),
            "contact_mask": np.asarray(p.lcp.contact_mask, dtype=bool),
            "torque_nm": np.float64(case.torque_nm), "lever_mm": np.float64(case.lever_mm)}


def _readme(arrays: dict, name: str, title: str) -> str:
    rows = "\n".join(f"| `{k}` | {np.shape(arrays[k]) or 'scalar'} | {v} |"
                     for k, v in FIELDS.items())
    return f"""# {name}.npz: {title}

The loaded contact of one tooth pair, as the linear complementarity problem gearcontact
solved, with its solution. Load with `numpy.load("{name}.npz")`.

## Problem

On the uniform tangent-plane grid (`x_mm`, `y_mm`, cell size `dx_mm` x `dy_mm`) find the
pressure `p >= 0` (MPa) and the rigid approach `delta` (mm) such that

    g = gap_mm + C p - delta >= 0,   p * g = 0 in every cell,   sum(p) dx dy = load_n

where `(C p)[j, i]` is the normal surface displacement at the centre of cell (j, i) of
an elastic half-space with combined modulus `e_star_mpa` under a uniform pressure on
each rectangular cell (Love 1929; Johnson 1985, eq. 3.25, with 1/(pi E*) for the two
bodies). Cells with `on_flank = False` lie beyond a flank: their gap is large, so the
solution leaves them unloaded.

## Arrays

| array | shape | meaning |
|---|---|---|
{rows}

## Check a solution

With your solver's `p`, verify `p >= 0`, `sum(p) * dx_mm * dy_mm == load_n`, and that
`gap_mm + C p - delta` is >= 0 with `p * g` ~ 0. gearcontact's solution is stored in
`pressure_mpa` and `delta_mm` for comparison.
"""


def write_lcp_problem(case, materials, out_dir, *, name: str = "ltca_problem",
                      title: str = "") -> list[Path]:
    """Write ``<name>.npz`` and ``<name>.README.md`` into ``out_dir``; returns both paths."""
    out = Path(out_dir)
    arrays = lcp_problem_arrays(case, materials)
    npz = out / f"{name}.npz"
    # np.savez stamps each member with the current time; fixed stamps keep identical
    # runs byte-identical (the format is the same: one .npy per array in a zip)
    with zipfile.ZipFile(npz, "w", compression=zipfile.ZIP_DEFLATED) as zf:
        for key, value in arrays.items():
            info = zipfile.ZipInfo(f"{key}.npy", date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            with zf.open(info, "w") as fh:
                np.lib.format.write_array(fh, np.asanyarray(value), allow_pickle=False)
    readme = out / f"{name}.README.md"
    readme.write_text(_readme(arrays, name, title or "single-pair loaded contact"))
    return [npz, readme]
