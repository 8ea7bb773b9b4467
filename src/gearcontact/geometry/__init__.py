"""Gear geometry: pair definition, blank design, cutter, generated flanks, kinematics.

Data flow (``docs/architecture.md``): :func:`load_pair` -> :class:`GearPair` ->
:func:`design_blank` (ISO 23509 Method 1, via ``GearPair.blank``) ->
:func:`build_flanks` -> :class:`FlankSet` (formate gear flanks, conjugate pinion
flanks with ease-off), each flank a :class:`Surface` in its member's body frame.
"""

from .blank import BlankDesign, design_blank
from .conjugate import ConjugateFlank, MeshingError, UndercutError
from .easeoff import EaseOff, apply_easeoff
from .flank import FlankSet, MemberFlanks, build_flanks
from .formate import SIDES, FlankBoundary, FormateFlank
from .kinematics import AssemblyErrors, MeshKinematics
from .pair import CutterSpec, EaseOffCoefficients, GearPair, load_pair, parse_pair
from .sampling import FlankGrid, principal_curvatures, sample_grid
from .sheet import RadialSheet
from .surface import Surface, SurfacePoint

__all__ = ["AssemblyErrors", "BlankDesign", "ConjugateFlank", "CutterSpec", "EaseOff",
           "EaseOffCoefficients", "FlankBoundary", "FlankGrid", "FlankSet", "FormateFlank",
           "GearPair", "MemberFlanks", "MeshKinematics", "MeshingError", "RadialSheet", "SIDES",
           "Surface", "SurfacePoint", "UndercutError", "apply_easeoff", "build_flanks",
           "design_blank", "load_pair", "parse_pair", "principal_curvatures", "sample_grid"]
