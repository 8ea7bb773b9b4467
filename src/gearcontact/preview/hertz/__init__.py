"""Stage D of the physics-direct preview: elliptic Hertz (Hamrock–Brewe).

Three models side by side sharing one set of constants:

* :mod:`.reference` — fp64 (:func:`hertz_preview`, :func:`hertz_preview_array`);
* :mod:`.golden` — bit-exact integer model of the serialized datapath
  (:func:`hertz_golden`, :func:`hertz_golden_trace`, encode/decode helpers) and
  :mod:`.golden_vec`, its vectorized bit-identical twin
  (:func:`.golden_vec.hertz_golden_array`; not imported here so that importing the
  package does not load numba);
* formats/constants (:mod:`.formats`), ROMs (:mod:`.luts`), divider (:mod:`.divider`)
  and the cycle schedule (:mod:`.schedule`) that the RTL imports.
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
