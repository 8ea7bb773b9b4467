"""Elastic materials and the effective contact modulus.

References
----------
K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, eq. (4.22).
B. J. Hamrock, D. Dowson, *Ball Bearing Lubrication*, Wiley, 1981 (E' = 2 E*).
"""

from __future__ import annotations

from dataclasses import dataclass

from .validation import InputRangeError, check_positive, check_range

__all__ = ["Material", "STEEL", "effective_modulus_mpa", "reduced_modulus_mpa"]


@dataclass(frozen=True)
class Material:
    """An isotropic linear-elastic material.

    Parameters
    ----------
    youngs_modulus_mpa : float
        Young's modulus E in MPa (N/mm^2); 209 GPa steel is 209000.
    poisson_ratio : float
        Poisson's ratio nu, dimensionless, in [0, 0.5).
    name : str
        Label for reports.
    """

    youngs_modulus_mpa: float
    poisson_ratio: float
    name: str = "material"

    def __post_init__(self):
        check_positive("youngs_modulus_mpa", self.youngs_modulus_mpa)
        check_range("poisson_ratio", self.poisson_ratio, 0.0, 0.5, hi_open=True)

    @classmethod
    def from_gpa(cls, youngs_modulus_gpa: float, poisson_ratio: float,
                 name: str = "material") -> "Material":
        """Build from E in GPa (the unit the CLI takes)."""
        return cls(check_positive("modulus (GPa)", youngs_modulus_gpa) * 1e3,
                   poisson_ratio, name)


#: Through-hardened gear steel of the s0003 pair (docs/spec.md sec. 3).
STEEL = Material(youngs_modulus_mpa=209_000.0, poisson_ratio=0.3, name="steel")


def reduced_modulus_mpa(m1: Material, m2: Material | None = None) -> float:
    """Johnson's contact modulus E* in MPa: 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2."""
    m2 = m1 if m2 is None else m2
    inv = ((1.0 - m1.poisson_ratio ** 2) / m1.youngs_modulus_mpa
           + (1.0 - m2.poisson_ratio ** 2) / m2.youngs_modulus_mpa)
    if not inv > 0.0:
        raise InputRangeError("materials", (m1, m2), "a pair with finite compliance")
    return 1.0 / inv


def effective_modulus_mpa(m1: Material, m2: Material | None = None) -> float:
    """Hamrock–Brewe effective modulus E' = 2 E* in MPa (steel/steel: 229,670 MPa)."""
    return 2.0 * reduced_modulus_mpa(m1, m2)
