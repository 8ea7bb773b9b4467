"""A fitted generating motion as ``design`` writes it: the roll a fit leaves at rounding
written as its seed's (docs/machine_settings.md sec. 5, "The written roll (session 29)").

A pinion flank is generated while the cradle rolls by ``psi`` and the work turns by
``phi(psi) = R_a (psi - sum_k c_k psi^k / k!)`` with the sliding base moving by
``V(psi) = sum_k h_k psi^k / k!`` (:mod:`.machine`). A fit of the settings
(:mod:`.setting_fit`) moves the ratio of roll ``R_a``, the modified roll ``c_k`` and,
where fitted, the helical motion ``h_k`` from its seed's (the conjugate pinion's); on a
side with nothing to fit (an all-zero ease-off) it leaves them at rounding (s0003's
drive: 2C -1.2e-11, 6D -8.7e-11, ``R_a`` 10.00000000027), which a file would claim as a
modified roll. Against the seed's motion the work turns by the extra angle
``dphi(psi) = (R_a - R_a0) psi - sum_k (R_a c_k - R_a0 c0_k) psi^k / k!`` and the apex
slides by ``dV(psi) = sum_k (h_k - h0_k) psi^k / k!``. Each member of the family of
cutter surfaces moves by ``dphi(psi) (z_w x X) + dV(psi) z_m``, so the envelope moves
along its normal by the normal part of that at the point generated at ``psi`` (first
order), at most

    D = r_max sum_k |a_k| Psi^k + sum_k |b_k| Psi^k

(``a_k``, ``b_k`` the coefficients of ``dphi`` and ``dV`` in powers of ``psi``; ``Psi``
the largest ``|psi|`` and ``r_max`` the largest radius from the work axis over the
flank's node grid, :func:`roll_reach`, 6 x 6 nodes over the active flank and its node
margin). Below :data:`~.written_blade.STRAIGHT_DEVIATION_MM` (1 nm, the blade's rule) the
side's ratio of roll, modified roll and helical motion are written as its seed's; every
other value is written as fitted. A relieved blade's side is written as it is.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from .conjugate import UndercutError
from .machine import MachineSetup, mirror_setup
from .written_blade import STRAIGHT_DEVIATION_MM

__all__ = ["motion_departure_mm", "roll_coefficients", "roll_reach", "seed_roll",
           "written_rolls"]

#: Nodes per direction of the grid :func:`roll_reach` reads ``Psi`` and ``r_max`` from.
REACH_NODES = 6


def roll_coefficients(setup: MachineSetup, seed: MachineSetup) -> tuple[tuple, tuple]:
    """Coefficients of the work's extra turn ``dphi`` (rad, ``a_1, a_2, ...`` of
    ``psi, psi^2, ...``) and of the apex's extra slide ``dV`` (mm, ``b_1, b_2, ...``)
    of ``setup``'s generating motion against ``seed``'s (module docstring)."""
    st, s0 = setup.settings, seed.settings

    def padded(vals, n):
        return tuple(vals) + (0.0,) * (n - len(vals))

    n = max(len(st.modified_roll), len(s0.modified_roll))
    c, c0 = padded(st.modified_roll, n), padded(s0.modified_roll, n)
    a = (st.ratio_of_roll - s0.ratio_of_roll,) + tuple(
        -(st.ratio_of_roll * ck - s0.ratio_of_roll * c0k) / math.factorial(k + 2)
        for k, (ck, c0k) in enumerate(zip(c, c0)))
    m = max(len(st.helical_motion), len(s0.helical_motion))
    h, h0 = padded(st.helical_motion, m), padded(s0.helical_motion, m)
    b = tuple((hk - h0k) / math.factorial(k + 1) for k, (hk, h0k) in enumerate(zip(h, h0)))
    return a, b


def motion_departure_mm(setup: MachineSetup, seed: MachineSetup, *, psi_max_rad: float,
                        radius_mm: float) -> float:
    """Bound ``D`` on the normal displacement of the flank ``setup`` generates from the
    one generated with ``seed``'s roll and helical motion (the rest of ``setup`` kept),
    for rolls within ``psi_max_rad`` (rad) and flank points within ``radius_mm`` of the
    work axis (module docstring), mm."""
    a, b = roll_coefficients(setup, seed)
    turn = sum(abs(ak) * psi_max_rad ** (k + 1) for k, ak in enumerate(a))
    slide = sum(abs(bk) * psi_max_rad ** (k + 1) for k, bk in enumerate(b))
    return radius_mm * turn + slide


def roll_reach(setup: MachineSetup, blank, *, pinion_face_width_mm: float, box=None
               ) -> tuple[float, float]:
    """``(Psi, r_max)``: the largest ``|psi|`` (rad) and the largest radius from the
    pinion axis (mm) over the :data:`REACH_NODES` x :data:`REACH_NODES` node grid of the
    pinion flank ``setup`` generates (its active flank with the node margin; ``box``:
    that active box when already traced, a :class:`~.formate.FlankBoundary`).

    Raises
    ------
    UndercutError
        The envelope does not reach a node of the grid."""
    from .generated import generated_pinion_flank     # the envelope: imported on use

    _, nodes = generated_pinion_flank(setup, blank, pinion_face_width_mm=pinion_face_width_mm,
                                      n_u=REACH_NODES, n_v=REACH_NODES, box=box)
    radius = np.hypot(nodes.x_mm[..., 1], nodes.x_mm[..., 2])   # pinion axis: body x
    return float(np.max(np.abs(nodes.psi_rad))), float(np.max(radius))


def seed_roll(setup: MachineSetup, seed: MachineSetup) -> MachineSetup:
    """``setup`` with ``seed``'s ratio of roll, modified roll and helical motion (every
    other value kept)."""
    s0 = seed.settings
    return dataclasses.replace(setup, settings=dataclasses.replace(
        setup.settings, ratio_of_roll=s0.ratio_of_roll, modified_roll=s0.modified_roll,
        helical_motion=s0.helical_motion))


def _motion_words(setup: MachineSetup) -> str:
    st = setup.settings
    words = [f"ratio of roll {st.ratio_of_roll:.12g}"]
    words += [f"{name} {v:.3g}" for name, v in zip(("2C", "6D", "24E", "120F"),
                                                   st.modified_roll) if v != 0.0]
    words += [f"V{k + 1} {v:.3g} mm" for k, v in enumerate(st.helical_motion) if v != 0.0]
    return ", ".join(words)


def written_rolls(cut, fits: dict, *, boxes: dict | None = None):
    """``cut`` with each fitted pinion side whose generating motion departs from its
    seed's by less than :data:`~.written_blade.STRAIGHT_DEVIATION_MM` over its flank
    (:func:`motion_departure_mm`) written with its seed's roll and helical motion, and
    the lines for the written file's head naming each. A side whose flank's node grid
    the envelope does not reach is written as fitted (no bound, no claim).

    Parameters
    ----------
    cut : GearPair
        The pair to write, its pinion set-ups the fits' (mirrored for a left-hand pair).
    fits : dict
        ``{side: SettingFit}`` of the pinion (``setup`` and ``seed`` on the right-hand
        twin, as :func:`~.easeoff_settings.easeoff_machine_pair` fits them).
    boxes : dict, optional
        ``{side: FlankBoundary}``: the fitted flanks' active boxes, already traced (the
        fit's ``SideResidual.box``); traced here where missing.

    Returns
    -------
    (GearPair, list of str)
    """
    left = cut.pinion_hand == "left"
    twin = dataclasses.replace(cut, pinion_hand="right") if left else cut
    machine, notes = [], []
    for setup in cut.machine:
        fit = fits.get(setup.side) if setup.member == "pinion" else None
        if fit is None or setup.blade.relieved or seed_roll(fit.setup, fit.seed) == fit.setup:
            machine.append(setup)
            continue
        try:
            psi_max, radius = roll_reach(fit.setup, twin.blank,
                                         pinion_face_width_mm=twin.pinion_face_width_mm,
                                         box=(boxes or {}).get(setup.side))
        except UndercutError:
            machine.append(setup)
            continue
        dev = motion_departure_mm(fit.setup, fit.seed, psi_max_rad=psi_max, radius_mm=radius)
        if dev < STRAIGHT_DEVIATION_MM:
            seed = mirror_setup(fit.seed) if left else fit.seed
            notes.append(f"machine.pinion.{setup.side}: the fitted motion ({_motion_words(setup)}) "
                         f"departs {dev * 1e3:.1g} um from its seed's over the flank (|psi| <= "
                         f"{psi_max:.3f} rad, radius <= {radius:.2f} mm; < "
                         f"{STRAIGHT_DEVIATION_MM * 1e3:g} um): written as the seed's "
                         f"({_motion_words(seed)}), docs/machine_settings.md sec. 5")
            setup = seed_roll(setup, seed)
        machine.append(setup)
    return dataclasses.replace(cut, machine=tuple(machine)), notes
