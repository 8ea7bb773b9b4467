"""Shared seeded input generators for the stage-D tests."""

import numpy as np
import pytest

from gearcontact.materials import STEEL, Material, effective_modulus_mpa

#: E' (MPa) of the material pairs of the accuracy domain: steel/steel (229 670),
#: aluminium 70 GPa / nu 0.33, titanium 110 GPa / nu 0.34 (like pairs), steel/cast iron
#: (120 GPa, nu 0.26).
E_PRIMES = {
    "steel": effective_modulus_mpa(STEEL),
    "aluminium": effective_modulus_mpa(Material(70_000.0, 0.33, "aluminium")),
    "titanium": effective_modulus_mpa(Material(110_000.0, 0.34, "titanium")),
    "steel-cast-iron": effective_modulus_mpa(STEEL, Material(120_000.0, 0.26, "cast iron")),
}


def accuracy_domain(n, seed):
    """n seeded points of the accuracy domain: A-, B- log-uniform in [1e-3, 1] 1/mm
    with B/A <= 127.5 (LUT range 128 less the input quantization of the ratio, <= 0.12
    at A- = 1e-3; 10 % of them with B/A in [1, 1.5], where the POW
    interpolation error peaks), W log-uniform in [10, 20 000] N. Returns (A, B, W)."""
    rng = np.random.default_rng(seed)
    a = np.exp(rng.uniform(np.log(1e-3), 0.0, n))
    ratio = np.exp(rng.uniform(0.0, np.log(127.5), n))
    near = rng.random(n) < 0.1
    ratio[near] = rng.uniform(1.0, 1.5, near.sum())
    b = np.minimum(a * ratio, 1.0)
    w = np.exp(rng.uniform(np.log(10.0), np.log(20_000.0), n))
    swap = rng.random(n) < 0.5                     # present both orders
    return np.where(swap, b, a), np.where(swap, a, b), w


@pytest.fixture(scope="session")
def e_primes():
    return E_PRIMES
