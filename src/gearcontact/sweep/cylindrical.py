"""Sweeps of a cylindrical pair (``kind = "cylindrical"``; docs/sweeps.md): the keys of
its TOML ``[modifications.pinion]``, ``[modifications.gear]`` and ``[assembly]`` tables
by their dotted names (``--vary modifications.pinion.tip_relief_um=0:20:5``,
``--vary assembly.axis_inclination_um=-20:20:9``), and one grid point's results.

Every key changes the pair itself (its flanks are closed-form involute helicoids with
the micro-geometry, built inside the TCA), so each grid point is a pair with the keys
replaced, checked again by :class:`~gearcontact.geometry.cylindrical.pair.CylindricalPair`
(a value outside its range, a tip relief without a start diameter: named
:class:`~gearcontact.validation.InputRangeError`). A point runs the unloaded mesh cycle
(:func:`~gearcontact.tca.cylindrical_cycle.cylindrical_mesh_cycle`) and per torque the
loaded TE over it (:func:`~gearcontact.ltca.cylindrical_lte.cylindrical_loaded_te`,
``cells`` along the face): the values an NVH engineer maps (TE0 and loaded TE
peak-to-peak, peak pressure, mean mesh stiffness), the same numbers as
``gearcontact tca`` / ``gearcontact lte`` on the modified pair file.
"""

from __future__ import annotations

import numpy as np

from ..geometry.cylindrical.pair import MeshAlignment, ToothModifications

__all__ = ["CYLINDRICAL_KEYS", "CYLINDRICAL_LTCA_VARIABLES", "CYLINDRICAL_TCA_VARIABLES",
           "CYLINDRICAL_BOOL_VARIABLES", "compute_cylindrical_point"]

#: TOML key (``table.key``) -> (CylindricalPair attribute, field of that attribute).
CYLINDRICAL_KEYS: dict[str, tuple[str, str]] = {
    **{f"modifications.{member}.{name}": (f"modifications_{member}", name)
       for member in ("pinion", "gear") for name in ToothModifications.__dataclass_fields__
       if name != "member"},
    **{f"assembly.{name}": ("assembly", name) for name in MeshAlignment.__dataclass_fields__},
}
#: Per grid point (the unloaded cycle does not depend on torque): name -> (unit, text).
CYLINDRICAL_TCA_VARIABLES = {
    "te0_pp_arcsec": ("arcsec", "unloaded transmission error, peak to peak"),
    "te0_mean_arcsec": ("arcsec", "unloaded transmission error, mean over the pitch "
                                  "(negative: the gear lags)"),
    "line_length_mean_mm": ("mm", "total length of the lines in the zone, mean over the "
                                  "pitch"),
    "pairs_in_contact_mean": ("1", "tooth pairs touching unloaded, mean over the pitch"),
}
#: Per cell with ``ltca`` (with the shell bending of both teeth, the loaded TE's default,
#: unless the loaded-TE options say otherwise).
CYLINDRICAL_LTCA_VARIABLES = {
    "lte_pp_arcsec": ("arcsec", "loaded transmission error, peak to peak"),
    "p_max_mpa": ("MPa", "peak contact pressure over the pitch"),
    "stiffness_mean_n_per_mm_um": ("N/(mm um)", "secant mesh stiffness per unit face "
                                                "width, mean over the pitch"),
    "lte_edge_touch": ("1", "a loaded cell on the edge of the strip across a line"),
}
CYLINDRICAL_BOOL_VARIABLES = {"lte_edge_touch"}


def _periodic_mean(x) -> float:
    """Mean over one pitch whose phases include both ends (the last is the first)."""
    return float(np.mean(np.asarray(x, dtype=float)[:-1]))


def compute_cylindrical_point(pair, torques_nm, *, side: str, compute: tuple,
                              phases: int = 61, cells: int = 40, options=None) -> dict:
    """Results of one grid point of a cylindrical pair.

    Parameters
    ----------
    pair : CylindricalPair
        The pair with this point's keys replaced (:func:`.design.vary_design`).
    torques_nm : sequence of float
        Gear torques, N·m (``ltca`` only).
    side : str
        ``"drive"`` or ``"coast"`` (the facing:
        :data:`~gearcontact.tca.cylindrical_cycle.FACING_OF_SIDE`).
    compute : tuple of str
        ``("tca",)`` or ``("tca", "ltca")``.
    phases, cells : int
        Phases per pinion pitch; cells along the face of the loaded TE.
    options : dict, optional
        Further keyword options of
        :func:`~gearcontact.ltca.cylindrical_lte.cylindrical_loaded_te`.

    Returns
    -------
    dict
        ``variable -> list over torques`` and ``error`` (``""`` or ``"Name: message"``;
        an LCP that does not converge is ``LCPNotConverged`` with its values kept).
    """
    from ..ltca.cylindrical_lte import cylindrical_loaded_te
    from ..tca.cylindrical_cycle import FACING_OF_SIDE, cylindrical_mesh_cycle

    n = len(torques_nm)
    cycle = cylindrical_mesh_cycle(pair, facing=FACING_OF_SIDE[side], phases=phases)
    out: dict = {
        "te0_pp_arcsec": [float(cycle.te0_pp_arcsec)] * n,
        "te0_mean_arcsec": [_periodic_mean(cycle.envelope_arcsec)] * n,
        "line_length_mean_mm": [float(cycle.mean_line_length_mm)] * n,
        "pairs_in_contact_mean": [_periodic_mean(cycle.pairs_in_contact)] * n,
        "error": [""] * n}
    if "ltca" not in compute:
        return out
    for name in CYLINDRICAL_LTCA_VARIABLES:
        out[name] = [False if name in CYLINDRICAL_BOOL_VARIABLES else np.nan] * n
    for i, torque in enumerate(torques_nm):
        res = cylindrical_loaded_te(pair, float(torque), cycle=cycle, cells_along=cells,
                                    **(options or {}))
        out["lte_pp_arcsec"][i] = res.lte_pp_arcsec
        out["p_max_mpa"][i] = float(res.max_pressure_mpa.max())
        out["stiffness_mean_n_per_mm_um"][i] = res.mean_stiffness_n_per_mm_um
        out["lte_edge_touch"][i] = bool(res.edge_touch)
        if not res.converged:
            out["error"][i] = "LCPNotConverged: the loaded TE's LCP at some phase"
    return out
