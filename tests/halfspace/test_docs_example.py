"""The sphere-on-a-flat example of docs/halfspace.md, run exactly as printed there.

Truth: the circular Hertz solution (:func:`gearcontact.analytic.hertz.circular_hertz`,
Johnson 1985 eqs. 4.22–4.23) of a ball of radius R on a flat (``A = 1/(2R)``), same
load and materials. Tolerances: those of the solver's own Hertz tests at 16 cells per
semi-axis (tests/halfspace/test_patch.py): peak pressure 1 %, approach 0.5 %, contact
radius one cell; the example resolves the radius with 18.7 cells. The exact sphere gap
differs from Hertz's paraboloid by ``r^4 / (8 R^3)``, 1e-4 of the gap at the contact
edge, far inside these tolerances. The printed line is checked too (what a reader sees).
"""

import contextlib
import io
import re
from pathlib import Path

import pytest

from gearcontact.analytic.hertz import circular_hertz
from gearcontact.materials import STEEL, effective_modulus_mpa

PAGE = Path(__file__).resolve().parents[2] / "docs" / "halfspace.md"


def _snippet() -> str:
    blocks = re.findall(r"```python\n(.*?)```", PAGE.read_text(encoding="utf-8"), re.S)
    assert len(blocks) == 1, "docs/halfspace.md shows one Python example"
    return blocks[0]


def test_sphere_on_flat_matches_circular_hertz():
    ns: dict = {}
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(_snippet(), str(PAGE), "exec"), ns)
    hz = circular_hertz(0.5 / ns["radius_mm"], ns["load_n"],
                        e_prime_mpa=effective_modulus_mpa(STEEL, STEEL))
    patch, grid = ns["patch"], ns["grid"]
    assert patch.converged and not patch.touches_edge
    assert patch.p_peak_mpa == pytest.approx(hz.p_max_mpa, rel=0.01)
    assert patch.delta_mm == pytest.approx(hz.approach_mm, rel=0.005)
    assert abs(patch.ellipse.semi_major_mm - hz.a_mm) <= grid.dx_mm[0]
    assert abs(patch.ellipse.semi_minor_mm - hz.b_mm) <= grid.dy_mm[0]
    # the page quotes the printed line; it must be what the snippet prints
    printed = out.getvalue().strip()
    assert f"It prints `{printed}`" in PAGE.read_text(encoding="utf-8").replace("\n", " ")
