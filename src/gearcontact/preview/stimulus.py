"""Seeded random and corner-case input codes for every preview core.

One generator per core returns the integer input codes the RTL and the golden model
consume (formats of docs/spec.md sec. 6), corner cases first, then ``n`` seeded random
vectors. The same function feeds the Verilator equivalence tests, the
``gearcontact rtl sim`` command and the golden-vector export, so "vector k of seed s"
means the same operands everywhere.

==========  ==========================================================================
core        fields of :attr:`Stimulus.fields` (``int64``, first axis = vector)
==========  ==========================================================================
gap         ``r`` (n, 3, 3) Q(21,19) with ``|c| <= 2^19``; ``t``, ``p`` (n, 3) and ``g``
            (n, N, 3) Q(24,16) mm; ``nrm`` (n, N, 3) normals like ``r``; ``tau2`` (n,)
            UQ(64,32) mm^2 in [1, 2^63 - 1]
fit         ``gaps`` (n, 49) STENCIL_GAP Q(32,21) mm, in the stencil order of
            :mod:`gearcontact.contract.stencil`
hertz       ``A``, ``B`` (n,) CURVATURE Q(32,20) 1/mm; ``W`` (n,) LOAD Q(32,8) N;
            ``e_prime`` (n,) Q(32,0) MPa
line        as hertz plus ``L`` (n,) LINE_LENGTH Q(32,20) mm (the line core,
            :mod:`.hertz.line`)
chain       ``gaps`` (n, 49) as for fit; ``W``, ``e_prime`` as for hertz (the C -> D
            chain and the combinational C + D core take the same inputs)
chain_line  as chain plus ``L`` as for line (the C -> line-core chain,
            :mod:`.chain_line_rtl`)
==========  ==========================================================================

Random vectors mix physically plausible operands (posed points near a sampled flank,
quadratic gap surfaces with curvatures in the envelope, log-uniform loads) with raw codes
drawn over each word's whole range, which exercise the overflow and envelope flags.
Corner cases (named in :attr:`Stimulus.labels`) cover what the RTL issue lists: gate
rejects every lane, ties, negative gaps, p' overflow, extreme curvature ratios, minimum
and maximum loads and curvatures (and one code beyond), saddle/flat/concave stencils,
all-zero operands (a go without data) and the extreme codes of every word.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..contract import envelope as ENV
from ..contract.qformat import CURVATURE, LOAD, STENCIL_GAP
from ..contract.stencil import STENCIL_SIZE, stencil_coordinates
from ..validation import InputRangeError

__all__ = ["Stimulus", "gap_stimulus", "fit_stimulus", "hertz_stimulus", "chain_stimulus",
           "line_stimulus", "chain_line_stimulus",
           "stimulus", "STIMULUS_CORES", "STEEL_E_PRIME_CODE"]

#: E' of steel/steel (2E*, 209 GPa, nu 0.3), integer MPa: the default constant register.
STEEL_E_PRIME_CODE = 229_670
_RF = 19
_ONE = 1 << _RF                     # normal / rotation code of 1.0
_CMAX, _CMIN = (1 << 23) - 1, -(1 << 23)   # Q(24,16) coordinate codes
_TAU2_MAX = (1 << 63) - 1


@dataclass(frozen=True)
class Stimulus:
    """Input codes of a batch of vectors for one core.

    Attributes
    ----------
    core : str
        ``gap``, ``fit``, ``hertz`` or ``chain``.
    fields : dict
        Field name -> ``int64`` array whose first axis is the vector (module table).
    labels : tuple of str
        Name of each vector: the corner case, or ``random`` / ``raw`` (whole-range codes).
    seed : int
        Seed of the random part.
    """

    core: str
    fields: dict
    labels: tuple
    seed: int

    def __len__(self) -> int:
        return len(self.labels)

    @property
    def n_corner(self) -> int:
        """Number of leading corner-case vectors."""
        return sum(1 for s in self.labels if s not in ("random", "raw"))

    def take(self, index) -> Stimulus:
        """Sub-batch of the vectors selected by ``index`` (slice or index array)."""
        idx = np.arange(len(self))[index]
        return Stimulus(self.core, {k: v[idx] for k, v in self.fields.items()},
                        tuple(self.labels[i] for i in np.atleast_1d(idx)), self.seed)


def _concat(core: str, corners: list, random: dict, random_labels: list,
            seed: int) -> Stimulus:
    names = list(random)
    fields = {k: np.concatenate([np.asarray([c[k] for _, c in corners], dtype=np.int64)
                                 .reshape((len(corners),) + random[k].shape[1:]),
                                 random[k].astype(np.int64)]) for k in names}
    return Stimulus(core, fields, tuple([lab for lab, _ in corners] + random_labels), seed)


def _check_n(n) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
        raise InputRangeError("n (random vectors)", n, "an integer >= 0")
    return int(n)


# ---------------------------------------------------------------------------------
# stage A/B gap core
# ---------------------------------------------------------------------------------
def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _rotations(rng, n: int) -> np.ndarray:
    q = _unit(rng.normal(size=(n, 4)))
    w, x, y, z = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1),
    ], axis=1)


def _ncode(x) -> np.ndarray:
    return np.clip(np.floor(np.asarray(x) * _ONE + 0.5), -_ONE, _ONE).astype(np.int64)


def _ccode(x_mm) -> np.ndarray:
    return np.clip(np.floor(np.asarray(x_mm) * 65536.0 + 0.5), _CMIN, _CMAX).astype(np.int64)


def _tau2(tau_mm) -> np.ndarray:
    t2 = np.ceil(np.square(np.asarray(tau_mm, float)) * 2.0 ** 32)
    return np.clip(t2, 1, 2.0 ** 62).astype(np.int64)


#: Random gap passes come in groups of this many poses sharing one sample set and gate
#: (many posed points against one flank patch, as in the TCA); the vectorized golden
#: model evaluates a group in one call.
GAP_GROUP = 32


def _gap_random(rng, n: int, N: int) -> tuple[dict, list]:
    """Plausible passes (posed points near a sampled flank patch) and raw codes."""
    groups = -(-n // GAP_GROUP)
    grp = np.arange(n) // GAP_GROUP
    centre = rng.uniform(-45, 45, (groups, 3))
    normals = _unit(rng.normal(size=(groups, N, 3)))
    scale = np.exp(rng.uniform(np.log(0.01), np.log(20.0), (groups, 1, 1)))
    lateral = rng.normal(size=(groups, N, 3)) * scale
    g = centre[:, None, :] + lateral - (lateral * normals).sum(-1, keepdims=True) \
        * normals + rng.normal(size=(groups, N, 1)) * scale * normals
    tau = np.exp(rng.uniform(np.log(0.005), np.log(40.0), groups))
    R = _rotations(rng, n)
    t = rng.uniform(-30, 30, (n, 3))
    pp = centre[grp] + rng.normal(size=(n, 3)) * scale[grp, 0]     # wanted p' = R p + t
    p = np.einsum("nji,nj->ni", R, pp - t)
    fields = {"r": _ncode(R), "t": _ccode(t), "p": _ccode(p), "g": _ccode(g)[grp],
              "nrm": _ncode(normals)[grp], "tau2": _tau2(tau)[grp]}
    labels = ["random"] * n
    raw_grp = rng.random(groups) < 0.125   # whole-range codes (non-orthogonal R, ...)
    raw = raw_grp[grp]
    k, kg = int(raw.sum()), int(raw_grp.sum())
    if k:
        fields["r"][raw] = rng.integers(-_ONE, _ONE + 1, (k, 3, 3))
        fields["t"][raw] = rng.integers(_CMIN, _CMAX + 1, (k, 3))
        fields["p"][raw] = rng.integers(_CMIN, _CMAX + 1, (k, 3))
        gi = np.flatnonzero(raw_grp)
        g_raw = rng.integers(_CMIN, _CMAX + 1, (kg, N, 3))
        n_raw = rng.integers(-_ONE, _ONE + 1, (kg, N, 3))
        tau_raw = rng.integers(1, _TAU2_MAX, kg, endpoint=True)
        pos = np.searchsorted(gi, grp[raw])
        fields["g"][raw], fields["nrm"][raw] = g_raw[pos], n_raw[pos]
        fields["tau2"][raw] = tau_raw[pos]
        for i in np.flatnonzero(raw):
            labels[i] = "raw"
    return fields, labels


def _gap_corners(N: int) -> list:
    eye = np.eye(3, dtype=np.int64) * _ONE
    z3 = np.zeros(3, np.int64)
    ez = np.tile(np.array([0, 0, _ONE]), (N, 1))
    i = np.arange(N)
    base = {"r": eye, "t": z3, "p": z3, "nrm": ez}

    def case(label, g, **kw):
        return (label, {**base, "g": np.asarray(g, np.int64), **kw})

    step = (1 << 20) // max(N, 16)            # sweeps stay within +-16 mm for any N
    lane_sweep = np.stack([i * step, -i * step, (i - N // 2) * (step // 16)], -1)
    sym = np.where((i % 2)[:, None] == 0, [0, 0, 1 << 16], [0, 0, -(1 << 16)])
    far = np.stack([np.full(N, 10 << 16), (i % 64) << 12, (i % 64) << 10], -1)
    last = np.tile([1 << 16, 0, 5 << 16], (N, 1))      # rho = 1 mm^2, |g| = 5 mm ...
    last[-1] = [0, 0, 1 << 16]                         # ... except rho = 0, |g| = 1 mm
    return [
        case("gate rejects every lane", far, tau2=_tau2(1.0).item()),
        case("gate tau2 = 1: only rho = 0 passes", lane_sweep, tau2=1),
        case("every sample identical (rho and |g| ties)", np.tile([0, 0, 3 << 16], (N, 1)),
             tau2=_TAU2_MAX),
        case("+-g ties across lanes", sym, tau2=_TAU2_MAX),
        case("negative gaps (penetration)",
             np.stack([(i % 16) << 10, (i % 16) << 11, (i + 1) * ((2 << 16) // N)], -1),
             p=np.array([0, 0, 3 << 16]), tau2=_tau2(2.0).item()),
        case("winner is the last sample", last, tau2=_TAU2_MAX),
        case("posed point overflows Q(24,16)", lane_sweep, p=np.full(3, _CMAX),
             t=np.full(3, _CMAX), tau2=_TAU2_MAX),
        case("posed point at the negative limit", np.full((N, 3), _CMAX),
             p=np.full(3, _CMIN), t=z3, nrm=np.full((N, 3), -_ONE), tau2=_TAU2_MAX),
        case("extreme codes: R = -I, g at the corners", np.where(
            (i % 2)[:, None] == 0, _CMAX, _CMIN) * np.ones((N, 3), np.int64),
            r=-eye, p=np.full(3, _CMIN + 1), nrm=np.full((N, 3), _ONE), tau2=_TAU2_MAX),
        case("zero normals (rho = |d|^2)", lane_sweep, nrm=np.zeros((N, 3), np.int64),
             tau2=_TAU2_MAX),
        case("all-zero operands (go without data)", np.zeros((N, 3)),
             r=np.zeros((3, 3), np.int64), nrm=np.zeros((N, 3), np.int64), tau2=1),
    ]


def gap_stimulus(n: int, seed: int = 0, *, n_samples: int = 16,
                 corners: bool = True) -> Stimulus:
    """Gap-core passes: corner cases, then ``n`` seeded random passes of ``n_samples``.

    Parameters
    ----------
    n : int
        Random passes (about 1 in 8 with whole-range raw codes).
    seed : int
        Seed of :func:`numpy.random.default_rng`.
    n_samples : int, keyword-only
        Samples per pass N (all vectors of the batch share it; the latency is
        ``gap_latency(N, L)``).
    corners : bool, keyword-only
        Prepend the corner cases.
    """
    n = _check_n(n)
    if isinstance(n_samples, bool) or not isinstance(n_samples, (int, np.integer)) \
            or not 1 <= n_samples <= 4096:
        raise InputRangeError("n_samples", n_samples, "an integer in [1, 4096]")
    rng = np.random.default_rng(seed)
    fields, labels = _gap_random(rng, n, int(n_samples))
    return _concat("gap", _gap_corners(int(n_samples)) if corners else [], fields, labels,
                   seed)


# ---------------------------------------------------------------------------------
# stage C fit core (and the C -> D stencil inputs)
# ---------------------------------------------------------------------------------
_S, _T = stencil_coordinates()


def _surface(c0, c1, c2, c3, c4, c5) -> np.ndarray:
    """Gap samples (mm) of ``c0 + c1 s + c2 t + c3 s^2 + c4 s t + c5 t^2``."""
    c = [np.asarray(x, float)[..., None] for x in (c0, c1, c2, c3, c4, c5)]
    return c[0] + c[1] * _S + c[2] * _T + c[3] * _S ** 2 + c[4] * _S * _T + c[5] * _T ** 2


def _elliptic(A, B, theta, c0, c1, c2) -> np.ndarray:
    """Surface with principal half curvatures A, B (1/mm) at angle theta."""
    c, s = np.cos(theta), np.sin(theta)
    return _surface(c0, c1, c2, A * c * c + B * s * s, 2 * (A - B) * c * s,
                    A * s * s + B * c * c)


def _gcode(x_mm) -> np.ndarray:
    return np.clip(np.floor(np.ldexp(np.asarray(x_mm, float), STENCIL_GAP.frac) + 0.5),
                   STENCIL_GAP.min_code, STENCIL_GAP.max_code).astype(np.int64)


def _curvature_pairs(rng, n: int, lo: float, hi: float) -> tuple[np.ndarray, np.ndarray]:
    """Half curvatures log-uniform in [lo, hi], ratio log-uniform in [1, 200] (so about
    1 in 10 exceeds the alpha <= 128 envelope), in random order."""
    a = np.exp(rng.uniform(np.log(lo), np.log(hi), n))
    b = np.minimum(a * np.exp(rng.uniform(0.0, np.log(200.0), n)), hi)
    swap = rng.random(n) < 0.5
    return np.where(swap, b, a), np.where(swap, a, b)


def _stencils(rng, n: int, lo: float, hi: float) -> tuple[np.ndarray, list]:
    A, B = _curvature_pairs(rng, n, lo, hi)
    gaps = _elliptic(A, B, rng.uniform(0, np.pi, n), rng.uniform(-0.1, 0.1, n),
                     rng.uniform(-0.3, 0.3, n), rng.uniform(-0.3, 0.3, n))
    codes = _gcode(gaps) + rng.integers(-2, 3, (n, STENCIL_SIZE))
    labels = ["random"] * n
    kind = rng.random(n)
    saddle = kind < 0.08                      # indefinite quadratics (not elliptic)
    codes[saddle] = _gcode(_surface(0, 0, 0, rng.uniform(-1, 1, (int(saddle.sum()))),
                                    rng.uniform(-1, 1, int(saddle.sum())),
                                    rng.uniform(-1, 1, int(saddle.sum()))))
    raw = (kind >= 0.08) & (kind < 0.16)      # whole-range STENCIL_GAP codes
    codes[raw] = rng.integers(STENCIL_GAP.min_code, STENCIL_GAP.max_code,
                              (int(raw.sum()), STENCIL_SIZE), endpoint=True)
    small = (kind >= 0.16) & (kind < 0.22)    # small codes of any shape
    codes[small] = rng.integers(-4096, 4097, (int(small.sum()), STENCIL_SIZE))
    for i in np.flatnonzero(raw | small):
        labels[i] = "raw"
    return codes, labels


def _stencil_corners() -> list:
    z = np.zeros(STENCIL_SIZE)
    imp = np.zeros(STENCIL_SIZE, np.int64)
    imp[STENCIL_SIZE // 2] = STENCIL_GAP.max_code
    alt = np.where(np.arange(STENCIL_SIZE) % 2 == 0, STENCIL_GAP.max_code,
                   STENCIL_GAP.min_code)
    return [
        ("flat stencil (all zero: go without data)", np.zeros(STENCIL_SIZE, np.int64)),
        ("sphere A = B (tie, d = 0)", _gcode(_elliptic(0.05, 0.05, 0.0, 0.0, 0, 0))),
        ("saddle", _gcode(_surface(0, 0, 0, 0.2, 0.0, -0.1))),
        ("concave (negative curvatures)", _gcode(_elliptic(-0.05, -0.02, 0.3, 0, 0, 0))),
        ("cylinder (B = 0)", _gcode(_elliptic(0.1, 0.0, 0.0, 0, 0, 0))),
        ("extreme curvature ratio 1e-3 : 1", _gcode(_elliptic(1.0, 1e-3, 0.7, 0, 0, 0))),
        ("extreme curvature ratio 1 : 128", _gcode(_elliptic(2.0 ** -4, 2.0 ** -11, 0, 0,
                                                             0, 0))),
        ("large curvature 16 1/mm", _gcode(_elliptic(16.0, 8.0, 0.2, 0, 0, 0))),
        ("tiny curvature 2^-11 1/mm", _gcode(_elliptic(2.0 ** -11, 2.0 ** -11, 0, 0, 0, 0))),
        ("every code at the maximum", np.full(STENCIL_SIZE, STENCIL_GAP.max_code)),
        ("every code at the minimum", np.full(STENCIL_SIZE, STENCIL_GAP.min_code)),
        ("alternating min/max codes (coefficient overflow)", alt),
        ("centre impulse at the maximum code", imp),
        ("negative gaps with an offset", _gcode(_elliptic(0.1, 0.05, 0.0, -2.0, 0.1, 0) + z)),
    ]


def fit_stimulus(n: int, seed: int = 0, *, corners: bool = True) -> Stimulus:
    """Fit-core stencils: corner cases, then ``n`` seeded random stencils.

    Random stencils are quadratic surfaces with half curvatures log-uniform in
    [1e-3, 5] 1/mm at a random angle, offset and slopes, plus +-2 LSB noise; about 8 %
    saddles, 8 % whole-range codes and 6 % small random codes.
    """
    n = _check_n(n)
    rng = np.random.default_rng(seed)
    codes, labels = _stencils(rng, n, 1e-3, 5.0)
    corner = [(lab, {"gaps": g}) for lab, g in _stencil_corners()] if corners else []
    return _concat("fit", corner, {"gaps": codes}, labels, seed)


# ---------------------------------------------------------------------------------
# stage D (Hertz) and the C -> D chain
# ---------------------------------------------------------------------------------
def _loads(rng, n: int) -> np.ndarray:
    w = np.exp(rng.uniform(np.log(1.0), np.log(2.0 ** 17), n))
    return np.clip(np.floor(w * 256 + 0.5), ENV.LOAD_MIN_CODE, ENV.LOAD_MAX_CODE).astype(np.int64)


def _e_primes(rng, n: int) -> np.ndarray:
    e = np.full(n, STEEL_E_PRIME_CODE, np.int64)
    other = rng.random(n) < 0.25
    e[other] = rng.integers(ENV.E_PRIME_MIN_CODE, ENV.E_PRIME_MAX_CODE, int(other.sum()),
                            endpoint=True)
    return e


_I32 = (-(1 << 31), (1 << 31) - 1)


def _hertz_corners() -> list:
    cmin, cmax = ENV.CURV_MIN_CODE, ENV.CURV_MAX_CODE
    wmin, wmax = ENV.LOAD_MIN_CODE, ENV.LOAD_MAX_CODE
    one, w1k, st = 1 << CURVATURE.frac, 1000 << LOAD.frac, STEEL_E_PRIME_CODE
    a128 = 1 << 12

    def case(label, A, B, W=w1k, e=st):
        return (label, {"A": A, "B": B, "W": W, "e_prime": e})

    return [
        case("all zero (go without data)", 0, 0, 0, 0),
        case("A = B (alpha = 1, sort tie)", one // 8, one // 8),
        case("A > B (swapped order)", one, one // 16),
        case("alpha = 128 exactly (POW LUT end)", a128, 128 * a128),
        case("alpha just above 128", a128, 128 * a128 + 1),
        case("alpha 128 at the curvature minimum", cmin, 128 * cmin),
        case("minimum load", one // 4, one // 2, wmin),
        case("maximum load", one // 4, one // 2, wmax),
        case("load below the envelope", one // 4, one // 2, wmin - 1),
        case("load above the envelope", one // 4, one // 2, wmax + 1),
        case("zero load", one // 4, one // 2, 0),
        case("negative load", one // 4, one // 2, -w1k),
        case("curvatures at the minimum", cmin, cmin),
        case("curvatures at the maximum", cmax, cmax),
        case("min load, min curvatures", cmin, cmin, wmin),
        case("max load, max curvatures", cmax, cmax, wmax),
        case("max load, min curvatures", cmin, cmin, wmax),
        case("curvature below the envelope", cmin - 1, one),
        case("curvature above the envelope", one, cmax + 1),
        case("zero curvature", 0, one),
        case("negative curvature", -one, one),
        case("E' at the minimum", one // 4, one // 2, w1k, ENV.E_PRIME_MIN_CODE),
        case("E' at the maximum", one // 4, one // 2, w1k, ENV.E_PRIME_MAX_CODE),
        case("E' below the envelope", one // 4, one // 2, w1k, ENV.E_PRIME_MIN_CODE - 1),
        case("E' above the envelope", one // 4, one // 2, w1k, ENV.E_PRIME_MAX_CODE + 1),
        case("largest codes", _I32[1], _I32[1], _I32[1], _I32[1]),
        case("smallest codes", _I32[0], _I32[0], _I32[0], _I32[0]),
    ]


def hertz_stimulus(n: int, seed: int = 0, *, corners: bool = True) -> Stimulus:
    """Stage-D inputs: corner cases, then ``n`` seeded random vectors.

    Random vectors: curvatures log-uniform over the envelope [2^-11, 16] 1/mm with a
    log-uniform ratio up to 200 (alpha beyond 128 gets flagged), loads log-uniform over
    [1, 2^17] N, E' steel or (25 %) uniform over its envelope; about 10 % draw every
    word over its whole 32-bit range (envelope flags).
    """
    n = _check_n(n)
    rng = np.random.default_rng(seed)
    A, B = (np.floor(x).astype(np.int64) for x in
            _curvature_pairs(rng, n, ENV.CURV_MIN_CODE, ENV.CURV_MAX_CODE))
    fields = {"A": A, "B": B, "W": _loads(rng, n), "e_prime": _e_primes(rng, n)}
    labels = _raw_words(rng, fields, n)
    return _concat("hertz", _hertz_corners() if corners else [], fields, labels, seed)


def _raw_words(rng, fields: dict, n: int) -> list[str]:
    """About 10 % of the vectors draw every word over its whole 32-bit range (envelope
    flags); returns the labels ("random" / "raw"). Overwrites ``fields`` in place."""
    labels = ["random"] * n
    raw = rng.random(n) < 0.1
    for k in fields:
        fields[k][raw] = rng.integers(*_I32, int(raw.sum()), endpoint=True)
    for i in np.flatnonzero(raw):
        labels[i] = "raw"
    return labels


def _line_corners() -> list:
    one, w1k, st = 1 << CURVATURE.frac, 1000 << LOAD.frac, STEEL_E_PRIME_CODE
    lmin, lmax = 1 << CURVATURE.frac, 1 << (CURVATURE.frac + 10)   # 1 mm, 1024 mm
    l20 = 20 << CURVATURE.frac

    def case(label, A, B, L=l20, W=w1k, e=st):
        return (label, {"A": A, "B": B, "W": W, "e_prime": e, "L": L})

    return [
        case("all zero (go without data)", 0, 0, 0, 0, 0),
        case("ellipse inside the flank (published core)", one // 8, one // 32),
        case("A_min 2^-12 (scale 1)", 256, 26_000),
        case("A_min 2^-15 (scale 2)", 32, 3_000),
        case("A_min 2^-20 (scale 3, ratio 600: line)", 1, 600),
        case("A_min = 0 (cylinder)", 0, one // 16),
        case("ratio above 128 (line)", 1_000, 200_000),
        case("ellipse longer than the flank", 256, 26_000, 5 << CURVATURE.frac,
             20_000 << LOAD.frac),
        case("length at the minimum", one // 8, one // 32, lmin),
        case("length at the maximum", one // 8, one // 32, lmax),
        case("length below the envelope", one // 8, one // 32, lmin - 1),
        case("length above the envelope", one // 8, one // 32, lmax + 1),
        case("B_max above the envelope", 0, ENV.CURV_MAX_CODE + 1),
        case("B_max below the envelope", 0, ENV.CURV_MIN_CODE - 1),
        case("negative A_min (saddle)", -one, one),
        case("largest codes", *(_I32[1],) * 5),
        case("smallest codes", *(_I32[0],) * 5),
    ]


def line_stimulus(n: int, seed: int = 0, *, corners: bool = True) -> Stimulus:
    """Line-core inputs (:mod:`.hertz.line`): corner cases, then ``n`` seeded random
    vectors: B_max log-uniform in [2^-11, 16] 1/mm, ratio B_max/A_min log-uniform up to
    1e5 (every SCALE exponent, both modes), loads and E' as :func:`hertz_stimulus`, L
    log-uniform in [0.5, 2048] mm (a little beyond the envelope each side); about 10 %
    draw every word over its whole 32-bit range."""
    n = _check_n(n)
    rng = np.random.default_rng(seed)
    b = np.exp(rng.uniform(np.log(2.0 ** -11), np.log(16.0), n))
    a = b / np.exp(rng.uniform(0.0, np.log(1e5), n))
    length = np.exp(rng.uniform(np.log(0.5), np.log(2048.0), n))
    swap = rng.random(n) < 0.5
    code = (lambda x: np.floor(x * (1 << CURVATURE.frac) + 0.5).astype(np.int64))
    fields = {"A": code(np.where(swap, b, a)), "B": code(np.where(swap, a, b)),
              "W": _loads(rng, n), "e_prime": _e_primes(rng, n),
              "L": np.minimum(code(length), _I32[1])}
    labels = _raw_words(rng, fields, n)
    return _concat("line", _line_corners() if corners else [], fields, labels, seed)


def chain_stimulus(n: int, seed: int = 0, *, corners: bool = True) -> Stimulus:
    """C -> D inputs (also the combinational C + D core): stencils, loads and E'.

    Corner cases: every fit corner at 1 kN steel, then an elliptic stencil at the
    minimum, maximum and out-of-envelope loads and E'. Random stencils have half
    curvatures log-uniform in [2^-11, 16] 1/mm (mixed as for :func:`fit_stimulus`).
    """
    n = _check_n(n)
    rng = np.random.default_rng(seed)
    codes, labels = _stencils(rng, n, 2.0 ** -11, 16.0)
    fields = {"gaps": codes, "W": _loads(rng, n), "e_prime": _e_primes(rng, n)}
    raw = np.array([lab == "raw" for lab in labels], bool)
    fields["W"][raw & (rng.random(n) < 0.5)] = 0
    corner = []
    if corners:
        w1k = 1000 << LOAD.frac
        corner = [(lab, {"gaps": g, "W": w1k, "e_prime": STEEL_E_PRIME_CODE})
                  for lab, g in _stencil_corners()]
        ell = _gcode(_elliptic(0.05, 0.01, 0.4, 0.0, 0.05, -0.02))
        for lab, w, e in (("minimum load", ENV.LOAD_MIN_CODE, STEEL_E_PRIME_CODE),
                          ("maximum load", ENV.LOAD_MAX_CODE, STEEL_E_PRIME_CODE),
                          ("load below the envelope", ENV.LOAD_MIN_CODE - 1,
                           STEEL_E_PRIME_CODE),
                          ("load above the envelope", ENV.LOAD_MAX_CODE + 1,
                           STEEL_E_PRIME_CODE),
                          ("E' at the minimum", w1k, ENV.E_PRIME_MIN_CODE),
                          ("E' above the envelope", w1k, ENV.E_PRIME_MAX_CODE + 1)):
            corner.append((f"elliptic stencil, {lab}", {"gaps": ell, "W": w, "e_prime": e}))
    return _concat("chain", corner, fields, labels, seed)


def chain_line_stimulus(n: int, seed: int = 0, *, corners: bool = True) -> Stimulus:
    """C -> line-core inputs: the vectors of :func:`chain_stimulus` (same seed), each
    with a contact-line length ``L`` drawn as :func:`line_stimulus` does (log-uniform in
    [0.5, 2048] mm, a little beyond the envelope each side; about 10 % over the whole
    32-bit range), from its own stream of the seed. Corner cases: the chain's at L =
    20 mm, then the elliptic stencil at the envelope's lengths and one code beyond."""
    chain = chain_stimulus(n, seed, corners=corners)
    rng = np.random.default_rng([seed, 1])         # an independent stream for L
    code = (lambda x: np.floor(x * (1 << CURVATURE.frac) + 0.5).astype(np.int64))
    length = np.minimum(code(np.exp(rng.uniform(np.log(0.5), np.log(2048.0), n))), _I32[1])
    raw = rng.random(n) < 0.1
    length[raw] = rng.integers(*_I32, int(raw.sum()), endpoint=True)
    fields = {k: v[chain.n_corner:] for k, v in chain.fields.items()}
    fields["L"] = length
    corner = []
    if corners:
        l20, lmin, lmax = (x << CURVATURE.frac for x in (20, 1, 1024))
        corner = [(lab, {**{k: v[i] for k, v in chain.fields.items()}, "L": l20})
                  for i, lab in enumerate(chain.labels[:chain.n_corner])]
        ell = _gcode(_elliptic(0.05, 0.01, 0.4, 0.0, 0.05, -0.02))
        w1k = 1000 << LOAD.frac
        for lab, length_code in (("length at the minimum", lmin),
                                 ("length at the maximum", lmax),
                                 ("length below the envelope", lmin - 1),
                                 ("length above the envelope", lmax + 1),
                                 ("zero length", 0)):
            corner.append((f"elliptic stencil, {lab}", {"gaps": ell, "W": w1k,
                                                        "e_prime": STEEL_E_PRIME_CODE,
                                                        "L": length_code}))
    return _concat("chain_line", corner, fields, list(chain.labels[chain.n_corner:]), seed)


#: Generator per core name (``comb`` shares the chain's inputs).
STIMULUS_CORES = {"gap": gap_stimulus, "fit": fit_stimulus, "hertz": hertz_stimulus,
                  "chain": chain_stimulus, "comb": chain_stimulus,
                  "hertz_exact": hertz_stimulus, "chain_exact": chain_stimulus,
                  "hertz_pipe": hertz_stimulus, "hertz_pipe_exact": hertz_stimulus,
                  "chain_pipe": chain_stimulus, "gap_lean": gap_stimulus,
                  "comb_exact": chain_stimulus, "hertz_line": line_stimulus,
                  "hertz_line_exact": line_stimulus, "chain_line": chain_line_stimulus}


def stimulus(core: str, n: int, seed: int = 0, **kwargs) -> Stimulus:
    """Dispatch to the generator of ``core`` (one of :data:`STIMULUS_CORES`)."""
    try:
        fn = STIMULUS_CORES[core]
    except KeyError:
        raise InputRangeError("core", core, f"one of {sorted(STIMULUS_CORES)}") from None
    return fn(n, seed, **kwargs)
