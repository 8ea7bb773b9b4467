"""Cradle-type face-milling machine: blades, basic machine settings and their kinematics.

One flank of one member is cut (single indexing, face milling) by one blade of a
face-milling cutter mounted on the cradle of a generator (docs/machine_settings.md has
the figure and the sign table). Frames:

- cutter ``S_t``: origin at the cutter centre in the plane of the blade tips, ``z_t``
  the cutter axis pointing out of the cutter towards the work. A blade is a surface of
  revolution about ``z_t``; its profile in the axial half-plane at blade angle
  ``theta`` (``e_rho = cos(theta) x_t + sin(theta) y_t``) is, with the arc length ``l``
  from the tip and the profile angle ``alpha(l)`` (straight blade: ``alpha`` constant),

      x = rho(l) e_rho - z(l) z_t,   rho' = -sigma sin(alpha),   z' = cos(alpha),
      n = sigma cos(alpha) e_rho - sin(alpha) z_t

  (``sigma`` = +1 inside blade, -1 outside blade; ``n`` the unit normal out of the cut
  tooth into the slot). A curved blade (profile radius ``r_b``) has
  ``alpha(l) = alpha_0 + (l - l_ref) / r_b`` (``r_b > 0``: the blade bulges into the
  slot, a crowned profile on the cut tooth; ``alpha_0`` holds at ``l_ref``). A blade
  with a higher-order profile adds the cubic and quartic terms ``c_3``, ``c_4`` of
  the profile about ``l_ref`` (``s = l - l_ref``):

      alpha(l) = alpha_0 + s / r_b + c_3 s^2 / 2 + c_4 s^3 / 6

  (the profile's curvature ``1/r_b + c_3 s + c_4 s^2 / 2`` varies along the blade; the
  normal offset from the tangent at ``l_ref`` is ``s^2/(2 r_b) + c_3 s^3/6 + c_4 s^4/24``
  to first order, positive into the slot), integrated by Gauss-Legendre quadrature.
- machine ``S_m``: origin at the machine centre (the cradle axis meets the plane of
  the blade tips), ``z_m`` the cradle axis towards the work, ``x_m`` the projection of
  the work axis onto the cradle plane, ``y_m = z_m x x_m``.
- cradle: turned by the roll ``psi`` about ``z_m``; the cutter centre lies at radial
  distance ``S_r`` and cradle angle ``q`` (from ``x_m``, about ``z_m``); the cutter
  axis is tilted by ``i`` from the cradle axis towards the cradle-plane direction at
  angle ``q + j`` (``j`` = swivel): ``T_0 = Rz(q + j) Ry(i)``.
- work ``S_w``: origin at the work's pitch apex, ``z_w`` the work axis (apex -> back),
  ``x_w = (sin gamma_m, 0, -cos gamma_m)`` (the radial direction in the plane of the
  two axes, towards the cradle plane) at zero roll; the work axis is
  ``w = (cos gamma_m, 0, sin gamma_m)`` (``gamma_m`` = machine root angle) and the apex
  lies at ``A = X_D w + (X_B + V(psi)) z_m + E_m y_m`` (machine centre to back, sliding
  base with helical motion ``V``, blank offset).

Generating motion (Litvin & Fuentes 2004, sec. 20.3 / 21.4; Fan 2006): the cradle
turns by ``psi`` and the work by ``phi(psi) = R_a (psi - sum_k c_k psi^k / k!)`` about
``z_w`` (``R_a`` ratio of roll work/cradle, ``c_2 = 2C``, ``c_3 = 6D``, ... the
modified-roll coefficients as printed), so that a cutter point maps to the work as

    X_w(l, theta, psi) = Rz(-phi) B^T (Rz(psi) (C_0 + T_0 x_t) - A(psi))

(``B`` = columns ``x_w, y_w, w`` in ``S_m``). The generated flank is the envelope of
the blade surface in this motion: ``n_w . dX_w/dpsi = 0`` (equation of meshing,
Litvin & Fuentes 2004, sec. 6.1). ``R_a = 0`` without helical motion is a formate cut
(the flank is the blade surface itself).

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 20-21
(face-milled spiral bevel and hypoid gears: head-cutter surfaces, machine-tool settings,
modified roll, tilted head cutter).
Q. Fan, "Computerized modeling and simulation of spiral bevel and hypoid gears
manufactured by Gleason face hobbing process", *ASME J. Mech. Des.* 128 (2006) 1315-1327
(universal generation model: radial, cradle angle, tilt, swivel, machine root, blank
offset, sliding base, helical motion, modified roll).
H. J. Stadtfeld, *Handbook of Bevel and Hypoid Gears: Calculation, Manufacturing,
Optimization*, Rochester Institute of Technology, 1993 (blade profiles beyond the
straight line: curved blades, Toprem and Flankrem reliefs, ground on a blade grinder).
Y.-P. Shih, Z.-H. Fong, "Flank modification methodology for face-hobbing hypoid gears
based on ease-off topology", *ASME J. Mech. Des.* 129 (2007) 1294-1302.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from ..validation import InputRangeError, check_range
from .blade import (BladeSettings, EdgeRound, blade_point, blade_profile, blade_through_point,
                    edge_round)

__all__ = ["BLADE_KEYS", "BladeSettings", "EdgeRound", "HELICAL_KEYS", "MACHINE_KEYS", "MEMBERS",
           "MODIFIED_ROLL_KEYS", "MachineKinematics", "MachineSettings", "MachineSetup",
           "blade_point", "blade_profile", "blade_through_point", "edge_round", "mirror_setup",
           "relieved_blade_keys", "setup_from_tables", "setup_to_tables"]

#: Members of a pair, in the order used by the pair format.
MEMBERS = ("gear", "pinion")

#: Largest |psi| (rad) the generating roll may reach; beyond it the cutter is far off
#: the work for any practical set-up (the modified-roll polynomial is a local series).
MAX_ROLL_RAD = 1.5


@dataclass(frozen=True)
class MachineSettings:
    """Basic machine settings of a cradle-type generator (``[machine.<member>.<flank>]``).

    Lengths in mm, angles in degrees (signs: module docstring and
    docs/machine_settings.md).

    Parameters
    ----------
    radial_distance_mm : float
        S_r, cradle axis to cutter centre, mm, >= 0.
    cradle_angle_deg : float
        q, from x_m about z_m, degrees, in (-180, 180].
    machine_root_angle_deg : float
        gamma_m, work axis to cradle plane, degrees, in [-10, 90].
    machine_centre_to_back_mm : float
        X_D, apex position along the work axis from the machine centre, mm.
    sliding_base_mm : float
        X_B, along the cradle axis, mm.
    blank_offset_mm : float
        E_m, along y_m, mm.
    ratio_of_roll : float
        R_a = work rotation / cradle rotation; 0 = formate (no roll).
    modified_roll : tuple of float
        (2C, 6D, 24E, 120F): ``phi = R_a (psi - 2C psi^2/2 - 6D psi^3/6 - ...)``,
        1/rad^(k-1), each in [-100, 100].
    tilt_deg, swivel_deg : float
        Cutter tilt i in [0, 60] and swivel j in (-180, 180], degrees.
    helical_motion : tuple of float
        (V_1, V_2): sliding base during the roll ``V(psi) = V_1 psi + V_2 psi^2 / 2``,
        mm/rad^k, each in [-1000, 1000].
    """

    radial_distance_mm: float
    cradle_angle_deg: float
    machine_root_angle_deg: float
    machine_centre_to_back_mm: float = 0.0
    sliding_base_mm: float = 0.0
    blank_offset_mm: float = 0.0
    ratio_of_roll: float = 0.0
    modified_roll: tuple = ()
    tilt_deg: float = 0.0
    swivel_deg: float = 0.0
    helical_motion: tuple = ()
    where: str = field(default="machine", compare=False, repr=False)

    def __post_init__(self):
        w = self.where
        check_range(f"{w}.radial_distance_mm", self.radial_distance_mm, 0.0, 1000.0)
        check_range(f"{w}.cradle_angle_deg", self.cradle_angle_deg, -180.0, 180.0,
                    lo_open=True)
        check_range(f"{w}.machine_root_angle_deg", self.machine_root_angle_deg, -10.0, 90.0)
        for name in ("machine_centre_to_back_mm", "sliding_base_mm", "blank_offset_mm"):
            check_range(f"{w}.{name}", getattr(self, name), -1000.0, 1000.0)
        check_range(f"{w}.ratio_of_roll", self.ratio_of_roll, -100.0, 100.0)
        check_range(f"{w}.tilt_deg", self.tilt_deg, 0.0, 60.0)
        check_range(f"{w}.swivel_deg", self.swivel_deg, -180.0, 180.0, lo_open=True)
        for name, keys, lim in (("modified_roll", MODIFIED_ROLL_KEYS, 100.0),
                                ("helical_motion", HELICAL_KEYS, 1000.0)):
            vals = getattr(self, name)
            if len(vals) > len(keys):
                raise InputRangeError(f"{w}.{name}", list(vals),
                                      f"at most {len(keys)} coefficients ({', '.join(keys)})")
            for key, x in zip(keys, vals):
                check_range(f"{w}.{key}", x, -lim, lim)
            object.__setattr__(self, name, tuple(float(x) for x in vals))

    @property
    def formate(self) -> bool:
        """True for a formate cut: no roll and no helical motion."""
        return self.ratio_of_roll == 0.0 and not any(self.helical_motion)


@dataclass(frozen=True)
class MachineSetup:
    """The machine settings and the blade that cut one flank (``member``, ``side``)."""

    member: str
    side: str
    settings: MachineSettings
    blade: BladeSettings


def relieved_blade_keys(setups) -> list[tuple[str, float]]:
    """``("[blade.<member>.<side>] toprem_angle_deg", 2.0)`` (and ``flankrem_angle_deg``)
    of every relieved blade among ``setups`` (its flank is a
    :class:`~.kinked.KinkedFlank`): what a consumer that cannot keep a kink names when it
    refuses the pair."""
    return [(f"[blade.{s.member}.{s.side}] {name}_angle_deg",
             float(getattr(s.blade, f"{name}_angle_deg")))
            for s in setups for name in ("toprem", "flankrem")
            if getattr(s.blade, f"{name}_angle_deg") != 0.0]


def mirror_setup(setup: MachineSetup) -> MachineSetup:
    """The set-up of the mirror image (``y_m -> -y_m``, the plane of the cradle axis and
    the work axis): the cradle and the work turn the other way (``psi -> -psi``,
    ``phi -> -phi``), so the cradle angle, swivel and blank offset change sign, and so
    do the even-order modified-roll terms (2C, 24E) and the odd-order helical term
    (V_1); the ratio of roll, machine root, tilt, MCTB and sliding base stay. A
    left-hand pair's settings are those of its right-hand twin mirrored."""
    st = setup.settings
    flip = lambda vals, first: tuple(-x if (k + first) % 2 == 0 else x  # noqa: E731
                                     for k, x in enumerate(vals))
    return dataclasses.replace(setup, settings=dataclasses.replace(
        st, cradle_angle_deg=-st.cradle_angle_deg if st.cradle_angle_deg != 180.0 else 180.0,
        swivel_deg=-st.swivel_deg if st.swivel_deg != 180.0 else 180.0,
        blank_offset_mm=-st.blank_offset_mm, modified_roll=flip(st.modified_roll, 2),
        helical_motion=flip(st.helical_motion, 2)))


def _rz(angle):
    """Rotation matrices about z, (..., 3, 3)."""
    a = np.asarray(angle, dtype=float)
    c, s = np.cos(a), np.sin(a)
    z, o = np.zeros_like(a), np.ones_like(a)
    return np.stack([np.stack([c, -s, z], -1), np.stack([s, c, z], -1),
                     np.stack([z, z, o], -1)], -2)


def _series(psi, coeffs, first: int):
    """``sum_k coeffs[k] psi^(k + first) / (k + first)!`` and its psi-derivative."""
    val, der = np.zeros_like(psi), np.zeros_like(psi)
    for k, c in enumerate(coeffs):
        p = k + first
        val = val + c * psi ** p / math.factorial(p)
        der = der + c * psi ** (p - 1) / math.factorial(p - 1)
    return val, der


@dataclass(frozen=True, eq=False)
class MachineKinematics:
    """Cutter -> work motion of one machine set-up (module docstring).

    Parameters
    ----------
    settings : MachineSettings
    """

    settings: MachineSettings

    @property
    def _fixed(self):
        got = self.__dict__.get("_fixed_cache")
        if got is None:
            st = self.settings
            q, i, j = (math.radians(x) for x in (st.cradle_angle_deg, st.tilt_deg,
                                                  st.swivel_deg))
            g = math.radians(st.machine_root_angle_deg)
            c0 = st.radial_distance_mm * np.array([math.cos(q), math.sin(q), 0.0])
            ry = np.array([[math.cos(i), 0.0, math.sin(i)], [0.0, 1.0, 0.0],
                           [-math.sin(i), 0.0, math.cos(i)]])
            t0 = _rz(q + j) @ ry
            w = np.array([math.cos(g), 0.0, math.sin(g)])
            b = np.column_stack([[math.sin(g), 0.0, -math.cos(g)], [0.0, 1.0, 0.0], w])
            a0 = (st.machine_centre_to_back_mm * w + st.sliding_base_mm * np.array([0, 0, 1.0])
                  + st.blank_offset_mm * np.array([0, 1.0, 0]))
            got = (c0, t0, b, a0)
            object.__setattr__(self, "_fixed_cache", got)
        return got

    def work_rotation(self, psi_rad):
        """``(phi, dphi/dpsi)`` of the work for cradle roll ``psi`` (rad)."""
        st = self.settings
        psi = np.asarray(psi_rad, dtype=float)
        mod, dmod = _series(psi, st.modified_roll, 2)
        return st.ratio_of_roll * (psi - mod), st.ratio_of_roll * (1.0 - dmod)

    def cutter_to_machine(self, x_t):
        """Cutter-frame points (..., 3) in the machine frame at zero roll."""
        c0, t0, _, _ = self._fixed
        return np.asarray(x_t) @ t0.T + c0

    def to_work(self, x_t, n_t, psi_rad):
        """Cutter point and normal -> work frame at roll ``psi``, with the velocity.

        Returns
        -------
        x_w, n_w, v_w : ndarray (..., 3)
            Point (mm), unit normal and ``dX_w/dpsi`` at fixed cutter point (mm/rad).
        """
        c0, t0, b, a0 = self._fixed
        x_t, n_t, psi = np.asarray(x_t, dtype=float), np.asarray(n_t, dtype=float), np.asarray(
            psi_rad, dtype=float)
        shape = np.broadcast_shapes(x_t.shape[:-1], n_t.shape[:-1], psi.shape)
        psi = np.broadcast_to(psi, shape)
        x0 = np.broadcast_to(x_t @ t0.T + c0, shape + (3,))   # machine frame, zero roll
        n0 = np.broadcast_to(n_t @ t0.T, shape + (3,))
        c, s = np.cos(psi)[..., None], np.sin(psi)[..., None]
        hel, dhel = _series(psi, self.settings.helical_motion, 1)
        # cradle roll about z_m, then the apex (with helical motion) and the work axes
        xm = np.concatenate([c * x0[..., :1] - s * x0[..., 1:2], s * x0[..., :1] + c * x0[..., 1:2],
                             x0[..., 2:] - hel[..., None]], axis=-1) - a0
        nm = np.concatenate([c * n0[..., :1] - s * n0[..., 1:2], s * n0[..., :1] + c * n0[..., 1:2],
                             n0[..., 2:]], axis=-1)
        dxm = np.concatenate([-(xm[..., 1:2] + a0[1]), xm[..., :1] + a0[0],
                              -dhel[..., None]], axis=-1)
        phi, dphi = self.work_rotation(psi)
        cw, sw = np.cos(phi)[..., None], np.sin(phi)[..., None]

        def work(v):  # Rz(-phi) B^T v
            y = v @ b
            return np.concatenate([cw * y[..., :1] + sw * y[..., 1:2],
                                   -sw * y[..., :1] + cw * y[..., 1:2], y[..., 2:]], axis=-1)

        x_w, n_w, dx = work(xm), work(nm), work(dxm)
        v_w = dx + dphi[..., None] * np.concatenate([x_w[..., 1:2], -x_w[..., :1],
                                                     np.zeros_like(x_w[..., :1])], axis=-1)
        return x_w, n_w, v_w


# --------------------------------------------------------------------------- TOML

#: ``[machine.<member>.<flank>]`` keys -> (MachineSettings field, required). The
#: modified-roll and helical-motion series are spelled out key by key (printed values).
MACHINE_KEYS = {
    "radial_distance_mm": ("radial_distance_mm", True),
    "cradle_angle_deg": ("cradle_angle_deg", True),
    "machine_root_angle_deg": ("machine_root_angle_deg", True),
    "machine_centre_to_back_mm": ("machine_centre_to_back_mm", False),
    "sliding_base_mm": ("sliding_base_mm", False),
    "blank_offset_mm": ("blank_offset_mm", False),
    "ratio_of_roll": ("ratio_of_roll", False),
    "tilt_deg": ("tilt_deg", False),
    "swivel_deg": ("swivel_deg", False),
}
#: Modified roll 2C, 6D, 24E, 120F (1/rad, 1/rad^2, ...) and helical motion (mm/rad^k).
MODIFIED_ROLL_KEYS = ("modified_roll_2c_per_rad", "modified_roll_6d_per_rad2",
                      "modified_roll_24e_per_rad3", "modified_roll_120f_per_rad4")
HELICAL_KEYS = ("helical_motion_mm_per_rad", "helical_motion_mm_per_rad2")
#: ``[blade.<member>.<flank>]`` keys -> required.
BLADE_KEYS = {"kind": True, "blade_angle_deg": True, "point_radius_mm": True,
              "edge_radius_mm": False, "profile_radius_mm": False,
              "profile_reference_mm": False, "profile_cubic_per_mm2": False,
              "profile_quartic_per_mm3": False, "toprem_angle_deg": False,
              "toprem_depth_mm": False, "flankrem_angle_deg": False, "flankrem_depth_mm": False}
#: Blade keys written only when non-zero (a circular blade's table stays as it was).
_HIGHER_ORDER_KEYS = ("profile_cubic_per_mm2", "profile_quartic_per_mm3", "toprem_angle_deg",
                      "toprem_depth_mm", "flankrem_angle_deg", "flankrem_depth_mm")


def _series_from(table: dict, keys: tuple) -> tuple:
    vals = [float(table.get(k, 0.0)) for k in keys]
    while vals and vals[-1] == 0.0:
        vals.pop()
    return tuple(vals)


def setup_from_tables(member: str, side: str, machine: dict, blade: dict) -> MachineSetup:
    """The :class:`MachineSetup` of typed (already type-checked) TOML tables
    ``[machine.<member>.<side>]`` and ``[blade.<member>.<side>]``; every value is
    range-checked here, naming the dotted key. The ratio of roll turns work and cradle
    in the same sense (docs/machine_settings.md sec. 2, both hands): a typed one is
    >= 0, and > 0 for the pinion, which is generated (a formate cut, 0, is the gear's
    only, sec. 4)."""
    where = f"machine.{member}.{side}"
    settings = MachineSettings(
        **{field_: machine[key] for key, (field_, _) in MACHINE_KEYS.items() if key in machine},
        modified_roll=_series_from(machine, MODIFIED_ROLL_KEYS),
        helical_motion=_series_from(machine, HELICAL_KEYS), where=where)
    if settings.ratio_of_roll < 0.0 or (member == "pinion" and settings.ratio_of_roll == 0.0):
        raise InputRangeError(
            f"{where}.ratio_of_roll", settings.ratio_of_roll,
            ("> 0: the pinion is generated (work / cradle rotation, the same sense for both "
             "hands; 0 would be a formate pinion, which is not cut), docs/machine_settings.md "
             "sec. 2 and 4" if member == "pinion" else
             ">= 0: work / cradle rotation, the same sense for both hands (0: a formate "
             "gear), docs/machine_settings.md sec. 2"))
    return MachineSetup(member, side, settings,
                        BladeSettings(**blade, where=f"blade.{member}.{side}"))


def setup_to_tables(setup: MachineSetup) -> tuple[dict, dict]:
    """``(machine table, blade table)`` of ``setup`` (inverse of :func:`setup_from_tables`)."""
    st, b = setup.settings, setup.blade
    machine = {key: float(getattr(st, field_)) for key, (field_, _) in MACHINE_KEYS.items()}
    for keys, vals in ((MODIFIED_ROLL_KEYS, st.modified_roll), (HELICAL_KEYS, st.helical_motion)):
        machine.update({k: float(v) for k, v in zip(keys, vals)})
    blade = {"kind": b.kind, **{k: float(getattr(b, k)) for k in BLADE_KEYS if k != "kind"
                                and (k not in _HIGHER_ORDER_KEYS or getattr(b, k) != 0.0)}}
    return machine, blade
