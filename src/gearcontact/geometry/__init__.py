"""Gear geometry: pair definition, blank design, cutter, generated flanks, kinematics.

Data flow (``docs/architecture.md``): :func:`load_pair` -> :class:`GearPair` ->
:func:`design_blank` (ISO 23509 Method 1, via ``GearPair.blank``) ->
:func:`build_flanks` -> :class:`FlankSet` (formate gear flanks, conjugate pinion
flanks with ease-off), each flank a :class:`Surface` in its member's body frame.
"""

from ..lazy_names import lazy_names

__all__ = ["AssemblyErrors", "BlankDesign", "ConjugateFlank", "CutterSpec", "EaseOff",
           "EaseOffCoefficients", "FlankBoundary", "FlankGrid", "FlankSet", "FormateFlank",
           "GearPair", "MemberFlanks", "MeshKinematics", "MeshingError", "RadialSheet", "SIDES",
           "Surface", "SurfacePoint", "UndercutError", "apply_easeoff", "build_flanks",
           "design_blank", "load_pair", "parse_pair", "principal_curvatures", "sample_grid"]

#: Each public name imports its module on first use: importing one module of the package
#: does not import the others (and their numpy, scipy and numba).
__getattr__ = lazy_names(__name__, {
    "blank": ("BlankDesign", "design_blank"),
    "conjugate": ("ConjugateFlank", "MeshingError", "UndercutError"),
    "easeoff": ("EaseOff", "apply_easeoff"),
    "flank": ("FlankSet", "MemberFlanks", "build_flanks"),
    "formate": ("SIDES", "FlankBoundary", "FormateFlank"),
    "kinematics": ("AssemblyErrors", "MeshKinematics"),
    "pair": ("CutterSpec", "EaseOffCoefficients", "GearPair", "load_pair", "parse_pair"),
    "sampling": ("FlankGrid", "principal_curvatures", "sample_grid"),
    "sheet": ("RadialSheet",),
    "surface": ("Surface", "SurfacePoint"),
})
