"""Stage A/B gap kernel, bit-exact fixed-point golden model and timing model.

This module *is* the datapath specification of the gap core: every integer below is a
register or wire of :mod:`.rtl`, which reproduces these numbers bit for bit and
:func:`gap_latency` cycle for cycle. It follows Algorithm 1 of docs/spec.md sec. 6; the
geometry and the selection rule are those of :mod:`.reference` (``lanes=L``).

Formats (defaults ``cf = 16`` coordinate and ``rf = 19`` normal fraction bits; ``cw``
is the coordinate word width, ``cw = 8 + cf``; all words two's complement)

==============  =============  ======================================================
signal          format         definition / bound
==============  =============  ======================================================
t, p, g, p'     Q(24,16)       coordinates, mm (``Q(cw, cf)``)
R, n            Q(21,19) [*]   rotation / unit-normal components, ``|code| <= 2^19``
R p product     44 b           ``|R_ij p_j| <= 2^19 2^23 = 2^42`` (Q(44,35))
pose acc        48 b           ``sum_j R_ij p_j + (t_i << 19)``, ``|acc| <= 2^44``
p'              Q(24,16)       ``round_shift(acc, 19)``; outside Q(24,16) -> overflow
d               Q(25,16)       ``p' - g``, ``|d| <= 2^24 - 1``
n.d             46 b           Q(46,35), ``|n.d| <= 3 (2^24 - 1) 2^19``
gamma           Q(32,16)       ``round_shift(-(n.d), 19)``, ``|gamma| <= 3 (2^24-1)``
gamma n_k       46 b           Q(46,35)
e_k             Q(27,16)       ``d_k + round_shift(gamma n_k, 19)``, ``|e_k| < 2^26``
rho             UQ(64,32)      ``e_0^2 + e_1^2 + e_2^2 < 3 2^52`` (54 significant bits)
tau^2           UQ(64,32)      ``ceil(tau^2 2^32)`` (so ``rho < tau2`` is exact)
key             UQ(32,16)      ``|gamma|`` if ``rho < tau2`` else ``KEY_INF = 2^32-1``
min_idx         16 b unsigned  winning sample index; sentinel ``0xFFFF``
min_gap         Q(32,16)       winning gamma; sentinel ``0x7FFFFFFF`` (+32768 mm)
==============  =============  ======================================================

[*] The contract format NORMAL is Q1.19 (Q(20,19)), whose range [-1, 1) misses
+1.0 -- yet unit normals such as (0, 0, 1) and the identity rotation need it. Instead
of clipping, the word is widened by one integer bit to Q(21,19) and restricted to the
closed unit interval, codes in [-2^19, +2^19]; the product magnitude stays
<= 2^42, so the 44-bit products and 48-bit accumulator of docs/spec.md sec. 6 are
unchanged. A component whose rounded code leaves [-2^19, 2^19] raises
:class:`~gearcontact.contract.qformat.FixedPointOverflow`.

For ``cf > 16`` (precision sweep, docs/spec.md sec. 8) ``e_k`` is round-shifted back to
16 fraction bits before squaring (``e_shift = cf - 16``) so that rho keeps the
UQ(64,32) format and the 64-bit budget; for ``cf <= 16`` rho is UQ(64, 2 cf). Every
bound above is structural (it holds for all in-range codes) and is re-checked on every
intermediate of :func:`gap_golden_codes`; nothing can wrap except p', whose overflow
is reported (``overflow = True`` forces ``valid = False`` and the sentinels).

Rounding is round-half-up by shift everywhere (``(x + 2^(n-1)) >> n``).

Variants (``variant=`` of the model functions and of ``GapCore``; :mod:`.variants`)
    ``"published"`` is the datapath above; ``"lean"`` saturates rho to 2^64 - 1 when a
    residual component leaves 18 bits (15 DSP48E1 per lane; equal outputs for
    ``tau2 <= 2^34``).

Selection and tie-breaking (exact)
    Lane ``l`` receives samples ``i = l + k L`` in increasing ``k`` and replaces its
    held sample only if ``rho_i < rho_held`` (strict), so among equal rho the
    earliest (lowest-index) sample of the lane is kept; lanes start at
    ``rho_held = 2^64 - 1`` and lanes without samples keep it (gate fails). At
    finalize, key = ``|gamma|`` if ``rho < tau2`` else ``KEY_INF``. Each comparator
    node of the log2(L)-level tree passes its right input only if its key is strictly
    smaller, so the winner is the *lowest-numbered lane* among those holding the
    minimal key. ``valid = (winning key != KEY_INF) and not overflow``.

Timing (cycles from the clock edge that accepts ``start`` to the edge that raises
``done``; see :func:`gap_latency`)::

    latency(N, L) = 1 capture + 2 transform + (L - 1) skew + K beats + 1 drain
                    + 1 finalize + log2(L) tree + 1 out
                  = L + K + log2(L) + 5,        K = ceil(N / L)

    N = 16, L = 16:  1 + 2 + 15 + 1 + 1 + 1 + 4 + 1 = 26

Capture registers the operands; transform is one stage of 9 products and one of
accumulate + round; p' then travels along the lanes in a register chain (one stage
per lane, bounding the fan-out of the 72-bit p' bus at L <= 64) so lane l starts
l cycles after lane 0 and streams its K samples at II = 1 from its own sample bank;
each lane has two stages (A: d and gamma; B: e, rho and the running-minimum update,
whose last update is the drain cycle); finalize registers the keys; the tree has one
registered level per comparator stage; out registers the re-selected gap.
The count is data-independent: a pass always takes latency(N, L) cycles.

References
----------
docs/spec.md sec. 6 (Algorithm 1, fixed-point contract); F. L. Litvin, A. Fuentes, *Gear
Geometry and Applied Theory*, 2nd ed., Cambridge Univ. Press, 2004 (normal-gap
definition); R. Yates, "Fixed-Point Arithmetic: An Introduction", Digital Signal Labs,
2013 (Q notation, rounding by shift).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np

from ...validation import InputRangeError, check_positive, check_range
from ...contract.qformat import FixedPointOverflow, QFormat, round_shift, sq, uq
from .reference import MAX_SAMPLES, check_lanes, validate_gap_inputs
from .variants import residual_limit

__all__ = ["GapFormat", "DEFAULT_FORMAT", "GapVector", "GapCodes", "GoldenGapResult",
           "GapTiming", "quantize_pass", "gap_golden_codes", "gap_golden_terms",
           "gap_golden", "gap_latency", "gap_timing", "gap_error_bound_mm",
           "quantize_tau2", "check_vector", "check_codes",
           "IDX_BITS", "IDX_SENTINEL"]

IDX_BITS = 16
IDX_SENTINEL = (1 << IDX_BITS) - 1
RHO_BITS = 64
#: fraction bits kept in the residual e_k (and hence rho = Q(64, 2 * this)).
E_FRAC_MAX = 16


@dataclass(frozen=True)
class GapFormat:
    """Word formats of the gap datapath (see the module table).

    Parameters
    ----------
    coord_frac : int
        Coordinate fraction bits cf in [0, 24] (one LSB = 2^-cf mm); default 16. Every
        bound of the module table is structural in ``cw = coord_int + cf`` (the widths
        of d, gamma, e_k and rho grow with cw and nothing else), so the arithmetic is
        exact-by-construction down to cf = 0 (integer millimetres); the upper end is
        the 64-bit rho budget (``e_shift``). Only the default format is built in RTL.
    normal_frac : int
        Normal / rotation fraction bits rf in [8, 24]; default 19.
    coord_int : int
        Coordinate integer bits incl. sign in [4, 8]; default 8 (range +-128 mm).
    """

    coord_frac: int = 16
    normal_frac: int = 19
    coord_int: int = 8

    def __post_init__(self):
        for name, lo, hi in (("coord_frac", 0, 24), ("normal_frac", 8, 24),
                             ("coord_int", 4, 8)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or not lo <= v <= hi:
                raise InputRangeError(name, v, f"an integer in [{lo}, {hi}]")

    @property
    def coord_bits(self) -> int:
        """Coordinate word width cw (24 by default)."""
        return self.coord_int + self.coord_frac

    @property
    def coord(self) -> QFormat:
        """Coordinate format Q(cw, cf), mm."""
        return sq(self.coord_bits, self.coord_frac)

    @property
    def normal(self) -> QFormat:
        """Normal/rotation word Q(rf + 2, rf); codes further limited to ``|c| <= 2^rf``."""
        return sq(self.normal_frac + 2, self.normal_frac)

    @property
    def normal_max_code(self) -> int:
        """Largest allowed normal code magnitude, ``2^rf`` (= 1.0)."""
        return 1 << self.normal_frac

    @property
    def product_bits(self) -> int:
        """Pose product width, ``cw + rf + 1`` (44)."""
        return self.coord_bits + self.normal_frac + 1

    @property
    def acc_bits(self) -> int:
        """Pose accumulator width, ``product_bits + 4`` (48)."""
        return self.product_bits + 4

    @property
    def diff_bits(self) -> int:
        """Width of d = p' - g, ``cw + 1`` (25)."""
        return self.coord_bits + 1

    @property
    def dot_bits(self) -> int:
        """Width of n.d and gamma n_k, ``cw + rf + 3`` (46)."""
        return self.coord_bits + self.normal_frac + 3

    @property
    def gap_bits(self) -> int:
        """Signed-gap word width, ``cw + 8`` (32)."""
        return self.coord_bits + 8

    @property
    def gap(self) -> QFormat:
        """Signed gap format Q(cw + 8, cf), mm (GAP = Q(32,16) by default)."""
        return sq(self.gap_bits, self.coord_frac)

    @property
    def e_shift(self) -> int:
        """Right shift applied to e_k before squaring, ``max(0, cf - 16)``."""
        return max(0, self.coord_frac - E_FRAC_MAX)

    @property
    def e_bits(self) -> int:
        """Width of the (shifted) residual components, ``cw + 3 - e_shift`` (27)."""
        return self.coord_bits + 3 - self.e_shift

    @property
    def rho_frac(self) -> int:
        """Fraction bits of rho and tau^2, ``2 min(cf, 16)`` (32)."""
        return 2 * min(self.coord_frac, E_FRAC_MAX)

    @property
    def rho(self) -> QFormat:
        """Perpendicular-residual format UQ(64, rho_frac), mm^2."""
        return uq(RHO_BITS, self.rho_frac)

    @property
    def key_inf(self) -> int:
        """Key of a gate-rejected lane, ``2^gap_bits - 1``."""
        return (1 << self.gap_bits) - 1

    @property
    def gap_sentinel(self) -> int:
        """min_gap code when not valid: the largest gap code."""
        return self.gap.max_code


DEFAULT_FORMAT = GapFormat()


@dataclass(frozen=True, eq=False)
class GapVector:
    """Integer operands of one pass (what the host writes into the core).

    Compared by identity (its fields are arrays).

    Attributes
    ----------
    r_code : numpy.ndarray
        Rotation, shape (3, 3), int64 codes of Q(rf+2, rf), ``|c| <= 2^rf``.
    t_code, p_code : numpy.ndarray
        Translation and body point, shape (3,), coordinate codes (mm).
    g_code : numpy.ndarray
        Gear sample positions, shape (N, 3), coordinate codes (mm).
    n_code : numpy.ndarray
        Gear unit normals, shape (N, 3), normal codes.
    tau2_code : int
        Gate ``tau^2`` as UQ(64, rho_frac) code (mm^2), in [1, 2^63 - 1].
    """

    r_code: np.ndarray
    t_code: np.ndarray
    p_code: np.ndarray
    g_code: np.ndarray
    n_code: np.ndarray
    tau2_code: int

    @property
    def n_samples(self) -> int:
        return int(self.g_code.shape[0])


@dataclass(frozen=True)
class GapCodes:
    """Fixed-point outputs of one pass (the core's output registers).

    Attributes
    ----------
    min_gap_code : int
        Winning signed gap, Q(gap_bits, cf) code (mm); ``gap_sentinel`` if not valid.
    min_idx : int
        Winning sample index; ``IDX_SENTINEL`` (0xFFFF) if not valid.
    valid : bool
        A lane passed the gate and p' did not overflow.
    overflow : bool
        p' = R p + t left the coordinate format.
    """

    min_gap_code: int
    min_idx: int
    valid: bool
    overflow: bool


@dataclass(frozen=True)
class GoldenGapResult:
    """Golden result of one pass in physical units (see :class:`GapCodes`).

    Attributes
    ----------
    min_gap_mm : float
        Winning signed gap, mm; ``nan`` if not valid.
    min_gap_code : int
        Its Q(gap_bits, cf) code.
    min_idx : int
        Winning sample index (``IDX_SENTINEL`` if not valid).
    valid : bool
    """

    min_gap_mm: float
    min_gap_code: int
    min_idx: int
    valid: bool


@dataclass(frozen=True)
class GapTiming:
    """Cycle schedule of one pass (module docstring); all fields in clock cycles.

    Attributes
    ----------
    capture : int
        Operand capture on the accepting edge (1).
    transform : int
        Pose transform: product stage + accumulate/round stage (2).
    skew : int
        Systolic p' distribution, lane L-1 starts L-1 cycles after lane 0.
    beats : int
        K = ceil(N / L) sample beats per lane at II = 1.
    drain : int
        Stage B (running-minimum update) of the last beat (1).
    finalize : int
        Gate -> key registers (1).
    tree : int
        log2(L) registered comparator levels.
    out : int
        Output registers and ``done`` (1).
    total : int
        Latency, the sum of the above.
    """

    capture: int
    transform: int
    skew: int
    beats: int
    drain: int
    finalize: int
    tree: int
    out: int
    total: int = field(init=False)

    def __post_init__(self):
        object.__setattr__(self, "total", self.capture + self.transform + self.skew
                           + self.beats + self.drain + self.finalize + self.tree + self.out)


def gap_timing(n_samples: int, lanes: int) -> GapTiming:
    """Cycle schedule of one pass over ``n_samples`` samples on ``lanes`` lanes."""
    lanes = check_lanes(lanes)
    if isinstance(n_samples, bool) or not isinstance(n_samples, (int, np.integer)) \
            or not 1 <= n_samples <= MAX_SAMPLES:
        raise InputRangeError("n_samples", n_samples, f"an integer in [1, {MAX_SAMPLES}]")
    return GapTiming(capture=1, transform=2, skew=lanes - 1,
                     beats=-(-int(n_samples) // lanes), drain=1, finalize=1,
                     tree=lanes.bit_length() - 1, out=1)


def gap_latency(n_samples: int, lanes: int) -> int:
    """Latency of one pass in clock cycles, ``L + ceil(N/L) + log2(L) + 5`` (26 at 16/16)."""
    return gap_timing(n_samples, lanes).total


def gap_error_bound_mm(*, coord_frac: int, normal_frac: int, d_inf_mm: float) -> float:
    """First-order bound on the fixed-point signed-gap error (docs/spec.md sec. 8), mm.

    ``|e_g| <= sqrt(3) 2^-cf + 3 ||d||_inf 2^-(rf+1) + 2^-(cf+1)``: coordinate
    quantization of p' and g (each component of d off by <= 2^-cf, projected on a unit
    normal), normal quantization (each component off by <= 2^-(rf+1)) and the final
    round-shift of gamma. The posed point is assumed to be quantized once (an exactly
    representable pose); quantizing R adds ``3 ||p||_inf 2^-(rf+1)`` per component of p'.

    Parameters
    ----------
    coord_frac, normal_frac : int
        Fraction bits cf and rf.
    d_inf_mm : float
        Largest ``|p' - g|`` component over the samples considered, mm (>= 0).
    """
    d_inf = check_range("d_inf_mm", d_inf_mm, 0.0, math.inf)
    cf, rf = int(coord_frac), int(normal_frac)
    return (math.sqrt(3.0) * 2.0 ** -cf + 3.0 * d_inf * 2.0 ** -(rf + 1)
            + 2.0 ** -(cf + 1))


def _quantize_normal_array(x, fmt: GapFormat, field: str) -> np.ndarray:
    code = fmt.normal.quantize_array(x, field=field)
    bad = np.abs(code) > fmt.normal_max_code
    if bad.any():
        i = tuple(int(j) for j in np.argwhere(bad)[0])
        raise FixedPointOverflow(f"{field}[{', '.join(map(str, i))}]",
                                 float(np.asarray(x)[i]),
                                 QFormat(fmt.normal.bits, fmt.normal_frac))
    return code


def quantize_tau2(tau_mm: float, *, fmt: GapFormat = DEFAULT_FORMAT) -> int:
    """Gate code ``ceil(tau^2 2^rho_frac)`` (exact rational arithmetic).

    For an integer residual code r, ``r < ceil(x)`` iff ``r < x``: the integer gate
    equals the exact real gate ``rho < tau^2`` applied to the quantized residual.
    """
    tau = check_positive("tau_mm", tau_mm)
    code = math.ceil(Fraction(tau) ** 2 * (1 << fmt.rho_frac))
    if code > (1 << 63) - 1:
        hi = math.sqrt(((1 << 63) - 1) / (1 << fmt.rho_frac))
        raise InputRangeError("tau_mm", tau_mm, f"(0, {hi:.6g}] mm")
    return int(code)


def quantize_pass(R, t, p, samples_xyz, normals, *, tau_mm: float,
                  fmt: GapFormat = DEFAULT_FORMAT) -> GapVector:
    """Validate real inputs (see :func:`.reference.validate_gap_inputs`) and quantize.

    Coordinates (mm) round half up to ``fmt.coord``; R and n to ``fmt.normal`` with
    ``|code| <= 2^rf``; ``tau_mm`` via :func:`quantize_tau2`. Out-of-range values
    raise :class:`FixedPointOverflow` naming the field -- nothing is clipped.
    """
    R, t, p, g, n = validate_gap_inputs(R, t, p, samples_xyz, normals)
    return GapVector(r_code=_quantize_normal_array(R, fmt, "R"),
                     t_code=fmt.coord.quantize_array(t, field="t_mm"),
                     p_code=fmt.coord.quantize_array(p, field="p_mm"),
                     g_code=fmt.coord.quantize_array(g, field="samples_xyz_mm"),
                     n_code=_quantize_normal_array(n, fmt, "normals"),
                     tau2_code=quantize_tau2(tau_mm, fmt=fmt))


def check_codes(*, fmt: GapFormat = DEFAULT_FORMAT, r=None, t=None, p=None, g=None,
                n=None, tau2=None) -> None:
    """Raise :class:`InputRangeError` unless the given code arrays are in contract.

    ``r``/``n``: integer codes with ``|c| <= 2^rf``; ``t``/``p``/``g``: integer codes
    of ``fmt.coord``; ``tau2``: an integer in [1, 2^63 - 1]. Arrays may have any
    leading shape; the last axis must be 3 (``r``: last two axes 3 x 3).
    """
    c, m = fmt.coord, fmt.normal_max_code
    for name, a in (("t_code", t), ("p_code", p), ("g_code", g)):
        if a is None:
            continue
        a = np.asarray(a)
        if not np.issubdtype(a.dtype, np.integer) or a.shape[-1:] != (3,) \
                or not c.fits(a).all():
            raise InputRangeError(name, a.tolist() if a.size < 10 else f"array {a.shape}",
                                  f"integer codes (..., 3) of {c} in [{c.min_code}, {c.max_code}]")
    for name, a, tail in (("r_code", r, (3, 3)), ("n_code", n, (3,))):
        if a is None:
            continue
        a = np.asarray(a)
        if not np.issubdtype(a.dtype, np.integer) or a.shape[-len(tail):] != tail \
                or (np.abs(a) > m).any():
            raise InputRangeError(name, a.tolist() if a.size < 10 else f"array {a.shape}",
                                  f"integer codes (..., {', '.join(map(str, tail))}) in "
                                  f"[{-m}, {m}] (Q{fmt.normal.bits - fmt.normal_frac}."
                                  f"{fmt.normal_frac}, |value| <= 1)")
    if tau2 is not None and (isinstance(tau2, bool) or not isinstance(tau2, (int, np.integer))
                             or not 1 <= int(tau2) <= (1 << 63) - 1):
        raise InputRangeError("tau2_code", tau2, "an integer in [1, 2^63 - 1]")


def check_vector(vec: GapVector, *, fmt: GapFormat = DEFAULT_FORMAT) -> None:
    """Raise :class:`InputRangeError` unless every code of ``vec`` is in contract."""
    for name, shape in (("r_code", (3, 3)), ("t_code", (3,)), ("p_code", (3,))):
        if np.shape(getattr(vec, name)) != shape:
            raise InputRangeError(f"{name}.shape", np.shape(getattr(vec, name)), str(shape))
    n = np.shape(vec.g_code)
    if len(n) != 2 or n[1] != 3 or not 1 <= n[0] <= MAX_SAMPLES \
            or np.shape(vec.n_code) != n:
        raise InputRangeError("g_code/n_code shape", (n, np.shape(vec.n_code)),
                              f"equal shapes (N, 3), 1 <= N <= {MAX_SAMPLES}")
    check_codes(fmt=fmt, r=vec.r_code, t=vec.t_code, p=vec.p_code, g=vec.g_code,
                n=vec.n_code, tau2=vec.tau2_code)


def _w(x: int, bits: int, name: str, *, signed: bool = True) -> int:
    """Structural width check of an intermediate (a failure is a design bug)."""
    lo, hi = (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if signed else (0, (1 << bits) - 1)
    if not lo <= x <= hi or bits > 64:
        raise AssertionError(f"gap datapath: {name} = {x} exceeds its {bits}-bit word")
    return x


def _posed_point(vec: GapVector, fmt: GapFormat) -> tuple[list[int], bool]:
    rf = fmt.normal_frac
    pp, ovf = [], False
    for i in range(3):
        acc = _w(int(vec.t_code[i]) << rf, fmt.acc_bits, "t << rf")
        for j in range(3):
            acc += _w(int(vec.r_code[i, j]) * int(vec.p_code[j]), fmt.product_bits, "R p")
        x = round_shift(_w(acc, fmt.acc_bits, "pose acc"), rf)
        ovf |= not fmt.coord.fits(x)
        pp.append(x)
    return pp, ovf


def _sample(pp: list[int], g, n, fmt: GapFormat, e_limit: int = 0) -> tuple[int, int]:
    """(gamma, rho) codes of one sample, every intermediate width-checked.

    ``e_limit > 0`` (lean variant): rho = 2^64 - 1 when an e_k leaves
    ``[-e_limit, e_limit - 1]``.
    """
    rf = fmt.normal_frac
    d = [_w(pp[k] - int(g[k]), fmt.diff_bits, "d") for k in range(3)]
    dot = _w(sum(int(n[k]) * d[k] for k in range(3)), fmt.dot_bits, "n.d")
    gamma = _w(round_shift(-dot, rf), fmt.gap_bits, "gamma")
    rho, saturated = 0, False
    for k in range(3):
        gn = _w(gamma * int(n[k]), fmt.dot_bits, "gamma n")
        e = _w(round_shift(d[k] + round_shift(gn, rf), fmt.e_shift), fmt.e_bits, "e")
        saturated |= e_limit > 0 and not -e_limit <= e < e_limit
        rho += e * e
    return gamma, (1 << RHO_BITS) - 1 if saturated else _w(rho, RHO_BITS, "rho", signed=False)


def gap_golden_terms(vec: GapVector, *, fmt: GapFormat = DEFAULT_FORMAT,
                     variant: str = "published"):
    """Per-sample integer terms: ``(pp_code (3,), gamma_code (N,), rho_code (N,))``.

    gamma in Q(gap_bits, cf), rho in UQ(64, rho_frac) (``variant="lean"``: 2^64 - 1
    where saturated).

    Raises
    ------
    FixedPointOverflow
        If p' leaves the coordinate format (the core would flag ``overflow``).
    """
    check_vector(vec, fmt=fmt)
    pp, ovf = _posed_point(vec, fmt)
    if ovf:
        raise FixedPointOverflow("posed_point_code", pp, fmt.coord)
    lim = residual_limit(variant)
    terms = [_sample(pp, vec.g_code[i], vec.n_code[i], fmt, lim)
             for i in range(vec.n_samples)]
    gam = np.array([g for g, _ in terms], dtype=np.int64)
    rho = np.array([r for _, r in terms], dtype=np.uint64)
    return np.array(pp, dtype=np.int64), gam, rho


def gap_golden_codes(vec: GapVector, *, lanes: int = 16, fmt: GapFormat = DEFAULT_FORMAT,
                     variant: str = "published") -> GapCodes:
    """Scalar bit-exact model of one pass of the gap core.

    Parameters
    ----------
    vec : GapVector
        Integer operands (checked against the contract; see :func:`check_vector`).
    lanes : int, keyword-only
        Lane count L, power of two in [8, 64].
    fmt : GapFormat, keyword-only
        Word formats (default: the contract of docs/spec.md sec. 6).
    variant : {"published", "lean"}, keyword-only
        Datapath variant (module docstring; ``"lean"`` equals ``"published"`` for
        ``tau2 <= lean_tau2_max()``).

    Returns
    -------
    GapCodes
        Exactly the core's output registers (tie rules in the module docstring).
    """
    lanes = check_lanes(lanes)
    lim = residual_limit(variant)
    check_vector(vec, fmt=fmt)
    pp, ovf = _posed_point(vec, fmt)
    if ovf:
        return GapCodes(fmt.gap_sentinel, IDX_SENTINEL, False, True)
    rho_inf = (1 << RHO_BITS) - 1
    held = [(rho_inf, 0, 0)] * lanes                       # (rho, gamma, idx) per lane
    for i in range(vec.n_samples):
        gamma, rho = _sample(pp, vec.g_code[i], vec.n_code[i], fmt, lim)
        lane = i % lanes
        if rho < held[lane][0]:                            # strict: earliest tie stays
            held[lane] = (rho, gamma, i)
    tau2 = int(vec.tau2_code)
    nodes = [(abs(gm) if rho < tau2 else fmt.key_inf, lane)
             for lane, (rho, gm, _) in enumerate(held)]
    while len(nodes) > 1:                                  # registered tree levels
        nodes = [b if b[0] < a[0] else a for a, b in zip(nodes[0::2], nodes[1::2])]
    key, win = nodes[0]
    if key == fmt.key_inf:
        return GapCodes(fmt.gap_sentinel, IDX_SENTINEL, False, False)
    return GapCodes(held[win][1], held[win][2], True, False)


def gap_golden(R, t, p, samples_xyz, normals, *, tau_mm: float, lanes: int = 16,
               fmt: GapFormat = DEFAULT_FORMAT, variant: str = "published") -> GoldenGapResult:
    """Quantize real inputs and run :func:`gap_golden_codes`.

    Parameters are those of :func:`.reference.gap_reference` (mm, dimensionless R
    and n); ``lanes``, ``fmt`` and ``variant`` as in :func:`gap_golden_codes`.

    Raises
    ------
    FixedPointOverflow
        If an input does not fit its format or p' = R p + t leaves the coordinate
        range (the core's ``overflow`` flag).
    """
    vec = quantize_pass(R, t, p, samples_xyz, normals, tau_mm=tau_mm, fmt=fmt)
    out = gap_golden_codes(vec, lanes=lanes, fmt=fmt, variant=variant)
    if out.overflow:
        pp = np.asarray(R, float) @ np.asarray(p, float) + np.asarray(t, float)
        raise FixedPointOverflow("posed_point_mm", pp.tolist(), fmt.coord)
    gap_mm = fmt.gap.to_float(out.min_gap_code) if out.valid else float("nan")
    return GoldenGapResult(min_gap_mm=gap_mm, min_gap_code=out.min_gap_code,
                           min_idx=out.min_idx, valid=out.valid)
