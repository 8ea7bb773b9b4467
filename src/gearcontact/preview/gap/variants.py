"""Datapath variants of the gap core: the published one and ``lean`` (15 DSP48E1 per lane).

Stage B of a lane forms, per component k, ``gamma n_k`` and ``e_k^2`` (docs/spec.md
sec. 6; formats in :mod:`.golden`). On a DSP48E1 (25 x 18 signed multiplier) the
published widths cost, per lane (``synth_xilinx -family xc7``):

==================  ==========  =================  ===============  ============
product             operands    published (plain)  ``gap`` (split)  ``gap_lean``
==================  ==========  =================  ===============  ============
n_k d_k             21 x 25 b   2                  2                2
gamma n_k           27 x 21 b   4                  2                2
e_k^2               27 x 27 b   4                  3                1
per lane (3 k)                  30                 21               15
==================  ==========  =================  ===============  ============

``"lean"`` squares e_k in 18 bits (:data:`LEAN_E_BITS`, one B port: one slice per
square). A sample with any e_k outside ``[-2^17, 2^17 - 1]`` gets the saturated residual
``rho = 2^64 - 1``: it is never held by its lane and never passes the gate. No other word
changes (n . d, gamma and gamma n are bit-identical), nor does the schedule: the lean core
takes :func:`.golden.gap_latency` cycles, 26 at N = L = 16.

Equivalence with the published datapath (exact, no precision argument needed)
    A saturated sample has ``rho >= e_k^2 >= (2^17)^2 = 2^34``. With a gate
    ``tau2 <= 2^34`` (:func:`lean_tau2_max`; tau <= 2 mm at cf = 16) it fails the gate in
    the published core too. Per lane: if the published minimum passes the gate, that
    sample is unsaturated, keeps its rho, and every sample tying it is unsaturated as
    well (rho < 2^34), so the lean lane holds the same (first) sample; if it does not
    pass, neither does the lean lane's (every rho' >= rho >= tau2). The keys, the tree
    and the outputs are then equal bit for bit. Above ``tau2 = 2^34`` the lean core
    follows its own golden model (``variant="lean"``) exactly and ignores samples whose
    residual component reaches 2 mm -- samples the published core would gate in only
    with a gate wider than the residual, i.e. off the local flank patch.

The gate is a flank-sampling radius (a sample counts if p' lies within tau of its
normal line); 2 mm covers sample grids up to ~2.8 mm pitch. The seeded random
stimulus (:func:`gearcontact.preview.stimulus.gap_stimulus`) draws tau up to 40 mm and
raw codes up to 2^63: those vectors check the lean core against its own model.
"""

from __future__ import annotations

from ...validation import InputRangeError

__all__ = ["GAP_VARIANTS", "LEAN_E_BITS", "check_variant", "lean_tau2_max",
           "lean_tau_max_mm", "residual_limit"]

#: Datapath variants: the published one and the lean (15 DSP48E1 per lane) one.
GAP_VARIANTS = ("published", "lean")
#: Width of e_k in the lean variant: the DSP48E1's 18-bit signed B port.
LEAN_E_BITS = 18
#: Fraction bits of e_k at most (:data:`.golden.E_FRAC_MAX`, repeated to avoid a cycle).
_E_FRAC_MAX = 16


def check_variant(variant) -> str:
    """``variant`` if it is one of :data:`GAP_VARIANTS`, else :class:`InputRangeError`."""
    if variant not in GAP_VARIANTS:
        raise InputRangeError("variant", variant, f"one of {list(GAP_VARIANTS)}")
    return variant


def residual_limit(variant: str = "published") -> int:
    """Bound ``E`` on the squared residual components (0: none).

    ``"lean"``: every e_k must lie in ``[-E, E - 1]``, ``E = 2^17`` codes
    (:data:`LEAN_E_BITS` signed bits), or the sample's rho saturates.
    """
    return 1 << (LEAN_E_BITS - 1) if check_variant(variant) == "lean" else 0


def lean_tau2_max() -> int:
    """Largest gate code (UQ(64, rho_frac), mm^2) with lean == published: ``2^34``."""
    return residual_limit("lean") ** 2


def lean_tau_max_mm(coord_frac: int = 16) -> float:
    """:func:`lean_tau2_max` as a gate radius, mm: ``2^17 2^-min(cf, 16)`` (2 mm)."""
    return residual_limit("lean") * 2.0 ** -min(int(coord_frac), _E_FRAC_MAX)
