"""Closed-form contact mechanics used as truth by the code and the tests.

See :mod:`gearcontact.analytic.hertz` (exact elliptical Hertz, Hamrock–Brewe, circular).
"""

from .hertz import (HB_ERROR_RATIOS, HertzContact, circular_hertz, exact_elliptic_hertz,
                    hamrock_brewe_error_table, hamrock_brewe_hertz,
                    hamrock_brewe_hertz_array, hamrock_brewe_terms)

__all__ = ["HertzContact", "exact_elliptic_hertz", "hamrock_brewe_hertz",
           "hamrock_brewe_hertz_array", "hamrock_brewe_terms", "circular_hertz",
           "hamrock_brewe_error_table", "HB_ERROR_RATIOS"]
