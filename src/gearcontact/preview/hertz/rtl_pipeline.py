"""Pipeline builder of the initiation-interval-1 stage D: live values and array dividers.

:class:`Pipeline` carries the values one evaluation still needs from stage to stage
(registered on a common enable); :class:`PipelinedDivision` is one unrolled restoring
division (:func:`.rtl_divider.restoring_step`, one row per dividend bit, MSB first)
whose rows are spread over consecutive stages; :func:`run_division_phase` clocks
divisions side by side until all are done. :mod:`.rtl_pipe` builds ``HertzPipe`` from
them.

References
----------
B. Parhami, *Computer Arithmetic*, 2nd ed., Oxford University Press, 2010, sec. 13.1
(restoring division) and ch. 16 (array dividers, pipelining).
"""

from __future__ import annotations

from amaranth import Cat, Const, Module, Signal, unsigned

from .rtl_divider import restoring_step

__all__ = ["Pipeline", "PipelinedDivision", "run_division_phase"]


class Pipeline:
    """Live values of one evaluation, registered from stage to stage on ``en``.

    ``live`` maps a name to the Amaranth value the next stage register takes;
    :meth:`stage` creates the registers (reset-less, except ``valid``) and makes them
    the live values; :meth:`comb` names a combinational value inside the current stage.
    """

    def __init__(self, m: Module, en):
        self.m, self.en = m, en
        self.live: dict = {}
        self.depth = 0
        self.sub = self._new_sub()

    def _new_sub(self) -> Module:
        sub = Module()
        self.m.submodules[f"s{self.depth + 1}"] = sub
        return sub

    def comb(self, name: str, value, shape=None):
        sig = Signal(shape if shape is not None else value.shape(),
                     name=f"s{self.depth + 1}_{name}")
        self.sub.d.comb += sig.eq(value)
        return sig

    def stage(self) -> None:
        """Register every live value (one pipeline stage)."""
        self.depth += 1
        new = {}
        with self.m.If(self.en):
            for name, value in self.live.items():
                shape = value.shape() if hasattr(value, "shape") else unsigned(1)
                reg = Signal(shape, name=f"p{self.depth}_{name}", reset_less=name != "valid")
                self.m.d.sync += reg.eq(value)
                new[name] = reg
        self.live = new
        self.sub = self._new_sub()

    def drop(self, *names: str) -> None:
        for n in names:
            del self.live[n]


class PipelinedDivision:
    """One unrolled restoring division in flight: the dividend bits not yet consumed
    (live ``<name>_num``: the register part of ``register << shift`` above the shift, or
    a Python constant), the quotient bits so far (``<name>_q``) and the partial
    remainder (``<name>_rem``); the divisor is a live value named ``den``."""

    def __init__(self, pipe: Pipeline, name: str, num, rows: int, den: str):
        self.name, self.rows, self.done, self.den = name, rows, 0, den
        self.const = num if isinstance(num, int) else None
        self.shift = 0 if self.const is not None else num[1]
        dbits = len(pipe.live[den].as_unsigned())
        pipe.live[f"{name}_rem"] = Const(0, dbits)
        if self.const is None:
            pipe.live[f"{name}_num"] = num[0]

    @property
    def finished(self) -> bool:
        return self.done == self.rows

    def advance(self, pipe: Pipeline, k: int) -> None:
        """Up to ``k`` rows in the current stage (comb rows, registered by the next
        :meth:`Pipeline.stage`); nothing once finished (the quotient travels on)."""
        if self.finished:
            return
        n, den = self.name, pipe.live[self.den].as_unsigned()
        rem = pipe.live[f"{n}_rem"]
        num = pipe.live.get(f"{n}_num")                   # None: constant or all consumed
        q = pipe.live.get(f"{n}_q")
        for _ in range(min(k, self.rows - self.done)):
            i = self.rows - 1 - self.done                 # dividend bit, MSB first
            if self.const is not None:
                bit = Const((self.const >> i) & 1, 1)
            elif i >= self.shift:
                bit = num[i - self.shift]
            else:                                         # shifted-in zeros: constants
                bit = Const(0, 1)
            new_rem, qbit = restoring_step(rem, bit, den)
            rem = pipe.comb(f"{n}_r{i}", new_rem, len(den))
            qb = pipe.comb(f"{n}_q{i}", qbit, 1)
            q = qb if q is None else Cat(qb, q)
            self.done += 1
        pipe.live[f"{n}_q"] = q
        left = self.rows - self.done - self.shift          # register bits still to come
        if num is not None:
            if left > 0:
                pipe.live[f"{n}_num"] = num[:left]
            else:
                pipe.live.pop(f"{n}_num", None)
        if self.finished:
            pipe.drop(f"{n}_rem")
        else:
            pipe.live[f"{n}_rem"] = rem

    def quotient(self, pipe: Pipeline):
        """The quotient (``rows`` bits) after the last row; removed from the live set."""
        assert self.finished
        return pipe.live.pop(f"{self.name}_q")


def run_division_phase(pipe: Pipeline, divs: list, rows_per_stage: int) -> None:
    """Clock the divisions ``divs`` side by side, ``rows_per_stage`` rows per stage, until
    all are done (a finished one carries its quotient on)."""
    while not all(d.finished for d in divs):
        for d in divs:
            d.advance(pipe, rows_per_stage)
        pipe.stage()
