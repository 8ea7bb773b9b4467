"""A pair's polynomial ease-off sampled as a measured deviation grid CSV (the format of
``gearcontact.geometry.easeoff.read_easeoff_grid``), shared by the setting-fit tests of
the library and the command line."""

import numpy as np

from gearcontact.geometry.easeoff import EaseOff


def write_grid_csv(path, pair, flanks, side, n_u=6, n_v=9, pad=0.0):
    """The pair's ease-off of ``side`` sampled on a grid over the active box, as CSV."""
    b = flanks.pinion_conjugate.side(side).boundary
    u_m, v_m = flanks.mean_contact[side]["pinion_uv"]
    eo = EaseOff.from_coefficients(getattr(pair, f"easeoff_{side}"), u_mean_mm=u_m,
                                   v_mean_mm=v_m)
    rows = ["side,v_mm,u_mm,easeoff_um"]
    for u in np.linspace(b.u_root, b.u_tip - pad, n_u):
        for v in np.linspace(b.v_toe, b.v_heel, n_v):
            rows.append(f"{side},{float(v)!r},{float(u)!r},{1e3 * float(eo.relief_mm(u, v))!r}")
    path.write_text("\n".join(rows) + "\n")
    return path
