"""gearcontact: gear tooth-contact computation with a physics-direct Hertz preview.

The curated public API is listed in ``__all__``; heavier parts (numba kernels,
Amaranth, matplotlib) load on first use of the name that needs them. See
``docs/architecture.md`` for the data flow.
"""

from .lazy_names import lazy_names

__version__ = "0.1.0"

#: module -> public names it defines (imported lazily: ``import gearcontact`` stays free
#: of numpy, so the console script reaches its Ctrl-C handler within milliseconds)
_LAZY = {
    # materials and errors
    "materials": ("Material", "STEEL", "effective_modulus_mpa", "reduced_modulus_mpa"),
    "validation": ("InputRangeError",),
    # geometry
    "geometry.pair": ("GearPair", "load_pair"),
    "geometry.blank": ("design_blank",),
    "geometry.flank": ("build_flanks",),
    "geometry.kinematics": ("AssemblyErrors", "MeshKinematics"),
    # TCA
    "tca.analysis": ("analyze_pair",),
    # loaded contact
    "halfspace.lcp": ("solve_lcp",),
    "halfspace.patch": ("solve_patch",),
    "halfspace.grid": ("TangentGrid",),
    "ltca.pair_ltca": ("single_pair_ltca",),
    # analytic truths
    "analytic.hertz": ("exact_elliptic_hertz", "hamrock_brewe_hertz", "circular_hertz"),
    # physics-direct preview
    "preview.engine": ("get_engine", "PreviewResult", "PreviewEngine"),
    # the main job
    "report.analyze": ("run_analysis",),
}

__all__ = ["__version__", *(name for names in _LAZY.values() for name in names)]

__getattr__ = lazy_names(__name__, _LAZY)


def __dir__():
    return sorted(set(globals()) | set(__all__))
