"""gearcontact: gear tooth-contact computation with a physics-direct Hertz preview.

The public API is curated here; see ``docs/architecture.md`` for the data flow.
"""

from .materials import STEEL, Material, effective_modulus_mpa, reduced_modulus_mpa
from .validation import InputRangeError

__version__ = "0.1.0"

__all__ = ["Material", "STEEL", "effective_modulus_mpa", "reduced_modulus_mpa",
           "InputRangeError", "__version__"]
