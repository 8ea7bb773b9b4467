"""Old names answer for one release with a DeprecationWarning; nothing inside uses them.

Truth: the promise of :mod:`gearcontact.deprecation` (issue 24): each moved name is the
very object of its new home and warns, naming that home; an unknown name is still an
AttributeError; and no module of the package, no test and no benchmark imports a moved
name from its old home (an AST scan of every ``from ... import`` in the sources).
"""

import ast
import importlib
import warnings
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

#: old module -> {moved name: new home}
MOVED = {
    "gearcontact.geometry.flank": {n: "gearcontact.geometry.formate" for n in (
        "FlankBoundary", "FormateFlank", "cone_vector", "gear_flank")},
    "gearcontact.tca.solve": {"VARIABLES": "gearcontact.tca.types",
                              "posed_point": "gearcontact.tca.mating",
                              "normal_derivatives": "gearcontact.tca.mating"},
    "gearcontact.preview.qformat": {n: "gearcontact.contract.qformat" for n in (
        "QFormat", "FixedPointOverflow", "round_shift", "sq", "uq", "COORD", "NORMAL",
        "LOAD", "CURVATURE", "SEMI_AXIS", "PMAX", "GAP")},
    "gearcontact.preview.fit.stencil": {n: "gearcontact.contract.stencil" for n in (
        "STENCIL_SIDE", "STENCIL_SIZE", "STENCIL_SPACING_MM", "stencil_coordinates",
        "read_stencil_csv", "write_stencil_csv")},
    "gearcontact.hw.synth": {n: "gearcontact.hw.dsp_study" for n in (
        "DSP_STUDY_VERILOG", "DSP_STUDY_COUNTS", "parse_stat_modules", "dsp_study")},
    # the rtl-soc backend beside the drivers it runs (tri_core, bhseq_core, line_core)
    "gearcontact.hw.driver": {"SocEngine": "gearcontact.hw.soc_engine"},
    # the typed keys of a flank's tables beside the check and the slip attribution
    "gearcontact.geometry.blank_check": {
        "typed_resolution": "gearcontact.geometry.typed_settings",
        **{n: "gearcontact.geometry.known_slips" for n in ("INCH_MM", "SLIPS", "UNIT_SLIPS")}},
}
#: Names the old module still imports for its own use: importable there without a
#: warning (an ordinary import), but no longer exported and used by nobody else.
KEPT = {
    "gearcontact.geometry.flank": {"SIDES", "gear_flanks"},
    "gearcontact.tca.solve": {"ARCSEC_PER_RAD", "EDGE_TE_LIMIT_ARCSEC", "ContactGuess",
                              "MatingPoint", "TcaPath", "EdgeContact",
                              "TcaConvergenceError", "solve_mating_point"},
    # one phase's solve moved to gearcontact.ltca.lte_phase (lte.py past 600 lines)
    "gearcontact.ltca.lte": {"ACTIVE_SHARE", "check_loaded", "preview_balance",
                             "solve_phase"},
    # the verdict's types moved to gearcontact.geometry.blank_verdict (past 600 lines)
    "gearcontact.geometry.blank_check": {"BlankCheck", "Comparison", "FlankCheck"},
}


@pytest.mark.parametrize("old, name, new", [(o, n, h) for o, names in MOVED.items()
                                            for n, h in names.items()])
def test_moved_name_warns_and_is_the_new_object(old, name, new):
    mod = importlib.import_module(old)
    with pytest.warns(DeprecationWarning, match=rf"{old}\.{name} is deprecated.*{new}\.{name}"):
        got = getattr(mod, name)
    assert got is getattr(importlib.import_module(new), name)
    assert name not in getattr(mod, "__all__", ())


@pytest.mark.parametrize("old", sorted(MOVED))
def test_unknown_name_is_still_an_attribute_error(old):
    mod = importlib.import_module(old)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(AttributeError, match="no attribute 'no_such_name'"):
            getattr(mod, "no_such_name")


def _resolve(node: ast.ImportFrom, path: Path) -> str | None:
    if not node.level:
        return node.module
    parts = path.relative_to(ROOT / "src").with_suffix("").parts
    base = parts[:len(parts) - node.level]
    return ".".join(base + ((node.module,) if node.module else ()))


def test_nothing_imports_a_name_from_its_old_home():
    offenders = []
    for top in ("src", "tests", "benchmarks", "examples"):
        for path in (ROOT / top).rglob("*.py"):
            tree = ast.parse(path.read_text(encoding="utf-8"))
            for node in ast.walk(tree):
                if not isinstance(node, ast.ImportFrom):
                    continue
                if node.level and top != "src":
                    continue
                mod = _resolve(node, path)
                old = MOVED.get(mod, {}).keys() | KEPT.get(mod, set())
                offenders += [f"{path.relative_to(ROOT)}:{node.lineno} {mod}.{a.name}"
                              for a in node.names if a.name in old]
    assert offenders == []
