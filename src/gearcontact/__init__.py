"""gearcontact: gear tooth-contact computation with a physics-direct Hertz preview.

The curated public API is listed in ``__all__``; heavier parts (numba kernels,
Amaranth, matplotlib) load on first use of the name that needs them. See
``docs/architecture.md`` for the data flow.
"""

from importlib import import_module

__version__ = "0.1.0"

#: public name -> module that defines it (imported lazily)
_LAZY = {
    # materials and errors (lazy too: ``import gearcontact`` stays free of numpy, so the
    # console script reaches its Ctrl-C handler within milliseconds)
    "Material": "materials", "STEEL": "materials", "effective_modulus_mpa": "materials",
    "reduced_modulus_mpa": "materials", "InputRangeError": "validation",
    # geometry
    "GearPair": "geometry.pair", "load_pair": "geometry.pair",
    "design_blank": "geometry.blank", "build_flanks": "geometry.flank",
    "AssemblyErrors": "geometry.kinematics", "MeshKinematics": "geometry.kinematics",
    # TCA
    "analyze_pair": "tca.analysis",
    # loaded contact
    "solve_lcp": "halfspace.lcp", "solve_patch": "halfspace.patch",
    "TangentGrid": "halfspace.grid", "single_pair_ltca": "ltca.pair_ltca",
    # analytic truths
    "exact_elliptic_hertz": "analytic.hertz", "hamrock_brewe_hertz": "analytic.hertz",
    "circular_hertz": "analytic.hertz",
    # physics-direct preview
    "get_engine": "preview.engine", "PreviewResult": "preview.engine",
    "PreviewEngine": "preview.engine",
    # the main job
    "run_analysis": "report.analyze",
}

__all__ = ["__version__", *_LAZY]


def __getattr__(name):
    try:
        module = _LAZY[name]
    except KeyError:
        raise AttributeError(f"module 'gearcontact' has no attribute {name!r}") from None
    value = getattr(import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_LAZY))
