"""Constants of the exported C library, read from the package's own tables.

Everything the C sources need (register fraction bits, shifts, constants, operating
envelope, flags, the ROM words and their interpolation geometry, the pseudo-inverse,
the gap kernel's sentinels and lane count) is collected here from
:mod:`gearcontact.preview.hertz.formats`, :mod:`gearcontact.preview.hertz.luts`,
:mod:`gearcontact.preview.fit.golden`, :mod:`gearcontact.preview.fit.pinv`,
:mod:`gearcontact.preview.gap.golden` and :mod:`gearcontact.contract.qformat`; the
templates print these numbers and never hold one of their own. Nothing is retyped: a change of a table in the package changes
the exported C on the next ``gearcontact export c``. The fp64 cube root's seed
polynomial (:func:`cbrt_seed`) is computed here too, in exact rational arithmetic.
"""

from __future__ import annotations

import math

from ..analytic.cube_root import seed_coefficients
from ..preview.chain import (FIT_FLAG_SHIFT, LINE_B_ZERO_CODES, LINE_CHAIN_FIT_FLAGS,
                             chain_flag_names)
from ..preview.fit import golden as G
from ..preview.fit.pinv import ACC, COEFF, N_COEFFS, N_TAPS, baked_pinv
from ..preview.fit.reference import HALF, QUADRATIC_LANES, pairwise_sum, quadratic_weights
from ..contract.stencil import STENCIL_SIDE
from ..preview.gap.cores import GAP_LANES
from ..preview.gap.golden import DEFAULT_FORMAT, IDX_SENTINEL
from ..preview.gap.variants import residual_limit
from ..preview.hertz import formats as F
from ..preview.hertz import line as LN
from ..preview.hertz.sqrt import SQRT_BITS
from ..preview.hertz.luts import (CBRT_SPEC, EE_DIVIDEND_SHIFT, EE_EXACT_SPEC, LUT_SIZE,
                                  POW_EXACT_SPEC, POW_SPEC, LutSpec, rom_words,
                                  same_geometry)
from ..contract.qformat import (CURVATURE, LOAD, PMAX, SEMI_AXIS, STENCIL_GAP,
                                FixedPointOverflow, sq)

__all__ = ["hertz_constants", "hertz_roms", "hertz_flags", "lut_geometry", "fit_constants",
           "fit_flags", "fit_weight_codes", "fit_mac_plan", "expand_fit_mac_plan",
           "fit_mac_ops", "fit_mac_schedule", "orbit_members",
           "fit_isqrt_seeds", "fit_linear_safe_code",
           "FIT_LANES", "fit_lanes_fp64", "cbrt_seed", "gap_constants", "line_constants",
           "exact_hertz_table_constants"]


def lut_geometry(spec: LutSpec) -> dict:
    """Interpolation geometry of one ROM (argument offset, sub-step bits, Q field, shift
    of the quadratic term, fraction bits of the result)."""
    return {"x0_code": spec.x0_code, "tbits": spec.tbits, "qbits": spec.qbits,
            "corr_shift": spec.corr_shift, "out_frac": spec.out_frac}


def hertz_flags() -> list[tuple[str, int]]:
    """``(name, bit)`` of every stage-D flag, bit order."""
    return [(name, bit) for bit, name in sorted(F.FLAG_NAMES.items())]


def hertz_roms() -> dict[str, tuple[int, ...]]:
    """The four stage-D ROMs (256 words each): POW and its exact twin POWX, the exact
    E_e numerator EEX, and CBRT, as the golden model and the RTL read them."""
    assert same_geometry(POW_SPEC, POW_EXACT_SPEC) and same_geometry(POW_SPEC, EE_EXACT_SPEC)
    return {"pow": rom_words(POW_SPEC), "pow_exact": rom_words(POW_EXACT_SPEC),
            "ee_exact": rom_words(EE_EXACT_SPEC), "cbrt": rom_words(CBRT_SPEC)}


def hertz_constants() -> dict[str, int]:
    """Named integer constants of the stage-D datapath (macro name -> value)."""
    c = {
        # dividends of DIV_RX/DIV_RY (one extra bit for the rounding) and DIV_R
        "RXY_DIVIDEND_LOG2": 2 * CURVATURE.frac,
        "R_DIVIDEND_LOG2": F.RADIUS.frac + CURVATURE.frac - 1,
        "ALPHA_FRAC": F.ALPHA.frac,
        "K_INT_FRAC": F.K_INT.frac, "K2_FRAC": F.K2.frac, "E6_FRAC": F.E6.frac,
        "T1_FRAC": F.T1.frac, "T2_FRAC": F.T2.frac, "T3_FRAC": F.T3.frac,
        "RADIUS_FRAC": F.RADIUS.frac, "CA_FRAC": F.CA.frac, "M_RED_FRAC": F.M_RED.frac,
        "CBRT_VAL_FRAC": F.CBRT_VAL.frac, "AXIS_W_FRAC": F.AXIS_W.frac,
        "SEMI_AXIS_FRAC": SEMI_AXIS.frac, "K_OUT_FRAC": F.K_OUT.frac,
        "PN2_SHIFT": F.PN2_SHIFT, "PMAX_SHIFT": F.PMAX_SHIFT,
        "EE_DIVIDEND_SHIFT": EE_DIVIDEND_SHIFT,
        "C6": F.C6, "N5": F.N5, "C3": F.C3,
        "CURV_MIN_CODE": F.CURV_MIN_CODE, "CURV_MAX_CODE": F.CURV_MAX_CODE,
        "LOAD_MIN_CODE": F.LOAD_MIN_CODE, "LOAD_MAX_CODE": F.LOAD_MAX_CODE,
        "E_PRIME_MIN_CODE": F.E_PRIME_MIN_CODE, "E_PRIME_MAX_CODE": F.E_PRIME_MAX_CODE,
        "ALPHA_MAX_CODE": F.ALPHA_MAX_CODE,
        # largest code of each output register (FLAG_OVERFLOW beyond it)
        "SEMI_AXIS_MAX_CODE": SEMI_AXIS.max_code, "PMAX_MAX_CODE": PMAX.max_code,
        "K_OUT_MAX_CODE": F.K_OUT.max_code, "CURVATURE_MAX_CODE": CURVATURE.max_code,
        "CURVATURE_FRAC": CURVATURE.frac, "LOAD_FRAC": LOAD.frac, "PMAX_FRAC": PMAX.frac,
        "LUT_SIZE": LUT_SIZE,
        # right shifts of the golden model's round_shift steps (module docstring of
        # gearcontact.preview.hertz.golden)
        "K_SHIFT": POW_SPEC.out_frac - F.K_INT.frac,
        "K2_SHIFT": 2 * F.K_INT.frac - F.K2.frac,
        "T1_SHIFT": F.K2.frac + F.E6.frac - F.T1.frac,
        "T2_SHIFT": F.T1.frac + F.RADIUS.frac - F.T2.frac,
        "CA_SHIFT": F.CA.frac - F.T3.frac,
        "AXIS_SHIFT": F.CBRT_VAL.frac - F.AXIS_W.frac,
        "OUT_AXIS_SHIFT": F.AXIS_W.frac - SEMI_AXIS.frac,
        "K_OUT_SHIFT": F.K_INT.frac - F.K_OUT.frac,
        # register widths bounding the divisors of DIV_B (k_int) and DIV_PMAX (b_w): the
        # C code's divider steps (gc_hertz_golden.c) are proven from them
        "K_INT_BITS": F.K_INT.bits, "AXIS_W_BITS": F.AXIS_W.bits,
    }
    # the golden model reads the CBRT interpolation as CBRT_VAL without a shift
    assert CBRT_SPEC.out_frac == F.CBRT_VAL.frac
    for name, spec in (("POW", POW_SPEC), ("CBRT", CBRT_SPEC)):
        for key, value in lut_geometry(spec).items():
            c[f"{name}_{key.upper()}"] = value
    return c


def fit_flags() -> list[tuple[str, int]]:
    """``(name, bit)`` of every stage-C flag (the fit core's flags word)."""
    bits = [1 << i for i in range(G.FLAG_BITS)]
    # the chain's names of the fit bits, without their "fit_" prefix
    return [(chain_flag_names(bit << FIT_FLAG_SHIFT)[0].removeprefix("fit_"), bit)
            for bit in bits]


def fit_weight_codes() -> tuple[tuple[int, ...], ...]:
    """The pseudo-inverse ROM, WEIGHT Q(32,20) codes ``[j][i]`` (6 x 49), as the golden
    fit and the RTL read it.

    Raises
    ------
    FixedPointOverflow
        A row's ``sum_i |M_ji|`` reaches 2^31: the 64-bit MAC of the C code would no
        longer be exact (``|acc| <= 2^31 sum_i |M_ji| < 2^62``).
    """
    rom = baked_pinv()
    if max(rom.weight_l1_codes) >= (1 << 31):
        raise FixedPointOverflow("sum_i |M_ji| (64-bit MAC bound)",
                                 max(rom.weight_l1_codes), sq(32, 0))
    return tuple(tuple(int(w) for w in row) for row in rom.weight_codes)


#: Parities of the stencil's orbit sums (:func:`fit_mac_plan`): even (0) or odd (1) in
#: s, then in t; ``None`` for a row without one (its MAC runs tap by tap).
PARITIES = ((0, 0), (1, 0), (0, 1), (1, 1))


def _tap(a: int, b: int) -> int:
    """Stencil tap of the point s = a, t = b (s along a row, t down a column)."""
    c = STENCIL_SIDE // 2
    return STENCIL_SIDE * (c + b) + c + a


def orbit_members(a: int, b: int, parity) -> list[tuple[int, int]]:
    """``(tap, sign)`` of the orbit sum u_p(a, b) = sum over the distinct points
    (+-a, +-b) of sign(s)^ps sign(t)^pt g(s, t) (``a, b >= 0``; an odd parity needs
    its coordinate nonzero)."""
    ps, pt = parity
    pts = {(sa * a, sb * b) for sa in (1, -1) for sb in (1, -1)}
    return sorted((_tap(s, t), (1 if s >= 0 or not ps else -1)
                   * (1 if t >= 0 or not pt else -1)) for s, t in pts)


def _parity(row) -> tuple[int, int] | None:
    """The parity of a weight row under s -> -s and t -> -t (None: neither even nor
    odd in one of them)."""
    c = STENCIL_SIDE // 2
    w = {(a, b): row[_tap(a, b)] for a in range(-c, c + 1) for b in range(-c, c + 1)}
    for ps, pt in PARITIES:
        if all(w[-a, b] == (-1) ** ps * v and w[a, -b] == (-1) ** pt * v
               for (a, b), v in w.items()):
            return ps, pt
    return None


def _plan_form(row) -> dict:
    """One linear form's terms: on the orbit sums of its parity (elements ``(a, b)``)
    or, without one, on the taps; one term per distinct nonzero magnitude of the word,
    ``word * (sum of plus - sum of minus)``, ``word`` the weight of the first element
    holding that magnitude."""
    parity = _parity(row)
    c = STENCIL_SIDE // 2
    if parity is None:
        weights = {i: w for i, w in enumerate(row)}
    else:
        weights = {(a, b): row[_tap(a, b)] for b in range(c + 1) for a in range(c + 1)
                   if (a or not parity[0]) and (b or not parity[1])}
    terms = []
    for mag in sorted({abs(w) for w in weights.values() if w}, reverse=True):
        word = next(w for w in weights.values() if abs(w) == mag)
        terms.append({"word": word,
                      "plus": [k for k, w in weights.items() if w == word],
                      "minus": [k for k, w in weights.items() if w == -word]})
    return {"parity": parity, "terms": terms}


def _transposed(row) -> tuple[int, ...]:
    """The row with s and t swapped."""
    n = STENCIL_SIDE
    return tuple(row[n * (i % n) + i // n] for i in range(n * n))


def _muls(forms) -> int:
    return sum(len(f["terms"]) for f in forms)


def fit_mac_plan(rom=None) -> dict:
    """The golden fit's MAC ``acc_j = sum_i M_ji g_i`` regrouped for the C code.

    The stencil's point symmetries: every ROM row is even or odd under s -> -s and
    under t -> -t, so it is a linear form in the 49 orbit sums u_p(a, b) =
    sum over (+-a, +-b) of sign(s)^ps sign(t)^pt g (:func:`orbit_members`, formed once
    by a butterfly and shared by all rows; a row of parity p reads the u_p), with one
    multiply per distinct ``|word|`` (equal words at (a, b) and (b, a) share one). Two
    rows that are each other's s <-> t swap with a parity even or odd in both (c3 and
    c5) are formed as P = acc_j + acc_j' and Q = acc_j - acc_j' (P symmetric under
    the swap, Q antisymmetric: their words pair up) and ``2 acc_j = P + Q``,
    ``2 acc_j' = P - Q``; the C code folds the halving into the rounding shift
    (``round_shift(2 x, s + 1) = round_shift(x, s)``). The regrouped sums are the same
    integers (the distributive law on exact integers; :func:`expand_fit_mac_plan`
    multiplies the plan out and this function checks it equals the ROM).

    Accumulator width: a tap enters each form once (orbits partition the stencil), so
    every partial sum of a form with weights W is at most ``2^31 sum_i |W_i|`` (gaps
    ``|g_i| <= 2^31``), for P and Q at most ``2^31 (L1(M_j) + L1(M_j'))``; checked here
    below 2^63 (int64), as ``|P + Q| = 2 |acc_j| < 2^32 L1(M_j)``.

    Parameters
    ----------
    rom : sequence of sequences of int, optional
        Weight codes ``[j][i]`` (default: :func:`fit_weight_codes`).

    Returns
    -------
    dict
        ``forms``: the linear forms, each ``parity`` ((ps, pt) or None: tap by tap)
        and ``terms`` (``word``, signed, and ``plus``, ``minus``: orbit points
        (a, b) or taps); ``coeffs``: per coefficient, ``halve`` (0 or 1) and ``parts``,
        ``[(sign, form index), ...]``: ``2^halve acc_j = sum sign form``.

    Raises
    ------
    FixedPointOverflow
        A form's partial sums could reach 2^63.
    """
    rom = fit_weight_codes() if rom is None else tuple(tuple(int(w) for w in r) for r in rom)
    forms, coeffs, done = [], [None] * len(rom), set()
    for j, row in enumerate(rom):
        if j in done:
            continue
        pair = next((k for k in range(j + 1, len(rom)) if k not in done
                     and rom[k] == _transposed(row) and rom[k] != row), None)
        alone = _plan_form(row)
        if pair is not None and alone["parity"] in ((0, 0), (1, 1)):
            p = _plan_form(tuple(x + y for x, y in zip(row, rom[pair])))
            q = _plan_form(tuple(x - y for x, y in zip(row, rom[pair])))
            if _muls([p, q]) < 2 * _muls([alone]):
                forms += [p, q]
                coeffs[j] = {"halve": 1, "parts": [(1, len(forms) - 2), (1, len(forms) - 1)]}
                coeffs[pair] = {"halve": 1, "parts": [(1, len(forms) - 2), (-1, len(forms) - 1)]}
                done |= {j, pair}
                continue
        forms.append(alone)
        coeffs[j] = {"halve": 0, "parts": [(1, len(forms) - 1)]}
        done.add(j)
    plan = {"forms": forms, "coeffs": coeffs}
    for f in forms:
        l1 = sum(abs(t["word"]) * len(_members(f["parity"], k)) for t in f["terms"]
                 for k in t["plus"] + t["minus"])
        if l1 >= 1 << 32:
            raise FixedPointOverflow("sum_i |W_i| of a fit MAC form (64-bit bound)", l1, sq(33, 0))
    if expand_fit_mac_plan(plan) != rom:         # by construction; never silently
        raise AssertionError("the regrouped fit MAC differs from the ROM")
    return plan


def _members(parity, key) -> list[tuple[int, int]]:
    """``(tap, sign)`` of one basis element of a form: an orbit sum, or a tap."""
    return [(key, 1)] if parity is None else orbit_members(*key, parity)


def expand_fit_mac_plan(plan: dict) -> tuple[tuple[int, ...], ...]:
    """The weight matrix ``[j][i]`` a plan of :func:`fit_mac_plan` computes (each form's
    basis elements expanded into signed taps, the forms combined and halved as the
    coefficient says; a halving that leaves a remainder raises)."""
    rows = []
    for f in plan["forms"]:
        w = [0] * N_TAPS
        for term in f["terms"]:
            for sign, keys in ((1, term["plus"]), (-1, term["minus"])):
                for key in keys:
                    for tap, s in _members(f["parity"], key):
                        w[tap] += sign * s * term["word"]
        rows.append(w)
    out = []
    for coeff in plan["coeffs"]:
        twice = [sum(sign * rows[k][i] for sign, k in coeff["parts"]) for i in range(N_TAPS)]
        if any(x % (1 << coeff["halve"]) for x in twice):
            raise AssertionError("a halved fit MAC form is odd")
        out.append(tuple(x >> coeff["halve"] for x in twice))
    return tuple(out)


def fit_mac_schedule(plan: dict) -> list[dict]:
    """The order in which gc_fit_golden.c runs a plan of :func:`fit_mac_plan`: the
    butterfly block of each column pair s = +-a (a = 0, 1, ...: its 7 rows' sums and
    differences and the orbit sums u_p(a, b)), each followed by the terms whose orbit
    sums are then all formed, so that few values are live at once (gcc keeps the
    source's order: the 49 orbit sums formed first spilled to the stack); the forms
    without a parity (tap by tap) after the last block.

    Returns
    -------
    list of dict
        Per block: ``a`` (None: the tap-by-tap forms) and ``terms``, a list of
        ``(form index, term, first)``; ``first`` marks the form's first term (it
        assigns, the others add); ``started``: the forms begun by the block's end
        (their running sums are pinned there: ``GC_SCHEDULE``, gc_arith.h).
    """
    blocks = {a: [] for a in range(STENCIL_SIDE // 2 + 1)}
    blocks[None] = []
    for k, f in enumerate(plan["forms"]):
        for t in f["terms"]:
            ready = None if f["parity"] is None else max(a for a, _ in t["plus"] + t["minus"])
            blocks[ready].append((k, t))
    seen, out = set(), []
    for a, terms in blocks.items():
        if terms or a is not None:
            out.append({"a": a, "terms": [(k, t, k not in seen and not seen.add(k))
                                          for k, t in terms], "started": sorted(seen)})
    return out


def fit_mac_ops(plan: dict) -> dict[str, int]:
    """Multiplies and additions of a plan as gc_fit_golden.c runs it: the orbit sums'
    butterfly (when a form reads them), each form's bracketed sums and the P +- Q."""
    n = STENCIL_SIDE
    butterfly = 2 * n * (n - 1) if any(f["parity"] for f in plan["forms"]) else 0
    adds = sum(len(t["plus"]) + len(t["minus"]) for f in plan["forms"] for t in f["terms"])
    return {"muls": _muls(plan["forms"]),
            "adds": butterfly + adds - len(plan["forms"])
            + sum(len(c["parts"]) - 1 for c in plan["coeffs"])}


#: Leading bits of the normalized radicand that index the seed table of the fit's
#: integer square root (:func:`fit_isqrt_seeds`): relative seed error <= 2^-8.
ISQRT_SEED_BITS = 9


def fit_isqrt_seeds() -> tuple[int, ...]:
    """Seeds of the C fit's floor(sqrt(d)): for the normalized radicand
    ``d' in [2^62, 2^64)`` with leading ``ISQRT_SEED_BITS`` bits ``k`` (``2^(b-2) <= k <
    2^b``), entry ``k - 2^(b-2)`` is ``isqrt(m - 1) + 1 > sqrt(d')`` with
    ``m = (k + 1) 2^(64 - b)``: an over-estimate within ``sqrt(1 + 2^(2-b)) - 1 <= 2^-8``
    relative (+1), from which two Newton steps land on floor(sqrt(d)) or one above
    (the proof: gc_fit_golden.c)."""
    b = ISQRT_SEED_BITS
    return tuple(math.isqrt(((k + 1) << (64 - b)) - 1) + 1
                 for k in range(1 << (b - 2), 1 << b))


#: Lanes of the fp64 fit's dot products (gc_fit_fp64.c): lane ``l`` sums the taps
#: ``FIT_LANES * k + l``; the taps past the last whole group of lanes are summed after.
#: The fp64 reference's lanes (c3..c5 are summed in them).
FIT_LANES = QUADRATIC_LANES


def _lanes_tree(product: str, groups: int) -> tuple[str, int]:
    """C text of the lanes' pairwise sum (:func:`pairwise_sum`) of ``groups`` products
    (``product`` with ``{k}`` for the group) and the tree's depth."""
    depth = math.ceil(math.log2(groups)) if groups > 1 else 0
    return pairwise_sum([product.format(k=k) for k in range(groups)],
                        lambda a, b: f"GC_ADD({a}, {b})"), depth


def fit_lanes_fp64() -> dict:
    """The fp64 fit's weights as gc_fit_fp64.c applies them.

    c0, c1, c2 tap by tap: every weight ``M_ji`` of the fp64 pseudo-inverse as its
    exact C99 hexadecimal literal, in groups of :data:`FIT_LANES` consecutive taps (one
    vector of weights per group and coefficient) and the taps after the last whole
    group. c3, c4, c5 as the fp64 reference sums them
    (:func:`gearcontact.preview.fit.reference.fitted_coefficients`): the
    :class:`~gearcontact.preview.fit.reference.QuadraticWeights` ``pair`` and ``skew``
    in groups of :data:`FIT_LANES` taps and ``total``, the same tree of additions.

    Returns
    -------
    dict
        ``lanes`` (:data:`FIT_LANES`); ``groups``: per linear coefficient (c0, c1, c2),
        per group, the literals of its taps; ``tail``: per linear coefficient
        ``[(tap, literal), ...]``; ``tree``: the lanes' sum of the groups' products as
        C, a pairwise tree (adjacent groups first; ``@`` stands for the coefficient's
        row), ``depth`` its levels. ``pair``, ``skew``: per quadratic coefficient, per
        group, the literals; ``total``: per quadratic coefficient, the literal;
        ``half``: the taps before the centre (``HALF``); ``quad_tree``, ``quad_depth``:
        the tree over the quadratic groups (``@`` the coefficient, 0 .. 2).
    """
    rows = [[float(w) for w in row] for row in baked_pinv().weights[:3]]
    whole = N_TAPS // FIT_LANES * FIT_LANES
    tree, depth = _lanes_tree("GC_MUL(FIT_M[@][{k}], x{k})", whole // FIT_LANES)
    quad = quadratic_weights()
    quad_tree, quad_depth = _lanes_tree("p@_{k}", HALF // FIT_LANES)

    def groups(row):
        return [[float(w).hex() for w in row[k:k + FIT_LANES]]
                for k in range(0, len(row) // FIT_LANES * FIT_LANES, FIT_LANES)]

    return {"lanes": FIT_LANES, "tree": tree, "depth": depth,
            "groups": [groups(row) for row in rows],
            "tail": [[(i, row[i].hex()) for i in range(whole, N_TAPS)] for row in rows],
            "half": HALF, "pair": [groups(row) for row in quad.pair],
            "skew": [groups(row) for row in quad.skew],
            "total": [float(t).hex() for t in quad.total],
            "quad_tree": quad_tree, "quad_depth": quad_depth}


def cbrt_seed() -> dict:
    """Seed of the fp64 cube root of gc_hertz_fp64.c: ``m^(1/3) ~ p(m - 3/2)`` on
    ``m in [1, 2)``, times ``2^(r/3)`` for ``r in {0, 1, 2}``, the coefficients of
    :func:`gearcontact.analytic.cube_root.seed_coefficients` (the twin's cube root: the
    same literals on every machine) as C99 literals. The seed's relative error,
    measured here on 2^16 + 1 points of [1, 2] (the error of a degree-5 interpolant of
    a function this smooth varies slowly between them), is at most ``bound`` (< 2^-18:
    one Halley step then leaves ``2 bound^3 / 3`` < 2^-54, below the rounding; the
    proof: gc_hertz_fp64.c).

    Returns
    -------
    dict
        ``poly``: C99 hexadecimal literals of p's coefficients, constant first;
        ``scale``: of ``2^(r/3)``, r = 0, 1, 2; ``bound``: the seed's relative error.

    Raises
    ------
    AssertionError
        The seed's error reaches 2^-18 (never silently).
    """
    poly, scale = seed_coefficients()
    bound = 0.0
    for k in range(2 ** 16 + 1):
        m = 1.0 + k / 2 ** 16
        u, y = m - 1.5, 0.0
        for c in reversed(poly):
            y = y * u + c
        bound = max(bound, abs(y / m ** (1.0 / 3.0) - 1.0))
    if bound >= 2.0 ** -18:
        raise AssertionError(f"cube-root seed error {bound:.3g} >= 2^-18")
    return {"poly": [c.hex() for c in poly], "scale": [c.hex() for c in scale],
            "bound": bound}


def fit_linear_safe_code() -> int:
    """The largest STENCIL_GAP code G such that every stencil with all ``|g_i| <= G``
    has c0, c1, c2 (the fit's linear part) within COEFF: ``|acc_j| <= G sum_i |W_ji|``
    and its rounding shift stays <= COEFF_MAX (>= COEFF_MIN alike). Where a caller
    guarantees it, ``gc_fit_golden_curvatures`` gives gc_fit_golden's outputs but c0..c2
    (gearcontact.h); 352,955,419 (168.3 mm) for the baked ROM."""
    s = ACC.frac - COEFF.frac
    rom = fit_weight_codes()
    top = ((COEFF.max_code + 1) << s) - (1 << (s - 1)) - 1
    return min(top // sum(abs(w) for w in rom[j]) for j in range(3))   # c0, c1, c2


def fit_constants() -> dict[str, int]:
    """Named integer constants of the stage-C fit core (macro name -> value)."""
    d_max = G.D_FMT.max_code
    return {"N_TAPS": N_TAPS, "N_COEFFS": N_COEFFS,
            "COEFF_SHIFT": ACC.frac - COEFF.frac,
            "COEFF_MIN_CODE": COEFF.min_code, "COEFF_MAX_CODE": COEFF.max_code,
            "D_MAX_CODE": d_max, "E_MAX_CODE": math.isqrt(d_max),
            "ISQRT_STEPS": G.ROOT_FMT.bits, "ISQRT_SEED_BITS": ISQRT_SEED_BITS,
            "ISQRT_SEED_SHIFT": 64 - ISQRT_SEED_BITS,
            "ISQRT_SEED_OFFSET": 1 << (ISQRT_SEED_BITS - 2),
            "CURVATURE_MIN_CODE": CURVATURE.min_code, "CURVATURE_MAX_CODE": CURVATURE.max_code,
            "STENCIL_GAP_FRAC": STENCIL_GAP.frac, "FIT_FLAG_SHIFT": FIT_FLAG_SHIFT,
            "LINE_B_ZERO_CODES": LINE_B_ZERO_CODES, "LINE_CHAIN_FIT_FLAGS": LINE_CHAIN_FIT_FLAGS,
            "LINEAR_SAFE_CODE": fit_linear_safe_code()}


def gap_constants() -> dict[str, int]:
    """Named integer constants of the stage A/B gap core (default formats, L lanes)."""
    fmt = DEFAULT_FORMAT
    # the C code keeps e_k at 16 fraction bits (no e_shift) and rho in 64 bits
    assert fmt.e_shift == 0
    return {"LANES": GAP_LANES, "MAX_SAMPLES": 16 * GAP_LANES,
            "NORMAL_FRAC": fmt.normal_frac,
            "COORD_MIN_CODE": fmt.coord.min_code, "COORD_MAX_CODE": fmt.coord.max_code,
            "GAP_SENTINEL": fmt.gap_sentinel, "IDX_SENTINEL": IDX_SENTINEL,
            "KEY_INF": fmt.key_inf, "LEAN_E_LIMIT": residual_limit("lean")}


def line_constants() -> dict[str, int]:
    """Named integer constants of the stage-D line core (:mod:`gearcontact.preview.
    hertz.line`): envelope of L and its format, similarity range, the line stage's
    constant and shifts, its flag bit and modes, and the host's lift of a shorter line
    (``LIFT_MAX_SHIFT``: down to ``LENGTH_MIN_CODE >> LIFT_MAX_SHIFT``)."""
    return {"LENGTH_MIN_CODE": LN.LENGTH_MIN_CODE, "LENGTH_MAX_CODE": LN.LENGTH_MAX_CODE,
            "SCALE_MAX": LN.SCALE_MAX, "C_IPI": LN.C_IPI, "QPI_SHIFT": LN.QPI_SHIFT,
            "Y_SHIFT": LN.Y_SHIFT, "SQRT_SHIFT": LN.SQRT_SHIFT, "BL_SHIFT": LN.BL_SHIFT,
            "P_SHIFT": LN.SQRT_OUT.frac - PMAX.frac,
            "B_SHIFT": LN.B_LINE.frac - SEMI_AXIS.frac, "SQRT_BITS": SQRT_BITS,
            "FLAG_LENGTH_RANGE": LN.FLAG_LENGTH_RANGE, "MODE_ELLIPTIC": LN.MODE_ELLIPTIC,
            "MODE_LINE": LN.MODE_LINE, "LENGTH_FRAC": LN.LINE_LENGTH.frac,
            "LIFT_MAX_SHIFT": LN.LIFT_MAX_SHIFT}


def exact_hertz_table_constants() -> dict:
    """The twin's exact elliptic Hertz table and its grid as C99 literals
    (gc_hertz_exact_table.h; exports with ``hertz_form="exact"``).

    The table is :func:`gearcontact.twin.exact_hertz.exact_hertz_table` itself (``ROWS``
    rows of ``ln c_a``, ``ln sqrt(p)``, ``ln K`` on the grid ``u = i STEP`` of ``ln
    alpha``), each double as its exact hexadecimal literal, and the constants of
    :func:`~gearcontact.twin.exact_hertz.exact_hertz_terms` formed by the same
    expressions: the C law reads the same doubles as the twin's compiled law.

    Returns
    -------
    dict
        ``rows``, ``columns`` (int); ``inv_step`` (1/STEP), ``ratio_max`` (the largest
        curvature ratio, dimensionless), ``three_over_pi``, ``three_over_2pi``: C99
        literals; ``table``: the ``rows * columns`` literals, row-major.
    """
    from ..twin import exact_hertz as X

    return {"rows": X.ROWS, "columns": X.COLUMNS, "inv_step": (1.0 / X.STEP).hex(),
            "ratio_max": float(X.RATIO_MAX).hex(), "three_over_pi": (3.0 / math.pi).hex(),
            "three_over_2pi": (1.5 / math.pi).hex(),
            "table": [float(v).hex() for v in X.exact_hertz_table()]}
