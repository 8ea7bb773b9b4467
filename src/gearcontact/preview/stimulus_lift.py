"""Line-core stimulus of the host's path: contact lines shorter than the core's 1 mm.

The line core takes ``L`` in [1, 1024] mm; the host lifts a shorter line to
``(W << s, L << s)`` and undoes the lift on the outputs (:func:`.hertz.line.length_lift`,
docs/hertz.md sec. 6). The generators here add such lines to the line cores' stimulus
(:func:`.stimulus.line_stimulus`, :func:`.stimulus.chain_line_stimulus`) for the
golden-vector export and the C library's tests:

* :func:`short_line_stimulus` -- the line stimulus's curvatures, loads and E' with
  every ``L`` log-uniform in [2^-9, 1) mm (every lift 1..8 and below the lift's floor);
* :func:`host_line_stimulus`, :func:`host_chain_line_stimulus` -- the line (chain)
  stimulus with every :data:`SHORT_LINE_EVERY`-th plausible random vector's ``L`` drawn
  that way, and the lift's corner cases after the core's.

Lift corners (a gear-like line contact; the chain: a cylinder stencil): at 100 N, ``L``
at the lift's floor ``2^-8`` mm (lift 8) and one code under it (no lift), one code under
1 mm (lift 1); at the floor, ``W`` at the most the lift allows (``W << 8`` at the load
envelope's top, 512 N) and one code over (no lift).
"""

from __future__ import annotations

import numpy as np

from ..contract import envelope as ENV
from ..contract.qformat import CURVATURE, LOAD
from .hertz.line import LENGTH_MIN_CODE, LIFT_MAX_SHIFT
from .stimulus import (STEEL_E_PRIME_CODE, Stimulus, _concat, _gcode, _surface,
                       chain_line_stimulus, line_stimulus)

__all__ = ["SHORT_LINE_EVERY", "SHORT_LINE_MIN_MM", "short_lengths", "short_line_stimulus",
           "host_line_stimulus", "host_chain_line_stimulus"]

#: Every this many-th plausible random vector of a host stimulus gets a short line.
SHORT_LINE_EVERY = 4
#: Shortest drawn line, mm: one octave under the lift's floor (2^-LIFT_MAX_SHIFT mm).
SHORT_LINE_MIN_MM = 2.0 ** -(LIFT_MAX_SHIFT + 1)


def short_lengths(rng, n: int) -> np.ndarray:
    """``n`` LINE_LENGTH Q(32,20) codes log-uniform in [2^-9, 1) mm (``int64``)."""
    return np.floor(np.exp(rng.uniform(np.log(SHORT_LINE_MIN_MM), 0.0, n)) * LENGTH_MIN_CODE
                    + 0.5).astype(np.int64)


def _lift_cases() -> list[tuple[str, int, int]]:
    """``(label, L code, W code)`` of the lift's corners (module docstring)."""
    floor_code, w_top = LENGTH_MIN_CODE >> LIFT_MAX_SHIFT, ENV.LOAD_MAX_CODE >> LIFT_MAX_SHIFT
    w = 100 << LOAD.frac                    # 100 N: lifted by 8, 25.6 kN, in the envelope
    return [("lift: L at the floor 2^-8 mm", floor_code, w),
            ("lift: L one code under the floor", floor_code - 1, w),
            ("lift: L one code under 1 mm", LENGTH_MIN_CODE - 1, w),
            ("lift: W at the most the lift allows", floor_code, w_top),
            ("lift: W one code over", floor_code, w_top + 1)]


def _line_lift_corners(e_prime: int) -> list:
    # a gear-like line contact: A 2^-12, B 2^-5 1/mm
    return [(lab, {"A": 1 << (CURVATURE.frac - 12), "B": 1 << (CURVATURE.frac - 5), "W": w,
                   "L": length, "e_prime": e_prime}) for lab, length, w in _lift_cases()]


def short_line_stimulus(n: int, seed: int = 0, *, corners: bool = True) -> Stimulus:
    """Line-core inputs with ``L`` below the core's 1 mm: the lift's corners (steel),
    then :func:`.stimulus.line_stimulus`'s ``n`` random curvatures, loads and E' (seed
    ``seed``) with ``L`` from :func:`short_lengths` (``default_rng(seed)``)."""
    f = dict(line_stimulus(n, seed, corners=False).fields)
    f["L"] = short_lengths(np.random.default_rng(seed), len(f["L"]))
    return _concat("line", _line_lift_corners(STEEL_E_PRIME_CODE) if corners else [], f,
                   ["random"] * len(f["L"]), seed)


def _with_short_lines(st: Stimulus, extra: list, seed: int) -> Stimulus:
    """``st`` with the corners ``extra`` after its own and every SHORT_LINE_EVERY-th
    ``random`` vector's L from :func:`short_lengths` (stream ``[seed, 2]``)."""
    n0 = st.n_corner
    labels = st.labels[n0:]
    pick = np.flatnonzero(np.array([lab == "random" for lab in labels], bool))
    pick = pick[SHORT_LINE_EVERY - 1::SHORT_LINE_EVERY]
    fields = {k: v[n0:].copy() for k, v in st.fields.items()}
    fields["L"][pick] = short_lengths(np.random.default_rng([seed, 2]), pick.size)
    corners = [(lab, {k: v[i] for k, v in st.fields.items()})
               for i, lab in enumerate(st.labels[:n0])] + extra
    return _concat(st.core, corners, fields, list(labels), seed)


def host_line_stimulus(n: int, seed: int = 0, *, corners: bool = True) -> Stimulus:
    """The host's line path (:func:`.hertz.line_vec.lifted_line_golden_array`):
    :func:`.stimulus.line_stimulus` (corner cases, ``n`` seeded random vectors: both
    modes, every similarity exponent, flagged inputs, L log-uniform in [0.5, 2048] mm)
    with every fourth plausible random vector's L log-uniform in [2^-9, 1) mm instead
    (every lift 1..8), and the lift's corner cases after the line core's."""
    st = line_stimulus(n, seed, corners=corners)
    extra = _line_lift_corners(STEEL_E_PRIME_CODE) if corners else []
    return _with_short_lines(st, extra, seed)


def host_chain_line_stimulus(n: int, seed: int = 0, *, corners: bool = True) -> Stimulus:
    """The host's line chain (:func:`.chain.lifted_chain_line_golden_batch`):
    :func:`.stimulus.chain_line_stimulus` with every fourth plausible random vector's L
    log-uniform in [2^-9, 1) mm instead (every lift 1..8), and the lift's corner cases
    on a cylinder stencil (half curvature 2^-5 1/mm across, B- = 0) after the chain's."""
    st = chain_line_stimulus(n, seed, corners=corners)
    cyl = _gcode(_surface(0.0, 0.0, 0.0, 2.0 ** -5, 0.0, 0.0))
    extra = [(lab, {"gaps": cyl, "W": w, "e_prime": STEEL_E_PRIME_CODE, "L": length})
             for lab, length, w in _lift_cases()] if corners else []
    return _with_short_lines(st, extra, seed)
