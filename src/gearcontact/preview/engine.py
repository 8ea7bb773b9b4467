"""One preview engine interface with interchangeable backends.

Host code asks a :class:`PreviewEngine` for the physics-direct preview of a contact and
does not care which representation answers:

=============  =================================================================
backend        what evaluates the preview
=============  =================================================================
``reference``  fp64 closed forms (:mod:`.hertz.reference`, :mod:`.fit.reference`)
``golden``     bit-exact fixed-point model of the datapath (:mod:`.hertz.golden`,
               :mod:`.fit.golden`); results carry the raw codes, flags and cycles
=============  =================================================================

This module knows only these two. The hardware backends live in :mod:`gearcontact.hw`
and register themselves here (:func:`register_backend`) when
:mod:`gearcontact.hw.backends` is imported (the command line does): ``rtl`` (the RTL
cores in simulation) and ``rtl-soc`` (the SoCs behind the host driver, returning the
register values read back).

Every backend evaluates stage D in either Hertz form, ``get_engine(name, hertz_form="hamrock-brewe" |
"exact")`` (:data:`.hertz.formats.HERTZ_FORMS`; the fixed-point ``"exact"`` form holds the
exact k and elliptic-integral terms in the same tables, :mod:`.hertz.luts`).

Near-line contact: ``hertz(A, B, W, line_length_mm=L)``, ``hertz_batch(A, B, W,
line_length_mm=L)`` and ``stencil(gaps, W, line_length_mm=L)`` (reference, golden, rtl)
run the *line core* of stage D (:mod:`.hertz.line`; 759 cycles; the stencil path: the
fit core's codes into it, :func:`.chain.chain_line_golden`): the Hertz ellipse (reduced
radii beyond the published 1 m by the Hertz similarity) or, where the flank (contact line
of length L) truncates a longer ellipse, the Hertz line contact; ``PreviewResult.mode`` /
``PreviewBatch.mode`` say which. The fixed-point line core reports its domain through
flags (never raises for it); the reference mirrors that domain unless ``envelope=False``
(host-side previews: any positive input, the physics alone). ``rtl-soc`` has no line
core (the SoCs hold the published cores) and refuses ``line_length_mm``.

Physical inputs are validated the same way for every backend (finite, positive; errors
name the field); range limits specific to a representation are then reported by that
representation: the reference raises :class:`~gearcontact.validation.InputRangeError`
outside its envelope, the golden model raises
:class:`~gearcontact.contract.qformat.FixedPointOverflow` for values that do not fit a
register and otherwise returns datapath flags (never a silently wrapped number).
"""

from __future__ import annotations

from typing import Callable, Protocol, runtime_checkable

import numpy as np

from ..materials import STEEL, Material, effective_modulus_mpa
from ..validation import InputRangeError, check_array_finite, check_positive, check_range
from . import chain
from .fit.golden import encode_gaps
from ..contract.stencil import STENCIL_SIZE
from .hertz.formats import DEFAULT_HERTZ_FORM, HERTZ_FORMS, check_hertz_form
from .hertz.golden import decode_hertz_codes, encode_e_prime, encode_hertz_inputs, hertz_golden
from .hertz.golden_vec import hertz_golden_array
from .hertz.line import (LINE_CYCLES, decode_line_codes, encode_length, length_lift,
                         line_golden, unlift_line_codes)
from .hertz.line_vec import lift_lengths, line_golden_array, unlift_line_array
from .hertz.reference import (ENVELOPE, check_envelope, hertz_preview, hertz_preview_array,
                              truncated_preview)
from .hertz.schedule import HERTZ_CYCLES
from .result import MODES, PreviewBatch, PreviewResult, elliptic_modes

#: Preset materials :func:`get_engine` accepts by name.
MATERIALS = {"steel": STEEL}

__all__ = ["PreviewResult", "PreviewBatch", "PreviewEngine", "ReferenceEngine",
           "GoldenEngine", "get_engine", "register_backend", "load_backend_plugins",
           "BACKENDS", "BACKEND_HERTZ_FORMS", "MODES", "elliptic_modes"]

@runtime_checkable
class PreviewEngine(Protocol):
    """What host code needs from a preview backend."""

    name: str
    material: Material

    def hertz(self, A_minus: float, B_minus: float, load_n: float) -> PreviewResult:
        """Stage D from half relative curvatures (1/mm, any order) and load (N).

        The reference and golden backends take ``line_length_mm=L`` as well (keyword):
        the length of the contact line on the flank, mm; stage D is then the line core
        (:mod:`.hertz.line`: an ellipse longer than the flank is truncated to a Hertz
        line contact, ``mode`` says which answered)."""
        ...

    def stencil(self, gaps_mm, load_n: float) -> PreviewResult:
        """Stage C then D on a 49-sample gap stencil (mm, in the order of
        :mod:`gearcontact.contract.stencil`);
        ``line_length_mm=L`` (keyword; reference, golden, rtl): stage D is the line
        core."""
        ...

    def hertz_batch(self, A_minus, B_minus, load_n) -> PreviewBatch:
        """Stage D over broadcastable arrays; ``line_length_mm=L`` (keyword, scalar or
        broadcastable array; reference, golden, rtl): the line core."""
        ...


def _check_positive_array(field_name: str, x) -> np.ndarray:
    """A finite float array, every element > 0 (else InputRangeError naming the field
    and the first offending index)."""
    arr = check_array_finite(field_name, x)
    bad = ~(arr > 0.0)
    if bad.any():
        i = tuple(int(j) for j in np.argwhere(bad)[0])
        raise InputRangeError(f"{field_name}[{', '.join(map(str, i))}]" if i else field_name,
                              float(arr[i]), "> 0")
    return arr


def _check_line_batch(A_minus, B_minus, load_n, line_length_mm) -> tuple[np.ndarray, ...]:
    """Line-core batch inputs: finite, > 0, broadcast to one shape (at least 1-d)."""
    return np.broadcast_arrays(*(np.atleast_1d(_check_positive_array(n, v)) for n, v in (
        ("A_minus (1/mm)", A_minus), ("B_minus (1/mm)", B_minus), ("load_n (N)", load_n),
        ("line_length_mm", line_length_mm))))


def _check_physical(A_minus, B_minus, load_n, e_prime_mpa: float
                    ) -> tuple[float, float, float]:
    """Backend-independent validation: every input a finite real scalar > 0 (not a bool),
    then inside the operating envelope (:data:`.hertz.reference.ENVELOPE`): every
    backend accepts exactly the same domain (field and range named)."""
    a, b, w = (check_positive("A_minus (1/mm)", A_minus),
               check_positive("B_minus (1/mm)", B_minus), check_positive("load_n (N)", load_n))
    check_envelope(a, b, w, e_prime_mpa=e_prime_mpa)
    return a, b, w


def _e_prime(material: Material, material2: Material | None) -> float:
    """E' = 2E* of the pair (MPa), inside the envelope every backend accepts."""
    lo, hi = ENVELOPE["e_prime_mpa"]
    return check_range("E' = 2 E* of the materials (MPa)",
                       effective_modulus_mpa(material, material2), lo, hi)


def _check_load(load_n) -> float:
    """The load of a stencil evaluation: finite, > 0 and inside the envelope (N)."""
    lo, hi = ENVELOPE["load_n"]
    return check_range("load_n (N)", check_positive("load_n (N)", load_n), lo, hi)


def _lifted(w_code: int, l_code: int) -> tuple[int, int, int]:
    """``(W << s, L << s, s)`` with the host's lift ``s`` of a line shorter than the line
    core's 1 mm (:func:`.hertz.line.length_lift`; 0 otherwise)."""
    s = int(length_lift(int(w_code), int(l_code)))
    return int(w_code) << s, int(l_code) << s, s


def _check_stencil(gaps_mm) -> np.ndarray:
    try:
        g = check_array_finite("gaps_mm", gaps_mm)
    except (TypeError, ValueError) as exc:   # strings, ragged lists, objects
        if isinstance(exc, InputRangeError):
            raise
        raise InputRangeError("gaps_mm", gaps_mm, f"{STENCIL_SIZE} finite gaps in mm "
                                                  "(array_like of numbers)") from None
    if g.shape != (STENCIL_SIZE,):
        raise InputRangeError("stencil length", g.shape, f"exactly {STENCIL_SIZE} gap samples")
    return g


class ReferenceEngine:
    """fp64 backend (Hamrock–Brewe closed forms, docs/spec.md sec. 6, or exact Hertz).

    Parameters
    ----------
    material, material2 : Material
        The two contacting bodies (default steel/steel); E' = 2E*.
    hertz_form : {"hamrock-brewe", "exact"}
        Stage-D Hertz form (default the published simplified forms).
    envelope : bool
        Enforce the datapath's operating envelope in :meth:`hertz` (default True; False
        accepts any physical input, e.g. host-side sizing of a large gear's contact
        beyond the hardware's range).
    """

    name = "reference"

    def __init__(self, *, material: Material = STEEL, material2: Material | None = None,
                 hertz_form: str = DEFAULT_HERTZ_FORM, envelope: bool = True):
        self.material = material
        self.e_prime_mpa = _e_prime(material, material2)
        self.hertz_form = check_hertz_form(hertz_form)
        self.envelope = bool(envelope)

    def hertz(self, A_minus, B_minus, load_n, *, line_length_mm=None) -> PreviewResult:
        if line_length_mm is not None:
            return self._line(A_minus, B_minus, load_n, line_length_mm)
        if self.envelope:
            a, b, w = _check_physical(A_minus, B_minus, load_n, self.e_prime_mpa)
        else:
            a, b, w = (check_positive("A_minus (1/mm)", A_minus),
                       check_positive("B_minus (1/mm)", B_minus),
                       check_positive("load_n (N)", load_n))
        hp = hertz_preview(a, b, w, e_prime_mpa=self.e_prime_mpa, envelope=self.envelope,
                           hertz_form=self.hertz_form)
        return PreviewResult(self.name, w, max(a, b), min(a, b), hp.a_mm, hp.b_mm, hp.k,
                             hp.p_max_mpa, hertz_form=self.hertz_form)

    def _line(self, A_minus, B_minus, load_n, line_length_mm) -> PreviewResult:
        """The line core's mode rule in fp64 (:func:`.hertz.reference.truncated_preview`;
        with ``envelope=False`` the physics alone, any positive input)."""
        a, b, w = (check_positive("A_minus (1/mm)", A_minus),
                   check_positive("B_minus (1/mm)", B_minus), check_positive("load_n (N)", load_n))
        tp = truncated_preview(a, b, w, line_length_mm, e_prime_mpa=self.e_prime_mpa,
                               envelope=self.envelope, hertz_form=self.hertz_form)
        return PreviewResult(self.name, w, max(a, b), min(a, b), tp.a_mm, tp.b_mm, tp.k,
                             tp.p_max_mpa, hertz_form=self.hertz_form, mode=tp.mode)

    def stencil(self, gaps_mm, load_n, *, line_length_mm=None) -> PreviewResult:
        g = _check_stencil(gaps_mm)
        w = _check_load(load_n)
        if line_length_mm is not None:
            length = check_positive("line_length_mm", line_length_mm)
            res = chain.chain_line_reference(g, w, length, e_prime_mpa=self.e_prime_mpa,
                                             envelope=self.envelope,
                                             hertz_form=self.hertz_form)
            mode = res.hertz.mode
        else:
            res = chain.chain_reference(g, w, e_prime_mpa=self.e_prime_mpa,
                                        hertz_form=self.hertz_form)
            mode = "elliptic"
        hp = res.hertz
        return PreviewResult(self.name, w, res.fit.A_minus_per_mm, res.fit.B_minus_per_mm,
                             hp.a_mm, hp.b_mm, hp.k, hp.p_max_mpa, angle_deg=res.fit.angle_deg,
                             hertz_form=self.hertz_form, mode=mode)

    def hertz_batch(self, A_minus, B_minus, load_n, *, line_length_mm=None) -> PreviewBatch:
        if line_length_mm is not None:
            return self._line_batch(A_minus, B_minus, load_n, line_length_mm)
        out = hertz_preview_array(A_minus, B_minus, load_n, e_prime_mpa=self.e_prime_mpa,
                                  hertz_form=self.hertz_form)
        a = np.asarray(out["a_mm"])
        return PreviewBatch(self.name, a, np.asarray(out["b_mm"]), np.asarray(out["k"]),
                            np.asarray(out["p_max_mpa"]), np.zeros(a.shape, dtype=np.int64),
                            elliptic_modes(a.shape))

    def _line_batch(self, A_minus, B_minus, load_n, line_length_mm) -> PreviewBatch:
        """:func:`.hertz.reference.truncated_preview` elementwise (a few us each)."""
        a, b, w, length = _check_line_batch(A_minus, B_minus, load_n, line_length_mm)
        out = {k: np.empty(a.shape) for k in ("a_mm", "b_mm", "k", "p_max_mpa")}
        mode = np.empty(a.shape, dtype="<U8")
        for idx in np.ndindex(a.shape):
            tp = truncated_preview(a[idx], b[idx], w[idx], length[idx],
                                   e_prime_mpa=self.e_prime_mpa, envelope=self.envelope,
                                   hertz_form=self.hertz_form)
            for k in out:
                out[k][idx] = getattr(tp, k)
            mode[idx] = tp.mode
        return PreviewBatch(self.name, out["a_mm"], out["b_mm"], out["k"], out["p_max_mpa"],
                            np.zeros(a.shape, dtype=np.int64), mode)


class GoldenEngine:
    """Bit-exact fixed-point backend (the specification of the RTL).

    Real inputs are quantized round-half-up to the contract formats (docs/spec.md sec. 6);
    E' is a constant register (integer MPa). Results carry the raw codes, the flags and
    the hardware cycle count of the evaluated path. ``hertz_form`` as for
    :class:`ReferenceEngine` (the golden model's tables, :mod:`.hertz.luts`).
    """

    name = "golden"

    def __init__(self, *, material: Material = STEEL, material2: Material | None = None,
                 hertz_form: str = DEFAULT_HERTZ_FORM):
        self.material = material
        self.e_prime_mpa = _e_prime(material, material2)
        self.e_prime_code = encode_e_prime(self.e_prime_mpa)
        self.hertz_form = check_hertz_form(hertz_form)

    def _result(self, hz, w, codes: dict, flags: tuple, cycles: int) -> PreviewResult:
        v = decode_hertz_codes(hz)
        codes.update(A_min=hz.A_min_code, B_max=hz.B_max_code, a=hz.a_code, b=hz.b_code,
                     k=hz.k_code, p_max=hz.p_max_code, flags=codes.get("flags", hz.flags))
        return PreviewResult(self.name, w, v.B_max_per_mm, v.A_min_per_mm, v.a_mm, v.b_mm,
                             v.k, v.p_max_mpa, codes=codes, flags=flags, cycles=cycles,
                             hertz_form=self.hertz_form,
                             mode="flagged" if flags else "elliptic")

    def encode_hertz(self, A_minus, B_minus, load_n) -> tuple[float, dict]:
        """Checked load (N) and the stage-D input codes ``{"A_in", "B_in", "W",
        "e_prime"}`` of one point (the quantization every fixed-point backend shares)."""
        a, b, w = _check_physical(A_minus, B_minus, load_n, self.e_prime_mpa)
        a_c, b_c, w_c, e_c = encode_hertz_inputs(a, b, w, e_prime_mpa=self.e_prime_mpa)
        return w, {"A_in": a_c, "B_in": b_c, "W": w_c, "e_prime": e_c}

    def encode_stencil(self, gaps_mm, load_n) -> tuple[float, np.ndarray, int]:
        """Checked load (N), the 49 STENCIL_GAP codes and the LOAD code of one stencil."""
        g = _check_stencil(gaps_mm)
        w = _check_load(load_n)
        return w, encode_gaps(g), encode_hertz_inputs(1.0, 1.0, w,
                                                      e_prime_mpa=self.e_prime_mpa)[2]

    def encode_line(self, A_minus, B_minus, load_n, line_length_mm) -> tuple[float, dict]:
        """Checked load (N) and the line core's input codes ``{"A_in", "B_in", "W",
        "L", "e_prime"}`` (no envelope check: the line core flags its own domain) and
        ``"lift"``: a line shorter than the core's 1 mm runs on ``(W << s, L << s)``
        (:func:`.hertz.line.length_lift`; ``W`` and ``L`` are the codes the core runs
        on), undone by :meth:`_line_result`.

        Raises
        ------
        InputRangeError
            A non-finite or non-positive input.
        FixedPointOverflow
            A value that does not fit its 32-bit input register (naming the field).
        """
        a, b, w = (check_positive("A_minus (1/mm)", A_minus),
                   check_positive("B_minus (1/mm)", B_minus), check_positive("load_n (N)", load_n))
        length = check_positive("line_length_mm", line_length_mm)
        a_c, b_c, w_c, e_c = encode_hertz_inputs(a, b, w, e_prime_mpa=self.e_prime_mpa)
        w_c, l_c, lift = _lifted(w_c, encode_length(length))
        return w, {"A_in": a_c, "B_in": b_c, "W": w_c, "L": l_c, "lift": lift,
                   "e_prime": e_c}

    def _line(self, A_minus, B_minus, load_n, line_length_mm) -> PreviewResult:
        """The line core (:func:`.hertz.line.line_golden`, :data:`LINE_CYCLES`)."""
        w, codes = self.encode_line(A_minus, B_minus, load_n, line_length_mm)
        lc = line_golden(codes["A_in"], codes["B_in"], codes["W"], codes["L"],
                         e_prime_code=codes["e_prime"], hertz_form=self.hertz_form)
        return self._line_result(lc, w, codes, LINE_CYCLES)

    def _line_result(self, lc, w, codes: dict, cycles: int, flags=None) -> PreviewResult:
        """A PreviewResult from line-core codes (:class:`.hertz.line.LineCodes`) of a run
        on ``codes``' inputs (their ``"lift"`` undone: :func:`.hertz.line.unlift_line`);
        ``flags``: the names to report (default the line core's)."""
        if codes.get("lift"):
            raw = lc
            lc = unlift_line_codes(raw, codes["lift"])
            if lc.flags != raw.flags:       # an elliptic answer of the lifted run
                if "flags" in codes:
                    codes["flags"] |= lc.flags
                if flags is not None:
                    flags = tuple(dict.fromkeys(flags + lc.flag_names))
        codes.update(A_min=lc.A_min_code, B_max=lc.B_max_code, a=lc.a_code, b=lc.b_code,
                     k=lc.k_code, p_max=lc.p_max_code, mode=lc.mode, scale=lc.scale,
                     flags=codes.get("flags", lc.flags))
        v = decode_line_codes(lc)
        flags = lc.flag_names if flags is None else flags
        return PreviewResult(self.name, w, v["B_max_per_mm"], v["A_min_per_mm"], v["a_mm"],
                             v["b_mm"], v["k"], v["p_max_mpa"], codes=codes, flags=flags,
                             cycles=cycles, hertz_form=self.hertz_form,
                             mode="flagged" if flags else lc.mode_name)

    def encode_line_batch(self, A_minus, B_minus, load_n, line_length_mm) -> dict:
        """The line core's input codes of a batch (``int64`` arrays of one shape):
        ``{"A_in", "B_in", "W", "L", "e_prime"}`` (no envelope check: the line core flags
        its own domain; ``"lift"`` as :meth:`encode_line`). Raises as :meth:`encode_line`,
        naming the element."""
        a, b, w, length = _check_line_batch(A_minus, B_minus, load_n, line_length_mm)
        a_c, b_c, w_c, e_c = encode_hertz_inputs(a, b, w, e_prime_mpa=self.e_prime_mpa)
        w_c, l_c, lift = lift_lengths(w_c, encode_length(length))
        return {"A_in": a_c, "B_in": b_c, "W": w_c.astype(np.int64),
                "L": l_c.astype(np.int64), "lift": lift.astype(np.int64),
                "e_prime": np.full(a.shape, e_c, dtype=np.int64)}

    def _line_batch(self, A_minus, B_minus, load_n, line_length_mm) -> PreviewBatch:
        c = self.encode_line_batch(A_minus, B_minus, load_n, line_length_mm)
        return self._line_batch_result(line_golden_array(
            c["A_in"], c["B_in"], c["W"], c["L"], e_prime_code=c["e_prime"],
            hertz_form=self.hertz_form), c["lift"])

    def _line_batch_result(self, lc, lift) -> PreviewBatch:
        """A PreviewBatch from a :class:`.hertz.line_vec.LineCodesArray` of a run on
        lifted inputs (``lift``: :meth:`encode_line_batch`'s, undone here)."""
        if lift.any():
            lc = unlift_line_array(lc, lift)
        v = decode_line_codes(lc)
        return PreviewBatch(self.name, v["a_mm"], v["b_mm"], v["k"], v["p_max_mpa"],
                            lc.flags, lc.mode_names)

    def hertz(self, A_minus, B_minus, load_n, *, line_length_mm=None) -> PreviewResult:
        if line_length_mm is not None:
            return self._line(A_minus, B_minus, load_n, line_length_mm)
        w, codes = self.encode_hertz(A_minus, B_minus, load_n)
        hz = hertz_golden(codes["A_in"], codes["B_in"], codes["W"],
                          e_prime_code=codes["e_prime"], hertz_form=self.hertz_form)
        return self._result(hz, w, codes, hz.flag_names, HERTZ_CYCLES)

    def stencil(self, gaps_mm, load_n, *, line_length_mm=None) -> PreviewResult:
        if line_length_mm is not None:
            return self._stencil_line(gaps_mm, load_n, line_length_mm)
        w, gap_codes, w_c = self.encode_stencil(gaps_mm, load_n)
        res = chain.chain_golden([int(x) for x in gap_codes], w_c, e_prime_code=self.e_prime_code,
                                 hertz_form=self.hertz_form)
        codes = {"W": w_c, "e_prime": self.e_prime_code,
                 "A_fit": res.fit.a_minus_code, "B_fit": res.fit.b_minus_code,
                 "flags": res.flags}
        return self._result(res.hertz, w, codes, res.flag_names, res.cycles)

    def encode_stencil_line(self, gaps_mm, load_n, line_length_mm) -> tuple[float, np.ndarray,
                                                                             int, int, int]:
        """Checked load (N), the 49 STENCIL_GAP codes, the LOAD and LINE_LENGTH codes the
        chain runs on and their lift (:meth:`encode_line`) of one stencil in line mode."""
        w, gap_codes, w_c = self.encode_stencil(gaps_mm, load_n)
        return w, gap_codes, *_lifted(w_c, encode_length(check_positive("line_length_mm",
                                                                        line_length_mm)))

    def _stencil_line(self, gaps_mm, load_n, line_length_mm) -> PreviewResult:
        """C -> line core (:func:`.chain.chain_line_golden`, :data:`.chain.CHAIN_LINE_CYCLES`)."""
        w, gap_codes, w_c, l_c, lift = self.encode_stencil_line(gaps_mm, load_n,
                                                                 line_length_mm)
        res = chain.chain_line_golden([int(x) for x in gap_codes], w_c, l_c,
                                      e_prime_code=self.e_prime_code, hertz_form=self.hertz_form)
        codes = {"W": w_c, "L": l_c, "lift": lift, "e_prime": self.e_prime_code,
                 "A_fit": res.fit.a_minus_code, "B_fit": res.fit.b_minus_code,
                 "flags": res.flags}
        return self._line_result(res.hertz, w, codes, res.cycles, res.flag_names)

    def hertz_batch(self, A_minus, B_minus, load_n, *, line_length_mm=None) -> PreviewBatch:
        if line_length_mm is not None:
            return self._line_batch(A_minus, B_minus, load_n, line_length_mm)
        a_c, b_c, w_c, e_c = encode_hertz_inputs(
            np.atleast_1d(np.asarray(A_minus, dtype=float)),
            np.atleast_1d(np.asarray(B_minus, dtype=float)),
            np.atleast_1d(np.asarray(load_n, dtype=float)), e_prime_mpa=self.e_prime_mpa)
        hz = hertz_golden_array(a_c, b_c, w_c, e_prime_code=e_c, hertz_form=self.hertz_form)
        v = decode_hertz_codes(hz)
        return PreviewBatch(self.name, v.a_mm, v.b_mm, v.k, v.p_max_mpa, hz.flags,
                            elliptic_modes(hz.flags.shape, hz.flags))


#: Registered backends: name -> factory(material=..., material2=...[, hertz_form=...]).
BACKENDS: dict[str, Callable[..., PreviewEngine]] = {}
#: Hertz forms each backend implements (a factory is passed ``hertz_form`` only when
#: it implements more than the default).
BACKEND_HERTZ_FORMS: dict[str, tuple[str, ...]] = {}


def register_backend(name: str, factory: Callable[..., PreviewEngine], *,
                     hertz_forms: tuple[str, ...] = (DEFAULT_HERTZ_FORM,)) -> None:
    """Add a backend (e.g. ``rtl``) under ``name``, implementing ``hertz_forms``."""
    BACKENDS[name] = factory
    BACKEND_HERTZ_FORMS[name] = tuple(check_hertz_form(f) for f in hertz_forms)


register_backend("reference", ReferenceEngine, hertz_forms=HERTZ_FORMS)
register_backend("golden", GoldenEngine, hertz_forms=HERTZ_FORMS)


#: Entry-point group through which installed packages add backends (the package's own
#: ``gearcontact.hw.backends`` registers ``rtl`` and ``rtl-soc`` this way, so the
#: preview layer never imports the hardware layer, yet ``get_engine("rtl")`` works
#: without the caller importing anything first).
BACKEND_ENTRY_POINTS = "gearcontact.preview_backends"
_plugins_loaded = False


def load_backend_plugins() -> None:
    """Import every module registered under :data:`BACKEND_ENTRY_POINTS` (once)."""
    global _plugins_loaded
    if _plugins_loaded:
        return
    _plugins_loaded = True
    from importlib.metadata import entry_points
    for point in entry_points(group=BACKEND_ENTRY_POINTS):
        point.load()


def get_engine(name: str = "reference", *, material: Material = STEEL,
               material2: Material | None = None,
               hertz_form: str = DEFAULT_HERTZ_FORM) -> PreviewEngine:
    """Create the preview engine ``name`` (one of :data:`BACKENDS`).

    Raises
    ------
    InputRangeError
        Unknown backend, unknown ``hertz_form``, or a form the backend does not
        implement (:data:`BACKEND_HERTZ_FORMS`; ``rtl-soc`` has the published form only).
    """
    if name not in BACKENDS:
        load_backend_plugins()
    try:
        factory = BACKENDS[name]
    except (KeyError, TypeError):
        raise InputRangeError("backend", name, f"one of {sorted(BACKENDS)}") from None
    forms = BACKEND_HERTZ_FORMS[name]
    if check_hertz_form(hertz_form) not in forms:
        raise InputRangeError(f"hertz_form (backend {name})", hertz_form, f"one of {forms}")
    materials = dict(material=_material(material, "material"),
                     material2=None if material2 is None else _material(material2, "material2"))
    if len(forms) > 1:
        return factory(**materials, hertz_form=hertz_form)
    return factory(**materials)


def _material(value, field: str) -> Material:
    """A :class:`Material`, or the name of a preset (``"steel"``)."""
    if isinstance(value, Material):
        return value
    if isinstance(value, str) and value.lower() in MATERIALS:
        return MATERIALS[value.lower()]
    raise InputRangeError(field, value, f"a gearcontact.Material or one of the preset "
                                        f"names {sorted(MATERIALS)}")
