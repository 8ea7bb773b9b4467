"""The start-point search of a relieved pair (:func:`gearcontact.tca.analysis.reference_start`)
and the Newton solve it repeats (:func:`gearcontact.tca.mating.solve_mating_point`).

Truth: Newton's iteration as it was before the search was made fast (the Jacobian
evaluated at every line-search trial, :func:`_full_newton` below, built on the module's
own residual, clamp and boxes): the solve now evaluates the Jacobian only at the trial
it takes, which must leave every iterate, and so every outcome, the same bit for bit -
converged point and iteration count, edge exit, or the residual left after the
iteration limit. Pair: the Flankrem gear pair (tests/data/toprem), whose mean point
lies on the gear's kink ridge, so that the search tries candidates that fail after the
full 40 iterations before one converges; and s0003's start.
"""

import numpy as np
import pytest

from gearcontact.tca import analysis, mating
from gearcontact.tca.types import VARIABLES, EdgeContact, TcaConvergenceError

FLANKREM = "tests/data/toprem/iso23509_f2_gear_flankrem.toml"


def _full_newton(pinion, gear, kin, guess, fixed, *, tol_mm=1e-10, max_iter=40):
    """The iteration with a Jacobian at every trial; ``("ok", x, iterations)``,
    ``("edge", phi1, where)`` or ``("none", phi1, residual)``."""
    free = [i for i, n in enumerate(VARIABLES) if n != fixed]
    boxes = mating._boxes(pinion, gear)
    x, hit = mating._clamp(guess.vector(), boxes)
    res, _, jac = mating._residual_and_jacobian(pinion, gear, kin, x)
    norm = np.linalg.norm(res)
    clamped = 0
    for it in range(1, max_iter + 1):
        try:
            step = np.linalg.solve(jac[:, free], -res)
        except np.linalg.LinAlgError:
            step = np.linalg.lstsq(jac[:, free], -res, rcond=None)[0]
        lam = 1.0
        while True:
            trial = x.copy()
            trial[free] += lam * step
            trial, hit = mating._clamp(trial, boxes)
            res_t, _, jac_t = mating._residual_and_jacobian(pinion, gear, kin, trial)
            norm_t = np.linalg.norm(res_t)
            if norm_t < norm or lam < 1e-3:
                break
            lam *= 0.5
        x, res, jac, norm = trial, res_t, jac_t, norm_t
        clamped = clamped + 1 if hit else 0
        if np.all(np.abs(res) < tol_mm) and not hit:
            return "ok", x, it
        if clamped >= 3:
            return "edge", float(x[4]), hit[0]
    return "none", float(x[4]), float(norm)


def _outcome(pinion, gear, kin, guess, fixed):
    """:func:`~gearcontact.tca.mating.solve_mating_point`'s outcome in the same form."""
    try:
        mp = mating.solve_mating_point(pinion, gear, kin, guess, fixed=fixed)
    except EdgeContact as exc:
        return "edge", exc.phi1_rad, exc.where
    except TcaConvergenceError as exc:
        return "none", exc.phi1_rad, exc.residual
    return "ok", np.array([mp.u1, mp.v1, mp.u2, mp.v2, mp.phi1_rad, mp.phi2_rad]), mp.iterations


def _same(a, b):
    return a[0] == b[0] and np.array_equal(a[1], b[1]) and a[2] == b[2]


@pytest.fixture(scope="module")
def flankrem():
    from gearcontact.geometry.flank import build_flanks
    from gearcontact.geometry.pair import load_pair

    pair = load_pair(FLANKREM)
    return pair, build_flanks(pair)


def test_search_solves_are_the_full_newton_bit_for_bit(flankrem, monkeypatch):
    pair, flanks = flankrem
    side = pair.design_side
    pinion, gear = flanks.flank("pinion", side), flanks.flank("gear", side)
    kin = pair.kinematics()
    calls = []
    solve = analysis.solve_mating_point

    def recorded(p, g, k, guess, *, fixed="phi1", **kw):
        calls.append((guess, fixed))
        return solve(p, g, k, guess, fixed=fixed, **kw)

    monkeypatch.setattr(analysis, "solve_mating_point", recorded)
    start, fixed = analysis.reference_start(pair, flanks, side)
    # the mean point (phi1 held) and the pinion points tried (u1 held), each once: the
    # candidates clipped onto one already tried are not solved again
    assert calls[0][1] == "phi1" and {f for _, f in calls[1:]} == {"u1"}
    tried = [(g.u1, g.v1) for g, _ in calls[1:]]
    assert len(set(tried)) == len(tried) >= 3
    outcomes = []
    for guess, fix in calls:
        got = _outcome(pinion, gear, kin, guess, fix)
        assert _same(got, _full_newton(pinion, gear, kin, guess, fix))
        outcomes.append(got[0])
    # every candidate before the start fails after the full iteration (the ridge), the
    # start converges
    assert outcomes[:-1] == ["none"] * (len(calls) - 1) and outcomes[-1] == "ok"
    assert (start, fixed) == calls[-1]


def test_s0003_start_solve_is_the_full_newton_bit_for_bit(s0003_centred):
    pair, flanks = s0003_centred
    side = pair.design_side
    pinion, gear = flanks.flank("pinion", side), flanks.flank("gear", side)
    start, fixed = analysis.reference_start(pair, flanks, side)
    got = _outcome(pinion, gear, pair.kinematics(), start, fixed)
    assert got[0] == "ok"
    assert _same(got, _full_newton(pinion, gear, pair.kinematics(), start, fixed))
