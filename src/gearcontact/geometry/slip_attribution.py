"""Which single typed key explains a flank that disagrees with its blank when no known
slip does: for each key of the flank's ``[machine.*]`` / ``[blade.*]`` table, the values
at which the flank agrees with the blank, every compared quantity within its tolerance
(:mod:`.blank_check`; docs/machine_settings.md sec. 2, "The check when a pair is
loaded").

One key ``k`` typed ``x0`` is moved alone; the flank's compared quantities ``m_q(v)``
against the blank's ``s_q`` give the excess

    phi(v) = max_q |m_q(v) - s_q| / tol_q - 1        (<= 0: the flank agrees)

with the tolerances ``tol_q`` of the typed flank (its rounding propagated: what the check
compared), and ``phi`` a large number (``_OUT``) where the flank does not reach its mean
point, its hand is not the blank's or the value is outside the key's range.
``phi(x0) > 0``. Per key:

1. the derivatives ``dm_q/dv`` by one forward difference (step :data:`STEP_FRACTION` of
   the key's scale, :func:`key_scale`);
2. each quantity's linearized band (``|h_q + J_q d| <= tol_q``), widened by
   :data:`NONLINEAR` of its distance from the typed value and intersected; empty (or a
   quantity the key does not move outside): the key cannot explain the flank, no more
   solves;
3. the centre of the unwidened intersection measured; where it is empty or outside,
   the minimum of ``phi`` on the widened one (scipy's bounded Brent,
   :func:`scipy.optimize.minimize_scalar`, to a quarter of the narrowest band); no
   agreeing value: not explained;
4. the agreeing interval's ends, roots of ``phi`` (:func:`scipy.optimize.brentq`, to
   1e-3 of the narrowest band) between the typed value and the agreeing one, and
   beyond it (the bracket doubled at most ``_EXPANSIONS`` times; an end not bracketed
   is reported open). Where ``phi`` has more than one agreeing interval (a root depth
   with a maximum near the typed point radius) the one found is reported.

A value is **near** the typed one when ``|v - x0| <= NEAR_FACTOR |x0| + key_scale(k)``
(:data:`NEAR_FACTOR`: a sign flipped, a leading digit or the decimal point one place
wrong, or a zero typed for a value of the key's scale); farther values are not searched
(a key whose derivative is small can reach agreement only far away, which says nothing
about a slip). Several keys can each explain one flank (the root depth moves with the
sliding base, the MCTB, the machine root and the tilt alike): all are reported,
ranked by the change in units of the key's typed rounding (half a unit of its last
typed decimal, :func:`.typed_settings.typed_resolution`), keys typed 0 (a set-up choice,
exact) after the others by the change relative to their agreeing half-width. The rank
is no probability: the words say "any one of ... alone makes it agree", not which key
slipped; and none where no single key does (two or more keys may be wrong).

References
----------
R. P. Brent, *Algorithms for Minimization without Derivatives*, Prentice-Hall, 1973
(the root finder and the bounded minimizer, as scipy implements them).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from scipy.optimize import brentq, minimize_scalar

__all__ = ["NEAR_FACTOR", "NONLINEAR", "STEP_FRACTION", "KeyValue", "describe",
           "explaining_values", "interval", "key_scale"]

#: The forward-difference step of the linearization, a fraction of the key's scale
#: (:func:`key_scale`): 1e-3 mm / deg, 1e-4 of a ratio of roll or a series term.
STEP_FRACTION = 1e-3
#: How far from the typed value ``x0`` a key's agreeing value is searched: ``|v - x0| <=
#: NEAR_FACTOR |x0| + key_scale`` (module docstring).
NEAR_FACTOR = 10.0
#: The linearized bands are widened by this fraction of each one's distance from the
#: typed value before they are intersected (step 2): a second-order allowance, so that a
#: key that must move far (a digit slip, 4 mm of radial distance) is not rejected by
#: the linearization's own error; the measured excess decides (step 3).
NONLINEAR = 0.25
_EXPANSIONS = 4                 # doublings of the bracket of an interval's far end
_OUT = 1e9       # phi where the flank is not measured or its hand differs (finite: for
                 # the interpolation of scipy's Brent methods)


def key_scale(key: str) -> float:
    """The scale of a setting: 1 mm (``*_mm``), 1 deg (``*_deg``), 0.1 for the ratio
    of roll and the printed series (modified roll, helical motion)."""
    if key.endswith("_mm") or key.endswith("_deg"):
        return 1.0
    return 0.1


@dataclass(frozen=True)
class KeyValue:
    """One key that alone explains a flank: ``key`` (the full name,
    ``machine.<member>.<flank>.<key>``), its ``typed`` value and ``half_unit`` (its
    typed rounding, 0 for a value typed 0), and the ends of the interval of values at
    which the flank agrees, ``low`` / ``high`` (None: open within the search)."""

    key: str
    typed: float
    half_unit: float
    low: float | None
    high: float | None

    @property
    def needed(self) -> float:
        """The interval's centre (its closed end when one end is open)."""
        ends = [x for x in (self.low, self.high) if x is not None]
        return sum(ends) / len(ends)

    @property
    def half_width(self) -> float | None:
        """Half the interval's width (None when an end is open)."""
        if self.low is None or self.high is None:
            return None
        return 0.5 * (self.high - self.low)

    @property
    def rank(self) -> tuple:
        """The sort key: keys typed 0 last; then the change in units of the typed
        rounding (module docstring)."""
        change = abs(self.needed - self.typed)
        if self.half_unit > 0.0:
            return (0, change / self.half_unit)
        return (1, change / (self.half_width or math.inf))


def _excess(rows) -> float:
    """``phi`` of one evaluation's comparisons (None: the flank was not measured)."""
    if rows is None:
        return _OUT
    worst = -math.inf
    for c in rows:
        if c.tolerance is None:
            if c.measured != c.stated:
                return _OUT
            continue
        worst = max(worst, abs(c.measured - c.stated) / c.tolerance)
    return worst - 1.0


def _linear_bands(rows0, rows1, step: float) -> list | None:
    """Per compared quantity, the changes ``(low, high, centre)`` (from the typed value)
    at which its linearization is within its tolerance; None when a quantity the key
    does not move is outside."""
    bands = []
    for c0, c1 in zip(rows0, rows1):
        if c0.tolerance is None:
            continue
        h = c0.measured - c0.stated
        slope = (c1.measured - c0.measured) / step
        if slope == 0.0:
            if abs(h) > c0.tolerance:
                return None
            continue
        low, high = sorted(((-c0.tolerance - h) / slope, (c0.tolerance - h) / slope))
        bands.append((low, high, -h / slope))
    return bands


def _intersection(bands, widen: float = 0.0) -> tuple[float, float] | None:
    """The intersection of ``bands``, each widened by ``widen`` times its centre's
    distance from the typed value; None when empty."""
    lo = max(b[0] - widen * abs(b[2]) for b in bands)
    hi = min(b[1] + widen * abs(b[2]) for b in bands)
    return (lo, hi) if lo <= hi else None


def _one_key(key: str, typed: float, half_unit: float, rows0,
             compare: Callable[[float], Sequence | None]) -> KeyValue | None:
    """:class:`KeyValue` of ``key`` or None (module docstring, steps 1-4)."""
    scale = key_scale(key)
    near = NEAR_FACTOR * abs(typed) + scale
    step = STEP_FRACTION * scale
    rows1 = compare(typed + step)
    if rows1 is None:
        rows1 = compare(typed - step)
        step = -step
    if rows1 is None:
        return None
    bands = _linear_bands(rows0, rows1, step)
    wide = _intersection(bands, NONLINEAR) if bands else None
    if wide is None or wide[1] < -near or wide[0] > near:
        return None
    memo = {typed: _excess(rows0), typed + step: _excess(rows1)}

    def phi(v: float) -> float:
        if v not in memo:
            memo[v] = _excess(compare(v))
        return memo[v]

    width = min(b[1] - b[0] for b in bands)         # the narrowest band
    tight = _intersection(bands)
    at = None if tight is None else typed + 0.5 * (tight[0] + tight[1])
    if at is None or phi(at) > 0.0:
        got = minimize_scalar(phi, bounds=(typed + max(wide[0], -near),
                                           typed + min(wide[1], near)),
                              method="bounded", options={"xatol": 0.25 * width})
        if not got.fun <= 0.0:
            return None
        at = float(got.x)
    if abs(at - typed) > near:
        return None
    xtol = max(1e-3 * width, 1e-12)
    # the end towards the typed value: bracketed by it (phi(typed) > 0)
    inner = brentq(phi, typed, at, xtol=xtol)
    # the far end: bracketed by doubling the distance beyond the agreeing value
    outer, reach = None, max(abs(at - inner), width)
    sign = math.copysign(1.0, at - typed)
    for _ in range(_EXPANSIONS):
        far = at + sign * reach
        if phi(far) > 0.0:
            outer = brentq(phi, at, far, xtol=xtol)
            break
        reach *= 2.0
    low, high = sorted((inner, outer if outer is not None else math.inf * sign))
    return KeyValue(key, typed, half_unit, low if math.isfinite(low) else None,
                    high if math.isfinite(high) else None)


def explaining_values(candidates: Sequence[tuple[str, float, float]], rows0,
                      compare: Callable[[str, float], Sequence | None]) -> tuple[KeyValue, ...]:
    """The keys of ``candidates`` that alone explain a disagreeing flank, best ranked
    first (module docstring).

    Parameters
    ----------
    candidates : sequence of (key, typed value, half unit)
        The flank's typed keys: the full name, the value as typed and its typed
        rounding.
    rows0 : sequence of Comparison
        The flank's comparisons as typed (:class:`.blank_verdict.Comparison`: ``measured``,
        ``stated``, ``tolerance``); at least one outside its tolerance.
    compare : callable
        ``compare(key, value)``: the flank's comparisons with ``key`` set to ``value``
        and the same tolerances, or None where the flank does not reach its mean point
        or the value is outside the key's range.

    Returns
    -------
    tuple of KeyValue
        Sorted by :attr:`KeyValue.rank`; empty when no single key explains the flank.
    """
    found = [got for key, typed, half_unit in candidates
             if (got := _one_key(key, typed, half_unit, rows0,
                                 lambda v, key=key: compare(key, v))) is not None]
    return tuple(sorted(found, key=lambda k: k.rank))


def _decimals(k: KeyValue) -> int:
    """Decimals that resolve the agreeing half-width to 2 digits (4 when open)."""
    w = k.half_width
    if not w:
        return 4
    return max(0, 1 - math.floor(math.log10(w)))


def _needs(k: KeyValue) -> str:
    """``"... typed -0.24; the blank needs 0.0000 +- 0.0011"`` (or ``>= x`` / ``<= x``
    for an interval open at one end within the search)."""
    d = _decimals(k)
    name = f"{k.key} typed {k.typed:g}; the blank needs "
    if k.half_width is None:
        end = "<=" if k.low is None else ">="
        return name + f"{end} {k.needed:.{d}f}"
    return name + f"{k.needed:.{d}f} +- {k.half_width:.2g}"


def interval(k: KeyValue) -> str:
    """The values of ``k``'s key at which the flank agrees: ``"[low, high]"`` (or ``">=
    low"`` / ``"<= high"`` for an interval open at one end within the search), in the
    digits :func:`describe` prints."""
    d = _decimals(k)
    if k.low is None or k.high is None:
        return f"<= {k.high:.{d}f}" if k.low is None else f">= {k.low:.{d}f}"
    return f"[{k.low:.{d}f}, {k.high:.{d}f}]"


def describe(found: Sequence[KeyValue]) -> str:
    """The words for the keys that alone make a flank agree: one key, any one of several
    ranked, or none (module docstring)."""
    if not found:
        return ("no single typed key alone makes it agree (two or more may be wrong, "
                "or a key not typed)")
    if len(found) == 1:
        return f"of its typed keys one alone makes it agree: {_needs(found[0])}"
    return (f"any one of {len(found)} of its typed keys alone makes it agree (which one "
            "slipped is not known; ranked by the change in units of its typed last "
            "digit): " + "; ".join(_needs(k) for k in found))
