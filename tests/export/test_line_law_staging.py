"""The drivetrain FMU's staged line law (gc_line_law.c: ``gc_line_laws``, the previews of
a call's pairs with the slice law's Newton in lockstep; ``gc_line_pair_loads``, the line
loads of a stage in lockstep) against the same law pair by pair (``gc_line_law``,
``gc_line_pair_load``: the port of the twin's line law the mesh FMU runs and the FMU
tests hold to the twin).

Truth: the pair-by-pair functions in the same binary. The staging only reorders
independent pairs' work (each pair's operations the same, in the same order), so the
contract is bit-for-bit equality of every output: exact, no tolerance. Operands: the
EV reducer's drivetrain FMU (7 phases) and its baked line rows, every row interval,
fractions in [0, 1], approaches of 1e-5 .. 1e-2 mm and Newton starts over the twin's
load envelope [1, 2^17] N, both backends (fp64, golden: the golden line chain, the fp64
one where it flags); seeded xorshift operands for the loads of 1..5 pairs.
"""

from __future__ import annotations

import pytest

fmpy = pytest.importorskip("fmpy")

from .test_fmu_cylindrical import _export  # noqa: E402
from .test_fmu_drivetrain import _run_harness  # noqa: E402

_HARNESS = r"""
#include <string.h>
#include "gc_drivetrain_fmu.c"
#include "gc_contact_law.c"

static uint64_t x = 88172645463325252u;
static uint64_t next(void) { x ^= x << 13; x ^= x >> 7; x ^= x << 17; return x; }
static double unit(void) { return (double)(next() >> 11) / 9007199254740992.0; }

int main(void)
{
    const double *r0[N_PAIRS], *r1[N_PAIRS];
    double d[N_PAIRS], cb[N_PAIRS], we[N_PAIRS], lam[N_PAIRS], pv[N_PAIRS][GC_LP_N];
    double lam1, pv1[GC_LP_N], dl[5], ll[5], bl[5], cl[5], wl[5], w0[5];
    double *warm[N_PAIRS];
    long same = 0, differ = 0, line = 0, hertz = 0, none = 0, p_same = 0, p_differ = 0;
    int b, i, j, k, n, q;
    for (b = 0; b < 2; b++)
        for (i = 0; i < N_ROWS - 1; i++)
            for (k = 0; k < 40; k++) {
                double f = k % 8 == 0 ? (double)(k % 16 == 0) : unit();
                for (j = 0; j < N_PAIRS; j++) {
                    r0[j] = LINE_ROWS[j][i];
                    r1[j] = LINE_ROWS[j][i + 1];
                    d[j] = exp(log(1e-5) + unit() * log(1e3));
                    we[j] = exp(unit() * log(131072.0));
                    cb[j] = 0.0;
                    warm[j] = NULL;
                }
                memset(pv, 0, sizeof pv);     /* a pair without law leaves a, b, p */
                gc_line_laws(b, N_PAIRS, r0, r1, f, i, d, cb, we, warm, lam, pv);
                for (j = 0; j < N_PAIRS; j++) {
                    memset(pv1, 0, sizeof pv1);
                    lam1 = gc_line_law(b, r0[j], r1[j], f, i, d[j], cb[j], we[j], NULL, pv1);
                    if (memcmp(&lam1, &lam[j], sizeof lam1) == 0
                        && memcmp(pv1, pv[j], sizeof pv1) == 0)
                        ++same;
                    else
                        ++differ;
                    if (lam1 <= 0.0)
                        ++none;
                    else if (pv1[GC_LP_MODE] == GC_LINE_LAW_LINE)
                        ++line;
                    else
                        ++hertz;
                }
            }
    for (k = 0; k < 20000; k++) {
        n = 1 + k % 5;
        for (q = 0; q < n; q++) {
            dl[q] = exp(log(1e-5) + unit() * log(1e3));
            ll[q] = 4.0 / (3.141592653589793 * 2.2e5 * (5.0 + 40.0 * unit()));
            bl[q] = 1.0 + 14.0 * unit();
            cl[q] = k % 3 == 0 ? 0.0 : 1e-6 * unit();
            w0[q] = wl[q] = k % 7 == 0 ? 0.0 : exp(unit() * log(131072.0));
        }
        gc_line_pair_loads(n, dl, ll, bl, cl, wl);
        for (q = 0; q < n; q++) {
            double w = gc_line_pair_load(dl[q], ll[q], bl[q], cl[q], w0[q]);
            if (memcmp(&w, &wl[q], sizeof w) == 0)
                ++p_same;
            else
                ++p_differ;
        }
    }
    printf("%d %d %ld %ld %ld %ld %ld %ld %ld\n", N_ROWS, N_PAIRS, same, differ, line, hertz,
           none, p_same, p_differ);
    return 0;
}
"""


@pytest.fixture(scope="module")
def drivetrain_fmu(tmp_path_factory):
    return _export(tmp_path_factory.mktemp("cyl_staging") / "drivetrain", "drivetrain")


def test_staged_line_law_equals_the_pair_by_pair_law(drivetrain_fmu, tmp_path):
    """gc_line_laws on all pairs of a row interval equals gc_line_law pair by pair, law
    and every pv output bit for bit (2 backends x every row interval x 40 fractions x
    every pair: line mode, and no law on the table's padding pairs, both exercised); gc_line_pair_loads of 1..5 pairs equals gc_line_pair_load per pair bit
    for bit (60,000 loads, Newton from a load or from the secant at 1 N). Exact: the
    same operations per pair (module docstring)."""
    from fmpy import __file__ as fmpy_file
    from pathlib import Path

    flags = [f"-I{Path(fmpy_file).parent / 'c-code'}"]
    words = _run_harness(drivetrain_fmu, tmp_path, _HARNESS, "staging", flags).split()
    rows, pairs, same, differ, line, hertz, none, p_same, p_differ = map(int, words)
    assert differ == 0 and same == 2 * (rows - 1) * 40 * pairs
    assert line > 1000 and none > 0         # the line law and the padding both reached
    assert line + hertz + none == same
    assert p_differ == 0 and p_same == 60000
