"""Test helper: the generating rack's tip rounding as an independent truth of a
cylindrical gear's generated boundary (ISO 53 basic rack), from the rolling of the
generating pitch circle on the rack's pitch line alone (not from the fillet's closed
form, which uses Willis' normal condition), and ISO 6336-3's critical section of the
same rack's trochoid; shared by the real-root and the undercut tests."""

import math

import numpy as np
from scipy.optimize import minimize_scalar


def rack(pair, member):
    """Transverse-section data of the generating rack (ISO 53, pair's factors)."""
    g = pair.geometry
    mn = g.normal_module_mm
    z = getattr(pair, f"{member}_teeth")
    x = getattr(pair, f"profile_shift_{member}")
    an, b = math.radians(g.normal_pressure_angle_deg), math.radians(g.helix_angle_deg)
    r = 0.5 * mn * z / math.cos(b)                  # generating pitch circle
    rho = pair.rack_tip_radius_factor * mn
    datum = r + x * mn                              # rack datum line (profile shift)
    cy = datum - pair.dedendum_factor * mn + rho    # tip rounding centre, rack frame
    # the rack tooth fills the space centred on X = 0; its flank x = pi m_n / 4 - (datum
    # - y) tan(alpha_n) in the normal section, the rounding's centre rho inside it
    cx = 0.25 * math.pi * mn - (datum - cy) * math.tan(an) - rho / math.cos(an)
    lead = (-1.0 if pair.hand(member) == "left" else 1.0) * math.tan(b) / r
    return dict(r=r, rho=rho, cx=cx / math.cos(b), cy=cy, cb=math.cos(b), z=z, lead=lead)


def envelope_gap_mm(rack, side, point):
    """min over the rack shift s of the tip rounding's implicit function at ``point``
    (body frame: tooth on +x), as a distance (F rho / 2, mm): 0 on the boundary the
    rounding generates, < 0 inside some position of it (cut away). The gear turns by
    s / r while the rack moves by s (rolling of the pitch circle on the pitch line);
    "coast" (clockwise facing) is the mirror image y -> -y of the other hand."""
    x, y, z = point
    k = rack["lead"]
    if side == "coast":
        y, k = -y, -k
    a = -k * z                                      # back to the section z = 0
    X, Y = math.cos(a) * x - math.sin(a) * y, math.sin(a) * x + math.cos(a) * y
    r, rho, cb = rack["r"], rack["rho"], rack["cb"]
    space = -(0.5 * math.pi - math.pi / rack["z"])  # the space centred on +y

    def f(s):
        t = -(s / r + space)
        qx = math.cos(t) * X - math.sin(t) * Y - s
        qy = math.sin(t) * X + math.cos(t) * Y
        return ((qx - rack["cx"]) * cb / rho) ** 2 + ((qy - rack["cy"]) / rho) ** 2 - 1.0

    grid = np.linspace(-2.0, 2.0, 801) * 2.0 * math.pi * r / rack["z"]
    vals = np.array([f(s) for s in grid])
    i = int(np.argmin(vals))
    got = minimize_scalar(f, bounds=(grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]),
                          method="bounded", options={"xatol": 1e-12})
    return got.fun * rho / 2.0


def iso_critical_section(pair, member):
    """ISO 6336-3 sec. 6.2: (s_Fn, rho_F) in mm from the generating rack (no
    protuberance, external gear), the theta iteration of the standard."""
    g = pair.geometry
    mn = g.normal_module_mm
    an, b = math.radians(g.normal_pressure_angle_deg), math.radians(g.helix_angle_deg)
    bb = math.asin(math.sin(b) * math.cos(an))
    zn = getattr(pair, f"{member}_teeth") / (math.cos(bb) ** 2 * math.cos(b))
    h_fp, rho_fp = pair.dedendum_factor, pair.rack_tip_radius_factor
    e = math.pi / 4 - h_fp * math.tan(an) - (1 - math.sin(an)) * rho_fp / math.cos(an)
    gg = rho_fp - h_fp + getattr(pair, f"profile_shift_{member}")
    h = 2 / zn * (math.pi / 2 - e) - math.pi / 3
    th = math.pi / 6
    for _ in range(100):
        th = 2 * gg / zn * math.tan(th) - h
    s_fn = zn * math.sin(math.pi / 3 - th) + math.sqrt(3) * (gg / math.cos(th) - rho_fp)
    rho_f = rho_fp + 2 * gg * gg / (math.cos(th) * (zn * math.cos(th) ** 2 - 2 * gg))
    return s_fn * mn, rho_f * mn


def radius_at(root, side, point, across, down, h_mm=0.02):
    """Radius of the circle through three side-curve points ``h_mm`` apart around
    ``point``, projected into the section plane (across, down), mm."""
    q = np.linspace(0.0, 1.0, 20001)
    pts = root.side_points(side, np.zeros_like(q), q)
    i = int(np.argmin(np.linalg.norm(pts - point, axis=1)))
    arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    qs = np.interp(arc[i] + np.array([-h_mm, 0.0, h_mm]), arc, q)
    a, b, c = (np.array([p @ across, p @ down])
               for p in root.side_points(side, np.zeros(3), qs))
    ab, bc, ca = np.linalg.norm(a - b), np.linalg.norm(b - c), np.linalg.norm(c - a)
    area2 = abs((b - a)[0] * (c - a)[1] - (b - a)[1] * (c - a)[0])
    return ab * bc * ca / (2.0 * area2)
